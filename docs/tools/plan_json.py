"""What the table scripts in docs/tools share: where the repository and the release binary are,
and one `posture-opt plan --json` run read back as a dict (the script stops with the binary's
message if the plan fails)."""
import json
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.path.join(ROOT, "target", "release", "posture-opt")


def shipped(task):
    """The path of a shipped task file, `tasks/<task>.yaml`."""
    return os.path.join(ROOT, "tasks", f"{task}.yaml")


def plan(path, args=()):
    """`posture-opt plan <path> --json <args>` as a dict."""
    r = subprocess.run([EXE, "plan", path, "--json", *args], capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f"{path}: {r.stderr}")
    return json.loads(r.stdout)
