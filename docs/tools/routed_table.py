#!/usr/bin/env python3
"""The shipped tasks planned with the default recovery (default-2026, one rate) and with the
two-deficit recovery (routed-2026): total fatigue U, the fatigue model's criterion and the shift
verdict (docs/fatigue-parameters.md, "A fast and a slow component").

    cargo build --release && python3 docs/tools/routed_table.py

Each task is planned as shipped (adaptive, the feet where the task puts them) and again from a
copy that adds `fatigue: {parameters: routed-2026}` (written beside it as
tasks/.routed_table_<task>.yaml, so that its relative paths resolve, and removed afterwards).
Prints a Markdown table.
"""
import os

from plan_json import ROOT, plan, shipped

TASKS = ["shelf", "shelf_lowered", "shelf_high", "shelf_heavy", "shelf_two_hands",
         "bench_assembly", "bench_seated", "overhead_drilling", "pallet", "pallet_raised",
         "side_transfer"]


def summary(d):
    v = d["assessment"]["verdict"]
    model = next(c for c in v["criteria"] if c["id"] == "fatigue_model")
    return d["summary"]["total_u"], model["status"], v["status"], v["binding"]


def main():
    print("| task | U default-2026 [min] | U routed-2026 [min] | the fatigue model's criterion | verdict (binding) |")
    print("|---|---|---|---|---|")
    for task in TASKS:
        base = summary(plan(shipped(task)))
        copy = os.path.join(ROOT, "tasks", f".routed_table_{task}.yaml")
        with open(shipped(task)) as fh:
            text = fh.read()
        with open(copy, "w") as fh:
            fh.write(text + "\nfatigue: {parameters: routed-2026}\n")
        try:
            routed = summary(plan(copy))
        finally:
            os.remove(copy)
        change = 100.0 * (routed[0] / base[0] - 1.0)
        same = lambda i: base[i] if base[i] == routed[i] else f"{base[i]} → {routed[i]}"
        verdict = (f"{base[2]} ({base[3]})" if base[2:] == routed[2:]
                   else f"{base[2]} ({base[3]}) → {routed[2]} ({routed[3]})")
        print(f"| {task} | {base[0]:.2f} | {routed[0]:.2f} ({change:+.1f} %) | {same(1)} | {verdict} |")


if __name__ == "__main__":
    main()
