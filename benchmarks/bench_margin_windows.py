"""Does the margin search of ``assess column`` step over overturning windows? (issue 28)

For every scene of ``rockcli assess column bassae nemea`` (the default records and isolation), runs
the scale factors ``f0 (1 + FINE)^k`` from ``f0 = 0.1`` up to the ``overturn_scale`` the search reports
(verdict-only, early stops, as the search runs them) and prints the scenes where a smaller factor
already overturns, with the surviving runs' peaks theta_max/alpha next to the window. No assertions.

    PYTHONPATH=$PWD ROCKCLI_RECORDS=/work/shared/records python benchmarks/bench_margin_windows.py [--fine 0.01]
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--columns", default="bassae,nemea")
    ap.add_argument("--fine", type=float, default=0.01)
    ap.add_argument("--grid", choices=("default", "refined"), default="default")
    args = ap.parse_args()
    from rockcli.assess import (find_overturn_scales, parse_column_spec, parse_configurations,
                                resolve_excitations)
    from rockcli.assess.margin import _scaled_job
    from rockcli.solve import simulate_many

    columns = [parse_column_spec(c) for c in args.columns.split(",")]
    excitations, _ = resolve_excitations(None, "auto")
    configurations = parse_configurations(None)
    scenes = [(b, c.foundation, x.motion) for b in columns for x in excitations for c in configurations
              if x.motion is not None]
    names = [f"{b.name} {x.label} {c.header}" for b in columns for x in excitations for c in configurations
             if x.motion is not None]
    t0 = time.perf_counter()
    found = find_overturn_scales(scenes)
    t_search = time.perf_counter() - t0
    jobs, where = [], []
    for i, (hi, lo, note) in enumerate(found):
        top = hi if math.isfinite(hi) else 4.0
        ks = np.arange(0, int(math.log(top / 0.1) / math.log1p(args.fine)) + 1)
        for f in 0.1 * (1 + args.fine) ** ks:
            jobs.append(_scaled_job(*scenes[i], float(f)))
            where.append((i, float(f)))
    t0 = time.perf_counter()
    res = simulate_many(jobs, early=True)
    t_fine = time.perf_counter() - t0
    print(f"{len(scenes)} scenes; search {t_search:.1f} s; fine grid ({args.fine:g}) {len(jobs)} runs {t_fine:.1f} s")
    per = {}
    for (i, f), r in zip(where, res):
        per.setdefault(i, []).append((f, r.overturned, r.theta_max_over_alpha))
    missed = 0
    for i, rows in per.items():
        hi, lo, _ = found[i]
        f = np.array([r[0] for r in rows])
        o = np.array([r[1] for r in rows])
        pk = np.array([r[2] for r in rows])
        if not o.any():
            continue
        j = int(np.argmax(o))
        first = f[j]
        if not math.isfinite(hi) or first < lo * (1 - 1e-9):
            missed += 1
            e = j + int(np.argmin(o[j:])) if not o[j:].all() else o.size
            print(f"  {names[i]}: overturns at {first:.4f} ({e - j} fine values wide), reported "
                  f"{hi:.4f} (survives {lo:.4f}); peaks below: {np.round(pk[max(0, j - 5):j], 2)}")
    print(f"{missed} of {len(scenes)} scenes: a factor below the reported margin overturns")


if __name__ == "__main__":
    main()
