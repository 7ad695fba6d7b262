"""Tests of img2logo.quality: recall, silhouette, outside, crossings, near-miss gaps."""

from __future__ import annotations

import math

import numpy as np
import pytest
from skimage.draw import circle_perimeter, disk

from img2logo import InvalidParameterError, quality
from img2logo.geometry import Arc, Circle, line_arc


def _circle(cx: float, cy: float, r: float, theta0: float = 0.0, sweep: float = 2 * math.pi) -> Arc:
    return Arc(Circle(cx, cy, r), theta0, sweep)


def test_recall_of_a_drawn_circle_is_complete_and_of_a_far_line_none():
    truth = np.zeros((100, 100), bool)
    rr, cc = circle_perimeter(50, 50, 30)
    truth[rr, cc] = True
    points = quality.logo_points([_circle(50.5, 50.5, 30.0)])
    assert quality.feature_recall(points, truth) == (1.0, 1.0, 1.0)
    far = quality.logo_points([line_arc(np.array([5.0, 95.0]), np.array([95.0, 95.0]))])
    r3, r6, r10 = quality.feature_recall(far, truth)
    assert r3 == r6 == r10 == 0.0


def test_recall_counts_half_a_circle():
    truth = np.zeros((100, 100), bool)
    rr, cc = circle_perimeter(50, 50, 30)
    truth[rr, cc] = True
    half = quality.logo_points([_circle(50.5, 50.5, 30.0, 0.0, math.pi)])  # the lower half (y down)
    r3 = quality.feature_recall(half, truth, (3.0,))[0]
    assert 0.45 < r3 < 0.6


def test_silhouette_and_outside_of_a_disc():
    mask = np.zeros((120, 120), bool)
    mask[disk((60, 60), 40)] = True
    outline = quality.logo_points([_circle(60.5, 60.5, 39.5)])
    assert quality.silhouette_recall(outline, mask) == 1.0
    assert quality.outside_fraction(outline, mask) == 0.0
    background = quality.logo_points([line_arc(np.array([2.0, 2.0]), np.array([2.0, 118.0]))])
    assert quality.outside_fraction(background, mask) == 1.0
    assert quality.silhouette_recall(background, mask) == 0.0


def test_crossing_in_the_middle_counts_and_meeting_at_ends_does_not():
    a = line_arc(np.array([0.0, 50.0]), np.array([100.0, 50.0]))
    b = line_arc(np.array([50.0, 0.0]), np.array([50.0, 100.0]))
    points = quality.crossings([a, b])
    assert points.shape == (1, 2)
    assert np.allclose(points[0], [50.0, 50.0], atol=1e-3)
    c = line_arc(np.array([100.0, 50.0]), np.array([100.0, 0.0]))  # a corner with a
    assert quality.crossings([a, c]).shape == (0, 2)


def test_near_miss_gap_is_an_open_end_short_of_another_arc():
    a = line_arc(np.array([0.0, 50.0]), np.array([100.0, 50.0]))
    short = line_arc(np.array([50.0, 10.0]), np.array([50.0, 47.0]))  # stops 3 px short of a
    joined = line_arc(np.array([20.0, 10.0]), np.array([20.0, 50.0]))  # ends on a
    free = line_arc(np.array([80.0, 10.0]), np.array([80.0, 30.0]))  # 20 px away: a free end
    gaps = quality.near_miss_gaps([a, short, joined, free])
    assert gaps.shape == (1, 2)
    assert np.allclose(gaps[0], [50.0, 47.0], atol=1e-3)


def test_measure_without_truth_gives_nan_recall():
    q = quality.measure([_circle(50.0, 50.0, 20.0)])
    assert q.arcs == 1 and q.crossings == 0 and q.gaps == 0
    assert all(math.isnan(r) for r in q.recall) and math.isnan(q.silhouette)


def test_missed_pixels_are_those_beyond_the_distance():
    truth = np.zeros((50, 50), bool)
    truth[10, 5:45] = True
    truth[40, 5:45] = True
    points = quality.logo_points([line_arc(np.array([5.0, 10.5]), np.array([45.0, 10.5]))])
    missed = quality.missed_pixels(points, truth, 10.0)
    assert missed[40].sum() == 40 and not missed[10].any()


def test_bad_inputs_have_messages():
    with pytest.raises(InvalidParameterError, match=r"truth must have shape \(H, W\), got \(3,\)"):
        quality.feature_recall(np.zeros((1, 2)), np.zeros(3, bool))
    with pytest.raises(InvalidParameterError, match="sequence of Arc, got str"):
        quality.crossings(["not an arc"])
