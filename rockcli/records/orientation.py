"""Ground motion along a rocking plane: two horizontal components projected onto an azimuth.

A planar rocking analysis needs the ground acceleration along the normal to the body's rocking axis.
Its azimuth ``theta`` (degrees clockwise from north) and two perpendicular horizontal components at
azimuths ``phi_1``, ``phi_2`` give

    a_theta(t) = a_1(t) cos(theta - phi_1) + a_2(t) cos(theta - phi_2)

(:func:`project`). The cosines of multiples of 90 deg are exact (0, +-1), so the projection onto a
component's own azimuth is that component, sample for sample. ``theta`` and ``theta + 180`` are the
same motion with its sign reversed, which a symmetric block answers with the mirrored response:
:func:`sweep_azimuths` covers 0 <= theta < 180.

A pair is checked (:func:`check_pair`): both horizontal with an orientation stated (by the file, the
catalogue, or given as ``FILE@DEG``), perpendicular, with the same time step and start, and from the
same station when both files name it. Components of different lengths are padded with zeros (the
ground is at rest after a record ends, as the solver takes it).
"""

from __future__ import annotations

import math
import re
from dataclasses import replace
from pathlib import Path

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number
from rockcli.records.record import Record

#: Default step of ``--azimuth worst`` [deg].
AZIMUTH_STEP = 5.0
#: Accepted steps of ``--azimuth worst`` [deg] (:func:`check_azimuth_step`, for the CLI and :func:`sweep_azimuths`).
#: The floor: the projection ``a_1 cos(theta - phi_1) + a_2 cos(theta - phi_2)`` changes by at most ``|a| dtheta``
#: between orientations ``dtheta`` apart, 0.17 % of the horizontal motion at 0.1 deg (finer than the margin's 1 %
#: bisection), and 0.1 deg already runs 1,800 orientations of every pair (``1e-9`` would build 1.8e11); the ceiling:
#: 90 deg still runs two orientations, 0 and 90 deg.
AZIMUTH_STEP_RANGE_DEG = (0.1, 90.0)
#: Largest departure from perpendicular of a pair [deg] (the projection assumes perpendicular axes).
PERPENDICULAR_TOL_DEG = 1e-6


def cos_deg(angle: float) -> float:
    """cos of an angle in degrees, exact (0, 1, -1) at multiples of 90 deg."""
    r = float(angle) % 360.0
    exact = {0.0: 1.0, 90.0: 0.0, 180.0: -1.0, 270.0: 0.0}
    return exact[r] if r in exact else math.cos(math.radians(r))


def split_source(text: str):
    """``(source, azimuth)`` from ``FILE@DEG`` (an orientation given for a file that states none); a source
    that exists as written is never split."""
    s = str(text)
    m = re.fullmatch(r"(.+)@\s*([-+]?\d+(?:\.\d+)?)\s*", s)
    from rockcli.records.reader import path_exists

    if m is None or path_exists(s):
        return s, None
    return m.group(1), float(m.group(2))


def pair_sources(text, option: str = "--records"):
    """``(A, B)`` of a pair of horizontal components written ``A+B`` (each a file, ``FILE@DEG`` or a catalogue id);
    None for a source with no ``+`` or one that exists as written (a file named ``a+b.txt``). A pair that lacks a
    file (``A+``, ``+B``) or names more than two is refused in one sentence naming ``option``."""

    s = str(text)
    if "+" not in s or _is_there(s):
        return None
    first, _, second = s.partition("+")
    if not first.strip() or not second.strip():
        which = "first" if not first.strip() else "second"
        raise RockcliInputError(f"{option} {s}: a pair of horizontal components is written A+B, two files or "
                                f"catalogue ids; this pair is missing its {which} file")
    if "+" in second:
        raise RockcliInputError(f"{option} {s}: a pair of horizontal components is written A+B, two files or "
                                f"catalogue ids; this one names {s.count('+') + 1} files")
    return first, second


def _is_there(text: str) -> bool:
    """A file or folder of that very name is there (one that cannot be looked at, in a folder without permission,
    is not taken for one: its ``+`` is then read as a pair's, and the reader names the file it cannot read)."""
    from pathlib import Path

    try:
        return Path(text).exists()
    except (OSError, ValueError):
        return False


def refuse_pair_without_azimuth(text, option: str = "--records") -> None:
    """A pair ``A+B`` given with no azimuth: one sentence that says it needs one (a planar run takes one
    direction of the ground's motion); nothing for any other source."""
    if pair_sources(text, option) is not None:
        raise RockcliInputError(f"{option} {text} is a pair of horizontal components: a pair needs --azimuth DEG "
                                f"(the direction the body rocks in, clockwise from north) or --azimuth worst (every "
                                f"direction)")


def oriented(rec: Record, given, label: str) -> Record:
    """``rec`` with the orientation ``given`` [deg] (from ``FILE@DEG``) when the file states none; a given
    orientation that contradicts the stated one is refused."""
    if given is None:
        return rec
    stated = rec.meta.get("azimuth_deg")
    if rec.meta.get("vertical"):
        raise RockcliInputError(f"{label}: the component is vertical; an azimuth @{format_number(given)} cannot be given to it")
    if stated is not None and abs((stated - given + 180.0) % 360.0 - 180.0) > 1e-9:
        raise RockcliInputError(f"{label}: the file states the orientation {format_number(stated)} deg "
                                f"({rec.meta.get('orientation_source')}) but @{format_number(given)} was given")
    return replace(rec, meta={**rec.meta, "azimuth_deg": given % 360.0, "vertical": False,
                              "orientation_source": f"given as @{format_number(given)}"})


def check_pair(first: Record, second: Record) -> tuple[Record, Record]:
    """The pair, checked: horizontal, oriented, perpendicular, one time base, one station."""
    names = [str(r.meta.get("path") or r.name) for r in (first, second)]
    for rec, name in zip((first, second), names):
        if rec.meta.get("vertical"):
            raise RockcliInputError(f"{name}: the component is vertical; an azimuth needs two horizontal components")
        if rec.meta.get("azimuth_deg") is None:
            raise RockcliInputError(f"{name}: the orientation of the component is not stated; give it as "
                                    f"{Path(name).name}@DEG (degrees clockwise from north)")
    a1, a2 = first.meta["azimuth_deg"], second.meta["azimuth_deg"]
    off = abs((a2 - a1) % 180.0 - 90.0)
    if off > PERPENDICULAR_TOL_DEG:
        raise RockcliInputError(f"{names[0]} and {names[1]}: the components at {a1:g} and {a2:g} deg are not "
                                f"perpendicular; an azimuth needs two perpendicular horizontal components")
    if not math.isclose(first.dt, second.dt, rel_tol=1e-9):
        raise RockcliInputError(f"{names[0]} and {names[1]}: the time steps differ ({first.dt:g} s and "
                                f"{second.dt:g} s); the two components must share one time base")
    if abs(first.t_start - second.t_start) > 0.5 * first.dt:
        raise RockcliInputError(f"{names[0]} and {names[1]}: the records start at different times "
                                f"({first.t_start:g} s and {second.t_start:g} s); they must share one time base")
    s1, s2 = (str(r.meta.get("station") or "").strip() for r in (first, second))
    if s1 and s2 and s1.lower() != s2.lower():
        raise RockcliInputError(f"{names[0]} and {names[1]}: the files are from different stations "
                                f"({s1!r} and {s2!r}); a pair must be two components of one record")
    return first, second


def project(first: Record, second: Record, azimuth_deg: float) -> Record:
    """The ground acceleration along ``azimuth_deg`` (clockwise from north) from a checked pair.

    Returns a :class:`Record` named ``<first>@<azimuth>``; onto a component's own azimuth it is that
    component's samples exactly (same length, same values).
    """
    theta = float(azimuth_deg)
    if not math.isfinite(theta):
        raise RockcliInputError(f"--azimuth {azimuth_deg!r} must be a finite angle in degrees")
    c1 = cos_deg(theta - first.meta["azimuth_deg"])
    c2 = cos_deg(theta - second.meta["azimuth_deg"])
    if c2 == 0.0:
        acc = first.acc * c1
    elif c1 == 0.0:
        acc = second.acc * c2
    else:
        n = max(first.npts, second.npts)
        acc = np.zeros(n)
        acc[:first.npts] += c1 * first.acc
        acc[:second.npts] += c2 * second.acc
    meta = {**first.meta, "component": f"{theta % 360.0:g} deg", "azimuth_deg": theta % 360.0, "vertical": False,
            "orientation_source": "projection of two components",
            "projection": {"azimuth_deg": theta, "components": [
                {"path": str(r.meta.get("path") or r.name), "azimuth_deg": r.meta["azimuth_deg"], "cos": c}
                for r, c in ((first, c1), (second, c2))]}}
    base = first.name if first.name == second.name else f"{first.name}+{second.name}"
    return Record(acc=acc, dt=first.dt, name=f"{base}@{theta % 360.0:g}", t_start=first.t_start, meta=meta)


def check_azimuth_step(step, what: str = "--azimuth-step") -> float:
    """``step`` [deg] of ``--azimuth worst`` when it lies in :data:`AZIMUTH_STEP_RANGE_DEG`, else one sentence
    naming ``what``, the limits and why."""
    from rockcli.io.inputs import parse_number

    lo, hi = AZIMUTH_STEP_RANGE_DEG
    if isinstance(step, (int, float)) and not isinstance(step, bool) and math.isfinite(step) and lo <= step <= hi:
        return float(step)
    step = parse_number(step, what)  # not a number: its own sentence
    raise RockcliInputError(f"{what} {format_number(step)} must lie between {format_number(lo)} deg "
                            f"({round(180 / lo):,} orientations of each pair, less than 0.2 % of the motion "
                            f"apart) and {format_number(hi)} deg (two orientations)")


def sweep_azimuths(step: float = AZIMUTH_STEP) -> np.ndarray:
    """Azimuths 0 <= theta < 180 deg every ``step`` degrees (``--azimuth worst``); ``step`` within
    :data:`AZIMUTH_STEP_RANGE_DEG` (:func:`check_azimuth_step`)."""
    step = check_azimuth_step(step, "sweep_azimuths: step")
    n = int(math.ceil(180.0 / step - 1e-9))
    return np.array([k * step for k in range(n) if k * step < 180.0])


def parse_azimuth(text) -> float | str | None:
    """``--azimuth``: None, ``"worst"`` or an angle in degrees."""
    if text is None:
        return None
    s = str(text).strip()
    if s.lower() == "worst":
        return "worst"
    from rockcli.io.inputs import parse_number

    return parse_number(s, "--azimuth")


def read_pair(first, second=None, **kwargs) -> tuple[Record, Record]:
    """Two horizontal components, checked: ``first`` and ``second`` sources (each ``FILE`` or ``FILE@DEG``), or
    the two horizontal components of the one multi-component file ``first``. ``kwargs`` go to the reader."""
    from rockcli.records.components import horizontal_pair
    from rockcli.records.reader import read_components, read_record

    component, column = kwargs.pop("component", None), kwargs.pop("column", None)
    if component is not None or column is not None:
        raise RockcliInputError("an azimuth projects two horizontal components onto the rocking plane: "
                                "--component/--record-column do not apply with --azimuth")
    src1, az1 = split_source(first)
    if second is None:
        comps = read_components(src1, **kwargs)
        if len(comps) == 1:
            raise RockcliInputError(f"{src1}: --azimuth needs two horizontal components: the file holds one; give "
                                    f"the other with --record-2 (or FILE+FILE in a suite)")
        return check_pair(*horizontal_pair(comps, str(src1)))
    src2, az2 = split_source(second)
    rec1 = oriented(read_record(src1, **kwargs), az1, str(src1))
    rec2 = oriented(read_record(src2, **kwargs), az2, str(src2))
    return check_pair(rec1, rec2)
