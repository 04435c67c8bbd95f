"""The friction driver against the slow reference on random scenes: verdicts, peaks, slips, counts, CPU.

    python benchmarks/bench_friction_reference.py --scenes 1000 --seed 1 [--kinds rigid1,rigid2,linear1,linear2]
        [--records] [--jobs 2] [--out out/friction_reference.json]

Each scene: a random body (one block, or a body on its plinth), a random friction per contact, a random pulse (or,
with ``--records``, half of them a short random record), on the ground or on linear bearings. Both run at rtol
1e-10. Printed: per kind the scenes, the verdicts that agree, the scenes whose slip and impact counts agree, the
largest differences of the peaks (over the slenderness), of the peak and residual slips (absolute, m), and the CPU
of each. The scenes that disagree are listed with their seeds, to be rerun alone (``--only SEED``).
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time
from concurrent.futures import ProcessPoolExecutor

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))


def scene(seed: int, kind: str, records: bool):
    from synthetic import random_record

    from rockcli.io.units import G
    from rockcli.models import Block, LinearIsolation, Plinth, Stack
    from rockcli.pulses import OneSine, RickerAntisymmetric, RickerSymmetric

    rng = np.random.default_rng(seed)
    if kind.endswith("1"):
        body = Block.from_dimensions(rng.uniform(0.4, 3.0), rng.uniform(0.25, 1.2))
        mu = float(rng.uniform(0.1, 1.0))
    else:
        b = Block.from_dimensions(rng.uniform(0.8, 2.5), rng.uniform(0.25, 0.7))
        body = Stack(b, Plinth(rng.uniform(0.3, 1.4), b.width * rng.uniform(1.02, 2.0)))
        mu = (float(rng.uniform(0.15, 1.0)), float(rng.uniform(0.15, 1.0)))
    if records and rng.random() < 0.5:
        exc = random_record(rng, pga_g=(0.2, 0.8), n_range=(150, 400))
    else:
        kinds = (RickerSymmetric, OneSine, RickerAntisymmetric)
        exc = kinds[int(rng.integers(0, 3))](rng.uniform(0.15, 0.8) * G, rng.uniform(0.25, 1.5))
    iso = None
    if kind.startswith("linear"):
        iso = LinearIsolation(T_b=float(rng.uniform(1.5, 3.5)), xi=float(rng.uniform(0.05, 0.2)),
                              gamma=float(rng.uniform(0.1, 0.6)))
    return body, exc, mu, iso


def run_one(args):
    seed, kind, records = args
    from rockcli.reference.friction import reference_friction
    from rockcli.solve.slide import simulate_friction

    body, exc, mu, iso = scene(seed, kind, records)
    t0 = time.process_time()
    r = simulate_friction(body, exc, mu, iso, rtol=1e-10)
    t1 = time.process_time()
    try:
        q = reference_friction(body, exc, mu, iso, rtol=1e-10, record_energy=True, deadline_s=600)
    except Exception as exc_:  # a reference failure is reported, not hidden
        return {"seed": seed, "kind": kind, "error": f"{type(exc_).__name__}: {exc_}"}
    t2 = time.process_time()
    out = {"seed": seed, "kind": kind, "verdict": r.verdict, "ref_verdict": q.verdict, "cpu_kernel": t1 - t0,
           "cpu_ref": t2 - t1, "energy_rise": max(q.energy_rises, default=0.0), "incons": r.n_inconsistent,
           "ref_incons": q.n_inconsistent, "interfaces": []}
    for j, p in enumerate(r.interfaces):
        out["interfaces"].append({
            "psi": p.psi_max / p.alpha, "ref_psi": q.psi_max[j] / p.alpha, "s_max": p.slide_max_m,
            "ref_s_max": q.s_max[j], "s_end": p.slide_residual_m, "ref_s_end": q.s_end[j], "slips": p.n_slips,
            "ref_slips": q.n_slips[j], "impacts": p.n_impacts, "ref_impacts": q.n_impacts[j]})
    return out


def summary(rows):
    kinds = sorted({r["kind"] for r in rows})
    for kind in kinds:
        rs = [r for r in rows if r["kind"] == kind and "error" not in r]
        errs = [r for r in rows if r["kind"] == kind and "error" in r]
        agree = [r for r in rs if r["verdict"] == r["ref_verdict"]]
        final = [r for r in agree if r["verdict"] not in ("overturned", "slid off")]
        counts = [r for r in rs if all(i["slips"] == i["ref_slips"] and i["impacts"] == i["ref_impacts"]
                                       for i in r["interfaces"])]
        dpsi = max((abs(i["psi"] - i["ref_psi"]) for r in final for i in r["interfaces"]), default=0.0)
        ds = max((abs(i["s_max"] - i["ref_s_max"]) for r in final for i in r["interfaces"]), default=0.0)
        de = max((abs(i["s_end"] - i["ref_s_end"]) for r in final for i in r["interfaces"]), default=0.0)
        slid = sum(1 for r in rs if any(i["slips"] for i in r["interfaces"]))
        rocked = sum(1 for r in rs if any(i["psi"] > 0 for i in r["interfaces"]))
        print(f"{kind}: {len(rs)} scenes ({slid} slide, {rocked} rock; {len(errs)} reference failures), verdicts "
              f"agree {len(agree)}/{len(rs)}, slip and impact counts agree {len(counts)}/{len(rs)}; largest "
              f"|d peak|/alpha {dpsi:.2e}, |d slide max| {ds:.2e} m, |d residual| {de:.2e} m; energy rise at an "
              f"impact <= {max((r['energy_rise'] for r in rs), default=0):.1e}; inconsistent patterns kernel "
              f"{sum(r['incons'] for r in rs)}, reference {sum(r['ref_incons'] for r in rs)}; CPU kernel "
              f"{sum(r['cpu_kernel'] for r in rs):.2f} s, reference {sum(r['cpu_ref'] for r in rs):.1f} s")
        for r in rs:
            if r["verdict"] != r["ref_verdict"]:
                print(f"    verdict differs: seed {r['seed']}: {r['verdict']} / reference {r['ref_verdict']}")
        for r in errs:
            print(f"    reference failed: seed {r['seed']}: {r['error']}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--scenes", type=int, default=200)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--kinds", default="rigid1,rigid2,linear1,linear2")
    ap.add_argument("--records", action="store_true")
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--only", type=int, default=None)
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    kinds = a.kinds.split(",")
    if a.only is not None:
        jobs = [(a.only, k, a.records) for k in kinds]
    else:
        jobs = [(a.seed * 1_000_000 + i, kinds[i % len(kinds)], a.records) for i in range(a.scenes)]
    if a.jobs > 1:
        with ProcessPoolExecutor(a.jobs) as ex:
            rows = list(ex.map(run_one, jobs, chunksize=4))
    else:
        rows = [run_one(j) for j in jobs]
    summary(rows)
    if a.out:
        os.makedirs(os.path.dirname(a.out) or ".", exist_ok=True)
        with open(a.out, "w") as f:
            json.dump(rows, f, indent=1)


if __name__ == "__main__":
    main()
