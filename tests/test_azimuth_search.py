"""``--azimuth worst`` searches the orientations of a pair together (issue 33 item 5).

:func:`rockcli.assess.find_overturn_scales` with ``groups`` scans the orientations of one column x pair x
configuration in increasing order of the factor and stops at the first factor at which any overturns; the
theorem in :mod:`rockcli.assess.azimuth` says that the row ``--azimuth worst`` keeps is then identical to
the one it keeps after every orientation's full search. Checked here against the unshared search on random
short pairs of every foundation (a coarse grid keeps the many scenes cheap), and end to end through
``run_assessment`` + ``collapse`` on the 1 % grid.
"""

from __future__ import annotations

import dataclasses
import math
from types import SimpleNamespace

import numpy as np
import pytest

from rockcli.assess import find_overturn_scales, parse_configurations, run_assessment
from rockcli.assess.azimuth import collapse, expand, worst_row
from rockcli.assess.margin import NOTE_ABOVE_GROUP, _scaled_job
from rockcli.assess.scenes import EXCITATION_RECORD, Excitation
from rockcli.models import (Block, DoubleConcaveSliding, LeadRubber, LinearIsolation, Rigid,
                            SingleConcaveSliding)
from rockcli.records import Record
from rockcli.records.orientation import check_pair, project, sweep_azimuths
from rockcli.solve import simulate_many
from rockcli.io.units import G

#: 31 factors 0.1 .. 4 with 1 among them, as in tests/test_margin_search.py
GRID = np.unique(np.concatenate([np.geomspace(0.1, 1.0, 19), np.geomspace(1.0, 4.0, 13)]))
SOLVER = {"horizon": 3.0}


def _pair(rng, n=None, dt=0.01):
    """Two perpendicular components (at a random azimuth) of a short random horizontal motion."""
    n = n or int(rng.integers(120, 300))
    t = np.arange(n) * dt
    env = np.sin(np.pi * t / t[-1]) ** 2
    north, east = np.zeros(n), np.zeros(n)
    for f in rng.uniform(0.4, 5.0, 4):
        north += rng.normal() * np.sin(2 * np.pi * f * t + rng.uniform(0, 2 * np.pi))
        east += rng.normal() * np.sin(2 * np.pi * f * t + rng.uniform(0, 2 * np.pi))
    east *= rng.uniform(0.2, 1.0)  # polarised motions: some orientations feel far less than others
    scale = rng.uniform(0.2, 0.8) * G / np.max(np.hypot(north, east) * env)
    phi = float(rng.choice([0.0, 30.0, 137.0]))
    c, s = math.cos(math.radians(phi)), math.sin(math.radians(phi))
    a1 = (north * c + east * s) * env * scale
    a2 = (-north * s + east * c) * env * scale

    def comp(acc, az):
        return Record(acc, dt, "pair", meta={"azimuth_deg": az % 360.0, "vertical": False, "station": "S",
                                             "component": f"{az:g}", "path": f"pair-{az:g}"})

    return check_pair(comp(a1, phi), comp(a2, phi + 90.0))


def _foundation(rng, kind):
    if kind == "rigid":
        return Rigid()
    if kind == "linear":
        return LinearIsolation(float(rng.uniform(0.8, 4.0)), float(rng.uniform(0.02, 0.3)),
                               float(rng.choice([0.0, 0.01, 0.3])))
    if kind == "scss":
        return SingleConcaveSliding(float(rng.uniform(1.5, 4.0)), float(rng.uniform(0.03, 0.1)))
    if kind == "lrb":
        return LeadRubber(float(rng.uniform(1.5, 3.0)), float(rng.uniform(0.03, 0.1)), 0.01)
    return DoubleConcaveSliding(1.0, 1.5, 0.03, 0.06)


#: every foundation; the sliding and lead-rubber ones (a floor of 0: every factor from the bottom) cost the most
KINDS = ["rigid"] * 8 + ["linear"] * 8 + ["scss", "lrb", "dcss"]


def _groups(seed, n_groups):
    """Random (block, foundation, pair) groups, each with its orientations: (scenes, group ids)."""
    rng = np.random.default_rng(seed)
    scenes, gids = [], []
    for g in range(n_groups):
        block = Block(float(rng.uniform(0.3, 2.0)), float(np.radians(rng.uniform(6.0, 16.0))))
        kind = KINDS[int(rng.integers(len(KINDS)))]
        foundation = _foundation(rng, kind)
        pair = _pair(rng, int(rng.integers(80, 160)))  # 0.8-1.6 s of motion: short runs, many scenes
        for theta in sweep_azimuths(float(rng.choice([30.0, 45.0, 60.0]))):
            scenes.append((block, foundation, project(*pair, theta)))
            gids.append(g)
    return scenes, gids


def _row(r, found):
    hi, _, _ = found
    return SimpleNamespace(error="", overturned=r.overturned, t_overturn_s=r.t_overturn_s,
                           theta_max_over_alpha=r.theta_max_over_alpha, overturn_scale=hi)


def _eq(a, b):
    return all((x == y) or (isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y))
               for x, y in zip(a, b))


def test_the_shared_search_keeps_the_same_orientation_as_the_full_one():
    """About 2,100 orientations of 480 random pairs (rigid, linear, sliding, lead-rubber; 3 to 6 orientations
    each): per group, the orientation kept (and whether one is) and its margin, bracket and note are the
    unshared search's; every orientation with a result has the unshared one; every one left out has an
    unshared margin above the kept one's, or none; and the shared search makes fewer runs."""
    import rockcli.solve as solve

    scenes, gids = _groups(3301, 480)
    known = simulate_many([_scaled_job(*s, 1.0) for s in scenes], **SOLVER)
    runs = {}
    original = solve.simulate_many

    def search(**kw):
        runs[bool(kw)] = 0

        def counting(jobs, **solver):
            runs[bool(kw)] += len(jobs)
            return original(jobs, **solver)

        solve.simulate_many = counting
        try:
            return find_overturn_scales(scenes, grid=GRID, known=known, **kw, **SOLVER)
        finally:
            solve.simulate_many = original

    full, shared = search(), search(groups=gids)
    members = {}
    for i, g in enumerate(gids):
        members.setdefault(g, []).append(i)
    cut = NOTE_ABOVE_GROUP.split("{")[0]
    left_out = named = ties = 0
    for idx in members.values():
        smallest = min((full[i][0] for i in idx if not math.isnan(full[i][0])), default=math.inf)
        for i in idx:
            if shared[i][2].startswith(cut):  # left out: its own margin is above the group's smallest, or none
                left_out += 1
                assert math.isnan(full[i][0]) or full[i][0] > smallest, (i, full[i], smallest)
            else:
                assert _eq(shared[i], full[i]), (i, shared[i], full[i])
        w = [_row(known[i], full[i]) for i in idx]
        s = [_row(known[i], shared[i]) for i in idx]
        (rw, one_w), (rs, one_s) = worst_row(w, True), worst_row(s, True)
        assert (w.index(rw), one_w) == (s.index(rs), one_s)
        assert _eq(shared[idx[s.index(rs)]], full[idx[w.index(rw)]])
        named += one_w
        ties += sum(not shared[i][2].startswith(cut) and math.isfinite(shared[i][0]) for i in idx) > 1  # same J
    assert len(scenes) > 2000 and left_out > len(scenes) // 4 and named > 300 and ties > 40, (left_out, named, ties)
    assert runs[True] < 0.8 * runs[False], runs
    assert any("not proven" in note for _, _, note in full)  # the notes on unproven runs are compared too


def _excitations(seed, n_pairs):
    rng = np.random.default_rng(seed)
    out = []
    for k in range(n_pairs):
        pair = _pair(rng)
        rec = project(*pair, 0.0)
        out.append(Excitation(f"pair{k}", EXCITATION_RECORD, rec, f"synthetic pair {k}", rec.pga_g, pair=pair,
                              azimuth_deg=0.0))
    return out


@pytest.mark.parametrize("margin", [True, False])
def test_assess_column_worst_rows_are_the_full_searchs(margin):
    """End to end on the 1 % grid: ``run_assessment(orientations=...)`` then ``collapse`` gives the rows the
    unshared search and neighbourhood give, field for field (5 random pairs, 2 columns, 3 foundations,
    6 orientations: 180 scenes; the sliding bearings, whose scan starts at 0.1x, are left to the test above)."""
    pairs = _excitations(3302, 5)
    columns = [Block(0.6, float(np.radians(12.0)), "small"), Block(1.5, float(np.radians(9.0)), "large")]
    configs = parse_configurations(["none", "linear:Tb=2", "linear:Tb=3,xi=0.05"])
    subs, groups = expand(pairs, sweep_azimuths(30.0))
    kw = dict(margin=margin, neighbourhood=True, **SOLVER)
    shared = collapse(run_assessment(columns, subs, configs, orientations=groups, **kw), pairs, groups)
    full = collapse(run_assessment(columns, subs, configs, **kw), pairs, groups)
    assert len(shared.rows) == len(full.rows) == 30
    for a, b in zip(shared.rows, full.rows):
        assert _eq(dataclasses.astuple(a), dataclasses.astuple(b)), (a, b)
    if margin:
        assert sum(not math.isnan(r.overturn_scale) for r in full.rows) > 15
