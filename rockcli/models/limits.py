"""What a model may be: the foundation kind codes, the default parameters, the supported ranges,
and the checks that refuse a value outside them in one sentence (:class:`RockcliInputError`).

The ranges are stated in the README's "Bad input" section.
"""

from __future__ import annotations

import math
from dataclasses import fields

from rockcli.errors import RockcliInputError

#: Foundation kinds understood by :mod:`rockcli.kernels` (``rockcli.kernels.layout.FOUNDATION_*``).
KIND_RIGID = 0
KIND_LINEAR = 1
KIND_BILINEAR = 2
KIND_DCSS = 3

#: Default mass ratio gamma = m / (m + m_b) of an isolated base: a heavy base, as in the paper's
#: parametric figures (Figs 6, 7, 9, 11). For gamma <= 0.1 the response hardly depends on gamma
#: (the paper's Figure 8: "complete similarity" in gamma).
DEFAULT_GAMMA = 0.01
#: Default viscous damping ratio of linear bearings: the paper's Table III (xi_b = 0.1).
DEFAULT_XI = 0.1
#: Default yield displacement of a sliding bearing [m]: the paper's u_y ~ 0.25 mm (after Eq 34).
DEFAULT_UY = 0.25e-3
#: Default Bouc-Wen exponent and shape parameters of Eq (34): n = 2, beta = gamma_bw = 0.5, common
#: practice for sliding bearings (reading notes, note 4). The form with A = 1 and beta + gamma_bw = 1,
#: so that |z| <= 1 and Q is the strength, is that of Constantinou, Mokha & Reinhorn (1990), "Teflon
#: bearings in base isolation II: modeling", J Struct Eng 116(2):455-474.
DEFAULT_BW_N = 2.0
DEFAULT_BW_BETA = 0.5
DEFAULT_BW_GAMMA = 0.5


# --------------------------------------------------------------------------------------------------
# Supported ranges (checked when a model is built; stated in the README's "Bad input" section)
# --------------------------------------------------------------------------------------------------
#: Semi-diagonal R [m]: from a figurine 2 cm tall to a monolith 140 m tall. Below 1 cm the block's
#: frequency p = sqrt(3 g / 4 R) (27 rad/s at 1 cm) makes the rocking ever faster to integrate and the
#: rigid-block idealisation has no object left; above 100 m no free-standing rigid body exists.
R_RANGE_M = (0.01, 100.0)
#: Smallest slenderness alpha [deg]: 1 deg is h/b = 57, far slenderer than any free-standing body
#: (temple columns 5-7, obelisks about 10). A slenderer body uplifts at g tan(alpha) < 0.017 g, i.e.
#: under ground noise; it loses almost nothing at impacts (1 - eta ~ 1.5 sin^2 alpha), so one
#: rocking cascade down to rest takes ln(1/rest_tol)/(3 sin^2 alpha) impacts (20,000 at 1 deg with
#: the default rest_tol 1e-8, 2 million at 0.1 deg: the event-driven run crawls to the step cap); and
#: theta/alpha grows without bound while theta stays finite (``--R 1 --alpha 1e-9`` "survived" with
#: theta/alpha = 1e10). The upper end is 90 deg exclusive: the kernel handles squat blocks (they
#: rarely uplift, and stop at their first impact once sin^2 alpha >= 2/3); sliding, which a squat
#: block on a low-friction base does first, is not modelled.
ALPHA_MIN_DEG = 1.0
#: Isolation period T_b [s]. Below 5 ms the bearings are a rigid foundation for every record (no
#: record carries motion above 100 Hz) and the base's frequency omega_b makes the integrator crawl;
#: at 1e6 s (11.6 days) the base is already fully decoupled from the ground (tested).
TB_RANGE_S = (0.005, 1e6)
#: Viscous damping ratio xi of the bearings: real bearings have 0.02-0.3; above 10 times critical
#: the dampers lock the base and its fastest rate, about 2 xi omega_b, sets the step (``xi=1e6``
#: would need ~1e8 steps).
XI_MAX = 10.0
#: Yield displacements of hysteretic bearings [m]: sliding bearings have 0.05-0.5 mm, lead-rubber
#: bearings tens of mm. Below 1 micrometre the elastic branch (stiffness Q/u_y) is stiffer than any
#: bearing and only slows the run down (the verdicts are those of u_y -> 0 well before that).
UY_RANGE_M = (1e-6, 0.1)


def _num(x) -> str:
    """A number for a message: plain float formatting (never ``np.float64(...)``), never rounded."""
    from rockcli.io.inputs import format_number

    return format_number(x)


def _check(cond: bool, message) -> None:
    """Raise ``message`` (the sentence, or a function that writes it) when ``cond`` is false.

    A function is called only for a check that fails: the checks run for every block and bearing a sweep builds,
    and :func:`_num` costs about 8 microseconds a number."""
    if not cond:
        raise RockcliInputError(message() if callable(message) else message)


def _finite(x) -> bool:
    """``x`` is a finite number (a numeric string too, as the specs give); a bool is not (``Plinth(True, 0.6)``
    would build a plinth 1 m tall)."""
    if isinstance(x, bool) or type(x).__name__ in ("bool", "bool_"):  # Python's and numpy's
        return False
    try:
        return math.isfinite(float(x))
    except (TypeError, ValueError):
        return False


def _check_period(T_b, what="isolation period Tb"):
    _check(_finite(T_b) and float(T_b) > 0, lambda: f"{what} must be positive (s), got {_num(T_b)}")
    lo, hi = TB_RANGE_S
    _check(lo <= float(T_b) <= hi,
           lambda: f"{what} = {_num(T_b)} s lies outside the supported {lo:g} s to {hi:g} s (stiffer bearings are a "
                   f"rigid foundation for any record: use 'none'; at {hi:g} s the base is already free)")


def _check_gamma(gamma):
    _check(_finite(gamma) and 0 <= float(gamma) < 1,
           lambda: f"mass ratio gamma = m/(m+m_b) must satisfy 0 <= gamma < 1, got {_num(gamma)}")




def _check_yield(u_y):
    lo, hi = UY_RANGE_M
    _check(_finite(u_y) and lo <= u_y <= hi,
           lambda: f"yield displacement uy must lie between {lo:g} m and {hi:g} m (sliding bearings have 0.05-0.5 mm), "
                   f"got {_num(u_y)}")


def _check_bouc_wen(n, beta, gamma_bw):
    """The Bouc-Wen parameters rockcli integrates exactly (see rockcli.kernels.bearings).

    ``n`` 1 or 2 (closed-form branches); ``beta + gamma_bw = 1`` (A = 1: |z| <= 1, so the strength
    is Q); ``gamma_bw >= |beta|`` (the element never gives back more energy than it stored, which
    the end-of-run proof P3s needs), i.e. ``beta <= 0.5``.
    """
    _check(_finite(n) and float(n) in (1.0, 2.0), lambda: f"Bouc-Wen exponent n must be 1 or 2, got {n!r}")
    _check(_finite(beta) and _finite(gamma_bw) and abs(float(beta) + float(gamma_bw) - 1.0) <= 1e-12,
           lambda: f"Bouc-Wen beta + gamma_bw must equal 1 (so that Q is the strength), got {beta!r} + {gamma_bw!r}")
    _check(float(gamma_bw) >= abs(float(beta)),
           lambda: f"Bouc-Wen gamma_bw must be at least |beta| (a passive element), got beta = {beta!r}")


def _check_fraction(what, x):
    """``0 < x < 1``: a coefficient of friction, or a bearing's strength over the weight."""
    _check(_finite(x) and 0 < x < 1, lambda: f"{what} must lie strictly between 0 and 1, got {x!r}")


def _check_hysteresis(bearing) -> None:
    """The checks every hysteretic bearing ends with (yield displacement, mass ratio, Bouc-Wen
    parameters); then its fields (all numbers) are stored as floats."""
    _check_yield(bearing.u_y)
    _check_gamma(bearing.gamma)
    _check_bouc_wen(bearing.n, bearing.beta, bearing.gamma_bw)
    for f in fields(bearing):
        object.__setattr__(bearing, f.name, float(getattr(bearing, f.name)))
