"""Conditioning: does an answer depend on the last bit of its input?

Rocking through many impacts can be sensitive to small changes of the ground motion (Yim, Chopra &
Penzien 1980). :func:`ulp_perturbed` gives the same ground motion to within rounding; an answer that
changes on it beyond :data:`ILL_PEAK` (or :data:`ILL_T_OVERTURN`), or whose verdict changes, is not
determined by its input at double precision: *ill-conditioned*, whatever the solver. Used by
``rockcli bench stability`` and ``rockcli assess column --check-tolerance``.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

#: Inputs moved by one ulp that each scene is rerun on.
ULP_DRAWS = 2
#: A peak |theta|/alpha that moves by more than this on them makes the scene ill-conditioned ...
ILL_PEAK = 1e-3
#: ... and so does an overturning time [s] that moves by more than this.
ILL_T_OVERTURN = 1e-3


def ulp_perturbed(excitation, rng):
    """The excitation with its numbers moved by one ulp, each up or down at random (``rng``, a NumPy
    Generator): every sample of a record; ``a_p`` of a pulse, and its ``t0`` later by one ulp or not
    (never earlier: the pulse must not start before the run). The same ground motion to within
    rounding: what changes in a solution is rounding noise."""
    if hasattr(excitation, "acc"):
        acc = np.asarray(excitation.acc, dtype=float)
        return dataclasses.replace(excitation, acc=np.nextafter(acc, np.where(rng.random(acc.size) < 0.5, -np.inf,
                                                                              np.inf)))
    a_p = float(np.nextafter(excitation.a_p, -np.inf if rng.random() < 0.5 else np.inf))
    t0 = float(np.nextafter(excitation.t0, np.inf)) if rng.random() < 0.5 else float(excitation.t0)
    return dataclasses.replace(excitation, a_p=a_p, t0=t0)


def measure_conditioning(block, foundation, excitation, *, draws: int = ULP_DRAWS, seed: int = 0, base=None,
                         **solver) -> tuple:
    """``(spread, verdicts)`` of ``excitation``'s scene: the verdicts of verdict-only runs
    (:func:`rockcli.solve.simulate` with ``solver`` options) on ``draws`` :func:`ulp_perturbed` copies,
    and the largest change of theta_max/alpha (of the overturning time [s] when the unperturbed run
    overturns) against the unperturbed run ``base`` (run here when None); NaN when a verdict changes."""
    from rockcli.solve import simulate

    rng = np.random.default_rng(seed)
    if base is None:
        base = simulate(block, foundation, excitation, **solver)
    spread, verdicts = 0.0, []
    for _ in range(draws):
        r = simulate(block, foundation, ulp_perturbed(excitation, rng), **solver)
        verdicts.append(r.verdict)
        spread = widest(spread, answer_change(base, r))
    return spread, tuple(verdicts)


def answer_change(base, other) -> float:
    """How far run ``other`` moved from run ``base``: NaN when the verdict differs, else the change of
    the overturning time [s] when ``base`` overturns (0 when both times are unknown), else of
    theta_max/alpha."""
    if other.verdict != base.verdict:
        return math.nan
    if base.verdict == "overturned":
        t_a, t_b = other.t_overturn_s, base.t_overturn_s
        return 0.0 if math.isnan(t_a) and math.isnan(t_b) else abs(t_a - t_b)
    return abs(other.theta_max_over_alpha - base.theta_max_over_alpha)


def widest(spread: float, change: float) -> float:
    """The running largest change: NaN (a changed verdict, an unknown time) once seen, stays."""
    return spread if math.isnan(spread) or change <= spread else change


def ill_conditioned(verdict: str, spread: float, verdicts) -> bool:
    """A verdict on the one-ulp copies differs from ``verdict``, or the answer moved beyond
    :data:`ILL_PEAK` (:data:`ILL_T_OVERTURN` for an overturning time)."""
    if any(v != verdict for v in verdicts):
        return True
    return not spread <= (ILL_T_OVERTURN if verdict == "overturned" else ILL_PEAK)
