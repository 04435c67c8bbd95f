"""A body on a free plinth on the command line (``--on``), its friction demand, the stack in the
batch path (``simulate_many``), its lift-off floor in the margin search, and the plinth in ``assess``."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.models import Block, Plinth, Rigid, Stack
from rockcli.pulses import OneSine, RickerSymmetric
from rockcli.io.units import G

STATUE = "statue:height=1.79,width=0.5"
KOBE = "kobe-1995-takarazuka-000"


def _run(*args):
    res = CliRunner().invoke(main, list(args))
    return res.exit_code, res.output


def _json(*args):
    code, out = _run(*args, "--json")
    assert code == 0, out
    return json.loads(out)


# ---------------------------------------------------------------------------------------------------------------
# simulate --on
# ---------------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("motion", [("--record", KOBE), ("--pulse", "ricker-sym:ap=0.35,Tp=1")])
def test_a_wide_low_plinth_gives_the_statue_on_rigid_ground_exactly(motion):
    """Done when: the plinth 0.2 m x 4 m cannot lift (it would need 3.2 g), so the statue's answer is its own on
    the ground, bit for bit: the same verdict, peak, times and impacts, printed and in the JSON."""
    alone = _json("simulate", "--body", STATUE, *motion)
    on = _json("simulate", "--body", STATUE, *motion, "--on", "plinth:height=0.2,width=4")
    assert on["verdict"] == alone["verdict"]
    assert on["body"]["theta_max_rad"] == alone["theta_max"]
    assert on["body"]["theta_max_over_alpha"] == alone["theta_max_over_alpha"]
    assert on["body"]["t_uplift_s"] == alone["t_uplift_s"]
    assert on["t_overturn_s"] == alone["t_overturn_s"]
    assert on["body"]["n_impacts"] == alone["n_impacts"]
    assert on["plinth"]["t_uplift_s"] is None and on["plinth"]["theta_max_rad"] == 0.0
    assert (on["toppled"] == "body") == (alone["verdict"] == "overturned")
    # the same lines printed
    _, text_alone = _run("simulate", "--body", STATUE, *motion)
    _, text_on = _run("simulate", "--body", STATUE, *motion, "--on", "plinth:height=0.2,width=4")

    def line(text, key):
        return next(ln for ln in text.splitlines() if ln.startswith(key))[len(key):].split()[0]

    for key in ("verdict", "peak |theta|/alpha", "overturn at"):
        assert line(text_on, key) == line(text_alone, key)
    assert "plinth peak" in text_on and "does not lift" in text_on


def test_a_tall_plinth_reports_both_blocks_and_the_friction_demand():
    d = _json("simulate", "--body", STATUE, "--record", KOBE, "--on", "plinth:height=1.0,width=0.6")
    for block in ("body", "plinth"):
        assert set(d[block]) >= {"theta_max_rad", "alpha_rad", "theta_max_over_alpha", "t_uplift_s", "n_impacts"}
    assert d["plinth"]["t_uplift_s"] is not None  # the plinth rocks (the assembly lifts first, at 0.225 g)
    fd = d["friction_demand"]
    assert set(fd) == {"base", "joint", "base_impulsive", "joint_impulsive"}
    assert all(v is None or v >= 0 for v in fd.values())
    assert d["plinth_model"]["mass_ratio"] == pytest.approx(1.0 * 0.6 / (1.79 * 0.5))
    assert d["plinth_model"]["assembly_uplift_g"] < d["plinth_model"]["body_uplift_g"]
    assert d["toppled"] in (None, "body", "plinth")
    assert "plain_words" in d
    _, text = _run("simulate", "--body", STATUE, "--record", KOBE, "--on", "plinth:height=1.0,width=0.6")
    assert "plinth peak" in text and "friction demand" in text and "In plain words:" in text


def test_the_history_of_a_stack(tmp_path):
    path = tmp_path / "h.csv"
    code, out = _run("simulate", "--body", STATUE, "--pulse", "ricker-sym:ap=0.35,Tp=1", "--on",
                     "plinth:height=1.0,width=0.6", "--history", str(path), "--plot", str(tmp_path / "h.png"))
    assert code == 0, out
    assert (tmp_path / "h.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    lines = path.read_text().splitlines()
    assert lines[0].split(",") == ["t_s", "ag_mps2", "ag_g", "psi_rad", "psi_over_alpha1", "psi_dot_radps",
                                   "theta2_rad", "theta2_over_alpha_asm", "theta2_dot_radps", "pattern", "event"]
    patterns = {ln.split(",")[-2] for ln in lines[1:]}
    assert patterns <= {"rest", "body rocks", "plinth rocks", "both rock"} and "plinth rocks" in patterns


@pytest.mark.parametrize("args, words", [
    (("--on", "plinth:height=1,width=0.3"), "no wider than its plinth"),
    (("--on", "plinth:height=x,width=1"), "height must be a number"),
    (("--on", "plinth"), "must be written NAME:height="),
    (("--on", "plinth:height=1"), "needs width"),
    (("--on", "plinth:height=1,width=1,mass_ratio=1e6"), "mass_ratio"),
    (("--on", "plinth:height=1,width=1,depth=2"), "is not one of height"),
    (("--on", "plinth:height=1,width=1", "--isolation", "scss:Tb=3,mu=0.05,gamma=0"), "gamma = 0"),
    (("--on", "plinth:height=1,width=1", "--cap-ratio", "0.2"), "--cap-ratio"),
    (("--on", "plinth:height=1,width=1", "--vertical-pulse", "sine:ap=0.1,Tp=0.3"), "--vertical"),
])
def test_bad_plinth_and_friction_input_is_one_sentence(args, words, tmp_path):
    code, out = _run("simulate", "--body", STATUE, "--pulse", "ricker-sym:ap=0.35,Tp=1", *args)
    assert code == 2, out
    assert words in out and "Traceback" not in out
    assert len(out.strip().splitlines()) == 1


# ---------------------------------------------------------------------------------------------------------------
# the batch path and the lift-off floor
# ---------------------------------------------------------------------------------------------------------------

def _random_stack(rng):
    h1 = rng.uniform(0.6, 3.0)
    w1 = h1 * rng.uniform(0.15, 0.6)
    body = Block.from_dimensions(h1, w1, "body")
    plinth = Plinth(rng.uniform(0.1, 1.5), w1 * rng.uniform(1.0, 3.0),
                    None if rng.random() < 0.5 else float(rng.uniform(0.2, 5.0)))
    return Stack(body, plinth)


def _random_pulse(rng):
    shape = RickerSymmetric if rng.random() < 0.5 else OneSine
    return shape(float(rng.uniform(0.1, 0.8)) * G, float(rng.uniform(0.3, 1.5)))


def test_simulate_many_runs_stacks_and_blocks_in_order():
    from rockcli.solve import simulate, simulate_many, simulate_stack

    rng = np.random.default_rng(5)
    jobs = []
    for _ in range(6):
        st, pulse = _random_stack(rng), _random_pulse(rng)
        jobs += [(st, Rigid(), pulse, 1.3), (st.body, Rigid(), pulse)]
    res = simulate_many(jobs)
    for job, r in zip(jobs, res):
        if isinstance(job[0], Stack):
            ref = simulate_stack(job[0], job[2].scaled(job[3]))
            assert r.verdict == ref.verdict and r.theta_max_over_alpha == ref.body.theta_max_over_alpha
            assert r.overturned == (ref.toppled is not None)
        else:
            assert r.verdict == simulate(*job).verdict
    from rockcli.models import LinearIsolation, SingleConcaveSliding

    bearings = LinearIsolation(2.0, 0.1, 0.01)
    on, ref = simulate_many([(jobs[0][0], bearings, jobs[0][2])])[0], simulate_stack(jobs[0][0], jobs[0][2],
                                                                                    isolation=bearings)
    assert on.verdict == ref.verdict and on.base_disp_max_m == ref.base_disp_max > 0.0
    sliding = SingleConcaveSliding(3.0, 0.05)
    on, ref = simulate_many([(jobs[0][0], sliding, jobs[0][2])])[0], simulate_stack(jobs[0][0], jobs[0][2],
                                                                                   isolation=sliding)
    assert on.verdict == ref.verdict and on.base_disp_max_m == ref.base_disp_max > 0.0
    bad = simulate_many([(jobs[0][0], SingleConcaveSliding(3.0, 0.05, gamma=0.0), jobs[0][2])])[0]
    assert bad.verdict == "error" and "gamma = 0" in bad.error


def test_stacks_on_threads_are_the_serial_loop_bit_for_bit(monkeypatch):
    """The stack jobs of a batch run on a pool of threads (the drivers are compiled nogil): every result, in job
    order, is the one the plain loop gives, bit for bit (repr of a float is exact), a refused job keeps its place,
    and progress rises by one from ``done`` to ``done + n``."""
    import rockcli.solve.pool as pool
    from rockcli.models import LinearIsolation, SingleConcaveSliding
    from rockcli.solve.stack_many import simulate_stacks

    rng = np.random.default_rng(36)
    jobs = []
    for i in range(24):
        st, pulse = _random_stack(rng), _random_pulse(rng)
        base = LinearIsolation(float(rng.uniform(1.0, 3.0)), 0.1, 0.3) if i % 3 == 0 else Rigid()
        jobs.append((st, base, pulse, float(rng.uniform(0.8, 2.0))))
    jobs.insert(7, (jobs[0][0], SingleConcaveSliding(3.0, 0.05, gamma=0.0), jobs[0][2]))  # refused: gamma = 0
    runs = {}
    for threads in (1, 3):
        monkeypatch.setattr(pool, "_threads", lambda: threads)
        seen = []
        runs[threads] = simulate_stacks(jobs, progress=seen.append, done=5)
        assert seen == list(range(6, 6 + len(jobs)))
    assert runs[3][7].error and "gamma = 0" in runs[3][7].error
    assert [repr(r) for r in runs[3]] == [repr(r) for r in runs[1]]
    assert sum(r.verdict == "overturned" for r in runs[1] if not getattr(r, "error", "")) >= 3


def test_the_stack_s_liftoff_floor_is_exact_on_random_scenes():
    """The floor (the smaller static threshold over the motion's peak, docs/plinth.md): at the floor nothing lifts
    and the run is proven (2,000 random stacks and pulses); just above it something lifts (the floor is tight: a
    pulse reaches its peak)."""
    from rockcli.assess.liftoff import liftoff_floors
    from rockcli.solve import simulate_many

    rng = np.random.default_rng(2026)
    scenes = [(_random_stack(rng), Rigid(), _random_pulse(rng)) for _ in range(2000)]
    floors = liftoff_floors(scenes)
    for (st, _, pulse), f in zip(scenes[:5], floors[:5]):
        assert f == pytest.approx(st.uplift_acceleration / abs(pulse.a_p), rel=1e-8)
    at = simulate_many([(*s, f) for s, f in zip(scenes, floors)])
    assert all(r.verdict == "no_uplift" and r.settled for r in at)
    above = simulate_many([(*s, f * (1 + 1e-6)) for s, f in zip(scenes[:300], floors[:300])])
    assert all(r.verdict != "no_uplift" for r in above)


def test_the_margin_search_with_the_floor_is_the_full_scan(monkeypatch):
    """The margin search of random stacks starting at the floor equals the scan of every factor (floor 0)."""
    import rockcli.assess.liftoff as liftoff
    from rockcli.assess import find_overturn_scales

    rng = np.random.default_rng(11)
    scenes = [(_random_stack(rng), Rigid(), _random_pulse(rng)) for _ in range(40)]
    grid = np.geomspace(0.1, 4.0, 60)
    fast = find_overturn_scales(scenes, grid=grid)
    monkeypatch.setattr(liftoff, "liftoff_floor", lambda *a, **k: 0.0)
    full = find_overturn_scales(scenes, grid=grid)
    assert fast == full
    assert sum(math.isfinite(s) for s, _, _ in fast) >= 5  # some scenes topple within the grid


# ---------------------------------------------------------------------------------------------------------------
# assess --on
# ---------------------------------------------------------------------------------------------------------------

def test_assess_column_on_a_plinth_compares_with_the_statue_alone():
    code, out = _run("assess", "column", STATUE, "--on", "plinth:height=1.0,width=0.6", "--records", KOBE,
                     "--records", "superstition-1987-parachute-225")
    assert code == 0, out
    assert "statue on plinth" in out and "Does the plinth help?" in out
    assert "left out of the default set" not in out  # the default set's linear bearings run with a plinth
    d = _json("assess", "column", STATUE, "--on", "plinth:height=1.0,width=0.6", "--records", KOBE,
              "--records", "superstition-1987-parachute-225", "--isolation", "none")
    rows = {(r["column"], r["record"]): r for r in d["rows"]}
    assert {c for c, _ in rows} == {"statue", "statue on plinth"}
    assert {r["configuration"] for r in d["rows"]} == {"none"}
    for (col, rec), r in rows.items():
        if col == "statue on plinth":
            assert r["plinth"].startswith("plinth:height=1,width=0.6")
            assert r["toppled"] in ("", "body", "plinth") and (r["toppled"] != "") == r["overturned"]
            assert math.isfinite(r["overturn_scale"]) or r["margin_note"]
            assert r["friction_demand_base"] >= 0
        else:
            assert r["plinth"] == "" and r["toppled"] == ""
    # the statue alone is the statue's own assessment
    alone = _json("assess", "column", STATUE, "--records", KOBE, "--isolation", "none")["rows"][0]
    mine = rows[("statue", KOBE)]
    for key in ("verdict", "theta_max_over_alpha", "overturn_scale", "overturn_scale_survives"):
        assert mine[key] == alone[key]


def test_assess_refuses_named_bearings_under_an_infinitely_heavy_base_with_a_plinth():
    code, out = _run("assess", "column", STATUE, "--on", "plinth:height=1.0,width=0.6", "--records", KOBE,
                     "--isolation", "none", "--isolation", "scss:Tb=3,mu=0.05,gamma=0")
    assert code == 2 and "gamma = 0" in out and "--isolation none or bearings with gamma > 0" in out
    code, out = _run("assess", "column", STATUE, "--on", "plinth:height=1.0,width=0.3", "--records", KOBE)
    assert code == 2 and "no wider than its plinth" in out


def test_the_plinth_sentence():
    """'Does the plinth help?' from rows whose verdicts differ both ways, and with equal verdicts the margins."""
    from types import SimpleNamespace as NS

    from rockcli.assess.verdicts import plinth_summary
    from rockcli.models import parse_isolation_spec

    statue = Block.from_dimensions(1.79, 0.5, "statue")
    st = Stack(statue, Plinth(1.0, 0.6))
    conf = NS(header="none", foundation=parse_isolation_spec("none"), isolated=False)
    xs = [NS(label=f"r{i}", motion=object()) for i in range(3)]

    def row(over, scale, peak=0.5):
        return NS(error="", overturned=over, proven=True, overturn_scale=scale, theta_max_over_alpha=peak,
                  verdict="overturned" if over else "rocked", record="")

    def words(alone, onp):
        table = {}
        for (name, rows) in ((statue.name, alone), (st.name, onp)):
            for x, r in zip(xs, rows):
                r.record = x.label
                table[(name, x.label)] = r
        a = NS(columns=[statue, st], excitations=xs, configurations=[conf],
               row=lambda c, x, h: table[(c, x)])
        return plinth_summary(a, st)

    def rows(*args):
        return [row(*a) for a in args]

    worse = words(rows(*[(False, 1.5)] * 3), rows((True, 0.8), (False, 1.2), (False, 1.2)))
    assert "makes it worse" in worse and "under r0," in worse and "1 of 3 records topple it on its plinth" in worse
    better = words(rows((True, 0.8), (False, 1.5), (False, 1.5)), rows(*[(False, 1.3)] * 3))
    assert "makes it better" in better and "under r0," in better
    same = words(rows(*[(False, 1.5)] * 3), rows(*[(False, 1.505)] * 3))
    assert "changes no verdict" in same and "no difference in the margin" in same
    less = words(rows(*[(False, 1.5)] * 3), rows(*[(False, 1.2)] * 3))
    assert "by the margin its plinth makes it worse" in less


def test_does_the_plinth_help_is_a_list_of_one_sentence_per_configuration(tmp_path):
    """The printout and the report give "Does the plinth help?" as one item per configuration (four sentences in
    one paragraph were hard to read), each naming its configuration, in the order of the table's columns."""
    import re

    report = tmp_path / "r.html"
    code, out = _run("assess", "column", STATUE, "--on", "plinth:height=1.0,width=0.6", "--records", KOBE,
                     "--no-margin", "--isolation", "none", "--isolation", "linear:Tb=2.5", "--report", str(report))
    assert code == 0, out
    lines = out.splitlines()
    k = lines.index("  Does the plinth help?")
    items = [line for line in lines[k + 1:] if line.startswith("  - ")]
    assert [i.split(",")[0] for i in items] == ["  - Standing on the ground", "  - On linear (rubber) bearings"]
    html = report.read_text(encoding="utf-8")
    listed = re.search(r"Does the plinth help\?</p><ul class='short'>(.*?)</ul>", html, re.S).group(1)
    assert [li.split(",")[0] for li in re.findall(r"<li>(.*?)</li>", listed)] == [
        "Standing on the ground", "On linear (rubber) bearings"]


def test_assess_fragility_on_a_plinth_fits_the_body_alone_and_on_it():
    import re

    code, out = _run("assess", "fragility", STATUE, "--on", "plinth:height=1.0,width=0.6", "--records", KOBE,
                     "--records", "superstition-1987-parachute-225", "--bootstrap", "0")
    assert code == 0, out
    medians = {m.group(1).strip(): float(m.group(2)) for m in
               re.finditer(r"^(statue(?: on plinth)?)\s+none\s+\d+\s+\d+\s+\d+\s+([0-9.]+)", out, re.M)}
    assert set(medians) == {"statue", "statue on plinth"}
    ratio = re.search(r"median capacity of statue on plinth over statue alone = ([0-9.]+)", out)
    assert ratio and float(ratio.group(1)) == pytest.approx(medians["statue on plinth"] / medians["statue"], abs=0.006)
