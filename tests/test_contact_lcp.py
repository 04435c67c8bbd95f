"""The contact law's pattern choice by a complementarity solve (rockcli.kernels.contact_lcp) against the enumeration of
every pattern the event allows (rockcli.kernels.contact.choose_pattern, impact), on thousands of random states of
chains of 2-4 blocks: the same pattern wherever the enumeration finds one that meets every condition, and at impacts
the same rates after. A shortcut of the pattern choice (Lemke instead of 9^n solves), checked against the path it
replaces."""

from __future__ import annotations

import numpy as np
import pytest

from rockcli.io.units import G
from rockcli.models.drums import DrumColumn


def _scene(rng, n):
    """A random column of drums (their slips too: some past the edge of the drum below) in a random mix of closed
    faces, faces sliding, pivots stuck and pivots sliding, under a random ground acceleration."""
    from rockcli.kernels import chain as ch
    from rockcli.solve.slide import chain_parameters

    w = rng.uniform(0.6, 1.6)
    col = DrumColumn(tuple((rng.uniform(0.3, 1.2), w * rng.uniform(0.85, 1.15)) for _ in range(n)))
    cp = chain_parameters(col, [float(rng.uniform(0.2, 1.0)) for _ in range(n)])
    y = np.zeros(ch.n_states(n))
    pat = np.zeros(2 * n)
    zp = np.zeros(n, dtype=np.bool_)
    zs = np.zeros(n, dtype=np.bool_)
    for j in range(n):
        b = cp[ch.CP_BLK + ch.NF_BLK * j + ch.F_B]
        y[ch.col_s(j)] = 0.0 if j == 0 or rng.random() < 0.5 else rng.uniform(-0.3, 0.3) * b
        kind = rng.choice(4, p=[0.55, 0.15, 0.15, 0.15])
        if kind in (0, 1):
            zp[j] = True
            if kind == 0:
                zs[j] = True
            else:
                y[ch.col_s(j) + 1] = rng.normal() * 0.2
                pat[2 * j + 1] = np.sign(y[ch.col_s(j) + 1])
        else:
            c = float(rng.choice([-1.0, 1.0]))
            pat[2 * j] = c
            y[ch.col_psi(j)] = c * rng.uniform(0.001, 0.2)
            y[ch.col_psi(j) + 1] = rng.normal() * 0.3
            if kind == 2:
                zs[j] = True
            else:
                y[ch.col_s(j) + 1] = rng.normal() * 0.2
                pat[2 * j + 1] = np.sign(y[ch.col_s(j) + 1])
    return ch, cp, pat, y, zp, zs, rng.uniform(-1.2, 1.2) * G


@pytest.mark.parametrize("n, trials", [(2, 800), (3, 800), (4, 300)])
def test_the_complementarity_solve_chooses_the_enumerations_pattern(n, trials):
    from rockcli.kernels.contact import choose_pattern
    from rockcli.kernels.contact_lcp import lcp_choose, lcp_space

    rng = np.random.default_rng(460 + n)
    clear = agree = 0
    for _ in range(trials):
        ch, cp, pat, y, zp, zs, ag = _scene(rng, n)
        ws = ch.workspace(n)
        frc = np.zeros((n, 3))
        b1 = np.zeros(2 * n)
        b2 = np.zeros(2 * n)
        m1, _ = choose_pattern(cp, pat, y, ag, ws, frc, zp.copy(), zs.copy(), b1)
        m2, _ = lcp_choose(cp, pat, y, ag, ws, frc, zp.copy(), zs.copy(), b2, lcp_space(n))
        if m1 < 1e-9:  # no pattern meets every condition (or only at rounding level): nothing to compare
            continue
        clear += 1
        if np.array_equal(b1, b2):
            agree += 1
            assert m2 == pytest.approx(m1, rel=1e-9, abs=1e-12)
    assert clear > 0.9 * trials
    assert agree == clear, f"{clear - agree} of {clear} differ"


@pytest.mark.parametrize("n, trials", [(2, 600), (3, 600), (4, 200)])
def test_the_complementarity_solve_gives_the_enumerations_impact(n, trials):
    """Moreau's impact with Coulomb's law: one interface's pivot back at angle 0 while closing, the others in any
    state; the pattern after and the rates after, against the enumeration's."""
    from rockcli.kernels.contact import impact
    from rockcli.kernels.contact_lcp import lcp_impact, lcp_space

    rng = np.random.default_rng(4600 + n)
    clear = agree = 0
    for _ in range(trials):
        ch, cp, pat, y, zp, zs, ag = _scene(rng, n)
        j = int(rng.integers(0, n))
        c = float(rng.choice([-1.0, 1.0]))
        pat[2 * j] = c
        y[ch.col_psi(j)] = 0.0
        y[ch.col_psi(j) + 1] = -c * rng.uniform(0.05, 1.0)
        if rng.random() < 0.5:
            y[ch.col_s(j) + 1] = rng.normal() * 0.2
            pat[2 * j + 1] = np.sign(y[ch.col_s(j) + 1])
        else:
            y[ch.col_s(j) + 1] = 0.0
            pat[2 * j + 1] = 0.0
        fc = np.array([i == j or pat[2 * i] == 0.0 for i in range(n)])
        ws = ch.workspace(n)
        frc = np.zeros((n, 3))
        b1, b2 = np.zeros(2 * n), np.zeros(2 * n)
        y1, y2 = np.zeros_like(y), np.zeros_like(y)
        v0, w0 = np.zeros((n, 2)), np.zeros(n)
        r1 = impact(cp, pat, pat.copy(), y, ws, frc, fc.copy(), fc.copy(), b1, v0, w0, y1)
        r2 = lcp_impact(cp, pat, pat.copy(), y, ws, frc, fc.copy(), fc.copy(), b2, v0, w0, y2, lcp_space(n))
        if r1[0] < 1e-9:
            continue
        clear += 1
        if np.array_equal(b1, b2):
            agree += 1
            assert r2[2] == r1[2]  # the rocking law's impulses fitted the cone in both, or in neither
            np.testing.assert_allclose(y2, y1, rtol=1e-12, atol=1e-14)
    assert clear > 0.9 * trials
    assert agree == clear, f"{clear - agree} of {clear} differ"
