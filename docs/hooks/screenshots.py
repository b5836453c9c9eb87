"""MkDocs hook: the guide pictures the page of this build.

The e2e test `guide_screenshots_in_headless_chromium` (crates/whipple-web/tests/e2e.rs, part of
`cargo test`) drives the page this build serves in Chromium and takes each screenshot the guide
shows, under its name in docs/screenshots, into `guide-screenshots` under the target folder
($WHIPPLE_GUIDE_SCREENSHOTS names another). This hook puts those in the built site in place of
the copies kept in docs/screenshots (which GitHub's view of the sources shows). With
WHIPPLE_GUIDE_SCREENSHOTS_REQUIRED=1 (`.ci/run` exports it: there the test command runs the e2e
test first) a missing or incomplete set fails the build; without it the build says, in its
log, that it shows the kept copies.
"""

import logging
import os
from pathlib import Path

import mkdocs.plugins
from mkdocs.exceptions import PluginError
from mkdocs.structure.files import File

ROOT = Path(__file__).resolve().parents[2]
KEPT = ROOT / "docs" / "screenshots"
log = logging.getLogger("mkdocs.hooks.screenshots")


def _taken() -> Path:
    given = os.environ.get("WHIPPLE_GUIDE_SCREENSHOTS")
    if given:
        return Path(given)
    target = os.environ.get("CARGO_TARGET_DIR")
    return (Path(target) if target else ROOT / "target") / "guide-screenshots"


@mkdocs.plugins.event_priority(40)
def on_files(files, config):
    taken = _taken()
    names = sorted(p.name for p in KEPT.glob("*.png"))
    missing = [n for n in names if not (taken / n).is_file()]
    if missing or not (taken / "done").is_file():
        message = (f"the page's screenshots of this build are not in {taken} "
                   f"({len(missing)} of {len(names)} missing): the e2e test "
                   "guide_screenshots_in_headless_chromium takes them (cargo test -p whipple-web "
                   "--test e2e -- guide_screenshots)")
        if os.environ.get("WHIPPLE_GUIDE_SCREENSHOTS_REQUIRED") == "1":
            raise PluginError(message)
        log.info("%s; the guide shows the copies kept in docs/screenshots", message)
        return files
    for name in names:
        uri = f"screenshots/{name}"
        old = files.get_file_from_path(uri)
        if old is not None:
            files.remove(old)
        files.append(File.generated(config, uri, abs_src_path=str(taken / name)))
    log.info("the guide shows the page's screenshots taken by this build's e2e test (%s)", taken)
    return files
