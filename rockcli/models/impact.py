"""The impact map with a given coefficient of restitution ``E`` (``--restitution``).

On a rigid foundation ``E`` is the ratio of angular velocities after / before an impact,
``theta_dot+ = E theta_dot-`` (Housner's value ``eta_H = 1 - 1.5 sin^2 alpha`` by default: the
block's angular momentum about the new pivot is kept, the whole impulse acting at that corner).

Derivation on an isolated base
------------------------------
Per unit total mass ``m + m_b``, at theta = 0 (``h = R cos alpha``, ``I_0 = 4/3 m R^2``):

* horizontal momentum ``u_dot + gamma h theta_dot``: the bearings' forces are finite, so no
  horizontal impulse acts on block + base and it is kept for ANY contact law;
* angular momentum of the block about the new pivot, per unit block mass,
  ``L = (4/3) R^2 theta_dot + h u_dot`` after and ``R^2 (1/3 + cos 2 alpha) theta_dot + h u_dot``
  before (the block still turns about the old corner).

Housner's point impulse keeps ``L``; together with the momentum that gives the default map
``eta(gamma) = (k - 2)/(k + 4)``, ``k = (4 - 3 gamma) cot^2 alpha``
(:func:`rockcli.models.impact_coefficient`). A measured ``E`` differs from ``eta_H`` because the
real contact is not one point: vertical impulses spread over the base add an impulsive couple
``C`` about the new pivot. A couple of vertical impulses has no horizontal part, so the momentum is
still kept. It is a property of the contact (block, joint), not of what lies under it, so we take
the same couple on every base, the one that turns Housner's ``eta_H`` into ``E`` on the ground:

    ``C / m = (4/3) R^2 (E - eta_H) theta_dot-``   (the rigid foundation: ``(4/3) R^2 (theta_dot+ -
    eta_H theta_dot-)``).

Adding ``C`` to the angular-momentum balance with the base free to move gives
``((4/3) R^2 - gamma h^2) theta_dot+ = (R^2 (1/3 + cos 2 alpha) - gamma h^2) theta_dot- + C/m``, i.e.

    ``eta_E(gamma) = 1 - 4 (1 - E) / (4 - 3 gamma cos^2 alpha)``   (clamped at 0),
    ``u_dot+ = u_dot- + gamma h (1 - eta_E) theta_dot-``.

Checks: ``gamma -> 0`` gives ``eta_E = E`` (the rigid foundation); ``E = eta_H`` gives ``eta(gamma)``
(the default map); ``E = 1`` gives ``eta_E = 1`` on every base (no loss at all). Energy: with the
momentum ``P`` kept, the kinetic energy at theta = 0 is ``P^2/2 + c theta_dot^2`` with
``c = gamma (2 R^2/3 - gamma h^2/2) > 0``, so an impact changes it by ``c (eta_E^2 - 1) theta_dot-^2
<= 0`` as ``0 <= eta_E <= 1`` for ``0 < E <= 1`` (the loss factor ``4/(4 - 3 gamma cos^2 alpha)`` is
>= 1). Impacts therefore never add energy, which is all the end-of-run proofs (P2, P4, P5, P6, P8
in :mod:`rockcli.kernels`) assume of them.

When ``E`` is not given, or equals Housner's value exactly, the default map is used unchanged (the
same numbers bit for bit).
"""

from __future__ import annotations

import math

from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number
from rockcli.models import impact_coefficient


def housner_restitution(alpha: float) -> float:
    """Housner's ratio ``1 - 1.5 sin^2 alpha`` (may be <= 0 for squat blocks, which then stop)."""
    return 1.0 - 1.5 * math.sin(alpha) ** 2


def check_restitution(restitution, what: str = "restitution"):
    """``restitution`` as a float (None stays None: Housner's value); one sentence if outside (0, 1]."""
    if restitution is None:
        return None
    try:
        E = float(restitution)
    except (TypeError, ValueError):
        raise RockcliInputError(f"{what} must be a number between 0 (exclusive) and 1, got {restitution!r}") from None
    if not (math.isfinite(E) and 0.0 < E <= 1.0):
        raise RockcliInputError(
            f"{what} must satisfy 0 < E <= 1 (the ratio of angular velocities after / before an impact on a rigid "
            f"foundation; 1 is a perfectly elastic impact), got {format_number(E)}")
    return E


def impact_ratio(alpha: float, gamma: float, restitution: float | None = None) -> float:
    """``theta_dot+ / theta_dot-`` at an impact on a base of mass ratio ``gamma`` (0: rigid foundation).

    ``restitution`` None (or Housner's value) gives the momentum map :func:`rockcli.models.impact_coefficient`;
    otherwise ``1 - 4 (1 - E)/(4 - 3 gamma cos^2 alpha)``, clamped at 0 (derivation in the module notes).
    """
    if restitution is None or restitution == housner_restitution(alpha):
        return impact_coefficient(alpha, gamma)
    E = float(restitution)
    return max(0.0, 1.0 - 4.0 * (1.0 - E) / (4.0 - 3.0 * gamma * math.cos(alpha) ** 2))


def restitution_label(restitution: float | None) -> str:
    """How reports name the impact rule: ``housner`` or the value."""
    return "housner" if restitution is None else f"{restitution:g}"
