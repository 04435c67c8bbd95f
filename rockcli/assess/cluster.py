"""``assess column --scheduler``: the runs of an assessment as tasks on a Dask cluster.

:func:`run_on_dask` runs :func:`rockcli.assess.table.run_assessment` with a ``runner`` that maps each
part (the verdicts at 1x, the margin search, the neighbourhood) over chunks of its items as Dask tasks
(:func:`rockcli.distributed.map_chunks`), and announces each part with the number of its tasks. Every
scene's runs are deterministic and depend on that scene only (a margin search: on its group, which a
chunk never splits), so the result is that of the local run, row for row.
"""

from __future__ import annotations

from typing import Callable

#: The parts of an assessment by the function a runner maps, as the progress line names them.
PARTS = {"simulate_many": "verdicts", "search_groups": "margin search", "overturn_shares": "neighbourhood"}


def _part(func) -> str:
    return PARTS.get(getattr(getattr(func, "func", func), "__name__", ""), "runs")


def dask_runner(client, progress: Callable[[int], None] | None = None) -> Callable:
    """A runner for :func:`rockcli.assess.margin.map_chunks` on ``client``: each call is one part,
    announced as ``<part> on Dask (N tasks)`` and counted in scenes as each task comes back."""
    from rockcli.assess.margin import SearchGroup, chunk_scenes
    from rockcli.distributed import map_chunks as dask_map
    from rockcli.progress import phase

    def scenes(chunk) -> int:
        return chunk_scenes(chunk) if chunk and isinstance(chunk[0], SearchGroup) else len(chunk)

    def runner(func, chunks):
        if progress is None:
            return dask_map(client, func, chunks)
        phase(progress, f"{_part(func)} on Dask ({len(chunks)} tasks)", sum(scenes(c) for c in chunks),
              known=False, unit="scenes")
        return dask_map(client, func, chunks, progress=lambda i: progress(scenes(chunks[i])))

    return runner


def run_on_dask(scheduler, columns, excitations, configurations, *, chunks_per_worker: int = 4,
                progress: Callable[[int], None] | None = None, **kwargs):
    """:func:`rockcli.assess.table.run_assessment` with its runs on a Dask cluster (same rows).

    ``scheduler`` is ``"local"`` (a LocalCluster here), ``"tcp://HOST:PORT"`` or a ``distributed.Client``;
    each part is split into about ``chunks_per_worker`` tasks per worker.
    """
    from rockcli.assess.table import run_assessment
    from rockcli.distributed import open_client

    with open_client(scheduler) as client:
        workers = max(1, len(client.scheduler_info().get("workers", {})))
        return run_assessment(columns, excitations, configurations, runner=dask_runner(client, progress),
                              chunks=workers * int(chunks_per_worker), **kwargs)
