"""Do two versions of the friction driver give the same answers, bit for bit, on random scenes?

    python benchmarks/friction_snapshot.py --write out/fr_now.json [--scenes 160 --seed 11]
    python benchmarks/friction_snapshot.py --compare out/fr_old.json out/fr_now.json

``--write`` runs ``simulate_friction`` (no reference) on random scenes of every kind the driver has (one block, a
body on its plinth, three drums; rigid ground and linear bearings; pulses and short random records; a quarter of
them with a coefficient of restitution where the body allows one) and writes every run's JSON answer. Run it in a
worktree of the older commit (``PYTHONPATH=<worktree> python <worktree>/benchmarks/friction_snapshot.py`` or this
file) and in the working tree, then ``--compare``: prints the scenes whose answers differ (any word, any number
not exactly equal; NaN equals NaN) and exits 1 when one does. Scenes come from
``bench_friction_reference.scene`` (the same seeds give the same scenes) and, for drums, from this file.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(__file__))
sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "tests"))

KINDS = ("rigid1", "rigid2", "linear1", "linear2", "drums3")


def drum_scene(seed: int, records: bool):
    from synthetic import random_record

    from rockcli.io.units import G
    from rockcli.models.drums import DrumColumn
    from rockcli.pulses import OneSine, RickerAntisymmetric, RickerSymmetric

    rng = np.random.default_rng(seed)
    drums = tuple((float(rng.uniform(0.4, 1.2)), float(rng.uniform(0.3, 0.8))) for _ in range(3))
    body = DrumColumn(drums)
    mu = tuple(float(rng.uniform(0.3, 1.0)) for _ in range(3))
    if records and rng.random() < 0.5:
        exc = random_record(rng, pga_g=(0.1, 0.4), n_range=(150, 300))
    else:
        kinds = (RickerSymmetric, OneSine, RickerAntisymmetric)
        exc = kinds[int(rng.integers(0, 3))](rng.uniform(0.1, 0.5) * G, rng.uniform(0.25, 1.2))
    return body, exc, mu, None


def write(path: str, scenes: int, seed: int) -> int:
    from bench_friction_reference import scene

    from rockcli.solve.slide import simulate_friction

    out = []
    t0 = time.process_time()
    for i in range(scenes):
        kind = KINDS[i % len(KINDS)]
        s = seed * 1000 + i
        if kind == "drums3":
            body, exc, mu, iso = drum_scene(s, True)
        else:
            body, exc, mu, iso = scene(s, kind, True)
        e = None
        if kind != "drums3" and np.random.default_rng(s + 7).random() < 0.25:
            e = float(np.random.default_rng(s + 7).uniform(0.5, 0.95))
        try:
            r = simulate_friction(body, exc, mu, iso, restitution=e)
            ans = r.as_dict()
        except Exception as err:  # an error is an answer too: it must not change either
            ans = {"error": f"{type(err).__name__}: {err}"}
        out.append({"seed": s, "kind": kind, "restitution": e, "answer": ans})
    with open(path, "w") as f:
        json.dump(out, f, indent=0, sort_keys=True, default=str)
    print(f"{scenes} scenes written to {path} ({time.process_time() - t0:.1f} s CPU)")
    return 0


def _diff(a, b, where, out):
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                out.append(f"{where}.{k}: only in {'new' if k in b else 'old'}")
            else:
                _diff(a[k], b[k], f"{where}.{k}", out)
    elif isinstance(a, list) and isinstance(b, list) and len(a) == len(b):
        for i, (x, y) in enumerate(zip(a, b)):
            _diff(x, y, f"{where}[{i}]", out)
    elif isinstance(a, float) and isinstance(b, float) and math.isnan(a) and math.isnan(b):
        return
    elif a != b:
        out.append(f"{where}: {a!r} -> {b!r}")


def compare(old: str, new: str) -> int:
    with open(old) as f:
        A = json.load(f)
    with open(new) as f:
        B = json.load(f)
    if len(A) != len(B):
        print(f"different scene counts: {len(A)} and {len(B)}")
        return 1
    bad = 0
    for a, b in zip(A, B):
        d = []
        _diff(a, b, "", d)
        if d:
            bad += 1
            print(f"seed {a['seed']} ({a['kind']}): {len(d)} differences, e.g. {'; '.join(d[:4])}")
    print(f"{len(A) - bad} of {len(A)} scenes bit for bit")
    return 1 if bad else 0


def main() -> int:
    ap = argparse.ArgumentParser()
    ap.add_argument("--write")
    ap.add_argument("--compare", nargs=2)
    ap.add_argument("--scenes", type=int, default=160)
    ap.add_argument("--seed", type=int, default=11)
    a = ap.parse_args()
    if a.compare:
        return compare(*a.compare)
    if a.write:
        return write(a.write, a.scenes, a.seed)
    ap.error("give --write FILE or --compare OLD NEW")
    return 2


if __name__ == "__main__":
    sys.exit(main())
