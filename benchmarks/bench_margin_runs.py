"""Runs, steps and time of the margin search of the README's main job, by foundation.

``rockcli assess column bassae nemea`` (80 scenes: 2 columns x 10 records x 4 configurations, 20 on a
rigid foundation, 60 on linear bearings) through :func:`rockcli.assess.run_assessment` with its margins,
counting every run the solver makes (:func:`rockcli.solve.simulate_many` wrapped) and its steps.

Prints (no assertions): per phase (the scenes at 1x, the margin search) and foundation the runs, the
steps per run and the right-hand-side evaluations per run; the runs per margin; the CPU time (all
threads) and wall time of each phase, with the load average before the run. ``--fill``/``--no-fill``
chooses whether the search keeps idle cores busy (:func:`rockcli.assess.find_overturn_scales`).
``--csv PATH`` writes the rows as ``assess column --csv`` does (to compare with a baseline).

Usage::

    ROCKCLI_RECORDS=../shared/records python benchmarks/bench_margin_runs.py [--no-fill] [--csv out/t.csv]
"""

from __future__ import annotations

import argparse
import collections
import os
import sys
import time


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--fill", action=argparse.BooleanOptionalAction, default=True)
    ap.add_argument("--csv", help="write the rows here (the CSV of assess column --csv)")
    args = ap.parse_args(argv)

    import rockcli.solve as solve
    from rockcli.assess import parse_column_spec, parse_configurations, resolve_excitations, run_assessment
    from rockcli.assess import margin as margin_mod
    from rockcli.models import LinearIsolation, Rigid

    original = solve.simulate_many
    stats = collections.defaultdict(lambda: [0, 0, 0])
    phase = ["scenes"]

    calls = collections.Counter()

    def counted(jobs, **kw):
        calls[phase[0]] += 1
        res = original(jobs, **kw)
        for job, r in zip(jobs, res):
            f = job[1]
            kind = "rigid" if isinstance(f, Rigid) else ("linear" if isinstance(f, LinearIsolation) else "other")
            st = stats[(phase[0], kind)]
            st[0] += 1
            st[1] += getattr(r, "steps", 0)
            st[2] += getattr(r, "nfev", 0)
        return res

    solve.simulate_many = counted
    find = margin_mod.find_overturn_scales
    times = {}

    def timed_find(*a, **k):
        phase[0] = "margin"
        c0, w0 = time.process_time(), time.perf_counter()
        out = find(*a, fill=args.fill, **k)
        times["margin"] = (time.process_time() - c0, time.perf_counter() - w0)
        return out

    margin_mod.find_overturn_scales = timed_find  # search_groups calls it by this name
    columns = [parse_column_spec("bassae"), parse_column_spec("nemea")]
    excitations, unavailable = resolve_excitations(None, "auto")
    configurations = parse_configurations(None)
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}; threads: {solve._threads()}")
    c0, w0 = time.process_time(), time.perf_counter()
    result = run_assessment(columns, excitations, configurations, margin=True, unavailable=unavailable)
    total = (time.process_time() - c0, time.perf_counter() - w0)
    margins = sum(1 for r in result.rows if not r.error)
    print(f"{'phase':8s} {'foundation':10s} {'runs':>7s} {'steps/run':>10s} {'nfev/run':>10s}")
    for (ph, kind), (runs, steps, nfev) in sorted(stats.items(), reverse=True):
        print(f"{ph:8s} {kind:10s} {runs:7d} {steps / max(runs, 1):10.0f} {nfev / max(runs, 1):10.0f}")
    runs_margin = sum(v[0] for (ph, _), v in stats.items() if ph == "margin")
    by_kind = collections.Counter(type(c.foundation).__name__ for c in configurations)
    print(f"margin runs: {runs_margin} for {margins} margins ({runs_margin / max(margins, 1):.1f} per margin); "
          f"configurations {dict(by_kind)}; {calls['margin']} batches (rounds of the scan and the bisection)")
    for kind in ("rigid", "linear"):
        n_kind = sum(1 for r in result.rows if not r.error and (r.isolation == "none") == (kind == "rigid"))
        runs = stats[("margin", kind)][0]
        print(f"  {kind}: {runs} runs for {n_kind} margins ({runs / max(n_kind, 1):.1f} per margin)")
    cpu, wall = times.get("margin", (float("nan"), float("nan")))
    print(f"margin search: {cpu:.1f} s CPU, {wall:.1f} s wall (fill={args.fill}); whole assessment: "
          f"{total[0]:.1f} s CPU, {total[1]:.1f} s wall")
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    if args.csv:
        from rockcli.report.tables import write_assessment_csv

        write_assessment_csv(result, args.csv)
    return 0


if __name__ == "__main__":
    sys.exit(main())
