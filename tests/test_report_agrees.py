"""The HTML report agrees with its answer (issue 35): over suites of short synthetic pulse records where
isolation helps, hurts and is mixed,

* the response figures show, for every configuration, the records that decide its verdict (each record
  that topples the body there, else the closest call), each on every configuration, and nothing else;
* the instant the body topples is drawn (a red vertical line inside the axes on every panel of that run);
* the stroke on the first screen is that of the surviving runs only;
* "In short" compares the foundations over the whole suite and names the records;
* every figure is readable where it is embedded (no text under 8 pt, nothing outside the canvas).

The expected records are derived here from the CSV the same command writes, not from the report's code.
The pulses were chosen (block R = 0.6 m, alpha = 12 deg; linear bearings Tb = 2 s) so that each has a known
outcome on the ground / on the bearings: ``help*`` topple it on the ground only, ``hurt*`` on the bearings
only (long pulses near the bearings' period), ``calm`` on neither, ``both`` on both; the tests check those
outcomes from the CSV before relying on them.
"""

from __future__ import annotations

import math
import re
from html.parser import HTMLParser

import pytest
from click.testing import CliRunner
from conftest import write_pulse_record

from rockcli.cli import main
from rockcli.report.tables import read_assessment_csv

pytest.importorskip("matplotlib")

#: name: (a_p [g], T_p [s], shape) and the expected outcome (ground, bearings), True = topples.
PULSES = {"help1": ((0.7, 0.5, "ricker-sym"), (True, False)), "help2": ((0.5, 0.8, "ricker-anti"), (True, False)),
          "hurt1": ((0.25, 2.0, "ricker-sym"), (False, True)), "hurt2": ((-0.22, 2.0, "ricker-anti"), (False, True)),
          "calm": ((0.35, 0.5, "ricker-sym"), (False, False)), "both": ((0.5, 1.2, "ricker-sym"), (True, True))}
SUITES = {"helps": ("help1", "calm"), "hurts": ("hurt2", "both"), "mixed": ("help2", "hurt1")}
BODY = "statue:R=0.6,alpha=12"
ISO = "Tb=2s"


@pytest.fixture()
def drawn(monkeypatch):
    """The report's response figures as they are drawn: ``(record, {configuration: response}, figure)``, and
    every figure saved, with what :func:`readability_problems` finds in it (measured before it is saved)."""
    import rockcli.report.html_figures as hf
    from matplotlib.figure import Figure

    out = {"responses": [], "problems": [], "figures": []}
    save = Figure.savefig

    def savefig(self, *args, **kwargs):
        png = save(self, *args, **kwargs)
        out["problems"] += hf.readability_problems(self, drawn=True)  # the layout just saved
        out["figures"].append(self)
        return png

    original = hf.responses_png

    def responses_png(runs, block, excitation, label):
        n = len(out["figures"])
        png = original(runs, block, excitation, label)
        out["responses"].append((label, {c.header: r for c, r in runs}, out["figures"][n]))
        return png

    monkeypatch.setattr(Figure, "savefig", savefig)
    monkeypatch.setattr(hf, "responses_png", responses_png)
    return out


class _Text(HTMLParser):
    """The text of each section, the first screen's key facts, the ``<h3>`` headings of the figures."""

    def __init__(self):
        super().__init__()
        self.text, self.facts, self.heads = {}, [], []
        self._section = self._tag = None
        self._fact = None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "section":
            self._section = a["id"]
            self.text[self._section] = ""
        if tag == "div" and a.get("class") == "fact":
            self._fact = ""
        self._tag = tag
        if tag == "h3" and self._section == "figures":
            self.heads.append("")

    def handle_endtag(self, tag):
        if tag == "div" and self._fact is not None:
            self.facts.append(self._fact)
            self._fact = None
        self._tag = None

    def handle_data(self, data):
        if self._section:
            self.text[self._section] += data
        if self._fact is not None:
            self._fact += data + " "
        if self._tag == "h3" and self._section == "figures":
            self.heads[-1] += data


def _report(tmp_path, suite: str, monkeypatch, margin: bool = True):
    folder = tmp_path / suite
    folder.mkdir()
    for name in SUITES[suite]:
        (a, T, shape), _ = PULSES[name]
        write_pulse_record(folder / f"{name}.txt", a, T, shape, pad=2.0)
    if suite != "mixed":  # the bar charts are checked on the mixed suite; the responses on all three
        import rockcli.report.html_pages as hp

        for name in ("margins_png", "share_png", "stroke_png"):
            monkeypatch.setattr(hp, name, lambda *a, **k: None)
    html, csv = tmp_path / f"{suite}.html", tmp_path / f"{suite}.csv"
    res = CliRunner().invoke(main, ["assess", "column", BODY, "--records", str(folder), "--isolation", "none",
                                    "--isolation", "linear:Tb=2", "--csv", str(csv), "--report", str(html)]
                             + ([] if margin else ["--no-margin"]))
    assert res.exit_code == 0, res.output
    df = read_assessment_csv(csv)
    for row in df.itertuples():  # the pulses do what they were chosen for
        assert bool(row.overturned) == PULSES[row.record.removesuffix(".txt")][1][row.configuration != "none"]
    page = _Text()
    page.feed(html.read_text(encoding="utf-8"))
    return df, page, res.output


def _deciding(df) -> dict:
    """Per configuration, the records that decide its verdict: every record that topples the body there,
    else the closest call (the smallest toppling factor; without margins, the largest peak tilt)."""
    out = {}
    for conf, rows in df.groupby("configuration"):
        fell = rows[rows.overturned.astype(bool)]
        if len(fell):
            out[conf] = set(fell.record)
        else:
            margins = rows.overturn_scale.notna().any()
            key = rows.overturn_scale.fillna(math.inf) if margins else -rows.theta_max_over_alpha
            out[conf] = {rows.record[key.idxmin()]}
    return out


def _red_lines(fig, t: float) -> int:
    """How many panels of ``fig`` draw a red vertical line at ``t`` inside their time axis."""
    from matplotlib.colors import to_rgba

    from rockcli.report.response import TOPPLE_COLOUR

    n = 0
    for ax in fig.axes:
        lo, hi = ax.get_xlim()
        for line in ax.get_lines():
            x = line.get_xdata()
            if (len(x) == 2 and x[0] == x[1] == t and to_rgba(line.get_color()) == to_rgba(TOPPLE_COLOUR)
                    and lo < t < hi):
                n += 1
    return n


@pytest.mark.parametrize("suite, effect", [("helps", "saves the statue"), ("hurts", "makes it worse"),
                                           ("mixed", "helps under some records and hurts under others")])
def test_the_figures_show_the_deciding_records_and_the_toppling_instant(suite, effect, tmp_path, monkeypatch,
                                                                        drawn):
    df, page, printout = _report(tmp_path, suite, monkeypatch)
    deciding = _deciding(df)
    expected = set().union(*deciding.values())
    shown = [label for label, _, _ in drawn["responses"]]
    assert sorted(shown) == sorted(expected)  # each deciding record once, nothing else
    for label, runs, fig in drawn["responses"]:
        assert set(runs) == set(df.configuration)  # every configuration, side by side
        xlims = {ax.get_xlim() for ax in fig.axes if ax.get_lines()}
        assert len(xlims) == 1  # common time axes
        for conf, resp in runs.items():
            row = df[(df.record == label) & (df.configuration == conf)].iloc[0]
            assert bool(resp.overturned) == bool(row.overturned)
            if resp.overturned:  # the instant it topples, on the ground, tilt (and base) panels of that run
                assert _red_lines(fig, resp.t_overturn_s) >= 2
        # the heading says why the record is shown
        head = next(h for h in page.heads if h.startswith(label))
        for conf, records in deciding.items():
            if label in records:
                fell = df[(df.configuration == conf) & (df.record == label)].overturned.astype(bool).iloc[0]
                assert ("topples the statue" if fell else "comes closest to toppling the statue") in head
    assert drawn["problems"] == []

    # In short: the foundations compared over the whole suite, the records named
    for text in (page.text["answer"], re.sub(r"\s+", " ", printout)):
        short = text[text.index("In short:"):]
        assert effect in short
        fell = {c: set(df[(df.configuration == c) & df.overturned.astype(bool)].record) for c in ("none", ISO)}
        for name in fell[ISO] - fell["none"]:
            assert name in short  # the records under which isolation topples it
        if fell["none"] - fell[ISO] and fell[ISO]:
            assert all(name in short for name in fell["none"] - fell[ISO])  # and those under which it saves it
        n, kg, ki = len(df) // 2, len(fell["none"]), len(fell[ISO])  # both counts, over the whole suite
        if kg == ki:
            assert f"in all, {ki} of {n} records topple it either way" in short
        elif ki == 0:
            assert f"survives all {n} records on the bearings" in short and f"against {kg} of {n}" in short
        else:
            assert f"in all, {ki} of {n} records topple it on the bearings against {kg} of {n} on the ground" in short

    # the stroke on the first screen: the largest base displacement where the statue survives on the bearings
    iso = df[df.configuration == ISO]
    kept = iso[~iso.overturned.astype(bool)]
    fact = next(f for f in page.facts if "the bearings must allow" in f)
    if len(kept):
        assert f"{kept.base_disp_max_m.max():.2f} m" in fact
        if kept.base_disp_max_m.max() < iso.base_disp_max_m.max():
            assert f"{iso.base_disp_max_m.max():.2f} m" not in fact and "left out" in fact
    else:
        assert "survives no record" in fact


def _assessment(rows_by_conf: dict):
    """A stand-in for :class:`rockcli.assess.Assessment` with the rows given per configuration header."""
    from types import SimpleNamespace

    from rockcli.assess.scenes import parse_configurations

    confs = parse_configurations(["none", "linear:Tb=2"])
    labels = [r.record for r in next(iter(rows_by_conf.values()))]
    rows = {(r.record, h): r for h, rs in rows_by_conf.items() for r in rs}
    excitations = [SimpleNamespace(label=lab, motion=object()) for lab in labels]
    return SimpleNamespace(configurations=confs, excitations=excitations,
                           row=lambda column, record, header: rows[(record, header)])


def _row(record, fell=False, scale=math.nan, peak=0.0, proven=True, error=""):
    from types import SimpleNamespace

    return SimpleNamespace(record=record, overturned=fell, overturn_scale=scale, theta_max_over_alpha=peak,
                           t_overturn_s=1.0 if fell else math.nan, proven=proven, error=error, verdict="rocked")


def test_deciding_records_rules():
    """Every toppling record (smallest factor first); else the undecided runs; else the closest call: the
    smallest toppling factor, or without margins the largest peak; a failed run decides nothing."""
    from rockcli.report.html_deciding import deciding_records

    a = _assessment({"none": [_row("a", True, 0.8), _row("b", scale=1.3, peak=0.5), _row("c", True, 0.4),
                              _row("d", error="unreadable")],
                     "Tb=2s": [_row("a", scale=1.9, peak=0.1), _row("b", scale=1.2, peak=0.05),
                               _row("c", scale=2.5, peak=0.6), _row("d", error="unreadable")]})
    got = deciding_records(a, SimpleBlock)
    assert got["none"][0] == "topples" and [r.record for r in got["none"][1]] == ["c", "a"]
    assert got["Tb=2s"][0] == "survives" and [r.record for r in got["Tb=2s"][1]] == ["b"]  # smallest factor
    no_margin = _assessment({"none": [_row("a", peak=0.2), _row("b", peak=0.7)],
                             "Tb=2s": [_row("a", peak=0.3, proven=False), _row("b", peak=0.1)]})
    got = deciding_records(no_margin, SimpleBlock)
    assert [r.record for r in got["none"][1]] == ["b"]  # the largest peak
    assert got["Tb=2s"][0] == "undecided" and [r.record for r in got["Tb=2s"][1]] == ["a"]


class SimpleBlock:
    name = "statue"


@pytest.mark.parametrize("drawn_first", [False, True])
def test_the_readability_check_can_fail(drawn_first):
    import io

    from rockcli.report.figures import new_figure
    from rockcli.report.html_figures import readability_problems

    fig = new_figure(4, 3)
    ax = fig.add_subplot()
    ax.plot([0, 1])
    ax.set_xlabel("time [s]", fontsize=6)  # too small
    fig.text(0.9, 0.5, "a long note that runs off the right edge of the canvas", fontsize=9)
    if drawn_first:
        fig.savefig(io.BytesIO(), format="png")
    got = readability_problems(fig, drawn=drawn_first)
    assert any("'time [s]': 6 pt" in p for p in got)
    assert any("runs off the right edge" in p and "outside the figure" in p for p in got)
    fig = new_figure(4, 3)
    fig.add_subplot().plot([0, 1])
    assert readability_problems(fig) == []
