"""The Python arguments of the spectra, checked before any run: a wrong type is one sentence.

:func:`rockcli.spectra.overturning_map` and its siblings take slenderness values, pulses, isolations and
grids. Pulses and isolations may be given as spec strings (``"ricker-sym"``, ``"linear:TbTp=2"``), as on
the command line; grids as :class:`~rockcli.spectra.grids.Grid` or ``"start:stop:count"``. Anything else
(a plain list where a grid is expected, a number where a list is) raises
:class:`~rockcli.errors.RockcliInputError` naming the argument, what it must be and what was given.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.io.inputs import as_list, check_type, type_words
from rockcli.spectra.grids import Grid, parse_grid
from rockcli.spectra.scenes import Isolation, PulseChoice, parse_isolation, parse_pulse_choice


def as_alphas(values, what: str = "alphas_deg") -> list:
    """Slenderness values [deg]: a list of numbers (one number is a list of one)."""
    out = []
    for a in as_list(values, what, "a list of slenderness values in degrees", one=(int, float, np.floating)):
        check_type(a, (int, float, np.integer, np.floating), f"{what}: each value", "a number of degrees")
        if not (math.isfinite(float(a)) and 0.0 < float(a) < 90.0):
            from rockcli.io.inputs import format_number

            raise RockcliInputError(f"{what}: alpha = {format_number(a)} deg must lie strictly between 0 and 90 deg")
        out.append(float(a))
    return out


def as_pulse_choice(pulse, what: str = "pulse") -> PulseChoice:
    """A :class:`PulseChoice`, or a spec string such as ``"ricker-sym"`` or ``"sine:Tp=0.6"``."""
    if isinstance(pulse, str):
        return parse_pulse_choice(pulse)
    return check_type(pulse, PulseChoice, what, "a pulse shape such as 'ricker-sym' (or a PulseChoice)")


def as_isolation(isolation, what: str = "isolation") -> Isolation:
    """An :class:`Isolation`, or a spec string such as ``"none"`` or ``"linear:TbTp=2,xi=0.05"``."""
    if isinstance(isolation, str):
        return parse_isolation(isolation)
    return check_type(isolation, Isolation, what, "an isolation spec such as 'none' or 'linear:TbTp=2' (or an "
                                                  "Isolation)")


def as_pulses(pulses, what: str = "pulses") -> list:
    return [as_pulse_choice(p, f"{what}: each pulse")
            for p in as_list(pulses, what, "a list of pulses ('ricker-sym', ...)", one=(str, PulseChoice))]


def as_isolations(isolations, what: str = "isolations") -> list:
    return [as_isolation(i, f"{what}: each isolation")
            for i in as_list(isolations, what, "a list of isolations ('none', 'linear:TbTp=2', ...)",
                             one=(str, Isolation))]


def as_grid(grid, what: str) -> Grid:
    """A :class:`Grid`, or ``"start:stop:count"`` (:func:`parse_grid`); a plain list is refused, naming both."""
    if isinstance(grid, str):
        return parse_grid(grid, what)
    if not isinstance(grid, Grid):
        raise RockcliInputError(f"{what} must be a grid, parse_grid('start:stop:count') or the text "
                                f"'start:stop:count' (e.g. '2:10:5'), got {type_words(grid)}")
    return grid


def as_values(values, what: str, *, positive: bool = False) -> np.ndarray:
    """A list of finite numbers (omega_p/p values, sizes; ``positive``: each > 0) as a float array."""
    items = as_list(values, what, "a list of numbers", one=(int, float, np.floating))
    for v in items:
        check_type(v, (int, float, np.integer, np.floating), f"{what}: each value", "a number")
    out = np.asarray(items, dtype=float).ravel()
    if not np.all(np.isfinite(out)) or (positive and not np.all(out > 0)):
        raise RockcliInputError(f"{what} must be finite{' positive' if positive else ''} numbers")
    return out


def as_plinths(plinths, what: str = "plinths") -> list:
    """What the body stands on in a spectrum: a list of None (the body alone) and/or
    :class:`~rockcli.spectra.plinth.PlinthRatio` plinths or their specs (``"plinth:height_ratio=0.5,width_ratio=1.5"``,
    :func:`~rockcli.spectra.plinth.parse_plinth_ratio`); one plinth or one spec is a list of itself, None the body
    alone. An empty list is refused, and so is a plinth in metres (a :class:`rockcli.models.Plinth`): a spectrum
    holds for a body of any size."""
    from rockcli.models import Plinth
    from rockcli.spectra.plinth import PlinthRatio, parse_plinth_ratio

    expected = ("None (the body alone) or a plinth in proportion to the body, a PlinthRatio or its spec such as "
                "'plinth:height_ratio=0.5,width_ratio=1.5'")
    out = []
    given = [None] if plinths is None else plinths
    for p in as_list(given, what, f"a list of plinths, each {expected}", one=(str, PlinthRatio, Plinth)):
        if isinstance(p, str):
            p = parse_plinth_ratio(p, f"{what}:")
        elif isinstance(p, Plinth):
            raise RockcliInputError(f"{what}: a spectrum is dimensionless (it holds for a body of any size), so give "
                                    f"the plinth in proportion to the body, e.g. 'plinth:height_ratio=0.5,"
                                    f"width_ratio=1.5', not a Plinth in metres, got {type_words(p)}")
        elif p is not None:
            check_type(p, PlinthRatio, f"{what}: each plinth", expected)
        out.append(p)
    if not out:
        raise RockcliInputError(f"{what} is empty: give None for the body alone and/or plinths in proportion to it")
    return out
