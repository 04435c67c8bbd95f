"""Spectra reports: overturning maps (Figures 6, 9), minimum-overturning curves (Figures 7, 8, 9, 11),
the Table-I-like critical-size table, as CSV, aligned text and figures.

matplotlib is imported inside the functions (Agg backend); every file is written atomically.
Accelerations are in units of ``g tan(alpha)`` (column names say so), periods in s, sizes in m.
"""

from __future__ import annotations

import csv
import io
import math
from pathlib import Path

from rockcli.io.files import check_output, save_figure, write_text
from rockcli.io.units import G
from rockcli.report.spectra_plinth import on_words, plinth_columns, plinth_title, with_plinth

#: Columns of ``rockcli spectrum overturning --csv`` (one row per cell of every map).
MAP_COLUMNS = ("alpha_deg", "pulse", "isolation", "T_p_s", "R_m", "wp_over_p", "ap_over_g_tan_alpha", "ap_g",
               "overturned", "theta_max_over_alpha", "uplift", "peak_final", "proven")
#: Columns of ``rockcli spectrum min-overturning --csv`` (one row per omega_p/p of every curve).
MIN_COLUMNS = ("alpha_deg", "pulse", "isolation", "T_p_s", "R_m", "wp_over_p", "ap_min_over_g_tan_alpha",
               "ap_safe_over_g_tan_alpha", "ap_uplift_over_g_tan_alpha", "ap_min_g", "scan_step", "tolerance",
               "ap_max_over_g_tan_alpha", "refine_step", "refine_band", "stepped_over_by_scan")
#: Columns of ``rockcli spectrum critical-size --csv`` (the paper's Table I layout, one row per entry).
CRITICAL_COLUMNS = ("source", "pulse", "T_p_s", "alpha_deg", "Tb_over_Tp", "Tb_s", "wp_over_p_cross", "R_critical_m")

#: Grey levels of the maps: no uplift, uplift without overturning (light), overturning (dark).
MAP_COLOURS = ("white", "0.80", "0.30")


def _size(T_p, x):
    """Block semi-diagonal [m] at omega_p/p = x for a pulse of period T_p [s] (NaN without T_p)."""
    if T_p is None:
        return float("nan")
    p = 2.0 * math.pi / (T_p * x)
    return 0.75 * G / (p * p)


def _fmt(v):
    if isinstance(v, bool):
        return str(v)  # True/False, as every rockcli CSV writes booleans
    if isinstance(v, float):
        return "" if math.isnan(v) else repr(float(v))
    return v


def _write_rows(path, columns, rows, extra: dict | None = None) -> Path:
    fh = io.StringIO()
    w = csv.writer(fh, lineterminator="\n")
    w.writerow(columns)
    for row in rows:
        w.writerow([_fmt(row[c]) for c in columns])
    return write_text(path, constant_columns(fh.getvalue(), extra))


def constant_columns(text: str, values: dict | None) -> str:
    """The CSV ``text`` with one column per ``values`` item appended (the same value on every row): the
    solver options a sweep ran with (e.g. ``restitution``) when they are not the defaults."""
    if not values:
        return text
    rows = list(csv.reader(io.StringIO(text)))
    fh = io.StringIO()
    w = csv.writer(fh, lineterminator="\n")
    w.writerow(rows[0] + list(values))
    for row in rows[1:]:
        w.writerow(row + [_fmt(v) for v in values.values()])
    return fh.getvalue()


def _check_image_path(path) -> Path:
    return check_output(path, image=True)


def _save(fig, path, dpi):
    return save_figure(fig, path, dpi=dpi)


def _finish(fig, path, dpi, title):
    """Title (if any; wrapped to the figure), save (constrained layout keeps everything on the canvas)."""
    from rockcli.report.figures import title as put_title

    if title:
        put_title(fig, title, fontsize=9)
    return _save(fig, path, dpi)


def _pyplot():
    from rockcli.report.figures import pyplot

    return pyplot()


# --------------------------------------------------------------------------------------------------
# Overturning maps
# --------------------------------------------------------------------------------------------------
def _column_text(values) -> list:
    """One CSV field per value, as :func:`_fmt` writes it, for a whole column at once."""
    import numpy as np

    v = np.asarray(values)
    if v.dtype == bool:
        return np.where(v, "True", "False").tolist()
    if v.dtype.kind == "f":
        return ["" if x != x else repr(x) for x in v.tolist()]  # x != x: NaN
    return [str(x) for x in v.tolist()]


def map_columns(m, plinth: bool | None = None) -> dict:
    """The cells of one map (:class:`rockcli.spectra.OverturningMap`) as columns keyed by
    :data:`MAP_COLUMNS`, row by row (a_p outer, omega_p/p inner); with ``plinth`` (None: when the map has one) also
    ``plinth`` (its spec, empty for the block alone) and ``toppled`` (``body``, ``plinth`` or empty)."""
    import numpy as np

    x = np.asarray(m.wp_over_p, dtype=float)
    y = np.asarray(m.ap_over_g_tan_alpha, dtype=float)
    X, Y = np.meshgrid(x, y)
    T_p = m.pulse.T_p
    n = X.size
    return {"alpha_deg": np.full(n, m.alpha_deg), "pulse": np.full(n, m.pulse.shape, dtype=object),
            "isolation": np.full(n, m.isolation.label, dtype=object),
            "T_p_s": np.full(n, math.nan if T_p is None else float(T_p)),
            "R_m": np.array([_size(T_p, v) for v in x] * y.size),
            "wp_over_p": X.ravel(), "ap_over_g_tan_alpha": Y.ravel(),
            "ap_g": Y.ravel() * math.tan(math.radians(m.alpha_deg)),
            "overturned": np.asarray(m.overturned, dtype=bool).ravel(),
            "theta_max_over_alpha": np.asarray(m.theta_max_over_alpha, dtype=float).ravel(),
            "uplift": np.asarray(m.uplifted, dtype=bool).ravel(),
            "peak_final": np.asarray(m.peak_final, dtype=bool).ravel(),
            "proven": (np.asarray(m.settled, dtype=bool) | np.asarray(m.overturned, dtype=bool)).ravel(),
            **(plinth_columns(m, n) if (m.plinth is not None if plinth is None else plinth) else {})}


def write_map_csv(maps, path, extra: dict | None = None) -> Path:
    """Write every cell of ``maps`` (:class:`rockcli.spectra.OverturningMap`) as CSV, atomically
    (``extra``: constant columns appended, see :func:`constant_columns`)."""
    maps = list(maps)
    columns = with_plinth(MAP_COLUMNS, maps)
    fh = io.StringIO()
    w = csv.writer(fh, lineterminator="\n")
    w.writerow(columns)
    for m in maps:
        cols = map_columns(m, plinth=columns != MAP_COLUMNS)
        w.writerows(zip(*(_column_text(cols[c]) for c in columns)))
    return write_text(path, constant_columns(fh.getvalue(), extra))


def _panel_grid(n_rows, n_cols, plt, width=3.4, height=3.0, extra=0.5, legend_rows: float = 0.0):
    """A figure of ``n_rows`` x ``n_cols`` panels; with ``legend_rows`` > 0 a last row of that height
    (in panel heights) holds an empty axes for the legend (returned as the third value)."""
    from rockcli.report.figures import new_figure

    fig = new_figure(width * n_cols + 0.4, height * (n_rows + legend_rows) + extra)
    if not legend_rows:
        return fig, fig.subplots(n_rows, n_cols, squeeze=False)
    grid = fig.add_gridspec(n_rows + 1, n_cols, height_ratios=[1.0] * n_rows + [legend_rows])
    axes = grid[:n_rows, :].subgridspec(n_rows, n_cols).subplots(squeeze=False)
    under = fig.add_subplot(grid[n_rows, :])
    under.axis("off")
    return fig, axes, under


def _r_axis(ax, T_p):
    import numpy as np

    if T_p is None:
        return

    def fwd(x):
        x = np.asarray(x, dtype=float)
        return 3.0 * G * T_p ** 2 * np.maximum(x, 0.0) ** 2 / (16.0 * math.pi ** 2)

    def inv(r):
        r = np.asarray(r, dtype=float)
        return np.sqrt(np.maximum(r, 0.0) * 16.0 * math.pi ** 2 / (3.0 * G * T_p ** 2))

    sec = ax.secondary_xaxis("top", functions=(fwd, inv))
    sec.set_xlabel(f"$R$ [m] for $T_p$ = {T_p:.3g} s", fontsize=7)
    sec.tick_params(labelsize=7)


def plot_maps(maps, path, *, n_cols: int | None = None, title: str | None = None, dpi: int = 100) -> Path:
    """Overturning maps like the paper's Figure 6: one panel per map, rows by slenderness.

    White: no uplift; light grey: rocks and survives; dark grey: overturns. x = omega_p/p,
    y = a_p/(g tan alpha); a top axis gives the block size R when the pulse period is known.
    """
    import numpy as np
    from matplotlib.colors import BoundaryNorm, ListedColormap
    from matplotlib.patches import Patch

    from rockcli.report.figures import split_labels
    from rockcli.report.figures import title as put_title

    _check_image_path(path)
    plt = _pyplot()
    maps = list(maps)
    alphas = list(dict.fromkeys(m.alpha_deg for m in maps))
    if n_cols is None:
        n_cols = max(1, len(maps) // len(alphas))
    n_rows = math.ceil(len(maps) / n_cols)
    fig, axes = _panel_grid(n_rows, n_cols, plt)
    legend, common = split_labels(_iso_label(m.isolation) for m in maps)
    cmap = ListedColormap(list(MAP_COLOURS))
    norm = BoundaryNorm([-0.5, 0.5, 1.5, 2.5], 3)
    try:
        for k, ax in enumerate(axes.ravel()):
            if k >= len(maps):
                ax.set_visible(False)
                continue
            m = maps[k]
            code = np.where(m.overturned, 2, np.where(m.uplifted, 1, 0))
            x, y = m.wp_over_p, m.ap_over_g_tan_alpha
            dx = (x[-1] - x[0]) / max(1, x.size - 1) if x.size > 1 else 1.0
            dy = (y[-1] - y[0]) / max(1, y.size - 1) if y.size > 1 else 1.0
            ax.imshow(code, origin="lower", aspect="auto", cmap=cmap, norm=norm, interpolation="nearest",
                      extent=(x[0] - dx / 2, x[-1] + dx / 2, y[0] - dy / 2, y[-1] + dy / 2))
            if m.toppled is not None and (np.asarray(m.toppled) == 2).any():  # --on: where the plinth topples
                from matplotlib.collections import PatchCollection
                from matplotlib.patches import Rectangle

                rows, cols = np.nonzero(np.asarray(m.toppled) == 2)
                ax.add_collection(PatchCollection(
                    [Rectangle((x[j] - dx / 2, y[i] - dy / 2), dx, dy) for i, j in zip(rows, cols)],
                    facecolor="none", edgecolor="white", hatch="////", linewidth=0.0))
            put_title(ax, f"$\\alpha$ = {m.alpha_deg:g}°, {_pulse_words(m.pulse)}\n{legend[_iso_label(m.isolation)]}"
                      + on_words(m, maps), fontsize=8)
            ax.set_xlabel(r"$\omega_p / p$", fontsize=8)
            ax.set_ylabel(r"$a_p / (g \tan\alpha)$", fontsize=8)
            ax.tick_params(labelsize=7)
            _r_axis(ax, m.pulse.T_p)
        handles = [Patch(facecolor=c, edgecolor="0.5", label=lab)
                   for c, lab in zip(MAP_COLOURS, ("no uplift", "no overturning", "overturning"))]
        if any(m.toppled is not None for m in maps):
            handles.append(Patch(facecolor=MAP_COLOURS[2], edgecolor="white", hatch="////",
                                 label="overturning: the plinth topples (else the body off it)"))
        fig.legend(handles=handles, loc="outside lower center", ncol=len(handles), fontsize=8, frameon=False)
        if common and not title:
            title = f"isolation: {common}"
        return _finish(fig, path, dpi, plinth_title(title, maps))
    finally:
        plt.close(fig)


# --------------------------------------------------------------------------------------------------
# Minimum overturning curves
# --------------------------------------------------------------------------------------------------
def min_rows(curves):
    """One dict per point of every curve, keyed by :data:`MIN_COLUMNS` (and ``plinth``, its spec or empty, when
    a curve stands on a plinth)."""
    curves = list(curves)
    on = any(c.plinth is not None for c in curves)
    for c in curves:
        tan_a = math.tan(math.radians(c.alpha_deg))
        T_p = c.pulse.T_p
        for j, x in enumerate(c.wp_over_p):
            yield {"alpha_deg": c.alpha_deg, "pulse": c.pulse.shape, "isolation": c.isolation.label,
                   "T_p_s": float("nan") if T_p is None else T_p, "R_m": _size(T_p, float(x)),
                   "wp_over_p": float(x), "ap_min_over_g_tan_alpha": float(c.ap_min[j]),
                   "ap_safe_over_g_tan_alpha": float(c.ap_safe[j]),
                   "ap_uplift_over_g_tan_alpha": float(c.ap_uplift[j]), "ap_min_g": float(c.ap_min[j]) * tan_a,
                   "scan_step": c.step, "tolerance": c.tol, "ap_max_over_g_tan_alpha": c.ap_max,
                   "refine_step": c.refine, "refine_band": c.refine_band,
                   "stepped_over_by_scan": bool(c.refined[j]) if c.refined is not None else False,
                   **({"plinth": "" if c.plinth is None else c.plinth.label} if on else {})}


def write_min_csv(curves, path, extra: dict | None = None) -> Path:
    """Write the minimum-overturning curves as CSV (:data:`MIN_COLUMNS`; ``extra`` appended), atomically."""
    curves = list(curves)
    return _write_rows(path, with_plinth(MIN_COLUMNS, curves), min_rows(curves), extra)


def _panels(curves) -> list:
    """``[(alpha_deg, shape, curves of that panel), ...]`` in the order the panels first appear."""
    curves = list(curves)
    keys = dict.fromkeys((c.alpha_deg, c.pulse.shape) for c in curves)
    return [(a, sh, [c for c in curves if (c.alpha_deg, c.pulse.shape) == (a, sh)]) for a, sh in keys]


def plot_min_curves(curves, path, *, crossings=None, title: str | None = None, y_max: float | None = None,
                    dpi: int = 100) -> Path:
    """Minimum overturning acceleration like the paper's Figures 7, 8, 11: one panel per
    ``(alpha, pulse)``, one curve per configuration, the rigid foundation as a heavy dark line.

    Each isolated curve has its own colour, line style and marker (every tenth point), so that
    overlapping curves (Figure 11's six bearings) stay apart in print and in grey. The legend names
    what differs between the curves, the title what they share (xi, gamma, mu, ...).

    ``crossings``: optional ``{(alpha_deg, shape): [(x, y, label), ...]}`` points to mark.
    A curve is drawn only where something overturns up to its ``ap_max``. A note under the panels
    says how the minima were found (:attr:`rockcli.spectra.MinCurve.found_by`) and how many of them
    lie in a window the first scan stepped over (marked with a small cross).
    """
    import numpy as np

    from rockcli.report.figures import footnote, split_labels
    from rockcli.report.figures import title as put_title

    _check_image_path(path)
    plt = _pyplot()
    panels = _panels(curves)
    alphas = list(dict.fromkeys(a for a, _, _ in panels))
    shapes = list(dict.fromkeys(s for _, s, _ in panels))
    n_iso = max(sum(not c.isolation.rigid for c in mine) for _, _, mine in panels)
    on = any(c.plinth is not None for c in curves)
    isos = list(dict.fromkeys(_iso_label(c.isolation) for c in curves))
    legend, common = split_labels(_iso_label(c.isolation) for c in curves)
    chars = max(len(lab.replace("$", "")) + len(on_words(c, curves)) for lab, c in
                ((legend[_iso_label(c.isolation)], c) for c in curves))
    n_leg = len({(legend[_iso_label(c.isolation)], on_words(c, curves)) for c in curves})
    ncol = max(1, min(n_leg, int((4.6 * len(shapes) + 0.4) * 72.0 / (chars * 0.5 * 7.0 + 40.0))))
    fig, axes, under = _panel_grid(len(alphas), len(shapes), plt, width=4.6, height=3.6, extra=0.7,
                                   legend_rows=0.065 * math.ceil(n_leg / ncol) / len(alphas) ** 0.5)
    styles = ["-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 1))]
    markers = ["o", "s", "^", "D", "v", "P", "X", "*"]
    try:
        for (a, sh, mine) in panels:
            ax = axes[alphas.index(a), shapes.index(sh)]
            k = 0
            top = 0.0
            for c in mine:
                y = np.asarray(c.ap_min, dtype=float)
                if np.isfinite(y).any():
                    top = max(top, float(np.nanmax(y)))
                label = legend[_iso_label(c.isolation)] + on_words(c, curves)
                if on:  # --on: one colour per foundation, solid alone and dashed on the plinth
                    j = isos.index(_iso_label(c.isolation))
                    colour = "k" if c.isolation.rigid else f"C{j % 10}"
                    ax.plot(c.wp_over_p, y, color=colour, ls="-" if c.plinth is None else "--",
                            lw=2.6 if c.isolation.rigid else 1.4, label=label, zorder=3 if c.isolation.rigid else 2)
                    k += 1
                elif c.isolation.rigid:
                    ax.plot(c.wp_over_p, y, color="k", lw=2.6, label=label, zorder=3)
                else:
                    every = max(1, c.wp_over_p.size // 10)
                    ax.plot(c.wp_over_p, y, ls=styles[k % len(styles)], lw=1.3, color=f"C{k % 10}",
                            marker=markers[k % len(markers)], ms=4, mfc="none", mew=0.9,
                            markevery=(int(k * every / max(1, n_iso)) % every, every),
                            label=label)
                    k += 1
                if c.refined is not None and c.refined.any():
                    ax.plot(c.wp_over_p[c.refined], y[c.refined], "x", ms=3.5, mew=0.8,
                            color=colour if on else "k" if c.isolation.rigid else f"C{(k - 1) % 10}", zorder=4)
                T_p = c.pulse.T_p
            for (xc, yc, lab) in (crossings or {}).get((a, sh), []):
                ax.plot([xc], [yc], "o", ms=5, mfc="none", mec="k")
                ax.annotate(lab, (xc, yc), textcoords="offset points", xytext=(4, -10), fontsize=6,
                            bbox=dict(boxstyle="round,pad=0.15", fc="white", ec="none", alpha=0.85), zorder=5)
            put_title(ax, f"$\\alpha$ = {a:g}°, {_pulse_words(mine[0].pulse)}", fontsize=8)
            ax.set_xlabel(r"$\omega_p / p$", fontsize=8)
            ax.set_ylabel(r"minimum overturning $a_p / (g \tan\alpha)$", fontsize=8)
            ax.set_ylim(0.0, y_max if y_max is not None else max(2.0, 1.05 * top))
            ax.set_xlim(c.wp_over_p[0], c.wp_over_p[-1])
            ax.grid(color="0.9", lw=0.5)
            ax.tick_params(labelsize=7)
            _r_axis(ax, T_p)
        handles = {}
        for ax in axes.ravel():
            for h, lab in zip(*ax.get_legend_handles_labels()):
                handles.setdefault(lab, h)
        under.legend(handles.values(), handles.keys(), loc="upper center", ncol=ncol, fontsize=7, frameon=False)
        footnote(fig, _search_note(curves), fontsize=6.5)
        if common and not title:
            title = f"isolation: {common}"
        return _finish(fig, path, dpi, plinth_title(title, curves))
    finally:
        plt.close(fig)


def _iso_label(isolation) -> str:
    """The resolved spec of a spectra isolation, a double concave bearing with its effective friction
    ``mu_e`` (Eq 38), ``uy`` and ``gamma`` as well (its spec keeps ``TbTp``, ``mu1``, ``mu2``, ``r``)."""
    label = isolation.label
    if isolation.kind == "dcss":
        f = isolation.foundation(1.0)
        keys = {k for k, _ in isolation.params}
        label += f",mu_e={f.mu_e:.4g}" + ("" if "uy" in keys else f",uy={f.u_y!r}") + \
            ("" if "gamma" in keys else f",gamma={f.gamma!r}")
    return label


def _pulse_words(pulse) -> str:
    """A spectra pulse in words: ``symmetric Ricker pulse`` (``, $T_p$ = 0.6 s`` when its period is set)."""
    from rockcli.report.figures import plain, pulse_text

    text = pulse_text(pulse.shape, None, pulse.T_p)
    return text if pulse.source == "pulse" else f"{text} ({plain(pulse.source)})"


def _search_note(curves) -> str:
    """How the minima of ``curves`` were found, and how many the refinement found (the figure note)."""
    ways = list(dict.fromkeys(c.found_by for c in curves))
    points = sum(c.wp_over_p.size for c in curves)
    refined = sum(int(c.refined.sum()) for c in curves if c.refined is not None)
    note = "minimum: " + "; ".join(ways)
    if any(c.refine > 0 for c in curves):
        note += f"; x: in a window the first scan stepped over ({refined} of {points} points)"
    capped = sorted({c.alpha_deg for c in curves if getattr(c, "capped", False)})
    if capped:
        note += f"; searched up to a_p = 100 g only at alpha = {', '.join(f'{a:g}' for a in capped)} deg"
    return note


def format_min_table(curves, n_rows: int = 12) -> str:
    """The curves at about ``n_rows`` values of omega_p/p, aligned (units of g tan alpha)."""
    import numpy as np

    lines = []
    for (a, sh, cs) in _panels(curves):
        x = cs[0].wp_over_p
        idx = np.unique(np.linspace(0, x.size - 1, min(n_rows, x.size)).round().astype(int))
        head = ["wp/p"] + [c.isolation.label + ("" if c.plinth is None else f" on {c.plinth.name}") for c in cs]
        table = [head, ["uplift"] + [_range(c.ap_uplift) for c in cs]]
        for i in idx:
            table.append([f"{x[i]:.3g}"] + [_num(c.ap_min[i], c.ap_max) for c in cs])
        widths = [max(len(r[j]) for r in table) for j in range(len(head))]
        lines.append(f"alpha = {a:g} deg, {sh}: minimum overturning a_p / (g tan alpha)")
        for r in table:
            lines.append("  ".join(v.rjust(w) for v, w in zip(r, widths)))
        lines.append("")
    return "\n".join(lines).rstrip()


def _range(values) -> str:
    """The uplift thresholds of a curve: one value, or ``lo..hi`` when they vary with omega_p/p
    (sliding bearings); ``-`` when the block never uplifts."""
    import numpy as np

    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v)]
    if not v.size:
        return "-"
    lo, hi = _num(float(v.min())), _num(float(v.max()))
    return lo if lo == hi else f"{lo}..{hi}"


def _num(v, ap_max=None):
    if v is None or (isinstance(v, float) and math.isnan(v)) or (hasattr(v, "__float__") and math.isnan(float(v))):
        return f">{ap_max:g}" if ap_max is not None else "-"
    return f"{float(v):.3f}"


# --------------------------------------------------------------------------------------------------
# Critical size (Table I)
# --------------------------------------------------------------------------------------------------
def write_critical_csv(rows, path, extra: dict | None = None) -> Path:
    """Write the critical sizes (:class:`rockcli.spectra.CriticalRow`) as CSV (:data:`CRITICAL_COLUMNS`;
    ``extra`` appended)."""
    rows = list(rows)
    on = any(getattr(r, "plinth", "") for r in rows)  # --on: the plinth of each row (empty: the body alone)
    return _write_rows(path, CRITICAL_COLUMNS + (("plinth",) if on else ()),
                       ({**r.as_dict(), **({"plinth": r.plinth} if on else {})} for r in rows), extra)


def format_critical_table(rows) -> str:
    """Table I as aligned text: one line per pulse, slenderness and T_b/T_p."""
    head = ["source", "pulse", "T_p [s]", "alpha [deg]", "Tb/Tp", "T_b [s]", "wp/p cross", "R_critical [m]"]
    rows = list(rows)
    on = any(getattr(r, "plinth", "") for r in rows)
    head += ["on"] if on else []
    table = [head]
    for r in rows:
        table.append([r.source, r.pulse, f"{r.T_p_s:.3g}", f"{r.alpha_deg:g}", f"{r.Tb_over_Tp:g}", f"{r.Tb_s:.3g}",
                      "-" if math.isnan(r.wp_over_p_cross) else f"{r.wp_over_p_cross:.3f}",
                      "-" if math.isnan(r.R_critical_m) else f"{r.R_critical_m:.3f}"]
                     + ([r.plinth.partition(":")[0] if r.plinth else "alone"] if on else []))
    widths = [max(len(t[j]) for t in table) for j in range(len(head))]
    out = []
    for k, t in enumerate(table):
        out.append("  ".join(v.ljust(w) if j < 2 else v.rjust(w) for j, (v, w) in enumerate(zip(t, widths))))
        if k == 0:
            out.append("  ".join("-" * w for w in widths))
    return "\n".join(out)
