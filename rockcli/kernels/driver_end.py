"""The end of a run on an isolated base (:func:`rockcli.kernels.driver.simulate_core`): the rule
(:func:`_end_of_run`) and the theorems it checks.

The run ends when the verdict is *proven* (or at overturning). Each proof below is a small theorem; the code checks
exactly its assumptions. A history run goes on after the proof until exactly ``t_exc_end + tail`` to show the free
motion; nothing after a proof can change the verdict, ``theta_max`` or ``n_impacts``, and nothing before it depends
on the mode or on ``tail`` (the same steps are taken). A run that reaches ``t_exc_end + horizon`` unproven ends
there with ``O_SETTLED = 0`` (e.g. an undamped base that keeps lifting the block): reported, never silently called
safe. (A block on a rigid foundation has its own proofs, P1, P2, P4, P6, P7, in :mod:`rockcli.kernels.rigid`.)

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
"""

from __future__ import annotations

import math

from rockcli.kernels.bearings import bearing_energy, free_disp_bound, free_force_bound
from rockcli.kernels.driver_phases import _hy
from rockcli.kernels.ground import _impulse_left
from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import (E_AP, FOUNDATION_BILINEAR, FOUNDATION_LINEAR, O_T_SETTLED, PHASE_ROCKING,
                                    PHASE_STUCK, P_ALPHA, P_COSA, P_G, P_GAMMA, P_K1, P_K2, P_Q1, P_Q2, P_R, P_THR, P_W,
                                    P_XI, RS_J, RS_PHASE, RS_S, RS_SEG, RS_SETTLED, RS_T, RS_THMAX, RS_UMAX, W_Y)
from rockcli.kernels.linear_base import base_norm, base_norm_of
from rockcli.kernels.steps import _out_of_time


@kernel(inline='always')
def _end_of_run(fkind, prm, ekind, epar, jtab, dt, lin, t_exc_end, early, want_history, t_show_end, t_horizon,
                max_steps, rs, W, out):
    """The end-of-run rule on an isolated base (P3, P3s, P5, P8, and with ``early`` P9, P9s, in
    the module notes): True when the run ends now."""
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
    (see P8 in the module notes); ``inf`` for an undamped base."""
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
