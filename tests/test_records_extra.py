"""The optional ``formats`` extra (USGS gmprocess): agency formats rockcli does not read itself (issue 24 item 1).

Without the extra, every such file is refused with one sentence naming it; with it (``pip install -e
".[formats]"``), every file of ``records/formats`` loads each channel with the peak of its SOURCES.csv.
"""

from __future__ import annotations

import csv
import subprocess
import sys

import pytest

from rockcli.records.extra import available
from rockcli.records.reader import read_components
from rockcli.errors import RockcliInputError


@pytest.fixture(scope="module")
def formats_rows(records_dirs):
    for d in records_dirs:
        if (d / "formats" / "SOURCES.csv").is_file():
            with open(d / "formats" / "SOURCES.csv", newline="") as fh:
                return d / "formats", list(csv.DictReader(fh))
    pytest.skip("records/formats not found in ROCKCLI_RECORDS")


def test_refusals_name_the_extra(formats_rows):
    if available():
        pytest.skip("the formats extra is installed: these files load")
    folder, rows = formats_rows
    refused = 0
    for name in sorted({r["file"] for r in rows}):
        try:
            read_components(folder / name)
        except RockcliInputError as exc:
            if "choose one with --record-column" in str(exc):
                continue  # CWB .dat: a text table rockcli reads column by column
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
        comps = read_components(folder / name)
        if len(comps) == 1 and len(chans) > 1:
            continue  # a text table (CWB .dat) read by rockcli itself, column by column
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
