"""Reports of ``rockcli bench``: aligned text, CSV and the work-precision figure.

matplotlib is imported inside :func:`plot_work_precision` (Agg backend); every file is written
atomically (a temporary file in the target folder, then renamed).
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

from rockcli.bench import NOISE_DRAWS
from rockcli.errors import RockcliInputError
from rockcli.io.files import atomic_path, save_figure

#: Columns of ``rockcli bench work-precision --csv``: one row per run (scene-level values repeated).
WP_COLUMNS = ("scene", "method", "rtol", "verdict", "verdict_ok", "theta_max_over_alpha", "err_theta_max_over_alpha",
              "event", "t_event_s", "err_t_event_s", "steps", "nfev", "wall_s", "calls", "note", "ref_verdict",
              "ref_theta_max_over_alpha", "ref_t_event_s", "check_method", "check_rtol", "check_d_theta_max_over_alpha",
              "check_d_t_event_s", "noise_theta_max_over_alpha", "noise_t_event_s", "kernel_order", "kernel_tol_slope")
#: Columns of ``rockcli bench stability --csv``: one row per scene.
STAB_COLUMNS = ("scene", "title", "status", "reason", "verdict_rtol_1e-6", "verdict_rtol_1e-10",
                "theta_max_over_alpha_rtol_1e-6", "theta_max_over_alpha_rtol_1e-10", "t_overturn_s_rtol_1e-6",
                "t_overturn_s_rtol_1e-10", "settled", "steps_rtol_1e-6", "steps_rtol_1e-10", "rejected_rtol_1e-10",
                "impacts_rtol_1e-10", "rests_rtol_1e-10", "wall_s_rtol_1e-6", "wall_s_rtol_1e-10", "wall_budget_s",
                "step_budget", "ulp_spread", "ulp_verdicts", "ill_conditioned", "checks")

METHOD_STYLE = {  # colour, marker
    "rockcli": ("k", "o"), "rockcli-verdict": ("0.55", "s"), "RK45": ("tab:blue", "^"), "DOP853": ("tab:orange", "v"),
    "Radau": ("tab:green", "D"), "LSODA": ("tab:red", "P"), "BDF": ("tab:purple", "X"),
    "RK45-free": ("tab:cyan", "<"),
}


def _fmt(v):
    import numpy as np

    if v is None:
        return ""
    if isinstance(v, (bool, np.bool_)):
        return str(bool(v))  # True/False, as every rockcli CSV writes booleans
    if isinstance(v, (float, np.floating)):
        return "" if math.isnan(v) else repr(float(v))
    if isinstance(v, np.integer):
        return str(int(v))
    return v


def _write(path, columns, rows) -> Path:
    with atomic_path(path) as tmp:
        with open(tmp, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh, lineterminator="\n")
            w.writerow(columns)
            for row in rows:
                w.writerow([_fmt(row.get(c)) for c in columns])
    return Path(path)


def aligned(header, rows, right=()) -> str:
    """Rows of strings as aligned text (columns named in ``right`` right-aligned)."""
    table = [list(header)] + [[str(c) for c in r] for r in rows]
    widths = [max(len(r[i]) for r in table) for i in range(len(header))]
    lines = []
    for r in table:
        cells = [r[i].rjust(widths[i]) if header[i] in right else r[i].ljust(widths[i]) for i in range(len(header))]
        lines.append("  ".join(cells).rstrip())
    return "\n".join(lines)


def _e(x, digits=1):
    return "" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{digits}e}"


# --------------------------------------------------------------------------------------------------
# work-precision
# --------------------------------------------------------------------------------------------------
def wp_rows(scenes) -> list:
    """One dict per run (and one per scene that could not run), keyed by :data:`WP_COLUMNS`."""
    out = []
    for ws in scenes:
        common = dict(scene=ws.scene.name, ref_verdict=ws.ref_verdict, ref_theta_max_over_alpha=ws.ref_theta_max_over_alpha,
                      ref_t_event_s=ws.ref_t_event_s, check_method=ws.check_method, check_rtol=ws.check_rtol,
                      check_d_theta_max_over_alpha=ws.check_d_theta, check_d_t_event_s=ws.check_d_t_event_s,
                      noise_theta_max_over_alpha=ws.noise_theta, noise_t_event_s=ws.noise_t_event_s,
                      kernel_order=ws.order, kernel_tol_slope=ws.tol_slope)
        if not ws.available:
            out.append(dict(common, note=ws.note))
            continue
        for r in ws.runs:
            out.append(dict(common, method=r.method, rtol=r.rtol, verdict=r.verdict, verdict_ok=r.verdict_ok,
                            theta_max_over_alpha=r.theta_max_over_alpha,
                            err_theta_max_over_alpha=r.err_theta_max_over_alpha, event=r.event, t_event_s=r.t_event_s,
                            err_t_event_s=r.err_t_event_s, steps=r.steps, nfev=r.nfev, wall_s=r.wall_s,
                            calls=r.calls, note=r.note))
    return out


def write_work_precision_csv(scenes, path) -> Path:
    return _write(path, WP_COLUMNS, wp_rows(scenes))


def format_work_precision(scenes) -> str:
    """Per scene: the reference and its check, then one aligned row per run."""
    blocks = []
    for ws in scenes:
        head = f"{ws.scene.name}: {ws.scene.title}"
        if not ws.available:
            blocks.append(f"{head}\n  {ws.note}")
            continue
        ev = "t_overturn" if ws.event == "overturn" else "t_rest"
        ref = (f"  reference: rockcli at rtol 1e-13: {ws.ref_verdict}, theta_max/alpha = {ws.ref_theta_max_over_alpha:.10f}, "
               f"{ev} = {ws.ref_t_event_s:.6f} s")
        if ws.check_method:
            ref += (f"\n  check: {ws.check_method} at rtol {ws.check_rtol:g} differs by {_e(ws.check_d_theta)} in "
                    f"theta_max/alpha and {_e(ws.check_d_t_event_s)} s in {ev}")
        if math.isfinite(ws.noise_theta):
            ref += (f"\n  noise: with the input moved by one ulp ({NOISE_DRAWS} draws) the reference moves by up to "
                    f"{_e(ws.noise_theta)} in theta_max/alpha and {_e(ws.noise_t_event_s)} s in {ev}")
        if not math.isnan(ws.order):
            ref += (f"\n  rockcli (verdict-only runs): error ~ RHS^-{ws.order:.1f} (observed order), "
                    f"error ~ rtol^{ws.tol_slope:.2f}")
        else:
            ref += ("\n  rockcli's error does not follow rtol here: its steps are capped by the record's sample "
                    "interval (half of it on a rigid foundation), and steps that long already meet the tolerance")
        if ws.note:
            ref += f"\n  note: {ws.note}"
        rows = []
        for r in ws.runs:
            mark = "" if r.verdict_ok in (None, True) or r.note else " WRONG"
            verdict = (r.verdict + mark) if not r.note else ("over budget" if "budget" in r.note else "failed")
            rows.append([r.method, f"{r.rtol:.0e}", verdict,
                         _e(r.err_theta_max_over_alpha), _e(r.err_t_event_s), "" if r.steps is None else str(r.steps),
                         "" if r.nfev is None else str(r.nfev),
                         "" if math.isnan(r.wall_s) else f"{1e3 * r.wall_s:.3f}", r.note])
        table = aligned(["method", "rtol", "verdict", "err theta/alpha", f"err {ev} [s]", "steps", "RHS", "wall [ms]",
                         "note"], rows, right={"err theta/alpha", f"err {ev} [s]", "steps", "RHS", "wall [ms]"})
        blocks.append(f"{head}\n{ref}\n" + "\n".join("  " + line for line in table.splitlines()))
    return "\n\n".join(blocks)


def format_wp_summary(summaries) -> str:
    """rockcli at its default rtol (5e-9; 2e-9 on sliding bearings) against RK45 (Radau for sliding bearings) at rtol 1e-8."""
    rows = []
    for s in summaries:
        if s is None:
            continue
        verdict = ("yes (floor)" if s.at_floor else "yes") if s.as_accurate else "NO"
        rows.append([s.scene, s.comparator, f"{s.rtol_kernel:g}", _e(s.err_kernel), _e(s.err_scipy), _e(s.floor), verdict,
                     f"{1e3 * s.wall_kernel_s:.2f}", f"{1e3 * s.wall_verdict_s:.2f}", f"{1e3 * s.wall_scipy_s:.0f}",
                     f"{s.time_ratio:.1e}", "yes" if s.verdicts_agree else "NO", _e(s.err_free)])
    if not rows:
        return ""
    return aligned(["scene", "vs", "rockcli rtol", "err rockcli", "err SciPy", "floor", "as accurate", "rockcli [ms]",
                    "verdict-only [ms]", "SciPy [ms]", "time ratio", "verdicts agree", "err SciPy free steps"], rows,
                   right={"err rockcli", "err SciPy", "floor", "rockcli [ms]", "verdict-only [ms]", "SciPy [ms]", "time ratio",
                          "err SciPy free steps"})


def _pyplot():
    from rockcli.report.figures import pyplot

    return pyplot()


def plot_work_precision(scenes, path, dpi: int = 100) -> Path:
    """Error against wall time, log-log, one panel per scene and one line per method.

    Survivors: the error in theta_max/alpha; overturning scenes: the error in the overturning time
    [s]. Errors of exactly zero are drawn at 1e-16; a red cross marks a run with the wrong verdict;
    the dotted line is the reference's check (its agreement with an independent SciPy solution).
    """
    path = Path(path)
    done = [ws for ws in scenes if ws.available and ws.runs]
    if not done:
        raise RockcliInputError("no scene ran: nothing to plot")
    from rockcli.bench.scenes import resolve_scene
    from rockcli.report.figures import block_text, foundation_text, motion_text, new_figure, title

    plt = _pyplot()
    n = len(done)
    ncol = min(3, n)
    nrow = math.ceil(n / ncol)
    fig = new_figure(4.4 * ncol, 4.0 * nrow + 0.4)
    axes = fig.subplots(nrow, ncol, squeeze=False)
    for ax, ws in zip(axes.flat, done):
        methods = []
        for r in ws.runs:
            if r.method not in methods:
                methods.append(r.method)
        for m in methods:
            pts = [r for r in ws.runs if r.method == m and not r.note and math.isfinite(r.error)
                   and math.isfinite(r.wall_s)]
            if not pts:
                continue
            pts.sort(key=lambda r: r.rtol, reverse=True)
            colour, marker = METHOD_STYLE.get(m, ("0.3", "."))
            x = [r.wall_s for r in pts]
            y = [max(r.error, 1e-16) for r in pts]
            ax.loglog(x, y, color=colour, marker=marker, ms=3.5, lw=1.0, label=m)
            bad = [(xx, yy) for xx, yy, r in zip(x, y, pts) if r.verdict_ok is False]
            if bad:
                ax.loglog(*zip(*bad), "x", color="red", ms=7, mew=1.5)
        if math.isfinite(ws.floor) and ws.floor > 0:
            ax.axhline(ws.floor, color="0.4", ls=":", lw=0.8)  # the reference's resolution
        block, foundation, exc = resolve_scene(ws.scene)
        title(ax, f"{ws.scene.name}: {block_text(block)}; {motion_text(exc)}; {foundation_text(foundation)}",
              fontsize=7)
        ax.set_xlabel("wall time [s]", fontsize=8)
        ax.set_ylabel(r"error in $t_{overturn}$ [s]" if ws.event == "overturn" else r"error in $\theta_{max}/\alpha$",
                      fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, which="major", lw=0.3)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    handles, labels = [], []
    for ax in axes.flat:
        for h, lab in zip(*ax.get_legend_handles_labels()):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    fig.legend(handles, labels, loc="outside lower center", ncol=len(labels), fontsize=8, frameon=False)
    try:
        return save_figure(fig, path, dpi=dpi)
    finally:
        plt.close(fig)


# --------------------------------------------------------------------------------------------------
# stability
# --------------------------------------------------------------------------------------------------
def stability_rows(results) -> list:
    out = []
    for res in results:
        sc = res.scene
        row = dict(scene=sc.name, title=sc.title, status=res.status, reason=res.reason, wall_budget_s=sc.wall_budget_s,
                   step_budget=sc.step_budget, ulp_spread=res.ulp_spread, ulp_verdicts=" ".join(res.ulp_verdicts),
                   ill_conditioned=res.ill_conditioned, checks="; ".join(f"{c.name}: {'ok' if c.ok else 'FAIL'}: {c.detail}"
                                                                for c in res.checks))
        for rt, d in res.runs.items():
            mant, _, exp = f"{rt:.0e}".partition("e")
            tag = f"rtol_{mant}e{int(exp)}"  # rtol_1e-6, rtol_1e-10
            row[f"verdict_{tag}"] = d["verdict"]
            row[f"theta_max_over_alpha_{tag}"] = d["theta_max_over_alpha"]
            row[f"t_overturn_s_{tag}"] = d["t_overturn_s"]
            row[f"steps_{tag}"] = d["steps"]
            row[f"rejected_{tag}"] = d["rejected"]
            row[f"impacts_{tag}"] = d["n_impacts"]
            row[f"rests_{tag}"] = d["n_rests"]
            row[f"wall_s_{tag}"] = d["wall_s"]
        if res.runs:
            row["settled"] = all(d["settled"] for d in res.runs.values())
        out.append(row)
    return out


def write_stability_csv(results, path) -> Path:
    return _write(path, STAB_COLUMNS, stability_rows(results))


def format_stability(results) -> str:
    """One aligned row per scene: status, verdicts and peaks at both tolerances, steps, time, reason."""
    rows = []
    for res in results:
        a, b = res.runs.get(1e-6), res.runs.get(1e-10)

        def peak(d):
            if d is None:
                return ""
            if d["verdict"] == "overturned":
                return f"t_ot {d['t_overturn_s']:.4f} s"
            return f"{d['theta_max_over_alpha']:.6f}"

        rows.append([res.scene.name, res.status, b["verdict"] if b else "", peak(a), peak(b), _ulp(res),
                     str(b["steps"]) if b else "", f"{1e3 * b['wall_s']:.1f}" if b else "",
                     res.reason if res.status != "pass" else ""])
    return aligned(["scene", "result", "verdict", "peak @1e-6", "peak @1e-10", "1 ulp moves it", "steps @1e-10",
                    "wall [ms]", "why"], rows, right={"1 ulp moves it", "steps @1e-10", "wall [ms]"})


def _ulp(res) -> str:
    """The conditioning column: how far one ulp of the input moves the answer (``ILL`` past the limits)."""
    if not res.ulp_verdicts:
        return ""
    if math.isnan(res.ulp_spread):
        return "verdict! ILL"
    unit = " s" if res.runs.get(1e-10, {}).get("verdict") == "overturned" else ""
    return f"{res.ulp_spread:.1e}{unit}" + (" ILL" if res.ill_conditioned else "")
