"""Turning library errors into one clear sentence and exit code 2."""

from __future__ import annotations

import functools

import click


class InputError(click.ClickException):
    """Bad input: printed as ``Error: <message>`` with exit code 2 and no traceback."""

    exit_code = 2


def user_errors(func):
    """Decorator for command bodies: library input errors become :class:`InputError`."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        from rockcli.errors import RockcliInputError

        try:
            return func(*args, **kwargs)
        except RockcliInputError as exc:
            raise InputError(str(exc)) from None

    return wrapper
