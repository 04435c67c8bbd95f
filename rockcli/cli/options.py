"""Reusable click options (rasterio style): one decorator per group of options."""

from __future__ import annotations

import click

from rockcli.cli.types import NUMBER, WHOLE
from rockcli.io.output_checks import REPORT_SUFFIXES  # noqa: F401 - the --report file's suffixes (check_outputs)


class Command(click.Command):
    """A rockcli command: "did you mean" for a mistyped option suggests only the options ``--help`` lists
    (never an old spelling kept as a hidden alias)."""

    def parse_args(self, ctx, args):
        try:
            return super().parse_args(ctx, args)
        except click.NoSuchOption as exc:
            hidden = {o for p in self.params if getattr(p, "hidden", False) for o in p.opts}
            exc.possibilities = [o for o in (exc.possibilities or ()) if o not in hidden]
            raise


class Group(click.Group):
    """A rockcli command group: its commands are :class:`Command`."""

    command_class = Command


class AliasOption(click.Option):
    """The old spelling of an option, kept for a release: hidden from ``--help``, the value goes to the
    new option's argument, and a note naming the new spelling is printed on stderr once per run.

    ``check(value)`` (optional) may refuse a value the new option would misread (raise
    :class:`rockcli.errors.RockcliInputError`). When both spellings are given, the one written last wins.
    """

    def __init__(self, param_decls, *, target: str, new: str, check=None, **kwargs):
        old = param_decls[0]
        super().__init__([old, f"{target}__old_{old.strip('-').replace('-', '_')}"], hidden=True,
                         expose_value=False, **kwargs)
        self.old, self.target, self.new, self.check = old, target, new, check

    def handle_parse_result(self, ctx, opts, args):
        from click.core import ParameterSource

        value, args = super().handle_parse_result(ctx, opts, args)
        if ctx.get_parameter_source(self.name) != ParameterSource.COMMANDLINE or ctx.resilient_parsing:
            return value, args
        if self.check is not None:
            from rockcli.errors import RockcliInputError

            try:
                self.check(value)
            except RockcliInputError as exc:
                from rockcli.cli.errors import InputError

                raise InputError(str(exc)) from None
        ctx.params[self.target] = value
        ctx.set_parameter_source(self.target, ParameterSource.COMMANDLINE)
        noted = ctx.meta.setdefault("rockcli.aliases_noted", set())
        if self.old not in noted:
            noted.add(self.old)
            click.echo(f"Note: {self.old} is now {self.new}; the old spelling works for one more release "
                       f"(docs/cli-conventions.md).", err=True)
        return value, args


class QuietSpellingOption(click.Option):
    """An option with extra spellings that work but are not listed in ``--help`` (``assess --record`` for
    ``--records``: a repeatable option whose values from both spellings are collected together)."""

    def __init__(self, *args, quiet_spellings=(), **kwargs):
        super().__init__(*args, **kwargs)
        self.quiet_spellings = set(quiet_spellings)

    def get_help_record(self, ctx):
        opts = self.opts
        self.opts = [o for o in opts if o not in self.quiet_spellings]
        try:
            return super().get_help_record(ctx)
        finally:
            self.opts = opts


def alias_option(old: str, target: str, new: str, **kwargs):
    """A decorator adding :class:`AliasOption` ``old`` for the argument ``target`` of the option ``new``."""
    return click.option(old, cls=AliasOption, target=target, new=new, **kwargs)


def record_options(func=None, *, column_alias: bool = False):
    """Add ``--units``, ``--dt``, ``--format``, ``--record-column`` (and ``--component``, ``--gain``): what
    ``read_record`` takes.

    The command receives them as the keyword arguments ``units``, ``dt``, ``fmt`` and ``column``.
    ``column_alias=True`` also accepts the old ``--column N`` (``records show``, ``records export``,
    ``fit-pulse``; ``--column`` was the body preset in ``simulate``, now ``--body``).
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
            click.option("--record-column", "column", type=WHOLE, default=None, metavar="N",
                         help="1-based column of a multi-column text file (a time column counts), or "
                              "component/trace of a multi-component file."),
            *([alias_option("--column", "column", "--record-column", type=WHOLE)] if column_alias else []),
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
    pair_help = ("the pair A+B of --records (each FILE or FILE@DEG), a catalogue pair by its id, or the two "
                 "horizontal components of a multi-component file" if suite else
                 "the two horizontal components (of --record, or --record and --record-2)")
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
    if step is not None:
        from rockcli.records.orientation import check_azimuth_step

        step = check_azimuth_step(step)  # one floor, shared with sweep_azimuths
    return {"record_2": record_2, "azimuth": azimuth, "step": AZIMUTH_STEP if step is None else step}


def _kept(flag: str, **kwargs):
    """An option not passed to the command: kept on the click context as ``rockcli.<name>`` (``--vertical-scale``
    -> ``rockcli.vertical_scale``), None when not given."""
    return click.option(flag, default=None, expose_value=False,
                        callback=_remember("rockcli." + flag.lstrip("-").replace("-", "_")), **kwargs)


def vertical_options(func):
    """``--vertical``, ``--vertical-column``, ``--vertical-component``, ``--vertical-pulse`` and ``--vertical-scale`` of
    the commands that run suites of records (``assess``): kept on the click context, read with
    :func:`given_vertical`."""
    options = [
        _kept("--vertical", metavar="SOURCE",
              help="Vertical ground acceleration (upward positive) under every record, rigid foundation only: a record "
                   "file or catalogue id on the records' time base (read with --units/--dt). Gravity becomes g + a_v; "
                   "the margin's scale factors multiply the horizontal motion only."),
        _kept("--vertical-column", type=WHOLE, metavar="N",
              help="Column of the --vertical file (a multi-column text file)."),
        _kept("--vertical-component", metavar="NAME",
              help="Run each record under its own vertical component, read from the same multi-component file: its "
                   "channel code (HNZ, UP, ...) or UP. With --vertical: the component of that file."),
        _kept("--vertical-pulse", metavar="SPEC",
              help="Vertical ground acceleration as an analytic pulse under every record (same SPEC as simulate "
                   "--pulse; ap in g, upward positive)."),
        _kept("--vertical-scale", type=NUMBER, help="Multiply the vertical acceleration by this factor [default: 1]."),
    ]
    return _stacked(func, options)


#: ``--vertical-component NAME`` of ``simulate``: the component of the ``--vertical`` file (kept on the click context)
simulate_vertical_component_option = _kept(
    "--vertical-component", metavar="NAME",
    help="Component of a multi-component --vertical file (HNZ, UP, ...; default: its one vertical component).")

#: ``--vertical-pulse`` of the pulse spectra (a :class:`rockcli.spectra.VerticalChoice`), kept on the click
#: context like :func:`vertical_options`'s and read with :func:`given_vertical`.
spectrum_vertical_option = _kept(
    "--vertical-pulse", metavar="SHAPE:ap=G[,TvTp=R]",
    help="A vertical pulse under every cell, rigid foundation only: its shape, amplitude a_v [g, upward positive] "
         "and period over the horizontal pulse's (default 1), centred on the horizontal pulse. Gravity becomes "
         "g + a_v.")


def given_vertical() -> dict:
    """``source``, ``component``, ``pulse`` and ``scale`` of :func:`vertical_options`."""
    ctx = click.get_current_context(silent=True)
    meta = {} if ctx is None else ctx.meta
    scale = meta.get("rockcli.vertical_scale")
    return {"source": meta.get("rockcli.vertical"), "column": meta.get("rockcli.vertical_column"),
            "component": meta.get("rockcli.vertical_component"),
            "pulse": meta.get("rockcli.vertical_pulse"), "scale": 1.0 if scale is None else scale,
            "scale_given": scale is not None}


def scaled(motion, factor, option: str, what: str, peak_g: float | None = None):
    """``motion`` (a record or a pulse) times the user's ``factor``, checked first
    (:func:`rockcli.io.inputs.check_scale`: finite, non-zero, the peak within 100 g); ``peak_g`` overrides the
    motion's own peak (the largest of every orientation of a pair)."""
    from rockcli.io.inputs import check_scale

    if peak_g is None:
        peak_g = motion.pga_g if hasattr(motion, "pga_g") else abs(motion.a_p_g)
    k = check_scale(factor, peak_g, option, what)
    return motion if k == 1.0 else motion.scaled(k)


def read_vertical(source, column, pulse, scale, read_kwargs: dict, component=None):
    """``(vertical motion or None, its label)`` from ``--vertical SOURCE`` (read with ``read_kwargs``; of a
    multi-component file its ``--vertical-component`` or ``--vertical-column``, else its one vertical component)
    or ``--vertical-pulse SPEC``, times ``--vertical-scale``. The horizontal record's ``--component`` does not
    apply to it."""
    from rockcli.errors import RockcliInputError
    from rockcli.io.inputs import check_scale, format_number

    if source is not None and pulse is not None:
        raise RockcliInputError("give the vertical ground motion as at most one of --vertical SOURCE or "
                                "--vertical-pulse SPEC")
    check_scale(scale, 0.0, "--vertical-scale")
    if source is None and pulse is None:
        if column is not None or scale != 1.0 or component is not None:
            raise RockcliInputError("--vertical-column, --vertical-component and --vertical-scale apply to "
                                    "--vertical/--vertical-pulse")
        return None, None
    if pulse is not None:
        from rockcli.pulses import parse_pulse_spec

        if column is not None or component is not None:
            raise RockcliInputError("--vertical-column and --vertical-component apply to --vertical, not to "
                                    "--vertical-pulse")
        vertical = scaled(parse_pulse_spec(pulse), scale, "--vertical-scale", "the vertical pulse")
        return vertical, f"{vertical.shape} pulse" + (f" x {format_number(scale)}" if scale != 1.0 else "")
    vertical = _read_vertical_record(source, column, component,
                                     {k: v for k, v in read_kwargs.items() if k not in ("component", "column")})
    add_inputs([vertical.meta.get("path")], "the vertical record")
    comp = vertical.meta.get("component")
    vertical = scaled(vertical, scale, "--vertical-scale", "the vertical record")
    return vertical, (f"record {vertical.name}" + (f" component {comp}" if comp else "")
                      + (f" x {format_number(scale)}" if scale != 1.0 else ""))


def _read_vertical_record(source, column, component, kwargs):
    """The vertical record of ``--vertical SOURCE``: its ``column``, its ``component``, or the one vertical
    component of a multi-component file."""
    from rockcli.errors import RockcliInputError
    from rockcli.records import read_record
    from rockcli.records.components import MultiComponent, select_component
    from rockcli.records.reader import read_components

    if column is not None and component is not None:
        raise RockcliInputError("give the vertical component either by --vertical-component NAME or by "
                                "--vertical-column N, not both")
    if component is not None:
        comps = read_components(source, **{k: v for k, v in kwargs.items() if v is not None})
        return select_component(comps, component, str(source))
    try:
        return read_record(source, **kwargs, column=column)
    except MultiComponent:
        comps = read_components(source, **{k: v for k, v in kwargs.items() if v is not None})
        up = [c for c in comps if c.meta.get("vertical")]
        if len(up) == 1:
            return up[0]
        raise RockcliInputError(f"--vertical {source}: the file holds {len(comps)} components, "
                                f"{len(up)} of them vertical: choose one with --vertical-component NAME "
                                f"(or --vertical-column N)") from None


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


def _stacked(func, options):
    """``func`` decorated with ``options``, the first listed shown first in ``--help``."""
    for option in reversed(options):
        func = option(func)
    return func


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
