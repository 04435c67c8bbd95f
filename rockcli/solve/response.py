"""What a run returns: the verdict names, :class:`Response` (with its :class:`History`),
:class:`JobError` (a batch job refused), :class:`Verdicts` (a batch as arrays), and
:func:`_response`, which reads a kernel's output row (``O_*``) into a :class:`Response`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from rockcli.models import Block
from rockcli.solve.options import _kernel


VERDICT_NO_UPLIFT = "no_uplift"
VERDICT_ROCKED = "rocked"
VERDICT_OVERTURNED = "overturned"
#: Verdict of a :func:`simulate_many` job that could not be run (see :class:`JobError`).
VERDICT_ERROR = "error"


#: The events of a history, by the kernel's row kind (``HK_*``): the name a row carries in the history
#: CSV's ``event`` column. An impact is two rows at the same time, the state just before it and just
#: after; when the block comes to rest there, the row after it is the ``rest``.
EVENT_KINDS = (("HK_UPLIFT", "uplift"), ("HK_IMPACT", "impact"), ("HK_IMPACT_AFTER", "impact"), ("HK_REST", "rest"),
               ("HK_OVERTURN", "overturn"), ("HK_PEAK", "peak"))


@dataclass(frozen=True)
class HistoryEvent:
    """An event of a run [SI units]: ``event`` is ``uplift``, ``impact``, ``rest`` (after an impact that
    ends the rocking), ``peak`` (a turning point of theta, located on the step's dense output:
    ``theta_dot`` = 0, ``theta`` its exact value) or ``overturn`` (``|theta|`` = pi/2).

    For an impact, ``theta_dot_rad_s`` and ``u_dot_mps`` are the velocities just before it and
    ``theta_dot_before``/``theta_dot_after`` both sides of the impact map.
    """

    event: str
    t_s: float
    theta_rad: float
    theta_dot_rad_s: float
    u_m: float
    u_dot_mps: float
    ag_mps2: float
    theta_dot_before: float | None = None
    theta_dot_after: float | None = None

    def as_dict(self) -> dict[str, Any]:
        """The event as a plain dict (JSON-ready; the impact velocities only for impacts)."""
        d = {k: getattr(self, k) for k in ("event", "t_s", "theta_rad", "theta_dot_rad_s", "u_m", "u_dot_mps",
                                           "ag_mps2")}
        if self.event == "impact":
            d.update(theta_dot_before=self.theta_dot_before, theta_dot_after=self.theta_dot_after)
        return d


@dataclass(frozen=True)
class History:
    """Time history of a run: arrays at every step end and event [SI units], or with ``grid_dt`` at
    the times ``k grid_dt`` (the steps' dense output; ``simulate(..., history_dt=...)``).

    ``z``, ``z2`` (Bouc-Wen variables; ``z2`` of the second surface of a double concave bearing)
    and ``bearing_force`` (the bearings' restoring force per unit total mass, ``k_b u + Q z`` over
    ``m + m_b`` [m/s^2]; linear bearings: ``k_b u + c_b u_dot`` over ``m + m_b``) are None where the
    foundation has none.

    ``events`` lists the run's :class:`HistoryEvent` in time order. ``rows`` (columns ``t, ag, theta,
    theta_dot, u, u_dot, z, z2, bearing force``) and ``row_event`` (the event's name, ``""`` for a plain
    row) are the rows of the history CSV. On the grid: the grid rows with every event row among them
    in time order (peaks with NaN bearing variables). At the steps: the step rows above, unchanged,
    those at an uplift, an impact, a rest or the overturn named (the peaks, between steps, are in
    ``events`` and ``peak_t``/``peak_theta`` only).
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
    events: tuple[HistoryEvent, ...] = ()
    rows: np.ndarray | None = field(default=None, repr=False)
    row_event: np.ndarray | None = field(default=None, repr=False)
    grid_dt: float | None = None


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
        Peak ``|u|``, base displacement relative to the ground [m] (0 on a rigid foundation; NaN
        when an ``early`` run ended before it was proven final).
    n_impacts : int
        Impacts while the ground moves (the same with or without history).
    n_impacts_total : int
        Impacts integrated, including free rocking after the excitation (a verdict-only run
        stops once the outcome is settled, so it may count fewer).
    settled : bool
        The verdict is proven (see the solver contract in :mod:`rockcli.solve`); False when the run
        reached its horizon.
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


def _history_events(k, H) -> tuple[HistoryEvent, ...]:
    """The events of the kernel's history rows ``H`` (the grid rows skipped, in time order): an impact is read
    from its row before and the next row that is not on the grid after it (the impact map's two sides)."""
    kinds = H[:, k.H_KIND]
    rows = np.flatnonzero(kinds != k.HK_GRID)
    rk = kinds[rows]
    at = np.flatnonzero((rk != k.HK_STATE) & (rk != k.HK_IMPACT_AFTER))
    idx = rows[at]
    # Python floats for the whole table at once (``tolist``), not one ``float()`` per cell
    states = H[idx][:, [k.H_T, k.H_TH, k.H_THD, k.H_U, k.H_UD, k.H_AG]].tolist()
    after = H[rows[np.minimum(at + 1, len(rows) - 1)], k.H_THD].tolist()  # the kernel writes the state just after
    names = _row_labels(k)
    events = []
    for kind, state, thd_after in zip(kinds[idx].astype(np.intp).tolist(), states, after):
        if kind == k.HK_IMPACT:
            events.append(HistoryEvent("impact", *state, theta_dot_before=state[2], theta_dot_after=thd_after))
        else:
            events.append(HistoryEvent(names[kind], *state))
    events.sort(key=lambda e: e.t_s)  # stable: events at one time keep the kernel's order
    return tuple(events)


@functools.cache
def _row_labels(k) -> np.ndarray:
    """Each row kind's event name (``""`` for a plain row), indexed by the kind's code."""
    codes = [int(getattr(k, name)) for name in dir(k) if name.startswith("HK_")]
    labels = np.full(max(codes) + 1, "", dtype=object)
    for code, name in EVENT_KINDS:
        labels[int(getattr(k, code))] = name
    return labels


def _history(k, H, fkind: int, grid_dt: float | None) -> History:
    """The :class:`History` of the kernel's rows ``H`` (kinds ``HK_*``) on a foundation ``fkind``."""
    hyst = fkind in (k.FOUNDATION_BILINEAR, k.FOUNDATION_DCSS)
    kinds = H[:, k.H_KIND]
    is_peak = kinds == k.HK_PEAK
    step_rows = ~is_peak & (kinds != k.HK_GRID)
    if grid_dt:
        plain, shown = kinds == k.HK_GRID, kinds != k.HK_STATE
    else:  # the step rows, as without the event column: the peaks (between steps) only in ``events``
        plain, shown = step_rows, step_rows
    shown_rows = H[shown]
    t = shown_rows[:, k.H_T]
    in_order = bool((t[1:] >= t[:-1]).all())  # a stable sort of times already in order leaves them be
    if not in_order:
        shown_rows = shown_rows[np.argsort(t, kind="stable")]
    P = shown_rows if in_order and not grid_dt else H[plain]
    cols = P[:, :k.H_KIND].T.copy()  # one contiguous row per column
    return History(t=cols[k.H_T], ag=cols[k.H_AG], theta=cols[k.H_TH], theta_dot=cols[k.H_THD], u=cols[k.H_U],
                   u_dot=cols[k.H_UD], z=cols[k.H_Z] if hyst else None,
                   z2=cols[k.H_Z2] if fkind == k.FOUNDATION_DCSS else None,
                   bearing_force=cols[k.H_FB] if fkind != k.FOUNDATION_RIGID else None,
                   peak_t=H[is_peak, k.H_T], peak_theta=H[is_peak, k.H_TH], events=_history_events(k, H),
                   rows=shown_rows[:, :k.H_KIND].copy(),
                   row_event=_row_labels(k)[shown_rows[:, k.H_KIND].astype(np.intp)], grid_dt=grid_dt or None)


def _response(out: np.ndarray, H, block, out_fkind: int = 0, grid_dt: float | None = None) -> Response:
    k = _kernel()
    alpha = block.alpha if isinstance(block, Block) else float(block)
    status = int(out[k.O_STATUS])
    if status == k.STATUS_OVERTURNED:
        verdict = VERDICT_OVERTURNED
        if math.isnan(out[k.O_T_OVERTURN]):
            message = (f"overturns: proven at t = {out[k.O_T_SETTLED]:.3f} s (early stop; the time it lands is not "
                       f"computed)")
        else:
            message = f"overturned at t = {out[k.O_T_OVERTURN]:.3f} s"
    elif out[k.O_UPLIFTED]:
        verdict = VERDICT_ROCKED
        message = f"rocked and survived (peak |theta|/alpha = {out[k.O_THETA_MAX] / alpha:.3f})"
    else:
        verdict = VERDICT_NO_UPLIFT
        message = "never uplifted: the base acceleration stayed below g tan(alpha)"
    if status == k.STATUS_MAX_STEPS:
        message = (f"stopped after {int(out[k.O_STEPS])} steps at t = {out[k.O_T_END]:.3f} s (step cap reached): "
                   + message)
    elif not out[k.O_SETTLED]:
        why = ("the block was still rocking (a very slender block loses little energy per impact)"
               if out[k.O_THETA_END] != 0.0 else
               "the block was at rest but its base could still lift it (lightly damped base)")
        message += (f"; NOT PROVEN: at t = {out[k.O_T_END]:.1f} s (the horizon) {why}, so it could still be lifted "
                    f"or overturn; lengthen the horizon to follow it")
    hist = None if H is None else _history(k, H, out_fkind, grid_dt)
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
