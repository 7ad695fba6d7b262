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
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from ._validation import check_choice, check_positive
from .constants import LADDER_SNAP_RTOL, LOG_PHI, PHI
from .errors import InvalidParameterError
from .geometry import Circle

__all__ = ["GoldenLadder", "bias_from_radius", "golden_circle"]


def _check_radius(r: object) -> float:
    return check_positive(r, "radius")


def _powers(exponents: np.ndarray) -> np.ndarray:
    # Every ladder radius goes through this one ufunc call: np.power and Python's **
    # may differ in the last bit, and snap must compare radii computed the same way.
    return np.power(PHI, np.asarray(exponents, dtype=np.float64))


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
            values = tuple(np.ravel(np.asarray(self.exponents, dtype=object)))
            if not values:
                raise InvalidParameterError("exponents must not be empty")
            for v in values:
                if isinstance(v, bool) or not isinstance(v, numbers.Integral):
                    raise InvalidParameterError(f"exponents must be integers, got {v!r}")
            object.__setattr__(self, "exponents", tuple(sorted({int(v) for v in values})))

    def radius(self, k: int) -> float:
        """The ladder radius ``phi ** (k + bias)`` of exponent ``k``, px (Eqn. 10).

        ``k`` must be an integer; it is not checked against a subset of ``exponents``.
        """
        if isinstance(k, bool) or not isinstance(k, numbers.Integral):
            raise InvalidParameterError(f"k must be an integer, got {k!r}")
        return float(_powers(np.array([int(k) + self.bias]))[0])

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
        k = int(self.snap_many(np.array([_check_radius(r)]))[0][0])
        return k, self.radius(k)

    def snap_many(self, radii: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Vectorized :meth:`snap`: exponents (int64) and snapped radii (px), shape of ``radii``."""
        r = np.asarray(radii, dtype=np.float64)
        if not np.all(np.isfinite(r)) or np.any(r <= 0):
            raise InvalidParameterError("radii must be finite and > 0")
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


def golden_circle(center: object, radius: float, ladder: GoldenLadder) -> Circle:
    """A circle at ``center`` (x, y; px) with ``radius`` snapped to ``ladder`` (Eqn. 12).

    Returns
    -------
    Circle
        With ``r = ladder.snap(radius)[1]`` and ``k`` the ladder exponent.
    """
    c = np.asarray(center, dtype=np.float64)
    if c.shape != (2,):
        raise InvalidParameterError(f"center must have shape (2,), got {c.shape}")
    k, r = ladder.snap(radius)
    return Circle(float(c[0]), float(c[1]), r, k)
