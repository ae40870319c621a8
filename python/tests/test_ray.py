"""The Ray recipe (examples/ray_study.py): a population x layout study run in shards on a local
Ray equals the single-process run."""

from __future__ import annotations

import importlib.util
import sys

import pytest

from conftest import PYTHON_DIR, QUICK, QUICK_LOW

ray = pytest.importorskip("ray")
pytestmark = pytest.mark.ray


def load_example():
    spec = importlib.util.spec_from_file_location("ray_study", PYTHON_DIR / "examples" / "ray_study.py")
    mod = importlib.util.module_from_spec(spec)
    sys.modules["ray_study"] = mod
    spec.loader.exec_module(mod)
    return mod


@pytest.fixture(scope="module")
def local_ray():
    ray.init(num_cpus=2, include_dashboard=False, log_to_driver=False, configure_logging=False)
    yield
    ray.shutdown()


def test_ray_study_equals_single_process(local_ray):
    study = load_example()
    layouts = [QUICK, QUICK_LOW]
    on_ray = study.run_on_ray(layouts, sample=3, seed=5, shards=2)
    single = study.run_single_process(layouts, sample=3, seed=5)
    assert on_ray["comparison"] == single["comparison"]
    assert on_ray["populations"] == single["populations"]
    assert on_ray["summary"] == single["summary"]
    assert sorted(r["layout"] for r in on_ray["summary"]) == sorted(layouts)
    assert [r["rank"] for r in on_ray["summary"]] == [1, 2]
    for pop in on_ray["populations"].values():
        assert pop["population"] == "sampled n=3 seed=5"
        assert [w["index"] for w in pop["workers"]] == [0, 1, 2]
