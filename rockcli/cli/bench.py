"""``rockcli bench``: how accurate, how fast and how robust the solver is."""

from __future__ import annotations

import sys

import click

from rockcli.cli.errors import InputError, user_errors
from rockcli.cli.options import Group
from rockcli.cli.types import SEED, Number

_METHODS = ("RK45", "DOP853", "Radau", "LSODA", "BDF", "RK45-free")


@click.group(name="bench", cls=Group)
def bench():
    """Accuracy, cost and robustness of the solver: work-precision against SciPy, stiff and extreme scenes."""


def _check_outputs(csv=None, plot=None):
    """Outputs checked before any run (rockcli.io.files): a long study never fails on its output."""
    from rockcli.cli.options import check_outputs

    check_outputs((csv, "--csv", False), (plot, "--plot", True))


def _rtols(text, opt):
    if text is None:
        return None
    out = []
    from rockcli.errors import RockcliInputError
    from rockcli.io.inputs import parse_number

    for item in filter(None, (s.strip() for s in text.split(","))):
        try:
            v = parse_number(item, f"{opt}: {item!r}", bad=f"{opt}: {item!r} is not a number")
        except RockcliInputError as exc:
            raise InputError(str(exc)) from None
        if not 1e-14 <= v <= 1e-2:
            raise InputError(f"{opt}: tolerances must lie between 1e-14 and 1e-2, got {item}")
        out.append(v)
    if not out:
        raise InputError(f"{opt}: give at least one tolerance")
    return tuple(out)


def _progress():
    if not sys.stderr.isatty():
        return None
    return lambda line: click.echo(f"  {line}", err=True)


def _failed_checks(results) -> dict:
    """How many scenes failed each kind of check (name before the '@')."""
    out = {}
    for res in results:
        for kind in sorted({c.name.split(" @")[0] for c in res.checks if not c.ok}
                           | ({"proven"} if "NOT PROVEN" in res.reason and res.status == "FAIL" else set())):
            out[kind] = out.get(kind, 0) + 1
    return out


def _scene_list(catalogue) -> str:
    return "\n".join(f"  {s.name:22s} {s.title}" for s in catalogue)


@bench.command(name="work-precision")
@click.option("--scene", "scenes", multiple=True, metavar="NAME", help="A scene to run (repeatable; default all; "
              "--list shows them).")
@click.option("--csv", "csv_path", default=None, metavar="FILE", help="Write one row per run.")
@click.option("--plot", "plot_path", default=None, metavar="FILE",
              help="Draw error against wall time, one panel per scene (.png, .pdf, .svg).")
@click.option("--kernel-rtol", default=None, metavar="LIST",
              help="rockcli's tolerances, comma-separated (default 1e-4,1e-5,...,1e-12).")
@click.option("--scipy-rtol", default=None, metavar="LIST",
              help="SciPy tolerances for every method (default: RK45 1e-6,1e-8,1e-10, DOP853 1e-8,1e-12, Radau "
                   "1e-6,1e-8, LSODA 1e-8, BDF 1e-6, RK45-free 1e-8).")
@click.option("--methods", default=",".join(_METHODS), show_default=True, metavar="LIST",
              help="SciPy methods, comma-separated, or 'none'. Steps are aligned to a record's samples, as "
                   "rockcli's; RK45-free (records only) lets RK45 step across them (max_step = dt).")
@click.option("--repeat", type=Number(integer=True, lo=1, hi=50), default=None,
              help="Timing repeats of a SciPy run (median; runs over 2 s are timed once). Default 1, --full 3.")
@click.option("--full", is_flag=True,
              help="Longer SciPy ladders (RK45 1e-4..1e-10, DOP853 1e-4..1e-12, the implicit methods 1e-4..1e-8, "
                   "RK45-free 1e-6..1e-10) and 3 timing repeats: the docs/ figures; about 12 min.")
@click.option("--no-check", is_flag=True, help="Do not verify the reference solution with SciPy.")
@click.option("--list", "list_only", is_flag=True, help="List the scenes and exit.")
@user_errors
def work_precision(scenes, csv_path, plot_path, kernel_rtol, scipy_rtol, methods, repeat, full, no_check, list_only):
    """Error against run time: rockcli's kernel and SciPy's solve_ivp methods on named scenes.

    Each scene is solved by rockcli at a ladder of rtol (full histories, and verdict-only runs
    as the sweeps use them) and by the SciPy reference (rockcli.reference: the equations typed
    again) with RK45, DOP853, Radau, LSODA and BDF at a ladder of rtol, all against a reference
    solution: rockcli at rtol 1e-13, checked against DOP853 at 1e-13 and recomputed on 4 inputs
    moved by one ulp (its rounding noise); the larger of the two is the scene's floor, below which
    errors are not ranked.
    Prints per run the error in theta_max/alpha, in the overturning time (or the time the block
    comes to rest), whether the verdict agrees, steps, right-hand sides and the median wall time;
    then rockcli at its default rtol (5e-9; 2e-9 on sliding bearings) against RK45 at rtol 1e-8 (Radau
    for sliding bearings).
    Each SciPy run has a wall budget (20 s; 120 s with --full): a slower run is reported "over budget".
    Timings depend on the machine and its load.

    \b
    Examples:
      ROCKCLI_RECORDS=../shared/records rockcli bench work-precision --csv wp.csv --plot wp.png
      ROCKCLI_RECORDS=../shared/records rockcli bench work-precision --full --csv wp-full.csv
      rockcli bench work-precision --scene rigid-ricker --kernel-rtol 1e-4,1e-8 --methods RK45 --scipy-rtol 1e-6
    """
    from rockcli.bench import (SCIPY_BUDGET_FULL_S, SCIPY_BUDGET_S, SCIPY_RTOLS, SCIPY_RTOLS_FULL, WP_SCENES,
                               run_work_precision, select_scenes, summarise)

    if list_only:
        click.echo(_scene_list(WP_SCENES))
        return
    chosen = select_scenes(scenes, WP_SCENES)
    _check_outputs(csv=csv_path, plot=plot_path)
    kernel_rtols = _rtols(kernel_rtol, "--kernel-rtol")
    scipy_rtols = _rtols(scipy_rtol, "--scipy-rtol")
    names = [m.strip() for m in methods.split(",") if m.strip()]
    if names == ["none"]:
        names = []
    by_lower = {m.lower(): m for m in _METHODS}
    bad = [m for m in names if m.lower() not in by_lower]
    if bad:
        raise InputError(f"--methods: unknown SciPy method {bad[0]!r} (use {', '.join(_METHODS)} or none)")
    names = [by_lower[m.lower()] for m in names]
    kw = {}
    if kernel_rtols is not None:
        kw["kernel_rtols"] = kernel_rtols
    ladders = scipy_rtols or (SCIPY_RTOLS_FULL if full else SCIPY_RTOLS)
    repeats = repeat if repeat is not None else (3 if full else 1)
    result = run_work_precision(chosen, scipy_rtols=ladders, methods=names, repeats=repeats,
                                scipy_budget_s=SCIPY_BUDGET_FULL_S if full else SCIPY_BUDGET_S,
                                check=not no_check, progress=_progress(), **kw)
    from rockcli.report.bench import format_work_precision, format_wp_summary

    click.echo(format_work_precision(result))
    summary = format_wp_summary([summarise(ws) for ws in result if ws.available])
    if summary:
        click.echo("\nrockcli at its default rtol (5e-9; 2e-9 on sliding bearings) against SciPy at rtol 1e-8 "
                   "(errors as plotted; time ratio = rockcli / SciPy):")
        click.echo(summary)
        click.echo("floor: the reference's resolution, the larger of its disagreement with the check and its "
                   "rounding noise; errors below it cannot be ranked. 'yes (floor)': rockcli's error is above "
                   "SciPy's, and both are below the floor.")
    click.echo("\nTimings are wall times on this machine and depend on its load.")
    if csv_path:
        from rockcli.report.bench import write_work_precision_csv

        write_work_precision_csv(result, csv_path)
        click.echo(f"wrote {csv_path}")
    if plot_path:
        from rockcli.report.bench import plot_work_precision

        plot_work_precision(result, plot_path)
        click.echo(f"wrote {plot_path}")


@bench.command(name="stability")
@click.option("--scene", "scenes", multiple=True, metavar="NAME", help="A scene to run (repeatable; default all; "
              "--list shows them).")
@click.option("--csv", "csv_path", default=None, metavar="FILE", help="Write one row per scene.")
@click.option("--list", "list_only", is_flag=True, help="List the scenes and exit.")
@click.option("--verbose", "-v", is_flag=True, help="Print every check of every scene.")
@click.option("--random", "n_random", type=Number(integer=True, lo=0, hi=100000), default=0, metavar="N",
              help="Instead of the named scenes, N random extreme pulse scenes (alpha 1-45 deg, R 0.2-20 m, rigid "
                   "or linear bearings with xi 0-1 and gamma 0-0.99, T_p 0.05-10 s, a_p up to 5 g).")
@click.option("--seed", type=SEED, default=1, show_default=True, help="Seed of --random.")
@user_errors
def stability(scenes, csv_path, list_only, verbose, n_random, seed):
    """Stiff and extreme scenes, each run at rtol 1e-6 and 1e-10 within a wall-time and step budget.

    A scene passes when: no NaN; no hang (budget); no step-size collapse; the same verdict at both
    tolerances with theta_max/alpha within 1e-3 (overturning time within 1 ms); momentum kept
    across every impact of the history; no energy created in free rocking after the excitation
    (rigid base); the verdict proven (an undamped base that keeps lifting the block ends NOT
    PROVEN at the horizon: reported as "stated"). Scenes the solver refuses are reported as
    refused, sliding-bearing scenes as pending until those bearings exist. Exit code 1 when a
    scene fails. Each scene is also rerun on 2 inputs moved by one ulp: a scene whose verdict
    changes there, or whose peak moves by more than 1e-3 alpha, is marked ILL (ill-conditioned:
    its answer is not determined by its input at double precision); that is reported, not failed.

    \b
    Examples:
      rockcli bench stability --csv stability.csv
      rockcli bench stability --scene xi-0 --scene alpha-at-end -v
    """
    from rockcli.bench import STABILITY_SCENES, run_stability, select_scenes

    if list_only:
        click.echo(_scene_list(STABILITY_SCENES))
        return
    if n_random and scenes:
        raise InputError("--random replaces the named scenes: give --scene or --random, not both")
    if n_random:
        from rockcli.bench import random_scenes

        chosen = random_scenes(n_random, seed)
    else:
        chosen = select_scenes(scenes, STABILITY_SCENES)
    _check_outputs(csv=csv_path)
    results = run_stability(chosen, progress=_progress())
    from rockcli.report.bench import format_stability

    if n_random:
        results_shown = [r for r in results if r.status not in ("pass", "stated")]
        click.echo(format_stability(results_shown) if results_shown else "every random scene passes")
        click.echo("\nFailed checks: " + (", ".join(f"{k} {v}" for k, v in _failed_checks(results).items()) or "none"))
    else:
        click.echo(format_stability(results))
    if verbose:
        for res in results:
            click.echo(f"\n{res.scene.name}: {res.scene.title}")
            for c in res.checks:
                click.echo(f"  {'ok  ' if c.ok else 'FAIL'} {c.name}: {c.detail}")
    counts = {}
    for res in results:
        counts[res.status] = counts.get(res.status, 0) + 1
    click.echo("\n" + ", ".join(f"{v} {k}" for k, v in counts.items()) + f" of {len(results)} scenes")
    ill = [res for res in results if res.ill_conditioned]
    if ill:
        names = ", ".join(res.scene.name for res in ill[:10]) + (", ..." if len(ill) > 10 else "")
        click.echo(f"ill-conditioned (ILL): {len(ill)} scene(s) whose verdict, or whose peak by more than 1e-3 alpha "
                   f"(overturning time by more than 1e-3 s), changes when the input moves by one ulp: {names}. "
                   "Their answer is not determined by the input at double precision (sensitive dependence through "
                   "impacts); the solver is not at fault, and such an answer should be read as one sample of a spread.")
    if csv_path:
        from rockcli.report.bench import write_stability_csv

        write_stability_csv(results, csv_path)
        click.echo(f"wrote {csv_path}")
    if counts.get("FAIL"):
        sys.exit(1)
