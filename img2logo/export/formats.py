"""What every writer of a level checks first: the file name's suffix against the format, the drawing's values."""

from __future__ import annotations

import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

from .._validation import check_instance, check_integer, check_positive
from ..errors import InvalidParameterError
from ..geometry.abstraction import Abstraction
from .plotting import (
    given_fills,
    level_stroke_width,
)

if TYPE_CHECKING:
    from ..design.fill_values import Fill


#: Suffixes that name a file format (lower case): an output named with one of them must be of that format.
FORMAT_SUFFIXES: frozenset[str] = frozenset(
    ".svg .svgz .json .png .apng .jpg .jpeg .jpe .jfif .jp2 .gif .webp .avif .heic .heif .tif .tiff .bmp .ico "
    ".pdf .eps .ps .ai .emf .wmf .psd .xcf .exr .hdr .pbm .pgm .ppm .pnm .csv .txt .html .htm .xml .yaml".split()
)


def check_format_suffix(path: str | os.PathLike[str], fmt: str) -> None:
    """Refuse ``path`` if its suffix names a format other than ``fmt`` (``"svg"``, ...): the file would lie.

    ``write_svg(a, "logo.pdf")`` would put SVG into a ``.pdf``. A suffix that names
    no known format (``logo.out``, none at all) is accepted: the name is the user's.

    Raises
    ------
    InvalidParameterError
        Naming the path, the suffix and the suffix to use.
    """
    if not isinstance(path, str | os.PathLike):
        return  # not a path: the writer's own check says so
    suffix = os.path.splitext(os.fspath(path))[1].lower()
    if suffix in FORMAT_SUFFIXES and suffix != f".{fmt}":
        raise InvalidParameterError(
            f"{os.fspath(path)}: {suffix} names another format (this writes {fmt.upper()}); "
            f"give a file name ending in .{fmt}"
        )


def checked_drawing(
    abstraction: Abstraction, fills: Sequence[Fill] | None, stroke_width: float | None
) -> tuple[list[Fill], int, int, float]:
    """The checked inputs of a drawn file: the fills (a list), width and height (px), the stroke width (px)."""
    check_instance(abstraction, Abstraction, "abstraction")
    fill_list = given_fills(fills)
    width = check_integer(abstraction.width, "width", 1)
    height = check_integer(abstraction.height, "height", 1)
    sw = level_stroke_width(abstraction) if stroke_width is None else check_positive(stroke_width, "stroke_width")
    return fill_list, width, height, sw
