"""The optional ``formats`` extra: USGS gmprocess reads the agency formats rockcli's own readers do not.

``pip install -e ".[formats]"`` installs gmprocess (about 1.8 GB with OpenQuake and GIS libraries), so it
is never imported unless a file is not recognised by rockcli's own readers and ObsPy, or is one of the
formats rockcli recognises only to refuse (USGS SMC, USC Volume I, BHRC VOL1, UNAM ASA 2.0): then
:func:`read_with_extra` calls ``gmprocess.io.read.read_data`` (ObsPy traces in cm/s^2 with each channel's
orientation in ``stats.standard``). Without the extra, those files are refused with one sentence that
names it (:data:`INSTALL_HINT`).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from rockcli.errors import RockcliInputError

#: How to get the extra, quoted in refusals.
INSTALL_HINT = "the optional extra reads it: pip install \"rockcli[formats]\" (USGS gmprocess)"


#: Units of a COSMOS file that gmprocess 2.8 converts to cm/s^2 while ``stats.standard.units`` keeps the file's
#: word (``gmprocess.io.cosmos.core``: ``data *= UNIT_CONVERSIONS[unit]``): taken as the cm/s^2 they are.
_COSMOS_CONVERTED = {"g", "g/10", "g*10", "mg", "in/s/s"}


#: gmprocess has read a file in this process (its first read is the slow one: it loads its readers).
_loaded = False


def _containers_copied(value):
    """``value`` with each of its dicts and lists (a parsed YAML file's) copied as a plain dict or list, all the way
    down; anything else (a number, a string: immutable) as it is."""
    if isinstance(value, dict):
        return {k: _containers_copied(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_containers_copied(v) for v in value]
    return value


class _config_parsed_once:
    """While a file is read, gmprocess's default configuration is parsed once per process, not once per trace.

    gmprocess 2.8 builds every trace (``StationTrace.__init__``) and ``read_data`` itself with
    ``get_config()`` when no configuration is passed, and most of its readers pass none: each call parses
    the package's YAML file anew with ruamel (about 0.5 s of CPU; 124 parses, three quarters of the time, to
    read the 17 files of ``records/extra``). Exact: ``get_config()`` without a folder reads only the file
    installed with gmprocess and validates it, so a copy of its first result is what every later call would
    return. The copy is of the containers (plain dicts and lists, each call its own, so that a reader that edits
    its configuration edits its own); the values in them are ruamel's immutable scalars, shared. A deep copy of
    ruamel's commented containers cost 50 ms a call. A call with a folder, or any other call, goes to gmprocess
    unchanged; the two module names are restored on the way out. tests/test_records_extra.py compares the copy
    with a fresh parse."""

    _parsed = None

    def __enter__(self):
        import gmprocess.core.stationtrace as trace_module
        import gmprocess.io.read as read_module

        self._modules = [m for m in (trace_module, read_module) if hasattr(m, "get_config")]
        self._saved = [m.get_config for m in self._modules]
        original = self._saved[0]

        def get_config(config_path=None):
            if config_path is not None:
                return original(config_path)
            if _config_parsed_once._parsed is None:
                _config_parsed_once._parsed = _containers_copied(original())
            return _containers_copied(_config_parsed_once._parsed)

        for m in self._modules:
            m.get_config = get_config
        return get_config

    def __exit__(self, *exc):
        for m, saved in zip(self._modules, self._saved):
            m.get_config = saved
        return False


def available() -> bool:
    """True when gmprocess is installed (found without importing it)."""
    import importlib.util

    try:
        return importlib.util.find_spec("gmprocess") is not None
    except (ImportError, ValueError):
        return False


def read_with_extra(path: Path, column, recognised: str | None = None) -> dict[str, Any]:
    """The ``column``-th trace (1-based) gmprocess reads from ``path``, as the readers' dict (values in the units
    gmprocess states, dt, orientation); several traces without ``column``: :class:`MultiComponent`.
    ``recognised``: the format rockcli recognised (a file gmprocess cannot read is then an error, not
    :class:`NotARecord`)."""
    import logging
    import warnings

    from rockcli.records.components import NotARecord, orientation_meta, pick_trace

    global _loaded
    if not _loaded:  # the first read_data loads gmprocess's readers: seconds without a sign of life otherwise
        from rockcli.progress import announce

        how = (f"reading {Path(path).name} with gmprocess (the formats extra" if recognised else
               f"{Path(path).name}: no built-in reader recognises it; trying gmprocess (the formats extra")
        announce(f"{how}; its first file takes 5-20 s while it loads its readers) ...")
        _loaded = True
    root = logging.getLogger()
    level = root.level
    root.setLevel(max(level, logging.ERROR))  # gmprocess logs every file it reads; the level is restored after
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            from gmprocess.io.read import read_data

            try:
                with _config_parsed_once():
                    streams = read_data(str(path))
            except (KeyboardInterrupt, SystemExit, GeneratorExit):
                raise
            except BaseException as exc:  # noqa: BLE001 -- gmprocess raises many kinds (its DMG reader a bare
                # BaseException for a damaged header); one sentence for the user
                from rockcli.records.reader import reason_words

                if recognised:  # rockcli knows the format: a damaged or unusual file, not a non-record
                    from rockcli.records.formats import FORMAT_NAMES

                    raise RockcliInputError(f"{path}: a {FORMAT_NAMES.get(recognised, recognised)} file that "
                                            f"gmprocess cannot read either{reason_words(exc)}") from None
                raise NotARecord(f"{path}: format not recognised by rockcli, ObsPy or gmprocess"
                                 f"{reason_words(exc)}; give it with --format, or convert the record to text "
                                 f"(a column of accelerations, read with --units and --dt)") from None
    finally:
        root.setLevel(level)
    traces = [tr for st in streams for tr in st]
    tr = pick_trace(traces, column, path, ", ".join(t.stats.channel for t in traces), "components")
    std = tr.stats.get("standard", {})
    if str(std.get("units_type", "acc")) != "acc":
        raise RockcliInputError(f"{path}: gmprocess reads {std.get('units_type')}, not acceleration")
    units = str(std.get("units", "") or "")
    if str(std.get("source_format", "")).lower() == "cosmos" and units.lower() in _COSMOS_CONVERTED:
        units = "cm/s^2"  # gmprocess's COSMOS reader converts the samples to cm/s^2 but keeps the file's label
    units = {"cm/s/s": "cm/s^2", "cm/s**2": "cm/s^2"}.get(units, units) or None
    channel = str(tr.stats.channel)
    orient = orientation_meta(channel, "gmprocess")
    if not orient["vertical"]:  # HN1/HN2: the azimuth is in gmprocess's station metadata (its orientation)
        az = std.get("horizontal_orientation", math.nan)
        if az is not None and math.isfinite(float(az)):
            orient = orientation_meta(channel, "gmprocess: horizontal_orientation", azimuth=float(az))
    values = np.asarray(tr.data, dtype=np.float64)
    meta = {"station": ".".join(x for x in (tr.stats.network, tr.stats.station) if x and x != "--"),
            "component": channel, "trace_id": tr.id, "starttime": str(tr.stats.starttime),
            "reader": "gmprocess", "source_format": str(std.get("source_format", "")),
            "processing": f"read by gmprocess {_version()} ({std.get('source_format', '?')} reader)", **orient}
    return {"values": values, "dt": float(tr.stats.delta), "dt_source": "extra (gmprocess)", "units": units,
            "units_source": "extra (gmprocess)",
            "t_start": 0.0, "meta": meta, "format": f"GMPROCESS_{str(std.get('source_format', '')).upper()}"}


def _version() -> str:
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("gmprocess")
    except PackageNotFoundError:
        return "?"
