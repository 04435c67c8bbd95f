"""``simulate(block, foundation, excitation)``: one rocking scene, validated, on the compiled kernel.

Solver contract
---------------
* The block starts at rest on its base, base and ground at rest, at the start of the excitation
  (or, with ``theta0``/``theta_dot0``, rocking from that state: :mod:`rockcli.initial`).
* A record is piecewise linear between its samples, zero after its last sample. A pulse is
  evaluated analytically and is zero outside its support.
* Uplift when the absolute base acceleration ``a`` passes ``-g tan(alpha)`` (rocking on the
  right corner, theta > 0) or ``+g tan(alpha)`` (theta < 0).
* Impacts at theta = 0 keep the total horizontal momentum and the block's angular momentum about
  the new pivot: ``theta_dot+ = eta theta_dot-`` with ``eta = (k - 2)/(k + 4)``,
  ``k = (4 - 3 gamma) cot^2(alpha)`` (Housner's ``1 - 1.5 sin^2 alpha`` when gamma = 0). A given
  coefficient of restitution ``0 < E <= 1`` replaces it by ``E`` on a rigid foundation and by
  ``1 - 4 (1 - E)/(4 - 3 gamma cos^2 alpha)`` on an isolated base (horizontal momentum kept;
  derivation in :mod:`rockcli.impact`).
* Rest: after an impact, when the current base acceleration ``a`` could not lift the block
  (``|a| < g tan alpha``) and the rotation it could still reach against the restoring
  acceleration ``p^2 cos(alpha) (tan(alpha) - |a|/g)``, ``theta_dot^2 / (2 p^2 cos(alpha) (tan(alpha) -
  |a|/g))``, is below ``rest_tol * alpha``, the block is set at rest (a plastic impact that ends
  the train of ever smaller impacts, momentum kept) and moves with its base until the uplift
  condition holds again. ``rest_tol > 0``: without a rest rule the train of impacts never ends.
* Overturning: ``|theta|`` reaches ``pi/2`` (the block lies on its side). The first time
  ``|theta|`` exceeds ``alpha`` is reported separately: passing alpha is not final while the
  ground still moves.
* End of the run, the same in every mode: the run ends once the verdict is *proven*
  (overturned; after the excitation, a block at rest that the still ground, or the free base,
  can no longer lift; on a rigid foundation a block with ``|theta| < alpha`` whose energy is below
  the energy needed to reach alpha). The proofs are stated in
  :func:`rockcli.kernels.simulate_core`. A history run then goes on to ``t_exc_end + tail`` to
  show the free motion. A run still unproven ``horizon`` seconds after the excitation ends there
  with ``settled = False`` and says so (e.g. an undamped base that keeps lifting the block).
  ``early=True`` (verdict-only sweeps) also stops during the excitation once survival is proven
  by the energy the rest of the ground motion can still supply, or overturning once the block,
  past alpha, can no longer be brought back; its ``theta_max`` is then only a lower bound and
  ``t_overturn_s`` may be NaN (``peak_final = False``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.colonnade import apply_cap_ratio, check_cap_ratio
from rockcli.impact import check_restitution, impact_ratio
from rockcli.initial import check_initial_state, still_ground_arrays
from rockcli.models import Block, DoubleConcaveSliding, LeadRubber, LinearIsolation, Rigid, SingleConcaveSliding
from rockcli.units import G

VERDICT_NO_UPLIFT = "no_uplift"
VERDICT_ROCKED = "rocked"
VERDICT_OVERTURNED = "overturned"
#: Verdict of a :func:`simulate_many` job that could not be run (see :class:`JobError`).
VERDICT_ERROR = "error"

#: Default rtol on a rigid foundation and on linear bearings: at least the accuracy of SciPy's RK45 at
#: rtol 1e-8 (the same Dormand-Prince pair, whose error test ``atol + rtol |y|`` is up to twice as strict
#: as the kernel's ``rtol max(|y|, scale)``: at an equal rtol the two tie), for about 13 % more work.
DEFAULT_RTOL = 5e-9
#: Default rtol on sliding and lead-rubber bearings (Bouc-Wen): their runs meet, at this rtol, at least
#: the accuracy of SciPy's Radau at rtol 1e-8 (the stiff reference solver a user would otherwise reach
#: for; measured in docs/bench-work-precision.txt), for about a quarter more work than at 1e-8.
DEFAULT_RTOL_HYSTERETIC = 2e-9
DEFAULT_TAIL = 10.0
DEFAULT_REST_TOL = 1e-8
DEFAULT_HORIZON = 600.0
#: Smallest rest threshold: as it tends to 0 a train of impacts down to rest grows without bound.
REST_TOL_MIN = 1e-15
DEFAULT_MAX_STEPS = 5_000_000
#: Longest free-motion tail of a history run [s].
TAIL_MAX = 1000.0
#: Longest horizon [s]: free motion followed after the excitation to prove a verdict (an hour).
HORIZON_MAX = 3600.0
#: Latest start of a pulse, in periods: float64 time then resolves the pulse to 2e-10 of a period.
PULSE_START_MAX_PERIODS = 1e6
#: points of the unit-pulse tables of the remaining ground impulse (kernels._impulse_left)
N_IMPULSE_TABLE = 257

_PULSE_CODES = {"ricker-sym": 1, "ricker-anti": 2, "sine": 3, "cosine": 4}


@dataclass(frozen=True)
class History:
    """Time history of a run: arrays at every step end and event [SI units].

    ``z``, ``z2`` (Bouc-Wen variables; ``z2`` of the second surface of a double concave bearing)
    and ``bearing_force`` (the bearings' restoring force per unit total mass, ``k_b u + Q z`` over
    ``m + m_b`` [m/s^2]; linear bearings: ``k_b u + c_b u_dot`` over ``m + m_b``) are None where the
    foundation has none.
    """

    t: np.ndarray
    ag: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    u: np.ndarray
    u_dot: np.ndarray
    z: np.ndarray | None = None
    z2: np.ndarray | None = None
    bearing_force: np.ndarray | None = None
    #: the turning points of theta while rocking (theta_dot = 0, on the dense output): times [s] and angles [rad]
    peak_t: np.ndarray | None = None
    peak_theta: np.ndarray | None = None


@dataclass(frozen=True)
class Response:
    """Outcome of :func:`simulate`.

    Attributes
    ----------
    verdict : str
        ``no_uplift``, ``rocked`` (survives) or ``overturned``.
    status : int
        0 finished, 1 overturned (terminal event), -1 failed (step cap reached).
    message : str
        What happened, in words.
    theta_max : float
        Peak ``|theta|`` [rad] (``pi/2`` when overturned).
    base_disp_max_m : float
        Peak ``|u|``, base displacement relative to the ground [m] (0 on a rigid foundation).
    n_impacts : int
        Impacts while the ground moves (the same with or without history).
    n_impacts_total : int
        Impacts integrated, including free rocking after the excitation (a verdict-only run
        stops once the outcome is settled, so it may count fewer).
    settled : bool
        The verdict is proven (see the module notes); False when the run reached its horizon.
    peak_final : bool
        ``theta_max`` is the run's peak (False only for ``early`` verdict-only runs stopped during
        the excitation: then it is the peak so far).
    n_base_reversals : int
        Steps that ended where a hysteretic base reversed (0 for other foundations).
    """

    verdict: str
    status: int
    message: str
    t_uplift_s: float
    t_overturn_s: float
    t_exceed_alpha_s: float
    theta_max: float
    theta_max_over_alpha: float
    t_theta_max_s: float
    n_impacts: int
    n_impacts_total: int
    n_uplifts: int
    n_rests: int
    base_disp_max_m: float
    steps: int
    rejected_steps: int
    nfev: int
    settled: bool
    t_end_s: float
    peak_final: bool = True
    t_settled_s: float = math.nan
    n_base_reversals: int = 0
    history: History | None = field(default=None, repr=False)

    @property
    def overturned(self) -> bool:
        return self.verdict == VERDICT_OVERTURNED

    def summary(self) -> dict[str, Any]:
        """The scalar results as a plain dict (JSON-ready; NaN becomes None)."""

        def clean(v):
            if isinstance(v, float) and math.isnan(v):
                return None
            return v

        keys = ("verdict", "t_uplift_s", "t_overturn_s", "t_exceed_alpha_s", "theta_max_over_alpha",
                "theta_max", "t_theta_max_s", "n_impacts", "n_impacts_total", "n_uplifts", "n_rests",
                "base_disp_max_m", "steps", "rejected_steps", "nfev", "settled", "t_settled_s", "peak_final",
                "t_end_s", "status", "message")
        return {k: clean(getattr(self, k)) for k in keys}


@dataclass(frozen=True)
class JobError:
    """What :func:`simulate_many` returns for a job that fails validation: the reason, no results.

    It reads like a :class:`Response` where callers look (``verdict`` is ``"error"``,
    ``overturned`` is False, ``message`` says why, numbers are NaN), so one bad scene does not
    stop a batch; ``error`` is the message (a :class:`Response` has no ``error``).
    """

    error: str
    verdict: str = VERDICT_ERROR
    status: int = -2
    overturned: bool = False
    theta_max_over_alpha: float = math.nan
    t_overturn_s: float = math.nan
    t_uplift_s: float = math.nan
    base_disp_max_m: float = math.nan
    n_impacts: int | None = None

    @property
    def message(self) -> str:
        return self.error


def _kernel():
    from rockcli import kernels

    return kernels


def _threads() -> int:
    """Threads a sweep runs on: the cores this process may use (``NUMBA_NUM_THREADS`` caps them)."""
    import os

    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    cap = os.environ.get("NUMBA_NUM_THREADS", "")
    return max(1, min(cores, int(cap))) if cap.isdigit() and int(cap) > 0 else max(1, cores)


def record_impulse_table(acc: np.ndarray, dt: float) -> np.ndarray:
    """Suffix integrals ``int_{t_j}^{t_end} |ag| dt`` [m/s] of a piecewise-linear record, one per sample.

    Exact per interval (a linear piece that changes sign integrates to ``dt (a0^2 + a1^2) /
    (2 (|a0| + |a1|))``), summed from the end and enlarged by 1e-9 relative for rounding: an upper
    bound, as the kernel's early stop (P4) needs.
    """
    a0, a1 = np.abs(acc[:-1]), np.abs(acc[1:])
    same = acc[:-1] * acc[1:] >= 0.0
    tot = a0 + a1
    piece = np.where(same, 0.5 * dt * tot, 0.5 * dt * (a0 * a0 + a1 * a1) / np.where(tot > 0, tot, 1.0))
    out = np.zeros(acc.size)
    out[:-1] = np.cumsum(piece[::-1])[::-1]
    return out * (1.0 + 1e-9)


_PULSE_ZEROS = {  # zeros of the unit pulse's acceleration, tau = t - t0 in units of T_p
    "ricker-sym": (-1.0 / (math.pi * math.sqrt(2.0)), 1.0 / (math.pi * math.sqrt(2.0))),
    "ricker-anti": (-1.5 / math.pi, 0.0, 1.5 / math.pi),
    "sine": (0.0, 0.5, 1.0),
    "cosine": (0.25, 0.75),
}
_UNIT_TABLES: dict = {}


def pulse_impulse_table(shape: str) -> tuple[np.ndarray, np.ndarray]:
    """``(zeros, J)``: suffix integrals of ``|ag|`` of the unit pulse (a_p = 1, T_p = 1) from
    :data:`N_IMPULSE_TABLE` equally spaced points of its support to its end.

    Exact: between consecutive zeros of the acceleration, ``int |ag| = |delta v|`` with the
    pulse's closed-form velocity. Enlarged by 1e-9 relative for rounding. Cached per shape (the
    zeros array is the kernel's dummy ``acc`` for a pulse, shared by all pulses of the shape).
    """
    if shape not in _UNIT_TABLES:
        from rockcli.pulses import make_pulse

        unit = make_pulse(shape, 1.0, 1.0)
        ts, te = unit.support()
        grid = np.linspace(ts, te, N_IMPULSE_TABLE)
        zeros = [unit.t0 + z for z in _PULSE_ZEROS[shape] if ts < unit.t0 + z < te]
        pts = np.unique(np.concatenate([grid, zeros]))
        dv = np.abs(np.diff(np.asarray(unit.velocity(pts), dtype=float)))
        suffix = np.zeros(pts.size)
        suffix[:-1] = np.cumsum(dv[::-1])[::-1]
        J = suffix[np.searchsorted(pts, grid)] * (1.0 + 1e-9) + 1e-15
        _UNIT_TABLES[shape] = (np.zeros(N_IMPULSE_TABLE), J)
    return _UNIT_TABLES[shape]


def _excitation_arrays(excitation):
    """(ekind, epar, acc, jtab, dt, t_begin, t_exc_end) for the kernel."""
    k = _kernel()
    if hasattr(excitation, "acc") and hasattr(excitation, "dt"):
        acc = np.ascontiguousarray(excitation.acc, dtype=np.float64)
        dt = float(excitation.dt)
        if acc.ndim != 1 or acc.size < 2:
            raise RockcliInputError(f"record {getattr(excitation, 'name', '')!r} needs at least 2 samples")
        if not np.all(np.isfinite(acc)):
            raise RockcliInputError(f"record {getattr(excitation, 'name', '')!r} has NaN or infinite samples")
        if not (math.isfinite(dt) and dt > 0):
            raise RockcliInputError(f"record {getattr(excitation, 'name', '')!r} has a non-positive time step {dt!r}")
        epar = np.zeros(8)
        epar[k.E_AP] = 1.0  # scale factor of the record
        return k.EXC_RECORD, epar, acc, record_impulse_table(acc, dt), dt, 0.0, (acc.size - 1) * dt
    shape = getattr(excitation, "shape", None)
    if shape in _PULSE_CODES:
        a_p, T_p, t0 = float(excitation.a_p), float(excitation.T_p), float(excitation.t0)
        if not (math.isfinite(a_p) and math.isfinite(T_p) and T_p > 0 and math.isfinite(t0)):
            raise RockcliInputError(f"pulse {shape}: a_p must be finite and T_p positive")
        ts, te = (float(v) for v in excitation.support())
        # the run starts at rest at t = 0: a pulse that starts earlier would be cut (its start lost)
        if ts < 0.0:
            raise RockcliInputError(
                f"pulse {shape} (T_p = {T_p:g} s, t0 = {t0:g} s) starts at {ts:g} s, before the run starts at "
                f"t = 0 s: give t0 >= {t0 - ts:g} s")
        # float64 time resolves the pulse to eps * t / T_p: 2e-10 of a period at t = 1e6 T_p
        if ts > PULSE_START_MAX_PERIODS * T_p:
            raise RockcliInputError(
                f"pulse {shape} (T_p = {T_p:g} s) starts at {ts:g} s, later than the supported "
                f"{PULSE_START_MAX_PERIODS:g} T_p = {PULSE_START_MAX_PERIODS * T_p:g} s (the run's clock could no "
                f"longer resolve the pulse): give a smaller t0")
        epar = np.zeros(8)
        epar[k.E_AP], epar[k.E_TP], epar[k.E_T0], epar[k.E_TS], epar[k.E_TE] = a_p, T_p, t0, ts, te
        if shape == "ricker-anti":
            from rockcli.pulses import RICKER_ANTI_BETA

            epar[k.E_BETA] = RICKER_ANTI_BETA
        zeros, jtab = pulse_impulse_table(shape)
        return _PULSE_CODES[shape], epar, zeros, jtab, 1.0, min(0.0, ts), te
    raise RockcliInputError(f"cannot simulate excitation of type {type(excitation).__name__}")


def default_rtol(foundation) -> float:
    """The default rtol of a foundation: :data:`DEFAULT_RTOL` (rigid, linear bearings) or
    :data:`DEFAULT_RTOL_HYSTERETIC` (sliding and lead-rubber bearings)."""
    if isinstance(foundation, (SingleConcaveSliding, DoubleConcaveSliding, LeadRubber)):
        return DEFAULT_RTOL_HYSTERETIC
    return DEFAULT_RTOL


def _rtol(foundation, rtol) -> float:
    """``rtol`` as given, or the foundation's default when None."""
    return default_rtol(foundation) if rtol is None else float(rtol)


def _parameters(block: Block, foundation, rtol, rest_tol: float, restitution: float | None = None,
                cap_ratio: float = 0.0):
    """``(fkind, prm)``: the kernel's foundation code and parameter vector (``rockcli.kernels.layout``);
    ``rtol`` None takes the foundation's default; ``restitution`` None Housner's (:mod:`rockcli.impact`);
    ``cap_ratio`` > 0 a capped colonnade (:mod:`rockcli.colonnade`)."""
    k = _kernel()
    rtol = _rtol(foundation, rtol)
    prm = np.zeros(k.N_PRM)
    p = block.p
    alpha = block.alpha
    gamma = foundation.gamma
    prm[k.P_P2] = p * p
    prm[k.P_G] = G
    prm[k.P_ALPHA] = alpha
    prm[k.P_R] = block.R
    prm[k.P_GAMMA] = gamma
    prm[k.P_THR] = G * math.tan(alpha)
    prm[k.P_SINA] = math.sin(alpha)
    prm[k.P_COSA] = math.cos(alpha)
    prm[k.P_H] = block.h
    prm[k.P_ETA] = impact_ratio(alpha, gamma, restitution)
    # base velocity jump at an impact, u_dot+ = u_dot- + P_DU theta_dot-: the total horizontal momentum
    # u_dot + gamma h theta_dot is kept, so P_DU = gamma h (1 - eta) (= 6 gamma h/(k + 4) when eta is not
    # clamped; a block too squat to rock, eta clamped to 0, hands all its momentum to the base)
    prm[k.P_DU] = gamma * block.h * (1.0 - prm[k.P_ETA])
    prm[k.P_REST] = rest_tol
    prm[k.P_RTOL] = rtol
    # error scales: the tolerance on a state is rtol * max(|y|, scale)
    prm[k.P_SC0 + 0] = alpha
    prm[k.P_SC0 + 1] = p * alpha
    if isinstance(foundation, Rigid):
        fkind = k.FOUNDATION_RIGID
        prm[k.P_SC0 + 2] = prm[k.P_SC0 + 3] = 1.0
    elif isinstance(foundation, LinearIsolation):
        fkind = k.FOUNDATION_LINEAR
        w = foundation.omega_b
        prm[k.P_W] = w
        prm[k.P_XI] = foundation.xi
        # the smaller of the displacement at which the bearings' force uplifts the block and the
        # block's own length scale g tan(alpha)/p^2 = (4/3) R tan(alpha)
        prm[k.P_SC0 + 2] = prm[k.P_THR] / max(w, p) ** 2
        prm[k.P_SC0 + 3] = prm[k.P_THR] / max(w, p)
    elif isinstance(foundation, (SingleConcaveSliding, LeadRubber, DoubleConcaveSliding)):
        w = foundation.omega_b
        prm[k.P_W] = w
        prm[k.P_BWN] = foundation.n
        prm[k.P_BWC] = foundation.gamma_bw - foundation.beta
        if isinstance(foundation, DoubleConcaveSliding):
            fkind = k.FOUNDATION_DCSS
            prm[k.P_K1] = G / foundation.R1_eff
            prm[k.P_K2] = G / foundation.R2_eff
            prm[k.P_Q1] = foundation.mu1 * G
            prm[k.P_Q2] = foundation.mu2 * G
            prm[k.P_UY1] = prm[k.P_UY2] = 0.5 * foundation.u_y  # the bearing as a whole yields at u_y
        else:
            fkind = k.FOUNDATION_BILINEAR
            prm[k.P_Q1] = foundation.strength_ratio * G
            prm[k.P_UY1] = foundation.u_y
        prm[k.P_SC0 + 2] = prm[k.P_THR] / max(w, p) ** 2
        prm[k.P_SC0 + 3] = prm[k.P_THR] / max(w, p)
    else:
        raise RockcliInputError(f"unknown foundation {foundation!r}")
    apply_cap_ratio(prm, k, block, check_cap_ratio(cap_ratio, foundation), restitution)  # a capped colonnade
    return fkind, prm


def bearing_force_path(foundation, u) -> dict[str, np.ndarray]:
    """The bearings of ``foundation`` under an imposed base displacement history ``u`` [m].

    Returns ``{"force": ..., "z": ..., "z2": ...}``: the bearings' restoring force per unit total
    mass ``(k_b u + Q z)/(m + m_b)`` [m/s^2] (divide by g for force over weight) and the Bouc-Wen
    variables (``z2`` for a double concave bearing only), from the same code the solver uses. The
    path is taken as monotone between samples (exact for a piecewise-monotone path). Linear
    bearings give their elastic force only (no velocity here).
    """
    if isinstance(foundation, Rigid):
        raise RockcliInputError("a rigid foundation has no bearings")
    u = np.ascontiguousarray(u, dtype=np.float64)
    if u.ndim != 1 or not np.all(np.isfinite(u)):
        raise RockcliInputError("the displacement path must be a 1-D array of finite values in m")
    k = _kernel()
    block = Block(1.0, 0.2)  # the bearing's parameters do not depend on the block
    fkind, prm = _parameters(block, foundation, DEFAULT_RTOL, DEFAULT_REST_TOL)
    out = np.zeros((u.size, 3))
    if fkind == k.FOUNDATION_LINEAR:
        out[:, 0] = -foundation.omega_b ** 2 * u
    else:
        k.force_along_path(fkind, tuple(float(v) for v in prm), u, out)
    res = {"force": -out[:, 0], "z": out[:, 1] if fkind >= k.FOUNDATION_BILINEAR else None,
           "z2": out[:, 2] if fkind == k.FOUNDATION_DCSS else None}
    return res


def validate_options(rtol=None, tail=DEFAULT_TAIL, rest_tol=DEFAULT_REST_TOL, horizon=DEFAULT_HORIZON,
                     max_steps=DEFAULT_MAX_STEPS):
    """Refuse solver options out of their limits (:class:`RockcliInputError`, one sentence)."""
    try:
        rtol = DEFAULT_RTOL if rtol is None else float(rtol)  # None: each foundation's default
        tail, rest_tol, horizon = float(tail), float(rest_tol), float(horizon)
    except (TypeError, ValueError):
        raise RockcliInputError("rtol, tail, rest_tol and horizon must be numbers") from None
    if not (math.isfinite(rtol) and 1e-14 <= rtol <= 1e-2):
        raise RockcliInputError(f"rtol must lie between 1e-14 and 1e-2, got {rtol:g}")
    if not (math.isfinite(tail) and 0 <= tail <= TAIL_MAX):
        raise RockcliInputError(f"tail must be a time between 0 and {TAIL_MAX:g} s (the free motion a history run "
                                f"shows after the excitation), got {tail:g}")
    if not (math.isfinite(horizon) and 0 <= horizon <= HORIZON_MAX):
        raise RockcliInputError(f"horizon must be a time between 0 and {HORIZON_MAX:g} s (the free motion followed "
                                f"after the excitation to prove a verdict), got {horizon:g}")
    if not (math.isfinite(rest_tol) and REST_TOL_MIN <= rest_tol < 1):
        raise RockcliInputError(
            f"rest_tol must satisfy {REST_TOL_MIN:g} <= rest_tol < 1 (without a rest rule a train of impacts never "
            f"ends), got {rest_tol:g}")
    if isinstance(max_steps, bool) or not isinstance(max_steps, (int, np.integer)) or max_steps < 1:
        raise RockcliInputError(f"max_steps must be a whole number >= 1, got {max_steps!r}")


def _estimate_steps(block: Block, foundation, prepared, rtol: float, tail: float, rest_tol: float,
                    horizon: float, history: bool, restitution: float | None = None):
    """``(estimate, samples, run)``: an upper estimate of the integrator steps a scene needs, its
    record samples and its longest run [s]; see :func:`_check_work`."""
    k = _kernel()
    rtol = _rtol(foundation, rtol)
    ekind, epar, acc, jtab, dt, t_begin, t_exc_end = prepared
    if ekind == k.EXC_RECORD:
        samples, active = acc.size, t_exc_end
    else:
        samples, active = 0, epar[k.E_TE] - epar[k.E_TS]
    f = max((default_rtol(foundation) / rtol) ** 0.2, 1.0)  # a looser rtol saves little where events and stiffness rule
    rate = 2.0 * block.p * f
    loss = 1.5 * math.sin(block.alpha) ** 2  # 1 - eta: the share of theta_dot an impact takes
    if restitution is not None:  # a restitution above Housner's loses less (at least 1e-3 counted)
        loss = min(loss, max(1.0 - restitution, 1e-3))
    settle = (2.0 / block.p) * math.sqrt(2.0) / loss  # a rocking cascade
    stiff = 0.0
    if isinstance(foundation, LinearIsolation):
        w, xi = foundation.omega_b, foundation.xi
        stiff = w * (xi + math.sqrt(xi * xi + 1.0))
        rate += stiff / 3.0 + (20.0 if xi < 0.05 else 3.0) * w * f
        if xi < 0.05:  # an undamped light base keeps lifting the block: impacts chatter near rest
            rate += 0.03 * foundation.gamma ** 8 * block.p / math.sqrt(rest_tol)
        slow = w * (xi - math.sqrt(xi * xi - 1.0)) if xi > 1.0 else xi * w  # slowest decay rate of the free base
        settle = max(settle, 40.0 / slow if slow > 0.0 else math.inf)
    after = min(max(horizon, tail), settle)
    if history:
        after = max(after, tail)
    impacts = math.log(1.0 / rest_tol) / (2.0 * loss)  # one cascade down to rest
    cascade = 2.0 * impacts * (1.0 + stiff / (3.0 * block.p))  # a flight of ~1/p at the base's stable step
    per_sample = k.RIGID_RECORD_SUBSTEPS if isinstance(foundation, Rigid) else 1  # steps per sample, at least
    return samples * per_sample + (active + after) * rate + cascade, samples, active + after


def _check_work(block: Block, foundation, prepared, rtol: float, tail: float, rest_tol: float, horizon: float,
                max_steps: int, history: bool = False, restitution: float | None = None) -> None:
    """Refuse, in one sentence, a scene whose estimated step count exceeds a fifth of ``max_steps``.

    So that an accepted scene never reaches the step cap, which is then left for genuine numerical
    failures. The estimate (:func:`_estimate_steps`) is one step per record sample (no step crosses
    one; two on a rigid foundation, whose steps span at most half a sample) plus a rate times the
    run: the active excitation (record length or pulse support) and, after it, the time the
    verdict may take to be proven, at most max(horizon, tail): the longer of a rocking cascade,
    ``(2/p) sqrt 2/(1.5 sin^2 alpha)``, and 40 decay times of the free base's slowest mode
    (infinite for an undamped base; a history run also shows ``tail``). The rate adds
    ``omega_b (xi + sqrt(xi^2 + 1))/3`` for a stiff base (explicit Dormand-Prince is stable to
    ``h lambda ~ 3.3``), ``B omega_b f`` for its oscillation at the accuracy rtol asks (``B = 3``
    steps per radian when damped, 20 when xi < 0.05: an undamped base keeps every kick of the
    record and of each impact) and ``2 p f`` for the block, with ``f = max((rtol_0/rtol)^(1/5), 1)``,
    ``rtol_0`` the foundation's default rtol
    (fifth-order accuracy; no credit for a looser rtol), and for an undamped base ``0.03 gamma^8
    p/sqrt(rest_tol)`` (a light base, gamma near 1, keeps lifting the block, whose impacts then
    chatter near the rest threshold, up to ``p/(2 sqrt(2 rest_tol))`` a second; an empirical term,
    negligible below gamma = 0.6); plus
    one cascade of impacts down to rest, ``ln(1/rest_tol)/(3 sin^2 alpha)`` impacts of ``2 (1 +
    lambda/(3 p))`` steps each (a flight of about 1/p at the base's stable step); a restitution E above
    Housner's value replaces ``1.5 sin^2 alpha`` by ``max(1 - E, 1e-3)`` in both. Calibrated on
    random scenes over every supported range, where the steps taken stayed within a few times this
    estimate; then checked on 60,000 others (README, Bad input): no accepted scene reached the cap.
    """
    rtol = _rtol(foundation, rtol)
    estimate, samples, run = _estimate_steps(block, foundation, prepared, rtol, tail, rest_tol, horizon, history,
                                             restitution)
    limit = max_steps // 5
    if estimate > limit:
        what = [f"{samples:,} record samples" if samples > limit / 4 else f"a run of up to {run:.4g} s"]
        if isinstance(foundation, LinearIsolation):
            what.append(f"a base oscillating at {foundation.omega_b:.3g} rad/s with xi = {foundation.xi:g} "
                        f"({foundation.label})")
        if rtol < default_rtol(foundation):
            what.append(f"rtol = {rtol:g}")
        raise RockcliInputError(
            f"this scene would need about {estimate:.2g} integrator steps, more than the {limit:,} allowed (a fifth "
            f"of the {max_steps:,}-step safety cap), for {' and '.join(what)}: shorten the record, the horizon "
            f"or the tail, loosen rtol, or damp the base (xi)")


def simulate(block: Block, foundation=None, excitation=None, *, rtol: float | None = None,
             history: bool = False, tail: float = DEFAULT_TAIL, rest_tol: float = DEFAULT_REST_TOL,
             horizon: float = DEFAULT_HORIZON, max_steps: int = DEFAULT_MAX_STEPS, early: bool = False,
             restitution: float | None = None, theta0: float = 0.0, theta_dot0: float = 0.0,
             cap_ratio: float = 0.0) -> Response:
    """Rocking response of ``block`` on ``foundation`` under ``excitation``.

    Parameters
    ----------
    block : Block
        The rigid block.
    foundation : Rigid, LinearIsolation, SingleConcaveSliding, LeadRubber or DoubleConcaveSliding, optional
        Default :class:`Rigid`.
    excitation : Record or pulse
        A :class:`rockcli.records.Record` (``acc`` [m/s^2], ``dt`` [s]) or an analytic pulse
        (``shape``, ``a_p`` [m/s^2], ``T_p`` [s], ``t0`` [s], ``support()``).
    rtol : float, optional
        Relative tolerance of the integrator; the error on each state is kept below
        ``rtol * max(|y|, scale)`` with scales alpha, p alpha, g tan(alpha)/omega_b^2, g tan(alpha)/omega_b.
        Default (None): :func:`default_rtol` of the foundation, 5e-9 on a rigid foundation and on
        linear bearings, 2e-9 on sliding and lead-rubber bearings.
    history : bool
        Return the time history (every step end and event). Without it the run stores nothing
        and stops as soon as the verdict is proven.
    tail : float
        Free motion a history run shows after the excitation [s]; it never changes the verdict.
    rest_tol : float
        Rest threshold (see the module notes), 0 < rest_tol < 1.
    horizon : float
        Longest free motion followed after the excitation to prove the verdict [s].
    early : bool
        Verdict only: also stop during the excitation once survival is proven (then
        ``peak_final`` is False). Not with ``history``.
    max_steps : int
        Safety cap on integrator steps.
    restitution : float, optional
        Coefficient of restitution E, 0 < E <= 1: ``theta_dot+ = E theta_dot-`` at an impact on a
        rigid foundation (None: Housner's ``1 - 1.5 sin^2 alpha``); on an isolated base the map
        keeps the horizontal momentum and E enters as in :mod:`rockcli.impact`.
    theta0, theta_dot0 : float
        Start rocking from this tilt [rad] (``|theta0| < pi/2``) and angular velocity [rad/s]
        instead of at rest (:mod:`rockcli.initial`); ``excitation`` may then be None (free rocking).
    cap_ratio : float
        A capped colonnade of such columns on a rigid foundation: beam mass over the columns' total
        mass, >= 0 (0: the solitary column; :mod:`rockcli.colonnade`).

    Returns
    -------
    Response
    """
    if foundation is None:
        foundation = Rigid()
    if not isinstance(block, Block):
        raise RockcliInputError(f"block must be a rockcli.models.Block, got {type(block).__name__}")
    theta0, theta_dot0 = check_initial_state(theta0, theta_dot0)
    if excitation is None and theta0 == 0.0 and theta_dot0 == 0.0:
        raise RockcliInputError("simulate needs an excitation (a record or a pulse), or a start away from rest "
                                "(theta0 or theta_dot0)")
    validate_options(rtol, tail, rest_tol, horizon, max_steps)
    restitution = check_restitution(restitution)
    if early and history:
        raise RockcliInputError("early stopping is for verdict-only runs; it cannot be combined with history")
    k = _kernel()
    prepared = still_ground_arrays(k) if excitation is None else _excitation_arrays(excitation)
    ekind, epar, acc, jtab, dt, t_begin, t_exc_end = prepared
    fkind, prm = _parameters(block, foundation, rtol, float(rest_tol), restitution, cap_ratio)
    prm[k.P_TH0], prm[k.P_THD0] = theta0, theta_dot0
    _check_work(block, foundation, prepared, rtol, float(tail), float(rest_tol), float(horizon),
                int(max_steps), bool(history), restitution)
    out = np.zeros(k.N_OUT)
    kernel = k.simulate_rigid if fkind == k.FOUNDATION_RIGID else k.simulate_core
    H = kernel(fkind, tuple(float(v) for v in prm), ekind, tuple(float(v) for v in epar), acc, jtab, dt,
               t_begin, t_exc_end, float(tail), float(horizon), int(max_steps), bool(history), bool(early), out)
    return _response(out, H if history else None, block, fkind)


def _response(out: np.ndarray, H, block, out_fkind: int = 0) -> Response:
    k = _kernel()
    alpha = block.alpha if isinstance(block, Block) else float(block)
    status = int(out[k.O_STATUS])
    if status == k.STATUS_OVERTURNED:
        verdict = VERDICT_OVERTURNED
        if math.isnan(out[k.O_T_OVERTURN]):
            message = f"overturns: proven at t = {out[k.O_T_SETTLED]:.3f} s (early stop; the time it lands is not computed)"
        else:
            message = f"overturned at t = {out[k.O_T_OVERTURN]:.3f} s"
    elif out[k.O_UPLIFTED]:
        verdict = VERDICT_ROCKED
        message = f"rocked and survived (peak |theta|/alpha = {out[k.O_THETA_MAX] / alpha:.3f})"
    else:
        verdict = VERDICT_NO_UPLIFT
        message = "never uplifted: the base acceleration stayed below g tan(alpha)"
    if status == k.STATUS_MAX_STEPS:
        message = f"stopped after {int(out[k.O_STEPS])} steps at t = {out[k.O_T_END]:.3f} s (step cap reached): " + message
    elif not out[k.O_SETTLED]:
        why = ("the block was still rocking (a very slender block loses little energy per impact)"
               if out[k.O_THETA_END] != 0.0 else
               "the block was at rest but its base could still lift it (lightly damped base)")
        message += (f"; NOT PROVEN: at t = {out[k.O_T_END]:.1f} s (the horizon) {why}, so it could still be lifted "
                    f"or overturn; lengthen the horizon to follow it")
    hist = None
    if H is not None:
        fkind = out_fkind
        hyst = fkind in (k.FOUNDATION_BILINEAR, k.FOUNDATION_DCSS)
        peaks = H[H[:, k.H_KIND] == k.HK_PEAK]
        H = H[H[:, k.H_KIND] == k.HK_STATE]
        hist = History(t=H[:, k.H_T].copy(), ag=H[:, k.H_AG].copy(), theta=H[:, k.H_TH].copy(),
                       theta_dot=H[:, k.H_THD].copy(), u=H[:, k.H_U].copy(), u_dot=H[:, k.H_UD].copy(),
                       z=H[:, k.H_Z].copy() if hyst else None,
                       z2=H[:, k.H_Z2].copy() if fkind == k.FOUNDATION_DCSS else None,
                       bearing_force=H[:, k.H_FB].copy() if fkind != k.FOUNDATION_RIGID else None,
                       peak_t=peaks[:, k.H_T].copy(), peak_theta=peaks[:, k.H_TH].copy())
    return Response(
        verdict=verdict, status=status, message=message,
        t_uplift_s=float(out[k.O_T_UPLIFT]), t_overturn_s=float(out[k.O_T_OVERTURN]),
        t_exceed_alpha_s=float(out[k.O_T_EXCEED]), theta_max=float(out[k.O_THETA_MAX]),
        theta_max_over_alpha=float(out[k.O_THETA_MAX] / alpha), t_theta_max_s=float(out[k.O_T_THETA_MAX]),
        n_impacts=int(out[k.O_N_IMPACTS]), n_impacts_total=int(out[k.O_N_IMPACTS_ALL]),
        n_uplifts=int(out[k.O_N_UPLIFTS]), n_rests=int(out[k.O_N_RESTS]),
        base_disp_max_m=float(out[k.O_U_MAX]), steps=int(out[k.O_STEPS]),
        rejected_steps=int(out[k.O_REJECTED]), nfev=int(out[k.O_NRHS]), settled=bool(out[k.O_SETTLED]),
        t_end_s=float(out[k.O_T_END]), peak_final=bool(out[k.O_PEAK_FINAL]),
        t_settled_s=float(out[k.O_T_SETTLED]) if out[k.O_SETTLED] and status != k.STATUS_OVERTURNED else math.nan,
        n_base_reversals=int(out[k.O_N_REVERSALS]), history=hist,
    )


def simulate_many(jobs, *, rtol: float | None = None, tail=DEFAULT_TAIL,
                  rest_tol: float = DEFAULT_REST_TOL, horizon: float = DEFAULT_HORIZON,
                  max_steps: int = DEFAULT_MAX_STEPS, early: bool = False,
                  progress=None, chunk: int | None = None, restitution=None, cap_ratio=0.0) -> list:
    """Verdict-only :func:`simulate` of many scenes, run in parallel on all cores.

    Parameters
    ----------
    jobs : sequence of (block, foundation, excitation) or (block, foundation, excitation, scale)
        ``scale`` multiplies a record's acceleration or a pulse's ``a_p`` (default 1): the same run
        as the scaled excitation. Scenes that share a record object share its samples.
    tail : float or sequence of float
        Free motion a history run would show [s] (one value or one per scene); it never changes a
        verdict-only run, which ends when its verdict is proven.
    early : bool
        Stop each run as soon as its verdict is proven, even during the excitation (the
        verdicts are the same; ``theta_max`` is then only the peak so far, ``peak_final`` False).
    progress : callable, optional
        Called as ``progress(n_done)`` after each chunk of scenes.
    chunk : int, optional
        Scenes per batch handed to a thread (default: about 1/8 of a thread's share, and at most
        1/50 of all scenes with ``progress``).
    restitution : float, None or sequence of them
        Coefficient of restitution of :func:`simulate` (one value or one per scene; None: Housner's).
    cap_ratio : float or sequence of float
        Capped colonnade of :func:`simulate` (one value or one per scene; 0: solitary columns).

    Returns
    -------
    list of Response or JobError
        In the order of ``jobs``, identical to what :func:`simulate` returns without history; a
        job that :func:`simulate` would refuse (bad block, foundation or excitation) gets a
        :class:`JobError` with the reason and the others still run. Invalid solver options
        (``rtol``, ``tail``, ``rest_tol``, ``horizon``) concern every job and raise.
    """
    outs, alphas, failed = _run_many(jobs, rtol=rtol, tail=tail, rest_tol=rest_tol, horizon=horizon,
                                     max_steps=max_steps, early=early, progress=progress, chunk=chunk,
                                     restitution=restitution, cap_ratio=cap_ratio)
    done = iter(range(outs.shape[0]))
    return [failed[i] if i in failed else _response(outs[next(done)], None, alphas[i]) for i in range(len(alphas))]


@dataclass(frozen=True)
class Verdicts:
    """Outcome of :func:`simulate_verdicts`: one array entry per scene, in the order of the jobs.

    ``overturned``, ``uplifted``, ``settled``, ``peak_final`` (bool); ``theta_max_over_alpha``
    (pi/2/alpha when overturned; with early stops only the peak so far where ``peak_final`` is
    False); ``status`` (0 finished, 1 overturned, -1 step cap); ``nfev`` (right-hand sides).
    """

    overturned: np.ndarray
    uplifted: np.ndarray
    theta_max_over_alpha: np.ndarray
    settled: np.ndarray
    status: np.ndarray
    nfev: np.ndarray
    peak_final: np.ndarray

    def __len__(self) -> int:
        return int(self.overturned.size)


def simulate_verdicts(jobs, *, rtol: float | None = None, tail=DEFAULT_TAIL, rest_tol: float = DEFAULT_REST_TOL,
                      horizon: float = DEFAULT_HORIZON, max_steps: int = DEFAULT_MAX_STEPS, early: bool = False,
                      progress=None, chunk: int | None = None, restitution=None, cap_ratio=0.0) -> Verdicts:
    """:func:`simulate_many` returning arrays (no :class:`Response` per scene): for large sweeps.

    Same arguments and the same runs; a job that fails validation raises here.
    """
    k = _kernel()
    outs, alphas, failed = _run_many(jobs, rtol=rtol, tail=tail, rest_tol=rest_tol, horizon=horizon,
                                     max_steps=max_steps, early=early, progress=progress, chunk=chunk,
                                     restitution=restitution, cap_ratio=cap_ratio)
    if failed:
        i = min(failed)
        raise RockcliInputError(f"job {i}: {failed[i].error}")
    return Verdicts(
        overturned=outs[:, k.O_STATUS] == k.STATUS_OVERTURNED, uplifted=outs[:, k.O_UPLIFTED] != 0.0,
        theta_max_over_alpha=outs[:, k.O_THETA_MAX] / np.asarray(alphas, dtype=float).reshape(-1),
        settled=outs[:, k.O_SETTLED] != 0.0, status=outs[:, k.O_STATUS].astype(np.int64),
        nfev=outs[:, k.O_NRHS].astype(np.int64), peak_final=outs[:, k.O_PEAK_FINAL] != 0.0)


def _scene_arrays(block, foundation, excitation, tail, rtol, rest_tol, horizon, max_steps, prepared, params,
                  checked, restitution=None, cap_ratio=0.0):
    """The kernel inputs of one (block, foundation, excitation, tail) of a sweep, validated and its work
    checked: ``(fkind, prm, ekind, epar, acc, jtab, dt, t_begin, t_exc_end)`` (``epar`` a copy).

    ``prepared``, ``params`` and ``checked`` are the sweep's caches: an excitation's arrays by id, the
    parameters by (block, foundation) and the work estimates that passed.
    """
    k = _kernel()
    key = id(excitation)
    if key not in prepared:
        try:
            prepared[key] = _excitation_arrays(excitation)
        except RockcliInputError as exc:
            prepared[key] = exc
    if isinstance(prepared[key], RockcliInputError):
        raise prepared[key]
    ekind, epar, acc, jtab, dt, t_begin, t_exc_end = prepared[key]
    try:
        cached = params.get((block, foundation, restitution, cap_ratio))
    except TypeError:  # an unhashable foundation: built for each scene
        cached = _parameters(block, foundation, rtol, float(rest_tol), restitution, cap_ratio)
    if cached is None:
        cached = params[(block, foundation, restitution, cap_ratio)] = _parameters(
            block, foundation, rtol, float(rest_tol), restitution, cap_ratio)
    fkind, prm = cached
    # the work estimate depends only on these (not on the amplitude): checked once per distinct set
    wkey = (block, foundation, ekind, acc.size, epar[k.E_TE] - epar[k.E_TS], t_exc_end, tail, restitution)
    try:
        known = wkey in checked
    except TypeError:
        known = False
    if not known:
        _check_work(block, foundation, prepared[key], rtol, tail, float(rest_tol), float(horizon), int(max_steps),
                    restitution=restitution)
        try:
            checked.add(wkey)
        except TypeError:
            pass
    return fkind, prm, ekind, epar.copy(), acc, jtab, dt, t_begin, t_exc_end


def _per_job(value, n: int, check, what: str) -> list:
    """A solver option given as one value or one per job, checked, as a list of ``n`` values."""
    if value is None or np.ndim(value) == 0:
        return [check(value)] * n
    values = list(value)
    if len(values) != n:
        raise RockcliInputError(f"{what} must be one value or one per job ({n}), got {len(values)}")
    return [check(v) for v in values]


def _run_many(jobs, *, rtol, tail, rest_tol, horizon, max_steps, early, progress, chunk, restitution=None,
              cap_ratio=0.0):
    """Kernel outputs (``O_*`` rows) of the valid jobs, each job's slenderness, and the failed jobs.

    Returns ``(outs, alphas, failed)``: ``outs`` has one row per valid job in job order,
    ``alphas`` one entry per job (NaN for a failed one), ``failed`` maps job index -> JobError.
    """
    jobs = list(jobs)
    tails_in = np.asarray(tail, dtype=float)
    if tails_in.ndim == 0:
        validate_options(rtol, float(tails_in), rest_tol, horizon, max_steps)
    else:
        if tails_in.shape != (len(jobs),):
            raise RockcliInputError(f"tail must be one value or one per job ({len(jobs)}), got {tails_in.shape}")
        if not np.all(np.isfinite(tails_in) & (tails_in >= 0) & (tails_in <= TAIL_MAX)):
            raise RockcliInputError(f"tail must be a time between 0 and {TAIL_MAX:g} s for every job")
        validate_options(rtol, 0.0, rest_tol, horizon, max_steps)
    restitutions = _per_job(restitution, len(jobs), check_restitution, "restitution")
    caps = _per_job(cap_ratio, len(jobs), check_cap_ratio, "cap_ratio")  # (the foundation is checked per job)
    k = _kernel()
    n = len(jobs)
    if n == 0:
        return np.zeros((0, k.N_OUT)), [], {}
    pieces, jpieces, where, total = [], [], {}, 0
    prepared = {}  # id(excitation) -> validated kernel arrays (or the error): a shared record is checked once
    params = {}  # (block, foundation) -> kernel parameters: built once per distinct pair
    checked = set()  # work estimates that passed (see _check_work)
    groups = {}  # (id(block), id(foundation), id(excitation), tail) -> index into G, or the error
    G = []  # per distinct scene: (fkind, prm, ekind, epar, offset, length, dt, t_begin, t_exc_end, alpha)
    failed = {}  # job index -> JobError; those jobs are not run
    gidx = np.full(n, -1, np.int64)
    scales = np.ones(n)
    ground = Rigid()
    for i, job in enumerate(jobs):
        try:
            block, foundation, excitation = job[:3]
            scale = float(job[3]) if len(job) > 3 else 1.0
            if not isinstance(block, Block):
                raise RockcliInputError(f"job {i}: block must be a rockcli.models.Block")
            foundation = foundation if foundation is not None else ground
            if not hasattr(foundation, "gamma"):
                raise RockcliInputError(f"job {i}: unknown foundation {foundation!r}")
            if not math.isfinite(scale):
                raise RockcliInputError(f"job {i}: the scale factor must be finite, got {scale!r}")
            tail_i = float(tails_in if tails_in.ndim == 0 else tails_in[i])
            # the jobs hold these objects, so their ids stay theirs for the whole loop
            gkey = (id(block), id(foundation), id(excitation), tail_i, restitutions[i], caps[i])
            g = groups.get(gkey)
            if g is None:
                try:
                    fkind, prm, ekind, epar, acc, jtab, dt, t_begin, t_exc_end = _scene_arrays(
                        block, foundation, excitation, tail_i, rtol, rest_tol, horizon, max_steps, prepared, params,
                        checked, restitutions[i], caps[i])
                except (RockcliInputError, TypeError, ValueError) as exc:
                    g = RockcliInputError(str(exc))
                else:
                    akey = id(acc)  # a record's samples, or the table shared by all pulses of one shape
                    if akey not in where:
                        where[akey] = total
                        pieces.append(acc)
                        jpieces.append(jtab)
                        total += acc.size
                    g = len(G)
                    G.append((fkind, prm, ekind, epar, where[akey], acc.size, dt, t_begin, t_exc_end, block.alpha))
                groups[gkey] = g
            if isinstance(g, RockcliInputError):
                raise g
        except (RockcliInputError, TypeError, ValueError) as exc:
            failed[i] = JobError(str(exc))
            continue
        gidx[i] = g
        scales[i] = scale
    if not G:  # every job failed
        if progress is not None:
            progress(n)
        return np.zeros((0, k.N_OUT)), [math.nan] * n, failed
    ok = np.flatnonzero(gidx >= 0)
    sel = gidx[ok]
    cols = list(zip(*G))

    def per_job(j, dtype=float):  # column j of G, one row per job that runs
        return np.array(cols[j], dtype=dtype)[sel]

    fkinds, prms, ekinds, epars = per_job(0, np.int64), per_job(1), per_job(2, np.int64), per_job(3)
    acc_off, acc_len = per_job(4, np.int64), per_job(5, np.int64)
    dts, t_begins, t_exc_ends = per_job(6), per_job(7), per_job(8)
    alphas = np.full(n, math.nan)
    alphas[ok] = per_job(9)
    alphas = alphas.tolist()
    record = ekinds == k.EXC_RECORD
    scale_ok = scales[ok]
    epars[record, k.E_AP] = scale_ok[record]  # a record: E_AP carries the scale factor
    epars[~record, k.E_AP] *= scale_ok[~record]  # a pulse: the kernel reads its amplitude from E_AP
    tails = np.full(ok.size, float(tails_in)) if tails_in.ndim == 0 else tails_in[ok].copy()
    m = fkinds.size
    acc_all = np.concatenate(pieces) if pieces else np.zeros(2)
    jtab_all = np.concatenate(jpieces) if jpieces else np.zeros(2)
    outs = np.zeros((m, k.N_OUT))
    threads = _threads()
    if chunk is None:  # pieces small enough to balance the threads, and to report progress ~50 times
        chunk = max(1, -(-m // (8 * threads)))
        if progress is not None:
            chunk = min(chunk, max(1, m // 50))
    tasks = []
    # one batch kernel per driver (rigid foundation, isolated base): a sweep compiles only what it uses
    rigid = fkinds == k.FOUNDATION_RIGID
    for batch, sel in ((k.simulate_batch_rigid, np.flatnonzero(rigid)), (k.simulate_batch, np.flatnonzero(~rigid))):
        whole = sel.size == m  # every job runs on this driver: pass views, the kernel writes into outs
        for lo in range(0, sel.size, chunk):
            hi = min(sel.size, lo + chunk)
            tasks.append((batch, slice(lo, hi) if whole else sel[lo:hi]))
    common = (acc_all, jtab_all)
    tail_args = (float(horizon), int(max_steps), bool(early))

    def run(task):
        batch, part = task
        o = outs[part] if isinstance(part, slice) else np.zeros((part.size, k.N_OUT))
        batch(fkinds[part], prms[part], ekinds[part], epars[part], *common, acc_off[part], acc_len[part],
              dts[part], t_begins[part], t_exc_ends[part], tails[part], *tail_args, o)
        if not isinstance(part, slice):
            outs[part] = o
        return o.shape[0]

    done = 0
    if threads == 1 or len(tasks) == 1:
        for task in tasks:
            done += run(task)
            if progress is not None:
                progress(n if done == m else done)
    else:
        from concurrent.futures import ThreadPoolExecutor, as_completed

        with ThreadPoolExecutor(max_workers=threads) as pool:  # the kernels run without the GIL
            futures = [pool.submit(run, task) for task in tasks]
            try:
                for fut in as_completed(futures):
                    done += fut.result()
                    if progress is not None:
                        progress(n if done == m else done)
            except BaseException:  # an error or Ctrl-C: drop the pieces not started, then re-raise
                for fut in futures:
                    fut.cancel()
                raise
    return outs, alphas, failed
