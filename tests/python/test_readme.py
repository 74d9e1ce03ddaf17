# Tests python/README.md and README.md: their Python examples run as written:
# the calibration example, and the population study block (the same in both),
# here with 2 robots of a short scenario and, with GPM_PY_README_LONG=1 (CTest
# python.readme_study_long, label long), as written: 100 robots of main.yaml.
import contextlib
import io
import os
import re

import pytest

from conftest import ROOT

TINY = ROOT / "tests" / "python" / "population_tiny.yaml"


def python_blocks(readme):
    return re.findall(r"```python\n(.*?)```", (ROOT / readme).read_text(), re.S)


def run_block(block, name):
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(block, name, "exec"), {})
    return out.getvalue()


def study_block(readme):
    blocks = [b for b in python_blocks(readme) if "gpm.study" in b]
    assert len(blocks) == 1
    assert len(blocks[0].strip().splitlines()) <= 10
    return blocks[0]


def test_calibration_example_runs_as_written(scratch, monkeypatch):
    blocks = [b for b in python_blocks("python/README.md") if "gpm.study" not in b]
    assert len(blocks) == 1
    assert len(blocks[0].strip().splitlines()) <= 10
    monkeypatch.chdir(scratch)  # the block writes calibration.png
    out = run_block(blocks[0], "python/README.md")
    assert "converged: True" in out
    assert (scratch / "calibration.png").read_bytes()[:4] == b"\x89PNG"
    # The repr the README shows is the block's output, line for line (up to its "...").
    shown = re.search(r"`print\(result\)` shows\n\n```text\n(.*?)```", (ROOT / "python/README.md").read_text(), re.S)
    lines = [l for l in shown.group(1).splitlines() if l.strip() != "..."]
    assert len(lines) == 3
    for line in lines:
        assert line in out.splitlines(), (line, out)


def test_study_block_is_the_same_in_both_readmes():
    assert study_block("python/README.md") == study_block("README.md")


def test_study_block_runs(scratch, monkeypatch, capsys):
    readme = "README.md"
    block = study_block(readme)
    if os.environ.get("GPM_PY_README_LONG") != "1":  # the default suite: 2 robots of a short scenario
        short = block.replace('gpm.scenarios_dir() + "/main.yaml", 100)', f'"{TINY}", 2)')
        assert short != block
        block = short
    monkeypatch.chdir(scratch)
    out = run_block(block, readme)
    assert re.search(r"^(2|100) robots \(0 failed\) in .* robots/min\): positioning median", out, re.M), out
    assert (scratch / "population.csv").read_text().startswith(",seed,failed,failure,")
    assert (scratch / "population.png").read_bytes()[:4] == b"\x89PNG"
    assert "robot " in capsys.readouterr().err
