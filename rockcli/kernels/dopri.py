"""The Dormand-Prince 5(4) step and its quartic dense output.

Dormand & Prince (1980) with local extrapolation and the dense output of Shampine (1986), the
coefficients SciPy's ``RK45`` uses.

Error norm. The error of each active state is kept below ``rtol * max(|y|, |ynew|, scale)``. For
the base displacement on a hysteretic bearing the tolerance is ``rtol / (1/max(|u|, |unew|, scale)
+ G)`` with ``G`` the largest ``|dz/du|`` on the step (:func:`rockcli.kernels.bearings.z_sensitivity`):
the error that u passes on to the Bouc-Wen variables, ``G |err_u|``, stays below ``rtol`` too (on
the elastic branch ``G = 1/u_y``; while the bearing slides ``G`` ~ 0 and the usual tolerance applies).
z itself is not integrated (it follows u exactly), so this is the whole of its error.
"""

from __future__ import annotations

import math

from rockcli.kernels.jit import kernel
from rockcli.kernels.layout import FOUNDATION_BILINEAR, P_RTOL, P_SC0, W_EV, W_FEV, W_RE, W_TMP, W_Y, W_YNEW
from rockcli.kernels.polynomials import _poly

# Tableau and dense-output coefficients. Module-level tuples: mathematical constants of the method,
# which numba compiles in as literals (they never change, so freezing them in the cache is safe).
_C = (0.0, 1 / 5, 3 / 10, 4 / 5, 8 / 9, 1.0, 1.0)
# rows 1-5: the stages; row 6: the weights of the 5th-order solution (first same as last: its
# derivative is stage 7, the next step's first)
_A = (
    (0.0, 0.0, 0.0, 0.0, 0.0, 0.0),
    (1 / 5, 0.0, 0.0, 0.0, 0.0, 0.0),
    (3 / 40, 9 / 40, 0.0, 0.0, 0.0, 0.0),
    (44 / 45, -56 / 15, 32 / 9, 0.0, 0.0, 0.0),
    (19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729, 0.0, 0.0),
    (9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656, 0.0),
    (35 / 384, 0.0, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84),
)
_E = (-71 / 57600, 0.0, 71 / 16695, -71 / 1920, 17253 / 339200, -22 / 525, 1 / 40)
_P = (
    (1.0, -8048581381 / 2820520608, 8663915743 / 2820520608, -12715105075 / 11282082432),
    (0.0, 0.0, 0.0, 0.0),
    (0.0, 131558114200 / 32700410799, -68118460800 / 10900136933, 87487479700 / 32700410799),
    (0.0, -1754552775 / 470086768, 14199869525 / 1410260304, -10690763975 / 1880347072),
    (0.0, 127303824393 / 49829197408, -318862633887 / 49829197408, 701980252875 / 199316789632),
    (0.0, -282668133 / 205662961, 2019193451 / 616988883, -1453857185 / 822651844),
    (0.0, 40617522 / 29380423, -110615467 / 29380423, 69997945 / 29380423),
)


@kernel(inline='always')
def _dp5_step(rhs_into, fkind, phase, s, prm, seg, epar, hy, gz, t, h, W, i0, i1, r0):
    """One Dormand-Prince step of the active states ``i0:i1`` from ``(t, W[r0 + W_Y])``.

    ``rhs_into`` is the driver's right-hand side (:mod:`rockcli.kernels.rhs`), passed as a
    function so that each driver compiles only its own; each driver compiles this once, in one
    function of its own that takes the step and retakes it to events (:func:`_restep_rows`).

    Works in rows ``r0 .. r0 + 9`` of ``W`` (``r0 = 0`` for a step, ``W_RE`` for a retaken one).
    Expects ``W[r0] = f(t, y)``; fills the stage derivatives ``W[r0 + 1 : r0 + 7]``
    (``W[r0 + 6] = f(t + h, ynew)``, first-same-as-last) and ``W[r0 + W_YNEW]``. Returns the RMS
    of the local error over the active states, each scaled by its tolerance (see the module notes;
    accept the step when <= 1). ``hy`` is the anchor of the hysteretic elements, ``gz`` their
    largest ``|dz/du|`` on the step.
    """
    ry = r0 + W_Y
    rn = r0 + W_YNEW
    for i in range(4):
        W[r0 + W_TMP, i] = W[ry, i]
        W[rn, i] = W[ry, i]
    for st in range(1, 7):  # one call site of the right-hand side (it is inlined once)
        row = r0 + W_TMP if st < 6 else rn
        for i in range(i0, i1):
            acc = 0.0
            for j in range(st):
                acc += _A[st][j] * W[r0 + j, i]
            W[row, i] = W[ry, i] + h * acc
        rhs_into(fkind, phase, s, prm, seg, epar, hy, t + _C[st] * h, W, row, r0 + st)
    rtol = prm[P_RTOL]
    tot = 0.0
    for i in range(i0, i1):
        err = 0.0
        for j in range(7):
            err += _E[j] * W[r0 + j, i]
        if i == 2 and fkind >= FOUNDATION_BILINEAR:
            sc = rtol / (1.0 / max(abs(W[ry, i]), abs(W[rn, i]), prm[P_SC0 + i]) + gz)
        else:
            sc = max(abs(W[ry, i]), abs(W[rn, i]), prm[P_SC0 + i]) * rtol
        tot += (h * err / sc) ** 2
    return math.sqrt(tot / (i1 - i0))


@kernel
def _dense(W, h, i, sign):
    """``sign *`` state ``i`` over the last step as a quartic in sigma = (t - t_step)/h: 5 coefficients."""
    c1 = 0.0
    c2 = 0.0
    c3 = 0.0
    c4 = 0.0
    for j in range(7):
        k = W[j, i]
        c1 += k * _P[j][0]
        c2 += k * _P[j][1]
        c3 += k * _P[j][2]
        c4 += k * _P[j][3]
    return (sign * W[W_Y, i], sign * h * c1, sign * h * c2, sign * h * c3, sign * h * c4)



@kernel(inline='always')
def _state_at(W, h, sig, nst):
    """Dense-output state at fraction ``sig`` of the last step, written into ``W[W_TMP]``."""
    for i in range(nst):
        W[W_TMP, i] = _poly(_dense(W, h, i, 1.0), sig)


@kernel(inline='always')
def _restep_rows(W):
    """Prepare a step retaken to an event inside the last one: its start state and derivative in
    rows ``W_RE + 0`` and ``W_RE + W_Y``; the driver then takes it with ``r0 = W_RE``
    (:func:`_dp5_step`), so the last step and its dense output are kept. The retaken state is
    ``W[W_EV]``, with ``W[W_FEV] = f`` there.

    Why: the quartic dense output that locates the event is of 4th order (local error O(h^5))
    while the step itself is of 5th (O(h^6)), and with local extrapolation the step's actual error
    is well below its estimate: a state read from the dense output carries an error up to about
    the tolerance, one retaken step a small fraction of it. Its error estimate is not needed: it
    is shorter than the accepted step (6 RHS).
    """
    for i in range(4):
        W[W_RE, i] = W[0, i]
        W[W_RE + W_Y, i] = W[W_Y, i]


@kernel(inline='always')
def _shift_event(W, dt, i0, i1):
    """Move the event state ``W[W_EV]`` by the small time ``dt`` along ``W[W_FEV] = f`` there: one
    Taylor term, onto the event's root, whose location on the dense output is off by O(h^5) (the
    neglected term is O(dt^2))."""
    for i in range(i0, i1):
        W[W_EV, i] += W[W_FEV, i] * dt
