#!/usr/bin/env python3
"""Abridge a posture-opt JSON document for docs/plan-json.md: every key is kept, every array is cut to
one element — its most complete (the one with the most keys, nested keys counted; the first
among equals), so that an optional object such as a baseline's `exhaustion` shows its keys —
followed by a string "... (N more)", numbers are rounded to 4 significant
digits, arrays of plain values are written on one line. The result is valid JSON with the same
key structure as the document.

    posture-opt plan tasks/pallet.yaml --json | python3 docs/tools/json_example.py > example.json
    posture-opt plan tasks/pallet.yaml --json | python3 docs/tools/json_example.py --update

With --update [FILE] (default docs/plan-json.md, beside this script's folder) the ```json block
after the marker `<!-- pallet plan json -->` in FILE is replaced by the result (the example that
tests/suite/cli.rs checks against a real run) instead of printing it.
"""
import os
import json
import sys


def key_count(v):
    if isinstance(v, dict):
        return sum(1 + key_count(x) for x in v.values())
    if isinstance(v, list):
        return max((key_count(x) for x in v), default=0)
    return 0


def abridge(v):
    if isinstance(v, dict):
        return {k: abridge(x) for k, x in v.items()}
    if isinstance(v, list):
        if not v:
            return []
        best = max(range(len(v)), key=lambda i: (key_count(v[i]), -i))
        head = [abridge(v[best])]
        if len(v) > 1:
            head.append(f"... ({len(v) - 1} more)")
        return head
    if isinstance(v, float):
        return float(f"{v:.4g}")
    return v


def dump(v, indent=0):
    pad = " " * indent
    if isinstance(v, dict):
        if not v:
            return "{}"
        items = [f'{pad} {json.dumps(k, ensure_ascii=False)}: {dump(x, indent + 1)}' for k, x in v.items()]
        return "{\n" + ",\n".join(items) + "\n" + pad + "}"
    if isinstance(v, list) and any(isinstance(x, (dict, list)) for x in v):
        items = [pad + " " + dump(x, indent + 1) for x in v]
        return "[\n" + ",\n".join(items) + "\n" + pad + "]"
    return json.dumps(v, ensure_ascii=False)


MARKER = "<!-- pallet plan json -->"


def update(path, example):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    start = text.index(MARKER)
    open_at = text.index("```json\n", start) + len("```json\n")
    close_at = text.index("\n```", open_at)
    with open(path, "w", encoding="utf-8") as f:
        f.write(text[:open_at] + example + text[close_at:])


if __name__ == "__main__":
    example = dump(abridge(json.load(sys.stdin)))
    if len(sys.argv) > 1 and sys.argv[1] == "--update":
        default = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "plan-json.md")
        update(sys.argv[2] if len(sys.argv) > 2 else default, example)
    else:
        print(example)
