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
