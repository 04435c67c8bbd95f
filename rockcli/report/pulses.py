"""Pulse-fit reports: the table of fitted pulses (CSV) and the Figure-3-like overlay plot.

matplotlib is imported inside the functions (Agg backend). Nothing is written half-way: outputs go
to a temporary file in the target folder and are renamed into place.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path

from rockcli.io.files import check_output, save_figure, write_text
from rockcli.io.units import G

#: Columns of ``rockcli fit-pulse --csv``.
FIT_COLUMNS = ("record", "wavelet", "pulse_shape", "a_p_g", "T_p_s", "t0_s", "energy_fraction",
               "at_period_bound", "period_min_s", "period_max_s")


def fit_rows(fits) -> list[dict]:
    """One dict per fit, keyed by :data:`FIT_COLUMNS` (SI/g values as floats)."""
    rows = []
    for f in fits:
        row = f.as_row()
        row["period_min_s"], row["period_max_s"] = f.periods
        rows.append({c: row[c] for c in FIT_COLUMNS})
    return rows


def write_fit_csv(fits, path) -> Path:
    """Write the fitted pulses as CSV (columns :data:`FIT_COLUMNS`), atomically."""
    fh = io.StringIO()
    writer = csv.DictWriter(fh, fieldnames=FIT_COLUMNS, lineterminator="\n")
    writer.writeheader()
    for row in fit_rows(fits):
        writer.writerow({k: (repr(float(v)) if isinstance(v, float) else v) for k, v in row.items()})
    return write_text(path, fh.getvalue())


#: Columns of ``rockcli fit-pulse --candidates N --csv``: one row per candidate pulse.
CANDIDATE_COLUMNS = ("record", "rank", "fit", "wavelet", "pulse_shape", "a_p_g", "T_p_s", "t0_s", "energy_fraction",
                     "at_period_bound", "period_min_s", "period_max_s")


def write_candidates_csv(fits, candidates, path) -> Path:
    """Write the candidate pulses of each record (columns :data:`CANDIDATE_COLUMNS`), atomically.

    ``fit`` is True on the candidate that is the record's fit; ``rank`` orders by explained energy.
    """
    fh = io.StringIO()
    writer = csv.DictWriter(fh, fieldnames=CANDIDATE_COLUMNS, lineterminator="\n")
    writer.writeheader()
    for f, cands in zip(fits, candidates):
        for rank, c in enumerate(cands, 1):
            row = c.as_row()
            row["rank"], row["fit"] = rank, c.pulse == f.pulse
            row["period_min_s"], row["period_max_s"] = c.periods
            writer.writerow({k: (repr(float(row[k])) if isinstance(row[k], float) else row[k])
                             for k in CANDIDATE_COLUMNS})
    return write_text(path, fh.getvalue())


def plot_pulse_fits(records, fits, path, *, candidates=None, dpi: int = 120) -> Path:
    """Overlay each fitted pulse on its record, one panel per record (like Figure 3 of the paper).

    Parameters
    ----------
    records : sequence of Record
        The records [m/s^2].
    fits : sequence of PulseFit
        Their fits, in the same order.
    candidates : sequence of list of PulseFit, optional
        Competing pulses of each record (:func:`rockcli.pulses_fit.fit_pulse_candidates`), drawn
        dashed in colour over the record with the fit.
    path : path-like
        Image file; the format follows the suffix (``.png``, ``.pdf``, ``.svg``).
    """
    import numpy as np

    from rockcli.report.figures import SHAPE_WORDS, new_figure, plain, pyplot, title

    path = check_output(path, image=True)
    plt = pyplot()
    n = len(fits)
    fig = new_figure(8.0, 2.5 * n + 0.4)
    axes = fig.subplots(n, 1, squeeze=False)
    colors = ("tab:red", "tab:blue", "tab:green", "tab:orange", "tab:purple", "tab:brown", "tab:pink", "tab:olive")
    try:
        for k, (ax, rec, fit) in enumerate(zip(axes[:, 0], records, fits)):
            t = rec.times
            ax.plot(t, rec.acc / G, color="0.55", lw=0.6, label=f"record (PGA = {rec.pga_g:.3g} g)")
            s0, s1 = fit.pulse.support()
            tp = np.linspace(max(s0, t[0]), min(s1, t[-1]), 1500)
            ax.plot(tp, fit.pulse.acceleration(tp) / G, color="k", lw=2.2,
                    label=f"fitted {SHAPE_WORDS.get(fit.shape, fit.shape)} pulse")
            others = [c for c in (candidates[k] if candidates else []) if c.pulse != fit.pulse]
            for j, c in enumerate(others):
                c0, c1 = c.pulse.support()
                tc = np.linspace(max(c0, t[0]), min(c1, t[-1]), 1500)
                ax.plot(tc, c.pulse.acceleration(tc) / G, "--", color=colors[j % len(colors)], lw=1.6,
                        label=f"{SHAPE_WORDS.get(c.shape, c.shape)}: $T_p$ = {c.T_p_s:.2f} s, "
                              f"$a_p$ = {c.a_p_g:+.2f} g, energy fraction {c.energy_fraction:.2f}")
            ax.axhline(0.0, color="0.8", lw=0.5)
            ax.set_ylabel(r"$\ddot u_g$ [g]")
            title(ax, f"{plain(fit.record_name)}: {SHAPE_WORDS.get(fit.shape, fit.shape)} pulse, "
                      f"$a_p$ = {fit.a_p_g:+.3f} g, $T_p$ = {fit.T_p_s:.3f} s, $t_0$ = {fit.t0_s:.2f} s, "
                      f"energy fraction {fit.energy_fraction:.2f}", fontsize=9, loc="left")
            ax.legend(loc="upper right", fontsize=7, frameon=False)
            ax.set_xlim(t[0], t[-1])
        axes[-1, 0].set_xlabel("time $t$ [s]")
        save_figure(fig, path, dpi=dpi)
    finally:
        plt.close(fig)
    return path
