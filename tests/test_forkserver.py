"""The tests' fork server (tests/forkserver.py) runs a ``rockcli`` command as the real process does.

Each command runs both ways, through the server's client and as the real process (what the plain shim runs),
from bash with ``-o pipefail`` as tests/test_docs.py runs a page's block, and must give the same exit code,
standard output and standard error; the server's log must show that it ran the command itself (a declined
request, which the client runs as the real process, would make the comparison empty), except where it must
decline (an environment variable read at import set on the command line).

No rockcli command reads its standard input; the descriptors reach the child all three alike (SCM_RIGHTS), and
the terminal test below checks one of them for what a command asks of it (``isatty``).
"""

from __future__ import annotations

import os
import pty
import re
import select
import signal
import subprocess
import time
from pathlib import Path

import pytest

import forkserver
import forkserver_warmup

ROOT = Path(__file__).resolve().parents[1]
SLOW = "rockcli assess column bassae nemea"  # the main job: seconds of margin search after the first progress line


@pytest.fixture(scope="module")
def both(tmp_path_factory, fork_servers, records_dir):
    """``{"server": env, "real": env}``: environments whose PATH finds ``rockcli`` as the server's client, or
    as the real process; and the server's log reader."""
    if not forkserver.enabled():
        pytest.skip(f"{forkserver.DISABLE_ENV} turns the fork server off")
    base = tmp_path_factory.mktemp("forkserver")
    envs = {}
    for way in ("server", "real"):
        bin_dir = base / way
        bin_dir.mkdir()
        # Python's default buffering of the standard streams (which the child rebuilds), whatever the suite's
        env = {k: v for k, v in os.environ.items() if k != "PYTHONUNBUFFERED"}
        env.update(PATH=f"{bin_dir}{os.pathsep}{os.environ.get('PATH', '')}", PYTHONPATH=str(ROOT), MPLBACKEND="Agg")
        shim = bin_dir / "rockcli"
        shim.write_text(fork_servers.shim(env) if way == "server" else fork_servers.real_shim())
        shim.chmod(0o755)
        envs[way] = env
    if "forkserver_client.py" not in (base / "server" / "rockcli").read_text():
        pytest.fail("the fork server did not start (see the warning above)")
    work = base / "work"
    work.mkdir()
    return envs, work, lambda: fork_servers.log(envs["server"])


def _bash(script: str, env: dict, cwd: Path, **kwargs):
    return subprocess.run(["bash", "-e", "-o", "pipefail", "-c", script], env=env, cwd=cwd, capture_output=True,
                          timeout=300, **kwargs)


def _served(log: str, args: str) -> list[str]:
    """The exit lines of the server's log for the command ``rockcli args``."""
    return [line for line in log.splitlines() if line.rstrip().endswith(f": rockcli {args}".rstrip())]


def _args(script: str) -> str:
    """The arguments of the rockcli command of a one-command ``script``."""
    return re.sub(r"^(\w+=\S+ )*rockcli ?", "", re.split(r" *(?:\||<&-|>|;)", script)[0].strip())


CASES = [
    # a single run, its verdict as JSON on stdout
    ("rockcli simulate --body nemea --pulse ricker-sym:ap=0.3,Tp=0.5 --json", 0),
    # bad input: one sentence, exit code 2
    ("rockcli simulate --body nemea --pulse nonsense:ap=0.3,Tp=0.5", 2),
    ("rockcli nope", 2),
    ("rockcli", 2),
    # a pipe to another command (which reads it all: see test_a_pipe_closed_early for a reader that does not)
    ("rockcli records list | tail -n 2", 0),
    # an environment variable given on the command line, read when the command runs
    ("ROCKCLI_RECORDS=/nonexistent/records rockcli records list", 2),
    # the standard input closed, the output to a file
    ("rockcli --version <&- > out.txt; cat out.txt", 0),
]


@pytest.mark.parametrize("script, code", CASES, ids=[c[0] for c in CASES])
def test_same_as_the_real_process(both, script, code):
    envs, work, log = both
    before = len(_served(log(), _args(script)))
    real, served = (_bash(script, envs[way], work) for way in ("real", "server"))
    assert real.returncode == code, real.stderr.decode()
    assert (served.returncode, served.stdout, served.stderr) == (real.returncode, real.stdout, real.stderr)
    assert len(_served(log(), _args(script))) == before + 1, f"the server did not run {script!r}:\n{log()}"
    if code == 2 and script != "rockcli":  # bad input (rockcli alone: click's usage, on stderr, exit code 2)
        assert served.stderr.decode().strip().splitlines()[-1].startswith("Error: "), served.stderr


def test_a_figure_is_the_real_process_figure(both):
    """The server has drawn a figure before forking (fonts, the mathtext parser: forkserver_warmup._draw_once):
    a command's figure is still byte for byte the real process's."""
    envs, work, log = both
    cmd = "rockcli simulate --height 1.79 --width 0.5 --pulse sine:ap=0.3,Tp=0.6 --plot fig.png"
    figures = []
    for way in ("real", "server"):
        done = _bash(cmd, envs[way], work)
        assert done.returncode == 0, done.stderr
        figures.append((work / "fig.png").read_bytes())
        (work / "fig.png").unlink()
    assert figures[0][:8] == b"\x89PNG\r\n\x1a\n" and figures[0] == figures[1]
    assert _served(log(), _args(cmd))


def test_a_pipe_closed_early(both):
    """``rockcli ... | head`` where head has gone before rockcli writes: the first write fails (EPIPE; Python
    ignores SIGPIPE), rockcli's exit code and message are the real process's. (In a shell pipeline whether the
    reader has gone by then is a race; here its end of the pipe is closed before the command starts.)"""
    envs, work, log = both
    results = []
    for way in ("real", "server"):
        r, w = os.pipe()
        os.close(r)
        proc = subprocess.run(["rockcli", "records", "list"], env=envs[way], cwd=work, stdout=w,
                              stderr=subprocess.PIPE, timeout=300)
        os.close(w)
        results.append((proc.returncode, proc.stderr))
    assert results[0] == results[1]
    assert results[0][0] != 0, results[0]


def test_a_variable_read_at_import_makes_it_decline(both):
    """NUMBA_NUM_THREADS is read when the kernels are imported (rockcli refuses 0 in one sentence): the server,
    which imported them under another value, declines and the client runs the real process."""
    envs, work, log = both
    script = "NUMBA_NUM_THREADS=0 rockcli simulate --body nemea --pulse ricker-sym:ap=0.3,Tp=0.5"
    served = _bash(script, envs["server"], work)  # run by the real process (both ways the same code)
    assert served.returncode == 2 and served.stderr.decode().splitlines() == [
        "Error: NUMBA_NUM_THREADS=0: give a positive number of threads, or unset it"], served.stderr
    assert "declined (environment differs in ['NUMBA_NUM_THREADS'])" in log()


def _signals_as_on_a_terminal() -> None:
    """SIGINT and SIGQUIT at their defaults, as a terminal's shell starts a command. A test run started in the
    background of a non-interactive shell (``pytest ... &`` in a script) has both ignored, as POSIX asks of such a
    shell, and a command started from it inherits that: Ctrl-C would not reach it, run for real or not."""
    for signum in (signal.SIGINT, signal.SIGQUIT):
        signal.signal(signum, signal.SIG_DFL)


def _on_a_terminal(cmd: str, env: dict, cwd: Path, until: bytes | None = None, then=None):
    """Run ``cmd`` with its standard error on a terminal; ``then(proc)`` once that terminal has shown ``until``.
    ``(exit code, stdout, what the terminal showed)``."""
    master, slave = pty.openpty()
    proc = subprocess.Popen(["bash", "-c", cmd], env=env, cwd=cwd, stdout=subprocess.PIPE, stderr=slave,
                            start_new_session=True, preexec_fn=_signals_as_on_a_terminal)
    os.close(slave)
    shown, deadline = b"", time.monotonic() + 300
    while time.monotonic() < deadline:
        ready, _, _ = select.select([master], [], [], 1.0)
        if not ready:
            continue
        try:
            chunk = os.read(master, 4096)
        except OSError:  # the terminal's other side closed: the command ended
            break
        if not chunk:
            break
        if until is not None and until in shown + chunk and until not in shown:
            then(proc)
        shown += chunk
    os.close(master)
    out = proc.stdout.read()
    proc.wait(timeout=60)
    return proc.returncode, out, shown


def _signal_masks(pid: int) -> str:
    """The SigBlk, SigIgn and SigCgt lines of ``/proc/<pid>/status`` (hex masks; bit n-1 is signal n)."""
    try:
        with open(f"/proc/{pid}/status") as f:
            return " ".join(line.strip() for line in f if line.startswith(("SigBlk", "SigIgn", "SigCgt")))
    except OSError as exc:
        return f"({exc})"


def test_a_terminal_is_a_terminal(both):
    """On a terminal rockcli draws progress lines on stderr (``isatty``), through the server as well."""
    envs, work, log = both
    cmd = "rockcli assess column statue:height=1.79,width=0.5 --records kobe-1995-takarazuka-000 --isolation none"
    (rc_real, out_real, tty_real), (rc, out, tty) = (_on_a_terminal(cmd, envs[way], work) for way in ("real", "server"))
    assert rc == rc_real == 0
    assert out == out_real
    for shown in (tty_real, tty):
        assert b"\rmargin search  [" in shown and b"\x1b[K" in shown, shown[-500:]
    assert _served(log(), cmd.removeprefix("rockcli "))


@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM], ids=["SIGINT", "SIGTERM"])
def test_signals_reach_the_command(both, signum):
    """A signal to the client reaches the command: SIGINT stops it as click does (``Aborted!``, exit code 1),
    SIGTERM kills it, and the client dies of it too, as the real process does. Sent once the command runs (its
    first progress line: before, the real process would still be importing). (SIGTERM's default action kills
    a Python process, which does not handle it: the real process is run for SIGINT only.)"""
    envs, work, log = both
    results = {"real": (-signum, b"", b"")}
    # what a failure shows: the signal masks of the process signalled (/proc: blocked, ignored, caught) and
    # this worker's own handler of the signal (an ignored one would be inherited by the command)
    masks = {"worker": signal.getsignal(signum)}

    def send(proc, way):
        masks[way] = _signal_masks(proc.pid)
        proc.send_signal(signum)

    for way in ("real", "server") if signum == signal.SIGINT else ("server",):
        # exec: the signal goes to the command's process itself, not to a shell waiting for it
        results[way] = _on_a_terminal(f"exec {SLOW}", envs[way], work, until=b"runs  [",
                                      then=lambda proc, way=way: send(proc, way))
    (rc_real, out_real, tty_real), (rc, out, tty) = results["real"], results["server"]
    assert rc == rc_real == (1 if signum == signal.SIGINT else -signum), (rc, rc_real, masks, tty_real[-400:],
                                                                          tty[-400:])
    if signum == signal.SIGINT:
        assert b"Aborted!" in tty and b"Aborted!" in tty_real
    assert out == out_real
    assert _served(log(), SLOW.removeprefix("rockcli "))


def test_a_killed_client_kills_the_command(both):
    """A command that outlives its time (subprocess's timeout kills the client with SIGKILL) is killed too."""
    envs, work, log = both
    before = len(_served(log(), SLOW.removeprefix("rockcli ")))
    with pytest.raises(subprocess.TimeoutExpired):
        subprocess.run(["rockcli", *SLOW.split()[1:]], env=envs["server"], cwd=work, capture_output=True, timeout=1.0)
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        lines = _served(log(), SLOW.removeprefix("rockcli "))
        if len(lines) > before:
            break
        time.sleep(0.1)
    assert lines[before:] and "signal 9:" in lines[before], log()


def test_env_reads_sees_lookups_not_walks():
    """What keeps the list of run-time variables honest (forkserver_warmup.EnvReads): a variable looked up by name is
    recorded, one only seen by a walk over the environment (numba's search for NUMBA_*) is not."""
    os.environ["ROCKCLI_TEST_ENV_READS"] = "1"
    try:
        with forkserver_warmup.EnvReads() as reads:
            dict(os.environ.items())
            list(os.environ.values())
            assert "ROCKCLI_TEST_ENV_READS" not in reads.names
            os.environ.get("ROCKCLI_RECORDS")
            os.getenv("ROCKCLI_CATALOG")
            _ = "ROCKCLI_DASK_TIMEOUT" in os.environ
            os.environb.get(b"ROCKCLI_TEST_ENV_READS")
        os.environ.get("ROCKCLI_AFTER")
    finally:
        del os.environ["ROCKCLI_TEST_ENV_READS"]
    assert reads.names == {"ROCKCLI_RECORDS", "ROCKCLI_CATALOG", "ROCKCLI_DASK_TIMEOUT", "ROCKCLI_TEST_ENV_READS"}
