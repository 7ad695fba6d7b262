"""make html (img2logo.experiments.html): an executed notebook as a page that reads offline."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from img2logo.errors import InvalidParameterError

nbformat = pytest.importorskip("nbformat")
pytest.importorskip("nbconvert", reason="the extra [html] (make html installs it)")
pytest.importorskip("jupyter_server_mathjax", reason="the extra [html] (make html installs it)")

from img2logo.experiments.html import export_html, external_references, main  # noqa: E402

# A 1 x 1 px PNG, as a notebook's figure output.
PIXEL = "iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mP8z8BQDwAEhQGAhKmMIQAAAABJRU5ErkJggg=="


def notebook(path: Path) -> Path:
    nb = nbformat.v4.new_notebook()
    nb.cells = [
        nbformat.v4.new_markdown_cell("# Levels\n\nThe levels $A^0, \\dots, A^t$ and $E^s = \\sum_i d_i$ px."),
        nbformat.v4.new_code_cell("show()", outputs=[nbformat.v4.new_output("display_data", {"image/png": PIXEL})]),
    ]
    nbformat.write(nb, path)
    return path


def test_the_page_loads_nothing_from_the_network(tmp_path):
    page = export_html(notebook(tmp_path / "01_demo.ipynb"), tmp_path / "html")
    assert page == tmp_path / "html" / "01_demo.html"
    text = page.read_text(encoding="utf-8")
    assert external_references(text) == []
    assert 'src="mathjax/MathJax.js?config=' in text and (tmp_path / "html" / "mathjax" / "MathJax.js").is_file()
    assert "data:image/png;base64," in text  # the figure is in the page
    assert "cdnjs" not in text and "require.min.js" not in text
    assert '<a href="notebooks.html">' in text  # back to the docs site's notebooks index


def test_a_notebook_page_names_what_it_reproduces(tmp_path):
    text = export_html(notebook(tmp_path / "05_connectivity_ablation.ipynb"), tmp_path / "html").read_text("utf-8")
    assert "05_connectivity_ablation reproduces Fig. 11, 6 of the paper" in text


def test_external_references_finds_loads_not_links():
    assert external_references('<script src="https://cdn.example/x.js"></script>') == ['src="https://cdn.example/x.js"']
    assert external_references('<link rel="stylesheet" href="//fonts.example/a.css">') != []
    assert external_references('<a href="https://doi.org/10.1111/cgf.14742">paper</a>') == []


def test_bad_notebook_is_one_line(tmp_path, capsys):
    with pytest.raises(InvalidParameterError, match="notebook not found"):
        export_html(tmp_path / "missing.ipynb", tmp_path)
    assert main([str(tmp_path / "missing.ipynb"), str(tmp_path)]) == 2
    assert capsys.readouterr().err.count("\n") == 1


def test_math_is_typeset_with_the_network_off(tmp_path):
    """Opened from disk in chromium with every non-file request refused: the TeX is typeset, nothing asked."""
    playwright = pytest.importorskip("playwright.sync_api")
    if not Path("/usr/bin/chromium").exists():
        pytest.skip("chromium is not installed (apt-get install chromium)")
    page_path = export_html(notebook(tmp_path / "demo.ipynb"), tmp_path / "html")
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
        try:
            page = browser.new_page()
            asked: list[str] = []

            def refuse(route):
                asked.append(route.request.url)
                route.abort()

            page.route(re.compile(r"^(?!file:).*"), refuse)
            page.goto(page_path.as_uri())
            page.wait_for_function("document.querySelectorAll('.MathJax').length >= 2", timeout=60_000)
            raw = page.evaluate("document.querySelector('.jp-RenderedMarkdown').innerText")
        finally:
            browser.close()
    assert asked == []
    assert "$A^0" not in raw and "\\dots" not in raw  # no TeX left as text
