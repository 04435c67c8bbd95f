"""Record reports: the catalogue status table (CSV) and the acceleration/velocity/displacement figure.

matplotlib is imported inside the functions (Agg backend); nothing is written half-way: outputs go
to a temporary file in the target folder and are renamed into place.
"""

from __future__ import annotations

import csv
import io
import os
from pathlib import Path

from rockcli.io.files import check_output, save_figure, write_text

#: Columns of the ``rockcli records list --csv`` table.
LIST_COLUMNS = ("id", "event", "year", "station", "component", "mw", "distance_km", "pga_published_g",
                "pgv_published_mps", "file", "status", "path", "present")


def write_list_csv(rows: list[dict], path: str | os.PathLike) -> Path:
    """Write the catalogue status rows (dicts keyed by :data:`LIST_COLUMNS`) as CSV, atomically."""
    fh = io.StringIO()
    writer = csv.DictWriter(fh, fieldnames=LIST_COLUMNS, lineterminator="\n")
    writer.writeheader()
    for row in rows:
        writer.writerow({k: ("" if row.get(k) is None else row.get(k)) for k in LIST_COLUMNS})
    return write_text(path, fh.getvalue())


def plot_record(record, path: str | os.PathLike, baseline: str = "linear") -> Path:
    """Plot acceleration [g], velocity [m/s] and displacement [m] of a record to a PNG file.

    Parameters
    ----------
    record : Record
        The record.
    path : path-like
        Output image (format from the suffix, e.g. ``.png``).
    baseline : {"none", "linear"}
        Baseline treatment of the integration (see :func:`rockcli.records.motion.integrate`).
    """
    from rockcli.records.motion import integrate
    from rockcli.report.figures import new_figure, plain, pyplot, title
    from rockcli.io.units import G

    check_output(path, image=True)
    plt = pyplot()
    vel, disp = integrate(record, baseline)
    t = record.times
    fig = new_figure(8, 7)
    axes = fig.subplots(3, 1, sharex=True)
    for ax, y, label in zip(axes, (record.acc / G, vel, disp),
                            (r"acceleration $\ddot u_g$ [g]", r"velocity $\dot u_g$ [m/s]", "displacement $u_g$ [m]")):
        ax.plot(t, y, lw=0.7, color="k")
        ax.axhline(0.0, lw=0.4, color="0.6")
        ax.set_ylabel(label)
        ax.grid(True, lw=0.3, alpha=0.5)
    axes[-1].set_xlabel("time $t$ [s]")
    axes[-1].set_xlim(t[0], t[-1])
    treatment = ("trapezoidal integration, linear baseline removed from velocity" if baseline == "linear"
                 else "trapezoidal integration of the record as given")
    units = record.meta.get("units")
    title(fig, f"record {plain(record.name)}: PGA = {record.pga_g:.3g} g, {record.npts} samples, $\\Delta t$ = "
               f"{record.dt:g} s" + (f" (units as read: {units})" if units else "") + f"\n{treatment}", fontsize=9)
    try:
        return save_figure(fig, path, dpi=120)
    finally:
        plt.close(fig)
