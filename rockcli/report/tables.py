"""Assessment reports: the Table-III-like matrix (text), the CSV report, per-run histories and figures.

pandas and matplotlib are imported inside the functions; files are written atomically (temporary
file in the target folder, then renamed), so nothing is left half-written.
"""

from __future__ import annotations

import math
import os
from pathlib import Path

from rockcli.errors import RockcliInputError

try:  # shared helper (report/files.py); older trees keep it in report/records.py
    from rockcli.report.files import atomic_path
except ImportError:  # pragma: no cover
    from rockcli.report.records import atomic_path

#: Columns of the CSV report, in order (units in the names; see rockcli.assess.AssessmentRow).
CSV_COLUMNS = ("column", "R_m", "alpha_deg", "height_m", "width_m", "record", "excitation", "source", "pga_g",
               "a_p_g", "T_p_s", "isolation", "configuration", "Tb_s", "xi", "mu", "gamma", "verdict",
               "overturned", "theta_max_over_alpha", "t_overturn_s", "t_uplift_s", "n_impacts",
               "base_disp_max_m", "overturn_scale", "overturn_scale_survives", "margin_note", "error")


# --------------------------------------------------------------------------------------------------
# text matrix
# --------------------------------------------------------------------------------------------------

def format_cell(row, margin: bool) -> str:
    """``survives 0.42 x1.85`` / ``no uplift x2.10`` / ``OVERTURNS x0.62`` / ``ERROR``."""
    if row.error:
        return "ERROR"
    if row.overturned:
        text = "OVERTURNS"
    elif row.verdict == "no_uplift":
        text = "no uplift"
    else:
        text = f"survives {row.theta_max_over_alpha:.2f}"
    if margin:
        if not math.isnan(row.overturn_scale):
            text += f" x{row.overturn_scale:.2f}"
        elif row.margin_note.startswith("no overturning"):
            text += " x>4"
    return text


def format_matrix(assessment) -> str:
    """The assessment as aligned text: per column, records x configurations, then the counts."""
    margin = assessment.margin
    blocks = []
    from rockcli.assess import column_title

    xs = assessment.excitations
    confs = assessment.configurations
    for b in assessment.columns:
        head = ["record"] + [c.header for c in confs]
        table = [head]
        for x in xs:
            label = x.label + (" (pulse)" if x.kind == "pulse" else "")
            table.append([label] + [format_cell(assessment.row(b.name, x.label, c.header), margin) for c in confs])
        counts = ["survives"]
        for c in confs:
            rows = [assessment.row(b.name, x.label, c.header) for x in xs]
            ran = [r for r in rows if not r.error]
            counts.append(f"{sum(not r.overturned for r in ran)} of {len(ran)}")
        widths = [max(len(r[i]) for r in table + [counts]) for i in range(len(head))]
        lines = [column_title(b)]
        for i, r in enumerate(table):
            lines.append("  ".join(cell.ljust(w) for cell, w in zip(r, widths)).rstrip())
            if i == 0:
                lines.append("  ".join("-" * w for w in widths))
        lines.append("  ".join("-" * w for w in widths))
        lines.append("  ".join(cell.ljust(w) for cell, w in zip(counts, widths)).rstrip())
        blocks.append("\n".join(lines))
    return "\n\n".join(blocks)


def format_notes(assessment) -> str:
    """Legend and what was idealised, not available or failed."""
    confs = assessment.configurations
    lines = ["survives r: the column rocks and survives, r = peak |theta|/alpha; no uplift: it never leaves its "
             "base; OVERTURNS: |theta| reaches 90 deg."]
    if assessment.margin:
        lines.append("xS: smallest scale factor of the record that overturns the column in that configuration "
                     "(S < 1: it overturns as recorded, at S times the record; S > 1: survival margin; "
                     "x>4: nothing up to 4x overturns).")
    iso = [c for c in confs if c.label != "none"]
    if iso:
        lines.append("Configurations: " + "; ".join(f"{c.header} = {c.label}" for c in iso)
                     + " (gamma = m/(m+m_b), the mass ratio of column to column + isolated base).")
    if assessment.idealised:
        lines.append("Idealised (record file not found; its catalogued Ricker pulse was run instead): "
                     + ", ".join(assessment.idealised) + ".")
    for u in assessment.unavailable:
        lines.append(f"Not available: {u.label} ({u.reason}).")
    for x in assessment.failed:
        lines.append(f"Could not run {x.label}: {x.error}")
    other = [r for r in assessment.rows if r.error and not any(x.label == r.record for x in assessment.failed)]
    for r in other:
        lines.append(f"Run failed: {r.column} / {r.record} / {r.configuration}: {r.error}")
    return "\n".join(lines)


# --------------------------------------------------------------------------------------------------
# CSV
# --------------------------------------------------------------------------------------------------

def assessment_frame(assessment):
    """The rows as a pandas DataFrame with :data:`CSV_COLUMNS`."""
    import pandas as pd

    data = [{k: getattr(r, k) for k in CSV_COLUMNS} for r in assessment.rows]
    df = pd.DataFrame(data, columns=list(CSV_COLUMNS))
    df["overturned"] = df["overturned"].astype("boolean")
    df["n_impacts"] = df["n_impacts"].astype("Int64")
    return df


def write_assessment_csv(assessment, path: str | os.PathLike) -> Path:
    """Write the CSV report (one row per column x record x configuration), atomically."""
    df = assessment_frame(assessment)
    with atomic_path(path) as tmp:
        df.to_csv(tmp, index=False, float_format="%.6g", lineterminator="\n")
    return Path(path)


def read_assessment_csv(path: str | os.PathLike):
    """Read a CSV report back into a DataFrame (``overturned`` boolean, empty cells NaN)."""
    import pandas as pd

    df = pd.read_csv(path, keep_default_na=True)
    for c in ("margin_note", "error", "verdict", "source"):
        df[c] = df[c].fillna("")
    return df


# --------------------------------------------------------------------------------------------------
# histories and figures (rockcli.report.response when present, else the minimal versions below)
# --------------------------------------------------------------------------------------------------

def history_frame(response):
    """Time history of a response as a DataFrame: t_s, ag_mps2, theta_rad, theta_over_alpha, ..."""
    import pandas as pd

    h = response.history
    if h is None:
        raise RockcliInputError("this run has no time history (simulate it with history=True)")
    return pd.DataFrame({"t_s": h.t, "ag_mps2": h.ag, "theta_rad": h.theta, "theta_dot_radps": h.theta_dot,
                         "u_m": h.u, "u_dot_mps": h.u_dot})


def _write_history_csv(response, path) -> Path:
    df = history_frame(response)
    with atomic_path(path) as tmp:
        df.to_csv(tmp, index=False, float_format="%.9g", lineterminator="\n")
    return Path(path)


def _plot_response(response, block, foundation, excitation_label, path) -> Path:
    """Figure 12 style: ground acceleration, theta/alpha and base displacement against time."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from rockcli.units import G

    h = response.history
    isolated = getattr(foundation, "label", "none") != "none"
    n = 3 if isolated else 2
    fig, axes = plt.subplots(n, 1, sharex=True, figsize=(7, 2.2 * n + 0.6), constrained_layout=True)
    axes[0].plot(h.t, h.ag / G, lw=0.7, color="k")
    axes[0].set_ylabel("ground acc. [g]")
    axes[1].plot(h.t, h.theta / block.alpha, lw=0.9, color="C3")
    axes[1].set_ylabel(r"$\theta/\alpha$")
    for y in (-1, 1):
        axes[1].axhline(y, lw=0.5, ls="--", color="0.5")
    if isolated:
        axes[2].plot(h.t, h.u, lw=0.9, color="C0")
        axes[2].set_ylabel("base disp. u [m]")
    for ax in axes:
        ax.axhline(0.0, lw=0.4, color="0.6")
        ax.grid(True, lw=0.3, alpha=0.5)
    axes[-1].set_xlabel("time [s]")
    axes[0].set_title(f"{block.name} on {getattr(foundation, 'label', 'none')}, {excitation_label}: "
                      f"{response.message}", fontsize=8)
    suffix = Path(path).suffix.lstrip(".") or "png"
    try:
        with atomic_path(path) as tmp:
            fig.savefig(tmp, dpi=110, format=suffix)
    except ValueError as exc:
        raise RockcliInputError(f"{path}: cannot write a figure in this format ({exc})") from None
    finally:
        plt.close(fig)
    return Path(path)


def response_writers():
    """(write_history_csv, plot_response): the solver's report.response versions when present."""
    try:
        from rockcli.report import response as mod
    except ImportError:
        return _write_history_csv, _plot_response
    return (getattr(mod, "write_history_csv", _write_history_csv), getattr(mod, "plot_response", _plot_response))
