"""Many verdict-only scenes in parallel: :func:`simulate_many` (a :class:`Response` or :class:`JobError`
per job) and :func:`simulate_verdicts` (arrays), both on :func:`_run_many`, which validates each distinct
scene once, packs the scenes' arrays and runs chunks of them on the process's pool of threads
(:mod:`rockcli.solve.pool`; the batch kernels release the GIL).
"""

from __future__ import annotations

import functools
import math
import threading

import numpy as np

from rockcli.models.colonnade import check_cap_ratio
from rockcli.errors import RockcliInputError
from rockcli.models.impact import check_restitution
from rockcli.models import Block, Rigid
from rockcli.solve.excitation import _excitation_arrays_cached, _vertical_arrays, attached_vertical
from rockcli.solve.options import (DEFAULT_HORIZON, DEFAULT_MAX_STEPS, DEFAULT_REST_TOL, DEFAULT_TAIL, TAIL_MAX,
                                   _kernel, check_foundation, validate_options)
from rockcli.solve.parameters import _parameters
from rockcli.solve.pool import _threads, run_tasks
from rockcli.solve.response import JobError, Verdicts, _response
from rockcli.solve.work import _check_work


def simulate_many(jobs, *, rtol: float | None = None, tail=DEFAULT_TAIL,
                  rest_tol: float = DEFAULT_REST_TOL, horizon: float = DEFAULT_HORIZON,
                  max_steps: int = DEFAULT_MAX_STEPS, early: bool = False,
                  progress=None, chunk: int | None = None, restitution=None, cap_ratio=0.0, vertical=None) -> list:
    """Verdict-only :func:`simulate` of many scenes, run in parallel on all cores.

    Parameters
    ----------
    jobs : sequence of (block, foundation, excitation) or (block, foundation, excitation, scale)
        ``scale`` multiplies a record's acceleration or a pulse's ``a_p`` (default 1): the same run
        as the scaled excitation. Scenes that share a record object share its samples.
    tail : float or sequence of float
        Free motion a history run would show [s] (one value or one per scene); it never changes a
        verdict-only run, which ends when its verdict is proven.
    early : bool
        Stop each run as soon as its verdict is proven, even during the excitation (the
        verdicts are the same; ``theta_max`` is then only the peak so far, ``peak_final`` False).
    progress : callable, optional
        Called as ``progress(n_done)`` after each chunk of scenes.
    chunk : int, optional
        Scenes per batch handed to a thread (default: about 1/8 of a thread's share, and at most
        1/50 of all scenes with ``progress``).
    restitution : float, None or sequence of them
        Coefficient of restitution of :func:`simulate` (one value or one per scene; None: Housner's).
    cap_ratio : float or sequence of float
        Capped colonnade of :func:`simulate` (one value or one per scene; 0: solitary columns).
    vertical : Record, pulse, None or a sequence of them, optional
        Vertical ground motion of :func:`simulate` (one for every scene, or one per scene; None:
        the one the scene's record carries, if any, :func:`rockcli.solve.with_vertical`). Never
        scaled: ``scale`` multiplies the horizontal motion only. Rigid foundation only (a scene on an
        isolated base gets a :class:`JobError`); these scenes run in the same batch machinery, on the
        rigid driver's vertical entry.

    A job whose block is a :class:`rockcli.models.Stack` (a body on a free plinth) runs on the stack driver
    (:mod:`rockcli.solve.stack_many`, on a pool of threads) and returns a ``StackRun``, which reads like a
    :class:`Response` (the body's peak on its plinth; either block toppling overturns the scene). A job whose block
    is a :class:`rockcli.solve.slide_many.Sliding` (a body with friction) runs on the friction driver and returns a
    ``SlideRun`` (the rocking model's own run where nothing slid: :mod:`rockcli.solve.slide_many`).

    Returns
    -------
    list of Response or JobError
        In the order of ``jobs``, identical to what :func:`simulate` returns without history; a
        job that :func:`simulate` would refuse (bad block, foundation or excitation) gets a
        :class:`JobError` with the reason and the others still run. Invalid solver options
        (``rtol``, ``tail``, ``rest_tol``, ``horizon``) concern every job and raise.
    """
    jobs = as_jobs(jobs)
    if jobs:  # a body with friction (a Sliding job) runs on the friction driver, or where nothing slides as without
        from rockcli.solve.slide_many import is_slide_job, mixed_slides

        if any(is_slide_job(j) for j in jobs):
            return mixed_slides(jobs, simulate_many, rtol=rtol, tail=tail, rest_tol=rest_tol, horizon=horizon,
                                max_steps=max_steps, early=early, progress=progress, chunk=chunk,
                                restitution=restitution, cap_ratio=cap_ratio, vertical=vertical)
    if jobs:  # a body on a plinth (a Stack job) runs on the stack driver
        from rockcli.solve.stack_many import is_stack_job, mixed

        if any(is_stack_job(j) for j in jobs):
            return mixed(jobs, simulate_many, rtol=rtol, tail=tail, rest_tol=rest_tol, horizon=horizon,
                         max_steps=max_steps, early=early, progress=progress, chunk=chunk, restitution=restitution,
                         cap_ratio=cap_ratio, vertical=vertical)
    outs, alphas, failed = _run_many(jobs, rtol=rtol, tail=tail, rest_tol=rest_tol, horizon=horizon,
                                     max_steps=max_steps, early=early, progress=progress, chunk=chunk,
                                     restitution=restitution, cap_ratio=cap_ratio, vertical=vertical)
    done = iter(range(outs.shape[0]))
    return [failed[i] if i in failed else _response(outs[next(done)], None, alphas[i]) for i in range(len(alphas))]


def simulate_verdicts(jobs, *, rtol: float | None = None, tail=DEFAULT_TAIL, rest_tol: float = DEFAULT_REST_TOL,
                      horizon: float = DEFAULT_HORIZON, max_steps: int = DEFAULT_MAX_STEPS, early: bool = False,
                      progress=None, chunk: int | None = None, restitution=None, cap_ratio=0.0,
                      vertical=None) -> Verdicts:
    """:func:`simulate_many` returning arrays (no :class:`Response` per scene): for large sweeps.

    Same arguments and the same runs; a job that fails validation raises here.
    """
    k = _kernel()
    outs, alphas, failed = _run_many(jobs, rtol=rtol, tail=tail, rest_tol=rest_tol, horizon=horizon,
                                     max_steps=max_steps, early=early, progress=progress, chunk=chunk,
                                     restitution=restitution, cap_ratio=cap_ratio, vertical=vertical)
    if failed:
        i = min(failed)
        raise RockcliInputError(f"job {i}: {failed[i].error}")
    return Verdicts(
        overturned=outs[:, k.O_STATUS] == k.STATUS_OVERTURNED, uplifted=outs[:, k.O_UPLIFTED] != 0.0,
        theta_max_over_alpha=outs[:, k.O_THETA_MAX] / np.asarray(alphas, dtype=float).reshape(-1),
        settled=outs[:, k.O_SETTLED] != 0.0, status=outs[:, k.O_STATUS].astype(np.int64),
        nfev=outs[:, k.O_NRHS].astype(np.int64), peak_final=outs[:, k.O_PEAK_FINAL] != 0.0)


#: What ``jobs`` must be, for the sentence that refuses anything else.
JOBS_EXPECTED = "a list of (block, foundation, excitation[, scale]) tuples"


def as_jobs(jobs) -> list:
    """``jobs`` as a list of jobs, else one sentence: a list, a tuple or another sequence of jobs; one job not
    wrapped in a list (``(block, foundation, pulse)``: its items would be three jobs, each an error row) is refused
    as such. A job that fails its own checks is not refused here: it comes back as a :class:`JobError` row."""
    from rockcli.io.inputs import as_list, type_words
    from rockcli.models import Stack

    from rockcli.solve.slide_many import Sliding

    items = as_list(jobs, "jobs", JOBS_EXPECTED)
    if items and isinstance(items[0], (Block, Stack, Sliding)):
        raise RockcliInputError(f"jobs must be {JOBS_EXPECTED}, got one job's items ({type_words(items[0])}, ...): "
                                f"give the job in a list, [(block, foundation, excitation)]")
    return items


#: The work estimates that passed in this process, by everything :func:`_check_work` reads: the block and the
#: foundation (frozen dataclasses: equal fields, equal estimate), the excitation's kind, samples, active length and
#: end, the tail, the restitution and the solver options. :func:`_check_work` is a function of exactly these, so a
#: key found here would pass again. (Cleared when it holds 4096 keys.)
_WORK_PASSED: set = set()
_PREPARE_LOCK = threading.Lock()


def _scene_arrays(block, foundation, excitation, tail, rtol, rest_tol, horizon, max_steps, prepared, params,
                  checked, restitution=None, cap_ratio=0.0):
    """The kernel inputs of one (block, foundation, excitation, tail) of a sweep, validated and its work
    checked: ``(fkind, prm, ekind, epar, acc, jtab, dt, t_begin, t_exc_end)`` (``epar`` a copy).

    ``prepared``, ``params`` and ``checked`` are the sweep's caches: an excitation's arrays by id, the
    parameters by (block, foundation) and the work estimates that passed.
    """
    k = _kernel()
    key = id(excitation)
    if key not in prepared:
        try:
            prepared[key] = _excitation_arrays_cached(excitation)
        except RockcliInputError as exc:
            prepared[key] = exc
    if isinstance(prepared[key], RockcliInputError):
        raise prepared[key]
    ekind, epar, acc, jtab, dt, t_begin, t_exc_end = prepared[key]
    try:
        cached = params.get((block, foundation, restitution, cap_ratio))
    except TypeError:  # an unhashable foundation: built for each scene
        cached = _parameters(block, foundation, rtol, float(rest_tol), restitution, cap_ratio)
    if cached is None:
        cached = params[(block, foundation, restitution, cap_ratio)] = _parameters(
            block, foundation, rtol, float(rest_tol), restitution, cap_ratio)
    fkind, prm = cached
    # the work estimate depends only on these (not on the amplitude): checked once per distinct set, and a set
    # that passed is remembered by the process (_WORK_PASSED)
    wkey = (block, foundation, ekind, acc.size, epar[k.E_TE] - epar[k.E_TS], t_exc_end, tail, restitution,
            rtol, float(rest_tol), float(horizon), int(max_steps))
    try:
        known = wkey in checked or wkey in _WORK_PASSED
    except TypeError:
        known = False
    if not known:
        _check_work(block, foundation, prepared[key], rtol, tail, float(rest_tol), float(horizon), int(max_steps),
                    restitution=restitution)
        try:
            checked.add(wkey)
            if len(_WORK_PASSED) >= 4096:
                _WORK_PASSED.clear()
            _WORK_PASSED.add(wkey)
        except TypeError:
            pass
    return fkind, prm, ekind, epar.copy(), acc, jtab, dt, t_begin, t_exc_end


def _per_job(value, n: int, check, what: str) -> list:
    """A solver option given as one value or one per job, checked, as a list of ``n`` values."""
    if value is None or np.ndim(value) == 0:
        return [check(value)] * n
    values = list(value)
    if len(values) != n:
        raise RockcliInputError(f"{what} must be one value or one per job ({n}), got {len(values)}")
    return [check(v) for v in values]


def _per_job_vertical(vertical, n: int) -> list:
    """The vertical motion of each of ``n`` jobs: one motion (or None) for all, or a list/tuple of one per job."""
    if not isinstance(vertical, (list, tuple)):
        return [vertical] * n
    if len(vertical) != n:
        raise RockcliInputError(f"vertical must be one motion or one per job ({n}), got {len(vertical)}")
    return list(vertical)


def _vertical_scene(vertical, excitation, foundation, g, vprepared):
    """A job's vertical series ``(vacc, vjtab, vdt, t_v_end)`` (:func:`_vertical_arrays`), cached by the ids of
    the motion and the horizontal excitation (the time-base check concerns both) and the kind of foundation."""
    key = (id(vertical), id(excitation), isinstance(foundation, Rigid))
    if key not in vprepared:
        try:
            vprepared[key] = _vertical_arrays(vertical, excitation, foundation, g)[:4]
        except RockcliInputError as exc:
            vprepared[key] = exc
    if isinstance(vprepared[key], RockcliInputError):
        raise vprepared[key]
    return vprepared[key]


def _run_many(jobs, *, rtol, tail, rest_tol, horizon, max_steps, early, progress, chunk, restitution=None,
              cap_ratio=0.0, vertical=None):
    """Kernel outputs (``O_*`` rows) of the valid jobs, each job's slenderness, and the failed jobs.

    Returns ``(outs, alphas, failed)``: ``outs`` has one row per valid job in job order,
    ``alphas`` one entry per job (NaN for a failed one), ``failed`` maps job index -> JobError.
    """
    jobs = as_jobs(jobs)
    tails_in = np.asarray(tail, dtype=float)
    if tails_in.ndim == 0:
        validate_options(rtol, float(tails_in), rest_tol, horizon, max_steps)
    else:
        if tails_in.shape != (len(jobs),):
            raise RockcliInputError(f"tail must be one value or one per job ({len(jobs)}), got {tails_in.shape}")
        if not np.all(np.isfinite(tails_in) & (tails_in >= 0) & (tails_in <= TAIL_MAX)):
            raise RockcliInputError(f"tail must be a time between 0 and {TAIL_MAX:g} s for every job")
        validate_options(rtol, 0.0, rest_tol, horizon, max_steps)
    restitutions = _per_job(restitution, len(jobs), check_restitution, "restitution")
    caps = _per_job(cap_ratio, len(jobs), check_cap_ratio, "cap_ratio")
    verticals = _per_job_vertical(vertical, len(jobs))
    k = _kernel()
    n = len(jobs)
    if n == 0:
        return np.zeros((0, k.N_OUT)), [], {}
    pieces, jpieces, where, total = [], [], {}, 0
    vpieces, vjpieces, vwhere, vtotal = [], [], {}, 0  # the vertical series, laid out alike
    vprepared = {}  # (id(vertical), id(excitation), rigid) -> its series (or the error)
    prepared = {}  # id(excitation) -> validated kernel arrays (or the error): a shared record is checked once
    params = {}  # (block, foundation) -> kernel parameters: built once per distinct pair
    checked = set()  # work estimates that passed (see _check_work)
    groups = {}  # (id(block), id(foundation), id(excitation), tail) -> index into G, or the error
    G = []  # per distinct scene: (fkind, prm, ekind, epar, offset, length, dt, t_begin, t_exc_end, alpha,
    #        vertical offset, vertical length, vertical dt)
    failed = {}  # job index -> JobError; those jobs are not run
    gidx = np.full(n, -1, np.int64)
    scales = np.ones(n)
    ground = Rigid()
    for i, job in enumerate(jobs):
        try:
            if not isinstance(job, (tuple, list)) or not 3 <= len(job) <= 4:
                from rockcli.io.inputs import type_words

                raise RockcliInputError(f"job {i} must be a tuple (block, foundation, excitation[, scale]), got "
                                        f"{type_words(job)}")
            block, foundation, excitation = job[:3]
            scale = float(job[3]) if len(job) > 3 else 1.0
            if not isinstance(block, Block):
                raise RockcliInputError(f"job {i}: block must be a rockcli.models.Block")
            foundation = foundation if foundation is not None else ground
            check_foundation(foundation, f"job {i}: the foundation")
            if not math.isfinite(scale):
                raise RockcliInputError(f"job {i}: the scale factor must be finite, got {scale!r}")
            tail_i = float(tails_in if tails_in.ndim == 0 else tails_in[i])
            vertical_i = verticals[i] if verticals[i] is not None else attached_vertical(excitation)
            # the jobs hold these objects, so their ids stay theirs for the whole loop
            gkey = (id(block), id(foundation), id(excitation), tail_i, restitutions[i], caps[i], id(vertical_i))
            g = groups.get(gkey)
            if g is None:
                try:
                    fkind, prm, ekind, epar, acc, jtab, dt, t_begin, t_exc_end = _scene_arrays(
                        block, foundation, excitation, tail_i, rtol, rest_tol, horizon, max_steps, prepared, params,
                        checked, restitutions[i], caps[i])
                    vacc, vjtab, vdt, t_v_end = _vertical_scene(vertical_i, excitation, foundation,
                                                                float(prm[k.P_G]), vprepared)
                except (RockcliInputError, TypeError, ValueError) as exc:
                    g = RockcliInputError(str(exc))
                else:
                    akey = id(acc)  # a record's samples, or the table shared by all pulses of one shape
                    if akey not in where:
                        where[akey] = total
                        pieces.append(acc)
                        jpieces.append(jtab)
                        total += acc.size
                    vkey = id(vacc)
                    if vacc.size and vkey not in vwhere:
                        vwhere[vkey] = vtotal
                        vpieces.append(vacc)
                        vjpieces.append(vjtab)
                        vtotal += vacc.size
                    g = len(G)
                    # the excitation ends when both motions have (as in simulate)
                    G.append((fkind, prm, ekind, epar, where[akey], acc.size, dt, t_begin, max(t_exc_end, t_v_end),
                              block.alpha, vwhere.get(vkey, 0), vacc.size, vdt))
                groups[gkey] = g
            if isinstance(g, RockcliInputError):
                raise g
        except (RockcliInputError, TypeError, ValueError) as exc:
            failed[i] = JobError(str(exc))
            continue
        gidx[i] = g
        scales[i] = scale
    if not G:  # every job failed
        if progress is not None:
            progress(n)
        return np.zeros((0, k.N_OUT)), [math.nan] * n, failed
    ok = np.flatnonzero(gidx >= 0)
    sel = gidx[ok]
    cols = list(zip(*G))

    def per_job(j, dtype=float):  # column j of G, one row per job that runs
        return np.array(cols[j], dtype=dtype)[sel]

    fkinds, prms, ekinds, epars = per_job(0, np.int64), per_job(1), per_job(2, np.int64), per_job(3)
    acc_off, acc_len = per_job(4, np.int64), per_job(5, np.int64)
    dts, t_begins, t_exc_ends = per_job(6), per_job(7), per_job(8)
    v_off, v_len, vdts = per_job(10, np.int64), per_job(11, np.int64), per_job(12)
    alphas = np.full(n, math.nan)
    alphas[ok] = per_job(9)
    alphas = alphas.tolist()
    record = ekinds == k.EXC_RECORD
    scale_ok = scales[ok]
    epars[record, k.E_AP] = scale_ok[record]  # a record: E_AP carries the scale factor
    epars[~record, k.E_AP] *= scale_ok[~record]  # a pulse: the kernel reads its amplitude from E_AP
    tails = np.full(ok.size, float(tails_in)) if tails_in.ndim == 0 else tails_in[ok].copy()
    m = fkinds.size
    acc_all = np.concatenate(pieces) if pieces else np.zeros(2)
    jtab_all = np.concatenate(jpieces) if jpieces else np.zeros(2)
    outs = np.zeros((m, k.N_OUT))
    threads = _threads()
    if chunk is None:  # pieces small enough to balance the threads, and to report progress ~50 times
        chunk = max(1, -(-m // (8 * threads)))
        if progress is not None:
            chunk = min(chunk, max(1, m // 50))
    tasks = []
    # one batch kernel per driver (rigid foundation, isolated base) and one for the rigid foundation under a
    # vertical motion: a sweep compiles only what it uses
    rigid = fkinds == k.FOUNDATION_RIGID
    shaken = v_len > 0  # (only on a rigid foundation: _vertical_arrays refuses the others)
    drivers = [(k.simulate_batch_rigid, np.flatnonzero(rigid & ~shaken)), (k.simulate_batch, np.flatnonzero(~rigid)),
               (k.simulate_batch_rigid_vertical, np.flatnonzero(shaken))]
    # loaded, or compiled (side by side on the first run on a machine) before any scene runs; the vertical
    # motion's kernel (rarely needed) compiles on its first call
    with _PREPARE_LOCK:  # one thread at a time (the margin search's lanes): the others then find them ready
        k.prepare([batch.__name__ for batch, sel in drivers if sel.size and batch.__name__ in k.BATCH_KERNELS])
    for batch, sel in drivers:
        whole = sel.size == m  # every job runs on this driver: pass views, the kernel writes into outs
        for lo in range(0, sel.size, chunk):
            hi = min(sel.size, lo + chunk)
            tasks.append((batch, slice(lo, hi) if whole else sel[lo:hi]))
    common = (acc_all, jtab_all)
    tail_args = (float(horizon), int(max_steps), bool(early))
    vacc_all = np.concatenate(vpieces) if vpieces else np.zeros(2)
    vjtab_all = np.concatenate(vjpieces) if vjpieces else np.zeros(2)

    def run(task):
        batch, part = task
        o = outs[part] if isinstance(part, slice) else np.zeros((part.size, k.N_OUT))
        vert = ((vacc_all, vjtab_all, v_off[part], v_len[part], vdts[part])
                if batch is k.simulate_batch_rigid_vertical else ())
        batch(fkinds[part], prms[part], ekinds[part], epars[part], *common, acc_off[part], acc_len[part],
              dts[part], t_begins[part], t_exc_ends[part], tails[part], *tail_args, *vert, o)
        if not isinstance(part, slice):
            outs[part] = o
        return o.shape[0]

    done = [0]

    def advance(count):
        done[0] += count
        if progress is not None:
            progress(n if done[0] == m else done[0])

    # the kernels run without the GIL, on the process's pool (one pool for every call: rockcli.solve.pool)
    run_tasks([functools.partial(run, task) for task in tasks], done=advance, threads=threads)
    return outs, alphas, failed
