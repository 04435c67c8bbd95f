"""The friction check of a run (``simulate --friction MU``): the peak friction demand ``|T|/N`` of a single block
on the ground from its history, and the judgement "the demand exceeds ``MU``" (docs/plinth.md, "Friction").

The judgement, stated once here and tested:

* **continuous demand**: the ratio of the tangential to the normal contact force while the contact carries the
  motion (rest, rocking). It *exceeds* ``MU`` when its peak over the run is strictly above ``MU``: at that instant
  a friction coefficient of ``MU`` cannot hold the contact, the interface would slide, and the rocking-only model
  no longer describes the motion from there. A jump (``N <= 0``) is a demand of ``inf``: it exceeds every ``MU``.
* **impulsive demand**: the ratio of the impulses at an impact, ``(h/b)(1 - eta)/(1 + eta)`` for a single block
  (``eta`` the impact ratio; the stack's from its impact law). It is reported apart and flagged apart: an impact
  lasts an instant, so a ratio above ``MU`` means a slip during the impact (a small jump of the contact point),
  which the instantaneous impact law does not model, not a sliding motion.
* For a block that **topples** the normal force tends to 0 as it falls and the demand grows without bound: its
  peak says nothing then (the topple is the answer). The single block's peak is read while ``|theta| <= alpha``
  only when it overturns; the stack driver reports its own.

The single block's demand is read at the rows of a history on a uniform grid (:func:`friction_grid_dt`) with the
event rows; the rows at an impact (``theta = 0`` with the block moving: the pivot is ambiguous at that instant)
are left out, the rows on either side kept. It is therefore a sampled peak: between rows it may be higher by what
the demand changes within one grid step.
"""

from __future__ import annotations

import math

import numpy as np

from rockcli.errors import RockcliInputError


def check_friction(mu, option: str = "--friction") -> float:
    """``mu`` as a float when it is a finite friction coefficient > 0 (at most 10), else one sentence."""
    try:
        value = float(mu)
    except (TypeError, ValueError):
        value = math.nan
    if not (math.isfinite(value) and 0.0 < value <= 10.0):
        raise RockcliInputError(f"{option} must be a friction coefficient between 0 (excluded) and 10, got {mu!r}")
    return value


def friction_grid_dt(excitation) -> float:
    """The grid [s] of the history the single block's demand is read on: the record's own sample interval
    (at rest the demand is ``|ag|/g``, largest at a sample), 1/400 of a pulse's period, 2 ms without motion."""
    if excitation is None:
        return 2e-3
    if hasattr(excitation, "acc"):
        return float(excitation.dt)
    return float(excitation.T_p) / 400.0


def friction_peak_single(block, response) -> tuple[float, float]:
    """``(peak demand, its time [s])`` of a single block on a rigid foundation, from ``response``'s history
    (:func:`rockcli.solve.simulate` with ``history=True``). See the module notes for the rows read."""
    from rockcli.solve.stack import friction_demand_single

    H = response.history
    if H is None:
        raise RockcliInputError("the friction demand is read from a history run (simulate(..., history=True))")
    rows = H.rows
    t, ag, th, thd = rows[:, 0], rows[:, 1], rows[:, 2], rows[:, 3]
    events = np.asarray(H.row_event, dtype=object)
    keep = ~((th == 0.0) & (thd != 0.0)) & (events != "impact")
    if response.overturned:
        keep &= np.abs(th) <= block.alpha
    if not np.any(keep):
        return 0.0, math.nan
    demand = friction_demand_single(block, th[keep], thd[keep], ag[keep])
    i = int(np.argmax(demand))
    return float(demand[i]), float(t[keep][i])


def impulsive_demand_single(block, eta: float) -> float:
    """The impulses' ratio ``|T|/N`` at an impact of a single block on the ground, ``(h/b)(1 - eta)/(1 + eta)``."""
    return block.h / block.b * (1.0 - eta) / (1.0 + eta)
