"""``assess column``'s outputs besides the table: the tolerance check's report (``--check-tolerance``) and the files of
every run (``--history-dir``, ``--plot-dir``), planned before any work and written in the command's transaction."""

from __future__ import annotations

import click

from rockcli.cli.errors import InputError


def _echo_tolerance_check(chk, as_json=False):
    from functools import partial

    from rockcli.conditioning import ILL_PEAK

    echo = partial(click.echo, err=as_json)
    bases = chk.base_rtols or (chk.base_rtol,)
    head = (f"Tolerance check: {chk.n_runs} scenes rerun at rtol {'/'.join(f'{b / 100:g}' for b in bases)} "
            f"(100x tighter than {'/'.join(f'{b:g}' for b in bases)}"
            + (", the defaults of rigid and linear / sliding bearings" if len(bases) > 1 else "") + "): ")
    if not chk.changed:
        echo(head + f"no verdict changes (largest change of a survivor's peak |theta|/alpha: "
                          f"{chk.max_peak_change:.1e}).")
    else:
        echo(head + f"{len(chk.changed)} VERDICTS CHANGE (decided by the numerics; treat as a coin toss):")
        for row, tight in chk.changed:
            echo(f"  {row.column} / {row.record} / {row.configuration}: {row.verdict} -> {tight}")
    head = (f"Conditioning check: the {chk.n_runs} scenes rerun on {chk.ulp_draws} copies of their motion moved by "
            f"one ulp (the same motion to within rounding): ")
    if not chk.ill:
        echo(head + f"no verdict changes (largest change of a survivor's peak |theta|/alpha: "
                          f"{chk.max_ulp_peak_change:.1e}).")
        return chk
    echo(head + f"{len(chk.ill)} ILL-CONDITIONED (the verdict changes, or the peak moves by more than "
                      f"{ILL_PEAK:g} alpha: the answer is not determined by the motion at double precision; read "
                      f"it as one sample of a spread, and look at the margin):")
    for row, verdicts, moved in chk.ill:
        what = f"peak moves by {moved:.2g} alpha" if moved == moved else f"{row.verdict} -> {', '.join(verdicts)}"
        echo(f"  {row.column} / {row.record} / {row.configuration}: {what}")
    return chk


def _plan_run_files(columns, excitations, configurations, hist_dir, plot_dir):
    """Declare the file of every run in --histories/--plot before any work: two runs whose names give
    the same file name (after the unsafe characters are replaced; letter case ignored) are refused."""
    from pathlib import Path

    from rockcli.assess import safe_name
    from rockcli.io.files import current

    outputs = current()
    seen = {}
    for b in columns:
        for x in (x for x in excitations if x.motion is not None):
            for c in configurations:
                stem = safe_name(b.name, x.label, c.header)
                other = seen.setdefault(stem.casefold(), (b.name, x.label, c.header))
                if other != (b.name, x.label, c.header):
                    raise InputError(f"the runs {' / '.join(other)} and {b.name} / {x.label} / {c.header} would write "
                                     f"the same file {stem}.*; give the columns (or records) names that differ in "
                                     f"letters or digits")
                for folder, option, suffix in ((hist_dir, "--history-dir", ".csv"), (plot_dir, "--plot-dir", ".png")):
                    if folder and outputs is not None:
                        outputs.declare(Path(folder) / f"{stem}{suffix}", option, check=False)


def _write_histories(result, hist_dir, plot_dir, as_json=False):
    """One history CSV and/or figure per run, staged in the command's transaction (nothing is replaced or
    left behind unless every one of them, and the rest of the run, succeeds)."""
    from pathlib import Path

    from rockcli.assess import history_runs, safe_name
    from rockcli.io.files import transaction
    from rockcli.report.figures import plot_grid_dt
    from rockcli.report.response import plot_response, write_history_csv
    from rockcli.solve import simulate

    n = 0
    with transaction() as outputs:
        for folder, option in ((hist_dir, "--history-dir"), (plot_dir, "--plot-dir")):
            if folder:
                outputs.make_folder(folder, option)
        for row, block, conf, x, resp in history_runs(result):
            if resp.status < 0:  # the step cap: no history to show as if it were valid
                continue
            stem = safe_name(row.column, row.record, row.configuration)
            label = x.label + (" (catalogued pulse)" if x.kind == "pulse" else "")
            if hist_dir:
                write_history_csv(resp, block, Path(hist_dir) / f"{stem}.csv")
            if plot_dir:  # drawn from the dense output between the steps
                dense = simulate(block, conf.foundation, x.motion, history=True, history_dt=plot_grid_dt(x.motion),
                                 **result.solver)
                plot_response(dense, block, conf.foundation, Path(plot_dir) / f"{stem}.png", excitation=x.motion,
                              motion=label)
            n += 1
    what = " and ".join(f"{k} in {d}" for k, d in (("histories", hist_dir), ("figures", plot_dir)) if d)
    click.echo(f"wrote {what} ({n} runs)", err=as_json)
