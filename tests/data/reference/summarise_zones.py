#!/usr/bin/env python3
"""Prints the markdown table of results_zones/<task>.json (what the code computed, nothing else)."""
import json
import os
import sys

here = os.path.dirname(os.path.abspath(__file__))
tasks = sys.argv[1:] or ["shelf", "bench_assembly"]
print("| task | distinct postures | best objective | total U [min] | zone slack sum [rad] | zones exceeded (> 1e-4 deg) | min gaze margin (s·d̂ − cos 15°) | max hand error [m] | min clearance obstacle / self [m] | min balance margin [m] | feasible | whole-plan local optima (objective / U) | starts | runtime [s] | checkpoint only? |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for t in tasks:
    p = os.path.join(here, "results_zones", f"{t}.json")
    if not os.path.exists(p):
        print(f"| {t} | (no result) |")
        continue
    r = json.load(open(p))
    ex = []
    for ph, rows in r["zones_exceeded"].items():
        for z in rows:
            ex.append(f"{ph}: {z['row']} +{z['excess_deg']:.3f}°")
    res = r["residuals"]
    herr = max(max(v["hand_error_m"].values()) for v in res.values())
    clo = min(v["min_clearance_obstacle_m"] for v in res.values())
    cls = min(v["min_clearance_self_m"] for v in res.values())
    bal = min(v["balance_margin_m"] for v in res.values())
    gm = [v["margin"] for v in r["gaze"].values() if v["margin"] is not None]
    jl = "; ".join(f"{d['objective']:.6f} / {d['total_u_min']:.4f}" for d in r["joint_local_optima"])
    print(f"| {t} | {len(r['postures'])} | {r['best_objective']:.9f} | {r['best_total_u_min']:.6f} | "
          f"{r['zone_slack_sum_rad']:.3g} | {'; '.join(ex) or 'none'} | {min(gm) if gm else None:.3g} | "
          f"{herr:.2g} | {clo:.4f} / {cls:.4f} | {bal:.4f} | {r['feasible']['ok']} | {jl} | "
          f"{r['starts']['count']} | {r['runtime_s']:.0f} | {r.get('checkpoint')} |")

# the sustainable whole-plan local optima (no muscle group exhausted) and the turn rows
print()
for t in tasks:
    p = os.path.join(here, "results_zones", f"{t}.json")
    if not os.path.exists(p):
        continue
    r = json.load(open(p))
    sus = sorted(d["objective"] for d in r["joint_local_optima"] if d.get("exhausted") is False)
    n = len(sus)
    med = (sus[n // 2] if n % 2 else 0.5 * (sus[n // 2 - 1] + sus[n // 2])) if n else None
    rows = next(iter(r["zone_angles_deg"].values()))
    print(f"{t}: {len(rows)} zone rows; {n} sustainable whole-plan local optima of "
          f"{len(r['joint_local_optima'])}, median objective {med if med is None else f'{med:.6f}'}")
    for ph, z in r["zone_angles_deg"].items():
        turn = z.get("trunk turn against the feet left")
        tw = z.get("trunk twist left")
        if turn is not None:
            print(f"  {ph}: twist {tw:.3f} deg, turn against the feet {turn:.3f} deg "
                  f"(pelvis {turn - tw:.3f} deg)")
