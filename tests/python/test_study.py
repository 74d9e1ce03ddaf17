# Tests python/study.py (gpm.study.population): the same seeds give the same
# numbers bit for bit run one after the other, on local threads and on a Dask
# LocalCluster of two worker processes (127.0.0.1, no dashboard); each row is
# gpm.run's summary of that robot's scenario; a robot whose run fails is a row
# with its seed and reason; the table, the progress lines and the figure.
import json
import math
import sys
import tempfile

import pytest

import gpm
import gpm.study
from conftest import ROOT, run_gpm

TINY = ROOT / "tests" / "python" / "population_tiny.yaml"

distributed = pytest.importorskip("distributed", reason="Dask (python3-distributed) is not installed")


def exact(pop):
    """The rows' numbers as text that differs when any bit does (repr of a float is exact)."""
    return repr(pop.numbers())


@pytest.fixture(scope="module")
def cluster():
    """A Dask LocalCluster of two worker processes on 127.0.0.1 and its client; removed afterwards."""
    with tempfile.TemporaryDirectory(prefix="gpm-pytest-dask-") as d:
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                      dashboard_address=None, local_directory=d) as c:
            with distributed.Client(c) as client:
                yield client


@pytest.fixture(scope="module")
def serial():
    return gpm.study.population(TINY, 2, threads=1, progress=False)


def test_rows_are_the_robots_runs(serial):
    assert [r["seed"] for r in serial.rows] == [300, 301]  # the scenario's seed + 0, 1
    assert not serial.failed
    text = gpm.population_robot_scenario(TINY, 301)
    assert text == serial.texts[301]
    alone = gpm.study.robot_row(301, gpm.run(text, base_dir=TINY.parent))
    assert repr(alone) == repr(serial.numbers()[1])
    assert alone["estimated"] == 11 and alone["positioning_rms_um"] > 0


def test_rows_equal_the_command_lines_study(serial, scratch):
    # The C++ study (run/population_study.cpp) of the same robot: the same numbers to the last bit.
    code, _, err = run_gpm("study", "population", TINY, "--seeds", 301, "--threads", 1, "-o", scratch)
    assert code == 0, err
    cpp = json.loads((scratch / "population.json").read_text())["robots"][0]
    row = serial.rows[1]
    assert cpp["seed"] == row["seed"] == 301 and cpp["failure"] is None
    assert cpp["positioning_um"]["rms"] == row["positioning_rms_um"]
    assert cpp["positioning_um"]["stated_sigma_rms"] == row["stated_sigma_rms_um"]
    # Poses stop-and-go: no bound of readings on the fly (null, NaN in the row).
    assert cpp["positioning_um"]["bound_rms"] is None and math.isnan(row["positioning_bound_um"])
    assert cpp["static_rms_um"]["calibrated"] == row["calibrated_static_rms_um"]
    assert cpp["floor_ratio"] == row["floor_ratio"]
    assert cpp["floor_ratio_ci95"] == [row["floor_ratio_ci95_lo"], row["floor_ratio_ci95_hi"]]
    assert cpp["within_3_sigma"] == row["within_3_sigma"] and cpp["estimated"] == row["estimated"]
    for name, p in cpp["parameters"].items():
        assert (p["error"], p["sigma"]) == (row["err_" + name], row["std_" + name]), name


def test_serial_threads_and_cluster_agree_bit_for_bit(serial, cluster):
    threads = gpm.study.population(TINY, 2, threads=2, progress=False)
    dask = gpm.study.population(TINY, 2, client=cluster, progress=False)
    assert exact(threads) == exact(serial)
    assert exact(dask) == exact(serial)
    workers = set(cluster.scheduler_info()["workers"])
    assert {r["worker"] for r in dask.rows} <= workers
    assert dask.retried == []


def failing_scenario(scenario_file, seed, keep_effects=False):
    return f"# robot {seed}\nname: broken\nsampling: {{pattern: disc, radius: 10, count: 0}}\n"


def test_failed_robots_are_reported_with_seed_and_reason(monkeypatch, capsys, cluster):
    monkeypatch.setattr(gpm, "population_robot_scenario", failing_scenario)
    for client in (None, cluster):
        pop = gpm.study.population(TINY, seeds=[7, 3], client=client, threads=2)
        assert [r["seed"] for r in pop.rows] == [7, 3]
        assert all(r["failed"] and "InputError" in r["failure"] and "sampling.count" in r["failure"]
                   for r in pop.rows)
        err = capsys.readouterr().err
        assert "robot 7: failed: InputError" in err and "robot 3: failed" in err
        assert "2 robots (2 failed" in err


def test_bad_input_before_any_run(scratch):
    for kwargs, message in [(dict(count=0), "count"), (dict(seeds=[5, 5]), "seeds"), (dict(seeds=[-1]), "seeds"),
                            (dict(count=10**19), "^count: must be an integer from 1 to 100000, got 1"),
                            (dict(count=2, threads=0), "^threads: must be an integer from 1 to 64, got 0"),
                            (dict(count=2, retries=-1), "^retries: must be an integer from 0 to 100")]:
        with pytest.raises(gpm.InputError, match=message) as e:
            gpm.study.population(TINY, **kwargs)
        assert not isinstance(e.value, TypeError)
    for kwargs, message in [(dict(count="2"), "^count: expected an integer from 1 to 100000, got str"),
                            (dict(seeds=["a"]), "^seeds: expected an integer"), (dict(seeds=5), "^seeds: expected a list"),
                            (dict(count=2, threads=1.5), "^threads: expected an integer from 1 to 64, got float")]:
        with pytest.raises(TypeError, match=message) as e:
            gpm.study.population(TINY, **kwargs)
        assert isinstance(e.value, gpm.InputTypeError)
    with pytest.raises(gpm.InputError, match="missing.yaml"):
        gpm.study.population(scratch / "missing.yaml", 2)


def test_table_and_figure(serial, scratch, monkeypatch):
    pandas = pytest.importorskip("pandas")
    table = serial.table
    assert isinstance(table, pandas.DataFrame) and list(table["seed"]) == [300, 301]
    assert table["positioning_rms_um"].tolist() == [r["positioning_rms_um"] for r in serial.rows]
    s = serial.summary()
    ratios = serial.sigma_ratios()
    assert len(ratios) == 22 and s["coverage_1_sigma"] == sum(x <= 1 for x in ratios) / 22
    fig = serial.plot(scratch / "population.png")
    assert len(fig.axes) == 3
    assert (scratch / "population.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    monkeypatch.setitem(sys.modules, "pandas", None)  # import pandas fails: a list of dicts
    assert serial.table == serial.rows


def test_write(serial, scratch):
    serial.write(scratch / "out")
    names = sorted(p.name for p in (scratch / "out").iterdir())
    assert names == ["population.csv", "population.json", "population.png", "robot_300.yaml", "robot_301.yaml"]
    assert (scratch / "out" / "population.csv").read_text().splitlines()[0].startswith("seed,failed,failure,")
