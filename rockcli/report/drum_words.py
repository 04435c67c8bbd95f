"""A column of drums beside its monolith in plain words and in the terse table (``assess column nemea-drums
--friction MU``, docs/physics-drums.md).

* :func:`is_drums`, :func:`monolith_name`: which columns of an assessment are drums, and the monolith beside each
  (read from the rows: the monolith's rows carry the drum column's name and one drum);
* :func:`drum_noun`, :func:`drum_words`, :func:`drum_title`: the column of drums named for a reader;
* :func:`fall_words`, :func:`offset_words`: where a column fails, and how far its drums are left offset;
* :func:`drum_table`: records x configurations, the drums beside the monolith, the comparison and the reliability;
* :func:`drum_answer`: "Do the drums make the column safer?", per configuration and record by record;
* :func:`drum_notes`: the legend, the friction assumed and the reliability caveat.

Only words: the numbers come from the rows (:class:`rockcli.assess.AssessmentRow`'s drum fields).
"""

from __future__ import annotations

import math

#: The question :func:`drum_answer` answers, as the printout and the HTML report head it.
DRUM_QUESTION = "Do the drums make the column safer?"

#: Said wherever an answer rests on runs whose contact law found no consistent pattern at some event.
UNRELIABLE_WORDS = ("NOT RELIABLE: at some events of the run (or of the scaled runs its margin rests on) no contact "
                    "pattern met every condition of the contact law; strong shaking of tall columns of drums is not "
                    "yet reliable (docs/physics-drums.md, 'Not yet')")


def is_drums(block) -> bool:
    """A column of drums (a :class:`rockcli.models.drums.DrumColumn`, bare or with friction)."""
    return isinstance(getattr(block, "drums", None), tuple)


def monolith_name(assessment, block) -> str | None:
    """The name of the monolith run beside the column of drums ``block`` (None when it was not run)."""
    return next((r.column for r in assessment.rows if r.drum_column == block.name and r.column != block.name), None)


def _place(block) -> str:
    """``Nemea``: the site of a preset column of drums (from its source), else ''."""
    from rockcli.models.drums import DRUM_PRESETS

    preset = DRUM_PRESETS.get(str(block.name).lower())
    if preset is None:
        return ""
    return preset[3].partition(":")[0].rpartition(" at ")[2]


def drum_noun(block) -> str:
    """``the drum column of Nemea`` (a preset), ``the shaft of 5 drums`` (a column of drums of one's own)."""
    place = _place(block)
    return f"the drum column of {place}" if place else f"the {block.name.replace('_', ' ')} of {len(block.drums)} drums"


def drum_words(block) -> str:
    """``The drum column of Nemea: 13 drums of 0.79 m, 10.33 m tall and 1.52 m wide at the base (as one block
    R = 5.22 m, alpha = 8.37 deg)``."""
    hs = {round(h, 6) for h, _ in block.drums}
    each = f" of {next(iter(hs)):.2f} m" if len(hs) == 1 else ""
    return (f"{drum_noun(block)[:1].upper()}{drum_noun(block)[1:]}: {len(block.drums)} drums{each}, "
            f"{block.height:.2f} m tall and {block.width:.2f} m wide at the base (as one block R = {block.R:.2f} m, "
            f"alpha = {block.alpha_deg:.3g} deg)")


def drum_title(block) -> str:
    """The head of its table: ``The drum column of Nemea (nemea-drums): 13 drums, ...``."""
    return f"{drum_words(block)} [{block.name}]"


def fall_words(row) -> str:
    """Where a column of drums (or its monolith) fails, from its row: ``the whole column falls about its base``,
    ``the drums above joint 3 fall``, ``a drum slides off the one below at joint 2``."""
    at = getattr(row, "falls_at", "") or ""
    if row.verdict == "slid_off":
        return f"a drum slides off the one below at {at}" if at else "a drum slides off the one below"
    if at.startswith("joint"):
        return f"the drums above {at} fall"
    return "the whole column falls about its base"


def _cm(x: float) -> str:
    x = abs(float(x))
    return f"{100 * x:.1f} cm" if x < 0.1 else f"{100 * x:.0f} cm"


def offset_words(row) -> str:
    """``its drums are left offset by up to 2.1 cm`` (a column of drums that stands, its largest residual offset from
    the footprint's axis; under 1 mm: ``its drums are left in place``); '' otherwise."""
    x = getattr(row, "residual_offset_max_m", math.nan)
    if row.overturned or not math.isfinite(x) or (getattr(row, "drums", None) or 0) < 2:
        return ""
    return "its drums are left in place (offsets under 1 mm)" if abs(x) < 1e-3 else \
        f"its drums are left offset by up to {_cm(x)}"


def _share(r: float) -> str:
    """A peak over an overturning angle in percent; ``under 1 %`` for a lift that rounds to 0 %."""
    return "0 %" if r == 0 else "under 1 %" if r < 0.005 else f"{100 * r:.0f} %"


def _reliable(row) -> bool:
    return getattr(row, "reliable", None) is not False


def drum_cell(row, margin: bool, neighbourhood: bool = False) -> str:
    """The terse cell of a column of drums or its monolith: :func:`rockcli.report.tables.format_cell` with the
    drums' failure named (``FALLS base``, ``FALLS >joint 3``, ``SLIDES OFF joint 2``)."""
    from rockcli.report.tables import format_cell

    text = format_cell(row, margin, neighbourhood)
    if row.error or not row.overturned:
        return text
    at = getattr(row, "falls_at", "") or "base"
    head = "SLIDES OFF" if row.verdict == "slid_off" else "OVERTURNS" + (f" {row.toppled}" if row.toppled else "")
    new = f"SLIDES OFF {at}" if row.verdict == "slid_off" else ("FALLS base" if at == "base" else f"FALLS >{at}")
    return new + text[len(head):]


def _offset_cell(row) -> str:
    x = getattr(row, "residual_offset_max_m", math.nan)
    if row.error or row.overturned or not math.isfinite(x):
        return "-"
    return f"{100 * x:+.1f} cm"


def _reliable_cell(row) -> str:
    if row.error or row.reliable is None:
        return "-"
    if row.reliable:
        return "yes"
    return f"NO ({row.n_inconsistent})" if row.n_inconsistent else "NO (margin)"


def drum_table(assessment, block) -> str:
    """One column of drums beside its monolith: per record and configuration the drums' cell, the monolith's, the
    comparison, the largest residual offset of a drum and whether the drums' answer is reliable; then per
    configuration how many records each survives."""
    mono = monolith_name(assessment, block)
    margin, nb = assessment.margin, assessment.neighbourhood
    head = ["record", "configuration", "drums", "monolith" + (f" ({mono})" if mono else ""), "drums vs monolith",
            "largest offset", "reliable"]
    table = [head]
    for x in assessment.excitations:
        label = x.label + (" (pulse)" if x.kind == "pulse" else "")
        for c in assessment.configurations:
            r = assessment.row(block.name, x.label, c.header)
            m = assessment.row(mono, x.label, c.header) if mono else None
            table.append([label, c.header, drum_cell(r, margin, nb), drum_cell(m, margin, nb) if m else "-",
                          r.drums_vs_monolith or "-", _offset_cell(r), _reliable_cell(r)])
    widths = [max(len(t[i]) for t in table) for i in range(len(head))]
    lines = [drum_title(block) + (f", beside its monolith [{mono}]" if mono else "")]
    for i, t in enumerate(table):
        lines.append("  ".join(cell.ljust(w) for cell, w in zip(t, widths)).rstrip())
        if i == 0:
            lines.append("  ".join("-" * w for w in widths))
    lines.append("  ".join("-" * w for w in widths))
    for c in assessment.configurations:
        lines.append(f"{c.header}: " + _counts(assessment, block.name, mono, c))
    return "\n".join(lines)


def _survived(rows) -> int:
    return sum(1 for r in rows if not r.error and not r.overturned and r.proven is not False)


def _counts(assessment, name, mono, c) -> str:
    ran = [x for x in assessment.excitations if x.motion is not None]
    d = [assessment.row(name, x.label, c.header) for x in ran]
    n = sum(not r.error for r in d)
    text = f"the drums survive {_survived(d)} of {n}"
    if mono:
        m = [assessment.row(mono, x.label, c.header) for x in ran]
        text += f", the monolith {_survived(m)} of {sum(not r.error for r in m)}"
    words = [r.drums_vs_monolith for r in d if r.drums_vs_monolith]
    if words:
        text += "; the drums are " + ", ".join(f"{k} under {words.count(k)}" for k in
                                                ("safer", "worse", "alike", "undecided") if words.count(k))
    bad = sum(r.reliable is False for r in d)
    if bad:
        text += f"; {bad} of {n} NOT RELIABLE"
    return text


def _record_sentence(r, m, noun: str) -> str:
    """One record: ``kobe-1995-takarazuka-000: the drum column of Nemea survives where its monolith topples: safer;
    its drums are left offset by up to 2.0 cm``."""
    from rockcli.report.words import SURVIVES, TOPPLES, outcome

    def what(row, who):
        o = outcome(row)
        if o == TOPPLES:
            s = row.overturn_scale
            tail = f", already at {s:.2f} times the record" if math.isfinite(s) and s <= 1 else ""
            if who == "its monolith":
                return f"{who} topples{tail}"
            return f"{who} fails: {fall_words(row)}{tail}"
        if o == SURVIVES:
            s = row.overturn_scale
            tail = (f" (a record {s:.2f} times stronger would make it fail)" if math.isfinite(s) and s > 1 else
                    " (only by the luck of the timing: a weaker record makes it fail)" if math.isfinite(s) else
                    " (not even a record 4 times stronger makes it fail)"
                    if str(row.margin_note).startswith("no overturning") else "")
            return f"{who} survives{tail}"
        return f"{who} is {o}"

    if m is None:
        text = what(r, noun)
    elif outcome(r) != outcome(m):
        text = f"{what(r, noun)} where {what(m, 'its monolith')}"
    elif what(r, "") == what(m, ""):  # the same words (no margin to tell them apart)
        text = f"{what(r, noun)}, and so does its monolith"
    else:
        text = f"{what(r, noun)}; {what(m, 'its monolith')}"
    if r.drums_vs_monolith:
        text += f": {r.drums_vs_monolith}"
        if r.verdict == m.verdict == "no_uplift":
            text += " (neither lifts off its base)"
        elif r.drums_vs_monolith in ("safer", "worse", "alike") and outcome(r) == outcome(m) == "survives":
            text += (f" (the whole column rocks to {_share(r.theta_max_over_alpha)} of its overturning angle "
                     f"against the monolith's {_share(m.theta_max_over_alpha)})")
    off = offset_words(r)
    if off:
        text += f"; {off}"
    if not _reliable(r):
        text += "; NOT RELIABLE" + (f" ({r.n_inconsistent} contact choice{'s' if r.n_inconsistent > 1 else ''} "
                                    f"without a consistent pattern)" if r.n_inconsistent else
                                    " (its margin rests on runs with contact choices without a consistent pattern)")
    return f"{r.record}: {text}"


def drum_answer(assessment, block) -> list:
    """:data:`DRUM_QUESTION`, answered for the column of drums ``block``: per configuration ``(the counts, [(drums vs
    monolith, sentence), ...])``, one sentence per record (:func:`_record_sentence`), safer and worse first."""
    from rockcli.report.words import configuration_words

    mono = monolith_name(assessment, block)
    noun = drum_noun(block)
    out = []
    ran = [x for x in assessment.excitations if x.motion is not None]
    for c in assessment.configurations:
        pairs = [(assessment.row(block.name, x.label, c.header),
                  assessment.row(mono, x.label, c.header) if mono else None) for x in ran]
        rank = {"safer": 0, "worse": 0, "undecided": 1, "alike": 2, "": 3}
        pairs.sort(key=lambda p: rank.get(p[0].drums_vs_monolith, 3))
        lines = [(r.drums_vs_monolith, _record_sentence(r, m, noun)) for r, m in pairs if not r.error]
        lines += [("", f"{r.record}: not computed ({r.error})") for r, _ in pairs if r.error]
        out.append((f"{configuration_words(c)}: {_counts(assessment, block.name, mono, c)}", lines))
    return out


def drum_notes(assessment) -> list:
    """The legend of :func:`drum_table` and, where it applies, the reliability caveat."""
    drums = [b for b in assessment.columns if is_drums(b)]
    if not drums:
        return []
    lines = ["Columns of drums (docs/physics-drums.md): every joint a contact that sticks, opens about either corner "
             "or slides (Coulomb, " + ", ".join(sorted({b.friction_label for b in drums if
                                                       getattr(b, "friction_label", "")})) + "), beside the monolith "
             "of the same height and base width with the same friction at its base. FALLS base: the whole column "
             "falls about its base; FALLS >joint k: the drums above joint k fall; SLIDES OFF joint k: a drum slides "
             "off the one below; xS: the smallest scale factor of the record that makes the column fail that way; "
             "drums vs monolith: by the verdict, then by the base's peak rocking (within 2 %: alike); largest "
             "offset: of a drum from the footprint's axis at the end."]
    bad = [r for r in assessment.rows if r.reliable is False]
    if bad:
        lines.append(f"{UNRELIABLE_WORDS}: {len(bad)} of {sum(1 for r in assessment.rows if r.drum_column)} runs "
                     f"(reliable NO in the table).")
    return lines


__all__ = ["DRUM_QUESTION", "UNRELIABLE_WORDS", "drum_answer", "drum_cell", "drum_noun", "drum_notes", "drum_table",
           "drum_title", "drum_words", "fall_words", "is_drums", "monolith_name", "offset_words"]
