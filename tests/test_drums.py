"""Columns of drums (issue "Columns as they stand"): the chain's kinematics where a drum has slid past the edge of the
one below (its pivot the corner of the top below, "kind B"), checked against finite differences of the positions;
the faces' corner forces at the ends of the overlap; the static thresholds of each joint against their closed forms;
a column of one drum as the single block and of drums that cannot open as the monolith."""

from __future__ import annotations

import math

import numpy as np
import pytest

from rockcli.errors import RockcliInputError
from rockcli.io.units import G
from rockcli.models import Block
from rockcli.models.drums import DrumColumn


def _chain(column, mu=0.7):
    from rockcli.kernels import chain as ch
    from rockcli.solve.slide import chain_parameters

    cp = chain_parameters(column, mu)
    return ch, cp


def _random_column(rng, n):
    drums = []
    w = rng.uniform(0.6, 1.6)
    for _ in range(n):
        drums.append((rng.uniform(0.3, 1.2), w * rng.uniform(0.85, 1.15)))
    return DrumColumn(tuple(drums))


def _positions(ch, cp, pat, y, ws):
    ch.kinematics(cp, pat, y, ws)
    return ws[5].copy(), ws[8].copy()  # G, th


def test_kinematics_of_drums_slid_past_each_other_are_the_derivatives_of_their_positions():
    """For random columns of 2-5 drums, every joint a pivot that slides (so every coordinate moves), at slips on both
    sides of the switch between the block's own corner and the corner below: the velocities the kinematics give are
    the time derivatives of its positions along q(t) = q + q' t + q'' t^2 / 2, and its affine accelerations ``AG q''
    + bG`` (``AA q'' + bA``) the derivatives of those velocities (central differences, step 1e-5 s)."""
    rng = np.random.default_rng(46)
    n_kind_b = 0
    worst_v = worst_a = 0.0
    for trial in range(400):
        n = int(rng.integers(2, 6))
        col = _random_column(rng, n)
        ch, cp = _chain(col)
        ws = ch.workspace(n)
        pat = np.zeros(2 * n)
        y = np.zeros(ch.n_states(n))
        for j in range(n):
            c = float(rng.choice([-1.0, 1.0]))
            pat[2 * j] = c
            pat[2 * j + 1] = float(rng.choice([-1.0, 1.0]))
            b = cp[ch.CP_BLK + ch.NF_BLK * j + ch.F_B]
            bl = cp[ch.CP_BLK + ch.NF_BLK * j + ch.F_BLOW]
            sw = c * (bl - b) if math.isfinite(bl) else 0.0
            y[ch.col_s(j)] = sw + rng.uniform(-0.3, 0.3) * b
            y[ch.col_s(j) + 1] = rng.normal() * 0.3
            y[ch.col_psi(j)] = c * rng.uniform(0.0, 0.3)
            y[ch.col_psi(j) + 1] = rng.normal() * 0.5
            if math.isfinite(bl) and c * y[ch.col_s(j)] + b > bl:
                n_kind_b += 1
        nf = ch.kinematics(cp, pat, y, ws)
        free = ws[0][:nf].copy()
        qdd = rng.normal(size=nf)
        AG, bG, AA, bA, vG, om = ws[1].copy(), ws[2].copy(), ws[3].copy(), ws[4].copy(), ws[6].copy(), ws[7].copy()
        aG = np.einsum("ijk,k->ij", AG[:, :, :nf], qdd) + bG
        aA = AA[:, :nf] @ qdd + bA

        def state(t):
            z = y.copy()
            for k, col in enumerate(free):
                z[col] = y[col] + y[col + 1] * t + 0.5 * qdd[k] * t * t
                z[col + 1] = y[col + 1] + qdd[k] * t
            return z

        hs = 1e-5
        Gp, thp = _positions(ch, cp, pat, state(hs), ws)
        Gm, thm = _positions(ch, cp, pat, state(-hs), ws)
        scale_v = 1.0 + np.abs(vG).max()
        worst_v = max(worst_v, np.abs((Gp - Gm) / (2 * hs) - vG).max() / scale_v,
                      np.abs((thp - thm) / (2 * hs) - om).max() / (1.0 + np.abs(om).max()))
        ch.kinematics(cp, pat, state(hs), ws)
        vp, op = ws[6].copy(), ws[7].copy()
        ch.kinematics(cp, pat, state(-hs), ws)
        vm, omm = ws[6].copy(), ws[7].copy()
        scale_a = 1.0 + np.abs(aG).max()
        worst_a = max(worst_a, np.abs((vp - vm) / (2 * hs) - aG).max() / scale_a,
                      np.abs((op - omm) / (2 * hs) - aA).max() / (1.0 + np.abs(aA).max()))
    assert n_kind_b > 200  # the corner of the top below was the pivot in many joints
    assert worst_v < 1e-7, worst_v
    assert worst_a < 1e-6, worst_a


def test_the_pivot_moves_continuously_to_the_corner_below():
    """At the switch (the block's corner exactly over the corner below) both descriptions give the same positions at
    any tilt, and the same velocities when the drum stands upright on the joint (``psi = 0``: the top below and the
    drum's base are parallel). Tilted, the corner that slid along the top below would leave the top's level at once:
    the switch's plastic map (``kernels.chain_kind.kind_switch``) keeps the new contact and never adds energy."""
    from rockcli.kernels.chain_kind import kind_switch

    rng = np.random.default_rng(7)
    gains = []
    for _ in range(300):
        n = int(rng.integers(2, 4))
        ch, cp = _chain(_random_column(rng, n))
        ws = ch.workspace(n)
        j = int(rng.integers(1, n))
        c = float(rng.choice([-1.0, 1.0]))
        pat = np.zeros(2 * n)
        pat[2 * j], pat[2 * j + 1] = c, float(rng.choice([-1.0, 1.0]))
        y = np.zeros(ch.n_states(n))
        tilt = c * rng.uniform(0, 0.4)
        y[ch.col_psi(j) + 1] = rng.normal()
        y[ch.col_s(j) + 1] = pat[2 * j + 1] * abs(rng.normal())
        b = cp[ch.CP_BLK + ch.NF_BLK * j + ch.F_B]
        bl = cp[ch.CP_BLK + ch.NF_BLK * j + ch.F_BLOW]
        sw = c * (bl - b)
        for psi in (0.0, tilt):
            y[ch.col_psi(j)] = psi
            out = []
            for eps in (-1e-13, 1e-13):
                y[ch.col_s(j)] = sw + eps
                ch.kinematics(cp, pat, y, ws)
                out.append((ws[5].copy(), ws[6].copy()))
            assert np.allclose(out[0][0], out[1][0], atol=1e-11)
            if psi == 0.0:
                assert np.allclose(out[0][1], out[1][1], atol=1e-10)
        # the plastic map at the switch: energy never rises; the new contact's normal velocity is 0 after it
        y[ch.col_s(j)] = sw
        y_before = y.copy()
        y_before[ch.col_s(j)] = sw - np.sign(y[ch.col_s(j) + 1]) * 1e-12 * bl
        e0 = sum(ch.energy(cp, pat, y_before, ws))
        kind_switch(cp, pat, y, j, ws, np.zeros((n, 2)), np.zeros(n))
        e1 = sum(ch.energy(cp, pat, y, ws))
        gains.append((e1 - e0) / max(e0, 1e-12))
    assert max(gains) < 1e-9, max(gains)
    assert min(gains) < -1e-4  # tilted drums lose energy at the switch


def test_face_corner_forces_at_the_ends_of_the_overlap():
    """A face's corner forces balance its normal force and its couple about the base's centre, with the forces at the
    ends of the overlap (``P_R + P_L = N``, ``e_R P_R + e_L P_L = -Mc``), and equal the centred formula where the
    block's corners are the ends."""
    from rockcli.kernels.contact import face_corners

    rng = np.random.default_rng(3)
    for _ in range(500):
        ch, cp = _chain(_random_column(rng, 2))
        j = 1
        b = cp[ch.CP_BLK + ch.NF_BLK * j + ch.F_B]
        bl = cp[ch.CP_BLK + ch.NF_BLK * j + ch.F_BLOW]
        s = rng.uniform(-1.5, 1.5) * b
        N, Mc = rng.uniform(0, 10), rng.normal() * 3
        pr, pl = face_corners(cp, j, s, N, Mc)
        er = min(b, bl - s)
        el = max(-b, -bl - s)
        assert pr + pl == pytest.approx(N, rel=1e-12, abs=1e-12)
        assert er * pr + el * pl == pytest.approx(-Mc, rel=1e-10, abs=1e-10)
        # at the edge (no overlap left: the slip where the run ends as slid off) the contact is a point: no division
        # by its zero width, the normal force shared
        for edge in (bl + b, -(bl + b)):
            assert face_corners(cp, j, edge, N, Mc) == (0.5 * N, 0.5 * N)


def test_static_thresholds_of_each_joint():
    """Each joint of a centred column at rest opens at ``g tan(alpha_j)``, ``alpha_j`` the slenderness of everything
    above it about its corner: for equal drums ``b (N - j) / (sum of the heights of the centres above)``, which for
    equal drums of height ``2 h`` is ``b / (h (N - j))``. The bottom joint is the monolith's ``b / h_total``."""
    col = DrumColumn.uniform(5.95, 1.11, 7)
    th = col.static_thresholds()
    b = 1.11 / 2
    hd = 5.95 / 7 / 2
    for j, t in enumerate(th):
        k = 7 - j  # drums above the joint
        assert t == pytest.approx(b / (hd * k), rel=1e-12)
    assert th[0] == pytest.approx(math.tan(col.monolith.alpha), rel=1e-12)
    assert th == sorted(th)  # the base opens first


def test_a_drum_column_refuses_bad_drums():
    with pytest.raises(RockcliInputError, match="drum 2: width"):
        DrumColumn(((1.0, 0.5), (1.0, -0.5)))
    with pytest.raises(RockcliInputError, match="1 to"):
        DrumColumn(())
    with pytest.raises(RockcliInputError, match="whole number"):
        DrumColumn.uniform(5.0, 1.0, 2.5)


def _pulse(rng):
    from rockcli.pulses import OneSine, RickerAntisymmetric, RickerSymmetric

    kinds = (RickerSymmetric, OneSine, RickerAntisymmetric)
    return kinds[int(rng.integers(0, 3))](rng.uniform(0.2, 0.9) * G, rng.uniform(0.3, 1.5))


def test_one_drum_is_the_block_and_two_are_the_body_on_its_plinth_bit_for_bit():
    """A column of one drum runs as the single block of its size, and of two drums (the upper no wider) as that body
    on that plinth, to the last bit, wherever no slip reaches the plinth's edge (where the plinth's fall criterion
    and the drums' overlap part: docs/physics-drums.md)."""
    from rockcli.models import Plinth, Stack
    from rockcli.solve.slide import simulate_friction

    rng = np.random.default_rng(461)
    same2 = 0
    for _ in range(12):
        h, w = rng.uniform(0.5, 3.0), rng.uniform(0.3, 1.2)
        exc = _pulse(rng)
        mu = float(rng.uniform(0.2, 1.0))
        a = simulate_friction(DrumColumn(((h, w),)), exc, mu).as_dict()
        b = simulate_friction(Block.from_dimensions(h, w), exc, mu).as_dict()
        assert a == b
        h2, w2 = rng.uniform(0.3, 1.4), w * rng.uniform(1.0, 1.6)
        mus = (float(rng.uniform(0.3, 1.0)), float(rng.uniform(0.3, 1.0)))
        c = simulate_friction(DrumColumn(((h2, w2), (h, w))), exc, mus)
        d = simulate_friction(Stack(Block.from_dimensions(h, w), Plinth(h2, w2)), exc, mus)
        if c.joint.slide_max_m < d.joint.edge_m and d.verdict != "slid off":
            same2 += 1
            cd, dd = c.as_dict(), d.as_dict()
            for x in (cd, dd):  # the drums' names and edge (the overlap's end) are theirs
                x["joint"].pop("edge_m"), x["joint"].pop("name")
            assert cd == dd
    assert same2 >= 8


def test_drums_that_cannot_open_or_slide_are_the_monolith():
    """Drums under a ground motion too weak to open any joint (every joint's static threshold above the peak
    acceleration, friction above it too) rock as one: the column's base does what the monolith does, within the
    solvers' tolerance (the stack integrates more coordinates), and no joint moves."""
    from rockcli.pulses import RickerSymmetric
    from rockcli.solve.drums import simulate_drums

    col = DrumColumn.uniform(5.95, 1.11, 5)
    th = col.static_thresholds()
    ap = 0.5 * (th[0] + th[1])  # above the base's threshold (the monolith rocks), below every joint's
    run = simulate_drums(col, RickerSymmetric(ap * G, 1.0), 1.0)
    assert run.monolith.verdict == "survives"
    assert run.stack.verdict == "survives"
    assert all(p.psi_max == 0.0 and p.n_slips == 0 for p in run.stack.interfaces[1:])
    assert run.stack.base.psi_max == pytest.approx(run.monolith.base.psi_max, abs=1e-6 * run.monolith.base.alpha)
    assert run.stack.base.n_impacts == run.monolith.base.n_impacts
    assert run.compared == "alike" and run.first_move[0] == "base"


def test_no_joint_turns_through_the_drum_below():
    """Every pivot's angle stays on its own side of the surface and below pi/2 (a topple ends the run there): on
    random columns of 3-6 drums under strong pulses, every history row has ``c psi >= 0`` for each joint that pivots
    on corner ``c`` and ``|psi| <= pi/2``. A joint of a 6-drum column once entered its pivot a rounding error
    (4e-31 rad) on the wrong side; the impact and topple events watch the angle on its own side, so it turned on
    through the drum below to 3.6 rad (kernels.chain_step.state_events now takes it as a wrong side)."""
    from rockcli.kernels import chain_out as co
    from rockcli.pulses import OneSine, RickerSymmetric
    from rockcli.solve.slide import simulate_friction

    rng = np.random.default_rng(46)
    scenes = [(DrumColumn.uniform(10.33, 1.52, 6), RickerSymmetric(0.5 * G, 1.0), 0.7)]  # the one that turned through
    for k in range(12):
        n = int(rng.integers(3, 7))
        col = DrumColumn.uniform(float(rng.uniform(4.0, 10.0)), float(rng.uniform(0.8, 1.6)), n)
        kind = (RickerSymmetric, OneSine)[k % 2]
        scenes.append((col, kind(float(rng.uniform(0.3, 0.8)) * G, float(rng.uniform(0.5, 1.5))),
                       float(rng.uniform(0.5, 0.9))))
    worst_side, worst_angle = 0.0, 0.0
    for col, pulse, mu in scenes:
        n = col.n
        r = simulate_friction(col, pulse, mu, history=True, max_steps=20000 if n == 6 and mu == 0.7 else 4000)
        H = r.history
        pats = H[:, co.HC_PAT:co.HC_PAT + 2 * n:2]
        psi = H[:, co.HC_PAT + 2 * n + 4:co.HC_PAT + 2 * n + 2 + 4 * n:4]
        worst_side = min(worst_side, float((pats * psi).min()))
        worst_angle = max(worst_angle, float(np.abs(psi).max()))
    assert worst_side >= -1e-12
    assert worst_angle <= 0.5 * math.pi + 1e-12
