"""The HTML report of ``rockcli simulate --on PLINTH``: one run of a body on its free plinth, beside the same body
alone on the same foundation (:func:`stack_report`).

The sections of :mod:`rockcli.report.html`; the figure is :func:`rockcli.report.stack.plot_stack_response` (the
figure of ``simulate --on --plot`` and of the ``assess column --on`` report); the words are
:mod:`rockcli.report.plinth_words`'s, the same as the printout's.
"""

from __future__ import annotations

import math

from rockcli.report.html import (assumptions_section, body_section, card, configurations_section, esc, figure, num,
                                 page, reproduce_section, table)
from rockcli.report.html_records import records_section
from rockcli.report.plinth_words import plinth_name, run_sentence
from rockcli.report.words import SURVIVES, TOPPLES, UNDECIDED, body_noun, body_words, configuration_words, past_words


def _demand(x: float) -> str:
    return f"{x:.3f}" if math.isfinite(x) else "unbounded"


def stack_report(stack, foundation, excitation, run, alone, *, label: str, command: str = "",
                 restitution: float | None = None) -> str:
    """The HTML report of ``rockcli simulate --on``: ``run`` a :class:`rockcli.solve.StackResponse` with its
    history, ``alone`` a :class:`rockcli.solve.Response` with history of ``stack.body`` on ``foundation`` (or
    None)."""
    from rockcli.io.units import G
    from rockcli.models.spec import configuration_of
    from rockcli.report.html_figures import DPI, png_of
    from rockcli.report.html_pages import _list, stroke_facts
    from rockcli.report.stack import plot_stack_response

    conf = configuration_of(foundation.label)
    where = configuration_words(conf)
    noun, name = body_noun(stack.body), plinth_name(stack)
    word = TOPPLES if run.toppled else SURVIVES if run.settled else UNDECIDED
    first = [f"<p class='question'>Does {esc(noun)} on its {esc(name)} topple under {esc(label)}, {esc(where)}?</p>",
             f"<h3>{esc(body_words(stack))}</h3>", card(word, where, f"{word}: {run_sentence(stack, run).rstrip('.')}")]
    if alone is not None:
        a_word = TOPPLES if alone.overturned else SURVIVES if alone.settled else UNDECIDED
        a_text = (f"it topples at {alone.t_overturn_s:.2f} s" if alone.overturned else
                  "it does not lift off its base" if alone.verdict == "no_uplift" else
                  f"it rocks to {100 * alone.theta_max_over_alpha:.0f} % of its overturning angle"
                  f"{past_words(alone.theta_max_over_alpha)}")
        first.append(card(a_word, f"{noun} alone, {where}", f"{a_word}: {a_text}"))
    isolated = math.isfinite(getattr(run, "base_disp_max", math.nan))
    if isolated:
        first.append(stroke_facts(run.base_disp_max, word))
    t = lambda v: num(v, ".3f", "s")  # noqa: E731
    pl = run.plinth
    which = {"body": f"{noun} topples off its {name}", "plinth": f"the {name} topples, {noun} with it"}
    result = [
        ("verdict", esc(word) + (f" ({esc(which[run.toppled])})" if run.toppled else "")),
        ("topples at", t(run.t_overturn_s)),
        (f"{esc(noun)}: lifts off its {esc(name)} at", t(run.body.t_uplift_s)),
        (f"the {esc(name)}: lifts off the {'isolated base' if isolated else 'ground'} at", t(pl.t_uplift_s)),
        (f"{esc(noun)}'s peak tilt on its {esc(name)} / its alpha",
         "-" if run.toppled == "body" else num(run.body.theta_max_over_alpha, ".4f")),
        (f"the {esc(name)}'s peak tilt / alpha_asm ({math.degrees(stack.alpha_asm):.2f} deg)",
         "-" if run.toppled == "plinth" else num(pl.theta_max / stack.alpha_asm, ".4f")),
        ("impacts", f"{run.body.n_impacts} of {esc(noun)} on its {esc(name)}, {pl.n_impacts} of the {esc(name)} on "
                    f"the {'isolated base' if isolated else 'ground'} (during shaking)"),
        ("friction demand |T|/N", f"base {_demand(run.friction_base)}, joint {_demand(run.friction_joint)}; at "
                                  f"impacts base {_demand(run.friction_base_impulsive)}, joint "
                                  f"{_demand(run.friction_joint_impulsive)}"),
        *([("peak base displacement", num(run.base_disp_max, ".4f", "m"))] if isolated else []),
        ("lifts from rest", f"{esc(noun)} off its {esc(name)} at {stack.body_uplift_acceleration / G:.3f} g, both "
                            f"together at {stack.assembly_uplift_acceleration / G:.3f} g"),
        ("integration", f"{run.steps} steps"),
    ]
    png = png_of(lambda path: plot_stack_response(run, stack, path, excitation=excitation, motion=label,
                                                  alone=alone, foundation=foundation, dpi=DPI))
    caption = (f"{label}, {where}: ground acceleration; {noun}'s tilt on its {name} over its own alpha (blue) "
               f"beside {noun} alone (grey, dashed); the {name}'s tilt over alpha_asm, the slenderness of {name} and "
               f"{noun[4:]} as one block (the tilt at which the {name} tips over while {noun} rests on it)"
               + ("; the displacement of the isolated base" if isolated else "")
               + ". Beyond the dotted lines at +-1 a block leans past its tipping point. "
               + ("A red line marks the instant a block topples. " if run.toppled else "")
               + ("A grey line the instant the body alone topples. " if alone is not None and alone.overturned
                  else ""))
    items = ["The numerical checks (--check-tolerance) are not run on a body on a plinth yet.",
             "The verdict is proven." if run.settled or run.toppled else
             "<b>NOT PROVEN</b>: the run reached the horizon still moving; lengthen --horizon to follow it.",
             "Rocking only: the plinth and the body do not slide. The friction demand above says how much friction "
             "that takes (docs/plinth.md, Friction): a demand above the friction of the real contact means the run "
             "is outside what the model describes.",
             "This is one run of the motion as given: how much stronger or weaker the motion would have to be to "
             "change the verdict is not computed here (<code>rockcli assess column --on</code> finds it)."]
    if run.n_jumps:
        items.append(f"{run.n_jumps} steps or impacts where a pivot would pull: the rocking-only model does not "
                     "describe the motion there.")
    sections = {
        "answer": "\n".join(first), "body": body_section([stack.body, stack], restitution=restitution),
        "configurations": configurations_section([conf]), "records": records_section([excitation]),
        "verdicts": table(None, [(k, v) for k, v in result]), "figures": figure(png, caption.strip()),
        "certainty": _list(items), "assumptions": assumptions_section(margins=False),
        "reproduce": reproduce_section(command),
    }
    return page(f"Will {noun} on its {name} topple?", "rockcli simulate --on: one run of a body on a free plinth",
                sections, names={"verdicts": "The verdict"})


__all__ = ["stack_report"]
