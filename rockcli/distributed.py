"""Running sweeps on a Dask cluster (optional: ``pip install -e ".[dask]"``).

Only this module imports dask, and only when a scheduler is asked for. A sweep is split into
chunks; each chunk is one task that runs the compiled kernel on a worker (on a thread per core of the
worker's cores) and returns small arrays. The workers need rockcli installed in the same version.
Results are gathered in the order of the chunks, so a sweep gives the same answer on any cluster
as on this machine (every scene is deterministic and independent of the others).
"""

from __future__ import annotations

import contextlib
import re

from rockcli.errors import RockcliInputError

_ADDRESS = re.compile(r"^(tcp|tls|ucx|inproc)://[^\s:/]+(:\d+)?/?$")


def _import_distributed():
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise RockcliInputError("--scheduler needs Dask: pip install -e \".[dask]\" (dask and distributed)") from None
    return distributed


def check_scheduler(scheduler) -> None:
    """Raise one sentence unless ``scheduler`` is ``local``, ``tcp://HOST:PORT`` (or tls/ucx) or a Client."""
    if scheduler is None or not isinstance(scheduler, str):
        return
    if scheduler != "local" and not _ADDRESS.match(scheduler):
        raise RockcliInputError(f"--scheduler {scheduler!r}: give 'local' or an address such as tcp://10.0.0.5:8786")


@contextlib.contextmanager
def open_client(scheduler, *, n_workers: int | None = None, processes: bool = True, timeout: float = 10.0):
    """A ``distributed.Client`` for ``scheduler``, closed (with its LocalCluster) on exit.

    Parameters
    ----------
    scheduler : str or distributed.Client
        ``"local"``: a new LocalCluster (``n_workers`` workers, one thread each, in processes
        unless ``processes=False``); ``"tcp://HOST:PORT"``: connect to a running scheduler;
        a ``Client``: used as it is (not closed).
    """
    check_scheduler(scheduler)
    if not isinstance(scheduler, str):
        yield scheduler
        return
    distributed = _import_distributed()
    if scheduler == "local":
        cluster = distributed.LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=processes,
                                           dashboard_address=None)
        client = distributed.Client(cluster)
        try:
            yield client
        finally:
            client.close()
            cluster.close()
        return
    try:
        client = distributed.Client(scheduler, timeout=timeout)
    except (OSError, TimeoutError) as exc:
        raise RockcliInputError(f"--scheduler {scheduler}: cannot connect ({exc})") from None
    try:
        yield client
    finally:
        client.close()


def map_chunks(client, func, chunks, *, progress=None) -> list:
    """``[func(c) for c in chunks]`` as Dask tasks, results in the order of ``chunks``.

    ``progress(i)`` is called with the index of each chunk as it finishes.
    """
    distributed = _import_distributed()
    futures = client.map(func, chunks, pure=False)
    index = {f.key: i for i, f in enumerate(futures)}
    if progress is not None:
        for fut in distributed.as_completed(futures):
            progress(index[fut.key])
    return client.gather(futures)
