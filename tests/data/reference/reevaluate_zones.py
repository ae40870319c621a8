#!/usr/bin/env python3
"""Re-evaluates the stored best plan of results_zones/<task>.json with the current code, after a
change of the statement's zone angles (no search): rewrites best_objective, zone_slack_sum_rad,
zones_exceeded, zone_angles_deg and phase_local_optima_totals (+ spread.phase_local_optima), the
fields Search.result computes from the zone rows at the stored postures and pool, keeping the old
values in previous_f_x_axis; joint_local_optima are left as they are (joint_local_optima_note);
<task>.report.json is rewritten (Problem.evaluate of the best plan). Postures, U and feasibility
do not change (asserted). Used on 2026-12-06 for the statement's third revision (f from the hip
axis); prints what changed."""
import copy
import json
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, here)
import optimise as O  # noqa: E402

NOTE = ("joint_local_optima (objective, objective_check, total_u_min and the spread of "
        "joint_local_optima) were found and evaluated with the previous pelvis heading f (the x-axis "
        "heading, R_P x on the floor; the turn rows with the hip-axis heading) and are pending a "
        "re-run (optimise.py --zones --resume ... --rerun-joint); best_objective, zone_* and "
        "phase_local_optima_totals are re-evaluated under the third revision of 2026-12-06 (f from "
        "the hip axis) at the stored postures and pool")


def main(key):
    path = os.path.join(here, "results_zones", f"{key}.json")
    with open(path) as fh:
        old = json.load(fh)
    s = O.Search(key, old.get("budget_s", 900.0), log=lambda m: None, zones=True)
    s.load_previous(path)           # best plan re-evaluated (offer -> plan_total), pool loaded
    new, rep = s.result()
    res = copy.deepcopy(old)
    assert abs(new["best_total_u_min"] - old["best_total_u_min"]) <= 1e-9 * old["best_total_u_min"]
    assert new["feasible"] == old["feasible"] and new["postures"] == old["postures"]
    assert new["gaze"] == old["gaze"] and new["residuals"] == old["residuals"]
    res["previous_f_x_axis"] = dict(best_objective=old["best_objective"],
                                    zone_slack_sum_rad=old["zone_slack_sum_rad"])
    for k in ("best_objective", "zone_slack_sum_rad", "zones_exceeded_note", "zones_exceeded",
              "zone_angles_deg", "phase_local_optima_totals"):
        res[k] = new[k]
    # spread.phase_local_optima as augment computes it (its other parts are left as they are)
    aug = O.augment(dict(phase_local_optima_totals=new["phase_local_optima_totals"]), s.t, {},
                    zones=True)
    res["spread"]["phase_local_optima"] = aug["spread"]["phase_local_optima"]
    res["joint_local_optima_note"] = NOTE
    with open(path, "w") as fh:
        json.dump(res, fh, indent=1)
    with open(path.replace(".json", ".report.json"), "w") as fh:
        json.dump(rep, fh, indent=1)
    # report
    dmax, where = 0.0, None
    for ph, rows in res["zone_angles_deg"].items():
        for row, v in rows.items():
            d = abs(v - old["zone_angles_deg"][ph][row])
            if d > dmax:
                dmax, where = d, (ph, row, old["zone_angles_deg"][ph][row], v)
    print(f"{key}: best_objective {old['best_objective']:.10g} -> {res['best_objective']:.10g}; "
          f"zone_slack_sum_rad {old['zone_slack_sum_rad']:.6g} -> {res['zone_slack_sum_rad']:.6g}; "
          f"total U {res['best_total_u_min']:.10g} min (unchanged)")
    print(f"  largest zone angle change {dmax:.6f} deg: {where}")
    for ph, rows in res["zones_exceeded"].items():
        for z in rows:
            print(f"  exceeded: {ph}: {z['row']} {z['angle_deg']:.4f} deg > {z['limit_deg']:.1f} "
                  f"(+{z['excess_deg']:.4f})")
    for ph, v in res["phase_local_optima_totals"].items():
        if v and v[0] < res["best_objective"] - 1e-6:
            print(f"  pool: {ph}: a pool posture gives {v[0]:.6f} < best (a pool swap would improve)")
    # the whole-plan local optima's postures in the pool (label = start), re-evaluated: reported only
    pool = {}
    with open(path.replace(".json", ".pool.json")) as fh:
        for g, lst in json.load(fh).items():
            pool[g] = [(d["label"], d["posture"]) for d in lst]
    for d in old["joint_local_optima"]:
        qs = []
        for g in s.t.groups:
            q = [p for lab, p in pool[g["name"]] if lab == d["start"]]
            qs.append(s.b.q_from_dict(q[0]) if q else None)
        if any(q is None for q in qs):
            print(f"  joint optimum {d['start']}: postures not in the pool")
            continue
        r = s.pr.evaluate(qs)
        print(f"  joint optimum {d['start']}: objective {d['objective']:.6f} -> {r['objective']:.6f} "
              f"(U {r['total_u_min']:.4f}, stored {d['total_u_min']:.4f})")


if __name__ == "__main__":
    for k in sys.argv[1:] or ["shelf", "bench_assembly"]:
        main(k)
