"""One interface (issue 25): old spellings still work and mean the same, messages suggest the right syntax,
``--json`` on every command that prints results, one set of isolation defaults, ``--plot`` always a file,
one CSV boolean convention, ``--quiet``, and every ``--help`` example runs as written.

The scheme is docs/cli-conventions.md.
"""

from __future__ import annotations

import csv
import json
import os
import re
import shlex
from pathlib import Path

import click
import pytest
from click.testing import CliRunner

from rockcli.cli import main

SINE = ["--pulse", "sine:ap=0.4,Tp=0.8"]


def _records_dir() -> Path | None:
    """The folder of the paper's records (the first ROCKCLI_RECORDS entry holding the Kobe file)."""
    for entry in os.environ.get("ROCKCLI_RECORDS", "").split(os.pathsep):
        if entry and (Path(entry) / "RSN1119_KOBE_TAZ000.AT2").is_file():
            return Path(entry)
    return None


RECORDS = _records_dir()
needs_records = pytest.mark.skipif(RECORDS is None, reason="the paper's records are not on ROCKCLI_RECORDS")


def invoke(args, **kwargs):
    return CliRunner().invoke(main, [str(a) for a in args], catch_exceptions=False, **kwargs)


def _walk(cmd=main, path=("rockcli",)):
    ctx = click.Context(main)
    if isinstance(cmd, click.Group):
        for name in cmd.list_commands(ctx):
            yield from _walk(cmd.get_command(ctx, name), (*path, name))
    else:
        yield path, cmd


def _parsed(path, args):
    """The values the command would receive for ``args`` (parsing and callbacks only, nothing run)."""
    cmd = main
    for name in path:
        cmd = cmd.get_command(click.Context(cmd), name)
    with cmd.make_context(" ".join(path), list(args)) as ctx:
        return dict(ctx.params)


# --------------------------------------------------------------------------------------------------
# old spellings: hidden, same value, a note once
# --------------------------------------------------------------------------------------------------
#: (command path, old arguments, new arguments)
RENAMED = [
    (("simulate",), ["--column", "nemea"], ["--body", "nemea"]),
    (("records", "show"), ["x.txt", "--column", "2"], ["x.txt", "--record-column", "2"]),
    (("records", "export"), ["x.txt", "y.txt", "--column", "3"], ["x.txt", "y.txt", "--record-column", "3"]),
    (("fit-pulse",), ["x.txt", "--column", "2"], ["x.txt", "--record-column", "2"]),
    (("spectrum", "overturning"), ["--alpha", "10", "--wp-p", "1:2:3"], ["--alpha", "10", "--wp-over-p", "1:2:3"]),
    (("spectrum", "min-overturning"), ["--alpha", "10", "--wp-p", "1:2:3"],
     ["--alpha", "10", "--wp-over-p", "1:2:3"]),
    (("spectrum", "critical-size"), ["--wp-p", "1:2:3", "--tb-tp", "2,5"], ["--wp-over-p", "1:2:3", "--tbtp", "2,5"]),
    (("assess", "column"), ["bassae", "--histories", "h", "--plot", "figs"], ["bassae", "--history-dir", "h",
                                                                            "--plot-dir", "figs"]),
    (("assess", "column"), ["bassae", "--record", "a", "--records", "b"], ["bassae", "--records", "a", "--records", "b"]),
    (("assess", "fragility"), ["bassae", "--record", "a"], ["bassae", "--records", "a"]),
]


@pytest.mark.parametrize("path, old, new", RENAMED, ids=lambda v: "-".join(v) if isinstance(v, tuple) else None)
def test_old_spelling_gives_the_same_value(path, old, new):
    got, want = _parsed(path, old), _parsed(path, new)
    assert got == want
    assert any(v not in (None, (), False) for k, v in want.items() if k in got)  # the value did arrive


def test_old_spellings_are_hidden_and_new_ones_listed():
    hidden = {"--column", "--wp-p", "--tb-tp", "--histories", "--record"}
    for path, cmd in _walk():
        listed = set()
        for p in cmd.params:
            record = p.get_help_record(click.Context(cmd)) if isinstance(p, click.Option) else None
            if record:
                listed |= set(re.findall(r"--[\w-]+", record[0]))
        if path[-1] != "simulate" and path[-2:] != ("spectrum", "critical-size"):
            assert not (hidden - {"--record"}) & listed, path
        if path[:2] == ("rockcli", "assess"):
            assert "--record" not in listed and "--records" in listed
    opts = {o for p in _command("simulate").params for o in p.opts if not getattr(p, "hidden", False)}
    assert {"--body", "--record-column", "--R"} <= opts and "--column" not in opts


def _command(*path):
    cmd = main
    for name in path:
        cmd = cmd.get_command(click.Context(cmd), name)
    return cmd


def test_old_spelling_runs_with_one_note_on_stderr():
    old = invoke(["simulate", "--column", "bassae", *SINE, "--json"])
    new = invoke(["simulate", "--body", "bassae", *SINE, "--json"])
    assert old.exit_code == new.exit_code == 0, old.output
    assert json.loads(old.stdout) == json.loads(new.stdout)
    assert old.stderr.count("--column is now --body") == 1 and "--column" not in new.stderr
    twice = invoke(["spectrum", "overturning", "--alpha", "10", "--wp-p", "1:2:2", "--wp-p", "1:3:2", "--ap", "1:2:2"])
    assert twice.exit_code == 0, twice.output
    assert twice.stderr.count("--wp-p is now --wp-over-p") == 1
    assert "omega_p/p 1:3:2" in twice.stdout  # the last one written wins, as for any option


# --------------------------------------------------------------------------------------------------
# messages that suggest the right syntax
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("args, words", [
    (["simulate", "--body", "statue", *SINE], ["unknown body 'statue'", "statue:height=", "NAME:R=<m>,alpha=<deg>"]),
    (["simulate", "--body", "nemia", *SINE], ["did you mean 'nemea'"]),
    (["assess", "column", "statue", "--records", "x"], ["unknown body 'statue'", "NAME:height=<m>,width=<m>"]),
    (["simulate", "--bdy", "bassae", *SINE], ["--body"]),
    (["spectrum", "overturning", "--alpha", "10", "--wp-over", "1:2:2"], ["--wp-over-p"]),
    (["simulate", "--body", "bassae", *SINE, "--isolation", "linar:Tb=2"], ["'linear:Tb=2.5,xi=0.1,gamma=0.01'"]),
    (["spectrum", "overturning", "--alpha", "10", "--isolation", "linear:Tb=2"], ["TbTp=<ratio>"]),
    (["assess", "column", "bassae", "--records", "x", "--plot", "statue.png"], ["--plot-dir"]),
])
def test_refusal_suggests_the_right_syntax(tmp_path, monkeypatch, args, words):
    monkeypatch.chdir(tmp_path)
    res = invoke(args)
    assert res.exit_code == 2, res.output
    assert "Traceback" not in res.output
    for w in words:
        assert w in res.output
    assert list(tmp_path.iterdir()) == []  # nothing written (no folder named statue.png)


def test_did_you_mean_never_offers_a_hidden_old_spelling():
    res = invoke(["simulate", "--colum", "bassae", *SINE])
    assert res.exit_code == 2 and "--colum'" in res.output and "'--column'" not in res.output
    res = invoke(["spectrum", "overturning", "--alpha", "10", "--wp-p-over", "1:2:2"])
    assert "--wp-over-p" in res.output and "'--wp-p'" not in res.output


# --------------------------------------------------------------------------------------------------
# --json: stdout is one JSON document
# --------------------------------------------------------------------------------------------------
def _json(args, tmp_path):
    """Run ``args`` in a new empty folder under ``tmp_path`` (the working folder restored after)."""
    import tempfile

    here = os.getcwd()
    os.chdir(tempfile.mkdtemp(dir=tmp_path))
    try:
        res = invoke(args)
    finally:
        os.chdir(here)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout), res


@needs_records
def test_json_records_list_and_show(tmp_path):
    data, res = _json(["records", "list", "--json", "--csv", "r.csv"], tmp_path)
    ids = [r["id"] for r in data["records"]]
    assert "kobe-1995-takarazuka-000" in ids and data["found"] == sum(r["status"] == "found" for r in data["records"])
    assert "wrote r.csv" in res.stderr
    show, _ = _json(["records", "show", "kobe-1995-takarazuka-000", "--json"], tmp_path)
    assert show["npts"] == 4096 and show["dt_s"] == 0.01 and show["duration_s"] == pytest.approx(40.95)
    assert show["pga_g"] == pytest.approx(show["pga_mps2"] / 9.80665)
    assert show["pgv_mps"] > 0 and show["pgd_linear_baseline_m"] > 0


def test_json_records_show_multi_component_file(tmp_path):
    path = tmp_path / "three.txt"
    path.write_text("# units: g\n# dt=0.01\n" + "".join(f"{(-1) ** k * k * 1e-3} {-k * 2e-3} {(-1) ** k * 3e-3}\n" for k in range(50)))
    data, _ = _json(["records", "show", str(path), "--record-column", "2", "--json"], tmp_path)
    assert data["pga_g"] == pytest.approx(49 * 2e-3)


def test_json_simulate_and_spectra_agree(tmp_path):
    """The map's cell at (omega_p/p, a_p) is the verdict of the same pulse run by simulate."""
    maps, res = _json(["spectrum", "overturning", "--alpha", "14", "--wp-over-p", "2:4:2", "--ap", "1.5:3:2",
                       "--isolation", "linear:TbTp=2", "--json"], tmp_path)
    assert "cells (omega_p/p" in res.stderr and "cells (omega_p/p" not in res.stdout
    (m,) = maps["maps"]
    assert m["isolation"] == "linear:TbTp=2,xi=0.1,gamma=0.01" and m["n_cells"] == 4
    cells = m["cells"]
    assert len(cells["overturned"]) == 4 and set(cells["overturned"]) <= {True, False}
    assert m["n_overturn"] == sum(cells["overturned"])
    mins, _ = _json(["spectrum", "min-overturning", "--alpha", "14", "--isolation", "none", "--wp-over-p", "2:4:2",
                     "--json"], tmp_path)
    pts = mins["points"]
    assert [p["wp_over_p"] for p in pts] == [2.0, 4.0]
    assert all(p["ap_min_over_g_tan_alpha"] >= p["ap_uplift_over_g_tan_alpha"] == 1.0 for p in pts)


def test_json_critical_size(tmp_path):
    data, _ = _json(["spectrum", "critical-size", "--alpha", "10", "--tbtp", "2", "--pulse", "ricker-sym:Tp=0.6",
                     "--wp-over-p", "1:6:6", "--xtol", "0.02", "--json"], tmp_path)
    (row,) = data["rows"]
    assert data["isolation"] == "linear:TbTp=<ratio>,xi=0.1,gamma=0.01"  # the one default, stated
    p = 2 * 3.141592653589793 / 0.6 / row["wp_over_p_cross"]
    assert row["R_critical_m"] == pytest.approx(0.75 * 9.80665 / p ** 2)


def _two_records(folder: Path):
    import math

    for name, ap, T in (("a.txt", 0.5, 0.7), ("b.txt", 0.35, 0.5), ("c.txt", 0.6, 0.9)):
        rows = [ap * math.sin(2 * math.pi * k * 0.01 / T) if k * 0.01 < T else 0.0 for k in range(300)]
        (folder / name).write_text("# units: g\n# dt=0.01\n" + "".join(f"{v!r}\n" for v in rows))


def test_json_assess_column_matches_its_csv(tmp_path):
    _two_records(tmp_path)
    args = ["assess", "column", "bassae", "s:R=0.5,alpha=14", "--records", str(tmp_path / "a.txt"), "--records",
            str(tmp_path / "b.txt"), "--isolation", "none", "--isolation", "linear:Tb=2", "--no-margin"]
    data, res = _json([*args, "--json", "--csv", str(tmp_path / "t.csv")], tmp_path)
    assert "wrote" in res.stderr and not res.stdout.lstrip().startswith("Temple")
    rows = list(csv.DictReader((tmp_path / "t.csv").open()))
    assert len(data["rows"]) == len(rows) == 8
    for j, c in zip(data["rows"], rows):
        assert j["verdict"] == c["verdict"] and str(j["overturned"]) == c["overturned"]
        rigid = j["configuration"] == "none"
        assert (j["xi"], j["gamma"]) == ((None, 0.0) if rigid else (0.1, 0.01))  # the defaults, stated per row
    assert [c["isolation"] for c in data["configurations"]] == ["none", "linear:Tb=2,xi=0.1,gamma=0.01"]


def test_json_fragility(tmp_path):
    _two_records(tmp_path)
    data, _ = _json(["assess", "fragility", "s:R=0.5,alpha=14", "--records", str(tmp_path), "--isolation", "none",
                     "--bootstrap", "0", "--json"], tmp_path)
    (curve,) = data["curves"]
    assert curve["n_records"] == 3 and len(data["rows"]) == 3
    caps = [r["capacity_g"] for r in data["rows"] if not r["censored"]]
    assert caps and all(c > 0 for c in caps)


# --------------------------------------------------------------------------------------------------
# defaults, CSV booleans, --plot, --quiet
# --------------------------------------------------------------------------------------------------
def test_default_text_is_the_library_default():
    from rockcli.cli.options import DEFAULT_GAMMA_TEXT, DEFAULT_XI_TEXT
    from rockcli.models import DEFAULT_GAMMA, DEFAULT_XI, parse_isolation_spec

    assert float(DEFAULT_XI_TEXT) == DEFAULT_XI and float(DEFAULT_GAMMA_TEXT) == DEFAULT_GAMMA
    f = parse_isolation_spec("linear:Tb=2")
    assert (f.xi, f.gamma) == (DEFAULT_XI, DEFAULT_GAMMA)
    params = {p.name: p.default for p in _command("spectrum", "min-overturning").params}
    assert all("xi=" not in s for s in params["isolations"])  # the default set takes the one default


def test_csv_booleans_are_true_false_everywhere(tmp_path):
    invoke(["spectrum", "overturning", "--alpha", "10", "--wp-over-p", "1:3:2", "--ap", "0.5:3:2", "--csv",
            tmp_path / "m.csv"])
    invoke(["spectrum", "min-overturning", "--alpha", "10", "--isolation", "none", "--wp-over-p", "1:3:2", "--csv",
            tmp_path / "n.csv"])
    seen = set()
    for name, cols in (("m.csv", ("overturned", "uplift", "peak_final", "proven")), ("n.csv", ("stepped_over_by_scan",))):
        for row in csv.DictReader((tmp_path / name).open()):
            seen |= {row[c] for c in cols}
    assert seen == {"True", "False"}


def test_quiet_drops_the_legend_not_the_table(tmp_path):
    _two_records(tmp_path)
    args = ["assess", "column", "s:R=0.5,alpha=14", "--records", str(tmp_path / "a.txt"), "--isolation", "none"]
    loud, quiet = invoke(args), invoke([*args, "-q"])
    assert loud.exit_code == quiet.exit_code == 0
    assert "xS: the smallest scale factor" in loud.stdout and "xS:" not in quiet.stdout
    assert loud.stdout.splitlines()[:5] == quiet.stdout.splitlines()[:5]
    assert max(len(line) for line in loud.stdout.splitlines()) < 250  # no 400-character legend


# --------------------------------------------------------------------------------------------------
# every --help example runs as written
# --------------------------------------------------------------------------------------------------
#: Examples that take minutes as written: run with the quick options their help names (or skipped).
QUICK = {
    ("spectrum", "overturning"): ["--wp-over-p", "2:6:2", "--ap", "1:5:2"],
    ("spectrum", "min-overturning"): ["--wp-over-p", "2:6:2", "--step", "0.1"],
    ("spectrum", "critical-size"): ["--wp-over-p", "2:6:2", "--step", "0.1"],
    ("assess", "column"): ["--no-margin"],
    ("assess", "fragility"): ["--glob", "RSN11*", "--isolation", "none", "--bootstrap", "100"],
}
SLOW = ("--full", "bench work-precision --csv", "bench stability --csv")


def _examples():
    for path, cmd in _walk():
        m = re.search(r"Examples?:\n(.*?)(?:\n\s*\n|\Z)", cmd.help or "", re.S)
        if not m:
            continue
        for line in m.group(1).replace("\\\n", " ").splitlines():
            if line.strip():
                yield pytest.param(path[1:], line.strip(), id=" ".join(path[1:]) + ": " + line.strip()[:60])


def test_every_command_that_prints_results_has_examples():
    have = {p.values[0] for p in _examples()}
    for path, _ in _walk():
        if path[1] != "bench":
            assert path[1:] in have, path


@needs_records
@pytest.mark.parametrize("path, line", list(_examples()))
def test_help_example_runs_as_written(path, line, tmp_path, monkeypatch):
    if any(s in line for s in SLOW):
        pytest.skip("minutes as written (the help says so)")
    words = shlex.split(line, comments=True)
    env = {}
    while "=" in words[0]:
        key, _, value = words.pop(0).partition("=")
        env[key] = value
    assert words[0] == "rockcli"
    shared = str(RECORDS.parent)

    def real(text: str) -> str:  # the examples are written from the repository root, next to ../shared
        return text.replace("../shared", shared)

    args = [real(w) for w in words[1:]]
    for key, value in env.items():
        monkeypatch.setenv(key, real(value))
    catalog = Path(__file__).resolve().parents[1] / "records" / "catalog.csv"
    (tmp_path / "catalog.csv").write_bytes(catalog.read_bytes())
    monkeypatch.setenv("ROCKCLI_CATALOG", str(tmp_path / "catalog.csv"))  # --update-catalog writes the copy
    args += QUICK.get(tuple(path), [])
    monkeypatch.chdir(tmp_path)
    res = CliRunner().invoke(main, args)
    assert res.exit_code == 0, f"{line}\n{res.output}"
    assert "Traceback" not in res.output


def test_a_dask_run_names_its_cluster_on_stderr(tmp_path):
    pytest.importorskip("distributed")
    args = ["spectrum", "overturning", "--alpha", "10", "--wp-over-p", "2:6:2", "--ap", "1:5:2", "--csv",
            tmp_path / "m.csv"]
    res = invoke([*args, "--scheduler", "local"])
    assert res.exit_code == 0, res.output
    line = next(ln for ln in res.stderr.splitlines() if ln.startswith("Dask:"))
    n = int(re.search(r"(\d+) worker\(s\)", line).group(1))
    assert "LocalCluster" in line and "tcp://" in line and n >= 1
    assert "dashboard" not in line  # the LocalCluster runs without one (dashboard_address=None)
    assert "Dask:" not in res.stdout
    assert invoke([*args[:-1], tmp_path / "n.csv"]).exit_code == 0
    assert (tmp_path / "m.csv").read_text() == (tmp_path / "n.csv").read_text()  # the same map either way


def test_fragility_help_speaks_of_the_body():
    """assess fragility takes any body (a statue, a cabinet): its help said "the column" (issue 35)."""
    res = invoke(["assess", "fragility", "--help"])
    assert res.exit_code == 0 and "P(the body overturns | IM)" in res.output
    assert "the column" not in res.output and "per column" not in res.output
