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
    """``the column`` (a temple preset), ``the statue`` (a block named statue) or ``the block`` (unnamed)."""
    name = str(getattr(block, "name", "") or "")
    if name.lower() in COLUMN_PRESETS:
        return "the column"
    if not name or _UNNAMED.fullmatch(name):
        return "the block"
    return "the " + name.replace("_", " ")


def body_words(block) -> str:
    """``The statue, 1.79 m tall and 0.50 m wide (R = 0.93 m, alpha = 15.5 deg)``; a preset names its temple."""
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
    else:
        r = row.theta_max_over_alpha
        if what == UNDECIDED:
            head = (f"undecided: still rocking when the computation stopped, at up to {_pct(r)} of its overturning "
                    "angle so far; not counted as surviving")
        elif row.verdict == "no_uplift":
            head = "survives: it does not even lift off its base"
        elif r < 0.005:
            head = "survives: it barely lifts off its base (it rocks to under 1 % of its overturning angle)"
        else:
            head = f"survives: it rocks to {_pct(r)} of its overturning angle"
        parts.append(head)
        if math.isfinite(s) and s > 1:
            parts.append(f"a record {_x(s)} times stronger would topple it")
        elif math.isfinite(s):
            parts.append(f"but a weaker record, {_x(s)} times this one, topples it (it survives on a 'safe island', "
                         "by the luck of the timing)")
        elif note.startswith("no overturning"):
            parts.append("not even a record 4 times stronger topples it")
    if isolated and stroke and math.isfinite(row.base_disp_max_m):
        parts.append(f"the base moves up to {row.base_disp_max_m:.2f} m (the stroke the bearings must allow)")
    share = getattr(row, "overturn_share_pm10", math.nan)
    if math.isfinite(share):
        parts.append(_share_words(share))
    return "; ".join(parts)


def configuration_sentence(rows, *, isolated: bool = False) -> str:
    """Every record of one body on one configuration in one sentence.

    With one record, :func:`scene_sentence`; with several, how many it survives, the closest call
    or the records that topple it (smallest factor first), undecided runs, and on isolation the
    largest base displacement over all records (the stroke the bearings must allow).
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
        if all(r.verdict == "no_uplift" for r in survived):
            parts.append("it does not even lift off its base")
        else:
            parts.append(f"at most it rocks to {_pct(peak.theta_max_over_alpha)} of its overturning angle "
                         f"({peak.record})")
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
        disp = [r for r in ran if math.isfinite(r.base_disp_max_m)]
        if disp:
            top = max(disp, key=lambda r: r.base_disp_max_m)
            parts.append(f"the base moves up to {top.base_disp_max_m:.2f} m ({top.record}; the stroke the bearings "
                         "must allow)")
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


def isolation_summary(assessment, block) -> str:
    """Does isolation help ``block``? One sentence comparing each isolated configuration with the
    ground (empty without both a rigid and an isolated configuration)."""
    lines = {c.header: (c, w) for b, c, w, _ in verdict_lines(assessment) if b is block}
    ground = [w for c, w in lines.values() if not c.isolated]
    if not ground or len(ground) == len(lines):
        return ""
    g = ground[0]
    parts = []
    for c, w in lines.values():
        if not c.isolated:
            continue
        rows = [assessment.row(block.name, x.label, c.header) for x in assessment.excitations]
        disp = max((r.base_disp_max_m for r in rows if outcome(r) != FAILED and math.isfinite(r.base_disp_max_m)),
                   default=math.nan)
        stroke = f", provided the bearings can move {disp:.2f} m" if math.isfinite(disp) else ""
        if g == TOPPLES and w == SURVIVES:
            parts.append(f"isolation {c.header} saves it{stroke}")
        elif g == SURVIVES and w == TOPPLES:
            parts.append(f"isolation {c.header} makes it worse: it topples on it")
        elif g == w == TOPPLES:
            parts.append(f"isolation {c.header} does not save it")
        elif g == w == SURVIVES:
            parts.append(f"it survives on isolation {c.header} too{stroke}")
        else:
            parts.append(f"on isolation {c.header} it is {w}")
    several = sum(x.motion is not None for x in assessment.excitations) > 1
    where = "on the ground" + ({TOPPLES: " (under at least one record)", SURVIVES: " (under every record)"}
                               .get(g, "") if several else "")
    return f"In short: {body_noun(block)} {g} {where}; " + "; ".join(parts) + "."


def question(assessment) -> str:
    """The question an assessment answers, in one sentence."""
    nouns = sorted({body_noun(b) for b in assessment.columns})
    who = nouns[0] if len(assessment.columns) == 1 else f"these {len(assessment.columns)} bodies"
    xs = [x for x in assessment.excitations if x.motion is not None]
    what = f"the record {xs[0].label}" if len(xs) == 1 else f"{len(xs)} records"
    iso = any(c.isolated for c in assessment.configurations)
    rigid = any(not c.isolated for c in assessment.configurations)
    where = ("standing on the ground or on isolation bearings" if iso and rigid else
             "on isolation bearings" if iso else "standing on the ground")
    return f"{'Does' if len(assessment.columns) == 1 else 'Do'} {who} topple under {what}, {where}?"


def format_verdicts(assessment, width: int = 100) -> str:
    """The answer as ``rockcli assess column`` prints it: per body, one sentence per configuration."""
    import textwrap

    lines = ["In plain words:"]
    xs = [x.label for x in assessment.excitations if x.motion is not None]
    under = f"under {xs[0]}" if len(xs) == 1 else f"under {len(xs)} records"
    answers = verdict_lines(assessment)
    for b in assessment.columns:
        lines.append(f"{body_words(b)}, {under}:")
        for _, c, _, sentence in (a for a in answers if a[0] is b):
            lines.append(textwrap.fill(f"{configuration_words(c)}: {sentence}.", width, initial_indent="  ",
                                       subsequent_indent="      "))
        short = isolation_summary(assessment, b)
        if short:
            lines.append(textwrap.fill(short, width, initial_indent="  ", subsequent_indent="      "))
    return "\n".join(lines)
