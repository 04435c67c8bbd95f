"""Verdict-only runs of many scenes: one serial loop per driver, compiled without the GIL.

:mod:`rockcli.solve` runs chunks of a sweep on a pool of threads, each thread calling one of these
on its chunk (numba's ``parallel=True`` would compile a second, much larger specialisation of the
driver for the same work). A sweep compiles only the driver its scenes need.

Row ``i`` of each argument describes scene ``i`` (``prms[i]`` in the ``P_*`` layout, ``N_PRM``
wide); records are slices ``acc_all[acc_off[i]:acc_off[i] + acc_len[i]]`` (scenes may share one;
``jtab_all`` is laid out alike). Results go to ``outs[i]`` (``O_*`` layout); nothing else is stored.
Under a vertical ground motion (rigid foundation only) the vertical series are slices
``vacc_all[v_off[i]:v_off[i] + v_len[i]]`` sampled every ``vdts[i]`` (``vjtab_all`` alike).

:func:`prepare` gets the kernels a sweep needs ready before it starts; on the first run on a machine
it compiles them side by side (one child process per kernel but one).
"""

from __future__ import annotations

import numpy as np

from rockcli.kernels.driver import simulate_core
from rockcli.kernels.jit import kernel
from rockcli.kernels.rigid import simulate_rigid, simulate_rigid_vertical


@kernel(inline='always')
def _scene(i, prms, epars):
    """Scene ``i``'s parameter and excitation tuples."""
    q = prms[i]
    prm = (q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8], q[9], q[10], q[11], q[12], q[13],
           q[14], q[15], q[16], q[17], q[18], q[19], q[20], q[21], q[22], q[23], q[24], q[25], q[26], q[27],
           q[28], q[29])
    e = epars[i]
    return prm, (e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7])


@kernel(inline='always')
def _run_scenes(simulate, fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins,
                t_exc_ends, tails, horizon, max_steps, early, outs):
    """Scene ``i`` of the rows through the driver ``simulate``, verdict only, into ``outs[i]``."""
    no_history = np.bool_(False)  # not a literal: the same compiled driver as a single run's
    for i in range(fkinds.shape[0]):
        prm, epar = _scene(i, prms, epars)
        a, b = acc_off[i], acc_off[i] + acc_len[i]
        simulate(fkinds[i], prm, ekinds[i], epar, acc_all[a:b], jtab_all[a:b], dts[i], t_begins[i],
                 t_exc_ends[i], tails[i], horizon, max_steps, no_history, early, outs[i])


@kernel(nogil=True)
def simulate_batch_rigid(fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins,
                         t_exc_ends, tails, horizon, max_steps, early, outs):
    """Scenes on a rigid foundation (:func:`rockcli.kernels.rigid.simulate_rigid`)."""
    _run_scenes(simulate_rigid, fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins,
                t_exc_ends, tails, horizon, max_steps, early, outs)


@kernel(nogil=True)
def simulate_batch(fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins, t_exc_ends,
                   tails, horizon, max_steps, early, outs):
    """Scenes on isolated bases (:func:`rockcli.kernels.driver.simulate_core`)."""
    _run_scenes(simulate_core, fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins,
                t_exc_ends, tails, horizon, max_steps, early, outs)


@kernel(nogil=True)
def simulate_batch_rigid_vertical(fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins,
                                  t_exc_ends, tails, horizon, max_steps, early, vacc_all, vjtab_all, v_off, v_len, vdts,
                                  outs):
    """Scenes on a rigid foundation under a vertical ground motion as well
    (:func:`rockcli.kernels.rigid.simulate_rigid_vertical`; its proofs under a vertical motion, PV)."""
    no_history = np.bool_(False)
    for i in range(fkinds.shape[0]):
        prm, epar = _scene(i, prms, epars)
        a, b = acc_off[i], acc_off[i] + acc_len[i]
        c, d = v_off[i], v_off[i] + v_len[i]
        simulate_rigid_vertical(fkinds[i], prm, ekinds[i], epar, acc_all[a:b], jtab_all[a:b], dts[i], t_begins[i],
                                t_exc_ends[i], tails[i], horizon, max_steps, no_history, early, vacc_all[c:d],
                                vjtab_all[c:d], vdts[i], outs[i])


# --------------------------------------------------------------------------------------------------
# getting the batch kernels ready: the first run compiles the ones it needs side by side
# --------------------------------------------------------------------------------------------------

#: The batch kernels by name (what a child process is asked to compile).
BATCH_KERNELS = ("simulate_batch_rigid", "simulate_batch")
#: Longest wait for a child's compile [s]; then it is stopped and the kernel compiled here.
CHILD_TIMEOUT = 900.0


def _empty_call(kernel) -> None:
    """Call ``kernel`` on no scenes, with the argument types of :func:`rockcli.solve.simulate_many`'s
    calls: it is compiled (or loaded from the disk cache) for exactly that signature, and runs nothing."""
    from rockcli.kernels.layout import N_EPAR, N_OUT, N_PRM

    ints, floats = np.zeros(0, np.int64), np.zeros(0)
    kernel(ints, np.zeros((0, N_PRM)), ints, np.zeros((0, N_EPAR)), floats, floats, ints, ints, floats, floats,
           floats, floats, 0.0, 1, False, np.zeros((0, N_OUT)))


def _cached(kernel) -> bool | None:
    """Whether numba's disk cache holds ``kernel`` compiled from the current sources (None: cannot tell,
    e.g. with the JIT disabled, no disk cache, or another numba's internals)."""
    try:
        locator = kernel._cache._impl.locator
        if getattr(locator, "_no_disk", False):
            return None
        return bool(kernel._cache._cache_file._load_index())
    except Exception:  # noqa: BLE001 - only an optimisation depends on it
        return None


def prepare(names) -> None:
    """Compile or load the batch kernels ``names`` (of :data:`BATCH_KERNELS`) before a sweep runs on them.

    A kernel already in this process costs nothing, one in the disk cache is loaded. When two or more
    must be compiled (the first run on a machine) and this machine has two cores or more, all but the
    last are compiled at the same time in child processes (numba compiles one function at a time in
    a process), which write them to the disk cache, from where this process then loads them: the
    same compiled code as compiling them here, in about the time of the longest compile instead of
    the sum. A child that fails or takes longer than :data:`CHILD_TIMEOUT` changes nothing: the
    kernel is then compiled here.
    """
    import os
    import subprocess
    import sys

    kernels = [globals()[name] for name in dict.fromkeys(names)]
    todo = [k for k in kernels if hasattr(k, "signatures") and not k.signatures]
    cold = [k for k in todo if _cached(k) is False]
    children = []
    try:
        cores = len(os.sched_getaffinity(0))
    except (AttributeError, OSError):
        cores = os.cpu_count() or 1
    here = cold[-1] if cold else None  # the isolated base's kernel, the longest compile, when both are cold
    if len(cold) >= 2 and cores >= 2:
        root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")])))
        for k in cold[:-1]:  # the child imports this very rockcli, so it writes where this process reads
            try:
                children.append(subprocess.Popen(
                    [sys.executable, "-c", f"from rockcli.kernels.batch import _compile_child; _compile_child("
                                           f"{k.py_func.__name__!r})"],
                    env=env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
            except OSError:
                break
    try:
        if children:
            _empty_call(here)
        for child in children:
            try:
                child.wait(timeout=CHILD_TIMEOUT)
            except subprocess.TimeoutExpired:
                child.kill()
                child.wait()
    finally:
        for child in children:
            if child.poll() is None:
                child.kill()
                child.wait()
    for k in todo:
        _empty_call(k)


def _compile_child(name: str) -> None:
    """In a child process of :func:`prepare`: compile the kernel ``name`` into the disk cache."""
    if name not in BATCH_KERNELS:
        raise SystemExit(f"not a batch kernel: {name}")
    _empty_call(globals()[name])
