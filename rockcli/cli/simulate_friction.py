"""``rockcli simulate --friction MU``: Coulomb friction as a model (docs/physics-sliding.md). The body, or the body
on its plinth (``--on``), may stick, slide, rock, or rock while its corner slides at every contact.

Where no contact slides in the friction run, the rocking model's answer is printed as it is without ``--friction``
(bit for bit: :mod:`rockcli.solve.slide_many`, "the rocking answer where nothing slides"), with one more row that
says so; where a contact slides, the friction run's answer."""

from __future__ import annotations

import math

import click

from rockcli.errors import RockcliInputError

#: The option's help (shared by simulate and assess).
FRICTION_HELP = ("Coulomb friction as a model (docs/physics-sliding.md): every contact may stick, slide, rock on a "
                 "corner or rock while its corner slides (static = kinetic coefficient). MU for every contact, or, "
                 "with --on, base=MU,joint=MU (the plinth on the ground, the body on the plinth). Where nothing "
                 "slides the answer is the rocking model's, unchanged. On the ground and on linear bearings.")


def parse_friction(text, stacked: bool):
    """``--friction`` as one coefficient, or ``(base, joint)`` for a body on a plinth; one sentence otherwise."""
    from rockcli.io.inputs import spec_numbers
    from rockcli.solve.slide import check_mu

    if text is None:
        return None
    s = str(text).strip()
    if "=" not in s:
        mu = check_mu(s, "--friction")
        return (mu, mu) if stacked else mu
    if not stacked:
        raise RockcliInputError(f"--friction {s}: a body alone has one contact, the base: give one coefficient "
                                f"(base=..,joint=.. is for a body on its plinth, --on)")
    values = spec_numbers(s, "--friction", {"base": "base", "joint": "joint"}, "base=MU, joint=MU")
    missing = [k for k in ("base", "joint") if k not in values]
    if missing:
        raise RockcliInputError(f"--friction {s}: give both contacts, base=MU,joint=MU (missing: "
                                f"{', '.join(missing)})")
    return (check_mu(values["base"], "--friction base"), check_mu(values["joint"], "--friction joint"))


def check_friction_scene(foundation, *, cap_ratio, vertical, moving, restitution, check, history_dt,
                         worst: bool, stacked: bool = False) -> None:
    """What ``--friction`` does not take (yet), each refused in one sentence."""
    from rockcli.models import LinearIsolation, Rigid

    if restitution is not None and not stacked and not isinstance(foundation, Rigid):
        raise RockcliInputError("--friction with --restitution runs on the ground, or for a body on its plinth (--on): "
                                "a single block on bearings reads the restitution another way (docs/simulate.md)")
    if not (isinstance(foundation, Rigid) or (isinstance(foundation, LinearIsolation) and foundation.gamma > 0)):
        raise RockcliInputError("--friction runs on the ground (--isolation none) and on linear bearings with a base "
                                "of finite mass (gamma > 0); not on sliding or lead-rubber bearings yet")
    refused = [name for name, given in (("--cap-ratio", cap_ratio), ("--vertical/--vertical-pulse", vertical),
                                        ("--theta0/--theta-dot0", moving),
                                        ("--check-tolerance", check), ("--history-dt", history_dt is not None),
                                        ("--azimuth worst", worst)) if given]
    if refused:
        raise RockcliInputError(f"--friction runs a body from rest under the horizontal ground motion, with the "
                                f"law of its impacts: {', '.join(refused)} {'is' if len(refused) == 1 else 'are'} "
                                f"not taken with --friction yet")


def _rocking_falls(body, foundation, excitation, **solver) -> bool:
    """Does the rocking model's run of the scene topple?"""
    from rockcli.models import Stack

    if isinstance(body, Stack):
        from rockcli.solve.stack_many import run_stack

        return run_stack(body, foundation, excitation, **solver).toppled is not None
    from rockcli.solve import simulate

    return simulate(body, foundation, excitation, **solver).overturned


def friction_keys(res, stacked: bool) -> dict:
    """The keys ``--friction`` adds to the JSON: the slips (``slide_max_m``, ``slide_residual_m`` at the top for a
    single block, under ``base`` and ``joint`` for a body on its plinth) and ``friction`` (the coefficients, whether
    anything slid, and the first slip)."""
    def num(x):
        return None if not math.isfinite(x) else x

    slid = res.slides and not res.falls_only
    out = {"friction": {"mu": list(res.mu), "slides": slid, "model": "Coulomb, static = kinetic",
                        "rocking_answer": not slid, **({"slides_in_its_fall": True} if res.falls_only else {})}}
    per = {p.name: {"slide_max_m": p.slide_max_m if slid else 0.0,
                    "slide_residual_m": p.slide_residual_m if slid else 0.0,
                    "t_slide_s": num(p.t_slide) if slid else None, "n_slips": p.n_slips if slid else 0,
                    **({"edge_m": p.edge_m} if math.isfinite(p.edge_m) else {})} for p in res.interfaces}
    if stacked:
        return {**out, "base": per["base"], "joint": per["joint"]}
    return {**out, **per["base"]}


def no_slide_row(res) -> tuple[str, str]:
    mus = " and ".join(f"{p.name} mu = {m:g}" for p, m in zip(res.interfaces, res.mu))
    if res.falls_only:
        return ("friction", f"{mus} (Coulomb): a contact slides only as the body falls (its contact unloads), so the "
                            f"rocking answer above stands as it is (docs/physics-sliding.md)")
    return ("friction", f"{mus} (Coulomb): no contact slides, so the rocking answer above stands as it is "
                        f"(docs/physics-sliding.md)")


def run_friction(body, foundation, excitation, label: str, mu, *, rtol, tail, horizon, history_path, plot_path,
                 report_path, as_json: bool, pga: str, motion=None, restitution=None):
    """The friction run of ``body`` (a Block or a Stack). Returns the :class:`rockcli.solve.slide.SlideResponse`
    when nothing slid (the caller then prints the rocking answer, with :func:`no_slide_row` and
    :func:`friction_keys`); else prints (or ``--json``) the friction run's answer, writes its history, figure and
    report, and returns None."""
    from rockcli.models import Rigid
    from rockcli.solve.slide import simulate_friction

    if excitation is None:
        raise RockcliInputError("--friction runs a body under a ground motion: give --record or --pulse")
    iso = None if isinstance(foundation, Rigid) else foundation
    want = bool(history_path or plot_path or report_path)
    res = simulate_friction(body, excitation, mu, iso, rtol=rtol, tail=tail, horizon=horizon, history=want,
                            restitution=restitution)
    if res.status < 0:
        raise click.ClickException(f"{res.why_undecided}: no result is given (please report the command line)")
    if not res.slides:
        return res
    stacked = res.joint is not None
    solver = {} if restitution is None else {"restitution": restitution}
    if res.falls_only and _rocking_falls(body, foundation, excitation, rtol=rtol, tail=tail, horizon=horizon,
                                         **solver):
        return res  # it slid only as it fell, and the rocking run falls too: the rocking answer (slide_many's notes)
    if history_path:
        from rockcli.report.slide import write_slide_history_csv

        write_slide_history_csv(res, body, history_path)
    if plot_path:
        from rockcli.report.slide import plot_slide_response

        plot_slide_response(res, body, plot_path, excitation=excitation, motion=motion, foundation=foundation)
    if report_path:
        from rockcli.cli.options import command_line
        from rockcli.report.html import write_report
        from rockcli.report.html_slide import slide_report

        write_report(report_path, slide_report(body, foundation, excitation, res, label=label,
                                               command=command_line()))
    from rockcli.report.slide_words import slide_sentence

    if as_json:
        from rockcli.cli.options import echo_json

        blk = body.body if stacked else body
        out = {"block": blk.name, "R_m": blk.R, "alpha_deg": blk.alpha_deg, "p_radps": blk.p,
               **({"plinth": body.plinth.name} if stacked else {}), "isolation": foundation.label,
               "excitation": label, **res.as_dict(), **friction_keys(res, stacked),
               "plain_words": slide_sentence(body, res)}
        echo_json(out)
        return None
    for k, v in _rows(body, foundation, label + pga, res):
        click.echo(f"{k:<19}  {v}")
    if not res.settled and res.verdict not in ("overturned", "slid off"):
        click.echo("NOTE: the verdict is NOT PROVEN: the run reached the horizon still moving; lengthen --horizon")
    click.echo("")
    click.echo("In plain words: " + slide_sentence(body, res))
    return None


def _t(x: float) -> str:
    return "-" if not math.isfinite(x) else f"{x:.3f} s"


def _rows(body, foundation, excitation: str, res) -> list:
    stacked = res.joint is not None
    blk = body.body if stacked else body
    verdict = {"overturned": "OVERTURNS", "slid off": "SLIDES OFF its plinth", "no motion": "survives (no motion)",
               "survives": "survives", "undecided": "undecided"}[res.verdict]
    if res.verdict == "survives":
        verdict += " (" + " and ".join(w for w, on in (("rocks", res.rocks), ("slides", res.slides)) if on) + ")"
    if res.verdict == "overturned" and stacked:
        verdict += (" (the body topples off its plinth)" if res.toppled == "body" else
                    " (the plinth topples, the body with it)")
    rows = [("block", f"{blk.name}: R = {blk.R:.3f} m, alpha = {blk.alpha_deg:.2f} deg (h/b = {blk.h / blk.b:.2f}), "
                      f"p = {blk.p:.3f} rad/s")]
    if stacked:
        p = body.plinth
        rows.append(("plinth", f"{p.name}: {p.height:.3f} m tall x {p.width:.3f} m wide, mass {body.m2:.3g} x the "
                               f"body's; the body's base may slide {body.b2 - body.b1:.3f} m either way before it "
                               f"reaches the plinth's edge"))
    rows += [("foundation", foundation.label), ("excitation", excitation),
             ("friction", ", ".join(f"{p.name} mu = {m:g}" for p, m in zip(res.interfaces, res.mu))
              + " (Coulomb, static = kinetic; docs/physics-sliding.md)"),
             ("verdict", verdict)]
    if res.verdict in ("overturned", "slid off"):
        rows.append(("fails at", _t(res.t_fail)))
    for p in reversed(res.interfaces):
        who = ("the body on its plinth" if p.name == "joint" else "the plinth on the ground") if stacked else "the base"
        rock = ("does not lift" if not math.isfinite(p.t_uplift) else
                f"lifts at {_t(p.t_uplift)}, peak {p.psi_max_over_alpha:.4f} alpha, {p.n_impacts} impacts")
        slide = ("does not slide" if not p.n_slips else
                 f"slides from {_t(p.t_slide)} ({p.n_slips} slip{'' if p.n_slips == 1 else 's'}): peak "
                 f"{p.slide_max_m:.4f} m, residual "
                 f"{p.slide_residual_m:+.4f} m" + (f", {max(p.edge_m - p.slide_max_m, 0):.4f} m from the edge at its "
                                                   f"farthest" if math.isfinite(p.edge_m) else ""))
        rows.append((f"{p.name}: rocking", f"{who} {rock}"))
        rows.append((f"{p.name}: sliding", slide))
    if math.isfinite(res.u_max):
        rows.append(("peak base disp.", f"{res.u_max:.4f} m (the stroke the bearings must allow)"))
    if res.n_slip_impacts:
        rows.append(("slipping impacts", f"{res.n_slip_impacts} impacts whose impulse left Coulomb's cone (the "
                                          f"contact slid during the impact)"))
    if res.n_jumps:
        rows.append(("jumps", f"{res.n_jumps} steps or impacts where a contact would pull: the model keeps it "
                              f"(no flight) without friction there"))
    rows.append(("integration", f"{res.steps} steps, {res.nrhs} right-hand sides, ended at {res.t_end:.2f} s"))
    return rows
