"""``Model.identify`` (docs/INTERFACE.md section 13): the differential
drive's mass, 5 in the run that made ``tests/data/drive_mass_5.csv``,
recovered from that run given as a CSV path, a dict, a DataFrame and a
``Trajectory`` simulated again here (in the Lagrange and the reduced
form), each the same estimate as ``chaplygin identify`` writes; bad data
refused in one line; estimates pickled; a grid of estimates on a process
pool, the same as here; Ctrl-C ending a long solve."""

import json
import os
import pickle
import signal
import threading
from concurrent.futures import ProcessPoolExecutor

import numpy
import pandas
import pytest

import chaplygin

#: The mass of the run that made the data.
TRUE_MASS = 5.0


@pytest.fixture(scope="module")
def drive():
    return chaplygin.builtin("differential-drive")


@pytest.fixture(scope="module")
def data_path(root):
    return root / "tests" / "data" / "drive_mass_5.csv"


@pytest.fixture(scope="module")
def from_csv(drive, data_path):
    return drive.identify(data_path, estimate=["m"])


def test_every_form_of_the_data_gives_the_command_line_s_estimate(drive, data_path, from_csv, command_line, tmp_path):
    frame = pandas.read_csv(data_path)
    # the run of the guide's `chaplygin simulate` that wrote the data
    run = drive.simulate(
        t_end=2.0,
        dt=0.05,
        params={"m": TRUE_MASS},
        inputs={"u_right": "0.2*sin(t)", "u_left": 0.1},
        formulation="lagrange",
    )
    numpy.testing.assert_allclose(run.data, frame.to_numpy(), rtol=0, atol=1e-12)
    given = {
        "dict": {name: frame[name].to_numpy() for name in frame.columns},
        "DataFrame": frame,
        "Trajectory": run,
    }
    command_line("identify", "differential-drive", "--data", str(data_path), "--estimate", "m", "--out", str(tmp_path))
    written = json.loads((tmp_path / "estimate.json").read_text())
    for estimate in [from_csv] + [drive.identify(data, estimate={"m": None}) for data in given.values()]:
        assert estimate.parameters["m"] == pytest.approx(written["parameters"]["m"], rel=1e-9)
        assert estimate.standard_errors["m"] == pytest.approx(written["standard_errors"]["m"], rel=1e-6)
        assert estimate.residual_rms == pytest.approx(written["residual_rms"], rel=1e-6)
    # the same run in the default, reduced form: its momenta read as velocities
    reduced = drive.simulate(t_end=2.0, dt=0.05, params={"m": TRUE_MASS}, inputs={"u_right": "0.2*sin(t)", "u_left": 0.1})
    assert "alpha1" in reduced.columns
    from_reduced = drive.identify(reduced, estimate=["m"])
    assert from_reduced.parameters["m"] == pytest.approx(written["parameters"]["m"], rel=1e-6)
    # the truth, to the midpoint rule's error on 41 rows 0.05 s apart
    assert from_csv.parameters["m"] == pytest.approx(TRUE_MASS, abs=5e-4)
    assert max(from_csv.report["kkt"].values()) <= 1e-6


def test_the_fit_holds_the_data_beside_the_fitted_states(from_csv, data_path):
    frame = pandas.read_csv(data_path)
    fit = from_csv.fit
    numpy.testing.assert_array_equal(fit.t, frame["t"].to_numpy())
    numpy.testing.assert_array_equal(fit["data(x)"], frame["x"].to_numpy())
    assert numpy.max(numpy.abs(fit["x"] - fit["data(x)"])) < 10 * from_csv.residual_rms + 1e-12
    assert from_csv.iterations == from_csv.report["iterations"]
    assert "Estimate(m = " in repr(from_csv)


def test_bad_data_are_refused_in_one_line(drive, data_path):
    frame = pandas.read_csv(data_path)
    bad = {"t": frame["t"].to_numpy(), "x": frame["x"].to_numpy(), "bogus": frame["x"].to_numpy()}
    with pytest.raises(ValueError, match=r"^--data <dict>: unknown columns bogus \(t, x, y, ") as raised:
        drive.identify(bad, estimate=["m"])
    assert "\n" not in str(raised.value)
    with pytest.raises(ValueError, match=r"^--estimate mass: unknown parameter"):
        drive.identify(frame, estimate=["mass"])
    with pytest.raises(ValueError, match="differ in length"):
        drive.identify({"t": [0.0, 1.0], "x": [0.0]}, estimate=["m"])
    with pytest.raises(ValueError, match="no column `t`"):
        drive.identify(frame.drop(columns="t"), estimate=["m"])


def test_estimates_pickle(from_csv):
    copy = pickle.loads(pickle.dumps(from_csv))
    assert copy.report == from_csv.report
    assert copy.parameters == from_csv.parameters
    assert copy.fit.columns == from_csv.fit.columns
    numpy.testing.assert_array_equal(copy.fit.data, from_csv.fit.data)


def test_a_grid_of_estimates_on_a_process_pool_is_the_same_as_here(drive, data_path, from_csv):
    grid = [dict(data=data_path, estimate={"m": guess}) for guess in (4.0, 6.0)]
    here = chaplygin.estimates(drive, grid)
    with ProcessPoolExecutor(max_workers=2) as pool:
        there = chaplygin.estimates(drive, grid, executor=pool)
    for local, remote in zip(here, there):
        assert remote.report == local.report
        numpy.testing.assert_array_equal(remote.fit.data, local.fit.data)
        # from either side the solve ends at the one optimum
        assert local.parameters["m"] == pytest.approx(from_csv.parameters["m"], rel=1e-6)


def test_ctrl_c_stops_the_solve(drive, data_path):
    # on 2001 nodes the call takes seconds, most of them its setup and the
    # verification of the answer: Ctrl-C a second in stops the solve at its
    # next iteration, or, coming after the last, raises as the call returns.
    # The test runs under Python's own handler of Ctrl-C, whatever this
    # process had.
    handler = signal.signal(signal.SIGINT, signal.default_int_handler)
    timer = threading.Timer(1.0, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            drive.identify(data_path, estimate={"m": 4.0}, nodes=2001)
    finally:
        timer.cancel()
        timer.join()
        signal.signal(signal.SIGINT, handler)
