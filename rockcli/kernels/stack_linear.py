"""The stack driver on bearings: :func:`simulate_stack_linear` runs a body on its plinth on an isolated base on
linear, sliding or lead-rubber bearings (docs/physics-plinth.md, "On linear bearings", "On sliding and lead-rubber
bearings"), event-driven, one pattern at a time.

States ``y = (psi, psi', theta2, theta2', u, u')`` in every pattern (the angles of a face stay 0), integrated by
Dormand-Prince 5(4) with its continuous extension (the coefficients of SciPy's ``RK45``), the error of each state
kept below ``rtol max(|y|, scale)``. On every accepted step the events are looked for on the continuous extension
at 16 points and located by bisection: a pivot's angle back to 0 (an impact), at ``pi/2`` (its block topples), the
watched face's smaller corner force down to 0 (R: the bearing's force reaching the lower uplift threshold; B: the
plinth's base; P: the joint), and the step is taken again to the first of them (so that no step crosses an event).
While a face is watched the steps stay below ``0.32/p`` and ``1.6/omega_b`` (16 samples each ``0.02/p`` and
``0.1/omega_b`` apart, the reference's resolution). Impacts, the pattern after them and the rest rules are those of
the reference (:mod:`rockcli.kernels.stack_linear_physics`); the step, its events and what is read along it are
in :mod:`rockcli.kernels.stack_linear_step`. The run ends at rest once the free base provably
cannot lift the stack again (after the excitation; linear bearings: P3, the free oscillator's energy bounds ``|F|``;
hysteretic bearings: P3s, ``sqrt(F^2 + K u'^2)`` bounds every later ``|F|``, both stated in
:mod:`rockcli.kernels.driver_end`: the stack at rest on the base is one rigid mass on the bearings,
exactly the single block's stuck base; the base then followed for its later peak, two periods, on hysteretic
bearings only until its energy bound of ``|u|`` is below the peak), when a block topples, or at the horizon. No
early stop during the excitation: verdict-only and history runs take the same steps. On hysteretic bearings the
steps follow the single block's rules for its Bouc-Wen elements (:func:`simulate_stack_linear`).

A lift below the tolerance (docs/physics-plinth.md, "A lift below the tolerance"): just above a threshold a pivot may
lift by less than its error floor ``rtol scale`` (2.6e-13 rad on the issue-36 scene, floor ~1e-9), where the sign of
its angle is the integration's noise; the driver then found it "back at 0" at once, applied impacts of no rate whose
pattern choice was noise, and cycled at one instant until its step cap. Rule (:func:`_unresolved_fall`): a pivot that
started the step at angle and rate exactly 0 and is found back at 0 before its angle passed its floor, its rate below
its floor, lands with no impulse and its face is held shut (not watched, not opened), while the lift it suppresses is
bounded by the double integral of the opening acceleration it would have (:func:`_held_push`, 17 samples per step):
the hold ends when the face holds again or when that bound (angle or rate) would pass its floor, and the face then
opens from rest. Exact to the tolerance: the held run differs from the resolved one by less than one accepted
step's error; a lift that passes its floor never triggers it (300 random scenes bit-identical).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.bearings import (free_disp_bound, free_force_bound, initial_anchor, knee_ratio, knee_step,
                                      motion_direction, reanchor, z_sensitivity)
from rockcli.kernels.ground import ground_at
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import FOUNDATION_LINEAR, J_BASE, J_JOINT, N_OUT, RS_SEG_END, RS_T
from rockcli.kernels.stack_linear_physics import (L_AASM, L_PMAX, L_RTOL, L_SC, L_THR1, L_THRA, L_WB, L_XI, accel,
                                                  choose_post, force, impact_into, kinetic_relative, mass_diag,
                                                  rel_rates, rest_moments, restoring, rhs, velocities)
from rockcli.kernels.stack_linear_step import (C_BODY, C_PLINTH, HALF_PI, V_IMPACT, V_OVERTURN, _dense, _dp5,
                                               _face_kind, _face_value, _first_fall, _held_push, _may_cross,
                                               _rest_bounds, _rest_bounds_hysteretic, _reversal, _scan,
                                               _unresolved_fall)
from rockcli.kernels.stack_linear_step import (N_Z, Z_FR0, Z_FR0_IN, Z_FR1, Z_FR1_IN, Z_FRI0, Z_FRI1,  # noqa: F401
                                               Z_INCONS, Z_JUMPS, Z_NIMP0, Z_NIMP1, Z_NIMPALL0, Z_NIMPALL1, Z_NPLASTIC,
                                               Z_NRESTS, Z_NRHS,
                                               Z_PEAK0, Z_PEAK1, Z_REJ, Z_SETTLED, Z_STATUS, Z_STEPS, Z_TEX0, Z_TEX1,
                                               Z_TILT, Z_TOPPLED, Z_TUP0, Z_TUP1, Z_T_END, Z_T_OVER, Z_T_SETTLED,
                                               Z_UMAX)  # the outputs z, read by rockcli.solve.stack
from rockcli.kernels.stack_physics import S_A1, S_E, S_G, S_REST, S_TOL, forces
from rockcli.kernels.steps import _advance_segment, _seg, _start

# history rows: t, ag, psi, psi', theta2, theta2', u, u', pattern (0 R, 1 B, 2 P, 3 BP), event
ZH_N = 10
EVH_STATE, EVH_UPLIFT, EVH_IMPACT, EVH_REST, EVH_OVERTURN = 0.0, 1.0, 2.0, 3.0, 4.0


@kernel
def _after_impact(j, s, k, sp, lp, bb, Md, y, t, t_exc_end, z, ag):
    """The impact at interface ``j`` (its angle set to 0): the pattern after it, the rest rules. Returns the new
    ``(s, k)``; ``y`` is updated."""
    q0 = y[2] if j == 1 else 0.0
    q1 = y[0] if j == 0 else 0.0
    if j == 0:
        y[2] = 0.0
    else:
        y[0] = 0.0
    vm = velocities(s, k, sp, q0, q1, y[3] if s != 0.0 else 0.0, y[1] if k != 0.0 else 0.0, y[5])
    if t <= t_exc_end:
        z[Z_NIMP0 + j] += 1.0
    z[Z_NIMPALL0 + j] += 1.0
    tol = sp[S_TOL]
    c0, c1, v, imp, margin, pulls, plastic = choose_post(s, k, j, sp, Md, q0, q1, vm, sp[S_E], tol)
    if margin < -tol:
        z[Z_INCONS] += 1.0
    if plastic:
        z[Z_NPLASTIC] += 1.0
    z[Z_JUMPS] += pulls
    for i in range(2):
        if imp[i, 0] > 0.0:
            z[Z_FRI0 + i] = max(z[Z_FRI0 + i], abs(imp[i, 1]) / imp[i, 0])
    r0, r1 = rel_rates(v)
    y[3] = r0 if c0 != 0.0 else 0.0
    y[1] = r1 if c1 != 0.0 else 0.0
    y[5] = v[6]
    rest = sp[S_REST]
    if (c0 != 0.0 or c1 != 0.0) and q0 == 0.0 and q1 == 0.0:
        # the whole stack's rest rule: nothing could lift it at rest, its energy below rest_tol min(alpha_j M_j)
        vs, _ = impact_into(0.0, 0.0, sp, Md, q0, q1, v, np.int64(0), 0.0, np.bool_(False))
        m1, m0 = rest_moments(sp, lp, force(lp, bb, y[4], vs[6]))
        if m1 > 0.0 and m0 > 0.0 and kinetic_relative(Md, v) < rest * min(sp[S_A1] * m1, lp[L_AASM] * m0):
            y[1] = 0.0
            y[3] = 0.0
            y[5] = vs[6]
            z[Z_NRESTS] += 1.0
            return 0.0, 0.0
    cj = c1 if j else c0
    if cj != 0.0:
        s0 = 0.0 if j == 0 else c0
        k0 = 0.0 if j == 1 else c1
        v0, _ = impact_into(s0, k0, sp, Md, q0, q1, v, np.int64(0), 0.0, np.bool_(False))
        d0, d1 = rel_rates(v0)
        d0 = d0 if s0 != 0.0 else 0.0
        d1 = d1 if k0 != 0.0 else 0.0
        R = restoring(j, s0, k0, sp, lp, q0, q1, d0, d1, force(lp, bb, y[4], v0[6]))
        rate = r1 if j else r0
        if R > 0.0 and rate * rate / (2.0 * R) < rest * (sp[S_A1] if j else lp[L_AASM]):
            y[3] = d0
            y[1] = d1
            y[5] = v0[6]
            z[Z_NRESTS] += 1.0
            return s0, k0
        # a pivot left with no opening rate goes where the accelerations take it (the reference's _no_rate)
        rm0, rm1 = rel_rates(vm)
        if cj * rate <= tol * max(abs(rm0), abs(rm1)):
            if j:
                y[1] = 0.0
            else:
                y[3] = 0.0
            pdd, tdd, _ = accel(c0, c1, sp, lp, bb, y, ag)
            if cj * (pdd if j else tdd) > 0.0:
                return c0, c1
            f0 = -c0 if j == 0 else c0
            f1 = -c1 if j == 1 else c1
            pdd, tdd, _ = accel(f0, f1, sp, lp, bb, y, ag)
            if -cj * (pdd if j else tdd) > 0.0:
                return f0, f1
            v0, _ = impact_into(s0, k0, sp, Md, q0, q1,
                                velocities(c0, c1, sp, q0, q1, y[3] if c0 != 0.0 else 0.0,
                                           y[1] if c1 != 0.0 else 0.0, y[5]), np.int64(0), 0.0, np.bool_(False))
            d0, d1 = rel_rates(v0)
            y[3] = d0 if s0 != 0.0 else 0.0
            y[1] = d1 if k0 != 0.0 else 0.0
            y[5] = v0[6]
            return s0, k0
    return c0, c1


@kernel
def _hist(H, nh, t, ag, y, s, k, kind):
    if nh >= H.shape[0]:
        H2 = np.empty((2 * H.shape[0], ZH_N))
        for i in range(nh):  # an explicit copy: a slice assignment compiles numba's generic broadcasting
            for j in range(ZH_N):
                H2[i, j] = H[i, j]
        H = H2
    H[nh, 0] = t
    H[nh, 1] = ag
    for i in range(6):
        H[nh, 2 + i] = y[i]
    H[nh, 8] = (0.0 if s == 0.0 else 2.0) + (0.0 if k == 0.0 else 1.0)
    H[nh, 9] = kind
    return H, nh + 1


@kernel
def _uplift(z, j, t):
    if math.isnan(z[Z_TUP0 + j]):
        z[Z_TUP0 + j] = t


@kernel(nogil=True)
def simulate_stack_linear(sp, lp, fk, bp, ekind, epar, acc, dt, t_begin, t_exc_end, tail, horizon, max_steps,
                          want_history, z):
    """Integrate a body on its plinth on an isolated base under one excitation (``sp`` the stack tuple of
    :func:`rockcli.solve.stack.stack_parameters`, ``lp`` the base's tuple ``L_*``, ``fk`` the bearings' code
    ``FOUNDATION_*`` and ``bp`` the single block's parameter tuple of a hysteretic bearing, whose bearing entries
    are read; anything on linear bearings). ``z`` gets the outputs (``Z_*``); returns the history rows (``t, ag,
    psi, psi', theta2, theta2', u, u', pattern, event``).

    On a hysteretic bearing (the module notes of :mod:`rockcli.kernels.bearings`) the Bouc-Wen elements follow
    ``u`` exactly on the branch of their anchor ``hy``, so, as for the single block, a step ends where ``u``
    reverses (an event, :func:`_reversal`), a step that starts the wrong way is retaken on the other branch, the
    knees of the loop bound the step (:func:`rockcli.kernels.bearings.knee_step`, ``knee_ratio``), the error
    of ``u`` is weighed by ``|dz/du|`` (:func:`_dp5`), and the anchor moves on after every step and event."""
    out = np.zeros(N_OUT)
    _W, rs, _H = _start(ekind, epar, acc, dt, t_begin, np.bool_(False), out)
    for i in range(N_Z):
        z[i] = 0.0
    z[Z_TOPPLED] = -1.0
    for i in (Z_T_OVER, Z_TUP0, Z_TUP1, Z_TEX0, Z_TEX1, Z_T_SETTLED):
        z[i] = np.nan
    H = np.empty((1024 if want_history else 1, ZH_N))
    nh = np.int64(0)
    Md = mass_diag(sp, lp)
    y = np.zeros(6)
    ynew = np.zeros(6)
    K = np.zeros((7, 6))
    s = 0.0
    k = 0.0
    t = t_begin
    h = 0.0
    fresh = True
    settled = False
    t_tail = np.inf
    wb = lp[L_WB]
    thr = min(lp[L_THR1], lp[L_THRA])
    body_first = lp[L_THR1] <= lp[L_THRA]
    # an interface held shut after a lift below the tolerance (_unresolved_fall), its corner, bounds
    held = np.int64(-1)
    hc = 0.0
    reach = 0.0
    rate_b = 0.0
    t_horizon = t_exc_end + max(horizon, tail)
    t_show = t_exc_end + tail
    bound = wb * math.sqrt(1.0 + 4.0 * lp[L_XI] ** 2)
    hyst = fk != FOUNDATION_LINEAR
    hy = initial_anchor(fk, bp) if hyst else (0.0, 1.0, 0.0, 0.0, 0.0, 0.0)
    bb = (fk, bp, hy)
    reversed_ = False
    steps = 0
    rej = 0
    nrhs = 0
    if want_history:
        H, nh = _hist(H, nh, t, 0.0, y, s, k, EVH_STATE)
    while True:
        rs[RS_T] = t
        _advance_segment(rs, ekind, epar, acc, dt, t_begin)
        seg = _seg(rs)
        if s == 0.0 and k == 0.0 and not settled and t >= t_exc_end:
            # the stack at rest rides the free base: P3 (linear) or P3s (hysteretic, rockcli.kernels.driver_end) bounds
            # every later |F| of the base; below the lower uplift threshold nothing lifts again
            if hyst:
                fbound = free_force_bound(fk, bp, hy, y[4], y[5])
            else:
                fbound = bound * math.hypot(y[5], wb * y[4])
            if fbound < thr:
                settled = True
                z[Z_T_SETTLED] = t
                t_tail = t + 4.0 * math.pi / wb
                if want_history:
                    t_tail = max(t_tail, t_show)
        if settled and t >= t_tail - 1e-12:
            break
        if (settled and hyst and (not want_history or t >= t_show)
                and free_disp_bound(fk, bp, hy, y[4], y[5]) <= z[Z_UMAX] * (1.0 + 1e-9)):
            break  # P3s: the free base's energy bounds every later |u| by the peak already reached
        if t >= t_horizon - 1e-12:
            break
        if steps + rej >= max_steps:
            z[Z_STATUS] = -1.0
            break
        t_stop = min(rs[RS_SEG_END], t_horizon, t_tail)
        if (held == 0 and s != 0.0) or (held == 1 and k != 0.0):
            held = -1  # an impact opened the held interface: it pivots on its own again
        if fresh:
            if hyst and not reversed_:  # after an event: the elements anchored where u is, for its direction now
                hy = reanchor(fk, bp, hy, y[4], motion_direction(y[5], hy[1]))
                bb = (fk, bp, hy)
            reversed_ = False
            ag0 = ground_at(t, seg, epar)
            rhs(s, k, sp, lp, bb, y, ag0, K[0])
            nrhs += 1
            fresh = False
            fkind = _face_kind(s, k, held)
            if fkind >= 0:  # a face that cannot hold at the start opens now
                if _face_value(s, k, sp, lp, bb, y, ag0, fkind) < -sp[S_TOL]:
                    s, k = _open(s, k, sp, lp, bb, y, ag0, body_first if held < 0 else held == 0, z, t)
                    fresh = True
                    if want_history:
                        H, nh = _hist(H, nh, t, ag0, y, s, k, EVH_UPLIFT)
                    continue
        fkind = _face_kind(s, k, held)
        watched = fkind >= 0
        cap = min(0.32 / lp[L_PMAX], 1.6 / wb) if watched else np.inf
        if h <= 0.0:
            h = min(0.02 / lp[L_PMAX], 0.1 / wb)
        h = min(h, cap)
        sig_rev = 2.0
        tol_u = 0.0
        flips = 0
        if hyst:  # the knees of the bearing's loop (the single block's rule)
            h = min(h, knee_step(fk, bp, hy, y[5], K[0, 5]))
            tol_u = lp[L_RTOL] / (1.0 / max(abs(y[4]), lp[L_SC + 4]) + z_sensitivity(fk, bp, hy))
        # ---- one accepted step ----
        while True:
            last = h >= t_stop - t
            hs = t_stop - t if last else h
            err = _dp5(s, k, sp, lp, bb, seg, epar, t, hs, y, K, ynew)
            nrhs += 6
            if err <= 1.0 and hyst:
                code, sr = _reversal(y, K, hs, hy[1], tol_u)
                if code == 2:  # the base left the anchor the other way: the other branch (f(t, y) is the same)
                    rej += 1
                    flips += 1
                    if flips > 1:
                        h = 0.5 * hs
                        flips = 0
                    hy = reanchor(fk, bp, hy, y[4], -hy[1])
                    bb = (fk, bp, hy)
                    tol_u = lp[L_RTOL] / (1.0 / max(abs(y[4]), lp[L_SC + 4]) + z_sensitivity(fk, bp, hy))
                    if steps + rej >= max_steps:
                        err = 2.0
                        break
                    continue
                sig_rev = sr if code == 1 else 2.0
                yy = np.empty(6)
                _dense(y, K, hs, min(sig_rev, 1.0), yy)
                kr = knee_ratio(fk, bp, hy, yy[4], hs, y[5])
                if kr > 1.0:  # the step ran through a knee of the loop unresolved: retake it shorter
                    rej += 1
                    h = hs * max(0.2, 0.9 / kr)
                    sig_rev = 2.0
                    if steps + rej >= max_steps:
                        err = 2.0
                        break
                    continue
            if err <= 1.0:
                fac = 5.0 if err == 0.0 else min(5.0, max(0.2, 0.9 * err ** -0.2))
                h = max(h, hs * fac) if last else hs * fac
                break
            rej += 1
            h = hs * max(0.2, 0.9 * err ** -0.2)
            if steps + rej >= max_steps:
                break
        if err > 1.0:
            z[Z_STATUS] = -1.0
            break
        steps += 1
        # ---- events ----
        sig = 1.0
        ev = -1
        reopen = False
        hair_j = -1
        if sig_rev <= 1.0:
            sig, ev = sig_rev, 5  # the base reverses: the step ends there (the elements change branch)
        if k != 0.0:
            if _may_cross(k, y[0], y[1], ynew[0], ynew[1], 0):
                sg = _first_fall(V_IMPACT, C_BODY, k, s, k, sp, lp, bb, seg, epar, t, hs, y, K, 1.0)
                if sg <= sig:
                    sig, ev = sg, 1  # the joint's impact
            if _may_cross(k, y[0], y[1], ynew[0], ynew[1], 1):
                sg = _first_fall(V_OVERTURN, C_BODY, k, s, k, sp, lp, bb, seg, epar, t, hs, y, K, 1.0)
                if sg <= sig:
                    sig, ev = sg, 3  # the body topples
        if s != 0.0:
            if _may_cross(s, y[2], y[3], ynew[2], ynew[3], 0):
                sg = _first_fall(V_IMPACT, C_PLINTH, s, s, k, sp, lp, bb, seg, epar, t, hs, y, K, 1.0)
                if sg < sig or (sg <= sig and ev < 0):
                    sig, ev = sg, 0  # the base's impact
            if _may_cross(s, y[2], y[3], ynew[2], ynew[3], 1):
                sg = _first_fall(V_OVERTURN, C_PLINTH, s, s, k, sp, lp, bb, seg, epar, t, hs, y, K, 1.0)
                if sg <= sig:
                    sig, ev = sg, 2  # the plinth topples
        if ev == 0 or ev == 1:  # a pivot that opened at the start and fell back unresolved: held (a hair-lift)
            c = 2 if ev == 0 else 0
            if _unresolved_fall(c, s if ev == 0 else k, lp, y, K, hs, sig):
                hair_j = ev
                ev = 6
        rest = s == 0.0 and k == 0.0
        fb = ub = np.inf
        if rest:  # at rest: the bearing's force and the base's displacement bounded over the step
            if hyst:
                fb, ub = _rest_bounds_hysteretic(lp, bb, y, K, hs)
            else:
                fb, ub = _rest_bounds(lp, y, K, hs)
        if watched and not (rest and fb < thr):
            sg = _first_fall(fkind, C_BODY, 0.0, s, k, sp, lp, bb, seg, epar, t, hs, y, K, min(sig, 1.0))
            if sg <= sig:
                sig, ev = sg, 4  # the watched face opens
        if not rest or ev >= 0 or ub > z[Z_UMAX] or fb > min(z[Z_FR0_IN], z[Z_FR1_IN]) * sp[S_G]:
            _scan(s, k, sp, lp, bb, seg, epar, t, hs, y, K, sig, z)
        if ev >= 0 and sig < 1.0:  # retake the step to the event
            _dp5(s, k, sp, lp, bb, seg, epar, t, sig * hs, y, K, ynew)
            nrhs += 6
        if held >= 0:  # the held lift's reach over the step; released past its error floor or once the face holds
            dt_ = sig * hs if (ev >= 0 and sig < 1.0) else hs
            amax = _held_push(held, hc, s, k, sp, lp, bb, seg, epar, t, dt_, y, K)
            reach += rate_b * dt_ + 0.5 * amax * dt_ * dt_
            rate_b += amax * dt_
            c = 0 if held == 1 else 2
            t_e = t + dt_
            if _face_value(s, k, sp, lp, bb, ynew, ground_at(t_e, seg, epar), 4 if held == 1 else 3) >= 0.0:
                held = -1  # the face holds again: the lift is over
            elif reach > lp[L_RTOL] * lp[L_SC + c] or rate_b > lp[L_RTOL] * lp[L_SC + c + 1]:
                held = -1  # the lift would pass the floor: it opens at the next step's start
                reopen = True
        t = t + sig * hs if sig < 1.0 else (t_stop if last else t + hs)
        for i in range(6):
            y[i] = ynew[i]
        if ev < 0:
            for i in range(6):
                K[0, i] = K[6, i]
            if hyst:  # the anchor moves on along the branch
                hy = reanchor(fk, bp, hy, y[4], motion_direction(y[5], hy[1]))
                bb = (fk, bp, hy)
            if want_history:
                H, nh = _hist(H, nh, t, ground_at(t, seg, epar), y, s, k, EVH_STATE)
            fresh = reopen
            continue
        fresh = True
        if ev == 6:  # a lift below the tolerance lands: the pivot sticks, its face held (no impulse above the floor)
            j = hair_j
            if t <= t_exc_end:
                z[Z_NIMP0 + j] += 1.0
            z[Z_NIMPALL0 + j] += 1.0
            c = 2 if j == 0 else 0
            y[c] = 0.0
            y[c + 1] = 0.0
            if j == 0:
                hc, s = s, 0.0
            else:
                hc, k = k, 0.0
            held = j
            reach = 0.0
            rate_b = 0.0
            if want_history:
                H, nh = _hist(H, nh, t, ground_at(t, seg, epar), y, s, k, EVH_IMPACT)
            continue
        if ev == 5:  # the base reversed: the elements take the other branch from here
            hy = reanchor(fk, bp, hy, y[4], -hy[1])
            bb = (fk, bp, hy)
            reversed_ = True
            if want_history:
                H, nh = _hist(H, nh, t, ground_at(t, seg, epar), y, s, k, EVH_STATE)
            continue
        ag = ground_at(t, seg, epar)
        if ev == 2 or ev == 3:
            z[Z_TOPPLED] = 0.0 if ev == 2 else 1.0
            z[Z_PEAK0 if ev == 2 else Z_PEAK1] = HALF_PI
            z[Z_T_OVER] = t
            z[Z_STATUS] = 1.0
            if want_history:
                H, nh = _hist(H, nh, t, ag, y, s, k, EVH_OVERTURN)
            break
        if ev == 0 or ev == 1:
            j = 0 if ev == 0 else 1
            if want_history:
                yy = y.copy()
                yy[2 * (1 - j)] = 0.0
                H, nh = _hist(H, nh, t, ag, yy, s, k, EVH_IMPACT)
            s, k = _after_impact(j, s, k, sp, lp, bb, Md, y, t, t_exc_end, z, ag)
            if want_history:
                H, nh = _hist(H, nh, t, ag, y, s, k, EVH_REST if (s == 0.0 and k == 0.0) else EVH_IMPACT)
            continue
        # the watched face opens
        s, k = _open(s, k, sp, lp, bb, y, ag, body_first, z, t)
        if want_history:
            H, nh = _hist(H, nh, t, ag, y, s, k, EVH_UPLIFT)
    if z[Z_TOPPLED] >= 0.0:  # a run that topples: its demand read while both blocks were inside (notes)
        z[Z_FR0] = z[Z_FR0_IN]
        z[Z_FR1] = z[Z_FR1_IN]
    z[Z_SETTLED] = 1.0 if (settled or z[Z_TOPPLED] >= 0.0) else 0.0
    z[Z_T_END] = t
    z[Z_STEPS] = steps
    z[Z_REJ] = rej
    z[Z_NRHS] = nrhs
    return H[:nh]


@kernel
def _open(s, k, sp, lp, bb, y, ag, body_first, z, t):
    """The watched face opens about the corner that keeps pressing: R -> B or P (the lower threshold), B -> BP
    (the plinth lifts), P -> BP (the body lifts off it). Returns the new ``(s, k)``."""
    if s == 0.0 and k == 0.0:
        side = -1.0 if force(lp, bb, y[4], y[5]) > 0.0 else 1.0
        if body_first:
            _uplift(z, J_JOINT, t)
            y[0] = 0.0
            y[1] = 0.0
            return 0.0, side
        _uplift(z, J_BASE, t)
        y[2] = 0.0
        y[3] = 0.0
        return side, 0.0
    pdd, tdd, ab = accel(s, k, sp, lp, bb, y, ag)
    f = forces(s, k, sp, y[2], y[0], y[3], y[1], tdd, pdd, ab)
    if s == 0.0:
        _uplift(z, J_BASE, t)
        y[2] = 0.0
        y[3] = 0.0
        return (1.0 if f[2] > f[3] else -1.0), k
    _uplift(z, J_JOINT, t)
    y[0] = 0.0
    y[1] = 0.0
    return s, (1.0 if f[6] > f[7] else -1.0)
