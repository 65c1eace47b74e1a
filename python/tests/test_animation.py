"""``Trajectory.animate`` and ``_repr_html_`` (docs/INTERFACE.md section 10):
a run as one offline HTML page, a mechanism's bodies and a ``drawing:``
section's items drawn at the run's parameters; a model with nothing to draw
refused by name."""

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
    assert [item["name"] for item in data["items"]] == ["wheel", "axle"]
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


def test_a_model_declared_by_its_energy_is_drawn_by_its_drawing_section():
    board = chaplygin.builtin("snakeboard")
    run = board.simulate(t_end=1.0, dt=0.01, params={"r": 0.4})
    data = scene(run.animate(fps=20))
    names = [item["name"] for item in data["items"]]
    wheels = [f"{end}_{side}_wheel" for end in ("front", "back") for side in ("right", "left")]
    assert names == ["board", "front_axle", "back_axle", *wheels, "post", "torso"]
    assert [trace["name"] for trace in data["traces"]] == ["front_wheels", "back_wheels"]
    rows = [list(run.t).index(t) for t in data["times"]]
    assert rows == list(range(0, len(run), 5))
    # the board: 2 r + 0.3 long at the run's r, at (x, y), turned about z by theta
    board = data["items"][0]
    assert board["shape"] == "box" and board["size"][0] == 2 * 0.4 + 0.3
    quaternion = numpy.array(board["quaternion"]).reshape(-1, 4)
    assert numpy.all(quaternion[:, :2] == 0)
    heading = 2 * numpy.arctan2(quaternion[:, 2], quaternion[:, 3])
    turned = numpy.angle(numpy.exp(1j * (heading - run["theta"][rows])))
    assert numpy.abs(turned).max() < 1e-12
    centre = numpy.array(board["position"]).reshape(-1, 3)
    assert numpy.allclose(centre[:, 0], run["x"][rows], atol=1e-12, rtol=0)
    assert numpy.allclose(centre[:, 1], run["y"][rows], atol=1e-12, rtol=0)
    # the front wheels' trace is r ahead of the centre along the heading
    front = numpy.array(data["traces"][0]["points"]).reshape(-1, 3)
    ahead = run["x"][rows] + 0.4 * numpy.cos(run["theta"][rows])
    assert numpy.allclose(front[:, 0], ahead, atol=1e-12, rtol=0)
    assert run._repr_html_().startswith('<iframe srcdoc="&lt;!DOCTYPE html&gt;')


def test_a_model_with_nothing_to_draw_is_refused(root):
    text = (root / "models/sleigh.model").read_text()
    plain = chaplygin.load(text[: text.index("    drawing: [")] + "}\n")
    run = plain.simulate(t_end=0.1, dt=0.01)
    with pytest.raises(ValueError, match="has nothing to draw"):
        run.animate()
    assert run._repr_html_() is None


def test_fps_must_be_positive():
    disk = chaplygin.builtin("rolling-disk-3d")
    run = disk.simulate(t_end=0.1, dt=0.01)
    with pytest.raises(ValueError, match="frames per second"):
        run.animate(fps=0)
