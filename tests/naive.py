"""Slow, obviously correct references for the compiled kernel: now :mod:`rockcli.reference`
(SciPy ``solve_ivp`` with events, equations typed again, the impact map as a 2x2 momentum system).

Kept as a thin re-export so that tests (and branches) importing ``naive`` keep working.
"""

from rockcli.reference import *  # noqa: F401,F403
