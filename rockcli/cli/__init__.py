"""Command-line interface. Thin: parse options, call the library, print, exit.

Subcommands live in their own modules and are imported only when invoked (or when ``--help``
lists them: those modules import nothing heavy at module level).
"""

from __future__ import annotations

import importlib

import click

from rockcli import __version__

#: command name -> "module:attribute"
_COMMANDS = {
    "records": "rockcli.cli.records:records",
    "simulate": "rockcli.cli.simulate:simulate",
    "fit-pulse": "rockcli.cli.fit_pulse:fit_pulse",
    "assess": "rockcli.cli.assess:assess",
    "spectrum": "rockcli.cli.spectrum:spectrum",
    "bench": "rockcli.cli.bench:bench",
}


class LazyGroup(click.Group):
    """A click group whose subcommands are imported on first use."""

    def __init__(self, *args, lazy_commands=None, **kwargs):
        super().__init__(*args, **kwargs)
        self._lazy = dict(lazy_commands or {})

    def list_commands(self, ctx):
        return sorted(set(super().list_commands(ctx)) | set(self._lazy))

    def get_command(self, ctx, name):
        if name in self._lazy:
            modname, attr = self._lazy[name].split(":")
            try:
                module = importlib.import_module(modname)
            except ModuleNotFoundError as exc:  # command not built yet
                if exc.name == modname:
                    return None
                raise
            return getattr(module, attr)
        return super().get_command(ctx, name)


@click.group(cls=LazyGroup, lazy_commands=_COMMANDS, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="rockcli")
def main():
    """Does a free-standing slender body (column, statue, cabinet) survive an earthquake,
    and does seismic isolation help it or make it worse?

    Implements Vassiliou & Makris (2012), Earthquake Engng Struct Dyn 41:177-196.
    """
    from rockcli.cli.progress import watch_compiles, watch_waits

    watch_compiles()  # one line on stderr when the kernels compile (the first run on a machine), piped or not
    watch_waits()  # and when a slow step that cannot show progress begins (a first read through gmprocess)


def run():
    """The console script ``rockcli``: :func:`main`, then the process ends without the interpreter's
    teardown.

    A finished command has written its files (atomically, closed) and its output; what Python does
    after the exit handlers is free every module and object, and with numba's compiled kernels loaded
    that takes about 0.3 s, a fifth of a whole 200 x 200 map. So the standard streams are flushed, the
    exit handlers run (:mod:`atexit`: logging, numba, multiprocessing) and the process ends with
    :func:`os._exit` and the exit code :func:`main` gave. ``python -m rockcli`` and click's test
    runner call :func:`main` itself and exit the ordinary way.
    """
    import atexit
    import os
    import sys

    try:
        main()
        code = 0
    except SystemExit as exc:
        code = exc.code
    if code is None:
        code = 0
    elif not isinstance(code, int):  # sys.exit("message"): Python prints it and exits with 1
        print(code, file=sys.stderr)
        code = 1
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError, AttributeError):  # a closed or full stream (None when closed at start)
            pass
    atexit._run_exitfuncs()
    os._exit(code)
