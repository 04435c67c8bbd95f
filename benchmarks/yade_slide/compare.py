"""rockcli's rocking and sliding (``simulate_friction``) against a discrete-element code (YADE): the same scenes.

Run from the repository (YADE is a Debian package: ``apt-get install -y yade``; it runs ``yade_scene.py`` in its
own interpreter, one process per scene; nothing of this is needed by the test suite)::

    python benchmarks/yade_slide/compare.py                  # every scene (about 10 min of CPU in YADE)
    python benchmarks/yade_slide/compare.py --only kobe      # the scenes whose name contains "kobe"
    python benchmarks/yade_slide/compare.py --check          # Coulomb's law in the DEM: tilted gravity, Newmark
    python benchmarks/yade_slide/compare.py --calibrate      # the DEM's rocking impacts against Housner's
    python benchmarks/yade_slide/compare.py --histories out/yade_slide   # keep both codes' time histories
    python benchmarks/yade_slide/compare.py --ks-over-kn 8 --dt 2e-5     # the DEM's sensitivity to its settings

Each scene runs in rockcli (``rockcli.solve.slide.simulate_friction``) and in YADE and prints one row: the
verdict of each (which block overturned or slid off, if any), and per contact (the base: on the ground; the
joint: the body on its plinth) the peak rotation ``psi`` of the block on its support, the peak and the residual
slip ``s`` of the block along its support (rockcli's coordinate: the block's base from its start on the ground, or
from the centre of the plinth's top, in the frame of that top), the CPU time of each. The table is written to
``benchmarks/yade_slide/results.json`` too (``--out``).

The DEM model (``yade_scene.py``) is the plinth harness's (``benchmarks/yade_plinth``): each block a clump of a box
and four spheres of radius ``R_SPHERE`` at its bottom corners; linear spring-dashpot contacts (``ViscElMat``) whose
stiffness and damping scale with the mass they carry (``KN_PER_KG``, ``CN_PER_KG``: calibrated there so that a
single block's free rocking loses what Housner's impact loses); a shear spring ``KS_OVER_KN`` times stiffer than
the normal one and no shear dashpot (README.md: why); friction angle ``atan(mu)`` at each contact; the ground
motion as gravity tilted by ``-ag(t)``; time step ``DT``. rockcli runs with ``tail = TAIL`` and its step cap at
``RK_MAX_STEPS``; where a block topples, both codes' peaks are taken up to ``TOPPLE_RAD`` on its support (``*`` in
the table), where the DEM stops (it has no contact on a block's side).
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

from rockcli.io.units import G
from rockcli.models import Block, Plinth, Stack
from rockcli.pulses import OneSine, RickerSymmetric
from rockcli.records import Record, read_record
from rockcli.solve.slide import simulate_friction

HERE = Path(__file__).resolve().parent
DEPTH = 0.5  # m, out of plane (the model is planar: the depth only scales the masses)
RHO = 2500.0  # kg/m^3 of the body
R_SPHERE = 5e-4  # m: the corner spheres
KN_PER_KG = 1e9 / 1119.0  # N/m per kg carried (the plinth harness's calibration)
CN_PER_KG = 5e6 / 1119.0  # N s/m per kg carried
KS_OVER_KN = 128.0  # a stiff shear spring: the DEM nears rigid Coulomb contacts (README: why, and the sensitivity)
CS_OVER_CN = 0.0  # no shear dashpot: YADE's would act uncapped by Coulomb's law (yade_scene.py says why)
DT = 1e-5  # s (the plinth harness: 2e-5 s; halved for the stiffer shear springs)
TAIL = 3.0  # s of free motion after the excitation, in both codes
TOPPLE_RAD = 1.4  # a block past this on its support is falling over (the DEM has no contact on its side)
SAMPLE_EVERY = 10  # DEM steps between samples (2e-4 s)
LIFT_RAD = 2e-4  # a DEM block rotated less than this on its support has not lifted (contact compliance)
SLIP_M = 1e-4  # a DEM slip below this is the shear springs' deflection, not sliding
OPT = {"ks_over_kn": KS_OVER_KN, "dt": DT}  # the DEM's settings of this run (``--ks-over-kn``, ``--dt``)
RK_MAX_STEPS = 200_000  # rockcli's step cap here (its default, 5e6, takes minutes where a run stalls)
KOBE = os.environ.get("ROCKCLI_KOBE", "/work/shared/records/RSN1119_KOBE_TAZ000.AT2")
KOBE_CUT = (2.0, 17.0)  # s of the record kept: 15 s around its strong motion (0.6-0.7 g between 4 s and 7 s)

CRATE = ("block", (0.5, 1.0))
STATUE_ON_PLINTH = ("stack", (1.79, 0.5), (1.0, 0.6))
SLENDER = ("block", (1.0, 0.5))
SCENES = [
    # name, body, mu (one, or (base, joint)), excitation (kind, a [g], T_p [s]; kobe: scale factor)
    ("crate mu 0.2, sine 0.5 g 1.0 s", CRATE, 0.2, ("sine", 0.5, 1.0)),
    ("crate mu 0.2, kobe", CRATE, 0.2, ("kobe", 1.0, None)),
    ("slender mu 0.4, sine 0.6 g 0.5 s", SLENDER, 0.4, ("sine", 0.6, 0.5)),
    ("slender mu 0.55, ricker 1.0 g 1.0 s", SLENDER, 0.55, ("ricker", 1.0, 1.0)),
    ("slender mu 0.55, sine 1.0 g 0.5 s", SLENDER, 0.55, ("sine", 1.0, 0.5)),
    ("slender mu 0.55, sine 1.0 g 1.0 s", SLENDER, 0.55, ("sine", 1.0, 1.0)),
    ("slender mu 0.5, ricker 0.6 g 0.5 s", SLENDER, 0.5, ("ricker", 0.6, 0.5)),
    ("slender mu 0.5, sine 0.8 g 1.0 s", SLENDER, 0.5, ("sine", 0.8, 1.0)),
    ("statue/plinth mu 0.3, ricker 0.5 g 0.5 s", STATUE_ON_PLINTH, 0.3, ("ricker", 0.5, 0.5)),
    ("statue/plinth mu 0.3, ricker 0.4 g 1.0 s", STATUE_ON_PLINTH, 0.3, ("ricker", 0.4, 1.0)),
    ("statue/plinth mu 0.3, ricker 0.5 g 1.0 s", STATUE_ON_PLINTH, 0.3, ("ricker", 0.5, 1.0)),
    ("statue/plinth mu 0.3, ricker 0.6 g 1.0 s", STATUE_ON_PLINTH, 0.3, ("ricker", 0.6, 1.0)),
    ("statue/plinth mu 0.5, sine 0.3 g 1.0 s", STATUE_ON_PLINTH, 0.5, ("sine", 0.3, 1.0)),
    ("statue/plinth mu 0.5, kobe", STATUE_ON_PLINTH, 0.5, ("kobe", 1.0, None)),
    ("statue/plinth mu 0.5, kobe x 0.7", STATUE_ON_PLINTH, 0.5, ("kobe", 0.7, None)),
    ("statue/plinth mu 0.5, kobe x 0.5", STATUE_ON_PLINTH, 0.5, ("kobe", 0.5, None)),
    ("statue/plinth mu 0.5 / 0.2, kobe x 0.5", STATUE_ON_PLINTH, (0.5, 0.2), ("kobe", 0.5, None)),
    ("statue/plinth mu 0.5 / 0.2, kobe x 0.7", STATUE_ON_PLINTH, (0.5, 0.2), ("kobe", 0.7, None)),
]


def make_body(spec):
    if spec[0] == "block":
        return Block.from_dimensions(*spec[1], "block")
    return Stack(Block.from_dimensions(*spec[1], "body"), Plinth(*spec[2]))


def excitation(spec):
    kind, a, T = spec
    if kind == "ricker":
        return RickerSymmetric(a * G, T)
    if kind == "sine":
        return OneSine(a * G, T)
    if kind == "const":  # a constant ground acceleration a [g] for T seconds (the DEM's Coulomb check)
        n = int(round(T / 1e-3))
        return Record(np.full(n + 1, a * G), 1e-3, f"const {a:g} g")
    rec = read_record(KOBE)
    i0, i1 = (int(round(t / rec.dt)) for t in KOBE_CUT)
    return Record(np.asarray(rec.acc[i0:i1 + 1], float) * a, rec.dt, f"kobe {KOBE_CUT[0]:g}-{KOBE_CUT[1]:g} s x{a:g}")


def ground_samples(exc):
    """``(t, ag, t_end)``: the ground acceleration as both codes read it (piecewise linear) and its end."""
    if hasattr(exc, "acc"):
        t = exc.dt * np.arange(exc.acc.size)
        return t, np.asarray(exc.acc, float), float(t[-1])
    _, te = exc.support()
    t = np.linspace(0.0, te, int(round(te / 1e-4)) + 1)
    return t, np.array([float(exc.acceleration(x)) for x in t]), float(te)


def dem_blocks(body, mu):
    """The scene's blocks bottom to top: ``[b, h, density, kn, cn, mu]`` (the masses from RHO and DEPTH)."""
    if isinstance(body, Stack):
        mus = mu if isinstance(mu, (tuple, list)) else (mu, mu)
        m1 = RHO * 4 * body.b1 * body.h1 * DEPTH
        m2 = body.m2 * m1
        rho2 = m2 / (4 * body.b2 * body.h2 * DEPTH)
        return [[body.b2, body.h2, rho2, KN_PER_KG * (m1 + m2), CN_PER_KG * (m1 + m2), float(mus[0])],
                [body.b1, body.h1, RHO, KN_PER_KG * m1, CN_PER_KG * m1, float(mus[1])]]
    mu0 = mu[0] if isinstance(mu, (tuple, list)) else mu
    m = RHO * 4 * body.b * body.h * DEPTH
    return [[body.b, body.h, RHO, KN_PER_KG * m, CN_PER_KG * m, float(mu0)]]


def _yade(scene, workdir):
    """Run one scene file in YADE: its output and the CPU time of the process."""
    sp, op = Path(workdir) / "scene.json", Path(workdir) / "out.json"
    sp.write_text(json.dumps(scene))
    ru0 = os.times()
    subprocess.run(["yade", "-n", "-x", str(HERE / "yade_scene.py"), str(sp), str(op)], check=True,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    ru1 = os.times()
    cpu = (ru1.children_user - ru0.children_user) + (ru1.children_system - ru0.children_system)
    return json.loads(op.read_text()), cpu


def scene_dict(blocks, t_end, ag_t, ag, sample_every=SAMPLE_EVERY, **extra):
    d = {"blocks": blocks, "depth": DEPTH, "r": R_SPHERE, "ks_over_kn": OPT["ks_over_kn"], "cs_over_cn": CS_OVER_CN,
         "dt": OPT["dt"], "t_end": t_end, "t_settle": 0.05, "g": G, "ag_t": list(ag_t), "ag": list(ag),
         "sample_every": sample_every, "topple_rad": TOPPLE_RAD}
    d.update(extra)
    return d


def run_yade(body, mu, exc, t_end, workdir, sample_every=SAMPLE_EVERY):
    """One scene in YADE: per interface the peaks, the verdict, the CPU time and the histories."""
    t, ag, _ = ground_samples(exc)
    d, cpu = _yade(scene_dict(dem_blocks(body, mu), t_end, t.tolist(), ag.tolist(), sample_every), workdir)
    tt = np.array(d["t"])
    psi, s = np.array(d["psi"]), np.array(d["s"])
    names = ["base", "joint"][:psi.shape[0]]
    inter = {}
    for j, nm in enumerate(names):
        k = int(np.argmax(np.abs(s[j])))
        inter[nm] = {"psi_max": float(np.max(np.abs(psi[j]))), "slide_max_m": float(np.abs(s[j][k])),
                     "slide_max_signed_m": float(s[j][k]), "slide_residual_m": float(s[j][-1]),
                     "t_slide": _first(tt, np.abs(s[j]) > SLIP_M), "t_uplift": _first(tt, np.abs(psi[j]) > LIFT_RAD)}
    stop = d["stopped"]
    block_names = ["block"] if len(names) == 1 else ["plinth", "body"]
    if stop is not None:
        verdict = ("overturned" if stop[0] == "topple" else "slid off") + f" ({block_names[stop[1]]})"
    elif any(v["psi_max"] > LIFT_RAD or v["slide_max_m"] > SLIP_M for v in inter.values()):
        verdict = "survives"
    else:
        verdict = "no motion"
    return {"verdict": verdict, "stopped": stop, "t_stop": float(tt[-1]) if stop else None, "interfaces": inter,
            "cpu_s": cpu, "steps": d["steps"], "hist": {"t": tt, "psi": psi, "s": s}}


def _first(t, mask):
    i = np.flatnonzero(mask)
    return float(t[i[0]]) if i.size else None


def run_rockcli(body, mu, exc):
    mus = tuple(mu) if isinstance(mu, (tuple, list)) else mu
    t0 = time.process_time()
    r = simulate_friction(body, exc, mus, tail=TAIL, history=True, max_steps=RK_MAX_STEPS)
    cpu = time.process_time() - t0
    if cpu < 0.2:  # short runs: the mean of a few
        t0 = time.process_time()
        for _ in range(5):
            simulate_friction(body, exc, mus, tail=TAIL, max_steps=RK_MAX_STEPS)
        cpu = (time.process_time() - t0) / 5
    verdict = r.verdict
    if r.verdict == "overturned":
        verdict += f" ({r.toppled if r.joint is not None else 'block'})"
    elif r.verdict == "slid off":
        verdict += " (body)"
    inter = {}
    for p in r.interfaces:
        inter[p.name] = {"psi_max": p.psi_max, "slide_max_m": p.slide_max_m, "slide_residual_m": p.slide_residual_m,
                         "t_slide": _num(p.t_slide), "t_uplift": _num(p.t_uplift), "n_slips": p.n_slips,
                         "n_impacts": p.n_impacts, "tilt_max": p.tilt_max}
    return {"verdict": verdict, "status": r.status, "t_fail": _num(r.t_fail), "t_end": r.t_end, "steps": r.steps,
            "n_jumps": r.n_jumps, "n_inconsistent": r.n_inconsistent, "n_slip_impacts": r.n_slip_impacts,
            "interfaces": inter, "cpu_s": cpu, "history": r.history}


def rk_until_topple_rad(H, n):
    """rockcli's peaks (``psi``, ``|s|``, and ``s`` then) over its history rows until a block first passes
    ``TOPPLE_RAD`` on its support (where the DEM stops), and that time: the slips of a falling block grow fast in
    its last few tenths of a radian, which the DEM does not run."""
    o = 3 + 2 * n + 2
    psi = np.abs(H[:, [o + 4 * j + 2 for j in range(n)]])
    past = np.flatnonzero(np.any(psi >= TOPPLE_RAD, axis=1))
    k = past[0] if past.size else H.shape[0]
    out = {}
    for j, nm in enumerate(["base", "joint"][:n]):
        sj = H[:k, o + 4 * j]
        out[nm] = {"psi_max": float(psi[:k, j].max()), "slide_max_m": float(np.abs(sj).max()),
                   "slide_residual_m": float(sj[-1])}
    return out, (float(H[k, 0]) if past.size else None)


def _num(x):
    return None if x is None or not math.isfinite(x) else float(x)


# --- an independent Newmark two-way rigid block (the squat crate's closed form, for the DEM's check) ----------

def newmark(t, ag, mu, g=G):
    """The two-way rigid-plastic block on the piecewise linear ground acceleration ``ag(t)``, integrated exactly
    interval by interval: ``s'' = -ag - mu g sign(s')`` while it slides, sticking when ``s' = 0`` and ``|ag| <= mu
    g``. Returns ``s`` at the samples ``t`` and its value at the end of the motion (once it sticks again)."""
    fy = mu * g
    s, v, d = 0.0, 0.0, 0  # slip, its rate, the sliding direction (0: stuck)
    out = np.zeros(t.size)
    for i in range(t.size - 1):
        t0, t1 = t[i], t[i + 1]
        a0, k = ag[i], (ag[i + 1] - ag[i]) / (t1 - t0)
        tau, span = 0.0, t1 - t0
        while tau < span - 1e-15:
            a_now = a0 + k * tau
            if d == 0:
                if abs(a_now) > fy * (1 + 1e-12):
                    d = -1 if a_now > 0 else 1
                    continue
                # stuck until ag leaves the band [-fy, fy]
                ex = None
                if k > 0:
                    ex = (fy - a_now) / k
                elif k < 0:
                    ex = (-fy - a_now) / k
                if ex is None or tau + ex >= span:
                    tau = span
                else:
                    tau += max(ex, 0.0)
                    d = -1 if k > 0 else 1
                continue
            # sliding in direction d: v(x) = v - (a_now + d fy) x - k x^2 / 2, x from tau
            A, B, C = -k / 2, -(a_now + d * fy), v
            rest = span - tau
            roots = _roots(A, B, C)
            stop = min([x for x in roots if 1e-14 < x <= rest], default=None)
            x = rest if stop is None else stop
            s += v * x - (a_now + d * fy) * x * x / 2 - k * x ** 3 / 6
            v = 0.0 if stop is not None else C + B * x + A * x * x
            tau += x
            if stop is not None:
                d = 0
        out[i + 1] = s
    # after the record: decelerates at mu g to rest
    s_end = s + (v * abs(v) / (2 * fy) if v != 0 else 0.0)
    return out, s_end


def padded(t, ag, tail):
    """The samples with ``tail`` seconds of still ground after them (the same spacing)."""
    dt = t[1] - t[0]
    k = int(round(tail / dt))
    return np.concatenate([t, t[-1] + dt * np.arange(1, k + 1)]), np.concatenate([ag, np.zeros(k)])


def _roots(A, B, C):
    if abs(A) < 1e-300:
        return [-C / B] if B != 0 else []
    disc = B * B - 4 * A * C
    if disc < 0:
        return []
    q = -0.5 * (B + math.copysign(math.sqrt(disc), B))
    r = [q / A] if q != 0 else []
    if q != 0:
        r.append(C / q)
    return r


def check(workdir):
    """Coulomb's law in the DEM: (1) the crate on a constant ground acceleration of 0.3 g for 1 s (mu = 0.2)
    slides at (0.3 - 0.2) g; (2) the crate under the one-sine pulse slides as Newmark's rigid block."""
    body = make_body(CRATE)
    exc = excitation(("const", 0.3, 1.0))
    dem = run_yade(body, 0.2, exc, 1.0, workdir, sample_every=5)
    h = dem["hist"]
    sel = (h["t"] > 0.2) & (h["t"] < 0.95)
    c = np.polyfit(h["t"][sel], h["s"][0][sel], 2)
    print(f"(1) constant ag = 0.3 g, mu = 0.2: the DEM's slip accelerates at {2 * c[0]:.5f} m/s^2, Coulomb "
          f"{-(0.3 - 0.2) * G:.5f} m/s^2 ({(2 * c[0]) / (-(0.1 * G)) - 1:+.2%}); s(1 s) = {h['s'][0][-1]:.5f} m "
          f"against {-0.05 * G:.5f} m; peak rotation {dem['interfaces']['base']['psi_max']:.2e} rad "
          f"(CPU {dem['cpu_s']:.1f} s)")
    exc = excitation(("sine", 0.5, 1.0))
    t, ag, te = ground_samples(exc)
    t, ag = padded(t, ag, TAIL)
    nm, nm_end = newmark(t, ag, 0.2)
    dem = run_yade(body, 0.2, exc, te + TAIL, workdir, sample_every=5)
    rk = run_rockcli(body, 0.2, exc)
    h = dem["hist"]
    nm_on_dem = np.interp(h["t"], t, nm)
    if os.environ.get("YADE_SLIDE_DEBUG"):
        np.savez("out/check_sine.npz", t=h["t"], s=h["s"][0], psi=h["psi"][0], nm=nm_on_dem)
    k = int(np.argmax(np.abs(nm)))
    print(f"(2) one-sine 0.5 g 1.0 s, mu = 0.2: peak slip Newmark {nm[k]:+.5f} m at {t[k]:.3f} s, DEM "
          f"{dem['interfaces']['base']['slide_max_signed_m']:+.5f} m, rockcli "
          f"{rk['interfaces']['base']['slide_max_m']:.5f} "
          f"m (|s|); residual Newmark {nm_end:+.5f} m, DEM {dem['interfaces']['base']['slide_residual_m']:+.5f} m, "
          f"rockcli {rk['interfaces']['base']['slide_residual_m']:+.5f} m; the DEM's largest departure from "
          f"Newmark's history {np.max(np.abs(h['s'][0] - nm_on_dem)):.2e} m")
    for label, exc in ((f"kobe {KOBE_CUT[0]:g}-{KOBE_CUT[1]:g} s", excitation(("kobe", 1.0, None))),
                       ("the whole kobe record", read_record(KOBE))):
        t, ag, te = ground_samples(exc)
        nm, nm_end = newmark(t, ag, 0.2)
        rk = run_rockcli(body, 0.2, exc)
        print(f"(3) {label}, mu = 0.2 (no DEM): peak |slip| Newmark {np.max(np.abs(nm)):.5f} m, rockcli "
              f"{rk['interfaces']['base']['slide_max_m']:.5f} m; residual Newmark {nm_end:+.5f} m, rockcli "
              f"{rk['interfaces']['base']['slide_residual_m']:+.5f} m (its run ends at {rk['t_end']:.1f} s)")


def calibrate(workdir, mu=5.0):
    """The statue released from a tilt of 0.15 rad on the ground (friction ``mu``: no slip): the ratio of its
    angular velocities across impacts, against Housner's ``1 - 1.5 sin^2 alpha``."""
    h, w = 1.79, 0.5
    b, hh = w / 2, h / 2
    body = Block.from_dimensions(h, w)
    d, cpu = _yade(scene_dict(dem_blocks(body, mu), 3.0, [0.0, 1.0], [0.0, 0.0], 5, theta0=0.15), workdir)
    th = np.array(d["theta"][0])
    a = np.abs(th)
    pk = [i for i in range(1, a.size - 1) if a[i] >= a[i - 1] and a[i] > a[i + 1] and a[i] > 1e-5]
    alpha, R = math.atan(b / hh), math.hypot(b, hh)
    p2 = 0.75 * G / R

    def rate(x):
        return math.sqrt(2 * p2 * (math.cos(alpha - abs(x)) - math.cos(alpha)))

    ratios = [rate(th[pk[i + 1]]) / rate(th[pk[i]]) for i in range(len(pk) - 1)]
    s = np.array(d["s"][0])
    print(f"mu {mu:g}: peaks {[round(float(th[i]), 5) for i in pk]}; DEM ratio per impact {np.mean(ratios):.4f} "
          f"(each: {[round(x, 4) for x in ratios]}); Housner 1 - 1.5 sin^2 alpha = "
          f"{1 - 1.5 * math.sin(alpha) ** 2:.4f}; slip range {s.min():+.2e} .. {s.max():+.2e} m (CPU {cpu:.0f} s)")


def _cm(x):
    return "-" if x is None else f"{100 * x:.2f}"


def table_row(name, rk, dem, cut):
    """One markdown row: per contact rockcli / YADE (``*``: rockcli's up to where the DEM stopped)."""
    cells = [name, f"{rk['verdict']} / {dem['verdict']}"]
    tf = [rk["t_fail"], dem["t_stop"]]
    if rk.get("until_topple_rad", {}).get("t") is not None:
        tf[0] = rk["until_topple_rad"]["t"]  # when it passed TOPPLE_RAD, as the DEM's stop
    cells.append(" / ".join("-" if x is None else f"{x:.2f}" for x in tf))
    for nm in ("base", "joint"):
        r, d = rk["interfaces"].get(nm), dem["interfaces"].get(nm)
        if r is None:
            cells += ["-", "-", "-"]
            continue
        star = ""
        if cut is not None:
            r, star = cut[nm], "*"
        cells.append(f"{r['psi_max']:.4f}{star} / {d['psi_max']:.4f}")
        cells.append(f"{_cm(r['slide_max_m'])}{star} / {_cm(d['slide_max_m'])}")
        cells.append(f"{100 * r['slide_residual_m']:+.2f}{star} / {100 * d['slide_residual_m']:+.2f}")
    cells.append(f"{rk['cpu_s']:.3f} / {dem['cpu_s']:.0f}")
    return "| " + " | ".join(cells) + " |"


HEADER = ("| scene | verdict: rockcli / YADE | t fail [s] | base psi_max [rad] | base s_max [cm] | base s_end [cm] "
          "| joint psi_max [rad] | joint s_max [cm] | joint s_end [cm] | CPU [s] |\n"
          "|---|---|---|---|---|---|---|---|---|---|")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--only", default="")
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--calibrate", action="store_true")
    ap.add_argument("--ks-over-kn", type=float, default=KS_OVER_KN, help="the DEM's shear over normal stiffness")
    ap.add_argument("--dt", type=float, default=DT, help="the DEM's time step [s]")
    ap.add_argument("--out", default=str(HERE / "results.json"))
    ap.add_argument("--histories", default="", help="a folder for both codes' time histories (npz per scene)")
    ap.add_argument("--rockcli-only", action="store_true",
                    help="rerun rockcli's side only; YADE's from the stored --out file (no YADE needed)")
    args = ap.parse_args(argv)
    OPT.update(ks_over_kn=args.ks_over_kn, dt=args.dt)
    # compile (or load) rockcli's kernels before anything is timed
    simulate_friction(Block.from_dimensions(0.5, 1.0), OneSine(0.3 * G, 0.5), 0.2)
    with tempfile.TemporaryDirectory() as wd:
        if args.calibrate:
            for mu in (5.0, 0.5):
                calibrate(wd, mu)
            return 0
        if args.check:
            check(wd)
            return 0
        rows = []
        stored = {}
        if args.rockcli_only:
            stored = {r["scene"]: r["yade"] for r in json.loads(Path(args.out).read_text())}
        print(HEADER)
        for name, bspec, mu, spec in SCENES:
            if args.only and args.only not in name:
                continue
            body = make_body(bspec)
            exc = excitation(spec)
            _, _, t_exc = ground_samples(exc)
            rk = run_rockcli(body, mu, exc)
            dem = dict(stored[name], hist=None) if args.rockcli_only else run_yade(body, mu, exc, t_exc + TAIL, wd)
            H = rk.pop("history")
            n = 2 if isinstance(body, Stack) else 1
            cut = None
            if dem["stopped"] is not None or rk["t_fail"] is not None:
                cut, t_cut = rk_until_topple_rad(H, n)
                rk["until_topple_rad"] = dict(cut, t=t_cut)
            if args.histories and not args.rockcli_only:
                Path(args.histories).mkdir(parents=True, exist_ok=True)
                fn = Path(args.histories) / (name.replace(" ", "_").replace(",", "").replace("/", "_") + ".npz")
                np.savez_compressed(fn, dem_t=dem["hist"]["t"], dem_psi=dem["hist"]["psi"], dem_s=dem["hist"]["s"],
                                    rk_history=H)
            dem.pop("hist")
            rows.append({"scene": name, "mu": mu, "excitation": list(spec), "rockcli": rk, "yade": dem})
            print(table_row(name, rk, dem, cut), flush=True)
        Path(args.out).write_text(json.dumps(rows, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
