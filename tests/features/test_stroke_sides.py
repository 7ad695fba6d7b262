"""Fills facing each other across a cartoon's outline stroke: known answers (features.stroke_sides, features.detail)."""

from __future__ import annotations

import cv2
import numpy as np
from helpers import blank

from img2logo import extract_feature_lines, load_image
from img2logo.features.clipart import clipart_regions
from img2logo.features.detail import merge_targets, outline_sides, region_adjacency
from img2logo.features.stroke_sides import across_strokes

ORANGE, YELLOW = (230, 120, 40), (240, 200, 60)


def _two_discs() -> np.ndarray:
    """Two coloured discs side by side inside one black outline 10 px wide, a stroke of it between them."""
    im = blank(300)
    for cx in (95, 205):
        cv2.circle(im, (cx, 150), 60, (0, 0, 0), -1, lineType=cv2.LINE_AA)
    for cx, colour in ((95, ORANGE), (205, YELLOW)):
        cv2.circle(im, (cx, 150), 50, colour, -1, lineType=cv2.LINE_AA)
    return im


def _lines_near(lines: np.ndarray, x: int, y: int, reach: int = 8) -> int:
    return int(lines[y - reach : y + reach + 1, x - reach : x + reach + 1].sum())


def test_fills_across_a_stroke_are_neighbours():
    img = load_image(_two_discs())
    regions = clipart_regions(img)
    left, right = int(regions[150, 95]), int(regions[150, 205])
    assert (min(left, right), max(left, right)) not in region_adjacency(regions)  # they touch only the outline
    sides = outline_sides(regions, img.lab)
    assert sides is not None
    target, _ = merge_targets(regions, img.lab, 1, sides=sides)
    assert target[left] == target[right]  # merged across the stroke


def test_under_an_arc_budget_merged_fills_lose_the_stroke_between_them_and_the_outline_stays():
    image = _two_discs()
    kept = extract_feature_lines(image)  # the default detail keeps both discs and the stroke between them
    assert kept.kind == "clipart"
    assert kept.regions[150, 95] != kept.regions[150, 205]
    assert _lines_near(kept.lines, 150, 150) > 0
    counted = extract_feature_lines(image, detail=1)  # the count alone keeps the outline as drawn
    assert counted.regions[150, 95] != counted.regions[150, 205]
    one = extract_feature_lines(image, detail=1, arcs=1)  # an arc budget merges across its strokes
    assert one.regions[150, 95] == one.regions[150, 205]  # one region
    assert _lines_near(one.lines, 150, 150, reach=20) == 0  # the stroke between them is no line
    for x, y in ((35, 150), (265, 150), (95, 90), (205, 210)):  # the silhouette, at the outline's outer edge
        assert _lines_near(one.lines, x, y) > 0, (x, y)


def test_fills_meeting_only_where_strokes_cross_are_no_neighbours():
    im = blank(300)
    cv2.rectangle(im, (40, 40), (260, 260), (0, 0, 0), -1)
    colours = ((230, 120, 40), (240, 200, 60), (60, 160, 220), (120, 200, 90))
    for k, colour in enumerate(colours):  # a 2 x 2 grid of squares, 10 px strokes between them
        x, y = 50 + 105 * (k % 2), 50 + 105 * (k // 2)
        cv2.rectangle(im, (x, y), (x + 94, y + 94), colour, -1)
    img = load_image(im)
    regions = clipart_regions(img)
    square = [int(regions[50 + 105 * (k // 2) + 47, 50 + 105 * (k % 2) + 47]) for k in range(4)]
    sides = outline_sides(regions, img.lab)
    assert sides is not None
    fixed = np.zeros(int(regions.max()) + 1, dtype=bool)
    fixed[0] = True
    fixed[int(regions[45, 150])] = True  # the outline
    border = across_strokes(sides, fixed, img.lab).border
    pairs = {tuple(sorted((square[a], square[b]))) for a, b in ((0, 1), (2, 3), (0, 2), (1, 3))}
    assert set(border) == pairs  # side by side across a stroke; the diagonal ones meet only at the crossing
    assert all(length >= 80 for length in border.values())
