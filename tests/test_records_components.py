"""Components of multi-component files: names, orientations, ``--component`` on every command (issue 24 item 2)."""

from __future__ import annotations

import csv
import shutil
from pathlib import Path

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.records import read_record
from rockcli.records.components import parse_orientation, select_component
from rockcli.records.reader import read_components


@pytest.mark.parametrize("text, expected", [
    ("140", (140.0, False)), ("022", (22.0, False)), ("360", (0.0, False)), ("0", (0.0, False)),
    ("N28W", (332.0, False)), ("S16W", (196.0, False)), ("S74E", (106.0, False)), ("N01E", (1.0, False)),
    ("S89E", (91.0, False)), ("N00W", (0.0, False)), ("E", (90.0, False)), ("-E", (None, False)),
    ("-242", (118.0, False)), ("+242", (242.0, False)), ("-S62W", (None, False)),
    ("NS", (0.0, False)), ("EW2", (90.0, False)), ("UD2", (None, True)), ("Up", (None, True)),
    ("DWN", (None, True)), ("HNE", (90.0, False)), ("HNN", (0.0, False)), ("HNZ", (None, True)),
    ("BNZ", (None, True)), ("HN1", (None, False)), ("HN2", (None, False)), ("FP", (None, False)),
    ("", (None, False)), ("400", (None, False)), ("N95E", (None, False)),
])
def test_parse_orientation(text, expected):
    assert parse_orientation(text) == expected


def _formats_rows(folder: Path, fmt: str):
    with open(folder / "SOURCES.csv", newline="") as fh:
        return [r for r in csv.DictReader(fh) if r["format"] == fmt]


def test_geonet_components_have_the_stated_orientations_and_peaks(records_dirs):
    """Every component of the GeoNet V2A sample: azimuth and peak [cm/s^2] as formats/SOURCES.csv states them."""
    folder = next((d / "formats" for d in records_dirs if (d / "formats" / "SOURCES.csv").is_file()), None)
    if folder is None:
        pytest.skip("records/formats not found in ROCKCLI_RECORDS")
    rows = _formats_rows(folder, "geonet")
    assert rows
    comps = read_components(folder / rows[0]["file"])
    assert len(comps) == 3
    by_peak = sorted(comps, key=lambda r: r.pga)
    for row in sorted(rows, key=lambda r: float(r["peak"])):
        rec = by_peak.pop(0)
        assert rec.pga * 100.0 == pytest.approx(float(row["peak"]), rel=1e-3)
        if row["horizontal_orientation"] != "nan":
            assert rec.meta["azimuth_deg"] == pytest.approx(float(row["horizontal_orientation"]))
        else:
            assert rec.meta["vertical"]


def test_select_component_by_code_letter_and_azimuth(find_record):
    path = find_record("20161113_110259_WTMC_20.V2A")
    comps = read_components(path)
    assert [c.meta["component"] for c in comps] == ["N28W", "S62W", "Up"]
    assert select_component(comps, "n28w", "f") is comps[0]
    assert select_component(comps, "332", "f") is comps[0]
    assert select_component(comps, "242", "f") is comps[1]
    assert select_component(comps, "UP", "f") is comps[2]
    assert select_component(comps, "z", "f") is comps[2]
    with pytest.raises(RockcliInputError, match=r"no component 'E' \(the file holds: N28W \(332 deg\)"):
        select_component(comps, "E", "f")
    # read_record(component=...) is the same samples as --column
    np.testing.assert_array_equal(read_record(path, component="S62W").acc, read_record(path, column=2).acc)
    with pytest.raises(RockcliInputError, match="either by --component NAME or by --record-column N"):
        read_record(path, component="S62W", column=2)


def test_at2_orientation_from_header_then_file_name(find_record, tmp_path):
    rec = read_record(find_record("RSN181_IMPVALL.H_H-E06140.AT2"))
    assert rec.meta["azimuth_deg"] == 140.0 and rec.meta["orientation_source"].startswith("AT2 header line 2")
    # a header whose component names no orientation: the file name's last three digits
    src = find_record("RSN181_IMPVALL.H_H-E06230.AT2")
    lines = src.read_text().splitlines(keepends=True)
    lines[1] = lines[1].replace(", 230", ", H2")
    named = tmp_path / "X_H-E06230.AT2"
    named.write_text("".join(lines))
    rec = read_record(named)
    assert rec.meta["azimuth_deg"] == 230.0 and rec.meta["orientation_source"] == "AT2 file name: component '230'"
    unnamed = tmp_path / "X_H-E06.AT2"
    unnamed.write_text("".join(lines))
    rec = read_record(unnamed)
    assert rec.meta["azimuth_deg"] is None and not rec.meta["vertical"]  # nothing guessed


def test_records_show_lists_components_and_picks_one(find_record):
    path = str(find_record("20161113_110259_WTMC_20.V2A"))
    res = CliRunner().invoke(main, ["records", "show", path])
    assert res.exit_code == 0, res.output
    assert "3 components" in res.output
    for line in ("N28W       332 deg", "S62W       242 deg", "Up         vertical"):
        assert line in res.output
    res = CliRunner().invoke(main, ["records", "show", path, "--component", "up"])
    assert res.exit_code == 0, res.output
    assert "Up (vertical; from the GEONET_V2A header" in res.output
    assert f"{read_record(path, column=3).pga_g:.4f} g" in res.output
    res = CliRunner().invoke(main, ["records", "show", path, "--component", "HNE"])
    assert res.exit_code == 2 and "no component 'HNE'" in res.output


def test_simulate_and_fragility_take_component(find_record, tmp_path):
    path = find_record("20161113_110259_WTMC_20.V2A")
    args = ["simulate", "--R", "1", "--alpha", "15", "--record", str(path), "--json"]
    by_name = CliRunner().invoke(main, [*args, "--component", "S62W"])
    by_column = CliRunner().invoke(main, [*args, "--record-column", "2"])
    assert by_name.exit_code == 0, by_name.output
    assert by_name.output == by_column.output
    # a suite: --component picks from multi-component files; one-component files are taken as they are
    folder = tmp_path / "suite"
    folder.mkdir()
    shutil.copy(path, folder / path.name)
    shutil.copy(find_record("RSN1119_KOBE_TAZ000.AT2"), folder / "kobe.AT2")
    res = CliRunner().invoke(main, ["assess", "fragility", "small:R=0.6,alpha=12", "--records", str(folder),
                                    "--isolation", "none", "--bootstrap", "0", "--component", "N28W",
                                    "--csv", str(tmp_path / "f.csv")])
    assert res.exit_code == 0, res.output
    import pandas as pd

    df = pd.read_csv(tmp_path / "f.csv", keep_default_na=False, na_values=[""]).set_index("record")
    assert df.error.isna().all()
    assert df.pga_g[path.name] == pytest.approx(read_record(path, column=1).pga_g, rel=1e-4)  # the CSV rounds
