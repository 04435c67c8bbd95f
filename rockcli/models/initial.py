"""A start away from rest (``simulate --theta0 RAD [--theta-dot0 RAD/S]``) and the still ground of a
free-rocking run.

The kernel starts the block rocking at ``t = 0`` from ``theta0`` with ``theta_dot0`` on the corner
``sign(theta0)`` (``sign(theta_dot0)`` when theta0 = 0), the base (if isolated) and the ground at
rest (:func:`rockcli.kernels.steps._initial_state`). Such a start counts as the first uplift, and
``|theta0|`` is the peak so far. Without ground motion the excitation is the still ground: it ends
at ``t = 0``, so the free rocking that follows is after the excitation (``n_impacts`` 0,
``n_impacts_total`` all of them) and a verdict-only run ends as soon as a proof holds (on a rigid
foundation at once when the energy is below the barrier, P2).

Free rocking on a rigid foundation has closed forms that the tests check: the time from the release
at ``theta0`` (from rest) to the first impact is the quarter period
``int_0^theta0 dtheta / sqrt(2 p^2 (cos(alpha - theta) - cos(alpha - theta0)))``, and successive peaks
obey ``cos(alpha - theta_{k+1}) = cos alpha + E^2 (cos(alpha - theta_k) - cos alpha)`` (energy
``theta_dot^2/2 + p^2 cos(alpha - |theta|)`` kept between impacts, ``theta_dot`` times E at each).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number


def check_initial_state(theta0, theta_dot0, names=("theta0", "theta_dot0")) -> tuple[float, float]:
    """``(theta0, theta_dot0)`` as floats [rad, rad/s]; one sentence (naming ``names``) when out of range."""
    try:
        th, thd = float(theta0), float(theta_dot0)
    except (TypeError, ValueError):
        raise RockcliInputError(f"{names[0]} and {names[1]} must be numbers (rad, rad/s)") from None
    if not (math.isfinite(th) and abs(th) < 0.5 * math.pi):
        raise RockcliInputError(f"{names[0]} must be an angle in rad with |theta0| < pi/2 (the block lying on its "
                                f"side), got {format_number(th)}")
    if not math.isfinite(thd):
        raise RockcliInputError(f"{names[1]} must be a finite angular velocity in rad/s, got {format_number(thd)}")
    return th, thd


def still_ground_arrays(kernels):
    """The kernel's excitation arrays of a ground at rest that ends at ``t = 0``:
    ``(ekind, epar, acc, jtab, dt, t_begin, t_exc_end)`` (a record of two zero samples 1 s apart)."""
    epar = np.zeros(kernels.N_EPAR)
    epar[kernels.E_AP] = 1.0
    return kernels.EXC_RECORD, epar, np.zeros(2), np.zeros(2), 1.0, 0.0, 0.0
