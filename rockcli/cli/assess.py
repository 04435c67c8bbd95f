"""``rockcli assess column`` (which columns survive which records, on the ground and on isolators) and
``rockcli assess fragility`` (how likely they overturn at a given intensity)."""

from __future__ import annotations

from functools import partial

import click

from rockcli.cli.assess_friction import friction_option, with_friction
from rockcli.cli.errors import InputError, user_errors
from rockcli.cli.options import (QuietSpellingOption, alias_option, azimuth_options, cap_ratio_option, check_outputs, command_line, custom_block_options,
                                 echo_json, given_azimuth, given_component, given_gain, given_suite, horizon_option,
                                 is_quiet, json_option, plinth_option, progress_bar, quiet_option, report_option,
                                 restitution_option, vertical_options)
from rockcli.cli.options import GAMMA_HELP, REPORT_SUFFIXES, Group
from rockcli.cli.types import NUMBER, SEED, Number


@click.group(name="assess", cls=Group)
def assess():
    """Assess free-standing bodies against records and isolation configurations."""


def _restitution_kw(restitution) -> dict:
    """The solver keyword of ``--restitution`` (checked; none when not given: Housner's rule)."""
    from rockcli.models.impact import check_restitution

    restitution = check_restitution(restitution, "--restitution")
    return {} if restitution is None else {"restitution": restitution}


def _cap_ratio_kw(cap_ratio) -> dict:
    """The solver keyword of ``--cap-ratio`` (checked; none when 0: solitary columns)."""
    from rockcli.models.colonnade import check_cap_ratio

    cap_ratio = check_cap_ratio(cap_ratio, "--cap-ratio")
    return {} if cap_ratio == 0.0 else {"cap_ratio": cap_ratio}


def _with_vertical(excitations, configurations, units, dt) -> list:
    """The excitations under the vertical motion of ``--vertical``/``--vertical-component``/``--vertical-pulse``
    (:func:`rockcli.assess.vertical.attach_verticals`); unchanged without them. Refused with an isolated
    configuration (one sentence why)."""
    from rockcli.assess.excitations import _file_read_kwargs
    from rockcli.cli.options import given_vertical, read_vertical
    from rockcli.solve.excitation import VERTICAL_RIGID_ONLY

    v = given_vertical()
    given = [f for f, k in (("--vertical", "source"), ("--vertical-pulse", "pulse")) if v[k] is not None]
    if v["component"] is not None and v["source"] is None:  # without --vertical: each record's own component
        given.append("--vertical-component")
    if v["column"] is not None and v["source"] is None:
        raise InputError("--vertical-column applies to --vertical SOURCE")
    if not given:
        if v["scale_given"]:
            raise InputError("--vertical-scale applies to --vertical, --vertical-component or --vertical-pulse")
        return list(excitations)
    if len(given) > 1:
        raise InputError(f"give the vertical ground motion as one of --vertical, --vertical-component or "
                         f"--vertical-pulse, not {' and '.join(given)}")
    if any(c.isolated for c in configurations):
        raise InputError(f"{given[0]}: {VERTICAL_RIGID_ONLY}; give --isolation none")
    from rockcli.assess.vertical import attach_verticals

    if v["component"] is not None and v["source"] is None:
        from rockcli.io.inputs import check_scale

        check_scale(v["scale"], 0.0, "--vertical-scale")  # each record's own peak: attach_verticals
        return attach_verticals(excitations, component=v["component"], scale=v["scale"],
                                read_kwargs=_file_read_kwargs(units, dt))
    motion, label = read_vertical(v["source"], v["column"], v["pulse"], v["scale"], {"units": units, "dt": dt},
                                  v["component"])
    return attach_verticals(excitations, motion=motion, label=label)


def _vertical_given() -> bool:
    """A vertical ground motion is asked for (``--vertical``, ``--vertical-pulse`` or ``--vertical-component``)."""
    from rockcli.cli.options import given_vertical

    v = given_vertical()
    return any(v[k] is not None for k in ("source", "pulse", "component"))


def _vertical_note(result) -> str:
    """A line of the notes naming the vertical motion of each record (none without one)."""
    from rockcli.assess.vertical import vertical_labels

    labels = vertical_labels(result.excitations)
    if not labels:
        return ""
    kinds = sorted(set(labels.values()))
    what = kinds[0] if len(kinds) == 1 else "; ".join(f"{k}: {v}" for k, v in labels.items())
    return (f"\nVertical motion (rigid foundation; gravity g + a_v; the scale factors multiply the horizontal "
            f"motion only): {what}.")


def _headerless_options(func):
    """``--units`` and ``--dt`` for record files that do not state them (headerless text, SAC, ...)."""
    from rockcli.cli.options import component_option, gain_option, suite_options

    func = suite_options(gain_option(component_option(func)))
    func = click.option("--dt", type=NUMBER, default=None, metavar="SECONDS",
                        help="Time step [s] of the record files that state none (it fills in only what a file "
                             "does not state). Catalogue files are read as the catalogue says.")(func)
    return click.option("--units", default=None, metavar="UNITS",
                        help="Units of the record files that do not state them (g, m/s^2, cm/s^2, gal, "
                             "mm/s^2, g/10; they fill in only what a file does not state).")(func)


def _run_counted(total: int, run):
    """``run(progress=...)`` under progress lines (none when piped; the run announces its parts, and a part
    whose steps were not all needed is completed when the next begins): its result."""
    with progress_bar(total) as bar:
        return run(progress=bar)


def _echo_result(result, table: str, notes: str, plain: str | None = None, *, as_json=None):
    """Print a result's table, notes (not with ``--quiet``) and (when given) the answer in plain words, or with
    ``as_json`` (the JSON document) that instead; and warn (stderr) about the records that could not be read
    or run."""
    if as_json is not None:
        echo_json(as_json)
    else:
        click.echo(table)
        if not is_quiet():
            click.echo("")
            click.echo(notes)
        if plain is not None:
            click.echo("")
            click.echo(plain)
    failed = result.failed
    if failed:
        click.echo(f"Warning: {len(failed)} of {len(result.excitations)} records could not be read or run; they "
                   f"have error rows: {', '.join(x.label for x in failed[:5])}{' ...' if len(failed) > 5 else ''}",
                   err=True)


def _warn_pulses(result, mode: str):
    """A catalogued pulse run in place of a record the user did not ask to replace changes the question:
    said on stderr too (the rows say "(pulse)" and the count line how many)."""
    if mode != "auto" or not result.idealised:
        return
    n, total = len(result.idealised), len(result.excitations)
    click.echo(f"Warning: {n} of {total} records ran as their catalogued pulse, not as the record (file not found "
               f"on ROCKCLI_RECORDS or in the repository's records/): the answer is about pulses; "
               f"--excitation record refuses this, --excitation pulse asks for it", err=True)


def _refuse_if_none_can_run(excitations, unavailable=()):
    """Nothing to report when no record can be run (none found, or none readable): exit 2 with one sentence
    per record or skipped file, nothing written (``assess column`` and ``assess fragility`` alike)."""
    from rockcli.assess.excitations import Duplicate, Skipped

    if not excitations:
        skipped = [u for u in unavailable if isinstance(u, Skipped)]
        missing = [f"{u.label}: {u.reason}" for u in unavailable if not isinstance(u, (Skipped, Duplicate))]
        why = (([f"no file of the folder(s) is a record ({'; '.join(u.reason for u in skipped)})"] if skipped else [])
               + missing)
        raise InputError("no record to run: " + ("; ".join(why) if why else "the sources name none"))
    if all(x.motion is None for x in excitations):
        failed = [x.error or f"{x.label}: cannot be run" for x in excitations]
        raise InputError(failed[0] if len(failed) == 1 else
                         f"none of the {len(failed)} records can be run:\n" + "\n".join(failed))


def _add_record_inputs(excitations):
    """The record files read: no output may be written onto one of them."""
    from rockcli.assess import EXCITATION_RECORD
    from rockcli.cli.options import add_inputs

    add_inputs([x.source for x in excitations if x.kind == EXCITATION_RECORD and x.pair is None]
               + [r.meta.get("path") for x in excitations if x.pair for r in x.pair], "the record")


def _not_an_image(path) -> None:
    """``assess column --plot``, the old spelling of ``--plot-dir``: a folder, so a file name is refused."""
    from pathlib import Path

    from rockcli.errors import RockcliInputError

    if Path(path).suffix.lower() in (".png", ".pdf", ".svg", ".jpg", ".jpeg", ".eps", ".ps", ".tif", ".tiff",
                                     ".webp"):
        raise RockcliInputError(f"assess column draws one figure per run into a folder: give it with --plot-dir "
                                f"(e.g. --plot-dir {Path(path).stem or 'figs'}); --plot {path} names an image file")


def _columns(names, R, alpha, height, width, name):
    from rockcli.assess import custom_column, parse_column_spec
    from rockcli.cli.options import BLOCK_FLAGS

    columns = [parse_column_spec(n) for n in names]
    if any(v is not None for v in (R, alpha, height, width)):
        columns.append(custom_column(name, R=R, alpha=alpha, height=height, width=width, labels=BLOCK_FLAGS))
    if not columns:
        raise InputError("name at least one column (bassae, nemea, or NAME:R=<m>,alpha=<deg>), or give --R/--alpha")
    seen = set()
    for b in columns:
        if b.name in seen:
            raise InputError(f"column name {b.name!r} is given twice; give each column its own name")
        seen.add(b.name)
    from rockcli.cli.options import warn_size

    return [warn_size(b) for b in columns]


@assess.command(name="column")
@click.argument("names", nargs=-1, metavar="NAME...")
@custom_block_options
@click.option("--records", "--record", "records", multiple=True, metavar="ID|FILE|DIR", cls=QuietSpellingOption,
              quiet_spellings=("--record",),
              help="Records to run (repeatable): catalogue ids, files, folders. Default: the catalogue's "
                   "Table II records (file where found on ROCKCLI_RECORDS, else the catalogued pulse).")
@_headerless_options
@azimuth_options(suite=True)
@vertical_options
@click.option("--excitation", type=click.Choice(["auto", "record", "pulse"]), default="auto", show_default=True,
              help="Catalogue records: the file where found else its fitted Ricker pulse (auto), files only "
                   "(record), or the pulses only (pulse).")
@click.option("--isolation", "isolation", multiple=True, metavar="SPEC",
              help="Foundation (repeatable): 'none', 'linear:Tb=2.5,xi=0.1,gamma=0.01', 'scss:Tb=2,mu=0.05', "
                   "'lrb:Tb=2.5,Q=0.06,uy=0.015' or 'dcss:R1=1.1,R2=1.1,mu1=0.03,mu2=0.07' (see 'rockcli simulate "
                   "--help'). Default: the paper's Table III set: none and linear Tb = 2, 2.5, 3 s with xi = 0.1 "
                   "(gamma = 0.01). " + GAMMA_HELP)
@click.option("--margin/--no-margin", default=True, show_default=True,
              help="Find the smallest scale factor of each record that overturns (0.1x..4x scan, then bisection).")
@click.option("--neighbourhood", is_flag=True,
              help="Also run 0.90x..1.10x of each record (21 factors) and report the share that overturns.")
@click.option("--csv", "csv_path", type=click.Path(), default=None,
              help="Write the report: one row per column x record x configuration.")
@click.option("--history-dir", "hist_dir", type=click.Path(), default=None, metavar="DIR",
              help="Write one time-history CSV per run into this folder.")
@alias_option("--histories", "hist_dir", "--history-dir", type=click.Path())
@click.option("--plot-dir", "plot_dir", type=click.Path(), default=None, metavar="DIR",
              help="Write one figure per run (like the paper's Figure 12) into this folder.")
@alias_option("--plot", "plot_dir", "--plot-dir", type=click.Path(), check=_not_an_image)
@click.option("--check-tolerance", is_flag=True,
              help="Rerun every scene at a 100x tighter rtol (5e-11; 2e-11 on sliding bearings) and flag any "
                   "verdict that changes; and on 2 copies of its motion moved by one ulp, and flag any scene "
                   "whose verdict changes or whose peak moves by more than 1e-3 alpha (ill-conditioned).")
@click.option("--scheduler", default=None, metavar="tcp://HOST:PORT|local",
              help="Run the scenes and their margin searches on a Dask cluster (pip install -e \".[dask]\"): the "
                   "address of an existing scheduler, or 'local' for a LocalCluster on this machine. Same results. "
                   "A scheduler that does not answer, has no worker or loses all its workers stops the run after "
                   "ROCKCLI_DASK_TIMEOUT seconds (default 60).")
@report_option
@json_option
@quiet_option
@horizon_option
@restitution_option
@cap_ratio_option
@plinth_option
@friction_option
@user_errors
def column(names, R, alpha, height, width, name, records, units, dt, excitation, isolation, margin, neighbourhood,
           csv_path, hist_dir, plot_dir, check_tolerance, scheduler, report_path, as_json, horizon, restitution,
           cap_ratio, plinth_spec, friction):
    """Do the columns NAME... survive the records, on a rigid base and on isolators?

    NAME is a preset (bassae, nemea) or a custom block NAME:R=<m>,alpha=<deg> or
    NAME:height=<m>,width=<m>; --R/--alpha or --height/--width add one more block (--name).
    A column as a stack of drums: nemea-drums, bassae-drums or NAME:height=<m>,width=<m>,drums=<N>,
    with --friction MU; each runs beside its monolith (docs/physics-drums.md), and the answer says,
    record by record, whether the drums make the column safer.
    Prints, per column, a table records x configurations (survives with peak |theta|/alpha,
    or OVERTURNS; xS is the smallest scale factor of the record that overturns) and how many
    records each configuration survives, then the answer in plain words: one sentence per body and
    configuration, with the stroke the isolation bearings must allow. --report writes all of it,
    with figures and the records' provenance, as one self-contained HTML file.

    \b
    Examples:
      ROCKCLI_RECORDS=../shared/records rockcli assess column bassae nemea --csv table.csv
      rockcli assess column statue:R=1.2,alpha=14 --records kobe-1995-takarazuka-000 --isolation none
      rockcli assess column nemea --records kobe-1995-takarazuka-000 --isolation linear:Tb=3 --plot-dir figs
      rockcli assess column bassae-drums --friction 0.7 --records kobe-1995-takarazuka-000 --excitation pulse \\
          --isolation linear:Tb=3 --no-margin --report drums.html
      rockcli assess column statue:R=0.93,alpha=15.5 --records ../shared/records/RSN1119_KOBE_TAZ000.AT2 \\
          --isolation none --isolation linear:Tb=2.5 --report statue.html

    The margins (--margin, the default) take most of the time: --no-margin gives the verdicts alone,
    in seconds. Columns of drums are far slower (the catalogue: minutes of CPU without margins, hours
    with them; docs/physics-drums.md): try one record first (--records ID --no-margin).
    """
    from rockcli.assess import count_runs, parse_configurations, resolve_excitations, run_assessment

    from rockcli.solve import validate_options

    validate_options(horizon=horizon)
    solver = _restitution_kw(restitution)
    columns = _columns(names, R, alpha, height, width, name)
    configurations = parse_configurations(isolation)
    from rockcli.cli.assess_drums import with_drums  # each column of drums beside its monolith

    columns = with_drums(columns, friction=friction, refused=(
        ("--on", plinth_spec is not None), ("--restitution", restitution is not None),
        ("--cap-ratio", bool(cap_ratio)), ("--azimuth worst", given_azimuth()["azimuth"] == "worst"),
        ("--vertical/--vertical-pulse/--vertical-component", _vertical_given()),
        ("--history-dir", hist_dir), ("--plot-dir", plot_dir), ("--check-tolerance", check_tolerance)))
    plinth_note = ""
    if plinth_spec is not None:  # each body alone and on the plinth (rockcli.cli.assess_plinth)
        from rockcli.cli.assess_plinth import with_plinth

        columns, configurations, plinth_note = with_plinth(
            columns, configurations, plinth_spec, isolation_given=bool(isolation), cap_ratio=cap_ratio,
            refused=(("--history-dir", hist_dir), ("--plot-dir", plot_dir)))
    columns, configurations, friction_note = with_friction(
        columns, configurations, friction, isolation_given=bool(isolation), restitution=restitution,
        refused=(("--cap-ratio", bool(cap_ratio)),
                 ("--history-dir", hist_dir), ("--plot-dir", plot_dir), ("--check-tolerance", check_tolerance)))
    plinth_note = " ".join(n for n in (plinth_note, friction_note) if n)
    solver.update(_cap_ratio_kw(cap_ratio))
    check_outputs((csv_path, "--csv", False), (report_path, "--report", REPORT_SUFFIXES),
                  folders=((hist_dir, "--history-dir"), (plot_dir, "--plot-dir")))
    if scheduler is not None:
        from rockcli.distributed import check_scheduler

        check_scheduler(scheduler)
    azimuth = given_azimuth()
    worst = azimuth["azimuth"] == "worst"
    if worst and (hist_dir or plot_dir or check_tolerance):
        raise InputError("--azimuth worst keeps the most adverse orientation of each pair: --history-dir, "
                         "--plot-dir and --check-tolerance need one --azimuth DEG")
    excitations, unavailable = resolve_excitations(records, excitation, units=units, dt=dt, gain=given_gain(),
                                                   component=given_component(), azimuth=azimuth["azimuth"],
                                                   azimuth_step=azimuth["step"] if worst else None, **given_suite())
    _refuse_if_none_can_run(excitations, unavailable)
    excitations = _with_vertical(excitations, configurations, units, dt)
    _refuse_if_none_can_run(excitations)
    _add_record_inputs(excitations)
    if hist_dir or plot_dir:
        from rockcli.cli.assess_runs import _plan_run_files

        _plan_run_files(columns, excitations, configurations, hist_dir, plot_dir)

    # with --azimuth worst, run_assessment runs every orientation of each pair (Excitation.azimuths) and keeps the
    # most adverse one's row: the path of resolve_excitations(..., azimuth="worst") + run_assessment from Python
    kwargs = dict(margin=margin, neighbourhood=neighbourhood, unavailable=unavailable, horizon=horizon, **solver)
    if scheduler is not None:
        from rockcli.assess.cluster import run_on_dask
        from rockcli.cli.options import dask_client

        client = dask_client(scheduler)
        n_scenes = count_runs(columns, excitations, configurations, margin=False)
        with progress_bar(n_scenes, "scenes on Dask") as bar:
            result = run_on_dask(client, columns, excitations, configurations, progress=bar, **kwargs)
    else:
        result = _run_counted(count_runs(columns, excitations, configurations, margin, neighbourhood),
                              partial(run_assessment, columns, excitations, configurations, **kwargs))

    from rockcli.report.tables import format_matrix, format_notes

    from rockcli.assess.verdicts import format_verdicts

    chk = None
    if check_tolerance:
        from rockcli.assess.table import check_tolerance as run_check

        chk = run_check(result)
    from rockcli.cli.assess_plinth import plinth_notes

    _echo_result(result, format_matrix(result), format_notes(result) + _vertical_note(result)
                 + plinth_notes(result, plinth_note), format_verdicts(result),
                 as_json=_assessment_json(result, columns, configurations, chk) if as_json else None)
    _warn_pulses(result, excitation)
    failed_runs = [r for r in result.rows if r.error and not any(x.label == r.record for x in result.failed)]
    if failed_runs:
        r = failed_runs[0]
        click.echo(f"Warning: {len(failed_runs)} run(s) failed; their rows carry the error (first: {r.column} / "
                   f"{r.record} / {r.configuration}: {r.error})", err=True)
    if chk is not None:
        from rockcli.cli.assess_runs import _echo_tolerance_check

        _echo_tolerance_check(chk, as_json)

    if csv_path:
        from rockcli.report.tables import write_assessment_csv

        write_assessment_csv(result, csv_path, check=chk)
        click.echo(f"wrote {csv_path} ({len(result.rows)} rows)", err=as_json)
    if hist_dir or plot_dir:
        from rockcli.cli.assess_runs import _write_histories

        _write_histories(result, hist_dir, plot_dir, as_json)
    if report_path:
        from rockcli.report.html import write_report
        from rockcli.report.html_pages import assessment_report

        write_report(report_path, assessment_report(result, check=chk, command=command_line()))
        click.echo(f"wrote {report_path} (HTML report)", err=as_json)


def _assessment_json(result, columns, configurations, check) -> dict:
    """``assess column --json``: the bodies, the configurations and one row per run (the CSV's columns)."""
    from rockcli.cli.assess_drums import drums_json
    from rockcli.report.tables import assessment_rows

    return {"columns": [{"name": b.name, "R_m": b.R, "alpha_deg": b.alpha_deg, "height_m": b.height,
                         "width_m": b.width, **_plinth_json(b), **drums_json(b)} for b in columns],
            "configurations": [{"header": c.header, "spec": c.spec, "isolation": c.label} for c in configurations],
            "rows": assessment_rows(result, check)}


def _plinth_json(b) -> dict:
    """A body on a plinth's plinth and assembly (``--on``), for ``--json``'s columns; nothing for a body alone."""
    if getattr(b, "plinth", None) is None:
        return {}
    from rockcli.cli.simulate_plinth import plinth_dict

    return {"body": b.body.name, "plinth": plinth_dict(b)}


@assess.command(name="fragility")
@click.argument("names", nargs=-1, metavar="NAME...")
@custom_block_options
@click.option("--records", "--record", "records", multiple=True, metavar="DIR|ID|FILE", cls=QuietSpellingOption,
              quiet_spellings=("--record",),
              help="The suite (repeatable, required): folders (every non-hidden file), catalogue ids, files. "
                   "A file that cannot be read becomes an error row; the others carry on.")
@_headerless_options
@azimuth_options(suite=True)
@vertical_options
@click.option("--isolation", "isolation", multiple=True, metavar="SPEC",
              help="Foundation (repeatable): 'none', 'linear:Tb=2.5,xi=0.1,gamma=0.01', 'scss:Tb=2,mu=0.05', "
                   "'lrb:...' or 'dcss:...' (see 'rockcli simulate --help'). Default: none and "
                   "linear Tb = 2, 2.5, 3 s with xi = 0.1 (gamma = 0.01), as in the paper's Table III. " + GAMMA_HELP)
@click.option("--im", type=click.Choice(["pga", "pgv", "ap"]), default="pga", show_default=True,
              help="Intensity measure: pga [g]; pgv [m/s] (trapezoid rule from rest, as 'records show'); "
                   "ap [g], the amplitude of the record's fitted Ricker pulse.")
@click.option("--bootstrap", "n_boot", type=Number(integer=True, lo=0, hi=100000), default=1000, show_default=True,
              help="Bootstrap resamples over records for the confidence intervals (0: none).")
@click.option("--seed", type=SEED, default=13, show_default=True, help="Seed of the bootstrap resamples.")
@click.option("--csv", "csv_path", type=click.Path(), default=None,
              help="Write one row per body x record x configuration (IM, scale, capacity, censoring, error) "
                   "with the fit of its body and configuration.")
@click.option("--plot", "plot_path", type=click.Path(), default=None,
              help="Write the fragility curves (one panel per body, every configuration) to this image, e.g. FILE.png.")
@click.option("--scheduler", default=None, metavar="tcp://HOST:PORT|local",
              help="Run the margin searches on a Dask cluster (pip install -e \".[dask]\"): the address of an "
                   "existing scheduler, or 'local' for a LocalCluster on this machine. Same results. A scheduler "
                   "that does not answer, has no worker or loses all its workers stops the run after "
                   "ROCKCLI_DASK_TIMEOUT seconds (default 60).")
@report_option
@json_option
@quiet_option
@horizon_option
@restitution_option
@plinth_option
@friction_option
@user_errors
def fragility(names, R, alpha, height, width, name, records, units, dt, isolation, im, n_boot, seed, csv_path,
              plot_path, scheduler, report_path, as_json, horizon, restitution, plinth_spec, friction):
    """Fragility curves of overturning: P(the body overturns | IM) from a suite of records.

    NAME is a body as in 'assess column' (a preset column, or a custom block). Each record is
    scaled (0.1x..4x, then bisection) to the smallest factor that overturns the body; that factor
    x the record's IM is its capacity. A lognormal (median, beta) is fitted to the capacities by
    maximum likelihood, records that never overturn up to 4x counting as right-censored, with
    intervals from a bootstrap over records. Prints median and beta per body and configuration,
    and each isolated median over the rigid one (< 1: isolation hurts).

    \b
    Examples:
      rockcli assess fragility bassae nemea --records ../shared/records --records ../shared/records/extra \\
          --csv fragility.csv --plot fragility.png
      rockcli assess fragility nemea --records ../shared/records --units g --dt 0.01 --im pgv --isolation none

    A suite of 30 records takes minutes; for a quick look take a few of its files and one
    configuration: --glob 'RSN11*' --isolation none --bootstrap 100.
    """
    from rockcli.assess import parse_configurations, resolve_excitations
    from rockcli.assess.fragility import count_fragility_runs, run_fragility
    from rockcli.solve import validate_options

    validate_options(horizon=horizon)
    solver = _restitution_kw(restitution)
    columns = _columns(names, R, alpha, height, width, name)
    from rockcli.cli.assess_drums import refuse_drums_in_fragility

    refuse_drums_in_fragility(columns)
    if not records:
        raise InputError("give the record suite with --records DIR|ID|FILE (repeatable)")
    configurations = parse_configurations(isolation)
    plinth_note = ""
    if plinth_spec is not None:  # each body alone and on the plinth (rockcli.cli.assess_plinth)
        from rockcli.cli.assess_plinth import with_plinth

        columns, configurations, plinth_note = with_plinth(columns, configurations, plinth_spec,
                                                           isolation_given=bool(isolation),
                                                           refused=(("--scheduler", scheduler),))
    columns, configurations, friction_note = with_friction(
        columns, configurations, friction, isolation_given=bool(isolation), restitution=restitution)
    plinth_note = " ".join(n for n in (plinth_note, friction_note) if n)
    check_outputs((csv_path, "--csv", False), (plot_path, "--plot", True),
                  (report_path, "--report", REPORT_SUFFIXES))
    if scheduler is not None:
        from rockcli.distributed import check_scheduler

        check_scheduler(scheduler)
    given = given_azimuth()
    azimuth = given["azimuth"]
    if azimuth == "worst" and report_path:
        raise InputError("--report shows one fragility per configuration: with --azimuth worst (two, the median "
                         "and the worst orientation) write --csv and --plot instead, or give one --azimuth DEG")
    excitations, unavailable = resolve_excitations(records, "record", units=units, dt=dt, gain=given_gain(),
                                                   azimuth=azimuth, component=given_component(),
                                                   azimuth_step=given["step"] if azimuth == "worst" else None,
                                                   **given_suite())
    _refuse_if_none_can_run(excitations, unavailable)
    excitations = _with_vertical(excitations, configurations, units, dt)
    _refuse_if_none_can_run(excitations)
    _add_record_inputs(excitations)

    run, n_runs = run_fragility, count_fragility_runs(columns, excitations, configurations)
    if azimuth == "worst":
        from rockcli.assess.fragility_azimuth import run_fragility_azimuths
        from rockcli.records.orientation import sweep_azimuths

        azimuths = sweep_azimuths(given["step"])
        run, n_runs = partial(run_fragility_azimuths, azimuths=azimuths), n_runs * len(azimuths)
    if scheduler is not None:
        from rockcli.assess.fragility import run_fragility_distributed
        from rockcli.cli.options import dask_client

        client = dask_client(scheduler)
        with progress_bar(n_runs, "margin search on Dask") as bar:  # the run announces it in scenes
            result = run_fragility_distributed(client, columns, excitations, configurations, im=im, n_boot=n_boot,
                                               seed=seed, unavailable=unavailable, horizon=horizon, run=run,
                                               progress=bar, **solver)
    else:
        result = _run_counted(n_runs, partial(run, columns, excitations, configurations, im=im, n_boot=n_boot,
                                              seed=seed, unavailable=unavailable, horizon=horizon, **solver))
    if azimuth == "worst":
        return _echo_fragility_azimuths(result, solver, csv_path, plot_path, len(azimuths), as_json)

    from rockcli.report.fragility import format_fragility, format_fragility_notes

    from rockcli.cli.assess_plinth import plinth_notes

    notes = format_fragility_notes(result) + _vertical_note(result) + plinth_notes(result, plinth_note)
    if solver:
        notes += f"\nImpacts: coefficient of restitution E = {solver['restitution']:g} (docs/simulate.md, Restitution)."
    _echo_result(result, format_fragility(result), notes, as_json=_fragility_json(result, solver) if as_json else None)
    if csv_path:
        from rockcli.report.fragility import write_fragility_csv

        write_fragility_csv(result, csv_path, solver)  # a given --restitution as a column
        click.echo(f"wrote {csv_path} ({len(result.rows)} rows)", err=as_json)
    if plot_path:
        from rockcli.report.fragility import plot_fragility

        plot_fragility(result, plot_path)
        click.echo(f"wrote {plot_path}", err=as_json)
    if report_path:
        from rockcli.report.html import write_report
        from rockcli.report.html_pages import fragility_report

        write_report(report_path, fragility_report(result, command=command_line(),
                                                   restitution=solver.get("restitution")))
        click.echo(f"wrote {report_path} (HTML report)", err=as_json)


def _fragility_json(fr, solver) -> dict:
    """``assess fragility --json``: one fit per column and configuration, and one row per run (the CSV's)."""
    from rockcli.report.fragility import fragility_rows

    return {"im": fr.im.key, "im_column": fr.im.column, "ci_level": fr.level, "n_boot": fr.n_boot, "seed": fr.seed,
            **solver,
            "curves": [{"column": c.column, "configuration": c.configuration.header,
                        "isolation": c.configuration.label, "median": c.median, "median_ci": list(c.median_ci),
                        "beta": c.beta, "beta_ci": list(c.beta_ci), "median_ratio_to_none": c.ratio_to_rigid,
                        "n_records": c.n_records, "n_censored": c.n_right + c.n_left} for c in fr.curves],
            "rows": fragility_rows(fr)}


def _echo_fragility_azimuths(results: dict, solver: dict, csv_path, plot_path, n_azimuths: int, as_json=False):
    """``assess fragility --azimuth worst``: both fits and the worst azimuths
    (:func:`rockcli.report.fragility.format_fragility_azimuths`), or with ``--json`` both fits as
    ``{"median": ..., "worst": ...}`` (each as without --azimuth worst); the CSV (both sets of rows) and the
    figure (the worst orientation's curves)."""
    from rockcli.report.fragility import format_fragility_azimuths

    table, notes = format_fragility_azimuths(results, n_azimuths)
    if solver:
        notes += f"\nImpacts: coefficient of restitution E = {solver['restitution']:g} (docs/simulate.md, Restitution)."
    _echo_result(results["worst"], table, notes,
                 as_json={"azimuths_run": n_azimuths, **{k: _fragility_json(results[k], solver)
                                                         for k in ("median", "worst")}} if as_json else None)
    if csv_path:
        from rockcli.report.fragility import write_fragility_csv

        write_fragility_csv([results["median"], results["worst"]], csv_path, solver)
        click.echo(f"wrote {csv_path} ({sum(len(r.rows) for r in results.values())} rows)", err=as_json)
    if plot_path:
        from rockcli.report.fragility import plot_fragility

        plot_fragility(results["worst"], plot_path)
        click.echo(f"wrote {plot_path} (the worst orientation's curves)", err=as_json)