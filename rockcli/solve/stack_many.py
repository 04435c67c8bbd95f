"""Bodies on plinths in a batch: :func:`simulate_stacks`, the :class:`rockcli.models.Stack` jobs of
:func:`rockcli.solve.simulate_many` (which hands them here), one :func:`rockcli.solve.simulate_stack` run each,
read back as a :class:`StackRun` that answers to the names of a :class:`rockcli.solve.Response` (the margin
search, the assessment table and the fragility read those).

The runs go on the process's pool of threads, as the single block's batches do (:func:`rockcli.solve.pool.run_tasks`,
the results in job order): both stack drivers are compiled ``nogil``, and each run is independent (its
own arrays in, its own out), so a run on a thread gives the bits it gives in a plain loop; the results are put
back in job order. Measured in docs/plinth.md.

Foundations: :func:`plinth_foundation_supported` says which ones a stack runs on: the rigid foundation, linear
bearings and sliding and lead-rubber bearings, on a base of finite mass (passed to
:func:`rockcli.solve.simulate_stack` as ``isolation=``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from rockcli.errors import RockcliInputError
from rockcli.models import HYSTERETIC, LinearIsolation, Rigid, Stack
from rockcli.solve.response import JobError

#: Why a stack on another foundation is refused (one sentence, the option to give named by the caller).
PLINTH_RIGID_ONLY = ("a body on a free plinth is modelled on a rigid foundation and on bearings under a base of "
                     "finite mass: an infinitely heavy base (gamma = 0) under a plinth is not modelled")


def plinth_foundation_supported(foundation) -> bool:
    """A body on a plinth can run on ``foundation``: the rigid foundation, and linear, sliding or lead-rubber
    bearings with ``gamma > 0``."""
    if foundation is None or isinstance(foundation, Rigid):
        return True
    return isinstance(foundation, (LinearIsolation, *HYSTERETIC)) and foundation.gamma > 0


@dataclass(frozen=True)
class StackRun:
    """One stack run as the batch callers read a :class:`rockcli.solve.Response`: the verdict (either block
    toppling overturns the scene), ``theta_max_over_alpha`` the body's peak on its plinth over its own
    slenderness, the body's uplift and impacts; ``stack`` the whole :class:`rockcli.solve.StackResponse`."""

    stack: Any
    base_disp_max_m: float = 0.0
    error: str = ""
    peak_final: bool = True  # the stack driver has no early stop during the excitation

    @property
    def verdict(self) -> str:
        return self.stack.verdict

    @property
    def overturned(self) -> bool:
        return self.stack.toppled is not None

    @property
    def settled(self) -> bool:
        return self.stack.settled

    @property
    def status(self) -> int:
        return self.stack.status

    @property
    def message(self) -> str:
        return self.stack.message

    @property
    def theta_max_over_alpha(self) -> float:
        return self.stack.body.theta_max_over_alpha

    @property
    def t_overturn_s(self) -> float:
        return self.stack.t_overturn_s

    @property
    def t_uplift_s(self) -> float:
        """The first uplift of either block [s] (NaN when nothing lifts)."""
        times = [t for t in (self.stack.body.t_uplift_s, self.stack.plinth.t_uplift_s) if not math.isnan(t)]
        return min(times) if times else math.nan

    @property
    def n_impacts(self) -> int:
        return self.stack.body.n_impacts

    @property
    def steps(self) -> int:
        return self.stack.steps

    @property
    def nfev(self) -> int:
        return self.stack.n_rhs


def run_stack(stack: Stack, foundation, motion, scale: float = 1.0, **solver):
    """One :func:`rockcli.solve.simulate_stack` run of ``stack`` on ``foundation`` under ``scale`` times ``motion``
    (a record, or a pulse: its ``a_p``); ``solver`` its keywords. Raises :class:`RockcliInputError` for a scene the
    model does not cover (a foundation it does not support, a capped colonnade)."""
    from rockcli.solve.stack import simulate_stack

    if not plinth_foundation_supported(foundation):
        raise RockcliInputError(PLINTH_RIGID_ONLY)
    if solver.pop("cap_ratio", 0.0):
        raise RockcliInputError("a body on a free plinth stands alone: a capped colonnade (cap_ratio) is not "
                                "modelled with a plinth")
    if solver.get("vertical") is not None:
        raise RockcliInputError("a body on a plinth runs under the horizontal ground motion only: no vertical motion")
    solver.pop("vertical", None)
    if foundation is not None and not isinstance(foundation, Rigid):
        solver["isolation"] = foundation
    if scale != 1.0:
        motion = motion.scaled(scale)
    return simulate_stack(stack, motion, **solver)


def simulate_stacks(jobs, *, early: bool = False, progress=None, done: int = 0, **solver) -> list:
    """The ``(stack, foundation, motion[, scale])`` jobs on a pool of threads (module notes): a :class:`StackRun`
    each, in job order, or a :class:`rockcli.solve.JobError` for a scene refused (the others still run).
    ``early`` is not taken (the stack driver makes the same steps either way); ``progress(n_done)`` after each run,
    counting from ``done`` (called from this thread, n_done rising by one each time). ``solver``:
    :func:`rockcli.solve.simulate_stack`'s keywords, and ``cap_ratio``/``vertical`` (refused when given)."""
    from rockcli.solve.options import _kernel
    from rockcli.solve.pool import run_tasks

    _kernel()  # the kernels imported here, not first on a worker thread

    jobs = list(jobs)

    def one(job):
        stack, foundation, motion = job[:3]
        scale = float(job[3]) if len(job) > 3 else 1.0
        try:
            res = run_stack(stack, foundation, motion, scale, **solver)
        except RockcliInputError as exc:
            return JobError(str(exc))
        disp = 0.0 if math.isnan(res.base_disp_max) else res.base_disp_max  # 0 on a rigid foundation, as a
        # single block's Response
        return StackRun(res, base_disp_max_m=disp)

    count = [done]

    def finished(_):
        count[0] += 1
        if progress is not None:
            progress(count[0])

    # the process's pool (rockcli.solve.pool): the stack drivers run without the GIL
    return run_tasks([lambda job=job: one(job) for job in jobs], done=finished)


def is_stack_job(job) -> bool:
    return isinstance(job, (tuple, list)) and len(job) >= 3 and isinstance(job[0], Stack)


def mixed(jobs, single, *, progress=None, **options) -> list:
    """:func:`rockcli.solve.simulate_many` over jobs some of which are stacks: the single blocks through
    ``single`` (the batch path, all cores), then the stacks (:func:`simulate_stacks`, all cores); results in job
    order."""
    jobs = list(jobs)
    flat = [i for i, j in enumerate(jobs) if not is_stack_job(j)]
    stacked = [i for i, j in enumerate(jobs) if is_stack_job(j)]
    out = [None] * len(jobs)
    if flat:
        res = single([jobs[i] for i in flat], progress=progress, **options)
        for i, r in zip(flat, res):
            out[i] = r
    keep = {k: options[k] for k in ("rtol", "tail", "rest_tol", "horizon", "max_steps") if k in options}
    for key in ("restitution", "cap_ratio", "vertical"):
        value = options.get(key)
        if value is not None and not isinstance(value, (int, float)):
            raise RockcliInputError(f"{key}: a body on a plinth takes one value for every job")
        keep[key] = value
    if not isinstance(keep.get("tail", 0.0), (int, float)):
        raise RockcliInputError("tail: a body on a plinth takes one value for every job")
    if keep.get("vertical") is None:
        keep.pop("vertical")
    res = simulate_stacks([jobs[i] for i in stacked], progress=progress, done=len(flat), **keep)
    for i, r in zip(stacked, res):
        out[i] = r
    return out


__all__ = ["PLINTH_RIGID_ONLY", "StackRun", "is_stack_job", "mixed", "plinth_foundation_supported", "run_stack",
           "simulate_stacks"]
