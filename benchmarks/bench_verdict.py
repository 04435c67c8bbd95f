"""Verdict-only speed: a 200 x 200 rigid-foundation pulse grid through ``simulate_many``.

Prints wall time and right-hand-side evaluations with and without the early stop during the
excitation (P4 in ``rockcli.kernels.rigid``) and checks that the verdicts agree. Figures
only, no assertions on time. Run: ``python benchmarks/bench_verdict.py [--n 200]``.
"""

from __future__ import annotations

import argparse
import math
import time

import numpy as np

from rockcli.models import Block, Rigid
from rockcli.pulses import make_pulse
from rockcli.solve import simulate_many
from rockcli.io.units import G


def grid_jobs(n: int, shape: str = "ricker-sym", alpha_deg: float = 10.0):
    block = Block.from_degrees(1.0, alpha_deg)
    jobs = []
    for wpp in np.linspace(0.5, 12.0, n):
        Tp = 2 * math.pi / (wpp * block.p)
        for ap in np.linspace(0.0, 10.0, n)[1:].tolist() + [10.0 + 10.0 / n]:
            jobs.append((block, Rigid(), make_pulse(shape, ap * G * math.tan(block.alpha), Tp)))
    return jobs


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--n", type=int, default=200)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    simulate_many(grid_jobs(4))  # load the compiled kernels
    t0 = time.perf_counter()
    jobs = grid_jobs(args.n)
    t_build = time.perf_counter() - t0
    print(f"{len(jobs)} scenes (alpha = 10 deg, symmetric Ricker, wp/p 0.5-12, ap/(g tan alpha) 0.05-10); "
          f"building the jobs: {t_build:.2f} s")
    results = {}
    for early in (False, True):
        times = []
        for _ in range(args.repeat):
            t0 = time.perf_counter()
            res = simulate_many(jobs, early=early)
            times.append(time.perf_counter() - t0)
        results[early] = res
        print(f"early={early!s:5}  median {np.median(times):.2f} s (min {min(times):.2f})  "
              f"RHS evaluations {sum(r.nfev for r in res):,}  steps {sum(r.steps for r in res):,}  "
              f"overturned {sum(r.overturned for r in res)}")
    same = sum(a.verdict == b.verdict for a, b in zip(results[False], results[True]))
    print(f"verdicts equal in {same} of {len(jobs)} scenes")


if __name__ == "__main__":
    main()
