"""``rockcli spectrum``: overturning maps, minimum overturning acceleration, critical block size."""

from __future__ import annotations


import click

from rockcli.cli.errors import InputError, user_errors
from rockcli.cli.options import (add_inputs, alias_option, cap_ratio_option, echo_json, horizon_option, json_option,
                                 progress_bar, quiet_option, record_kwargs, record_options, restitution_option,
                                 spectrum_vertical_option)
from rockcli.cli.options import DEFAULT_GAMMA_TEXT, DEFAULT_XI_TEXT, GAMMA_HELP, Group
from rockcli.cli.spectrum_plinth import on_option, plinth_summary, spectrum_plinths
from rockcli.cli.types import NUMBER

_SHAPES = "ricker-sym|ricker-anti|sine|cosine"


@click.group(name="spectrum", cls=Group)
def spectrum():
    """Overturning spectra over omega_p/p and a_p/(g tan alpha) (the paper's Figures 6-9, 11, Table I).

    Every cell is a pulse of amplitude a_p and period T_p = 2 pi/omega_p on a block of slenderness
    alpha; the result does not depend on the block size when T_b/T_p is kept fixed, so isolation
    is given as KIND:TbTp=<T_b/T_p>,... (e.g. linear:TbTp=2,xi=0.05,gamma=0.01). Left out, xi = 0.1
    and gamma = 0.01, as in every command; the paper's Figures 6-9, 11 and Table I have xi = 0.05.

    A full figure takes from seconds to minutes: for a quick look add a coarse grid to any example,
    --wp-over-p 2:6:2 with --ap 1:5:2 (overturning) or with --step 0.1 (min-overturning,
    critical-size).

    'rocking' is the spectrum of one record instead: peak theta/alpha against the block size R,
    with bearings given by their period in s (docs/rocking-spectrum.md).

    --on NAME:height_ratio=H2/H1,width_ratio=B2/B1 runs every configuration alone and standing on a
    free plinth in proportion to the block (docs/spectra.md).
    """


def _scene_options(isolation_help: str, isolation_default, multiple_isolation: bool = True):
    def decorate(f):
        options = [
            click.option("--alpha", "alpha", required=True, metavar="DEG[,DEG...]",
                         help="Block slenderness atan(b/h) [degrees]; a comma list gives one row of panels each."),
            click.option("--pulse", "pulses", multiple=True, metavar="SHAPE[:Tp=S]",
                         help=f"Pulse shape ({_SHAPES}), repeatable; an optional period Tp [s] adds a block-size "
                              "axis. Default ricker-sym."),
            click.option("--record", "records", multiple=True, metavar="ID|FILE",
                         help="Take the pulse shape and T_p from the pulse fitted to this record (catalogue id or "
                              "file; rockcli fit-pulse), repeatable."),
            click.option("--isolation", "isolations", multiple=multiple_isolation, default=isolation_default,
                         metavar="SPEC", help=isolation_help),
            click.option("--csv", "csv_path", type=click.Path(), default=None,
                         help="Write the result as CSV."),
            click.option("--plot", "plot_path", type=click.Path(), default=None,
                         help="Draw the figure (.png, .pdf, .svg)."),
            click.option("--scheduler", default=None, metavar="tcp://HOST:PORT|local",
                         help="Run the cells in chunks on a Dask cluster (pip install -e \".[dask]\"): an "
                              "existing scheduler, or 'local' for a LocalCluster on this machine. A scheduler that "
                              "does not answer, has no worker or loses all its workers stops the run after "
                              "ROCKCLI_DASK_TIMEOUT seconds (default 60)."),
            json_option,
            quiet_option,
            horizon_option,
            restitution_option,
            cap_ratio_option,
            spectrum_vertical_option,
        ]
        f = record_options(f)
        for option in reversed(options):
            f = option(f)
        return f

    return decorate


def _check_ap_reach(text: str, y_max: float, alphas) -> None:
    """The grid's largest a_p = y g tan(alpha) within the pulses' supported 100 g (a grid reaching 1e306 g
    overflowed inside the solver and its cells were reported as not overturning)."""
    import math

    from rockcli.pulses import A_P_MAX_G

    a = max(alphas)
    reach = y_max * math.tan(math.radians(a))
    if reach > A_P_MAX_G:
        raise InputError(f"--ap {text!r} reaches a_p = {reach:.3g} g at alpha = {a:g} deg, beyond the supported "
                         f"{A_P_MAX_G:g} g (recorded peaks reach about 4 g); lower the grid's stop")


def _check_outputs(csv_path, plot_path):
    from rockcli.cli.options import check_outputs

    check_outputs((csv_path, "--csv", False), (plot_path, "--plot", True))


def _pulses(pulses, records, units, dt, fmt, column, default=("ricker-sym",)):
    """PulseChoices from --pulse and --record (notes printed for fitted records)."""
    from rockcli.spectra import parse_pulse_choice, pulse_from_record

    if any(v is not None for v in (units, dt, fmt, column)) and not records:
        raise InputError("--units, --dt, --format and --record-column apply to --record")
    out = [parse_pulse_choice(p) for p in pulses]
    if records:
        from rockcli.records import read_record

        for src in records:
            rec = read_record(src, **record_kwargs(units, dt, fmt, column))
            add_inputs([rec.meta.get("path")], "the record")
            out.append(pulse_from_record(rec))
    if not out:
        out = [parse_pulse_choice(p) for p in default]
    return out


def _runner(scheduler, horizon, restitution=None, cap_ratio=0.0, isolations=(), fix="give --isolation none"):
    """The Runner of a spectrum, its options checked (``isolations``: Isolation specs or foundations)."""
    from rockcli.models.colonnade import check_cap_ratio
    from rockcli.models.impact import check_restitution
    from rockcli.solve import validate_options
    from rockcli.spectra import Runner

    validate_options(horizon=horizon)
    restitution = check_restitution(restitution, "--restitution")
    cap_ratio = check_cap_ratio(cap_ratio, "--cap-ratio")
    vertical = _vertical_choice(isolations, fix)
    if scheduler is not None:
        from rockcli.cli.options import dask_client
        from rockcli.distributed import check_scheduler

        check_scheduler(scheduler)
        scheduler = dask_client(scheduler)
    return Runner(scheduler, horizon=horizon, restitution=restitution, cap_ratio=cap_ratio, vertical=vertical)


def _vertical_choice(isolations, fix):
    """``--vertical-pulse`` as a :class:`rockcli.spectra.VerticalChoice` (None when not given); refused with an
    isolated foundation, in one sentence why."""
    from rockcli.cli.options import given_vertical

    text = given_vertical()["pulse"]
    if text is None:
        return None
    from rockcli.solve.excitation import VERTICAL_RIGID_ONLY
    from rockcli.spectra import parse_vertical_choice

    if not all(iso.rigid for iso in isolations):
        raise InputError(f"--vertical-pulse: {VERTICAL_RIGID_ONLY}; {fix}")
    return parse_vertical_choice(text)


def _echo_impacts(runner, err=False):
    if runner.restitution is not None:
        click.echo(f"impacts: coefficient of restitution E = {runner.restitution:g} (docs/simulate.md, "
                   f"Restitution)", err=err)
    if runner.cap_ratio > 0.0:
        click.echo(f"capped colonnades: beam/columns mass gamma_c = {runner.cap_ratio:g} (docs/physics-colonnade.md)",
                   err=err)
    if runner.vertical is not None:
        click.echo(f"vertical motion: a {runner.vertical.label} pulse under every cell, centred on the horizontal "
                   f"one (docs/vertical.md)", err=err)


def _csv_options(runner) -> dict:
    """Constant CSV columns of a given --restitution and --cap-ratio (nothing for the defaults)."""
    extra = {"restitution": runner.restitution} if runner.restitution is not None else {}
    if runner.cap_ratio > 0.0:
        extra["cap_ratio"] = runner.cap_ratio
    if runner.vertical is not None:
        extra["vertical"] = runner.vertical.label
    return extra


def _echo_unproven(runner, err=False):
    _echo_impacts(runner, err)
    if runner.unproven:
        click.echo(f"note: {runner.unproven} runs reached the solver's horizon with the verdict NOT PROVEN "
                   "(counted as surviving)", err=err)


def _echo_notes(pcs, err=False):
    for pc in pcs:
        if pc.note:
            click.echo(pc.note, err=err)


@spectrum.command(name="overturning")
@_scene_options("Foundation: none, or KIND:TbTp=<T_b/T_p>,... e.g. linear:TbTp=2,xi=0.05,gamma=0.01 "
                "(repeatable: one panel each). Default none. " + GAMMA_HELP, ("none",))
@alias_option("--wp-p", "wp_p", "--wp-over-p")
@click.option("--wp-over-p", "wp_p", default="0.5:12:200", show_default=True, metavar="START:STOP:COUNT",
              help="omega_p/p grid, both ends included.")
@click.option("--ap", "ap", default="0:10:200", show_default=True, metavar="START:STOP:COUNT",
              help="a_p/(g tan alpha) grid, both ends included.")
@click.option("--early/--full-peaks", default=True, show_default=True,
              help="--early (the default) stops each run as soon as its verdict is proven, even during the "
                   "pulse: theta_max_over_alpha is then only a lower bound where peak_final is 0. --full-peaks "
                   "follows every run until its peak is final (the same map, slower).")
@on_option
@user_errors
def overturning(alpha, pulses, records, isolations, csv_path, plot_path, scheduler, as_json, units, dt, fmt, column,
                wp_p, ap, early, horizon, restitution, cap_ratio, plinth_spec):
    """Overturning map over omega_p/p x a_p/(g tan alpha), like the paper's Figures 6 and 9.

    Light grey: the block rocks and survives; dark grey: it overturns; white: it never uplifts.
    The CSV has one row per cell (alpha_deg, pulse, isolation, T_p_s, R_m, wp_over_p,
    ap_over_g_tan_alpha, ap_g, overturned, theta_max_over_alpha, uplift, peak_final, proven).

    \b
    Examples:
      rockcli spectrum overturning --alpha 10 --plot fig6.png
      rockcli spectrum overturning --alpha 10,20 --isolation none --isolation linear:TbTp=2,xi=0.05,gamma=0.01 \\
          --isolation linear:TbTp=3,xi=0.05,gamma=0.01 --wp-over-p 0.5:12:120 --ap 0:10:120 --plot fig6.png
    """
    import time

    from rockcli.spectra import overturning_maps, parse_grid, parse_isolation, parse_list

    alphas = parse_list(alpha, "--alpha", lo=0, hi=90, lo_open=True, hi_open=True)
    wp_grid = parse_grid(wp_p, "--wp-over-p", positive=True)
    ap_grid = parse_grid(ap, "--ap")
    _check_ap_reach(ap, ap_grid.stop, alphas)
    isos = [parse_isolation(s) for s in isolations]
    _check_outputs(csv_path, plot_path)
    plinths = spectrum_plinths(plinth_spec, alphas, isos, cap_ratio=cap_ratio)
    runner = _runner(scheduler, horizon, restitution, cap_ratio, isos)
    pcs = _pulses(pulses, records, units, dt, fmt, column)
    n = len(alphas) * len(pcs) * len(isos) * len(plinths) * wp_grid.count * ap_grid.count
    t0 = time.perf_counter()
    with runner, progress_bar(n, "cells") as bar:
        update = bar.update if bar else None
        maps = overturning_maps(alphas, pcs, isos, wp_grid, ap_grid, runner=runner, progress=update, early=early,
                                plinths=plinths)
    elapsed = time.perf_counter() - t0
    _echo_notes(pcs, as_json)
    summaries = []
    for m in maps:
        cells = m.overturned.size
        unsettled = int((~m.settled & ~m.overturned).sum())  # reached the solver's horizon unproven
        summaries.append({"alpha_deg": m.alpha_deg, "pulse": m.pulse.label, "isolation": m.isolation.label,
                          **(plinth_summary(m.plinth) if plinth_spec else {}), "n_cells": cells, "n_overturn": int(m.overturned.sum()), "n_never_uplift": int((~m.uplifted).sum()),
                          "n_not_proven": unsettled})
        if not as_json:
            on = "" if not plinth_spec else (" on " + m.plinth.label if m.plinth else " alone")
            click.echo(f"alpha = {m.alpha_deg:g} deg, {m.pulse.label}, {m.isolation.label}{on}: "
                       f"{int(m.overturned.sum())} of {cells} cells overturn, {int((~m.uplifted).sum())} never uplift"
                       + (f", {unsettled} NOT PROVEN (still moving at the solver's horizon)" if unsettled else ""))
    if as_json:
        from rockcli.report.spectra import map_columns

        echo_json({**_csv_options(runner), "maps": [{**summary, "cells": map_columns(m)}
                                                     for summary, m in zip(summaries, maps)]})
    click.echo(f"{n} cells (omega_p/p {wp_grid}, a_p/(g tan alpha) {ap_grid}) in {elapsed:.2f} s", err=as_json)
    _echo_impacts(runner, as_json)
    if csv_path:
        from rockcli.report.spectra import write_map_csv

        write_map_csv(maps, csv_path, _csv_options(runner))
        click.echo(f"wrote {csv_path} ({n} rows)", err=as_json)
    if plot_path:
        from rockcli.report.spectra import plot_maps

        plot_maps(maps, plot_path, n_cols=len(pcs) * len(isos) * len(plinths))
        click.echo(f"wrote {plot_path}", err=as_json)


def _search_options(f):
    """--step, --refine, --refine-band, --tol of the minimum-overturning search (defaults: those of
    :mod:`rockcli.spectra.minimum`, written out so that ``--help`` imports no numpy)."""
    options = [
        click.option("--step", type=NUMBER, default=0.01, show_default=True,
                     help="Relative step of the scan up from the uplift threshold."),
        click.option("--refine", type=NUMBER, default=0.001, show_default=True,
                     help="Relative step of the second scan below the scan's first overturning value (see "
                          "--refine-band); 0: none (overturning windows narrower than --step can then be "
                          "missed)."),
        click.option("--refine-band", "refine_band", type=NUMBER, default=0.1, show_default=True,
                     help="How far below the scan's first overturning value the second scan starts (relative)."),
        click.option("--tol", type=NUMBER, default=0.001, show_default=True,
                     help="Relative resolution of the bisection after the scans."),
    ]
    for option in reversed(options):
        f = option(f)
    return f


@spectrum.command(name="min-overturning")
@_scene_options("Foundation (repeatable, one curve each): none, or KIND:TbTp=<T_b/T_p>,... "
                "Default: none and linear TbTp = 2, 3, 4 with the default xi = 0.1, gamma = 0.01 (the paper's "
                "Figure 7 has xi = 0.05: give linear:TbTp=2,xi=0.05 and so on). " + GAMMA_HELP,
                ("none", "linear:TbTp=2", "linear:TbTp=3", "linear:TbTp=4"))
@click.option("--gamma", "gammas", default=None, metavar="G[,G...]",
              help="Mass ratios m/(m + m_b): each isolated --isolation is run once per value (Figure 8).")
@alias_option("--wp-p", "wp_p", "--wp-over-p")
@click.option("--wp-over-p", "wp_p", default="0.5:12:93", show_default=True, metavar="START:STOP:COUNT",
              help="omega_p/p values, both ends included.")
@click.option("--ap-max", type=NUMBER, default=20.0, show_default=True,
              help="Largest a_p/(g tan alpha) tried; above it the curve is left empty.")
@_search_options
@on_option
@user_errors
def min_overturning(alpha, pulses, records, isolations, csv_path, plot_path, scheduler, as_json, units, dt, fmt,
                    column, gammas, wp_p, ap_max, step, tol, refine, refine_band, horizon, restitution,
                    cap_ratio, plinth_spec):
    """Minimum overturning acceleration over omega_p/p, like the paper's Figures 7, 8, 9 and 11.

    For each omega_p/p: the smallest a_p that overturns, found by scanning up from the uplift
    threshold in steps of --step (relative), scanning again in steps of --refine over the
    --refine-band below the first overturning value (where narrow overturning windows lie), and
    bisecting to --tol between the first overturning value scanned and the value below it, so
    overturning below a safe island is not missed. One curve per configuration; the rigid
    foundation as a heavy line.

    \b
    Examples:
      rockcli spectrum min-overturning --alpha 10,20 --pulse ricker-sym --pulse ricker-anti --isolation none \\
          --isolation linear:TbTp=2,xi=0.05 --isolation linear:TbTp=3,xi=0.05 --isolation linear:TbTp=4,xi=0.05 \\
          --plot fig7.png
      rockcli spectrum min-overturning --alpha 12 --isolation linear:TbTp=2,xi=0.05 \\
          --gamma 0.01,0.05,0.1,0.3,0.5 --pulse ricker-sym --pulse ricker-anti --plot fig8.png
    """
    import time

    from rockcli.spectra import min_overturning_curves, parse_grid, parse_isolation, parse_list

    alphas = parse_list(alpha, "--alpha", lo=0, hi=90, lo_open=True, hi_open=True)
    xs = parse_grid(wp_p, "--wp-over-p", positive=True).values
    isos = [parse_isolation(s) for s in isolations]
    if gammas is not None:
        gs = parse_list(gammas, "--gamma", lo=0, hi=1, hi_open=True)
        isos = [iso if iso.rigid else iso.with_param("gamma", g) for iso in isos for g in (gs if not iso.rigid else [0])]
        for iso in isos:
            iso.foundation(1.0)
    isos = list(dict.fromkeys(isos))
    _check_outputs(csv_path, plot_path)
    plinths = spectrum_plinths(plinth_spec, alphas, isos, cap_ratio=cap_ratio)
    runner = _runner(scheduler, horizon, restitution, cap_ratio, isos)
    pcs = _pulses(pulses, records, units, dt, fmt, column)
    n = len(alphas) * len(pcs) * len(isos) * len(plinths) * xs.size
    t0 = time.perf_counter()
    with runner, progress_bar(n, "search", eta=False, unit="columns") as bar:
        update = bar  # the columns done, and the runs as they finish (bar.runs)
        curves = min_overturning_curves(alphas, pcs, isos, xs, ap_max=ap_max, step=step, tol=tol, refine=refine,
                                        refine_band=refine_band, runner=runner, progress=update, plinths=plinths)
    elapsed = time.perf_counter() - t0

    from rockcli.report.spectra import format_min_table, min_rows

    _echo_notes(pcs, as_json)
    if as_json:
        echo_json({**_csv_options(runner), "points": list(min_rows(curves))})
    else:
        click.echo(format_min_table(curves))
    refined = sum(int(c.refined.sum()) for c in curves)
    click.echo(f"{len(curves)} curves x {xs.size} values of omega_p/p: {runner.cells_run} runs in {elapsed:.2f} s "
               f"({curves[0].found_by}, up to {ap_max:g} g tan alpha)"
               + (f"; {refined} minima lie in windows the first scan stepped over" if refine > 0 else ""), err=as_json)
    from rockcli.spectra.minimum import capped_note

    if capped_note(curves):
        click.echo(capped_note(curves), err=as_json)
    _echo_unproven(runner, as_json)
    if csv_path:
        from rockcli.report.spectra import write_min_csv

        write_min_csv(curves, csv_path, _csv_options(runner))
        click.echo(f"wrote {csv_path} ({len(curves) * xs.size} rows)", err=as_json)
    if plot_path:
        from rockcli.report.spectra import plot_min_curves

        plot_min_curves(curves, plot_path)
        click.echo(f"wrote {plot_path}", err=as_json)


@spectrum.command(name="critical-size")
@click.option("--alpha", "alpha", default="10,20", show_default=True, metavar="DEG[,DEG...]",
              help="Block slenderness [degrees] (Table I: 10 and 20).")
@alias_option("--tb-tp", "tb_tp", "--tbtp")
@click.option("--tbtp", "tb_tp", default="2,3,4", show_default=True, metavar="R[,R...]",
              help="Isolation periods as T_b/T_p (Table I: 2, 3, 4).")
@click.option("--isolation", "bearing", default="linear", show_default=True, metavar="KIND[:k=v,...]",
              help="Bearing kind and its parameters other than the period (T_b = ratio x T_p).")
@click.option("--xi", type=NUMBER, default=None,
              help=f"Damping ratio of linear bearings [default {DEFAULT_XI_TEXT}, as in every command; the paper's "
                   "Table I has 0.05: --xi 0.05].")
@click.option("--gamma", type=NUMBER, default=None,
              help=f"Mass ratio m/(m + m_b) [default {DEFAULT_GAMMA_TEXT}, as in every command and in Table I]. "
                   + GAMMA_HELP)
@click.option("--pulse", "pulses", multiple=True, metavar="SHAPE:Tp=S",
              help="A pulse with its period [s], repeatable. Default: the paper's Table I pulses, "
                   "ricker-sym:Tp=0.6 (Aigio OTE FP 1995) and ricker-anti:Tp=0.9 (Coyote Lake Gilroy #6 230).")
@click.option("--record", "records", multiple=True, metavar="ID|FILE",
              help="Take shape and T_p from the pulse fitted to this record (repeatable).")
@record_options
@alias_option("--wp-p", "wp_p", "--wp-over-p")
@click.option("--wp-over-p", "wp_p", default="0.5:12:47", show_default=True, metavar="START:STOP:COUNT",
              help="omega_p/p grid on which the curves are compared before the crossing is refined.")
@click.option("--xtol", type=NUMBER, default=1e-3, show_default=True,
              help="Relative resolution of the crossing in omega_p/p.")
@click.option("--ap-max", type=NUMBER, default=50.0, show_default=True,
              help="Largest a_p/(g tan alpha) tried (above it: no overturning).")
@_search_options
@click.option("--csv", "csv_path", type=click.Path(), default=None,
              help="Write the table as CSV (source, pulse, T_p_s, alpha_deg, Tb_over_Tp, Tb_s, "
                   "wp_over_p_cross, R_critical_m).")
@click.option("--plot", "plot_path", type=click.Path(), default=None,
              help="Draw the compared curves with the crossings marked.")
@click.option("--scheduler", default=None, metavar="tcp://HOST:PORT|local",
              help="Run the cells on a Dask cluster (see overturning).")
@json_option
@quiet_option
@horizon_option
@restitution_option
@spectrum_vertical_option
@on_option
@user_errors
def critical_size(alpha, tb_tp, bearing, xi, gamma, pulses, records, units, dt, fmt, column, wp_p, xtol, ap_max,
                  step, tol, refine, refine_band, csv_path, plot_path, scheduler, as_json, horizon, restitution,
                  plinth_spec):
    """Block size beyond which a block is safer without isolation, like the paper's Table I.

    Where the minimum overturning curves of the rigid foundation and of the isolated base cross
    (the last crossing on the grid, rigid better beyond it), converted to the semi-diagonal R with
    p = omega_p/(omega_p/p)_cross and R = 3 g/(4 p^2). Defaults: the paper's Table I scenes,
    alpha = 10 and 20 deg, T_b/T_p = 2, 3, 4, linear bearings, pulses
    ricker-sym T_p = 0.6 s and ricker-anti T_p = 0.9 s; the bearings have the default xi = 0.1, gamma = 0.01
    of every command (Table I has xi = 0.05: add --xi 0.05).

    \b
    Examples:
      rockcli spectrum critical-size --xi 0.05 --csv table1.csv
      rockcli spectrum critical-size --alpha 10.56 --tbtp 2,2.5,3 --xi 0.1 --record coyotelake-1979-gilroy6-230
    """
    import time

    from rockcli.spectra import critical_sizes, parse_grid, parse_list, table_i_isolations, table_i_pulses

    alphas = parse_list(alpha, "--alpha", lo=0, hi=90, lo_open=True, hi_open=True)
    ratios = parse_list(tb_tp, "--tbtp", lo=0, lo_open=True)
    grid = parse_grid(wp_p, "--wp-over-p", positive=True)
    if grid.count < 2:
        raise InputError(f"--wp-over-p {wp_p}: the crossing needs at least 2 grid values")
    kind = bearing.strip().partition(":")[0].strip().lower()
    if kind in ("none", "rigid", "fixed"):
        raise InputError("--isolation: give a bearing kind (e.g. linear); the rigid foundation is always compared")
    from rockcli.models import DEFAULT_GAMMA, DEFAULT_XI

    if xi is None and kind == "linear":
        xi = DEFAULT_XI
    if gamma is None:
        gamma = DEFAULT_GAMMA
    isos = table_i_isolations(ratios, xi=xi, gamma=gamma, template=bearing)
    _check_outputs(csv_path, plot_path)
    plinths = spectrum_plinths(plinth_spec, alphas, isos)
    runner = _runner(scheduler, horizon, restitution, isolations=isos,
                     fix="critical-size compares the rigid foundation with isolated bases, so it cannot take one")
    if pulses or records:
        pcs = _pulses(pulses, records, units, dt, fmt, column, default=())
    else:
        if any(v is not None for v in (units, dt, fmt, column)):
            raise InputError("--units, --dt, --format and --record-column apply to --record")
        pcs = table_i_pulses()
    for pc in pcs:
        if pc.T_p is None:
            raise InputError(f"--pulse {pc.shape}: give its period, e.g. {pc.shape}:Tp=0.6")
    shapes = list(dict.fromkeys(pc.shape for pc in pcs))
    n = len(shapes) * len(alphas) * len(plinths) * (1 + len(isos)) * grid.count
    t0 = time.perf_counter()
    with runner, progress_bar(n, "search", eta=False, unit="columns") as bar:
        update = bar  # the columns done, and the runs as they finish (bar.runs)
        result = critical_sizes(pcs, alphas, isos, wp_grid=grid, xtol=xtol, ap_max=ap_max, step=step, tol=tol,
                                refine=refine, refine_band=refine_band, runner=runner, progress=update,
                                plinths=plinths)
    elapsed = time.perf_counter() - t0

    from rockcli.report.spectra import format_critical_table

    _echo_notes(pcs, as_json)
    isolation = isos[0].label.replace(f'TbTp={isos[0].ratio:g}', 'TbTp=<ratio>')
    if as_json:
        echo_json({"isolation": isolation, **_csv_options(runner),
                   "rows": [{**r.as_dict(), **({"plinth": r.plinth or None} if plinth_spec else {}),
                             "ap_cross_over_g_tan_alpha": r.ap_cross_over_g_tan_alpha,
                             "note": r.note or None} for r in result.rows],
                   "notes": list(result.notes)})
    else:
        click.echo(f"isolation: {isolation}")
        click.echo(format_critical_table(result.rows))
        for r in result.rows:
            if r.note:
                click.echo(f"note: {r.source}, alpha = {r.alpha_deg:g} deg, T_b/T_p = {r.Tb_over_Tp:g}"
                           f"{' on ' + r.plinth if r.plinth else ''}: {r.note}")
        for note in result.notes:
            click.echo(f"note: {note}")
    click.echo(f"{len(result.rows)} crossings: {result.runs} runs in {elapsed:.2f} s (omega_p/p grid {grid}, "
               f"refined to {xtol:g}; minima: {result.curves[0].found_by})", err=as_json)
    _echo_unproven(runner, as_json)
    if csv_path:
        from rockcli.report.spectra import write_critical_csv

        write_critical_csv(result.rows, csv_path, _csv_options(runner))
        click.echo(f"wrote {csv_path} ({len(result.rows)} rows)", err=as_json)
    if plot_path:
        from rockcli.report.spectra import plot_min_curves

        crossings = {}
        for r in result.rows:
            if r.wp_over_p_cross == r.wp_over_p_cross:
                crossings.setdefault((r.alpha_deg, r.pulse), []).append(
                    (r.wp_over_p_cross, r.ap_cross_over_g_tan_alpha,
                     f"$R$ = {r.R_critical_m:.2f} m ($T_p$ = {r.T_p_s:.3g} s, $T_b/T_p$ = {r.Tb_over_Tp:g}"
                     f"{', on the plinth' if r.plinth else ''})"))
        plot_min_curves(result.curves, plot_path, crossings=crossings)
        click.echo(f"wrote {plot_path}", err=as_json)


from rockcli.cli.spectrum_rocking import rocking  # noqa: E402 (it uses the helpers above)

spectrum.add_command(rocking)
