"""``assess column --azimuth worst``: every orientation of the rocking plane, and the most adverse one.

A pair of horizontal components (an :class:`~rockcli.assess.scenes.Excitation` with ``pair``) is
projected onto the azimuths 0 <= theta < 180 deg (:func:`expand`: one excitation per azimuth, run like
any other, margins included, on all cores); :func:`collapse` keeps, per column x pair x configuration,
the row of the most adverse orientation -- the smallest overturning scale (margin), then an overturn at
1x, then the largest peak |theta|/alpha -- with its azimuth (``azimuth_deg``) and the orientations that
overturn at 1x (``overturning_azimuths``). theta and theta + 180 deg are the same motion reversed, which
a symmetric block answers with the mirrored response, so half a turn covers every orientation.
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


def _badness(row, margin: bool):
    """Sort key: smaller is more adverse."""
    scale = row.overturn_scale if margin and not math.isnan(row.overturn_scale) else math.inf
    over = 0 if row.overturned else 1
    t = row.t_overturn_s if row.overturned else math.inf
    peak = row.theta_max_over_alpha if not math.isnan(row.theta_max_over_alpha) else -math.inf
    return (scale, over, t, -peak) if margin else (over, t, -peak)


def worst_row(rows: Sequence, margin: bool):
    """The most adverse of one scene's rows over orientations (an error row if any run failed)."""
    failed = [r for r in rows if r.error]
    if failed:
        return failed[0]
    return min(rows, key=lambda r: _badness(r, margin))


def collapse(result, excitations: Sequence, groups: dict):
    """The assessment of the original ``excitations``: one row per column x pair x configuration, the worst
    orientation's, with ``azimuth_deg`` and ``overturning_azimuths`` set."""
    from rockcli.assess.table import Assessment

    rows = []
    for b in result.columns:
        for x in excitations:
            for c in result.configurations:
                if x.label not in groups:
                    rows.append(result.row(b.name, x.label, c.header))
                    continue
                subs = [result.row(b.name, label, c.header) for label in groups[x.label]]
                worst = worst_row(subs, result.margin)
                over = [r.record.rpartition("@")[2] for r in subs if r.overturned]
                rows.append(replace(worst, record=x.label, source=x.source,
                                    overturning_azimuths=" ".join(over) if over else "none",
                                    azimuths_run=len(subs)))
    return Assessment(result.columns, list(excitations), result.configurations, rows, result.unavailable,
                      result.margin, result.timings, result.neighbourhood, result.solver)
