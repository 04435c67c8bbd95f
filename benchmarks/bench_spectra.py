"""Benchmark of ``rockcli spectrum``: 200 x 200 maps, the Table I search, and the cold start.

Prints (no assertions):

1. wall time of the whole process (median and min of ``--repeat`` runs, warm kernel cache):
   ``spectrum overturning --alpha 10`` (200 x 200 rigid map; early stops, the default), the same
   with ``--isolation linear:TbTp=2,xi=0.05,gamma=0.01`` and with ``--isolation scss:TbTp=2,mu=0.05``,
   the rigid and linear ones also with ``--full-peaks``,
   ``spectrum critical-size --xi 0.05`` (Table I, one run), and ``rockcli --help``;
2. the split of the rigid and linear maps inside one process: imports, loading the compiled
   kernels, building the 40,000 scenes, the kernel (wall and CPU), with cells/s and right-hand sides;
3. with ``--cold``: the first run with an empty numba cache (``NUMBA_CACHE_DIR`` pointed at a new
   folder, so the real cache is left alone): time until the kernels are ready for the rigid map,
   for the linear one (and which kernel functions were compiled more than once), and the whole
   rigid map command.

The machine may be shared with other jobs: CPU time shows the work, wall time the wait too.

Usage (from the repository root)::

    python benchmarks/bench_spectra.py [--repeat 3] [--cold] [--skip-table]
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
LIN = "linear:TbTp=2,xi=0.05,gamma=0.01"
SCSS = "scss:TbTp=2,mu=0.05"

# printed after a cold run: each kernel function numba compiled for more than one set of argument
# types (a literal int argument is a type of its own, so one more copy of the function to compile)
SPECIALISATIONS = r"""
import importlib, pkgutil
import rockcli.kernels as K
for m in pkgutil.iter_modules(K.__path__):
    mod = importlib.import_module("rockcli.kernels." + m.name)
    for name, f in vars(mod).items():
        if hasattr(f, "signatures") and f.py_func.__module__ == mod.__name__ and len(f.signatures) > 1:
            print(f"{m.name}.{name} x{len(f.signatures)}")
"""

SPLIT = r"""
import time, json, sys
w0, c0 = time.perf_counter(), time.process_time()
marks = []
def mark(name):
    marks.append((name, time.perf_counter(), time.process_time()))
from rockcli import spectra as S
from rockcli import solve
mark("imports (numpy, rockcli.spectra)")
import rockcli.kernels
mark("import numba + rockcli.kernels")
S.overturning_map(10, "ricker-sym", ISO, S.Grid(1, 2, 2), S.Grid(1, 2, 2))
mark("loading the compiled kernels (first call)")
orig = solve.simulate_verdicts
stats = {}
def timed(jobs, **kw):
    t, c = time.perf_counter(), time.process_time()
    v = orig(jobs, **kw)
    stats["kernel"] = (time.perf_counter() - t, time.process_time() - c)
    stats["nfev"] = int(v.nfev.sum())
    return v
solve.simulate_verdicts = timed
t = time.perf_counter()
m = S.overturning_map(10, "ricker-sym", ISO, S.Grid(0.5, 12, 200), S.Grid(0, 10, 200), early=EARLY)
mark("the 200 x 200 map (scenes + kernel)")
print(json.dumps({"w0": w0, "c0": c0, "marks": marks, "stats": stats,
                  "overturned": int(m.overturned.sum())}))
"""


def run(args, env, cwd=ROOT):
    t = time.perf_counter()
    subprocess.run(args, env=env, cwd=cwd, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t


def whole(args, repeat, env):
    times = [run(args, env) for _ in range(repeat)]
    return statistics.median(times), min(times)


def split(iso, early, env):
    out = subprocess.run([sys.executable, "-c", f"ISO = {iso!r}\nEARLY = {early!r}\n" + SPLIT], env=env, cwd=ROOT,
                         check=True,
                         capture_output=True, text=True).stdout
    d = json.loads(out.strip().splitlines()[-1])
    prev_w, prev_c = d["w0"], d["c0"]
    rows = []
    for name, w, c in d["marks"]:
        rows.append((name, w - prev_w, c - prev_c))
        prev_w, prev_c = w, c
    kw, kc = d["stats"]["kernel"]
    total = rows[-1][1]
    rows[-1] = ("  of which building the 40,000 scenes", total - kw, rows[-1][2] - kc)
    rows.append(("  of which the kernel (simulate_batch, all cores)", kw, kc))
    return rows, d["stats"]["nfev"], kw


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--cold", action="store_true", help="also time a run with an empty numba cache")
    parser.add_argument("--skip-table", action="store_true", help="leave out the Table I run (~30 s)")
    opts = parser.parse_args()
    env = dict(os.environ)
    env["PYTHONPATH"] = str(ROOT) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    # the console script a user runs (rockcli.cli:run), in this interpreter
    base = [sys.executable, "-c", "import sys; from rockcli.cli import run; sys.argv[0] = 'rockcli'; run()"]
    rigid = base + ["spectrum", "overturning", "--alpha", "10"]
    linear = rigid + ["--isolation", LIN]
    for iso in (LIN, SCSS):  # warm the kernel cache (both drivers)
        run(base + ["spectrum", "overturning", "--alpha", "10", "--wp-over-p", "1:2:2", "--ap", "1:2:2", "--isolation", iso],
            env)
    print(f"whole process, median (min) of {opts.repeat} runs, {os.cpu_count()} cores, warm cache "
          f"(machine shared with other jobs: noisy):")
    for label, args, n in (("rockcli --help (start-up floor)", base + ["--help"], opts.repeat),
                           ("overturning --alpha 10 (200 x 200, rigid)", rigid, opts.repeat),
                           ("  ... --full-peaks", rigid + ["--full-peaks"], opts.repeat),
                           ("  ... --isolation " + LIN, linear, opts.repeat),
                           ("  ... --isolation " + LIN + " --full-peaks", linear + ["--full-peaks"], opts.repeat),
                           ("  ... --isolation " + SCSS, rigid + ["--isolation", SCSS], 1),
                           ("critical-size (Table I: defaults, --xi 0.05)", base + ["spectrum", "critical-size", "--xi",
                                                                                    "0.05"],
                            0 if opts.skip_table else 1)):
        if n == 0:
            continue
        med, best = whole(args, n, env)
        print(f"  {label:60s} {med:6.2f} s ({best:.2f} s)")

    for iso, early in (("none", True), ("none", False), (LIN, True)):
        rows, nfev, kw = split(iso, early, env)
        print(f"\nsplit of one 200 x 200 map in a fresh process, isolation {iso}{', early' if early else ''} "
              f"(wall / CPU):")
        for name, w, c in rows:
            print(f"  {name:52s} {w:6.3f} s / {c:6.3f} s")
        print(f"  {40000 / kw:,.0f} cells/s, {nfev:,} right-hand sides ({nfev / 40000:,.0f} per cell)")

    if opts.cold:
        for label, iso in (("rigid", "none"), ("linear", LIN)):
            cache = tempfile.mkdtemp(prefix="numba-cold-")
            cold_env = dict(env, NUMBA_CACHE_DIR=cache)
            code = ("import time; t = time.perf_counter()\n"
                    "from rockcli import spectra as S\n"
                    f"S.overturning_map(10, 'ricker-sym', {iso!r}, S.Grid(1, 2, 2), S.Grid(1, 2, 2))\n"
                    "print(time.perf_counter() - t)\n" + SPECIALISATIONS)
            t = time.perf_counter()
            out = subprocess.run([sys.executable, "-c", code], env=cold_env, cwd=ROOT, check=True,
                                 capture_output=True, text=True).stdout.splitlines()
            total = time.perf_counter() - t
            print(f"\ncold numba cache, {label} map: kernels ready after {float(out[0]):.1f} s "
                  f"(process {total:.1f} s)")
            print("  kernel functions compiled more than once (one per distinct argument types): "
                  + (", ".join(out[1:]) or "none"))
            if iso == "none":
                shutil.rmtree(cache, ignore_errors=True)
                cold_env = dict(env, NUMBA_CACHE_DIR=tempfile.mkdtemp(prefix="numba-cold-"))
                print(f"  overturning --alpha 10 (200 x 200, rigid) with an empty cache, whole process "
                      f"{run(rigid, cold_env):.2f} s")
                shutil.rmtree(cold_env["NUMBA_CACHE_DIR"], ignore_errors=True)
            shutil.rmtree(cache, ignore_errors=True)


if __name__ == "__main__":
    main()
