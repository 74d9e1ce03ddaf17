# Tests python/bind_design.cpp: gpm.design, gpm.pose_bounds, gpm.crb.
import re

import numpy as np
import pytest

import gpm
from conftest import cli_error, run_gpm


@pytest.fixture(scope="module")
def design():
    return gpm.design(count=15, grid_step=15.0)


def test_design_poses_are_reachable_and_bounded_as_reported(design):
    robot = gpm.load_robot()
    assert design.poses.shape == (15, 2) and design.candidates >= 15
    assert all(robot.check_reach(x, y)[0] for x, y in design.poses)
    again = gpm.pose_bounds(robot, design.poses, sigma=1e-4)
    assert again["free"] == design.bounds["free"]
    np.testing.assert_allclose(again["scaled"], design.bounds["scaled"], rtol=1e-9)
    assert design.bounds["worst_mm"] == pytest.approx(design.bounds["scaled"].max())
    # the exchange never ends worse than its greedy start (worst criterion)
    assert design.bounds["worst_mm"] <= design.start_bounds["worst_mm"] * (1 + 1e-12)


def test_design_poses_are_a_view_without_copy(design):
    a, b = design.poses, design.poses
    assert np.shares_memory(a, b) and not a.flags.writeable


def test_crb_from_poses_and_from_their_readings_agree_with_pose_bounds(design):
    robot = gpm.load_robot()
    readings = robot.ik(design.poses)
    a = gpm.crb(robot, poses=design.poses, sigma=2e-4)
    b = gpm.crb(robot, readings=readings, sigma=2e-4)
    assert a["std"] == pytest.approx(b["std"], rel=1e-12)
    bounds = gpm.pose_bounds(robot, design.poses, sigma=2e-4)
    np.testing.assert_allclose([a["std"][n] for n in a["free"]], bounds["sigma"], rtol=1e-6)
    # covariance is the inverse of the Fisher information
    np.testing.assert_allclose(a["covariance"] @ a["fisher"], np.eye(11), atol=1e-6)


def test_sigma_only_scales_the_bounds(design):
    robot = gpm.load_robot()
    a = gpm.crb(robot, poses=design.poses, sigma=1e-4)
    b = gpm.crb(robot, poses=design.poses, sigma=3e-4)
    for n in a["free"]:
        assert b["std"][n] == pytest.approx(3 * a["std"][n], rel=1e-9)


def test_same_poses_as_the_command_line(design, scratch):
    code, _, err = run_gpm("design", "--count", 15, "--grid-step", 15, "-o", scratch / "p.yaml")
    assert code == 0, err
    text = (scratch / "p.yaml").read_text()
    poses = [[float(x), float(y)] for x, y in re.findall(r"^    - \[(\S+), (\S+)\]$", text, re.M)]
    np.testing.assert_array_equal(design.poses, poses)
    assert design.to_yaml().split("sampling:")[1] == text.split("sampling:")[1]


def test_design_errors_match_the_command_line(scratch):
    code, _, err = run_gpm("design", "--count", 5, "-o", scratch / "p.yaml")
    assert code == 2
    with pytest.raises(gpm.InputError) as e:
        gpm.design(count=5)
    assert str(e.value) == cli_error(err)
    with pytest.raises(gpm.InputError, match="criterion: 'e' is not d, worst or positioning"):
        gpm.design(criterion="e")


def test_positioning_design_matches_the_command_line_and_states_its_bound(design, scratch):
    assert design.positioning_bound_um is None  # not the positioning criterion
    d = gpm.design(count=15, grid_step=15.0, sigma=1e-5, criterion="positioning")
    code, out, err = run_gpm("design", "--count", 15, "--grid-step", 15, "--sigma", 1e-5, "--criterion",
                             "positioning", "-o", scratch / "p.yaml", "--json")
    assert code == 0, err
    import json
    info = json.loads(out)["design"]
    assert info["criterion"] == "positioning"
    assert info["positioning_bound_um"] == pytest.approx(d.positioning_bound_um, rel=1e-12)
    assert 0 < d.positioning_bound_um < 1e3
