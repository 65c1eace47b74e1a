"""``Trajectory.animate`` and ``_repr_html_`` (docs/INTERFACE.md section 10):
a mechanism's run as one offline HTML page, its bodies drawn at the run's
parameters; a model declared by its energy refused by name."""

import json
import re

import numpy
import pytest

import chaplygin


def scene(page: str) -> dict:
    """The scene embedded in a page."""
    found = re.search(r'<script type="application/json" id="chaplygin-data">(.*?)</script>', page, re.S)
    assert found is not None
    return json.loads(found.group(1))


def test_a_rolling_disk_s_run_is_a_page_of_its_wheel(tmp_path):
    disk = chaplygin.builtin("rolling-disk-3d")
    run = disk.simulate(t_end=1.0, dt=0.01, initial={"phi": 0.2}, params={"r": 0.25})
    path = tmp_path / "animation.html"
    page = run.animate(path, fps=20)
    assert page.startswith("<!DOCTYPE html>")
    assert path.read_text(encoding="utf-8") == page
    data = scene(page)
    assert [item["name"] for item in data["items"]] == ["wheel"]
    wheel = data["items"][0]
    assert wheel["shape"] == "disc"
    assert wheel["radius"] == 0.25
    # every fifth row of 10 ms, and the last
    rows = [list(run.t).index(t) for t in data["times"]]
    assert rows == list(range(0, len(run), 5))
    # the centre is r cos(phi) above the ground, over the contact trace
    heights = numpy.array(wheel["position"][2::3])
    assert numpy.allclose(heights, 0.25 * numpy.cos(run["phi"][rows]), atol=1e-12, rtol=0)
    contact = numpy.array(data["traces"][0]["points"]).reshape(-1, 3)
    assert numpy.allclose(contact[:, 0], run["x"][rows], atol=1e-12, rtol=0)
    assert [label["name"] for label in data["labels"]] == ["x", "y", "psi"]
    shown = run._repr_html_()
    assert shown.startswith('<iframe srcdoc="&lt;!DOCTYPE html&gt;')


def test_a_model_declared_by_its_energy_has_nothing_to_draw():
    board = chaplygin.builtin("snakeboard")
    run = board.simulate(t_end=0.1, dt=0.01)
    with pytest.raises(ValueError, match="declares no bodies"):
        run.animate()
    assert run._repr_html_() is None


def test_fps_must_be_positive():
    disk = chaplygin.builtin("rolling-disk-3d")
    run = disk.simulate(t_end=0.1, dt=0.01)
    with pytest.raises(ValueError, match="frames per second"):
        run.animate(fps=0)
