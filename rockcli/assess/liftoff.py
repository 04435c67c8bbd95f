"""The lift-off floor of a scene: a scale factor below which the block provably never leaves its base.

Before the block first lifts off, it moves with its foundation, and on a rigid foundation or on
linear bearings that motion is linear in the scale factor ``s`` of the excitation (the run starts
from rest; the scale multiplies the ground acceleration). The block lifts off where the absolute
acceleration of what it stands on first exceeds ``g tan(alpha)`` in magnitude, so with ``M`` an
upper bound of that acceleration over the whole run at ``s = 1``, no run at ``s < g tan(alpha)/M``
lifts the block: its verdict is ``no_uplift``, it cannot overturn, and its run is proven (settled)
before the solver's horizon. :func:`liftoff_floors` returns that factor for each scene (with a
safety margin), and the margin search (:mod:`rockcli.assess.margin`) never runs a factor below it.

* Rigid foundation: ``M`` = the peak of ``|ag|`` (a record's largest sample: the kernel reads a
  record as linear between samples; a pulse's ``|a_p|``), exactly what the kernel's uplift scan
  compares with ``g tan(alpha)`` (:func:`rockcli.kernels.ground._rigid_uplift`). Under a vertical
  ground motion (never scaled) the threshold is ``(g + a_v) tan(alpha) >= (g + min a_v) tan(alpha)``,
  so that lower bound takes the place of ``g tan(alpha)``. A block that stands on a rigid foundation
  after the excitation is at rest: its run is proven at once. Margin :data:`RIGID_MARGIN` (1e-9
  relative) for the rounding of ``s * acc``.
* Linear bearings under a record: ``M`` from one exact run of the base alone at ``s = 1``
  (:func:`rockcli.kernels.linear_base.stuck_peak`: the piecewise-exact solution, a rigorous bound
  inside every sample interval, and after the record P3's bound, which bounds every later ``|a|``);
  P3 proves the run (``s`` times its bound is below ``g tan(alpha)`` from ``t_proof`` on) when
  ``t_proof`` lies before the horizon, else the floor is 0. The solver's stuck phase on linear
  bearings under a record is the same solution (:func:`rockcli.kernels.driver_phases._linear_stuck_step`:
  the same coefficients, the same arithmetic, ``s`` times the samples), so the run at ``s`` differs
  from ``s`` times the run at 1 by rounding only: a relative ``n eps`` at most after ``n`` steps of a
  recurrence that never amplifies (the transition matrix's energy norm is at most 1), about 1e-11
  for 120,000 steps (600 s of 5 ms samples). Margin :data:`LINEAR_MARGIN` = 1e-9.
* A body on a free plinth (:class:`rockcli.models.Stack`) on a rigid foundation: ``M`` the peak of ``|ag|`` as
  above, and in place of ``g tan(alpha)`` the smaller of the stack's two static thresholds (the body off the still
  plinth, ``g tan(alpha1)``; the assembly off the ground, ``g tan(alpha_asm) = g b2/y_c``), as the stack driver
  builds them. Proof: the stack starts at rest (pattern R: both interfaces faces) and, at rest, its contact
  forces are linear in ``ag`` (docs/physics-plinth.md, "Uplift: leaving each pattern", from rest): the joint's
  unloading corner force reaches 0 exactly at ``|ag| = g tan(alpha1)``, the base's at ``|ag| = g tan(alpha_asm)``,
  and the stack driver leaves R at the first time ``|ag|`` exceeds the smaller of the two
  (:func:`rockcli.kernels.ground._rigid_uplift` with that threshold, or the body's own stuck scan, the single
  block's, when the body's threshold is the smaller). While ``s M`` stays below that threshold the run never leaves
  R: its verdict is ``no_uplift``, nothing overturns, and after the excitation R is proven at once (P1). No
  vertical motion (the stack refuses it). Margin :data:`RIGID_MARGIN` for the rounding of ``s * acc``.
  Tested against every factor of a scan on random stacks and motions (tests/test_plinth_cli.py).
* A body on a free plinth on linear bearings under a record: at rest the body, the plinth and the base move as one
  rigid mass on the bearings, a linear oscillator of the same ``omega_b`` and ``xi`` as a single block's base (the
  stack's ``gamma`` counts body and plinth as the mass the base carries, docs/physics-plinth.md, "On linear
  bearings"), so ``M`` is the single block's (:func:`rockcli.kernels.linear_base.stuck_peak`, with P3 after the
  record), and each block's patterns are the rigid foundation's with the base's absolute acceleration in place of
  ``ag``: the stack leaves rest where ``|a_b|`` first exceeds the smaller static threshold, as above. The stack
  driver integrates its rest phase by Dormand-Prince (not by the exact recurrence), so its ``a_b`` differs from
  ``s`` times the exact one by the integration error (relative ``rtol``, 5e-9 by default, at most
  :data:`STACK_LINEAR_RTOL_MAX` = 1e-5 for this floor, else 0; a damped oscillator does not amplify it); margin
  :data:`STACK_LINEAR_MARGIN` = 1e-3, far above it and a tenth of the grid's 1 % step
  (tested: at the floor nothing lifts, on random stacks, bearings and records, tests/test_plinth_floor.py).
* A body with friction (:class:`rockcli.solve.slide_many.Sliding`, friction as a model) on a rigid foundation: it
  fails by toppling or by sliding off its plinth, and either needs it to leave rest first. At rest its contact forces
  are affine in ``ag`` with ``T_j/N_j = ag/g`` at every contact, so it leaves rest where ``|ag|`` first exceeds ``g``
  times the smallest of each contact's ``mu_j`` (a slip) and ``tan(alpha_j)`` (everything above contact ``j`` tipping
  as one body), and the friction driver scans for exactly that band (:func:`rockcli.kernels.ground.band_exit`):
  ``M`` the peak of ``|ag|``, that threshold in place of ``g tan(alpha)``. Margin :data:`RIGID_MARGIN`. On bearings:
  floor 0.
* Anything else (sliding and lead-rubber bearings, a pulse on linear bearings, a scene the solver
  would refuse): floor 0, every factor may need a run.
"""

from __future__ import annotations

import math

import numpy as np

#: Relative safety margin of the rigid foundation's floor (rounding of ``s * acc`` in the kernel).
RIGID_MARGIN = 1e-9
#: Relative safety margin of the floor on linear bearings (see the module notes).
LINEAR_MARGIN = 1e-9
#: Relative safety margin of a plinth's floor on linear bearings (see the module notes).
STACK_LINEAR_MARGIN = 1e-3
#: The loosest ``rtol`` for which that margin is taken (looser: floor 0).
STACK_LINEAR_RTOL_MAX = 1e-5
#: After the record, ``stuck_peak`` stops where P3's bound is within this of the bound so far.
P3_SLACK = 1e-3
#: ``stuck_peak`` refines its bound inside the sample intervals to this relative width.
PEAK_TOL = 1e-6


def _peak(motion) -> float:
    """Peak ``|ag|`` [m/s^2]: a record's largest sample, a pulse's ``|a_p|``."""
    if hasattr(motion, "acc"):
        return float(np.max(np.abs(motion.acc)))
    return abs(float(motion.a_p))


def _vertical_low(motion, solver: dict, g: float) -> float:
    """The lowest vertical ground acceleration of a rigid-foundation scene [m/s^2] (0 without one, or above 0)."""
    from rockcli.solve import attached_vertical
    from rockcli.solve.excitation import _vertical_arrays

    vertical = solver.get("vertical")
    if vertical is None:
        vertical = attached_vertical(motion)
    if vertical is None:
        return 0.0
    vacc = _vertical_arrays(vertical, motion, None, g)[0]
    return min(0.0, float(np.min(vacc)))


def liftoff_floor(block, foundation, motion, **solver) -> float:
    """The factor below which the scene provably never lifts off (see the module notes); 0 when unknown."""
    from rockcli.errors import RockcliInputError
    from rockcli.models import LinearIsolation, Rigid
    from rockcli.solve import DEFAULT_HORIZON, DEFAULT_REST_TOL, _parameters, attached_vertical
    from rockcli.io.units import G

    from rockcli.models import Stack
    from rockcli.solve.slide_many import Sliding

    if isinstance(block, Sliding):
        return _sliding_floor(block, foundation, motion)
    if isinstance(block, Stack):
        return _stack_floor(block, foundation, motion, **solver)
    try:
        if isinstance(foundation, Rigid) or foundation is None:
            thr = block.uplift_acceleration * (1.0 + _vertical_low(motion, solver, G) / G)
            peak = _peak(motion)
            return math.inf if peak == 0.0 else thr / peak * (1.0 - RIGID_MARGIN)
        m = _linear_base_peak(block, foundation, motion, **solver)
        if m is None:
            return 0.0
        from rockcli.solve.options import _kernel

        _, prm = _parameters(block, foundation, solver.get("rtol"), float(solver.get("rest_tol", DEFAULT_REST_TOL)),
                             solver.get("restitution"), solver.get("cap_ratio", 0.0) or 0.0)
        return math.inf if m == 0.0 else float(prm[_kernel().P_THR]) / m * (1.0 - LINEAR_MARGIN)
    except (RockcliInputError, TypeError, ValueError):
        return 0.0


def _sliding_floor(sliding, foundation, motion) -> float:
    """A body with friction on the rigid ground (module notes): ``g min_j(mu_j, tan(alpha_j)) / M``; 0 elsewhere."""
    from rockcli.io.units import G
    from rockcli.kernels import chain as ch
    from rockcli.models import Rigid
    from rockcli.solve.slide import chain_parameters

    if not (foundation is None or isinstance(foundation, Rigid)):
        return 0.0
    cp = chain_parameters(sliding.subject, sliding.mu)
    n = int(cp[ch.CP_N])
    thr = G * min(min(cp[ch.CP_BLK + ch.NF_BLK * j + ch.F_MU], math.tan(cp[ch.CP_BLK + ch.NF_BLK * j + ch.F_AREST]))
                  for j in range(n))
    peak = _peak(motion)
    return math.inf if peak == 0.0 else thr / peak * (1.0 - RIGID_MARGIN)


def _linear_base_peak(block, foundation, motion, **solver):
    """``M``: the bound of the absolute acceleration of a standing body's linear base over the whole run at ``s = 1``
    (module notes), or None when there is none (not linear bearings, not a record, a vertical motion, or P3 does
    not prove the run before the horizon)."""
    from rockcli.models import LinearIsolation
    from rockcli.solve import DEFAULT_HORIZON, DEFAULT_REST_TOL, _parameters, attached_vertical

    if not (isinstance(foundation, LinearIsolation) and hasattr(motion, "acc")):
        return None
    if solver.get("vertical") is not None or attached_vertical(motion) is not None:
        return None  # refused on bearings: the runs say why
    from rockcli.kernels.linear_base import stuck_peak
    from rockcli.solve.excitation import _samples
    from rockcli.solve.options import _kernel

    _, prm = _parameters(block, foundation, solver.get("rtol"), float(solver.get("rest_tol", DEFAULT_REST_TOL)),
                         solver.get("restitution"), solver.get("cap_ratio", 0.0) or 0.0)
    k = _kernel()
    acc, dt = _samples(motion, "record")
    t_limit = (acc.size - 1) * dt + float(solver.get("horizon", DEFAULT_HORIZON))
    m, t_proof = stuck_peak(float(prm[k.P_W]), float(prm[k.P_XI]), acc, dt, 1.0, t_limit, P3_SLACK, PEAK_TOL)
    return float(m) if math.isfinite(t_proof) else None


def load_floor_kernel() -> None:
    """Load (or compile) the kernel of the floor on linear bearings, :func:`rockcli.kernels.linear_base.stuck_peak`,
    with the argument types :func:`liftoff_floor` calls it with, on a record of two zero samples (its result is
    not used). :func:`rockcli.assess.run_assessment` does it on a caller thread while the verdicts run, so that
    loading it does not hold up the margin search that follows."""
    from rockcli.kernels.linear_base import stuck_peak

    stuck_peak(1.0, 0.1, np.zeros(2), 0.01, 1.0, 1.0, P3_SLACK, PEAK_TOL)


def _stack_floor(stack, foundation, motion, **solver) -> float:
    """A body on a plinth: the smaller static threshold over the peak of what it stands on (module notes), on a rigid
    foundation or on linear bearings under a record; 0 on any other foundation (every factor may need a run)."""
    from rockcli.errors import RockcliInputError
    from rockcli.models import Rigid

    if solver.get("vertical") is not None:
        return 0.0
    if not (foundation is None or isinstance(foundation, Rigid)):
        if solver.get("rtol") is not None and float(solver["rtol"]) > STACK_LINEAR_RTOL_MAX:
            return 0.0  # an integration error that could approach the margin
        try:
            m = _linear_base_peak(stack.body, foundation, motion, **solver)
            if m is None:
                return 0.0
            from rockcli.solve import DEFAULT_REST_TOL
            from rockcli.solve.options import _kernel
            from rockcli.solve.stack import stack_parameters

            k = _kernel()
            rest_tol = float(solver.get("rest_tol", DEFAULT_REST_TOL))
            prm, prm_asm, _ = stack_parameters(stack, solver.get("rtol"), rest_tol, solver.get("restitution"))
            thr = min(float(prm[k.P_THR]), float(prm_asm[k.P_THR]))
        except (RockcliInputError, TypeError, ValueError):
            return 0.0
        return math.inf if m == 0.0 else thr / m * (1.0 - STACK_LINEAR_MARGIN)
    try:
        from rockcli.solve import DEFAULT_REST_TOL
        from rockcli.solve.options import _kernel
        from rockcli.solve.stack import stack_parameters

        k = _kernel()
        prm, prm_asm, _ = stack_parameters(stack, solver.get("rtol"), float(solver.get("rest_tol", DEFAULT_REST_TOL)),
                                           solver.get("restitution"))
        thr = min(float(prm[k.P_THR]), float(prm_asm[k.P_THR]))  # the thresholds the stack driver compares |ag| with
        peak = _peak(motion)
    except (RockcliInputError, TypeError, ValueError):
        return 0.0
    return math.inf if peak == 0.0 else thr / peak * (1.0 - RIGID_MARGIN)


def liftoff_floors(scenes, **solver) -> np.ndarray:
    """:func:`liftoff_floor` of each ``(block, foundation, motion)``; one bound per distinct scene."""
    out = np.zeros(len(scenes))
    seen = {}
    for i, (b, f, mo) in enumerate(scenes):
        key = (id(b), id(f), id(mo))
        if key not in seen:
            seen[key] = liftoff_floor(b, f, mo, **solver)
        out[i] = seen[key]
    return out
