"""The isolated-base driver: :func:`simulate_core` runs one scene on bearings as a loop over phases.

(A block on a rigid foundation runs in :mod:`rockcli.kernels.rigid`; what both share is in
:mod:`rockcli.kernels.steps`.) Phases and states (``W`` columns ``theta, theta_dot, u, u_dot``;
hysteretic bearings add their Bouc-Wen variables, which follow u exactly and live in the anchor
of the run record ``rs``):

* *stuck*: the block moves with its base (theta = theta_dot = 0); only the base is integrated
  (:func:`_after_stuck_step`), or, on linear bearings under a record, advanced exactly from sample to
  sample (:func:`_linear_stuck_step`, :mod:`rockcli.kernels.linear_base`).
* *rocking* about the corner ``s`` (+1 right, -1 left): all four states (:func:`_after_rocking_step`).

Each pass of the loop: move to the excitation segment that contains t
(:func:`rockcli.kernels.steps._advance_segment`), apply the end-of-run rule (:func:`_end_of_run`),
then take one Dormand-Prince step (:func:`_take_step`) and handle the events inside it. On a
hysteretic base a step also ends where the base reverses (the Bouc-Wen variables follow u exactly
only while u moves one way); the bearings are re-anchored after every step (:func:`_reanchor`).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.bearings import (base_force, bearing_energy, free_disp_bound, free_force_bound,
                                      force_rate, initial_anchor, knee_ratio, knee_step, motion_direction, reanchor,
                                      z_sensitivity)
from rockcli.kernels.dopri import _dense, _dp5_step, _restep_rows, _shift_event, _state_at
from rockcli.kernels.events import (REV_AT, REV_WRONG_START, _count_uplift, _hist_grid, _hist_grid_cut, _hist_peak,
                                    _hist_state, _u_extremum, hysteretic_uplift, impact_map, reversal_check)
from rockcli.kernels.ground import _impulse_left, ground_at
from rockcli.kernels.jit import kernel
from rockcli.kernels.linear_base import (advance, base_acceleration, base_norm, base_norm_of, coefficients, first_exceed,
                                         free_part, linear_base_table, step_clear, velocity_zero)
from rockcli.kernels.layout import (EXC_RECORD, FOUNDATION_BILINEAR, FOUNDATION_LINEAR, H_KIND, H_T, HK_GRID, HK_IMPACT,
                                    HK_STATE, HK_UPLIFT,
                                    O_T_SETTLED, P_ALPHA, P_COSA, P_G, P_HDT,
                                    P_GAMMA, P_H, P_R, P_RTOL, P_SC0, P_TH0, P_THD0, P_THR, P_W, P_XI, PHASE_ROCKING,
                                    PHASE_STUCK, RS_DIR, RS_FRESH, RS_NREV, RS_NRHS, RS_PHASE, RS_PK_ON, RS_PK_SIG,
                                    RS_PK_T, RS_REJ, RS_S, RS_SEG_END, RS_SETTLED,
                                    RS_SPLIT, RS_STATUS, RS_STEPS, RS_T, RS_THMAX, RS_U1A, RS_UA, RS_UMAX, RS_XI1,
                                    RS_XI2, STATUS_MAX_STEPS, W_EV, W_FEV, W_RE, W_TMP, W_Y, W_YNEW)
from rockcli.kernels.layout import E_AP, P_K1, P_K2, P_Q1, P_Q2, RS_J, RS_SEG  # the early stops P9, P9s
from rockcli.kernels.polynomials import _first_exceed, _poly
from rockcli.kernels.rhs import _rhs_into
from rockcli.kernels.steps import (EV_FAILED, EV_IMPACT, EV_OVERTURN, _advance_segment, _bounce, _close_step,
                                   _finish, _grown, _initial_state, _out_of_time, _rocking_events, _row_kind, _seg,
                                   _shrink, _start, _step_start, _to_impact, _to_overturn, _to_step_end)


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
def _history_row(H, nh, fkind, prm, rs, epar, W, row, kind):
    """Append the state ``W[row]`` at ``rs[RS_T]`` to the history, with the bearing's z and force."""
    t = rs[RS_T]
    return _hist_state(H, nh, t, ground_at(t, _seg(rs), epar), fkind, prm, _hy(rs), W, row, kind)


@kernel
def _mark_uplift(H, nh, t):
    """Mark the last history row as the uplift when it is a plain step row at ``t``."""
    if nh > 0 and H[nh - 1, H_KIND] == HK_STATE and H[nh - 1, H_T] == t:
        H[nh - 1, H_KIND] = HK_UPLIFT


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
# Phases
# ---------------------------------------------------------------------------------------------
@kernel(inline='always')
def _end_of_run(fkind, prm, ekind, epar, jtab, dt, lin, t_exc_end, early, want_history, t_show_end, t_horizon,
                max_steps, rs, W, out):
    """The end-of-run rule on an isolated base (P3, P3s, P5, P8, and with ``early`` P9, P9s, in
    :func:`simulate_core`): True when the run ends now."""
    t = rs[RS_T]
    phase = rs[RS_PHASE]
    alpha = prm[P_ALPHA]
    thr = prm[P_THR]
    w = prm[P_W]
    if early and rs[RS_SETTLED] == 0.0 and phase == PHASE_STUCK:
        proven, u_bound = _early_stuck(fkind, prm, ekind, epar, jtab, dt, lin, rs, W)
        if proven:  # P9, P9s: the block never lifts again; theta_max and the impacts are final
            rs[RS_SETTLED] = 1.0
            out[O_T_SETTLED] = t
            if not u_bound <= rs[RS_UMAX] * (1.0 + 1e-9):
                rs[RS_UMAX] = math.nan  # the base's peak is not final: unknown, not the peak so far
            return True
    if rs[RS_SETTLED] == 0.0 and t >= t_exc_end:
        settled = False
        if phase == PHASE_STUCK:
            if fkind >= FOUNDATION_BILINEAR:
                if free_force_bound(fkind, prm, _hy(rs), W[W_Y, 2], W[W_Y, 3]) < thr:
                    settled = True  # P3s
            elif w * math.sqrt(1.0 + 4.0 * prm[P_XI] * prm[P_XI]) * math.sqrt(W[W_Y, 3] ** 2 + w * w * W[W_Y, 2] ** 2) < thr:
                settled = True  # P3
        if not settled and rs[RS_THMAX] > 0.0:
            level = min(rs[RS_THMAX], alpha)
            if abs(W[W_Y, 0]) < level:
                if _free_energy(fkind, prm, rs, W) < _barrier(prm, level, prm[P_GAMMA]):
                    settled = True  # P5
                elif (fkind == FOUNDATION_LINEAR and prm[P_GAMMA] == 0.0
                      and _decoupled_energy_bound(prm, rs, W) < _barrier(prm, level, 1.0)):
                    settled = True  # P8
        if settled:
            rs[RS_SETTLED] = 1.0
            out[O_T_SETTLED] = t
    if rs[RS_SETTLED] != 0.0 and (not want_history or t >= t_show_end):
        # the verdict is settled; the peak base displacement is final once the free base's energy
        # bound on every later |u| cannot exceed it (or, undamped, after one more period, in which
        # the base reaches its amplitude)
        more = False
        if phase == PHASE_STUCK and t < out[O_T_SETTLED] + 2.0 * math.pi / w and t < t_horizon:
            if fkind >= FOUNDATION_BILINEAR:
                more = free_disp_bound(fkind, prm, _hy(rs), W[W_Y, 2], W[W_Y, 3]) > rs[RS_UMAX] * (1.0 + 1e-9)
            else:
                more = math.sqrt(W[W_Y, 3] ** 2 + w * w * W[W_Y, 2] ** 2) > w * rs[RS_UMAX] * (1.0 + 1e-9)
        if not more:
            return True
        if early:  # a verdict-only early run does not follow the base to its peak: unknown
            rs[RS_UMAX] = math.nan
            return True
    return _out_of_time(rs, t_horizon, max_steps)


#: Relative margin of the early stops P9, P9s below the uplift acceleration (see P9).
EARLY_MARGIN = 1e-6


@kernel
def _early_stuck(fkind, prm, ekind, epar, jtab, dt, lin, rs, W):
    """P9, P9s (block stuck, ``early`` only): ``(proven, u_bound)``: True when no later base acceleration
    can reach ``g tan(alpha)`` (to within :data:`EARLY_MARGIN`), and a bound of every later ``|u|`` [m].

    Linear base: every later norm ``S`` of the base (:func:`rockcli.kernels.linear_base.base_norm`) is at
    most ``S + J`` (``J`` the remaining ground impulse), and at a sample of a record at most ``|s|``
    times the largest later norm of the record's linear response (``lin``,
    :func:`rockcli.kernels.linear_base.linear_base_table`) plus the norm of the difference from it.
    Hysteretic base: every later ``sqrt(2 E) <= sqrt(2 E) + J`` (P9s) bounds the force.
    """
    t = rs[RS_T]
    u = W[W_Y, 2]
    v = W[W_Y, 3]
    w = prm[P_W]
    thr = prm[P_THR] * (1.0 - EARLY_MARGIN)
    J = _impulse_left(ekind, jtab, epar, dt, t)
    if fkind == FOUNDATION_LINEAR:
        c, k_a, k_u = base_norm(prm[P_XI])
        B = base_norm_of(c, w, u, v) + J
        k = int(rs[RS_J])
        if lin.shape[0] > 0 and t == rs[RS_SEG + 3] and k < lin.shape[0]:  # at sample k of the record
            s = epar[E_AP]
            B = min(B, abs(s) * lin[k, 2] + base_norm_of(c, w, u - s * lin[k, 0], v - s * lin[k, 1]))
        return w * k_a * B < thr, k_u * B / w
    root = w * free_disp_bound(fkind, prm, _hy(rs), u, v) + J  # bounds every later sqrt(2 E)
    if fkind == FOUNDATION_BILINEAR:
        F = w * root + prm[P_Q1]
    else:
        F = min(math.sqrt(prm[P_K1]) * root + prm[P_Q1], math.sqrt(prm[P_K2]) * root + prm[P_Q2])
    return F < thr, root / w


@kernel
def _free_energy(fkind, prm, rs, W):
    """Mechanical energy of block + base per unit total mass ``m + m_b`` [J/kg] at ``W[W_Y]`` (P5):
    kinetic ``u'^2/2 + gamma R cos(A) u' theta' + (2/3) gamma R^2 theta'^2`` (block centre of mass at
    ``u + x`` with Eq 9's x, ``I_cm = m R^2/3``), the block's height above rest
    ``gamma g R (cos A - cos alpha)``, ``A = s alpha - theta``, and the energy stored in the bearings."""
    th = W[W_Y, 0]
    thd = W[W_Y, 1]
    ud = W[W_Y, 3]
    gR = prm[P_GAMMA] * prm[P_R]
    A = rs[RS_S] * prm[P_ALPHA] - th if rs[RS_PHASE] == PHASE_ROCKING else prm[P_ALPHA]
    kin = 0.5 * ud * ud + gR * math.cos(A) * ud * thd + (2.0 / 3.0) * gR * prm[P_R] * thd * thd
    pot = gR * prm[P_G] * (math.cos(A) - prm[P_COSA])
    return kin + pot + bearing_energy(fkind, prm, _hy(rs), W[W_Y, 2])


@kernel
def _decoupled_energy_bound(prm, rs, W):
    """P8 (gamma = 0, linear bearings, ground still): a bound on the block's energy per unit block mass
    [J/kg] at every later time, ``(sqrt(E0) + sqrt(3/2)/2 J)^2`` with ``E0 = (2/3) R^2 theta'^2 + g R
    (cos A - cos alpha)`` now and ``J >= integral of |u''|`` over all later times of the free base
    (see P8 in :func:`simulate_core`); ``inf`` for an undamped base."""
    xi = prm[P_XI]
    if not xi > 0.0:
        return math.inf
    w = prm[P_W]
    c = xi if xi <= 0.5 else xi / (1.0 + xi * xi)
    q11 = 4.0 * xi - 2.0 * c
    q12 = 2.0 * c * xi
    q22 = 2.0 * c
    bq = q11 + q22 - 2.0 * c * q12
    det = q11 * q22 - q12 * q12
    lam = 2.0 * det / (bq + math.sqrt(max(bq * bq - 4.0 * (1.0 - c * c) * det, 0.0)))
    u = W[W_Y, 2]
    ud = W[W_Y, 3]
    l0 = ud * ud + 2.0 * c * w * u * ud + (w * u) ** 2
    J = math.sqrt(1.0 + 4.0 * xi * xi) * math.sqrt(max(l0, 0.0) / (1.0 - c)) * 2.0 / lam
    R = prm[P_R]
    e0 = 0.0
    if rs[RS_PHASE] == PHASE_ROCKING:
        A = rs[RS_S] * prm[P_ALPHA] - W[W_Y, 0]
        e0 = (2.0 / 3.0) * R * R * W[W_Y, 1] ** 2 + R * prm[P_G] * (math.cos(A) - prm[P_COSA])
    root = math.sqrt(max(e0, 0.0)) + 0.5 * math.sqrt(1.5) * J
    return root * root


@kernel
def _barrier(prm, level, weight):
    """Energy the block needs to reach ``|theta| = level <= alpha`` from rest: per unit total mass with
    ``weight = gamma`` (P5), per unit block mass with ``weight = 1`` (P8) [J/kg]."""
    return weight * prm[P_R] * prm[P_G] * (math.cos(prm[P_ALPHA] - level) - prm[P_COSA])


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
    The run ends when the verdict is *proven* (or at overturning). Each proof below is a small
    theorem; the code checks exactly its assumptions. A history run goes on after the proof until
    exactly ``t_exc_end + tail`` to show the free motion; nothing after a proof can change the
    verdict, ``theta_max`` or ``n_impacts``, and nothing before it depends on the mode or on
    ``tail`` (the same steps are taken). A run that reaches
    ``t_exc_end + horizon`` unproven ends there with ``O_SETTLED = 0`` (e.g. an undamped base that
    keeps lifting the block): reported, never silently called safe.

    P3 (linear isolated base, ground still, block stuck). The block moves with its base, a free
       damped oscillator ``u'' + 2 xi w u' + w^2 u = 0`` (any gamma < 1: the block rides on the base)
       whose energy ``(u'^2 + w^2 u^2)/2`` never grows for any ``xi >= 0``. The absolute base
       acceleration ``|a| = |w^2 u + 2 xi w u'| <= w sqrt(1 + 4 xi^2) sqrt(u'^2 + w^2 u^2)``
       (Cauchy-Schwarz), so once this bound is below ``g tan(alpha)`` the block can never be lifted
       again. The peak base displacement is final only once ``sqrt(u'^2 + w^2 u^2)/w``, which
       bounds every later ``|u|``, is below it, or one base period later: the run follows the free
       base until then (2 states, a few steps).
    P3s (hysteretic base: single concave, lead-rubber, double concave; ground still, block stuck).
       The free base obeys ``u'' = F``; with the Bouc-Wen variables following u (``c = gamma_bw - beta
       >= 0``), F along any stretch where u moves one way is a decreasing function of u alone whose
       tangent stiffness ``K = -dF/du > 0`` never grows along the stretch (``g`` of every element
       falls as its ``|z|`` grows on loading and stays or falls on unloading; two elements in series
       have ``K = K1 K2/(K1 + K2)``, non-increasing in each). Take a stretch from the state
       ``(F0, v0)`` to the next reversal ``v = 0``, ``F = F1``. Along it ``d(v^2/2) = F du = -F dF/K``.
       Split at ``F = 0``, where ``K = K_0``: before it (if F0 has the sign of v) the force falls from
       F0 to 0 with ``K >= K_0``, after it it goes from 0 to F1 with ``K <= K_0``, so ``v0^2/2 >=
       (F1^2 - F0^2)/(2 K_0)``; if F0 opposes v the whole stretch has ``K <= K`` (now) and
       ``v0^2/2 >= (F1^2 - F0^2)/(2 K)``. With ``K_0 <= K`` (now): ``F1^2 <= F0^2 + K v0^2``, F is
       monotone on the stretch, and from a reversal (``v0 = 0``) on every later stretch has
       ``|F| <= |F1|``. Hence ``|a| = |F| <= sqrt(F0^2 + K v0^2)`` for all later times
       (:func:`rockcli.kernels.bearings.free_force_bound`; for a linear spring it is P3's bound with
       xi = 0), and once it is below ``g tan(alpha)`` the block can never be lifted again. Steps
       end at the reversals of u, where ``v0 ~ 0`` and the bound is the force itself, so it proves
       the verdict as soon as the base rests in its dish with ``|F| < g tan(alpha)``. The peak base
       displacement is final once ``sqrt(2 E)/w`` is below it (``E = v^2/2 + sum (k_i u_i^2 + q_i u_yi
       z_i^2)/2`` never grows: ``dE/dt = -sum q_i |z_i|^n (gamma_bw |u_i' z_i| + beta u_i' z_i) <= 0``
       for ``gamma_bw >= |beta|``), or one period ``2 pi/w`` later.
    P5 (isolated base, linear or hysteretic, ground still, after an uplift, any phase). Per unit total mass the energy
       of block + base, ``E = u'^2/2 + gamma R cos(A) u' theta' + (2/3) gamma R^2 theta'^2 + gamma g R (cos A
       - cos alpha) + E_b`` (kinetic energy of base and block, ``I_cm = m R^2/3``; the block's height
       above rest; ``E_b`` the energy stored in the bearings, :func:`rockcli.kernels.bearings.bearing_energy`),
       never grows with the ground still: the bearings are passive (P3s), an impact keeps the horizontal
       momentum (and, with Housner's rule, the angular momentum about the new pivot) and changes the kinetic
       energy by ``gamma (2 R^2/3 - gamma h^2/2) (eta^2 - 1) theta'^2 <= 0`` for every ``0 <= eta <= 1``, so for
       every restitution ``0 < E <= 1`` (:mod:`rockcli.models.impact`; tests/test_solver.py, tests/test_restitution.py),
       a rest or a failed uplift keeps the momentum and
       loses ``theta'^2 gamma (2 R^2/3 - gamma h^2/2) > 0``. The block's height term alone is
       ``gamma g R (cos(alpha - |theta|) - cos alpha)``, increasing in ``|theta|`` up to alpha. Hence if
       ``|theta| < L = min(theta_max, alpha)`` now and ``E`` is below the height term at ``L``, the block
       can never reach ``|theta| = L``: it survives and ``theta_max`` is final. Past alpha the same
       energy means the block falls away (issue 9): the condition ``|theta| < L`` is essential. (It ends the long free rocking of slender
       blocks on heavy-ish bases, ``gamma`` not small; for ``gamma -> 0`` the bearings' energy dominates
       and it never applies. It holds for linear bearings too (viscous damping only dissipates, ``-c u'^2``), and
       is applied to every isolated base.)
    P8 (linear bearings, gamma = 0, xi > 0, ground still, after an uplift, any phase): P5 for the decoupled
       block, whose weight in P5's energy is zero. The base is then a free oscillator that the block
       does not act on: ``u'' = -w^2 u - 2 xi w u'``, which is also its absolute acceleration ``a``.
       (i) With ``x = u'``, ``y = w u`` and ``Lc = x^2 + 2 c x y + y^2`` (``0 < c < 1``),
       ``dLc/dt = -w Q`` with ``Q = (4 xi - 2 c) x^2 + 4 c xi x y + 2 c y^2``; with ``c = xi`` for
       ``xi <= 1/2`` (then ``Q = 2 xi Lc``) and ``c = xi/(1 + xi^2)`` above (``Q`` positive definite),
       ``Q >= lam Lc`` with ``lam`` the smaller generalised eigenvalue of the two forms, so
       ``Lc(t) <= Lc(0) exp(-lam w t)``. As ``|a| <= w sqrt(1 + 4 xi^2) sqrt(x^2 + y^2)`` and
       ``x^2 + y^2 <= Lc/(1 - c)``, every later ``integral |a| dt <= J = sqrt(1 + 4 xi^2) sqrt(Lc/(1 -
       c)) 2/lam``. (ii) Per unit block mass the block's energy ``E = (2/3) R^2 theta'^2 + g R (cos A -
       cos alpha)`` obeys ``(4/3) R^2 theta'' = -g R sin A - R cos(A) a``, so ``dE/dt = -R cos(A) a theta'``;
       while ``|theta| <= 2 alpha`` the height term is >= 0, so ``theta'^2 <= 3 E/(2 R^2)`` and
       ``d sqrt(E)/dt <= sqrt(3/2) |a|/2``; impacts only lose kinetic energy (gamma = 0 is Eq 4's
       impact, ``theta'+ = eta theta'-`` with ``eta <= 1`` also for a given restitution E <= 1) and a
       rest or an uplift sets or starts it at 0. Hence ``E <= (sqrt(E0) + sqrt(3/2) J/2)^2``
       for all later times (:func:`_decoupled_energy_bound`), and if ``|theta| < L = min(theta_max,
       alpha)`` and this bound is below ``g R (cos(alpha - L) - cos alpha)``, the block's height at
       ``L``, the block never reaches ``L`` (the bound keeps ``|theta| < L <= 2 alpha`` throughout): it
       survives and ``theta_max`` is final. (It ends the minutes of free rocking of very slender blocks,
       alpha 1-2 deg, which with gamma = 0 otherwise ran to the horizon NOT PROVEN.)
    P9 (``early`` only, linear bearings, block stuck, at any time: during the excitation too). While the
       block rides on its base the base is the oscillator ``u'' + 2 xi w u' + w^2 u = -ag`` (any gamma < 1:
       gamma does not enter it), and the block lifts only where ``|a| > g tan(alpha)``, ``a = -(w^2 u + 2 xi
       w u')`` the absolute base acceleration. Take the norm ``S^2 = v^2 + 2 c v y + y^2 = (v + c y)^2 + (1
       - c^2) y^2`` (``v = u'``, ``y = w u``, ``0 <= c < 1`` as in P8, :func:`rockcli.kernels.linear_base.base_norm`):
       ``dS^2/dt = -w Q - 2 (v + c y) ag`` with ``Q >= 0`` (P8 (i)), so ``dS/dt <= |ag|`` (``|v + c y| <=
       S``), and S never grows with the ground still; ``|a| <= k_a w S`` and ``|u| <= k_u S/w`` (the largest
       of a linear form over the ellipse ``S = 1``). Two bounds of every later S follow: (i) ``S + J``, J
       the remaining ground impulse (:func:`rockcli.kernels.ground._impulse_left`); (ii) on a record, at a
       sample ``t_k``: write the state as ``s z_lin(t_k) + d``, ``z_lin`` the response of the base alone to
       the record of unit scale from rest (:func:`rockcli.kernels.linear_base.linear_base_table`, exact steps
       between samples) and s the scale factor; while the block rides, the state is ``s z_lin(t') +
       d(t')`` with ``d(t')`` the free motion from d (superposition: both obey the same linear equation),
       so ``S <= |s| S*_k + S(d)``, ``S*_k`` the table's bound of every later ``S(z_lin)`` (inside a sample
       interval S grows by at most ``int |ag| <= dt (|a_j| + |a_j+1|)/2``; after the record it never
       grows). (ii) is nearly exact when the block has not lifted (``d = 0``) or has barely moved a heavy
       base (gamma small). If ``k_a w B < g tan(alpha)`` with B the smaller bound, ``|a|`` stays below
       ``g tan(alpha)`` for as long as the block rides, so it rides for ever: it never lifts again. The
       verdict (``no_uplift`` if it never lifted, else ``rocked``), ``theta_max`` and its time, the impacts,
       uplifts and rests are then final (``peak_final`` stays True) and the run ends; ``t_settled`` is the
       time of the proof. The peak base displacement is final only if ``k_u B/w`` does not exceed it, else
       it is NaN (unknown, never the peak so far). Checked exactly: ``early``, the block stuck, linear
       bearings (any ``xi >= 0``), (ii) only on a record and only at a sample (``t`` at the start of the
       record's sample interval). The bound must stay below ``g tan(alpha) (1 - 1e-6)``
       (:data:`EARLY_MARGIN`): the theorem is about the exact motion from the current state, which the
       run, continued, follows to the integrator's tolerance (and the table to rounding, ~1e-13); the
       margin leaves a grazing later peak, within 1e-6 of the threshold, to the integration itself.
    P9s (``early`` only, sliding and lead-rubber bearings, block stuck). With P3s's energy ``E = v^2/2 +
       sum (k_i u_i^2 + q_i u_yi z_i^2)/2`` of the base and bearings, while the block rides ``dE/dt = -ag v
       - (the dissipation, >= 0 for gamma_bw >= |beta|)``, so ``d sqrt(2 E)/dt <= |ag|`` and every later
       ``sqrt(2 E) <= r = sqrt(2 E) + J``. One element: ``F = -(w^2 u + Q z)`` with ``|z| <= 1`` (``A = 1``,
       ``beta + gamma_bw = 1``; both conditions are checked by :mod:`rockcli.models.limits`) and ``w |u| <=
       sqrt(2 E)``, so ``|F| <= w r + Q``; two in series carry the same force ``-(k_i u_i + Q_i z_i)`` and
       ``sqrt(k_i) |u_i| <= sqrt(2 E)``, so ``|F| <= min_i (sqrt(k_i) r + Q_i)``. Below ``g tan(alpha) (1 -
       1e-6)`` the block never lifts again (as P9); ``|u| <= r/w``. P9's superposition (ii) does not carry
       over (the bearings are not linear), so P9s proves the verdict only once the rest of the record is
       weak: ``w r + Q`` below the uplift acceleration.
    Not covered: a block still rocking during the excitation on an isolated base. With gamma small (the
    default 0.01) P5's energy is nearly all the base's, and P8's bound of the block's own energy needs
    ``int |a|`` of the base over the rest of the record, which the moving ground keeps large; the run
    follows the rocking until the block rests (the rest rule) and P9 applies from then on.

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
