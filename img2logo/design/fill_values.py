"""What a filled region of a logo is painted with: :class:`Fill`, :class:`Gradient` and ``#rrggbb`` colours.

The values of the ``fills`` key of the ``img2logo.abstraction/1`` document
(``contract/README.md``) and of the writers' ``fills=``, with their checks; they need
only the SVG path data (:mod:`img2logo.geometry.svg_path`), so that reading and writing a
document loads nothing of the arrangement or the image. Computing the fills of an
abstraction (a palette, a gradient, the input's colours) is :mod:`img2logo.design.fills`,
which re-exports these names.

Coordinates are input-image pixels, x right, y down, as everywhere in img2logo.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .._validation import check_choice
from ..constants import ARC_SAMPLE_STEP
from ..errors import InvalidParameterError
from ..geometry.svg_path import check_path_data, sample_path, svg_number

__all__ = ["HEX_COLOR", "Fill", "Gradient", "check_fills", "hex_to_rgb", "parse_color", "rgb_to_hex"]

#: A colour as the document writes it: ``#rrggbb``.
HEX_COLOR = re.compile(r"^#[0-9a-fA-F]{6}$")


@dataclass(frozen=True)
class Gradient:
    """A linear or radial colour gradient, in image pixels (SVG ``userSpaceOnUse``).

    Attributes
    ----------
    kind : {"linear", "radial"}
        ``"linear"``: the colour varies along the vector ``start -> end`` (SVG
        ``x1 y1 x2 y2``), offset 0 at ``start``, 1 at ``end``, constant across.
        ``"radial"``: ``start`` is the centre (offset 0) and the circle through
        ``end`` has offset 1 (SVG ``cx cy r``).
    stops : tuple of (float, str)
        ``(offset, "#rrggbb")`` pairs, offsets non-decreasing in [0, 1], at least
        two. Colours are interpolated linearly in sRGB between stops and held
        beyond the first and the last (SVG's defaults: ``color-interpolation``
        sRGB, ``spreadMethod`` pad).
    start, end : (float, float)
        See ``kind``, px.
    """

    kind: str
    stops: tuple[tuple[float, str], ...]
    start: tuple[float, float]
    end: tuple[float, float]

    def __post_init__(self) -> None:
        check_choice(self.kind, "gradient kind", ("linear", "radial"))
        stops = tuple(self.stops)
        if len(stops) < 2:
            raise InvalidParameterError(f"a gradient needs at least two stops, got {len(stops)}")
        clean = []
        last = 0.0
        for i, stop in enumerate(stops):
            try:
                offset, color = stop
                offset = float(offset)
            except (TypeError, ValueError) as exc:
                raise InvalidParameterError(f"gradient stop {i} must be a pair (offset, colour), got {stop!r}") from exc
            if not (math.isfinite(offset) and last <= offset <= 1.0):
                raise InvalidParameterError(
                    f"gradient stop {i}: offsets must be non-decreasing in [0, 1], got {offset!r} after {last!r}"
                )
            last = offset
            clean.append((offset, parse_color(color, f"gradient stop {i} colour")))
        object.__setattr__(self, "stops", tuple(clean))
        for name in ("start", "end"):
            value = getattr(self, name)
            try:
                x, y = (float(v) for v in value)
            except (TypeError, ValueError) as exc:
                raise InvalidParameterError(f"gradient {name} must be a point (x, y), got {value!r}") from exc
            if not (math.isfinite(x) and math.isfinite(y)):
                raise InvalidParameterError(f"gradient {name} must be finite, got {value!r}")
            object.__setattr__(self, name, (x, y))
        if self.start == self.end:
            raise InvalidParameterError(f"gradient start and end must differ, got {self.start} twice")

    def offsets(self, points: np.ndarray) -> np.ndarray:
        """Gradient offsets of ``points`` (..., 2), clipped to [0, 1]."""
        p = np.asarray(points, dtype=np.float64)
        s = np.asarray(self.start)
        d = np.asarray(self.end) - s
        if self.kind == "linear":
            t = ((p - s) @ d) / float(d @ d)
        else:
            t = np.hypot(p[..., 0] - s[0], p[..., 1] - s[1]) / math.hypot(d[0], d[1])
        return np.clip(t, 0.0, 1.0)

    def color_at(self, points: np.ndarray) -> np.ndarray:
        """The gradient's colours at ``points`` (..., 2): RGB floats in [0, 1], shape (..., 3)."""
        t = self.offsets(points)
        offs = np.array([o for o, _ in self.stops])
        rgb = np.array([hex_to_rgb(c) for _, c in self.stops])
        return np.stack([np.interp(t, offs, rgb[:, k]) for k in range(3)], axis=-1)

    def svg(self, element_id: str) -> str:
        """The ``<linearGradient>`` or ``<radialGradient>`` element, in user space (image px)."""
        n = svg_number
        (x1, y1), (x2, y2) = self.start, self.end
        if self.kind == "linear":
            head = f'<linearGradient id="{element_id}" gradientUnits="userSpaceOnUse" x1="{n(x1)}" y1="{n(y1)}" '
            head += f'x2="{n(x2)}" y2="{n(y2)}">'
            tail = "</linearGradient>"
        else:
            r = math.hypot(x2 - x1, y2 - y1)
            head = f'<radialGradient id="{element_id}" gradientUnits="userSpaceOnUse" cx="{n(x1)}" cy="{n(y1)}" '
            head += f'r="{n(r)}">'
            tail = "</radialGradient>"
        stops = "".join(f'<stop offset="{n(o)}" stop-color="{c}"/>' for o, c in self.stops)
        return head + stops + tail


@dataclass(frozen=True)
class Fill:
    """One filled region: an SVG path and its colour (an entry of the document's ``fills``).

    Attributes
    ----------
    path : str
        SVG path data of the region, normally :attr:`img2logo.design.arrangement.Face.path` (exact arc
        commands, one subpath per loop), drawn with ``fill-rule="evenodd"``.
    color : str
        ``#rrggbb`` (lower case). With a gradient, the gradient's colour at the
        face's centroid: the ``img2logo.abstraction/1`` document only knows one
        colour per region, so that is what the JSON records, while the SVG and
        the PNG draw the true gradient.
    gradient : Gradient or None
        Paint the region with this gradient instead of ``color`` (SVG, PNG).
    face : int or None
        Index of the face in :func:`img2logo.design.arrangement.faces` of the abstraction, when known (None
        for fills read back from a document).
    """

    path: str
    color: str
    gradient: Gradient | None = None
    face: int | None = None

    def __post_init__(self) -> None:
        check_path_data(self.path)
        object.__setattr__(self, "color", parse_color(self.color, "fill color"))
        if self.gradient is not None and not isinstance(self.gradient, Gradient):
            raise InvalidParameterError(f"fill gradient must be a Gradient or None, got {type(self.gradient).__name__}")
        if self.face is not None and (isinstance(self.face, bool) or not isinstance(self.face, int | np.integer)):
            raise InvalidParameterError(f"fill face must be an integer or None, got {self.face!r}")

    def rings(self, step: float = ARC_SAMPLE_STEP) -> list[np.ndarray]:
        """The closed loops of :attr:`path` sampled about ``step`` px apart (see :func:`sample_path`)."""
        return sample_path(self.path, step)

    def to_json(self) -> dict[str, str]:
        """The document entry ``{"path": ..., "color": ...}``."""
        return {"path": self.path, "color": self.color}


def check_fills(fills: object) -> list[Fill] | None:
    """``fills`` as a list of :class:`Fill`, or None when not given (writers and plotting)."""
    if fills is None:
        return None
    if isinstance(fills, Fill | str) or not isinstance(fills, Sequence):
        raise InvalidParameterError(f"fills must be a sequence of Fill, got {type(fills).__name__}")
    out = list(fills)
    for i, f in enumerate(out):
        if not isinstance(f, Fill):
            raise InvalidParameterError(f"fills[{i}] must be a Fill, got {type(f).__name__}")
    return out


def parse_color(value: object, name: str = "colour") -> str:
    """A colour as lower-case ``#rrggbb``.

    Parameters
    ----------
    value : str or sequence of 3 numbers
        ``"#rrggbb"`` (any case), or RGB floats in [0, 1].
    name : str
        What to call it in an error message.

    Raises
    ------
    InvalidParameterError
        ``colour '#12345' is not of the form #rrggbb`` and the like.
    """
    if isinstance(value, str):
        if not HEX_COLOR.match(value):
            raise InvalidParameterError(f"{name} {value!r} is not of the form #rrggbb")
        return value.lower()
    try:
        rgb = [float(c) for c in value]  # type: ignore[attr-defined]
    except (TypeError, ValueError) as exc:
        raise InvalidParameterError(f"{name} must be '#rrggbb' or 3 floats in [0, 1], got {value!r}") from exc
    if len(rgb) != 3 or not all(math.isfinite(c) and 0.0 <= c <= 1.0 for c in rgb):
        raise InvalidParameterError(f"{name} must be '#rrggbb' or 3 floats in [0, 1], got {value!r}")
    return rgb_to_hex(np.array(rgb))


def rgb_to_hex(rgb: np.ndarray) -> str:
    """RGB floats in [0, 1], shape (3,), as ``#rrggbb`` (each channel rounded to 8 bits)."""
    r, g, b = (round(float(c) * 255.0) for c in np.clip(rgb, 0.0, 1.0))
    return f"#{r:02x}{g:02x}{b:02x}"


def hex_to_rgb(color: str) -> np.ndarray:
    """``#rrggbb`` as RGB floats in [0, 1], shape (3,)."""
    return np.array([int(color[k : k + 2], 16) for k in (1, 3, 5)], dtype=np.float64) / 255.0
