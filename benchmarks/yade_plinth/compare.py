"""rockcli's body on a plinth against a discrete-element code (YADE): the same scenes, verdicts and peaks.

Run from the repository (YADE is a Debian package: ``apt-get install -y yade``; it runs ``yade_scene.py`` in its
own interpreter, one process per scene; nothing of this is needed by the test suite)::

    python benchmarks/yade_plinth/compare.py                 # every scene (about 10 min of CPU)
    python benchmarks/yade_plinth/compare.py --only kobe     # the scenes whose name contains "kobe"
    python benchmarks/yade_plinth/compare.py --calibrate     # the corner contacts' rocking restitution

Each scene runs in rockcli's slow reference (``rockcli.reference.stack``), in the compiled kernel
(``rockcli.solve.simulate_stack``, when present) and in YADE, and prints one row per scene: the verdict (which
block topples, if any) and the peak rotation of each block on its own support (the body on the plinth, the
plinth on the ground) over the same time (the excitation and ``TAIL`` seconds after it). The table is written to
``benchmarks/yade_plinth/results.json`` too (``--out``).

The DEM model (``yade_scene.py``): each block a clump of a box and four spheres of radius ``R_SPHERE`` at its
bottom corners; corner contacts are linear spring-dashpots (``ViscElMat``) scaled with the mass they carry,
``KN_PER_KG`` and ``CN_PER_KG`` per kg, calibrated once (``--calibrate``) so that a single block's free rocking
loses what Housner's impact loses (the statue 1.79 m x 0.5 m: 0.8928 against 0.8914 per impact); friction angle
80 deg (nothing slides); the ground motion as an inertial force (gravity tilted by ``-ag(t)``); time step 2e-5 s.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

from rockcli.models import Block, Plinth, Stack
from rockcli.pulses import OneSine, RickerSymmetric
from rockcli.records import Record, read_record
from rockcli.reference.stack import reference_plinth
from rockcli.io.units import G

HERE = Path(__file__).resolve().parent
DEPTH = 0.5  # m, out of plane (the model is planar: the depth only scales the masses)
RHO = 2500.0  # kg/m^3 of the body
R_SPHERE = 5e-4  # m: the corner spheres (the pivot sits R_SPHERE inside the corner: alpha off by r/b)
KN_PER_KG = 1e9 / 1119.0  # N/m per kg carried (the statue: 1,119 kg on kn = 1e9 N/m)
CN_PER_KG = 5e6 / 1119.0  # N s/m per kg carried
DT = 2e-5  # s
TAIL = 3.0  # s of free motion after the excitation, in every code
TOPPLE_RAD = 1.4  # a block past this on its support is falling over (the DEM has no contact on its side)

STATUE = (1.79, 0.5)
SCENES = [
    # name, body (height, width), plinth (height, width, mass ratio or None), excitation
    ("wide plinth, ricker 0.35 g 1.0 s", STATUE, (0.5, 1.2, None), ("ricker", 0.35, 1.0)),
    ("wide plinth, sine 0.3 g 1.2 s", STATUE, (0.5, 1.2, None), ("sine", 0.3, 1.2)),
    ("tall plinth, ricker 0.3 g 1.0 s", STATUE, (1.0, 0.6, None), ("ricker", 0.3, 1.0)),
    ("tall plinth, sine 0.25 g 1.0 s", STATUE, (1.0, 0.6, None), ("sine", 0.25, 1.0)),
    ("tall plinth, ricker 0.6 g 0.5 s", STATUE, (1.0, 0.6, None), ("ricker", 0.6, 0.5)),
    ("slender pair, ricker 0.45 g 0.9 s", (1.2, 0.3), (1.0, 0.5, 1.5), ("ricker", 0.45, 0.9)),
    ("slender pair, sine 0.35 g 0.8 s", (1.2, 0.3), (1.0, 0.5, 1.5), ("sine", 0.35, 0.8)),
    ("tall plinth, kobe TAZ000 2-12 s x 0.5", STATUE, (1.0, 0.6, None), ("kobe", 0.5, None)),
    ("wide plinth, kobe TAZ000 2-12 s x 1.0", STATUE, (0.5, 1.2, None), ("kobe", 1.0, None)),
]


def excitation(spec):
    kind, a, T = spec
    if kind == "ricker":
        return RickerSymmetric(a * G, T)
    if kind == "sine":
        return OneSine(a * G, T)
    path = Path(os.environ.get("ROCKCLI_KOBE", "/work/shared/records/RSN1119_KOBE_TAZ000.AT2"))
    rec = read_record(str(path))
    piece = rec.acc[200:1201] * a  # 2 s to 12 s
    return Record(piece, rec.dt, f"kobe x{a:g}")


def ground_samples(exc):
    """``(t, ag, t_end)``: the ground acceleration as YADE reads it (piecewise linear) and its end."""
    if hasattr(exc, "acc"):
        t = exc.dt * np.arange(exc.acc.size)
        return t, np.asarray(exc.acc, float), float(t[-1])
    ts, te = exc.support()
    t = np.linspace(0.0, te, int(te / 1e-3) + 1)
    return t, np.array([float(exc.acceleration(x)) for x in t]), float(te)


def run_yade(stack, exc, t_end, workdir):
    """One scene in YADE: ``{"peak": [plinth, body], "toppled": -1/0/1, "cpu_s": ..}``."""
    b1, h1, b2, h2 = stack.b1, stack.h1, stack.b2, stack.h2
    m1 = RHO * 4 * b1 * h1 * DEPTH
    m2 = stack.m2 * m1
    rho2 = m2 / (4 * b2 * h2 * DEPTH)
    t, ag, _ = ground_samples(exc)
    scene = {"blocks": [[b2, h2, rho2, KN_PER_KG * (m1 + m2), CN_PER_KG * (m1 + m2)],
                        [b1, h1, RHO, KN_PER_KG * m1, CN_PER_KG * m1]],
             "depth": DEPTH, "r": R_SPHERE, "ks_over_kn": 0.5, "friction_deg": 80.0, "dt": DT, "t_end": t_end,
             "t_settle": 0.05, "g": G, "ag_t": t.tolist(), "ag": ag.tolist(), "sample_every": 5,
             "topple_rad": TOPPLE_RAD + 0.05}
    return _yade(scene, workdir)


def _yade(scene, workdir):
    sp, op = Path(workdir) / "scene.json", Path(workdir) / "out.json"
    sp.write_text(json.dumps(scene))
    ru0 = os.times()
    subprocess.run(["yade", "-n", "-x", str(HERE / "yade_scene.py"), str(sp), str(op)], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    ru1 = os.times()
    cpu = (ru1.children_user - ru0.children_user) + (ru1.children_system - ru0.children_system)
    d = json.loads(op.read_text())
    th = np.array(d["theta"])  # absolute angles, bottom to top
    rel = np.vstack([th[0], th[1] - th[0]]) if th.shape[0] > 1 else th
    peak = np.max(np.abs(rel), axis=1)
    toppled = -1
    over = [np.nonzero(np.abs(r) > TOPPLE_RAD)[0] for r in rel]
    firsts = [o[0] if o.size else None for o in over]
    cand = [(f, i) for i, f in enumerate(firsts) if f is not None]
    if cand:
        toppled = min(cand)[1]
    return {"peak": peak.tolist(), "toppled": toppled, "cpu_s": cpu, "steps": d["steps"], "t": d["t"],
            "theta": d["theta"]}


def run_kernel(stack, exc, tail):
    try:
        from rockcli.solve import simulate_stack
    except ImportError:
        return None
    r = simulate_stack(stack, exc, horizon=tail, tail=tail)
    t0 = time.process_time()
    for _ in range(5):
        simulate_stack(stack, exc, horizon=tail, tail=tail)
    cpu = (time.process_time() - t0) / 5
    return {"peak": [r.plinth.theta_max, r.body.theta_max], "toppled": {"plinth": 0, "body": 1}.get(r.toppled, -1),
            "cpu_s": cpu}


def verdict(toppled, peak, lift=2e-4):
    if toppled >= 0:
        return ("plinth" if toppled == 0 else "body") + " topples"
    moved = [name for name, p in zip(("plinth", "body"), peak) if p > lift]
    return "rocks (" + " and ".join(moved) + ")" if moved else "no uplift"


def calibrate(workdir):
    """A single block released from a tilt of 0.15 rad: the ratio of angular velocities across impacts."""
    h, w = STATUE
    b, hh = w / 2, h / 2
    m = RHO * 4 * b * hh * DEPTH
    scene = {"blocks": [[b, hh, RHO, KN_PER_KG * m, CN_PER_KG * m]], "depth": DEPTH, "r": R_SPHERE,
             "ks_over_kn": 0.5, "friction_deg": 80.0, "dt": DT, "t_end": 3.0, "g": G, "ag_t": [0.0, 1.0],
             "ag": [0.0, 0.0], "theta0": 0.15, "sample_every": 5}
    d = _yade(scene, workdir)
    th = np.array(d["theta"][0])
    a = np.abs(th)
    pk = [i for i in range(1, a.size - 1) if a[i] >= a[i - 1] and a[i] > a[i + 1] and a[i] > 1e-5]
    alpha, R = math.atan(b / hh), math.hypot(b, hh)
    p2 = 0.75 * G / R

    def rate(x):
        return math.sqrt(2 * p2 * (math.cos(alpha - abs(x)) - math.cos(alpha)))

    ratios = [rate(th[pk[i + 1]]) / rate(th[pk[i]]) for i in range(len(pk) - 1)]
    print(f"peaks {[round(float(th[i]), 5) for i in pk]}")
    print(f"DEM ratio per impact {np.mean(ratios):.4f} (each: {[round(x, 4) for x in ratios]}); "
          f"Housner 1 - 1.5 sin^2 alpha = {1 - 1.5 * math.sin(alpha) ** 2:.4f}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default="")
    ap.add_argument("--calibrate", action="store_true")
    ap.add_argument("--out", default=str(HERE / "results.json"))
    args = ap.parse_args(argv)
    with tempfile.TemporaryDirectory() as wd:
        if args.calibrate:
            calibrate(wd)
            return 0
        rows = []
        print("| scene | reference, kernel | YADE | body peak / alpha1: ref / kernel / YADE | plinth peak / alpha_asm: "
              "ref / kernel / YADE | CPU s: ref / kernel / YADE |")
        print("|---|---|---|---|---|---|")
        for name, body, plinth, spec in SCENES:
            if args.only and args.only not in name:
                continue
            stack = Stack(Block.from_dimensions(*body, "body"), Plinth(*plinth))
            exc = excitation(spec)
            _, _, t_exc = ground_samples(exc)
            t0 = time.process_time()
            ref = reference_plinth(stack, exc, horizon=TAIL)
            ref_cpu = time.process_time() - t0
            ker = run_kernel(stack, exc, TAIL)
            dem = run_yade(stack, exc, t_exc + TAIL, wd)
            row = {"scene": name, "alpha": [stack.alpha2, stack.body.alpha],
                   "reference": {"peak": ref.peak, "toppled": ref.toppled, "cpu_s": ref_cpu,
                                 "friction": ref.friction, "n_impacts": ref.n_impacts},
                   "kernel": ker, "yade": {k: v for k, v in dem.items() if k not in ("t", "theta")}}
            rows.append(row)
            al = (stack.alpha_asm, stack.body.alpha)  # peaks over: the plinth's alpha_asm, the body's alpha1
            r_al = [p / a for p, a in zip(ref.peak, al)]
            d_al = [p / a for p, a in zip(dem["peak"], al)]
            k_al = [p / a for p, a in zip(ker["peak"], al)] if ker else [math.nan, math.nan]
            print(f"| {name} | {verdict(ref.toppled, ref.peak)} | {verdict(dem['toppled'], dem['peak'])} | "
                  f"{r_al[1]:.4f} / {k_al[1]:.4f} / {d_al[1]:.4f} | {r_al[0]:.4f} / {k_al[0]:.4f} / {d_al[0]:.4f} | "
                  f"{ref_cpu:.2f} / {ker['cpu_s'] if ker else math.nan:.4f} / {dem['cpu_s']:.1f} |", flush=True)
        Path(args.out).write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
