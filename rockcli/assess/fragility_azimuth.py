"""``assess fragility --azimuth worst``: overturning capacities per orientation of the rocking plane.

Each pair of horizontal components is projected onto the azimuths 0 <= theta < 180 deg
(:func:`rockcli.assess.azimuth.expand`) and every projection gets its overturning scale, the margin
search of :func:`rockcli.assess.fragility.run_fragility` (373 factors 0.1x..4x, bisection to 1 %).
A fragility needs one intensity measure per record, independent of the orientation, so the pair's IM
is the **median over the orientations run** of the IM of the projections (for PGA at a 5 deg step,
the RotD50 PGA of the pair, Boore 2010), and the capacity of an orientation is its overturning scale
x that IM. Per pair, two capacities are kept:

* ``median``: the median orientation's (the lower of the two middle ones for an even count, an
  orientation actually run): the body's capacity when its facade's azimuth is unknown;
* ``worst``: the smallest over the orientations, the rocking analogue of RotD100: the capacity of
  the most adverse orientation, with its azimuth.

Censoring follows the orientation kept: a pair whose worst orientation does not overturn up to 4x
is right-censored (then none does); the ordering puts left-censored capacities (overturning at 0.1x)
first and right-censored ones last. Each set of capacities is fitted as in
:func:`rockcli.assess.fragility.run_fragility` (lognormal MLE with censoring, the same paired
bootstrap over records), giving two :class:`~rockcli.assess.fragility.Fragility` results. The worst
capacity of each pair is at most its median one.
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Sequence

import numpy as np

from rockcli.errors import RockcliInputError

#: The two capacities kept per pair, in the order they are reported.
ORIENTATIONS = ("median", "worst")


def run_fragility_azimuths(columns, excitations: Sequence, configurations, *, azimuths=None, im: str = "pga",
                           n_boot: int | None = None, seed: int | None = None, level: float | None = None,
                           unavailable=(), **kwargs) -> dict:
    """``{"median": Fragility, "worst": Fragility}`` of the pairs in ``excitations`` over ``azimuths`` [deg]
    (None: each pair's own, ``Excitation.azimuths``).

    ``excitations`` come from :func:`rockcli.assess.resolve_excitations` with ``azimuth="worst"`` (pairs,
    or error rows); ``kwargs`` (progress, runner, chunk_size, solver options) go to the margin runs of
    :func:`rockcli.assess.fragility.run_fragility`. Rows carry ``azimuth_deg`` (the orientation kept) and
    ``orientation``.
    """
    from rockcli.assess.azimuth import expand
    from rockcli.assess.fragility import (CENSORED_RIGHT, DEFAULT_LEVEL, DEFAULT_N_BOOT, DEFAULT_SEED, IMS,
                                          MARGIN_GRID, Fragility, FragilityRow, _fit_curves, run_fragility)
    from rockcli.assess.scenes import check_scenes

    n_boot = DEFAULT_N_BOOT if n_boot is None else int(n_boot)
    seed = DEFAULT_SEED if seed is None else int(seed)
    level = DEFAULT_LEVEL if level is None else float(level)
    expanded, groups = expand(excitations, azimuths)
    # an azimuth normal to a motion that stays in one vertical plane feels nothing: it never overturns
    # (right-censored at any factor), and its IM is 0; it is not run
    still = {x.label for x in expanded if x.pair is not None and x.motion is not None and not np.any(x.motion.acc)}
    run = [x for x in expanded if x.label not in still]
    if run:
        each = run_fragility(columns, run, configurations, im=im, n_boot=0, seed=seed, level=level,
                             unavailable=unavailable, **kwargs)
    else:  # no motion along any orientation of any pair: nothing to run (run_fragility refuses no excitation)
        columns, _, configurations = check_scenes(columns, excitations, configurations)
        if im not in IMS:
            raise RockcliInputError(f"intensity measure {im!r} is not one of {', '.join(IMS)}")
        each = Fragility(list(columns), list(configurations), [], IMS[im], [], [], 0, seed, level,
                         (float(MARGIN_GRID[0]), float(MARGIN_GRID[-1])), list(unavailable))
    by_key = {(r.column, r.record, r.configuration): r for r in each.rows}
    for b in columns:
        for c in configurations:
            for label in still:
                by_key[(b.name, label, c.header)] = FragilityRow(
                    b.name, b.R, b.alpha_deg, label, "", c.label, c.header, 0.0, censored=CENSORED_RIGHT,
                    margin_note="no motion along this azimuth")
    out = {}
    for how in ORIENTATIONS:
        rows = []
        for b in columns:
            for x in excitations:
                for c in configurations:
                    if x.label not in groups:  # an error row (a pair that could not be read)
                        rows.append(replace(by_key[(b.name, x.label, c.header)], orientation=how))
                        continue
                    subs = [by_key[(b.name, label, c.header)] for label in groups[x.label]]
                    rows.append(_kept_row(subs, x, how, each.grid))
        curves = _fit_curves(columns, configurations, excitations, rows, n_boot, seed, level)
        out[how] = replace(each, excitations=list(excitations), rows=rows, curves=curves, n_boot=n_boot)
    return out


def _order(row, lo_f: float):
    """Sort key of an orientation's capacity in scale units: left-censored first, right-censored last."""
    from rockcli.assess.fragility import CENSORED_LEFT, CENSORED_RIGHT

    if row.censored == CENSORED_LEFT:
        return (lo_f, -1)
    if row.censored == CENSORED_RIGHT:
        return (math.inf, 1)
    return (row.overturn_scale, 0)


def _kept_row(subs: Sequence, x, how: str, grid):
    """The pair's row: the median (lower middle) or the smallest capacity of its orientations, at the pair's
    IM (the median of the projections' IMs). The worst orientation is the most adverse of
    :func:`rockcli.assess.azimuth.most_adverse` (the smallest overturning scale; the first of equals), the
    definition of ``assess column`` and ``simulate``; when every orientation ranks equal (typically none
    overturns up to 4x) no azimuth is named (``azimuth_deg`` NaN), for the median either: any orientation
    would be an accident of the sweep's order."""
    from rockcli.assess.azimuth import adverse_key, most_adverse
    from rockcli.assess.fragility import CENSORED_RIGHT

    lo_f, hi_f = grid
    failed = [r for r in subs if r.error]
    im_pair = float(np.median([r.im_value for r in subs]))
    if failed:
        return replace(failed[0], record=x.label, source=x.source, im_value=im_pair, orientation=how)
    if not im_pair > 0:
        return replace(subs[0], record=x.label, source=x.source, im_value=im_pair, orientation=how, censored="",
                       error=f"{x.source}: the IM is 0 along the median orientation: nothing to scale")
    worst = most_adverse([adverse_key(False, math.nan, math.nan, r.overturn_scale) for r in subs])
    ranked = sorted(subs, key=lambda r: _order(r, lo_f))
    kept = (ranked[0] if worst is None else subs[worst]) if how == "worst" else ranked[(len(ranked) - 1) // 2]
    scale = _order(kept, lo_f)[0] if kept.censored != CENSORED_RIGHT else hi_f  # the factor, or the bound
    if worst is None and len(subs) > 1:
        theta, where = math.nan, f"any azimuth ({tied_words(subs, grid)})"
    else:
        theta = float(kept.record.rpartition("@")[2])
        where = f"azimuth {theta:g} deg ({how} of {len(subs)} orientations)"
    return replace(kept, record=x.label, source=x.source, im_value=im_pair, capacity=scale * im_pair,
                   azimuth_deg=theta, orientation=how,
                   margin_note=(f"{kept.margin_note}; " if kept.margin_note else "") + where)


def tied_words(subs: Sequence, grid) -> str:
    """Why no orientation of a pair is more adverse than another, in the words of ``assess column``'s ``@any``."""
    from rockcli.assess.fragility import CENSORED_LEFT, CENSORED_RIGHT

    n = len(subs)
    if all(r.censored == CENSORED_RIGHT for r in subs):
        why = f"none of the {n} orientations overturns it up to {grid[1]:g}x"
    elif all(r.censored == CENSORED_LEFT for r in subs):
        why = f"all {n} orientations overturn it already at {grid[0]:g}x"
    else:
        why = f"the {n} orientations rank the same"
    return f"no orientation is more adverse than another: {why}"
