"""Running sweeps on a Dask cluster (optional: ``pip install -e ".[dask]"``).

Only this module imports dask, and only when a scheduler is asked for. A sweep is split into
chunks; each chunk is one task that runs the compiled kernel on a worker (on a thread per core of the
worker's cores) and returns small arrays. The workers need rockcli installed in the same version.
Results are gathered in the order of the chunks, so a sweep gives the same answer on any cluster
as on this machine (every scene is deterministic and independent of the others).

Nothing waits forever (the timeout is ``ROCKCLI_DASK_TIMEOUT`` seconds, default
:data:`DEFAULT_TIMEOUT`; every message states it):

* the address is checked before any work: ``local`` or ``tcp://HOST[:PORT]`` (other protocols
  need settings rockcli does not pass, and are refused);
* before the Dask client connects, :func:`probe_scheduler` opens a plain socket and reads the
  greeting a Dask server sends first: a server that says nothing within the timeout, or whose
  first message is not a Dask handshake (an HTTP or SSH server, say), is refused in one sentence
  instead of hanging or of reading its bytes as a frame length (a huge allocation);
* the run starts only when a worker has joined (within the timeout);
* while the tasks run, a cluster left without any worker for longer than the timeout (the only
  worker died and nothing restarted it), a lost scheduler, or a task that killed its workers
  (Dask's ``KilledWorker``) stops the run with one sentence; no output is written.
"""

from __future__ import annotations

import contextlib
import os
import re
import socket
import struct
import time

from rockcli.errors import RockcliInputError

#: Seconds rockcli waits for a scheduler's greeting, for a first worker, or for a lost worker's
#: replacement (``ROCKCLI_DASK_TIMEOUT`` overrides it).
DEFAULT_TIMEOUT = 60.0

_ADDRESS = re.compile(r"^tcp://(?P<host>\[[0-9A-Fa-f:.]+\]|[^\s:/\[\]]+)(?::(?P<port>\d{1,5}))?/?$")
_OTHER = re.compile(r"^(?P<scheme>[A-Za-z][A-Za-z0-9+.-]*)://")
_DEFAULT_PORT = 8786
#: A Dask handshake is one small message: a first length field beyond this is not Dask.
_HANDSHAKE_MAX = 1 << 20


def timeout_s() -> float:
    """The timeout [s] of every wait on a cluster (``ROCKCLI_DASK_TIMEOUT``, default :data:`DEFAULT_TIMEOUT`)."""
    text = os.environ.get("ROCKCLI_DASK_TIMEOUT", "").strip()
    if not text:
        return DEFAULT_TIMEOUT
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not 0.1 <= value <= 86400:  # also refuses nan
        raise RockcliInputError(f"ROCKCLI_DASK_TIMEOUT={text!r}: give a number of seconds from 0.1 to 86400")
    return value


def _import_distributed():
    try:
        import distributed  # noqa: F401
    except ImportError:
        raise RockcliInputError("--scheduler needs Dask: pip install -e \".[dask]\" (dask and distributed)") from None
    return distributed


def _split_address(scheduler: str) -> tuple[str, int]:
    m = _ADDRESS.match(scheduler)
    if m is None:
        other = _OTHER.match(scheduler)
        if other is not None and other.group("scheme").lower() != "tcp":
            raise RockcliInputError(f"--scheduler {scheduler!r}: the {other.group('scheme')}:// protocol is not "
                                    f"supported; give 'local' or a tcp:// address such as tcp://10.0.0.5:8786")
        raise RockcliInputError(f"--scheduler {scheduler!r}: give 'local' or an address such as tcp://10.0.0.5:8786")
    port = int(m.group("port") or _DEFAULT_PORT)
    if not 1 <= port <= 65535:
        raise RockcliInputError(f"--scheduler {scheduler!r}: port {port} is outside 1 to 65535")
    return m.group("host").strip("[]"), port


#: Said after a scheduler address that cannot be reached: what to start there, or how to do without one.
NO_SCHEDULER_HINT = ("; start a Dask scheduler there (dask scheduler --port PORT, with workers: dask worker ADDRESS), "
                     "or give --scheduler local to run a Dask cluster on this machine")


def check_scheduler(scheduler) -> None:
    """Raise one sentence unless ``scheduler`` is ``local``, ``tcp://HOST[:PORT]`` or a Client."""
    if scheduler is None or not isinstance(scheduler, str):
        return
    if scheduler != "local":
        _split_address(scheduler)
    timeout_s()


def probe_scheduler(scheduler: str, timeout: float) -> None:
    """Check that a Dask server answers at ``scheduler`` before the Dask client is let near it.

    A Dask server writes its handshake as soon as a connection is accepted: an 8-byte length,
    then that many bytes, starting with the 8-byte count of its frames. Only these 16 bytes are read.

    Raises
    ------
    RockcliInputError
        Nothing listens there, nothing is said within ``timeout`` seconds, or what is said is not
        the start of a Dask handshake.
    """
    host, port = _split_address(scheduler)
    try:
        sock = socket.create_connection((host, port), timeout=timeout)
    except socket.timeout:
        raise RockcliInputError(f"--scheduler {scheduler}: no answer within {timeout:g} s{NO_SCHEDULER_HINT}") from None
    except OSError as exc:
        raise RockcliInputError(f"--scheduler {scheduler}: cannot connect ({exc.strerror or exc}){NO_SCHEDULER_HINT}"
                                ) from None
    with sock:
        head = b""
        deadline = time.monotonic() + timeout
        try:
            while len(head) < 16:
                sock.settimeout(max(0.01, deadline - time.monotonic()))
                chunk = sock.recv(16 - len(head))
                if not chunk:
                    break
                head += chunk
        except socket.timeout:
            raise RockcliInputError(f"--scheduler {scheduler}: the server there accepts connections but says "
                                    f"nothing in {timeout:g} s; it is not a Dask scheduler") from None
        except OSError as exc:
            raise RockcliInputError(f"--scheduler {scheduler}: the connection failed ({exc.strerror or exc})") from None
    if len(head) < 16:
        raise RockcliInputError(f"--scheduler {scheduler}: the server there closed the connection without a Dask "
                                f"greeting; it is not a Dask scheduler")
    size, n_frames = struct.unpack("<QQ", head)
    if not (16 <= size <= _HANDSHAKE_MAX and 1 <= n_frames <= 64):
        raise RockcliInputError(f"--scheduler {scheduler}: the server there does not speak the Dask protocol "
                                f"(it began with {head[:8]!r})")


@contextlib.contextmanager
def open_client(scheduler, *, n_workers: int | None = None, processes: bool = True, timeout: float | None = None):
    """A ``distributed.Client`` for ``scheduler`` with a worker ready, closed (with its LocalCluster) on exit.

    Parameters
    ----------
    scheduler : str or distributed.Client
        ``"local"``: a new LocalCluster (``n_workers`` workers, one thread each, in processes
        unless ``processes=False``); ``"tcp://HOST:PORT"``: connect to a running scheduler
        (probed first, see :func:`probe_scheduler`); a ``Client``: used as it is (not closed).
    timeout : float, optional
        Seconds to wait for the scheduler and for a first worker (default :func:`timeout_s`).
    """
    check_scheduler(scheduler)
    timeout = timeout_s() if timeout is None else float(timeout)
    if not isinstance(scheduler, str):
        yield scheduler
        return
    distributed = _import_distributed()
    from rockcli.progress import announce

    if scheduler == "local":
        announce("starting a Dask LocalCluster on this machine ...")
        cluster = distributed.LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=processes,
                                           dashboard_address=None)
        client = distributed.Client(cluster)
        try:
            yield client
        finally:
            import logging

            # a worker process slow to exit (a loaded machine) is killed by its nanny after 4 s with a WARNING:
            # a shutdown detail after the results are in, which read as a fault at the end of a good run
            nanny = logging.getLogger("distributed.nanny")
            level = nanny.level
            nanny.setLevel(logging.ERROR)
            try:
                client.close()
                cluster.close()
            finally:
                nanny.setLevel(level)
        return
    announce(f"connecting to the Dask scheduler at {scheduler} (waiting up to {timeout:g} s) ...")
    probe_scheduler(scheduler, timeout)
    try:
        client = distributed.Client(scheduler, timeout=timeout)
    except (OSError, TimeoutError) as exc:
        raise RockcliInputError(f"--scheduler {scheduler}: cannot connect within {timeout:g} s ({exc})"
                                f"{NO_SCHEDULER_HINT}") from None
    try:
        try:
            client.wait_for_workers(1, timeout=timeout)
        except (OSError, TimeoutError):
            raise RockcliInputError(f"--scheduler {scheduler}: no worker joined the scheduler within {timeout:g} s "
                                    f"(start one with: dask worker {scheduler})") from None
        yield client
    finally:
        with contextlib.suppress(Exception):
            client.close(timeout=min(timeout, 5.0))


def describe_cluster(client, local: bool = False) -> str:
    """One line on the cluster ``client`` uses: scheduler address, workers, threads, dashboard address
    (``local``: a LocalCluster this process started, without a dashboard (``dashboard_address=None``): nothing is
    said of one; its scheduler still lists an HTTP service named ``dashboard``, which serves only ``/health``)."""
    try:
        nthreads = client.nthreads()
    except Exception:  # noqa: BLE001 - a scheduler out of reach: say what is known
        nthreads = {}
    address = getattr(getattr(client, "scheduler", None), "address", None) or "?"
    kind = "a LocalCluster on this machine, scheduler" if local else "the scheduler"
    head = f"Dask: {kind} at {address}, {len(nthreads)} worker(s) with {sum(nthreads.values())} thread(s)"
    if local:
        return head
    try:
        services = client.scheduler_info().get("services", {})
    except Exception:  # noqa: BLE001
        services = {}
    dashboard = client.dashboard_link if services.get("dashboard") else None
    return f"{head}; dashboard: {dashboard or 'none'}"


def _n_workers(client, timeout: float) -> int | None:
    """Workers the scheduler knows now (None: the scheduler did not answer within ``timeout``)."""
    try:
        return len(client.sync(client.scheduler.ncores, callback_timeout=timeout))
    except Exception:  # noqa: BLE001 - a closed comm, a timeout: the scheduler is out of reach
        return None


def _where(client) -> str:
    address = getattr(client, "scheduler", None)
    return f"the Dask scheduler {getattr(address, 'address', '') or ''}".rstrip()


def wait_for_results(client, futures, *, progress=None, timeout: float | None = None, poll: float = 0.5) -> list:
    """The results of ``futures`` in their order, watching the cluster while they run.

    ``progress(i)`` is called with the index of each future as it finishes. Raises one sentence
    when the cluster has had no worker for ``timeout`` seconds, when the scheduler is lost, or
    when a task killed its workers; an error raised by a task itself is raised here unchanged.
    """
    distributed = _import_distributed()
    timeout = timeout_s() if timeout is None else float(timeout)
    pending = dict(enumerate(futures))
    alone_since = None
    last_check = 0.0
    while pending:
        for i, fut in list(pending.items()):
            status = fut.status
            if status == "pending":
                continue
            if status in ("cancelled", "lost"):
                raise RockcliInputError(f"{_where(client)} lost the tasks (it stopped or restarted); no result is "
                                        f"given")
            if status == "error":
                try:
                    fut.result()
                except distributed.KilledWorker:
                    raise RockcliInputError(f"{_where(client)}: the workers running a task died each time it was "
                                            f"tried (Dask's KilledWorker: out of memory?); no result is "
                                            f"given") from None
            del pending[i]
            if progress is not None:
                progress(i)
        if not pending:
            break
        now = time.monotonic()
        if now - last_check >= 1.0:
            last_check = now
            workers = _n_workers(client, timeout)
            if workers is None:
                raise RockcliInputError(f"{_where(client)} did not answer within {timeout:g} s; no result is given")
            if workers:
                alone_since = None
            elif alone_since is None:
                alone_since = now
            elif now - alone_since > timeout:
                raise RockcliInputError(f"{_where(client)} has had no worker for {timeout:g} s (the workers died or "
                                        f"left); no result is given")
        try:  # returns as soon as one more task ends, or after ``poll`` seconds
            distributed.wait(list(pending.values()), timeout=poll, return_when="FIRST_COMPLETED")
        except TimeoutError:
            pass
        except Exception:  # noqa: BLE001 - cancelled tasks (the statuses above tell), or another default client
            time.sleep(poll)
    try:
        return client.gather(list(futures))
    except distributed.KilledWorker:  # pragma: no cover - the loop above saw every error first
        raise RockcliInputError(f"{_where(client)}: a task's workers died while running it") from None


def map_chunks(client, func, chunks, *, progress=None) -> list:
    """``[func(c) for c in chunks]`` as Dask tasks, results in the order of ``chunks``.

    ``progress(i)`` is called with the index of each chunk as it finishes; a run that cannot finish
    (see :func:`wait_for_results`) stops with one sentence within the timeout.
    """
    futures = client.map(func, chunks, pure=False)
    try:
        return wait_for_results(client, futures, progress=progress)
    except BaseException:
        with contextlib.suppress(Exception):
            client.cancel(futures)
        raise
