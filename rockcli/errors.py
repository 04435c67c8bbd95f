"""Exceptions that carry a message meant for the user.

Library code raises :class:`RockcliInputError` (a ``ValueError``) with one clear sentence naming
what is wrong and where (file, option, parameter). The CLI turns it into exit code 2 without a
traceback.
"""


class RockcliInputError(ValueError):
    """Bad input: a missing or malformed file, an invalid parameter, an unknown option value."""
