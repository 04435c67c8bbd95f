"""The optional ``formats`` extra (USGS gmprocess): agency formats rockcli does not read itself (issue 24 item 1).

Without the extra, every such file is refused with one sentence naming it; with it (``pip install -e
".[formats]"``), every file of ``records/formats`` loads each channel with the peak of its SOURCES.csv.
"""

from __future__ import annotations

import csv
import subprocess
import sys

import pytest

from rockcli.records.reader import read_components
from rockcli.errors import RockcliInputError


@pytest.fixture(scope="module")
def formats_rows(records_dirs):
    for d in records_dirs:
        if (d / "formats" / "SOURCES.csv").is_file():
            with open(d / "formats" / "SOURCES.csv", newline="") as fh:
                return d / "formats", list(csv.DictReader(fh))
    pytest.skip("records/formats not found in ROCKCLI_RECORDS")


def test_refusals_name_the_extra(formats_rows, monkeypatch):
    """Without the extra (or with it, pretended absent): every agency file it would read is refused in one
    sentence naming it."""
    from rockcli.records import extra

    monkeypatch.setattr(extra, "available", lambda: False)
    folder, rows = formats_rows
    refused = 0
    for name in sorted({r["file"] for r in rows}):
        try:
            read_components(folder / name)
        except RockcliInputError as exc:
            assert 'pip install "rockcli[formats]"' in str(exc), str(exc)
            assert str(exc).count("\n") == 0
            refused += 1
    assert refused >= 8  # SMC, USC, BHRC, UNAM, DMG x2, GeoNet V1A x2, RENADIC x2


def test_the_extra_is_imported_only_when_needed(find_record):
    code = ("import sys; from rockcli.records import read_record; read_record(sys.argv[1]); "
            "print('gmprocess' in sys.modules)")
    out = subprocess.run([sys.executable, "-c", code, str(find_record("RSN1119_KOBE_TAZ000.AT2"))],
                         capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_every_format_loads_with_the_extra(formats_rows):
    pytest.importorskip("gmprocess")
    folder, rows = formats_rows
    by_file = {}
    for r in rows:
        by_file.setdefault(r["file"], []).append(r)
    for name, chans in by_file.items():
        comps = read_components(folder / name)  # CWB .dat: read by rockcli itself, U N E as its header orders them
        assert len(comps) == len(chans), name
        for row in chans:
            demeaned = comps[0].meta.get("format") == "KNET"  # rockcli's K-NET path: the header's Max. Acc.
            want = float(row["peak_demeaned" if demeaned else "peak"])
            got = [c.pga * 100.0 for c in comps]  # m/s^2 -> cm/s^2
            assert any(abs(g - want) <= 2e-3 * want + 1e-9 for g in got), (name, row["channel"], want, got)
            az = row["horizontal_orientation"]
            if az not in ("", "nan") and not row["channel"].endswith("Z"):
                assert any(c.meta.get("azimuth_deg") is not None and abs(c.meta["azimuth_deg"] - float(az) % 360) < 1e-6
                           for c in comps), (name, az)


def test_gmprocess_configuration_parsed_once_is_a_fresh_parse():
    """The configuration rockcli hands gmprocess's readers (parsed once per process, then copied) equals a
    fresh parse, each call gets its own copy, and gmprocess's own function is back after the read."""
    pytest.importorskip("gmprocess")
    import gmprocess.core.stationtrace as trace_module
    from gmprocess.utils.config import get_config

    from rockcli.records.extra import _config_parsed_once

    before = trace_module.get_config
    with _config_parsed_once() as once:
        first, second = once(), once()
        assert trace_module.get_config is once
    assert trace_module.get_config is before
    fresh = get_config()
    assert first == fresh and second == fresh
    first["read"]["sac_source"] = "edited by a reader"
    assert second["read"]["sac_source"] == fresh["read"]["sac_source"]

    def containers(x):  # every dict and list of a configuration, by identity
        inner = x.values() if isinstance(x, dict) else x if isinstance(x, list) else ()
        return [id(x)] * isinstance(x, (dict, list)) + [i for v in inner for i in containers(v)]

    assert not set(containers(second)) & set(containers(once()))  # no container shared between two calls


def test_cosmos_units_as_gmprocess_converts_them(tmp_path, monkeypatch):
    """gmprocess's COSMOS reader multiplies a file in g by 980.665 (to cm/s^2) but leaves ``units`` = "g": the
    samples are read as the cm/s^2 they are, not converted a second time (a stand-in for read_data here)."""
    import types

    import numpy as np
    from obspy import Trace

    from rockcli.records.extra import read_with_extra

    data = np.array([0.0, 49.0, -98.0665, 12.5])  # cm/s^2, as gmprocess returns them
    tr = Trace(data=data, header={"delta": 0.01, "network": "AK", "station": "BMR", "channel": "HN1"})
    tr.stats.standard = {"units": "g", "units_type": "acc", "source_format": "cosmos", "horizontal_orientation": 40.0}
    fake = types.ModuleType("gmprocess.io.read")
    fake.read_data = lambda path: [[tr]]
    monkeypatch.setitem(sys.modules, "gmprocess", types.ModuleType("gmprocess"))
    monkeypatch.setitem(sys.modules, "gmprocess.io", types.ModuleType("gmprocess.io"))
    monkeypatch.setitem(sys.modules, "gmprocess.io.read", fake)
    import logging

    level = logging.getLogger().level
    out = read_with_extra(tmp_path / "x.V1", None)
    assert out["units"] == "cm/s^2" and out["meta"]["azimuth_deg"] == 40.0
    assert logging.getLogger().level == level  # quiet while gmprocess reads, then as it was
    tr.stats.standard = {**tr.stats.standard, "source_format": "esm", "units": "g"}  # other readers: as stated
    assert read_with_extra(tmp_path / "x.V1", None)["units"] == "g"
