"""Column assessment: columns x records x foundations -> survive / overturn, with a margin.

This is the library behind ``rockcli assess column`` (no click, no pandas). It

1. resolves the *columns* (presets ``bassae``/``nemea`` or custom blocks), the *excitations*
   (catalogue records, files, folders; a catalogue record whose file is not found is replaced by
   its catalogued Ricker pulse) and the *configurations* (isolation specs);
2. runs every scene column x excitation x configuration verdict-only through
   :func:`rockcli.solve.simulate_many` (all cores);
3. optionally finds, for each scene, the **overturning scale** (the margin): the smallest factor
   ``s`` such that ``s`` times the record overturns the column in that configuration;
4. returns plain :class:`AssessmentRow` objects; :mod:`rockcli.report.tables` turns them into CSV.

Margin method
-------------
Overturning is not monotone in the amplitude of the excitation (there are safe islands above the
smallest overturning amplitude), so a bisection alone could miss the smallest factor. The factors
of :data:`MARGIN_GRID` (40 log-spaced values from 0.1 to 4 with a ratio of about 1.1 between
neighbours; 1 is one of them and reuses the main run) are scanned first, all scenes in one batch;
then, for each scene, the interval between the first overturning factor and the grid factor
below it (which survives) is bisected geometrically, all scenes together at each iteration,
until the two ends are within :data:`MARGIN_RTOL` (1 %). ``overturn_scale`` is the upper end
(it overturns), ``overturn_scale_survives`` the lower end (it survives). Overturning islands
narrower than the grid step (10 %) can be missed; nothing overturning up to 4x gives NaN and the
note ``no overturning up to 4x``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, Sequence

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.models import COLUMN_PRESETS, Block, LinearIsolation, Rigid, column, parse_isolation_spec
from rockcli.units import G

#: The paper's Table III configurations: rigid foundation and linear bearings with
#: T_b = 2, 2.5, 3 s and xi_b = 0.1 (gamma = rockcli.models.DEFAULT_GAMMA = 0.01).
DEFAULT_ISOLATION = ("none", "linear:Tb=2,xi=0.1", "linear:Tb=2.5,xi=0.1", "linear:Tb=3,xi=0.1")

#: Scale factors scanned for the margin: 0.1 .. 1 (25 values) and 1 .. 4 (16 values), log-spaced.
MARGIN_GRID = np.unique(np.concatenate([np.geomspace(0.1, 1.0, 25), np.geomspace(1.0, 4.0, 16)]))
#: Relative width of the bracket at which the bisection stops.
MARGIN_RTOL = 0.01

EXCITATION_RECORD = "record"
EXCITATION_PULSE = "pulse"
#: How records are turned into excitations: the file where found, else the catalogued pulse
#: (``auto``); files only (``record``); catalogued pulses only (``pulse``).
EXCITATION_MODES = ("auto", "record", "pulse")


# --------------------------------------------------------------------------------------------------
# columns
# --------------------------------------------------------------------------------------------------

_NUMBER = re.compile(r"\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*")


def parse_column_spec(text: str) -> Block:
    """A column from a preset name or a custom spec.

    ``bassae``, ``nemea`` (presets, see :data:`rockcli.models.COLUMN_PRESETS`), or
    ``NAME:R=<m>,alpha=<deg>`` or ``NAME:height=<m>,width=<m>`` (full height and base width).

    Examples
    --------
    >>> parse_column_spec("statue:R=1.2,alpha=14").name
    'statue'
    """
    raw = str(text).strip()
    name, colon, rest = raw.partition(":")
    name = name.strip()
    if not colon:
        return column(name)
    if not name:
        raise RockcliInputError(f"column {raw!r} needs a name before ':' (e.g. statue:R=1.2,alpha=14)")
    values = {}
    keys = {"r": "R", "alpha": "alpha", "height": "height", "width": "width"}
    for item in filter(None, (s.strip() for s in rest.split(","))):
        key, eq, val = item.partition("=")
        k = key.strip().lower()
        if not eq or k not in keys:
            raise RockcliInputError(f"column {raw!r}: {item!r} is not one of R=<m>, alpha=<deg>, "
                                    f"height=<m>, width=<m>")
        if not _NUMBER.fullmatch(val):
            raise RockcliInputError(f"column {raw!r}: {key.strip()} must be a number, got {val.strip()!r}")
        values[keys[k]] = float(val)
    return custom_column(name, **values)


def custom_column(name: str, R=None, alpha=None, height=None, width=None) -> Block:
    """A custom block from ``R`` [m] and ``alpha`` [deg], or from ``height`` and ``width`` [m]."""
    by_r = R is not None or alpha is not None
    by_dim = height is not None or width is not None
    if by_r and by_dim:
        raise RockcliInputError(f"column {name!r}: give either R and alpha, or height and width, not both")
    if by_r:
        if R is None or alpha is None:
            raise RockcliInputError(f"column {name!r}: R (m) and alpha (deg) go together")
        return Block.from_degrees(R, alpha, name)
    if by_dim:
        if height is None or width is None:
            raise RockcliInputError(f"column {name!r}: height (m) and width (m) go together")
        return Block.from_dimensions(height, width, name)
    raise RockcliInputError(f"column {name!r}: give R and alpha, or height and width")


def column_title(block: Block) -> str:
    """``Temple of Apollo at Bassae (bassae): R = 3.03 m, alpha = 10.56 deg, h/b = 5.36``."""
    preset = COLUMN_PRESETS.get(block.name)
    head = f"{preset[2]} ({block.name})" if preset else block.name
    return (f"{head}: R = {block.R:.2f} m, alpha = {block.alpha_deg:.2f} deg, h/b = {block.h / block.b:.2f}, "
            f"height {block.height:.2f} m, width {block.width:.2f} m")


# --------------------------------------------------------------------------------------------------
# configurations
# --------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Configuration:
    """A foundation and how the user wrote it."""

    spec: str
    foundation: object
    header: str

    @property
    def label(self) -> str:
        return self.foundation.label


def _short_header(foundation, spec: str) -> str:
    if isinstance(foundation, Rigid):
        return "none"
    T_b = getattr(foundation, "T_b", None)
    return f"Tb={T_b:g}s" if T_b is not None else spec


def parse_configurations(specs: Sequence[str] | None = None) -> list[Configuration]:
    """Parse isolation specs (default :data:`DEFAULT_ISOLATION`) with column headers for the table.

    Headers are short (``none``, ``Tb=2s``) when that is unambiguous, else the spec as written.
    Any spec :func:`rockcli.models.parse_isolation_spec` accepts works.
    """
    specs = list(specs) if specs else list(DEFAULT_ISOLATION)
    out, seen = [], set()
    for s in specs:
        f = parse_isolation_spec(s)
        if f.label in seen:
            continue  # the same foundation twice: run it once
        seen.add(f.label)
        out.append((s.strip(), f))
    headers = [_short_header(f, s) for s, f in out]
    if len(set(headers)) < len(headers):
        headers = ["none" if isinstance(f, Rigid) else s for s, f in out]
    return [Configuration(s, f, h) for (s, f), h in zip(out, headers)]


# --------------------------------------------------------------------------------------------------
# excitations
# --------------------------------------------------------------------------------------------------

@dataclass(frozen=True)
class Excitation:
    """One ground motion of the assessment.

    Attributes
    ----------
    label : str
        Catalogue id or file name.
    kind : str
        ``record`` (the accelerogram) or ``pulse`` (the catalogued Ricker pulse that idealises it).
    motion : Record or pulse or None
        What the solver runs (None when it could not be read: see ``error``).
    source : str
        File path, or ``catalogue pulse <shape> a_p=.. g T_p=.. s``.
    pga_g : float
        Peak ground acceleration of the motion [g] (|a_p| for a pulse).
    error : str
        Why the motion could not be read (runs then get this error in their rows).
    """

    label: str
    kind: str
    motion: object
    source: str
    pga_g: float = math.nan
    error: str = ""
    a_p_g: float = math.nan
    T_p_s: float = math.nan


@dataclass(frozen=True)
class Unavailable:
    """A record asked for (or in the default set) that cannot be run: neither file nor pulse."""

    label: str
    reason: str


def _pulse_excitation(entry) -> Excitation:
    from rockcli.pulses import make_pulse

    pulse = make_pulse(entry.pulse_shape, entry.a_p_g * G, entry.T_p_s)
    source = f"catalogue pulse {entry.pulse_shape} a_p={entry.a_p_g:+.4f} g T_p={entry.T_p_s:.4f} s"
    return Excitation(entry.id, EXCITATION_PULSE, pulse, source, abs(entry.a_p_g), "", entry.a_p_g, entry.T_p_s)


def _read_excitation(label: str, path: Path, read_kwargs: dict) -> Excitation:
    from rockcli.records import read_record

    try:
        rec = read_record(path, **read_kwargs)
    except RockcliInputError as exc:
        return Excitation(label, EXCITATION_RECORD, None, str(path), error=str(exc))
    except Exception as exc:  # a file the reader chokes on: report it in its rows, keep the others
        return Excitation(label, EXCITATION_RECORD, None, str(path), error=f"{path}: {type(exc).__name__}: {exc}")
    if rec.npts < 2 or not np.all(np.isfinite(rec.acc)) or not rec.dt > 0:
        return Excitation(label, EXCITATION_RECORD, None, str(path),
                          error=f"{path}: not a usable record (needs >= 2 finite samples and dt > 0)")
    return Excitation(label, EXCITATION_RECORD, rec, str(path), rec.pga_g)


def _entry_read_kwargs(entry) -> dict:
    return {"format": entry.format or None, "units": entry.units, "dt": entry.dt, "column": entry.column}


def _has_pulse(entry) -> bool:
    return bool(entry.pulse_shape) and entry.a_p_g is not None and entry.T_p_s is not None


def _from_entry(entry, mode: str):
    """Excitation (or Unavailable) for a catalogue entry."""
    from rockcli.records.catalog import find_file, search_path

    path = find_file(entry) if (entry.available and mode != "pulse") else None
    if path is not None:
        return _read_excitation(entry.id, path, _entry_read_kwargs(entry))
    if mode != "record" and _has_pulse(entry):
        return _pulse_excitation(entry)
    if not entry.available:
        why = "no public file is known"
    elif mode == "pulse":
        why = "it has no catalogued pulse"
    else:
        why = f"file {entry.file!r} not found in {', '.join(str(p) for p in search_path())}"
    if mode == "auto" and not _has_pulse(entry):
        why += " and it has no catalogued pulse"
    return Unavailable(entry.id, why)


def table_ii_entries() -> list:
    """The catalogue rows of the paper's Table II (those with a published PGA), in catalogue order."""
    from rockcli.records.catalog import load_catalog

    return [e for e in load_catalog() if e.pga_published_g is not None]


def resolve_excitations(sources: Sequence[str] | None = None, mode: str = "auto"):
    """Turn record sources into excitations.

    Parameters
    ----------
    sources : sequence of str, optional
        Catalogue ids, record files, or folders (every regular, non-hidden file in it, sorted).
        Default: the catalogue's Table II records.
    mode : {"auto", "record", "pulse"}
        For catalogue records: the file where found, else the catalogued pulse (``auto``); files
        only (``record``); the catalogued pulses (``pulse``).

    Returns
    -------
    excitations : list of Excitation
        In the order given; a file that cannot be read is kept, with its ``error``.
    unavailable : list of Unavailable
        Default-set records that can be run neither from a file nor as a pulse.

    Raises
    ------
    RockcliInputError
        A named source that is neither an existing file or folder nor a catalogue id, a named
        catalogue record that cannot be run, an empty folder, an unknown ``mode``.
    """
    from rockcli.records.catalog import load_catalog

    if mode not in EXCITATION_MODES:
        raise RockcliInputError(f"excitation mode {mode!r} is not one of {', '.join(EXCITATION_MODES)}")
    entries = load_catalog()
    by_id = {e.id: e for e in entries}
    by_file = {e.file: e for e in entries if e.file}
    out, unavailable, seen = [], [], set()

    def add(x):
        if x.label not in seen:
            seen.add(x.label)
            out.append(x)

    if not sources:
        for e in table_ii_entries():
            x = _from_entry(e, mode)
            (unavailable.append(x) if isinstance(x, Unavailable) else add(x))
        return out, unavailable

    for src in sources:
        src = str(src)
        path = Path(src).expanduser()
        if path.is_dir():
            files = sorted(p for p in path.iterdir() if p.is_file() and not p.name.startswith("."))
            if not files:
                raise RockcliInputError(f"--records {src}: the folder holds no files")
            for p in files:
                add(_file_excitation(p, by_file))
        elif path.is_file():
            add(_file_excitation(path, by_file))
        elif src in by_id:
            x = _from_entry(by_id[src], mode)
            if isinstance(x, Unavailable):
                raise RockcliInputError(f"record {src!r} cannot be run: {x.reason}")
            add(x)
        else:
            raise RockcliInputError(f"--records {src}: no such file or folder, nor a catalogue id "
                                    f"(see 'rockcli records list')")
    return out, unavailable


def _file_excitation(path: Path, by_file: dict) -> Excitation:
    """A record file; one the catalogue lists is read as the catalogue says and labelled by its id."""
    entry = by_file.get(path.name)
    if entry is not None:
        return _read_excitation(entry.id, path, _entry_read_kwargs(entry))
    return _read_excitation(path.name, path, {})


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

    def row(self, column: str, record: str, configuration: str) -> AssessmentRow:
        """The row of one scene (by column name, record label, configuration header)."""
        index = self.__dict__.get("_index")
        if index is None or len(index) != len(self.rows):
            index = self.__dict__["_index"] = {(r.column, r.record, r.configuration): r for r in self.rows}
        return index[(column, record, configuration)]

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
        error=x.error)


def _scaled_job(block, foundation, motion, scale: float):
    """A simulate_many job at ``scale`` times the motion (records scale in the kernel, pulses by a_p)."""
    if hasattr(motion, "acc"):
        return (block, foundation, motion, scale)
    return (block, foundation, motion if scale == 1.0 else motion.scaled(scale))


def _run_batch(jobs, progress=None, **solver):
    """simulate_many, or scene by scene when the batch refuses a job: (responses, errors)."""
    from rockcli.solve import simulate_many

    try:
        return simulate_many(jobs, progress=progress, **solver), [""] * len(jobs)
    except RockcliInputError:
        responses, errors = [], []
        for job in jobs:
            try:
                responses.append(simulate_many([job], **solver)[0])
                errors.append("")
            except RockcliInputError as exc:
                responses.append(None)
                errors.append(str(exc))
        return responses, errors


def _linear_before_uplift(foundation) -> bool:
    """True when the motion before uplift is linear in the excitation (rigid, linear bearings).

    Then "no uplift at scale s" implies "no uplift at any smaller scale", which prunes the scan.
    """
    return isinstance(foundation, (Rigid, LinearIsolation))


def find_overturn_scales(scenes, *, grid=MARGIN_GRID, rtol: float = MARGIN_RTOL, known=None,
                         progress: Callable[[int], None] | None = None, batch: int = 4, **solver):
    """Smallest scale factor of the excitation that overturns each scene (see the module notes).

    Parameters
    ----------
    scenes : sequence of (block, foundation, motion)
        ``motion`` a Record or a pulse.
    grid : array
        Increasing scale factors scanned; 1 should be one of them.
    rtol : float
        Bisection stops when ``hi / lo - 1 <= rtol``.
    known : sequence of Response or None, optional
        Responses at scale 1 when already computed.
    progress : callable, optional
        ``progress(n)`` with the number of runs just done.
    batch : int
        Grid factors per scene per parallel batch of the scan.
    **solver
        Passed to :func:`rockcli.solve.simulate_many`.

    Returns
    -------
    list of (overturn_scale, survives_scale, note)
        ``overturn_scale`` overturns, ``survives_scale`` (< it, within rtol) survives; NaN and a
        note when nothing up to ``grid[-1]`` overturns; ``(grid[0], NaN, note)`` when ``grid[0]``
        already overturns.

    Notes
    -----
    The result is that of scanning every grid factor, then bisecting below the first overturning
    one. The scan is pruned without changing it: factors are visited downwards from 1 until the
    block no longer uplifts (for rigid and linear foundations the motion before uplift is linear
    in the scale, so no smaller factor uplifts either; on a rigid base the record's PGA tells
    this without a run), then, only for scenes that did not overturn at or below 1, upwards from
    1 until the first overturning factor.
    """
    from rockcli.solve import VERDICT_NO_UPLIFT, simulate_many

    grid = np.asarray(grid, dtype=float)
    n, m = len(scenes), grid.size
    # state[i, j]: 0 not run, 1 survives, 2 overturns, 3 survives without uplift
    state = np.zeros((n, m), dtype=np.int8)
    ones = np.flatnonzero(np.isclose(grid, 1.0))
    i1 = int(ones[0]) if ones.size else int(np.searchsorted(grid, 1.0))

    def code(r):
        return 2 if r.overturned else (3 if r.verdict == VERDICT_NO_UPLIFT else 1)

    def run(pairs):
        if not pairs:
            return
        pairs = _balanced([(i, j) for i, j in pairs], [_cost(scenes[i][2]) for i, _ in pairs])
        jobs = [_scaled_job(*scenes[i], float(grid[j])) for i, j in pairs]
        res = simulate_many(jobs, **solver)
        for (i, j), r in zip(pairs, res):
            state[i, j] = code(r)
        if progress is not None:
            progress(len(pairs))

    linear = [_linear_before_uplift(f) for _, f, _ in scenes]
    for i, (b, f, mo) in enumerate(scenes):
        if known is not None and ones.size:
            state[i, i1] = code(known[i])
        if isinstance(f, Rigid):
            state[i, grid * _peak(mo) < b.uplift_acceleration * (1 - 1e-9)] = 3
    # downwards from 1 (or from the top of the grid below 1)
    down = {i: list(range(min(i1, m - 1), -1, -1)) for i in range(n)}
    while True:
        pairs = []
        for i, js in down.items():
            taken = 0
            while js and taken < batch:
                j = js[0]
                if state[i, j] == 3 and linear[i]:
                    js.clear()
                    break
                js.pop(0)
                if state[i, j] == 0:
                    pairs.append((i, j))
                    taken += 1
        if not pairs:
            break
        run(pairs)
    # upwards from 1 for the scenes that have not overturned at or below 1
    up = {i: list(range(i1 + 1, m)) for i in range(n) if not (state[i, : i1 + 1] == 2).any()}
    while up:
        pairs = []
        for i, js in up.items():
            pairs += [(i, j) for j in js[:batch] if state[i, j] == 0]
            del js[:batch]
        run(pairs)
        up = {i: js for i, js in up.items() if js and not (state[i] == 2).any()}

    out = [None] * n
    lo, hi, active = np.zeros(n), np.zeros(n), []
    for i in range(n):
        idx = np.flatnonzero(state[i] == 2)
        if idx.size == 0:
            out[i] = (math.nan, grid[-1], f"no overturning up to {grid[-1]:g}x")
        elif idx[0] == 0:
            out[i] = (grid[0], math.nan, f"overturns already at {grid[0]:g}x, the smallest factor scanned")
        else:
            lo[i], hi[i] = grid[idx[0] - 1], grid[idx[0]]
            active.append(i)
    while active:
        mids = {i: math.sqrt(lo[i] * hi[i]) for i in active}
        res = simulate_many([_scaled_job(*scenes[i], mids[i]) for i in active], **solver)
        for i, r in zip(active, res):
            if r.overturned:
                hi[i] = mids[i]
            else:
                lo[i] = mids[i]
        active = [i for i in active if hi[i] / lo[i] - 1.0 > rtol]
    for i in range(n):
        if out[i] is None:
            out[i] = (float(hi[i]), float(lo[i]), "")
    return out


#: Scale factors of the neighbourhood check: 0.90, 0.91, ..., 1.10.
NEIGHBOURHOOD = np.round(np.linspace(0.9, 1.1, 21), 10)


def overturn_shares(scenes, *, factors=NEIGHBOURHOOD, progress=None, **solver) -> list[float]:
    """Share of the scale factors ``factors`` (default 0.90..1.10 in steps of 0.01) that overturn each scene.

    Near the overturning boundary the verdict can flip back and forth within a per cent of the
    amplitude (the boundary is ragged, not a single threshold); this share says how robust the
    verdict at scale 1 is: 0 or 1 robust, around 0.5 a coin toss within the uncertainty of any record.
    """
    from rockcli.solve import simulate_many

    pairs = [(i, float(s)) for i in range(len(scenes)) for s in factors]
    pairs = _balanced(pairs, [_cost(scenes[i][2]) for i, _ in pairs])
    res = simulate_many([_scaled_job(*scenes[i], s) for i, s in pairs], progress=progress,
                        chunk=max(1, len(pairs) // 50) if progress else None, **solver)
    count = np.zeros(len(scenes))
    for (i, _), r in zip(pairs, res):
        count[i] += r.overturned
    return list(count / len(factors))


def _cost(motion) -> float:
    """Rough cost of a run: the samples of a record (the solver steps at least once per sample)."""
    return float(motion.acc.size) if hasattr(motion, "acc") else 100.0


def _balanced(items, costs):
    """Items reordered so that the halves of the list (numba's static split over 2+ threads) cost alike."""
    order = sorted(range(len(items)), key=lambda k: -costs[k])
    return [items[k] for k in order[0::2]] + [items[k] for k in order[1::2]]


def _peak(motion) -> float:
    if hasattr(motion, "acc"):
        return float(np.max(np.abs(motion.acc)))
    return abs(float(motion.a_p))


def run_assessment(columns: Sequence[Block], excitations: Sequence[Excitation],
                   configurations: Sequence[Configuration], *, margin: bool = True, neighbourhood: bool = False,
                   unavailable: Sequence[Unavailable] = (), progress=None, **solver) -> Assessment:
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
        ``progress(n)`` after each chunk of ``n`` runs; :func:`count_runs` gives the total.
    **solver
        Passed to :func:`rockcli.solve.simulate_many` (``rtol``, ``tail``, ...).

    Returns
    -------
    Assessment
        Rows in the order column, excitation, configuration. Excitations that could not be read
        give rows with ``error`` set and no results.
    """
    import time

    if not columns:
        raise RockcliInputError("no column to assess: name a preset (bassae, nemea) or give a custom block")
    if not configurations:
        raise RockcliInputError("no isolation configuration to assess")
    timings = {}
    rows, scenes, run_rows = [], [], []
    for b in columns:
        for x in excitations:
            for c in configurations:
                row = _base_row(b, x, c)
                rows.append(row)
                if x.motion is not None:
                    scenes.append((b, c.foundation, x.motion))
                    run_rows.append(row)
    t0 = time.perf_counter()
    chunk_progress = None
    if progress is not None:
        chunk_progress = _Advance(progress)
    responses, errors = _run_batch([_scaled_job(*s, 1.0) for s in scenes], chunk_progress, **solver)
    timings["runs_s"] = time.perf_counter() - t0
    for row, r, err in zip(run_rows, responses, errors):
        if r is None:
            row.error = err
            continue
        row.verdict = r.verdict
        row.overturned = r.overturned
        row.theta_max_over_alpha = r.theta_max_over_alpha
        row.t_overturn_s = r.t_overturn_s
        row.t_uplift_s = r.t_uplift_s
        row.n_impacts = r.n_impacts
        row.base_disp_max_m = r.base_disp_max_m
    if margin:
        t0 = time.perf_counter()
        ok = [i for i, r in enumerate(responses) if r is not None]
        found = find_overturn_scales([scenes[i] for i in ok], known=[responses[i] for i in ok],
                                     progress=_Advance(progress) if progress else None, **solver)
        for i, (hi, lo, note) in zip(ok, found):
            run_rows[i].overturn_scale, run_rows[i].overturn_scale_survives, run_rows[i].margin_note = hi, lo, note
        timings["margin_s"] = time.perf_counter() - t0
    if neighbourhood:
        t0 = time.perf_counter()
        ok = [i for i, r in enumerate(responses) if r is not None]
        shares = overturn_shares([scenes[i] for i in ok], progress=_Advance(progress) if progress else None, **solver)
        for i, share in zip(ok, shares):
            run_rows[i].overturn_share_pm10 = share
        timings["neighbourhood_s"] = time.perf_counter() - t0
    return Assessment(list(columns), list(excitations), list(configurations), rows, list(unavailable), margin,
                      timings, neighbourhood)


class _Advance:
    """Adapts simulate_many's cumulative ``progress(n_done)`` to increments ``progress(n)``."""

    def __init__(self, progress):
        self.progress, self.done = progress, 0

    def __call__(self, n_done):
        self.progress(n_done - self.done)
        self.done = n_done


def count_runs(columns, excitations, configurations, margin: bool, neighbourhood: bool = False) -> int:
    """Runs for the progress bar: the scenes, plus the margin grid (an upper bound) and the neighbourhood."""
    n = len(columns) * sum(x.motion is not None for x in excitations) * len(configurations)
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
        b, c = blocks[row.column], confs[row.configuration]
        yield row, b, c, x, simulate(b, c.foundation, x.motion, history=True, **solver)


def safe_name(*parts: str) -> str:
    """A file-name stem from parts (``bassae_kobe-1995-takarazuka-000_Tb=2s`` -> safe characters only)."""
    text = "_".join(str(p) for p in parts)
    return re.sub(r"[^A-Za-z0-9.=+-]+", "_", text).strip("_")[:150] or "run"


__all__ = ["DEFAULT_ISOLATION", "MARGIN_GRID", "MARGIN_RTOL", "Assessment", "AssessmentRow", "Configuration",
           "Excitation", "Unavailable", "ROW_FIELDS", "column_title", "count_runs", "custom_column",
           "find_overturn_scales", "history_runs", "overturn_shares", "parse_column_spec", "parse_configurations",
           "resolve_excitations", "run_assessment", "safe_name", "table_ii_entries"]
