"""A drum's pivot that slides past the edge of the drum below (docs/physics-drums.md): where a block's corner
overhangs the top below, the pivot is that top's corner and the block's base slides over it
(:func:`rockcli.kernels.chain.kinematics`, "kind B"). The friction driver (:mod:`rockcli.kernels.chain_run`) stops a
step where a sliding pivot reaches the switch (``kernels.chain_step.state_events``, ``EVC_KIND``) and maps the
velocities here."""

from __future__ import annotations

from rockcli.kernels.chain import CP_N, F_B, F_BLOW, col_s, fld, kinematics, solve_level
from rockcli.kernels.jit import kernel


@kernel
def kind_switch(cp, pat, y, j, ws, v0, w0):
    """Interface ``j``'s sliding pivot reaches the edge of the top below (a drum's corner over the corner under it):
    from there the top's corner bears on the drum's base (kernels.chain.kinematics, "kind B"), or back. Positions
    are continuous; the velocities that kept the old contact (the corner moving along the top below) need not keep
    the new one (the base sliding over the corner below): a tilted drum's corner leaves the top's level at once. The
    model has no flight, so the new contact takes a plastic impulse with Coulomb's law (the impact law of
    :func:`rockcli.kernels.contact.impact` with the pattern kept): the velocities before, projected; energy never
    rises. The slip is set past the switch by a hair (1e-12 of the top's half width) so that the next step starts on
    the new side."""
    n = int(cp[CP_N])
    free, AG, bG, AA, bA, G, vG, om, th, fr, M, r, x, mo, fq = ws
    cs = col_s(j)
    sw = pat[2 * j] * (fld(cp, j, F_BLOW) - fld(cp, j, F_B))
    hair = (1e-12 if y[cs + 1] > 0.0 else -1e-12) * fld(cp, j, F_BLOW)
    y[cs] = sw - hair  # the velocities before, on the side the slip comes from
    kinematics(cp, pat, y, ws)
    for i in range(n):
        v0[i, 0] = vG[i, 0]
        v0[i, 1] = vG[i, 1]
        w0[i] = om[i]
    y[cs] = sw + hair
    nf = kinematics(cp, pat, y, ws)
    for i in range(n):
        vG[i, 0] = v0[i, 0]
        vG[i, 1] = v0[i, 1]
        om[i] = w0[i]
    if nf > 0 and solve_level(cp, pat, y, ws, nf, 0.0, True):
        for k in range(nf):
            y[free[k] + 1] = x[k]
