"""The studio (notebook 14) as its page: served by Voila as ``make studio`` serves it, driven by chromium.

``make test-browser`` runs it: the Voila command of ``make studio``
(:func:`img2logo.studio.serve.serve_command`) on a free port of 127.0.0.1 with its token, Debian's
chromium driven by playwright through its ``executable_path``, a 1366 x 768 window. The tests
share one page and run in order, as a designer would: the layout, the level, an arc deleted and
undone, a lock stroke painted and Run, an upload and Run, the downloads, a bad upload, the
subject of a photo. It skips, saying why, where chromium, playwright or Voila is missing.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import pytest
from browser_support import CHROMIUM, CHROMIUM_ARGS, start_studio

from img2logo.studio.serve import stop_server

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "data"
#: Seconds to wait for Voila to answer; ms for a step in the page (a Run on a loaded machine is slow).
START_TIMEOUT = 60.0
STEP_TIMEOUT_MS = 90_000
VIEWPORT = {"width": 1366, "height": 768}


def _requirements() -> str | None:
    if not Path(CHROMIUM).is_file():
        return f"no chromium at {CHROMIUM} (Debian: apt-get install chromium; or set IMG2LOGO_CHROMIUM)"
    for module in ("playwright", "voila", "ipycanvas"):
        try:
            __import__(module)
        except ImportError:
            return f"{module} is not installed (make test-browser installs the [browser] extra)"
    return None


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """``make studio``'s Voila on a free port with its token; stopped and reaped at the end."""
    reason = _requirements()
    if reason:
        pytest.skip(reason)
    folder = tmp_path_factory.mktemp("studio")
    try:
        studio = start_studio(folder, ROOT, START_TIMEOUT)
    except RuntimeError as e:
        pytest.fail(str(e))
    try:
        yield studio.url, folder, studio.log
    finally:
        stop_server(studio.process)


@pytest.fixture(scope="module")
def page(server):
    from playwright.sync_api import sync_playwright

    url, folder, log_path = server
    with sync_playwright() as p:
        browser = p.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)
        try:
            context = browser.new_context(viewport=VIEWPORT, accept_downloads=True)
            page = context.new_page()
            page.set_default_timeout(STEP_TIMEOUT_MS)
            page.goto(url)
            try:
                page.wait_for_selector(".img2logo-studio")
                _wait_status(page, "done:")
            except Exception:
                shot = Path(os.environ.get("IMG2LOGO_BROWSER_FAILURES", folder)) / "studio-failure.png"
                page.screenshot(path=str(shot))
                pytest.fail(f"the studio did not appear; the page is in {shot}, Voila's log in {log_path}")
            yield page
        finally:
            browser.close()


# --------------------------------------------------------------------------- helpers
def _status(page) -> str:
    return page.locator(".img2logo-studio .studio-status").first.inner_text()


def _title(page) -> str:
    return page.locator(".img2logo-studio .studio-title").first.inner_text()


def _wait_status(page, text: str) -> None:
    page.wait_for_function(
        "t => { const s = document.querySelector('.img2logo-studio .studio-status');"
        " return s && s.innerText.includes(t); }",
        arg=text,
    )


def _wait_title(page, text: str) -> None:
    page.wait_for_function(
        "t => document.querySelector('.img2logo-studio .studio-title').innerText.includes(t)",
        arg=text,
    )


def _canvas_box(page) -> dict:
    return page.locator(".img2logo-studio canvas").first.bounding_box()


def _logo_pixels(page) -> str:
    """The drawing's pixels (a data URL; ipycanvas composites its layers into one canvas), to see it change."""
    return page.evaluate("() => document.querySelector('.img2logo-studio canvas').toDataURL()")


def _to_screen(page, x: float, y: float, size: tuple[int, int]) -> tuple[float, float]:
    """Image pixel (x, y) of an image of ``size`` (w, h) to page coordinates (centred in the square drawing)."""
    box = _canvas_box(page)
    w, h = size
    k = box["width"] / max(w, h)
    return box["x"] + (box["width"] - w * k) / 2 + x * k, box["y"] + (box["height"] - h * k) / 2 + y * k


def _tool(page, name: str) -> None:
    page.locator(".img2logo-studio .widget-toggle-button", has_text=name).first.click()


def _click_button(page, name: str) -> None:
    page.locator(".img2logo-studio button", has_text=name).first.click()


def _upload(page, path: Path) -> None:
    """Choose ``path`` in the upload button's file dialog."""
    with page.expect_file_chooser() as chooser:
        page.locator(".img2logo-studio button", has_text="Upload image").first.click()
    chooser.value.set_files(str(path))


@pytest.fixture(scope="module")
def fish():
    """The run the page shows first (clipart-fish.png with the defaults), made here to find its arcs."""
    from img2logo.studio.session import Studio

    s = Studio("clipart-fish.png")
    assert s.run()
    return s


# --------------------------------------------------------------------------- the tests, in a designer's order
def test_the_page_fits_a_laptop_screen_with_a_large_drawing(page):
    box = _canvas_box(page)
    assert box["width"] >= 440 and box["height"] >= 440
    columns = page.locator(".img2logo-studio .widget-hbox").evaluate_all(
        "els => els.map(e => e.getBoundingClientRect()).map(r => [r.right, r.bottom])"
    )
    assert max(r for r, _ in columns) <= VIEWPORT["width"]
    assert max(b for _, b in columns) <= VIEWPORT["height"]
    sizes = page.locator(".img2logo-studio label, .img2logo-studio button, .img2logo-studio select").evaluate_all(
        "els => els.filter(e => e.offsetParent).map(e => parseFloat(getComputedStyle(e).fontSize))"
    )
    assert sizes and min(sizes) >= 12
    for name in ("Run", "Delete arc", "Connect", "Undo", "Download SVG", "Download JSON", "Download PNG"):
        assert page.locator(".img2logo-studio").get_by_text(name, exact=True).first.is_visible(), name


def test_moving_the_level_redraws_the_drawing(page):
    before = _logo_pixels(page)
    title = _title(page)
    n = int(title.split(" of ")[1].split(",")[0])
    handle = page.locator(".img2logo-studio .widget-slider", has_text="level t").locator(".noUi-handle").first
    handle.focus()
    handle.press("ArrowLeft")
    _wait_title(page, f"level t = {n - 1} of {n}")
    page.wait_for_function("old => document.querySelector('.img2logo-studio canvas').toDataURL() !== old", arg=before)
    handle.press("ArrowRight")
    _wait_title(page, f"level t = {n} of {n}")


def test_click_an_arc_delete_it_and_undo(page, fish):
    a = fish.shown
    i = max(range(len(a.arcs)), key=lambda j: a.arcs[j].length)
    points = a.arcs[i].sample(step=1.0)
    x, y = _to_screen(page, *points[len(points) // 2], (a.width, a.height))
    _tool(page, "Select")
    page.mouse.click(x, y)
    _wait_status(page, f"arc {i} selected")
    before = _logo_pixels(page)
    _click_button(page, "Delete arc")
    _wait_status(page, f"arc {i} deleted; {len(a.arcs) - 1} arcs")
    assert "1 edit" in _title(page)
    assert _logo_pixels(page) != before
    _click_button(page, "Undo")
    _wait_status(page, "edit undone")
    assert f"|A| = {len(a.arcs)}" in _title(page) and "edit" not in _title(page)


def test_paint_a_lock_stroke_and_run_again(page, fish):
    a = fish.shown
    i = max(range(len(a.arcs)), key=lambda j: a.arcs[j].length)
    points = a.arcs[i].sample(step=8.0)
    _tool(page, "Brush")
    before = _logo_pixels(page)
    page.mouse.move(*_to_screen(page, *points[0], (a.width, a.height)))
    page.mouse.down()
    for p in points[1:]:
        page.mouse.move(*_to_screen(page, *p, (a.width, a.height)))
    page.mouse.up()
    _wait_status(page, "lock mask:")
    assert _logo_pixels(page) != before  # the stroke is shown
    _click_button(page, "Run")
    _wait_status(page, "segments locked")
    _click_button(page, "Clear mask")
    _wait_status(page, "lock mask cleared")


@pytest.fixture(scope="module")
def uploaded(page, tmp_path_factory):
    """clipart-cat.png uploaded as my-cat.png, and Run."""
    folder = tmp_path_factory.mktemp("upload")
    path = folder / "my-cat.png"
    shutil.copy(DATA / "clipart-cat.png", path)
    _upload(page, path)
    _wait_status(page, "my-cat.png: 512x512 px; press Run")
    _click_button(page, "Run")
    _wait_status(page, "done:")
    return path


def test_upload_an_image_and_run(page, uploaded):
    assert _title(page).startswith("my-cat: level t = ")
    assert "error" not in _status(page)


def test_download_the_svg_and_json_of_the_logo_shown(page, uploaded, tmp_path):
    from img2logo import load_image
    from img2logo.export import writers
    from img2logo.export.contract import from_document

    files = {}
    for fmt in ("svg", "json", "png"):
        with page.expect_download() as info:
            page.locator(".img2logo-studio").get_by_text(f"Download {fmt.upper()}", exact=True).click()
        download = info.value
        assert download.suggested_filename == f"my-cat.{fmt}"
        target = tmp_path / download.suggested_filename
        download.save_as(target)
        files[fmt] = target.read_bytes()
    doc = json.loads(files["json"])
    logo = from_document(doc)  # a valid img2logo.abstraction document
    assert doc["format"].startswith("img2logo.abstraction")
    image = load_image(uploaded)
    assert (logo.width, logo.height) == (image.width, image.height)
    assert doc["params"]["source"] == "my-cat.png"
    assert f"|A| = {len(logo.arcs)}" in _title(page)
    assert files["svg"] == writers.to_svg(logo).encode("utf-8")  # the SVG of that very logo
    assert files["png"].startswith(b"\x89PNG")


def test_a_bad_upload_is_one_line_and_the_result_stays(page, uploaded, tmp_path):
    title = _title(page)
    bad = tmp_path / "notes.png"
    bad.write_text("not an image")
    _upload(page, bad)
    _wait_status(page, "error: notes.png: not a readable image")
    assert "\n" not in _status(page).strip() and "Traceback" not in page.inner_text("body")
    assert _title(page) == title


def test_drag_a_subject_rectangle_on_a_photo_and_run(page):
    page.locator(".img2logo-studio select").first.select_option("photo-cat.png")
    _wait_status(page, "photo-cat.png: 451x300 px; press Run")
    page.locator(".img2logo-studio .widget-dropdown", has_text="kind").locator("select").select_option("photo")
    _tool(page, "Subject")
    size = (451, 300)
    page.mouse.move(*_to_screen(page, 110, 70, size))
    page.mouse.down()
    page.mouse.move(*_to_screen(page, 220, 150, size))
    page.mouse.move(*_to_screen(page, 340, 230, size))
    page.mouse.up()
    _wait_status(page, "subject: x=")
    _click_button(page, "Run")
    _wait_status(page, "subject: kept the object in")
    assert _title(page).startswith("photo-cat: level t = ")
