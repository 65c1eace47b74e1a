#!/usr/bin/env bash
# The Python package's tests: a virtual environment in target/python-venv
# with the tests' dependencies (all that `python/test.sh dependencies`
# does), the package built into it from this tree (unoptimized, in the
# workspace's target directory), then pytest on every core (pytest-xdist),
# the command line it compares against built beside it.
set -euo pipefail
cd "$(dirname "$0")/.."

venv=target/python-venv
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
# Without byte-compiling what it installs: 22 s instead of 57 (the tests
# import a small part of it).
"$venv/bin/python" -m pip install --quiet --no-compile \
    numpy scipy sympy pytest pytest-xdist hypothesis matplotlib pandas 'dask[distributed]'
# `python/test.sh dependencies` stops here (CI prepares the environment
# beside its lints).
if [ "${1:-}" = dependencies ]; then
    exit 0
fi
# The command line the tests compare against: the binary the workspace's
# own tests run, built with their features (after `cargo test --workspace`,
# as in CI, nothing is rebuilt; `cargo build --bin` would resolve other
# features and rebuild the engine), copied before maturin's build (whose
# features differ again) leaves the workspace's artifacts stale.
cargo test --workspace --no-run --quiet
cp target/debug/chaplygin "$venv/bin/chaplygin-cli"
CARGO_TARGET_DIR="$PWD/target" MATURIN_PEP517_ARGS="--profile dev" \
    "$venv/bin/python" -m pip install --quiet --force-reinstall --no-deps ./python
CHAPLYGIN_CLI="$PWD/$venv/bin/chaplygin-cli" "$venv/bin/python" -m pytest -q -n auto python/tests
