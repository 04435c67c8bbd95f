"""Reusable click options (rasterio style): one decorator per group of options."""

from __future__ import annotations

import click
from rockcli.cli.types import NUMBER, WHOLE


def record_options(func=None, *, column_flag: str = "--column"):
    """Add ``--units``, ``--dt``, ``--format`` and ``--column``: what ``read_record`` takes.

    The command receives them as the keyword arguments ``units``, ``dt``, ``fmt`` and ``column``.
    Commands where ``--column`` means something else (``simulate --column nemea``) rename the
    flag: ``@record_options(column_flag="--record-column")``.
    """

    def decorate(f):
        options = [
            click.option("--units", default=None, metavar="UNITS",
                         help="Units of the values in the file (g, m/s^2, cm/s^2, gal, mm/s^2, g/10); "
                              "needed when the file does not state them."),
            click.option("--dt", type=NUMBER, default=None, metavar="SECONDS",
                         help="Time step [s]; needed when the file states none (single-column text)."),
            click.option("--format", "fmt", default=None, metavar="NAME",
                         help="File format (PEER_AT2, TEXT, ESM, ITACA, COSMOS, GEONET_V2A, or an ObsPy "
                              "format such as SAC, MSEED, KNET); detected when omitted."),
            click.option(column_flag, "column", type=WHOLE, default=None, metavar="N",
                         help="1-based column of a multi-column text file (a time column counts), or "
                              "component/trace of a multi-component file."),
        ]
        for option in reversed(options):
            f = option(f)
        return f

    return decorate(func) if func is not None else decorate


def record_kwargs(units, dt, fmt, column) -> dict:
    """The keyword arguments of ``read_record`` from the values of :func:`record_options`."""
    return {"units": units, "dt": dt, "format": fmt, "column": column}


def block_options(func):
    """Add the block choice: ``--column NAME``, or ``--R`` with ``--alpha``, or ``--height`` with ``--width``.

    The command receives ``column``, ``R``, ``alpha``, ``height``, ``width`` and ``name``; turn them
    into a :class:`rockcli.models.Block` with :func:`block_from_options`.
    """
    options = [
        click.option("--column", "column_name", default=None, metavar="NAME",
                     help="A temple column preset: bassae (5.95 m x 1.11 m) or nemea (10.33 m x 1.52 m)."),
        click.option("--R", "R", type=NUMBER, default=None, metavar="METRES",
                     help="Semi-diagonal of the block (centre of mass to a base corner) [m]."),
        click.option("--alpha", type=NUMBER, default=None, metavar="DEGREES",
                     help="Slenderness atan(b/h) [degrees], with --R."),
        click.option("--height", type=NUMBER, default=None, metavar="METRES", help="Full height [m], with --width."),
        click.option("--width", type=NUMBER, default=None, metavar="METRES",
                     help="Base width (a column's base drum diameter) [m], with --height."),
        click.option("--name", default=None, help="Label of a custom block in reports."),
    ]
    for option in reversed(options):
        func = option(func)
    return func


def horizon_option(func):
    """``--horizon S``: the solver's horizon, the longest free motion followed after the excitation to
    prove a verdict. The command checks it (:func:`rockcli.solve.validate_options`) before any work."""
    return click.option("--horizon", type=NUMBER, default=600.0, show_default=True, metavar="S",
                        help="Longest free motion followed after the excitation to prove a verdict [s] (at most "
                             "3600); a run still moving then is reported NOT PROVEN.")(func)


#: The block flags, as :func:`rockcli.models.build_block` names them in messages.
BLOCK_FLAGS = {"preset": "--column NAME", "R": "--R", "alpha": "--alpha", "height": "--height", "width": "--width"}


def block_from_options(column_name=None, R=None, alpha=None, height=None, width=None, name=None):
    """The :class:`Block` named by exactly one of the three forms of :func:`block_options`."""
    from rockcli.models import build_block

    return build_block(preset=column_name, R=R, alpha_deg=alpha, height=height, width=width, name=name,
                       labels=BLOCK_FLAGS)


def check_outputs(*files, folders=()):
    """Check every output before any work: ``files`` are ``(path, option, is_image)``, ``folders`` ``(path, option)``.

    Entries whose path is None (option not given) are skipped. Raises ``RockcliInputError`` with
    one sentence naming the option and the path (see :mod:`rockcli.files`).
    """
    from rockcli.files import check_output, check_output_folder

    for path, option, image in files:
        if path is not None:
            check_output(path, option, image=image)
    for path, option in folders:
        if path is not None:
            check_output_folder(path, option)


def progress_bar(total: int, label: str = "runs", *, eta: bool = True):
    """A progress bar on stderr when it is a terminal, else nothing: a context manager yielding the
    bar (call ``bar.update(n)``) or ``None`` (piped output stays quiet)."""
    import contextlib
    import sys

    if not sys.stderr.isatty() or total <= 0:
        return contextlib.nullcontext(None)
    return click.progressbar(length=total, label=label, file=sys.stderr, show_eta=eta)
