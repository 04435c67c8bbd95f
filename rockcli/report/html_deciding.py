"""The records that decide each verdict of an ``assess column`` report, and their figures.

* :func:`deciding_records`: for each configuration, every record that topples the body there (the most
  severe first), else the runs not proven, else the closest call;
* :func:`response_figures`: those records rerun with their history, each on every configuration side by
  side on common axes (:func:`rockcli.report.html_figures.responses_png`), under a heading that says
  which verdict the record decides.

The figures then agree with the answer: a configuration that topples the body is shown toppling it.
"""

from __future__ import annotations

import math

from rockcli.assess.verdicts import SURVIVES, TOPPLES, UNDECIDED, body_noun, configuration_words, outcome
from rockcli.report.html import esc, figure


#: At most this many records per configuration get a response figure (the most severe first: the smallest
#: toppling factor); the others that decide its verdict are named under the figures.
MAX_DECIDING = 4


def _severity(r):
    """Sort key of the rows that topple a body: smallest toppling factor first, then earliest fall."""
    s = r.overturn_scale
    return (s if math.isfinite(s) else math.inf, r.t_overturn_s if math.isfinite(r.t_overturn_s) else math.inf)


def _closeness(r):
    """Sort key of surviving rows: the closest call first (smallest toppling factor, then largest peak)."""
    s = r.overturn_scale
    return (s if math.isfinite(s) else math.inf, -r.theta_max_over_alpha)


def deciding_records(assessment, block) -> dict:
    """The records that decide the verdict of ``block`` on each configuration.

    Returns ``{configuration header: (why, rows)}``: ``why`` is :data:`TOPPLES` (``rows``: every record
    that topples it there, the most severe first), ``undecided`` (no record topples it, ``rows``: the
    runs not proven) or ``survives`` (``rows``: the closest call alone, the smallest toppling factor,
    else the largest peak tilt). Records that could not be run decide nothing.
    """
    out = {}
    ran = [x.label for x in assessment.excitations if x.motion is not None]
    for c in assessment.configurations:
        rows = [assessment.row(block.name, lab, c.header) for lab in ran]
        rows = [r for r in rows if not r.error]
        topples = sorted((r for r in rows if outcome(r) == TOPPLES), key=_severity)
        undecided = [r for r in rows if outcome(r) == UNDECIDED]
        survived = sorted((r for r in rows if outcome(r) == SURVIVES), key=_closeness)
        if topples:
            out[c.header] = (TOPPLES, topples)
        elif undecided:
            out[c.header] = (UNDECIDED, undecided)
        elif survived:
            out[c.header] = (SURVIVES, survived[:1])
    return out


def _why_words(why: str, c, noun: str) -> str:
    where = configuration_words(c)
    return {TOPPLES: f"topples {noun} {where}", UNDECIDED: f"leaves {noun} undecided {where}",
            SURVIVES: f"comes closest to toppling {noun} {where} (which it survives)"}[why]


def _caption(label: str, part) -> str:
    from rockcli.report.html_figures import QUIET_SHARE

    where = " and ".join(configuration_words(c) for c, _ in part)
    base = "; displacement of the isolated base" if any(c.isolated for c, _ in part) else ""
    fell = ("A red line marks the instant it topples." if any(r.overturned for _, r in part) else
            "It topples in none of these runs.")
    return (f"{label} {where}: ground acceleration; tilt over alpha (beyond the dashed lines at +-1 the body leans "
            f"past its tipping point){base}. {fell} The panels share their axes; they end when the motion has died "
            f"out (every curve under {100 * QUIET_SHARE:g} % of its peak).")


def response_figures(assessment, block) -> str:
    """For every configuration, the records that decide its verdict (:func:`deciding_records`: each
    toppling record, else the closest call), rerun with their history; each record on every configuration
    side by side, on common axes (:func:`rockcli.report.html_figures.responses_png`, at most three
    configurations a figure), under a heading that says which verdicts it decides."""
    from rockcli.report.figures import plot_grid_dt
    from rockcli.report.html_figures import responses_png
    from rockcli.solve import simulate

    confs = {c.header: c for c in assessment.configurations}
    noun = body_noun(block)
    reasons, left = {}, []
    for header, (why, rows) in deciding_records(assessment, block).items():
        for r in rows[:MAX_DECIDING]:
            reasons.setdefault(r.record, []).append(_why_words(why, confs[header], noun))
        if len(rows) > MAX_DECIDING:
            more = ", ".join(r.record for r in rows[MAX_DECIDING:])
            left.append(f"{_why_words(why, confs[header], noun)}: also {more} (the first {MAX_DECIDING} are drawn)")
    out = []
    for x in assessment.excitations:
        if x.label not in reasons:
            continue
        runs, notes = [], []
        for c in assessment.configurations:
            resp = simulate(block, c.foundation, x.motion, history=True, history_dt=plot_grid_dt(x.motion),
                            **assessment.solver)
            if resp.status < 0:
                notes.append(f"{configuration_words(c)}: the rerun failed ({resp.message})")
                continue
            if bool(resp.overturned) != bool(assessment.row(block.name, x.label, c.header).overturned):
                notes.append(f"{configuration_words(c)}: the rerun with its history gives another verdict than "
                             "the table (a knife-edge case)")
            runs.append((c, resp))
        figs = "".join(figure(responses_png(runs[k:k + 3], block, x.motion, x.label), _caption(x.label, runs[k:k + 3]))
                       for k in range(0, len(runs), 3))
        out.append(f"<h3>{esc(x.label)}: the record that {esc('; and that '.join(reasons[x.label]))}</h3>" + figs
                   + ("<p class='note'>" + esc("; ".join(notes)) + ".</p>" if notes else ""))
    if left:
        out.append("<p>" + esc("; ".join(left)) + ".</p>")
    if not out:
        return ""
    return (f"<p>For each configuration, the records that decide {esc(noun)}'s verdict: every record that topples "
            f"it (at most {MAX_DECIDING}, the most severe first), else the closest call; each on every "
            "configuration, side by side.</p>" + "".join(out))
