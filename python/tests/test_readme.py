"""The README's Python example runs as written."""

import re
import shutil


def test_the_readmes_python_example_runs(root, tmp_path, monkeypatch):
    readme = (root / "README.md").read_text()
    section = readme.split("## From Python", 1)[1].split("\n## ", 1)[0]
    [example] = re.findall(r"```python\n(.*?)```", section, flags=re.S)
    shutil.copytree(root / "models", tmp_path / "models")
    monkeypatch.chdir(tmp_path)
    exec(compile(example, "README.md (From Python)", "exec"), {})
    assert (tmp_path / "bicycle_lean.png").stat().st_size > 10_000
    assert (tmp_path / "bicycle_eigenvalues.png").stat().st_size > 5_000


def test_the_readmes_design_map_example_runs(root, tmp_path, monkeypatch):
    """The Dask example of README's "Design maps": the map on every core
    equals the map on a local Dask cluster."""
    readme = (root / "README.md").read_text()
    section = readme.split("### Design maps", 1)[1].split("\n### ", 1)[0]
    [example] = re.findall(r"```python\n(.*?)```", section, flags=re.S)
    monkeypatch.chdir(tmp_path)
    namespace = {"__name__": "__main__"}
    exec(compile(example, "README.md (Design maps)", "exec"), namespace)
    assert namespace["here"].shape == (2, 2)
