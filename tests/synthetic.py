"""Short random accelerograms for the tests and benchmarks that need many records of their own."""

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
