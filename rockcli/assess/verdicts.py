"""The answer in plain words: one sentence per body and configuration, for readers who are not engineers.

The terse matrix of :mod:`rockcli.report.tables` (``OVERTURNS x0.73 [95%]``) is for experts; this
module says the same thing in words that fit the body (``the column`` for a temple preset, ``the
statue`` for a block the user named ``statue``, ``the block`` when it has no name):

* :func:`scene_sentence`: one run (one record): ``survives: it rocks to 39 % of its overturning
  angle; a record 1.60 times stronger would topple it``, ``topples: already at 0.73 times this
  record``;
* :func:`configuration_sentence`: every record of one body on one configuration, with the stroke
  the isolation bearings must allow (the peak base displacement);
* :func:`format_verdicts`: the text ``rockcli assess column`` prints under its table.

Only words here: no click, no pandas. The numbers come from :class:`rockcli.assess.AssessmentRow`
(any object with its attribute names works, e.g. for ``rockcli simulate``).
"""

from __future__ import annotations

import math
import re

from rockcli.models import COLUMN_PRESETS, Rigid

#: Names :func:`rockcli.models.build_block` and the CLI give a block the user did not name.
_UNNAMED = re.compile(r"(custom|block|R[-+0-9.eE]+m-alpha[-+0-9.eE]+deg|[-+0-9.eE]+x[-+0-9.eE]+m)")

#: Words for the isolation families (the part of a foundation's label before ``:``).
_BEARINGS = {"linear": "linear (rubber) bearings", "scss": "single concave sliding bearings",
             "lrb": "lead-rubber bearings", "dcss": "double concave sliding bearings"}

TOPPLES, SURVIVES, UNDECIDED, FAILED = "topples", "survives", "undecided", "not computed"


def body_noun(block) -> str:
    """``the column`` (a temple preset), ``the statue`` (a block named statue) or ``the block`` (unnamed); a body
    on a plinth (:class:`rockcli.models.Stack`): ``the statue on its plinth``."""
    plinth = getattr(block, "plinth", None)
    if plinth is not None:
        return f"{body_noun(block.body)} on its {plinth.name.replace('_', ' ')}"
    name = str(getattr(block, "name", "") or "")
    if name.lower() in COLUMN_PRESETS:
        return "the column"
    if not name or _UNNAMED.fullmatch(name):
        return "the block"
    return "the " + name.replace("_", " ")


def body_words(block) -> str:
    """``The statue, 1.79 m tall and 0.50 m wide (R = 0.93 m, alpha = 15.5 deg)``; a preset names its temple."""
    plinth = getattr(block, "plinth", None)
    if plinth is not None:
        return (f"{body_words(block.body)}, on a free {plinth.name.replace('_', ' ')} {plinth.height:.2f} m tall and "
                f"{plinth.width:.2f} m wide ({block.m2:.2g} times its mass)")
    preset = COLUMN_PRESETS.get(str(block.name).lower())
    head = body_noun(block).capitalize() + (f" of the {preset[2]}" if preset else "")
    return (f"{head}, {block.height:.2f} m tall and {block.width:.2f} m wide "
            f"(R = {block.R:.2f} m, alpha = {block.alpha_deg:.3g} deg)")


def configuration_words(configuration) -> str:
    """``standing on the ground`` or ``on linear (rubber) bearings, Tb=2.5s``."""
    f = getattr(configuration, "foundation", configuration)
    if isinstance(f, Rigid):
        return "standing on the ground"
    family = f.label.partition(":")[0]
    header = getattr(configuration, "header", f.label)
    return f"on {_BEARINGS.get(family, family + ' bearings')}, {header}"


def outcome(row) -> str:
    """:data:`TOPPLES`, :data:`SURVIVES`, :data:`UNDECIDED` (not proven) or :data:`FAILED` (an error)."""
    if getattr(row, "error", ""):
        return FAILED
    if row.overturned:
        return TOPPLES
    if row.proven is False:
        return UNDECIDED
    return SURVIVES


def _x(s: float) -> str:
    return f"{s:.2f}"


def _pct(r: float) -> str:
    return f"{100 * r:.0f} %"


#: Said after a survivor's peak shown as 100 % of its overturning angle or more: a block past that tilt falls only
#: if nothing pushes it back, and the shaking did.
PAST_WORDS = " (past the tilt at which it would fall if everything stood still; the shaking brought it back)"


def past_words(r: float) -> str:
    """:data:`PAST_WORDS` after a survivor's peak ``r`` (over its overturning angle) shown as 100 % or more, else ''."""
    return PAST_WORDS if math.isfinite(r) and round(100 * r) >= 100 else ""


def _share_words(share: float, n_factors: int = 21) -> str:
    k = int(round(share * n_factors))
    text = f"scaled by 0.90 to 1.10 it topples in {k} of {n_factors} cases"
    if k in (0, n_factors):
        return text + " (a robust verdict)"
    if 0.2 <= share <= 0.8:
        return text + " (a coin toss: within the uncertainty of any record the verdict flips)"
    return text


def scene_sentence(row, *, isolated: bool = False, stroke: bool = True) -> str:
    """One run in words, e.g. ``survives: it rocks to 39 % of its overturning angle; a record 1.60 times
    stronger would topple it``.

    ``row`` has the fields of :class:`rockcli.assess.AssessmentRow` (``overturn_scale`` etc. NaN when
    the margin was not searched). ``isolated``: name the base displacement as the bearings' stroke
    (when ``stroke``).
    """
    what = outcome(row)
    if what == FAILED:
        return f"{FAILED}: {row.error}"
    s = getattr(row, "overturn_scale", math.nan)
    note = getattr(row, "margin_note", "") or ""
    parts = []
    if what == TOPPLES:
        fall = f"as recorded, it falls after {row.t_overturn_s:.1f} s" if math.isfinite(row.t_overturn_s) else ""
        if math.isfinite(s):
            least = ", the weakest scale tried" if note.startswith("overturns already") else ""
            parts.append(f"topples: {'even' if least else 'already'} at {_x(s)} times this record{least}")
            parts += [fall] if fall else []
        else:
            parts.append(f"topples: {fall or 'it overturns'}")
        if getattr(row, "toppled", "") == "plinth":
            parts.append("the plinth topples, and the body with it")
        elif getattr(row, "toppled", "") == "body":
            parts.append("the body topples off its plinth")
    else:
        r = row.theta_max_over_alpha
        stacked = bool(getattr(row, "plinth", ""))  # a body on a plinth: each block's peak (plinth_words)
        if stacked:
            from rockcli.assess.plinth_words import row_peak_words

            words = row_peak_words(row)
        if what == UNDECIDED:
            head = (f"undecided: still moving when the computation stopped ({words} so far); not counted as "
                    "surviving" if stacked else
                    f"undecided: still rocking when the computation stopped, at up to {_pct(r)} of its overturning "
                    "angle so far; not counted as surviving")
        elif stacked:
            head = f"survives: {words}"
        elif row.verdict == "no_uplift":
            head = "survives: it does not even lift off its base"
        elif r < 0.005:
            head = "survives: it barely lifts off its base (it rocks to under 1 % of its overturning angle)"
        else:
            head = f"survives: it rocks to {_pct(r)} of its overturning angle{past_words(r)}"
        parts.append(head)
        if math.isfinite(s) and s > 1:
            parts.append(f"a record {_x(s)} times stronger would topple it")
        elif math.isfinite(s):
            parts.append(f"but a weaker record, {_x(s)} times this one, topples it (it survives on a 'safe island', "
                         "by the luck of the timing)")
        elif note.startswith("no overturning"):
            parts.append("not even a record 4 times stronger topples it")
    if isolated and stroke and (math.isfinite(row.base_disp_max_m) or _all_azimuths(row)):
        parts.append(stroke_words(row))
    share = getattr(row, "overturn_share_pm10", math.nan)
    if math.isfinite(share):
        parts.append(_share_words(share))
    return "; ".join(parts)


def stroke_words(row) -> str:
    """The peak base displacement of one isolated run, named for what it is: the stroke the bearings must
    allow when the body survives; only a displacement before the fall when it topples (a toppled run's
    displacement is no demand to design the bearings for); a lower bound when the run is undecided. With
    ``--azimuth worst`` (a row standing for every orientation run) the stroke over the orientations in which it
    survives (:func:`stroke_m`), whatever the most adverse one did."""
    if _all_azimuths(row):
        s = stroke_m(row)
        if not math.isfinite(s):
            return f"it survives in none of the {row.azimuths_run} orientations: no stroke to give"
        return (f"over the orientations in which it survives, the base moves up to {s:.2f} m (the stroke the "
                f"bearings must allow)")
    d = f"{row.base_disp_max_m:.2f} m"
    what = outcome(row)
    if what == TOPPLES:
        return f"the base had moved up to {d} when it toppled (not a stroke to design for)"
    if what == UNDECIDED:
        return f"the base moved up to {d} so far (the stroke needed is at least that)"
    return f"the base moves up to {d} (the stroke the bearings must allow)"


def _all_azimuths(row) -> bool:
    """The row stands for every orientation of a pair (``--azimuth worst``)."""
    return bool(getattr(row, "azimuths_run", None))


def stroke_m(row) -> float:
    """The stroke [m] one row asks of the bearings: its peak base displacement when the body survives the run
    (NaN when it topples, is undecided or failed); with ``--azimuth worst`` the largest over the orientations
    in which it survives (``base_disp_max_surviving_azimuths_m``), whatever the most adverse one did."""
    if _all_azimuths(row):
        return getattr(row, "base_disp_max_surviving_azimuths_m", math.nan)
    return getattr(row, "base_disp_max_m", math.nan) if outcome(row) == SURVIVES else math.nan


def survivor_stroke(rows):
    """The row with the largest stroke (:func:`stroke_m`) among the runs the body survives (None when it
    survives none): the stroke the bearings must allow is that of the surviving runs only, since where the
    body topples the bearings' travel protects nothing."""
    kept = [r for r in rows if math.isfinite(stroke_m(r))]
    return max(kept, key=stroke_m, default=None)


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
            from rockcli.assess.plinth_words import survivors_peak_words

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
    xs = [x for x in assessment.excitations if x.motion is not None]
    what = f"the record {xs[0].label}" if len(xs) == 1 else f"{len(xs)} records"
    iso = any(c.isolated for c in assessment.configurations)
    rigid = any(not c.isolated for c in assessment.configurations)
    where = ("standing on the ground or on isolation bearings" if iso and rigid else
             "on isolation bearings" if iso else "standing on the ground")
    one = len(assessment.columns) == 1 or (len(plinths) == 1 and len(assessment.columns) == 2)
    return f"{'Does' if one else 'Do'} {who} topple under {what}, {where}?"


def _fill(text: str, width: int, **kw) -> str:
    """``textwrap.fill`` that never breaks a number from its unit (``62 %``, ``0.34 m``, ``6.8 s``, ``0.28 g``)."""
    import textwrap

    glued = re.sub(r"(\d) (%|m|s|g)(?!\w)", "\\1\x1f\\2", text)
    return textwrap.fill(glued, width, **kw).replace("\x1f", " ")


def format_verdicts(assessment, width: int = 100) -> str:
    """The answer as ``rockcli assess column`` prints it: per body, one sentence per configuration.

    Raises
    ------
    RockcliInputError
        ``assessment`` is not what :func:`rockcli.assess.run_assessment` returns, or ``width`` is not a whole
        number >= 40.
    """
    import numbers

    from rockcli.assess.table import Assessment
    from rockcli.errors import RockcliInputError
    from rockcli.io.inputs import check_type

    check_type(assessment, Assessment, "assessment", "the Assessment of run_assessment(...)")
    check_type(width, numbers.Integral, "width", "a whole number of characters >= 40")
    if width < 40:
        raise RockcliInputError(f"width must be a whole number of characters >= 40, got {width}")

    lines = ["In plain words:"]
    xs = [x.label for x in assessment.excitations if x.motion is not None]
    under = f"under {xs[0]}" if len(xs) == 1 else f"under {len(xs)} records"
    answers = verdict_lines(assessment)
    for b in assessment.columns:
        lines.append(f"{body_words(b)}, {under}:")
        for _, c, _, sentence in (a for a in answers if a[0] is b):
            lines.append(_fill(f"{configuration_words(c)}: {sentence}.", width, initial_indent="  ",
                                       subsequent_indent="      "))
        short = isolation_summary(assessment, b)
        if short:
            lines.append(_fill(short, width, initial_indent="  ", subsequent_indent="      "))
        helps = plinth_help_parts(assessment, b) if getattr(b, "plinth", None) is not None else []
        if helps:
            lines.append(f"  {PLINTH_QUESTION}")
            lines += [_fill(h, width, initial_indent="  - ", subsequent_indent="    ") for h in helps]
    return "\n".join(lines)


from rockcli.assess.plinth_words import PLINTH_QUESTION, plinth_help_parts, plinth_summary  # noqa: E402,F401
