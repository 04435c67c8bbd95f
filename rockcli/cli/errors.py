"""Turning library errors into one clear sentence and exit code 2."""

from __future__ import annotations

import functools

import click


class InputError(click.ClickException):
    """Bad input: printed as ``Error: <message>`` with exit code 2 and no traceback."""

    exit_code = 2


def user_errors(func):
    """Decorator for command bodies: library input errors become :class:`InputError` (exit 2), and an
    arithmetic failure inside the library one sentence with exit code 1 instead of a traceback."""

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        from rockcli.errors import RockcliInputError

        try:
            return func(*args, **kwargs)
        except RockcliInputError as exc:
            raise InputError(str(exc)) from None
        except ArithmeticError as exc:  # a numerical failure in the library: one sentence, exit 1
            raise click.ClickException(
                f"numerical failure ({type(exc).__name__}: {exc}); no result is given (please report the "
                f"command line)") from None

    return wrapper
