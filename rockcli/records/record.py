"""The :class:`Record`: a uniformly sampled ground acceleration in SI units."""

from __future__ import annotations

from dataclasses import dataclass, field, replace
from typing import Any, Mapping

import numpy as np

from rockcli.io.units import G


@dataclass(frozen=True, eq=False)
class Record:
    """A ground-acceleration time series sampled at a constant time step.

    Parameters
    ----------
    acc : ndarray
        Acceleration samples [m/s^2], float64, finite.
    dt : float
        Time step [s], > 0.
    name : str
        Short label (file stem or catalogue id).
    t_start : float
        Time of the first sample [s] as stated by the source (0 when unstated).
    meta : mapping
        What the source says: ``units`` (as stated in the file), ``factor`` (multiplier that was
        applied to reach m/s^2), ``format``, ``path``, ``event``, ``station``, ``component``, ...

    Notes
    -----
    The solver treats the record as piecewise linear between samples, starting from rest at the
    first sample (time 0 of the simulation) and zero after the last one.
    """

    acc: np.ndarray
    dt: float
    name: str = "record"
    t_start: float = 0.0
    meta: Mapping[str, Any] = field(default_factory=dict)

    def __post_init__(self):
        acc = np.ascontiguousarray(self.acc, dtype=np.float64)
        object.__setattr__(self, "acc", acc)
        object.__setattr__(self, "dt", float(self.dt))

    @property
    def npts(self) -> int:
        """Number of samples."""
        return int(self.acc.size)

    @property
    def duration(self) -> float:
        """Time from the first to the last sample [s]."""
        return (self.npts - 1) * self.dt if self.npts else 0.0

    @property
    def times(self) -> np.ndarray:
        """Sample times [s], starting at ``t_start``."""
        return self.t_start + self.dt * np.arange(self.npts)

    @property
    def pga(self) -> float:
        """Peak absolute acceleration [m/s^2]."""
        return float(np.max(np.abs(self.acc))) if self.npts else 0.0

    @property
    def pga_g(self) -> float:
        """Peak absolute acceleration [g]."""
        return self.pga / G

    def scaled(self, k: float) -> "Record":
        """The record multiplied by ``k`` (a negative ``k`` also flips it).

        Raises
        ------
        RockcliInputError
            ``k`` is not a finite non-zero number, or takes the record's peak past the 100 g that rockcli runs
            (:func:`rockcli.io.inputs.check_scale`, the check of ``--scale``).
        """
        from rockcli.io.inputs import check_scale

        k = check_scale(k, self.pga_g, "Record.scaled: the factor", f"the record {self.name}")
        return replace(self, acc=self.acc * k, meta={**self.meta, "scale": self.meta.get("scale", 1.0) * k})

    def flipped(self) -> "Record":
        """The record with its sign reversed (the same motion seen from the other side)."""
        return self.scaled(-1.0)
