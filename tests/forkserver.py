"""A pre-warmed fork server for the tests' ``rockcli`` processes.

Every ``rockcli`` process pays about a second of CPU before its first run: importing numba, NumPy, SciPy,
matplotlib and pandas and loading the compiled kernels from numba's disk cache. tests/test_docs.py starts about
ninety of them. The fork server pays this once per pytest worker: it imports rockcli's command line with
everything its commands import lazily, loads every kernel that numba's disk cache holds for the current sources,
and then forks one child per command. A child becomes the process the plain shim would have started
(``python -c "import sys; sys.argv[0] = 'rockcli'; from rockcli.cli import run; run()" ARG...``): it takes the
client's working folder, umask, environment, signal dispositions and mask and its standard input, output and
error (the descriptors themselves), rebuilds ``sys.stdin``/``stdout``/``stderr`` as Python's start-up builds them
(buffering, line buffering on a terminal, encoding, error handler), gets a fresh ``__main__`` and
``sys.argv``, reseeds NumPy's global random state, and runs the shim's very code (the same entry point, click's
standalone mode, the exit code). The client (:mod:`forkserver_client`) ends as the child ended.

When a child is the same as a real process
--------------------------------------------
A child differs from a fresh process only by what the server did before forking: modules already imported and
kernels already loaded. That is invisible to a command when

* importing wrote nothing: the warm-up's standard output and error are captured and must be empty (a warning
  shown at import would otherwise be shown once in the server and never in a child); the server refuses to serve
  otherwise;
* nothing an import read differs: the environment of a request may differ from the server's only in
  :data:`RUNTIME_ENV`, variables read when a command runs and never at import (ROCKCLI_RECORDS,
  ROCKCLI_CATALOG and ROCKCLI_DASK_TIMEOUT are read inside functions; NUMBA_*, PYTHON*, MPL*, LANG/LC_*,
  HOME, TMPDIR, OPENBLAS/OMP and every other variable make the server decline, and the client runs the real
  process); the working folder must hold no file read at import (``.numba_config.yaml``, ``matplotlibrc``)
  and no module or package that would shadow an imported one (``''`` is first on ``sys.path`` of ``python -c``);
  the process limits, CPU affinity, priority and user must be the server's (else: declined);
* the kernels are the ones a real process would load: numba keys each cached kernel on its argument types and
  a Python call runs the specialisation for exactly its argument types (it compiles one for new types rather
  than converting to a loaded one), so loading every cached specialisation beforehand changes no call; the
  machine code loaded is the bytes a real process loads from the same cache (see
  :func:`rockcli.kernels.cache._load_unrefreshed`). Kernels that appear in the cache while the server runs (a
  fresh clone compiles them during the suite) are loaded before the next fork. The server never compiles: a
  load that would compile stops it from serving (:func:`rockcli.compiling.compiles` must stay 0);
* the garbage collector sees only the command's own objects: after the warm-up (its output captured with the
  warm-up's) the server collects its garbage and freezes what is left (``gc.freeze``), all of it reachable, so
  a child never walks the server's heap (a walk touches every object and copies nearly every page the fork
  shared, about 0.1 s of CPU per command) and no finalizer a real process would run is lost.

Fork safety: before each fork the server checks that no Python thread but the main one exists
(``threading.enumerate()``), that numba's threading layer was never started (``numba.np.ufunc.parallel``),
and that the native threads are no more than the warm-up left: OpenBLAS's pools of NumPy's and SciPy's copies
(stopped by OpenBLAS's own ``pthread_atfork`` handler before each fork) and jemalloc's background thread
(pyarrow's; jemalloc's fork handlers). A failed check declines the request. The server itself is one thread: a
``select`` loop, SIGCHLD through a wake-up pipe.

Run ``python forkserver_server.py SOCKET`` with the environment of the commands it will serve; it prints
``ready`` (or ``unavailable: REASON``) on its standard output and serves until its standard input closes or
it gets SIGTERM (then it kills the children still running). :class:`ForkServers` starts and stops servers for
the tests. Files: this one (the notes, the settings, :class:`ForkServers`), ``forkserver_warmup.py`` (the
warm-up and the fork-safety checks), ``forkserver_server.py`` (the server process and its children),
``forkserver_client.py`` (the ``rockcli`` command).
"""

from __future__ import annotations

import os
import select
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
CLIENT = HERE / "forkserver_client.py"
SERVER = HERE / "forkserver_server.py"
#: Set to 0 (or off, no, false) to run every test command as a real process.
DISABLE_ENV = "ROCKCLI_TEST_FORKSERVER"
#: A file to which the servers' logs are appended when they stop (for a look at what was served and declined).
LOG_ENV = "ROCKCLI_TEST_FORKSERVER_LOG"
#: Environment variables a request may set differently from the server's: read when a command runs, never at
#: import (the shell's own: bash drops the prompts PS1 and PS2 from a non-interactive shell's environment; the
#: terminal's size; rockcli's run-time settings).
RUNTIME_ENV = frozenset({"_", "PWD", "OLDPWD", "SHLVL", "PS1", "PS2", "COLUMNS", "LINES",
                         "ROCKCLI_RECORDS", "ROCKCLI_CATALOG", "ROCKCLI_DASK_TIMEOUT"})
#: Of those, the ones an import does read, into a value nothing uses: numba.core.types.functions sets
#: ``_termwidth`` from the terminal's size (COLUMNS, LINES) and never reads it. Any other of RUNTIME_ENV that the
#: warm-up reads (a lookup by name, os.environ[...] or os.getenv) is taken off the list (see :class:`EnvReads`).
READ_UNUSED = frozenset({"COLUMNS", "LINES"})
#: Files of the working folder read at import (numba's configuration, matplotlib's).
IMPORT_TIME_FILES = (".numba_config.yaml", "matplotlibrc")
#: What the plain shim runs, the code a child runs (as ``python -c`` runs it).
REAL = "import sys; sys.argv[0] = 'rockcli'; from rockcli.cli import run; run()"
#: Third-party modules rockcli's commands import inside functions, imported by the warm-up.
LAZY_IMPORTS = ("scipy.integrate", "scipy.optimize", "scipy.special", "scipy.ndimage", "obspy",
                "obspy.core.util", "pandas")
MAGIC = b"RKC1"


def enabled() -> bool:
    return os.environ.get(DISABLE_ENV, "1").strip().lower() not in {"0", "off", "no", "false"}


# ---------------------------------------------------------------------------------------------------
# for the tests: start and stop servers


class ForkServers:
    """Fork servers of one pytest process, one per environment (started on first use, stopped by :meth:`close`)."""

    READY_TIMEOUT_S = 300.0

    def __init__(self):
        self.servers = {}  # frozen environment -> (process, socket path) or None
        self.folders = []  # their folders (socket, log), removed by close()

    @staticmethod
    def real_shim() -> str:
        """The text of the plain ``rockcli`` shim: the real process."""
        return f'#!/bin/sh\nexec "{sys.executable}" -c "{REAL}" "$@"\n'

    def shim(self, env: dict) -> str:
        """The text of a ``rockcli`` shim for commands run with ``env`` (the real process without a server)."""
        path = self.socket(env) if enabled() else None
        if path is None:
            return self.real_shim()
        return f'#!/bin/sh\nexec "{sys.executable}" -I -S "{CLIENT}" "{path}" "$@"\n'

    def command(self, env: dict) -> list[str]:
        """The argv prefix that runs ``rockcli`` for a process with environment ``env`` (through a server if any)."""
        path = self.socket(env) if enabled() else None
        if path is None:
            return [sys.executable, "-c", REAL]
        return [sys.executable, "-I", "-S", str(CLIENT), path]

    def socket(self, env: dict) -> str | None:
        key = frozenset((k, v) for k, v in env.items() if k not in RUNTIME_ENV)
        if key not in self.servers:
            self.servers[key] = self._start(env)
        found = self.servers[key]
        return None if found is None else found[1]

    def _start(self, env: dict):
        import tempfile

        workdir = Path(tempfile.mkdtemp(prefix="rockcli-fs-", dir="/tmp" if os.path.isdir("/tmp") else None))
        self.folders.append(workdir)
        path = str(workdir / "s")  # a short path: a Unix socket's is limited to about 100 bytes
        logfile = open(workdir / "log", "ab")
        # a process group of its own (a terminal's Ctrl-C reaches the commands through their clients only)
        group = {"process_group": 0} if sys.version_info >= (3, 11) else {"start_new_session": True}
        proc = subprocess.Popen([sys.executable, str(SERVER), path], env=env, cwd=workdir, stdin=subprocess.PIPE,
                                stdout=subprocess.PIPE, stderr=logfile, **group)
        logfile.close()
        ready, _, _ = select.select([proc.stdout], [], [], self.READY_TIMEOUT_S)
        line = proc.stdout.readline().decode(errors="replace").strip() if ready else "no answer"
        if line != "ready":
            self._end(proc)
            sys.stderr.write(f"rockcli fork server not used ({line}): {(workdir / 'log').read_text()[-2000:]}\n")
            return None
        return proc, path

    def log(self, env: dict) -> str:
        """What the server for ``env`` has logged so far ("" without one)."""
        path = self.socket(env) if enabled() else None
        try:
            return (Path(path).parent / "log").read_text(errors="replace") if path else ""
        except OSError:
            return ""

    @staticmethod
    def _end(proc) -> None:
        try:
            proc.stdin.close()
        except OSError:
            pass
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()
            proc.wait()

    def close(self) -> None:
        import shutil

        for found in self.servers.values():
            if found is not None:
                self._end(found[0])
        self.servers.clear()
        keep = os.environ.get(LOG_ENV)
        for folder in self.folders:
            if keep and (folder / "log").exists():
                with open(keep, "a", encoding="utf-8") as out:
                    out.write((folder / "log").read_text(errors="replace"))
            shutil.rmtree(folder, ignore_errors=True)
        self.folders.clear()
