"""``--azimuth worst`` everywhere an answer is read (issue 44, items 1 and 2): the HTML report draws, for each
configuration, the orientation its row gives, with the row's verdict and toppling time; its ground-motion table
fingerprints both files of the pair and describes the projections run (not the 0 deg one); the verdict table's
cells can wrap; and from Python ``resolve_excitations([pair], azimuth="worst")`` + ``run_assessment`` gives the
CLI's rows, never the 0 deg projection in silence.

The pair is synthetic and short: a 0.7 g, 0.5 s Ricker pulse along azimuth 60 deg (it topples the statue on the
ground; its projection onto 0 deg, half as strong, does not) and then a 0.25 g, 2 s one along 150 deg (near the
bearings' period: it topples the statue on them), recorded by sensors at 0 and 90 deg. The test checks those
outcomes against ``simulate`` before relying on them.
"""

from __future__ import annotations

import hashlib
import json
import math
import re
from html.parser import HTMLParser

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.io.units import G

BODY = "statue:R=0.6,alpha=12"
ISOLATION = ["none", "linear:Tb=2"]
STEP = 30.0  # 6 orientations: 0, 30, ..., 150 deg


def _write(path, acc_g, dt=0.01):
    path.write_text(f"# dt={dt} sec\n# units: g\n" + "\n".join(f"{v:.10e}" for v in acc_g) + "\n")
    return path


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    """``FILE@0+FILE@90`` of the two-pulse pair of the module notes, and the two paths."""
    from rockcli.pulses import make_pulse

    folder = tmp_path_factory.mktemp("pair")
    t = np.arange(0.0, 14.0, 0.01)
    short = make_pulse("ricker-sym", 0.7 * G, 0.5).acceleration(t - 1.0) / G
    long = make_pulse("ricker-sym", 0.25 * G, 2.0).acceleration(t - 5.0) / G
    north = short * math.cos(math.radians(60)) + long * math.cos(math.radians(150))
    east = short * math.sin(math.radians(60)) + long * math.sin(math.radians(150))
    n, e = _write(folder / "north.txt", north), _write(folder / "east.txt", east)
    return f"{n}@0+{e}@90", (n, e)


def _cli(args) -> dict:
    res = CliRunner().invoke(main, ["assess", "column", BODY, *sum((["--isolation", i] for i in ISOLATION), []),
                                    *args, "--json"])
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


class _Page(HTMLParser):
    """Each section's text; the figures' ``<h3>`` headings; the cells of the tables of each section (with
    their class and inner HTML)."""

    def __init__(self, html: str):
        super().__init__()
        self.text, self.heads, self.cells = {}, [], {}
        self._section = self._h3 = self._cell = None
        self.html = html
        self.feed(html)

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if self._section and tag != "wbr":
            self.text[self._section] += " "  # a <br> or a new cell parts words (a <wbr> only may)
        if tag == "section":
            self._section = a["id"]
            self.text[self._section] = ""
            self.cells[self._section] = []
        if tag == "h3" and self._section == "figures":
            self.heads.append("")
            self._h3 = True
        if tag == "tr" and self._section:
            self.cells[self._section].append([])
        if tag == "td":
            self._cell = [a.get("class", ""), ""]
            self.cells[self._section][-1].append(self._cell)
        elif self._cell is not None:
            self._cell[1] += self.get_starttag_text()

    def handle_endtag(self, tag):
        if tag == "h3":
            self._h3 = None
        if tag == "td":
            self._cell = None
        elif self._cell is not None:
            self._cell[1] += f"</{tag}>"

    def handle_data(self, data):
        if self._section:
            self.text[self._section] += data
        if self._h3:
            self.heads[-1] += data
        if self._cell is not None:
            self._cell[1] += data


@pytest.fixture(scope="module")
def report(pair, tmp_path_factory):
    """The CLI's rows (``--json``), the page, and the runs its response figures drew: ``(label, excitation,
    {configuration: response})`` per figure."""
    import rockcli.report.html_figures as hf

    drawn = []
    original = hf.responses_png

    def responses_png(runs, block, excitation, label):
        drawn.append((label, excitation, {c.header: r for c, r in runs}))
        return original(runs, block, excitation, label)

    mp = pytest.MonkeyPatch()
    mp.setattr(hf, "responses_png", responses_png)
    html = tmp_path_factory.mktemp("report") / "w.html"
    try:
        out = _cli(["--records", pair[0], "--azimuth", "worst", "--azimuth-step", f"{STEP:g}", "--report", str(html)])
    finally:
        mp.undo()
    return out["rows"], _Page(html.read_text(encoding="utf-8")), drawn


def test_the_pair_does_what_it_was_chosen_for(pair, report):
    """On the ground the most adverse orientation topples the statue where 0 deg does not (so a figure of the
    0 deg projection would contradict the table); on the bearings both topple it, at different times."""
    from rockcli.models import Block, LinearIsolation, Rigid
    from rockcli.records.orientation import project, read_pair
    from rockcli.solve import simulate

    rows = {r["configuration"]: r for r in report[0]}
    assert rows["none"]["azimuth_deg"] == 60.0 and rows["Tb=2s"]["azimuth_deg"] == 150.0
    assert rows["none"]["overturned"] and rows["Tb=2s"]["overturned"]
    block, both = Block(0.6, math.radians(12)), read_pair(*pair[0].split("+"))
    zero = project(*both, 0.0)
    assert simulate(block, Rigid(), zero).verdict == "rocked"
    on_bearings = simulate(block, LinearIsolation(2.0, 0.1, 0.01), zero)
    assert on_bearings.overturned and on_bearings.t_overturn_s != rows["Tb=2s"]["t_overturn_s"]


def test_the_figures_draw_each_rows_orientation_verdict_and_time(pair, report):
    """Each configuration is drawn once, on the projection onto its row's azimuth (the very samples), with the
    row's verdict and its toppling time (the same run: equal, not close), under a heading naming that azimuth."""
    from rockcli.records.orientation import project, read_pair

    rows, page, drawn = report
    both = read_pair(*pair[0].split("+"))
    seen = {}
    for label, excitation, runs in drawn:
        for conf, resp in runs.items():
            assert conf not in seen, f"{conf} drawn twice"
            seen[conf] = (label, excitation, resp)
    assert set(seen) == {r["configuration"] for r in rows}
    for row in rows:
        label, excitation, resp = seen[row["configuration"]]
        theta = row["azimuth_deg"]
        assert label == f"{row['record']}@{theta:g}"
        assert np.array_equal(excitation.acc, project(*both, theta).acc)
        assert resp.verdict == row["verdict"] and resp.t_overturn_s == row["t_overturn_s"]
        assert any(h.startswith(f"{row['record']}, projected onto {theta:g} deg, the most adverse of its 6 "
                                f"orientations") for h in page.heads), page.heads
    assert "knife-edge" not in page.text["figures"] and "the table's run at" not in page.text["figures"]


def test_the_ground_motions_are_both_files_and_the_projections_run(pair, report):
    """Both files with their SHA-256; one row per projection the rows ran (60 and 150 deg) with its PGA, and none
    of the 0 deg projection that no row ran."""
    from rockcli.records.orientation import project, read_pair

    rows, page, _ = report
    text = " ".join(page.text["records"].split())
    for path in pair[1]:
        assert path.name in text
        assert hashlib.sha256(path.read_bytes()).hexdigest() in text
    both = read_pair(*pair[0].split("+"))
    for theta, where in ((60, "standing on the ground"), (150, "on linear (rubber) bearings, Tb=2s")):
        assert (f"projected onto {theta} deg: the motion run the most adverse of its 6 orientations {where}"
                in text), text
        assert f"{project(*both, theta).pga_g:.3f} g" in text
    assert "projected onto 0 deg" not in text


def test_the_verdict_table_cells_can_wrap(report):
    """Nothing long and unbreakable in the verdict table: a numeric cell (kept on one line) holds its number,
    with any words in a note that wraps; a record label can break after its separators; the sentence in words
    has a width of its own (at 1280 px the table used to overflow, one word a line in "in words")."""
    _, page, _ = report
    table = [r for r in page.cells["verdicts"] if r]
    assert len(table) == 2
    for row in table:
        for css, inner in row:
            if css == "num":
                bare = re.sub(r"<span class=.note.>.*?</span>|<[^>]+>", "", inner)
                assert len(bare) <= 12, inner
        label = row[0][1]
        assert max(len(part) for part in re.split(r"<wbr>|[\s-]", label)) <= 20, label
        assert row[7][1].startswith("<div class='words'>")


def test_python_gives_the_clis_worst_rows(pair, report):
    """``resolve_excitations([pair], azimuth="worst")`` then ``run_assessment``: the rows of ``assess column
    --azimuth worst`` (same azimuths, verdicts, margins, times), not the 0 deg projection's."""
    from rockcli.assess import parse_column_spec, parse_configurations, resolve_excitations, run_assessment

    xs, _ = resolve_excitations([pair[0]], azimuth="worst", azimuth_step=STEP)
    assert xs[0].azimuths == (0.0, 30.0, 60.0, 90.0, 120.0, 150.0)
    result = run_assessment([parse_column_spec(BODY)], xs, parse_configurations(ISOLATION))
    cli = report[0]
    assert len(result.rows) == len(cli) == 2
    for mine, theirs in zip(result.rows, cli):
        for key in ("record", "configuration", "verdict", "azimuth_deg", "overturn_scale", "overturn_scale_survives",
                    "t_overturn_s", "overturning_azimuths", "azimuths_run"):
            assert getattr(mine, key) == theirs[key], key
    # the motion each row ran, and the reruns of history_runs, are the row's orientation
    from rockcli.assess import history_runs

    for row, _, _, x, resp in history_runs(result):
        assert x.label == f"{row.record}@{row.azimuth_deg:g}" and x.azimuth_deg == row.azimuth_deg
        assert resp.verdict == row.verdict and resp.t_overturn_s == row.t_overturn_s


def test_python_default_step_is_the_clis(pair):
    """Without ``azimuth_step`` both sweep 36 orientations (5 deg) and agree (verdicts only, to stay quick)."""
    from rockcli.assess import parse_column_spec, parse_configurations, resolve_excitations, run_assessment

    xs, _ = resolve_excitations([pair[0]], azimuth="worst")
    mine = run_assessment([parse_column_spec(BODY)], xs, parse_configurations(["none"]), margin=False).rows[0]
    theirs = _cli(["--isolation", "none", "--records", pair[0], "--azimuth", "worst", "--no-margin"])["rows"]
    theirs = next(r for r in theirs if r["configuration"] == "none")
    assert (mine.azimuth_deg, mine.verdict, mine.t_overturn_s, mine.azimuths_run) == (
        theirs["azimuth_deg"], theirs["verdict"], theirs["t_overturn_s"], 36)
    assert len(xs[0].azimuths) == 36


def test_what_does_not_sweep_says_so(pair):
    """A fragility of the pairs of azimuth="worst" would be that of their 0 deg projection: refused in one
    sentence naming the function that sweeps; a step without "worst" too."""
    from rockcli.assess import (parse_column_spec, parse_configurations, resolve_excitations, run_assessment,
                                run_fragility)

    xs, _ = resolve_excitations([pair[0]], azimuth="worst", azimuth_step=STEP)
    with pytest.raises(RockcliInputError, match=r"is a pair to run in every orientation \(azimuth='worst'\): "
                                                r"run_fragility_azimuths"):
        run_fragility([parse_column_spec(BODY)], xs, parse_configurations(["none"]), n_boot=0)
    with pytest.raises(RockcliInputError, match=r"is a pair to run in every orientation \(azimuth='worst'\) and "
                                                r"orientations= is given"):
        run_assessment([parse_column_spec(BODY)], xs, parse_configurations(["none"]), orientations={})
    with pytest.raises(RockcliInputError, match="azimuth_step 30 is the step of azimuth='worst'"):
        resolve_excitations([pair[0]], azimuth=30, azimuth_step=30)
    fixed, _ = resolve_excitations([pair[0]], azimuth=60)
    assert fixed[0].azimuths == () and fixed[0].label.endswith("@60")  # one azimuth: its projection runs


def test_parse_column_spec_from_rockcli():
    """docs/python.md takes the columns from parse_column_spec, imported from rockcli."""
    import rockcli
    from rockcli.assess import parse_column_spec

    assert rockcli.parse_column_spec is parse_column_spec and "parse_column_spec" in rockcli.__all__
