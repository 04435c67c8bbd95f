"""The margin search leaves out only runs that cannot change its result (issue 33).

:func:`rockcli.assess.find_overturn_scales` scans upwards from each scene's lift-off floor and stops
at the first overturning factor. Its result must be exactly that of running every grid factor, taking
the first that overturns and bisecting below it (``_full_scan`` below), on random scenes of every
foundation; the floor must be a proof (a factor below it runs without uplift, proven); the progress
must add up. Short synthetic records and a coarse grid keep it cheap.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockcli.assess import find_overturn_scales, overturn_shares
from rockcli.assess.liftoff import LINEAR_MARGIN, liftoff_floors
from rockcli.assess.margin import NOTE_NO_OVERTURN, NOTE_OVERTURNS_AT_MIN, RTOL_FLOOR, _scaled_job
from rockcli.models import (Block, DoubleConcaveSliding, LeadRubber, LinearIsolation, Rigid,
                            SingleConcaveSliding)
from rockcli.pulses import make_pulse
from rockcli.records import Record
from rockcli.solve import simulate_many, with_vertical
from rockcli.io.units import G
from synthetic import random_record

#: 31 factors 0.1 .. 4 with 1 among them (ratio ~1.13): the search's logic, not its resolution, is tested
GRID = np.unique(np.concatenate([np.geomspace(0.1, 1.0, 19), np.geomspace(1.0, 4.0, 13)]))


def _foundation(rng, kind):
    if kind == "rigid":
        return Rigid()
    if kind == "linear":
        xi = 0.0 if rng.random() < 0.2 else float(rng.uniform(0.01, 0.4))
        return LinearIsolation(float(rng.uniform(0.5, 4.0)), xi, float(rng.choice([0.0, 0.01, 0.3])))
    if kind == "scss":
        return SingleConcaveSliding(float(rng.uniform(1.5, 4.0)), float(rng.uniform(0.03, 0.1)))
    if kind == "lrb":
        return LeadRubber(float(rng.uniform(1.5, 3.0)), float(rng.uniform(0.03, 0.1)), 0.01)
    return DoubleConcaveSliding(1.0, 1.5, 0.03, 0.06)


def _scenes(seed, n):
    rng = np.random.default_rng(seed)
    kinds = ["rigid"] * 4 + ["linear"] * 5 + ["scss", "lrb", "dcss"]
    out = []
    for _ in range(n):
        block = Block(float(rng.uniform(0.3, 2.5)), float(np.radians(rng.uniform(5.0, 16.0))))
        kind = kinds[int(rng.integers(len(kinds)))]
        if rng.random() < 0.15:
            motion = make_pulse(str(rng.choice(["ricker-sym", "sine"])), float(rng.uniform(0.1, 0.6)) * G,
                                float(rng.uniform(0.3, 1.5)))
        else:
            motion = random_record(rng)
        out.append((block, _foundation(rng, kind), motion))
    return out


def _full_scan(scenes, grid, rtol, known=None, **solver):
    """Every grid factor of every scene run; the first overturning one; the bisection below it; the note
    counting the unproven runs at or below the margin (the factor 1 of ``known`` not run, not counted)."""
    ones = np.flatnonzero(np.isclose(grid, 1.0))
    pairs = [(i, j) for i in range(len(scenes)) for j in range(grid.size)
             if known is None or not ones.size or j != ones[0]]
    res = dict(zip(pairs, simulate_many([_scaled_job(*scenes[i], float(grid[j])) for i, j in pairs], early=True,
                                        **solver)))
    if known is not None and ones.size:
        for i in range(len(scenes)):
            res[(i, int(ones[0]))] = known[i]
    out = []
    for i, scene in enumerate(scenes):
        rs = [res[(i, j)] for j in range(grid.size)]
        unproven = [j for j, r in enumerate(rs) if r.verdict != "error" and not r.overturned and not r.settled
                    and not (known is not None and ones.size and j == ones[0])]
        err = next((r.error for r in rs if r.verdict == "error"), None)
        over = [j for j, r in enumerate(rs) if r.overturned]
        if err is not None:
            hi, lo, note = math.nan, math.nan, f"error: {err}"
        elif not over:
            hi, lo, note = math.nan, grid[-1], NOTE_NO_OVERTURN.format(grid[-1])
        elif over[0] == 0:
            hi, lo, note = grid[0], math.nan, NOTE_OVERTURNS_AT_MIN.format(grid[0])
        else:
            lo, hi, note = grid[over[0] - 1], grid[over[0]], ""
            first = True
            while first or hi / lo - 1.0 > max(rtol, RTOL_FLOOR):
                first = False
                mid = math.sqrt(lo * hi)
                r = simulate_many([_scaled_job(*scene, mid)], early=True, **solver)[0]
                unproven.append(-1) if (not r.overturned and not r.settled) else None
                hi, lo = (mid, lo) if r.overturned else (hi, mid)
            hi, lo = float(hi), float(lo)
        count = len([j for j in unproven if not over or j <= over[0]])
        if count:
            note = (note + "; " if note else "") + f"{count} scaled run(s) not proven at the solver's horizon, " \
                                                   "counted as surviving"
        out.append((hi, lo, note))
    return out


def _same(a, b):
    (h1, l1, n1), (h2, l2, n2) = a, b
    eq = lambda x, y: (math.isnan(x) and math.isnan(y)) or x == y  # noqa: E731
    return eq(h1, h2) and eq(l1, l2) and n1 == n2


@pytest.mark.parametrize("seed,known,n", [(331, False, 100), (332, True, 60)])
def test_search_equals_the_full_scan_on_random_scenes(seed, known, n):
    """160 random scenes (rigid, linear, sliding and lead-rubber bases; records and pulses; undamped bases,
    a short horizon so that some runs end unproven): the search returns exactly the full scan's results,
    notes included, with and without the responses at 1x given."""
    scenes = _scenes(seed, n)
    solver = {"horizon": 3.0}
    responses = simulate_many([_scaled_job(*s, 1.0) for s in scenes], **solver) if known else None
    got = find_overturn_scales(scenes, grid=GRID, known=responses, **solver)
    want = _full_scan(scenes, GRID, 0.01, known=responses, **solver)
    bad = [(i, g, w) for i, (g, w) in enumerate(zip(got, want)) if not _same(g, w)]
    assert not bad, bad[:5]
    assert sum(np.isfinite(h) for h, _, _ in got) >= n // 4  # the test sees margins, not only 'no overturning'
    assert any("not proven" in note for _, _, note in got)  # and the note's count


def test_the_search_leaves_out_the_runs_it_can():
    """Fewer runs than the full scan: none below a rigid or linear scene's floor, none past its first
    overturning factor (without ``fill``), and the progress adds up to every pair."""
    import rockcli.solve as solve

    scenes = [s for s in _scenes(333, 60) if isinstance(s[1], (Rigid, LinearIsolation)) and hasattr(s[2], "acc")]
    floors = liftoff_floors(scenes)
    assert np.all(floors > 0)
    made = []
    original = solve.simulate_many

    def counting(jobs, **kw):
        made.extend((id(j[1]), id(j[2]), id(j[0]), j[3]) for j in jobs)
        return original(jobs, **kw)

    steps = []
    solve.simulate_many = counting
    try:
        found = find_overturn_scales(scenes, grid=GRID, progress=steps.append, fill=False)
    finally:
        solve.simulate_many = original
    assert sum(steps) == len(scenes) * GRID.size and min(steps) > 0
    for (b, f, mo), floor, (hi, lo, _) in zip(scenes, floors, found):
        scales = sorted(s for fid, mid, bid, s in made if (fid, mid, bid) == (id(f), id(mo), id(b)))
        grid_runs = [s for s in scales if s in GRID]
        assert all(s >= floor for s in grid_runs)
        if math.isfinite(hi):
            assert max(grid_runs) <= max(hi, GRID[np.searchsorted(GRID, hi)]) * (1 + 1e-12)
    assert len(made) < 0.6 * len(scenes) * GRID.size


def test_the_liftoff_floor_is_a_proof_and_tight():
    """Just below each floor (rigid and linear bases) the run never lifts the block and is proven; on linear
    bearings 1 % above the floor (at most 0.1 % below the exact lift-off factor) it lifts."""
    rng = np.random.default_rng(334)
    scenes = []
    for _ in range(60):
        block = Block(float(rng.uniform(0.3, 2.5)), float(np.radians(rng.uniform(5.0, 16.0))))
        scenes.append((block, _foundation(rng, "rigid" if rng.random() < 0.3 else "linear"), random_record(rng)))
    floors = liftoff_floors(scenes)
    below = simulate_many([_scaled_job(*s, f * (1 - 1e-7)) for s, f in zip(scenes, floors)], early=True)
    assert all(r.verdict == "no_uplift" and r.settled for r in below)
    above = simulate_many([_scaled_job(*s, f * 1.01) for s, f in zip(scenes, floors)], early=True)
    assert all(r.verdict != "no_uplift" for r in above), [(s[1], r.verdict) for s, r in zip(scenes, above)]
    assert LINEAR_MARGIN <= 1e-9


def test_the_rigid_floor_under_a_vertical_motion_takes_its_lowest_gravity():
    """With a vertical motion (never scaled) the block lifts where ``s |ag| > (g + a_v) tan(alpha)``: the floor
    is ``(g + min a_v) tan(alpha) / PGA``, below the floor without it, and a factor between the two can lift
    the block (the peak of the horizontal record meets a dip of the vertical one)."""
    block = Block(1.0, float(np.radians(10.0)))
    n, dt = 400, 0.01
    acc = np.zeros(n)
    acc[200] = 0.5 * G  # one spike: ag is piecewise linear, peak at t = 2 s
    up = np.zeros(n)
    up[190:211] = -0.3 * G  # gravity 0.7 g around it
    rec = with_vertical(Record(acc, dt, "spike"), Record(up, dt, "dip"), "dip")
    plain = Record(acc, dt, "spike")
    (f_v,), (f_0,) = liftoff_floors([(block, Rigid(), rec)]), liftoff_floors([(block, Rigid(), plain)])
    assert f_v == pytest.approx(0.7 * f_0, rel=1e-6)
    s = 0.8 * f_0  # above the vertical floor, below the plain one
    r_v, r_0 = simulate_many([(block, Rigid(), rec, s), (block, Rigid(), plain, s)], early=True)
    assert r_v.verdict != "no_uplift" and r_0.verdict == "no_uplift"
    r = simulate_many([(block, Rigid(), rec, f_v * (1 - 1e-7))], early=True)[0]
    assert r.verdict == "no_uplift" and r.settled


def test_neighbourhood_shares_skip_only_factors_below_the_floor():
    scenes = [s for s in _scenes(335, 40) if isinstance(s[1], (Rigid, LinearIsolation))][:12]
    factors = np.geomspace(0.2, 3.0, 15)
    got = overturn_shares(scenes, factors=factors)
    res = simulate_many([_scaled_job(*s, float(f)) for s in scenes for f in factors], early=True)
    want = np.array([r.overturned for r in res]).reshape(len(scenes), factors.size).mean(axis=1)
    assert np.array_equal(np.array(got), want)
