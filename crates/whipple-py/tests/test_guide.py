"""The user guide's Python examples run: every ```python block of docs/guide/*.md is run as a
script against the installed package, in a scratch directory holding the field's parameter files
the guide names. A block that only includes a file (`--8<-- "…"`) is skipped here: the example
scripts are run by test_examples.py (and executed as notebooks when the guide is built)."""

import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import DATA, ROOT

GUIDE = ROOT / "docs" / "guide"
FENCE = re.compile(r"^```python\n(.*?)^```", re.M | re.S)


def blocks():
    found = []
    for chapter in sorted(GUIDE.glob("*.md")):
        text = chapter.read_text(encoding="utf-8")
        for match in FENCE.finditer(text):
            code = match.group(1)
            line = text.count("\n", 0, match.start()) + 1
            if code.strip().startswith("--8<--"):
                continue
            found.append(pytest.param(code, id=f"{chapter.stem}:{line}"))
    return found


def test_the_guide_has_python_examples():
    assert len(blocks()) >= 3


@pytest.mark.parametrize("code", blocks())
def test_guide_python_block_runs(code, tmp_path):
    for sub in ("bicycleparameters", "humancontrol"):
        for path in (DATA / sub).glob("*.txt"):
            shutil.copy(path, tmp_path / path.name)
    env = dict(os.environ, MPLBACKEND="Agg", WHIPPLE_EXAMPLES_OUT=str(tmp_path))
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=tmp_path, env=env, timeout=600)
    assert done.returncode == 0, done.stderr
