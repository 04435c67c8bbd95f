"""``--azimuth worst`` when nothing lifts the body off (issue 35): one definition of the most adverse
orientation for ``simulate`` and ``assess column``, and none named when every orientation ranks equal
(it used to print "worst azimuth: 0 deg" and "overturning azimuths: none deg" where ``assess column``
said @50)."""

from __future__ import annotations

import json
import math

import numpy as np
import pandas as pd
import pytest
from click.testing import CliRunner

from rockcli.assess.azimuth import adverse_key, most_adverse
from rockcli.cli import main

NAN = math.nan


def test_the_ranking_and_its_ties():
    rocked = [adverse_key(False, NAN, p) for p in (0.2, 0.7, 0.4)]
    assert most_adverse(rocked) == 1  # the largest peak
    over = rocked + [adverse_key(True, 8.0, NAN), adverse_key(True, 5.5, NAN)]
    assert most_adverse(over) == 4  # an overturn beats any peak; the earliest first
    assert most_adverse([adverse_key(True, NAN, NAN), adverse_key(False, NAN, 0.9)]) == 0  # early stop: no time
    calm = [adverse_key(False, NAN, 0.0)] * 4  # nothing lifts off
    assert most_adverse(calm) is None and most_adverse(calm[:1]) == 0 and most_adverse([]) is None
    # with margins (assess column): the smallest overturning scale first, NaN (none up to 4x) last
    margins = [adverse_key(False, NAN, 0.0, s) for s in (NAN, 2.31, 1.8, NAN)]
    assert most_adverse(margins) == 2
    assert most_adverse([adverse_key(False, NAN, 0.0, NAN)] * 3) is None
    tied = [adverse_key(False, NAN, 0.0, 2.0), adverse_key(False, NAN, 0.0, 2.0), adverse_key(False, NAN, 0.0, 3.0)]
    assert most_adverse(tied) == 0  # the first of equals when some other is less adverse


def _write(path, acc_g, dt=0.01):
    path.write_text(f"# dt={dt} sec\n# units: g\n" + "\n".join(f"{v:.12e}" for v in acc_g) + "\n")
    return path


@pytest.fixture()
def calm_pair(tmp_path):
    """A one-sine pulse of 0.32 g along azimuth 60 seen by sensors at 0 and 90: below the uplift of a block of
    alpha = 20 deg (tan 20 deg = 0.364 g) in every orientation, but it topples it at a larger scale."""
    t = np.arange(0, 6, 0.01)
    motion = 0.32 * np.sin(2 * np.pi * t / 0.8) * (t < 0.8)
    north = _write(tmp_path / "n.txt", motion * math.cos(math.radians(60)))
    east = _write(tmp_path / "e.txt", motion * math.sin(math.radians(60)))
    return f"{north}@0", f"{east}@90"


def test_simulate_names_no_worst_azimuth_when_nothing_lifts_off(calm_pair):
    north, east = calm_pair
    base = ["simulate", "--R", "0.8", "--alpha", "20", "--record", north, "--record-2", east, "--azimuth", "worst",
            "--azimuth-step", "30"]
    res = CliRunner().invoke(main, base)
    assert res.exit_code == 0, res.output
    assert "<- worst" not in res.output and "none deg" not in res.output
    assert res.output.splitlines()[-1].startswith("worst azimuth: none (the block does not lift off its base in any "
                                                  "orientation, so no orientation is worse than another)")
    out = json.loads(CliRunner().invoke(main, [*base, "--json"]).output)
    assert set(out["verdicts"]) == {"no_uplift"} and out["worst_azimuth_deg"] is None
    assert out["worst_verdict"] == "no_uplift" and out["overturning_azimuths_deg"] == []


def test_assess_column_agrees(calm_pair, tmp_path):
    """Without margins no orientation is named (@any, azimuth_deg empty); with them the most adverse is the one
    of the smallest margin: the motion's own direction, 60 deg, whose run at 1x is the no-uplift simulate saw."""
    north, east = calm_pair
    args = ["assess", "column", "b:R=0.8,alpha=20", "--isolation", "none", "--records", f"{north}+{east}",
            "--azimuth", "worst", "--azimuth-step", "30"]
    res = CliRunner().invoke(main, [*args, "--no-margin", "--csv", str(tmp_path / "a.csv")])
    assert res.exit_code == 0, res.output
    assert "no uplift @any" in res.output and "@0" not in res.output
    assert "@any: no orientation is more adverse than another: none lifts the body off at 1x." in res.output
    df = pd.read_csv(tmp_path / "a.csv")
    assert math.isnan(df.azimuth_deg[0]) and df.verdict[0] == "no_uplift" and df.overturning_azimuths[0] == "none"

    res = CliRunner().invoke(main, [*args, "--csv", str(tmp_path / "b.csv")])
    assert res.exit_code == 0, res.output
    df = pd.read_csv(tmp_path / "b.csv")
    assert df.azimuth_deg[0] == 60.0 and df.verdict[0] == "no_uplift" and 1.0 < df.overturn_scale[0] < 4.0
    assert "@60" in res.output and "@any" not in res.output
    one = CliRunner().invoke(main, [*args[:6], f"{north}+{east}", "--azimuth", "60", "--csv", str(tmp_path / "c.csv")])
    assert one.exit_code == 0, one.output
    assert pd.read_csv(tmp_path / "c.csv").overturn_scale[0] == df.overturn_scale[0]


def test_the_stroke_is_the_largest_over_the_orientations_it_survives(calm_pair, tmp_path):
    """On bearings the stroke is the largest peak base displacement over the orientations in which the body
    survives, not the most adverse orientation's (here no orientation lifts the body off: the row is the first
    orientation's, 0 deg, which feels half the motion along 60 deg). Checked against simulate at each azimuth."""
    from rockcli.models import Block, LinearIsolation
    from rockcli.records.orientation import project, read_pair, sweep_azimuths
    from rockcli.solve import simulate

    north, east = calm_pair
    res = CliRunner().invoke(main, ["assess", "column", "b:R=0.8,alpha=20", "--isolation", "linear:Tb=2.5",
                                    "--records", f"{north}+{east}", "--azimuth", "worst", "--azimuth-step", "30",
                                    "--no-margin", "--csv", str(tmp_path / "a.csv")])
    assert res.exit_code == 0, res.output
    row = pd.read_csv(tmp_path / "a.csv").iloc[0]
    assert row.verdict == "no_uplift" and math.isnan(row.azimuth_deg)
    pair = read_pair(north, east)
    block, bearings = Block(0.8, math.radians(20)), LinearIsolation(2.5, 0.1, 0.01)
    each = {float(t): simulate(block, bearings, project(*pair, t)) for t in sweep_azimuths(30)}
    assert all(r.verdict == "no_uplift" for r in each.values())
    stroke = max(r.base_disp_max_m for r in each.values())
    assert row.base_disp_max_m == pytest.approx(each[0.0].base_disp_max_m, rel=1e-5)  # the row: the first's (CSV %.6g)
    assert row.base_disp_max_surviving_azimuths_m == pytest.approx(stroke, rel=1e-5)
    assert stroke > 1.5 * row.base_disp_max_m  # what the bug reported as the stroke was well short of it
    assert (f"over the orientations in which it survives, the base moves up to {stroke:.2f} m (the stroke the "
            f"bearings must allow)") in " ".join(res.output.split())


def test_stroke_words_over_orientations():
    """stroke_m and the sentences on fabricated rows: the most adverse orientation toppled, others survived; none
    survived; a row of one azimuth (no sweep) keeps its own displacement, and none when it toppled."""
    from types import SimpleNamespace

    from rockcli.assess.verdicts import configuration_sentence, scene_sentence, stroke_m, survivor_stroke

    def row(record, overturned, disp, over_all=NAN, run=None):
        return SimpleNamespace(record=record, overturned=overturned, proven=True, error="", verdict="overturned"
                               if overturned else "rocked", theta_max_over_alpha=NAN if overturned else 0.3,
                               t_overturn_s=4.0 if overturned else NAN, overturn_scale=NAN, margin_note="",
                               overturn_share_pm10=NAN, base_disp_max_m=disp, azimuths_run=run,
                               base_disp_max_surviving_azimuths_m=over_all)

    mixed = row("a+b", True, 0.6, over_all=0.25, run=36)  # toppled at its worst azimuth, survived elsewhere
    fallen = row("c+d", True, 0.7, run=36)  # toppled in every orientation
    plain = row("e", False, 0.4)
    assert stroke_m(mixed) == 0.25 and math.isnan(stroke_m(fallen)) and stroke_m(plain) == 0.4
    assert math.isnan(stroke_m(row("f", True, 0.9)))
    assert survivor_stroke([mixed, fallen]) is mixed and survivor_stroke([fallen]) is None
    assert "over the orientations in which it survives, the base moves up to 0.25 m" in scene_sentence(
        mixed, isolated=True)
    assert "it survives in none of the 36 orientations: no stroke to give" in scene_sentence(fallen, isolated=True)
    assert ("over the orientations in which it survives, the base moves up to 0.25 m (a+b; the stroke the bearings "
            "must allow)") in configuration_sentence([mixed, fallen], isolated=True)
