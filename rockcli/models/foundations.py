"""The foundations a block stands on: :class:`Rigid`, :class:`LinearIsolation` (viscoelastic
bearings), and the hysteretic bearings with Bouc-Wen elements: :class:`SingleConcaveSliding` and
:class:`LeadRubber` (bilinear, sharing :class:`_Bilinear`) and :class:`DoubleConcaveSliding`.

Each carries its kind code for :mod:`rockcli.kernels`, the number of states it adds and its spec
``label`` (which :func:`rockcli.models.parse_isolation_spec` reads back).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from rockcli.models.limits import (DEFAULT_BW_BETA, DEFAULT_BW_GAMMA, DEFAULT_BW_N, DEFAULT_GAMMA, DEFAULT_UY,
                                   DEFAULT_XI, KIND_BILINEAR, KIND_DCSS, KIND_LINEAR, KIND_RIGID, XI_MAX, _check,
                                   _check_fraction, _check_gamma, _check_hysteresis, _check_period, _finite, _num)
from rockcli.io.units import G


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
        _check_period(self.T_b)
        _check(_finite(self.xi) and float(self.xi) >= 0,
               lambda: f"isolation damping ratio xi must be >= 0, got {_num(self.xi)}")
        _check(float(self.xi) <= XI_MAX,
               lambda: f"isolation damping ratio xi = {_num(self.xi)} is above the supported {XI_MAX:g} (bearings have "
                       f"0.02-0.3; beyond {XI_MAX:g} times critical the dampers lock the base and the run needs "
                       f"~2 xi omega_b steps per second)")
        _check_gamma(self.gamma)
        for f in ("T_b", "xi", "gamma"):
            object.__setattr__(self, f, float(getattr(self, f)))

    @property
    def omega_b(self) -> float:
        return 2.0 * math.pi / self.T_b

    @property
    def label(self) -> str:
        return f"linear:Tb={_spec_num(self.T_b)},xi={_spec_num(self.xi)},gamma={_spec_num(self.gamma)}"


def _spec_num(x: float) -> str:
    """A number for a spec label: short, and read back exactly (``repr`` when ``:g`` would round)."""
    short = f"{x:g}"
    return short if float(short) == x else repr(x)


def _bouc_wen_label(f) -> str:
    if (f.n, f.beta, f.gamma_bw) == (DEFAULT_BW_N, DEFAULT_BW_BETA, DEFAULT_BW_GAMMA):
        return ""
    return f",n={_spec_num(f.n)},beta={_spec_num(f.beta)},gammabw={_spec_num(f.gamma_bw)}"


class _Bilinear:
    """What the two bilinear bearings share (:class:`SingleConcaveSliding`, :class:`LeadRubber`).

    A second slope of period ``T_b`` and one Bouc-Wen element of strength ``Q = strength_ratio
    (m + m_b) g`` and yield displacement ``u_y``: the checks, ``omega_b`` and the spec label. The
    two differ only in the name of the strength, set by each in :attr:`_strength`.
    """

    kind = KIND_BILINEAR
    n_states = 3
    #: (spec kind, the field holding Q/((m + m_b) g), its key in a spec, its words in messages)
    _strength = ("", "", "", "")

    def __post_init__(self):
        _, name, _, what = self._strength
        _check_period(self.T_b)
        _check_fraction(what, getattr(self, name))
        _check_hysteresis(self)

    @property
    def omega_b(self) -> float:
        return 2.0 * math.pi / self.T_b

    @property
    def strength_ratio(self) -> float:
        """``Q / ((m + m_b) g)``."""
        return getattr(self, self._strength[1])

    @property
    def label(self) -> str:
        kind, _, key, _ = self._strength
        return (f"{kind}:Tb={_spec_num(self.T_b)},{key}={_spec_num(self.strength_ratio)},uy={_spec_num(self.u_y)},"
                f"gamma={_spec_num(self.gamma)}" + _bouc_wen_label(self))


@dataclass(frozen=True)
class SingleConcaveSliding(_Bilinear):
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

    _strength = ("scss", "mu", "mu", "friction coefficient mu")

    @property
    def R_eff(self) -> float:
        """Effective radius of curvature ``g / omega_b^2`` [m]."""
        return G / self.omega_b ** 2


@dataclass(frozen=True)
class LeadRubber(_Bilinear):
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

    _strength = ("lrb", "Q_ratio", "Q", "strength ratio Q = Q/((m+m_b) g)")


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
            _check(_finite(v) and v > 0,
                   lambda: f"effective radius {name[:2]} must be a positive length in m, got {v!r}")
            _check_period(2.0 * math.pi * math.sqrt(float(v) / G), f"the period of surface {name[:2]} alone")
        _check_period(2.0 * math.pi * math.sqrt((float(self.R1_eff) + float(self.R2_eff)) / G))
        _check_fraction("friction coefficient mu1", self.mu1)
        _check_fraction("friction coefficient mu2", self.mu2)
        _check_hysteresis(self)

    @classmethod
    def from_period(cls, T_b: float, mu1: float, mu2: float, ratio: float = 1.0, **kwargs) -> "DoubleConcaveSliding":
        """The bearing of period ``T_b = 2 pi sqrt((R1_eff + R2_eff)/g)`` with ``R2_eff/R1_eff = ratio``."""
        _check_period(T_b)
        _check(_finite(ratio) and ratio > 0, lambda: f"radius ratio r = R2/R1 must be positive, got {ratio!r}")
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
