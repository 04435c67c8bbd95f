"""The equations every reference run shares, typed again from the paper (never from the kernels).

The ground motion as a function of time, the impact map as the 2x2 momentum system of Eqs 14 and 16,
the rocking accelerations on a moving base (Eqs 10-11), and the state scales of the mixed error test.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.models import Block
from rockcli.units import G


def ground_function(excitation):
    """``(ag(t) [m/s^2], end of the excitation [s], scan grid step [s], max_step for solve_ivp [s])``.

    Records: solve_ivp steps at most one sample interval (piecewise-linear input); pulses are smooth
    and leave the step size to the error control.
    """
    if hasattr(excitation, "acc"):
        acc = np.asarray(excitation.acc, float)
        tt = excitation.dt * np.arange(acc.size)

        def ag(t):
            if t > tt[-1] or t < 0:
                return 0.0
            return float(np.interp(t, tt, acc))

        return ag, float(tt[-1]), float(excitation.dt), float(excitation.dt)

    def ag(t):
        return float(excitation.acceleration(t))

    ts, te = excitation.support()
    return ag, float(te), excitation.T_p / 200.0, np.inf


def impact_map_linear_system(block: Block, gamma: float, thd1: float, ud1: float):
    """Velocities after an impact from Eq (14) (angular momentum about the new pivot) and Eq (16)
    (horizontal momentum of block + base), per unit block mass, solved as a linear system."""
    R, b, h = block.R, block.b, block.h
    Io = 4.0 / 3.0 * R * R  # per unit mass
    mb_over_m = (1.0 - gamma) / gamma if gamma > 0 else np.inf
    if not np.isfinite(mb_over_m):
        return thd1 * (Io - 2 * b * b) / Io, ud1
    # unknowns (thd2, ud2):   Io thd2 + h ud2 = (Io - 2 b^2) thd1 + h ud1
    #                      h thd2 + (1 + mb/m) ud2 = h thd1 + (1 + mb/m) ud1
    M = np.array([[Io, h], [h, 1.0 + mb_over_m]])
    rhs = np.array([(Io - 2 * b * b) * thd1 + h * ud1, h * thd1 + (1.0 + mb_over_m) * ud1])
    thd2, ud2 = np.linalg.solve(M, rhs)
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
