"""MkDocs hook: the guide's figures are made by the commands the guide shows, at every build.

Each ```sh block line of a chapter that runs `whipple ... --plot F`, `--figure F` or `--out F`,
where the guide shows `img/F` (or `--report DIR`, where it shows `img/DIR/NAME`: a file of the
report), is run in a scratch folder (holding the field's files the examples read, written by
`whipple examples`, as a chapter's own `whipple examples --out .` writes them) by the whipple
binary named in $WHIPPLE_GUIDE_BIN (docs/build-guide builds it), and its F becomes the page's
img/F. A command that fails fails the build, so a figure can never be older
than the program: none of these figures is kept in the repository.
"""

import os
import re
import shlex
import shutil
import subprocess
import tempfile
from pathlib import Path

import mkdocs.plugins
from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File

ROOT = Path(__file__).resolve().parents[2]
GUIDE = ROOT / "docs" / "guide"
FIGURE_OPTIONS = ("--plot", "--figure", "--out")
REPORT_OPTION = "--report"
# One command's bound: the slowest (a design map) takes seconds.
TIMEOUT = 300

_scratch = None


def _commands(text):
    """(line, words) of every `whipple ...` line of the ```sh blocks (`\\` continues a line)."""
    found, in_sh, pending = [], False, None
    for n, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if stripped.startswith("```"):
            in_sh = not in_sh and stripped == "```sh"
            continue
        if not in_sh:
            continue
        start, joined = (pending[0], f"{pending[1]} {stripped}") if pending else (n, stripped)
        pending = None
        if joined.endswith("\\"):
            pending = (start, joined[:-1].rstrip())
            continue
        if joined.startswith("whipple "):
            found.append((start, shlex.split(joined, comments=True)))
    return found


def _figures():
    """{figure's path in the scratch folder: (chapter, line, words)} for every figure a chapter
    both makes and shows."""
    wanted = {}
    for page in sorted(GUIDE.glob("*.md")):
        text = page.read_text(encoding="utf-8")
        for line, words in _commands(text):
            for option, value in zip(words, words[1:]):
                if option in FIGURE_OPTIONS and f"](img/{value})" in text:
                    wanted.setdefault(value, (page.name, line, words))
                if option == REPORT_OPTION:
                    folder = value.rstrip("/")
                    for shown in re.findall(rf"\]\(img/({re.escape(folder)}/[^)\s]+)\)", text):
                        wanted.setdefault(shown, (page.name, line, words))
    return wanted


@mkdocs.plugins.event_priority(50)
def on_files(files, config):
    global _scratch
    binary = os.environ.get("WHIPPLE_GUIDE_BIN")
    if not binary or not Path(binary).is_file():
        raise PluginError(
            "the guide's figures are made by its commands: set WHIPPLE_GUIDE_BIN to a built "
            "whipple binary (docs/build-guide does)")
    _scratch = Path(tempfile.mkdtemp(prefix="whipple-guide-figures."))
    # The field's files the chapters' commands read, as `whipple examples --out .` writes them.
    made = subprocess.run([binary, "examples", "--out", str(_scratch)], capture_output=True,
                          text=True, timeout=TIMEOUT)
    if made.returncode != 0:
        raise PluginError(f"`whipple examples` failed ({made.returncode}): {made.stderr.strip()}")
    done = {}
    for name, (chapter, line, words) in sorted(_figures().items()):
        # A command that makes several figures (a report) runs once.
        key = (chapter, line)
        if key not in done:
            try:
                done[key] = subprocess.run([binary, *words[1:]], cwd=_scratch,
                                           capture_output=True, text=True, timeout=TIMEOUT)
            except subprocess.TimeoutExpired:
                raise PluginError(f"docs/guide/{chapter}:{line}: no answer in {TIMEOUT} s")
        run = done[key]
        made = _scratch / name
        if run.returncode != 0 or not made.is_file():
            raise PluginError(f"docs/guide/{chapter}:{line}: `{' '.join(words)}` failed "
                              f"({run.returncode}): {run.stderr.strip()}")
        uri = f"guide/img/{name}"
        old = files.get_file_from_path(uri)
        if old is not None:
            files.remove(old)
        files.append(File.generated(config, uri, abs_src_path=str(made)))
    return files


def on_post_build(config):
    if _scratch is not None:
        shutil.rmtree(_scratch, ignore_errors=True)
