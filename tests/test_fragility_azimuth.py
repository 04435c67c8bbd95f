"""``assess fragility --azimuth worst``: capacities per orientation, fitted over the median orientation of each
pair and over the worst one (issue 24 item 3)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.assess import parse_configurations, resolve_excitations
from rockcli.assess.fragility import run_fragility
from rockcli.assess.fragility_azimuth import run_fragility_azimuths
from rockcli.cli import main
from rockcli.models import Block
from rockcli.records.orientation import sweep_azimuths


def _write(path, acc_g, dt=0.01):
    path.write_text(f"# dt={dt} sec\n# units: g\n" + "\n".join(f"{v:.10e}" for v in acc_g) + "\n")
    return path


def _pair(folder, along_deg, amplitude_g, period_s, name):
    """A one-sine pulse moving the ground along ``along_deg``, recorded by sensors at 0 (N) and 90 (E)."""
    t = np.arange(0, 8, 0.01)
    motion = amplitude_g * np.sin(2 * np.pi * t / period_s) * (t < period_s)
    n = _write(folder / f"{name}-n.txt", motion * math.cos(math.radians(along_deg)))
    e = _write(folder / f"{name}-e.txt", motion * math.sin(math.radians(along_deg)))
    return f"{n}@0+{e}@90"


@pytest.fixture()
def suite(tmp_path):
    """Three pairs moving along 60, 20 and 135 deg with different amplitudes and periods."""
    return [_pair(tmp_path, 60.0, 0.9, 0.8, "a"), _pair(tmp_path, 20.0, 0.7, 1.0, "b"),
            _pair(tmp_path, 135.0, 1.1, 0.6, "c")]


def test_capacities_per_orientation(suite):
    """Each pair's worst capacity is the smallest of its orientations' (the orientation of its motion), its median
    one the median orientation's; each equals the margin of a run at that one azimuth, at the pair's IM (the
    median of its projections' PGAs)."""
    block = Block(R=0.8, alpha=math.radians(14))
    confs = parse_configurations(["none"])
    step = 30.0
    azimuths = sweep_azimuths(step)
    xs, _ = resolve_excitations(suite, "record", azimuth="worst")
    res = run_fragility_azimuths([block], xs, confs, azimuths=azimuths, n_boot=50)
    median, worst = res["median"], res["worst"]
    along = {"a": 60.0, "b": 20.0, "c": 135.0}
    for x, rm, rw in zip(xs, median.rows, worst.rows):
        assert rm.record == rw.record == x.label and not rm.error and not rw.error
        # each orientation on its own (the projection onto it, as --azimuth DEG runs it)
        per = {}
        for theta in azimuths:
            one, _ = resolve_excitations([s for s in suite if s.startswith(x.pair[0].meta["path"])], "record",
                                         azimuth=float(theta))
            r = run_fragility([block], one, confs, n_boot=0).rows[0]
            per[float(theta)] = r
        pgas = [per[t].im_value for t in per]
        im_pair = float(np.median(pgas))
        assert rw.im_value == rm.im_value == pytest.approx(im_pair, rel=1e-12)
        scales = {t: (r.overturn_scale if not r.censored else math.inf) for t, r in per.items()}
        t_worst = min(scales, key=scales.get)
        assert rw.azimuth_deg == t_worst and rw.orientation == "worst"
        assert rw.overturn_scale == per[t_worst].overturn_scale
        assert rw.capacity == pytest.approx(per[t_worst].overturn_scale * im_pair, rel=1e-12)
        # the motion's own direction (or its reverse) is the most adverse on this grid of 30 deg
        name = x.label.split("-")[0]
        assert min(abs((t_worst - along[name] + 90) % 180 - 90), 90) <= step / 2
        ranked = sorted(scales, key=lambda t: (scales[t], t))
        t_med = rm.azimuth_deg
        assert scales[t_med] == scales[ranked[(len(ranked) - 1) // 2]]
        assert rm.capacity >= rw.capacity
    # fits: the worst-orientation median never exceeds the median-orientation one here (every capacity is lower)
    cm, cw = median.curves[0], worst.curves[0]
    assert cw.median <= cm.median
    assert cm.n_records == cw.n_records == 3


def test_cli_fragility_worst_azimuth(suite, tmp_path):
    import pandas as pd

    args = ["assess", "fragility", "small:R=0.8,alpha=14", "--isolation", "none", "--bootstrap", "20",
            "--azimuth", "worst", "--azimuth-step", "45", "--csv", str(tmp_path / "f.csv")]
    for s in suite:
        args += ["--records", s]
    res = CliRunner().invoke(main, args)
    assert res.exit_code == 0, res.output
    assert "Median orientation of each pair" in res.output and "Worst orientation of each pair" in res.output
    df = pd.read_csv(tmp_path / "f.csv")
    assert list(df.orientation) == ["median"] * 3 + ["worst"] * 3
    worst = df[df.orientation == "worst"].reset_index()
    median = df[df.orientation == "median"].reset_index()
    assert (worst.capacity_g <= median.capacity_g + 1e-15).all()
    assert set(worst.azimuth_deg) <= {0.0, 45.0, 90.0, 135.0}
    assert worst.median_g[0] <= median.median_g[0]
    # one sentence for what is not supported with worst
    res = CliRunner().invoke(main, [*args, "--report", str(tmp_path / "r.html")])
    assert res.exit_code == 2 and "--report" in res.output and not (tmp_path / "r.html").exists()


def test_zero_motion_orientation_is_right_censored(tmp_path):
    """A motion along north has nothing along east (90 deg): that orientation never overturns, and is kept as
    right-censored when it is the median one; its IM (0) counts in the pair's IM."""
    pair = _pair(tmp_path, 0.0, 0.9, 0.8, "z")
    block = Block(R=0.8, alpha=math.radians(14))
    xs, _ = resolve_excitations([pair], "record", azimuth="worst")
    res = run_fragility_azimuths([block], xs, parse_configurations(["none"]), azimuths=np.array([0.0, 90.0]),
                                 n_boot=0)
    rw, rm = res["worst"].rows[0], res["median"].rows[0]
    assert rw.azimuth_deg == 0.0 and not rw.censored
    # two orientations: the lower middle one is the worst; the pair's IM is the mean of 0.9 g and 0
    assert rm.azimuth_deg == 0.0
    assert rw.im_value == pytest.approx(0.45, rel=1e-3)
    # no motion along any orientation run: nothing to scale, an error row (not a capacity of 0)
    res = run_fragility_azimuths([block], xs, parse_configurations(["none"]), azimuths=np.array([90.0]), n_boot=0)
    assert "nothing to scale" in res["worst"].rows[0].error and not math.isfinite(res["worst"].curves[0].median)


def test_no_azimuth_named_when_every_orientation_ranks_equal(tmp_path):
    """Every orientation right-censored (0.05 g pulses: 4x is still below g tan(14 deg) = 0.25 g, so nothing lifts
    the body off, without a run): the worst orientation was "azimuth 0 deg (worst of 4 orientations)", the first
    of the sweep. Now none is named, for the median either, in the words of assess column's @any
    (rockcli.assess.azimuth.most_adverse); the capacity is the bound, the same in every orientation."""
    weak = _pair(tmp_path, 60.0, 0.05, 0.8, "w")
    strong = _pair(tmp_path, 60.0, 0.9, 0.8, "s")
    block = Block(R=0.8, alpha=math.radians(14))
    xs, _ = resolve_excitations([weak, strong], "record", azimuth="worst")
    res = run_fragility_azimuths([block], xs, parse_configurations(["none"]), azimuths=sweep_azimuths(45), n_boot=0)
    words = ("any azimuth (no orientation is more adverse than another: none of the 4 orientations overturns it up "
             "to 4x)")
    for how in ("median", "worst"):
        tied, named = res[how].rows
        assert math.isnan(tied.azimuth_deg) and tied.censored == "right" and tied.margin_note.endswith(words)
        assert tied.capacity == pytest.approx(4.0 * tied.im_value, rel=1e-12)
        assert named.azimuth_deg in (0.0, 45.0, 90.0, 135.0) and f"({how} of 4 orientations)" in named.margin_note
    args = ["assess", "fragility", "small:R=0.8,alpha=14", "--isolation", "none", "--bootstrap", "0", "--azimuth",
            "worst", "--azimuth-step", "45", "--records", weak, "--records", strong]
    out = CliRunner().invoke(main, args).output
    assert f": {words}, capacity >" in out and ": 0 deg, capacity >" not in out, out
