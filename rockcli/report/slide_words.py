"""A friction run in plain words (:func:`slide_sentence`): how far each contact slid, how the body rocked, and the
new way to fail, sliding off the plinth."""

from __future__ import annotations

import math


def _noun(block) -> str:
    name = getattr(block, "name", "") or "block"
    return name if name[:1].isupper() else f"the {name}"


def cm(x: float) -> str:
    """A length [m] in centimetres for a sentence: 1 decimal under 10 cm, none above; under 1 mm in mm."""
    x = abs(float(x))
    if x < 1e-3:
        return f"{x * 1000:.1f} mm" if x >= 5e-5 else "less than 0.1 mm"
    return f"{x * 100:.1f} cm" if x < 0.1 else f"{x * 100:.0f} cm"


def pct(x: float) -> str:
    return f"{100 * x:.0f} %" if x >= 0.01 else "under 1 %"


def _slid(p, on: str) -> str:
    """'slides 4.2 cm on its plinth (it ends 1.1 cm off where it stood)'."""
    end = abs(p.slide_residual_m)
    tail = "" if end < 0.05 * p.slide_max_m or end < 1e-4 else f", ending {cm(end)} from where it stood"
    return f"slides {cm(p.slide_max_m)} on {on}{tail}"


def slide_sentence(body, res) -> str:
    """One or two sentences for ``res`` (a :class:`rockcli.solve.slide.SlideResponse`) of ``body`` (a Block or a
    Stack)."""
    stack = res.joint is not None
    who = _noun(body.body if stack else body)
    Who = who[:1].upper() + who[1:]
    plinth = f"its {body.plinth.name}" if stack else ""
    ground = "the isolated base" if math.isfinite(res.u_max) else "the ground"
    if res.verdict == "slid off":
        p = res.joint
        text = (f"{Who} slides off {plinth} at {res.t_fail:.2f} s: its base reaches the {body.plinth.name}'s edge, "
                f"{cm(p.edge_m)} from centred (from there the model of flat faces no longer holds; read it as a "
                f"fall)")
        if res.base.psi_max >= res.base.alpha:
            text += f", as the {body.plinth.name} itself tilts past its tipping point"
        return text + "."
    if res.verdict == "overturned":
        if res.toppled == "plinth":
            head = f"The {body.plinth.name} topples at {res.t_fail:.2f} s, and {who} with it"
        else:
            head = f"{Who} topples{' off ' + plinth if stack else ''} at {res.t_fail:.2f} s"
        slid = [p for p in res.interfaces if p.n_slips]
        if slid:
            head += f" (having slid up to {cm(max(p.slide_max_m for p in slid))} before)"
        return head + "."
    if res.verdict == "no motion":
        return f"{Who} neither rocks nor slides: it moves with {ground}."
    parts = []
    b = res.body
    if math.isfinite(b.t_uplift):
        parts.append(f"rocks to {pct(b.psi_max_over_alpha)} of its overturning angle")
    if b.n_slips:
        parts.append(_slid(b, plinth if stack else ground))
    if not parts:
        parts.append(f"stays on {plinth}" if stack else "stays put")
    text = f"{Who} " + " and ".join(parts)
    if stack and b.n_slips and math.isfinite(b.edge_m):
        text += f"; at its farthest {cm(max(b.edge_m - b.slide_max_m, 0.0))} from the {body.plinth.name}'s edge"
    text += ", and survives." if res.settled else " (not proven: still moving at the horizon)."
    if stack:
        p = res.base
        pp = []
        if math.isfinite(p.t_uplift):
            pp.append(f"rocks to {pct(p.psi_max_over_alpha)} of the overturning angle of the two as one block")
        if p.n_slips:
            pp.append(_slid(p, ground))
        if pp:
            text += f" The {body.plinth.name} " + " and ".join(pp) + "."
    return text
