"""The step and the phases of the isolated-base driver (:func:`rockcli.kernels.driver.simulate_core`).

* *stuck*: the block moves with its base (theta = theta_dot = 0); only the base is integrated
  (:func:`_after_stuck_step`), or, on linear bearings under a record, advanced exactly from sample to
  sample (:func:`_linear_stuck_step`, :mod:`rockcli.kernels.linear_base`).
* *rocking* about the corner ``s`` (+1 right, -1 left): all four states (:func:`_after_rocking_step`), the
  impact at theta = 0 (:func:`_impact`).

One Dormand-Prince step (:func:`_take_step`); on a hysteretic base a step also ends where the base reverses (the
Bouc-Wen variables follow u exactly only while u moves one way), and the bearings are re-anchored after every step
(:func:`_reanchor`; the anchor lives in the run record, :func:`_hy`).
"""

from __future__ import annotations

import numpy as np

from rockcli.kernels.bearings import (base_force, force_rate, knee_ratio, knee_step, motion_direction, reanchor,
                                      z_sensitivity)
from rockcli.kernels.dopri import _dense, _dp5_step, _restep_rows, _shift_event, _state_at
from rockcli.kernels.events import (REV_AT, REV_WRONG_START, _count_uplift, _hist_state, _u_extremum, hysteretic_uplift,
                                    impact_map, reversal_check)
from rockcli.kernels.ground import ground_at
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (FOUNDATION_BILINEAR, HK_GRID, PHASE_ROCKING, PHASE_STUCK, P_GAMMA, P_H, P_RTOL,
                                    P_SC0, P_THR, P_W, P_XI, RS_DIR, RS_FRESH, RS_NREV, RS_NRHS, RS_PHASE, RS_PK_ON,
                                    RS_PK_SIG, RS_REJ, RS_S, RS_SPLIT, RS_STEPS, RS_T, RS_U1A, RS_UA, RS_UMAX, RS_XI1,
                                    RS_XI2, W_EV, W_FEV, W_RE, W_TMP, W_Y, W_YNEW)
from rockcli.kernels.linear_base import (advance, base_acceleration, coefficients, first_exceed, free_part, step_clear,
                                         velocity_zero)
from rockcli.kernels.polynomials import _first_exceed, _poly
from rockcli.kernels.rhs import _rhs_into
from rockcli.kernels.steps import (EV_FAILED, EV_IMPACT, EV_OVERTURN, _bounce, _close_step, _grown, _rocking_events,
                                   _seg, _shrink, _step_start, _to_impact, _to_overturn, _to_step_end)


# ---------------------------------------------------------------------------------------------
# Small accessors of the run record
# ---------------------------------------------------------------------------------------------
@kernel(inline='always')
def _hy(rs):
    """The anchor of the hysteretic elements (``rockcli.kernels.bearings``)."""
    return (rs[RS_UA], rs[RS_DIR], rs[RS_XI1], rs[RS_U1A], rs[RS_XI2], rs[RS_SPLIT])


@kernel(inline='always')
def _set_hy(rs, hy):
    rs[RS_UA] = hy[0]
    rs[RS_DIR] = hy[1]
    rs[RS_XI1] = hy[2]
    rs[RS_U1A] = hy[3]
    rs[RS_XI2] = hy[4]
    rs[RS_SPLIT] = hy[5]


@kernel(inline='always')
def _reanchor(fkind, prm, rs, u, d_new):
    """Anchor the hysteretic elements at ``u`` (reached on the current branch) for motion in ``d_new``."""
    if fkind >= FOUNDATION_BILINEAR:
        _set_hy(rs, reanchor(fkind, prm, _hy(rs), u, d_new))


@kernel
def _dp5_iso(fkind, phase, s, prm, seg, epar, hy, gz, t, h, W, i0, i1, r0):
    """The Dormand-Prince step on an isolated base (compiled once for this driver)."""
    return _dp5_step(_rhs_into, fkind, phase, s, prm, seg, epar, hy, gz, t, h, W, i0, i1, r0)


@kernel
def _restep_iso(fkind, phase, s, prm, seg, epar, hy, t, h, W, i0, i1):
    """The last step retaken to an event at ``t + h`` (:func:`rockcli.kernels.dopri._restep_rows`)."""
    _restep_rows(W)
    _dp5_iso(fkind, phase, s, prm, seg, epar, hy, 0.0, t, h, W, i0, i1, np.int64(W_RE))


# ---------------------------------------------------------------------------------------------
# The step and the phases
# ---------------------------------------------------------------------------------------------
@kernel
def _take_step(fkind, prm, ekind, epar, max_steps, rs, W, t_stop, nst):
    """One accepted Dormand-Prince step from ``rs[RS_T]`` inside ``[t, t_stop]``.

    Returns ``(ok, hs, last, sig_lim)``: the step size taken, whether it reached ``t_stop``, and
    the fraction of it that stands (1, or on a hysteretic base the reversal of u where it ends).
    ``ok`` is False when the step cap is reached first.
    """
    phase = int(rs[RS_PHASE])
    s = rs[RS_S]
    t = rs[RS_T]
    seg = _seg(rs)
    hyst = fkind >= FOUNDATION_BILINEAR
    i0 = 2 if phase == PHASE_STUCK else 0
    h = _step_start(_rhs_into, fkind, prm, ekind, epar, rs, W, _hy(rs))
    last = False
    hs = h
    err = 2.0
    sig_lim = 1.0
    gz = 0.0
    tol_u = 0.0
    if hyst:
        gz = z_sensitivity(fkind, prm, _hy(rs))
        uu = abs(W[W_Y, 2])
        tol_u = prm[P_RTOL] / (1.0 / max(uu, prm[P_SC0 + 2]) + gz)
        # resolve the knee of a bearing's loop (bearings.knee_step)
        h = min(h, knee_step(fkind, prm, _hy(rs), W[W_Y, 3], W[0, 3]))
    flips = 0
    steps = rs[RS_STEPS]
    rej = rs[RS_REJ]
    nrhs = rs[RS_NRHS]
    hy = _hy(rs)
    while steps + rej < max_steps:
        hs = h
        last = hs >= t_stop - t
        if last:
            hs = t_stop - t
        err = _dp5_iso(fkind, phase, s, prm, seg, epar, hy, gz, t, hs, W, i0, nst, np.int64(0))
        nrhs += 6
        if err <= 1.0 and hyst:
            code, sr = reversal_check(W, hs, rs[RS_DIR], tol_u)
            if code == REV_WRONG_START:
                # the base left the anchor against the guessed direction: take the other branch
                # (f(t, y) does not depend on it) and retake the step; twice means u barely moves
                # either way within the step: halve it
                rej += 1
                flips += 1
                if flips > 1:
                    h = 0.5 * hs
                    flips = 0
                _reanchor(fkind, prm, rs, W[W_Y, 2], -rs[RS_DIR])
                hy = _hy(rs)
                gz = z_sensitivity(fkind, prm, hy)
                tol_u = prm[P_RTOL] / (1.0 / max(abs(W[W_Y, 2]), prm[P_SC0 + 2]) + gz)
                continue
            if code == REV_AT:
                sig_lim = sr
                last = False
            u_end = W[W_YNEW, 2] if code != REV_AT else _poly(_dense(W, hs, np.int64(2), 1.0), sr)
            kr = knee_ratio(fkind, prm, hy, u_end, hs, W[W_Y, 3])
            if kr > 1.0:
                # the step ran through a knee of the bearing's loop unresolved: retake it shorter
                rej += 1
                h = hs * max(0.2, 0.9 / kr)
                sig_lim = 1.0
                continue
        if err <= 1.0:
            h = _grown(h, hs, err, last)
            break
        rej += 1
        h = hs * _shrink(err)
    if not _close_step(rs, h, rej, nrhs, steps, err):
        return False, hs, last, sig_lim
    if sig_lim < 1.0:
        # the step stands up to the reversal of u: its end state is the state there, retaken as a
        # step (the dense output keeps describing the whole step for the events inside it)
        _restep_iso(fkind, phase, s, prm, seg, epar, hy, t, sig_lim * hs, W, i0, nst)
        rs[RS_NRHS] += 6
        for i in range(nst):
            W[W_YNEW, i] = W[W_EV, i]
        rs[RS_NREV] += 1
    return True, hs, last, sig_lim


@kernel(inline='always')
def _after_stuck_step(fkind, prm, rs, W, out, hs, t_new, sig_lim, epar):
    """Stuck on an isolated base, after a step of the base: uplift when |a| crosses g tan(alpha)."""
    thr = prm[P_THR]
    if fkind >= FOUNDATION_BILINEAR:
        sig, su = hysteretic_uplift(fkind, prm, _hy(rs), _dense(W, hs, np.int64(2), 1.0), sig_lim, thr)
    else:
        # a(sigma) is linear in the states, so a quartic in sigma like them; every step is
        # checked (no pre-filter on the step ends)
        w = prm[P_W]
        xi = prm[P_XI]
        cu = _dense(W, hs, np.int64(2), 1.0)
        cv = _dense(W, hs, np.int64(3), 1.0)
        ca = (-w * w * cu[0] - 2.0 * xi * w * cv[0], -w * w * cu[1] - 2.0 * xi * w * cv[1],
              -w * w * cu[2] - 2.0 * xi * w * cv[2], -w * w * cu[3] - 2.0 * xi * w * cv[3],
              -w * w * cu[4] - 2.0 * xi * w * cv[4])
        sig, sa = _first_exceed(ca, thr)
        su = -sa  # the block pivots on the corner s = -sign(a)
    if (W[W_Y, 3] > 0.0) != (W[W_YNEW, 3] > 0.0):
        rs[RS_UMAX] = max(rs[RS_UMAX], _u_extremum(W, hs, sig_lim if sig < 0.0 else sig))
    if sig >= 0.0:
        # the state at the uplift with the accuracy of a step: retake the step to it, then onto the
        # root of |a| = g tan(alpha) (a = F: the block rides on the base)
        t = rs[RS_T]
        hy = _hy(rs)
        _restep_iso(fkind, np.int64(PHASE_STUCK), 0.0, prm, _seg(rs), epar, hy, t, sig * hs, W, np.int64(2),
                    np.int64(4))
        rs[RS_NRHS] += 6
        F, Fd = force_rate(fkind, prm, hy, W[W_EV, 2], W[W_EV, 3], W[W_FEV, 3])
        dt_e = (-su * thr - F) / Fd if Fd != 0.0 else 0.0
        dt_e = min(max(dt_e, -sig * hs), (1.0 - sig) * hs)
        _shift_event(W, dt_e, 2, 4)
        W[W_Y, 2] = W[W_EV, 2]
        W[W_Y, 3] = W[W_EV, 3]
        rs[RS_T] = t + sig * hs + dt_e
        rs[RS_S] = su
        rs[RS_PHASE] = PHASE_ROCKING
        _count_uplift(out, rs[RS_T])
        rs[RS_FRESH] = 1.0
        _reanchor(fkind, prm, rs, W[W_Y, 2], motion_direction(W[W_Y, 3], rs[RS_DIR]))
    else:
        rs[RS_T] = t_new
        for i in range(2, 4):
            W[W_Y, i] = W[W_YNEW, i]
            W[0, i] = W[6, i]
        if sig_lim < 1.0:
            rs[RS_FRESH] = 1.0  # W[6] is f at the end of the whole step, not at the reversal
            _reanchor(fkind, prm, rs, W[W_Y, 2], -rs[RS_DIR])
        else:
            _reanchor(fkind, prm, rs, W[W_Y, 2], motion_direction(W[W_Y, 3], rs[RS_DIR]))
    rs[RS_UMAX] = max(rs[RS_UMAX], abs(W[W_Y, 2]))


@kernel
def _linear_stuck_step(prm, rs, W, out, t_stop, dt, lbc):
    """Stuck on linear bearings under a record: the base advanced exactly to ``t_stop`` (the end of the
    sample interval; after the record at most ``dt`` on), or to the lift-off inside the step.

    The piecewise-exact solution of :mod:`rockcli.kernels.linear_base` (``lbc`` its coefficients for a
    whole sample interval ``dt``, computed once per run; a shorter step, after a rest, computes its
    own). Lift-off where ``|a|`` first exceeds ``g tan(alpha)`` inside the step (exact up to rounding:
    :func:`rockcli.kernels.linear_base.first_exceed`), the block pivoting on the corner ``-sign(a)``;
    the peak base displacement at a reversal inside the step
    (:func:`rockcli.kernels.linear_base.velocity_zero`). One step counts as one accepted step."""
    w = prm[P_W]
    xi = prm[P_XI]
    thr = prm[P_THR]
    t = rs[RS_T]
    seg = _seg(rs)
    b = seg[2]
    a0 = seg[1] + b * (t - seg[3])
    ulps = 1e-14 * (abs(t) + dt)  # (a whole interval, up to the rounding of t)
    h = t_stop - t
    t_end = t_stop
    if h > dt + ulps:  # after the record: sample-long steps
        h = dt
        t_end = t + dt
    c = lbc if abs(h - dt) <= ulps else coefficients(w, xi, h)
    u0 = W[W_Y, 2]
    v0 = W[W_Y, 3]
    a_s, ah, ahd, k = free_part(w, xi, u0, v0, a0, b)
    u1, v1 = advance(c, u0, v0, a0, b)
    tau = -1.0
    sa = 0.0
    if not step_clear(a_s, base_acceleration(w, xi, u1, v1), k, h, thr):
        tau, sa = first_exceed(w, xi, a_s, ah, ahd, k, a0, b, h, thr)
    span = h
    if tau >= 0.0:
        span = tau
        if tau < h:
            u1, v1 = advance(coefficients(w, xi, tau), u0, v0, a0, b)
    if (v0 > 0.0) != (v1 > 0.0):
        rs[RS_UMAX] = max(rs[RS_UMAX], abs(velocity_zero(w, xi, u0, v0, a0, b, span)))
    W[W_Y, 2] = u1
    W[W_Y, 3] = v1
    rs[RS_UMAX] = max(rs[RS_UMAX], abs(u1))
    rs[RS_STEPS] += 1
    rs[RS_FRESH] = 1.0  # W[0] is not kept up to date here
    if tau >= 0.0:
        rs[RS_T] = t + tau
        rs[RS_S] = -sa
        rs[RS_PHASE] = PHASE_ROCKING
        _count_uplift(out, rs[RS_T])
    else:
        rs[RS_T] = t_end


@kernel
def _hist_grid_linear(H, nh, kg, hdt, t0, u0, v0, seg, t_end, fkind, prm, hy, epar, W):
    """The grid rows (``HK_GRID``) at ``kg hdt, ... <= t_end`` of an exact stuck step from ``t0``
    (state ``u0, v0``; ground of the segment ``seg``): :func:`_hist_grid` for :func:`_linear_stuck_step`."""
    w = prm[P_W]
    xi = prm[P_XI]
    b = seg[2]
    a0 = seg[1] + b * (t0 - seg[3])
    while kg * hdt <= t_end:
        tg = kg * hdt
        u, v = advance(coefficients(w, xi, max(tg - t0, 0.0)), u0, v0, a0, b)
        W[W_TMP, 0] = 0.0
        W[W_TMP, 1] = 0.0
        W[W_TMP, 2] = u
        W[W_TMP, 3] = v
        H, nh = _hist_state(H, nh, tg, ground_at(tg, seg, epar), fkind, prm, hy, W, W_TMP, HK_GRID)
        kg += 1
    return H, nh, kg


@kernel(inline='always')
def _after_rocking_step(fkind, prm, rs, W, out, hs, t_new, sig_lim, nst, epar):
    """Rocking on an isolated base, after a step: the events in theta
    (:func:`rockcli.kernels.steps._rocking_events`) and the base's part of each. Returns the event
    code (``EV_*``); at an impact the state is left just before it (see :func:`_impact`)."""
    code, sig = _rocking_events(prm, rs, W, out, hs, t_new, sig_lim)
    if rs[RS_PK_ON] != 0.0:  # the state at a turning point of theta, for the history (W_TMP is kept below)
        _state_at(W, hs, rs[RS_PK_SIG], nst)
    if (W[W_Y, 3] > 0.0) != (W[W_YNEW, 3] > 0.0):
        rs[RS_UMAX] = max(rs[RS_UMAX], _u_extremum(W, hs, sig))
    if code == EV_OVERTURN:
        _to_overturn(rs, W, out, hs, sig, nst)
        _reanchor(fkind, prm, rs, W[W_Y, 2], motion_direction(W[W_Y, 3], rs[RS_DIR]))
    elif code == EV_FAILED:
        # the block never left theta = 0: back to the stuck phase at the end of the step,
        # keeping the total horizontal momentum (u_dot + gamma h theta_dot per unit mass); the
        # uplift still counts (the uplift condition held; the rotation is below resolution)
        rs[RS_T] = t_new
        W[W_Y, 2] = W[W_YNEW, 2]
        W[W_Y, 3] = W[W_YNEW, 3] + prm[P_GAMMA] * prm[P_H] * W[W_YNEW, 1]
        W[W_Y, 0] = 0.0
        W[W_Y, 1] = 0.0
        rs[RS_PHASE] = PHASE_STUCK
        rs[RS_S] = 0.0
        rs[RS_FRESH] = 1.0
        rs[RS_UMAX] = max(rs[RS_UMAX], abs(W[W_Y, 2]))
        _reanchor(fkind, prm, rs, W[W_Y, 2], motion_direction(W[W_Y, 3], rs[RS_DIR]))
    elif code == EV_IMPACT:
        _to_impact(_restep_iso, fkind, prm, rs, W, epar, _hy(rs), hs, sig, nst)
        # the bearings reach the impact point on the step's branch (u does not jump)
        _reanchor(fkind, prm, rs, W[W_Y, 2], rs[RS_DIR])
    else:
        _to_step_end(rs, W, t_new, nst)
        rs[RS_UMAX] = max(rs[RS_UMAX], abs(W[W_Y, 2]))
        if sig_lim < 1.0:
            rs[RS_FRESH] = 1.0
            _reanchor(fkind, prm, rs, W[W_Y, 2], -rs[RS_DIR])
        else:
            _reanchor(fkind, prm, rs, W[W_Y, 2], motion_direction(W[W_Y, 3], rs[RS_DIR]))
    return code


@kernel(inline='always')
def _impact(fkind, prm, rs, W, out, t_exc_end):
    """The impact at theta = 0 (state in ``W[W_Y]`` with theta_dot before it): the momentum map,
    the pivot switch and the rest rule (the base acceleration that could lift the block again is
    the bearing force, with the block's momentum handed to the base if it rests)."""
    thd1 = W[W_Y, 1]
    thd2, dud = impact_map(prm, thd1)
    W[W_Y, 3] += dud
    rs[RS_S] = -rs[RS_S]
    a_rest = base_force(fkind, prm, W[W_Y, 2], W[W_Y, 3] + prm[P_GAMMA] * prm[P_H] * thd2, _hy(rs))
    if _bounce(prm, rs, W, out, thd1, t_exc_end, a_rest, thd2, prm[P_THR]):
        W[W_Y, 3] += prm[P_GAMMA] * prm[P_H] * thd2
    rs[RS_UMAX] = max(rs[RS_UMAX], abs(W[W_Y, 2]))
    _reanchor(fkind, prm, rs, W[W_Y, 2], motion_direction(W[W_Y, 3], rs[RS_DIR]))
