"""What both drivers share: the run record's accessors, the excitation segments, the step-size
controller, the events of a rocking step in theta, the impact bookkeeping and the run's outputs.

Nothing here depends on the foundation: the rigid-foundation driver (:mod:`rockcli.kernels.rigid`)
and the isolated-base driver (:mod:`rockcli.kernels.driver`) call these with their own right-hand
side (a function argument where one is needed), so each compiles only its own foundation's code.

Integer arguments of compiled calls (row offsets, state counts, state indices, phase codes) are
passed as ``np.int64(...)``, never as bare literals: numba types a literal ``0`` as
``Literal[int](0)``, a type of its own, and compiles the callee once more for each literal value.
One extra copy of a step function costs about 0.7 s on a cold cache (the rigid map's cold start
went from 9.4-9.8 s to 7.7-8.5 s, the linear one from 28-31 s to 19-21 s when they were removed).
``benchmarks/bench_spectra.py --cold`` lists any function compiled more than once. The batch loops
pass ``want_history`` as ``np.bool_(False)`` for the same reason: numba does not prune the history
branches for a literal ``False`` (it still compiles them), so a literal only compiled the whole driver
a second time in a process that also runs single scenes (1.5-4 s more on a cold cache).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.dopri import _dense, _shift_event, _state_at
from rockcli.kernels.events import _count_uplift, comes_to_rest
from rockcli.kernels.ground import _pulse_segment
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (E_AP, E_TP, EXC_RECORD, HK_IMPACT_AFTER, HK_OVERTURN, HK_REST, HK_STATE, N_HIST, N_OUT, N_RS, N_W, O_N_IMPACTS, O_N_IMPACTS_ALL,
                                    O_N_RESTS, O_N_REVERSALS, O_NRHS, O_PEAK_FINAL, O_REJECTED, O_SETTLED, O_STATUS,
                                    O_STEPS, O_T_END, O_T_EXCEED, O_T_OVERTURN, O_T_THETA_MAX, O_T_UPLIFT,
                                    O_THETA_END, O_THETA_MAX, O_U_END, O_U_MAX, P_ALPHA, P_P2, P_TH0, P_THD0,
                                    PHASE_ROCKING, PHASE_STUCK, RS_FRESH, RS_H, RS_J, RS_NREV, RS_NRHS,
                                    RS_PEAK_FINAL, RS_PHASE, RS_PK_ON, RS_PK_SIG, RS_PK_T,
                                    RS_REJ, RS_S, RS_SEG, RS_SEG_END, RS_SETTLED, RS_STATUS, RS_STEPS, RS_T,
                                    RS_THMAX, RS_UMAX, RS_VEND, RS_VJ, RS_VSEG, SEG_LINEAR, STATUS_DONE,
                                    STATUS_MAX_STEPS, STATUS_OVERTURNED,
                                    W_EV, W_FEV, W_TMP, W_Y, W_YNEW)
from rockcli.kernels.polynomials import _first_down, _poly


# ---------------------------------------------------------------------------------------------
# The run record
# ---------------------------------------------------------------------------------------------
@kernel(inline='always')
def _seg(rs):
    """The segment tuple ``(mode, a0, slope, ts, v0, vslope, tv)``: the horizontal ground motion
    (:func:`rockcli.kernels.ground._ground`) and the vertical one (:func:`rockcli.kernels.ground._vertical`)."""
    return (rs[RS_SEG], rs[RS_SEG + 1], rs[RS_SEG + 2], rs[RS_SEG + 3], rs[RS_VSEG], rs[RS_VSEG + 1],
            rs[RS_VSEG + 2])


@kernel(inline='always')
def _set_seg(rs, seg, seg_end):
    rs[RS_SEG] = seg[0]
    rs[RS_SEG + 1] = seg[1]
    rs[RS_SEG + 2] = seg[2]
    rs[RS_SEG + 3] = seg[3]
    rs[RS_SEG_END] = seg_end


@kernel
def _start(ekind, epar, acc, dt, t_begin, want_history, out):
    """A new run: cleared outputs, the work array ``W``, the run record ``rs`` at ``t_begin`` on
    the first excitation segment, and an empty history ``H`` (room for the run when wanted)."""
    for k in range(N_OUT):
        out[k] = 0.0
    out[O_T_UPLIFT] = np.nan
    out[O_T_OVERTURN] = np.nan
    out[O_T_EXCEED] = np.nan
    out[O_T_THETA_MAX] = np.nan
    W = np.zeros((N_W, 4))
    rs = np.zeros(N_RS)
    rs[RS_T] = t_begin
    rs[RS_PHASE] = PHASE_STUCK
    rs[RS_FRESH] = 1.0  # W[0] = f(t, y) must be (re)computed
    rs[RS_PEAK_FINAL] = 1.0
    rs[RS_STATUS] = STATUS_DONE
    rs[RS_J] = 0.0
    rs[RS_VEND] = np.inf
    rs[RS_VJ] = -1.0
    if ekind == EXC_RECORD:
        rscale = epar[E_AP]  # records: the factor the record is scaled by
        _set_seg(rs, (float(SEG_LINEAR), rscale * acc[0], rscale * (acc[1] - acc[0]) / dt, 0.0), dt)
    else:
        seg0, seg_end0 = _pulse_segment(np.int64(0), ekind, epar, t_begin)
        _set_seg(rs, seg0, seg_end0)
    if want_history:
        H = np.empty((2 * acc.shape[0] + 1024 if ekind == EXC_RECORD else 4096, N_HIST))
    else:
        H = np.empty((0, N_HIST))
    return W, rs, H


@kernel
def _initial_state(prm, rs, W, out):
    """A start from a tilt ``theta0`` and/or an angular velocity ``theta_dot0`` (``P_TH0``, ``P_THD0``;
    both 0: at rest, nothing to do). The block starts rocking at ``t_begin`` on the corner
    ``s = sign(theta0)`` (``sign(theta_dot0)`` when theta0 = 0), the base and the ground at rest; this
    counts as its first uplift, its peak so far is ``|theta0|``. Every end-of-run proof argues from the
    current state (energy and impulse bounds, never from the history), so none assumes a start at rest;
    the early stops P4, P6, P7 wait for the first uplift only so that a ``no_uplift`` verdict stays
    final, and a tilted start has uplifted."""
    th0 = prm[P_TH0]
    thd0 = prm[P_THD0]
    if th0 == 0.0 and thd0 == 0.0:
        return
    W[W_Y, 0] = th0
    W[W_Y, 1] = thd0
    ref = th0 if th0 != 0.0 else thd0
    rs[RS_S] = 1.0 if ref > 0.0 else -1.0
    rs[RS_PHASE] = PHASE_ROCKING
    rs[RS_FRESH] = 1.0
    _count_uplift(out, rs[RS_T])
    if th0 != 0.0:
        rs[RS_THMAX] = abs(th0)
        out[O_T_THETA_MAX] = rs[RS_T]
        if abs(th0) >= prm[P_ALPHA]:
            out[O_T_EXCEED] = rs[RS_T]


@kernel(inline='always')
def _finish(rs, W, out):
    """Copy the run record's results into ``out`` (``O_*`` layout)."""
    out[O_STATUS] = rs[RS_STATUS]
    out[O_THETA_MAX] = rs[RS_THMAX]
    out[O_U_MAX] = rs[RS_UMAX]
    out[O_STEPS] = rs[RS_STEPS]
    out[O_REJECTED] = rs[RS_REJ]
    out[O_NRHS] = rs[RS_NRHS]
    out[O_T_END] = rs[RS_T]
    out[O_SETTLED] = 1.0 if (rs[RS_SETTLED] != 0.0 or rs[RS_STATUS] == STATUS_OVERTURNED) else 0.0
    out[O_PEAK_FINAL] = rs[RS_PEAK_FINAL]
    out[O_THETA_END] = W[W_Y, 0]
    out[O_U_END] = W[W_Y, 2]
    out[O_N_REVERSALS] = rs[RS_NREV]


@kernel(inline='always')
def _advance_segment(rs, ekind, epar, acc, dt, t_begin):
    """Move to the excitation segment that contains t (records: one per sample interval)."""
    nrec = acc.shape[0]
    while rs[RS_T] >= rs[RS_SEG_END]:
        j = int(rs[RS_J]) + 1
        rs[RS_J] = j
        if ekind == EXC_RECORD:
            rscale = epar[E_AP]
            if j < nrec - 1:
                _set_seg(rs, (float(SEG_LINEAR), rscale * acc[j], rscale * (acc[j + 1] - acc[j]) / dt, j * dt),
                         (j + 1) * dt)
                # a record is continuous across samples: the FSAL derivative stays valid
            else:
                _set_seg(rs, (float(SEG_LINEAR), 0.0, 0.0, (nrec - 1) * dt), np.inf)
                rs[RS_FRESH] = 1.0
        else:
            seg, seg_end = _pulse_segment(j, ekind, epar, t_begin)
            _set_seg(rs, seg, seg_end)
            rs[RS_FRESH] = 1.0


@kernel(inline='always')
def _vertical_piece(rs, vacc, vdt):
    """Move to the piece of the vertical series ``vacc`` (samples every ``vdt`` from t = 0, zero after
    the last) that contains t; nothing without a vertical motion (``vacc`` empty). The series is
    continuous across its samples (the first-same-as-last derivative stays valid), not at its end."""
    n = vacc.shape[0]
    t = rs[RS_T]
    if n == 0 or (t < rs[RS_VEND] and rs[RS_VJ] >= 0.0):
        return
    k = int(t / vdt) if t > 0.0 else 0
    while k > 0 and k * vdt > t:
        k -= 1
    while k < n - 1 and (k + 1) * vdt <= t:
        k += 1
    if k < n - 1:
        rs[RS_VSEG] = vacc[k]
        rs[RS_VSEG + 1] = (vacc[k + 1] - vacc[k]) / vdt
        rs[RS_VSEG + 2] = k * vdt
        rs[RS_VEND] = (k + 1) * vdt
    else:
        rs[RS_VSEG] = 0.0
        rs[RS_VSEG + 1] = 0.0
        rs[RS_VSEG + 2] = (n - 1) * vdt
        rs[RS_VEND] = np.inf
        rs[RS_FRESH] = 1.0
    rs[RS_VJ] = k


@kernel(inline='always')
def _out_of_time(rs, t_horizon, max_steps):
    """The horizon or the step cap is reached (the latter sets ``STATUS_MAX_STEPS``)."""
    if rs[RS_T] >= t_horizon:
        return True
    if rs[RS_STEPS] + rs[RS_REJ] >= max_steps:
        rs[RS_STATUS] = STATUS_MAX_STEPS
        return True
    return False


# ---------------------------------------------------------------------------------------------
# Step-size control (Dormand-Prince 5(4), the controller SciPy's RK45 uses)
# ---------------------------------------------------------------------------------------------
@kernel(inline='always')
def _step_start(rhs_into, fkind, prm, ekind, epar, rs, W, hy):
    """The step size to try from ``rs[RS_T]``; (re)computes ``W[0] = f(t, y)`` when stale.

    A first step is ``0.02/p`` (and at most ``T_p/50`` on a pulse). Just after an impact the step
    must not swallow a short flight that the angular acceleration turns back (flight ~ 2 thd/|thdd|).
    """
    h = rs[RS_H]
    if h <= 0.0:
        h = 0.02 / math.sqrt(prm[P_P2])
        if ekind != EXC_RECORD:
            h = min(h, epar[E_TP] / 50.0)
    if rs[RS_FRESH] != 0.0:
        s = rs[RS_S]
        phase = rs[RS_PHASE]
        rhs_into(fkind, phase, s, prm, _seg(rs), epar, hy, rs[RS_T], W, W_Y, np.int64(0))
        rs[RS_NRHS] += 1
        rs[RS_FRESH] = 0.0
        if phase == PHASE_ROCKING and W[W_Y, 0] == 0.0:
            vel = s * W[W_Y, 1]
            back = -s * W[0, 1]
            if vel > 0.0 and back > 0.0:
                h = min(h, 0.5 * vel / back)
    return h


@kernel(inline='always')
def _accept_step(dp5, s, prm, seg, epar, t, h, W, rs, max_steps, t_stop):
    """The step-size loop of a driver with a single Dormand-Prince step ``dp5(s, prm, seg, epar, t, h, W, r0)`` (the
    rigid block's, the stack's pattern BP): from ``t`` with the proposal ``h``, clipped to ``t_stop``, retried smaller
    until accepted or the step cap; the bookkeeping written back (:func:`_close_step`). Returns ``(ok, hs, last)``."""
    last = False
    hs = h
    err = 2.0
    steps = rs[RS_STEPS]
    rej = rs[RS_REJ]
    nrhs = rs[RS_NRHS]
    while steps + rej < max_steps:
        hs = h
        last = hs >= t_stop - t
        if last:
            hs = t_stop - t
        err = dp5(s, prm, seg, epar, t, hs, W, np.int64(0))
        nrhs += 6
        if err <= 1.0:
            h = _grown(h, hs, err, last)
            break
        rej += 1
        h = hs * _shrink(err)
    return _close_step(rs, h, rej, nrhs, steps, err), hs, last


@kernel(inline='always')
def _grown(h, hs, err, last):
    """Step size to try after an accepted step of size ``hs`` with scaled error ``err <= 1``: grown
    by the controller, unless the step was cut short to land on ``t_stop`` and would grow (then the
    proposal ``h`` it was cut from stands)."""
    fac = 5.0 if err == 0.0 else min(5.0, 0.9 * err ** -0.2)
    return hs * fac if (not last or fac < 1.0) else h


@kernel(inline='always')
def _shrink(err):
    """Factor of the retry after a rejected step with scaled error ``err > 1``."""
    return max(0.2, 0.9 * err ** -0.2)


@kernel(inline='always')
def _close_step(rs, h, rej, nrhs, steps, err):
    """Write a step's bookkeeping back to the run record; True when the step was accepted."""
    rs[RS_H] = h
    rs[RS_REJ] = rej
    rs[RS_NRHS] = nrhs
    if err > 1.0:
        return False
    rs[RS_STEPS] = steps + 1
    return True


# ---------------------------------------------------------------------------------------------
# Events of a rocking step in theta
# ---------------------------------------------------------------------------------------------
EV_NONE = 0  # no event: the step stands to sig_lim
EV_OVERTURN = 1  # s theta reaches pi/2 at sigma
EV_FAILED = 2  # the block never rose above theta = 0: the uplift did not take
EV_IMPACT = 3  # s theta falls to 0 at sigma


@kernel
def _rocking_events(prm, rs, W, out, hs, t_new, sig_lim):
    """Events in theta of a rocking step about corner ``s`` over ``[0, sig_lim]`` of the step:
    ``(code, sigma)`` (``EV_*``; sigma of the event, or ``sig_lim``). Updates the peak
    ``theta_max`` (its time) and the time alpha is first exceeded; changes no state. A peak of theta
    (``theta_dot`` = 0) inside the step is noted in ``RS_PK_*`` (for the history's peak rows)."""
    rs[RS_PK_ON] = 0.0
    s = rs[RS_S]
    t = rs[RS_T]
    alpha = prm[P_ALPHA]
    halfpi = 0.5 * math.pi
    sth1 = s * W[W_YNEW, 0]
    sd0 = s * W[W_Y, 1]
    sd1 = s * W[W_YNEW, 1]
    sig_end = sig_lim
    impact = False
    if sth1 <= 0.0 or (sd0 < 0.0 and sd1 > 0.0):
        sig = _first_down(_dense(W, hs, np.int64(0), s), 0.0, 0.0, sig_lim)
        if sig >= 0.0:
            impact = True
            sig_end = sig
        elif sth1 <= 0.0:
            return EV_FAILED, sig_lim
    if sd0 >= 0.0 and (sd1 <= 0.0 or impact):  # sd0 = 0 right after an uplift
        sp = _first_down(_dense(W, hs, np.int64(1), s), 0.0, 0.0, sig_end)
        if sp >= 0.0:
            thp = _poly(_dense(W, hs, np.int64(0), s), sp)
            rs[RS_PK_ON] = 1.0
            rs[RS_PK_SIG] = sp
            rs[RS_PK_T] = t + sp * hs
            if thp > rs[RS_THMAX]:
                rs[RS_THMAX] = thp
                out[O_T_THETA_MAX] = t + sp * hs
    if not impact and sth1 > rs[RS_THMAX]:
        rs[RS_THMAX] = sth1
        out[O_T_THETA_MAX] = t_new
    if math.isnan(out[O_T_EXCEED]) and rs[RS_THMAX] >= alpha:
        sa = _first_down(_dense(W, hs, np.int64(0), -s), -alpha, 0.0, sig_end)
        out[O_T_EXCEED] = t + (sa if sa >= 0.0 else sig_end) * hs
    if not impact and sth1 >= halfpi:
        so = _first_down(_dense(W, hs, np.int64(0), -s), -halfpi, 0.0, sig_lim)
        return EV_OVERTURN, (so if so >= 0.0 else sig_lim)
    if impact:
        return EV_IMPACT, sig_end
    return EV_NONE, sig_lim


@kernel(inline='always')
def _row_kind(code, rs):
    """The history kind (``HK_*``) of the row at the end of a rocking step whose event was ``code``."""
    if code == EV_IMPACT:
        return HK_REST if rs[RS_PHASE] == PHASE_STUCK else HK_IMPACT_AFTER
    if code == EV_OVERTURN:
        return HK_OVERTURN
    return HK_STATE


@kernel(inline='always')
def _to_overturn(rs, W, out, hs, so, nst):
    """The state at ``s theta = pi/2`` (fraction ``so`` of the step) ends the run: overturned."""
    _state_at(W, hs, so, nst)
    for i in range(nst):
        W[W_Y, i] = W[W_TMP, i]
    rs[RS_UMAX] = max(rs[RS_UMAX], abs(W[W_Y, 2]))
    rs[RS_T] = rs[RS_T] + so * hs
    rs[RS_THMAX] = 0.5 * math.pi
    out[O_T_THETA_MAX] = rs[RS_T]
    out[O_T_OVERTURN] = rs[RS_T]
    rs[RS_STATUS] = STATUS_OVERTURNED


@kernel(inline='always')
def _to_impact(restep, fkind, prm, rs, W, epar, hy, hs, sig, nst):
    """The state at the impact, fraction ``sig`` of the step: the step retaken to it (``restep``,
    the driver's :func:`rockcli.kernels.dopri._restep_rows`), moved onto the root theta = 0 by one
    Taylor term, theta then set to exactly 0."""
    t = rs[RS_T]
    restep(fkind, np.int64(PHASE_ROCKING), rs[RS_S], prm, _seg(rs), epar, hy, t, sig * hs, W, np.int64(0), nst)
    rs[RS_NRHS] += 6
    dt_e = -W[W_EV, 0] / W[W_FEV, 0] if W[W_FEV, 0] != 0.0 else 0.0
    dt_e = min(max(dt_e, -sig * hs), (1.0 - sig) * hs)
    _shift_event(W, dt_e, np.int64(0), nst)
    for i in range(nst):
        W[W_Y, i] = W[W_EV, i]
    rs[RS_T] = t + sig * hs + dt_e
    W[W_Y, 0] = 0.0


@kernel(inline='always')
def _to_step_end(rs, W, t_new, nst):
    """Accept the whole step: its end state and (first same as last) its end derivative."""
    rs[RS_T] = t_new
    for i in range(nst):
        W[W_Y, i] = W[W_YNEW, i]
        W[0, i] = W[6, i]


@kernel(inline='always')
def _bounce(prm, rs, W, out, thd1, t_exc_end, a_rest, thd2, thr):
    """After the impact map (``theta_dot`` ``thd1`` before, ``thd2`` after, the pivot switched):
    count the impact and apply the rest rule under the base acceleration ``a_rest`` and the uplift
    threshold ``thr`` (``g tan(alpha)``; ``(g + a_v) tan(alpha)`` under a vertical motion).
    Returns True when the block comes to rest (theta_dot = 0, stuck)."""
    out[O_N_IMPACTS_ALL] += 1
    if rs[RS_T] <= t_exc_end:
        out[O_N_IMPACTS] += 1
    rs[RS_FRESH] = 1.0
    if comes_to_rest(prm, a_rest, thd2, thr, prm[P_ALPHA]):
        W[W_Y, 1] = 0.0
        rs[RS_PHASE] = PHASE_STUCK
        rs[RS_S] = 0.0
        out[O_N_RESTS] += 1
        return True
    W[W_Y, 1] = thd2
    return False
