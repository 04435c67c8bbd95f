"""Benchmark of ``rockcli assess fragility``: two columns x 4 configurations over 20 records, warm caches.

Prints (no assertions):

1. wall time of the whole process ``python -m rockcli assess fragility bassae nemea --records <20 files>``
   (median and min of ``--repeat`` runs, kernel cache warm);
2. the split of one run in a fresh process: start-up and imports, reading the records, loading the
   compiled kernels, the margin searches (the scan and bisection runs, counted), the maximum
   likelihood fits with the bootstrap, the report (pandas, CSV, figure), as wall and CPU time (the
   machine may be shared: CPU time shows the work, wall the wait).

The 20 records are the first 20 files (sorted by folder, then name) of the ROCKCLI_RECORDS folders
that load as records (catalogue files as the catalogue says, others as they state).

Usage::

    ROCKCLI_RECORDS=../shared/records:../shared/records/extra python benchmarks/bench_fragility.py [--repeat 3]
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

REPO = Path(__file__).resolve().parents[1]

PHASES = r"""
import time, json
c0, w0 = time.process_time(), time.perf_counter()
marks = []
def mark(name):
    marks.append((name, time.perf_counter(), time.process_time()))
import click
from rockcli.cli import main
from rockcli import assess as A
from rockcli.assess import fragility as F
from rockcli.solve import simulate_many
import rockcli.kernels
mark("start-up and imports (click, numpy, numba, rockcli)")
xs, _ = A.resolve_excitations(FILES, "record")
mark(f"reading the records ({len(xs)} files)")
blocks = [A.parse_column_spec("bassae"), A.parse_column_spec("nemea")]
confs = A.parse_configurations(None)
simulate_many([(blocks[0], confs[0].foundation, xs[0].motion)])
mark("loading the compiled kernels (first call)")
n = [0]
fr = F.run_fragility(blocks, xs, confs, progress=lambda k: n.__setitem__(0, n[0] + k))
t = fr.timings
marks.append((f"margin searches ({len(blocks) * len(xs) * len(confs)} scenes, {n[0]} runs)",
              marks[-1][1] + t["im_s"] + t["margin_s"], None))
marks.append((f"MLE fits + bootstrap ({fr.n_boot} resamples x {len(fr.curves)} curves)",
              marks[-1][1] + t["fit_s"], None))
mark("(rest of run_fragility)")
from rockcli.report.fragility import format_fragility, plot_fragility, write_fragility_csv
format_fragility(fr)
write_fragility_csv(fr, OUT + ".csv")
plot_fragility(fr, OUT + ".png")
mark("report (pandas, CSV, matplotlib figure)")
print(json.dumps({"w0": w0, "c0": c0, "marks": marks,
                  "fits": [(c.column, c.configuration.header, c.median, c.beta) for c in fr.curves]}))
"""


def suite(n: int = 20) -> list[str]:
    """The first ``n`` files of the ROCKCLI_RECORDS folders that load as records."""
    sys.path.insert(0, str(REPO))
    from rockcli.assess import resolve_excitations

    folders = [p for p in os.environ.get("ROCKCLI_RECORDS", "").split(os.pathsep) if p and Path(p).is_dir()]
    files = []
    for folder in folders:
        xs, _ = resolve_excitations([folder], "record")
        files += [x.source for x in xs if x.motion is not None]
    return files[:n]


def whole(args, repeat, env):
    times = []
    for _ in range(repeat):
        t = time.perf_counter()
        subprocess.run(args, env=env, check=True, stdout=subprocess.DEVNULL, cwd=REPO)
        times.append(time.perf_counter() - t)
    return statistics.median(times), min(times)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    opts = parser.parse_args()
    env = dict(os.environ)
    files = suite(20)
    if len(files) < 20:
        print(f"note: only {len(files)} loadable records on ROCKCLI_RECORDS (wanted 20)")
    if not files:
        sys.exit("set ROCKCLI_RECORDS to folders of records")
    records = [a for f in files for a in ("--records", f)]
    base = [sys.executable, "-m", "rockcli", "assess", "fragility", "bassae", "nemea"] + records
    tmp = tempfile.mkdtemp()
    subprocess.run(base + ["--bootstrap", "10"], env=env, check=True, stdout=subprocess.DEVNULL,
                   cwd=REPO)  # warm the kernel cache
    print(f"whole process, median (min) of {opts.repeat} runs, {os.cpu_count()} cores, {len(files)} records:")
    for label, extra in (("assess fragility bassae nemea (4 configurations)", []),
                         ("  ... --csv --plot", ["--csv", os.path.join(tmp, "f.csv"), "--plot",
                                                 os.path.join(tmp, "f.png")])):
        med, best = whole(base + extra, opts.repeat, env)
        print(f"  {label:50s} {med:6.2f} s ({best:.2f} s)")

    code = f"FILES = {files!r}\nOUT = {os.path.join(tmp, 'p')!r}\n" + PHASES
    out = subprocess.run([sys.executable, "-c", code], env=env, check=True, capture_output=True, text=True,
                         cwd=REPO).stdout
    data = json.loads(out.strip().splitlines()[-1])
    print("\nsplit of one run in a fresh process (wall / CPU):")
    prev_w, prev_c = data["w0"], data["c0"]
    for name, w, c in data["marks"]:
        cpu = f"{c - prev_c:6.3f} s" if c is not None else "     -  "
        print(f"  {name:60s} {w - prev_w:6.3f} s / {cpu}")
        prev_w = w
        if c is not None:
            prev_c = c
    print("  (CPU of the margin and fit phases is in the '(rest of run_fragility)' line)")
    print("\nfits (median [g], beta):")
    for col, conf, med, beta in data["fits"]:
        print(f"  {col:7s} {conf:8s} {med:7.3f} {beta:6.2f}")
    shutil.rmtree(tmp, ignore_errors=True)


if __name__ == "__main__":
    main()
