"""Slow, obviously correct reference for rocking on sliding (hysteretic) bearings: now
:func:`rockcli.reference.reference_sliding` (SciPy ``solve_ivp``, Radau, Eq (34)'s ``z`` as a stiff
state, the double concave bearing in rate form, the impact map as the 2x2 momentum system).

Kept as a thin re-export so that the sliding tests and ``benchmarks/bench_sliding.py`` keep working.
"""

from rockcli.reference import Bearing, RefResult, reference_simulate, reference_sliding  # noqa: F401
