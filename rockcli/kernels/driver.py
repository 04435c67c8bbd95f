"""The scene driver: :func:`simulate_core` runs one scene as a loop over phases.

Phases and states (``W`` columns ``theta, theta_dot, u, u_dot``; hysteretic bearings add their
Bouc-Wen variables, which follow u exactly and live in the anchor of the run record ``rs``):

* *stuck*: the block moves with its base (theta = theta_dot = 0). On a rigid foundation nothing
  is integrated: the ground acceleration is scanned for the uplift condition
  (:func:`_stuck_rigid`). On an isolated base only the base is integrated (:func:`_after_stuck_step`).
* *rocking* about the corner ``s`` (+1 right, -1 left): ``theta, theta_dot`` on a rigid foundation,
  all four on an isolated base (:func:`_after_rocking_step`).

Each pass of the loop: move to the excitation segment that contains t (:func:`_advance_segment`),
apply the end-of-run rule (:func:`_end_of_run`), then either scan (rigid, stuck) or take one
Dormand-Prince step (:func:`_take_step`) and handle the events inside it. On a hysteretic base a
step also ends where the base reverses (the Bouc-Wen variables follow u exactly only while u
moves one way); the bearings are re-anchored after every step (:func:`_reanchor`).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from rockcli.kernels.bearings import (base_force, bearing_energy, element_states, free_disp_bound, free_force_bound,
                                      force_rate, initial_anchor, knee_ratio, knee_step, reanchor, z_sensitivity)
from rockcli.kernels.dopri import _dense, _dp5_step, _restep, _shift_event, _state_at
from rockcli.kernels.events import (REV_AT, REV_WRONG_START, _count_uplift, _hist_push, _u_extremum,
                                    comes_to_rest, hysteretic_uplift, impact_map, reversal_check)
from rockcli.kernels.ground import _ground, _impulse_left, _pulse_segment, _rigid_uplift
from rockcli.kernels.polynomials import _first_down, _first_exceed, _poly
from rockcli.kernels.rhs import _rhs_into
from rockcli.kernels.layout import (E_AP, E_TP, EXC_RECORD, FOUNDATION_BILINEAR, FOUNDATION_RIGID, N_HIST, N_OUT,
                                    N_RS, N_W, O_N_IMPACTS, O_N_IMPACTS_ALL, O_N_RESTS, O_N_REVERSALS, O_N_UPLIFTS,
                                    O_NRHS, O_PEAK_FINAL, O_REJECTED, O_SETTLED, O_STATUS, O_STEPS, O_T_END,
                                    O_T_EXCEED, O_T_OVERTURN, O_T_SETTLED, O_T_THETA_MAX, O_T_UPLIFT, O_THETA_END,
                                    O_THETA_MAX, O_U_END, O_U_MAX, O_UPLIFTED, P_ALPHA, P_COSA, P_ETA, P_G, P_GAMMA, P_SINA,
                                    P_H, P_P2, P_R, P_RTOL, P_SC0, P_THR, P_W, P_XI, PHASE_ROCKING, PHASE_STUCK, RS_DIR,
                                    RS_FRESH, RS_H, RS_J, RS_NREV, RS_NRHS, RS_PEAK_FINAL, RS_PHASE,
                                    RS_REJ, RS_S, RS_SEG, RS_SEG_END, RS_SETTLED, RS_SPLIT, RS_STATUS, RS_STEPS,
                                    RS_T, RS_THMAX, RS_U1A, RS_UA, RS_UMAX, RS_XI1, RS_XI2, SEG_LINEAR,
                                    STATUS_DONE, STATUS_MAX_STEPS, STATUS_OVERTURNED, W_EV, W_FEV, W_TMP, W_Y, W_YNEW)


# ---------------------------------------------------------------------------------------------
# Small accessors of the run record
# ---------------------------------------------------------------------------------------------
@njit(cache=True, inline='always')
def _seg(rs):
    return (rs[RS_SEG], rs[RS_SEG + 1], rs[RS_SEG + 2], rs[RS_SEG + 3])


@njit(cache=True, inline='always')
def _set_seg(rs, seg, seg_end):
    rs[RS_SEG] = seg[0]
    rs[RS_SEG + 1] = seg[1]
    rs[RS_SEG + 2] = seg[2]
    rs[RS_SEG + 3] = seg[3]
    rs[RS_SEG_END] = seg_end


@njit(cache=True, inline='always')
def _hy(rs):
    """The anchor of the hysteretic elements (``rockcli.kernels.bearings``)."""
    return (rs[RS_UA], rs[RS_DIR], rs[RS_XI1], rs[RS_U1A], rs[RS_XI2], rs[RS_SPLIT])


@njit(cache=True, inline='always')
def _set_hy(rs, hy):
    rs[RS_UA] = hy[0]
    rs[RS_DIR] = hy[1]
    rs[RS_XI1] = hy[2]
    rs[RS_U1A] = hy[3]
    rs[RS_XI2] = hy[4]
    rs[RS_SPLIT] = hy[5]


@njit(cache=True, inline='always')
def _reanchor(fkind, prm, rs, u, d_new):
    """Anchor the hysteretic elements at ``u`` (reached on the current branch) for motion in ``d_new``."""
    if fkind >= FOUNDATION_BILINEAR:
        _set_hy(rs, reanchor(fkind, prm, _hy(rs), u, d_new))


@njit(cache=True, inline='always')
def _direction(rs, ud):
    """Direction of motion for the next step: the sign of u_dot (the current one if it is 0)."""
    if ud > 0.0:
        return 1.0
    if ud < 0.0:
        return -1.0
    return rs[RS_DIR]


@njit(cache=True)
def _history_row(H, nh, fkind, prm, rs, epar, W, row):
    """Append the state ``W[row]`` at ``rs[RS_T]`` to the history, with the bearing's z and force."""
    t = rs[RS_T]
    ag = _ground(t, _seg(rs), epar)
    z1 = 0.0
    z2 = 0.0
    fb = 0.0
    if fkind != FOUNDATION_RIGID:
        u = W[row, 2]
        hy = _hy(rs)
        fb = -base_force(fkind, prm, u, W[row, 3], hy)
        if fkind >= FOUNDATION_BILINEAR:
            z1, z2, _ = element_states(fkind, prm, hy, u)
    return _hist_push(H, nh, t, ag, W, row, z1, z2, fb)


# ---------------------------------------------------------------------------------------------
# Phases
# ---------------------------------------------------------------------------------------------
@njit(cache=True, inline='always')
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


@njit(cache=True, inline='always')
def _end_of_run(fkind, prm, ekind, epar, jtab, dt, t_exc_end, early, want_history, t_show_end, t_horizon,
                max_steps, rs, W, out):
    """The end-of-run rule (P1-P6, P3s in :func:`simulate_core`): True when the run ends now."""
    isolated = fkind != FOUNDATION_RIGID
    t = rs[RS_T]
    phase = rs[RS_PHASE]
    alpha = prm[P_ALPHA]
    p2 = prm[P_P2]
    thr = prm[P_THR]
    w = prm[P_W]
    if rs[RS_SETTLED] == 0.0:
        settled = False
        if t >= t_exc_end:
            if phase == PHASE_STUCK:
                if not isolated:
                    settled = True  # P1
                elif fkind >= FOUNDATION_BILINEAR:
                    if free_force_bound(fkind, prm, _hy(rs), W[W_Y, 2], W[W_Y, 3]) < thr:
                        settled = True  # P3s
                elif w * math.sqrt(1.0 + 4.0 * prm[P_XI] * prm[P_XI]) * math.sqrt(W[W_Y, 3] ** 2 + w * w * W[W_Y, 2] ** 2) < thr:
                    settled = True  # P3
            elif not isolated and abs(W[W_Y, 0]) < alpha:
                th = W[W_Y, 0]
                thd = W[W_Y, 1]
                En = 0.5 * thd * thd + p2 * math.cos(alpha - abs(th))
                if th * thd < 0.0:  # heading for the pivot: the impact is certain
                    c_a = p2 * prm[P_COSA]
                    En = c_a + prm[P_ETA] ** 2 * (En - c_a)
                if En < p2:  # P2
                    pk = alpha - math.acos(En / p2)
                    if pk > rs[RS_THMAX]:
                        rs[RS_THMAX] = pk
                        out[O_T_THETA_MAX] = np.nan
                    settled = True
            if not settled and isolated and rs[RS_THMAX] > 0.0:
                level = min(rs[RS_THMAX], alpha)
                if abs(W[W_Y, 0]) < level and _free_energy(fkind, prm, rs, W) < _barrier(prm, level):
                    settled = True  # P5
        if not settled and early and not isolated and out[O_UPLIFTED] != 0.0:
            c_imp = p2 / (math.sqrt(2.0) * prm[P_G])  # P4, P6: dX/dt <= c_imp |ag|
            imp = c_imp * _impulse_left(ekind, jtab, epar, dt, t)
            x_bar = math.sqrt(p2 * (1.0 - prm[P_COSA]))  # P4: E < p^2  <=>  X < x_bar
            if phase == PHASE_STUCK:
                if imp < x_bar:
                    settled = True  # P4
                    rs[RS_PEAK_FINAL] = 0.0
            else:
                ath = abs(W[W_Y, 0])
                En = 0.5 * W[W_Y, 1] ** 2 + p2 * math.cos(alpha - ath)
                if ath < alpha:
                    if math.sqrt(max(0.0, En - p2 * prm[P_COSA])) + imp < x_bar:
                        settled = True  # P4
                        rs[RS_PEAK_FINAL] = 0.0
                elif (math.sqrt(max(0.0, En - p2 * prm[P_SINA])) + imp < math.sqrt(p2 * (1.0 - prm[P_SINA]))
                      or (imp == 0.0 and rs[RS_S] * W[W_Y, 1] >= 0.0)):
                    # P6: it falls; the time it lands is not computed
                    rs[RS_STATUS] = STATUS_OVERTURNED
                    rs[RS_THMAX] = 0.5 * math.pi
                    rs[RS_PEAK_FINAL] = 0.0
                    out[O_T_SETTLED] = t
                    return True
        if settled:
            rs[RS_SETTLED] = 1.0
            out[O_T_SETTLED] = t
    if rs[RS_SETTLED] != 0.0 and (not want_history or t >= t_show_end):
        # the verdict is settled; the peak base displacement is final once the free base's energy
        # bound on every later |u| cannot exceed it (or, undamped, after one more period, in which
        # the base reaches its amplitude)
        more = False
        if isolated and phase == PHASE_STUCK and t < out[O_T_SETTLED] + 2.0 * math.pi / w and t < t_horizon:
            if fkind >= FOUNDATION_BILINEAR:
                more = free_disp_bound(fkind, prm, _hy(rs), W[W_Y, 2], W[W_Y, 3]) > rs[RS_UMAX] * (1.0 + 1e-9)
            else:
                more = math.sqrt(W[W_Y, 3] ** 2 + w * w * W[W_Y, 2] ** 2) > w * rs[RS_UMAX] * (1.0 + 1e-9)
        if not more:
            return True
    if t >= t_horizon:
        return True
    if rs[RS_STEPS] + rs[RS_REJ] >= max_steps:
        rs[RS_STATUS] = STATUS_MAX_STEPS
        return True
    return False


@njit(cache=True)
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


@njit(cache=True)
def _barrier(prm, level):
    """Energy per unit total mass the block needs to reach ``|theta| = level <= alpha`` from rest [J/kg]."""
    return prm[P_GAMMA] * prm[P_R] * prm[P_G] * (math.cos(prm[P_ALPHA] - level) - prm[P_COSA])


@njit(cache=True, inline='always')
def _stuck_rigid(prm, rs, epar, t_stop, out):
    """Stuck on a rigid foundation: scan the ground motion up to ``t_stop``, integrate nothing."""
    tu, su = _rigid_uplift(_seg(rs), epar, prm[P_THR], rs[RS_T], t_stop)
    if tu < 0.0:
        rs[RS_T] = t_stop
    else:
        rs[RS_T] = tu
        rs[RS_S] = su
        rs[RS_PHASE] = PHASE_ROCKING
        _count_uplift(out, tu)
        rs[RS_FRESH] = 1.0


@njit(cache=True, inline='always')
def _take_step(fkind, prm, ekind, epar, max_steps, rs, W, t_stop, nst):
    """One accepted Dormand-Prince step from ``rs[RS_T]`` inside ``[t, t_stop]``.

    Returns ``(ok, hs, last, sig_lim)``: the step size taken, whether it reached ``t_stop``, and
    the fraction of it that stands (1, or on a hysteretic base the reversal of u where it ends).
    ``ok`` is False when the step cap is reached first.
    """
    phase = rs[RS_PHASE]
    s = rs[RS_S]
    t = rs[RS_T]
    seg = _seg(rs)
    hyst = fkind >= FOUNDATION_BILINEAR
    i0 = 2 if phase == PHASE_STUCK else 0
    p2 = prm[P_P2]
    h = rs[RS_H]
    if h <= 0.0:
        h = 0.02 / math.sqrt(p2)
        if ekind != EXC_RECORD:
            h = min(h, epar[E_TP] / 50.0)
    if rs[RS_FRESH] != 0.0:
        _rhs_into(fkind, phase, s, prm, seg, epar, _hy(rs), t, W, W_Y, 0)
        rs[RS_NRHS] += 1
        rs[RS_FRESH] = 0.0
        if phase == PHASE_ROCKING and W[W_Y, 0] == 0.0:
            # just after an impact: the first step must not swallow a short flight that the
            # angular acceleration turns back (flight ~ 2 thd / |thdd|)
            vel = s * W[W_Y, 1]
            back = -s * W[0, 1]
            if vel > 0.0 and back > 0.0:
                h = min(h, 0.5 * vel / back)
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
        err = _dp5_step(fkind, phase, s, prm, seg, epar, hy, gz, t, hs, W, i0, nst)
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
            kr = knee_ratio(fkind, prm, hy, W[W_YNEW, 2] if code != REV_AT else _poly(_dense(W, hs, 2, 1.0), sr),
                            hs, W[W_Y, 3])
            if kr > 1.0:
                # the step ran through a knee of the bearing's loop unresolved: retake it shorter
                rej += 1
                h = hs * max(0.2, 0.9 / kr)
                sig_lim = 1.0
                continue
        if err <= 1.0:
            fac = 5.0 if err == 0.0 else min(5.0, 0.9 * err ** -0.2)
            if not last or fac < 1.0:
                h = hs * fac
            break
        rej += 1
        h = hs * max(0.2, 0.9 * err ** -0.2)
    rs[RS_H] = h
    rs[RS_REJ] = rej
    rs[RS_NRHS] = nrhs
    if err > 1.0:
        return False, hs, last, sig_lim
    rs[RS_STEPS] = steps + 1
    if sig_lim < 1.0:
        # the step stands up to the reversal of u: its end state is the state there, retaken as a
        # step (the dense output keeps describing the whole step for the events inside it)
        _restep(fkind, phase, s, prm, seg, epar, hy, t, sig_lim * hs, W, i0, nst)
        rs[RS_NRHS] += 6
        for i in range(nst):
            W[W_YNEW, i] = W[W_EV, i]
        rs[RS_NREV] += 1
    return True, hs, last, sig_lim


@njit(cache=True, inline='always')
def _after_stuck_step(fkind, prm, rs, W, out, hs, t_new, sig_lim, epar):
    """Stuck on an isolated base, after a step of the base: uplift when |a| crosses g tan(alpha)."""
    thr = prm[P_THR]
    if fkind >= FOUNDATION_BILINEAR:
        sig, su = hysteretic_uplift(fkind, prm, _hy(rs), _dense(W, hs, 2, 1.0), sig_lim, thr)
    else:
        # a(sigma) is linear in the states, so a quartic in sigma like them; every step is
        # checked (no pre-filter on the step ends)
        w = prm[P_W]
        xi = prm[P_XI]
        cu = _dense(W, hs, 2, 1.0)
        cv = _dense(W, hs, 3, 1.0)
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
        _restep(fkind, PHASE_STUCK, 0.0, prm, _seg(rs), epar, hy, t, sig * hs, W, 2, 4)
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
        _reanchor(fkind, prm, rs, W[W_Y, 2], _direction(rs, W[W_Y, 3]))
    else:
        rs[RS_T] = t_new
        for i in range(2, 4):
            W[W_Y, i] = W[W_YNEW, i]
            W[0, i] = W[6, i]
        if sig_lim < 1.0:
            rs[RS_FRESH] = 1.0  # W[6] is f at the end of the whole step, not at the reversal
            _reanchor(fkind, prm, rs, W[W_Y, 2], -rs[RS_DIR])
        else:
            _reanchor(fkind, prm, rs, W[W_Y, 2], _direction(rs, W[W_Y, 3]))
    rs[RS_UMAX] = max(rs[RS_UMAX], abs(W[W_Y, 2]))


@njit(cache=True, inline='always')
def _after_rocking_step(fkind, prm, rs, W, out, hs, t_new, sig_lim, t_exc_end, nst, epar):
    """Rocking, after a step: impact (s theta falls to 0), peak, alpha, overturning (s theta = pi/2).

    Returns 0 (go on), 1 (overturned: the run ends), 2 (the uplift did not take: back to stuck).
    """
    isolated = fkind != FOUNDATION_RIGID
    s = rs[RS_S]
    t = rs[RS_T]
    alpha = prm[P_ALPHA]
    halfpi = 0.5 * math.pi
    sth1 = s * W[W_YNEW, 0]
    sd0 = s * W[W_Y, 1]
    sd1 = s * W[W_YNEW, 1]
    sig_end = sig_lim
    impact = False
    failed = False
    if sth1 <= 0.0 or (sd0 < 0.0 and sd1 > 0.0):
        sig = _first_down(_dense(W, hs, 0, s), 0.0, 0.0, sig_lim)
        if sig >= 0.0:
            impact = True
            sig_end = sig
        elif sth1 <= 0.0:
            failed = True  # never rose above theta = 0: the uplift did not take
    if not failed:
        if sd0 >= 0.0 and (sd1 <= 0.0 or impact):  # sd0 = 0 right after an uplift
            sp = _first_down(_dense(W, hs, 1, s), 0.0, 0.0, sig_end)
            if sp >= 0.0:
                thp = _poly(_dense(W, hs, 0, s), sp)
                if thp > rs[RS_THMAX]:
                    rs[RS_THMAX] = thp
                    out[O_T_THETA_MAX] = t + sp * hs
        if not impact and sth1 > rs[RS_THMAX]:
            rs[RS_THMAX] = sth1
            out[O_T_THETA_MAX] = t_new
        if math.isnan(out[O_T_EXCEED]) and rs[RS_THMAX] >= alpha:
            sa = _first_down(_dense(W, hs, 0, -s), -alpha, 0.0, sig_end)
            out[O_T_EXCEED] = t + (sa if sa >= 0.0 else sig_end) * hs
        if not impact and sth1 >= halfpi:
            so = _first_down(_dense(W, hs, 0, -s), -halfpi, 0.0, sig_lim)
            if so < 0.0:
                so = sig_lim
            if isolated and (W[W_Y, 3] > 0.0) != (W[W_YNEW, 3] > 0.0):
                rs[RS_UMAX] = max(rs[RS_UMAX], _u_extremum(W, hs, so))
            _state_at(W, hs, so, nst)
            for i in range(nst):
                W[W_Y, i] = W[W_TMP, i]
            rs[RS_UMAX] = max(rs[RS_UMAX], abs(W[W_Y, 2]))
            rs[RS_T] = t + so * hs
            rs[RS_THMAX] = halfpi
            out[O_T_THETA_MAX] = rs[RS_T]
            out[O_T_OVERTURN] = rs[RS_T]
            rs[RS_STATUS] = STATUS_OVERTURNED
            _reanchor(fkind, prm, rs, W[W_Y, 2], _direction(rs, W[W_Y, 3]))
            return 1
    if isolated and (W[W_Y, 3] > 0.0) != (W[W_YNEW, 3] > 0.0):
        rs[RS_UMAX] = max(rs[RS_UMAX], _u_extremum(W, hs, sig_end))

    if failed:
        # the block never left theta = 0: back to the stuck phase at the end of the step,
        # keeping the total horizontal momentum (u_dot + gamma h theta_dot per unit mass); the
        # uplift still counts (the uplift condition held; the rotation is below resolution)
        rs[RS_T] = t_new
        if isolated:
            W[W_Y, 2] = W[W_YNEW, 2]
            W[W_Y, 3] = W[W_YNEW, 3] + prm[P_GAMMA] * prm[P_H] * W[W_YNEW, 1]
        W[W_Y, 0] = 0.0
        W[W_Y, 1] = 0.0
        rs[RS_PHASE] = PHASE_STUCK
        rs[RS_S] = 0.0
        rs[RS_FRESH] = 1.0
        rs[RS_UMAX] = max(rs[RS_UMAX], abs(W[W_Y, 2]))
        _reanchor(fkind, prm, rs, W[W_Y, 2], _direction(rs, W[W_Y, 3]))
        return 2

    if impact:
        # the state at the impact with the accuracy of a step, then onto the root theta = 0
        _restep(fkind, PHASE_ROCKING, s, prm, _seg(rs), epar, _hy(rs), t, sig_end * hs, W, 0, nst)
        rs[RS_NRHS] += 6
        dt_e = -W[W_EV, 0] / W[W_FEV, 0] if W[W_FEV, 0] != 0.0 else 0.0
        dt_e = min(max(dt_e, -sig_end * hs), (1.0 - sig_end) * hs)
        _shift_event(W, dt_e, 0, nst)
        for i in range(nst):
            W[W_Y, i] = W[W_EV, i]
        rs[RS_T] = t + sig_end * hs + dt_e
        W[W_Y, 0] = 0.0
        # the bearings reach the impact point on the step's branch (u does not jump)
        _reanchor(fkind, prm, rs, W[W_Y, 2], rs[RS_DIR])
        return 3
    # accepted step without events
    rs[RS_T] = t_new
    for i in range(nst):
        W[W_Y, i] = W[W_YNEW, i]
        W[0, i] = W[6, i]
    if isolated:
        rs[RS_UMAX] = max(rs[RS_UMAX], abs(W[W_Y, 2]))
    if sig_lim < 1.0:
        rs[RS_FRESH] = 1.0
        _reanchor(fkind, prm, rs, W[W_Y, 2], -rs[RS_DIR])
    else:
        _reanchor(fkind, prm, rs, W[W_Y, 2], _direction(rs, W[W_Y, 3]))
    return 0


@njit(cache=True, inline='always')
def _impact(fkind, prm, rs, W, out, seg, epar, t_exc_end):
    """The impact at theta = 0 (state in ``W[W_Y]`` with theta_dot before it): the momentum map,
    the pivot switch and the rest rule."""
    isolated = fkind != FOUNDATION_RIGID
    t = rs[RS_T]
    thd1 = W[W_Y, 1]
    out[O_N_IMPACTS_ALL] += 1
    if t <= t_exc_end:
        out[O_N_IMPACTS] += 1
    thd2, dud = impact_map(prm, thd1)
    if isolated:
        W[W_Y, 3] += dud
    rs[RS_S] = -rs[RS_S]
    if isolated:
        a_rest = base_force(fkind, prm, W[W_Y, 2], W[W_Y, 3] + prm[P_GAMMA] * prm[P_H] * thd2, _hy(rs))
    else:
        a_rest = _ground(t, seg, epar)
    if comes_to_rest(prm, a_rest, thd2, prm[P_THR], prm[P_ALPHA]):
        if isolated:
            W[W_Y, 3] += prm[P_GAMMA] * prm[P_H] * thd2
        W[W_Y, 1] = 0.0
        rs[RS_PHASE] = PHASE_STUCK
        rs[RS_S] = 0.0
        out[O_N_RESTS] += 1
    else:
        W[W_Y, 1] = thd2
    rs[RS_UMAX] = max(rs[RS_UMAX], abs(W[W_Y, 2]))
    rs[RS_FRESH] = 1.0
    _reanchor(fkind, prm, rs, W[W_Y, 2], _direction(rs, W[W_Y, 3]))


# ---------------------------------------------------------------------------------------------
# The simulation kernel
# ---------------------------------------------------------------------------------------------
@njit(cache=True)
def simulate_core(fkind, prm, ekind, epar, acc, jtab, dt, t_begin, t_exc_end, tail, horizon, max_steps,
                  want_history, early, out):
    """Integrate one scene. Fills ``out`` (see the ``O_*`` layout) and returns the history.

    End of the run (one rule for every mode)
    ----------------------------------------
    The run ends when the verdict is *proven* (or at overturning). Each proof below is a small
    theorem; the code checks exactly its assumptions. A history run goes on after the proof until
    exactly ``t_exc_end + tail`` to show the free motion; nothing after a proof can change the
    verdict, ``theta_max`` or ``n_impacts``, and nothing before it depends on the mode or on
    ``tail`` (the same steps are taken). A run that reaches
    ``t_exc_end + horizon`` unproven ends there with ``O_SETTLED = 0`` (e.g. an undamped base that
    keeps lifting the block): reported, never silently called safe.

    P1 (rigid foundation, ground still, block stuck). With ``ag = 0`` and theta = 0 the uplift
       condition ``|ag| > g tan(alpha)`` can never hold again.
    P2 (rigid foundation, ground still, rocking, ``|theta| < alpha``). Between impacts
       ``E = theta_dot^2/2 + p^2 cos(alpha - |theta|)`` is conserved (Eq 3 with ``ag = 0``); an impact
       keeps theta = 0 and multiplies theta_dot by ``|eta| <= 1``, so E never grows; a rest sets
       ``E = p^2 cos(alpha)``. The potential ``p^2 cos(alpha - |theta|)`` is largest, ``p^2``, at
       ``|theta| = alpha``. Hence if ``E < p^2`` while ``|theta| < alpha`` the block never reaches
       alpha, so never pi/2, and each later peak ``alpha - acos(E/p^2)`` is at most the next one,
       which is added to ``theta_max`` (so the peak is final too). If the block is heading for the
       pivot (``theta theta_dot < 0``) with ``|theta| < alpha``, the potential falls all the way to
       theta = 0, so the impact is certain and ``E`` after it, ``p^2 cos(alpha) + eta^2 (E - p^2
       cos(alpha))``, may be used. Past alpha (``|theta| >= alpha``) no such conclusion holds: the
       same energy means the block falls away from the barrier (issue 9), and the run goes on.
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
       never grows with the ground still: the bearings are passive (P3s), an impact keeps both momenta
       and loses kinetic energy (tests/test_solver.py), a rest or a failed uplift keeps the momentum and
       loses ``theta'^2 gamma (2 R^2/3 - gamma h^2/2) > 0``. The block's height term alone is
       ``gamma g R (cos(alpha - |theta|) - cos alpha)``, increasing in ``|theta|`` up to alpha. Hence if
       ``|theta| < L = min(theta_max, alpha)`` now and ``E`` is below the height term at ``L``, the block
       can never reach ``|theta| = L``: it survives and ``theta_max`` is final. Past alpha the same
       energy means the block falls away (issue 9): the condition ``|theta| < L`` is essential. (It ends the long free rocking of slender
       blocks on heavy-ish bases, ``gamma`` not small; for ``gamma -> 0`` the bearings' energy dominates
       and it never applies. It holds for linear bearings too (viscous damping only dissipates, ``-c u'^2``), and
       is applied to every isolated base.)
    P4 (rigid foundation, ``early`` only, during the excitation, after the first uplift, block
       stuck or ``|theta| < alpha``). ``dE/dt = -p^2 (ag/g) cos(A) theta_dot`` and, while
       ``|theta| <= alpha``, ``theta_dot^2/2 <= E - p^2 cos(alpha) = X^2``, so
       ``dX/dt <= p^2 |ag| / (sqrt(2) g)`` (impacts and rests only lower X). Hence
       ``X(t') <= X(t) + p^2/(sqrt(2) g) int_t^t' |ag|``. If that bound with the whole remaining
       impulse (:func:`rockcli.kernels.ground._impulse_left`) is below ``p sqrt(1 - cos(alpha))``
       (``E < p^2``), the block cannot reach alpha before the ground stops (a first arrival at alpha
       needs ``E >= p^2``), and P2 holds from then on: it survives. ``theta_max`` is then only the
       peak so far (``O_PEAK_FINAL = 0``).
    P6 (rigid foundation, ``early`` only, after the first uplift, ``|theta| >= alpha``). Beyond
       alpha the potential is at least ``p^2 sin(alpha)`` (its value at pi/2), so with
       ``Z^2 = E - p^2 sin(alpha)`` the argument of P4 gives ``Z(t') <= Z(t) + p^2/(sqrt(2) g)
       int_t^t' |ag|``. Coming back inside needs ``|theta| = alpha`` again, so ``E >= p^2``,
       ``Z >= p sqrt(1 - sin(alpha))``; if the bound with the whole remaining impulse stays below
       that, the block can never come back, and once the ground is still it falls (between alpha
       and pi/2 the potential falls outward; below the barrier a block moving inward turns back).
       With the ground already still, a block beyond alpha moving outward falls as well. The run
       ends as overturned with ``t_overturn`` unknown (NaN).

    Parameters
    ----------
    fkind : int
        Foundation kind (``FOUNDATION_*``).
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
        Also stop during the excitation once survival is proven (P4); ``theta_max`` is then not
        final. Verdict-only sweeps use it; never together with ``want_history``.
    out : float64[N_OUT]
        Filled with the results.

    Returns
    -------
    H : float64[n, N_HIST]
        History rows ``t, ag, theta, theta_dot, u, u_dot, z1, z2, bearing force`` (empty when not
        wanted).
    """
    isolated = fkind != FOUNDATION_RIGID
    nst = 4 if isolated else 2

    W = np.zeros((N_W, 4))
    for k in range(N_OUT):
        out[k] = 0.0
    out[O_T_UPLIFT] = np.nan
    out[O_T_OVERTURN] = np.nan
    out[O_T_EXCEED] = np.nan
    out[O_T_THETA_MAX] = np.nan

    nrec = acc.shape[0]
    if want_history:
        H = np.empty((2 * nrec + 1024 if ekind == EXC_RECORD else 4096, N_HIST))
    else:
        H = np.empty((0, N_HIST))
    nh = 0

    rs = np.zeros(N_RS)
    rs[RS_T] = t_begin
    rs[RS_PHASE] = PHASE_STUCK
    rs[RS_FRESH] = 1.0  # W[0] = f(t, y) must be (re)computed
    rs[RS_PEAK_FINAL] = 1.0
    rs[RS_STATUS] = STATUS_DONE
    if fkind >= FOUNDATION_BILINEAR:
        _set_hy(rs, initial_anchor(fkind, prm))
    t_show_end = t_exc_end + tail
    t_horizon = t_exc_end + max(horizon, tail)

    rs[RS_J] = 0.0
    if ekind == EXC_RECORD:
        rscale = epar[E_AP]  # records: the factor the record is scaled by
        _set_seg(rs, (float(SEG_LINEAR), rscale * acc[0], rscale * (acc[1] - acc[0]) / dt, 0.0), dt)
    else:
        seg0, seg_end0 = _pulse_segment(0, ekind, epar, t_begin)
        _set_seg(rs, seg0, seg_end0)
    if want_history:
        H, nh = _history_row(H, nh, fkind, prm, rs, epar, W, W_Y)

    while True:
        _advance_segment(rs, ekind, epar, acc, dt, t_begin)
        t_stop = min(rs[RS_SEG_END], t_horizon)
        if rs[RS_SETTLED] != 0.0 and rs[RS_T] < t_show_end:
            t_stop = min(t_stop, t_show_end)  # a history run shows the free motion up to exactly here

        if _end_of_run(fkind, prm, ekind, epar, jtab, dt, t_exc_end, early, want_history, t_show_end, t_horizon,
                       max_steps, rs, W, out):
            break

        if rs[RS_PHASE] == PHASE_STUCK and not isolated:
            _stuck_rigid(prm, rs, epar, t_stop, out)
            if want_history:
                H, nh = _history_row(H, nh, fkind, prm, rs, epar, W, W_Y)
            continue

        if rs[RS_PHASE] == PHASE_STUCK:
            # stuck on an isolated base: already beyond the uplift threshold?
            a_now = base_force(fkind, prm, W[W_Y, 2], W[W_Y, 3], _hy(rs))
            if abs(a_now) > prm[P_THR]:
                rs[RS_S] = -1.0 if a_now > 0.0 else 1.0
                rs[RS_PHASE] = PHASE_ROCKING
                _count_uplift(out, rs[RS_T])
                rs[RS_FRESH] = 1.0
                continue

        ok, hs, last, sig_lim = _take_step(fkind, prm, ekind, epar, max_steps, rs, W, t_stop, nst)
        if not ok:
            rs[RS_STATUS] = STATUS_MAX_STEPS
            break
        t_new = t_stop if last else rs[RS_T] + sig_lim * hs

        if rs[RS_PHASE] == PHASE_STUCK:
            _after_stuck_step(fkind, prm, rs, W, out, hs, t_new, sig_lim, epar)
            if want_history:
                H, nh = _history_row(H, nh, fkind, prm, rs, epar, W, W_Y)
            continue

        code = _after_rocking_step(fkind, prm, rs, W, out, hs, t_new, sig_lim, t_exc_end, nst, epar)
        if code == 3:
            if want_history:  # the state just before the impact, then (below) just after
                H, nh = _history_row(H, nh, fkind, prm, rs, epar, W, W_Y)
            _impact(fkind, prm, rs, W, out, _seg(rs), epar, t_exc_end)
        if want_history:
            H, nh = _history_row(H, nh, fkind, prm, rs, epar, W, W_Y)
        if code == 1:
            break

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
    return H[:nh]
