"""The history CSV of a body on a plinth (``simulate --on ... --history FILE``), written atomically."""

from __future__ import annotations

import io
import math
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
    """A body on its plinth beside the same body alone, one run each (``simulate --on --plot`` and the HTML report
    of ``assess column --on``, which embeds this figure: one figure for both).

    Panels, on one time axis: the ground acceleration [g]; the body's rotation on its plinth over its own
    slenderness ``psi/alpha1`` and, with ``alone`` (a :class:`rockcli.solve.Response` with history of the same body
    standing alone on the same foundation), its ``theta/alpha`` dashed in grey; the plinth's rotation over the
    slenderness of body and plinth as one block ``theta2/alpha_asm``; on bearings, the base's displacement [m]
    (the stack's, and the body alone's in grey). Dotted lines at +-1 mark each block's tipping point; a red line
    the instant a block of the stack topples, named on its panel; a grey one the instant the body alone does. The
    legends give each run's outcome and peak; the title names the body, the plinth, the motion, the foundation and
    the verdict (:func:`rockcli.report.plinth_words.run_sentence`). The stack's curves are drawn through its
    history rows (every step end and event of the run). Time runs until the motion has died out (every curve
    under 5 % of its peak) or the last block has toppled, within ``t_end`` [s] when given. Fonts of at least
    8 pt at the report's scale (:func:`rockcli.report.html_figures.readability_problems`).
    """
    from rockcli.report.plinth_words import plinth_name, run_sentence
    from rockcli.report.words import body_noun
    from rockcli.io.files import check_output, save_figure
    from rockcli.report.figures import block_text, foundation_text, motion_text, new_figure, plain, pyplot, title
    from rockcli.report.html_figures import FIGURE_WIDTH_IN, _rc
    from rockcli.report.response import LABEL_BOX, TOPPLE_COLOUR

    H = response.history
    if H is None:
        raise ValueError("this response was computed without history (simulate_stack(..., history=True))")
    check_output(path, image=True)
    plt = pyplot()
    a1, aa = stack.body.alpha, stack.alpha_asm
    A = alone.history.rows if alone is not None and alone.history is not None else None
    on_bearings = H.u is not None
    t0, t1 = _time_window(response, A, alone, excitation, t_end)
    noun, name = plain(body_noun(stack.body)), plain(plinth_name(stack))  # the user's names, drawn as written
    where = ("standing on the ground" if foundation is None or not on_bearings else "on the same bearings")
    keys = ["ground", "body", "plinth"] + (["base"] if on_bearings else [])
    with _rc():
        fig = new_figure(FIGURE_WIDTH_IN, 1.2 + 1.75 * len(keys), dpi=dpi)
        axes = {}
        for i, k in enumerate(keys):
            axes[k] = fig.add_subplot(len(keys), 1, i + 1, **({"sharex": axes["ground"]} if i else {}))
        from rockcli.report.figures import excitation_samples

        tg, ag = excitation_samples(excitation, t0, t1)
        axes["ground"].plot(tg, ag / G, lw=0.8, color="0.2")
        axes["ground"].set_ylabel("ground acc. [g]")
        ax = axes["body"]
        ax.plot(H.t, H.psi / a1, lw=1.1, color="tab:blue", label=f"{noun} on its {name}: {_body_words(response)}")
        if A is not None:
            ax.plot(A[:, 0], A[:, 2] / a1, lw=1.0, color="0.55", ls="--", zorder=1.5,
                    label=f"{noun} alone, {where}: {_alone_words(alone)}")
        ax.set_ylabel(f"{noun[4:]}'s tilt /\nits alpha ({math.degrees(a1):.3g}°)")
        ax = axes["plinth"]
        ax.plot(H.t, H.theta2 / aa, lw=1.1, color="tab:brown", label=f"the {name}: {_plinth_words(response, noun)}")
        ax.set_ylabel(f"{name}'s tilt /\nalpha_asm ({math.degrees(aa):.3g}°)")
        if on_bearings:
            ax = axes["base"]
            ax.plot(H.t, H.u, lw=1.0, color="tab:green", label=f"under {noun} on its {name}")
            if A is not None:
                ax.plot(A[:, 0], A[:, 4], lw=0.9, color="0.55", ls="--", zorder=1.5, label=f"under {noun} alone")
            ax.set_ylabel("base moves [m]")
        for k, lim in (("body", math.pi / 2 / a1), ("plinth", math.pi / 2 / aa)):
            ax = axes[k]
            for y in (-1.0, 1.0):
                ax.axhline(y, color="0.4", lw=0.7, ls=":", label="±1: tipping point" if y > 0 else None)
            shown = [abs(c) for c in _within(ax, t0, t1)]
            top = min(2.0, lim, max(1.2, 1.05 * max(shown, default=0.0)))
            ax.set_ylim(-top, top)
        if alone is not None and alone.verdict == "overturned" and math.isfinite(alone.t_overturn_s):
            axes["body"].axvline(alone.t_overturn_s, color="0.55", lw=1.0)
        if response.toppled:
            for ax in axes.values():
                ax.axvline(response.t_overturn_s, color=TOPPLE_COLOUR, lw=1.4)
            late = response.t_overturn_s - t0 > 0.6 * (t1 - t0)
            who = noun if response.toppled == "body" else f"the {name}"
            text = f"{who} topples at {response.t_overturn_s:.2f} s"
            k = "plinth" if response.toppled == "plinth" else "body"
            falls_down = (H.theta2 if k == "plinth" else H.psi)[-1] < 0  # the label on the side it does not fall to
            axes[k].annotate(text, (response.t_overturn_s, 0.97 if falls_down else 0.03),
                             xycoords=("data", "axes fraction"), xytext=(-5 if late else 5, 0),
                             textcoords="offset points", va="top" if falls_down else "bottom",
                             ha="right" if late else "left", color=TOPPLE_COLOUR, fontsize=8.5, fontweight="bold",
                             bbox=LABEL_BOX)  # beside the red line, never on it
        for k, ax in axes.items():
            ax.grid(True, lw=0.3)
            if k != keys[-1]:
                ax.tick_params(labelbottom=False)
            if k != "ground":
                ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=2, fontsize=8.5, frameon=False,
                          borderaxespad=0.1, handlelength=1.8, columnspacing=1.2)
        axes["ground"].set_xlim(t0, t1)
        axes[keys[-1]].set_xlabel("time since the record's first sample [s]" if hasattr(excitation, "times") else
                                  "time [s]")
        p = stack.plinth
        head = (f"{block_text(stack.body)}, on a free {name} {p.height:g} m tall x {p.width:g} m wide "
                f"({stack.m2:.2g} times its mass)\n{motion_text(excitation, motion)}; "
                f"{'rigid foundation' if foundation is None else foundation_text(foundation)}")
        title(fig, f"{head}\n{plain(run_sentence(stack, response))}", fontsize=10, x=0.01, ha="left")
    try:
        return save_figure(fig, path, dpi=dpi)
    finally:
        plt.close(fig)


def _within(ax, t0: float, t1: float):
    """The values of the curves of ``ax`` drawn between ``t0`` and ``t1``."""
    import numpy as np

    out = []
    for line in ax.get_lines():
        x, y = np.asarray(line.get_xdata(), float), np.asarray(line.get_ydata(), float)
        if x.size > 2:
            out += list(y[(x >= t0) & (x <= t1)])
    return out


def _time_window(response, A, alone, excitation, t_end):
    """``(t0, t1)``: from the first row until the motion has died out on every panel (the ground, each block,
    the base: :func:`rockcli.report.html_figures._last_above`) or the last toppling, a little after; within
    ``t_end``."""
    from rockcli.report.html_figures import _active_end_ground, _last_above

    H = response.history
    t0 = float(H.t[0])
    last = float(H.t[-1]) if A is None else max(float(H.t[-1]), float(A[-1, 0]))
    if t_end is not None:
        last = min(last, float(t_end))
    ends = [_active_end_ground(excitation, t0, last)]
    ends.append(response.t_overturn_s if response.toppled else
                max(_last_above(H.t, H.psi), _last_above(H.t, H.theta2),
                    _last_above(H.t, H.u) if H.u is not None else t0))
    if A is not None:
        ends.append(alone.t_overturn_s if alone.verdict == "overturned" else
                    max(_last_above(A[:, 0], A[:, 2]), _last_above(A[:, 0], A[:, 4])))
    t1 = min(max(ends), last) if t_end is not None else max(ends)
    t1 = max(t1, t0 + 1e-3)
    return t0, t1 + 0.04 * (t1 - t0)


def _peak(v: float) -> str:
    """A peak over a tipping angle: two decimals, one significant digit under 0.01 (a lift is never "0.00")."""
    return f"peak {v:.2f}" if v >= 0.01 else f"peak {v:.1g}"


def _alone_words(alone) -> str:
    if alone.verdict == "overturned":
        return f"topples at {alone.t_overturn_s:.2f} s"
    if alone.verdict == "no_uplift":
        return "does not lift off"
    return _peak(alone.theta_max_over_alpha) + ("" if alone.settled else " so far")


def _body_words(res) -> str:
    if res.toppled == "body":
        return f"topples off it at {res.t_overturn_s:.2f} s"
    if res.toppled == "plinth":
        return f"falls with it at {res.t_overturn_s:.2f} s"
    if res.body.theta_max == 0.0:
        return "stays put on it (does not lift)"
    return _peak(res.body.theta_max_over_alpha)


def _plinth_words(res, noun: str) -> str:
    if res.toppled == "plinth":
        return f"topples at {res.t_overturn_s:.2f} s"
    if math.isnan(res.plinth.t_uplift_s):
        return "does not rock"
    return _peak(res.plinth.theta_max / res.alpha_asm) + (f" until {noun} fell" if res.toppled else "")
