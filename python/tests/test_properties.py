"""Properties of the Python API on inputs drawn at random (Hypothesis, with
a fixed seed and a few dozen examples each, as CI runs them): whatever a
caller passes, a call returns, or raises one of the package's errors,
``ValueError`` or ``TypeError``; never a Rust panic (pyo3's
``PanicException``, a ``BaseException``) nor any other exception. What a
call returns for finite input of the right size is finite where the model
is defined there."""

import math

import numpy
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import chaplygin

EXPECTED = (chaplygin.ChaplyginError, ValueError, TypeError)

PROFILE = settings(
    max_examples=40,
    derandomize=True,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow],
)

SLEIGH = chaplygin.builtin("sleigh")

SPECIAL = [0.0, -0.0, -1.0, math.nan, math.inf, -math.inf, 1e-300, 1e300]
numbers = st.one_of(st.sampled_from(SPECIAL), st.floats(-1e3, 1e3))
names = st.sampled_from(
    ["x", "y", "theta", "dot(x)", "dot(y)", "dot(theta)", "m", "a", "inertia", "t", "", "dot(", "1x", "blade"]
)
expressions = st.one_of(
    numbers.map(repr),
    st.text(alphabet="xythetadotsincoqrab()*+-/^.0123456789 ,<>=", max_size=24),
)


def outcome(call):
    """What `call` returns, or the expected error it raises; any other
    exception propagates and fails the property."""
    try:
        return call()
    except EXPECTED as error:
        return error


@PROFILE
@given(
    t_end=st.sampled_from([0.0, -1.0, math.nan, math.inf, 1e300, 0.05, 0.3]),
    dt=st.sampled_from([0.0, -0.1, math.nan, math.inf, 1e-300, 0.01, 0.1, 1.0]),
    tolerance=st.one_of(st.sampled_from(SPECIAL), st.floats(1e-12, 1.0)),
    initial=st.dictionaries(names, st.one_of(numbers, expressions), max_size=3),
    params=st.dictionaries(names, numbers, max_size=2),
    integrator=st.sampled_from([None, "rk4", "dopri5", "midpoint", "discrete-gradient", "euler"]),
    formulation=st.sampled_from(["reduced", "lagrange", "momentum", "hamilton"]),
    stop_when=st.one_of(st.none(), expressions),
    fixed_step=st.booleans(),
)
def test_simulate_returns_or_raises_an_expected_error(
    t_end, dt, tolerance, initial, params, integrator, formulation, stop_when, fixed_step
):
    run = outcome(
        lambda: SLEIGH.simulate(
            t_end=t_end,
            dt=dt,
            initial=initial,
            params=params,
            formulation=formulation,
            integrator=integrator,
            stop_when=stop_when,
            rtol=tolerance,
            atol=tolerance,
            fixed_step=fixed_step,
        )
    )
    if isinstance(run, chaplygin.Trajectory):
        assert run.t[0] == 0.0 and numpy.all(numpy.diff(run.t) > 0)


@PROFILE
@given(
    x=st.lists(numbers, min_size=0, max_size=7),
    u=st.one_of(st.none(), st.lists(numbers, min_size=0, max_size=2)),
    t=numbers,
    formulation=st.sampled_from(["reduced", "lagrange", "momentum"]),
)
def test_rhs_and_jacobian_return_or_raise_an_expected_error(x, u, t, formulation):
    f = SLEIGH.rhs(formulation)
    state = numpy.asarray(x, dtype=float)
    inputs = None if u is None else numpy.asarray(u, dtype=float)
    value = outcome(lambda: f(t, state, inputs))
    jacobian = outcome(lambda: f.jacobian(t, state, inputs))
    finite = numpy.all(numpy.isfinite(state)) and abs(t) < 1e300 and numpy.all(numpy.abs(state) < 1e3)
    if isinstance(value, numpy.ndarray):
        assert value.shape == (len(f.state),)
        assert not finite or numpy.all(numpy.isfinite(value)), (state, value)
    if isinstance(jacobian, numpy.ndarray):
        assert jacobian.shape == (len(f.state), len(f.state))


@PROFILE
@given(
    q=st.lists(numbers, max_size=4),
    qdot=st.lists(numbers, max_size=4),
    u=st.one_of(st.none(), st.lists(numbers, max_size=2)),
)
def test_acceleration_returns_or_raises_an_expected_error(q, qdot, u):
    outcome(lambda: SLEIGH.acceleration(q, qdot, u))


@PROFILE
@given(
    cut=st.tuples(st.integers(0, 900), st.integers(0, 40)),
    inserted=st.text(alphabet="xytheta()[]{},:;=*+-/^.012 dotpubstrucm\n", max_size=12),
)
def test_a_model_text_cut_and_patched_loads_or_raises_model_error(root, cut, inserted):
    text = (root / "models" / "sleigh.model").read_text()
    start, length = cut
    start = min(start, len(text))
    mutated = text[:start] + inserted + text[start + length :]
    model = outcome(lambda: chaplygin.load(mutated))
    assert isinstance(model, (chaplygin.Model, chaplygin.ModelError, ValueError)), model


@PROFILE
@given(
    at=st.dictionaries(names, st.one_of(numbers, expressions), max_size=3),
    params=st.dictionaries(names, numbers, max_size=2),
)
def test_linearize_returns_or_raises_an_expected_error(at, params):
    outcome(lambda: SLEIGH.linearize(at=at, params=params))
