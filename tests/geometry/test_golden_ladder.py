"""Tests of the golden ratio ladder (paper Eqn. 10-12, 14; Sec. 7 Fig. 15)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, strategies as st

from img2logo.constants import PHI
from img2logo.errors import InvalidParameterError
from img2logo.geometry.golden_ladder import (
    FIBONACCI_MAX_UNIT,
    FibonacciLadder,
    GoldenLadder,
    bias_from_radius,
    fibonacci,
    make_ladder,
    unit_from_radius,
)
from img2logo.geometry.primitives import Circle, golden_circle

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


@given(bias=biases, r=radii, exps=st.lists(st.integers(-10, 32), min_size=1, max_size=6))
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


# --- The Fibonacci grid (paper Fig. 2b, 3a; contract "ladder": "fibonacci") ----------

FIB = [0, 1, 1, 2, 3, 5, 8, 13, 21, 34, 55, 89, 144, 233, 377, 610]
units = st.floats(min_value=1e-2, max_value=1e2)


def test_fibonacci_numbers():
    assert [fibonacci(k) for k in range(len(FIB))] == FIB
    assert fibonacci(100) == 354224848179261915075  # exact, beyond float precision
    with pytest.raises(InvalidParameterError, match="k must be >= 0, got -1"):
        fibonacci(-1)
    with pytest.raises(InvalidParameterError, match=r"k must be an integer, got 2\.0"):
        fibonacci(2.0)


def test_fibonacci_radii_are_unit_times_fibonacci_numbers():
    ladder = FibonacciLadder(2.5)
    assert [ladder.radius(k) for k in range(1, 12)] == [2.5 * f for f in FIB[1:12]]
    assert ladder.radius(1) == ladder.radius(2) == 2.5  # F(1) = F(2): one radius, the unit
    for k in range(3, 40):  # every circle is the sum of the two below it (designers' grid)
        assert ladder.radius(k) == pytest.approx(ladder.radius(k - 1) + ladder.radius(k - 2), rel=1e-15)
    assert ladder.radius(41) / ladder.radius(40) == pytest.approx(PHI, rel=1e-15)
    assert ladder.bias == 0.0 and ladder.rounding == "nearest"


@pytest.mark.parametrize("rounding", ["nearest", "ceil"])
def test_fibonacci_rungs_snap_to_themselves_with_k_at_least_2(rounding):
    for unit in (0.7, 1.0, 3.3):
        ladder = FibonacciLadder(unit, rounding=rounding)
        for k in range(2, 60):
            assert ladder.snap(ladder.radius(k)) == (k, ladder.radius(k))
        assert ladder.snap(ladder.radius(1)) == (2, unit)  # F(1) = F(2): k = 2 keeps k and r one to one


def test_fibonacci_nearest_snap_in_log_space():
    ladder = FibonacciLadder(2.0)  # rungs 2, 4, 6, 10, 16, 26, ...
    border = math.sqrt(4.0 * 6.0)  # between F(3) and F(4): the geometric mean
    assert ladder.snap(border * (1 - 1e-9)) == (3, 4.0)
    assert ladder.snap(border * (1 + 1e-9)) == (4, 6.0)
    assert ladder.snap(2.83)[0] == 3  # sqrt(2 * 4) = 2.828...
    assert ladder.snap(2.82)[0] == 2
    assert ladder.snap(0.01) == (2, 2.0)  # nothing below the unit
    assert ladder.snap(1000.0) == (15, 1220.0)  # 754 < 1000 < 1220, nearer 1220 in log space


def test_fibonacci_ceil_snap_rounds_up():
    ladder = FibonacciLadder(2.0, rounding="ceil")
    assert ladder.snap(4.0001) == (4, 6.0)
    assert ladder.snap(4.0 * (1 + 1e-12)) == (3, 4.0)  # a hair above a rung is that rung
    assert ladder.snap(0.5) == (2, 2.0)
    assert ladder.snap(21.0) == (7, 26.0)


def test_fibonacci_subset_snaps_to_nearest_allowed_index():
    ladder = FibonacciLadder(2.0, exponents=(9, 3, 5, 5))
    assert ladder.exponents == (3, 5, 9)
    k, r = ladder.snap_many(np.array([1.0, 7.0, 20.0, 100.0]))
    assert k.tolist() == [3, 5, 5, 9] and r.tolist() == [4.0, 10.0, 10.0, 68.0]


def test_fibonacci_snap_many_matches_snap():
    ladder = FibonacciLadder(0.8)
    r = np.array([[0.3, 3.0], [17.2, 9000.0]])
    k, snapped = ladder.snap_many(r)
    assert k.shape == r.shape and snapped.shape == r.shape and k.dtype == np.int64
    for idx in np.ndindex(r.shape):
        assert (k[idx], snapped[idx]) == ladder.snap(float(r[idx]))


def test_fibonacci_exponent_is_k_at_the_rungs():
    ladder = FibonacciLadder(1.5)
    assert [ladder.exponent(ladder.radius(k)) for k in range(2, 30)] == pytest.approx(list(range(2, 30)), abs=1e-12)
    assert ladder.exponent(math.sqrt(ladder.radius(5) * ladder.radius(6))) == pytest.approx(5.5, abs=1e-12)
    assert ladder.exponent(0.75) == pytest.approx(1.0)  # below the unit: the first gap's ratio 2


@given(unit=units, r=radii)
def test_fibonacci_nearest_snap_is_the_nearest_rung(unit, r):
    ladder = FibonacciLadder(unit)
    k, snapped = ladder.snap(r)
    assert k >= 2 and snapped == ladder.radius(k) == unit * fibonacci(k)
    if r >= unit:  # rungs at most a factor 2 apart (F(3) / F(2)), so within sqrt(2)
        assert r / math.sqrt(2) * (1 - 1e-12) <= snapped <= r * math.sqrt(2) * (1 + 1e-12)
        x = ladder.exponent(r)
        assert abs(k - x) <= 0.5 + 1e-9
    gap = abs(math.log(snapped / r))
    for other in (k - 1, k + 1):
        if other >= 2:
            assert gap <= abs(math.log(ladder.radius(other) / r)) + 1e-12


@given(unit=units, r=radii)
def test_fibonacci_ceil_snap_is_the_smallest_rung_not_below_r(unit, r):
    ladder = FibonacciLadder(unit, rounding="ceil")
    k, snapped = ladder.snap(r)
    assert snapped >= r * (1 - 1e-9)
    assert k == 2 or ladder.radius(k - 1) < r


def test_unit_from_radius():
    assert unit_from_radius(200.0) == pytest.approx(200.0 / 233)  # the largest 200 / F(k) <= 1 px
    assert unit_from_radius(0.5) == 0.5  # already below 1 px: the radius is the unit (k = 2)
    assert unit_from_radius(1.5) == 0.75  # 1.5 / F(3)
    assert unit_from_radius(200.0, max_unit=10.0) == pytest.approx(200.0 / 21)
    with pytest.raises(InvalidParameterError, match=r"radius must be > 0, got 0\.0"):
        unit_from_radius(0.0)
    with pytest.raises(InvalidParameterError, match=r"max_unit must be > 0, got -1\.0"):
        unit_from_radius(3.0, max_unit=-1.0)


@given(r=st.floats(min_value=1.0, max_value=1e12))
def test_unit_from_radius_puts_the_radius_on_a_rung(r):  # the analogue of Eqn. 14
    unit = unit_from_radius(r)
    assert 0.5 < unit <= FIBONACCI_MAX_UNIT
    k, snapped = FibonacciLadder(unit).snap(r)
    assert snapped == pytest.approx(r, rel=1e-12)
    assert r / fibonacci(k - 1) > FIBONACCI_MAX_UNIT or k == 2  # the largest such unit


def test_make_ladder():
    assert make_ladder("phi", bias=0.25) == GoldenLadder(0.25)
    assert make_ladder("phi", PHI**3.25).bias == pytest.approx(0.25)  # Eqn. 14
    assert make_ladder("fibonacci", unit=3.0, exponents=[4, 2], rounding="ceil") == FibonacciLadder(3.0, (2, 4), "ceil")
    assert make_ladder("fibonacci", 200.0).unit == pytest.approx(200.0 / 233)


@pytest.mark.parametrize(
    ("args", "kwargs", "message"),
    [
        (("hex", 1.0), {}, "ladder must be one of 'phi', 'fibonacci', got 'hex'"),
        (("fibonacci", 1.0), {"bias": 0.3}, "bias is a parameter of the phi ladder; the Fibonacci ladder takes unit"),
        (("phi", 1.0), {"unit": 2.0}, r"unit is a parameter of the Fibonacci ladder \(ladder='fibonacci'\)"),
        (("fibonacci",), {}, "the Fibonacci ladder needs unit or a radius to choose it from"),
        (("phi",), {}, r"the phi ladder needs bias or a radius to choose it from \(Eqn. 14\)"),
    ],
)
def test_make_ladder_errors(args, kwargs, message):
    with pytest.raises(InvalidParameterError, match=message):
        make_ladder(*args, **kwargs)


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"unit": 0.0}, "unit must be > 0, got 0.0"),
        ({"unit": math.nan}, "unit must be finite, got nan"),
        ({"unit": 1.0, "rounding": "floor"}, "rounding must be one of 'nearest', 'ceil', got 'floor'"),
        ({"unit": 1.0, "exponents": ()}, "exponents must not be empty"),
        ({"unit": 1.0, "exponents": (3, 1)}, r"exponents of the Fibonacci ladder must be >= 2 \(F\(1\) = F\(2\) = 1"),
        ({"unit": 1.0, "exponents": (3, 2.5)}, "exponents must be integers, got 2.5"),
    ],
)
def test_bad_fibonacci_ladder(kwargs, message):
    with pytest.raises(InvalidParameterError, match=message):
        FibonacciLadder(**kwargs)


def test_bad_fibonacci_index_and_radius():
    ladder = FibonacciLadder(1.0)
    with pytest.raises(InvalidParameterError, match=r"k must be in 1\.\.1476 on the Fibonacci ladder"):
        ladder.radius(0)
    with pytest.raises(InvalidParameterError, match="radius must be > 0"):
        ladder.snap(-1.0)
    with pytest.raises(InvalidParameterError, match="radii must be finite and > 0"):
        ladder.snap_many(np.array([1.0, np.inf]))
    with pytest.raises(InvalidParameterError, match="is beyond the Fibonacci ladder of unit"):
        FibonacciLadder(1e-300).snap(1e300)


def test_golden_circle_on_the_fibonacci_ladder():
    c = golden_circle((1.0, 2.0), 7.0, FibonacciLadder(1.0))
    assert (c.r, c.k) == (8.0, 6)


@pytest.mark.parametrize("unit", [None, 3.0])
def test_the_optimizer_on_the_fibonacci_ladder(unit):
    pytest.importorskip("jsonschema")
    from helpers import drawing

    from img2logo import abstract
    from img2logo.export.contract import from_document, to_document, validate_document

    result = abstract(drawing("spiral"), ladder="fibonacci", unit=unit, progress=False)
    ladder = result.progression.ladder
    assert isinstance(ladder, FibonacciLadder) and result.bias == 0.0
    if unit is None:  # chosen from the longest segment (unit_from_radius)
        assert 0.5 < ladder.unit <= FIBONACCI_MAX_UNIT
    else:
        assert ladder.unit == unit
    for level in result.levels:
        assert level.bias == 0.0
        assert level.params["ladder"] == "fibonacci" and level.params["unit"] == ladder.unit
        assert level.params["unit_given"] == unit
        for c in level.circles:
            assert c.k >= 2 and c.r == ladder.radius(c.k) == pytest.approx(ladder.unit * fibonacci(c.k), rel=1e-12)
    doc = to_document(result.final)
    validate_document(doc)
    assert (doc["ladder"], doc["unit"], doc["bias"]) == ("fibonacci", ladder.unit, 0.0)
    assert from_document(doc).params["ladder"] == "fibonacci"


def test_the_optimizer_refuses_mixed_ladder_parameters():
    from helpers import drawing

    from img2logo import abstract

    with pytest.raises(InvalidParameterError, match="bias is a parameter of the phi ladder"):
        abstract(drawing("circle"), ladder="fibonacci", bias=0.2, progress=False)
    with pytest.raises(InvalidParameterError, match="ladder must be one of 'phi', 'fibonacci', got 'golden'"):
        abstract(drawing("circle"), ladder="golden", progress=False)
