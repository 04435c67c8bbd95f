""":func:`simulate_stack`: a body on a free plinth (docs/physics-plinth.md), one run on the compiled stack driver
(:mod:`rockcli.kernels.stack` on a rigid foundation, :mod:`rockcli.kernels.stack_linear` on linear, sliding and
lead-rubber bearings), read back into a :class:`StackResponse`.

On the rigid foundation the body's parameters are those :func:`rockcli.solve.simulate` gives it on the ground (the
same vector), so a plinth that never moves leaves the body's answer the single block's, bit for bit.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.models import LinearIsolation, Rigid, Stack
from rockcli.models.foundations import HYSTERETIC
from rockcli.models.impact import check_restitution
from rockcli.solve.excitation import _excitation_arrays, attached_vertical
from rockcli.solve.options import (DEFAULT_HORIZON, DEFAULT_MAX_STEPS, DEFAULT_REST_TOL, DEFAULT_TAIL, _kernel, _rtol,
                                   validate_options)
from rockcli.solve.parameters import _parameters
from rockcli.solve.response import VERDICT_NO_UPLIFT, VERDICT_OVERTURNED, VERDICT_ROCKED
from rockcli.io.units import G

#: Relative slack of the impact consistency tests (docs/physics-plinth.md, "Which pattern follows").
IMPACT_TOL = 1e-9
PATTERNS = ("rest", "body rocks", "plinth rocks", "both rock")


@dataclass(frozen=True)
class BlockPeak:
    """One block's response: its peak rotation on its own support ``theta_max`` [rad] (the body on the plinth, the
    plinth on the ground; pi/2 when it toppled), over its own slenderness ``alpha`` [rad]; its first uplift, the
    first time it passed alpha, its impacts while the ground moved."""

    theta_max: float
    alpha: float
    t_uplift_s: float
    t_exceed_alpha_s: float
    n_impacts: int

    @property
    def theta_max_over_alpha(self) -> float:
        return self.theta_max / self.alpha

    def as_dict(self) -> dict[str, Any]:
        return {"theta_max_rad": self.theta_max, "alpha_rad": self.alpha,
                "theta_max_over_alpha": self.theta_max_over_alpha, "t_uplift_s": _num(self.t_uplift_s),
                "t_exceed_alpha_s": _num(self.t_exceed_alpha_s), "n_impacts": self.n_impacts}


@dataclass(frozen=True)
class StackHistory:
    """The run's rows: ``psi`` the body on the plinth, ``theta2`` the plinth, their rates, the pattern of each
    row (:data:`PATTERNS`) and its event (``uplift``, ``impact``, ``rest``, ``overturn`` or ``""``)."""

    t: np.ndarray
    ag: np.ndarray
    psi: np.ndarray
    psi_dot: np.ndarray
    theta2: np.ndarray
    theta2_dot: np.ndarray
    pattern: np.ndarray
    event: np.ndarray
    #: the base's displacement [m] on linear bearings (None on a rigid foundation)
    u: np.ndarray | None = None


@dataclass(frozen=True)
class StackResponse:
    """Outcome of :func:`simulate_stack` (SI). ``toppled`` is None, ``"body"`` or ``"plinth"`` (the body falls
    with it); ``friction_*`` the peak friction demand ``|T|/N`` at the base and at the joint (``_impulsive``: of the
    impacts' impulses; a run that topples: read while both blocks were inside their slenderness, docs/plinth.md
    "Friction"); ``n_jumps`` the steps and impacts where a pivot would pull (the rocking-only model fails
    there); ``n_inconsistent`` impacts with no consistent pattern after them."""

    verdict: str
    toppled: str | None
    status: int
    settled: bool
    message: str
    body: BlockPeak
    plinth: BlockPeak
    body_tilt_max: float
    alpha_asm: float
    friction_base: float
    friction_joint: float
    friction_base_impulsive: float
    friction_joint_impulsive: float
    n_jumps: int
    n_inconsistent: int
    t_overturn_s: float
    steps: int
    rejected: int
    n_rhs: int
    proof: str
    history: StackHistory | None = field(default=None, repr=False)
    #: peak base displacement on the bearings [m]; NaN on a rigid foundation
    base_disp_max: float = math.nan

    def as_dict(self) -> dict[str, Any]:
        """JSON-ready (no history)."""
        return {"verdict": self.verdict, "toppled": self.toppled, "settled": self.settled, "message": self.message,
                "body": self.body.as_dict(), "plinth": self.plinth.as_dict(), "body_tilt_max_rad": self.body_tilt_max,
                "alpha_asm_rad": self.alpha_asm, "friction_demand": {
                    "base": self.friction_base, "joint": self.friction_joint,
                    "base_impulsive": self.friction_base_impulsive, "joint_impulsive": self.friction_joint_impulsive},
                "n_jumps": self.n_jumps, "n_inconsistent": self.n_inconsistent,
                "t_overturn_s": _num(self.t_overturn_s), "base_disp_max_m": _num(self.base_disp_max),
                "steps": self.steps}


def _num(x):
    return None if x is None or (isinstance(x, float) and math.isnan(x)) else x


def stack_parameters(stack: Stack, rtol, rest_tol: float, restitution):
    """``(prm, prm_asm, sp)``: the body's parameter vector on the ground (as :func:`rockcli.solve.simulate` builds
    it), the assembly's as one block (``eta_asm``, or ``E``), and the stack tuple of :mod:`rockcli.kernels.stack`."""
    from rockcli.kernels import stack_physics as ph

    k = _kernel()
    _, prm = _parameters(stack.body, Rigid(), rtol, rest_tol, restitution)
    _, prm_asm = _parameters(stack.as_block(), Rigid(), rtol, rest_tol, restitution)
    if restitution is None:
        prm_asm[k.P_ETA] = max(0.0, stack.eta_asm)
    sp = np.zeros(ph.N_SP)
    p1, pa = stack.body.p, stack.p_asm
    sp[k.P_P2] = max(p1, pa) ** 2
    sp[k.P_G] = G
    sp[k.P_RTOL] = _rtol(Rigid(), rtol)
    sp[k.P_SC0:k.P_SC0 + 4] = stack.body.alpha, p1 * stack.body.alpha, stack.alpha_asm, pa * stack.alpha_asm
    sp[ph.S_B1], sp[ph.S_H1], sp[ph.S_R1], sp[ph.S_A1] = stack.b1, stack.h1, stack.body.R, stack.body.alpha
    sp[ph.S_I1] = stack.body.R ** 2 / 3.0
    sp[ph.S_B2], sp[ph.S_H2], sp[ph.S_R2], sp[ph.S_A2] = stack.b2, stack.h2, stack.R2, stack.alpha2
    sp[ph.S_M2], sp[ph.S_I2] = stack.m2, stack.R2 ** 2 / 3.0
    sp[ph.S_G] = G
    sp[ph.S_E] = -1.0 if restitution is None else float(restitution)
    sp[ph.S_REST] = rest_tol
    sp[ph.S_A1REST], sp[ph.S_AAREST] = stack.body.alpha, stack.alpha_asm
    sp[ph.S_TOL] = IMPACT_TOL
    return prm, prm_asm, sp


def simulate_stack(stack: Stack, excitation, *, rtol: float | None = None, history: bool = False,
                   tail: float = DEFAULT_TAIL, rest_tol: float = DEFAULT_REST_TOL, horizon: float = DEFAULT_HORIZON,
                   max_steps: int = DEFAULT_MAX_STEPS, restitution: float | None = None,
                   isolation=None) -> StackResponse:
    """The body of ``stack`` on its plinth under ``excitation`` (a record or a pulse) on ``isolation``.

    Parameters
    ----------
    stack : Stack
        The body and its plinth (:class:`rockcli.models.Stack`).
    excitation : Record or pulse
        As for :func:`rockcli.solve.simulate` (horizontal only).
    rtol, tail, rest_tol, horizon, max_steps
        As for :func:`rockcli.solve.simulate` (the rigid foundation's default rtol).
    history : bool
        Return the rows of the run (:class:`StackHistory`).
    restitution : float, optional
        Coefficient of restitution ``E`` (``0 < E <= 1``) of every impact, read as the energetic rule of the note
        (``theta_dot+ = E theta_dot-`` for one block on the ground); None: the plastic (Housner-type) law.
    isolation : optional
        What the plinth stands on, as the ``foundation`` of :func:`rockcli.solve.simulate`: None or
        :class:`rockcli.models.Rigid` the rigid foundation; :class:`rockcli.models.LinearIsolation`, or sliding and
        lead-rubber bearings (:class:`~rockcli.models.SingleConcaveSliding`, :class:`~rockcli.models.LeadRubber`,
        :class:`~rockcli.models.DoubleConcaveSliding`), with ``gamma > 0`` (docs/physics-plinth.md, "On linear
        bearings" and "On sliding and lead-rubber bearings").

    Returns
    -------
    StackResponse
    """
    if not isinstance(stack, Stack):
        raise RockcliInputError(f"stack must be a rockcli.models.Stack, got {type(stack).__name__}")
    if excitation is None:
        raise RockcliInputError("simulate_stack needs an excitation (a record or a pulse)")
    if attached_vertical(excitation) is not None:
        raise RockcliInputError("a body on a plinth runs under the horizontal ground motion only: the record "
                                "carries a vertical component")
    check_stack_isolation(isolation)
    if isinstance(isolation, (LinearIsolation, *HYSTERETIC)):
        return _simulate_stack_linear(stack, excitation, isolation, rtol=rtol, history=history, tail=tail,
                                      rest_tol=rest_tol, horizon=horizon, max_steps=max_steps, restitution=restitution)
    validate_options(rtol, tail, rest_tol, horizon, max_steps)
    restitution = check_restitution(restitution)
    from rockcli.kernels import stack as kst

    k = _kernel()
    ekind, epar, acc, jtab, dt, t_begin, t_exc_end = _excitation_arrays(excitation)
    prm, prm_asm, sp = stack_parameters(stack, rtol, float(rest_tol), restitution)
    out = np.zeros(k.N_OUT)
    xo = np.zeros(kst.N_XO)
    H = kst.simulate_stack(tuple(float(v) for v in prm), tuple(float(v) for v in prm_asm),
                           tuple(float(v) for v in sp), ekind, tuple(float(v) for v in epar), acc, jtab, dt, t_begin,
                           t_exc_end, float(tail), float(horizon), int(max_steps), bool(history), out, xo)
    return _stack_response(out, xo, H if history else None, stack, k, kst)


def linear_parameters(stack: Stack, isolation, rtol) -> np.ndarray:
    """The base's tuple ``lp`` of :mod:`rockcli.kernels.stack_linear_physics` (docs/physics-plinth.md, "On
    linear bearings": ``gamma`` reads ``m`` as body and plinth; on hysteretic bearings ``omega_b`` of the second
    slope and no viscous damping)."""
    from rockcli.kernels import stack_linear_physics as lph

    if not isolation.gamma > 0:
        raise RockcliInputError("a body on a plinth on bearings needs a base of finite mass: give gamma > 0 "
                                "(gamma = 0, an infinitely heavy base, is modelled for the single block only)")
    lp = np.zeros(lph.N_LP)
    body, eff = stack.body, stack.as_block()
    m = 1.0 + stack.m2
    total = m / isolation.gamma
    w = isolation.omega_b
    lp[lph.L_P1SQ], lp[lph.L_PASQ], lp[lph.L_AASM] = body.p ** 2, stack.p_asm ** 2, stack.alpha_asm
    lp[lph.L_RE], lp[lph.L_ETA] = eff.R, stack.eta_asm
    lp[lph.L_G1], lp[lph.L_GE] = isolation.gamma / m, isolation.gamma * stack.R_asm / eff.R
    lp[lph.L_MT], lp[lph.L_WB], lp[lph.L_XI], lp[lph.L_MB] = total, w, getattr(isolation, "xi", 0.0), total - m
    lp[lph.L_RTOL] = _rtol(isolation, rtol)
    pmax = max(body.p, stack.p_asm)
    thr = G * math.tan(min(body.alpha, stack.alpha_asm))
    ws = max(w, pmax)
    lp[lph.L_SC:lph.L_SC + 6] = (body.alpha, body.p * body.alpha, stack.alpha_asm, stack.p_asm * stack.alpha_asm,
                                  thr / ws ** 2, thr / ws)
    lp[lph.L_THR1], lp[lph.L_THRA] = stack.body_uplift_acceleration, stack.assembly_uplift_acceleration
    lp[lph.L_PMAX], lp[lph.L_YC] = pmax, stack.y_c
    return lp


def bearing_parameters(stack: Stack, isolation, rtol, lp) -> tuple:
    """``(fkind, bp)``: the bearings' code and, on hysteretic bearings, the single block's parameter tuple whose
    bearing entries the stack driver reads (:func:`rockcli.kernels.stack_linear_physics.force`), with the stack's
    tolerance and base scales; on linear bearings a tuple of zeros (not read)."""
    from rockcli.kernels import stack_linear_physics as lph

    k = _kernel()
    if isinstance(isolation, LinearIsolation):
        return k.FOUNDATION_LINEAR, (0.0,) * k.N_PRM
    fkind, prm = _parameters(stack.body, isolation, rtol, DEFAULT_REST_TOL)
    prm[k.P_RTOL] = lp[lph.L_RTOL]
    prm[k.P_SC0 + 2], prm[k.P_SC0 + 3] = lp[lph.L_SC + 4], lp[lph.L_SC + 5]
    return int(fkind), tuple(float(v) for v in prm)


def _simulate_stack_linear(stack: Stack, excitation, isolation, *, rtol=None, history=False,
                           tail=DEFAULT_TAIL, rest_tol=DEFAULT_REST_TOL, horizon=DEFAULT_HORIZON,
                           max_steps=DEFAULT_MAX_STEPS, restitution=None) -> StackResponse:
    """The compiled driver on bearings, linear or hysteretic (:mod:`rockcli.kernels.stack_linear`), read into a
    :class:`StackResponse`."""
    from rockcli.kernels import stack_linear as ksl

    validate_options(rtol, tail, rest_tol, horizon, max_steps)
    restitution = check_restitution(restitution)
    ekind, epar, acc, jtab, dt, t_begin, t_exc_end = _excitation_arrays(excitation)
    _, _, sp = stack_parameters(stack, rtol, float(rest_tol), restitution)
    lp = linear_parameters(stack, isolation, rtol)
    fk, bp = bearing_parameters(stack, isolation, rtol, lp)
    z = np.zeros(ksl.N_Z)
    H = ksl.simulate_stack_linear(tuple(float(v) for v in sp), tuple(float(v) for v in lp), fk, bp, ekind,
                                  tuple(float(v) for v in epar), acc, dt, t_begin, t_exc_end, float(tail),
                                  float(horizon), int(max_steps), bool(history), z)
    toppled = {0: "plinth", 1: "body"}.get(int(z[ksl.Z_TOPPLED]))
    up = not (math.isnan(z[ksl.Z_TUP0]) and math.isnan(z[ksl.Z_TUP1]))
    verdict = VERDICT_OVERTURNED if toppled else (VERDICT_ROCKED if up else VERDICT_NO_UPLIFT)
    settled = bool(z[ksl.Z_SETTLED])
    body = BlockPeak(float(z[ksl.Z_PEAK1]), stack.body.alpha, float(z[ksl.Z_TUP1]), float(z[ksl.Z_TEX1]),
                     int(z[ksl.Z_NIMP1]))
    plinth = BlockPeak(float(z[ksl.Z_PEAK0]), stack.alpha2, float(z[ksl.Z_TUP0]), float(z[ksl.Z_TEX0]),
                       int(z[ksl.Z_NIMP0]))
    status = int(z[ksl.Z_STATUS])
    message = _message(status, toppled, verdict, settled, float(z[ksl.Z_T_OVER]), body, plinth, stack)
    hist = None
    if history:
        names = {1.0: "uplift", 2.0: "impact", 3.0: "rest", 4.0: "overturn"}
        hist = StackHistory(H[:, 0].copy(), H[:, 1].copy(), H[:, 2].copy(), H[:, 3].copy(), H[:, 4].copy(),
                            H[:, 5].copy(), np.array([PATTERNS[int(x)] for x in H[:, 8]], dtype=object),
                            np.array([names.get(float(x), "") for x in H[:, 9]], dtype=object), H[:, 6].copy())
    return StackResponse(verdict, toppled, status, settled, message, body, plinth, float(z[ksl.Z_TILT]),
                         stack.alpha_asm, float(z[ksl.Z_FR0]), float(z[ksl.Z_FR1]), float(z[ksl.Z_FRI0]),
                         float(z[ksl.Z_FRI1]), int(z[ksl.Z_JUMPS]), int(z[ksl.Z_INCONS]), float(z[ksl.Z_T_OVER]),
                         int(z[ksl.Z_STEPS]), int(z[ksl.Z_REJ]), int(z[ksl.Z_NRHS]),
                         "bearings at rest" if settled and toppled is None else "", hist,
                         base_disp_max=float(z[ksl.Z_UMAX]))


def _message(status: int, toppled, verdict: str, settled: bool, t_overturn: float, body: BlockPeak,
             plinth: BlockPeak, stack: Stack) -> str:
    """The run's one-line message (both foundations' drivers)."""
    if status == -1:
        return "FAILED: the step cap was reached"
    if toppled is not None:
        return f"the {toppled} topples at t = {t_overturn:.3f} s"
    if verdict == VERDICT_ROCKED:
        return (f"survives: the body peaks at {body.theta_max_over_alpha:.3g} alpha1 on the plinth, the plinth at "
                f"{plinth.theta_max / stack.alpha_asm:.3g} alpha_asm" + ("" if settled else " (NOT PROVEN: horizon)"))
    return "nothing lifts"


def check_stack_isolation(isolation) -> None:
    """Refuse, with one sentence, what a body on a plinth cannot stand on (anything but a rigid foundation, linear
    bearings and the hysteretic ones of :data:`rockcli.models.foundations.HYSTERETIC`)."""
    if isolation is None or isinstance(isolation, (Rigid, LinearIsolation, *HYSTERETIC)):
        return
    raise RockcliInputError(f"a body on a plinth stands on a rigid foundation or on bearings, not on "
                            f"{type(isolation).__name__}")


def _stack_response(out, xo, H, stack: Stack, k, kst) -> StackResponse:
    status = int(out[k.O_STATUS])
    toppled = {0: "plinth", 1: "body"}.get(int(xo[kst.X_TOPPLED]))
    body_up = out[k.O_UPLIFTED] != 0.0 or out[k.O_THETA_MAX] > 0.0
    plinth_up = not math.isnan(xo[kst.X_PL_T_UPLIFT])
    if toppled is not None:
        verdict = VERDICT_OVERTURNED
    elif body_up or plinth_up:
        verdict = VERDICT_ROCKED
    else:
        verdict = VERDICT_NO_UPLIFT
    settled = bool(out[k.O_SETTLED])
    body = BlockPeak(float(out[k.O_THETA_MAX]), stack.body.alpha, float(out[k.O_T_UPLIFT]),
                     float(out[k.O_T_EXCEED]), int(out[k.O_N_IMPACTS]))
    plinth = BlockPeak(float(xo[kst.X_PL_MAX]), stack.alpha2, float(xo[kst.X_PL_T_UPLIFT]),
                       float(xo[kst.X_PL_T_EXCEED]), int(xo[kst.X_PL_N_IMP]))
    message = _message(status, toppled, verdict, settled, float(out[k.O_T_OVERTURN]), body, plinth, stack)
    hist = None if H is None else _history(H, k)
    return StackResponse(verdict, toppled, status, settled, message, body, plinth, float(xo[kst.X_TILT_MAX]),
                         stack.alpha_asm, float(xo[kst.X_FR_B]), float(xo[kst.X_FR_J]), float(xo[kst.X_FRI_B]),
                         float(xo[kst.X_FRI_J]), int(xo[kst.X_N_JUMP]), int(xo[kst.X_N_INCONS]),
                         float(out[k.O_T_OVERTURN]), int(out[k.O_STEPS]), int(out[k.O_REJECTED]), int(out[k.O_NRHS]),
                         "P2S" if xo[kst.X_P2S] else ("P1" if settled and toppled is None else ""), hist)


def _history(H, k) -> StackHistory:
    names = {k.HK_UPLIFT: "uplift", k.HK_IMPACT: "impact", k.HK_IMPACT_AFTER: "impact", k.HK_REST: "rest",
             k.HK_OVERTURN: "overturn"}
    kinds = H[:, k.H_KIND]
    event = np.array([names.get(float(x), "") for x in kinds], dtype=object)
    pattern = np.array([PATTERNS[int(x)] for x in H[:, k.H_Z]], dtype=object)
    return StackHistory(H[:, k.H_T].copy(), H[:, k.H_AG].copy(), H[:, k.H_TH].copy(), H[:, k.H_THD].copy(),
                        H[:, k.H_U].copy(), H[:, k.H_UD].copy(), pattern, event)


def friction_demand_single(block, theta, theta_dot, ag):
    """The friction demand ``|F_x|/F_y`` of a single block rocking on the ground at the states ``theta`` [rad],
    ``theta_dot`` [rad/s] under ``ag`` [m/s^2] (arrays; a history's rows): docs/physics-plinth.md, "Friction
    demand". At rest (``theta = theta_dot = 0``) it is ``|ag|/g``; where ``F_y <= 0`` (the block would jump) it is
    inf. The peak over a history is a sampled one (its rows).

    A row at ``theta = theta_dot = 0`` under ``|ag| > g tan(alpha)`` is no rest (docs/plinth.md, "Friction"): the
    ground acceleration jumped past the uplift threshold there (a one-cosine pulse starts at ``a_p``), and the block
    rocks from zero state on the corner ``-sign(ag)``: its demand there, which grows with ``|ag|`` from ``tan(alpha)``
    at the threshold, is the limit of the same jump ramped in over a time that tends to 0."""
    theta = np.asarray(theta, float)
    theta_dot = np.asarray(theta_dot, float)
    ag = np.asarray(ag, float)
    s = np.where(theta > 0, 1.0, np.where(theta < 0, -1.0, 0.0))
    lifted = (s == 0) & (theta_dot == 0) & (np.abs(ag) > G * math.tan(block.alpha))
    s = np.where(lifted, -np.sign(ag), s)
    A = s * block.alpha - theta
    Rthdd = -0.75 * (G * np.sin(A) + ag * np.cos(A))  # R theta'' from Eq (3), R p^2 = 3 g/4
    fx = np.where(s == 0, ag, Rthdd * np.cos(A) + block.R * theta_dot ** 2 * np.sin(A) + ag)
    fy = np.where(s == 0, G, Rthdd * np.sin(A) - block.R * theta_dot ** 2 * np.cos(A) + G)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(fy > 0, np.abs(fx) / fy, np.inf)
