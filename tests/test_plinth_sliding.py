"""A body on its plinth on sliding and lead-rubber bearings (docs/physics-plinth.md "On sliding and lead-rubber
bearings"). The slow reference (rockcli.reference.stack_hysteretic): a plinth that cannot lift leaves the body the
single block on the same bearings (against the single block's own hysteretic reference), the base alone is the
single block's base, impacts never add energy and leave the bearings' states alone. Short pulses, at most 0.3 s
after them."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockcli.models import Block, DoubleConcaveSliding, LeadRubber, Plinth, SingleConcaveSliding, Stack
from rockcli.pulses import OneSine
from rockcli.reference import reference_sliding
from rockcli.reference.stack import reference_plinth
from rockcli.solve import simulate
from rockcli.io.units import G

BODY = Block.from_dimensions(1.2, 0.3)
WIDE = Stack(BODY, Plinth(0.2, 3.0, mass_ratio=5.0))  # a plinth that cannot lift
COUPLED = Stack(BODY, Plinth(1.0, 0.5, mass_ratio=1.5))  # both blocks rock


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
    iso = SingleConcaveSliding(0.8, 0.1, u_y=0.001, gamma=0.3)
    out = reference_plinth(COUPLED, OneSine(0.5 * G, 0.4), isolation=iso, horizon=0.3, rtol=1e-9,
                           record_impacts=True)
    assert out.verdict in ("rocked", "overturned") and len(out.impacts) >= 3
    assert not math.isnan(out.t_uplift[0]) and not math.isnan(out.t_uplift[1])
    mb = (1.0 + COUPLED.m2) / 0.3 - 1.0 - COUPLED.m2
    for imp in out.impacts:  # maximal velocities: plinth (x, y, theta), body (x, y, theta), base x
        assert imp["ke_plus"] <= imp["ke_minus"] * (1 + 1e-9)
        vm, vp = imp["v_minus"], imp["v_plus"]
        p_minus = COUPLED.m2 * vm[0] + vm[3] + mb * vm[6]
        p_plus = COUPLED.m2 * vp[0] + vp[3] + mb * vp[6]
        assert p_plus == pytest.approx(p_minus, abs=1e-9 * (abs(p_minus) + 1e-3))
