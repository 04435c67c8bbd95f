"""Small traps of a first hour with rockcli (issue 35 item 2): a size that looks like centimetres is warned
about, a record's component is named one way whichever way it is read, the fragility table speaks of the
body it assesses, and --restitution says that it is the rigid-ground ratio, which a base lowers."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.models.impact import impact_ratio
from rockcli.models import Block
from rockcli.models.block import PLAUSIBLE_SIZE_M, size_warning

ROOT = Path(__file__).resolve().parents[1]


# --------------------------------------------------------------------------------------------------
# sizes that look like centimetres
# --------------------------------------------------------------------------------------------------

def test_the_size_rule():
    assert size_warning(Block.from_dimensions(1.8, 0.5, "statue")) == ""
    assert size_warning(Block.from_dimensions(32.2, 2.9, "obelisk")) == ""  # the Lateran obelisk
    assert size_warning(Block.from_dimensions(PLAUSIBLE_SIZE_M, 3.0, "tower")) == ""
    text = size_warning(Block.from_dimensions(180, 50, "statue"))
    assert text.startswith("statue is 180 m tall and 50 m wide") and text.endswith("give height=1.8,width=0.5")
    assert size_warning(Block.from_dimensions(20, 36, "slab"))  # the width alone
    tall = Block.from_degrees(93.0, 15.5, "R-form")  # R = 93 m: accepted (R up to 100 m), but warned
    assert size_warning(tall).startswith("R-form is 179 m tall")


@pytest.mark.parametrize("args", [
    ["simulate", "--body", "statue:height=180,width=50", "--pulse", "sine:ap=0.3,Tp=1"],
    ["simulate", "--height", "180", "--width", "50", "--name", "statue", "--pulse", "sine:ap=0.3,Tp=1"],
    ["assess", "column", "statue:height=180,width=50", "--records", "kobe-1995-takarazuka-000", "--excitation",
     "pulse", "--isolation", "none", "--no-margin"],
])
def test_a_180_m_statue_runs_with_a_warning(args):
    res = CliRunner().invoke(main, args)
    assert res.exit_code == 0, res.output
    assert res.stderr.startswith("Warning: statue is 180 m tall and 50 m wide, larger than any free-standing body")
    assert "if these are centimetres, give height=1.8,width=0.5" in res.stderr
    assert "Warning" not in res.stdout  # the results stay clean on stdout
    fine = [a.replace("180", "1.8").replace("width=50", "width=0.5") if a.startswith("statue:") else a for a in args]
    fine = ["1.8" if a == "180" else "0.5" if a == "50" else a for a in fine]
    res = CliRunner().invoke(main, fine)
    assert res.exit_code == 0 and "Warning" not in res.output, res.output


# --------------------------------------------------------------------------------------------------
# one name per component
# --------------------------------------------------------------------------------------------------

def test_a_component_is_named_alike_from_its_file_and_from_the_catalogue(find_record):
    from rockcli.records import read_record
    from rockcli.records.at2 import _parse_title

    by_file = read_record(str(find_record("RSN1119_KOBE_TAZ000.AT2")))  # the header says "Takarazuka, 0"
    by_id = read_record("kobe-1995-takarazuka-000")
    assert by_file.meta["component"] == by_id.meta["component"] == "000"
    assert by_file.meta["azimuth_deg"] == by_id.meta["azimuth_deg"] == 0.0
    assert _parse_title("Northridge-01, 1/17/1994, Jensen Filter Plant, 22")["component"] == "022"
    assert _parse_title("San Fernando, 2/9/1971, Pacoima Dam, 164")["component"] == "164"
    assert _parse_title("Loma Prieta, 10/18/1989, Gilroy, UP")["component"] == "UP"
    assert _parse_title("X, 1/1/2000, Y, 400")["component"] == "400"  # not an azimuth: as written


# --------------------------------------------------------------------------------------------------
# the fragility table names the body
# --------------------------------------------------------------------------------------------------

def test_the_fragility_printout_speaks_of_the_body():
    from rockcli.assess import parse_column_spec, parse_configurations, resolve_excitations, run_fragility
    from rockcli.report.fragility import format_fragility, format_fragility_notes

    xs, _ = resolve_excitations(["kobe-1995-takarazuka-000", "northridge-1994-jensen-generator-022"], "pulse")
    cabinet = parse_column_spec("cabinet:height=1.9,width=0.6")
    fr = run_fragility([cabinet], xs, parse_configurations(["none"]), n_boot=0)
    table, notes = format_fragility(fr), format_fragility_notes(fr)
    assert table.split()[:2] == ["body", "configuration"] and "\ncabinet" in table
    assert "overturns the cabinet (" in notes and "isolation makes the cabinet more fragile" in notes
    assert "column" not in table + notes
    two = run_fragility([cabinet, parse_column_spec("bassae")], xs, parse_configurations(["none"]), n_boot=0)
    assert "overturns the body (" in format_fragility_notes(two)


# --------------------------------------------------------------------------------------------------
# --restitution: the rigid-ground ratio, lowered by a base
# --------------------------------------------------------------------------------------------------

def test_restitution_is_the_rigid_ground_ratio_and_the_help_says_what_a_base_does():
    help_text = " ".join(CliRunner().invoke(main, ["simulate", "--help"]).output.split())
    assert "E is always this rigid-ground ratio" in help_text
    assert "lowers the ratio to (4 E - 3 gamma cos^2" in help_text
    alpha = math.radians(15.0)
    for gamma, expected in ((0.0, 0.9), (0.01, 0.8992953093335103), (0.5, 0.8461822993025251)):
        c = 3 * gamma * math.cos(alpha) ** 2
        assert impact_ratio(alpha, gamma, 0.9) == pytest.approx((3.6 - c) / (4 - c), rel=1e-14)
        assert impact_ratio(alpha, gamma, 0.9) == pytest.approx(expected, rel=1e-12) and expected <= 0.9
    assert impact_ratio(alpha, 0.5, 1.0) == pytest.approx(1.0)  # elastic on every base
    out = json.loads(CliRunner().invoke(main, ["simulate", "--R", "1", "--alpha", "15", "--pulse", "sine:ap=0.5,Tp=0.5",
                                               "--isolation", "linear:Tb=2,gamma=0.5", "--restitution", "0.9",
                                               "--json"]).output)
    assert out["restitution"] == 0.9 and out["impact_ratio"] == pytest.approx(0.8461822993025251, rel=1e-12)


def test_the_docs_say_it():
    physics = (ROOT / "docs" / "physics.md").read_text()
    assert "### A free plinth" in physics and "[a statue on its plinth](plinth.md)" in physics
    assert "### Restitution on an isolated base" in physics
    assert "counted from the record's first sample" in " ".join((ROOT / "docs" / "simulate.md").read_text().split())
    assert (ROOT / "docs" / "python.md").read_text().count("## Reference notes") == 1
