"""The excitation as the kernel reads it: a record's samples or a pulse's parameters, validated,
with the table of the ground impulse still to come (the bound behind the early stops).
"""

from __future__ import annotations

import math
import threading
import weakref

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.io.inputs import format_number
from rockcli.solve.options import _kernel


#: Latest start of a pulse, in periods: float64 time then resolves the pulse to 2e-10 of a period.
PULSE_START_MAX_PERIODS = 1e6
#: points of the unit-pulse tables of the remaining ground impulse (kernels._impulse_left)
N_IMPULSE_TABLE = 257

_PULSE_CODES = {"ricker-sym": 1, "ricker-anti": 2, "sine": 3, "cosine": 4}


def record_impulse_table(acc: np.ndarray, dt: float) -> np.ndarray:
    """Suffix integrals ``int_{t_j}^{t_end} |ag| dt`` [m/s] of a piecewise-linear record, one per sample.

    Exact per interval (a linear piece that changes sign integrates to ``dt (a0^2 + a1^2) /
    (2 (|a0| + |a1|))``), summed from the end and enlarged by 1e-9 relative for rounding: an upper
    bound, as the kernel's early stop (P4) needs.
    """
    a0, a1 = np.abs(acc[:-1]), np.abs(acc[1:])
    same = acc[:-1] * acc[1:] >= 0.0
    tot = a0 + a1
    piece = np.where(same, 0.5 * dt * tot, 0.5 * dt * (a0 * a0 + a1 * a1) / np.where(tot > 0, tot, 1.0))
    out = np.zeros(acc.size)
    out[:-1] = np.cumsum(piece[::-1])[::-1]
    return out * (1.0 + 1e-9)


_PULSE_ZEROS = {  # zeros of the unit pulse's acceleration, tau = t - t0 in units of T_p
    "ricker-sym": (-1.0 / (math.pi * math.sqrt(2.0)), 1.0 / (math.pi * math.sqrt(2.0))),
    "ricker-anti": (-1.5 / math.pi, 0.0, 1.5 / math.pi),
    "sine": (0.0, 0.5, 1.0),
    "cosine": (0.25, 0.75),
}
_UNIT_TABLES: dict = {}


def pulse_impulse_table(shape: str) -> tuple[np.ndarray, np.ndarray]:
    """``(zeros, J)``: suffix integrals of ``|ag|`` of the unit pulse (a_p = 1, T_p = 1) from
    :data:`N_IMPULSE_TABLE` equally spaced points of its support to its end.

    Exact: between consecutive zeros of the acceleration, ``int |ag| = |delta v|`` with the
    pulse's closed-form velocity. Enlarged by 1e-9 relative for rounding. Cached per shape (the
    zeros array is the kernel's dummy ``acc`` for a pulse, shared by all pulses of the shape).
    """
    if shape not in _UNIT_TABLES:
        from rockcli.pulses import make_pulse

        unit = make_pulse(shape, 1.0, 1.0)
        ts, te = unit.support()
        grid = np.linspace(ts, te, N_IMPULSE_TABLE)
        zeros = [unit.t0 + z for z in _PULSE_ZEROS[shape] if ts < unit.t0 + z < te]
        pts = np.unique(np.concatenate([grid, zeros]))
        dv = np.abs(np.diff(np.asarray(unit.velocity(pts), dtype=float)))
        suffix = np.zeros(pts.size)
        suffix[:-1] = np.cumsum(dv[::-1])[::-1]
        J = suffix[np.searchsorted(pts, grid)] * (1.0 + 1e-9) + 1e-15
        _UNIT_TABLES[shape] = (np.zeros(N_IMPULSE_TABLE), J)
    return _UNIT_TABLES[shape]


def _samples(record, what: str):
    """``(acc, dt)`` of a record, checked: at least 2 finite samples, a positive time step."""
    acc = np.ascontiguousarray(record.acc, dtype=np.float64)
    dt = float(record.dt)
    name = getattr(record, "name", "")
    if acc.ndim != 1 or acc.size < 2:
        raise RockcliInputError(f"{what} {name!r} needs at least 2 samples")
    if not np.all(np.isfinite(acc)):
        raise RockcliInputError(f"{what} {name!r} has NaN or infinite samples")
    if not (math.isfinite(dt) and dt > 0):
        raise RockcliInputError(f"{what} {name!r} has a non-positive time step {dt!r}")
    return acc, dt


def _excitation_arrays(excitation):
    """(ekind, epar, acc, jtab, dt, t_begin, t_exc_end) for the kernel."""
    k = _kernel()
    if hasattr(excitation, "acc") and hasattr(excitation, "dt"):
        acc, dt = _samples(excitation, "record")
        epar = np.zeros(8)
        epar[k.E_AP] = 1.0  # scale factor of the record
        return k.EXC_RECORD, epar, acc, record_impulse_table(acc, dt), dt, 0.0, (acc.size - 1) * dt
    shape = getattr(excitation, "shape", None)
    if shape in _PULSE_CODES:
        a_p, T_p, t0 = float(excitation.a_p), float(excitation.T_p), float(excitation.t0)
        if not (math.isfinite(a_p) and math.isfinite(T_p) and T_p > 0 and math.isfinite(t0)):
            raise RockcliInputError(f"pulse {shape}: a_p must be finite and T_p positive")
        ts, te = (float(v) for v in excitation.support())
        # the run starts at rest at t = 0: a pulse that starts earlier would be cut (its start lost)
        if ts < 0.0:
            raise RockcliInputError(
                f"pulse {shape} (T_p = {format_number(T_p)} s, t0 = {format_number(t0)} s) starts at "
                f"{format_number(ts)} s, before the run starts at t = 0 s: give t0 >= {format_number(t0 - ts)} s")
        # float64 time resolves the pulse to eps * t / T_p: 2e-10 of a period at t = 1e6 T_p
        if ts > PULSE_START_MAX_PERIODS * T_p:
            raise RockcliInputError(
                f"pulse {shape} (T_p = {format_number(T_p)} s) starts at {format_number(ts)} s, later than the "
                f"supported {PULSE_START_MAX_PERIODS:g} T_p = {format_number(PULSE_START_MAX_PERIODS * T_p)} s (the "
                f"run's clock could no "
                f"longer resolve the pulse): give a smaller t0")
        epar = np.zeros(8)
        epar[k.E_AP], epar[k.E_TP], epar[k.E_T0], epar[k.E_TS], epar[k.E_TE] = a_p, T_p, t0, ts, te
        if shape == "ricker-anti":
            from rockcli.pulses import RICKER_ANTI_BETA

            epar[k.E_BETA] = RICKER_ANTI_BETA
        zeros, jtab = pulse_impulse_table(shape)
        return _PULSE_CODES[shape], epar, zeros, jtab, 1.0, min(0.0, ts), te
    raise RockcliInputError(f"cannot simulate excitation of type {type(excitation).__name__}")


#: The records' kernel arrays already prepared by :func:`_excitation_arrays_cached`: record -> (dt, private copy of
#: the samples, the arrays); entries go when their record is garbage-collected, or the oldest first when together
#: they hold more than :data:`RECORD_CACHE_BYTES` of samples.
_RECORD_ARRAYS = weakref.WeakKeyDictionary()
_RECORD_LOCK = threading.Lock()
RECORD_CACHE_BYTES = 64 * 2**20


def _excitation_arrays_cached(excitation):
    """:func:`_excitation_arrays`; a record's arrays from the process's cache when its samples are, bit for bit,
    those of the arrays cached for the same record object (the batch path's calls, :mod:`rockcli.solve.batch`).

    Why it cannot return a stale array: :func:`_excitation_arrays` of a record is a function of its samples (as
    contiguous float64) and its time step only (the name appears in error messages, and a record that raises is
    never cached). An entry keeps a private copy of the samples it was made from, and the arrays it returns (that
    copy, the impulse table, ``epar``) are read-only: nobody can change them. It is returned only when the
    record's time step equals the entry's and its samples equal the copy bit for bit (compared as 64-bit
    integers, so -0.0 is not 0.0 and a NaN never matches), i.e. when :func:`_excitation_arrays` would compute
    the same arrays from the same inputs. Keyed on the record object (weakly: the entry goes with the record, so
    a new record cannot inherit an old one's entry), so a record changed in place is caught by the comparison,
    and one that is never mutated pays an equality test of its samples (memory speed) per call instead of the
    validation and the impulse table. Pulses, and objects that cannot be weakly referenced, are prepared as before.
    """
    if not (hasattr(excitation, "acc") and hasattr(excitation, "dt")):
        return _excitation_arrays(excitation)
    try:
        acc = np.ascontiguousarray(excitation.acc, dtype=np.float64)
        dt = float(excitation.dt)
        with _RECORD_LOCK:
            entry = _RECORD_ARRAYS.get(excitation)
    except (TypeError, ValueError):  # not a number, unhashable, no weak reference: as before
        return _excitation_arrays(excitation)
    if (entry is not None and entry[0] == dt and entry[1].shape == acc.shape
            and np.array_equal(entry[1].view(np.uint64), acc.view(np.uint64))):
        return entry[2]
    ekind, epar, acc_k, jtab, dt_k, t_begin, t_exc_end = _excitation_arrays(excitation)  # raises as before
    own = np.array(acc_k, dtype=np.float64, copy=True)
    for a in (own, jtab, epar):
        a.flags.writeable = False
    arrays = (ekind, epar, own, jtab, dt_k, t_begin, t_exc_end)
    with _RECORD_LOCK:
        try:
            _RECORD_ARRAYS[excitation] = (dt, own, arrays)
        except TypeError:
            return arrays
        held = sum(e[1].nbytes for e in _RECORD_ARRAYS.values())
        for key in list(_RECORD_ARRAYS.keys()):
            if held <= RECORD_CACHE_BYTES or key is excitation:
                break
            held -= _RECORD_ARRAYS.pop(key)[1].nbytes
    return arrays


#: the key of a record's ``meta`` that carries its vertical component (:func:`with_vertical`)
VERTICAL_KEY = "vertical_motion"


def with_vertical(record, vertical, label: str = ""):
    """``record`` carrying ``vertical`` (a record or a pulse, upward positive) as its vertical ground motion.

    :func:`rockcli.solve.simulate` and :func:`rockcli.solve.simulate_many` run a record that carries one under
    it when no ``vertical=`` is given; the vertical motion is kept by :meth:`Record.scaled` and by copies made
    with :func:`dataclasses.replace` (the scale factor of a sweep multiplies the horizontal motion only).
    ``label`` says which motion it is, for the outputs (:func:`vertical_label`).
    """
    import dataclasses

    if not hasattr(record, "meta"):
        raise RockcliInputError("only a record can carry a vertical component (an analytic pulse cannot)")
    return dataclasses.replace(record, meta={**record.meta, VERTICAL_KEY: vertical, VERTICAL_KEY + "_label": label})


def attached_vertical(excitation):
    """The vertical motion an excitation carries (:func:`with_vertical`), or None."""
    meta = getattr(excitation, "meta", None)
    return meta.get(VERTICAL_KEY) if meta else None


def vertical_label(excitation) -> str:
    """What the vertical motion an excitation carries is (``""``: none)."""
    meta = getattr(excitation, "meta", None)
    return (meta.get(VERTICAL_KEY + "_label") or "vertical motion") if attached_vertical(excitation) is not None else ""


#: why a vertical motion is refused on an isolated base (the commands add what to give instead)
VERTICAL_RIGID_ONLY = ("a vertical ground motion is modelled on a rigid foundation only: on an isolated base it also "
                       "changes the bearings' normal force (a sliding bearing's friction mu (m + m_b)(g + a_v), a "
                       "pendulum's restoring force), which the bearing models do not include")

#: samples per period of a vertical pulse (read piecewise linear, like a record)
VERTICAL_PULSE_SAMPLES = 2000
#: relative difference of time steps still read as the same time base
_SAME_DT = 1e-9


def _vertical_arrays(vertical, excitation, foundation, g: float):
    """``(vacc, vjtab, vdt, t_v_end, label)`` of a vertical ground acceleration (upward positive) for the
    rigid-foundation kernel: samples every ``vdt`` from t = 0, piecewise linear, zero after the last.

    ``vertical`` is None (none: empty arrays), a record (same time step and start as a horizontal
    record; its length may differ) or an analytic pulse (sampled every ``T_p/VERTICAL_PULSE_SAMPLES``
    from t = 0 to the end of its support). Refused on an isolated base, and wherever ``g + a_v <= 0``.
    """
    from rockcli.models import Rigid

    if vertical is None:
        return np.empty(0), np.empty(0), 1.0, 0.0, "none"
    if foundation is not None and not isinstance(foundation, Rigid):
        raise RockcliInputError(VERTICAL_RIGID_ONLY)
    if hasattr(vertical, "acc") and hasattr(vertical, "dt"):
        vacc, vdt = _samples(vertical, "vertical record")
        name = getattr(vertical, "name", "")
        if excitation is not None and hasattr(excitation, "acc") and hasattr(excitation, "dt"):
            hdt = float(excitation.dt)
            if abs(vdt - hdt) > _SAME_DT * hdt:
                raise RockcliInputError(
                    f"vertical record {name!r} has time step {format_number(vdt)} s, the horizontal record {format_number(hdt)} s: the two "
                    f"components must share one time base (resample one of them first)")
            hs, vs = float(getattr(excitation, "t_start", 0.0)), float(getattr(vertical, "t_start", 0.0))
            if abs(hs - vs) > 0.5 * hdt:
                raise RockcliInputError(
                    f"vertical record {name!r} starts at {format_number(vs)} s, the horizontal record at {format_number(hs)} s: the two "
                    f"components must share one time base")
            vdt = hdt
        label = f"record {name}" if name else "record"
    else:
        shape = getattr(vertical, "shape", None)
        if shape not in _PULSE_CODES:
            raise RockcliInputError(f"cannot use a {type(vertical).__name__} as the vertical ground motion")
        T_p = float(vertical.T_p)
        ts, te = (float(v) for v in vertical.support())
        if not (math.isfinite(T_p) and T_p > 0 and math.isfinite(float(vertical.a_p))):
            raise RockcliInputError(f"vertical pulse {shape}: a_p must be finite and T_p positive")
        if ts < 0.0:
            raise RockcliInputError(f"vertical pulse {shape} starts at {format_number(ts)} s, before the run starts at "
                                    f"t = 0 s: give a larger t0")
        vdt = T_p / VERTICAL_PULSE_SAMPLES
        n = int(math.ceil(te / vdt)) + 1
        if n > 50_000_000:
            raise RockcliInputError(f"vertical pulse {shape} ends too late ({format_number(te)} s) for its period: "
                                    f"give a smaller t0")
        tt = vdt * np.arange(n)
        vacc = np.where((tt >= ts) & (tt <= te), np.asarray(vertical.acceleration(tt), dtype=float), 0.0)
        label = f"pulse {shape} a_p={float(vertical.a_p):g}m/s2 T_p={T_p:g}s t0={float(vertical.t0):g}s"
    low = int(np.argmin(vacc))
    if g + vacc[low] <= 0.0:
        raise RockcliInputError(
            f"the vertical ground acceleration reaches {vacc[low]:.4g} m/s^2 at t = {low * vdt:g} s, so g + a_v <= 0: "
            f"the block would lift off the ground, which rockcli does not model")
    return vacc, record_impulse_table(vacc, vdt), vdt, (vacc.size - 1) * vdt, label
