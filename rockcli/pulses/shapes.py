"""Idealised acceleration pulses: symmetric and antisymmetric Ricker wavelets, one-sine, one-cosine.

Vassiliou & Makris (2012) describe the coherent pulse of a near-source record by two numbers, the
acceleration amplitude ``a_p`` [m/s^2] and the pulse period ``T_p = 2 pi / omega_p`` [s]. This module
gives the four pulse shapes used by rockcli with their exact velocity and displacement, so that the
solver (which re-implements exactly these formulas in its compiled kernel) and the wavelet fitter
(:mod:`rockcli.pulses.fit`) share one definition.

With ``tau = t - t0`` (``t0`` is the centre of a Ricker and the start of a sine/cosine pulse):

``ricker-sym`` (Eq 5)
    ``a = a_p (1 - 2 pi^2 tau^2 / T_p^2) exp(-pi^2 tau^2 / T_p^2)``, truncated to ``t0 +- 3 T_p``.
``ricker-anti`` (Eq 6)
    ``x = 2 pi tau / (sqrt(3) T_p)``, ``a = (a_p / beta) (x^2 - 3) x exp(-x^2 / 2)``, truncated to
    ``t0 +- 3 T_p``; ``beta`` (:data:`RICKER_ANTI_BETA`, about 1.38) makes the largest value exactly
    ``a_p``, reached at ``x = -sqrt(3 - sqrt 6)`` (before ``t0``), followed by ``-a_p`` after ``t0``.
``sine``
    ``a = a_p sin(2 pi tau / T_p)`` for ``0 <= tau <= T_p``, else 0.
``cosine``
    ``a = a_p cos(2 pi tau / T_p)`` for ``0 <= tau <= T_p``, else 0.

``a_p`` is signed: a negative value is the same pulse with reversed polarity.
Velocity and displacement are exact integrals of the (truncated) acceleration with the ground at
rest before the pulse starts; after the pulse ends the velocity stays constant and the displacement
grows linearly (both are zero to within ``exp(-9 pi^2)`` for the Rickers; the one-sine pulse leaves a
permanent displacement ``a_p T_p^2 / (2 pi)``).

Fourier-peak relation
---------------------
A Ricker is the (negated) n-th derivative of a Gaussian ``exp(-tau^2 / (2 sigma^2))`` (n = 2 symmetric,
n = 3 antisymmetric). Its Fourier amplitude is proportional to ``omega^n exp(-omega^2 sigma^2 / 2)``,
largest at ``omega = sqrt(n) / sigma``, so the period that maximises the Fourier amplitude spectrum is
``2 pi sigma / sqrt(n)`` (:func:`gaussian_derivative_peak_period`). Eqs 5 and 6 choose
``sigma = T_p / (sqrt 2 pi)`` and ``sigma = sqrt 3 T_p / (2 pi)`` respectively, so that this period is
exactly ``T_p`` (the statement after Eqs 5 and 6 of the paper). See :meth:`RickerSymmetric.sigma`,
:meth:`RickerSymmetric.fourier_amplitude`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import ClassVar, Optional, Tuple

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number
from rockcli.io.units import G

__all__ = [
    "RICKER_ANTI_BETA",
    "RICKER_ANTI_X_PEAK",
    "RICKER_HALF_WIDTH",
    "PULSE_SHAPES",
    "Pulse",
    "RickerSymmetric",
    "RickerAntisymmetric",
    "OneSine",
    "OneCosine",
    "gaussian_derivative_peak_period",
    "T_P_RANGE_S",
    "A_P_MAX_G",
]

#: ``x`` where ``(x^2 - 3) x exp(-x^2/2)`` reaches its largest value: ``-sqrt(3 - sqrt 6)``
#: (the roots of the derivative satisfy ``x^4 - 6 x^2 + 3 = 0``; ``x^2 = 3 + sqrt 6`` gives the
#: smaller secondary lobes).
RICKER_ANTI_X_PEAK = -math.sqrt(3.0 - math.sqrt(6.0))

#: ``beta`` of Eq (6): ``max |(x^2 - 3) x exp(-x^2/2)| = sqrt(6) sqrt(3 - sqrt 6) exp(-(3 - sqrt 6)/2)``
#: (about 1.3801; the paper rounds it to 1.38).
RICKER_ANTI_BETA = math.sqrt(6.0) * math.sqrt(3.0 - math.sqrt(6.0)) * math.exp(-(3.0 - math.sqrt(6.0)) / 2.0)

#: Rickers are truncated at ``t0 +- RICKER_HALF_WIDTH * T_p`` (the acceleration there is below
#: ``1e-36 a_p``).
RICKER_HALF_WIDTH = 3.0


#: Supported pulse periods T_p [s]: from 1 ms (no accelerogram, sampled at >= 5 ms, carries a
#: shorter pulse) to 1000 s (longer than any earthquake's strong motion).
T_P_RANGE_S = (1e-3, 1e3)
#: Largest pulse amplitude |a_p| [g]: the strongest accelerations ever recorded are about 4 g, so
#: only a unit mistake (cm/s^2 read as g multiplies by 981) gets past 100 g.
A_P_MAX_G = 100.0


def gaussian_derivative_peak_period(order: int, sigma: float) -> float:
    """Period [s] that maximises the Fourier amplitude of the n-th derivative of a Gaussian.

    Parameters
    ----------
    order : int
        Derivative order ``n`` >= 1 (2 for the symmetric Ricker, 3 for the antisymmetric one).
    sigma : float
        Standard deviation [s] of the Gaussian ``exp(-t^2 / (2 sigma^2))``.

    Returns
    -------
    float
        ``2 pi sigma / sqrt(n)``: ``|F(omega)|`` is proportional to ``omega^n exp(-omega^2 sigma^2/2)``,
        whose maximum is at ``omega = sqrt(n) / sigma``.
    """
    if order < 1:
        raise ValueError("order must be >= 1")
    return 2.0 * math.pi * float(sigma) / math.sqrt(order)


def _check_param(name: str, value) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise RockcliInputError(f"pulse parameter {name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise RockcliInputError(f"pulse parameter {name} must be finite, got {format_number(v)}")
    return v


@dataclass(frozen=True)
class Pulse:
    """Base class of the pulses: amplitude ``a_p`` [m/s^2] (signed), period ``T_p`` [s], time ``t0`` [s].

    Subclasses define the acceleration on the pulse's own time ``tau = t - t0`` together with one
    antiderivative ``V`` and a second antiderivative ``D``; this class turns them into velocity and
    displacement that start from rest at the start of the support.
    """

    a_p: float
    T_p: float
    t0: Optional[float] = None

    shape: ClassVar[str] = ""
    #: support in units of T_p relative to t0
    _support_tau: ClassVar[Tuple[float, float]] = (0.0, 1.0)
    #: default t0 in units of T_p
    _default_t0: ClassVar[float] = 0.0

    def __post_init__(self):
        a_p = _check_param("a_p", self.a_p)
        T_p = _check_param("T_p", self.T_p)
        if T_p <= 0.0:
            raise RockcliInputError(f"pulse period T_p must be > 0 s, got {format_number(T_p)}")
        lo, hi = T_P_RANGE_S
        if not lo <= T_p <= hi:
            raise RockcliInputError(f"pulse period T_p = {format_number(T_p)} s lies outside the supported {lo:g} s "
                                    f"to {hi:g} s (no earthquake pulse is shorter or longer)")
        if abs(a_p) > A_P_MAX_G * G:
            raise RockcliInputError(f"pulse amplitude a_p = {format_number(a_p / G, derived=True)} g is beyond the "
                                    f"supported {A_P_MAX_G:g} g "
                                    f"(recorded peaks reach about 4 g; check the units: a_p is in g on the "
                                    f"command line, in m/s^2 in Python)")
        t0 = self._default_t0 * T_p if self.t0 is None else _check_param("t0", self.t0)
        object.__setattr__(self, "a_p", a_p)
        object.__setattr__(self, "T_p", T_p)
        object.__setattr__(self, "t0", t0)

    # --- to be provided by subclasses: functions of tau (array), valid inside the support ---------
    def _A(self, tau):  # pragma: no cover - abstract
        raise NotImplementedError

    def _V(self, tau):  # pragma: no cover - abstract
        raise NotImplementedError

    def _D(self, tau):  # pragma: no cover - abstract
        raise NotImplementedError

    # --- public API -------------------------------------------------------------------------------
    @property
    def omega_p(self) -> float:
        """Pulse circular frequency ``2 pi / T_p`` [rad/s]."""
        return 2.0 * math.pi / self.T_p

    @property
    def a_p_g(self) -> float:
        """Amplitude in g (signed)."""
        return self.a_p / G

    def support(self) -> Tuple[float, float]:
        """``(t_start, t_end)`` [s]: the acceleration is exactly 0 outside this closed interval."""
        lo, hi = self._support_tau
        return (self.t0 + lo * self.T_p, self.t0 + hi * self.T_p)

    def _tau_bounds(self):
        lo, hi = self._support_tau
        return lo * self.T_p, hi * self.T_p

    def acceleration(self, t):
        """Ground acceleration [m/s^2] at times ``t`` [s] (scalar or array)."""
        if isinstance(t, float):  # one time (a Python or numpy float): the same operations, without arrays
            tau = t - self.t0
            ts, te = self._tau_bounds()
            return float(self._A(np.float64(tau))) if ts <= tau <= te else 0.0
        t = np.asarray(t, dtype=float)
        tau = t - self.t0
        ts, te = self._tau_bounds()
        inside = (tau >= ts) & (tau <= te)
        out = np.where(inside, self._A(np.clip(tau, ts, te)), 0.0)
        return out if out.ndim else float(out)

    def velocity(self, t):
        """Ground velocity [m/s], zero before the pulse starts, constant after it ends."""
        t = np.asarray(t, dtype=float)
        ts, te = self._tau_bounds()
        tau = np.clip(t - self.t0, ts, te)
        out = self._V(tau) - self._V(np.float64(ts))
        return out if out.ndim else float(out)

    def displacement(self, t):
        """Ground displacement [m], zero before the pulse starts, linear in time after it ends."""
        t = np.asarray(t, dtype=float)
        ts, te = self._tau_bounds()
        tau_all = t - self.t0
        tau = np.clip(tau_all, ts, te)
        v_s = self._V(np.float64(ts))
        inside = self._D(tau) - self._D(np.float64(ts)) - v_s * (tau - ts)
        v_end = self._V(np.float64(te)) - v_s
        out = inside + v_end * np.maximum(tau_all - te, 0.0)
        return out if out.ndim else float(out)

    def sampled(self, dt: float, t_end: Optional[float] = None, *, name: Optional[str] = None):
        """The pulse as a :class:`~rockcli.records.record.Record` sampled every ``dt`` seconds.

        Samples run from ``min(0, support start)`` to ``t_end`` (default: the end of the support)
        inclusive; ``Record.t_start`` is the time of the first sample.
        """
        from rockcli.records.record import Record

        dt = float(dt)
        if not (math.isfinite(dt) and dt > 0.0):
            raise RockcliInputError(f"time step dt must be a positive number of seconds, got {dt!r}")
        s0, s1 = self.support()
        start = min(0.0, s0)
        stop = s1 if t_end is None else float(t_end)
        if not (math.isfinite(stop) and stop > start):
            raise RockcliInputError(f"t_end must be later than the first sample at {start:g} s, got {t_end!r}")
        n = int(math.floor((stop - start) / dt + 1e-9)) + 1
        t = start + dt * np.arange(n)
        label = name or f"{self.shape} ap={self.a_p_g:.4g}g Tp={self.T_p:.4g}s"
        meta = {"format": "pulse", "units": "m/s^2", "factor": 1.0, "pulse": self.spec()}
        return Record(acc=self.acceleration(t), dt=dt, name=label, t_start=start, meta=meta)

    def spec(self) -> str:
        """The pulse as a CLI spec string (``ap`` in g), readable by :func:`parse_pulse_spec`."""
        return f"{self.shape}:ap={self.a_p_g!r},Tp={self.T_p!r},t0={self.t0!r}"

    def scaled(self, k: float) -> "Pulse":
        """The same pulse with amplitude multiplied by ``k``."""
        return type(self)(self.a_p * float(k), self.T_p, self.t0)

    def shifted(self, dt: float) -> "Pulse":
        """The same pulse ``dt`` seconds later."""
        return type(self)(self.a_p, self.T_p, self.t0 + float(dt))


@dataclass(frozen=True)
class _Ricker(Pulse):
    """What the two Rickers share: the (negated) ``n``-th derivative of a Gaussian of standard
    deviation ``sigma``, truncated to ``t0 +- 3 T_p``, with default ``t0 = 3 T_p`` (the support
    starts at 0). Subclasses set ``_order`` (``n``), ``_beta`` (the amplitude divisor of Eq 6, 1 for
    Eq 5) and ``sigma``."""

    _support_tau: ClassVar[Tuple[float, float]] = (-RICKER_HALF_WIDTH, RICKER_HALF_WIDTH)
    _default_t0: ClassVar[float] = RICKER_HALF_WIDTH
    _order: ClassVar[int] = 0
    _beta: ClassVar[float] = 1.0

    def fourier_amplitude(self, omega):
        """``|F(omega)|`` [m/s] of the untruncated pulse, ``F = integral a(t) exp(-i omega t) dt``.

        ``sqrt(2 pi) (|a_p| / beta) sigma (omega sigma)^n exp(-(omega sigma)^2 / 2)`` (``n = 2``,
        ``beta = 1`` for the symmetric Ricker; ``n = 3``, ``beta`` = :data:`RICKER_ANTI_BETA` for the
        antisymmetric one), largest at ``omega = 2 pi / T_p``.
        """
        s = self.sigma
        w = np.asarray(omega, dtype=float) * s
        return math.sqrt(2.0 * math.pi) * abs(self.a_p) / self._beta * s * w**self._order * np.exp(-(w**2) / 2.0)


@dataclass(frozen=True)
class RickerSymmetric(_Ricker):
    """Symmetric Ricker ("Mexican hat") pulse, Eq (5): peak ``a_p`` at ``t0``, support ``t0 +- 3 T_p``.

    Default ``t0 = 3 T_p`` (the support starts at 0).
    """

    shape: ClassVar[str] = "ricker-sym"
    _order: ClassVar[int] = 2

    @property
    def _k(self) -> float:
        return (math.pi / self.T_p) ** 2

    @property
    def sigma(self) -> float:
        """Standard deviation [s] of the underlying Gaussian: ``T_p / (sqrt 2 pi)``."""
        return self.T_p / (math.sqrt(2.0) * math.pi)

    def _A(self, tau):
        k = self._k
        return self.a_p * (1.0 - 2.0 * k * tau**2) * np.exp(-k * tau**2)

    def _V(self, tau):
        return self.a_p * tau * np.exp(-self._k * tau**2)

    def _D(self, tau):
        k = self._k
        return -self.a_p * np.exp(-k * tau**2) / (2.0 * k)


@dataclass(frozen=True)
class RickerAntisymmetric(_Ricker):
    """Antisymmetric Ricker pulse, Eq (6): ``+a_p`` before ``t0``, ``-a_p`` after, support ``t0 +- 3 T_p``.

    Default ``t0 = 3 T_p`` (the support starts at 0).
    """

    shape: ClassVar[str] = "ricker-anti"
    _order: ClassVar[int] = 3
    _beta: ClassVar[float] = RICKER_ANTI_BETA

    @property
    def _c(self) -> float:
        return 2.0 * math.pi / (math.sqrt(3.0) * self.T_p)

    @property
    def sigma(self) -> float:
        """Standard deviation [s] of the underlying Gaussian: ``sqrt 3 T_p / (2 pi)``."""
        return 1.0 / self._c

    @property
    def t_peak(self) -> float:
        """Time [s] of the positive peak ``+a_p`` (for ``a_p > 0``): ``t0 + x_peak / c``, before t0."""
        return self.t0 + RICKER_ANTI_X_PEAK / self._c

    def _A(self, tau):
        x = self._c * tau
        return (self.a_p / RICKER_ANTI_BETA) * (x**2 - 3.0) * x * np.exp(-(x**2) / 2.0)

    def _V(self, tau):
        c = self._c
        x = c * tau
        return -(self.a_p / (RICKER_ANTI_BETA * c)) * (x**2 - 1.0) * np.exp(-(x**2) / 2.0)

    def _D(self, tau):
        c = self._c
        x = c * tau
        return (self.a_p / (RICKER_ANTI_BETA * c**2)) * x * np.exp(-(x**2) / 2.0)


@dataclass(frozen=True)
class OneSine(Pulse):
    """One full cycle of a sine, ``a_p sin(omega_p (t - t0))`` for ``t0 <= t <= t0 + T_p``; default t0 = 0."""

    shape: ClassVar[str] = "sine"

    def _A(self, tau):
        return self.a_p * np.sin(self.omega_p * tau)

    def _V(self, tau):
        w = self.omega_p
        return -self.a_p * np.cos(w * tau) / w

    def _D(self, tau):
        w = self.omega_p
        return -self.a_p * np.sin(w * tau) / w**2


@dataclass(frozen=True)
class OneCosine(Pulse):
    """One full cycle of a cosine, ``a_p cos(omega_p (t - t0))`` for ``t0 <= t <= t0 + T_p``; default t0 = 0."""

    shape: ClassVar[str] = "cosine"

    def _A(self, tau):
        return self.a_p * np.cos(self.omega_p * tau)

    def _V(self, tau):
        w = self.omega_p
        return self.a_p * np.sin(w * tau) / w

    def _D(self, tau):
        w = self.omega_p
        return -self.a_p * np.cos(w * tau) / w**2


#: shape name -> class
PULSE_SHAPES = {
    "ricker-sym": RickerSymmetric,
    "ricker-anti": RickerAntisymmetric,
    "sine": OneSine,
    "cosine": OneCosine,
}
