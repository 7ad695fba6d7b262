"""Tests of the free circle fits: Hyper fit, capping, fixed-radius centre, mean error (Sec. 5.3, Eqn. 9)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import arc_points

from img2logo.constants import MAX_RADIUS_FACTOR
from img2logo.errors import FitError, InvalidParameterError
from img2logo.geometry.circle_fitting import fit_center, fit_circle, mean_abs_error

# --- Helpers ------------------------------------------------------------------------


def kasa_radius(p):
    """Radius of the Kasa fit (what scikit-image's CircleModel does), for comparison."""
    a = np.column_stack([2 * p, np.ones(len(p))])
    (cx, cy, c), *_ = np.linalg.lstsq(a, np.sum(p * p, axis=1), rcond=None)
    return math.sqrt(c + cx * cx + cy * cy)


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


def test_fit_center_recovers_a_fixed_radius_centre():
    t = np.linspace(0.2, 1.4, 120)
    pts = np.column_stack([40.0 + 25.0 * np.cos(t), -10.0 + 25.0 * np.sin(t)])
    np.testing.assert_allclose(fit_center(pts, 25.0, [35.0, -5.0]), [40.0, -10.0], atol=1e-8)


def test_unrefined_hyper_fit_is_close_on_pixel_arcs():
    # The optimizer uses the Hyper fit alone: on a rasterized arc it must agree
    # with the refined fit to a small fraction of a pixel.
    t = np.linspace(0.3, 1.5, 200)
    pts = np.floor(np.column_stack([200 + 90 * np.cos(t), 150 + 90 * np.sin(t)])) + 0.5
    a, b = fit_circle(pts), fit_circle(pts, refine=False)
    assert abs(a.radius - b.radius) < 0.5
    assert np.hypot(*(a.center - b.center)) < 0.5
