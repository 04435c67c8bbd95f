"""The slow reference of a stack of rocking blocks on a rigid foundation or on linear bearings (a body on its plinth:
two blocks): SciPy ``solve_ivp`` with events for every contact change, phases chained in plain Python.

Written independently of :mod:`rockcli.kernels` and of the closed forms of docs/physics-plinth.md: the
mechanics are the separate bodies' Newton-Euler equations with the contact constraints of each pattern
(:class:`rockcli.reference.stack_mechanics.StackModel`), for any number of blocks. The rules are those of the
note:

* At rest every interface is a face; the face forces are linear in ``ag``, so the ground motion is scanned for
  the first ``ag`` at which a corner force of some face reaches 0, solved by ``brentq``; that face opens about its
  other corner.
* Rocking: the relative angles of the pivots are integrated; terminal events: a pivot's angle back to 0 (an
  impact), a pivot's angle at ``pi/2`` (the block above it topples), a corner force of a face down to 0 (the face
  opens about its other corner; while a face is watched the steps stay below ``0.02/p`` of the fastest block, so
  that a short dip of its force below 0 is not stepped over).
* Impact at interface ``j``: every candidate pattern after it (the interfaces at angle 0 free to be a face or
  either pivot; the others keep their pivot) gets its velocities from the plastic impact (impulses at its own
  constraints) or, with a restitution ``E``, from the energetic rule (the impacting pivot's new rate is ``E`` times
  the largest the kinetic energy allows); the one whose impulses press (every corner impulse >= 0) and whose new
  pivots open is taken. A persistent pivot's impulse is not required to press: a pulling one is counted as a
  jump (``n_jumps``; the rocking-only assumption fails there).
* Rest: after an impact with every angle at 0, the whole stack is at rest when nothing could lift it from rest
  and its kinetic energy is below ``rest_tol`` times the smallest slenderness-weighted restoring moment; else, an
  impact that leaves the impacting interface pivoting sticks it again (plastic, momentum kept along the other
  pivots) when the ground and the rest of the stack could not open it (both corners' relative accelerations
  restore it) and the rotation it could still reach against the smaller of them is below ``rest_tol`` times its
  slenderness. Both are the single block's rule for one block.
* The run ends at rest after the excitation, when a block topples, or ``horizon`` after the excitation.

On linear bearings (``base``, :func:`stack_base`; docs/physics-plinth.md "On linear bearings") the base's
displacement ``u`` is one more coordinate: the stack at rest rides the base (integrated, with the face events),
impacts keep the total horizontal momentum, the rest rules ride on the bearing's force after a plastic stick
(``F(u, u'_stuck)`` for ``ag``), a pivot an impact leaves with no rate goes where the accelerations take it, the
steps stay below ``0.02/p`` in every pattern (a chatter of impacts was otherwise stepped over) and below
``0.1/omega_b`` while a face is watched, and the run ends at rest once the free base's energy bound keeps every face
shut after the excitation (then the base's later peak is read over two periods).

Friction demand ``|T|/N`` is read on each rocking phase's dense output at its steps, ``demand_points`` equally
spaced times and the midpoints between all of these, and while at rest it is ``|ag|/g`` (on the rest scan's
grid); the impulsive demand is ``|T|/N`` of the impulses of each impact. The two edges of docs/plinth.md
("Friction") as the kernel reads them: at rest the stack carries ``ag`` up to its threshold only, and a jump past it
(an excitation that starts with one) is read along the patterns the stack passes through at zero state, where each
face stops holding and at the acceleration after the jump (the limit of a ramp); a run that topples reports the
demand read while every pivot was inside its slenderness (``|psi_i| <= alpha_i``).

Where (in reading order): this module, the entry (:func:`reference_stack`, :func:`reference_plinth`, the blocks
and the base of a :class:`rockcli.models.Stack`); :mod:`~rockcli.reference.stack_run`, the run (its result and
its phases); :mod:`~rockcli.reference.stack_impact`, the pattern after an impact;
:mod:`~rockcli.reference.stack_mechanics`, the bodies' equations; :mod:`~rockcli.reference.stack_hysteretic`, the
hysteretic bearings' run.
"""
from __future__ import annotations

import time

from rockcli.reference.stack_mechanics import StackModel
from rockcli.reference.stack_run import StackRefResult, _Run


def stack_blocks(stack) -> list:
    """``[(b, h, m), ...]`` bottom to top of a :class:`rockcli.models.Stack` (body mass 1)."""
    return [(stack.b2, stack.h2, stack.m2), (stack.b1, stack.h1, 1.0)]


def stack_base(stack, isolation):
    """``(m_b, k_b, c_b)`` per unit body mass of a :class:`rockcli.models.LinearIsolation` under ``stack``, or None
    (a rigid foundation). The isolation's ``gamma = m/(m + m_b)`` reads ``m`` as everything the base carries, body
    and plinth (``m1 + m2``), and its ``T_b``, ``xi`` as for the single block: ``k_b = (m + m_b) omega_b^2``,
    ``c_b = 2 xi omega_b (m + m_b)`` (docs/physics-plinth.md, "On linear bearings")."""
    if isolation is None or getattr(isolation, "kind", None) == 0:
        return None
    m = 1.0 + stack.m2
    if not isolation.gamma > 0:
        raise ValueError("the stack reference needs a base of finite mass (gamma > 0)")
    total = m / isolation.gamma
    w = isolation.omega_b
    return (total - m, total * w * w, 2.0 * isolation.xi * w * total)


def reference_plinth(stack, excitation, isolation=None, **kw) -> StackRefResult:
    """:func:`reference_stack` of a body on its plinth (``stack``: a :class:`rockcli.models.Stack`) on a rigid
    foundation, on linear bearings (``isolation``: a :class:`rockcli.models.LinearIsolation`) or on hysteretic ones
    (:class:`rockcli.models.SingleConcaveSliding`, :class:`~rockcli.models.LeadRubber`,
    :class:`~rockcli.models.DoubleConcaveSliding`: :mod:`rockcli.reference.stack_hysteretic`, ``Radau`` unless a
    ``method`` is given)."""
    if hasattr(isolation, "u_y"):
        from rockcli.reference.stack_hysteretic import hysteretic_base

        base, bearing = hysteretic_base(stack, isolation)
        kw.setdefault("method", "Radau")
        return reference_stack(stack_blocks(stack), excitation, base=base, bearing=bearing, **kw)
    return reference_stack(stack_blocks(stack), excitation, base=stack_base(stack, isolation), **kw)


def reference_stack(blocks, excitation, *, rtol=1e-10, atol=None, horizon=600.0, rest_tol=1e-8, restitution=None,
                    method="DOP853", align=True, max_phases=200000, demand_points=8, record_impacts=False,
                    deadline_s=None, tol=1e-9, base=None, bearing=None) -> StackRefResult:
    """Run the stack ``blocks`` (``[(b, h, m), ...]`` bottom to top) under ``excitation`` (a record or a pulse).

    ``atol`` None: ``rtol`` times the state scales (each interface's slenderness and ``p alpha``); ``align``: a
    record's sample intervals integrated one by one (no step across a kink); ``record_impacts``: keep every
    impact's states and energies in ``impacts`` (the tests' conservation checks); ``tol``: the relative slack of
    the impact consistency tests; ``base``: ``(m_b, k_b, c_b)`` of an isolated base on linear bearings
    (:func:`stack_base`), None the rigid ground; ``bearing``: a hysteretic bearing
    (:class:`rockcli.reference.hysteretic.Bearing`) under a base ``(m_b, 0, 0)``, in place of the linear one.
    """
    t_wall = time.perf_counter()
    cls = _Run
    if bearing is not None:
        from rockcli.reference.stack_hysteretic import HystRun

        cls = type("HystRunOf", (HystRun,), {"brg": bearing})
    run = cls(StackModel(blocks, base), excitation, rtol, atol, horizon, rest_tol, restitution, method, align,
              demand_points, record_impacts, deadline_s, tol)
    for _ in range(max_phases):
        if not run.phase():
            break
    out = run.result()
    out.wall_s = time.perf_counter() - t_wall
    return out
