"""Random accelerograms for the tests and benchmarks that need records of their own (no file): :func:`random_record`
(short, a few sines under a sin^2 envelope) and :func:`synthetic_record` (band-limited, rising and decaying)."""

from __future__ import annotations

import math

import numpy as np

from rockcli.io.units import G
from rockcli.records import Record


def random_record(rng, n: int | None = None, *, dt: float = 0.01, n_range=(150, 400), pga_g=(0.15, 0.8),
                  n_sines: int = 5, f_range=(0.4, 5.0)) -> Record:
    """``n`` samples (else drawn from ``n_range``) at ``dt``: ``n_sines`` sines of frequencies drawn from
    ``f_range`` [Hz], normal amplitudes and uniform phases, under a ``sin^2`` envelope (zero at both ends), scaled
    to a PGA of ``pga_g`` [g] (a number, or a range drawn from last)."""
    n = n or int(rng.integers(*n_range))
    t = np.arange(n) * dt
    acc = np.zeros(n)
    for f in rng.uniform(*f_range, n_sines):
        acc += rng.normal() * np.sin(2 * math.pi * f * t + rng.uniform(0, 2 * math.pi))
    acc *= np.sin(math.pi * t / t[-1]) ** 2
    pga = float(pga_g) if np.isscalar(pga_g) else float(rng.uniform(*pga_g))
    return Record(acc * (pga * G / np.max(np.abs(acc))), dt, "synthetic")


def synthetic_record(seed=0, duration=12.0, dt=0.01, pga=0.45 * G):
    """A band-limited random accelerogram with an envelope (no file needed)."""
    rng = np.random.default_rng(seed)
    t = np.arange(0.0, duration, dt)
    acc = np.zeros_like(t)
    for f in rng.uniform(0.3, 4.0, 12):
        acc += rng.normal() * np.sin(2 * np.pi * f * t + rng.uniform(0, 2 * np.pi))
    acc *= (t / 2.0) ** 2 * np.exp(-t / 2.0 + 2.0) / 4.0
    acc *= pga / np.max(np.abs(acc))
    return Record(acc, dt, f"synthetic-{seed}")


def random_drum_scene(seed: int, n: int, linear: float = 0.0, scale=(1.0, 3.0), cap: float = 1.0):
    """A random column of ``n`` drums and its shaking (benchmarks/bench_drums_reference.py and
    tests/test_drums_reference.py): ``(column, excitation, mu per contact, foundation)``. Heights 0.3-1.5 m, widths 0.3-1.0 m (a third tapering
    upwards, the others free, so that some drums overhang), friction 0.3-1.0 per contact, a pulse or a short random
    record of 1-3 times (``scale``) the column's first static threshold (at most ``cap`` [g]); a fraction ``linear`` on
    linear bearings (the defaults draw the same scenes as ever)."""
    from rockcli.io.units import G
    from rockcli.models import LinearIsolation
    from rockcli.models.drums import DrumColumn
    from rockcli.pulses import OneSine, RickerAntisymmetric, RickerSymmetric

    rng = np.random.default_rng([seed, n])
    heights = rng.uniform(0.3, 1.5, n)
    if rng.random() < 1 / 3:  # a tapering shaft
        widths = np.sort(rng.uniform(0.3, 1.0, n))[::-1]
    else:
        widths = rng.uniform(0.3, 1.0, n)
    col = DrumColumn(tuple((float(h), float(w)) for h, w in zip(heights, widths)))
    mu = tuple(float(x) for x in rng.uniform(0.3, 1.0, n))
    # the shaking from just above the column's first static threshold (the joint that opens or slides first) to
    # three times it, at most 1 g: every scene moves
    first = min(min(m, t) for m, t in zip(mu, col.static_thresholds()))
    amp = min(cap, first * float(rng.uniform(*scale)))
    if rng.random() < 0.5:
        exc = random_record(rng, pga_g=amp, n_range=(150, 300))
    else:
        kinds = (RickerSymmetric, OneSine, RickerAntisymmetric)
        exc = kinds[int(rng.integers(0, 3))](amp * G, rng.uniform(0.25, 1.5))
    iso = None
    if rng.random() < linear:
        iso = LinearIsolation(T_b=float(rng.uniform(1.5, 3.5)), xi=float(rng.uniform(0.05, 0.2)),
                              gamma=float(rng.uniform(0.1, 0.6)))
    return col, exc, mu, iso
