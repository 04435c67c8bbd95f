"""Vertical motion beyond ``simulate`` (issue 27 item 3): a record that carries its vertical component
(``rockcli.solve.with_vertical``) through the batch path, the margin search and the copies the checks
make; ``assess column`` and ``assess fragility`` with ``--vertical-component``/``--vertical``/
``--vertical-pulse``; the refusal on isolated bases in every command that takes a vertical motion."""

from __future__ import annotations

import csv
import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.assess import find_overturn_scales
from rockcli.assess.excitations import Excitation
from rockcli.assess.vertical import attach_verticals
from rockcli.conditioning import ulp_perturbed
from rockcli.models import Block, LinearIsolation, Rigid
from rockcli.pulses import make_pulse
from rockcli.records import Record
from rockcli.solve import attached_vertical, simulate, simulate_many, with_vertical
from rockcli.io.units import G
from synthetic import synthetic_record


def _cli(args):
    from rockcli.cli import main

    return CliRunner().invoke(main, args)


def _rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


# ------------------------------------------------------------------------------------------
# A record that carries its vertical component
# ------------------------------------------------------------------------------------------
def test_a_carried_vertical_is_the_same_run_as_vertical_given():
    block, rec = Block(1.2, 0.2), synthetic_record(11, duration=8.0, pga=0.5 * G)
    up = synthetic_record(12, duration=8.0, pga=0.6 * G)
    carried = with_vertical(rec, up, "up")
    given = simulate(block, Rigid(), rec, vertical=up, history=True)
    assert repr(simulate(block, Rigid(), carried, history=True).summary()) == repr(given.summary())
    plain = simulate(block, Rigid(), rec)
    assert plain.t_uplift_s != given.t_uplift_s  # the vertical motion does change the run
    # kept by the copies the sweeps make: a scale factor (horizontal only) and the one-ulp copies
    assert attached_vertical(carried.scaled(2.0)) is up
    assert attached_vertical(ulp_perturbed(carried, np.random.default_rng(0))) is up
    many = simulate_many([(block, Rigid(), carried, 1.5), (block, Rigid(), rec, 1.5)])
    assert many[0].theta_max == simulate(block, Rigid(), rec.scaled(1.5), vertical=up).theta_max
    assert many[1].theta_max == simulate(block, Rigid(), rec.scaled(1.5)).theta_max
    bad = simulate_many([(block, LinearIsolation(2.0, 0.1, 0.01), carried)])
    assert bad[0].verdict == "error" and "rigid foundation only" in bad[0].error


def test_the_margin_scales_the_horizontal_motion_only():
    """The overturning scale under a carried vertical motion brackets the verdict change of simulate runs
    with the horizontal record scaled and the vertical one as recorded."""
    block = Block(1.0, 0.2)
    rec = synthetic_record(21, duration=8.0, pga=0.35 * G)
    up = synthetic_record(22, duration=8.0, pga=0.7 * G)
    carried = with_vertical(rec, up, "up")
    (s_over, s_surv, note), (s_plain, _, _) = find_overturn_scales([(block, Rigid(), carried), (block, Rigid(), rec)])
    assert math.isfinite(s_over) and s_over != s_plain, note
    assert simulate(block, Rigid(), rec.scaled(s_over), vertical=up).overturned
    assert not simulate(block, Rigid(), rec.scaled(s_surv), vertical=up).overturned
    assert s_surv < s_over <= s_surv * 1.011


def test_attach_verticals_turns_what_cannot_carry_one_into_error_rows():
    rec = synthetic_record(31, duration=6.0)
    xs = [Excitation("r", "record", rec, "r.txt", rec.pga_g),
          Excitation("p", "pulse", make_pulse("sine", 0.2 * G, 0.5), "catalogue pulse", 0.2),
          Excitation("other-dt", "record", Record(rec.acc, 0.02, "other-dt"), "o.txt", rec.pga_g),
          Excitation("bad", "record", None, "bad.txt", error="bad.txt: unreadable")]
    out = attach_verticals(xs, motion=rec.scaled(0.5), label="record r x 0.5")
    assert attached_vertical(out[0].motion) is not None and out[0].error == ""
    assert out[1].motion is None and "catalogued pulse" in out[1].error
    assert out[2].motion is None and "time base" in out[2].error
    assert out[3] is xs[3]
    lift = attach_verticals(xs[:1], motion=make_pulse("sine", -1.1 * G, 0.5, t0=1.0), label="down")
    assert lift[0].motion is None and "lift off" in lift[0].error


def test_every_projection_of_a_pair_keeps_the_vertical_component():
    """--azimuth worst projects a pair onto every orientation: each projection carries the pair's vertical."""
    from dataclasses import replace

    from rockcli.assess.azimuth import expand
    from rockcli.records.orientation import project

    a = replace(synthetic_record(51, duration=4.0), meta={"azimuth_deg": 0.0, "vertical": False})
    b = replace(synthetic_record(52, duration=4.0), meta={"azimuth_deg": 90.0, "vertical": False})
    up = synthetic_record(53, duration=4.0, pga=0.3 * G)
    x = Excitation("a+b", "record", with_vertical(project(a, b, 0.0), up, "up"), "a", pair=(a, b))
    out, groups = expand([x], [0.0, 45.0, 90.0])
    assert len(out) == 3 and all(attached_vertical(o.motion) is up for o in out)


# ------------------------------------------------------------------------------------------
# assess column / assess fragility
# ------------------------------------------------------------------------------------------
def test_assess_column_runs_each_record_under_its_own_vertical_component(find_record, tmp_path):
    """Kaikoura 2016, GeoNet WTMC (three components): N28W horizontally and its Up component (at 0.9: the
    recorded one reaches -1.08 g, lift-off, which is refused), against simulate."""
    from rockcli.assess import parse_column_spec
    from rockcli.records.reader import read_components

    path = str(find_record("20161113_110259_WTMC_20.V2A"))
    args = ["assess", "column", "bassae", "--records", path, "--component", "N28W", "--isolation", "none",
            "--no-margin", "--csv"]
    lifted = _cli(args + [str(tmp_path / "x.csv"), "--vertical-component", "Up"])
    assert lifted.exit_code == 2 and "lift off" in lifted.output and not (tmp_path / "x.csv").exists()
    out = _cli(args + [str(tmp_path / "v.csv"), "--vertical-component", "UP", "--vertical-scale", "0.9"])
    assert out.exit_code == 0, out.output
    assert "Vertical motion" in out.output and "component Up of 20161113_110259_WTMC_20.V2A x 0.9" in out.output
    row, = _rows(tmp_path / "v.csv")
    assert row["vertical"] == "component Up of 20161113_110259_WTMC_20.V2A x 0.9"
    comps = {c.meta["component"]: c for c in read_components(path)}
    block = parse_column_spec("bassae")
    lib = simulate(block, Rigid(), comps["N28W"], vertical=comps["Up"].scaled(0.9), early=True)
    assert row["verdict"] == lib.verdict
    assert float(row["theta_max_over_alpha"]) == pytest.approx(lib.theta_max / block.alpha, rel=1e-5)
    plain = simulate(block, Rigid(), comps["N28W"], early=True)
    assert abs(plain.theta_max - lib.theta_max) > 0.1 * block.alpha  # it does move the peak


def test_simulate_reads_the_vertical_component_of_a_three_component_file(find_record):
    """--component picks the horizontal record; the --vertical file's own component is its one vertical one
    (or --vertical-component/--vertical-column), never the horizontal --component (it used to be)."""
    import json

    from rockcli.assess import parse_column_spec
    from rockcli.records.reader import read_components

    path = str(find_record("20161113_110259_WTMC_20.V2A"))
    comps = {c.meta["component"]: c for c in read_components(path)}
    lib = simulate(parse_column_spec("bassae"), Rigid(), comps["S62W"], vertical=comps["Up"].scaled(0.5))
    base = ["simulate", "--body", "bassae", "--record", path, "--component", "S62W", "--vertical", path,
            "--vertical-scale", "0.5", "--json"]
    for extra in ([], ["--vertical-component", "UP"], ["--vertical-column", "3"]):
        out = _cli(base + extra)
        assert out.exit_code == 0, out.output
        got = json.loads(out.stdout)
        assert got["theta_max"] == lib.theta_max and got["verdict"] == lib.verdict, extra
        assert "component Up" in got["vertical"] or extra, got["vertical"]
    bad = _cli(base + ["--vertical-component", "UP", "--vertical-column", "3"])
    assert bad.exit_code == 2 and "not both" in bad.output


def _suite(tmp_path, n=3):
    folder = tmp_path / "suite"
    folder.mkdir()
    for k in range(n):
        np.savetxt(folder / f"r{k}.txt", synthetic_record(40 + k, duration=8.0, pga=0.3 * G).acc / G)
    return folder


def test_assess_fragility_takes_a_vertical_pulse_and_says_so(tmp_path):
    folder = _suite(tmp_path)
    base = ["assess", "fragility", "demo:R=1,alpha=12", "--records", str(folder), "--units", "g", "--dt", "0.01",
            "--isolation", "none", "--bootstrap", "0"]
    plain = _cli(base + ["--csv", str(tmp_path / "p.csv")])
    up = _cli(base + ["--csv", str(tmp_path / "v.csv"), "--vertical-pulse", "sine:ap=0.6,Tp=0.6,t0=2"])
    assert plain.exit_code == 0 and up.exit_code == 0, up.output
    assert "Vertical motion" in up.output and "sine pulse" in up.output and "Vertical motion" not in plain.output
    p_rows, v_rows = _rows(tmp_path / "p.csv"), _rows(tmp_path / "v.csv")
    assert "vertical" not in p_rows[0] and {r["vertical"] for r in v_rows} == {"sine pulse"}
    assert [r["overturn_scale"] for r in p_rows] != [r["overturn_scale"] for r in v_rows]


@pytest.mark.parametrize("command", [["assess", "column", "nemea"], ["assess", "fragility", "nemea"]])
def test_vertical_motion_on_isolated_bases_is_refused_in_one_sentence(command, tmp_path):
    folder = _suite(tmp_path, 1)
    common = command + ["--records", str(folder), "--units", "g", "--dt", "0.01", "--csv", str(tmp_path / "o.csv")]
    for isolation in ([], ["--isolation", "none", "--isolation", "linear:Tb=2.5"]):  # the default set is isolated too
        out = _cli(common + isolation + ["--vertical-pulse", "sine:ap=0.2,Tp=1"])
        assert out.exit_code == 2 and "Traceback" not in out.output
        assert "rigid foundation only" in out.output and "normal force" in out.output, out.output
        assert "give --isolation none" in out.output and not (tmp_path / "o.csv").exists()
    both = _cli(common + ["--isolation", "none", "--vertical-pulse", "sine:ap=0.2,Tp=1", "--vertical-component", "UP"])
    assert both.exit_code == 2 and "one of --vertical" in both.output
    alone = _cli(common + ["--isolation", "none", "--vertical-scale", "0.5"])
    assert alone.exit_code == 2 and "--vertical-scale applies" in alone.output


# ------------------------------------------------------------------------------------------
# The pulse spectra: --vertical-pulse SHAPE:ap=G[,TvTp=R]
# ------------------------------------------------------------------------------------------
def _family(alpha_deg=10.0, shape="ricker-sym", R=1.0):
    from rockcli.spectra import Family, parse_isolation

    return Family(math.radians(alpha_deg), shape, parse_isolation("none"), R)


def test_a_map_under_a_vertical_pulse_is_its_cells_and_does_not_depend_on_the_block_size():
    from rockcli.spectra import Runner, Grid, overturning_maps, parse_pulse_choice, parse_isolation
    from rockcli.spectra import parse_vertical_choice

    vertical = parse_vertical_choice("sine:ap=0.5,TvTp=0.7")
    args = ([12.0], [parse_pulse_choice("ricker-anti")], [parse_isolation("none")], Grid(1.0, 8.0, 9),
            Grid(0.5, 6.0, 9))
    a = overturning_maps(*args, runner=Runner(vertical=vertical))[0]
    b = overturning_maps(*args, R=3.7, runner=Runner(vertical=vertical))[0]
    plain = overturning_maps(*args)[0]
    assert np.array_equal(a.overturned, b.overturned) and np.array_equal(a.uplifted, b.uplifted)
    assert np.allclose(a.theta_max_over_alpha, b.theta_max_over_alpha, rtol=1e-5, atol=1e-7)
    assert not np.array_equal(a.uplifted, plain.uplifted) or not np.array_equal(a.overturned, plain.overturned)
    fam = _family(12.0, "ricker-anti")
    rng = np.random.default_rng(5)
    for _ in range(12):  # each cell is the simulate run of its block, pulse and vertical pulse
        i, j = rng.integers(9, size=2)
        block, foundation, pulse = fam.scene(a.wp_over_p[j], a.ap_over_g_tan_alpha[i])
        r = simulate(block, foundation, pulse, vertical=vertical.pulse(pulse))
        assert r.overturned == a.overturned[i, j] and (r.verdict != "no_uplift") == a.uplifted[i, j]


def test_min_overturning_under_a_vertical_pulse_brackets_the_simulate_runs():
    """The uplift threshold is no longer y = 1: found by bisection, it brackets simulate's uplift; ap_min
    overturns and ap_safe does not."""
    from rockcli.spectra import Runner, parse_vertical_choice, search_min_overturning

    vertical = parse_vertical_choice("sine:ap=0.4,TvTp=2")
    fam = _family(10.0, "sine")
    xs = np.array([1.5, 3.0, 6.0])
    res = search_min_overturning([fam], np.zeros(xs.size, np.int64), xs, runner=Runner(vertical=vertical))
    assert np.all(np.abs(res.ap_uplift - 1.0) > 1e-3)  # it moved
    for k, x in enumerate(xs):
        def run(y):
            block, foundation, pulse = fam.scene(x, y)
            return simulate(block, foundation, pulse, vertical=vertical.pulse(pulse), early=True)

        assert run(res.ap_uplift[k] * (1 + 1e-6)).verdict != "no_uplift" == run(res.ap_uplift[k] * (1 - 1e-6)).verdict
        assert run(res.ap_min[k]).overturned and not run(res.ap_safe[k]).overturned


@pytest.mark.parametrize("command", ["overturning", "min-overturning"])
def test_spectrum_vertical_pulse_is_reported_and_refused_on_isolated_bases(command, tmp_path):
    base = ["spectrum", command, "--alpha", "10", "--wp-over-p", "2:3:2"] + (["--ap", "0:4:3"] if command == "overturning"
                                                                       else ["--isolation", "none"])
    out = _cli(base + ["--vertical-pulse", "sine:ap=0.3", "--csv", str(tmp_path / "v.csv")])
    assert out.exit_code == 0, out.output
    assert "vertical motion: a sine:ap=0.3,TvTp=1 pulse" in out.output
    assert {r["vertical"] for r in _rows(tmp_path / "v.csv")} == {"sine:ap=0.3,TvTp=1"}
    iso = _cli(base + ["--vertical-pulse", "sine:ap=0.3", "--isolation", "linear:TbTp=2,xi=0.1"])
    assert iso.exit_code == 2 and "rigid foundation only" in iso.output and "Traceback" not in iso.output
    for spec, msg in (("sine:ap=-1.2", "lift off"), ("sine:ap=0.2,Tp=1", "TvTp"), ("box:ap=0.2", "unknown shape"),
                      ("sine:TvTp=2", "give the vertical amplitude")):
        bad = _cli(base + ["--vertical-pulse", spec])
        assert bad.exit_code == 2 and msg in bad.output, (spec, bad.output)


def test_spectrum_critical_size_refuses_a_vertical_pulse():
    """It always compares isolated bases with the rigid foundation: refused, in one sentence, not 'no such option'."""
    out = _cli(["spectrum", "critical-size", "--vertical-pulse", "sine:ap=0.2"])
    assert out.exit_code == 2 and "rigid foundation only" in out.output and "critical-size compares" in out.output
