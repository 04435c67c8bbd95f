"""Runs and CPU time of ``assess column bassae nemea --azimuth worst``, pair by pair, shared and unshared.

For each pair (default: the catalogue's own, as ``--azimuth worst`` without ``--records`` runs them; or the
``--records`` given, ``A+B`` or catalogue ids) :func:`rockcli.assess.run_assessment` runs every orientation
(``--azimuth-step``, 5 deg: 36) of the two columns on the four default configurations with margins, and
:func:`rockcli.assess.azimuth.collapse` keeps the most adverse one; every run the solver makes is counted
(:func:`rockcli.solve.simulate_many` wrapped) by phase and foundation.

``--unshared`` also runs the search of every orientation alone (no ``orientations``: each margin searched in
full, the neighbourhood of every orientation) and checks that the collapsed rows are identical, field for
field: the theorem of :mod:`rockcli.assess.azimuth` on real records. It costs several times more.

Prints (no assertions but the ``--unshared`` check): per pair, the runs at 1x and in the margin search, by
foundation, and the CPU time (all threads) of the shared search (and of the unshared one), with the load
average before and after.

Usage::

    ROCKCLI_RECORDS=../shared/records python benchmarks/bench_azimuth.py [--unshared] [--records A+B ...]
"""

from __future__ import annotations

import argparse
import collections
import dataclasses
import math
import os
import sys
import time


def _same(a, b) -> bool:
    return all(x == y or (isinstance(x, float) and isinstance(y, float) and math.isnan(x) and math.isnan(y))
               for x, y in zip(dataclasses.astuple(a), dataclasses.astuple(b)))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--records", action="append", help="a pair A+B or a catalogue id (repeatable)")
    ap.add_argument("--azimuth-step", type=float, default=5.0)
    ap.add_argument("--unshared", action="store_true", help="also run every orientation's full search and compare")
    ap.add_argument("--neighbourhood", action="store_true")
    args = ap.parse_args(argv)

    import rockcli.solve as solve
    from rockcli.assess import parse_column_spec, parse_configurations, resolve_excitations, run_assessment
    from rockcli.assess.azimuth import collapse, expand
    from rockcli.models import LinearIsolation, Rigid
    from rockcli.records.orientation import sweep_azimuths

    original = solve.simulate_many
    runs = collections.Counter()
    phase = ["1x"]

    def counted(jobs, **kw):
        for job in jobs:
            f = job[1]
            kind = "rigid" if isinstance(f, Rigid) else ("linear" if isinstance(f, LinearIsolation) else "other")
            runs[(phase[0], kind)] += 1
        return original(jobs, **kw)

    solve.simulate_many = counted
    import rockcli.assess.table as table_mod

    searched = table_mod.overturn_scales_chunked

    def search(*a, **k):
        phase[0] = "margin"
        try:
            return searched(*a, **k)
        finally:
            phase[0] = "neighbourhood"

    table_mod.overturn_scales_chunked = search

    columns = [parse_column_spec("bassae"), parse_column_spec("nemea")]
    configurations = parse_configurations(None)
    excitations, _ = resolve_excitations(args.records, "auto", azimuth="worst")
    pairs = [x for x in excitations if x.pair is not None]
    print(f"load average before: {' '.join(f'{x:.2f}' for x in os.getloadavg())}; threads: {solve._threads()}; "
          f"{len(pairs)} pairs, {len(sweep_azimuths(args.azimuth_step))} orientations each")
    kw = dict(margin=True, neighbourhood=args.neighbourhood)
    totals = collections.Counter()
    bad = 0
    for x in pairs:
        subs, groups = expand([x], sweep_azimuths(args.azimuth_step))
        cpu = {}
        rows = {}
        for mode in ("shared", "unshared") if args.unshared else ("shared",):
            runs.clear()
            phase[0] = "1x"
            c0 = time.process_time()
            result = run_assessment(columns, subs, configurations, orientations=groups if mode == "shared" else None,
                                    **kw)
            cpu[mode] = time.process_time() - c0
            rows[mode] = collapse(result, [x], groups).rows
            totals[mode] += cpu[mode]
            by = " ".join(f"{ph} {kind} {n}" for (ph, kind), n in sorted(runs.items()))
            print(f"{x.label:42s} {mode:8s} {cpu[mode]:6.1f} s CPU; runs: {by}")
        if args.unshared:
            same = sum(_same(a, b) for a, b in zip(rows["shared"], rows["unshared"]))
            bad += len(rows["shared"]) - same
            print(f"{'':42s} rows identical: {same} of {len(rows['shared'])}")
    print("total CPU: " + ", ".join(f"{m} {t:.1f} s" for m, t in totals.items()))
    print(f"load average after: {' '.join(f'{x:.2f}' for x in os.getloadavg())}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
