# Tests python/bind_calibrate.cpp: gpm.calibrate, gpm.CalibrationResult, gpm.load_result.
import json
import pathlib
import tempfile
import warnings

import numpy as np
import pytest

import gpm
from conftest import ROOT, TABLE5, cli_error, run_gpm

FREE = [n for n in gpm.PARAM_NAMES if n not in ("xa1", "ya1", "xa2", "ya2")]


def test_same_geometry_as_the_command_line(table5_samples, scratch):
    out = scratch / "cli.yaml"
    code, _, err = run_gpm("calibrate", "--data", table5_samples, "-o", out)
    assert code == 0, err
    cli = gpm.load_result(out)
    py = gpm.calibrate(gpm.read_samples(table5_samples), gpm.load_robot())
    for name in gpm.PARAM_NAMES:
        assert py.geometry[name] == pytest.approx(cli.geometry[name], abs=1e-12), name
    for name in FREE:
        assert py.std[name] == pytest.approx(cli.std[name], rel=1e-9), name
    assert py.fixed == cli.fixed == ["xa1", "ya1", "xa2", "ya2"]
    assert py.diagnostics["iterations"] == cli.diagnostics["iterations"]
    assert py.diagnostics["converged"] and py.converged


def test_noiseless_samples_give_the_true_robot(table5_samples):
    readings, xy = gpm.read_samples(table5_samples, with_xy=True)
    start = gpm.Robot(geometry=dict(ya2=TABLE5["ya2"]))  # nominal, the fixed frame at its true values
    r = gpm.calibrate(readings, start, true_xy=xy)
    assert r.geometry == pytest.approx(TABLE5, abs=1e-7)
    assert r.diagnostics["kmrmse_mm"] < 1e-6
    assert r.diagnostics["rank"] == 11 and r.diagnostics["cost_function"] == "ml"
    # the calibrated robot closes every loop: fk of the readings is the true point
    np.testing.assert_allclose(r.robot.fk(readings), xy, atol=1e-6)


def test_given_sigma_gives_the_cramer_rao_bound(table5_samples):
    # At noiseless readings the ML solution is the truth and its covariance
    # sigma^2 (J'J)^-1 is the Cramer-Rao bound of calib/crb.hpp there.
    readings = gpm.read_samples(table5_samples)
    r = gpm.calibrate(readings, gpm.Robot(geometry=dict(ya2=TABLE5["ya2"])), sigma=1e-4)
    bound = gpm.crb(gpm.Robot(geometry=TABLE5), readings=readings, sigma=1e-4)
    assert bound["free"] == r.free == FREE
    for name in FREE:
        assert r.std[name] == pytest.approx(bound["std"][name], rel=1e-4), name
    cov = r.covariance
    idx = [gpm.PARAM_NAMES.index(n) for n in FREE]
    np.testing.assert_allclose(cov[np.ix_(idx, idx)], bound["covariance"], rtol=1e-3,
                               atol=1e-6 * np.abs(bound["covariance"]).max())


def test_result_file_round_trip_and_use_as_robot(table5_samples, scratch):
    r = gpm.calibrate(gpm.read_samples(table5_samples), gpm.load_robot(), cost="j3")
    r.save(scratch / "r.yaml")
    back = gpm.load_result(scratch / "r.yaml")
    assert back.geometry == r.geometry
    assert back.std == r.std and back.diagnostics["cost_function"] == "j3"
    assert r.to_yaml() == (scratch / "r.yaml").read_text()
    assert r.robot.geometry == r.geometry


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # the global path reports its rank as a note
def test_global_method_through_the_dispatch(table5_samples):
    r = gpm.calibrate(gpm.read_samples(table5_samples), gpm.load_robot(), cost="j3", method="de", budget=20000)
    assert r.diagnostics["method"] == "de"
    assert r.diagnostics["evaluations"] <= 20000 + 1000


def test_too_few_samples_same_message_as_the_command_line(table5_samples, scratch):
    lines = table5_samples.read_text().splitlines()
    few = scratch / "few.csv"
    few.write_text("\n".join(lines[:6]) + "\n")
    code, _, err = run_gpm("calibrate", "--data", few, "-o", scratch / "r.yaml")
    assert code == 2
    with pytest.raises(gpm.InputError) as e:
        gpm.calibrate(gpm.read_samples(few), gpm.load_robot())
    assert str(e.value) == cli_error(err)
    assert not (scratch / "r.yaml").exists()


def test_rank_deficient_free_set_says_what_the_command_line_says_in_python_words(table5_samples, scratch):
    code, _, err = run_gpm("calibrate", "--data", table5_samples, "--fix", "xa1,ya1", "-o", scratch / "r.yaml")
    assert code == 2
    with pytest.raises(gpm.InputError) as e:
        gpm.calibrate(gpm.read_samples(table5_samples), gpm.load_robot(), fix=["xa1", "ya1"])
    cli = cli_error(err)
    assert "pass --allow-rank-deficient" in cli and cli.startswith("--fix: ")
    # The same sentence with every flag as its keyword (python/errors.cpp).
    expected = (cli.replace("--allow-rank-deficient", "allow_rank_deficient=True")
                .replace("--fix xa1,ya1,xa2,ya2", 'fix=["xa1", "ya1", "xa2", "ya2"]').replace("--fix", "fix"))
    assert str(e.value) == expected
    assert "--" not in str(e.value)


def test_argument_errors_name_the_keyword_where_the_command_line_names_its_flag(table5_samples, scratch):
    readings = gpm.read_samples(table5_samples)
    robot = gpm.load_robot()
    # (arguments, flags, the command line's words -> Python's)
    cases = [(dict(fix=["xa1", "xb1"]), ["--fix", "xa1,xb1"], [("--fix", "fix")]),
             (dict(cost="j4"), ["--cost", "j4"], [("--cost", "cost")]),
             (dict(method="newton"), ["--method", "newton"], [("--method", "method")]),
             (dict(sigma=-1.0), ["--sigma", "-1"], [("--sigma", "sigma")]),
             (dict(cost="ml", method="de"), ["--cost", "ml", "--method", "de"], [("--cost ml", 'cost="ml"')])]
    for kwargs, flags, words in cases:
        code, _, err = run_gpm("calibrate", "--data", table5_samples, "-o", scratch / "r.yaml", *flags)
        assert code == 2, flags
        with pytest.raises(gpm.InputError) as e:
            gpm.calibrate(readings, robot, **kwargs)
        expected = cli_error(err)
        for cli_word, python_word in words:
            assert cli_word in expected, (cli_word, expected)
            expected = expected.replace(cli_word, python_word)
        assert str(e.value) == expected
        assert "--" not in str(e.value)
    with pytest.raises(gpm.InputError, match=r"readings: expected shape \(n, 3\), got \(50, 2\)"):
        gpm.calibrate(readings[:, :2], robot)


def test_no_warnings_on_a_well_posed_problem(table5_samples):
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        gpm.calibrate(gpm.read_samples(table5_samples), gpm.load_robot())


@pytest.fixture(scope="module")
def on_the_fly_run():
    """gpm run of a short on-the-fly scenario (about 20 s): its output folder."""
    with tempfile.TemporaryDirectory(prefix="gpm-pytest-") as d:
        out = pathlib.Path(d) / "run"
        code, _, err = run_gpm("run", ROOT / "tests" / "fixtures" / "on_the_fly_small.yaml", "-o", out)
        assert code == 0, err
        yield out


def samples_columns(path):
    """The samples file's columns by name (float64 arrays)."""
    data = np.genfromtxt(path, delimiter=",", names=True)
    return {name: data[name] for name in data.dtype.names}


def test_on_the_fly_samples_get_the_runs_procedure(on_the_fly_run, scratch):
    # Times and torques given: gpm run's motion model, as gpm calibrate runs it on the file, to the last bit.
    path = on_the_fly_run / "samples.csv"
    code, out, err = run_gpm("calibrate", "--data", path, "--model", ROOT / "models" / "gpm2002.yaml",
                             "-o", scratch / "cli.yaml")
    assert code == 0, err
    cli = gpm.load_result(scratch / "cli.yaml")
    c = samples_columns(path)
    readings, xy = gpm.read_samples(path, with_xy=True)
    three = lambda name: np.stack([c[f"{name}{i}"] for i in (1, 2, 3)], axis=1)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # the procedure's notes
        r = gpm.calibrate(readings, gpm.load_robot(ROOT / "models" / "gpm2002.yaml"), true_xy=xy, t=c["t"],
                          tau_last=three("tau_last"), tau_between=three("tau_between"))
        static = gpm.calibrate(readings, gpm.load_robot(ROOT / "models" / "gpm2002.yaml"))
    assert r.geometry == cli.geometry
    summary = json.loads((on_the_fly_run / "summary.json").read_text())["model_test"]
    test = r.diagnostics["model_test"]
    assert (test["chi2"], test["dof"], test["passed"]) == (summary["chi2"], summary["dof"], summary["passed"])
    assert "model_test_chi2" in r.to_yaml()
    # The positioning 1-sigma it states: what gpm calibrate printed, and
    # within 2 % of gpm run's (taken at the actual robot's sensitivities).
    p = r.diagnostics["positioning_um"]
    line = next(l for l in out.splitlines() if l.startswith("positioning over the 80 mm disc"))
    assert f"stated 1-sigma {p['stated_sigma_rms']:.2f} um per axis" in line, line
    run = json.loads((on_the_fly_run / "summary.json").read_text())["positioning_um"]
    assert abs(p["stated_sigma_rms"] - run["stated_sigma_rms"]) <= 0.02 * run["stated_sigma_rms"]
    assert p["points"] == run["points"]
    # Readings alone: the static fit, whose model test says the readings disagree with it.
    assert static.geometry != r.geometry
    assert not static.diagnostics["model_test"]["passed"]


def test_bad_times_refused(table5_samples):
    readings = gpm.read_samples(table5_samples)
    t = np.arange(len(readings)) * 1e-3
    t[5] = t[4]
    with pytest.raises(gpm.InputError, match=r"t\[5\]: .*the times must increase"):
        gpm.calibrate(readings, gpm.load_robot(), t=t)
    with pytest.raises(gpm.InputError, match="tau_last: 3 rows for 50 rows of readings"):
        gpm.calibrate(readings, gpm.load_robot(), tau_last=np.zeros((3, 3)))
