"""Tests of img2logo._compiled.kernels: the compiled SQP of Eqn. 13 against its Python reference, on seeded problems."""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence

import numpy as np
import pytest
from helpers import arc_through, modules_loaded

import img2logo.fit.constrained_fit as cfit
from img2logo._compat import unique
from img2logo._validation import readonly
from img2logo.constants import INTERSECTION_TOL, PHI
from img2logo.errors import FitError
from img2logo.fit.arc_extraction import ArcFit, admissible_arcs, best_by_frechet, extract_arc
from img2logo.fit.constants import CONSTRAINED_FIT_MAX_ITER, CONSTRAINED_FIT_TOL
from img2logo.fit.constrained_fit import fit_constrained
from img2logo.fit.intersections import (
    RedundantIntersection,
    arc_intersections,
    arc_pairs_near,
    arc_params,
    redundant_intersections,
)
from img2logo.geometry import circle_fitting
from img2logo.geometry.circle_fitting import fit_center, fit_circle, mean_abs_error
from img2logo.geometry.primitives import TAU, Arc, Circle

# The Python references of the compiled kernels of arc extraction and arc intersections: their oracles.


def extract_reference(circle: Circle, seg: np.ndarray, junctions: np.ndarray) -> ArcFit:
    """``extract_arc`` (method "frechet") in Python: the oracle of its compiled kernel."""
    kept, cap = admissible_arcs(circle, seg, junctions)
    return best_by_frechet(kept, seg, cap)


def redundant_reference(
    arcs: Sequence[Arc], junctions: np.ndarray, owned: Sequence[np.ndarray], rows: np.ndarray, tol: float
) -> list[RedundantIntersection]:
    """The test of ``redundant_intersections`` in Python: the oracle of its compiled kernel."""
    out = []
    for i, j in arc_pairs_reference(arcs, rows, INTERSECTION_TOL):
        shared = junctions[np.intersect1d(owned[i], owned[j])]
        for p in arc_intersections(arcs[i], arcs[j], tol=INTERSECTION_TOL):
            if len(shared) and np.min(np.hypot(*(shared - p).T)) <= tol:
                continue
            out.append(RedundantIntersection(int(i), int(j), readonly(p.copy())))
    return out


def arc_pairs_reference(arcs: Sequence[Arc], rows: np.ndarray, tol: float) -> list[tuple[int, int]]:
    """``arc_pairs_near`` in numpy: the oracle of its compiled kernel."""
    params = arc_params(arcs)
    centers, radii = params[:, :2], params[:, 2]
    boxes = _bounding_boxes(params)  # (n, 4): xmin, ymin, xmax, ymax
    n = len(arcs)
    d = np.hypot(*(centers[rows, None, :] - centers[None, :, :]).transpose(2, 0, 1))
    rr, rc = radii[rows, None], radii[None, :]
    meet = (d <= rr + rc + tol) & (d >= np.abs(rr - rc) - tol)
    br, bc = boxes[rows, None, :], boxes[None, :, :]
    overlap = (br[..., 0] <= bc[..., 2] + tol) & (bc[..., 0] <= br[..., 2] + tol)
    overlap &= (br[..., 1] <= bc[..., 3] + tol) & (bc[..., 1] <= br[..., 3] + tol)
    mask = meet & overlap
    mask[np.arange(len(rows)), rows] = False
    r_idx, c_idx = np.nonzero(mask)
    i, j = rows[r_idx], c_idx
    lo, hi = np.minimum(i, j), np.maximum(i, j)
    key = unique(lo * n + hi)  # a pair of two candidates appears twice
    return [(int(k // n), int(k % n)) for k in key]


def _bounding_boxes(params: np.ndarray) -> np.ndarray:
    """Axis-aligned bounding boxes of arcs given as rows (cx, cy, r, theta0, sweep): (n, 4).

    Columns xmin, ymin, xmax, ymax, px: the extremes of the end points and of the
    points at angles 0, pi/2, pi, 3 pi/2 that lie on the arc.
    """
    cx, cy, r, t0, sw = params.T
    ang = np.empty((len(params), 6))
    ang[:, 0], ang[:, 1], ang[:, 2:] = t0, t0 + sw, np.arange(4) * (math.pi / 2)
    offset = np.mod((ang - t0[:, None]) * np.sign(sw)[:, None], TAU)
    on = (offset <= np.abs(sw)[:, None]) | (np.abs(sw)[:, None] >= TAU - 1e-9)
    on[:, :2] = True
    x = cx[:, None] + r[:, None] * np.cos(ang)
    y = cy[:, None] + r[:, None] * np.sin(ang)
    inf = np.where(on, 0.0, np.inf)
    return np.stack([(x + inf).min(1), (y + inf).min(1), (x - inf).max(1), (y - inf).max(1)], axis=1)


def _loop(n_arcs: int, seed: int, noise: float = 0.5, jitter: float = 2.0):
    """A closed loop of ``n_arcs`` golden arcs with noisy points and nudged centres (the inputs of a fit)."""
    rng = np.random.default_rng(seed)
    angles = np.linspace(0, 2 * math.pi, n_arcs, endpoint=False)
    junctions = 300.0 + 40.0 / math.sin(math.pi / n_arcs) * np.column_stack([np.cos(angles), np.sin(angles)])
    radii, centers, sets, incidence = [], [], [], []
    for i in range(n_arcs):
        r = PHI ** (8 + 0.5 + i % 3)
        o, p = arc_through(junctions[i], junctions[(i + 1) % n_arcs], r, 1 if i % 2 else -1, 40)
        radii.append(r)
        centers.append(o)
        sets.append(p + rng.normal(0.0, noise, p.shape))
        incidence += [[i, i], [i, (i + 1) % n_arcs]]
    start = np.array(centers) + rng.normal(0.0, jitter, (n_arcs, 2))
    return sets, np.array(radii), start, junctions, np.array(incidence)


def _both(monkeypatch, *args, **kwargs):
    """The fit by the compiled kernel and by the Python reference."""
    compiled = fit_constrained(*args, **kwargs)
    with monkeypatch.context() as m:
        m.setattr(cfit, "solve_sqp", functools.partial(cfit.solve_sqp, compiled=False))
        reference = fit_constrained(*args, **kwargs)
    return compiled, reference


def _assert_same(compiled, reference, tol=CONSTRAINED_FIT_TOL):
    """The same fit: the same outcome, and values within ``tol`` px.

    Rounding differs (the kernel sums in another order): every SQP iterate agrees
    to ~1e-12 px (see the iterate-by-iterate test), but the last, polishing step
    is taken in a direction the solver only knows to its tolerance.
    """
    assert compiled.converged == reference.converged
    assert abs(compiled.iterations - reference.iterations) <= 1  # a convergence test at rounding level
    assert compiled.centers == pytest.approx(reference.centers, abs=tol)
    assert compiled.displacements == pytest.approx(reference.displacements, abs=tol)
    assert compiled.objective == pytest.approx(reference.objective, rel=1e-6, abs=1e-12)
    assert compiled.violation == pytest.approx(reference.violation, abs=tol)
    assert not compiled.centers.flags.writeable and not compiled.displacements.flags.writeable


@pytest.mark.parametrize("seed", range(6))
def test_window_of_a_loop_matches_the_reference(monkeypatch, seed):
    # Three free circles and their junctions of an 8-arc loop: the localized fit of Sec. 5.4 (dense, 28 unknowns).
    sets, radii, start, junctions, incidence = _loop(8, seed)
    free = [seed % 8, (seed + 1) % 8, (seed + 2) % 8]
    compiled, reference = _both(
        monkeypatch,
        sets,
        radii,
        start,
        junctions,
        incidence,
        free_circles=free,
        free_junctions=[(seed + 1) % 8, (seed + 2) % 8],
        segment_weight=1.0 / (8 * 40),
        junction_weight=1.0 / 8,
    )
    assert not reference.converged or reference.violation <= CONSTRAINED_FIT_TOL
    _assert_same(compiled, reference)


@pytest.mark.parametrize("seed", range(4))
def test_whole_small_loop_matches_the_reference(monkeypatch, seed):
    # Every variable free: 4 arcs, 16 unknowns + 8 multipliers.
    compiled, reference = _both(monkeypatch, *_loop(4, 100 + seed, noise=1.0, jitter=4.0))
    _assert_same(compiled, reference)


@pytest.mark.parametrize("side1", [1, -1], ids=["internal", "external"])
def test_tangency_rows_match_the_reference(monkeypatch, side1):
    # Two arcs touching at a junction (Newton steps with the tangency curvature).
    r0, r1 = PHI ** (8 + 0.3), PHI ** (9 + 0.3)
    c0 = np.array([0.0, -r0])
    t0 = np.linspace(math.pi / 2 + 0.8, math.pi / 2, 60)
    p0 = c0 + r0 * np.column_stack([np.cos(t0), np.sin(t0)])
    c1 = side1 * np.array([math.sin(0.2), -math.cos(0.2)]) * r1
    a = math.atan2(-c1[1], -c1[0])
    t1 = a + side1 * np.linspace(0.0, 0.8, 60)
    p1 = c1 + r1 * np.column_stack([np.cos(t1), np.sin(t1)])
    junctions = np.array([[0.0, 0.0], p0[0], p1[-1]])
    incidence = np.array([[0, 0], [1, 0], [0, 1], [1, 2]])
    start = np.array([c0 + np.array([0.7, 0.4]), c1 - np.array([0.5, 0.6])])
    compiled, reference = _both(
        monkeypatch, [p0, p1], np.array([r0, r1]), start, junctions, incidence, tangents=[[0, 1, 0]]
    )
    assert reference.converged
    _assert_same(compiled, reference)


def test_mirror_axis_matches_the_reference(monkeypatch):
    # Circle 0 centred on the axis x = 300 and junction 1 on it: those x unknowns leave the system.
    sets, radii, start, junctions, incidence = _loop(4, 7)
    compiled, reference = _both(
        monkeypatch, sets, radii, start, junctions, incidence, axis=300.0, axis_circles=[0], axis_junctions=[0]
    )
    _assert_same(compiled, reference)
    assert compiled.centers[0, 0] == 300.0
    assert junctions[0, 0] + compiled.displacements[0, 0] == 300.0


def test_every_iterate_matches_the_reference(monkeypatch):
    # Stopped after k steps, the two solvers are at the same iterate (Gauss-Newton, then Newton with tangency).
    for k in range(1, 4):
        for case in (_loop(4, 11, noise=1.0, jitter=4.0), _loop(8, 12)):
            compiled, reference = _both(monkeypatch, *case, max_iter=k)
            assert compiled.iterations == reference.iterations == k
            _assert_same(compiled, reference, tol=1e-9)


def test_infeasible_and_unconstrained_match_the_reference(monkeypatch):
    # Radius 10 but the two fixed junctions are 40 px apart: no centre works, the fit stalls.
    args = ([np.array([[0.0, 0.0], [10.0, 10.0], [20.0, 0.0]])], [10.0], [[10.0, 0.0]], [[0.0, 0.0], [40.0, 0.0]])
    compiled, reference = _both(monkeypatch, *args, [[0, 0], [0, 1]], free_junctions=[])
    assert not reference.converged and reference.iterations < CONSTRAINED_FIT_MAX_ITER
    _assert_same(compiled, reference)
    sets, radii, start, junctions, incidence = _loop(4, 3)
    compiled, reference = _both(monkeypatch, sets, radii, start, junctions, incidence, connectivity=False)
    _assert_same(compiled, reference)
    compiled, reference = _both(
        monkeypatch, sets, radii, start, junctions, incidence, free_circles=[], free_junctions=[]
    )
    assert compiled.iterations == 0
    _assert_same(compiled, reference)


def test_large_systems_take_the_banded_kernel(monkeypatch):
    # 12 arcs all free: 48 unknowns + 24 multipliers > KKT_DENSE_MAX, the banded kernel, not the dense one.
    import img2logo._compiled.kernels as kernels

    dense, banded = [], []
    monkeypatch.setattr(kernels, "sqp_dense", lambda *a: dense.append(a))
    real = kernels.sqp_banded
    monkeypatch.setattr(kernels, "sqp_banded", lambda *a: banded.append(a) or real(*a))
    fit = fit_constrained(*_loop(12, 5))
    assert fit.converged and not dense and len(banded) == 1


def test_a_system_above_the_compiled_cap_runs_the_reference(monkeypatch):
    # Above KKT_COMPILED_MAX the banded kernel's dense scratch matrix would be too large: the Python reference.
    import img2logo._compiled.kernels as kernels

    calls = []
    monkeypatch.setattr(kernels, "sqp_banded", lambda *a: calls.append(a))
    monkeypatch.setattr(cfit, "KKT_COMPILED_MAX", 50)
    fit = fit_constrained(*_loop(12, 5))
    assert fit.converged and not calls


@pytest.mark.parametrize("seed", range(4))
def test_global_loop_matches_the_reference(monkeypatch, seed):
    # A global solve: every variable of a 30-arc loop free (120 unknowns + 60 multipliers), solved in a band.
    compiled, reference = _both(monkeypatch, *_loop(30, 200 + seed, noise=1.0, jitter=3.0))
    _assert_same(compiled, reference)


def test_global_loop_iterates_match_the_reference(monkeypatch):
    # Stopped after k steps the banded kernel and the reference are at the same iterate.
    for k in range(1, 4):
        compiled, reference = _both(monkeypatch, *_loop(24, 13, noise=1.0, jitter=4.0), max_iter=k)
        assert compiled.iterations == reference.iterations == k
        _assert_same(compiled, reference, tol=1e-9)


def test_global_loop_with_tangencies_and_fixed_parts_matches_the_reference(monkeypatch):
    # Tangent joins (Newton steps with their curvature), some circles and junctions fixed, a mirror axis.
    sets, radii, start, junctions, incidence = _loop(20, 21)
    tangents = [[i, i + 1, i + 1] for i in range(0, 18, 3)]
    compiled, reference = _both(
        monkeypatch, sets, radii, start, junctions, incidence, tangents=tangents,
        free_circles=[i for i in range(20) if i % 7], free_junctions=[k for k in range(20) if k % 5],
    )  # fmt: skip
    _assert_same(compiled, reference)
    compiled, reference = _both(
        monkeypatch, sets, radii, start, junctions, incidence, axis=300.0, axis_circles=[3], axis_junctions=[0]
    )
    _assert_same(compiled, reference)


# --- Redundant intersections -----------------------------------------------------


def _random_arcs(seed: int, n: int = 40):
    """Random arcs in a 200 px square, with repeats of circles (overlaps), tangent circles and whole circles."""
    rng = np.random.default_rng(seed)
    arcs = []
    for i in range(n):
        if i >= 4 and i % 7 == 0:  # another arc of an earlier circle
            circle = arcs[i - 3].circle
        elif i >= 4 and i % 11 == 0:  # a circle tangent (outside) to an earlier one
            c = arcs[i - 2].circle
            r = float(rng.uniform(5, 60))
            t = float(rng.uniform(-math.pi, math.pi))
            circle = Circle(c.cx + (c.r + r) * math.cos(t), c.cy + (c.r + r) * math.sin(t), r)
        else:
            circle = Circle(*rng.uniform(0, 200, 2), float(rng.uniform(5, 80)))
        sweep = TAU if i % 13 == 5 else float(rng.uniform(0.2, 6.0)) * (1 if rng.random() < 0.5 else -1)
        arcs.append(Arc(circle, float(rng.uniform(-math.pi, math.pi)), sweep))
    junctions = rng.uniform(0, 200, (30, 2))
    owned = [rng.choice(30, size=int(rng.integers(0, 4)), replace=False) for _ in range(n)]
    # Some junctions on both arcs of a meeting pair, exactly where they meet.
    for i, j in arc_pairs_reference(arcs, np.arange(n), INTERSECTION_TOL)[::3]:
        pts = arc_intersections(arcs[i], arcs[j])
        if len(pts):
            k = len(junctions)
            junctions = np.vstack([junctions, pts[:1]])
            owned[i], owned[j] = np.append(owned[i], k), np.append(owned[j], k)
    return arcs, junctions, [list(map(int, o)) for o in owned]


@pytest.mark.parametrize("seed", range(5))
def test_arc_pairs_near_matches_the_reference(seed):
    arcs, _, _ = _random_arcs(seed)
    for rows in (np.arange(len(arcs)), np.array([0, 5, 7]), np.array([len(arcs) - 1])):
        assert arc_pairs_near(arcs, rows, INTERSECTION_TOL) == arc_pairs_reference(arcs, rows, INTERSECTION_TOL)


@pytest.mark.parametrize("seed", range(5))
def test_redundant_intersections_match_the_reference(seed):
    arcs, junctions, owned = _random_arcs(seed)
    for candidates in (None, [3, 14, 21]):
        rows = np.arange(len(arcs)) if candidates is None else np.array(candidates)
        got = redundant_intersections(arcs, junctions, owned, candidates=candidates)
        want = redundant_reference(arcs, junctions, [np.array(o, dtype=np.int64) for o in owned], rows, 1.0)
        assert [(r.arc_a, r.arc_b) for r in got] == [(r.arc_a, r.arc_b) for r in want]
        assert len(got) > 0
        for r, w in zip(got, want, strict=True):
            assert r.point == pytest.approx(w.point, abs=1e-9)
            assert not r.point.flags.writeable


def test_intersection_kernel_matches_arc_intersections():
    import img2logo._compiled.kernels as kernels

    arcs, _, _ = _random_arcs(9, 60)
    out = np.empty((4, 2))
    pairs = 0
    for i in range(len(arcs)):
        for j in range(len(arcs)):
            want = arc_intersections(arcs[i], arcs[j])
            k = kernels.arc_intersections_kernel(
                arc_params([arcs[i]])[0], arc_params([arcs[j]])[0], INTERSECTION_TOL, out
            )
            assert out[:k] == pytest.approx(want, abs=1e-9), (i, j)
            pairs += k > 0
    assert pairs > 100


# --- Arc extraction --------------------------------------------------------------


@pytest.mark.parametrize("seed", range(8))
def test_extract_arc_matches_the_reference(seed):
    # A noisy pixel chain along an arc of a circle, its junctions on the circle (2 to 4, a closed loop for seed 0).
    rng = np.random.default_rng(seed)
    for _ in range(20):
        circle = Circle(*rng.uniform(50, 250, 2), float(PHI ** rng.uniform(2, 14)))
        t0, sweep = rng.uniform(-math.pi, math.pi), rng.uniform(0.1, 2 * math.pi) * rng.choice([-1, 1])
        if seed == 0:
            sweep = TAU
        t = t0 + sweep * np.linspace(0.0, 1.0, int(rng.integers(3, 200)))
        seg = circle.point_at(t) + rng.normal(0.0, rng.uniform(0.0, 2.0), (len(t), 2))
        inner = np.sort(rng.uniform(0.0, 1.0, int(rng.integers(0, 3))))
        junctions = circle.point_at(t0 + sweep * np.concatenate([[0.0], inner, [1.0]]))
        got = extract_arc(circle, seg, junctions)
        want = extract_reference(circle, seg, junctions)
        assert (got.arc.theta0, got.arc.sweep, got.frechet) == (want.arc.theta0, want.arc.sweep, want.frechet)


def test_extract_arc_when_every_candidate_is_too_long_matches_the_reference():
    # A 1 px chain between junctions a quarter circle apart: both candidates exceed the cap
    # (3 x 1 + 10 px), the shortest is kept and sampled as if it were cap long.
    circle = Circle(0.0, 0.0, 100.0)
    seg = np.array([[100.0, 0.0], [100.0, 1.0]])
    junctions = circle.point_at(np.array([0.0, math.pi / 2]))
    got, want = extract_arc(circle, seg, junctions), extract_reference(circle, seg, junctions)
    assert (got.arc.theta0, got.arc.sweep, got.frechet) == (want.arc.theta0, want.arc.sweep, want.frechet)
    assert got.arc.sweep == pytest.approx(math.pi / 2)


def test_without_a_disk_cache_the_kernels_still_run(monkeypatch):
    # A read-only install (numba cannot cache) compiles the kernels in the process: the fit has no
    # second path, the same kernels run.
    import img2logo._compiled.kernels as kernels

    called = []
    monkeypatch.setattr(kernels, "CACHED", False)
    for name in ("sqp_dense", "extract_arc_kernel", "redundant_kernel", "arc_pairs_kernel"):
        kernel = getattr(kernels, name)
        monkeypatch.setattr(kernels, name, lambda *a, _k=kernel, _n=name: called.append(_n) or _k(*a))
    sets, radii, start, junctions, incidence = _loop(4, 21)
    assert fit_constrained(sets, radii, start, junctions, incidence).converged
    arcs, junction_points, owned = _random_arcs(2)
    assert redundant_intersections(arcs, junction_points, owned)
    assert arc_pairs_near(arcs, np.arange(3), INTERSECTION_TOL) == arc_pairs_reference(
        arcs, np.arange(3), INTERSECTION_TOL
    )
    circle = Circle(0.0, 0.0, 100.0)
    got = extract_arc(circle, circle.point_at(np.linspace(0.0, 1.0, 50)), circle.point_at(np.array([0.0, 1.0])))
    assert got.arc.sweep == pytest.approx(1.0)
    assert set(called) == {"sqp_dense", "extract_arc_kernel", "redundant_kernel", "arc_pairs_kernel"}


# --- Circle fits: the free fit (Hyper, by Newton), a golden circle's centre -------------


def _pixel_arc(rng, m):
    r, sweep, c = rng.uniform(2, 300), rng.uniform(0.2, 6.3), rng.uniform(0, 512, 2)
    theta = rng.uniform(0, sweep, m)
    return np.round((c + r * np.c_[np.cos(theta), np.sin(theta)]) * 2) / 2 + rng.normal(0, 0.3, (m, 2))


@pytest.mark.parametrize("seed", range(4))
def test_free_circle_kernel_matches_the_svd_reference(seed):
    rng = np.random.default_rng(seed)
    for _ in range(100):
        p = _pixel_arc(rng, int(rng.integers(3, 150)))
        ref = circle_fitting._fit_circle_svd(p, None, False)
        got = fit_circle(p, refine=False)
        assert got.capped == ref.capped
        assert np.max(np.abs(got.center - ref.center)) <= 1e-9 * max(ref.radius, 1.0)
        assert got.radius == pytest.approx(ref.radius, rel=1e-9) and got.rms == pytest.approx(ref.rms, abs=1e-9)


def test_free_circle_kernel_caps_straight_points_and_refuses_what_the_reference_refuses():
    line = np.c_[np.arange(10.0), 2.0 * np.arange(10.0)]
    bent = line + np.array([[0.0, 0.0]] * 9 + [[0.1, 0.0]])
    for p, max_radius in ((line, None), (bent, 50.0), (line[::-1], None)):
        got = fit_circle(p, max_radius=max_radius, refine=False)
        ref = circle_fitting._fit_circle_svd(p, max_radius, False)
        assert got.capped and ref.capped and got.radius == ref.radius
        assert np.allclose(got.center, ref.center, atol=1e-9)
    with pytest.raises(FitError, match="at least 3 distinct points, got 2"):
        fit_circle([[0, 0], [1, 1], [0, 0]], refine=False)
    with pytest.raises(FitError, match="less than half the points' extent"):
        fit_circle(line, max_radius=1.0, refine=False)


def _fit_center_reference(p: np.ndarray, r: float, o: np.ndarray, iterations: int) -> np.ndarray:
    """:func:`~img2logo.geometry.circle_fitting.fit_center` in numpy: the compiled kernel's oracle."""
    for _ in range(iterations):
        vx, vy = o[0] - p[:, 0], o[1] - p[:, 1]
        dist = np.sqrt(vx * vx + vy * vy)  # np.hypot is ~5x slower; px cannot overflow
        dist[dist == 0] = 1e-12
        ux, uy = vx / dist, vy / dist
        e = dist - r
        jtj = np.array([[ux @ ux, ux @ uy], [ux @ uy, uy @ uy]])
        step = np.linalg.lstsq(jtj, -np.array([ux @ e, uy @ e]), rcond=None)[0]
        o += step
        if float(np.abs(step).max()) < 1e-9:
            break
    return o


def test_fit_center_and_mean_abs_error_kernels_match_the_reference():
    rng = np.random.default_rng(5)
    for _ in range(300):
        p = _pixel_arc(rng, int(rng.integers(2, 100)))
        start, radius = p.mean(axis=0) + rng.normal(0, 30, 2), rng.uniform(2, 300)
        ref = _fit_center_reference(p, radius, start.copy(), 8)
        got = fit_center(p, radius, start)
        assert np.max(np.abs(got - ref)) <= 1e-9
        assert mean_abs_error(p, got, radius) == pytest.approx(
            float(np.mean(np.abs(np.hypot(*(p - got).T) - radius))), abs=1e-12
        )
    # All the points at the centre: no direction, no step (least squares' minimum norm).
    assert np.array_equal(fit_center(np.zeros((3, 2)), 2.0, [0.0, 0.0]), [0.0, 0.0])


# --- Loading: ahead of time, just in time ----------------------------------------


def _aot_or_skip():
    import sysconfig

    import img2logo._compiled.kernels as kernels

    kernels.usable()
    if not kernels.source.endswith(sysconfig.get_config_var("EXT_SUFFIX")):
        pytest.skip("no ahead-of-time module here (no C compiler): the kernels run by numba's JIT")
    return kernels


def test_ahead_of_time_and_jit_kernels_agree_bit_for_bit(monkeypatch):
    # One numba code, one set of types, the same processor: the same floating-point operations.
    import importlib

    kernels = _aot_or_skip()

    def run():
        fits = [fit_constrained(*_loop(n, seed)) for n, seed in ((3, 1), (5, 2), (6, 3))]
        arcs, junctions, owned = _random_arcs(4)
        rng = np.random.default_rng(7)
        circle = Circle(120.0, 90.0, 60.0)
        seg = circle.point_at(np.linspace(0.3, 2.5, 80)) + rng.normal(0.0, 1.0, (80, 2))
        arc = extract_arc(circle, seg, circle.point_at(np.array([0.3, 1.4, 2.5])))
        free = fit_circle(seg, refine=False)
        golden = fit_center(seg, 55.0, free.center)
        return (
            fits,
            redundant_intersections(arcs, junctions, owned),
            arc,
            free,
            golden,
            mean_abs_error(seg, golden, 55.0),
        )

    aot = run()
    for name, (source, _, _) in kernels.ENTRY_POINTS.items():
        module = importlib.import_module(f"img2logo._compiled.{source}")
        monkeypatch.setitem(kernels._loaded, name, getattr(module, name))
    jit = run()
    for a, b in zip(aot[0], jit[0], strict=True):
        assert a.centers.tobytes() == b.centers.tobytes() and a.displacements.tobytes() == b.displacements.tobytes()
        assert (a.objective, a.violation, a.iterations) == (b.objective, b.violation, b.iterations)
    assert [(r.arc_a, r.arc_b, r.point.tobytes()) for r in aot[1]] == [
        (r.arc_a, r.arc_b, r.point.tobytes()) for r in jit[1]
    ]
    (a, b) = (aot[2], jit[2])
    assert (a.arc.theta0, a.arc.sweep, a.frechet) == (b.arc.theta0, b.arc.sweep, b.frechet)
    assert aot[3].center.tobytes() == jit[3].center.tobytes() and (aot[3].radius, aot[3].rms) == (
        jit[3].radius,
        jit[3].rms,
    )
    assert aot[4].tobytes() == jit[4].tobytes() and aot[5] == jit[5]


def test_an_ahead_of_time_entry_point_checks_its_arrays():
    kernels = _aot_or_skip()
    p = np.array([[0.0, 0.0], [3.0, 4.0], [6.0, 8.0]])
    # Converted: a strided view and integers give the same distance as the C-contiguous float array.
    assert kernels.frechet(p[::2], np.array([[0, 0], [6, 8]]), math.inf) == kernels.frechet(
        np.ascontiguousarray(p[::2]), np.array([[0.0, 0.0], [6.0, 8.0]]), math.inf
    )
    with pytest.raises(TypeError, match="must have 2 dimensions, got 1"):
        kernels.frechet(p[0], p, math.inf)
    with pytest.raises(TypeError, match="argument 3 of arc_intersections_kernel must be a C-contiguous float64"):
        kernels.arc_intersections_kernel(p[0], p[1], 1e-6, np.empty((4, 2), dtype=np.float32))


def test_the_command_loads_no_numba(tmp_path):
    # A run imports the ahead-of-time module, not numba (its import and registries were ~0.7 s of CPU a run).
    _aot_or_skip()
    code = (
        "import sys, numpy as np\n"
        "from img2logo.fit.constrained_fit import fit_constrained\n"
        "from img2logo.geometry.primitives import Circle\n"
        "c = Circle(0.0, 0.0, 10.0)\n"
        "fit_constrained([c.point_at(np.linspace(0, 3, 20))], np.array([10.0]), np.array([[0.5, 0.2]]),"
        " np.zeros((0, 2)), np.zeros((0, 2), dtype=int))\n"
    )
    assert modules_loaded(code, "numba", cwd=tmp_path) == []


def test_two_threads_loading_at_once_both_get_every_entry_point(monkeypatch):
    """A photo's run loads the kernels from two threads; neither may see half of them."""
    import threading

    import img2logo._compiled.kernels as kernels

    real = kernels._entry_points
    calls = []

    def slow():  # widens the window in which the other thread could look
        calls.append(1)
        threading.Event().wait(0.05)
        return real()

    monkeypatch.setattr(kernels, "_loaded", {})
    monkeypatch.setattr(kernels, "_entry_points", slow)
    seen = []
    threads = [threading.Thread(target=lambda: seen.append(set(kernels._load()))) for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert seen == [set(kernels.ENTRY_POINTS)] * 2
    assert len(calls) == 1


def largest_gap_reference(points: np.ndarray, cx: float, cy: float, radius: float) -> float:
    """The farthest point's distance from the circle, in numpy: the oracle of ``largest_gap_kernel``."""
    return float(np.max(np.abs(np.hypot(points[:, 0] - cx, points[:, 1] - cy) - radius)))


def test_largest_gap_kernel_matches_the_reference():
    from img2logo._compiled import kernels

    rng = np.random.default_rng(17)
    for _ in range(50):
        points = rng.uniform(-300.0, 300.0, (int(rng.integers(1, 400)), 2))
        cx, cy, radius = *rng.uniform(-200.0, 200.0, 2), float(rng.uniform(1.0, 1e6))
        got = kernels.largest_gap_kernel(points, cx, cy, radius)
        assert got == pytest.approx(largest_gap_reference(points, cx, cy, radius), rel=1e-12, abs=1e-9)
