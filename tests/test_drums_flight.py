"""Flight in the slow reference of a column of drums (``reference_drums(..., flight=True)``,
rockcli.reference.drum_flight, docs/physics-drums.md "Flight (in the reference)"): the answer without pulls is the
answer without flight, free flight is a parabola, landings take energy out and conserve the angular momentum about the
landing corner, and strong shaking leaves no pivot pulling."""

from __future__ import annotations

import math
import os
import sys

import numpy as np
import pytest

from rockcli.io.units import G
from rockcli.models.drums import DrumColumn
from rockcli.pulses import RickerSymmetric
from rockcli.reference.friction_drums import chain_of, reference_drums

sys.path.insert(0, os.path.dirname(__file__))  # tests/synthetic.py

STRONG = dict(scale=(3.0, 6.0), cap=1.5)  # 3-6 times the column's first static threshold, at most 1.5 g


def _scene(seed, n, strong=True):
    from synthetic import random_drum_scene

    return random_drum_scene(seed, n, **(STRONG if strong else {}))


@pytest.mark.parametrize("seed,n,kw", [(4, 2, {}), (6, 2, {}), (5, 2, {}), (203, 4, {"horizon": 0.0}),
                                        (201, 4, {"horizon": 0.0, "max_phases": 60})])
def test_without_pulls_flight_changes_nothing(seed, n, kw):
    """Strong scenes where no pivot pulls (flight=False counts no jump and flight=True lifts nothing off): the same
    verdict, counts and peaks (to 1e-12: the runs take the same events; found 4e-14)."""
    col, exc, mu, iso = _scene(seed, n)
    a = reference_drums(col, exc, mu, iso, **kw)
    b = reference_drums(col, exc, mu, iso, flight=True, **kw)
    assert a.n_jumps == 0 and b.n_flights == 0 and b.n_jumps == 0
    assert a.verdict == b.verdict and (a.toppled, a.slid_off) == (b.toppled, b.slid_off)
    assert (a.n_slips, a.n_impacts, a.n_inconsistent) == (b.n_slips, b.n_impacts, b.n_inconsistent)
    for x, y in ((a.psi_max, b.psi_max), (a.s_max, b.s_max), (a.s_end, b.s_end)):
        assert y == pytest.approx(x, abs=1e-12, rel=0)


def test_free_flight_is_a_parabola():
    """Two drums, a strong Ricker pulse: the top drum's pivot (of kind B: it overhangs) pulls and lifts off, and
    flies 0.57 s while the drum below slides. In flight nothing acts on the top drum but gravity and the inertial
    force of the ground's motion: along the sampled flight its centre's height is ``y0 + vy0 t - g t^2 / 2``, its
    angle ``theta0 + omega0 t``, its rates ``vy0 - g t`` and ``omega0``, and its horizontal rate ``vx0 - int ag``."""
    from scipy.integrate import quad

    col, exc, mu, iso = _scene(2, 2)
    r = reference_drums(col, exc, mu, iso, flight=True, trace=True)
    assert r.n_flights >= 1 and r.flight_time[1] > 0.3 and r.n_jumps == 0
    path = [p for p in r.flight_path if 1 in p[3]]
    t0, X0, V0, _ = path[0]
    first = [p for p in path if p[0] - t0 <= r.flight_time[1] + 1e-9]
    assert len(first) > 50
    scale = col.drums[1][0]
    for t, X, V, _ in first:
        dt = t - t0
        assert X[4] == pytest.approx(X0[4] + V0[4] * dt - 0.5 * G * dt * dt, abs=1e-12 * scale)
        assert X[5] == pytest.approx(X0[5] + V0[5] * dt, abs=1e-12)
        assert V[4] == pytest.approx(V0[4] - G * dt, abs=1e-11 * scale)
        assert V[5] == pytest.approx(V0[5], abs=1e-11)
        dvx = -quad(exc.acceleration, t0, t, epsabs=1e-13, limit=200)[0] if dt > 0 else 0.0
        assert V[3] == pytest.approx(V0[3] + dvx, abs=1e-9 * scale)


def test_energy_never_rises_across_a_landing():
    """Random strong scenes of 2 and 3 drums with flights and landings: every landing (as every impact, switch and
    projection) takes kinetic energy out, to rounding."""
    landings = 0
    for seed, n in ((0, 2), (1, 2), (100, 3), (200, 3), (210, 3)):
        col, exc, mu, iso = _scene(seed, n)
        r = reference_drums(col, exc, mu, iso, flight=True, record_energy=True, horizon=0.0)
        landings += r.n_landings
        assert max(r.energy_rises, default=0.0) <= 1e-12 * G * sum(h * w for h, w in col.drums)
    assert landings >= 3


def _run(col, mu):
    """A flight run at rest (no shaking) whose state the test sets."""
    from rockcli.reference.drum_flight_run import FlightRun

    ch = chain_of(col, mu)
    return FlightRun(ch, RickerSymmetric(0.0, 1.0), 1e-10, 0.0, 1e-8, "DOP853", False, None, 1e-9, True, "auto")


@pytest.mark.parametrize("n", [1, 2])
def test_a_tilted_landing_on_a_corner_conserves_the_angular_momentum_about_it(n):
    """A drum flying tilted (``psi`` up to 0.3 rad, any rates, closing) lands on its lowest corner, alone on the
    ground or on a wide, low drum resting on its face (which it cannot tip): Moreau's plastic impact, sticking (``mu =
    5``), leaves it turning about that corner with ``omega+ = H_C / I_C`` (``H_C`` its angular momentum about the
    corner before, ``I_C = 4/3 m (b^2 + h^2)``), its centre moving with the corner at rest, and the kinetic energy
    lower. At a tilt of 1e-7 after turning about the other corner, ``omega+ / omega- = 1 - 3/2 sin^2 alpha``, the
    rocking model's coefficient."""
    rng = np.random.default_rng(7 + n)
    top = n - 1
    for k in range(40):
        h, w = rng.uniform(0.4, 1.5), rng.uniform(0.3, 1.0)
        drums = ((0.2, 4.0),) * (n - 1) + ((h, w),)  # a wide, low drum below: its face cannot open
        col = DrumColumn(drums)
        run = _run(col, 5.0)
        ch = run.ch
        b, hh, m, I = ch.b[top], ch.h[top], ch.m[top], ch.I[top]
        side = float(rng.choice([-1.0, 1.0]))
        classic = k == 0
        psi = side * (1e-7 if classic else rng.uniform(0.02, 0.3))
        pat = [0.0] * (2 * n)
        pat[2 * top] = 2.0 * side  # flying, in the chart of the corner `side` (kind A), its gap 0
        q, qd = np.zeros(1 + 3 * n), np.zeros(1 + 3 * n)
        q[1 + 2 * top] = rng.uniform(-0.1, 0.1) * b if n > 1 else 0.0
        q[2 + 2 * top] = psi
        if classic:  # turning about the other corner, which is at gap 2 b sin(psi)
            om = side * rng.uniform(0.5, 2.0)
            qd[2 + 2 * top] = om
            qd[1 + 2 * n + top] = -2 * b * om * side * math.cos(psi)  # the corner's gap rate
            qd[1 + 2 * top] = 0.0
        else:
            qd[1 + 2 * top] = rng.normal() * 0.5
            qd[2 + 2 * top] = rng.normal() * 2.0
            qd[1 + 2 * n + top] = -rng.uniform(0.2, 2.0)
        run.pat, run.q, run.qd = pat, q, qd
        X, V = ch.maximal(pat, q, qd)
        gx, gy = X[3 * top], X[3 * top + 1]
        vx, vy, om_cw = V[3 * top], V[3 * top + 1], V[3 * top + 2]
        c, s_ = math.cos(X[3 * top + 2]), math.sin(X[3 * top + 2])
        cx, cy = gx + side * b * c - hh * s_, gy - side * b * s_ - hh * c  # the landing corner
        rx, ry = gx - cx, gy - cy
        H = -I * om_cw + m * (rx * vy - ry * vx)  # counter-clockwise
        if classic:
            # the state is the one of turning about the other corner: the centre's velocity is om x (G - C_other)
            ox, oy = gx - side * b * c - hh * s_, gy + side * b * s_ - hh * c
            assert vx == pytest.approx(om_cw * (gy - oy), rel=1e-6)
            assert vy == pytest.approx(-om_cw * (gx - ox), rel=1e-6, abs=1e-12)
        run._landing(top, side)
        assert run.pat[2 * top] == side and run.pat[2 * top + 1] == 0.0 and run.n_landings == 1
        assert all(p == 0.0 for p in run.pat[:2 * top])
        X2, V2 = ch.maximal(run.pat, run.q, run.qd)
        w_ccw = -V2[3 * top + 2]
        assert w_ccw == pytest.approx(H / (I + m * (rx * rx + ry * ry)), rel=1e-9, abs=1e-12)
        assert I + m * (rx * rx + ry * ry) == pytest.approx(4.0 / 3.0 * m * (b * b + hh * hh), rel=1e-12)
        assert (V2[3 * top], V2[3 * top + 1]) == pytest.approx((-w_ccw * ry, w_ccw * rx), abs=1e-9)
        assert run.energy_rises[-1] <= 1e-12
        if classic:
            alpha = math.atan2(b, hh)
            assert V2[3 * top + 2] / om_cw == pytest.approx(1 - 1.5 * math.sin(alpha) ** 2, abs=1e-6)


def test_strong_shaking_leaves_no_pivot_pulling():
    """Random strong scenes of 3 and 4 drums (seeds 200-219, 3-6 times the first static threshold, at most 1.5 g;
    the first 20 phases of each, and not seed 209, whose run with flight takes 20 s: its impacts' mixed-integer
    searches reach their cap of 64 patterns; benchmarks/bench_drums_reference.py --flight runs such scenes whole): without flight pivots pull (counted as
    jumps: 14 in these scenes); with flight none does (``n_jumps == 0``: no pattern chosen with a pulling pivot, at an
    event or an impact), drums lift off and land, and energy never rises."""
    jumps, flights, landings, scenes = 0, 0, 0, 0
    lines = []
    for seed in range(200, 220):
        if seed == 209:
            continue
        n = 3 + seed % 2
        col, exc, mu, iso = _scene(seed, n)
        a = reference_drums(col, exc, mu, iso, horizon=0.0, max_phases=20)
        b = reference_drums(col, exc, mu, iso, flight=True, record_energy=True, horizon=0.0, max_phases=20)
        lines.append(f"seed {seed} n={n}: no flight {a.verdict}, {a.n_jumps} jumps; flight {b.verdict}, "
                     f"{b.n_flights} lift-offs, {b.n_landings} landings, {b.n_jumps} pulls")
        jumps += a.n_jumps
        flights += b.n_flights
        landings += b.n_landings
        scenes += 1
        assert b.n_jumps == 0, lines[-1]
        assert max(b.energy_rises, default=0.0) <= 1e-12 * G * sum(h * w for h, w in col.drums)
    print("\n".join(lines))
    print(f"{scenes} scenes: without flight {jumps} jumps; with flight {flights} lift-offs, {landings} landings, "
          "no pull")
    assert jumps >= 10 and flights >= 10 and landings >= 5 and scenes == 19
