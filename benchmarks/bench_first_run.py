"""Benchmark of the first run on a fresh install against the next one: the README's main job,
``rockcli assess column bassae nemea --csv table.csv``, cold and warm.

Cold: an empty numba cache (``NUMBA_CACHE_DIR`` a new temporary folder; the kernels' disk cache,
:mod:`rockcli.kernels.cache`, is all rockcli caches) and no Python bytecode (``PYTHONPYCACHEPREFIX``
a new temporary folder), as on a fresh clone. Warm: the same job again with those folders as the
cold run left them. Each repeat runs cold then warm back to back (the machine may be shared: the
pairs see the same load), and the load average is printed before each run.

Prints (no assertions):

1. per repeat: wall and CPU time (user + system, all threads) of the cold and the warm process,
   their ratio, the load average; then the medians and the median ratio cold / warm;
2. the kernels that compile in the job's own process (numba's cache misses, as :mod:`rockcli.compiling`
   reports them: the outermost function of each compile) with the wall and CPU time of each (medians
   of the cold runs; one compiled side by side in a child process is in the CPU total only), and how
   many compiles the warm runs needed (0: everything loaded from the cache).

Usage::

    ROCKCLI_RECORDS=../shared/records python benchmarks/bench_first_run.py [--repeat 3]
    python benchmarks/bench_first_run.py --repeat 1 -- assess column nemea --records RSN1119_KOBE_TAZ000.AT2

Arguments after ``--`` replace the job (a rockcli command line without ``rockcli``); ``--csv`` is
pointed into a temporary folder by the default job only.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

#: The job: runs the command line in this process with the compiles recorded, and prints them (JSON).
DRIVER = r"""
import json, sys, time
from rockcli import compiling
seen, open_ = [], {}
def start(name):
    open_[name] = (time.perf_counter(), time.thread_time())
def end(name, seconds):
    t0, c0 = open_.pop(name, (time.perf_counter(), time.thread_time()))
    seen.append({"kernel": name, "wall_s": seconds, "cpu_s": time.thread_time() - c0})
compiling.subscribe(start, end)
from rockcli.cli import main
try:
    main(sys.argv[1:], prog_name="rockcli")
except SystemExit as exc:
    code = exc.code
else:
    code = 0
sys.stdout.flush()
print("\n@@compiles " + json.dumps(seen), file=sys.stderr)
sys.exit(code)
"""

MAIN_JOB = ["assess", "column", "bassae", "nemea"]


def _run(args, env) -> dict:
    """One process: wall and CPU time, its exit code and the compiles it reported."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    load = os.getloadavg()[0]
    t0 = time.perf_counter()
    proc = subprocess.run([sys.executable, "-c", DRIVER, *args], env=env, stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    compiles = []
    for line in proc.stderr.splitlines():
        if line.startswith("@@compiles "):
            compiles = json.loads(line[len("@@compiles "):])
    if proc.returncode != 0:
        sys.exit(f"the job failed (exit {proc.returncode}):\n{proc.stderr[-2000:]}")
    return {"wall": wall, "cpu": cpu, "load": load, "compiles": compiles}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--repeat", type=int, default=3, help="cold + warm pairs (default 3)")
    parser.add_argument("job", nargs="*", help="the rockcli command line (default: the main job)")
    opts = parser.parse_args(argv)
    if not os.environ.get("ROCKCLI_RECORDS"):
        print("note: ROCKCLI_RECORDS is not set: records not in the repository run as their catalogued pulses")
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    work = tempfile.mkdtemp(prefix="rockcli-first-run-")
    job = opts.job or MAIN_JOB + ["--csv", os.path.join(work, "table.csv")]
    print(f"job: rockcli {' '.join(job)}")
    print(f"machine: {os.cpu_count()} cores; load average at the start {os.getloadavg()[0]:.2f} "
          f"(a shared machine: compare cold with the warm run next to it)")
    rows = []
    try:
        for k in range(opts.repeat):
            env = dict(os.environ, NUMBA_CACHE_DIR=os.path.join(work, f"numba-{k}"),
                       PYTHONPYCACHEPREFIX=os.path.join(work, f"pyc-{k}"),
                       PYTHONPATH=os.pathsep.join(filter(None, [repo, os.environ.get("PYTHONPATH")])))
            cold = _run(job, env)
            warm = _run(job, env)
            rows.append((cold, warm))
            print(f"  {k + 1}: cold {cold['wall']:6.1f} s wall {cold['cpu']:6.1f} s CPU (load {cold['load']:.1f}) | "
                  f"warm {warm['wall']:6.1f} s wall {warm['cpu']:6.1f} s CPU (load {warm['load']:.1f}) | "
                  f"cold/warm {cold['wall'] / warm['wall']:.2f} wall, {cold['cpu'] / warm['cpu']:.2f} CPU", flush=True)
    finally:
        shutil.rmtree(work, ignore_errors=True)
    med = statistics.median
    cw, ww = med(c["wall"] for c, _ in rows), med(w["wall"] for _, w in rows)
    cc, wc = med(c["cpu"] for c, _ in rows), med(w["cpu"] for _, w in rows)
    print(f"median: cold {cw:.1f} s, warm {ww:.1f} s wall (ratio {med(c['wall'] / w['wall'] for c, w in rows):.2f}); "
          f"CPU cold {cc:.1f} s, warm {wc:.1f} s (ratio {med(c['cpu'] / w['cpu'] for c, w in rows):.2f})")
    print("kernels compiled by the cold run (median over the cold runs):")
    names = list(dict.fromkeys(x["kernel"] for c, _ in rows for x in c["compiles"]))
    for name in names:
        got = [x for c, _ in rows for x in c["compiles"] if x["kernel"] == name]
        print(f"  {name:40s} {med(x['wall_s'] for x in got):6.1f} s wall {med(x['cpu_s'] for x in got):6.1f} s CPU "
              f"({len(got)} compile(s) in {len(rows)} run(s))")
    total = [sum(x["cpu_s"] for x in c["compiles"]) for c, _ in rows]
    print(f"  total compile CPU per cold run: {med(total):.1f} s; compiles in the warm runs: "
          f"{sum(len(w['compiles']) for _, w in rows)}")
    print("  (a kernel compiled side by side in a child process (rockcli.kernels.batch.prepare) is not listed;"
          " its CPU time is in the cold run's total)")


if __name__ == "__main__":
    main()
