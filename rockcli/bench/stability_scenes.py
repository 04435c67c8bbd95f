"""The stiff and extreme scenes of the stability study (:data:`STABILITY_SCENES`) and random ones.

Each :class:`StabilityScene` builds its ``(block, foundation, excitation)`` when run; some build a
record on purpose (a long band-limited record, a 10 g spike, a record that ends while the block is in
the air or exactly as |theta| reaches alpha).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable

import numpy as np

from rockcli.bench.scenes import parse_foundation
from rockcli.io.units import G


@dataclass(frozen=True)
class StabilityScene:
    """A stiff or extreme scene: ``build()`` returns ``(block, foundation, excitation)`` (or raises
    :class:`SceneUnavailable` / RockcliInputError when refused)."""

    name: str
    title: str
    build: Callable
    expect: str | None = None  # the verdict physics demands, when it is known
    unproven_ok: bool = False  # NOT PROVEN at the horizon is the stated behaviour
    unproven_why: str = "an undamped base that keeps lifting the block"  # ... and why (the README's limit)
    wall_budget_s: float = 30.0
    step_budget: int = 5_000_000  # the solver's default step cap
    tail: float = 10.0


def _pulse(shape, ap_g, tp, t0=None):
    from rockcli.pulses import make_pulse

    return make_pulse(shape, ap_g * G, tp) if t0 is None else make_pulse(shape, ap_g * G, tp, t0)


def _bassae():
    from rockcli.models import column

    return column("bassae")


def _record(acc, dt, name):
    from rockcli.records import Record

    return Record(np.asarray(acc, dtype=float), float(dt), name)


def band_limited_record(duration=100.0, dt=0.001, pga_g=0.4, f_lo=0.3, f_hi=8.0, seed=12):
    """A synthetic band-limited accelerogram: white noise filtered to ``[f_lo, f_hi]`` Hz (ideal FFT
    band-pass), a 5 s rise and a decay over the last third, scaled to ``pga_g``."""
    rng = np.random.default_rng(seed)
    n = int(round(duration / dt)) + 1
    spec = np.fft.rfft(rng.standard_normal(n))
    f = np.fft.rfftfreq(n, dt)
    spec[(f < f_lo) | (f > f_hi)] = 0.0
    acc = np.fft.irfft(spec, n)
    t = np.arange(n) * dt
    env = np.clip(t / 5.0, 0.0, 1.0) * np.clip((duration - t) / (duration / 3.0), 0.0, 1.0)
    acc *= env
    acc *= pga_g * G / np.max(np.abs(acc))
    return _record(acc, dt, f"band-limited-{duration:g}s-dt{dt:g}")


def _spike_record(g_level=10.0, dt=0.01, duration=10.0, at=2.0):
    acc = np.zeros(int(round(duration / dt)) + 1)
    acc[int(round(at / dt))] = g_level * G
    return _record(acc, dt, f"spike-{g_level:g}g")


def _sampled(pulse, dt, t_end):
    t = np.arange(0.0, t_end + 0.5 * dt, dt)
    return np.asarray(pulse.acceleration(t), dtype=float)


def _ends_mid_rocking():
    """A sampled Ricker cut while the block is in the air (half way up its first excursion)."""
    from rockcli.models import Rigid
    from rockcli.solve import simulate

    b, dt = _bassae(), 0.01
    pulse = _pulse("ricker-sym", 0.5, 1.2)
    full = _record(_sampled(pulse, dt, pulse.support()[1]), dt, "ricker")
    h = simulate(b, Rigid(), full, history=True, rtol=1e-12).history
    th = np.abs(h.theta)
    k_peak = int(np.argmax(th))
    k_cut = int(np.nonzero(th[:k_peak] >= 0.5 * th[k_peak])[0][0])
    n = int(h.t[k_cut] / dt)
    return b, Rigid(), _record(full.acc[: n + 1], dt, "ricker-cut-mid-rocking")


def _passes_alpha_at_end():
    """A sampled overturning Ricker whose last sample falls exactly when |theta| first reaches alpha:
    ``dt`` is adjusted (fixed point ``dt = t_alpha(dt)/n``) so that the crossing is a sample time."""
    from rockcli.models import Rigid
    from rockcli.solve import simulate

    b = _bassae()
    pulse = _pulse("ricker-sym", 0.8, 1.2)
    dt, n = 0.01, None
    for _ in range(30):
        full = _record(_sampled(pulse, dt, pulse.support()[1]), dt, "ricker")
        tx = simulate(b, Rigid(), full, rtol=1e-12).t_exceed_alpha_s
        if n is None:
            n = int(round(tx / dt))
        new = tx / n
        if abs(new - dt) <= 1e-16:
            break
        dt = new
    rec = _record(full.acc[: n + 1], dt, "ricker-ends-at-alpha")
    return b, Rigid(), rec


def _weak_chatter():
    """Bassae under a long weak harmonic motion just above its uplift threshold: many small uplifts,
    trains of impacts and rests."""
    from rockcli.models import Rigid

    b, dt = _bassae(), 0.005
    t = np.arange(0.0, 30.0 + dt / 2, dt)
    env = np.clip(t / 3.0, 0, 1) * np.clip((30.0 - t) / 3.0, 0, 1)
    acc = 1.05 * G * math.tan(b.alpha) * env * np.sin(2 * math.pi * 2.0 * t)
    return b, Rigid(), _record(acc, dt, "weak-2Hz")


def _subnormal_uplift():
    """A random extreme scene (``--random 5000 --seed 7``, number 3669), its numbers kept exactly."""
    from rockcli.models import Block, LinearIsolation
    from rockcli.pulses import make_pulse

    return (Block(4.185866746376747, 0.023977874382879526, "subnormal-uplift"),
            LinearIsolation(0.533663188523473, 0.5, 0.0), make_pulse("ricker-sym", 0.9275447215073718, 0.25285436453418914))


def _iso(spec):
    return parse_foundation(spec)


def _alpha_block(deg, R=1.0):
    from rockcli.models import Block

    return Block.from_degrees(R, deg, f"R{R:g}m-alpha{deg:g}deg")


def _ap_g_for(block, factor):
    return factor * math.tan(block.alpha)


STABILITY_SCENES = (
    StabilityScene("alpha-1deg", "R = 1 m, alpha = 1 deg, rigid, symmetric Ricker 3 g tan(alpha), 0.5 s",
                   lambda: (_alpha_block(1.0), _iso("none"), _pulse("ricker-sym", _ap_g_for(_alpha_block(1.0), 3), 0.5))),
    StabilityScene("alpha-1deg-linear", "R = 1 m, alpha = 1 deg, linear Tb = 2 s, symmetric Ricker 3 g tan(alpha), 2 s",
                   lambda: (_alpha_block(1.0), _iso("linear:Tb=2,xi=0.1"),
                            _pulse("ricker-sym", _ap_g_for(_alpha_block(1.0), 3), 2.0))),
    StabilityScene("alpha-45deg", "R = 1 m, alpha = 45 deg, rigid, symmetric Ricker 3 g, 0.5 s",
                   lambda: (_alpha_block(45.0), _iso("none"), _pulse("ricker-sym", 3.0, 0.5))),
    StabilityScene("ap5g-Tp0.05", "Bassae, rigid, symmetric Ricker 5 g, 0.05 s",
                   lambda: (_bassae(), _iso("none"), _pulse("ricker-sym", 5.0, 0.05))),
    StabilityScene("ap5g-Tp0.05-linear", "Bassae, linear Tb = 2 s, symmetric Ricker 5 g, 0.05 s",
                   lambda: (_bassae(), _iso("linear:Tb=2,xi=0.1"), _pulse("ricker-sym", 5.0, 0.05))),
    StabilityScene("ap5g-Tp10", "Bassae, rigid, symmetric Ricker 5 g, 10 s", lambda: (_bassae(), _iso("none"),
                   _pulse("ricker-sym", 5.0, 10.0))),
    StabilityScene("ap5g-Tp10-linear", "Bassae, linear Tb = 2 s, symmetric Ricker 5 g, 10 s",
                   lambda: (_bassae(), _iso("linear:Tb=2,xi=0.1"), _pulse("ricker-sym", 5.0, 10.0))),
    StabilityScene("record-100s", "Bassae, rigid, 100 s band-limited record (0.3-8 Hz, 0.4 g) at dt = 0.001 s",
                   lambda: (_bassae(), _iso("none"), band_limited_record())),
    StabilityScene("record-100s-linear", "Bassae, linear Tb = 2.5 s, xi = 0.1, the same 100 s record at 0.5 g",
                   lambda: (_bassae(), _iso("linear:Tb=2.5,xi=0.1"), band_limited_record(pga_g=0.5))),
    StabilityScene("chatter-pulse", "Bassae, rigid, symmetric Ricker 1.05 g tan(alpha), 0.5 s (chatters to rest)",
                   lambda: (_bassae(), _iso("none"), _pulse("ricker-sym", _ap_g_for(_bassae(), 1.05), 0.5))),
    StabilityScene("chatter-weak-record", "Bassae, rigid, 30 s of 2 Hz motion at 1.05 g tan(alpha)", _weak_chatter),
    StabilityScene("gamma-0", "Bassae, linear Tb = 2 s, xi = 0.1, gamma = 0, symmetric Ricker 0.3 g, 1.2 s",
                   lambda: (_bassae(), _iso("linear:Tb=2,xi=0.1,gamma=0"), _pulse("ricker-sym", 0.3, 1.2))),
    StabilityScene("gamma-0.9", "Bassae, linear Tb = 2 s, xi = 0.1, gamma = 0.9, symmetric Ricker 0.3 g, 1.2 s",
                   lambda: (_bassae(), _iso("linear:Tb=2,xi=0.1,gamma=0.9"), _pulse("ricker-sym", 0.3, 1.2))),
    StabilityScene("xi-0", "Bassae, linear Tb = 2.5 s, xi = 0 (undamped), symmetric Ricker 0.3 g, 1.2 s: the free "
                   "base keeps lifting the block", lambda: (_bassae(), _iso("linear:Tb=2.5,xi=0"),
                                                            _pulse("ricker-sym", 0.3, 1.2)), unproven_ok=True),
    StabilityScene("xi-0.5", "Bassae, linear Tb = 2.5 s, xi = 0.5, symmetric Ricker 0.4 g, 1.2 s",
                   lambda: (_bassae(), _iso("linear:Tb=2.5,xi=0.5"), _pulse("ricker-sym", 0.4, 1.2))),
    StabilityScene("spike-10g", "Bassae, rigid, 10 s record with a single 10 g sample (dt = 0.01 s)",
                   lambda: (_bassae(), _iso("none"), _spike_record())),
    StabilityScene("spike-10g-linear", "Bassae, linear Tb = 2.5 s, the same 10 g spike",
                   lambda: (_bassae(), _iso("linear:Tb=2.5,xi=0.1"), _spike_record())),
    StabilityScene("ends-mid-rocking", "Bassae, rigid, sampled Ricker 0.5 g, 1.2 s cut while the block is in the air",
                   _ends_mid_rocking),
    StabilityScene("alpha-at-end", "Bassae, rigid, sampled Ricker 0.8 g, 1.2 s ending exactly as |theta| reaches "
                   "alpha", _passes_alpha_at_end, expect="overturned"),
    StabilityScene("alpha-45deg-gamma-0.9", "R = 2 m, alpha = 45 deg, linear Tb = 0.5 s, xi = 0.1, gamma = 0.9 (a squat "
                   "block on a light base: eta clamped to 0), antisymmetric Ricker 5 g, 0.25 s",
                   lambda: (_alpha_block(45.0, 2.0), _iso("linear:Tb=0.5,xi=0.1,gamma=0.9"),
                            _pulse("ricker-anti", 5.0, 0.25))),
    StabilityScene("slender-1.4deg-linear", "R = 17 m, alpha = 1.4 deg, linear Tb = 0.8 s, xi = 0.1, symmetric Ricker "
                   "0.7 g, 0.3 s (eta = 0.9991: the free rocking outlasts the horizon)",
                   lambda: (_alpha_block(1.4, 17.0), _iso("linear:Tb=0.8,xi=0.1"), _pulse("ricker-sym", 0.7, 0.3))),
    StabilityScene("subnormal-uplift", "R = 4.19 m, alpha = 1.37 deg, linear Tb = 0.534 s, xi = 0.5, gamma = 0, "
                   "symmetric Ricker 0.0946 g, 0.253 s (micro-uplifts: theta falls to subnormal numbers; found by "
                   "--random 5000 --seed 7)", _subnormal_uplift),
    StabilityScene("bouc-wen-uy-0.01mm", "Bassae, SCSS Tb = 3 s, mu = 0.05, u_y = 0.01 mm, symmetric Ricker 0.5 g, "
                   "1.2 s", lambda: (_bassae(), _iso("scss:Tb=3,mu=0.05,uy=0.00001"), _pulse("ricker-sym", 0.5, 1.2))),
    StabilityScene("slender-1.5deg-scss", "R = 2 m, alpha = 1.5 deg, SCSS Tb = 3 s, mu = 0.06, symmetric Ricker "
                   "0.157 g (6 g tan alpha), 0.5 s: rocks on a base at rest off centre",
                   lambda: (_alpha_block(1.5, 2.0), _iso("scss:Tb=3,mu=0.06"), _pulse("ricker-sym", 0.157, 0.5)),
                   unproven_ok=True, unproven_why="a very slender block rocking on a sliding base that rests off "
                                                  "centre (README, Sliding isolation: the limit)"),
)


def random_scenes(n: int, seed: int = 1) -> list:
    """``n`` random extreme pulse scenes (fixed ``seed``): alpha 1-45 deg, R 0.2-20 m (log-uniform),
    rigid (40 %) or linear bearings (T_b 0.3-6 s, xi in {0, 0.02, 0.1, 0.5, 1}, gamma in {0, 0.01, 0.3,
    0.9, 0.99}), any pulse shape, T_p 0.05-10 s, a_p 0.5-50 g tan(alpha) capped at 5 g. An undamped
    base (xi = 0) may end NOT PROVEN (stated)."""
    from rockcli.models import Block, LinearIsolation, Rigid

    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        alpha = math.radians(float(np.exp(rng.uniform(math.log(1), math.log(45)))))
        R = float(np.exp(rng.uniform(math.log(0.2), math.log(20))))
        if rng.random() < 0.4:
            f = Rigid()
        else:
            f = LinearIsolation(float(np.exp(rng.uniform(math.log(0.3), math.log(6)))),
                                float(rng.choice([0, 0.02, 0.1, 0.5, 1.0])), float(rng.choice([0, 0.01, 0.3, 0.9, 0.99])))
        shape = str(rng.choice(["ricker-sym", "ricker-anti", "sine", "cosine"]))
        tp = float(np.exp(rng.uniform(math.log(0.05), math.log(10))))
        ap_g = min(float(np.exp(rng.uniform(math.log(0.5), math.log(50)))) * math.tan(alpha), 5.0)
        blk = Block(R, alpha, f"random-{i}")
        title = (f"R = {R:.3g} m, alpha = {math.degrees(alpha):.3g} deg, {getattr(f, 'label', 'none')}, {shape} "
                 f"{ap_g:.3g} g, {tp:.3g} s")
        out.append(StabilityScene(f"random-{seed}-{i}", title,
                                  (lambda b=blk, f=f, e=(shape, ap_g, tp): (b, f, _pulse(*e))),
                                  unproven_ok=bool(getattr(f, "xi", 1.0) == 0.0)))
    return out
