"""What the batch path keeps between calls (issue 33) changes no run: the process's pool of threads
(:mod:`rockcli.solve.pool`), the records' kernel arrays (:func:`rockcli.solve.excitation._excitation_arrays_cached`)
and the work estimates that passed (``rockcli.solve.batch._WORK_PASSED``).

The cache of a record's arrays returns them only for the same record object with the same time step and the
same samples bit for bit: tested on hits, on records changed in place between calls (a sample, the sign of a
zero, a NaN), on a record that goes away, and on the byte cap; then on 2,000 random short runs, each call's
results equal to those of the path without the cache, with the records changed between the calls.
"""

from __future__ import annotations

import gc
import threading

import numpy as np
import pytest

from rockcli.errors import RockcliInputError
from rockcli.models import Block, LinearIsolation, Rigid
from rockcli.solve import JobError, simulate_many
from rockcli.solve import batch, excitation
from rockcli.solve.excitation import _excitation_arrays, _excitation_arrays_cached
from rockcli.solve.pool import run_tasks
from synthetic import random_record


def _record(rng, n=None):
    """A short random accelerogram, PGA 0.1 .. 0.6 g."""
    return random_record(rng, n, n_range=(100, 250), pga_g=(0.1, 0.6), n_sines=4, f_range=(0.5, 5.0))


def _same(a, b):
    """Two ``_excitation_arrays`` tuples equal bit for bit."""
    assert len(a) == len(b)
    for x, y in zip(a, b):
        if isinstance(x, np.ndarray):
            assert x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes()
        else:
            assert x == y


def test_a_record_is_prepared_once_and_its_arrays_are_read_only():
    rec = _record(np.random.default_rng(1))
    first = _excitation_arrays_cached(rec)
    _same(first, _excitation_arrays(rec))
    assert _excitation_arrays_cached(rec) is first  # a hit: the same tuple
    ekind, epar, acc, jtab = first[:4]
    assert acc is not rec.acc  # a private copy: the record's own array may change
    for a in (epar, acc, jtab):
        with pytest.raises(ValueError):
            a[0] = 1.0


@pytest.mark.parametrize("change", ["sample", "negative zero", "last ulp", "dt"])
def test_a_record_changed_in_place_is_prepared_again(change):
    rng = np.random.default_rng(2)
    rec = _record(rng)
    rec.acc[5] = 0.0
    first = _excitation_arrays_cached(rec)
    if change == "sample":
        rec.acc[7] *= 1.5
    elif change == "negative zero":
        rec.acc[5] = -0.0  # equal as a float, another bit pattern: not the arrays prepared
    elif change == "last ulp":
        rec.acc[9] = np.nextafter(rec.acc[9], np.inf)
    else:
        object.__setattr__(rec, "dt", 0.02)
    again = _excitation_arrays_cached(rec)
    assert again is not first
    _same(again, _excitation_arrays(rec))
    assert _excitation_arrays_cached(rec) is again


def test_a_record_changed_to_nan_is_refused_as_before():
    rec = _record(np.random.default_rng(3))
    _excitation_arrays_cached(rec)
    rec.acc[3] = np.nan
    with pytest.raises(RockcliInputError, match="NaN or infinite"):
        _excitation_arrays_cached(rec)
    res = simulate_many([(Block(1.0, 0.2), Rigid(), rec)])
    assert isinstance(res[0], JobError) and "NaN" in res[0].error


def test_entries_go_with_their_record_and_under_the_byte_cap(monkeypatch):
    rng = np.random.default_rng(4)
    gc.collect()
    before = len(excitation._RECORD_ARRAYS)
    rec = _record(rng)
    _excitation_arrays_cached(rec)
    assert len(excitation._RECORD_ARRAYS) == before + 1
    del rec
    gc.collect()
    assert len(excitation._RECORD_ARRAYS) == before
    monkeypatch.setattr(excitation, "RECORD_CACHE_BYTES", 3 * 8 * 400)  # three records of 400 samples
    recs = [_record(rng, n=400) for _ in range(5)]
    for r in recs:
        _excitation_arrays_cached(r)
    held = [r for r in recs if r in excitation._RECORD_ARRAYS]
    assert held == recs[2:]  # the oldest went first
    _same(_excitation_arrays_cached(recs[0]), _excitation_arrays(recs[0]))  # prepared again when needed


def test_runs_with_the_caches_equal_runs_without_them_on_random_scenes(monkeypatch):
    """2,000 short verdict-only runs in four calls, the records changed in place between calls: each call's
    results equal, field for field, those of the same call without the record cache and the work cache."""
    rng = np.random.default_rng(33)
    records = [_record(rng) for _ in range(12)]
    blocks = [Block(float(rng.uniform(0.3, 3.0)), float(rng.uniform(0.1, 0.3))) for _ in range(6)]
    foundations = [Rigid(), LinearIsolation(2.0, 0.1, 0.3), LinearIsolation(3.0, 0.05, 0.1)]
    fields = ("verdict", "overturned", "theta_max_over_alpha", "t_uplift_s", "n_impacts", "settled", "nfev")

    def call(jobs, cached):
        if not cached:
            monkeypatch.setattr(batch, "_excitation_arrays_cached", _excitation_arrays)
            monkeypatch.setattr(batch, "_WORK_PASSED", set())
        try:
            return [repr(tuple(getattr(r, f) for f in fields)) for r in simulate_many(jobs, early=True)]  # NaN == NaN
        finally:
            monkeypatch.undo()

    for round_ in range(4):
        jobs = [(blocks[rng.integers(6)], foundations[rng.integers(3)], records[rng.integers(12)],
                 float(rng.uniform(0.3, 3.0))) for _ in range(500)]
        got, want = call(jobs, True), call(jobs, False)
        assert got == want, f"call {round_}"
        for rec in records[::3]:  # change some records in place before the next call
            rec.acc[rng.integers(rec.acc.size)] *= float(rng.uniform(0.5, 2.0))


def test_the_work_check_is_remembered_per_solver_options():
    rec = _record(np.random.default_rng(5))
    job = (Block(1.0, 0.2), Rigid(), rec)
    assert not isinstance(simulate_many([job])[0], JobError)  # passed, and remembered
    refused = simulate_many([job], max_steps=100)  # the same scene with a step cap it cannot meet
    assert isinstance(refused[0], JobError) and "integrator steps" in refused[0].error


def test_run_tasks_runs_in_order_and_raises_and_nests():
    assert run_tasks([lambda i=i: i * i for i in range(20)], threads=2) == [i * i for i in range(20)]
    seen = []
    assert run_tasks([lambda i=i: i for i in range(7)], done=seen.append, threads=2) == list(range(7))
    assert sorted(seen) == list(range(7))
    started = []

    def boom():
        raise ValueError("task failed")

    with pytest.raises(ValueError, match="task failed"):
        run_tasks([boom] + [lambda: started.append(1)] * 50, done=lambda r: None, threads=2)
    assert len(started) < 50  # the tasks not started were dropped
    names = run_tasks([lambda: run_tasks([lambda: threading.current_thread().name] * 3, threads=2)] * 2, threads=2)
    assert all(len(set(inner)) == 1 for inner in names)  # a task on the pool runs its own tasks in its thread


def test_in_background_runs_tasks_on_the_pool():
    """A caller thread (the margin search's lanes) is not one of the pool's: its tasks go to the pool's threads."""
    from rockcli.solve.pool import in_background

    def lane():
        here = threading.current_thread().name
        return here, run_tasks([lambda: threading.current_thread().name] * 4, threads=2)

    here, names = in_background(lane).result()
    assert here.startswith("rockcli-caller") and all(n.startswith("rockcli-kernel") for n in names)


@pytest.mark.parametrize("threads", ["1", "2"])
def test_the_margin_search_lanes_keep_to_the_thread_count(monkeypatch, threads):
    """Two lanes of rounds at once on two threads, one round at a time when one thread is allowed; the same
    margins either way."""
    import rockcli.solve as solve
    from rockcli.assess import find_overturn_scales

    rng = np.random.default_rng(7)
    scenes = [(Block(float(rng.uniform(0.5, 2.0)), 0.2), Rigid(), _record(rng)) for _ in range(6)]
    grid = np.geomspace(0.5, 4.0, 25)
    original, now, most = solve.simulate_many, [0], [0]
    lock = threading.Lock()

    def counting(jobs, **kw):
        with lock:
            now[0] += 1
            most[0] = max(most[0], now[0])
        try:
            return original(jobs, **kw)
        finally:
            with lock:
                now[0] -= 1

    want = find_overturn_scales(scenes, grid=grid)
    monkeypatch.setenv("NUMBA_NUM_THREADS", threads)
    monkeypatch.setattr(solve, "simulate_many", counting)
    got = find_overturn_scales(scenes, grid=grid)
    assert repr(got) == repr(want)
    assert most[0] <= int(threads)
