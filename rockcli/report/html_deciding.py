"""The records that decide each verdict of an ``assess column`` report, and their figures.

* :func:`deciding_records`: for each configuration, every record that topples the body there (the most
  severe first), else the runs not proven, else the closest call;
* :func:`response_runs`, :func:`response_figures`: those records rerun with their history, each on every
  configuration side by side on common axes (:func:`rockcli.report.html_figures.responses_png`), under a
  heading that says which verdict the record decides. Each configuration is rerun on the motion its row ran
  (``Assessment.excitation_of``): a pair of ``--azimuth worst`` in the orientation its row gives, named in
  the heading (configurations whose orientations differ get a figure each).

* :func:`stack_runs`, :func:`stack_figures`: the same for a body on a plinth (``--on``): each record that
  decides its verdict on a configuration, rerun there with its history beside the body alone on the same
  foundation, drawn by :func:`rockcli.report.stack.plot_stack_response` (the figure of ``simulate --on --plot``).

The figures then agree with the answer: a configuration that topples the body is shown toppling it, at the
instant the table says (the same run; a rerun that differs from its row is said under its figure).
"""

from __future__ import annotations

import math

from rockcli.report.html import esc, figure
from rockcli.report.words import SURVIVES, TOPPLES, UNDECIDED, body_noun, configuration_words, outcome


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


def orientation_words(n: int, items) -> str:
    """Why a pair's projection was run, for the rows ``items`` (``(where, row)``, ``where`` in words) that ran it:
    ``the most adverse of its 36 orientations standing on the ground``, or for a row none of whose orientations
    is more adverse than another (``azimuth_deg`` NaN: the first one is its run) ``any of ...``."""
    def where(rows) -> str:
        return " and ".join(w for w, _ in rows)

    adverse = [(w, r) for w, r in items if math.isfinite(r.azimuth_deg)]
    tied = [(w, r) for w, r in items if not math.isfinite(r.azimuth_deg)]
    return "; ".join(([f"the most adverse of its {n} orientations {where(adverse)}"] if adverse else [])
                     + ([f"any of its {n} orientations {where(tied)} (none is more adverse than another)"]
                        if tied else []))


def _where_oriented(x, ran, items) -> str:
    """How a pair of ``azimuth="worst"`` is drawn for the rows ``items`` (``(configuration, row)``): projected
    onto the azimuth of those rows (``ran``, the projection they ran) and why; "" for any other record."""
    if not getattr(x, "azimuths", ()):
        return ""
    words = orientation_words(len(x.azimuths), [(configuration_words(c), r) for c, r in items])
    return f"projected onto {ran.azimuth_deg:g} deg, {words}"


def response_runs(assessment, block) -> list:
    """The runs the response figures of ``block`` draw: for every record that decides a verdict
    (:func:`deciding_records`), each configuration's row rerun with its history on the motion that row ran
    (``assessment.excitation_of(row)``: a pair of ``azimuth="worst"`` in the orientation the row gives, which
    may differ between configurations), with the assessment's solver options, so that each run is the table's
    run. ``[(excitation, ran, items, runs, reasons, notes)]``: ``ran`` the excitation the runs share (the record,
    or one orientation of a pair: its configurations side by side), ``items`` their ``(configuration, row)``,
    ``runs`` their ``(configuration, row, response)`` (a rerun that failed left out), ``reasons`` the verdicts
    it decides there, ``notes`` a rerun that failed or disagrees with its row (it should not)."""
    from rockcli.report.figures import plot_grid_dt
    from rockcli.solve import simulate

    confs = {c.header: c for c in assessment.configurations}
    noun = body_noun(block)
    reasons = {}
    for header, (why, rows) in deciding_records(assessment, block).items():
        for r in rows[:MAX_DECIDING]:
            reasons.setdefault(r.record, {})[header] = _why_words(why, confs[header], noun)
    out = []
    for x in assessment.excitations:
        if x.label not in reasons:
            continue
        parts = {}  # the configurations of one motion run, in their order
        for c in assessment.configurations:
            row = assessment.row(block.name, x.label, c.header)
            ran = assessment.excitation_of(row)
            parts.setdefault(ran.label, (ran, []))[1].append((c, row))
        for ran, items in parts.values():
            runs, notes = [], []
            for c, row in items:
                resp = simulate(block, c.foundation, ran.motion, history=True, history_dt=plot_grid_dt(ran.motion),
                                **assessment.solver)
                if resp.status < 0:
                    notes.append(f"{configuration_words(c)}: the rerun failed ({resp.message})")
                    continue
                notes += _disagrees(c, row, resp)
                runs.append((c, row, resp))
            out.append((x, ran, items, runs,
                        [reasons[x.label][c.header] for c, _ in items if c.header in reasons[x.label]], notes))
    return out


def _disagrees(c, row, resp) -> list:
    """A note when a figure's rerun is not the table's run: another verdict (a knife-edge case), or another
    toppling time."""
    if bool(resp.overturned) != bool(row.overturned):
        return [f"{configuration_words(c)}: the rerun with its history gives another verdict than the table (a "
                "knife-edge case)"]
    t, t_row = resp.t_overturn_s, row.t_overturn_s
    if resp.overturned and math.isfinite(t_row) and not abs(t - t_row) <= 1e-9 * max(1.0, abs(t_row)):
        return [f"{configuration_words(c)}: the rerun with its history topples at {t:.3f} s, the table's run at "
                f"{t_row:.3f} s"]
    return []


def response_figures(assessment, block) -> str:
    """For every configuration, the records that decide its verdict (:func:`deciding_records`: each
    toppling record, else the closest call), rerun with their history (:func:`response_runs`); each record on
    every configuration side by side, on common axes (:func:`rockcli.report.html_figures.responses_png`, at most
    three configurations a figure), under a heading that says which verdicts it decides; a pair of
    ``azimuth="worst"`` once per orientation its rows give, the heading naming the azimuth."""
    from rockcli.report.html_figures import responses_png

    noun = body_noun(block)
    left = []
    for header, (why, rows) in deciding_records(assessment, block).items():
        if len(rows) > MAX_DECIDING:
            c = next(c for c in assessment.configurations if c.header == header)
            more = ", ".join(r.record for r in rows[MAX_DECIDING:])
            left.append(f"{_why_words(why, c, noun)}: also {more} (the first {MAX_DECIDING} are drawn)")
    out, oriented = [], False
    for x, ran, items, runs, why, notes in response_runs(assessment, block):
        pairs = [(c, r) for c, _, r in runs]
        figs = "".join(figure(responses_png(pairs[k:k + 3], block, ran.motion, ran.label),
                              _caption(ran.label, pairs[k:k + 3])) for k in range(0, len(pairs), 3))
        where = _where_oriented(x, ran, items)
        oriented = oriented or bool(where)
        head = f"{x.label}, {where}" if where else x.label
        out.append(f"<h3>{esc(head)}" + (f": the record that {esc('; and that '.join(why))}" if why else "")
                   + "</h3>" + figs + ("<p class='note'>" + esc("; ".join(notes)) + ".</p>" if notes else ""))
    if left:
        out.append("<p>" + esc("; ".join(left)) + ".</p>")
    if not out:
        return ""
    return (f"<p>For each configuration, the records that decide {esc(noun)}'s verdict: every record that topples "
            f"it (at most {MAX_DECIDING}, the most severe first), else the closest call; each on every "
            "configuration, side by side."
            + (" A pair of horizontal components run in every orientation is drawn, on each configuration, in the "
               "orientation its row gives (the most adverse there), the configurations of one orientation side by "
               "side; each heading names the azimuth (of the normal to the rocking axis, clockwise from north)."
               if oriented else "") + "</p>" + "".join(out))


#: The solver options a stack run takes (as :func:`rockcli.solve.stack_many.mixed` passes them on).
_STACK_OPTIONS = ("rtol", "tail", "rest_tol", "horizon", "max_steps", "restitution")


def stack_runs(assessment, stack) -> list:
    """The records that decide the verdicts of ``stack`` (a body on its plinth, :func:`deciding_records`), each
    rerun on the configuration it decides with its history, and the body alone there:
    ``[(excitation, configuration, why, run, alone, row)]`` (``excitation`` the one the row ran,
    ``assessment.excitation_of(row)``: a pair of ``azimuth="worst"`` in the row's orientation; ``run`` a
    :class:`rockcli.solve.StackResponse`, ``alone`` a :class:`rockcli.solve.Response`, None when the rerun failed),
    with the assessment's solver options, so that each run is the table's run (the stack driver takes the same
    steps with and without history)."""
    from rockcli.report.figures import plot_grid_dt
    from rockcli.solve import simulate
    from rockcli.solve.stack_many import run_stack

    options = {k: v for k, v in assessment.solver.items() if k in _STACK_OPTIONS and v is not None}
    confs = {c.header: c for c in assessment.configurations}
    out = []
    for header, (why, rows) in deciding_records(assessment, stack).items():
        c = confs[header]
        for r in rows[:MAX_DECIDING]:
            x = assessment.excitation_of(r)
            run = run_stack(stack, c.foundation, x.motion, history=True, **options)
            alone = simulate(stack.body, c.foundation, x.motion, history=True, history_dt=plot_grid_dt(x.motion),
                             **assessment.solver)
            out.append((x, c, why, run if run.status >= 0 else None, alone if alone.status >= 0 else None, r))
    return out


def _stack_caption(x, c, stack, run, alone) -> str:
    from rockcli.report.plinth_words import plinth_name

    name = plinth_name(stack)
    noun = body_noun(stack.body)
    return (f"{x.label} {configuration_words(c)}: ground acceleration; {noun}'s tilt on its {name} over its own "
            f"alpha (blue) beside {noun} alone on the same foundation (grey, dashed); the {name}'s tilt over "
            f"alpha_asm = {math.degrees(stack.alpha_asm):.3g}°, the slenderness of {name} and {noun[4:]} as one block "
            f"(the tilt at which the {name} tips over while {noun} rests on it)"
            + ("; the displacement of the isolated base" if c.isolated else "")
            + ". Beyond the dotted lines at +-1 a block leans past its tipping point (it falls unless the ground "
            "pushes it back). " + ("A red line marks the instant a block topples. " if run.toppled else "")
            + ("A grey line the instant the body alone topples. " if alone is not None and alone.overturned else "")
            + "The panels end when the motion has died out.")


def stack_figures(assessment, stack) -> str:
    """The time histories of a body on its plinth (:func:`stack_runs`) under headings that say which verdict each
    record decides; a note where a rerun disagrees with the table (it should not: the same run)."""
    from rockcli.report.html_figures import DPI, png_of
    from rockcli.report.stack import plot_stack_response

    noun = body_noun(stack)
    out = []
    for x, c, why, run, alone, row in stack_runs(assessment, stack):
        head = f"<h3>{esc(x.label)}: the record that {esc(_why_words(why, c, noun))}</h3>"
        if run is None:
            out.append(head + "<p class='note'>The rerun with its history failed: no figure.</p>")
            continue
        note = ("" if (run.toppled or "") == row.toppled and run.verdict == row.verdict else
                "<p class='note'>The rerun with its history gives another verdict than the table (please report "
                "the command line).</p>")
        png = png_of(lambda path: plot_stack_response(run, stack, path, excitation=x.motion, motion=x.label,
                                                      alone=alone, foundation=c.foundation, dpi=DPI))
        out.append(head + figure(png, _stack_caption(x, c, stack, run, alone)) + note)
    if not out:
        return ""
    return (f"<p>For each configuration, the records that decide the verdict of {esc(noun)}: every record that "
            f"topples it (at most {MAX_DECIDING}, the most severe first), else the closest call; each drawn on that "
            "configuration, the body on its plinth beside the body alone.</p>" + "".join(out))
