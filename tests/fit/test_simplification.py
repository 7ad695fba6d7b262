"""Tests of img2logo.fit.simplification: segment groups and the line-segment simplification (Sec. 5.4)."""

from __future__ import annotations

import numpy as np
from helpers import DATA

from img2logo import build_segment_graph, extract_feature_lines
from img2logo.fit.constants import SIMPLIFICATION_ERROR
from img2logo.fit.progressive import optimize
from img2logo.fit.simplification import Group, is_straight, merge_candidate, merge_groups, simplify, straight_line


def test_simplification_reduces_the_initial_arcs():
    graph = build_segment_graph(extract_feature_lines(DATA / "drawing-fish.png"))
    plain = optimize(graph, simplify=False, merging=False)
    simplified = optimize(graph, simplify=True, merging=False)
    assert len(plain.levels[0].arcs) == graph.n_segments
    assert len(simplified.levels[0].arcs) < 0.6 * graph.n_segments
    assert len(simplified.simplified) == len(simplified.levels[0].arcs)


def _arc(t0: float, t1: float, r: float = 50.0, n: int = 40) -> np.ndarray:
    t = np.linspace(t0, t1, n)
    return np.column_stack([100 + r * np.cos(t), 100 + r * np.sin(t)])


def test_merge_groups_joins_at_the_common_node_whatever_the_directions():
    a = Group((0,), (0, 1), _arc(0.0, 1.0), False)
    b = Group((1,), (2, 1), _arc(2.0, 1.0), True)  # runs towards the common node 1
    merged = merge_groups(a, b, 1)
    assert merged.segments == (0, 1) and merged.nodes == (0, 1, 2) and merged.locked
    np.testing.assert_array_equal(merged.points, np.vstack([a.points, b.points[::-1][1:]]))
    again = merge_groups(a.reversed(), b, 1)  # a's far end still starts the result
    assert again.nodes == (0, 1, 2)


def test_a_merge_candidate_is_scored_once_per_pair_and_never_of_a_locked_group():
    a = Group((0,), (0, 1), _arc(0.0, 1.0), False)
    b = Group((1,), (1, 2), _arc(1.0, 2.0), False)
    calls = []

    def error(g):
        calls.append(g.segments)
        return 0.25

    scores = {}
    err, merged = merge_candidate(a, b, 1, error, scores)
    assert err == 0.25 and merged.segments == (0, 1) and merged.nodes == (0, 1, 2)
    assert merge_candidate(a, b, 1, error, scores) == (err, merged) and calls == [(0, 1)]  # scored once
    assert merge_candidate(a, Group((1,), (1, 2), b.points, True), 1, error, scores) is None  # locked
    assert merge_candidate(a, a, 1, error, scores) is None  # one group's two ends


def test_simplify_merges_at_split_points_only_below_the_error():
    parts = [Group((0,), (0, 1), _arc(0.0, 1.0), False), Group((1,), (1, 2), _arc(1.0, 2.0), False)]
    valence = np.array([1, 2, 1])
    (merged,) = simplify(parts, lambda g: 0.1, valence)
    assert merged.segments == (0, 1) and merged.nodes == (0, 1, 2)
    assert len(simplify(parts, lambda g: SIMPLIFICATION_ERROR, valence)) == 2  # not below the error
    assert len(simplify(parts, lambda g: 0.1, np.array([1, 3, 1]))) == 2  # a real junction is the loop's
    assert len(simplify(parts, lambda g: 0.1, valence, axis_nodes={1})) == 2  # on the mirror axis
    locked = [parts[0], Group((1,), (1, 2), parts[1].points, True)]
    assert len(simplify(locked, lambda g: 0.1, valence)) == 2


def test_a_straight_stroke_is_told_from_an_arc():
    x = np.arange(0.0, 60.0)
    stroke = Group((0,), (0, 1), np.column_stack([x, 10.0 + 0.02 * x]), False)
    assert is_straight(stroke)
    start, end = straight_line(stroke)
    np.testing.assert_allclose([start, end], [[0.0, 10.0], [59.0, 11.18]], atol=1e-9)
    assert not is_straight(Group((0,), (0, 1), _arc(0.0, 1.5), False))
    assert straight_line(Group((0,), (0, 1), _arc(0.0, 1.5), False)) is None
    assert not is_straight(Group((0,), (0, 0), stroke.points, False))  # a closed group is never a line


def _full_scan(groups, error, valence, axis_nodes=frozenset()):
    """The simplification by a scan of every node in order after each merge (the reference of the incremental order)."""
    current = list(groups)
    scores = {}
    while True:
        at = {}
        for i, g in enumerate(current):
            for n in set(g.ends):
                at.setdefault(n, []).append(i)
        best, best_err = None, SIMPLIFICATION_ERROR
        for node, idx in sorted(at.items()):
            if valence[node] != 2 or len(idx) != 2 or node in axis_nodes:
                continue
            scored = merge_candidate(current[idx[0]], current[idx[1]], node, error, scores)
            if scored is None:
                continue
            err, merged = scored
            if err < best_err:
                best, best_err = (idx[0], idx[1], merged), err
        if best is None:
            return current
        i, j, merged = best
        current = [g for k, g in enumerate(current) if k not in (i, j)] + [merged]


def test_simplify_makes_the_merges_of_a_full_scan_in_the_same_order():
    """The incremental simplification merges what a scan of every node after each merge would, ties included."""
    graph = build_segment_graph(extract_feature_lines(DATA / "clipart-fish.png"))
    locked = np.zeros(graph.n_segments, dtype=bool)
    locked[::17] = True
    groups = [
        Group((i,), tuple(int(n) for n in graph.ends[i]), seg, bool(locked[i])) for i, seg in enumerate(graph.segments)
    ]
    valence = graph.valence

    def fitted(g):  # the mean distance to the fitted circle, rounded to 0.25 px: many ties
        from img2logo.geometry.circle_fitting import fit_circle, mean_abs_error

        fit = fit_circle(g.points, refine=False)
        return round(4 * mean_abs_error(g.points, fit.center, fit.radius)) / 4

    for error, axis in ((fitted, frozenset()), (lambda g: 0.5, frozenset()), (fitted, frozenset(range(0, 400, 7)))):
        ours, reference = simplify(groups, error, valence, axis), _full_scan(groups, error, valence, axis)
        assert len(ours) < len(groups)
        assert [(g.segments, g.nodes) for g in ours] == [(g.segments, g.nodes) for g in reference]
        for a, b in zip(ours, reference, strict=True):
            np.testing.assert_array_equal(a.points, b.points)
