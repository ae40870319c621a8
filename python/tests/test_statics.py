"""statics(): the `posture-opt statics --json` document, for a URDF file or a task's body."""

from __future__ import annotations

import numpy as np
import pytest

import posture_opt as po

URDF = "robots/worker.urdf"
POSE = {"r_shoulder_flexion": 1.2, "r_elbow_flexion": 0.6, "lumbar_flexion": 0.3}


def same(py, ref):
    assert py["frame"] == ref["frame"]
    np.testing.assert_allclose(py["position_m"], ref["position_m"], rtol=1e-12, atol=1e-15)
    assert [j["name"] for j in py["joints"]] == [j["name"] for j in ref["joints"]]
    for a, b in zip(py["joints"], ref["joints"]):
        for k in ("q_rad", "gravity_torque_nm", "load_torque_nm", "torque_nm"):
            assert a[k] == pytest.approx(b[k], rel=1e-12, abs=1e-12), (a["name"], k)
    np.testing.assert_allclose(np.asarray(py["jacobian"]), np.asarray(ref["jacobian"]), rtol=1e-12, atol=1e-15)


def test_urdf_matches_cli(cli):
    q = ",".join(f"{k}={v}" for k, v in POSE.items())
    ref = cli.json("statics", "--json", "--robot", URDF, "--frame", "r_hand_grip", "--q", q, "--hand-load-kg", "5")
    py = po.statics(URDF, "r_hand_grip", POSE, hand_load_kg=5.0)
    same(py, ref)
    # the arrays, in joint order
    n = len(py["joints"])
    assert py["joint_names"] == [j["name"] for j in ref["joints"]]
    assert py["torque_nm"].shape == (n,) and py["jacobian_matrix"].shape == (3, n)
    k = py["joint_names"].index("r_shoulder_flexion")
    assert py["q_rad"][k] == 1.2
    np.testing.assert_allclose(py["jacobian_matrix"][:, k], np.asarray(ref["jacobian"])[:, k])
    np.testing.assert_allclose(py["torque_nm"], py["gravity_torque_nm"] + py["load_torque_nm"], atol=1e-9)


def test_force_gravity_and_array_posture_match_cli(cli):
    ref = cli.json(
        "statics", "--json", "--robot", URDF, "--frame", "r_hand_grip", "--q", "r_shoulder_flexion=0.4",
        "--hand-force=10,-5,-30", "--gravity=0,0,-9.0",
    )
    names = [j["name"] for j in ref["joints"]]
    q = np.zeros(len(names))
    q[names.index("r_shoulder_flexion")] = 0.4
    same(po.statics(URDF, "r_hand_grip", q, hand_force=[10, -5, -30], gravity=(0, 0, -9.0)), ref)


def test_task_body():
    task = po.load_task("tasks/shelf.yaml")  # robots/worker.urdf, right hand r_hand_grip
    a = po.statics(task, q=POSE, hand_load_kg=2.0)
    b = po.statics(URDF, "r_hand_grip", POSE, hand_load_kg=2.0)
    same(a, b)
    # the generated worker: torques at the shoulder grow with the load
    w = po.default_setup()
    light = po.statics(w, q=POSE)
    heavy = po.statics(w, q=POSE, hand_load_kg=10.0)
    k = light["joint_names"].index("r_shoulder_flexion")
    assert abs(heavy["torque_nm"][k]) > abs(light["torque_nm"][k]) + 10
