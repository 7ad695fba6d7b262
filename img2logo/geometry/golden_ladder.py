"""The golden ratio ladder of radii r = phi ** (k + sigma) (paper Eqn. 10-12, 14).

A :class:`GoldenLadder` is the discrete set of radii a golden ratio logo may use:
``phi ** (k + bias)`` for integer exponents k and one bias sigma in [0, 1)
(Eqn. 10). Any two of its radii have a ratio that is an integer power of phi
(Eqn. 11). A fitted radius is snapped to the ladder by rounding its continuous
exponent *up* (Eqn. 12); the bias itself is estimated from one fitted radius
(Eqn. 14). The user may restrict the ladder to a subset of exponents (Sec. 7,
Fig. 15); a radius is then snapped to the allowed exponent nearest in log space.

The paper takes k as a non-negative integer; here any integer is allowed, so that
radii below 1 px (k < 0) stay representable. Radii are in px.

Beyond the paper, a :class:`FibonacciLadder` is the grid designers draw by hand
(paper Fig. 2b, 3a): radii ``unit * F(k)`` with the Fibonacci numbers F(1) = F(2)
= 1, F(3) = 2, 3, 5, 8, ... (the contract's ``"ladder": "fibonacci"``). It has
the same interface (``radius``, ``exponent``, ``snap``, ``snap_many``), so the
progressive optimization runs on either; :func:`make_ladder` builds the one a
run asks for. Ratios of consecutive rungs tend to phi (2, 1.5, 1.67, 1.6,
1.625, ...), and every rung is the sum of the two below it.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from .._validation import check_choice, check_positive
from ..constants import LOG_PHI, MAX_LENGTH, MIN_LADDER_RADIUS, PHI
from ..errors import InvalidParameterError
from .constants import LADDER_SNAP_RTOL

__all__ = [
    "FIBONACCI_MAX_UNIT",
    "FibonacciLadder",
    "GoldenLadder",
    "bias_from_radius",
    "fibonacci",
    "make_ladder",
    "unit_from_radius",
]

#: The automatic unit of a Fibonacci ladder is the largest ``r / F(k)`` not above
#: this, px (:func:`unit_from_radius`): no rung lies below the unit, so every
#: radius of at least a pixel stays on the ladder.
FIBONACCI_MAX_UNIT: float = 1.0

#: Largest Fibonacci index whose F(k) is a finite float64 (F(1476) ~ 1.3e308).
FIBONACCI_MAX_INDEX: int = 1476


def _check_radius(r: object) -> float:
    return check_positive(r, "radius")


def _check_exponents(exponents: object) -> tuple[int, ...]:
    """``exponents`` as a sorted tuple of distinct ints; raise if empty or not integers."""
    values = tuple(np.ravel(np.asarray(exponents, dtype=object)))
    if not values:
        raise InvalidParameterError("exponents must not be empty")
    for v in values:
        if isinstance(v, bool) or not isinstance(v, numbers.Integral):
            raise InvalidParameterError(f"exponents must be integers, got {v!r}")
    return tuple(sorted({int(v) for v in values}))


def _powers(exponents: np.ndarray) -> np.ndarray:
    # Every ladder radius goes through this one ufunc call: np.power and Python's **
    # may differ in the last bit, and snap must compare radii computed the same way.
    return np.power(PHI, np.asarray(exponents, dtype=np.float64))


@lru_cache(maxsize=1024)
def _power(exponent: float) -> float:
    """:func:`_powers` of one exponent, as a float: a rung's radius is asked for again and again (the tangent pass)."""
    return float(_powers(np.array([exponent]))[0])


@dataclass(frozen=True)
class GoldenLadder:
    """The golden ratio radii ``phi ** (k + bias)`` (Eqn. 10), optionally a subset.

    Parameters
    ----------
    bias : float
        The bias sigma in [0, 1) (Eqn. 10, 14).
    exponents : tuple of int or None
        If given, the only allowed exponents k (a user's choice of radii, Sec. 7,
        Fig. 15); stored sorted and without repeats. None allows every integer.
    rounding : {"nearest", "ceil"}
        How a fitted radius is snapped on the full ladder. ``"ceil"`` is the
        paper's Eqn. 12, the smallest rung >= r: a radius a hair above a rung
        (a noisy fit of a golden arc) then jumps a whole rung up, a factor phi.
        ``"nearest"`` (the default) takes the rung nearest in log space, so the
        radius is off by at most a factor sqrt(phi) and golden arcs keep their
        rung under noise.

    Raises
    ------
    InvalidParameterError
        If ``bias`` is not a finite number in [0, 1), or ``exponents`` is empty
        or holds a value that is not an integer.

    Examples
    --------
    >>> from img2logo import PHI, GoldenLadder
    >>> ladder = GoldenLadder(0.0)
    >>> ladder.radius(3) == PHI**3, ladder.snap(4.0)[0]  # 4 px is nearest to phi^3
    (True, 3)
    """

    bias: float
    exponents: tuple[int, ...] | None = None
    rounding: str = "nearest"

    def __post_init__(self) -> None:
        check_choice(self.rounding, "rounding", ("nearest", "ceil"))
        try:
            bias = float(self.bias)
        except (TypeError, ValueError) as exc:
            raise InvalidParameterError(f"bias must be a number, got {self.bias!r}") from exc
        if not (0.0 <= bias < 1.0):  # also rejects NaN
            raise InvalidParameterError(f"bias must be in [0, 1), got {bias}")
        object.__setattr__(self, "bias", bias)
        if self.exponents is not None:
            values = _check_exponents(self.exponents)
            # Compared in log space, so that no phi ** k overflows (k = 99999) or underflows.
            lo = math.ceil(math.log(MIN_LADDER_RADIUS) / LOG_PHI - bias)
            hi = math.floor(math.log(MAX_LENGTH) / LOG_PHI - bias)
            if values[0] < lo or values[-1] > hi:
                bad = values[0] if values[0] < lo else values[-1]
                raise InvalidParameterError(
                    f"exponents (--radii) must be in {lo}..{hi} (radii phi**(k + bias) from {MIN_LADDER_RADIUS:g} "
                    f"to {MAX_LENGTH:g} px), got k = {bad}"
                )
            object.__setattr__(self, "exponents", values)

    def radius(self, k: int) -> float:
        """The ladder radius ``phi ** (k + bias)`` of exponent ``k``, px (Eqn. 10).

        ``k`` must be an integer; it is not checked against a subset of ``exponents``.
        """
        # A plain int first: the abstract class's check costs more than the power (thousands of calls a run).
        if type(k) is not int and (isinstance(k, bool) or not isinstance(k, numbers.Integral)):
            raise InvalidParameterError(f"k must be an integer, got {k!r}")
        return _power(int(k) + self.bias)

    def exponent(self, r: float) -> float:
        """The continuous exponent ``log r / log phi - bias`` of radius ``r`` (px)."""
        return math.log(_check_radius(r)) / LOG_PHI - self.bias

    def snap(self, r: float) -> tuple[int, float]:
        """Snap a fitted radius ``r`` (px) to the ladder: ``(k, phi ** (k + bias))``.

        With ``rounding="nearest"`` (default), k is the integer nearest to the
        continuous exponent ``log r / log phi - bias``, so ``r / sqrt(phi) <=
        snapped <= r * sqrt(phi)``. With ``rounding="ceil"``, on the full ladder
        this is Eqn. 12, ``k = ceil(log r / log phi - bias)``:
        the smallest ladder radius >= ``r`` (less a relative ``LADDER_SNAP_RTOL``
        = 1e-9, the accuracy of a fit), so ``r <= snapped < r * phi``. The
        ceiling is taken on the radii themselves, so a radius that is already on
        the ladder snaps to itself despite rounding in the logarithm. With a
        subset of ``exponents``, k is the allowed exponent nearest to the
        continuous exponent (in log space; a tie goes to the larger radius).

        Raises
        ------
        InvalidParameterError
            If ``r`` is not finite or not > 0.
        """
        # The one radius checked here: snap_many's checks of an array cost more than the snap (the merge
        # loop snaps every new merged group's circle).
        k = int(self._snap_checked(np.array([_check_radius(r)]))[0][0])
        return k, self.radius(k)

    def snap_many(self, radii: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Vectorized :meth:`snap`: exponents (int64) and snapped radii (px), shape of ``radii``."""
        r = np.asarray(radii, dtype=np.float64)
        if not np.all(np.isfinite(r)) or np.any(r <= 0):
            raise InvalidParameterError("radii must be finite and > 0")
        return self._snap_checked(r)

    def _snap_checked(self, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """:meth:`snap_many` of float64 radii already known to be finite and > 0."""
        x = np.log(r) / LOG_PHI - self.bias
        if self.exponents is None and self.rounding == "nearest":
            k = np.floor(x + 0.5).astype(np.int64)  # ties go to the larger radius
        elif self.exponents is None:
            k = np.ceil(x)
            # Correct the ceiling by one where rounding put it on the wrong side.
            # A fitted radius within LADDER_SNAP_RTOL above a rung is that rung: a
            # clean fit is only exact to ~1e-12, and the ceiling would jump a rung.
            k = np.where(_powers(k - 1.0 + self.bias) >= r * (1.0 - LADDER_SNAP_RTOL), k - 1.0, k)
            k = np.where(_powers(k + self.bias) < r * (1.0 - LADDER_SNAP_RTOL), k + 1.0, k)
            k = k.astype(np.int64)
        else:
            allowed = np.asarray(self.exponents, dtype=np.int64)
            # Last index of the minimum distance: ties go to the larger exponent.
            dist = np.abs(x[..., None] - allowed)
            idx = allowed.size - 1 - np.argmin(dist[..., ::-1], axis=-1)
            k = allowed[idx]
        return k, _powers(k + self.bias)


def bias_from_radius(r: float) -> float:
    """The bias sigma in [0, 1) that puts radius ``r`` (px) on the ladder (Eqn. 14).

    ``sigma = log r / log phi - floor(log r / log phi)``. The paper fits ``r`` to
    the longest simplified segment (Sec. 5.4). A result that rounds to 1.0 is
    returned as 0.0, so the value is always in [0, 1).

    Raises
    ------
    InvalidParameterError
        If ``r`` is not finite or not > 0.
    """
    x = math.log(_check_radius(r)) / LOG_PHI
    sigma = x - math.floor(x)
    return sigma if sigma < 1.0 else 0.0


# --------------------------------------------------------------------------- the Fibonacci grid
def fibonacci(k: int) -> int:
    """The Fibonacci number F(k), exactly: F(0) = 0, F(1) = F(2) = 1, F(3) = 2, F(4) = 3, ...

    Raises
    ------
    InvalidParameterError
        If ``k`` is not an integer >= 0.
    """
    if isinstance(k, bool) or not isinstance(k, numbers.Integral):
        raise InvalidParameterError(f"k must be an integer, got {k!r}")
    if k < 0:
        raise InvalidParameterError(f"k must be >= 0, got {k}")
    a, b = 0, 1
    for _ in range(int(k)):
        a, b = b, a + b
    return a


@lru_cache(maxsize=1)
def _fibonacci_table() -> np.ndarray:
    """F(0) ... F(FIBONACCI_MAX_INDEX) as float64, each the float nearest the exact integer (read-only)."""
    values = [0, 1]
    while len(values) <= FIBONACCI_MAX_INDEX:
        values.append(values[-1] + values[-2])
    table = np.array([float(v) for v in values])
    table.setflags(write=False)
    return table


def _check_index(k: object) -> int:
    """``k`` as a Fibonacci ladder index: an integer in 1 .. FIBONACCI_MAX_INDEX."""
    if isinstance(k, bool) or not isinstance(k, numbers.Integral):
        raise InvalidParameterError(f"k must be an integer, got {k!r}")
    if not 1 <= k <= FIBONACCI_MAX_INDEX:
        raise InvalidParameterError(
            f"k must be in 1..{FIBONACCI_MAX_INDEX} on the Fibonacci ladder (F(1) = F(2) = 1 is the unit), got {k}"
        )
    return int(k)


@dataclass(frozen=True)
class FibonacciLadder:
    """The Fibonacci grid of radii ``unit * F(k)`` (paper Fig. 2b, 3a), optionally a subset.

    The circle grid logo designers draw by hand: circles of 1, 1, 2, 3, 5, 8, 13,
    ... units, every one the sum of the two below it, consecutive ratios tending to
    phi. Same interface as :class:`GoldenLadder`, so the progressive optimization
    runs on either (``optimize(..., ladder="fibonacci")``); an abstraction on it is
    written with the contract's ``"ladder": "fibonacci"`` and ``unit``.

    F(1) = F(2) = 1 are one radius, the unit: snapping always gives k >= 2, so
    that radii and indices correspond one to one (:meth:`radius` accepts k = 1,
    as the contract does). No rung lies below the unit, so a radius below it
    snaps to the unit (k = 2): choose the unit no larger than the smallest circle
    wanted (:func:`unit_from_radius` keeps it at most ``FIBONACCI_MAX_UNIT`` = 1 px).

    Parameters
    ----------
    unit : float
        The radius F(2) = 1 unit of the smallest circle, px (> 0).
    exponents : tuple of int or None
        If given, the only allowed indices k, each >= 2 (a user's choice of
        circles, as Sec. 7, Fig. 15 does on the phi ladder); stored sorted and
        without repeats. None allows every k >= 2.
    rounding : {"nearest", "ceil"}
        ``"nearest"`` (default): the rung nearest in log space (a tie goes to the
        larger radius). ``"ceil"``: the smallest rung >= r, as Eqn. 12 on the
        phi ladder (a radius within a relative ``LADDER_SNAP_RTOL`` above a rung
        is that rung).

    Raises
    ------
    InvalidParameterError
        If ``unit`` is not a finite number > 0, ``rounding`` is not one of the
        two, or ``exponents`` is empty or holds a value that is not an integer >= 2.

    Examples
    --------
    >>> from img2logo import FibonacciLadder
    >>> ladder = FibonacciLadder(1.0)
    >>> [ladder.radius(k) for k in range(1, 7)]
    [1.0, 1.0, 2.0, 3.0, 5.0, 8.0]
    """

    unit: float
    exponents: tuple[int, ...] | None = None
    rounding: str = "nearest"

    def __post_init__(self) -> None:
        check_choice(self.rounding, "rounding", ("nearest", "ceil"))
        unit = check_positive(self.unit, "unit")
        object.__setattr__(self, "unit", unit)
        if self.exponents is not None:
            values = _check_exponents(self.exponents)
            if values[0] < 2:
                raise InvalidParameterError(
                    "exponents of the Fibonacci ladder must be >= 2 (F(1) = F(2) = 1: k = 2 is the unit), "
                    f"got {values[0]}"
                )
            table = _fibonacci_table()
            top = int(np.searchsorted(table, MAX_LENGTH / unit, side="right")) - 1  # unit * F(top) <= MAX_LENGTH
            if values[-1] > top:
                raise InvalidParameterError(
                    f"exponents (--radii) of the Fibonacci ladder of unit {unit:g} px must be <= {top}, radii "
                    f"unit * F(k) up to {MAX_LENGTH:g} px, got {values[-1]}"
                )
            object.__setattr__(self, "exponents", values)

    @property
    def bias(self) -> float:
        """Always 0.0: the radii ``unit * F(k)`` have no bias.

        It is what the contract's ``bias`` field holds for a Fibonacci document,
        so code that records ``ladder.bias`` works with either ladder.
        """
        return 0.0

    def radius(self, k: int) -> float:
        """The ladder radius ``unit * F(k)`` of index ``k`` >= 1, px.

        ``k`` is not checked against a subset of ``exponents``.
        """
        return float(self.unit * _fibonacci_table()[_check_index(k)])

    def _rungs(self, r_max: float) -> tuple[np.ndarray, np.ndarray]:
        """Indices k = 2 .. K and their radii, K two rungs past the first >= ``r_max``."""
        table = _fibonacci_table()
        first = int(np.searchsorted(table, r_max / self.unit, side="left"))
        top = max(first + 1, 3)
        if top > FIBONACCI_MAX_INDEX:
            raise InvalidParameterError(
                f"radius {r_max!r} px is beyond the Fibonacci ladder of unit {self.unit!r} px "
                f"(F({FIBONACCI_MAX_INDEX}) units at most)"
            )
        ks = np.arange(2, top + 1, dtype=np.int64)
        return ks, self.unit * table[ks]

    def exponent(self, r: float) -> float:
        """The continuous index of radius ``r`` (px): k at ``unit * F(k)``, linear in log r between rungs.

        Rounding it to the nearest integer is snapping to the nearest rung in log
        space. Below the unit it continues with the first gap's ratio, 2:
        ``2 + log2(r / unit)``.
        """
        r = _check_radius(r)
        ks, rungs = self._rungs(r)
        j = int(np.searchsorted(rungs, r, side="right")) - 1
        if j < 0:
            return 2.0 + math.log2(r / self.unit)
        j = min(j, len(rungs) - 2)
        lo, hi = math.log(rungs[j]), math.log(rungs[j + 1])
        return float(ks[j]) + (math.log(r) - lo) / (hi - lo)

    def snap(self, r: float) -> tuple[int, float]:
        """Snap a fitted radius ``r`` (px) to the ladder: ``(k, unit * F(k))`` with k >= 2.

        See the class for ``rounding``; with a subset of ``exponents``, k is the
        allowed index nearest in log space (a tie goes to the larger radius). A
        radius on the ladder snaps to itself.

        Raises
        ------
        InvalidParameterError
            If ``r`` is not finite or not > 0, or beyond the largest rung.
        """
        k = int(self.snap_many(np.array([_check_radius(r)]))[0][0])
        return k, self.radius(k)

    def snap_many(self, radii: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Vectorized :meth:`snap`: indices (int64) and snapped radii (px), shape of ``radii``."""
        r = np.asarray(radii, dtype=np.float64)
        if not np.all(np.isfinite(r)) or np.any(r <= 0):
            raise InvalidParameterError("radii must be finite and > 0")
        if r.size == 0:
            return np.zeros(r.shape, dtype=np.int64), np.zeros(r.shape)
        table = _fibonacci_table()
        if self.exponents is not None:
            allowed = np.asarray(self.exponents, dtype=np.int64)
            dist = np.abs(np.log(r)[..., None] - np.log(self.unit * table[allowed]))
            # Last index of the minimum distance: ties go to the larger index.
            k = allowed[allowed.size - 1 - np.argmin(dist[..., ::-1], axis=-1)]
        else:
            ks, rungs = self._rungs(float(r.max()))
            if self.rounding == "nearest":
                j = np.clip(np.searchsorted(rungs, r, side="right") - 1, 0, rungs.size - 2)
                log_r, log_rungs = np.log(r), np.log(rungs)
                up = (log_rungs[j + 1] - log_r) <= (log_r - log_rungs[j])
                k = ks[j + up]
            else:
                i = np.searchsorted(rungs, r * (1.0 - LADDER_SNAP_RTOL), side="left")
                k = ks[np.minimum(i, rungs.size - 1)]
        k = np.asarray(k, dtype=np.int64)
        return k, self.unit * table[k]


#: Either ladder: the phi ladder of the paper or the designers' Fibonacci grid.
Ladder = GoldenLadder | FibonacciLadder


def unit_from_radius(r: float, max_unit: float = FIBONACCI_MAX_UNIT) -> float:
    """The Fibonacci ladder's unit that puts radius ``r`` (px) on a rung, at most ``max_unit``.

    The analogue of the bias of Eqn. 14: the optimization fits ``r`` to the
    longest simplified segment. ``unit = r / F(k)`` with k the smallest index >= 2
    for which that is <= ``max_unit`` (default ``FIBONACCI_MAX_UNIT`` = 1 px): the
    largest such unit, so that ``r`` is exactly ``unit * F(k)`` and every radius of
    at least ``max_unit`` lies within the ladder (none is below the unit). For
    ``r <= max_unit`` the unit is ``r`` itself.

    Raises
    ------
    InvalidParameterError
        If ``r`` or ``max_unit`` is not finite or not > 0.
    """
    r = _check_radius(r)
    m = check_positive(max_unit, "max_unit")
    table = _fibonacci_table()
    k = max(2, int(np.searchsorted(table, r / m, side="left")))
    while k < FIBONACCI_MAX_INDEX and r / table[k] > m:  # a rounding guard
        k += 1
    return float(r / table[k])


def make_ladder(
    ladder: str = "phi",
    radius: float | None = None,
    *,
    bias: float | None = None,
    unit: float | None = None,
    exponents: object = None,
    rounding: str = "nearest",
) -> Ladder:
    """The ladder of a run: the phi ladder (Eqn. 10) or the Fibonacci grid (Fig. 2b).

    Parameters
    ----------
    ladder : {"phi", "fibonacci"}
        Radii ``phi ** (k + bias)`` (:class:`GoldenLadder`) or ``unit * F(k)``
        (:class:`FibonacciLadder`).
    radius : float, optional
        The fitted radius of the longest segment, px: gives the bias (Eqn. 14,
        :func:`bias_from_radius`) or the unit (:func:`unit_from_radius`) when
        that is not given.
    bias : float, optional
        The phi ladder's bias sigma in [0, 1).
    unit : float, optional
        The Fibonacci ladder's unit, px.
    exponents : sequence of int, optional
        Only these exponents / indices k.
    rounding : {"nearest", "ceil"}
        How a fitted radius is snapped.

    Returns
    -------
    GoldenLadder or FibonacciLadder

    Raises
    ------
    InvalidParameterError
        If ``ladder`` is not one of the two, ``bias`` is given with the
        Fibonacci ladder or ``unit`` with the phi ladder, neither the ladder's
        parameter nor ``radius`` is given, or a value is out of range.
    """
    check_choice(ladder, "ladder", ("phi", "fibonacci"))
    if ladder == "fibonacci":
        if bias is not None:
            raise InvalidParameterError(
                f"bias is a parameter of the phi ladder; the Fibonacci ladder takes unit, got bias={bias!r}"
            )
        if unit is None:
            if radius is None:
                raise InvalidParameterError("the Fibonacci ladder needs unit or a radius to choose it from")
            unit = unit_from_radius(radius)
        return FibonacciLadder(unit, exponents, rounding)  # type: ignore[arg-type]
    if unit is not None:
        raise InvalidParameterError(
            f"unit is a parameter of the Fibonacci ladder (ladder='fibonacci'), got unit={unit!r} with ladder='phi'"
        )
    if bias is None:
        if radius is None:
            raise InvalidParameterError("the phi ladder needs bias or a radius to choose it from (Eqn. 14)")
        bias = bias_from_radius(radius)
    return GoldenLadder(bias, exponents, rounding)  # type: ignore[arg-type]
