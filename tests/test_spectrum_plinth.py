"""The spectra with a body on a free plinth (``rockcli spectrum ... --on``, :mod:`rockcli.spectra.plinth`): the
scaling theorem (a plinth in proportion to the body leaves the spectrum dimensionless), a plinth that cannot lift,
a spectrum cell against ``simulate --on``, the minimum search's uplift threshold, and bad ``--on`` values.

Cheap by design: short pulses (omega_p/p >= 1 on the 1 m reference block, T_p <= 2.3 s), a few dozen cells."""

from __future__ import annotations

import csv
import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.spectra import Family, Grid, overturning_maps, parse_isolation, parse_pulse_choice, run_cells_local
from rockcli.spectra.minimum import min_overturning_curves
from rockcli.spectra.plinth import PlinthRatio, parse_plinth_ratio

ON = "plinth:height_ratio=0.6,width_ratio=1.4"


def _run(*args):
    res = CliRunner().invoke(main, list(args))
    return res.exit_code, res.output


# ---------------------------------------------------------------------------------------------------------------
# The scaling theorem (docs/spectra.md, "A body on a free plinth")
# ---------------------------------------------------------------------------------------------------------------

@pytest.mark.parametrize("iso", ["none", "linear:TbTp=2.5,xi=0.1,gamma=0.05"])
def test_two_body_sizes_with_the_same_ratios_give_the_same_spectrum(iso):
    """Every length scaled by 4.3 (the body, and its plinth through the ratios), the same omega_p/p and
    a_p/(g tan alpha): the same verdict, uplift and toppled block at every one of 30 random cells, the peak within
    1e-9 (measured: 3e-12, and the same number of right-hand sides: the driver's steps scale exactly)."""
    rng = np.random.default_rng(36)
    n = 30
    x, y = rng.uniform(1.0, 8.0, n), rng.uniform(0.8, 6.0, n)
    fams = [Family(math.radians(12), "ricker-anti", parse_isolation(iso), R, PlinthRatio(0.6, 1.4, 2.0))
            for R in (1.0, 4.3)]
    a = run_cells_local(fams, np.zeros(n, int), x, y)
    b = run_cells_local(fams, np.ones(n, int), x, y)
    assert 0 < a.overturned.sum() < n and a.uplifted.sum() > a.overturned.sum()  # all three outcomes are tried
    np.testing.assert_array_equal(a.overturned, b.overturned)
    np.testing.assert_array_equal(a.uplifted, b.uplifted)
    np.testing.assert_array_equal(a.toppled, b.toppled)
    np.testing.assert_allclose(a.theta_max_over_alpha, b.theta_max_over_alpha, rtol=1e-9, atol=1e-12)
    assert a.peak_final.all() and b.peak_final.all()  # the stack driver has no early stop during the pulse


# ---------------------------------------------------------------------------------------------------------------
# Limits and exactness
# ---------------------------------------------------------------------------------------------------------------

def test_a_plinth_that_cannot_lift_gives_the_body_alone_spectrum():
    """A plinth 20 times as wide as the body and 1000 times as heavy would need a_p above 8 g tan(alpha) to lift
    with the body (its static threshold, 1.5 times the grid's top here), so on the rigid foundation the body rocks
    on it as on the ground: the same verdict, uplift and peak at every cell of the map (``--full-peaks``: the
    same peaks too, the single block's solver and the stack's on the same body)."""
    plinth = PlinthRatio(0.1, 20.0, 1000.0)
    st = plinth.stack(Family(math.radians(14), "sine", parse_isolation("none")).block)
    assert st.assembly_uplift_acceleration / st.body_uplift_acceleration > 1.5 * 6.0
    alone, on = overturning_maps([14], [parse_pulse_choice("sine")], [parse_isolation("none")], Grid(1.0, 7.0, 5),
                                 Grid(0.5, 6.0, 6), plinths=[None, plinth])
    assert on.plinth is plinth and alone.plinth is None
    assert 0 < alone.overturned.sum() < alone.overturned.size
    np.testing.assert_array_equal(alone.overturned, on.overturned)
    np.testing.assert_array_equal(alone.uplifted, on.uplifted)
    assert not (on.toppled == 2).any()  # the plinth never topples
    np.testing.assert_allclose(on.theta_max_over_alpha, alone.theta_max_over_alpha, rtol=1e-12, atol=0)


def test_a_spectrum_cell_is_the_simulate_on_run():
    """One cell of ``spectrum overturning --on`` (the reference block R = 1 m, alpha = 12 deg) against ``rockcli
    simulate --on`` of that block with the plinth in metres, the pulse's a_p in g and T_p in s: the same verdict,
    toppled block and peak (to rounding: a_p goes through g once more on the command line)."""
    from rockcli.io.units import G
    from rockcli.models import Block

    body = Block.from_degrees(1.0, 12.0)
    for x, y, iso, iso_sim in [(3.0, 2.2, "none", "none"), (4.0, 4.0, "none", "none"),
                               (2.5, 2.6, "linear:TbTp=2,xi=0.1,gamma=0.05", None)]:
        code, out = _run("spectrum", "overturning", "--alpha", "12", "--wp-over-p", f"{x}:{x}:1", "--ap", f"{y}:{y}:1",
                         "--isolation", iso, "--on", ON, "--json")
        assert code == 0, out
        maps = json.JSONDecoder().raw_decode(out)[0]["maps"]  # the summary follows on stderr
        assert [m["plinth"] for m in maps] == [None, ON]
        cell = {k: v[0] for k, v in maps[1]["cells"].items()}
        T_p = 2 * math.pi / (x * body.p)
        ap_g = y * math.tan(body.alpha)
        iso_sim = iso_sim or f"linear:Tb={2 * T_p!r},xi=0.1,gamma=0.05"
        code, out = _run("simulate", "--R", "1", "--alpha", "12", "--pulse", f"ricker-sym:ap={ap_g!r},Tp={T_p!r}",
                         "--isolation", iso_sim, "--on", f"plinth:height={0.6 * body.height!r},width={1.4 * body.width!r}",
                         "--json")
        assert code == 0, out
        sim = json.JSONDecoder().raw_decode(out)[0]
        assert cell["overturned"] == (sim["verdict"] == "overturned")
        assert cell["toppled"] == (sim["toppled"] or "")
        assert cell["uplift"] == (sim["verdict"] != "no_uplift")
        assert cell["theta_max_over_alpha"] == pytest.approx(sim["body"]["theta_max_over_alpha"], rel=1e-7)
        assert abs(G * ap_g - y * G * math.tan(body.alpha)) < 1e-12


def test_the_minimum_on_a_plinth_starts_at_the_static_uplift_threshold():
    """A tall narrow plinth lifts with the body before the body lifts off it: the search's uplift threshold is the
    assembly's, tan(alpha_asm)/tan(alpha1) < 1, checked by two runs (nothing lifts there, something lifts 1e-7
    above); on linear bearings the bisection's. Every minimum overturns and the value within tol below does not:
    both re-run here on the stack driver, the same verdicts."""
    plinth = PlinthRatio(1.5, 1.0)
    fam = Family(math.radians(15), "ricker-sym", parse_isolation("none"), plinth=plinth)
    st = fam.body
    expect = st.assembly_uplift_acceleration / st.body_uplift_acceleration
    assert expect < 1.0
    curves = min_overturning_curves([15], ["ricker-sym"], ["none", "linear:TbTp=2"], np.array([2.0, 5.0]),
                                    step=0.1, refine=0.01, plinths=[plinth])
    rigid, iso = curves
    np.testing.assert_array_equal(rigid.ap_uplift, [expect, expect])
    assert np.isfinite(iso.ap_uplift).all()
    for c in curves:
        f = Family(math.radians(15), "ricker-sym", c.isolation, plinth=plinth)
        ok = np.isfinite(c.ap_min)
        assert ok.any()
        xs = np.concatenate([c.wp_over_p[ok]] * 2)
        ys = np.concatenate([c.ap_min[ok], c.ap_safe[ok]])
        r = run_cells_local([f], np.zeros(xs.size, int), xs, ys)
        k = int(ok.sum())
        assert r.overturned[:k].all() and not r.overturned[k:].any()


# ---------------------------------------------------------------------------------------------------------------
# The command line
# ---------------------------------------------------------------------------------------------------------------

def test_the_csv_names_the_plinth_and_the_toppled_block(tmp_path):
    out = tmp_path / "m.csv"
    code, text = _run("spectrum", "overturning", "--alpha", "12", "--wp-over-p", "2:4:2", "--ap", "1:5:3", "--on", ON,
                      "--csv", str(out), "--plot", str(tmp_path / "m.png"))
    assert code == 0, text
    assert (tmp_path / "m.png").stat().st_size > 10_000  # drawn (the hatching of the plinth's topples was looked at by hand)
    rows = list(csv.DictReader(out.open()))
    assert len(rows) == 12 and {r["plinth"] for r in rows} == {"", ON}
    assert {r["toppled"] for r in rows if r["plinth"] == ""} <= {""}
    assert {r["toppled"] for r in rows if r["overturned"] == "True" and r["plinth"]} <= {"body", "plinth"}
    assert " on " + ON in text and " alone:" in text


@pytest.mark.parametrize("args, words", [
    (("--on", "plinth:height=1,width=0.6"), "in proportion to the body"),
    (("--on", "plinth:height_ratio=0.5"), "needs width_ratio"),
    (("--on", "plinth:height_ratio=0.5,width_ratio=0.8"), "width_ratio"),
    (("--on", "plinth:height_ratio=0.5,width_ratio=2,colour=red"), "is not one of"),
    (("--on", "plinth:height_ratio=0.5,width_ratio=2,mass_ratio=1e6"), "mass_ratio"),
    (("--on", "plinth"), "must be written"),
    (("--on", ON, "--isolation", "scss:TbTp=2,mu=0.05,gamma=0"), "gamma > 0"),  # an infinitely heavy base
    (("--on", ON, "--cap-ratio", "0.5"), "--cap-ratio"),
    (("--on", ON, "--vertical-pulse", "sine:ap=0.2"), "--vertical-pulse"),
])
def test_bad_on_values_exit_2_with_one_sentence(args, words):
    code, out = _run("spectrum", "overturning", "--alpha", "12", "--wp-over-p", "2:2:1", "--ap", "2:2:1", *args)
    assert code == 2, out
    assert words in out and "Traceback" not in out and len(out.strip().splitlines()) == 1, out


def test_min_overturning_refuses_a_plinth_in_metres():
    code, out = _run("spectrum", "min-overturning", "--alpha", "12", "--wp-over-p", "2:2:1", "--on",
                     "plinth:height=1,width=0.6")
    assert code == 2 and "height_ratio" in out, out


def test_parse_plinth_ratio_reads_the_spec():
    p = parse_plinth_ratio("pedestal:height_ratio=0.25,width_ratio=1.2,mass_ratio=3")
    assert (p.name, p.height_ratio, p.width_ratio, p.mass_ratio) == ("pedestal", 0.25, 1.2, 3.0)
    assert p.label == "pedestal:height_ratio=0.25,width_ratio=1.2,mass_ratio=3"
    assert parse_plinth_ratio(p.label) == p


def test_the_rocking_spectrum_on_a_plinth_is_the_stack_run_of_each_size(tmp_path):
    """``spectrum rocking --on``: each size's point on the plinth is the stack driver's run of that body on the plinth
    scaled with it (the same verdict, toppled block and peak, bit for bit: the same run), the block-alone curve is
    the one without ``--on``, and the CSV names the plinth."""
    from conftest import write_pulse_record

    from rockcli.models import Block, Rigid
    from rockcli.records import read_record
    from rockcli.solve.stack_many import run_stack

    path = write_pulse_record(tmp_path / "ricker.txt", a_p_g=0.5, T_p=0.6, pad=2.0)
    args = ["spectrum", "rocking", str(path), "--alpha", "14", "--R", "0.3:3:4", "--json"]
    code, out = _run(*args, "--on", ON)
    assert code == 0, out
    on = json.JSONDecoder().raw_decode(out)[0]["curves"]
    code, out = _run(*args)
    assert code == 0, out
    alone = json.JSONDecoder().raw_decode(out)[0]["curves"]
    assert [c["plinth"] for c in on] == [None, ON]
    assert {k: v for k, v in on[0].items() if k != "plinth"} == alone[0]
    record = read_record(str(path))
    plinth = parse_plinth_ratio(ON)
    curve = on[1]
    assert any(curve["overturned"]) and not all(curve["overturned"])
    for i, R in enumerate(curve["R_m"]):
        res = run_stack(plinth.stack(Block.from_degrees(R, 14.0)), Rigid(), record)
        assert curve["overturned"][i] == (res.toppled is not None)
        assert curve["toppled"][i] == (res.toppled or "")
        assert curve["theta_max_over_alpha"][i] == res.body.theta_max_over_alpha


def test_chunks_as_a_scheduler_runs_them_give_the_one_batch():
    """What ``--scheduler`` does with cells on a plinth, without a cluster: the families pickled, the cells cut into
    chunks of 7 run by the worker task, the chunks' Cells put together: the same arrays as one batch here (the CLI
    writes the same CSV with and without ``--scheduler local``: checked by hand, 18 cells)."""
    import pickle

    from rockcli.spectra.runner import Cells, _run_cells_task

    fams = [Family(math.radians(12), "sine", parse_isolation("none")),
            Family(math.radians(12), "sine", parse_isolation("none"), plinth=PlinthRatio(0.6, 1.4))]
    rng = np.random.default_rng(7)
    n = 20
    fam, x, y = rng.integers(0, 2, n), rng.uniform(1.0, 6.0, n), rng.uniform(0.5, 5.0, n)
    one = run_cells_local(fams, fam, x, y)
    shipped = pickle.loads(pickle.dumps(tuple(fams)))
    parts = [_run_cells_task((shipped, fam[lo:lo + 7], x[lo:lo + 7], y[lo:lo + 7], False, None, None, 0.0, None))
             for lo in range(0, n, 7)]
    both = Cells.concatenate(parts)
    for f in ("overturned", "uplifted", "theta_max_over_alpha", "settled", "toppled"):
        np.testing.assert_array_equal(getattr(both, f), getattr(one, f))
    assert (one.toppled[fam == 0] == 0).all() and one.overturned.any()


def test_uplift_only_runs_give_the_full_runs_uplift_and_end_a_chatter():
    """The minimum search asks stack runs only whether something lifts (``uplift_only``): they stop at 20,000 steps,
    exact for that flag (a lift is recorded when it happens; a run stopped before any lift is run again in full).
    20 random cells around the thresholds on linear bearings: the same flags as the full runs. And the cell the
    search met just above a threshold (alpha 10 deg, T_b/T_p = 4, omega_p/p = 3.5), where the body lifts by a hair
    (the stack driver chattered there to its 5-million-step cap until the hair-lift rule, docs/physics-plinth.md "A
    lift below the tolerance"): lifted, and the full run, too, now ends in a normal number of steps."""
    from rockcli.spectra.runner import UPLIFT_ONLY_STEPS

    plinth = PlinthRatio(0.5, 1.5)
    fam = [Family(math.radians(10), "ricker-sym", parse_isolation("linear:TbTp=2"), plinth=plinth)]
    rng = np.random.default_rng(3)
    x, y = rng.uniform(1.0, 6.0, 20), rng.uniform(1.0, 2.5, 20)
    full = run_cells_local(fam, np.zeros(20, int), x, y)
    quick = run_cells_local(fam, np.zeros(20, int), x, y, uplift_only=True)
    assert 0 < full.uplifted.sum() < 20
    np.testing.assert_array_equal(quick.uplifted, full.uplifted)
    chatter = [Family(math.radians(10), "ricker-sym", parse_isolation("linear:TbTp=4"), plinth=plinth)]
    c = run_cells_local(chatter, np.zeros(1, int), np.array([3.5]), np.array([8.421630859375]), uplift_only=True)
    assert c.uplifted[0]
    f = run_cells_local(chatter, np.zeros(1, int), np.array([3.5]), np.array([8.421630859375]))
    assert f.uplifted[0] and f.settled[0] and f.nfev[0] < UPLIFT_ONLY_STEPS  # no chatter: no cap needed
