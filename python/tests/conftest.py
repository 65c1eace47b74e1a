"""Shared fixtures: the repository's root, and the command line run from it."""

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
    """Runs the `chaplygin` command line (built by cargo if need be) and
    returns its standard output."""

    def run(*arguments: str) -> str:
        completed = subprocess.run(
            ["cargo", "run", "--quiet", "--bin", "chaplygin", "--", *arguments],
            cwd=ROOT,
            capture_output=True,
            text=True,
            check=False,
        )
        assert completed.returncode == 0, completed.stderr
        return completed.stdout

    return run
