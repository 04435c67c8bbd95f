"""Critical block size (the paper's Table I) and the Table I scenes.

Where the rigid-foundation and isolated minimum-overturning curves cross: on a coarse ``x`` grid the
last change from "isolation is better" (``y_rigid <= y_iso``) to "rigid is better" beyond which the
rigid curve stays above the isolated one, refined by bisection in ``x``. The block size follows from
the pulse period: ``p = omega_p / x_cross = 2 pi / (T_p x_cross)``, ``R = 3 g / (4 p^2)``; larger
blocks are safer without isolation.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import Optional, Sequence

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.spectra.grids import Grid
from rockcli.spectra.minimum import (DEFAULT_REFINE, DEFAULT_REFINE_BAND, DEFAULT_STEP, DEFAULT_TOL, TOL_MIN,
                                     curves_of, search_min_overturning, y_limit)
from rockcli.spectra.runner import Runner
from rockcli.spectra.scenes import REFERENCE_R, Family, Isolation, PulseChoice, parse_isolation
from rockcli.io.units import G

#: The paper's Table I scenes (Figures 6-7): the pulses it states for the Aigio OTE FP 1995 and
#: Coyote Lake Gilroy #6 230 1979 records, slenderness, T_b/T_p, and the bearings of Figure 6.
TABLE_I_PULSES = (("Aigio OTE FP 1995 (paper's pulse)", "ricker-sym", 0.6),
                  ("Coyote Lake Gilroy #6 230 1979 (paper's pulse)", "ricker-anti", 0.9))
TABLE_I_ALPHAS_DEG = (10.0, 20.0)
TABLE_I_TB_TP = (2.0, 3.0, 4.0)
TABLE_I_XI = 0.05
TABLE_I_GAMMA = 0.01
#: x grid on which the curves are compared before the crossing is refined.
CROSSING_GRID = (0.5, 12.0, 47)


def critical_R(T_p: float, wp_over_p: float) -> float:
    """Block semi-diagonal [m] whose ``omega_p / p`` is ``wp_over_p`` under a pulse of period ``T_p`` [s]:
    ``p = 2 pi / (T_p wp_over_p)``, ``R = 3 g / (4 p^2)``."""
    p = 2.0 * math.pi / (T_p * wp_over_p)
    return 0.75 * G / (p * p)


@dataclass(frozen=True)
class CriticalRow:
    """One row of the Table-I-like result."""

    source: str
    pulse: str
    T_p_s: float
    alpha_deg: float
    Tb_over_Tp: float
    Tb_s: float
    wp_over_p_cross: float
    R_critical_m: float
    isolation: str = ""
    note: str = ""
    ap_cross_over_g_tan_alpha: float = float("nan")
    #: the plinth the body stands on, rigid and isolated alike (its spec; empty: the body alone)
    plinth: str = ""

    def as_dict(self) -> dict:
        return {k: getattr(self, k) for k in ("source", "pulse", "T_p_s", "alpha_deg", "Tb_over_Tp", "Tb_s",
                                               "wp_over_p_cross", "R_critical_m")}


@dataclass(frozen=True)
class CriticalResult:
    rows: list
    curves: list = field(default_factory=list)  # the coarse-grid curves (MinCurve), rigid first per panel
    notes: list = field(default_factory=list)
    runs: int = 0


def critical_sizes(pulses: Sequence[PulseChoice], alphas_deg: Sequence[float], isolations: Sequence[Isolation], *,
                   wp_grid: Grid = Grid(*CROSSING_GRID), xtol: float = 1e-3, ap_max: float = 50.0,
                   step: float = DEFAULT_STEP, tol: float = DEFAULT_TOL, refine: float = DEFAULT_REFINE,
                   refine_band: float = DEFAULT_REFINE_BAND, R: float = REFERENCE_R,
                   runner: Optional[Runner] = None, progress=None, plinths: Sequence = (None,)) -> CriticalResult:
    """Where the rigid and isolated minimum-overturning curves cross, as a block size (Table I).

    For every pulse (with ``T_p``), slenderness and isolation: the curves on ``wp_grid``, the last
    change from ``y_rigid <= y_iso`` to ``y_rigid > y_iso`` beyond which the rigid curve stays above
    (no overturning up to ``ap_max`` counts as infinitely high; where neither overturns, as "rigid
    better": isolation brings nothing there), refined by bisection in ``x`` to ``xtol`` (relative).
    Rows come in the order pulse, alpha, isolation, plinth. ``plinths``: None (the body alone) and/or
    :class:`rockcli.spectra.plinth.PlinthRatio` plinths: the rigid and the isolated curves of the body on that
    plinth are compared (the size is the body's R, the plinth in proportion to it).
    """
    from rockcli.spectra.arguments import as_alphas, as_grid, as_isolations, as_plinths, as_pulses

    pulses, alphas_deg, isolations = as_pulses(pulses), as_alphas(alphas_deg), as_isolations(isolations)
    plinths = as_plinths(plinths)
    wp_grid = as_grid(wp_grid, "wp_grid")
    if not (isinstance(xtol, (int, float)) and math.isfinite(xtol) and TOL_MIN <= xtol <= 0.5):
        raise RockcliInputError(f"xtol must lie in [{TOL_MIN:g}, 0.5] (relative; double precision cannot bisect "
                                f"finer), got {xtol!r}")
    for pc in pulses:
        if pc.T_p is None:
            raise RockcliInputError(f"pulse {pc.shape}: critical size needs its period, e.g. {pc.shape}:Tp=0.6")
    if any(iso.rigid for iso in isolations):
        raise RockcliInputError("critical size compares isolation with the rigid foundation: give isolated "
                                "configurations only")
    runner = runner or Runner()
    xs = wp_grid.values
    shapes = list(dict.fromkeys(pc.shape for pc in pulses))
    rigid = Isolation("none")
    # the dimensionless curves depend on the shape, not on T_p: one rigid + isolated set per shape
    fam_keys = [(a, sh, iso, pl) for sh in shapes for a in alphas_deg for pl in plinths
                for iso in [rigid, *isolations]]
    families = [Family(math.radians(a), sh, iso, R, pl) for a, sh, iso, pl in fam_keys]
    findex = {k: i for i, k in enumerate(fam_keys)}
    fam = np.repeat(np.arange(len(families)), xs.size)
    search = dict(ap_max=ap_max, step=step, tol=tol, refine=refine, refine_band=refine_band)
    res = search_min_overturning(families, fam, np.tile(xs, len(families)), runner=runner, progress=progress,
                                 **search)
    runs = res.runs
    grid_min = {k: res.ap_min[i * xs.size:(i + 1) * xs.size] for k, i in findex.items()}
    curves = curves_of(res, [(a, PulseChoice(sh), iso, pl) for a, sh, iso, pl in fam_keys], xs, **search)

    def better_rigid(yr, yi):
        # no overturning up to ap_max counts as infinitely high; when neither overturns, isolation
        # brings nothing within the range explored: counted as "rigid better"
        both = np.isnan(yr) & np.isnan(yi)
        yr = np.where(np.isnan(yr), np.inf, yr)
        yi = np.where(np.isnan(yi), np.inf, yi)
        return (yr > yi) | both

    # per (shape, alpha, isolation): bracket on the grid
    tasks = {}
    notes = []
    for sh, a, pl in ((sh, a, pl) for sh in shapes for a in alphas_deg for pl in plinths):
        yr = grid_min[(a, sh, rigid, pl)]
        on = "" if pl is None else f" on {pl.label}"
        for iso in isolations:
            yi = grid_min[(a, sh, iso, pl)]
            both_inf = np.isnan(yr) & np.isnan(yi)
            b = better_rigid(yr, yi)
            key = (sh, a, iso, pl)
            changes = int(np.count_nonzero(b[1:] != b[:-1]))
            if both_inf.any():
                top = min(ap_max, y_limit(math.radians(a)))  # the search stops at a_p = 100 g
                upto = f"{ap_max:g}" if top >= ap_max else f"about {top:.4g} (a_p = 100 g)"
                notes.append(f"{sh}, alpha = {a:g} deg, {iso.label}{on}: neither overturns up to "
                             f"{upto} g tan(alpha) at omega_p/p >= {xs[both_inf][0]:.3g} "
                             f"({int(both_inf.sum())} grid values, counted as rigid better)")
            if b.all():
                tasks[key] = ("below", xs[0], xs[0])
            elif not b[-1]:
                tasks[key] = ("above", xs[-1], xs[-1])
            else:
                i = int(np.flatnonzero(~b)[-1])
                tasks[key] = ("bracket", xs[i], xs[i + 1])
                if changes > 1:
                    notes.append(f"{sh}, alpha = {a:g} deg, {iso.label}{on}: the curves cross {changes} times on "
                                 f"the grid; the last crossing is used (rigid better beyond it)")
    # bisection in x, all brackets together
    lo = {k: v[1] for k, v in tasks.items() if v[0] == "bracket"}
    hi = {k: v[2] for k, v in tasks.items() if v[0] == "bracket"}
    y_at = {}
    while True:
        act = [k for k in lo if hi[k] - lo[k] > xtol * hi[k]]
        if not act:
            break
        fams, xv = [], []
        for k in act:
            sh, a, iso, pl = k
            m = 0.5 * (lo[k] + hi[k])
            fams += [findex[(a, sh, rigid, pl)], findex[(a, sh, iso, pl)]]
            xv += [m, m]
        r = search_min_overturning(families, np.array(fams), np.array(xv), runner=runner, **search)
        runs += r.runs
        for j, k in enumerate(act):
            m = xv[2 * j]
            yr, yi = r.ap_min[2 * j], r.ap_min[2 * j + 1]
            if better_rigid(np.array([yr]), np.array([yi]))[0]:
                hi[k] = m
                y_at[k] = (yr, yi)
            else:
                lo[k] = m
    rows = []
    for pc, a, iso, pl in ((pc, a, iso, pl) for pc in pulses for a in alphas_deg for iso in isolations
                           for pl in plinths):
        key = (pc.shape, a, iso, pl)
        kind, x0, x1 = tasks[key]
        note = ""
        if kind == "bracket":
            xc = 0.5 * (lo[key] + hi[key])
            Rc = critical_R(pc.T_p, xc)
            yc = y_at.get(key, (np.nan, np.nan))[1]
        elif kind == "below":
            xc, Rc, yc = np.nan, np.nan, np.nan
            note = (f"rigid better over the whole grid: crossing below omega_p/p = {x0:g} "
                    f"(R < {critical_R(pc.T_p, x0):.3g} m)")
        else:
            xc, Rc, yc = np.nan, np.nan, np.nan
            note = (f"isolation better up to omega_p/p = {x1:g}: crossing beyond the grid "
                    f"(R > {critical_R(pc.T_p, x1):.3g} m)")
        rows.append(CriticalRow(pc.source, pc.shape, float(pc.T_p), float(a), float(iso.ratio),
                                float(f"{iso.ratio * pc.T_p:.12g}"), float(xc), float(Rc), iso.label, note, float(yc),
                                "" if pl is None else pl.label))
    return CriticalResult(rows=rows, curves=curves, notes=notes, runs=runs)


def table_i_isolations(tb_tp=TABLE_I_TB_TP, xi: float = TABLE_I_XI, gamma: float = TABLE_I_GAMMA,
                       template: str = "linear") -> list[Isolation]:
    """Isolations ``template`` with ``TbTp`` from ``tb_tp`` and the given ``xi``/``gamma`` (None: leave out)."""
    kind, _, rest = str(template).strip().partition(":")
    base = f"{kind}:TbTp=1" + (f",{rest}" if rest.strip() else "")
    out = []
    for r in tb_tp:
        iso = replace(parse_isolation(base), ratio=float(r))
        if xi is not None:
            iso = iso.with_param("xi", xi)
        if gamma is not None:
            iso = iso.with_param("gamma", gamma)
        iso.foundation(1.0)
        out.append(iso)
    return out


def table_i_pulses() -> list[PulseChoice]:
    """The paper's Table I pulses (ricker-sym T_p = 0.6 s, ricker-anti T_p = 0.9 s) with their records' names."""
    return [PulseChoice(shape, T_p, source) for source, shape, T_p in TABLE_I_PULSES]
