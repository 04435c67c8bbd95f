"""The ``n`` strongest distinct pulses of a record: the fit of :func:`~rockcli.pulses.fit.fit_pulse` and its
competitors (``rockcli fit-pulse --candidates``).

Where two pulses explain similar energy (a near tie), the largest wavelet coefficient picks one and hides
the other; the candidates are the other local maxima of the CWT, each refined exactly like the main fit
(:mod:`rockcli.pulses.fit`), with the duplicates of one pulse removed (:func:`same_pulse`).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.pulses.cwt import _cwt_grid, _grid_estimate
from rockcli.pulses.fit import DEFAULT_PERIODS, PulseFit, _prepare, _refine

__all__ = ["DUPLICATE_PERIOD_RATIO", "DUPLICATE_TIME_SHARE", "fit_pulse_candidates", "same_pulse"]

#: Two pulses are the same pulse when their centres are closer than this share of the longer period
#: (about where a Ricker's side lobes end) ...
DUPLICATE_TIME_SHARE = 0.75
#: ... and their periods differ by less than this factor (half an octave).
DUPLICATE_PERIOD_RATIO = math.sqrt(2.0)


def same_pulse(a: PulseFit, b: PulseFit) -> bool:
    """True when two fitted pulses overlap in time and period (see :func:`fit_pulse_candidates`)."""
    T_long, T_short = max(a.T_p_s, b.T_p_s), min(a.T_p_s, b.T_p_s)
    return abs(a.t0_s - b.t0_s) < DUPLICATE_TIME_SHARE * T_long and T_long / T_short < DUPLICATE_PERIOD_RATIO


def fit_pulse_candidates(record, n: int = 3, wavelet: str = "best", *, periods=DEFAULT_PERIODS,
                         scales_per_octave: int = 12) -> list[PulseFit]:
    """The ``n`` strongest distinct pulses of ``record``: the fit of :func:`fit_pulse` and its competitors.

    Where two pulses explain similar energy (a near tie), the largest wavelet coefficient picks one
    and hides the other; this lists both, so that one can see the alternative another fit (or a
    paper) picked.

    Parameters
    ----------
    record, wavelet, periods, scales_per_octave
        As :func:`fit_pulse` (``"best"``: both shapes compete).
    n : int
        How many pulses, >= 1.

    Returns
    -------
    list of PulseFit
        Sorted by explained energy fraction (largest first), at most ``n``; the first fit of
        :func:`fit_pulse` (same settings) is always among them (``alternative`` is None on all).

    Notes
    -----
    1. Candidates are the local maxima of ``|CWT|`` over period and time (each grid value at
       least as large as its 8 neighbours), for each shape; the ``4 n + 8`` largest of each shape
       are refined exactly like the main fit (parabolas on the grid, then least squares on the
       record's samples), each on its own: its ``energy_fraction`` is what that pulse alone
       explains (fractions of different pulses do not add up).
    2. De-duplication: the fit of :func:`fit_pulse` first, then the others by explained energy; a
       pulse is dropped when it overlaps one already kept in time *and* period (:func:`same_pulse`:
       centres closer than 3/4 of the longer period and periods within a factor sqrt 2) -- e.g. the
       antisymmetric description of the same symmetric pulse, or two maxima refined onto one pulse.
    """
    if int(n) != n or n < 1:
        raise RockcliInputError(f"the number of candidate pulses must be a whole number >= 1, got {n!r}")
    from scipy.ndimage import maximum_filter

    acc, dt, t_start, name, kinds, periods, spo = _prepare(record, wavelet, periods, scales_per_octave)
    per_shape = 4 * int(n) + 8
    mains, others = [], []
    for kind in kinds:
        T_grid, scales, coef, dtc = _cwt_grid(acc, dt, kind, periods, spo)
        mag = np.abs(coef)
        peaks = np.argwhere((mag == maximum_filter(mag, size=3, mode="nearest")) & (mag > 0))
        order = np.argsort(-mag[peaks[:, 0], peaks[:, 1]], kind="stable")[:per_shape]
        top = np.unravel_index(int(np.argmax(mag)), mag.shape)
        for k in order:
            i, j = (int(v) for v in peaks[k])
            est = _grid_estimate(kind, T_grid, scales, coef, mag, dtc, t_start, periods, i, j)
            fit = _refine(acc, dt, t_start, name, kind, periods, *est)
            (mains if (i, j) == tuple(int(v) for v in top) else others).append(fit)
    main = max(mains, key=lambda f: f.energy_fraction)  # what fit_pulse returns (without 'alternative')
    kept = [main]
    for f in sorted(mains + others, key=lambda f: f.energy_fraction, reverse=True):
        if len(kept) == n:
            break
        if f is main or any(same_pulse(f, k) for k in kept):
            continue
        kept.append(f)
    return sorted(kept, key=lambda f: f.energy_fraction, reverse=True)
