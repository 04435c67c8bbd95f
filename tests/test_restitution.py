"""``restitution`` / ``--restitution E``: the impact map with a given coefficient of restitution
(rockcli.models.impact), its limits and invariants, the unchanged default, the options. The verdict-only
shortcuts re-proved for every E: tests/test_verdict_paths.py (random restitutions)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.errors import RockcliInputError
from rockcli.models.impact import housner_restitution, impact_ratio
from rockcli.models import Block, LinearIsolation, Rigid, SingleConcaveSliding, impact_coefficient
from rockcli.pulses import make_pulse
from rockcli.solve import simulate, simulate_many, simulate_verdicts
from rockcli.io.units import G
from test_solver import angular_momentum_about


def _impacts(hist):
    """(before, after) row indices of the impacts of a history: consecutive rows at the same time with theta = 0."""
    t, th = hist.t, hist.theta
    i = np.flatnonzero((t[1:] == t[:-1]) & (th[1:] == 0.0) & (th[:-1] == 0.0))
    return i, i + 1


@pytest.mark.parametrize("alpha", [0.05, 0.2, 0.35, 1.0])
def test_the_map_limits(alpha):
    for E in (0.3, 0.8, 0.95, 1.0):
        assert impact_ratio(alpha, 0.0, E) == pytest.approx(E, rel=1e-15)  # a rigid foundation: theta_dot+ = E theta_dot-
        for gamma in (0.01, 0.3, 0.9):
            eta = impact_ratio(alpha, gamma, E)
            assert 0.0 <= eta <= E  # a moving base takes a share of the rebound, never adds to it
            # gamma -> 0 tends to the rigid foundation
            assert impact_ratio(alpha, gamma * 1e-9, E) == pytest.approx(E, rel=1e-8)
    assert impact_ratio(alpha, 0.4, 1.0) == 1.0  # elastic on every base
    # Housner's value (exactly, or not given) is the momentum map, bit for bit
    for gamma in (0.0, 0.01, 0.5):
        assert impact_ratio(alpha, gamma, housner_restitution(alpha)) == impact_coefficient(alpha, gamma)
        assert impact_ratio(alpha, gamma, None) == impact_coefficient(alpha, gamma)
        if housner_restitution(alpha) > 0:  # the formula itself tends to it as E -> Housner's value
            E = housner_restitution(alpha) * (1 + 1e-13)
            assert impact_ratio(alpha, gamma, E) == pytest.approx(impact_coefficient(alpha, gamma), abs=1e-12)


@pytest.mark.parametrize("alpha", [0.1, 0.2, 0.35])
@pytest.mark.parametrize("gamma", [0.0, 0.01, 0.3, 0.8])
@pytest.mark.parametrize("E", [0.5, 0.85, 0.99, 1.0])
def test_the_map_keeps_momentum_and_adds_the_contact_couple(alpha, gamma, E):
    """Horizontal momentum kept; the angular impulse about the new pivot is the couple
    (4/3) R^2 (E - eta_H) theta_dot- of the rigid foundation, whatever the base; no energy gained."""
    block = Block(2.0, alpha)
    b = block.b
    thd1, ud1 = -0.7, 0.13  # on the right corner (theta > 0) coming back to theta = 0
    eta = impact_ratio(alpha, gamma, E)
    thd2 = eta * thd1
    ud2 = ud1 + gamma * block.h * (1 - eta) * thd1  # the kernel's P_DU
    assert ud1 + gamma * block.h * thd1 == pytest.approx(ud2 + gamma * block.h * thd2, abs=1e-14)
    L1 = angular_momentum_about(block, -b, thd1, +b, ud1)
    L2 = angular_momentum_about(block, -b, thd2, -b, ud2)
    couple = -(4.0 / 3.0) * block.R ** 2 * (E - housner_restitution(alpha)) * thd1  # z component (omega_z = -thd)
    if eta > 0:  # (clamped at 0 the block stops: a smaller couple than E asks)
        assert L2 - L1 == pytest.approx(couple, rel=2e-3, abs=2e-3 * abs(L1))
    else:
        assert 4 * E < 3 * gamma * math.cos(alpha) ** 2
    Io = 4 / 3 * block.R ** 2
    if gamma:
        mb = (1 - gamma) / gamma
        T1 = 0.5 * (1 + mb) * ud1 ** 2 + block.h * ud1 * thd1 + 0.5 * Io * thd1 ** 2
        T2 = 0.5 * (1 + mb) * ud2 ** 2 + block.h * ud2 * thd2 + 0.5 * Io * thd2 ** 2
        assert T2 <= T1 * (1 + 1e-14)
        if E < 1:
            assert T2 < T1


@pytest.mark.parametrize("foundation", [Rigid(), LinearIsolation(2.0, 0.1, 0.3), SingleConcaveSliding(2.0, 0.05, gamma=0.3)])
def test_runs_apply_the_map_at_every_impact(foundation):
    block = Block.from_degrees(2.0, 14.0)
    a_p = (1.6 if isinstance(foundation, Rigid) else 1.8) * G * math.tan(block.alpha)
    pulse = make_pulse("ricker-sym", a_p, 1.0)
    E = 0.83
    res = simulate(block, foundation, pulse, restitution=E, history=True, tail=3.0)
    h = res.history
    i, j = _impacts(h)
    assert i.size >= 3
    eta = impact_ratio(block.alpha, foundation.gamma, E)
    rested = h.theta_dot[j] == 0.0  # the rest rule ends the train (a plastic last impact)
    assert np.allclose(h.theta_dot[j][~rested], eta * h.theta_dot[i][~rested], rtol=1e-14, atol=0)
    gh = foundation.gamma * block.h
    assert np.allclose(h.u_dot[j] + gh * h.theta_dot[j], h.u_dot[i] + gh * h.theta_dot[i], rtol=0, atol=1e-14)


@pytest.mark.parametrize("foundation", [Rigid(), LinearIsolation(2.5, 0.1, 0.05), SingleConcaveSliding(2.0, 0.05)])
def test_housners_value_given_is_the_default_bit_for_bit(foundation):
    block = Block.from_degrees(1.5, 12.0)
    pulse = make_pulse("sine", 1.3 * G * math.tan(block.alpha), 1.1)
    a = simulate(block, foundation, pulse, history=True)
    b = simulate(block, foundation, pulse, history=True, restitution=housner_restitution(block.alpha))
    assert a.summary() == b.summary()
    assert np.array_equal(a.history.theta, b.history.theta) and np.array_equal(a.history.u, b.history.u)
    c = simulate(block, foundation, pulse, history=True, restitution=0.7)
    assert c.summary() != a.summary()


def test_restitution_is_checked():
    block, pulse = Block(1.0, 0.2), make_pulse("sine", 3.0, 1.0)
    for bad in (0.0, -0.5, 1.0000001, math.nan, math.inf, "x"):
        with pytest.raises(RockcliInputError, match="restitution"):
            simulate(block, Rigid(), pulse, restitution=bad)
    with pytest.raises(RockcliInputError, match="one per job"):
        simulate_many([(block, Rigid(), pulse)] * 3, restitution=[0.5, 0.6])


def test_per_job_restitution_equals_single_runs():
    block = Block.from_degrees(1.0, 12.0)
    pulse = make_pulse("ricker-sym", 2.0 * G * math.tan(block.alpha), 0.9)
    Es = [None, 0.6, 0.9, 1.0]
    many = simulate_many([(block, Rigid(), pulse)] * 4, restitution=Es)
    arr = simulate_verdicts([(block, Rigid(), pulse)] * 4, restitution=Es)
    for E, r, th in zip(Es, many, arr.theta_max_over_alpha):
        one = simulate(block, Rigid(), pulse, restitution=E)
        assert r.summary() == one.summary()
        assert th == one.theta_max_over_alpha
    assert len({r.theta_max for r in many}) == 4


def test_cli_restitution(tmp_path):
    from rockcli.cli import main

    args = ["simulate", "--R", "1", "--alpha", "14", "--pulse", "ricker-sym:ap=0.5,Tp=1", "--json"]
    runner = CliRunner()
    base = json.loads(runner.invoke(main, args).output)
    assert "restitution" not in base  # the default reports nothing new
    out = runner.invoke(main, args + ["--restitution", "0.7", "--isolation", "linear:Tb=2,gamma=0.2"])
    assert out.exit_code == 0, out.output
    got = json.loads(out.output)
    assert got["restitution"] == 0.7
    assert got["impact_ratio"] == impact_ratio(math.radians(14), 0.2, 0.7)
    block = Block.from_degrees(1.0, 14.0)
    ref = simulate(block, LinearIsolation(2.0, 0.1, 0.2), make_pulse("ricker-sym", 0.5 * G, 1.0), restitution=0.7)
    assert got["theta_max"] == ref.theta_max
    bad = runner.invoke(main, args + ["--restitution", "0"])
    assert bad.exit_code == 2 and "--restitution must satisfy 0 < E <= 1" in bad.output


def test_cli_spectrum_and_assess_pass_restitution(tmp_path):
    from rockcli.cli import main

    runner = CliRunner()
    csvs = []
    for extra in ([], ["--restitution", "0.6"]):
        path = tmp_path / f"map{len(extra)}.csv"
        out = runner.invoke(main, ["spectrum", "overturning", "--alpha", "10", "--wp-over-p", "2:6:3", "--ap", "2:6:3",
                                   "--csv", str(path), "--full-peaks", *extra])
        assert out.exit_code == 0, out.output
        import csv

        csvs.append(list(csv.DictReader(path.open())))
    # every cell is the simulate run of its scene with that restitution
    from rockcli.spectra import Family, parse_isolation

    fam = Family(math.radians(10.0), "ricker-sym", parse_isolation("none"))
    for row in csvs[1]:
        scene = fam.scene(float(row["wp_over_p"]), float(row["ap_over_g_tan_alpha"]))
        r = simulate(*scene, restitution=0.6)
        assert float(row["theta_max_over_alpha"]) == pytest.approx(r.theta_max_over_alpha, rel=1e-5)
        assert (row["overturned"] in ("True", "1", "true")) == r.overturned
    assert [r["theta_max_over_alpha"] for r in csvs[0]] != [r["theta_max_over_alpha"] for r in csvs[1]]
    assert "restitution" not in csvs[0][0] and all(float(r["restitution"]) == 0.6 for r in csvs[1])
    assert "coefficient of restitution E = 0.6" in out.output
    path = tmp_path / "a.csv"
    out = runner.invoke(main, ["assess", "column", "statue:R=1.2,alpha=14", "--records", "kobe-1995-takarazuka-000",
                               "--excitation", "pulse", "--isolation", "none", "--no-margin", "--csv", str(path),
                               "--restitution", "0.9"])
    assert out.exit_code == 0, out.output
    assert "restitution" in path.read_text().splitlines()[0]
    assert "coefficient of restitution E = 0.9" in out.output


def test_out_of_range_values_are_quoted_unrounded():
    """Issue 23's class: a limit error names the value as given, never rounded (1.0000001 printed as '1')."""
    from rockcli.models.colonnade import check_cap_ratio
    from rockcli.errors import RockcliInputError
    from rockcli.models.impact import check_restitution
    from rockcli.models.initial import check_initial_state

    for call, text in ((lambda: check_restitution(1.0000001), "got 1.0000001"),
                       (lambda: check_initial_state(1.5707964, 0.0), "got 1.5707964")):
        with pytest.raises(RockcliInputError, match=text.replace(".", r"\.")):
            call()
    with pytest.raises(RockcliInputError) as exc:
        check_cap_ratio(-1e-7)
    assert "-1e-07" in str(exc.value)
