"""``--azimuth worst``: every orientation of the rocking plane, and the most adverse one.

A pair of horizontal components (an :class:`~rockcli.assess.scenes.Excitation` with ``pair``) is
projected onto the azimuths 0 <= theta < 180 deg (:func:`expand`: one excitation per azimuth, run like
any other, margins included, on all cores); :func:`collapse` keeps, per column x pair x configuration,
the row of the most adverse orientation, with its azimuth (``azimuth_deg``) and the orientations that
overturn at 1x (``overturning_azimuths``). theta and theta + 180 deg are the same motion reversed, which
a symmetric block answers with the mirrored response, so half a turn covers every orientation.
``resolve_excitations(..., azimuth="worst")`` marks each pair with its orientations (``Excitation.azimuths``),
and :func:`rockcli.assess.run_assessment` expands, runs and collapses them: one path for ``assess column
--azimuth worst`` and for Python. A kept row's own motion is :func:`row_excitation` (the pair's ``motion`` is
its 0 deg projection only): the report's figures and provenance, the reruns of ``history_runs`` and
``check_tolerance`` use it.

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

**The search shared by the orientations** (``run_assessment(orientations=...)``, issue 33): every
orientation runs at 1x (its verdict, peak, overturn time and stroke; ``overturning_azimuths``), but the
margins of one column x pair x configuration are searched together
(``find_overturn_scales(groups=...)``), from each orientation's own lift-off floor (its projection's peak
on a rigid base, one exact linear run of the base on linear bearings), in increasing order of the factor
across the orientations, up to the first grid factor ``J`` at which any of them overturns; only the
orientations that first overturn at ``J`` are bisected, and the neighbourhood (``--neighbourhood``) runs
for the row kept only. Theorem: the row :func:`collapse` keeps is identical, field for field, to the one
it keeps after every orientation's full search. Proof. Assumptions: a run's result depends on its scene
and factor only (not on the batch it runs in; the kernels are deterministic); below its lift-off floor a
scene provably does not overturn (:mod:`rockcli.assess.liftoff`); a scene the solver refuses is refused at
every factor (its checks are of the block, the foundation and the excitation, not the scale). Let
``f_k`` be orientation ``k``'s first overturning grid factor in its full search (none: it never
overturns up to 4x, or is refused), and ``J = min_k f_k``. (1) The shared scan runs every factor of
every orientation from its floor up to ``J``, so ``J`` is found, and so is every ``k`` with ``f_k = J``;
those get the full search's ``(overturn_scale, overturn_scale_survives, margin_note)`` exactly: the same
runs up to ``J``, the same bisection runs, the same count of runs unproven at the horizon. (2) Every other
orientation is refused (margin NaN in both searches) or survives every factor up to ``J``: then its
full-search margin is above ``grid[J]`` (the bisection
of a first overturning factor ``f`` ends in ``(grid[f - 1], grid[f]]``), or NaN; the bisected margins
of the ``f_k = J`` orientations are at most ``grid[J]``. So in the full search every other orientation's
:func:`adverse_key` is strictly larger than the kept one's, and in the shared search it is too (its
margin is NaN, ranked last, with :data:`~rockcli.assess.margin.NOTE_ABOVE_GROUP`). :func:`most_adverse`
therefore picks the same orientation (the smallest key; among equal keys, all of them among the
``f_k = J`` ones, the first), and "all keys equal" holds in both or in neither (with more than one
orientation and one left out, in neither). (3) Without any ``J`` (nothing overturns up to 4x) nothing
is left out: every orientation has its full search. (4) The 1x fields, the failed runs,
``overturning_azimuths`` and the stroke over the surviving orientations (below) come from the 1x runs,
made for every orientation. The kept row's
neighbourhood share is its own run of 0.90x..1.10x. ``tests/test_azimuth_search.py`` checks the theorem
against the unshared search on random pairs of every foundation; ``benchmarks/bench_azimuth.py`` on the
catalogue's pairs.

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


def expand(excitations: Sequence, azimuths=None) -> tuple[list, dict]:
    """The excitations with every pair replaced by its projections onto ``azimuths`` (None: each pair's own
    ``Excitation.azimuths``; a pair without them, or an excitation that is no pair, is kept as it is); and,
    per pair label, the labels of its projections in azimuth order."""
    out, groups = [], {}
    for x in excitations:
        thetas = x.azimuths if azimuths is None else azimuths
        if x.pair is None or x.motion is None or not len(thetas):
            out.append(x)
            continue
        subs = [projection(x, theta) for theta in thetas]
        out += subs
        groups[x.label] = [sub.label for sub in subs]
    return out, groups


def projection(x, theta: float):
    """The pair ``x`` (an :class:`~rockcli.assess.scenes.Excitation` with ``pair``) projected onto ``theta``
    [deg]: one excitation labelled ``LABEL@THETA``, run like any other (the pair's vertical component, if
    attached, goes with it)."""
    from rockcli.records.orientation import project
    from rockcli.solve import attached_vertical, vertical_label, with_vertical

    rec = project(*x.pair, float(theta))
    if attached_vertical(x.motion) is not None:  # the pair's vertical component goes with every projection
        rec = with_vertical(rec, attached_vertical(x.motion), vertical_label(x.motion))
    return replace(x, label=f"{x.label}@{float(theta):g}", motion=rec, pga_g=rec.pga_g, azimuth_deg=float(theta),
                   azimuths=())


def row_excitation(x, row):
    """The excitation that ``row`` (a row of :func:`collapse`, of the excitation ``x``) ran: for a pair run in
    every orientation (``x.azimuths``), its projection onto the row's azimuth, or onto the first orientation
    when none is more adverse than another (``azimuth_deg`` NaN: the row is that one's, see :func:`collapse`);
    else ``x`` itself. The figures, the reruns and the provenance of a row use it, so that they show the run
    the row reports (``x.motion`` of such a pair is its projection onto 0 deg only)."""
    if not getattr(x, "azimuths", ()) or x.pair is None or x.motion is None:
        return x
    theta = row.azimuth_deg if math.isfinite(row.azimuth_deg) else x.azimuths[0]
    return projection(x, theta)


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
