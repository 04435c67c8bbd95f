"""Turning library errors into one clear sentence and exit code 2; every command's outputs are one transaction."""

from __future__ import annotations

import errno
import functools
import os
import sys

import click


class InputError(click.ClickException):
    """Bad input: printed as ``Error: <message>`` with exit code 2 and no traceback."""

    exit_code = 2


def _from_echo(exc: BaseException) -> bool:
    """The error was raised while click.echo wrote to a standard stream (closed, full, broken pipe)."""
    tb = exc.__traceback__
    while tb is not None and tb.tb_next is not None:
        tb = tb.tb_next
    if tb is None:
        return False
    code = tb.tb_frame.f_code
    return code.co_name == "echo" and os.path.join("click", "utils.py") in code.co_filename


def _silence_stdout() -> None:
    """Point the standard output at the null device: the interpreter's last flush cannot fail again."""
    try:
        fd = os.open(os.devnull, os.O_WRONLY)
        os.dup2(fd, sys.stdout.fileno())
        os.close(fd)
    except (OSError, ValueError, AttributeError):
        pass


def user_errors(func):
    """Decorator for command bodies.

    * The command's outputs are one transaction (:func:`rockcli.io.files.transaction`): written when
      the body returns (or ends itself with an exit code after its report), discarded on any error
      or on SIGINT/SIGTERM/SIGHUP, so that a failed run changes no file.
    * Library input errors become :class:`InputError` (exit 2); an arithmetic failure inside the
      library one sentence with exit code 1; a standard output that is full or closed one sentence
      with exit code 2 (a broken pipe, as in ``| head``, ends quietly), never a traceback.
    """

    @functools.wraps(func)
    def wrapper(*args, **kwargs):
        from rockcli.errors import RockcliInputError
        from rockcli.io.files import transaction

        try:
            with transaction() as outputs:
                try:
                    return func(*args, **kwargs)
                except (SystemExit, click.exceptions.Exit):  # ended itself after delivering its report
                    outputs.commit()
                    raise
        except RockcliInputError as exc:
            raise InputError(str(exc)) from None
        except ArithmeticError as exc:  # a numerical failure in the library: one sentence, exit 1
            raise click.ClickException(
                f"numerical failure ({type(exc).__name__}: {exc}); no result is given (please report the "
                f"command line)") from None
        except OSError as exc:
            if not _from_echo(exc):
                raise
            _silence_stdout()
            if exc.errno == errno.EPIPE:  # the reader has gone (| head): nothing more to say
                sys.exit(1)
            from rockcli.io.files import os_error_reason

            raise InputError(f"cannot write to the standard output ({os_error_reason(exc)}); no file was "
                             f"written") from None

    return wrapper
