"""Fragility reports: the table of fitted medians and dispersions, the CSV, and the figure.

pandas and matplotlib are imported inside the functions; files are written atomically.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

from rockcli.errors import RockcliInputError
from rockcli.io.files import check_output, save_figure, write_text


def _fmt(v, spec=".3g") -> str:
    return "-" if v is None or not math.isfinite(v) else format(v, spec)


def _ci(ci, spec=".3g") -> str:
    lo, hi = ci
    return "-" if not (math.isfinite(lo) and math.isfinite(hi)) else f"{lo:{spec}}-{hi:{spec}}"


def _noun(fr) -> str:
    """The bodies in words: ``the cabinet`` (:func:`rockcli.report.words.body_noun`) when they all take the same one
    (``the column`` for the temple presets), else ``the body``."""
    from rockcli.report.words import body_noun

    nouns = {body_noun(b) for b in fr.columns}
    return nouns.pop() if len(nouns) == 1 else "the body"


def format_fragility(fr) -> str:
    """The fits as aligned text: one row per body x configuration, then the notes."""
    im = fr.im
    pct = f"{100 * fr.level:g}%"
    head = ("body", "configuration", "records", "exact", "censored", f"median [{im.units}]", f"{pct} CI",
            "beta", f"{pct} CI", "median/none", f"{pct} CI")
    table = [head]
    for c in fr.curves:
        table.append((c.column, c.configuration.header, str(c.n_records), str(c.n_exact),
                      str(c.n_right + c.n_left), _fmt(c.median, ".3f"), _ci(c.median_ci, ".3f"), _fmt(c.beta, ".2f"),
                      _ci(c.beta_ci, ".2f"), _fmt(c.ratio_to_rigid, ".2f"), _ci(c.ratio_ci, ".2f")))
    right = set(range(2, len(head)))
    widths = [max(len(r[i]) for r in table) for i in range(len(head))]
    lines = []
    for k, r in enumerate(table):
        lines.append("  ".join(cell.rjust(w) if i in right else cell.ljust(w)
                               for i, (cell, w) in enumerate(zip(r, widths))).rstrip())
        if k == 0:
            lines.append("  ".join("-" * w for w in widths))
    return "\n".join(lines)


def format_fragility_notes(fr) -> str:
    """How the numbers were obtained, the configurations, and what could not be used."""
    im = fr.im
    lo, hi = fr.grid
    noun = _noun(fr)
    lines = [
        f"IM = {im.name} [{im.units}]: {im.description}. Capacity of a record = smallest scale factor that "
        f"overturns {noun} ({lo:g}x..{hi:g}x scan, bisection to 1 %) x the record's {im.name}.",
        f"Fragility P(overturn | {im.name}) = Phi(ln({im.name}/median)/beta), maximum likelihood; a record that "
        f"does not overturn {noun} up to {hi:g}x is right-censored (capacity > {hi:g} x {im.name}), one that "
        f"overturns already at {lo:g}x left-censored.",
        f"{100 * fr.level:g}% intervals: bootstrap over records, {fr.n_boot} resamples (seed {fr.seed}), the same "
        f"resamples for every configuration; median/none: this median over the median on a rigid foundation "
        f"(< 1: isolation makes {noun} more fragile).",
    ]
    iso = [c for c in fr.configurations if c.isolated]
    if iso:
        lines.append("Configurations: " + "; ".join(f"{c.header} = {c.label}" for c in iso) + ".")
    for c in fr.curves:
        if c.note:
            lines.append(f"{c.column} / {c.configuration.header}: {c.note}.")
        elif fr.n_boot and c.n_boot_ok < fr.n_boot:
            lines.append(f"{c.column} / {c.configuration.header}: {fr.n_boot - c.n_boot_ok} resamples had no fit "
                         f"(fewer than two exact capacities) and were left out of the intervals.")
    unproven = [r for r in fr.rows if "not proven" in r.margin_note]
    if unproven:
        lines.append(f"{len(unproven)} capacities include scaled runs still moving at the solver's horizon, counted "
                     "as surviving (the capacity is then an upper estimate; margin_note in the CSV; --horizon "
                     "follows them longer).")
    from rockcli.report.words import unavailable_notes

    lines += unavailable_notes(fr.unavailable)
    failed = fr.failed
    if failed:
        lines.append(f"Not used ({len(failed)} records; error rows in the CSV):")
        lines += [f"  {x.label}: {x.error}" for x in failed]
    other = [r for r in fr.rows if r.error and not any(x.label == r.record for x in failed)]
    for r in other:
        lines.append(f"Run failed: {r.column} / {r.record} / {r.configuration}: {r.error}")
    return "\n".join(lines)


def format_fragility_azimuths(results: dict, n_azimuths: int) -> tuple[str, str]:
    """``assess fragility --azimuth worst`` as text: (the fits over the median and over the worst orientation of
    each pair, with each pair's worst azimuth; the notes)."""
    median, worst = results["median"], results["worst"]
    mark = {"right": ">", "left": "<"}
    lines = [f"Median orientation of each pair (capacities over {n_azimuths} orientations; a pair's IM is the median "
             f"of its projections' IMs, RotD50-like):", format_fragility(median), "",
             "Worst orientation of each pair (its smallest capacity, the rocking analogue of RotD100):",
             format_fragility(worst), "", "Worst azimuth of each pair [deg clockwise from north]:"]
    lines += [f"  {r.column} / {r.record} / {r.configuration}: "
              + (f"{r.azimuth_deg:g} deg" if math.isfinite(r.azimuth_deg) else
                 f"any azimuth {r.margin_note.rpartition('any azimuth ')[2]}")
              + f", capacity {mark.get(r.censored, '')}{r.capacity:.3g} {worst.im.units}"
              for r in worst.rows if not r.error and (math.isfinite(r.azimuth_deg) or "any azimuth (" in r.margin_note)]
    notes = (f"With --azimuth worst a record is a pair of horizontal components: its IM is the median of the IMs of "
             f"its projections onto the {n_azimuths} orientations, and each orientation's capacity is its smallest "
             f"overturning factor x that IM.\n" + format_fragility_notes(worst))
    return "\n".join(lines), notes


def fragility_columns(im) -> tuple:
    """CSV columns for intensity measure ``im`` (the IM and capacity columns carry its unit)."""
    s = im.suffix
    return ("column", "R_m", "alpha_deg", "record", "source", "isolation", "configuration", "im", im.column,
            "overturn_scale", "overturn_scale_survives", f"capacity_{s}", "censored", "margin_note", "error",
            f"median_{s}", f"median_ci_low_{s}", f"median_ci_high_{s}", "beta", "beta_ci_low", "beta_ci_high",
            "median_ratio_to_none", "n_records", "n_censored", "ci_level", "n_boot", "seed")


def fragility_rows(fr) -> list[dict]:
    """One dict per column x record x configuration (the fit of its column and configuration repeated),
    keyed by :func:`fragility_columns`."""
    im = fr.im
    s = im.suffix
    fits = {(c.column, c.configuration.header): c for c in fr.curves}
    data = []
    for r in fr.rows:
        c = fits.get((r.column, r.configuration))
        data.append({
            "column": r.column, "R_m": r.R_m, "alpha_deg": r.alpha_deg, "record": r.record, "source": r.source,
            "isolation": r.isolation, "configuration": r.configuration, "im": im.key, im.column: r.im_value,
            "overturn_scale": r.overturn_scale, "overturn_scale_survives": r.overturn_scale_survives,
            f"capacity_{s}": r.capacity, "censored": r.censored, "margin_note": r.margin_note, "error": r.error,
            f"median_{s}": c.median, f"median_ci_low_{s}": c.median_ci[0], f"median_ci_high_{s}": c.median_ci[1],
            "beta": c.beta, "beta_ci_low": c.beta_ci[0], "beta_ci_high": c.beta_ci[1],
            "median_ratio_to_none": c.ratio_to_rigid, "n_records": c.n_records, "n_censored": c.n_right + c.n_left,
            "ci_level": fr.level, "n_boot": fr.n_boot, "seed": fr.seed,
        })
    return data


def fragility_frame(fr):
    """:func:`fragility_rows` as a pandas DataFrame."""
    import pandas as pd

    return pd.DataFrame(fragility_rows(fr), columns=list(fragility_columns(fr.im)))


def write_fragility_csv(fr, path: str | os.PathLike, extra: dict | None = None) -> Path:
    """Write the fragility CSV (see :func:`fragility_columns`; ``extra``: constant columns appended), atomically.

    ``fr`` may be a list of results (``--azimuth worst``: the median and the worst orientation): their rows
    one after the other, with the columns ``orientation`` and ``azimuth_deg`` after ``configuration``."""
    from rockcli.report.spectra import constant_columns

    if isinstance(fr, (list, tuple)):
        import pandas as pd

        df = pd.concat([fragility_table(one) for one in fr], ignore_index=True)
    else:
        df = fragility_table(fr)
    return write_text(path, constant_columns(df.to_csv(index=False, float_format="%.6g", lineterminator="\n"), extra))


def fragility_table(fr):
    """The CSV's rows of one result as a pandas DataFrame (:func:`fragility_frame`, the ``vertical`` column when
    a record ran under one, and ``orientation``, ``azimuth_deg`` after ``configuration`` for a result of
    ``--azimuth worst``; :meth:`rockcli.assess.Fragility.to_dataframe`)."""
    from rockcli.report.tables import _vertical_column

    df = fragility_frame(fr)
    _vertical_column(df, fr)
    if any(r.orientation for r in fr.rows):
        at = df.columns.get_loc("configuration") + 1
        df.insert(at, "orientation", [r.orientation for r in fr.rows])
        df.insert(at + 1, "azimuth_deg", [r.azimuth_deg for r in fr.rows])
    return df


def plot_fragility(fr, path: str | os.PathLike, *, dpi: int = 90) -> Path:
    """One panel per column: the fitted curve of every configuration with its bootstrap band and the records.

    Filled markers: the records' capacities at their Kaplan-Meier plotting positions; open
    triangles: censored records at their bound (their capacity lies beyond it).
    """
    import numpy as np

    from rockcli.report.figures import block_text, footnote, new_figure, pyplot, split_labels, title

    path = check_output(path, image=True)
    im = fr.im
    # the axis spans the exact capacities and the fitted curves from 1 % to 99 %; censored records
    # outside it (weak records censored at a tiny IM say little) are not drawn
    vals = [r.capacity for r in fr.rows if not r.error and not r.censored and math.isfinite(r.capacity)]
    for c in fr.curves:
        if math.isfinite(c.median):
            vals += [c.median * math.exp(-2.33 * c.beta), c.median * math.exp(2.33 * c.beta)]
    vals = [v for v in vals if v > 0]
    if not vals:
        raise RockcliInputError("nothing to plot: no record has an exact capacity")
    x = np.geomspace(min(vals) / 1.2, max(vals) * 1.2, 300)
    ncol = len(fr.columns)
    plt = pyplot()
    fig = new_figure(5.4 * ncol + 0.6, 5.0 + 0.25 * len(fr.configurations))
    axes = fig.subplots(1, ncol, squeeze=False, sharey=True)
    legend, common = split_labels(c.foundation.label for c in fr.configurations)
    colors = ["k"] + [plt.cm.viridis(v) for v in np.linspace(0.15, 0.85, max(1, len(fr.configurations) - 1))]
    try:
        for ax, b in zip(axes[0], fr.columns):
            k_iso = 0
            for c in fr.configurations:
                curve = fr.curve(b.name, c.header)
                if c.isolated:
                    k_iso += 1
                color = colors[k_iso] if c.isolated else "k"
                style = "-" if c.isolated else "--"
                ex, ce = fr.plotting_points(b.name, c.header)
                ce = [(v, p) for v, p in ce if x[0] <= v <= x[-1]]
                if math.isfinite(curve.median):
                    label = (f"{legend[c.foundation.label]}: median {curve.median:.3g} {im.units}, $\\beta$ = {curve.beta:.2f}")
                    ax.plot(x, curve.probability(x), style, color=color, lw=1.8, label=label)
                    if curve.boot_median is not None and curve.n_boot_ok >= 2:
                        P = curve.boot_probabilities(x)
                        q = (100 * (1 - fr.level) / 2, 100 * (1 + fr.level) / 2)
                        lo, hi = np.percentile(P, q, axis=0)
                        ax.fill_between(x, lo, hi, color=color, alpha=0.12, lw=0)
                else:
                    ax.plot([], [], style, color=color, label=f"{legend[c.foundation.label]}: no fit")
                if ex:
                    ax.plot(*zip(*ex), "o", ms=4, color=color, alpha=0.85)
                if ce:
                    ax.plot(*zip(*ce), ">", ms=5, mfc="none", color=color, alpha=0.85)
            ax.set_xscale("log")
            ax.set_xlim(x[0], x[-1])
            ax.set_ylim(-0.02, 1.02)
            ax.grid(True, which="both", color="0.9", lw=0.5)
            ax.set_xlabel(f"{im.name} [{im.units}]")
            title(ax, block_text(b), fontsize=10, loc="left")
            ax.legend(loc="upper left", fontsize=7, frameon=False)
        axes[0, 0].set_ylabel("P(overturn)")
        if common:
            title(fig, f"isolated configurations: {common}", fontsize=9)
        footnote(fig, f"lines: lognormal MLE; bands: {100 * fr.level:g} % bootstrap ({fr.n_boot} resamples); "
                      f"dots: records (Kaplan-Meier positions); open triangles: no overturning up to {fr.grid[1]:g}x "
                      f"(drawn where inside the axis)")
        save_figure(fig, path, dpi=dpi)
    finally:
        plt.close(fig)
    return path

