"""``rockcli spectrum rocking``: a record's rocking spectrum, peak theta/alpha against the block size."""

from __future__ import annotations

import click

from rockcli.cli.errors import InputError, user_errors
from rockcli.cli.options import (Command, add_inputs, cap_ratio_option, check_outputs, echo_json, horizon_option,
                                 json_option, progress_bar, quiet_option, record_kwargs, record_options,
                                 restitution_option, scaled)
from rockcli.cli.spectrum_plinth import on_option
from rockcli.cli.types import NUMBER


@click.command(name="rocking", cls=Command)
@click.argument("source", metavar="SOURCE")
@click.option("--alpha", "alpha", required=True, metavar="DEG[,DEG...]",
              help="Block slenderness atan(b/h) [degrees]; a comma list gives one curve each.")
@click.option("--R", "R", default="0.2:20:200", show_default=True, metavar="START:STOP:COUNT",
              help="Block sizes (semi-diagonal R [m]): COUNT values from START to STOP, both included, evenly "
                   "spaced on the log axis.")
@click.option("--isolation", "isolations", multiple=True, default=("none",), show_default=True, metavar="SPEC",
              help="Foundation, repeatable (one curve each): 'none' (rigid) or a bearing as in 'rockcli simulate' "
                   "with its period in s, e.g. linear:Tb=2.5,xi=0.05,gamma=0.01 or scss:Tb=3,mu=0.05.")
@record_options
@click.option("--scale", type=NUMBER, default=1.0, show_default=True,
              help="Multiply the record's acceleration by this factor (negative: the record reversed).")
@click.option("--csv", "csv_path", type=click.Path(), default=None,
              help="Write one row per block size and curve (record, scale, alpha_deg, isolation, R_m, p_radps, "
                   "theta_max_over_alpha, overturned, uplift, proven, peak_final).")
@click.option("--plot", "plot_path", type=click.Path(), default=None,
              help="Draw peak theta/alpha against R (log axis, p on top), overturning marked at 1 (.png, .pdf, .svg).")
@json_option
@quiet_option
@click.option("--scheduler", default=None, metavar="tcp://HOST:PORT|local",
              help="Run the blocks in chunks on a Dask cluster (see 'rockcli spectrum overturning').")
@horizon_option
@restitution_option
@cap_ratio_option
@on_option
@user_errors
def rocking(source, alpha, R, isolations, units, dt, fmt, column, scale, csv_path, plot_path, as_json, scheduler,
            horizon, restitution, cap_ratio, plinth_spec):
    """Rocking spectrum of one record: peak |theta|/alpha against the block size R (Makris & Konstantinidis 2003).

    SOURCE is a record file or a catalogue id ('rockcli records list'). Every point is the block
    R, alpha on its foundation under the record, run to the end of the motion (the same run as
    'rockcli simulate --R R --alpha ALPHA --record SOURCE'); blocks that overturn are drawn at 1
    and marked. The rigid-foundation and isolated curves of one alpha on one figure show for which
    sizes isolation lowers the rocking under this record, and for which it raises it.

    \b
    Examples:
      rockcli spectrum rocking kobe-1995-takarazuka-000 --alpha 10 --R 0.2:20:200 --isolation none \\
          --isolation linear:Tb=2.5 --plot kobe.png
      rockcli spectrum rocking northridge-1994-jensen-generator-022 --alpha 8,12 --csv jensen.csv --json
    """
    import time

    from rockcli.models import parse_isolation_spec
    from rockcli.records import read_record
    from rockcli.spectra import parse_list, rocking_spectrum, size_grid

    alphas = parse_list(alpha, "--alpha", lo=0, hi=90, lo_open=True, hi_open=True)
    sizes = size_grid(R, "--R")
    foundations = list(dict.fromkeys(parse_isolation_spec(s) for s in isolations))
    from rockcli.io.inputs import check_scale, format_number

    check_scale(scale, 0.0, "--scale")  # and the record's peak times it, once read
    check_outputs((csv_path, "--csv", False), (plot_path, "--plot", True))
    from rockcli.cli.spectrum import _runner
    from rockcli.cli.spectrum_plinth import spectrum_plinths

    plinths = spectrum_plinths(plinth_spec, alphas, foundations, cap_ratio=cap_ratio, sizes=sizes)

    runner = _runner(scheduler, horizon, restitution, cap_ratio, foundations)
    record = read_record(source, **record_kwargs(units, dt, fmt, column))
    add_inputs([record.meta.get("path")], "the record")
    name = record.name
    record = scaled(record, scale, "--scale", "the record")
    n = len(alphas) * len(foundations) * len(plinths) * sizes.size
    t0 = time.perf_counter()
    with runner, progress_bar(n, "blocks") as bar:
        curves = rocking_spectrum(record, alphas, foundations, sizes, runner=runner,
                                  progress=bar.update if bar else None, plinths=plinths)
    elapsed = time.perf_counter() - t0
    from rockcli.cli.spectrum import _csv_options

    extra = _csv_options(runner)  # a given --restitution and --cap-ratio
    if csv_path:
        from rockcli.report.rocking import write_rocking_csv

        write_rocking_csv(curves, csv_path, name, scale, extra)
    if plot_path:
        from rockcli.report.figures import plain
        from rockcli.report.rocking import plot_rocking_spectrum

        shown = plain(name) + (f" x {format_number(scale)}" if scale != 1.0 else "")
        plot_rocking_spectrum(curves, plot_path, title=f"Rocking spectrum under {shown} (PGA {record.pga_g:.3g} g)")
    if as_json:
        from rockcli.report.rocking import rocking_json

        out = {"record": name, "scale": scale, "pga_g": record.pga_g, "runs": n, "peaks": "final (early=False)",
               **extra, "curves": rocking_json(curves)}
        echo_json(out)
    else:
        _echo_summary(curves, name, scale, record.pga_g, n, elapsed, runner)
    for path in (csv_path, plot_path):
        if path:
            click.echo(f"wrote {path}", err=as_json)


def _echo_summary(curves, name, scale, pga_g, n, elapsed, runner) -> None:
    """Per curve: the sizes that overturn and the largest peak that survives; per isolated curve: the
    sizes where it lowers or raises the peak of the rigid foundation's block of the same alpha."""
    import numpy as np

    from rockcli.cli.spectrum import _echo_unproven
    from rockcli.spectra import describe_sizes, isolation_helps, size_ranges

    from rockcli.io.inputs import format_number

    shown = name + (f" x {format_number(scale)}" if scale != 1.0 else "")
    click.echo(f"record {shown} (PGA {pga_g:.3f} g): {n} blocks, R {curves[0].R[0]:g}-{curves[0].R[-1]:g} m, "
               f"in {elapsed:.2f} s (every run to the end of the motion: peaks final)")
    rigid = {(c.alpha_deg, c.plinth): c for c in curves if c.isolation == "none"}
    alone = {(c.alpha_deg, c.isolation): c for c in curves if c.plinth is None}
    on = any(c.plinth is not None for c in curves)
    for c in curves:
        over = np.asarray(c.overturned, bool)
        alive = ~over & np.asarray(c.uplifted, bool)
        peak = f", largest surviving peak {c.theta_max_over_alpha[alive].max():.3f}" if alive.any() else ""
        where = "" if not on else (f" on {c.plinth.label}" if c.plinth is not None else " alone")
        click.echo(f"alpha = {c.alpha_deg:g} deg, {c.isolation}{where}: overturns at R = "
                   f"{describe_sizes(size_ranges(c.R, over))}{peak}; never uplifts at R = "
                   f"{describe_sizes(size_ranges(c.R, ~np.asarray(c.uplifted, bool)))}")
        base = rigid.get((c.alpha_deg, c.plinth))
        if base is not None and c is not base:
            helps = isolation_helps(base, c)
            hurts = isolation_helps(c, base)
            click.echo(f"  isolation lowers the peak at R = {describe_sizes(size_ranges(c.R, helps))}; raises it at "
                       f"R = {describe_sizes(size_ranges(c.R, hurts))}")
        base = alone.get((c.alpha_deg, c.isolation))
        if c.plinth is not None and base is not None:  # the body's own peak, alone and on its plinth
            helps = isolation_helps(base, c)
            hurts = isolation_helps(c, base)
            click.echo(f"  the plinth lowers the body's peak at R = {describe_sizes(size_ranges(c.R, helps))}; raises "
                       f"it at R = {describe_sizes(size_ranges(c.R, hurts))}")
    _echo_unproven(runner)
