"""The kernel's parameter vector ``prm`` of a block on a foundation (``rockcli.kernels.layout``), and
:func:`bearing_force_path`, the bearings alone under an imposed displacement, from the same code.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.models.colonnade import apply_cap_ratio, check_cap_ratio
from rockcli.models.impact import impact_ratio
from rockcli.models import Block, DoubleConcaveSliding, LeadRubber, LinearIsolation, Rigid, SingleConcaveSliding
from rockcli.solve.options import DEFAULT_REST_TOL, DEFAULT_RTOL, _kernel, _rtol
from rockcli.io.units import G


def _parameters(block: Block, foundation, rtol, rest_tol: float, restitution: float | None = None,
                cap_ratio: float = 0.0):
    """``(fkind, prm)``: the kernel's foundation code and parameter vector (``rockcli.kernels.layout``);
    ``rtol`` None takes the foundation's default; ``restitution`` None Housner's (:mod:`rockcli.models.impact`);
    ``cap_ratio`` > 0 a capped colonnade (:mod:`rockcli.models.colonnade`)."""
    k = _kernel()
    rtol = _rtol(foundation, rtol)
    prm = np.zeros(k.N_PRM)
    p = block.p
    alpha = block.alpha
    gamma = foundation.gamma
    prm[k.P_P2] = p * p
    prm[k.P_G] = G
    prm[k.P_ALPHA] = alpha
    prm[k.P_R] = block.R
    prm[k.P_GAMMA] = gamma
    prm[k.P_THR] = G * math.tan(alpha)
    prm[k.P_SINA] = math.sin(alpha)
    prm[k.P_COSA] = math.cos(alpha)
    prm[k.P_H] = block.h
    prm[k.P_ETA] = impact_ratio(alpha, gamma, restitution)
    # base velocity jump at an impact, u_dot+ = u_dot- + P_DU theta_dot-: the total horizontal momentum
    # u_dot + gamma h theta_dot is kept, so P_DU = gamma h (1 - eta) (= 6 gamma h/(k + 4) when eta is not
    # clamped; a block too squat to rock, eta clamped to 0, hands all its momentum to the base)
    prm[k.P_DU] = gamma * block.h * (1.0 - prm[k.P_ETA])
    prm[k.P_REST] = rest_tol
    prm[k.P_RTOL] = rtol
    # error scales: the tolerance on a state is rtol * max(|y|, scale)
    prm[k.P_SC0 + 0] = alpha
    prm[k.P_SC0 + 1] = p * alpha
    if isinstance(foundation, Rigid):
        fkind = k.FOUNDATION_RIGID
        prm[k.P_SC0 + 2] = prm[k.P_SC0 + 3] = 1.0
    elif isinstance(foundation, LinearIsolation):
        fkind = k.FOUNDATION_LINEAR
        w = foundation.omega_b
        prm[k.P_W] = w
        prm[k.P_XI] = foundation.xi
        # the smaller of the displacement at which the bearings' force uplifts the block and the
        # block's own length scale g tan(alpha)/p^2 = (4/3) R tan(alpha)
        prm[k.P_SC0 + 2] = prm[k.P_THR] / max(w, p) ** 2
        prm[k.P_SC0 + 3] = prm[k.P_THR] / max(w, p)
    elif isinstance(foundation, (SingleConcaveSliding, LeadRubber, DoubleConcaveSliding)):
        w = foundation.omega_b
        prm[k.P_W] = w
        prm[k.P_BWN] = foundation.n
        prm[k.P_BWC] = foundation.gamma_bw - foundation.beta
        if isinstance(foundation, DoubleConcaveSliding):
            fkind = k.FOUNDATION_DCSS
            prm[k.P_K1] = G / foundation.R1_eff
            prm[k.P_K2] = G / foundation.R2_eff
            prm[k.P_Q1] = foundation.mu1 * G
            prm[k.P_Q2] = foundation.mu2 * G
            prm[k.P_UY1] = prm[k.P_UY2] = 0.5 * foundation.u_y  # the bearing as a whole yields at u_y
        else:
            fkind = k.FOUNDATION_BILINEAR
            prm[k.P_Q1] = foundation.strength_ratio * G
            prm[k.P_UY1] = foundation.u_y
        prm[k.P_SC0 + 2] = prm[k.P_THR] / max(w, p) ** 2
        prm[k.P_SC0 + 3] = prm[k.P_THR] / max(w, p)
    else:
        raise RockcliInputError(f"unknown foundation {foundation!r}")
    apply_cap_ratio(prm, k, block, foundation, check_cap_ratio(cap_ratio), restitution)  # a capped colonnade
    return fkind, prm


def bearing_force_path(foundation, u) -> dict[str, np.ndarray]:
    """The bearings of ``foundation`` under an imposed base displacement history ``u`` [m].

    Returns ``{"force": ..., "z": ..., "z2": ...}``: the bearings' restoring force per unit total
    mass ``(k_b u + Q z)/(m + m_b)`` [m/s^2] (divide by g for force over weight) and the Bouc-Wen
    variables (``z2`` for a double concave bearing only), from the same code the solver uses. The
    path is taken as monotone between samples (exact for a piecewise-monotone path). Linear
    bearings give their elastic force only (no velocity here).
    """
    if isinstance(foundation, Rigid):
        raise RockcliInputError("a rigid foundation has no bearings")
    u = np.ascontiguousarray(u, dtype=np.float64)
    if u.ndim != 1 or not np.all(np.isfinite(u)):
        raise RockcliInputError("the displacement path must be a 1-D array of finite values in m")
    k = _kernel()
    block = Block(1.0, 0.2)  # the bearing's parameters do not depend on the block
    fkind, prm = _parameters(block, foundation, DEFAULT_RTOL, DEFAULT_REST_TOL)
    out = np.zeros((u.size, 3))
    if fkind == k.FOUNDATION_LINEAR:
        out[:, 0] = -foundation.omega_b ** 2 * u
    else:
        k.force_along_path(fkind, tuple(float(v) for v in prm), u, out)
    res = {"force": -out[:, 0], "z": out[:, 1] if fkind >= k.FOUNDATION_BILINEAR else None,
           "z2": out[:, 2] if fkind == k.FOUNDATION_DCSS else None}
    return res
