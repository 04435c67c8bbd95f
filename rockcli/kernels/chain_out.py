STATUS_SLID_OFF = 2
#: the run stopped where its steps made no progress (the step size collapsed at a point the contact law cannot pass:
#: pivots that pull, which the model without flight cannot follow), or where events at one instant never end (64,000
#: in a row): undecided, as at the step cap
STATUS_STALLED = -2
#: accepted steps in a row that leave the time unchanged before a run is stopped as stalled (events at one instant:
#: this times the driver's MAX_STALL)
MAX_NO_PROGRESS = 1000

# the run's outputs
X_STATUS, X_TOPPLED, X_SLIDOFF, X_T_END, X_T_FAIL, X_STEPS, X_REJ, X_NRHS = 0, 1, 2, 3, 4, 5, 6, 7
X_N_JUMP, X_N_INCONS, X_N_SLIP_IMPACTS, X_SETTLED, X_T_SETTLED = 8, 9, 10, 11, 12
X_U_MAX, X_T_U_MAX, X_N_SWITCH, X_U_END, X_T_FIRST, X_N_STALL = 13, 14, 15, 16, 17, 18
X_N_SLIP_IN = 19  # slips that start while every block is inside its slenderness (not during a fall)
X_N_PLASTIC = 20  # impacts where a given restitution could not be carried (its impulses left the cone): plastic
N_XG = 24
# per interface
J_PSI_MAX, J_T_PSI_MAX, J_T_EXCEED, J_S_MAX, J_T_S_MAX, J_TILT = 0, 1, 2, 3, 4, 5
J_T_UPLIFT, J_N_IMP, J_N_IMP_ALL, J_N_RESTS, J_T_SLIDE, J_N_SLIPS, J_S_END, J_PSI_END = 6, 7, 8, 9, 10, 11, 12, 13
NX_J = 14

# history rows: t, ag, kind, the pattern (2 n), the state (2 + 4 n)
HC_T, HC_AG, HC_KIND, HC_PAT = 0, 1, 2, 3
HK_STATE, HK_EVENT, HK_IMPACT, HK_IMPACT_AFTER, HK_END = 0.0, 1.0, 2.0, 3.0, 4.0


def n_out(n: int) -> int:
    return N_XG + NX_J * n
