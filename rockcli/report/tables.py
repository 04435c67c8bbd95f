"""Assessment reports: the Table-III-like matrix (text) and the CSV report.

Per-run histories and figures come from :mod:`rockcli.report.response`.

pandas and matplotlib are imported inside the functions; files are written atomically (temporary
file in the target folder, then renamed), so nothing is left half-written.
"""

from __future__ import annotations

import math
import os
from pathlib import Path


from rockcli.io.files import write_text

#: Columns of the CSV report, in order (units in the names; see rockcli.assess.AssessmentRow).
CSV_COLUMNS = ("column", "R_m", "alpha_deg", "height_m", "width_m", "record", "excitation", "source", "pga_g",
               "a_p_g", "T_p_s", "isolation", "configuration", "Tb_s", "xi", "mu", "gamma", "verdict",
               "overturned", "proven", "theta_max_over_alpha", "t_overturn_s", "t_uplift_s", "n_impacts",
               "base_disp_max_m", "overturn_scale", "overturn_scale_survives", "margin_note", "overturn_share_pm10",
               "error")


# --------------------------------------------------------------------------------------------------
# text matrix
# --------------------------------------------------------------------------------------------------

def peak_text(r: float) -> str:
    """A peak over an overturning angle in a cell: ``0.42``; ``<0.01`` for a lift that would print as 0.00 (it lifts,
    by less than 1 %); ``0`` for a block that never lifts (a body on a still plinth)."""
    if r == 0:
        return "0"
    return "<0.01" if 0 < r < 0.005 else f"{r:.2f}"


def format_cell(row, margin: bool, neighbourhood: bool = False) -> str:
    """``survives 0.42 x1.85`` / ``survives <0.01 p0.37 x1.20`` / ``no uplift x2.10`` / ``OVERTURNS x0.62 [43%]`` /
    ``ERROR``."""
    if row.error:
        return "ERROR"
    if row.overturned and getattr(row, "verdict", "") == "slid_off":
        text = "SLIDES OFF"
    elif row.overturned:
        text = "OVERTURNS" + (f" {row.toppled}" if row.toppled else "")
    elif row.proven is False:
        text = f"NOT PROVEN {row.theta_max_over_alpha:.2f}"
    elif row.verdict == "no_uplift":
        text = "no uplift"
    else:
        text = f"survives {peak_text(row.theta_max_over_alpha)}"
        if row.plinth:  # a body on a plinth: the plinth's peak over alpha_asm too
            text += f" p{peak_text(row.plinth_theta_max_over_alpha_asm)}"
    slide = getattr(row, "slide_max_m", 0.0)
    if not row.overturned and getattr(row, "friction", "") and slide > 0:  # it slid: how far, in cm
        text += " s<0.1cm" if slide < 5e-4 else f" s{100 * slide:.1f}cm"
    if margin:
        if not math.isnan(row.overturn_scale):
            text += f" x{row.overturn_scale:.2f}"
        elif row.margin_note.startswith("no overturning"):
            text += " x>4"
    if row.azimuths_run:  # --azimuth worst: the most adverse orientation (any: none is more adverse)
        text += " @any" if math.isnan(row.azimuth_deg) else f" @{row.azimuth_deg:g}"
    if neighbourhood and not math.isnan(row.overturn_share_pm10):
        text += f" [{100 * row.overturn_share_pm10:.0f}%]"
    return text


def format_matrix(assessment) -> str:
    """The assessment as aligned text: per column, records x configurations, then the counts."""
    margin = assessment.margin
    blocks = []
    from rockcli.report.words import column_title

    xs = assessment.excitations
    confs = assessment.configurations
    from rockcli.report.drum_words import drum_table, is_drums

    beside = {r.column for r in assessment.rows if r.drum_column and r.column != r.drum_column}  # the monoliths
    for b in assessment.columns:
        if is_drums(b):  # a column of drums: beside its monolith, in one table
            blocks.append(drum_table(assessment, b))
            continue
        if b.name in beside:
            continue
        head = ["record"] + [c.header for c in confs]
        table = [head]
        for x in xs:
            label = x.label + (" (pulse)" if x.kind == "pulse" else "")
            table.append([label] + [format_cell(assessment.row(b.name, x.label, c.header), margin, assessment.neighbourhood) for c in confs])
        n_pulses = sum(x.kind == "pulse" for x in xs)  # a pulse in place of a record: said on the count too
        counts = ["survives" + (f" ({n_pulses} of {len(xs)} are pulses)" if n_pulses else "")]
        for c in confs:
            rows = [assessment.row(b.name, x.label, c.header) for x in xs]
            ran = [r for r in rows if not r.error]
            unproven = sum(r.proven is False for r in ran)
            counts.append(f"{sum(not r.overturned and r.proven is not False for r in ran)} of {len(ran)}"
                          + (f" ({unproven} not proven)" if unproven else ""))
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
    lines = ["survives r: the body rocks and survives, r = peak |theta|/alpha; no uplift: it never leaves its "
             "base; OVERTURNS: |theta| reaches 90 deg."]
    shown = {peak_text(v) for r in assessment.rows if not r.error and not r.overturned and r.verdict != "no_uplift"
             for v in (r.theta_max_over_alpha, getattr(r, "plinth_theta_max_over_alpha_asm", math.nan))}
    tiny = [w for t, w in (("<0.01", "<0.01: it lifts, by less than 1 % of its overturning angle"),
                           ("0", "0: it does not lift (a body on a plinth that rocks)")) if t in shown]
    if tiny:
        lines[0] += " " + "; ".join(tiny) + "."
    frictions = sorted({r.friction for r in assessment.rows if getattr(r, "friction", "")})
    if frictions:
        lines.append(f"Friction as a model ({', '.join(frictions)}; docs/physics-sliding.md): sX: the body slid X at "
                     "most on its own contact (the floor, or its plinth); SLIDES OFF: its base reached the plinth's "
                     "edge (a fall); a run where nothing slides is the rocking model's.")
    from rockcli.report.drum_words import drum_notes

    lines += drum_notes(assessment)
    if assessment.unproven:
        from rockcli.solve import DEFAULT_HORIZON

        horizon = assessment.solver.get("horizon", DEFAULT_HORIZON)
        lines.append(f"NOT PROVEN r: still moving {horizon:g} s after the record ended (the solver's horizon), "
                     "peak so far r; it had not overturned, but its survival is not proven and it is not counted "
                     "as surviving (very slender blocks on sliding bearings, see the README); --horizon "
                     "(up to 3600 s) follows it longer.")
    if assessment.solver.get("restitution") is not None:
        lines.append(f"Impacts: coefficient of restitution E = {assessment.solver['restitution']:g} (on the ground "
                     "theta_dot+ = E theta_dot-; on isolators lowered by the base, docs/simulate.md, Restitution), not "
                     "Housner's 1 - 1.5 sin^2 alpha.")
    if assessment.solver.get("cap_ratio"):
        lines.append(f"Capped colonnades: each column stands in a colonnade carrying a beam of gamma_c = "
                     f"{assessment.solver['cap_ratio']:g} times the columns' mass; on isolators gamma is the mass of "
                     f"columns and beam over the whole moving mass (docs/physics-colonnade.md).")
    if assessment.margin:
        lines.append("xS: the smallest scale factor of the record that overturns the body (S > 1: the margin; S < 1 on "
                     "a survivor: a weaker record overturns it, a safe island; x>4: none up to 4x), 0.1x..4x in "
                     "1 % steps.")
    worst = [r for r in assessment.rows if r.azimuths_run and not r.error]
    if worst:
        rank = ("the smallest margin xS, then the earliest overturn at 1x, then the largest peak |theta|/alpha"
                if assessment.margin else "the earliest overturn, then the largest peak |theta|/alpha")
        lines.append(f"@A: the most adverse orientation of the two horizontal components, of the "
                     f"{worst[0].azimuths_run} orientations run (0-179 deg; A = azimuth of the normal to the rocking "
                     f"axis, clockwise from north): {rank}.")
        tied = [r for r in worst if math.isnan(r.azimuth_deg)]
        if tied:
            calm = all(r.verdict == "no_uplift" and (not assessment.margin or math.isnan(r.overturn_scale))
                       for r in tied)
            lines.append("@any: no orientation is more adverse than another: "
                         + (("none lifts the body off at 1x" + (" and none overturns it up to 4x" if assessment.margin
                                                                 else "")) if calm
                            else "they all rank the same by these") + ".")
        over = [r for r in worst if r.overturning_azimuths not in ("", "none")]
        for r in over:
            lines.append(f"Overturning orientations: {r.column} / {r.record} / {r.configuration}: "
                         f"{r.overturning_azimuths.replace(' ', ', ')} deg.")
    reasons = {}
    for x in assessment.excitations:
        if getattr(x, "as_recorded", ""):
            reasons.setdefault(x.as_recorded, []).append(x.label)
    if reasons:  # --azimuth worst: a catalogue record without its second horizontal component (rockcli.assess.pairs)
        lines.append("Run as recorded, in one orientation (no pair to turn): "
                     + "; ".join(f"{', '.join(labels)} ({why})" for why, labels in reasons.items()) + ".")
    if assessment.neighbourhood:
        lines.append("[P%]: share of the scale factors 0.90x, 0.91x, ..., 1.10x of the record that overturn "
                     "(0% or 100%: a robust verdict; in between: the verdict flips within +-10% of the record).")
    iso = [c for c in confs if c.label != "none"]
    if iso:
        lines.append("Configurations: " + "; ".join(f"{c.header} = {c.label}" for c in iso)
                     + " (gamma = m/(m+m_b), the mass ratio of body to body + isolated base).")
    if assessment.idealised:
        lines.append("Idealised (record file not found; its catalogued Ricker pulse was run instead): "
                     + ", ".join(assessment.idealised) + ". A single pulse lacks the record's other cycles: "
                     "with the paper's records it misses many overturns, above all on isolators (see README).")
    from rockcli.report.words import unavailable_notes

    lines += unavailable_notes(assessment.unavailable)
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


#: Columns added by ``--check-tolerance`` (:func:`rockcli.assess.table.check_tolerance`), empty on rows
#: that were not rerun (errors, unavailable motions).
#: Columns of an assessment with ``--azimuth`` (after :data:`CSV_COLUMNS`).
AZIMUTH_COLUMNS = ("azimuth_deg", "overturning_azimuths", "azimuths_run", "base_disp_max_surviving_azimuths_m")
#: Columns of an assessment with ``--on`` (a body on a plinth; empty on the rows of a body alone).
PLINTH_COLUMNS = ("plinth", "toppled", "plinth_theta_max_over_alpha_asm", "friction_demand_base",
                  "friction_demand_joint")
#: Columns of an assessment with ``--friction`` (friction as a model): the coefficients, and how far the body's own
#: contact (on the floor, or on its plinth) and the plinth's slid (0 where nothing slid: the rocking answer).
FRICTION_COLUMNS = ("friction", "slide_max_m", "slide_residual_m", "plinth_slide_max_m", "plinth_slide_residual_m")
#: Columns of an assessment with columns of drums (empty on the rows of other bodies; docs/physics-drums.md).
DRUM_COLUMNS = ("drum_column", "drums", "falls_at", "first_move", "first_move_t_s", "first_joint_open",
                "first_joint_open_t_s", "joint_open_max_over_alpha",
                "joint_open_max_at", "joint_slide_max_m", "joint_slide_max_at", "peak_openings_over_alpha",
                "residual_offsets_m", "residual_offset_max_m", "drums_vs_monolith", "monolith_verdict",
                "monolith_overturn_scale", "n_inconsistent", "n_jumps", "reliable")
CHECK_COLUMNS = ("tight_rtol_verdict", "tight_rtol_peak_change", "ulp_verdicts", "ulp_peak_change", "ill_conditioned")


def extra_columns(assessment, check=None) -> dict:
    """The columns after :data:`CSV_COLUMNS`, one list per name: the orientation (``--azimuth``), the
    given physics options (``restitution``, ``cap_ratio``; nothing for the defaults) and, with ``check``
    (a :class:`rockcli.assess.table.ToleranceCheck`), the :data:`CHECK_COLUMNS`."""
    rows = assessment.rows
    cols = {}
    if any(not math.isnan(r.azimuth_deg) or r.azimuths_run for r in rows):  # --azimuth: the columns of orientation
        for key in AZIMUTH_COLUMNS:
            cols[key] = [getattr(r, key) for r in rows]
    if any(r.plinth for r in rows):  # --on: each block's answer and the friction demands
        for key in PLINTH_COLUMNS:
            cols[key] = [getattr(r, key) for r in rows]
    if any(r.friction for r in rows):  # --friction: how far each contact slid
        for key in FRICTION_COLUMNS:
            cols[key] = [getattr(r, key) for r in rows]
    if any(r.drum_column for r in rows):  # columns of drums beside their monoliths
        for key in DRUM_COLUMNS:
            cols[key] = [getattr(r, key) for r in rows]
    for key in ("restitution", "cap_ratio"):
        if assessment.solver.get(key):
            cols[key] = [assessment.solver[key]] * len(rows)
    _vertical_column(cols, assessment)
    if check is not None:
        from rockcli.conditioning import ill_conditioned

        by_row = {id(row): rest for row, *rest in check.per_row}
        cols.update({c: [] for c in CHECK_COLUMNS})
        for row in rows:
            got = by_row.get(id(row))
            if got is None:
                for c in CHECK_COLUMNS:
                    cols[c].append(None)
                continue
            tight_verdict, tight_moved, ulp_verdicts, ulp_moved = got
            cols["tight_rtol_verdict"].append(tight_verdict)
            cols["tight_rtol_peak_change"].append(tight_moved)
            cols["ulp_verdicts"].append(" ".join(ulp_verdicts))
            cols["ulp_peak_change"].append(ulp_moved)
            cols["ill_conditioned"].append(ill_conditioned(row.verdict, ulp_moved, ulp_verdicts))
    return cols


def assessment_rows(assessment, check=None) -> list[dict]:
    """One dict per column x record x configuration: :data:`CSV_COLUMNS` and :func:`extra_columns` (the
    ``--json`` of ``assess column``)."""
    extra = extra_columns(assessment, check)
    return [{**{k: getattr(r, k) for k in CSV_COLUMNS}, **{k: v[i] for k, v in extra.items()}}
            for i, r in enumerate(assessment.rows)]


def assessment_table(assessment, check=None):
    """The CSV report as a pandas DataFrame (one row per column x record x configuration): :data:`CSV_COLUMNS`
    and :func:`extra_columns` (:meth:`rockcli.assess.Assessment.to_dataframe`)."""
    df = assessment_frame(assessment)
    for key, values in extra_columns(assessment, check).items():
        df[key] = values
    if check is not None:
        df["ill_conditioned"] = df["ill_conditioned"].astype("boolean")
    if "drums" in df:  # columns of drums: counts with gaps (the other bodies' rows), a flag with gaps
        for key in ("drums", "n_inconsistent", "n_jumps"):
            df[key] = df[key].astype("Int64")
        df["reliable"] = df["reliable"].astype("boolean")
    return df


def write_assessment_csv(assessment, path: str | os.PathLike, check=None) -> Path:
    """Write the CSV report (:func:`assessment_table`), atomically: the text pandas would write, made without
    pandas where :func:`rockcli.report.csv_text.csv_text` knows every column's values, else by pandas."""
    from rockcli.report.csv_text import BOOLEAN, INT64, csv_text

    columns = {k: [getattr(r, k) for r in assessment.rows] for k in CSV_COLUMNS}
    columns.update(extra_columns(assessment, check))
    text = csv_text(columns, {"overturned": BOOLEAN, "n_impacts": INT64, "ill_conditioned": BOOLEAN,
                              "drums": INT64, "n_inconsistent": INT64, "n_jumps": INT64, "reliable": BOOLEAN})
    if text is None:
        text = assessment_table(assessment, check).to_csv(index=False, float_format="%.6g", lineterminator="\n")
    return write_text(path, text)


def vertical_labels(excitations) -> dict:
    """``{record label: its vertical motion}`` of the excitations that carry one (empty: none does)."""
    from rockcli.solve import vertical_label

    return {x.label: vertical_label(x.motion) for x in excitations if vertical_label(x.motion)}


def _vertical_column(cols: dict, result) -> None:
    """``vertical``: the vertical motion each row's record ran under (only when one did)."""
    labels = vertical_labels(result.excitations)
    if labels:
        cols["vertical"] = [labels.get(r.record, "none") for r in result.rows]


def read_assessment_csv(path: str | os.PathLike):
    """Read a CSV report back into a DataFrame (``overturned`` boolean, empty cells NaN)."""
    import pandas as pd

    text = ("margin_note", "error", "verdict", "source")
    df = pd.read_csv(path, dtype={c: object for c in text})
    for c in text:
        df[c] = df[c].fillna("")
    return df
