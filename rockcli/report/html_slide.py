"""The HTML report of one friction run in which a contact slid (``simulate --friction MU --report``): the answer in
words on the first screen (the sliding itself, how far from the plinth's edge, the friction assumed), the numbers
per contact, the figure with the slips, the friction in the assumptions, the command."""

from __future__ import annotations

import math

from rockcli.report.html import (assumptions_section, card, configurations_section, esc, figure, num, page,
                                 reproduce_section, table)

#: What the friction model assumes, for the report's assumptions (docs/physics-sliding.md).
FRICTION_ASSUMPTIONS = (
    "Friction is part of the model (--friction): every contact may stick, slide, rock on a corner or rock while its "
    "corner slides, under Coulomb's law with one coefficient mu per contact (static = kinetic); the stone-on-stone "
    "values of the literature span about 0.5-0.8, and the answer can depend on where in that band the real contact "
    "lies: run the lower bound too.",
    "Impacts with friction are instantaneous and plastic (Moreau's law with Coulomb's cone): an impact whose "
    "impulses fit the cone is the rocking model's; one that does not slips during the impact.",
    "A body whose base reaches the edge of its plinth's top is read as fallen (slid off): from there the model of "
    "flat faces no longer holds; a real body may hang on a little further, until its centre of mass passes the edge.",
    "A contact that would pull (the body leaving the surface: a jump) is kept in contact, without friction, and "
    "counted: the model has no flight.",
)


def slide_report(body, foundation, excitation, res, *, label: str, command: str) -> str:
    """The page for ``res`` (a :class:`rockcli.solve.slide.SlideResponse` with its history) of ``body`` (a Block or a
    Stack) on ``foundation`` under ``excitation``."""
    from rockcli.models.spec import configuration_of
    from rockcli.report.html_figures import png_of
    from rockcli.report.html_records import records_section
    from rockcli.report.slide import plot_slide_response
    from rockcli.report.slide_words import slide_sentence

    conf = configuration_of(foundation.label)
    stacked = res.joint is not None
    blk = body.body if stacked else body
    name = blk.name
    where = "on its plinth" if stacked else ("standing on the ground" if not conf.isolated else "on the bearings")
    word = {"overturned": "topples", "slid off": "topples", "undecided": "undecided"}.get(res.verdict, "survives")
    fails = "slides off its plinth" if res.verdict == "slid off" else word
    mus = ", ".join(f"{p.name} mu = {m:g}" for p, m in zip(res.interfaces, res.mu))
    first = [f"<p class='question'>Does the {esc(name)} topple or slide off under {esc(label)}, {esc(where)}, with "
             f"friction {esc(mus)}?</p>",
             card(word, where, f"{fails}: {slide_sentence(body, res).rstrip('.')}")]
    rows = [("verdict", esc(res.verdict)), ("fails at", num(res.t_fail, ".3f", "s")), ("friction", esc(mus))]
    for p in reversed(res.interfaces):
        who = ("the body on its plinth" if p.name == "joint" else "the plinth on the ground") if stacked else "the base"
        rows += [(f"{esc(who)}: peak rotation / alpha", num(p.psi_max_over_alpha, ".4f")),
                 (f"{esc(who)}: lifts at", num(p.t_uplift, ".3f", "s")),
                 (f"{esc(who)}: impacts", str(p.n_impacts)),
                 (f"{esc(who)}: first slides at", num(p.t_slide, ".3f", "s")),
                 (f"{esc(who)}: peak slip", num(p.slide_max_m, ".4f", "m")),
                 (f"{esc(who)}: residual slip", num(p.slide_residual_m, "+.4f", "m"))]
        if math.isfinite(p.edge_m):
            rows.append((f"{esc(who)}: closest to the edge", num(max(p.edge_m - p.slide_max_m, 0.0), ".4f", "m")))
    if math.isfinite(res.u_max):
        rows.append(("peak base displacement", num(res.u_max, ".4f", "m")))
    rows.append(("integration", f"{res.steps} steps, ended at {res.t_end:.2f} s"))
    png = png_of(lambda path: plot_slide_response(res, body, path, excitation=excitation, foundation=foundation))
    caption = ("Ground acceleration; each contact's rotation over its slenderness (the dotted lines at +-1: its "
               "tipping point) and its slip (shaded where it slides"
               + ("; the dashed lines: the plinth's edge" if stacked else "") + ").")
    items = ["The verdict is proven." if res.settled or res.verdict in ("overturned", "slid off") else
             f"<b>NOT PROVEN</b>: at {res.t_end:.1f} s (the horizon) it was still moving; lengthen --horizon.",
             "This is one run of the motion as given: rockcli assess column --friction finds the smallest scale "
             "factor of a record that topples the body or slides it off its plinth."]
    if res.n_jumps:
        items.append(f"{res.n_jumps} steps or impacts had a contact that would pull (a jump): the model keeps it in "
                     f"contact, so the motion near there is not described exactly.")
    sections = {
        "answer": "\n".join(first), "body": "<p>" + esc(_body_text(body, stacked)) + "</p>",
        "configurations": configurations_section([conf]),
        "records": records_section([excitation]), "verdicts": table(None, rows),
        "figures": figure(png, caption), "certainty": "<ul>" + "".join(f"<li>{i}</li>" for i in items) + "</ul>",
        "assumptions": assumptions_section(FRICTION_ASSUMPTIONS, margins=False),
        "reproduce": reproduce_section(command),
    }
    return page(f"Will the {name} topple or slide?", "rockcli simulate --friction: rocking and sliding of one body "
                                                      "under one ground motion", sections,
                names={"verdicts": "The verdict"})


def _body_text(body, stacked: bool) -> str:
    blk = body.body if stacked else body
    text = (f"The {blk.name}: {blk.height:.3f} m tall, {blk.width:.3f} m wide (R = {blk.R:.3f} m, alpha = "
            f"{blk.alpha_deg:.2f} deg).")
    if stacked:
        p = body.plinth
        text += (f" It stands on a free {p.name} {p.height:.3f} m tall and {p.width:.3f} m wide ({body.m2:.3g} times "
                 f"its mass); its base may slide {body.b2 - body.b1:.3f} m either way before it reaches the "
                 f"{p.name}'s edge.")
    return text


def slide_figures(assessment, sliding) -> str:
    """The time histories of a body with friction (a :class:`rockcli.solve.slide_many.Sliding` column) under the
    records that decide its verdicts: each rerun with its history, by the friction model (where nothing slides the
    run is the rocking model's: the figure draws it all the same, the slips at 0)."""
    from rockcli.report.html_deciding import MAX_DECIDING, _why_words, deciding_records
    from rockcli.report.html_figures import DPI, png_of
    from rockcli.report.slide import plot_slide_response
    from rockcli.report.words import body_noun
    from rockcli.models import Rigid
    from rockcli.solve.slide import simulate_friction

    noun = body_noun(sliding.subject)
    confs = {c.header: c for c in assessment.configurations}
    options = {k: v for k, v in assessment.solver.items() if k in ("rtol", "tail", "rest_tol", "horizon")
               and v is not None}
    out = []
    for header, (why, rows) in deciding_records(assessment, sliding).items():
        c = confs[header]
        for r in rows[:MAX_DECIDING]:
            x = assessment.excitation_of(r)
            head = f"<h3>{esc(x.label)}: the record that {esc(_why_words(why, c, noun))}</h3>"
            iso = None if isinstance(c.foundation, Rigid) else c.foundation
            run = simulate_friction(sliding.subject, x.motion, sliding.mu, iso, history=True, **options)
            if run.status < 0:
                out.append(head + "<p class='note'>The rerun with its history failed: no figure.</p>")
                continue
            png = png_of(lambda path: plot_slide_response(run, sliding.subject, path, excitation=x.motion,
                                                          motion=x.label, foundation=c.foundation, dpi=DPI))
            out.append(head + figure(png, f"{x.label}, {header}: the ground acceleration; each contact's rotation "
                                          f"over its slenderness and its slip, shaded where it slides (friction "
                                          f"{sliding.friction_label})."))
    if not out:
        return ""
    return (f"<p>For each configuration, the records that decide the verdict of {esc(noun)} with friction "
            f"({esc(sliding.friction_label)}): every record that topples it or slides it off its plinth (at most "
            f"{MAX_DECIDING}), else the closest call.</p>" + "".join(out))
