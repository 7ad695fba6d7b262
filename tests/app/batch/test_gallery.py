"""The batch's gallery (img2logo.app.batch.gallery): OUTPUT_DIR/index.html, offline, every input beside its logo."""

from __future__ import annotations

import re
import shutil
from html.parser import HTMLParser
from pathlib import Path
from urllib.parse import unquote

import pytest
from helpers import DATA

from img2logo.app.batch.gallery import GALLERY_NAME, gallery_html, write_gallery
from img2logo.app.batch.run import BatchFailure, BatchReport, BatchRow, run_batch


class _Links(HTMLParser):
    """Every src and href of a page, and whether it has a script or an external stylesheet."""

    def __init__(self) -> None:
        super().__init__()
        self.links: list[str] = []
        self.scripts = 0

    def handle_starttag(self, tag, attrs):
        self.scripts += tag == "script" or (tag == "link" and ("rel", "stylesheet") in attrs)
        self.links.extend(v for k, v in attrs if k in ("src", "href") and v)


def parse(text: str) -> _Links:
    p = _Links()
    p.feed(text)
    return p


def report_of(tmp_path: Path) -> tuple[BatchReport, Path]:
    """A report of two images (one with a space in its name) and one failure, with its files present."""
    src, out = tmp_path / "in put", tmp_path / "out"
    src.mkdir()
    out.mkdir()
    shutil.copy(DATA / "drawing-leaf.png", src / "my leaf.png")
    (src / "scan.tif").write_bytes(b"II*\0")
    (src / "bad.png").write_text("no")
    for name in ("my leaf.svg", "my leaf.png", "my leaf.json", "scan.svg"):
        (out / name).write_text("x")
    rows = (
        BatchRow(
            "my leaf.png",
            str(src / "my leaf.png"),
            "drawing",
            12,
            5,
            1.234,
            0.56,
            tuple(str(out / f"my leaf.{f}") for f in ("svg", "json", "png")),
        ),
        BatchRow("scan.tif", str(src / "scan.tif"), "clipart", 1, 1, 0.5, 2.0, (str(out / "scan.svg"),)),
    )
    failures = (BatchFailure("bad.png", str(src / "bad.png"), "not a readable image"),)
    inputs = (str(src / "my leaf.png"), str(src / "bad.png"), str(src / "scan.tif"))
    return BatchReport(rows, failures, inputs), out


def test_gallery_rows_numbers_and_relative_links(tmp_path):
    report, out = report_of(tmp_path)
    text = gallery_html(report, out)
    page = parse(text)
    assert page.scripts == 0 and "http" not in text  # nothing from the network
    # Every link is relative and names a file that exists, from the output folder.
    assert page.links
    for link in page.links:
        assert not link.startswith(("/", "file:")), link
        assert (out / unquote(link)).exists(), link
    assert "../in%20put/my%20leaf.png" in page.links and "my%20leaf.svg" in page.links
    # Input order; the numbers: arcs, E^s (2 decimals), levels, seconds (1 decimal).
    names = re.findall(r"<tr><td>([^<]+)", text)
    assert names == ["my leaf.png", "bad.png", "scan.tif"]
    assert '<td class="num">12</td><td class="num">1.23</td><td class="num">5</td><td class="num">0.6</td>' in text
    assert "failed: not a readable image" in text
    assert "not shown: browsers do not display .tif" in text  # a TIFF is named, not linked as a picture
    assert "<title>img2logo: 2 logos</title>" in text


def test_write_gallery_is_atomic(tmp_path, monkeypatch):
    report, out = report_of(tmp_path)
    path = write_gallery(report, out)
    assert path == out / GALLERY_NAME and path.read_text(encoding="utf-8").startswith("<!DOCTYPE html>")
    assert not [p for p in out.iterdir() if p.name.startswith(".")]  # no temporary file left


def test_a_batch_writes_its_gallery_with_the_summary(tmp_path):
    src = tmp_path / "in"
    src.mkdir()
    shutil.copy(DATA / "drawing-leaf.png", src / "leaf.png")
    (src / "broken.png").write_text("not a PNG")
    report = run_batch(sorted(src.iterdir()), tmp_path / "out", jobs=1, progress=False)
    page = (tmp_path / "out" / "index.html").read_text(encoding="utf-8")
    assert "leaf.png" in page and "failed:" in page and f"{report.rows[0].arcs}</td>" in page
    for link in parse(page).links:
        assert (tmp_path / "out" / unquote(link)).is_file(), link


def test_gallery_opens_offline_in_chromium(tmp_path):
    """The page, opened from disk with every network request refused, shows both pictures."""
    playwright = pytest.importorskip("playwright.sync_api")
    if not Path("/usr/bin/chromium").exists():
        pytest.skip("chromium is not installed (apt-get install chromium)")
    src = tmp_path / "in"
    src.mkdir()
    shutil.copy(DATA / "drawing-leaf.png", src / "leaf.png")
    run_batch([src / "leaf.png"], tmp_path / "out", jobs=1, progress=False)
    with playwright.sync_playwright() as p:
        browser = p.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
        try:
            page = browser.new_page(viewport={"width": 1366, "height": 768})
            asked: list[str] = []

            def refuse(route):
                asked.append(route.request.url)
                route.abort()

            page.route(re.compile(r"^(?!file:).*"), refuse)
            page.goto((tmp_path / "out" / "index.html").as_uri())
            page.wait_for_load_state("load")
            sizes = page.eval_on_selector_all("img", "els => els.map(e => [e.complete, e.naturalWidth])")
        finally:
            browser.close()
    assert asked == []
    assert len(sizes) == 2 and all(done and width > 0 for done, width in sizes)
