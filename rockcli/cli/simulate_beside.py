"""``rockcli simulate`` with several ``--pulse`` or several ``--isolation``: the scenes side by side in one figure.

The paper's Figure 1 is one block under two pulses (0.5 g, 0.5 s: it survives; 0.29 g, 2 s: it topples) and its
Figure 12 one column under one record on the ground and on an isolated base: two panels each. ``simulate --pulse A
--pulse B --plot FILE`` (or ``--isolation none --isolation linear:Tb=3``) runs each scene as ``simulate`` runs one,
prints each one's answer, and draws them in one figure, one column each (:func:`rockcli.report.response.
plot_responses`). The outputs of one run (``--json``, ``--history``, ``--report``, the checks) take one scene.
"""

from __future__ import annotations

import click

from rockcli.errors import RockcliInputError


def run_beside(block, isolations, pulses, *, record_source, record_kw: dict, scale: float, flip: bool, rtol, tail,
               horizon, restitution, cap_ratio, plot_path, one_scene: dict) -> None:
    """Run the scenes ``isolations`` x ``pulses`` (or x the record ``record_source``) of ``block`` and draw them side
    by side into ``plot_path``. ``one_scene``: the options given that take one scene (``{"--json": True, ...}``),
    refused in one sentence."""
    from rockcli.cli.options import scaled
    from rockcli.cli.simulate import _flipped, _pga
    from rockcli.io.units import G
    from rockcli.models import parse_isolation_spec
    from rockcli.models.colonnade import check_cap_ratio
    from rockcli.models.impact import check_restitution

    what = "several --isolation" if len(isolations) > 1 else "several --pulse"
    if len(isolations) > 1 and len(pulses) > 1:
        raise RockcliInputError("give several --pulse or several --isolation, not both: the figure has one column per "
                                "scene")
    given = [option for option, value in one_scene.items() if value]
    if given:
        raise RockcliInputError(f"{given[0]} takes one scene: {what} draw their scenes side by side with --plot, and "
                                f"that is all they do")
    if plot_path is None:
        raise RockcliInputError(f"{what} draw their scenes side by side: give --plot FILE (one figure, one column "
                                f"per scene)")
    if pulses and record_source is not None:
        raise RockcliInputError("give the ground motion as exactly one of --record SOURCE or --pulse SPEC")
    foundations = [parse_isolation_spec(s) for s in isolations]
    restitution = check_restitution(restitution, "--restitution")
    cap_ratio = check_cap_ratio(cap_ratio, "--cap-ratio")
    solver = ({} if restitution is None else {"restitution": restitution}) | ({"cap_ratio": cap_ratio} if cap_ratio
                                                                              else {})
    from rockcli.io.inputs import check_scale, format_number

    check_scale(scale, 0.0, "--scale")
    if pulses:
        from rockcli.pulses import parse_pulse_spec

        if any(v is not None for v in record_kw.values()):
            raise RockcliInputError("--units, --dt, --format and --record-column apply to --record, not to --pulse")
        motions = []
        for spec in pulses:
            x = _flipped(scaled(parse_pulse_spec(spec), scale, "--scale", "the pulse"), flip)
            motions.append((x, None, f"{x.shape} pulse"))
    elif record_source is not None:
        from rockcli.cli.azimuth import read_excitation, wants_worst

        if wants_worst():
            raise RockcliInputError(f"--azimuth worst runs every orientation verdict-only: {what} need one --azimuth "
                                    f"DEG")
        rec, _ = read_excitation(record_source, record_kw)
        factor = -scale if flip else scale
        label = f"record {rec.name}" + (f" x {format_number(factor)}" if factor != 1.0 else "")
        motions = [(_flipped(scaled(rec, scale, "--scale", "the record"), flip), label, label)]
    else:
        raise RockcliInputError(f"give the ground motion of the {what}: --record SOURCE or --pulse SPEC")

    from rockcli.report.figures import plot_grid_dt
    from rockcli.solve import simulate

    runs, lines = [], []
    scenes = [(f, m) for f in foundations for m in motions]
    for k, (foundation, (excitation, motion, label)) in enumerate(scenes, start=1):
        res = simulate(block, foundation, excitation, rtol=rtol, tail=tail, horizon=horizon, history=True,
                       history_dt=plot_grid_dt(excitation), **solver)
        if res.status < 0:  # a genuine numerical failure: no result is printed or drawn as if it were valid
            raise click.ClickException(
                f"scene {k}: the integrator stopped at its safety cap of {res.steps + res.rejected_steps:,} steps at "
                f"t = {res.t_end_s:.3f} s, a numerical failure: no result is given (please report the command line)")
        runs.append((res, foundation, excitation, motion))
        verdict = ({"overturned": f"OVERTURNS at {res.t_overturn_s:.3f} s", "rocked": "survives (rocks)",
                    "no_uplift": "survives (no uplift)"}[res.verdict]
                   + ("" if res.overturned else f", peak |theta|/alpha {res.theta_max_over_alpha:.4f}")
                   + ("" if res.settled else " (NOT PROVEN: still moving at the horizon)"))
        lines += [(f"scene {k} (column {k})", f"{foundation.label}; {label}{_pga(excitation, G)}"),
                  ("  verdict", verdict)]
        if getattr(foundation, "kind", 0) != 0:
            lines.append(("  peak base disp.", f"{res.base_disp_max_m:.4f} m"))
    from rockcli.report.response import plot_responses

    plot_responses(runs, block, plot_path)
    lines.insert(0, ("block", f"{block.name}: R = {block.R:.3f} m, alpha = {block.alpha_deg:.2f} deg "
                              f"(h/b = {block.h / block.b:.2f}), p = {block.p:.3f} rad/s"))
    width = max(len(k) for k, _ in lines)
    for key, value in lines:
        click.echo(f"{key:<{width}}  {value}")
    click.echo(f"wrote {plot_path} ({len(runs)} scenes side by side)", err=True)
