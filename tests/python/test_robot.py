# Tests python/bind_robot.cpp: gpm.Robot, gpm.load_robot, gpm.read_samples.
import math

import numpy as np
import pytest

import gpm
from conftest import ROOT

NOMINAL = dict(xa1=0, ya1=250, xa2=433, ya2=0, xa3=433, ya3=500, la1=244, la2=244, la3=244,
               lb1=244, lb2=244, lb3=244, dth1=0, dth2=0, dth3=0)  # paper section 2.5
POINTS = [(216.5, 250.0), (180.0, 220.0), (260.0, 300.0), (216.5, 180.0), (150.0, 260.0)]


def test_nominal_robot_file_has_the_papers_geometry():
    robot = gpm.load_robot()
    assert list(robot.geometry) == list(gpm.PARAM_NAMES)
    assert robot.geometry == pytest.approx(NOMINAL, abs=1e-12)
    assert robot == gpm.load_robot(ROOT / "models" / "gpm2002.yaml")


def test_ik_then_fk_returns_the_point():
    robot = gpm.Robot(geometry=dict(la1=244.1, lb3=244.6, dth2=-0.01, xa3=433.5))
    for x, y in POINTS:
        readings = robot.ik(x, y)
        assert readings.shape == (3,)
        np.testing.assert_allclose(robot.fk(readings), [x, y], atol=1e-9)
    batch = robot.ik(np.array(POINTS))
    assert batch.shape == (len(POINTS), 3)
    np.testing.assert_array_equal(batch[1], robot.ik(*POINTS[1]))
    np.testing.assert_allclose(robot.fk(batch), POINTS, atol=1e-9)


def test_ik_closes_every_loop_by_hand():
    # eq. 29-30, 35: elbow B_i = A_i + la_i (cos, sin)(theta_m + dth) lies lb_i from the point.
    robot = gpm.Robot(geometry=dict(dth1=0.02, dth3=-0.01, lb2=243.0))
    g = robot.geometry
    for x, y in POINTS:
        theta_m = robot.ik(x, y)
        for i in range(3):
            c = i + 1
            ta = theta_m[i] + g[f"dth{c}"]
            bx = g[f"xa{c}"] + g[f"la{c}"] * math.cos(ta)
            by = g[f"ya{c}"] + g[f"la{c}"] * math.sin(ta)
            assert math.hypot(x - bx, y - by) == pytest.approx(g[f"lb{c}"], abs=1e-9)


def test_jacobian_matches_finite_differences_of_ik():
    robot = gpm.load_robot()
    h = 1e-5
    for x, y in POINTS:
        J = robot.jacobian(x, y)
        assert J.shape == (3, 2)
        fd = np.stack([(robot.ik(x + h, y) - robot.ik(x - h, y)) / (2 * h),
                       (robot.ik(x, y + h) - robot.ik(x, y - h)) / (2 * h)], axis=1)
        np.testing.assert_allclose(J, fd, rtol=1e-6, atol=1e-10)


def test_conditioning_is_the_transmission_of_the_joint_angles():
    robot = gpm.load_robot()
    theta_a, theta_b = robot.ik_angles(200.0, 240.0)
    c = robot.conditioning(200.0, 240.0)
    np.testing.assert_allclose(c["transmission"], np.abs(np.sin(theta_a - theta_b)), atol=1e-12)
    assert c["min_transmission"] == pytest.approx(c["transmission"].min())
    assert 0 < c["direct"] <= 1
    s = np.linalg.svd(robot.jacobian(200.0, 240.0), compute_uv=False)
    assert c["jacobian_condition"] == pytest.approx(s[0] / s[-1], rel=1e-9)


def test_out_of_reach_raises_input_error_naming_the_chain():
    robot = gpm.load_robot()
    with pytest.raises(gpm.InputError, match="chain") as e:
        robot.ik(1000.0, 250.0)
    assert isinstance(e.value, ValueError)
    ok, reason = robot.check_reach(1000.0, 250.0)
    assert not ok and reason
    assert robot.check_reach(216.5, 250.0) == (True, "")


def test_unknown_parameter_names_the_nearest():
    with pytest.raises(gpm.InputError, match=r"unknown parameter 'xb1' \(did you mean xa1\?\)"):
        gpm.Robot(geometry=dict(xb1=1.0))
    robot = gpm.load_robot()
    with pytest.raises(gpm.InputError, match="la1"):
        robot.geometry = dict(la1=-5.0)
    assert robot.geometry["la1"] == 244.0  # a refused change leaves the robot as it was


def test_robot_file_round_trip(scratch):
    robot = gpm.Robot(geometry=dict(la2=244.123456789, dth3=1e-3), name="twin")
    robot.save(scratch / "r.yaml")
    assert gpm.load_robot(scratch / "r.yaml") == robot


def test_data_sheet_is_the_robot_files(scratch):
    sheet = gpm.load_robot().data_sheet  # models/gpm2002.yaml: a 400 W servo behind a 10:1 planetary
    assert sheet["gear_ratio"] == 10 and sheet["encoder_bits"] == 17
    assert sheet["cogging_periods"] == 24  # the motor's 12 slots and 8 poles
    assert sheet["coulomb_Nm"] == dict(nominal=0.3, min=0.15, max=0.6)
    assert sheet["rotor_inertia_kg_m2"]["nominal"] == 2.6e-5
    assert math.isclose(sheet["rotor_inertia_kg_m2"]["max"], 2.86e-5)  # +-10 %
    text = (ROOT / "models" / "gpm2002.yaml").read_text().split("data_sheet:")[0]
    (scratch / "r.yaml").write_text(text + "data_sheet: {coulomb_Nm: 0.5}\n")
    robot = gpm.load_robot(scratch / "r.yaml")
    assert robot.data_sheet["coulomb_Nm"] == dict(nominal=0.5, min=0.5, max=0.5)  # a number: exact
    assert robot.data_sheet["viscous_Nm_s"] == sheet["viscous_Nm_s"]  # left out: the GPM2002's
    robot.save(scratch / "s.yaml")
    assert gpm.load_robot(scratch / "s.yaml").data_sheet == robot.data_sheet


def test_read_samples_is_the_csv_without_a_copy(scratch):
    path = scratch / "s.csv"
    path.write_text("sample,x,theta_m1,theta_m2,theta_m3,y\n4,1.5,0.1,0.2,0.3,2.5\n9,3.5,1.1,1.2,1.3,4.5\n")
    a = gpm.read_samples(path)
    assert a.dtype == np.float64 and a.shape == (2, 3)
    np.testing.assert_array_equal(a, [[0.1, 0.2, 0.3], [1.1, 1.2, 1.3]])
    # The array views the parsed C++ vector (owned by a capsule), not a copy.
    assert not a.flags.owndata and type(a.base).__name__ == "PyCapsule"
    readings, xy = gpm.read_samples(path, with_xy=True)
    np.testing.assert_array_equal(xy, [[1.5, 2.5], [3.5, 4.5]])
    assert readings.base is xy.base


def test_read_samples_error_names_file_and_line(scratch):
    path = scratch / "bad.csv"
    path.write_text("sample,theta_m1,theta_m2,theta_m3\n0,0.1,0.2,0.3\n1,0.1,abc,0.3\n")
    with pytest.raises(gpm.InputError) as e:
        gpm.read_samples(path)
    assert str(path) in str(e.value) and ":3" in str(e.value)
