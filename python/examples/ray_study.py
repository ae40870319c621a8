#!/usr/bin/env python3
"""A population x layout study on Ray, through the posture_opt Python package.

For every workstation layout (a task file) the study plans

* the comparison of the layouts for the task's own worker (``posture_opt.compare``), and
* the population sweep of each layout (``posture_opt.sweep``): the 5th/50th/95th-percentile
  women and men, or ``--sample N`` workers drawn with ``--seed``.

Both are split into deterministic shards (item ``j`` belongs to shard ``j mod n``); each Ray task
runs one shard with one thread and returns the shard result (a small dict), and the driver merges
them with ``posture_opt.merge_compare`` / ``posture_opt.merge_sweep``. Planning is deterministic,
so the merged study equals the single-process run (``--local``) exactly. See docs/ray.md.

    python python/examples/ray_study.py tasks/shelf.yaml tasks/shelf_lowered.yaml \
        --sample 40 --shards 8 --out study.json              # a local Ray on this machine
    python python/examples/ray_study.py ... --address auto   # a running Ray cluster
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from typing import Any, Dict, List, Optional, Sequence, Tuple

import posture_opt as po


def _options(adapt: bool, fatigue_only: bool, capacity_floor: float) -> Dict[str, Any]:
    return {"adapt": adapt, "fatigue_only": fatigue_only, "capacity_floor": capacity_floor}


def _summary(comparison: Dict[str, Any], populations: Dict[str, Dict[str, Any]]) -> List[Dict[str, Any]]:
    """One row per layout, in the comparison's rank order."""
    rows = []
    for o in comparison["layouts"]:
        s = populations[o["file"]]
        rows.append(
            {
                "rank": o["rank"],
                "layout": o["file"],
                "task": o["task"],
                "feasible": o["feasible"],
                "u_per_hour_min": o["u_per_hour_min"],
                "minutes_to_exhaustion": o["minutes_to_exhaustion"],
                "workers": len(s["workers"]),
                "cannot_do": s["cannot_do"],
                "sustain_all": s["sustain_all"],
            }
        )
    return rows


def run_single_process(
    layouts: Sequence[str],
    *,
    sample: Optional[int] = None,
    seed: int = 1,
    adapt: bool = True,
    fatigue_only: bool = False,
    capacity_floor: float = po.DEFAULT_CAPACITY_FLOOR,
) -> Dict[str, Any]:
    """The whole study in this process (the reference the Ray run must equal)."""
    opts = _options(adapt, fatigue_only, capacity_floor)
    names = [os.fspath(p) for p in layouts]
    comparison = po.compare(list(layouts), names=names, **opts)
    populations = {n: po.sweep(p, sample=sample, seed=seed, **opts) for n, p in zip(names, layouts)}
    return {"comparison": comparison, "populations": populations, "summary": _summary(comparison, populations)}


def run_on_ray(
    layouts: Sequence[str],
    *,
    sample: Optional[int] = None,
    seed: int = 1,
    shards: int = 4,
    adapt: bool = True,
    fatigue_only: bool = False,
    capacity_floor: float = po.DEFAULT_CAPACITY_FLOOR,
) -> Dict[str, Any]:
    """The study on the Ray cluster `ray.init` connected to (started here if none).

    Each layout's sweep is split into `shards` shards and the comparison into
    min(shards, layouts) shards; every shard is one Ray task (1 CPU, 1 planning thread).
    """
    import ray

    if not ray.is_initialized():
        ray.init()
    opts = _options(adapt, fatigue_only, capacity_floor)
    names = [os.fspath(p) for p in layouts]
    # Validate every task here (a bad file fails before the cluster works) and ship the task
    # files' data, so the workers need no files: a dict plus the absolute path the task came from
    # (which locates a relative `robot:` URDF, the one file a worker may still need).
    tasks = [po.load_task(p) for p in layouts]
    data: List[Tuple[Dict[str, Any], str]] = []
    for t in tasks:
        d = t.to_dict()
        assert d is not None  # loaded from a file
        data.append((d, os.path.abspath(t.path)))

    # Nested functions are shipped by value: the workers only need `posture_opt` installed.
    @ray.remote(num_cpus=1)
    def sweep_shard(task: Dict[str, Any], path: str, i: int, n: int) -> Dict[str, Any]:
        t = po.load_task(task, path=path)
        return po.sweep(t, sample=sample, seed=seed, shard=(i, n), threads=1, **opts)

    @ray.remote(num_cpus=1)
    def compare_shard(i: int, n: int) -> Dict[str, Any]:
        ts = [po.load_task(d, path=p) for d, p in data]
        return po.compare(ts, names=names, shard=(i, n), threads=1, **opts)

    data_ref = [(ray.put(d), p) for d, p in data]
    n_compare = max(1, min(shards, len(layouts)))
    compare_refs = [compare_shard.remote(i, n_compare) for i in range(n_compare)]
    sweep_refs = {
        name: [sweep_shard.remote(d, p, i, shards) for i in range(shards)] for name, (d, p) in zip(names, data_ref)
    }
    # Shard results come back in any order; merging checks that each item appears exactly once.
    comparison = po.merge_compare(ray.get(compare_refs))
    populations = {name: po.merge_sweep(ray.get(refs)) for name, refs in sweep_refs.items()}
    return {"comparison": comparison, "populations": populations, "summary": _summary(comparison, populations)}


def _table(rows: List[Dict[str, Any]]) -> str:
    out = [f"{'rank':>4}  {'layout':<40} {'U/h [min]':>10} {'cannot do':>10} {'sustain (95% CI)':>22}"]
    for r in rows:
        s = r["sustain_all"]
        share = f"{s['share']:.0%} ({s['low']:.0%}-{s['high']:.0%})" if s else "-"
        out.append(
            f"{r['rank']:>4}  {r['layout']:<40} {r['u_per_hour_min']:>10.2f} {r['cannot_do']:>5}/{r['workers']:<4} {share:>22}"
        )
    return "\n".join(out)


def main(argv: Optional[Sequence[str]] = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("layouts", nargs="+", help="task files, one per layout")
    p.add_argument("--sample", type=int, help="workers drawn per layout (default: P5/P50/P95 women and men)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument("--shards", type=int, default=4, help="shards per sweep (Ray tasks per layout)")
    p.add_argument("--no-adapt", action="store_true")
    p.add_argument("--fatigue-only", action="store_true")
    p.add_argument("--capacity-floor", type=float, default=po.DEFAULT_CAPACITY_FLOOR)
    p.add_argument("--address", help="Ray cluster address (e.g. auto); default: start a local Ray")
    p.add_argument("--num-cpus", type=int, help="CPUs of the local Ray (default: all)")
    p.add_argument("--local", action="store_true", help="run in this process, without Ray")
    p.add_argument("--out", help="write the study (comparison, populations, summary) as JSON")
    a = p.parse_args(argv)
    kw = dict(sample=a.sample, seed=a.seed, adapt=not a.no_adapt, fatigue_only=a.fatigue_only, capacity_floor=a.capacity_floor)
    started = time.perf_counter()
    try:
        if a.local:
            study = run_single_process(a.layouts, **kw)
        else:
            import ray

            ray.init(address=a.address, num_cpus=a.num_cpus if a.address is None else None)
            study = run_on_ray(a.layouts, shards=a.shards, **kw)
    except po.Error as e:
        print(f"error: {e}", file=sys.stderr)
        return 2
    print(_table(study["summary"]))
    print(f"{len(a.layouts)} layouts in {time.perf_counter() - started:.0f} s", file=sys.stderr)
    if a.out:
        with open(a.out, "w", encoding="utf-8") as f:
            json.dump(po.jsonable(study), f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main())
