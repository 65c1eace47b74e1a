"""`Model.steady`: steady motions found from unknowns of their point,
against the rolling disk's steady-turn condition (MATH.md section 6.2), the
sleigh's straight motions (section 6.3) and the command line's row."""

import csv
import math

import pytest

import chaplygin


def disk_spin(phi: float, omega: float) -> float:
    """The disk's spin in a steady turn at lean ``phi`` and turning rate
    ``omega``, from ``A W^2 sin cos - (C + m r^2) w2 W cos - m g r sin = 0``
    with ``w2 = dot(theta) + W sin(phi)`` (m = 1, r = 0.5, g = 9.81)."""
    m, r, g = 1.0, 0.5, 9.81
    a, c = m * r * r / 4, m * r * r / 2
    sin, cos = math.sin(phi), math.cos(phi)
    axial = (a * omega**2 * sin * cos - m * g * r * sin) / ((c + m * r * r) * omega * cos)
    return axial - omega * sin


def test_the_disks_steady_turn_meets_the_newton_euler_condition():
    disk = chaplygin.builtin("rolling-disk-3d")
    found = disk.steady(
        at={"phi": 0.3, "dot(psi)": 1.5, "dot(phi)": 0, "dot(theta)": "s"},
        solve=["s"],
        guess={"s": 3},
    )
    assert found.values["s"] == pytest.approx(disk_spin(0.3, 1.5), rel=1e-9)
    assert found.values["dot(theta)"] == found.values["s"]
    assert found.values["radius"] == pytest.approx(0.5 * abs(found.values["s"]) / 1.5, rel=1e-9)
    assert not found.stable
    assert len(found.eigenvalues) == len(found.state)
    assert len(found.family) == 2


def test_the_sleighs_straight_motion_is_stable_forwards():
    sleigh = chaplygin.builtin("sleigh")
    found = sleigh.steady(at={"dot(x)": 1, "dot(theta)": "w"}, solve=["w"], guess={"w": 0.3})
    assert abs(found.values["w"]) < 1e-12
    assert found.values["radius"] == math.inf
    assert found.stable
    nonzero = [e for e in found.eigenvalues if abs(e) > 1e-9]
    assert nonzero == pytest.approx([-0.5 / 0.35], rel=1e-12)


def test_the_command_lines_row_is_the_same(command_line, tmp_path):
    arguments = ["--at", "phi=0.4", "--at", "dot(theta)=-6", "--at", "dot(phi)=0"]
    command_line(
        "steady", "rolling-disk-3d", *arguments, "--at", "dot(psi)=w",
        "--solve", "w", "--guess", "w=1", "--out", str(tmp_path),
    )
    with open(tmp_path / "steady.csv", newline="") as file:
        row = next(csv.DictReader(file))
    found = chaplygin.builtin("rolling-disk-3d").steady(
        at={"phi": 0.4, "dot(theta)": -6, "dot(phi)": 0, "dot(psi)": "w"},
        solve=["w"],
        guess={"w": 1},
    )
    assert found.values["w"] == float(row["w"])
    assert found.stable == (row["stable"] == "1")


def test_no_steady_motion_near_the_guess_is_a_value_error():
    disk = chaplygin.builtin("rolling-disk-3d")
    with pytest.raises(ValueError, match="no steady motion near the guess"):
        disk.steady(
            at={"phi": 0.3, "dot(psi)": 0, "dot(phi)": 0, "dot(theta)": "s"},
            solve=["s"],
            guess={"s": 2},
        )


def test_a_traced_family_is_the_command_lines(command_line, tmp_path):
    """The sleigh's straight motions over the speed: the rows and the change
    of stability at v = 0 (where ``-m a v / (I + m a^2)`` crosses zero) as
    ``chaplygin steady --trace`` gives them."""
    arguments = ["--at", "dot(x)=v", "--at", "dot(theta)=w", "--solve", "w", "--guess", "w=0.1"]
    printed = command_line(
        "steady", "sleigh", *arguments, "--trace", "v=-1.1:1:0.3", "--out", str(tmp_path)
    )
    with open(tmp_path / "steady.csv", newline="") as file:
        rows = list(csv.DictReader(file))
    family = chaplygin.builtin("sleigh").steady(
        at={"dot(x)": "v", "dot(theta)": "w"},
        solve=["w"],
        guess={"w": 0.1},
        trace=("v", [-1.1 + 0.3 * i for i in range(8)]),
    )
    assert list(family.columns) == list(rows[0].keys())
    assert family["v"] == pytest.approx([float(row["v"]) for row in rows], abs=1e-12)
    assert list(family["stable"]) == [float(row["stable"]) for row in rows]
    assert "stable from v = 0.000000000" in family.report
    assert "stable from v = 0.000000000" in printed
