"""Columns of drums in the HTML report of ``assess column`` (docs/physics-drums.md): on the first screen, per
column of drums and configuration, whether the drums make the column safer than its monolith (the counts and the
records whose verdict they change) with the reliability caveat where it applies; in the verdicts, the comparison
record by record (:func:`drum_comparison`); in the figures, where along the column the joints opened and where the
drums were left (:func:`openings_png`, from the rows: no rerun); in the assumptions, what the drums assume.

Only words and drawings of the rows' drum fields (:class:`rockcli.assess.AssessmentRow`)."""

from __future__ import annotations

import math

from rockcli.report.drum_words import (DRUM_QUESTION, UNRELIABLE_WORDS, _record_sentence, drum_answer, drum_cell,
                                       drum_noun, drum_words, is_drums, monolith_name)
from rockcli.report.html import esc, figure, num, table

#: What a column of drums assumes, for the report's assumptions (docs/physics-drums.md).
DRUM_ASSUMPTIONS = (
    "A column of drums is a stack of rigid drums free at every joint: each joint sticks, opens about either corner or "
    "slides under Coulomb's law with the one friction coefficient given (--friction), impacts are plastic, and a "
    "joint that would pull apart is kept shut (no flight). The drums are taken equal, of the base drum's diameter "
    "(the paper gives neither the taper nor the capital); the number of drums of Bassae (6) is an assumption.",
    "The monolith beside it is the paper's idealisation: one rigid block of the column's height and base width, with "
    "the same friction at its base. 'Safer' and 'worse' compare the two verdicts under each record; where both "
    "stand, the whole column's peak rocking on its footprint (within 2 %: alike).",
    "Each instant's contact pattern is chosen by a complementarity solve; where no pattern meets every condition of "
    "the contact law the run counts it. Such runs are marked NOT RELIABLE: strong shaking of tall columns of drums "
    "is not yet reliable in this model.",
)


def _unreliable(assessment, block) -> list:
    return [r for r in assessment.rows if r.column == block.name and r.reliable is False]


def caveat(assessment, block) -> str:
    """The reliability caveat of ``block`` (a column of drums), said plainly where it applies; '' where every run
    of it is reliable."""
    bad = _unreliable(assessment, block)
    if not bad:
        return ""
    n = sum(1 for r in assessment.rows if r.column == block.name and not r.error)
    return (f"<p class='short' style='color:#c0392b'>{esc(UNRELIABLE_WORDS)}: {len(bad)} of {n} answers for "
            f"{esc(drum_noun(block))} are not to be relied on ({esc(', '.join(sorted({r.record for r in bad})[:4]))}"
            f"{' ...' if len({r.record for r in bad}) > 4 else ''}).</p>")


def drum_certainty(assessment) -> str:
    """"How sure is this?" for the columns of drums: the caveat of each, or that every answer of theirs is
    reliable ('' without drums)."""
    out = []
    for b in (b for b in assessment.columns if is_drums(b)):
        text = caveat(assessment, b)
        out.append(text or f"<p>{esc(drum_noun(b)[:1].upper() + drum_noun(b)[1:])}: at every event of every run "
                           "(and of the scaled runs of the margins) the contact law found a consistent pattern.</p>")
    return "".join(out)


def drum_first_screen(assessment, block) -> str:
    """The first screen's answer to :data:`DRUM_QUESTION` for ``block``: per configuration the counts and the
    records whose verdict the drums change (safer or worse), and the caveat."""
    friction = getattr(block, "friction_label", "")
    parts = [f"<p class='short'>{esc(DRUM_QUESTION)} {esc(drum_noun(block)[:1].upper() + drum_noun(block)[1:])}, "
             f"beside its monolith{esc(f' (friction {friction} at every contact)' if friction else '')}:</p>",
             "<ul class='short'>"]
    for head, sentences in drum_answer(assessment, block):
        changed = [t for word, t in sentences if word in ("safer", "worse")]
        more = f"<li>and {len(changed) - 4} more (in 'Verdicts and margins')</li>" if len(changed) > 4 else ""
        parts.append(f"<li>{esc(head[:1].upper() + head[1:])}."
                     + ("<ul>" + "".join(f"<li>{esc(t)}.</li>" for t in changed[:4]) + more + "</ul>" if changed
                        else "") + "</li>")
    parts.append("</ul>")
    return "".join(parts) + caveat(assessment, block)


def _factor(r) -> str:
    s = r.overturn_scale
    return num(s, ".2f") if math.isfinite(s) else ">4" if str(r.margin_note).startswith("no overturning") else "-"


def drum_comparison(assessment, block) -> str:
    """Record by record, per configuration: the drums beside the monolith (verdict, failing factor), the
    comparison, where the column failed or which joint moved first, the largest opening and offset, reliability,
    and the sentence."""
    mono = monolith_name(assessment, block)
    head = ("record", "configuration", "drums", "monolith", "drums vs monolith", "drums fail at factor",
            "monolith fails at factor", "first to move", "largest joint opening", "largest drum offset", "reliable",
            "in words")
    rows = []
    for x in assessment.excitations:
        for c in assessment.configurations:
            r = assessment.row(block.name, x.label, c.header)
            m = assessment.row(mono, x.label, c.header) if mono else None
            if r.error:
                rows.append((esc(x.label), esc(c.header), "not computed", "-", "-", "-", "-", "-", "-", "-", "-",
                             esc(r.error)))
                continue
            word = r.drums_vs_monolith or "-"
            colour = {"safer": "w-survives", "worse": "w-topples", "undecided": "w-undecided"}.get(word, "")
            first = f"{r.first_move} at {r.first_move_t_s:.2f} s" if r.first_move else "nothing moves"
            if r.first_joint_open and not r.first_move.startswith(r.first_joint_open + " "):
                first += f"; the first joint to open: {r.first_joint_open} at {r.first_joint_open_t_s:.2f} s"
            opening = (f"{num(100 * r.joint_open_max_over_alpha, '.0f', '%')} ({esc(r.joint_open_max_at)})"
                       if math.isfinite(r.joint_open_max_over_alpha) and not r.overturned else "-")
            offset = (num(100 * r.residual_offset_max_m, "+.1f", "cm") if math.isfinite(r.residual_offset_max_m)
                      and not r.overturned else "-")
            rel = ("yes" if r.reliable else
                   f"<b class='w-topples'>NO</b> ({r.n_inconsistent} event{'s' if r.n_inconsistent > 1 else ''})"
                   if r.n_inconsistent else "<b class='w-topples'>NO</b> (its margin's runs)")
            rows.append((esc(x.label), esc(c.header), f"<code>{esc(drum_cell(r, assessment.margin))}</code>",
                         f"<code>{esc(drum_cell(m, assessment.margin))}</code>" if m else "-",
                         f"<b class='{colour}'>{esc(word)}</b>", _factor(r), _factor(m) if m else "-", esc(first),
                         opening, offset, rel,
                         f"<div class='words'>{esc(_record_sentence(r, m, drum_noun(block)).partition(': ')[2])}."
                         f"</div>"))
    friction = getattr(block, "friction_label", "")
    return (f"<h3>{esc(DRUM_QUESTION)} {esc(drum_words(block))}</h3>"
            f"<p>Beside its monolith{esc(f' ({mono})' if mono else '')}, with friction {esc(friction)} at every "
            f"contact (the base and each joint). A <b>joint's opening</b> is its peak rotation over the slenderness "
            f"of the drums above it (100 %: the tilt at which they would fall if everything stood still); a "
            f"<b>drum's offset</b> is how far it is left from the axis of the footprint, what one measures on a "
            f"standing column. The factors are the smallest scale of the record that makes each fail.</p>"
            + caveat(assessment, block)
            + table(head, rows, numeric=(5, 6, 8, 9)))


def openings_png(assessment, block) -> bytes | None:
    """One row of panels per configuration: left, each record's peak opening of every contact (over its
    slenderness) up the column where the column stands (green; amber: not proven), and a red cross at the contact
    where it failed under the other records (how many beside it); right, where each drum was left [cm]."""
    from collections import Counter

    from rockcli.report.html_figures import COLOURS, DPI, FIGURE_WIDTH_IN, _bytes, _rc
    from rockcli.report.figures import new_figure, plain
    from rockcli.report.words import outcome

    confs = assessment.configurations
    rows = {(r.record, r.configuration): r for r in assessment.rows if r.column == block.name and not r.error
            and r.peak_openings_over_alpha}
    if not rows:
        return None
    n = len(block.drums)
    names = ["base"] + [f"joint {j}" for j in range(1, n)]
    with _rc():
        fig = new_figure(FIGURE_WIDTH_IN, 1.0 + 0.16 * n * len(confs) + 0.9 * len(confs), dpi=DPI)
        axes = fig.subplots(len(confs), 2, squeeze=False)
        for k, c in enumerate(confs):
            ax, bx = axes[k]
            fell = Counter()
            for x in assessment.excitations:
                r = rows.get((x.label, c.header))
                if r is None:
                    continue
                if r.overturned:
                    fell[r.falls_at or "base"] += 1
                    continue
                colour = COLOURS[outcome(r)]
                peaks = [float(v) for v in r.peak_openings_over_alpha.split()]
                ax.plot(peaks, range(len(peaks)), marker="o", ms=3, lw=1, color=colour, alpha=0.8)
                if r.residual_offsets_m:
                    offs = [100 * float(v) for v in r.residual_offsets_m.split()]
                    bx.plot(offs, range(len(offs)), marker="o", ms=3, lw=1, color=colour, alpha=0.8)
            for at, count in fell.items():
                y = names.index(at) if at in names else 0
                ax.plot([3.0], [y], marker="x", ms=7, mew=2, color=COLOURS["topples"])
                ax.text(4.0, y, f"{count} record{'s' if count > 1 else ''}", va="center", fontsize=8.0,
                        color=COLOURS["topples"])
            for a, labels in ((ax, names), (bx, [f"drum {j + 1}" for j in range(n)])):
                a.set_yticks(range(n))
                a.set_yticklabels(labels, fontsize=8.0)
                a.set_ylim(-0.5, n - 0.5)
                a.grid(True, color="0.9", lw=0.5)
            ax.axvline(1.0, color="0.4", ls=":", lw=0.8)
            ax.set_xscale("symlog", linthresh=0.01)
            ax.set_xlim(0.0, 60.0)
            where = c.header if c.isolated else "on the ground"
            ax.set_title(plain(f"{where}: peak opening / slenderness; x: where it fails"), fontsize=9, loc="left")
            bx.set_title(plain(f"{where}: residual offset of each drum [cm]"), fontsize=9, loc="left")
        fig.suptitle(plain(f"{block.name}: green, a record it stands; x, the contact about which it fails"),
                     fontsize=9.5)
    return _bytes(fig)


def drum_figure(assessment, block) -> str:
    """The figure of :func:`openings_png` with its caption ('' when nothing ran)."""
    png = openings_png(assessment, block)
    if png is None:
        return ""
    return figure(png, f"{drum_noun(block)[:1].upper() + drum_noun(block)[1:]}: under the records it stands, how far "
                       "each joint opened (left; the dotted line at 1: the tilt at which the drums above would fall "
                       "if everything stood still) and where each drum was left (right), bottom to top; under the "
                       "others, the contact about which it failed and under how many records. The time history of "
                       "one run: rockcli simulate --drums N --friction MU.")


__all__ = ["DRUM_ASSUMPTIONS", "caveat", "drum_certainty", "drum_comparison", "drum_figure", "drum_first_screen", "is_drums",
           "openings_png"]
