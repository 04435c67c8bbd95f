"""Overturning maps over ``omega_p/p x a_p/(g tan alpha)`` (the paper's Figures 6 and 9).

Maps run to the end of the motion by default so that ``theta_max_over_alpha`` is the run's peak;
``early=True`` makes them faster, with the peak then only a lower bound for runs stopped during the
pulse (``peak_final`` False).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.spectra.grids import MAX_CELLS, Grid
from rockcli.spectra.runner import Runner
from rockcli.spectra.scenes import REFERENCE_R, Family, Isolation, PulseChoice


@dataclass(frozen=True)
class OverturningMap:
    """Verdicts over ``wp_over_p`` (columns) x ``ap_over_g_tan_alpha`` (rows).

    Arrays have shape ``(len(ap_over_g_tan_alpha), len(wp_over_p))``.
    """

    alpha_deg: float
    pulse: PulseChoice
    isolation: Isolation
    wp_over_p: np.ndarray
    ap_over_g_tan_alpha: np.ndarray
    overturned: np.ndarray
    uplifted: np.ndarray
    theta_max_over_alpha: np.ndarray
    settled: np.ndarray
    peak_final: np.ndarray
    nfev: int
    #: the plinth the block stands on in every cell (:class:`rockcli.spectra.plinth.PlinthRatio`; None: alone)
    plinth: Optional[object] = None
    #: which block toppled, per cell, on a plinth: 0 none, 1 the body, 2 the plinth (None without a plinth)
    toppled: Optional[np.ndarray] = None

    @property
    def isolation_label(self) -> str:
        return self.isolation.label


def overturning_maps(alphas_deg: Sequence[float], pulses: Sequence[PulseChoice], isolations: Sequence[Isolation],
                     wp_grid: Grid, ap_grid: Grid, *, R: float = REFERENCE_R, runner: Optional[Runner] = None,
                     progress=None, early: bool = False, plinths: Sequence = (None,)) -> list[OverturningMap]:
    """Overturning maps for every ``alpha x pulse x isolation x plinth`` (in that nesting order), in one batch.

    ``early``: stop each run once its verdict is proven (faster; the same verdicts and uplift flags,
    ``theta_max_over_alpha`` then a lower bound where ``peak_final`` is False). ``plinths``: None (the block
    alone) and/or :class:`rockcli.spectra.plinth.PlinthRatio` plinths the block stands on (its maps then run on
    the stack driver, full peaks whatever ``early`` says: :mod:`rockcli.spectra.runner`).
    """
    from rockcli.spectra.arguments import as_alphas, as_grid, as_isolations, as_plinths, as_pulses

    alphas_deg, pulses, isolations = as_alphas(alphas_deg), as_pulses(pulses), as_isolations(isolations)
    wp_grid, ap_grid = as_grid(wp_grid, "wp_grid"), as_grid(ap_grid, "ap_grid")
    plinths = as_plinths(plinths)
    cells = len(alphas_deg) * len(pulses) * len(isolations) * len(plinths) * wp_grid.count * ap_grid.count
    if cells > MAX_CELLS:
        raise RockcliInputError(f"the maps have {cells:,} cells (slenderness x pulse x foundation x omega_p/p x "
                                f"a_p); at most {MAX_CELLS:,} are run at once (about 20 minutes on 2 cores): use "
                                "coarser grids or fewer configurations")
    runner = runner or Runner()
    xs, ys = wp_grid.values, ap_grid.values
    keys = [(a, pc, iso, pl) for a in alphas_deg for pc in pulses for iso in isolations for pl in plinths]
    families = [Family(math.radians(a), pc.shape, iso, R, pl) for a, pc, iso, pl in keys]
    Y, X = np.meshgrid(ys, xs, indexing="ij")
    ncell = X.size
    fam = np.repeat(np.arange(len(families)), ncell)
    res = runner(families, fam, np.tile(X.ravel(), len(families)), np.tile(Y.ravel(), len(families)), progress,
                 early=early)
    maps = []
    shape = X.shape
    for j, (a, pc, iso, pl) in enumerate(keys):
        s = slice(j * ncell, (j + 1) * ncell)
        maps.append(OverturningMap(
            alpha_deg=float(a), pulse=pc, isolation=iso, wp_over_p=xs, ap_over_g_tan_alpha=ys,
            overturned=res.overturned[s].reshape(shape), uplifted=res.uplifted[s].reshape(shape),
            theta_max_over_alpha=res.theta_max_over_alpha[s].reshape(shape),
            settled=res.settled[s].reshape(shape), peak_final=res.peak_final[s].reshape(shape),
            nfev=int(res.nfev[s].sum()), plinth=pl,
            toppled=None if pl is None else res.toppled[s].reshape(shape)))
    return maps


def overturning_map(alpha_deg: float, pulse, isolation, wp_grid: Grid, ap_grid: Grid, **kwargs) -> OverturningMap:
    """One overturning map (see :func:`overturning_maps`); ``pulse`` and ``isolation`` may be spec strings, the
    grids ``"start:stop:count"``; a wrong type is one sentence (:mod:`rockcli.spectra.arguments`)."""
    from rockcli.io.inputs import check_type
    from rockcli.spectra.arguments import as_isolation, as_pulse_choice

    check_type(alpha_deg, (int, float, np.integer, np.floating), "alpha_deg", "a number of degrees")
    return overturning_maps([alpha_deg], [as_pulse_choice(pulse)], [as_isolation(isolation)], wp_grid, ap_grid,
                            **kwargs)[0]
