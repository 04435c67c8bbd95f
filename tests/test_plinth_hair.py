"""A body that lifts off its plinth by a hair on linear bearings (docs/physics-plinth.md, "A lift below the
tolerance"): the compiled driver once chattered there to its 5-million-step cap. At rest on linear bearings the stack
rides the base as one rigid mass, linear in ``a_p``: its uplift threshold is closed-form up to one SDOF integration,
``a_p* = g tan(alpha) / max|F per unit a_p|`` (the lower of the body's and the assembly's thresholds), and every scene
just above it must lift, every scene below it must not, with no run near the step cap."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import minimize_scalar

from rockcli.io.units import G
from rockcli.reference.equations import ground_function
from rockcli.solve import simulate_stack
from rockcli.spectra.plinth import PlinthRatio
from rockcli.spectra.scenes import Family, parse_isolation

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benchmarks"))
from bench_plinth import random_linear_scene  # noqa: E402

SCENE_36 = Family(math.radians(10), "ricker-sym", parse_isolation("linear:TbTp=4"), plinth=PlinthRatio(0.5, 1.5))


def peak_bearing_force(iso, pulse, horizon) -> float:
    """``max |F|`` of a stack at rest on linear bearings under ``pulse`` until ``horizon`` after it (``u'' = F - ag``;
    F per unit moving mass), integrated tightly and refined at the largest sampled maximum."""
    ag, t_end, _, _ = ground_function(pulse)
    w, xi = iso.omega_b, iso.xi
    sol = solve_ivp(lambda t, y: [y[1], -w * w * y[0] - 2 * xi * w * y[1] - ag(t)], (0.0, t_end + horizon),
                    [0.0, 0.0], method="DOP853", rtol=1e-12, atol=1e-14 * abs(pulse.a_p), dense_output=True)

    def F(t):
        u, ud = sol.sol(t)
        return abs(-w * w * u - 2 * xi * w * ud)

    ts = np.linspace(0.0, sol.t[-1], 4001)
    u, ud = sol.sol(ts)
    vals = np.abs(-w * w * u - 2 * xi * w * ud)
    i = int(np.argmax(vals))
    lo, hi = ts[max(i - 1, 0)], ts[min(i + 1, ts.size - 1)]
    return max(vals[i], -minimize_scalar(lambda t: -F(t), bounds=(lo, hi), method="bounded",
                                         options={"xatol": 1e-12}).fun)


def test_the_issue_36_scene_lifts_by_a_hair_and_ends_in_a_normal_number_of_steps():
    """The spectra's scene (alpha 10 deg, plinth 0.5 x 1.5, T_b/T_p = 4, omega_p/p = 3.5, a_p/(g tan alpha) =
    8.421630859375): the bearings' force passes the body's threshold by 1.7e-6 of it for about 0.5 ms, the body lifts
    by about 2.6e-13 rad (the reference with steps below 1e-4 s: rocked, that peak, one impact of the body; with its
    default steps it steps over the 0.5 ms and reports no uplift). The driver: rocked, its peak below the error floor
    ``rtol alpha`` (so within it of the reference's), one landing of the body, and ~256 steps, not the cap."""
    stack, iso, pulse = SCENE_36.scene(3.5, 8.421630859375)
    excess = peak_bearing_force(iso, pulse, 4.0) / stack.body_uplift_acceleration - 1.0
    assert 1e-6 < excess < 3e-6  # a true lift, by a hair
    for history in (False, True):
        r = simulate_stack(stack, pulse, isolation=iso, history=history, max_steps=5000)
        assert r.status == 0 and r.verdict == "rocked" and r.settled
        assert r.steps < 400
        assert r.body.theta_max < 1e-10 * stack.body.alpha and r.plinth.theta_max == 0.0
        assert (r.body.n_impacts, r.plinth.n_impacts) == (1, 0)
        assert r.body.t_uplift_s == r.body.t_uplift_s  # recorded
    below = SCENE_36.scene(3.5, 8.421630859375 / (1 + 2 * excess))  # a_p below the threshold by as much
    r = simulate_stack(below[0], below[2], isolation=below[1], max_steps=5000)
    assert r.status == 0 and r.verdict == "no_uplift"


def test_random_scenes_just_above_and_below_the_uplift_threshold_never_chatter():
    """120 random scenes on linear bearings (bench_plinth's, short pulses, verdict-only, horizon 1 s): a_p = a_p*
    (1 +- e), e log-uniform in [1e-7, 1e-3] (the band where the driver chattered: 6 of 200 such scenes reached a
    20,000-step cap before the fix, measured). Every run ends in under 1,000 steps; below the threshold no run lifts;
    above it every run with e >= 1e-5 lifts (thinner windows, under ~1e-4 s, may be stepped over between the face's
    samples, as by the reference)."""
    rng = np.random.default_rng(36)
    lifted_thin = 0
    for i in range(120):
        stack, iso, pulse = random_linear_scene(rng)
        thr = min(stack.body_uplift_acceleration, stack.assembly_uplift_acceleration)
        a_star = thr * abs(pulse.a_p) / peak_bearing_force(iso, pulse, 1.0)
        e = 10 ** rng.uniform(-7, -3)
        below = i % 4 == 3
        p = type(pulse)(math.copysign(a_star * (1 - e if below else 1 + e), pulse.a_p), pulse.T_p)
        r = simulate_stack(stack, p, isolation=iso, horizon=1.0, tail=0.0, max_steps=20000)
        assert r.status == 0 and r.steps < 1000, (i, r.steps)
        if below:
            assert r.verdict == "no_uplift", i
        elif e >= 1e-5:
            assert r.verdict != "no_uplift", i
        else:
            lifted_thin += r.verdict != "no_uplift"
    assert lifted_thin > 0
