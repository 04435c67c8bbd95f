"""``rockcli fit-pulse``: the dominant acceleration pulse (a_p, T_p) of records, by wavelet fit."""

from __future__ import annotations

import click

from rockcli.cli.errors import InputError, user_errors
from rockcli.cli.options import Command, add_inputs, catalog_file, check_outputs, json_option, record_kwargs, record_options
from rockcli.cli.types import Number

#: Pulse columns of records/catalog.csv that ``--update-catalog`` fills, and their rounding.
_CATALOG_DIGITS = {"a_p_g": 4, "T_p_s": 4, "t0_s": 3, "pulse_energy": 4}


def _catalog_sources(warn):
    """(id, None) for every available catalogue entry whose file is found; warn about the others."""
    from rockcli.records.catalog import find_file, load_catalog, search_path

    out, missing = [], []
    for e in load_catalog():
        if not e.available:
            continue
        if find_file(e) is None:
            missing.append(e.id)
        else:
            out.append(e.id)
    if missing:
        warn(f"skipped {len(missing)} catalogue record(s) whose file is not on the search path "
             f"({', '.join(str(p) for p in search_path())}): {', '.join(missing)}")
    if not out:
        raise InputError("no catalogue record file was found; set ROCKCLI_RECORDS to the folder holding them")
    return out


def _table(fits) -> str:
    head = ("record", "wavelet", "a_p_g", "T_p_s", "t0_s", "energy_fraction")
    rows = [head]
    for f in fits:
        flag = "*" if f.at_period_bound else ""
        rows.append((f.record_name, f.wavelet, f"{f.a_p_g:+.4f}", f"{f.T_p_s:.4f}{flag}", f"{f.t0_s:.3f}",
                     f"{f.energy_fraction:.3f}"))
    widths = [max(len(r[i]) for r in rows) for i in range(len(head))]
    right = {2, 3, 4, 5}
    lines = ["  ".join(c.rjust(w) if i in right else c.ljust(w) for i, (c, w) in enumerate(zip(r, widths))).rstrip()
             for r in rows]
    return "\n".join(lines)


def _candidate_row(c, rank, fit) -> dict:
    """A candidate pulse as a JSON/CSV row: its rank, whether it is the fit, and its parameters."""
    row = c.as_row()
    return {"rank": rank, "fit": c.pulse == fit.pulse, **{k: row[k] for k in (
        "wavelet", "pulse_shape", "a_p_g", "T_p_s", "t0_s", "energy_fraction", "at_period_bound")}}


def _candidates_table(fits, candidates) -> str:
    head = ("record", "rank", "wavelet", "a_p_g", "T_p_s", "t0_s", "energy_fraction", "")
    rows = [head]
    for f, cands in zip(fits, candidates):
        for k, c in enumerate(cands, 1):
            flag = "*" if c.at_period_bound else ""
            rows.append((f.record_name if k == 1 else "", str(k), c.wavelet, f"{c.a_p_g:+.4f}", f"{c.T_p_s:.4f}{flag}",
                         f"{c.t0_s:.3f}", f"{c.energy_fraction:.3f}", "<- fit" if c.pulse == f.pulse else ""))
    widths = [max(len(r[i]) for r in rows) for i in range(len(head))]
    right = {1, 3, 4, 5, 6}
    lines = ["  ".join(c.rjust(w) if i in right else c.ljust(w) for i, (c, w) in enumerate(zip(r, widths))).rstrip()
             for r in rows]
    lines.append("energy_fraction: share of the record's energy (integral of a^2 dt) that the pulse explains on its "
                 "own; pulses overlapping in time and period (centres within half the longer period, periods "
                 "within a factor 1.41) count as one.")
    return "\n".join(lines)


def _update_catalog(fits):
    """Fill the pulse columns of the fitted catalogue rows in place: every other column (a user's own
    too), cell, row and line ending stays as it was; a linked catalogue stays a link, its mode stays."""
    import csv
    import io

    from rockcli.io.files import write_text
    from rockcli.records.catalog import catalog_path

    path = catalog_path()
    raw = path.read_bytes()
    text = raw.decode("utf-8-sig")
    newline = "\r\n" if "\r\n" in text else "\n"
    rows = list(csv.reader(io.StringIO(text, newline="")))
    head = rows[0]
    col = {name: head.index(name) for name in ("id", *_CATALOG_DIGITS, "pulse_shape")}
    by_id = {f.record_name: f for f in fits}
    for row in rows[1:]:
        f = by_id.get(row[col["id"]]) if len(row) > col["id"] else None
        if f is None:
            continue
        row.extend([""] * (len(head) - len(row)))
        values = {"pulse_shape": f.pulse.shape, "a_p_g": f.a_p_g, "T_p_s": f.T_p_s, "t0_s": f.t0_s,
                  "pulse_energy": f.energy_fraction}
        for name, value in values.items():
            row[col[name]] = value if name == "pulse_shape" else repr(round(float(value), _CATALOG_DIGITS[name]))
    out = io.StringIO()
    csv.writer(out, lineterminator=newline).writerows(rows)
    bom = "\ufeff" if raw.startswith(b"\xef\xbb\xbf") else ""
    write_text(path, bom + out.getvalue(), "--update-catalog")
    return path


@click.command(name="fit-pulse", cls=Command)
@click.argument("sources", nargs=-1, metavar="SOURCE...")
@record_options(column_alias=True)
@click.option("--catalog", "use_catalog", is_flag=True,
              help="Fit every available catalogue record (files found on ROCKCLI_RECORDS).")
@click.option("--wavelet", type=click.Choice(["best", "symmetric", "antisymmetric"], case_sensitive=False),
              default="best", show_default=True,
              help="Symmetric Ricker (Eq 5, pywt 'mexh'), antisymmetric Ricker (Eq 6, 'gaus3'), or the one "
                   "that explains more of the record's energy.")
@click.option("--periods", default="0.1:6", show_default=True, metavar="MIN:MAX",
              help="Range of pulse periods T_p searched [s].")
@click.option("--csv", "csv_path", type=click.Path(), default=None,
              help="Also write the fits to this CSV file.")
@json_option
@click.option("--plot", "plot_path", type=click.Path(), default=None,
              help="Overlay each fitted pulse on its record (one panel per record) in this image, e.g. FILE.png.")
@click.option("--candidates", "n_candidates", type=Number(integer=True, lo=1, hi=20), default=None, metavar="N",
              help="List the N strongest distinct pulses of each record (local maxima of the wavelet transform, "
                   "both shapes, each refined like the fit), with the energy each explains alone.")
@click.option("--update-catalog", is_flag=True,
              help="With --catalog: store the fitted pulse (pulse_shape, a_p_g, T_p_s, t0_s, pulse_energy) "
                   "in records/catalog.csv (or ROCKCLI_CATALOG).")
@user_errors
def fit_pulse(sources, units, dt, fmt, column, use_catalog, wavelet, periods, csv_path, as_json, plot_path,
              n_candidates, update_catalog):
    """Fit the dominant acceleration pulse of each SOURCE (a record file or a catalogue id).

    The pulse is the symmetric or antisymmetric Ricker wavelet (Vassiliou & Makris 2011) that is
    closest to the record in the least-squares sense: largest continuous-wavelet-transform
    coefficient, refined off the scale grid. Prints one row per record: amplitude a_p [g] (signed),
    period T_p [s], centre t0 [s, record time] and the fraction of the record's energy (integral of
    a^2 dt) the pulse explains. A * after T_p marks a period at an end of --periods. With
    --candidates N: the N strongest distinct pulses of each record, ranked by the energy each
    explains alone (the fit is marked), e.g. where a published T_p differs from the fit.

    \b
    Examples:
      rockcli fit-pulse ../shared/records/RSN1119_KOBE_TAZ000.AT2
      rockcli fit-pulse ../shared/records/C02-065 --units g --dt 0.01 --wavelet antisymmetric
      ROCKCLI_RECORDS=../shared/records rockcli fit-pulse --catalog --plot fits.png
      ROCKCLI_RECORDS=../shared/records rockcli fit-pulse --catalog --update-catalog
      ROCKCLI_RECORDS=../shared/records rockcli fit-pulse kobe-1995-takarazuka-000 --candidates 3
    """
    from rockcli.pulses_fit import parse_periods

    period_range = parse_periods(periods)
    options_given = any(v is not None for v in (units, dt, fmt, column))
    if update_catalog and not use_catalog:
        raise InputError("--update-catalog needs --catalog (it stores the fits of all catalogue records)")
    if use_catalog and options_given:
        raise InputError("--units, --dt, --format and --record-column apply to files, not to --catalog records "
                         "(the catalogue states them)")
    if update_catalog and n_candidates:
        raise InputError("--update-catalog stores the fit only; leave out --candidates")
    if not sources and not use_catalog:
        raise InputError("give at least one SOURCE (a record file or catalogue id), or --catalog")
    check_outputs((csv_path, "--csv", False), (plot_path, "--plot", True),
                  (catalog_file() if update_catalog else None, "--update-catalog", False),
                  catalogue_is_input=not update_catalog)

    warnings = []
    jobs = [(s, record_kwargs(units, dt, fmt, column)) for s in sources]
    if use_catalog:
        jobs += [(i, {}) for i in _catalog_sources(warnings.append)]

    from rockcli.pulses_fit import fit_pulse as fit
    from rockcli.records import read_record

    records = [read_record(source, **kwargs) for source, kwargs in jobs]
    add_inputs([rec.meta.get("path") for rec in records], "the record")
    fits, candidates = [], []
    for rec in records:
        fits.append(fit(rec, wavelet.lower(), periods=period_range))
        if n_candidates:
            from rockcli.pulses_fit import fit_pulse_candidates

            candidates.append(fit_pulse_candidates(rec, n_candidates, wavelet.lower(), periods=period_range))

    if as_json:
        import json

        out = []
        for f in fits:
            row = f.as_row()
            row["periods_s"] = list(f.periods)
            if f.alternative is not None:
                a = f.alternative
                row["alternative"] = {"wavelet": a.wavelet, "a_p_g": a.a_p_g, "T_p_s": a.T_p_s, "t0_s": a.t0_s,
                                      "energy_fraction": a.energy_fraction}
            if n_candidates:
                row["candidates"] = [_candidate_row(c, k, f) for k, c in enumerate(candidates[len(out)], 1)]
            out.append(row)
        click.echo(json.dumps(out, indent=2))
    else:
        click.echo(_candidates_table(fits, candidates) if n_candidates else _table(fits))
        if any(f.at_period_bound for f in fits) or any(c.at_period_bound for cs in candidates for c in cs):
            click.echo(f"* T_p at an end of the searched range {period_range[0]:g}:{period_range[1]:g} s; "
                       f"widen --periods to check.")
    for f in fits:
        if f.periods[0] > period_range[0]:
            warnings.append(f"{f.record_name}: periods searched from {f.periods[0]:g} s only (4 time steps), "
                            f"not {period_range[0]:g} s")
        if f.periods[1] < period_range[1]:
            warnings.append(f"{f.record_name}: periods searched up to {f.periods[1]:g} s only, the record's "
                            f"duration (a longer pulse cannot be fitted), not {period_range[1]:g} s")
    for w in warnings:
        click.echo(f"Warning: {w}", err=True)

    if csv_path:
        from rockcli.report.pulses import write_candidates_csv, write_fit_csv

        if n_candidates:
            write_candidates_csv(fits, candidates, csv_path)
        else:
            write_fit_csv(fits, csv_path)
        click.echo(f"wrote {csv_path}", err=as_json)
    if plot_path:
        from rockcli.report.pulses import plot_pulse_fits

        plot_pulse_fits(records, fits, plot_path, candidates=candidates or None)
        click.echo(f"wrote {plot_path}", err=as_json)
    if update_catalog:
        path = _update_catalog(fits)
        click.echo(f"updated the pulse columns of {len(fits)} record(s) in {path}", err=as_json)
