"""Reusable click options (rasterio style): one decorator per group of options."""

from __future__ import annotations

import click


def record_options(func):
    """Add ``--units``, ``--dt``, ``--format`` and ``--column``: what ``read_record`` takes.

    The command receives them as the keyword arguments ``units``, ``dt``, ``fmt`` and ``column``.
    """
    options = [
        click.option("--units", default=None, metavar="UNITS",
                     help="Units of the values in the file (g, m/s^2, cm/s^2, gal, mm/s^2, g/10); "
                          "needed when the file does not state them."),
        click.option("--dt", type=float, default=None, metavar="SECONDS",
                     help="Time step [s]; needed when the file states none (single-column text)."),
        click.option("--format", "fmt", default=None, metavar="NAME",
                     help="File format (PEER_AT2, TEXT, ESM, ITACA, COSMOS, GEONET_V2A, or an ObsPy "
                          "format such as SAC, MSEED, KNET); detected when omitted."),
        click.option("--column", type=int, default=None, metavar="N",
                     help="1-based column of a multi-column text file (a time column counts), or "
                          "component/trace of a multi-component file."),
    ]
    for option in reversed(options):
        func = option(func)
    return func


def record_kwargs(units, dt, fmt, column) -> dict:
    """The keyword arguments of ``read_record`` from the values of :func:`record_options`."""
    return {"units": units, "dt": dt, "format": fmt, "column": column}
