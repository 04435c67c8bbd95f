"""The slow reference's own economies give SciPy's and NumPy's numbers bit for bit.

The reference (rockcli/reference) integrates with SciPy; three of its pieces are cheaper ways to the same
numbers: Radau's LU factorisation and solves straight from LAPACK, DOP853's dense output at one time in plain
Python floats (the event search), and the record's interpolant at one time in plain Python floats. Each is
compared here with the path it replaces, bit for bit, on random problems, and on reference runs.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from rockcli.io.units import G
from rockcli.models import Block, LinearIsolation, Rigid, SingleConcaveSliding
from rockcli.pulses import make_pulse
from rockcli.reference import ivp, reference_simulate, reference_sliding
from rockcli.reference.equations import interpolant, ground_function
from synthetic import random_record


def test_the_record_interpolant_is_numpys_bit_for_bit():
    """20,000 times in 40 random records (flat stretches, zeros, huge and tiny values, 1 to 500 samples): sample
    times themselves, the ends, and times between."""
    rng = np.random.default_rng(5)
    for k in range(40):
        n = int(rng.integers(1, 500))
        dt = float(rng.choice([0.005, 0.01, 0.02, 1.0 / 3.0]))
        y = rng.normal(size=n) * 10.0 ** rng.uniform(-6, 6)
        y[rng.random(n) < 0.2] = 0.0
        if n > 3:
            y[1:3] = y[0]  # a flat stretch
        x = dt * np.arange(n)
        interp = interpolant(x, y)
        ts = np.concatenate([x, rng.uniform(0.0, x[-1], 500), [0.0, x[-1]], np.nextafter(x[1:], 0.0)])
        got = np.array([interp(t) for t in ts])
        want = np.array([np.interp(t, x, y) for t in ts])
        assert np.array_equal(got, want), k


def test_the_reference_ground_function_is_the_record_interpolated():
    rec = random_record(np.random.default_rng(2), 300)
    ag = ground_function(rec)[0]
    x = 0.01 * np.arange(len(rec.acc))
    ts = np.random.default_rng(3).uniform(-0.5, x[-1] + 0.5, 2000)
    want = [0.0 if (t < 0 or t > x[-1]) else float(np.interp(t, x, rec.acc)) for t in ts]
    assert [ag(t) for t in ts] == want


def _rocking(t, y):
    """A stiff-ish test problem: a damped oscillator driving a pendulum-like state, a fast decaying one."""
    return [y[1], -4.0 * y[0] - 0.3 * y[1] + math.sin(3.0 * t), math.sin(y[0]) - 0.5 * y[2], -2000.0 * (y[3] - y[0])]


def test_dop853s_dense_output_at_one_time_is_scipys_bit_for_bit():
    """Every step's interpolant of three random problems (150 steps each), at 40 times of each step (ends included):
    SciPy's own."""
    from scipy.integrate._ivp.rk import Dop853DenseOutput

    fast = ivp._dop853_scalar_dense()
    rng = np.random.default_rng(7)
    for k in range(3):
        y0 = rng.normal(size=4)
        solver = fast(_rocking, 0.0, y0, 5.0, rtol=1e-10, atol=1e-12)
        steps = 0
        while solver.status == "running" and steps < 150:
            solver.step()
            steps += 1
            dense = solver.dense_output()
            ts = np.concatenate([[dense.t_old, dense.t], rng.uniform(dense.t_old, dense.t, 38)])
            for t in ts:
                got = dense(t)
                want = Dop853DenseOutput._call_impl(dense, np.asarray(t))
                assert np.array_equal(got, want), (k, steps, t)
            many = rng.uniform(dense.t_old, dense.t, 5)
            assert np.array_equal(dense(many), Dop853DenseOutput._call_impl(dense, many))
        assert steps > 20


def test_radau_with_lapack_straight_is_scipys_radau_bit_for_bit():
    """Radau on a stiff random problem, with events and dense output: every state, step, event and count equal."""
    rng = np.random.default_rng(9)
    ev = lambda t, y: y[0] - 0.1  # noqa: E731
    for k in range(3):
        y0 = rng.normal(size=4)
        runs = [solve_ivp(_rocking, (0.0, 3.0), y0, method=m, rtol=1e-9, atol=1e-12, events=ev, dense_output=True)
                for m in ("Radau", ivp._radau_direct())]
        a, b = runs
        assert np.array_equal(a.t, b.t) and np.array_equal(a.y, b.y), k
        assert (a.nfev, a.njev, a.nlu) == (b.nfev, b.njev, b.nlu)
        assert all(np.array_equal(x, y) for x, y in zip(a.t_events, b.t_events))
        ts = np.linspace(0.0, 3.0, 301)
        assert np.array_equal(a.sol(ts), b.sol(ts))


def test_radau_with_lapack_straight_refuses_non_finite_values_as_scipy_does():
    lu_solver = ivp._radau_direct()(lambda t, y: [math.nan * y[0]], 0.0, [1.0], 1.0)
    with pytest.raises(ValueError):
        lu_solver.lu(np.array([[math.nan]]))


def _fields(r):
    return {k: v for k, v in dataclasses.asdict(r).items() if k != "wall_s"}


@pytest.mark.parametrize("scene", ["rigid-pulse", "linear-record", "sliding"])
def test_reference_runs_are_the_same_with_scipys_own_solvers(monkeypatch, scene):
    """Whole reference runs (impacts, rests, events), with the economies and with SciPy's plain methods: every
    field of the result the same, the counts of work included."""
    block = Block(1.2, 0.18)
    if scene == "rigid-pulse":
        args = (block, Rigid(), make_pulse("ricker-anti", 1.6 * G * math.tan(0.18), 0.8))
        run = lambda: reference_simulate(*args, horizon=20.0)  # noqa: E731
    elif scene == "linear-record":
        rec = random_record(np.random.default_rng(4), 250, pga_g=1.8 * math.tan(0.18))
        args = (block, LinearIsolation(1.5, 0.1, 0.3), rec)
        run = lambda: reference_simulate(*args, horizon=2.0)  # noqa: E731
    else:
        args = (block, SingleConcaveSliding(2.0, 0.04), make_pulse("sine", 2.0 * G * math.tan(0.18), 0.7))
        run = lambda: reference_sliding(*args, horizon=0.5, rtol=1e-7)  # noqa: E731
    ours = run()
    monkeypatch.setattr(ivp, "_radau_direct", lambda: "Radau")
    monkeypatch.setattr(ivp, "_dop853_scalar_dense", lambda: "DOP853")
    plain = run()
    assert ours.verdict == "rocked" and ours.n_impacts >= 1 and ours.steps > 500
    same = [(x == y) or (isinstance(x, float) and math.isnan(x) and math.isnan(y))
            for x, y in zip(_fields(ours).values(), _fields(plain).values())]
    assert all(same), (_fields(ours), _fields(plain))
