"""The built book in a real browser (headless Chromium, network off).

Run after the book build: ``python -m pytest -m browser tests/test_browser.py``. Needs Debian's
``chromium`` (``/usr/bin/chromium``, or the path in ``FDSC_CHROMIUM``) and the ``playwright``
package; Playwright's own browser download is not used. Screenshots of two pages are saved in
``book/_build/screenshots`` as CI artifacts.
"""

import os
from pathlib import Path
from urllib.parse import urlparse

import pytest

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parent.parent
HTML = ROOT / "book" / "_build" / "html"
SHOTS = ROOT / "book" / "_build" / "screenshots"
CHROMIUM = os.environ.get("FDSC_CHROMIUM", "/usr/bin/chromium")
#: Pages that carry mathematics and must show typeset MathJax output.
MATH_PAGES = ("intro.html", "frequency_ranges.html", "gkyp_lemma.html", "passive_controllers.html",
              "frequency_selective.html", "theorem1.html", "switching_law.html", "stationary.html")
#: Pages screenshotted for the CI artifacts.
SHOT_PAGES = ("frequency_ranges.html", "gkyp_lemma.html")
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                 "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def pages():
    if not (HTML / "index.html").is_file():
        pytest.fail(f"no built book in {HTML}; run `jupyter-book build book` first")
    # index.html is only a redirect to the root chapter (tested on its own)
    return sorted(p.name for p in HTML.glob("*.html") if p.name != "index.html")


@pytest.fixture(scope="module")
def browser():
    sync_api = pytest.importorskip("playwright.sync_api", reason="pip install playwright")
    if not Path(CHROMIUM).is_file():
        pytest.fail(f"Chromium not found at {CHROMIUM} (apt-get install chromium)")
    with sync_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        yield b
        b.close()


@pytest.fixture
def page(browser):
    context = browser.new_context(viewport={"width": 1300, "height": 1000})
    web_requests = []

    def block_web(route):
        # network off: anything that is not a file of the book is recorded and refused
        web_requests.append(route.request.url)
        route.abort()

    context.route("http://**/*", block_web)
    context.route("https://**/*", block_web)
    pg = context.new_page()
    pg.web_requests = web_requests
    pg.console_errors = []
    pg.on("console", lambda m: m.type == "error" and pg.console_errors.append(m.text))
    pg.on("pageerror", lambda e: pg.console_errors.append(str(e)))
    yield pg
    context.close()


def test_index_redirects_to_the_introduction(page):
    page.goto((HTML / "index.html").as_uri())
    page.wait_for_url("**/intro.html", timeout=10_000)
    assert page.web_requests == []


@pytest.mark.parametrize("name", pages() if (HTML / "index.html").is_file() else ["intro.html"])
def test_page_renders_offline(page, name):
    page.goto((HTML / name).as_uri(), wait_until="load")
    if name in MATH_PAGES:
        # MathJax typesets asynchronously; wait until it has produced its output
        page.wait_for_function("() => window.MathJax && MathJax.startup && "
                               "MathJax.startup.promise && document.querySelector('mjx-container')",
                               timeout=30_000)
        page.evaluate("() => MathJax.startup.promise")
        n_math = page.locator("mjx-container").count()
        assert n_math > 0, f"{name}: no typeset mathematics"
        assert page.locator("mjx-merror").count() == 0, f"{name}: MathJax reported TeX errors"
    sizes = page.eval_on_selector_all(
        "img", "imgs => imgs.map(i => [i.getAttribute('src'), i.naturalWidth, i.naturalHeight])")
    for src, w, h in sizes:
        assert w > 0 and h > 0, f"{name}: image {src} did not load"
    hrefs = page.eval_on_selector_all("a[href]", "as => as.map(a => a.href)")
    for href in hrefs:
        u = urlparse(href)
        if u.scheme == "file":
            assert Path(u.path).exists(), f"{name}: broken internal link {href}"
    assert page.web_requests == [], f"{name}: tried to load from the web: {page.web_requests}"
    assert page.console_errors == [], f"{name}: console errors: {page.console_errors}"
    if name in SHOT_PAGES:
        SHOTS.mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(SHOTS / name.replace(".html", ".png")), full_page=True)
