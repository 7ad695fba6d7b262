"""Tests of img2logo.segment_graph: graphs of known drawings, invariants, real images."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import DATA, drawing, two_discs

from img2logo import InvalidParameterError, SegmentGraph, build_segment_graph, extract_feature_lines


def graph_of(image, **kw) -> SegmentGraph:
    return build_segment_graph(extract_feature_lines(image, kind=kw.pop("kind", "auto")), **kw)


def check_invariants(g: SegmentGraph) -> None:
    """What every segment graph promises (see SegmentGraph's docstring)."""
    assert g.ends.shape == (g.n_segments, 2)
    assert np.all(g.ends[:, 0] != g.ends[:, 1]), "a segment must not start and end at one node"
    for i, seg in enumerate(g.segments):
        assert seg.shape[1] == 2 and len(seg) >= 2
        np.testing.assert_array_equal(seg[0], g.junctions[g.ends[i, 0]])
        np.testing.assert_array_equal(seg[-1], g.junctions[g.ends[i, 1]])
        steps = np.hypot(*np.diff(seg, axis=0).T)
        if len(steps) > 2:
            assert steps[1:-1].max() <= np.sqrt(2) + 1e-9, "inner points are 8-neighbouring pixels"
        assert steps.max() < 8.0, "a node is near the pixels of its segments"
    assert np.all(g.valence >= 1)
    assert np.all((g.junctions >= 0) & (g.junctions <= [g.width, g.height]))


# --------------------------------------------------------------------------- known graphs
@pytest.mark.parametrize("thickness", [1, 3, 7])
def test_y_has_one_junction_of_valence_three(thickness):
    g = graph_of(drawing("Y", thickness), rdp_tolerance=50.0)
    check_invariants(g)
    assert g.n_segments == 3
    assert sorted(g.valence.tolist()) == [1, 1, 1, 3]
    hub = g.junctions[g.valence == 3][0]
    assert np.hypot(*(hub - [100.5, 100.5])) < 3.0
    ends = g.junctions[g.valence == 1]
    for target in ([100.5, 180.5], [40.5, 40.5], [160.5, 40.5]):
        assert np.min(np.hypot(*(ends - target).T)) < 3.0 + thickness


@pytest.mark.parametrize("thickness", [1, 3, 7])
def test_x_has_one_junction_of_valence_four(thickness):
    g = graph_of(drawing("X", thickness), rdp_tolerance=50.0)
    check_invariants(g)
    assert sorted(g.valence.tolist()) == [1, 1, 1, 1, 4]
    assert np.hypot(*(g.junctions[g.valence == 4][0] - [100.5, 100.5])) < 3.0


def test_two_disjoint_strokes():
    g = graph_of(drawing("two"), rdp_tolerance=50.0)
    check_invariants(g)
    assert g.n_segments == 2
    assert g.n_components() == 2
    assert sorted(g.valence.tolist()) == [1, 1, 1, 1]


@pytest.mark.parametrize("thickness", [1, 3, 7])
def test_circle_is_one_loop_split_into_segments(thickness):
    g = graph_of(drawing("circle", thickness))
    check_invariants(g)
    assert g.n_components() == 1
    assert np.all(g.valence == 2)
    assert g.n_segments == g.n_junctions >= 2
    # Every point lies on the drawn circle.
    pts = np.vstack(g.segments)
    assert np.all(np.abs(np.hypot(*(pts - 100.5).T) - 60) < 1.5)


def test_circle_with_a_huge_rdp_tolerance_is_still_split_in_two():
    g = graph_of(drawing("circle"), rdp_tolerance=1000.0)
    assert g.n_segments == 2
    assert np.all(g.valence == 2)
    assert abs(g.lengths[0] - g.lengths[1]) < 5.0  # split half-way round


def test_square_is_split_at_its_four_corners():
    g = graph_of(drawing("square", thickness=1), rdp_tolerance=2.0)
    check_invariants(g)
    assert g.n_segments == 4
    corners = np.array([[40.5, 40.5], [160.5, 40.5], [160.5, 160.5], [40.5, 160.5]])
    for c in corners:
        assert np.min(np.hypot(*(g.junctions - c).T)) < 1.5
    np.testing.assert_allclose(np.sort(g.lengths), 120.0, atol=1.0)


def test_rdp_tolerance_controls_the_number_of_segments():
    counts = [graph_of(drawing("spiral"), rdp_tolerance=t).n_segments for t in (0.5, 1.0, 2.0, 4.0, 8.0)]
    assert counts == sorted(counts, reverse=True)
    assert counts[0] > 2 * counts[-1]


def test_spiral_is_one_open_chain():
    g = graph_of(drawing("spiral"))
    check_invariants(g)
    assert g.n_components() == 1
    assert (g.valence == 1).sum() == 2 and (g.valence >= 3).sum() == 0


def test_two_touching_discs_have_two_junctions_of_valence_three():
    g = graph_of(two_discs(), kind="clipart")
    check_invariants(g)
    assert (g.valence >= 3).sum() == 2
    assert np.all(g.valence[g.valence >= 3] == 3)
    # At the circles' intersections (105.5, 100 -+ 37.4), within the anti-aliasing.
    hubs = g.junctions[g.valence == 3]
    hubs = hubs[np.argsort(hubs[:, 1])]
    np.testing.assert_allclose(hubs, [[105.5, 63.1], [105.5, 137.9]], atol=2.0)


def test_rgba_clipart_gives_the_same_graph():
    im = two_discs()
    rgba = np.dstack([im, np.full(im.shape[:2], 255, np.uint8)])
    rgba[(im == 255).all(axis=2)] = 0
    a, b = graph_of(im), graph_of(rgba)
    assert a.n_segments == b.n_segments
    np.testing.assert_array_equal(a.junctions, b.junctions)
    np.testing.assert_array_equal(a.ends, b.ends)


def test_short_spur_is_pruned_long_branch_kept():
    im = drawing("two", thickness=3)
    import cv2

    cv2.line(im, (60, 100), (66, 100), (0, 0, 0), 3)  # a short spur off the first stroke
    cv2.line(im, (150, 110), (190, 110), (0, 0, 0), 3)  # a long branch off the second
    g = graph_of(im, rdp_tolerance=50.0, min_length=12.0)
    assert (g.valence >= 3).sum() == 1
    assert (g.valence == 1).sum() == 5


# --------------------------------------------------------------------------- values and errors
def test_segment_graph_is_frozen():
    g = graph_of(drawing("Y"))
    with pytest.raises(AttributeError):
        g.junctions = np.zeros((1, 2))  # type: ignore[misc]
    with pytest.raises(ValueError):
        g.segments[0][0, 0] = 1.0
    with pytest.raises(ValueError):
        g.ends[0, 0] = 1


def test_segments_at_is_omega_of_p():
    g = graph_of(drawing("Y"), rdp_tolerance=50.0)
    hub = int(np.flatnonzero(g.valence == 3)[0])
    assert len(g.segments_at(hub)) == 3
    assert all(hub in g.ends[i] for i in g.segments_at(hub))


def test_empty_map_gives_an_empty_graph():
    g = build_segment_graph(np.zeros((30, 30), bool))
    assert g.n_segments == 0 and g.n_junctions == 0 and g.n_components() == 0


@pytest.mark.parametrize(
    ("kw", "message"),
    [
        ({"rdp_tolerance": 0}, "rdp_tolerance must be > 0, got 0.0"),
        ({"rdp_tolerance": -1}, "rdp_tolerance must be > 0"),
        ({"rdp_tolerance": float("nan")}, "rdp_tolerance must be finite"),
        ({"min_length": -2}, "min_length must be >= 0"),
    ],
)
def test_bad_parameters(kw, message):
    with pytest.raises(InvalidParameterError, match=message):
        build_segment_graph(np.zeros((30, 30), bool), **kw)


def test_lines_must_be_two_dimensional():
    with pytest.raises(InvalidParameterError, match=r"lines must be a 2-D map of shape \(H, W\), got shape \(3,\)"):
        build_segment_graph(np.zeros(3, bool))


def test_constructor_validates_ends():
    seg = np.array([[0.0, 0.0], [1.0, 1.0]])
    with pytest.raises(InvalidParameterError, match="ends must have one row per segment"):
        SegmentGraph((seg,), np.zeros((2, 2)), np.zeros((0, 2)), 10, 10)
    with pytest.raises(InvalidParameterError, match=r"ends must index junctions 0\.\.1"):
        SegmentGraph((seg,), np.zeros((2, 2)), np.array([[0, 5]]), 10, 10)


# --------------------------------------------------------------------------- real images
# Count ranges checked by eye on the rendered graphs (figures/00_segment_graphs/).
@pytest.mark.parametrize(
    ("name", "segments", "junctions3", "max_components"),
    [
        ("clipart-fish", (60, 130), (4, 14), 3),
        ("clipart-bird", (70, 160), (3, 12), 4),
        ("drawing-fish", (30, 80), (0, 2), 2),
        ("drawing-rabbit", (35, 90), (0, 3), 3),
        ("photo-cat", (30, 150), (0, 20), 20),
    ],
)
def test_examples_give_plausible_graphs(name, segments, junctions3, max_components):
    g = graph_of(DATA / f"{name}.png")
    check_invariants(g)
    assert segments[0] <= g.n_segments <= segments[1]
    assert junctions3[0] <= int((g.valence >= 3).sum()) <= junctions3[1]
    assert 1 <= g.n_components() <= max_components


@pytest.mark.parametrize("name", ["clipart-fish", "drawing-fish"])
def test_outline_is_one_connected_component(name):
    # The largest component holds most of the line length: the object's outline is not broken.
    g = graph_of(DATA / f"{name}.png")
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components

    n = g.n_junctions
    _, labels = connected_components(coo_matrix((np.ones(g.n_segments), (g.ends[:, 0], g.ends[:, 1])), shape=(n, n)))
    per_comp = np.bincount(labels[g.ends[:, 0]], weights=g.lengths)
    assert per_comp.max() > 0.75 * per_comp.sum()


# --- the turn at a node (tangent joins) ----------------------------------------------


def test_turns_are_small_on_a_circle_and_a_right_angle_at_a_square_corner():
    import cv2

    ring = np.zeros((300, 300), np.uint8)
    cv2.circle(ring, (150, 150), 100, 255, 1)
    g = build_segment_graph(ring > 0)
    turns = np.degrees(g.turns[np.isfinite(g.turns)])
    assert len(turns) == g.n_junctions  # every node of a loop has valence 2
    # A 1-px raster circle: its 0.5 px steps tilt a tangent by a few degrees.
    assert np.median(turns) < 4.0 and np.mean(turns < 10.0) >= 0.9
    assert len(g.smooth_nodes()) == int(np.sum(turns < 10.0))
    square = np.zeros((200, 200), bool)
    square[40, 40:161] = square[160, 40:161] = square[40:161, 40] = square[40:161, 160] = True
    sq = build_segment_graph(square)
    corners = [k for k, p in enumerate(sq.junctions) if np.min(np.abs(p - 40.5)) < 3 and np.min(np.abs(p - 160.5)) < 3]
    corners += [k for k, p in enumerate(sq.junctions) if np.all(np.abs(p - 40.5) < 3) or np.all(np.abs(p - 160.5) < 3)]
    assert corners
    for k in corners:
        assert np.degrees(sq.turns[k]) == pytest.approx(90.0, abs=5.0)
        assert k not in sq.smooth_nodes()


def test_turns_are_nan_off_valence_two():
    g = SegmentGraph(
        [[[0.0, 0.0], [10.0, 0.0]], [[10.0, 0.0], [20.0, 0.0]], [[10.0, 0.0], [10.0, 10.0]]],
        [[0.0, 0.0], [10.0, 0.0], [20.0, 0.0], [10.0, 10.0]],
        [[0, 1], [1, 2], [1, 3]],
        30,
        30,
    )
    assert np.isnan(g.turns).all() and g.smooth_nodes() == frozenset()
    straight = SegmentGraph(
        [[[0.0, 0.0], [5.0, 0.0], [10.0, 0.0]], [[10.0, 0.0], [15.0, 0.0], [20.0, 0.0]]],
        [[0.0, 0.0], [10.0, 0.0], [20.0, 0.0]],
        [[0, 1], [1, 2]],
        30,
        30,
    )
    assert straight.turns[1] == pytest.approx(0.0, abs=1e-9) and straight.smooth_nodes() == {1}


def test_turns_compiled_are_end_tangents_turns():
    # SegmentGraph.turns takes every end's tangent in one compiled call: end_tangent's numbers, to the bit.
    from img2logo.segment_graph import end_tangent

    for name in ("clipart-fish.png", "drawing-bird.png"):
        g = build_segment_graph(extract_feature_lines(DATA / name))
        want = np.full(g.n_junctions, np.nan)
        for k in range(g.n_junctions):
            ends = [(i, e) for i, pair in enumerate(g.ends.tolist()) for e in (0, 1) if pair[e] == k]
            if len(ends) == 2 and ends[0][0] != ends[1][0]:
                t0, t1 = (end_tangent(g.segments[i], e == 0) for i, e in ends)
                want[k] = float(np.arccos(np.clip(-np.dot(t0, t1), -1.0, 1.0)))
        assert np.array_equal(g.turns, want, equal_nan=True)
        assert np.isfinite(want).sum() > 10
