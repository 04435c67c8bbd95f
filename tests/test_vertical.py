"""``vertical=`` / ``--vertical``: a vertical ground acceleration on a rigid foundation (issue 27 item 3).

Gravity becomes ``g + a_v`` in Eq (3), in the uplift threshold and in the rest rule; the early stops and
end-of-run proofs are re-proved for it (rockcli.kernels.rigid, PV). Checked here: a constant a_v is the
block of gravity g + a_v (by the exact scaling R -> R g/(g + a_v), a_p -> a_p g/(g + a_v)); the three
verdict paths agree on random scenes with random vertical motions; the slow SciPy reference agrees; the
refusals; the command line."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from naive import reference_simulate
from rockcli.errors import RockcliInputError
from rockcli.models import Block, LinearIsolation, Rigid
from rockcli.pulses import make_pulse
from rockcli.records import Record
from rockcli.solve import simulate, simulate_many
from rockcli.io.units import G
from synthetic import synthetic_record

SHAPES = ("ricker-sym", "ricker-anti", "sine", "cosine")


def _constant(a_v, duration, dt=0.01):
    """A constant vertical acceleration ``a_v`` from t = 0 to ``duration``."""
    return Record(np.full(int(round(duration / dt)) + 1, float(a_v)), dt, "constant")


def _scaled_twin(block, shape, a_p, T_p, a_v, t0=None):
    """The block and pulse that, under g alone, obey the same equation as (block, pulse) under g + a_v:
    ``p^2 = 3 g/(4 R)`` times ``(g + a_v)/g``, ``a_p`` over ``g`` kept."""
    c = G / (G + a_v)
    kw = {} if t0 is None else {"t0": t0}
    return Block(block.R * c, block.alpha), make_pulse(shape, a_p * c, T_p, **kw)


# ------------------------------------------------------------------------------------------
# A constant vertical acceleration is a change of gravity
# ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("a_v", [-0.4 * G, -0.1 * G, 0.25 * G, 0.6 * G])
@pytest.mark.parametrize("shape", SHAPES)
def test_constant_vertical_is_the_block_of_gravity_g_plus_av(a_v, shape):
    """A map cell: the same verdict, uplift time and peak as the scaled twin, for rocking and overturning
    cells (the vertical motion lasts past the end of the rocking)."""
    rng = np.random.default_rng([SHAPES.index(shape), int(round(1000 * a_v / G)) + 1000])
    seen = set()
    for _ in range(8):
        block = Block(math.exp(rng.uniform(math.log(0.3), math.log(5.0))), rng.uniform(0.1, 0.3))
        T_p = 2 * math.pi / (rng.uniform(1.0, 8.0) * block.p)
        a_p = rng.uniform(1.1, 4.0) * (G + a_v) * math.tan(block.alpha) * rng.choice([-1.0, 1.0])
        pulse = make_pulse(shape, a_p, T_p)
        # at rtol 1e-10: the two runs take different steps (the vertical series cuts them at its samples),
        # so they differ by the integration error (3e-9 rad on a 7e-4 rad peak at the default 5e-9)
        vert = simulate(block, Rigid(), pulse, vertical=_constant(a_v, pulse.support()[1] + 200.0), rtol=1e-10)
        twin_block, twin_pulse = _scaled_twin(block, shape, a_p, T_p, a_v, pulse.t0)
        twin = simulate(twin_block, Rigid(), twin_pulse, horizon=300.0, rtol=1e-10)
        seen.add(vert.verdict)
        assert vert.verdict == twin.verdict
        assert vert.t_uplift_s == pytest.approx(twin.t_uplift_s, rel=1e-12)
        if vert.overturned:
            assert vert.t_overturn_s == pytest.approx(twin.t_overturn_s, rel=1e-7)
        else:
            assert vert.theta_max == pytest.approx(twin.theta_max, rel=1e-6, abs=1e-9)
    assert seen <= {"rocked", "overturned"}


def test_constant_vertical_moves_the_uplift_threshold_to_g_plus_av_tan_alpha():
    block = Block(1.5, 0.2)
    for a_v in (-0.3 * G, 0.3 * G):
        thr = (G + a_v) * math.tan(block.alpha)
        vertical = _constant(a_v, 30.0)
        for f, verdict in ((0.999, "no_uplift"), (1.001, "rocked")):
            r = simulate(block, Rigid(), make_pulse("sine", f * thr, 0.3), vertical=vertical)
            assert r.verdict == verdict, (a_v, f)


def _threshold(block, T_p, vertical, lo, hi, n=18):
    """The smallest sine-pulse amplitude [m/s^2] in [lo, hi] that overturns the block (bisection)."""
    for _ in range(n):
        mid = 0.5 * (lo + hi)
        if simulate(block, Rigid(), make_pulse("sine", mid, T_p), vertical=vertical).overturned:
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("a_v", [-0.3 * G, 0.4 * G])
def test_the_overturning_threshold_scales_with_g_plus_av(a_v):
    """A sine pulse's minimum overturning amplitude under g + a_v is (g + a_v)/g times the scaled twin's."""
    block, T_p = Block(1.0, 0.2), 1.2
    c = G / (G + a_v)
    twin = Block(block.R * c, block.alpha)
    base = _threshold(twin, T_p, None, 0.5 * G * math.tan(block.alpha), 20.0 * G * math.tan(block.alpha))
    got = _threshold(block, T_p, _constant(a_v, 200.0), base / c * 0.9, base / c * 1.1)
    assert got == pytest.approx(base / c, rel=2e-5)
    assert abs(got / base - 1) > 0.1  # it did move


# ------------------------------------------------------------------------------------------
# The verdict paths and the reference
# ------------------------------------------------------------------------------------------
def _random_vertical(rng, horizontal, dt):
    """A random vertical motion: a noise record on the horizontal record's time base (shorter or longer),
    or a pulse; PGA up to 0.9 g, so g + a_v > 0."""
    if rng.random() < 0.5:
        duration = rng.uniform(2.0, 20.0)
        rec = synthetic_record(int(rng.integers(1_000_000)), duration=duration, dt=dt, pga=rng.uniform(0.05, 0.9) * G)
        return rec if rng.random() < 0.5 else rec.scaled(-1.0)
    T_p = rng.uniform(0.1, 1.5)
    shape = SHAPES[int(rng.integers(4))]
    unit = make_pulse(shape, 1.0, T_p)
    return make_pulse(shape, rng.uniform(-0.9, 0.9) * G, T_p, t0=unit.t0 + rng.uniform(0.0, 6.0))


def random_vertical_scenes(n, seed):
    """Rigid-foundation scenes: a noise record or a pulse horizontally, a random vertical motion."""
    rng = np.random.default_rng(seed)
    recs = [synthetic_record(500 + k, duration=8.0, pga=0.5 * G) for k in range(10)]
    jobs = []
    for i in range(n):
        block = Block(math.exp(rng.uniform(math.log(0.2), math.log(20.0))), rng.uniform(0.05, 0.4))
        if i % 2:
            horizontal = recs[i % 10].scaled(rng.uniform(0.3, 3.0))
        else:
            T_p = 2 * math.pi / (rng.uniform(0.5, 12.0) * block.p)
            a_p = rng.uniform(0.8, 8.0) * G * math.tan(block.alpha) * rng.choice([-1.0, 1.0])
            unit = make_pulse(SHAPES[i % 4], 1.0, T_p)
            horizontal = make_pulse(SHAPES[i % 4], a_p, T_p, t0=unit.t0 + rng.uniform(0.0, 3.0))
        jobs.append((block, horizontal, _random_vertical(rng, horizontal, 0.01)))
    return jobs


@pytest.mark.parametrize("chunk", range(4))
def test_three_verdict_paths_agree_under_random_vertical_motions(chunk):
    """Early (P4, P6, P7 with the vertical impulse) and verdict-only (P1, P2 after both motions) runs through
    the batch machinery (simulate_many, one vertical motion per scene), and full history runs: the same
    verdict, impacts and peak; an early peak never above the true one. 2,000 scenes."""
    jobs = random_vertical_scenes(2000, 27)[chunk::4]
    scenes = [(block, Rigid(), horizontal) for block, horizontal, _ in jobs]
    verticals = [vertical for _, _, vertical in jobs]
    early = simulate_many(scenes, early=True, vertical=verticals)
    verdict_only = simulate_many(scenes, vertical=verticals)
    mismatches, verdicts = [], []
    for i, (block, horizontal, vertical) in enumerate(jobs):
        e, v = early[i], verdict_only[i]
        h = simulate(block, Rigid(), horizontal, vertical=vertical, history=True)
        verdicts.append(v.verdict)
        same = e.verdict == v.verdict == h.verdict and v.n_impacts == h.n_impacts and v.settled == h.settled
        same = same and v.theta_max == pytest.approx(h.theta_max, rel=1e-6, abs=1e-15)
        same = same and e.theta_max <= h.theta_max * (1 + 1e-7) + 1e-15
        if e.peak_final:
            same = same and e.theta_max == pytest.approx(h.theta_max, rel=1e-7, abs=1e-15)
        if v.overturned:
            same = same and v.t_overturn_s == h.t_overturn_s
        if not same:
            mismatches.append((i, e.verdict, v.verdict, h.verdict, v.theta_max, h.theta_max))
    assert mismatches == []
    assert min(verdicts.count(x) for x in ("no_uplift", "rocked", "overturned")) > 10
    assert sum(not r.peak_final for r in early) > 10  # the early stops (P4, P6, P7) do fire
    for i in range(0, len(jobs), 25):  # the batch entry is the single run's kernel: bit for bit
        block, horizontal, vertical = jobs[i]
        for many, kw in ((early[i], {"early": True}), (verdict_only[i], {})):
            one = simulate(block, Rigid(), horizontal, vertical=vertical, **kw)
            assert repr(many.summary()) == repr(one.summary()), (chunk, i)


def _as_series(vertical):
    """The kernel's piecewise-linear series of a vertical motion, for the reference."""
    from rockcli.solve.excitation import _vertical_arrays

    vacc, _, vdt, _, _ = _vertical_arrays(vertical, None, None, G)
    return vacc, vdt


@pytest.mark.parametrize("chunk", range(2))
def test_agreement_with_the_slow_reference_under_vertical_motion(chunk):
    """Against the SciPy reference with g + a_v typed in (rockcli.reference.linear): 12 scenes with vertical
    records (a sampled vertical pulse costs the reference minutes; 80 scenes of both kinds agree, README)."""
    jobs = [j for j in random_vertical_scenes(40, 8) if isinstance(j[2], Record)][:12][chunk::2]
    for i, (block, horizontal, vertical) in enumerate(jobs):
        ref = reference_simulate(block, Rigid(), horizontal, vertical=_as_series(vertical), align=True)
        fast = simulate(block, Rigid(), horizontal, vertical=vertical, rtol=1e-10)
        assert fast.verdict == ref.verdict, (chunk, i)
        if fast.verdict == "rocked":
            assert fast.theta_max == pytest.approx(ref.theta_max, rel=2e-6, abs=1e-8 * block.alpha), (chunk, i)
        if fast.overturned:
            assert fast.t_overturn_s == pytest.approx(ref.t_overturn, rel=1e-6), (chunk, i)
        assert fast.t_uplift_s == pytest.approx(ref.t_uplift, rel=1e-8, nan_ok=True), (chunk, i)


def test_no_vertical_and_a_zero_vertical_are_the_same_run():
    block, rec = Block(2.0, 0.2), synthetic_record(3, duration=8.0, pga=0.6 * G)
    plain = simulate(block, Rigid(), rec, history=True)
    zero = simulate(block, Rigid(), rec, history=True, vertical=Record(np.zeros(rec.acc.size), rec.dt, "zero"))
    assert plain.verdict == zero.verdict and plain.theta_max == zero.theta_max
    assert np.array_equal(plain.history.theta, zero.history.theta)


def test_simulate_many_takes_one_vertical_motion():
    rec = synthetic_record(4, duration=8.0, pga=0.6 * G)
    vertical = synthetic_record(5, duration=8.0, pga=0.5 * G)
    jobs = [(Block(R, 0.2), Rigid(), rec, s) for R, s in ((1.0, 1.0), (3.0, 2.0), (0.5, 0.7))]
    many = simulate_many(jobs, vertical=vertical)
    for (b, f, e, s), r in zip(jobs, many):
        one = simulate(b, f, e.scaled(s), vertical=vertical)
        assert r.verdict == one.verdict and r.theta_max == pytest.approx(one.theta_max, rel=1e-12)
    bad = simulate_many([(Block(1.0, 0.2), LinearIsolation(2.0, 0.1, 0.1), rec)], vertical=vertical)
    assert bad[0].verdict == "error" and "rigid foundation" in bad[0].error


# ------------------------------------------------------------------------------------------
# Refusals
# ------------------------------------------------------------------------------------------
def test_lift_off_is_refused():
    rec = synthetic_record(6, duration=5.0)
    down = Record(np.concatenate([np.zeros(100), [-1.01 * G], np.zeros(10)]), rec.dt, "down")
    with pytest.raises(RockcliInputError, match=r"g \+ a_v <= 0.*lift off"):
        simulate(Block(1.0, 0.2), Rigid(), rec, vertical=down)
    with pytest.raises(RockcliInputError, match="lift off"):
        simulate(Block(1.0, 0.2), Rigid(), rec, vertical=make_pulse("sine", -1.2 * G, 0.5))
    simulate(Block(1.0, 0.2), Rigid(), rec, vertical=down.scaled(0.9))  # g + a_v > 0 runs


def test_isolated_bases_and_other_time_bases_are_refused():
    rec = synthetic_record(7, duration=5.0)
    with pytest.raises(RockcliInputError, match="rigid foundation only.*normal force"):
        simulate(Block(1.0, 0.2), LinearIsolation(2.0, 0.1, 0.1), rec, vertical=rec.scaled(0.1))
    with pytest.raises(RockcliInputError, match="time base"):
        simulate(Block(1.0, 0.2), Rigid(), rec, vertical=Record(rec.acc * 0.1, 0.02, "v"))
    with pytest.raises(RockcliInputError, match="time base"):
        simulate(Block(1.0, 0.2), Rigid(), rec, vertical=Record(rec.acc * 0.1, rec.dt, "v", t_start=1.0))


# ------------------------------------------------------------------------------------------
# Command line
# ------------------------------------------------------------------------------------------
def _cli(args):
    from rockcli.cli import main

    return CliRunner().invoke(main, args)


def test_cli_vertical_pulse_and_json(tmp_path):
    base = ["simulate", "--R", "1", "--alpha", "12", "--pulse", "sine:ap=0.3,Tp=0.8", "--json"]
    plain = _cli(base)
    up = _cli(base + ["--vertical-pulse", "sine:ap=0.5,Tp=0.8"])
    assert plain.exit_code == 0 and up.exit_code == 0, up.output
    a, b = json.loads(plain.output), json.loads(up.output)
    assert "vertical" not in a and b["vertical"].startswith("sine pulse")
    assert a["theta_max"] != b["theta_max"]
    lib = simulate(Block(1.0, math.radians(12)), Rigid(), make_pulse("sine", 0.3 * G, 0.8),
                   vertical=make_pulse("sine", 0.5 * G, 0.8))
    assert b["theta_max"] == lib.theta_max


def test_cli_vertical_record(tmp_path):
    rec = synthetic_record(8, duration=6.0, pga=0.6 * G)
    h, v = tmp_path / "h.txt", tmp_path / "v.txt"
    np.savetxt(h, rec.acc / G)
    np.savetxt(v, 0.4 * rec.acc[::-1] / G)
    args = ["simulate", "--R", "1", "--alpha", "12", "--record", str(h), "--units", "g", "--dt", "0.01", "--json"]
    out = _cli(args + ["--vertical", str(v)])
    assert out.exit_code == 0, out.output
    assert json.loads(out.output)["vertical"] == "record v.txt"
    half = _cli(args + ["--vertical", str(v), "--vertical-scale", "0.5"])
    assert json.loads(half.output)["vertical"] == "record v.txt x 0.5"
    for extra, msg in ((["--vertical", str(v), "--vertical-pulse", "sine:ap=0.1,Tp=1"], "at most one"),
                       (["--vertical", str(v), "--isolation", "linear:Tb=2.5,xi=0.1"], "rigid foundation only"),
                       (["--vertical-scale", "2"], "apply to --vertical"),
                       (["--vertical-pulse", "sine:ap=1.2,Tp=1"], "lift off")):
        bad = _cli(args + extra)
        assert bad.exit_code == 2 and msg in bad.output and "Traceback" not in bad.output, (extra, bad.output)
