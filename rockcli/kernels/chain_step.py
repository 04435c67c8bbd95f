"""One step of the friction driver (:mod:`rockcli.kernels.chain_run`) and what happens inside it: the Dormand-Prince
step over the chain's states (:mod:`rockcli.kernels.chain`), the step retaken to an event, the events located on
the step's dense output, and the peaks.

Events of a step, the earliest taken:

* on the quartics of the states: a pivot's angle back to 0 (an impact), at ``pi/2`` (the blocks above it
  topple), a slip rate back to 0 (the slip stops: it sticks or turns), a slip reaching the edge of the top below
  (the block above slides off);
* on the contact forces, sampled at 16 points of the step and bisected (as the plinth driver watches its faces): a
  face's corner force down to 0 (it opens about the other corner), a sticking contact reaching Coulomb's cone
  (it starts to slide). A pivot whose normal force is negative at a sample is counted (a jump, once a step).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.chain import (BASE_RIGID, CP_BASE, CP_N, CP_RTOL, F_B, F_BLOW, F_EDGE, F_MU, F_P, F_SC_PSI, F_SC_S, col_psi,
                                   col_s, fld)
from rockcli.kernels.contact import face_corners, solve_pattern
from rockcli.kernels.dopri import _A, _C, _E, _P
from rockcli.kernels.ground import ground_at
from rockcli.kernels.jit import hot, kernel
from rockcli.kernels.layout import W_EV, W_FEV, W_RE, W_TMP, W_Y, W_YNEW
from rockcli.kernels.polynomials import _first_down, _poly
from rockcli.kernels.chain import accelerations, contact_forces, forces_one, kinematics

CP_SC_U, CP_SC_UD = 12, 13  # error scales of the base's u [m] and u' [m/s]
W_DRATE = W_RE + W_TMP  # scratch row: the dense output's derivative at a sample (free until a step is retaken)

EVC_NONE, EVC_IMPACT, EVC_TOPPLE, EVC_SLIP_STOP, EVC_SLIDE_OFF, EVC_FACE_OPENS, EVC_SLIP_STARTS = 0, 1, 2, 3, 4, 5, 6
EVC_WRONG_SIDE = 7
EVC_KIND = 8  # a drum's sliding pivot passes the edge of the top below: its pivot moves to that edge (same state)
N_SAMPLES = 16


@kernel(inline='always')
def _rhs(cp, pat, seg, epar, t, W, src, dst, ws):
    accelerations(cp, pat, W[src], ground_at(t, seg, epar), ws, W[dst])


@hot
def scale_of(cp, col):
    """The error scale of state column ``col``."""
    if col == 0:
        return cp[CP_SC_U]
    if col == 1:
        return cp[CP_SC_UD]
    j = (col - 2) // 4
    k = (col - 2) % 4
    sc = fld(cp, j, F_SC_S) if k < 2 else fld(cp, j, F_SC_PSI)
    return sc * fld(cp, j, F_P) if k % 2 == 1 else sc


@hot
def dp5(cp, pat, seg, epar, t, h, W, r0, ws, fcols, nfc):
    """One Dormand-Prince 5(4) step of every state column from ``(t, W[r0 + W_Y])``, ``W[r0] = f(t, y)`` given;
    the stage derivatives in ``W[r0 + 1 .. r0 + 6]`` (``W[r0 + 6] = f(t + h, ynew)``), the new state in ``W[r0 +
    W_YNEW]``. Returns the RMS of the scaled local error over the free coordinates ``fcols[:nfc]`` (state columns
    of their positions; their rates count too)."""
    ny = W.shape[1]
    ry = r0 + W_Y
    rn = r0 + W_YNEW
    for st in range(1, 7):
        row = r0 + W_TMP if st < 6 else rn
        for i in range(ny):
            acc = 0.0
            for jj in range(st):
                acc += _A[st][jj] * W[r0 + jj, i]
            W[row, i] = W[ry, i] + h * acc
        _rhs(cp, pat, seg, epar, t + _C[st] * h, W, row, r0 + st, ws)
    rtol = cp[CP_RTOL]
    tot = 0.0
    cnt = 0
    for q in range(nfc):
        for i in (fcols[q], fcols[q] + 1):
            err = 0.0
            for jj in range(7):
                err += _E[jj] * W[r0 + jj, i]
            sc = max(abs(W[ry, i]), abs(W[rn, i]), scale_of(cp, i)) * rtol
            tot += (h * err / sc) ** 2
            cnt += 1
    if cnt == 0:
        return 0.0
    return math.sqrt(tot / cnt)


@hot
def restep(cp, pat, seg, epar, t, h, W, ws, fcols, nfc):
    """The last step retaken to ``t + h`` (an event inside it) in rows ``W_RE + ..``; its end state is ``W[W_EV]``
    and ``W[W_FEV]`` its derivative there."""
    ny = W.shape[1]
    for i in range(ny):
        W[W_RE, i] = W[0, i]
        W[W_RE + W_Y, i] = W[W_Y, i]
    dp5(cp, pat, seg, epar, t, h, W, np.int64(W_RE), ws, fcols, nfc)


@hot
def dense_at(W, hs, sig, dst):
    """The dense-output state at fraction ``sig`` of the last step into row ``dst`` of ``W``."""
    ny = W.shape[1]
    for i in range(ny):
        W[dst, i] = _dense_col(W, hs, sig, i)


@kernel(inline='always')
def _dense_col(W, hs, sig, i):
    c1 = 0.0
    c2 = 0.0
    c3 = 0.0
    c4 = 0.0
    for jj in range(7):
        k = W[jj, i]
        c1 += k * _P[jj][0]
        c2 += k * _P[jj][1]
        c3 += k * _P[jj][2]
        c4 += k * _P[jj][3]
    return W[W_Y, i] + sig * hs * (c1 + sig * (c2 + sig * (c3 + sig * c4)))


@kernel(inline='always')
def _dense_rate_col(W, sig, i):
    c1 = 0.0
    c2 = 0.0
    c3 = 0.0
    c4 = 0.0
    for jj in range(7):
        k = W[jj, i]
        c1 += k * _P[jj][0]
        c2 += k * _P[jj][1]
        c3 += k * _P[jj][2]
        c4 += k * _P[jj][3]
    return c1 + sig * (2.0 * c2 + sig * (3.0 * c3 + sig * 4.0 * c4))


@hot
def dense_free_at(W, hs, sig, dst, ddst, fcols, nfc):
    """The dense-output state at fraction ``sig`` into row ``dst`` and the accelerations of the free coordinates
    into row ``ddst`` (the time derivative of their rates' dense output), for the free coordinates only (state
    columns ``fcols[:nfc]`` of their positions): the others do not move in the pattern, their rows keep the step's
    start."""
    ny = W.shape[1]
    for i in range(ny):
        W[dst, i] = W[W_Y, i]
    for q in range(nfc):
        c = fcols[q]
        W[dst, c] = _dense_col(W, hs, sig, c)
        W[dst, c + 1] = _dense_col(W, hs, sig, c + 1)
        W[ddst, c + 1] = _dense_rate_col(W, sig, c + 1)


@hot
def quartic(W, hs, i, sign, shift):
    """``sign * (state i) + shift`` over the last step as a quartic in sigma."""
    c1 = 0.0
    c2 = 0.0
    c3 = 0.0
    c4 = 0.0
    for jj in range(7):
        k = W[jj, i]
        c1 += k * _P[jj][0]
        c2 += k * _P[jj][1]
        c3 += k * _P[jj][2]
        c4 += k * _P[jj][3]
    return (sign * W[W_Y, i] + shift, sign * hs * c1, sign * hs * c2, sign * hs * c3, sign * hs * c4)


@hot
def state_events(cp, pat, W, hs, sig_lim):
    """The first event of the step on the quartics of the states in ``(0, sig_lim]``: ``(code, j, sigma)``."""
    n = int(cp[CP_N])
    best = sig_lim
    code = EVC_NONE
    who = -1
    halfpi = 0.5 * math.pi
    for j in range(n):
        c = pat[2 * j]
        sl = pat[2 * j + 1]
        if c != 0.0:
            ci = col_psi(j)
            q = quartic(W, hs, ci, c, 0.0)
            sg = _first_down(q, 0.0, 0.0, best)
            if sg >= 0.0 and (sg < best or code == EVC_NONE):
                best, code, who = sg, EVC_IMPACT, j
            elif sg < 0.0 and q[0] <= 0.0 and _poly(q, best) < 0.0:
                # a pivot entered at angle 0 that turns the wrong way (into the surface: the pattern could not
                # hold, e.g. at a tie of thresholds): the pattern is chosen again at the start of the step. Also
                # one whose angle starts a rounding error on the wrong side (a joint of a column of drums entered
                # its pivot at -1e-31): without this it would turn on through the surface, unseen by the impact
                # and topple events, which watch the angle on its own side
                return EVC_WRONG_SIDE, j, 0.0
            sg = _first_down(quartic(W, hs, ci, -c, halfpi), 0.0, 0.0, best)
            if sg >= 0.0 and (sg < best or code == EVC_NONE):
                best, code, who = sg, EVC_TOPPLE, j
        if sl != 0.0:
            cs = col_s(j)
            q = quartic(W, hs, cs + 1, sl, 0.0)
            sg = _first_down(q, 0.0, 0.0, best)
            if sg >= 0.0 and (sg < best or code == EVC_NONE):
                best, code, who = sg, EVC_SLIP_STOP, j
            elif sg < 0.0 and q[0] <= 0.0 and _poly(q, best) < 0.0:
                # the slip's analogue of the pivot's wrong side: a slide entered at a rate a rounding error the wrong
                # way (-2e-16 after an impact) would go on backwards with its friction pushing it, unseen by the
                # slip-stop event, which watches the rate on its own side: the slip stops at the start of the step
                # and the contact law chooses again
                return EVC_SLIP_STOP, j, 0.0
            blow = fld(cp, j, F_BLOW)
            if c != 0.0 and math.isfinite(blow):
                sw = c * (blow - fld(cp, j, F_B))  # kernels.chain.kinematics: kind A below, kind B past it
                for d in (1.0, -1.0):
                    sg = _first_down(quartic(W, hs, cs, -d, d * sw), 0.0, 0.0, best)
                    if sg >= 0.0 and (sg < best or code == EVC_NONE):
                        best, code, who = sg, EVC_KIND, j
            edge = fld(cp, j, F_EDGE)
            if math.isfinite(edge):
                for d in (1.0, -1.0):
                    sg = _first_down(quartic(W, hs, cs, -d, edge), 0.0, 0.0, best)
                    if sg >= 0.0 and (sg < best or code == EVC_NONE):
                        best, code, who = sg, EVC_SLIDE_OFF, j
    return code, who, best


@hot
def _force_margins(cp, pat, W, hs, sig, t, seg, epar, ws, frc, mg, fcols, nfc):
    """The pattern's force conditions at fraction ``sig`` of the step, relative to each contact's normal force:
    ``mg[2 j]`` interface ``j``'s face (its smaller corner force), ``mg[2 j + 1]`` its cone while it sticks (``mu N -
    |T|``); ``inf`` where the condition does not apply. Returns the pivots that pull (-1: a singular system)."""
    dense_free_at(W, hs, sig, W_TMP, W_DRATE, fcols, nfc)
    ag = ground_at(t + sig * hs, seg, epar)
    # the forces from the dense output's accelerations (no solve: the step's own accelerations, to its accuracy)
    n = int(cp[CP_N])
    if n == 1 and cp[CP_BASE] == BASE_RIGID:
        sdd = W[W_DRATE, 3] if pat[1] != 0.0 else 0.0  # the row holds the free coordinates' only
        pdd = W[W_DRATE, 5] if pat[0] != 0.0 else 0.0
        forces_one(cp, pat, W[W_TMP], sdd, pdd, ag, frc)
    else:
        nf = kinematics(cp, pat, W[W_TMP], ws)
        free = ws[0]
        x = ws[12]
        for k in range(nf):
            x[k] = W[W_DRATE, free[k] + 1]
        contact_forces(cp, pat, ws, nf, ag, frc)
    for k in range(2 * n):
        mg[k] = math.inf
    pulls = 0
    for j in range(n):
        c = pat[2 * j]
        sl = pat[2 * j + 1]
        N = frc[j, 0]
        scale = max(abs(N), 1e-300)
        if c == 0.0:
            pr, pl = face_corners(cp, j, W[W_TMP, col_s(j)], N, frc[j, 2])
            mg[2 * j] = min(pr, pl) / scale
        elif N < 0.0:
            pulls += 1
        if sl == 0.0 and (c == 0.0 or N > 0.0):
            mg[2 * j + 1] = (fld(cp, j, F_MU) * N - abs(frc[j, 1])) / scale
    return pulls


@hot
def _forces_constant(cp, pat, fcols, nfc):
    """True when no force condition of the pattern can change along a step: every contact a pivot that slides (no
    condition but the pull, which is counted only), or the whole chain sliding as one body on the rigid ground (the
    only free coordinate the bottom slip: every acceleration is the same horizontal one, so every force is the weight
    times a constant ratio and each condition's relative margin is constant; e.g. a crate sliding on the floor)."""
    n = int(cp[CP_N])
    if cp[CP_BASE] == BASE_RIGID and nfc == 1 and fcols[0] == col_s(0) and pat[0] == 0.0:
        return True
    for j in range(n):
        if pat[2 * j] == 0.0 or pat[2 * j + 1] == 0.0:
            return False
    return True


@hot
def _crossing(mg0, mg, n2):
    """The smallest margin among the conditions that were positive at ``mg0`` and are not at ``mg``, and which:
    ``(value, k)``; ``(inf, -1)`` when none crossed."""
    best = math.inf
    who = -1
    for k in range(n2):
        if mg0[k] > 0.0 and mg[k] <= 0.0 and mg[k] < best:
            best = mg[k]
            who = k
    return best, who


@hot
def force_events(cp, pat, W, hs, t, seg, epar, ws, frc, sig_lim, mg0, mg1, mg2, fcols, nfc):
    """The first force event of the step in ``(0, sig_lim]``: a condition that is positive and then is not (16
    samples, then bisection between the last sample where every crossing condition held and the first where one
    failed). A condition that does not hold at the start of the step (a tangency: the pattern was entered at its
    threshold) is an event only once it has held. Returns ``(code, j, sigma, pulled)``; ``pulled`` True when a pivot's
    normal force was negative at a sample before it. ``mg0``, ``mg1``, ``mg2``: scratch (2 n)."""
    n2 = 2 * int(cp[CP_N])
    pulled = False
    if _forces_constant(cp, pat, fcols, nfc):
        return EVC_NONE, -1, sig_lim, pulled
    _force_margins(cp, pat, W, hs, 0.0, t, seg, epar, ws, frc, mg0, fcols, nfc)
    prev = 0.0
    for m in range(1, N_SAMPLES + 1):
        sg = sig_lim * m / N_SAMPLES
        pulls = _force_margins(cp, pat, W, hs, sg, t, seg, epar, ws, frc, mg1, fcols, nfc)
        if pulls > 0:
            pulled = True
        v, k = _crossing(mg0, mg1, n2)
        if k >= 0:
            lo = prev
            hi = sg
            for _ in range(60):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                _force_margins(cp, pat, W, hs, mid, t, seg, epar, ws, frc, mg2, fcols, nfc)
                vm, km = _crossing(mg0, mg2, n2)
                if km >= 0:
                    hi = mid
                    k = km
                else:
                    lo = mid
            code = EVC_FACE_OPENS if k % 2 == 0 else EVC_SLIP_STARTS
            return code, k // 2, hi, pulled
        for q in range(n2):  # a condition that holds now counts as held from here on
            if mg1[q] > 0.0:
                mg0[q] = mg1[q]
        prev = sg
    return EVC_NONE, -1, sig_lim, pulled


@hot
def _abs_peak(c, d, sig_end):
    """``(max |poly(c)| on [0, sig_end], its sigma)``: at the end and at the roots of its rate ``d``."""
    best = abs(_poly(c, sig_end))
    sbest = sig_end
    for sgn in (1.0, -1.0):
        dd = (sgn * d[0], sgn * d[1], sgn * d[2], sgn * d[3], sgn * d[4])
        lo = 0.0
        for _ in range(4):  # up to four turning points
            sp = _first_down(dd, 0.0, lo, sig_end)
            if sp < 0.0:
                break
            v = abs(_poly(c, sp))
            if v > best:
                best, sbest = v, sp
            lo = sp
    return best, sbest


@hot
def peaks(cp, pat, W, hs, t, sig_end, xo, x_psi, x_s, x_tilt, x_u, nx_j, alpha_rest):
    """Peaks of ``|psi_j|``, ``|s_j|``, the blocks' absolute tilts and ``|u|`` over ``[0, sig_end]`` of the last step,
    and the first time ``|psi_j|`` reaches the slenderness ``alpha_rest[j]``. ``x_*`` the indices of the fields in
    ``xo`` (interface fields every ``nx_j``, the base's peak and its time at ``x_u``, ``x_u + 1``)."""
    n = int(cp[CP_N])
    tilt = (0.0, 0.0, 0.0, 0.0, 0.0)
    dtilt = (0.0, 0.0, 0.0, 0.0, 0.0)
    for j in range(n):
        o = j * nx_j
        cp_ = quartic(W, hs, col_psi(j), 1.0, 0.0)
        dp_ = quartic(W, hs, col_psi(j) + 1, 1.0, 0.0)
        if pat[2 * j] != 0.0:
            v, sv = _abs_peak(cp_, dp_, sig_end)
            if v > xo[x_psi + o]:
                xo[x_psi + o] = v
                xo[x_psi + o + 1] = t + sv * hs
            if math.isnan(xo[x_psi + o + 2]) and xo[x_psi + o] >= alpha_rest[j]:
                sa = _first_down(quartic(W, hs, col_psi(j), -pat[2 * j], alpha_rest[j]), 0.0, 0.0, sig_end)
                xo[x_psi + o + 2] = t + (sa if sa >= 0.0 else sv) * hs
        if pat[2 * j + 1] != 0.0:
            cs = quartic(W, hs, col_s(j), 1.0, 0.0)
            ds = quartic(W, hs, col_s(j) + 1, 1.0, 0.0)
            v, sv = _abs_peak(cs, ds, sig_end)
            if v > xo[x_s + o]:
                xo[x_s + o] = v
                xo[x_s + o + 1] = t + sv * hs
        tilt = (tilt[0] + cp_[0], tilt[1] + cp_[1], tilt[2] + cp_[2], tilt[3] + cp_[3], tilt[4] + cp_[4])
        dtilt = (dtilt[0] + dp_[0], dtilt[1] + dp_[1], dtilt[2] + dp_[2], dtilt[3] + dp_[3], dtilt[4] + dp_[4])
        if tilt[1] != 0.0 or tilt[2] != 0.0 or tilt[3] != 0.0 or tilt[4] != 0.0 or tilt[0] != 0.0:
            v, sv = _abs_peak(tilt, dtilt, sig_end)
            xo[x_tilt + o] = max(xo[x_tilt + o], v)
    if x_u >= 0:
        v, sv = _abs_peak(quartic(W, hs, 0, 1.0, 0.0), quartic(W, hs, 1, 1.0, 0.0), sig_end)
        if v > xo[x_u]:
            xo[x_u] = v
            xo[x_u + 1] = t + sv * hs
