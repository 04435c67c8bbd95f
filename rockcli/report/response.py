"""Time-history reports of one run: the history CSV and the Figure 1 / Figure 12 style plot.

matplotlib is imported inside the plotting function (Agg backend); files are written atomically.
"""

from __future__ import annotations

import io
import math
import os
from pathlib import Path

import numpy as np

from rockcli.io.files import check_output, save_figure, write_text
from rockcli.io.units import G

#: Columns of a history CSV (SI units, g only where labelled).
HISTORY_COLUMNS = ("t_s", "ag_mps2", "ag_g", "theta_rad", "theta_over_alpha", "theta_dot_radps", "u_m", "u_dot_mps")
#: Columns added for hysteretic bearings (sliding, lead-rubber): the Bouc-Wen variable(s) and the
#: bearings' restoring force over the weight of block + base, ``(k_b u + Q z)/((m + m_b) g)``.
BEARING_COLUMNS = ("z", "bearing_force_over_W")
DCSS_COLUMNS = ("z1", "z2", "bearing_force_over_W")


def history_columns(response) -> tuple[str, ...]:
    """The CSV columns of ``response``'s history (:data:`HISTORY_COLUMNS`, then the bearing's)."""
    H = response.history
    if H is None or H.z is None:
        return HISTORY_COLUMNS
    return HISTORY_COLUMNS + (DCSS_COLUMNS if H.z2 is not None else BEARING_COLUMNS)


def history_table(response, block) -> np.ndarray:
    """The history of ``response`` as an array in the order of :func:`history_columns`."""
    H = response.history
    if H is None:
        raise ValueError("this response was computed without history (simulate(..., history=True))")
    cols = [H.t, H.ag, H.ag / G, H.theta, H.theta / block.alpha, H.theta_dot, H.u, H.u_dot]
    if H.z is not None:
        cols += [H.z] + ([H.z2] if H.z2 is not None else []) + [H.bearing_force / G]
    return np.column_stack(cols)


def history_csv_table(response, block) -> tuple[np.ndarray, np.ndarray]:
    """The rows of the history CSV: ``(numbers in the order of history_columns, event names)``, the
    plain rows and the event rows in time order (:attr:`rockcli.solve.History.rows`)."""
    H = response.history
    if H is None:
        raise ValueError("this response was computed without history (simulate(..., history=True))")
    R = H.rows
    t, ag, th, thd, u, ud, z, z2, fb = (R[:, j] for j in range(9))
    cols = [t, ag, ag / G, th, th / block.alpha, thd, u, ud]
    if H.z is not None:
        cols += [z] + ([z2] if H.z2 is not None else []) + [fb / G]
    return np.column_stack(cols), H.row_event


def write_history_csv(response, block, path: str | os.PathLike) -> Path:
    """Write ``t, ground acceleration, theta, theta_dot, u, u_dot`` of a run as CSV, atomically
    (hysteretic bearings add ``z`` (``z1, z2``) and the bearing force over the weight), and last an
    ``event`` column.

    Rows are every integrator step end, or with ``simulate(..., history_dt=...)`` the uniform grid
    with the event rows among them in time order. Events: ``uplift``, ``impact`` (two rows at the
    same time, just before and just after it; the row after it is ``rest`` when the block comes to
    rest there), ``peak`` (a turning point of theta, theta_dot = 0, the bearing columns NaN; grid
    only: at the steps the peaks fall between rows, and the rows stay those of a run without the
    column) and ``overturn``.
    """
    table, events = history_csv_table(response, block)
    buf = io.StringIO()
    np.savetxt(buf, table, delimiter=",", comments="", fmt="%.10g")
    lines = buf.getvalue().splitlines()
    header = ",".join(history_columns(response) + ("event",))
    body = "".join(f"{line},{ev}\n" for line, ev in zip(lines, events))
    return write_text(path, header + "\n" + body)


#: Colour of the line that marks the instant the body topples (the reports' captions name it).
TOPPLE_COLOUR = "tab:red"
#: The box behind the label of that line: the curves and the grid do not run through its text.
LABEL_BOX = {"boxstyle": "square,pad=0.15", "facecolor": "white", "edgecolor": "none", "alpha": 0.85}


def draw_run(axes: dict, response, block, *, excitation=None, t_end: float | None = None,
             label_topple: bool = True) -> None:
    """Draw one run (``response`` with its history) on ``axes``, a dict of the panels wanted:
    ``"ground"`` (ground acceleration [g], from ``excitation`` itself up to ``t_end``), ``"tilt"``
    (theta/alpha, dashed at +-1), ``"rate"`` (theta_dot/p), ``"base"`` (base displacement [m]).

    When the body topples, a red vertical line marks the instant on every panel (labelled ``topples at
    t s`` on the tilt panel when ``label_topple``); the body's curves end there.
    """
    H = response.history
    if H is None:
        raise ValueError("this response was computed without history (simulate(..., history=True))")
    rows = H.rows
    t, th, thd, u = rows[:, 0], rows[:, 2], rows[:, 3], rows[:, 4]
    end = float(t[-1]) if t_end is None else max(float(t_end), float(t[-1]))
    if "ground" in axes:
        from rockcli.report.figures import excitation_samples

        tg, ag = excitation_samples(excitation, float(t[0]), end)
        axes["ground"].plot(tg, ag / G, lw=0.8, color="0.2")
        axes["ground"].axhline(0.0, color="0.6", lw=0.5)
    if "tilt" in axes:
        axes["tilt"].plot(t, th / block.alpha, lw=1.0, color="tab:blue")
        for y in (-1, 1):
            axes["tilt"].axhline(y, color="0.6", lw=0.6, ls="--")
    if "rate" in axes:
        axes["rate"].plot(t, thd / block.p, lw=1.0, color="tab:orange")
    if "base" in axes:
        axes["base"].plot(t, u, lw=1.0, color="tab:green")
    if response.verdict == "overturned" and math.isfinite(response.t_overturn_s):
        for ax in axes.values():
            ax.axvline(response.t_overturn_s, color=TOPPLE_COLOUR, lw=1.4)
        if label_topple and "tilt" in axes:
            # beside the line, never on it (a few points off), and at the panel's edge away from the fall: the
            # curve leaves through the top when the body falls to theta > 0, so the label goes to the bottom
            late = response.t_overturn_s - float(t[0]) > 0.6 * (end - float(t[0]))  # the label left of the line
            up = float(th[-1]) > 0 if th.size else True
            axes["tilt"].annotate(f"topples at {response.t_overturn_s:.2f} s", (response.t_overturn_s, 0.0 if up else 1.0),
                                  xycoords=("data", "axes fraction"), xytext=(-5 if late else 5, 4 if up else -4),
                                  textcoords="offset points", va="bottom" if up else "top",
                                  ha="right" if late else "left", color=TOPPLE_COLOUR, fontsize=8.5, fontweight="bold",
                                  bbox=LABEL_BOX)


def plot_response(response, block, foundation, path: str | os.PathLike, *, excitation=None, motion: str | None = None,
                  dpi: int = 120) -> Path:
    """Ground acceleration [g], theta/alpha, theta_dot/p and (isolated) base displacement [m] vs time.

    The layout of the paper's Figures 1 and 12; the overturning instant is marked. On hysteretic
    bearings (sliding, lead-rubber) a last panel draws the bearing's force-displacement loop
    (force over the weight of block + base against u).

    The ground acceleration is drawn from ``excitation`` itself (a pulse evaluated on its own fine
    grid, a record's samples), not from the solver's steps; the response from the history's rows
    (run with ``history_dt``, e.g. :func:`rockcli.report.figures.plot_grid_dt`, for the dense output
    between steps; the event rows sit among them). The title names the body (R, alpha, p), the
    motion (``motion``, else the record's name; a pulse's a_p and T_p) and the foundation with all
    its parameters. Several runs side by side: :func:`plot_responses`.
    """
    return plot_responses([(response, foundation, excitation, motion)], block, path, dpi=dpi)


def _right_end(response) -> float:
    """The right end of a run's time axis: its last row, and a little room past the red line of a run that topples."""
    t = response.history.rows[:, 0]
    right = float(t[-1])
    if response.verdict == "overturned":  # the red line at the instant it topples, inside the frame
        right += 0.04 * (right - float(t[0]))
    return right


def plot_responses(runs, block, path: str | os.PathLike, *, dpi: int = 120) -> Path:
    """Runs of one body side by side, one column each, as :func:`plot_response` draws one: the paper's Figures 1
    (two pulses) and 12 (the ground and an isolated base), both panels in one figure.

    ``runs``: ``(response, foundation, excitation, motion)`` tuples (``motion`` as in :func:`plot_response`), each
    response with its history. Each column has its own time axis (each run to its own end; one axis for all when they
    share one motion, as the ground and the bearings under one record); its top names the
    motion, the foundation and the verdict, the figure's title the body. With an isolated base among them every
    column has a base-displacement row (a rigid foundation's says the base does not move), and a loop row when a
    run is on hysteretic bearings.
    """
    import numpy as np

    from rockcli.report.figures import block_text, foundation_text, motion_text, new_figure, pyplot, title

    runs = list(runs)
    for response, *_ in runs:
        if response.history is None:
            raise ValueError("this response was computed without history (simulate(..., history=True))")
    check_output(path, image=True)
    plt = pyplot()
    iso = [getattr(f, "kind", 0) != 0 for _, f, _, _ in runs]
    loops = [r.history.z is not None and r.history.bearing_force is not None for r, *_ in runs]
    n = 4 if any(iso) else 3
    many = len(runs) > 1
    fig = new_figure(8.0 if not many else 6.0 * len(runs), 1.9 * n + (1.2 if not many else 1.6)
                     + (3.0 if any(loops) else 0.0))
    heights = [1.0] * n + ([1.7] if any(loops) else [])
    grid = fig.add_gridspec(len(heights), len(runs), height_ratios=heights)
    # one motion on several foundations (Figure 12): one time axis, each run seen against the same record
    same = many and all(x is runs[0][2] for _, _, x, _ in runs)
    t_right = max(_right_end(r) for r, *_ in runs)
    for j, (response, foundation, excitation, motion) in enumerate(runs):
        axes = [fig.add_subplot(grid[0, j])]
        for i in range(1, n):
            axes.append(fig.add_subplot(grid[i, j], sharex=axes[0]))
        for ax in axes[:-1]:
            ax.tick_params(labelbottom=False)
        rows = response.history.rows
        t = rows[:, 0]
        right = t_right if same else _right_end(response)
        keys = ("ground", "tilt", "rate") + (("base",) if iso[j] else ())
        draw_run(dict(zip(keys, axes)), response, block, excitation=excitation, t_end=right)
        if j == 0 or not many:
            axes[0].set_ylabel(r"ground acc. $\ddot u_g$ [g]")
            axes[1].set_ylabel(r"$\theta/\alpha$")
            axes[2].set_ylabel(r"$\dot\theta/p$")
        if iso[j] and j == iso.index(True):  # the first isolated column names the row
            axes[3].set_ylabel("base displacement $u$ [m]")
        if n == 4 and not iso[j]:  # a rigid foundation beside an isolated base: its base does not move
            axes[3].text(0.5, 0.5, "rigid foundation:\nthe base does not move", ha="center", va="center",
                         transform=axes[3].transAxes, fontsize=8.5, color="0.35")
            axes[3].tick_params(left=False, labelleft=False)
        if response.verdict == "overturned":
            axes[1].set_ylim(-math.pi / 2 / block.alpha * 1.05, math.pi / 2 / block.alpha * 1.05)
        for ax in axes[:3] if n == 4 and not iso[j] else axes:
            ax.grid(True, lw=0.3)
        if n == 4 and not iso[j]:
            axes[3].grid(False)
        axes[0].set_xlim(float(t[0]), right)
        axes[-1].set_xlabel("time $t$ [s]")
        if loops[j]:
            ax = fig.add_subplot(grid[n, j])
            fu, ff = rows[:, 4], rows[:, 8]
            ok = np.isfinite(ff)  # the peak rows carry no bearing force
            ax.plot(fu[ok], ff[ok] / G, lw=0.8, color="tab:purple")
            ax.set_xlabel("base displacement $u$ [m]")
            ax.set_ylabel("bearing force / $W$")
            ax.set_title("force-displacement loop of the bearings ($W = (m + m_b)\\,g$)", fontsize=8)
            ax.grid(True, lw=0.3)
        verdict = {"overturned": f"OVERTURNS at $t$ = {response.t_overturn_s:.2f} s",
                   "rocked": f"survives, peak $|\\theta|/\\alpha$ = {response.theta_max_over_alpha:.2f}",
                   "no_uplift": "no uplift"}[response.verdict]
        scene = f"{motion_text(excitation, motion)}\n{foundation_text(foundation)}\n{verdict}"
        if many:
            title(axes[0], scene, fontsize=9, color="#c0392b" if response.verdict == "overturned" else "0.1")
    title(fig, f"{block_text(block)}\n{scene}" if not many else block_text(block), fontsize=9 if not many else 10)
    try:
        return save_figure(fig, path, dpi=dpi)
    finally:
        plt.close(fig)
