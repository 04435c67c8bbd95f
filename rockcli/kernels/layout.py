"""Codes and array layouts shared by the kernels and :mod:`rockcli.solve` (constants only: no numba here).

numba compiles these module-level integers into the kernels as constants; they are codes and
indices, never physical constants (those travel in the parameter tuple ``prm``).

The codes and rows that the kernels pass as arguments of compiled calls (the rows of ``W``, the phases,
:data:`FK_RIGID`, :data:`J_BASE` and :data:`J_JOINT`) are ``np.int64`` values: numba types a plain
module-level int, like a literal ``0``, as ``Literal[int](0)``, a type of its own, and compiles the callee
once more for each value it is called with (its frontend, and one more copy in the caller's LLVM module;
:mod:`rockcli.kernels.steps` has the measurements). An int64 value gives one compiled callee for all.
"""

import numpy as _np

# ---------------------------------------------------------------------------------------------
# Foundation families (one right-hand side each, rockcli.kernels.rhs)
# ---------------------------------------------------------------------------------------------
FOUNDATION_RIGID = 0  # block on the ground: states theta, theta_dot
FOUNDATION_LINEAR = 1  # linear viscoelastic bearings (Eqs 7-11): + u, u_dot
FOUNDATION_BILINEAR = 2  # one Bouc-Wen element (SCSS, lead-rubber; Eqs 33-36): + u, u_dot, z
FOUNDATION_DCSS = 3  # two Bouc-Wen elements in series, massless slider: + u, u_dot, z1, z2
FK_RIGID = _np.int64(FOUNDATION_RIGID)  # the code the rigid-foundation drivers pass to the shared functions

# ---------------------------------------------------------------------------------------------
# Excitations
# ---------------------------------------------------------------------------------------------
EXC_RECORD = 0
EXC_RICKER_SYM = 1
EXC_RICKER_ANTI = 2
EXC_SINE = 3
EXC_COSINE = 4
#: Steps per sample interval of a record, at least, on a rigid foundation (see rockcli.kernels.rigid).
RIGID_RECORD_SUBSTEPS = 2

# layout of the excitation tuple ``epar`` (pulses; for a record E_AP is the scale factor)
E_AP, E_TP, E_T0, E_TS, E_TE, E_BETA = 0, 1, 2, 3, 4, 5
N_EPAR = 8

# segment modes (how the right-hand side evaluates the ground acceleration)
SEG_LINEAR = 0  # ag = a0 + slope (t - ts); zero tails are linear with a0 = slope = 0

# ---------------------------------------------------------------------------------------------
# The parameter tuple ``prm`` (built by rockcli.solve._parameters)
# ---------------------------------------------------------------------------------------------
P_P2, P_G, P_ALPHA, P_R, P_GAMMA, P_W, P_XI, P_THR = 0, 1, 2, 3, 4, 5, 6, 7
P_SINA, P_COSA, P_H, P_ETA, P_DU, P_REST, P_RTOL = 8, 9, 10, 11, 12, 13, 14
P_SC0 = 15  # 4 state scales follow: theta, theta_dot, u, u_dot
# hysteretic bearings (Bouc-Wen, Eq 34 with A = 1 and beta + gamma_bw = 1):
P_Q1 = 19  # strength per unit total mass [m/s^2]: mu g (SCSS), Q/(m + m_b) (LRB), mu1 g (DCSS surface 1)
P_UY1 = 20  # yield displacement of the element [m] (DCSS: of surface 1)
P_BWN = 21  # Bouc-Wen exponent n (1 or 2)
P_BWC = 22  # gamma_bw - beta_bw (>= 0): 0 makes the unloading branch linear in u
P_K1 = 23  # DCSS: stiffness per unit total mass of surface 1, g / R1_eff [1/s^2]
P_K2 = 24  # DCSS: g / R2_eff [1/s^2]
P_Q2 = 25  # DCSS: mu2 g [m/s^2]
P_UY2 = 26  # DCSS: yield displacement of surface 2 [m]
# the initial state (rockcli.kernels.steps._initial_state): 0, 0 is a start at rest
P_TH0 = 27  # theta at the start [rad], |theta0| < pi/2
P_THD0 = 28  # theta_dot at the start [rad/s]
P_HDT = 29  # spacing of the history's uniform grid [s] (0: no grid rows; rockcli.kernels.events._hist_grid)
N_PRM = 30

# ---------------------------------------------------------------------------------------------
# The output vector
# ---------------------------------------------------------------------------------------------
O_STATUS, O_UPLIFTED, O_T_UPLIFT, O_T_OVERTURN, O_THETA_MAX, O_T_THETA_MAX = 0, 1, 2, 3, 4, 5
O_T_EXCEED, O_N_IMPACTS, O_U_MAX, O_STEPS, O_REJECTED, O_NRHS, O_T_END = 6, 7, 8, 9, 10, 11, 12
O_N_RESTS, O_N_UPLIFTS, O_N_IMPACTS_ALL, O_SETTLED, O_THETA_END, O_U_END = 13, 14, 15, 16, 17, 18
O_PEAK_FINAL, O_T_SETTLED, O_N_REVERSALS = 19, 20, 21
N_OUT = 22

STATUS_DONE = 0
STATUS_OVERTURNED = 1
STATUS_MAX_STEPS = -1

# ---------------------------------------------------------------------------------------------
# History columns (z, z2 and the bearing force are filled for hysteretic bearings only)
# ---------------------------------------------------------------------------------------------
H_T, H_AG, H_TH, H_THD, H_U, H_UD, H_Z, H_Z2, H_FB = 0, 1, 2, 3, 4, 5, 6, 7, 8
# row kind: HK_STATE a state at a step end; HK_PEAK a turning point of theta while rocking
# (theta_dot = 0, located on the step's dense output; z, z2 and the force NaN); HK_GRID a state on
# the uniform grid (the step's dense output); the other kinds are step rows at an event: the uplift,
# the states just before (HK_IMPACT) and just after an impact (HK_IMPACT_AFTER, or HK_REST when the
# block comes to rest there), the overturn (s theta = pi/2)
H_KIND = 9
HK_STATE, HK_PEAK, HK_GRID, HK_UPLIFT, HK_IMPACT, HK_IMPACT_AFTER, HK_REST, HK_OVERTURN = (
    0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0)
N_HIST = 10

PHASE_STUCK = _np.int64(0)
PHASE_ROCKING = _np.int64(1)

# the interfaces of a body on its plinth (rockcli.kernels.stack, stack_linear): the plinth on the base, the body on
# the plinth (the impacting interface ``j`` of the impact code, the uplift outputs)
J_BASE, J_JOINT = _np.int64(0), _np.int64(1)

# ---------------------------------------------------------------------------------------------
# The work array ``W`` of a step (rows) x the integrated states (columns theta, theta_dot, u, u_dot)
# ---------------------------------------------------------------------------------------------
W_Y = _np.int64(7)  # state at the start of the step (rows 0..6: stage derivatives, row 6 = f(t + h, ynew))
W_YNEW = _np.int64(8)  # state at the end of the step
W_TMP = _np.int64(9)  # stage state / dense-output state
# a step retaken to an event inside the last one (rockcli.kernels.dopri._restep_rows) uses rows
# W_RE + 0..9 the way a step uses rows 0..9, leaving the last step (and its dense output) intact
W_RE = _np.int64(10)
W_EV = W_RE + W_YNEW  # the state at the event
W_FEV = W_RE + 6  # f there
N_W = 20

# ---------------------------------------------------------------------------------------------
# The run record ``rs`` (float array) that the phase functions of the driver share
# ---------------------------------------------------------------------------------------------
RS_T = 0  # time [s]
RS_PHASE = 1  # PHASE_STUCK / PHASE_ROCKING
RS_S = 2  # pivot corner: +1 right, -1 left, 0 stuck
RS_H = 3  # step-size proposal [s] (0: choose one)
RS_STEPS = 4
RS_REJ = 5
RS_NRHS = 6
RS_FRESH = 7  # 1: W[0] = f(t, y) must be recomputed
RS_UMAX = 8
RS_THMAX = 9
RS_SETTLED = 10
RS_PEAK_FINAL = 11
RS_STATUS = 12
RS_J = 13  # index of the current excitation segment
RS_SEG_END = 14
RS_SEG = 15  # 4 entries: the segment tuple (mode, a0, slope, ts)
# the hysteresis anchor (rockcli.kernels.bearings): the state of the Bouc-Wen elements at the
# start of the step, from which z follows u exactly while u moves one way
RS_UA = 19  # u at the anchor [m]
RS_DIR = 20  # direction of motion of the step, +1 or -1
RS_XI1 = 21  # branch coordinate of element 1 (bearings.bw_xi)
RS_U1A = 22  # DCSS: displacement across surface 1 at the anchor [m]
RS_XI2 = 23  # DCSS: branch coordinate of element 2
RS_SPLIT = 24  # DCSS: share of a displacement increment taken by surface 1 at the anchor (Newton's start)
RS_NREV = 25  # steps ended at a reversal of the base
# a peak of theta (theta_dot = 0) inside the last rocking step (rockcli.kernels.steps._rocking_events)
RS_PK_ON = 26  # 1: there is one
RS_PK_SIG = 27  # its fraction of the step
RS_PK_T = 28  # its time [s]
# the vertical ground acceleration (rigid foundation only; zeros without one): a piecewise-linear
# series from t = 0, read on the current piece as a_v = v0 + slope (t - tv) (rockcli.kernels.ground)
RS_VSEG = 29  # 3 entries: (v0, slope, tv), the last three entries of the segment tuple
RS_VEND = 32  # end of the current piece [s] (inf after the series)
RS_VJ = 33  # index of the current piece
N_RS = 34
