"""The Python examples of README.md and of the guide (docs/guide/) run as
written, and the installed package describes itself with the README."""

import email
import re
import shutil
from importlib import metadata

import pytest


def example(path, heading=None):
    """The one Python example of the Markdown file `path`, or of its
    section under `heading`."""
    text = path.read_text()
    if heading is not None:
        text = text.split(heading + "\n", 1)[1].split("\n## ", 1)[0]
    [code] = re.findall(r"```python\n(.*?)```", text, flags=re.S)
    return code


def run(code, name):
    """Runs `code` as a script (`__name__ == "__main__"`); its namespace."""
    namespace = {"__name__": "__main__"}
    exec(compile(code, name, "exec"), namespace)
    return namespace


@pytest.fixture
def in_scratch(root, tmp_path, monkeypatch):
    """A scratch directory holding a copy of `models/`, as the current one."""
    shutil.copytree(root / "models", tmp_path / "models")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_the_readmes_python_example_runs(root, in_scratch):
    namespace = run(example(root / "README.md", "## The same engine from Python"), "README.md")
    assert namespace["lin"].stable


def test_the_python_chapters_example_runs(root, in_scratch):
    run(example(root / "docs/guide/python.md"), "docs/guide/python.md")
    assert (in_scratch / "bicycle_lean.png").stat().st_size > 10_000
    assert (in_scratch / "bicycle_eigenvalues.png").stat().st_size > 5_000


def test_the_design_map_example_runs(root, in_scratch):
    """The Dask example of the guide's "Design maps": the map on every core
    equals the map on a local Dask cluster."""
    namespace = run(example(root / "docs/guide/stability.md", "## Design maps"), "docs/guide/stability.md")
    assert namespace["here"].shape == (2, 2)


def test_the_reversed_handlebars_example_runs(root):
    """The guide's hands-free turns with the handlebar reversed: stable
    from lean 0.63 (the grid value past the fold at 0.624) to 0.81, the
    change of stability at the fold, as the guide says."""
    namespace = run(
        example(root / "docs/guide/stability.md", "## Hands-free turns with the handlebar reversed"),
        "docs/guide/stability.md",
    )
    turns, stable = namespace["reversed_turns"], namespace["stable"]
    assert turns["lean"][stable].min() == pytest.approx(0.63, abs=1e-12)
    assert turns["lean"][stable].max() == pytest.approx(0.81, abs=1e-12)
    assert "stable from lean = 0.624183" in turns.report


def test_the_package_s_metadata_is_the_readme_the_licences_and_classifiers(root):
    """The installed wheel's METADATA (pyproject.toml's `readme`,
    `license-files` and `classifiers`): the README as the long description,
    both licence texts, and the package's audience, languages and topic."""
    text = metadata.distribution("chaplygin").read_text("METADATA")
    found = email.message_from_string(text)
    assert found["Description-Content-Type"].startswith("text/markdown")
    assert found.get_payload().strip() == (root / "README.md").read_text().strip()
    assert found["License-Expression"] == "MIT OR Apache-2.0"
    assert sorted(found.get_all("License-File")) == ["LICENSE-APACHE", "LICENSE-MIT"]
    licences = {path.name: path for path in metadata.files("chaplygin") if "licenses" in path.parts}
    for name in ["LICENSE-APACHE", "LICENSE-MIT"]:
        assert licences[name].read_text() == (root / name).read_text()
    classifiers = found.get_all("Classifier")
    for expected in [
        "Development Status :: 3 - Alpha",
        "Intended Audience :: Science/Research",
        "Programming Language :: Rust",
        "Programming Language :: Python :: 3",
        "Topic :: Scientific/Engineering :: Physics",
    ]:
        assert expected in classifiers
