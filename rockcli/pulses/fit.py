"""Fit the dominant acceleration pulse of a record with a symmetric or antisymmetric Ricker wavelet.

The method is that of Vassiliou & Makris (2011, BSSA), reference [22] of the 2012 paper: the
continuous wavelet transform (CWT) of the acceleration record with the symmetric Ricker (PyWavelets
``mexh``) and antisymmetric Ricker (PyWavelets ``gaus3``) wavelets; the scale and position of the
largest coefficient give the pulse, which is then refined off the grid by least squares.

Criterion
---------
For unit-energy wavelets ``psi_{s,b}`` the single wavelet ``c psi_{s,b}`` closest to the record ``x``
in the least-squares sense has ``c = <x, psi_{s,b}>`` and leaves the residual energy
``||x||^2 - <x, psi_{s,b}>^2``; so the best scale and position are those of the largest ``|CWT|``
(PyWavelets scales its wavelets by ``1/sqrt(s)``, which makes them unit-energy). The fitter

1. computes the CWT with ``pywt.cwt(..., method="fft")`` on a log-spaced grid of periods
   (``scales_per_octave`` per octave, default 12) within ``periods``, on a decimated copy when the
   record is sampled finer than ``T_min / 10`` (:mod:`rockcli.pulses.cwt`);
2. takes the largest ``|coefficient|``, refines its period and position with parabolas through the
   neighbouring grid values, and converts the coefficient to an amplitude (scale to period and
   normalisation: :mod:`rockcli.pulses.cwt`);
3. refines ``(T_p, t0)`` off the grid by maximising the explained energy of the sampled pulse itself,
   ``<x, p>^2 / <p, p>`` (Nelder-Mead from step 2; ``a_p = <x, p> / <p, p>`` in closed form), with
   ``T_p`` kept inside ``periods``.

``wavelet="best"`` fits both shapes and keeps the one that explains the larger fraction of the
record's energy (the smaller least-squares residual; both shapes have the same three parameters).
:mod:`rockcli.pulses.candidates` lists the competitors of the fit (other maxima of the CWT).

Energy fraction
---------------
``1 - sum (x - p)^2 / sum x^2`` over the record's samples, with ``p`` the fitted pulse: the fraction of
the record's "energy" ``integral a^2 dt`` (proportional to the Arias intensity) that the pulse explains.
At the least-squares optimum this equals ``sum p^2 / sum x^2``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Optional, Tuple, Union

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number
from rockcli.pulses.cwt import (WAVELETS, _cwt_grid, _grid_estimate, _grid_shape, coefficient_to_amplitude,
                                period_to_scale, scale_to_period)
from rockcli.pulses.shapes import RICKER_HALF_WIDTH, T_P_RANGE_S, RickerAntisymmetric, RickerSymmetric
from rockcli.io.units import G

__all__ = [
    "DEFAULT_PERIODS",
    "WAVELETS",
    "PulseFit",
    "fit_pulse",
    "parse_periods",
    "scale_to_period",
    "period_to_scale",
    "coefficient_to_amplitude",
]

#: Default range of pulse periods searched [s]. 0.1 s is the shortest period at which a rocking
#: block of practical size responds to a pulse at all; 6 s covers the long near-fault pulses
#: (Chi-Chi, Kobe) while staying clear of the baseline drift of processed records.
DEFAULT_PERIODS = (0.1, 6.0)

#: Shortest period the fitter accepts, in samples of the record (a Ricker needs a few samples).
_MIN_SAMPLES_PER_PERIOD = 4.0

Ricker = Union[RickerSymmetric, RickerAntisymmetric]


@dataclass(frozen=True)
class PulseFit:
    """The dominant pulse of a record.

    Attributes
    ----------
    pulse : RickerSymmetric or RickerAntisymmetric
        The fitted pulse in SI units; ``pulse.t0`` is in the record's time (includes ``t_start``).
    wavelet : str
        ``"symmetric"`` or ``"antisymmetric"``.
    a_p_g : float
        Signed amplitude [g] (negative: the pulse of Eq 5/6 with reversed polarity).
    T_p_s : float
        Pulse period [s].
    t0_s : float
        Pulse centre [s] in the record's time.
    energy_fraction : float
        ``1 - sum (x - p)^2 / sum x^2``: fraction of the record's energy explained by the pulse.
    record_name : str
        ``Record.name``.
    periods : (float, float)
        Period range actually searched [s] (the lower end is raised to 4 samples, the upper end
        lowered to the record's duration, if needed).
    at_period_bound : bool
        True when the fitted period sits on an end of ``periods`` (widen the range to check).
    cwt_a_p_g, cwt_T_p_s, cwt_t0_s : float
        The estimate from the CWT grid alone (coefficient normalisation + parabolic refinement),
        before the least-squares refinement.
    alternative : PulseFit or None
        With ``wavelet="best"``, the fit of the other shape (for comparison).
    """

    pulse: Ricker
    wavelet: str
    a_p_g: float
    T_p_s: float
    t0_s: float
    energy_fraction: float
    record_name: str
    periods: Tuple[float, float]
    at_period_bound: bool
    cwt_a_p_g: float
    cwt_T_p_s: float
    cwt_t0_s: float
    alternative: Optional["PulseFit"] = field(default=None, repr=False, compare=False)

    @property
    def shape(self) -> str:
        """Pulse shape name (``ricker-sym`` or ``ricker-anti``)."""
        return self.pulse.shape

    def as_row(self) -> dict:
        """The fit as a flat dict with unit-labelled keys (for tables, CSV, JSON)."""
        return {
            "record": self.record_name,
            "wavelet": self.wavelet,
            "pulse_shape": self.pulse.shape,
            "a_p_g": self.a_p_g,
            "T_p_s": self.T_p_s,
            "t0_s": self.t0_s,
            "energy_fraction": self.energy_fraction,
            "at_period_bound": self.at_period_bound,
        }


def parse_periods(text: str) -> Tuple[float, float]:
    """Parse a period range ``"MIN:MAX"`` in seconds (e.g. ``"0.1:6"``) into a validated tuple."""
    parts = str(text).split(":")
    if len(parts) != 2:
        raise RockcliInputError(f"--periods {text!r} must be MIN:MAX in seconds, e.g. 0.1:6")
    from rockcli.io.inputs import parse_number

    bad = f"--periods {text!r} must be two numbers MIN:MAX in seconds, e.g. 0.1:6"
    if any(p.strip().lower().lstrip("+-") in ("nan", "inf", "infinity") for p in parts):
        raise RockcliInputError(f"--periods {text!r} must satisfy 0 < min < max (seconds) with finite ends")
    lo, hi = (parse_number(p, f"--periods {text!r}: {name}", bad=bad) for p, name in zip(parts, ("MIN", "MAX")))
    return _check_periods((lo, hi), what=f"--periods {text!r}")


def _check_periods(periods, what="periods") -> Tuple[float, float]:
    try:
        lo, hi = (float(v) for v in periods)
    except (TypeError, ValueError):
        raise RockcliInputError(f"{what} must be a pair (min, max) of periods in seconds") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo < hi):
        raise RockcliInputError(f"{what} must satisfy 0 < min < max (seconds), got {format_number(lo)}:{format_number(hi)}")
    return lo, hi


def _check_record(record):
    acc = np.asarray(getattr(record, "acc", None), dtype=float)
    dt = float(getattr(record, "dt", float("nan")))
    name = getattr(record, "name", "record")
    if acc.ndim != 1 or acc.size < 8:
        raise RockcliInputError(f"record {name!r} has too few samples to fit a pulse ({acc.size})")
    if not (math.isfinite(dt) and dt > 0.0):
        raise RockcliInputError(f"record {name!r} has an invalid time step dt={dt!r}")
    if not np.all(np.isfinite(acc)):
        raise RockcliInputError(f"record {name!r} contains non-finite acceleration samples")
    if not np.any(acc != 0.0):
        raise RockcliInputError(f"record {name!r} is all zeros: there is no pulse to fit")
    return acc, dt


#: Largest coarse CWT the fitter computes (periods x samples, float64: 240 MB).
_MAX_CWT_COEFFICIENTS = 30_000_000


def _effective_periods(lo, hi, acc, dt, name, scales_per_octave):
    """The period range searched: ``lo`` raised to 4 time steps (and 1 ms), ``hi`` lowered to the
    record's duration (a longer pulse cannot be fitted: its lobes would lie outside the record; and
    the CWT of ever longer periods grows without bound, ``--periods 0.1:1e6`` ate GBs) and to 1000 s.

    Raises one sentence when nothing is left to search or the CWT would be too large.
    """
    duration = (acc.size - 1) * dt
    lo_eff = max(lo, _MIN_SAMPLES_PER_PERIOD * dt, T_P_RANGE_S[0])
    hi_eff = min(hi, duration, T_P_RANGE_S[1])
    if lo_eff >= duration:
        raise RockcliInputError(
            f"record {name!r} lasts {duration:g} s, not longer than the shortest period searched {lo_eff:g} s: "
            f"a pulse longer than the record cannot be fitted (lower the periods)")
    if hi_eff <= lo_eff * 1.01:
        if lo_eff > lo:
            raise RockcliInputError(
                f"record {name!r}: the period range {lo:g}:{hi:g} s is too short for its time step {dt:g} s "
                f"(periods must be at least {lo_eff:g} s)")
        raise RockcliInputError(
            f"record {name!r}: the period range {lo:g}:{hi:g} s leaves nothing to search (periods above "
            f"{hi_eff:g} s, the record's duration or 1000 s, cannot be fitted)")
    q, n_per = _grid_shape(lo_eff, hi_eff, dt, scales_per_octave)
    size = n_per * int(math.ceil(acc.size / q))
    if size > _MAX_CWT_COEFFICIENTS:
        raise RockcliInputError(
            f"record {name!r}: the wavelet transform over {lo_eff:g}:{hi_eff:g} s would hold {size:.3g} "
            f"coefficients, more than the {_MAX_CWT_COEFFICIENTS:.0e} allowed: narrow the periods or raise "
            f"their lower end")
    return lo_eff, hi_eff


class _Projector:
    """Least-squares projection of the record on a unit-peak pulse of given (T_p, t0)."""

    def __init__(self, acc, dt, t_start, cls):
        self.acc = acc
        self.dt = dt
        self.t_start = t_start
        self.cls = cls
        self.n = acc.size

    def window(self, T_p, t0):
        h = RICKER_HALF_WIDTH * T_p
        i0 = max(int(math.ceil((t0 - h - self.t_start) / self.dt)), 0)
        i1 = min(int(math.floor((t0 + h - self.t_start) / self.dt)) + 1, self.n)
        return i0, i1

    def unit_pulse(self, T_p, t0, i0, i1):
        t = self.t_start + self.dt * np.arange(i0, i1)
        return self.cls(1.0, T_p, t0).acceleration(t)

    def project(self, T_p, t0):
        """``(a_p, explained)`` with ``explained = <x,p>^2/<p,p>`` (0 if the pulse misses the record)."""
        i0, i1 = self.window(T_p, t0)
        if i1 - i0 < 2:
            return 0.0, 0.0
        p = self.unit_pulse(T_p, t0, i0, i1)
        pp = float(p @ p)
        if pp <= 0.0:
            return 0.0, 0.0
        xp = float(self.acc[i0:i1] @ p)
        return xp / pp, xp * xp / pp


def _refine(acc, dt, t_start, name, kind, periods, T_cwt, t0_cwt, a_cwt, step):
    """Step 3: least-squares refinement of (T_p, t0) on the original samples -> PulseFit."""
    from scipy.optimize import minimize

    w = WAVELETS[kind]
    lo, hi = periods
    proj = _Projector(acc, dt, t_start, w.pulse_cls)
    log_lo, log_hi = math.log(lo), math.log(hi)

    def negative_explained(v):
        T = math.exp(min(max(v[0], log_lo), log_hi))
        return -proj.project(T, v[1])[1]

    x0 = np.array([math.log(T_cwt), t0_cwt])
    simplex = np.array([x0, x0 + [step, 0.0], x0 + [0.0, max(0.05 * T_cwt, dt)]])
    res = minimize(
        negative_explained, x0, method="Nelder-Mead",
        options={"initial_simplex": simplex, "xatol": 1e-7, "fatol": 1e-12 * float(acc @ acc), "maxiter": 400},
    )
    v = res.x if res.fun <= negative_explained(x0) else x0
    T_p = math.exp(min(max(v[0], log_lo), log_hi))
    t0 = float(v[1])
    a_p, _ = proj.project(T_p, t0)

    pulse = w.pulse_cls(a_p, T_p, t0)
    i0, i1 = proj.window(T_p, t0)
    p = np.zeros_like(acc)
    p[i0:i1] = pulse.acceleration(t_start + dt * np.arange(i0, i1))
    energy = float(acc @ acc)
    resid = acc - p
    frac = 1.0 - float(resid @ resid) / energy
    at_bound = T_p <= lo * (1.0 + 1e-6) or T_p >= hi * (1.0 - 1e-6)
    return PulseFit(
        pulse=pulse, wavelet=kind, a_p_g=a_p / G, T_p_s=T_p, t0_s=t0, energy_fraction=frac,
        record_name=name, periods=(lo, hi), at_period_bound=bool(at_bound),
        cwt_a_p_g=a_cwt / G, cwt_T_p_s=T_cwt, cwt_t0_s=float(t0_cwt),
    )


def _fit_one(acc, dt, t_start, name, kind, periods, scales_per_octave):
    T_grid, scales, coef, dtc = _cwt_grid(acc, dt, kind, periods, scales_per_octave)
    mag = np.abs(coef)
    i, j = np.unravel_index(int(np.argmax(mag)), mag.shape)
    est = _grid_estimate(kind, T_grid, scales, coef, mag, dtc, t_start, periods, i, j)
    return _refine(acc, dt, t_start, name, kind, periods, *est)


def fit_pulse(record, wavelet: str = "best", *, periods=DEFAULT_PERIODS, scales_per_octave: int = 12) -> PulseFit:
    """Fit the dominant acceleration pulse of ``record`` with a Ricker wavelet.

    Parameters
    ----------
    record : Record
        Ground acceleration [m/s^2] sampled every ``record.dt`` seconds from ``record.t_start``.
    wavelet : {"best", "symmetric", "antisymmetric"}
        Pulse shape: symmetric Ricker (Eq 5, PyWavelets ``mexh``), antisymmetric Ricker (Eq 6,
        ``gaus3``), or ``"best"``: the one that explains the larger fraction of the record's energy.
    periods : (float, float)
        Range of pulse periods searched [s], default :data:`DEFAULT_PERIODS` (0.1, 6.0). The lower
        end is raised to 4 time steps when the record is too coarse for it; the upper end is lowered
        to the record's duration (``PulseFit.periods`` is the range searched).
    scales_per_octave : int
        Density of the coarse CWT grid (the result is refined off the grid).

    Returns
    -------
    PulseFit

    Raises
    ------
    RockcliInputError
        Unknown wavelet, invalid period range, or a record with too few, non-finite or all-zero
        samples.

    Notes
    -----
    The criterion, normalisation and energy fraction are described in the module docstring. The
    fit is linear in the record: scaling the record by ``k`` scales ``a_p`` by ``k`` (a negative
    ``k`` flips its sign) and leaves ``T_p`` and ``t0`` unchanged; shifting ``t_start`` shifts ``t0``.

    Examples
    --------
    >>> from rockcli.pulses import RickerSymmetric
    >>> rec = RickerSymmetric(0.3 * 9.80665, 0.8, 4.0).sampled(0.01, 10.0)
    >>> fit = fit_pulse(rec, "symmetric")
    >>> round(fit.a_p_g, 4), round(fit.T_p_s, 4), round(fit.t0_s, 4)
    (0.3, 0.8, 4.0)
    """
    acc, dt, t_start, name, kinds, periods, spo = _prepare(record, wavelet, periods, scales_per_octave)
    fits = [_fit_one(acc, dt, t_start, name, k, periods, spo) for k in kinds]
    if len(fits) == 1:
        return fits[0]
    best, other = sorted(fits, key=lambda f: f.energy_fraction, reverse=True)
    return PulseFit(**{**best.__dict__, "alternative": other})


def _prepare(record, wavelet, periods, scales_per_octave):
    """Validated inputs of a fit: (acc, dt, t_start, name, wavelet kinds, effective periods, scales per octave)."""
    key = str(wavelet).strip().lower()
    if key not in ("best", *WAVELETS):
        raise RockcliInputError(f"unknown wavelet {wavelet!r} (expected symmetric, antisymmetric or best)")
    lo, hi = _check_periods(periods)
    acc, dt = _check_record(record)
    name = getattr(record, "name", "record")
    if int(scales_per_octave) < 2:
        raise RockcliInputError("scales_per_octave must be at least 2")
    lo_eff, hi_eff = _effective_periods(lo, hi, acc, dt, name, int(scales_per_octave))
    t_start = float(getattr(record, "t_start", 0.0))
    kinds = list(WAVELETS) if key == "best" else [key]
    return acc, dt, t_start, name, kinds, (lo_eff, hi_eff), int(scales_per_octave)
