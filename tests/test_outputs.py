"""The output layer (issue 23): a run's outputs are one transaction, checked before the work.

Each example of the issue: an output on an input (the record, the catalogue), two outputs on one
path (also through a symbolic link), ``fit-pulse --update-catalog`` keeping a user's columns, a
link and its mode, ``assess column --histories`` leaving ``--csv`` and an earlier run's files alone
when a history write fails and refusing two runs whose names give one file name, a temporary name
longer than NAME_MAX, a full or closed standard output, ``NUMBA_NUM_THREADS=0`` and ``--seed -1``.
Faults (signals, a full disk, concurrent writers, a Dask cluster) are in ``test_faults.py``.
"""

from __future__ import annotations

import csv
import io
import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import write_pulse_record

from rockcli.cli import main
from rockcli.errors import RockcliInputError
from rockcli.io.files import Transaction, transaction, write_text
from rockcli.records.catalog import COLUMNS

REPO = Path(__file__).resolve().parents[1]
SIM = ["simulate", "--height", "2", "--width", "0.5"]
ASSESS = ["assess", "column", "--no-margin", "--isolation", "none"]


def run_cli(args):
    return CliRunner().invoke(main, [str(a) for a in args])


def snapshot(folder: Path) -> dict:
    """Every path under ``folder`` (hidden ones too), files with their bytes."""
    return {str(p.relative_to(folder)): (p.read_bytes() if p.is_file() else "folder")
            for p in sorted(folder.rglob("*"))}


def one_error(res, *words):
    out = res.output
    lines = [ln for ln in out.splitlines() if ln.strip()]
    assert res.exit_code == 2 and "Traceback" not in out, out
    assert len(lines) == 1 and lines[0].startswith("Error: "), out
    for w in words:
        assert w in lines[0], (w, out)


def _catalogue(folder: Path, extra_column: str | None = None) -> Path:
    """A one-record catalogue (a synthetic Ricker record in ``folder``), optionally with a user's column."""
    write_pulse_record(folder / "syn.txt", 0.4, 0.7)
    row = {c: "" for c in COLUMNS}
    row.update(id="syn-2000-test-000", event="Synthetic", year="2000", station="Test", component="000",
               file="syn.txt", format="TEXT", units="g", dt="0.01", available="yes", notes="a test record")
    head = list(COLUMNS) + ([extra_column] if extra_column else [])
    if extra_column:
        row[extra_column] = "my own note, with a comma"
    buf = io.StringIO()
    writer = csv.writer(buf, lineterminator="\n")
    writer.writerow(head)
    writer.writerow([row[c] for c in head])
    path = folder / "catalog.csv"
    path.write_text(buf.getvalue())
    return path


@pytest.fixture
def work(tmp_path, monkeypatch):
    """A scratch folder (the current directory) with a synthetic record, its own catalogue and record path."""
    monkeypatch.chdir(tmp_path)
    monkeypatch.setenv("ROCKCLI_RECORDS", str(tmp_path))
    monkeypatch.setenv("ROCKCLI_CATALOG", str(_catalogue(tmp_path)))
    return tmp_path


# --------------------------------------------------------------------------------------------------
# outputs against inputs and against each other, before any work
# --------------------------------------------------------------------------------------------------
def test_history_onto_the_record_is_refused(work):
    before = snapshot(work)
    res = run_cli([*SIM, "--record", "syn.txt", "--history", "syn.txt"])
    one_error(res, "--history syn.txt", "is also an input", "the record")
    assert snapshot(work) == before


def test_history_onto_the_record_through_a_link_is_refused(work):
    (work / "alias.txt").symlink_to(work / "syn.txt")
    before = snapshot(work)
    one_error(run_cli([*SIM, "--record", "syn.txt", "--history", "alias.txt"]), "is also an input")
    os.link(work / "syn.txt", work / "hard.txt")  # a hard link: another name, the same file
    before = snapshot(work)
    one_error(run_cli([*SIM, "--record", "hard.txt", "--history", "syn.txt"]), "is also an input")
    assert snapshot(work) == before


@pytest.mark.parametrize("args", [
    ["records", "list", "--csv", "catalog.csv"],
    ["fit-pulse", "syn.txt", "--csv", "catalog.csv"],
    [*SIM, "--pulse", "sine:ap=0.5,Tp=0.5", "--history", "./catalog.csv"],
])
def test_an_output_onto_the_catalogue_is_refused(work, args):
    before = snapshot(work)
    one_error(run_cli(args), "catalog.csv", "is also an input", "the record catalogue")
    assert snapshot(work) == before
    assert run_cli(["records", "list"]).exit_code == 0  # the catalogue still works


def test_two_outputs_on_one_path_are_refused(work):
    before = snapshot(work)
    one_error(run_cli(["fit-pulse", "syn.txt", "--csv", "out.png", "--plot", "out.png"]),
              "--csv out.png and --plot out.png are the same file")
    assert snapshot(work) == before
    (work / "link.png").symlink_to("real.png")  # a dangling link: it names the file --plot names
    one_error(run_cli(["fit-pulse", "syn.txt", "--csv", "link.png", "--plot", "real.png"]), "are the same file")
    assert not (work / "real.png").exists() and not list(work.glob(".*"))


def test_transaction_checks_inputs_declared_after_outputs(tmp_path):
    t = Transaction()
    t.declare(tmp_path / "a.csv", "--csv")
    with pytest.raises(RockcliInputError, match="--csv .*a.csv is also an input"):
        t.add_inputs([tmp_path / "." / "a.csv"], "the record")


# --------------------------------------------------------------------------------------------------
# replaced in place: links stay links, modes stay; the catalogue keeps every column
# --------------------------------------------------------------------------------------------------
def test_an_output_through_a_link_keeps_the_link_and_the_mode(work):
    (work / "data").mkdir()
    real = work / "data" / "real.csv"
    real.write_text("old\n")
    real.chmod(0o640)
    (work / "link.csv").symlink_to(real)
    res = run_cli(["records", "list", "--csv", "link.csv"])
    assert res.exit_code == 0, res.output
    assert (work / "link.csv").is_symlink() and os.readlink(work / "link.csv") == str(real)
    assert real.read_text().startswith("id,") and stat.S_IMODE(real.stat().st_mode) == 0o640
    assert not [p for p in work.rglob(".*")]  # no temporary file left


def test_update_catalog_keeps_user_columns_link_and_mode(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "shared").mkdir()
    real = _catalogue(tmp_path / "shared", extra_column="my_notes")
    real.chmod(0o640)
    link = tmp_path / "catalog-link.csv"
    link.symlink_to(real)
    monkeypatch.setenv("ROCKCLI_RECORDS", str(tmp_path / "shared"))
    monkeypatch.setenv("ROCKCLI_CATALOG", str(link))
    before = list(csv.DictReader(io.StringIO(real.read_text())))
    res = run_cli(["fit-pulse", "--catalog", "--update-catalog"])
    assert res.exit_code == 0, res.output
    assert link.is_symlink() and os.readlink(link) == str(real)
    assert stat.S_IMODE(real.stat().st_mode) == 0o640
    after = list(csv.DictReader(io.StringIO(real.read_text())))
    assert list(after[0]) == list(before[0])  # every column, the user's own included, in its place
    pulse = {"pulse_shape", "a_p_g", "T_p_s", "t0_s", "pulse_energy"}
    assert {k: v for k, v in after[0].items() if k not in pulse} == {k: v for k, v in before[0].items()
                                                                    if k not in pulse}
    assert after[0]["pulse_shape"] == "ricker-sym" and abs(float(after[0]["T_p_s"]) - 0.7) < 0.07
    assert abs(float(after[0]["a_p_g"]) - 0.4) < 0.04  # the synthetic record is a 0.4 g, 0.7 s Ricker pulse


# --------------------------------------------------------------------------------------------------
# assess column --histories / --plot
# --------------------------------------------------------------------------------------------------
def test_assess_refuses_two_runs_with_one_file_name(work):
    before = snapshot(work)
    res = run_cli([*ASSESS, "a#b:R=1,alpha=14", "a_b:R=1.2,alpha=14", "--records", "syn.txt", "--history-dir", "h"])
    one_error(res, "a#b", "a_b", "would write the same file")
    assert snapshot(work) == before


def test_assess_history_failure_keeps_csv_and_earlier_histories(work, monkeypatch):
    import rockcli.io.files

    args = [*ASSESS, "bassae", "nemea", "--records", "syn.txt", "--csv", "table.csv", "--history-dir", "h"]
    first = run_cli(args)
    assert first.exit_code == 0, first.output
    earlier = snapshot(work)
    assert len([k for k in earlier if k.startswith("h/")]) == 2

    calls = []

    def failing(fh, data):  # the second history file meets a full disk
        if "/h/" in fh.name:
            calls.append(fh.name)
            if len(calls) == 2:
                raise OSError(28, "No space left on device")
        fh.write(data)

    monkeypatch.setattr(rockcli.io.files, "_write", failing)
    (work / "table.csv").write_text("the table of an earlier run\n")
    earlier = snapshot(work)
    res = run_cli(args)
    assert res.exit_code == 2 and "no space left on the device" in res.output and "Traceback" not in res.output
    assert snapshot(work) == earlier  # --csv not rewritten, the earlier histories kept, no temporary file


# --------------------------------------------------------------------------------------------------
# names near the file system's limit
# --------------------------------------------------------------------------------------------------
def test_temporary_name_never_exceeds_name_max(work):
    limit = os.pathconf(work, "PC_NAME_MAX")
    name = "t" * (limit - 4) + ".csv"  # the longest allowed name: a suffixed temporary name would not fit
    res = run_cli(["records", "list", "--csv", name])
    assert res.exit_code == 0, res.output
    assert (work / name).read_text().startswith("id,")
    long = "t" * (limit + 1) + ".csv"
    one_error(run_cli(["records", "list", "--csv", long]), "more than this file system's limit")


def test_library_write_without_transaction_is_atomic_and_joins_an_open_one(tmp_path):
    target = tmp_path / "a.txt"
    write_text(target, "one\n")
    assert target.read_text() == "one\n"
    with pytest.raises(RuntimeError):
        with transaction():
            write_text(target, "two\n")
            assert target.read_text() == "one\n"  # staged, not yet visible
            raise RuntimeError("the run fails")
    assert target.read_text() == "one\n" and sorted(p.name for p in tmp_path.iterdir()) == ["a.txt"]


# --------------------------------------------------------------------------------------------------
# the environment: standard output, numba's threads, seeds
# --------------------------------------------------------------------------------------------------
def _run(args, env=None, **kw):
    full = {**os.environ, "PYTHONPATH": str(REPO), **(env or {})}
    return subprocess.run([sys.executable, "-m", "rockcli", *args], env=full, capture_output=True, text=True,
                          timeout=120, **kw)


def test_full_stdout_one_sentence_and_no_file(work):
    with open("/dev/full", "w") as full:
        res = subprocess.run([sys.executable, "-m", "rockcli", "records", "list", "--csv", "out.csv"],
                             env={**os.environ, "PYTHONPATH": str(REPO)}, stdout=full, stderr=subprocess.PIPE,
                             text=True, timeout=120)
    assert res.returncode == 2 and "Traceback" not in res.stderr, res.stderr
    assert res.stderr.strip().splitlines() == [
        "Error: cannot write to the standard output (no space left on the device); no file was written"]
    assert not (work / "out.csv").exists()


def test_closed_stdout_clean_exit(work):
    res = subprocess.run([sys.executable, "-c", "import sys; sys.argv = ['rockcli', 'records', 'list', '--csv', "
                          "'out.csv']; from rockcli.cli import run; run()"],
                         env={**os.environ, "PYTHONPATH": str(REPO)}, stdout=subprocess.DEVNULL,
                         stderr=subprocess.PIPE, text=True, timeout=120, pass_fds=(),
                         preexec_fn=lambda: os.close(1))
    assert res.returncode == 0 and res.stderr == "", res.stderr
    assert (work / "out.csv").read_text().startswith("id,")


def test_numba_num_threads_zero_one_sentence(work):
    res = _run([*SIM, "--pulse", "sine:ap=0.5,Tp=0.5"], env={"NUMBA_NUM_THREADS": "0"})
    assert res.returncode == 2 and "Traceback" not in res.stderr
    assert res.stderr.strip().splitlines() == ["Error: NUMBA_NUM_THREADS=0: give a positive number of threads, "
                                               "or unset it"]


@pytest.mark.parametrize("args", [["bench", "stability", "--random", "1", "--seed", "-1"],
                                  ["assess", "fragility", "bassae", "--records", "syn.txt", "--seed", "-1"]])
def test_negative_seed_is_refused(work, args):
    res = run_cli(args)
    assert res.exit_code == 2 and "Traceback" not in res.output and "--seed" in res.output, res.output
