"""Figures of the HTML report, as PNG bytes to embed (matplotlib, imported inside the functions).

* :func:`png_of`: the bytes of a figure drawn by one of the file-writing plotters
  (:func:`rockcli.report.response.plot_response`, :func:`rockcli.report.fragility.plot_fragility`),
  captured in memory, so that those plotters stay the one place that draws them;
* :func:`responses_png`: one record's response on every configuration, side by side on common axes
  (:func:`rockcli.report.response.draw_run` draws each run), the toppling instant marked in red;
* :func:`margins_png`: per record and configuration, the smallest scale factor that topples the body;
* :func:`share_png`: for several records, the share of them that topple the body when all are scaled
  by the same factor (an empirical fragility in units of the records themselves);
* :func:`stroke_png`: the peak base displacement on every isolated configuration (the bearings' stroke).

Every function takes rows with the fields of :class:`rockcli.assess.AssessmentRow` (the fragility
rows have the margin fields too) and returns PNG bytes, or None when there is nothing to draw.

Readable where embedded: the page shows a figure ``w`` inches wide ``96 w`` pixels wide
(:func:`rockcli.report.html.figure`), so that no font is under :data:`MIN_FONT_PT` (8 pt, 10.7 px);
:func:`readability_problems` lists any text that is smaller or falls off the canvas (the tests call it
on every figure drawn here). Bars and legends name a configuration by its short name (``on the
ground``, ``Tb=2.5s``), which the report's configuration table spells out.
"""

from __future__ import annotations

import io
import math
import tempfile
from pathlib import Path

from rockcli.report.figures import plain

#: Colours of the outcomes (the report's CSS uses the same).
COLOURS = {"topples": "#c0392b", "survives": "#2e7d32", "undecided": "#e69500", "not computed": "#777777"}
_CONF_COLOURS = ("#444444", "#1f77b4", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf")
#: The smallest font of the report's figures [pt] (10.7 px at 96 px per inch).
MIN_FONT_PT = 8.0
#: Resolution the figures are rendered at [dots per inch]: 1.5 times the 96 px per inch they are shown at,
#: for sharp text on high-density screens and in print.
DPI = 144
#: Fonts of the figures drawn here [pt].
_RC = {"font.size": 9.0, "axes.titlesize": 9.5, "axes.labelsize": 9.0, "xtick.labelsize": 8.5,
       "ytick.labelsize": 8.5, "legend.fontsize": 8.5, "figure.titlesize": 10.0}
#: Widths [in] of a figure across the page and of a figure alone (at 96 px per inch: 1100 and 820 px).
PAGE_WIDTH_IN, FIGURE_WIDTH_IN = 11.45, 8.5


def png_of(draw) -> bytes:
    """The PNG bytes that ``draw(path)`` (a plotter that writes a figure file) would write.

    The figure is captured in memory (:func:`rockcli.io.files.captured_figures`); the path names a private
    temporary folder only so that the plotter's checks of its output path pass.
    """
    from rockcli.io.files import captured_figures

    with tempfile.TemporaryDirectory(prefix="rockcli-report-") as folder, captured_figures() as got:
        path = Path(folder) / "figure.png"
        draw(path)
        return got[path]


def _pyplot():
    from rockcli.report.figures import pyplot

    return pyplot()


def _rc():
    """The fonts of the report's figures, for the ``with`` block that creates a figure's artists."""
    return _pyplot().rc_context(_RC)


def _figure(width: float, height: float):
    """A figure with one axes, in constrained layout, with the report's fonts."""
    from rockcli.report.figures import new_figure

    with _rc():
        fig = new_figure(width, height, dpi=DPI)
        return fig, fig.add_subplot()


def short_name(configuration) -> str:
    """``on the ground`` or the configuration's short name (``Tb=2.5s``)."""
    return configuration.header if configuration.isolated else "on the ground"


def _title(ax, title: str, configurations=()) -> None:
    """``title`` on ``ax``, then a key from each isolated configuration's short name to all its parameters
    (the bars and legends use the short names)."""
    from rockcli.report.figures import foundation_text
    from rockcli.report.figures import title as put_title

    key = "; ".join(f"{c.header}: {foundation_text(c.foundation)}" for c in configurations if c.isolated)
    put_title(ax, title + (f"\n{key}" if key else ""), fontsize=9.5, loc="left")


def _drawn_texts(fig) -> list:
    """The text artists ``fig`` draws: its own texts, and per axes the titles, axis labels, texts, legend
    and the tick labels of the ticks in view."""
    out = list(fig.texts) + [t for t in (fig._suptitle, fig._supxlabel, fig._supylabel) if t is not None]
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        out += [ax.title, ax._left_title, ax._right_title, ax.xaxis.label, ax.yaxis.label, *ax.texts]
        legend = ax.get_legend()
        if legend is not None:
            out += list(legend.get_texts())
        for axis in (ax.xaxis, ax.yaxis):
            for tick in axis._update_ticks():  # the ticks in view, as drawn
                out += [t for t in (tick.label1, tick.label2) if t.get_visible()]
    return [t for t in out if t.get_visible() and t.get_text().strip()]


def readability_problems(fig, min_pt: float = MIN_FONT_PT, *, drawn: bool = False) -> list[str]:
    """What makes ``fig`` hard to read where the report embeds it: texts smaller than ``min_pt`` and texts
    (or anything else drawn) outside the canvas, one line each (empty: none). ``drawn``: the figure has just
    been drawn (saved at its own dpi): measure its layout as it is instead of laying it out again."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    if not hasattr(fig.canvas, "get_renderer"):  # a figure pyplot has closed
        FigureCanvasAgg(fig)
    if not drawn:
        fig.draw_without_rendering()  # the layout as drawn, without the pixels
    renderer = fig.canvas.get_renderer()
    box = fig.bbox
    out = []

    def outside(e) -> bool:
        return e.x0 < box.x0 - 1 or e.y0 < box.y0 - 1 or e.x1 > box.x1 + 1 or e.y1 > box.y1 + 1

    for t in _drawn_texts(fig):
        if t.get_fontsize() < min_pt - 1e-9:
            out.append(f"{t.get_text()!r}: {t.get_fontsize():g} pt < {min_pt:g} pt")
        e = t.get_window_extent(renderer)
        if outside(e):
            out.append(f"{t.get_text()!r}: outside the figure ({e.x0:.0f}..{e.x1:.0f} x {e.y0:.0f}..{e.y1:.0f} "
                       f"of {box.x1:.0f} x {box.y1:.0f} px)")
    tight = fig.get_tightbbox(renderer).transformed(fig.dpi_scale_trans)
    if outside(tight):
        out.append(f"something drawn lies outside the figure ({tight})")
    return out


def _bytes(fig) -> bytes:
    """The PNG of ``fig`` at its own resolution (:data:`DPI`: the figures are made at the resolution they are
    saved at, so that what is measured after saving, e.g. a legend's place, is what was saved)."""
    plt = _pyplot()
    dpi = fig.dpi
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


def _verdict_text(configuration, response) -> str:
    from rockcli.report.words import configuration_words

    where = configuration_words(configuration)
    if response.verdict == "overturned":
        return f"{where}: TOPPLES at {response.t_overturn_s:.2f} s"
    if response.verdict == "no_uplift":
        return f"{where}: survives (it does not lift off)"
    word = "survives" if response.settled else "undecided (still rocking at the end)"
    return f"{where}: {word}, peak tilt {100 * response.theta_max_over_alpha:.0f} % of alpha"


#: The response figures end where the motion has died out: the ground acceleration, the tilt and the base
#: displacement all below this share of their peaks (a run that topples: at the instant it topples).
QUIET_SHARE = 0.05


def _last_above(t, v, share: float = QUIET_SHARE) -> float:
    """The last time ``|v|`` reaches ``share`` of its peak (``t[0]`` when ``v`` is zero throughout)."""
    import numpy as np

    a = np.abs(np.asarray(v, dtype=float))
    peak = float(a.max()) if a.size else 0.0
    return float(t[np.nonzero(a >= share * peak)[0][-1]]) if peak > 0 else float(t[0])


def _active_end(response, block) -> float:
    """When the run's motion has died out: the instant it topples, else the last time its tilt or its
    base displacement reaches :data:`QUIET_SHARE` of its peak."""
    if response.verdict == "overturned" and math.isfinite(response.t_overturn_s):
        return float(response.t_overturn_s)
    rows = response.history.rows
    return max(_last_above(rows[:, 0], rows[:, 2]), _last_above(rows[:, 0], rows[:, 4]))


def _active_end_ground(excitation, t_begin: float, t_end: float) -> float:
    """The last time the ground acceleration reaches :data:`QUIET_SHARE` of its peak."""
    from rockcli.report.figures import excitation_samples

    t, a = excitation_samples(excitation, t_begin, t_end)
    return _last_above(t, a)


def responses_png(runs, block, excitation, label: str) -> bytes | None:
    """One record's response on every configuration, side by side on common axes.

    ``runs``: ``(configuration, response)`` pairs, each response with its history. One column per run
    (at most three; the caller splits more); rows: the ground acceleration [g], the tilt over alpha
    (dashed at +-1, where the body tips over its corner) and, when a configuration is isolated, the
    displacement of the isolated base [m]. Every panel of a row has the same axes: time from the
    record's start until the motion has died out on every panel (:data:`QUIET_SHARE`), tilt within
    +-max(1.2, peak) (at most 2: beyond that the body is falling), the largest base displacement. A red
    line marks the instant the body topples (:func:`rockcli.report.response.draw_run`).
    """
    from rockcli.report.figures import block_text, foundation_text, motion_text, new_figure, title, wrap_to
    from rockcli.report.response import draw_run

    runs = [(c, r) for c, r in runs if r is not None and r.history is not None]
    if not runs:
        return None
    plt = _pyplot()
    iso = any(c.isolated for c, _ in runs)
    keys = ["ground", "tilt"] + (["base"] if iso else [])
    n = len(runs)
    t0 = min(float(r.history.rows[0, 0]) for _, r in runs)
    t1 = max([_active_end_ground(excitation, t0, max(float(r.history.rows[-1, 0]) for _, r in runs))]
             + [_active_end(r, block) for _, r in runs])
    t1 += 0.04 * (t1 - t0)
    peak = 0.0
    for _, r in runs:
        th = r.history.rows[:, 2] / block.alpha
        peak = max(peak, float(abs(th).max()) if th.size else 0.0)
    tilt = min(2.0, max(1.2, 1.05 * peak))
    width = PAGE_WIDTH_IN if n > 1 else FIGURE_WIDTH_IN
    with _rc():
        fig = new_figure(width, 0.75 + 1.55 * len(keys), dpi=DPI)
        grid = fig.add_gridspec(len(keys), n)
        axes, first = {}, None
        for j in range(n):
            for i, k in enumerate(keys):
                share = {} if first is None else {"sharex": first}
                if j > 0:
                    share["sharey"] = axes[(0, k)]
                ax = fig.add_subplot(grid[i, j], **share)
                first = first or ax
                axes[(j, k)] = ax
        for j, (c, r) in enumerate(runs):
            mine = {k: axes[(j, k)] for k in keys if k != "base" or c.isolated}
            draw_run(mine, r, block, excitation=excitation, t_end=t1)
            top = axes[(j, "ground")]
            top.set_title(wrap_to(fig, f"{_verdict_text(c, r)}\n{foundation_text(c.foundation)}", 9.0, 0.84 / n),
                          fontsize=9.0, loc="left", color="#c0392b" if r.verdict == "overturned" else "0.1")
            if iso and not c.isolated:
                ax = axes[(j, "base")]
                ax.text(0.5, 0.5, "standing on the ground:\nno bearings, the base does not move", ha="center",
                        va="center", transform=ax.transAxes, fontsize=8.5, color="0.35")
                ax.tick_params(left=False, labelleft=False)
            for k in keys:
                ax = axes[(j, k)]
                ax.grid(True, lw=0.3)
                if k != keys[-1]:
                    ax.tick_params(labelbottom=False)
                if j > 0:
                    ax.tick_params(labelleft=False)
            axes[(j, keys[-1])].set_xlabel("time since the record's first sample [s]")
        first.set_xlim(t0, t1)
        axes[(0, "tilt")].set_ylim(-tilt, tilt)
        axes[(0, "ground")].set_ylabel("ground acc. [g]")
        axes[(0, "tilt")].set_ylabel("tilt / alpha")
        if iso:
            j_iso = next(j for j, (c, _) in enumerate(runs) if c.isolated)
            axes[(j_iso, "base")].set_ylabel("base moves [m]")
            axes[(j_iso, "base")].tick_params(labelleft=True)
        title(fig, f"{motion_text(excitation, label)}; {block_text(block)}", fontsize=10, x=0.01, ha="left")
    return _bytes(fig)


def margins_png(rows, records, configurations, title: str) -> bytes | None:
    """Horizontal bars: the smallest scale factor of each record that topples the body, per configuration.

    Bars to the right of the line at 1 are margins (the record would have to be that much stronger);
    to the left, the body topples already at that fraction of the record. Records nothing up to 4x
    topples are drawn to 4 with an arrow. Each bar is labelled with its factor and the configuration's
    short name; its colour is the outcome (red topples, green survives, amber undecided).
    """
    from rockcli.report.words import outcome

    by = {(r.record, r.configuration): r for r in rows}
    if not any(math.isfinite(getattr(r, "overturn_scale", math.nan)) or
               str(getattr(r, "margin_note", "")).startswith("no overturning") for r in rows):
        return None
    n_c = len(configurations)
    height = 0.8 / n_c
    fig, ax = _figure(FIGURE_WIDTH_IN, 1.4 + 0.34 * n_c * len(records) + 0.3 * len(records))
    _title(ax, title, configurations)
    for j, c in enumerate(configurations):
        for i, rec in enumerate(records):
            r = by.get((rec, c.header))
            if r is None or r.error:
                continue
            y = i + (j - (n_c - 1) / 2) * height
            s = r.overturn_scale
            capped = not math.isfinite(s)
            if capped and not str(r.margin_note).startswith("no overturning"):
                continue
            value = 4.0 if capped else s
            colour = COLOURS[outcome(r)] if hasattr(r, "overturned") else _CONF_COLOURS[j % len(_CONF_COLOURS)]
            ax.barh(y, value - 0.1, left=0.1, height=height * 0.9, color=colour, alpha=0.85)
            ax.text(value * 1.03, y, (">4" if capped else f"{s:.2f}") + f"  {short_name(c)}", va="center",
                    fontsize=8.5, bbox={"facecolor": "white", "edgecolor": "none", "pad": 0.6, "alpha": 0.85})
    ax.axvline(1.0, color="k", lw=1.0)
    _scale_axis(ax, (0.1, 12), (0.1, 0.2, 0.5, 1, 2, 4, 10))
    ax.set_yticks(range(len(records)))
    ax.set_yticklabels([plain(rec) for rec in records])  # the records' names as written
    ax.set_ylim(len(records) - 0.5, -0.5)
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
    fig, ax = _figure(FIGURE_WIDTH_IN, 4.1)
    _title(ax, title, configurations)
    drawn = False
    s = np.geomspace(0.1, 4.0, 400)
    for j, c in enumerate(configurations):
        mine = [r for r in rows if r.configuration == c.header and not r.error]
        if len(mine) < 2:
            continue
        scales = np.array([r.overturn_scale for r in mine], dtype=float)
        share = [(np.isfinite(scales) & (scales <= v)).sum() / len(mine) for v in s]
        ax.step(s, share, where="post", color=_CONF_COLOURS[j % len(_CONF_COLOURS)], lw=1.8,
                label=f"{short_name(c)} ({len(mine)} records)")
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
    ax.legend(frameon=False, loc="upper left")
    return _bytes(fig)


def stroke_png(rows, records, configurations, title: str) -> bytes | None:
    """Bars: the peak base displacement [m] of every record on every isolated configuration; the runs in
    which the body toppled are hatched and labelled as such (a displacement until the fall, not a stroke
    to design the bearings for). With ``--azimuth worst`` a pair's bar is its stroke over the orientations in
    which the body survives (:func:`rockcli.report.words.stroke_m`), hatched only when it survives in none."""
    from rockcli.report.words import TOPPLES, outcome, stroke_m

    iso = [c for c in configurations if c.isolated]
    by = {(r.record, r.configuration): r for r in rows}
    if not iso:
        return None
    n_c = len(iso)
    height = 0.8 / n_c
    fig, ax = _figure(FIGURE_WIDTH_IN, 1.4 + 0.34 * n_c * len(records) + 0.3 * len(records))
    _title(ax, title, iso)
    top = 0.0
    for j, c in enumerate(iso):
        for i, rec in enumerate(records):
            r = by.get((rec, c.header))
            if r is None or r.error or not math.isfinite(r.base_disp_max_m):
                continue
            y = i + (j - (n_c - 1) / 2) * height
            d, toppled = r.base_disp_max_m, outcome(r) == TOPPLES
            if r.azimuths_run and math.isfinite(stroke_m(r)):  # --azimuth worst: where it survives, every azimuth
                d, toppled = stroke_m(r), False
            ax.barh(y, d, height=height * 0.9, color=_CONF_COLOURS[(j + 1) % len(_CONF_COLOURS)],
                    hatch="//" if toppled else None, alpha=0.5 if toppled else 0.85)
            ax.text(d, y, f" {d:.2f} m" + (f"  {c.header}" if n_c > 1 else "")
                    + (" (it toppled)" if toppled else ""), va="center", fontsize=8.5)
            top = max(top, d)
    ax.set_xlim(0, max(top, 1e-3) * 1.55)
    ax.set_yticks(range(len(records)))
    ax.set_yticklabels([plain(rec) for rec in records])  # the records' names as written
    ax.set_ylim(len(records) - 0.5, -0.5)
    ax.set_xlabel("peak displacement of the isolated base relative to the ground [m]")
    ax.grid(True, axis="x", color="0.9", lw=0.5)
    return _bytes(fig)
