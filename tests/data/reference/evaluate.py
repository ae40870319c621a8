#!/usr/bin/env python3
"""Evaluate given postures with the reference model and print a JSON report.

    python3 evaluate.py TASK.yaml POSTURES.json [--rest REST.json] [--out FILE]

TASK.yaml: a task file (a bare key such as `shelf` means inputs/shelf.yaml).
POSTURES.json: one posture (joint name -> value, radians / metres) per distinct phase, in any of
these forms:
  * {"postures": {...}} or the mapping itself: phase name -> posture (any member name of a group of
    phases sharing a posture may be used; if several members are given they must agree);
  * a list with one posture per phase of the task (in task order) or per distinct phase;
  * a posture-opt plan-like object with "phases": [{"name": ..., "posture_rad"|"posture"|"q": {...}}]
    and optionally "summary": {"rest_posture_rad": {...}};
  * the JSON of `posture-opt plan --json` ("joints" and "summary.phases[].q_rad" lists).
Joints missing from a posture keep the value of the task's rest posture (reported as a warning).
"""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from reference import model as M  # noqa: E402


def _posture_of(entry):
    if isinstance(entry, dict):
        for k in ("posture_rad", "posture", "q", "joints"):
            if k in entry and isinstance(entry[k], dict):
                return entry[k]
        return entry
    raise ValueError("cannot read a posture from %r" % (entry,))


def read_postures(task, data):
    """Returns (list of q per distinct phase, rest q or None, warnings)."""
    b = task.body
    warn = []
    rest = None
    if isinstance(data, dict) and isinstance(data.get("joints"), list) and \
            isinstance(data.get("summary"), dict) and isinstance(data["summary"].get("phases"), list):
        # a `posture-opt plan --json` document: postures are lists in the order of "joints"
        names = data["joints"]
        summ = data["summary"]
        if isinstance(summ.get("rest_posture_rad"), list):
            rest = dict(zip(names, summ["rest_posture_rad"]))
        data = {ph["phase"]: dict(zip(names, ph["q_rad"])) for ph in summ["phases"]}
    if isinstance(data, dict) and isinstance(data.get("summary"), dict) and \
            isinstance(data["summary"].get("rest_posture_rad"), dict):
        rest = data["summary"]["rest_posture_rad"]
    if isinstance(data, dict) and "postures" in data:
        data = data["postures"]
    if isinstance(data, dict) and "phases" in data and isinstance(data["phases"], list):
        data = {ph.get("name"): _posture_of(ph) for ph in data["phases"]}
    per_group = [None] * task.P
    if isinstance(data, list):
        if len(data) == len(task.phases):
            items = [(ph.group, _posture_of(d)) for ph, d in zip(task.phases, data)]
        elif len(data) == task.P:
            items = [(gi, _posture_of(d)) for gi, d in enumerate(data)]
        else:
            raise ValueError(f"{len(data)} postures for {len(task.phases)} phases / {task.P} groups")
    else:
        name_to_group = {ph.name: ph.group for ph in task.phases}
        items = []
        for name, d in data.items():
            if name not in name_to_group:
                if name == "rest":
                    rest = _posture_of(d)
                    continue
                warn.append(f"unknown phase name {name!r} ignored")
                continue
            items.append((name_to_group[name], _posture_of(d)))
    for gi, d in items:
        missing = [n for n in b.joint_names if n not in d]
        if missing:
            warn.append(f"group {task.groups[gi]['name']!r}: joints missing, rest values used: {missing}")
        q = b.q_from_dict(d, base=task.rest_q)
        if per_group[gi] is not None and np.max(np.abs(per_group[gi] - q)) > 1e-9:
            warn.append(f"group {task.groups[gi]['name']!r}: members disagree; the first is used")
            continue
        if per_group[gi] is None:
            per_group[gi] = q
    for gi in range(task.P):
        if per_group[gi] is None:
            raise ValueError(f"no posture for phase group {task.groups[gi]['members']}")
    rest_q = None if rest is None else b.q_from_dict(rest, base=task.rest_q)
    return per_group, rest_q, warn


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("task")
    ap.add_argument("postures")
    ap.add_argument("--rest", default=None, help="rest posture JSON (default inputs/<task>.rest_posture.json "
                    "or the plan's summary.rest_posture_rad)")
    ap.add_argument("--out", default=None)
    a = ap.parse_args()
    task = M.load_task(a.task)
    with open(a.postures) as fh:
        data = json.load(fh)
    qs, rest_q, warn = read_postures(task, data)
    if a.rest:
        with open(a.rest) as fh:
            rest_q = task.body.q_from_dict(json.load(fh), base=task.rest_q)
    prob = M.Problem(task)
    if rest_q is not None:
        # the rest loads follow the rest posture used
        tau, _ = M.statics(task.body, rest_q, np.zeros(3), np.zeros(3))
        prob.rest_loads, _ = M.half_loads(task.body, rest_q, tau)
    rep = prob.evaluate(qs, rest_q=rest_q)
    rep["warnings"] = warn
    txt = json.dumps(rep, indent=1)
    if a.out:
        with open(a.out, "w") as fh:
            fh.write(txt)
    print(txt)


if __name__ == "__main__":
    main()
