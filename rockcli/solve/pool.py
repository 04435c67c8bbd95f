"""The process's pool of threads that the batch kernels run on (they release the GIL): :func:`run_tasks`.

One pool per process, created on first use with :func:`_threads` workers and kept: a margin search calls
:func:`rockcli.solve.simulate_many` a few hundred times, and a pool per call started two threads each time
(issue 33). A forked child gets a pool of its own (threads do not survive a fork), a change of the thread
count (``NUMBA_NUM_THREADS``) a new one. A task that itself runs tasks (a callable on the pool calling
:func:`run_tasks`) runs them in its own thread, one after the other: a bounded pool waiting on itself
would deadlock.
"""

from __future__ import annotations

import os
import threading

_LOCK = threading.Lock()
_POOL = None  # (pid, workers, ThreadPoolExecutor)
_CALLERS = None  # (pid, ThreadPoolExecutor): the threads of in_background
_ON_POOL = threading.local()  # .yes on the pool's own threads


def _threads() -> int:
    """Threads a sweep runs on: the cores this process may use (``NUMBA_NUM_THREADS`` caps them)."""
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    cap = os.environ.get("NUMBA_NUM_THREADS", "")
    return max(1, min(cores, int(cap))) if cap.isdigit() and int(cap) > 0 else max(1, cores)


def _mark():
    _ON_POOL.yes = True


def _pool(workers: int):
    """The process's executor with ``workers`` threads (made on first use, after a fork or a new count)."""
    global _POOL
    with _LOCK:
        pid = os.getpid()
        if _POOL is None or _POOL[0] != pid or _POOL[1] != workers:
            from concurrent.futures import ThreadPoolExecutor

            if _POOL is not None and _POOL[0] == pid:
                _POOL[2].shutdown(wait=False)  # its idle threads end; tasks already queued still run
            _POOL = (pid, workers, ThreadPoolExecutor(max_workers=workers, thread_name_prefix="rockcli-kernel",
                                                      initializer=_mark))
        return _POOL[2]


def in_background(func, *args, **kwargs):
    """``func(*args, **kwargs)`` on one of the process's two caller threads (not the pool's): a Future.

    For a caller that prepares its next batch while the pool runs the last one (the margin search's two lanes,
    :func:`rockcli.assess.find_overturn_scales`): ``func`` may call :func:`run_tasks`, which then uses the pool
    (a caller thread is not one of the pool's, so nothing waits on itself).
    """
    global _CALLERS
    with _LOCK:
        if _CALLERS is None or _CALLERS[0] != os.getpid():
            from concurrent.futures import ThreadPoolExecutor

            _CALLERS = (os.getpid(), ThreadPoolExecutor(max_workers=2, thread_name_prefix="rockcli-caller"))
        return _CALLERS[1].submit(func, *args, **kwargs)


def run_tasks(tasks, *, done=None, threads: int | None = None) -> list:
    """Call each of ``tasks`` (callables without arguments) on the pool; their results, in the order of ``tasks``.

    The tasks start in their order: each of ``threads`` workers takes the next task not yet taken when it is
    free (so a list ordered longest first keeps the workers busy alike). ``done(result)`` is called here (the
    calling thread) as each task finishes, in the order they finish. With one thread, one task, or when called
    from a task on the pool, the tasks run here one after the other. An error in a task, or Ctrl-C, stops the
    tasks not yet started and is raised (the ones running finish in the background: a compiled kernel cannot be
    interrupted).
    """
    tasks = list(tasks)
    threads = _threads() if threads is None else max(1, int(threads))
    if threads == 1 or len(tasks) <= 1 or getattr(_ON_POOL, "yes", False):
        out = []
        for task in tasks:
            out.append(task())
            if done is not None:
                done(out[-1])
        return out
    import queue

    results = [None] * len(tasks)
    order = iter(range(len(tasks)))  # shared: next() on it hands each index to one worker (atomic under the GIL)
    stop = []
    finished = queue.SimpleQueue() if done is not None else None

    def worker():
        try:
            for i in order:
                if stop:
                    return
                results[i] = tasks[i]()
                if finished is not None:
                    finished.put(i)
        except BaseException:
            stop.append(True)
            if finished is not None:
                finished.put(-1)  # wakes the caller, which then raises this worker's error
            raise

    pool = _pool(threads)
    futures = [pool.submit(worker) for _ in range(min(threads, len(tasks)))]
    try:
        if finished is not None:
            for _ in range(len(tasks)):
                i = finished.get()
                if i < 0:
                    break
                done(results[i])
        for fut in futures:
            fut.result()  # a worker's error, raised here
    except BaseException:
        stop.append(True)
        raise
    return results
