"""MkDocs hook: how to cite whipple says one thing everywhere.

The workspace's Cargo.toml is the one home of the version and of the repository's address. The
build fails, naming the file, when CITATION.bib (which the guide's "How to cite" page includes),
CITATION.cff, the README's BibTeX, the guide's `repo_url` or the Python package's URLs disagree
with it, so that filling the address in once and building the guide shows every place still
to change; docs/set-repository-url fills a new address in everywhere at once.
"""

import re
import tomllib
from pathlib import Path

from mkdocs.exceptions import PluginError

ROOT = Path(__file__).resolve().parents[2]


def _field(bib: str, name: str) -> str:
    match = re.search(rf"^\s*{name}\s*=\s*\{{(.*)\}},?\s*$", bib, re.M)
    if not match:
        raise PluginError(f"CITATION.bib: the software's entry has no `{name}`")
    return match.group(1)


def on_config(config):
    package = tomllib.loads((ROOT / "Cargo.toml").read_text())["workspace"]["package"]
    version, repository = package["version"], package["repository"]
    bib = (ROOT / "CITATION.bib").read_text()
    software = re.search(r"@software\{whipple,.*?\n\}\n", bib, re.S)
    if not software:
        raise PluginError("CITATION.bib has no @software{whipple, ...} entry")
    problems = []
    if _field(software.group(0), "version") != version:
        problems.append(f"CITATION.bib: version {_field(software.group(0), 'version')}, Cargo.toml {version}")
    if _field(software.group(0), "url") != repository:
        problems.append(f"CITATION.bib: url {_field(software.group(0), 'url')}, Cargo.toml {repository}")
    readme = (ROOT / "README.md").read_text()
    shown = re.search(r"```bibtex\n(.*?)```", readme, re.S)
    if not shown or shown.group(1) not in bib:
        problems.append("README.md: its BibTeX is not CITATION.bib's software entry as written there")
    cff = (ROOT / "CITATION.cff").read_text()
    for key, want in (("version", version), ("repository-code", repository)):
        match = re.search(rf'^{key}:\s*"?([^"\n]+)"?\s*$', cff, re.M)
        if not match or match.group(1) != want:
            problems.append(f"CITATION.cff: {key} {match.group(1) if match else 'missing'}, Cargo.toml {want}")
    if config.get("repo_url") != repository:
        problems.append(f"mkdocs.yml: repo_url {config.get('repo_url')}, Cargo.toml {repository}")
    urls = tomllib.loads((ROOT / "crates" / "whipple-py" / "pyproject.toml").read_text())["project"]["urls"]
    for name, url in urls.items():
        if not url.startswith(repository):
            problems.append(f"crates/whipple-py/pyproject.toml: {name} {url} is not under {repository}")
    if problems:
        raise PluginError("how to cite whipple disagrees with Cargo.toml: " + "; ".join(problems)
                          + " (docs/set-repository-url rewrites the address everywhere)")
    return config
