"""Verdict-only runs of many scenes in parallel (numba ``prange``)."""

from __future__ import annotations

from numba import njit, prange

from rockcli.kernels.driver import simulate_core


@njit(cache=True, parallel=True)
def simulate_batch(fkinds, prms, ekinds, epars, acc_all, jtab_all, acc_off, acc_len, dts, t_begins, t_exc_ends,
                   tails, horizon, max_steps, early, outs):
    """Verdict-only runs of many scenes in parallel (one scene per ``prange`` iteration).

    Row ``i`` of each argument describes scene ``i`` (``prms[i]`` in the ``P_*`` layout, ``N_PRM``
    wide); records are slices ``acc_all[acc_off[i]:acc_off[i] + acc_len[i]]`` (scenes may share
    one; ``jtab_all`` is laid out alike). Results go to ``outs[i]`` (``O_*`` layout); nothing else
    is stored.
    """
    for i in prange(fkinds.shape[0]):
        q = prms[i]
        prm = (q[0], q[1], q[2], q[3], q[4], q[5], q[6], q[7], q[8], q[9], q[10], q[11], q[12], q[13],
               q[14], q[15], q[16], q[17], q[18], q[19], q[20], q[21], q[22], q[23], q[24], q[25], q[26])
        e = epars[i]
        epar = (e[0], e[1], e[2], e[3], e[4], e[5], e[6], e[7])
        acc = acc_all[acc_off[i]:acc_off[i] + acc_len[i]]
        jtab = jtab_all[acc_off[i]:acc_off[i] + acc_len[i]]
        simulate_core(fkinds[i], prm, ekinds[i], epar, acc, jtab, dts[i], t_begins[i], t_exc_ends[i], tails[i],
                      horizon, max_steps, False, early, outs[i])
