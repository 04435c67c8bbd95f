"""The Python entry point (issue 26 item 4): the main names importable from ``rockcli`` itself,
lazily (PEP 562), so that ``import rockcli`` imports none of the heavy dependencies; and
``docs/python.md``, whose code blocks run here in order, in one namespace."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from rockcli.errors import RockcliInputError

ROOT = Path(__file__).resolve().parents[1]
HEAVY = ("numba", "obspy", "pandas", "matplotlib", "scipy")


def _fresh(code: str) -> str:
    """Run ``code`` in a fresh interpreter on this tree; its stdout."""
    env = {"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin"}
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, env=env, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    return out.stdout


def test_import_rockcli_imports_no_heavy_dependency():
    loaded = _fresh("import sys, rockcli; print(' '.join(sorted(m for m in sys.modules if m.split('.')[0] in "
                    f"{HEAVY!r})))")
    assert loaded.split() == []


def test_every_advertised_name_resolves_and_stays_light():
    code = ("import sys, rockcli\n"
            "names = [n for n in rockcli.__all__ if n != '__version__']\n"
            "objs = [getattr(rockcli, n) for n in names]\n"
            "assert set(names) <= set(dir(rockcli))\n"
            f"print(len(names), ' '.join(sorted(m for m in sys.modules if m.split('.')[0] in {HEAVY!r})))")
    n, *heavy = _fresh(code).split()
    assert int(n) >= 25
    assert "numba" not in heavy and "matplotlib" not in heavy and "pandas" not in heavy  # no run yet, no report


def test_names_are_the_library_objects():
    import rockcli
    from rockcli.models import Block
    from rockcli.solve import simulate, simulate_many

    assert rockcli.Block is Block and rockcli.simulate is simulate and rockcli.simulate_many is simulate_many
    from rockcli import make_pulse, read_record  # noqa: F401  (the from-import form)
    with pytest.raises(AttributeError, match="no attribute 'nonsense'"):
        rockcli.nonsense  # noqa: B018


def _blocks(page: Path) -> list[str]:
    return re.findall(r"^```python\n(.*?)^```", page.read_text(), flags=re.S | re.M)


def test_the_python_page_runs(records_dirs, capsys):
    blocks = _blocks(ROOT / "docs" / "python.md")
    assert len(blocks) >= 4
    ns: dict = {}
    for code in blocks:
        exec(compile(code, "docs/python.md", "exec"), ns)  # noqa: S102
    out = capsys.readouterr().out
    res, peaks = ns["res"], ns["peaks"]
    assert res.verdict == "rocked" and "impact:" in out
    assert max(abs(e.theta_rad) for e in peaks) == pytest.approx(res.theta_max, rel=1e-8)
    assert ns["m"].overturned.shape == (5, 5) and ns["m"].overturned.any() and not ns["m"].overturned.all()
    # the assessment from Python (issue 35): the verdicts in plain words and the rows as a DataFrame
    table = ns["table"]
    assert list(table.configuration) == ["none", "Tb=2.5s"] and "In short:" in out
    assert table.verdict[0] == "overturned" and table.overturn_scale[0] < 1 < table.overturn_scale[1]
    # azimuth="worst" (issue 44): one row, its most adverse orientation's, and the motion that row ran
    row = ns["row"]
    assert len(ns["worst"].rows) == 1 and row.azimuths_run == 12 and row.azimuth_deg in ns["pairs"][0].azimuths
    assert ns["worst"].excitation_of(row).label == f"{row.record}@{row.azimuth_deg:g}"


def _pulse_suite():
    from rockcli import parse_configurations, resolve_excitations
    from rockcli.assess import parse_column_spec

    xs, unavailable = resolve_excitations(["kobe-1995-takarazuka-000", "northridge-1994-jensen-generator-022"], "pulse")
    return [parse_column_spec("statue:height=1.8,width=0.5")], xs, parse_configurations(["none", "linear:Tb=2.5"])


def test_the_pair_resolve_excitations_returns_is_refused_in_one_sentence():
    from rockcli import resolve_excitations, run_assessment, run_fragility

    columns, _, confs = _pulse_suite()
    pair = resolve_excitations(["kobe-1995-takarazuka-000"], "pulse")
    for run in (run_assessment, run_fragility):
        with pytest.raises(RockcliInputError, match=r"unavailable = resolve_excitations\(\[\.\.\.\]\); got a list"):
            run(columns, pair, confs)
    with pytest.raises(RockcliInputError, match="got str"):
        run_assessment(columns, ["kobe-1995-takarazuka-000"], confs)


def test_results_give_the_csv_as_a_dataframe(tmp_path):
    """``to_dataframe()`` is the CSV report's table (the same columns and values), built in rockcli.report."""
    import pandas as pd

    from rockcli import run_assessment, run_fragility
    from rockcli.report.fragility import write_fragility_csv
    from rockcli.report.tables import write_assessment_csv

    columns, xs, confs = _pulse_suite()
    result = run_assessment(columns, xs, confs, margin=False)
    df = result.to_dataframe()
    write_assessment_csv(result, tmp_path / "a.csv")
    csv = pd.read_csv(tmp_path / "a.csv")
    assert list(df.columns) == list(csv.columns) and len(df) == 4
    assert list(df.verdict) == list(csv.verdict) and np.allclose(df.theta_max_over_alpha, csv.theta_max_over_alpha)
    fr = run_fragility(columns, xs, confs, n_boot=0)
    df = fr.to_dataframe()
    write_fragility_csv(fr, tmp_path / "f.csv")
    csv = pd.read_csv(tmp_path / "f.csv")
    assert list(df.columns) == list(csv.columns) and np.allclose(df.capacity_g, csv.capacity_g)
