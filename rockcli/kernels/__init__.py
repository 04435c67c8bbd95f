"""Compiled kernels (numba): the only package of rockcli that imports numba.

Files (data flows down this list):

========================  ======================================================================
``layout``                codes and array layouts shared with :mod:`rockcli.solve` (plain Python)
``cache``                 numba's disk cache keyed on the sources of this whole package
``jit``                   ``@kernel``: the ``njit`` options every kernel function shares
``ground``                ground motion: pulses, segments, the rigid-foundation uplift scan, the
                          remaining ground impulse
``polynomials``           the dense-output quartics: evaluation, first crossings and excursions
``bearings``              the bearings' force per foundation family; the Bouc-Wen element solved
                          exactly along the path of u (the stiff treatment); the DCSS slider
``linear_base``           the linear base carrying the standing block in closed form (the exact
                          step per sample interval, the lift-off inside it, the peak of a record;
                          the norm and the record table of the early stop P9)
``rhs``                   right-hand sides (rigid, isolated: stuck and rocking)
``dopri``                 the Dormand-Prince 5(4) step, its error norm and dense output
``events``                impact map, rest rule, uplift on a hysteretic base, reversals, history rows
                          (step, peak and uniform-grid rows)
``steps``                 what both drivers share: run record, segments, step-size control, the
                          events of a rocking step in theta, impact bookkeeping
``rigid``                 :func:`simulate_rigid`: a block on a rigid foundation (two states; the
                          end-of-run proofs P1, P2, P4, P6, P7 in its notes)
``driver_phases``         the isolated-base driver's step and phases (stuck, rocking, the impact), the anchor
                          of the hysteretic elements in the run record
``driver_end``            the end of a run on an isolated base: the rule and the theorems it checks
``driver``                :func:`simulate_core`: a block on an isolated base as a loop over phases
                          (proofs P3, P3s, P5, P8, and the early stops P9, P9s during the
                          excitation, stated in ``driver_end``)
``stack_physics``         a body on a free plinth: the equations of both rocking, contact forces, impacts
``stack_step``            what the stack driver reads along a step: its record ``xo``, the faces' corner
                          forces, impacts ahead, peaks, the friction demand
``stack_patterns``        the stack driver's changes of pattern and rest rules
``stack``                 :func:`simulate_stack`: the body on its plinth on a rigid foundation (the
                          rigid driver's code for one rocking body, the 2x2 system for both)
``stack_linear_physics``  the body on its plinth on bearings (linear, sliding, lead-rubber): every
                          pattern's equations with the base, impacts in maximal coordinates with the
                          base (a small KKT system)
``stack_linear_step``     one step of the stack driver on bearings: Dormand-Prince on six states, its
                          continuous extension, the events on it, what is read along it
``stack_linear``          :func:`rockcli.kernels.stack_linear.simulate_stack_linear`: the body on its
                          plinth on bearings (the hysteretic elements along the path of u, impacts,
                          rest rules, the end of the run)
``batch``                 :func:`simulate_batch_rigid`, :func:`simulate_batch`,
                          :func:`simulate_batch_rigid_vertical`: many verdict-only scenes in
                          parallel, one entry per driver (and one for a vertical motion);
                          :func:`prepare` gets them ready (compiled side by side on the first run
                          on a machine)
========================  ======================================================================

Every physical constant reaches the kernels as an argument (the ``prm`` tuple); module-level
names are codes, indices and the fixed coefficients of the integration method.

Compile time (a cold cache compiles every kernel: about two minutes of CPU). Every function is decorated
``@kernel`` (:mod:`rockcli.kernels.jit`: ``njit(cache=True, no_cfunc_wrapper=True)``, without the C-ABI
wrapper the kernels never need). Integers passed to compiled functions are int64 values, never literals
(:mod:`rockcli.kernels.layout`). ``benchmarks/bench_compile.py`` measures the cold compile of each driver.
"""

from rockcli.kernels import cache as _cache

_cache.install()  # before any @kernel (njit(cache=True)) of this package is applied

from rockcli.kernels.layout import *  # noqa: E402,F401,F403
from rockcli.kernels.layout import N_PRM  # noqa: E402,F401
from rockcli.kernels.ground import (_impulse_left, _pulse_segment, _pulse_turns, _rigid_uplift,  # noqa: E402,F401
                                    pulse_acc)
from rockcli.kernels.polynomials import (_first_down, _first_exceed, _golden_max, _poly,  # noqa: E402,F401
                                         _refine_root)
from rockcli.kernels.bearings import (base_force, bw_phi, bw_phi_inv, bw_slope, dcss_split,  # noqa: E402,F401
                                      force_along_path, free_force_bound, reanchor)
from rockcli.kernels.dopri import _dense, _dp5_step, _state_at  # noqa: E402,F401
from rockcli.kernels.rigid import simulate_rigid, simulate_rigid_vertical  # noqa: E402,F401
from rockcli.kernels.driver import simulate_core  # noqa: E402,F401
from rockcli.kernels.batch import (BATCH_KERNELS, prepare, simulate_batch, simulate_batch_rigid,  # noqa: E402,F401
                                   simulate_batch_rigid_vertical)
from rockcli.kernels.stack import simulate_stack  # noqa: E402,F401
