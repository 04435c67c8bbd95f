"""Shared fixtures.

On several workers, the drivers numba's disk cache lacks are compiled ahead in child processes
(tests/kernel_first_calls.py).

``fork_servers``: this pytest process's pre-warmed fork servers for ``rockcli`` commands
(tests/forkserver.py; ``ROCKCLI_TEST_FORKSERVER=0`` turns them off).

``records_dir``: the folders of real records named by ROCKCLI_RECORDS (os.pathsep-separated);
tests that need them skip cleanly when the variable is unset or names no existing folder.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from rockcli.pulses import make_pulse
from rockcli.io.units import G


def _absolute_record_folders() -> None:
    """ROCKCLI_RECORDS as absolute paths of the folders that exist, for the whole session.

    The README's test command gives it relative to the repository (``../shared/records``), but tests run
    commands from temporary folders too, and rockcli refuses a ROCKCLI_RECORDS entry that does not exist
    (Bad input). A folder that is absent is dropped here, so that tests needing it skip cleanly.
    """
    raw = os.environ.get("ROCKCLI_RECORDS")
    if raw is None:
        return
    folders = [str(Path(p).resolve()) for p in raw.split(os.pathsep) if p and Path(p).is_dir()]
    if folders:
        os.environ["ROCKCLI_RECORDS"] = os.pathsep.join(folders)
    else:
        del os.environ["ROCKCLI_RECORDS"]


_absolute_record_folders()


def _no_compile_notice_in_process() -> None:
    """No compile notice in the output of the commands this process runs (click's ``CliRunner``): the notice goes to
    stderr on the first run whatever it is (rockcli.cli.progress.watch_compiles), and a test's output must not depend
    on whether a kernel happened to compile during it. tests/test_first_run.py tests the notice itself; commands run
    as real processes say it as a user's would."""
    from rockcli.cli import progress

    progress._watching = True


_no_compile_notice_in_process()


def pytest_configure(config):
    """pytest's main process writes rockcli's Python bytecode, as a user's first run leaves it: where
    PYTHONDONTWRITEBYTECODE is set (as on this machine and some CI machines) every process of the session, the
    workers, the fork servers and the commands run for real, would otherwise compile rockcli from source again
    (0.2-0.4 s of CPU each); ``__pycache__`` is ignored by git, like numba's cache of the kernels beside it.
    On several workers (``-n 2``), it then starts compiling the drivers numba's disk cache lacks, one child
    process per group, before the workers need them (tests/kernel_first_calls.py)."""
    if hasattr(config, "workerinput"):
        return
    import compileall

    compileall.compile_dir(str(Path(__file__).resolve().parents[1] / "rockcli"), quiet=1)
    if not getattr(config.option, "numprocesses", None):
        return
    import kernel_first_calls

    config.rockcli_compiling = kernel_first_calls.start()


def pytest_unconfigure(config):
    children = getattr(config, "rockcli_compiling", None)
    if children:
        import kernel_first_calls

        kernel_first_calls.stop(children)


def _record_folders() -> list[Path]:
    return [Path(p) for p in os.environ.get("ROCKCLI_RECORDS", "").split(os.pathsep) if p and Path(p).is_dir()]


@pytest.fixture(scope="session")
def fork_servers():
    """:class:`forkserver.ForkServers`: ``.shim(env)`` and ``.command(env)`` run ``rockcli`` through a fork server
    warmed up for ``env`` (started on first use, stopped at the end of the session), or as a real process."""
    from forkserver import ForkServers

    servers = ForkServers()
    yield servers
    servers.close()


@pytest.fixture(scope="session")
def records_dirs() -> list[Path]:
    """All existing folders named by ROCKCLI_RECORDS (skips when there are none)."""
    folders = _record_folders()
    if not folders:
        pytest.skip("ROCKCLI_RECORDS names no existing folder of records")
    return folders


@pytest.fixture(scope="session")
def records_dir(records_dirs) -> Path:
    """The first folder named by ROCKCLI_RECORDS (skips when there is none)."""
    return records_dirs[0]


@pytest.fixture(scope="session")
def find_record(records_dirs):
    """Function ``find_record(name) -> Path`` looking a file up in ROCKCLI_RECORDS (skips if absent)."""

    def find(name: str) -> Path:
        for folder in records_dirs:
            if (folder / name).is_file():
                return folder / name
        pytest.skip(f"{name} not found in ROCKCLI_RECORDS")

    return find


def write_pulse_record(path: Path, a_p_g=0.5, T_p=0.6, shape="ricker-sym", dt=0.01, pad=4.0) -> Path:
    """A sampled pulse followed by quiet, as a one-column text file that states dt and units."""
    p = make_pulse(shape, a_p_g * G, T_p)
    t = np.arange(0.0, p.support()[1] + pad, dt)
    acc_g = p.acceleration(t) / G
    lines = [f"# synthetic {shape} ap={a_p_g} g Tp={T_p} s", f"# dt={dt} sec", "# units: g"]
    lines += [f"{v:.10e}" for v in acc_g]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture()
def pulse_records(tmp_path):
    """A folder with two synthetic pulse records (sym.txt, anti.txt) as self-describing text files."""
    folder = tmp_path / "recs"
    folder.mkdir()
    write_pulse_record(folder / "sym.txt", 0.45, 0.7, "ricker-sym")
    write_pulse_record(folder / "anti.txt", -0.5, 0.5, "ricker-anti")
    return folder
