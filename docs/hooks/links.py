"""MkDocs hook: the built site opens at its home page, and none of its internal links is broken.

- The site's root gets an index.html that sends the reader to the guide's home page
  (guide/index.html), so that `site/index.html` opened from the build output and `/` on a
  static server both show it; with `use_directory_urls: false` every link of the site is a
  file's name and works from the file system too.
- After the build, every href and src of every HTML page of the site (the chapters, the
  notebooks, rustdoc's pages; not the 404 page, whose links are absolute by design) that points inside the site must name a file that exists, and
  its #anchor, when it has one and points into a chapter or a design note, an id of that page.
  A broken link fails the build, naming the page and the link. Links to other sites are not
  fetched (the build runs offline).
"""

import html
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlsplit

import mkdocs.plugins
from mkdocs.exceptions import PluginError

HOME = "guide/index.html"
# rustdoc's own pages link to files its scripts make or fetch at run time (search index
# shards, source listings of other crates, settings.html, help.html); those are checked by
# rustdoc itself (`-D warnings`), not here.
RUSTDOC = "api/rust/"
# MkDocs' 404 page is served in place of any missing path, so its links are absolute on purpose.
NOT_FOUND_PAGE = "404.html"


class _Links(HTMLParser):
    def __init__(self):
        super().__init__(convert_charrefs=True)
        self.links, self.ids = [], set()

    def handle_starttag(self, tag, attrs):
        for name, value in attrs:
            if value is None:
                continue
            if name in ("href", "src") and tag in ("a", "link", "img", "script", "source",
                                                    "iframe", "embed"):
                self.links.append(value)
            elif name in ("id", "name") and tag != "meta":
                self.ids.add(value)


def _parse(path, cache):
    if path not in cache:
        parser = _Links()
        parser.feed(path.read_text(encoding="utf-8", errors="replace"))
        cache[path] = parser
    return cache[path]


def _target(site, page, link):
    """The file a relative link of `page` points at, with its fragment; None when it leaves
    the site (another scheme or host) or stays on the page."""
    parts = urlsplit(html.unescape(link))
    if parts.scheme or parts.netloc or link.startswith("//"):
        return None
    if not parts.path:
        return (page, unquote(parts.fragment)) if parts.fragment else None
    if parts.path.startswith("/"):
        return "outside", parts.path
    target = (page.parent / unquote(parts.path)).resolve()
    if target.is_dir():
        target = target / "index.html"
    return target, unquote(parts.fragment)


@mkdocs.plugins.event_priority(-100)
def on_post_build(config):
    site = Path(config["site_dir"]).resolve()
    if not (site / HOME).is_file():
        raise PluginError(f"the guide's home page {HOME} was not built")
    root = site / "index.html"
    if not root.exists():
        root.write_text(
            "<!doctype html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n"
            "<title>whipple user guide</title>\n"
            f"<meta http-equiv=\"refresh\" content=\"0; url={HOME}\">\n"
            f"<link rel=\"canonical\" href=\"{HOME}\"></head>\n"
            f"<body><p>The guide is at <a href=\"{HOME}\">{HOME}</a>.</p></body></html>\n",
            encoding="utf-8")
    cache, broken, checked = {}, [], 0
    for page in sorted(site.rglob("*.html")):
        rel = page.relative_to(site).as_posix()
        if rel == NOT_FOUND_PAGE:
            continue
        in_rustdoc = rel.startswith(RUSTDOC)
        for link in _parse(page, cache).links:
            found = _target(site, page, link)
            if found is None:
                continue
            target, fragment = found
            if target == "outside":
                broken.append(f"{rel}: {link} (an absolute path: it leaves the site on a static host)")
                continue
            checked += 1
            try:
                target.relative_to(site)
            except ValueError:
                broken.append(f"{rel}: {link} (outside the site)")
                continue
            if not target.is_file():
                if not in_rustdoc:
                    broken.append(f"{rel}: {link} (no such file)")
                continue
            # Anchors are checked where they are ours: chapters, notebooks and design notes.
            if (fragment and target.suffix == ".html" and not in_rustdoc
                    and not target.relative_to(site).as_posix().startswith(RUSTDOC)
                    and fragment not in _parse(target, cache).ids):
                broken.append(f"{rel}: {link} (no #{fragment} there)")
    if broken:
        listed = "\n  ".join(broken[:40])
        more = f"\n  … and {len(broken) - 40} more" if len(broken) > 40 else ""
        raise PluginError(f"{len(broken)} broken links in the built site:\n  {listed}{more}")
    if checked < 500:
        raise PluginError(f"only {checked} internal links found in the built site: the link "
                          "checker has lost its way")
