"""Tests of the connectivity-constrained fit and its local window (Sec. 5.3, 5.4, Eqn. 7, 9, 13)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers import arc_through

import img2logo.fit.constrained_fit as cfit
from img2logo.constants import PHI
from img2logo.errors import InvalidParameterError
from img2logo.fit.constants import CONSTRAINED_FIT_MAX_ITER
from img2logo.fit.constrained_fit import fit_constrained
from img2logo.geometry.circle_fitting import fit_center

# --- Helpers ------------------------------------------------------------------------


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
    monkeypatch.setattr(cfit, "KKT_DENSE_MAX", 10_000)
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
        ({"tangents": [[0, 1]]}, InvalidParameterError, r"tangents must be an integer array of shape \(T, 3\)"),
        ({"tangents": [[0, 7, 1]]}, InvalidParameterError, r"tangents\[:, :2\] must index 0..2, got values"),
        ({"tangents": [[0, 1, 9]]}, InvalidParameterError, r"tangents\[:, 2\] must index 0..3, got values"),
        ({"tangents": [[1, 1, 1]]}, InvalidParameterError, "tangents must name two different circles in each row"),
    ],
)
def test_bad_constrained_input(chain, change, exc, message):
    sets, radii, centers, junctions, incidence = chain
    kwargs = {"radii": radii, "centers0": centers, "incidence": incidence} | change
    positional = (sets, kwargs.pop("radii"), kwargs.pop("centers0"), junctions, kwargs.pop("incidence"))
    with pytest.raises(exc, match=message):
        fit_constrained(*positional, **kwargs)


# --- fit_constrained: tangency (tangent joins, beyond the paper) ---------------------


def _smooth_pair(r0, r1, side1, kink):
    """Two arcs meeting at q = (0, 0): arc 0 (radius r0, centre (0, -r0)) ends there heading +x, arc 1
    (radius r1) leaves it ``kink`` rad off +x, curving the same way (side1 = 1) or the other (-1).

    Returns the fit's inputs: points, radii, centres (the true ones, nudged), junctions, incidence.
    """
    c0 = np.array([0.0, -r0])
    t0 = np.linspace(math.pi / 2 + 0.8, math.pi / 2, 60)  # towards q, clockwise on screen
    p0 = c0 + r0 * np.column_stack([np.cos(t0), np.sin(t0)])
    heading = np.array([math.cos(kink), math.sin(kink)])
    normal = side1 * np.array([heading[1], -heading[0]])  # towards the centre
    c1 = r1 * normal
    a = math.atan2(-c1[1], -c1[0])
    t1 = a + np.linspace(0.0, 0.8, 60)
    p1 = c1 + r1 * np.column_stack([np.cos(t1), np.sin(t1)])
    if np.dot(p1[5] - p1[0], heading) < 0:  # the arc leaves q along the heading
        t1 = a - (t1 - a)
        p1 = c1 + r1 * np.column_stack([np.cos(t1), np.sin(t1)])
    junctions = np.array([[0.0, 0.0], p0[0], p1[-1]])
    incidence = np.array([[0, 0], [1, 0], [0, 1], [1, 2]])
    start = np.array([c0 + np.array([0.7, 0.4]), c1 - np.array([0.5, 0.6])])
    return [p0, p1], np.array([r0, r1]), start, junctions, incidence


@pytest.mark.parametrize("side1", [1, -1], ids=["internal", "external"])
def test_tangency_makes_the_circles_touch_at_the_junction(side1):
    r0, r1 = PHI ** (8 + 0.3), PHI ** (9 + 0.3)
    # Arc 1 leaves the junction 6 degrees off arc 0's tangent: the pixels kink a little.
    sets, radii, centers, junctions, incidence = _smooth_pair(r0, r1, side1, math.radians(6.0))
    free = fit_constrained(sets, radii, centers, junctions, incidence)
    fit = fit_constrained(sets, radii, centers, junctions, incidence, tangents=[[0, 1, 0]])
    assert free.converged and fit.converged and fit.violation <= 1e-6
    q = junctions[0] + fit.displacements[0]
    o0, o1 = fit.centers
    touching = abs(r0 - r1) if side1 > 0 else r0 + r1
    # The circles touch: centre distance |r0 - r1| (same side) or r0 + r1, to 1e-6 px ...
    assert abs(np.linalg.norm(o0 - o1) - touching) <= 1e-6
    # ... at the junction: on both circles and on the line of centres.
    assert abs(np.linalg.norm(o0 - q) - r0) <= 1e-6 and abs(np.linalg.norm(o1 - q) - r1) <= 1e-6
    u = (o1 - o0) / np.linalg.norm(o1 - o0)
    assert abs(u[0] * (q - o0)[1] - u[1] * (q - o0)[0]) <= 1e-6
    # Without it the circles cross at the junction: the paper's kink.
    free_gap = abs(np.linalg.norm(free.centers[0] - free.centers[1]) - touching)
    assert free_gap > 0.1


def test_tangency_between_fixed_variables_is_evaluated_not_enforced():
    r0, r1 = PHI ** (8 + 0.3), PHI ** (9 + 0.3)
    sets, radii, centers, junctions, incidence = _smooth_pair(r0, r1, 1, math.radians(20.0))
    fit = fit_constrained(
        sets, radii, centers, junctions, incidence, tangents=[[0, 1, 0]], free_circles=[], free_junctions=[]
    )
    assert fit.iterations == 0 and fit.violation > 1.0


def test_tangency_is_dropped_without_connectivity():
    r0, r1 = PHI ** (8 + 0.3), PHI ** (9 + 0.3)
    sets, radii, centers, junctions, incidence = _smooth_pair(r0, r1, 1, math.radians(6.0))
    plain = fit_constrained(sets, radii, centers, junctions, incidence, connectivity=False)
    fit = fit_constrained(sets, radii, centers, junctions, incidence, connectivity=False, tangents=[[0, 1, 0]])
    assert fit.centers == pytest.approx(plain.centers, abs=1e-9)


def test_tangency_with_the_sparse_solver(monkeypatch):
    r0, r1 = PHI ** (8 + 0.3), PHI ** (9 + 0.3)
    args = _smooth_pair(r0, r1, -1, math.radians(6.0))
    dense = fit_constrained(*args, tangents=[[0, 1, 0]])
    monkeypatch.setattr(cfit, "KKT_DENSE_MAX", 0)
    sparse = fit_constrained(*args, tangents=[[0, 1, 0]])
    assert sparse.converged and sparse.violation <= 1e-6
    assert sparse.centers == pytest.approx(dense.centers, abs=1e-6)


def test_bad_point_set(chain):
    sets, radii, centers, junctions, incidence = chain
    with pytest.raises(InvalidParameterError, match=r"point_sets\[1\] must have shape \(N, 2\), got \(4,\)"):
        fit_constrained([sets[0], np.zeros(4), sets[2]], radii, centers, junctions, incidence)


def test_fit_center_matches_the_unconstrained_fit_of_fit_constrained():
    rng = np.random.default_rng(7)
    t = np.linspace(0.0, 1.0, 80)
    pts = np.column_stack([100 * np.cos(t), 100 * np.sin(t)]) + rng.normal(0, 0.5, (80, 2))
    ref = fit_constrained([pts], [120.0], [[0.0, 0.0]], np.zeros((0, 2)), np.zeros((0, 2), int), connectivity=False)
    np.testing.assert_allclose(fit_center(pts, 120.0, [0.0, 0.0]), ref.centers[0], atol=1e-6)


def test_window_problem_is_what_fit_constrained_solves(chain):
    sets, radii, centers, junctions, incidence = chain
    free_c, free_j = np.array([1]), np.array([1, 2])
    ws = np.full(3, 1.0 / 3)
    public = fit_constrained(
        sets, radii, centers, junctions, incidence[::-1], free_circles=free_c, free_junctions=free_j
    )
    problem = cfit.WindowProblem.of(
        sets, radii, centers, junctions, np.zeros((4, 2)), incidence[::-1], free_c, free_j, ws, 0.25, True,
        np.zeros((0, 3), dtype=np.int64),
    )  # fmt: skip
    assert problem.incidence.tolist() == incidence.tolist()  # distinct and sorted
    assert problem.kkt_size() == 6 + 4  # unknowns: one centre, two displacements; the 4 incidences they touch
    for compiled in (True, False):
        fit = cfit.solve_sqp(problem, compiled=compiled)
        assert fit.converged
        np.testing.assert_allclose(fit.centers, public.centers, atol=1e-9)
    assert np.array_equal(cfit.solve_sqp(problem).centers, public.centers)  # the same arithmetic
    with pytest.raises(dataclasses.FrozenInstanceError):
        problem.tol = 1.0  # type: ignore[misc]
