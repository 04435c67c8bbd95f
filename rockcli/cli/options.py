"""Reusable click options (rasterio style): one decorator per group of options.

Every command imports its options from here. This module holds the body (``--body``, ``--R``/``--alpha``,
``--height``/``--width``, ``--on``), the solver's ``--horizon``/``--restitution``/``--cap-ratio``, and what a
command writes (outputs checked before the work, ``--json``, ``--quiet``, progress, ``--scheduler``, ``--report``,
the command line); it re-exports the kinds of option (:mod:`rockcli.cli.option_kinds`: ``Command``, ``Group``,
hidden aliases) and the options of the ground motion (:mod:`rockcli.cli.motion_options`: reading a record, the
orientation of a pair, a vertical motion, a folder suite).
"""

from __future__ import annotations

import click

from rockcli.cli.motion_options import (azimuth_options, component_option, gain_option,  # noqa: F401
                                        given_azimuth, given_component, given_gain, given_suite, given_vertical,
                                        read_vertical, record_kwargs, record_options, scaled, spectrum_vertical_option,
                                        simulate_vertical_component_option, suite_options, vertical_options)
from rockcli.cli.option_kinds import (AliasOption, Command, Group, QuietSpellingOption,  # noqa: F401
                                      _remember, _stacked, alias_option)
from rockcli.cli.types import NUMBER
from rockcli.io.output_checks import REPORT_SUFFIXES  # noqa: F401 - the --report file's suffixes (check_outputs)

#: The isolation defaults (:data:`rockcli.models.DEFAULT_XI`, :data:`rockcli.models.DEFAULT_GAMMA`, written out
#: so that ``--help`` imports nothing heavy; a test keeps them equal) and what gamma means, for help texts.
DEFAULT_XI_TEXT, DEFAULT_GAMMA_TEXT = "0.1", "0.01"
GAMMA_HELP = (f"Left out of a spec, xi = {DEFAULT_XI_TEXT} and gamma = {DEFAULT_GAMMA_TEXT} in every command. "
              "gamma = m/(m + m_b) is the body's mass over the body's plus the isolated base's: 0.01 is a base 99 "
              "times heavier than the body (a temple column on an isolated foundation slab; for gamma <= 0.1 the "
              "answer hardly depends on it, the paper's Figure 8). A museum platform is often lighter than the "
              "object it carries: give its own gamma (e.g. gamma=0.5 for a platform as heavy as the statue).")

#: What a body of one's own looks like, for help texts and messages.
BODY_FORMS = "NAME:R=<m>,alpha=<deg> or NAME:height=<m>,width=<m>"


def block_options(func):
    """Add the block choice: ``--body NAME|SPEC``, or ``--R`` with ``--alpha``, or ``--height`` with ``--width``
    (and the old ``--column NAME``, hidden).

    The command receives ``column_name`` (the ``--body`` text), ``R``, ``alpha``, ``height``, ``width`` and
    ``name``; turn them into a :class:`rockcli.models.Block` with :func:`block_from_options`.
    """
    options = [
        click.option("--body", "column_name", default=None, metavar="NAME|SPEC",
                     help="The body: a temple column preset, bassae (5.95 m x 1.11 m) or nemea (10.33 m x 1.52 m), "
                          f"or a body of your own, {BODY_FORMS} (e.g. statue:height=1.7,width=0.45).",
                     shell_complete=_complete_presets),
        alias_option("--column", "column_name", "--body"),
        click.option("--R", "R", type=NUMBER, default=None, metavar="METRES",
                     help="Semi-diagonal of the block (centre of mass to a base corner) [m], the paper's R."),
        click.option("--alpha", type=NUMBER, default=None, metavar="DEGREES",
                     help="Slenderness atan(b/h) [degrees], with --R."),
        click.option("--height", type=NUMBER, default=None, metavar="METRES", help="Full height [m], with --width."),
        click.option("--width", type=NUMBER, default=None, metavar="METRES",
                     help="Base width (a column's base drum diameter) [m], with --height."),
        click.option("--name", default=None, help="Label of a block given by --R/--alpha or --height/--width."),
    ]
    return _stacked(func, options)


def _complete_presets(ctx, param, incomplete):
    from rockcli.models.block import COLUMN_PRESETS

    return [k for k in COLUMN_PRESETS if k.startswith(incomplete)]


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


#: What ``--on`` takes, for help texts and messages.
PLINTH_FORM = "NAME:height=<m>,width=<m>[,mass_ratio=<plinth mass over the body's>]"


def plinth_option(func):
    """``--on NAME:height=H,width=W[,mass_ratio=M]``: the body stands on a free plinth (the command receives
    ``plinth_spec``; turn it into a :class:`rockcli.models.Stack` with :func:`stack_from_option`)."""
    return click.option("--on", "plinth_spec", default=None, metavar="PLINTH",
                        help=f"Stand the body on a free plinth, {PLINTH_FORM} (e.g. plinth:height=1.0,width=0.6): "
                             "a rigid block at least as wide as the body, which can rock with it (the two-block "
                             "assembly, rocking only: docs/plinth.md). mass_ratio left out: the same density as "
                             "the body (the ratio of the areas height x width). On a rigid foundation and on "
                             "every --isolation kind (linear, sliding and lead-rubber bearings; not gamma=0, an "
                             "infinitely heavy base).")(func)


def stack_from_option(block, plinth_spec):
    """``block`` on the plinth of ``--on`` (a :class:`rockcli.models.Stack`), None without ``--on``; a bad spec, or
    a plinth the model refuses (narrower than the body, a mass ratio out of range), is one sentence."""
    if plinth_spec is None:
        return None
    from rockcli.errors import RockcliInputError
    from rockcli.models import Stack, parse_plinth_spec

    try:
        return Stack(block, parse_plinth_spec(plinth_spec))
    except RockcliInputError as exc:
        text = str(exc)  # "plinth 'SPEC': ..." from the parser, or the Stack's own sentence
        raise RockcliInputError("--on " + text[len("plinth "):] if text.startswith("plinth '") else
                                f"--on {plinth_spec!r}: {text}") from None


def horizon_option(func):
    """``--horizon S``: the solver's horizon, the longest free motion followed after the excitation to
    prove a verdict. The command checks it (:func:`rockcli.solve.validate_options`) before any work."""
    return click.option("--horizon", type=NUMBER, default=600.0, show_default=True, metavar="S",
                        help="Longest free motion followed after the excitation to prove a verdict [s] (at most "
                             "3600); a run still moving then is reported NOT PROVEN.")(func)


def restitution_option(func):
    """``--restitution E``: the coefficient of restitution of every impact (``restitution`` keyword of
    :func:`rockcli.solve.simulate`); the command checks it (:func:`rockcli.models.impact.check_restitution`)."""
    return click.option("--restitution", type=NUMBER, default=None, metavar="E",
                        help="Coefficient of restitution, 0 < E <= 1: theta_dot after / before an impact on rigid "
                             "ground [default: Housner's 1 - 1.5 sin^2 alpha]. E is always this rigid-ground ratio: "
                             "on an isolated base the impact also keeps the horizontal momentum, which lowers the "
                             "ratio to (4 E - 3 gamma cos^2 alpha)/(4 - 3 gamma cos^2 alpha) (docs/simulate.md, "
                             "Restitution).")(func)


def cap_ratio_option(func):
    """``--cap-ratio GAMMA_C``: a capped colonnade of the columns (``cap_ratio`` keyword of
    :func:`rockcli.solve.simulate`) on any foundation (:mod:`rockcli.models.colonnade`)."""
    return click.option("--cap-ratio", "cap_ratio", type=NUMBER, default=0.0, metavar="GAMMA_C",
                        help="A capped colonnade of N such columns carrying a rigid beam (Makris & Vassiliou 2013): "
                             "beam mass over the columns' total mass; they rock as one column with p times "
                             "sqrt((1 + 2 gamma_c)/(1 + 3 gamma_c)). On an isolation layer its gamma is the mass "
                             "of columns + beam over the whole moving mass (docs/physics-colonnade.md). "
                             "0: solitary columns.")(func)


#: The block flags, as :func:`rockcli.models.build_block` names them in messages.
BLOCK_FLAGS = {"preset": "--body NAME|SPEC", "R": "--R", "alpha": "--alpha", "height": "--height", "width": "--width"}


def block_from_options(column_name=None, R=None, alpha=None, height=None, width=None, name=None):
    """The :class:`Block` named by exactly one of the three forms of :func:`block_options` (a size that looks
    like centimetres is warned about on stderr: :func:`warn_size`)."""
    from rockcli.models import build_block

    if column_name is not None and ":" in column_name:  # --body NAME:R=..,alpha=.. or NAME:height=..,width=..
        build_block(preset=column_name, R=R, alpha_deg=alpha, height=height, width=width, labels=BLOCK_FLAGS,
                    check_only=True)
        if name is not None:
            from rockcli.errors import RockcliInputError

            raise RockcliInputError(f"--body {column_name} names the body already; leave out --name")
        from rockcli.assess import parse_column_spec

        return warn_size(parse_column_spec(column_name))
    return warn_size(build_block(preset=column_name, R=R, alpha_deg=alpha, height=height, width=width, name=name,
                                 labels=BLOCK_FLAGS))


def warn_size(block):
    """``block``, after a warning on stderr when its size looks like centimetres given as metres
    (:func:`rockcli.models.block.size_warning`; the run goes on)."""
    from rockcli.models.block import size_warning

    text = size_warning(block)
    if text:
        click.echo(f"Warning: {text}", err=True)
    return block


def check_outputs(*files, folders=(), catalogue_is_input: bool = True):
    """Declare and check every output before any work: ``files`` are ``(path, option, kind)`` (``kind``: True for a
    figure, the only suffixes allowed such as :data:`REPORT_SUFFIXES` for the HTML report, else False),
    ``folders`` ``(path, option)``; entries whose path is None (option not given) are skipped.

    The outputs join the command's transaction (:mod:`rockcli.io.files`, opened by ``user_errors``):
    two outputs on one path are refused, and so is an output on the record catalogue, which every
    command may read (``catalogue_is_input=False`` for the command that updates it). Raises
    ``RockcliInputError`` with one sentence naming the option and the path.
    """
    from rockcli.io.files import Transaction, current

    outputs = current() or Transaction()
    if catalogue_is_input:
        add_inputs([catalog_file()], "the record catalogue")
    for path, option, kind in files:
        if path is not None:
            outputs.declare(path, option, image=kind is True, suffixes=kind if isinstance(kind, tuple) else None)
    for path, option in folders:
        if path is not None:
            outputs.declare_folder(path, option)
    return outputs


def catalog_file():
    """The record catalogue's path (``ROCKCLI_CATALOG`` or the repository's ``records/catalog.csv``)."""
    from rockcli.records.catalog import catalog_path

    return catalog_path()


def add_inputs(paths, what: str) -> None:
    """Files the command reads (records, the catalogue): an output on one of them is refused
    (:func:`rockcli.io.files.note_inputs`)."""
    from rockcli.io.files import note_inputs

    note_inputs([p for p in paths if p], what)


def json_option(func):
    """``--json``: the command's result as one JSON document on stdout (read it with :func:`echo_json`);
    every other line (notes, warnings, ``wrote FILE``) goes to stderr, so that stdout parses as it is."""
    return click.option("--json", "as_json", is_flag=True,
                        help="Print the result as one JSON document on stdout instead of the table (notes and "
                             "'wrote FILE' lines go to stderr).")(func)


def _plain(value):
    """``value`` with NaN as None, tuples as lists and numpy scalars and arrays as Python values."""
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):  # numpy array or scalar
        return _plain(value.tolist())
    if isinstance(value, float) and value != value:
        return None
    return value


def echo_json(obj, *, indent=None) -> None:
    """Print ``obj`` as JSON on stdout (NaN as null: strict JSON)."""
    import json

    click.echo(json.dumps(_plain(obj), allow_nan=False, indent=indent))


def quiet_option(func):
    """``--quiet/-q``: no progress bar and no explanatory legend (the table, verdicts and warnings stay);
    kept on the click context, read with :func:`is_quiet`."""
    return click.option("--quiet", "-q", is_flag=True, expose_value=False, callback=_remember("rockcli.quiet"),
                        help="No progress bar and no legend under the table (the results, warnings and "
                             "'wrote FILE' lines stay).")(func)


def is_quiet() -> bool:
    """The running command was given ``--quiet``."""
    ctx = click.get_current_context(silent=True)
    return bool(ctx is not None and ctx.meta.get("rockcli.quiet"))


def progress_bar(total: int, label: str = "runs", *, eta: bool = True, unit: str | None = None):
    """Progress lines on stderr when it is a terminal, else nothing: a context manager yielding the
    :class:`rockcli.cli.progress.Progress` (call it with increments; the library may begin parts with
    :func:`rockcli.progress.phase`; ``eta=False``: the steps do not measure the time left) or ``None``
    (piped output and ``--quiet`` stay quiet)."""
    import contextlib
    import sys

    if not sys.stderr.isatty() or total <= 0 or is_quiet():
        return contextlib.nullcontext(None)
    from rockcli.cli.progress import Progress

    return Progress(total, label, eta=eta, unit=unit, stream=sys.stderr)


def dask_client(scheduler):
    """``--scheduler``: the ``distributed.Client`` of the running command (None without ``--scheduler``), opened
    once and closed when the command ends; which cluster it is (workers, dashboard) is said on stderr."""
    if scheduler is None:
        return None
    from rockcli.distributed import describe_cluster, open_client

    client = click.get_current_context().with_resource(open_client(scheduler))
    click.echo(describe_cluster(client, local=scheduler == "local"), err=True)
    return client


def report_option(func):
    """``--report FILE.html``: the self-contained HTML report (:mod:`rockcli.report.html`)."""
    return click.option("--report", "report_path", type=click.Path(), default=None, metavar="FILE.html",
                        help="Write a self-contained HTML report (figures embedded, no network needed) for "
                             "readers who are not engineers: the question and the answer, the body, the "
                             "records with their SHA-256, the verdicts, figures, checks, assumptions and the "
                             "command to reproduce it (FILE ends in .html or .htm).")(func)


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
