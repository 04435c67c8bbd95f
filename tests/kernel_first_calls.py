"""The first call of each compiled driver, with the argument types rockcli passes; and the suite's compiles ahead.

:data:`GROUPS` names the drivers' first calls in four groups that share no large kernel: the rigid foundation
(single runs, the batch kernel, under a vertical motion), the isolated base (single runs, the batch kernel, the
lift-off floor, a bearing's loop), the body on its plinth on a rigid foundation, and on bearings. The friction driver
(one block, a plinth, drums: one kernel) is a fifth group. A first call
compiles its driver, or loads it from numba's disk cache. ``benchmarks/bench_compile.py`` times them one after
the other, in one process.

:func:`start` is what the test suite does with them when it runs on several workers (``pytest -n 2``) and some
driver is not in the disk cache (a fresh clone): one child process per cold group compiles it into the cache,
all of them at once, started by pytest's main process before the workers ask for the drivers. Without it the
worker that first needs a driver compiles it (numba compiles one function at a time in a process) while the
other waits on the compile lock (:mod:`rockcli.kernels.cache`) for every test that needs the same driver: about
a minute of one core idle on a fresh clone. The compiled code is the same wherever it is compiled (numba's cache
is keyed on the sources and the machine); a child that fails changes nothing (the tests then compile it as
before). ``ROCKCLI_TEST_COMPILE_AHEAD=0`` turns it off.
"""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _vertical_batch(kernel) -> None:
    import numpy as np

    from rockcli.kernels.layout import N_EPAR, N_OUT, N_PRM

    ints, floats = np.zeros(0, np.int64), np.zeros(0)
    kernel(ints, np.zeros((0, N_PRM)), ints, np.zeros((0, N_EPAR)), floats, floats, ints, ints, floats, floats,
           floats, floats, 0.0, 1, False, floats, floats, ints, ints, floats, np.zeros((0, N_OUT)))


def first_calls() -> list[tuple[str, str, object]]:
    """``(group, driver, call)`` in the order ``bench_compile`` times them: ``call()`` makes the driver's first call."""
    import numpy as np

    from rockcli.assess.liftoff import load_floor_kernel
    from rockcli.io.units import G
    from rockcli.kernels import batch as kb
    from rockcli.models import Block, LinearIsolation, Plinth, Rigid, SingleConcaveSliding, Stack
    from rockcli.pulses import make_pulse
    from rockcli.records import Record
    from rockcli.solve import bearing_force_path, simulate, simulate_stack
    from rockcli.solve.slide import simulate_friction

    block = Block(1.0, 0.2)
    pulse = make_pulse("sine", 2.0 * G * math.tan(0.2), 0.5)
    stack = Stack(Block.from_dimensions(1.5, 0.4, "body"), Plinth(0.5, 1.0, None))
    bearings = LinearIsolation(2.0, xi=0.1, gamma=0.2)
    vertical = Record(np.full(200, 1.0), 0.01, "constant")
    return [
        ("rigid", "rigid.simulate_rigid", lambda: simulate(block, Rigid(), pulse)),
        ("rigid", "rigid.simulate_rigid_vertical", lambda: simulate(block, Rigid(), pulse, vertical=vertical)),
        ("isolated", "driver.simulate_core", lambda: simulate(block, LinearIsolation(2.0), pulse)),
        ("plinth", "stack.simulate_stack", lambda: simulate_stack(stack, pulse)),
        ("plinth-bearings", "stack_linear.simulate_stack_linear",
         lambda: simulate_stack(stack, pulse, isolation=bearings)),
        ("rigid", "batch.simulate_batch_rigid", lambda: kb._empty_call(kb.simulate_batch_rigid)),
        ("isolated", "batch.simulate_batch", lambda: kb._empty_call(kb.simulate_batch)),
        ("rigid", "batch.simulate_batch_rigid_vertical", lambda: _vertical_batch(kb.simulate_batch_rigid_vertical)),
        ("isolated", "linear_base.stuck_peak", lambda: load_floor_kernel()),
        ("isolated", "bearings.force_along_path",
         lambda: bearing_force_path(SingleConcaveSliding(2.0, 0.05), np.zeros(3))),
        ("friction", "chain_run.simulate_chain", lambda: simulate_friction(stack.body, pulse, 0.5)),
    ]


#: The driver whose absence from the disk cache makes a group cold (module, function).
GROUP_DRIVERS = {"rigid": ("rigid", "simulate_rigid"), "isolated": ("driver", "simulate_core"),
                 "plinth": ("stack", "simulate_stack"), "plinth-bearings": ("stack_linear", "simulate_stack_linear"),
                 "friction": ("chain_run", "simulate_chain")}


def compile_group(group: str) -> None:
    """Make the first calls of ``group`` (in a child process of :func:`start`)."""
    for g, _, call in first_calls():
        if g == group:
            call()


def cold_groups() -> list[str]:
    """The groups whose driver numba's disk cache lacks for the current sources (none when it cannot tell)."""
    import importlib

    from rockcli.kernels.batch import _cached

    cold = []
    for group, (module, name) in GROUP_DRIVERS.items():
        driver = getattr(importlib.import_module(f"rockcli.kernels.{module}"), name)
        if _cached(driver) is False:
            cold.append(group)
    return cold


def start() -> list[subprocess.Popen]:
    """One child process compiling each cold group into the disk cache; the children, to :func:`stop` at the end."""
    if os.environ.get("ROCKCLI_TEST_COMPILE_AHEAD", "1") == "0" or os.environ.get("NUMBA_DISABLE_JIT") == "1":
        return []
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), str(ROOT / "tests"),
                                                                    os.environ.get("PYTHONPATH")])))
    children = []
    for group in cold_groups():
        try:
            children.append(subprocess.Popen(
                [sys.executable, "-c", f"import kernel_first_calls as k; k.compile_group({group!r})"], cwd=ROOT,
                env=env, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        except OSError:
            break
    return children


def stop(children: list[subprocess.Popen]) -> None:
    """Stop the children still compiling (the suite is over: what they would write, no test needs)."""
    for child in children:
        if child.poll() is None:
            child.kill()
        child.wait()
