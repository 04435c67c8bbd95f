"""The entry points: :func:`reference_simulate` (any base, any SciPy method) and :func:`reference_sliding`."""

from __future__ import annotations

import time

import numpy as np

from rockcli.models import Block, LinearIsolation
from rockcli.reference.equations import is_hysteretic, state_scales
from rockcli.reference.hysteretic import Bearing, reference_hysteretic
from rockcli.reference.ivp import Work
from rockcli.reference.linear import reference_linear
from rockcli.reference.result import RefResult


def reference_simulate(block: Block, foundation, excitation, *, rtol=1e-10, atol=1e-13, horizon=600.0,
                       rest_tol=1e-8, max_phases=200000, method="DOP853", deadline_s=None,
                       align=False, vertical=None, restitution=None, cap_ratio=0.0) -> RefResult:
    """Chain stuck and rocking phases with ``solve_ivp`` and terminal events.

    Parameters
    ----------
    block, foundation, excitation
        As for :func:`rockcli.solve.simulate` (rigid, linear, or a hysteretic bearing).
    rtol : float
        Relative tolerance of ``solve_ivp``.
    atol : float, array or None
        Absolute tolerance, passed to ``solve_ivp`` as given; ``None`` gives ``rtol`` times the state
        scales of :func:`state_scales` (the kernel's mixed error test).
    method : str
        One of :data:`METHODS`. Hysteretic bearings (a stiff ``z`` for small ``u_y``) call for ``Radau``.
    deadline_s : float, optional
        Wall-time budget [s]; past it the run raises :class:`ReferenceTimeout`.
    align : bool
        Records only: integrate each sample interval by its own ``solve_ivp`` call, so that no step
        straddles a kink of the piecewise-linear ground motion (as the kernel does). Otherwise the
        steps are only limited to one sample interval, and the error of the steps across kinks
        limits the accuracy (about 1e-7 in theta_max/alpha on Kobe Takarazuka at any rtol).
    vertical : (acc, dt), optional
        Rigid foundation only: a vertical ground acceleration [m/s^2, upward positive] sampled every
        ``dt`` from t = 0, piecewise linear, zero after its last sample. Gravity becomes ``g + a_v``
        in Eq (3), in the uplift threshold and in the rest rule.
    restitution : float, optional
        Coefficient of restitution E (theta_dot+ = E theta_dot- on a rigid foundation; on a base the
        momentum map with the impulsive couple of :mod:`rockcli.models.impact`); None: Housner's rule.
    cap_ratio : float
        A capped colonnade of such columns (beam mass over the columns'; docs/physics-colonnade.md),
        written from its bodies' mass properties; on a base ``gamma`` is columns + beam over the moving mass.

    Returns
    -------
    RefResult
        Verdict, peaks and the work done. Raises :class:`ReferenceFailure` when ``solve_ivp`` fails.
    """
    import scipy.integrate  # noqa: F401  (imported before the clock starts)
    import scipy.optimize  # noqa: F401

    t_wall = time.perf_counter()
    hysteretic = is_hysteretic(foundation)
    if hysteretic:
        n_total = 2 + Bearing.of(foundation).nb
    else:
        n_total = 4 if isinstance(foundation, LinearIsolation) else 2
    full = state_scales(block, foundation, n_total)
    # rocking integrates every state; a stuck block only the base states (the last ones)
    work = Work(method, rtol, atol, lambda n: full[-n:], deadline_s)
    if align and hasattr(excitation, "acc"):
        work.breaks = float(excitation.dt) * np.arange(1, np.asarray(excitation.acc).size)
    if vertical is not None:
        if hysteretic or isinstance(foundation, LinearIsolation):
            raise ValueError("the reference takes a vertical motion on a rigid foundation only")
        vbreaks = float(vertical[1]) * np.arange(1, np.asarray(vertical[0]).size)
        old = getattr(work, "breaks", None)
        work.breaks = vbreaks if old is None else np.union1d(old, vbreaks)
    run = reference_hysteretic if hysteretic else reference_linear
    with np.errstate(all="ignore"):  # a diverging method is reported (ReferenceFailure), not warned about
        extra = {} if vertical is None else {"vertical": vertical}
        extra.update(restitution=restitution, cap_ratio=float(cap_ratio))
        out = run(block, foundation, excitation, work, horizon=horizon, rest_tol=rest_tol, max_phases=max_phases,
                  **extra)
    out.steps, out.nfev, out.njev, out.nlu = work.steps, work.nfev, work.njev, work.nlu
    out.wall_s = time.perf_counter() - t_wall
    out.method, out.rtol, out.atol = method, float(rtol), atol
    return out


def reference_sliding(block, foundation, excitation, *, rtol=1e-9, atol=1e-12, horizon=600.0, rest_tol=1e-8,
                      method="Radau", max_phases=20000, stats=None, restitution=None, cap_ratio=0.0) -> RefResult:
    """:func:`reference_simulate` with the defaults of a hysteretic base (Radau, ``rtol`` 1e-9,
    ``atol`` 1e-12 on every state).

    ``stats`` (a dict), when given, accumulates ``steps``, ``nfev``, ``njev`` and ``nlu`` of the
    ``solve_ivp`` calls (the benchmark's cost figures); ``restitution`` and ``cap_ratio`` as for
    :func:`reference_simulate`.
    """
    out = reference_simulate(block, foundation, excitation, rtol=rtol, atol=atol, horizon=horizon,
                             rest_tol=rest_tol, max_phases=max_phases, method=method, restitution=restitution,
                             cap_ratio=cap_ratio)
    if stats is not None:
        for key in ("steps", "nfev", "njev", "nlu"):
            stats[key] = stats.get(key, 0) + int(getattr(out, key, 0) or 0)
    return out
