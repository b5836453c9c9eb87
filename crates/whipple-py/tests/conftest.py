"""Shared fixtures: the benchmark bicycle, the repository's data files, the CLI binary."""

import os
import shutil
from pathlib import Path

import pytest

import whipple

#: The repository root (these tests run from a clone).
ROOT = Path(__file__).resolve().parents[3]
#: The field's parameter files shipped with the core's tests (their README cites each source).
DATA = ROOT / "crates" / "whipple" / "tests" / "data"


@pytest.fixture(scope="session")
def benchmark():
    return whipple.Bicycle.preset("benchmark")


def _required(name: str) -> bool:
    return os.environ.get(name, "") not in ("", "0")


@pytest.fixture(scope="session")
def cli():
    """The `whipple` binary: $WHIPPLE_CLI, else target/release or target/debug of this clone.
    Missing, the CLI cross-checks skip with the reason, or fail with WHIPPLE_PY_REQUIRED=1
    (which ci-test sets)."""
    candidates = [os.environ.get("WHIPPLE_CLI", "")]
    candidates += [str(ROOT / "target" / p / "whipple") for p in ("release", "debug")]
    candidates.append(shutil.which("whipple") or "")
    for c in candidates:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return c
    message = "the whipple binary is not built (cargo build -p whipple-cli, or set WHIPPLE_CLI)"
    if _required("WHIPPLE_PY_REQUIRED"):
        pytest.fail(message)
    pytest.skip(message)


def _excused(module: str) -> bool:
    """Whether ci-test let this package go missing: WHIPPLE_PY_MISSING names those it could not
    install where they are not required (outside CI)."""
    return module in os.environ.get("WHIPPLE_PY_MISSING", "").split(",")


def optional(module: str, *, module_level: bool = False):
    """Imports an optional package of the test environment; skips with the reason when it is
    missing, fails with WHIPPLE_PY_REQUIRED=1 (which ci-test sets) unless ci-test excused it
    (WHIPPLE_PY_MISSING). `module_level`: called at a test module's top, where a failure stops
    the whole run (a collection error) and a skip skips the module."""
    try:
        return __import__(module)
    except ImportError as error:
        message = f"{module} is not installed in this environment ({error}); ci-test installs it"
        if _required("WHIPPLE_PY_REQUIRED") and not _excused(module):
            pytest.fail(message, pytrace=False)
        pytest.skip(message, allow_module_level=module_level)
