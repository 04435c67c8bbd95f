"""A record's rocking spectrum: the peak rotation ``|theta|_max / alpha`` against the block size ``R``.

Makris & Konstantinidis (2003) plot, for one accelerogram, how far blocks of one slenderness rock as
a function of their size, the way a response spectrum plots an oscillator's peak against its period.
Here a curve is one slenderness ``alpha`` on one foundation (the rigid ground or an isolated base
with its own ``T_b``, ``xi``, ``gamma``: a record has no pulse period, so ``T_b`` is in seconds, as in
``rockcli simulate``) over the semi-diagonals ``R`` of a :func:`size_grid`; the frequency parameter
``p = sqrt(3 g / 4 R)`` is the second axis. The rigid and the isolated curves of one ``alpha`` side
by side answer "for which sizes does isolation help under this record".

Every point is one run of :func:`rockcli.solve.simulate_verdicts` (through the
:class:`~rockcli.spectra.runner.Runner`, so on this machine or on a Dask cluster) with
``early=False``: the run follows the motion to its end and stops only once the verdict is proven,
and the end-of-run proofs (P2, P3, P5 of :mod:`rockcli.kernels`) add every later peak to
``theta_max``, so the peak is final (``peak_final``) and the point is the same run, bit for bit, as
``rockcli simulate`` of that block (``tests/test_spectrum_rocking.py`` checks it). ``early=True``
would stop a run once survival is proven while the ground still moves, leaving only a lower bound
of the peak: no use for a spectrum of peaks.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Optional, Sequence

import numpy as np

from rockcli.errors import RockcliInputError
from rockcli.models import R_RANGE_M, Block
from rockcli.spectra.grids import MAX_CELLS, parse_grid
from rockcli.spectra.runner import Runner
from rockcli.io.units import G


def size_grid(text: str, option: str = "--R") -> np.ndarray:
    """Block sizes ``R`` [m] from ``start:stop:count``: ``count`` values from ``start`` to ``stop``, both
    included, evenly spaced on a log axis (``numpy.geomspace``), within the supported sizes."""
    grid = parse_grid(text, option, positive=True)
    lo, hi = R_RANGE_M
    if grid.start < lo or grid.stop > hi:
        raise RockcliInputError(f"{option} {str(text).strip()!r}: block sizes must lie between {lo:g} m and "
                                f"{hi:g} m")
    values = np.geomspace(grid.start, grid.stop, grid.count)
    values[0], values[-1] = grid.start, grid.stop  # exactly as written
    return values


def frequency_parameter(R) -> np.ndarray:
    """``p = sqrt(3 g / 4 R)`` [rad/s] of blocks of semi-diagonal ``R`` [m] (a solitary block)."""
    return np.sqrt(0.75 * G / np.asarray(R, dtype=float))


@dataclass(frozen=True)
class RecordFamily:
    """Blocks of one slenderness on one foundation under one record: the Runner's cells ``(x, y)`` are
    the block ``R = x`` [m] under the record times ``y`` (the spectrum runs ``y = 1``)."""

    alpha_deg: float
    foundation: object
    record: object
    #: a :class:`rockcli.spectra.plinth.PlinthRatio` every block stands on (None: alone)
    plinth: Optional[object] = None

    def scene(self, x: float, y: float):
        """``(block or stack, foundation, record)`` of the block ``R = x`` (on its plinth, scaled with it); the
        Runner passes ``y`` to the batch as the record's scale factor."""
        block = Block.from_degrees(float(x), self.alpha_deg)
        return (block if self.plinth is None else self.plinth.stack(block)), self.foundation, self.record


@dataclass(frozen=True)
class RockingCurve:
    """Peaks of blocks of one slenderness on one foundation over the sizes ``R``.

    ``theta_max_over_alpha`` is the run's peak ``|theta|/alpha`` (``pi/(2 alpha)`` where the block
    overturned, as everywhere in rockcli); :attr:`plotted` caps it at 1 for the figure.
    """

    alpha_deg: float
    foundation: object
    R: np.ndarray
    theta_max_over_alpha: np.ndarray
    overturned: np.ndarray
    uplifted: np.ndarray
    settled: np.ndarray
    peak_final: np.ndarray
    #: the plinth the blocks stand on (None: alone); ``toppled`` per size: 0 none, 1 the body, 2 the plinth
    plinth: Optional[object] = None
    toppled: Optional[np.ndarray] = None

    @property
    def p(self) -> np.ndarray:
        return frequency_parameter(self.R)

    @property
    def isolation(self) -> str:
        """The foundation's spec with every parameter resolved (``none``, ``linear:Tb=2.5,xi=0.05,gamma=0.01``)."""
        return self.foundation.label

    @property
    def proven(self) -> np.ndarray:
        """The verdict is proven (not a run still moving at the solver's horizon)."""
        return np.asarray(self.settled, bool) | np.asarray(self.overturned, bool)

    @property
    def plotted(self) -> np.ndarray:
        """``theta_max_over_alpha``, 1 where the block overturned."""
        return np.where(self.overturned, 1.0, self.theta_max_over_alpha)


def rocking_spectrum(record, alphas_deg: Sequence[float], foundations: Sequence, R: Sequence[float], *,
                     runner: Optional[Runner] = None, progress=None,
                     plinths: Sequence = (None,)) -> list[RockingCurve]:
    """The rocking spectra of ``record`` for every ``alpha x foundation`` (in that nesting order).

    Parameters
    ----------
    record : Record
        The ground motion (already scaled if wanted; :meth:`rockcli.records.Record.scaled`).
    alphas_deg : sequence of float
        Slenderness values [degrees].
    foundations : sequence
        :class:`rockcli.models.Rigid` or isolated bases (:func:`rockcli.models.parse_isolation_spec`).
    R : sequence of float
        Semi-diagonals [m] (:func:`size_grid`).
    runner : Runner, optional
        Where the runs go (its horizon, restitution and cap ratio apply to every run); default this machine.
    progress : callable, optional
        ``progress(n)`` with the number of runs finished since the last call.
    plinths : sequence, optional
        None (the block alone) and/or :class:`rockcli.spectra.plinth.PlinthRatio` plinths in proportion to each
        block (the stack driver: its peaks are final too).

    Returns
    -------
    list of RockingCurve
        One per ``(alpha, foundation, plinth)``, peaks final (``early=False``, see the module notes).
    """
    from rockcli.io.inputs import as_list, check_type
    from rockcli.records.record import Record
    from rockcli.solve import check_foundation
    from rockcli.spectra.arguments import as_alphas, as_plinths, as_values

    check_type(record, Record, "record", "a rockcli Record (read_record(...))")
    alphas_deg = as_alphas(alphas_deg)
    foundations = [check_foundation(f, "foundations: each foundation")
                   for f in as_list(foundations, "foundations", "a list of foundations (Rigid(), ...)")]
    R = as_values(R, "R", positive=True)
    plinths = as_plinths(plinths)
    families = [RecordFamily(float(a), f, record, pl) for a in alphas_deg for f in foundations for pl in plinths]
    n = len(families) * R.size
    if n > MAX_CELLS:
        raise RockcliInputError(f"the spectrum has {n:,} runs (slenderness x foundation x size); at most "
                                f"{MAX_CELLS:,} are run at once: use fewer sizes or configurations")
    for fam in families:  # every block is valid before any run (one sentence from Block otherwise)
        for x in {R.min(), R.max()} if R.size else ():
            fam.scene(x, 1.0)
    runner = runner or Runner()
    fam_index = np.repeat(np.arange(len(families)), R.size)
    cells = runner(families, fam_index, np.tile(R, len(families)), np.ones(n), progress=progress, early=False)
    curves = []
    for k, fam in enumerate(families):
        s = slice(k * R.size, (k + 1) * R.size)
        curves.append(RockingCurve(fam.alpha_deg, fam.foundation, R.copy(), cells.theta_max_over_alpha[s],
                                   cells.overturned[s], cells.uplifted[s], cells.settled[s], cells.peak_final[s],
                                   fam.plinth, None if fam.plinth is None else cells.toppled[s]))
    return curves


def isolation_helps(rigid: RockingCurve, isolated: RockingCurve) -> np.ndarray:
    """Where the isolated base lowers the peak of the rigid foundation's block (per size; an overturning
    block counts as the largest peak): True/False per ``R``."""
    if not np.array_equal(rigid.R, isolated.R):
        raise ValueError("the curves must share their sizes")

    def rank(c):  # an overturning block above every peak, also a survivor's above 1 (it passed alpha and came back)
        return np.where(np.asarray(c.overturned, bool), np.inf, np.asarray(c.theta_max_over_alpha, float))

    return rank(isolated) < rank(rigid)


def size_ranges(R: np.ndarray, mask: np.ndarray) -> list[tuple[float, float]]:
    """The runs of consecutive ``True`` in ``mask`` as ``(R_first, R_last)`` pairs [m]."""
    out = []
    start = None
    for i, m in enumerate(np.asarray(mask, bool).tolist() + [False]):
        if m and start is None:
            start = i
        elif not m and start is not None:
            out.append((float(R[start]), float(R[i - 1])))
            start = None
    return out


def describe_sizes(ranges) -> str:
    """``0.2-1.5 m, 3.1-20 m`` (``none`` when empty)."""
    if not ranges:
        return "none"
    return ", ".join(f"{a:.3g} m" if a == b else f"{a:.3g}-{b:.3g} m" for a, b in ranges)

