"""Tests of img2logo.quality: recall, silhouette, outside, crossings, near-miss gaps, junction gaps."""

from __future__ import annotations

import math

import numpy as np
import pytest
from skimage.draw import circle_perimeter, disk

from img2logo import InvalidParameterError, quality
from img2logo.constants import PHI
from img2logo.fit.arc_extraction import nearest_on_arc
from img2logo.geometry.abstraction import Abstraction
from img2logo.geometry.primitives import Arc, Circle, line_arc
from img2logo.quality import junction_gaps, level_redundant_intersections
from img2logo.segment_graph import SegmentGraph


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


def test_silhouette_of_a_logo_drawn_with_a_wide_stroke():
    """Known answer: a circle 8 px inside a disc's outline misses sil6 as a hairline, and keeps it drawn
    8 px wide (its stroke's edge 4 px from the outline); 2 px wide, its edge is still 7 px away."""
    mask = np.zeros((120, 120), bool)
    mask[disk((60, 60), 40)] = True
    inside = quality.logo_points([_circle(60.5, 60.5, 31.5)])
    assert quality.silhouette_recall(inside, mask) == 0.0
    assert quality.silhouette_recall(inside, mask, stroke_width=8.0) == 1.0
    assert quality.silhouette_recall(inside, mask, stroke_width=2.0) == 0.0
    assert quality.measure([_circle(60.5, 60.5, 31.5)], mask=mask, stroke_width=8.0).silhouette == 1.0
    with pytest.raises(InvalidParameterError, match="stroke_width must be >= 0"):
        quality.silhouette_recall(inside, mask, stroke_width=-1.0)


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


def test_nearest_on_arc_projects_inside_and_clamps_to_the_ends():
    arc = Arc(Circle(0.0, 0.0, 10.0), 0.0, math.pi / 2)  # from (10, 0) to (0, 10)
    d, q = nearest_on_arc(arc, np.array([20.0, 20.0]))
    assert d == pytest.approx(math.hypot(20, 20) - 10)
    np.testing.assert_allclose(q, [10 / math.sqrt(2), 10 / math.sqrt(2)])
    d, q = nearest_on_arc(arc, np.array([12.0, -5.0]))
    np.testing.assert_allclose(q, [10.0, 0.0], atol=1e-12)
    assert d == pytest.approx(math.hypot(2, 5))
    d, q = nearest_on_arc(arc, np.array([[0.0, 0.0], [20.0, 20.0]]))  # the centre: the nearer end
    assert d.shape == (2,) and d[0] == pytest.approx(10.0)


def test_redundant_intersections_of_two_crossing_arcs():
    a = Arc(Circle(0.0, 0.0, 10.0, 4), 0.0, math.pi)
    b = Arc(Circle(10.0, 0.0, 10.0, 4), math.pi / 2, math.pi)
    junctions = np.array([[10.0, 0.0], [-10.0, 0.0]])  # the ends of a; b owns none
    bias = math.log(10.0) / math.log((1.0 + math.sqrt(5.0)) / 2.0) - 4.0  # r = 10 on the ladder: phi ** (4 + bias)
    level = Abstraction(0, (a, b), ((0,), (1,)), junctions, ((0,), (0,)), 1.0, bias, 5.0, 30, 30)
    found = level_redundant_intersections(level)
    assert len(found) == 1
    np.testing.assert_allclose(found[0].point, [5.0, math.sqrt(75.0)])


def test_junction_gaps_known_answer():
    a = Arc(Circle(0.0, 0.0, 10.0), 0.0, math.pi / 2)  # from (10, 0) to (0, 10)
    b = Arc(Circle(13.0, 10.0, 10.0), math.pi / 2, math.pi / 2)  # from (13, 20) to (3, 10)
    points = np.array([[0.0, 10.0], [10.0, 0.0]])
    gap, spread = junction_gaps([a, b], points, [[0, 1], [0]])
    assert gap == pytest.approx([3.0, 0.0]) and spread == pytest.approx([3.0, 0.0])
    with pytest.raises(InvalidParameterError, match="2 junction points but 1"):
        junction_gaps([a, b], points, [[0]])


def test_detail_error_is_the_mean_distance_of_the_masked_pixels_to_the_arcs():
    from img2logo.segment_graph import SegmentGraph

    x = np.linspace(10.0, 50.0, 41)
    graph = SegmentGraph(
        (np.column_stack([x, 20.0 + 0 * x]),), np.array([[10.0, 20.0], [50.0, 20.0]]), np.array([[0, 1]]), 60, 40
    )
    arc = line_arc(np.array([10.0, 23.0]), np.array([50.0, 23.0]))  # 3 px below the stroke
    level = Abstraction(0, (arc,), ((0,),), np.zeros((0, 2)), (), 3.0, 0.0, 5.0, 60, 40)
    everything = np.ones((40, 60), bool)
    assert quality.detail_error(level, graph, everything) == pytest.approx(3.0, abs=0.02)  # samples 0.5 px apart
    assert math.isnan(quality.detail_error(level, graph, ~everything))


# --- joins on smooth input (tangent joins, beyond the paper) --------------------------


def _kinked_pair(kink: float) -> tuple[Abstraction, SegmentGraph]:
    """Two golden arcs meeting at q = (100, 100), the second leaving ``kink`` rad off the first's
    tangent, over a straight segment graph (smooth at q) with a right-angle corner at the second's end."""
    q = np.array([100.0, 100.0])
    r = PHI**8
    # Arc 0 arrives at q heading +x: centre below q (y down), from -pi/2 - 0.5 to -pi/2.
    a0 = Arc(Circle(q[0], q[1] + r, r, 8), -math.pi / 2 - 0.5, 0.5)
    # Arc 1 leaves q heading (cos kink, sin kink): its start angle t0 has (-sin t0, cos t0) = heading.
    t0 = kink - math.pi / 2
    c1 = q - r * np.array([math.cos(t0), math.sin(t0)])
    a1 = Arc(Circle(c1[0], c1[1], r, 8), t0, 0.5)
    corner = a1.end
    line = np.column_stack([np.arange(40.0, 100.5, 1.0), np.full(61, 100.0)])
    after = np.column_stack([np.arange(100.0, 140.5, 1.0), np.full(41, 100.0)])
    down = np.column_stack([np.full(41, 140.0), np.arange(100.0, 140.5, 1.0)])
    nodes = np.array([[40.0, 100.0], q, [140.0, 100.0], [140.0, 140.0]])
    graph = SegmentGraph((line, after, down), nodes, [[0, 1], [1, 2], [2, 3]], 200, 200)
    level = Abstraction(
        level=0,
        arcs=(a0, a1),
        arc_segments=((0,), (1,)),
        junctions=np.array([q, corner]),
        junction_arcs=((0, 1), (1,)),
        similarity=0.0,
        bias=0.0,
        tolerance=5.0,
        width=200,
        height=200,
        junction_nodes=(1, 2),
    )
    return level, graph


@pytest.mark.parametrize("kink_deg", [0.0, 1.0, 30.0])
def test_joins_measure_the_kink_at_a_smooth_junction_only(kink_deg):
    level, graph = _kinked_pair(math.radians(kink_deg))
    found = quality.joins(level, graph)
    # Junction 1 is at a right-angle corner of the input: not a join on smooth input.
    assert graph.turns[2] == pytest.approx(math.pi / 2, abs=0.05)
    assert found.junctions.tolist() == [0] and found.count == 1
    assert math.degrees(found.kinks[0]) == pytest.approx(kink_deg, abs=1e-9)
    assert found.tangent_fraction() == (1.0 if kink_deg < 2.0 else 0.0)
    assert math.degrees(found.median_kink) == pytest.approx(kink_deg, abs=1e-9)


def test_joins_none_gives_nan_fraction_and_kink():
    level, graph = _kinked_pair(0.0)
    corner_only = SegmentGraph(graph.segments, graph.junctions, graph.ends, 200, 200)
    found = quality.joins(level, corner_only, max_turn=0.0)
    assert found.count == 0 and math.isnan(found.tangent_fraction()) and math.isnan(found.median_kink)


def test_joins_check_their_input():
    level, graph = _kinked_pair(0.0)
    with pytest.raises(InvalidParameterError, match="graph must be a SegmentGraph, got str"):
        quality.joins(level, "graph")
    with pytest.raises(InvalidParameterError, match="abstraction must be an Abstraction, got list"):
        quality.joins([], graph)


def test_lost_ink_parts_are_the_dark_parts_no_logo_point_reaches():
    gray = np.ones((100, 100))
    gray[disk((30, 30), 5)] = 0.0  # an eye of 81 px: kept by a circle through it
    gray[disk((70, 70), 5)] = 0.0  # another, far from the logo: lost
    gray[10:14, 80:84] = 0.0  # 16 px: a speck, not counted
    points = quality.logo_points([_circle(30.5, 30.5, 2.0)])
    lost = quality.lost_ink_parts(points, gray)
    np.testing.assert_allclose(lost, [[70.5, 70.5]], atol=1e-9)
    assert len(quality.lost_ink_parts(np.zeros((0, 2)), gray)) == 2
    assert len(quality.lost_ink_parts(points, np.ones((20, 20)))) == 0
    with pytest.raises(InvalidParameterError, match=r"gray must have shape \(H, W\), got \(3,\)"):
        quality.lost_ink_parts(points, np.ones(3))


def test_stroke_width_ratio_of_a_12_px_bar():
    ink = np.zeros((100, 100), bool)
    ink[44:56, 10:90] = True
    assert quality.stroke_width_ratio(6.0, ink) == pytest.approx(0.5, abs=0.05)
    assert math.isnan(quality.stroke_width_ratio(6.0, np.zeros((10, 10), bool)))


def test_free_ends_are_the_open_ends_of_arcs():
    circle = Circle(50.0, 50.0, 20.0)
    top, bottom = Arc(circle, 0.0, np.pi), Arc(circle, np.pi, np.pi)
    assert len(quality.free_ends([top])) == 2  # a half circle alone: a broken outline
    assert len(quality.free_ends([top, bottom])) == 0  # two halves close the circle
    assert len(quality.free_ends([Arc(circle, 0.0, 2 * np.pi)])) == 0  # a whole circle has no end
    near = Arc(circle, np.pi, np.pi - 0.2)  # stops 4 px short of the top's start: two ends, a near-miss gap
    far = Arc(circle, np.pi, np.pi - 1.0)  # stops 19 px short: two dangling ends, no gap
    for other, gaps in ((near, 2), (far, 0)):
        found = quality.measure([top, other])
        assert (found.free_ends, found.gaps) == (2, gaps)
