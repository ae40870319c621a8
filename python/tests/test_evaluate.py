"""evaluate(): arrays in, arrays out, against `posture-opt evaluate --json`; the streaming
Evaluator against the offline evaluation and `evaluate --stream`."""

from __future__ import annotations

import json

import numpy as np
import pytest

import posture_opt as po

RECORDING = "recordings/shelf_plan.csv"
REL = 1e-9


def read_recording(path=RECORDING):
    with open(path) as f:
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    cols = {name: data[:, i] for i, name in enumerate(header)}
    t = cols.pop("t_s")
    force = np.stack([cols.pop("force_x_n"), cols.pop("force_y_n"), cols.pop("force_z_n")], axis=1)
    return t, cols, force


@pytest.fixture(scope="module")
def recording():
    return read_recording()


@pytest.fixture(scope="module")
def offline(recording):
    t, q, force = recording
    return po.evaluate(t, q, force)


def same_evaluation(py, ref, source=True):
    for k in ("robot", "worker", "fatigue_parameters", "hold_rule", "standing", "half_joint_ids", "groups", "samples",
              "worst_group", "lowest_capacity_group", "samples_outside_range"):
        assert py[k] == ref[k], k
    if source:
        assert py["source"] == ref["source"]
    for k in ("duration_s", "total_u_min", "worst_u_min", "lowest_capacity", "lowest_capacity_t_s"):
        assert py[k] == pytest.approx(ref[k], rel=REL), k
    np.testing.assert_allclose(py["final_capacity"], ref["final_capacity"], rtol=REL)
    np.testing.assert_allclose(py["final_fatigue_u_min"], ref["final_fatigue_u_min"], rtol=REL)
    assert len(py["exhaustions"]) == len(ref["exhaustions"])
    for a, b in zip(py["exhaustions"], ref["exhaustions"]):
        assert (a["half_joint"], a["group"], a["exceeds_capacity_at_start"]) == (b["half_joint"], b["group"], b["exceeds_capacity_at_start"])
        assert a["t_s"] == pytest.approx(b["t_s"], rel=REL)
        assert a["load"] == pytest.approx(b["load"], rel=REL)
    tl, rt = py["timeline"], ref["timeline"]
    assert tl["stride"] == rt["stride"]
    np.testing.assert_allclose(tl["t_s"], rt["t_s"], rtol=REL)
    for k in ("capacity", "fatigue_u_min", "load"):
        np.testing.assert_allclose(tl[k], np.array(rt[k]), rtol=REL, atol=1e-15)


def test_arrays_match_cli(cli, offline):
    ref = cli.json("evaluate", "--json", RECORDING)
    assert offline["source"] == "arrays"
    assert set(offline) == set(ref) | {"per_sample"}
    same_evaluation(offline, ref, source=False)
    assert len(offline["exhaustions"]) > 0  # the recording does exhaust the shoulder


def test_arrays_out(offline, recording):
    t = recording[0]
    ps = offline["per_sample"]
    n, nh = len(t), len(offline["half_joint_ids"])
    for k in ("capacity", "fatigue_u_min", "load"):
        assert isinstance(ps[k], np.ndarray) and ps[k].shape == (n, nh)
    np.testing.assert_array_equal(ps["t_s"], t)
    np.testing.assert_array_equal(ps["capacity"][-1], offline["final_capacity"])
    np.testing.assert_array_equal(ps["capacity"][0], np.ones(nh))  # rested at the first sample
    assert ps["capacity"].min() == offline["lowest_capacity"]
    assert offline["timeline"]["capacity"].shape == (len(offline["timeline"]["t_s"]), nh)


def test_file_matches_cli(cli):
    ref = cli.json("evaluate", "--json", RECORDING)
    same_evaluation(po.evaluate_file(RECORDING), ref)


def test_file_with_task_and_loads_matches_cli(cli, tmp_path):
    # joint angles only, constant loads in both hands, the body of a task file
    t, q, _ = read_recording()
    path = tmp_path / "angles.csv"
    names = list(q)
    with open(path, "w") as f:
        f.write(",".join(["t_s"] + names) + "\n")
        for i in range(len(t)):
            f.write(",".join(repr(float(x)) for x in [t[i]] + [q[n][i] for n in names]) + "\n")
    ref = cli.json("evaluate", "--json", "--task", "tasks/shelf.yaml", "--right-load-kg", "3", "--left-load-kg", "1.5", str(path))
    py = po.evaluate(t, q, task="tasks/shelf.yaml", hand_load_kg=(3.0, 1.5))
    same_evaluation(py, ref, source=False)
    same_evaluation(po.evaluate_file(path, task="tasks/shelf.yaml", hand_load_kg=(3, 1.5)), ref)


def test_degrees(offline, recording):
    t, q, force = recording
    qd = {k: np.degrees(v) for k, v in q.items()}
    d = po.evaluate(t, qd, force, degrees=True)
    np.testing.assert_allclose(d["per_sample"]["capacity"], offline["per_sample"]["capacity"], rtol=1e-9)


def test_matrix_and_both_hands_forms(offline, recording):
    t, q, force = recording
    task = po.default_setup()
    qm = np.zeros((len(t), task.nq))
    for name, col in q.items():
        qm[:, task.joint_names.index(name)] = col
    both = np.zeros((len(t), 2, 3))
    both[:, 0, :] = force
    a = po.evaluate(t, qm, both, task=task)
    b = po.evaluate(t, qm, {"right": force, "left": np.zeros_like(force)}, task=task)
    for d in (a, b):
        np.testing.assert_array_equal(d["per_sample"]["capacity"], offline["per_sample"]["capacity"])
        assert d["total_u_min"] == offline["total_u_min"]


def test_streaming_equals_offline(offline, recording):
    t, q, force = recording
    ev = po.Evaluator()
    assert ev.half_joint_ids == offline["half_joint_ids"]
    events = []
    for i in range(len(t)):
        line = ev.push(t[i], {k: v[i] for k, v in q.items()}, force[i])
        assert line["t_s"] == t[i]
        np.testing.assert_array_equal(line["capacity"], offline["per_sample"]["capacity"][i])
        np.testing.assert_array_equal(line["fatigue_u_min"], offline["per_sample"]["fatigue_u_min"][i])
        np.testing.assert_array_equal(ev.load, offline["per_sample"]["load"][i])
        events.extend(line["exhausted"])
    assert ev.samples == len(t) and ev.t_s == t[-1]
    assert events == offline["exhaustions"] == ev.exhaustions
    doc = ev.result()
    assert doc["source"] == "stream"
    same_evaluation(doc, offline, source=False)
    np.testing.assert_array_equal(doc["final_capacity"], offline["final_capacity"])


def test_push_many_equals_offline(offline, recording):
    t, q, force = recording
    ev = po.Evaluator()
    half = len(t) // 2
    n1 = ev.push_many(t[:half], {k: v[:half] for k, v in q.items()}, force[:half])
    n2 = ev.push_many(t[half:], {k: v[half:] for k, v in q.items()}, force[half:])
    assert n1 + n2 == len(offline["exhaustions"])
    np.testing.assert_array_equal(ev.capacity, offline["final_capacity"])
    same_evaluation(ev.result(), offline, source=False)


def test_streaming_matches_cli_stream(cli, recording):
    t, q, force = recording
    n = 200
    with open(RECORDING) as f:
        lines = [f.readline() for _ in range(n + 1)]
    r = cli.run("evaluate", "--stream", stdin="".join(lines))
    assert r.returncode == 0, r.stderr
    out = [json.loads(x) for x in r.stdout.splitlines()]
    head, body = out[0], out[1:]
    ev = po.Evaluator()
    assert head["half_joint_ids"] == ev.half_joint_ids and head["hold_rule"] == po.HOLD_RULE
    assert len(body) == n
    for i, ref in enumerate(body):
        line = ev.push(t[i], {k: v[i] for k, v in q.items()}, force[i])
        np.testing.assert_allclose(line["capacity"], ref["capacity"], rtol=REL)
        np.testing.assert_allclose(line["fatigue_u_min"], ref["fatigue_u_min"], rtol=REL, atol=1e-15)
        assert [e["half_joint"] for e in line["exhausted"]] == [e["half_joint"] for e in ref["exhausted"]]
