"""The options of :func:`img2logo.abstract`, checked before any work.

One check for every entry point: :func:`img2logo.abstract` calls it first (an
unknown keyword or a bad value fails before the image is read), the command
line calls it before reading the input, and :func:`img2logo.batch.run_batch`
once before its workers start (not once per image).
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping
from typing import Any

import numpy as np

from ._validation import check_choice, check_positive
from .errors import InvalidParameterError, UnknownOptionError

__all__ = ["ABSTRACT_OPTIONS", "SWITCHES", "check_abstract_options"]

#: The on/off switches of :func:`img2logo.progressive.optimize` (paper Fig. 11, 12, Sec. 5.4, 9).
SWITCHES: tuple[str, ...] = (
    "connectivity",
    "inner_junctions",
    "merging",
    "avoid_intersections",
    "localized",
    "simplify",
    "lines",
)

#: Keyword arguments of :func:`img2logo.abstract` (not ``image``).
ABSTRACT_OPTIONS: frozenset[str] = frozenset(
    {
        "tolerance",
        "kind",
        "rdp_tolerance",
        "min_length",
        "foreground",
        "subject",
        "bias",
        "exponents",
        "ladder",
        "unit",
        "rounding",
        "lock_mask",
        "progress",
        "arc_selection",
        "max_arc_distance",
        "symmetry",
        *SWITCHES,
    }
)


def check_abstract_options(options: Mapping[str, Any], allowed: frozenset[str] = ABSTRACT_OPTIONS) -> None:
    """Check keyword arguments of :func:`img2logo.abstract` without doing any work.

    Parameters
    ----------
    options : mapping
        Name -> value; names not given keep :func:`img2logo.abstract`'s defaults.
    allowed : frozenset of str
        The names accepted (a batch does not take ``lock_mask`` nor ``progress``).

    Raises
    ------
    UnknownOptionError
        Naming the first unknown option and the nearest known name (an
        InvalidParameterError and a TypeError).
    InvalidParameterError
        Naming the first value out of range: ``tolerance`` and ``rdp_tolerance`` > 0 px,
        ``min_length`` >= 0 px, ``kind``, ``foreground`` and ``subject``,
        ``max_arc_distance`` > 0 px, ``symmetry`` (auto, none, vertical,
        horizontal or degrees; not with a lock mask), the ladder's
        ``ladder``, ``bias``, ``unit``, ``exponents`` and ``rounding`` (as
        :func:`img2logo.golden_ladder.make_ladder` checks them), the switches
        True or False, ``arc_selection``.
    """
    from .golden_ladder import make_ladder

    for name in options:
        if name not in allowed:
            near = difflib.get_close_matches(str(name), sorted(allowed), n=1)
            hint = f" (did you mean {near[0]!r}?)" if near else ""
            raise UnknownOptionError(
                f"unknown option {name!r}{hint}: expected keyword arguments of img2logo.abstract "
                f"({', '.join(sorted(allowed))})"
            )
    for name in ("tolerance", "rdp_tolerance"):
        if name in options:
            check_positive(options[name], name)
    if "min_length" in options:
        check_positive(options["min_length"], "min_length", allow_zero=True)
    if "kind" in options:
        check_choice(options["kind"], "kind", ("auto", "photo", "clipart", "drawing"))
    from .subject import check_foreground_option, subject_rectangle_numbers

    if "foreground" in options:
        check_foreground_option(options["foreground"])
    if options.get("subject") is not None:
        subject_rectangle_numbers(options["subject"])
    if options.get("max_arc_distance") is not None:
        check_positive(options["max_arc_distance"], "max_arc_distance")
    for name in SWITCHES:
        if name in options and not isinstance(options[name], bool | np.bool_):
            raise InvalidParameterError(f"{name} must be True or False, got {options[name]!r}")
    if "symmetry" in options:
        from .symmetry import check_symmetry_option

        check_symmetry_option(options["symmetry"])
        if options.get("lock_mask") is not None and check_symmetry_option(options["symmetry"]) is not None:
            raise InvalidParameterError("a lock mask cannot be combined with symmetry (use symmetry='none')")
    if "arc_selection" in options:
        check_choice(options["arc_selection"], "arc_selection", ("frechet", "sum_of_squares"))
    make_ladder(
        options.get("ladder", "phi"),
        1.0,  # a stand-in radius: only the values given are checked
        bias=options.get("bias"),
        unit=options.get("unit"),
        exponents=options.get("exponents"),
        rounding=options.get("rounding", "nearest"),
    )
