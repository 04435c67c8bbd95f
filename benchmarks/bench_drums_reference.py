"""The friction driver on columns of drums against the slow reference (rockcli.reference.friction_drums) on random
stacks: verdicts, slip and impact counts, peaks, residual offsets, CPU.

    python benchmarks/bench_drums_reference.py --scenes 50 --n 2,3,4 --seed 1 [--jobs 2] [--deadline 600]
        [--linear 0.2] [--only SEED --n N] [--out out/drums_reference.json] [--flight [--scale 3,6 --cap 1.5]]

Each scene: ``n`` drums (heights 0.3-1.5 m, widths 0.3-1.0 m; a third of the columns tapering upwards, the others
with widths drawn freely, so that some drums overhang the one below), friction 0.3-1.0 drawn per contact, a random
pulse (Ricker, one-sine) or, for half of them, a short random record (tests/synthetic.py ``random_record``), of 1-3
times the column's first static threshold (at most 1 g), on the rigid ground (``--linear F``: a fraction F on linear bearings). Both at rtol 1e-10. The reference has a wall-clock
deadline per scene (``--deadline``): a scene past it is reported as a timeout, not dropped. Printed per ``n``: the
scenes, the verdicts that agree, the scenes whose slip and impact counts agree, the largest differences of the
peaks over the slenderness and of the residual offsets (m) where both survive, the CPU per scene of each, and every
disagreeing seed (rerun one alone with ``--only SEED --n N``).

``--flight``: the reference is also run with flight (``reference_drums(..., flight=True)``, each within the same
deadline), and printed per scene and per ``n``: the verdicts of the driver (which has no flight), of the reference
without flight and with it, how many scenes change verdict with flight, the pulls (jumps) counted without flight and
left with it, the lift-offs and landings, and the CPU of each. ``--scale LO,HI`` and ``--cap G`` draw stronger
shaking (tests/synthetic.py ``random_drum_scene``: LO-HI times the first static threshold, at most G).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor, as_completed

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))


def scene(seed: int, n: int, linear: float = 0.0):
    """``(column, excitation, mu per contact, foundation)`` of one seed (tests/synthetic.py)."""
    from synthetic import random_drum_scene

    kw = {}
    if os.environ.get("BENCH_DRUMS_SCALE"):
        kw["scale"] = tuple(float(x) for x in os.environ["BENCH_DRUMS_SCALE"].split(","))
    if os.environ.get("BENCH_DRUMS_CAP"):
        kw["cap"] = float(os.environ["BENCH_DRUMS_CAP"])
    return random_drum_scene(seed, n, linear, **kw)


def run_isolated(args):
    """:func:`run_one` in a process of its own (HiGHS, under the reference's mixed-integer search, has crashed a
    process: scipy issue 22188): a crash is reported as the reference's failure, with the problem HiGHS was given
    (out/milp-crash-SEED-N.npz)."""
    import subprocess

    seed, n, linear, deadline, flight = args
    dump = os.path.join("out", f"milp-crash-{seed}-{n}.npz")
    env = dict(os.environ, ROCKCLI_MILP_DUMP=dump)
    p = subprocess.run([sys.executable, "-X", "faulthandler", __file__, "--child",
                        f"{seed},{n},{linear},{deadline},{int(flight)}"],
                       capture_output=True, text=True, env=env)
    if p.returncode == 0:
        if os.path.exists(dump):
            os.remove(dump)
        return json.loads(p.stdout.strip().splitlines()[-1])
    col, exc, mu, iso = scene(seed, n, linear)
    return {"seed": seed, "n": n, "iso": iso is not None, "verdict": "?", "cpu_kernel": 0.0, "incons": 0,
            "ref_verdict": "error", "cpu_ref": 0.0,
            "error": f"the process ended with code {p.returncode}: {p.stderr.strip().splitlines()[-1:]}"}


def run_flight(col, exc, mu, iso, deadline):
    """The reference with flight: its verdict, counts and CPU (a timeout or failure reported as the verdict)."""
    from rockcli.reference.friction_drums import reference_drums
    from rockcli.reference.result import ReferenceTimeout

    t0 = time.process_time()
    try:
        q = reference_drums(col, exc, mu, iso, rtol=1e-10, record_energy=True, deadline_s=deadline, flight=True)
    except ReferenceTimeout:
        return {"fl_verdict": "timeout", "cpu_fl": time.process_time() - t0}
    except Exception as exc_:  # a failure is reported, not hidden
        return {"fl_verdict": "error", "fl_error": f"{type(exc_).__name__}: {exc_}", "cpu_fl": time.process_time() - t0}
    names = col.joint_names()
    return {"fl_verdict": q.verdict, "cpu_fl": time.process_time() - t0, "fl_jumps": q.n_jumps,
            "fl_incons": q.n_inconsistent, "fl_flights": q.n_flights, "fl_landings": q.n_landings,
            "fl_time": q.flight_time, "fl_energy_rise": max(q.energy_rises, default=0.0),
            "fl_toppled": None if q.toppled < 0 else names[q.toppled]}


def run_one(args):
    seed, n, linear, deadline, flight = args
    from rockcli.reference.friction_drums import reference_drums
    from rockcli.reference.result import ReferenceTimeout
    from rockcli.solve.drums import DrumRun
    from rockcli.solve.slide import simulate_friction

    col, exc, mu, iso = scene(seed, n, linear)
    out = {"seed": seed, "n": n, "iso": iso is not None}
    if flight:
        out.update(run_flight(col, exc, mu, iso, deadline))
    t0 = time.process_time()
    r = simulate_friction(col, exc, mu, iso, rtol=1e-10)
    t1 = time.process_time()
    out.update(verdict=r.verdict, cpu_kernel=t1 - t0, incons=r.n_inconsistent, jumps=r.n_jumps,
               offsets=DrumRun(col, r, None).residual_offsets_m, toppled=r.toppled)
    try:
        q = reference_drums(col, exc, mu, iso, rtol=1e-10, record_energy=True, deadline_s=deadline)
    except ReferenceTimeout:
        out.update(ref_verdict="timeout", cpu_ref=time.process_time() - t1)
        return out
    except Exception as exc_:  # a reference failure is reported, not hidden
        out.update(ref_verdict="error", error=f"{type(exc_).__name__}: {exc_}", cpu_ref=time.process_time() - t1)
        return out
    t2 = time.process_time()
    names = col.joint_names()
    out.update(ref_verdict=q.verdict, cpu_ref=t2 - t1, ref_jumps=q.n_jumps,
               energy_rise=max(q.energy_rises, default=0.0),
               ref_incons=q.n_inconsistent, ref_offsets=q.residual_offsets, how=q.how,
               ref_toppled=None if q.toppled < 0 else names[q.toppled], kind_switches=q.n_kind_switches,
               interfaces=[])
    for j, p in enumerate(r.interfaces):
        out["interfaces"].append({
            "psi": p.psi_max / p.alpha, "ref_psi": q.psi_max[j] / p.alpha, "s_max": p.slide_max_m,
            "ref_s_max": q.s_max[j], "slips": p.n_slips, "ref_slips": q.n_slips[j], "impacts": p.n_impacts,
            "ref_impacts": q.n_impacts[j]})
    return out


def flight_summary(rows):
    """Per scene and per ``n``: the verdicts of the driver, the reference without and with flight (--flight)."""
    for n in sorted({r["n"] for r in rows}):
        rs = [r for r in rows if r["n"] == n and "fl_verdict" in r]
        if not rs:
            continue
        for r in rs:
            print(f"    seed {r['seed']} n={n}: driver {r['verdict']}, reference {r['ref_verdict']} "
                  f"({r.get('ref_jumps', '?')} jumps), with flight {r['fl_verdict']} ({r.get('fl_flights', '?')} "
                  f"lift-offs, {r.get('fl_landings', '?')} landings, {r.get('fl_jumps', '?')} pulls); CPU "
                  f"{r['cpu_kernel']:.2f} / {r['cpu_ref']:.1f} / {r['cpu_fl']:.1f} s")
        done = [r for r in rs if r["ref_verdict"] not in ("timeout", "error", "?")
                and r["fl_verdict"] not in ("timeout", "error")]
        change = [r for r in done if r["ref_verdict"] != r["fl_verdict"]]
        drv = [r for r in rs if r["fl_verdict"] not in ("timeout", "error") and r["verdict"] != r["fl_verdict"]]
        flew = [r for r in done if r.get("fl_flights", 0)]
        jumped = [r for r in done if r.get("ref_jumps", 0)]
        print(f"n={n} flight: {len(rs)} scenes, both references done {len(done)}; drums flew in {len(flew)}, "
              f"pivots pulled without flight in {len(jumped)}; the verdict changes with flight in {len(change)}/"
              f"{len(done)}, the driver's differs from the reference with flight in {len(drv)}; pulls left with "
              f"flight {sum(r.get('fl_jumps', 0) for r in done)}; energy rise <= "
              f"{max((r.get('fl_energy_rise', 0.0) for r in done), default=0.0):.1e}; CPU per scene with flight "
              f"{sum(r['cpu_fl'] for r in rs) / max(1, len(rs)):.1f} s")


def summary(rows):
    flight_summary(rows)
    for n in sorted({r["n"] for r in rows}):
        rs = [r for r in rows if r["n"] == n]
        done = [r for r in rs if r["ref_verdict"] not in ("timeout", "error")]
        agree = [r for r in done if r["verdict"] == r["ref_verdict"]]
        both = [r for r in agree if r["verdict"] not in ("overturned", "slid off")]
        counts = [r for r in done if all(i["slips"] == i["ref_slips"] and i["impacts"] == i["ref_impacts"]
                                         for i in r["interfaces"])]
        dpsi = max((abs(i["psi"] - i["ref_psi"]) for r in both for i in r["interfaces"]), default=0.0)
        doff = max((abs(a - b) for r in both for a, b in zip(r["offsets"], r["ref_offsets"])), default=0.0)
        ck = sum(r["cpu_kernel"] for r in rs) / max(1, len(rs))
        cr = sum(r["cpu_ref"] for r in done) / max(1, len(done))
        print(f"n={n}: {len(rs)} scenes ({len(rs) - len(done)} reference timeouts/failures), verdicts agree "
              f"{len(agree)}/{len(done)}, slip and impact counts agree {len(counts)}/{len(done)}; where both "
              f"stand ({len(both)}): largest |d peak|/alpha {dpsi:.2e}, |d residual offset| {doff:.2e} m; energy "
              f"rise <= {max((r.get('energy_rise', 0.0) for r in done), default=0.0):.1e}; inconsistent patterns "
              f"driver {sum(r['incons'] for r in rs)}, reference {sum(r.get('ref_incons', 0) for r in done)}; "
              f"CPU per scene driver {ck:.2f} s, reference {cr:.1f} s")
        for r in rs:
            if r["ref_verdict"] in ("timeout", "error"):
                print(f"    reference {r['ref_verdict']}: seed {r['seed']} n={n} {r.get('error', '')}")
            elif r["verdict"] != r["ref_verdict"]:
                print(f"    verdict differs: seed {r['seed']} n={n}: driver {r['verdict']} ({r['toppled']}) / "
                      f"reference {r['ref_verdict']} ({r['ref_toppled']})")
            elif r not in counts:
                print(f"    counts differ: seed {r['seed']} n={n} ({r['verdict']})")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenes", type=int, default=20, help="scenes per n")
    ap.add_argument("--n", default="2,3,4", help="numbers of drums, comma separated")
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--linear", type=float, default=0.0, help="fraction of scenes on linear bearings")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--deadline", type=float, default=600.0, help="the reference's wall budget per scene [s]")
    ap.add_argument("--only", type=int, default=None)
    ap.add_argument("--out", default=None)
    ap.add_argument("--child", default=None, help=argparse.SUPPRESS)
    ap.add_argument("--summary", default=None, help="print the summary of a JSON file written by --out")
    ap.add_argument("--flight", action="store_true", help="also run the reference with flight, compare the verdicts")
    ap.add_argument("--scale", default=None, help="LO,HI: the shaking LO-HI times the first static threshold")
    ap.add_argument("--cap", default=None, help="the shaking at most this [g]")
    a = ap.parse_args()
    if a.scale:
        os.environ["BENCH_DRUMS_SCALE"] = a.scale
    if a.cap:
        os.environ["BENCH_DRUMS_CAP"] = a.cap
    if a.summary:
        with open(a.summary) as f:
            summary(json.load(f))
        return
    if a.child:
        seed, n, linear, deadline, flight = a.child.split(",")
        print(json.dumps(run_one((int(seed), int(n), float(linear), float(deadline), flight == "1")), default=str))
        return
    ns = [int(x) for x in a.n.split(",")]
    if a.only is not None:
        jobs = [(a.only, n, a.linear, a.deadline, a.flight) for n in ns]
    else:
        jobs = [(a.seed * 1_000_000 + i, n, a.linear, a.deadline, a.flight) for n in ns for i in range(a.scenes)]
    rows = []

    def done(r):
        rows.append(r)
        fl = f", with flight {r['fl_verdict']} ({r['cpu_fl']:.1f} s)" if "fl_verdict" in r else ""
        print(f"  seed {r['seed']} n={r['n']}: driver {r['verdict']} ({r['cpu_kernel']:.1f} s), reference "
              f"{r['ref_verdict']} ({r['cpu_ref']:.1f} s){fl}", file=sys.stderr, flush=True)
        if a.out:  # after every scene: a run stopped half-way keeps what it did
            os.makedirs(os.path.dirname(a.out) or ".", exist_ok=True)
            with open(a.out, "w") as f:
                json.dump(rows, f, indent=1, default=str)

    if a.jobs > 1:
        with ProcessPoolExecutor(a.jobs) as ex:
            for f in as_completed([ex.submit(run_isolated, j) for j in jobs]):
                done(f.result())
    else:
        for j in jobs:
            done(run_isolated(j))
    rows.sort(key=lambda r: (r["n"], r["seed"]))
    summary(rows)


if __name__ == "__main__":
    main()
