"""``assess column --scheduler`` (issue 33 item 6): the verdicts, the margin searches (the orientations of
``--azimuth worst`` searched together, one group per task at most) and the neighbourhood as Dask tasks, with
the local run's results, byte for byte in the CSV."""

from __future__ import annotations

import math

import numpy as np
import pytest
from click.testing import CliRunner

from rockcli.cli import main

from conftest import write_pulse_record


def _write(path, acc_g, dt=0.01):
    path.write_text(f"# dt={dt} sec\n# units: g\n" + "\n".join(f"{v:.12e}" for v in acc_g) + "\n")
    return path


@pytest.fixture()
def small_suite(tmp_path):
    """A pair (a sine pulse along 60 deg and a weaker cross motion; sensors at 0 and 90 deg) and two single
    records."""
    t = np.arange(0, 6, 0.01)
    along = 0.45 * np.sin(2 * np.pi * t / 0.8) * (t < 0.8)
    cross = 0.2 * np.sin(2 * np.pi * t / 0.5) * ((t > 1) & (t < 2))
    c, s = math.cos(math.radians(60)), math.sin(math.radians(60))
    north = _write(tmp_path / "n.txt", along * c - cross * s)
    east = _write(tmp_path / "e.txt", along * s + cross * c)
    one = write_pulse_record(tmp_path / "one.txt", 0.4, 0.6, "ricker-sym", pad=2.0)
    two = write_pulse_record(tmp_path / "two.txt", -0.3, 0.9, "ricker-anti", pad=2.0)
    return [f"{north}@0+{east}@90", str(one), str(two)]


def test_assess_column_on_a_local_dask_cluster_writes_the_local_csv(small_suite, tmp_path):
    """--scheduler local: the same CSV, byte for byte, as the run on this machine (pair and singles, margins,
    neighbourhood), and the cluster named on stderr; --azimuth worst with a single record is an error row in
    both."""
    pytest.importorskip("distributed")
    args = ["assess", "column", "small:R=0.6,alpha=12", "--isolation", "none", "--isolation", "linear:Tb=2",
            "--neighbourhood", "--azimuth", "worst", "--azimuth-step", "60"]
    for src in small_suite:
        args += ["--records", src]
    here = CliRunner().invoke(main, [*args, "--csv", str(tmp_path / "here.csv")])
    assert here.exit_code == 0, here.output
    there = CliRunner().invoke(main, [*args, "--csv", str(tmp_path / "dask.csv"), "--scheduler", "local"])
    assert there.exit_code == 0, there.output
    assert "LocalCluster" in there.stderr and "Dask:" not in there.stdout
    assert (tmp_path / "dask.csv").read_bytes() == (tmp_path / "here.csv").read_bytes()
    text = (tmp_path / "here.csv").read_text()
    assert "n.txt+e.txt" in text and text.count("\n") == 1 + 3 * 2


def test_assessment_parts_on_dask_are_announced_and_equal_the_local_rows(small_suite):
    """The library: :func:`rockcli.assess.cluster.run_on_dask` on an in-process cluster of two workers (a pair's
    orientations and two single records); each part announced as ``<part> on Dask (N tasks)`` in scenes, every
    step told; the rows equal the local ones."""
    distributed = pytest.importorskip("distributed")
    import dataclasses

    from rockcli.assess import parse_column_spec, parse_configurations, resolve_excitations, run_assessment
    from rockcli.assess.azimuth import collapse, expand
    from rockcli.assess.cluster import run_on_dask
    from rockcli.records.orientation import sweep_azimuths

    xs = resolve_excitations(small_suite[:1], "record", azimuth="worst")[0] + resolve_excitations(small_suite[1:])[0]
    subs, groups = expand(xs, sweep_azimuths(45.0))
    columns = [parse_column_spec("small:R=0.6,alpha=12"), parse_column_spec("big:R=1.2,alpha=10")]
    configs = parse_configurations(["none", "linear:Tb=2.5"])
    parts = []

    class Progress:
        def phase(self, name, steps, *, known, unit):
            parts.append([name, steps, unit, 0])

        def __call__(self, n):
            parts[-1][3] += n

    kw = dict(orientations=groups, neighbourhood=True, horizon=3.0)
    local = collapse(run_assessment(columns, subs, configs, **kw), xs, groups)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None) as cl, \
            distributed.Client(cl) as client:
        remote = collapse(run_on_dask(client, columns, subs, configs, progress=Progress(), **kw), xs, groups)
    same = [all(a == b or (a != a and b != b) for a, b in zip(dataclasses.astuple(r), dataclasses.astuple(s)))
            for r, s in zip(remote.rows, local.rows)]
    assert len(same) == len(local.rows) == 12 and all(same)
    n = len(columns) * len(subs) * len(configs)  # 2 columns x (4 orientations + 2 singles) x 2 configurations
    names = [p[0].split(" on Dask")[0] for p in parts]
    assert names == ["verdicts", "margin search", "neighbourhood"], parts
    assert all(p[0].endswith("tasks)") and p[2] == "scenes" and p[1] == p[3] for p in parts), parts
    assert parts[0][1] == parts[1][1] == n and parts[2][1] == len(local.rows)


def test_a_scheduler_address_that_is_none_is_refused_before_any_run(small_suite):
    """One sentence naming --scheduler, exit 2, before the records are read (as assess fragility and the
    spectra do)."""
    res = CliRunner().invoke(main, ["assess", "column", "bassae", "--records", small_suite[1], "--scheduler",
                                    "http//x"])
    assert res.exit_code == 2 and "--scheduler" in res.output and "Traceback" not in res.output, res.output
