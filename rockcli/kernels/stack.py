"""The stack driver: :func:`simulate_stack` runs a body on a free plinth on a rigid foundation
(docs/physics-plinth.md), event-driven, one pattern of motion at a time.

Patterns (``xo[X_PAT]``): R at rest; B the body rocking on the still plinth (states ``psi, psi'`` in columns 0-1
of ``W``, ``rs[RS_S]`` its corner ``k``); P the plinth rocking with the body stuck (``theta2, theta2'`` in columns
0-1, ``rs[RS_S]`` the corner ``s``); BP both rocking (``psi, psi', theta2, theta2'`` in columns 0-3, ``rs[RS_S] =
2 s + k``). R and B are the rigid driver's own code with the body's parameters (:mod:`rockcli.kernels.rigid`:
the uplift scan, the Dormand-Prince step, the rocking events, the impact map and the rest rule), so that while the
plinth cannot move the run is the single block's, bit for bit; P is the same code with the assembly's parameters
(``prm_asm``: ``p_asm``, ``alpha_asm``, ``eta_asm``); BP integrates the 2x2 Lagrange system
(:mod:`rockcli.kernels.stack_physics`). What the stack adds is watched on every step: in B the base's corner forces
(the plinth lifts when one reaches 0), in P the joint's (the body lifts off the plinth), each located on the step's
dense output by sampling 16 sub-intervals and bisection (:mod:`rockcli.kernels.stack_step`, what is read along a
step, with the peaks and the friction demand); at every impact the pattern after it is chosen by
:func:`rockcli.kernels.stack_physics.choose_after_impact`, and where the plinth (or the body on it) stays, the
single block's map is used (:mod:`rockcli.kernels.stack_patterns`, the changes of pattern and the rest rules).

End of the run: P1 (at rest once the ground is still) and P2S, the single block's P2 for the body on the still
plinth when the plinth provably cannot lift again: the ground still, ``|psi| < alpha1``, the body's energy ``En``
(after the coming impact if it is heading for one) below ``p1^2``; then ``psi'^2 <= V2 = 2 (En - p1^2 cos
alpha1)`` and ``|psi''| <= p1^2 sin(alpha1)`` for ever (the energy never grows: impacts on the still plinth
multiply ``psi'`` by ``|e| <= 1``), so the joint force per unit body mass has ``F_y >= g - R1 (p1^2 sin^2 alpha1 +
V2)`` and ``|F_x| <= R1 sin(alpha1) (p1^2 + V2)``, and each base corner force is at least ``(F_y,min (b2 - b1) +
m2 g b2 - 2 h2 |F_x|max)/(2 b2)``; and at every later impact the joint's impulse has ``|T|/N = (h1/b1)(1 - e)/(1 +
e)``, which leaves the base's corner impulses pressing when ``2 h2 |T|/N <= b2 - b1``. When both bounds hold (and
``F_y,min > 0``: the body never jumps) the plinth never moves again and P2's conclusion (the body's later peaks,
the run settled) holds as on the ground. P and BP after the excitation are followed until rest or the horizon.
There is no early stop during the excitation (``early`` is not taken).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.dopri import _dense, _dp5_step, _restep_rows, _shift_event, _state_at
from rockcli.kernels.events import _count_uplift, _hist_push, comes_to_rest, impact_map
from rockcli.kernels.ground import _rigid_uplift, ground_at
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (EXC_RECORD, E_TP, FK_RIGID, HK_IMPACT, HK_IMPACT_AFTER, HK_OVERTURN, HK_REST,
                                    HK_STATE, HK_UPLIFT, J_BASE, J_JOINT, O_N_IMPACTS, O_N_IMPACTS_ALL, O_T_EXCEED,
                                    O_T_OVERTURN, O_T_SETTLED, O_T_THETA_MAX, O_UPLIFTED, PHASE_ROCKING, PHASE_STUCK,
                                    P_ALPHA, P_COSA, P_ETA, P_G, P_P2, P_THR, RS_FRESH, RS_H, RS_NRHS, RS_PHASE, RS_S,
                                    RS_SEG_END, RS_SETTLED, RS_STATUS, RS_T, RS_THMAX, STATUS_MAX_STEPS,
                                    STATUS_OVERTURNED, W_EV, W_FEV, W_RE, W_TMP, W_Y, W_YNEW)
from rockcli.kernels.polynomials import _first_down
from rockcli.kernels.rigid import _NO_HY, _restep_rigid, _stuck_rigid, _substep_stop, _take_step_rigid
from rockcli.kernels.stack_patterns import _after_impact, _plinth_lifts, _set_pattern
from rockcli.kernels.stack_physics import (S_B1, S_B2, S_G, S_H1, S_H2, S_M2, S_R1, _rhs_bp_into, choose_after_impact,
                                           max_velocities)
from rockcli.kernels.stack_step import (HALF_PI, PAT_B, PAT_BP, PAT_P, PAT_R, _abs_max, _bp_demand, _bp_peaks,
                                        _face_opens, _impact_ahead, _jump_demand, _max_abs_ag, _rest_demand)
from rockcli.kernels.stack_step import (N_XO, X_FR_B, X_FR_B_IN, X_FR_J, X_FR_J_IN, X_FRI_B, X_FRI_J, X_K,  # noqa: F401
                                        X_N_INCONS, X_N_JUMP, X_N_PLASTIC, X_N_SWITCH, X_P2S, X_PAT, X_PL_MAX,
                                        X_PL_N_IMP, X_PL_N_IMP_ALL, X_PL_N_RESTS, X_PL_T_EXCEED, X_PL_T_MAX,
                                        X_PL_T_UPLIFT, X_S, X_STEPS_BP, X_TILT_MAX,
                                        X_TOPPLED)  # the record xo, read by rockcli.solve.stack
from rockcli.kernels.steps import (EV_FAILED, EV_IMPACT, EV_OVERTURN, _accept_step, _advance_segment, _bounce, _finish,
                                   _out_of_time, _rocking_events, _seg, _start, _to_impact, _to_overturn, _to_step_end)


# ---------------------------------------------------------------------------------------------
# Pattern BP: the step, its events
# ---------------------------------------------------------------------------------------------
@kernel
def _dp5_bp(code, sp, seg, epar, t, h, W, r0):
    return _dp5_step(_rhs_bp_into, FK_RIGID, PHASE_ROCKING, code, sp, seg, epar, _NO_HY, 0.0, t, h, W, 0, 4, r0)


@kernel
def _take_step_bp(sp, ekind, epar, max_steps, rs, W, t_stop):
    """One accepted step of pattern BP (4 states) inside ``[t, t_stop]``: ``(ok, hs, last)``."""
    code = rs[RS_S]
    t = rs[RS_T]
    seg = _seg(rs)
    h = rs[RS_H]
    if h <= 0.0:
        h = 0.02 / math.sqrt(sp[P_P2])
        if ekind != EXC_RECORD:
            h = min(h, epar[E_TP] / 50.0)
    if rs[RS_FRESH] != 0.0:
        _rhs_bp_into(FK_RIGID, PHASE_ROCKING, code, sp, seg, epar, _NO_HY, t, W, W_Y, 0)
        rs[RS_NRHS] += 1
        rs[RS_FRESH] = 0.0
        # a pivot just back at 0 (an impact, an uplift): do not step over a short flight
        s = 1.0 if code > 0.0 else -1.0
        k = code - 2.0 * s
        for col, c in ((0, k), (2, s)):
            if W[W_Y, col] == 0.0:
                vel = c * W[W_Y, col + 1]
                back = -c * W[0, col + 1]
                if vel > 0.0 and back > 0.0:
                    h = min(h, 0.5 * vel / back)
    return _accept_step(_dp5_bp, code, sp, seg, epar, t, h, W, rs, max_steps, t_stop)


@kernel
def _restep_bp(code, sp, seg, epar, t, h, W):
    _restep_rows(W)
    _dp5_bp(code, sp, seg, epar, t, h, W, np.int64(W_RE))


# ---------------------------------------------------------------------------------------------
# The run
# ---------------------------------------------------------------------------------------------
@kernel
def _hist(H, nh, rs, epar, W, xo, kind):
    """A history row: ``t, ag, psi, psi', theta2, theta2'`` (the rigid layout's ``theta, theta_dot, u, u_dot``), the
    pattern code in the ``z`` column, ``kind``."""
    t = rs[RS_T]
    pat = xo[X_PAT]
    if pat == PAT_P:
        W[W_TMP, 0] = 0.0
        W[W_TMP, 1] = 0.0
        W[W_TMP, 2] = W[W_Y, 0]
        W[W_TMP, 3] = W[W_Y, 1]
    else:
        for i in range(4):
            W[W_TMP, i] = W[W_Y, i] if (pat == PAT_BP or i < 2) else 0.0
    return _hist_push(H, nh, t, ground_at(t, _seg(rs), epar), W, W_TMP, pat, 0.0, 0.0, kind)


@kernel
def _p2s(prm, sp, rs, W, out, xo):
    """P2S (module notes): True when the body rocking on the still plinth after the excitation is settled."""
    alpha = prm[P_ALPHA]
    p2 = prm[P_P2]
    th = W[W_Y, 0]
    thd = W[W_Y, 1]
    if abs(th) >= alpha:
        return False
    En = 0.5 * thd * thd + p2 * math.cos(alpha - abs(th))
    if th * thd < 0.0:  # heading for the pivot: the impact is certain
        c_a = p2 * prm[P_COSA]
        En = c_a + prm[P_ETA] ** 2 * (En - c_a)
    if En >= p2:
        return False
    b1, h1, b2, h2, R1, m2, g = sp[S_B1], sp[S_H1], sp[S_B2], sp[S_H2], sp[S_R1], sp[S_M2], sp[S_G]
    V2 = max(0.0, 2.0 * (En - p2 * prm[P_COSA]))
    sa = math.sin(alpha)
    fy = g - R1 * (p2 * sa * sa + V2)
    fx = R1 * sa * (p2 + V2)
    e = prm[P_ETA]
    ratio = h1 * (1.0 - e) / (b1 * (1.0 + e))
    if not (fy > 0.0 and fy * (b2 - b1) + m2 * g * b2 - 2.0 * h2 * fx > 0.0 and 2.0 * h2 * ratio <= b2 - b1):
        return False
    pk = alpha - math.acos(En / p2)  # the single block's P2, as on the ground
    if pk > rs[RS_THMAX]:
        rs[RS_THMAX] = pk
        out[O_T_THETA_MAX] = math.nan
    xo[X_TILT_MAX] = max(xo[X_TILT_MAX], pk)
    xo[X_P2S] = 1.0
    return True


@kernel(nogil=True)
def simulate_stack(prm, prm_asm, sp, ekind, epar, acc, jtab, dt, t_begin, t_exc_end, tail, horizon, max_steps,
                   want_history, out, xo):
    """Integrate a body on its plinth under one excitation (arguments as :func:`rockcli.kernels.simulate_rigid`;
    ``prm`` the body's parameters on the ground, ``prm_asm`` the assembly's as one block, ``sp`` the stack tuple).
    ``out`` gets the body's results in the single block's layout (``theta_max``: its peak rotation on the plinth),
    ``xo`` the stack's (``X_*``). Returns the history rows (columns as the rigid driver's, ``theta, theta_dot`` =
    ``psi, psi'``, ``u, u_dot`` = ``theta2, theta2'``, ``z`` the pattern)."""
    W, rs, H = _start(ekind, epar, acc, dt, t_begin, want_history, out)
    for i in range(N_XO):
        xo[i] = 0.0
    xo[X_PL_T_MAX] = np.nan
    xo[X_PL_T_EXCEED] = np.nan
    xo[X_PL_T_UPLIFT] = np.nan
    xo[X_TOPPLED] = -1.0
    nh = np.int64(0)
    t_show_end = t_exc_end + tail
    t_horizon = t_exc_end + max(horizon, tail)
    body_first = prm[P_THR] <= prm_asm[P_THR]
    thr = min(prm[P_THR], prm_asm[P_THR])  # the ground acceleration the stack at rest carries, at most
    if want_history:
        H, nh = _hist(H, nh, rs, epar, W, xo, HK_STATE)

    while True:
        _advance_segment(rs, ekind, epar, acc, dt, t_begin)
        t_stop = min(rs[RS_SEG_END], t_horizon)
        # ---- the end of the run: P1, P2S -------------------------------------------------------
        t = rs[RS_T]
        pat = xo[X_PAT]
        if rs[RS_SETTLED] == 0.0 and t >= t_exc_end:
            if pat == PAT_R or (pat == PAT_B and _p2s(prm, sp, rs, W, out, xo)):
                rs[RS_SETTLED] = 1.0
                out[O_T_SETTLED] = t
        if rs[RS_SETTLED] != 0.0 and rs[RS_T] < t_show_end:  # a settled run's history ends at the tail's end
            t_stop = min(t_stop, t_show_end)
        if rs[RS_SETTLED] != 0.0 and (not want_history or t >= t_show_end):
            break
        if _out_of_time(rs, t_horizon, max_steps):
            break
        seg = _seg(rs)

        # ---- at rest: scan the ground for the lower threshold ---------------------------------
        if pat == PAT_R:
            t0 = rs[RS_T]
            if body_first:
                _stuck_rigid(prm, rs, epar, t_stop, out, np.bool_(False))
                if rs[RS_PHASE] == PHASE_ROCKING:
                    _set_pattern(rs, W, xo, 0.0, rs[RS_S], 0.0, 0.0, 0.0, 0.0)
            else:
                tu, su = _rigid_uplift(seg, epar, prm_asm[P_THR], rs[RS_T], t_stop)
                if tu < 0.0:
                    rs[RS_T] = t_stop
                else:
                    rs[RS_T] = tu
                    _set_pattern(rs, W, xo, su, 0.0, 0.0, 0.0, 0.0, 0.0)
                    _plinth_lifts(xo, tu)
            aa = _max_abs_ag(seg, epar, t0, rs[RS_T]) / prm[P_G]
            a1 = ground_at(t0, seg, epar)
            if xo[X_PAT] != PAT_R and rs[RS_T] == t0 and abs(a1) > thr:
                # a jump out of rest (stack_step's notes): at rest the stack carries the acceleration up to its
                # threshold only; past it, the demand of the pattern it enters, at zero state
                aa = thr / prm[P_G]
                _jump_demand(xo[X_PAT], xo[X_S], xo[X_K], sp, prm if xo[X_PAT] == PAT_B else prm_asm,
                             thr if a1 > 0.0 else -thr, a1, xo)
            _rest_demand(xo, aa)
            if want_history:
                H, nh = _hist(H, nh, rs, epar, W, xo, HK_UPLIFT if xo[X_PAT] != PAT_R else HK_STATE)
            continue

        if ekind == EXC_RECORD:
            t_stop = _substep_stop(rs[RS_T], rs[RS_SEG_END], dt, t_stop)
        s = xo[X_S]
        k = xo[X_K]

        # ---- one pattern, one rigid body: B (the body) or P (the assembly) --------------------
        if pat == PAT_B or pat == PAT_P:
            pb = prm if pat == PAT_B else prm_asm
            c = k if pat == PAT_B else s
            if pat == PAT_P:  # the rigid events track the plinth's peak: swap its record in
                rs[RS_THMAX], xo[X_PL_MAX] = xo[X_PL_MAX], rs[RS_THMAX]
                out[O_T_THETA_MAX], xo[X_PL_T_MAX] = xo[X_PL_T_MAX], out[O_T_THETA_MAX]
                out[O_T_EXCEED], xo[X_PL_T_EXCEED] = xo[X_PL_T_EXCEED], out[O_T_EXCEED]
            ok, hs, last = _take_step_rigid(pb, ekind, epar, max_steps, rs, W, t_stop)
            t_new = t_stop if last else rs[RS_T] + hs
            code = 0
            sig = 1.0
            s_open = -1.0
            side = 0.0
            if ok:
                s_ev = _impact_ahead(W, hs, 0, c)
                if c * W[W_YNEW, 0] >= HALF_PI:  # nothing past the overturn is read
                    so = _first_down(_dense(W, hs, np.int64(0), -c), -HALF_PI, 0.0, 1.0)
                    s_ev = min(s_ev, so if so >= 0.0 else 1.0)
                s_open, side = _face_opens(pat, s, k, sp, pb, W, hs, rs[RS_T], seg, epar, xo, s_ev)
                if s_open >= 0.0:  # the step stands up to the face opening: retake it there
                    _restep_rigid(FK_RIGID, PHASE_ROCKING, c, pb, seg, epar, _NO_HY, rs[RS_T], s_open * hs, W,
                                  np.int64(0), np.int64(2))
                    rs[RS_NRHS] += 6
                    W[W_YNEW, 0] = W[W_EV, 0]
                    W[W_YNEW, 1] = W[W_EV, 1]
                    t_new = rs[RS_T] + s_open * hs
                code, sig = _rocking_events(pb, rs, W, out, hs, t_new, 1.0 if s_open < 0.0 else s_open)
                sig_end = sig if (code == EV_IMPACT or code == EV_OVERTURN) else (1.0 if s_open < 0.0 else s_open)
                xo[X_TILT_MAX] = max(xo[X_TILT_MAX], min(_abs_max(_dense(W, hs, np.int64(0), 1.0), sig_end),
                                                         HALF_PI))
            if pat == PAT_P:
                rs[RS_THMAX], xo[X_PL_MAX] = xo[X_PL_MAX], rs[RS_THMAX]
                out[O_T_THETA_MAX], xo[X_PL_T_MAX] = xo[X_PL_T_MAX], out[O_T_THETA_MAX]
                out[O_T_EXCEED], xo[X_PL_T_EXCEED] = xo[X_PL_T_EXCEED], out[O_T_EXCEED]
            if not ok:
                rs[RS_STATUS] = STATUS_MAX_STEPS
                break
            if code == EV_OVERTURN:
                if pat == PAT_B:
                    _to_overturn(rs, W, out, hs, sig, 2)
                    xo[X_TOPPLED] = 1.0
                else:
                    _state_at(W, hs, sig, 2)
                    W[W_Y, 0] = W[W_TMP, 0]
                    W[W_Y, 1] = W[W_TMP, 1]
                    rs[RS_T] = rs[RS_T] + sig * hs
                    out[O_T_OVERTURN] = rs[RS_T]
                    rs[RS_STATUS] = STATUS_OVERTURNED
                    xo[X_PL_MAX] = HALF_PI
                    xo[X_TOPPLED] = 0.0
                if want_history:
                    H, nh = _hist(H, nh, rs, epar, W, xo, HK_OVERTURN)
                break
            if code == EV_FAILED:
                rs[RS_T] = t_new
                _set_pattern(rs, W, xo, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
            elif code == EV_IMPACT:
                _to_impact(_restep_rigid, FK_RIGID, pb, rs, W, epar, _NO_HY, hs, sig, np.int64(2))
                if want_history:
                    H, nh = _hist(H, nh, rs, epar, W, xo, HK_IMPACT)
                thd1 = W[W_Y, 1]
                t = rs[RS_T]
                ag = ground_at(t, _seg(rs), epar)
                if pat == PAT_B:
                    V = max_velocities(0.0, k, sp, 0.0, 0.0, 0.0, thd1)
                    s1, k1, V1, margin, jump, db, dj, plastic = choose_after_impact(0.0, k, J_JOINT, sp, 0.0, 0.0, V)
                else:
                    V = max_velocities(s, 0.0, sp, 0.0, 0.0, thd1, 0.0)
                    s1, k1, V1, margin, jump, db, dj, plastic = choose_after_impact(s, 0.0, J_BASE, sp, 0.0, 0.0, V)
                if ((pat == PAT_B and s1 == 0.0) or (pat == PAT_P and k1 == 0.0)) and not plastic:
                    # the plinth stays (B), the body stays on it (P): the single block's impact map and rest rule
                    xo[X_FRI_B] = max(xo[X_FRI_B], db)
                    xo[X_FRI_J] = max(xo[X_FRI_J], dj)
                    thd2, _ = impact_map(pb, thd1)
                    rs[RS_S] = -rs[RS_S]
                    if pat == PAT_B:
                        xo[X_K] = rs[RS_S]
                        _bounce(pb, rs, W, out, thd1, t_exc_end, ag, thd2, pb[P_THR])
                        if rs[RS_PHASE] == PHASE_STUCK:
                            _set_pattern(rs, W, xo, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
                    else:
                        xo[X_S] = rs[RS_S]
                        xo[X_PL_N_IMP_ALL] += 1.0
                        if t <= t_exc_end:
                            xo[X_PL_N_IMP] += 1.0
                        rs[RS_FRESH] = 1.0
                        if comes_to_rest(pb, ag, thd2, pb[P_THR], pb[P_ALPHA]):
                            xo[X_PL_N_RESTS] += 1.0
                            _set_pattern(rs, W, xo, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
                        else:
                            W[W_Y, 1] = thd2
                else:
                    if pat == PAT_B:
                        out[O_N_IMPACTS_ALL] += 1.0
                        if t <= t_exc_end:
                            out[O_N_IMPACTS] += 1.0
                        _after_impact(J_JOINT, 0.0, k, sp, prm, prm_asm, 0.0, 0.0, V, rs, W, out, xo, t, ag)
                    else:
                        xo[X_PL_N_IMP_ALL] += 1.0
                        if t <= t_exc_end:
                            xo[X_PL_N_IMP] += 1.0
                        _after_impact(J_BASE, s, 0.0, sp, prm, prm_asm, 0.0, 0.0, V, rs, W, out, xo, t, ag)
                if want_history:
                    H, nh = _hist(H, nh, rs, epar, W, xo, HK_REST if xo[X_PAT] == PAT_R else HK_IMPACT_AFTER)
                continue
            elif s_open >= 0.0:
                # the face opens: the plinth lifts (from B) or the body lifts off it (from P)
                _to_step_end(rs, W, t_new, 2)
                if pat == PAT_B:
                    _set_pattern(rs, W, xo, side, k, W[W_Y, 0], W[W_Y, 1], 0.0, 0.0)
                    _plinth_lifts(xo, rs[RS_T])
                else:
                    _set_pattern(rs, W, xo, s, side, 0.0, 0.0, W[W_Y, 0], W[W_Y, 1])
                    if out[O_UPLIFTED] == 0.0:  # the body's first rotation on the plinth
                        _count_uplift(out, rs[RS_T])
                if want_history:
                    H, nh = _hist(H, nh, rs, epar, W, xo, HK_UPLIFT)
                continue
            else:
                _to_step_end(rs, W, t_new, 2)
            if want_history:
                H, nh = _hist(H, nh, rs, epar, W, xo, HK_STATE)
            continue

        # ---- both rock -------------------------------------------------------------------------
        code = rs[RS_S]
        ok, hs, last = _take_step_bp(sp, ekind, epar, max_steps, rs, W, t_stop)
        if not ok:
            rs[RS_STATUS] = STATUS_MAX_STEPS
            break
        xo[X_STEPS_BP] += 1.0
        t_new = t_stop if last else rs[RS_T] + hs
        # events: an impact at either pivot, a block toppling; the earliest wins
        sig_b = _impact_ahead(W, hs, 2, s)
        sig_j = _impact_ahead(W, hs, 0, k)
        sig_ob = 2.0
        sig_oj = 2.0
        if s * W[W_YNEW, 2] >= HALF_PI:
            so = _first_down(_dense(W, hs, np.int64(2), -s), -HALF_PI, 0.0, 1.0)
            sig_ob = so if so >= 0.0 else 1.0
        if k * W[W_YNEW, 0] >= HALF_PI:
            so = _first_down(_dense(W, hs, np.int64(0), -k), -HALF_PI, 0.0, 1.0)
            sig_oj = so if so >= 0.0 else 1.0
        failed_b = sig_b == 1.0 and s * W[W_YNEW, 2] <= 0.0
        failed_j = sig_j == 1.0 and k * W[W_YNEW, 0] <= 0.0
        sig = min(sig_b, sig_j, sig_ob, sig_oj, 1.0)
        ev = 0
        if sig_ob <= sig and sig_ob <= 1.0:
            ev = 1
        elif sig_oj <= sig and sig_oj <= 1.0:
            ev = 2
        elif sig_b < 1.0 and sig_b <= sig:
            ev = 3
        elif sig_j < 1.0 and sig_j <= sig:
            ev = 4
        _bp_peaks(rs, out, xo, sp, W, hs, sig)
        if _bp_demand(s, k, sp, W, hs, sig, rs[RS_T], seg, epar, xo):
            xo[X_N_JUMP] += 1.0
        if ev == 1 or ev == 2:
            _state_at(W, hs, sig, 4)
            rs[RS_T] = rs[RS_T] + sig * hs
            out[O_T_OVERTURN] = rs[RS_T]
            rs[RS_STATUS] = STATUS_OVERTURNED
            if ev == 1:
                xo[X_TOPPLED] = 0.0
                xo[X_PL_MAX] = HALF_PI
            else:
                xo[X_TOPPLED] = 1.0
                rs[RS_THMAX] = HALF_PI
            for i in range(4):
                W[W_Y, i] = W[W_TMP, i]
            if want_history:
                H, nh = _hist(H, nh, rs, epar, W, xo, HK_OVERTURN)
            break
        if ev == 3 or ev == 4:
            col = 2 if ev == 3 else 0
            t0 = rs[RS_T]
            _restep_bp(code, sp, seg, epar, t0, sig * hs, W)
            rs[RS_NRHS] += 6
            dt_e = -W[W_EV, col] / W[W_FEV, col] if W[W_FEV, col] != 0.0 else 0.0
            dt_e = min(max(dt_e, -sig * hs), (1.0 - sig) * hs)
            _shift_event(W, dt_e, 0, 4)
            for i in range(4):
                W[W_Y, i] = W[W_EV, i]
            W[W_Y, col] = 0.0
            rs[RS_T] = t0 + sig * hs + dt_e
            t = rs[RS_T]
            if want_history:
                H, nh = _hist(H, nh, rs, epar, W, xo, HK_IMPACT)
            psi, psid, th2, thd2 = W[W_Y, 0], W[W_Y, 1], W[W_Y, 2], W[W_Y, 3]
            V = max_velocities(s, k, sp, th2, psi, thd2, psid)
            ag = ground_at(t, _seg(rs), epar)
            if ev == 3:
                xo[X_PL_N_IMP_ALL] += 1.0
                if t <= t_exc_end:
                    xo[X_PL_N_IMP] += 1.0
                _after_impact(J_BASE, s, k, sp, prm, prm_asm, th2, psi, V, rs, W, out, xo, t, ag)
            else:
                out[O_N_IMPACTS_ALL] += 1.0
                if t <= t_exc_end:
                    out[O_N_IMPACTS] += 1.0
                _after_impact(J_JOINT, s, k, sp, prm, prm_asm, th2, psi, V, rs, W, out, xo, t, ag)
            if want_history:
                H, nh = _hist(H, nh, rs, epar, W, xo, HK_IMPACT_AFTER)
            continue
        _to_step_end(rs, W, t_new, 4)
        if failed_b or failed_j:
            # a pivot that never rose above 0 within the step (an uplift that did not take): stuck again
            psi, psid, th2, thd2 = W[W_Y, 0], W[W_Y, 1], W[W_Y, 2], W[W_Y, 3]
            if failed_b and failed_j:
                _set_pattern(rs, W, xo, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
            elif failed_b:
                _set_pattern(rs, W, xo, 0.0, k, psi, psid, 0.0, 0.0)
            else:
                _set_pattern(rs, W, xo, s, 0.0, 0.0, 0.0, th2, thd2)
        if want_history:
            H, nh = _hist(H, nh, rs, epar, W, xo, HK_STATE)

    if xo[X_TOPPLED] >= 0.0:  # a run that topples: its demand read while both blocks were inside (stack_step)
        xo[X_FR_B] = xo[X_FR_B_IN]
        xo[X_FR_J] = xo[X_FR_J_IN]
    _finish(rs, W, out)
    return H[:nh]
