"""Tests of img2logo.fit.recovery: the initial fit when the joint fit fails, radii that cannot reach."""

from __future__ import annotations

import warnings

import numpy as np
import pytest
from helpers import DATA, check_level, golden_chain, golden_radius, hand_built_state, sampled_arc

from img2logo import InvalidParameterError
from img2logo.fit import window_solve
from img2logo.fit.fit_values import Seed
from img2logo.fit.progressive import optimize
from img2logo.fit.recovery import ConnectivityWarning, centred_seeds, parts, recover
from img2logo.geometry.primitives import line_arc
from img2logo.segment_graph import SegmentGraph


def _three_lines_and_an_arc():
    """Three straight 60 px segments from node 0 (nodes 1, 2, 3 at their far ends), and apart an arc (nodes 4, 5).

    The seeds: the lines on their pixels, except the third turned about its far end to miss
    node 0 by 2.28 px (three fixed lines through one junction: Eqn. 13 has no solution), and the
    arc on its own golden circle (k = 8).
    """
    o = np.array([100.0, 100.0])
    ends = [o + 60.0 * np.array([np.cos(t), np.sin(t)]) for t in (0.0, 2.1, 4.2)]
    center = np.array([300.0, 300.0])
    arc = sampled_arc(center, golden_radius(8), 0.0, 1.5)
    graph = SegmentGraph(
        (*(np.linspace(o, e, 61) for e in ends), arc),
        np.array([o, *ends, arc[0], arc[-1]]),
        np.array([[0, 1], [0, 2], [0, 3], [4, 5]]),
        400,
        400,
    )
    seeds = {}
    for i, end in enumerate(ends):
        circle = line_arc(o if i < 2 else o + np.array([0.0, 5.0]), end).circle
        seeds[i] = Seed(circle.center, circle.r, None)
    seeds[3] = Seed(center, golden_radius(8), 8)
    return graph, seeds


def test_recover_releases_the_junction_the_circles_miss_most_and_keeps_the_rest():
    graph, seeds = _three_lines_and_an_arc()
    state = hand_built_state(graph)
    assert parts(state) == [[0, 1, 2], [3]]
    whole = window_solve.solve_whole(
        state, dict(state.groups), seeds, state.node_groups(), n_groups_total=4, n_junctions_total=6
    )
    assert whole is None  # the joint fit fails: recovery's case
    with pytest.warns(ConnectivityWarning, match=r"could not meet 1 of 6 junctions"):
        fits, disp = recover(state, seeds)
    assert state.released == {0} and state.stats.released_junctions == 1
    assert parts(state) == [[0], [1], [2], [3]]  # released, node 0 joins nothing
    assert sorted(fits) == [0, 1, 2, 3] and [fits[g].k for g in range(4)] == [None, None, None, 8]
    # The arc's part converged alone with its exact connectivity; the lines pass their far ends.
    np.testing.assert_allclose(fits[3].center, [300.0, 300.0], atol=1e-6)
    assert sorted(disp) == [1, 2, 3, 4, 5]
    np.testing.assert_allclose(np.array(list(disp.values())), 0.0, atol=1e-6)
    # A line's arc ends where the released junction projects on it: its nearest point to node 0.
    miss = abs(float(np.hypot(*(graph.junctions[0] - seeds[2].center))) - seeds[2].radius)
    assert miss == pytest.approx(2.28, abs=0.01)
    arc = fits[2].arc.arc
    near = min(float(np.hypot(*(p - graph.junctions[0]))) for p in (arc.start, arc.end))
    assert near == pytest.approx(miss, abs=1e-6)


def test_recover_meets_every_junction_it_can():
    # The third line through node 0 as well: each part converges at once, nothing is released.
    graph, seeds = _three_lines_and_an_arc()
    circle = line_arc(graph.junctions[0], graph.junctions[3]).circle
    seeds[2] = Seed(circle.center, circle.r, None)
    state = hand_built_state(graph)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fits, disp = recover(state, seeds)
    assert not state.released and state.stats.released_junctions == 0 and sorted(fits) == [0, 1, 2, 3]
    assert state.stats.global_solves == 2  # one per connected part
    np.testing.assert_allclose(np.array(list(disp.values())), 0.0, atol=1e-6)


def test_radii_too_small_for_the_junctions_are_named():
    graph, _ = golden_chain()
    with pytest.raises(InvalidParameterError, match=r"chosen radii \(k = 1, 2, 3: .* px\) are too small"):
        optimize(graph, exponents=[1, 2, 3])


def test_a_junction_the_fit_cannot_meet_is_released(monkeypatch):
    from img2logo.fit import recovery

    graph, _ = golden_chain()
    stuck = 2  # pretend that no fit can meet junction 2 (where arcs 2 and 3 join)
    solve = window_solve.solve

    def failing(state, groups, *args, **kwargs):
        nodes = {n for g in groups.values() for n in state.constrained_nodes(g)}
        return None if stuck in nodes else solve(state, groups, *args, **kwargs)

    monkeypatch.setattr(window_solve, "solve", failing)
    with pytest.warns(recovery.ConnectivityWarning, match=r"could not meet [12] of 4 junctions"):
        progression = optimize(graph, merging=False, simplify=False)
    assert 1 <= progression.stats["released_junctions"] <= 2
    level = progression.levels[0]
    check_level(level)  # the junctions it lists are met exactly
    assert len(level.arcs) == 3
    assert not any(np.allclose(j, graph.junctions[stuck], atol=1e-6) for j in level.junctions)


def test_a_part_with_every_junction_released_still_gets_its_arcs(monkeypatch):
    # No fit with any constraint succeeds: recovery releases every junction, and the last
    # solve (a window no junction touches) fits each circle alone.
    from img2logo.fit import recovery

    graph, truth = golden_chain()
    solve = window_solve.solve

    def failing(state, groups, *args, **kwargs):
        constrained = any(state.constrained_nodes(g) for g in groups.values())
        return None if constrained else solve(state, groups, *args, **kwargs)

    monkeypatch.setattr(window_solve, "solve", failing)
    with pytest.warns(recovery.ConnectivityWarning, match=r"could not meet 4 of 4 junctions"):
        progression = optimize(graph, merging=False, simplify=False)
    level = progression.levels[0]
    assert len(level.arcs) == 3 and progression.stats["released_junctions"] == 4
    for arc, (center, radius) in zip(level.arcs, truth, strict=True):  # each circle where its points are
        assert arc.circle.r == pytest.approx(radius, rel=1e-9)
        np.testing.assert_allclose(arc.circle.center, center, atol=1e-3)


def test_one_huge_radius_on_a_real_drawing_gives_a_logo(data_dir):
    # --radii 15 (r = 1364 px on a 512 px drawing): every circle 1364 px, not a crash. From the
    # free centres the joint fit stalls; from the centred ones (the circles on their pixels) it
    # meets every junction.
    from img2logo import abstract

    result = abstract(data_dir / "drawing-fish.png", exponents=[15], progress=False)
    assert result.final.arcs and {a.circle.k for a in result.final.arcs} == {15}
    assert result.progression.stats["released_junctions"] == 0
    check_level(result.levels[0])


def test_radii_too_large_for_the_image_are_named():
    # The smallest radius allowed is over 20 x the longer side (600 px): a straight line to the fit.
    graph, _ = golden_chain()
    with pytest.raises(
        InvalidParameterError, match=r"the smallest, 1\.5e\+04 px, is over 20 x .* \(600 px\), .*--unit"
    ):
        optimize(graph, ladder="fibonacci", unit=15000.0)
    with pytest.raises(InvalidParameterError, match=r"choose smaller exponents \(--radii\)"):
        optimize(graph, exponents=[24, 25], bias=0.0)  # phi**24 = 103682 px


def test_centred_seeds_put_each_golden_circle_where_its_pixels_are():
    # A seed's centre is its free circle's; with the radius snapped the circle runs off the
    # pixels by the difference of the radii. Centred, it lies on them; a line keeps its place.
    graph, truth = golden_chain()
    state = hand_built_state(graph)
    seeds = {g: Seed(c + np.array([40.0, -25.0]), r, 8 + g) for g, (c, r) in enumerate(truth)}
    line = line_arc(graph.junctions[0], graph.junctions[1]).circle
    seeds[0] = Seed(line.center, line.r, None)
    centred = centred_seeds(state, seeds)
    np.testing.assert_array_equal(centred[0].center, seeds[0].center)
    for g in (1, 2):
        np.testing.assert_allclose(centred[g].center, truth[g][0], atol=1e-6)
        assert centred[g].radius == seeds[g].radius and centred[g].k == seeds[g].k


def test_a_part_that_stalls_from_the_free_centres_is_solved_from_the_centred_ones(monkeypatch):
    # Eqn. 13 from the free centres is made to fail; the retry from the centred seeds converges
    # before any junction is released.
    graph, truth = golden_chain()
    state = hand_built_state(graph)
    seeds = {g: Seed(c + np.array([30.0, 0.0]), r, 8 + g) for g, (c, r) in enumerate(truth)}
    solve = window_solve.solve

    def stalls_off_the_pixels(state, groups, seeds_, *args, **kwargs):
        off = any(np.hypot(*(seeds_[g].center - truth[g][0])) > 1.0 for g in groups)
        return None if off else solve(state, groups, seeds_, *args, **kwargs)

    monkeypatch.setattr(window_solve, "solve", stalls_off_the_pixels)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        fits, disp = recover(state, seeds)
    assert not state.released and sorted(fits) == [0, 1, 2]
    np.testing.assert_allclose(np.array(list(disp.values())), 0.0, atol=1e-6)


def test_a_clip_art_with_thin_legs_keeps_every_junction():
    # The held-out critter-c (a body on two 22 px legs with round caps, a head, a tail): its
    # straight leg sides' free circles are capped at 1400 px and snapped to 1646 px, 240 px off
    # their pixels, and the joint fit from there stalled; recovery released the four junctions
    # of the legs, which came out as open arcs 1-4 px from the body (near-miss gaps).
    from img2logo import abstract, quality

    path = DATA.parent / "benchmarks" / "data" / "heldout" / "clipart-critter-c.png"
    with warnings.catch_warnings():
        warnings.simplefilter("error", ConnectivityWarning)
        result = abstract(path, progress=False)
    assert result.progression.stats["released_junctions"] == 0
    assert len(quality.near_miss_gaps(result.final)) == 0
