"""Right-hand sides: one per driver, scalars in, scalars out (no arrays in the hot path).

* Rigid foundation, Eq (3): ``theta_ddot = -p^2 (sin A + ag/g cos A)``, ``A = s alpha - theta``; under a
  vertical ground acceleration ``a_v`` (upward positive) gravity becomes ``g + a_v`` in the restoring
  term: ``theta_ddot = -p^2 ((1 + a_v/g) sin A + ag/g cos A)`` (``p^2 = 3 g/(4 R)``).
* Isolated base (linear, single concave / lead-rubber, double concave: only the bearing force
  ``F`` differs, :func:`rockcli.kernels.bearings.base_force`):
  - stuck: block and base move together, ``u_ddot = F - ag``;
  - rocking: Eqs (10)-(11) (Eq 36 for the hysteretic bearings) with the corrected denominator
    (reading notes 1-2), written through the absolute base acceleration
    ``a = (F - gamma R thd^2 sin A + gamma R p^2 sin A cos A)/(1 - gamma R p^2 cos^2 A / g)``,
    ``theta_ddot = -p^2 (sin A + a/g cos A)``, ``u_ddot = a - ag``.

``hy`` is the anchor of the hysteretic elements (see :mod:`rockcli.kernels.bearings`): their
variables z follow u exactly inside a step and are not integrated here.
"""

from __future__ import annotations

import math

from rockcli.kernels.bearings import base_force
from rockcli.kernels.ground import _ground, _vertical
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import P_ALPHA, P_G, P_GAMMA, P_P2, P_R, PHASE_STUCK


@kernel(inline='always')
def _rhs_rigid(s, prm, seg, epar, t, th, thd):
    """Rigid foundation: ``(theta_dot, theta_ddot)`` at ``t`` (Eq 3)."""
    ag = _ground(t, seg, epar)
    gv = 1.0 + _vertical(t, seg) / prm[P_G]  # (g + a_v)/g: exactly 1 without a vertical motion
    A = s * prm[P_ALPHA] - th
    return thd, -prm[P_P2] * (math.sin(A) * gv + ag / prm[P_G] * math.cos(A))


@kernel(inline='always')
def _rhs_rigid_into(fkind, phase, s, prm, seg, epar, hy, t, W, src, dst):
    """:func:`_rhs_rigid` from row ``src`` into row ``dst`` of ``W`` (the signature of :func:`_rhs_into`)."""
    d0, d1 = _rhs_rigid(s, prm, seg, epar, t, W[src, 0], W[src, 1])
    W[dst, 0] = d0
    W[dst, 1] = d1


@kernel(inline='always')
def _rhs(fkind, phase, s, prm, seg, epar, hy, t, th, thd, u, ud):
    """Isolated base: derivatives ``(theta_dot, theta_ddot, u_dot, u_ddot)`` of the scene's states at ``t``."""
    ag = _ground(t, seg, epar)
    F = base_force(fkind, prm, u, ud, hy)
    if phase == PHASE_STUCK:
        return 0.0, 0.0, ud, F - ag
    A = s * prm[P_ALPHA] - th
    sA = math.sin(A)
    cA = math.cos(A)
    gR = prm[P_GAMMA] * prm[P_R]
    a = (F - gR * thd * thd * sA + gR * prm[P_P2] * sA * cA) / (1.0 - gR * prm[P_P2] * cA * cA / prm[P_G])
    return thd, -prm[P_P2] * (sA + a / prm[P_G] * cA), ud, a - ag


@kernel(inline='always')
def _rhs_into(fkind, phase, s, prm, seg, epar, hy, t, W, src, dst):
    d0, d1, d2, d3 = _rhs(fkind, phase, s, prm, seg, epar, hy, t, W[src, 0], W[src, 1], W[src, 2], W[src, 3])
    W[dst, 0] = d0
    W[dst, 1] = d1
    W[dst, 2] = d2
    W[dst, 3] = d3
