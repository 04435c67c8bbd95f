"""``rockcli simulate``: one block, one foundation, one excitation."""

from __future__ import annotations

import math

import click

from rockcli.cli.errors import user_errors
from rockcli.cli.options import (azimuth_options, block_from_options, block_options, cap_ratio_option,
                                 check_outputs, command_line, horizon_option, json_option, plinth_option,
                                 record_kwargs, record_options, report_option, restitution_option, scaled,
                                 simulate_vertical_component_option, stack_from_option)
from rockcli.cli.options import GAMMA_HELP, REPORT_SUFFIXES, Command
from rockcli.cli.simulate_drums import DRUMS_HELP
from rockcli.cli.simulate_friction import FRICTION_HELP
from rockcli.cli.types import NUMBER, WHOLE


@click.command(cls=Command, context_settings={"show_default": True})
@block_options
@click.option("--isolation", default=("none",), multiple=True, metavar="SPEC",
              help="Foundation (repeatable: several draw their scenes side by side with --plot, like the paper's "
                   "Figure 12): 'none' (rigid); 'linear:Tb=2.5,xi=0.1,gamma=0.01'; single concave sliding "
                   "'scss:Tb=3,mu=0.05[,uy=0.00025,gamma=0.01]'; lead-rubber 'lrb:Tb=2.5,Q=0.06,uy=0.015' "
                   "(Q = strength/weight); double concave 'dcss:R1=1.1,R2=1.1,mu1=0.03,mu2=0.07[,uy=..,gamma=..]' "
                   "(effective radii R-h in m) or 'dcss:Tb=3,mu1=0.03,mu2=0.07[,r=R2/R1]'; uy = yield displacement "
                   "[m]. " + GAMMA_HELP)
@click.option("--record", "record_source", default=None, metavar="SOURCE",
              help="Ground motion: a record file or a catalogue id (see 'rockcli records list').")
@record_options
@azimuth_options
@click.option("--pulse", multiple=True, metavar="SPEC",
              help="Ground motion: an analytic pulse, e.g. 'ricker-sym:ap=0.3,Tp=0.6' (ap in g, Tp in s); "
                   "shapes ricker-sym, ricker-anti, sine, cosine (repeatable: several draw their scenes side by side "
                   "with --plot, like the paper's Figure 1).")
@click.option("--vertical", "vertical_source", default=None, metavar="SOURCE",
              help="Vertical ground acceleration (upward positive), rigid foundation only: a record file or a "
                   "catalogue id, read with the same --units/--dt/--format as --record; it must share the horizontal "
                   "record's time step and start (it may be shorter or longer: zero after its end). Gravity becomes "
                   "g + a_v.")
@click.option("--vertical-column", "vertical_column", type=WHOLE, default=None, metavar="N",
              help="Column of the --vertical file (as --record-column).")
@simulate_vertical_component_option
@click.option("--vertical-pulse", "vertical_pulse", default=None, metavar="SPEC",
              help="Vertical ground acceleration as an analytic pulse (same SPEC as --pulse; ap in g, upward "
                   "positive).")
@click.option("--vertical-scale", "vertical_scale", type=NUMBER, default=1.0,
              help="Multiply the vertical acceleration by this factor (--scale and --flip act on the horizontal only).")
@click.option("--theta0", type=NUMBER, default=0.0, metavar="RAD",
              help="Start rocking from this tilt [rad] (|theta0| < pi/2; > 0 on the right corner) instead of at rest; "
                   "without --record/--pulse the block rocks freely on still ground.")
@click.option("--theta-dot0", "theta_dot0", type=NUMBER, default=0.0, metavar="RAD/S",
              help="Start with this angular velocity [rad/s] (with or without --theta0).")
@click.option("--scale", type=NUMBER, default=1.0, help="Multiply the record's acceleration by this factor.")
@click.option("--flip", is_flag=True, help="Reverse the sign of the ground motion.")
@click.option("--rtol", type=NUMBER, default=None,
              help="Relative tolerance of the integrator [default: 5e-9; 2e-9 on sliding and lead-rubber bearings].")
@click.option("--tail", type=NUMBER, default=10.0,
              help="Free motion shown after the excitation in --history/--plot [s]; never changes the verdict.")
@horizon_option
@restitution_option
@cap_ratio_option
@click.option("--check-tolerance", "check", is_flag=True,
              help="Rerun at a 100x tighter rtol, and on 2 copies of the motion moved by one ulp, and report "
                   "whether the verdict or the peak changes (ill-conditioned: the answer is not determined by the "
                   "motion at double precision).")
@json_option
@click.option("--history", "history_path", type=click.Path(), default=None,
              help="Write the time history (t, ground acceleration, theta, theta_dot, u, u_dot; on sliding and "
                   "lead-rubber bearings also z and the bearing force over the weight) as CSV.")
@click.option("--history-dt", "history_dt", type=NUMBER, default=None, metavar="SECONDS",
              help="Write the history (--history, --plot, --report) on a uniform grid of this spacing, from the "
                   "solver's dense output, instead of at its steps, up to the end of the excitation plus --tail "
                   "(at most 2,000,000 rows, counted before the run); the event rows (uplift, impact, peak, rest, "
                   "overturn) stay exact either way.")
@click.option("--plot", "plot_path", type=click.Path(), default=None,
              help="Draw ground acceleration, theta/alpha, theta_dot/p (and base displacement u(t); on sliding "
                   "and lead-rubber bearings also their force-displacement loop) to an image.")
@report_option
@plinth_option
@click.option("--friction", default=None, metavar="MU|base=MU,joint=MU", help=FRICTION_HELP)
@click.option("--drums", default=None, metavar="N|HxW,HxW,...", help=DRUMS_HELP)
@user_errors
def simulate(column_name, R, alpha, height, width, name, isolation, record_source, units, dt, fmt, column,
             pulse, vertical_source, vertical_column, vertical_pulse, vertical_scale, theta0, theta_dot0, scale,
             flip, rtol, tail, horizon, restitution, cap_ratio, check, as_json,
             history_path, history_dt, plot_path, report_path, plinth_spec, friction, drums):
    """Rocking response of one block to one ground motion, on a rigid or an isolated base.

    \b
    Examples:
      rockcli simulate --height 2 --width 0.5 --pulse sine:ap=0.29,Tp=2
      rockcli simulate --height 2 --width 0.5 --pulse sine:ap=0.5,Tp=0.5 --pulse sine:ap=0.29,Tp=2 --plot fig1.png
      ROCKCLI_RECORDS=../shared/records rockcli simulate --body nemea --record kobe-1995-takarazuka-000 \\
          --isolation linear:Tb=3
      rockcli simulate --body statue:height=1.7,width=0.45 --pulse ricker-anti:ap=0.4,Tp=0.5 --json
      rockcli simulate --R 1 --alpha 16 --pulse ricker-sym:ap=0.5,Tp=0.6 --isolation scss:Tb=1.8,mu=0.05 --plot f.png
      rockcli simulate --R 2.5 --alpha 11.5 --theta0 0.1 --restitution 0.9 --history free.csv
      rockcli simulate --R 1 --alpha 14 --theta0 0.2 --history-dt 0.01 --history free.csv --json
      rockcli simulate --body bassae --record ../shared/records/RSN1119_KOBE_TAZ000.AT2 \\
          --vertical-pulse sine:ap=0.2,Tp=0.3
      rockcli simulate --body statue:height=1.79,width=0.5 --pulse ricker-sym:ap=0.35,Tp=1 \\
          --on plinth:height=1.0,width=0.6 --friction 0.5
      rockcli simulate --body crate:height=0.5,width=1.0 --pulse sine:ap=0.5,Tp=1 --friction 0.2
    """
    import json

    from rockcli.errors import RockcliInputError
    from rockcli.models.impact import check_restitution
    from rockcli.models import parse_isolation_spec
    from rockcli.io.units import G

    check_outputs((history_path, "--history", False), (plot_path, "--plot", True),
                  (report_path, "--report", REPORT_SUFFIXES))
    if history_dt is not None:
        from rockcli.solve.single import check_history_dt

        history_dt = check_history_dt(history_dt, "--history-dt")
    block = block_from_options(column_name, R, alpha, height, width, name)
    if len(isolation) > 1 or len(pulse) > 1:  # several scenes side by side in one figure (Figures 1 and 12)
        from rockcli.cli.simulate_beside import run_beside

        return run_beside(block, isolation, pulse, record_source=record_source,
                          record_kw=record_kwargs(units, dt, fmt, column), scale=scale, flip=flip, rtol=rtol,
                          tail=tail, horizon=horizon, restitution=restitution, cap_ratio=cap_ratio,
                          plot_path=plot_path, one_scene={
                              "--json": as_json, "--history": history_path, "--history-dt": history_dt,
                              "--report": report_path, "--check-tolerance": check, "--on": plinth_spec,
                              "--friction": friction, "--theta0": theta0, "--theta-dot0": theta_dot0,
                              "--drums": drums,
                              "--vertical": vertical_source, "--vertical-pulse": vertical_pulse})
    isolation, pulse = isolation[0], (pulse[0] if pulse else None)
    foundation = parse_isolation_spec(isolation)
    restitution = check_restitution(restitution, "--restitution")
    solver = {} if restitution is None else {"restitution": restitution}
    from rockcli.models.colonnade import check_cap_ratio
    from rockcli.models.initial import check_initial_state

    cap_ratio = check_cap_ratio(cap_ratio, "--cap-ratio")
    if cap_ratio > 0.0:
        solver["cap_ratio"] = cap_ratio

    theta0, theta_dot0 = check_initial_state(theta0, theta_dot0, ("--theta0", "--theta-dot0"))
    moving = theta0 != 0.0 or theta_dot0 != 0.0
    stack = stack_from_option(block, plinth_spec)
    if drums is not None:
        from rockcli.cli.azimuth import wants_worst
        from rockcli.cli.simulate_drums import check_drums_scene, parse_drums
        from rockcli.cli.simulate_friction import check_friction_scene, parse_friction

        check_drums_scene(stacked=stack is not None, restitution=restitution, friction=friction, others=(
            ("--history", history_path), ("--plot", plot_path), ("--report", report_path)))
        drums = parse_drums(drums, block)
        friction = parse_friction(friction, False)
        check_friction_scene(foundation, cap_ratio=cap_ratio, moving=moving, restitution=None, check=check,
                             history_dt=history_dt, worst=wants_worst(), stacked=False,
                             vertical=vertical_source is not None or vertical_pulse is not None)
    elif friction is not None:
        from rockcli.cli.azimuth import wants_worst
        from rockcli.cli.simulate_friction import check_friction_scene, parse_friction

        friction = parse_friction(friction, stack is not None)
        check_friction_scene(foundation, cap_ratio=cap_ratio, moving=moving, restitution=restitution, check=check,
                             history_dt=history_dt, worst=wants_worst(), stacked=stack is not None,
                             vertical=vertical_source is not None or vertical_pulse is not None)
    if stack is not None:
        from rockcli.cli.simulate_plinth import refuse_with_plinth

        refuse_with_plinth(foundation, cap_ratio=cap_ratio, moving=moving, check=check,
                           history_dt=history_dt, vertical=(vertical_source, vertical_pulse))
    if moving:
        solver.update(theta0=theta0, theta_dot0=theta_dot0)
    if record_source is not None and pulse is not None:
        raise RockcliInputError("give the ground motion as exactly one of --record SOURCE or --pulse SPEC")
    if record_source is None and pulse is None and not moving:
        raise RockcliInputError("give the ground motion as exactly one of --record SOURCE or --pulse SPEC, or start "
                                "the block rocking freely with --theta0 RAD and/or --theta-dot0 RAD/S")
    if check and record_source is None and pulse is None:
        raise RockcliInputError("--check-tolerance perturbs the ground motion: it needs --record or --pulse")
    from rockcli.io.inputs import check_scale, format_number

    check_scale(scale, 0.0, "--scale")  # and the motion's peak times it, once read
    factor = -scale if flip else scale
    if record_source is None:
        from rockcli.cli.azimuth import refuse_without_record

        refuse_without_record()
    if record_source is None and pulse is None:
        if any(v is not None for v in (units, dt, fmt, column)):
            raise RockcliInputError("--units, --dt, --format and --record-column apply to --record")
        excitation, label = None, "free rocking (no ground motion)"
    elif pulse is not None:
        from rockcli.pulses import parse_pulse_spec

        if any(v is not None for v in (units, dt, fmt, column)):
            raise RockcliInputError("--units, --dt, --format and --record-column apply to --record, not to --pulse")
        excitation = _flipped(scaled(parse_pulse_spec(pulse), scale, "--scale", "the pulse"), flip)
        label = f"{excitation.shape} pulse"
    else:
        from rockcli.cli.azimuth import read_excitation, run_worst, wants_worst

        excitation, pair = read_excitation(record_source, record_kwargs(units, dt, fmt, column))
        label = f"record {excitation.name}" + (f" x {format_number(factor)}" if factor != 1.0 else "")
        # every orientation of a pair peaks at most at max_t |(a_1, a_2)| (perpendicular components): checked
        # for --azimuth worst, which runs them all
        record = _flipped(scaled(excitation, scale, "--scale", "the record",
                                 peak_g=_pair_peak_g(pair) if pair is not None and wants_worst() else None), flip)
        if pair is not None and wants_worst():
            if history_path or plot_path or report_path or check or moving:
                raise RockcliInputError("--azimuth worst runs every orientation verdict-only: --history, --plot, "
                                        "--report, --check-tolerance and --theta0 need one --azimuth DEG")
            return run_worst(block, foundation, pair, factor, as_json=as_json, label=label.split("@")[0],
                             rtol=rtol, tail=tail, horizon=horizon, **solver)
        excitation = record

    vertical, vlabel = _vertical(vertical_source, vertical_column, vertical_pulse, vertical_scale, units, dt, fmt)
    if vertical is not None:
        solver["vertical"] = vertical

    if drums is not None:
        from rockcli.cli.simulate_drums import run_drums

        return run_drums(drums, foundation, excitation, label, friction, as_json=as_json, rtol=rtol, tail=tail,
                         horizon=horizon, pga=_pga(excitation, G))
    friction_res = None
    if friction is not None:  # the friction run first: where nothing slides, the rocking answer below stands
        from rockcli.cli.simulate_friction import run_friction

        friction_res = run_friction(stack if stack is not None else block, foundation, excitation, label, friction,
                                    rtol=rtol, tail=tail, horizon=horizon, history_path=history_path,
                                    plot_path=plot_path, report_path=report_path, as_json=as_json,
                                    pga=_pga(excitation, G), motion=None if pulse is not None else label,
                                    restitution=restitution)
        if friction_res is None:
            return
    if stack is not None:
        from rockcli.cli.simulate_plinth import run_plinth

        return run_plinth(stack, foundation, excitation, label, restitution=restitution, rtol=rtol, tail=tail,
                          horizon=horizon, history_path=history_path, as_json=as_json, friction_res=friction_res,
                          pga=_pga(excitation, G), plot_path=plot_path, motion=None if pulse is not None else label,
                          report_path=report_path)
    from rockcli.solve import simulate as run

    res = run(block, foundation, excitation, rtol=rtol, tail=tail, horizon=horizon,
              history=bool(history_path or plot_path or report_path), history_dt=history_dt, **solver)
    if res.status < 0:  # a genuine numerical failure: no result is printed or written as if it were valid
        raise click.ClickException(
            f"the integrator stopped at its safety cap of {res.steps + res.rejected_steps:,} steps at "
            f"t = {res.t_end_s:.3f} s, a numerical failure: no result is given (please report the command line)")
    checked = _check(block, foundation, excitation, res, rtol, horizon, solver) if check else None
    if history_path:
        from rockcli.report.response import write_history_csv

        write_history_csv(res, block, history_path)
    shown = res  # the figures draw the response from the dense output between the steps
    if (plot_path or report_path) and res.history.grid_dt is None:
        from rockcli.report.figures import plot_grid_dt

        shown = run(block, foundation, excitation, rtol=rtol, tail=tail, horizon=horizon, history=True,
                    history_dt=plot_grid_dt(excitation), **solver)
    motion = (None if pulse is not None else label) if vertical is None else f"{label}; vertical: {vlabel}"
    if plot_path:
        from rockcli.report.response import plot_response

        plot_response(shown, block, foundation, plot_path, excitation=excitation, motion=motion)
    if report_path:
        from rockcli.report.html import write_report
        from rockcli.report.html_pages import simulate_report

        write_report(report_path, simulate_report(block, foundation, excitation, shown, label=label, checked=checked,
                                                  command=command_line(), restitution=restitution,
                                                  cap_ratio=cap_ratio))

    if as_json:
        out = {"block": block.name, "R_m": block.R, "alpha_deg": block.alpha_deg, "p_radps": block.p,
               "isolation": foundation.label, "excitation": label,
               **_impact_keys(block, foundation, restitution, cap_ratio),
               **({"theta0": theta0, "theta_dot0": theta_dot0} if moving else {}),
               **({"vertical": vlabel} if vertical is not None else {}),
               **res.summary()}
        if res.history is not None:  # a history run (--history, --history-dt, --plot, --report): its events
            out["events"] = [e.as_dict() for e in res.history.events]
        if checked:
            out.update({k: (None if isinstance(v, float) and v != v else v) for k, v in checked.items()})
        if friction_res is not None:
            from rockcli.cli.simulate_friction import friction_keys

            out.update(friction_keys(friction_res, False))
        click.echo(json.dumps(out, allow_nan=False))
        return

    def fmt_t(x):
        return "-" if x != x else f"{x:.3f} s"

    rows = [
        ("block", f"{block.name}: R = {block.R:.3f} m, alpha = {block.alpha_deg:.2f} deg "
                  f"(h/b = {block.h / block.b:.2f}), p = {block.p:.3f} rad/s"),
        ("foundation", foundation.label),
        *([("colonnade", _colonnade_row(block, foundation, cap_ratio))] if cap_ratio > 0.0 else []),
        *([("impact rule", _impact_row(block, foundation, restitution, cap_ratio))] if restitution is not None else []),
        ("excitation", label + _pga(excitation, G)),
        *([("vertical", vlabel + _pga(vertical, G))] if vertical is not None else []),
        *([("start", f"theta0 = {theta0:g} rad ({theta0 / block.alpha:.4g} alpha), theta_dot0 = {theta_dot0:g} rad/s")]
          if moving else []),
        ("verdict", {"overturned": "OVERTURNS", "rocked": "survives (rocks)",
                     "no_uplift": "survives (no uplift)"}[res.verdict]),
        ("uplift at", fmt_t(res.t_uplift_s)),
        ("|theta| > alpha at", fmt_t(res.t_exceed_alpha_s)),
        ("overturn at", fmt_t(res.t_overturn_s)),
        ("peak |theta|/alpha", f"{res.theta_max_over_alpha:.4f}" if not res.overturned else "overturned"),
        ("impacts", f"{res.n_impacts} during shaking, {res.n_impacts_total} in all"),
        ("peak base disp.", f"{res.base_disp_max_m:.4f} m"),
        ("integration", f"{res.steps} steps, {res.nfev} right-hand sides, ended at {res.t_end_s:.2f} s"),
    ]
    if checked:
        rows += _check_rows(checked, res)
    if friction_res is not None:
        from rockcli.cli.simulate_friction import no_slide_row

        rows.append(no_slide_row(friction_res))
    width_ = max(len(k) for k, _ in rows)
    for k, v in rows:
        click.echo(f"{k:<{width_}}  {v}")
    if not res.settled:
        click.echo(f"NOTE: the verdict is NOT PROVEN: at {res.t_end_s:.1f} s (the horizon) the base could still lift "
                   "the block; lengthen --horizon to follow it")


def _flipped(motion, flip: bool):
    """``--flip``: the motion times -1 (exact: ``scaled(scale)`` then ``scaled(-1)`` is ``scaled(-scale)``)."""
    return motion.scaled(-1.0) if flip else motion


def _pair_peak_g(pair) -> float:
    """The largest peak [g] of the projections of a perpendicular pair onto any azimuth: ``max_t |(a_1, a_2)|``."""
    import numpy as np

    from rockcli.io.units import G

    n = max(r.npts for r in pair)
    a = [np.pad(r.acc, (0, n - r.npts)) for r in pair]
    return float(np.max(np.hypot(*a))) / G if n else 0.0


def _vertical(source, column, pulse, scale, units, dt, fmt):
    """``(vertical motion or None, its label)`` from ``--vertical``/``--vertical-pulse``/``--vertical-scale``."""
    from rockcli.cli.options import given_vertical, read_vertical

    return read_vertical(source, column, pulse, scale, record_kwargs(units, dt, fmt, None),
                         given_vertical()["component"])


def _eta(block, foundation, restitution, cap_ratio) -> float:
    """``theta_dot+ / theta_dot-`` at an impact of this block or colonnade on this foundation."""
    from rockcli.models.colonnade import impact_ratio_on_base
    from rockcli.models.impact import impact_ratio

    if cap_ratio > 0.0:
        return impact_ratio_on_base(block.alpha, foundation.gamma, cap_ratio, restitution)
    return impact_ratio(block.alpha, foundation.gamma, restitution)


def _impact_keys(block, foundation, restitution, cap_ratio=0.0) -> dict:
    """JSON keys of a given restitution and of a colonnade (none for the defaults)."""
    from rockcli.models.colonnade import frequency_factor

    out = {} if restitution is None else {"restitution": restitution}
    if cap_ratio > 0.0:
        out.update(cap_ratio=cap_ratio, p_colonnade_radps=block.p * math.sqrt(frequency_factor(cap_ratio)))
    if out:
        out["impact_ratio"] = _eta(block, foundation, restitution, cap_ratio)
    return out


def _colonnade_row(block, foundation, cap_ratio) -> str:
    from rockcli.models.colonnade import frequency_factor

    return (f"capped, beam/columns mass gamma_c = {cap_ratio:g}: p = {block.p * math.sqrt(frequency_factor(cap_ratio)):.3f} "
            f"rad/s, impact ratio {_eta(block, foundation, None, cap_ratio):.4f} (Makris & Vassiliou 2013)")


def _impact_row(block, foundation, restitution, cap_ratio) -> str:
    from rockcli.models.impact import housner_restitution

    return (f"restitution E = {restitution:g} (Housner's {housner_restitution(block.alpha):.4f}): "
            f"theta_dot+ = {_eta(block, foundation, restitution, cap_ratio):.4f} theta_dot-")


def _check(block, foundation, excitation, res, rtol, horizon, solver=None) -> dict:
    """``--check-tolerance``: the verdict-only run at a 100x tighter rtol and on one-ulp copies of
    the motion, compared with this run's verdict and peak (|theta|/alpha; the overturning time [s]
    when it overturns). Changes are NaN where the verdict changed."""
    from rockcli.conditioning import ULP_DRAWS, answer_change, ill_conditioned, measure_conditioning
    from rockcli.solve import default_rtol, simulate

    base_rtol = default_rtol(foundation) if rtol is None else rtol
    solver = solver or {}
    tight = simulate(block, foundation, excitation, rtol=base_rtol / 100.0, horizon=horizon, **solver)
    d_tight = answer_change(res, tight)
    spread, verdicts = measure_conditioning(block, foundation, excitation, seed=1980,
                                            base=res if res.history is None else None, rtol=rtol, horizon=horizon,
                                            **solver)
    return {"check_tight_rtol": base_rtol / 100.0, "check_tight_rtol_verdict": tight.verdict,
            "check_tight_rtol_change": d_tight, "check_ulp_draws": ULP_DRAWS, "check_ulp_verdicts": list(verdicts),
            "check_ulp_change": spread, "check_ill_conditioned": ill_conditioned(res.verdict, spread, verdicts)}


def _check_rows(c: dict, res) -> list:
    what = "overturning time" if res.overturned else "peak |theta|/alpha"
    unit = " s" if res.overturned else ""
    tight = f"rtol {c['check_tight_rtol']:g}: "
    if c["check_tight_rtol_verdict"] != res.verdict:
        tight += f"VERDICT CHANGES to {c['check_tight_rtol_verdict']} (decided by the numerics)"
    else:
        tight += f"same verdict, {what} moves by {c['check_tight_rtol_change']:.1e}{unit}"
    head = f"{c['check_ulp_draws']} motions moved by one ulp: "
    if any(v != res.verdict for v in c["check_ulp_verdicts"]):
        ulp = head + f"VERDICT CHANGES ({', '.join(c['check_ulp_verdicts'])}): ILL-CONDITIONED"
    else:
        ulp = head + f"same verdict, {what} moves by up to {c['check_ulp_change']:.1e}{unit}"
        if c["check_ill_conditioned"]:
            ulp += ": ILL-CONDITIONED (the answer is not determined by the motion at double precision)"
    return [("tolerance check", tight), ("conditioning", ulp)]


def _pga(excitation, G) -> str:
    if excitation is None:
        return ""
    if hasattr(excitation, "pga_g"):
        return f", PGA {excitation.pga_g:.3f} g, {excitation.duration:.2f} s at dt = {excitation.dt:g} s"
    return f", a_p = {abs(excitation.a_p) / G:.3f} g, T_p = {excitation.T_p:g} s"
