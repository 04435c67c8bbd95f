"""The rigid-foundation driver: :func:`simulate_rigid` runs a block on the ground.

Two states are integrated (theta, theta_dot) and only while the block rocks; while it is stuck the
ground acceleration is scanned for the uplift condition and nothing is integrated
(:func:`_stuck_rigid`). No bearing code is compiled into this kernel: a command that only needs
the rigid foundation compiles only this (and :mod:`rockcli.kernels.steps`, ``dopri``, ``events``,
``ground``, ``polynomials``). The isolated bases have their own driver, :mod:`rockcli.kernels.driver`.

End of the run: the proofs P1, P2, P4, P6, P7 (re-proved under a vertical motion in PV; the general
rule, and P3, P3s, P5, P8 for isolated bases with their early stops P9, P9s during the excitation, are stated in
:func:`rockcli.kernels.driver.simulate_core` and :mod:`rockcli.kernels.driver_end`):

P1 (ground still, block stuck). With ``ag = 0`` and theta = 0 the uplift condition
   ``|ag| > g tan(alpha)`` can never hold again.
P2 (ground still, rocking, ``|theta| < alpha``). Between impacts
   ``E = theta_dot^2/2 + p^2 cos(alpha - |theta|)`` is conserved (Eq 3 with ``ag = 0``); an impact
   keeps theta = 0 and multiplies theta_dot by ``|eta| <= 1`` (Housner's ``1 - 1.5 sin^2 alpha``, or a
   given restitution ``0 < E <= 1``: all this proof and P4 ask of an impact), so E never grows; a rest sets
   ``E = p^2 cos(alpha)``. The potential ``p^2 cos(alpha - |theta|)`` is largest, ``p^2``, at
   ``|theta| = alpha``. Hence if ``E < p^2`` while ``|theta| < alpha`` the block never reaches
   alpha, so never pi/2, and each later peak ``alpha - acos(E/p^2)`` is at most the next one,
   which is added to ``theta_max`` (so the peak is final too). If the block is heading for the
   pivot (``theta theta_dot < 0``) with ``|theta| < alpha``, the potential falls all the way to
   theta = 0, so the impact is certain and ``E`` after it, ``p^2 cos(alpha) + eta^2 (E - p^2
   cos(alpha))``, may be used. Past alpha (``|theta| >= alpha``) no such conclusion holds: the
   same energy means the block falls away from the barrier (issue 9), and the run goes on.
P4 (``early`` only, during the excitation, after the first uplift, block stuck or
   ``|theta| < alpha``). ``dE/dt = -p^2 (ag/g) cos(A) theta_dot`` and, while
   ``|theta| <= alpha``, ``theta_dot^2/2 <= E - p^2 cos(alpha) = X^2``, so
   ``dX/dt <= p^2 |ag| / (sqrt(2) g)`` (impacts, ``X -> |eta| X`` with ``|eta| <= 1`` for any
   restitution, and rests only lower X). Hence
   ``X(t') <= X(t) + p^2/(sqrt(2) g) int_t^t' |ag|``. If that bound with the whole remaining
   impulse (:func:`rockcli.kernels.ground._impulse_left`) is below ``p sqrt(1 - cos(alpha))``
   (``E < p^2``), the block cannot reach alpha before the ground stops (a first arrival at alpha
   needs ``E >= p^2``), and P2 holds from then on: it survives. ``theta_max`` is then only the
   peak so far (``O_PEAK_FINAL = 0``).
P6 (``early`` only, after the first uplift, ``|theta| >= alpha``). Beyond alpha the potential is
   at least ``p^2 sin(alpha)`` (its value at pi/2), so with ``Z^2 = E - p^2 sin(alpha)`` the
   argument of P4 gives ``Z(t') <= Z(t) + p^2/(sqrt(2) g) int_t^t' |ag|``. Coming back inside
   needs ``|theta| = alpha`` again, so ``E >= p^2``, ``Z >= p sqrt(1 - sin(alpha))``; if the bound
   with the whole remaining impulse stays below that, the block can never come back, and once
   the ground is still it falls (between alpha and pi/2 the potential falls outward; below the
   barrier a block moving inward turns back). With the ground already still, a block beyond
   alpha moving outward falls as well. The run ends as overturned with ``t_overturn`` unknown (NaN).
P7 (``early`` only, ``|theta| >= alpha``, moving outward). With ``v = s theta_dot`` (outward
   positive) Eq (3) reads ``dv/dt = -s p^2 sin(A) - s p^2 (ag/g) cos(A)``, ``A = s alpha - theta``.
   Beyond alpha (``s theta`` between alpha and pi/2) ``-s sin(A) >= 0`` (gravity pulls outward) and
   ``sin(alpha) <= cos(A) <= 1``, so ``dv/dt >= -p^2 |ag|/g`` and
   ``v(t') >= v(t) - (p^2/g) int_t^t' |ag|``. If ``v > (p^2/g)`` times the whole remaining impulse, v
   stays positive: theta keeps moving outward (so stays beyond alpha, where the bound holds) until
   the ground is still, and then falls (P6's last case). The run ends as overturned, ``t_overturn``
   unknown (NaN). (P6 bounds the energy, P7 the outward velocity: a block that crossed the barrier
   slowly is caught by P6, one thrown over it by P7.)

PV (a vertical ground acceleration ``a_v``, upward positive; ``g + a_v > 0`` throughout, checked by
   :mod:`rockcli.solve`). Eq (3) becomes ``theta_ddot = -p^2 ((1 + a_v/g) sin A + (ag/g) cos A)``, the
   uplift threshold ``(g + a_v) tan(alpha)`` (the scan :func:`rockcli.kernels.ground._rigid_uplift_vertical`;
   exact on a record, sub-sampled on a pulse) and so the rest rule's threshold (its restoring
   acceleration ``p^2 cos(alpha) ((g + a_v) tan(alpha) - |a|)/g``); the impact map is instantaneous and
   unchanged. ``t_exc_end`` is the end of both motions. What each proof becomes, with
   ``E = theta_dot^2/2 + p^2 cos(alpha - |theta|)`` still defined with the constant g:
   P1, P2: used only after ``t_exc_end``, when ``a_v = 0`` again: unchanged.
   P4: ``dE/dt = -p^2 theta_dot ((a_v/g) sin A + (ag/g) cos A)`` and ``|sin A| <= sin(alpha)`` while
   ``|theta| <= alpha``, so ``dX/dt <= p^2 (|ag| + sin(alpha) |a_v|)/(sqrt(2) g)``: the bound uses the
   remaining impulse of ``|ag|`` plus ``sin(alpha)`` times that of ``|a_v|``
   (:func:`rockcli.kernels.ground._vertical_left`); the rest of the argument is unchanged (a first
   arrival at alpha needs ``E >= p^2`` whatever a_v is; P2 takes over at ``t_exc_end``).
   P6: beyond alpha ``|sin A| <= cos(alpha) <= 1``: the bound uses ``|ag| + |a_v|``, and "the ground is
   still" means both motions are.
   P7: ``-s sin(A) (1 + a_v/g) >= 0`` still holds beyond alpha (``g + a_v > 0``), so
   ``dv/dt >= -p^2 |ag|/g`` as before: unchanged (and with ``ag = 0`` a vertical motion alone cannot
   turn the block back: it still falls).
   The remaining-impulse tables: the horizontal one is unchanged; the vertical series has its own
   (the record table of its samples). The rigid uplift scan: see above.

Steps on a record. A record is piecewise linear, so a step never crosses a sample (the right-hand
side has a kink there) and, on a rigid foundation, also spans at most ``1/RIGID_RECORD_SUBSTEPS``
(a half) of a sample interval. With one Dormand-Prince step per interval the error test is met
by far at every rtol rockcli accepts, yet the truncation error left in the peak is 9.9e-14 alpha
under Kobe (Bassae); at half an interval it is at the rounding floor (1.2e-14, where solutions
perturbed by one ulp of the input scatter by up to 3.9e-14). The cost is about 1.9 times the steps
and 1.6 times the time of a rigid record run. On an isolated base the base's own error dominates and
the full interval is kept (``docs/bench-work-precision.txt``).
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.kernels.dopri import _dp5_step, _restep_rows, _state_at
from rockcli.kernels.events import _count_uplift, _hist_grid, _hist_grid_cut, _hist_peak, _hist_push, impact_map
from rockcli.kernels.ground import (_impulse_left, _rigid_uplift, _rigid_uplift_vertical, _vertical, _vertical_left,
                                   ground_at)
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (EXC_RECORD, FK_RIGID, HK_IMPACT, HK_STATE, HK_UPLIFT, O_T_SETTLED, O_T_THETA_MAX,
                                    O_UPLIFTED, P_ALPHA, P_COSA, P_ETA, P_G, P_HDT, P_P2, P_SINA, P_TH0, P_THD0, P_THR,
                                    PHASE_ROCKING, PHASE_STUCK,
                                    RIGID_RECORD_SUBSTEPS, RS_FRESH, RS_PK_ON, RS_PK_SIG, RS_PK_T,
                                    RS_PEAK_FINAL, RS_PHASE, RS_S, RS_SEG_END, RS_SETTLED, RS_STATUS,
                                    RS_T, RS_THMAX, RS_VEND, STATUS_MAX_STEPS, STATUS_OVERTURNED, W_RE, W_TMP,
                                    W_Y)
from rockcli.kernels.rhs import _rhs_rigid_into
from rockcli.kernels.steps import (EV_FAILED, EV_IMPACT, EV_OVERTURN, _accept_step, _advance_segment, _bounce,
                                   _finish, _initial_state, _out_of_time, _rocking_events, _row_kind, _seg, _start,
                                   _step_start, _to_impact, _to_overturn, _to_step_end, _vertical_piece)

_NO_HY = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)  # no hysteretic elements


@kernel
def _end_of_run_rigid(prm, ekind, epar, jtab, dt, t_exc_end, early, want_history, t_show_end, t_horizon,
                      max_steps, rs, W, out, vjtab, vdt):
    """The end-of-run rule on the ground (P1, P2, P4, P6, P7 in the module notes): True when the run ends now."""
    t = rs[RS_T]
    alpha = prm[P_ALPHA]
    p2 = prm[P_P2]
    if rs[RS_SETTLED] == 0.0:
        settled = False
        if t >= t_exc_end:
            if rs[RS_PHASE] == PHASE_STUCK:
                settled = True  # P1
            elif abs(W[W_Y, 0]) < alpha:
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
                        out[O_T_THETA_MAX] = math.nan
                    settled = True
        if not settled and early and out[O_UPLIFTED] != 0.0:
            c_imp = p2 / (math.sqrt(2.0) * prm[P_G])  # P4, P6: dX/dt <= c_imp |ag|; P7: dv/dt >= -sqrt(2) c_imp |ag|
            h_imp = _impulse_left(ekind, jtab, epar, dt, t)
            v_imp = _vertical_left(vjtab, vdt, t)  # 0 without a vertical motion (PV in the module notes)
            imp = c_imp * h_imp  # P7
            imp4 = c_imp * (h_imp + prm[P_SINA] * v_imp)  # P4 (= imp without a vertical motion)
            imp6 = c_imp * (h_imp + v_imp)  # P6
            x_bar = math.sqrt(p2 * (1.0 - prm[P_COSA]))  # P4: E < p^2  <=>  X < x_bar
            if rs[RS_PHASE] == PHASE_STUCK:
                if imp4 < x_bar:
                    settled = True  # P4
                    rs[RS_PEAK_FINAL] = 0.0
            else:
                ath = abs(W[W_Y, 0])
                En = 0.5 * W[W_Y, 1] ** 2 + p2 * math.cos(alpha - ath)
                if ath < alpha:
                    if math.sqrt(max(0.0, En - p2 * prm[P_COSA])) + imp4 < x_bar:
                        settled = True  # P4
                        rs[RS_PEAK_FINAL] = 0.0
                elif (math.sqrt(max(0.0, En - p2 * prm[P_SINA])) + imp6 < math.sqrt(p2 * (1.0 - prm[P_SINA]))
                      or rs[RS_S] * W[W_Y, 1] > math.sqrt(2.0) * imp
                      or (imp6 == 0.0 and rs[RS_S] * W[W_Y, 1] >= 0.0)):
                    # P6, P7: it falls; the time it lands is not computed
                    rs[RS_STATUS] = STATUS_OVERTURNED
                    rs[RS_THMAX] = 0.5 * math.pi
                    rs[RS_PEAK_FINAL] = 0.0
                    out[O_T_SETTLED] = t
                    return True
        if settled:
            rs[RS_SETTLED] = 1.0
            out[O_T_SETTLED] = t
    if rs[RS_SETTLED] != 0.0 and (not want_history or t >= t_show_end):
        return True
    return _out_of_time(rs, t_horizon, max_steps)


@kernel
def _stuck_rigid(prm, rs, epar, t_stop, out, vertical):
    """Stuck on a rigid foundation: scan the ground motion up to ``t_stop``, integrate nothing."""
    if vertical:
        tu, su = _rigid_uplift_vertical(_seg(rs), epar, prm[P_THR], prm[P_G], rs[RS_T], t_stop)
    else:
        tu, su = _rigid_uplift(_seg(rs), epar, prm[P_THR], rs[RS_T], t_stop)
    if tu < 0.0:
        rs[RS_T] = t_stop
    else:
        rs[RS_T] = tu
        rs[RS_S] = su
        rs[RS_PHASE] = PHASE_ROCKING
        _count_uplift(out, tu)
        rs[RS_FRESH] = 1.0


@kernel
def _take_step_rigid(prm, ekind, epar, max_steps, rs, W, t_stop):
    """One accepted Dormand-Prince step of theta, theta_dot inside ``[t, t_stop]``:
    ``(ok, hs, last)`` (``ok`` False when the step cap is reached first)."""
    h = _step_start(_rhs_rigid_once, FK_RIGID, prm, ekind, epar, rs, W, _NO_HY)
    return _accept_step(_dp5_rigid, rs[RS_S], prm, _seg(rs), epar, rs[RS_T], h, W, rs, max_steps, t_stop)


@kernel
def _rhs_rigid_once(fkind, phase, s, prm, seg, epar, hy, t, W, src, dst):
    """:func:`rockcli.kernels.rhs._rhs_rigid_into` as a call: for the derivative at a step's start
    after an event (rare), so that the step's own copy is the only inlined one."""
    _rhs_rigid_into(fkind, phase, s, prm, seg, epar, hy, t, W, src, dst)


@kernel
def _dp5_rigid(s, prm, seg, epar, t, h, W, r0):
    """The Dormand-Prince step of theta, theta_dot (compiled once for this driver)."""
    return _dp5_step(_rhs_rigid_into, FK_RIGID, PHASE_ROCKING, s, prm, seg, epar, _NO_HY, 0.0, t, h, W, 0, 2, r0)


@kernel
def _restep_rigid(fkind, phase, s, prm, seg, epar, hy, t, h, W, i0, i1):
    """The last step retaken to an event at ``t + h`` (:func:`rockcli.kernels.dopri._restep_rows`)."""
    _restep_rows(W)
    _dp5_rigid(s, prm, seg, epar, t, h, W, np.int64(W_RE))


@kernel(inline='always')
def _history_rigid(H, nh, rs, epar, W, kind):
    t = rs[RS_T]
    return _hist_push(H, nh, t, ground_at(t, _seg(rs), epar), W, W_Y, 0.0, 0.0, 0.0, kind)


@kernel(inline='always')
def _substep_stop(t, seg_end, dt, t_stop):
    """``t_stop``, or the next of the ``RIGID_RECORD_SUBSTEPS - 1`` points that divide the sample
    interval ending at ``seg_end`` evenly, if one lies ahead of ``t`` and before it."""
    n = RIGID_RECORD_SUBSTEPS
    seg_start = seg_end - dt
    for m in range(1, n):
        t_m = seg_start + (m * dt) / n
        if t < t_m:
            return min(t_stop, t_m)
    return t_stop


@kernel
def simulate_rigid(fkind, prm, ekind, epar, acc, jtab, dt, t_begin, t_exc_end, tail, horizon, max_steps,
                   want_history, early, out):
    """Integrate one scene on a rigid foundation; the arguments, outputs and the general end-of-run
    rule are those of :func:`rockcli.kernels.driver.simulate_core` (``fkind`` is ignored)."""
    none = np.empty(0)
    return simulate_rigid_vertical(fkind, prm, ekind, epar, acc, jtab, dt, t_begin, t_exc_end, tail, horizon,
                                   max_steps, want_history, early, none, none, 1.0, out)


@kernel
def simulate_rigid_vertical(fkind, prm, ekind, epar, acc, jtab, dt, t_begin, t_exc_end, tail, horizon, max_steps,
                            want_history, early, vacc, vjtab, vdt, out):
    """:func:`simulate_rigid` under a vertical ground acceleration as well: ``vacc`` [m/s^2, upward
    positive] sampled every ``vdt`` [s] from t = 0, piecewise linear, zero after its last sample
    (empty: none), ``vjtab`` its :func:`rockcli.solve.record_impulse_table`; ``t_exc_end`` is the end
    of both motions. ``g + a_v > 0`` throughout is the caller's to check (module notes, PV)."""
    vertical = vacc.shape[0] > 0
    W, rs, H = _start(ekind, epar, acc, dt, t_begin, want_history, out)
    _initial_state(prm, rs, W, out)
    nh = np.int64(0)
    t_show_end = t_exc_end + tail
    t_horizon = t_exc_end + max(horizon, tail)
    hdt = prm[P_HDT]
    grid = want_history and hdt > 0.0
    kg = np.int64(math.ceil(rs[RS_T] / hdt)) if grid else np.int64(0)  # the next grid time is kg hdt
    if want_history:
        H, nh = _history_rigid(H, nh, rs, epar, W, HK_STATE)
        if grid:
            H, nh, kg = _hist_grid(H, nh, kg, hdt, rs[RS_T], 0.0, rs[RS_T], FK_RIGID, prm, _NO_HY, _seg(rs), epar, W,
                                   np.int64(0), np.int64(2))
        if prm[P_TH0] != 0.0 and prm[P_THD0] == 0.0:  # released from rest at a tilt: its first peak
            H, nh = _hist_peak(H, nh, rs[RS_T], ground_at(rs[RS_T], _seg(rs), epar), W, W_Y)

    while True:
        _advance_segment(rs, ekind, epar, acc, dt, t_begin)
        t_stop = min(rs[RS_SEG_END], t_horizon)
        if vertical:
            _vertical_piece(rs, vacc, vdt)
            t_stop = min(t_stop, rs[RS_VEND])
        if _end_of_run_rigid(prm, ekind, epar, jtab, dt, t_exc_end, early, want_history, t_show_end, t_horizon,
                             max_steps, rs, W, out, vjtab, vdt):
            break
        # a history run shows the free motion up to exactly here (checked after the end-of-run rule, which may
        # have just proven the verdict: a block at rest when the excitation ends stays there to t_show_end,
        # not to the horizon)
        if rs[RS_SETTLED] != 0.0 and rs[RS_T] < t_show_end:
            t_stop = min(t_stop, t_show_end)

        if rs[RS_PHASE] == PHASE_STUCK:
            t0 = rs[RS_T]
            _stuck_rigid(prm, rs, epar, t_stop, out, vertical)
            if grid:  # at rest on the ground: theta = theta_dot = 0 up to the end (or the uplift); no grid row
                # after t_show_end (the grid follows the tail: its rows are counted before the run)
                H, nh, kg = _hist_grid(H, nh, kg, hdt, t0, 0.0, min(rs[RS_T], t_show_end), FK_RIGID, prm, _NO_HY,
                                       _seg(rs), epar, W, np.int64(0), np.int64(2))
            if want_history:
                H, nh = _history_rigid(H, nh, rs, epar, W, HK_UPLIFT if rs[RS_PHASE] == PHASE_ROCKING else HK_STATE)
            continue

        if ekind == EXC_RECORD:  # at most 1/RIGID_RECORD_SUBSTEPS of a sample per step (module notes)
            t_stop = _substep_stop(rs[RS_T], rs[RS_SEG_END], dt, t_stop)
        ok, hs, last = _take_step_rigid(prm, ekind, epar, max_steps, rs, W, t_stop)
        if not ok:
            rs[RS_STATUS] = STATUS_MAX_STEPS
            break
        t_new = t_stop if last else rs[RS_T] + hs

        code, sig = _rocking_events(prm, rs, W, out, hs, t_new, 1.0)
        if want_history and rs[RS_PK_ON] != 0.0:  # a turning point of theta inside the step
            _state_at(W, hs, rs[RS_PK_SIG], np.int64(2))
            H, nh = _hist_peak(H, nh, rs[RS_PK_T], ground_at(rs[RS_PK_T], _seg(rs), epar), W, W_TMP)
        n0 = nh
        if grid:  # the step's grid rows up to t_show_end (those past an event inside it are dropped below)
            H, nh, kg = _hist_grid(H, nh, kg, hdt, rs[RS_T], hs, min(t_new, t_show_end), FK_RIGID, prm, _NO_HY,
                                   _seg(rs), epar, W, np.int64(0), np.int64(2))
        if code == EV_OVERTURN:
            _to_overturn(rs, W, out, hs, sig, 2)
        elif code == EV_FAILED:
            # the block never left theta = 0: back to the stuck phase at the end of the step (the
            # uplift still counts: the uplift condition held; the rotation is below resolution)
            rs[RS_T] = t_new
            W[W_Y, 0] = 0.0
            W[W_Y, 1] = 0.0
            rs[RS_PHASE] = PHASE_STUCK
            rs[RS_S] = 0.0
            rs[RS_FRESH] = 1.0
        elif code == EV_IMPACT:
            _to_impact(_restep_rigid, FK_RIGID, prm, rs, W, epar, _NO_HY, hs, sig, np.int64(2))
            if grid:
                nh, kg = _hist_grid_cut(H, n0, nh, kg, rs[RS_T])
            if want_history:  # the state just before the impact, then (below) just after
                H, nh = _history_rigid(H, nh, rs, epar, W, HK_IMPACT)
            thd1 = W[W_Y, 1]
            thd2, _ = impact_map(prm, thd1)
            rs[RS_S] = -rs[RS_S]
            thr_v = prm[P_THR] * (1.0 + _vertical(rs[RS_T], _seg(rs)) / prm[P_G])  # (g + a_v) tan(alpha)
            _bounce(prm, rs, W, out, thd1, t_exc_end, ground_at(rs[RS_T], _seg(rs), epar), thd2, thr_v)
        else:
            _to_step_end(rs, W, t_new, 2)
        if grid and code == EV_OVERTURN:
            nh, kg = _hist_grid_cut(H, n0, nh, kg, rs[RS_T])
        if want_history:
            H, nh = _history_rigid(H, nh, rs, epar, W, _row_kind(code, rs))
        if code == EV_OVERTURN:
            break

    _finish(rs, W, out)
    return H[:nh]
