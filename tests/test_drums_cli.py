"""``rockcli simulate --drums``: a column of drums beside its monolith, printed and as JSON; what it refuses."""

from __future__ import annotations

import json

import pytest
from click.testing import CliRunner

from rockcli.cli import main


def _run(*args):
    res = CliRunner().invoke(main, list(args))
    return res.exit_code, res.output


def test_a_column_of_drums_beside_its_monolith_as_json():
    code, out = _run("simulate", "--body", "bassae", "--drums", "6", "--friction", "0.7", "--pulse",
                     "ricker-sym:ap=0.4,Tp=1", "--json")
    assert code == 0, out
    d = json.loads(out)
    assert len(d["column"]["drums"]) == 6 and len(d["joints"]) == 5
    assert d["verdict"] == "survives" and d["monolith"]["verdict"] == "survives"
    # no joint opens or slides: the column rocks as one on its base, as the monolith does
    assert d["first_move"]["contact"] == "base" and d["first_move"]["how"] == "opens"
    assert d["base"]["psi_max_over_alpha"] == pytest.approx(d["monolith"]["psi_max_over_alpha"], abs=1e-6)
    assert d["drums_against_monolith"] == "alike" and d["n_inconsistent"] == 0
    assert d["column"]["static_thresholds_g"][0] == pytest.approx(1.11 / 5.95, rel=1e-9)  # the monolith's b/h


def test_the_printout_names_each_joint():
    code, out = _run("simulate", "--body", "shaft:height=3,width=0.8", "--drums", "1.0x0.8,1.0x0.78,1.0x0.76",
                     "--friction", "0.6", "--pulse", "sine:ap=0.3,Tp=1")
    assert code == 0, out
    for word in ("3 drums", "joint 1", "joint 2", "residual offsets", "drums vs monolith"):
        assert word in out


@pytest.mark.parametrize("args, words", [
    (("--drums", "6"), "needs --friction"),
    (("--drums", "2.5", "--friction", "0.6"), "whole number"),
    (("--drums", "1x1,1xa", "--friction", "0.6"), "drum 2 is '1xa'"),
    (("--drums", "0", "--friction", "0.6"), ">= 1"),
    (("--drums", "3", "--friction", "0.6", "--plot", "{tmp}/never.png"), "--plot is not taken"),
    (("--drums", "3", "--friction", "0.6", "--on", "plinth:height=1,width=2"), "--drums and --on"),
    (("--drums", "3", "--friction", "0.6", "--restitution", "0.8"), "restitution"),
    (("--drums", "3", "--friction", "0.6", "--isolation", "scss:Tb=3,mu=0.05"), "linear bearings"),
])
def test_what_drums_refuse(args, words, tmp_path):
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    code, out = _run("simulate", "--body", "bassae", "--pulse", "sine:ap=0.5,Tp=1", *args)
    assert code == 2 and words in out and "Traceback" not in out
    assert not any(tmp_path.iterdir())  # nothing written
