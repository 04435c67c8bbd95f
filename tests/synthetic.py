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
