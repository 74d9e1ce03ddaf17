# Tests python/bind_run.cpp (gpm.run): its summary is the summary.json that
# `gpm run` writes, out_dir gets the run's outputs, the overrides equal the same
# edit of the scenario file, bad input raises gpm.InputError before any run,
# and the GIL is released while it runs.
import json
import pathlib
import re
import tempfile
import threading

import pytest

import gpm
from conftest import ROOT, run_gpm

TINY = ROOT / "tests" / "python" / "population_tiny.yaml"
PARAMS = {"xa3", "ya3", "la1", "la2", "la3", "lb1", "lb2", "lb3", "dth1", "dth2", "dth3"}


@pytest.fixture(scope="module")
def tiny_run():
    """gpm.run of the tiny scenario with out_dir: (summary, out_dir, stages seen)."""
    with tempfile.TemporaryDirectory(prefix="gpm-pytest-") as d:
        stages = []
        yield gpm.run(TINY, d, progress=stages.append), pathlib.Path(d), stages


def test_summary_is_the_summary_json_written(tiny_run):
    summary, out, stages = tiny_run
    assert summary == json.loads((out / "summary.json").read_text())
    for name in ("samples.csv", "calibration.yaml", "report.html", "actual.yaml"):
        assert (out / name).is_file(), name
    assert summary["verdict"] == "passed"
    assert set(summary["parameters"]) == PARAMS
    assert summary["robot_time_s"] > 0
    assert 0 < summary["plan_deviation_mm"] < 20  # the twin's farthest from its sampling plan (mm)
    assert stages[0] == "sampling on the twin through the hardware interface" and "calibrating" in stages


def test_summary_equals_the_command_line(tiny_run, scratch):
    code, _, err = run_gpm("run", TINY, "-o", scratch, "-q")
    assert code == 0, err
    assert json.loads((scratch / "summary.json").read_text()) == tiny_run[0]


def test_overrides_equal_the_edited_scenario_and_the_gil_is_released(tiny_run):
    text = TINY.read_text()
    text = re.sub(r"(?m)^seed: 300$", "seed: 301", text)
    text = re.sub(r"count: 24,", "count: 20,", text)
    text = re.sub(r"(?m)^robot: .*$", f"robot: {ROOT / 'models' / 'gpm2002.yaml'}\neffects: ideal", text)
    assert "seed: 301" in text and "count: 20," in text
    edited = gpm.run(text, base_dir=TINY.parent)
    result, spins = {}, 0
    t = threading.Thread(target=lambda: result.update(
        s=gpm.run(str(TINY), seed=301, count=20, effects="ideal", robot=ROOT / "models" / "gpm2002.yaml")))
    t.start()
    while t.is_alive():  # runs only while gpm.run has let go of the GIL
        spins += 1
    t.join()
    assert result["s"] == edited
    assert edited["parameters"] != tiny_run[0]["parameters"]  # another robot
    assert spins > 10000


@pytest.mark.parametrize("kwargs, message", [
    (dict(seed=-1), "seed"),
    (dict(seed="7"), "seed: expected an integer"),
    (dict(seed=True), "seed: expected an integer"),
    (dict(count=0), "count"),
    (dict(count=2.5), "count: expected an integer"),
    (dict(effects="nonsense"), "effects"),
    (dict(effects=3), "effects: expected a preset name"),
    (dict(robot="/nonexistent/robot.yaml"), "/nonexistent/robot.yaml"),
    (dict(base_dir="."), "base_dir: only for scenario text"),
    (dict(progress=5), "progress: expected a callable"),
])
def test_bad_arguments_raise_input_error(kwargs, message):
    with pytest.raises(gpm.InputError, match=re.escape(message)):
        gpm.run(TINY, **kwargs)


def test_bad_scenarios_raise_input_error(scratch):
    with pytest.raises(gpm.InputError, match="missing.yaml"):
        gpm.run(scratch / "missing.yaml")
    with pytest.raises(gpm.InputError, match="scenario text"):
        gpm.run("name: x\nseed: [\n")
    with pytest.raises(gpm.InputError, match="hardware"):
        gpm.run(TINY.read_text() + "hardware: twin.yaml\n", base_dir=TINY.parent)
    with pytest.raises(gpm.InputError, match="sampling section"):
        gpm.run("name: x\npath: {shape: circle, radius: 10, period_s: 1}\n", count=3)
    (scratch / "file").write_text("")
    with pytest.raises(gpm.InputError, match="file"):
        gpm.run(TINY, scratch / "file")
    assert issubclass(gpm.InputError, ValueError)


def test_an_exception_of_progress_stops_the_run():
    class Stop(Exception):
        pass

    def stop(stage):
        raise Stop(stage)

    with pytest.raises(Stop, match="sampling on the twin"):
        gpm.run(TINY, progress=stop)
    with pytest.raises(gpm.InputError, match="NUL"):
        gpm.run("m\x00.yaml")
