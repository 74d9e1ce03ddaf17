# Tests python/study.py (gpm.study.population on Dask) when a worker process
# is killed (SIGKILL) while it runs a robot: the scheduler runs that robot
# again on a worker, the study completes with every robot, its numbers equal
# the serial run's bit for bit, and the robot is listed as retried.
import os
import signal
import tempfile
import threading

import pytest

import gpm
import gpm.study
from conftest import ROOT

TINY = ROOT / "tests" / "python" / "population_tiny.yaml"

distributed = pytest.importorskip("distributed", reason="Dask (python3-distributed) is not installed")


class FirstProcessing(distributed.diagnostics.plugin.SchedulerPlugin):
    """Notes the worker of the first task that goes to `processing` (the scheduler runs in this process)."""

    def __init__(self, scheduler):
        self.scheduler, self.worker, self.event = scheduler, None, threading.Event()

    def transition(self, key, start, finish, *args, **kwargs):
        if finish == "processing" and not self.event.is_set():
            self.worker = self.scheduler.tasks[key].processing_on.address
            self.event.set()


def test_a_worker_killed_mid_study():
    serial = gpm.study.population(TINY, 2, threads=1, progress=False)
    with tempfile.TemporaryDirectory(prefix="gpm-pytest-dask-") as d:
        with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                                      dashboard_address=None, local_directory=d) as cluster, \
                distributed.Client(cluster) as client:
            client.wait_for_workers(2)
            plugin = FirstProcessing(cluster.scheduler)
            cluster.scheduler.add_plugin(plugin)
            result = {}
            study = threading.Thread(target=lambda: result.update(
                pop=gpm.study.population(TINY, 2, client=client, progress=False)))
            study.start()
            assert plugin.event.wait(120)
            pid = client.run(os.getpid, workers=[plugin.worker])[plugin.worker]
            os.kill(pid, signal.SIGKILL)  # the nanny starts a new worker; the robot runs again
            study.join(300)
            assert not study.is_alive()
    pop = result["pop"]
    assert [r["seed"] for r in pop.rows] == [300, 301] and not pop.failed
    assert repr(pop.numbers()) == repr(serial.numbers())
    assert len(pop.retried) >= 1 and set(pop.retried) <= {300, 301}
    assert "retried: robots" in pop.summary_line()
