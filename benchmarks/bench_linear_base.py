"""Two versions of the kernel on linear bearings under records: verdicts, peaks, steps and CPU per run.

Runs the same random scenes (a block on linear bearings under a record at a random scale, fixed seed)
with the rockcli of the working tree and with that of a git revision (exported into a temporary folder
with ``git archive``), each in its own process, verdict only (``simulate_many``), and compares them:

* verdicts: how many differ (and which scenes: seed index, verdicts, peaks);
* peaks of the scenes that rock in both: the largest |change| of ``theta_max/alpha``, of the peak base
  displacement (relative) and of the uplift time;
* work: accepted steps and right-hand-side evaluations per run, and the CPU time per run of each
  version (the kernel calls only, all threads), with the load average.

Scenes: ``--n`` synthetic records (a few enveloped sines, 300-1500 samples, dt 0.005-0.02 s) on random
bearings (``T_b`` 0.3-6 s, ``xi`` 0 (a fifth of them) or 0.01-0.6, a few up to 3, ``gamma`` 0-0.5) and
blocks (R 0.3-6 m, alpha 4-20 deg) at scales around their uplift, plus ``--n-real`` scenes on the
catalogue records of the main job (ROCKCLI_RECORDS) when they are found.

Usage::

    python benchmarks/bench_linear_base.py --baseline HEAD~1 [--n 3000] [--n-real 300]
    python benchmarks/bench_linear_base.py --only out.npz   # run the scenes with this tree only
    python benchmarks/bench_linear_base.py --reference 200 --keep DIR   # and the first 200 against the reference

``--reference N`` also runs the first N scenes with the slow reference (:func:`rockcli.reference.reference_simulate`,
DOP853 at rtol 1e-10, aligned to the samples) and prints how far each version is from it.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

CATALOGUE = ("parkfield-1966-c02-065", "imperialvalley-1979-elcentro6-230", "irpinia-1980-sturno-270",
             "sansalvador-1986-gic", "superstition-1987-parachute-225", "erzincan-1992-erzincan-ew",
             "northridge-1994-jensen-generator-022", "kobe-1995-takarazuka-000", "chichi-1999-chy101-e",
             "chichi-1999-tcu128-n")
VERDICTS = ("no_uplift", "rocked", "overturned", "error")


def scenes(n: int, n_real: int, seed: int = 3301):
    """``(block, foundation, record, scale)`` of the comparison (the same list in every version)."""
    from rockcli.models import Block, LinearIsolation
    from rockcli.records import Record
    from rockcli.io.units import G

    rng = np.random.default_rng(seed)
    out = []
    real = []
    if n_real:
        from rockcli.assess import resolve_excitations

        try:
            real = [x.motion for x in resolve_excitations(list(CATALOGUE))[0] if x.motion is not None]
        except Exception:  # no ROCKCLI_RECORDS: synthetic scenes only
            real = []
    for i in range(n + (n_real if real else 0)):
        if i < n:
            dt = float(rng.choice([0.005, 0.01, 0.02]))
            m = int(rng.integers(300, 1500))
            t = np.arange(m) * dt
            acc = np.zeros(m)
            for f in rng.uniform(0.3, 6.0, 6):
                acc += rng.normal() * np.sin(2 * np.pi * f * t + rng.uniform(0, 2 * np.pi))
            acc *= np.sin(np.pi * t / t[-1]) ** 2 * G / np.max(np.abs(acc))
            rec = Record(acc, dt, f"synthetic-{i}")
        else:
            rec = real[int(rng.integers(len(real)))]
        xi = 0.0 if rng.random() < 0.2 else float(rng.uniform(0.01, 0.6) if rng.random() < 0.9 else rng.uniform(0.6, 3))
        f = LinearIsolation(float(rng.uniform(0.3, 6.0)), xi, float(rng.choice([0.0, 0.01, 0.1, 0.5])))
        b = Block(float(rng.uniform(0.3, 6.0)), float(np.radians(rng.uniform(4.0, 20.0))))
        scale = float(np.exp(rng.uniform(np.log(0.05), np.log(2.0))))  # a tenth to twice the record's PGA of 1 g
        out.append((b, f, rec, scale))
    return out


def run_here(n: int, n_real: int, path: str, horizon: float) -> None:
    """Run the scenes with the rockcli on ``sys.path`` and save the results to ``path`` (npz)."""
    import time

    from rockcli.solve import simulate_many

    jobs = scenes(n, n_real)
    simulate_many(jobs[:2])  # load the kernels before the clock starts
    c0, w0 = time.process_time(), time.perf_counter()
    res = simulate_many(jobs, horizon=horizon)
    cpu, wall = time.process_time() - c0, time.perf_counter() - w0
    np.savez(path, verdict=np.array([VERDICTS.index(r.verdict) for r in res]),
             theta=np.array([r.theta_max_over_alpha for r in res]), umax=np.array([r.base_disp_max_m for r in res]),
             t_uplift=np.array([r.t_uplift_s for r in res]), steps=np.array([getattr(r, "steps", 0) for r in res]),
             nfev=np.array([getattr(r, "nfev", 0) for r in res]), settled=np.array([bool(r.settled) for r in res]),
             cpu=cpu, wall=wall, load=os.getloadavg()[0])


def compare(old: dict, new: dict, jobs) -> None:
    vo, vn = old["verdict"], new["verdict"]
    n = vo.size
    diff = np.flatnonzero(vo != vn)
    print(f"{n} scenes: verdicts differ in {diff.size}")
    for i in diff[:20]:
        b, f, rec, s = jobs[i]
        print(f"  scene {i}: {VERDICTS[vo[i]]} -> {VERDICTS[vn[i]]}; theta/alpha {old['theta'][i]:.9g} -> "
              f"{new['theta'][i]:.9g}; {rec.name} x {s:.6g}, R={b.R:.4g} alpha={np.degrees(b.alpha):.4g} deg, "
              f"Tb={f.T_b:.4g} xi={f.xi:.4g} gamma={f.gamma:.4g}")
    both = (vo == vn) & (vo == VERDICTS.index("rocked"))
    same = vo == vn
    dth = np.abs(old["theta"][both] - new["theta"][both])
    rel_u = np.abs(old["umax"][same] - new["umax"][same]) / np.maximum(np.abs(old["umax"][same]), 1e-12)
    up = same & np.isfinite(old["t_uplift"]) & np.isfinite(new["t_uplift"])
    dtu = np.abs(old["t_uplift"][up] - new["t_uplift"][up])
    for name, d in (("|d theta_max/alpha| (rocked in both)", dth), ("|d u_max|/u_max", rel_u),
                    ("|d t_uplift| [s]", dtu)):
        if d.size:
            print(f"  {name}: median {np.median(d):.2e}, 99 % {np.quantile(d, 0.99):.2e}, max {d.max():.2e} "
                  f"({d.size} scenes)")
    print(f"  settled differs in {int(np.count_nonzero(old['settled'] != new['settled']))} scenes")
    for tag, r in (("old", old), ("new", new)):
        print(f"  {tag}: {r['steps'].mean():.0f} steps/run, {r['nfev'].mean():.0f} rhs/run, "
              f"{1e3 * float(r['cpu']) / n:.3f} ms CPU/run ({float(r['cpu']):.1f} s CPU, "
              f"{float(r['wall']):.1f} s wall, "
              f"load {float(r['load']):.1f})")
    by = {k: np.flatnonzero(vo == VERDICTS.index(k)) for k in VERDICTS[:3]}
    print("  verdicts (old): " + ", ".join(f"{k} {v.size}" for k, v in by.items()))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--baseline", default="HEAD", help="git revision to compare the working tree with")
    ap.add_argument("--n", type=int, default=3000)
    ap.add_argument("--n-real", type=int, default=300)
    ap.add_argument("--horizon", type=float, default=60.0)
    ap.add_argument("--only", metavar="NPZ", help="only run the scenes with this tree into NPZ")
    ap.add_argument("--keep", metavar="DIR", help="keep both result files here")
    ap.add_argument("--reference", type=int, default=0, metavar="N", help="also compare the first N with the reference")
    args = ap.parse_args(argv)
    if args.only:
        run_here(args.n, args.n_real, args.only, args.horizon)
        return 0
    root = Path(__file__).resolve().parent.parent
    work = Path(args.keep or tempfile.mkdtemp(prefix="rockcli-linear-base-"))
    work.mkdir(parents=True, exist_ok=True)
    tree = Path(tempfile.mkdtemp(prefix="rockcli-tree-"))
    archive = subprocess.run(["git", "-C", str(root), "archive", args.baseline], check=True, capture_output=True)
    subprocess.run(["tar", "-x", "-C", str(tree)], input=archive.stdout, check=True)
    cmd = [sys.executable, str(Path(__file__).resolve()), "--n", str(args.n), "--n-real", str(args.n_real),
           "--horizon", str(args.horizon), "--only"]
    for tag, where in (("old", tree), ("new", root)):
        print(f"running {tag} ({args.baseline if tag == 'old' else 'working tree'}) ...", file=sys.stderr)
        subprocess.run(cmd + [str(work / f"{tag}.npz")], check=True, env=dict(os.environ, PYTHONPATH=str(where)))
    sys.path.insert(0, str(root))
    old, new = dict(np.load(work / "old.npz")), dict(np.load(work / "new.npz"))
    jobs = scenes(args.n, args.n_real)
    compare(old, new, jobs)
    if args.reference:
        against_reference(old, new, jobs[:args.reference], args.horizon)
    shutil.rmtree(tree, ignore_errors=True)
    print(json.dumps({"results": str(work)}))
    return 0


def against_reference(old: dict, new: dict, jobs, horizon: float) -> None:
    """Both versions against the slow reference on ``jobs`` (the first scenes of the comparison)."""
    from rockcli.reference import reference_simulate

    n = len(jobs)
    ref = [reference_simulate(b, f, rec.scaled(s), horizon=horizon, align=True) for b, f, rec, s in jobs]
    rv = np.array([VERDICTS.index(r.verdict) for r in ref])
    rth = np.array([r.theta_max / b.alpha for r, (b, _, _, _) in zip(ref, jobs)])
    ru = np.array([r.u_max for r in ref])
    print(f"against the reference ({n} scenes):")
    for tag, r in (("old", old), ("new", new)):
        v = r["verdict"][:n]
        rocked = (v == rv) & (rv == VERDICTS.index("rocked"))
        dth = np.abs(r["theta"][:n][rocked] - rth[rocked])
        du = np.abs(r["umax"][:n] - ru) / np.maximum(ru, 1e-12)
        print(f"  {tag}: verdicts differ in {int(np.count_nonzero(v != rv))}; |d theta_max/alpha| median "
              f"{np.median(dth) if dth.size else 0:.1e}, max {dth.max() if dth.size else 0:.1e} ({dth.size} rocking); "
              f"|d u_max|/u_max median {np.median(du):.1e}, max {du.max():.1e}")


if __name__ == "__main__":
    sys.exit(main())
