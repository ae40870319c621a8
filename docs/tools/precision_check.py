"""Measures how much the QP solver's precision moves each shipped task's plan (the planner goal:
settings that only change the solver's precision move the total by at most 1e-4, relative).

Usage: python3 docs/tools/precision_check.py [POSTURE_OPT] [--fatigue-only]
       (default binary: target/release/posture-opt)
Run from the repository root. Plans every task held (`--no-adapt`) at `--qp-tolerance` 1e-9 (the
default) and 1e-8 and prints one Markdown row per task: both totals and their relative change.
"""
import json
import subprocess
import sys

TASKS = [
    "shelf", "shelf_lowered", "shelf_high", "shelf_heavy", "shelf_two_hands",
    "bench_assembly", "overhead_drilling", "pallet", "pallet_raised", "side_transfer",
    "bench_seated",
]
GOAL = 1e-4


def total(binary, task, tol, extra):
    out = subprocess.run(
        [binary, "plan", f"tasks/{task}.yaml", "--no-adapt", "--json", "--qp-tolerance", tol, *extra],
        check=True, capture_output=True, text=True,
    )
    return json.loads(out.stdout)["summary"]["total_u"]


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    extra = [a for a in sys.argv[1:] if a.startswith("--")]
    binary = args[0] if args else "target/release/posture-opt"
    print("| task | U at 1e-9 [min] | U at 1e-8 [min] | relative change |")
    print("|---|---|---|---|")
    beyond = 0
    for task in TASKS:
        a, b = total(binary, task, "1e-9", extra), total(binary, task, "1e-8", extra)
        rel = abs(a - b) / a
        beyond += rel > GOAL
        print(f"| {task} | {a:.3f} | {b:.3f} | {rel:.1e}{' (beyond the goal)' if rel > GOAL else ''} |")
    print(f"\n{beyond} of {len(TASKS)} tasks beyond the {GOAL:g} goal")


if __name__ == "__main__":
    main()
