"""Idealised acceleration pulses and the wavelet fit of a record's dominant pulse.

A pulse is two numbers (Vassiliou & Makris 2012): amplitude ``a_p`` [m/s^2] and period ``T_p`` [s],
with a shape and a time ``t0``. Pure numpy (the fit imports PyWavelets and SciPy when it runs). Read
it in this order:

:mod:`rockcli.pulses.shapes`
    The four shapes with exact velocity and displacement: :class:`RickerSymmetric` (Eq 5),
    :class:`RickerAntisymmetric` (Eq 6), :class:`OneSine`, :class:`OneCosine`, on the base
    :class:`Pulse`; the limits ``T_P_RANGE_S`` and ``A_P_MAX_G``; the Fourier-peak relation.
:mod:`rockcli.pulses.spec`
    Pulses by name: :func:`make_pulse` (SI units) and :func:`parse_pulse_spec`, the command line's
    ``SHAPE:ap=<g>,Tp=<s>[,t0=<s>]``.
:mod:`rockcli.pulses.cwt`
    The wavelet side of the fit: PyWavelets' ``mexh``/``gaus3`` as the two Rickers (scale <-> period,
    coefficient -> amplitude, :data:`WAVELETS`), the coarse CWT grid and the parabolic refinement of
    its peak.
:mod:`rockcli.pulses.fit`
    :func:`fit_pulse`: the dominant pulse of a record (CWT peak, then least squares on the samples)
    -> :class:`PulseFit`; :func:`parse_periods`.
:mod:`rockcli.pulses.candidates`
    :func:`fit_pulse_candidates`: the ``n`` strongest distinct pulses (the fit and its competitors).

Every public name is importable from ``rockcli.pulses``; ``rockcli.pulses_fit`` (the fitter's old
home) re-exports the fitter's names.
"""

from rockcli.pulses.candidates import DUPLICATE_PERIOD_RATIO, DUPLICATE_TIME_SHARE, fit_pulse_candidates, same_pulse
from rockcli.pulses.cwt import WAVELETS, coefficient_to_amplitude, period_to_scale, scale_to_period
from rockcli.pulses.fit import DEFAULT_PERIODS, PulseFit, fit_pulse, parse_periods
from rockcli.pulses.shapes import (A_P_MAX_G, PULSE_SHAPES, RICKER_ANTI_BETA, RICKER_ANTI_X_PEAK, RICKER_HALF_WIDTH,
                                   T_P_RANGE_S, OneCosine, OneSine, Pulse, RickerAntisymmetric, RickerSymmetric,
                                   gaussian_derivative_peak_period)
from rockcli.pulses.spec import PulseLike, make_pulse, parse_pulse_spec

__all__ = ["A_P_MAX_G", "DEFAULT_PERIODS", "DUPLICATE_PERIOD_RATIO", "DUPLICATE_TIME_SHARE", "PULSE_SHAPES",
           "RICKER_ANTI_BETA", "RICKER_ANTI_X_PEAK", "RICKER_HALF_WIDTH", "T_P_RANGE_S", "WAVELETS", "OneCosine",
           "OneSine", "Pulse", "PulseFit", "PulseLike", "RickerAntisymmetric", "RickerSymmetric",
           "coefficient_to_amplitude", "fit_pulse", "fit_pulse_candidates", "gaussian_derivative_peak_period",
           "make_pulse", "parse_periods", "parse_pulse_spec", "period_to_scale", "same_pulse", "scale_to_period"]
