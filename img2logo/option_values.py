"""The values of single options, checked or parsed: lengths in px, the regions kept, the symmetry axis, the time
budget, radii.

:class:`img2logo.options.Options` checks each field with these when it is made; the
command line parses its flags' text with them. Each raises
:class:`~img2logo.errors.InvalidParameterError` naming the option, what was expected
and what came.
"""

from __future__ import annotations

import math

from ._validation import check_positive
from .constants import MAX_LENGTH
from .errors import InvalidParameterError

#: The largest angle an option takes, degrees (``symmetry``'s axis direction, either sign).
MAX_ANGLE_DEGREES: float = 360.0


def check_length(value: object, name: str, *, allow_zero: bool = False, low: float = 0.0) -> float:
    """A length option, px: a finite number > 0 (or >= 0), at least ``low``, at most ``MAX_LENGTH``."""
    import numpy as np

    if isinstance(value, bool | np.bool_) or isinstance(value, str):
        raise InvalidParameterError(f"{name} must be a number of px, got {value!r}")
    v = check_positive(value, name, allow_zero=allow_zero)
    if low and not low <= v <= MAX_LENGTH:
        raise InvalidParameterError(f"{name} must be in {low:g}..{MAX_LENGTH:g} px, got {v:g}")
    if v > MAX_LENGTH:
        raise InvalidParameterError(f"{name} must be at most {MAX_LENGTH:g} px (longer than any image), got {v:g}")
    return v


#: The largest ``stretch``: past it E^s is no bound (MAX_LENGTH px at T = 1 px does the same).
MAX_STRETCH: float = 100.0


def check_stretch(value: object) -> float:
    """The ``stretch`` option: a finite factor of T, 1 (the paper's rule) to ``MAX_STRETCH``.

    Examples
    --------
    >>> from img2logo.option_values import check_stretch
    >>> check_stretch(1.5)
    1.5
    """
    import numpy as np

    if isinstance(value, bool | np.bool_ | str) or not isinstance(value, int | float | np.integer | np.floating):
        raise InvalidParameterError(f"stretch must be a factor of T from 1 to {MAX_STRETCH:g}, got {value!r}")
    v = float(value)
    if not 1.0 <= v <= MAX_STRETCH:  # NaN fails too
        raise InvalidParameterError(f"stretch must be a factor of T from 1 to {MAX_STRETCH:g}, got {v:g}")
    return v


def parse_budget(text: str | float | None) -> float | None:
    """``--time-budget S`` as seconds, or None for ``none`` (no bound)."""
    if text is None or (isinstance(text, str) and text.strip().lower() == "none"):
        return None
    try:
        return float(text)
    except ValueError as exc:
        raise InvalidParameterError(f"--time-budget must be a number of seconds or none, got {text!r}") from exc


def parse_radii(text: str | None) -> tuple[int, ...] | None:
    """``--radii K1,K2,...`` as exponents."""
    if text is None:
        return None
    try:
        values = [int(v) for v in text.split(",") if v.strip()]
    except ValueError as exc:
        raise InvalidParameterError(f"--radii must be integers separated by commas, got {text!r}") from exc
    if not values:
        raise InvalidParameterError("--radii must list at least one exponent k")
    return tuple(values)


def refuse_lock_mask(lock_mask: object) -> None:
    """Raise if ``lock_mask`` is given: a symmetric optimization takes none."""
    if lock_mask is not None:
        raise InvalidParameterError("a lock mask cannot be combined with symmetry (use symmetry='none')")


def check_symmetry_option(value: object) -> str | None:
    """The ``symmetry`` option checked: None for ``"none"``, else its canonical text.

    Accepts ``"none"``, ``"auto"``, ``"vertical"``, ``"horizontal"`` or an angle in
    degrees (a number, or a string of one, within +-``MAX_ANGLE_DEGREES``), the
    direction of the axis from +x towards +y (90 is upright).

    Raises
    ------
    InvalidParameterError
        For anything else.
    """
    if value is None or (isinstance(value, str) and value.strip().lower() == "none"):
        return None
    if isinstance(value, str) and value.strip().lower() in ("auto", "vertical", "horizontal"):
        return value.strip().lower()
    if isinstance(value, bool):
        raise InvalidParameterError(
            f"symmetry must be auto, none, vertical, horizontal or an angle in degrees, got {value!r}"
        )
    try:
        angle = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise InvalidParameterError(
            f"symmetry must be auto, none, vertical, horizontal or an angle in degrees, got {value!r}"
        ) from None
    if not math.isfinite(angle) or abs(angle) > MAX_ANGLE_DEGREES:
        raise InvalidParameterError(
            f"symmetry angle must be a number of degrees in -{MAX_ANGLE_DEGREES:g}..{MAX_ANGLE_DEGREES:g}, "
            f"got {value!r}"
        )
    return f"{angle:g}"


def check_detail(value: object, name: str = "detail", unit: str = "regions") -> int:
    """The ``detail`` option (or ``arcs``: ``name``, ``unit``) checked: a whole number, at least 1, as int.

    Raises
    ------
    InvalidParameterError
        For anything else (a bool, a string, a fraction, 0 or less).
    """
    import numpy as np

    message = f"{name} must be a whole number of {unit}, at least 1, got {value!r}"
    if isinstance(value, bool | np.bool_ | str) or not isinstance(value, int | float | np.integer | np.floating):
        raise InvalidParameterError(message)
    v = float(value)
    if not (np.isfinite(v) and v >= 1.0 and v == int(v)):
        raise InvalidParameterError(message)
    return int(v)
