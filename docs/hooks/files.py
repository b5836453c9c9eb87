"""MkDocs hook: pages of the guide whose sources live outside docs/, so each has one home.

- The Python examples (crates/whipple-py/examples/*.py, percent format, run by the Python tests)
  become guide/examples/*.py, which mkdocs-jupyter executes and renders as notebooks.
- The Rust API reference is rustdoc's own output (`cargo doc`), copied under api/rust/. Its
  folder is $WHIPPLE_RUSTDOC_DIR, else target/doc of the clone; docs/build-guide builds it.
"""

import os
from pathlib import Path

import mkdocs.plugins
from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "crates" / "whipple-py" / "examples"
# The crates whose rustdoc the guide links to (docs/guide/api-rust.md).
CRATES = ("whipple", "whipple_report", "whipple_web", "whipple_cli")


def _rustdoc_dir() -> Path:
    given = os.environ.get("WHIPPLE_RUSTDOC_DIR")
    if given:
        return Path(given)
    target = os.environ.get("CARGO_TARGET_DIR")
    return (Path(target) if target else ROOT / "target") / "doc"


# Before mkdocs-jupyter's own on_files, which turns the examples into notebook pages.
@mkdocs.plugins.event_priority(100)
def on_files(files, config):
    for script in sorted(EXAMPLES.glob("*.py")):
        files.append(File.generated(config, f"guide/examples/{script.name}",
                                    abs_src_path=str(script)))
    rustdoc = _rustdoc_dir()
    missing = [c for c in CRATES if not (rustdoc / c / "index.html").is_file()]
    if missing:
        raise PluginError(
            f"the Rust API reference is not built ({', '.join(missing)} missing in {rustdoc}): "
            "run docs/build-guide, or `cargo doc --no-deps -p whipple -p whipple-report "
            "-p whipple-web -p whipple-cli` first")
    for path in sorted(rustdoc.rglob("*")):
        rel = path.relative_to(rustdoc)
        if path.is_file() and path.name != ".lock" and _ours(rel.parts):
            files.append(File.generated(config, f"api/rust/{rel.as_posix()}",
                                        abs_src_path=str(path)))
    return files


# rustdoc's shared folders; every other folder is one crate's pages (or sources under src/).
SHARED = ("static.files", "search.index", "trait.impl", "type.impl")


def _ours(parts) -> bool:
    """Whether a file of the rustdoc folder belongs to the four crates' reference: a target/doc
    that also holds dependencies' pages (a `cargo doc` without --no-deps) adds none of them."""
    if len(parts) == 1 or parts[0] in SHARED:
        return True
    if parts[0] == "src":
        return len(parts) > 2 and parts[1] in CRATES
    return parts[0] in CRATES


def on_nav(nav, config, files):
    # mkdocs-jupyter wraps each example in a NotebookFile, which reads the source path through
    # the wrapped file's folder; an added file has none, so give the wrapper the path itself.
    for file in files:
        inner = getattr(file, "file", None)
        if inner is not None and str(inner.src_uri).startswith("guide/examples/"):
            file.__dict__["abs_src_path"] = inner.abs_src_path
    return nav
