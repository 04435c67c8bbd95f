"""``rockcli assess column``: which columns survive which records, on the ground and on isolators."""

from __future__ import annotations

import sys

import click

from rockcli.cli.errors import InputError, user_errors


@click.group(name="assess")
def assess():
    """Assess free-standing bodies against records and isolation configurations."""


def _headerless_options(func):
    """``--units`` and ``--dt`` for record files that do not state them (headerless text, SAC, ...)."""
    func = click.option("--dt", type=float, default=None, metavar="SECONDS",
                        help="Time step [s] of the record files that state none; a file that states "
                             "another one is an error row. Catalogue files are read as the catalogue says.")(func)
    return click.option("--units", default=None, metavar="UNITS",
                        help="Units of the record files that do not state them (g, m/s^2, cm/s^2, gal, "
                             "mm/s^2, g/10); a file that states other units is an error row.")(func)


def _progress(total: int):
    """A progress bar with an ETA on stderr when it is a terminal, else nothing (a context manager)."""
    import contextlib

    if not sys.stderr.isatty():
        return contextlib.nullcontext(None)
    return click.progressbar(length=total, label="runs", file=sys.stderr, show_eta=True)


def _warn_failed(failed, n_total: int):
    if failed:
        click.echo(f"Warning: {len(failed)} of {n_total} records could not be read or run; they have "
                   f"error rows: {', '.join(x.label for x in failed[:5])}{' ...' if len(failed) > 5 else ''}",
                   err=True)


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
    return columns


@assess.command(name="column")
@click.argument("names", nargs=-1, metavar="NAME...")
@click.option("--R", "R", type=float, default=None, metavar="M",
              help="Custom block: semi-diagonal R [m] (with --alpha).")
@click.option("--alpha", type=float, default=None, metavar="DEG", help="Custom block: slenderness [deg] (with --R).")
@click.option("--height", type=float, default=None, metavar="M", help="Custom block: full height [m] (with --width).")
@click.option("--width", type=float, default=None, metavar="M",
              help="Custom block: base width or drum diameter [m] (with --height).")
@click.option("--name", default="custom", show_default=True, help="Name of the custom block.")
@click.option("--records", "records", multiple=True, metavar="ID|FILE|DIR",
              help="Records to run (repeatable): catalogue ids, files, folders. Default: the catalogue's "
                   "Table II records (file where found on ROCKCLI_RECORDS, else the catalogued pulse).")
@_headerless_options
@click.option("--excitation", type=click.Choice(["auto", "record", "pulse"]), default="auto", show_default=True,
              help="Catalogue records: the file where found else its fitted Ricker pulse (auto), files only "
                   "(record), or the pulses only (pulse).")
@click.option("--isolation", "isolation", multiple=True, metavar="SPEC",
              help="Foundation (repeatable): 'none' or 'linear:Tb=2.5,xi=0.1,gamma=0.01'. Default: the paper's "
                   "Table III set: none and linear Tb = 2, 2.5, 3 s with xi = 0.1 (gamma = 0.01).")
@click.option("--margin/--no-margin", default=True, show_default=True,
              help="Find the smallest scale factor of each record that overturns (0.1x..4x scan, then bisection).")
@click.option("--neighbourhood", is_flag=True,
              help="Also run 0.90x..1.10x of each record (21 factors) and report the share that overturns.")
@click.option("--csv", "csv_path", type=click.Path(dir_okay=False), default=None,
              help="Write the report: one row per column x record x configuration.")
@click.option("--histories", "hist_dir", type=click.Path(file_okay=False), default=None,
              help="Write one time-history CSV per run into this folder.")
@click.option("--plot", "plot_dir", type=click.Path(file_okay=False), default=None,
              help="Write one figure per run (like the paper's Figure 12) into this folder.")
@user_errors
def column(names, R, alpha, height, width, name, records, units, dt, excitation, isolation, margin, neighbourhood,
           csv_path, hist_dir, plot_dir):
    """Do the columns NAME... survive the records, on a rigid base and on isolators?

    NAME is a preset (bassae, nemea) or a custom block NAME:R=<m>,alpha=<deg> or
    NAME:height=<m>,width=<m>; --R/--alpha or --height/--width add one more block (--name).
    Prints, per column, a table records x configurations (survives with peak |theta|/alpha,
    or OVERTURNS; xS is the smallest scale factor of the record that overturns) and how many
    records each configuration survives.

    \b
    Examples:
      ROCKCLI_RECORDS=../shared/records rockcli assess column bassae nemea --csv table.csv
      rockcli assess column statue:R=1.2,alpha=14 --records kobe-1995-takarazuka-000 --isolation none
      rockcli assess column nemea --records RSN983_NORTHR_JGB022.AT2 --isolation linear:Tb=3 --plot figs
    """
    from pathlib import Path

    from rockcli.assess import count_runs, parse_configurations, resolve_excitations, run_assessment

    columns = _columns(names, R, alpha, height, width, name)
    configurations = parse_configurations(isolation)
    for folder, opt in ((hist_dir, "--histories"), (plot_dir, "--plot")):
        if folder is not None and Path(folder).exists() and not Path(folder).is_dir():
            raise InputError(f"{opt} {folder}: exists and is not a folder")
    if csv_path is not None and not Path(csv_path).resolve().parent.is_dir():
        raise InputError(f"--csv {csv_path}: folder {Path(csv_path).resolve().parent} does not exist")
    excitations, unavailable = resolve_excitations(records, excitation, units=units, dt=dt)
    if not excitations:
        raise InputError("no record to run: " + "; ".join(f"{u.label}: {u.reason}" for u in unavailable))

    total = count_runs(columns, excitations, configurations, margin, neighbourhood)
    with _progress(total) as bar:
        result = run_assessment(columns, excitations, configurations, margin=margin, neighbourhood=neighbourhood,
                                unavailable=unavailable, progress=bar.update if bar else None)
        if bar:
            bar.update(total)

    from rockcli.report.tables import format_matrix, format_notes

    click.echo(format_matrix(result))
    click.echo("")
    click.echo(format_notes(result))
    _warn_failed(result.failed, len(result.excitations))

    if csv_path:
        from rockcli.report.tables import write_assessment_csv

        write_assessment_csv(result, csv_path)
        click.echo(f"wrote {csv_path} ({len(result.rows)} rows)")
    if hist_dir or plot_dir:
        _write_histories(result, hist_dir, plot_dir)


def _write_histories(result, hist_dir, plot_dir):
    from pathlib import Path

    from rockcli.assess import history_runs, safe_name
    from rockcli.report.response import plot_response, write_history_csv
    n = 0
    for folder in (hist_dir, plot_dir):
        if folder:
            Path(folder).mkdir(parents=True, exist_ok=True)
    for row, block, conf, x, resp in history_runs(result):
        stem = safe_name(row.column, row.record, row.configuration)
        label = x.label + (" (catalogued pulse)" if x.kind == "pulse" else "")
        if hist_dir:
            write_history_csv(resp, block, Path(hist_dir) / f"{stem}.csv")
        if plot_dir:
            plot_response(resp, block, conf.foundation, f"{block.name}, {label}, {conf.label}",
                          Path(plot_dir) / f"{stem}.png")
        n += 1
    what = " and ".join(f"{k} in {d}" for k, d in (("histories", hist_dir), ("figures", plot_dir)) if d)
    click.echo(f"wrote {what} ({n} runs)")
