"""Figures of the HTML report, as PNG bytes to embed (matplotlib, imported inside the functions).

* :func:`png_of`: the bytes of a figure drawn by one of the file-writing plotters
  (:func:`rockcli.report.response.plot_response`, :func:`rockcli.report.fragility.plot_fragility`),
  captured in memory, so that those plotters stay the one place that draws them;
* :func:`margins_png`: per record and configuration, the smallest scale factor that topples the body;
* :func:`share_png`: for several records, the share of them that topple the body when all are scaled
  by the same factor (an empirical fragility in units of the records themselves);
* :func:`stroke_png`: the peak base displacement on every isolated configuration (the bearings' stroke).

Every function takes rows with the fields of :class:`rockcli.assess.AssessmentRow` (the fragility
rows have the margin fields too) and returns PNG bytes, or None when there is nothing to draw.
"""

from __future__ import annotations

import io
import math
import tempfile
from pathlib import Path

#: Colours of the outcomes (the report's CSS uses the same).
COLOURS = {"topples": "#c0392b", "survives": "#2e7d32", "undecided": "#e69500", "not computed": "#777777"}
_CONF_COLOURS = ("#444444", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf")


def png_of(draw) -> bytes:
    """The PNG bytes that ``draw(path)`` (a plotter that writes a figure file) would write.

    The figure is captured in memory (:func:`rockcli.files.captured_figures`); the path names a private
    temporary folder only so that the plotter's checks of its output path pass.
    """
    from rockcli.files import captured_figures

    with tempfile.TemporaryDirectory(prefix="rockcli-report-") as folder, captured_figures() as got:
        path = Path(folder) / "figure.png"
        draw(path)
        return got[path]


def _pyplot():
    from rockcli.report.figures import pyplot

    return pyplot()


def _figure(width: float, height: float):
    """A figure with one axes, in constrained layout."""
    from rockcli.report.figures import new_figure

    fig = new_figure(width, height)
    return fig, fig.add_subplot()


def _title(ax, title: str, configurations) -> dict:
    """Put ``title`` (and the isolation parameters the configurations share) on ``ax``; returns the
    legend text of each configuration (what differs between them, in symbols)."""
    from rockcli.report.figures import split_labels
    from rockcli.report.figures import title as put_title

    legend, common = split_labels(c.foundation.label for c in configurations)
    put_title(ax, title + (f"\nisolation: {common}" if common else ""), fontsize=9, loc="left")
    return {c.header: legend[c.foundation.label] for c in configurations}


def _bytes(fig, dpi: int = 90) -> bytes:
    plt = _pyplot()
    buf = io.BytesIO()
    try:
        fig.savefig(buf, format="png", dpi=dpi)
    finally:
        plt.close(fig)
    return buf.getvalue()


def _scale_axis(ax, limits, ticks) -> None:
    """A log axis of scale factors with plain tick labels (0.5, 1, 2)."""
    from matplotlib.ticker import NullFormatter

    ax.set_xscale("log")
    ax.set_xlim(*limits)
    ax.set_xticks(ticks)
    ax.set_xticklabels([f"{t:g}" for t in ticks])
    ax.xaxis.set_minor_formatter(NullFormatter())


def margins_png(rows, records, configurations, title: str) -> bytes | None:
    """Horizontal bars: the smallest scale factor of each record that topples the body, per configuration.

    Bars to the right of the line at 1 are margins (the record would have to be that much stronger);
    to the left, the body topples already at that fraction of the record. Records nothing up to 4x
    topples are drawn to 4 with an arrow.
    """
    from rockcli.assess.verdicts import outcome

    by = {(r.record, r.configuration): r for r in rows}
    if not any(math.isfinite(getattr(r, "overturn_scale", math.nan)) or
               str(getattr(r, "margin_note", "")).startswith("no overturning") for r in rows):
        return None
    plt = _pyplot()
    n_c = len(configurations)
    height = 0.8 / n_c
    fig, ax = _figure(8.0, 1.3 + 0.32 * n_c * len(records) + 0.4)
    names = _title(ax, title, configurations)
    for j, c in enumerate(configurations):
        for i, rec in enumerate(records):
            r = by.get((rec, c.header))
            if r is None or r.error:
                continue
            y = i + (j - (n_c - 1) / 2) * height
            s = r.overturn_scale
            capped = not math.isfinite(s)
            value = 4.0 if capped else s
            colour = COLOURS[outcome(r)] if hasattr(r, "overturned") else _CONF_COLOURS[j % len(_CONF_COLOURS)]
            ax.barh(y, value - 0.1, left=0.1, height=height * 0.9, color=colour, alpha=0.85,
                    edgecolor=_CONF_COLOURS[j % len(_CONF_COLOURS)], lw=1.2)
            ax.text(value * 1.03, y, (">4 (nothing up to 4x topples it)" if capped else f"{s:.2f}") + f"  {names[c.header]}",
                    va="center", fontsize=7)
    ax.axvline(1.0, color="k", lw=1.0)
    _scale_axis(ax, (0.1, 12), (0.1, 0.2, 0.5, 1, 2, 4, 10))
    ax.set_yticks(range(len(records)))
    ax.set_yticklabels(records, fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("smallest scale factor of the record that topples the body (log scale)")
    ax.grid(True, axis="x", which="both", color="0.9", lw=0.5)
    return _bytes(fig)


def share_png(rows, configurations, title: str) -> bytes | None:
    """For several records: the share of them whose smallest toppling factor is at most ``s``, against ``s``.

    An empirical fragility in units of the records: at ``s = 1`` it is (apart from safe islands)
    the share of the records, as recorded, that topple the body.
    """
    import numpy as np

    plt = _pyplot()
    fig, ax = _figure(8.0, 3.9)
    names = _title(ax, title, configurations)
    drawn = False
    s = np.geomspace(0.1, 4.0, 400)
    for j, c in enumerate(configurations):
        mine = [r for r in rows if r.configuration == c.header and not r.error]
        if len(mine) < 2:
            continue
        scales = np.array([r.overturn_scale for r in mine], dtype=float)
        share = [(np.isfinite(scales) & (scales <= v)).sum() / len(mine) for v in s]
        ax.step(s, share, where="post", color=_CONF_COLOURS[j % len(_CONF_COLOURS)], lw=1.8,
                label=f"{names[c.header]} ({len(mine)} records)")
        drawn = True
    if not drawn:
        plt.close(fig)
        return None
    ax.axvline(1.0, color="k", lw=0.8)
    _scale_axis(ax, (0.1, 4.0), (0.1, 0.2, 0.5, 1, 2, 4))
    ax.set_ylim(-0.02, 1.02)
    ax.set_xlabel("every record scaled by the same factor (log scale)")
    ax.set_ylabel("share of the records\nthat topple the body")
    ax.grid(True, which="both", color="0.9", lw=0.5)
    ax.legend(fontsize=8, frameon=False, loc="upper left")
    return _bytes(fig)


def stroke_png(rows, records, configurations, title: str) -> bytes | None:
    """Bars: the peak base displacement [m] of every record on every isolated configuration."""
    from rockcli.assess.verdicts import TOPPLES, outcome

    iso = [c for c in configurations if c.isolated]
    by = {(r.record, r.configuration): r for r in rows}
    if not iso:
        return None
    plt = _pyplot()
    n_c = len(iso)
    height = 0.8 / n_c
    fig, ax = _figure(8.0, 1.3 + 0.32 * n_c * len(records) + 0.4)
    names = _title(ax, title, iso)
    top = 0.0
    for j, c in enumerate(iso):
        for i, rec in enumerate(records):
            r = by.get((rec, c.header))
            if r is None or r.error or not math.isfinite(r.base_disp_max_m):
                continue
            y = i + (j - (n_c - 1) / 2) * height
            toppled = outcome(r) == TOPPLES
            ax.barh(y, r.base_disp_max_m, height=height * 0.9, color=_CONF_COLOURS[(j + 1) % len(_CONF_COLOURS)],
                    hatch="//" if toppled else None, alpha=0.85)
            ax.text(r.base_disp_max_m, y, f" {r.base_disp_max_m:.2f} m  {names[c.header]}"
                    + (" (until it toppled)" if toppled else ""), va="center", fontsize=7)
            top = max(top, r.base_disp_max_m)
    ax.set_xlim(0, max(top, 1e-3) * 1.45)
    ax.set_yticks(range(len(records)))
    ax.set_yticklabels(records, fontsize=7)
    ax.invert_yaxis()
    ax.set_xlabel("peak displacement of the isolated base relative to the ground [m]")
    ax.grid(True, axis="x", color="0.9", lw=0.5)
    return _bytes(fig)
