#!/usr/bin/env python3
"""The shipped tasks planned with the feet fixed and with a standing area (docs/results.md,
"Stepping and turning"): total fatigue U, the largest trunk twist and turn against the feet, RULA and REBA, steps per
cycle, converged phases and the shift verdict.

    cargo build --release && python3 docs/tools/stance_table.py

Each task is planned twice (`posture-opt plan --json`): as shipped (feet on the nominal stance;
side_transfer without its `stance` line) and with `stance: {area_m: ±0.5 m square}` (side_transfer
as shipped). Temporary task files are written next to the shipped ones (their `robot:` paths are
relative) and removed. Prints a Markdown table.
"""
import os

from plan_json import ROOT, plan
TASKS = ["shelf", "shelf_lowered", "shelf_high", "shelf_heavy", "shelf_two_hands",
         "bench_assembly", "overhead_drilling", "pallet", "pallet_raised", "side_transfer"]
AREA = "stance: {area_m: [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]]}"


def run(task, text):
    path = os.path.join(ROOT, "tasks", f".stance_table_{task}.yaml")
    with open(path, "w") as f:
        f.write(text)
    try:
        d = plan(path)
    finally:
        os.remove(path)
    phases, a = d["summary"]["phases"], d["assessment"]
    return dict(
        u=d["summary"]["total_u"],
        twist=max(abs(p["angles"]["trunk_twist_deg"]) for p in a["phases"]),
        turn=max(abs(p["angles"]["trunk_twist_deg"] + p["angles"]["pelvis_turn_deg"])
                 for p in a["phases"]),
        rula=a["rula_max"], reba=a["reba_max"],
        steps=sum(p["feet"]["steps"] for p in phases if p.get("feet"))
        + ((d["summary"].get("rest_feet") or {}).get("steps") or 0),
        converged=f"{sum(p['converged'] for p in phases)}/{len(phases)}",
        verdict=a["verdict"]["status"].replace("_", " "),
    )


def main():
    print("| task | feet fixed: U [min], twist / turn, RULA, REBA, verdict | standing area: U [min], twist / turn, "
          "RULA, REBA, steps per cycle, converged phases, verdict |")
    print("|---|---|---|")
    for t in TASKS:
        text = open(os.path.join(ROOT, "tasks", f"{t}.yaml")).read()
        shipped_area = any(l.startswith("stance:") for l in text.splitlines())
        fixed_text = "\n".join(l for l in text.splitlines() if not l.startswith("stance:")) + "\n"
        placed_text = text if shipped_area else text + "\n" + AREA + "\n"
        f, p = run(t, fixed_text), run(t, placed_text)
        print(f"| {t} | {f['u']:.2f}, {f['twist']:.0f}° / {f['turn']:.0f}°, {f['rula']}, {f['reba']}, {f['verdict']} | "
              f"{p['u']:.2f}, {p['twist']:.0f}° / {p['turn']:.0f}°, {p['rula']}, {p['reba']}, {p['steps']}, "
              f"{p['converged']}, {p['verdict']} |", flush=True)


if __name__ == "__main__":
    main()
