"""Verdict-only runs of many scenes: one serial loop per driver, compiled without the GIL.

:mod:`rockcli.solve` runs chunks of a sweep on a pool of threads, each thread calling one of these
on its chunk (numba's ``parallel=True`` would compile a second, much larger specialisation of the
driver for the same work). A sweep compiles only the driver its scenes need.

Row ``i`` of each argument describes scene ``i`` (``prms[i]`` in the ``P_*`` layout, ``N_PRM``
wide); records are slices ``acc_all[acc_off[i]:acc_off[i] + acc_len[i]]`` (scenes may share one;
``jtab_all`` is laid out alike). Results go to ``outs[i]`` (``O_*`` layout); nothing else is stored.
Under a vertical ground motion (rigid foundation only) the vertical series are slices
``vacc_all[v_off[i]:v_off[i] + v_len[i]]`` sampled every ``vdts[i]`` (``vjtab_all`` alike).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from rockcli.kernels.driver import simulate_core
from rockcli.kernels.rigid import simulate_rigid, simulate_rigid_vertical


@njit(cache=True, inline='always')
def _scene(i, prms, epars):
    """Scene ``i``'s parameter and excitation tuples."""
    q = prms[i]
    prm = (q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8], q[9], q[10], q[11], q[12], q[13],
           q[14], q[15], q[16], q[17], q[18], q[19], q[20], q[21], q[22], q[23], q[24], q[25], q[26], q[27],
           q[28], q[29])
    e = epars[i]
    return prm, (e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7])


@njit(cache=True, inline='always')
def _run_scenes(simulate, fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins,
                t_exc_ends, tails, horizon, max_steps, early, outs):
    """Scene ``i`` of the rows through the driver ``simulate``, verdict only, into ``outs[i]``."""
    no_history = np.bool_(False)  # not a literal: the same compiled driver as a single run's
    for i in range(fkinds.shape[0]):
        prm, epar = _scene(i, prms, epars)
        a, b = acc_off[i], acc_off[i] + acc_len[i]
        simulate(fkinds[i], prm, ekinds[i], epar, acc_all[a:b], jtab_all[a:b], dts[i], t_begins[i],
                 t_exc_ends[i], tails[i], horizon, max_steps, no_history, early, outs[i])


@njit(cache=True, nogil=True)
def simulate_batch_rigid(fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins,
                         t_exc_ends, tails, horizon, max_steps, early, outs):
    """Scenes on a rigid foundation (:func:`rockcli.kernels.rigid.simulate_rigid`)."""
    _run_scenes(simulate_rigid, fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins,
                t_exc_ends, tails, horizon, max_steps, early, outs)


@njit(cache=True, nogil=True)
def simulate_batch(fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins, t_exc_ends,
                   tails, horizon, max_steps, early, outs):
    """Scenes on isolated bases (:func:`rockcli.kernels.driver.simulate_core`)."""
    _run_scenes(simulate_core, fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins,
                t_exc_ends, tails, horizon, max_steps, early, outs)


@njit(cache=True, nogil=True)
def simulate_batch_rigid_vertical(fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins,
                                  t_exc_ends, tails, horizon, max_steps, early, vacc_all, vjtab_all, v_off, v_len, vdts,
                                  outs):
    """Scenes on a rigid foundation under a vertical ground motion as well
    (:func:`rockcli.kernels.rigid.simulate_rigid_vertical`; its proofs under a vertical motion, PV)."""
    no_history = np.bool_(False)
    for i in range(fkinds.shape[0]):
        prm, epar = _scene(i, prms, epars)
        a, b = acc_off[i], acc_off[i] + acc_len[i]
        c, d = v_off[i], v_off[i] + v_len[i]
        simulate_rigid_vertical(fkinds[i], prm, ekinds[i], epar, acc_all[a:b], jtab_all[a:b], dts[i], t_begins[i],
                                t_exc_ends[i], tails[i], horizon, max_steps, no_history, early, vacc_all[c:d],
                                vjtab_all[c:d], vdts[i], outs[i])
