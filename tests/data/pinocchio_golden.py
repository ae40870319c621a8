#!/usr/bin/env python3
"""Regenerates tests/data/pinocchio_golden.json with Pinocchio (pip install pin), an independent
implementation of forward kinematics, frame Jacobians and generalized gravity.

For each model and posture: the frame position, its 3xn positional Jacobian (world-aligned), the
gravity torque g(q) and the load torque -J^T F. q is given per joint name (pinocchio orders joints
itself). Run from the repository root:  python3 tests/data/pinocchio_golden.py
"""
import json
import numpy as np
import pinocchio as pin

CASES = [
    ("robots/worker.urdf", "hand_grip", [0.0, 0.0, -5.0 * 9.81], [
        {},
        {"lumbar_flexion": 0.3, "r_shoulder_flexion": 1.2, "r_elbow_flexion": 0.6},
        {"lumbar_flexion": 0.5, "lumbar_lateral_bending": -0.2, "lumbar_axial_rotation": 0.4,
         "r_shoulder_flexion": 0.9, "r_shoulder_abduction": 0.5, "r_shoulder_rotation": -0.3,
         "r_elbow_flexion": 1.4, "r_forearm_pronation": 0.7, "r_wrist_flexion": -0.4, "r_wrist_deviation": 0.2},
    ]),
    ("tests/data/tree.urdf", "tip", [3.0, -20.0, -45.0], [
        {"j1": 0.3, "j2": -0.7, "j3": 0.1, "j4": 1.1, "js": 0.4, "js2": -0.9},
        {"j1": -1.2, "j2": 0.9, "j3": -0.15, "j4": -0.4, "js": 2.0, "js2": 0.3},
    ]),
]

out = []
for path, frame, force, postures in CASES:
    model = pin.buildModelFromUrdf(path)
    data = model.createData()
    fid = model.getFrameId(frame)
    names = [model.names[i] for i in range(1, model.njoints)]
    for qn in postures:
        q = pin.neutral(model)
        for name, v in qn.items():
            jid = model.getJointId(name)
            q[model.joints[jid].idx_q] = v
        pin.forwardKinematics(model, data, q)
        pin.updateFramePlacements(model, data)
        pin.computeJointJacobians(model, data, q)
        J = pin.getFrameJacobian(model, data, fid, pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)[:3, :]
        g = pin.computeGeneralizedGravity(model, data, q)
        load = -J.T @ np.array(force)
        joints = {}
        for i, name in enumerate(names):
            iv = model.joints[model.getJointId(name)].idx_v
            joints[name] = {"q_rad": float(q[model.joints[model.getJointId(name)].idx_q]),
                            "gravity_torque_nm": float(g[iv]), "load_torque_nm": float(load[iv]),
                            "jacobian": [float(x) for x in J[:, iv]]}
        out.append({"robot": path, "frame": frame, "force_n": force,
                    "position_m": [float(x) for x in data.oMf[fid].translation], "joints": joints})

with open("tests/data/pinocchio_golden.json", "w") as f:
    json.dump({"generator": f"pinocchio {pin.__version__}", "cases": out}, f, indent=1)
print(f"wrote {len(out)} cases")
