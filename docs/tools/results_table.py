"""Prints the planner results table (docs/results.md) from `posture-opt plan TASK --json` documents.

Usage: python3 docs/tools/results_table.py [POSTURE_OPT]   (default: target/release/posture-opt)
Run from the repository root; it plans every task listed below (a few minutes).
"""
import json
import subprocess
import sys

TASKS = [
    ("shelf.yaml", "4 kg, one hand, boards 1.10/1.40 m"),
    ("shelf_lowered.yaml", "boards 0.95/1.25 m"),
    ("shelf_high.yaml", "6 kg, boards 1.25/1.55 m"),
    ("shelf_heavy.yaml", "6 kg"),
    ("shelf_two_hands.yaml", "4 kg box, both hands"),
    ("bench_assembly.yaml", "female worker"),
    ("overhead_drilling.yaml", None),
    ("pallet.yaml", "8 kg, pallet at 0.30 m, 2 h"),
    ("pallet_raised.yaml", "pallet on a lift table"),
    ("bench_seated.yaml", "female worker, seated"),
]


def ended(e):
    words = "exceeds strength" if e.get("exceeds_strength") else "exhausted"
    return f"{words} at {e['t_s']:.0f} s"


def baseline(s, name):
    b = next(b for b in s["baselines"] if b["name"] == name)
    if b["exhaustion"]:
        return ended(b["exhaustion"])
    return f"{b['total_u']:.1f} ({100 * b['change']:+.0f} %)".replace("+", "")


def main():
    exe = sys.argv[1] if len(sys.argv) > 1 else "target/release/posture-opt"
    for task, words in TASKS:
        out = subprocess.run([exe, "plan", f"tasks/{task}", "--json"], check=True,
                             capture_output=True, text=True).stdout
        d = json.loads(out)
        s, a = d["summary"], d["assessment"]
        label = f"{task} ({words})" if words else task
        total = f"{s['total_u']:.1f}" if not s["exhaustion"] else ended(s["exhaustion"])
        cells = [
            label,
            total,
            f"{s['lowest_capacity']:.2f} ({s['lowest_capacity_half_joint']})",
            baseline(s, "fatigue_unaware"),
            baseline(s, "minimum_joint_load"),
            baseline(s, "nearest_neutral"),
            f"{a['rula_max']} / {a['reba_max']}",
            f"{a['back_compression_max_n']:.0f}",
            f"{100 * a['capable_men']:.0f} % / {100 * a['capable_women']:.0f} %",
        ]
        print("| " + " | ".join(cells) + " |")


if __name__ == "__main__":
    main()
