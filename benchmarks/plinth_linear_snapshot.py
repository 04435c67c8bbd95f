"""Snapshot of the stack driver on linear bearings, to check that a change leaves it bit for bit.

``--write FILE`` runs ``--scenes`` random scenes (bench_plinth's random linear scenes, seed ``--seed``: pulses, with
a restitution in every third; every fifth with history) through :func:`rockcli.solve.simulate_stack` and saves every
output of the compiled driver (verdict, peaks, times, counts, friction demands, steps, base peak) and the history
rows; ``--compare A B`` reports every scene whose outputs differ (exactly: ``==`` on the floats, NaN equal NaN).
"""

from __future__ import annotations

import argparse
import sys

import numpy as np


def _outputs(r):
    vals = [r.body.theta_max, r.body.t_uplift_s, r.body.t_exceed_alpha_s, r.body.n_impacts, r.plinth.theta_max,
            r.plinth.t_uplift_s, r.plinth.t_exceed_alpha_s, r.plinth.n_impacts, r.body_tilt_max, r.friction_base,
            r.friction_joint, r.friction_base_impulsive, r.friction_joint_impulsive, r.n_jumps, r.n_inconsistent,
            r.t_overturn_s, r.steps, r.rejected, r.n_rhs, r.base_disp_max, r.status, float(r.settled),
            {"no_uplift": 0.0, "rocked": 1.0, "overturned": 2.0}[r.verdict]]
    return np.array(vals, float)


def write(path, n, seed):
    from bench_plinth import random_linear_scene

    from rockcli.solve import simulate_stack

    rng = np.random.default_rng(seed)
    outs, hists = [], {}
    for i in range(n):
        stack, iso, pulse = random_linear_scene(rng)
        E = float(rng.uniform(0.5, 1.0)) if i % 3 == 2 else None
        hist = i % 5 == 0
        r = simulate_stack(stack, pulse, horizon=1.0, tail=1.0, restitution=E, isolation=iso, history=hist)
        outs.append(_outputs(r))
        if hist:
            h = r.history
            hists[f"h{i}"] = np.column_stack([h.t, h.ag, h.psi, h.psi_dot, h.theta2, h.theta2_dot, h.u])
    np.savez(path, outputs=np.array(outs), **hists)
    print(f"{n} scenes written to {path}")


def compare(a, b):
    A, B = np.load(a), np.load(b)
    bad = 0
    oa, ob = A["outputs"], B["outputs"]
    for i in range(min(len(oa), len(ob))):
        if not np.array_equal(oa[i], ob[i], equal_nan=True):
            bad += 1
            print(f"scene {i}: outputs differ at columns {np.nonzero(~((oa[i] == ob[i]) | (np.isnan(oa[i]) & np.isnan(ob[i]))))[0]}")
    for key in A.files:
        if key != "outputs" and not np.array_equal(A[key], B[key], equal_nan=True):
            bad += 1
            print(f"history {key} differs")
    print(f"{len(oa)} scenes, {len([k for k in A.files if k != 'outputs'])} histories: {bad} differ")
    return bad


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--write")
    ap.add_argument("--compare", nargs=2)
    ap.add_argument("--scenes", type=int, default=300)
    ap.add_argument("--seed", type=int, default=36)
    args = ap.parse_args(argv)
    if args.write:
        write(args.write, args.scenes, args.seed)
    if args.compare:
        return 1 if compare(*args.compare) else 0
    return 0


if __name__ == "__main__":
    sys.exit(main())
