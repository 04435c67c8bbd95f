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
from dataclasses import dataclass

from rockcli.errors import RockcliInputError
from rockcli.units import G

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


def _num(x) -> str:
    """A number for a message: plain float formatting (never ``np.float64(...)``), never rounded."""
    from rockcli.inputs import format_number

    return format_number(x)


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
    shown = _num(R) if not source else f"{float(R):g}"  # a derived R: the source quotes what was given
    _check(lo <= float(R) <= hi,
           f"block size R = {shown} m{source} lies outside the supported {lo:g} m to {hi:g} m (a figurine 2 cm "
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


def _check_period(T_b, what="isolation period Tb"):
    _check(_finite(T_b) and T_b > 0, f"{what} must be positive (s), got {_num(T_b)}")
    lo, hi = TB_RANGE_S
    _check(lo <= float(T_b) <= hi,
           f"{what} = {_num(T_b)} s lies outside the supported {lo:g} s to {hi:g} s (stiffer bearings are a "
           f"rigid foundation for any record: use 'none'; at {hi:g} s the base is already free)")


def _check_gamma(gamma):
    _check(_finite(gamma) and 0 <= gamma < 1,
           f"mass ratio gamma = m/(m+m_b) must satisfy 0 <= gamma < 1, got {gamma!r}")


def _check_friction(name, mu):
    _check(_finite(mu) and 0 < mu < 1, f"friction coefficient {name} must lie strictly between 0 and 1, got {mu!r}")


#: Yield displacements of hysteretic bearings [m]: sliding bearings have 0.05-0.5 mm, lead-rubber
#: bearings tens of mm. Below 1 micrometre the elastic branch (stiffness Q/u_y) is stiffer than any
#: bearing and only slows the run down (the verdicts are those of u_y -> 0 well before that).
UY_RANGE_M = (1e-6, 0.1)


def _check_yield(u_y):
    lo, hi = UY_RANGE_M
    _check(_finite(u_y) and lo <= u_y <= hi,
           f"yield displacement uy must lie between {lo:g} m and {hi:g} m (sliding bearings have 0.05-0.5 mm), "
           f"got {_num(u_y)}")


def _check_bouc_wen(n, beta, gamma_bw):
    """The Bouc-Wen parameters rockcli integrates exactly (see rockcli.kernels.bearings).

    ``n`` 1 or 2 (closed-form branches); ``beta + gamma_bw = 1`` (A = 1: |z| <= 1, so the strength
    is Q); ``gamma_bw >= |beta|`` (the element never gives back more energy than it stored, which
    the end-of-run proof P3s needs), i.e. ``beta <= 0.5``.
    """
    _check(_finite(n) and float(n) in (1.0, 2.0), f"Bouc-Wen exponent n must be 1 or 2, got {n!r}")
    _check(_finite(beta) and _finite(gamma_bw) and abs(float(beta) + float(gamma_bw) - 1.0) <= 1e-12,
           f"Bouc-Wen beta + gamma_bw must equal 1 (so that Q is the strength), got {beta!r} + {gamma_bw!r}")
    _check(float(gamma_bw) >= abs(float(beta)),
           f"Bouc-Wen gamma_bw must be at least |beta| (a passive element), got beta = {beta!r}")


def _spec_num(x: float) -> str:
    """A number for a spec label: short, and read back exactly (``repr`` when ``:g`` would round)."""
    short = f"{x:g}"
    return short if float(short) == x else repr(x)


def _bouc_wen_label(f) -> str:
    if (f.n, f.beta, f.gamma_bw) == (DEFAULT_BW_N, DEFAULT_BW_BETA, DEFAULT_BW_GAMMA):
        return ""
    return f",n={_spec_num(f.n)},beta={_spec_num(f.beta)},gammabw={_spec_num(f.gamma_bw)}"


def _floats(obj, names):
    for f in names:
        object.__setattr__(obj, f, float(getattr(obj, f)))


@dataclass(frozen=True)
class SingleConcaveSliding:
    """Isolated base on single concave spherical sliding bearings (paper Eqs 33-36).

    Bilinear with a Bouc-Wen element: bearing force ``k_b u + Q z`` with the second slope
    ``k_b = (m + m_b) omega_b^2`` (``R_eff = g/omega_b^2``, the normal force taken constant) and the
    strength ``Q = mu (m + m_b) g``.

    Parameters
    ----------
    T_b : float
        Isolation period of the second slope, ``2 pi sqrt(R_eff/g)`` [s], > 0.
    mu : float
        Coefficient of friction, 0 < mu < 1.
    u_y : float
        Yield displacement of the Bouc-Wen element [m] (default 0.25 mm).
    gamma : float
        Mass ratio ``m / (m + m_b)``, 0 <= gamma < 1.
    n, beta, gamma_bw : float
        Bouc-Wen parameters of Eq (34) (defaults 2, 0.5, 0.5; see :data:`DEFAULT_BW_N`).
    """

    T_b: float
    mu: float
    u_y: float = DEFAULT_UY
    gamma: float = DEFAULT_GAMMA
    n: float = DEFAULT_BW_N
    beta: float = DEFAULT_BW_BETA
    gamma_bw: float = DEFAULT_BW_GAMMA

    kind = KIND_BILINEAR
    n_states = 3

    def __post_init__(self):
        _check_period(self.T_b)
        _check_friction("mu", self.mu)
        _check_yield(self.u_y)
        _check_gamma(self.gamma)
        _check_bouc_wen(self.n, self.beta, self.gamma_bw)
        _floats(self, ("T_b", "mu", "u_y", "gamma", "n", "beta", "gamma_bw"))

    @property
    def omega_b(self) -> float:
        return 2.0 * math.pi / self.T_b

    @property
    def R_eff(self) -> float:
        """Effective radius of curvature ``g / omega_b^2`` [m]."""
        return G / self.omega_b ** 2

    @property
    def strength_ratio(self) -> float:
        """``Q / ((m + m_b) g)``."""
        return self.mu

    @property
    def label(self) -> str:
        return (f"scss:Tb={_spec_num(self.T_b)},mu={_spec_num(self.mu)},uy={_spec_num(self.u_y)},gamma={_spec_num(self.gamma)}"
                + _bouc_wen_label(self))


@dataclass(frozen=True)
class LeadRubber:
    """Isolated base on lead-rubber bearings: Eq (36) with ``Q/(m + m_b)`` in place of ``mu g``.

    Parameters
    ----------
    T_b : float
        Isolation period of the second (post-yield) slope [s], > 0.
    Q_ratio : float
        Characteristic strength over the weight, ``Q / ((m + m_b) g)``, > 0.
    u_y : float
        Yield displacement [m] (a lead-rubber bearing's is of the order of 10-25 mm).
    gamma : float
        Mass ratio ``m / (m + m_b)``, 0 <= gamma < 1.
    n, beta, gamma_bw : float
        Bouc-Wen parameters of Eq (34).
    """

    T_b: float
    Q_ratio: float
    u_y: float
    gamma: float = DEFAULT_GAMMA
    n: float = DEFAULT_BW_N
    beta: float = DEFAULT_BW_BETA
    gamma_bw: float = DEFAULT_BW_GAMMA

    kind = KIND_BILINEAR
    n_states = 3

    def __post_init__(self):
        _check_period(self.T_b)
        _check(_finite(self.Q_ratio) and 0 < self.Q_ratio < 1,
               f"strength ratio Q = Q/((m+m_b) g) must lie strictly between 0 and 1, got {self.Q_ratio!r}")
        _check_yield(self.u_y)
        _check_gamma(self.gamma)
        _check_bouc_wen(self.n, self.beta, self.gamma_bw)
        _floats(self, ("T_b", "Q_ratio", "u_y", "gamma", "n", "beta", "gamma_bw"))

    @property
    def omega_b(self) -> float:
        return 2.0 * math.pi / self.T_b

    @property
    def strength_ratio(self) -> float:
        return self.Q_ratio

    @property
    def label(self) -> str:
        return (f"lrb:Tb={_spec_num(self.T_b)},Q={_spec_num(self.Q_ratio)},uy={_spec_num(self.u_y)},gamma={_spec_num(self.gamma)}"
                + _bouc_wen_label(self))


@dataclass(frozen=True)
class DoubleConcaveSliding:
    """Isolated base on double concave spherical sliding bearings (paper's Figure 10, Eqs 37-38).

    Two single concave surfaces in series joined by an articulated slider, modelled as a massless
    node where the two surface forces balance (:mod:`rockcli.kernels.bearings`). Surface i has the
    effective radius ``R_i_eff = R_i - h_i``, friction ``mu_i`` and a Bouc-Wen element of yield
    displacement ``u_y/2``, so that the bearing as a whole yields at ``u_y`` like a single concave one.
    With ``mu1 = mu2`` it is a single concave bearing of radius ``R1_eff + R2_eff`` (Eq 37); with
    ``mu1 != mu2`` its loop is trilinear, and Eq (38) gives the equivalent single concave friction.

    Parameters
    ----------
    R1_eff, R2_eff : float
        Effective radii of the two sliding surfaces [m], > 0.
    mu1, mu2 : float
        Their coefficients of friction, 0 < mu < 1.
    u_y : float
        Yield displacement of the bearing [m] (default 0.25 mm; each surface u_y/2).
    gamma : float
        Mass ratio ``m / (m + m_b)``.
    n, beta, gamma_bw : float
        Bouc-Wen parameters of Eq (34), the same for both surfaces.
    """

    R1_eff: float
    R2_eff: float
    mu1: float
    mu2: float
    u_y: float = DEFAULT_UY
    gamma: float = DEFAULT_GAMMA
    n: float = DEFAULT_BW_N
    beta: float = DEFAULT_BW_BETA
    gamma_bw: float = DEFAULT_BW_GAMMA

    kind = KIND_DCSS
    n_states = 4

    def __post_init__(self):
        for name in ("R1_eff", "R2_eff"):
            v = getattr(self, name)
            _check(_finite(v) and v > 0, f"effective radius {name[:2]} must be a positive length in m, got {v!r}")
            _check_period(2.0 * math.pi * math.sqrt(float(v) / G), f"the period of surface {name[:2]} alone")
        _check_period(2.0 * math.pi * math.sqrt((float(self.R1_eff) + float(self.R2_eff)) / G))
        _check_friction("mu1", self.mu1)
        _check_friction("mu2", self.mu2)
        _check_yield(self.u_y)
        _check_gamma(self.gamma)
        _check_bouc_wen(self.n, self.beta, self.gamma_bw)
        _floats(self, ("R1_eff", "R2_eff", "mu1", "mu2", "u_y", "gamma", "n", "beta", "gamma_bw"))

    @classmethod
    def from_period(cls, T_b: float, mu1: float, mu2: float, ratio: float = 1.0, **kwargs) -> "DoubleConcaveSliding":
        """The bearing of period ``T_b = 2 pi sqrt((R1_eff + R2_eff)/g)`` with ``R2_eff/R1_eff = ratio``."""
        _check_period(T_b)
        _check(_finite(ratio) and ratio > 0, f"radius ratio r = R2/R1 must be positive, got {ratio!r}")
        R_e = G * (float(T_b) / (2.0 * math.pi)) ** 2
        R1 = R_e / (1.0 + float(ratio))
        return cls(R1, R_e - R1, mu1, mu2, **kwargs)

    @property
    def R_e(self) -> float:
        """Radius of the equivalent single concave bearing, ``R1_eff + R2_eff`` (Eq 37) [m]."""
        return self.R1_eff + self.R2_eff

    @property
    def mu_e(self) -> float:
        """Equivalent friction of Eq (38), ``(mu1 R1_eff + mu2 R2_eff)/(R1_eff + R2_eff)``."""
        return (self.mu1 * self.R1_eff + self.mu2 * self.R2_eff) / self.R_e

    @property
    def mu(self) -> float:
        """The equivalent friction ``mu_e`` (Eq 38), the friction a table of bearings reports."""
        return self.mu_e

    @property
    def T_b(self) -> float:
        """Isolation period of the final slope, ``2 pi sqrt((R1_eff + R2_eff)/g)`` [s]."""
        return 2.0 * math.pi * math.sqrt(self.R_e / G)

    @property
    def omega_b(self) -> float:
        return math.sqrt(G / self.R_e)

    @property
    def label(self) -> str:
        return (f"dcss:R1={_spec_num(self.R1_eff)},R2={_spec_num(self.R2_eff)},mu1={_spec_num(self.mu1)},mu2={_spec_num(self.mu2)},"
                f"uy={_spec_num(self.u_y)},gamma={_spec_num(self.gamma)}" + _bouc_wen_label(self))


#: Foundations whose bearings are hysteretic (Bouc-Wen elements).
HYSTERETIC = (SingleConcaveSliding, LeadRubber, DoubleConcaveSliding)

Foundation = Rigid | LinearIsolation | SingleConcaveSliding | LeadRubber | DoubleConcaveSliding

_BW_KEYS = {"n": "n", "beta": "beta", "gammabw": "gamma_bw"}
_SPEC_KEYS = {
    "linear": {"tb": "T_b", "xi": "xi", "gamma": "gamma"},
    "scss": {"tb": "T_b", "mu": "mu", "uy": "u_y", "gamma": "gamma", **_BW_KEYS},
    "lrb": {"tb": "T_b", "q": "Q_ratio", "uy": "u_y", "gamma": "gamma", **_BW_KEYS},
    "dcss": {"r1": "R1_eff", "r2": "R2_eff", "tb": "T_b", "r": "ratio", "mu1": "mu1", "mu2": "mu2", "uy": "u_y",
             "gamma": "gamma", **_BW_KEYS},
}
_SPEC_EXAMPLES = ("'none', 'linear:Tb=2.5,xi=0.1,gamma=0.01', 'scss:Tb=3,mu=0.05[,uy=0.00025,gamma=0.01]', "
                  "'lrb:Tb=2.5,Q=0.06,uy=0.015' or 'dcss:R1=1.1,R2=1.1,mu1=0.03,mu2=0.07[,uy=..,gamma=..]'")
_REQUIRED = {
    "linear": (("T_b", "Tb=<period in s>"),),
    "scss": (("T_b", "Tb=<period in s>"), ("mu", "mu=<friction coefficient>")),
    "lrb": (("T_b", "Tb=<period in s>"), ("Q_ratio", "Q=<strength / weight>"), ("u_y", "uy=<yield displacement in m>")),
    "dcss": (("mu1", "mu1=<friction of surface 1>"), ("mu2", "mu2=<friction of surface 2>")),
}
_CLASSES = {"linear": LinearIsolation, "scss": SingleConcaveSliding, "lrb": LeadRubber}


def parse_isolation_spec(text: str):
    """Parse an isolation spec into a foundation.

    ``none``; ``linear:Tb=2.5[,xi=0.1,gamma=0.01]``; ``scss:Tb=3,mu=0.05[,uy=0.00025,gamma=0.01]``;
    ``lrb:Tb=2.5,Q=0.06,uy=0.015[,gamma=0.01]`` (``Q`` = strength / weight);
    ``dcss:R1=1.1,R2=1.1,mu1=0.03,mu2=0.07[,uy=0.00025,gamma=0.01]`` (effective radii ``R_i - h_i`` in m),
    or ``dcss:Tb=3,mu1=0.03,mu2=0.07[,r=<R2/R1, default 1>]``. The Bouc-Wen elements also take
    ``n``, ``beta``, ``gammabw``. Periods in s, lengths in m; defaults as in :mod:`rockcli.models`.
    Any bad spec raises :class:`RockcliInputError` with one sentence.
    """
    raw = str(text).strip()
    kind, _, rest = raw.partition(":")
    kind = kind.strip().lower()
    if kind in ("none", "rigid", "fixed") and not rest.strip():
        return Rigid()
    if kind not in _SPEC_KEYS:
        raise RockcliInputError(f"unknown isolation {kind!r} in {raw!r} (use {_SPEC_EXAMPLES})")
    from rockcli.inputs import parse_number, spec_items

    keys = _SPEC_KEYS[kind]
    values = {}
    for key, val, eq in spec_items(rest, f"isolation {raw!r}"):
        k = key.lower()
        if not eq or k not in keys:
            item = f"{key}={val}" if eq else key
            raise RockcliInputError(
                f"isolation {raw!r}: {item!r} is not one of {', '.join(k + '=...' for k in keys)}")
        values[keys[k]] = parse_number(val, f"isolation {raw!r}: {key}",
                                       bad=f"isolation {raw!r}: {key} must be a number, got {val!r}")
    if "beta" in values and "gamma_bw" not in values:  # A = 1: one of them fixes the other
        values["gamma_bw"] = 1.0 - values["beta"]
    elif "gamma_bw" in values and "beta" not in values:
        values["beta"] = 1.0 - values["gamma_bw"]
    for name, hint in _REQUIRED[kind]:
        if name not in values:
            raise RockcliInputError(f"isolation {raw!r} needs {hint}")
    by_radii = "R1_eff" in values or "R2_eff" in values
    by_period = "T_b" in values or "ratio" in values
    if kind == "dcss" and (by_radii == by_period or (by_radii and not ("R1_eff" in values and "R2_eff" in values))
                           or (by_period and "T_b" not in values)):
        raise RockcliInputError(f"isolation {raw!r} needs either R1=<m>,R2=<m> or Tb=<s>[,r=<R2/R1>]")
    try:
        if kind != "dcss":
            return _CLASSES[kind](**values)
        if by_period:
            T_b, ratio = values.pop("T_b"), values.pop("ratio", 1.0)
            return DoubleConcaveSliding.from_period(T_b, ratio=ratio, **values)
        return DoubleConcaveSliding(**values)
    except RockcliInputError as exc:
        raise RockcliInputError(f"isolation {raw!r}: {exc}") from None
