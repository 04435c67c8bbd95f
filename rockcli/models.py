"""Physical models: the rigid block and the foundations it stands on.

Everything here is SI: lengths [m], angles [rad], periods [s]. Each foundation carries its
kind code for :mod:`rockcli.kernels` and the number of states it adds; :mod:`rockcli.solve` turns
it into the kernel's parameter vector.

Notation follows Vassiliou & Makris (2012): ``R`` semi-diagonal, ``alpha`` slenderness,
``p = sqrt(3 g / (4 R))`` frequency parameter, ``gamma = m / (m + m_b)`` mass ratio,
``T_b = 2 pi / omega_b`` isolation period with ``omega_b = sqrt(k_b / (m + m_b))``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass

from rockcli.errors import RockcliInputError
from rockcli.units import G

#: Foundation kinds understood by :mod:`rockcli.kernels`.
KIND_RIGID = 0
KIND_LINEAR = 1

#: Default mass ratio gamma = m / (m + m_b) of an isolated base: a heavy base, as in the paper's
#: parametric figures (Figs 6, 7, 9, 11). For gamma <= 0.1 the response hardly depends on gamma
#: (the paper's Figure 8: "complete similarity" in gamma).
DEFAULT_GAMMA = 0.01
#: Default viscous damping ratio of linear bearings: the paper's Table III (xi_b = 0.1).
DEFAULT_XI = 0.1


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


def _num(x) -> str:
    """A number for a message: plain float formatting (never ``np.float64(...)``)."""
    try:
        return f"{float(x):g}"
    except (TypeError, ValueError):
        return repr(x)


def _check(cond: bool, message: str) -> None:
    if not cond:
        raise RockcliInputError(message)


def _finite(x) -> bool:
    try:
        return math.isfinite(float(x))
    except (TypeError, ValueError):
        return False


@dataclass(frozen=True)
class Block:
    """A rigid rectangular block rocking about its base corners.

    Parameters
    ----------
    R : float
        Semi-diagonal, centre of mass to a base corner [m], > 0.
    alpha : float
        Slenderness ``atan(b / h)`` [rad], 0 < alpha < pi/2.
    name : str
        Label used in reports.
    """

    R: float
    alpha: float
    name: str = "block"

    def __post_init__(self):
        _check_block(self.R, self.alpha)
        object.__setattr__(self, "R", float(self.R))
        object.__setattr__(self, "alpha", float(self.alpha))

    @classmethod
    def from_dimensions(cls, height: float, width: float, name: str = "block") -> "Block":
        """Block of full ``height`` and base ``width`` [m] (for a column: the base drum diameter)."""
        _check(_finite(height) and float(height) > 0,
               f"block height must be a positive length in m, got {_num(height)}")
        _check(_finite(width) and float(width) > 0, f"block width must be a positive length in m, got {_num(width)}")
        h, b = 0.5 * float(height), 0.5 * float(width)
        R, alpha = math.hypot(h, b), math.atan2(b, h)
        _check_block(R, alpha, f" (from height {_num(height)} m and width {_num(width)} m)")
        return cls(R, alpha, name)

    @classmethod
    def from_degrees(cls, R: float, alpha_deg: float, name: str = "block") -> "Block":
        """Block from its semi-diagonal [m] and slenderness in degrees."""
        _check(_finite(alpha_deg) and 0 < float(alpha_deg) < 90,
               f"block slenderness alpha must lie strictly between 0 and 90 degrees, got {_num(alpha_deg)}")
        return cls(R, math.radians(float(alpha_deg)), name)

    @property
    def b(self) -> float:
        """Half width [m]."""
        return self.R * math.sin(self.alpha)

    @property
    def h(self) -> float:
        """Half height, height of the centre of mass [m]."""
        return self.R * math.cos(self.alpha)

    @property
    def height(self) -> float:
        return 2.0 * self.h

    @property
    def width(self) -> float:
        return 2.0 * self.b

    @property
    def alpha_deg(self) -> float:
        return math.degrees(self.alpha)

    @property
    def p(self) -> float:
        """Frequency parameter ``sqrt(3 g / (4 R))`` [rad/s] (rectangular block, I_o = 4/3 m R^2)."""
        return math.sqrt(0.75 * G / self.R)

    @property
    def uplift_acceleration(self) -> float:
        """Base acceleration that uplifts the block from rest, ``g tan(alpha)`` [m/s^2]."""
        return G * math.tan(self.alpha)

    @property
    def housner_restitution(self) -> float:
        """Housner's ratio of angular velocities across an impact on a rigid base, ``1 - 1.5 sin^2 alpha``."""
        return 1.0 - 1.5 * math.sin(self.alpha) ** 2


def _check_block(R, alpha, source: str = "") -> None:
    """Raise one sentence when R [m] or alpha [rad] lies outside :data:`R_RANGE_M` / :data:`ALPHA_MIN_DEG`."""
    _check(_finite(R) and float(R) > 0, f"block size R must be a positive length in m, got {_num(R)}")
    _check(_finite(alpha) and 0 < float(alpha) < math.pi / 2,
           f"block slenderness alpha must lie strictly between 0 and 90 degrees, got {_num(alpha)} rad")
    lo, hi = R_RANGE_M
    _check(lo <= float(R) <= hi,
           f"block size R = {_num(R)} m{source} lies outside the supported {lo:g} m to {hi:g} m (a figurine 2 cm "
           f"tall to a 140 m monolith; smaller bodies rock too fast to integrate, p = sqrt(3 g/4 R))")
    deg = math.degrees(float(alpha))
    _check(deg >= ALPHA_MIN_DEG * (1 - 1e-12),
           f"block slenderness alpha = {deg:.3g} deg{source} is below the supported {ALPHA_MIN_DEG:g} deg "
           f"(h/b = {1 / math.tan(float(alpha)):.3g} > 57): such a needle uplifts under ground noise, "
           f"rocks through ever longer impact cascades, and its theta/alpha means nothing")


#: The temple columns of the paper (monolithic idealisation): full height and base drum diameter [m].
COLUMN_PRESETS = {
    "bassae": (5.95, 1.11, "Temple of Apollo at Bassae"),
    "nemea": (10.33, 1.52, "Temple of Zeus at Nemea"),
}


def column(name: str) -> Block:
    """A named column preset (``bassae`` or ``nemea``) as a :class:`Block`."""
    key = str(name).strip().lower()
    if key not in COLUMN_PRESETS:
        raise RockcliInputError(f"unknown column {name!r} (known: {', '.join(sorted(COLUMN_PRESETS))})")
    height, width, _ = COLUMN_PRESETS[key]
    return Block.from_dimensions(height, width, key)


#: How :func:`build_block` names each quantity in its messages (the library's words). The CLI
#: passes its flag names instead (``{"R": "--R", ...}``).
BLOCK_LABELS = {"preset": "a preset name", "R": "R (m)", "alpha": "alpha (deg)", "height": "height (m)",
                "width": "width (m)"}


def build_block(*, preset: str | None = None, R: float | None = None, alpha_deg: float | None = None,
                height: float | None = None, width: float | None = None, name: str | None = None,
                labels: dict | None = None, allow_preset: bool = True, context: str = "") -> Block:
    """The :class:`Block` given by exactly one of three forms: a preset, R with alpha, height with width.

    The one block builder of rockcli (the library's custom columns and the CLI's block options).

    Parameters
    ----------
    preset : str, optional
        A column preset (:data:`COLUMN_PRESETS`); with ``allow_preset=False`` it is not offered.
    R, alpha_deg : float, optional
        Semi-diagonal [m] and slenderness [deg], together.
    height, width : float, optional
        Full height and base width [m], together.
    name : str, optional
        Label of a custom block (default ``R<R>m-alpha<alpha>deg`` or ``<height>x<width>m``).
    labels : dict, optional
        How to name ``preset``, ``R``, ``alpha``, ``height``, ``width`` in error messages
        (default :data:`BLOCK_LABELS`; the CLI gives its flags, e.g. ``{"R": "--R"}``).
    context : str
        Prefix of error messages (e.g. ``"column 'statue'"``).

    Raises
    ------
    RockcliInputError
        No form or more than one; half a pair; values out of range (from :class:`Block`).
    """
    L = {**BLOCK_LABELS, **(labels or {})}
    head = f"{context}: " if context else ""
    by_preset = allow_preset and preset is not None
    by_r = R is not None or alpha_deg is not None
    by_dim = height is not None or width is not None
    pairs = f"{L['R']} with {L['alpha']}, or {L['height']} with {L['width']}"
    n = by_preset + by_r + by_dim
    if n != 1:
        if allow_preset:
            raise RockcliInputError(f"{head}give the block as exactly one of {L['preset']}, {pairs}")
        raise RockcliInputError(f"{head}give {pairs}" + (", not both" if n > 1 else ""))
    if by_preset:
        return column(preset)
    if by_r:
        if R is None or alpha_deg is None:
            raise RockcliInputError(f"{head}{L['R']} and {L['alpha']} go together")
        return Block.from_degrees(R, alpha_deg, name or f"R{R:g}m-alpha{alpha_deg:g}deg")
    if height is None or width is None:
        raise RockcliInputError(f"{head}{L['height']} and {L['width']} go together")
    return Block.from_dimensions(height, width, name or f"{height:g}x{width:g}m")


def impact_coefficient(alpha: float, gamma: float) -> float:
    """Ratio theta_dot after / before an impact, with momentum conserved (paper Eq 18, corrected).

    With ``gamma = m/(m+m_b)`` and ``k = (4 - 3 gamma) cot^2(alpha)``: ``(k - 2)/(k + 4)``.
    ``gamma = 0`` (rigid foundation) gives Housner's ``1 - 1.5 sin^2(alpha)``. A block too squat
    for this ratio to be positive stops rocking at its first impact (ratio 0).
    """
    cot2 = (math.cos(alpha) / math.sin(alpha)) ** 2
    k = (4.0 - 3.0 * gamma) * cot2
    return max(0.0, (k - 2.0) / (k + 4.0))


@dataclass(frozen=True)
class Rigid:
    """A rigid foundation: the block's base moves with the ground."""

    kind = KIND_RIGID
    n_states = 0

    @property
    def label(self) -> str:
        return "none"

    @property
    def gamma(self) -> float:
        return 0.0


@dataclass(frozen=True)
class LinearIsolation:
    """Isolated base on linear viscoelastic bearings (paper Eqs 7-11).

    Parameters
    ----------
    T_b : float
        Isolation period ``2 pi sqrt((m + m_b)/k_b)`` [s], > 0.
    xi : float
        Viscous damping ratio of the bearings, ``c_b = 2 xi omega_b (m + m_b)``, >= 0.
    gamma : float
        Mass ratio ``m / (m + m_b)``, 0 <= gamma < 1.
    """

    T_b: float
    xi: float = DEFAULT_XI
    gamma: float = DEFAULT_GAMMA

    kind = KIND_LINEAR
    n_states = 2

    def __post_init__(self):
        _check(_finite(self.T_b) and float(self.T_b) > 0,
               f"isolation period Tb must be positive (s), got {_num(self.T_b)}")
        lo, hi = TB_RANGE_S
        _check(lo <= float(self.T_b) <= hi,
               f"isolation period Tb = {_num(self.T_b)} s lies outside the supported {lo:g} s to {hi:g} s "
               f"(stiffer bearings are a rigid foundation for any record: use 'none'; at {hi:g} s the base is "
               f"already free)")
        _check(_finite(self.xi) and float(self.xi) >= 0,
               f"isolation damping ratio xi must be >= 0, got {_num(self.xi)}")
        _check(float(self.xi) <= XI_MAX,
               f"isolation damping ratio xi = {_num(self.xi)} is above the supported {XI_MAX:g} (bearings have "
               f"0.02-0.3; beyond {XI_MAX:g} times critical the dampers lock the base and the run needs "
               f"~2 xi omega_b steps per second)")
        _check(_finite(self.gamma) and 0 <= float(self.gamma) < 1,
               f"mass ratio gamma = m/(m+m_b) must satisfy 0 <= gamma < 1, got {_num(self.gamma)}")
        for f in ("T_b", "xi", "gamma"):
            object.__setattr__(self, f, float(getattr(self, f)))

    @property
    def omega_b(self) -> float:
        return 2.0 * math.pi / self.T_b

    @property
    def label(self) -> str:
        return f"linear:Tb={self.T_b:g},xi={self.xi:g},gamma={self.gamma:g}"


Foundation = Rigid | LinearIsolation

_SPEC_KEYS = {
    "linear": {"tb": "T_b", "xi": "xi", "gamma": "gamma"},
}


def parse_isolation_spec(text: str):
    """Parse an isolation spec: ``none`` or ``linear:Tb=2.5,xi=0.1,gamma=0.01``.

    ``xi`` defaults to :data:`DEFAULT_XI`, ``gamma`` to :data:`DEFAULT_GAMMA`; ``Tb`` is required.
    """
    raw = str(text).strip()
    kind, _, rest = raw.partition(":")
    kind = kind.strip().lower()
    if kind in ("none", "rigid", "fixed") and not rest.strip():
        return Rigid()
    if kind not in _SPEC_KEYS:
        raise RockcliInputError(
            f"unknown isolation {kind!r} in {raw!r} (use 'none' or 'linear:Tb=2.5,xi=0.1,gamma=0.01')")
    keys = _SPEC_KEYS[kind]
    values = {}
    for item in filter(None, (s.strip() for s in rest.split(","))):
        key, eq, val = item.partition("=")
        k = key.strip().lower()
        if not eq or k not in keys:
            raise RockcliInputError(
                f"isolation {raw!r}: {item!r} is not one of {', '.join(k + '=...' for k in keys)}")
        if not re.fullmatch(r"\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*", val):
            raise RockcliInputError(f"isolation {raw!r}: {key.strip()} must be a number, got {val.strip()!r}")
        values[keys[k]] = float(val)
    if "T_b" not in values:
        raise RockcliInputError(f"isolation {raw!r} needs Tb=<period in s>")
    return LinearIsolation(**values)
