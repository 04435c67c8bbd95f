""":func:`simulate`: one scene, validated, on the compiled kernel (the driver of its foundation)."""

from __future__ import annotations

import math

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.models.impact import check_restitution
from rockcli.io.inputs import format_number, type_words
from rockcli.models.initial import check_initial_state, still_ground_arrays
from rockcli.models import Block
from rockcli.solve.excitation import _excitation_arrays, _vertical_arrays, attached_vertical
from rockcli.solve.options import (DEFAULT_HORIZON, DEFAULT_MAX_STEPS, DEFAULT_REST_TOL, DEFAULT_TAIL, _kernel,
                                   check_foundation, validate_options)
from rockcli.solve.parameters import _parameters
from rockcli.solve.response import Response, _response
from rockcli.solve.work import _check_work


def simulate(block: Block, foundation=None, excitation=None, *, rtol: float | None = None,
             history: bool = False, tail: float = DEFAULT_TAIL, rest_tol: float = DEFAULT_REST_TOL,
             horizon: float = DEFAULT_HORIZON, max_steps: int = DEFAULT_MAX_STEPS, early: bool = False,
             restitution: float | None = None, theta0: float = 0.0, theta_dot0: float = 0.0,
             cap_ratio: float = 0.0, history_dt: float | None = None, vertical=None,
             _scale: float = 1.0) -> Response:
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
        Rest threshold (see the solver contract in :mod:`rockcli.solve`), 0 < rest_tol < 1.
    horizon : float
        Longest free motion followed after the excitation to prove the verdict [s].
    early : bool
        Verdict only: also stop during the excitation once the verdict is proven (on a rigid
        foundation ``peak_final`` is then False; on an isolated base ``base_disp_max_m`` is NaN
        unless proven final). Not with ``history``.
    max_steps : int
        Safety cap on integrator steps.
    restitution : float, optional
        Coefficient of restitution E, 0 < E <= 1: ``theta_dot+ = E theta_dot-`` at an impact on a
        rigid foundation (None: Housner's ``1 - 1.5 sin^2 alpha``); on an isolated base the map
        keeps the horizontal momentum and E enters as in :mod:`rockcli.models.impact`.
    theta0, theta_dot0 : float
        Start rocking from this tilt [rad] (``|theta0| < pi/2``) and angular velocity [rad/s]
        instead of at rest (:mod:`rockcli.models.initial`); ``excitation`` may then be None (free rocking).
    cap_ratio : float
        A capped colonnade of such columns: beam mass over the columns' total mass, >= 0 (0: the
        solitary column; :mod:`rockcli.models.colonnade`). On an isolated base the foundation's ``gamma`` is
        the mass of columns and beam over the whole moving mass.
    history_dt : float, optional
        The history on a uniform grid: rows at the times ``k history_dt`` [s] from the start to the
        excitation's end plus ``tail`` (the steps' dense output, exact to the integrator's tolerance;
        the ground acceleration from the excitation itself) instead of at the step ends; implies
        ``history``. The events stay exact either way (:attr:`History.events`), also after the tail
        when the run goes on to prove its verdict. The grid's rows are counted before the run
        (:func:`grid_rows`): more than :data:`HISTORY_GRID_ROWS_MAX` are refused.
    vertical : Record or pulse, optional
        Vertical ground acceleration [m/s^2, upward positive], rigid foundation only: gravity becomes
        ``g + a_v`` in Eq (3) and in the uplift threshold. A record shares a horizontal record's time
        step and start (its length may differ: zero after its end); a pulse is sampled every
        ``T_p/2000`` and read piecewise linear. ``g + a_v <= 0`` anywhere is refused (lift-off).
        None: the vertical motion the record carries, if any (:func:`rockcli.solve.with_vertical`).

    Returns
    -------
    Response
    """
    if not isinstance(block, Block):
        raise RockcliInputError(f"block must be a rockcli.models.Block (Block(R, alpha), Block.from_dimensions(height, "
                                f"width), column('bassae')), got {type_words(block)}")
    foundation = check_foundation(foundation)
    theta0, theta_dot0 = check_initial_state(theta0, theta_dot0)
    if excitation is None and theta0 == 0.0 and theta_dot0 == 0.0:
        raise RockcliInputError("simulate needs an excitation (a record or a pulse), or a start away from rest "
                                "(theta0 or theta_dot0)")
    validate_options(rtol, tail, rest_tol, horizon, max_steps)
    if history_dt is not None:
        history_dt = check_history_dt(history_dt)
        history = True
    restitution = check_restitution(restitution)
    if early and history:
        raise RockcliInputError("early stopping is for verdict-only runs; it cannot be combined with history")
    k = _kernel()
    prepared = still_ground_arrays(k) if excitation is None else _excitation_arrays(excitation)
    ekind, epar, acc, jtab, dt, t_begin, t_exc_end = prepared
    if _scale != 1.0:  # simulate_many's scale factor, applied as its batch applies it
        epar = epar.copy()
        epar[k.E_AP] = _scale if ekind == k.EXC_RECORD else epar[k.E_AP] * _scale
    fkind, prm = _parameters(block, foundation, rtol, float(rest_tol), restitution, cap_ratio)
    prm[k.P_TH0], prm[k.P_THD0] = theta0, theta_dot0
    if vertical is None:
        vertical = attached_vertical(excitation)
    vacc, vjtab, vdt, t_v_end, _ = _vertical_arrays(vertical, excitation, foundation, float(prm[k.P_G]))
    if history_dt is not None:
        prm[k.P_HDT] = history_dt
        _check_grid_rows(history_dt, t_begin, max(t_exc_end, t_v_end) + float(tail))
    _check_work(block, foundation, prepared, rtol, float(tail), float(rest_tol), float(horizon),
                int(max_steps), bool(history), restitution)
    out = np.zeros(k.N_OUT)
    args = (fkind, tuple(float(v) for v in prm), ekind, tuple(float(v) for v in epar), acc, jtab, dt, t_begin,
            max(t_exc_end, t_v_end), float(tail), float(horizon), int(max_steps), bool(history), bool(early))
    if vacc.size:
        H = k.simulate_rigid_vertical(*args, vacc, vjtab, vdt, out)
    else:
        H = (k.simulate_rigid if fkind == k.FOUNDATION_RIGID else k.simulate_core)(*args, out)
    return _response(out, H if history else None, block, fkind, history_dt)


#: The most rows a uniform history grid may have, counted before the run (:func:`grid_rows`): 2,000,000 rows
#: make a CSV of about 120 MB, written with a peak memory of about 1.3 GB (measured: a 41 s record every
#: 2.6e-5 s, 13 s CPU); 5 million took 3 GB and 40 s, and the old estimate let 64 million through to a
#: MemoryError. Two million rows are a row every 25 us of a 50 s run, finer than any figure or comparison needs.
HISTORY_GRID_ROWS_MAX = 2_000_000


def check_history_dt(history_dt, name: str = "history_dt") -> float:
    """``history_dt`` as a float, or one sentence why it cannot be a grid spacing [s]."""
    try:
        v = float(history_dt)
    except (TypeError, ValueError):
        raise RockcliInputError(f"{name} must be a number of seconds, got {history_dt!r}") from None
    if not (math.isfinite(v) and v > 0.0):
        raise RockcliInputError(f"{name} must be a positive number of seconds, got {format_number(history_dt)}")
    return v


def grid_rows(history_dt: float, t_begin: float, t_show_end: float) -> int:
    """The number of rows of the uniform history grid, known before the run: the times ``k history_dt`` from
    ``t_begin`` to ``t_show_end`` (the excitation's end plus the tail), computed with the kernel's own float
    operations (``kg = ceil(t_begin / hdt)``, rows while ``kg * hdt <= t_show_end``). The kernels write no grid
    row after ``t_show_end`` (a run that goes on to prove its verdict adds only its step and event rows), so a
    run has at most this many grid rows (fewer when it overturns earlier)."""
    span = (t_show_end - t_begin) / history_dt
    if not span < 2.0 ** 50:  # far beyond any cap (and beyond counting one by one in floats): the estimate
        return int(min(span, 2.0 ** 62))
    first = math.ceil(t_begin / history_dt)
    last = math.floor(t_show_end / history_dt)
    for _ in range(4):  # the quotients may be one off the kernel's products k * hdt
        if (last + 1) * history_dt <= t_show_end:
            last += 1
        elif last >= first and last * history_dt > t_show_end:
            last -= 1
        else:
            break
    return max(0, last - first + 1)


def _check_grid_rows(history_dt: float, t_begin: float, t_show_end: float) -> None:
    """Refuse a grid of more than :data:`HISTORY_GRID_ROWS_MAX` rows (:func:`grid_rows`), before any work."""
    n = grid_rows(history_dt, t_begin, t_show_end)
    if n > HISTORY_GRID_ROWS_MAX:
        rows = f"{n:,}" if n < 2 ** 50 else f"about {(t_show_end - t_begin) / history_dt:.3g}"
        raise RockcliInputError(f"a history every {format_number(history_dt)} s from {format_number(t_begin)} s to "
                                f"{format_number(t_show_end)} s (the excitation's end plus the tail) would be {rows} "
                                f"rows, more than the {HISTORY_GRID_ROWS_MAX:,} allowed: choose a coarser grid or a "
                                f"shorter tail")
