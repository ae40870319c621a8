"""Bad input raises posture_opt.Error (a ValueError) with the command line's message."""

from __future__ import annotations

import numpy as np
import pytest

import posture_opt as po
from conftest import QUICK, QUICK_LOW


def test_error_is_a_value_error():
    assert issubclass(po.Error, ValueError)
    assert issubclass(po.PlanningError, RuntimeError)


def test_missing_file_same_message(cli):
    msg = cli.error("plan", "python/tests/data/no_such_task.yaml")
    with pytest.raises(po.Error) as e:
        po.load_task("python/tests/data/no_such_task.yaml")
    assert str(e.value) == msg


@pytest.mark.parametrize(
    "name, text",
    [
        ("unknown_field", "name: x\nworker: {sex: male, stature_m: 1.75, mass_kg: 78}\nphases: []\ncycles: 1\nwrker: 3\n"),
        ("bad_stature", "name: x\nworker: {sex: male, stature_m: 3.5, mass_kg: 78}\nphases: [{name: a, target_m: [0.4, -0.2, 1.0], duration_s: 1}]\ncycles: 1\n"),
        ("no_phases", "name: x\nworker: {sex: male, stature_m: 1.75, mass_kg: 78}\nphases: []\ncycles: 1\n"),
        ("bad_sex", "name: x\nworker: {sex: robot, stature_m: 1.75, mass_kg: 78}\nphases: [{name: a, target_m: [0.4, -0.2, 1.0], duration_s: 1}]\ncycles: 1\n"),
        ("not_yaml", "name: [unclosed\n"),
    ],
)
def test_bad_task_same_message(cli, tmp_path, name, text):
    f = tmp_path / f"{name}.yaml"
    f.write_text(text)
    msg = cli.error("plan", str(f))
    with pytest.raises(po.Error) as e:
        po.load_task(str(f))
    assert str(e.value) == msg
    # the same text given as YAML, named like the file
    with pytest.raises(po.Error) as e2:
        po.load_task(text, path=str(f))
    assert str(e2.value) == msg


def test_bad_dict():
    with pytest.raises(po.Error, match="worker"):
        po.load_task({"name": "x", "worker": {"sex": "male", "stature_m": 9.0, "mass_kg": 70}, "phases": [], "cycles": 1})
    with pytest.raises(po.Error, match="not a task file's data"):
        po.load_task({"name": object()})
    with pytest.raises(TypeError):
        po.load_task(42)  # type: ignore[arg-type]


def test_bad_options():
    with pytest.raises(po.Error, match="capacity_floor: must be a number between 0 and 1"):
        po.plan(QUICK, capacity_floor=1.5)
    with pytest.raises(po.Error, match="shard"):
        po.compare([QUICK, QUICK_LOW], shard=(2, 2))
    with pytest.raises(po.Error, match="a shard is written i/n"):
        po.compare([QUICK, QUICK_LOW], shard="0/2")
    with pytest.raises(po.Error, match="threads must be"):
        po.compare([QUICK, QUICK_LOW], threads=0)
    with pytest.raises(po.Error, match="sample must be at least 1"):
        po.sweep(QUICK, sample=0)
    with pytest.raises(po.Error, match="a sweep needs a task loaded from a task file"):
        po.sweep(po.default_setup())
    with pytest.raises(po.Error, match="sex"):
        po.default_setup(sex="robot")


def test_merge_errors_same_message(cli, tmp_path):
    shard = po.compare([QUICK, QUICK_LOW], shard=(0, 2))
    f = tmp_path / "s1.json"
    import json

    f.write_text(json.dumps(shard))
    msg = cli.error("compare", "--merge", "--json", str(f))
    with pytest.raises(po.Error) as e:
        po.merge_compare([str(f)])
    assert str(e.value) == msg
    assert "missing [1]" in msg
    with pytest.raises(po.Error, match="appears in two shards"):
        po.merge_compare([shard, shard])
    with pytest.raises(po.Error, match="not a compare shard result"):
        po.merge_compare(['{"kind": 3}'])
    with pytest.raises(po.Error, match="not a sweep shard result"):
        po.merge_sweep([shard])


def test_evaluate_errors():
    task = po.default_setup()
    nq = task.nq
    q = np.zeros((3, nq))
    with pytest.raises(po.Error, match=r"sample 2 \(t = 0.5 s\): time 0.5 does not increase"):
        po.evaluate([0.0, 1.0, 0.5], q, task=task)
    with pytest.raises(po.Error, match=r"q: expected shape \(3, %d\)" % nq):
        po.evaluate([0.0, 1.0, 2.0], np.zeros((3, nq + 1)), task=task)
    with pytest.raises(po.Error, match="every value must be finite"):
        po.evaluate([0.0, np.nan], np.zeros((2, nq)), task=task)
    with pytest.raises(po.Error, match="is not a moving joint"):
        po.evaluate([0.0, 1.0], {"r_shoulder_flexon": [0.0, 0.1]}, task=task)
    with pytest.raises(po.Error, match="right_load_kg must be 0"):
        po.evaluate([0.0, 1.0], np.zeros((2, nq)), task=task, hand_load_kg=(-1.0, 0.0))
    with pytest.raises(po.Error, match="a hand force must be within"):
        po.evaluate([0.0, 1.0], np.zeros((2, nq)), np.full((2, 3), 2e4), task=task)
    k = task.joint_names.index("r_shoulder_flexion")
    deg = np.zeros((2, nq))
    deg[:, k] = 90.0  # degrees given as radians
    with pytest.raises(po.Error, match="degrees=True"):
        po.evaluate([0.0, 1.0], deg, task=task)
    ev = po.Evaluator(task)
    ev.push(0.0, np.zeros(nq))
    with pytest.raises(po.Error, match="does not increase"):
        ev.push(0.0, np.zeros(nq))
    assert ev.samples == 1  # the refused sample changed nothing
    with pytest.raises(po.Error, match="no samples"):
        po.Evaluator(task).result()
    with pytest.raises(po.Error, match="cannot read"):
        po.evaluate_file("recordings/none.csv")


def test_statics_errors(cli):
    msg = cli.error("statics", "--robot", "robots/worker.urdf", "--frame", "r_hand_grip", "--q", "r_shoulder_flexon=0.5")
    with pytest.raises(po.Error) as e:
        po.statics("robots/worker.urdf", "r_hand_grip", {"r_shoulder_flexon": 0.5})
    assert str(e.value) == msg
    with pytest.raises(po.Error, match="hand_load_kg must be within"):
        po.statics("robots/worker.urdf", "r_hand_grip", hand_load_kg=-2)
    with pytest.raises(po.Error, match="magnitude above 3 g"):
        po.statics("robots/worker.urdf", "r_hand_grip", gravity=[25.0, 25.0, 0.0])
