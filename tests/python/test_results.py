# Tests the result types' __repr__ and plot() of the gpm module (python/plots.py,
# python/bind_calibrate.cpp, bind_simulate.cpp, bind_design.cpp, study.py):
# each repr holds the object's figures as its attributes give them, and plot
# writes a PNG of the stated size that is not blank, drawing what it says.
import re
import struct
import warnings

import numpy as np
import pytest

import gpm
import gpm.study
from conftest import ROOT

SCENARIO = ROOT / "scenarios" / "procedure_disc_stopgo.yaml"  # 50 poses, perturbed actual robot


@pytest.fixture(scope="module")
def run():
    return gpm.simulate(SCENARIO)


@pytest.fixture(scope="module")
def result(run):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return gpm.calibrate(run.readings, run.controller)


def png_size(path):
    """(width, height) from the PNG's IHDR chunk, read without matplotlib."""
    data = path.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR"
    return struct.unpack(">II", data[16:24])


def assert_not_blank(path):
    from matplotlib.image import imread
    pixels = imread(str(path))[:, :, :3]
    ink = np.any(pixels < 0.9, axis=2).mean()  # share of pixels that are not (near) white
    colours = len(np.unique((pixels * 255).astype(np.uint8).reshape(-1, 3), axis=0))
    assert 0.03 < ink < 0.6 and colours > 20, (ink, colours)


def test_simulation_repr_holds_its_figures(run):
    text = repr(run)
    assert text.startswith(f"<gpm.Simulation '{run.name}': {len(run.readings)} samples "
                           f"({int(run.samples['settled'].sum())} settled) in {run.sampling_s:.3f} s of robot time")
    for figure in (f"{run.simulated_s:.3f} s simulated", f"{len(run.trajectory['t'])} trajectory rows",
                   f"max torque {run.max_torque:.4g} N m", f"violation {run.max_violation_m:.3g} m",
                   "la=({la1:.4f}, {la2:.4f}, {la3:.4f})".format(**run.actual.geometry),
                   "dth=({dth1:.5f}, {dth2:.5f}, {dth3:.5f})".format(**run.actual.geometry)):
        assert figure in text, (figure, text)
    assert len(text.splitlines()) == 2 and text.endswith(">")


def test_calibration_result_repr_holds_every_estimate_and_its_sigma(result):
    text = repr(result)
    d = result.diagnostics
    test = d["model_test"]
    assert text.startswith(f"<gpm.CalibrationResult {d['method']} ({d['cost_function']}): "
                           f"{d['free_parameters']} free, converged in {d['iterations']} iterations, "
                           f"J = {d['cost']:.4g}, rank {d['rank']}")
    assert (f"model test {'passed' if test['passed'] else 'failed'}: chi2/dof = {test['chi2_per_dof']:.4g} for "
            f"{test['dof']:g} dof, p = {test['p_value']:.3g}") in text
    shown = {m[0]: (float(m[1]), float(m[2])) for m in re.findall(r"(\w+)\s+(-?\d+\.\d{6}) \u00b1 (\S+?)(?=\s|>)", text)}
    assert sorted(shown) == sorted(result.free)
    for name, (value, std) in shown.items():
        assert value == pytest.approx(result.geometry[name], abs=5e-7)
        assert std == pytest.approx(result.std[name], rel=0.05)
    assert len(text.splitlines()) <= 6


def test_loaded_result_repr_has_no_model_test(result, scratch):
    result.save(scratch / "r.yaml")
    loaded = gpm.load_result(scratch / "r.yaml")
    assert "model test" not in repr(loaded) and f"{result.diagnostics['free_parameters']} free" in repr(loaded)
    assert loaded.residuals is None and loaded.convergence["iteration"] == []
    loaded.plot(scratch / "loaded.png")  # the panels without data say so
    assert png_size(scratch / "loaded.png") == (1200, 800)


def test_design_repr_holds_its_bounds():
    d = gpm.design(count=15, grid_step=15.0)
    b = d.bounds
    assert repr(d) == (f"<gpm.Design 15 poses by the worst criterion from {d.candidates} candidates "
                       f"({d.exchanges} exchanges): worst bound {b['worst_mm']:.4g} mm ({b['worst_param']}), "
                       f"mean {b['mean_mm']:.4g} mm; the greedy start's worst {d.start_bounds['worst_mm']:.4g} mm>")


def test_population_repr_holds_its_summary():
    rows = [dict(seed=s, failed=False, positioning_rms_um=pos, robot_time_s=60.0, err_la1=err, std_la1=1.0)
            for s, pos, err in [(1, 9.0, 0.5), (2, 11.0, 2.0), (3, 10.0, -0.2)]]
    rows.append(dict(seed=4, failed=True, failure="InputError: x"))
    pop = gpm.study.Population("main.yaml", rows, 12.5, [], {})
    # median 10 um, worst 11 um, 2 of 3 parameters within 1 sigma
    assert repr(pop) == ("<gpm.study.Population 4 robots (1 failed): positioning median 10 um, worst 11 um; "
                         "within the stated 1-sigma 67% (normal 68%); 12.5 s>")
    # rows without the plan deviation (a real robot's) give none; rows with it, the worst
    assert pop.summary()["plan_deviation_worst_mm"] != pop.summary()["plan_deviation_worst_mm"]
    rows[0]["plan_deviation_mm"], rows[1]["plan_deviation_mm"] = 4.5, 12.0
    assert gpm.study.Population("main.yaml", rows, 12.5, [], {}).summary()["plan_deviation_worst_mm"] == 12.0


def test_calibration_plot_is_a_png_of_1200_by_800_px(result, run, scratch):
    path = scratch / "calibration.png"
    fig = result.plot(path, truth=run.actual)
    assert png_size(path) == (1200, 800)
    assert_not_blank(path)
    # The first panel's bars are (estimate - truth) / 1-sigma, one per estimated parameter.
    from matplotlib.patches import Rectangle
    bars = [p.get_width() for p in fig.axes[0].patches if isinstance(p, Rectangle)]
    expected = [(result.geometry[n] - run.actual.geometry[n]) / result.std[n] for n in result.free]
    np.testing.assert_allclose(bars, expected, rtol=1e-12)
    labels = [t.get_text() for t in fig.axes[0].get_yticklabels()]
    assert labels == result.free
    # The third panel draws each reading's normalised residual.
    drawn = {l.get_label(): l for l in fig.axes[2].get_lines()}
    np.testing.assert_array_equal(drawn["reading"].get_ydata(), result.residuals)


def test_residuals_are_those_of_the_model_test(result, run):
    # Their squares sum to the model test's chi-square (computed apart, in calib/model_test.cpp).
    z = result.residuals
    assert z.shape == (len(run.readings),)
    assert np.sum(z ** 2) == pytest.approx(result.diagnostics["model_test"]["chi2"], rel=1e-12)


def test_calibration_plot_without_path_returns_the_figure_and_writes_nothing(result, scratch):
    import matplotlib.figure
    fig = result.plot()
    assert isinstance(fig, matplotlib.figure.Figure)
    assert tuple(fig.get_size_inches() * fig.dpi) == (1200, 800)
    assert "start" in fig.axes[0].get_xlabel()
    # the convergence panel draws every LM iteration
    lines = fig.axes[3].get_lines()
    assert len(lines[0].get_xdata()) == len(result.convergence["iteration"]) == len(result.convergence["cost"]) > 1
    assert not list(scratch.iterdir())


def test_calibration_plot_refuses_an_unknown_truth_key(result):
    with pytest.raises(gpm.InputError, match="truth: unknown parameter 'la4'"):
        result.plot(truth={"la4": 1.0})


def test_simulation_plot_is_a_png_of_1200_by_500_px_of_the_path(run, scratch):
    path = scratch / "simulation.png"
    fig = run.plot(path)
    assert png_size(path) == (1200, 500)
    assert_not_blank(path)
    drawn = {l.get_label(): l for l in fig.axes[0].get_lines()}
    np.testing.assert_array_equal(drawn["actual"].get_xydata(), run.trajectory["actual"])
    np.testing.assert_array_equal(drawn[f"{len(run.xy)} samples"].get_xydata(), run.xy)
    t, err = fig.axes[1].get_lines()[0].get_xydata().T
    expected = np.hypot(*(run.trajectory["actual"] - run.trajectory["desired"]).T)
    scale = 1.0 if "(mm)" in fig.axes[1].get_ylabel() else 1e3
    np.testing.assert_allclose(err, expected * scale, rtol=1e-12)
