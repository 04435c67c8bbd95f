"""A friction run drawn and written (``simulate --friction MU --plot/--history``): its figure and its history CSV."""

from __future__ import annotations

import io
import math
import os
from pathlib import Path

import numpy as np

from rockcli.io.files import write_text
from rockcli.io.units import G


def history_columns(res, body) -> tuple[list, list]:
    """``(names, columns)`` of the history of ``res`` (a :class:`rockcli.solve.slide.SlideResponse` with history) of
    ``body``: time, ground acceleration, and per contact (``base``, ``joint``) its rotation over its slenderness,
    its slip [m] and slip rate [m/s], and its pattern (face or pivot, stuck or sliding)."""
    from rockcli.kernels import chain_out as co

    H = res.history
    n = len(res.interfaces)
    names = ["t_s", "ag_mps2", "ag_g"]
    cols = [H[:, co.HC_T], H[:, co.HC_AG], H[:, co.HC_AG] / G]
    y0 = co.HC_PAT + 2 * n
    for j, p in enumerate(res.interfaces):
        k = p.name
        names += [f"{k}_psi_rad", f"{k}_psi_over_alpha", f"{k}_slide_m", f"{k}_slide_rate_mps", f"{k}_corner",
                  f"{k}_slipping"]
        cols += [H[:, y0 + 4 + 4 * j], H[:, y0 + 4 + 4 * j] / p.alpha, H[:, y0 + 2 + 4 * j], H[:, y0 + 3 + 4 * j],
                 H[:, co.HC_PAT + 2 * j], H[:, co.HC_PAT + 2 * j + 1]]
    if math.isfinite(res.u_max):
        names += ["u_m"]
        cols += [H[:, y0]]
    return names, cols


def write_slide_history_csv(res, body, path: str | os.PathLike) -> Path:
    """The rows of the run (every step end and event) as CSV: :func:`history_columns`."""
    if res.history is None:
        raise ValueError("this response was computed without history (simulate_friction(..., history=True))")
    names, cols = history_columns(res, body)
    buf = io.StringIO()
    np.savetxt(buf, np.column_stack(cols), delimiter=",", comments="", fmt="%.10g")
    return write_text(path, ",".join(names) + "\n" + buf.getvalue())


def plot_slide_response(res, body, path: str | os.PathLike, *, excitation=None, motion: str | None = None,
                        foundation=None, dpi: int = 120) -> Path:
    """Panels on one time axis: the ground acceleration [g]; per contact its rotation over its slenderness
    ``psi/alpha`` and its slip [cm] (the block above it along the surface below), shaded where it slides; on
    bearings the base's displacement. A red line the instant it fails (topples, or slides off: then the plinth's edge
    is drawn on the slip panel). The title names the body, the friction, the motion and the verdict in words."""
    from rockcli.io.files import check_output, save_figure
    from rockcli.kernels import chain_out as co
    from rockcli.report.figures import new_figure, plain, pyplot
    from rockcli.report.html_figures import FIGURE_WIDTH_IN, _rc
    from rockcli.report.response import TOPPLE_COLOUR
    from rockcli.report.slide_words import slide_sentence

    if res.history is None:
        raise ValueError("this response was computed without history (simulate_friction(..., history=True))")
    check_output(path, image=True)
    plt = pyplot()
    H = res.history
    t = H[:, co.HC_T]
    n = len(res.interfaces)
    y0 = co.HC_PAT + 2 * n
    iso = math.isfinite(res.u_max)
    stack = res.joint is not None
    order = list(range(n - 1, -1, -1))  # the body's contact first
    keys = ["ground"] + [f"rock{j}" for j in order] + [f"slide{j}" for j in order] + (["base"] if iso else [])
    with _rc():
        fig = new_figure(FIGURE_WIDTH_IN, 1.2 + 1.5 * len(keys), dpi=dpi)
        axes = {}
        for i, k in enumerate(keys):
            axes[k] = fig.add_subplot(len(keys), 1, i + 1, **({"sharex": axes["ground"]} if i else {}))
        ax = axes["ground"]
        tg, ag = _ground(excitation, t[-1]) if excitation is not None else (t, H[:, co.HC_AG])
        ax.plot(tg, ag / G, lw=0.8, color="0.3")
        ax.set_ylabel("ground acc. [g]")
        for j in order:
            p = res.interfaces[j]
            label = ("body on plinth" if j == 1 else "plinth on ground") if stack else "block"
            a = axes[f"rock{j}"]
            a.plot(t, H[:, y0 + 4 + 4 * j] / p.alpha, lw=0.9, color="C0")
            for s in (1.0, -1.0):
                a.axhline(s, ls=":", lw=0.7, color="0.5")
            a.set_ylabel(f"{label}:\nrotation / alpha")
            b = axes[f"slide{j}"]
            s_cm = 100.0 * H[:, y0 + 2 + 4 * j]
            b.plot(t, s_cm, lw=0.9, color="C2")
            slipping = H[:, co.HC_PAT + 2 * j + 1] != 0.0
            if slipping.any():
                lo, hi = b.get_ylim()
                b.fill_between(t, lo, hi, where=slipping, color="C2", alpha=0.12, step="post", lw=0)
                b.set_ylim(lo, hi)
            if math.isfinite(p.edge_m):
                for s in (1.0, -1.0):
                    b.axhline(100.0 * s * p.edge_m, ls="--", lw=0.8, color=TOPPLE_COLOUR)
            b.set_ylabel(f"{label}:\nslip [cm]")
        if iso:
            axes["base"].plot(t, H[:, y0], lw=0.9, color="C1")
            axes["base"].set_ylabel("base disp. [m]")
        if res.verdict in ("overturned", "slid off") and math.isfinite(res.t_fail):
            for a in axes.values():
                a.axvline(res.t_fail, color=TOPPLE_COLOUR, lw=1.0)
        axes[keys[-1]].set_xlabel("time [s]")
        mus = ", ".join(f"{p.name} mu = {m:g}" for p, m in zip(res.interfaces, res.mu))
        head = f"{plain(body.name)}: friction {mus}" + (f"; {plain(motion)}" if motion else "")
        fig.suptitle(head + "\n" + plain(_wrap(slide_sentence(body, res), 110)), fontsize=9)
        if fig.get_layout_engine() is None:  # (the report's figures lay themselves out)
            fig.subplots_adjust(left=0.11, right=0.98, bottom=0.06, top=1.0 - 0.9 / fig.get_figheight(),
                                hspace=0.35)
        return save_figure(fig, path, dpi=dpi)


def _ground(excitation, t_end: float):
    """``(t, ag)`` of the excitation up to ``t_end``: a record's samples, a pulse sampled 400 times a period."""
    if hasattr(excitation, "acc"):
        acc = np.asarray(excitation.acc, float)
        t = excitation.dt * np.arange(acc.size)
        keep = t <= t_end
        return np.append(t[keep], t_end), np.append(acc[keep], 0.0 if t_end > t[-1] else acc[keep][-1])
    t = np.linspace(0.0, t_end, max(2, int(400 * t_end / excitation.T_p)))
    return t, np.array([excitation.acceleration(x) for x in t])


def _wrap(text: str, width: int) -> str:
    import textwrap

    return "\n".join(textwrap.wrap(text, width))
