"""The options that choose and read the ground motion (:mod:`rockcli.cli.options` re-exports them): how a record
file is read (``--units``, ``--dt``, ``--format``, ``--record-column``, ``--component``, ``--gain``), the
orientation of a pair (``--record-2``, ``--azimuth``, ``--azimuth-step``), a vertical motion (``--vertical`` and its
kin), a folder suite's ``--glob``/``--exclude``; each read back by its ``given_*`` function, and the scale factors
checked (:func:`scaled`)."""

from __future__ import annotations

import click

from rockcli.cli.option_kinds import _kept, _remember, _stacked, alias_option
from rockcli.cli.types import NUMBER, WHOLE


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
    from rockcli.cli.options import add_inputs
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
