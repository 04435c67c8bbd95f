"""The friction driver: :func:`simulate_chain` runs a chain of blocks (one block, a body on its plinth) on a rigid
foundation or on linear bearings with Coulomb friction at every contact (docs/physics-sliding.md), event-driven,
one pattern of contacts at a time.

The run. While everything stands still on the rigid ground (every interface a face that sticks) nothing is
integrated: the contact forces are linear in the ground acceleration, so the band of ``ag`` in which every face
presses and every contact sticks is computed once and the ground motion scanned for its exit
(:func:`rockcli.kernels.ground.band_exit`); the pattern that starts there is chosen by the contact law. Otherwise a
Dormand-Prince step of the chain's states (:mod:`rockcli.kernels.chain_step`), its events on the dense output (the
earliest taken, the step retaken to it), and at each event the pattern that follows (:mod:`rockcli.kernels.contact`):
an impact by Moreau's law with Coulomb friction and the rest rules, a face that opens, a contact that starts or
stops sliding. The run ends when a block topples (a pivot's angle reaches ``pi/2``) or slides off the block below
(its base's centre ``b_below - b`` from centred: its corner at the edge), at rest once the ground is still (on
bearings: once the free base's energy cannot open a face or start a slip, the bound in :func:`_base_settled`), or
at the horizon.

The impacts, the rest rules after them and the bookkeeping of a change of pattern are in
:mod:`rockcli.kernels.chain_impact`.

Outputs ``xo``: the fields of :mod:`rockcli.kernels.chain_out` (imported here too).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.chain import (BASE_RIGID, CP_BASE, CP_CB, CP_KB, CP_MB, CP_N, CP_P2MAX, CP_TOL, F_AREST, F_B, F_M,
                                   F_MU, col_psi, col_s, fld, free_coordinates, workspace)
from rockcli.kernels.chain_impact import after_impact, cone_after_impact, switch
from rockcli.kernels.chain_kind import kind_switch
from rockcli.kernels.chain_out import (HC_AG, HC_KIND, HC_PAT, HC_T, HK_END, HK_EVENT, HK_IMPACT, HK_IMPACT_AFTER,
                                       HK_STATE, J_PSI_END, J_PSI_MAX, J_S_END, J_S_MAX, J_TILT, J_T_EXCEED,
                                       J_T_PSI_MAX, J_T_SLIDE, J_T_S_MAX, J_T_UPLIFT, MAX_NO_PROGRESS, NX_J, N_XG,
                                       STATUS_SLID_OFF, STATUS_STALLED,
                                       X_NRHS, X_N_INCONS, X_N_JUMP, X_N_STALL, X_REJ, X_SETTLED, X_SLIDOFF, X_STATUS,
                                       X_STEPS, X_TOPPLED, X_T_END, X_T_FAIL, X_T_FIRST, X_T_SETTLED, X_T_U_MAX,
                                       X_U_END, X_U_MAX)
from rockcli.kernels.contact_lcp import choose, lcp_space
from rockcli.kernels.chain_rest import quiet_until, rest_interval
from rockcli.kernels.linear_base import coefficients
from rockcli.kernels.chain_step import (EVC_FACE_OPENS, EVC_IMPACT, EVC_KIND, EVC_NONE, EVC_SLIDE_OFF, EVC_SLIP_STOP,
                                        EVC_TOPPLE, EVC_WRONG_SIDE, _rhs, dp5, force_events, peaks, restep,
                                        state_events)
from rockcli.kernels.contact import face_corners, solve_pattern
from rockcli.kernels.ground import _pulse_segment, band_exit, ground_at
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (E_AP, E_TP, EXC_RECORD, N_RS, N_W, RS_FRESH, RS_H, RS_J, RS_SEG_END, RS_T,
                                    RS_VEND, RS_VJ, SEG_LINEAR, STATUS_DONE, STATUS_MAX_STEPS, STATUS_OVERTURNED,
                                    W_EV, W_FEV, W_Y, W_YNEW)
from rockcli.kernels.steps import _advance_segment, _grown, _seg, _set_seg, _shrink

MAX_STALL = 64  # events in a row at one instant before the contact law's choice is forced on



@kernel
def _all_stuck(pat, n):
    for i in range(2 * n):
        if pat[i] != 0.0:
            return False
    return True


@kernel
def _hist(H, nh, t, ag, kind, pat, W, row):
    if nh >= H.shape[0]:
        H2 = np.empty((2 * H.shape[0] + 16, H.shape[1]))
        H2[:nh] = H[:nh]
        H = H2
    npat = pat.shape[0]
    H[nh, HC_T] = t
    H[nh, HC_AG] = ag
    H[nh, HC_KIND] = kind
    for i in range(npat):
        H[nh, HC_PAT + i] = pat[i]
    for i in range(W.shape[1]):
        H[nh, HC_PAT + npat + i] = W[row, i]
    return H, nh + 1


@kernel
def rest_band(cp, y, ws, frc, scratch):
    """``(a_lo, a_hi)``: the ground accelerations under which the chain at rest on the rigid ground (every face
    sticking, at the slips of ``y``) stays at rest: every corner force pressing and every contact inside Coulomb's
    cone. At rest the forces are affine in ``ag`` (nothing accelerates in the ground's frame)."""
    n = int(cp[CP_N])
    for i in range(2 * n):
        scratch[i] = 0.0
    base = cp[CP_BASE]
    cp[CP_BASE] = BASE_RIGID  # on bearings: the chain riding the base, ``ag`` read as the base's acceleration
    solve_pattern(cp, scratch, y, 0.0, ws, frc)
    f0 = ws[14]  # (scratch forces)
    for j in range(n):
        for q in range(3):
            f0[j, q] = frc[j, q]
    solve_pattern(cp, scratch, y, 1.0, ws, frc)
    cp[CP_BASE] = base
    lo = -math.inf
    hi = math.inf
    for j in range(n):
        b = fld(cp, j, F_B)
        mu = fld(cp, j, F_MU)
        N0, T0, M0 = f0[j, 0], f0[j, 1], f0[j, 2]
        N1, T1, M1 = frc[j, 0] - N0, frc[j, 1] - T0, frc[j, 2] - M0
        pr0, pl0 = face_corners(cp, j, y[col_s(j)], N0, M0)
        pr1, pl1 = face_corners(cp, j, y[col_s(j)], N1, M1)
        for c0, c1 in ((pr0, pr1), (pl0, pl1), (mu * N0 - T0, mu * N1 - T1), (mu * N0 + T0, mu * N1 + T1)):
            # c0 + c1 ag >= 0
            if c1 > 0.0:
                lo = max(lo, -c0 / c1)
            elif c1 < 0.0:
                hi = min(hi, -c0 / c1)
            elif c0 < 0.0:
                lo = math.inf
    return lo, hi


@kernel
def _base_settled(cp, y, ws, frc, scratch):
    """On bearings, the ground still and the chain standing on the base: the base's energy ``E = (M u'^2 + k u^2)/2``
    never grows, so ``|u| <= sqrt(2E/k)``, ``|u'| <= sqrt(2E/M)`` and the acceleration of everything on it,
    ``|a| = |k u + c u'|/M``, stays below ``(k sqrt(2E/k) + c sqrt(2E/M))/M`` for ever; True when that is inside
    the band in which the chain stays at rest (:func:`rest_band`, with ``a`` for ``ag``)."""
    n = int(cp[CP_N])
    M = cp[CP_MB]
    for j in range(n):
        M += fld(cp, j, 2)
    k = cp[CP_KB]
    c = cp[CP_CB]
    E = 0.5 * M * y[1] ** 2 + 0.5 * k * y[0] ** 2
    amax = (k * math.sqrt(2.0 * E / k) + c * math.sqrt(2.0 * E / M)) / M
    lo, hi = rest_band(cp, y, ws, frc, scratch)
    return -amax > lo and amax < hi


@kernel
def _first_h(cp, pat, W, h):
    """Shorten the first step after an event so that it does not swallow a short excursion: a pivot just opened
    (angle 0) whose rate the acceleration turns back, a slip whose rate is being brought to 0."""
    n = int(cp[CP_N])
    for j in range(n):
        if pat[2 * j] != 0.0 and W[W_Y, col_psi(j)] == 0.0:
            c = pat[2 * j]
            vel = c * W[W_Y, col_psi(j) + 1]
            back = -c * W[0, col_psi(j) + 1]
            if vel > 0.0 and back > 0.0:
                h = min(h, 0.5 * vel / back)
        if pat[2 * j + 1] != 0.0:
            sl = pat[2 * j + 1]
            vel = sl * W[W_Y, col_s(j) + 1]
            back = -sl * W[0, col_s(j) + 1]
            if vel > 0.0 and back > 0.0:
                h = min(h, 0.5 * vel / back)
    return h


@kernel
def simulate_chain(cp, pat0, y0, ekind, epar, acc, dt, t_begin, t_exc_end, tail, horizon, max_steps, want_history,
                   xo):
    """Run the chain ``cp`` from the pattern ``pat0`` and state ``y0`` at ``t_begin`` under the ground motion
    (``ekind``, ``epar``, ``acc``, ``dt`` as for :func:`rockcli.kernels.rigid.simulate_rigid`); the excitation ends at
    ``t_exc_end``, a history run shows ``tail`` after it, the run stops ``max(horizon, tail)`` after it. Fills
    ``xo`` (:func:`n_out`); returns the history rows (empty unless ``want_history``)."""
    n = int(cp[CP_N])
    ny = 2 + 4 * n
    for k in range(xo.shape[0]):
        xo[k] = 0.0
    for k in (X_T_FAIL, X_T_SETTLED, X_T_U_MAX, X_T_FIRST):
        xo[k] = np.nan
    xo[X_TOPPLED] = -1.0
    xo[X_SLIDOFF] = -1.0
    for j in range(n):
        o = N_XG + NX_J * j
        for k in (J_T_PSI_MAX, J_T_EXCEED, J_T_S_MAX, J_T_UPLIFT, J_T_SLIDE):
            xo[o + k] = np.nan
    W = np.zeros((N_W, ny))
    rs = np.zeros(N_RS)
    rs[RS_T] = t_begin
    rs[RS_FRESH] = 1.0
    rs[RS_VEND] = np.inf
    rs[RS_VJ] = -1.0
    if ekind == EXC_RECORD:
        rscale = epar[E_AP]
        _set_seg(rs, (float(SEG_LINEAR), rscale * acc[0], rscale * (acc[1] - acc[0]) / dt, 0.0), dt)
    else:
        seg0, seg_end0 = _pulse_segment(np.int64(0), ekind, epar, t_begin)
        _set_seg(rs, seg0, seg_end0)
    pat = pat0.copy()
    for i in range(ny):
        W[W_Y, i] = y0[i]
    ws = workspace(n)
    sp = lcp_space(n)
    frc = np.zeros((n, 3))
    best = np.zeros(2 * n)
    v0 = np.zeros((n, 2))
    w0 = np.zeros(n)
    ynew = np.zeros(ny)
    ytmp = np.zeros(ny)
    zero_psi = np.zeros(n, dtype=np.bool_)
    zero_s = np.zeros(n, dtype=np.bool_)
    free_corner = np.zeros(n, dtype=np.bool_)
    fcols = np.zeros(2 * n + 1, dtype=np.int64)
    mg0 = np.zeros(2 * n)
    mg1 = np.zeros(2 * n)
    mg2 = np.zeros(2 * n)
    alpha_rest = np.zeros(n)
    for j in range(n):
        alpha_rest[j] = fld(cp, j, F_AREST)
    rigid = cp[CP_BASE] == BASE_RIGID
    t_show_end = t_exc_end + tail
    t_horizon = t_exc_end + max(horizon, tail)
    nrows = 2 * acc.shape[0] + 1024 if ekind == EXC_RECORD else 4096
    H = np.empty((nrows if want_history else 0, 3 + 2 * n + ny))
    nh = 0
    if want_history:
        H, nh = _hist(H, nh, rs[RS_T], ground_at(rs[RS_T], _seg(rs), epar), HK_STATE, pat, W, W_Y)
    settled = False
    status = STATUS_DONE
    stall = 0
    no_progress = 0
    t_last_event = -math.inf
    x_u = X_U_MAX if not rigid else -1
    band_ok = False  # the rest band on the bearings, computed once each time the chain comes to rest
    blo = -math.inf
    bhi = math.inf
    wb = 0.0
    xib = 0.0
    coef = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    if not rigid:
        mtot = cp[CP_MB]
        for j in range(n):
            mtot += fld(cp, j, F_M)
        wb = math.sqrt(cp[CP_KB] / mtot)
        xib = cp[CP_CB] / (2.0 * mtot * wb)
        if ekind == EXC_RECORD:
            coef = coefficients(wb, xib, dt)
    while True:
        _advance_segment(rs, ekind, epar, acc, dt, t_begin)
        t = rs[RS_T]
        seg = _seg(rs)
        if not settled and t >= t_exc_end and _all_stuck(pat, n):
            if rigid or _base_settled(cp, W[W_Y], ws, frc, best):
                settled = True
                xo[X_SETTLED] = 1.0
                xo[X_T_SETTLED] = t
        if settled and (not want_history or t >= t_show_end):
            break
        if t >= t_horizon:
            break
        if xo[X_STEPS] + xo[X_REJ] >= max_steps:
            status = STATUS_MAX_STEPS
            break
        t_stop = min(rs[RS_SEG_END], t_horizon)
        if settled:
            t_stop = min(t_stop, t_show_end)
        if rigid and _all_stuck(pat, n):
            if not band_ok:  # computed once each time the chain comes to rest (the slips fix it)
                blo, bhi = rest_band(cp, W[W_Y], ws, frc, best)
                band_ok = True
            lo, hi = blo, bhi
            tu, side = band_exit(seg, epar, lo, hi, t, t_stop)
            if tu < 0.0:
                rs[RS_T] = t_stop
                if want_history and t_stop <= t_show_end:  # at rest through the piece: its end
                    H, nh = _hist(H, nh, t_stop, ground_at(t_stop, seg, epar), HK_STATE, pat, W, W_Y)
                elif ekind == EXC_RECORD and t_stop == rs[RS_SEG_END]:  # the quiet samples after it, at once
                    k = quiet_until(acc, epar[E_AP], int(rs[RS_J]), lo, hi, min(t_exc_end, t_horizon), dt)
                    if k > int(rs[RS_J]) + 1:
                        rs[RS_J] = k - 1
                        rs[RS_T] = k * dt
                continue
            rs[RS_T] = tu
            ag = ground_at(tu, seg, epar)  # the pattern chosen just past the band's edge (the motion that starts)
            if side > 0.0:
                ag = max(ag, hi + 1e-9 * abs(hi))
            else:
                ag = min(ag, lo - 1e-9 * abs(lo))
            for j in range(n):
                zero_psi[j] = True
                zero_s[j] = True
            choose(cp, pat, W[W_Y], ag, ws, frc, zero_psi, zero_s, best, sp)
            switch(xo, pat, best, n, tu, cp, W[W_Y])
            band_ok = False
            rs[RS_FRESH] = 1.0
            rs[RS_H] = 0.0
            if want_history:
                H, nh = _hist(H, nh, tu, ground_at(tu, seg, epar), HK_EVENT, pat, W, W_Y)
            if _all_stuck(pat, n):  # the threshold met without crossing it (a tangency): go on past it
                rs[RS_T] = min(t_stop, tu + 1e-9 * max(1.0, tu))
            continue
        if not rigid and ekind == EXC_RECORD and _all_stuck(pat, n):
            # at rest on the bearings under a record: the base in closed form (kernels.chain_rest)
            if not band_ok:
                blo, bhi = rest_band(cp, W[W_Y], ws, frc, best)
                band_ok = True
            t_stop = min(t_stop, t + dt)  # after the record (one endless zero segment): a sample interval at a time
            seg_t0 = seg[3]
            a0 = seg[1] + seg[2] * (t - seg_t0)
            tau, u1, v1, upk = rest_interval(wb, xib, coef, dt, W[W_Y, 0], W[W_Y, 1], a0, seg[2], t_stop - t, blo,
                                             bhi)
            W[W_Y, 0] = u1
            W[W_Y, 1] = v1
            if upk > xo[X_U_MAX]:
                xo[X_U_MAX] = upk
                xo[X_T_U_MAX] = t + tau
            rs[RS_T] = t + tau if tau < t_stop - t else t_stop
            rs[RS_FRESH] = 1.0
            if tau < t_stop - t:  # the chain leaves rest here: the pattern the contact law picks
                t_ev = t + tau
                for j in range(n):
                    zero_psi[j] = True
                    zero_s[j] = True
                choose(cp, pat, W[W_Y], ground_at(t_ev, seg, epar), ws, frc, zero_psi, zero_s, best, sp)
                switch(xo, pat, best, n, t_ev, cp, W[W_Y])
                rs[RS_H] = 0.0
                band_ok = False
                if want_history:
                    H, nh = _hist(H, nh, t_ev, ground_at(t_ev, seg, epar), HK_EVENT, pat, W, W_Y)
            elif want_history and rs[RS_T] <= t_show_end:
                H, nh = _hist(H, nh, rs[RS_T], ground_at(rs[RS_T], seg, epar), HK_STATE, pat, W, W_Y)
            continue
        band_ok = False
        # one step of the free coordinates
        nfc = free_coordinates(cp, pat, fcols)
        if rs[RS_FRESH] != 0.0:
            _rhs(cp, pat, seg, epar, t, W, np.int64(W_Y), np.int64(0), ws)
            xo[X_NRHS] += 1.0
            rs[RS_FRESH] = 0.0
        h = rs[RS_H]
        if h <= 0.0:
            h = 0.02 / math.sqrt(cp[CP_P2MAX])
            if ekind != EXC_RECORD:
                h = min(h, epar[E_TP] / 50.0)
            h = _first_h(cp, pat, W, h)
        steps = xo[X_STEPS]
        rej = xo[X_REJ]
        ok = False
        hs = h
        last = False
        while steps + rej < max_steps:
            hs = h
            last = hs >= t_stop - t
            if last:
                hs = t_stop - t
            err = dp5(cp, pat, seg, epar, t, hs, W, np.int64(0), ws, fcols, nfc)
            xo[X_NRHS] += 6.0
            if err <= 1.0:
                h = _grown(h, hs, err, last)
                ok = True
                break
            rej += 1.0
            h = hs * _shrink(err)
        rs[RS_H] = h
        xo[X_REJ] = rej
        if not ok:
            status = STATUS_MAX_STEPS
            break
        xo[X_STEPS] = steps + 1.0
        t_new = t_stop if last else t + hs
        code, who, sig = state_events(cp, pat, W, hs, 1.0)
        fcode, fwho, fsig, pulled = force_events(cp, pat, W, hs, t, seg, epar, ws, frc, sig, mg0, mg1, mg2, fcols,
                                                 nfc)
        if pulled:
            xo[X_N_JUMP] += 1.0
        if fcode != EVC_NONE and (fsig <= sig or code == EVC_NONE):
            code, who, sig = fcode, fwho, fsig
        peaks(cp, pat, W, hs, t, sig, xo, N_XG + J_PSI_MAX, N_XG + J_S_MAX, N_XG + J_TILT, x_u, NX_J, alpha_rest)
        if code == EVC_NONE:
            no_progress = no_progress + 1 if t_new == t else 0
            if no_progress > MAX_NO_PROGRESS:  # the step size has collapsed: stop, undecided, not at the step cap
                status = STATUS_STALLED
                break
            rs[RS_T] = t_new
            for i in range(ny):
                W[W_Y, i] = W[W_YNEW, i]
                W[0, i] = W[6, i]
            if want_history:
                H, nh = _hist(H, nh, t_new, ground_at(t_new, seg, epar), HK_STATE, pat, W, W_Y)
            continue
        # an event: the step retaken to it
        if sig > 0.0:
            restep(cp, pat, seg, epar, t, sig * hs, W, ws, fcols, nfc)
            xo[X_NRHS] += 6.0
            for i in range(ny):
                W[W_Y, i] = W[W_EV, i]
        t_ev = t + sig * hs
        if t_ev == t_last_event:
            stall += 1
        else:
            stall = 0
        t_last_event = t_ev
        if stall > MAX_NO_PROGRESS * MAX_STALL:  # events at one instant for ever: stop, undecided
            status = STATUS_STALLED
            break
        rs[RS_FRESH] = 1.0
        rs[RS_H] = 0.0
        y = W[W_Y]
        if code == EVC_WRONG_SIDE:
            vs = 1e-300
            for j in range(n):
                vs = max(vs, abs(y[col_psi(j) + 1]))
            if pat[2 * who] * y[col_psi(who) + 1] < -cp[CP_TOL] * vs:
                code = EVC_IMPACT  # a pivot at its surface turning into it beyond rounding: an impact there, not a
                # choice at the force level, which takes its rate as 0; a rate at rounding level is a choice (the
                # impact law would leave it as it is)
        if code == EVC_IMPACT:
            ci = col_psi(who)
            if sig > 0.0 and W[W_FEV, ci] != 0.0:  # onto the root by one Taylor term
                dt_e = -W[W_EV, ci] / W[W_FEV, ci]
                dt_e = min(max(dt_e, -sig * hs), (1.0 - sig) * hs)
                for i in range(ny):
                    y[i] += W[W_FEV, i] * dt_e
                t_ev += dt_e
            y[ci] = 0.0
            rs[RS_T] = t_ev
            if want_history:
                H, nh = _hist(H, nh, t_ev, ground_at(t_ev, seg, epar), HK_IMPACT, pat, W, W_Y)
            after_impact(cp, pat, y, who, t_ev, t_exc_end, ground_at(t_ev, seg, epar), xo, ws, frc, best, v0, w0,
                         ynew, zero_psi, free_corner, ytmp, sp)
            cone_after_impact(cp, pat, y, t_ev, ground_at(t_ev, seg, epar), xo, ws, frc, best, zero_psi, zero_s, sp)
            kind = HK_IMPACT_AFTER
        elif code == EVC_TOPPLE:
            y[col_psi(who)] = pat[2 * who] * 0.5 * math.pi
            rs[RS_T] = t_ev
            o = N_XG + NX_J * who
            xo[o + J_PSI_MAX] = 0.5 * math.pi
            status = STATUS_OVERTURNED
            xo[X_TOPPLED] = who
            xo[X_T_FAIL] = t_ev
            if want_history:
                H, nh = _hist(H, nh, t_ev, ground_at(t_ev, seg, epar), HK_END, pat, W, W_Y)
            break
        elif code == EVC_KIND:
            # the pivot passes the edge of the top below (kernels.chain.kinematics): the state goes on, the equations
            # change; the slip set on the far side of the switch, by a hair, so that the next step starts there
            kind_switch(cp, pat, y, who, ws, v0, w0)
            if y[col_s(who) + 1] * pat[2 * who + 1] <= 0.0:  # the plastic map stopped the slip: stick or turn
                for j in range(n):
                    zero_psi[j] = False
                    zero_s[j] = False
                zero_s[who] = True
                y[col_s(who) + 1] = 0.0
                choose(cp, pat, y, ground_at(t_ev, seg, epar), ws, frc, zero_psi, zero_s, best, sp)
                switch(xo, pat, best, n, t_ev, cp, y)
            rs[RS_T] = t_ev
            kind = HK_EVENT
        elif code == EVC_SLIDE_OFF:
            rs[RS_T] = t_ev
            status = STATUS_SLID_OFF
            xo[X_SLIDOFF] = who
            xo[X_T_FAIL] = t_ev
            o = N_XG + NX_J * who
            xo[o + J_S_MAX] = max(xo[o + J_S_MAX], abs(y[col_s(who)]))
            if want_history:
                H, nh = _hist(H, nh, t_ev, ground_at(t_ev, seg, epar), HK_END, pat, W, W_Y)
            break
        else:
            rs[RS_T] = t_ev
            for j in range(n):
                zero_psi[j] = False
                zero_s[j] = False
            if code == EVC_SLIP_STOP:
                y[col_s(who) + 1] = 0.0
                zero_s[who] = True
            elif code == EVC_FACE_OPENS or code == EVC_WRONG_SIDE:
                if code == EVC_WRONG_SIDE and pat[2 * who] * y[col_psi(who)] < 0.0:
                    y[col_psi(who)] = 0.0  # a rounding error on the wrong side of the surface: on it
                zero_psi[who] = True
                zero_s[who] = pat[2 * who + 1] == 0.0
            else:  # a stuck contact reaches the cone
                zero_s[who] = True
                zero_psi[who] = pat[2 * who] == 0.0
            for j in range(n):  # a pivot still at angle and rate 0 may turn either way, or close again
                if pat[2 * j] != 0.0 and y[col_psi(j)] == 0.0 and y[col_psi(j) + 1] == 0.0:
                    zero_psi[j] = True
            if stall > MAX_STALL:
                xo[X_N_STALL] += 1.0
            if stall > MAX_STALL and code == EVC_WRONG_SIDE and n >= 3:
                # a pivot the contact law opens at a tangency (its opening acceleration at rounding level) turns the
                # other way at once, again and again: it is shut (angle and rate 0 already), counted
                for i in range(2 * n):
                    best[i] = pat[i]
                best[2 * who] = 0.0
                m = -math.inf
            else:
                m, pulls = choose(cp, pat, y, ground_at(t_ev, seg, epar), ws, frc, zero_psi, zero_s, best, sp)
                if code == EVC_SLIP_STOP and m < -cp[CP_TOL] and best[2 * who + 1] != 0.0:
                    # no pattern meets the conditions where the slip stopped (a Painleve-like case, or one that needs
                    # flight): the contact sticks, as the least of the failures (friction never pushes a slip on;
                    # a slide at rate 0 whose rate turns the wrong way would stop again at once, for ever)
                    sl_was = pat[2 * who + 1]
                    pat[2 * who + 1] = 0.0
                    zero_s[who] = False
                    m, pulls = choose(cp, pat, y, ground_at(t_ev, seg, epar), ws, frc, zero_psi, zero_s, best, sp)
                    pat[2 * who + 1] = sl_was
            if m < -cp[CP_TOL]:
                xo[X_N_INCONS] += 1.0
            switch(xo, pat, best, n, t_ev, cp, y)
            kind = HK_EVENT
        if want_history:
            H, nh = _hist(H, nh, rs[RS_T], ground_at(rs[RS_T], seg, epar), kind, pat, W, W_Y)
    if want_history and (nh == 0 or H[nh - 1, HC_T] < rs[RS_T]):
        H, nh = _hist(H, nh, rs[RS_T], ground_at(rs[RS_T], _seg(rs), epar), HK_END, pat, W, W_Y)
    xo[X_STATUS] = status
    xo[X_T_END] = rs[RS_T]
    xo[X_U_END] = W[W_Y, 0]
    for j in range(n):
        o = N_XG + NX_J * j
        xo[o + J_S_END] = W[W_Y, col_s(j)]
        xo[o + J_PSI_END] = W[W_Y, col_psi(j)]
    return H[:nh]
