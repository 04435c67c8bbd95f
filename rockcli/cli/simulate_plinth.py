"""``rockcli simulate --on PLINTH``: a body on a free plinth (one run of :func:`rockcli.solve.simulate_stack`),
and ``--friction MU``, the friction check of a run (single block or stack; the judgement is
:mod:`rockcli.solve.friction`'s)."""

from __future__ import annotations

import math

import click

from rockcli.errors import RockcliInputError


def check_friction_scene(friction, foundation, cap_ratio, *vertical) -> float:
    """``--friction MU`` checked, and the scene it can be read for: a rigid foundation without a vertical motion
    or a colonnade (the demand is that of a block on the ground, docs/plinth.md)."""
    from rockcli.models import Rigid
    from rockcli.solve.friction import check_friction

    mu = check_friction(friction, "--friction")
    if not isinstance(foundation, Rigid):
        raise RockcliInputError("--friction reads the friction demand of a body on the ground (or on its plinth on "
                                "the ground): give --isolation none")
    from rockcli.cli.azimuth import wants_worst

    if wants_worst():
        raise RockcliInputError("--friction reads the demand of one run: give one --azimuth DEG, not worst")
    if cap_ratio or any(v is not None for v in vertical):
        raise RockcliInputError("--friction reads the friction demand under the horizontal ground motion of a "
                                "solitary body: not with --cap-ratio, --vertical or --vertical-pulse")
    return mu


def refuse_with_plinth(foundation, *, cap_ratio, moving, check, history_dt, vertical) -> None:
    """What ``--on`` does not take (yet), each refused with one sentence."""
    from rockcli.cli.azimuth import wants_worst
    from rockcli.solve.stack_many import PLINTH_RIGID_ONLY, plinth_foundation_supported

    if not plinth_foundation_supported(foundation):
        raise RockcliInputError(f"--on: {PLINTH_RIGID_ONLY}; give --isolation none or bearings with gamma > 0")
    refused = [name for name, given in (("--cap-ratio", cap_ratio), ("--theta0/--theta-dot0", moving),
                                        ("--check-tolerance", check),
                                        ("--history-dt", history_dt is not None),
                                        ("--vertical/--vertical-pulse", any(v is not None for v in vertical)),
                                        ("--azimuth worst", wants_worst())) if given]
    if refused:
        raise RockcliInputError(f"--on runs a body on its plinth from rest under the horizontal ground motion and "
                                f"writes its history at the steps (--history): {', '.join(refused)} "
                                f"{'is' if len(refused) == 1 else 'are'} not taken with --on")


def _g(x: float) -> float:
    from rockcli.io.units import G

    return x / G


def _finite(x):
    return x if isinstance(x, (int, float)) and math.isfinite(x) else None


def plinth_dict(stack) -> dict:
    """The plinth and the assembly, for the JSON."""
    p = stack.plinth
    return {"name": p.name, "height_m": p.height, "width_m": p.width, "mass_ratio": stack.m2,
            "mass_ratio_given": p.mass_ratio is not None, "alpha2_deg": math.degrees(stack.alpha2),
            "alpha_asm_deg": math.degrees(stack.alpha_asm), "body_uplift_g": _g(stack.body_uplift_acceleration),
            "assembly_uplift_g": _g(stack.assembly_uplift_acceleration)}


def stack_friction(res, mu: float) -> dict:
    """The friction check of a stack run: each interface's peak demand against ``mu`` (continuous and impulsive
    apart; a demand without a finite value is null and exceeds)."""

    def over(x):
        return not (math.isfinite(x) and x <= mu)

    return {"mu": mu, "exceeded": {"base": over(res.friction_base), "joint": over(res.friction_joint)},
            "exceeded_impulsive": {"base": over(res.friction_base_impulsive),
                                   "joint": over(res.friction_joint_impulsive)}}


def single_friction(block, foundation, excitation, res, mu: float, restitution, solver: dict) -> dict:
    """The friction check of a single block on the ground: its peak demand from a run on the grid of
    :func:`rockcli.solve.friction.friction_grid_dt` (the run ``res`` itself when it has that history), and the
    impulsive demand of its impacts (none without impacts)."""
    from rockcli.models.impact import impact_ratio
    from rockcli.solve import simulate
    from rockcli.solve.friction import friction_grid_dt, friction_peak_single, impulsive_demand_single

    grid = friction_grid_dt(excitation)
    H = res.history
    run = res if H is not None and H.grid_dt == grid else simulate(block, foundation, excitation, history=True,
                                                                    history_dt=grid, **solver)
    peak, t_peak = friction_peak_single(block, run)
    impulsive = impulsive_demand_single(block, impact_ratio(block.alpha, 0.0, restitution)) \
        if max(run.n_impacts_total, res.n_impacts_total) > 0 else 0.0
    return {"mu": mu, "peak_demand": _finite(peak), "t_peak_s": _finite(t_peak), "peak_demand_impulsive": impulsive,
            "exceeded": not (math.isfinite(peak) and peak <= mu), "exceeded_impulsive": impulsive > mu,
            "grid_dt_s": grid, "toppled": res.overturned}


def single_friction_row(f: dict) -> tuple[str, str]:
    peak = "unbounded (a jump)" if f["peak_demand"] is None else f"{f['peak_demand']:.3f}"
    if f["peak_demand"] is not None and f["t_peak_s"] is not None:
        peak += f" at {f['t_peak_s']:.3f} s"
    words = (f"EXCEEDS mu = {f['mu']:g}: the block would slide (the rocking-only model fails there)"
             if f["exceeded"] else f"within mu = {f['mu']:g}")
    if f["toppled"]:
        words += " (read until it passed alpha: a falling block's demand grows without bound)"
    imp = f"at impacts {f['peak_demand_impulsive']:.3f}" + (
        f", above mu: a slip during the impact" if f["exceeded_impulsive"] else "")
    return "friction demand", f"peak {peak}, {words}; {imp}"


def _fmt_t(x: float) -> str:
    return "-" if x != x else f"{x:.3f} s"


def _demand(x: float) -> str:
    return f"{x:.3f}" if math.isfinite(x) else "unbounded"


def run_plinth(stack, foundation, excitation, label: str, *, restitution, rtol, tail, horizon, history_path,
               as_json: bool, friction_res=None, pga: str, plot_path=None, motion=None, report_path=None):
    """``simulate --on``: one run of the body on its plinth, printed (or ``--json``), its history written, its
    figure drawn and its HTML report written (with the body alone on the same foundation beside it)."""
    from rockcli.assess.plinth_words import run_sentence
    from rockcli.cli.options import echo_json
    from rockcli.solve.stack_many import run_stack

    if excitation is None:
        raise RockcliInputError("--on runs a body on its plinth under a ground motion: give --record or --pulse")
    # through run_stack: a foundation other than the rigid one goes to simulate_stack as isolation=, once it takes it
    res = run_stack(stack, foundation, excitation, rtol=rtol, tail=tail, horizon=horizon,
                    history=bool(history_path or plot_path or report_path), restitution=restitution)
    if res.status < 0:
        raise click.ClickException(f"the integrator stopped at its safety cap of {res.steps:,} steps: no result is "
                                   f"given (please report the command line)")
    if history_path:
        from rockcli.report.stack import write_stack_history_csv

        write_stack_history_csv(res, stack, history_path)
    if plot_path or report_path:
        from rockcli.report.figures import plot_grid_dt
        from rockcli.solve import simulate

        solver = {} if restitution is None else {"restitution": restitution}
        alone = simulate(stack.body, foundation, excitation, rtol=rtol, tail=tail, horizon=horizon, history=True,
                         history_dt=plot_grid_dt(excitation), **solver)
    if plot_path:
        from rockcli.report.stack import plot_stack_response
        from rockcli.solve.excitation import _excitation_arrays

        t_show = _excitation_arrays(excitation)[6] + tail  # the figure shows the excitation and --tail after it
        plot_stack_response(res, stack, plot_path, excitation=excitation, motion=motion, alone=alone, t_end=t_show,
                            foundation=foundation)
    if report_path:
        from rockcli.cli.options import command_line
        from rockcli.report.html import write_report
        from rockcli.report.html_stack import stack_report

        write_report(report_path, stack_report(stack, foundation, excitation, res, alone, label=label,
                                               command=command_line(), restitution=restitution))
    body = stack.body
    if as_json:
        d = res.as_dict()
        d["friction_demand"] = {k: _finite(v) for k, v in d["friction_demand"].items()}
        out = {"block": body.name, "R_m": body.R, "alpha_deg": body.alpha_deg, "p_radps": body.p,
               "plinth_model": plinth_dict(stack), "isolation": foundation.label, "excitation": label,
               **({"restitution": restitution} if restitution is not None else {}), **d,
               "plain_words": run_sentence(stack, res)}
        if friction_res is not None:  # nothing slid in the friction run (cli.simulate_friction)
            from rockcli.cli.simulate_friction import friction_keys

            out.update(friction_keys(friction_res, True))
        echo_json(out)
        return
    p = stack.plinth
    words = {"overturned": "OVERTURNS", "rocked": "survives (rocks)", "no_uplift": "survives (no uplift)"}
    verdict = words[res.verdict]
    if res.toppled:
        verdict += (" (the body topples off its plinth)" if res.toppled == "body" else
                    " (the plinth topples, the body with it)")
    pl = res.plinth
    isolated = math.isfinite(getattr(res, "base_disp_max", math.nan))
    rows = [
        ("block", f"{body.name}: R = {body.R:.3f} m, alpha = {body.alpha_deg:.2f} deg (h/b = {body.h / body.b:.2f}), "
                  f"p = {body.p:.3f} rad/s"),
        ("plinth", f"{p.name}: {p.height:.3f} m tall x {p.width:.3f} m wide, mass {stack.m2:.3g} x the body's"
                   f"{'' if p.mass_ratio is not None else ' (same density)'}; the body and plinth as one block: "
                   f"alpha_asm = {math.degrees(stack.alpha_asm):.2f} deg"),
        ("foundation", foundation.label),
        *([("impact rule", f"restitution E = {restitution:g} at every impact (docs/physics-plinth.md, Impacts)")]
          if restitution is not None else []),
        ("excitation", label + pga),
        ("lifts from rest", f"the body off the plinth at {_g(stack.body_uplift_acceleration):.3f} g, body and plinth "
                            f"together at {_g(stack.assembly_uplift_acceleration):.3f} g"),
        ("verdict", verdict),
        ("uplift at", f"body {_fmt_t(res.body.t_uplift_s)}, plinth {_fmt_t(pl.t_uplift_s)}"),
        ("overturn at", _fmt_t(res.t_overturn_s)),
        ("peak |theta|/alpha", (f"{res.body.theta_max_over_alpha:.4f}" if res.toppled is None else "overturned")
         + " (the body on its plinth: |psi|/alpha1)"),
        ("plinth peak", "does not lift" if math.isnan(pl.t_uplift_s) else
         (f"|theta2| = {pl.theta_max:.4g} rad: {pl.theta_max / res.alpha_asm:.4f} alpha_asm, "
          f"{pl.theta_max_over_alpha:.4f} alpha2" if res.toppled != "plinth" else "overturned")),
        ("impacts", f"{res.body.n_impacts} of the body on the plinth, {pl.n_impacts} of the plinth on the "
                    f"{'isolated base' if isolated else 'ground'} (during shaking)"),
        *([("peak base disp.", f"{res.base_disp_max:.4f} m (the isolated base relative to the ground: the stroke "
                               f"the bearings must allow)")] if isolated else []),
        ("friction demand", f"peak |T|/N base {_demand(res.friction_base)}, joint {_demand(res.friction_joint)}; "
                            f"at impacts base {_demand(res.friction_base_impulsive)}, joint "
                            f"{_demand(res.friction_joint_impulsive)}"
                            + ("; a toppling block's contact unloads as it falls, so the peaks near the fall are "
                               "no demand to compare" if res.toppled else "")),
    ]
    if friction_res is not None:
        from rockcli.cli.simulate_friction import no_slide_row

        rows.append(no_slide_row(friction_res))
    if res.n_jumps:
        rows.append(("jumps", f"{res.n_jumps} steps or impacts where a pivot would pull: the rocking-only model "
                              f"does not describe the motion there"
                              + (" (the contact of a falling block unloads as it falls)" if res.toppled else "")))
    rows.append(("integration", f"{res.steps} steps, {res.n_rhs} right-hand sides"))
    w = max(len(k) for k, _ in rows)
    for k, v in rows:
        click.echo(f"{k:<{w}}  {v}")
    if not res.settled and res.toppled is None:
        click.echo("NOTE: the verdict is NOT PROVEN: the run reached the horizon still moving; lengthen --horizon")
    click.echo("")
    click.echo("In plain words: " + run_sentence(stack, res))
