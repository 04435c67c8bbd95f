"""Do the stack drivers still give the same bits? Random bodies on plinths, every output written and compared.

    python benchmarks/bench_stack_identity.py --write /tmp/stack-a          # run the scenes, keep every output
    python benchmarks/bench_stack_identity.py --write /tmp/stack-b
    python benchmarks/bench_stack_identity.py --compare /tmp/stack-a /tmp/stack-b
    python benchmarks/bench_stack_identity.py --compare A B --except friction   # a change meant to move these

A refactor of :mod:`rockcli.kernels.stack` (and the nogil line of :mod:`rockcli.kernels.stack_linear`) must leave
every output of every run identical, bit for bit. The scenes (fixed seed, ``--scenes`` of them, default 300): the
random bodies and plinths of ``benchmarks/bench_plinth.py`` on the rigid foundation (two in three) and on linear
bearings, under a pulse (Ricker or one-sine, 0.05-1.5 g) or a short random record (1.5-4 s at 0.01 s), a random
restitution in one scene of four; each run verdict-only and with its history. Kept per run: the kernel's raw
output vectors (``out`` and ``xo`` of the rigid driver, ``z`` of the bearings'), every field of the
:class:`rockcli.solve.StackResponse` and the history's rows. The same verdict-only runs are also made as one batch
through :func:`rockcli.solve.simulate_many` (the path of the margin search) and its results kept.

``--compare`` prints the number of runs and values compared, the first differences, and exits 1 on one.
``--except friction`` leaves out the friction demands (``xo[11:13]`` of the rigid driver, ``z[13:15]`` of the one on
bearings, the two non-impulsive ``friction_*`` fields, and the output slots a version adds after the old ones), which a
change of where the demand is read moves on purpose; it prints their largest change instead. Also printed
on ``--write``: the CPU time of the runs and how many runs had steps of each pattern (coverage of the scenes).
"""

from __future__ import annotations

import argparse
import math
import pickle
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from bench_plinth import random_scene  # noqa: E402
from synthetic import random_record  # noqa: E402

from rockcli.io.units import G  # noqa: E402
from rockcli.models import LinearIsolation  # noqa: E402
from rockcli.pulses import OneSine, RickerAntisymmetric, RickerSymmetric  # noqa: E402

FRICTION_XO = (11, 12)  # X_FR_B, X_FR_J of rockcli.kernels.stack (the record xo: raw[1] of a rigid run)
FRICTION_Z = (13, 14)  # Z_FR0, Z_FR1 of rockcli.kernels.stack_linear (the outputs z: raw[0] of a run on bearings)
FRICTION_FIELDS = ("friction_base", "friction_joint")


def scenes(n, seed=36):
    """``(stack, isolation or None, motion, restitution)`` for ``n`` random scenes."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        stack, _ = random_scene(rng)
        iso = None
        if rng.random() < 1.0 / 3.0:
            iso = LinearIsolation(float(rng.uniform(0.5, 3.0)), float(rng.uniform(0.02, 0.3)),
                                  float(rng.uniform(0.05, 0.7)))
        if rng.random() < 0.3:
            motion = random_record(rng, pga_g=(0.1, 1.0))
        else:
            shape = (RickerSymmetric, RickerAntisymmetric, OneSine)[int(rng.integers(3))]
            motion = shape(float(rng.uniform(0.05, 1.5)) * G * rng.choice([-1, 1]), float(rng.uniform(0.2, 1.5)))
        E = float(rng.uniform(0.5, 1.0)) if rng.random() < 0.25 else None
        out.append((stack, iso, motion, E))
    return out


class _Tap:
    """Wrap a kernel entry: keep copies of the output vectors of each call (serial runs only)."""

    def __init__(self, module, name, arg_index):
        self.module, self.name, self.arg_index = module, name, arg_index
        self.kernel = getattr(module, name)
        self.last = None

    def __call__(self, *args):
        res = self.kernel(*args)
        self.last = [np.array(args[i], copy=True) for i in self.arg_index]
        return res

    def __enter__(self):
        setattr(self.module, self.name, self)
        return self

    def __exit__(self, *exc):
        setattr(self.module, self.name, self.kernel)


def _fields(res):
    d = {}
    for name, value in vars(res).items():
        if name == "history":
            continue
        if hasattr(value, "__dict__"):
            for k, v in vars(value).items():
                d[f"{name}.{k}"] = v
        else:
            d[name] = value
    if res.history is not None:
        for k, v in vars(res.history).items():
            d[f"history.{k}"] = None if v is None else np.asarray(v)
    return d


def write(folder: Path, n: int) -> None:
    from rockcli.kernels import stack as kst
    from rockcli.kernels import stack_linear as ksl
    from rockcli.solve import simulate_many, simulate_stack

    folder.mkdir(parents=True, exist_ok=True)
    sc = scenes(n)
    runs = []
    cpu = 0.0
    seen = {"body rocks": 0, "plinth rocks": 0, "both rock": 0, "toppled": 0}
    with _Tap(kst, "simulate_stack", (14, 15)) as tap_r, _Tap(ksl, "simulate_stack_linear", (12,)) as tap_l:
        for stack, iso, motion, E in sc:
            for history in (False, True):
                t0 = time.process_time()
                res = simulate_stack(stack, motion, history=history, restitution=E, isolation=iso, tail=1.0,
                                     horizon=2.0)
                cpu += time.process_time() - t0
                tap = tap_l if iso is not None else tap_r
                runs.append({"raw": tap.last, "fields": _fields(res)})
                if history:
                    for p in set(res.history.pattern):
                        if p in seen:
                            seen[p] += 1
                    seen["toppled"] += res.toppled is not None
    t0 = time.process_time()
    jobs = [(stack, iso, motion) for stack, iso, motion, E in sc if E is None]
    batch = simulate_many(jobs, tail=1.0, horizon=2.0)
    cpu_batch = time.process_time() - t0
    batch = [_fields(r.stack) for r in batch]
    with open(folder / "stack-runs.pkl", "wb") as f:
        pickle.dump({"runs": runs, "batch": batch}, f)
    print(f"{len(sc)} scenes ({sum(s[1] is None for s in sc)} rigid, {sum(s[1] is not None for s in sc)} on linear "
          f"bearings), {len(runs)} runs in {cpu:.2f} s of CPU; batch of {len(jobs)} verdict-only in "
          f"{cpu_batch:.2f} s of CPU")
    print("runs with steps of each pattern (history runs): " + ", ".join(f"{k} {v}" for k, v in seen.items()))


def _same(a, b) -> bool:
    if isinstance(a, np.ndarray) or isinstance(b, np.ndarray):
        a, b = np.asarray(a), np.asarray(b)
        if a.shape != b.shape or a.dtype != b.dtype:
            return False
        if a.dtype == object:
            return bool(np.all(a == b))
        return a.tobytes() == b.tobytes()
    if isinstance(a, float) and isinstance(b, float):
        return (math.isnan(a) and math.isnan(b)) or np.float64(a).tobytes() == np.float64(b).tobytes()
    return a == b


def compare(a: Path, b: Path, skip_friction: bool) -> int:
    A = pickle.load(open(a / "stack-runs.pkl", "rb"))
    B = pickle.load(open(b / "stack-runs.pkl", "rb"))
    bad = []
    values = 0
    moved = []  # (run, name, old, new) of the friction values left out
    if len(A["runs"]) != len(B["runs"]) or len(A["batch"]) != len(B["batch"]):
        print("different numbers of runs")
        return 1
    for i, (ra, rb) in enumerate(zip(A["runs"], B["runs"])):
        for j, (xa, xb) in enumerate(zip(ra["raw"], rb["raw"])):
            xa, xb = xa.copy(), xb.copy()
            slots = (FRICTION_XO if len(ra["raw"]) == 2 and j == 1 else FRICTION_Z if len(ra["raw"]) == 1 else ())
            if skip_friction and slots and xa.size > max(slots):
                n = min(xa.size, xb.size)  # slots added after the old ones (the demands read inside) are left out
                xa, xb = xa[:n], xb[:n]
                for q in slots:
                    moved.append((i, f"{'xo' if j else 'z'}[{q}]", xa[q], xb[q]))
                    xa[q] = xb[q] = 0.0
            values += xa.size
            if xa.shape != xb.shape:
                bad.append((i, f"raw[{j}]", f"{xa.size} values against {xb.size}"))
            elif not _same(xa, xb):
                bad.append((i, f"raw[{j}]", np.flatnonzero(xa.view(np.int64) != xb.view(np.int64)).tolist()))
        for name in ra["fields"]:
            if skip_friction and name in FRICTION_FIELDS:
                continue
            va, vb = ra["fields"][name], rb["fields"].get(name, "<missing>")
            values += np.size(va) if va is not None else 1
            if not _same(va, vb):
                bad.append((i, name, (va, vb) if np.size(va) == 1 else "arrays differ"))
    for i, (fa, fb) in enumerate(zip(A["batch"], B["batch"])):
        for name in fa:
            if skip_friction and name in FRICTION_FIELDS:
                continue
            values += 1
            if not _same(fa[name], fb.get(name, "<missing>")):
                bad.append((f"batch {i}", name, (fa[name], fb.get(name))))
    print(f"{len(A['runs'])} runs and {len(A['batch'])} batch results, {values} values compared: "
          f"{len(bad)} differences")
    for x in bad[:20]:
        print("  ", x)
    if moved:
        rel = [abs(n - o) / max(abs(o), 1e-300) for _, _, o, n in moved if o != n]
        up = sum(1 for _, _, o, n in moved if n > o)
        down = sum(1 for _, _, o, n in moved if n < o)
        print(f"friction demands left out: {len(moved)} values, {up} higher, {down} lower, largest relative change "
              f"{max(rel) if rel else 0.0:.3g}")
        low = [(r, nm, o, n) for r, nm, o, n in moved if n < 2.0]  # below 2: a contact that holds (above, a normal
        # force tending to 0, a block leaving its contact)
        print(f"  of those below 2 after: {sum(1 for _, _, o, n in low if n != o)} of {len(low)} moved, largest "
              f"change {max((n - o for _, _, o, n in low), default=0.0):.4g}")
        worst = sorted(low, key=lambda m: -abs(m[3] - m[2]))[:5]
        for run, name, o, n in worst:
            print(f"   run {run} {name}: {o:.6g} -> {n:.6g}")
    return 1 if bad else 0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--write", type=Path)
    ap.add_argument("--compare", type=Path, nargs=2)
    ap.add_argument("--scenes", type=int, default=300)
    ap.add_argument("--except", dest="skip", choices=["friction"])
    args = ap.parse_args(argv)
    if args.write:
        write(args.write, args.scenes)
    if args.compare:
        return compare(*args.compare, args.skip == "friction")
    return 0


if __name__ == "__main__":
    sys.exit(main())
