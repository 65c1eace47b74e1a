#!/usr/bin/env bash
# The Python package's tests: a virtual environment in target/python-venv,
# the package built into it from this tree (unoptimized, sharing the
# workspace's build of the engine), then pytest, the command line it
# compares against built beside it.
set -euo pipefail
cd "$(dirname "$0")/.."

venv=target/python-venv
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet numpy scipy sympy pytest matplotlib pandas
CARGO_TARGET_DIR="$PWD/target" MATURIN_PEP517_ARGS="--profile dev" \
    "$venv/bin/python" -m pip install --quiet --force-reinstall --no-deps ./python
cargo build --quiet --bin chaplygin
CHAPLYGIN_CLI="$PWD/target/debug/chaplygin" "$venv/bin/python" -m pytest -q python/tests
