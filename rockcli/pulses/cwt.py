"""The wavelet side of the pulse fit: Ricker wavelets of PyWavelets, the coarse CWT grid and its peak.

Steps 1 and 2 of :mod:`rockcli.pulses.fit`: the continuous wavelet transform (CWT) of the record on a
log-spaced grid of periods, with the symmetric Ricker (PyWavelets ``mexh``) or the antisymmetric Ricker
(``gaus3``); a grid point refined with parabolas through its neighbours, and its coefficient turned
into a pulse amplitude. When the record is sampled finer than ``T_min / 10`` the CWT is taken of a copy
decimated by an integer factor to about ``T_min / 10`` per sample after an ideal FFT low-pass (for speed
only: the least-squares refinement of the fit uses the original samples, and the Ricker spectra are below
1e-5 of their peak at that Nyquist frequency).

Scale to period
---------------
PyWavelets' ``mexh`` is ``psi(x) = 2 / (sqrt 3 pi^(1/4)) (1 - x^2) exp(-x^2/2)`` and ``gaus3`` is
``psi(x) = C (8 x^3 - 12 x) exp(-x^2)`` with ``C = (sqrt 2 / (15 sqrt pi))^(1/2)`` (the third derivative
of ``exp(-x^2)``, negated), both with unit L2 norm; ``x = (n - b) / s`` with ``s`` in samples. Matching
Eqs (5) and (6) gives exactly ``T_p = sqrt 2 pi s dt`` (mexh) and ``T_p = 2 pi s dt / sqrt 6`` (gaus3),
which is also the period of the Fourier-amplitude peak of the scaled wavelet. ``pywt.central_frequency``
(0.25 and 0.4, i.e. periods ``4 s dt`` and ``2.5 s dt``) is estimated from a quantised FFT of the sampled
wavelet and is not used.

Normalisation
-------------
The CWT coefficient is ``W(s, b) ~= s^(-1/2) sum_n x[n] psi((n - b)/s)``. For ``x = a_p psi(...)/psi_max``
at the same scale, ``W = a_p sqrt(s) / psi_max`` (since ``sum_n psi(n/s)^2 ~= s``), so
``a_p = W psi_max / sqrt(s)``, with ``psi_max = 2 / (sqrt 3 pi^(1/4))`` (mexh) and
``psi_max = 2 sqrt 2 beta C`` (gaus3; ``beta`` of Eq 6). Both wavelets have the sign of Eqs (5)-(6), so
the sign of ``W`` is the sign of ``a_p``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rockcli.pulses.shapes import RICKER_ANTI_BETA, RickerAntisymmetric, RickerSymmetric

__all__ = ["WAVELETS", "scale_to_period", "period_to_scale", "coefficient_to_amplitude"]

#: Samples per shortest period for the coarse CWT grid (the record is resampled to at least this
#: when it is sampled finer; the least-squares refinement always uses the original samples).
_COARSE_SAMPLES_PER_PERIOD = 10.0

_MEXH_PSI_MAX = 2.0 / (math.sqrt(3.0) * math.pi**0.25)
_GAUS3_C = math.sqrt(math.sqrt(2.0) / (15.0 * math.sqrt(math.pi)))
_GAUS3_PSI_MAX = 2.0 * math.sqrt(2.0) * RICKER_ANTI_BETA * _GAUS3_C


@dataclass(frozen=True)
class _Wavelet:
    name: str  # rockcli name
    pywt_name: str
    pulse_cls: type
    period_per_scale: float  # T_p = period_per_scale * s * dt
    psi_max: float


#: rockcli wavelet name -> its PyWavelets wavelet, pulse class and constants
WAVELETS = {
    "symmetric": _Wavelet("symmetric", "mexh", RickerSymmetric, math.sqrt(2.0) * math.pi, _MEXH_PSI_MAX),
    "antisymmetric": _Wavelet("antisymmetric", "gaus3", RickerAntisymmetric, 2.0 * math.pi / math.sqrt(6.0),
                              _GAUS3_PSI_MAX),
}


def scale_to_period(wavelet: str, scale, dt: float):
    """Pulse period ``T_p`` [s] of the PyWavelets scale ``scale`` (in samples of step ``dt``)."""
    return WAVELETS[wavelet].period_per_scale * np.asarray(scale, dtype=float) * dt


def period_to_scale(wavelet: str, T_p, dt: float):
    """PyWavelets scale (in samples of step ``dt``) whose wavelet is the Ricker of period ``T_p``."""
    return np.asarray(T_p, dtype=float) / (WAVELETS[wavelet].period_per_scale * dt)


def coefficient_to_amplitude(wavelet: str, coefficient, scale):
    """Pulse amplitude (in the record's units) of a ``pywt.cwt`` coefficient at ``scale``: ``W psi_max / sqrt(s)``."""
    return np.asarray(coefficient, dtype=float) * WAVELETS[wavelet].psi_max / np.sqrt(np.asarray(scale, dtype=float))


def _grid_shape(lo, hi, dt, scales_per_octave):
    """``(q, n_per)`` of the coarse CWT over periods ``lo..hi`` [s] of a record sampled every ``dt``:
    the record is decimated by ``q`` (about ``lo / 10`` per sample), and ``n_per`` log-spaced periods
    (``scales_per_octave`` per octave, at least 3) are transformed."""
    q = max(int(math.floor(lo / (_COARSE_SAMPLES_PER_PERIOD * dt))), 1)
    n_per = max(int(math.ceil(math.log2(hi / lo) * scales_per_octave)) + 1, 3)
    return q, n_per


def _parabola_offset(y0, y1, y2):
    """Vertex offset in [-0.5, 0.5] of the parabola through (-1, y0), (0, y1), (1, y2)."""
    den = y0 - 2.0 * y1 + y2
    if den >= 0.0:  # not a maximum
        return 0.0
    return float(np.clip(0.5 * (y0 - y2) / den, -0.5, 0.5))


def _decimate(x, q):
    """Every ``q``-th sample of ``x`` after an ideal (FFT) low-pass at the new Nyquist frequency.

    Output sample ``k`` is at the time of input sample ``k q``; the record is zero-padded by a
    quarter of its length so that the filter does not wrap one end onto the other.
    """
    n = x.size
    m = int(math.ceil(1.25 * n / q))
    spec = np.fft.rfft(x, m * q)[: m // 2 + 1]
    return np.fft.irfft(spec, m)[: int(math.ceil(n / q))] / q


def _cwt_grid(acc, dt, kind, periods, scales_per_octave):
    """Step 1: the CWT on the log-spaced period grid -> (T_grid, scales, coef, dtc)."""
    import pywt

    w = WAVELETS[kind]
    lo, hi = periods
    # coarse CWT grid, on a low-passed, decimated copy when the record is sampled much finer
    q, n_per = _grid_shape(lo, hi, dt, scales_per_octave)
    xc = _decimate(acc, q) if q > 1 else acc
    dtc = dt * q
    T_grid = np.geomspace(lo, hi, n_per)
    scales = period_to_scale(kind, T_grid, dtc)
    coef, _ = pywt.cwt(xc, scales, w.pywt_name, method="fft")
    return T_grid, scales, coef, dtc


def _grid_estimate(kind, T_grid, scales, coef, mag, dtc, t_start, periods, i, j):
    """Step 2 at grid point (i, j): parabolic refinement in log(period) and position; amplitude."""
    lo, hi = periods
    n_per, n_t = mag.shape
    di = _parabola_offset(mag[i - 1, j], mag[i, j], mag[i + 1, j]) if 0 < i < n_per - 1 else 0.0
    dj = _parabola_offset(mag[i, j - 1], mag[i, j], mag[i, j + 1]) if 0 < j < n_t - 1 else 0.0
    step = math.log(T_grid[1] / T_grid[0])
    T_cwt = float(np.clip(T_grid[i] * math.exp(di * step), lo, hi))
    t0_cwt = t_start + (j + dj) * dtc
    a_cwt = float(coefficient_to_amplitude(kind, coef[i, j], scales[i]))
    return T_cwt, float(t0_cwt), a_cwt, step
