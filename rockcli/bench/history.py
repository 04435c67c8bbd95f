"""Reading a kernel history (the rows of ``simulate(..., history=True)``): impacts and the time of rest.

An impact is written as two rows at one time, both with theta = 0: theta_dot before and after the
impact map. A rest is an impact after which theta_dot is 0.
"""

from __future__ import annotations

import math

import numpy as np


def impact_rows(t, theta, theta_dot):
    """Indices k of the impacts in a history: rows k, k+1 at one time with theta = 0, theta_dot != 0 before."""
    t, th, thd = (np.asarray(a, dtype=float) for a in (t, theta, theta_dot))
    return np.nonzero((t[1:] == t[:-1]) & (th[1:] == 0.0) & (th[:-1] == 0.0) & (thd[:-1] != 0.0))[0]


def history_rest_time(h) -> float:
    """Time [s] the block was last set at rest for good, from a kernel history (NaN if it never
    rests, or lifts off again): the last impact after which theta_dot is 0, with theta 0 ever after."""
    t, th, thd = (np.asarray(a, dtype=float) for a in (h.t, h.theta, h.theta_dot))
    k = impact_rows(t, th, thd)
    rests = k[thd[k + 1] == 0.0] + 1
    if rests.size == 0 or np.any(th[rests[-1]:] != 0.0):
        return math.nan
    return float(t[rests[-1]])
