"""The arc budget of a clip art's inner lines: known answers (features.boundary_cost, features.detail)."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from helpers import blank

from img2logo import InvalidParameterError, Options, abstract, load_image
from img2logo.features.boundary_cost import ARC_CHORDS, boundary_arcs
from img2logo.features.clipart import clipart_regions
from img2logo.features.detail import merge_by_importance

GREEN, LIGHT_GREEN = (60, 160, 60), (150, 220, 120)


def _wiggly(im: np.ndarray, cx: int, cy: int, radius: float, colour: tuple[int, int, int], lobes: int = 12) -> None:
    """A filled blob whose outline wiggles (``lobes`` bumps of a fifth of its radius): many arcs for its area."""
    t = np.linspace(0, 2 * np.pi, 400, endpoint=False)
    r = radius * (1 + 0.2 * np.sin(lobes * t))
    pts = np.stack([cx + r * np.cos(t), cy + r * np.sin(t)], axis=1).round().astype(np.int32)
    cv2.fillPoly(im, [pts], colour, lineType=cv2.LINE_AA)


def _square_with(blobs: int, wiggly: bool) -> np.ndarray:
    im = blank(400)
    cv2.rectangle(im, (30, 30), (370, 370), GREEN, -1)
    for k in range(blobs):
        cx, cy = 90 + 110 * (k % 3), 90 + 110 * (k // 3)
        if wiggly:
            _wiggly(im, cx, cy, 35, LIGHT_GREEN)
        else:
            cv2.circle(im, (cx, cy), 35, LIGHT_GREEN, -1, lineType=cv2.LINE_AA)
    return im


def test_a_wiggly_boundary_costs_more_arcs_than_a_round_one():
    round_, wavy = (clipart_regions(load_image(_square_with(1, w))) for w in (False, True))
    inner = [sum(c for (i, j), c in boundary_arcs(r).items() if i != 0) for r in (round_, wavy)]
    assert inner[0] <= 16 / ARC_CHORDS  # a circle of radius 35: about 15 chords within 2 px, a few arcs
    assert inner[1] > 2 * inner[0]  # twelve bumps: more than twice the arcs


def test_a_stroke_counts_half_on_each_side():
    regions = np.zeros((60, 60), dtype=np.int64)
    regions[10:50, 10:50] = 1
    regions[10:50, 28:32] = 2  # a 4 px stroke across the square
    regions[10:50, 32:50] = 3
    full = boundary_arcs(regions)
    halved = boundary_arcs(regions, strokes=np.array([2]))
    assert halved[1, 2] == full[1, 2] / 2 and halved[2, 3] == full[2, 3] / 2
    assert (1, 3) not in full  # the stroke parts them


def test_wiggly_regions_over_the_budget_merge_and_the_silhouette_stays():
    img = load_image(_square_with(9, wiggly=True))
    regions = clipart_regions(img)
    assert regions.max() == 10  # the square and its nine wiggly blobs
    whole = merge_by_importance(regions, img.lab, 24, arcs=None)
    assert whole.detail == 10  # a count of 24 keeps them all
    kept = merge_by_importance(regions, img.lab, 24, arcs=20.0)
    assert 1 <= kept.detail < 10  # the budget keeps fewer
    assert sum(boundary_arcs(kept.regions).values()) <= 20.0  # and the logo's predicted arcs are within it
    assert np.array_equal(kept.regions > 0, regions > 0)  # the silhouette is the same


def test_round_regions_within_the_budget_are_all_kept():
    img = load_image(_square_with(9, wiggly=False))
    regions = clipart_regions(img)
    assert regions.max() == 10
    assert merge_by_importance(regions, img.lab, 24, arcs=sum(boundary_arcs(regions).values())).detail == 10


def test_the_dark_marks_are_kept_under_any_budget():
    im = _square_with(6, wiggly=True)
    cv2.circle(im, (310, 310), 6, (0, 0, 0), -1, lineType=cv2.LINE_AA)  # an eye
    img = load_image(im)
    regions = clipart_regions(img)
    kept = merge_by_importance(regions, img.lab, 24, arcs=0.0)
    eye = kept.regions[310, 310]
    assert eye != kept.regions[200, 200] and eye != 0  # the eye is a region of its own
    assert kept.detail == 2  # the square and the eye: every wiggly blob went


@pytest.mark.parametrize("bad", [0, -3, 2.5, "40", True])
def test_arcs_must_be_a_whole_number_of_arcs(bad):
    with pytest.raises(InvalidParameterError, match=r"^arcs must be a whole number of arcs, at least 1, got "):
        Options(arcs=bad)


def test_the_arc_budget_is_an_option_of_abstract():
    im = _square_with(9, wiggly=True)
    whole = abstract(im, progress=False)
    budget = abstract(im, progress=False, arcs=12)
    assert Options().arcs is None  # no region merged for the count unless asked (the fit alone: LOGO_ARCS)
    assert budget.final.params["detail"] < whole.final.params["detail"] == 10  # fewer regions kept
    assert len(budget.final.arcs) < len(whole.final.arcs)
