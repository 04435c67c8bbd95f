"""One scene of rocking and sliding in YADE (run as ``yade -n -x yade_scene.py SCENE.json OUT.json``; never
imported by rockcli or its tests).

Rigid blocks standing on each other on a rigid foundation, in the x-z plane (YADE's z is up), as in
``benchmarks/yade_plinth/yade_scene.py``: each block a clump of a box (its mass and inertia) and four small spheres
at its bottom corners (the contact points: YADE has no box-box contact). A sphere touches the box below it (the
ground box, or the box of the block below) through ``Ig2_Box_Sphere_ScGeom`` and a linear spring-dashpot with
Coulomb friction (``ViscElMat`` and ``Law2_ScGeom_ViscElPhys_Basic``): normal ``kn``, ``cn``; tangential ``ks =
ks_over_kn kn`` and ``cs = cs_over_cn cn``; the tangential force is an elastic spring loaded by the contact's slip
rate and capped at ``tan(frictionAngle)`` times the normal force (Coulomb: static = kinetic), plus the shear dashpot
while it sticks. The friction angle of interface ``j`` (under block ``j``) is ``atan(mu_j)``: both materials that meet
there (the corner spheres of block ``j`` and the box under them) carry it. The clumps move in x and z and turn about
y only (``blockedDOFs = 'yXZ'``). The ground motion enters as an inertial force in the ground's frame: gravity is
``(-ag(t), 0, -g)`` at every step, the foundation box stays still.

Outputs, sampled every ``sample_every`` steps from the start of the motion (after ``t_settle`` under gravity
alone): per block its absolute angle about y ``theta`` (positive moves the top towards +x: rockcli's clockwise
sign), its rotation on its support ``psi`` (``theta_j - theta_{j-1}``), and the slip ``s`` of interface ``j``
(rockcli's coordinate): in the frame of the top of the block below (the ground: its start), the position of the
corner the block stands on (the right one when ``psi > 0``, the left when ``psi < 0``) minus ``c b`` (``c = +1,
-1, 0``), from the centre of that top; so pure rocking keeps ``s`` constant and a flat block's ``s`` is its base's
centre. The run stops when a block passes ``topple_rad`` on its support (the model has no contact for its side)
or when a block's slip passes ``edge_j + r`` (its corner sphere off the edge of the block below: the DEM has no
box-box contact, so what follows would not be modelled).

SCENE.json: {"blocks": [[half_width, half_height, density, kn, cn, mu], ...] bottom to top (kn [N/m], cn [N s/m]
of each material at the interface under that block, mu its friction coefficient), "depth": m, "r": sphere radius,
"ks_over_kn": .., "cs_over_cn": .. (0: see below), "dt": s, "t_end": s, "t_settle": s, "g": m/s^2, "ag_t": [...],
"ag": [...] (uniformly sampled, piecewise linear, zero outside), "sample_every": n, "topple_rad": rad, "theta0": rad
(optional: the single block released from this tilt about its right corner, the calibration of the impacts)}

Why no shear dashpot (``cs_over_cn`` 0): YADE's law caps the elastic shear force at Coulomb's limit but adds the
shear dashpot ``cs v`` uncapped whenever the elastic part sits below the limit, which it does at every step where
the normal force grows a little (the corner forces change as the block is pushed): a block pushed beyond its
friction then creeps at ``v = (F - mu N) / cs`` (0.4 mm/s for the crate at 0.3 g, mu = 0.2) instead of sliding.
"""

import json
import math
import sys

from yade import O, utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Box_Aabb, Bo1_Sphere_Aabb, InteractionLoop,
                          Ig2_Box_Sphere_ScGeom, Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_ScGeom_ViscElPhys_Basic,
                          NewtonIntegrator, PyRunner, ViscElMat)
from yade.minieigenHP import Vector3

scene_path, out_path = sys.argv[-2], sys.argv[-1]
S = json.load(open(scene_path))
g = S["g"]
depth, r = S["depth"], S["r"]
ksr = S["ks_over_kn"]
blocks = S["blocks"]  # [half_width, half_height, density, kn, cn, mu] bottom to top
n = len(blocks)


csr = S.get("cs_over_cn", 0.0)


def contact_material(kn, cn, mu, density):
    return O.materials.append(ViscElMat(kn=kn, ks=kn * ksr, cn=cn, cs=cn * csr, frictionAngle=math.atan(mu),
                                        density=density))


# interface j (under block j): block j's corner spheres and the surface they touch (the ground box, or the top of
# block j - 1's box) share one material (stiffness scaled with the mass it carries, friction atan(mu_j))
mats = [contact_material(kn, cn, mu, 1.0) for (_, _, _, kn, cn, mu) in blocks]
mats_sph = [contact_material(kn, cn, mu, 1e-6) for (_, _, _, kn, cn, mu) in blocks]  # the spheres carry no mass
ground = utils.box(center=(0, 0, -0.5), extents=(50.0, 5.0, 0.5), fixed=True, material=mats[0])
O.bodies.append(ground)
clumps, boxes = [], []
z0 = 0.0
for i, (b, h, rho, _, _, _) in enumerate(blocks):
    top_mat = mats[i + 1] if i + 1 < n else mats[i]
    box = utils.box(center=(0, 0, z0 + h), extents=(b, depth / 2, h), material=top_mat)
    m = rho * 8 * b * h * depth / 2
    box.state.mass = m
    box.state.inertia = Vector3(m * (depth ** 2 + (2 * h) ** 2) / 12, m * ((2 * b) ** 2 + (2 * h) ** 2) / 12,
                                m * ((2 * b) ** 2 + depth ** 2) / 12)
    sph = [utils.sphere(center=(sx * (b - r), sy * (depth / 2 - r), z0 + r), radius=r, material=mats_sph[i])
           for sx in (-1, 1) for sy in (-1, 1)]
    cid, ids = O.bodies.appendClumped([box] + sph)
    O.bodies[cid].state.blockedDOFs = "yXZ"
    clumps.append(cid)
    boxes.append(ids[0])  # the box member: its state follows the clump, in the box's own (unrotated) frame
    z0 += 2 * h

ag_t, ag_v = S["ag_t"], S["ag"]
n_ag = len(ag_t)
dt_ag = ag_t[1] - ag_t[0]


def ground_acc(t):
    if t <= ag_t[0] or t >= ag_t[-1]:
        return 0.0
    k = min(int((t - ag_t[0]) / dt_ag), n_ag - 2)
    w = (t - ag_t[k]) / dt_ag
    return ag_v[k] + w * (ag_v[k + 1] - ag_v[k])


newton = NewtonIntegrator(damping=0.0, gravity=(0, 0, -g))
O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Box_Aabb(), Bo1_Sphere_Aabb()]),
    InteractionLoop([Ig2_Box_Sphere_ScGeom()], [Ip2_ViscElMat_ViscElMat_ViscElPhys()],
                    [Law2_ScGeom_ViscElPhys_Basic()]),
    PyRunner(command="drive()", iterPeriod=1),
    newton,
]
O.dt = S["dt"]
T_MOTION = [1e9]  # the simulation time at which the ground motion starts (after the settling)


def drive():
    a = ground_acc(O.time + O.dt - T_MOTION[0])  # the force of the coming step
    newton.gravity = Vector3(-a, 0, -g)


def frame(i):
    """``(x, z, theta, tx, tz)``: block ``i``'s centre, its angle and its x axis (from its box member)."""
    st = O.bodies[boxes[i]].state
    ex = st.ori * Vector3(1, 0, 0)
    ez = st.ori * Vector3(0, 0, 1)
    return st.pos[0], st.pos[2], math.atan2(ez[0], ez[2]), ex[0], ex[2]


X0 = [0.0]  # the base's start on the ground (set after the settling)


def kinematics():
    """``(theta, psi, s)`` of every block / interface now."""
    th, ps, ss = [], [], []
    below = None
    for i, (b, h, _, _, _, _) in enumerate(blocks):
        x, z, t, tx, tz = frame(i)
        if below is None:
            Tx, Tz, ux, uz, tl = X0[0], 0.0, 1.0, 0.0, 0.0
        else:
            bx, bz, tl, btx, btz = below
            hb = blocks[i - 1][1]
            # the top centre of the block below: its centre + h_below along its own z axis (perp. to its x axis)
            Tx, Tz, ux, uz = bx - hb * btz, bz + hb * btx, btx, btz
        psi = t - tl
        c = 1.0 if psi > 0 else (-1.0 if psi < 0 else 0.0)
        # the corner (c b, -h) of this block: centre + c b x-axis - h z-axis
        Cx = x + c * b * tx + h * tz
        Cz = z + c * b * tz - h * tx
        s = (Cx - Tx) * ux + (Cz - Tz) * uz - c * b
        th.append(t)
        ps.append(psi)
        ss.append(s)
        below = (x, z, t, tx, tz)
    return th, ps, ss


theta0 = S.get("theta0")
if theta0:  # the whole block turned about its right corner (no settling: released at once)
    from yade.minieigenHP import Quaternion
    pivot = Vector3(blocks[0][0], 0, 0)
    rot = Quaternion(Vector3(0, 1, 0), theta0)
    for cid in clumps:
        st = O.bodies[cid].state
        st.pos = pivot + rot * (st.pos - pivot)
        st.ori = rot * st.ori

# settle under gravity alone before the motion starts (the springs take their static deflection)
t_settle = S.get("t_settle", 0.0)
if t_settle > 0 and not theta0:
    O.run(int(t_settle / O.dt), True)
    for cid in clumps:
        O.bodies[cid].state.vel = Vector3(0, 0, 0)
        O.bodies[cid].state.angVel = Vector3(0, 0, 0)
X0[0] = frame(0)[0]
T_MOTION[0] = O.time

every = S["sample_every"]
n_steps = int(S["t_end"] / O.dt)
T, TH, PS, SS = [], [[] for _ in blocks], [[] for _ in blocks], [[] for _ in blocks]
STOP = [None]
edges = [math.inf] + [blocks[i - 1][0] - blocks[i][0] for i in range(1, n)]
topple = S.get("topple_rad", 1.45)


def sample():
    T.append(O.time - T_MOTION[0])
    th, ps, ss = kinematics()
    for i in range(n):
        TH[i].append(th[i])
        PS[i].append(ps[i])
        SS[i].append(ss[i])
    for i in range(n):
        if abs(ps[i]) > topple:
            STOP[0] = ["topple", i]
        elif abs(ss[i]) > edges[i] + r:
            STOP[0] = ["slid off", i]
        if STOP[0] is not None:
            O.pause()
            return


O.engines = O.engines + [PyRunner(command="sample()", iterPeriod=every)]
sample()
it0 = O.iter
O.run(n_steps, True)
json.dump({"t": T, "theta": TH, "psi": PS, "s": SS, "steps": O.iter - it0, "stopped": STOP[0]},
          open(out_path, "w"))
