#!/usr/bin/env python3
"""The shipped tasks' postures and RULA/REBA before and after the planner learnt the standards'
acceptable zones, the gaze and the posture terms (README.md, "Before and after").

    cargo build --release && python3 docs/tools/before_after_table.py

"Before" is the plan the planner makes without them — `--fatigue-only --no-zones --no-gaze`: the
least fatigue, nothing else (the body and the strength data are today's in both). "After" is the
default plan. Both are held plans (`--no-adapt`) with the feet where the task puts them. Per plan:
total fatigue U, and over the phases the largest trunk twist (against the pelvis), the largest
turn of the trunk against the feet (the twist plus the pelvis's turn on the feet), side bend and
forward inclination (trunk flexion), the head's largest inclination from upright (forward
positive, the largest magnitude) and its largest turn against the trunk, the worst RULA and
REBA. Prints a Markdown table.
"""
from plan_json import plan, shipped
TASKS = ["shelf", "shelf_lowered", "shelf_high", "shelf_heavy", "shelf_two_hands",
         "bench_assembly", "bench_seated", "overhead_drilling", "pallet", "pallet_raised",
         "side_transfer"]
BEFORE = ["--fatigue-only", "--no-zones", "--no-gaze"]


def run(task, extra):
    d = plan(shipped(task), ["--no-adapt", *extra])
    a = d["assessment"]
    angles = [p["angles"] for p in a["phases"] if p.get("angles")]

    def largest(key):
        return max((x[key] for x in angles), key=abs)

    return dict(
        u=d["summary"]["total_u"],
        twist=abs(largest("trunk_twist_deg")),
        turn=max(abs(x["trunk_twist_deg"] + x["pelvis_turn_deg"]) for x in angles),
        bend=abs(largest("trunk_side_bend_deg")),
        stoop=max(x["trunk_flexion_deg"] for x in angles),
        head=largest("head_inclination_deg"),
        head_turn=abs(largest("neck_twist_deg")),
        rula=a["rula_max"], reba=a["reba_max"],
    )


def cells(r):
    return (f"{r['u']:.1f} | {r['twist']:.0f}° / {r['turn']:.0f}° / {r['bend']:.0f}° / "
            f"{r['stoop']:.0f}° | {r['head']:+.0f}° / {r['head_turn']:.0f}° | {r['rula']} | {r['reba']}")


def main():
    print("| task | before: U [min] | twist / turn / side bend / stoop | head bow / turn | RULA "
          "| REBA | after: U [min] | twist / turn / side bend / stoop | head bow / turn | RULA "
          "| REBA |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for t in TASKS:
        before, after = run(t, BEFORE), run(t, [])
        print(f"| {t} | {cells(before)} | {cells(after)} |", flush=True)


if __name__ == "__main__":
    main()
