"""A body on its plinth on linear bearings (docs/physics-plinth.md "On linear bearings"). The slow reference
(rockcli.reference.stack with the isolated base): its limits against the single block's own reference on the
isolated base, the rigid foundation as the bearings stiffen and the base grows heavy, impacts (energy never
rises, the momenta the impulses cannot touch kept, the total horizontal momentum among them), symmetry. The
compiled driver (rockcli.kernels.stack_linear through simulate_stack): against the reference, the single block's
compiled runs in the limits, verdict-only against history, symmetry; and what simulate_stack refuses. Short
pulses, at most 0.5 s after them."""

from __future__ import annotations

import functools
import math

import numpy as np
import pytest

from rockcli.errors import RockcliInputError
from rockcli.models import Block, LinearIsolation, Plinth, Rigid, SingleConcaveSliding, Stack
from rockcli.pulses import OneSine, RickerAntisymmetric, RickerSymmetric
from rockcli.records import Record
from rockcli.reference import reference_simulate
from rockcli.reference.stack import reference_plinth, stack_base, stack_blocks
from rockcli.reference.stack_mechanics import StackModel
from rockcli.solve import simulate, simulate_stack
from rockcli.io.units import G

BODY = Block.from_dimensions(1.2, 0.3)
WIDE = Stack(BODY, Plinth(0.2, 3.0, mass_ratio=5.0))  # a plinth that cannot lift
COUPLED = Stack(BODY, Plinth(1.0, 0.5, mass_ratio=1.5))  # both blocks rock
SQUAT = Stack(Block.from_dimensions(0.3, 0.4), Plinth(1.6, 0.4, mass_ratio=2.0))  # a body that stays on its plinth


def test_base_parameters_read_the_isolation_as_for_the_single_block():
    """gamma = (m1 + m2)/(m1 + m2 + m_b), k_b = (m + m_b) w^2, c_b = 2 xi w (m + m_b): per unit body mass."""
    iso = LinearIsolation(1.5, 0.08, 0.4)
    mb, kb, cb = stack_base(COUPLED, iso)
    total = (1.0 + COUPLED.m2) / 0.4
    assert mb == pytest.approx(total - 1.0 - COUPLED.m2, rel=1e-15)
    assert kb == pytest.approx(total * iso.omega_b ** 2, rel=1e-15)
    assert cb == pytest.approx(2 * 0.08 * iso.omega_b * total, rel=1e-15)
    assert stack_base(COUPLED, None) is None and stack_base(COUPLED, Rigid()) is None


@pytest.mark.parametrize("pulse", [OneSine(0.4 * G, 0.8), RickerAntisymmetric(0.5 * G, 0.6)])
def test_a_plinth_that_cannot_lift_is_the_single_block_with_the_plinth_in_the_base(pulse):
    """Pattern B on the bearings: the still plinth is part of the base, so the body is the single block on the
    isolated base of mass m_b + m2, i.e. gamma1 = m1/(m1 + m2 + m_b) = gamma/(1 + m2), the same T_b and xi (the
    same total mass, stiffness and damping). Against the single block's reference (angles, uplift, impacts) and
    its compiled run (the base's peak: the single block's reference does not follow the free base once it rests
    at the end of the excitation)."""
    iso = LinearIsolation(0.5, 0.05, 0.5)
    single = LinearIsolation(0.5, 0.05, 0.5 / (1.0 + WIDE.m2))
    out = reference_plinth(WIDE, pulse, isolation=iso, horizon=0.2, rtol=1e-10)
    ref = reference_simulate(BODY, single, pulse, atol=None, horizon=0.2, rtol=1e-10)
    assert ref.verdict == "rocked" and ref.n_impacts >= 1
    assert out.verdict == ref.verdict and out.peak[0] == 0.0 and math.isnan(out.t_uplift[0])
    assert out.peak[1] == pytest.approx(ref.theta_max, rel=1e-8)
    assert out.t_uplift[1] == pytest.approx(ref.t_uplift, abs=1e-9)
    assert out.n_impacts[1] == ref.n_impacts
    fast = simulate(BODY, single, pulse, horizon=0.2)
    assert out.base_disp_max == pytest.approx(fast.base_disp_max_m, rel=1e-6)
    assert out.n_jumps == 0 and out.n_inconsistent == 0


def test_a_body_that_cannot_lift_rocks_with_its_plinth_as_one_block_on_the_bearings():
    """Pattern P on the bearings: the assembly is one rigid body of first moment M R_asm and inertia J_asm about
    the corner. The single block ``as_block()`` (R_e = 3 g/(4 p_asm^2)) has the same p_asm and alpha_asm; its
    coupling to the base, gamma R per unit moving mass, equals the assembly's gamma R_asm when its gamma is
    gamma R_asm/R_e; and its impact with the restitution E = eta_asm (the single block's momentum rule E J theta'-)
    is the assembly's plastic impact (K_asm = eta_asm J_asm)."""
    iso = LinearIsolation(1.0, 0.1, 0.3)
    eff = SQUAT.as_block()
    single = LinearIsolation(1.0, 0.1, 0.3 * SQUAT.R_asm / eff.R)
    pulse = OneSine(0.4 * G, 0.8)
    out = reference_plinth(SQUAT, pulse, isolation=iso, horizon=0.5, rtol=1e-11)
    ref = reference_simulate(eff, single, pulse, restitution=SQUAT.eta_asm, atol=None, horizon=0.5, rtol=1e-11)
    assert ref.verdict == "rocked" and out.verdict == ref.verdict and out.peak[1] == 0.0
    assert out.peak[0] == pytest.approx(ref.theta_max, rel=1e-8)
    assert out.n_impacts[0] == ref.n_impacts
    assert out.t_uplift[0] == pytest.approx(ref.t_uplift, abs=1e-9)


def test_stiff_bearings_under_a_heavy_base_tend_to_the_rigid_foundation():
    """As T_b falls (gamma = 0.001: a heavy base, so that an impact's impulse moves it by nothing) the stack tends
    to the rigid foundation's: same verdict and impacts, the peaks' differences falling at least as T_b (measured:
    10 %, 4.6 %, 1.3 % at T_b = 0.08, 0.04, 0.02 s: about as T_b^2 once T_b is small).
    (A light base does not tend to the rigid foundation: a spring carries no impulse, so at each impact the base
    recoils with its own mass whatever its stiffness.)"""
    pulse = OneSine(-0.35 * G, 0.8)
    rigid = reference_plinth(COUPLED, pulse, horizon=0.2, rtol=1e-9)
    diffs = []
    for Tb in (0.08, 0.04):
        out = reference_plinth(COUPLED, pulse, isolation=LinearIsolation(Tb, 0.3, 0.001), horizon=0.2, rtol=1e-9)
        assert out.verdict == rigid.verdict and out.n_impacts == rigid.n_impacts
        diffs.append(max(abs(a / b - 1) for a, b in zip(out.peak, rigid.peak)))
    assert diffs[1] < 0.06 and diffs[1] < diffs[0] / 1.8


@functools.lru_cache(maxsize=None)
def _coupled(a_p_g: float, restitution):
    """Both blocks rock on the bearings, impacts at both interfaces, recorded."""
    pulse = OneSine(a_p_g * G, 0.8)
    return reference_plinth(COUPLED, pulse, isolation=LinearIsolation(0.5, 0.05, 0.5), record_impacts=True,
                            restitution=restitution, horizon=0.3, rtol=1e-9)


@pytest.mark.parametrize("restitution", [None, 0.8])
def test_impacts_on_the_bearings_never_add_energy_and_keep_their_momenta(restitution):
    """Every impact of a coupled scene on the bearings: the kinetic energy (blocks and base) never rises; the
    generalized momenta of the pattern after it are kept (with E: all but the impacting pivot's), the total
    horizontal momentum of blocks and base among them (the bearings' forces are finite)."""
    iso = LinearIsolation(0.5, 0.05, 0.5)
    model = StackModel(stack_blocks(COUPLED), stack_base(COUPLED, iso))
    out = _coupled(0.4, restitution)
    kinds = set()
    for d in out.impacts:
        kinds.add((d["j"], d["post"][1 - d["j"]] != 0))
        assert d["ke_plus"] <= d["ke_minus"] * (1 + 1e-12)
        post, q, vm, vp = list(d["post"]), d["q"], d["v_minus"], d["v_plus"]
        kept = list(post)
        if restitution is not None:
            kept[d["j"]] = 0
        assert np.allclose(model.momenta(kept, q, vm), model.momenta(kept, q, vp), rtol=1e-9, atol=1e-12)
        px = [float(np.sum(model.Mdiag[0::3][:2] * v[0:6:3]) + model.Mdiag[-1] * v[-1]) for v in (vm, vp)]
        assert px[1] == pytest.approx(px[0], rel=1e-9, abs=1e-12)
        assert vp[-1] != vm[-1]  # the base does take part
    assert {j for j, _ in kinds} == {0, 1}  # impacts at the base and at the joint


def test_a_restitution_on_the_bearings_is_the_energetic_rule():
    """With a plinth that stays, a body's impact with E keeps theta_dot+ = E theta_dot- exactly and the total
    horizontal momentum (the energetic rule of the note). The single block on an isolated base reads E as an
    impulsive couple (E J theta_dot- as the momentum before), which gives a smaller rebound: the two agree only on
    the rigid foundation (docs/physics-plinth.md, "On linear bearings")."""
    pulse = RickerAntisymmetric(0.5 * G, 0.6)
    out = reference_plinth(WIDE, pulse, isolation=LinearIsolation(0.5, 0.05, 0.5), restitution=0.8,
                           record_impacts=True, horizon=0.2, rtol=1e-9)
    assert len(out.impacts) >= 2
    for d in out.impacts:
        assert d["post"][0] == 0 and d["j"] == 1
        w_m, w_p = d["v_minus"][5], d["v_plus"][5]
        assert w_p == pytest.approx(0.8 * w_m, rel=1e-9)


def test_flipping_the_ground_motion_flips_the_stack_and_its_base():
    a, b = _coupled(0.4, None), _coupled(-0.4, None)
    assert a.verdict == b.verdict and a.n_impacts == b.n_impacts
    assert [tuple(-s for s in p) for _, p in a.patterns] == [p for _, p in b.patterns]
    assert np.allclose(a.peak, b.peak, rtol=1e-7) and np.allclose(a.theta_peak, b.theta_peak, rtol=1e-7)
    assert a.base_disp_max == pytest.approx(b.base_disp_max, rel=1e-7)


@pytest.mark.parametrize("iso, words", [
    (LinearIsolation(2.0, 0.1, 0.0), "needs a base of finite mass: give gamma > 0"),
    (SingleConcaveSliding(2.5, 0.05, gamma=0.0), "needs a base of finite mass: give gamma > 0"),
    ("scss", "stands on a rigid foundation or on bearings, not on str")])
def test_simulate_stack_refuses_what_its_driver_does_not_run(iso, words):
    with pytest.raises(RockcliInputError, match=re_escape(words)):
        simulate_stack(WIDE, RickerSymmetric(0.3 * G, 1.0), isolation=iso)


def test_simulate_stack_on_a_rigid_foundation_reports_no_base_displacement():
    r = simulate_stack(WIDE, RickerSymmetric(0.3 * G, 1.0), isolation=Rigid())
    assert math.isnan(r.base_disp_max) and r.as_dict()["base_disp_max_m"] is None
    assert r.as_dict() == simulate_stack(WIDE, RickerSymmetric(0.3 * G, 1.0)).as_dict()


def re_escape(s):
    import re

    return re.escape(s)


def _bp_linear(stack, iso, s, k, th1, th2, thd1, thd2, u, ud, ag):
    """Pattern BP on the bearings as docs/physics-plinth.md writes it: the rigid foundation's 2x2 Lagrange system
    with the base's absolute acceleration a_b for ag, closed by the horizontal momentum balance (3x3)."""
    b1, h1, b2, h2, m2 = stack.b1, stack.h1, stack.b2, stack.h2, stack.m2
    R1, a1, R2, a2 = stack.body.R, stack.body.alpha, stack.R2, stack.alpha2
    D, delta = math.hypot(s * b2 - k * b1, 2 * h2), math.atan2(s * b2 - k * b1, 2 * h2)
    phi = th1 - k * a1 - th2 + delta
    M11, M22, M12 = 4 / 3 * R1 ** 2, 4 / 3 * m2 * R2 ** 2 + D ** 2, D * R1 * math.cos(phi)
    c1 = R1 * math.cos(k * a1 - th1)
    c2 = m2 * R2 * math.cos(s * a2 - th2) + D * math.cos(th2 - delta)
    Q1 = -R1 * G * math.sin(k * a1 - th1) - D * R1 * math.sin(phi) * thd2 ** 2
    Q2 = -m2 * R2 * G * math.sin(s * a2 - th2) + D * G * math.sin(th2 - delta) + D * R1 * math.sin(phi) * thd1 ** 2
    Mt = (1 + m2) / iso.gamma
    F = -iso.omega_b ** 2 * u - 2 * iso.xi * iso.omega_b * ud
    Q3 = Mt * F + R1 * math.sin(th1 - k * a1) * thd1 ** 2 + (m2 * R2 * math.sin(th2 - s * a2)
                                                              + D * math.sin(th2 - delta)) * thd2 ** 2
    A = np.array([[M11, M12, c1], [M12, M22, c2], [c1, c2, Mt]])
    th1dd, th2dd, ab = np.linalg.solve(A, [Q1, Q2, Q3])
    return th1dd, th2dd, ab - ag


def _random_stack_model(rng, iso):
    """A random body on a random plinth of its own mass ratio, and the reference's model of it on ``iso``."""
    stack = Stack(Block.from_dimensions(rng.uniform(0.4, 2.5), rng.uniform(0.15, 0.8)),
                  Plinth(rng.uniform(0.1, 1.5), rng.uniform(0.8, 2.0), mass_ratio=float(rng.uniform(0.2, 5))))
    return stack, StackModel(stack_blocks(stack), stack_base(stack, iso))


def test_the_3x3_system_of_the_note_is_newton_euler_with_constraints():
    """At random states of every pattern BP, the closed form of the note (3x3: both angles and the base) agrees
    with the reference's Newton-Euler equations with constraint multipliers."""
    rng = np.random.default_rng(36)
    iso = LinearIsolation(0.8, 0.15, 0.4)
    worst = 0.0
    for _ in range(200):
        stack, model = _random_stack_model(rng, iso)
        s, k = rng.choice([-1, 1], 2)
        th2, psi = s * rng.uniform(0, 0.3), k * rng.uniform(0, 0.3)
        thd2, psid, u, ud, ag = rng.normal(size=5)
        qdd, _, udd = model.accelerations([int(s), int(k)], [th2, psi], [thd2, psid], ag, u, ud)
        th1dd, th2dd, udd_n = _bp_linear(stack, iso, s, k, th2 + psi, th2, thd2 + psid, thd2, u, ud, ag)
        got = np.array([th2dd, th1dd - th2dd, udd_n])
        ref = np.array([qdd[0], qdd[1], udd])
        worst = max(worst, float(np.max(np.abs(got - ref)) / (1 + np.max(np.abs(ref)))))
    assert worst < 1e-11


def test_patterns_b_and_p_are_the_single_block_on_the_bearings_at_random_states():
    """Pattern B is Eqs (10)-(11) of the body with gamma1 = gamma/(1 + m2), pattern P those of ``as_block()``
    with gamma R_asm/R_e (the note's two equivalences), at random states; the base's corner forces in B are the
    rigid foundation's with the base's absolute acceleration a_b for ag."""
    from rockcli.reference.equations import rocking_on_base

    rng = np.random.default_rng(7)
    iso = LinearIsolation(0.8, 0.15, 0.4)
    worst = 0.0
    for _ in range(200):
        stack, model = _random_stack_model(rng, iso)
        c = int(rng.choice([-1, 1]))
        a, ad, u, ud, ag = c * rng.uniform(0, 0.3), *rng.normal(size=4)
        F = -iso.omega_b ** 2 * u - 2 * iso.xi * iso.omega_b * ud
        # B: the body on corner c of the still plinth
        qdd, f, udd = model.accelerations([0, c], [0.0, a], [0.0, ad], ag, u, ud)
        b = stack.body
        thdd, a_abs = rocking_on_base(a, ad, c, F, alpha=b.alpha, p2=b.p ** 2, gamma=iso.gamma / (1 + stack.m2),
                                      R=b.R)
        worst = max(worst, abs(qdd[1] - thdd) / (1 + abs(thdd)), abs(udd + ag - a_abs) / (1 + abs(a_abs)))
        A1 = c * b.alpha - a  # the joint's force from the body's centre acceleration in the base's frame
        ax = b.R * (thdd * math.cos(A1) + ad ** 2 * math.sin(A1))
        ay = b.R * (thdd * math.sin(A1) - ad ** 2 * math.cos(A1))
        FJx, FJy = ax + a_abs, ay + G
        P_left = (FJy * (stack.b2 - c * stack.b1) + stack.m2 * G * stack.b2 + 2 * stack.h2 * FJx
                  + stack.m2 * stack.h2 * a_abs) / (2 * stack.b2)
        worst = max(worst, abs(f[0][3] - P_left) / (1 + stack.m2) / G)
        # P: the assembly on corner c
        qdd, f, udd = model.accelerations([c, 0], [a, 0.0], [ad, 0.0], ag, u, ud)
        e = stack.as_block()
        thdd, a_abs = rocking_on_base(a, ad, c, F, alpha=stack.alpha_asm, p2=stack.p_asm ** 2,
                                      gamma=iso.gamma * stack.R_asm / e.R, R=e.R)
        worst = max(worst, abs(qdd[0] - thdd) / (1 + abs(thdd)), abs(udd + ag - a_abs) / (1 + abs(a_abs)))
    assert worst < 1e-11


# ---------------------------------------------------------------------------------------------
# The compiled driver
# ---------------------------------------------------------------------------------------------
def _close(a, r, stack, rel=1e-5):
    """The kernel's run ``a`` against the reference's ``r``: verdict, block toppled, impacts, peaks over the
    slenderness within ``rel``, the base's peak relatively (unless a block toppled)."""
    assert a.verdict == r.verdict and a.toppled == {-1: None, 0: "plinth", 1: "body"}[r.toppled]
    assert [a.plinth.n_impacts, a.body.n_impacts] == r.n_impacts
    assert abs(a.body.theta_max - r.peak[1]) / stack.body.alpha < rel
    assert abs(a.plinth.theta_max - r.peak[0]) / stack.alpha_asm < rel
    if a.toppled is None:
        assert a.base_disp_max == pytest.approx(r.base_disp_max, rel=rel)


@pytest.mark.parametrize("restitution", [None, 0.8])
@pytest.mark.parametrize("a_p_g", [0.4, -0.4])
def test_the_compiled_driver_agrees_with_the_reference_where_both_blocks_rock(a_p_g, restitution):
    r = _coupled(a_p_g, restitution)
    a = simulate_stack(COUPLED, OneSine(a_p_g * G, 0.8), isolation=LinearIsolation(0.5, 0.05, 0.5),
                       restitution=restitution, horizon=0.3, tail=0.0)
    assert r.n_impacts[0] > 0 and r.n_impacts[1] > 0
    _close(a, r, COUPLED)


@pytest.mark.parametrize("pulse", [OneSine(0.4 * G, 0.8), RickerAntisymmetric(0.5 * G, 0.6),
                                   RickerSymmetric(0.6 * G, 0.5), OneSine(-0.9 * G, 0.4)])
def test_the_compiled_driver_with_a_plinth_that_cannot_lift_is_the_single_block_on_the_bearings(pulse):
    """Pattern B in the compiled driver against the single block's compiled run with gamma/(1 + m2): the same
    verdict and impacts, peaks and the base's peak to 1e-6 (two integrators, each to its tolerance; not bit for
    bit as on the rigid foundation, where the stack reuses the single block's own code)."""
    single = LinearIsolation(0.5, 0.05, 0.5 / (1.0 + WIDE.m2))
    a = simulate_stack(WIDE, pulse, isolation=LinearIsolation(0.5, 0.05, 0.5), horizon=2.0)
    ref = simulate(BODY, single, pulse, horizon=2.0)
    assert a.plinth.theta_max == 0.0 and math.isnan(a.plinth.t_uplift_s)
    assert a.verdict == ref.verdict and a.body.n_impacts == ref.n_impacts
    assert a.body.theta_max == pytest.approx(ref.theta_max, rel=1e-6)
    assert a.body.t_uplift_s == pytest.approx(ref.t_uplift_s, abs=1e-7)
    if a.verdict != "overturned":
        assert a.base_disp_max == pytest.approx(ref.base_disp_max_m, rel=1e-6)


def test_the_compiled_driver_with_a_body_that_cannot_lift_is_the_assembly_on_the_bearings():
    iso = LinearIsolation(1.0, 0.1, 0.3)
    eff = SQUAT.as_block()
    pulse = RickerSymmetric(0.5 * G, 0.6)
    a = simulate_stack(SQUAT, pulse, isolation=iso, horizon=2.0)
    ref = simulate(eff, LinearIsolation(1.0, 0.1, 0.3 * SQUAT.R_asm / eff.R), pulse, restitution=SQUAT.eta_asm,
                   horizon=2.0)
    assert ref.verdict == "rocked" and ref.n_impacts > 2 and a.verdict == ref.verdict and a.body.theta_max == 0.0
    assert a.plinth.theta_max == pytest.approx(ref.theta_max, rel=1e-6)
    assert a.plinth.n_impacts == ref.n_impacts


def test_verdict_only_and_history_runs_agree_and_the_mirror_flips():
    iso = LinearIsolation(0.5, 0.05, 0.5)
    for pulse in (OneSine(0.4 * G, 0.8), RickerAntisymmetric(0.5 * G, 0.6)):
        a = simulate_stack(COUPLED, pulse, isolation=iso, horizon=2.0)
        b = simulate_stack(COUPLED, pulse, isolation=iso, horizon=2.0, history=True)
        da, db = a.as_dict(), b.as_dict()
        assert da.pop("steps") <= db.pop("steps")  # the history run goes on for its tail once settled
        assert da == db
        assert b.history is not None and b.history.u is not None and np.max(np.abs(b.history.u)) <= a.base_disp_max
        m = simulate_stack(COUPLED, type(pulse)(-pulse.a_p, pulse.T_p), isolation=iso, horizon=2.0)
        assert m.verdict == a.verdict and m.toppled == a.toppled
        assert m.body.theta_max == pytest.approx(a.body.theta_max, rel=1e-9)
        assert m.plinth.theta_max == pytest.approx(a.plinth.theta_max, rel=1e-9)
        assert m.base_disp_max == pytest.approx(a.base_disp_max, rel=1e-9)


def test_a_plinth_left_with_no_rate_by_an_impact_goes_where_the_accelerations_take_it(find_record):
    """The statue on a plinth 1.0 m x 0.6 m on a light base (gamma = 0.5) under the first 9 s of the Friuli record:
    at t = 7.5103 s a base impact leaves the plinth's pivot with no rate either way; taking the pivot the impulses
    chose, both codes chattered between the plinth's corners at that instant (thousands of impacts, the step cap).
    With the rule (the pivot goes where the accelerations take it; here neither corner opens, the face sticks) the
    run goes on: its impacts are those of a rocking stack (the reference, run once: 199 and 97) and it settles."""
    from rockcli.records import read_record

    rec = read_record(find_record("RSN292_ITALY_A-STU270.AT2"))
    short = Record(np.asarray(rec.acc)[:int(9.0 / rec.dt)], rec.dt, "friuli-9s")
    stack = Stack(Block.from_dimensions(1.79, 0.5), Plinth(1.0, 0.6))
    a = simulate_stack(stack, short, isolation=LinearIsolation(2.0, 0.1, 0.5), horizon=0.0, tail=0.0)
    assert a.status == 0 and a.verdict == "rocked"
    assert 50 < a.plinth.n_impacts < 400 and 20 < a.body.n_impacts < 200
