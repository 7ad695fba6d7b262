"""Tests of img2logo.features.detail.close_line_ends: a clip art's lines whole, each end joined or its mark dropped."""

from __future__ import annotations

import warnings

import cv2
import numpy as np
import pytest
from helpers import DATA, blank

from img2logo import build_segment_graph, extract_feature_lines, load_image
from img2logo.features.detail import close_line_ends
from img2logo.images.skeleton import classify

OPENCLIPART = DATA.parent / "benchmarks" / "data" / "openclipart"


def _ends(lines: np.ndarray) -> np.ndarray:
    """(row, col) of the line ends of a 1-px map: pixels with one 8-neighbour on the line."""
    return np.argwhere(lines & (classify(lines)[1] == 1))


def _disc_with_mark(mark_end: tuple[int, int]) -> np.ndarray:
    """An orange disc 70 px round with a dark 3 px stroke from its middle to ``mark_end``."""
    im = blank(200)
    cv2.circle(im, (100, 100), 70, (230, 120, 40), -1, lineType=cv2.LINE_AA)
    cv2.line(im, (100, 100), mark_end, (60, 30, 10), 3, lineType=cv2.LINE_AA)
    return im


# --------------------------------------------------------------------------- known answers
@pytest.mark.parametrize("end", [164, 170])
def test_a_stroke_that_stops_short_of_the_outline_is_joined_to_it(end):
    # The stroke stops 6 px inside the disc's edge (x = 170), or meets it; its centre line stops 13 px
    # short (the outline's pixels near the silhouette are the silhouette's line): it is joined to it.
    lines = extract_feature_lines(_disc_with_mark((end, 100))).lines
    assert lines[97:104, 150:171].any(axis=0).all()  # the line runs on to the outline
    assert len(_ends(lines)) == 1  # the stroke's other end, 61 px from the outline, is its only end


def _map_and_regions(branch: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A disc's outline and a 40 px mark inside it, as a line map, its regions and their colours."""
    paint = np.zeros((120, 120), dtype=np.uint8)
    cv2.circle(paint, (60, 60), 45, 1, -1)
    cv2.line(paint, (40, 60), (80, 60), 2, 3)  # the mark's ink, region 2, 3 px wide
    regions = paint.astype(np.int64)
    lab = np.zeros((120, 120, 3))
    lab[regions == 1] = (60.0, 40.0, 60.0)
    lab[regions == 2] = (30.0, 30.0, 40.0)
    lines = np.zeros((120, 120), dtype=np.uint8)
    cv2.circle(lines, (60, 60), 45, 1, 1)
    cv2.line(lines, (40 if not branch else 15, 60), (80, 60), 1, 1)  # a branch runs on to the outline
    return lines.astype(bool), regions, lab


@pytest.mark.parametrize("branch", [False, True])
def test_a_mark_lighter_than_the_budget_is_dropped_whole(branch):
    lines, regions, lab = _map_and_regions(branch)
    assert len(_ends(lines)) == (1 if branch else 2)
    # The mark's Ward weight: about 3 x 41 px of ink times (30^2 + 10^2 + 20^2) squared Delta E, about 1.7e5.
    light = close_line_ends(lines, regions, lab, budget=1e6)
    assert len(_ends(light)) == 0
    assert not light[58:63, 40:80].any()  # no piece of the mark is left
    assert light[60, 105] and light[15, 60]  # the outline is whole
    heavy = close_line_ends(lines, regions, lab, budget=1e4)
    assert np.array_equal(heavy, lines)  # as weighty as the regions kept: kept as it is
    assert np.array_equal(close_line_ends(lines, regions, lab, budget=0.0), lines)  # nothing was merged


def test_an_end_at_the_image_frame_is_left_alone():
    regions = np.zeros((80, 80), dtype=np.int64)
    regions[:, 40:] = 1  # a fill that runs off the picture
    lab = np.zeros((80, 80, 3))
    lab[regions == 1] = (50.0, 0.0, 0.0)
    lines = np.zeros((80, 80), dtype=bool)
    lines[1:79, 40] = True  # its boundary, from frame to frame
    assert np.array_equal(close_line_ends(lines, regions, lab, budget=1e12), lines)


# --------------------------------------------------------------------------- real clip art
@pytest.mark.parametrize(
    ("name", "most"),
    [
        ("clipart-gallo.png", 3),
        ("clipart-tramway.png", 3),
        ("clipart-simbolo.png", 3),
        ("clipart-farfalla.png", 4),
        ("clipart-beagle.png", 6),
    ],
)
def test_real_clip_art_has_few_line_ends(name, most):
    # Before, these had 20, 8, 8, 9 and 14 line ends (nodes of valence 1 of the segment graph): broken
    # outlines. The beagle keeps its eye's and ear's black strokes, as weighty as the boundaries kept.
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        lines = extract_feature_lines(load_image(OPENCLIPART / name))
    assert lines.kind == "clipart"
    graph = build_segment_graph(lines)
    assert np.count_nonzero(graph.valence == 1) <= most


def test_a_mark_on_the_paper_is_part_of_the_silhouette_and_kept():
    # A whisker on the paper beside a disc: the fill it lies on is the background, whatever the budget.
    lines, regions, lab = _paper_mark()
    assert len(_ends(lines)) == 1
    assert np.array_equal(close_line_ends(lines, regions, lab, budget=1e12), lines)


def _paper_mark() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A disc's outline and a 30 px whisker on the paper beside it: line map, regions, colours."""
    paint = np.zeros((120, 120), dtype=np.uint8)
    cv2.circle(paint, (50, 60), 30, 1, -1)
    cv2.line(paint, (80, 60), (110, 60), 2, 3)
    lab = np.zeros((120, 120, 3))
    lab[paint == 0] = (100.0, 0.0, 0.0)
    lab[paint == 1] = (60.0, 40.0, 60.0)
    lab[paint == 2] = (10.0, 5.0, 5.0)
    lines = np.zeros((120, 120), dtype=np.uint8)
    cv2.circle(lines, (50, 60), 30, 1, 1)
    cv2.line(lines, (80, 60), (110, 60), 1, 1)
    return lines.astype(bool), paint.astype(np.int64), lab
