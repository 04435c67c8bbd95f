"""Cold-compile CPU of each compiled driver (numba), with an empty numba cache; the real cache is left alone.

One child process (``NUMBA_CACHE_DIR`` pointed at a new, empty folder) makes the first call of each driver in a
fixed order, with the argument types :mod:`rockcli.solve` passes (``tests/kernel_first_calls.py``, whose groups
the test suite compiles ahead on a fresh clone): the rigid foundation, the rigid foundation under
a vertical motion, the isolated base, the body on its plinth (rigid foundation, then bearings), the three batch
kernels, and the two kernels called from Python elsewhere (the lift-off floor, a bearing's loop). It prints the
CPU time of each outermost compile (a driver compiles the callees that an earlier driver has not compiled already,
so the order matters and is fixed), their total, and each kernel function numba compiled for more than one set of
argument types (a literal int argument, or a different array layout, is a type of its own: one more copy of the
function to compile and optimise).

With ``--callees`` it also prints the CPU of every compile nested inside the drivers (exclusive of the callees
it compiled itself), the largest first: where a driver's compile time goes.

The machine may be shared with other jobs: CPU time shows the work; repeat (``--repeat``) to see the spread.

Usage (from the repository root)::

    python benchmarks/bench_compile.py [--repeat 1] [--callees 30]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

CHILD = r"""
import json, math, sys, time, threading
import numpy as np
import numba.core.dispatcher as D

log = []  # (depth, name, cpu exclusive of nested compiles, signature)
local = threading.local()
orig = D.Dispatcher.compile

def compile(self, sig):
    stack = local.__dict__.setdefault("stack", [])
    stack.append(0.0)
    n = len(self.overloads)
    c = time.thread_time()
    try:
        return orig(self, sig)
    finally:
        total = time.thread_time() - c
        nested = stack.pop()
        if stack:
            stack[-1] += total
        if len(self.overloads) > n:  # a real compile (numba also calls this for a signature it has)
            f = self.py_func
            log.append((len(stack), f"{f.__module__.replace('rockcli.kernels.', '')}.{f.__qualname__}", total,
                        total - nested, str(sig)))

D.Dispatcher.compile = compile

sys.path.insert(0, sys.argv[1])
from kernel_first_calls import first_calls

steps = [(name, call) for _, name, call in first_calls()]
rows = []
for name, call in steps:
    n = len(log)
    c = time.process_time()
    call()
    rows.append((name, time.process_time() - c, sum(r[2] for r in log[n:] if r[0] == 0)))
counts = {}
for depth, name, total, own, sig in log:
    counts.setdefault(name, []).append(sig)
dups = {name: sigs for name, sigs in counts.items() if len(sigs) > 1}
print(json.dumps({"rows": rows, "log": log, "dups": dups}))
"""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=1, help="cold runs (each in a new process and cache folder)")
    parser.add_argument("--callees", type=int, default=0, metavar="N",
                        help="also print the N nested compiles of most CPU (exclusive of their own callees)")
    parser.add_argument("--signatures", action="store_true",
                        help="print the signatures of those compiled twice or more")
    parser.add_argument("--json", metavar="FILE", help="write every run's rows and compile log to FILE")
    opts = parser.parse_args()
    runs = []
    for _ in range(opts.repeat):
        cache = tempfile.mkdtemp(prefix="numba-cold-")
        try:
            env = dict(os.environ, NUMBA_CACHE_DIR=cache,
                       PYTHONPATH=os.pathsep.join(filter(None, [str(ROOT), os.environ.get("PYTHONPATH")])))
            child = subprocess.run([sys.executable, "-c", CHILD, str(ROOT / "tests")], env=env, cwd=ROOT,
                                   capture_output=True, text=True)
            if child.returncode != 0:
                sys.exit(f"the child process failed:\n{child.stderr}")
            out = child.stdout
        finally:
            shutil.rmtree(cache, ignore_errors=True)
        runs.append(json.loads(out.strip().splitlines()[-1]))
    names = [r[0] for r in runs[0]["rows"]]
    print(f"{'kernel (first call, in this order)':40s} " + " ".join(f"{'CPU s':>7s}" for _ in runs))
    for i, name in enumerate(names):
        print(f"{name:40s} " + " ".join(f"{run['rows'][i][1]:7.1f}" for run in runs))
    print(f"{'total':40s} " + " ".join(f"{sum(r[1] for r in run['rows']):7.1f}" for run in runs))
    dups = runs[-1]["dups"]
    print(f"\nkernel functions compiled more than once: {len(dups)}")
    for name, sigs in sorted(dups.items(), key=lambda kv: -len(kv[1])):
        print(f"  {name} x{len(sigs)}" + ("".join(f"\n      {sig[:300]}" for sig in sigs) if opts.signatures else ""))
    if opts.callees:
        own = {}
        for depth, name, total, excl, sig in runs[-1]["log"]:
            if depth > 0:
                own.setdefault(name, [0.0, 0])
                own[name][0] += excl
                own[name][1] += 1
        print(f"\nnested compiles by CPU (exclusive of their callees), the {opts.callees} largest:")
        for name, (cpu, n) in sorted(own.items(), key=lambda kv: -kv[1][0])[:opts.callees]:
            print(f"  {cpu:6.2f} s  x{n}  {name}")
    if opts.json:
        Path(opts.json).write_text(json.dumps(runs))


if __name__ == "__main__":
    main()
