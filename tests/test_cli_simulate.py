"""``rockcli simulate`` end to end through click's CliRunner."""

from __future__ import annotations

import json

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main
from rockcli.models import Block, Rigid
from rockcli.pulses import make_pulse
from rockcli.solve import simulate
from rockcli.io.units import G


def run(*args):
    return CliRunner().invoke(main, ["simulate", *args])


def test_figure_1_from_the_command_line():
    short = run("--height", "2", "--width", "0.5", "--pulse", "sine:ap=0.5,Tp=0.5", "--json")
    long = run("--height", "2", "--width", "0.5", "--pulse", "sine:ap=0.29,Tp=2", "--json")
    assert short.exit_code == 0 and long.exit_code == 0, short.output + long.output
    a, b = json.loads(short.output), json.loads(long.output)
    assert a["verdict"] == "rocked" and b["verdict"] == "overturned"
    for key in ("verdict", "t_uplift_s", "t_overturn_s", "theta_max_over_alpha", "n_impacts", "base_disp_max_m", "steps"):
        assert key in a
    direct = simulate(Block.from_dimensions(2.0, 0.5), Rigid(), make_pulse("sine", 0.29 * G, 2.0))
    assert b["t_overturn_s"] == pytest.approx(direct.t_overturn_s, rel=1e-12)
    assert a["t_overturn_s"] is None


def test_text_output_names_the_verdict_with_units():
    res = run("--R", "1.5", "--alpha", "12", "--pulse", "ricker-sym:ap=0.35,Tp=0.8", "--isolation", "linear:Tb=2.5")
    assert res.exit_code == 0, res.output
    assert "verdict" in res.output and "deg" in res.output and " m" in res.output
    assert "linear:Tb=2.5,xi=0.1,gamma=0.01" in res.output


def test_flip_mirrors_the_response(tmp_path):
    args = ["--body", "bassae", "--pulse", "ricker-anti:ap=0.4,Tp=1", "--isolation", "linear:Tb=2,xi=0.05"]
    a = run(*args, "--history", str(tmp_path / "a.csv"))
    b = run(*args, "--flip", "--history", str(tmp_path / "b.csv"))
    assert a.exit_code == 0 and b.exit_code == 0
    A = np.loadtxt(tmp_path / "a.csv", delimiter=",", skiprows=1, usecols=range(8))  # the last column: event names
    B = np.loadtxt(tmp_path / "b.csv", delimiter=",", skiprows=1, usecols=range(8))
    assert A.shape == B.shape and A.shape[1] == 8
    np.testing.assert_allclose(B[:, 3], -A[:, 3], atol=1e-12)
    np.testing.assert_allclose(B[:, 1], -A[:, 1], atol=1e-12)


def test_history_and_plot_files(tmp_path):
    hist, fig = tmp_path / "h.csv", tmp_path / "f.png"
    res = run("--body", "nemea", "--pulse", "ricker-sym:ap=0.3,Tp=1.2", "--isolation", "linear:Tb=3",
              "--history", str(hist), "--plot", str(fig))
    assert res.exit_code == 0, res.output
    header = hist.read_text().splitlines()[0]
    assert header == "t_s,ag_mps2,ag_g,theta_rad,theta_over_alpha,theta_dot_radps,u_m,u_dot_mps,event"
    data = np.loadtxt(hist, delimiter=",", skiprows=1, usecols=range(8))
    assert np.all(np.diff(data[:, 0]) >= 0) and data[0, 0] == 0.0
    assert fig.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_record_from_the_catalogue(records_dirs):
    res = run("--body", "nemea", "--record", "northridge-1994-jensen-generator-022", "--json")
    assert res.exit_code == 0, res.output
    iso = run("--body", "nemea", "--record", "northridge-1994-jensen-generator-022", "--isolation", "linear:Tb=3", "--json")
    # the paper's Figure 12: standing free it survives, isolated with T_b = 3 s it overturns
    assert json.loads(res.output)["verdict"] == "rocked"
    assert json.loads(iso.output)["verdict"] == "overturned"


def test_record_scale_and_text_column_options(tmp_path):
    t = np.arange(0, 4, 0.01)
    acc = 0.6 * np.sin(2 * np.pi * t) * np.exp(-t)
    path = tmp_path / "rec.txt"
    np.savetxt(path, np.column_stack([t, 0 * t, acc]))
    base = ["--height", "1", "--width", "0.3", "--record", str(path), "--units", "g", "--record-column", "3", "--json"]
    one = json.loads(run(*base).output)
    half = json.loads(run(*base, "--scale", "0.2").output)
    assert one["verdict"] != "no_uplift" and half["verdict"] == "no_uplift"


def test_check_tolerance_reports_a_well_and_an_ill_conditioned_run(tmp_path):
    out = run("--body", "bassae", "--pulse", "ricker-sym:ap=0.5,Tp=1.2", "--check-tolerance")
    assert out.exit_code == 0, out.output
    lines = {ln.split("  ")[0]: ln for ln in out.output.splitlines()}
    assert "rtol 5e-11: same verdict" in lines["tolerance check"]
    assert "2 motions moved by one ulp: same verdict" in lines["conditioning"] and "ILL" not in lines["conditioning"]
    data = json.loads(run("--body", "bassae", "--pulse", "ricker-sym:ap=0.5,Tp=1.2", "--check-tolerance",
                          "--json").output)
    assert data["check_tight_rtol_verdict"] == data["verdict"] == "rocked" and data["check_tight_rtol_change"] < 1e-7
    assert data["check_ulp_verdicts"] == ["rocked", "rocked"] and data["check_ulp_change"] < 1e-12
    assert data["check_ill_conditioned"] is False
    # Bassae under 100 s of band-limited motion (596 impacts; the stability bench's record-100s): one
    # ulp of the record moves the peak, reached after 56 s, by tenths of alpha
    from rockcli.bench import band_limited_record

    rec = band_limited_record()
    path = tmp_path / "long.txt"
    np.savetxt(path, rec.acc, fmt="%.17g")
    out = run("--body", "bassae", "--record", str(path), "--units", "m/s^2", "--dt", "0.001", "--check-tolerance",
              "--json")
    assert out.exit_code == 0, out.output
    data = json.loads(out.output)
    assert data["theta_max_over_alpha"] == pytest.approx(0.3954, abs=1e-4)  # the file holds the record exactly
    assert data["check_ill_conditioned"] is True and data["check_ulp_change"] > 0.1


@pytest.mark.parametrize("args, words", [
    (["--body", "parthenon", "--pulse", "sine:ap=1,Tp=1"], "unknown body"),
    (["--R", "1", "--pulse", "sine:ap=1,Tp=1"], "--R and --alpha"),
    (["--R", "-1", "--alpha", "10", "--pulse", "sine:ap=1,Tp=1"], "positive"),
    (["--body", "bassae", "--column-x"], "No such option"),
    (["--body", "bassae"], "exactly one of --record"),
    (["--body", "bassae", "--pulse", "sine:ap=1,Tp=1", "--record", "x"], "exactly one of --record"),
    (["--body", "bassae", "--pulse", "square:ap=1,Tp=1"], "square"),
    (["--body", "bassae", "--pulse", "sine:ap=1,Tp=1", "--isolation", "rubber"], "unknown isolation"),
    (["--body", "bassae", "--record", "/no/such/file.AT2"], "no such file"),
    (["--body", "bassae", "--pulse", "sine:ap=1,Tp=1", "--rtol", "2"], "rtol"),
])
def test_bad_input_is_one_clear_sentence_and_exit_code_2(args, words, tmp_path):
    out = tmp_path / "never.csv"
    res = run(*args, "--history", str(out))
    assert res.exit_code == 2, res.output
    assert words in res.output
    assert "Traceback" not in res.output
    assert not out.exists()
