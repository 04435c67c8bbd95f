"""The fork server process and its children (see forkserver.py): ``python forkserver_server.py SOCKET``."""

from __future__ import annotations

import gc
import os
import select
import signal
import socket
import struct
import sys
import time

from forkserver import IMPORT_TIME_FILES, MAGIC, READ_UNUSED, REAL, RUNTIME_ENV
from forkserver_client import _limits  # the client's fingerprint of the process limits, compared with this one's
from forkserver_warmup import EnvReads, _native_threads, fork_unsafe, warm_up


def _unpack(payload: bytes) -> list[bytes]:
    items, at = [], 0
    while at < len(payload):
        (n,) = struct.unpack_from("!I", payload, at)
        items.append(payload[at + 4:at + 4 + n])
        at += 4 + n
    return items


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

    @staticmethod
    def freeze() -> None:
        """Move every object the server holds out of reach of the cyclic garbage collector (``gc.freeze``).

        A child's first collections would otherwise walk the whole warmed-up heap (NumPy, SciPy, numba, matplotlib
        and the kernels: some hundreds of MB), touching every object and so copying nearly every page the fork
        shared: about 0.1 s of CPU per command. What is frozen is what the server holds after a full collection,
        all of it reachable, so no object a real process would free is kept and no finalizer is skipped."""
        gc.collect()
        gc.freeze()

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
        loaded = self.kernels.loaded
        self.kernels.refresh()
        if self.kernels.loaded != loaded:
            self.freeze()
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
        gc.collect()  # the warm-up's garbage goes now, its finalizers' output captured with the warm-up's
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
    gc.freeze()  # after the collection above (see Server.freeze)
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


if __name__ == "__main__":
    sys.exit(main(sys.argv))
