"""The equations every reference run shares, typed again from the paper (never from the kernels).

The ground motion as a function of time, the impact map as the 2x2 momentum system of Eqs 14 and 16,
the rocking accelerations on a moving base (Eqs 10-11), and the state scales of the mixed error test.

A capped colonnade (``cap_ratio`` gamma_c > 0: N columns carrying a beam of gamma_c times their mass,
docs/physics-colonnade.md) is written from its bodies' mass properties (:func:`colonnade_masses`): the
rocking accelerations as the 2x2 system of Lagrange's equations in u and theta, the impact map as the
2x2 momentum system with the beam's terms; never through the kernel's effective block. A given
coefficient of restitution ``E`` replaces the momentum before the impact by ``E`` times the one after it
on the ground (the impulsive couple of rockcli.models.impact).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from rockcli.models import Block
from rockcli.io.units import G


def ground_function(excitation):
    """``(ag(t) [m/s^2], end of the excitation [s], scan grid step [s], max_step for solve_ivp [s])``.

    Records: solve_ivp steps at most one sample interval (piecewise-linear input); pulses are smooth
    and leave the step size to the error control.
    """
    if hasattr(excitation, "acc"):
        acc = np.asarray(excitation.acc, float)
        tt = excitation.dt * np.arange(acc.size)
        interp = interpolant(tt, acc)

        def ag(t):
            if t > tt[-1] or t < 0:
                return 0.0
            return interp(t)

        return ag, float(tt[-1]), float(excitation.dt), float(excitation.dt)

    def ag(t):
        return float(excitation.acceleration(t))

    ts, te = excitation.support()
    return ag, float(te), excitation.T_p / 200.0, np.inf


def interpolant(x, y):
    """``numpy.interp(t, x, y)`` at one time ``t`` inside ``[x[0], x[-1]]``, as NumPy computes it (the interval by
    bisection, a sample's own value where ``t`` is one, else ``slope * (t - x[j]) + y[j]``), in plain Python
    floats: some 5 times cheaper than ``numpy.interp`` on a scalar, which the right-hand side calls at every
    stage. tests/test_reference.py checks it against ``numpy.interp`` bit for bit."""
    from bisect import bisect_right

    xs, ys = np.asarray(x, float).tolist(), np.asarray(y, float).tolist()
    last = len(xs) - 1

    def interp(t):
        t = float(t)
        j = bisect_right(xs, t) - 1
        if j >= last or xs[j] == t:
            return ys[min(j, last)]
        slope = (ys[j + 1] - ys[j]) / (xs[j + 1] - xs[j])
        value = slope * (t - xs[j]) + ys[j]
        if math.isnan(value):  # as NumPy: from the interval's other end, or the common value of a flat one
            value = slope * (t - xs[j + 1]) + ys[j + 1]
            if math.isnan(value) and ys[j] == ys[j + 1]:
                value = ys[j]
        return value

    return interp


class ColonnadeMasses(NamedTuple):
    """Mass properties per unit mass of one column (N columns rocking together, the beam on their top
    corners opposite the pivots, so at twice the distance of their centres of mass; the base below)."""

    total: float  # the moving mass M (columns, beam and base; inf on a rigid foundation or for gamma = 0)
    first: float  # S: sum of m times the distance from the pivot, (1 + 2 gamma_c) R
    inertia: float  # J about the pivots, (4/3 + 4 gamma_c) R^2
    before: float  # K: theta-momentum of the mechanism after an impact per unit theta_dot before it
    p2: float  # g S / J [1/s^2]


def colonnade_masses(block: Block, gamma: float, cap_ratio: float = 0.0) -> ColonnadeMasses:
    """:class:`ColonnadeMasses` of ``block`` columns capped with a beam of ``cap_ratio`` times their mass on a
    base of mass ratio ``gamma`` (columns + beam over the moving mass; 0: rigid foundation). Per column
    and its beam share: the column about its pivot ``(4/3) R^2`` after and ``R^2 (1/3 + cos 2 alpha)``
    before (Housner), the beam at ``2 R`` from the pivot ``4 gamma_c R^2`` after and ``4 gamma_c (h^2 -
    b^2)`` before (its velocity ``2 R theta_dot`` along the old diagonal projected on the new one)."""
    R, b, h, gc = block.R, block.b, block.h, float(cap_ratio)
    Io = 4.0 / 3.0 * R * R
    total = (1.0 + gc) * (1.0 + (1.0 - gamma) / gamma) if gamma > 0 else np.inf
    first, inertia = (1.0 + 2.0 * gc) * R, Io + 4.0 * gc * R * R
    p2 = block.p ** 2 if gc == 0.0 else G * first / inertia
    return ColonnadeMasses(total, first, inertia, Io - 2 * b * b + 4.0 * gc * (h * h - b * b), p2)


def impact_map_linear_system(block: Block, gamma: float, thd1: float, ud1: float, restitution: float | None = None,
                             cap_ratio: float = 0.0):
    """Velocities after an impact from Eq (14) (angular momentum about the new pivot) and Eq (16)
    (horizontal momentum of block + base), per unit block mass, solved as a linear system.

    A colonnade (``cap_ratio`` > 0) adds the beam's terms (:func:`colonnade_masses`); a given
    ``restitution`` E takes ``E J theta_dot-`` as the momentum before (theta_dot+ = E theta_dot- on the
    ground). A rebound against the rocking (a squat body) is clamped to theta_dot+ = 0, the base taking
    the horizontal momentum."""
    m = colonnade_masses(block, gamma, cap_ratio)
    K = m.before if restitution is None else float(restitution) * m.inertia
    Sh = m.first * math.cos(block.alpha)
    if not np.isfinite(m.total):
        thd2, ud2 = thd1 * K / m.inertia, ud1
    else:
        # unknowns (thd2, ud2):   J thd2 + S h/R ud2 = K thd1 + S h/R ud1
        #                      S h/R thd2 + M ud2 = S h/R thd1 + M ud1
        M = np.array([[m.inertia, Sh], [Sh, m.total]])
        rhs = np.array([K * thd1 + Sh * ud1, Sh * thd1 + m.total * ud1])
        thd2, ud2 = (float(v) for v in np.linalg.solve(M, rhs))
    if thd2 * thd1 < 0.0:
        thd2, ud2 = 0.0, ud1 + (Sh / m.total * thd1 if np.isfinite(m.total) else 0.0)
    return float(thd2), float(ud2)


def is_hysteretic(foundation) -> bool:
    """A sliding or lead-rubber bearing (a Bouc-Wen element): recognised by its fields, so that this
    module needs no bearing class (they live in :mod:`rockcli.models` once sliding bearings exist)."""
    return hasattr(foundation, "u_y") and (hasattr(foundation, "mu1") or hasattr(foundation, "mu")
                                          or hasattr(foundation, "Q_ratio"))


def state_scales(block: Block, foundation, n_states: int) -> np.ndarray:
    """Scales of the states (theta, theta_dot, u, u_dot, hysteretic...) for a mixed error test.

    The kernel keeps the error on each state below ``rtol * max(|y|, scale)``; ``atol = rtol * scale``
    gives SciPy the same test: alpha, p alpha, ``g tan(alpha)/max(omega_b, p)^2`` and
    ``g tan(alpha)/max(omega_b, p)`` for the base, 1 for a Bouc-Wen ``z`` (|z| <= 1) and the
    displacement scale for a DCSS surface displacement.
    """
    p, alpha = block.p, block.alpha
    sc = [alpha, p * alpha]
    if n_states > 2:
        thr = G * math.tan(alpha)
        w = getattr(foundation, "omega_b", p)
        w = max(w, p)
        sc += [thr / w ** 2, thr / w]
        if n_states > 4:
            extra = n_states - 4
            sc += [1.0] * extra if extra == 1 else [thr / w ** 2] + [1.0] * (extra - 1)
    return np.asarray(sc[:n_states], dtype=float)


def rocking_on_base(th: float, thd: float, s: float, F: float, *, alpha: float, p2: float, gamma: float, R: float):
    """``(theta_dot_dot [rad/s^2], absolute base acceleration [m/s^2])`` of a block rocking on corner
    ``s`` (+1 or -1) on a base whose bearing pushes with ``F`` [m/s^2] per unit total mass (Eqs 10-11
    with the reading-notes corrections; ``gamma = m/(m + m_b)``, ``p2 = p^2``)."""
    g = G
    A = alpha * s - th
    num = F - gamma * R * thd ** 2 * math.sin(A) + gamma * R * p2 * math.cos(A) * math.sin(A)
    a_abs = num / (1 - gamma * R * p2 * math.cos(A) ** 2 / g)  # Eq (10) + ug_ddot
    thdd = -p2 * (math.sin(A) + math.cos(A) * num / (g - gamma * R * p2 * math.cos(A) ** 2))  # Eq (11)
    return thdd, a_abs


def rocking_accelerations(block: Block, gamma: float, cap_ratio: float = 0.0):
    """``f(th, thd, s, F) -> (theta_dot_dot, absolute base acceleration)`` of ``block`` (or its capped
    colonnade) rocking on corner ``s`` on a base pushed by ``F`` [m/s^2 per unit moving mass]: Eqs 10-11
    (:func:`rocking_on_base`) for one block; for a colonnade Lagrange's equations in u and theta,
    ``M a + S (theta'' cos A + theta'^2 sin A) = M F``, ``S cos A a + J theta'' = -S g sin A``, solved."""
    if cap_ratio == 0.0:
        p2 = block.p ** 2

        def one_block(th, thd, s, F):
            return rocking_on_base(th, thd, s, F, alpha=block.alpha, p2=p2, gamma=gamma, R=block.R)
        return one_block
    m = colonnade_masses(block, gamma, cap_ratio)

    def colonnade(th, thd, s, F):
        A = block.alpha * s - th
        sA, cA = math.sin(A), math.cos(A)
        Mt, S, J = m.total, m.first, m.inertia
        if not np.isfinite(Mt):  # an infinitely heavy base moves with its bearings' force alone
            return -S * (G * sA + F * cA) / J, F
        r1, r2 = Mt * F - S * thd * thd * sA, -S * G * sA
        det = Mt * J - S * S * cA * cA
        return (Mt * r2 - S * cA * r1) / det, (r1 * J - S * cA * r2) / det
    return colonnade
