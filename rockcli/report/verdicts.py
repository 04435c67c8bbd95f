"""The answer in plain words over many runs: every record of one body on one configuration
(:func:`configuration_sentence`, with the stroke the isolation bearings must allow), every body and configuration of
an assessment (:func:`verdict_lines`), whether isolation helps (:func:`compare_foundations`,
:func:`isolation_summary`: the records it saves the body under or topples it under, and where the verdicts agree,
the margins) and the question an assessment answers (:func:`question`).

Only words (:mod:`rockcli.report.words` for one run): the numbers come from the rows of an assessment (any object
with the attribute names of :class:`rockcli.assess.Assessment` works).
"""

from __future__ import annotations

import math

from rockcli.report.words import (FAILED, SURVIVES, TOPPLES, UNDECIDED, _all_azimuths, _pct, _x, body_noun, outcome,
                                  past_words, scene_sentence, stroke_m, survivor_stroke)


def configuration_sentence(rows, *, isolated: bool = False) -> str:
    """Every record of one body on one configuration in one sentence.

    With one record, :func:`scene_sentence`; with several, how many it survives, the closest call
    or the records that topple it (smallest factor first), undecided runs, and on isolation the
    largest base displacement over the records it survives (the stroke the bearings must allow; the
    runs in which it topples are left out, see :func:`survivor_stroke`).
    """
    rows = list(rows)
    ran = [r for r in rows if outcome(r) != FAILED]
    if len(rows) == 1:
        return scene_sentence(rows[0], isolated=isolated)
    if not ran:
        return f"{FAILED}: none of the {len(rows)} records could be run"
    n = len(ran)
    topples = sorted((r for r in ran if outcome(r) == TOPPLES), key=lambda r: _key(r.overturn_scale))
    undecided = [r for r in ran if outcome(r) == UNDECIDED]
    survived = [r for r in ran if outcome(r) == SURVIVES]
    parts = []
    if topples:
        named = ", ".join(f"{r.record}" + (f" already at {_x(r.overturn_scale)} times" if
                                           math.isfinite(r.overturn_scale) else "") for r in topples[:3])
        more = f" and {len(topples) - 3} more" if len(topples) > 3 else ""
        parts.append(f"topples under {len(topples)} of {n} records ({named}{more})")
        if survived:
            parts.append(f"survives the other {len(survived)}")
    elif survived:
        parts.append(f"survives {len(survived)} of {n} records" if undecided else
                     "survives both records" if n == 2 else f"survives all {n} records")
        peak = max(survived, key=lambda r: r.theta_max_over_alpha)
        if any(getattr(r, "plinth", "") for r in survived):  # a body on a plinth: each block's largest peak
            from rockcli.report.plinth_words import survivors_peak_words

            parts.append(survivors_peak_words(survived))
        elif all(r.verdict == "no_uplift" for r in survived):
            parts.append("it does not even lift off its base")
        else:
            parts.append(f"at most it rocks to {_pct(peak.theta_max_over_alpha)} of its overturning angle "
                         f"({peak.record}){past_words(peak.theta_max_over_alpha)}")
    if survived:
        weakest = min(survived, key=lambda r: _key(r.overturn_scale))
        s = weakest.overturn_scale
        if math.isfinite(s) and s > 1:
            parts.append(f"the closest call is {weakest.record}: {_x(s)} times stronger, it would topple it")
        islands = [r for r in survived if math.isfinite(r.overturn_scale) and r.overturn_scale <= 1]
        if islands:
            parts.append(f"{len(islands)} survived only on a 'safe island' (a weaker version of the record topples "
                         f"it: {', '.join(r.record for r in islands[:3])})")
        if not math.isfinite(s) and all(r.margin_note.startswith("no overturning") for r in survived):
            parts.append("not even records 4 times stronger topple it")
    if undecided:
        parts.append(f"{len(undecided)} undecided (still rocking when the computation stopped)")
    failed = len(rows) - n
    if failed:
        parts.append(f"{failed} could not be computed")
    if isolated:
        top = survivor_stroke(ran)
        if top is not None:
            where = ("over the orientations in which it survives, " if _all_azimuths(top) else
                     "where it survives, " if len(survived) < n else "")
            parts.append(f"{where}the base moves up to {stroke_m(top):.2f} m ({top.record}; the stroke the "
                         "bearings must allow)")
    return "; ".join(parts)


def _key(s: float) -> float:
    return s if math.isfinite(s) else math.inf


def verdict_lines(assessment) -> list[tuple]:
    """``(block, configuration, outcome word, sentence)`` for every body and configuration.

    The outcome word is that of the worst record: :data:`TOPPLES` if any record topples the body,
    else :data:`UNDECIDED` if any run is not proven, else :data:`SURVIVES` (:data:`FAILED` when none ran).
    """
    out = []
    for b in assessment.columns:
        for c in assessment.configurations:
            rows = [assessment.row(b.name, x.label, c.header) for x in assessment.excitations]
            words = {outcome(r) for r in rows}
            worst = next((w for w in (TOPPLES, UNDECIDED, SURVIVES) if w in words), FAILED)
            out.append((b, c, worst, configuration_sentence(rows, isolated=c.isolated)))
    return out


def _names(labels, limit: int = 3) -> str:
    """``a``, ``a and b``, ``a, b and c``, ``a, b, c and 2 more``."""
    labels = list(labels)
    shown = labels[:limit] + ([f"{len(labels) - limit} more"] if len(labels) > limit else [])
    return ", ".join(shown[:-1]) + " and " + shown[-1] if len(shown) > 1 else "".join(shown)


def compare_foundations(ground_rows, isolated_rows) -> dict:
    """How an isolated configuration compares with the ground, record by record.

    ``ground_rows`` and ``isolated_rows``: the rows of the same records (same order) on the ground and
    on the isolation. Returns the record labels that topple the body on the ground (``ground``) and on
    the bearings (``isolated``), those isolation saves (topple on the ground, survive on the bearings:
    ``saved``) and those it topples the body under although it survives them on the ground (``harmed``),
    those not compared because a run is undecided or failed on either (``open``), the number of records
    compared both ways (``n``) and the ``effect``: ``worse`` (harms under some records, saves under
    none), ``better`` (the reverse), ``mixed`` (both), ``same`` (no verdict differs).
    """
    pairs = list(zip(ground_rows, isolated_rows))
    decided = [(g, i) for g, i in pairs if {outcome(g), outcome(i)} <= {TOPPLES, SURVIVES}]
    out = {"n": len(decided), "open": [g.record for g, i in pairs if (g, i) not in decided],
           "ground": [g.record for g, _ in decided if outcome(g) == TOPPLES],
           "isolated": [i.record for _, i in decided if outcome(i) == TOPPLES],
           "saved": [g.record for g, i in decided if outcome(g) == TOPPLES and outcome(i) == SURVIVES],
           "harmed": [g.record for g, i in decided if outcome(g) == SURVIVES and outcome(i) == TOPPLES]}
    out["effect"] = ("mixed" if out["saved"] and out["harmed"] else "worse" if out["harmed"] else
                     "better" if out["saved"] else "same")
    return out


def _smallest_factor(rows) -> float:
    return min((r.overturn_scale for r in rows if math.isfinite(getattr(r, "overturn_scale", math.nan))),
               default=math.nan)


def _factor(rows) -> float:
    """The smallest toppling factor over ``rows`` for comparing margins: inf when every row's search found none up
    to 4x (``no overturning``), NaN when a factor is missing otherwise (no margin search, an error)."""
    s = _smallest_factor(rows)
    if math.isfinite(s):
        return s
    notes = [str(getattr(r, "margin_note", "") or "") for r in rows]
    return math.inf if notes and all(n.startswith("no overturning") for n in notes) else math.nan


def _fx(s: float) -> str:
    return "above 4" if s == math.inf else _x(s)


def _luck(row) -> bool:
    """The body survives the run only by the luck of the timing: a weaker version of the record topples it."""
    s = getattr(row, "overturn_scale", math.nan)
    return outcome(row) == SURVIVES and math.isfinite(s) and s <= 1


def _one_margin(row) -> str:
    """How far one run is from toppling the body, in words (:func:`_margin_clause` with one record)."""
    s = getattr(row, "overturn_scale", math.nan)
    if outcome(row) == TOPPLES:
        return f"it topples already at {_x(s)} times the record"
    if _luck(row):
        return f"it survives only by the luck of the timing (a weaker record, {_x(s)} times this one, topples it)"
    if s == math.inf or not math.isfinite(s):
        return "not even a record 4 times stronger topples it"
    return f"a record {_x(s)} times stronger would topple it"


def _margin_clause(c, g_rows, i_rows) -> str:
    """The margins compared where the verdicts alone say nothing (the same verdict either way), record by record:
    ``; by the margin isolation Tb=2.5s makes it better: ...``; with several records, under which records the
    toppling factor rises on the bearings and under which it falls (the largest changes first), a survival by the
    luck of the timing (a 'safe island': no margin at all) named where a margin replaces it or it replaces one;
    ``; no difference in the margin ...`` within the 1 % of the margin search; '' without margins."""
    iso = f"isolation {c.header}"
    pairs = [(g, i, _factor([g]), _factor([i])) for g, i in zip(g_rows, i_rows)
             if {outcome(g), outcome(i)} <= {TOPPLES, SURVIVES}]
    pairs = [p for p in pairs if not (math.isnan(p[2]) or math.isnan(p[3]) or p[2] == p[3] == math.inf)]
    if not pairs:
        return ""
    up = sorted((p for p in pairs if p[3] > 1.01 * p[2]), key=lambda p: -p[3] / p[2])
    down = sorted((p for p in pairs if p[3] < 0.99 * p[2]), key=lambda p: p[3] / p[2])
    if len(g_rows) == 1:
        sides = f"on the ground {_one_margin(g_rows[0])}; on the bearings {_one_margin(i_rows[0])}"
        if not up and not down:
            return f"; no difference in the margin: {sides}"
        return f"; by the margin {iso} makes it {'better' if up else 'worse'}: {sides}"
    if not up and not down:
        return (f"; no difference in the margin either: under every record the toppling factor on the bearings is "
                f"that on the ground, within 1 %")

    def item(p):
        g, i, a, b = p
        note = (": from a survival by the luck of the timing to a margin" if _luck(g) and b > 1 else
                ": from a margin to a survival by the luck of the timing" if _luck(i) and a > 1 else "")
        return f"{g.record} ({_fx(a)} to {_fx(b)}{note})"

    way = ("helps under some records and hurts under others" if up and down else
           "makes it better" if up else "makes it worse")
    moves = ([f"rises under {_names([item(p) for p in up])}"] if up else []) + \
            ([f"falls under {_names([item(p) for p in down])}"] if down else [])
    return (f"; by the margin, record by record, {iso} {way}: the toppling factor (on the ground, then on the "
            f"bearings) {', and '.join(moves)}")


def _saved_by_luck(c, g_rows, i_rows) -> str:
    """`` (but only by the luck of the timing under X: ...)`` when a record isolation saves the body under is a
    survival on a 'safe island' on the bearings (a weaker version of it topples the body there too)."""
    lucky = [i.record for g, i in zip(g_rows, i_rows) if outcome(g) == TOPPLES and _luck(i)]
    if not lucky:
        return ""
    under = f" under {_names(lucky)}" if len(g_rows) > 1 else ""
    return (f" (but only by the luck of the timing{under}: a weaker version of the record topples it on the bearings "
            f"too)")


def _one_record_clause(c, g_word: str, w: str, stroke: str, g_rows=(), i_rows=()) -> str:
    """The comparison under a single record (the words the README quotes); with the same verdict both ways, the
    margins compared (:func:`_margin_clause`): a survival by the luck of the timing is no margin."""
    if g_word == TOPPLES and w == SURVIVES:
        return f"isolation {c.header} saves it{stroke}{_saved_by_luck(c, g_rows, i_rows)}"
    if g_word == SURVIVES and w == TOPPLES:
        return f"isolation {c.header} makes it worse: it topples on it"
    if g_word == w == TOPPLES:
        return f"isolation {c.header} does not save it{_margin_clause(c, g_rows, i_rows)}"
    if g_word == w == SURVIVES:
        return f"it survives on isolation {c.header} too{stroke}{_margin_clause(c, g_rows, i_rows)}"
    return f"on isolation {c.header} it is {w}"


def _suite_clause(c, cmp: dict, g_rows, i_rows, stroke: str, noun: str) -> str:
    """The comparison over a suite of records: counts both ways, the records isolation saves ``noun``
    under and those it topples it under although it survives them on the ground."""
    n, kg, ki = cmp["n"], len(cmp["ground"]), len(cmp["isolated"])
    iso = f"isolation {c.header}"
    counts = (f"in all, {ki} of {n} records topple it on the bearings against {kg} of {n} on the ground"
              if ki != kg else f"in all, {ki} of {n} records topple it either way")
    s = "s" if len(cmp["saved"]) == 1 else ""
    saved = f"saves {noun} under {_names(cmp['saved'])} (which topple{s} it on the ground)"
    harmed = f"topples it under {_names(cmp['harmed'])} (which it survives on the ground)"
    effect = cmp["effect"]
    if effect == "mixed":
        return f"{iso} helps under some records and hurts under others: it {saved} but {harmed}; {counts}"
    if effect == "worse":
        return f"{iso} makes it worse: it topples {noun} under {_names(cmp['harmed'])} (which it survives on the " \
               f"ground); {counts}"
    if effect == "better":
        luck = _saved_by_luck(c, g_rows, i_rows)
        if ki == 0:
            return (f"{iso} saves {noun}: it survives all {n} records on the bearings{stroke}, against {kg} of {n} "
                    f"toppling it on the ground{luck}")
        return f"{iso} helps: it {saved}{stroke}{luck}; {counts}"
    # the same verdicts under every record: the margins decide (a survival by the luck of the timing is no margin)
    margins = _margin_clause(c, g_rows, i_rows)
    if kg:
        return f"{iso} changes no verdict: {noun} topples under the same {kg} of {n} records either way " \
               f"({_names(cmp['ground'])}){margins}"
    return f"{noun} survives all {n} records both on the ground and on {iso}{stroke}{margins}"


def isolation_summary(assessment, block) -> str:
    """Does isolation help ``block``? One sentence comparing each isolated configuration with the
    ground over the whole suite (empty without both a rigid and an isolated configuration).

    With one record: ``saves it``, ``makes it worse``, ``does not save it``, ``survives ... too``. With
    several (:func:`compare_foundations`): the records that topple the body each way, counted, and
    whether isolation makes it worse (it topples the body under records it survives on the ground, and
    saves it under none), better (the reverse), is mixed (both: the records are named) or changes no
    verdict; with the same verdicts, the margins compared record by record (:func:`_margin_clause`: a survival by
    the luck of the timing is no margin). The stroke is that of the surviving runs only (:func:`survivor_stroke`).
    """
    lines = {c.header: (c, w) for b, c, w, _ in verdict_lines(assessment) if b is block}
    grounds = [(c, w) for c, w in lines.values() if not c.isolated]
    if not grounds or len(grounds) == len(lines):
        return ""
    g, g_word = grounds[0]
    ran = [x for x in assessment.excitations if x.motion is not None]
    g_rows = [assessment.row(block.name, x.label, g.header) for x in ran]
    parts = []
    for c, w in lines.values():
        if not c.isolated:
            continue
        i_rows = [assessment.row(block.name, x.label, c.header) for x in ran]
        top = survivor_stroke(i_rows)
        stroke = f", provided the bearings can move {stroke_m(top):.2f} m" if top is not None else ""
        if len(ran) <= 1:
            parts.append(_one_record_clause(c, g_word, w, stroke, g_rows, i_rows))
            continue
        cmp = compare_foundations(g_rows, i_rows)
        noun = body_noun(block)
        clause = (_suite_clause(c, cmp, g_rows, i_rows, stroke, noun) if cmp["n"] else
                  f"on isolation {c.header} {noun} is {w}")
        if cmp["open"]:
            clause += (f" ({_names(cmp['open'])} not compared: undecided or not computed on one of the two)")
        parts.append(clause)
    if len(ran) <= 1:
        return f"In short: {body_noun(block)} {g_word} on the ground; " + "; ".join(parts) + "."
    return "In short: " + ". ".join(p if k == 0 else p[:1].upper() + p[1:] for k, p in enumerate(parts)) + "."


def question(assessment) -> str:
    """The question an assessment answers, in one sentence."""
    nouns = sorted({body_noun(b) for b in assessment.columns})
    who = nouns[0] if len(assessment.columns) == 1 else f"these {len(assessment.columns)} bodies"
    plinths = [b for b in assessment.columns if getattr(b, "plinth", None) is not None]
    if plinths and len(assessment.columns) == 2 * len(plinths):  # each body alone and on the plinth (--on)
        bodies = [b.body for b in plinths]
        who = (f"{body_noun(bodies[0])}, alone or on its {plinths[0].plinth.name.replace('_', ' ')}," if
               len(bodies) == 1 else f"these {len(bodies)} bodies, alone or on a plinth,")
        nouns = [who]
    drums = [b for b in assessment.columns if isinstance(getattr(b, "drums", None), tuple)]
    if drums and len(assessment.columns) == 2 * len(drums):  # each column of drums beside its monolith
        who = (f"{body_noun(drums[0])} and its monolith" if len(drums) == 1 else
               f"these {len(drums)} columns of drums and their monoliths")
        plinths = []
    xs = [x for x in assessment.excitations if x.motion is not None]
    what = f"the record {xs[0].label}" if len(xs) == 1 else f"{len(xs)} records"
    iso = any(c.isolated for c in assessment.configurations)
    rigid = any(not c.isolated for c in assessment.configurations)
    where = ("standing on the ground or on isolation bearings" if iso and rigid else
             "on isolation bearings" if iso else "standing on the ground")
    one = (len(assessment.columns) == 1 or (len(plinths) == 1 and len(assessment.columns) == 2)) and not drums
    return f"{'Does' if one else 'Do'} {who} topple under {what}, {where}?"
