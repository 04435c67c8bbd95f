"""A record's rocking spectrum (``rockcli spectrum rocking``): its CSV and JSON columns and its figure.

matplotlib is imported inside :func:`plot_rocking_spectrum` (Agg backend); files are written atomically.
Sizes in m, frequency parameters in rad/s, rotations as ``|theta|_max / alpha``.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

from rockcli.io.files import check_output, save_figure, write_text
from rockcli.report.figures import spec_text
from rockcli.report.spectra import _column_text, _pyplot, constant_columns
from rockcli.report.spectra_plinth import on_words, plinth_columns, plinth_title, with_plinth

#: Columns of ``rockcli spectrum rocking --csv`` (one row per block size of every curve); the same names
#: in its ``--json`` curves.
ROCKING_COLUMNS = ("record", "scale", "alpha_deg", "isolation", "R_m", "p_radps", "theta_max_over_alpha",
                   "overturned", "uplift", "proven", "peak_final")


def rocking_columns(curve, record: str, scale: float, plinth: bool | None = None) -> dict:
    """One curve (:class:`rockcli.spectra.RockingCurve`) as columns keyed by :data:`ROCKING_COLUMNS` (with
    ``plinth``, None: when the curve has one, also ``plinth`` and ``toppled``, as the overturning maps')."""
    import numpy as np

    n = curve.R.size
    return {"record": np.full(n, record, dtype=object), "scale": np.full(n, float(scale)),
            "alpha_deg": np.full(n, float(curve.alpha_deg)), "isolation": np.full(n, curve.isolation, dtype=object),
            "R_m": np.asarray(curve.R, float), "p_radps": np.asarray(curve.p, float),
            "theta_max_over_alpha": np.asarray(curve.theta_max_over_alpha, float),
            "overturned": np.asarray(curve.overturned, bool), "uplift": np.asarray(curve.uplifted, bool),
            "proven": np.asarray(curve.proven, bool), "peak_final": np.asarray(curve.peak_final, bool),
            **(plinth_columns(curve, n) if (curve.plinth is not None if plinth is None else plinth) else {})}


def write_rocking_csv(curves, path, record: str, scale: float = 1.0, extra: dict | None = None) -> Path:
    """Every point of ``curves`` as CSV, atomically (``extra``: constant columns appended, e.g. a given
    ``restitution``; :func:`rockcli.report.spectra.constant_columns`)."""
    curves = list(curves)
    columns = with_plinth(ROCKING_COLUMNS, curves)
    fh = io.StringIO()
    w = csv.writer(fh, lineterminator="\n")
    w.writerow(columns)
    for c in curves:
        cols = rocking_columns(c, record, scale, plinth=columns != ROCKING_COLUMNS)
        w.writerows(zip(*(_column_text(cols[k]) for k in columns)))
    return write_text(path, constant_columns(fh.getvalue(), extra))


def rocking_json(curves) -> list:
    """The curves for ``--json``: per curve ``alpha_deg``, ``isolation`` and one list per varying column
    (``R_m``, ``p_radps``, ``theta_max_over_alpha``, ``overturned``, ``uplift``, ``proven``, ``peak_final``)."""
    out = []
    for c in curves:
        cols = rocking_columns(c, "", 1.0)
        out.append({"alpha_deg": float(c.alpha_deg), "isolation": c.isolation,
                    **({"plinth": c.plinth.label, "toppled": cols["toppled"].tolist()} if c.plinth is not None else
                       {"plinth": None} if any(d.plinth is not None for d in curves) else {}),
                    **{k: cols[k].tolist() for k in ROCKING_COLUMNS[4:]}})
    return out


_STYLES = ("-", "--", ":", "-.")
#: Tick values of the log axes (those inside the range are used).
_TICKS = (0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 1, 1.5, 2, 3, 5, 7, 10, 15, 20, 30, 50, 70, 100, 150, 200)


def _log_ticks(axis, lo: float, hi: float) -> None:
    """Plain-number ticks (0.2, 0.5, 1, 2, ...) on a log ``axis`` spanning ``lo``-``hi``."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullLocator

    ticks = [t for t in _TICKS if lo * (1 - 1e-9) <= t <= hi * (1 + 1e-9)]
    if len(ticks) > 9:
        ticks = [t for t in ticks if str(t).lstrip("0.")[0] in "125"]
    axis.set_major_locator(FixedLocator(ticks))
    axis.set_major_formatter(FuncFormatter(lambda v, _: f"{v:g}"))
    axis.set_minor_locator(NullLocator())


def plot_rocking_spectrum(curves, path, *, title: str, dpi: int = 120) -> Path:
    """Peak ``|theta|/alpha`` against ``R`` (log axis, ``p`` on the top axis), one line per curve.

    The rigid foundation is drawn heavy and black, isolated bases in colour on top of it; slenderness
    values differ by line style. Sizes that overturn are drawn at 1 and marked with a circle (the rigid
    foundation's larger, so that both show where they coincide); sizes that never uplift lie at 0; a
    block that passed alpha and came back peaks above 1 (the axis then reaches above 1).
    """
    import numpy as np
    from matplotlib.lines import Line2D

    from rockcli.spectra.rocking import frequency_parameter
    from rockcli.io.units import G

    check_output(path, image=True)
    plt = _pyplot()
    curves = list(curves)
    alphas = list(dict.fromkeys(c.alpha_deg for c in curves))
    isolated = list(dict.fromkeys(c.isolation for c in curves if c.isolation != "none"))
    rows = -(-(len(curves) + 1) // 2)  # legend rows under the axes (two columns)
    height = 4.4 + 0.16 * rows
    fig, ax = plt.subplots(figsize=(7.0, height))
    try:
        for c in curves:
            style = _STYLES[alphas.index(c.alpha_deg) % len(_STYLES)]
            rigid = c.isolation == "none"
            colour = "k" if rigid else f"C{isolated.index(c.isolation) % 10}"
            label = f"$\\alpha$ = {c.alpha_deg:g}$\\degree$, {spec_text(c.isolation)}" + on_words(c, curves)
            mark = {} if c.plinth is None else {"marker": "v", "ms": 3.5, "mfc": "none", "mew": 0.8,
                                                 "markevery": max(1, c.R.size // 12)}  # --on: marked, thinner
            ax.plot(c.R, c.plotted, ls=style, lw=2.6 if rigid and c.plinth is None else 1.3, color=colour, label=label,
                    **mark,
                    zorder=3 if rigid else 4)
            over = np.asarray(c.overturned, bool)
            if over.any():
                ax.plot(c.R[over], np.ones(int(over.sum())), ls="none", marker="o", ms=5.5 if rigid else 3.0,
                        mfc="none" if rigid else colour, mec=colour, mew=0.8, zorder=3.5 if rigid else 4.5)
        R_all = np.concatenate([c.R for c in curves])
        lo, hi = float(R_all.min()), float(R_all.max())
        ax.set_xscale("log")
        ax.set_xlim(lo, hi)
        _log_ticks(ax.xaxis, lo, hi)
        survived = [c.theta_max_over_alpha[~np.asarray(c.overturned, bool)] for c in curves]
        top_peak = max([1.0] + [float(v.max()) for v in survived if v.size])
        ax.set_ylim(-0.02, 1.06 * top_peak)  # a block that passed alpha and came back peaks above 1
        ax.set_xlabel("block size R (semi-diagonal) [m]")
        ax.set_ylabel(r"peak $|\theta|/\alpha$")
        ax.grid(color="0.9", lw=0.5)

        def to_p(r):
            return frequency_parameter(np.maximum(np.asarray(r, float), 1e-12))

        def to_r(p):
            return 0.75 * G / np.maximum(np.asarray(p, float), 1e-12) ** 2

        top = ax.secondary_xaxis("top", functions=(to_p, to_r))
        _log_ticks(top.xaxis, float(to_p(hi)), float(to_p(lo)))
        top.set_xlabel(r"frequency parameter $p = \sqrt{3g/4R}$ [rad/s]", fontsize=8)
        top.tick_params(labelsize=8)
        handles, labels = ax.get_legend_handles_labels()
        if any(np.asarray(c.overturned).any() for c in curves):
            handles.append(Line2D([], [], color="0.3", marker="o", mfc="none", ls="none", mew=0.8))
            labels.append(r"overturns (drawn at $|\theta|/\alpha$ = 1)")
        ax.set_title(plinth_title(title, curves), fontsize=9,
                     **({"wrap": True} if any(c.plinth is not None for c in curves) else {}))
        fig.legend(handles, labels, fontsize=7, frameon=False, loc="lower center", ncol=2)
        fig.tight_layout(rect=(0, (0.05 + 0.15 * rows) / height, 1, 1))
        return save_figure(fig, path, dpi=dpi)
    finally:
        plt.close(fig)
