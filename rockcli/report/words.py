"""The answer in plain words, one body and one run at a time, for readers who are not engineers.

The terse matrix of :mod:`rockcli.report.tables` (``OVERTURNS x0.73 [95%]``) is for experts; these words fit the
body (``the column`` for a temple preset, ``the statue`` for a block the user named ``statue``, ``the block`` when
it has no name):

* :func:`body_noun`, :func:`body_words`, :func:`column_title`, :func:`configuration_words`: the body and where it
  stands;
* :func:`outcome`: a run's verdict as a word (:data:`TOPPLES`, :data:`SURVIVES`, :data:`UNDECIDED`, :data:`FAILED`);
* :func:`scene_sentence`: one run (one record): ``survives: it rocks to 39 % of its overturning angle; a record
  1.60 times stronger would topple it``, ``topples: already at 0.73 times this record``;
* :func:`stroke_words`, :func:`stroke_m`, :func:`survivor_stroke`: the stroke the isolation bearings must allow;
* :func:`unavailable_notes`: the records that could not be run, in sentences.

Only words here: no click, no pandas, nothing computed but the words. The numbers come from the rows
(:class:`rockcli.assess.AssessmentRow`; any object with its attribute names works, e.g. for ``rockcli simulate``).
Sentences over many runs are in :mod:`rockcli.report.verdicts`, a body on a plinth in
:mod:`rockcli.report.plinth_words`; :mod:`rockcli.assess.verdicts` re-exports them all.
"""

from __future__ import annotations

import math
import re

from rockcli.models import COLUMN_PRESETS, Rigid
from rockcli.records.unavailable import Duplicate, Skipped

#: Names :func:`rockcli.models.build_block` and the CLI give a block the user did not name.
_UNNAMED = re.compile(r"(custom|block|R[-+0-9.eE]+m-alpha[-+0-9.eE]+deg|[-+0-9.eE]+x[-+0-9.eE]+m)")

#: Words for the isolation families (the part of a foundation's label before ``:``).
_BEARINGS = {"linear": "linear (rubber) bearings", "scss": "single concave sliding bearings",
             "lrb": "lead-rubber bearings", "dcss": "double concave sliding bearings"}

TOPPLES, SURVIVES, UNDECIDED, FAILED = "topples", "survives", "undecided", "not computed"


def body_noun(block) -> str:
    """``the column`` (a temple preset), ``the statue`` (a block named statue) or ``the block`` (unnamed); a body
    on a plinth (:class:`rockcli.models.Stack`): ``the statue on its plinth``."""
    from rockcli.report.drum_words import drum_noun, is_drums

    if is_drums(block):  # a column of drums (docs/physics-drums.md)
        return drum_noun(block)
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
    from rockcli.report.drum_words import drum_words, is_drums

    if is_drums(block):
        return drum_words(block)
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
    drummed = (getattr(row, "drums", None) or 0) > 1  # a column of drums: where it fails, how far its drums moved
    if what == TOPPLES:
        fall = f"as recorded, it falls after {row.t_overturn_s:.1f} s" if math.isfinite(row.t_overturn_s) else ""
        if math.isfinite(s):
            least = ", the weakest scale tried" if note.startswith("overturns already") else ""
            parts.append(f"topples: {'even' if least else 'already'} at {_x(s)} times this record{least}")
            parts += [fall] if fall else []
        else:
            parts.append(f"topples: {fall or 'it overturns'}")
        if drummed:
            from rockcli.report.drum_words import fall_words

            parts[0] = parts[0].replace("topples:", "fails:", 1)
            parts.append(fall_words(row))
        elif row.verdict == "slid_off":
            parts[0] = parts[0].replace("topples:", "slides off its plinth:", 1).replace("it falls", "it slides off")
            parts.append("its base reaches the plinth's edge (read as a fall)")
        elif getattr(row, "toppled", "") == "plinth":
            parts.append("the plinth topples, and the body with it")
        elif getattr(row, "toppled", "") == "body":
            parts.append("the body topples off its plinth")
    else:
        r = row.theta_max_over_alpha
        stacked = bool(getattr(row, "plinth", ""))  # a body on a plinth: each block's peak (plinth_words)
        if stacked:
            from rockcli.report.plinth_words import row_peak_words

            words = row_peak_words(row)
        if what == UNDECIDED:
            head = (f"undecided: still moving when the computation stopped ({words} so far); not counted as "
                    "surviving" if stacked else
                    f"undecided: still rocking when the computation stopped, at up to {_pct(r)} of its overturning "
                    "angle so far; not counted as surviving")
        elif stacked:
            head = f"survives: {words}"
        elif row.verdict == "slid":
            head = "survives: it does not rock"
        elif row.verdict == "no_uplift":
            head = "survives: it does not even lift off its base"
        elif r < 0.005:
            head = "survives: it barely lifts off its base (it rocks to under 1 % of its overturning angle)"
        else:
            head = f"survives: it rocks to {_pct(r)} of its overturning angle{past_words(r)}"
        parts.append(head)
        slide = getattr(row, "slide_max_m", math.nan)
        if getattr(row, "friction", "") and math.isfinite(slide) and slide > 0.0:  # friction as a model: it slid
            on = "on its plinth" if stacked else ("on the isolated base" if isolated else "on the ground")
            parts.append(f"it slides {slide_cm(slide)} {on} (friction {row.friction}), ending "
                         f"{slide_cm(abs(row.slide_residual_m))} from where it stood")
        if drummed:
            from rockcli.report.drum_words import offset_words

            parts += [w for w in (offset_words(row),) if w]
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


def slide_cm(x: float) -> str:
    """A slip [m] for a sentence: centimetres (1 decimal under 10 cm), under 1 mm in mm."""
    x = abs(float(x))
    if x < 1e-3:
        return f"{x * 1000:.1f} mm" if x >= 5e-5 else "less than 0.1 mm"
    return f"{x * 100:.1f} cm" if x < 0.1 else f"{x * 100:.0f} cm"


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


def column_title(block) -> str:
    """``Temple of Apollo at Bassae (bassae): R = 3.03 m, alpha = 10.56 deg, h/b = 5.36``."""
    from rockcli.report.drum_words import drum_title, is_drums

    if is_drums(block):
        return drum_title(block)
    preset = COLUMN_PRESETS.get(block.name)
    head = f"{preset[2]} ({block.name})" if preset else block.name
    return (f"{head}: R = {block.R:.2f} m, alpha = {block.alpha_deg:.2f} deg, h/b = {block.h / block.b:.2f}, "
            f"height {block.height:.2f} m, width {block.width:.2f} m")


def unavailable_notes(unavailable) -> list[str]:
    """Sentences for the notes: the skipped files of folder suites, counted, the records named twice, then
    what is not available."""
    skipped = [u for u in unavailable if isinstance(u, Skipped)]
    lines = []
    if skipped:
        lines.append(f"Skipped {len(skipped)} file(s) of the folder(s) that are not records (no reader recognises "
                     f"their content): {', '.join(u.label for u in skipped)}.")
    lines += [f"Counted once: {u.label} is {u.reason}." for u in unavailable if isinstance(u, Duplicate)]
    lines += [f"Not available: {u.label} ({u.reason})." for u in unavailable
              if not isinstance(u, (Skipped, Duplicate))]
    return lines
