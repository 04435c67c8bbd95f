"""Reusable click options (rasterio style): one decorator per group of options."""

from __future__ import annotations

import click

from rockcli.cli.types import NUMBER, WHOLE


def record_options(func=None, *, column_flag: str = "--column"):
    """Add ``--units``, ``--dt``, ``--format``, ``--column`` (and ``--component``, ``--gain``): what
    ``read_record`` takes.

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
            component_option,
            gain_option,
        ]
        return _stacked(f, options)

    return decorate(func) if func is not None else decorate


def _remember(key):
    def callback(ctx, param, value):
        if value is not None:
            ctx.meta[key] = value
        return value

    return callback


#: ``--component NAME``: one component of a multi-component file. Not passed to the command: it is kept
#: on the click context and :func:`record_kwargs` adds it (every command that reads records takes it).
component_option = click.option(
    "--component", default=None, metavar="NAME", expose_value=False, callback=_remember("rockcli.component"),
    help="Component of a multi-component file: its channel code (HN1, HNE, HNZ, EW2, N28W, ...), N, E or UP, "
         "or an azimuth in degrees ('rockcli records show FILE' lists them).")


#: ``--gain FACTOR``: counts -> ``--units``, for a file in raw counts. Kept on the click context like
#: ``--component``; :func:`record_kwargs` adds it.
gain_option = click.option(
    "--gain", default=None, metavar="FACTOR", expose_value=False, callback=_remember("rockcli.gain"),
    help="Factor from raw counts to --units, for a file in counts (integer MiniSEED/GSE2 samples, 'units: "
         "counts'): --gain 1.2e-6 --units m/s^2 reads count x 1.2e-6 m/s^2. Refused for files that state "
         "physical units.")


def given_gain():
    """The ``--gain`` of the running command (None when not given; checked by the reader)."""
    ctx = click.get_current_context(silent=True)
    return None if ctx is None else ctx.meta.get("rockcli.gain")


def azimuth_options(func=None, *, suite: bool = False):
    """``--record-2``, ``--azimuth`` and ``--azimuth-step`` (``simulate``; ``suite=True``: without
    ``--record-2``, for ``assess``, whose pairs are ``A+B`` sources): kept on the click context, read with
    :func:`given_azimuth` (so the command's signature does not change)."""
    if func is None:
        return lambda f: azimuth_options(f, suite=suite)
    pair_help = ("the pair A+B of --records (each FILE or FILE@DEG) or the two horizontal components of a "
                 "multi-component file" if suite else "the two horizontal components (of --record, or --record "
                 "and --record-2)")
    options = [] if suite else [
        click.option("--record-2", "record_2", default=None, metavar="SOURCE", expose_value=False,
                     callback=_remember("rockcli.record_2"),
                     help="The other horizontal component of --record (FILE, or FILE@DEG when the file states no "
                          "orientation), for --azimuth."),
    ]
    options += [
        click.option("--azimuth", default=None, metavar="DEG|worst", expose_value=False,
                     callback=_remember("rockcli.azimuth"),
                     help=f"Normal to the body's rocking axis, degrees clockwise from north: {pair_help} are "
                          "projected onto it. 'worst' runs every orientation 0-179 deg and reports the most "
                          "adverse."),
        click.option("--azimuth-step", "azimuth_step", type=NUMBER, default=None, metavar="DEG", expose_value=False,
                     callback=_remember("rockcli.azimuth_step"),
                     help="Step of --azimuth worst [deg; default 5]."),
    ]
    return _stacked(func, options)


def given_azimuth() -> dict:
    """``record_2``, ``azimuth`` (None, ``"worst"`` or degrees) and ``step`` of :func:`azimuth_options`."""
    from rockcli.records.orientation import AZIMUTH_STEP, parse_azimuth

    ctx = click.get_current_context(silent=True)
    meta = {} if ctx is None else ctx.meta
    step = meta.get("rockcli.azimuth_step")
    azimuth = parse_azimuth(meta.get("rockcli.azimuth"))
    record_2 = meta.get("rockcli.record_2")
    from rockcli.errors import RockcliInputError

    if azimuth is None and record_2 is not None:
        raise RockcliInputError("--record-2 is the second horizontal component for --azimuth: give --azimuth DEG|worst")
    if step is not None and azimuth != "worst":
        raise RockcliInputError("--azimuth-step applies to --azimuth worst")
    return {"record_2": record_2, "azimuth": azimuth, "step": AZIMUTH_STEP if step is None else step}


def suite_options(func):
    """``--glob`` and ``--exclude`` (multiple) for folder suites: kept on the click context, read with
    :func:`given_suite`."""
    options = [
        click.option("--glob", "glob", multiple=True, metavar="PATTERN", expose_value=False,
                     callback=_remember("rockcli.glob"),
                     help="Take only the files of a --records folder whose names match this shell pattern "
                          "(e.g. '*.AT2'; repeatable)."),
        click.option("--exclude", "exclude", multiple=True, metavar="PATTERN", expose_value=False,
                     callback=_remember("rockcli.exclude"),
                     help="Leave out the files of a --records folder whose names match this shell pattern "
                          "(repeatable)."),
    ]
    return _stacked(func, options)


def given_suite() -> dict:
    """``glob`` and ``exclude`` of :func:`suite_options` (tuples)."""
    ctx = click.get_current_context(silent=True)
    meta = {} if ctx is None else ctx.meta
    return {"glob": tuple(meta.get("rockcli.glob") or ()), "exclude": tuple(meta.get("rockcli.exclude") or ())}


def given_component():
    """The ``--component`` of the running command (None when not given)."""
    ctx = click.get_current_context(silent=True)
    return None if ctx is None else ctx.meta.get("rockcli.component")


def record_kwargs(units, dt, fmt, column) -> dict:
    """The keyword arguments of ``read_record`` from the values of :func:`record_options` (and ``--component``)."""
    return {"units": units, "dt": dt, "format": fmt, "column": column, "component": given_component(),
            "gain": given_gain()}


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
    return _stacked(func, options)


def custom_block_options(func):
    """Add one more (custom) block beside named columns: ``--R`` with ``--alpha`` or ``--height`` with ``--width``,
    and ``--name`` (default ``custom``); the flags of :func:`block_options` without ``--column``.

    The command receives ``R``, ``alpha``, ``height``, ``width`` and ``name`` (``rockcli assess``).
    """
    options = [
        click.option("--R", "R", type=NUMBER, default=None, metavar="M",
                     help="Custom block: semi-diagonal R [m] (with --alpha)."),
        click.option("--alpha", type=NUMBER, default=None, metavar="DEG",
                     help="Custom block: slenderness [deg] (with --R)."),
        click.option("--height", type=NUMBER, default=None, metavar="M",
                     help="Custom block: full height [m] (with --width)."),
        click.option("--width", type=NUMBER, default=None, metavar="M",
                     help="Custom block: base width or drum diameter [m] (with --height)."),
        click.option("--name", default="custom", show_default=True, help="Name of the custom block."),
    ]
    return _stacked(func, options)


def _stacked(func, options):
    """``func`` decorated with ``options``, the first listed shown first in ``--help``."""
    for option in reversed(options):
        func = option(func)
    return func


def horizon_option(func):
    """``--horizon S``: the solver's horizon, the longest free motion followed after the excitation to
    prove a verdict. The command checks it (:func:`rockcli.solve.validate_options`) before any work."""
    return click.option("--horizon", type=NUMBER, default=600.0, show_default=True, metavar="S",
                        help="Longest free motion followed after the excitation to prove a verdict [s] (at most "
                             "3600); a run still moving then is reported NOT PROVEN.")(func)


def restitution_option(func):
    """``--restitution E``: the coefficient of restitution of every impact (``restitution`` keyword of
    :func:`rockcli.solve.simulate`); the command checks it (:func:`rockcli.impact.check_restitution`)."""
    return click.option("--restitution", type=NUMBER, default=None, metavar="E",
                        help="Coefficient of restitution, 0 < E <= 1: theta_dot after / before an impact on a rigid "
                             "foundation [default: Housner's 1 - 1.5 sin^2 alpha]. On an isolated base the impact "
                             "keeps the horizontal momentum and theta_dot+ = (1 - 4 (1 - E)/(4 - 3 gamma cos^2 "
                             "alpha)) theta_dot- (README, Restitution).")(func)


def cap_ratio_option(func):
    """``--cap-ratio GAMMA_C``: a capped colonnade of the columns (``cap_ratio`` keyword of
    :func:`rockcli.solve.simulate`), rigid foundation only (:mod:`rockcli.colonnade`)."""
    return click.option("--cap-ratio", "cap_ratio", type=NUMBER, default=0.0, metavar="GAMMA_C",
                        help="A capped colonnade of N such columns carrying a rigid beam (Makris & Vassiliou 2013), "
                             "rigid foundation only: beam mass over the columns' total mass; they rock as one column "
                             "with p times sqrt((1 + 2 gamma_c)/(1 + 3 gamma_c)) (docs/physics-colonnade.md). "
                             "0: solitary columns.")(func)


#: The block flags, as :func:`rockcli.models.build_block` names them in messages.
BLOCK_FLAGS = {"preset": "--column NAME", "R": "--R", "alpha": "--alpha", "height": "--height", "width": "--width"}


def block_from_options(column_name=None, R=None, alpha=None, height=None, width=None, name=None):
    """The :class:`Block` named by exactly one of the three forms of :func:`block_options`."""
    from rockcli.models import build_block

    return build_block(preset=column_name, R=R, alpha_deg=alpha, height=height, width=width, name=name,
                       labels=BLOCK_FLAGS)


def check_outputs(*files, folders=(), catalogue_is_input: bool = True):
    """Declare and check every output before any work: ``files`` are ``(path, option, is_image)``,
    ``folders`` ``(path, option)``; entries whose path is None (option not given) are skipped.

    The outputs join the command's transaction (:mod:`rockcli.files`, opened by ``user_errors``):
    two outputs on one path are refused, and so is an output on the record catalogue, which every
    command may read (``catalogue_is_input=False`` for the command that updates it). Raises
    ``RockcliInputError`` with one sentence naming the option and the path.
    """
    from rockcli.files import Transaction, current

    outputs = current() or Transaction()
    if catalogue_is_input:
        add_inputs([catalog_file()], "the record catalogue")
    for path, option, image in files:
        if path is not None:
            outputs.declare(path, option, image=image)
    for path, option in folders:
        if path is not None:
            outputs.declare_folder(path, option)
    return outputs


def catalog_file():
    """The record catalogue's path (``ROCKCLI_CATALOG`` or the repository's ``records/catalog.csv``)."""
    from rockcli.records.catalog import catalog_path

    return catalog_path()


def add_inputs(paths, what: str) -> None:
    """Files the command reads (records, the catalogue): an output on one of them is refused."""
    from rockcli.files import current

    outputs = current()
    if outputs is not None:
        outputs.add_inputs([p for p in paths if p], what)


def progress_bar(total: int, label: str = "runs", *, eta: bool = True):
    """A progress bar on stderr when it is a terminal, else nothing: a context manager yielding the
    bar (call ``bar.update(n)``) or ``None`` (piped output stays quiet)."""
    import contextlib
    import sys

    if not sys.stderr.isatty() or total <= 0:
        return contextlib.nullcontext(None)
    return click.progressbar(length=total, label=label, file=sys.stderr, show_eta=eta)


def report_option(func):
    """``--report FILE.html``: the self-contained HTML report (:mod:`rockcli.report.html`)."""
    return click.option("--report", "report_path", type=click.Path(), default=None, metavar="FILE.html",
                        help="Write a self-contained HTML report (figures embedded, no network needed) for "
                             "readers who are not engineers: the question and the answer, the body, the "
                             "records with their SHA-256, the verdicts, figures, checks, assumptions and the "
                             "command to reproduce it.")(func)


def command_line() -> str:
    """The command line as typed (``rockcli ...``), for the report's "how to reproduce it".

    When the command was called from Python (``CliRunner``, a notebook), the command path and the
    parameters that were given stand in for it.
    """
    import shlex
    import sys
    from pathlib import Path

    argv0 = Path(sys.argv[0] if sys.argv else "")
    if argv0.name == "rockcli" or (argv0.name == "__main__.py" and argv0.parent.name == "rockcli"):
        return shlex.join(["rockcli", *sys.argv[1:]])
    ctx = click.get_current_context(silent=True)
    if ctx is None:
        return "rockcli"
    given = ", ".join(f"{k}={v!r}" for k, v in ctx.params.items() if v not in (None, (), False))
    return f"{ctx.command_path} (called from Python with {given})"
