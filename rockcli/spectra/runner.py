"""Running cells: :class:`Cells` (the outcome arrays) and the :class:`Runner` (here or on Dask).

A cell is one run of a :class:`~rockcli.spectra.scenes.Family` at ``(x, y)``. Runs go through
:func:`rockcli.solve.simulate_verdicts`, all columns in one batch; ``early=True`` stops each run as
soon as its verdict is proven (the same verdicts; the peak then only a lower bound for runs stopped
during the pulse, ``peak_final`` False). The cells of a family on a plinth (``--on``) are runs of the stack
driver (:func:`rockcli.solve.stack_many.simulate_stacks`), whatever ``early`` says: its verdict is exactly the
stack driver's at that point and its peak final (the driver has no early stop during the excitation).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Optional, Sequence

import numpy as np

from rockcli.spectra.scenes import Family


@dataclass(frozen=True)
class Cells:
    """Outcome of cells: arrays in the order of the cells asked for."""

    overturned: np.ndarray
    uplifted: np.ndarray
    theta_max_over_alpha: np.ndarray
    settled: np.ndarray
    peak_final: np.ndarray
    nfev: np.ndarray
    #: which block toppled where a cell is a body on a plinth: 0 none (or a single block), 1 the body, 2 the plinth
    #: (None: no cell of the batch has a plinth)
    toppled: Optional[np.ndarray] = None

    @staticmethod
    def concatenate(parts: Sequence["Cells"]) -> "Cells":
        if not parts:
            return Cells(*(np.zeros(0, dt) for dt in (bool, bool, float, bool, bool, np.int64)))
        out = [np.concatenate([getattr(p, f) for p in parts])
               for f in ("overturned", "uplifted", "theta_max_over_alpha", "settled", "peak_final", "nfev")]
        if any(p.toppled is not None for p in parts):
            out.append(np.concatenate([p.toppled if p.toppled is not None else np.zeros(p.nfev.size, np.int8)
                                       for p in parts]))
        return Cells(*out)


#: :attr:`Cells.toppled` codes of a stack run's ``toppled``.
TOPPLED_CODES = {None: 0, "body": 1, "plinth": 2}
#: The step cap of a stack run asked only whether something lifts (``uplift_only``): far above the few hundred to
#: few thousand steps of a run near an uplift threshold, far below the 5 million of a verdict run.
UPLIFT_ONLY_STEPS = 20_000


def _run_stacks(jobs, horizon, restitution, progress, uplift_only: bool = False) -> Cells:
    """The cells that are bodies on plinths, one :func:`rockcli.solve.stack_many.simulate_stacks` run each: the
    stack driver's own verdict (it has no early stop during the excitation, so every peak is final), its uplift
    (either block lifted: the verdict is not ``no_uplift``), the body's peak over its own alpha (as ``simulate
    --on`` prints it) and which block toppled.

    ``uplift_only``: the caller reads only ``uplifted`` (the minimum search's uplift thresholds). The runs then
    stop at :data:`UPLIFT_ONLY_STEPS` steps. Exact for that flag: a lift is an event the driver records when it
    happens, so a run stopped after it has lifted, as the full run would have; a run stopped before any lift is run
    again in full. (Why: on linear bearings, a body that lifts by a hair just above its threshold can make the
    driver chatter until its 5-million-step cap, minutes per run: measured, issue noted in docs/spectra.md.) The
    other arrays of such a run are not a verdict, and the caller does not read them."""
    from rockcli.solve.stack_many import simulate_stacks
    from rockcli.solve.response import VERDICT_NO_UPLIFT

    if uplift_only:
        runs = simulate_stacks(jobs, horizon=horizon, restitution=restitution, max_steps=UPLIFT_ONLY_STEPS)
        again = [i for i, r in enumerate(runs) if hasattr(r, "stack") and r.status < 0 and r.verdict == VERDICT_NO_UPLIFT]
        for i, r in zip(again, simulate_stacks([jobs[i] for i in again], horizon=horizon, restitution=restitution)):
            runs[i] = r
        if progress is not None:
            progress(len(jobs))
    else:
        runs = simulate_stacks(jobs, horizon=horizon, restitution=restitution, progress=progress)
    bad = [r for r in runs if not hasattr(r, "stack")]
    if bad:  # a scene the model does not cover: the command refuses it before any run
        from rockcli.errors import RockcliInputError

        raise RockcliInputError(bad[0].error)
    for r in runs:
        if r.status < 0 and not (uplift_only and r.verdict != VERDICT_NO_UPLIFT):
            raise ArithmeticError(f"a body on a plinth stopped at the integrator's safety cap of {r.steps:,} steps: "
                                  f"no verdict (please report the command line)")
    return Cells(np.array([r.overturned for r in runs], bool),
                 np.array([r.verdict != VERDICT_NO_UPLIFT for r in runs], bool),
                 np.array([r.theta_max_over_alpha for r in runs], float), np.array([r.settled for r in runs], bool),
                 np.array([r.peak_final for r in runs], bool), np.array([r.nfev for r in runs], np.int64),
                 np.array([TOPPLED_CODES[r.stack.toppled] for r in runs], np.int8))


def run_cells_local(families: Sequence[Family], fam: np.ndarray, x: np.ndarray, y: np.ndarray,
                    progress: Optional[Callable[[int], None]] = None, early: bool = False,
                    horizon: float | None = None, restitution: float | None = None, cap_ratio: float = 0.0,
                    vertical=None, uplift_only: bool = False) -> Cells:
    """Run cells ``(families[fam[i]], x[i], y[i])`` with :func:`rockcli.solve.simulate_verdicts` (all cores).

    ``progress(n)`` is called with the number of cells finished since the last call; ``early``: stop
    each run once its verdict is proven (the same verdicts; peaks may be lower bounds); ``horizon``:
    the solver's horizon [s] (None: its default, 600 s); ``restitution``: the coefficient of
    restitution of every impact (None: Housner's); ``cap_ratio``: capped colonnades (0: solitary blocks);
    ``vertical``: a :class:`~rockcli.spectra.scenes.VerticalChoice` under every cell (None: none);
    ``uplift_only``: only ``uplifted`` is read (the cells on a plinth may then stop once they lift: :func:`_run_stacks`;
    the single blocks run as ever).
    """
    from rockcli.solve import DEFAULT_HORIZON, simulate_verdicts
    from rockcli.solve.stack_many import is_stack_job

    n = len(x)
    if n == 0:
        return Cells.concatenate([])
    jobs = []
    columns = {}  # (family, x) -> the scene at y = 1 (a_p = g tan alpha), built once per column
    verticals = {}  # (family, x) -> its vertical pulse (one object per column: its series is built once)
    for i in range(n):
        key = (int(fam[i]), float(x[i]))
        col = columns.get(key)
        if col is None:
            col = columns[key] = families[key[0]].scene(key[1], 1.0)
            if vertical is not None:
                verticals[key] = vertical.pulse(col[2])
        # the kernel scales the unit pulse's a_p by y: the same run as Family.scene(x, y)
        jobs.append((col[0], col[1], col[2], float(y[i])))
    vjobs = None if vertical is None else [verticals[(int(fam[i]), float(x[i]))] for i in range(n)]
    done = [0]

    def step(k):
        progress(k - done[0])
        done[0] = k

    # The scenes run in contiguous pieces, one thread each, and a map's cost grows with a_p (rows):
    # run the cells in a fixed shuffled order so that every piece carries a fair share, and put the
    # results back. Cells are independent: the order changes no result.
    order = np.random.default_rng(0).permutation(n)
    stacked = np.array([is_stack_job(jobs[i]) for i in range(n)], bool)
    if stacked.any():
        # bodies on plinths (the stack driver) and single blocks (the batch) apart, put back in cell order
        if cap_ratio or vertical is not None:
            from rockcli.errors import RockcliInputError

            raise RockcliInputError("a body on a plinth stands alone under the horizontal ground motion: no capped "
                                    "colonnade (cap_ratio) or vertical pulse with a plinth")
        out = {f: np.empty(n, dt) for f, dt in (("overturned", bool), ("uplifted", bool), ("theta_max_over_alpha",
                                                float), ("settled", bool), ("peak_final", bool), ("nfev", np.int64))}
        toppled = np.zeros(n, np.int8)
        flat = order[~stacked[order]]
        on = order[stacked[order]]
        if flat.size:
            v = simulate_verdicts([jobs[i] for i in flat], early=early, progress=step if progress else None,
                                  horizon=DEFAULT_HORIZON if horizon is None else horizon, restitution=restitution)
            for f in out:
                out[f][flat] = getattr(v, f)
        c = _run_stacks([jobs[i] for i in on], DEFAULT_HORIZON if horizon is None else horizon, restitution,
                        (lambda k: step(flat.size + k)) if progress else None, uplift_only)
        for f in out:
            out[f][on] = getattr(c, f)
        toppled[on] = c.toppled
        return Cells(**out, toppled=toppled)
    v = simulate_verdicts([jobs[i] for i in order], early=early, progress=step if progress else None,
                          horizon=DEFAULT_HORIZON if horizon is None else horizon, restitution=restitution,
                          cap_ratio=cap_ratio, vertical=None if vjobs is None else [vjobs[i] for i in order])
    back = np.empty(n, np.int64)
    back[order] = np.arange(n)
    return Cells(v.overturned[back], v.uplifted[back], v.theta_max_over_alpha[back], v.settled[back],
                 v.peak_final[back], v.nfev[back])


def _run_cells_task(args) -> Cells:
    """One chunk on a Dask worker (module-level so that it pickles by reference)."""
    families, fam, x, y, early, horizon, restitution, cap_ratio, vertical, *uplift_only = args
    return run_cells_local(families, fam, x, y, early=early, horizon=horizon, restitution=restitution,
                           cap_ratio=cap_ratio, vertical=vertical, uplift_only=bool(uplift_only and uplift_only[0]))


class Runner:
    """Runs batches of cells here (``scheduler=None``) or in chunks on a Dask cluster.

    Parameters
    ----------
    scheduler : str or dask.distributed.Client, optional
        ``None`` (this machine, numba on all cores), ``"local"`` (a Dask LocalCluster),
        ``"tcp://HOST:PORT"`` (an existing scheduler; its workers need rockcli installed), or a
        ``Client``.
    chunk : int
        Cells per Dask task.
    horizon : float, optional
        The solver's horizon [s] for every run (None: its default, 600 s).
    restitution : float, optional
        The coefficient of restitution of every impact (None: Housner's; :mod:`rockcli.models.impact`).
    cap_ratio : float
        Capped colonnades of the blocks, on any foundation (:mod:`rockcli.models.colonnade`; 0: none).
    vertical : VerticalChoice, optional
        A vertical pulse under every cell, rigid foundation only (:class:`rockcli.spectra.VerticalChoice`).
    """

    def __init__(self, scheduler=None, *, chunk: int = 2000, horizon: float | None = None,
                 restitution: float | None = None, cap_ratio: float = 0.0, vertical=None):
        self.scheduler = scheduler
        self.chunk = int(chunk)
        self.horizon = horizon
        self.restitution = restitution
        self.cap_ratio = cap_ratio
        self.vertical = vertical
        self._client = None
        self._close = None
        self.cells_run = 0
        self.nfev = 0
        self.unproven = 0  # runs that reached the solver's horizon with the verdict unproven

    def __enter__(self):
        if self.scheduler is not None:
            from rockcli.distributed import open_client

            self._close = open_client(self.scheduler)
            self._client = self._close.__enter__()
        return self

    def __exit__(self, *exc):
        if self._close is not None:
            self._close.__exit__(*exc)
            self._close = self._client = None
        return False

    def __call__(self, families, fam, x, y, progress=None, early: bool = False, uplift_only: bool = False) -> Cells:
        fam = np.asarray(fam, dtype=np.int64)
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        if self.scheduler is None:
            out = run_cells_local(families, fam, x, y, progress, early, self.horizon, self.restitution,
                                  self.cap_ratio, self.vertical, uplift_only)
        else:
            if self._client is None:
                raise RuntimeError("use the Runner as a context manager to run on a scheduler")
            from rockcli.distributed import map_chunks

            n = len(x)
            bounds = [(lo, min(n, lo + self.chunk)) for lo in range(0, n, self.chunk)]
            tasks = [(tuple(families), fam[lo:hi], x[lo:hi], y[lo:hi], early, self.horizon, self.restitution,
                      self.cap_ratio, self.vertical, uplift_only) for lo, hi in bounds]
            sizes = [hi - lo for lo, hi in bounds]
            parts = map_chunks(self._client, _run_cells_task, tasks,
                               progress=(lambda i: progress(sizes[i])) if progress else None)
            out = Cells.concatenate(parts)
        self.cells_run += len(x)
        self.nfev += int(out.nfev.sum())
        counted = ~out.settled & ~out.overturned
        if uplift_only:  # an uplift-only run of a stack is no verdict (_run_stacks): not counted
            counted &= np.array([getattr(families[f], "plinth", None) is None for f in fam], bool)
        self.unproven += int(np.count_nonzero(counted))
        return out
