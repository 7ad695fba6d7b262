"""The drawing's zoom and pan as the browser sends them (``zoom_pan.js``): the kernel's view is the truth.

The page is built without a browser (its widgets talk to no front end); what the browser would
receive is caught from :class:`~img2logo.studio.zoom_pan.ZoomPan`'s ``send``.
"""

from __future__ import annotations

import pytest

pytest.importorskip("ipycanvas")
pytest.importorskip("anywidget")

from img2logo.studio.drawing import ZOOM_STEP
from img2logo.studio.page import studio_page
from img2logo.studio.zoom_pan import operations


@pytest.fixture
def page(monkeypatch):
    """The studio page on clipart-fish.png, its messages to the browser kept in ``page.sent``."""
    p = studio_page("clipart-fish.png")
    p.sent = []
    monkeypatch.setattr(p.controls["zoom_pan"], "send", lambda content, buffers=None: p.sent.append(content))
    return p


def test_only_known_operations_with_finite_numbers_are_taken_in_order():
    ops = [
        ["zoom", 10, 20.5, 1.25],
        ["pan", 1, -2],
        ["zoom", 1, 2, 0],
        ["zoom", 1, 2, -1.25],
        ["pan", "1", 2],
        ["pan", True, 1],
        ["pan", float("nan"), 0],
        ["pan", 1, 2, 3],
        ["spin", 1],
        [],
        "pan",
    ]
    assert operations({"ops": ops}) == [("zoom", (10.0, 20.5, 1.25)), ("pan", (1.0, -2.0))]
    assert operations({"ops": "zoom"}) == [] and operations(None) == [] and operations({}) == []


def test_operations_sent_together_end_at_the_view_of_the_same_ones_sent_one_by_one(page):
    ops = [["zoom", 600, 400, ZOOM_STEP]] * 3 + [["pan", 12, -7]] * 4 + [["zoom", 100, 900, 1 / ZOOM_STEP]]
    ops += [["pan", -5000, 0]]  # against the edge: a pan keeps a quarter of the square in view
    for op in ops:
        page.operate(operations({"ops": [op]}))
    slow = (page.scale, page.offset)
    assert [m["answer"] for m in page.sent] == [True] * len(ops)
    page.fit_view()
    assert page.sent[-1]["answer"] is False and page.sent[-1]["view"] is None
    page.sent.clear()
    page.operate(operations({"ops": ops}))
    assert (page.scale, page.offset) == slow
    assert len(page.sent) == 1 and page.sent[0]["answer"] is True
    assert page.sent[0]["view"] == [page.scale, *page.offset] == page.controls["zoom_pan"].geometry["view"]
    assert page.offset[0] == pytest.approx(page.side / 4 - 512 * page.scale)
    assert page.controls["zoom"].value == f"{page.zoom:.0%}"


def test_a_wheel_notch_keeps_the_image_point_under_the_mouse_and_clicks_map_through_the_view(page):
    x, y = 300.0, 700.0
    before = page.to_image(x, y)
    page.operate(operations({"ops": [["zoom", x, y, ZOOM_STEP]]}))
    assert page.zoom == pytest.approx(ZOOM_STEP)
    assert page.to_image(x, y) == pytest.approx(before)
    page.operate(operations({"ops": [["pan", 40, -30]]}))
    assert page.to_image(x + 40, y - 30) == pytest.approx(before)


def test_a_message_with_nothing_valid_is_answered_with_the_view_unchanged(page):
    page.operate(operations({"ops": [["zoom", 1, 2, 1.25]]}))
    view = page.sent[-1]["view"]
    page.operate(operations({"ops": [["zoom", "x", 2, 1.25]]}))
    assert page.sent[-1] == {"view": view, "geometry": page.view_geometry(), "answer": True}


def test_zooming_out_past_the_whole_image_fits_it_and_a_fitted_image_does_not_pan(page):
    page.operate(operations({"ops": [["zoom", 100, 100, ZOOM_STEP], ["zoom", 500, 500, 1 / ZOOM_STEP**3]]}))
    assert page.sent[-1]["view"] is None and page.controls["zoom"].value == "fit"
    page.operate(operations({"ops": [["pan", 50, 50]]}))
    assert page.sent[-1]["view"] is None and page.offset == (0.0, 0.0)
