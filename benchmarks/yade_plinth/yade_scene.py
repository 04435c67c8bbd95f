"""One scene in YADE (run as ``yade -n -x yade_scene.py SCENE.json OUT.json``; never imported by rockcli).

Rigid blocks standing on each other on a rigid foundation, in the x-z plane (YADE's z is up): each block is a clump
of a box (its mass and inertia) and four small spheres at its bottom corners (the contact points: YADE has no
box-box contact, and these are the points a rocking block pivots on). A sphere touches the box below it (the ground
box, or the plinth's box) through ``Ig2_Box_Sphere_ScGeom`` and a linear spring-dashpot with Coulomb friction
(``ViscElMat``: stiffness ``kn``, damping ``cn`` per contact, friction angle large enough that nothing slides). The
clumps may only translate in x and z and turn about y (``blockedDOFs = 'yXZ'``): planar rocking. The horizontal
ground motion enters, as in the rocking equations, as an inertial force in the ground's frame: gravity is set to
``(-ag(t), 0, -g)`` at every step (the foundation box stays still). Output: the angle of each block about y
(clockwise in rockcli's x-z picture: positive moves the top towards +x), sampled every ``sample_every`` steps.

SCENE.json: {"blocks": [[half_width, half_height, density, kn, cn], ...] bottom to top (kn [N/m], cn [N s/m] of
the corner contacts under that block), "depth": m, "r": sphere radius, "ks_over_kn": .., "friction_deg": ..,
"dt": s, "t_end": s, "t_settle": s, "g": m/s^2,
"ag_t": [...], "ag": [...] (piecewise linear, zero outside), "theta0": [..] optional initial tilts (radians,
about each block's right corner; single-block calibration only), "sample_every": n}
"""

import json
import math
import sys

from yade import O, utils
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Box_Aabb, Bo1_Sphere_Aabb, InteractionLoop,
                          Ig2_Box_Sphere_ScGeom, Ip2_ViscElMat_ViscElMat_ViscElPhys, Law2_ScGeom_ViscElPhys_Basic,
                          NewtonIntegrator, PyRunner, ViscElMat)
from yade.minieigenHP import Quaternion, Vector3

scene_path, out_path = sys.argv[-2], sys.argv[-1]
S = json.load(open(scene_path))
g = S["g"]
depth, r = S["depth"], S["r"]
fr = math.radians(S["friction_deg"])
ksr = S["ks_over_kn"]


def contact_material(kn, cn, density):
    return O.materials.append(ViscElMat(kn=kn, ks=kn * ksr, cn=cn, cs=cn * ksr, frictionAngle=fr, density=density))


# interface i (under block i) has its own spring-dashpot, scaled by the mass it carries: block i's corner
# spheres and the surface they touch (the ground box, or the top of block i - 1's box) share one material, so
# every contact is between two equal materials (as in the calibration)
blocks = S["blocks"]  # [half_width, half_height, density, kn, cn] bottom to top
mats = [contact_material(kn, cn, 1.0) for (_, _, _, kn, cn) in blocks]
mats_sph = [contact_material(kn, cn, 1e-6) for (_, _, _, kn, cn) in blocks]  # the spheres carry no mass
ground = utils.box(center=(0, 0, -0.5), extents=(50.0, 5.0, 0.5), fixed=True, material=mats[0])
O.bodies.append(ground)
clumps, ORI0 = [], []
z0 = 0.0
for i, (b, h, rho, _, _) in enumerate(blocks):
    top_mat = mats[i + 1] if i + 1 < len(blocks) else mats[i]
    box = utils.box(center=(0, 0, z0 + h), extents=(b, depth / 2, h), material=top_mat)
    m = rho * 8 * b * h * depth / 2
    box.state.mass = m
    box.state.inertia = Vector3(m * (depth ** 2 + (2 * h) ** 2) / 12, m * ((2 * b) ** 2 + (2 * h) ** 2) / 12,
                                m * ((2 * b) ** 2 + depth ** 2) / 12)
    sph = [utils.sphere(center=(sx * (b - r), sy * (depth / 2 - r), z0 + r), radius=r, material=mats_sph[i])
           for sx in (-1, 1) for sy in (-1, 1)]
    cid, _ = O.bodies.appendClumped([box] + sph)
    O.bodies[cid].state.blockedDOFs = "yXZ"
    clumps.append(cid)
    ORI0.append(Quaternion(O.bodies[cid].state.ori))  # a clump sits on its principal axes: angles from here
    z0 += 2 * h

ag_t, ag_v = S["ag_t"], S["ag"]
n_ag = len(ag_t)


def ground_acc(t):
    if t <= ag_t[0] or t >= ag_t[-1]:
        return 0.0
    # uniform sampling
    dt = ag_t[1] - ag_t[0]
    k = min(int((t - ag_t[0]) / dt), n_ag - 2)
    w = (t - ag_t[k]) / dt
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


def angle(i):
    q = O.bodies[clumps[i]].state.ori * ORI0[i].conjugate()
    axis, ang = q.toAxisAngle()
    if ang > math.pi:
        ang -= 2 * math.pi
    return ang * axis[1]


T_MOTION = [0.0]  # the simulation time at which the ground motion starts (after the settling)


def drive():
    a = ground_acc(O.time + O.dt - T_MOTION[0])  # the force of the coming step
    newton.gravity = Vector3(-a, 0, -g)


# optional initial tilt of one block (the calibration of the corner contacts): turn the whole stack above the
# ground about the right corner of the bottom block
theta0 = S.get("theta0")
if theta0:
    b0 = blocks[0][0]
    pivot = Vector3(b0, 0, 0)
    rot = Quaternion(Vector3(0, 1, 0), theta0)
    for cid in clumps:
        st = O.bodies[cid].state
        st.pos = pivot + rot * (st.pos - pivot)
        st.ori = rot * st.ori

# settle under gravity alone before the motion starts (the springs take their static deflection)
t_settle = S.get("t_settle", 0.0)
if t_settle > 0 and not theta0:
    T_MOTION[0] = 1e9  # no motion while settling
    O.run(int(t_settle / O.dt), True)
    for cid in clumps:
        O.bodies[cid].state.vel = Vector3(0, 0, 0)
        O.bodies[cid].state.angVel = Vector3(0, 0, 0)
    T_MOTION[0] = O.time

every = S["sample_every"]
n_steps = int(S["t_end"] / O.dt)
T, TH = [], [[] for _ in clumps]
STOP = [False]


def sample():
    T.append(O.time - T_MOTION[0])
    for i in range(len(clumps)):
        TH[i].append(angle(i))
    # a block past ``topple_rad`` on its support has fallen (the model has no contact for its side)
    rel = [TH[0][-1]] + [TH[i][-1] - TH[i - 1][-1] for i in range(1, len(clumps))]
    if any(abs(x) > S.get("topple_rad", 1.45) for x in rel):
        STOP[0] = True
        O.pause()


O.engines = O.engines + [PyRunner(command="sample()", iterPeriod=every)]
it0 = O.iter
O.run(n_steps, True)
json.dump({"t": T, "theta": TH, "steps": O.iter - it0, "stopped": STOP[0]}, open(out_path, "w"))
