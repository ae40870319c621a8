"""Prints the assessment-zone table (docs/results.md): each shipped task planned (default, adaptive) with
`objective.zone_weight` 0 (the default), 30 and 300.

Usage: python3 docs/tools/zone_table.py [POSTURE_OPT]   (default: target/release/posture-opt)
Run from the repository root (needs PyYAML); it writes each variant as tasks/.zone_NAME.yaml
next to the task (so its relative paths hold), plans it and deletes it. About five minutes.
"""
import json
import math
import os
import subprocess
import sys

import yaml

TASKS = [
    "shelf", "shelf_lowered", "shelf_high", "shelf_heavy", "shelf_two_hands",
    "bench_assembly", "overhead_drilling", "pallet", "pallet_raised",
]
WEIGHTS = [0, 30, 300]


def plan(binary, task, weight):
    d = yaml.safe_load(open(f"tasks/{task}.yaml"))
    if weight:
        d.setdefault("objective", {})["zone_weight"] = weight
    path = f"tasks/.zone_{task}.yaml"
    with open(path, "w") as f:
        yaml.safe_dump(d, f, sort_keys=False)
    try:
        out = subprocess.run([binary, "plan", path, "--json"], check=True, capture_output=True, text=True)
    finally:
        os.remove(path)
    return json.loads(out.stdout)


def largest_deg(doc, names):
    joints = doc["joints"]
    return max(
        abs(math.degrees(q))
        for p in doc["summary"]["phases"]
        for j, q in zip(joints, p["q_rad"])
        if j in names
    )


def row(binary, task):
    docs = [plan(binary, task, w) for w in WEIGHTS]
    cols = [
        [f"{d['summary']['total_u']:.1f}" for d in docs],
        [f"{largest_deg(d, {'lumbar_axial_rotation'}):.0f}" for d in docs],
        [f"{largest_deg(d, {'r_wrist_flexion', 'l_wrist_flexion'}):.0f}" for d in docs],
        [str(max(p['reba']['reba_score'] for p in d['assessment']['phases'])) for d in docs],
        [f"{100 * d['assessment']['capable_women']:.0f} %" for d in docs],
        [f"{sum(p['converged'] for p in d['summary']['phases'])}/{len(d['summary']['phases'])}" for d in docs],
    ]
    return f"| {task} | " + " | ".join(" / ".join(c) for c in cols) + " |"


def main():
    binary = sys.argv[1] if len(sys.argv) > 1 else "target/release/posture-opt"
    print("| task | U [min] | largest trunk twist [°] | largest wrist flexion [°] | worst REBA "
          "| women strong enough | phases converged |")
    print("|---|---|---|---|---|---|---|")
    for task in TASKS:
        print(row(binary, task), flush=True)


if __name__ == "__main__":
    main()
