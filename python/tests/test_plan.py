"""``Model.plan`` (docs/INTERFACE.md section 13): a point mass moved between
rests against its closed-form optimum ``12 m^2 d^2 / T^3``; a plan's
trajectory animated from its nodes; plans pickled; a grid of plans on a
process pool, the same as here; bad requests refused; and a plan on every
built-in model with inputs whose inputs, simulated, reach its goal with the
midpoint rule's error, of order 2."""

import json
import pickle
import re
from concurrent.futures import ProcessPoolExecutor

import numpy
import pytest

import chaplygin

#: ``m xddot = push``.
POINT_MASS = """pub struct PointMass {
    coordinates: [x],
    parameters: [m = 2.0],
    kinetic_energy: m/2*dot(x)^2,
    inputs: [push = x],
}"""


def rest_to_rest(duration: float, distance: float, nodes: int, m: float) -> dict:
    """The point mass moved from rest at 0 to rest at ``distance``."""
    return dict(
        duration=duration,
        nodes=nodes,
        start={"x": 0, "dot(x)": 0},
        goal={"x": distance, "dot(x)": 0},
        params={"m": m},
    )


def closed_form(duration: float, distance: float, m: float) -> float:
    """``min int push^2 dt`` under ``m xddot = push`` between rests: the
    Euler-Lagrange equations give ``push`` linear in t, and the cost
    ``12 m^2 d^2 / T^3``."""
    return 12 * m**2 * distance**2 / duration**3


@pytest.fixture(scope="module")
def point_mass():
    return chaplygin.load(POINT_MASS)


def test_a_free_duration_by_hermite_simpson_meets_its_closed_form(point_mass, tmp_path):
    # min T + int push^2 dt with m = d = 1: over a given T the cost is
    # T + 12/T^3, least where 1 = 36/T^4, T = sqrt 6, where it is
    # 8/sqrt 6; Hermite-Simpson is exact on the cubic optimum
    request = rest_to_rest(2.0, 1.0, 21, 1.0)
    plan = point_mass.plan(**request, scheme="hermite-simpson", final_cost="t", free_duration=True)
    assert plan.duration == pytest.approx(6**0.5, abs=1e-6)
    assert plan.objective == pytest.approx(8 / 6**0.5, abs=1e-8)
    assert plan.t[-1] == pytest.approx(plan.duration, abs=1e-12)
    # the plan's own table is a guess the solver starts from, and ends at
    path = tmp_path / "plan.csv"
    numpy.savetxt(path, numpy.column_stack([plan.t, plan["x"], plan["push"]]), delimiter=",",
                  header="t,x,push", comments="")
    restart = dict(request, duration=plan.duration)
    again = point_mass.plan(**restart, scheme="hermite-simpson", final_cost="t", free_duration=True,
                            guess=path)
    assert again.objective == pytest.approx(plan.objective, abs=1e-8)


def test_the_point_mass_plan_meets_the_closed_form(point_mass):
    duration, distance, m = 1.5, 0.5, 3.0
    coarse, fine = (point_mass.plan(**rest_to_rest(duration, distance, nodes, m)) for nodes in (21, 41))
    exact = closed_form(duration, distance, m)
    assert exact == pytest.approx(8.0)
    # the midpoint rule's error is O(h^2): halving h quarters it, and the
    # Richardson extrapolation of the two grids leaves the O(h^4) term
    # (1.6e-6 relative here, against 6e-4 on 41 nodes alone)
    errors = [plan.objective - exact for plan in (coarse, fine)]
    assert errors[0] / errors[1] == pytest.approx(4.0, rel=0.01)
    assert (4 * fine.objective - coarse.objective) / 3 == pytest.approx(exact, rel=1e-5)
    assert fine.duration == duration
    assert fine.report["nodes"] == 41 and fine.report["scheme"] == "midpoint"
    assert max(fine.report["kkt"].values()) <= 1e-6
    numpy.testing.assert_allclose(fine.t, numpy.linspace(0, duration, 41), rtol=0, atol=1e-15)
    assert (fine["x"][0], fine["x"][-1]) == (0.0, distance)
    assert fine.columns[:4] == ["t", "x", "dot(x)", "push"]
    assert "Plan(objective" in repr(fine)


def scene(page: str) -> dict:
    """The scene embedded in a page."""
    found = re.search(r'<script type="application/json" id="chaplygin-data">(.*?)</script>', page, re.S)
    assert found is not None
    return json.loads(found.group(1))


def parking(nodes: int) -> dict:
    """The differential drive parked 0.3 m ahead and 0.1 m aside, from rest."""
    start = {name: 0 for q in ("x", "y", "theta", "phi_r", "phi_l") for name in (q, f"dot({q})")}
    goal = {"x": 0.3, "y": 0.1, "theta": 0, "dot(phi_r)": 0, "dot(phi_l)": 0}
    return dict(duration=4.0, nodes=nodes, start=start, goal=goal)


@pytest.fixture(scope="module")
def parked():
    return chaplygin.builtin("differential-drive").plan(**parking(21))


def test_a_plan_s_trajectory_animates_from_its_nodes(parked, tmp_path):
    path = tmp_path / "animation.html"
    page = parked.trajectory.animate(path, fps=5)
    assert path.read_text(encoding="utf-8") == page
    data = scene(page)
    # 5 frames a second of nodes 0.2 s apart: every node
    rows = [list(parked.t).index(t) for t in data["times"]]
    assert rows == list(range(len(parked)))
    chassis = next(item for item in data["items"] if item["shape"] == "box")
    centre = numpy.array(chassis["position"]).reshape(-1, 3)
    numpy.testing.assert_allclose(centre[:, 0], parked["x"], rtol=0, atol=1e-12)
    numpy.testing.assert_allclose(centre[:, 1], parked["y"], rtol=0, atol=1e-12)


def test_a_reduced_plan_nears_the_lagrange_plan_as_the_nodes_double(parked):
    # the two forms' discrete problems differ by the scheme's error: their
    # optima approach each other at its order (2.5 % on 11 nodes)
    drive = chaplygin.builtin("differential-drive")
    reduced = drive.plan(**parking(21), formulation="reduced")
    assert reduced.report["formulation"] == "reduced" and reduced.report["chart"] == 0
    assert reduced.columns[1:8] == ["x", "y", "theta", "phi_r", "phi_l", "alpha1", "alpha2"]
    coarse = drive.plan(**parking(11))
    coarse_reduced = drive.plan(**parking(11), formulation="reduced")
    gap = abs(reduced.objective - parked.objective) / parked.objective
    coarse_gap = abs(coarse_reduced.objective - coarse.objective) / coarse.objective
    assert gap < coarse_gap / 3
    numpy.testing.assert_allclose(reduced["x"][-1], 0.3, atol=1e-8)
    with pytest.raises(ValueError, match="unknown formulation `hamilton`"):
        drive.plan(**parking(11), formulation="hamilton")


def test_the_drive_s_momentum_plan_is_its_reduced_plan():
    # its momentum state (q, dot(phi_r), dot(phi_l)) holds no momentum, and
    # chart 0's reduced momenta are the same wheel rates: one plan, reached
    # through two derivations
    drive = chaplygin.builtin("differential-drive")
    momentum = drive.plan(**parking(11), formulation="momentum")
    reduced = drive.plan(**parking(11), formulation="reduced")
    assert momentum.report["formulation"] == "momentum" and momentum.report["chart"] is None
    assert momentum.columns[6:8] == ["dot(phi_r)", "dot(phi_l)"]
    numpy.testing.assert_allclose(momentum["dot(phi_r)"], reduced["alpha1"], rtol=1e-9, atol=1e-12)
    numpy.testing.assert_allclose(momentum.objective, reduced.objective, rtol=1e-9)
    with pytest.raises(ValueError, match="the model declares no symmetry"):
        chaplygin.builtin("caster-robot").plan(**parking(11), formulation="momentum")


def test_plans_pickle(parked):
    copy = pickle.loads(pickle.dumps(parked))
    assert copy.report == parked.report
    assert copy.columns == parked.columns
    numpy.testing.assert_array_equal(copy.trajectory.data, parked.trajectory.data)
    assert copy.trajectory.animate(fps=5) == parked.trajectory.animate(fps=5)


def test_a_grid_of_plans_on_a_process_pool_is_the_same_as_here(point_mass):
    grid = [rest_to_rest(duration, 1.0, 21, m) for duration in (1.0, 2.0) for m in (1.0, 2.0)]
    here = chaplygin.plans(point_mass, grid)
    with ProcessPoolExecutor(max_workers=2) as pool:
        there = chaplygin.plans(point_mass, grid, executor=pool)
    for request, local, remote in zip(grid, here, there):
        assert remote.objective == local.objective
        numpy.testing.assert_array_equal(remote.trajectory.data, local.trajectory.data)
        exact = closed_form(request["duration"], 1.0, request["params"]["m"])
        # the midpoint rule's relative error on 21 nodes is under 1 %
        assert local.objective == pytest.approx(exact, rel=0.01)


def test_bad_plans_are_refused_with_their_reason(point_mass):
    request = rest_to_rest(2.0, 1.0, 11, 2.0)
    with pytest.raises(ValueError, match="unknown scheme `trapezoid`"):
        point_mass.plan(**request, scheme="trapezoid")
    with pytest.raises(ValueError, match=r"bounds\['push'\]: give \(lo, hi\)"):
        point_mass.plan(**request, bounds={"push": 2.5})
    # infeasible (a push of at most 0.1 moves the mass 0.05 in the time):
    # on one interval the solver says so in 40 iterations
    with pytest.raises(ValueError, match="no verified optimum"):
        point_mass.plan(**dict(request, nodes=2), bounds={"push": (-0.1, 0.1)})
    with pytest.raises(ValueError, match="unknown name `y`"):
        point_mass.plan(**dict(request, goal={"y": 1}))


def at_rest(coordinates, **values) -> dict:
    """Every coordinate at 0 but those given, every velocity 0."""
    state = {q: values.get(q, 0.0) for q in coordinates}
    state.update({f"dot({q})": 0.0 for q in coordinates})
    return state


def sideways() -> dict:
    """The snakeboard parked 0.2 aside at rest, its wheels within 1.2 rad
    of straight (where their axles lie along the board the constraints
    lose rank)."""
    coordinates = ["x", "y", "theta", "psi", "phi"]
    goal = at_rest(coordinates, y=0.2, phi=0.3)
    del goal["psi"]
    return dict(duration=6.0, nodes=41, start=at_rest(coordinates, phi=0.3), goal=goal, bounds={"phi": (-1.2, 1.2)})


def lane_change() -> dict:
    """The benchmark bicycle from its straight run at 5 m/s to y_p = 1 in
    3 s, upright, steer straight, by its steer torque alone."""
    coordinates = ["x_p", "y_p", "psi", "phi", "theta_b", "delta", "theta_r", "theta_f"]
    start = at_rest(coordinates)
    start.update({"dot(x_p)": 5.0, "dot(theta_r)": -5.0 / 0.3, "dot(theta_f)": -5.0 / 0.35})
    goal = {"y_p": 1.0, "psi": 0.0, "phi": 0.0, "delta": 0.0, "dot(phi)": 0.0, "dot(delta)": 0.0}
    return dict(duration=3.0, nodes=31, start=start, goal=goal, bounds={"lean_torque": (0, 0)})


#: A midpoint-rule plan per built-in model with inputs, the library's
#: catalog tests' (src/driver/plan/catalog_tests.rs), and the miss of its
#: re-simulated end from the goal that its grid allows: the catalog's,
#: but the upright disk's (2.4e-2 measured with inputs interpolated
#: linearly, where the catalog holds them over each interval).
CATALOG = {
    "caster-robot": (
        dict(duration=4.0, nodes=21, start=at_rest(["x", "y", "theta", "phi_l", "phi_r", "beta", "phi_c"]),
             goal={"x": 0.2, "y": 0.05, "theta": 0.0, "dot(phi_l)": 0.0, "dot(phi_r)": 0.0}),
        1e-2,
    ),
    "differential-drive": (parking(21), 1e-2),
    "rolling-disk": (
        dict(duration=4.0, nodes=21, start=at_rest(["x", "y", "theta", "phi"]),
             goal={"x": 0.3, "y": 0.1, "theta": 0.0, "dot(theta)": 0.0, "dot(phi)": 0.0}),
        1e-2,
    ),
    "rolling-disk-3d": (
        dict(duration=2.0, nodes=41, start=at_rest(["x", "y", "psi", "phi", "theta"]),
             goal={"x": 0.1, "y": 0.02, "psi": 0.0, "phi": 0.0, "dot(phi)": 0.0, "dot(theta)": 0.0}),
        3e-2,
    ),
    "three-link-snake": (
        dict(duration=2.0, nodes=21, start=at_rest(["x", "y", "theta", "a1", "a2"], a1=0.6, a2=-0.6),
             goal={"a1": 0.3, "a2": -0.3, "dot(a1)": 0.0, "dot(a2)": 0.0}),
        1e-2,
    ),
    "snakeboard": (sideways(), 3e-2),
    "snakeboard-bodies": (sideways(), 3e-2),
    "bicycle": (lane_change(), 2e-2),
}


def piecewise_linear(times: numpy.ndarray, values: numpy.ndarray) -> str:
    """The input law through ``(times, values)``, linear between them and
    held beyond their ends, as an expression of ``t``: the first value
    plus a ramp ``(s + abs(s)) / 2``, ``s = t - times[k]``, per change of
    slope."""
    slopes = numpy.concatenate([[0.0], numpy.diff(values) / numpy.diff(times), [0.0]])
    terms = [repr(float(values[0]))]
    for knot, change in zip(times, numpy.diff(slopes)):
        terms.append(f"({float(change)!r})*(t-({float(knot)!r})+abs(t-({float(knot)!r})))/2")
    return "+".join(terms)


def test_every_built_in_model_with_inputs_has_a_case():
    with_inputs = {name for name in chaplygin.builtins() if chaplygin.builtin(name, "interpret").inputs}
    assert with_inputs == set(CATALOG)


#: Plans that take seconds each in a debug build: only their coarse grid.
COARSE_ONLY = {"snakeboard", "snakeboard-bodies", "bicycle"}


def resimulated_miss(model, request: dict) -> float:
    """The largest distance from the goal of the plan's inputs simulated
    from its first row (Lagrange-d'Alembert, Dormand-Prince to 1e-10). The
    midpoint rule applies node i's inputs at the middle of interval i: the
    law is the line through those points."""
    plan = model.plan(**request)
    assert max(plan.report["kkt"].values()) <= 1e-6
    middles = (plan.t[:-1] + plan.t[1:]) / 2
    laws = {u: piecewise_linear(middles, plan[u][:-1]) for u in model.inputs}
    initial = {q: plan[q][0] for q in model.coordinates + model.velocities}
    step = plan.t[1] - plan.t[0]
    run = model.simulate(t_end=plan.duration, dt=step, initial=initial, inputs=laws, formulation="lagrange",
                         integrator="dopri5", rtol=1e-10, atol=1e-10)
    assert run.t[-1] == pytest.approx(plan.duration, abs=1e-9)
    return max(abs(run[goal][-1] - value) for goal, value in request["goal"].items())


@pytest.mark.parametrize("name", sorted(CATALOG))
def test_a_plan_s_inputs_resimulated_reach_its_goal(name):
    # the miss is the scheme's error: within the catalog's bound on the
    # coarse grid, and quartered (order 2) as the step halves
    request, allowed = CATALOG[name]
    model = chaplygin.builtin(name)
    coarse = resimulated_miss(model, request)
    assert coarse < allowed, f"{name}: the re-simulated end misses the goal by {coarse:.3e}"
    if name not in COARSE_ONLY:
        fine = resimulated_miss(model, dict(request, nodes=2 * request["nodes"] - 1))
        assert numpy.log2(coarse / fine) > 1.7, f"{name}: misses {coarse:.3e} and {fine:.3e}"
