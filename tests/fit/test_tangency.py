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
    assert found.count >= 1 and result.progression.stats["tangent_joins"] == found.count
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


def test_split_a_chain_where_the_junction_slid():
    from img2logo.fit.tangency import split_chain

    chain = np.column_stack([np.arange(10.0), np.zeros(10)])
    head, tail, off = split_chain(chain, np.array([4.25, 0.5]))
    # The foot of the junction on the chain ends the head and starts the tail; its distance off the line.
    assert np.allclose(head[-1], (4.25, 0.0)) and np.allclose(tail[0], (4.25, 0.0))
    assert len(head) == 6 and len(tail) == 6 and off == pytest.approx(0.5)
    assert np.array_equal(np.vstack([head[:-1], tail[1:]]), chain)
    # Slid so far that one group would keep fewer than SLIDE_MIN_PIXELS pixels: no split.
    assert split_chain(chain, np.array([1.5, 0.0])) is None
    assert split_chain(chain, np.array([8.5, 0.0])) is None


@pytest.fixture(scope="module")
def umbrella():
    return abstract(DATA.parent / "benchmarks" / "data" / "drawing-umbrella.png", progress=False)


def test_joins_made_tangent_one_at_a_time_stay_exact(umbrella):
    result = umbrella
    level = result.final
    found = quality.joins(level, result.graph)
    # Both joins on smooth input tangent (the whole refit at once made one of the two).
    assert found.count == 2 and np.all(np.degrees(found.kinks) < 1e-3)
    assert result.progression.stats["tangent_joins"] == 2
    for j in found.junctions:
        a, b = (level.arcs[i].circle for i in level.arcs_at(j))
        distance = math.dist(a.center, b.center)
        assert min(abs(distance - abs(a.r - b.r)), abs(distance - (a.r + b.r))) <= 1e-6
    # Every arc still ends at its junctions to 1e-6 px, and the radii are on the ladder.
    for arc, t in zip(level.arcs, level.arc_junctions, strict=True):
        for end, j in ((arc.start, t.start), (arc.end, t.end)):
            if j is not None:
                assert math.dist(end, level.junctions[j]) <= 1e-6
        if arc.circle.k is not None:
            assert arc.circle.r == pytest.approx(level.ladder.radius(arc.circle.k), rel=1e-9)
    assert level.similarity <= level.tolerance


def test_the_compiled_split_finds_numpys_foot_to_the_bit():
    from img2logo.fit.tangency import split_chain

    rng = np.random.default_rng(7)
    for _ in range(200):
        chain = np.cumsum(rng.normal(size=(int(rng.integers(12, 60)), 2)), axis=0)
        q = chain[int(rng.integers(len(chain)))] + rng.normal(scale=2.0, size=2)
        # The feet of q on every step of the chain, in numpy (the first nearest one is the split).
        a, v = chain[:-1], chain[1:] - chain[:-1]
        t = np.einsum("ij,ij->i", q - a, v) / np.maximum(np.einsum("ij,ij->i", v, v), 1e-300)
        foot = a + np.clip(t, 0.0, 1.0)[:, None] * v
        dist = np.hypot(*(q - foot).T)
        i = int(dist.argmin())
        out = split_chain(chain, q)
        if out is not None:
            head, tail, off = out
            assert len(head) == i + 2 and np.array_equal(head[-1], foot[i]) and np.array_equal(tail[0], foot[i])
            assert off == dist[i]


def test_cutting_off_tries_over_the_bound_changes_no_result(monkeypatch):
    """A try is cut off once its E^s must exceed the bound (``window_solve.solve``'s ``bound``): the same logo."""
    from img2logo.fit import window_solve

    image = DATA / "clipart-fish.png"
    cut = abstract(image, progress=False)
    within = window_solve._fits
    cuts = []

    def never_cut(*args, bound=None, **kwargs):
        if bound is None:
            return within(*args, **kwargs)
        out = within(*args, bound=bound, **kwargs)
        full = within(*args, bound=math.inf, **kwargs)
        cuts.append(out is None and full is not None)
        return full

    monkeypatch.setattr(window_solve, "_fits", never_cut)
    whole = abstract(image, progress=False)
    assert any(cuts)  # some tries were cut off, and every one would have failed on E^s
    assert whole.progression.stats == cut.progression.stats
    assert whole.final.arcs == cut.final.arcs and whole.final.similarity == cut.final.similarity


def test_the_tangent_joins_make_no_near_miss_gap():
    # Regression: on the seal of make quality's photo2 at T = 7 the tangent refit of a join moved two
    # arcs' free ends 2-5 px from the arc beside them (the loop's last level had none).
    seal = DATA.parent / "benchmarks" / "data" / "photo2" / "photo2-seal.png"
    result = abstract(seal, tolerance=7.0, progress=False)
    assert result.progression.stats["tangent_joins"] >= 1
    assert len(quality.near_miss_gaps(result.final)) == 0 and len(quality.crossings(result.final)) == 0
