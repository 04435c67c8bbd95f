"""Solver options: their defaults and limits, each foundation's default rtol, and their validation.

Also :func:`_kernel`, the handle on :mod:`rockcli.kernels` that every module of this package
uses: the kernels (and numba) are imported on the first run, never by ``import rockcli.solve``.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number
from rockcli.models import DoubleConcaveSliding, LeadRubber, LinearIsolation, Rigid, SingleConcaveSliding

#: The foundations a scene stands on.
FOUNDATION_TYPES = (Rigid, LinearIsolation, SingleConcaveSliding, LeadRubber, DoubleConcaveSliding)


def check_foundation(foundation, what: str = "foundation"):
    """``foundation`` when it is one of :data:`FOUNDATION_TYPES` (None: :class:`Rigid`), else one sentence naming
    what was given and how to make one from a spec."""
    if foundation is None:
        return Rigid()
    if not isinstance(foundation, FOUNDATION_TYPES):
        from rockcli.io.inputs import type_words

        raise RockcliInputError(f"{what} must be a rockcli foundation (Rigid(), LinearIsolation(T_b=2.5), ...; from "
                                f"a spec such as 'none' or 'linear:Tb=2.5': parse_isolation_spec(spec)), got "
                                f"{type_words(foundation)}")
    return foundation


#: Default rtol on a rigid foundation and on linear bearings: at least the accuracy of SciPy's RK45 at
#: rtol 1e-8 (the same Dormand-Prince pair, whose error test ``atol + rtol |y|`` is up to twice as strict
#: as the kernel's ``rtol max(|y|, scale)``: at an equal rtol the two tie), for about 13 % more work.
DEFAULT_RTOL = 5e-9
#: Default rtol on sliding and lead-rubber bearings (Bouc-Wen): their runs meet, at this rtol, at least
#: the accuracy of SciPy's Radau at rtol 1e-8 (the stiff reference solver a user would otherwise reach
#: for; measured in docs/bench-work-precision.txt), for about a quarter more work than at 1e-8.
DEFAULT_RTOL_HYSTERETIC = 2e-9
DEFAULT_TAIL = 10.0
DEFAULT_REST_TOL = 1e-8
DEFAULT_HORIZON = 600.0
#: Smallest rest threshold: as it tends to 0 a train of impacts down to rest grows without bound.
REST_TOL_MIN = 1e-15
DEFAULT_MAX_STEPS = 5_000_000
#: Longest free-motion tail of a history run [s].
TAIL_MAX = 1000.0
#: Longest horizon [s]: free motion followed after the excitation to prove a verdict (an hour).
HORIZON_MAX = 3600.0


def _kernel():
    from rockcli import kernels

    return kernels


def default_rtol(foundation) -> float:
    """The default rtol of a foundation: :data:`DEFAULT_RTOL` (rigid, linear bearings) or
    :data:`DEFAULT_RTOL_HYSTERETIC` (sliding and lead-rubber bearings)."""
    check_foundation(foundation)
    if isinstance(foundation, (SingleConcaveSliding, DoubleConcaveSliding, LeadRubber)):
        return DEFAULT_RTOL_HYSTERETIC
    return DEFAULT_RTOL


def _rtol(foundation, rtol) -> float:
    """``rtol`` as given, or the foundation's default when None."""
    return default_rtol(foundation) if rtol is None else float(rtol)


def validate_options(rtol=None, tail=DEFAULT_TAIL, rest_tol=DEFAULT_REST_TOL, horizon=DEFAULT_HORIZON,
                     max_steps=DEFAULT_MAX_STEPS):
    """Refuse solver options out of their limits (:class:`RockcliInputError`, one sentence)."""
    try:
        rtol = DEFAULT_RTOL if rtol is None else float(rtol)  # None: each foundation's default
        tail, rest_tol, horizon = float(tail), float(rest_tol), float(horizon)
    except (TypeError, ValueError):
        raise RockcliInputError("rtol, tail, rest_tol and horizon must be numbers") from None
    if not (math.isfinite(rtol) and 1e-14 <= rtol <= 1e-2):
        raise RockcliInputError(f"rtol must lie between 1e-14 and 1e-2, got {format_number(rtol)}")
    if not (math.isfinite(tail) and 0 <= tail <= TAIL_MAX):
        raise RockcliInputError(f"tail must be a time between 0 and {TAIL_MAX:g} s (the free motion a history run "
                                f"shows after the excitation), got {format_number(tail)}")
    if not (math.isfinite(horizon) and 0 <= horizon <= HORIZON_MAX):
        raise RockcliInputError(f"horizon must be a time between 0 and {HORIZON_MAX:g} s (the free motion followed "
                                f"after the excitation to prove a verdict), got {format_number(horizon)}")
    if not (math.isfinite(rest_tol) and REST_TOL_MIN <= rest_tol < 1):
        raise RockcliInputError(
            f"rest_tol must satisfy {REST_TOL_MIN:g} <= rest_tol < 1 (without a rest rule a train of impacts never "
            f"ends), got {format_number(rest_tol)}")
    if isinstance(max_steps, bool) or not isinstance(max_steps, (int, np.integer)) or max_steps < 1:
        raise RockcliInputError(f"max_steps must be a whole number >= 1, got {max_steps!r}")
