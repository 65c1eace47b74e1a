"""Models from Python: loading and its errors, simulation against SciPy's
integrators on the package's own right-hand sides, SymPy expressions against
MATH.md's hand-derived snakeboard, runs into a singular configuration."""

import math

import numpy
import pytest
import sympy
from scipy.integrate import solve_ivp

import chaplygin


def test_the_built_ins_are_listed_and_load_with_their_names():
    assert "snakeboard" in chaplygin.builtins() and "bicycle" in chaplygin.builtins()
    board = chaplygin.builtin("snakeboard")
    assert board.name == "snakeboard"
    assert board.coordinates == ["x", "y", "theta", "psi", "phi"]
    assert board.velocities[-1] == "dot(phi)"
    assert board.inputs == ["u_torso", "u_wheels"]
    assert board.constraints == ["front", "back"]
    assert board.parameters == {"m": 1.0, "r": 0.5, "jt": 0.3, "jw": 0.05}
    assert board.engine in ("jit", "interpret")
    with pytest.raises(ValueError, match="unknown built-in model `skateboard`"):
        chaplygin.builtin("skateboard")


def test_a_file_and_its_text_load_the_same_model(root):
    path = root / "models" / "sleigh.model"
    from_file = chaplygin.load(str(path))
    from_text = chaplygin.load(path.read_text())
    assert (from_file.name, from_text.name) == (str(path), "<string>")
    q, qdot = [0.1, 0.2, 0.3], [1.0, 0.3, 0.5]
    assert numpy.array_equal(from_file.acceleration(q, qdot)[0], from_text.acceleration(q, qdot)[0])
    with pytest.raises(FileNotFoundError):
        chaplygin.load(str(root / "models" / "no-such.model"))
    # A path given to the class itself is pointed to `load`, not kept to
    # fail at the first use.
    for given in (str(path), path):
        with pytest.raises(TypeError, match=r"chaplygin\.load\(path_or_text\)"):
            chaplygin.Model(given)


def test_a_bad_model_raises_model_error_at_its_line_and_column():
    text = "pub struct Bad {\n    coordinates: [x],\n    kinetic_energy: dot(x)^2 + m*dot(y)^2,\n}"
    with pytest.raises(chaplygin.ModelError) as raised:
        chaplygin.load(text)
    error = raised.value
    # `m` is the first unknown name: line 3, column 32 (from 1)
    assert (error.line, error.column) == (3, text.splitlines()[2].index("m*") + 1)
    assert error.message.startswith("unknown name `m`")
    assert "<string>:3:32: error: unknown name `m`" in str(error)
    assert "unknown name `y`" in str(error)


def test_the_sleigh_accelerates_as_by_hand():
    # The Chaplygin sleigh (Bloch 2003, section 1.7): at theta = 0 with the
    # blade along x, thetadot = w and xdot = v, the constraint ydot = 0 holds;
    # v' = a w^2 and w' = -m a v w / (j + m a^2).
    sleigh = chaplygin.builtin("sleigh")
    m, j, a = (sleigh.parameters[name] for name in ("m", "inertia", "a"))
    v, w = 0.7, 0.4
    qddot, multipliers = sleigh.acceleration([0.0, 0.0, 0.0], [v, 0.0, w])
    assert abs(qddot[0] - a * w**2) < 1e-12
    assert abs(qddot[2] + m * a * v * w / (j + m * a**2)) < 1e-12
    assert multipliers.shape == (1,)


@pytest.mark.parametrize("formulation", ["reduced", "lagrange"])
def test_solve_ivp_on_rhs_agrees_with_the_packages_integrator(formulation):
    disk = chaplygin.builtin("rolling-disk-3d")
    f = disk.rhs(formulation)
    x0 = f.initial_state()
    assert len(x0) == len(f.state)
    scipy_run = solve_ivp(f, (0.0, 2.0), x0, method="DOP853", rtol=1e-12, atol=1e-12)
    assert scipy_run.success
    own = disk.simulate(t_end=2.0, dt=0.002, formulation=formulation, integrator="rk4")
    ours = numpy.array([own[name][-1] for name in f.state])
    assert numpy.max(numpy.abs(scipy_run.y[:, -1] - ours)) < 1e-8


def test_the_jacobian_is_the_derivative_of_the_rhs():
    board = chaplygin.builtin("snakeboard")
    f = board.rhs("reduced", inputs={"u_torso": "0.3*sin(2*t)", "u_wheels": "-phi"})
    x = f.initial_state({"phi": 0.4, "dot(phi)": 0.2, "dot(psi)": 0.1, "dot(x)": 0.5})
    jacobian = f.jacobian(0.3, x)
    for j in range(len(x)):
        step = 1e-6 * max(1.0, abs(x[j]))
        plus, minus = x.copy(), x.copy()
        plus[j] += step
        minus[j] -= step
        difference = (f(0.3, plus) - f(0.3, minus)) / (2 * step)
        assert numpy.allclose(jacobian[:, j], difference, rtol=1e-6, atol=1e-8), j
    # Inputs given at the call replace the laws: by MATH.md 3.1,
    # alpha1' = -(sin(phi)/r) u1, alpha2' = u1, alpha3' = u2.
    u = numpy.array([0.7, -0.2])
    xdot = f(0.0, x, u)
    r, phi = board.parameters["r"], x[4]
    assert numpy.allclose(xdot[5:], [-math.sin(phi) / r * u[0], u[0], u[1]], atol=1e-14)


def test_sympy_is_the_hand_derived_snakeboard():
    derived = chaplygin.builtin("snakeboard").sympy()
    x, y, theta, psi, phi, m, r, jt, jw = sympy.symbols("x y theta psi phi m r jt jw")
    J = jt + m * r**2
    # MATH.md section 3.1
    g = sympy.Matrix([[m, 0, 0, 0, 0], [0, m, 0, 0, 0], [0, 0, J, jt, 0], [0, 0, jt, jt, 0], [0, 0, 0, 0, jw]])
    a = sympy.Matrix([
        [-sympy.sin(theta + phi), sympy.cos(theta + phi), r * sympy.cos(phi), 0, 0],
        [-sympy.sin(theta - phi), sympy.cos(theta - phi), -r * sympy.cos(phi), 0, 0],
    ])
    assert sympy.simplify(derived["mass_matrix"] - g) == sympy.zeros(5, 5)
    assert sympy.simplify(derived["constraint_matrix"] - a) == sympy.zeros(2, 5)
    assert derived["potential_energy"] == 0
    alpha1, alpha2, alpha3 = sympy.symbols("group torso wheels")
    hamiltonian = alpha1**2 / (2 * m) + alpha2**2 / (2 * jt) + alpha3**2 / (2 * jw)
    assert sympy.simplify(derived["hamiltonian"] - hamiltonian) == 0
    structure = derived["structure_matrix"]
    assert sympy.simplify(structure + structure.T) == sympy.zeros(8, 8)
    qdot = sympy.Matrix(sympy.symbols("dot_x dot_y dot_theta dot_psi dot_phi"))
    assert sympy.simplify(derived["kinetic_energy"] - (qdot.T * g * qdot)[0, 0] / 2) == 0


def test_a_run_into_the_singular_configuration_raises_simulation_error():
    board = chaplygin.builtin("snakeboard")
    # From phi = 1.2 with phidot = alpha3/jw = 0.5 and phi'' = u_wheels/jw = 1,
    # phi = 1.2 + t/2 + t^2/2 reaches pi/2 at t = (-1 + sqrt(1 + 8 (pi/2 - 1.2))) / 2.
    crossing = (-1.0 + math.sqrt(1.0 + 8.0 * (math.pi / 2 - 1.2))) / 2.0
    with pytest.raises(chaplygin.SimulationError) as raised:
        board.simulate(t_end=2.0, dt=0.01, initial={"phi": 1.2}, inputs={"u_wheels": 0.05}, integrator="rk4")
    error = raised.value
    assert abs(error.t - crossing) < 0.011, (error.t, crossing)
    assert abs(error.state[4] - math.pi / 2) < 0.02
    assert "singular configuration" in error.message
    assert error.trajectory.t[-1] < error.t + 1e-12
    assert len(error.trajectory) > 10


def test_a_trajectory_has_named_columns_and_a_summary():
    board = chaplygin.builtin("snakeboard")
    run = board.simulate(t_end=1.0, dt=0.01, stop_when="t > 0.5")
    assert run.summary["stopped"] == "t > 0.5"
    assert abs(run.t[-1] - 0.5) < 1e-9
    assert run.summary["integrator"] == "discrete-gradient"
    assert abs(run.summary["energy_drift"]) < 1e-12
    assert run.summary["max_holonomic_residual"] is None
    assert set(run.summary) >= {
        "t_end", "steps", "integrator", "engine", "energy_drift", "max_constraint_residual",
        "max_holonomic_residual", "chart_switches", "stopped", "energy_scale",
        "accepted_steps", "rejected_steps", "newton_iterations",
    }
    # discrete-gradient steps following the tolerance: three implicit
    # solves per trial, each at least one Newton iteration
    trials = run.summary["accepted_steps"] + run.summary["rejected_steps"]
    assert run.summary["accepted_steps"] >= run.summary["steps"]
    assert run.summary["newton_iterations"] >= 3 * trials
    assert numpy.array_equal(run["x"], run.data[:, run.columns.index("x")])
    frame = run.to_pandas()
    assert list(frame.columns) == run.columns and numpy.array_equal(frame["phi"], run["phi"])
    with pytest.raises(KeyError):
        run["nothing"]
    with pytest.raises(ValueError, match="unknown parameter `mass`"):
        board.simulate(t_end=1.0, params={"mass": 2.0})


def test_a_gait_from_python_equals_the_command_lines(command_line):
    board = chaplygin.builtin("snakeboard")
    period = 2 * math.pi
    gait = board.gait({"psi": "0.8*sin(t)", "phi": "0.5*cos(t)"}, period=period, cycles=2)
    assert gait.displacements.shape == (2, 3)
    text = command_line(
        "gait", "snakeboard", "--shape", "psi,phi", "--cycle", "psi=0.8*sin(t)",
        "--cycle", "phi=0.5*cos(t)", "--period", repr(period), "--out", "target/python-gait",
    )
    line = next(l for l in text.splitlines() if l.startswith("net displacement per cycle: "))
    printed = [float(part.split(" = ")[1]) for part in line.split(": ", 1)[1].split(", ")]
    assert numpy.array_equal(gait.displacements[0], printed)
    assert gait.trajectory.columns == ["t", "x", "y", "theta", "psi", "phi", "p1"]
    assert len(gait.trajectory) == 4001
    with pytest.raises(ValueError, match="no law for phi"):
        board.gait({"psi": "sin(t)"}, period=period)


def test_an_optimal_gait_from_python_equals_the_command_lines(command_line):
    snake = chaplygin.builtin("three-link-snake")
    found = snake.optimal_gait("rotate", starts=2)
    text = command_line(
        "gait", "three-link-snake", "--shape", "a1,a2", "--optimize", "rotate",
        "--starts", "2", "--out", "target/python-optimal-gait",
    )
    line = next(l for l in text.splitlines() if l.startswith("optimal loop: "))
    printed = dict(law.split("=", 1) for law in line.split(": ", 1)[1].split("; "))
    assert found.laws == printed
    efficiency = next(l for l in text.splitlines() if l.startswith("efficiency: "))
    assert float(efficiency.split()[1]) == found.efficiency
    assert found.coefficients.shape == (2, 3)
    # The printed laws run as a prescribed gait turn the snake as the optimum.
    again = snake.gait(found.laws, period=2 * math.pi, steps=400)
    assert numpy.array_equal(again.displacements[0], found.displacement)
    assert found.displacement[2] > 0.5
    with pytest.raises(ValueError, match="the limit must be positive"):
        snake.optimal_gait(limit=0.0)


def test_the_rust_a_model_compiles_to_is_the_command_lines(command_line):
    sleigh = chaplygin.builtin("sleigh")
    code = sleigh.document(format="rust")
    assert code == command_line("derive", "sleigh", "--format", "rust")
    assert "    pub fn reduced_rhs(" in code
    with pytest.raises(ValueError, match="formats: text, latex, json, rust"):
        sleigh.document(format="c")


def test_array_arguments_take_what_numpy_asarray_takes(root):
    board = chaplygin.builtin("snakeboard")
    f = board.rhs("reduced")
    x = f.initial_state({"phi": 0.4, "dot(phi)": 0.2, "dot(psi)": 0.1, "dot(x)": 0.5})
    u = numpy.array([0.7, -0.2])
    xdot, jacobian, energy = f(0.3, x, u), f.jacobian(0.3, x, u), f.energy(x)
    column = numpy.zeros((len(x), 3))
    column[:, 1] = x  # a view with a stride of three entries
    for state in (list(x), tuple(x), column[:, 1]):
        for inputs in (list(u), tuple(u), u[::-1][::-1]):
            assert numpy.array_equal(f(0.3, state, inputs), xdot)
            assert numpy.array_equal(f.jacobian(0.3, state, inputs), jacobian)
        assert f.energy(state) == energy
    # data not aligned for float64 (as a buffer a cluster sent may be)
    unaligned = numpy.frombuffer(bytes(1) + x.tobytes(), dtype=float, offset=1)
    assert not unaligned.flags.aligned
    assert numpy.array_equal(f(0.3, unaligned, u), xdot)
    # another dtype: the same as its float64 copy
    single = x.astype(numpy.float32)
    assert numpy.array_equal(f(0.3, single, [1, 0]), f(0.3, single.astype(float), numpy.array([1.0, 0.0])))
    # a model with one input takes a scalar for it
    racer = chaplygin.load(str(root / "tests" / "models" / "roller_racer.model"))
    g = racer.rhs("reduced")
    y = g.initial_state({"phi": 0.3, "dot(x)": 1.0, "dot(phi)": 0.0})
    assert numpy.array_equal(g(0.0, y, 0.05), g(0.0, y, numpy.array([0.05])))
    assert numpy.array_equal(g(0.0, y, [0.05]), g(0.0, y, numpy.array([0.05])))
    # acceleration, from lists and tuples
    q, qdot = [0.1, -0.2, 0.3, 0.4, 0.5], (0.0, 0.0, 0.0, 0.2, 0.1)
    by_lists = board.acceleration(q, qdot, [0.7, -0.2])
    by_arrays = board.acceleration(numpy.array(q), numpy.array(qdot), numpy.array([0.7, -0.2]))
    assert all(numpy.array_equal(a, b) for a, b in zip(by_lists, by_arrays))


def test_an_array_argument_of_another_shape_is_named_in_the_error():
    board = chaplygin.builtin("snakeboard")
    f = board.rhs("reduced")
    x = f.initial_state()
    d = len(x)
    with pytest.raises(ValueError, match=rf"x must have shape \({d},\), the state's entries; it has shape \({d - 1},\)"):
        f(0.0, x[:-1])
    with pytest.raises(ValueError, match=r"u must have shape \(2,\), one per input; it has shape \(3,\)"):
        f.jacobian(0.0, x, [1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match=rf"x must be one-dimensional; it has shape \(2, {d}\)"):
        f.energy(numpy.stack([x, x]))
    with pytest.raises(ValueError, match=r"u must have shape \(2,\), one per input; it has shape \(\)"):
        f(0.0, x, 0.5)
    with pytest.raises(ValueError, match=r"qdot must have shape \(5,\), one per coordinate; it has shape \(4,\)"):
        board.acceleration([0.0] * 5, [0.0] * 4)
    with pytest.raises(ValueError, match="could not convert"):
        f(0.0, ["a"] * d)


def test_a_frames_angles_and_angular_velocity_go_in_as_lists(root):
    ball = chaplygin.load(str(root / "models" / "chaplygin_ball.model"))
    run = ball.simulate(
        t_end=0.01,
        formulation="lagrange",
        initial={"angles(ball, zxz)": [0.3, 0.5, 0.7], "omega(ball)": [1.0, 1.6, "2.2"]},
    )
    e = numpy.array([run[name][0] for name in ("e0", "e1", "e2", "e3")])
    rates = numpy.array([run[f"dot({name})"][0] for name in ("e0", "e1", "e2", "e3")])
    # e = q_z(0.3) q_x(0.5) q_z(0.7): e0 = cos(theta/2) cos((psi + phi)/2)
    assert abs(e[0] - math.cos(0.25) * math.cos(0.5)) < 1e-12
    e0, e1, e2, e3 = e
    turning = numpy.array([[-e1, e0, e3, -e2], [-e2, -e3, e0, e1], [-e3, e2, -e1, e0]])
    assert numpy.allclose(2.0 * turning @ rates, [1.0, 1.6, 2.2], atol=1e-12)


def test_a_prescribed_steering_angle_is_followed_and_its_force_recorded(root):
    car = chaplygin.load(str(root / "tests" / "models" / "kinematic_car.model"))
    run = car.simulate(
        t_end=2.0, dt=0.01, formulation="lagrange", initial={"dot(x)": 1}, prescribe={"phi": "0.2*sin(t)"}
    )
    t = run.t
    assert numpy.max(numpy.abs(run["phi"] - 0.2 * numpy.sin(t))) < 1e-8
    assert numpy.max(numpy.abs(run["dot(phi)"] - 0.2 * numpy.cos(t))) < 1e-8
    # No constraint row has a dot(phi) term, so the steering row of the
    # equations of motion is js phi'' = force(phi).
    js = car.parameters["js"]
    assert numpy.max(numpy.abs(run["force(phi)"] + js * 0.2 * numpy.sin(t))) < 1e-9
    assert run.summary["power_balance"] < 1e-7
    with pytest.raises(ValueError, match="--prescribe l: `l` is a parameter"):
        car.simulate(t_end=1.0, initial={"dot(x)": 1}, prescribe={"l": 2})
