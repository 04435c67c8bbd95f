"""A body on a free plinth in the report and in words (issue 36, items 3-4).

* the words say each block truthfully: nothing lifts, only the body rocks, only the plinth rocks, both rock, one
  topples (never "rocks to 0 % of its overturning angle" for a block that never lifted);
* the HTML report of ``assess column --on`` draws the stack's time history for the records that decide its
  verdicts, and each figure's run is the table's run (the same verdict, the same block toppled, the same peaks and
  instant of toppling, exactly), beside the body alone as the table has it; the figures are readable where
  embedded.
"""

from __future__ import annotations

import math
from types import SimpleNamespace as NS

import pytest
from click.testing import CliRunner
from conftest import write_pulse_record

from rockcli.assess.plinth_words import peak_words, plinth_summary, run_sentence
from rockcli.assess.verdicts import configuration_sentence, scene_sentence
from rockcli.models import Block, Plinth, Stack, parse_isolation_spec

STATUE = Block.from_dimensions(1.79, 0.5, "statue")
STACK = Stack(STATUE, Plinth(1.0, 0.6))


def _res(body: float, plinth: float, toppled=None, t=math.nan, settled=True):
    """A stack response with the body's peak ``body`` [alpha1] and the plinth's ``plinth`` [alpha_asm]."""
    a1, aa = STATUE.alpha, STACK.alpha_asm
    return NS(toppled=toppled, t_overturn_s=t, settled=settled, alpha_asm=aa, base_disp_max=math.nan,
              body=NS(theta_max=body * a1, theta_max_over_alpha=body, t_uplift_s=1.0 if body > 0 else math.nan),
              plinth=NS(theta_max=plinth * aa, t_uplift_s=1.5 if plinth > 0 else math.nan))


def test_the_words_of_one_run_say_each_block_truthfully():
    nothing = run_sentence(STACK, _res(0.0, 0.0))
    assert nothing == ("Nothing lifts: the statue stays put on its plinth and the plinth does not rock: both move "
                       "with the ground.")
    survive = "The statue and its plinth survive: "
    body = run_sentence(STACK, _res(0.4, 0.0))
    assert body == survive + "the plinth does not rock; the statue rocks on it to 40 % of its overturning angle."
    plinth = run_sentence(STACK, _res(0.0, 0.3))
    assert plinth == survive + ("the statue stays put on its plinth, which rocks with it to 30 % of the overturning "
                                "angle of the two as one block.")
    both = run_sentence(STACK, _res(0.4, 0.3))
    assert both == survive + ("the statue rocks on its plinth to 40 % of its overturning angle, and the plinth to "
                              "30 % of the overturning angle of the two as one block.")
    assert "under 1 %" in run_sentence(STACK, _res(0.001, 0.0))  # a lift that rounds to 0 % is still a lift
    assert run_sentence(STACK, _res(5.8, 0.2, "body", 3.456)) == "The statue topples off its plinth at 3.46 s."
    assert run_sentence(STACK, _res(0.3, 7.1, "plinth", 2.5)) == "The plinth topples at 2.50 s, and the statue with it."
    assert run_sentence(STACK, _res(0.4, 0.0, settled=False)).startswith("Not proven (still moving at the horizon): "
                                                                         "Neither the statue nor its plinth has "
                                                                         "toppled: the plinth does not")
    for text in (nothing, body, plinth):
        assert " 0 %" not in text


def _row(record="r0", body=0.0, plinth=0.0, toppled="", scale=math.nan, verdict=None):
    over = bool(toppled)
    verdict = verdict or ("overturned" if over else "rocked" if body > 0 or plinth > 0 else "no_uplift")
    return NS(record=record, error="", overturned=over, proven=True, verdict=verdict, theta_max_over_alpha=body,
              plinth_theta_max_over_alpha_asm=plinth, toppled=toppled, plinth="plinth:height=1,width=0.6",
              overturn_scale=scale, margin_note="", overturn_share_pm10=math.nan, base_disp_max_m=0.0,
              t_overturn_s=2.0 if over else math.nan)


def test_the_rows_of_a_body_on_a_plinth_in_words():
    assert scene_sentence(_row()) == ("survives: nothing lifts: the body stays put on its plinth and the plinth does "
                                      "not rock")
    assert scene_sentence(_row(body=0.25)) == ("survives: the plinth does not rock; the body rocks on it to 25 % of "
                                               "its overturning angle")
    assert scene_sentence(_row(plinth=0.1)).startswith("survives: the body stays put on its plinth, which rocks")
    assert "the body rocks on its plinth to 25 %" in scene_sentence(_row(body=0.25, plinth=0.1))
    assert "the body topples off its plinth" in scene_sentence(_row(body=5.8, toppled="body"))
    assert "the plinth topples, and the body with it" in scene_sentence(_row(toppled="plinth"))
    several = configuration_sentence([_row("a", 0.25, 0.0), _row("b", 0.1, 0.3)])
    assert ("the body rocks on its plinth to at most 25 % of its overturning angle (a), and the plinth to at most "
            "30 % of the overturning angle of the two as one block (b)") in several
    assert "nothing lifts" in configuration_sentence([_row("a"), _row("b")])
    assert peak_words(0.0, 0.0, body="the statue") == ("nothing lifts: the statue stays put on its plinth and the "
                                                       "plinth does not rock")


def _summary(alone_rows, stack_rows):
    conf = NS(header="none", foundation=parse_isolation_spec("none"), isolated=False)
    xs = [NS(label=r.record, motion=object()) for r in alone_rows]
    table = {(STATUE.name, r.record): r for r in alone_rows} | {(STACK.name, r.record): r for r in stack_rows}
    a = NS(columns=[STATUE, STACK], excitations=xs, configurations=[conf], row=lambda c, x, h: table[(c, x)])
    return plinth_summary(a, STACK)


def _alone(record, peak, **kw):
    r = _row(record, body=peak, **kw)
    r.plinth, r.plinth_theta_max_over_alpha_asm = "", math.nan
    return r


def test_does_the_plinth_help_says_when_nothing_lifts():
    still = _summary([_alone("a", 0.0, scale=2.0)], [_row("a", scale=1.8)])
    assert "0 %" not in still
    assert ("where it survives both ways, alone it does not lift off its base; on its plinth, nothing lifts: the "
            "statue stays put on its plinth and the plinth does not rock") in still
    mixed = _summary([_alone("a", 0.5, scale=2.0)], [_row("a", plinth=0.2, scale=1.8)])
    assert ("alone it rocks to at most 50 % of its overturning angle; the statue stays put on its plinth, which "
            "rocks with it to at most 20 % of the overturning angle of the two as one block") in mixed
    # a save on a 'safe island' only (a weaker record topples it on the plinth too) is no help: said so first
    island = _summary([_alone("a", 5.8, toppled="body", scale=0.7)], [_row("a", 1.03, 0.4, scale=0.6)])
    assert "makes it better" not in island
    assert "its plinth saves it only by the luck of the timing: the statue survives on it under a, which topples" \
        in island and "the record topples it alone, not on its plinth" in island
    # one save with a margin and one on an island: better, the island said apart
    both = _summary([_alone("a", 5.8, toppled="body", scale=0.7), _alone("b", 5.8, toppled="body", scale=0.8)],
                    [_row("a", 1.03, 0.4, scale=0.6), _row("b", 0.5, 0.3, scale=1.3)])
    assert "its plinth makes it better: the statue survives on it under a and b, which topple it" in both
    assert "(but only by the luck of the timing: under a it survives on its plinth on a 'safe island'" in both
    assert "0 of 2 records topple it on its plinth against 2 of 2 alone" in both
    # helps under one record and hurts under another: each record's verb agrees with it, 'standing alone' as above
    mixed = _summary([_alone("a", 5.8, toppled="body", scale=0.7), _alone("b", 0.5, scale=1.3)],
                     [_row("a", 0.5, 0.3, scale=1.3), _row("b", 5.8, toppled="body", scale=0.8)])
    assert ("its plinth helps under some records and hurts under others: the statue survives on it under a (which "
            "topples it standing alone) but topples on it under b (which it survives standing alone)") in mixed


# --------------------------------------------------------------------------------------------------
# the report's figures: the table's runs
# --------------------------------------------------------------------------------------------------

#: Short pulse records (statue 1.79 x 0.5 m on a plinth 1.0 x 0.6 m; restitution E = 0.9 at every impact, which
#: the reruns must honour: with the default impact law ``rock`` does not topple the stack on the ground): on the
#: ground ``fall`` topples the plinth and ``rock`` the statue off it; on linear bearings Tb = 2 s ``fall`` topples
#: the statue off its plinth.
RECORDS = {"fall": (0.6, 1.0), "rock": (0.8, 0.6)}
EXPECTED = {("fall.txt", "none"): "plinth", ("rock.txt", "none"): "body", ("fall.txt", "Tb=2s"): "body"}


def test_the_report_draws_the_stack_s_runs_of_the_table(tmp_path, monkeypatch):
    pytest.importorskip("matplotlib")
    from matplotlib.figure import Figure

    import rockcli.report.html_pages as hp
    import rockcli.report.stack as rs
    from rockcli.cli import main
    from rockcli.report.html_figures import readability_problems

    for name in RECORDS:
        write_pulse_record(tmp_path / f"{name}.txt", *RECORDS[name], "ricker-sym", pad=2.0)
    for name in ("margins_png", "share_png", "stroke_png"):  # the bar charts are checked elsewhere
        monkeypatch.setattr(hp, name, lambda *a, **k: None)
    monkeypatch.setattr(hp, "response_figures", lambda *a, **k: "")  # the body alone's: test_report_agrees
    got = {"drawn": [], "figures": []}
    save, plot, report = Figure.savefig, rs.plot_stack_response, hp.assessment_report

    def savefig(self, *args, **kwargs):
        out = save(self, *args, **kwargs)
        got["figures"].append((self, readability_problems(self, drawn=True)))  # the layout just saved
        return out

    def plot_stack_response(run, stack, path, **kw):
        out = plot(run, stack, path, **kw)
        got["drawn"].append((run, kw, got["figures"][-1]))
        return out

    def assessment_report(assessment, **kw):
        got["assessment"] = assessment
        return report(assessment, **kw)

    monkeypatch.setattr(Figure, "savefig", savefig)
    monkeypatch.setattr(rs, "plot_stack_response", plot_stack_response)
    monkeypatch.setattr(hp, "assessment_report", assessment_report)
    html = tmp_path / "r.html"
    res = CliRunner().invoke(main, ["assess", "column", "statue:height=1.79,width=0.5", "--on",
                                    "plinth:height=1.0,width=0.6", "--records", str(tmp_path), "--isolation", "none",
                                    "--isolation", "linear:Tb=2", "--restitution", "0.9",
                                    "--no-margin", "--report", str(html)])
    assert res.exit_code == 0, res.output
    a = got["assessment"]
    stack = next(b for b in a.columns if getattr(b, "plinth", None) is not None)
    rows = [r for r in a.rows if r.column == stack.name]
    # the records that decide each configuration's verdict, from the table: every toppling one, else the largest peak
    expected = set()
    for c in a.configurations:
        mine = [r for r in rows if r.configuration == c.header]
        fell = [r for r in mine if r.overturned]
        expected |= {(r.record, c.header) for r in fell} if fell else {
            (max(mine, key=lambda r: r.theta_max_over_alpha).record, c.header)}
    drawn = {}
    for run, kw, (fig, problems) in got["drawn"]:
        header = next(c.header for c in a.configurations if c.foundation is kw["foundation"])
        drawn[(kw["motion"], header)] = run
        row = a.row(stack.name, kw["motion"], header)
        # the figure's run is the table's run
        assert (run.verdict, run.toppled or "") == (row.verdict, row.toppled)
        assert run.body.theta_max_over_alpha == row.theta_max_over_alpha
        assert run.plinth.theta_max / run.alpha_asm == row.plinth_theta_max_over_alpha_asm
        assert run.t_overturn_s == row.t_overturn_s or (math.isnan(run.t_overturn_s) and math.isnan(row.t_overturn_s))
        alone, alone_row = kw["alone"], a.row(stack.body.name, kw["motion"], header)
        assert alone.verdict == alone_row.verdict
        assert alone.theta_max_over_alpha == pytest.approx(alone_row.theta_max_over_alpha, rel=1e-6)
        # and says what the table says
        assert run_sentence(stack, run) in fig._suptitle.get_text().replace("\n", " ")
        if row.overturned:
            assert f"topples at {row.t_overturn_s:.2f} s" in " ".join(t.get_text() for ax in fig.axes
                                                                     for t in ax.texts)
        assert problems == []
    assert set(drawn) == expected
    assert {k: r.toppled for k, r in drawn.items()} == EXPECTED  # each block toppling, E = 0.9 honoured
    page = html.read_text(encoding="utf-8")
    assert page.count("the record that") == len(expected)  # one heading a figure (the body alone's left out)
    assert "body stays put,<br>plinth does not rock" in page  # rock.txt on the bearings: the peak cell, each block


def test_simulate_on_writes_a_report_that_says_what_the_printout_says(tmp_path):
    """``simulate --on --report``: the sentence and the numbers of ``--json``, the body alone beside it, the figure."""
    import html as html_lib
    import json

    pytest.importorskip("matplotlib")
    from rockcli.cli import main

    report = tmp_path / "one.html"
    res = CliRunner().invoke(main, ["simulate", "--body", "statue:height=1.79,width=0.5", "--pulse",
                                    "ricker-sym:ap=0.6,Tp=1", "--on", "plinth:height=1.0,width=0.6", "--json",
                                    "--report", str(report)])
    assert res.exit_code == 0, res.output
    d = json.loads(res.output)
    page = html_lib.unescape(report.read_text(encoding="utf-8"))
    assert d["toppled"] == "plinth"  # the pulse topples the plinth, and the statue alone survives it
    assert d["plain_words"].rstrip(".") in page and "(the plinth topples, the statue with it)" in page
    assert f"{d['t_overturn_s']:.3f} s" in page and "The statue alone, standing on the ground" in page
    assert page.count("<img") == 1 and "A red line marks the instant a block topples" in page


def test_a_cell_says_a_lift_under_1_percent_and_no_lift_readably():
    """The table's cell of a survivor: a peak that rounds to 0.00 is '<0.01' (it lifts, a hair), a block that never
    lifts '0' (the body on a plinth that rocks), never 'survives 0.00 p0.00 x1.20'; the legend says what they mean
    when a cell shows them; the words never say 'at most under 1 %'."""
    from rockcli.report.tables import format_cell

    def row(r, p=math.nan, plinth="", s=1.2):
        return NS(error="", overturned=False, proven=True, verdict="rocked", theta_max_over_alpha=r,
                  plinth=plinth, plinth_theta_max_over_alpha_asm=p, overturn_scale=s, margin_note="",
                  azimuths_run=0, overturn_share_pm10=math.nan, toppled="")

    on = "plinth:height=1,width=0.6"
    assert format_cell(row(1e-6, 5.7e-5, on), True) == "survives <0.01 p<0.01 x1.20"
    assert format_cell(row(0.0, 0.37, on, 1.12), True) == "survives 0 p0.37 x1.12"
    assert format_cell(row(0.000577, s=1.24), True) == "survives <0.01 x1.24"
    assert format_cell(row(0.393, 0.005, on), True) == "survives 0.39 p0.01 x1.20"
    words = peak_words(0.002, 0.004, most=True)
    assert "at most under" not in words and "under 1 % of its overturning angle" in words
    assert "at most 39 %" in peak_words(0.39, 0.004, most=True)
