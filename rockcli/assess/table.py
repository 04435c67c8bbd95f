"""``rockcli assess column``: the Table-III-like matrix of verdicts, with the margin of each scene.

:func:`run_assessment` runs every scene column x excitation x configuration verdict-only through
:func:`rockcli.solve.simulate_many` (all cores), optionally finds each scene's overturning scale
(:mod:`rockcli.assess.margin`) and the neighbourhood share, and returns plain
:class:`AssessmentRow` objects; :mod:`rockcli.report.tables` turns them into text and CSV.
"""

from __future__ import annotations

import functools
import math
import re
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from rockcli.conditioning import ULP_DRAWS, ill_conditioned, ulp_perturbed, widest
from rockcli.errors import RockcliInputError
from rockcli.models import Block, LinearIsolation
from rockcli.assess.margin import (MARGIN_GRID, NEIGHBOURHOOD, _scaled_job, map_chunks, overturn_scales_chunked,
                                   overturn_shares)
from rockcli.assess.scenes import EXCITATION_PULSE, Configuration, Excitation, Unavailable


# --------------------------------------------------------------------------------------------------
# runs
# --------------------------------------------------------------------------------------------------

@dataclass
class AssessmentRow:
    """One scene: column x excitation x configuration (SI/g/deg as the names say)."""

    column: str
    R_m: float
    alpha_deg: float
    height_m: float
    width_m: float
    record: str
    excitation: str
    source: str
    pga_g: float
    a_p_g: float
    T_p_s: float
    isolation: str
    configuration: str
    Tb_s: float
    xi: float
    mu: float
    gamma: float
    verdict: str = ""
    overturned: bool | None = None
    #: the verdict is proven (it overturned, or the run ended by a theorem before the solver's horizon);
    #: False: still moving at the horizon, counted neither as survived nor as overturned
    proven: bool | None = None
    theta_max_over_alpha: float = math.nan
    t_overturn_s: float = math.nan
    t_uplift_s: float = math.nan
    n_impacts: int | None = None
    base_disp_max_m: float = math.nan
    overturn_scale: float = math.nan
    overturn_scale_survives: float = math.nan
    margin_note: str = ""
    overturn_share_pm10: float = math.nan
    error: str = ""
    #: the azimuth of the rocking plane's normal [deg from north] when two components were projected onto it
    #: (``--azimuth``; with ``worst``, the most adverse orientation, see :mod:`rockcli.assess.azimuth`)
    azimuth_deg: float = math.nan
    #: ``--azimuth worst``: the orientations [deg] that overturn at 1x (``none``), of ``azimuths_run`` run
    overturning_azimuths: str = ""
    azimuths_run: int | None = None
    #: ``--azimuth worst``: the largest ``base_disp_max_m`` over the orientations run in which the body survives
    #: (NaN: it survives in none), the stroke the bearings must allow whatever the body's orientation;
    #: ``base_disp_max_m`` stays the most adverse orientation's, like every other field of the row
    base_disp_max_surviving_azimuths_m: float = math.nan
    #: a body on a free plinth (``--on``): the plinth (``NAME:height=..,width=..,mass_ratio=..``), which block
    #: toppled (``body``, ``plinth`` or ""), the plinth's peak rotation over the assembly's slenderness alpha_asm,
    #: the peak friction demands |T|/N at the base and at the joint (docs/plinth.md); theta_max_over_alpha is the
    #: body's on its plinth
    plinth: str = ""
    toppled: str = ""
    plinth_theta_max_over_alpha_asm: float = math.nan
    friction_demand_base: float = math.nan
    friction_demand_joint: float = math.nan
    #: friction as a model (``--friction``): the coefficients (``mu=0.5``, ``base=0.5,joint=0.7``), the peak and the
    #: residual slip of the body's own contact (on the floor, or on its plinth) and of the plinth on the floor [m]
    #: (0 where nothing slid: then the row is the rocking model's); verdict ``slid_off``: the body slid off its plinth
    friction: str = ""
    slide_max_m: float = math.nan
    slide_residual_m: float = math.nan
    plinth_slide_max_m: float = math.nan
    plinth_slide_residual_m: float = math.nan
    #: a column of drums (``assess column nemea-drums --friction MU``, :mod:`rockcli.assess.drums`) and the monolith
    #: run beside it: the drum column's name (on both rows) and its drums (1 on the monolith's row); where it fails
    #: (``base``: the whole column falls; ``joint k``: the drums above joint k fall, or a drum slid off there); the
    #: first contact to move and how (``joint 3 opens``) and when, and the first joint between drums to open and when;
    #: the largest opening of a joint between drums
    #: over its slenderness and the largest slip of one [m], and where; each contact's peak opening over its
    #: slenderness and each drum's residual offset from the footprint's axis [m], bottom to top, space-separated,
    #: and the largest offset; on the drums' row the drums against the monolith (``safer``, ``worse``, ``alike``:
    #: :func:`rockcli.solve.drums.compare`) with the monolith's verdict and margin; the contact law's events
    #: without a consistent pattern and its pulling pivots; ``reliable``: no such event in the run or in the runs
    #: its margin rests on
    drum_column: str = ""
    drums: int | None = None
    falls_at: str = ""
    first_move: str = ""
    first_move_t_s: float = math.nan
    first_joint_open: str = ""
    first_joint_open_t_s: float = math.nan
    joint_open_max_over_alpha: float = math.nan
    joint_open_max_at: str = ""
    joint_slide_max_m: float = math.nan
    joint_slide_max_at: str = ""
    peak_openings_over_alpha: str = ""
    residual_offsets_m: str = ""
    residual_offset_max_m: float = math.nan
    drums_vs_monolith: str = ""
    monolith_verdict: str = ""
    monolith_overturn_scale: float = math.nan
    n_inconsistent: int | None = None
    n_jumps: int | None = None
    reliable: bool | None = None


#: CSV column order (every field of :class:`AssessmentRow`).
ROW_FIELDS = tuple(AssessmentRow.__dataclass_fields__)


@dataclass
class Assessment:
    """What :func:`run_assessment` returns: the inputs, the rows and what could not be run."""

    columns: list
    excitations: list
    configurations: list
    rows: list
    unavailable: list = field(default_factory=list)
    margin: bool = True
    timings: dict = field(default_factory=dict)
    neighbourhood: bool = False
    #: the solver options the scenes ran with (``horizon``, ``rtol``, ...), for the reruns
    solver: dict = field(default_factory=dict)

    def to_dataframe(self):
        """The rows as a pandas DataFrame, the columns of the CSV report (``assess column --csv``; docs/assess.md):
        :func:`rockcli.report.tables.assessment_table` (pandas is imported there, on first use)."""
        from rockcli.report.tables import assessment_table

        return assessment_table(self)

    @property
    def unproven(self) -> list:
        """Rows whose run reached the solver's horizon with the verdict unproven."""
        return [r for r in self.rows if r.proven is False]

    def row(self, column: str, record: str, configuration: str) -> AssessmentRow:
        """The row of one scene (by column name, record label, configuration header)."""
        index = self.__dict__.get("_index")
        if index is None or len(index) != len(self.rows):
            index = self.__dict__["_index"] = {(r.column, r.record, r.configuration): r for r in self.rows}
        return index[(column, record, configuration)]

    def excitation_of(self, row: AssessmentRow) -> Excitation:
        """The excitation ``row`` ran: its record's, or for a pair run in every orientation (``azimuth="worst"``)
        the projection onto the row's azimuth (:func:`rockcli.assess.azimuth.row_excitation`), labelled
        ``LABEL@AZIMUTH``. What a figure, a rerun or a provenance of the row must use."""
        from rockcli.assess.azimuth import row_excitation

        return row_excitation(next(x for x in self.excitations if x.label == row.record), row)

    @property
    def idealised(self) -> list:
        return [x.label for x in self.excitations if x.kind == EXCITATION_PULSE]

    @property
    def failed(self) -> list:
        return [x for x in self.excitations if x.error]


def _nan(v):
    return math.nan if v is None else float(v)


def _base_row(block: Block, x: Excitation, conf: Configuration) -> AssessmentRow:
    f = conf.foundation
    return AssessmentRow(
        column=block.name, R_m=block.R, alpha_deg=block.alpha_deg, height_m=block.height, width_m=block.width,
        record=x.label, excitation=x.kind, source=x.source, pga_g=x.pga_g, a_p_g=x.a_p_g, T_p_s=x.T_p_s,
        isolation=conf.label, configuration=conf.header, Tb_s=_nan(getattr(f, "T_b", None)),
        xi=_nan(getattr(f, "xi", None)), mu=_nan(getattr(f, "mu", None)), gamma=float(getattr(f, "gamma", 0.0)),
        error=x.error, azimuth_deg=x.azimuth_deg, plinth=_plinth_label(block),
        friction=getattr(block, "friction_label", ""))


def _plinth_label(block) -> str:
    """The plinth of a body on a plinth as a spec that gives the same plinth when rerun (``--on LABEL``):
    ``plinth:height=1,width=0.6,mass_ratio=0.6703910614525139`` (every number as the shortest text that reads back
    as the same double, :func:`rockcli.io.inputs.format_number`; the mass ratio as run, also when it came from the
    density); "" for a single block."""
    from rockcli.io.inputs import format_number as num

    plinth = getattr(block, "plinth", None)
    if plinth is None:
        return ""
    return f"{plinth.name}:height={num(plinth.height)},width={num(plinth.width)},mass_ratio={num(block.m2)}"


def _plinth_fields(row: AssessmentRow, r) -> None:
    """A body on a plinth's own results (``r`` a :class:`rockcli.solve.stack_many.StackRun`)."""
    st = r.stack
    row.toppled = st.toppled or ""
    row.plinth_theta_max_over_alpha_asm = st.plinth.theta_max / st.alpha_asm
    row.friction_demand_base = st.friction_base
    row.friction_demand_joint = st.friction_joint


def _slide_fields(row: AssessmentRow, r) -> None:
    """A friction run's own results (``r`` a :class:`rockcli.solve.slide_many.SlideRun`; where nothing slid the
    rocking run's fields stand, and the slips are 0)."""
    row.slide_max_m, row.slide_residual_m = r.slide_max_m, r.slide_residual_m
    row.plinth_slide_max_m, row.plinth_slide_residual_m = r.plinth_slide_max_m, r.plinth_slide_residual_m
    st = r.slide
    if r.slid and st.joint is not None:  # a body on its plinth that slid: the plinth's answer from the friction run
        row.toppled = st.toppled or ""
        row.plinth_theta_max_over_alpha_asm = st.base.psi_max / st.base.alpha
        row.friction_demand_base = row.friction_demand_joint = math.nan


def run_assessment(columns: Sequence[Block], excitations: Sequence[Excitation],
                   configurations: Sequence[Configuration], *, margin: bool = True, neighbourhood: bool = False,
                   unavailable: Sequence[Unavailable] = (), progress=None, orientations: dict | None = None,
                   runner=None, chunks: int | None = None, **solver) -> Assessment:
    """Run every scene column x excitation x configuration (verdict only, all cores).

    Parameters
    ----------
    columns, excitations, configurations
        From :func:`parse_column_spec`, :func:`resolve_excitations`, :func:`parse_configurations`.
    margin : bool
        Also find ``overturn_scale`` for every scene (see the module notes).
    neighbourhood : bool
        Also run 0.90x..1.10x of every record and store the share that overturns
        (``overturn_share_pm10``, see :func:`overturn_shares`).
    progress : callable, optional
        ``progress(n)`` after each chunk of ``n`` steps: runs, and in the margin search (scene, factor)
        pairs settled (:func:`find_overturn_scales`); :func:`count_runs` gives the total. Each part
        (verdicts, margin search, neighbourhood) is announced with :func:`rockcli.progress.phase`
        (local runs only: a ``runner`` reports its own, see :func:`rockcli.assess.cluster.run_on_dask`).
    orientations : dict, optional
        The projections of each pair (:func:`rockcli.assess.azimuth.expand`), for ``excitations`` expanded
        already. The orientations of one column, pair and configuration are searched together, only as far
        as the most adverse one needs, and the neighbourhood runs for that one only
        (:mod:`rockcli.assess.azimuth`): the other orientations' rows are complete at 1x only;
        :func:`rockcli.assess.azimuth.collapse` the result. Without it, the pairs of
        ``resolve_excitations(..., azimuth="worst")`` (``Excitation.azimuths``) are expanded, run so and
        collapsed here: one row per column x pair x configuration, the most adverse orientation's, with its
        ``azimuth_deg`` (``assess column --azimuth worst``).
    runner, chunks
        Where the runs go: :func:`rockcli.assess.margin.map_chunks` (default: here, one chunk of
        everything), in ``chunks`` chunks per part. The verdicts and the neighbourhood map over scenes,
        the margin search over its groups (:func:`rockcli.assess.margin.overturn_scales_chunked`); every
        scene's result is the same wherever it runs.
    **solver
        Passed to :func:`rockcli.solve.simulate_many` (``rtol``, ``tail``, ...).

    Returns
    -------
    Assessment
        Rows in the order column, excitation, configuration. Excitations that could not be read
        give rows with ``error`` set and no results.
    """
    import time

    from rockcli.assess.scenes import check_count, check_flag, check_scenes

    columns, excitations, configurations = check_scenes(columns, excitations, configurations)
    margin, neighbourhood = check_flag(margin, "margin"), check_flag(neighbourhood, "neighbourhood")
    chunks = check_count(chunks, "chunks", "None (one chunk of everything) or a whole number of chunks >= 1")
    if not columns:
        raise RockcliInputError("no body to assess: name a preset (bassae, nemea) or give a body of your own")
    if not configurations:
        raise RockcliInputError("no isolation configuration to assess")
    swept = next((x for x in excitations if x.azimuths), None)
    if swept is not None and orientations is not None:  # its motion is its 0 deg projection only
        raise RockcliInputError(f"excitations: {swept.label} is a pair to run in every orientation (azimuth='worst') "
                                f"and orientations= is given: pass the pairs without orientations=, or expand them "
                                f"with rockcli.assess.azimuth.expand first")
    if swept is not None:  # azimuth="worst": every orientation, the most adverse kept (the CLI's path)
        from rockcli.assess.azimuth import collapse, expand

        expanded, groups = expand(excitations)
        result = run_assessment(columns, expanded, configurations, margin=margin, neighbourhood=neighbourhood,
                                unavailable=unavailable, progress=progress, orientations=groups, runner=runner,
                                chunks=chunks, **solver)
        return collapse(result, excitations, groups)
    timings = {}
    rows, scenes, run_rows = [], [], []
    from rockcli.assess.drums import drum_fields, drum_roles, drum_row, pair_drum_rows

    roles = drum_roles(columns)  # columns of drums and the monoliths beside them
    for b in columns:
        for x in excitations:
            for c in configurations:
                row = _base_row(b, x, c)
                if b.name in roles:  # a column of drums or its monolith, also on a row that could not run
                    drum_row(row, b, roles[b.name])
                rows.append(row)
                if x.motion is not None:
                    scenes.append((b, c.foundation, x.motion))
                    run_rows.append(row)
    t0 = time.perf_counter()
    chunk_progress = None
    if progress is not None:
        chunk_progress = _Advance(progress)
    from rockcli.progress import phase
    from rockcli.solve import VERDICT_ERROR, JobError, simulate_many

    here = runner is None
    if here:
        if margin and any(isinstance(s[1], LinearIsolation) and hasattr(s[2], "acc") for s in scenes):
            from rockcli.assess.liftoff import load_floor_kernel
            from rockcli.solve.pool import in_background

            in_background(load_floor_kernel)  # the search's first step needs it: loaded while the verdicts run
        phase(progress, "verdicts", len(scenes), unit="runs")
        responses = simulate_many([_scaled_job(*s, 1.0) for s in scenes], progress=chunk_progress, **solver)
    else:
        responses = map_chunks(functools.partial(simulate_many, **solver), [_scaled_job(*s, 1.0) for s in scenes],
                               chunk_size=_size(len(scenes), chunks), runner=runner)
    # a run stopped by the step cap is a numerical failure, not a result: an error row like a refused job
    responses = [JobError(r.message) if r.verdict != VERDICT_ERROR and r.status < 0 else r for r in responses]
    timings["runs_s"] = time.perf_counter() - t0
    for row, r in zip(run_rows, responses):
        if r.verdict == VERDICT_ERROR:  # the solver refused this scene; the others ran
            row.error = r.error
            continue
        row.verdict = r.verdict
        row.overturned = r.overturned
        row.proven = bool(r.overturned or r.settled)
        row.theta_max_over_alpha = r.theta_max_over_alpha
        row.t_overturn_s = r.t_overturn_s
        row.t_uplift_s = r.t_uplift_s
        row.n_impacts = r.n_impacts
        row.base_disp_max_m = r.base_disp_max_m
        if hasattr(r, "stack"):
            _plinth_fields(row, r)
        if hasattr(r, "slide"):
            _slide_fields(row, r)
        if row.column in roles:
            drum_fields(row, r, roles[row.column])
    ok = [i for i, r in enumerate(responses) if r.verdict != VERDICT_ERROR]
    groups = _orientation_groups(run_rows, orientations)
    if margin:
        t0 = time.perf_counter()
        kw = dict(solver)
        if here:  # (scene, factor) pairs, factor 1 known: how far each search goes is what it finds out (no ETA)
            phase(progress, "margin search", len(ok) * (MARGIN_GRID.size - 1), known=False)
            kw["progress"] = progress
        n_items = len(ok) if groups is None else len({groups[i] for i in ok})
        found = overturn_scales_chunked([scenes[i] for i in ok], known=[responses[i] for i in ok],
                                        groups=None if groups is None else [groups[i] for i in ok],
                                        chunk_size=_size(n_items, chunks), runner=runner, **kw)
        for i, (hi, lo, note) in zip(ok, found):
            run_rows[i].overturn_scale, run_rows[i].overturn_scale_survives, run_rows[i].margin_note = hi, lo, note
        timings["margin_s"] = time.perf_counter() - t0
    if neighbourhood:
        t0 = time.perf_counter()
        if groups is not None:  # the orientation each scene reports: the most adverse one's share only
            ok = _most_adverse(ok, run_rows, groups, margin)
        if here:
            phase(progress, "neighbourhood", len(ok) * NEIGHBOURHOOD.size, unit="runs")
            shares = overturn_shares([scenes[i] for i in ok], progress=_Advance(progress) if progress else None,
                                     **solver)
        else:
            shares = map_chunks(functools.partial(overturn_shares, **solver), [scenes[i] for i in ok],
                                chunk_size=_size(len(ok), chunks), runner=runner)
        for i, share in zip(ok, shares):
            run_rows[i].overturn_share_pm10 = share
        timings["neighbourhood_s"] = time.perf_counter() - t0
    pair_drum_rows(rows, roles, margin)
    return Assessment(list(columns), list(excitations), list(configurations), rows, list(unavailable), margin,
                      timings, neighbourhood, dict(solver))


def _size(items: int, chunks: int | None) -> int | None:
    """Items per chunk for about ``chunks`` chunks (None: one chunk)."""
    return None if not chunks else max(1, -(-items // int(chunks)))


def _orientation_groups(run_rows, orientations) -> list | None:
    """Per scene run, its group of the margin search: ``(column, pair, configuration)`` for a projection of a
    pair of ``orientations``, the scene itself otherwise (None without ``orientations``)."""
    if orientations is None:
        return None
    pair_of = {label: pair for pair, labels in orientations.items() for label in labels}
    return [(r.column, pair_of[r.record], r.configuration) if r.record in pair_of else k
            for k, r in enumerate(run_rows)]


def _most_adverse(ok, run_rows, groups, margin: bool) -> list:
    """The scenes of ``ok`` that :func:`rockcli.assess.azimuth.collapse` reports: in each group, the row
    :func:`rockcli.assess.azimuth.worst_row` keeps (a scene alone: itself; a group with a failed run reports
    that run, which is not in ``ok``)."""
    from rockcli.assess.azimuth import worst_row

    members = {}
    for i, g in enumerate(groups):
        members.setdefault(g, []).append(i)
    keep = set()
    for idx in members.values():
        row, _ = worst_row([run_rows[i] for i in idx], margin)
        keep.add(next(i for i in idx if run_rows[i] is row))
    return [i for i in ok if i in keep]


class _Advance:
    """Adapts simulate_many's cumulative ``progress(n_done)`` to increments ``progress(n)``."""

    def __init__(self, progress):
        self.progress, self.done = progress, 0

    def __call__(self, n_done):
        self.progress(n_done - self.done)
        self.done = n_done


def count_runs(columns, excitations, configurations, margin: bool, neighbourhood: bool = False) -> int:
    """Runs for the progress bar: the scenes (a pair of ``azimuth="worst"``: one per orientation), plus the
    margin grid (an upper bound) and the neighbourhood."""
    n = len(columns) * sum(max(1, len(x.azimuths)) for x in excitations if x.motion is not None) * len(configurations)
    return n * (1 + (MARGIN_GRID.size - 1 if margin else 0) + (NEIGHBOURHOOD.size if neighbourhood else 0))


def history_runs(assessment: Assessment, **solver):
    """Full-history runs of every scene that ran, serially: yields (row, block, configuration, excitation, response)."""
    from rockcli.solve import simulate

    blocks = {b.name: b for b in assessment.columns}
    confs = {c.header: c for c in assessment.configurations}
    xs = {x.label: x for x in assessment.excitations}
    for row in assessment.rows:
        x = xs[row.record]
        if x.motion is None or row.error:
            continue
        b, c, x = blocks[row.column], confs[row.configuration], assessment.excitation_of(row)  # a pair: its azimuth
        yield row, b, c, x, simulate(b, c.foundation, x.motion, history=True, **{**assessment.solver, **solver})


def safe_name(*parts: str) -> str:
    """A file-name stem from parts (``bassae_kobe-1995-takarazuka-000_Tb=2s`` -> safe characters only)."""
    text = "_".join(str(p) for p in parts)
    return re.sub(r"[^A-Za-z0-9.=+-]+", "_", text).strip("_")[:150] or "run"


@dataclass(frozen=True)
class ToleranceCheck:
    """Outcome of :func:`check_tolerance`: every scene rerun at ``rtol`` (``factor`` times tighter).

    ``changed`` holds ``(row, verdict at the tight rtol)`` for each scene whose verdict differs;
    ``max_peak_change`` is the largest change of theta_max/alpha among scenes that survive at both.

    Conditioning (:mod:`rockcli.conditioning`): every scene is also rerun, at its own rtol, on
    ``ulp_draws`` copies of its motion moved by one ulp. ``ill`` holds ``(row, verdicts, peak change)``
    for each scene whose verdict changes on one of them (peak change NaN) or whose survivor's peak
    moves by more than ``ILL_PEAK``: its answer is not determined by its input at double precision.
    ``max_ulp_peak_change`` is the largest change of a survivor's peak there.
    """

    rtol: float
    base_rtol: float
    n_runs: int
    changed: list
    max_peak_change: float
    #: every base rtol used (each foundation's default when none was given), loosest first
    base_rtols: tuple = ()
    ulp_draws: int = 0
    ill: list = field(default_factory=list)
    max_ulp_peak_change: float = 0.0
    #: per checked row: ``(row, verdict at the tight rtol, its peak change, verdicts on the one-ulp
    #: motions, their largest peak change)``; a peak change is NaN where a verdict changed (and 0 for
    #: an overturned scene, whose peak is not compared)
    per_row: list = field(default_factory=list)


def _peak_change(row: AssessmentRow, r) -> float:
    """How far rerun ``r`` moved from ``row``: NaN when the verdict differs, the change of a
    survivor's peak theta_max/alpha, 0 otherwise (an overturn's or a no-uplift's peak is not compared)."""
    if r.verdict != row.verdict:
        return math.nan
    return abs(r.theta_max_over_alpha - row.theta_max_over_alpha) if r.verdict == "rocked" else 0.0


def check_tolerance(assessment: Assessment, *, factor: float = 100.0, base_rtol: float | None = None,
                    ulp_draws: int = ULP_DRAWS, seed: int = 1980) -> ToleranceCheck:
    """Rerun every scene of ``assessment`` that ran at a ``factor`` times tighter rtol (verdict
    only, all cores) and report the verdicts that change (they were decided by the numerics); then
    at its own rtol on ``ulp_draws`` motions moved by one ulp (``seed``), and report the scenes
    whose answer changes there (ill-conditioned; see :class:`ToleranceCheck`).
    ``base_rtol`` None: each foundation's default (:func:`rockcli.solve.default_rtol`)."""
    from rockcli.solve import DEFAULT_RTOL, default_rtol, simulate_many

    blocks = {b.name: b for b in assessment.columns}
    confs = {c.header: c for c in assessment.configurations}
    xs = {x.label: x for x in assessment.excitations}
    rows = [r for r in assessment.rows if not r.error and r.verdict and xs[r.record].motion is not None]
    ran = [assessment.excitation_of(r) for r in rows]  # a pair of azimuth="worst": the row's orientation
    motions = {}  # each motion run, in the order of the excitations (the one-ulp copies are drawn in this order)
    for x in assessment.excitations:
        if x.motion is not None:
            motions.update({y.label: y.motion for y in ran if y.label.rpartition("@")[0] == x.label}
                           if x.azimuths else {x.label: x.motion})
    jobs = [(blocks[r.column], confs[r.configuration].foundation, x.motion) for r, x in zip(rows, ran)]
    bases = [default_rtol(j[1]) if base_rtol is None else float(base_rtol) for j in jobs]
    other = {k: v for k, v in assessment.solver.items() if k != "rtol"}

    def sweep(job_list, scale):  # one sweep per base tolerance, in the order of job_list
        out = [None] * len(job_list)
        for base in sorted(set(bases)):
            idx = [i for i, b in enumerate(bases) if b == base]
            for i, r in zip(idx, simulate_many([job_list[i] for i in idx], rtol=base * scale, **other)):
                out[i] = r
        return out

    changed, peak = [], 0.0
    tight = sweep(jobs, 1.0 / factor)
    tight_moved = []
    for row, r in zip(rows, tight):
        d = _peak_change(row, r)
        if r.verdict != row.verdict:
            changed.append((row, r.verdict))
        else:
            peak = max(peak, d)
        tight_moved.append(d)
    # conditioning: the same scenes on motions moved by one ulp (one copy per motion and draw)
    rng = np.random.default_rng(seed)
    verdicts = [[] for _ in rows]
    moved = [0.0] * len(rows)
    for _ in range(ulp_draws):
        copies = {label: ulp_perturbed(m, rng) for label, m in motions.items()}
        for i, r in enumerate(sweep([(b, f, copies[x.label]) for (b, f, _), x in zip(jobs, ran)], 1.0)):
            verdicts[i].append(r.verdict)
            moved[i] = widest(moved[i], _peak_change(rows[i], r))
    ill = [(row, tuple(v), d) for row, v, d in zip(rows, verdicts, moved) if ill_conditioned(row.verdict, d, v)]
    ulp_peak = max((d for d in moved if not math.isnan(d)), default=0.0)
    base = max(bases) if bases else (DEFAULT_RTOL if base_rtol is None else float(base_rtol))
    per_row = [(row, r.verdict, dt, tuple(v), d) for row, r, dt, v, d in zip(rows, tight, tight_moved, verdicts, moved)]
    return ToleranceCheck(base / factor, base, len(rows), changed, peak, tuple(sorted(set(bases), reverse=True)),
                          ulp_draws, ill, ulp_peak, per_row)
