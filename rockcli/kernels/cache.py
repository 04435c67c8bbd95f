"""numba's on-disk cache, keyed on the sources of the whole kernel package.

numba stamps each cached function with a hash of *its own* source file only. A kernel that calls
(or inlines) a function from another file of this package would then be loaded stale after an
edit of that callee. :class:`PackageLocator` fixes this for the functions of this package (and
only for them): their cache stamp is a SHA-256 of every ``*.py`` file of ``rockcli/kernels``,
so an edit anywhere in the package recompiles every kernel, and an unchanged package loads from
the cache. The cache lives in the package's ``__pycache__`` (numba's own default place), or, when
that is not writable, in the user cache folder (``NUMBA_CACHE_DIR`` when set).

The disk cache is an optimisation, never a condition of a run:

* when none of these folders can be written (a read-only install and home, as on shared clusters
  and in containers), the kernels run without a disk cache (compiled in memory, every run) and
  one notice line says so on the standard error;
* when writing the cache fails (a full disk, a quota, a file size limit), or reading it fails, the
  run carries on without it (one notice line): :func:`install` wraps numba's ``save_overload`` and
  ``load_overload`` for the functions of this package only.

A warm process loads its cached kernels without numba's refresh of its compiler's registries, which
only a compile needs (:func:`_load_unrefreshed`: 0.7 s of CPU per process), and finds the cache folder
once per kernel file, not once per function.

:func:`install` registers the locator with numba; it must run before the kernel modules are
imported (numba picks a function's locator when ``@njit(cache=True)`` is applied). It changes
nothing for functions outside this package.

:func:`install` also tells :mod:`rockcli.compiling` when numba starts and ends compiling a kernel of
this package (a cache miss: the first run on a machine, or after an edit), so that the command line
can say why it waits (:func:`_watch_compiles`).

``NUMBA_NUM_THREADS`` set to 0 or less makes numba fail at import; it is refused here first, in one
sentence (:func:`check_thread_setting`).
"""

from __future__ import annotations

import hashlib
import os
import pickle
import sys
import threading
import time
from pathlib import Path

from rockcli.errors import RockcliInputError

PACKAGE_DIR = Path(__file__).resolve().parent
_notices: set = set()
_folders: dict = {}  # (NUMBA_CACHE_DIR, source file) -> (cache folder, writable), or None: not this package's
_held: dict = {}  # compile lock file -> its descriptor, for the functions this process is compiling
#: Longest wait for another process's compile of the same function [s]; then it is compiled here as well.
COMPILE_WAIT_S = 900.0


def check_thread_setting() -> None:
    """Refuse ``NUMBA_NUM_THREADS`` <= 0 in one sentence (numba itself raises a traceback at import)."""
    text = os.environ.get("NUMBA_NUM_THREADS", "").strip()
    try:
        value = int(text)
    except ValueError:
        return  # unset, or a value numba ignores with its own warning
    if value <= 0:
        raise RockcliInputError(f"NUMBA_NUM_THREADS={text}: give a positive number of threads, or unset it")


check_thread_setting()


def notice(text: str) -> None:
    """Print ``text`` once per process on the standard error, as one line."""
    if text in _notices:
        return
    _notices.add(text)
    try:
        sys.stderr.write(f"rockcli: {text}\n")
        sys.stderr.flush()
    except (OSError, ValueError, AttributeError):  # no standard error: nothing more to do
        pass


def source_hash(folder: Path = PACKAGE_DIR) -> str:
    """SHA-256 (hex) over the names and contents of the ``*.py`` files of ``folder``, sorted by name."""
    h = hashlib.sha256()
    for path in sorted(folder.glob("*.py")):
        h.update(path.name.encode())
        h.update(b"\0")
        h.update(path.read_bytes())
        h.update(b"\0")
    return h.hexdigest()


def install() -> None:
    """Register :class:`PackageLocator` first in numba's list of cache locators, and make cache
    reads and writes of this package's functions non-fatal (idempotent)."""
    from numba.core import caching

    locators = caching.CacheImpl._locator_classes
    for cls in list(locators):  # a re-import of this module defines a new class: replace the old one
        if getattr(cls, "_rockcli_package_locator", False) and cls is not PackageLocator:
            locators.remove(cls)
    if PackageLocator not in locators:
        locators.insert(0, PackageLocator)
    _wrap_cache_io(caching.Cache)
    _watch_compiles()


def _watch_compiles() -> None:
    """Report each outermost compile of a function of this package to :mod:`rockcli.compiling` (idempotent).

    numba triggers a ``numba:compile`` event only when it really compiles (a function loaded from the
    disk cache triggers none), once per function, nested for the callees a kernel pulls in: only the
    outermost function of this package in a thread is reported.
    """
    from numba.core import event

    if any(getattr(x, "_rockcli_watch", False) for x in event._registered.get("numba:compile", ())):
        return
    from rockcli import compiling

    local = threading.local()

    class _Watch(event.Listener):
        _rockcli_watch = True

        def _name(self, ev):
            func = getattr(ev.data.get("dispatcher"), "py_func", None)
            module = getattr(func, "__module__", "") or ""
            if not module.startswith(__package__ + "."):
                return None
            return f"{module.rsplit('.', 1)[-1]}.{func.__qualname__}"

        def on_start(self, ev):
            name = self._name(ev)
            if name is None:
                return
            stack = local.__dict__.setdefault("stack", [])
            stack.append(time.perf_counter())
            if len(stack) == 1:
                compiling.started(name)

        def on_end(self, ev):
            name = self._name(ev)
            if name is None:
                return
            dispatcher, args = ev.data.get("dispatcher"), tuple(ev.data.get("args", ()))
            if args not in getattr(dispatcher, "overloads", {}):
                _release_compile(getattr(dispatcher, "_cache", None), args)  # it failed: nothing will be saved
            stack = local.__dict__.get("stack")
            if not stack:
                return
            t0 = stack.pop()
            if not stack:
                compiling.ended(name, time.perf_counter() - t0)

    event.register("numba:compile", _Watch())


def _ours(cache) -> bool:
    locator = getattr(getattr(cache, "_impl", None), "locator", None)
    return bool(getattr(locator, "_rockcli_package_locator", False))


def _wrap_cache_io(cache_cls) -> None:
    """Cache I/O of this package's functions: an OSError (or a damaged file) skips the cache with a notice."""
    save, load = cache_cls.save_overload, cache_cls.load_overload
    if getattr(save, "_rockcli_tolerant", False):
        return

    def save_overload(self, sig, data):
        if not _ours(self):
            return save(self, sig, data)
        if getattr(self._impl.locator, "_no_disk", False):
            return None
        try:
            return save(self, sig, data)
        except OSError as exc:
            self.disable()
            reason = (exc.strerror or type(exc).__name__).lower()
            notice(f"numba's disk cache could not be written in {self.cache_path} ({reason}); the kernels "
                   f"run without it")
            return None
        finally:
            _release_compile(self, sig)  # saved (or not): a process waiting for this compile loads it now

    def load_overload(self, sig, target_context):
        if not _ours(self):
            return load(self, sig, target_context)
        def attempt():
            if hasattr(self, "_load_overload"):  # numba's internals as this module knows them
                return _load_unrefreshed(self, sig, target_context)
            return load(self, sig, target_context)

        try:
            data = attempt()
            if data is None and _claim_compile(self, sig):
                data = attempt()  # the process this one waited for (if any) has saved it meanwhile
                if data is not None:
                    _release_compile(self, sig)
            return data
        except (OSError, EOFError, pickle.UnpicklingError):
            _release_compile(self, sig)
            return None  # an unreadable or damaged entry: compiled again

    save_overload._rockcli_tolerant = True
    cache_cls.save_overload, cache_cls.load_overload = save_overload, load_overload


def _compile_lock_path(cache, sig) -> str | None:
    """The lock file of one specialisation (argument types ``sig``) of ``cache``'s function, beside its index."""
    locator = getattr(getattr(cache, "_impl", None), "locator", None)
    index = getattr(getattr(cache, "_cache_file", None), "_index_path", None)
    if locator is None or getattr(locator, "_no_disk", False) or not index:
        return None
    try:
        from numba.core import sigutils

        args = sigutils.normalize_signature(sig)[0]
    except Exception:  # noqa: BLE001 - only an optimisation depends on it
        return None
    return f"{index}.{hashlib.sha256(str(tuple(args)).encode()).hexdigest()[:16]}.lock"


def _claim_compile(cache, sig) -> bool:
    """Before this process compiles a function of this package for argument types ``sig`` that the disk cache
    lacks: wait while another process compiles the same specialisation (an exclusive ``flock`` on a lock file
    beside the function's cache index, one per argument types), then
    hold that lock until this process has saved it (:func:`_release_compile`). True when this process holds
    the lock (the caller then loads again: a process it waited for, or one that finished just before the
    lock was taken, has saved the function), False when it cannot lock (then it compiles, as without it).

    Two processes that start on a machine whose cache lacks a kernel (a fresh clone's test suite on two
    workers, two first commands at once, :func:`rockcli.kernels.batch.prepare`'s child and parent with
    their shared callees) would otherwise each compile it: the same machine code, twice the CPU. Waiting
    changes nothing but who compiles: the code loaded is the code the other process compiled and saved,
    the same as compiling it here (numba's cache is keyed on the sources and the machine). No deadlock:
    a process waits for a specialisation only while compiling its callers (or nothing), and holds only
    the locks of the specialisations it is compiling, so every wait follows the call graph of the
    kernels, which has no cycle (no kernel is recursive); and a process that dies releases its locks. The wait ends after
    :data:`COMPILE_WAIT_S` in any case (then it compiles here). On a file system without ``flock``, or
    without a writable cache, nothing is locked.
    """
    path = _compile_lock_path(cache, sig)
    if path is None or path in _held:
        return False
    try:
        import fcntl

        fd = os.open(path, os.O_RDWR | os.O_CREAT, 0o666)
    except (ImportError, OSError):
        return False
    from rockcli import compiling

    waited, signalled, t0 = False, False, time.monotonic()
    try:
        while True:
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
                break
            except BlockingIOError:
                if not waited and not compiling.compiling():  # the wait is the first run's compile
                    compiling.started(_kernel_name(cache))
                    signalled = True
                waited = True
                if time.monotonic() - t0 > COMPILE_WAIT_S:
                    os.close(fd)
                    return False
                time.sleep(0.05)
    except OSError:
        os.close(fd)
        return False
    finally:
        if signalled:
            compiling.ended(_kernel_name(cache), time.monotonic() - t0)
    _held[path] = fd
    return True


def _release_compile(cache, sig) -> None:
    """Release the compile lock :func:`_claim_compile` took for ``cache``'s function and ``sig`` (if held here)."""
    path = _compile_lock_path(cache, sig) if cache is not None else None
    fd = _held.pop(path, None) if path else None
    if fd is not None:
        try:
            os.close(fd)  # closing the only descriptor of the file releases the flock
        except OSError:
            pass


def _kernel_name(cache) -> str:
    func = getattr(cache, "_py_func", None)
    return f"{getattr(func, '__module__', '').rsplit('.', 1)[-1]}.{getattr(func, '__qualname__', '?')}"


def _load_unrefreshed(cache, sig, target_context):
    """numba's ``Cache.load_overload`` for a function of this package, without its first step, the
    refresh of the compiler's registries.

    ``Cache.load_overload`` begins with ``target_context.refresh()``, which imports and installs every
    typing and lowering implementation numba has (``numba.np.arraymath`` among them, which imports
    ``scipy.linalg`` to look for a BLAS): about 0.7 s of CPU, more than half of a warm ``rockcli
    simulate``, spent once per process before the first kernel is loaded. A load needs none of it:

    * a cache entry is the function's machine code (object code, callees linked in), its bitcode for
      inlining and pickled descriptors; loading links that object code into numba's JIT engine and
      resolves its external symbols, and compiles nothing. The code that runs is the same bytes
      whether the registries were refreshed or not, so a result cannot change.
    * the external symbols it may use are numba's C helpers and the C math functions (registered
      when numba's CPU context is created, before any load), the runtime's (NRT; registered by
      ``rtsys.initialize``, which the refresh would call and which is called here), and the hash
      secrets of ``numba.cpython.hashing`` (registered at its import, done here). The only other
      symbols numba registers are the parallel scheduler's, for ``parallel=True`` code, which this
      package does not have (its kernels run on a pool of threads, see :mod:`rockcli.kernels.batch`;
      tests/test_first_run.py checks both that no kernel asks for it and that every batch and
      single-run kernel loads and runs this way in a fresh process, with the same results as after
      a refresh). A symbol missing at link time would stop the process with LLVM's error, never run
      other code.
    * a cache miss returns None and numba compiles the function; its compiler refreshes the
      registries itself first (``CompilerBase.__init__``), as every later compile does.
    """
    from numba.core.runtime import rtsys

    import numba.cpython.hashing  # noqa: F401  (its symbols, see above)

    rtsys.initialize(target_context)
    with cache._guard_against_spurious_io_errors():
        return cache._load_overload(sig, target_context)


def _make_locator():
    from numba.core import caching, config

    class _PackageLocator(caching.InTreeCacheLocator):
        """Cache locator of the kernel package: stamp = hash of all its sources (see the module notes)."""

        _rockcli_package_locator = True
        _stamp = None

        def __init__(self, py_func, py_file, cache_path):
            self._py_file = py_file
            self._lineno = py_func.__code__.co_firstlineno if py_func is not None else 0
            self._cache_path = cache_path

        def get_source_stamp(self):
            if _PackageLocator._stamp is None:
                _PackageLocator._stamp = source_hash()
            return _PackageLocator._stamp

        @classmethod
        def from_function(cls, py_func, py_file):
            key = (config.CACHE_DIR, py_file)
            if key not in _folders:
                _folders[key] = cls._folder(py_file)
            found = _folders[key]
            if found is None:
                return None  # not ours: numba's own locators decide
            path, writable = found
            return (cls if writable else _NoDiskLocator)(py_func, py_file, path)

        @classmethod
        def _folder(cls, py_file):
            """``(cache folder, writable)`` of the functions of ``py_file``, or None when it is not a file of this
            package. Found once per file and process (the package's ~110 functions share one or a few folders;
            a folder that can no longer be written later makes a save fail with the notice of
            :func:`_wrap_cache_io`)."""
            try:
                inside = Path(py_file).resolve().parent == PACKAGE_DIR
            except OSError:
                return None
            if not inside:
                return None
            candidates = []
            if config.CACHE_DIR:
                candidates.append(os.path.join(config.CACHE_DIR, cls.get_suitable_cache_subpath(py_file)))
            else:
                candidates.append(str(PACKAGE_DIR / "__pycache__"))
                from numba.misc.appdirs import AppDirs

                user = AppDirs(appname="numba", appauthor=False).user_cache_dir
                candidates.append(os.path.join(user, "rockcli", cls.get_suitable_cache_subpath(py_file)))
            for path in candidates:
                try:
                    cls(None, py_file, path).ensure_cache_path()
                except OSError:
                    continue
                return path, True
            if config.CACHE_DIR:
                bases = [config.CACHE_DIR]
            else:
                bases = [str(PACKAGE_DIR / "__pycache__"), str(Path(user) / "rockcli")]
            notice(f"numba's disk cache cannot be written (tried {' and '.join(bases)}); kernels not cached there are "
                   f"compiled in memory on every run (about a minute; set NUMBA_CACHE_DIR to a writable folder)")
            return candidates[0], False

    class _NoDiskLocator(_PackageLocator):
        """No folder can be written: nothing is saved; loads use what is there (a cache shipped read-only)."""

        _no_disk = True

        def ensure_cache_path(self):
            pass

    return _PackageLocator


PackageLocator = _make_locator()
