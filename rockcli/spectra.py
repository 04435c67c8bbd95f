"""Overturning spectra, minimum overturning acceleration and critical block size (sweeps layer).

The paper's Figures 6-9 and 11 and its Table I, for any slenderness, pulse shape and isolation.

Dimensionless presentation
--------------------------
A map is drawn over ``x = omega_p / p`` and ``y = a_p / (g tan alpha)`` for a block of slenderness
``alpha``. Written in the time ``p t``, Eq (3) (rigid foundation) depends only on ``alpha``,
``a_p / g`` and ``omega_p / p``; Eqs (7)-(11) (isolated base) in addition on ``omega_b / omega_p =
T_p / T_b``, ``xi`` and ``gamma`` (``gamma R p^2 / g = 0.75 gamma``). So a map does not depend on the
block size as long as ``T_b / T_p`` is kept fixed over the map, as the paper does. rockcli runs
every cell on one reference block, ``R = REFERENCE_R = 1 m`` (``p = 2.712 rad/s``) unless told
otherwise, and sets ``T_p = 2 pi / (x p)`` for each column; ``tests/test_spectra.py`` checks that
another ``R`` gives the same map. The solver's tolerances are scaled by ``alpha``, ``p alpha`` and
``g tan(alpha) / max(omega_b, p)^2`` and its first step by ``1/p`` and ``T_p``, and a verdict-only run
ends when its verdict is proven (the theorems of :func:`rockcli.kernels.simulate_core`), which does not
depend on the block size either: the dimensionless result is the same to rounding. (A run still
unproven at the solver's horizon, 600 s after the pulse, would end there: such cells are counted and
reported as "still moving", ``settled`` False.)

Verdicts only: the minimum-overturning search runs with ``early=True`` (each run stops as soon as its
verdict is proven, even during the pulse; the same verdicts). Maps run to the end of the motion by
default so that ``theta_max_over_alpha`` is the run's peak; ``early=True`` makes them faster, with the
peak then only a lower bound for runs stopped during the pulse (``peak_final`` False).

Pulses have ``a_p > 0`` (the larger lobe first for the antisymmetric Ricker). Reversing the sign
mirrors theta and leaves every verdict unchanged (the block is symmetric).

Uplift threshold
----------------
On a rigid foundation the block uplifts when ``|ag|`` passes ``g tan(alpha)``; all four pulse shapes
peak at exactly ``|a_p|`` (the antisymmetric Ricker through its factor beta), so the no-uplift zone is
exactly ``y <= 1`` for each of them. On an isolated base, before uplift, block and base move together
as a linear oscillator, so the peak base acceleration is proportional to ``a_p``: uplift is monotone
in ``a_p`` and its threshold is found by bisection on the solver's uplift flag.

Minimum overturning acceleration
--------------------------------
Overturning is not monotone in ``a_p`` (safe islands lie above the minimum), so a bisection between
"safe" and "overturns" alone could land on the upper edge of an island. :func:`min_overturning`
scans ``y`` upwards from the uplift threshold ``y_u`` on the geometric grid ``y_u (1 + step)^k``
(default step 1 %), all columns in parallel batches, stops each column at its first overturning grid
value and bisects (geometrically) between it and the grid value below (safe) to ``tol`` (default
0.1 %). Result: ``ap_min`` overturns, ``ap_safe`` (within ``tol`` below) does not, and no grid value
between the uplift threshold and ``ap_safe`` overturns. Stated resolution: an overturning window
narrower than one scan step (1 % of ``a_p``) can be missed.

Critical size
-------------
Where the rigid-foundation and isolated minimum-overturning curves cross: on a coarse ``x`` grid the
last change from "isolation is better" (``y_rigid <= y_iso``) to "rigid is better" beyond which the
rigid curve stays above the isolated one, refined by bisection in ``x``. The block size follows from
the pulse period: ``p = omega_p / x_cross = 2 pi / (T_p x_cross)``, ``R = 3 g / (4 p^2)``; larger
blocks are safer without isolation.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace
from typing import Callable, Optional, Sequence

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.models import Block, Rigid, parse_isolation_spec
from rockcli.pulses import make_pulse
from rockcli.units import G

#: Semi-diagonal of the reference block every cell is run on [m] (``p = sqrt(3 g / 4) = 2.712 rad/s``).
REFERENCE_R = 1.0
#: Pulse shapes of the spectra.
SHAPES = ("ricker-sym", "ricker-anti", "sine", "cosine")
#: Defaults of the minimum-overturning search: relative scan step, relative bisection tolerance,
#: and the largest a_p / (g tan alpha) tried.
DEFAULT_STEP = 0.01
DEFAULT_TOL = 1e-3
DEFAULT_AP_MAX = 20.0
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

_NUMBER = r"[-+]?([0-9]+\.?[0-9]*|\.[0-9]+)([eE][-+]?[0-9]+)?"  # ASCII digits (\d also takes other scripts)


# --------------------------------------------------------------------------------------------------
# Inputs: grids, pulses, isolation with T_b / T_p fixed
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Grid:
    """``count`` values from ``start`` to ``stop``, both ends included (``numpy.linspace``)."""

    start: float
    stop: float
    count: int

    @property
    def values(self) -> np.ndarray:
        return np.linspace(self.start, self.stop, self.count)

    def __str__(self) -> str:
        return f"{self.start:g}:{self.stop:g}:{self.count}"


def parse_grid(text: str, option: str = "grid", *, positive: bool = False) -> Grid:
    """Parse ``start:stop:count`` (both ends included), e.g. ``0.5:12:200``.

    ``positive``: the start must be > 0 (otherwise >= 0). One clear sentence on any problem.
    """
    raw = str(text).strip()
    parts = raw.split(":")
    example = "0.5:12:200" if positive else "0:10:200"
    if len(parts) != 3:
        raise RockcliInputError(f"{option} {raw!r}: give start:stop:count (both ends included), e.g. {example}")
    if not all(re.fullmatch(r"\s*" + _NUMBER + r"\s*", p) for p in parts[:2]) \
            or not re.fullmatch(r"\s*\d+\s*", parts[2]):
        raise RockcliInputError(f"{option} {raw!r}: start and stop must be numbers and count a whole number, "
                                f"e.g. {example}")
    start, stop, count = float(parts[0]), float(parts[1]), int(parts[2])
    if not (math.isfinite(start) and math.isfinite(stop)):
        raise RockcliInputError(f"{option} {raw!r}: start and stop must be finite")
    if count < 1 or count > 100_000:
        raise RockcliInputError(f"{option} {raw!r}: count must lie between 1 and 100000")
    if (start <= 0 if positive else start < 0):
        raise RockcliInputError(f"{option} {raw!r}: start must be {'> 0' if positive else '>= 0'}")
    if count == 1 and stop != start:
        raise RockcliInputError(f"{option} {raw!r}: a single value needs start = stop")
    if count > 1 and not stop > start:
        raise RockcliInputError(f"{option} {raw!r}: stop must be larger than start")
    return Grid(start, stop, count)


def parse_list(text: str, option: str, *, lo: float = -math.inf, hi: float = math.inf,
               lo_open: bool = False, hi_open: bool = False) -> tuple:
    """Parse a comma-separated list of numbers within ``[lo, hi]`` (open ends as told)."""
    raw = str(text).strip()
    out = []
    for item in raw.split(","):
        item = item.strip()
        if not re.fullmatch(_NUMBER, item):
            raise RockcliInputError(f"{option} {raw!r}: {item!r} is not a number (write e.g. 10,20)")
        v = float(item)
        if not (math.isfinite(v) and (v > lo if lo_open else v >= lo) and (v < hi if hi_open else v <= hi)):
            lo_s = f"{'>' if lo_open else '>='} {lo:g}"
            hi_s = f"{'<' if hi_open else '<='} {hi:g}"
            raise RockcliInputError(f"{option} {raw!r}: {item} must be {lo_s} and {hi_s}")
        out.append(v)
    return tuple(out)


@dataclass(frozen=True)
class PulseChoice:
    """The pulse of a spectrum: a shape, optionally its period, and where it comes from.

    ``T_p`` [s] only matters for the conversion to block sizes (critical size, the R axis);
    the dimensionless spectra do not depend on it.
    """

    shape: str
    T_p: Optional[float] = None
    source: str = "pulse"
    note: str = ""

    @property
    def label(self) -> str:
        return self.shape if self.T_p is None else f"{self.shape} T_p={self.T_p:g}s"


def parse_pulse_choice(text: str) -> PulseChoice:
    """``ricker-sym`` or ``ricker-sym:Tp=0.6`` (shape, optional period in s)."""
    raw = str(text).strip()
    shape, _, rest = raw.partition(":")
    shape = shape.strip().lower()
    shape = {"one-sine": "sine", "one-cosine": "cosine"}.get(shape, shape)
    if shape not in SHAPES:
        raise RockcliInputError(f"pulse {raw!r}: unknown shape {shape!r} (use {', '.join(SHAPES)})")
    from rockcli.inputs import parse_number, spec_items

    T_p = None
    for key, val, eq in spec_items(rest, f"pulse {raw!r}"):
        if key.lower() != "tp" or not eq:
            item = f"{key}={val}" if eq else key
            raise RockcliInputError(f"pulse {raw!r}: {item!r} is not Tp=<period in s> (the amplitude is swept)")
        T_p = parse_number(val, f"pulse {raw!r}: Tp", lo=0.0, lo_open=True, unit="s",
                           bad=f"pulse {raw!r}: Tp must be a positive period in s, got {val!r}")
    return PulseChoice(shape, T_p)


def pulse_from_record(record, *, wavelet: str = "best") -> PulseChoice:
    """Shape and ``T_p`` of a record's fitted pulse (:func:`rockcli.pulses_fit.fit_pulse`)."""
    from rockcli.pulses_fit import fit_pulse

    fit = fit_pulse(record, wavelet)
    note = (f"T_p and shape from the pulse fitted to record {fit.record_name}: {fit.shape}, "
            f"a_p = {fit.a_p_g:+.3f} g, T_p = {fit.T_p_s:.3f} s, energy fraction {fit.energy_fraction:.2f}"
            + (" (T_p on the end of the searched period range)" if fit.at_period_bound else ""))
    return PulseChoice(fit.shape, float(fit.T_p_s), f"record {fit.record_name} (fitted pulse)", note)


@dataclass(frozen=True)
class Isolation:
    """A foundation with ``T_b / T_p`` fixed, for any pulse period.

    ``kind`` is ``none`` (rigid foundation) or a bearing kind of
    :func:`rockcli.models.parse_isolation_spec`; ``params`` its other ``key=value`` items;
    ``ratio`` is ``T_b / T_p``. :meth:`foundation` substitutes ``Tb = ratio * T_p`` and parses the
    spec, so every bearing kind that takes ``Tb=`` works.
    """

    kind: str
    ratio: Optional[float] = None
    params: tuple = ()

    @property
    def rigid(self) -> bool:
        return self.kind == "none"

    def spec(self, T_p: float) -> str:
        items = [f"Tb={float(self.ratio) * float(T_p)!r}"] + [f"{k}={v}" for k, v in self.params]
        return f"{self.kind}:{','.join(items)}"

    def foundation(self, T_p: float):
        if self.rigid:
            return Rigid()
        return parse_isolation_spec(self.spec(T_p))

    def param(self, key: str):
        for k, v in self.params:
            if k.lower() == key.lower():
                return v
        return None

    def with_param(self, key: str, value) -> "Isolation":
        """The same isolation with ``key=value`` set (added or replaced)."""
        params = [(k, v) for k, v in self.params if k.lower() != key.lower()] + [(key, f"{value:g}")]
        return replace(self, params=tuple(params))

    @property
    def label(self) -> str:
        """The spec with every parameter resolved (defaults included), ``TbTp=`` for ``Tb=``."""
        if self.rigid:
            return "none"
        resolved = self.foundation(1.0).label
        if re.search(r"\bTb=[^,]*", resolved):
            return re.sub(r"\bTb=[^,]*", f"TbTp={self.ratio:g}", resolved, count=1)
        return ",".join([f"{self.kind}:TbTp={self.ratio:g}"] + [f"{k}={v}" for k, v in self.params])

    @property
    def short_label(self) -> str:
        if self.rigid:
            return "rigid foundation"
        extras = ", ".join(f"{k} = {v}" for k, v in self.params)
        return f"{self.kind}, $T_b/T_p$ = {self.ratio:g}" + (f", {extras}" if extras else "")


def parse_isolation(text: str) -> Isolation:
    """Parse ``none`` or ``KIND:TbTp=<T_b/T_p>,...`` (e.g. ``linear:TbTp=2,xi=0.05,gamma=0.01``).

    Spectra keep ``T_b / T_p`` fixed over the map, as the paper does, so ``Tb=`` (a period in s) is
    refused. The spec is checked once (with ``T_p = 1 s``) so that errors surface before any run.
    """
    raw = str(text).strip()
    kind, _, rest = raw.partition(":")
    kind = kind.strip().lower()
    if kind in ("none", "rigid", "fixed") and not rest.strip():
        return Isolation("none")
    from rockcli.inputs import parse_number, spec_items

    ratio = None
    params = []
    for key, val, eq in spec_items(rest, f"isolation {raw!r}"):
        if not eq:
            raise RockcliInputError(f"isolation {raw!r}: {key!r} is not key=value")
        if key.lower() == "tb":
            raise RockcliInputError(f"isolation {raw!r}: spectra keep T_b/T_p fixed over the map; "
                                    f"write TbTp=<ratio> instead of Tb=")
        if key.lower() == "tbtp":
            ratio = parse_number(val, f"isolation {raw!r}: TbTp", lo=0.0, lo_open=True,
                                 bad=f"isolation {raw!r}: TbTp must be a positive number, got {val!r}")
        else:
            params.append((key, val))
    if ratio is None:
        raise RockcliInputError(f"isolation {raw!r} needs TbTp=<T_b/T_p> (e.g. linear:TbTp=2,xi=0.05,gamma=0.01)")
    iso = Isolation(kind, ratio, tuple(params))
    iso.foundation(1.0)  # raises with the parser's own sentence if anything else is wrong
    return iso


# --------------------------------------------------------------------------------------------------
# Scenes and the runner
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Family:
    """Scenes that differ only in ``x = omega_p/p`` and ``y = a_p/(g tan alpha)``: one map or one curve."""

    alpha: float  # [rad]
    shape: str
    isolation: Isolation
    R: float = REFERENCE_R

    @property
    def alpha_deg(self) -> float:
        return math.degrees(self.alpha)

    @property
    def block(self) -> Block:
        return Block(self.R, self.alpha, "reference")

    def T_p(self, x: float) -> float:
        """Pulse period [s] of column ``x`` on the reference block."""
        return 2.0 * math.pi / (x * self.block.p)

    def scene(self, x: float, y: float):
        """``(block, foundation, pulse)`` of cell ``(x, y)``."""
        T_p = self.T_p(x)
        return self.block, self.isolation.foundation(T_p), make_pulse(self.shape, y * (G * math.tan(self.alpha)), T_p)


@dataclass(frozen=True)
class Cells:
    """Outcome of cells: arrays in the order of the cells asked for."""

    overturned: np.ndarray
    uplifted: np.ndarray
    theta_max_over_alpha: np.ndarray
    settled: np.ndarray
    peak_final: np.ndarray
    nfev: np.ndarray

    @staticmethod
    def concatenate(parts: Sequence["Cells"]) -> "Cells":
        if not parts:
            return Cells(*(np.zeros(0, dt) for dt in (bool, bool, float, bool, bool, np.int64)))
        return Cells(*(np.concatenate([getattr(p, f) for p in parts])
                       for f in ("overturned", "uplifted", "theta_max_over_alpha", "settled", "peak_final", "nfev")))


def run_cells_local(families: Sequence[Family], fam: np.ndarray, x: np.ndarray, y: np.ndarray,
                    progress: Optional[Callable[[int], None]] = None, early: bool = False,
                    horizon: float | None = None, restitution: float | None = None, cap_ratio: float = 0.0) -> Cells:
    """Run cells ``(families[fam[i]], x[i], y[i])`` with :func:`rockcli.solve.simulate_verdicts` (all cores).

    ``progress(n)`` is called with the number of cells finished since the last call; ``early``: stop
    each run once its verdict is proven (the same verdicts; peaks may be lower bounds); ``horizon``:
    the solver's horizon [s] (None: its default, 600 s); ``restitution``: the coefficient of
    restitution of every impact (None: Housner's); ``cap_ratio``: capped colonnades (0: solitary blocks).
    """
    from rockcli.solve import DEFAULT_HORIZON, simulate_verdicts

    n = len(x)
    if n == 0:
        return Cells.concatenate([])
    jobs = []
    columns = {}  # (family, x) -> the scene at y = 1 (a_p = g tan alpha), built once per column
    for i in range(n):
        key = (int(fam[i]), float(x[i]))
        col = columns.get(key)
        if col is None:
            col = columns[key] = families[key[0]].scene(key[1], 1.0)
        # the kernel scales the unit pulse's a_p by y: the same run as Family.scene(x, y)
        jobs.append((col[0], col[1], col[2], float(y[i])))
    done = [0]

    def step(k):
        progress(k - done[0])
        done[0] = k

    # The scenes run in contiguous pieces, one thread each, and a map's cost grows with a_p (rows):
    # run the cells in a fixed shuffled order so that every piece carries a fair share, and put the
    # results back. Cells are independent: the order changes no result.
    order = np.random.default_rng(0).permutation(n)
    v = simulate_verdicts([jobs[i] for i in order], early=early, progress=step if progress else None,
                          horizon=DEFAULT_HORIZON if horizon is None else horizon, restitution=restitution,
                          cap_ratio=cap_ratio)
    back = np.empty(n, np.int64)
    back[order] = np.arange(n)
    return Cells(v.overturned[back], v.uplifted[back], v.theta_max_over_alpha[back], v.settled[back],
                 v.peak_final[back], v.nfev[back])


def _run_cells_task(args) -> Cells:
    """One chunk on a Dask worker (module-level so that it pickles by reference)."""
    families, fam, x, y, early, horizon, restitution, cap_ratio = args
    return run_cells_local(families, fam, x, y, early=early, horizon=horizon, restitution=restitution,
                           cap_ratio=cap_ratio)


class Runner:
    """Runs batches of cells here (``scheduler=None``) or in chunks on a Dask cluster.

    Parameters
    ----------
    scheduler : str or dask.distributed.Client, optional
        ``None`` (this machine, numba on all cores), ``"local"`` (a Dask LocalCluster),
        ``"tcp://HOST:PORT"`` (an existing scheduler; its workers need rockcli installed), or a
        ``Client``.
    chunk : int
        Cells per Dask task.
    horizon : float, optional
        The solver's horizon [s] for every run (None: its default, 600 s).
    restitution : float, optional
        The coefficient of restitution of every impact (None: Housner's; :mod:`rockcli.impact`).
    cap_ratio : float
        Capped colonnades of the blocks, rigid foundation only (:mod:`rockcli.colonnade`; 0: none).
    """

    def __init__(self, scheduler=None, *, chunk: int = 2000, horizon: float | None = None,
                 restitution: float | None = None, cap_ratio: float = 0.0):
        self.scheduler = scheduler
        self.chunk = int(chunk)
        self.horizon = horizon
        self.restitution = restitution
        self.cap_ratio = cap_ratio
        self._client = None
        self._close = None
        self.cells_run = 0
        self.nfev = 0
        self.unproven = 0  # runs that reached the solver's horizon with the verdict unproven

    def __enter__(self):
        if self.scheduler is not None:
            from rockcli.distributed import open_client

            self._close = open_client(self.scheduler)
            self._client = self._close.__enter__()
        return self

    def __exit__(self, *exc):
        if self._close is not None:
            self._close.__exit__(*exc)
            self._close = self._client = None
        return False

    def __call__(self, families, fam, x, y, progress=None, early: bool = False) -> Cells:
        fam = np.asarray(fam, dtype=np.int64)
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        if self.scheduler is None:
            out = run_cells_local(families, fam, x, y, progress, early, self.horizon, self.restitution,
                                  self.cap_ratio)
        else:
            if self._client is None:
                raise RuntimeError("use the Runner as a context manager to run on a scheduler")
            from rockcli.distributed import map_chunks

            n = len(x)
            bounds = [(lo, min(n, lo + self.chunk)) for lo in range(0, n, self.chunk)]
            tasks = [(tuple(families), fam[lo:hi], x[lo:hi], y[lo:hi], early, self.horizon, self.restitution,
                      self.cap_ratio) for lo, hi in bounds]
            sizes = [hi - lo for lo, hi in bounds]
            parts = map_chunks(self._client, _run_cells_task, tasks,
                               progress=(lambda i: progress(sizes[i])) if progress else None)
            out = Cells.concatenate(parts)
        self.cells_run += len(x)
        self.nfev += int(out.nfev.sum())
        self.unproven += int(np.count_nonzero(~out.settled & ~out.overturned))
        return out


# --------------------------------------------------------------------------------------------------
# Overturning map (Figures 6, 9)
# --------------------------------------------------------------------------------------------------
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

    @property
    def isolation_label(self) -> str:
        return self.isolation.label


def overturning_maps(alphas_deg: Sequence[float], pulses: Sequence[PulseChoice], isolations: Sequence[Isolation],
                     wp_grid: Grid, ap_grid: Grid, *, R: float = REFERENCE_R, runner: Optional[Runner] = None,
                     progress=None, early: bool = False) -> list[OverturningMap]:
    """Overturning maps for every ``alpha x pulse x isolation`` (in that nesting order), in one batch.

    ``early``: stop each run once its verdict is proven (faster; the same verdicts and uplift flags,
    ``theta_max_over_alpha`` then a lower bound where ``peak_final`` is False).
    """
    runner = runner or Runner()
    xs, ys = wp_grid.values, ap_grid.values
    families = [Family(math.radians(a), pc.shape, iso, R) for a in alphas_deg for pc in pulses for iso in isolations]
    keys = [(a, pc, iso) for a in alphas_deg for pc in pulses for iso in isolations]
    Y, X = np.meshgrid(ys, xs, indexing="ij")
    ncell = X.size
    fam = np.repeat(np.arange(len(families)), ncell)
    res = runner(families, fam, np.tile(X.ravel(), len(families)), np.tile(Y.ravel(), len(families)), progress,
                 early=early)
    maps = []
    shape = X.shape
    for j, (a, pc, iso) in enumerate(keys):
        s = slice(j * ncell, (j + 1) * ncell)
        maps.append(OverturningMap(
            alpha_deg=float(a), pulse=pc, isolation=iso, wp_over_p=xs, ap_over_g_tan_alpha=ys,
            overturned=res.overturned[s].reshape(shape), uplifted=res.uplifted[s].reshape(shape),
            theta_max_over_alpha=res.theta_max_over_alpha[s].reshape(shape),
            settled=res.settled[s].reshape(shape), peak_final=res.peak_final[s].reshape(shape),
            nfev=int(res.nfev[s].sum())))
    return maps


def overturning_map(alpha_deg: float, pulse, isolation, wp_grid: Grid, ap_grid: Grid, **kwargs) -> OverturningMap:
    """One overturning map (see :func:`overturning_maps`); ``pulse`` and ``isolation`` may be spec strings."""
    pc = parse_pulse_choice(pulse) if isinstance(pulse, str) else pulse
    iso = parse_isolation(isolation) if isinstance(isolation, str) else isolation
    return overturning_maps([alpha_deg], [pc], [iso], wp_grid, ap_grid, **kwargs)[0]


# --------------------------------------------------------------------------------------------------
# Minimum overturning acceleration (Figures 7, 8, 9, 11)
# --------------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class MinSearch:
    """Per column: uplift threshold, and the bracket of the smallest overturning amplitude.

    ``ap_min`` overturns, ``ap_safe`` (within ``tol`` below it) does not; both NaN when nothing
    overturns up to ``ap_max`` (``ap_uplift`` NaN too when the block does not even uplift). All in
    units of ``g tan(alpha)``. ``unproven``: runs still moving at the solver's horizon (counted safe).
    """

    ap_uplift: np.ndarray
    ap_min: np.ndarray
    ap_safe: np.ndarray
    runs: int
    unproven: int = 0  # runs that reached the solver's horizon unproven (counted as safe)


def search_min_overturning(families: Sequence[Family], fam, x, *, ap_max: float = DEFAULT_AP_MAX,
                           step: float = DEFAULT_STEP, tol: float = DEFAULT_TOL, runner: Optional[Runner] = None,
                           progress=None) -> MinSearch:
    """Smallest ``y = a_p/(g tan alpha)`` that overturns, for columns ``(families[fam[i]], x[i])``.

    See the module notes: uplift threshold, geometric scan up from it with ratio ``1 + step``, then
    geometric bisection to ``tol`` between the last safe and the first overturning scan value.
    ``progress(n)`` is told when ``n`` more columns are finished.
    """
    if not (math.isfinite(step) and 0 < step <= 0.5):
        raise RockcliInputError(f"scan step must lie in (0, 0.5] (relative), got {step!r}")
    if not (math.isfinite(tol) and 0 < tol <= step):
        raise RockcliInputError(f"tolerance must lie in (0, step], got {tol!r}")
    if not (math.isfinite(ap_max) and ap_max > 1):
        raise RockcliInputError(f"ap_max must be > 1 (in units of g tan alpha), got {ap_max!r}")
    runner = runner or Runner()
    fam = np.asarray(fam, dtype=np.int64)
    x = np.asarray(x, dtype=float)
    n = len(x)
    runs = 0

    unproven = 0

    def run(idx, yv, early=True):
        nonlocal runs, unproven
        runs += len(idx)
        out = runner(families, fam[idx], x[idx], yv, early=early)
        unproven += int(np.count_nonzero(~out.settled & ~out.overturned))
        return out

    # 1. uplift threshold: exactly 1 on a rigid foundation (every shape peaks at |a_p|); on an
    # isolated base the stuck motion is linear in a_p, so uplift is monotone: bisection.
    y_u = np.ones(n)
    iso_cols = np.array([i for i in range(n) if not families[fam[i]].isolation.rigid], dtype=np.int64)
    if iso_cols.size:
        lo = np.zeros(iso_cols.size)
        hi = np.ones(iso_cols.size)
        pending = np.arange(iso_cols.size)
        while pending.size:  # bracket: double hi until the block uplifts
            up = run(iso_cols[pending], hi[pending], early=False).uplifted
            lo[pending[~up]] = hi[pending[~up]]
            hi[pending[~up]] *= 2.0
            pending = pending[~up & (hi[pending] <= 2.0 * ap_max)]
        ok = hi <= 2.0 * ap_max
        act = np.flatnonzero(ok)
        while act.size:
            mid = 0.5 * (lo[act] + hi[act])
            up = run(iso_cols[act], mid, early=False).uplifted
            hi[act[up]] = mid[up]
            lo[act[~up]] = mid[~up]
            act = act[(hi[act] - lo[act]) > 1e-7 * hi[act]]
        y_u[iso_cols] = np.where(ok, lo, np.nan)

    # 2. scan upwards from the threshold on y_u (1 + step)^k; first overturning grid value. From here
    # on only verdicts count: early runs (stopped once the verdict is proven; the same verdicts).
    ratio = 1.0 + step
    ap_min = np.full(n, np.nan)
    ap_safe = np.full(n, np.nan)
    safe = y_u.copy()  # largest scanned value known safe (the threshold itself does not uplift)
    hi_ot = np.full(n, np.nan)
    kdone = np.zeros(n, np.int64)
    width = np.full(n, 4, np.int64)
    active = np.flatnonzero(np.isfinite(y_u) & (y_u < ap_max))
    if progress:
        progress(int(n - active.size))
    while active.size:
        cols, ks = [], []
        for i in active:
            k = np.arange(kdone[i] + 1, kdone[i] + 1 + width[i])
            cols.append(np.full(k.size, i))
            ks.append(k)
        cols = np.concatenate(cols)
        ks = np.concatenate(ks)
        yv = np.minimum(y_u[cols] * ratio ** ks, ap_max)
        res = run(cols, yv).overturned
        still = []
        pos = 0
        for i in active:
            w = int(width[i])
            o = res[pos:pos + w]
            yy = yv[pos:pos + w]
            pos += w
            hit = np.flatnonzero(o)
            if hit.size:
                j = int(hit[0])
                hi_ot[i] = yy[j]
                if j > 0:
                    safe[i] = yy[j - 1]
            elif yy[-1] >= ap_max:
                safe[i] = ap_max
                if progress:
                    progress(1)
            else:
                safe[i] = yy[-1]
                kdone[i] += w
                width[i] = min(2 * w, 64)
                still.append(i)
        active = np.array(still, dtype=np.int64)

    # 3. bisection between the last safe and the first overturning scan value
    act = np.flatnonzero(np.isfinite(hi_ot))
    lo = safe.copy()
    hi = hi_ot.copy()
    act = act[hi[act] > lo[act] * (1.0 + tol)]
    done0 = np.flatnonzero(np.isfinite(hi_ot) & ~np.isin(np.arange(n), act))
    if progress and done0.size:
        progress(int(done0.size))
    while act.size:
        mid = np.sqrt(lo[act] * hi[act])
        o = run(act, mid).overturned
        hi[act[o]] = mid[o]
        lo[act[~o]] = mid[~o]
        keep = hi[act] > lo[act] * (1.0 + tol)
        if progress and (~keep).any():
            progress(int((~keep).sum()))
        act = act[keep]
    found = np.isfinite(hi_ot)
    ap_min[found] = hi[found]
    ap_safe[found] = lo[found]
    return MinSearch(ap_uplift=y_u, ap_min=ap_min, ap_safe=ap_safe, runs=runs, unproven=unproven)


@dataclass(frozen=True)
class MinCurve:
    """Minimum overturning acceleration over ``wp_over_p`` for one configuration (units of g tan alpha)."""

    alpha_deg: float
    pulse: PulseChoice
    isolation: Isolation
    wp_over_p: np.ndarray
    ap_min: np.ndarray
    ap_safe: np.ndarray
    ap_uplift: np.ndarray
    ap_max: float
    step: float
    tol: float


def min_overturning_curves(alphas_deg: Sequence[float], pulses: Sequence[PulseChoice],
                           isolations: Sequence[Isolation], wp_values, *, ap_max: float = DEFAULT_AP_MAX,
                           step: float = DEFAULT_STEP, tol: float = DEFAULT_TOL, R: float = REFERENCE_R,
                           runner: Optional[Runner] = None, progress=None) -> list[MinCurve]:
    """Minimum overturning curves for every ``alpha x pulse x isolation`` (nesting order), one search."""
    xs = np.asarray(wp_values, dtype=float)
    keys = [(a, pc, iso) for a in alphas_deg for pc in pulses for iso in isolations]
    families = [Family(math.radians(a), pc.shape, iso, R) for a, pc, iso in keys]
    fam = np.repeat(np.arange(len(families)), xs.size)
    res = search_min_overturning(families, fam, np.tile(xs, len(families)), ap_max=ap_max, step=step, tol=tol,
                                 runner=runner, progress=progress)
    out = []
    for j, (a, pc, iso) in enumerate(keys):
        s = slice(j * xs.size, (j + 1) * xs.size)
        out.append(MinCurve(float(a), pc, iso, xs, res.ap_min[s], res.ap_safe[s], res.ap_uplift[s], ap_max, step,
                            tol))
    return out


# --------------------------------------------------------------------------------------------------
# Critical size (Table I)
# --------------------------------------------------------------------------------------------------
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
                   step: float = DEFAULT_STEP, tol: float = DEFAULT_TOL, R: float = REFERENCE_R,
                   runner: Optional[Runner] = None, progress=None) -> CriticalResult:
    """Where the rigid and isolated minimum-overturning curves cross, as a block size (Table I).

    For every pulse (with ``T_p``), slenderness and isolation: the curves on ``wp_grid``, the last
    change from ``y_rigid <= y_iso`` to ``y_rigid > y_iso`` beyond which the rigid curve stays above
    (no overturning up to ``ap_max`` counts as infinitely high; where neither overturns, as "rigid
    better": isolation brings nothing there), refined by bisection in ``x`` to ``xtol`` (relative).
    Rows come in the order pulse, alpha, isolation.
    """
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
    fam_keys = [(a, sh, iso) for sh in shapes for a in alphas_deg for iso in [rigid, *isolations]]
    families = [Family(math.radians(a), sh, iso, R) for a, sh, iso in fam_keys]
    findex = {k: i for i, k in enumerate(fam_keys)}
    fam = np.repeat(np.arange(len(families)), xs.size)
    res = search_min_overturning(families, fam, np.tile(xs, len(families)), ap_max=ap_max, step=step, tol=tol,
                                 runner=runner, progress=progress)
    runs = res.runs
    grid_min = {k: res.ap_min[i * xs.size:(i + 1) * xs.size] for k, i in findex.items()}
    curves = [MinCurve(a, PulseChoice(sh), iso, xs, grid_min[(a, sh, iso)],
                       res.ap_safe[findex[(a, sh, iso)] * xs.size:(findex[(a, sh, iso)] + 1) * xs.size],
                       res.ap_uplift[findex[(a, sh, iso)] * xs.size:(findex[(a, sh, iso)] + 1) * xs.size],
                       ap_max, step, tol) for a, sh, iso in fam_keys]

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
    for sh in shapes:
        for a in alphas_deg:
            yr = grid_min[(a, sh, rigid)]
            for iso in isolations:
                yi = grid_min[(a, sh, iso)]
                both_inf = np.isnan(yr) & np.isnan(yi)
                b = better_rigid(yr, yi)
                key = (sh, a, iso)
                changes = int(np.count_nonzero(b[1:] != b[:-1]))
                if both_inf.any():
                    notes.append(f"{sh}, alpha = {a:g} deg, {iso.label}: neither overturns up to "
                                 f"{ap_max:g} g tan(alpha) at omega_p/p >= {xs[both_inf][0]:.3g} "
                                 f"({int(both_inf.sum())} grid values, counted as rigid better)")
                if b.all():
                    tasks[key] = ("below", xs[0], xs[0])
                elif not b[-1]:
                    tasks[key] = ("above", xs[-1], xs[-1])
                else:
                    i = int(np.flatnonzero(~b)[-1])
                    tasks[key] = ("bracket", xs[i], xs[i + 1])
                    if changes > 1:
                        notes.append(f"{sh}, alpha = {a:g} deg, {iso.label}: the curves cross {changes} times on "
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
            sh, a, iso = k
            m = 0.5 * (lo[k] + hi[k])
            fams += [findex[(a, sh, rigid)], findex[(a, sh, iso)]]
            xv += [m, m]
        r = search_min_overturning(families, np.array(fams), np.array(xv), ap_max=ap_max, step=step, tol=tol,
                                   runner=runner)
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
    for pc in pulses:
        for a in alphas_deg:
            for iso in isolations:
                kind, x0, x1 = tasks[(pc.shape, a, iso)]
                note = ""
                if kind == "bracket":
                    xc = 0.5 * (lo[(pc.shape, a, iso)] + hi[(pc.shape, a, iso)])
                    Rc = critical_R(pc.T_p, xc)
                    yc = y_at.get((pc.shape, a, iso), (np.nan, np.nan))[1]
                elif kind == "below":
                    xc, Rc, yc = np.nan, np.nan, np.nan
                    note = (f"rigid better over the whole grid: crossing below omega_p/p = {x0:g} "
                            f"(R < {critical_R(pc.T_p, x0):.3g} m)")
                else:
                    xc, Rc, yc = np.nan, np.nan, np.nan
                    note = (f"isolation better up to omega_p/p = {x1:g}: crossing beyond the grid "
                            f"(R > {critical_R(pc.T_p, x1):.3g} m)")
                rows.append(CriticalRow(pc.source, pc.shape, float(pc.T_p), float(a), float(iso.ratio),
                                        float(f"{iso.ratio * pc.T_p:.12g}"), float(xc), float(Rc), iso.label, note, float(yc)))
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
