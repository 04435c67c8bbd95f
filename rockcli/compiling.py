"""When the kernels compile, as the rest of rockcli sees it (plain Python: no numba here).

The first run on a machine compiles the kernels (numba; a cache miss) and later runs load them from
the disk cache (:mod:`rockcli.kernels.cache`). A compile takes tens of seconds while nothing else
seems to happen, so whoever shows progress wants to know: :mod:`rockcli.kernels.cache` calls
:func:`started` when numba begins compiling a kernel of rockcli (the outermost function of a
compile, not each callee it pulls in), or when this process begins to wait for another process's
compile of a kernel it needs, and :func:`ended` when that compile or wait is done; a loaded kernel
calls neither. The command line subscribes with :func:`subscribe` (a one-line notice on a terminal,
and a progress bar that shows no ETA while the kernels compile).

Importing this module costs nothing (no numba), so it can be done before the kernels are needed.
"""

from __future__ import annotations

import threading

_listeners: list = []
_lock = threading.Lock()
_active = 0
_count = 0


def subscribe(on_start=None, on_end=None):
    """Call ``on_start(name)`` when a compile of a kernel begins and ``on_end(name, seconds)`` when it
    ends (``name``: ``module.function``; either may be None). Returns a function that unsubscribes."""
    entry = (on_start, on_end)
    with _lock:
        _listeners.append(entry)

    def unsubscribe():
        with _lock:
            if entry in _listeners:
                _listeners.remove(entry)

    return unsubscribe


def compiling() -> bool:
    """True while a kernel compiles (in any thread of this process)."""
    return _active > 0


def compiles() -> int:
    """How many kernel compiles have begun in this process (0: every kernel came from the cache)."""
    return _count


def started(name: str) -> None:
    """Called by :mod:`rockcli.kernels.cache` when a kernel's compile begins (listeners' errors are dropped)."""
    global _active, _count
    with _lock:
        _active += 1
        _count += 1
        listeners = list(_listeners)
    for on_start, _ in listeners:
        _call(on_start, name)


def ended(name: str, seconds: float) -> None:
    """Called by :mod:`rockcli.kernels.cache` when a kernel's compile ends (``seconds`` of wall time)."""
    global _active
    with _lock:
        _active = max(0, _active - 1)
        listeners = list(_listeners)
    for _, on_end in listeners:
        _call(on_end, name, seconds)


def _call(func, *args) -> None:
    """A listener's call: what it raises must not reach numba's compiler (the compile goes on)."""
    if func is None:
        return
    try:
        func(*args)
    except Exception:  # noqa: BLE001 - a notice that cannot be shown is no reason to fail the run
        pass
