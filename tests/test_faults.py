"""Faults from outside (issue 23): signals during a write, a full disk, concurrent writers, a Dask
cluster whose worker dies, that has no worker, or an address that is not a Dask scheduler.

Every case runs in a subprocess or against real sockets and processes, and is bounded in time:
a signal leaves no partial output and no temporary file; a full disk leaves the earlier file as it
was; concurrent writers each leave a whole file; a cluster fault stops the run with one sentence
after the stated timeout (``ROCKCLI_DASK_TIMEOUT``), never a hang.
"""

from __future__ import annotations

import importlib.util
import json
import os
import resource
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from click.testing import CliRunner
from conftest import write_pulse_record

from rockcli.cli import main
from rockcli.errors import RockcliInputError

REPO = Path(__file__).resolve().parents[1]
ENV = {**os.environ, "PYTHONPATH": str(REPO)}


def _default_signals():
    """In the child: SIGINT, SIGHUP and SIGTERM act as in a terminal even when the test runner ignores or blocks
    them (a child inherits its parent thread's signal mask: in CI a worker had them blocked, and the child slept
    through them until the test's timeout)."""
    stops = (signal.SIGINT, signal.SIGHUP, signal.SIGTERM)
    for sig in stops:
        signal.signal(sig, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, stops)


def _signal_state(pid: int) -> str:
    """The signal lines of a live process's /proc status (pending, blocked, ignored, caught masks) and its threads."""
    try:
        lines = Path(f"/proc/{pid}/status").read_text().splitlines()
        threads = len(os.listdir(f"/proc/{pid}/task"))
    except OSError as exc:
        return f"(status unreadable: {exc})"
    keep = [ln for ln in lines if ln.startswith(("State", "ShdPnd", "SigPnd", "SigBlk", "SigIgn", "SigCgt"))]
    extra = []
    for name in ("syscall", "wchan"):
        try:
            extra.append(f"{name} {Path(f'/proc/{pid}/{name}').read_text().strip()}")
        except OSError as exc:
            extra.append(f"{name} unreadable ({exc.strerror})")
    return "; ".join(keep + extra) + f"; threads {threads}"


def listing(folder: Path) -> dict:
    return {str(p.relative_to(folder)): (p.read_bytes() if p.is_file() else "folder")
            for p in sorted(folder.rglob("*"))}


# --------------------------------------------------------------------------------------------------
# signals: the staged outputs of a run are removed, its created folders too, earlier files kept
# --------------------------------------------------------------------------------------------------
STAGED_RUN = r"""
import faulthandler, signal, sys, time
from pathlib import Path
faulthandler.register(signal.SIGUSR1)  # the test asks where the child is when it outlives its signal
from rockcli.io.files import transaction, write_bytes, write_text
out = Path(sys.argv[1])
with transaction() as t:
    t.declare(out / "table.csv", "--csv")
    t.declare_folder(out / "figs", "--plot")
    write_text(out / "table.csv", "the new table\n" * 1000)
    t.make_folder(out / "figs")
    for i in range(3):
        write_bytes(out / "figs" / f"run{i}.png", b"\x89PNG" + bytes(5000))
    print("staged", flush=True)
    for _ in range(600):  # a run: Python code between calls into C (see the test's docstring)
        time.sleep(0.1)
"""


@pytest.mark.parametrize("sig, code", [(signal.SIGTERM, -signal.SIGTERM), (signal.SIGHUP, -signal.SIGHUP),
                                       (signal.SIGINT, -signal.SIGINT)])
def test_signal_during_a_run_leaves_nothing(tmp_path, sig, code):
    """A run stopped by SIGTERM, SIGHUP or SIGINT removes its staged files and created folders, and dies by the signal.

    The child sleeps in steps of 0.1 s, as a run executes Python between its calls into compiled code. CPython runs
    a Python signal handler between bytecodes: a signal that lands after the interpreter's last check and before a
    blocking call starts is handled only when that call returns. With one 60 s sleep the child outlived the test's
    30 s timeout in 3 of 5 fresh-clone runs of the full suite (never alone), its signal taken (none pending) and its
    handler not run: that window is the one explanation the recorded process state leaves. If it happens again, the
    failure says where the child was (its /proc state, system call and Python stack)."""
    (tmp_path / "table.csv").write_text("the table of an earlier run\n")
    before = listing(tmp_path)
    proc = subprocess.Popen([sys.executable, "-c", STAGED_RUN, str(tmp_path)], env=ENV, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, preexec_fn=_default_signals)
    try:
        assert proc.stdout.readline().strip() == "staged"
        assert len(list(tmp_path.rglob(".*.tmp"))) == 4  # the staged files exist, hidden, next to their targets
        os.kill(proc.pid, sig)
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:  # say what the child's signal state was (it slept through the signal)
            staged = len(list(tmp_path.rglob(".*.tmp")))  # 4: its handler never discarded them; 0: it did
            state = _signal_state(proc.pid)
            os.kill(proc.pid, signal.SIGUSR1)  # its Python stack, on its stderr
            time.sleep(1)
            proc.kill()
            _, err = proc.communicate()
            pytest.fail(f"the child lived on 30 s after signal {sig}: {state}; {staged} staged files left; its "
                        f"stderr: {err[-2000:]}")
    finally:
        proc.kill()
        proc.wait()
    assert proc.returncode == code
    assert listing(tmp_path) == before  # no temporary file, no figs/ folder, the earlier table unchanged


def test_sigint_during_assess_plot_folder_leaves_no_folder(tmp_path):
    """The issue's example: SIGINT while `assess column --plot DIR` draws its figures."""
    write_pulse_record(tmp_path / "a.txt", 0.4, 0.7)
    write_pulse_record(tmp_path / "b.txt", 0.3, 0.5)
    args = [sys.executable, "-m", "rockcli", "assess", "column", "bassae", "nemea", "x:R=1,alpha=14", "--records",
            "a.txt", "--records", "b.txt", "--no-margin", "--isolation", "none", "--isolation", "linear:Tb=2",
            "--plot-dir", "figs", "--csv", "t.csv"]
    proc = subprocess.Popen(args, cwd=tmp_path, env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            preexec_fn=_default_signals)
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and proc.poll() is None:
            if list((tmp_path / "figs").glob(".*.tmp")):  # a figure is staged: the run is writing its folder
                break
            time.sleep(0.02)
        assert proc.poll() is None, "the run ended before a figure was staged"
        os.kill(proc.pid, signal.SIGINT)
        _, err = proc.communicate(timeout=30)
    finally:
        proc.kill()
        proc.wait()
    assert proc.returncode == 1 and b"Traceback" not in err, err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.txt", "b.txt"]  # no figs/, no t.csv, nothing hidden


# --------------------------------------------------------------------------------------------------
# a full disk (a file size limit) and concurrent writers
# --------------------------------------------------------------------------------------------------
def _small_files():
    resource.setrlimit(resource.RLIMIT_FSIZE, (1024, 1024))  # 1 KiB: the records list CSV is larger


def test_full_disk_keeps_the_earlier_file(tmp_path):
    (tmp_path / "out.csv").write_text("the earlier list\n")
    before = listing(tmp_path)
    res = subprocess.run([sys.executable, "-m", "rockcli", "records", "list", "--csv", "out.csv"], cwd=tmp_path,
                         env=ENV, capture_output=True, text=True, timeout=120, preexec_fn=_small_files)
    assert res.returncode == 2 and "Traceback" not in res.stderr, res.stderr
    assert res.stderr.strip().splitlines()[-1].startswith("Error: out.csv: cannot write there: the file is too large")
    assert listing(tmp_path) == before


def test_full_tmpfs_keeps_the_earlier_file(tmp_path):
    """A real full file system, where a small tmpfs can be mounted (root on Linux)."""
    mnt = tmp_path / "mnt"
    mnt.mkdir()
    if os.geteuid() != 0 or subprocess.run(["mount", "-t", "tmpfs", "-o", "size=16k", "tmpfs", str(mnt)],
                                           capture_output=True).returncode != 0:
        pytest.skip("cannot mount a small tmpfs here")
    try:
        (mnt / "out.csv").write_text("the earlier list\n")
        (mnt / "filler").write_bytes(bytes(12288))  # with out.csv's page: the 16 KiB are full
        before = listing(mnt)
        res = subprocess.run([sys.executable, "-m", "rockcli", "records", "list", "--csv", str(mnt / "out.csv")],
                             env=ENV, capture_output=True, text=True, timeout=120)
        assert res.returncode == 2 and "no space left on the device" in res.stderr, res.stderr
        assert listing(mnt) == before
    finally:
        subprocess.run(["umount", str(mnt)], capture_output=True)


def test_concurrent_writers_each_leave_a_whole_file(tmp_path):
    expected = CliRunner().invoke(main, ["records", "list", "--csv", str(tmp_path / "one.csv")])
    assert expected.exit_code == 0
    procs = [subprocess.Popen([sys.executable, "-m", "rockcli", "records", "list", "--csv", "same.csv"],
                              cwd=tmp_path, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
             for _ in range(4)]
    for p in procs:
        _, err = p.communicate(timeout=120)
        assert p.returncode == 0, err
    assert (tmp_path / "same.csv").read_bytes() == (tmp_path / "one.csv").read_bytes()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["one.csv", "same.csv"]  # no temporary file left


# --------------------------------------------------------------------------------------------------
# Dask: a real scheduler and worker on 127.0.0.1, and servers that are not Dask
# --------------------------------------------------------------------------------------------------
needs_dask = pytest.mark.skipif(importlib.util.find_spec("distributed") is None, reason="needs dask.distributed")
TIMEOUT = 2.0  # ROCKCLI_DASK_TIMEOUT in these tests [s]


@pytest.fixture
def dask_timeout(monkeypatch):
    monkeypatch.setenv("ROCKCLI_DASK_TIMEOUT", str(TIMEOUT))


def _start(args, tmp_path, name, **env):
    log = open(tmp_path / f"{name}.log", "w")
    return subprocess.Popen([sys.executable, "-m", *args], env={**ENV, **env}, stdout=log, stderr=log, cwd=tmp_path)


def _stop(proc):
    proc.kill()
    proc.wait(timeout=30)


def _scheduler(tmp_path, **env):
    """A `dask scheduler` subprocess on 127.0.0.1, no worker: (process, address)."""
    info = tmp_path / "scheduler.json"
    proc = _start(["distributed.cli.dask_scheduler", "--host", "127.0.0.1", "--port", "0", "--no-dashboard",
                   "--scheduler-file", str(info)], tmp_path, "scheduler", **env)
    deadline = time.monotonic() + 60
    while not info.exists() and time.monotonic() < deadline:
        time.sleep(0.1)
    if not info.exists():
        _stop(proc)
        pytest.fail((tmp_path / "scheduler.log").read_text())
    time.sleep(0.2)
    return proc, json.loads(info.read_text())["address"]


@pytest.fixture
def scheduler(tmp_path):
    """The address of a `dask scheduler` subprocess on 127.0.0.1 without a worker."""
    proc, address = _scheduler(tmp_path)
    yield address
    _stop(proc)


@pytest.fixture
def strict_scheduler(tmp_path):
    """As ``scheduler``, but a task whose worker dies once is given up at once (Dask's KilledWorker)."""
    proc, address = _scheduler(tmp_path, DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES="0")
    yield address
    _stop(proc)


def _server(reply: bytes):
    """A TCP server on 127.0.0.1 that accepts, sends ``reply`` (maybe nothing), and keeps the connection open."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen(8)
    held = []

    def serve():
        while True:
            try:
                conn, _ = srv.accept()
            except OSError:
                return
            held.append(conn)
            if reply:
                conn.sendall(reply)

    threading.Thread(target=serve, daemon=True).start()
    return srv, f"tcp://127.0.0.1:{srv.getsockname()[1]}"


SPECTRUM = ["spectrum", "overturning", "--alpha", "10", "--wp-over-p", "1:2:2", "--ap", "1:2:2"]


def _one_error(res, *words):
    lines = [ln for ln in res.output.splitlines() if ln.strip()]
    assert res.exit_code == 2 and "Traceback" not in res.output, res.output
    assert len(lines) == 1 and lines[0].startswith("Error: --scheduler"), res.output
    for w in words:
        assert w in lines[0], (w, res.output)


@needs_dask
@pytest.mark.parametrize("reply, words", [
    (b"", "says nothing in 2 s"),
    (b"HTTP/1.1 400 Bad Request\r\n\r\n", "does not speak the Dask protocol"),
    (b"\xff" * 16, "does not speak the Dask protocol"),  # a length field of 2^64 - 1 bytes: never allocated
])
def test_a_server_that_is_not_dask_is_refused(dask_timeout, tmp_path, reply, words):
    srv, address = _server(reply)
    try:
        t0 = time.monotonic()
        res = CliRunner().invoke(main, [*SPECTRUM, "--scheduler", address, "--csv", str(tmp_path / "m.csv")])
        assert time.monotonic() - t0 < 30
    finally:
        srv.close()
    _one_error(res, words)
    assert not (tmp_path / "m.csv").exists()


@needs_dask
def test_nothing_listening_names_the_local_cluster(tmp_path):
    """A scheduler address where nothing listens ("Connection refused"): the sentence says what to do, including
    running without a cluster of one's own (--scheduler local)."""
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    address = f"tcp://127.0.0.1:{srv.getsockname()[1]}"
    srv.close()  # the port is free again: nothing listens there
    res = CliRunner().invoke(main, [*SPECTRUM, "--scheduler", address, "--csv", str(tmp_path / "m.csv")])
    _one_error(res, "cannot connect", "--scheduler local")
    assert not (tmp_path / "m.csv").exists()


@needs_dask
@pytest.mark.parametrize("address", ["tls://127.0.0.1:8786", "inproc://127.0.0.1/1/2", "ucx://127.0.0.1:8786",
                                     "ws://127.0.0.1:8786", "tcp://127.0.0.1:70000"])
def test_other_protocols_are_refused_up_front(address):
    res = CliRunner().invoke(main, [*SPECTRUM, "--scheduler", address])
    _one_error(res)


@needs_dask
def test_a_scheduler_without_worker_stops_after_the_timeout(dask_timeout, scheduler, tmp_path):
    res = CliRunner().invoke(main, [*SPECTRUM, "--scheduler", scheduler, "--csv", str(tmp_path / "m.csv")])
    _one_error(res, "no worker joined the scheduler within 2 s")
    assert not (tmp_path / "m.csv").exists()


@needs_dask
def test_the_only_worker_killed_mid_run_stops_with_one_sentence(dask_timeout, scheduler, tmp_path):
    from rockcli.distributed import map_chunks, open_client

    worker = _start(["distributed.cli.dask_worker", scheduler, "--no-nanny", "--nthreads", "1", "--no-dashboard"],
                    tmp_path, "worker")
    try:
        with open_client(scheduler, timeout=60) as client:
            assert len(client.scheduler_info()["workers"]) == 1
            threading.Timer(1.0, worker.kill).start()  # the worker dies while it sleeps in the task
            t0 = time.monotonic()
            with pytest.raises(RockcliInputError, match=r"has had no worker for 2 s .*no result is given"):
                map_chunks(client, time.sleep, [30.0, 30.0])
            assert time.monotonic() - t0 < 25  # the timeout and a few polls, not the tasks' 30 s
    finally:
        _stop(worker)



@needs_dask
def test_a_task_that_kills_its_worker_stops_with_one_sentence(dask_timeout, strict_scheduler, tmp_path):
    from rockcli.distributed import map_chunks, open_client

    worker = _start(["distributed.cli.dask_worker", strict_scheduler, "--nthreads", "1", "--no-dashboard"], tmp_path,
                    "worker")
    try:
        with open_client(strict_scheduler, timeout=60) as client:
            with pytest.raises(RockcliInputError, match=r"died each time it was tried \(Dask's KilledWorker"):
                map_chunks(client, os._exit, [3])  # the task ends its worker's process (the nanny restarts it)
    finally:
        _stop(worker)


# --------------------------------------------------------------------------------------------------
# searches end: a bisection tolerance below what double precision resolves is raised to a floor
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("rtol", [0.0, 1e-300])
def test_margin_bisection_below_double_precision_ends(rtol):
    from rockcli.assess import find_overturn_scales, parse_column_spec
    from rockcli.assess.margin import RTOL_FLOOR
    from rockcli.models import Rigid
    from rockcli.pulses import make_pulse
    from rockcli.io.units import G

    block = parse_column_spec("a:R=0.8,alpha=12")
    scene = (block, Rigid(), make_pulse("ricker-sym", 0.5 * G, 0.6))
    found = []
    worker = threading.Thread(target=lambda: found.extend(find_overturn_scales([scene], rtol=rtol)), daemon=True)
    worker.start()
    worker.join(timeout=120)
    assert not worker.is_alive(), "the bisection did not end"
    hi, lo, note = found[0]
    assert note == "" and 0 < hi / lo - 1 <= RTOL_FLOOR  # bracketed to the floor: a few ulps
    coarse = find_overturn_scales([scene])[0]  # the default 1 % bracket holds the fine one
    assert coarse[1] <= lo < hi <= coarse[0]


# --------------------------------------------------------------------------------------------------
# numba's disk cache: never a condition of a run
# --------------------------------------------------------------------------------------------------
KERNEL_CALL = ("import numpy as np; from rockcli.kernels import polynomials as p; "
               "print(p._first_exceed(np.array([0.0, 1.0, 0.0, 0.0, 0.0]), 0.5)[0])")


def test_kernels_run_without_a_writable_cache_or_with_a_full_disk(tmp_path):
    """No folder for the cache (one under a regular file: even root cannot make it), and a cache folder on a
    'full disk' (a 512-byte file size limit): the kernel runs, one notice line each, no temporary file left.
    Both cases compile one small kernel in memory, in parallel."""
    (tmp_path / "afile").write_text("a file: no folder can be made under it\n")
    cases = {"no folder": (tmp_path / "afile" / "numba", None, "rockcli: numba's disk cache cannot be written"),
             "full disk": (tmp_path / "cache", lambda: resource.setrlimit(resource.RLIMIT_FSIZE, (512, 512)),
                           "rockcli: numba's disk cache could not be written")}
    procs = {k: subprocess.Popen([sys.executable, "-c", KERNEL_CALL], env={**ENV, "NUMBA_CACHE_DIR": str(folder)},
                                 stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, preexec_fn=limit)
             for k, (folder, limit, _) in cases.items()}
    for k, proc in procs.items():
        out, err = proc.communicate(timeout=300)
        assert proc.returncode == 0, (k, err)
        assert abs(float(out) - 0.5) < 1e-12  # the polynomial c(x) = x first exceeds 0.5 at x = 0.5
        notes = err.strip().splitlines()
        assert len(notes) == 1 and notes[0].startswith(cases[k][2]), (k, err)
    assert not [p for p in (tmp_path / "cache").rglob("*") if ".tmp." in p.name]  # numba's partial files removed
