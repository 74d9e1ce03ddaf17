# Tests python/README.md and README.md: their Python example runs as written.
import contextlib
import io
import re

from conftest import ROOT


import pytest


@pytest.mark.parametrize("readme", ["python/README.md", "README.md"])
def test_readme_example_runs_as_written(readme):
    text = (ROOT / readme).read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 1
    assert len(blocks[0].strip().splitlines()) <= 10
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(blocks[0], readme, "exec"), {})
    assert "converged: True" in out.getvalue()
