"""The three HTML reports: ``assess column`` (:func:`assessment_report`), ``assess fragility``
(:func:`fragility_report`) and ``simulate`` (:func:`simulate_report`).

Each returns the page as a string (see :mod:`rockcli.report.html` for its sections); the CLI writes
it with :func:`rockcli.report.html.write_report`. Drawing the figures reruns the records that decide
each verdict with their full history (:mod:`rockcli.report.html_deciding`: a few runs); everything
else comes from the results passed in.
"""

from __future__ import annotations

import math
from types import SimpleNamespace

from rockcli.report.html import (assumptions_section, body_section, breakable, card, configurations_section, esc,
                                 figure, num, page, plural, reproduce_section, table)
from rockcli.report.html_deciding import orientation_words, response_figures, stack_figures
from rockcli.report.html_records import records_section
from rockcli.report.figures import block_text
from rockcli.report.html_figures import margins_png, png_of, share_png, stroke_png
from rockcli.report.plinth_words import PLINTH_QUESTION, plinth_help_parts
from rockcli.report.verdicts import isolation_summary, question, verdict_lines
from rockcli.report.words import (SURVIVES, TOPPLES, body_noun, body_words, configuration_words, outcome,
                                  scene_sentence, stroke_m, survivor_stroke)

MARGIN_WORDS = (
    "<p>The <b>toppling factor</b> is the smallest number the record must be multiplied by for the body to "
    "topple. Above 1, the body survives the record with that margin (1.6: a record 1.6 times stronger would "
    "topple it). At or below 1 on a body that topples: it topples already at that fraction of the record. At or "
    "below 1 on a body that survives: weaker versions of the record topple it, and it survived this one by the "
    "luck of the timing (a 'safe island'): count that as no margin. '&gt;4': nothing up to 4 times the record "
    "topples it. <b>Peak rocking</b> is the largest tilt as a share of the angle beyond which the body falls "
    "(alpha). The <b>&plusmn;10 % share</b> (when run) says how many of the records scaled by 0.90, 0.91, ..., "
    "1.10 topple it: 0 or 21 of 21 is a firm verdict, anything between says the answer is on a knife's "
    "edge.</p>")

NO_MARGIN_WORDS = (
    "<p>The margins (toppling factors) were not searched (<code>--no-margin</code>): each verdict is that of the "
    "record as given. <b>Peak rocking</b> is the largest tilt as a share of the angle beyond which the body falls "
    "(alpha). The <b>&plusmn;10 % share</b> (when run) says how many of the records scaled by 0.90, 0.91, ..., "
    "1.10 topple it.</p>")


def _title(blocks) -> str:
    return f"Will {body_noun(blocks[0])} topple?" if len(blocks) == 1 else "Will these bodies topple?"


def stroke_facts(disp_m: float, word: str) -> str:
    """The base's stroke of a run on bearings as a key figure read by its ``word`` (SURVIVES: the stroke the
    bearings must allow; TOPPLES: how far it had moved, not a stroke to design for; else: at least that)."""
    d = f"{disp_m:.2f} m"
    return _facts([("the bearings must allow", d)] if word == SURVIVES else
                  [("the base had moved", d, "until it toppled: not a stroke to design for")]
                  if word == TOPPLES else [("the base moved", d, "so far: the stroke needed is at least that")])


def _facts(facts) -> str:
    """Key figures: ``(name, value)`` or ``(name, value, note)``."""
    return ('<div class="keyfacts">' + "".join(f'<div class="fact">{esc(f[0])}<br><b>{esc(f[1])}</b>'
                                               + (f"<br><span class='note'>{esc(f[2])}</span>" if len(f) > 2 else "")
                                               + "</div>" for f in facts) + "</div>")


def _friction_assumptions(blocks) -> tuple:
    """The friction model's assumptions when a column has friction (``--friction``), else none."""
    if not any(getattr(b, "friction_label", "") for b in blocks):
        return ()
    from rockcli.report.html_slide import FRICTION_ASSUMPTIONS

    return FRICTION_ASSUMPTIONS


def _list(items) -> str:
    return "<ul>" + "".join(f"<li>{i}</li>" for i in items) + "</ul>"


# --------------------------------------------------------------------------------------------------
# assess column
# --------------------------------------------------------------------------------------------------

def _peak_cell(r) -> str:
    if r.error or r.overturned:
        return "-"
    if getattr(r, "plinth", ""):  # a body on a plinth: each block over its own tipping angle, or that it stays put
        def pct(v: float, still: str) -> str:
            return still if not v > 0 else "&lt;1 %" if v < 0.005 else num(100 * v, ".0f", "%")

        return (f"body {pct(r.theta_max_over_alpha, 'stays put')},<br>plinth "
                f"{pct(r.plinth_theta_max_over_alpha_asm, 'does not rock')}")
    return "no lift-off" if r.verdict == "no_uplift" else num(100 * r.theta_max_over_alpha, ".0f", "%")


def _verdict_table(assessment, block) -> str:
    from rockcli.report.tables import format_cell

    rows = []
    for x in assessment.excitations:
        for c in assessment.configurations:
            r = assessment.row(block.name, x.label, c.header)
            word = outcome(r)
            s = r.overturn_scale
            factor = (num(s, ".2f") if math.isfinite(s) else ">4" if r.margin_note.startswith("no overturning")
                      else "-")
            css = "w-" + word.replace(" ", "-")
            rows.append((breakable(x.label), esc(c.header), f'<b class="{css}">{esc(word)}</b>', _peak_cell(r),
                         factor, _stroke_cell(r, word) if c.isolated else "-",
                         num(100 * r.overturn_share_pm10, ".0f", "%"),
                         f"<div class='words'>{esc(scene_sentence(r, isolated=False) + '.')}</div>",
                         f"<code>{esc(format_cell(r, assessment.margin, assessment.neighbourhood))}</code>"))
    head = ("record", "configuration", "verdict", "peak rocking", "toppling factor", "base moves up to",
            "&plusmn;10 % share toppling", "in words", "terse")
    note = ("" if getattr(block, "plinth", None) is None else
            f"<p class='note'>Peak rocking on the plinth: the body's tilt on its plinth over its own alpha "
            f"({block.body.alpha_deg:.3g} deg), the plinth's over alpha_asm ({math.degrees(block.alpha_asm):.3g} deg: "
            "the slenderness of body and plinth as one block, the tilt at which the plinth tips over while the body "
            "rests on it).</p>")
    return f"<h3>{esc(body_words(block))}</h3>" + table(head, rows, numeric=(3, 4, 5, 6)) + note


def _certainty(assessment, check) -> str:
    from rockcli.conditioning import ILL_PEAK

    items = []
    if check is None:
        items.append("The numerical checks were not run (add <code>--check-tolerance</code> to rerun every scene "
                     "at a 100 times tighter tolerance and on motions moved by one rounding unit).")
    else:
        if check.changed:
            items.append(f"<b>{len(check.changed)} verdicts change</b> at a 100 times tighter tolerance: they are "
                         "decided by the numerics, read them as a coin toss: "
                         + ", ".join(esc(f"{r.column} / {r.record} / {r.configuration}") for r, _ in check.changed))
        else:
            items.append(f"Tolerance: all {check.n_runs} scenes give the same verdicts at a 100 times tighter "
                         f"tolerance (rtol {check.rtol:g}); the largest change of a peak is "
                         f"{check.max_peak_change:.1e} of alpha.")
        if check.ill:
            items.append(f"<b>{len(check.ill)} scenes are ill-conditioned</b>: moving the ground motion by one "
                         f"rounding unit changes the verdict or moves the peak by more than {ILL_PEAK:g} alpha; "
                         "their answer is one sample of a spread: "
                         + ", ".join(esc(f"{r.column} / {r.record} / {r.configuration}") for r, _, _ in check.ill))
        else:
            items.append(f"Conditioning: on {check.ulp_draws} copies of each motion moved by one rounding unit, "
                         f"no verdict changes (largest change of a peak {check.max_ulp_peak_change:.1e} of "
                         "alpha): the answers are determined by the inputs.")
    def scenes(rows, extra=lambda r: "") -> str:
        return ", ".join(esc(f"{r.column} / {r.record} / {r.configuration}{extra(r)}") for r in rows)

    if assessment.neighbourhood:
        shaky = [r for r in assessment.rows if 0 < r.overturn_share_pm10 < 1]
        items.append(f"Neighbourhood: the verdict changes between 0.90 and 1.10 times the record in "
                     f"{plural(len(shaky), 'scene')} (the &plusmn;10 % share above): {scenes(shaky)}" if shaky else
                     "Neighbourhood: no verdict changes between 0.90 and 1.10 times the records: every verdict "
                     "is firm.")
    else:
        items.append("The neighbourhood check was not run (add <code>--neighbourhood</code> to see whether each "
                     "verdict holds for the record scaled by 0.90 to 1.10).")
    if assessment.margin:
        islands = [r for r in assessment.rows if outcome(r) == SURVIVES and math.isfinite(r.overturn_scale)
                   and r.overturn_scale <= 1]
        items.append(f"Safe islands: a weaker version of the record topples {plural(len(islands), 'surviving scene')}"
                     f": {scenes(islands, lambda r: f' (x{r.overturn_scale:.2f})')}." if islands else
                     "Safe islands: none (no surviving scene is toppled by a weaker version of its record).")
        notes = [r for r in assessment.rows if "not proven" in r.margin_note]
        if notes:
            items.append(f"Scaled runs still moving at the end of the computation, counted as surviving, enter "
                         f"{plural(len(notes), 'margin')}: those margins are upper estimates.")
    unproven = assessment.unproven
    items.append(f"<b>NOT PROVEN: {plural(len(unproven), 'run')}</b> still rocking when the computation stopped "
                 f"(not counted as surviving): {scenes(unproven)}" if unproven else
                 "Every verdict is proven: each run either toppled or came to rest (or could no longer topple) "
                 "before the computation stopped.")
    if assessment.idealised:
        items.append("<b>Idealised</b>: " + esc(", ".join(assessment.idealised)) + " were run as their catalogued "
                     "single pulse, not as records (their files were not found); a pulse misses many overturns.")
    for x in assessment.failed:
        items.append(f"Not used: {esc(x.label)}: {esc(x.error)}")
    return _list(items)


def _stroke_cell(r, word: str) -> str:
    """The verdict table's "base moves up to": the run's peak base displacement (until the fall when it toppled);
    with --azimuth worst, the stroke over the orientations in which the body survives."""
    def note(text: str) -> str:  # wraps under the number (the cell's numbers do not)
        return f"<br><span class='note'>{text}</span>"

    if getattr(r, "azimuths_run", None):
        s = stroke_m(r)
        return (num(s, ".3f", "m") + note("largest over the orientations it survives") if math.isfinite(s) else
                "-" + note("it survives in no orientation"))
    return num(r.base_disp_max_m, ".3f", "m") + (note("until it toppled") if word == TOPPLES else "")


def _not_available(unavailable) -> list:
    from rockcli.records.unavailable import Skipped

    return [u for u in unavailable if not isinstance(u, Skipped)]


def _stroke_fact(assessment, block, c, many: bool) -> tuple:
    """The stroke the bearings of ``c`` must allow: the largest base displacement of the runs the body
    survives (:func:`rockcli.report.words.survivor_stroke`); the runs in which it topples are left out
    and said to be."""
    rows = [assessment.row(block.name, x.label, c.header) for x in assessment.excitations if x.motion is not None]
    rows = [r for r in rows if not r.error]
    name = f"the bearings must allow ({c.header}" + (f", {block.name})" if many else ")")
    top = survivor_stroke(rows)
    fell = sum(outcome(r) == TOPPLES for r in rows)
    kept = sum(outcome(r) == SURVIVES for r in rows)
    if top is None:
        return (name, "-", "it survives no record on them: no stroke to give")
    if any(getattr(r, "azimuths_run", None) for r in rows):  # --azimuth worst: over the orientations it survives
        return (name, f"{stroke_m(top):.2f} m", f"under {top.record}, the largest over the orientations in which "
                f"it survives")
    if not fell:
        return (name, f"{top.base_disp_max_m:.2f} m") + ((f"under {top.record}",) if len(rows) > 1 else ())
    return (name, f"{top.base_disp_max_m:.2f} m",
            f"under {top.record}, the largest where it survives ({kept} of {len(rows)} records); the "
            f"{plural(fell, 'run')} in which it topples {'is' if fell == 1 else 'are'} left out")


def _projections(assessment) -> dict:
    """Per pair run in every orientation (``azimuth="worst"``), the projections its rows ran and why:
    ``{label: [(record, words)]}`` (:func:`rockcli.report.html_records.records_section`), in azimuth order."""
    out = {}
    many = len(assessment.columns) > 1
    for x in assessment.excitations:
        if not getattr(x, "azimuths", ()) or x.motion is None:
            continue
        used = {}
        for b in assessment.columns:
            for c in assessment.configurations:
                row = assessment.row(b.name, x.label, c.header)
                if row.error:
                    continue
                ran = assessment.excitation_of(row)
                where = configuration_words(c) + (f" ({b.name})" if many else "")
                used.setdefault(ran.azimuth_deg, (ran, []))[1].append((where, row))
        out[x.label] = [(ran.motion, orientation_words(len(x.azimuths), items))
                        for _, (ran, items) in sorted(used.items())]
    return out


def assessment_report(assessment, *, check=None, command: str = "") -> str:
    """The HTML report of ``rockcli assess column`` (``check``: a :class:`rockcli.assess.table.ToleranceCheck`)."""
    blocks = assessment.columns
    answers = verdict_lines(assessment)
    first = [f"<p class='question'>{esc(question(assessment))}</p>"]
    for b in blocks:
        first.append(f"<h3>{esc(body_words(b))}</h3>")
        first += [card(w, configuration_words(c), s) for bb, c, w, s in answers if bb is b]
        short = isolation_summary(assessment, b)
        if short:
            first.append(f"<p class='short'>{esc(short)}</p>")
        helps = plinth_help_parts(assessment, b) if getattr(b, "plinth", None) is not None else []
        if helps:
            first.append(f"<p class='short'>{esc(PLINTH_QUESTION)}</p><ul class='short'>"
                         + "".join(f"<li>{esc(h)}</li>" for h in helps) + "</ul>")
    from rockcli.report.html_drums import (DRUM_ASSUMPTIONS, drum_certainty, drum_comparison, drum_figure,
                                           drum_first_screen, is_drums)

    first += [drum_first_screen(assessment, b) for b in blocks if is_drums(b)]  # do the drums make it safer?
    facts = []
    for b in blocks:
        for c in assessment.configurations:
            if c.isolated:
                facts.append(_stroke_fact(assessment, b, c, many=len(blocks) > 1))
    n_ran = sum(x.motion is not None for x in assessment.excitations)
    missing = _not_available(assessment.unavailable)
    facts.append(("ground motions", f"{n_ran}", *([f"{len(missing)} more not available"] if missing else [])))
    frictions = sorted({getattr(b, "friction_label", "") for b in blocks} - {""})
    if frictions:  # friction as a model: said on the first screen
        slid = sum(1 for r in assessment.rows if r.friction and (r.verdict in ("slid", "slid_off")
                                                                  or (r.slide_max_m or 0.0) > 0.0))
        facts.append(("friction (Coulomb)", ", ".join(frictions),
                      f"every contact may slide; it slides in {slid} of {len(assessment.rows)} runs"))
    if assessment.unproven:  # a card of "0" undecided runs on the first screen reads as an alarm: none then
        facts.append(("runs not proven", f"{len(assessment.unproven)}", "still rocking when the computation stopped: "
                                                                       "not counted as surviving (see 'How sure is "
                                                                       "this?')"))
    first.append(_facts(facts))
    figs = []
    for b in blocks:
        if is_drums(b):  # a column of drums: where its joints opened and its drums were left, every record
            figs.append(drum_figure(assessment, b))
        elif getattr(b, "friction_label", ""):  # friction as a model: the friction runs, with their slips
            from rockcli.report.html_slide import slide_figures

            figs.append(slide_figures(assessment, b))
        elif getattr(b, "plinth", None) is None:  # the response figures draw a single block's rocking
            figs.append(response_figures(assessment, b))
        else:  # a body on its plinth: both blocks, beside the body alone
            figs.append(stack_figures(assessment, b))
        records = [x.label for x in assessment.excitations if x.motion is not None]
        rows = [r for r in assessment.rows if r.column == b.name]
        confs = assessment.configurations
        figs.append(figure(margins_png(rows, records, confs, f"{block_text(b)}\nhow far each record is from toppling it"),
                           "Toppling factor per record and configuration (red: topples as recorded; green: "
                           "survives; amber: undecided), labelled with the configuration's short name (see 'How it "
                           "stands'). Right of the line at 1: the margin."))
        if n_ran > 1 and assessment.margin:
            figs.append(figure(share_png(rows, confs, f"{block_text(b)}\nshare of the records that topple it"),
                               "If every record were scaled by the same factor: the share of them that topple the "
                               "body (from each record's smallest toppling factor)."))
        figs.append(figure(stroke_png(rows, records, confs, f"{block_text(b)}\ndisplacement demand on the bearings"),
                           "Peak displacement of the isolated base relative to the ground: where the body "
                           "survives, the stroke the bearings and the gap around the base must allow; hatched, the "
                           "runs in which it toppled (the displacement until it fell, not a stroke to design for)."
                           + (" A pair of components: the largest over the orientations in which the body survives "
                              "(hatched: the most adverse one's, when it survives in none)."
                              if any(r.azimuths_run for r in rows) else "")))
    sections = {
        "answer": "\n".join(first),
        "body": body_section(blocks, restitution=assessment.solver.get("restitution"),
                             cap_ratio=assessment.solver.get("cap_ratio") or 0.0),
        "configurations": configurations_section(assessment.configurations),
        "records": records_section(assessment.excitations, assessment.unavailable, _projections(assessment)),
        "verdicts": (MARGIN_WORDS if assessment.margin else NO_MARGIN_WORDS)
                    + "\n".join(_verdict_table(assessment, b) for b in blocks)
                    + "\n".join(drum_comparison(assessment, b) for b in blocks if is_drums(b)),
        "figures": "\n".join(f for f in figs if f) or "<p>No run to draw.</p>",
        "certainty": _certainty(assessment, check) + drum_certainty(assessment),
        "assumptions": assumptions_section(_friction_assumptions(blocks)
                                           + (DRUM_ASSUMPTIONS if any(is_drums(b) for b in blocks) else ()),
                                           margins=assessment.margin),
        "reproduce": reproduce_section(command),
    }
    return page(_title(blocks), "rockcli assess column: rocking and overturning of free-standing bodies "
                                "(Vassiliou & Makris 2012)", sections)


# --------------------------------------------------------------------------------------------------
# assess fragility
# --------------------------------------------------------------------------------------------------

def _fragility_sentence(fr, curve, rows, rigid) -> tuple[str, str]:
    im = fr.im
    ran = [r for r in rows if not r.error]
    k = sum(math.isfinite(r.overturn_scale) and r.overturn_scale <= 1 for r in ran)
    word = TOPPLES if k else SURVIVES
    parts = [f"{k} of {len(ran)} records topple it at or below their recorded strength"]
    if math.isfinite(curve.median):
        lo, hi = curve.median_ci
        parts.append(f"half of such records would topple it at {im.name} = {curve.median:.3f} {im.units}"
                     + (f" ({100 * fr.level:g} % interval {lo:.3f} to {hi:.3f})" if math.isfinite(lo) else "")
                     + f", one in six already at {curve.median * math.exp(-curve.beta):.3f} {im.units}")
    else:
        parts.append("no curve could be fitted" + (f" ({curve.note})" if curve.note else ""))
    if curve.configuration.isolated and math.isfinite(curve.ratio_to_rigid) and rigid:
        ratio, (lo, hi) = curve.ratio_to_rigid, curve.ratio_ci
        if math.isfinite(lo) and lo <= 1 <= hi:
            effect = f"(interval {lo:.2f} to {hi:.2f}: not clearly better or worse than on the ground)"
        else:
            effect = "(it makes the body more robust)" if ratio > 1 else "(it makes the body more fragile)"
        parts.append(f"isolation multiplies that {im.name} by {ratio:.2f} {effect}")
    return word, "; ".join(parts)


def fragility_report(fr, *, command: str = "", restitution: float | None = None) -> str:
    """The HTML report of ``rockcli assess fragility``."""
    from rockcli.report.fragility import plot_fragility

    blocks = fr.columns
    rigid = any(not c.isolated for c in fr.configurations)
    first = [f"<p class='question'>How likely is {esc(body_noun(blocks[0]) if len(blocks) == 1 else 'each body')} "
             f"to topple as the shaking grows ({esc(fr.im.description)}), "
             + ("standing on the ground or on isolation bearings?" if rigid else "on isolation bearings?") + "</p>"]
    curve_rows, record_rows = [], []
    for b in blocks:
        first.append(f"<h3>{esc(body_words(b))}</h3>")
        for c in fr.configurations:
            curve = fr.curve(b.name, c.header)
            rows = fr.rows_of(b.name, c.header)
            word, sentence = _fragility_sentence(fr, curve, rows, rigid)
            first.append(card(word, configuration_words(c), sentence))
            curve_rows.append((esc(b.name), esc(c.header), str(curve.n_records), str(curve.n_right + curve.n_left),
                               num(curve.median, ".3f", fr.im.units), esc(f"{num(curve.median_ci[0], '.3f')} to "
                                                                           f"{num(curve.median_ci[1], '.3f')}"),
                               num(curve.beta, ".2f"), num(curve.ratio_to_rigid, ".2f"), esc(curve.note)))
            for r in rows:
                record_rows.append((esc(b.name), esc(r.record), esc(c.header), num(r.im_value, ".3f"),
                                    num(r.overturn_scale, ".2f"), num(r.capacity, ".3f"), esc(r.censored),
                                    esc(r.error or r.margin_note)))
    im = fr.im
    verdicts = (f"<p>Each record is scaled until the body topples; the factor times the record's {esc(im.name)} is "
                f"its capacity. A lognormal curve is fitted to the capacities: the <b>median</b> is the "
                f"{esc(im.name)} at which half of such records topple the body, <b>beta</b> the spread (0.3: "
                f"records agree; 0.8: they differ widely). <b>median/none</b> above 1: isolation helps.</p>"
                + table(("body", "configuration", "records", "censored", f"median [{esc(im.units)}]",
                         f"{100 * fr.level:g} % interval", "beta", "median/none", "note"), curve_rows,
                        numeric=(2, 3, 4, 6, 7))
                + "<h3>Per record</h3>"
                + table(("body", "record", "configuration", f"{esc(im.name)} [{esc(im.units)}]", "toppling factor",
                         f"capacity [{esc(im.units)}]", "censored", "note"), record_rows, numeric=(3, 4, 5)))
    figs = []
    try:
        figs.append(figure(png_of(lambda path: plot_fragility(fr, path)),
                           f"Probability of toppling against {im.name}: fitted curves, bands of "
                           f"{100 * fr.level:g} % (bootstrap), dots: the records.", smallest_pt=7.0))
    except Exception as exc:  # no exact capacity: no curve to draw, the tables still say why
        figs.append(f"<p>No fragility curve drawn: {esc(exc)}</p>")
    records = [x.label for x in fr.excitations if x.motion is not None]
    for b in blocks:
        rows = [r for r in fr.rows if r.column == b.name]
        figs.append(figure(margins_png(rows, records, fr.configurations, f"{block_text(b)}\ntoppling factor per record"),
                           "Toppling factor per record: right of the line at 1, the margin."))
    unproven = [r for r in fr.rows if "not proven" in r.margin_note]
    items = [f"The intervals come from {fr.n_boot} bootstrap resamples over the records (seed {fr.seed}); "
             "with few records they are wide, and they are the honest measure of how sure the median is.",
             f"Records that do not topple the body up to {fr.grid[1]:g} times are counted as censored (their "
             "capacity is known only to be larger)."]
    items.append(f"{len(unproven)} capacities include scaled runs still rocking when the computation stopped, "
                 "counted as surviving (upper estimates)." if unproven else
                 "Every scaled run reached a proven verdict.")
    items += [f"Not used: {esc(x.label)}: {esc(x.error)}" for x in fr.failed]
    sections = {
        "answer": "\n".join(first), "body": body_section(blocks, restitution=restitution),
        "configurations": configurations_section(fr.configurations),
        "records": records_section(fr.excitations, fr.unavailable),
        "verdicts": verdicts, "figures": "\n".join(f for f in figs if f), "certainty": _list(items),
        "assumptions": assumptions_section(("A fragility curve describes records like these; it is only as "
                                            "representative of a site as the suite is.",)),
        "reproduce": reproduce_section(command),
    }
    return page(_title(blocks), f"rockcli assess fragility: probability of toppling against {im.name}", sections)


# --------------------------------------------------------------------------------------------------
# simulate
# --------------------------------------------------------------------------------------------------

def simulate_report(block, foundation, excitation, response, *, label: str, checked: dict | None = None,
                    command: str = "", restitution: float | None = None, cap_ratio: float = 0.0) -> str:
    """The HTML report of ``rockcli simulate`` (``response`` with its history; ``checked``: the
    ``check_*`` results of ``--check-tolerance``)."""
    from rockcli.models.spec import configuration_of
    from rockcli.report.html_figures import responses_png

    conf = configuration_of(foundation.label)
    row = SimpleNamespace(error="", overturned=response.overturned,
                          proven=bool(response.overturned or response.settled),
                          verdict=response.verdict, theta_max_over_alpha=response.theta_max_over_alpha,
                          t_overturn_s=response.t_overturn_s, base_disp_max_m=response.base_disp_max_m,
                          overturn_scale=math.nan, margin_note="", overturn_share_pm10=math.nan)
    word = outcome(row)
    where = configuration_words(conf)
    first = [f"<p class='question'>Does {esc(body_noun(block))} topple under {esc(label)}, {esc(where)}?</p>",
             f"<h3>{esc(body_words(block))}</h3>", card(word, where, scene_sentence(row, isolated=conf.isolated))]
    if conf.isolated:
        first.append(stroke_facts(response.base_disp_max_m, word))
    t = lambda v: num(v, ".3f", "s")  # noqa: E731
    result = [("verdict", esc(word)), ("lifts off at", t(response.t_uplift_s)),
              ("tilts beyond alpha at", t(response.t_exceed_alpha_s)), ("topples at", t(response.t_overturn_s)),
              ("peak tilt / alpha", "-" if response.overturned else num(response.theta_max_over_alpha, ".4f")),
              ("impacts", f"{response.n_impacts} during shaking, {response.n_impacts_total} in all"),
              ("peak base displacement", num(response.base_disp_max_m, ".4f", "m")),
              ("integration", f"{response.steps} steps, ended at {response.t_end_s:.2f} s")]
    png = responses_png([(conf, response)], block, excitation, label)
    caption = (f"Response of {block.name} to {label}, {where}: ground acceleration; tilt over alpha (beyond the "
               "dashed lines at +-1 the body leans past its tipping point)"
               + ("; displacement of the isolated base" if conf.isolated else "") + ". "
               + ("A red line marks the instant it topples." if response.overturned else ""))
    items = []
    if checked:
        same = checked["check_tight_rtol_verdict"] == response.verdict
        items.append(f"At a 100 times tighter tolerance (rtol {checked['check_tight_rtol']:g}) the verdict "
                     + ("is the same." if same else f"<b>changes to {esc(checked['check_tight_rtol_verdict'])}</b>: "
                                                    "it is decided by the numerics."))
        items.append(f"On {checked['check_ulp_draws']} copies of the motion moved by one rounding unit: "
                     + ("<b>ill-conditioned</b>: the answer is not determined by the motion at double precision."
                        if checked["check_ill_conditioned"] else "the same verdict; the answer is well determined."))
    else:
        items.append("The numerical checks were not run (add <code>--check-tolerance</code>).")
    items.append("The verdict is proven." if response.settled or response.overturned else
                 f"<b>NOT PROVEN</b>: at {response.t_end_s:.1f} s (the horizon) the base could still lift the "
                 "body; lengthen --horizon to follow it.")
    items.append("This is one run of the motion as given: how much stronger (or weaker) the motion would have to "
                 "be to change the verdict is not computed here (<code>rockcli assess column</code> finds the "
                 "smallest scale factor of a record that topples the body).")
    sections = {
        "answer": "\n".join(first), "body": body_section([block], restitution=restitution, cap_ratio=cap_ratio),
        "configurations": configurations_section([conf]),
        "records": records_section([excitation]), "verdicts": table(None, [(esc(k), v) for k, v in result]),
        "figures": figure(png, caption.strip()), "certainty": _list(items),
        "assumptions": assumptions_section(margins=False), "reproduce": reproduce_section(command),
    }
    return page(_title([block]), "rockcli simulate: the rocking response of one body to one ground motion", sections,
                names={"verdicts": "The verdict"})


__all__ = ["assessment_report", "fragility_report", "simulate_report"]
