"""The built book in a real browser (headless Chromium, network off).

Run after the book build: ``python -m pytest -m browser tests/test_browser.py``. Needs Debian's
``chromium`` (``/usr/bin/chromium``, or the path in ``FDSC_CHROMIUM``) and the ``playwright``
package; Playwright's own browser download is not used. Screenshots of two pages are saved in
``book/_build/screenshots`` as CI artifacts. Once MathJax has run, the text a page shows (minus
MathJax's output and code) must hold no TeX source (``check_book_html.raw_tex_snippets``).
"""

import os
import shutil
from pathlib import Path
from urllib.parse import urlparse

import pytest
from check_book_html import raw_tex_snippets

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parent.parent
HTML = ROOT / "book" / "_build" / "html"
SHOTS = ROOT / "book" / "_build" / "screenshots"
CHROMIUM = os.environ.get("FDSC_CHROMIUM", "/usr/bin/chromium")
#: Pages that carry mathematics and must show typeset MathJax output.
MATH_PAGES = ("intro.html", "frequency_ranges.html", "gkyp_lemma.html", "passive_controllers.html",
              "frequency_selective.html", "theorem1.html", "switching_law.html", "simulations.html")
#: Pages screenshotted for the CI artifacts.
SHOT_PAGES = ("frequency_ranges.html", "gkyp_lemma.html")
#: What MathJax produced, and code: not prose. Elements of class ``math`` stay, so maths that
#: MathJax did not typeset shows as ``\(...\)`` and is reported.
NOT_PROSE = ("mjx-container, script, style, noscript, template, pre, code, kbd, samp, tt, "
             ".highlight, .cell_input")
#: The page's visible text without NOT_PROSE. The live page is changed (it is closed afterwards):
#: the innerText of a detached copy would be its textContent, hidden elements included.
VISIBLE_TEXT = f"""() => {{
    document.querySelectorAll({NOT_PROSE!r}).forEach(e => e.remove());
    return document.body.innerText;
}}"""
#: A page with display maths inside a list item and a paragraph, as Jupyter Book 1 builds it.
RAW_TEX_PAGE = Path(__file__).resolve().parent / "fixtures" / "raw_tex_page.html"
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
    # pages outside MATH_PAGES may load MathJax too; its text is read once typesetting is done
    page.evaluate("async () => { if (window.MathJax?.startup?.promise) await MathJax.startup.promise; }")
    raw = raw_tex_snippets(page.evaluate(VISIBLE_TEXT))
    assert raw == [], f"{name}: raw TeX in visible text: " + "; ".join(f"'{s}'" for s in raw[:3])


def test_the_answer_is_on_the_first_screen(browser):
    """At 1280×800 the landing page shows its findings heading without scrolling, and the sidebar
    names the book's parts."""
    context = browser.new_context(viewport={"width": 1280, "height": 800})
    pg = context.new_page()
    pg.goto((HTML / "intro.html").as_uri(), wait_until="load")
    heading = pg.get_by_role("heading", name="Does FDSC work, and when?")
    box = heading.bounding_box()
    assert box is not None and 0 <= box["y"] and box["y"] + box["height"] <= 800, box
    captions = pg.locator(".caption-text").all_inner_texts()
    for part in ("I. The paper, reproduced", "II. Does FDSC pay?", "Appendices"):
        assert any(part in c for c in captions), (part, captions)
    context.close()


def test_raw_tex_is_found_in_a_page_built_with_the_defect(page, tmp_path):
    mathjax = HTML / "_static" / "mathjax"
    if not mathjax.is_dir():
        pytest.fail(f"no MathJax in {mathjax}; run `jupyter-book build book` first")
    shutil.copy(RAW_TEX_PAGE, tmp_path / "defect.html")
    (tmp_path / "_static").mkdir()
    (tmp_path / "_static" / "mathjax").symlink_to(mathjax, target_is_directory=True)
    page.goto((tmp_path / "defect.html").as_uri(), wait_until="load")
    page.evaluate("() => MathJax.startup.promise")
    # the page's well-formed maths (one inline, one display, and the pieces of the broken $$)
    assert page.locator("mjx-container").count() >= 2
    assert page.locator(".math:not(:has(mjx-container))").count() == 0
    raw = raw_tex_snippets(page.evaluate(VISIBLE_TEXT))
    assert len(raw) == 3, raw
    assert "quadratic form with matrix $$ is negative" in raw[0]
    assert r"\left[\begin{smallmatrix}" in raw[1]
    assert r"Reliable $H_\infty $ control" in raw[2]
