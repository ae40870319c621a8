#!/usr/bin/env python3
"""Golden statics from Pinocchio (pip install pin), an independent rigid-body library, for
tests/suite/body_golden.rs. Writes tests/data/pinocchio/<robot>.json. Run from the repository root:

    python3 tests/data/pinocchio_golden.py

For every robot and posture it records, by joint name (Pinocchio orders joints itself):

* the joint torques of inverse dynamics at zero velocity and acceleration, `rnea(q, 0, 0, fext)`,
  with gravity (0, 0, -9.81) and external loads: a force and a moment in world axes at a point
  fixed on a link, chosen here (hand loads and arbitrary foot forces, not posture-opt's ground
  reaction). Pinocchio wants each load as a spatial force in the local frame of the joint that
  moves the link, about that joint's origin; the conversion is written out below. Inverse dynamics
  at rest gives the torque the joints must produce to hold the posture: posture-opt's holding
  torque, same sign.
* the gravity part alone (`computeGeneralizedGravity`) and its derivative
  (`computeGeneralizedGravityDerivatives`);
* the world placement of every link frame (`updateFramePlacements`);
* the world position of each load point and its 6xn Jacobian (an operational frame added at the
  point, `getFrameJacobian` in LOCAL_WORLD_ALIGNED: rows 0-2 the point's velocity, rows 3-5 the
  link's angular velocity);
* the centre of mass and its Jacobian (`jacobianCenterOfMass`). Pinocchio leaves out the mass of
  a fixed-base robot's root link (it rides on the "universe"); posture-opt counts every link.
  Both are written: `com_pinocchio_m` / `com_jacobian_pinocchio` as Pinocchio gives them, and
  `com_m` / `com_jacobian` with the root link's mass added back (it does not move, so the
  Jacobian only scales by the mass ratio).

Continuous joints have two coordinates in Pinocchio (cos, sin); the angle is given per joint.

The worker's postures include two with the feet placed off the nominal stance, as the planner
places them (issue 33): "turned" (the whole body turned 60 degrees about the vertical and moved
0.3 m sideways) and "staggered" (the left foot 0.25 m ahead of the right, the feet at yaws +30 and
-5 degrees, both flat on the floor: the leg joints are solved here with Pinocchio's frame
kinematics, `feet_placed`). The loads are the same for every posture; the foot forces act at
points of the soles, so they move with the placed feet. "seated" sits (hips and knees at 90
degrees, the pelvis lowered and moved back) with a fifth load, a seat's reaction at the pelvis's
ischial point (issue 33.2).
"""
import json
import math
import os

import numpy as np
import pinocchio as pin

OUT = "tests/data/pinocchio"


def load(link, point, force, moment):
    return {"link": link, "point_in_link_m": point, "force_n": force, "moment_nm": moment}


# The worker's postures (radians, metres for pelvis_tx/ty/tz), by name.
STAND = {}
STOOP = {"lumbar_flexion": 0.9, "r_hip_flexion": 0.6, "l_hip_flexion": 0.6, "pelvis_tilt": 0.5,
         "r_shoulder_flexion": 0.7, "l_shoulder_flexion": 0.7, "neck_flexion": -0.3}
SQUAT = {"pelvis_tz": -0.42, "pelvis_tilt": 0.25, "r_hip_flexion": 1.7, "l_hip_flexion": 1.7,
         "r_knee_flexion": 2.1, "l_knee_flexion": 2.1, "r_ankle_dorsiflexion": 0.35,
         "l_ankle_dorsiflexion": 0.35, "lumbar_flexion": 0.4, "r_shoulder_flexion": 1.2,
         "l_shoulder_flexion": 1.2, "r_elbow_flexion": 0.5, "l_elbow_flexion": 0.5}
REACH = {"lumbar_flexion": 0.35, "lumbar_axial_rotation": 0.3, "r_shoulder_flexion": 1.55,
         "r_shoulder_abduction": 0.25, "r_elbow_flexion": 0.2, "r_wrist_flexion": -0.3,
         "l_shoulder_flexion": 0.4, "l_elbow_flexion": 1.3, "r_hip_flexion": 0.2,
         "l_hip_flexion": 0.2, "pelvis_tx": 0.05}
ASYM = {"pelvis_tx": 0.12, "pelvis_ty": -0.08, "pelvis_tz": -0.05, "pelvis_rotation": 0.4,
        "pelvis_list": -0.15, "pelvis_tilt": 0.3, "lumbar_flexion": 0.5,
        "lumbar_lateral_bending": -0.25, "lumbar_axial_rotation": 0.45, "neck_flexion": 0.3,
        "neck_lateral_bending": 0.2, "neck_axial_rotation": -0.6, "r_shoulder_flexion": 1.1,
        "r_shoulder_abduction": 0.6, "r_shoulder_rotation": -0.7, "r_elbow_flexion": 1.2,
        "r_forearm_pronation": 0.9, "r_wrist_flexion": 0.5, "r_wrist_deviation": -0.3,
        "l_shoulder_flexion": -0.4, "l_shoulder_abduction": 1.4, "l_shoulder_rotation": 0.5,
        "l_elbow_flexion": 0.3, "l_forearm_pronation": -1.0, "l_wrist_flexion": -0.8,
        "l_wrist_deviation": 0.2, "r_hip_flexion": 0.8, "r_hip_abduction": 0.3,
        "r_hip_rotation": -0.4, "r_knee_flexion": 1.0, "r_ankle_dorsiflexion": -0.5,
        "r_ankle_inversion": 0.3, "l_hip_flexion": -0.2, "l_hip_abduction": -0.3,
        "l_hip_rotation": 0.6, "l_knee_flexion": 0.4, "l_ankle_dorsiflexion": 0.2,
        "l_ankle_inversion": -0.2}

# The feet placed off the nominal stance, as the planner places them (issue 33): the floating
# pelvis and the leg joints put each foot anywhere on the floor, flat, at any yaw.
# TURNED: the whole body turned 60 degrees about the vertical and moved 0.3 m to its own left
# (along the turned body's y axis: pelvis_tx = -0.3 sin 60 deg, pelvis_ty = 0.3 cos 60 deg), the
# legs straight, so both feet stand flat at the nominal stance's shape, turned and moved with it.
TURNED = {"pelvis_rotation": math.radians(60.0), "pelvis_tx": -0.3 * math.sin(math.radians(60.0)),
          "pelvis_ty": 0.3 * math.cos(math.radians(60.0)), "lumbar_flexion": 0.2,
          "lumbar_axial_rotation": -0.25, "r_shoulder_flexion": 0.6, "l_shoulder_flexion": 0.5,
          "r_elbow_flexion": 1.1, "l_elbow_flexion": 1.2, "neck_flexion": 0.2}
# STAGGERED: the left foot 0.25 m ahead of the right (world x), the feet at different yaws (left
# +30 degrees, right -5 degrees), the pelvis lowered, turned, tilted and listed; each leg's six
# joints are solved below (feet_placed) so that both feet stand flat on the floor where these say.
STAGGERED_BODY = {"pelvis_tx": 0.03, "pelvis_ty": 0.01, "pelvis_tz": -0.02, "pelvis_rotation": 0.2,
                  "pelvis_list": 0.05, "pelvis_tilt": 0.15, "lumbar_flexion": 0.35,
                  "lumbar_lateral_bending": 0.1, "lumbar_axial_rotation": -0.3,
                  "neck_flexion": 0.25, "r_shoulder_flexion": 1.2, "r_shoulder_abduction": 0.2,
                  "r_elbow_flexion": 0.7, "r_wrist_flexion": 0.2, "l_shoulder_flexion": 0.9,
                  "l_elbow_flexion": 0.9, "l_forearm_pronation": 0.4}
# foot link frame: world x, y (m) and yaw (rad) of its x axis; flat, at the nominal height
STAGGERED_FEET = {"l_foot": (0.20, 0.14, math.radians(30.0)),
                  "r_foot": (-0.05, -0.10, math.radians(-5.0))}
LEG = ["hip_flexion", "hip_abduction", "hip_rotation", "knee_flexion", "ankle_dorsiflexion",
       "ankle_inversion"]

# Hand loads (a 10 kg box split between the hands, pulled a little sideways, with a twist) and
# arbitrary foot forces at points of the soles (not a balanced ground reaction: the test is of
# the torques' arithmetic, which must hold for any loads).
WORKER_LOADS = [
    load("r_hand_grip", [0.01, -0.02, -0.03], [8.0, -5.0, -49.05], [1.5, -0.5, 0.8]),
    load("l_hand_grip", [0.0, 0.015, 0.0], [-3.0, 6.0, -49.05], [-0.4, 0.9, -0.3]),
    load("r_foot", [0.09, -0.02, -0.068], [25.0, 30.0, 410.0], [0.0, 0.0, 2.5]),
    load("l_foot", [-0.04, 0.03, -0.068], [-15.0, -10.0, 395.0], [0.3, -0.2, -1.5]),
    # a seat's reaction at the ischial tuberosities (0.055 x stature below the mid-hip point)
    load("pelvis", [0.01, -0.005, -0.0965], [4.0, -2.0, 610.0], [0.0, 0.0, 0.7]),
]
# Sitting: the pelvis lowered and moved back by about a thigh's length, hips and knees at 90 deg
# (the feet wherever the legs put them: the loads are arbitrary).
SEATED = {"pelvis_tx": -0.42, "pelvis_tz": -0.42, "pelvis_tilt": -0.1, "lumbar_flexion": 0.15,
          "r_hip_flexion": math.pi / 2, "l_hip_flexion": math.pi / 2,
          "r_knee_flexion": math.pi / 2, "l_knee_flexion": math.pi / 2,
          "r_shoulder_flexion": 0.6, "r_elbow_flexion": 1.1, "neck_flexion": 0.3}

ROBOTS = [
    ("worker", "robots/worker.urdf", WORKER_LOADS, [
        ("standing", STAND), ("stoop", STOOP), ("squat", SQUAT), ("reach", REACH),
        ("asymmetric", ASYM), ("turned", TURNED),
        ("staggered", (STAGGERED_BODY, STAGGERED_FEET)),  # (body, feet): see feet_placed
        ("seated", SEATED),
    ]),
    ("two_link", "tests/data/two_link.urdf",
     [load("tip", [0.0, 0.0, 0.0], [0.0, 0.0, -49.05], [0.0, 0.0, 0.0]),
      load("fore", [0.05, 0.01, -0.02], [7.0, -3.0, 12.0], [0.2, 1.1, -0.4])], [
        ("zero", {}), ("bent", {"shoulder": 0.7, "elbow": 1.2}),
        ("down", {"shoulder": -1.3, "elbow": 2.4}),
    ]),
    ("tree", "tests/data/tree.urdf",
     [load("tip", [0.02, -0.01, 0.03], [3.0, -20.0, -45.0], [0.5, 0.0, -1.0]),
      load("side2", [0.0, 0.05, -0.1], [-6.0, 4.0, 15.0], [0.0, 0.7, 0.2]),
      load("l2", [0.1, 0.0, 0.0], [0.0, 9.0, -2.0], [0.0, 0.0, 0.0])], [
        ("a", {"j1": 0.3, "j2": -0.7, "j3": 0.1, "j4": 1.1, "js": 0.4, "js2": -0.9}),
        ("b", {"j1": -1.2, "j2": 0.9, "j3": -0.15, "j4": -0.4, "js": 2.0, "js2": 0.3}),
    ]),
    ("geometry", "tests/data/geometry.urdf",
     [load("tool", [0.01, 0.02, -0.03], [5.0, -8.0, -30.0], [0.4, -0.3, 0.2]),
      load("a2_mid", [0.0, 0.03, 0.0], [-2.0, 1.0, 6.0], [0.0, 0.5, 0.0]),
      load("b2", [0.02, -0.05, 0.01], [3.0, 3.0, -12.0], [-0.2, 0.0, 0.6]),
      load("c1", [0.04, 0.0, 0.02], [0.0, -4.0, 2.0], [0.1, 0.1, 0.1])], [
        ("zero", {}),
        ("a", {"ja1": 0.4, "ja2": -2.5, "ja3": 0.12, "ja4": 1.3, "jb1": -0.1, "jb2": 3.5,
               "jc1": -0.8}),
        ("b", {"ja1": -1.1, "ja2": 4.0, "ja3": -0.2, "ja4": -2.2, "jb1": 0.3, "jb2": -1.2,
               "jc1": 1.5}),
    ]),
]


def set_q(model, values):
    q = pin.neutral(model)
    for name, v in values.items():
        if not model.existJointName(name):
            raise SystemExit(f"no joint {name}")
        j = model.joints[model.getJointId(name)]
        if j.nq == 2:  # continuous: (cos, sin)
            q[j.idx_q], q[j.idx_q + 1] = math.cos(v), math.sin(v)
        else:
            q[j.idx_q] = v
    return q


def feet_placed(model, body, feet):
    """The posture `body` with each leg's six joints solved so that each foot of `feet` stands flat
    on the floor where it says: its link frame at (x, y, the nominal stance's height), rotated by
    the yaw about the vertical only (roll and pitch zero). Gauss-Newton on the foot frame's
    placement error log6(target^-1 oMf) (all six: x, y, height, roll, pitch, yaw) over the leg's six
    joints, with Pinocchio's frame Jacobian (LOCAL) through Jlog6; the joints must end within their
    URDF limits."""
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    # the nominal (neutral posture's) foot frame heights: soles on the floor
    heights = {foot: data.oMf[model.getFrameId(foot, pin.FrameType.BODY)].translation[2]
               for foot in feet}
    q = set_q(model, dict(body, **{f"{s}_knee_flexion": 0.2 for s in "lr"}))
    for foot, (x, y, yaw) in feet.items():
        fid = model.getFrameId(foot, pin.FrameType.BODY)
        z = heights[foot]
        target = pin.SE3(pin.rpy.rpyToMatrix(0.0, 0.0, yaw), np.array([x, y, z]))
        cols = [model.joints[model.getJointId(f"{foot[0]}_{j}")].idx_v for j in LEG]
        for _ in range(100):
            pin.framesForwardKinematics(model, data, q)
            err_m = target.actInv(data.oMf[fid])
            err = pin.log6(err_m).vector
            if np.linalg.norm(err) < 1e-14:
                break
            J = pin.Jlog6(err_m) @ pin.computeFrameJacobian(model, data, q, fid,
                                                             pin.ReferenceFrame.LOCAL)
            q[cols] -= np.linalg.solve(J[:, cols], err)
        else:
            raise SystemExit(f"{foot}: no flat placement (error {np.linalg.norm(err):.1e})")
        for j in LEG:
            i = model.getJointId(f"{foot[0]}_{j}")
            v = q[model.joints[i].idx_q]
            lo = model.lowerPositionLimit[model.joints[i].idx_q]
            hi = model.upperPositionLimit[model.joints[i].idx_q]
            if not lo <= v <= hi:
                raise SystemExit(f"{foot[0]}_{j} = {v:.3f} outside [{lo:.3f}, {hi:.3f}]")
    return q


def angle_of(model, q, name):
    j = model.joints[model.getJointId(name)]
    if j.nq == 2:
        return math.atan2(q[j.idx_q + 1], q[j.idx_q])
    return float(q[j.idx_q])


def by_joint(model, names, vec):
    return {n: float(vec[model.joints[model.getJointId(n)].idx_v]) for n in names}


def columns(model, names, mat):
    return {n: [float(x) for x in mat[:, model.joints[model.getJointId(n)].idx_v]] for n in names}


def run(key, path, loads, postures):
    model = pin.buildModelFromUrdf(path)
    names = [model.names[i] for i in range(1, model.njoints)]
    links = [f.name for f in model.frames if f.type == pin.FrameType.BODY]
    # an operational frame at each load point, on the joint that moves its link
    load_frames = []
    for e, ld in enumerate(loads):
        lf = model.frames[model.getFrameId(ld["link"], pin.FrameType.BODY)]
        placement = lf.placement * pin.SE3(np.eye(3), np.array(ld["point_in_link_m"]))
        fid = model.addFrame(pin.Frame(f"load{e}", lf.parentJoint, model.getFrameId(ld["link"]),
                                       placement, pin.FrameType.OP_FRAME))
        load_frames.append(fid)
    data = model.createData()
    root = model.inertias[0]  # the root link, fixed to the universe
    cases = []
    for pname, qn in postures:
        q = feet_placed(model, *qn) if isinstance(qn, tuple) else set_q(model, qn)
        zero = np.zeros(model.nv)
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacements(model, data)
        pin.computeJointJacobians(model, data, q)
        fext = pin.StdVec_Force()
        for _ in range(model.njoints):
            fext.append(pin.Force.Zero())
        out_loads = []
        for e, ld in enumerate(loads):
            fid = load_frames[e]
            jid = model.frames[fid].parentJoint
            p_w = data.oMf[fid].translation.copy()
            F = np.array(ld["force_n"], dtype=float)
            M = np.array(ld["moment_nm"], dtype=float)
            oMi = data.oMi[jid]
            R, o = oMi.rotation, oMi.translation
            # spatial force about the joint origin, in the joint frame
            fext[jid] = fext[jid] + pin.Force(R.T @ F, R.T @ (np.cross(p_w - o, F) + M))
            J = pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
            out_loads.append(dict(ld, point_world_m=[float(x) for x in p_w],
                                  jacobian_linear=columns(model, names, J[:3, :]),
                                  jacobian_angular=columns(model, names, J[3:, :])))
        tau = pin.rnea(model, data, q, zero, zero, fext)
        g = pin.computeGeneralizedGravity(model, data, q)
        dg = pin.computeGeneralizedGravityDerivatives(model, data, q)
        com_p = pin.centerOfMass(model, data, q).copy()
        jcom_p = pin.jacobianCenterOfMass(model, data, q).copy()
        m_moving = data.mass[0]
        m_total = m_moving + root.mass
        com = (m_moving * com_p + root.mass * root.lever) / m_total if m_total > 0 else com_p
        jcom = jcom_p * (m_moving / m_total) if m_total > 0 else jcom_p
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacements(model, data)
        placements = {}
        for ln in links:
            X = data.oMf[model.getFrameId(ln, pin.FrameType.BODY)]
            placements[ln] = {"position_m": [float(x) for x in X.translation],
                              "rotation": [[float(x) for x in row] for row in X.rotation]}
        cases.append({
            "name": pname,
            "q_rad": {n: angle_of(model, q, n) for n in names},
            "loads": out_loads,
            "tau_nm": by_joint(model, names, tau),
            "tau_gravity_nm": by_joint(model, names, g),
            # rows: torque of joint r, columns: angle of joint c, both in the order of "joints"
            "dtau_gravity_dq": [[float(dg[model.joints[model.getJointId(r)].idx_v,
                                          model.joints[model.getJointId(c)].idx_v])
                                 for c in names] for r in names],
            "com_m": [float(x) for x in com],
            "com_jacobian": columns(model, names, jcom),
            "com_pinocchio_m": [float(x) for x in com_p],
            "com_jacobian_pinocchio": columns(model, names, jcom_p),
            "links": placements,
        })
    doc = {"generator": f"pinocchio {pin.__version__} (tests/data/pinocchio_golden.py)",
           "robot": path, "gravity_m_s2": [float(x) for x in model.gravity.linear],
           "total_mass_kg": float(m_total), "root_mass_kg": float(root.mass),
           "joints": names, "cases": cases}
    os.makedirs(OUT, exist_ok=True)
    with open(f"{OUT}/{key}.json", "w") as f:
        # one line per posture: the files are read by the tests, not by people
        head = {k: v for k, v in doc.items() if k != "cases"}
        f.write(json.dumps(head, indent=1)[:-2] + ',\n "cases": [\n')
        f.write(",\n".join("  " + json.dumps(c) for c in cases))
        f.write("\n ]\n}\n")
    print(f"{OUT}/{key}.json: {len(cases)} postures, {len(names)} joints, {len(loads)} loads")


for key, path, loads, postures in ROBOTS:
    run(key, path, loads, postures)
