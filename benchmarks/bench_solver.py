"""Compiled kernel vs the SciPy reference (rockcli.reference) on the same scenes, at matched accuracy.

Prints, for a 40 s record (Kobe Takarazuka 000, rigid and isolated) and one Ricker pulse:
the error of each solver against a converged solution, wall times, the speed-up at matched
accuracy, right-hand-side evaluations per run, and the first-call compile and cached-load times.

Run:  ROCKCLI_RECORDS=../shared/records python benchmarks/bench_solver.py
No assertions: figures only (timings depend on the machine and its load).
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parent))

from rockcli.models import LinearIsolation, Rigid, column  # noqa: E402
from rockcli.pulses import make_pulse  # noqa: E402
from rockcli.records import read_record  # noqa: E402
from rockcli.reference import reference_simulate  # noqa: E402
from rockcli.solve import simulate  # noqa: E402
from rockcli.io.units import G  # noqa: E402


def best_time(fn, repeat=7, number=None):
    """Best wall time of ``fn()`` [s] over ``repeat`` rounds of ``number`` calls."""
    if number is None:
        t = time.perf_counter()
        fn()
        once = time.perf_counter() - t
        number = max(1, int(0.05 / max(once, 1e-9)))
    best = float("inf")
    for _ in range(repeat):
        t = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t) / number)
    return best


def compile_and_load_times():
    """First call in a fresh process with an empty cache (compile), then with the cache (load)."""
    code = ("import time; t=time.perf_counter(); from rockcli.models import Block, Rigid; "
            "from rockcli.solve import simulate; from rockcli.pulses import make_pulse; "
            "simulate(Block(1, 0.2), Rigid(), make_pulse('sine', 3.0, 1.0)); print(time.perf_counter()-t)")
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        first = float(subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                                     check=True).stdout)
        cached = float(subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                                      check=True).stdout)
    return first, cached


def main():
    folders = [Path(p) for p in os.environ.get("ROCKCLI_RECORDS", "").split(os.pathsep) if p]
    kobe = next((f / "RSN1119_KOBE_TAZ000.AT2" for f in folders if (f / "RSN1119_KOBE_TAZ000.AT2").exists()), None)
    scenes = []
    if kobe is not None:
        rec = read_record(kobe)
        scenes += [("Kobe TAZ000 40.96 s, Bassae, rigid", column("bassae"), Rigid(), rec),
                   ("Kobe TAZ000 40.96 s, Bassae, Tb=2.5 s", column("bassae"), LinearIsolation(2.5), rec),
                   ("Kobe TAZ000 40.96 s, Nemea, rigid", column("nemea"), Rigid(), rec)]
    else:
        print("(ROCKCLI_RECORDS does not name a folder with RSN1119_KOBE_TAZ000.AT2: pulse only)")
    scenes += [("symmetric Ricker 0.32 g, 1 s, R=1 m alpha=0.2", _blk(), Rigid(), make_pulse("ricker-sym", 0.32 * G, 1.0)),
               ("antisym. Ricker 0.6 g, 0.8 s, Tb=2 s", _blk(), LinearIsolation(2.0, 0.05, 0.1),
                make_pulse("ricker-anti", 0.6 * G, 0.8))]

    print(f"{'scene':44s} {'solver':8s} {'rtol':>7s} {'err th_max':>10s} {'time':>10s} {'RHS evals':>10s} {'steps':>7s}")
    for label, block, found, exc in scenes:
        truth = simulate(block, found, exc, rtol=1e-13, history=True).theta_max
        ref_rows, ker_rows = [], []
        for rt in (1e-6, 1e-8, 1e-10):
            t = time.perf_counter()
            ref = reference_simulate(block, found, exc, rtol=rt, atol=rt * 1e-3)
            ref_rows.append((rt, abs(ref.theta_max - truth) / truth, time.perf_counter() - t))
        for rt in (1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-10, 1e-12):
            r = simulate(block, found, exc, rtol=rt)
            tk = best_time(lambda: simulate(block, found, exc, rtol=rt))
            ker_rows.append((rt, abs(r.theta_max - truth) / truth, tk, r.nfev, r.steps, r.verdict))
        for rt, err, tr in ref_rows:
            print(f"{label:44s} {'scipy':8s} {rt:7.0e} {err:10.1e} {tr * 1e3:8.1f}ms {'':>10s} {'':>7s}")
        for rt, err, tk, nfev, steps, verdict in ker_rows:
            print(f"{label:44s} {'kernel':8s} {rt:7.0e} {err:10.1e} {tk * 1e3:8.3f}ms {nfev:10d} {steps:7d}")
        # matched accuracy: for each reference run, the cheapest kernel run at least as accurate
        for rt, err, tr in ref_rows:
            ok = [row for row in ker_rows if row[1] <= max(err, 1e-15)]
            if ok:
                fastest = min(ok, key=lambda row: row[2])
                print(f"  -> at the reference's error {err:.1e} (scipy rtol {rt:.0e}): kernel {fastest[2] * 1e3:.3f} ms "
                      f"(rtol {fastest[0]:.0e}) vs scipy {tr * 1e3:.0f} ms: speed-up {tr / fastest[2]:,.0f}x")
        print(f"  verdict: {ker_rows[-1][5]}")

    first, cached = compile_and_load_times()
    print(f"\nfirst call in a fresh process, empty numba cache (compile): {first:.1f} s")
    print(f"first call in a fresh process, warm numba cache (load):   {cached:.2f} s")


def _blk():
    from rockcli.models import Block

    return Block(1.0, 0.2)


if __name__ == "__main__":
    main()
