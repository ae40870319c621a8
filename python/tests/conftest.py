"""Shared fixtures: the repository, the command line binary and its JSON results (cached)."""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path
from typing import Any, Dict, Tuple

import pytest

PYTHON_DIR = Path(__file__).resolve().parents[1]
REPO = PYTHON_DIR.parent
DATA = Path(__file__).resolve().parent / "data"

# Quick tasks (a few seconds to plan each); paths relative to the repository, as the command line
# is run from there, so that results name the files the same way.
QUICK = "python/tests/data/quick_bench.yaml"
QUICK_LOW = "python/tests/data/quick_bench_low.yaml"
QUICK_OVERHEAD = "python/tests/data/quick_overhead.yaml"


# the Python calls see the same relative paths as the command line
os.chdir(REPO)


def cli_path() -> Path:
    env = os.environ.get("POSTURE_OPT_CLI")
    return Path(env) if env else REPO / "target" / "release" / "posture-opt"


@pytest.fixture(scope="session")
def repo() -> Path:
    return REPO


class Cli:
    """Runs `posture-opt` from the repository root, caching outputs by arguments."""

    def __init__(self, exe: Path) -> None:
        self.exe = exe
        self._cache: Dict[Tuple[str, ...], subprocess.CompletedProcess] = {}

    def run(self, *args: str, stdin: str | None = None) -> subprocess.CompletedProcess:
        key = tuple(args) + ((stdin,) if stdin is not None else ())
        if key not in self._cache:
            self._cache[key] = subprocess.run(
                [str(self.exe), *args], cwd=REPO, input=stdin, capture_output=True, text=True, timeout=1800
            )
        return self._cache[key]

    def json(self, *args: str) -> Any:
        r = self.run(*args)
        assert r.returncode == 0, f"posture-opt {' '.join(args)} failed ({r.returncode}): {r.stderr}"
        return json.loads(r.stdout)

    def error(self, *args: str) -> str:
        """The message of a failing run, without the `error: ` prefix."""
        r = self.run(*args)
        assert r.returncode == 2, f"posture-opt {' '.join(args)}: expected exit 2, got {r.returncode}: {r.stderr}"
        msg = r.stderr.strip()
        assert msg.startswith("error: "), msg
        return msg[len("error: ") :]


@pytest.fixture(scope="session")
def cli() -> Cli:
    exe = cli_path()
    if not exe.exists():
        why = f"{exe} not built: run `cargo build --release` first (or set POSTURE_OPT_CLI)"
        # CI sets this: a comparison with the CLI must not skip there
        if os.environ.get("POSTURE_OPT_REQUIRE_CLI") == "1":
            pytest.fail(why)
        pytest.skip(why)
    return Cli(exe)
