"""The history CSV of a body on a plinth (``simulate --on ... --history FILE``), written atomically."""

from __future__ import annotations

import io
import os
from pathlib import Path

import numpy as np

from rockcli.io.files import write_text
from rockcli.io.units import G

#: Columns of a stack's history CSV (SI, g where labelled): the body's rotation on the plinth ``psi``, the plinth's
#: ``theta2``, the pattern of motion of the row and its event.
STACK_HISTORY_COLUMNS = ("t_s", "ag_mps2", "ag_g", "psi_rad", "psi_over_alpha1", "psi_dot_radps", "theta2_rad",
                         "theta2_over_alpha_asm", "theta2_dot_radps", "pattern", "event")


def write_stack_history_csv(response, stack, path: str | os.PathLike) -> Path:
    """Write the rows of ``response.history`` (a :class:`rockcli.solve.StackHistory`: every step end and event of
    the run) as CSV: :data:`STACK_HISTORY_COLUMNS`."""
    H = response.history
    if H is None:
        raise ValueError("this response was computed without history (simulate_stack(..., history=True))")
    columns = [H.t, H.ag, H.ag / G, H.psi, H.psi / stack.body.alpha, H.psi_dot, H.theta2,
               H.theta2 / stack.alpha_asm, H.theta2_dot]
    names = list(STACK_HISTORY_COLUMNS)
    if H.u is not None:  # on bearings: the base's displacement relative to the ground, before the pattern
        columns.append(H.u)
        names.insert(len(columns) - 1, "u_m")
    buf = io.StringIO()
    np.savetxt(buf, np.column_stack(columns), delimiter=",", comments="", fmt="%.10g")
    lines = buf.getvalue().splitlines()
    body = "".join(f"{line},{pat},{ev}\n" for line, pat, ev in zip(lines, H.pattern, H.event))
    return write_text(path, ",".join(names) + "\n" + body)


def plot_stack_response(response, stack, path: str | os.PathLike, *, excitation=None, motion: str | None = None,
                        alone=None, t_end: float | None = None, foundation=None, dpi: int = 120) -> Path:
    """A body on its plinth: ground acceleration [g]; the body's rotation on the plinth over its slenderness
    ``psi/alpha1`` (with ``alone``, a :class:`rockcli.solve.Response` with history of the body standing on the
    ground, its ``theta/alpha`` in grey); the plinth's ``theta2/alpha_asm``. The stack's curves are drawn through
    its history rows (every step end and event of the run); a red line marks the instant a block topples."""
    import math

    from rockcli.io.files import check_output, save_figure
    from rockcli.report.figures import (block_text, excitation_samples, foundation_text, motion_text, new_figure,
                                        pyplot, title)

    H = response.history
    if H is None:
        raise ValueError("this response was computed without history (simulate_stack(..., history=True))")
    check_output(path, image=True)
    plt = pyplot()
    fig = new_figure(8.0, 7.0)
    axes = fig.subplots(3, 1, sharex=True)
    t = H.t
    end = float(t[-1])
    if alone is not None and alone.history is not None:
        end = max(end, float(alone.history.t[-1]))
    if t_end is not None:  # the end of the excitation + tail (a history at rest may hold a last row far beyond)
        end = min(end, float(t_end))
    tg, ag = excitation_samples(excitation, float(t[0]), end)
    axes[0].plot(tg, ag / G, lw=0.8, color="0.2")
    axes[0].set_ylabel(r"ground acc. $\ddot u_g$ [g]")
    a1 = stack.body.alpha
    if alone is not None and alone.history is not None:
        axes[1].plot(alone.history.t, alone.history.theta / a1, lw=0.8, color="0.6", ls="--",
                     label=f"alone on the ground: {_words(alone.verdict, alone.theta_max_over_alpha)}")
    on = ("topples off the plinth" if response.toppled == "body" else "falls with the plinth"
          if response.toppled == "plinth" else "does not lift" if response.body.theta_max == 0.0 else
          f"peak {response.body.theta_max_over_alpha:.2f}")
    axes[1].plot(t, H.psi / a1, lw=0.9, color="tab:blue", label=f"on its plinth: {on}")
    axes[1].set_ylabel(r"body on plinth $\psi/\alpha_1$")
    axes[2].plot(t, H.theta2 / stack.alpha_asm, lw=0.9, color="tab:brown",
                 label="the plinth" + (": topples" if response.toppled == "plinth" else
                                       f": peak {response.plinth.theta_max / stack.alpha_asm:.2f}"))
    axes[2].set_ylabel(r"plinth $\theta_2/\alpha_{asm}$")
    for ax, lim in ((axes[1], math.pi / 2 / a1), (axes[2], math.pi / 2 / stack.alpha_asm)):
        for y in (-1.0, 1.0):
            ax.axhline(y, color="0.5", lw=0.6, ls=":")
        top = max(1.2, min(lim, 1.05 * float(max(abs(ax.get_ylim()[0]), abs(ax.get_ylim()[1])))))
        ax.set_ylim(-top, top)
        ax.legend(loc="upper left", fontsize=7)
    if response.toppled:
        for ax in axes:
            ax.axvline(response.t_overturn_s, color="tab:red", lw=1.0)
    for ax in axes:
        ax.grid(True, lw=0.3)
    axes[0].set_xlim(float(t[0]), end)
    axes[-1].set_xlabel("time $t$ [s]")
    p = stack.plinth
    verdict = (f"the {response.toppled} topples at $t$ = {response.t_overturn_s:.2f} s" if response.toppled else
               "both survive")
    title(fig, f"{block_text(stack.body)}, on a free plinth {p.height:g} m x {p.width:g} m "
               f"({stack.m2:.2g} times its mass)\n{motion_text(excitation, motion)}; "
               f"{'rigid foundation' if foundation is None else foundation_text(foundation)}\n{verdict}",
          fontsize=9)
    try:
        return save_figure(fig, path, dpi=dpi)
    finally:
        plt.close(fig)


def _words(verdict: str, peak: float) -> str:
    return {"overturned": "topples", "no_uplift": "no uplift"}.get(verdict, f"peak {peak:.2f}")
