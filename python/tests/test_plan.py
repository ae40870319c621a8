"""plan(): the same document as `posture-opt plan --json`, from a file, a dict or YAML text."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

import posture_opt as po
from conftest import QUICK, QUICK_OVERHEAD

REL = 1e-9


@pytest.fixture(scope="module")
def quick_plan():
    return po.plan(QUICK)


def key_figures(doc):
    s = doc["summary"]
    return {
        "task": doc["task"],
        "joints": doc["joints"],
        "half_joint_ids": doc["half_joint_ids"],
        "phases": [p["phase"] for p in s["phases"]],
        "steps": len(doc["steps"]["t_s"]),
        "exhaustion": s["exhaustion"],
        "worst_half_joint": s["worst_half_joint"],
        "lowest_capacity_half_joint": s["lowest_capacity_half_joint"],
    }


def test_plan_matches_cli(cli, quick_plan):
    ref = cli.json("plan", "--json", QUICK)
    py = quick_plan
    assert set(py) == set(ref)  # the same keys as the command line's document
    assert key_figures(py) == key_figures(ref)
    s, r = py["summary"], ref["summary"]
    assert s["total_u"] == pytest.approx(r["total_u"], rel=REL)
    assert s["lowest_capacity"] == pytest.approx(r["lowest_capacity"], rel=REL)
    assert s["duration_s"] == pytest.approx(r["duration_s"], rel=REL)
    for p, q in zip(s["phases"], r["phases"]):
        assert p["hand_error_m"] == pytest.approx(q["hand_error_m"], rel=REL, abs=1e-12)
    np.testing.assert_allclose(py["steps"]["capacity"], np.array(ref["steps"]["capacity"]), rtol=REL)
    np.testing.assert_allclose(py["steps"]["fatigue_u_min"], np.array(ref["steps"]["fatigue_u_min"]), rtol=REL, atol=1e-15)
    np.testing.assert_allclose(py["steps"]["t_s"], ref["steps"]["t_s"], rtol=REL)
    assert py["steps"]["phase"] == ref["steps"]["phase"]
    assert py["steps"]["posture"].tolist() == ref["steps"]["posture"]
    np.testing.assert_allclose(s["final_capacity"], r["final_capacity"], rtol=REL)
    for a, b in zip(py["postures"], ref["postures"]):
        np.testing.assert_allclose(a["q_rad"], b["q_rad"], rtol=REL, atol=1e-12)
    # the assessment
    a, b = py["assessment"], ref["assessment"]
    assert a["rula_max"] == b["rula_max"] and a["reba_max"] == b["reba_max"]
    assert a["capable_women"] == pytest.approx(b["capable_women"], rel=REL)
    assert a["meaning"]["words"] == b["meaning"]["words"]


def test_plan_arrays(quick_plan):
    steps = quick_plan["steps"]
    n, nh = len(steps["t_s"]), len(quick_plan["half_joint_ids"])
    assert isinstance(steps["capacity"], np.ndarray) and steps["capacity"].shape == (n, nh)
    assert steps["fatigue_u_min"].shape == (n, nh)
    assert steps["cycle"].dtype == np.int64 and steps["posture"].dtype == np.int64
    assert np.all((steps["capacity"] > 0) & (steps["capacity"] <= 1))
    # JSON again
    import json

    json.dumps(po.jsonable(quick_plan))


def test_plan_from_dict_and_yaml_is_the_same(quick_plan):
    path = Path(QUICK)
    task = po.load_task(QUICK)
    from_yaml = po.load_task(path.read_text(), path=QUICK)
    from_dict = po.load_task(task.to_dict(), path=QUICK)
    assert from_yaml.to_dict() == task.to_dict() == from_dict.to_dict()
    d = po.plan(from_dict)
    assert key_figures(d) == key_figures(quick_plan)
    assert d["summary"]["total_u"] == quick_plan["summary"]["total_u"]  # deterministic


def test_task_properties():
    t = po.load_task(QUICK_OVERHEAD)
    assert t.name == "Quick overhead (panel at 1.95 m)"
    assert t.path == QUICK_OVERHEAD
    assert t.phases == ["hold panel", "fetch"]
    assert t.cycles == 4 and t.rest_s == 2.0
    assert t.cycle_s == pytest.approx(26.0) and t.duration_s == pytest.approx(104.0)
    assert t.nq == len(t.joint_names) > 10
    assert len(t.half_joint_ids) == len(t.groups)
    assert t.worker["sex"] == "male"
    assert t.hand_frames[0]
    assert "Quick overhead" in repr(t)
    schema = po.task_schema()
    assert "properties" in schema and "phases" in schema["properties"]


def test_plan_options_match_cli(cli):
    ref = cli.json("plan", "--json", "--no-adapt", "--fatigue-only", "--capacity-floor", "0.8", QUICK)
    py = po.plan(QUICK, adapt=False, fatigue_only=True, capacity_floor=0.8)
    assert py["summary"]["adaptive"] is False and py["summary"]["fatigue_only"] is True
    assert key_figures(py) == key_figures(ref)
    assert py["summary"]["total_u"] == pytest.approx(ref["summary"]["total_u"], rel=REL)
    assert py["assessment"]["rest"]["capacity_floor"] == 0.8
    assert py["assessment"]["rest"]["rohmert"]["rest_s_per_cycle"] == pytest.approx(
        ref["assessment"]["rest"]["rohmert"]["rest_s_per_cycle"], rel=REL
    )


def test_plan_releases_the_gil():
    """A Python thread keeps running while Rust plans (the GIL is released)."""
    import threading
    import time

    task = po.load_task(QUICK)
    ticks = []
    stop = threading.Event()

    def tick():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.005)

    th = threading.Thread(target=tick)
    th.start()
    time.sleep(0.05)
    t0 = time.perf_counter()
    po.plan(task)
    t1 = time.perf_counter()
    stop.set()
    th.join()
    during = [t for t in ticks if t0 < t < t1]
    # with the GIL held the ticker could not run at all while planning
    assert len(during) > 0.2 * (t1 - t0) / 0.005, (len(during), t1 - t0)
