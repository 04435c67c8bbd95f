"""Fragility of overturning: P(the column overturns | IM = x) from a suite of records.

Method
------
For each column, configuration and record, the record's **overturning capacity** is the smallest
scale factor that overturns the column (the margin search of :mod:`rockcli.assess.margin`: a scan
of 373 log-spaced factors 0.1..4 in steps just under 1 %, the first overturning one and the one below
it bracketing the capacity to 1 %)
times the record's intensity measure (IM): the IM at which that record, scaled, first topples the
column. This is incremental dynamic analysis (IDA) reduced to its collapse point ("IDA-like").
The capacities of the records are taken as a sample of a lognormal variable, and the fragility is
its distribution function

    P(overturn | IM = x) = Phi( ln(x / theta) / beta )

with median ``theta`` and dispersion ``beta`` fitted by **maximum likelihood** (Baker 2015,
*Earthquake Spectra* 31(1):579-599, the IDA case). A record that does not overturn the column up
to the largest factor scanned (4x) is **right-censored**: its capacity is only known to exceed
4 x IM, and it enters the likelihood as ``1 - Phi(ln(4 IM / theta) / beta)`` instead of a density
(the censored-normal / Tobit likelihood in ``ln IM``). A record that overturns it already at the
smallest factor (0.1x) is left-censored (``Phi(ln(0.1 IM / theta) / beta)``). Without censoring the
MLE is closed-form: ``ln theta`` = mean of ``ln c``, ``beta`` = their standard deviation with
divisor n (not n - 1: the MLE is biased low by ``sqrt((n - 1)/n)``, 5 % for n = 10).

The likelihood is maximised by Newton's method in Olsen's (1978) parameters ``(mu/beta, 1/beta)``,
in which the censored-normal log-likelihood is concave, so the maximum found is the global one; it
exists when at least two records have different exact capacities.

Confidence: a bootstrap over records (resample the records with replacement, refit; percentile
intervals), with a fixed seed so that runs repeat. The same resamples serve every column and
configuration (a paired bootstrap), so the ratio of the isolated to the non-isolated median has
its own interval: "does isolation help" is a statement about that ratio.

Intensity measures (:data:`IMS`)
--------------------------------
``pga`` peak |acceleration| [g]; ``pgv`` peak |velocity| [m/s] of the record integrated by the
trapezoid rule from rest, as given (no baseline correction; the ``PGV`` of ``rockcli records
show``); ``ap`` the |a_p| [g] of the record's fitted Ricker pulse (:func:`rockcli.pulses_fit.fit_pulse`,
default settings, the catalogue's ``a_p_g``). All scale with the record, so capacity = factor x IM.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field
from typing import Callable, Sequence

import numpy as np

from rockcli.assess.margin import MARGIN_GRID, MARGIN_RTOL, NOTE_NO_OVERTURN, NOTE_OVERTURNS_AT_MIN, \
    overturn_scales_chunked
from rockcli.assess.lognormal import (CENSORED_LEFT, CENSORED_RIGHT, DEFAULT_N_BOOT, DEFAULT_SEED,  # noqa: F401
                                     _censor_codes, _tobit_mle, bootstrap_lognormal, fit_lognormal,
                                     fragility_probability)
from rockcli.assess.scenes import Configuration, Excitation, Unavailable
from rockcli.errors import RockcliInputError
from rockcli.models import Block
from rockcli.io.units import G

#: Two-sided confidence level of the intervals.
DEFAULT_LEVEL = 0.90


@dataclass(frozen=True)
class IntensityMeasure:
    """An intensity measure: its key, how it is printed, its units and its column name."""

    key: str
    name: str
    units: str
    column: str
    description: str

    @property
    def suffix(self) -> str:
        """Unit suffix of column names: ``g`` or ``mps``."""
        return self.column.rsplit("_", 1)[-1]


IMS = {
    "pga": IntensityMeasure("pga", "PGA", "g", "pga_g", "peak ground acceleration [g]"),
    "pgv": IntensityMeasure("pgv", "PGV", "m/s", "pgv_mps",
                            "peak ground velocity [m/s], trapezoid rule from rest, no baseline correction"),
    "ap": IntensityMeasure("ap", "a_p", "g", "a_p_g", "amplitude |a_p| of the fitted Ricker pulse [g]"),
}


def intensity_measure(motion, im: str) -> float:
    """The intensity measure ``im`` (a key of :data:`IMS`) of a record or pulse, in its units (g or m/s).

    Raises
    ------
    RockcliInputError
        Unknown ``im``; a record whose pulse cannot be fitted (``ap``).
    """
    if im not in IMS:
        raise RockcliInputError(f"intensity measure {im!r} is not one of {', '.join(IMS)}")
    if hasattr(motion, "acc"):
        if im == "pga":
            return float(np.max(np.abs(motion.acc))) / G
        if im == "pgv":
            from rockcli.records.motion import cumtrapz

            return float(np.max(np.abs(cumtrapz(motion.acc, motion.dt))))
        from rockcli.pulses_fit import fit_pulse

        return abs(fit_pulse(motion).a_p_g)
    # an analytic pulse: a_p is its peak acceleration; its velocity is exact
    if im in ("pga", "ap"):
        return abs(float(motion.a_p)) / G
    t0, t1 = motion.support()
    t = np.linspace(t0, t1, 4001)
    return float(np.max(np.abs(motion.velocity(t))))


# --------------------------------------------------------------------------------------------------
# the suite
# --------------------------------------------------------------------------------------------------

@dataclass
class FragilityRow:
    """One record for one column and configuration: its IM, overturning scale and capacity."""

    column: str
    R_m: float
    alpha_deg: float
    record: str
    source: str
    isolation: str
    configuration: str
    im_value: float = math.nan
    overturn_scale: float = math.nan
    overturn_scale_survives: float = math.nan
    capacity: float = math.nan
    censored: str = ""
    margin_note: str = ""
    error: str = ""
    azimuth_deg: float = math.nan  #: with --azimuth worst: the orientation whose capacity is kept
    orientation: str = ""  #: with --azimuth worst: "median" or "worst" (:mod:`rockcli.assess.fragility_azimuth`)


@dataclass
class FragilityCurve:
    """The fitted fragility of one column in one configuration.

    ``median`` is in the IM's units; the ``*_ci`` are (low, high) percentile intervals of the
    bootstrap at the suite's level; ``boot_median``/``boot_beta`` hold the resamples (NaN where a
    resample had no fit). ``ratio_to_rigid`` is this median over the median on a rigid foundation
    (same column), with its paired-bootstrap interval; NaN on the rigid configuration itself.
    """

    column: str
    configuration: Configuration
    n_records: int
    n_exact: int
    n_right: int
    n_left: int
    median: float
    beta: float
    median_ci: tuple = (math.nan, math.nan)
    beta_ci: tuple = (math.nan, math.nan)
    boot_median: np.ndarray = field(default=None, repr=False)
    boot_beta: np.ndarray = field(default=None, repr=False)
    n_boot_ok: int = 0
    ratio_to_rigid: float = math.nan
    ratio_ci: tuple = (math.nan, math.nan)
    note: str = ""

    def probability(self, im):
        """The fitted fragility ``P(overturn)`` at the intensities ``im`` (an array, the IM's units):
        :func:`rockcli.assess.lognormal.fragility_probability` with this curve's median and beta."""
        return fragility_probability(im, self.median, self.beta)

    def boot_probabilities(self, im):
        """``P(overturn)`` at ``im`` of every bootstrap resample that has a fit: an array, one row per resample."""
        ok = np.isfinite(self.boot_median)
        return fragility_probability(np.asarray(im)[None, :], self.boot_median[ok, None], self.boot_beta[ok, None])


@dataclass
class Fragility:
    """What :func:`run_fragility` returns."""

    columns: list
    configurations: list
    excitations: list
    im: IntensityMeasure
    rows: list
    curves: list
    n_boot: int
    seed: int
    level: float
    grid: tuple
    unavailable: list = field(default_factory=list)
    timings: dict = field(default_factory=dict)

    def curve(self, column: str, configuration: str) -> FragilityCurve:
        """The curve of a column (name) and configuration (header)."""
        for c in self.curves:
            if c.column == column and c.configuration.header == configuration:
                return c
        raise KeyError((column, configuration))

    def rows_of(self, column: str, configuration: str) -> list:
        return [r for r in self.rows if r.column == column and r.configuration == configuration]

    def plotting_points(self, column: str, configuration: str) -> tuple[list, list]:
        """``(exact, censored)``: the records' ``(capacity, probability)`` of a column (name) and configuration
        (header) at their Kaplan-Meier plotting positions (:func:`empirical_points`), the right-censored ones
        (no overturning up to the grid's top) apart, at their bound."""
        pts = empirical_points(self.rows_of(column, configuration))
        return ([(v, p) for v, p, cen in pts if cen != CENSORED_RIGHT],
                [(v, p) for v, p, cen in pts if cen == CENSORED_RIGHT])

    def to_dataframe(self):
        """The rows as a pandas DataFrame, the columns of the CSV (``assess fragility --csv``; docs/fragility.md),
        each with the fit of its column and configuration: :func:`rockcli.report.fragility.fragility_table`
        (pandas is imported there, on first use)."""
        from rockcli.report.fragility import fragility_table

        return fragility_table(self)

    @property
    def failed(self) -> list:
        """Excitations that could not be read or measured (their rows carry the error)."""
        return [x for x in self.excitations if x.error]


def count_fragility_runs(columns, excitations, configurations) -> int:
    """Upper bound of the runs (for a progress bar): every grid factor plus the bisection of each scene."""
    n = len(columns) * sum(x.motion is not None and not x.error for x in excitations) * len(configurations)
    bisection = int(math.ceil(math.log2(math.log(MARGIN_GRID[1] / MARGIN_GRID[0]) / math.log1p(MARGIN_RTOL))))
    return n * (MARGIN_GRID.size + bisection)


def _measure(excitations, im: str) -> tuple[list, dict]:
    """(excitations with the IM errors folded in, {label: IM value})."""
    from dataclasses import replace

    out, values = [], {}
    for x in excitations:
        if x.motion is None or x.error:
            out.append(x)
            continue
        try:
            v = intensity_measure(x.motion, im)
        except RockcliInputError as exc:
            out.append(replace(x, motion=None, error=f"{x.source}: {IMS[im].name} could not be measured: {exc}"))
            continue
        if not (math.isfinite(v) and v > 0):
            out.append(replace(x, motion=None, error=f"{x.source}: {IMS[im].name} is {v:g}: nothing to scale"))
            continue
        values[x.label] = v
        out.append(x)
    return out, values


def run_fragility(columns: Sequence[Block], excitations: Sequence[Excitation],
                  configurations: Sequence[Configuration], *, im: str = "pga", n_boot: int = DEFAULT_N_BOOT,
                  seed: int = DEFAULT_SEED, level: float = DEFAULT_LEVEL, unavailable: Sequence[Unavailable] = (),
                  progress: Callable[[int], None] | None = None, runner: Callable | None = None,
                  chunk_size: int | None = None, **solver) -> Fragility:
    """Overturning capacities of every record and a lognormal fragility per column x configuration.

    Parameters
    ----------
    columns, excitations, configurations
        From :func:`rockcli.assess.parse_column_spec`, :func:`rockcli.assess.resolve_excitations`,
        :func:`rockcli.assess.parse_configurations`. Excitations with an ``error`` give error rows.
    im : {"pga", "pgv", "ap"}
        Intensity measure (:data:`IMS`).
    n_boot, seed, level
        Bootstrap resamples over records, their seed, the two-sided level of the intervals.
    progress : callable, optional
        ``progress(n)`` as ``n`` more (scene, factor) pairs of the margin search are settled (local
        runner only; :func:`rockcli.assess.find_overturn_scales`), the search announced with
        :func:`rockcli.progress.phase` (a Dask run reports its own: :func:`run_fragility_distributed`).
    runner, chunk_size
        Where the margin searches run: see :func:`rockcli.assess.margin.map_chunks` (default:
        here, all scenes in one chunk).
    **solver
        Passed to :func:`rockcli.solve.simulate_many`.

    Returns
    -------
    Fragility
        Rows in the order column, excitation, configuration; curves in the order column,
        configuration.
    """
    from rockcli.assess.scenes import check_count, check_scenes

    columns, excitations, configurations = check_scenes(columns, excitations, configurations)
    if im not in IMS:
        raise RockcliInputError(f"intensity measure {im!r} is not one of {', '.join(IMS)}")
    if not columns:
        raise RockcliInputError("no body to assess: name a preset (bassae, nemea) or give a body of your own")
    if not configurations:
        raise RockcliInputError("no isolation configuration to assess")
    worst = next((x for x in excitations if x.azimuths), None)
    if worst is not None:  # its motion is the projection onto 0 deg only: never a fragility of that in silence
        raise RockcliInputError(f"excitations: {worst.label} is a pair to run in every orientation "
                                f"(azimuth='worst'): run_fragility_azimuths(columns, excitations, configurations) "
                                f"gives the fragility of its median and of its worst orientation")
    chunk_size = check_count(chunk_size, "chunk_size", "None (one chunk of everything) or a whole number of scenes "
                                                       ">= 1")
    n_boot = check_count(n_boot, "n_boot", "a whole number of bootstrap samples >= 0", lo=0, none=False)
    if not (0 < level < 1):
        raise RockcliInputError("n_boot must be >= 0 and the confidence level between 0 and 1")
    timings = {}
    t0 = time.perf_counter()
    excitations, im_values = _measure(excitations, im)
    timings["im_s"] = time.perf_counter() - t0

    rows, scenes, run_rows = [], [], []
    for b in columns:
        for x in excitations:
            for c in configurations:
                row = FragilityRow(b.name, b.R, b.alpha_deg, x.label, x.source, c.label, c.header,
                                   im_values.get(x.label, math.nan), error=x.error)
                rows.append(row)
                if x.motion is not None and not x.error:
                    scenes.append((b, c.foundation, x.motion))
                    run_rows.append(row)
    t0 = time.perf_counter()
    kw = dict(solver)
    if progress is not None and runner is None:
        from rockcli.progress import phase

        phase(progress, "margin search", len(scenes) * MARGIN_GRID.size, known=False)
        kw["progress"] = progress
    found = overturn_scales_chunked(scenes, runner=runner, chunk_size=chunk_size, **kw)
    timings["margin_s"] = time.perf_counter() - t0
    lo_f, hi_f = float(MARGIN_GRID[0]), float(MARGIN_GRID[-1])
    for row, (hi, lo, note) in zip(run_rows, found):
        row.overturn_scale, row.overturn_scale_survives, row.margin_note = hi, lo, note
        if note.startswith("error"):
            row.error = note[len("error: "):]
        elif note.startswith(NOTE_NO_OVERTURN.format(hi_f)):  # (a note on unproven runs may follow)
            row.capacity, row.censored = hi_f * row.im_value, CENSORED_RIGHT
        elif note.startswith(NOTE_OVERTURNS_AT_MIN.format(lo_f)):
            row.capacity, row.censored = lo_f * row.im_value, CENSORED_LEFT
        else:
            row.capacity = hi * row.im_value

    t0 = time.perf_counter()
    curves = _fit_curves(columns, configurations, excitations, rows, int(n_boot), int(seed), float(level))
    timings["fit_s"] = time.perf_counter() - t0
    return Fragility(list(columns), list(configurations), excitations, IMS[im], rows, curves, int(n_boot),
                     int(seed), float(level), (lo_f, hi_f), list(unavailable), timings)


#: Fewer records than this leave the dispersion beta undetermined: the fit is reported with a warning.
MIN_RECORDS_FOR_BETA = 5
#: A fitted beta below this is a step function, not a measured dispersion.
BETA_STEP = 0.01


def _thin_fit_note(curve) -> str:
    """A warning when a fit stands on too few records or its beta is a step (empty when the fit is sound)."""
    if curve.beta < BETA_STEP:
        return (f"WARNING: beta = {curve.beta:.2g}: the capacities of the {curve.n_records} records coincide, so the "
                f"curve is a step, not a measured dispersion; run more (and more different) records")
    if curve.n_records < MIN_RECORDS_FOR_BETA:
        return (f"WARNING: fitted over {curve.n_records} records only: beta is not determined by so few (at least "
                f"{MIN_RECORDS_FOR_BETA}, better 10 or more); read the curve as indicative")
    return ""


def _fit_curves(columns, configurations, excitations, rows, n_boot, seed, level) -> list:
    labels = [x.label for x in excitations if x.motion is not None and not x.error]
    n = len(labels)
    pos = {lab: k for k, lab in enumerate(labels)}
    # one set of resamples for every column and configuration (paired)
    idx = np.random.default_rng(seed).integers(0, n, size=(n_boot, n)) if n and n_boot else None
    q = (100 * (1 - level) / 2, 100 * (1 + level) / 2)
    by_key = {}
    for r in rows:
        by_key.setdefault((r.column, r.configuration), []).append(r)
    curves = []
    for b in columns:
        rigid = None
        for c in configurations:
            group = [r for r in by_key.get((b.name, c.header), []) if not r.error and r.record in pos]
            x = np.full(n, np.nan)
            codes = np.zeros(n, dtype=np.int8)
            for r in group:
                x[pos[r.record]] = r.capacity
                codes[pos[r.record]] = 1 if r.censored == CENSORED_RIGHT else (-1 if r.censored == CENSORED_LEFT else 0)
            have = np.isfinite(x)
            n_exact = int((have & (codes == 0)).sum())
            curve = FragilityCurve(b.name, c, int(have.sum()), n_exact, int((have & (codes == 1)).sum()),
                                   int((have & (codes == -1)).sum()), math.nan, math.nan)
            if have.any():
                logx = np.where(have, np.log(np.where(have, x, 1.0)), 0.0)
                mu, sigma = _tobit_mle(logx, codes, have[None, :].astype(float))
                curve.median, curve.beta = float(np.exp(mu[0])), float(sigma[0])
            if not math.isfinite(curve.median):
                curve.note = (f"no fit: {n_exact} record(s) with an exact capacity; at least two different "
                              f"ones are needed")
            elif idx is not None:
                W = np.zeros((n_boot, n))
                np.add.at(W, (np.repeat(np.arange(n_boot), n), idx.ravel()), 1.0)
                W *= have[None, :]
                mu_b, sig_b = _tobit_mle(logx, codes, W)
                curve.boot_median, curve.boot_beta = np.exp(mu_b), sig_b
                okb = np.isfinite(mu_b)
                curve.n_boot_ok = int(okb.sum())
                if curve.n_boot_ok >= 2:
                    curve.median_ci = tuple(float(v) for v in np.percentile(curve.boot_median[okb], q))
                    curve.beta_ci = tuple(float(v) for v in np.percentile(sig_b[okb], q))
            if math.isfinite(curve.median):
                curve.note = _thin_fit_note(curve)
            if not c.isolated and rigid is None:
                rigid = curve
            curves.append(curve)
        if rigid is not None and math.isfinite(rigid.median):
            for curve in curves[-len(configurations):]:
                if curve is rigid or not math.isfinite(curve.median):
                    continue
                curve.ratio_to_rigid = curve.median / rigid.median
                if curve.boot_median is not None and rigid.boot_median is not None:
                    ratio = curve.boot_median / rigid.boot_median
                    ok = np.isfinite(ratio)
                    if ok.sum() >= 2:
                        curve.ratio_ci = tuple(float(v) for v in np.percentile(ratio[ok], q))
    return curves


def empirical_points(rows) -> list[tuple[float, float, str]]:
    """Plotting positions of the records' capacities: (capacity, probability, censored).

    Kaplan-Meier estimate of the distribution of capacities with right-censoring (a censored
    record leaves the risk set at its bound); each exact capacity is placed at the midpoint of its
    step (``(i - 0.5)/n`` without censoring). Left-censored capacities are placed as exact at their
    bound. Censored records are returned at their bound with the estimate reached there.
    """
    pts = sorted(((r.capacity, r.censored) for r in rows if not r.error and math.isfinite(r.capacity)),
                 key=lambda p: (p[0], p[1] == CENSORED_RIGHT))
    n = len(pts)
    out, S, at_risk = [], 1.0, n
    for cap, cens in pts:
        if cens == CENSORED_RIGHT:
            out.append((cap, 1.0 - S, cens))
        else:
            S_new = S * (1.0 - 1.0 / at_risk)
            out.append((cap, 1.0 - 0.5 * (S + S_new), cens))
            S = S_new
        at_risk -= 1
    return out


def run_fragility_distributed(scheduler, columns, excitations, configurations, *, chunks_per_worker: int = 2,
                              run: Callable | None = None, progress: Callable[[int], None] | None = None,
                              **kwargs) -> Fragility:
    """:func:`run_fragility` (or ``run``, which takes the same arguments and passes ``runner`` and
    ``chunk_size`` on to it) with the margin searches on a Dask cluster (:mod:`rockcli.distributed`).

    ``scheduler`` is ``"local"`` (a LocalCluster here), ``"tcp://HOST:PORT"`` or a ``distributed.Client``.
    The scenes are split into about ``chunks_per_worker`` chunks per worker; each chunk's search
    depends on its scenes only, so the results are those of :func:`run_fragility`. ``progress(n)`` is
    told as each chunk of ``n`` scenes comes back, the search announced with :func:`rockcli.progress.phase`
    (in scenes, no time left: the chunks' searches go as far as they find).
    """
    from rockcli.assess.cluster import dask_runner
    from rockcli.distributed import open_client

    n_scenes = max(1, len(columns) * len(excitations) * len(configurations))
    with open_client(scheduler) as client:
        workers = max(1, len(client.scheduler_info().get("workers", {})))
        size = max(1, -(-n_scenes // (workers * chunks_per_worker)))
        runner = dask_runner(client, progress)  # "margin search on Dask (N tasks)", in scenes
        return (run or run_fragility)(columns, excitations, configurations, chunk_size=size, runner=runner,
                                      **kwargs)
