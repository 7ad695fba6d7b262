"""Tests of img2logo.fit.fit_state: the optimizer's state, its seeds, fits, counts and mirror-axis hooks."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from helpers import golden_chain, golden_radius, hand_built_state, line_and_a_stroke

from img2logo.fit import window_solve
from img2logo.fit.fit_state import FitState
from img2logo.fit.fit_values import FreeCircles, GroupFit, Seed, Stats, on_axis
from img2logo.fit.merge_checks import gap_ends, open_ends, redundant_pairs
from img2logo.fit.progressive import initial_fit, optimize
from img2logo.fit.simplification import merge_groups
from img2logo.fit.symmetry import HalfAxis
from img2logo.segment_graph import SegmentGraph

#: The counts of a run, in the order Progression.stats has always listed them (bench, JSON-free).
STATS = (
    "evaluated",
    "local_failed",
    "global_solves",
    "rejected_hopeless",
    "rejected_intersections",
    "rejected_far_arc",
    "released_junctions",
    "tangent_joins",
    "released_tangencies",
    "rejected_crossing",
    "rejected_gaps",
    "split_groups",
    "wide_windows",
)


def test_stats_are_the_progressions_counts_in_their_order():
    assert tuple(Stats().as_dict()) == STATS and set(Stats().as_dict().values()) == {0}
    graph, _ = golden_chain()
    progression = optimize(graph)
    assert tuple(progression.stats) == STATS
    assert all(type(v) is int for v in progression.stats.values())
    assert progression.stats["global_solves"] >= 1  # the initial fit at least


def test_a_seed_is_a_named_centre_radius_and_rung():
    seed = Seed(np.array([1.0, 2.0]), 3.0, 4)
    center, radius, k = seed  # it unpacks as the (centre, radius, k) it replaces
    assert (radius, k) == (3.0, 4) and seed.center is center
    assert Seed(np.zeros(2), 1e6, None).k is None  # a straight line


def test_a_group_fit_is_frozen_and_seeds_the_next_fit():
    graph, _ = golden_chain()
    state = hand_built_state(graph)
    initial_fit(state)
    fit = state.fits[0]
    assert isinstance(fit, GroupFit) and fit.seed == (fit.center, fit.radius, fit.k)
    with pytest.raises(dataclasses.FrozenInstanceError):
        fit.radius = 1.0  # type: ignore[misc]


def test_golden_snaps_the_free_radius_to_the_ladder():
    # The chain's arcs lie on golden circles k = 8, 9, 10: the seed is that rung, the centre the free fit's.
    graph, truth = golden_chain()
    state = hand_built_state(graph)
    for gid, (center, radius) in enumerate(truth):
        seed = state.golden(state.groups[gid])
        assert seed.k == 8 + gid and seed.radius == pytest.approx(radius, rel=1e-12)
        np.testing.assert_allclose(seed.center, center, atol=1e-6)
        assert state.golden_error(state.groups[gid]) < 1e-6


def test_the_initial_fit_of_an_exact_chain_meets_its_junctions():
    graph, truth = golden_chain()
    state = hand_built_state(graph)
    initial_fit(state)
    assert state.stats.global_solves == 1 and not state.released
    for gid, (center, radius) in enumerate(truth):
        assert state.fits[gid].radius == pytest.approx(radius, rel=1e-12)
        np.testing.assert_allclose(state.fits[gid].center, center, atol=1e-3)
    np.testing.assert_allclose(state.disp, 0.0, atol=1e-3)
    f, d, nj = state.totals()
    assert nj == 4 and state.similarity() == pytest.approx(f / 3 + d / 4)


def test_node_groups_follow_merges_and_released_junctions():
    graph, _ = golden_chain()
    state = hand_built_state(graph)
    assert state.node_groups() == {0: [0], 1: [0, 1], 2: [1, 2], 3: [2]}
    assert state.end_groups() == state.node_groups()
    merged = merge_groups(state.groups[0], state.groups[1], 1)
    after = state.node_groups_after(0, 1, merged)
    # Node 1 is inside the merged arc, where only two segments meet: it leaves J' (Sec. 6.2).
    assert after == {0: [-1], 2: [2, -1], 3: [2]} and state.constrained_nodes(merged) == (0, 2)
    assert state.node_groups() == {0: [0], 1: [0, 1], 2: [1, 2], 3: [2]}  # the state is unchanged
    state.release(3)
    assert state.constrained_nodes(state.groups[2]) == (2,) and 3 not in state.node_groups()
    assert state.path_nodes(state.groups[2]) == (2, 3)


def test_merge_replaces_two_groups_by_one():
    graph, _ = golden_chain()
    state = hand_built_state(graph)
    initial_fit(state)
    merged = merge_groups(state.groups[0], state.groups[1], 1)
    fit = dataclasses.replace(state.fits[0])
    gid = state.merge(0, 1, merged, {-1: fit}, {1: np.array([0.5, 0.0])})
    assert gid == 3 and sorted(state.groups) == [2, 3] and state.groups[3] is merged
    assert state.fits[3] is fit and sorted(state.fits) == [2, 3]
    np.testing.assert_array_equal(state.disp[1], [0.5, 0.0])


def test_the_ladder_is_given_and_kept():
    graph, _ = golden_chain()
    state = hand_built_state(graph)
    assert state.ladder.radius(9) == pytest.approx(golden_radius(9))
    with pytest.raises(TypeError):
        FitState(graph, state.options)  # type: ignore[call-arg]


def test_a_circle_on_the_mirror_axis_is_fitted_with_its_mirror_image():
    # A half circle left of the axis x = 100, ending square to it at node 1: its circle is centred on the axis.
    t = np.linspace(np.pi / 2, np.pi, 40)
    half = np.column_stack([100 + 30 * np.cos(t), 100 + 30 * np.sin(t)])

    graph = SegmentGraph((half,), np.array([half[0], half[-1]]), np.array([[0, 1]]), 200, 200)
    axis = HalfAxis(100.0, frozenset({0}), frozenset({(0, 0)}))
    state = hand_built_state(graph)
    assert not on_axis(None, state.groups[0]) and on_axis(axis, state.groups[0])
    center, radius = FreeCircles(axis).circle(state.groups[0])
    np.testing.assert_allclose(center, [100.0, 100.0], atol=1e-6)
    assert radius == pytest.approx(30.0, rel=1e-6)
    mirrored = FitState(graph, state.options, state.ladder, axis)
    assert mirrored.axis_constraints([0], state.groups, [0, 1])["axis_circles"] == [0]
    assert mirrored.axis_constraints([0], state.groups, [0, 1])["axis_junctions"] == [0]
    assert state.axis_constraints([0], state.groups, [0, 1]) == {}


def _bounded_chain():
    """The golden chain's initial fit, the middle circle one rung up: a window whose refit cannot be exact."""
    graph, _ = golden_chain()
    state = hand_built_state(graph)
    initial_fit(state)
    seeds = {g: f.seed for g, f in state.fits.items()}
    c, _, k = seeds[1]
    seeds[1] = Seed(c, state.ladder.radius(k + 1), k + 1)
    node_groups = state.node_groups()
    keywords = {
        "changed": [1],
        "free_nodes": sorted(state.constrained_nodes(state.groups[1])),
        "fixed": set(),
        "n_groups_total": len(state.groups),
        "n_junctions_total": len(node_groups),
    }
    return state, seeds, node_groups, keywords


def _similarity_with(state, out):
    """E^s of ``state`` with a solve's fits and displacements applied (the state left as it was)."""
    fits, disp = dict(state.fits), state.disp.copy()
    state.fits.update(out[0])
    for n, d in out[1].items():
        state.disp[n] = d
    try:
        return state.similarity()
    finally:
        state.fits, state.disp = fits, disp


def test_a_bounded_solve_fails_exactly_where_the_unbounded_one_exceeds_the_bound():
    state, seeds, node_groups, keywords = _bounded_chain()
    out = window_solve.solve(state, dict(state.groups), seeds, node_groups, **keywords)
    assert out is not None
    after = _similarity_with(state, out)
    assert after > 0.1  # the rung moved: not an exact fit
    for factor in (0.0, 0.5, 0.999, 1.001, 2.0):
        got = window_solve.solve(state, dict(state.groups), seeds, node_groups, **keywords, bound=factor * after)
        assert (got is None) == (after > factor * after)
        if got is not None:  # a fit within the bound is the unbounded one, the same numbers
            assert got[0].keys() == out[0].keys() and got[1].keys() == out[1].keys()
            for g, f in out[0].items():
                assert got[0][g].arc.frechet == f.arc.frechet and np.array_equal(got[0][g].center, f.center)
            for n, d in out[1].items():
                assert np.array_equal(got[1][n], d)


def test_a_bounded_solve_regroups_before_extracting_and_fails_with_the_regroup():
    state, seeds, node_groups, keywords = _bounded_chain()
    keywords["fixed"] = {0}  # group 0 keeps its circle: outside the fitted groups
    seen = []

    def regroup(at, moved):
        seen.append((sorted(moved), {n: at(n).copy() for n in node_groups}))
        return {0: dataclasses.replace(state.groups[0], points=state.groups[0].points[:-3])}, {}

    out = window_solve.solve(state, dict(state.groups), seeds, node_groups, **keywords)
    got = window_solve.solve(state, dict(state.groups), seeds, node_groups, **keywords, bound=np.inf, regroup=regroup)
    assert got is not None and len(seen) == 1
    moved, at = seen[0]
    assert moved == sorted(out[0])  # called with the groups the window fits, and every node's d_k after it
    for n in node_groups:
        np.testing.assert_array_equal(at[n], out[1].get(n, state.disp[n]))
    # The group outside the window keeps its circle; its arc is on the pixels the regroup gave it.
    fit0 = state.fits[0]
    assert 0 not in out[0] and np.array_equal(got[0][0].center, fit0.center) and got[0][0].radius == fit0.radius
    shorter = dataclasses.replace(state.groups[0], points=state.groups[0].points[:-3])
    expected = state.arc_for(shorter, fit0.center, fit0.radius, fit0.k, lambda n: at[n])
    assert got[0][0].arc.frechet == expected.frechet
    failed = window_solve.solve(
        state, dict(state.groups), seeds, node_groups, **keywords, bound=np.inf, regroup=lambda *a: None
    )
    assert failed is None


def test_an_arc_memoized_is_the_arc_extracted_again_for_the_same_pixels_circle_and_ends():
    graph, _ = golden_chain()
    state = hand_built_state(graph)
    initial_fit(state)
    group, fit = state.groups[0], state.fits[0]
    at = state.disp.__getitem__
    memo: dict = {}
    first = state.arc_for(group, fit.center, fit.radius, fit.k, at, memo)
    assert first == state.arc_for(group, fit.center, fit.radius, fit.k, at) and len(memo) == 1
    assert state.arc_for(group, fit.center, fit.radius, fit.k, at, memo) is first  # read back
    # Another group's circle and ends: its own arc; another pixel array (equal values, another object): anew.
    other, fit1 = state.groups[1], state.fits[1]
    assert state.arc_for(other, fit1.center, fit1.radius, fit1.k, at, memo) == fit1.arc and len(memo) == 2
    copy = dataclasses.replace(group, points=group.points.copy())
    assert state.arc_for(copy, fit.center, fit.radius, fit.k, at, memo) is not first and len(memo) == 3


# --------------------------------------------------------------------------- topology
def test_open_ends_are_the_free_ends_and_a_gap_is_one_0_75_to_6_px_from_another_arc():
    for tip, gaps in ((7.5, set()), (3.0, {4}), (0.2, set())):
        state = hand_built_state(line_and_a_stroke(120.5, tip))
        initial_fit(state)
        assert open_ends(state) == [(0, 0), (2, 1), (3, 2), (4, 2)]  # node 1 joins two arcs: not open
        assert gap_ends(state) == gaps, tip  # 7.5 px: a free end; 3 px: a near miss; 0.2 px: joined (0.55 px)


def test_redundant_pairs_are_the_groups_whose_arcs_cross_away_from_their_junctions():
    state = hand_built_state(line_and_a_stroke(120.5, -8.0))  # the stroke runs 8 px on across the line
    initial_fit(state)
    assert redundant_pairs(state) == [(0, 2)] and redundant_pairs(state, of={1}) == []
    state = hand_built_state(line_and_a_stroke(120.5, 3.0))
    initial_fit(state)
    assert redundant_pairs(state) == []


def test_reach_is_half_the_widest_span_of_the_junctions_a_circle_must_pass():
    # Cached by the group's path: the same answer asked again, a new one once a junction is released
    # or the rest points are another array (a biarc's start moves them for one fit).
    graph, _ = golden_chain()
    state = hand_built_state(graph)
    merged = merge_groups(merge_groups(state.groups[0], state.groups[1], 1), state.groups[2], 2)
    j = graph.junctions
    assert state.reach(merged) == 0.5 * float(np.hypot(*(j[0] - j[3])))  # nodes 1 and 2 are inner, of valence 2
    moved = j.copy()
    moved[3] += (0.0, 40.0)
    state.graph = dataclasses.replace(graph, junctions=moved)
    assert state.reach(merged) == 0.5 * float(np.hypot(*(j[0] - moved[3])))
    state.graph = graph
    assert state.reach(merged) == 0.5 * float(np.hypot(*(j[0] - j[3])))
    assert state.reach(state.groups[2]) == 0.5 * float(np.hypot(*(j[2] - j[3])))
    state.release(3)  # node 2 is all its circle must pass now: no span
    assert state.reach(state.groups[2]) == 0.0


def test_an_arcs_floor_is_at_most_its_frechet_distance():
    # The bound the tangent pass rejects a refit by before extracting its arcs: never above the
    # extracted arc's discrete Fréchet distance; the pixels' largest distance from the circle.
    from img2logo.fit.arc_extraction import extract_arc
    from img2logo.fit.window_solve import arc_floor
    from img2logo.geometry.primitives import Circle

    rng = np.random.default_rng(3)
    for _ in range(200):
        r, c = float(rng.uniform(5.0, 400.0)), rng.uniform(-50.0, 50.0, 2)
        t = np.linspace(0.0, rng.uniform(0.3, 5.0), int(rng.integers(3, 120)))
        points = c + (r + rng.normal(0.0, rng.uniform(0.0, 4.0), len(t)))[:, None] * np.stack([np.cos(t), np.sin(t)], 1)
        ends = c + r * np.stack([np.cos(t[[0, -1]]), np.sin(t[[0, -1]])], 1)
        fit = extract_arc(Circle(float(c[0]), float(c[1]), r), points, ends)
        floor = arc_floor(points, c, r)
        assert 0.0 <= floor <= fit.frechet
        assert floor == pytest.approx(np.max(np.abs(np.hypot(*(points - c).T) - r)), abs=1e-6)
