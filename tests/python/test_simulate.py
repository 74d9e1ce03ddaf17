# Tests python/bind_simulate.cpp: gpm.simulate and gpm.Simulation.
import numpy as np
import pytest

import gpm
from conftest import ROOT, run_gpm

SCENARIO = ROOT / "scenarios" / "procedure_disc_stopgo.yaml"  # 50 poses in a 150 mm disc, perturbed actual robot


@pytest.fixture(scope="module")
def run():
    return gpm.simulate(SCENARIO)


def test_same_samples_as_the_command_line(run, scratch):
    code, _, err = run_gpm("simulate", SCENARIO, "-o", scratch)
    assert code == 0, err
    readings, xy = gpm.read_samples(scratch / "samples.csv", with_xy=True)
    np.testing.assert_allclose(run.readings, readings, rtol=0, atol=1e-12)
    np.testing.assert_allclose(run.xy, xy, rtol=0, atol=1e-12)
    assert run.actual == gpm.load_robot(scratch / "actual.yaml")


def test_samples_are_views_without_copies(run):
    assert run.readings.shape == (50, 3) and run.readings.dtype == np.float64
    assert np.shares_memory(run.readings, run.samples["theta_m"])
    assert not run.readings.flags.writeable
    t = run.trajectory
    m = t["t"].shape[0]
    assert m > 0 and t["readings"].shape == (m, 3) and t["desired"].shape == (m, 2)
    assert np.all(np.diff(t["t"]) > 0)


def test_readings_close_the_loops_of_the_actual_robot(run):
    # fk of the actual robot at the averaged readings is the true end-effector
    # (17-bit encoders: 4.8e-5 rad steps, about 0.01 mm at the elbow)
    np.testing.assert_allclose(run.actual.fk(run.readings), run.xy, atol=0.05)
    assert run.max_violation_m < 1e-5


def test_calibration_from_the_twin_closes_the_loops_better(run):
    # The calibrated robot explains the twin's readings: fk of the readings
    # lands nearer the true end-effector than with the controller's model.
    r = gpm.calibrate(run.readings, run.controller)
    before = np.linalg.norm(run.controller.fk(run.readings) - run.xy, axis=1).max()
    after = np.linalg.norm(r.robot.fk(run.readings) - run.xy, axis=1).max()
    assert after < before / 20


def test_bad_scenario_raises_input_error(scratch):
    bad = scratch / "bad.yaml"
    bad.write_text("sampling:\n  pattern: spiral\n")
    with pytest.raises(gpm.InputError, match="pattern"):
        gpm.simulate(bad)
