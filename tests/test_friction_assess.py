"""Friction as a model in the batch path and the assessment (rockcli.solve.slide_many, assess --friction): the
shortcut "where nothing slides, the rocking model's own run" against the friction run it replaces, bit for bit
against the answer without friction, and the assessment's rows, CSV and margins."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.io.units import G
from rockcli.models import Block, LinearIsolation, Plinth, Rigid, Stack
from rockcli.pulses import OneSine, RickerAntisymmetric, RickerSymmetric
from rockcli.solve import simulate_many
from rockcli.solve.slide import simulate_friction
from rockcli.solve.slide_many import SlideRun, Sliding

KOBE = "kobe-1995-takarazuka-000"


def _scenes(seed, k):
    rng = np.random.default_rng(seed)
    kinds = (RickerSymmetric, RickerAntisymmetric, OneSine)
    out = []
    for i in range(k):
        body = Block.from_dimensions(rng.uniform(0.8, 3.0), rng.uniform(0.2, 0.6))
        if i % 3 == 2:
            body = Stack(body, Plinth(rng.uniform(0.3, 1.2), body.width * rng.uniform(1.05, 1.8)))
        f = Rigid() if i % 4 else LinearIsolation(T_b=rng.uniform(1.5, 3.0), xi=0.1, gamma=rng.uniform(0.1, 0.5))
        out.append((body, f, kinds[i % 3](rng.uniform(0.2, 0.7) * G, rng.uniform(0.3, 1.2))))
    return out


def test_where_nothing_slides_the_batch_gives_the_rocking_answer_bit_for_bit_and_the_friction_run_agrees():
    """The shortcut's theorem, checked both ways on random scenes (single blocks and plinths, on the ground and on
    bearings) with a friction nothing reaches: the SlideRun is the rocking model's own run, every field identical;
    the friction run it stands for (the path without the shortcut) has the same verdict and peaks within the
    solvers' tolerance, and slid nowhere."""
    scenes = _scenes(4, 36)
    rock = simulate_many(scenes)
    fr = simulate_many([(Sliding(b, 10.0), f, m) for b, f, m in scenes])
    compared = 0
    for (b, f, m), r, s in zip(scenes, rock, fr):
        assert isinstance(s, SlideRun)
        direct = simulate_friction(b, m, 10.0, None if isinstance(f, Rigid) else f)
        if direct.slides:  # a falling block's contact slips as it unloads: then the friction run's own answer
            assert r.overturned and s.overturned
            continue
        compared += 1
        assert not s.slid and s.rock is not None
        for name in ("verdict", "overturned", "settled", "theta_max_over_alpha", "t_uplift_s", "n_impacts",
                     "base_disp_max_m", "steps", "nfev"):
            a, c = getattr(r, name), getattr(s, name)
            assert a == c or (isinstance(a, float) and math.isnan(a) and math.isnan(c)), name
        assert (direct.verdict == "overturned") == r.overturned
        if not r.overturned:
            alpha = direct.body.alpha
            assert direct.body.psi_max == pytest.approx(r.theta_max_over_alpha * alpha, abs=2e-6 * alpha)
    assert compared >= 25


def _run(*args):
    res = CliRunner().invoke(main, list(args))
    return res.exit_code, res.output


def test_assess_column_with_a_friction_nothing_reaches_writes_the_rows_without_friction(tmp_path):
    """--friction 10: every column of the CSV without friction is the same, byte for byte; the friction columns say
    nothing slid."""
    a, b = tmp_path / "a.csv", tmp_path / "b.csv"
    args = ("assess", "column", "statue:height=1.79,width=0.5", "--records", KOBE, "--isolation", "none",
            "--isolation", "linear:Tb=2.5", "--no-margin")
    assert _run(*args, "--csv", str(a))[0] == 0
    code, out = _run(*args, "--friction", "10", "--csv", str(b))
    assert code == 0, out
    ra, rb = list(csv.DictReader(a.open())), list(csv.DictReader(b.open()))
    assert len(ra) == len(rb) == 2
    for x, y in zip(ra, rb):
        assert {k: y[k] for k in x} == x
        assert y["friction"] == "mu=10" and float(y["slide_max_m"]) == 0.0


def test_a_crate_s_assessment_slides_and_its_margin_is_a_topple_or_nothing(tmp_path, find_record):
    find_record("RSN1119_KOBE_TAZ000.AT2")  # without the record the catalogue's pulse would run
    path = tmp_path / "c.csv"
    code, out = _run("assess", "column", "crate:height=0.5,width=1.0", "--records", KOBE, "--isolation", "none",
                     "--friction", "0.2", "--csv", str(path))
    assert code == 0, out
    row = next(csv.DictReader(path.open()))
    assert row["verdict"] == "slid" and float(row["slide_max_m"]) == pytest.approx(0.15716, abs=1e-4)
    assert "s15.7cm" in out and "slides 16 cm on the ground" in out
    assert row["margin_note"].startswith("no overturning")  # a crate on the floor has nothing to slide off


def test_sliding_off_the_plinth_is_a_failure_in_the_margin():
    """A body on a plinth whose joint is slippery: the margin search counts sliding off as failing, and the factor it
    finds fails while the one below it survives (checked by running both)."""
    from rockcli.assess.margin import find_overturn_scales

    body = Block.from_dimensions(1.2, 0.6, "vase")
    stack = Sliding(Stack(body, Plinth(0.4, 0.72)), (0.6, 0.15))
    pulse = OneSine(0.3 * G, 1.0)
    (hi, lo, note), = find_overturn_scales([(stack, Rigid(), pulse)])
    assert math.isfinite(hi) and lo < hi
    top, below = simulate_many([(stack, Rigid(), pulse, hi), (stack, Rigid(), pulse, lo)])
    assert top.overturned and not below.overturned
    assert top.verdict in ("slid_off", "overturned")


@pytest.mark.parametrize("args, words", [
    (("--friction", "0.5", "--restitution", "0.9"), "a single block on bearings"),
    (("--friction", "0.5", "--isolation", "scss:Tb=3,mu=0.05"), "not on scss"),
    (("--friction", "base=0.5,joint=0.2"), "a body alone has one contact"),
])
def test_assess_refuses_what_friction_does_not_take(args, words):
    code, out = _run("assess", "column", "statue:height=1.79,width=0.5", "--records", KOBE, "--no-margin", *args)
    assert code == 2 and words in out and "Traceback" not in out, out
