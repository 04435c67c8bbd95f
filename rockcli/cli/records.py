"""``rockcli records``: the record catalogue and a look at any record file."""

from __future__ import annotations

import click

from rockcli.cli.errors import user_errors
from rockcli.cli.options import Group, add_inputs, check_outputs, echo_json, json_option, record_kwargs, record_options


@click.group(name="records", cls=Group)
def records():
    """Ground-motion records: the paper's catalogue and any accelerogram file."""


def _status_rows() -> list[dict]:
    from rockcli.records.catalog import find_file, load_catalog
    from rockcli.records.components import orientation_meta

    rows = []
    for e in load_catalog():
        path = find_file(e) if e.available else None
        status = "not available" if not e.available else ("found" if path else "missing")
        comps = []
        for comp, file in e.components:
            found = find_file(e, file) if e.available else None
            orient = orientation_meta(comp, "catalogue")
            comps.append({"component": comp, "file": file, "azimuth_deg": orient["azimuth_deg"],
                          "vertical": orient["vertical"], "path": str(found) if found else None})
        rows.append({"id": e.id, "event": e.event, "year": e.year, "station": e.station,
                     "component": e.component, "mw": e.mw, "distance_km": e.distance_km,
                     "pga_published_g": e.pga_published_g, "pgv_published_mps": e.pgv_published_mps,
                     "file": e.file, "status": status, "path": str(path) if path else "",
                     "components": comps, "present": _present(comps), "former_ids": list(e.aliases)})
    return rows


def _present(comps: list[dict]) -> str:
    """The components a row names, each marked when its file is missing: ``230+140``, ``000+090 (090 missing)``."""
    if not comps:
        return "-"
    missing = [c["component"] for c in comps if c["path"] is None]
    text = "+".join(c["component"] or "?" for c in comps)
    return text + (f" ({', '.join(missing)} missing)" if missing and len(missing) < len(comps) else "")


def _fmt(value, spec: str) -> str:
    return "-" if value is None else format(value, spec)


@records.command(name="list")
@click.option("--csv", "csv_path", type=click.Path(), default=None,
              help="Also write the table to this CSV file.")
@json_option
@user_errors
def list_records(csv_path, as_json):
    """List the catalogue and, for each id, whether and where its file was found.

    Files are looked up in the folders of ROCKCLI_RECORDS (path list), then in the repository's
    records/ folder. The components column names the components a row gives (230+140: two horizontal
    ones, usable with --azimuth; UP: the vertical one), with those whose file is missing.

    \b
    Examples:
      ROCKCLI_RECORDS=../shared/records rockcli records list
      ROCKCLI_RECORDS=../shared/records rockcli records list --json --csv records.csv
    """
    from rockcli.records.catalog import search_path

    check_outputs((csv_path, "--csv", False))
    rows = _status_rows()
    add_inputs([c["path"] for r in rows for c in r["components"]], "the record file")
    found = sum(r["status"] == "found" for r in rows)
    if as_json:
        echo_json({"records": rows, "found": found, "searched": [str(p) for p in search_path()]})
    else:
        _echo_list(rows, found, search_path())
    if csv_path:
        from rockcli.report.records import write_list_csv

        write_list_csv(rows, csv_path)
        click.echo(f"wrote {csv_path}", err=as_json)


def _echo_list(rows, found, searched) -> None:
    table = [("id", "event", "PGA [g]", "PGV [m/s]", "components", "status", "path")]
    for r in rows:
        table.append((r["id"], f"{r['event']} {r['year']}", _fmt(r["pga_published_g"], ".2f"),
                      _fmt(r["pgv_published_mps"], ".2f"), r["present"], r["status"],
                      r["path"] or r["file"] or "-"))
    widths = [max(len(row[i]) for row in table) for i in range(len(table[0]) - 1)]
    for row in table:
        click.echo("  ".join(cell.ljust(w) for cell, w in zip(row, widths)) + "  " + row[-1])
    click.echo(f"\n{found} of {len(rows)} files found; PGA/PGV are the published values (Table II). "
               f"Searched: {', '.join(str(p) for p in searched)}")
    former = [f"{a} (now {r['id']})" for r in rows for a in r["former_ids"]]
    if former:
        click.echo(f"Former ids, still accepted: {', '.join(former)}.")


@records.command(name="show")
@click.argument("source")
@record_options(column_alias=True)
@click.option("--plot", "plot_path", type=click.Path(), default=None,
              help="Plot acceleration, velocity and displacement to this image (e.g. FILE.png).")
@json_option
@user_errors
def show(source, units, dt, fmt, column, plot_path, as_json):
    """Print npts, dt, duration, PGA and PGV of SOURCE (a file or a catalogue id).

    PGV is computed by trapezoidal integration of the record as given (from rest), and again
    after removing a straight line fitted to the velocity (linear baseline); both are printed.
    A file of several components lists them (pick one with --component).

    \b
    Examples:
      ROCKCLI_RECORDS=../shared/records rockcli records show kobe-1995-takarazuka-000 --plot kobe.png
      rockcli records show ../shared/records/C02-065 --units g --dt 0.01 --json
      rockcli records show ../shared/records/extra/20161113_110259_WTMC_20.V2A
    """
    from rockcli.records import read_record
    from rockcli.records.motion import calc_peaks

    from rockcli.records.components import MultiComponent

    check_outputs((plot_path, "--plot", True))
    kwargs = record_kwargs(units, dt, fmt, column)
    try:
        rec = read_record(source, **kwargs)
    except MultiComponent:
        _list_components(source, kwargs, as_json)
        return
    add_inputs([rec.meta.get("path")], "the record")
    from rockcli.records.at2 import rsn_of

    peaks = calc_peaks(rec)
    meta = rec.meta
    former = meta.get("catalog_id") and meta["catalog_id"] != source
    lines = [("record", rec.name + (f" (asked as {source}, its former id)" if former else ""))]
    if meta.get("path"):
        lines.append(("file", meta["path"]))
    lines.append(("format", str(meta.get("format", ""))))
    for key in ("event", "station"):
        if meta.get(key):
            lines.append((key, str(meta[key])))
    rsn = rsn_of(meta.get("path") or "")
    if rsn is not None:
        lines.append(("PEER RSN", f"{rsn} (the NGA record sequence number, from the file's name)"))
    lines.append(("component", _component_text(rec)))
    if meta.get("catalog_id"):
        from rockcli.records.catalog import get_entry

        others = [c for c, _ in get_entry(meta["catalog_id"]).components if c != meta.get("component")]
        if others:
            lines.append(("other components", f"{', '.join(others)} (--component NAME; two horizontal ones: "
                                              f"--azimuth DEG|worst)"))
    lines += [
        ("units in file", f"{meta.get('units')} (from the {meta.get('units_source')}; x{meta.get('factor'):.6g} to m/s^2)"),
        ("npts", str(rec.npts)),
        ("dt", f"{rec.dt:.6g} s (from the {meta.get('dt_source')})"),
        ("duration", f"{rec.duration:.3f} s"),
        ("start time", f"{rec.t_start:.6g} s"),
        ("PGA", f"{peaks.pga_g:.4f} g ({rec.pga:.4f} m/s^2)"),
        ("PGV", f"{peaks.pgv_mps:.4f} m/s (trapezoidal integration of the record as given, from rest)"),
        ("PGV, linear baseline", f"{peaks.pgv_linear_mps:.4f} m/s (linear fit removed from the velocity)"),
        ("PGD, linear baseline", f"{peaks.pgd_m:.4f} m"),
    ]
    if meta.get("processing"):
        lines.append(("processing", str(meta["processing"])))
    if as_json:
        from rockcli.records.components import component_name, orientation_text

        echo_json({"record": rec.name, "file": meta.get("path"), "format": meta.get("format"),
                   "event": meta.get("event"), "station": meta.get("station"), "rsn": rsn,
                   "component": component_name(rec),
                   "orientation": orientation_text(rec), "units_in_file": meta.get("units"),
                   "units_source": meta.get("units_source"), "factor_to_mps2": meta.get("factor"),
                   "npts": rec.npts, "dt_s": rec.dt, "dt_source": meta.get("dt_source"), "duration_s": rec.duration,
                   "t_start_s": rec.t_start, "pga_g": peaks.pga_g, "pga_mps2": rec.pga, "pgv_mps": peaks.pgv_mps,
                   "pgv_linear_baseline_mps": peaks.pgv_linear_mps, "pgd_linear_baseline_m": peaks.pgd_m,
                   "processing": meta.get("processing")})
    else:
        width = max(len(k) for k, _ in lines)
        for key, value in lines:
            click.echo(f"{key.ljust(width)}  {value}")
    if plot_path:
        from rockcli.report.records import plot_record

        plot_record(rec, plot_path, baseline="linear")
        click.echo(f"wrote {plot_path} (velocity and displacement with the linear baseline)", err=as_json)


def _component_text(rec) -> str:
    from rockcli.records.components import component_name, orientation_text

    source = rec.meta.get("orientation_source")
    return f"{component_name(rec)} ({orientation_text(rec)}" + (f"; from the {source})" if source else ")")


def _list_components(source, kwargs, as_json=False) -> None:
    """A multi-component file: one line per component (name, orientation, npts, dt, PGA)."""
    from rockcli.records.reader import read_components

    kwargs = {k: v for k, v in kwargs.items() if k not in ("column", "component")}
    comps = read_components(source, **kwargs)
    add_inputs([comps[0].meta.get("path")], "the record")
    first = comps[0]
    if as_json:
        from rockcli.records.components import component_name, orientation_text

        echo_json({"file": first.meta.get("path", source), "format": first.meta.get("format"),
                   "station": first.meta.get("station"),
                   "components": [{"component": component_name(r), "orientation": orientation_text(r),
                                   "npts": r.npts, "dt_s": r.dt, "pga_g": r.pga_g, "pga_mps2": r.pga} for r in comps]})
        return
    click.echo(f"{first.meta.get('path', source)}: {len(comps)} components ({first.meta.get('format')}"
               + (f", station {first.meta['station']}" if first.meta.get("station") else "") + ")")
    rows = [("component", "orientation", "npts", "dt [s]", "PGA [g]", "PGA [m/s^2]")]
    for rec in comps:
        from rockcli.records.components import component_name, orientation_text

        rows.append((component_name(rec), orientation_text(rec), str(rec.npts), f"{rec.dt:.6g}",
                     f"{rec.pga_g:.4f}", f"{rec.pga:.4f}"))
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    for r in rows:
        click.echo("  ".join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
    click.echo("pick one with --component NAME (a channel code as listed, N, E, UP, or an azimuth in degrees)")


@records.command(name="export")
@click.argument("source")
@click.argument("out", type=click.Path())
@record_options(column_alias=True)
@user_errors
def export(source, out, units, dt, fmt, column):
    """Write one component of SOURCE as a plain text record OUT (m/s^2, its dt in a comment), which rockcli
    reads back sample for sample: ``rockcli records show OUT``.

    \b
    Example:
      rockcli records export ../shared/records/extra/20161113_110259_WTMC_20.V2A wtmc-n28w.txt --component N28W
    """
    from rockcli.io.files import write_text
    from rockcli.records import read_record
    from rockcli.records.components import record_text

    check_outputs((out, "OUT", False))
    rec = read_record(source, **record_kwargs(units, dt, fmt, column))
    add_inputs([rec.meta.get("path")], "the record")
    write_text(out, record_text(rec))
    click.echo(f"wrote {out} ({rec.npts} samples, dt = {rec.dt:g} s, m/s^2; component {_component_text(rec)})")
