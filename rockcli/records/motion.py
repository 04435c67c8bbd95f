"""Velocity and displacement of a record by integration, and its peaks."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.records.record import Record

#: Baseline treatments of :func:`integrate`.
BASELINES = ("none", "linear")


def cumtrapz(y: np.ndarray, dt: float) -> np.ndarray:
    """Cumulative trapezoidal integral of ``y`` sampled at ``dt``, starting from 0 (same length as ``y``)."""
    y = np.asarray(y, dtype=np.float64)
    out = np.zeros_like(y)
    if y.size > 1:
        np.cumsum(0.5 * (y[1:] + y[:-1]) * dt, out=out[1:])
    return out


def integrate(record: Record, baseline: str = "none") -> tuple[np.ndarray, np.ndarray]:
    """Ground velocity [m/s] and displacement [m] of a record.

    Parameters
    ----------
    record : Record
        Acceleration [m/s^2].
    baseline : {"none", "linear"}
        ``"none"``: trapezoidal integration of the record as given, from rest (v(0) = 0,
        u(0) = 0). ``"linear"``: the same velocity minus the straight line fitted to it by least
        squares (removes the drift caused by a constant offset in the acceleration), then
        integrated again.

    Returns
    -------
    vel : ndarray
        Velocity [m/s].
    disp : ndarray
        Displacement [m].
    """
    if baseline not in BASELINES:
        raise RockcliInputError(f"baseline {baseline!r} is not one of {', '.join(BASELINES)}")
    vel = cumtrapz(record.acc, record.dt)
    if baseline == "linear" and vel.size > 1:
        t = record.dt * np.arange(vel.size)
        slope, intercept = np.polyfit(t, vel, 1)
        vel = vel - (slope * t + intercept)
    return vel, cumtrapz(vel, record.dt)


@dataclass(frozen=True)
class Peaks:
    """Peak values of a record.

    Attributes
    ----------
    pga_g : float
        Peak ground acceleration [g].
    pgv_mps : float
        Peak ground velocity [m/s], trapezoidal integration of the record as given.
    pgv_linear_mps : float
        Peak ground velocity [m/s] after removing a linear baseline fitted to the velocity.
    pgd_m : float
        Peak ground displacement [m], from the linear-baseline velocity.
    """

    pga_g: float
    pgv_mps: float
    pgv_linear_mps: float
    pgd_m: float


def calc_peaks(record: Record) -> Peaks:
    """PGA [g], PGV [m/s] (as given, and with linear baseline) and PGD [m] of a record."""
    vel, _ = integrate(record, "none")
    vel_lin, disp_lin = integrate(record, "linear")
    return Peaks(pga_g=record.pga_g, pgv_mps=float(np.abs(vel).max()),
                 pgv_linear_mps=float(np.abs(vel_lin).max()), pgd_m=float(np.abs(disp_lin).max()))
