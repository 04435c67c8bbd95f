"""The slow, obviously correct reference: SciPy ``solve_ivp`` with events, one phase at a time.

Written independently of :mod:`rockcli.kernels` (never imports it, nor numba): the equations are
typed again from the paper (Eq 3; Eqs 7-11 with the reading-notes corrections; Eqs 33-38 for
sliding bearings), the impact map is obtained by solving the two momentum balances (Eqs 14 and 16)
as a 2x2 linear system instead of using the closed form, and the phases are chained in plain Python.
The same documented rules are applied: uplift threshold, rest criterion (with the base
acceleration), overturning at |theta| = pi/2. The end of the run takes no shortcut on a rigid
foundation: after the excitation the free rocking is followed until the block rests (the rest rule)
or overturns. On an isolated base a stuck block is followed until the free base provably cannot
lift it again (its oscillator energy bounds |a|), or the horizon.

Any of SciPy's methods (``RK45``, ``DOP853``, ``Radau``, ``LSODA``, ``BDF``) at any ``rtol``/``atol``
can integrate the phases; :class:`RefResult` also says how much work that took (steps, right-hand
sides, Jacobians, LU decompositions, wall time), which ``rockcli bench work-precision`` compares with
the kernel. SciPy is imported when a reference runs, not when this package is imported.

What is where, in reading order (every name is importable from ``rockcli.reference``):

* :mod:`~rockcli.reference.run`: :func:`reference_simulate` (any base, any method) and
  :func:`reference_sliding` (a hysteretic base with Radau's defaults).
* :mod:`~rockcli.reference.result`: :class:`RefResult`, :data:`METHODS`, the two failures.
* :mod:`~rockcli.reference.equations`: the ground motion as a function of time, the impact map
  (:func:`impact_map_linear_system`), the rocking accelerations on a moving base (Eqs 10-11), the
  state scales of the mixed error test.
* :mod:`~rockcli.reference.phases`: :class:`Phases`, the chain of stuck and rocking phases every
  base shares: the rocking phase, the impact and the rest rule, peaks and counts.
* :mod:`~rockcli.reference.linear`: the stuck phases on a rigid foundation and on linear bearings.
* :mod:`~rockcli.reference.hysteretic`: :class:`Bearing` (SCSS, lead-rubber, DCSS, with ``z`` as a
  state) and its stuck phase.
* :mod:`~rockcli.reference.ivp`: ``solve_ivp`` with the work counted, a wall budget and a record's
  samples as break points.
* :mod:`~rockcli.reference.stack` and :mod:`~rockcli.reference.stack_mechanics`: a stack of rocking blocks on
  the ground or on linear bearings (a body on its plinth), from the separate bodies' Newton-Euler equations with
  the contact constraints (:func:`reference_stack`, :func:`reference_plinth`; docs/physics-plinth.md); its run
  (:mod:`~rockcli.reference.stack_run`), the pattern after an impact (:mod:`~rockcli.reference.stack_impact`) and
  the hysteretic bearings (:mod:`~rockcli.reference.stack_hysteretic`).
* :mod:`~rockcli.reference.friction` and :mod:`~rockcli.reference.friction_mechanics`: a block or a body on its
  plinth with Coulomb friction at every contact (:func:`~rockcli.reference.friction.reference_friction`).
* :mod:`~rockcli.reference.friction_drums`: a column of drums with friction at every joint
  (:func:`~rockcli.reference.friction_drums.reference_drums`, docs/physics-drums.md); its mechanics in maximal
  coordinates (:mod:`~rockcli.reference.drum_mechanics`: faces at the ends of the overlap, pivots of kind A and B)
  and the pattern after an event by enumeration or a mixed-integer problem (:mod:`~rockcli.reference.drum_patterns`);
  with ``flight=True`` the drums may lift off, fly and land (:mod:`~rockcli.reference.drum_flight`: the contact law
  with flight, the gaps of a flying joint; :mod:`~rockcli.reference.drum_flight_run`: its run).

The test suite's ``tests/naive.py`` and ``tests/naive_sliding.py`` re-export this package.
"""

from rockcli.reference.equations import (ground_function, impact_map_linear_system, is_hysteretic, rocking_on_base,
                                         state_scales)
from rockcli.reference.hysteretic import Bearing
from rockcli.reference.phases import Phases
from rockcli.reference.result import IMPLICIT, METHODS, RefResult, ReferenceFailure, ReferenceTimeout
from rockcli.reference.run import reference_simulate, reference_sliding
from rockcli.reference.stack import StackRefResult, reference_plinth, reference_stack

__all__ = ["IMPLICIT", "METHODS", "Bearing", "Phases", "RefResult", "ReferenceFailure", "ReferenceTimeout",
           "StackRefResult", "ground_function", "impact_map_linear_system", "is_hysteretic", "reference_plinth",
           "reference_simulate", "reference_sliding", "reference_stack", "rocking_on_base", "state_scales"]
