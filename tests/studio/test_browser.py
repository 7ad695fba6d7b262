"""The studio (notebook 14) as its page: served by Voila as ``make studio`` serves it, driven by chromium.

``make test-browser`` runs it: the Voila command of ``make studio``
(:func:`img2logo.studio.serve.serve_command`) on a free port of 127.0.0.1 with its token, Debian's
chromium driven by playwright through its ``executable_path``, a 1366 x 768 window. The tests
share one page and run in order, as a designer would: the layout, the level, an arc deleted and
undone, the keys, several arcs selected, a circle's centre dragged, the golden circles shown,
the input hidden, the labels, downloads that are always the level shown, a lock stroke painted
and Run, an upload that runs by itself (and again with the same file), the downloads, a bad
upload, the End key of the level slider, an input over 2048 px, the subject of a photo. It
skips, saying why, where chromium, playwright or Voila is missing.
"""

from __future__ import annotations

import json
import os
import shutil
from pathlib import Path

import numpy as np
import pytest
from browser_support import CHROMIUM, CHROMIUM_ARGS, skip_unless_installed, start_studio

from img2logo.studio.serve import stop_server

pytestmark = pytest.mark.browser

ROOT = Path(__file__).resolve().parents[2]
DATA = ROOT / "data"
#: Seconds to wait for Voila to answer; ms for a step in the page (a Run on a loaded machine is slow).
START_TIMEOUT = 60.0
STEP_TIMEOUT_MS = int(os.environ.get("IMG2LOGO_BROWSER_STEP_MS", "300000"))
VIEWPORT = {"width": 1366, "height": 768}


@pytest.fixture(scope="module")
def server(tmp_path_factory):
    """``make studio``'s Voila on a free port with its token; stopped and reaped at the end."""
    skip_unless_installed("playwright", "voila", "ipycanvas", chromium=True)
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


def _level(page) -> tuple[int, int]:
    """(t, last t) of the title ``name: level t of n, ...``."""
    words = _title(page).split(": level ", 1)[1].split(",")[0].split(" of ")
    return int(words[0]), int(words[1])


#: JS: the RGBA values of the (2 r + 1) px square of the drawing around page point (x, y), as composited on screen.
PIXELS = """([x, y, r]) => {
    const c = document.querySelector('.img2logo-studio canvas'); const box = c.getBoundingClientRect();
    const t = document.createElement('canvas'); t.width = c.width; t.height = c.height;
    const g = t.getContext('2d'); g.drawImage(c, 0, 0);
    const px = Math.round((x - box.left) * c.width / box.width), py = Math.round((y - box.top) * c.height / box.height);
    return Array.from(g.getImageData(px - r, py - r, 2 * r + 1, 2 * r + 1).data); }"""


def _pixel(page, x: float, y: float) -> list[int]:
    """The RGBA of the drawing at page point (x, y) (the layers as composited on screen)."""
    return page.evaluate(PIXELS, [x, y, 0])


def _wait_pixels(page, x: float, y: float, r: int, condition: str) -> None:
    """Wait until ``condition`` (JS on ``d``, the RGBA values around (x, y)) holds."""
    page.wait_for_function(f"a => {{ const d = ({PIXELS})(a); return {condition}; }}", arg=[x, y, r])


def _level_handle(page):
    return page.locator(".img2logo-studio .widget-slider", has_text="Level").locator(".noUi-handle").first


def _focus_drawing(page) -> None:
    """Give the drawing the keyboard (a click on its frame's corner, off the logo, selects nothing)."""
    box = _canvas_box(page)
    page.mouse.click(box["x"] + 2, box["y"] + 2)
    _wait_status(page, "nothing selected")


def _longest_arc(a) -> int:
    """The index of the longest arc of the logo ``a``."""
    return max(range(len(a.arcs)), key=lambda j: a.arcs[j].length)


def _middle_on_screen(page, a, arc) -> tuple[float, float]:
    """The middle of ``arc``, an arc on the logo ``a``, in page coordinates (the drawing fitted)."""
    points = arc.sample(step=1.0)
    return _to_screen(page, *points[len(points) // 2], (a.width, a.height))


def _select_arc(page, fish, i: int) -> None:
    page.mouse.click(*_middle_on_screen(page, fish.shown, fish.shown.arcs[i]))


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
    names = ("Run", "Delete arc", "Connect", "Undo", "Redo", "Golden circles", "SVG", "PDF", "PNG (white)")
    for name in (*names, "PNG (transparent)", "JSON"):
        assert page.locator(".img2logo-studio").get_by_text(name, exact=True).first.is_visible(), name


def test_moving_the_level_redraws_the_drawing(page):
    before = _logo_pixels(page)
    _, n = _level(page)
    handle = _level_handle(page)
    handle.focus()
    handle.press("ArrowLeft")
    _wait_title(page, f"level {n - 1} of {n}")
    page.wait_for_function("old => document.querySelector('.img2logo-studio canvas').toDataURL() !== old", arg=before)
    handle.press("ArrowRight")
    _wait_title(page, f"level {n} of {n}")


def test_click_an_arc_delete_it_and_undo(page, fish):
    a = fish.shown
    i = _longest_arc(a)
    x, y = _middle_on_screen(page, a, a.arcs[i])
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
    assert f", {len(a.arcs)} arcs," in _title(page) and "edit" not in _title(page)


def test_the_keys_undo_redo_delete_and_nudge(page, fish):
    a = fish.shown
    i = _longest_arc(a)
    _select_arc(page, fish, i)
    _wait_status(page, f"arc {i} selected")
    page.keyboard.press("Delete")
    _wait_status(page, f"arc {i} deleted; {len(a.arcs) - 1} arcs")
    page.keyboard.press("Control+z")
    _wait_status(page, "edit undone")
    page.keyboard.press("Control+Shift+Z")
    _wait_status(page, "edit redone")
    assert f", {len(a.arcs) - 1} arcs," in _title(page)
    page.keyboard.press("Control+z")
    _wait_status(page, "edit undone")
    _select_arc(page, fish, i)
    _wait_status(page, f"arc {i} selected")
    page.keyboard.press("ArrowRight")
    _wait_status(page, f"circle of arc {i} moved by (2, 0) px")
    page.keyboard.press("Shift+ArrowUp")
    _wait_status(page, f"circle of arc {i} moved by (0, -20) px")
    assert "2 edits" in _title(page)
    page.keyboard.press("Control+z")
    page.keyboard.press("Control+z")
    _wait_title(page, f", {len(a.arcs)} arcs,")
    page.wait_for_function("() => !document.querySelector('.img2logo-studio .studio-title').innerText.includes('edit')")


def test_shift_click_selects_several_arcs_and_delete_removes_them(page, fish):
    a = fish.shown
    longest = sorted(range(len(a.arcs)), key=lambda j: -a.arcs[j].length)[:3]
    _focus_drawing(page)
    for i in longest:
        page.keyboard.down("Shift")
        _select_arc(page, fish, i)
        page.keyboard.up("Shift")
        _wait_status(page, f"{longest.index(i) + 1} arc")
    _wait_status(page, f"3 arcs selected: {', '.join(map(str, longest))}")
    page.keyboard.press("Delete")
    _wait_status(page, f"; {len(a.arcs) - 3} arcs")
    assert "1 edit" in _title(page)
    _click_button(page, "Undo")
    _wait_status(page, "edit undone")


def test_drag_the_selected_circles_centre_to_move_it(page, fish):
    a = fish.shown
    i = max((j for j in range(len(a.arcs)) if not a.arcs[j].is_line), key=lambda j: a.arcs[j].length)
    c = a.arcs[i].circle
    _select_arc(page, fish, i)
    _wait_status(page, f"arc {i} selected")
    x, y = _to_screen(page, c.cx, c.cy, (a.width, a.height))
    assert _pixel(page, x, y)[:3] == [0x1F, 0x6F, 0xD1]  # the centre is drawn, in the selection's colour
    before = _logo_pixels(page)
    page.mouse.move(x, y)
    page.mouse.down()
    for step in range(1, 6):
        page.mouse.move(x + 4 * step, y + 2 * step)
    page.mouse.up()
    _wait_status(page, f"circle of arc {i} moved by (")
    assert "1 edit" in _title(page) and _logo_pixels(page) != before
    _click_button(page, "Undo")
    _wait_status(page, "edit undone")


def test_the_golden_circles_are_shown_and_the_input_hidden(page, fish):
    a = fish.shown
    # A point on a golden circle away from every arc: the circles layer draws it.
    far = None
    for arc in a.arcs:
        if arc.is_line:
            continue
        c = arc.circle
        for t in np.linspace(0.0, 2.0 * np.pi, 72, endpoint=False):
            q = np.array([c.cx + c.r * np.cos(t), c.cy + c.r * np.sin(t)])
            inside = 8 < q[0] < a.width - 8 and 8 < q[1] < a.height - 8
            if inside and min(np.hypot(*(s.sample(step=1.0) - q).T).min() for s in a.arcs) > 12:
                far = q
                break
        if far is not None:
            break
    assert far is not None
    x, y = _to_screen(page, *far, (a.width, a.height))
    _click_button(page, "Hidden")
    _wait_pixels(page, x, y, 0, "d[0] === 255 && d[1] === 255 && d[2] === 255")  # white: no input under it
    page.locator(".img2logo-studio").get_by_text("Golden circles", exact=True).click()
    _wait_pixels(page, x, y, 2, "d.some((v, i) => i % 4 === 2 && v < 200)")  # the circle's gold is there
    page.locator(".img2logo-studio").get_by_text("Golden circles", exact=True).click()
    _click_button(page, "Faded")


def test_add_the_other_side_of_a_selected_arcs_circle(page, fish):
    a = fish.shown
    i = next(
        j
        for j in sorted(range(len(a.arcs)), key=lambda j: -a.arcs[j].length)
        if not a.arcs[j].is_line and None not in (a.arc_junctions[j].start, a.arc_junctions[j].end)
    )
    _select_arc(page, fish, i)
    _wait_status(page, f"arc {i} selected")
    _click_button(page, "Add other side")
    _wait_status(page, f"the other side of arc {i}'s circle added; {len(a.arcs) + 1} arcs")
    _click_button(page, "Undo")
    _wait_status(page, "edit undone")


def test_only_some_circle_sizes(page, fish):
    ks = sorted({c.k for c in fish.levels[0].golden_circles})[-4:]
    sizes = page.locator(".img2logo-studio .widget-text", has_text="Only circle sizes").locator("input")
    sizes.fill(", ".join(map(str, ks)))
    _click_button(page, "Run")
    _wait_status(page, "done:")
    with page.expect_download() as info:
        page.locator(".img2logo-studio a.studio-download", has_text="JSON").first.click()
    doc = json.loads(Path(info.value.path()).read_text())
    assert {c["k"] for c in doc["circles"] if c.get("k") is not None} <= set(ks)
    sizes.fill("")
    _click_button(page, "Delete arc")  # nothing selected: a line that is not "done:", to wait for the Run's
    _wait_status(page, "error: select an arc first")
    _click_button(page, "Run")
    _wait_status(page, "done:")


def test_click_a_region_to_give_it_its_own_colour(page, fish):
    import shapely

    from img2logo.studio.controls import FILL_PRESETS
    from img2logo.studio.session import Studio

    s = Studio("clipart-fish.png")
    s.result, s.levels, s.level = fish.result, fish.levels, fish.level
    assert s.set_fill(FILL_PRESETS["palette"]), s.message
    fills = s.fills()
    order = sorted(range(len(fills)), key=lambda j: -shapely.Polygon(fills[j].rings()[0]).area)
    point = next(
        p
        for j in order
        for p in [np.array(shapely.Polygon(fills[j].rings()[0]).representative_point().coords[0])]
        if s.region_at(*p) == j
    )
    a = fish.shown
    fills_menu = page.locator(".img2logo-studio .widget-dropdown", has_text="Fills").locator("select")
    fills_menu.select_option("palette")
    _wait_status(page, "regions")
    _tool(page, "Colour")
    page.locator(".img2logo-studio input[type=color]").first.fill("#ff0000")
    x, y = _to_screen(page, *point, (a.width, a.height))
    page.mouse.click(x, y)
    _wait_status(page, ": #ff0000")
    _wait_pixels(page, x, y, 0, "d[0] > 200 && d[1] < 80 && d[2] < 80")
    fills_menu.select_option("none")
    _wait_status(page, "no fill")
    _tool(page, "Select")


def test_the_wheel_zooms_the_hand_pans_and_fit_comes_back(page):
    box = _canvas_box(page)
    zoom = page.locator(".img2logo-studio .widget-label", has_text="fit").first
    centre = (box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    before = _logo_pixels(page)
    page.mouse.move(*centre)
    page.mouse.wheel(0, -100)
    page.wait_for_function(
        "() => [...document.querySelectorAll('.img2logo-studio .widget-label')].some(e => e.innerText === '125%')"
    )
    page.wait_for_function("old => document.querySelector('.img2logo-studio canvas').toDataURL() !== old", arg=before)
    _tool(page, "Hand")
    zoomed = _logo_pixels(page)
    page.mouse.move(*centre)
    page.mouse.down()
    page.mouse.move(centre[0] + 40, centre[1] + 30)
    page.mouse.up()
    page.wait_for_function("old => document.querySelector('.img2logo-studio canvas').toDataURL() !== old", arg=zoomed)
    _click_button(page, "Fit")
    page.wait_for_function("old => document.querySelector('.img2logo-studio canvas').toDataURL() === old", arg=before)
    assert zoom.inner_text() == "fit"
    _tool(page, "Select")


def test_space_held_pans_the_zoomed_drawing_with_any_tool(page):
    _tool(page, "Select")
    _focus_drawing(page)
    box = _canvas_box(page)
    centre = (box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
    before = _logo_pixels(page)
    page.mouse.move(*centre)
    page.mouse.wheel(0, -100)
    page.wait_for_function("old => document.querySelector('.img2logo-studio canvas').toDataURL() !== old", arg=before)
    zoomed = _logo_pixels(page)
    page.keyboard.down(" ")
    page.mouse.down()
    page.mouse.move(centre[0] + 40, centre[1] + 30, steps=4)
    page.mouse.up()
    page.keyboard.up(" ")
    page.wait_for_function("old => document.querySelector('.img2logo-studio canvas').toDataURL() !== old", arg=zoomed)
    assert "selected:" not in _status(page)  # the drag panned: it selected nothing
    # Space released (no press since): a drag with Select is a click again, not a pan.
    page.wait_for_timeout(800)
    panned = _logo_pixels(page)
    page.mouse.move(box["x"] + 3, box["y"] + 3)
    page.mouse.down()
    page.mouse.move(box["x"] + 30, box["y"] + 20, steps=3)
    page.mouse.up()
    _wait_status(page, "nothing selected")
    assert _logo_pixels(page) == panned
    _click_button(page, "Fit")
    page.wait_for_function("old => document.querySelector('.img2logo-studio canvas').toDataURL() === old", arg=before)


def _wait_exact(page, zoom: str) -> None:
    """Wait until the drawing on screen is the kernel's own drawing of the view shown, at ``zoom`` (the label)."""
    page.wait_for_function(
        "z => document.querySelector('.img2logo-studio canvas').dataset.view === 'exact' &&"
        " [...document.querySelectorAll('.img2logo-studio .widget-label')].some(e => e.innerText === z)",
        arg=zoom,
    )


#: JS on ``d`` (the RGBA values around a point): some pixel is the arcs' black.
DARK = "d.some((v, i) => i % 4 === 0 && v < 60 && d[i + 1] < 60 && d[i + 2] < 60)"


def test_a_wheel_notch_zooms_about_the_mouse_and_a_click_after_a_pan_selects_the_arc_under_it(page, fish):
    from img2logo.studio.drawing import ZOOM_STEP

    a = fish.shown
    i = _longest_arc(a)
    x, y = _middle_on_screen(page, a, a.arcs[i])
    _tool(page, "Select")
    _click_button(page, "Hidden")  # the arcs alone on white
    box = _canvas_box(page)
    mouse = (box["x"] + 0.3 * box["width"], box["y"] + 0.6 * box["height"])  # off the centre
    page.mouse.move(*mouse)
    page.mouse.wheel(0, -100)
    _wait_exact(page, f"{ZOOM_STEP:.0%}")
    # About the mouse: the point under it stays, the arc's point goes ZOOM_STEP times as far from it.
    x, y = mouse[0] + (x - mouse[0]) * ZOOM_STEP, mouse[1] + (y - mouse[1]) * ZOOM_STEP
    _wait_pixels(page, x, y, 2, DARK)
    _tool(page, "Hand")
    page.mouse.move(*mouse)
    page.mouse.down()
    page.mouse.move(mouse[0] + 36, mouse[1] - 24, steps=4)
    page.mouse.up()
    x, y = x + 36, y - 24
    _wait_pixels(page, x, y, 2, DARK)
    _wait_exact(page, f"{ZOOM_STEP:.0%}")
    _tool(page, "Select")
    page.mouse.click(x, y)  # the kernel's view is the one on screen: the click finds the arc
    _wait_status(page, f"arc {i} selected")
    page.keyboard.press("Escape")
    _wait_status(page, "nothing selected")
    _click_button(page, "Fit")
    _wait_exact(page, "fit")
    _click_button(page, "Faded")


def test_quick_wheel_notches_and_pan_moves_end_at_the_view_of_slow_ones(page):
    """Notches and moves that come while the kernel draws go to it together: the same view, the same drawing."""
    box = _canvas_box(page)
    mouse = (box["x"] + 0.6 * box["width"], box["y"] + 0.45 * box["height"])
    _tool(page, "Select")

    def gesture(slow: bool) -> str:
        _focus_drawing(page)  # Space to the drawing
        page.mouse.move(*mouse)
        for n in range(1, 5):
            page.mouse.wheel(0, -100)
            if slow:
                _wait_exact(page, f"{1.25**n:.0%}")
        page.keyboard.down(" ")
        page.mouse.down()
        for step in range(1, 7):
            page.mouse.move(mouse[0] - 9 * step, mouse[1] + 5 * step)
            if slow:
                page.wait_for_function(
                    "() => document.querySelector('.img2logo-studio canvas').dataset.view === 'exact'"
                )
        page.mouse.up()
        page.keyboard.up(" ")
        _wait_exact(page, f"{1.25**4:.0%}")
        return _logo_pixels(page)

    slow = gesture(slow=True)
    _click_button(page, "Fit")
    _wait_exact(page, "fit")
    quick = gesture(slow=False)
    assert quick == slow
    _click_button(page, "Fit")
    _wait_exact(page, "fit")


def test_click_two_free_ends_and_add_an_arc_on_a_chosen_circle(page, fish):
    from img2logo.studio.session import Studio

    a = fish.shown
    i = _longest_arc(a)
    # The same edits in Python: the free ends the deletion leaves, and the arcs that would join two of them.
    s = Studio("clipart-fish.png")
    s.result, s.levels, s.level, s.selected = fish.result, fish.levels, fish.level, [i]
    assert s.delete_selected(), s.message
    b = s.shown
    ends = s.free_end_junctions()
    assert len(ends) >= 2
    j0, j1 = ends[0], ends[-1]  # any two, not a pair the page offers
    _select_arc(page, fish, i)
    _wait_status(page, f"arc {i} selected")
    page.keyboard.press("Delete")
    _wait_status(page, f"arc {i} deleted")
    for j in (j0, j1):
        page.mouse.click(*_to_screen(page, *b.junctions[j], (a.width, a.height)))
        s.select_end_at(*b.junctions[j], 1.0)
    _wait_status(page, f"free ends {j0} and {j1} chosen")
    _click_button(page, "Other circle")
    _wait_status(page, "(option 2 of")
    s.other_end_circle()
    arc = s.end_arc()
    assert arc is not None
    x, y = _middle_on_screen(page, a, arc)
    _wait_pixels(page, x, y, 2, "d.some((v, i) => i % 4 === 0 && v > 180 && d[i + 1] < 120 && d[i + 2] < 90)")
    _click_button(page, "Add arc")
    _wait_status(page, f"arc added between free ends {j0} and {j1}; {len(b.arcs) + 1} arcs")
    assert "2 edits" in _title(page)
    with page.expect_download() as info:
        page.locator(".img2logo-studio a.studio-download", has_text="JSON").first.click()
    doc = json.loads(Path(info.value.path()).read_text())
    assert len(doc["arcs"]) == len(b.arcs) + 1
    for _ in range(2):
        _click_button(page, "Undo")
        _wait_status(page, "edit undone")


def test_the_labels_are_a_designers_words_with_the_papers_symbol_in_a_tooltip(page):
    box = page.locator(".img2logo-studio")
    for label, symbol in (
        ("Tolerance (px)", "T:"),
        ("Circle size offset", "\u03c3"),
        ("Simplify lines (px)", "Ramer-Douglas-Peucker"),
        ("Level", "A^t"),
        ("Detail", "--detail"),
    ):
        widget = box.locator(".widget-slider", has_text=label).first
        assert widget.is_visible(), label
        titles = widget.evaluate("e => [e, ...e.querySelectorAll('[title]')].map(x => x.title).join(' ')")
        assert symbol in titles, (label, titles)
    assert "E^s" in box.locator(".studio-title b").first.get_attribute("title")
    assert "error " in _title(page) and "tolerance " in _title(page) and "|A|" not in _title(page)


def test_a_download_is_always_the_level_shown(page):
    """With a slow fill the files are made after the drawing: until then there is no link to click."""
    fills = page.locator(".img2logo-studio .widget-dropdown", has_text="Fills").locator("select")
    fills.select_option("gradient")
    _wait_status(page, "regions")
    page.evaluate("() => { window.__stale = []; }")
    watch = """() => { const t = document.querySelector('.img2logo-studio .studio-title').innerText;
        const level = Number(t.split(': level ')[1].split(' of ')[0]);
        const a = document.querySelector('.img2logo-studio a.studio-download[download$=".json"]');
        if (!a) return false;
        const doc = JSON.parse(atob(a.href.split(',')[1]));
        if (doc.level !== level) { window.__stale.push([doc.level, level]); return false; }
        return true; }"""
    handle = _level_handle(page)
    for key in ("ArrowLeft", "ArrowLeft", "ArrowRight", "ArrowRight"):
        t, _ = _level(page)
        handle.focus()
        handle.press(key)
        _wait_title(page, f"level {t + (1 if key == 'ArrowRight' else -1)} of")
        page.wait_for_function(watch, polling="raf")
    assert page.evaluate("() => window.__stale") == []
    fills.select_option("none")
    _wait_status(page, "no fill")


def test_paint_a_lock_stroke_and_run_again(page, fish):
    a = fish.shown
    i = _longest_arc(a)
    points = a.arcs[i].sample(step=8.0)
    _tool(page, "Brush")
    before = _logo_pixels(page)
    page.mouse.move(*_to_screen(page, *points[0], (a.width, a.height)))
    page.mouse.down()
    for p in points[1:]:
        page.mouse.move(*_to_screen(page, *p, (a.width, a.height)))
    page.mouse.up()
    _wait_status(page, "lock mask:")
    _wait_status(page, "the next Run locks")  # the segments under the stroke, highlighted before Run
    assert _logo_pixels(page) != before  # the stroke is shown
    _click_button(page, "Run")
    _wait_status(page, "segments locked")
    _click_button(page, "Clear mask")
    _wait_status(page, "lock mask cleared")


def _run_if_asked(page) -> None:
    """Press Run when the page asks for it (an upload runs by itself: then this waits for its result)."""
    page.wait_for_function(
        "() => { const s = document.querySelector('.img2logo-studio .studio-status').innerText;"
        " return s.includes('press Run') || s.startsWith('done:') || s.startsWith('error'); }"
    )
    if "press Run" in _status(page):
        _click_button(page, "Run")
    _wait_status(page, "done:")


@pytest.fixture(scope="module")
def uploaded(page, tmp_path_factory):
    """clipart-cat.png uploaded as my-cat.png: it runs by itself."""
    folder = tmp_path_factory.mktemp("upload")
    path = folder / "my-cat.png"
    shutil.copy(DATA / "clipart-cat.png", path)
    _upload(page, path)
    _wait_title(page, "my-cat: level ")
    _wait_status(page, "done:")
    return path


def test_an_upload_runs_by_itself(page, uploaded):
    assert _title(page).startswith("my-cat: level ")
    assert "error" not in _status(page)


def test_the_same_file_uploaded_again_is_read_again(page, uploaded):
    _click_button(page, "Delete arc")  # nothing selected: the page says so, the logo stays
    _wait_status(page, "error: select an arc first")
    _upload(page, uploaded)
    _wait_status(page, "done:")
    assert _title(page).startswith("my-cat: level ")


def test_download_the_svg_and_json_of_the_logo_shown(page, uploaded, tmp_path):
    from img2logo import load_image
    from img2logo.export import writers
    from img2logo.export.contract import from_document

    files = {}
    t, _ = _level(page)
    links = {
        "svg": ("SVG", f"my-cat-level{t}.svg"),
        "json": ("JSON", f"my-cat-level{t}.json"),
        "pdf": ("PDF", f"my-cat-level{t}.pdf"),
        "png": ("PNG (white)", f"my-cat-level{t}.png"),
        "png-transparent": ("PNG (transparent)", f"my-cat-level{t}-transparent.png"),
    }
    for fmt, (label, name) in links.items():
        with page.expect_download() as info:
            page.locator(".img2logo-studio a.studio-download", has_text=label).first.click()
        download = info.value
        assert download.suggested_filename == name
        target = tmp_path / download.suggested_filename
        download.save_as(target)
        files[fmt] = target.read_bytes()
    doc = json.loads(files["json"])
    logo = from_document(doc)  # a valid img2logo.abstraction document
    assert doc["format"].startswith("img2logo.abstraction")
    image = load_image(uploaded)
    assert (logo.width, logo.height) == (image.width, image.height)
    assert doc["params"]["source"] == "my-cat.png"
    assert f", {len(logo.arcs)} arcs," in _title(page)
    assert files["svg"] == writers.to_svg(logo).encode("utf-8")  # the SVG of that very logo
    assert files["pdf"].startswith(b"%PDF")
    from io import BytesIO

    from PIL import Image

    white, clear = (Image.open(BytesIO(files[f])) for f in ("png", "png-transparent"))
    assert white.size == clear.size == (image.width, image.height)
    assert white.getpixel((0, 0))[:3] == (255, 255, 255) and clear.getpixel((0, 0))[3] == 0


def test_a_bad_upload_is_one_line_and_the_result_stays(page, uploaded, tmp_path):
    title = _title(page)
    bad = tmp_path / "notes.png"
    bad.write_text("not an image")
    _upload(page, bad)
    _wait_status(page, "error: notes.png: not a readable image")
    assert "\n" not in _status(page).strip() and "Traceback" not in page.inner_text("body")
    assert _title(page) == title


def test_an_upload_over_10_mb_is_refused_in_one_line(page):
    from img2logo.studio.session import MAX_UPLOAD_BYTES

    title = _title(page)
    size = 11 * 2**20  # over Tornado's default websocket message cap of 10 MiB
    with page.expect_file_chooser() as chooser:
        page.locator(".img2logo-studio button", has_text="Upload image").first.click()
    chooser.value.set_files({"name": "huge.png", "mimeType": "image/png", "buffer": b"\x89PNG" + bytes(size - 4)})
    _wait_status(page, f"error: huge.png: the file has {size} bytes, more than the studio takes ({MAX_UPLOAD_BYTES})")
    assert _title(page) == title


def test_a_long_name_is_shown_cut(page):
    name = "a-very-long-name-" * 20 + ".png"
    with page.expect_file_chooser() as chooser:
        page.locator(".img2logo-studio button", has_text="Upload image").first.click()
    chooser.value.set_files({"name": name, "mimeType": "image/png", "buffer": (DATA / "clipart-cat.png").read_bytes()})
    from img2logo.studio.session import MAX_NAME_CHARS

    _wait_title(page, name[: MAX_NAME_CHARS - len(".png")] + ": level")
    _wait_status(page, "done:")


def test_the_end_key_goes_to_the_last_level_of_the_image_shown(page):
    """After runs with fewer and then more levels than the first one shown, End is this run's last level."""
    for name in ("drawing-fish", "clipart-cat"):
        page.locator(".img2logo-studio select").first.select_option(f"{name}.png")
        _wait_title(page, f"{name}: level")
        _run_if_asked(page)
    _, n = _level(page)
    handle = _level_handle(page)
    handle.focus()
    handle.press("Home")
    _wait_title(page, f"level 0 of {n}")
    handle.press("End")
    _wait_title(page, f"level {n} of {n}")
    page.wait_for_timeout(500)
    assert _level(page) == (n, n)


def test_an_input_over_2048_px_shows_its_logo_in_one_unit(page, tmp_path):
    import cv2

    big = tmp_path / "big-fish.png"
    rgb = cv2.imread(str(DATA / "clipart-fish.png"))
    cv2.imwrite(str(big), cv2.resize(rgb, (2600, 2600), interpolation=cv2.INTER_NEAREST))
    _upload(page, big)
    _wait_title(page, "big-fish")
    _run_if_asked(page)
    title = _title(page)
    error = float(title.split("error ")[1].split(" px")[0])
    tolerance = float(title.split("(tolerance ")[1].split(" px")[0])
    assert error <= tolerance and "working copy" in title, title
    from img2logo.studio.session import Studio

    s = Studio(str(big))
    assert s.run(), s.message
    a = s.shown
    i = _longest_arc(a)
    x, y = _middle_on_screen(page, a, a.arcs[i])
    _wait_pixels(page, x, y, 2, DARK)  # the logo is drawn there (once the kernel's drawing has arrived)
    _tool(page, "Select")
    page.mouse.click(x, y)
    _wait_status(page, f"arc {i} selected")


def test_drag_a_subject_rectangle_on_a_photo_and_run(page):
    page.locator(".img2logo-studio select").first.select_option("photo-cat.png")
    _wait_title(page, "photo-cat: level")
    _wait_status(page, "done:")
    page.locator(".img2logo-studio .widget-dropdown", has_text="Image type").locator("select").select_option("photo")
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
    assert _title(page).startswith("photo-cat: level ")
