"""Time-history reports of one run: the history CSV and the Figure 1 / Figure 12 style plot.

matplotlib is imported inside the plotting function (Agg backend); files are written atomically.
"""

from __future__ import annotations

import io
import math
import os
from pathlib import Path

import numpy as np

from rockcli.report.files import check_output, save_figure, write_text
from rockcli.units import G

#: Columns of a history CSV (SI units, g only where labelled).
HISTORY_COLUMNS = ("t_s", "ag_mps2", "ag_g", "theta_rad", "theta_over_alpha", "theta_dot_radps", "u_m", "u_dot_mps")


def history_table(response, block) -> np.ndarray:
    """The history of ``response`` as an (n, 8) array in the order of :data:`HISTORY_COLUMNS`."""
    H = response.history
    if H is None:
        raise ValueError("this response was computed without history (simulate(..., history=True))")
    return np.column_stack([H.t, H.ag, H.ag / G, H.theta, H.theta / block.alpha, H.theta_dot, H.u, H.u_dot])


def write_history_csv(response, block, path: str | os.PathLike) -> Path:
    """Write ``t, ground acceleration, theta, theta_dot, u, u_dot`` of a run as CSV, atomically.

    Rows are every integrator step end and event; an impact appears as two rows at the same time
    (just before and just after it).
    """
    table = history_table(response, block)
    buf = io.StringIO()
    np.savetxt(buf, table, delimiter=",", header=",".join(HISTORY_COLUMNS), comments="", fmt="%.10g")
    return write_text(path, buf.getvalue())


def plot_response(response, block, foundation, title: str, path: str | os.PathLike, *, dpi: int = 120) -> Path:
    """Ground acceleration [g], theta/alpha, theta_dot/p and (isolated) base displacement [m] vs time.

    The layout of the paper's Figures 1 and 12; the overturning instant is marked.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    H = response.history
    if H is None:
        raise ValueError("this response was computed without history (simulate(..., history=True))")
    check_output(path, image=True)
    isolated = getattr(foundation, "kind", 0) != 0
    n = 4 if isolated else 3
    fig, axes = plt.subplots(n, 1, sharex=True, figsize=(8.0, 1.9 * n + 0.8))
    axes[0].plot(H.t, H.ag / G, lw=0.8, color="0.2")
    axes[0].set_ylabel("ground acc. [g]")
    axes[1].plot(H.t, H.theta / block.alpha, lw=1.0, color="tab:blue")
    axes[1].set_ylabel(r"$\theta/\alpha$")
    for y in (-1, 1):
        axes[1].axhline(y, color="0.6", lw=0.6, ls="--")
    axes[2].plot(H.t, H.theta_dot / block.p, lw=1.0, color="tab:orange")
    axes[2].set_ylabel(r"$\dot\theta/p$")
    if isolated:
        axes[3].plot(H.t, H.u, lw=1.0, color="tab:green")
        axes[3].set_ylabel("base disp. u [m]")
    if response.verdict == "overturned":
        for ax in axes:
            ax.axvline(response.t_overturn_s, color="tab:red", lw=0.8)
        axes[1].set_ylim(-math.pi / 2 / block.alpha * 1.05, math.pi / 2 / block.alpha * 1.05)
    for ax in axes:
        ax.grid(True, lw=0.3)
    axes[-1].set_xlabel("time [s]")
    verdict = {"overturned": f"OVERTURNS at {response.t_overturn_s:.2f} s",
               "rocked": f"survives, peak |theta|/alpha = {response.theta_max_over_alpha:.2f}",
               "no_uplift": "no uplift"}[response.verdict]
    axes[0].set_title(f"{title}\n{verdict}", fontsize=9)
    fig.tight_layout()
    try:
        return save_figure(fig, path, dpi=dpi)
    finally:
        plt.close(fig)
