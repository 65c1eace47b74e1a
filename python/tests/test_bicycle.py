"""The benchmark bicycle from Python: its eigenvalues against Meijaard et al.
(2007) and against the command line, its self-stable speed range."""

import re
import warnings

import numpy
import pytest

import chaplygin

UPRIGHT = {"dot(theta_r)": "-v/rR", "dot(phi)": 0, "dot(delta)": 0, "phi": 0, "delta": 0}

# Meijaard, Papadopoulos, Ruina & Schwab (2007), Table 2, v = 5 m/s.
PUBLISHED_AT_5 = [
    -0.77534188219585 + 4.46486771378823j,
    -0.77534188219585 - 4.46486771378823j,
    -0.32286642900409,
    -14.07838969279822,
]


@pytest.fixture(scope="module")
def bicycle():
    return chaplygin.builtin("bicycle")


def test_the_eigenvalues_at_5_m_s_are_the_papers(bicycle):
    linear = bicycle.linearize(at={**UPRIGHT, "dot(theta_r)": "-5/rR"})
    nonzero = [e for e in linear.eigenvalues if abs(e) > 1e-7]
    assert len(nonzero) == 4
    for published in PUBLISHED_AT_5:
        assert min(abs(e - published) for e in nonzero) < 1e-12, (published, nonzero)
    assert linear.stable and linear.conserved == 1


def test_the_eigenvalues_equal_the_command_lines(bicycle, command_line):
    arguments = ["linearize", "bicycle"]
    for name, value in {**UPRIGHT, "dot(theta_r)": "-3/rR"}.items():
        arguments += ["--at", f"{name}={value}"]
    text = command_line(*arguments)
    printed = [
        complex(float(re_), (1 if sign == "+" else -1) * float(im))
        for re_, sign, im in re.findall(r"^\s+(\S+) ([+-]) (\S+) i", text, flags=re.M)
    ]
    linear = bicycle.linearize(at={**UPRIGHT, "dot(theta_r)": "-3/rR"})
    assert len(printed) == len(linear.eigenvalues)
    # printed with 9 decimals in scientific notation
    for ours, theirs in zip(linear.eigenvalues, printed):
        assert abs(ours - theirs) <= 1e-8 * max(1.0, abs(ours)), (ours, theirs)


def test_the_self_stable_range_is_the_papers(bicycle):
    sweep = bicycle.linearize(at=UPRIGHT, sweep=("v", numpy.linspace(0.0, 10.0, 101)))
    assert sweep.eigenvalues.shape == (101, 5)
    assert sweep.values.shape == (101,)
    # Meijaard et al. (2007), section 6: weave speed 4.292382536341, capsize speed 6.024262015388.
    [(weave, capsize)] = sweep.stable
    assert abs(weave - 4.292382536341) < 1e-8
    assert abs(capsize - 6.024262015388) < 1e-8
    # each row by descending real part
    assert numpy.all(numpy.diff(sweep.eigenvalues.real, axis=1) <= 1e-12)


def test_a_fall_at_the_default_step_is_split_where_the_steer_whips_round(bicycle):
    """Released at 3 m/s, below its weave speed, the bicycle falls. At a
    fixed step of the default 10 ms Newton's iteration diverges where the steer whips
    round: those steps are split in halves, the energy is kept, and the lean
    reaches 1 rad within 0.02 s of the 1 ms run (second order: 100 times
    the 1 ms run's own 1.1e-4 s)."""
    initial = {"dot(theta_r)": -10, "dot(phi)": 0.2, "dot(delta)": 0}

    def fall(dt):
        return bicycle.simulate(
            t_end=4.0, dt=dt, initial=initial, stop_when="abs(phi) > 1", fixed_step=True
        )

    coarse, fine = fall(0.01), fall(0.001)
    assert coarse.summary["split_steps"] > 0
    assert fine.summary["split_steps"] == 0
    assert coarse.summary["stopped"] == fine.summary["stopped"] == "abs(phi) > 1"
    assert abs(coarse.t[-1] - fine.t[-1]) < 0.02, (coarse.t[-1], fine.t[-1])
    energy = coarse["energy"]
    assert numpy.max(numpy.abs(energy - energy[0])) < 1e-9 * energy[0]


def test_a_run_beyond_its_tolerance_warns_and_one_within_it_does_not(bicycle):
    """RK4 at a fixed 20 ms step gains 845 % of the falling bicycle's energy,
    nearly all of the kinetic energy the run reaches (a drift of 0.9986 of
    it): the run issues a RuntimeWarning naming the drift. With its step following
    the default tolerance it does not warn, and the lean reaches 1.2 within
    1e-6 s of Dormand-Prince at a tolerance of 1e-11."""
    initial = {"dot(theta_r)": -10, "dot(phi)": 0.2, "dot(delta)": 0}

    def fall(**options):
        return bicycle.simulate(t_end=5.0, initial=initial, stop_when="abs(phi) > 1.2", **options)

    with pytest.warns(RuntimeWarning, match="energy drift"):
        coarse = fall(integrator="rk4", dt=0.02, fixed_step=True)
    assert coarse.summary["energy_drift"] > 0.5
    assert len(coarse.summary["warnings"]) == 1
    reference = fall(integrator="dopri5", rtol=1e-11, atol=1e-11)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        controlled = fall(integrator="rk4")
    assert controlled.summary["warnings"] == []
    assert abs(controlled.t[-1] - reference.t[-1]) < 1e-6, (controlled.t[-1], reference.t[-1])


def test_a_sweep_over_a_list_is_the_sweep_over_its_array(bicycle):
    speeds = [1.0, 4.5, 7]
    over_list = bicycle.linearize(at=UPRIGHT, sweep=("v", speeds))
    over_array = bicycle.linearize(at=UPRIGHT, sweep=("v", numpy.array(speeds)))
    assert numpy.array_equal(over_list.values, over_array.values)
    assert numpy.array_equal(over_list.eigenvalues, over_array.eigenvalues)
