"""compare / sweep: the command line's results, and shards that merge into the single run."""

from __future__ import annotations

import json

import pytest

import posture_opt as po
from conftest import QUICK, QUICK_LOW

LAYOUTS = [QUICK, QUICK_LOW]
REL = 1e-9


@pytest.fixture(scope="module")
def comparison():
    return po.compare(LAYOUTS)


@pytest.fixture(scope="module")
def population():
    return po.sweep(QUICK, sample=3, seed=7)


def layout_figures(c):
    return [
        (o["rank"], o["index"], o["file"], o["task"], o["feasible"], o["worst_group"], o["exhaustion"], o["rula_max"])
        for o in c["layouts"]
    ]


def test_compare_matches_cli(cli, comparison):
    ref = cli.json("compare", "--json", *LAYOUTS)
    assert set(comparison) == set(ref)
    assert layout_figures(comparison) == layout_figures(ref)
    for a, b in zip(comparison["layouts"], ref["layouts"]):
        assert a["total_u_min"] == pytest.approx(b["total_u_min"], rel=REL)
        assert a["lowest_capacity"] == pytest.approx(b["lowest_capacity"], rel=REL)
    assert comparison["findings"] == ref["findings"]
    assert comparison["ranking_rule"] == po.RANKING_RULE


def test_compare_shards_merge_into_the_single_run(cli, comparison, tmp_path):
    shards = [po.compare(LAYOUTS, shard=(i, 2), threads=1) for i in range(2)]
    assert [s["shard"] for s in shards] == ["1/2", "2/2"]
    assert [len(s["outcomes"]) for s in shards] == [1, 1]
    assert po.merge_compare(shards) == comparison
    assert po.merge_compare(list(reversed(shards))) == comparison
    # the command line's shard results merge too, and the command line merges ours
    files = []
    for i in (1, 2):
        r = cli.run("compare", "--json", "--shard", f"{i}/2", *LAYOUTS)
        assert r.returncode == 0, r.stderr
        f = tmp_path / f"cli{i}.json"
        f.write_text(r.stdout)
        files.append(str(f))
        assert [o["index"] for o in json.loads(r.stdout)["outcomes"]] == [o["index"] for o in shards[i - 1]["outcomes"]]
    assert layout_figures(po.merge_compare(files)) == layout_figures(comparison)
    ours = []
    for i, s in enumerate(shards):
        f = tmp_path / f"py{i}.json"
        f.write_text(json.dumps(s))
        ours.append(str(f))
    assert layout_figures(cli.json("compare", "--merge", "--json", *ours)) == layout_figures(comparison)


def worker_figures(s):
    return [(w["index"], w["label"], w["worker"], w["can_do"], w["problems"], w["worst_group"]) for w in s["workers"]]


def test_sweep_matches_cli(cli, population):
    ref = cli.json("sweep", "--json", "--sample", "3", "--seed", "7", QUICK)
    assert set(population) == set(ref)
    assert worker_figures(population) == worker_figures(ref)
    for a, b in zip(population["workers"], ref["workers"]):
        assert a["total_u_min"] == pytest.approx(b["total_u_min"], rel=REL)
    assert population["population"] == ref["population"] == "sampled n=3 seed=7"
    assert population["cannot_do"] == ref["cannot_do"]
    assert population["sustain_all"] == ref["sustain_all"]


def test_sweep_shards_merge_into_the_single_run(population):
    shards = [po.sweep(QUICK, sample=3, seed=7, shard=(i, 2), threads=1) for i in range(2)]
    assert [w["index"] for w in shards[0]["workers"]] == [0, 2]
    assert [w["index"] for w in shards[1]["workers"]] == [1]
    assert po.merge_sweep(shards) == population
    # CLI-style shard strings, JSON text
    assert po.merge_sweep([json.dumps(s) for s in shards]) == population
    with pytest.raises(po.Error, match="missing|cover"):
        po.merge_sweep(shards[:1])


def test_standard_population_labels():
    # the population's members without planning: a one-worker shard of the standard population
    s = po.sweep(QUICK, shard=(5, 6))
    assert s["population"] == "P5/P50/P95 women and men"
    assert s["workers_total"] == 6 and len(s["workers"]) == 1
