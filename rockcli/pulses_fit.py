"""The wavelet pulse fitter's old home, kept so that ``from rockcli.pulses_fit import fit_pulse`` keeps working.

The fitter lives in :mod:`rockcli.pulses.fit` (with :mod:`rockcli.pulses.cwt` and
:mod:`rockcli.pulses.candidates`); import from there, or from :mod:`rockcli.pulses`.
"""

from rockcli.pulses.candidates import DUPLICATE_PERIOD_RATIO, DUPLICATE_TIME_SHARE, fit_pulse_candidates, same_pulse
from rockcli.pulses.cwt import _decimate  # noqa: F401  (tests/test_fit_pulse.py checks the low-pass)
from rockcli.pulses.fit import (DEFAULT_PERIODS, WAVELETS, PulseFit, coefficient_to_amplitude, fit_pulse,
                                parse_periods, period_to_scale, scale_to_period)

__all__ = ["DEFAULT_PERIODS", "WAVELETS", "PulseFit", "fit_pulse", "fit_pulse_candidates", "same_pulse",
           "parse_periods", "scale_to_period", "period_to_scale", "coefficient_to_amplitude",
           "DUPLICATE_PERIOD_RATIO", "DUPLICATE_TIME_SHARE"]
