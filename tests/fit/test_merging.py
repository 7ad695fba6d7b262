"""Tests of img2logo.fit.merging: candidate pairs, their evaluation and the greedy loop (Sec. 5.2)."""

from __future__ import annotations

import dataclasses
import itertools

import numpy as np
import pytest
from helpers import DATA, golden_chain, golden_radius, hand_built_state, line_and_a_stroke, sampled_arc

from img2logo import build_segment_graph, extract_feature_lines, quality
from img2logo.fit import window_solve
from img2logo.fit.arc_extraction import ArcFit
from img2logo.fit.constants import FAR_ARC_RETRY, MERGE_FALLBACK_RINGS
from img2logo.fit.fit_state import FitState
from img2logo.fit.fit_values import GroupFit
from img2logo.fit.intersections import redundant_intersections
from img2logo.fit.merge_checks import gap_ends, new_gaps
from img2logo.fit.merging import candidates, evaluate, merge_loop
from img2logo.fit.progressive import initial_fit, optimize
from img2logo.fit.simplification import Group, merge_groups
from img2logo.fit.symmetry import HalfAxis
from img2logo.geometry.primitives import Arc, Circle
from img2logo.segment_graph import SegmentGraph

#: The evaluation set of ``make quality``.
BENCH = DATA.parent / "benchmarks" / "data"


class _Unsolvable(FitState):
    """A state whose constrained fits (Eqn. 13) fail once ``failing`` is set: the rules after a failed window."""

    failing = False

    @property
    def tried(self):  # the (rings, first ring, tangent) of every failed solve
        return self.__dict__.setdefault("_tried", [])


@pytest.fixture(autouse=True)
def _unsolvable_fails(monkeypatch):
    """:func:`~img2logo.fit.window_solve.solve` of an :class:`_Unsolvable` state fails once it is ``failing``."""
    solve = window_solve.solve

    def solve_unless_failing(state, *args, **kwargs):
        if getattr(state, "failing", False):
            state.tried.append((kwargs.get("rings", 1), kwargs.get("first_ring", 1), bool(kwargs.get("tangent"))))
            return None
        return solve(state, *args, **kwargs)

    monkeypatch.setattr(window_solve, "solve", solve_unless_failing)


def _fitted_chain(cls=FitState, **settings):
    """The golden chain (three arcs k = 8, 9, 10 in an S) as a fitted state, one group per segment."""
    graph, _ = golden_chain()
    state = hand_built_state(graph, cls, **settings)
    initial_fit(state)
    return state


def _plus():
    """Four straight segments from a centre node 0 to nodes 1 (east), 2 (south), 3 (west), 4 (north)."""
    o = np.array([50.5, 50.5])
    ends = [o + 30 * np.array(d) for d in ((1, 0), (0, 1), (-1, 0), (0, -1))]
    segments = tuple(np.linspace(o, e, 31) for e in ends)
    return SegmentGraph(segments, np.array([o, *ends]), np.array([[0, 1], [0, 2], [0, 3], [0, 4]]), 100, 100)


# --------------------------------------------------------------------------- candidates
def test_candidates_are_the_pairs_of_groups_with_a_common_end():
    graph, _ = golden_chain()
    assert candidates(hand_built_state(graph)) == [(0, 1, 1), (1, 2, 2)]
    plus = hand_built_state(_plus())
    assert candidates(plus) == [(0, 1, 0), (0, 2, 0), (0, 3, 0), (1, 2, 0), (1, 3, 0), (2, 3, 0)]


def test_locked_and_closed_groups_and_the_mirror_axis_are_never_merged():
    graph, _ = golden_chain()
    state = hand_built_state(graph)
    state.groups[1] = dataclasses.replace(state.groups[1], locked=True)  # Sec. 7, Fig. 16
    assert candidates(state) == []
    state = hand_built_state(graph)
    loop = Group((0, 1), (1, 0, 1), np.vstack([graph.segments[0][::-1], graph.segments[0]]), False)
    state.groups[0] = loop  # a closed group: it has no free end to join
    assert loop.closed and candidates(state) == [(1, 2, 2)]
    axis = HalfAxis(0.0, frozenset({1}), frozenset())
    mirrored = FitState(graph, state.options, state.ladder, axis)
    for g in hand_built_state(graph).groups.values():
        mirrored.add_group(g)
    assert candidates(mirrored) == [(1, 2, 2)]  # no arc runs on through the axis at node 1


# --------------------------------------------------------------------------- evaluate, rule by rule
def test_an_exact_merge_is_scored_by_its_change_of_es():
    state = _fitted_chain()
    before = state.totals()
    out = evaluate(state, (0, 1, 1))
    assert out is not None and out.pair == (0, 1, 1) and not out.global_solve and out.redundant == 0
    assert out.merged.segments == (0, 1) and -1 in out.fits
    assert out.delta_j == -1  # node 1 leaves J'
    assert out.delta_f == pytest.approx(
        sum(f.arc.frechet for f in out.fits.values())
        - sum(state.fits[g].arc.frechet for g in {0, 1} | (set(out.fits) - {-1}))
    )
    assert state.totals() == before and sorted(state.groups) == [0, 1, 2]  # tentative: the state is unchanged
    assert state.stats.evaluated == 1 and state.stats.local_failed == 0


def test_a_merge_through_a_junction_another_arc_runs_on_through_is_rejected():
    # Groups 0 (east) and 2 (west) ending at the centre, where north-south runs on: merging them makes an X.
    state = hand_built_state(_plus())
    south, north = state.groups.pop(1), state.groups.pop(3)
    state.add_group(merge_groups(south, north, 0))
    assert evaluate(state, (0, 2, 0)) is None
    assert state.stats.rejected_crossing == 1 and state.stats.global_solves == 0


def test_a_hopeless_merge_is_rejected_without_a_global_solve():
    # The S of arcs 8 and 9 is 6.2 px from its best golden circle: above T = 0.5 once its window fails.
    state = _fitted_chain(_Unsolvable, tolerance=0.5)
    solves = state.stats.global_solves
    assert state.golden_error(merge_groups(state.groups[0], state.groups[1], 1)) > 0.5
    state.failing = True
    assert evaluate(state, (0, 1, 1)) is None
    assert state.stats.local_failed == 1 and state.stats.rejected_hopeless == 1
    assert state.stats.global_solves == solves


def test_a_merge_whose_wider_window_fails_is_rejected_without_a_global_solve():
    state = _fitted_chain(_Unsolvable, tolerance=100.0, tangency=False)
    solves = state.stats.global_solves
    state.failing = True
    assert evaluate(state, (0, 1, 1)) is None
    assert state.stats.local_failed == 1 and state.stats.rejected_hopeless == 0 and state.stats.wide_windows == 1
    # The two rings of the local window, then the wider window from its third ring on; never the whole graph.
    assert state.tried == [(2, 1, False), (MERGE_FALLBACK_RINGS, 3, False)]
    assert state.stats.global_solves == solves
    # With a smooth join held tangent (node 2), each window is tried with it, then without.
    state = _fitted_chain(_Unsolvable, tolerance=100.0)
    state.failing = True
    assert evaluate(state, (0, 1, 1)) is None
    wide = MERGE_FALLBACK_RINGS
    assert state.tried == [(2, 1, True), (2, 1, False), (wide, 3, True), (wide, 3, False)]
    # Without localized fitting the global problem is the only one solved.
    state = _fitted_chain(_Unsolvable, localized=False)
    state.failing = True
    assert evaluate(state, (0, 1, 1)) is None and state.stats.local_failed == 0 and state.stats.wide_windows == 0


def test_a_merged_arc_farther_than_the_bound_is_rejected():
    free = evaluate(_fitted_chain(), (0, 1, 1))
    assert free is not None and free.fits[-1].arc.frechet > 10.0  # one arc for the S: far from its pixels
    state = _fitted_chain(max_arc_distance=10.0)
    assert evaluate(state, (0, 1, 1)) is None and state.stats.rejected_far_arc == 1


def test_a_merged_arc_no_circle_of_its_radius_brings_near_is_rejected_before_its_fit():
    state = _fitted_chain(_Unsolvable, max_arc_distance=10.0)
    state.failing = True  # a fit would fail: the candidate must not get that far
    assert evaluate(state, (0, 1, 1)) is None
    assert state.stats.rejected_far_arc == 1 and state.stats.local_failed == 0
    assert list(state.far_arcs.values()) == [True]  # the proof is made once per merged group and radius
    # ... and the pair's two groups, under this T (past T the bound grows: the pair is proved again)
    assert state.far_pairs == {(0, 1, 1): (state.groups[0], state.groups[1], 0, state.options.tolerance)}
    # The loop evaluates it again only once a merge changed one of the two (``tried``): then it is gone.
    tried: set[int] = set()
    assert evaluate(state, (0, 1, 1), tried) is None and state.stats.rejected_far_arc == 2 and tried == {0, 1}
    state.options = dataclasses.replace(state.options, tolerance=2 * state.options.tolerance)  # past T
    assert evaluate(state, (0, 1, 1)) is None and state.far_pairs[0, 1, 1][3] == state.options.tolerance
    # Another group under one of the ids (a tangent join's slide splits pixels anew): proved again.
    state.groups[0] = dataclasses.replace(state.groups[0])
    state.far_arcs.clear()
    assert evaluate(state, (0, 1, 1)) is None and state.stats.rejected_far_arc == 4 and state.far_arcs
    # A bound the merged arc meets: no proof, the fit decides.
    state = _fitted_chain(max_arc_distance=1000.0)
    assert evaluate(state, (0, 1, 1)) is not None and list(state.far_arcs.values()) == [False]


def test_the_far_circle_proof_never_excludes_a_circle_that_comes_near():
    from img2logo._compiled import kernels

    rng = np.random.default_rng(7)
    # Points on a circle of radius 40 (a 2 rad arc), with noise.
    t = np.linspace(0.0, 2.0, 60)
    pts = np.c_[100 + 40 * np.cos(t), 100 + 40 * np.sin(t)] + rng.normal(0, 0.5, (60, 2))
    pts = np.ascontiguousarray(pts)
    start = (100.0, 100.0)
    assert not kernels.far_circle_kernel(pts, 40.0, *start, 2.0, 20000)  # its own circle is near
    assert kernels.far_circle_kernel(pts, 15.0, *start, 2.0, 20000)  # too small to reach along it
    assert kernels.far_circle_kernel(pts, 400.0, *start, 2.0, 20000)  # too flat for its bend
    # Whenever it proves a radius far, no centre of a fine grid brings every point within the bound.
    xs = np.linspace(-400, 600, 401)
    grid = np.stack(np.meshgrid(xs, xs), axis=-1).reshape(-1, 2)
    dist = np.hypot(grid[:, None, 0] - pts[None, ::3, 0], grid[:, None, 1] - pts[None, ::3, 1])
    for r in (25.0, 30.0, 35.0, 45.0, 60.0, 90.0, 150.0):
        for bound in (1.0, 3.0, 6.0, 12.0):
            if kernels.far_circle_kernel(pts, r, *start, bound, 20000):
                assert np.abs(dist - r).max(axis=1).min() > bound


def _arc_and_a_stroke_across_it():
    """Two arcs of one golden circle (k = 9) end to end, and a 16 px straight stroke across the first."""
    c, r = np.array([150.0, 150.0]), golden_radius(9)
    a, b = sampled_arc(c, r, 0.0, 1.0), sampled_arc(c, r, 1.0, 2.0)
    u = np.array([np.cos(0.5), np.sin(0.5)])
    stroke = np.linspace(c + (r - 8) * u, c + (r + 8) * u, 17)
    junctions = np.array([a[0], a[-1], b[-1], stroke[0], stroke[-1]])
    return SegmentGraph((a, b, stroke), junctions, np.array([[0, 1], [1, 2], [3, 4]]), 300, 300)


def test_a_merge_that_leaves_a_redundant_intersection_is_counted_and_not_made():
    state = hand_built_state(_arc_and_a_stroke_across_it())
    initial_fit(state)
    out = evaluate(state, (0, 1, 1))
    assert out is not None and out.redundant == 1 and out.fits[-1].arc.frechet < 1.0  # a good arc, but it crosses
    assert merge_loop(state, 5.0) == "no mergeable pair"
    assert state.stats.rejected_intersections == 1 and sorted(state.groups) == [0, 1, 2]
    # Without the avoidance (Fig. 12) the crossing is not looked for, and the two arcs merge.
    state = hand_built_state(_arc_and_a_stroke_across_it(), avoid_intersections=False)
    initial_fit(state)
    assert evaluate(state, (0, 1, 1)).redundant == 0
    assert merge_loop(state, 5.0) == "no mergeable pair" and len(state.groups) == 2


def _sagging(sag: float) -> GroupFit:
    """A fit of the whole line from (50.5, 100.5) to (250.5, 100.5) whose arc sags ``sag`` px in its middle."""
    r = (100.0**2 + sag**2) / (2 * sag)
    circle = Circle(150.5, 100.5 + sag - r, r)
    t0, t1 = circle.angle_of(np.array([[50.5, 100.5], [250.5, 100.5]]))
    return GroupFit(circle.center, r, None, ArcFit(Arc(circle, float(t0), float(t1 - t0)), 0.0))


def test_a_merge_that_brings_a_free_end_within_a_near_miss_is_counted_and_not_made():
    # The stroke's tip (node 4) is 7.5 px below the line: a free end, no gap. A merge of the line
    # whose arc sagged 3 px would leave it 4.5 px from the arc: a near-miss gap it made.
    state = hand_built_state(line_and_a_stroke(150.5, 7.5))
    initial_fit(state)
    assert gap_ends(state) == set()
    assert new_gaps(state, (0, 1, 1), {-1: _sagging(3.0)}, {}) == 1
    assert new_gaps(state, (0, 1, 1), {-1: _sagging(0.5)}, {}) == 0  # 7 px: still a free end
    assert new_gaps(state, (0, 1, 1), {-1: _sagging(7.2)}, {}) == 0  # 0.3 px: joined
    # The refit moving the free end itself counts too: the stroke's tip 3 px nearer.
    stroke = dataclasses.replace(state.fits[2])
    assert new_gaps(state, (0, 1, 1), {-1: _sagging(0.5), 2: stroke}, {4: np.array([0.0, -3.0])}) == 1
    # A gap the input has already is no reason to refuse the merge.
    state = hand_built_state(line_and_a_stroke(150.5, 3.0))
    initial_fit(state)
    assert gap_ends(state) == {4} and new_gaps(state, (0, 1, 1), {-1: _sagging(0.5)}, {}) == 0
    out = evaluate(state, (0, 1, 1))
    assert out is not None and out.gaps == 0 and out.redundant == 0


def test_the_loop_refuses_a_merge_that_would_leave_a_near_miss_gap(monkeypatch):
    import img2logo.fit.merging as merging

    state = hand_built_state(line_and_a_stroke(150.5, 7.5))
    initial_fit(state)
    # Every refit of the line sags 3 px (as the coffee cup's rim's did), then the loop must not merge.
    real = merging.evaluate

    def sagging(state, pair, tried=None, level=None):
        out = real(state, pair, tried, level)
        if out is None or pair[:2] != (0, 1):
            return out
        fits = {**out.fits, -1: _sagging(3.0)}
        return dataclasses.replace(out, fits=fits, gaps=new_gaps(state, pair, fits, out.displacements))

    monkeypatch.setattr(merging, "evaluate", sagging)
    assert merge_loop(state, 50.0) == "no mergeable pair"
    assert sorted(state.groups) == [0, 1, 2] and state.stats.rejected_gaps == 1


def test_no_merged_arc_runs_on_through_a_junction_another_arc_runs_on_through():
    # Regression: on the clip-art cactus at T = 9 an arm's outline merged into an arc from one of
    # its inner junctions to the other, running on across the stem at its two end nodes (an X at each).
    graph = build_segment_graph(extract_feature_lines(BENCH / "clipart-cactus.png"))
    prog = optimize(graph, tolerance=9.0)
    level = prog.final
    runs: dict[int, set[int]] = {}
    for i, t in enumerate(level.arc_junctions):
        for j in t.through:
            runs.setdefault(j, set()).add(i)
    assert all(len(arcs) == 1 for arcs in runs.values())
    assert len(quality.crossings(level)) == 0 and prog.stats["rejected_crossing"] > 0


# --------------------------------------------------------------------------- the loop
def test_the_loop_reports_every_merge_through_its_callback():
    state = _fitted_chain()
    seen = []
    stopped = merge_loop(state, 50.0, lambda s: seen.append((len(s.groups), s.similarity())))
    assert stopped == "no mergeable pair" and [n for n, _ in seen] == [2, 1] and len(state.groups) == 1
    assert seen[-1][1] == pytest.approx(state.similarity())
    state = _fitted_chain()
    assert merge_loop(state, 0.0) == "tolerance" and len(state.groups) == 3  # no merge is within T = 0


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

    from img2logo.features.preprocessing import FeatureLines

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


# --------------------------------------------------------------------------- tangent joins (beyond the paper)
def _touch(state, out, node, pair):
    """How far two circles of a merge's outcome are from touching at ``node``: |sin| of the angle of their radii x r."""
    fits = {**state.fits, **out.fits}
    p = state.graph.junctions[node] + out.displacements.get(node, state.disp[node])
    a, b = (fits[g].center - p for g in pair)
    sin = abs(float(a[0] * b[1] - a[1] * b[0])) / float(np.hypot(*a) * np.hypot(*b))
    return sin * min(fits[g].radius for g in pair)


def _arc_then_bend(**settings):
    """One golden circle (k = 9) cut in two segments, then a circle off the ladder touching it: fitted, one group each.

    Segments 0 and 1 meet at node 1 on the first circle; segment 2 runs on
    from node 2 on a circle of 1.3 x r(k = 8) that touches it from outside.
    """
    r1, r2 = golden_radius(9), 1.3 * golden_radius(8)
    c1 = np.array([200.0, 200.0])
    a0 = sampled_arc(c1, r1, np.pi, 0.75 * np.pi)
    a1 = sampled_arc(c1, r1, 0.75 * np.pi, 0.5 * np.pi)
    j2 = a1[-1]
    c2 = j2 + (j2 - c1) / r1 * r2
    a2 = sampled_arc(c2, r2, -0.5 * np.pi, -0.5 * np.pi + 1.0)
    graph = SegmentGraph(
        (a0, a1, a2), np.array([a0[0], a0[-1], j2, a2[-1]]), np.array([[0, 1], [1, 2], [2, 3]]), 600, 600
    )
    state = hand_built_state(graph, **settings)
    initial_fit(state)
    return state


def test_a_merge_is_judged_with_the_smooth_join_it_ends_at_tangent():
    from img2logo.fit.merging import held_joins

    state = _arc_then_bend()
    assert state.smooth == {1, 2}
    after = {-1: merge_groups(state.groups[0], state.groups[1], 1), 2: state.groups[2]}
    seeds = {2: state.fits[2].seed, -1: state.golden(after[-1])}
    # The merged arc ends at node 2, a smooth join with group 2; node 1 is inside it now.
    held = held_joins(state, seeds, after[-1], (0, 1, 1))
    assert held == {2: (2, -1)}
    # The joins of FitState.tangencies after the merge, the two groups in its order (the merged one last).
    assert held == {n: p for n, p in state.tangencies({2: after[2], -1: after[-1]}, seeds).items() if n in held}
    out = evaluate(state, (0, 1, 1))
    assert out is not None and not out.global_solve
    assert _touch(state, out, 2, (-1, 2)) <= 1e-6
    # Without tangency (the paper's fit) the circles of the snapped radii kink there.
    paper = _arc_then_bend(tangency=False)
    assert paper.smooth == frozenset()
    out = evaluate(paper, (0, 1, 1))
    assert out is not None and _touch(paper, out, 2, (-1, 2)) > 1e-3


def test_the_loop_keeps_the_tangencies_it_made():
    state = _arc_then_bend()
    assert merge_loop(state, 10.0) == "tolerance"
    # The one circle's two segments merged; the join it ends at is tangent and held for later merges.
    assert sorted(g.segments for g in state.groups.values()) == [(0, 1), (2,)]
    assert state.held == state.touching_joins({2}) == {2}


def test_a_far_merged_arc_is_found_before_the_windows_other_arcs():
    state = _fitted_chain(max_arc_distance=10.0)
    calls = []
    arc_for = state.arc_for
    state.arc_for = lambda group, *a: calls.append(group) or arc_for(group, *a)
    merged = merge_groups(state.groups[0], state.groups[1], 1)
    key = (merged.segments, merged.nodes, float(state.golden(merged).radius), 10.0)
    state.far_arcs[key] = False  # not proved far (under the bound of 10 px)
    assert evaluate(state, (0, 1, 1)) is None and state.stats.rejected_far_arc == 1
    assert len(calls) == 1  # the merged arc only: the merge is rejected on it
    state = _fitted_chain()
    out = evaluate(state, (0, 1, 1))
    assert out is not None and sorted(out.fits) == [-1, 2]  # without a bound, the window's arcs


def test_a_merged_arc_far_past_the_bound_is_refitted_again_only_once_its_window_changed():
    frechet = evaluate(_fitted_chain(), (0, 1, 1)).fits[-1].arc.frechet
    # Far past the bound: the window's groups go to ``tried`` (the merged group's as the pair's two), as
    # for a failed refit, so that the loop refits it again only once a merge changed one of them.
    # Just past it (within FAR_ARC_RETRY times the bound): refitted at every level, none go.
    for bound, window in ((frechet / (2 * FAR_ARC_RETRY), {0, 1, 2}), (frechet / (0.5 + 0.5 * FAR_ARC_RETRY), set())):
        state = _fitted_chain(max_arc_distance=bound)
        merged = merge_groups(state.groups[0], state.groups[1], 1)
        state.far_arcs[(merged.segments, merged.nodes, float(state.golden(merged).radius), bound)] = False
        tried: set[int] = set()
        assert evaluate(state, (0, 1, 1), tried) is None and state.stats.rejected_far_arc == 1
        assert tried == window


def test_the_levels_arrays_are_made_again_after_a_merge():
    from img2logo.fit.merge_checks import level_view

    state = _fitted_chain()
    first = level_view(state)
    assert level_view(state) is first and first.gids == (0, 1, 2) and first.inner == {}
    assert first.ends == state.end_groups()
    out = evaluate(state, (0, 1, 1))
    state.merge(0, 1, out.merged, out.fits, out.displacements)
    again = level_view(state)
    assert again is not first and again.gids == (2, 3) and again.inner == {1: [3]}
    assert again.flat.tolist() == [n for g in state.groups.values() for n in state.constrained_nodes(g)]


def _four_arcs_chain() -> SegmentGraph:
    """Four arcs of one golden circle (k = 9) end to end over 270 degrees, nodes 0 ... 4."""
    c, r = np.array([300.0, 300.0]), golden_radius(9)
    cuts = np.linspace(0.0, 1.5 * np.pi, 5)
    arcs = tuple(sampled_arc(c, r, t0, t1) for t0, t1 in itertools.pairwise(cuts))
    junctions = np.array([arcs[0][0], *(a[-1] for a in arcs)])
    return SegmentGraph(arcs, junctions, np.array([[i, i + 1] for i in range(4)]), 600, 600)


@pytest.mark.parametrize("whole", [False, True])
def test_a_failed_candidate_is_tried_again_only_once_a_merge_changed_its_windows(monkeypatch, whole):
    # (1, 2) and (2, 3) fail; (0, 1) is merged first. The refit of (2, 3) held group 3 alone
    # (whole False): merging (0, 1) left it as it was, and it is not tried again; holding every
    # group (whole True), the merge changed its windows and it is.
    from img2logo.fit import merging

    real, calls = merging.evaluate, []

    def evaluate_(state, pair, tried=None, level=None):
        calls.append(pair)
        if pair[:2] in ((1, 2), (2, 3)):
            state.stats.evaluated += 1
            tried.update(set(state.groups) if whole else {pair[1]})
            return None
        return real(state, pair, tried, level)

    monkeypatch.setattr(merging, "evaluate", evaluate_)
    state = hand_built_state(_four_arcs_chain(), tangency=False)
    initial_fit(state)
    merging.merge_loop(state, 5.0)
    assert calls[:3] == [(0, 1, 1), (1, 2, 2), (2, 3, 3)]
    assert calls.count((2, 3, 3)) == (2 if whole else 1)
