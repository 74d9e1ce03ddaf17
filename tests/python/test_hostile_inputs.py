# Tests the gpm module's input checks (python/convert.cpp: path_arg, finite
# arrays and geometry; models/kinematics.cpp: non-finite targets): NaN, NUL
# and non-path arguments raise gpm.InputError with one line; nothing is
# written or loaded under a path cut at a NUL.
import math
import os

import numpy as np
import pytest

import gpm


def one_line(err):
    text = str(err.value)
    assert "\n" not in text and text, text
    return text


def test_check_reach_refuses_a_nan_target():
    robot = gpm.load_robot()
    for x, y in [(math.nan, 250.0), (216.5, math.inf), (-math.inf, math.nan)]:
        ok, reason = robot.check_reach(x, y)
        assert ok is False
        assert "finite" in reason


@pytest.mark.parametrize("call", [
    lambda r: r.ik(math.nan, 250.0),
    lambda r: r.ik(216.5, math.inf),
    lambda r: r.ik_angles(math.nan, 250.0),
    lambda r: r.jacobian(math.nan, 250.0),
    lambda r: r.conditioning(216.5, math.nan),
    lambda r: r.ik(np.array([[216.5, 250.0], [math.nan, 250.0]])),
    lambda r: r.fk(np.array([0.0, math.nan, 1.0])),
    lambda r: gpm.crb(r, poses=np.array([[216.5, math.nan]] * 12)),
    lambda r: gpm.crb(r, readings=np.full((12, 3), math.nan)),
    lambda r: gpm.calibrate(np.full((20, 3), math.inf), r),
    lambda r: gpm.Robot(geometry=dict(la1=math.nan)),
    lambda r: gpm.Robot(geometry=dict(lb2=math.inf)),
    lambda r: gpm.Robot(geometry=dict(la1="244")),
    lambda r: gpm.design(count=10**9),
    lambda r: gpm.design(count=2.5),
    lambda r: gpm.design(grid_step=1e-9),
    lambda r: gpm.design(guard=math.nan),
    lambda r: gpm.crb(r, poses=np.array([[216.5, 250.0]] * 12), sigma=1e-300),
])
def test_non_finite_numbers_raise_input_error(call):
    robot = gpm.load_robot()
    with pytest.raises(gpm.InputError) as err:
        call(robot)
    one_line(err)


def test_nan_row_is_named():
    robot = gpm.load_robot()
    with pytest.raises(gpm.InputError) as err:
        robot.fk(np.array([[1.0, 3.0, 4.8], [1.0, math.nan, 4.8]]))
    assert "row 1 column 1" in one_line(err)


def test_paths_with_nul_are_refused_and_nothing_is_written(scratch):
    robot = gpm.load_robot()
    cut = scratch / "b"
    with pytest.raises(gpm.InputError) as err:
        robot.save(str(cut) + "\x00c")
    assert "NUL" in one_line(err)
    assert not cut.exists()
    for call in [lambda: gpm.load_robot("a\x00/etc/passwd"), lambda: gpm.read_samples("s.csv\x00x"),
                 lambda: gpm.load_result("r\x00.yaml"), lambda: gpm.simulate("m\x00.yaml")]:
        with pytest.raises(gpm.InputError) as err:
            call()
        assert "NUL" in one_line(err)


def test_paths_must_be_text_and_not_empty(scratch):
    with pytest.raises(gpm.InputError):
        gpm.load_robot("")
    with pytest.raises(gpm.InputError) as err:
        gpm.load_robot(42)
    assert "os.PathLike" in one_line(err)
    robot = gpm.load_robot()
    robot.save(scratch / "robot.yaml")  # os.PathLike still works
    assert gpm.load_robot(scratch / "robot.yaml") == robot


def test_short_fuzz_of_entry_points_raises_only_python_errors():
    # Random hostile scalars into every numeric entry point: each call either
    # answers with finite numbers or raises a Python exception of the module
    # (gpm.InputError) or a TypeError for a non-number; never a crash.
    rng = np.random.default_rng(20261202)
    hostile = [math.nan, math.inf, -math.inf, 0.0, -0.0, 1e308, -1e308, 5e-324, 216.5, 250.0, 1e6]
    robot = gpm.load_robot()
    for _ in range(int(os.environ.get("GPM_PY_FUZZ_ITERATIONS", "400"))):
        x, y = rng.choice(hostile), rng.choice(hostile)
        for call in (robot.ik, robot.ik_angles, robot.jacobian, robot.conditioning):
            try:
                out = call(x, y)
            except gpm.InputError:
                continue
            values = out if isinstance(out, tuple) else [out]
            for v in values:
                if isinstance(v, dict):
                    v = [np.asarray(a) for a in v.values()]
                for a in (v if isinstance(v, list) else [v]):
                    assert np.all(np.isfinite(a)), (call, x, y, out)
        ok, reason = robot.check_reach(x, y)
        assert ok or reason
        readings = rng.choice(hostile, size=(2, 3))
        try:
            assert np.all(np.isfinite(robot.fk(readings)))
        except gpm.InputError:
            pass
        try:
            gpm.crb(robot, readings=robot.ik(np.array([[216.5, 250.0]] * 12)) + rng.normal(0, 0.1, (12, 3)),
                    sigma=rng.choice(hostile))
        except gpm.InputError:
            pass
