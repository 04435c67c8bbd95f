"""What a reference run returns, and how it fails."""

from __future__ import annotations

import math
from dataclasses import dataclass

#: The SciPy ``solve_ivp`` methods a reference can use.
METHODS = ("RK45", "DOP853", "Radau", "LSODA", "BDF")
#: Implicit methods: their right-hand-side count includes the finite-difference Jacobian columns.
IMPLICIT = ("Radau", "BDF", "LSODA")


@dataclass
class RefResult:
    """Outcome of :func:`reference_simulate` (SI units).

    ``verdict``, peak ``theta_max`` [rad], ``t_uplift``, ``t_overturn`` [s] (NaN when it does not
    overturn), ``n_impacts`` (while the ground moves), peak base displacement ``u_max`` [m];
    ``t_rest`` [s], the last time the block was set at rest for good (NaN when it never rests or
    overturns); ``t_theta_max`` [s], when the peak was reached; the work: ``steps`` (accepted steps
    of every ``solve_ivp`` call), ``nfev`` (right-hand sides, including ``n_states`` per
    finite-difference Jacobian), ``njev``, ``nlu``
    and ``wall_s`` (the whole run); ``method``, ``rtol`` and ``atol`` as used.
    """

    verdict: str
    theta_max: float
    t_uplift: float
    t_overturn: float
    n_impacts: int
    u_max: float
    t_rest: float = math.nan
    t_theta_max: float = math.nan
    steps: int = 0
    nfev: int = 0
    njev: int = 0
    nlu: int = 0
    wall_s: float = math.nan
    method: str = "DOP853"
    rtol: float = math.nan
    atol: object = None
    n_rests: int = 0


class ReferenceTimeout(RuntimeError):
    """A reference run passed its wall-time budget (``deadline_s``)."""


class ReferenceFailure(RuntimeError):
    """``solve_ivp`` gave up (e.g. the step size fell below its minimum)."""
