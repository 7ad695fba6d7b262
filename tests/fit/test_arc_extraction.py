"""Arc extraction (Sec. 5.3, Fig. 9) and redundant intersections (Sec. 5.2, Fig. 6, 12)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import frechet_table

from img2logo.errors import FitError, InvalidParameterError
from img2logo.fit.arc_extraction import ArcFit, discrete_frechet, extract_arc, frechet_distance
from img2logo.fit.intersections import arc_intersections, redundant_intersections
from img2logo.geometry.primitives import TAU, Arc, Circle

CIRCLE = Circle(100.0, 100.0, 50.0)


def on_circle(t0: float, t1: float, circle: Circle = CIRCLE) -> np.ndarray:
    """Points of ``circle`` from angle t0 to t1, about 1 px apart."""
    n = max(2, math.ceil(abs(t1 - t0) * circle.r) + 1)
    return circle.point_at(np.linspace(t0, t1, n))


def angle_diff(a: float, b: float) -> float:
    return abs(math.remainder(a - b, TAU))


def rows(points: object) -> list[tuple[float, ...]]:
    """Points as sorted rounded tuples, to compare sets of points."""
    return sorted(tuple(p) for p in np.round(np.asarray(points, dtype=float).reshape(-1, 2), 9))


# --------------------------------------------------------------------------- Fréchet
def test_frechet_of_identical_curves_is_zero() -> None:
    p = on_circle(0.0, 2.0)
    assert frechet_distance(p, p) == 0.0


def test_frechet_of_parallel_lines_is_their_offset() -> None:
    x = np.linspace(0.0, 100.0, 101)
    assert frechet_distance(np.column_stack([x, 0 * x]), np.column_stack([x, 0 * x + 3.5])) == pytest.approx(3.5)


def test_frechet_matches_the_reference_on_random_curves() -> None:
    rng = np.random.default_rng(7)
    for trial in range(150):
        n, m = rng.integers(1, 25, 2)
        p = np.cumsum(rng.normal(size=(n, 2)), axis=0)
        q = np.cumsum(rng.normal(size=(m, 2)), axis=0) if trial % 2 else p[np.sort(rng.integers(0, n, m))] + 0.2
        assert frechet_distance(p, q) == pytest.approx(frechet_table(p, q), abs=1e-12)


def test_frechet_of_unequal_long_curves_matches_the_reference() -> None:
    rng = np.random.default_rng(8)
    p, q = rng.normal(size=(40, 2)), rng.normal(size=(300, 2))
    assert frechet_distance(p, q) == pytest.approx(frechet_table(p, q), abs=1e-12)
    assert frechet_distance(q[:5], p) == pytest.approx(frechet_table(q[:5], p), abs=1e-12)
    assert frechet_distance(p[:1], q) == pytest.approx(frechet_table(p[:1], q), abs=1e-12)


def test_frechet_of_one_point_is_its_largest_distance() -> None:
    q = np.array([[0.0, 0.0], [3.0, 4.0], [1.0, 0.0]])
    assert frechet_distance([[0.0, 0.0]], q) == pytest.approx(5.0)
    assert frechet_distance(q, [[0.0, 0.0]]) == pytest.approx(5.0)
    assert frechet_distance([[1.0, 1.0]], [[4.0, 5.0]]) == pytest.approx(5.0)


def test_frechet_is_symmetric_and_sees_direction() -> None:
    t = np.linspace(0.0, 1.0, 51)
    p, q = CIRCLE.point_at(t), Circle(100.0, 100.0, 52.0).point_at(t)
    assert frechet_distance(p, q) == pytest.approx(2.0)
    assert frechet_distance(p, q[::3]) == pytest.approx(frechet_distance(q[::3], p))
    assert frechet_distance(p, q[::-1]) > 40.0


def test_bounded_frechet_stops_early_only_when_it_cannot_win() -> None:
    rng = np.random.default_rng(9)
    p, q = rng.normal(size=(60, 2)), rng.normal(size=(70, 2)) * 3
    exact = frechet_table(p, q)
    assert discrete_frechet(p, q, bound=exact + 1e-9) == pytest.approx(exact)
    assert discrete_frechet(p, q, bound=exact * 0.5) == math.inf


@pytest.mark.parametrize("seed", range(4))
def test_banded_frechet_is_the_whole_table_bit_for_bit(seed) -> None:
    # The kernel fills only a band of the table (cells within a greedy coupling's distance):
    # the same number as the whole table, also on integer pixels (ties), one-point curves,
    # curves far apart and near ones; with a bound, the same number below it and inf or at
    # least the bound otherwise.
    rng = np.random.default_rng(seed)
    for trial in range(150):
        n, m = (int(v) for v in rng.integers(1, 40, 2))
        p = np.cumsum(rng.normal(size=(n, 2)), axis=0) * rng.uniform(0.2, 3.0)
        if trial % 3 == 0:  # a noisy copy of p, resampled: the band is narrow
            q = p[np.sort(rng.integers(0, n, m))] + rng.normal(size=(m, 2)) * 0.4
        else:
            q = np.cumsum(rng.normal(size=(m, 2)), axis=0) * rng.uniform(0.2, 3.0) + rng.normal(size=2) * 5
        if trial % 4 == 0:
            p, q = np.round(p), np.round(q)
        exact = frechet_table(p, q)
        assert discrete_frechet(p, q) == exact
        for bound in (exact, exact * 1.5 + 1e-9, exact * rng.uniform(0.0, 1.0)):
            got = discrete_frechet(p, q, bound=bound)
            assert got == exact if exact < bound else got >= bound


def test_extract_arc_with_a_far_first_candidate_matches_the_whole_table(monkeypatch) -> None:
    # Two junctions a third of a circle apart and the pixels along the short arc between them,
    # clockwise: the long arc (far from the pixels) comes first among candidates of equal lower
    # bound. Cut at the nearest option's greedy coupling, it costs a band, not a whole table;
    # the arc and its distance are those of the whole tables.
    import img2logo.fit.arc_extraction as extraction

    circle = Circle(0.0, 0.0, 40.0)
    seg = circle.point_at(np.linspace(0.0, -2.1, 90)) + np.random.default_rng(3).normal(0.0, 0.6, (90, 2))
    junctions = circle.point_at(np.array([0.0, -2.1]))
    tried = []
    monkeypatch.setattr(
        extraction, "discrete_frechet", lambda p, q, bound=math.inf: tried.append(len(q)) or frechet_table(p, q)
    )
    kept, cap = extraction.admissible_arcs(circle, seg, junctions)
    want = extraction.best_by_frechet(kept, seg, cap)  # the compiled extraction's Python reference
    assert tried[0] > 150  # the long way round first
    monkeypatch.undo()
    got = extract_arc(circle, seg, junctions)
    assert (got.arc.theta0, got.arc.sweep, got.frechet) == (want.arc.theta0, want.arc.sweep, want.frechet)
    assert got.arc.sweep == pytest.approx(-2.1)


@pytest.mark.parametrize(
    ("p", "message"),
    [
        (np.zeros(3), r"p must have shape \(N, 2\), got \(3,\)"),
        (np.zeros((0, 2)), "p must have at least 1 points, got 0"),
        ([[0.0, math.nan]], "p must be finite"),
    ],
)
def test_frechet_rejects_bad_curves(p: object, message: str) -> None:
    with pytest.raises(InvalidParameterError, match=message):
        frechet_distance(p, np.zeros((2, 2)))


# --------------------------------------------------------------------------- arc extraction
def test_extract_arc_recovers_a_noisy_arc_the_short_way() -> None:
    rng = np.random.default_rng(1)
    seg = on_circle(0.3, 1.7) + rng.normal(scale=0.3, size=(71, 2))
    fit = extract_arc(CIRCLE, seg, CIRCLE.point_at(np.array([0.3, 1.7])))
    assert isinstance(fit, ArcFit)
    assert angle_diff(fit.arc.theta0, 0.3) < 0.02
    assert fit.arc.sweep == pytest.approx(1.4, abs=0.02)
    assert fit.frechet < 1.5


def test_extract_arc_follows_the_direction_of_the_pixels() -> None:
    seg = on_circle(1.7, 0.3)
    fit = extract_arc(CIRCLE, seg, CIRCLE.point_at(np.array([1.7, 0.3])))
    assert angle_diff(fit.arc.theta0, 1.7) < 1e-9
    assert fit.arc.sweep == pytest.approx(-1.4)
    np.testing.assert_allclose(fit.arc.start, seg[0], atol=1e-9)


def test_extract_arc_goes_the_long_way_round_when_the_pixels_do() -> None:
    end = math.radians(300.0)
    seg = on_circle(0.0, end)
    fit = extract_arc(CIRCLE, seg, CIRCLE.point_at(np.array([0.0, end])))
    assert fit.arc.sweep == pytest.approx(end)
    assert fit.frechet < 1.0


@pytest.mark.parametrize("middle", [math.pi / 2, -math.pi / 2])
def test_a_middle_junction_forces_the_arc_through_it(middle: float) -> None:
    # Pixels along a diameter: both half circles are 50 px from them. The
    # junction in the middle decides which one the arc must take.
    seg = np.column_stack([np.linspace(150.0, 50.0, 101), np.full(101, 100.0)])
    junctions = CIRCLE.point_at(np.array([0.0, middle, math.pi]))
    fit = extract_arc(CIRCLE, seg, junctions)
    assert fit.arc.sweep == pytest.approx(math.copysign(math.pi, middle))
    assert angle_diff(fit.arc.theta0, 0.0) < 1e-12
    assert fit.frechet == pytest.approx(50.0)


def test_a_closed_loop_gives_the_whole_circle_from_its_node() -> None:
    seg = on_circle(1.0, 1.0 - TAU)  # once round, negative sense
    node = CIRCLE.point_at(1.0)
    fit = extract_arc(CIRCLE, seg, np.array([node, CIRCLE.point_at(-2.0), node]))
    assert fit.arc.is_full_circle
    assert fit.arc.sweep == pytest.approx(-TAU)
    np.testing.assert_allclose(fit.arc.start, node, atol=1e-9)
    assert fit.frechet < 1.0


def test_frechet_and_sum_of_squares_disagree_on_a_hook() -> None:
    # Fig. 9: the pixels leave the junction at 0 the wrong way (to -60 degrees),
    # come back and go on to the junction at 90 degrees. The short arc 0 -> 90
    # (Fréchet 50: its start waits while the hook is drawn) is the paper's pick.
    # The sum of squared distances to the arc only asks every pixel to be near
    # *some* part of it, so it prefers the 270 degree arc 0 -> -60 -> ... -> 90,
    # which covers the hook at the price of a redundant part nobody drew.
    hook = np.vstack([on_circle(0.0, -math.pi / 3), on_circle(-math.pi / 3, math.pi / 2)[1:]])
    junctions = CIRCLE.point_at(np.array([0.0, math.pi / 2]))
    by_frechet = extract_arc(CIRCLE, hook, junctions)
    by_squares = extract_arc(CIRCLE, hook, junctions, method="sum_of_squares")
    assert by_frechet.arc.sweep == pytest.approx(math.pi / 2)
    assert by_frechet.frechet == pytest.approx(50.0, abs=0.5)
    assert not by_frechet.arc.contains_angle(math.pi)
    assert abs(by_squares.arc.sweep) == pytest.approx(1.5 * math.pi)
    assert by_squares.arc.contains_angle(math.pi)  # the redundant part
    assert by_squares.frechet > by_frechet.frechet + 40.0


def test_frechet_and_sum_of_squares_agree_on_a_plain_arc() -> None:
    seg = on_circle(0.5, 2.5)
    junctions = CIRCLE.point_at(np.array([0.5, 2.5]))
    assert extract_arc(CIRCLE, seg, junctions, method="sum_of_squares").arc == extract_arc(CIRCLE, seg, junctions).arc


def test_the_long_way_round_of_a_huge_circle_is_skipped() -> None:
    huge = Circle(0.0, 1e6, 1e6)  # the long way round is 6.3 million px
    seg = on_circle(-math.pi / 2, -math.pi / 2 + 1e-4, huge)
    junctions = seg[[0, -1]]
    fit = extract_arc(huge, seg, junctions)
    assert fit.arc.length == pytest.approx(100.0, rel=1e-6)


def test_when_every_candidate_is_too_long_the_shortest_is_kept() -> None:
    seg = np.array([[150.0, 100.0], [150.0, 101.0]])  # 1 px of pixels between junctions 150 px apart
    junctions = CIRCLE.point_at(np.array([0.0, 3.0]))
    fit = extract_arc(CIRCLE, seg, junctions)
    assert abs(fit.arc.sweep) == pytest.approx(3.0)
    assert fit.frechet == pytest.approx(math.dist(seg[-1], junctions[1]), rel=0.05)
    # A closed loop on a huge circle: 6.3 million px, compared through 13 samples.
    huge = Circle(0.0, 1e6, 1e6)
    node = huge.point_at(-math.pi / 2)
    fit = extract_arc(huge, np.array([node, node + np.array([1.0, 0.0])]), np.array([node, node]))
    assert fit.arc.is_full_circle
    assert fit.frechet > 1e6


def test_extract_arc_rejects_a_junction_off_the_circle() -> None:
    junctions = np.array([CIRCLE.point_at(0.0), CIRCLE.point_at(1.0) + np.array([0.0, 0.5])])
    with pytest.raises(FitError, match=r"junction point 1 is 0\.\d+ px off the circle \(tolerance 0\.001 px\)"):
        extract_arc(CIRCLE, on_circle(0.0, 1.0), junctions)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"circle": (100, 100, 50)}, "circle must be a Circle, got tuple"),
        ({"segment_points": np.zeros(3)}, r"segment_points must have shape \(N, 2\), got \(3,\)"),
        ({"segment_points": np.zeros((1, 2))}, "segment_points must have at least 2 points, got 1"),
        ({"junction_points": CIRCLE.point_at(np.array([0.0]))}, "junction_points must have at least 2 points, got 1"),
        ({"method": "least_squares"}, "method must be one of 'frechet', 'sum_of_squares', got 'least_squares'"),
    ],
)
def test_extract_arc_rejects_bad_input(kwargs: dict, message: str) -> None:
    args = {
        "circle": CIRCLE,
        "segment_points": on_circle(0.0, 1.0),
        "junction_points": CIRCLE.point_at(np.array([0.0, 1.0])),
    }
    args.update(kwargs)
    method = args.pop("method", "frechet")
    with pytest.raises(InvalidParameterError, match=message):
        extract_arc(args["circle"], args["segment_points"], args["junction_points"], method=method)


# --------------------------------------------------------------------------- intersections
def test_two_crossing_arcs_meet_at_the_known_point() -> None:
    a = Arc(Circle(0.0, 0.0, 10.0), 0.0, math.pi)  # lower half (y down): y >= 0
    b = Arc(Circle(10.0, 0.0, 10.0), math.pi / 2, math.pi)
    np.testing.assert_allclose(arc_intersections(a, b), [[5.0, math.sqrt(75.0)]], atol=1e-12)
    full = Arc(a.circle, 0.0, TAU)
    pts = arc_intersections(full, Arc(b.circle, 0.0, TAU))
    assert rows(pts) == rows([[5.0, -math.sqrt(75.0)], [5.0, math.sqrt(75.0)]])


def test_disjoint_and_concentric_circles_do_not_meet() -> None:
    a = Arc(Circle(0.0, 0.0, 10.0), 0.0, TAU)
    assert arc_intersections(a, Arc(Circle(30.0, 0.0, 10.0), 0.0, TAU)).shape == (0, 2)
    assert arc_intersections(a, Arc(Circle(0.0, 0.0, 4.0), 0.0, TAU)).shape == (0, 2)
    assert arc_intersections(a, Arc(Circle(1.0, 0.0, 4.0), 0.0, TAU)).shape == (0, 2)  # inside


def test_circles_crossing_outside_the_angle_ranges_give_nothing() -> None:
    a = Arc(Circle(0.0, 0.0, 10.0), math.pi / 2, math.pi)  # the left half: x <= 0
    b = Arc(Circle(10.0, 0.0, 10.0), 0.0, TAU)  # crosses a's circle at x = 5 only
    assert arc_intersections(a, b).shape == (0, 2)


def test_tangent_circles_meet_once() -> None:
    a = Arc(Circle(0.0, 0.0, 10.0), 0.0, TAU)
    np.testing.assert_allclose(arc_intersections(a, Arc(Circle(16.0, 0.0, 6.0), 0.0, TAU)), [[10.0, 0.0]], atol=1e-9)
    np.testing.assert_allclose(arc_intersections(a, Arc(Circle(0.0, 4.0, 6.0), 0.0, TAU)), [[0.0, 10.0]], atol=1e-9)


def test_tangency_has_a_tolerance() -> None:
    a = Arc(Circle(0.0, 0.0, 100.0), 0.0, TAU)
    for gap in (5e-7, -5e-7, 0.0):  # apart, overlapping, exactly touching: once
        pts = arc_intersections(a, Arc(Circle(162.0 + 100.0 + gap, 0.0, 162.0), 0.0, TAU))
        np.testing.assert_allclose(pts, [[100.0, 0.0]], atol=1e-6)
    pts = arc_intersections(a, Arc(Circle(262.0 - 1e-3, 0.0, 162.0), 0.0, TAU))
    assert len(pts) == 2
    np.testing.assert_allclose(np.hypot(*(pts - [100.0, 0.0]).T), 0.35166, rtol=1e-3)
    assert arc_intersections(a, Arc(Circle(262.0 + 1e-3, 0.0, 162.0), 0.0, TAU)).shape == (0, 2)


def test_arcs_of_one_circle_meet_at_the_ends_of_their_overlap() -> None:
    c = Circle(0.0, 0.0, 10.0)
    q = math.pi / 2
    overlapping = arc_intersections(Arc(c, 0.0, 2 * q), Arc(c, q, 2 * q))  # overlap: q .. 2q
    assert rows(overlapping) == rows([c.point_at(q), c.point_at(2 * q)])
    touching = arc_intersections(Arc(c, 0.0, q), Arc(c, q, q))
    np.testing.assert_allclose(touching, [c.point_at(q)], atol=1e-9)
    assert arc_intersections(Arc(c, 0.0, q / 2), Arc(c, q, q)).shape == (0, 2)
    contained = arc_intersections(Arc(c, 0.0, TAU), Arc(c, -q, -q))
    assert rows(contained) == rows([c.point_at(-q), c.point_at(-2 * q)])
    assert arc_intersections(Arc(c, 0.0, TAU), Arc(c, 1.0, -TAU)).shape == (1, 2)


def test_arc_intersections_rejects_bad_input() -> None:
    a = Arc(CIRCLE, 0.0, 1.0)
    with pytest.raises(InvalidParameterError, match="b must be an Arc, got Circle"):
        arc_intersections(a, CIRCLE)  # type: ignore[arg-type]
    with pytest.raises(InvalidParameterError, match=r"tol must be >= 0, got -1\.0"):
        arc_intersections(a, a, tol=-1.0)


# --------------------------------------------------------------------------- redundant intersections
def test_arcs_meeting_only_at_their_shared_junction_are_fine() -> None:
    j = np.array([[10.0, 0.0], [0.0, 10.0], [-10.0, 0.0]])
    c = Circle(0.0, 0.0, 10.0)
    arcs = [Arc(c, 0.0, math.pi / 2), Arc(Circle(-10.0, 10.0, 10.0), 0.0, -math.pi / 2)]
    assert redundant_intersections(arcs, j, [[0, 1], [1, 2]]) == []
    # Touching inside at a junction both pass through, overlapping by a rounding
    # error: their circles cross twice, 0.05 px either side of it. Still fine.
    inner = Circle(0.0, 4.0 + 1e-4, 6.0)
    arcs = [Arc(c, math.pi / 4, math.pi / 2), Arc(inner, math.pi / 4, math.pi / 2)]
    crossings = arc_intersections(*arcs)
    assert len(crossings) == 2
    assert np.all(np.hypot(*(crossings - j[1]).T) < 0.1)
    assert redundant_intersections(arcs, j, [[1], [1]]) == []
    assert len(redundant_intersections(arcs, j, [[1], [0]])) == 2


def test_a_crossing_away_from_the_junctions_is_found() -> None:
    a = Arc(Circle(0.0, 0.0, 10.0), 0.0, math.pi)
    b = Arc(Circle(10.0, 0.0, 10.0), math.pi / 2, math.pi)
    junctions = np.vstack([a.start, a.end, b.start, b.end])
    found = redundant_intersections([a, b], junctions, [[0, 1], [2, 3]])
    assert len(found) == 1
    assert (found[0].arc_a, found[0].arc_b) == (0, 1)
    np.testing.assert_allclose(found[0].point, [5.0, math.sqrt(75.0)], atol=1e-12)
    assert not found[0].point.flags.writeable
    # Where they cross is a junction of only one of them: still redundant.
    junctions = np.vstack([junctions, [5.0, math.sqrt(75.0)]])
    assert len(redundant_intersections([a, b], junctions, [[0, 1, 4], [2, 3]])) == 1
    assert len(redundant_intersections([a, b], junctions, [[0, 1, 4], [2, 3, 4]])) == 0


def random_arcs(rng: np.random.Generator, n: int) -> list[Arc]:
    out = []
    for _ in range(n):
        c = Circle(*rng.uniform(0, 200, 2), rng.uniform(5, 60))
        out.append(Arc(c, rng.uniform(-math.pi, math.pi), rng.choice([-1, 1]) * rng.uniform(0.2, TAU)))
    return out


def test_candidates_give_the_full_check_restricted_to_their_pairs() -> None:
    rng = np.random.default_rng(3)
    arcs = random_arcs(rng, 40)
    junctions = np.array([p for a in arcs for p in (a.start, a.end)])
    arc_junctions = [[2 * i, 2 * i + 1] for i in range(len(arcs))]
    everything = redundant_intersections(arcs, junctions, arc_junctions)
    assert len(everything) > 20
    for cands in ([5], [0, 39], [3, 4, 5, 6]):
        part = redundant_intersections(arcs, junctions, arc_junctions, candidates=cands)
        expected = [r for r in everything if r.arc_a in cands or r.arc_b in cands]
        assert [(r.arc_a, r.arc_b) for r in part] == [(r.arc_a, r.arc_b) for r in expected]
        np.testing.assert_allclose([r.point for r in part], [r.point for r in expected])
    # The prefilter loses nothing: the same as the exact test on every pair.
    brute = [(i, j) for i in range(40) for j in range(i + 1, 40) for _ in arc_intersections(arcs[i], arcs[j])]
    assert [(r.arc_a, r.arc_b) for r in everything] == brute


@pytest.mark.parametrize(
    ("call", "message"),
    [
        (lambda a, j: redundant_intersections([a, "x"], j, [[0], [1]]), "arcs\\[1\\] must be an Arc, got str"),
        (lambda a, j: redundant_intersections([a, a], j, [[0]]), r"one entry per arc \(2\), got 1"),
        (lambda a, j: redundant_intersections([a, a], j, [[0], [2]]), r"arc_junctions\[1\] must index .* 0\.\.1"),
        (lambda a, j: redundant_intersections([a, a], j, [[0], [1]], candidates=[2]), r"candidates must index arcs"),
        (lambda a, j: redundant_intersections([a, a], j[0], [[0], [1]]), r"must have shape \(N, 2\), got \(2,\)"),
        (lambda a, j: redundant_intersections([a, a], j, [[0], [1]], tol=-1), "tol must be >= 0, got -1.0"),
    ],
)
def test_redundant_intersections_reject_bad_input(call, message: str) -> None:
    a = Arc(CIRCLE, 0.0, 1.0)
    with pytest.raises(InvalidParameterError, match=message):
        call(a, np.vstack([a.start, a.end]))


def test_redundant_intersections_of_fewer_than_two_arcs_are_none() -> None:
    a = Arc(CIRCLE, 0.0, 1.0)
    assert redundant_intersections([], np.zeros((0, 2)), []) == []
    assert redundant_intersections([a], np.zeros((0, 2)), [[]]) == []
    assert redundant_intersections([a, a], np.zeros((0, 2)), [[], []], candidates=[]) == []


def test_distances_to_many_arcs_are_nearest_on_arcs_and_bounded_beyond_the_limit():
    from img2logo.fit.arc_extraction import distances_to_arcs, nearest_on_arc
    from img2logo.fit.intersections import arc_params

    rng = np.random.default_rng(3)
    arcs = [
        Arc(Circle(*rng.uniform(0, 100, 2), rng.uniform(1, 80)), rng.uniform(-3, 3), rng.uniform(-6.28, 6.28))
        for _ in range(120)
    ]
    arcs.append(Arc(Circle(50.0, 50.0, 10.0), 0.3, 2 * np.pi))  # a whole circle
    points = rng.uniform(-50, 150, (60, 2))
    points[0] = arcs[0].circle.center  # the centre itself: the nearer end
    exact = np.stack([nearest_on_arc(a, points)[0] for a in arcs], axis=1)
    np.testing.assert_allclose(distances_to_arcs(points, arc_params(arcs)), exact, rtol=0, atol=1e-9)
    near = distances_to_arcs(points, arc_params(arcs), 6.0)
    within = exact <= 6.0
    np.testing.assert_allclose(near[within], exact[within], rtol=0, atol=1e-9)
    assert np.all(near[~within] > 6.0) and np.all(near <= exact + 1e-9)  # beyond it, a lower bound above it
