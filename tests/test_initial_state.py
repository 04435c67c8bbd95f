"""``theta0`` / ``theta_dot0`` (``simulate --theta0 RAD [--theta-dot0 RAD/S]``): a start away from rest,
with or without ground motion. Free rocking against its closed forms (the quarter period by
quadrature of the energy integral, the decay of the peaks), the peaks the kernel records, and the
verdict-only shortcuts against full-history runs from random initial states."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner
from scipy.integrate import quad

from rockcli.errors import RockcliInputError
from rockcli.models.impact import housner_restitution
from rockcli.models import Block, LinearIsolation, Rigid
from rockcli.pulses import make_pulse
from rockcli.solve import simulate
from rockcli.io.units import G

ALPHA = 0.2
BLOCK = Block(0.5 / math.sin(ALPHA), ALPHA)  # full width B = 1 m


def quarter_period(block: Block, theta0: float) -> float:
    """Time from a release at rest at theta0 to theta = 0: the energy integral
    ``int_0^theta0 dtheta / sqrt(2 p^2 (cos(alpha - theta0) - cos(alpha - theta)))``, with
    ``theta = theta0 (1 - u^2)`` to remove the end singularity."""
    a, p2 = block.alpha, block.p ** 2

    def f(u):
        if u == 0.0:
            return 2.0 * theta0 / math.sqrt(2.0 * p2 * math.sin(a - theta0) * theta0)
        d = 2.0 * math.sin(a - theta0 + 0.5 * theta0 * u * u) * math.sin(0.5 * theta0 * u * u)
        return 2.0 * theta0 * u / math.sqrt(2.0 * p2 * d)

    return quad(f, 0.0, 1.0, epsabs=1e-14, epsrel=1e-13, limit=200)[0]


def _impact_times(h):
    i = np.flatnonzero((h.t[1:] == h.t[:-1]) & (h.theta[1:] == 0.0) & (h.theta[:-1] == 0.0))
    return h.t[i]


def test_the_first_impact_of_a_released_block_is_the_quarter_period():
    assert G == 9.80665
    T = quarter_period(BLOCK, 0.5 * ALPHA)
    assert T == pytest.approx(0.771277, abs=5e-7)  # the value (the linearised one is 0.7704 s)
    for E in (None, 0.8):
        res = simulate(BLOCK, Rigid(), None, theta0=0.5 * ALPHA, history=True, tail=3.0, restitution=E)
        t_imp = _impact_times(res.history)
        assert t_imp[0] == pytest.approx(T, abs=1e-8)  # measured 1.6e-9 s at the default rtol
        tight = simulate(BLOCK, Rigid(), None, theta0=0.5 * ALPHA, history=True, tail=1.0, restitution=E, rtol=1e-12)
        assert _impact_times(tight.history)[0] == pytest.approx(T, abs=1e-11)
    # mirror image: released on the other corner
    left = simulate(BLOCK, Rigid(), None, theta0=-0.5 * ALPHA, history=True, tail=3.0)
    right = simulate(BLOCK, Rigid(), None, theta0=0.5 * ALPHA, history=True, tail=3.0)
    assert np.array_equal(left.history.t, right.history.t)
    assert np.array_equal(left.history.theta, -right.history.theta)


@pytest.mark.parametrize("E", [None, 0.8])
def test_successive_peaks_follow_the_energy_recurrence(E):
    """cos(alpha - theta_{k+1}) = cos alpha + E^2 [cos(alpha - theta_k) - cos alpha] on the exact peaks the
    kernel records (turning points located on the dense output), for Housner's E and for 0.8."""
    Ev = housner_restitution(ALPHA) if E is None else E
    res = simulate(BLOCK, Rigid(), None, theta0=0.5 * ALPHA, history=True, tail=6.0, restitution=E)
    h = res.history
    pk_t, pk = h.peak_t, np.abs(h.peak_theta)
    assert pk_t[0] == 0.0 and pk[0] == 0.5 * ALPHA  # the release
    assert pk.size >= 5
    assert np.all(np.sign(h.peak_theta[1:]) == -np.sign(h.peak_theta[:-1]))  # one peak per side, alternating
    t_imp = _impact_times(h)
    assert np.all(t_imp[: pk.size - 1] > pk_t[:-1]) and np.all(t_imp[: pk.size - 1] < pk_t[1:])  # impact between
    ca = math.cos(ALPHA)
    predicted = ALPHA - np.arccos(ca + Ev ** 2 * (np.cos(ALPHA - pk[:-1]) - ca))
    assert np.max(np.abs(predicted - pk[1:])) < 1e-8 * ALPHA
    # the peaks are where theta turns: every history row lies inside the envelope of its half-cycle
    for k in range(pk.size - 1):
        inside = (h.t > pk_t[k]) & (h.t < pk_t[k + 1])
        assert np.all(np.abs(h.theta[inside]) <= np.maximum(pk[k], pk[k + 1]) * (1 + 1e-12))


def test_peak_rows_during_ground_motion_and_on_an_isolated_base():
    block = Block.from_degrees(2.0, 14.0)
    pulse = make_pulse("ricker-sym", 1.8 * G * math.tan(block.alpha), 1.0)
    for f in (Rigid(), LinearIsolation(2.0, 0.1, 0.3)):
        res = simulate(block, f, pulse, history=True)
        h = res.history
        assert h.peak_t.size >= 3
        # each recorded peak is a local maximum of |theta| of the rows around it, and the largest is theta_max
        assert np.max(np.abs(h.peak_theta)) == pytest.approx(res.theta_max, rel=1e-12)
        j = np.searchsorted(h.t, h.peak_t)
        assert np.all(np.abs(h.peak_theta) >= np.abs(h.theta[j]) - 1e-12)
        assert np.all(np.abs(h.peak_theta) >= np.abs(h.theta[j - 1]) - 1e-12)


def test_a_start_at_rest_is_the_default_bit_for_bit():
    pulse = make_pulse("sine", 1.4 * G * math.tan(BLOCK.alpha), 1.0)
    a = simulate(BLOCK, Rigid(), pulse, history=True)
    b = simulate(BLOCK, Rigid(), pulse, history=True, theta0=0.0, theta_dot0=0.0)
    assert a.summary() == b.summary() and np.array_equal(a.history.theta, b.history.theta)


def test_initial_state_is_checked():
    for kw in ({"theta0": math.pi / 2}, {"theta0": -2.0}, {"theta0": math.nan}, {"theta_dot0": math.inf}):
        with pytest.raises(RockcliInputError, match="theta"):
            simulate(BLOCK, Rigid(), None, **kw)
    with pytest.raises(RockcliInputError, match="excitation"):
        simulate(BLOCK, Rigid(), None)


def _random_starts(n, seed):
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        alpha = math.radians(rng.uniform(3.0, 30.0))
        block = Block(math.exp(rng.uniform(math.log(0.2), math.log(30.0))), alpha)
        th0 = rng.uniform(-1.3, 1.3) * alpha if rng.random() < 0.8 else 0.0
        thd0 = rng.normal() * 0.6 * block.p * alpha if rng.random() < 0.5 else 0.0
        if th0 == 0.0 and thd0 == 0.0:
            th0 = 0.3 * alpha
        if rng.random() < 0.4:
            pulse = None
        else:
            Tp = 2.0 * math.pi / (rng.uniform(0.5, 15.0) * block.p)
            pulse = make_pulse(("ricker-sym", "sine")[i % 2], rng.uniform(0.3, 5.0) * G * math.tan(alpha)
                               * rng.choice([-1.0, 1.0]), Tp)
        f = Rigid() if rng.random() < 0.5 else LinearIsolation(rng.uniform(1.0, 4.0) * 2 * math.pi / block.p,
                                                               rng.uniform(0.02, 0.5), rng.uniform(0.0, 0.5))
        E = None if rng.random() < 0.5 else float(rng.uniform(0.5, 1.0))
        out.append((block, f, pulse, dict(theta0=th0, theta_dot0=thd0, restitution=E)))
    return out


def test_verdict_only_equals_full_history_from_random_initial_states():
    """Every shortcut re-checked for a start away from rest (P1-P8 argue from the current state):
    600 random starts (tilts up to 1.3 alpha either way, velocities), with and without a pulse, rigid and
    linear bases, Housner's or a random restitution: early, verdict-only and full-history runs agree."""
    bad, verdicts = [], []
    for i, (block, f, pulse, kw) in enumerate(_random_starts(600, 2027)):
        full = simulate(block, f, pulse, history=True, **kw)
        b = simulate(block, f, pulse, **kw)
        a = simulate(block, f, pulse, early=True, **kw)
        same = a.verdict == b.verdict == full.verdict and b.settled == full.settled
        same = same and b.n_impacts_total <= full.n_impacts_total
        same = same and b.theta_max == pytest.approx(full.theta_max, rel=1e-6, abs=1e-15)
        same = same and a.theta_max <= full.theta_max * (1 + 1e-7) + 1e-15
        if not same:
            bad.append((i, kw, a.verdict, b.verdict, full.verdict, b.theta_max, full.theta_max))
        verdicts.append(full.verdict)
    assert bad == []
    assert min(verdicts.count(v) for v in ("rocked", "overturned")) > 100


def test_cli_free_rocking():
    from rockcli.cli import main

    runner = CliRunner()
    args = ["simulate", "--width", "1", "--height", str(1 / math.tan(ALPHA)), "--theta0", str(0.5 * ALPHA), "--json"]
    out = runner.invoke(main, args)
    assert out.exit_code == 0, out.output
    got = json.loads(out.output)
    assert got["verdict"] == "rocked" and got["excitation"].startswith("free rocking")
    assert got["theta0"] == 0.5 * ALPHA and got["theta_max_over_alpha"] == pytest.approx(0.5, rel=1e-12)
    none = runner.invoke(main, ["simulate", "--R", "1", "--alpha", "10"])
    assert none.exit_code == 2 and "--theta0" in none.output
    bad = runner.invoke(main, ["simulate", "--R", "1", "--alpha", "10", "--theta0", "1.6"])
    assert bad.exit_code == 2 and "--theta0 must be an angle" in bad.output
    chk = runner.invoke(main, ["simulate", "--R", "1", "--alpha", "10", "--theta0", "0.1", "--check-tolerance"])
    assert chk.exit_code == 2 and "--check-tolerance" in chk.output
