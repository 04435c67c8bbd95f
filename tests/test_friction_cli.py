"""``--friction`` on the command line: friction as a model (docs/physics-sliding.md). Where nothing slides the
rocking answer bit for bit; where a contact slides, the friction run's answer, in JSON, text, history and figure."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner

from rockcli.cli import main

sys.path.insert(0, str(Path(__file__).parent))
from test_friction_model import newmark_two_way  # noqa: E402

STATUE = "statue:height=1.79,width=0.5"
CRATE = "crate:height=0.5,width=1.0"
PLINTH = "plinth:height=1.0,width=0.6"
KOBE = "kobe-1995-takarazuka-000"


def _run(*args):
    res = CliRunner().invoke(main, list(args))
    return res.exit_code, res.output


def _json(*args):
    code, out = _run(*args, "--json")
    assert code == 0, out
    return json.loads(out)


def test_a_crate_under_kobe_slides_as_newmarks_block(find_record):
    """Done when: the crate with mu = 0.2 under Kobe reports slide_max_m and slide_residual_m within 1 % of Newmark's
    two-way rigid block of yield 0.2 g on the same record (here to 1e-6), and no rocking."""
    from rockcli.records import read_record

    d = _json("simulate", "--body", CRATE, "--record", KOBE, "--friction", "0.2")
    rec = read_record(str(find_record("RSN1119_KOBE_TAZ000.AT2")))
    smax, send = newmark_two_way(rec.acc, rec.dt, 0.2)
    assert d["slide_max_m"] == pytest.approx(smax, rel=1e-6)
    assert d["slide_residual_m"] == pytest.approx(send, rel=1e-6)
    assert d["psi_max_rad"] == 0.0 and d["t_uplift_s"] is None and d["n_impacts"] == 0
    assert d["verdict"] == "survives" and d["friction"]["slides"] is True
    assert "slides" in d["plain_words"] and "cm" in d["plain_words"]


@pytest.mark.parametrize("on", [(), ("--on", PLINTH)])
def test_a_friction_nothing_reaches_gives_the_rocking_answer_bit_for_bit(on):
    """Done when: --friction 10 gives the rocking-only answer exactly, alone and on a plinth: every key of the JSON
    without --friction, the same value, and the text's rows the same plus one."""
    motion = ("--pulse", "ricker-sym:ap=0.35,Tp=1")
    plain = _json("simulate", "--body", STATUE, *motion, *on)
    fr = _json("simulate", "--body", STATUE, *motion, *on, "--friction", "10")
    assert {k: fr[k] for k in plain} == plain
    assert fr["friction"]["slides"] is False and fr["friction"]["rocking_answer"] is True
    if on:
        assert fr["base"]["slide_max_m"] == 0.0 and fr["joint"]["slide_max_m"] == 0.0
    else:
        assert fr["slide_max_m"] == 0.0 and fr["slide_residual_m"] == 0.0
    _, text = _run("simulate", "--body", STATUE, *motion, *on)
    _, text_fr = _run("simulate", "--body", STATUE, *motion, *on, "--friction", "10")
    extra = [ln for ln in text_fr.splitlines() if ln not in text.splitlines()]
    assert len(extra) == 1 and extra[0].startswith("friction") and "no contact slides" in extra[0]


def test_the_statue_on_its_plinth_under_kobe_slides_at_the_base_and_the_joint(find_record):
    """The statue on its 1.0 m x 0.6 m plinth with mu = 0.5 under Kobe: the rocking model's demand is 0.595 at the
    base and 0.476 at the joint (0.808 and 0.412 at impacts), so the plinth slides on the floor; once it has, the
    statue's demand on the plinth changes and it slides there too (4.2 cm, 8 mm short of the plinth's edge) and
    topples at 7.29 s, where the rocking-only model has it survive. The slow reference (rockcli.reference.friction)
    gives the same peaks to 1e-10 (docs/physics-sliding.md); here both contacts are reported and the words say it."""
    find_record("RSN1119_KOBE_TAZ000.AT2")
    d = _json("simulate", "--body", STATUE, "--record", KOBE, "--on", PLINTH, "--friction", "0.5")
    assert d["verdict"] == "overturned" and d["friction"]["slides"] is True
    assert d["base"]["n_slips"] > 0 and d["base"]["slide_max_m"] > 0.0
    assert d["joint"]["n_slips"] > 0 and 0.0 < d["joint"]["slide_max_m"] < d["joint"]["edge_m"]
    assert d["joint"]["edge_m"] == pytest.approx(0.05)
    assert d["joint"]["t_slide_s"] > d["base"]["t_slide_s"]  # the joint slides once the base has
    words = d["plain_words"]
    assert "topples" in words and "slid" in words
    rocking = _json("simulate", "--body", STATUE, "--record", KOBE, "--on", PLINTH)
    assert rocking["verdict"] == "rocked"  # survives, rocking: the rocking-only answer this model corrects
    d = _json("simulate", "--body", STATUE, "--record", KOBE, "--on", PLINTH, "--friction", "base=0.5,joint=0.3")
    assert d["friction"]["mu"] == [0.5, 0.3] and d["joint"]["n_slips"] > 0


def test_a_sliding_run_writes_its_history_figure_and_report(tmp_path):
    """Issue 44's "friction reaches the committee": the report of a run that slides says so on its first screen
    (the card: how far the statue slid on its plinth and how close it came to the edge) and the friction assumed in
    its assumptions."""
    h, png, rep = tmp_path / "h.csv", tmp_path / "h.png", tmp_path / "r.html"
    code, out = _run("simulate", "--body", STATUE, "--pulse", "ricker-sym:ap=0.6,Tp=0.6", "--on", PLINTH,
                     "--friction", "base=0.5,joint=0.25", "--history", str(h), "--plot", str(png), "--report",
                     str(rep))
    assert code == 0, out
    html = rep.read_text()
    card = html[html.index('<div class="card'):html.index("</div>", html.index('<div class="card'))]
    assert "slides" in card and "plinth" in card and "edge" in card
    assert "Coulomb" in html and "mu = 0.25" in html and "<img" in html
    assert "sliding" in out and "In plain words:" in out
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    head = h.read_text().splitlines()[0].split(",")
    assert head[:3] == ["t_s", "ag_mps2", "ag_g"] and "joint_slide_m" in head and "base_slide_m" in head


@pytest.mark.parametrize("args, words", [
    (("--friction", "0"), "--friction must be a friction coefficient"),
    (("--friction", "nan"), "--friction"),
    (("--friction", "base=0.5,joint=0.5"), "a body alone has one contact"),
    (("--friction", "0.5", "--isolation", "scss:Tb=3,mu=0.05"), "not on sliding or lead-rubber bearings"),
    (("--friction", "0.5", "--restitution", "0.9", "--isolation", "linear:Tb=3"), "a single block on bearings"),
    (("--friction", "0.5", "--theta0", "0.1"), "--theta0"),
    (("--friction", "base=0.5", "--on", PLINTH), "missing: joint"),
])
def test_bad_friction_input_is_one_sentence(args, words):
    code, out = _run("simulate", "--body", STATUE, "--pulse", "ricker-sym:ap=0.35,Tp=1", *args)
    assert code == 2, out
    assert words in out and "Traceback" not in out
    assert len(out.strip().splitlines()) == 1
