#!/usr/bin/env python3
"""Regenerate everything: self-checks, then the global search of every task (one at a time).

    nice -n 10 python3 run_all.py [--budget SECONDS_PER_TASK] [--jobs 1] [--tasks shelf pallet ...]

Writes results/verification.json, results/<task>.json (+ .report.json, .log) and
results/summary.json.
"""
import argparse
import json
import os
import subprocess
import sys
import time
from concurrent.futures import ThreadPoolExecutor

HERE = os.path.dirname(os.path.abspath(__file__))
TASKS = ["shelf", "bench_assembly", "shelf_two_hands"]


def run_task(key, budget):
    t0 = time.time()
    cmd = [sys.executable, os.path.join(HERE, "optimise.py"), key, "--budget", str(budget)]
    with open(os.path.join(HERE, "results", f"{key}.stdout"), "w") as fh:
        rc = subprocess.call(cmd, stdout=fh, stderr=subprocess.STDOUT, cwd=HERE)
    return key, rc, time.time() - t0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--budget", type=float, default=600.0)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--tasks", nargs="*", default=TASKS)
    ap.add_argument("--skip-verify", action="store_true")
    a = ap.parse_args()
    os.makedirs(os.path.join(HERE, "results"), exist_ok=True)
    t0 = time.time()
    if not a.skip_verify:
        subprocess.check_call([sys.executable, os.path.join(HERE, "verify.py")], cwd=HERE)
    with ThreadPoolExecutor(max_workers=a.jobs) as ex:
        done = list(ex.map(lambda k: run_task(k, a.budget), a.tasks))
    summary = {}
    for key, rc, dt in done:
        path = os.path.join(HERE, "results", f"{key}.json")
        if rc != 0 or not os.path.exists(path):
            summary[key] = dict(error=f"exit code {rc}")
            continue
        with open(path) as fh:
            r = json.load(fh)
        summary[key] = dict(best_total_u_min=r["best_total_u_min"], exhausted=r["exhausted"],
                            exhaustion_time_min=r["exhaustion_time_min"],
                            feasible=r["feasible"]["ok"], starts=r["starts"]["count"],
                            joint_local_optima=r["local_optima_totals"],
                            joint_local_optima_median=r["spread"]["joint_local_optima"]["median"],
                            best_found_by=r["best_found_by"], runtime_s=r["runtime_s"])
    summary["_total_runtime_s"] = time.time() - t0
    with open(os.path.join(HERE, "results", "summary.json"), "w") as fh:
        json.dump(summary, fh, indent=1)
    print(json.dumps(summary, indent=1))


if __name__ == "__main__":
    main()
