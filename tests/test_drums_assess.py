"""``assess column nemea-drums --friction MU``: columns of drums beside their monoliths (rockcli.assess.drums): what is
refused, the same verdicts in the table, the CSV, the JSON, the words and the report, the assessment's row against
``simulate_drums`` of the same scene, a column whose joints cannot move against its monolith, and a margin checked
by running both ends of its bracket."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.io.units import G
from rockcli.models import LinearIsolation, Rigid
from rockcli.models.drums import DrumColumn, drum_preset, monolith_beside, parse_drum_spec
from rockcli.pulses import OneSine, RickerSymmetric
from rockcli.solve import simulate_many
from rockcli.solve.drums import simulate_drums
from rockcli.solve.slide_many import Sliding
from synthetic import synthetic_record

SHAFT = "shaft:height=3,width=0.6,drums=3"
#: synthetic records (seed, peak [g]) under which the shaft of 3 drums fails or stands, by sliding off or toppling,
#: beside a monolith that does the same or not (none of them takes seconds)
RECORDS = ((40, 0.3), (41, 0.5), (42, 0.6), (45, 0.6))


def _run(*args):
    res = CliRunner().invoke(main, [str(a) for a in args])
    return res.exit_code, res.output


@pytest.fixture
def suite(tmp_path):
    folder = tmp_path / "suite"
    folder.mkdir()
    for seed, pga in RECORDS:
        np.savetxt(folder / f"r{seed}.txt", synthetic_record(seed, duration=8.0, pga=pga * G).acc / G)
    return folder


def _base(suite):
    return ("assess", "column", SHAFT, "--records", suite, "--units", "g", "--dt", "0.01", "--friction", "0.6",
            "--isolation", "none", "--isolation", "linear:Tb=2.5", "--no-margin")


# --------------------------------------------------------------------------------------------------
# what is refused
# --------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("args, words", [
    (("nemea-drums",), "give --friction MU"),
    (("nemea-drums", "--friction", "base=0.6,joint=0.7"), "one coefficient for every contact"),
    (("nemea-drums", "--friction", "0.7", "--on", "plinth:height=1,width=2"), "--on is not taken with drums"),
    (("nemea-drums", "--friction", "0.7", "--restitution", "0.9"), "--restitution is not taken with drums"),
    (("nemea-drums", "--friction", "0.7", "--cap-ratio", "0.2"), "--cap-ratio is not taken with drums"),
    (("nemea-drums", "--friction", "0.7", "--vertical-pulse", "ricker-sym:ap=0.2,Tp=0.5"), "--vertical"),
    (("nemea-drums", "--friction", "0.7", "--isolation", "scss:Tb=3,mu=0.05"), "not on scss"),
    (("nemea-drums", "--friction", "0.7", "--isolation", "lrb:Tb=2.5,Q=0.06,uy=0.015"), "not on lrb"),
    (("nemea-drums", "--friction", "0.7", "--isolation", "linear:Tb=2.5,gamma=0"), "gamma > 0"),
    (("shaft:height=3,width=0.6,drums=2.5", "--friction", "0.7"), "whole number"),
    (("shaft:height=3,drums=3", "--friction", "0.7"), "missing: width"),
    (("shaft:R=2,alpha=10,drums=3", "--friction", "0.7"), "is not one of height=<m>, width=<m>, drums=<N>"),
    (("nemea-drum", "--friction", "0.7"), "did you mean 'nemea-drums'"),
])
def test_what_a_column_of_drums_does_not_take_is_refused_in_one_sentence_and_nothing_is_written(args, words,
                                                                                              tmp_path):
    out_csv, out_html = tmp_path / "o.csv", tmp_path / "o.html"
    code, out = _run("assess", "column", *args, "--records", "kobe-1995-takarazuka-000", "--excitation", "pulse",
                     "--no-margin", "--csv", out_csv, "--report", out_html)
    assert code == 2 and words in out and "Traceback" not in out, out
    assert out.count("Error:") == 1 and len(out.strip().splitlines()) <= 2
    assert not out_csv.exists() and not out_html.exists()


def test_fragility_refuses_columns_of_drums(tmp_path):
    code, out = _run("assess", "fragility", "bassae-drums", "--records", "kobe-1995-takarazuka-000", "--friction",
                     "0.7", "--csv", tmp_path / "f.csv")
    assert code == 2 and "does not take columns of drums" in out and "Traceback" not in out
    assert not (tmp_path / "f.csv").exists()


def test_the_names_of_drum_columns_and_their_monoliths():
    nemea = parse_drum_spec("nemea-drums")
    assert nemea.n == 13 and monolith_beside(nemea).name == "nemea"
    from rockcli.models import column

    assert monolith_beside(nemea) == column("nemea")  # the paper's column, bit for bit
    shaft = parse_drum_spec(SHAFT)
    assert shaft.n == 3 and shaft.height == pytest.approx(3.0) and shaft.width == 0.6
    mono = monolith_beside(shaft)
    assert mono.name == "shaft monolith" and (mono.R, mono.alpha) == (shaft.monolith.R, shaft.monolith.alpha)
    assert parse_drum_spec("nemea") is None and parse_drum_spec("statue:height=2,width=0.5") is None


# --------------------------------------------------------------------------------------------------
# the same answer in every output
# --------------------------------------------------------------------------------------------------

def _cell_word(cell: str) -> str:
    return ("fails" if cell.startswith(("FALLS", "SLIDES OFF", "OVERTURNS")) else
            "stands" if cell.startswith(("survives", "no uplift")) else cell)


def _drum_words(out: str) -> dict:
    """``{("ground" | "bearings", record): sentence}`` of the printout's answer to "Do the drums make the column
    safer?" (wrapped lines joined)."""
    lines = out[out.index("Do the drums make the column safer?"):].splitlines()[1:]
    items, where, last = [], None, None
    for line in lines:
        if line.startswith("  - "):
            items.append([where, line[4:]])
            last = "item"
        elif line.startswith("      "):
            if last == "item":
                items[-1][1] += " " + line.strip()
        elif line.startswith("  "):
            where, last = ("ground" if "on the ground" in line.lower() else "bearings"), "head"
        else:
            break
    return {(w, t.partition(":")[0]): t for w, t in items}


def test_the_table_the_csv_the_json_the_words_and_the_report_say_the_same(suite, tmp_path):
    csv_path, html = tmp_path / "d.csv", tmp_path / "d.html"
    code, out = _run(*_base(suite), "--csv", csv_path, "--report", html)
    assert code == 0, out
    code_j, out_j = _run(*_base(suite), "--json")
    assert code_j == 0, out_j
    doc, _ = json.JSONDecoder().raw_decode(out_j[out_j.index("{"):])  # a warning on stderr may follow
    rows = list(csv.DictReader(csv_path.open()))
    assert [r["column"] for r in rows] == [r["column"] for r in doc["rows"]]
    assert {r["column"] for r in rows} == {"shaft", "shaft monolith"}  # each column of drums beside its monolith
    for k in ("drum_column", "drums", "falls_at", "first_move", "first_joint_open", "joint_open_max_over_alpha",
              "residual_offsets_m",
              "residual_offset_max_m", "drums_vs_monolith", "monolith_verdict", "n_inconsistent", "reliable"):
        assert k in rows[0] and k in doc["rows"][0], k
    cols = {c["name"]: c for c in doc["columns"]}
    assert cols["shaft"]["monolith"] == "shaft monolith" and len(cols["shaft"]["drums"]) == 3
    by = {(r["column"], r["record"], r["configuration"]): r for r in rows}
    table = out[:out.index("\n\n")]
    words = _drum_words(out)
    compared = set()
    for (col, rec, conf), r in by.items():
        j = next(x for x in doc["rows"] if (x["column"], x["record"], x["configuration"]) == (col, rec, conf))
        assert j["verdict"] == r["verdict"] and str(j["drums_vs_monolith"] or "") == r["drums_vs_monolith"]
        assert r["drum_column"] == "shaft" and int(r["drums"]) == (3 if col == "shaft" else 1)
        assert j["error"] == r["error"]
        if r["error"]:  # a run that failed: said in the table and the words, compared with nothing
            line = next(l for l in table.splitlines() if l.startswith(rec) and f" {conf} " in l)
            assert "ERROR" in line and not r["drums_vs_monolith"]
            if col == "shaft":
                assert "not computed" in words[("bearings" if conf != "none" else "ground", rec)]
            continue
        fails = r["verdict"] in ("overturned", "slid_off")
        assert (r["overturned"] == "True") == fails and bool(r["falls_at"]) == fails
        assert r["reliable"] == str(int(r["n_inconsistent"]) == 0)
        if col != "shaft":
            continue
        m = by[("shaft monolith", rec, conf)]
        mfails = m["verdict"] in ("overturned", "slid_off")
        assert r["monolith_verdict"] == m["verdict"]
        want = ("worse" if fails and not mfails else "safer" if mfails and not fails else
                "alike" if fails else r["drums_vs_monolith"])
        assert r["drums_vs_monolith"] == want and want in ("safer", "worse", "alike")
        if not fails and not mfails:  # both stand: the base's peaks decide (within 2 %: alike)
            a, b = float(r["theta_max_over_alpha"]), float(m["theta_max_over_alpha"])
            assert (want == "alike") == (abs(a - b) <= 0.02 * max(a, b, 1e-12))
        compared.add(want)
        # the table's line of this record and configuration: the drums' cell, the monolith's, the comparison
        line = next(l for l in table.splitlines() if l.startswith(rec) and f" {conf} " in l)
        cells = [c for c in line.split("  ") if c.strip()]
        assert _cell_word(cells[2].strip()) == ("fails" if fails else "stands")
        assert _cell_word(cells[3].strip()) == ("fails" if mfails else "stands")
        assert cells[4].strip() == want and cells[6].strip().startswith("yes" if r["reliable"] == "True" else "NO")
        if r["verdict"] == "slid_off":
            assert cells[2].strip().startswith(f"SLIDES OFF {r['falls_at']}")
        # the words, record by record
        sentence = words[("bearings" if conf != "none" else "ground", rec)]
        assert sentence.startswith(f"{rec}: the shaft of 3 drums")
        assert f": {want}" in sentence and (("NOT RELIABLE" in sentence) == (r["reliable"] == "False")), sentence
    assert len(compared) >= 2  # the records were chosen to give different answers
    page = html.read_text()
    assert "Do the drums make the column safer?" in page and "shaft monolith" in page
    assert ("NOT RELIABLE" in page) == any(r["reliable"] == "False" for r in rows)
    assert "friction mu=0.6" in page


def test_a_fault_of_the_driver_in_one_scene_is_that_scene_s_error_row(suite, tmp_path, monkeypatch):
    """An arithmetic fault of the compiled driver in one run (a division by zero) does not end the assessment: that
    scene's row says so (ERROR, the error in the CSV, 'not computed' in the words), the others are computed."""
    import rockcli.solve.slide_many as sm

    real = sm.run_slide

    def faulty(sliding, foundation, motion, scale=1.0, **kw):
        if isinstance(sliding.subject, DrumColumn) and isinstance(foundation, LinearIsolation):
            raise ZeroDivisionError("division by zero")
        return real(sliding, foundation, motion, scale, **kw)

    monkeypatch.setattr(sm, "run_slide", faulty)
    path = tmp_path / "f.csv"
    code, out = _run(*_base(suite), "--csv", path)
    assert code == 0 and "Traceback" not in out, out
    rows = list(csv.DictReader(path.open()))
    failed = [r for r in rows if r["error"]]
    assert failed and all(r["column"] == "shaft" and r["configuration"] != "none" for r in failed)
    assert all("ZeroDivisionError" in r["error"] and "fault of the driver" in r["error"] for r in failed)
    assert all(r["verdict"] for r in rows if not r["error"]) and "run(s) failed" in out
    assert out.count("not computed") >= len(failed)


def test_the_row_is_simulate_drums_of_the_same_scene(suite):
    """The assessment's row of a column of drums and its monolith's are the run of ``simulate_drums`` (the driver of
    ``simulate --drums``): the same verdicts, where it fails, the first joint to move, the residual offsets, the
    counts, and the same comparison."""
    from rockcli.assess import parse_configurations, resolve_excitations, run_assessment
    from rockcli.assess.drums import with_monoliths

    col = parse_drum_spec(SHAFT)
    xs, _ = resolve_excitations([str(suite)], "record", units="g", dt=0.01)
    confs = parse_configurations(["none", "linear:Tb=2.5"])
    columns = [Sliding(c, 0.6) for c in with_monoliths([col])]
    res = run_assessment(columns, xs, confs, margin=False)
    for x in xs:
        for c in confs:
            r, m = res.row("shaft", x.label, c.header), res.row("shaft monolith", x.label, c.header)
            assert not r.error and not m.error, (r.error, m.error)
            run = simulate_drums(col, x.motion, 0.6, None if isinstance(c.foundation, Rigid) else c.foundation)
            v = {"overturned": "overturned", "slid off": "slid_off", "no motion": "no_uplift"}
            assert r.verdict == v.get(run.verdict, "rocked" if run.stack.rocks else "slid")
            assert m.overturned == (run.monolith.verdict in ("overturned", "slid off"))
            assert (r.falls_at or None) == run.falls_at and r.n_inconsistent == run.stack.n_inconsistent
            fm = run.first_move
            assert r.first_move == ("" if fm is None else f"{fm[0]} {fm[2]}")
            opened = [p for p in run.stack.interfaces[1:] if math.isfinite(p.t_uplift)]
            assert r.first_joint_open == (min(opened, key=lambda p: p.t_uplift).name if opened else "")
            assert (r.first_joint_open_t_s == min(p.t_uplift for p in opened)) if opened else \
                math.isnan(r.first_joint_open_t_s)
            if not r.overturned:
                assert [float(v) for v in r.residual_offsets_m.split()] == pytest.approx(run.residual_offsets_m,
                                                                                          rel=1e-5, abs=1e-9)
            assert r.drums_vs_monolith == run.compared


# --------------------------------------------------------------------------------------------------
# physics
# --------------------------------------------------------------------------------------------------

def test_a_column_whose_joints_cannot_open_or_slide_has_its_monolith_s_verdict():
    """Joints that cannot move (every joint's static threshold above the ground's peak acceleration, friction far
    above it): the column rocks as one on its base, as its monolith does: the same verdict under pulses it
    survives and under one that topples it, nothing opening above the base where it stands, and ``alike``."""
    from rockcli.assess import Excitation, parse_configurations, run_assessment
    from rockcli.assess.drums import with_monoliths

    col = DrumColumn.uniform(2.4, 0.6, 4, "stele")
    th = col.static_thresholds()
    assert th[0] < min(th[1:])
    pulses = [RickerSymmetric(0.5 * (th[0] + th[1]) * G, 1.0), OneSine(0.5 * (th[0] + th[1]) * G, 0.6),
              OneSine(0.95 * th[1] * G, 2.0), RickerSymmetric(0.9 * th[0] * G, 1.0)]
    xs = [Excitation(f"p{k}", "pulse", p, "test", abs(p.a_p) / G) for k, p in enumerate(pulses)]
    res = run_assessment([Sliding(c, 5.0) for c in with_monoliths([col])], xs, parse_configurations(["none"]),
                         margin=False)
    verdicts = set()
    for x in xs:
        r, m = res.row("stele", x.label, "none"), res.row("stele monolith", x.label, "none")
        assert r.overturned == m.overturned and r.drums_vs_monolith == "alike", (x.label, r.verdict, m.verdict)
        verdicts.add(m.verdict)
        if not r.overturned:
            assert r.joint_open_max_over_alpha == 0.0 and r.joint_slide_max_m == 0.0
            assert r.theta_max_over_alpha == pytest.approx(m.theta_max_over_alpha, abs=1e-5)
            assert r.first_move in ("", "base opens") and r.reliable
    assert {"rocked", "overturned", "no_uplift"} <= verdicts  # the pulses span the three answers


def test_the_margin_of_a_column_of_drums_fails_at_its_factor_and_stands_below_it():
    """The existing margin search on a column of drums: the factor it finds makes the column fail (a drum falls or
    slides off), the one below it does not (both rerun by simulate_drums); below the lift-off floor nothing moves;
    the row says whether the margin rests on runs without a consistent contact pattern."""
    from rockcli.assess import Excitation, parse_configurations, run_assessment
    from rockcli.assess.drums import with_monoliths
    from rockcli.assess.liftoff import liftoff_floor

    col = DrumColumn.uniform(3.0, 0.6, 3, "shaft")
    pulse = OneSine(0.25 * G, 1.2)
    xs = [Excitation("sine", "pulse", pulse, "test", 0.25)]
    res = run_assessment([Sliding(c, 0.6) for c in with_monoliths([col])], xs, parse_configurations(["none"]))
    for name in ("shaft", "shaft monolith"):
        r = res.row(name, "sine", "none")
        assert math.isfinite(r.overturn_scale) and r.overturn_scale_survives < r.overturn_scale, r.margin_note
        body = Sliding(col if name == "shaft" else monolith_beside(col), 0.6)
        top, below = simulate_many([(body, Rigid(), pulse.scaled(s)) for s in (r.overturn_scale,
                                                                              r.overturn_scale_survives)])
        assert top.overturned and not below.overturned
        assert r.reliable == ("not reliable" not in r.margin_note and not r.n_inconsistent)
    drums = res.row("shaft", "sine", "none")
    assert drums.monolith_overturn_scale == res.row("shaft monolith", "sine", "none").overturn_scale
    floor = liftoff_floor(Sliding(col, 0.6), Rigid(), pulse)
    assert 0 < floor < drums.overturn_scale
    assert simulate_drums(col, pulse.scaled(floor * 0.999), 0.6).verdict == "no motion"


def test_the_presets_run_on_bearings_and_the_catalogue_record(find_record):
    """The paper's two columns as drums under one record, on linear bearings (a short run): each beside the paper's
    monolith; the monolith's row is the assessment of the monolith alone with the same friction, bit for bit."""
    find_record("RSN1119_KOBE_TAZ000.AT2")
    from rockcli.assess import parse_configurations, resolve_excitations, run_assessment
    from rockcli.assess.drums import with_monoliths

    xs, _ = resolve_excitations(["kobe-1995-takarazuka-000"], "record")
    confs = parse_configurations(["linear:Tb=2.5"])
    cols = with_monoliths([drum_preset("bassae-drums"), drum_preset("nemea-drums")])
    assert [c.name for c in cols] == ["bassae-drums", "bassae", "nemea-drums", "nemea"]
    res = run_assessment([Sliding(c, 0.7) for c in cols], xs, confs, margin=False)
    alone = run_assessment([Sliding(c, 0.7) for c in cols[1::2]], xs, confs, margin=False)
    for name in ("bassae", "nemea"):
        a, b = res.row(name, xs[0].label, "Tb=2.5s"), alone.row(name, xs[0].label, "Tb=2.5s")
        assert (a.verdict, a.theta_max_over_alpha, a.base_disp_max_m) == (b.verdict, b.theta_max_over_alpha,
                                                                        b.base_disp_max_m)
        d = res.row(f"{name}-drums", xs[0].label, "Tb=2.5s")
        assert d.drums == (6 if name == "bassae" else 13) and d.drums_vs_monolith in ("safer", "worse", "alike")
        assert math.isfinite(d.base_disp_max_m) and d.base_disp_max_m > 0


def test_on_a_local_dask_cluster_the_same_csv_with_margins(suite, tmp_path):
    """--scheduler local: the rows of the columns of drums and their monoliths, margins and reliability included,
    byte for byte those of the run on this machine."""
    pytest.importorskip("distributed")
    args = ("assess", "column", SHAFT, "--records", suite / "r41.txt", "--records", suite / "r42.txt", "--units", "g",
            "--dt", "0.01", "--friction", "0.6", "--isolation", "none")
    here, there = tmp_path / "here.csv", tmp_path / "dask.csv"
    assert _run(*args, "--csv", here)[0] == 0
    code, out = _run(*args, "--csv", there, "--scheduler", "local")
    assert code == 0, out
    assert there.read_bytes() == here.read_bytes()
    rows = list(csv.DictReader(here.open()))
    assert any(math.isfinite(float(r["overturn_scale"] or "nan")) for r in rows)
