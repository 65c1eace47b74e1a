"""chaplygin.design_map: the self-stable speeds over a grid of parameters,
against the closed form of the Chaplygin sleigh, against the command line,
the same bit for bit on an executor (a process pool here; the guide's
example, run by test_readme.py, on a local Dask cluster); models pickle;
long native calls release the GIL."""

import csv
import math
import pickle
import threading
import time
from concurrent.futures import ProcessPoolExecutor

import numpy
import pytest

import chaplygin

#: The sleigh moving straight along its blade at speed v.
STRAIGHT = {"dot(x)": "v", "dot(y)": 0, "dot(theta)": 0, "theta": 0}

#: The benchmark bicycle running upright at speed v.
UPRIGHT = {"dot(theta_r)": "-v/rR", "dot(phi)": 0, "dot(delta)": 0}


def test_the_sleigh_is_stable_where_its_centre_of_mass_leads():
    """The turning rate's eigenvalue is -m a v / (inertia + m a^2): stable
    exactly where a v > 0, one mode changing at v = 0, whatever the mass
    (held at 2) and the inertia (varied)."""
    sleigh = chaplygin.builtin("sleigh")
    speeds = numpy.linspace(-1.0, 1.0, 9)
    found = chaplygin.design_map(
        sleigh, speed=("v", speeds), params={"a": [-0.5, 0.5], "inertia": (0.1, 0.2), "m": 2}, at=STRAIGHT
    )
    assert found.shape == (2, 2)
    assert list(found.params) == ["a", "inertia"]
    numpy.testing.assert_array_equal(found.params["inertia"], [0.1, 0.2])
    for j in range(2):
        assert found.stable_from[0, j] == -1.0 and abs(found.stable_to[0, j]) < 1e-10
        assert abs(found.stable_from[1, j]) < 1e-10 and found.stable_to[1, j] == 1.0
        (change,) = found.changes[0][j]
        assert abs(change[0]) < 1e-10 and change[1:] == (0, 1)
        (change,) = found.changes[1][j]
        assert abs(change[0]) < 1e-10 and change[1:] == (1, 0)
        assert found.failures[0][j] is None
    only_forward = chaplygin.design_map(sleigh, speed=("v", [0.5, 1.0]), params={"a": [-0.5]}, at=STRAIGHT)
    assert math.isnan(only_forward.stable_from[0]) and only_forward.intervals == [[]]


def test_the_map_is_the_command_lines(command_line, tmp_path):
    """The bicycle over its trail: the stable intervals and changes equal,
    to the last bit, what `chaplygin map` writes to map.csv."""
    bicycle = chaplygin.builtin("bicycle")
    found = chaplygin.design_map(
        bicycle, speed=("v", numpy.arange(0, 21) * 0.5), params={"c": [0.04, 0.08]}, at=UPRIGHT
    )
    arguments = ["map", "bicycle", "--speed", "v=0:10:0.5", "--param", "c=0.04:0.08:0.04"]
    for name, value in UPRIGHT.items():
        arguments += ["--at", f"{name}={value}"]
    command_line(*arguments, "--out", str(tmp_path))
    with open(tmp_path / "map.csv", newline="") as file:
        rows = list(csv.DictReader(file))
    assert [float(row["c"]) for row in rows] == [0.04, 0.08]
    for i, row in enumerate(rows):
        intervals = [tuple(map(float, pair.split(":"))) for pair in row["intervals"].split(";")]
        assert found.intervals[i] == intervals
        assert found.stable_from[i] == float(row["stable_from"])
        changes = []
        for change in row["changes"].split(";"):
            speed, counts = change.split(":")
            before, after = counts.split(">")
            changes.append((float(speed), int(before), int(after)))
        assert found.changes[i] == changes


def assert_same_map(found, expected):
    """Two maps equal bit for bit (NaN where the other has NaN)."""
    assert found.shape == expected.shape
    numpy.testing.assert_array_equal(found.stable_from, expected.stable_from)
    numpy.testing.assert_array_equal(found.stable_to, expected.stable_to)
    assert found.intervals == expected.intervals
    assert found.changes == expected.changes
    assert found.failures == expected.failures


#: A map of the sleigh with stable, unstable and failing points (m = 0
#: makes the mass matrix singular).
SLEIGH_MAP = dict(speed=("v", numpy.linspace(-1, 1, 5)), params={"a": [-0.5, 0.25, 0.5], "m": [0.0, 1.0, 2.0]}, at=STRAIGHT)


def test_a_process_pool_gives_the_same_map_bit_for_bit():
    sleigh = chaplygin.builtin("sleigh")
    here = chaplygin.design_map(sleigh, **SLEIGH_MAP)
    assert sum(f is not None for row in here.failures for f in row) == 3
    with ProcessPoolExecutor(max_workers=2) as pool:
        there = chaplygin.design_map(sleigh, executor=pool, chunks=4, **SLEIGH_MAP)
    assert_same_map(there, here)


def test_models_pickle_as_their_text(root):
    for model in (chaplygin.builtin("sleigh"), chaplygin.load((root / "models/sleigh.model").read_text())):
        copy = pickle.loads(pickle.dumps(model))
        assert copy.parameters == model.parameters and copy.engine == model.engine
        assert copy.coordinates == model.coordinates
        at = dict(STRAIGHT, **{"dot(x)": 0.5})
        numpy.testing.assert_array_equal(copy.linearize(at=at).eigenvalues, model.linearize(at=at).eigenvalues)


#: Long native calls, each of which releases the GIL, and the built-in
#: model each runs on, chosen so that the call lasts several times the
#: 0.05 s the test requires (the caster robot's document takes about 0.4 s;
#: the snakeboard's, 0.02-0.04 s, was too short on a fast machine).
LONG_CALLS = {
    "design_map": ("bicycle", lambda m: m._native.design_points(
        UPRIGHT, None, ("v", numpy.arange(0, 11.0)), ["c"], numpy.array([[0.04], [0.06], [0.08]]), 1
    )),
    "simulate": ("bicycle", lambda m: m.simulate(t_end=1.0, dt=0.01, initial={"dot(theta_r)": "-5/rR", "dot(phi)": 0.5, "dot(delta)": 0.0})),
    "linearize": ("bicycle", lambda m: m.linearize(at=UPRIGHT, sweep=("v", numpy.linspace(0, 10, 4001)))),
    "document": ("caster-robot", lambda m: m.document("json")),
}


@pytest.fixture(scope="module")
def built_ins():
    """The built-in models the long calls run on, each loaded once."""
    return {name: chaplygin.builtin(name) for name in {model for model, _ in LONG_CALLS.values()}}


@pytest.mark.parametrize("call", sorted(LONG_CALLS))
def test_long_calls_release_the_gil(call, built_ins):
    """While a long native call runs in one thread, Python code runs in
    another: its loop turns inside the call's own time window."""
    model_name, run = LONG_CALLS[call]
    model = built_ins[model_name]
    window = {}

    def native_call():
        window["start"] = time.perf_counter()
        run(model)
        window["end"] = time.perf_counter()

    worker = threading.Thread(target=native_call)
    turns = []
    worker.start()
    while worker.is_alive():
        turns.append(time.perf_counter())
    worker.join()
    inside = [t for t in turns if window["start"] < t < window["end"]]
    assert window["end"] - window["start"] > 0.05
    assert len(inside) > 1000, f"{len(inside)} turns in {window['end'] - window['start']:.3f} s"


def test_bad_maps_are_refused_with_their_reason():
    sleigh = chaplygin.builtin("sleigh")
    with pytest.raises(ValueError, match="unknown parameter `length`"):
        chaplygin.design_map(sleigh, speed=("v", [1.0]), params={"length": [1.0]}, at=STRAIGHT)
    with pytest.raises(ValueError, match="vary at least one parameter"):
        chaplygin.design_map(sleigh, speed=("v", [1.0]), params={"a": 1.0}, at=STRAIGHT)
    with pytest.raises(ValueError, match="`a` is a parameter"):
        chaplygin.design_map(sleigh, speed=("a", [1.0]), params={"m": [1.0]}, at=STRAIGHT)
    with pytest.raises(ValueError, match=r"points must have shape \(n, 1\).*\(2, 2\)"):
        sleigh._native.design_points(STRAIGHT, None, ("v", [1.0]), ["a"], [[1.0, 2.0], [3.0, 4.0]], None)
