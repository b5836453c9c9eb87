"""The examples run as a new user runs them (scripts in percent format), so they never rot."""

import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import optional

EXAMPLES = sorted((Path(__file__).resolve().parents[1] / "examples").glob("*.py"))


@pytest.mark.parametrize("script", EXAMPLES, ids=[p.stem for p in EXAMPLES])
def test_example_runs(script, tmp_path):
    # A copy, run from a scratch directory: an example needs only the installed package and
    # the data it ships (issue 28), never a file of the clone.
    copy = tmp_path / script.name
    shutil.copy(script, copy)
    env = dict(os.environ, WHIPPLE_EXAMPLES_OUT=str(tmp_path), MPLBACKEND="Agg")
    done = subprocess.run([sys.executable, str(copy)], capture_output=True, text=True,
                          cwd=tmp_path, env=env, timeout=600)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip()
    if "matplotlib" in script.read_text():
        try:
            import matplotlib  # noqa: F401
        except ImportError:
            return
        assert list(tmp_path.glob("*.png")), "the example wrote no figure"


def test_plots_draw(tmp_path):
    matplotlib = optional("matplotlib")
    matplotlib.use("Agg")
    import numpy as np

    import whipple

    bike = whipple.Bicycle.preset("benchmark")
    ax = bike.eig(np.linspace(0, 10, 101)).plot()
    assert len(ax.lines) >= 4
    left, right = bike.simulate(4.6, 1.0, lean_rate=0.5).plot()
    assert left.lines and right.lines
