"""Rocking and sliding (friction as a model) against rocking alone: CPU per verdict-only run.

    ROCKCLI_RECORDS=../shared/records python benchmarks/bench_friction.py [--rounds 5]

Scenes (each under the ten Table II records found in ROCKCLI_RECORDS, at scale 1): the statue (1.79 m x 0.5 m)
alone and on a plinth 1.0 m x 0.6 m, a squat crate (0.5 m x 1.0 m, mu = 0.2: it slides), on the rigid ground and
on linear bearings (T_b = 2.5 s, xi = 0.1, gamma = 0.2). For each: the rocking model's run
(``simulate``/``simulate_stack``) and the friction model's (``simulate_friction``, the kernel itself, without the
shortcut of the batch that hands back the rocking run when nothing slid), CPU per run (the median of the rounds
over the records), the ratio, the steps and on how many records
the two agree that the body topples or not. No assertions: figures only.
"""

from __future__ import annotations

import argparse
import sys
import time

import numpy as np

from rockcli.models import Block, LinearIsolation, Plinth, Stack


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args(argv)
    from rockcli.assess.excitations import resolve_excitations
    from rockcli.solve import simulate, simulate_stack
    from rockcli.solve.slide import simulate_friction

    recs = [e.motion for e in resolve_excitations(None, "record")[0] if not e.error]
    if not recs:
        print("no Table II records found: set ROCKCLI_RECORDS")
        return 1
    statue = Block.from_dimensions(1.79, 0.5, "statue")
    crate = Block.from_dimensions(0.5, 1.0, "crate")
    stack = Stack(statue, Plinth(1.0, 0.6))
    lin = LinearIsolation(T_b=2.5, xi=0.1, gamma=0.2)
    cases = [
        ("statue, ground, mu 0.5", lambda r: simulate(statue, None, r), lambda r: simulate_friction(statue, r, 0.5)),
        ("statue, ground, mu 10", lambda r: simulate(statue, None, r), lambda r: simulate_friction(statue, r, 10)),
        ("crate, ground, mu 0.2", lambda r: simulate(crate, None, r), lambda r: simulate_friction(crate, r, 0.2)),
        ("statue on plinth, ground, mu 0.5", lambda r: simulate_stack(stack, r),
         lambda r: simulate_friction(stack, r, 0.5)),
        ("statue, linear bearings, mu 0.5", lambda r: simulate(statue, lin, r),
         lambda r: simulate_friction(statue, r, 0.5, lin)),
        ("statue on plinth, linear, mu 0.5", lambda r: simulate_stack(stack, r, isolation=lin),
         lambda r: simulate_friction(stack, r, 0.5, lin)),
    ]
    for _, rock, fric in cases:  # compiled / loaded before the clock
        rock(recs[0])
        fric(recs[0])
    print(f"{len(recs)} records, median of {args.rounds} rounds, CPU per run")
    for name, rock, fric in cases:
        out = []
        for f in (rock, fric):
            times, steps, verdicts = [], 0, []
            for k in range(args.rounds):
                t0 = time.process_time()
                rs = [f(r) for r in recs]
                times.append(time.process_time() - t0)
                if k == 0:
                    steps = sum(getattr(r, "steps", 0) for r in rs)
                    verdicts = [r.verdict == "overturned" for r in rs]
            out.append((float(np.median(times)) / len(recs), steps, verdicts))
        (t1, s1, v1), (t2, s2, v2) = out
        same = sum(a == b for a, b in zip(v1, v2))
        print(f"{name:34s} rocking {1e3 * t1:7.2f} ms ({s1} steps)  friction {1e3 * t2:7.2f} ms ({s2} steps)  "
              f"ratio {t2 / t1:5.1f}  topple or not alike {same}/{len(recs)}", flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
