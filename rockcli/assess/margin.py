"""Margin search: the smallest scale factor of a record that overturns a column (``overturn_scale``).

Overturning is not monotone in the amplitude of the excitation (there are safe islands above the
smallest overturning amplitude), so a bisection alone could step over a lower overturning scale.
The result of :func:`find_overturn_scales` is therefore defined by a scan:

1. of the factors of :data:`MARGIN_GRID` (373 log-spaced values from 0.1 to 4, a ratio just
   under 1.01 between neighbours; 1 is one of them and can reuse a run already made), taking the
   *first* (smallest) factor that overturns;
2. then a geometric bisection between that factor and the grid factor below it (which survives),
   all scenes together at each iteration, until the two ends are within :data:`MARGIN_RTOL` (1 %).
   It takes at least one step, also with the 1 % grid, whose bracket is already that narrow: the
   reported ``overturn_scale`` is then often the midpoint of two grid factors.

Only the runs that cannot change that result are made: each scene's factors from its lift-off
floor upwards (:mod:`rockcli.assess.liftoff`: below it the block provably never leaves its base),
stopping at the first that overturns (see :func:`find_overturn_scales`, Notes).

``overturn_scale`` is the upper end (it overturns), ``overturn_scale_survives`` the lower end (it
survives). Why a 1 % grid (issue 28): under records the overturning boundary is ragged, and with the
earlier grid of 40 factors (ratio 1.1) the scan stepped over overturning windows 1-4 % wide below
the reported factor in 38 of the 80 scenes of ``assess column bassae nemea`` (by up to 14 %;
``benchmarks/bench_margin_windows.py``), on the unsafe side. The peaks of the surviving runs next
to those windows are often far from 1 (0.01-0.3: the block overturns from a jump of the response,
e.g. an uplift that happens or does not), so no cheaper criterion tells where to look more
closely. Windows narrower than 1 % can still be missed (the stated resolution of the margin);
nothing overturning up to 4x gives NaN and the note ``no overturning up to 4x``.

:func:`overturn_shares` is the neighbourhood check (share of 0.90x..1.10x that overturns), and
:func:`map_chunks` the seam for running the search on chunks of scenes elsewhere (one local
chunk by default; a distributed runner only has to map a function over a list).
"""

from __future__ import annotations

import functools
import math
from typing import Callable, NamedTuple, Sequence

import numpy as np


#: Scale factors scanned for the margin: 0.1 .. 1 (233 values) and 1 .. 4 (141 values), log-spaced with a
#: ratio just under 1 + MARGIN_RTOL (1.00997 and 1.00995).
MARGIN_GRID = np.unique(np.concatenate([np.geomspace(0.1, 1.0, 233), np.geomspace(1.0, 4.0, 141)]))
#: With ``fill``: the runs a round of the search should hold per thread; when fewer scenes are scanning, each runs
#: its next few factors at once (fewer rounds, each with work enough to keep the threads busy: in the README's
#: main job 114 rounds instead of 226, for 18 more runs; 4: 165 rounds, 6 more runs; 16: 73 rounds, 58 more).
FILL_JOBS_PER_THREAD = 8
#: The search's groups run in this many lanes (group id modulo LANES), each lane's rounds one after the other:
#: while the pool runs one lane's round, the next round of another is read and prepared (Notes). One lane when
#: the process may use one thread only (``NUMBA_NUM_THREADS=1``): no two runs at once.
LANES = 2
#: Relative width of the bracket at which the bisection stops.
MARGIN_RTOL = 0.01
#: The smallest bisection width used: below a few ulps the geometric midpoint equals an end of the
#: bracket and the bisection would never end, so a smaller ``rtol`` is raised to this floor.
RTOL_FLOOR = 8 * float(np.finfo(float).eps)

NOTE_NO_OVERTURN = "no overturning up to {:g}x"
NOTE_OVERTURNS_AT_MIN = "overturns already at {:g}x, the smallest factor scanned"
#: The runs of a search (those at or below the margin, as the unproven ones) whose contact law found no consistent
#: pattern at some event (``n_inconsistent > 0``: a column of drums under strong shaking): the margin rests on them.
NOTE_INCONSISTENT = "{} scaled run(s) with contact choices no pattern made consistent: not reliable"
#: A scene of a group left out of the search (``find_overturn_scales(groups=...)``): its margin is above
#: the group's smallest, which is at most this factor.
NOTE_ABOVE_GROUP = "searched up to {:g}x only: it does not overturn up to there, and another orientation does"


def _scaled_job(block, foundation, motion, scale: float):
    """A simulate_many job at ``scale`` times the motion (records scale in the kernel, pulses by a_p)."""
    if hasattr(motion, "acc"):
        return (block, foundation, motion, scale)
    return (block, foundation, motion if scale == 1.0 else motion.scaled(scale))


def find_overturn_scales(scenes, *, grid=MARGIN_GRID, rtol: float = MARGIN_RTOL, known=None,
                         progress: Callable[[int], None] | None = None, fill: bool = True, groups=None, **solver):
    """Smallest scale factor of the excitation that overturns each scene (see the module notes).

    Parameters
    ----------
    scenes : sequence of (block, foundation, motion)
        ``motion`` a Record or a pulse.
    grid : array
        Increasing scale factors scanned; 1 should be one of them.
    rtol : float
        The bisection stops when ``hi / lo - 1 <= rtol`` (raised to :data:`RTOL_FLOOR`, 8 ulps, when
        smaller); it always takes at least one step (Notes).
    known : sequence of Response or None, optional
        Responses at scale 1 when already computed.
    progress : callable, optional
        ``progress(n)`` with the number of (scene, grid factor) pairs just settled: run, or shown not
        to need a run (below the scene's lift-off floor, above its first overturning factor). Over the
        search they add up to ``len(scenes) * len(grid)``, less the factor 1 of each scene when
        ``known`` is given; the bisection is not counted.
    fill : bool
        When fewer scenes (groups) are still scanning than :data:`FILL_JOBS_PER_THREAD` times the threads,
        run the next few factors of each at once (that product over the scenes, rounded up), so that each
        round has work enough for every thread and the long scans take fewer rounds; the runs past a
        scene's first overturning factor are then wasted CPU (at most that many less one per scene; 18
        more runs than 3,386 in the README's main job), and change no result.
    groups : sequence, optional
        One hashable key per scene: the scenes of one key are scanned together, and only the group's
        smallest margin is searched (Notes, 3; the orientations of one column, pair and configuration,
        :mod:`rockcli.assess.azimuth`). None: each scene alone, every margin searched.
    **solver
        Passed to :func:`rockcli.solve.simulate_many`.

    Returns
    -------
    list of (overturn_scale, survives_scale, note)
        ``overturn_scale`` overturns, ``survives_scale`` (< it, within rtol) survives; NaN and a
        note when nothing up to ``grid[-1]`` overturns; ``(grid[0], NaN, note)`` when ``grid[0]``
        already overturns; ``(NaN, NaN, "error: ...")`` when the solver refused the scene. The note
        counts the runs at or below the margin (every run when nothing overturns; the bisection's
        runs included, the factor 1 of ``known`` not) that reached the solver's horizon unproven:
        runs of the full scan, which the search's path does not change; and likewise those whose contact
        law found no consistent pattern at some event (:data:`NOTE_INCONSISTENT`). With ``groups``, a scene left
        out (Notes, 3) gets ``(NaN, NaN, note)`` with :data:`NOTE_ABOVE_GROUP`.

    Notes
    -----
    The result is that of running every grid factor, taking the first (smallest) that overturns,
    then bisecting geometrically between it and the grid factor below it (which survives) until
    ``hi / lo - 1 <= rtol``. The bisection takes at least one step even when the grid's own bracket
    is already that narrow (the 1 % grid's ratio is 1.00997 and ``rtol`` 0.01): ``overturn_scale``
    is then often the geometric midpoint of two grid factors, and the outputs depend on that run.

    Only runs that cannot change this result are left out:

    1. Factors below the scene's lift-off floor (:func:`rockcli.assess.liftoff.liftoff_floors`: on a
       rigid base from the peak of the ground acceleration, on linear bearings from one exact linear
       run of the base at 1x; 0 otherwise): no such run lifts the block, so none overturns, and each
       is proven (settled) by the solver before its horizon.
    2. Factors above the first overturning one.
    3. With ``groups``: factors above the group's first overturning factor ``J`` (the smallest first
       overturning factor of its scenes). The scenes of a group run their factors in increasing order
       across the group (each round the scenes at the group's lowest pending factor, and with ``fill``
       the next few), so the scan stops at ``J`` having run every factor at or below it of every scene
       (from its floor). The scenes whose first overturning factor is ``J`` get their full result (the
       same runs, the same bisection, the same note); every other scene (not refused) survives every
       factor up to ``J``, so its margin, from the full scan, is above ``grid[J]`` and therefore above
       the group's smallest: its result says so (:data:`NOTE_ABOVE_GROUP`) instead. A scene refused
       by the solver is refused at every factor (the checks are of the block, the foundation and the
       excitation, not of the scale), so it has the full scan's ``error`` result as soon as it runs
       once. Why this is what ``--azimuth worst`` needs: :mod:`rockcli.assess.azimuth`.

    So each scene runs its factors upwards from its floor, one per round (with ``fill``, a few), and
    stops at the first that overturns; the factor 1 of ``known`` is not run again. The groups run in
    :data:`LANES` lanes (group id modulo LANES): a lane's round is one parallel batch of all its scanning
    groups, run on a caller thread (:func:`rockcli.solve.pool.in_background`) while this thread reads
    the other lane's last round and prepares its next, so the pool's threads always have work queued.
    Which round a run falls in changes nothing: a run depends on its scene and factor only, and each
    group's next factors only on its own runs (and ``fill`` only on how many groups are scanning,
    which decides how many runs past a first overturning factor are wasted, no result).
    """
    from rockcli.assess.liftoff import liftoff_floors
    from rockcli.assess.scenes import check_scale_search
    from rockcli.errors import RockcliInputError
    from rockcli.solve import VERDICT_ERROR, VERDICT_NO_UPLIFT, _threads, simulate_many
    from rockcli.solve.pool import in_background

    scenes = check_scale_search(scenes, grid, known, progress)  # the types, in one sentence
    if not (isinstance(rtol, (int, float)) and rtol >= 0 and math.isfinite(rtol)):
        raise RockcliInputError(f"margin bisection tolerance must be a finite number >= 0, got {rtol!r}")
    rtol = max(float(rtol), RTOL_FLOOR)
    grid = np.asarray(grid, dtype=float)
    n, m = len(scenes), grid.size
    # state[i, j]: 0 not run, 1 survives, 2 overturns, 3 survives without uplift, 4 refused
    state = np.zeros((n, m), dtype=np.int8)
    ones = np.flatnonzero(np.isclose(grid, 1.0))
    i1 = int(ones[0]) if ones.size else -1
    errors = {}
    unproven = np.zeros((n, m), dtype=bool)  # grid runs that reached the solver's horizon unproven
    unproven_bisection = np.zeros(n, dtype=np.int64)
    # runs whose contact law found no consistent pattern at some event (a column of drums: not reliable)
    inconsistent = np.zeros((n, m), dtype=bool)
    inconsistent_bisection = np.zeros(n, dtype=np.int64)

    def is_unproven(r):
        return r.verdict != VERDICT_ERROR and not r.overturned and not r.settled

    def code(r):
        if r.verdict == VERDICT_ERROR:
            return 4
        return 2 if r.overturned else (3 if r.verdict == VERDICT_NO_UPLIFT else 1)

    def start(pairs):  # a round of one lane: its runs prepared and run on a caller thread (Notes)
        pairs = _balanced(pairs, [_cost(scenes[i][2]) for i, _ in pairs])
        jobs = [_scaled_job(*scenes[i], float(grid[j])) for i, j in pairs]
        return pairs, in_background(simulate_many, jobs, early=True, **solver)  # verdicts only

    def collect(pairs, res):
        for (i, j), r in zip(pairs, res):
            unproven[i, j] = is_unproven(r)
            inconsistent[i, j] = getattr(r, "n_inconsistent", 0) > 0
            state[i, j] = code(r)
            if state[i, j] == 4:
                errors.setdefault(i, r.error)

    if known is not None and i1 >= 0:
        for i in range(n):
            state[i, i1] = code(known[i])
            if state[i, i1] == 4:
                errors[i] = known[i].error
    floors = liftoff_floors(scenes, **solver)
    pos = np.searchsorted(grid, floors, side="left")  # the first factor >= the floor: nothing below runs
    first = np.full(n, -1)  # first overturning factor, once found
    settled = [n if known is not None and i1 >= 0 else 0]  # pairs counted so far (factor 1 known)
    gid = _group_ids(groups, n)
    cap = np.full(int(gid.max()) + 1 if n else 0, m)  # per group: the smallest first overturning factor found

    def scanning(i):
        return first[i] < 0 and i not in errors and pos[i] < m and pos[i] <= cap[gid[i]]

    def next_round(active, per):  # the next round of these groups (group -> its scanning scenes): (scene, factor) pairs
        pairs = []
        for g, members in active.items():
            lowest = min(pos[i] for i in members)  # each scanning scene's next factor to run is its pos
            take = [(int(pos[i]), i) for i in members if pos[i] == lowest]
            if len(take) < per:  # fill: the next factors of the group, lowest first
                todo = []
                for i in members:
                    end = cap[g] + 1
                    over = np.flatnonzero(state[i, pos[i]:end] == 2)  # a known overturn ends the scene first
                    end = pos[i] + over[0] if over.size else end
                    todo += [(int(j), i) for j in (np.flatnonzero(state[i, pos[i]:end] == 0) + pos[i])[:per]]
                take = sorted(todo)[:per]
            pairs += [(i, j) for j, i in take]
        return pairs

    def advance():  # move each scene past the factors settled; progress: every pair that may no longer run
        for i in range(n):
            while scanning(i) and state[i, pos[i]] != 0:
                if state[i, pos[i]] == 2:
                    first[i] = pos[i]
                    cap[gid[i]] = min(cap[gid[i]], pos[i])
                else:
                    pos[i] += 1
        if progress is not None:
            left = sum(int(np.count_nonzero(state[i, pos[i]:cap[gid[i]] + 1] == 0)) for i in range(n) if scanning(i))
            k = n * m - left - settled[0]
            if k > 0:
                settled[0] += k
                progress(k)

    advance()
    threads = _threads()
    n_lanes = LANES if threads > 1 else 1  # one thread allowed: one round at a time
    lanes = {}  # lane -> (pairs, Future) of its round running, in the order started
    try:
        while True:
            active = {}
            for i in range(n):
                if scanning(i):
                    active.setdefault(int(gid[i]), []).append(i)
            per = -(-FILL_JOBS_PER_THREAD * threads // max(1, len(active))) if fill else 1
            for lane in range(n_lanes):
                if lane not in lanes:
                    pairs = next_round({g: mem for g, mem in active.items() if g % n_lanes == lane}, per)
                    if pairs:
                        lanes[lane] = start(pairs)
            if not lanes:
                break
            pairs, future = lanes.pop(next(iter(lanes)))  # the round started first
            collect(pairs, future.result())
            advance()
    except BaseException:  # an error or Ctrl-C: no round is started after this one
        for _, future in lanes.values():
            future.cancel()
        raise

    out = [None] * n
    lo, hi, active, left_out = np.zeros(n), np.zeros(n), [], set()
    for i in range(n):
        if i in errors:
            out[i] = (math.nan, math.nan, f"error: {errors[i]}")
        elif first[i] < 0 and pos[i] >= m:
            out[i] = (math.nan, grid[-1], NOTE_NO_OVERTURN.format(grid[-1]))
        elif first[i] < 0 or first[i] > cap[gid[i]]:  # left out: another scene of its group overturns lower
            out[i] = (math.nan, math.nan, NOTE_ABOVE_GROUP.format(grid[cap[gid[i]]]))
            left_out.add(i)
        elif first[i] == 0:
            out[i] = (grid[0], math.nan, NOTE_OVERTURNS_AT_MIN.format(grid[0]))
        else:
            lo[i], hi[i] = grid[first[i] - 1], grid[first[i]]
            active.append(i)
    while active:
        mids = {i: math.sqrt(lo[i] * hi[i]) for i in active}
        res = simulate_many([_scaled_job(*scenes[i], mids[i]) for i in active], early=True, **solver)
        for i, r in zip(active, res):
            unproven_bisection[i] += is_unproven(r)
            inconsistent_bisection[i] += getattr(r, "n_inconsistent", 0) > 0
            if r.verdict == VERDICT_ERROR:  # cannot happen for a scene that ran at the grid factors
                out[i], hi[i], lo[i] = (math.nan, math.nan, f"error: {r.error}"), 1.0, 1.0
            elif r.overturned:
                hi[i] = mids[i]
            else:
                lo[i] = mids[i]
        active = [i for i in active if hi[i] / lo[i] - 1.0 > rtol]
    for i in range(n):
        if out[i] is None:
            out[i] = (float(hi[i]), float(lo[i]), "")
        elif i in left_out:
            continue
        upto = m if first[i] < 0 else first[i] + 1
        count = int(np.count_nonzero(unproven[i, :upto])) + int(unproven_bisection[i])
        if count:
            hi_i, lo_i, note = out[i]
            out[i] = (hi_i, lo_i, (note + "; " if note else "") + f"{count} scaled run(s) not proven at the "
                      "solver's horizon, counted as surviving")
        count = int(np.count_nonzero(inconsistent[i, :upto])) + int(inconsistent_bisection[i])
        if count:
            hi_i, lo_i, note = out[i]
            out[i] = (hi_i, lo_i, (note + "; " if note else "") + NOTE_INCONSISTENT.format(count))
    return out


#: Scale factors of the neighbourhood check: 0.90, 0.91, ..., 1.10.
NEIGHBOURHOOD = np.round(np.linspace(0.9, 1.1, 21), 10)


def overturn_shares(scenes, *, factors=NEIGHBOURHOOD, progress=None, **solver) -> list[float]:
    """Share of the scale factors ``factors`` (default 0.90..1.10 in steps of 0.01) that overturn each scene.

    Near the overturning boundary the verdict can flip back and forth within a per cent of the
    amplitude (the boundary is ragged, not a single threshold); this share says how robust the
    verdict at scale 1 is: 0 or 1 robust, around 0.5 a coin toss within the uncertainty of any record.
    """
    from rockcli.assess.liftoff import liftoff_floors
    from rockcli.solve import simulate_many

    floors = liftoff_floors(scenes, **solver)  # a factor below its scene's floor cannot overturn: not run
    pairs = [(i, float(s)) for i in range(len(scenes)) for s in factors if s >= floors[i]]
    pairs = _balanced(pairs, [_cost(scenes[i][2]) for i, _ in pairs])
    skipped = len(scenes) * len(factors) - len(pairs)

    def advance(n_done):  # the factors left out count as done from the start
        progress(skipped + n_done)

    if progress is not None and skipped:
        progress(skipped)
    res = simulate_many([_scaled_job(*scenes[i], s) for i, s in pairs],
                        progress=advance if progress is not None else None,
                        chunk=max(1, len(pairs) // 50) if progress else None, early=True, **solver) if pairs else []
    count = np.zeros(len(scenes))
    for (i, _), r in zip(pairs, res):
        count[i] += r.overturned
    return list(count / len(factors))


def _group_ids(groups, n: int) -> np.ndarray:
    """Consecutive integer ids of ``groups`` (one hashable key per scene; None: each scene its own group)."""
    if groups is None:
        return np.arange(n)
    groups = list(groups)
    if len(groups) != n:
        raise ValueError(f"groups names {len(groups)} scenes' groups for {n} scenes")
    ids = {}
    return np.array([ids.setdefault(g, len(ids)) for g in groups], dtype=np.int64).reshape(n)


def _cost(motion) -> float:
    """Rough cost of a run: the samples of a record (the solver steps at least once per sample)."""
    return float(motion.acc.size) if hasattr(motion, "acc") else 100.0


def _balanced(items, costs):
    """Items reordered longest first: the threads take the next piece when free (:func:`rockcli.solve.pool.run_tasks`),
    so the longest runs start first and the short ones fill the gaps at the end (stable for equal costs)."""
    order = sorted(range(len(items)), key=lambda k: -costs[k])
    return [items[k] for k in order]


def run_local(func: Callable, chunks: Sequence) -> list:
    """The default runner of :func:`map_chunks`: ``[func(chunk) for chunk in chunks]`` in this process.

    Each call uses every core of this machine (:func:`rockcli.solve.simulate_many`).
    """
    return [func(chunk) for chunk in chunks]


def map_chunks(func: Callable, items: Sequence, *, chunk_size: int | None = None,
               runner: Callable | None = None) -> list:
    """``func`` applied to consecutive chunks of ``items`` by ``runner``; the results, flattened in order.

    This is the seam for running a long margin search elsewhere: ``func`` takes a list of items
    (e.g. scenes) and returns one result per item; ``runner(func, chunks)`` returns one result
    list per chunk, in order. The default, :func:`run_local`, runs one chunk of everything here.
    A distributed runner needs only to map a picklable function over a list, e.g. with Dask::

        runner = lambda func, chunks: client.gather(client.map(func, chunks))

    ``func`` must then be picklable (a module-level function or a :func:`functools.partial` of one;
    no progress callback).
    """
    items = list(items)
    if not items:
        return []
    size = len(items) if not chunk_size else max(1, int(chunk_size))
    chunks = [items[k:k + size] for k in range(0, len(items), size)]
    results = (runner or run_local)(func, chunks)
    out = []
    for chunk, res in zip(chunks, results):
        res = list(res)
        if len(res) != len(chunk):
            raise RuntimeError(f"runner returned {len(res)} results for a chunk of {len(chunk)}")
        out.extend(res)
    return out


class SearchGroup(NamedTuple):
    """One item of a chunked search (:func:`overturn_scales_chunked`): scenes searched together (one group
    of ``find_overturn_scales(groups=...)``, or one scene), with their responses at 1x (or None)."""

    scenes: tuple
    known: tuple | None = None


def chunk_scenes(chunk) -> int:
    """The scenes of a chunk of :class:`SearchGroup` items (for a runner's progress)."""
    return sum(len(item.scenes) for item in chunk)


def search_groups(items: Sequence[SearchGroup], **kwargs) -> list:
    """:func:`find_overturn_scales` of the scenes of ``items``, each item one group: one list of results
    per item (the function a runner maps over chunks; picklable with :func:`functools.partial`)."""
    scenes = [s for item in items for s in item.scenes]
    known = None
    if any(item.known is not None for item in items):
        known = [r for item in items for r in item.known]
    found = find_overturn_scales(scenes, known=known, groups=[k for k, item in enumerate(items) for _ in item.scenes],
                                 **kwargs)
    out, at = [], 0
    for item in items:
        out.append(found[at:at + len(item.scenes)])
        at += len(item.scenes)
    return out


def overturn_scales_chunked(scenes, *, groups=None, known=None, chunk_size: int | None = None,
                            runner: Callable | None = None, **kwargs) -> list:
    """:func:`find_overturn_scales` over chunks of ``scenes`` through :func:`map_chunks` (same results).

    The items mapped are :class:`SearchGroup`: one per group of ``groups`` (a group is searched as
    one, see :func:`find_overturn_scales`), else one per scene, with its response at 1x when ``known``
    is given. Each item's search depends on that item only, so chunking changes nothing but where and
    in which batches the runs happen; ``chunk_size`` counts items.
    """
    n = len(scenes)
    if known is not None and len(known) != n:
        raise ValueError(f"{len(known)} responses at 1x for {n} scenes")
    gid = _group_ids(groups, n)
    members = {}
    for i, g in enumerate(gid.tolist()):
        members.setdefault(g, []).append(i)
    order = list(members.values())
    items = [SearchGroup(tuple(scenes[i] for i in idx), None if known is None else tuple(known[i] for i in idx))
             for idx in order]
    found = map_chunks(functools.partial(search_groups, **kwargs), items, chunk_size=chunk_size, runner=runner)
    out = [None] * n
    for idx, res in zip(order, found):
        for i, r in zip(idx, res):
            out[i] = r
    return out
