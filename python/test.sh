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
# The command line the tests compare against, copied before maturin's build
# (whose compiler flags differ) leaves the workspace's artifacts stale.
cargo build --quiet --bin chaplygin
cp target/debug/chaplygin "$venv/bin/chaplygin-cli"
CARGO_TARGET_DIR="$PWD/target" MATURIN_PEP517_ARGS="--profile dev" \
    "$venv/bin/python" -m pip install --quiet --force-reinstall --no-deps ./python
CHAPLYGIN_CLI="$PWD/$venv/bin/chaplygin-cli" "$venv/bin/python" -m pytest -q python/tests
