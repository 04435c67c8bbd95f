"""The first run: the compile notice, the margin search's progress (every (scene, factor) pair settled
exactly once), and the batch kernels compiled side by side (``rockcli.kernels.batch.prepare``). The
progress lines' ETA, which a compile does not fool: tests/test_progress.py."""

from __future__ import annotations

import io
import json
import os
import re
import subprocess
import sys
import time
import types
from pathlib import Path

import numpy as np
import pytest

from rockcli import compiling
from rockcli.assess import MARGIN_GRID, find_overturn_scales, parse_column_spec, parse_configurations
from rockcli.cli import progress as progress_mod
from rockcli.pulses import make_pulse
from rockcli.solve import simulate_many
from rockcli.io.units import G

COARSE_GRID = np.append(MARGIN_GRID[:-1:8], MARGIN_GRID[-1])


class _Tty(io.StringIO):
    def isatty(self):
        return True


@pytest.fixture
def fresh_watch(monkeypatch):
    """No compile watch installed yet, and the subscriptions of this test dropped afterwards."""
    monkeypatch.setattr(progress_mod, "_watching", False)
    before = list(compiling._listeners)
    yield
    compiling._listeners[:] = before


# --------------------------------------------------------------------------------------------------
# the compile notice
# --------------------------------------------------------------------------------------------------

def test_compile_notice_once_on_a_terminal_and_once_when_piped(fresh_watch):
    """The first run says once that it compiles, on a terminal and when its output is piped, redirected or in a CI
    log (it used to sit silent for minutes there); piped, as a plain line without terminal codes."""
    tty = _Tty()
    progress_mod.watch_compiles(tty)
    assert tty.getvalue() == ""  # nothing until a kernel compiles
    compiling.started("batch.simulate_batch")
    compiling.ended("batch.simulate_batch", 20.0)
    compiling.started("batch.simulate_batch_rigid")
    assert tty.getvalue().count("compiling the solver kernels") == 1 and tty.getvalue().endswith("...\n")
    compiling.ended("batch.simulate_batch_rigid", 20.0)
    assert not compiling.compiling()

    progress_mod._watching = False
    piped = io.StringIO()
    progress_mod.watch_compiles(piped)
    assert piped.getvalue() == ""  # nothing until a kernel compiles
    for name in ("batch.simulate_batch", "batch.simulate_batch_rigid"):
        compiling.started(name)
        compiling.ended(name, 1.0)
    assert piped.getvalue() == progress_mod.COMPILE_NOTICE + "\n"  # once, a plain line


def test_a_failing_listener_does_not_reach_the_compiler(fresh_watch):
    def boom(*_):
        raise OSError("stderr closed")

    unsubscribe = compiling.subscribe(boom, boom)
    compiling.started("x.y")  # would raise inside numba's compile otherwise
    compiling.ended("x.y", 0.0)
    unsubscribe()
    assert (boom, boom) not in compiling._listeners


def test_kernels_report_only_real_compiles():
    """numba's compile of a function of rockcli.kernels is reported once, as it begins and ends; a kernel
    already compiled or loaded, and a function outside the package, are not."""
    from numba import njit
    from numba.core import event

    import rockcli.kernels as K

    scene = (parse_column_spec("c:R=1,alpha=10"), None, make_pulse("ricker-sym", 0.3 * G, 0.5))
    simulate_many([scene])  # compiled or loaded now
    seen = []
    unsubscribe = compiling.subscribe(lambda name: seen.append(("start", name, compiling.compiling())),
                                      lambda name, s: seen.append(("end", name, s >= 0)))
    try:
        simulate_many([scene])
        assert seen == []

        @njit
        def outside(x):  # not a function of rockcli.kernels: not reported
            return x + 1

        outside(1)
        assert seen == []
        fresh = njit(K.ground.pulse_acc.py_func)  # a new dispatcher of a kernel function: a real compile
        fresh(np.int64(K.EXC_RICKER_SYM), (0.1, 1.0, 0.5, 0.0, 2.0, 1.0, 0.0, 0.0), 0.25)
        assert seen == [("start", "ground.pulse_acc", True), ("end", "ground.pulse_acc", True)]
        assert not compiling.compiling()
        watch = [x for x in event._registered["numba:compile"] if getattr(x, "_rockcli_watch", False)]
        assert len(watch) == 1
    finally:
        unsubscribe()


# --------------------------------------------------------------------------------------------------
# the margin search's progress
# --------------------------------------------------------------------------------------------------

def test_margin_progress_settles_every_pair_once_and_changes_nothing():
    blocks = [parse_column_spec("a:R=0.8,alpha=12"), parse_column_spec("b:R=2.5,alpha=9")]
    confs = parse_configurations(["none", "linear:Tb=2,xi=0.1"])
    pulses = [make_pulse("ricker-anti", 0.3 * G, 0.8), make_pulse("ricker-sym", 0.15 * G, 1.5)]
    scenes = [(b, c.foundation, m) for b in blocks for m in pulses for c in confs]
    n, m = len(scenes), COARSE_GRID.size
    steps = []
    found = find_overturn_scales(scenes, grid=COARSE_GRID, progress=steps.append)
    assert all(k > 0 for k in steps) and sum(steps) == n * m
    assert len(steps) > 2  # it moves during the search, not only at the end
    assert found == find_overturn_scales(scenes, grid=COARSE_GRID)

    known = simulate_many(scenes)
    steps = []
    assert find_overturn_scales(scenes, grid=COARSE_GRID, known=known, progress=steps.append) == found
    assert all(k > 0 for k in steps) and sum(steps) == n * (m - 1)  # factor 1 was counted by the caller


# --------------------------------------------------------------------------------------------------
# the batch kernels compiled side by side
# --------------------------------------------------------------------------------------------------

class _Kernel:
    def __init__(self, name, compiled=False):
        self.signatures = ["sig"] if compiled else []
        self.py_func = types.SimpleNamespace(__name__=name)
        self.calls = 0


def _fake_kernels(monkeypatch, cached, compiled=()):
    from rockcli.kernels import batch

    kernels = {name: _Kernel(name, name in compiled) for name in batch.BATCH_KERNELS}
    for name, k in kernels.items():
        monkeypatch.setitem(batch.__dict__, name, k)
    monkeypatch.setattr(batch, "_cached", lambda k: cached[k.py_func.__name__])
    calls = []
    monkeypatch.setattr(batch, "_empty_call", lambda k: calls.append(k.py_func.__name__))
    spawned = []

    class _Popen:
        def __init__(self, args, **kw):
            spawned.append(args[-1])

        def wait(self, timeout=None):
            return 0

        def poll(self):
            return 0

    monkeypatch.setattr(subprocess, "Popen", _Popen)
    monkeypatch.setattr(os, "sched_getaffinity", lambda pid: {0, 1}, raising=False)
    return batch, calls, spawned


def test_prepare_compiles_the_second_cold_kernel_in_a_child(monkeypatch):
    batch, calls, spawned = _fake_kernels(monkeypatch, {"simulate_batch_rigid": False, "simulate_batch": False})
    batch.prepare(["simulate_batch_rigid", "simulate_batch"])
    assert len(spawned) == 1 and "_compile_child('simulate_batch_rigid')" in spawned[0]
    # the isolated kernel compiled here while the child compiles the rigid one; then both loaded here
    assert calls == ["simulate_batch", "simulate_batch_rigid", "simulate_batch"]


@pytest.mark.parametrize("cached, names, compiled", [
    ({"simulate_batch_rigid": True, "simulate_batch": False}, ["simulate_batch_rigid", "simulate_batch"], ()),
    ({"simulate_batch_rigid": False, "simulate_batch": False}, ["simulate_batch_rigid"], ()),
    ({"simulate_batch_rigid": None, "simulate_batch": None}, ["simulate_batch_rigid", "simulate_batch"], ()),
    ({"simulate_batch_rigid": False, "simulate_batch": False}, ["simulate_batch_rigid", "simulate_batch"],
     ("simulate_batch",)),
])
def test_prepare_spawns_nothing_unless_two_kernels_must_compile(monkeypatch, cached, names, compiled):
    batch, calls, spawned = _fake_kernels(monkeypatch, cached, compiled)
    batch.prepare(names)
    assert spawned == []
    assert calls == [n for n in names if n not in compiled]  # each kernel not in memory: loaded or compiled here


# --------------------------------------------------------------------------------------------------
# a warm process loads its kernels without refreshing numba's registries (kernels/cache._load_unrefreshed)
# --------------------------------------------------------------------------------------------------
_LOAD_CHILD = r"""
import json, sys
import numpy as np
if sys.argv[1] == "refresh":  # numba's own order: the registries first, then the load
    from numba.core import registry
    registry.cpu_target.target_context.refresh()
from rockcli import compiling
from rockcli.models import LinearIsolation, Rigid, SingleConcaveSliding
from rockcli.pulses import make_pulse
from rockcli.records import Record
from rockcli.solve import bearing_force_path, simulate, simulate_many
from rockcli.assess import parse_column_spec
from rockcli.io.units import G
block = parse_column_spec("c:R=1.2,alpha=12")
pulse = make_pulse("ricker-anti", 0.35 * G, 0.9)
wave = Record(0.3 * G * np.sin(np.linspace(0.0, 25.0, 800)) * np.exp(-np.linspace(0.0, 4.0, 800)), 0.01, "wave")
vertical = Record(np.full(600, 0.1 * G), 0.01, "constant")
bases = [Rigid(), LinearIsolation(T_b=2.5, xi=0.1), SingleConcaveSliding(T_b=3.0, mu=0.05)]
out = []
for base in bases:  # the single-run drivers, with their histories
    r = simulate(block, base, wave, history=True)
    out += [r.status, r.theta_max, r.base_disp_max_m, r.steps, float(np.sum(r.history.theta))]
r = simulate(block, Rigid(), pulse, vertical=vertical, history=True)  # the vertical driver
out += [r.status, r.theta_max, r.steps]
scenes = [(block, base, ex, s) for base in bases for ex in (pulse, wave) for s in (0.5, 1.0, 1.7)]
for r in simulate_many(scenes) + simulate_many(scenes[:6], vertical=vertical):  # the three batch kernels
    out += [r.status, r.theta_max, r.nfev]
out += list(bearing_force_path(bases[2], np.linspace(0.0, 0.2, 50))["force"])
print(json.dumps({"compiles": compiling.compiles(), "registries": "numba.np.linalg" in sys.modules,
                  "out": [float(x).hex() if isinstance(x, float) else str(x) for x in out]}))
"""


def _load_child(mode):
    proc = subprocess.run([sys.executable, "-c", _LOAD_CHILD, mode], capture_output=True, text=True, timeout=900,
                          env={k: v for k, v in os.environ.items() if k != "NUMBA_DISABLE_JIT"})
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.splitlines()[-1])


def test_a_warm_process_loads_every_kernel_without_numbas_registries_and_gets_the_same_results():
    """A process whose kernels are all in the disk cache loads them without refreshing numba's registries
    (nothing compiled, ``numba.np.linalg`` never imported) and every driver (single runs with histories on a
    rigid base, linear and sliding bearings, under a vertical motion; the three batch kernels; the bearings'
    force along a path) gives, bit for bit, what a process that refreshed them first gives (numba's order)."""
    first = _load_child("plain")  # compiles what the disk cache lacks (nothing, after any earlier run)
    plain, refreshed = _load_child("plain"), _load_child("refresh")
    assert plain["compiles"] == 0 and not plain["registries"], plain
    assert refreshed["registries"]
    assert plain["out"] == refreshed["out"] == first["out"]
    # the parallel scheduler's symbols are the only ones a refresh registers that a load could miss
    import rockcli.kernels as K

    for path in Path(K.__file__).parent.glob("*.py"):
        text = path.read_text()
        assert not re.search(r"jit\([^)]*parallel\s*=\s*True", text) and "prange" not in text, path.name


# --------------------------------------------------------------------------------------------------
# two processes that both lack a kernel compile it once (kernels/cache._claim_compile)
# --------------------------------------------------------------------------------------------------
_FIRST_EXCEED = ("import json, sys, numpy as np; from rockcli.kernels import polynomials as p; "
                 "print('ready', flush=True); sys.stdin.readline(); "
                 "x = p._first_exceed(np.array([0.0, 1.0, 0.0, 0.0, 0.0]), 0.5)[0]; k = p._first_exceed; "
                 "print(json.dumps({'x': float(x).hex(), 'misses': sum(k._cache_misses.values()), "
                 "'hits': sum(k._cache_hits.values())}))")


def test_two_processes_that_lack_a_kernel_compile_it_once(tmp_path):
    """Two processes that need a kernel the disk cache lacks, at the same moment (both imported, then told
    to go together): one compiles it, the other waits for that compile and loads what the first saved,
    instead of compiling it again (without the lock both compiled it); both get the same result (the
    polynomial c(x) = x first exceeds 0.5 at x = 0.5)."""
    env = {k: v for k, v in os.environ.items() if k != "NUMBA_DISABLE_JIT"}
    env["NUMBA_CACHE_DIR"] = str(tmp_path)
    procs = [subprocess.Popen([sys.executable, "-c", _FIRST_EXCEED], env=env, stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for _ in range(2)]
    for proc in procs:
        assert proc.stdout.readline().strip() == "ready", proc.stderr.read()
    for proc in procs:
        proc.stdin.write("go\n")
        proc.stdin.flush()
    outs = []
    for proc in procs:
        out, err = proc.communicate(timeout=900)
        assert proc.returncode == 0, err
        outs.append(json.loads(out.splitlines()[-1]))
    assert sorted(o["misses"] for o in outs) == [0, 1] and sum(o["hits"] for o in outs) == 1, outs
    assert outs[0]["x"] == outs[1]["x"] and abs(float.fromhex(outs[0]["x"]) - 0.5) < 1e-12


# --------------------------------------------------------------------------------------------------
# the suite's compiles ahead (tests/kernel_first_calls.py)
# --------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("cached, switch, started", [(False, None, 5), (True, None, 0), (None, None, 0),
                                                     (False, "0", 0)])
def test_the_suite_compiles_ahead_only_the_groups_the_cache_lacks(monkeypatch, cached, switch, started):
    """A child per group whose driver the disk cache lacks (``_cached`` False), none when it has them or cannot
    tell, none when turned off; each child runs its own group's first calls, from this repository."""
    import kernel_first_calls as k

    import rockcli.kernels.batch as batch

    monkeypatch.setattr(batch, "_cached", lambda kernel: cached)
    if switch is None:
        monkeypatch.delenv("ROCKCLI_TEST_COMPILE_AHEAD", raising=False)
    else:
        monkeypatch.setenv("ROCKCLI_TEST_COMPILE_AHEAD", switch)
    spawned = []

    class _Popen:
        def __init__(self, argv, **kw):
            spawned.append((argv, kw))

    monkeypatch.setattr(k.subprocess, "Popen", _Popen)
    assert len(k.start()) == started
    groups = [argv[-1].split("compile_group(")[1].rstrip(")") for argv, _ in spawned]
    assert groups == [repr(g) for g in k.GROUP_DRIVERS][:started]
    for _, kw in spawned:
        assert str(k.ROOT) in kw["env"]["PYTHONPATH"].split(os.pathsep)


def test_each_group_of_first_calls_reaches_its_driver():
    """Every group compiles the driver that makes it cold, and every first call belongs to a group."""
    import kernel_first_calls as k

    calls = k.first_calls()
    assert {g for g, _, _ in calls} == set(k.GROUP_DRIVERS)
    for group, (module, name) in k.GROUP_DRIVERS.items():
        assert f"{module}.{name}" in [driver for g, driver, _ in calls if g == group]
