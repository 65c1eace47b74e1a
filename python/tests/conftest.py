"""Shared fixtures: the repository's root, and the command line run from it."""

import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def root() -> pathlib.Path:
    """The repository's root (where `models/` and the command line live)."""
    return ROOT


@pytest.fixture(scope="session")
def command_line():
    """Runs the `chaplygin` command line and returns its standard output:
    the binary `CHAPLYGIN_CLI` names (`python/test.sh` builds it), else
    `cargo run`, which builds it if need be."""
    binary = os.environ.get("CHAPLYGIN_CLI")
    command = [binary] if binary else ["cargo", "run", "--quiet", "--bin", "chaplygin", "--"]

    def run(*arguments: str) -> str:
        completed = subprocess.run(
            [*command, *arguments],
            cwd=ROOT,
            capture_output=True,
            text=True,
            check=False,
        )
        assert completed.returncode == 0, completed.stderr
        return completed.stdout

    return run
