"""The `whipple` command that `pip install` puts on PATH ([project.scripts] -> whipple._cli): the
very CLI of crates/whipple-cli, run in the interpreter's process by the native module. Checked
against the Rust binary of this clone: same output files, same messages, same exit statuses."""

import subprocess
import sys
from pathlib import Path

import pytest

import whipple

PNG = b"\x89PNG\r\n\x1a\n"


def script():
    """The installed script beside this interpreter (bin/ on POSIX, Scripts/ on Windows)."""
    here = Path(sys.executable).parent
    for name in ("whipple", "whipple.exe"):
        if (here / name).is_file():
            return str(here / name)
    pytest.fail(f"the package installed no `whipple` script in {here}")


def run(args, cwd):
    return subprocess.run(args, capture_output=True, text=True, cwd=cwd, timeout=300)


def test_the_script_draws_the_benchmark_eigenvalues(tmp_path):
    done = run([script(), "eig", "--bike", "benchmark", "--plot", "eig.png"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert "weave" in done.stdout
    data = (tmp_path / "eig.png").read_bytes()
    assert data.startswith(PNG) and len(data) > 10_000


def test_the_script_prints_what_the_binary_prints(cli, tmp_path):
    args = ["speeds", "--bike", "benchmark", "--format", "json"]
    ours, theirs = run([script(), *args], tmp_path), run([cli, *args], tmp_path)
    assert ours.returncode == theirs.returncode == 0
    assert ours.stdout == theirs.stdout


@pytest.mark.parametrize("args, status", [
    (["eig", "--bike", "benchmark", "--no-such-option"], 2),   # clap's usage error
    (["speeds", "--bike", "no-such-bike"], 1),                 # the command's own error
    (["show", "--bike", "missing.toml"], 1),                   # a file that is not there
])
def test_a_bad_command_fails_with_the_clis_message(cli, tmp_path, args, status):
    ours, theirs = run([script(), *args], tmp_path), run([cli, *args], tmp_path)
    assert ours.returncode == theirs.returncode == status
    assert ours.stderr.strip() and ours.stderr == theirs.stderr
    assert ours.stdout == ""


def test_python_m_whipple_is_the_same_command(tmp_path):
    done = run([sys.executable, "-m", "whipple", "--version"], tmp_path)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["whipple", whipple.__version__]


def test_the_command_runs_in_process_more_than_once(tmp_path, capfd):
    # Options are per run (the Python function may be called again in one process).
    assert whipple._whipple.cli_main(["whipple", "--strict", "speeds", "--bike",
                                      str(tmp_path / "missing.toml")]) == 1
    assert whipple._whipple.cli_main(["whipple", "presets"]) == 0
    out, err = capfd.readouterr()
    assert "benchmark" in out and "missing.toml" in err
