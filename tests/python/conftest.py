# Shared fixtures of the Python tests (python/*.cpp, the gpm module): where the
# build and the command line are, a scratch folder removed afterwards, and
# noiseless samples of the paper's Table 5 robot written by `gpm study samples`.
import os
import pathlib
import subprocess
import tempfile

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
BUILD = pathlib.Path(os.environ.get("GPM_BUILD_DIR", ROOT / "build"))
GPM = BUILD / "app" / "gpm"

# Paper Table 5 (actual robot), the truth of `gpm study samples --actual table5`.
TABLE5 = dict(xa1=0, ya1=250, xa2=433, ya2=0.3, xa3=433.5, ya3=499.4, la1=244.1, la2=244.2, la3=243.5,
              lb1=243.8, lb2=244.2, lb3=244.6, dth1=0.01, dth2=-0.01, dth3=0.01)


def run_gpm(*args):
    """Runs the command line; returns (exit code, stdout, stderr)."""
    p = subprocess.run([str(GPM), *map(str, args)], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def cli_error(stderr):
    """The message of the command line's one error line 'gpm: error: MSG'."""
    lines = [l for l in stderr.splitlines() if l.startswith("gpm: error: ")]
    assert len(lines) == 1, stderr
    return lines[0][len("gpm: error: "):]


@pytest.fixture
def scratch():
    """A temporary folder, removed after the test (pytest's tmp_path is kept)."""
    with tempfile.TemporaryDirectory(prefix="gpm-pytest-") as d:
        yield pathlib.Path(d)


@pytest.fixture(scope="module")
def table5_samples():
    """50 noiseless samples of the Table 5 robot in a 120 mm disc (CSV path)."""
    with tempfile.TemporaryDirectory(prefix="gpm-pytest-") as d:
        path = pathlib.Path(d) / "samples.csv"
        code, out, err = run_gpm("study", "samples", "--actual", "table5", "--n", 50, "--radius", 120,
                                 "--seed", 1, "-o", path)
        assert code == 0, err
        yield path
