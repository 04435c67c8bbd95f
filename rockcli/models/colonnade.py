"""A capped colonnade (``--cap-ratio GAMMA_C``): N equal free-standing columns carrying a rigid beam.

Makris & Vassiliou (2013), EESD 42:431-449; the derivation is written out in
``docs/physics-colonnade.md``. On a rigid foundation the N columns rock together (one angle
theta), the beam translates without rotating, resting on the top corners diagonally opposite the
pivots (no slip, no lift-off), so it moves exactly twice as far as a column's centre of mass.
With ``gamma_c = m_beam / (N m_column)``:

* between impacts the colonnade is the solitary column with ``p^2`` multiplied by
  ``(1 + 2 gamma_c)/(1 + 3 gamma_c)`` (Lagrange: inertia ``N (4/3) m R^2 + 4 m_b R^2`` about the
  pivots, moment ``(N m + 2 m_b) R (g sin A + ag cos A)``, ``A = s alpha - theta``);
* uplift when ``|ag| > g tan(alpha)``, as for one column (the moment changes sign there);
* at an impact the generalized momentum of the mechanism after it (the columns' angular momenta
  about their new pivots plus the beam's moment of momentum about a column's new pivot, taken at
  its new top contact) is kept, which gives
  ``theta_dot+ / theta_dot- = (1 - 1.5 sin^2 alpha + 3 gamma_c cos 2 alpha)/(1 + 3 gamma_c)``, the
  square root of the published energy ratio (the same map).

Hence the rigid-foundation kernel runs a colonnade unchanged with ``P_P2`` and ``P_ETA`` replaced,
and every end-of-run proof carries over (they use only the equation's form, with ``p^2`` as a
parameter, and ``0 <= eta <= 1``).

On an isolated base (base mass ``m_b``; ``gamma = (N m + m_beam)/(N m + m_beam + m_b)``, the mass the
bearings carry above the base over the whole moving mass) Lagrange with ``u`` and theta gives the
solitary block's Eqs (10)-(11) exactly, with the semi-diagonal ``R_eff = R (1 + 3 gamma_c)/(1 + 2 gamma_c)``
(the same ``p_c``) and the mass ratio :func:`effective_gamma`; the impact map (the whole system's
horizontal momentum and the momentum conjugate to theta of the mechanism after the impact) is the
isolated map of :mod:`rockcli.models.impact` with ``E`` the colonnade's ratio on the ground (or the given
``--restitution``) and the effective mass ratio. So the isolated kernels run it unchanged, with
``P_P2, P_R, P_H, P_GAMMA, P_ETA, P_DU`` replaced (:func:`apply_cap_ratio`); the bearings' forces per
unit moving mass (``omega_b^2 u``, ``mu g``) take the beam's mass with the rest.
"""

from __future__ import annotations

import math

from rockcli.errors import RockcliInputError
from rockcli.models.impact import impact_ratio
from rockcli.io.inputs import format_number
from rockcli.models import Rigid

#: Largest cap ratio accepted: a beam 100 times the columns' mass (the factor on p^2 is then 0.6689).
CAP_RATIO_MAX = 100.0


def check_cap_ratio(cap_ratio, what: str = "cap_ratio") -> float:
    """``cap_ratio`` as a float in [0, CAP_RATIO_MAX] (one sentence otherwise)."""
    try:
        gc = float(cap_ratio)
    except (TypeError, ValueError):
        raise RockcliInputError(f"{what} must be a number >= 0 (beam mass over the columns' total mass)") from None
    if not (math.isfinite(gc) and 0.0 <= gc <= CAP_RATIO_MAX):
        raise RockcliInputError(f"{what} must lie between 0 and {CAP_RATIO_MAX:g} (beam mass over the columns' total "
                                f"mass), got {format_number(gc)}")
    return gc


def frequency_factor(cap_ratio: float) -> float:
    """``(p_colonnade / p)^2 = (1 + 2 gamma_c)/(1 + 3 gamma_c)``."""
    return (1.0 + 2.0 * cap_ratio) / (1.0 + 3.0 * cap_ratio)


def colonnade_restitution(alpha: float, cap_ratio: float) -> float:
    """``theta_dot+ / theta_dot-`` at an impact of the colonnade,
    ``(1 - 1.5 sin^2 alpha + 3 gamma_c cos 2 alpha)/(1 + 3 gamma_c)`` (clamped at 0)."""
    return max(0.0, (1.0 - 1.5 * math.sin(alpha) ** 2 + 3.0 * cap_ratio * math.cos(2.0 * alpha))
               / (1.0 + 3.0 * cap_ratio))


def effective_gamma(gamma: float, cap_ratio: float) -> float:
    """The solitary block's mass ratio that gives a colonnade of mass ratio ``gamma`` (superstructure over
    the whole moving mass) on its base: ``S/(M R_eff)`` with ``S = N m (1 + 2 gamma_c) R`` the first
    moment about the pivots and ``M`` the moving mass, i.e. ``gamma (1 + 2 gamma_c)^2/((1 + gamma_c)
    (1 + 3 gamma_c))`` (between gamma and 4/3 gamma; the equations need only ``gamma_eff cos^2 alpha < 4/3``)."""
    return gamma * (1.0 + 2.0 * cap_ratio) ** 2 / ((1.0 + cap_ratio) * (1.0 + 3.0 * cap_ratio))


def impact_ratio_on_base(alpha: float, gamma: float, cap_ratio: float, restitution: float | None) -> float:
    """``theta_dot+ / theta_dot-`` of a colonnade on a base of mass ratio ``gamma`` (0: rigid foundation):
    its ratio on the ground (or the given ``restitution``) through the isolated map of :mod:`rockcli.models.impact`."""
    E = colonnade_restitution(alpha, cap_ratio) if restitution is None else restitution
    if gamma == 0.0:
        return E
    return impact_ratio(alpha, effective_gamma(gamma, cap_ratio), E)


def apply_cap_ratio(prm, kernels, block, foundation, cap_ratio: float, restitution: float | None) -> None:
    """Turn the parameters ``prm`` of ``block`` on ``foundation`` into those of its colonnade (in place);
    ``cap_ratio`` 0 leaves them untouched (the solitary column, bit for bit). A given ``restitution``
    overrides the colonnade's impact ratio on the ground."""
    if cap_ratio == 0.0:
        return
    k = kernels
    p2 = prm[k.P_P2] * frequency_factor(cap_ratio)
    prm[k.P_P2] = p2
    prm[k.P_SC0 + 1] = math.sqrt(p2) * block.alpha  # error scale of theta_dot: p alpha
    if isinstance(foundation, Rigid):
        prm[k.P_ETA] = impact_ratio_on_base(block.alpha, 0.0, cap_ratio, restitution)
        prm[k.P_DU] = 0.0
        return
    R_eff = block.R / frequency_factor(cap_ratio)
    gamma = effective_gamma(foundation.gamma, cap_ratio)
    prm[k.P_R] = R_eff
    prm[k.P_H] = R_eff * math.cos(block.alpha)
    prm[k.P_GAMMA] = gamma
    prm[k.P_ETA] = impact_ratio_on_base(block.alpha, foundation.gamma, cap_ratio, restitution)
    prm[k.P_DU] = gamma * prm[k.P_H] * (1.0 - prm[k.P_ETA])  # the moving system's horizontal momentum is kept
    w = max(prm[k.P_W], math.sqrt(p2))  # the base's error scales, as for the block of semi-diagonal R_eff
    prm[k.P_SC0 + 2] = prm[k.P_THR] / w ** 2
    prm[k.P_SC0 + 3] = prm[k.P_THR] / w
