"""The docs site in chromium at 1366 x 768: no page scrolls sideways, the API pages typeset math.

Builds the site (Sphinx, the extra [docs]) into a temporary folder with warnings as errors, then
opens its pages from disk in Debian's chromium through playwright (the extra [browser]).
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest
from browser_support import CHROMIUM, CHROMIUM_ARGS

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[1]
WIDTH, HEIGHT = 1366, 768
#: The pages a reader starts from: the guide, how it works, the notebooks index, a design note.
PAGES = (
    "index.html",
    "guide/index.html",
    "guide/cli.html",
    "guide/python.html",
    "guide/studio.html",
    "guide/batch.html",
    "how-it-works.html",
    "notebooks.html",
    "design/large-images.html",
    "quality.html",
)


@pytest.fixture(scope="module")
def site(tmp_path_factory):
    pytest.importorskip("sphinx", reason="the extra [docs] (make docs installs it)")
    pytest.importorskip("numpydoc", reason="the extra [docs] (make docs installs it)")
    pytest.importorskip("myst_parser", reason="the extra [docs] (make docs installs it)")
    out = tmp_path_factory.mktemp("docs")
    done = subprocess.run(
        [sys.executable, "-m", "sphinx", "-q", "-W", "--keep-going", "-b", "html", "docs", str(out)],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=1800,
    )
    assert done.returncode == 0, f"sphinx-build -W failed:\n{done.stderr[-3000:]}"
    return out


@pytest.fixture(scope="module")
def browser():
    playwright = pytest.importorskip("playwright.sync_api")
    if not Path(CHROMIUM).exists():
        pytest.skip("chromium is not installed (apt-get install chromium)")
    with playwright.sync_playwright() as p:
        chromium = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        try:
            yield chromium
        finally:
            chromium.close()


def _open(browser, path: Path):
    page = browser.new_page(viewport={"width": WIDTH, "height": HEIGHT})
    page.goto(path.as_uri())
    page.wait_for_load_state("load")
    return page


@pytest.mark.parametrize("name", PAGES)
def test_the_page_fits_the_window(site, browser, name):
    page = _open(browser, site / name)
    try:
        width = page.evaluate("document.documentElement.scrollWidth")
        assert width <= WIDTH, f"{name} is {width} px wide in a {WIDTH} px window"
    finally:
        page.close()


def test_the_api_pages_typeset_the_papers_symbols(site, browser):
    page = _open(browser, site / "generated" / "img2logo.pipeline.html")
    try:
        page.wait_for_function("window.MathJax && MathJax.Hub && MathJax.Hub.queue.pending === 0", timeout=60000)
        typeset = page.evaluate("document.querySelectorAll('.MathJax, .MathJax_SVG, mjx-container').length")
        # The symbols outside code, scripts and MathJax's own copies: none left as plain text.
        raw = page.evaluate(
            "(() => { const b = document.body.cloneNode(true);"
            " b.querySelectorAll('code, pre, script, .MathJax_Preview, .MathJax, .MathJax_SVG')"
            ".forEach(e => e.remove());"
            " return b.textContent.includes('E^s'); })()"
        )
        assert typeset > 0 and not raw
    finally:
        page.close()


def test_the_notebooks_index_names_each_paper_item(site):
    from img2logo.experiments.runner import PAPER_ITEMS

    text = (site / "notebooks.html").read_text(encoding="utf-8")
    for name, (item, _) in PAPER_ITEMS.items():
        assert name in text and item.replace("'", "&#8217;").split(",")[0] in text
