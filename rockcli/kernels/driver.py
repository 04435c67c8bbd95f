"""The isolated-base driver: :func:`simulate_core` runs one scene on bearings as a loop over phases.

(A block on a rigid foundation runs in :mod:`rockcli.kernels.rigid`; what both share is in
:mod:`rockcli.kernels.steps`.) Phases and states (``W`` columns ``theta, theta_dot, u, u_dot``;
hysteretic bearings add their Bouc-Wen variables, which follow u exactly and live in the anchor
of the run record ``rs``), in :mod:`rockcli.kernels.driver_phases`:

* *stuck*: the block moves with its base (theta = theta_dot = 0); only the base is integrated
  (:func:`~rockcli.kernels.driver_phases._after_stuck_step`), or, on linear bearings under a record, advanced
  exactly from sample to sample (:func:`~rockcli.kernels.driver_phases._linear_stuck_step`,
  :mod:`rockcli.kernels.linear_base`).
* *rocking* about the corner ``s`` (+1 right, -1 left): all four states
  (:func:`~rockcli.kernels.driver_phases._after_rocking_step`).

Each pass of the loop: move to the excitation segment that contains t
(:func:`rockcli.kernels.steps._advance_segment`), apply the end-of-run rule
(:func:`rockcli.kernels.driver_end._end_of_run`, with its proofs), then take one Dormand-Prince step
(:func:`~rockcli.kernels.driver_phases._take_step`) and handle the events inside it. On a hysteretic base a step
also ends where the base reverses (the Bouc-Wen variables follow u exactly only while u moves one way); the
bearings are re-anchored after every step (:func:`~rockcli.kernels.driver_phases._reanchor`).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.bearings import base_force, initial_anchor
from rockcli.kernels.driver_end import _end_of_run
from rockcli.kernels.driver_phases import (_after_rocking_step, _after_stuck_step, _hist_grid_linear, _hy, _impact,
                                           _linear_stuck_step, _set_hy, _take_step)
from rockcli.kernels.events import _count_uplift, _hist_grid, _hist_grid_cut, _hist_peak, _hist_state
from rockcli.kernels.ground import ground_at
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (EXC_RECORD, FOUNDATION_BILINEAR, FOUNDATION_LINEAR, HK_IMPACT, HK_STATE, HK_UPLIFT,
                                    H_KIND, H_T, PHASE_ROCKING, PHASE_STUCK, P_HDT, P_TH0, P_THD0, P_THR, P_W, P_XI,
                                    RS_FRESH, RS_PHASE, RS_PK_ON, RS_PK_T, RS_S, RS_SEG_END, RS_SETTLED, RS_STATUS,
                                    RS_T, STATUS_MAX_STEPS, W_TMP, W_Y)
from rockcli.kernels.linear_base import coefficients, linear_base_table
from rockcli.kernels.steps import (EV_IMPACT, EV_OVERTURN, _advance_segment, _finish, _initial_state, _row_kind, _seg,
                                   _start)


# ---------------------------------------------------------------------------------------------
# History rows
# ---------------------------------------------------------------------------------------------
@kernel
def _history_row(H, nh, fkind, prm, rs, epar, W, row, kind):
    """Append the state ``W[row]`` at ``rs[RS_T]`` to the history, with the bearing's z and force."""
    t = rs[RS_T]
    return _hist_state(H, nh, t, ground_at(t, _seg(rs), epar), fkind, prm, _hy(rs), W, row, kind)


@kernel
def _mark_uplift(H, nh, t):
    """Mark the last history row as the uplift when it is a plain step row at ``t``."""
    if nh > 0 and H[nh - 1, H_KIND] == HK_STATE and H[nh - 1, H_T] == t:
        H[nh - 1, H_KIND] = HK_UPLIFT


# ---------------------------------------------------------------------------------------------
# The simulation kernel
# ---------------------------------------------------------------------------------------------
@kernel
def simulate_core(fkind, prm, ekind, epar, acc, jtab, dt, t_begin, t_exc_end, tail, horizon, max_steps,
                  want_history, early, out):
    """Integrate one scene on an isolated base. Fills ``out`` (see the ``O_*`` layout) and returns the history.

    Scenes on a rigid foundation run in :func:`rockcli.kernels.rigid.simulate_rigid` (same
    arguments and outputs; its proofs P1, P2, P4, P6, P7 are stated there).

    End of the run (one rule for every mode)
    ----------------------------------------
    The run ends when the verdict is *proven* (or at overturning): the rule and the theorems it checks, P3, P3s,
    P5, P8, and with ``early`` P9, P9s, are stated in :mod:`rockcli.kernels.driver_end`. A history run goes on after
    the proof until exactly ``t_exc_end + tail`` to show the free motion (nothing after a proof can change the
    verdict, ``theta_max`` or ``n_impacts``); a run that reaches ``t_exc_end + horizon`` unproven ends there with
    ``O_SETTLED = 0``: reported, never silently called safe.

    Parameters
    ----------
    fkind : int
        Foundation kind (``FOUNDATION_*``, not rigid).
    prm : tuple of N_PRM floats
        Block, foundation and tolerance constants (``P_*`` layout).
    ekind : int
        Excitation kind (``EXC_*``): ``acc`` [m/s^2] and ``dt`` [s] for a record (scaled by
        ``epar[E_AP]``), ``epar`` (tuple of 8 floats, ``E_*`` layout) for a pulse.
    t_begin, t_exc_end : float
        Start of the integration and end of the excitation [s].
    acc, jtab : float64 arrays
        The record's samples and the suffix integrals of ``|ag|`` (``ground._impulse_left``).
    tail : float
        Free motion shown by a history run after the excitation [s] (see "End of the run").
    horizon : float
        Longest free motion followed after the excitation to prove the verdict [s].
    max_steps : int
        Hard cap on accepted + rejected steps (status ``STATUS_MAX_STEPS`` when reached).
    want_history : bool
        Store the state at every step end and event.
    early : bool
        Verdict only: also stop during the excitation once the verdict is proven (P9, P9s, for a block
        at rest on its base; on a rigid foundation P4, P6, P7), and do not follow the free base to its
        peak displacement after a proof: ``O_U_MAX`` is then NaN unless proven final.
    out : float64[N_OUT]
        Filled with the results.

    Returns
    -------
    H : float64[n, N_HIST]
        History rows ``t, ag, theta, theta_dot, u, u_dot, z1, z2, bearing force, kind`` (empty when not
        wanted); ``kind`` ``HK_PEAK`` marks the turning points of theta (theta_dot = 0, z's and force
        NaN), ``HK_GRID`` the rows on the uniform grid ``k prm[P_HDT]`` (when ``P_HDT > 0``: each
        step's dense output at the grid times inside it, written before its events move the state),
        ``HK_UPLIFT``, ``HK_IMPACT``, ``HK_IMPACT_AFTER``, ``HK_REST``, ``HK_OVERTURN`` the step rows at
        those events, ``HK_STATE`` every other step row (``rockcli.kernels.layout``).

    The start: at rest, or rocking from ``prm[P_TH0], prm[P_THD0]``
    (:func:`rockcli.kernels.steps._initial_state`); the proofs above argue from the current state
    only, so they hold for any start.
    """
    nst = np.int64(4)  # (not a literal 4: one compiled specialization of each callee, see steps.py)
    W, rs, H = _start(ekind, epar, acc, dt, t_begin, want_history, out)
    _initial_state(prm, rs, W, out)
    nh = np.int64(0)
    if fkind >= FOUNDATION_BILINEAR:
        _set_hy(rs, initial_anchor(fkind, prm))
    t_show_end = t_exc_end + tail
    t_horizon = t_exc_end + max(horizon, tail)
    early = early and not want_history
    lin = np.empty((0, 3))  # the record's linear base response for P9 (early runs on linear bearings)
    if early and fkind == FOUNDATION_LINEAR and ekind == EXC_RECORD:
        lin = linear_base_table(acc, dt, prm[P_W], prm[P_XI])
    # a record on linear bearings: the stuck phase in closed form (_linear_stuck_step)
    exact = fkind == FOUNDATION_LINEAR and ekind == EXC_RECORD
    lbc = coefficients(prm[P_W], prm[P_XI], dt)
    hdt = prm[P_HDT]
    grid = want_history and hdt > 0.0
    kg = np.int64(math.ceil(rs[RS_T] / hdt)) if grid else np.int64(0)  # the next grid time is kg hdt
    if want_history:
        H, nh = _history_row(H, nh, fkind, prm, rs, epar, W, W_Y, HK_STATE)
        if grid:
            H, nh, kg = _hist_grid(H, nh, kg, hdt, rs[RS_T], 0.0, rs[RS_T], fkind, prm, _hy(rs), _seg(rs), epar, W,
                                   np.int64(0), nst)
        if prm[P_TH0] != 0.0 and prm[P_THD0] == 0.0:  # released from rest at a tilt: its first peak
            H, nh = _hist_peak(H, nh, rs[RS_T], ground_at(rs[RS_T], _seg(rs), epar), W, W_Y)

    while True:
        _advance_segment(rs, ekind, epar, acc, dt, t_begin)
        t_stop = min(rs[RS_SEG_END], t_horizon)
        if rs[RS_SETTLED] != 0.0 and rs[RS_T] < t_show_end:
            t_stop = min(t_stop, t_show_end)  # a history run shows the free motion up to exactly here

        if _end_of_run(fkind, prm, ekind, epar, jtab, dt, lin, t_exc_end, early, want_history, t_show_end,
                       t_horizon, max_steps, rs, W, out):
            break

        if rs[RS_PHASE] == PHASE_STUCK:
            # stuck: already beyond the uplift threshold?
            a_now = base_force(fkind, prm, W[W_Y, 2], W[W_Y, 3], _hy(rs))
            if abs(a_now) > prm[P_THR]:
                rs[RS_S] = -1.0 if a_now > 0.0 else 1.0
                rs[RS_PHASE] = PHASE_ROCKING
                if want_history:  # the uplift is at the time of the last row (the end of the last step)
                    _mark_uplift(H, nh, rs[RS_T])
                _count_uplift(out, rs[RS_T])
                rs[RS_FRESH] = 1.0
                continue
            if exact:
                t0 = rs[RS_T]
                u0 = W[W_Y, 2]
                v0 = W[W_Y, 3]
                seg0 = _seg(rs)
                _linear_stuck_step(prm, rs, W, out, t_stop, dt, lbc)
                if grid:
                    H, nh, kg = _hist_grid_linear(H, nh, kg, hdt, t0, u0, v0, seg0, rs[RS_T], fkind, prm, _hy(rs),
                                                  epar, W)
                if want_history:
                    H, nh = _history_row(H, nh, fkind, prm, rs, epar, W, W_Y,
                                         HK_UPLIFT if rs[RS_PHASE] == PHASE_ROCKING else HK_STATE)
                continue

        ok, hs, last, sig_lim = _take_step(fkind, prm, ekind, epar, max_steps, rs, W, t_stop, nst)
        if not ok:
            rs[RS_STATUS] = STATUS_MAX_STEPS
            break
        t_new = t_stop if last else rs[RS_T] + sig_lim * hs
        n0 = nh
        if grid:  # the step's grid rows, before its events move W[W_Y] (those past an event are dropped below)
            i0 = np.int64(2) if rs[RS_PHASE] == PHASE_STUCK else np.int64(0)  # stuck: theta = theta_dot = 0
            H, nh, kg = _hist_grid(H, nh, kg, hdt, rs[RS_T], hs, min(t_new, t_show_end), fkind, prm, _hy(rs), _seg(rs),
                                   epar, W, i0, nst)  # no grid row after t_show_end: counted before the run

        if rs[RS_PHASE] == PHASE_STUCK:
            _after_stuck_step(fkind, prm, rs, W, out, hs, t_new, sig_lim, epar)
            if grid:
                nh, kg = _hist_grid_cut(H, n0, nh, kg, rs[RS_T])
            if want_history:
                H, nh = _history_row(H, nh, fkind, prm, rs, epar, W, W_Y,
                                     HK_UPLIFT if rs[RS_PHASE] == PHASE_ROCKING else HK_STATE)
            continue

        code = _after_rocking_step(fkind, prm, rs, W, out, hs, t_new, sig_lim, nst, epar)
        if grid:
            nh, kg = _hist_grid_cut(H, n0, nh, kg, rs[RS_T])
        if want_history and rs[RS_PK_ON] != 0.0 and code != EV_OVERTURN:  # a turning point inside the step
            H, nh = _hist_peak(H, nh, rs[RS_PK_T], ground_at(rs[RS_PK_T], _seg(rs), epar), W, W_TMP)
        if code == EV_IMPACT:
            if want_history:  # the state just before the impact, then (below) just after
                H, nh = _history_row(H, nh, fkind, prm, rs, epar, W, W_Y, HK_IMPACT)
            _impact(fkind, prm, rs, W, out, t_exc_end)
        if want_history:
            H, nh = _history_row(H, nh, fkind, prm, rs, epar, W, W_Y, _row_kind(code, rs))
        if code == EV_OVERTURN:
            break

    _finish(rs, W, out)
    return H[:nh]
