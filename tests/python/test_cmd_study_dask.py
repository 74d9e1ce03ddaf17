# Tests app/cmd_study.cpp's `gpm study population --scheduler ADDRESS` (run
# by python/study.py main): a dask-scheduler and two dask-worker processes on
# 127.0.0.1 (no dashboard), the study of the README's three commands; its
# rows equal gpm.run of each robot's scenario bit for bit. Every process is
# ended and every file removed at the end.
import json
import os
import re
import shutil
import signal
import subprocess
import tempfile
import threading

import pytest

import gpm
import gpm.study
from conftest import ROOT, cli_error, run_gpm

TINY = ROOT / "tests" / "python" / "population_tiny.yaml"

pytest.importorskip("distributed", reason="Dask (python3-distributed) is not installed")


class Server:
    """A dask-scheduler or dask-worker started in its own session; its stderr drained into lines."""

    def __init__(self, args, pattern):
        self.lines, self.found, self.match = [], threading.Event(), None
        self.proc = subprocess.Popen(args, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                                     text=True, start_new_session=True)
        self.reader = threading.Thread(target=self._drain, args=(re.compile(pattern),), daemon=True)
        self.reader.start()

    def _drain(self, pattern):
        for line in self.proc.stderr:
            self.lines.append(line)
            m = pattern.search(line)
            if m and not self.found.is_set():
                self.match = m
                self.found.set()

    def wait(self, seconds=60):
        """The first match of the pattern in its log (bounded wait)."""
        assert self.found.wait(seconds), "".join(self.lines)
        return self.match

    def stop(self):
        """Ends its process group (the worker's nanny and its worker) and waits for it."""
        if self.proc.poll() is None:
            os.killpg(self.proc.pid, signal.SIGTERM)
            try:
                self.proc.wait(20)
            except subprocess.TimeoutExpired:
                os.killpg(self.proc.pid, signal.SIGKILL)
                self.proc.wait(20)
        self.reader.join(20)


@pytest.fixture(scope="module")
def dask_servers():
    """A scheduler and two workers on 127.0.0.1: (address, workers' local folder)."""
    tool = shutil.which("dask-scheduler")
    if tool is None:
        pytest.skip("dask-scheduler is not installed (python3-distributed)")
    with tempfile.TemporaryDirectory(prefix="gpm-pytest-dask-") as d:
        servers = []
        try:
            scheduler = Server([tool, "--host", "127.0.0.1", "--port", "0", "--no-dashboard"],
                               r"Scheduler at:\s+(tcp://127\.0\.0\.1:\d+)")
            servers.append(scheduler)
            address = scheduler.wait().group(1)
            for k in (1, 2):
                worker = Server([shutil.which("dask-worker"), address, "--host", "127.0.0.1", "--nthreads", "1",
                                 "--no-dashboard", "--local-directory", d, "--name", f"w{k}"],
                                r"Registered to:")
                servers.append(worker)
            for w in servers[1:]:
                w.wait()
            yield address
        finally:
            for s in reversed(servers):
                s.stop()


def test_study_on_a_scheduler_and_two_workers(dask_servers, scratch):
    out = scratch / "pop"
    code, stdout, err = run_gpm("study", "population", TINY, "-o", out, "--count", 2, "--scheduler", dask_servers)
    assert code == 0, err
    assert "2 robots (0 failed" in stdout and "robot 301:" in err
    assert sorted(p.name for p in out.iterdir()) == ["population.csv", "population.json", "population.png",
                                                     "robot_300.yaml", "robot_301.yaml"]
    rows = json.loads((out / "population.json").read_text())["robots"]
    assert [r["seed"] for r in rows] == [300, 301]
    assert all(r["worker"].startswith("tcp://127.0.0.1:") for r in rows)
    text = (out / "robot_301.yaml").read_text()
    alone = gpm.study.robot_row(301, gpm.run(text, base_dir=TINY.parent))
    numbers = {k: v for k, v in rows[1].items() if k not in gpm.study.RUN_COLUMNS}
    assert repr(numbers) == repr(alone)


def test_scheduler_option_errors(scratch):
    code, _, err = run_gpm("study", "population", TINY, "-o", scratch / "p", "--scheduler", "tcp://127.0.0.1:1",
                           "--threads", 2)
    assert code == 2 and "--threads" in cli_error(err)
    code, _, err = run_gpm("study", "population", TINY, "-o", scratch / "p", "--scheduler", "tcp://127.0.0.1:1",
                           "--seeds", "4,4")
    assert code == 2 and "--seeds" in cli_error(err)
    assert not (scratch / "p").exists()
