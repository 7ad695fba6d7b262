"""Small validation helpers for the public boundary.

Each raises :class:`~img2logo.errors.InvalidParameterError` with a message that
says what was expected and what came, e.g.
``points must have shape (N, 2), got (3,)``.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from typing import TYPE_CHECKING, TypeVar

from .errors import InvalidParameterError

if TYPE_CHECKING:
    import numpy as np

# numpy is imported by the helpers that need it, not here: the command line's
# option parsing uses this module, and ``img2logo --version`` should not load numpy.

_T = TypeVar("_T")


def check_points(points: object, name: str = "points", min_count: int = 1) -> np.ndarray:
    """Return ``points`` as a float64 array of shape (N, 2), N >= ``min_count``.

    Raises
    ------
    InvalidParameterError
        If the shape is not (N, 2), N is too small, or a value is not finite.
    """
    import numpy as np

    try:
        arr = np.asarray(points, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InvalidParameterError(f"{name} must be an array of numbers, got {type(points).__name__}") from exc
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise InvalidParameterError(f"{name} must have shape (N, 2), got {arr.shape}")
    if arr.shape[0] < min_count:
        raise InvalidParameterError(f"{name} must have at least {min_count} points, got {arr.shape[0]}")
    if not np.isfinite(arr).all():  # the array's method: np.all's dispatch costs more on a few points
        raise InvalidParameterError(f"{name} must be finite, got NaN or infinity")
    return arr


def check_finite(value: object, name: str) -> float:
    """Return ``value`` as a finite float."""
    try:
        v = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError) as exc:
        raise InvalidParameterError(f"{name} must be a number, got {value!r}") from exc
    if not math.isfinite(v):
        raise InvalidParameterError(f"{name} must be finite, got {v}")
    return v


def check_positive(value: object, name: str, *, allow_zero: bool = False) -> float:
    """Return ``value`` as a float, checking it is finite and > 0 (or >= 0)."""
    v = check_finite(value, name)
    if v < 0 or (v == 0 and not allow_zero):
        bound = ">= 0" if allow_zero else "> 0"
        raise InvalidParameterError(f"{name} must be {bound}, got {v}")
    return v


def check_choice(value: object, name: str, choices: Iterable[str]) -> str:
    """Return ``value`` if it is one of ``choices``, else raise with the list."""
    options = tuple(choices)
    if value not in options:
        raise InvalidParameterError(f"{name} must be one of {', '.join(map(repr, options))}, got {value!r}")
    return str(value)


def check_integer(value: object, name: str, minimum: int) -> int:
    """``value`` as an int >= ``minimum`` (Python or numpy integer, not bool)."""
    if type(value) is int and value >= minimum:  # the common case, without numpy's types
        return value
    import numpy as np

    if isinstance(value, bool | np.bool_) or not isinstance(value, int | np.integer):
        raise InvalidParameterError(f"{name} must be an integer, got {value!r}")
    v = int(value)
    if v < minimum:
        raise InvalidParameterError(f"{name} must be >= {minimum}, got {v}")
    return v


def readonly(arr: np.ndarray) -> np.ndarray:
    """Return ``arr`` marked read-only, so frozen values stay frozen."""
    arr.setflags(write=False)
    return arr


def check_instance(value: object, cls: type[_T], name: str) -> _T:
    """``value``, known to be a ``cls``; else raise ``abstraction must be an Abstraction, got dict``."""
    if not isinstance(value, cls):
        article = "an" if cls.__name__[:1].lower() in "aeiou" else "a"
        raise InvalidParameterError(f"{name} must be {article} {cls.__name__}, got {type(value).__name__}")
    return value
