#!/usr/bin/env python3
"""The shipped tasks planned within ISO 11226 / EN 1005-4's acceptable zones (the default) and
without them (`--no-zones`), held plans (docs/results.md, "Acceptable posture zones"): total
fatigue U, the largest trunk twist and turn against the feet, RULA and REBA, converged phases, the EN 1005-4 and ISO 11226
criteria and the shift verdict, and the zones the targets force the posture beyond.

    cargo build --release && python3 docs/tools/posture_zones_table.py

Each task is planned twice with `posture-opt plan --no-adapt --json` (and `--no-zones`). Prints a
Markdown table, then the forced excesses.
"""
from plan_json import plan, shipped
TASKS = ["shelf", "shelf_lowered", "shelf_high", "shelf_heavy", "shelf_two_hands",
         "bench_assembly", "overhead_drilling", "pallet", "pallet_raised", "side_transfer",
         "bench_seated"]


def run(task, extra):
    d = plan(shipped(task), ["--no-adapt", *extra])
    phases, a = d["summary"]["phases"], d["assessment"]
    crit = {c["id"]: c["status"].replace("_", " ") for c in a["verdict"]["criteria"]}
    return dict(
        u=d["summary"]["total_u"],
        twist=max(abs(p["angles"]["trunk_twist_deg"]) for p in a["phases"] if p.get("angles")),
        turn=max(abs(p["angles"]["trunk_twist_deg"] + p["angles"]["pelvis_turn_deg"])
                 for p in a["phases"] if p.get("angles")),
        rula=a["rula_max"], reba=a["reba_max"],
        converged=f"{sum(p['converged'] for p in phases)}/{len(phases)}",
        iso=crit.get("iso_11226"), en=crit.get("en_1005_4"),
        verdict=a["verdict"]["status"].replace("_", " "),
        outside=[(p["phase"], z["what"], z["angle_deg"], z["limit_deg"], z["source"])
                 for p in phases for z in p["outside_zones"]],
    )


def cells(r):
    return (f"{r['u']:.2f}, {r['twist']:.0f}° / {r['turn']:.0f}°, {r['rula']}, {r['reba']}, {r['converged']}, "
            f"{r['iso']} / {r['en']}, {r['verdict']}")


def main():
    print("| task | without zones: U [min], twist / turn against the feet, RULA, REBA, converged, ISO 11226 / EN 1005-4, "
          "verdict | within zones (default): the same |")
    print("|---|---|---|")
    forced = []
    for t in TASKS:
        free, kept = run(t, ["--no-zones"]), run(t, [])
        print(f"| {t} | {cells(free)} | {cells(kept)} |", flush=True)
        forced += [(t,) + o for o in kept["outside"]]
    print()
    print("Zones the targets force (within zones):")
    for t, ph, what, ang, lim, src in forced:
        print(f"* {t} '{ph}': {what} {ang:.0f}° (at most {lim:.0f}°, {src})")


if __name__ == "__main__":
    main()
