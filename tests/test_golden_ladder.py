"""Tests of the golden ratio ladder (paper Eqn. 10-12, 14; Sec. 7 Fig. 15)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from img2logo.constants import PHI
from img2logo.errors import InvalidParameterError
from img2logo.geometry import Circle
from img2logo.golden_ladder import GoldenLadder, bias_from_radius, golden_circle

biases = st.floats(min_value=0.0, max_value=1.0, exclude_max=True)
radii = st.floats(min_value=1e-3, max_value=1e6)


# --- Known answers ------------------------------------------------------------------


def test_radius_is_a_power_of_phi():
    assert GoldenLadder(0.0).radius(0) == 1.0
    assert GoldenLadder(0.0).radius(1) == pytest.approx(PHI, rel=1e-15)
    assert GoldenLadder(0.0).radius(2) == pytest.approx(PHI + 1.0, rel=1e-15)  # phi^2 = phi + 1
    assert GoldenLadder(0.5).radius(3) == pytest.approx(PHI**3.5, rel=1e-15)
    assert GoldenLadder(0.25).radius(-1) == pytest.approx(PHI**-0.75, rel=1e-15)


def test_ratios_are_integer_powers_of_phi():  # Eqn. 11
    ladder = GoldenLadder(0.37)
    for ki, kj in [(5, 2), (9, 9), (3, 7)]:
        assert ladder.radius(ki) / ladder.radius(kj) == pytest.approx(PHI ** (ki - kj), rel=1e-13)


def test_exponent_is_continuous_log_phi_minus_bias():
    ladder = GoldenLadder(0.2)
    assert ladder.exponent(PHI**4.7) == pytest.approx(4.5, abs=1e-12)


def test_ceil_snap_rounds_up():  # Eqn. 12
    ladder = GoldenLadder(0.0, rounding="ceil")
    assert ladder.snap(PHI**3.01) == (4, pytest.approx(PHI**4))
    assert ladder.snap(PHI**3.99)[0] == 4
    assert ladder.snap(PHI**2.2 * 1.0)[0] == 3
    assert GoldenLadder(0.5, rounding="ceil").snap(10.0) == (5, pytest.approx(PHI**5.5))  # log_phi 10 = 4.785


def test_nearest_snap_rounds_in_log_space():
    ladder = GoldenLadder(0.0)
    assert ladder.rounding == "nearest"
    assert ladder.snap(PHI**3.01) == (3, pytest.approx(PHI**3))
    assert ladder.snap(PHI**3.49)[0] == 3
    assert ladder.snap(PHI**3.51)[0] == 4
    assert GoldenLadder(0.5).snap(10.0) == (4, pytest.approx(PHI**4.5))  # log_phi 10 - 0.5 = 4.285


def test_bad_rounding():
    with pytest.raises(InvalidParameterError, match="rounding must be one of 'nearest', 'ceil', got 'floor'"):
        GoldenLadder(0.0, rounding="floor")


@pytest.mark.parametrize("rounding", ["nearest", "ceil"])
def test_snap_of_a_ladder_radius_is_itself(rounding):
    for bias in (0.0, 0.3, 0.999):
        ladder = GoldenLadder(bias, rounding=rounding)
        for k in range(-5, 30):
            assert ladder.snap(ladder.radius(k)) == (k, ladder.radius(k))


def test_snap_many_matches_snap():
    ladder = GoldenLadder(0.61)
    r = np.array([[0.5, 3.0], [17.2, 900.0]])
    k, snapped = ladder.snap_many(r)
    assert k.shape == r.shape and snapped.shape == r.shape
    for idx in np.ndindex(r.shape):
        assert (k[idx], snapped[idx]) == ladder.snap(float(r[idx]))


def test_subset_snaps_to_nearest_allowed_exponent():  # Sec. 7, Fig. 15
    ladder = GoldenLadder(0.0, exponents=(9, 3, 6, 6))
    assert ladder.exponents == (3, 6, 9)
    assert ladder.snap(PHI**4.4) == (3, pytest.approx(PHI**3))  # nearest, not rounded up
    assert ladder.snap(PHI**4.6)[0] == 6
    assert ladder.snap(PHI**4.5)[0] == 6  # a tie goes to the larger radius
    assert ladder.snap(PHI**40)[0] == 9
    assert ladder.snap(1e-3)[0] == 3
    assert ladder.snap_many(np.array([PHI**4.4, PHI**8.0]))[0].tolist() == [3, 9]


def test_bias_from_radius():  # Eqn. 14
    assert bias_from_radius(PHI**3.25) == pytest.approx(0.25, abs=1e-12)
    assert bias_from_radius(PHI**-2.75) == pytest.approx(0.25, abs=1e-12)
    assert bias_from_radius(1.0) == 0.0
    b = bias_from_radius(PHI**7)  # 0 or just below 1, depending on rounding
    assert min(b, 1.0 - b) < 1e-12


def test_bias_from_radius_puts_the_radius_on_the_ladder():
    r = 123.456
    ladder = GoldenLadder(bias_from_radius(r))
    k, snapped = ladder.snap(r)
    assert snapped == pytest.approx(r, rel=1e-12)
    assert k == math.floor(math.log(r) / math.log(PHI))


def test_golden_circle():
    c = golden_circle((10.0, 20.0), 7.0, GoldenLadder(0.5))
    assert isinstance(c, Circle)
    assert (c.cx, c.cy, c.k) == (10.0, 20.0, 4)  # log_phi 7 - 0.5 = 3.54
    assert c.r == pytest.approx(PHI**4.5)


# --- Invariants ---------------------------------------------------------------------


@given(r=st.floats(min_value=1e-300, max_value=1e300))
def test_bias_is_always_in_unit_interval(r):
    assert 0.0 <= bias_from_radius(r) < 1.0


@given(bias=biases, r=radii)
def test_snapped_radius_is_the_smallest_ladder_radius_not_below_r(bias, r):
    ladder = GoldenLadder(bias, rounding="ceil")
    k, snapped = ladder.snap(r)
    assert snapped == ladder.radius(k)
    assert snapped >= r
    assert snapped < r * PHI * (1 + 1e-12)
    assert ladder.radius(k - 1) < r


@given(bias=biases, r=radii, exps=st.lists(st.integers(-10, 40), min_size=1, max_size=6))
def test_subset_snap_is_allowed_and_nearest(bias, r, exps):
    ladder = GoldenLadder(bias, exponents=tuple(exps))
    k, snapped = ladder.snap(r)
    assert k in exps
    assert snapped == ladder.radius(k)
    x = ladder.exponent(r)
    assert abs(k - x) <= min(abs(e - x) for e in exps) + 1e-9


# --- Bad input ----------------------------------------------------------------------


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"bias": 1.2}, r"bias must be in \[0, 1\), got 1.2"),
        ({"bias": 1.0}, r"bias must be in \[0, 1\), got 1.0"),
        ({"bias": -0.1}, r"bias must be in \[0, 1\), got -0.1"),
        ({"bias": float("nan")}, r"bias must be in \[0, 1\), got nan"),
        ({"bias": "a"}, r"bias must be a number, got 'a'"),
        ({"bias": 0.5, "exponents": ()}, "exponents must not be empty"),
        ({"bias": 0.5, "exponents": (1, 2.5)}, "exponents must be integers, got 2.5"),
        ({"bias": 0.5, "exponents": (True,)}, "exponents must be integers, got True"),
    ],
)
def test_bad_ladder(kwargs, message):
    with pytest.raises(InvalidParameterError, match=message):
        GoldenLadder(**kwargs)


def test_numpy_integer_exponents_are_accepted():
    assert GoldenLadder(0.1, exponents=np.array([4, 2])).exponents == (2, 4)


@pytest.mark.parametrize(
    ("r", "message"),
    [(0.0, r"radius must be > 0, got 0.0"), (-3.0, "radius must be > 0"), (math.inf, "radius must be finite")],
)
def test_bad_radius(r, message):
    ladder = GoldenLadder(0.3)
    with pytest.raises(InvalidParameterError, match=message):
        ladder.snap(r)
    with pytest.raises(InvalidParameterError, match=message):
        ladder.exponent(r)
    with pytest.raises(InvalidParameterError, match=message):
        bias_from_radius(r)


def test_bad_exponent():
    with pytest.raises(InvalidParameterError, match=r"k must be an integer, got 2\.5"):
        GoldenLadder(0.3).radius(2.5)


def test_bad_radii_in_snap_many():
    with pytest.raises(InvalidParameterError, match="radii must be finite and > 0"):
        GoldenLadder(0.3).snap_many(np.array([1.0, np.nan]))


def test_bad_center():
    with pytest.raises(InvalidParameterError, match=r"center must have shape \(2,\), got \(3,\)"):
        golden_circle((1.0, 2.0, 3.0), 5.0, GoldenLadder(0.0))


@given(bias=biases, r=radii)
def test_nearest_snap_is_within_sqrt_phi(bias, r):
    _, snapped = GoldenLadder(bias).snap(r)
    assert r / np.sqrt(PHI) * (1 - 1e-12) <= snapped <= r * np.sqrt(PHI) * (1 + 1e-12)


def test_a_fitted_radius_a_hair_above_a_rung_snaps_to_it():
    ladder = GoldenLadder(0.3, rounding="ceil")
    rung = ladder.radius(8)
    assert ladder.snap(rung * (1 + 1e-12)) == (8, rung)
    assert ladder.snap(rung * (1 + 1e-6))[0] == 9
