"""Slow, obviously correct reference for rocking on sliding (hysteretic) bearings.

The reference lives in :mod:`rockcli.reference` (``_reference_hysteretic``: SciPy ``solve_ivp``,
Radau by default here, with Eq (34)'s ``z`` integrated as a stiff state, the double concave bearing
in rate form, the impact map as the 2x2 momentum system), written independently of
:mod:`rockcli.kernels`. This module keeps the names the sliding tests and
``benchmarks/bench_sliding.py`` use.
"""

from __future__ import annotations

from rockcli.reference import Bearing, RefResult, reference_simulate  # noqa: F401  (re-exported)


def reference_sliding(block, foundation, excitation, *, rtol=1e-9, atol=1e-12, horizon=600.0, rest_tol=1e-8,
                      method="Radau", max_phases=20000, stats=None) -> RefResult:
    """:func:`rockcli.reference.reference_simulate` on a hysteretic base (``atol`` scaled by the states).

    ``stats`` (a dict), when given, accumulates ``steps``, ``nfev``, ``njev`` and ``nlu`` of the
    ``solve_ivp`` calls (the benchmark's cost figures).
    """
    out = reference_simulate(block, foundation, excitation, rtol=rtol, atol=atol, horizon=horizon,
                             rest_tol=rest_tol, max_phases=max_phases, method=method)
    if stats is not None:
        for key in ("steps", "nfev", "njev", "nlu"):
            stats[key] = stats.get(key, 0) + int(getattr(out, key, 0) or 0)
    return out
