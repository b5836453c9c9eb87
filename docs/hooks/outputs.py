"""MkDocs hook: the output a page shows is the output of its command, run at this build.

A fenced block opened with ```output holds commands only, one `$ whipple ...` per line (a
trailing `\\` continues a line). At every build the block's commands run in order, in a new
empty folder (as a reader who has just installed whipple would run them: a file a command reads
must be written by an earlier line of the same block: `$ whipple examples --out .` writes the
field's files), by the whipple binary named in
$WHIPPLE_GUIDE_BIN (docs/build-guide builds it). The page then shows a ```text block with each
command and what it printed (standard output and standard error as the terminal interleaves
them). A command that fails fails the build, unless the block is opened with ```output fails:
then its last command must fail (and the others succeed), and its message is what the page
shows. Nothing a page shows as output is kept in the repository, so none can be older than the
program. crates/whipple-cli/tests/guide.rs runs the same commands under `cargo test`.
"""

import os
import re
import shlex
import shutil
import subprocess
import tempfile
from pathlib import Path

from mkdocs.exceptions import PluginError

# One command's bound: the slowest shown takes a second or two.
TIMEOUT = 300
_FENCE = re.compile(r"^```output( fails)?[ \t]*\n(.*?)^```[ \t]*$", re.M | re.S)


def _commands(body, where):
    """The block's commands as (as written, words), continued lines joined."""
    commands, pending = [], ""
    for line in body.splitlines():
        line = line.strip()
        if not line and not pending:
            continue
        line = f"{pending} {line}".strip() if pending else line
        pending = ""
        if line.endswith("\\"):
            pending = line[:-1].rstrip()
            continue
        if not line.startswith("$ whipple "):
            raise PluginError(f"{where}: an output block holds `$ whipple ...` lines only, not `{line}`")
        command = line[2:]
        commands.append((command, shlex.split(command, comments=True)))
    if pending or not commands:
        raise PluginError(f"{where}: an output block with no complete command")
    return commands


def _run(binary, commands, must_fail, where):
    folder = Path(tempfile.mkdtemp(prefix="whipple-guide-output."))
    shown = []
    try:
        for i, (command, words) in enumerate(commands):
            last = i == len(commands) - 1
            try:
                run = subprocess.run([binary, *words[1:]], cwd=folder, stdout=subprocess.PIPE,
                                     stderr=subprocess.STDOUT, text=True, timeout=TIMEOUT,
                                     env={**os.environ, "NO_COLOR": "1"})
            except subprocess.TimeoutExpired:
                raise PluginError(f"{where}: `{command}` gave no answer in {TIMEOUT} s")
            failed = run.returncode != 0
            if failed != (must_fail and last):
                expected = "to fail" if must_fail and last else "to succeed"
                raise PluginError(f"{where}: `{command}` was expected {expected}; it exited with "
                                  f"status {run.returncode}:\n{run.stdout}")
            if "NaN" in run.stdout:
                raise PluginError(f"{where}: `{command}` printed a NaN:\n{run.stdout}")
            shown.append(f"$ {command}\n{run.stdout}")
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    return "".join(s if s.endswith("\n") else s + "\n" for s in shown)


def on_page_markdown(markdown, page, config, files):
    if "```output" not in markdown:
        return markdown
    binary = os.environ.get("WHIPPLE_GUIDE_BIN")
    if not binary or not Path(binary).is_file():
        raise PluginError(
            "the guide's outputs are made by its commands: set WHIPPLE_GUIDE_BIN to a built "
            "whipple binary (docs/build-guide does)")

    def replace(match):
        line = markdown.count("\n", 0, match.start()) + 1
        where = f"docs/{page.file.src_uri}:{line}"
        text = _run(binary, _commands(match.group(2), where), bool(match.group(1)), where)
        if "```" in text:
            raise PluginError(f"{where}: the output holds a code fence")
        return f"```text\n{text}```"

    return _FENCE.sub(replace, markdown)
