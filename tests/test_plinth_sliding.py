"""A body on its plinth on sliding and lead-rubber bearings (docs/physics-plinth.md "On sliding and lead-rubber
bearings"). The slow reference (rockcli.reference.stack_hysteretic): a plinth that cannot lift leaves the body the
single block on the same bearings (against the single block's own hysteretic reference), the base alone is the
single block's base, impacts never add energy and leave the bearings' states alone. Short pulses, at most 0.3 s
after them."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from rockcli.models import Block, DoubleConcaveSliding, LeadRubber, Plinth, SingleConcaveSliding, Stack
from rockcli.pulses import OneSine
from rockcli.reference import reference_sliding
from rockcli.reference.stack import reference_plinth
from rockcli.solve import simulate, simulate_stack
from rockcli.io.units import G

BODY = Block.from_dimensions(1.2, 0.3)
WIDE = Stack(BODY, Plinth(0.2, 3.0, mass_ratio=5.0))  # a plinth that cannot lift
COUPLED = Stack(BODY, Plinth(1.0, 0.5, mass_ratio=1.5))  # both blocks rock


COUPLED_ISO = SingleConcaveSliding(0.8, 0.1, u_y=0.001, gamma=0.3)  # both blocks rock on it under COUPLED_PULSE
COUPLED_PULSE = OneSine(0.5 * G, 0.4)


@functools.lru_cache(maxsize=None)
def _coupled_reference():
    return reference_plinth(COUPLED, COUPLED_PULSE, isolation=COUPLED_ISO, horizon=0.3, rtol=1e-9,
                            record_impacts=True)


def _scss(gamma):
    return SingleConcaveSliding(2.0, 0.05, gamma=gamma)


def _lrb(gamma):
    return LeadRubber(2.0, 0.06, 0.01, gamma=gamma)


def _dcss(gamma):
    return DoubleConcaveSliding.from_period(2.5, 0.03, 0.07, gamma=gamma)


@pytest.mark.parametrize("bearing", [_scss, _lrb])
def test_a_plinth_that_cannot_lift_is_the_single_block_on_the_same_sliding_base(bearing):
    """The still plinth is part of the base: the body is the single block on the same bearings (their force per
    unit of the whole moving mass is the same) with gamma1 = gamma/(1 + m2). Against the single block's own
    hysteretic reference: angles, uplift, impacts, the base's peak (both stop at the horizon, 0.3 s after the
    pulse)."""
    pulse = OneSine(0.4 * G, 0.8)
    single = bearing(0.5 / (1.0 + WIDE.m2))
    out = reference_plinth(WIDE, pulse, isolation=bearing(0.5), horizon=0.3, rtol=1e-9)
    ref = reference_sliding(BODY, single, pulse, horizon=0.3, rtol=1e-9, atol=None)
    assert ref.verdict == "rocked" and ref.n_impacts >= 1
    assert out.verdict == ref.verdict and out.peak[0] == 0.0 and math.isnan(out.t_uplift[0])
    assert out.peak[1] == pytest.approx(ref.theta_max, rel=1e-8)
    assert out.t_uplift[1] == pytest.approx(ref.t_uplift, abs=1e-9)
    assert out.n_impacts[1] == ref.n_impacts
    assert out.base_disp_max == pytest.approx(ref.u_max, rel=1e-8)


def test_the_base_alone_is_the_single_block_base_on_double_concave_bearings():
    """Nothing lifts: the stack rides the base, which is the single block's stuck base (u'' = F - ag per unit
    moving mass, whatever rides it). The trilinear double concave bearing, against the single block's compiled
    run (its peak, read as the stack's over the free base's later swings)."""
    pulse = OneSine(0.3 * G, 0.5)
    out = reference_plinth(COUPLED, pulse, isolation=_dcss(0.5), horizon=0.3, rtol=1e-9)
    fast = simulate(BODY, _dcss(0.5 / (1.0 + COUPLED.m2)), pulse, horizon=0.3)
    assert out.verdict == fast.verdict == "no_uplift"
    assert out.settled and fast.settled
    assert out.base_disp_max > 0.01
    assert out.base_disp_max == pytest.approx(fast.base_disp_max_m, rel=1e-6)


def test_impacts_on_sliding_bearings_never_add_energy_and_keep_the_horizontal_momentum():
    """Both blocks rock on a single concave base: across every impact the kinetic energy (base included) never
    rises and the total horizontal momentum is kept (the bearings carry no impulse). (The bearing's own states are
    left as they are at an impact by construction: functions of the path of u, which an impact does not move.)"""
    out = _coupled_reference()
    assert out.verdict in ("rocked", "overturned") and len(out.impacts) >= 3
    assert not math.isnan(out.t_uplift[0]) and not math.isnan(out.t_uplift[1])
    mb = (1.0 + COUPLED.m2) / 0.3 - 1.0 - COUPLED.m2
    for imp in out.impacts:  # maximal velocities: plinth (x, y, theta), body (x, y, theta), base x
        assert imp["ke_plus"] <= imp["ke_minus"] * (1 + 1e-9)
        vm, vp = imp["v_minus"], imp["v_plus"]
        p_minus = COUPLED.m2 * vm[0] + vm[3] + mb * vm[6]
        p_plus = COUPLED.m2 * vp[0] + vp[3] + mb * vp[6]
        assert p_plus == pytest.approx(p_minus, abs=1e-9 * (abs(p_minus) + 1e-3))


# ---------------------------------------------------------------------------------------------
# The compiled driver (rockcli.kernels.stack_linear on hysteretic bearings)
# ---------------------------------------------------------------------------------------------
@pytest.mark.parametrize("bearing", [_scss, _lrb, _dcss])
@pytest.mark.parametrize("pulse", [OneSine(0.4 * G, 0.8), OneSine(-0.7 * G, 0.5)])
def test_the_compiled_driver_with_a_plinth_that_cannot_lift_is_the_single_block_on_the_same_bearings(bearing, pulse):
    """Against the single block's compiled run with gamma/(1 + m2) on the same bearings: verdict, impacts, uplift;
    peaks and the base's peak to 1e-6 (two integrators, each to its tolerance)."""
    a = simulate_stack(WIDE, pulse, isolation=bearing(0.5), horizon=2.0)
    ref = simulate(BODY, bearing(0.5 / (1.0 + WIDE.m2)), pulse, horizon=2.0)
    assert a.status != -1 and a.plinth.theta_max == 0.0 and math.isnan(a.plinth.t_uplift_s)
    assert a.verdict == ref.verdict and a.body.n_impacts == ref.n_impacts
    assert a.body.theta_max == pytest.approx(ref.theta_max, rel=1e-6)
    if ref.verdict != "no_uplift":
        assert a.body.t_uplift_s == pytest.approx(ref.t_uplift_s, abs=1e-7)
    if a.verdict != "overturned":
        assert a.settled == ref.settled
        assert a.base_disp_max == pytest.approx(ref.base_disp_max_m, rel=1e-6)


def test_the_compiled_driver_agrees_with_the_reference_where_both_blocks_rock():
    """The coupled scene of the impact test (both blocks rock, 18 impacts while the ground moves, on single concave
    bearings): verdict, impacts, peaks within 1e-7 of each slenderness, the base's peak within 1e-7 (measured
    6e-9, 3e-9, 6e-10; at the kernel's rtol 1e-11 and the reference's 1e-10 all within 3e-10)."""
    r = _coupled_reference()
    a = simulate_stack(COUPLED, COUPLED_PULSE, isolation=COUPLED_ISO, horizon=0.3, tail=0.0)
    assert r.n_impacts[0] > 0 and r.n_impacts[1] > 0
    assert a.verdict == r.verdict and a.toppled == {-1: None, 0: "plinth", 1: "body"}[r.toppled]
    assert [a.plinth.n_impacts, a.body.n_impacts] == r.n_impacts
    assert abs(a.body.theta_max - r.peak[1]) / BODY.alpha < 1e-7
    assert abs(a.plinth.theta_max - r.peak[0]) / COUPLED.alpha_asm < 1e-7
    assert a.toppled is None and a.base_disp_max == pytest.approx(r.base_disp_max, rel=1e-7)


def _random_sliding(rng):
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
    from bench_plinth import random_sliding_scene

    return random_sliding_scene(rng)


def test_verdict_only_and_history_runs_agree_and_the_mirror_flips_on_random_sliding_scenes():
    """60 random stacks on random sliding and lead-rubber bearings (bench_plinth's scenes, seed 36; every other one
    with a random coefficient of restitution E in 0.5-0.95, the rest with the momentum rule): a history run takes the
    verdict-only run's steps (the same outputs; more steps only for its tail once settled), and the flipped pulse
    gives the mirror image (peaks to 1e-9)."""
    rng, rng_e = np.random.default_rng(36), np.random.default_rng(37)
    kinds = set()
    for i in range(60):
        stack, iso, pulse = _random_sliding(rng)
        e = float(rng_e.uniform(0.5, 0.95)) if i % 2 else None
        a = simulate_stack(stack, pulse, isolation=iso, horizon=1.0, tail=1.0, restitution=e)
        b = simulate_stack(stack, pulse, isolation=iso, horizon=1.0, tail=1.0, history=True, restitution=e)
        da, db = a.as_dict(), b.as_dict()
        assert da.pop("steps") <= db.pop("steps")
        assert da.pop("base_disp_max_m") <= db.pop("base_disp_max_m")  # the history run's tail may swing on
        assert da == db
        m = simulate_stack(stack, type(pulse)(-pulse.a_p, pulse.T_p), isolation=iso, horizon=1.0, tail=1.0,
                           restitution=e)
        assert m.verdict == a.verdict and m.toppled == a.toppled
        assert m.body.theta_max == pytest.approx(a.body.theta_max, rel=1e-9, abs=1e-12)
        assert m.plinth.theta_max == pytest.approx(a.plinth.theta_max, rel=1e-9, abs=1e-12)
        kinds.add((a.verdict, e is None))
    assert {v for v, _ in kinds} == {"no_uplift", "rocked", "overturned"}
    assert {("rocked", True), ("rocked", False), ("overturned", False)} <= kinds
