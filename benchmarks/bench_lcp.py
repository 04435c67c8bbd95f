"""Lemke's method (:mod:`rockcli.kernels.lcp`): time per solve and pivots.

    python benchmarks/bench_lcp.py [--problems 2000] [--rounds 5]

Random planar friction LCPs (Pfeiffer-Glocker form, as in tests/test_lcp.py: a random symmetric positive definite
Delassus matrix, mu in [0.1, 1], random bias) of k = 1, 2, 4, 8, 16 contacts (m = 3k), and random P-matrix LCPs of m
= 4, 8, 16, 32 (half symmetric positive definite, half diagonally dominant). Each problem is solved in a compiled loop
(the time per solve without Python's call) and from Python (one ``lemke`` call per problem, as a caller outside
numba would pay); the best of the rounds, after a warm-up. Also the mean number of pivots and how many problems ended
without a solution. No assertions: figures only.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
from numba import njit

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from test_lcp import p_matrices, random_friction  # noqa: E402

from rockcli.kernels.lcp import LCP_OK, lcp_pivots, lcp_workspace, lemke  # noqa: E402


@njit
def _solve_all(Ms, qs, Z, W, ws, status, pivots):
    """Every problem of the stack in turn (one workspace)."""
    for n in range(qs.shape[0]):
        status[n] = lemke(Ms[n], qs[n], Z[n], W[n], ws)
        pivots[n] = lcp_pivots(ws)


def bench(Ms, qs, rounds):
    """``(us per solve in the loop, us per solve from Python, mean pivots, problems not solved)``."""
    N, m = qs.shape
    ws = lcp_workspace(m)
    Z, W = np.zeros((N, m)), np.zeros((N, m))
    status, pivots = np.zeros(N, dtype=np.int64), np.zeros(N, dtype=np.int64)
    _solve_all(Ms[:2], qs[:2], Z, W, ws, status, pivots)  # compile / warm up
    loop = []
    for _ in range(rounds):
        t = time.perf_counter()
        _solve_all(Ms, qs, Z, W, ws, status, pivots)
        loop.append((time.perf_counter() - t) / N)
    py = []
    z, w = np.zeros(m), np.zeros(m)
    for _ in range(rounds):
        t = time.perf_counter()
        for n in range(N):
            lemke(Ms[n], qs[n], z, w, ws)
        py.append((time.perf_counter() - t) / N)
    return 1e6 * min(loop), 1e6 * min(py), pivots.mean(), int(np.count_nonzero(status != LCP_OK))


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--problems", type=int, default=2000)
    ap.add_argument("--rounds", type=int, default=5)
    args = ap.parse_args(argv)
    rng = np.random.default_rng(1)
    print(f"{args.problems} problems per size, best of {args.rounds} rounds")
    print(f"{'problem':>24} {'m':>3} {'us/solve':>9} {'us (Python)':>12} {'pivots':>7} {'no solution':>12}")
    for k in (1, 2, 4, 8, 16):
        probs = [random_friction(rng, k)[:2] for _ in range(args.problems)]
        Ms, qs = np.array([p[0] for p in probs]), np.array([p[1] for p in probs])
        loop, py, piv, bad = bench(Ms, qs, args.rounds)
        print(f"{f'friction, k = {k}':>24} {3 * k:>3} {loop:9.2f} {py:12.2f} {piv:7.1f} {bad:12d}")
    for m in (4, 8, 16, 32):
        Ms, qs = p_matrices(rng, m, args.problems), rng.normal(size=(args.problems, m))
        loop, py, piv, bad = bench(Ms, qs, args.rounds)
        print(f"{'P-matrix':>24} {m:>3} {loop:9.2f} {py:12.2f} {piv:7.1f} {bad:12d}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
