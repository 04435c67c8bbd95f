"""The stability checks: plain functions of arrays, each returning a :class:`Check`.

Each can be fed a planted failure (the tests do). :func:`rockcli.bench.stability.judge_run` applies
them to a history run.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from rockcli.bench.history import impact_rows

#: Largest |change| in theta_max/alpha between rtol 1e-6 and 1e-10 that counts as "the same answer".
PEAK_TOL = 1e-3
#: Largest change in the overturning time [s] between the two tolerances.
T_OVERTURN_TOL = 1e-3
#: Relative tolerance on the momentum balances across an impact (exact algebra: rounding only).
MOMENTUM_TOL = 1e-9
#: Largest energy rise in free rocking, as a fraction of p^2, allowed per unit of rtol (integration error).
ENERGY_TOL_PER_RTOL = 100.0
#: A step shorter than this [s] is tiny; a run of COLLAPSE_RUN consecutive tiny steps is a collapse.
TINY_STEP = 1e-9
COLLAPSE_RUN = 50
#: Largest share of rejected steps.
MAX_REJECTED = 0.5


@dataclass(frozen=True)
class Check:
    """One check: its name, whether it held, and a sentence with the measured value."""

    name: str
    ok: bool
    detail: str


def check_finite(**arrays) -> Check:
    """No NaN or inf in any of the named arrays or numbers."""
    bad = [k for k, v in arrays.items() if v is not None and not np.all(np.isfinite(np.asarray(v, dtype=float)))]
    return Check("finite", not bad, "no NaN/inf" if not bad else f"NaN or inf in {', '.join(bad)}")


def check_budget(wall_s: float, budget_s: float, status: int, steps: int, step_budget: int) -> Check:
    """Wall time within ``budget_s`` and the step cap not reached (status -1): no hang."""
    if status == -1 or steps >= step_budget:
        return Check("budget", False, f"step budget reached ({steps} of {step_budget} steps)")
    if not wall_s <= budget_s:
        return Check("budget", False, f"{wall_s:.2f} s, over the {budget_s:g} s budget")
    return Check("budget", True, f"{wall_s:.3f} s <= {budget_s:g} s, {steps} steps <= {step_budget}")


def check_steps(t, steps: int, rejected: int, *, tiny: float = TINY_STEP, run: int = COLLAPSE_RUN,
                max_rejected: float = MAX_REJECTED) -> Check:
    """No step-size collapse: no ``run`` consecutive steps shorter than ``tiny`` [s] in the history
    (events give two rows at one time: those zero-length pairs are not steps), and at most
    ``max_rejected`` of the steps rejected."""
    t = np.asarray(t, dtype=float)
    d = np.diff(t)
    d = d[d > 0]
    longest = 0
    if d.size:
        tinies = d < tiny
        # longest run of consecutive True
        if tinies.any():
            edges = np.diff(np.concatenate(([0], tinies.astype(np.int8), [0])))
            starts, ends = np.nonzero(edges == 1)[0], np.nonzero(edges == -1)[0]
            longest = int(np.max(ends - starts))
    share = rejected / max(steps, 1)
    h_min = float(d.min()) if d.size else math.nan
    if longest >= run:
        return Check("steps", False, f"step size collapsed: {longest} consecutive steps shorter than {tiny:g} s")
    if share > max_rejected:
        return Check("steps", False, f"{100 * share:.0f}% of the steps rejected")
    return Check("steps", True, f"shortest step {h_min:.2g} s, {100 * share:.1f}% rejected")


def check_tolerance(verdict_a: str, verdict_b: str, peak_a: float, peak_b: float, t_ot_a: float = math.nan,
                    t_ot_b: float = math.nan, *, peak_tol: float = PEAK_TOL, t_tol: float = T_OVERTURN_TOL) -> Check:
    """The answer does not change with the tolerance: the same verdict, theta_max/alpha within
    ``peak_tol`` and (overturning) the overturning time within ``t_tol`` [s]."""
    if verdict_a != verdict_b:
        return Check("tolerance", False, f"verdict changes with rtol: {verdict_a} vs {verdict_b}")
    if verdict_a == "overturned":
        d = abs(t_ot_a - t_ot_b)
        if math.isnan(d) and not (math.isnan(t_ot_a) and math.isnan(t_ot_b)):
            return Check("tolerance", False, "overturning time missing at one tolerance")
        if not (d <= t_tol or (math.isnan(t_ot_a) and math.isnan(t_ot_b))):
            return Check("tolerance", False, f"overturning time changes by {d:.2g} s (> {t_tol:g} s)")
        return Check("tolerance", True, f"same verdict, overturning time within {d:.2g} s")
    d = abs(peak_a - peak_b)
    if not d <= peak_tol:
        return Check("tolerance", False, f"theta_max/alpha changes by {d:.2g} (> {peak_tol:g})")
    return Check("tolerance", True, f"same verdict, theta_max/alpha within {d:.2g}")



def check_momentum(t, theta, theta_dot, u_dot, *, R: float, alpha: float, gamma: float, isolated: bool,
                   tol: float = MOMENTUM_TOL) -> Check:
    """Momentum across every impact of a history.

    Per unit block mass, the angular momentum about the new pivot, ``I_o theta_dot + h u_dot`` after
    against ``(I_o - 2 b^2) theta_dot + h u_dot`` before (``I_o = 4 R^2/3``; Eq 14), for every impact
    that is not a rest (a rest is plastic by design); on an isolated base also the total horizontal
    momentum per unit total mass ``u_dot + gamma h theta_dot`` (Eq 16), for every impact and rest.
    """
    th, thd, ud = (np.asarray(a, dtype=float) for a in (theta, theta_dot, u_dot))
    k = impact_rows(t, theta, theta_dot)
    if k.size == 0:
        return Check("momentum", True, "no impact")
    h, b = R * math.cos(alpha), R * math.sin(alpha)
    Io = 4.0 / 3.0 * R * R
    t1, t2 = thd[k], thd[k + 1]
    u1, u2 = (ud[k], ud[k + 1]) if isolated else (np.zeros(k.size), np.zeros(k.size))
    worst_ang = worst_lin = 0.0
    rest = t2 == 0.0
    ang = np.abs(Io * t2 + h * u2 - ((Io - 2 * b * b) * t1 + h * u1)) / (Io * np.abs(t1) + h * np.abs(u1))
    if (~rest).any():
        worst_ang = float(np.max(ang[~rest]))
    if isolated:
        lin = np.abs(u2 + gamma * h * t2 - (u1 + gamma * h * t1)) / (np.abs(u1) + gamma * h * np.abs(t1) + 1e-300)
        worst_lin = float(np.max(lin))
    ok = worst_ang <= tol and worst_lin <= tol
    what = f"{k.size} impacts ({int(rest.sum())} rests): angular momentum to {worst_ang:.1e}"
    if isolated:
        what += f", horizontal momentum to {worst_lin:.1e}"
    return Check("momentum", ok, (what if ok else "momentum not kept: " + what) + f" (tolerance {tol:g})")


def check_energy(t, theta, theta_dot, *, p: float, alpha: float, t_exc_end: float, rtol: float,
                 per_rtol: float = ENERGY_TOL_PER_RTOL) -> Check:
    """Rigid foundation, after the excitation: ``E = theta_dot^2/2 + p^2 cos(alpha - |theta|)`` never
    rises above its running minimum by more than ``per_rtol * rtol * p^2`` (free rocking conserves
    E between impacts; impacts and rests only lower it)."""
    t, th, thd = (np.asarray(a, dtype=float) for a in (t, theta, theta_dot))
    m = t >= t_exc_end
    if m.sum() < 2:
        return Check("energy", True, "no free motion in the history")
    E = 0.5 * thd[m] ** 2 + p * p * np.cos(alpha - np.abs(th[m]))
    rise = float(np.max(E - np.minimum.accumulate(E))) / (p * p)
    tol = per_rtol * rtol
    if not rise <= tol:  # NaN fails too
        return Check("energy", False, f"energy created in free rocking: rise {rise:.2e} p^2 (> {tol:.0e} p^2)")
    return Check("energy", True, f"largest rise {rise:.1e} p^2 (<= {tol:.0e} p^2)")


def check_dissipation(u, z, *, Q: float, u_y: float, tol: float = 1e-6) -> Check:
    """Hysteretic bearing: the energy it has dissipated, ``Q (int z du - u_y z^2/2)`` per unit total
    mass (work of the hysteretic force minus the energy stored in its elastic part), never falls
    below zero or below an earlier value by more than ``tol`` of ``Q max|u|`` (trapezoid rule
    on the history)."""
    u, z = np.asarray(u, dtype=float), np.asarray(z, dtype=float)
    if u.size < 2:
        return Check("dissipation", True, "no base motion")
    work = np.concatenate(([0.0], np.cumsum(0.5 * (z[1:] + z[:-1]) * np.diff(u))))
    D = Q * (work - 0.5 * u_y * z * z)
    scale = Q * max(float(np.max(np.abs(u))), u_y)
    drop = float(np.max(np.maximum.accumulate(D) - D)) / scale
    low = float(-min(0.0, np.min(D))) / scale
    if not (drop <= tol and low <= tol):  # NaN fails too
        return Check("dissipation", False, f"bearing energy created: dissipated energy falls by {max(drop, low):.1e} "
                                           f"of Q max|u|")
    return Check("dissipation", True, f"dissipated energy never falls (to {max(drop, low):.0e} of Q max|u|)")
