"""Tests of img2logo.fit_state: the optimizer's state, its seeds, fits, counts and mirror-axis hooks."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from helpers import golden_chain, golden_radius, hand_built_state

from img2logo.fit_state import FitState, FreeCircles, GroupFit, Seed, Stats, on_axis
from img2logo.progressive import initial_fit, optimize
from img2logo.simplification import merge_groups
from img2logo.symmetry import HalfAxis

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
    from img2logo.segment_graph import SegmentGraph

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
