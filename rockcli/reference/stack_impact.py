"""The pattern after an impact in the slow stack reference (:mod:`rockcli.reference.stack`), for any number of
blocks: every candidate pattern after an impact at interface ``j`` (the interfaces at angle 0 free to be a face or
either pivot; the others keep their pivot) gets its velocities from the plastic impact (impulses at its own
constraints) or, with a restitution ``E``, from the energetic rule (the impacting pivot's new rate is ``E`` times
the largest the kinetic energy allows); the one whose impulses press (every corner impulse >= 0) and whose new
pivots open is taken. A persistent pivot's impulse is not required to press: a pulling one is counted as a jump
(``n_jumps``; the rocking-only assumption fails there).
"""

from __future__ import annotations

import math

import numpy as np

def _candidates(model, st, q, j, E):
    """The patterns that may follow an impact at ``j``: the interfaces at angle 0 a face or either pivot (with a
    restitution the impacting one on its new corner), the others keeping their pivot."""
    import itertools

    opts = []
    for i in range(model.n):
        if i == j and E is not None:
            opts.append((-st[j],))
        elif q[i] == 0.0:
            opts.append((0, 1, -1))
        else:
            opts.append((st[i],))
    return list(itertools.product(*opts))


def post_velocities(model, c, q, v_minus, j, E):
    """Velocities and impulses after an impact at ``j`` into the pattern ``c``: plastic, or with a restitution the
    energetic rule (docs/physics-plinth.md)."""
    if E is None or c[j] == 0:
        return model.impact(c, q, v_minus)
    s0 = list(c)
    s0[j] = 0
    v0, _ = model.impact(s0, q, v_minus)  # the plastic part: every motion but the impacting pivot's
    w, _ = model.impact(c, q, np.zeros_like(v_minus), rate=(j, 1.0))  # the impacting pivot's own mode
    dv = v_minus - v0
    W = math.sqrt(max(0.0, float(np.sum(model.Mdiag * dv * dv)) / float(np.sum(model.Mdiag * w * w))))
    target = E * W * math.copysign(1.0, model.rel_rates(v_minus)[j])
    return model.impact(c, q, v_minus, rate=(j, target))


def choose_post(model, st, q, v_minus, j, E=None, tol=1e-9):
    """The pattern after an impact at ``j`` (``q[j] = 0``) from ``st``: ``(pattern, v+, impulses, margin, pulls)``.

    Each candidate's impulses must press (both corners of a face, the corner of a pivot) and its new pivots open;
    the candidate with the largest smallest margin is taken (``margin < 0``: none was consistent). A restitution
    that no candidate can carry (its couple would lift a face) gives way to the plastic law. ``pulls`` counts the
    kept pivots whose impulse pulls (a jump the model does not follow)."""
    c, v, imp, margin = _best(model, st, q, v_minus, j, E)
    if E is not None and margin < -tol:  # no pattern carries the rebound: the plastic law
        c, v, imp, margin = _best(model, st, q, v_minus, j, None)
    zero = [i for i in range(model.n) if q[i] == 0.0]
    pscale = max(abs(x[0]) for x in imp)
    pulls = sum(1 for i in range(model.n) if c[i] != 0 and i not in zero and max(imp[i][2], imp[i][3]) < -tol * pscale)
    return c, v, imp, margin, pulls


def _best(model, st, q, v_minus, j, E):
    zero = [i for i in range(model.n) if q[i] == 0.0]
    vscale = float(np.max(np.abs(model.rel_rates(v_minus)))) + 1e-300
    best = None
    for c in _candidates(model, st, q, j, E):
        v, imp = post_velocities(model, c, q, v_minus, j, E)
        rel = model.rel_rates(v)
        pscale = max(abs(x[0]) for x in imp) + 1e-300
        margin = math.inf
        for i in zero:
            if c[i] == 0:
                margin = min(margin, min(imp[i][2], imp[i][3]) / pscale)
            else:
                margin = min(margin, c[i] * rel[i] / vscale)
                if not (i == j and E is not None):
                    margin = min(margin, max(imp[i][2], imp[i][3]) / pscale)
        if best is None or margin > best[0]:
            best = (margin, c, v, imp)
    margin, c, v, imp = best
    return c, v, imp, margin
