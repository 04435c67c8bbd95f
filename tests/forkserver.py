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
  load that would compile stops it from serving (:func:`rockcli.compiling.compiles` must stay 0).

Fork safety: before each fork the server checks that no Python thread but the main one exists
(``threading.enumerate()``), that numba's threading layer was never started (``numba.np.ufunc.parallel``),
and that the native threads are no more than the warm-up left: OpenBLAS's pools of NumPy's and SciPy's copies
(stopped by OpenBLAS's own ``pthread_atfork`` handler before each fork) and jemalloc's background thread
(pyarrow's; jemalloc's fork handlers). A failed check declines the request. The server itself is one thread: a
``select`` loop, SIGCHLD through a wake-up pipe.

Run ``python forkserver.py SOCKET LOG`` with the environment of the commands it will serve; it prints
``ready`` (or ``unavailable: REASON``) on its standard output and serves until its standard input closes or
it gets SIGTERM (then it kills the children still running). :class:`ForkServers` starts and stops servers for
the tests.
"""

from __future__ import annotations

import os
import select
import signal
import socket
import struct
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
CLIENT = HERE / "forkserver_client.py"
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
# the warm-up


def _dispatchers():
    """Every numba dispatcher defined in rockcli.kernels (its modules all imported)."""
    import importlib
    import pkgutil

    import rockcli.kernels as kernels
    from numba.core.dispatcher import Dispatcher

    found = []
    for info in pkgutil.iter_modules(kernels.__path__):
        module = importlib.import_module(f"rockcli.kernels.{info.name}")
        for obj in vars(module).values():
            if isinstance(obj, Dispatcher) and getattr(obj.py_func, "__module__", None) == module.__name__:
                found.append(obj)
    return found


class Kernels:
    """Loads every specialisation numba's disk cache holds for the current sources, again when an index changes."""

    def __init__(self):
        self.dispatchers = _dispatchers()
        self.seen = {}  # index path -> (mtime_ns, size) when last loaded
        self.loaded = 0

    def refresh(self) -> None:
        for disp in self.dispatchers:
            cache = disp._cache
            index = getattr(getattr(cache, "_cache_file", None), "_index_path", None)
            if not index:
                continue
            try:
                st = os.stat(index)
            except OSError:
                continue
            stamp = (st.st_mtime_ns, st.st_size)
            if self.seen.get(index) == stamp:
                continue
            self.seen[index] = stamp
            codegen = disp.targetctx.codegen()
            for key in cache._cache_file._load_index():
                sig = key[0]
                args = tuple(sig.args) if hasattr(sig, "args") else tuple(sig)
                if key != cache._index_key(sig, codegen) or args in disp.overloads:
                    continue
                disp.compile(sig)  # a load from the disk cache (the key is there); see the module notes
                self.loaded += 1


def _draw_once() -> None:
    """What a process's first figure pays and its later ones do not: matplotlib's fonts opened (FreeType), the
    mathtext parser built, the Agg renderer and constrained layout run, text measured as rockcli measures it
    (about 0.4 s of CPU per command that draws). Into memory, outside pyplot (no figure number is taken), on texts
    no rockcli figure has (its cache of parsed formulas then holds nothing a command looks up).
    tests/test_forkserver.py checks that a figure is byte for byte the real process's."""
    import io

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.font_manager import FontProperties
    from matplotlib.textpath import TextToPath

    fig = Figure(figsize=(3.0, 2.0), layout="constrained")
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    ax.plot([0.0, 1.0], [0.0, 1.0], label="warm-up")
    ax.set_xlabel(r"$\omega_{\mathrm{warm}}/p$ [-]")
    ax.set_ylabel("warm-up [m]")
    ax.legend()
    fig.suptitle(r"fork server warm-up $\theta_{warm}$", fontsize=9)
    fig.savefig(io.BytesIO(), format="png", dpi=50)
    for text in ("fork server warm-up", r"$\alpha_{\mathrm{warm}}$ = 1 s"):
        TextToPath().get_text_width_height_descent(text, FontProperties(size=9), ismath=text.count("$") >= 2)


def warm_up():
    """Import what the commands import and load the cached kernels; the :class:`Kernels`."""
    import importlib
    import pkgutil

    import rockcli
    import rockcli.cli

    for target in rockcli.cli._COMMANDS.values():
        importlib.import_module(target.split(":")[0])
    for info in pkgutil.walk_packages(rockcli.__path__, "rockcli."):
        importlib.import_module(info.name)
    for name in LAZY_IMPORTS:
        importlib.import_module(name)
    from rockcli.report.figures import pyplot

    pyplot()  # matplotlib on Agg, as a command that draws sets it up
    _draw_once()
    kernels = Kernels()
    kernels.refresh()
    return kernels


class EnvReads:
    """Records the environment variables Python code looks up by name (``os.environ[...]``, ``.get``,
    ``os.getenv``, ``in``) while active; a walk over the whole environment (numba's search for NUMBA_*) is not
    a lookup. Variables read by C code (getenv) are not seen: none of them is in :data:`RUNTIME_ENV`."""

    def __init__(self):
        self.names = set()

    def __enter__(self):
        cls = type(os.environ)
        self.saved = get = cls.__getitem__
        names = self.names

        def getitem(environ, key):
            caller = sys._getframe(1).f_code
            if not (caller.co_name == "__iter__" and "_collections_abc" in caller.co_filename):  # items(), values()
                names.add(os.fsdecode(key) if isinstance(key, bytes) else key)
            return get(environ, key)

        cls.__getitem__ = getitem
        return self

    def __exit__(self, *exc):
        type(os.environ).__getitem__ = self.saved


def _native_threads() -> int:
    try:
        return len(os.listdir("/proc/self/task"))
    except OSError:
        return 1


def fork_unsafe(max_native: int) -> str | None:
    """Why forking now would not be safe, or None."""
    import threading

    if threading.active_count() != 1 or threading.enumerate() != [threading.main_thread()]:
        return f"Python threads are running: {threading.enumerate()}"
    parallel = sys.modules.get("numba.np.ufunc.parallel")
    if parallel is not None and getattr(parallel, "_is_initialized", False):
        return "numba's threading layer was started"
    if _native_threads() > max_native:
        return f"{_native_threads()} native threads, more than the {max_native} the warm-up left"
    return None


# ---------------------------------------------------------------------------------------------------
# requests


def _unpack(payload: bytes) -> list[bytes]:
    items, at = [], 0
    while at < len(payload):
        (n,) = struct.unpack_from("!I", payload, at)
        items.append(payload[at + 4:at + 4 + n])
        at += 4 + n
    return items


def _limits() -> bytes:
    import resource

    out = []
    for name in sorted(n for n in dir(resource) if n.startswith("RLIMIT_")):
        try:
            soft, hard = resource.getrlimit(getattr(resource, name))
        except (ValueError, OSError):
            continue
        out.append(f"{name}={soft},{hard}")
    return ";".join(out).encode()


class Request:
    def __init__(self, fields: list[bytes], fds: list[int], open_mask: int):
        self.umask = int(fields[0])
        self.ignored = {int(x) for x in fields[1].split(b",") if x}
        self.blocked = {int(x) for x in fields[2].split(b",") if x}
        self.cpus, self.limits, self.priority = fields[3], fields[4], int(fields[5])
        n = int(fields[6])
        self.args = [os.fsdecode(a) for a in fields[7:7 + n]]
        self.env = dict(item.split(b"=", 1) for item in fields[7 + n:])
        self.cwd_fd, self.fds = fds[0], fds[1:]
        self.open = [fd for fd in (0, 1, 2) if open_mask & (1 << fd)]
        assert len(self.fds) == len(self.open), "descriptors and their mask disagree"

    def close(self) -> None:
        for fd in [self.cwd_fd] + self.fds:
            try:
                os.close(fd)
            except OSError:
                pass


def _receive(conn) -> Request:
    conn.settimeout(10.0)
    header, ancdata, _flags, _addr = conn.recvmsg(9, socket.CMSG_SPACE(4 * struct.calcsize("i")))
    fds = []
    for level, kind, data in ancdata:
        if level == socket.SOL_SOCKET and kind == socket.SCM_RIGHTS:
            fds += list(struct.unpack("%di" % (len(data) // 4), data[:len(data) - len(data) % 4]))
    try:
        while len(header) < 9:
            more = conn.recv(9 - len(header))
            if not more:
                raise OSError("short header")
            header += more
        if header[:4] != MAGIC:
            raise OSError("not a request")
        open_mask, size = struct.unpack("!BI", header[4:])
        chunks, got = [], 0
        while got < size:
            chunk = conn.recv(min(1 << 20, size - got))
            if not chunk:
                raise OSError("short request")
            chunks.append(chunk)
            got += len(chunk)
        conn.settimeout(None)
        return Request(_unpack(b"".join(chunks)), fds, open_mask)
    except BaseException:
        for fd in fds:
            os.close(fd)
        raise


def _is_package(dir_fd: int, name: str) -> bool:
    try:
        os.stat(f"{name}/__init__.py", dir_fd=dir_fd)
        return True
    except OSError:
        return False


class Server:
    def __init__(self, kernels, max_native: int, runtime_env=RUNTIME_ENV):
        self.runtime_env = runtime_env
        if runtime_env != RUNTIME_ENV:
            log(f"read by the warm-up, so a request must not change them: {sorted(RUNTIME_ENV - runtime_env)}")
        self.kernels = kernels
        self.max_native = max_native
        self.env = dict(os.environb)
        self.limits = _limits()
        self.cpus = ",".join(str(c) for c in sorted(os.sched_getaffinity(0))).encode()
        self.priority = os.getpriority(os.PRIO_PROCESS, 0)
        self.modules = {name.split(".")[0] for name in sys.modules}
        self.broken = None  # why the server stopped serving
        self.served = self.declined = 0
        self.running = {}  # pid -> connection
        self.args = {}  # pid -> the command's arguments (for the log)
        self.waiting = {}  # connection -> pid (until the client goes away)
        self.internal = []  # descriptors a child must not keep

    # -- what a request may differ in
    def decline(self, req: Request, conn) -> str | None:
        if self.broken:
            return self.broken
        creds = conn.getsockopt(socket.SOL_SOCKET, socket.SO_PEERCRED, struct.calcsize("3i"))
        _pid, uid, gid = struct.unpack("3i", creds)
        if (uid, gid) != (os.getuid(), os.getgid()):
            return "another user"
        keys = set(req.env) | set(self.env)
        differ = sorted(k.decode(errors="replace") for k in keys if req.env.get(k) != self.env.get(k))
        differ = [k for k in differ if k not in self.runtime_env]
        if differ:
            return f"environment differs in {differ}"
        if (req.limits, req.cpus, req.priority) != (self.limits, self.cpus, self.priority):
            return "process limits, CPU affinity or priority differ"
        try:
            names = os.listdir(req.cwd_fd)
        except OSError as exc:
            return f"working folder unreadable ({exc})"
        for name in names:
            if name in IMPORT_TIME_FILES:
                return f"the working folder holds {name}"
            stem = name.split(".")[0]
            if stem in self.modules and (name.endswith((".py", ".pyc", ".so")) or _is_package(req.cwd_fd, name)):
                return f"the working folder's {name} would shadow the imported module {stem}"
        self.kernels.refresh()
        from rockcli import compiling

        if compiling.compiles():
            self.broken = "a kernel compiled in the server"
            return self.broken
        return fork_unsafe(self.max_native)

    def handle(self, conn) -> None:
        try:
            req = _receive(conn)
        except (OSError, ValueError, AssertionError) as exc:
            log(f"bad request: {exc}")
            conn.close()
            return
        try:
            reason = self.decline(req, conn)
        except Exception as exc:  # noqa: BLE001 - a request the server cannot judge runs as a real process
            reason = f"{type(exc).__name__}: {exc}"
        if reason:
            self.declined += 1
            log(f"declined ({reason}): rockcli {' '.join(req.args)}")
            req.close()
            try:
                conn.sendall(f"fallback {reason}\n".encode())
            except OSError:
                pass
            conn.close()
            return
        for stream in (sys.stdout, sys.stderr):
            stream.flush()
        pid = os.fork()
        if pid == 0:
            _child(req, conn, self.internal + list(self.waiting))
        req.close()
        self.served += 1
        self.running[pid] = conn
        self.waiting[conn] = pid
        self.args[pid] = req.args
        try:
            conn.sendall(b"pid %d\n" % pid)
        except OSError:
            self.client_gone(conn)

    def client_gone(self, conn) -> None:
        """The client closed (killed, or it ended): a command still running is killed, as the client was."""
        pid = self.waiting.pop(conn, None)
        if pid is not None and pid in self.running:
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass

    def reap(self) -> None:
        while self.running:
            try:
                pid, status, usage = os.wait4(-1, os.WNOHANG)
            except ChildProcessError:
                return
            if pid == 0:
                return
            conn = self.running.pop(pid, None)
            if conn is None:
                continue
            code = os.waitstatus_to_exitcode(status)
            cpu = usage.ru_utime + usage.ru_stime
            log(f"{cpu:.2f} s CPU, {'exit' if code >= 0 else 'signal'} {abs(code)}: "
                f"rockcli {' '.join(self.args.pop(pid, []))}")
            msg = b"exit %d\n" % code if code >= 0 else b"signal %d\n" % -code
            if conn in self.waiting:
                self.waiting.pop(conn)
                try:
                    conn.sendall(msg)
                except OSError:
                    pass
            conn.close()

    def stop(self) -> None:
        for pid in list(self.running):
            try:
                os.kill(pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
        deadline = time.monotonic() + 5
        while self.running and time.monotonic() < deadline:
            self.reap()
            time.sleep(0.01)
        log(f"served {self.served}, declined {self.declined}, kernels loaded {self.kernels.loaded}")

    def serve(self, listener, death_fd: int) -> None:
        wake_r, wake_w = os.pipe()
        os.set_blocking(wake_r, False)
        os.set_blocking(wake_w, False)
        signal.set_wakeup_fd(wake_w)
        stopping = []
        signal.signal(signal.SIGCHLD, lambda signum, frame: None)
        signal.signal(signal.SIGTERM, lambda signum, frame: stopping.append(signum))
        self.internal = [listener, wake_r, wake_w, death_fd, 2]
        while not stopping:
            watch = [listener, wake_r, death_fd] + list(self.waiting)
            ready, _, _ = select.select(watch, [], [])
            if wake_r in ready:
                try:
                    while os.read(wake_r, 512):
                        pass
                except BlockingIOError:
                    pass
                self.reap()
            if death_fd in ready and not os.read(death_fd, 512):
                break
            for conn in ready:
                if isinstance(conn, socket.socket) and conn is not listener and conn in self.waiting:
                    try:
                        data = conn.recv(512)
                    except OSError:
                        data = b""
                    if not data:
                        self.client_gone(conn)
            if listener in ready:
                try:
                    conn, _ = listener.accept()
                except OSError:
                    continue
                self.handle(conn)
        self.stop()


# ---------------------------------------------------------------------------------------------------
# the child


def _stdio(fd: int, name: str, old, buffered: bool):
    """``sys.std*`` for ``fd`` as Python's start-up builds it (Python/pylifecycle.c, create_stdio)."""
    import io

    try:
        os.fstat(fd)
    except OSError:
        return None
    write = fd != 0
    buf = io.open(fd, "wb" if write else "rb", buffering=0 if (write and not buffered) else -1, closefd=False)
    raw = buf.raw if hasattr(buf, "raw") else buf
    raw.name = name
    tty = raw.isatty()
    stream = io.TextIOWrapper(buf, old.encoding, old.errors, "\n", buffered and (tty or fd == 2), not buffered)
    stream.mode = "w" if write else "r"
    return stream


_KEEP = []  # the server's standard streams, kept alive in a child (their finaliser must not run there)


def _child(req: Request, conn, internal: list[int]) -> None:
    """Become the command's process (never returns)."""
    import builtins
    import importlib.machinery
    import types

    try:
        for item in internal:  # a socket object gives its descriptor up first (its finaliser must not close it)
            try:
                os.close(item.detach() if isinstance(item, socket.socket) else item)
            except OSError:
                pass
        signal.set_wakeup_fd(-1)
        for sig in signal.Signals:
            if sig in (signal.SIGKILL, signal.SIGSTOP):
                continue
            if sig in (signal.SIGPIPE, signal.SIGXFSZ) or int(sig) in req.ignored:
                want = signal.SIG_IGN  # Python ignores these two at start-up; the rest as inherited
            elif sig == signal.SIGINT:
                want = signal.default_int_handler
            else:
                want = signal.SIG_DFL
            if signal.getsignal(sig) is not want:
                signal.signal(sig, want)
        os.fchdir(req.cwd_fd)
        os.umask(req.umask)
        for target, fd in zip(req.open, req.fds):
            os.dup2(fd, target)
        req.close()
        for fd in (0, 1, 2):
            if fd not in req.open:
                try:
                    os.close(fd)
                except OSError:
                    pass
        os.environ.clear()
        for key, value in req.env.items():
            os.environb[key] = value
        time.tzset()
        old = (sys.__stdin__, sys.__stdout__, sys.__stderr__)
        _KEEP.extend(old + (sys.stdin, sys.stdout, sys.stderr))
        buffered = not old[1].write_through  # Python's -u and PYTHONUNBUFFERED (the same as the client's)
        sys.stdin = sys.__stdin__ = _stdio(0, "<stdin>", old[0], buffered)
        sys.stdout = sys.__stdout__ = _stdio(1, "<stdout>", old[1], buffered)
        sys.stderr = sys.__stderr__ = _stdio(2, "<stderr>", old[2], buffered)
        main = types.ModuleType("__main__")
        main.__builtins__ = builtins
        main.__loader__ = importlib.machinery.BuiltinImporter
        main.__annotations__ = {}
        sys.modules["__main__"] = main
        sys.argv = ["-c"] + req.args
        sys.path[0] = ""
        if "numpy.random" in sys.modules:
            sys.modules["numpy.random"].seed()  # a fresh process seeds NumPy's global state afresh
        signal.pthread_sigmask(signal.SIG_SETMASK, req.blocked)
        conn.close()
        code = compile(REAL, "<string>", "exec")
    except BaseException as exc:  # noqa: BLE001
        try:
            os.write(2, f"rockcli (tests' fork server): the child could not be set up: {exc!r}\n".encode())
        finally:
            os._exit(70)
    try:
        exec(code, main.__dict__)
        status = 0
    except SystemExit as exc:  # as Python ends on an uncaught SystemExit
        status = exc.code
        if status is None:
            status = 0
        elif not isinstance(status, int):
            print(status, file=sys.stderr)
            status = 1
    except BaseException as exc:  # noqa: BLE001 - as Python reports an uncaught exception
        sys.excepthook(type(exc), exc, exc.__traceback__.tb_next)
        status = -signal.SIGINT if isinstance(exc, KeyboardInterrupt) else 1
    import atexit

    atexit._run_exitfuncs()
    for stream in (sys.stdout, sys.stderr):
        try:
            stream.flush()
        except (OSError, ValueError, AttributeError):
            pass
    if status == -signal.SIGINT:
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        os.kill(os.getpid(), signal.SIGINT)
    os._exit(status & 0xFF)


# ---------------------------------------------------------------------------------------------------
# the server process


def log(text: str) -> None:
    try:
        os.write(2, f"[forkserver {os.getpid()}] {text}\n".encode())
    except OSError:
        pass


def main(argv) -> int:
    socket_path = argv[1]
    sys.path[0] = ""  # as ``python -c`` has it (the server runs in an empty folder)
    ready = os.fdopen(os.dup(1), "w")
    death_fd = os.dup(0)
    null = os.open(os.devnull, os.O_RDWR)
    os.dup2(null, 0)
    capture = os.open(f"{socket_path}.warmup", os.O_RDWR | os.O_CREAT | os.O_TRUNC, 0o600)
    log_fd = os.dup(2)
    os.dup2(capture, 1)
    os.dup2(capture, 2)
    t0 = time.process_time()
    reason = None
    reads = EnvReads()
    try:
        with reads:
            kernels = warm_up()
    except BaseException as exc:  # noqa: BLE001
        reason = f"the warm-up failed: {exc!r}"
    for stream in (sys.stdout, sys.stderr):
        stream.flush()
    os.dup2(null, 1)
    os.dup2(log_fd, 2)
    os.close(log_fd)
    written = os.fstat(capture).st_size
    os.close(capture)
    if reason is None and written:
        reason = f"the warm-up wrote {written} bytes (see {socket_path}.warmup): a child would not write them"
    if reason is None:
        from rockcli import compiling

        if compiling.compiles():
            reason = "a kernel compiled during the warm-up"
    max_native = _native_threads()
    if reason is None:
        reason = fork_unsafe(max_native)
    if reason is not None:
        log(f"unavailable: {reason}")
        ready.write(f"unavailable: {reason}\n")
        ready.close()
        return 1
    server = Server(kernels, max_native, RUNTIME_ENV - (reads.names - READ_UNUSED))
    listener = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    listener.bind(socket_path)
    listener.listen(64)
    log(f"ready: warm-up {time.process_time() - t0:.2f} s of CPU, {kernels.loaded} kernels loaded, "
        f"{max_native} native threads")
    ready.write("ready\n")
    ready.close()
    try:
        server.serve(listener, death_fd)
    finally:
        listener.close()
        try:
            os.unlink(socket_path)
        except OSError:
            pass
    return 0


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
        proc = subprocess.Popen([sys.executable, str(Path(__file__).resolve()), path], env=env, cwd=workdir,
                                stdin=subprocess.PIPE, stdout=subprocess.PIPE, stderr=logfile, process_group=0)
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


if __name__ == "__main__":
    sys.exit(main(sys.argv))
