#!/usr/bin/env python3
"""Check stored results against the held-object clearance (statement section 4, "held objects").

    python3 check_held.py [RESULT.json ...] [--out FILE]

Default: every results/*.json and results_zones/*.json whose task has a phase holding an `object`
with `size_m`. For each, the stored best plan is re-evaluated with the current model
(`Problem.evaluate`, which now reports `min_clearance_held_m` and includes it in `feasible`), and
the smallest clearance between the non-arm body capsules and the held boxes of each distinct
phase is recomputed exactly here (no far-pair lower bound): the minimum over the capsule's axis of
the box's signed distance (golden section, as `geometry.capsule_obstacle`) minus the radius. The
whole-plan local optima stored in `<result>.pool.json` (postures labelled by their start, as
`optimise.augment` reads them), when that file exists, are checked the same way, and every pool
posture is counted as within / outside the held-object clearance. Nothing is re-optimised and no
result file is rewritten.
"""
import glob
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference import geometry as geo  # noqa: E402
from reference import model as M  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))


def held_clearances(task, gi, q):
    """Exact min clearance [m] and its capsule link per held box of distinct phase gi (after fk)."""
    b = task.body
    b.fk(q)
    caps = b.world_capsules()
    out = []
    for k, (c, h) in enumerate(task.groups[gi]["held"]):
        best = (np.inf, None)
        for i in range(len(caps)):
            if b.capsules[i]["link"] in b.arm_links:
                continue
            a, bb, r = caps[i]
            sd, _, _ = geo._seg_convex_sd(a, bb, 0, c, np.eye(3), h, 0.0, 0.0)
            if sd - r < best[0]:
                best = (float(sd - r), b.capsules[i]["link"])
        out.append(dict(box=k, center_m=c.tolist(), size_m=(2 * h).tolist(),
                        min_clearance_m=best[0], link=best[1]))
    return out


def plan_check(task, prob, qs):
    rep = prob.evaluate(qs)
    phases = {}
    for gi, g in enumerate(task.groups):
        if not g["held"]:
            continue
        ex = held_clearances(task, gi, qs[gi])
        m = min(e["min_clearance_m"] for e in ex)
        r = rep["phases"][gi]["residuals"]
        phases[g["name"]] = dict(members=g["members"], min_clearance_held_m=m,
                                 closest_link=min(ex, key=lambda e: e["min_clearance_m"])["link"],
                                 per_box=ex,
                                 evaluate_min_clearance_held_m=r["min_clearance_held_m"],
                                 evaluate_pair=r["min_clearance_held_pair"],
                                 ok=m >= task.clearance - 1e-6)
    return rep, phases


def check(path):
    with open(path) as fh:
        res = json.load(fh)
    key = res["task"]
    task = M.load_task(key)
    if not any(g["held"] for g in task.groups):
        return None
    zones = bool(res.get("zones_on"))
    prob = M.Problem(task, zones=zones)
    b = task.body
    qs = [b.q_from_dict(res["postures"][g["name"]]) for g in task.groups]
    rep, phases = plan_check(task, prob, qs)
    out = dict(result=os.path.relpath(path, HERE), task=key, zones=zones,
               clearance_m=task.clearance,
               arm_links=sorted(l for l in b.arm_links if l in set(b.cap_links)),
               non_arm_capsule_links=sorted(set(b.capsules[i]["link"] for i in prob.pairs.nonarm_caps)),
               stored_best_total_u_min=res["best_total_u_min"],
               stored_best_objective=res.get("best_objective"),
               reevaluated_total_u_min=rep["total_u_min"],
               reevaluated_objective=rep["objective"],
               stored_feasible=res["feasible"]["ok"],
               feasible_with_held=rep["feasible"]["ok"],
               violations=rep["feasible"]["violations"],
               best_phases=phases)
    pool_path = path.replace(".json", ".pool.json")
    if os.path.exists(pool_path):
        with open(pool_path) as fh:
            pool = json.load(fh)
        jl = []
        for d in res.get("joint_local_optima", []):
            qd = [[p["posture"] for p in pool.get(g["name"], []) if p["label"] == d["start"]]
                  for g in task.groups]
            if any(not x for x in qd):
                jl.append(dict(start=d["start"], total_u_min=d["total_u_min"], postures="not in pool"))
                continue
            qs_l = [b.q_from_dict(x[0]) for x in qd]
            rep_l, ph_l = plan_check(task, prob, qs_l)
            jl.append(dict(start=d["start"], total_u_min=d["total_u_min"],
                           reevaluated_total_u_min=rep_l["total_u_min"],
                           feasible_with_held=rep_l["feasible"]["ok"],
                           violations=rep_l["feasible"]["violations"],
                           min_clearance_held_m={n: v["min_clearance_held_m"] for n, v in ph_l.items()}))
        out["joint_local_optima"] = jl
        cnt = {}
        for gi, g in enumerate(task.groups):
            if not g["held"]:
                continue
            vals = [min(e["min_clearance_m"] for e in held_clearances(task, gi, b.q_from_dict(p["posture"])))
                    for p in pool.get(g["name"], [])]
            cnt[g["name"]] = dict(count=len(vals),
                                  within=int(sum(v >= task.clearance - 1e-6 for v in vals)),
                                  min_m=min(vals) if vals else None, max_m=max(vals) if vals else None)
        out["pool_postures"] = cnt
    return out


def main():
    args = [a for a in sys.argv[1:]]
    out_file = None
    if "--out" in args:
        i = args.index("--out")
        out_file = args[i + 1]
        del args[i:i + 2]
    paths = args or sorted(p for d in ("results", "results_zones")
                           for p in glob.glob(os.path.join(HERE, d, "*.json"))
                           if not p.endswith((".pool.json", ".report.json", "verification.json",
                                              "summary.json")))
    report = []
    for p in paths:
        try:
            r = check(p)
        except Exception as ex:  # a result of another format: say so and go on
            r = dict(result=p, error=repr(ex))
        if r is None:
            continue
        report.append(r)
        if "error" in r:
            print(f"{p}: {r['error']}")
            continue
        print(f"{r['result']} ({r['task']}): best total U {r['stored_best_total_u_min']:.6f} min"
              + (f", objective {r['stored_best_objective']:.6f}" if r['stored_best_objective'] is not None else "")
              + f", stored feasible {r['stored_feasible']}, with held objects {r['feasible_with_held']}")
        for n, v in r["best_phases"].items():
            print(f"   {n} {v['members']}: min clearance to held box {v['min_clearance_held_m']:.5f} m "
                  f"({v['closest_link']}) {'ok' if v['ok'] else 'VIOLATED'}")
        for d in r.get("joint_local_optima", []):
            mc = d.get("min_clearance_held_m")
            print(f"   local optimum {d['start']} U {d['total_u_min']:.4f}: "
                  + (", ".join(f"{n} {v:.4f}" for n, v in mc.items()) if mc else str(d.get("postures")))
                  + (f" feasible {d['feasible_with_held']}" if mc else ""))
        for n, v in r.get("pool_postures", {}).items():
            print(f"   pool {n}: {v['within']}/{v['count']} within, min {v['min_m']:.4f} max {v['max_m']:.4f}")
    if out_file:
        with open(out_file, "w") as fh:
            json.dump(report, fh, indent=1)


if __name__ == "__main__":
    main()
