"""Tests of circle fitting: free fits and the connectivity-constrained fit (Sec. 5.3, Eqn. 7, 9, 13)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import img2logo.circle_fitting as cf
from img2logo.circle_fitting import fit_center, fit_circle, fit_constrained, mean_abs_error
from img2logo.constants import CONSTRAINED_FIT_MAX_ITER, MAX_RADIUS_FACTOR, PHI
from img2logo.errors import FitError, InvalidParameterError

# --- Helpers ------------------------------------------------------------------------


def arc_points(center, radius, theta0, sweep, n):
    t = theta0 + sweep * np.linspace(0.0, 1.0, n)
    return np.asarray(center, dtype=float) + radius * np.column_stack([np.cos(t), np.sin(t)])


def arc_through(q0, q1, radius, side, n):
    """Centre and n points of the minor arc of radius ``radius`` from q0 to q1."""
    q0, q1 = np.asarray(q0, dtype=float), np.asarray(q1, dtype=float)
    chord = np.linalg.norm(q1 - q0)
    t = (q1 - q0) / chord
    center = (q0 + q1) / 2 + side * math.sqrt(radius**2 - chord**2 / 4) * np.array([-t[1], t[0]])
    a0, a1 = (math.atan2(*(q - center)[::-1]) for q in (q0, q1))
    sweep = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi
    return center, arc_points(center, radius, a0, sweep, n)


def kasa_radius(p):
    """Radius of the Kasa fit (what scikit-image's CircleModel does), for comparison."""
    a = np.column_stack([2 * p, np.ones(len(p))])
    (cx, cy, c), *_ = np.linalg.lstsq(a, np.sum(p * p, axis=1), rcond=None)
    return math.sqrt(c + cx * cx + cy * cy)


def energy(point_sets, radii, centers, disp, ws, wj):
    """E^l of Eqn. 7, written out."""
    fit = sum(
        np.sum((np.linalg.norm(p - o, axis=1) - r) ** 2) for p, r, o in zip(point_sets, radii, centers, strict=True)
    )
    return ws * fit + wj * np.sum(disp**2)


@pytest.fixture
def chain():
    """Three golden arcs meeting at known junctions: 0 -(arc 0)- 1 -(arc 1)- 2 -(arc 2)- 3."""
    junctions = np.array([[100.0, 100.0], [160.0, 120.0], [200.0, 180.0], [210.0, 250.0]])
    radii = np.array([PHI ** (7 + 0.3), PHI ** (8 + 0.3), PHI ** (9 + 0.3)])
    centers, sets = [], []
    for i, side in enumerate([1, -1, 1]):
        o, p = arc_through(junctions[i], junctions[i + 1], radii[i], side, 80)
        centers.append(o)
        sets.append(p)
    incidence = np.array([[0, 0], [0, 1], [1, 1], [1, 2], [2, 2], [2, 3]])
    return sets, radii, np.array(centers), junctions, incidence


@pytest.fixture
def y_junction():
    """Three circles through one junction (0) with noisy points; other ends 1, 2, 3."""
    rng = np.random.default_rng(7)
    q0 = np.array([100.0, 100.0])
    ends = np.array([[160.0, 90.0], [60.0, 150.0], [90.0, 30.0]])
    radii = np.array([PHI**9.4, PHI**8.4, PHI**10.4])
    centers, sets = [], []
    for q1, r, side in zip(ends, radii, [1, -1, 1], strict=True):
        o, p = arc_through(q0, q1, r, side, 80)
        centers.append(o)
        sets.append(p + rng.normal(0.0, 0.7, p.shape))
    incidence = np.array([[0, 0], [1, 0], [2, 0], [0, 1], [1, 2], [2, 3]])
    return sets, radii, np.array(centers), np.vstack([q0, ends]), incidence


def constraint_values(fit, junctions, radii, incidence):
    q = junctions + fit.displacements
    return np.linalg.norm(fit.centers[incidence[:, 0]] - q[incidence[:, 1]], axis=1) - radii[incidence[:, 0]]


# --- fit_circle: known answers ------------------------------------------------------


def test_clean_full_circle_is_exact():
    p = arc_points((1203.5, 847.5), 37.0, 0.0, 2 * math.pi * 99 / 100, 100)
    fit = fit_circle(p)
    assert fit.center == pytest.approx([1203.5, 847.5], abs=1e-9)
    assert fit.radius == pytest.approx(37.0, abs=1e-9)
    assert fit.rms < 1e-9
    assert not fit.capped


@pytest.mark.parametrize("sweep", [0.1, 0.5, 1.0, 3.0, -2.0])
def test_clean_arcs_are_exact(sweep):
    p = arc_points((300.0, 400.0), 137.0, 0.3, sweep, 25)
    fit = fit_circle(p)
    assert fit.center == pytest.approx([300.0, 400.0], abs=1e-8)
    assert fit.radius == pytest.approx(137.0, abs=1e-8)
    assert fit.rms < 1e-8


def test_three_points_define_the_circle():
    fit = fit_circle([[0.0, 0.0], [2.0, 0.0], [1.0, 1.0]])
    assert fit.center == pytest.approx([1.0, 0.0], abs=1e-12)
    assert fit.radius == pytest.approx(1.0, abs=1e-12)


def test_noisy_short_arcs_hyper_beats_kasa():
    # 30-degree arcs of radius 100, 1 px Gaussian noise: a Kasa fit shrinks the radius
    # (about 43 px mean error here), the Hyper + geometric fit does not (about 12-13 px).
    rng = np.random.default_rng(0)
    errors, kasa_errors = [], []
    for _ in range(50):
        p = arc_points(rng.uniform(-50, 50, 2), 100.0, rng.uniform(0, 2 * math.pi), math.pi / 6, 53)
        p += rng.normal(0.0, 1.0, p.shape)
        errors.append(abs(fit_circle(p, max_radius=1e6).radius - 100.0))
        kasa_errors.append(abs(kasa_radius(p) - 100.0))
    assert np.mean(errors) < 15.0
    assert np.mean(kasa_errors) > 30.0


def test_collinear_points_are_capped_through_the_end_points():
    x = np.linspace(0.0, 10.0, 11)
    p = np.column_stack([x, 2 * x + 1])
    fit = fit_circle(p)
    extent = math.hypot(10.0, 20.0)
    assert fit.capped
    assert fit.radius == pytest.approx(MAX_RADIUS_FACTOR * extent, rel=1e-12)
    for end in (p[0], p[-1]):
        assert math.dist(fit.center, end) == pytest.approx(fit.radius, rel=1e-12)
    # The sagitta c^2 / (8 R) bounds the error of the middle point.
    assert fit.rms < extent / (8 * MAX_RADIUS_FACTOR)


def test_explicit_max_radius():
    x = np.linspace(0.0, 10.0, 11)
    p = np.column_stack([x, np.zeros_like(x)])
    fit = fit_circle(p, max_radius=100.0)
    assert fit.capped and fit.radius == 100.0
    assert math.dist(fit.center, (0.0, 0.0)) == pytest.approx(100.0)
    assert math.dist(fit.center, (10.0, 0.0)) == pytest.approx(100.0)


def test_exactly_straight_capping_is_deterministic():
    x = np.linspace(-5.0, 5.0, 21)
    p = np.column_stack([x, 0.5 * x])
    a, b = fit_circle(p), fit_circle(p[::-1])
    assert a.center == pytest.approx(b.center, abs=1e-9)
    assert a.radius == b.radius


def test_nearly_straight_points_are_capped_on_their_concave_side():
    # y = c (x - 50)^2 curves towards +y with radius of curvature 1 / (2c) = 5000 px,
    # more than the default cap of 20 x 100 px: the capped centre lies at +y.
    x = np.linspace(0.0, 100.0, 101)
    for c in (1e-4, -1e-4):
        p = np.column_stack([x, c * (x - 50.0) ** 2])
        fit = fit_circle(p)
        assert fit.capped
        assert fit.radius == pytest.approx(2000.0, rel=1e-9)
        assert np.sign(fit.center[1]) == np.sign(c)
        mirrored = np.array([fit.center[0], p[0, 1] - (fit.center[1] - p[0, 1])])
        assert fit.rms < mean_abs_error(p, mirrored, fit.radius)


def test_a_circle_below_the_cap_is_not_capped():
    p = arc_points((50.0, 1000.0), 900.0, -math.pi / 2, 0.2, 40)  # extent ~180 px, cap ~3600 px
    fit = fit_circle(p)
    assert not fit.capped
    assert fit.radius == pytest.approx(900.0, rel=1e-9)


def test_mean_abs_error():
    p = np.array([[11.0, 0.0], [0.0, 9.0], [-10.0, 0.0]])
    assert mean_abs_error(p, (0.0, 0.0), 10.0) == pytest.approx(2.0 / 3.0)
    assert mean_abs_error(arc_points((1.0, 2.0), 5.0, 0.0, 1.0, 9), (1.0, 2.0), 5.0) < 1e-12


# --- fit_circle: bad input ----------------------------------------------------------


def test_too_few_points():
    with pytest.raises(FitError, match="a circle fit needs at least 3 points, got 2"):
        fit_circle([[0.0, 0.0], [1.0, 1.0]])


def test_too_few_distinct_points():
    with pytest.raises(FitError, match="a circle fit needs at least 3 distinct points, got 1"):
        fit_circle([[2.0, 3.0]] * 5)
    with pytest.raises(FitError, match="a circle fit needs at least 3 distinct points, got 2"):
        fit_circle([[0.0, 0.0], [1.0, 1.0], [0.0, 0.0], [1.0, 1.0]])


def test_bad_points_shape():
    with pytest.raises(InvalidParameterError, match=r"points must have shape \(N, 2\), got \(3,\)"):
        fit_circle([1.0, 2.0, 3.0])
    with pytest.raises(InvalidParameterError, match="points must be finite"):
        fit_circle([[0.0, 0.0], [1.0, np.nan], [2.0, 0.0]])


def test_bad_max_radius():
    p = arc_points((0.0, 0.0), 10.0, 0.0, 1.0, 10)
    with pytest.raises(InvalidParameterError, match=r"max_radius must be > 0, got -1.0"):
        fit_circle(p, max_radius=-1.0)
    line = np.column_stack([np.linspace(0, 100, 5), np.zeros(5)])
    with pytest.raises(FitError, match="max_radius 10 is less than half the points' extent 50"):
        fit_circle(line, max_radius=10.0)


def test_bad_mean_abs_error_input():
    with pytest.raises(InvalidParameterError, match=r"center must be a finite array of shape \(2,\)"):
        mean_abs_error([[0.0, 0.0]], (0.0, 0.0, 0.0), 1.0)
    with pytest.raises(InvalidParameterError, match="radius must be > 0"):
        mean_abs_error([[0.0, 0.0]], (0.0, 0.0), 0.0)


# --- fit_constrained: known answers -------------------------------------------------


def test_chain_recovers_the_true_centres(chain):
    sets, radii, centers, junctions, incidence = chain
    rng = np.random.default_rng(1)
    fit = fit_constrained(sets, radii, centers + rng.normal(0.0, 3.0, centers.shape), junctions, incidence)
    assert fit.converged
    assert fit.violation <= 1e-6
    assert fit.centers == pytest.approx(centers, abs=1e-4)
    assert np.abs(fit.displacements).max() < 1e-4
    assert fit.objective < 1e-8
    assert fit.centers.shape == (3, 2) and fit.displacements.shape == (4, 2)
    assert not fit.centers.flags.writeable


def test_y_junction_meets_at_one_point(y_junction):
    sets, radii, centers, junctions, incidence = y_junction
    fit = fit_constrained(sets, radii, centers + np.array([[3.0, -2.0], [-2.0, 2.0], [1.0, 3.0]]), junctions, incidence)
    assert fit.converged
    assert fit.violation <= 1e-6
    assert np.abs(constraint_values(fit, junctions, radii, incidence)).max() <= 1e-6
    meet = junctions[0] + fit.displacements[0]
    for i in range(3):
        assert math.dist(fit.centers[i], meet) == pytest.approx(radii[i], abs=1e-6)
    assert np.abs(fit.displacements).max() < 2.0  # noise of 0.7 px moves them a little
    assert fit.objective == pytest.approx(energy(sets, radii, fit.centers, fit.displacements, 1 / 3, 1 / 4), rel=1e-12)


def test_fixed_variables_stay_exactly_fixed(y_junction):
    sets, radii, centers, junctions, incidence = y_junction
    disp0 = np.array([[0.25, -0.5], [0.0, 0.0], [1.0, 1.0], [0.0, 0.0]])
    start = centers + np.array([[2.0, 0.0], [0.0, -2.0], [0.0, 0.0]])
    # Circle 2 and junction 0 are boundary conditions (Sec. 5.4); the fixed junction is
    # moved onto circle 2 so that the problem stays feasible.
    v = junctions[0] + disp0[0] - start[2]
    disp0[0] += v / np.linalg.norm(v) * radii[2] - v
    fit = fit_constrained(
        sets, radii, start, junctions, incidence, displacements0=disp0, free_circles=[0, 1], free_junctions=[1, 2, 3]
    )
    assert fit.converged and fit.violation <= 1e-6
    assert np.array_equal(fit.centers[2], start[2])
    assert np.array_equal(fit.displacements[0], disp0[0])
    assert not np.array_equal(fit.centers[0], start[0])


def test_nothing_free_only_evaluates(chain):
    sets, radii, centers, junctions, incidence = chain
    fit = fit_constrained(sets, radii, centers + 1.0, junctions, incidence, free_circles=[], free_junctions=[])
    assert fit.iterations == 0 and not fit.converged
    assert np.array_equal(fit.centers, centers + 1.0)
    assert fit.violation > 0.1
    exact = fit_constrained(sets, radii, centers, junctions, incidence, free_circles=[], free_junctions=[])
    assert exact.converged and exact.violation < 1e-9


def test_nearly_straight_segment_with_a_huge_radius_converges():
    rng = np.random.default_rng(3)
    junctions = np.array([[10.0, 10.0], [110.0, 12.0], [150.0, 60.0]])
    o0, p0 = arc_through(junctions[0], junctions[1], 1e5, 1, 100)
    o1, p1 = arc_through(junctions[1], junctions[2], PHI**8, -1, 60)
    sets = [p0 + rng.normal(0.0, 0.5, p0.shape), p1 + rng.normal(0.0, 0.5, p1.shape)]
    incidence = np.array([[0, 0], [0, 1], [1, 1], [1, 2]])
    start = np.array([o0, o1]) + rng.normal(0.0, 3.0, (2, 2))
    fit = fit_constrained(sets, [1e5, PHI**8], start, junctions, incidence)
    assert fit.converged
    assert fit.violation <= 1e-6


def test_without_connectivity_each_centre_fits_alone(y_junction):
    sets, radii, centers, junctions, incidence = y_junction
    start = centers + np.array([[3.0, -2.0], [-2.0, 2.0], [1.0, 3.0]])
    free = fit_constrained(sets, radii, start, junctions, incidence, connectivity=False)
    tied = fit_constrained(sets, radii, start, junctions, incidence)
    assert free.converged
    assert free.violation > 1e-3  # the noisy circles miss each other
    assert free.objective < tied.objective
    assert np.array_equal(free.displacements, np.zeros((4, 2)))
    for p, r, o in zip(sets, radii, free.centers, strict=True):  # stationary: the gradient vanishes
        d = np.linalg.norm(p - o, axis=1)
        grad = np.sum(((d - r) / d)[:, None] * (o - p), axis=0)
        assert np.abs(grad).max() < 1e-6


def test_infeasible_boundary_conditions_report_failure():
    # Radius 10 but the two fixed junctions are 40 px apart: no centre works.
    fit = fit_constrained(
        [np.array([[0.0, 0.0], [10.0, 10.0], [20.0, 0.0]])],
        [10.0],
        [[10.0, 0.0]],
        [[0.0, 0.0], [40.0, 0.0]],
        [[0, 0], [0, 1]],
        free_junctions=[],
    )
    assert not fit.converged
    assert fit.violation >= 10.0 - 1e-9


def test_infeasible_local_window_stops_early(chain):
    # Circle 1 is fixed 10 px off while its junctions 1 and 2 are fixed too.
    sets, radii, centers, junctions, incidence = chain
    start = centers.copy()
    start[1] += 10.0
    fit = fit_constrained(sets, radii, start, junctions, incidence, free_circles=[0, 2], free_junctions=[0, 3])
    assert not fit.converged
    assert fit.violation > 1.0
    assert fit.iterations < CONSTRAINED_FIT_MAX_ITER


def test_weights_set_the_objective(chain):
    sets, radii, centers, junctions, incidence = chain
    disp0 = np.full((4, 2), 0.5)
    fit = fit_constrained(
        sets, radii, centers, junctions, incidence, displacements0=disp0, max_iter=0, segment_weight=2.0
    )
    assert fit.iterations == 0
    assert fit.objective == pytest.approx(energy(sets, radii, centers, disp0, 2.0, 1 / 4), rel=1e-12)
    fit = fit_constrained(sets, radii, centers, junctions, incidence, displacements0=disp0, max_iter=0)
    assert fit.objective == pytest.approx(energy(sets, radii, centers, disp0, 1 / 3, 1 / 4), rel=1e-12)


def test_sparse_and_dense_solvers_agree(monkeypatch):
    # A closed loop of 12 arcs: 48 unknowns + 24 multipliers, above KKT_DENSE_MAX.
    rng = np.random.default_rng(11)
    angles = np.linspace(0, 2 * math.pi, 12, endpoint=False)
    junctions = 300.0 + 200.0 * np.column_stack([np.cos(angles), np.sin(angles)])
    radii, centers, sets, incidence = [], [], [], []
    for i in range(12):
        r = PHI ** (8 + 0.5 + i % 3)
        o, p = arc_through(junctions[i], junctions[(i + 1) % 12], r, 1 if i % 2 else -1, 50)
        radii.append(r)
        centers.append(o)
        sets.append(p + rng.normal(0.0, 0.5, p.shape))
        incidence += [[i, i], [i, (i + 1) % 12]]
    start = np.array(centers) + rng.normal(0.0, 2.0, (12, 2))
    args = (sets, np.array(radii), start, junctions, np.array(incidence))
    sparse = fit_constrained(*args)
    monkeypatch.setattr(cf, "KKT_DENSE_MAX", 10_000)
    dense = fit_constrained(*args)
    assert sparse.converged and dense.converged
    assert sparse.violation <= 1e-6
    assert sparse.centers == pytest.approx(dense.centers, abs=1e-6)
    assert sparse.objective == pytest.approx(dense.objective, rel=1e-9)


def test_no_incidences_is_the_unconstrained_fit(chain):
    sets, radii, centers, junctions, _ = chain
    fit = fit_constrained(sets, radii, centers + 2.0, junctions, np.zeros((0, 2), dtype=int))
    assert fit.converged and fit.violation == 0.0
    assert fit.centers == pytest.approx(centers, abs=1e-5)


# --- fit_constrained: bad input -----------------------------------------------------


@pytest.mark.parametrize(
    ("change", "exc", "message"),
    [
        ({"radii": [1.0, 2.0]}, InvalidParameterError, r"point_sets must have one entry per radius \(2\), got 3"),
        ({"radii": [1.0, -2.0, 3.0]}, InvalidParameterError, "radii must be finite and > 0"),
        ({"centers0": np.zeros((2, 2))}, InvalidParameterError, r"centers0 must have shape \(3, 2\), got \(2, 2\)"),
        ({"incidence": [[0, 9]]}, InvalidParameterError, r"incidence\[:, 1\] must index 0..3, got values from 9"),
        ({"incidence": [[0.0, 1.0]]}, InvalidParameterError, r"incidence must be an integer array of shape \(M, 2\)"),
        ({"free_circles": [5]}, InvalidParameterError, "free_circles must index 0..2"),
        ({"free_junctions": [[1]]}, InvalidParameterError, "free_junctions must be a 1-D array of integers"),
        ({"displacements0": np.zeros((3, 2))}, InvalidParameterError, r"displacements0 must have shape \(4, 2\)"),
        ({"segment_weight": -1.0}, InvalidParameterError, "segment_weight must be >= 0, got -1.0"),
        ({"tol": 0.0}, InvalidParameterError, "tol must be > 0, got 0.0"),
        ({"max_iter": 2.5}, InvalidParameterError, "max_iter must be an integer >= 0, got 2.5"),
    ],
)
def test_bad_constrained_input(chain, change, exc, message):
    sets, radii, centers, junctions, incidence = chain
    kwargs = {"radii": radii, "centers0": centers, "incidence": incidence} | change
    positional = (sets, kwargs.pop("radii"), kwargs.pop("centers0"), junctions, kwargs.pop("incidence"))
    with pytest.raises(exc, match=message):
        fit_constrained(*positional, **kwargs)


def test_bad_point_set(chain):
    sets, radii, centers, junctions, incidence = chain
    with pytest.raises(InvalidParameterError, match=r"point_sets\[1\] must have shape \(N, 2\), got \(4,\)"):
        fit_constrained([sets[0], np.zeros(4), sets[2]], radii, centers, junctions, incidence)


def test_fit_center_recovers_a_fixed_radius_centre():
    t = np.linspace(0.2, 1.4, 120)
    pts = np.column_stack([40.0 + 25.0 * np.cos(t), -10.0 + 25.0 * np.sin(t)])
    np.testing.assert_allclose(fit_center(pts, 25.0, [35.0, -5.0]), [40.0, -10.0], atol=1e-8)


def test_fit_center_matches_the_unconstrained_fit_of_fit_constrained():
    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 1.0, 80)
    pts = np.column_stack([100 * np.cos(t), 100 * np.sin(t)]) + rng.normal(0, 0.5, (80, 2))
    ref = fit_constrained([pts], [120.0], [[0.0, 0.0]], np.zeros((0, 2)), np.zeros((0, 2), int), connectivity=False)
    np.testing.assert_allclose(fit_center(pts, 120.0, [0.0, 0.0]), ref.centers[0], atol=1e-6)


def test_unrefined_hyper_fit_is_close_on_pixel_arcs():
    # The optimizer uses the Hyper fit alone: on a rasterized arc it must agree
    # with the refined fit to a small fraction of a pixel.
    t = np.linspace(0.3, 1.5, 200)
    pts = np.floor(np.column_stack([200 + 90 * np.cos(t), 150 + 90 * np.sin(t)])) + 0.5
    a, b = fit_circle(pts), fit_circle(pts, refine=False)
    assert abs(a.radius - b.radius) < 0.5
    assert np.hypot(*(a.center - b.center)) < 0.5


# --------------------------------------------------------------------------- the window of a local refit
def _chain_of_three():
    """Circles 0, 1, 2 in a row, r = 10; junction 0 joins circles 0 and 1, junction 1 circles 1 and 2.

    Circle 0's points lie on a circle moved 1 px up: only the fit can say where it goes.
    """
    radii = {0: 10.0, 1: 10.0, 2: 10.0}
    centers = {0: np.array([0.0, 0.0]), 1: np.array([20.0, 0.0]), 2: np.array([40.0, 0.0])}
    t = np.linspace(-1.0, 1.0, 21)
    points = {
        0: np.stack([10 * np.cos(t + math.pi), 10 * np.sin(t + math.pi) - 1.0], axis=1),
        1: np.stack([20 + 10 * np.cos(t - math.pi / 2), 10 * np.sin(t - math.pi / 2)], axis=1),
        2: np.stack([40 + 10 * np.cos(t), 10 * np.sin(t)], axis=1),
    }
    circle_junctions = {0: (0,), 1: (0, 1), 2: (1,)}
    junction_circles = {0: [0, 1], 1: [1, 2]}
    junctions = np.array([[10.0, 0.0], [30.0, 0.0]])
    return points, radii, centers, circle_junctions, junction_circles, junctions


def test_window_holds_the_junctions_beyond_the_first_ring():
    args = _chain_of_three()
    w = cf.fit_window(*args, changed=[0], free_junctions=[0])
    assert w.ok and w.circles == (0, 1) and w.junctions == (0, 1) and w.free_junctions == {0}
    d = w.displacements()
    np.testing.assert_array_equal(d[1], [0.0, 0.0])  # held: the boundary of the window (Sec. 5.4)
    for c in w.circles:  # every circle still passes through its junctions
        for n in args[3][c]:
            assert math.dist(w.center(c), args[5][n] + d[n]) == pytest.approx(10.0, abs=1e-6)
    assert w.center(0)[1] < -0.1  # circle 0 followed its points up


def test_window_grows_by_a_ring_when_it_does_not_solve_and_keeps_fixed_circles():
    args = _chain_of_three()
    failed = cf.fit_window(*args, changed=[0], free_junctions=[0], max_violation=-1.0)  # never good enough
    assert not failed.ok and failed.circles == (0, 1, 2) and failed.free_junctions == {0, 1}
    one = cf.fit_window(*args, changed=[0], free_junctions=[0], max_violation=-1.0, rings=1)
    assert one.circles == (0, 1)
    fixed = cf.fit_window(*args, changed=[0], free_junctions=[0], fixed={1})
    np.testing.assert_array_equal(fixed.center(1), [20.0, 0.0])
    ordered = cf.fit_window(*args, changed=[0], free_junctions=[0], order=lambda c: -c)
    assert ordered.circles == (1, 0)
    empty = cf.fit_window(*args, changed=[], free_junctions=[])
    assert empty.ok and empty.fit is None and empty.displacements() == {}
