"""Benchmark of the default column assessment (``rockcli assess column bassae nemea``), warm caches.

Prints (no assertions):

1. wall time of the whole process, median of ``--repeat`` runs, with and without the margin and
   with ``--csv``;
2. the split of one run inside a fresh process: start-up/imports, reading the records, loading
   the compiled kernels (first call), the 80 runs, the margin search, the report (pandas + CSV),
   each as wall and CPU time (the machine may be shared: CPU time shows the work, wall the wait).

Usage::

    ROCKCLI_RECORDS=../shared/records python benchmarks/bench_assess.py [--repeat 5]
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

PHASES = r"""
import time, json
c0, w0 = time.process_time(), time.perf_counter()
marks = []
def mark(name):
    marks.append((name, time.perf_counter(), time.process_time()))
import click
from rockcli.cli import main
from rockcli import assess as A
from rockcli.solve import simulate_many
import rockcli.kernels
mark("start-up and imports (click, numpy, numba, rockcli)")
xs, unavailable = A.resolve_excitations(None)
blocks = [A.parse_column_spec("bassae"), A.parse_column_spec("nemea")]
confs = A.parse_configurations(None)
mark(f"reading the records ({sum(x.kind == 'record' for x in xs)} files)")
simulate_many([(blocks[0], confs[0].foundation, xs[0].motion)])
mark("loading the compiled kernels (first call)")
a = A.run_assessment(blocks, xs, confs, margin=False, unavailable=unavailable)
mark(f"the {len(a.rows)} runs")
scenes = [(b, c.foundation, x.motion) for b in blocks for x in xs for c in confs]
known = simulate_many(scenes)
t = time.perf_counter()
import rockcli.solve as S
n, many = [0], S.simulate_many
def counted(jobs, **kw):
    jobs = list(jobs)
    n[0] += len(jobs)
    return many(jobs, **kw)
S.simulate_many = counted
A.find_overturn_scales(scenes, known=known)
S.simulate_many = many
mark(f"margin ({n[0]} runs: scan + bisection)")
from rockcli.report.tables import format_matrix, write_assessment_csv
a = A.run_assessment(blocks, xs, confs, margin=False, unavailable=unavailable)
format_matrix(a)
write_assessment_csv(a, OUT)
mark("report (pandas import, CSV)")
print(json.dumps({"w0": w0, "c0": c0, "marks": marks}))
"""


def whole(args, repeat, env):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        subprocess.run(args, env=env, check=True, stdout=subprocess.DEVNULL)
        times.append(time.perf_counter() - t)
    return statistics.median(times), min(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    opts = parser.parse_args()
    env = dict(os.environ)
    if not env.get("ROCKCLI_RECORDS"):
        print("note: ROCKCLI_RECORDS is not set: the records run as their catalogued pulses")
    exe = shutil.which("rockcli") or sys.executable
    base = [exe] if exe.endswith("rockcli") else [exe, "-m", "rockcli"]
    tmp = tempfile.mkdtemp()
    csv = os.path.join(tmp, "table.csv")
    subprocess.run(base + ["assess", "column", "bassae", "nemea"], env=env, check=True,
                   stdout=subprocess.DEVNULL)  # warm the kernel cache
    print(f"whole process, median (min) of {opts.repeat} runs, {os.cpu_count()} cores:")
    for label, extra in (("assess column bassae nemea", []),
                         ("  ... --csv table.csv", ["--csv", csv]),
                         ("  ... --no-margin", ["--no-margin"]),
                         ("rockcli --help (start-up floor)", None)):
        args = base + ["--help"] if extra is None else base + ["assess", "column", "bassae", "nemea"] + extra
        med, best = whole(args, opts.repeat, env)
        print(f"  {label:34s} {med:6.2f} s ({best:.2f} s)")

    import json

    out = subprocess.run([sys.executable, "-c", f"OUT = {csv!r}\n" + PHASES], env=env, check=True,
                         capture_output=True, text=True).stdout
    data = json.loads(out.strip().splitlines()[-1])
    print("\nsplit of one run in a fresh process (wall / CPU):")
    prev_w, prev_c = data["w0"], data["c0"]
    for name, w, c in data["marks"]:
        print(f"  {name:52s} {w - prev_w:6.3f} s / {c - prev_c:6.3f} s")
        prev_w, prev_c = w, c
    print("  (interpreter start before the first line: see 'rockcli --help' above)")
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
