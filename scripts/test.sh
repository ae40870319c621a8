#!/usr/bin/env bash
# Sets up what the tests need on a fresh Debian/Ubuntu machine and runs every test:
#   * the Rust tests (release build, shared with `cargo run --release`), including the HTML
#     report's render test in headless Chromium (installed here if missing);
#   * the Python package's tests (a venv under target/, maturin, pytest, numpy, ray).
# Needs the Rust toolchain (rustc >= 1.89), python3 (>= 3.9) with venv, and network access to
# crates.io, PyPI and the Debian archive.
set -euo pipefail
cd "$(dirname "$0")/.."

as_root() {
  if [ "$(id -u)" -eq 0 ]; then "$@"; elif command -v sudo >/dev/null 2>&1; then sudo "$@"; else
    echo "need root (or sudo) to install: $*" >&2; exit 1; fi
}

if ! command -v cargo >/dev/null 2>&1; then
  echo "cargo not found: install the Rust toolchain (https://rustup.rs) first" >&2
  exit 1
fi
if ! command -v chromium >/dev/null 2>&1; then
  echo "installing chromium (headless render test of the HTML report)"
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq chromium >/dev/null
fi
if ! python3 -c 'import venv, ensurepip' >/dev/null 2>&1; then
  echo "installing python3-venv"
  as_root apt-get update -qq
  DEBIAN_FRONTEND=noninteractive as_root apt-get install -y -qq python3-venv >/dev/null
fi

# The render test must not skip here.
export POSTURE_OPT_REQUIRE_CHROMIUM=1
cargo test --release --locked

# The Python package, built by maturin into a venv (same target directory, same release build
# of the library).
VENV=target/python-venv
if [ ! -x "$VENV/bin/python" ]; then
  python3 -m venv "$VENV"
fi
"$VENV/bin/python" -m pip install -q --upgrade pip
"$VENV/bin/python" -m pip install -q "maturin>=1.9,<2" "pytest>=7" "numpy>=1.21" "ray>=2.9"
(cd python && VIRTUAL_ENV="$PWD/../$VENV" PATH="$PWD/../$VENV/bin:$PATH" maturin develop --release --locked -q)
"$VENV/bin/python" -m pytest python/tests -q
