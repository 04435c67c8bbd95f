"""The early stops of an isolated base (P9, P9s in ``rockcli.kernels.driver_end``): what they save,
and the larger checks that are too slow for the test suite. Prints figures, asserts nothing.

``--jobs FILE``: the verdict-only early runs that the margin search of the main job
(``assess column bassae nemea``) makes on linear bearings, written to FILE on the first call (a pickle)
and read from it afterwards, so that two versions of rockcli run the same list::

    ROCKCLI_RECORDS=../shared/records python benchmarks/bench_early_isolated.py --jobs /tmp/margin-jobs.pkl
    PYTHONPATH=/path/to/older/tree python benchmarks/bench_early_isolated.py --jobs /tmp/margin-jobs.pkl

prints runs, steps per run and CPU per run (process time, all threads), by verdict.

``--linear N``, ``--sliding N``: N random scenes of ``tests/test_early_isolated.py`` (other seeds) on linear,
or on SCSS / DCSS / lead-rubber bearings: early, verdict-only and (every tenth) full-history runs compared (the
suite runs 3,000 and 600). ``--reference N``: N scenes per bearing family and verdict proven by P9s during the
excitation, against the slow SciPy reference.
"""

from __future__ import annotations

import argparse
import collections
import math
import pickle
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))


def margin_jobs(path: Path):
    """The early runs of the main job's margin search on linear bearings (recorded once, then read)."""
    if path.exists():
        return pickle.loads(path.read_bytes())
    import rockcli.solve as S
    from rockcli import assess as A
    from rockcli.models import LinearIsolation

    xs, _ = A.resolve_excitations(None)
    blocks = [A.parse_column_spec("bassae"), A.parse_column_spec("nemea")]
    confs = A.parse_configurations(None)
    scenes = [(b, c.foundation, x.motion) for b in blocks for x in xs for c in confs if x.motion is not None]
    known = S.simulate_many(scenes)
    jobs, many = [], S.simulate_many

    def recording(js, **kw):
        js = list(js)
        if kw.get("early"):
            jobs.extend(j for j in js if isinstance(j[1], LinearIsolation))
        return many(js, **kw)

    S.simulate_many = recording
    try:
        A.find_overturn_scales(scenes, known=known)
    finally:
        S.simulate_many = many
    path.write_bytes(pickle.dumps(jobs))
    return jobs


def bench_jobs(path: Path) -> None:
    from rockcli.solve import simulate_many

    jobs = margin_jobs(path)
    simulate_many(jobs[:2], early=True)  # load the kernel
    c0 = time.process_time()
    res = simulate_many(jobs, early=True)
    cpu = time.process_time() - c0
    by = collections.defaultdict(lambda: [0, 0])
    for r in res:
        by[r.verdict][0] += 1
        by[r.verdict][1] += r.steps
    steps = sum(r.steps for r in res)
    print(f"{len(jobs)} early runs on linear bearings: {steps / len(jobs):.0f} steps per run, "
          f"{1e3 * cpu / len(jobs):.2f} ms CPU per run ({cpu:.1f} s CPU in all)")
    for v, (n, s) in sorted(by.items()):
        print(f"  {v:10s} {n:6d} runs, {s / n:7.0f} steps per run")
    print(f"  base's peak unknown (NaN) in {sum(math.isnan(r.base_disp_max_m) for r in res)} runs")


def bench_modes(kind: str, n: int) -> None:
    import test_early_isolated as T

    jobs = T._linear_scenes(n, 133) if kind == "linear" else T._sliding_scenes(n, 134)
    c0 = time.process_time()
    early, bad, during = T._compare(jobs, history_every=10)
    print(f"{n} {kind} scenes: {len(bad)} mismatches, {during} proven during the excitation, "
          f"verdicts {dict(collections.Counter(r.verdict for r in early))}, {time.process_time() - c0:.0f} s CPU")
    for b in bad[:10]:
        print("  mismatch", b)


def bench_reference(n: int) -> None:
    import test_early_isolated as T
    from naive import reference_simulate
    from rockcli.solve import simulate_many

    jobs = T._sliding_scenes(60 * n, 136)
    early = simulate_many(jobs, early=True)
    picked = collections.defaultdict(list)
    for j, r in zip(jobs, early):
        if r.t_settled_s < T._t_exc_end(j) and not r.overturned and len(picked[(type(j[1]).__name__, r.verdict)]) < n:
            picked[(type(j[1]).__name__, r.verdict)].append((j, r))
    agree = total = 0
    for key, items in sorted(picked.items()):
        for j, r in items:
            c0 = time.process_time()
            ref = reference_simulate(j[0], j[1], j[2].scaled(j[3]), align=True, method="Radau")
            total += 1
            agree += ref.verdict == r.verdict
            print(f"  {key[0]:22s} {r.verdict:9s} reference {ref.verdict:9s} ({time.process_time() - c0:.1f} s CPU)")
    print(f"reference: {agree} of {total} scenes proven by P9s agree")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--jobs", type=Path, help="pickle of the margin search's early runs on linear bearings")
    ap.add_argument("--linear", type=int, default=0, help="random linear scenes to compare in three modes")
    ap.add_argument("--sliding", type=int, default=0, help="random sliding scenes to compare in three modes")
    ap.add_argument("--reference", type=int, default=0, help="sliding scenes per family and verdict vs the reference")
    args = ap.parse_args()
    if args.jobs:
        bench_jobs(args.jobs)
    if args.linear:
        bench_modes("linear", args.linear)
    if args.sliding:
        bench_modes("sliding", args.sliding)
    if args.reference:
        bench_reference(args.reference)


if __name__ == "__main__":
    main()
