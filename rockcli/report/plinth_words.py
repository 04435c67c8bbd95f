"""A body on a free plinth in plain words: how each block rocked, whether the plinth helps.

* :func:`peak_words`: how the two blocks rocked, each said truthfully (nothing lifts; the body rocks on a
  still plinth; the plinth rocks with the body stuck to it; both rock), each peak over its own overturning
  angle (the body's ``alpha1`` on the plinth, the plinth's ``alpha_asm``: body and plinth as one block);
* :func:`row_peak_words`, :func:`survivors_peak_words`: the same from the rows of an assessment (one run, the
  largest over the runs it survives);
* :func:`run_sentence`: one run of ``simulate --on`` in a sentence or two (:class:`rockcli.solve.StackResponse`);
* :func:`plinth_summary`: does the plinth help? The body on its plinth against the same body alone.

A block "does not lift" when its peak rotation on its own support is exactly 0 (the solver's peak: it never left
its face). Only words here; the numbers come from the rows (:class:`rockcli.assess.AssessmentRow`) or the response.
"""

from __future__ import annotations

import math


def _share(r: float) -> str:
    """A peak over an overturning angle in percent; ``under 1 %`` for a lift that rounds to 0 %."""
    return "under 1 %" if 0.0 < r < 0.005 else f"{100 * r:.0f} %"


def plinth_name(row_or_stack) -> str:
    """``plinth``: the plinth's name, from a :class:`rockcli.models.Stack` or a row's ``plinth`` label
    (``plinth:height=1,...``)."""
    plinth = getattr(row_or_stack, "plinth", "")
    name = plinth.name if hasattr(plinth, "name") else str(plinth).partition(":")[0]
    return (name or "plinth").replace("_", " ")


def peak_words(body_peak: float, plinth_peak: float, *, body: str = "the body", plinth: str = "plinth",
               most: bool = False, body_where: str = "", plinth_where: str = "") -> str:
    """How a body on its plinth rocked, each block truthfully.

    ``body_peak``: the body's peak rotation on the plinth over its slenderness ``alpha1``; ``plinth_peak``: the
    plinth's over ``alpha_asm`` (body and plinth as one block); 0 where the block never lifted. ``most``: the peaks
    are the largest over several runs (``at most``); ``body_where``, ``plinth_where``: appended to each peak (the
    record that gave it). E.g. ``nothing lifts: the statue stays put on its plinth and the plinth does not rock``,
    ``the plinth does not rock; the statue rocks on it to 40 % of its overturning angle``.
    """
    from rockcli.report.words import past_words

    def at(r):  # "at most under 1 %" says "under" twice
        return "at most " if most and _share(r) != "under 1 %" else ""

    b = f"{at(body_peak)}{_share(body_peak)} of its overturning angle{body_where}{past_words(body_peak)}"
    p = (f"{at(plinth_peak)}{_share(plinth_peak)} of the overturning angle of the two as one block{plinth_where}"
         f"{past_words(plinth_peak)}")
    up_b, up_p = body_peak > 0, plinth_peak > 0
    if not up_b and not up_p:
        return f"nothing lifts: {body} stays put on its {plinth} and the {plinth} does not rock"
    if not up_p:
        return f"the {plinth} does not rock; {body} rocks on it to {b}"
    if not up_b:
        return f"{body} stays put on its {plinth}, which rocks with it to {p}"
    return f"{body} rocks on its {plinth} to {b}, and the {plinth} to {p}"


def _plinth_peak(row) -> float:
    p = getattr(row, "plinth_theta_max_over_alpha_asm", math.nan)
    return p if math.isfinite(p) else 0.0


def row_peak_words(row, *, body: str = "the body") -> str:
    """:func:`peak_words` of one assessment row of a body on a plinth (a run it did not topple in)."""
    return peak_words(row.theta_max_over_alpha, _plinth_peak(row), body=body, plinth=plinth_name(row))


def survivors_peak_words(rows, *, body: str = "the body", named: bool = True) -> str:
    """:func:`peak_words` of the largest peaks of each block over ``rows`` (the runs a body on a plinth survives),
    each named by its record when ``named``."""
    rb = max(rows, key=lambda r: r.theta_max_over_alpha)
    rp = max(rows, key=_plinth_peak)
    return peak_words(rb.theta_max_over_alpha, _plinth_peak(rp), body=body, plinth=plinth_name(rb), most=True,
                      body_where=f" ({rb.record})" if named else "", plinth_where=f" ({rp.record})" if named else "")


def run_sentence(stack, res) -> str:
    """One run of a body on its plinth (``res`` a :class:`rockcli.solve.StackResponse`) in one or two sentences:
    which block topples and when, or how each one rocks."""
    from rockcli.report.words import body_noun

    body, name = body_noun(stack.body), plinth_name(stack)
    if res.toppled == "body":
        return f"{body.capitalize()} topples off its {name} at {res.t_overturn_s:.2f} s."
    if res.toppled == "plinth":
        return f"The {name} topples at {res.t_overturn_s:.2f} s, and {body} with it."
    head = "" if res.settled else "Not proven (still moving at the horizon): "
    body_up = res.body.theta_max > 0.0 or not math.isnan(res.body.t_uplift_s)
    plinth_up = not math.isnan(res.plinth.t_uplift_s)
    b = res.body.theta_max_over_alpha if body_up else 0.0
    p = res.plinth.theta_max / res.alpha_asm if plinth_up else 0.0
    words = peak_words(b, p, body=body, plinth=name)
    if not body_up and not plinth_up:
        isolated = math.isfinite(getattr(res, "base_disp_max", math.nan))
        return head + (words[:1].upper() + words[1:] + f": both move with the "
                       f"{'isolated base' if isolated else 'ground'}.")
    return head + (f"{body.capitalize()} and its {name} survive" if res.settled else
                   f"Neither {body} nor its {name} has toppled") + ": " + words + "."


#: The question :func:`plinth_help_parts` answers, as the text and the HTML report head their answers.
PLINTH_QUESTION = "Does the plinth help?"


def plinth_summary(assessment, stack) -> str:
    """:data:`PLINTH_QUESTION` and :func:`plinth_help_parts` as one paragraph ('' when there is nothing to compare)."""
    parts = plinth_help_parts(assessment, stack)
    return (f"{PLINTH_QUESTION} " + " ".join(parts)) if parts else ""


def plinth_help_parts(assessment, stack) -> list:
    """Does the plinth help the body? One sentence per configuration on which both ran, comparing the body on the
    plinth (``stack``, a :class:`rockcli.models.Stack` column) with the same body alone (the column
    ``stack.body``), record by record (:func:`rockcli.report.verdicts.compare_foundations`): the records whose
    verdict the plinth changes decide it (``makes it worse``: it topples the body under records it survives alone,
    and saves it under none; ``better``: the reverse; ``helps under some records and hurts under others``); with no
    verdict changed, the closest calls (the smallest toppling factors) and the peaks compare the margins (``no
    difference`` when they agree to the 1 % of the margin search). Empty when the body alone is not in the
    assessment."""
    from rockcli.report.verdicts import _names, compare_foundations
    from rockcli.report.words import body_noun, configuration_words

    names = {b.name for b in assessment.columns}
    if stack.body.name not in names:
        return []
    body, on = body_noun(stack.body), f"its {plinth_name(stack)}"
    ran = [x for x in assessment.excitations if x.motion is not None]
    parts = []
    for c in assessment.configurations:
        alone = [assessment.row(stack.body.name, x.label, c.header) for x in ran]
        onp = [assessment.row(stack.name, x.label, c.header) for x in ran]
        cmp = compare_foundations(alone, onp)
        where = configuration_words(c)
        n, ka, kp = cmp["n"], len(cmp["ground"]), len(cmp["isolated"])
        if not n:
            parts.append(f"{where}: not compared (undecided or not computed)")
            continue
        counts = _topple_counts(kp, ka, n, on)
        effect = cmp["effect"]
        # a save by the luck of the timing is no margin (docs/assess.md, safe islands)
        islands = [p.record for p in onp if p.record in cmp["saved"]
                   and math.isfinite(getattr(p, "overturn_scale", math.nan)) and p.overturn_scale <= 1]
        topple = f"topple{'s' if len(cmp['saved']) == 1 else ''}"
        if effect == "worse":
            text = (f"{on} makes it worse: {body} topples on it under {_names(cmp['harmed'])}, which it survives "
                    f"standing alone; {counts}")
        elif effect == "better" and set(islands) == set(cmp["saved"]):  # every save a safe island: no real help
            text = (f"{on} saves it only by the luck of the timing: {body} survives on it under "
                    f"{_names(cmp['saved'])}, which {topple} it standing alone, but on a 'safe island' (a weaker "
                    f"version of the record topples it on {on} too); {counts}")
            islands = []
        elif effect == "better":
            text = (f"{on} makes it better: {body} survives on it under {_names(cmp['saved'])}, which {topple} it "
                    f"standing alone; {counts}")
        elif effect == "mixed":
            text = (f"{on} helps under some records and hurts under others: {body} survives on it under "
                    f"{_names(cmp['saved'])} (which {topple} it standing alone) but topples on it under "
                    f"{_names(cmp['harmed'])} (which it survives standing alone); {counts}")
        else:
            text = f"{on} changes no verdict ({counts})"
        if islands:
            text += (f" (but only by the luck of the timing: under {_names(islands)} it survives on {on} on a 'safe "
                     f"island', a weaker version of the record toppling it)")
        text += _margin_words(alone, onp, on, body)
        if cmp["open"]:
            text += f" ({_names(cmp['open'])} not compared: undecided or not computed on one of the two)"
        parts.append(f"{where}, {text}")
    return [p[:1].upper() + p[1:] + "." for p in parts]


def _topple_counts(kp: int, ka: int, n: int, on: str) -> str:
    """How many of the ``n`` records compared topple the body on the plinth (``kp``) and alone (``ka``)."""
    if n == 1:
        if kp == ka:
            return "the record topples it either way" if kp else "it survives the record either way"
        return f"the record topples it on {on}, not alone" if kp else f"the record topples it alone, not on {on}"
    if kp != ka:
        return f"{kp} of {n} records topple it on {on} against {ka} of {n} alone"
    return f"{kp} of {n} records topple it either way"


def _margin_words(alone, onp, on: str, body: str = "the body") -> str:
    """With the same verdicts: the closest calls (smallest toppling factor over the records) and the largest peaks
    of the survivors, alone and on the plinth, and which way they point (``no difference`` within 1 %); each
    block's peak said truthfully (:func:`survivors_peak_words`: a block that never lifts is said not to)."""
    from rockcli.report.verdicts import _smallest_factor
    from rockcli.report.words import SURVIVES, _x, outcome

    sa, sp = _smallest_factor(alone), _smallest_factor(onp)
    out = []
    if math.isfinite(sa) and math.isfinite(sp):
        if abs(sp / sa - 1.0) <= 0.01:
            out.append(f"no difference in the margin: the smallest toppling factor is {_x(sa)} alone and {_x(sp)} "
                       f"on {on}")
        else:
            out.append(f"by the margin {on} makes it {'better' if sp > sa else 'worse'}: the smallest toppling factor "
                       f"over the records is {_x(sa)} alone and {_x(sp)} on {on}")
    survived = [(a, p) for a, p in zip(alone, onp) if outcome(a) == SURVIVES and outcome(p) == SURVIVES]
    if survived:
        from rockcli.report.words import past_words

        pa = max(a.theta_max_over_alpha for a, _ in survived)
        alone_words = ("it does not lift off its base" if pa == 0 else
                       f"it rocks to at most {_share(pa)} of its overturning angle{past_words(pa)}")
        words = survivors_peak_words([p for _, p in survived], body=body, named=False)
        out.append(f"where it survives both ways, alone {alone_words}; "
                   + (f"on {on}, {words}" if words.startswith("nothing") else words))
    return ("; " + "; ".join(out)) if out else ""


__all__ = ["PLINTH_QUESTION", "peak_words", "plinth_help_parts", "plinth_name", "plinth_summary", "row_peak_words",
           "run_sentence", "survivors_peak_words"]
