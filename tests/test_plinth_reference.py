"""The slow reference of a body on its plinth (rockcli.reference.stack, docs/physics-plinth.md): its closed-form
limits against the single block's own reference, the static uplift thresholds, the impact laws (energy never
rises, the momentum balances the impulses leave untouched), symmetry. Each run is a short pulse and at most 1 s
of free motion after it (the same ``horizon`` on both sides of a comparison)."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from rockcli.models import Block, Plinth, Stack
from rockcli.pulses import OneSine, RickerAntisymmetric, RickerSymmetric
from rockcli.records import Record
from rockcli.reference import reference_simulate
from rockcli.reference.stack import reference_plinth, reference_stack, stack_blocks
from rockcli.reference.stack_mechanics import StackModel
from rockcli.io.units import G

STATUE = Block.from_dimensions(1.79, 0.5, "statue")


def test_a_plinth_that_cannot_lift_leaves_the_body_on_rigid_ground():
    """A wide low plinth (4 m x 0.2 m) never lifts: the statue rocks exactly as on the ground. The two references
    differ only in their steps (the stack's stay below 0.02/p while the plinth's face is watched), so they are
    compared at rtol 1e-13, where both have converged (1.4e-10 of the peak apart; 1e-9 allowed)."""
    stack = Stack(STATUE, Plinth(0.2, 4.0))
    for pulse in (RickerSymmetric(0.35 * G, 1.0), OneSine(0.3 * G, 1.2)):
        ref = reference_simulate(STATUE, None, pulse, atol=None, horizon=0.5, rtol=1e-13)
        out = reference_plinth(stack, pulse, horizon=0.5, rtol=1e-13)
        assert out.verdict == ref.verdict
        assert out.toppled == (1 if ref.verdict == "overturned" else -1)
        assert math.isnan(out.t_uplift[0]) and out.peak[0] == 0.0  # the plinth never moved
        assert out.peak[1] == pytest.approx(ref.theta_max, rel=1e-9)
        assert out.t_uplift[1] == pytest.approx(ref.t_uplift, abs=1e-12)
        assert out.n_impacts[1] == ref.n_impacts
        assert out.n_jumps == 0 and out.n_inconsistent == 0


def test_one_block_is_the_single_block():
    """The stack machinery with one block is the single block's reference (Eq 3, Housner, the rest rule)."""
    pulse = RickerAntisymmetric(0.4 * G, 0.8)
    out = reference_stack([(STATUE.b, STATUE.h, 1.0)], pulse, horizon=1.0)
    ref = reference_simulate(STATUE, None, pulse, atol=None, horizon=1.0)
    assert out.verdict == ref.verdict and out.n_impacts[0] == ref.n_impacts
    assert out.peak[0] == pytest.approx(ref.theta_max, rel=1e-8)


def test_a_body_that_cannot_lift_rocks_with_its_plinth_as_one_block():
    """A squat body as wide as its plinth never lifts off it: the assembly is the single block of
    (p_asm, alpha_asm) with the impact ratio eta_asm (pattern P of the note)."""
    stack = Stack(Block.from_dimensions(0.3, 0.4), Plinth(1.6, 0.4, mass_ratio=2.0))
    pulse = RickerSymmetric(0.25 * G, 0.5)
    out = reference_plinth(stack, pulse, horizon=0.5)
    ref = reference_simulate(stack.as_block(), None, pulse, restitution=stack.eta_asm, atol=None, horizon=0.5)
    assert ref.verdict == "rocked" and ref.n_impacts > 2
    assert out.verdict == ref.verdict and out.peak[1] == 0.0
    assert out.peak[0] == pytest.approx(ref.theta_max, rel=1e-9)
    assert out.n_impacts[0] == ref.n_impacts


def test_a_body_far_lighter_than_its_plinth_leaves_the_plinth_a_single_block():
    """As the body's mass over the plinth's falls (1e-2, 1e-3), the plinth's peak tends to its own as a single
    block, the difference falling with the mass ratio."""
    pulse = OneSine(0.35 * G, 0.6)
    plinth = Plinth(1.6, 0.4)
    ref = reference_simulate(plinth.block, None, pulse, atol=None, horizon=0.5)
    assert ref.verdict == "rocked"
    diffs = []
    for mr in (100.0, 1000.0):
        stack = Stack(Block.from_dimensions(0.3, 0.4), Plinth(1.6, 0.4, mass_ratio=mr))
        out = reference_plinth(stack, pulse, horizon=0.5)
        assert out.verdict == ref.verdict
        diffs.append(abs(out.peak[0] / ref.theta_max - 1))
    assert diffs[1] < 1e-2 and diffs[1] < diffs[0] / 5 and diffs[1] > 0


@pytest.mark.parametrize("dims, first", [((1.79, 0.5, 0.5, 1.2, None), 1),  # the statue lifts off its plinth
                                         ((1.79, 0.5, 1.0, 0.6, None), 0),  # the assembly lifts first
                                         ((0.4, 0.3, 1.6, 0.4, None), 0),  # a squat body on a slender plinth
                                         ((1.2, 0.3, 0.6, 0.5, 3.0), 1)])
def test_static_uplift_thresholds(dims, first):
    """A slowly ramped ground acceleration lifts the stack at exactly the lower of g tan(alpha1) (the body off the
    still plinth) and g b2 / y_c (the assembly off the ground), about the corner opposite the motion."""
    h1, w1, h2, w2, mr = dims
    stack = Stack(Block.from_dimensions(h1, w1), Plinth(h2, w2, mass_ratio=mr))
    thr = (stack.assembly_uplift_acceleration, stack.body_uplift_acceleration)
    assert min(thr) == thr[first] and math.isclose(thr[0], G * math.tan(stack.alpha_asm), rel_tol=1e-14)
    rate = 0.5  # m/s^3: slow enough for a static threshold; the record ends 0.05 s after it, so does the run
    for sign in (1.0, -1.0):
        n = int((thr[first] / rate + 0.05) / 0.01) + 1
        ramp = Record(sign * rate * 0.01 * np.arange(n), 0.01, "ramp")
        out = reference_plinth(stack, ramp, horizon=0.0)
        assert out.t_uplift[first] == pytest.approx(thr[first] / rate, abs=1e-9)
        assert math.isnan(out.t_uplift[1 - first]) or out.t_uplift[1 - first] > out.t_uplift[first]
        assert out.patterns[1][1][first] == -int(sign)  # pivots on the corner opposite the ground's push


COUPLED = Stack(Block.from_dimensions(1.2, 0.3), Plinth(1.0, 0.5, mass_ratio=1.5))


@functools.lru_cache(maxsize=None)
def _coupled(a_p_g: float, shape: str, restitution):
    """A scene where both blocks rock (impacts at both joints), with its impacts recorded."""
    pulse = (RickerSymmetric if shape == "ricker" else OneSine)(a_p_g * G, 0.9 if shape == "ricker" else 0.8)
    return reference_plinth(COUPLED, pulse, record_impacts=True, restitution=restitution, horizon=0.5, rtol=1e-9)


def _angular_momentum(model, v, st, q, point, blocks=None):
    """Clockwise angular momentum of the ``blocks`` (default all) about ``point`` (absolute velocities)."""
    _, Gs, _ = model.positions(st, q)
    L = 0.0
    for i in range(model.n) if blocks is None else blocks:
        dx, dy = Gs[i] - point
        vx, vy, w = v[3 * i:3 * i + 3]
        L += model.I[i] * w - model.m[i] * (dx * vy - dy * vx)
    return L


@pytest.mark.parametrize("restitution", [None, 0.8])
def test_impacts_never_add_energy_and_keep_their_momenta(restitution):
    """Over the impacts of a few coupled scenes (both blocks rocking): the kinetic energy never rises; the
    generalized momenta the impulses cannot touch are kept (the plastic rule: every pivot direction of the pattern
    after; with a restitution E: every one but the impacting pivot's); at a joint impact with the plinth on its
    corner, the whole stack's angular momentum about that corner (no impulse there has a moment about it); at a
    base impact with the body on its corner, the body's about its pivot."""
    model = StackModel(stack_blocks(COUPLED))
    seen = {"joint": 0, "base": 0}
    for a_p_g, shape in ((0.45, "ricker"), (-0.35, "sine")):
        out = _coupled(a_p_g, shape, restitution)
        assert out.impacts
        for d in out.impacts:
            assert d["ke_plus"] <= d["ke_minus"] * (1 + 1e-12)
            post, q, vm, vp = list(d["post"]), d["q"], d["v_minus"], d["v_plus"]
            kept = list(post)
            if restitution is not None:
                kept[d["j"]] = 0
            assert np.allclose(model.momenta(kept, q, vm), model.momenta(kept, q, vp), rtol=1e-9, atol=1e-12)
            _, _, piv = model.positions(post, q)
            if d["j"] == 1 and post[0] != 0 and d["pre"][0] == post[0]:
                seen["joint"] += 1
                La, Lb = (_angular_momentum(model, v, post, q, piv[0]) for v in (vm, vp))
                assert Lb == pytest.approx(La, rel=1e-9, abs=1e-12)
            if d["j"] == 0 and post[1] != 0 and d["pre"][1] == post[1]:
                seen["base"] += 1
                La, Lb = (_angular_momentum(model, v, post, q, piv[1], blocks=[1]) for v in (vm, vp))
                assert Lb == pytest.approx(La, rel=1e-9, abs=1e-12)
    assert seen["joint"] and seen["base"]


def test_flipping_the_ground_motion_flips_the_angles():
    a, b = _coupled(0.45, "ricker", None), _coupled(-0.45, "ricker", None)
    assert a.verdict == b.verdict and a.n_impacts == b.n_impacts
    assert [tuple(-s for s in p) for _, p in a.patterns] == [p for _, p in b.patterns]
    assert np.allclose(a.peak, b.peak, rtol=1e-7) and np.allclose(a.theta_peak, b.theta_peak, rtol=1e-7)
