"""Tangent joins (beyond the paper): the result's circles touch where the input runs on smoothly."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import DATA

from img2logo import abstract, quality
from img2logo.quality import arc_direction


@pytest.fixture(scope="module")
def snail():
    return {t: abstract(DATA / "drawing-snail.png", progress=False, tangency=t) for t in (True, False)}


def test_smooth_joins_are_tangent_and_their_circles_touch(snail):
    result = snail[True]
    found = quality.joins(result.final, result.graph)
    assert found.count == 2 and result.progression.stats["tangent_joins"] == 2
    for j in found.junctions:
        a, b = (result.final.arcs[i].circle for i in result.final.arcs_at(j))
        q = result.final.junctions[j]
        distance = math.dist(a.center, b.center)
        # The circles touch at the junction: centre distance |r1 - r2| or r1 + r2, to 1e-6 px ...
        assert min(abs(distance - abs(a.r - b.r)), abs(distance - (a.r + b.r))) <= 1e-6
        # ... and the junction is on the line of centres.
        u = (b.center - a.center) / distance
        assert abs(u[0] * (q - a.center)[1] - u[1] * (q - a.center)[0]) <= 1e-6
    assert np.all(np.degrees(found.kinks) < 1e-3)
    assert result.final.params["tangency"] is True


def test_without_tangency_the_paper_kinks(snail):
    result = snail[False]
    found = quality.joins(result.final, result.graph)
    assert found.count == 2 and np.all(np.degrees(found.kinks) > 2.0)
    assert result.final.params["tangency"] is False
    assert result.progression.stats["tangent_joins"] == 0


def test_a_right_angle_corner_stays_a_corner(tmp_path):
    import cv2

    img = np.full((200, 200, 3), 255, np.uint8)
    cv2.polylines(img, [np.array([[40, 160], [40, 40], [160, 40]], np.int32)], False, (0, 0, 0), 3)
    path = tmp_path / "corner.png"
    cv2.imwrite(str(path), img)
    result = abstract(path, progress=False, kind="drawing")
    graph, level = result.graph, result.final
    assert not result.progression.stats["tangent_joins"]
    corner = [j for j, p in enumerate(level.junctions) if math.dist(p, (40.5, 40.5)) < 6 and len(level.arcs_at(j)) == 2]
    assert corner, "the corner is a junction of two arcs"
    j = corner[0]
    assert level.junction_nodes[j] not in graph.smooth_nodes()
    ends = []
    for i in level.arcs_at(j):
        t = level.arc_junctions[i]
        ends.append(arc_direction(level.arcs[i], t.start == j))
    kink = math.degrees(math.acos(float(np.clip(-np.dot(*ends), -1.0, 1.0))))
    assert kink == pytest.approx(90.0, abs=15.0)
