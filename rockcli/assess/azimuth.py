"""``--azimuth worst``: every orientation of the rocking plane, and the most adverse one.

A pair of horizontal components (an :class:`~rockcli.assess.scenes.Excitation` with ``pair``) is
projected onto the azimuths 0 <= theta < 180 deg (:func:`expand`: one excitation per azimuth, run like
any other, margins included, on all cores); :func:`collapse` keeps, per column x pair x configuration,
the row of the most adverse orientation, with its azimuth (``azimuth_deg``) and the orientations that
overturn at 1x (``overturning_azimuths``). theta and theta + 180 deg are the same motion reversed, which
a symmetric block answers with the mirrored response, so half a turn covers every orientation.

**The most adverse orientation** (one definition for ``assess column`` and ``simulate``,
:func:`adverse_key` and :func:`most_adverse`): the smallest overturning scale (the margin, when it was
searched: ``assess column`` without ``--no-margin``), then an overturn at 1x (the earliest), then the
largest peak |theta|/alpha; among equals the first (smallest azimuth). When every orientation ranks
equal there is none: typically nothing lifts the body off at 1x (every peak is 0) and, with margins,
nothing overturns up to 4x either. Naming one then (0 deg, the first of the sweep) would be an
accident of the sweep's order, so none is named: ``simulate`` says that no orientation lifts it off,
``assess column`` shows ``@any`` (``azimuth_deg`` empty). A record that lifts nothing off at 1x but
overturns the body at some larger scale *has* a most adverse orientation for ``assess column`` (the
smallest margin) and none for ``simulate``, which runs 1x only: the two agree, and say so.

**The stroke** the bearings must allow is not the most adverse orientation's: a row keeps that orientation's
run (``base_disp_max_m`` with its verdict and peak), and :func:`collapse` adds
``base_disp_max_surviving_azimuths_m``, the largest peak base displacement over the orientations in which
the body survives (a toppled run's displacement is no demand to design for), which every sentence about the
stroke uses (:func:`rockcli.assess.verdicts.stroke_m`).
"""

from __future__ import annotations

import math
from dataclasses import replace
from typing import Sequence


def expand(excitations: Sequence, azimuths) -> tuple[list, dict]:
    """The excitations with every pair replaced by its projections onto ``azimuths``; and, per pair label,
    the labels of its projections in azimuth order."""
    from rockcli.records.orientation import project
    from rockcli.solve import attached_vertical, vertical_label, with_vertical

    out, groups = [], {}
    for x in excitations:
        if x.pair is None or x.motion is None:
            out.append(x)
            continue
        subs = []
        for theta in azimuths:
            rec = project(*x.pair, float(theta))
            if attached_vertical(x.motion) is not None:  # the pair's vertical component goes with every projection
                rec = with_vertical(rec, attached_vertical(x.motion), vertical_label(x.motion))
            sub = replace(x, label=f"{x.label}@{float(theta):g}", motion=rec, pga_g=rec.pga_g,
                          azimuth_deg=float(theta))
            subs.append(sub.label)
            out.append(sub)
        groups[x.label] = subs
    return out, groups


def adverse_key(overturned: bool, t_overturn_s: float, theta_max_over_alpha: float,
                overturn_scale: float | None = None) -> tuple:
    """Sort key of one orientation's run: smaller is more adverse (see the module notes). ``overturn_scale``:
    its margin when one was searched (NaN: none up to the top of the scan), None when not."""
    peak = theta_max_over_alpha if not math.isnan(theta_max_over_alpha) else -math.inf
    key = (0 if overturned else 1, t_overturn_s if overturned and not math.isnan(t_overturn_s) else math.inf, -peak)
    if overturn_scale is None:
        return key
    return (overturn_scale if not math.isnan(overturn_scale) else math.inf, *key)


def most_adverse(keys: Sequence[tuple]) -> int | None:
    """Index of the most adverse of the orientations' :func:`adverse_key` (the first of equals), or None
    when they all rank equal (no orientation is more adverse than another)."""
    if not keys:
        return None
    best = min(range(len(keys)), key=lambda i: keys[i])
    if len(keys) > 1 and all(k == keys[best] for k in keys):
        return None
    return best


def _key(row, margin: bool) -> tuple:
    return adverse_key(bool(row.overturned), row.t_overturn_s, row.theta_max_over_alpha,
                       row.overturn_scale if margin else None)


def worst_row(rows: Sequence, margin: bool):
    """The most adverse of one scene's rows over orientations (an error row if any run failed), and whether
    it is more adverse than another (False: they all rank equal, and the first is returned)."""
    failed = [r for r in rows if r.error]
    if failed:
        return failed[0], True
    i = most_adverse([_key(r, margin) for r in rows])
    return (rows[0], False) if i is None else (rows[i], True)


def collapse(result, excitations: Sequence, groups: dict):
    """The assessment of the original ``excitations``: one row per column x pair x configuration, the worst
    orientation's, with ``azimuth_deg`` (NaN when no orientation is more adverse than another: the row is
    then the first orientation's, like every other's) and ``overturning_azimuths`` set."""
    from rockcli.assess.table import Assessment
    from rockcli.assess.verdicts import SURVIVES, outcome

    rows = []
    for b in result.columns:
        for x in excitations:
            for c in result.configurations:
                if x.label not in groups:
                    rows.append(result.row(b.name, x.label, c.header))
                    continue
                subs = [result.row(b.name, label, c.header) for label in groups[x.label]]
                worst, one = worst_row(subs, result.margin)
                over = [r.record.rpartition("@")[2] for r in subs if r.overturned]
                strokes = [r.base_disp_max_m for r in subs
                           if outcome(r) == SURVIVES and math.isfinite(r.base_disp_max_m)]
                rows.append(replace(worst, record=x.label, source=x.source,
                                    azimuth_deg=worst.azimuth_deg if one else math.nan,
                                    overturning_azimuths=" ".join(over) if over else "none",
                                    azimuths_run=len(subs),
                                    base_disp_max_surviving_azimuths_m=max(strokes, default=math.nan)))
    return Assessment(result.columns, list(excitations), result.configurations, rows, result.unavailable,
                      result.margin, result.timings, result.neighbourhood, result.solver)
