"""Tests of img2logo.merging: candidate pairs, their evaluation and the greedy loop (Sec. 5.2)."""

from __future__ import annotations

import numpy as np
from helpers import DATA

from img2logo import build_segment_graph, extract_feature_lines
from img2logo.arc_extraction import redundant_intersections
from img2logo.progressive import optimize


def test_no_redundant_intersection_when_an_arc_outside_the_window_moved():
    # Regression: on the clip-art fox at T = 12 a merge was cached with no crossing,
    # then applied after another merge had moved an arc it crosses.
    graph = build_segment_graph(extract_feature_lines(DATA / "clipart-fox.png"))
    prog = optimize(graph, tolerance=12.0)
    level = prog.final
    arc_junctions = [[] for _ in level.arcs]
    for k, arcs in enumerate(level.junction_arcs):
        for i in arcs:
            arc_junctions[i].append(k)
    assert redundant_intersections(list(level.arcs), level.junctions, arc_junctions) == []


def test_max_arc_distance_rejects_merges_that_stray_from_their_line():
    # A wave: at a large T its bumps merge into one or two arcs that cut across them.
    from skimage.draw import line

    from img2logo.preprocessing import FeatureLines

    lines = np.zeros((60, 200), bool)
    xs = np.arange(10, 190)
    ys = np.round(30 + 8 * np.sin(xs / 12.0)).astype(int)
    for i in range(len(xs) - 1):
        rr, cc = line(ys[i], xs[i], ys[i + 1], xs[i + 1])
        lines[rr, cc] = True
    graph = build_segment_graph(FeatureLines(lines, "drawing", "given"))
    free = optimize(graph, tolerance=12.0)
    capped = optimize(graph, tolerance=12.0, max_arc_distance=3.0)
    assert capped.final.params["max_arc_distance"] == 3.0 and "max_arc_distance" not in free.final.params
    assert capped.stats["rejected_far_arc"] > 0
    assert len(capped.final.arcs) > len(free.final.arcs)
    # Every arc's circle is within the bound of its pixels (a circle is nearer than its arc).
    for arc, ids in zip(capped.final.arcs, capped.final.arc_segments, strict=True):
        pts = np.concatenate([graph.segments[i] for i in ids])
        assert np.max(np.abs(arc.circle.distance(pts))) <= 3.0 + 1e-6
