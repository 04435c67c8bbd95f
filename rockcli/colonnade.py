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
parameter, and ``0 <= eta <= 1``). A colonnade on an isolated base is refused: the beam's mass
would enter the base's horizontal momentum and the impact map, which are not derived here.
"""

from __future__ import annotations

import math

from rockcli.errors import RockcliInputError
from rockcli.inputs import format_number
from rockcli.models import Rigid

#: Largest cap ratio accepted: a beam 100 times the columns' mass (the factor on p^2 is then 0.6689).
CAP_RATIO_MAX = 100.0


def check_cap_ratio(cap_ratio, foundation=None, what: str = "cap_ratio") -> float:
    """``cap_ratio`` as a float in [0, CAP_RATIO_MAX]; refused (one sentence) on an isolated base when > 0."""
    try:
        gc = float(cap_ratio)
    except (TypeError, ValueError):
        raise RockcliInputError(f"{what} must be a number >= 0 (beam mass over the columns' total mass)") from None
    if not (math.isfinite(gc) and 0.0 <= gc <= CAP_RATIO_MAX):
        raise RockcliInputError(f"{what} must lie between 0 and {CAP_RATIO_MAX:g} (beam mass over the columns' total "
                                f"mass), got {format_number(gc)}")
    if gc > 0.0 and foundation is not None and not isinstance(foundation, Rigid):
        raise RockcliInputError(f"{what} needs a rigid foundation: a capped colonnade on an isolated base (the beam's "
                                f"mass in the base's momentum and impact map) is not derived in rockcli")
    return gc


def frequency_factor(cap_ratio: float) -> float:
    """``(p_colonnade / p)^2 = (1 + 2 gamma_c)/(1 + 3 gamma_c)``."""
    return (1.0 + 2.0 * cap_ratio) / (1.0 + 3.0 * cap_ratio)


def colonnade_restitution(alpha: float, cap_ratio: float) -> float:
    """``theta_dot+ / theta_dot-`` at an impact of the colonnade,
    ``(1 - 1.5 sin^2 alpha + 3 gamma_c cos 2 alpha)/(1 + 3 gamma_c)`` (clamped at 0)."""
    return max(0.0, (1.0 - 1.5 * math.sin(alpha) ** 2 + 3.0 * cap_ratio * math.cos(2.0 * alpha))
               / (1.0 + 3.0 * cap_ratio))


def apply_cap_ratio(prm, kernels, block, cap_ratio: float, restitution: float | None) -> None:
    """Turn the rigid-foundation parameters ``prm`` of ``block`` into those of its colonnade (in place);
    ``cap_ratio`` 0 leaves them untouched (the solitary column, bit for bit). A given ``restitution``
    overrides the colonnade's impact ratio."""
    if cap_ratio == 0.0:
        return
    p2 = prm[kernels.P_P2] * frequency_factor(cap_ratio)
    prm[kernels.P_P2] = p2
    prm[kernels.P_SC0 + 1] = math.sqrt(p2) * block.alpha  # error scale of theta_dot: p alpha
    prm[kernels.P_ETA] = colonnade_restitution(block.alpha, cap_ratio) if restitution is None else restitution
    prm[kernels.P_DU] = 0.0
