"""Check a built book: images exist and are non-empty, internal links resolve, nothing is fetched
from the web when a page loads (no external scripts, stylesheets or images), and MathJax is the
book's own copy.

Usage: ``python tests/check_book_html.py book/_build/html``. Exits non-zero on any problem.
Run by ``.ci/run`` after the book build (a figure that silently fails to render, e.g. when a
non-inline matplotlib backend is forced, leaves a chapter without images).
"""

import sys
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote, urlparse

#: Chapters and the least number of figures each must show.
MIN_IMAGES = {"frequency_ranges.html": 3, "gkyp_lemma.html": 1, "passive_controllers.html": 3,
              "frequency_selective.html": 3, "theorem1.html": 1, "switching_law.html": 2,
              "stationary.html": 4}


class _Collector(HTMLParser):
    def __init__(self):
        super().__init__()
        self.images, self.links, self.loads = [], [], []

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if tag == "img" and a.get("src"):
            self.images.append(a["src"])
        if tag == "a" and a.get("href"):
            self.links.append(a["href"])
        if tag == "script" and a.get("src"):
            self.loads.append(a["src"])
        if tag == "link" and a.get("rel") in ("stylesheet", "preload") and a.get("href"):
            self.loads.append(a["href"])


def check(root):
    root = Path(root)
    problems = []
    for page in sorted(root.glob("*.html")):
        c = _Collector()
        c.feed(page.read_text(encoding="utf-8"))
        for src in c.images:
            if urlparse(src).scheme:
                problems.append(f"{page.name}: external image {src}")
                continue
            f = (page.parent / unquote(src)).resolve()
            if not f.is_file() or f.stat().st_size == 0:
                problems.append(f"{page.name}: missing or empty image {src}")
        for src in c.loads:
            if urlparse(src).scheme in ("http", "https") or src.startswith("//"):
                problems.append(f"{page.name}: loads {src} from the web")
        if page.name in MIN_IMAGES and not any("_static/mathjax/" in s for s in c.loads):
            problems.append(f"{page.name}: does not load the book's own MathJax")
        if len(c.images) < MIN_IMAGES.get(page.name, 0):
            problems.append(f"{page.name}: {len(c.images)} images, expected >= {MIN_IMAGES[page.name]}")
        for href in c.links:
            u = urlparse(href)
            if u.scheme or href.startswith(("#", "mailto:")):
                continue
            target = (page.parent / unquote(u.path)).resolve()
            if not target.exists():
                problems.append(f"{page.name}: broken link {href}")
    return problems


if __name__ == "__main__":
    found = check(sys.argv[1] if len(sys.argv) > 1 else "book/_build/html")
    print("\n".join(found) or "book HTML: images present, internal links resolve, no web loads")
    sys.exit(1 if found else 0)
