"""The SVG of a level, for designers: one exact elliptical-arc ``<path>`` per arc in an "Arcs" layer.

Path data by :mod:`img2logo.geometry.svg_path`; the golden circles in a hidden, locked and clipped
"Golden circles" construction layer that Inkscape shows as a layer to toggle; the coloured regions of
:mod:`img2logo.design.fills` (paper Fig. 18) in a "Fills" layer under everything else. Written by hand
with fixed decimals: the same level gives the same bytes.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .._io import atomic_write
from .._validation import check_positive
from ..constants import FORMAT_NAME
from ..errors import InvalidParameterError
from ..geometry.abstraction import Abstraction
from ..geometry.golden_ladder import FibonacciLadder
from ..geometry.primitives import Circle
from ..geometry.svg_path import arc_path, svg_number
from .constants import CONSTRUCTION_MARGIN
from .plotting import (
    ARC_COLOR,
    CIRCLE_COLOR,
)

if TYPE_CHECKING:
    from ..design.fill_values import Fill

from .formats import check_format_suffix, checked_drawing

_SVG_NS = "http://www.w3.org/2000/svg"


_INKSCAPE_NS = "http://www.inkscape.org/namespaces/inkscape"


_SODIPODI_NS = "http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd"


#: The namespace of img2logo's own attributes in an SVG (``img2logo:k``, ``img2logo:circle``,
#: ``img2logo:face``, ``img2logo:line``): SVG 1.1 allows attributes of foreign namespaces, not
#: undeclared ``data-*`` ones. A URN: a name, not an address to fetch.
SVG_METADATA_NS = "urn:img2logo:svg:1"


def to_svg(
    abstraction: Abstraction,
    *,
    construction_circles: bool = True,
    show_construction_circles: bool = False,
    stroke_width: float | None = None,
    image_size: tuple[float, float] | None = None,
    fills: Sequence[Fill] | None = None,
) -> str:
    """The SVG text of an abstraction (see :func:`write_svg` for the layout)."""
    fill_list, width, height, sw = checked_drawing(abstraction, fills, stroke_width)
    if image_size is None:
        shown_w, shown_h = float(width), float(height)
    else:
        try:
            shown_w, shown_h = image_size
        except (TypeError, ValueError) as exc:
            raise InvalidParameterError(f"image_size must be a pair (width, height), got {image_size!r}") from exc
        shown_w = check_positive(shown_w, "image_size width")
        shown_h = check_positive(shown_h, "image_size height")

    circles = abstraction.golden_circles  # numbered as in the JSON document
    index = {c: i for i, c in enumerate(circles)}
    n = svg_number
    if isinstance(abstraction.ladder, FibonacciLadder):
        grid = f"unit*F(k) (Fibonacci grid, unit={float(abstraction.ladder.unit):.6g} px)"
    else:
        grid = f"phi**(k+bias); bias={float(abstraction.bias):.6g}"
    desc = (
        f"{FORMAT_NAME} golden ratio logo by img2logo (Hsiao et al., Img2Logo, CGF 2023): "
        f"{len(abstraction.arcs)} circular arcs on {len(circles)} circles of radius {grid}, "
        f"level={int(abstraction.level)}, "
        f"E^s={float(abstraction.similarity):.6g} px, tolerance T={float(abstraction.tolerance):.6g} px. "
        f"Coordinates in pixels of the {width} x {height} input image."
    )
    lines = [
        '<?xml version="1.0" encoding="UTF-8" standalone="no"?>',
        f'<svg xmlns="{_SVG_NS}" xmlns:inkscape="{_INKSCAPE_NS}" xmlns:sodipodi="{_SODIPODI_NS}" '
        f'xmlns:img2logo="{SVG_METADATA_NS}" version="1.1" '
        f'width="{n(shown_w)}" height="{n(shown_h)}" viewBox="0 0 {width} {height}">',
        f"  <title>{_escape(f'Golden ratio logo (level {int(abstraction.level)})')}</title>",
        f"  <desc>{_escape(desc)}</desc>",
    ]
    if fill_list:
        lines.extend(_svg_fill_layer(fill_list))
    if construction_circles:
        hidden = "" if show_construction_circles else ' style="display:none"'
        m = CONSTRUCTION_MARGIN * max(width, height)
        lines.append(
            f'  <clipPath id="golden-circles-clip"><rect x="{n(-m)}" y="{n(-m)}" '
            f'width="{n(width + 2 * m)}" height="{n(height + 2 * m)}"/></clipPath>'
        )
        lines.append(
            '  <g id="golden-circles" inkscape:groupmode="layer" inkscape:label="Golden circles" '
            f'sodipodi:insensitive="true" clip-path="url(#golden-circles-clip)"{hidden} '
            f'fill="none" stroke="{CIRCLE_COLOR}" stroke-width="{n(max(0.5, sw / 4.0))}">'
        )
        for i, c in enumerate(circles):
            lines.append(f'    <circle id="circle-{i}"{_k_attr(c)} cx="{n(c.cx)}" cy="{n(c.cy)}" r="{n(c.r)}"/>')
        guide = None
        if "symmetry" in abstraction.params:  # a symmetric logo's record: the mirror's module loads for it only
            from ..geometry.mirror import axis_segment

            guide = axis_segment(abstraction.params, width, height)
        if guide is not None:  # a symmetric logo: its mirror axis as a guide line across the image
            (x0, y0), (x1, y1) = guide
            ends = f'x1="{n(x0)}" y1="{n(y0)}" x2="{n(x1)}" y2="{n(y1)}"'
            lines.append(f'    <line id="mirror-axis" {ends} stroke-dasharray="4 2"/>')
        lines.append("  </g>")
    lines.append(
        f'  <g id="arcs" inkscape:groupmode="layer" inkscape:label="Arcs" fill="none" stroke="{ARC_COLOR}" '
        f'stroke-width="{n(sw)}" stroke-linecap="round" stroke-linejoin="round">'
    )
    for i, a in enumerate(abstraction.arcs):
        if a.is_line:
            d = f"M {n(a.start[0])} {n(a.start[1])} L {n(a.end[0])} {n(a.end[1])}"
            lines.append(f'    <path id="line-{i}" img2logo:line="true" d="{d}"/>')
            continue
        lines.append(
            f'    <path id="arc-{i}" img2logo:circle="{index[a.circle]}"{_k_attr(a.circle)} d="{arc_path(a)}"/>'
        )
    lines.append("  </g>")
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


def write_svg(
    abstraction: Abstraction,
    path: str | os.PathLike[str],
    *,
    construction_circles: bool = True,
    show_construction_circles: bool = False,
    stroke_width: float | None = None,
    image_size: tuple[float, float] | None = None,
    fills: Sequence[Fill] | None = None,
) -> Path:
    """Write an abstraction as SVG for designers: exact arcs, construction circles as a layer.

    The drawing's user units are input-image pixels: ``viewBox="0 0 W H"`` with W x H
    the input size. Each arc is one ``<path id="arc-i" img2logo:circle="c" img2logo:k="k">``
    made of SVG elliptical-arc commands ``A r r 0 large-arc sweep x y`` (exact, not
    polylines): ``large-arc = |sweep| > pi``, ``sweep-flag = 1`` for a positive
    sweep (clockwise with y down). A full circle is two half arcs closed with
    ``Z``; an arc within 1e-3 rad of a full turn is also split in two. Arcs sit in
    an Inkscape layer "Arcs" (black stroke, no fill, round caps and joins); the
    circles, numbered as in the JSON document, in a layer "Golden circles" hidden
    by default (``style="display:none"``), locked (``sodipodi:insensitive``: a
    click on the drawing selects an arc, not a circle) and clipped to the image
    plus ``CONSTRUCTION_MARGIN`` x its longer side on every side (a circle of the
    ladder can be many times the image: unhidden, it would fill the artboard).
    img2logo's own attributes (``img2logo:circle``, ``img2logo:k``,
    ``img2logo:line``, ``img2logo:face``) are in the namespace
    :data:`SVG_METADATA_NS`, so the file is valid SVG 1.1. Coordinates carry
    ``SVG_DECIMALS`` decimals. Atomic and deterministic.

    With ``fills`` (paper Fig. 18, :mod:`img2logo.design.fills`) the coloured regions
    come first, so they lie under everything else: an Inkscape layer "Fills"
    (``<g id="fills">``, no stroke) with one ``<path id="fill-i" fill="#rrggbb"
    fill-rule="evenodd">`` per region, its ``d`` the region's exact arc path
    (holes as extra subpaths). Gradient fills are painted with
    ``fill="url(#fill-gradient-j)"``, the gradients defined once each in
    ``<defs>`` in image-pixel user space.

    Parameters
    ----------
    abstraction : Abstraction
        The result to write.
    path : str or path-like
        Target file; parent directories are created.
    construction_circles : bool
        Include the "Golden circles" layer.
    show_construction_circles : bool
        Make that layer visible instead of hidden.
    stroke_width : float, optional
        Width of the arcs, px; default :func:`img2logo.export.plotting.level_stroke_width` (the run's
        ``stroke_width`` param: a drawing's own stroke width).
    image_size : (float, float), optional
        Displayed size (width, height) in px of the SVG; default the input size.
        The viewBox stays the input frame, so the drawing scales.
    fills : sequence of img2logo.design.fills.Fill, optional
        Coloured regions, drawn under the arcs.

    Returns
    -------
    pathlib.Path
        The path of the SVG written (whole, or nothing on failure).

    Examples
    --------
    >>> from img2logo import abstract, data, write_svg
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> path = write_svg(abstract(image, progress=False).final, "ring.svg")
    >>> path.read_text(encoding="utf-8").startswith("<?xml")
    True
    """
    check_format_suffix(path, "svg")
    text = to_svg(
        abstraction,
        construction_circles=construction_circles,
        show_construction_circles=show_construction_circles,
        stroke_width=stroke_width,
        image_size=image_size,
        fills=fills,
    )
    data = text.encode("utf-8")
    return atomic_write(path, lambda f: f.write(data))


def _svg_fill_layer(fills: Sequence[Fill]) -> list[str]:
    """The ``<defs>`` of the gradients and the "Fills" layer (see :func:`write_svg`)."""
    gradient_ids: dict[Any, str] = {}
    for f in fills:
        if f.gradient is not None and f.gradient not in gradient_ids:
            gradient_ids[f.gradient] = f"fill-gradient-{len(gradient_ids)}"
    lines = []
    if gradient_ids:
        lines.append("  <defs>")
        lines.extend(f"    {g.svg(gid)}" for g, gid in gradient_ids.items())
        lines.append("  </defs>")
    lines.append('  <g id="fills" inkscape:groupmode="layer" inkscape:label="Fills" stroke="none">')
    for i, f in enumerate(fills):
        paint = f.color if f.gradient is None else f"url(#{gradient_ids[f.gradient]})"
        face = "" if f.face is None else f' img2logo:face="{int(f.face)}"'
        lines.append(f'    <path id="fill-{i}"{face} fill="{_attr(paint)}" fill-rule="evenodd" d="{_attr(f.path)}"/>')
    lines.append("  </g>")
    return lines


def _escape(text: str) -> str:
    """``text`` safe as XML character data (``xml.sax.saxutils.escape`` without its slow import)."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _attr(text: str) -> str:
    """``text`` safe inside a double-quoted XML attribute: ``&``, ``<``, ``>`` and ``"`` escaped.

    Fill paths and colours are checked when made (:class:`~img2logo.design.fills.Fill`);
    escaping them too means no value can end its attribute, whatever a caller built.
    """
    return _escape(text).replace('"', "&quot;")


def _k_attr(circle: Circle) -> str:
    """The ``img2logo:k`` attribute of a circle, or nothing when it has no k."""
    return "" if circle.k is None else f' img2logo:k="{int(circle.k)}"'
