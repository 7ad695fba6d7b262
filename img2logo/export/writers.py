"""Result files: the ``img2logo.abstraction/1`` JSON document, SVG, PNG and PDF.

The JSON document is the stable record of a result (its contract, made and
checked by :mod:`img2logo.export.contract`). The SVG is for designers: one exact
elliptical-arc ``<path>`` per arc in an "Arcs" layer (path data by
:mod:`img2logo.geometry.svg_path`), and the golden circles in a hidden, locked and clipped
"Golden circles" construction layer that Inkscape shows as a layer to toggle, and,
when given, the coloured regions of :mod:`img2logo.design.fills` (paper Fig. 18) in a
"Fills" layer under everything else (also the document's ``fills`` key and the
PNG). The PNGs are drawn with :mod:`img2logo.export.plotting` on matplotlib's Agg
canvas, ``width`` x ``height`` px of the input image (times a scale), over the
faded input, on white or transparent; the PDF is vector, drawn by matplotlib's
PDF backend, 1 px = 1 pt.

Every writer is atomic and deterministic: the bytes go to a temporary file in the
target's directory that is then renamed over the target (:func:`os.replace`), so a
file is written whole or not at all; missing parent directories are created; the
same input always gives byte-identical files (sorted JSON keys, ``repr`` floats, SVG
written by hand with fixed decimals, PNG without timestamp or software metadata).
Inside :func:`output_set` the files of a run appear together at its end, or none
of them. A path that cannot be written raises :class:`~img2logo.errors.OutputError`
naming it; :func:`check_output_paths` finds most such paths, and outputs that
are inputs, before any work (both from :mod:`img2logo._io`, with the atomic write).

Coordinates are input-image pixels: x right, y down, angles from +x towards +y, so
a positive sweep is clockwise on screen, SVG's ``sweep-flag = 1``.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any

import numpy as np

from .._io import as_path, atomic_write, check_output_paths, output_set
from .._validation import check_choice, check_instance, check_integer, check_positive
from ..constants import FORMAT_NAME, MAX_IMAGE_SIDE, MAX_PNG_IMAGE_SIDE, MAX_PNG_SIDE
from ..design.fill_values import Fill, check_fills
from ..errors import InputNotFoundError, InvalidParameterError
from ..geometry.abstraction import Abstraction
from ..geometry.golden_ladder import FibonacciLadder
from ..geometry.mirror import axis_segment
from ..geometry.primitives import Circle
from ..geometry.svg_path import arc_path, svg_number
from .constants import CONSTRUCTION_MARGIN, PNG_DPI
from .plotting import (
    ARC_COLOR,
    CIRCLE_COLOR,
    default_stroke_width,
    level_stroke_width,
    plot_abstraction,
    plot_segment_graph,
)

if TYPE_CHECKING:
    from ..segment_graph import SegmentGraph

__all__ = [
    "FORMAT_SUFFIXES",
    "PNG_BACKGROUNDS",
    "SVG_METADATA_NS",
    "check_format_suffix",
    "check_output_paths",
    "output_set",
    "read_json",
    "save_figure",
    "to_svg",
    "write",
    "write_json",
    "write_pdf",
    "write_png",
    "write_segment_graph_png",
    "write_svg",
    "write_table",
]

_SVG_NS = "http://www.w3.org/2000/svg"
_INKSCAPE_NS = "http://www.inkscape.org/namespaces/inkscape"
_SODIPODI_NS = "http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd"
#: The namespace of img2logo's own attributes in an SVG (``img2logo:k``, ``img2logo:circle``,
#: ``img2logo:face``, ``img2logo:line``): SVG 1.1 allows attributes of foreign namespaces, not
#: undeclared ``data-*`` ones. A URN: a name, not an address to fetch.
SVG_METADATA_NS = "urn:img2logo:svg:1"
#: What ``--png-background`` offers (:func:`write_png`).
PNG_BACKGROUNDS: tuple[str, ...] = ("input", "white", "transparent")


# --- JSON --------------------------------------------------------------------------


def read_json(path: str | os.PathLike[str]) -> Abstraction:
    """Read an ``img2logo.abstraction/1`` JSON file written by :func:`write_json`.

    Raises
    ------
    InputNotFoundError
        If there is no such file (an Img2LogoError and a FileNotFoundError).
    InvalidParameterError
        If it is a folder, cannot be read, is not UTF-8 JSON or not a valid document
        (see :func:`img2logo.export.contract.from_document`).

    Examples
    --------
    >>> import cv2, numpy as np
    >>> image = np.full((160, 160, 3), 255, np.uint8)
    >>> _ = cv2.circle(image, (80, 80), 50, (0, 0, 0), 3)  # a black ring, 50 px round
    >>> from img2logo import abstract, read_json, write_json
    >>> path = write_json(abstract(image, progress=False).final, "ring.json")
    >>> logo = read_json("ring.json")
    >>> round(logo.arcs[0].circle.r, 1), logo.arcs[0].circle.k
    (50.0, 8)
    """
    import json  # the JSON document's modules load with its first reader or writer, not for an SVG

    from .contract import from_document

    p = as_path(path)
    if not p.exists():
        raise InputNotFoundError(f"JSON file not found: {p}")
    if p.is_dir():
        raise InvalidParameterError(f"{p} is a folder, not a JSON file")
    if not p.is_file():  # a FIFO would block the read
        raise InvalidParameterError(f"{p} is not a regular file (a device, a pipe, ...), not a JSON file")
    try:
        text = p.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise InvalidParameterError(f"{p} is not JSON: not UTF-8 text ({exc.reason} at byte {exc.start})") from exc
    except OSError as exc:
        raise InvalidParameterError(f"{p}: cannot read the file: {exc.strerror or exc}") from exc
    try:
        doc = json.loads(text)
    except ValueError as exc:  # JSONDecodeError, or an integer of more than 4300 digits
        raise InvalidParameterError(f"{p} is not JSON: {exc}") from exc
    except RecursionError as exc:  # arrays or objects nested thousands deep
        raise InvalidParameterError(f"{p} is not a valid document: JSON nested too deeply") from exc
    return from_document(doc)


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


def write_json(
    abstraction: Abstraction,
    path: str | os.PathLike[str],
    params: Mapping[str, Any] | None = None,
    *,
    check: bool = False,
    fills: Sequence[Fill] | None = None,
) -> Path:
    """Write the ``img2logo.abstraction/1`` document of ``abstraction`` (:func:`~img2logo.export.contract.to_document`).

    UTF-8 JSON with sorted keys, two-space indentation and a final newline; floats
    are written with Python's ``repr``, so they read back exactly. Atomic.
    ``fills`` (:mod:`img2logo.design.fills`) go into the ``fills`` key; read them back
    with :func:`img2logo.export.contract.read_fills`.

    Returns
    -------
    pathlib.Path
        The path written.

    Examples
    --------
    >>> import cv2, numpy as np
    >>> image = np.full((160, 160, 3), 255, np.uint8)
    >>> _ = cv2.circle(image, (80, 80), 50, (0, 0, 0), 3)  # a black ring, 50 px round
    >>> from img2logo import abstract, read_json, write_json
    >>> result = abstract(image, progress=False)
    >>> write_json(result.final, "ring.json", result.params).name
    'ring.json'
    >>> len(read_json("ring.json").arcs)
    1
    """
    import json

    from .contract import to_document

    check_format_suffix(path, "json")
    doc = to_document(abstraction, params, check=check, fills=fills)
    text = json.dumps(doc, indent=2, sort_keys=True, allow_nan=False, ensure_ascii=False) + "\n"
    # A file name of bytes that are not UTF-8 holds surrogate escapes (PEP 383): written as JSON's own
    # escape (\udce9), valid UTF-8 that json.loads reads back as the same name.
    data = text.encode("utf-8", errors="backslashreplace")
    return atomic_write(path, lambda f: f.write(data))


# --- SVG ---------------------------------------------------------------------------


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
    fill_list, width, height, sw = _drawing(abstraction, fills, stroke_width)
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
        The path written.

    Examples
    --------
    >>> import cv2, numpy as np
    >>> image = np.full((160, 160, 3), 255, np.uint8)
    >>> _ = cv2.circle(image, (80, 80), 50, (0, 0, 0), 3)  # a black ring, 50 px round
    >>> from img2logo import abstract, write_svg
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


# --- PNG ---------------------------------------------------------------------------


def write_png(
    abstraction: Abstraction,
    path: str | os.PathLike[str],
    *,
    image: np.ndarray | None = None,
    dpi: float = PNG_DPI,
    show_junctions: bool = False,
    show_circles: bool = False,
    stroke_width: float | None = None,
    fills: Sequence[Fill] | None = None,
    background: str | None = None,
    scale: float | None = None,
) -> Path:
    """Render an abstraction to a PNG of the input image's size (times ``scale``), see :func:`png_size`.

    Drawn with :func:`img2logo.export.plotting.plot_abstraction` on matplotlib's Agg
    canvas with matplotlib's default style (a user's matplotlibrc does not change
    the file), without metadata that could vary: the same input gives the same
    bytes. Atomic.

    Parameters
    ----------
    abstraction : Abstraction
        The result to draw.
    path : str or path-like
        Target file; parent directories are created.
    image : ndarray, shape (height, width) or (height, width, C), C in 1..4, optional
        The input image, drawn faded underneath with ``background="input"``.
    dpi : float
        Figure resolution; it only converts px to points, the PNG is always
        ``round(width * scale)`` x ``round(height * scale)`` px.
    show_junctions, show_circles : bool
        Mark the junctions; draw the golden circles.
    stroke_width : float, optional
        Width of the arcs, px of the input; default :func:`img2logo.export.plotting.level_stroke_width`
        (the run's ``stroke_width`` param: a drawing's own stroke width). It scales with ``scale``.
    fills : sequence of img2logo.design.fills.Fill, optional
        Coloured regions (paper Fig. 18), drawn under the arcs
        (:func:`img2logo.export.plotting.draw_fills`).
    background : {"input", "white", "transparent"}, optional
        Under the logo: the faded input (``image`` is then needed), white, or
        nothing (an RGBA PNG, alpha 0 off the strokes and fills: the clean logo
        to place on a layout). Default ``"input"`` when ``image`` is given,
        else ``"white"``.
    scale : float, optional
        Size of the PNG relative to the input, > 0 (2.0: twice the width and
        height, strokes as thick in proportion). Default 1, but at most the
        working size ``MAX_IMAGE_SIDE`` on the longer side (an input over it is
        drawn at the size it was worked at). At most ``MAX_PNG_SIDE`` px a side,
        ``MAX_PNG_IMAGE_SIDE`` over the faded input.

    Returns
    -------
    pathlib.Path
        The path written.

    Examples
    --------
    >>> import cv2, numpy as np
    >>> image = np.full((160, 160, 3), 255, np.uint8)
    >>> _ = cv2.circle(image, (80, 80), 50, (0, 0, 0), 3)  # a black ring, 50 px round
    >>> from img2logo import abstract, load_image, write_png
    >>> path = write_png(abstract(image, progress=False).final, "ring.png", image=image)
    >>> load_image(path).width
    160
    """
    check_format_suffix(path, "png")
    fill_list, width, height, sw = _drawing(abstraction, fills, stroke_width)
    d = check_positive(dpi, "dpi")
    if background is None:
        background = "white" if image is None else "input"
    check_choice(background, "background", PNG_BACKGROUNDS)
    if background == "input" and image is None:
        raise InvalidParameterError('background "input" needs the input image (image=...), got none')
    size = png_size(width, height, scale, background)

    def draw(ax: Any) -> None:
        plot_abstraction(
            abstraction,
            ax,
            image=image if background == "input" else None,
            show_circles=show_circles,
            show_junctions=show_junctions,
            linewidth=sw * 72.0 / d,
            fills=fill_list,
        )

    return _write_figure_png(path, width, height, d, draw, size=size, transparent=background == "transparent")


#: The formats :func:`write` writes a level in.
LEVEL_FORMATS: tuple[str, ...] = ("json", "svg", "pdf", "png")


def write(
    level: Abstraction,
    path: str | os.PathLike[str],
    format: str,
    *,
    fills: Sequence[Fill] | None = None,
    image: np.ndarray | None = None,
    background: str | None = None,
    scale: float | None = None,
) -> Path:
    """Write ``level`` to ``path`` in ``format``: the one way the command line, the batch and the studio write a level.

    Parameters
    ----------
    level : Abstraction
        The level to write.
    path : str or path-like
        Target file, its suffix the format's; parent directories are created.
    format : {"json", "svg", "pdf", "png"}
        :func:`write_json`, :func:`write_svg`, :func:`write_pdf` or :func:`write_png`.
    fills : sequence of img2logo.design.fills.Fill, optional
        Coloured regions (paper Fig. 18).
    image, background, scale
        The PNG's (:func:`write_png`); the other formats do not draw the input.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    InvalidParameterError
        If ``format`` is none of ``LEVEL_FORMATS``, or the writer refuses a value.
    """
    check_choice(format, "format", LEVEL_FORMATS)
    if format == "json":
        return write_json(level, path, fills=fills)
    if format == "svg":
        return write_svg(level, path, fills=fills)
    if format == "pdf":
        return write_pdf(level, path, fills=fills)
    return write_png(level, path, image=image, fills=fills, background=background, scale=scale)


def png_size(width: float, height: float, scale: float | None = None, background: str = "white") -> tuple[int, int]:
    """(width, height) of the PNG :func:`write_png` draws of a ``width`` x ``height`` px input, px.

    ``round(width * scale)`` x ``round(height * scale)``. Without ``scale``, the
    input's size, or for an input over ``MAX_IMAGE_SIDE`` its working size (the
    longer side ``MAX_IMAGE_SIDE`` px): the image under the logo has no more
    pixels, and drawing it at 12000 x 12000 px took 12 GB and minutes.

    Raises
    ------
    InvalidParameterError
        If ``scale`` is not > 0, or a side would be under 1 px or over
        ``MAX_PNG_SIDE`` (over ``MAX_PNG_IMAGE_SIDE`` with ``background="input"``).
    """
    if scale is None:
        s = min(1.0, MAX_IMAGE_SIDE / max(float(width), float(height)))
    elif isinstance(scale, str | bytes | bool | np.bool_):  # float("2") and float(True) would pass
        raise InvalidParameterError(f"scale must be a number, got {scale!r}")
    else:
        s = check_positive(scale, "scale")
    bound = MAX_PNG_IMAGE_SIDE if background == "input" else MAX_PNG_SIDE
    w, h = float(width) * s, float(height) * s  # compared before rounding: 1e308 times a side is inf
    if not max(w, h) < 2 * bound or min(round(w), round(h)) < 1 or max(round(w), round(h)) > bound:
        over = f" over the faded input (white or transparent: up to {MAX_PNG_SIDE} px)" if bound != MAX_PNG_SIDE else ""
        raise InvalidParameterError(
            f"scale {s:g} makes a {w:.0f} x {h:.0f} px PNG; each side must be in 1..{bound} px{over}"
        )
    return (round(w), round(h))


def write_pdf(
    abstraction: Abstraction,
    path: str | os.PathLike[str],
    *,
    stroke_width: float | None = None,
    fills: Sequence[Fill] | None = None,
) -> Path:
    """Write an abstraction as a vector PDF of one page, 1 px of the input = 1 pt (1/72 in).

    For print and for editors that read PDF (Illustrator, Affinity, Inkscape).
    Drawn by matplotlib's PDF backend: each arc is a path of cubic Bezier
    curves (:meth:`matplotlib.path.Path.arc`, the standard approximation of
    L. Maisonobe: 2 ** ceil(sweep / 90 deg) pieces, each at most 90 degrees, whose
    radial error is below 2.7e-4 x r, far below a stroke), a line a straight
    segment, black, round caps and joins, on a white page of ``width`` x
    ``height`` pt. ``fills`` are drawn underneath as polygons (their arcs
    sampled every ``ARC_SAMPLE_STEP`` px, as in the PNG).
    No date or software tag: the same input gives the same bytes. Atomic.

    Parameters
    ----------
    abstraction : Abstraction
        The result to write.
    path : str or path-like
        Target file; parent directories are created.
    stroke_width : float, optional
        Width of the arcs, px (= pt); default :func:`img2logo.export.plotting.level_stroke_width`.
    fills : sequence of img2logo.design.fills.Fill, optional
        Coloured regions (paper Fig. 18), drawn under the arcs.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    check_format_suffix(path, "pdf")
    import matplotlib.style
    from matplotlib.backends.backend_pdf import FigureCanvasPdf
    from matplotlib.figure import Figure
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath
    from matplotlib.transforms import Affine2D

    from .plotting import draw_fills, frame_image

    fill_list, width, height, sw = _drawing(abstraction, fills, stroke_width)
    target = as_path(path)
    with matplotlib.style.context("default"):
        fig = Figure(figsize=(width / 72.0, height / 72.0), dpi=72.0, facecolor="white")
        FigureCanvasPdf(fig)
        ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
        frame_image(ax, width, height)
        if fill_list:
            draw_fills(fill_list, ax, width=width, height=height)
        style = {"fill": False, "edgecolor": ARC_COLOR, "linewidth": sw, "capstyle": "round", "joinstyle": "round"}
        for a in abstraction.arcs:
            if a.is_line:
                shape = MplPath([a.start, a.end])
            else:
                lo = math.degrees(min(a.theta0, a.theta0 + a.sweep))
                unit = MplPath.arc(lo, lo + math.degrees(abs(a.sweep)))
                shape = Affine2D().scale(a.circle.r).translate(a.circle.cx, a.circle.cy).transform_path(unit)
            ax.add_patch(PathPatch(shape, zorder=3, **style))

        def save(f: IO[bytes]) -> None:
            fig.savefig(
                f, format="pdf", facecolor="white", metadata={"Creator": None, "Producer": None, "CreationDate": None}
            )

        return atomic_write(target, save)


def write_segment_graph_png(
    graph: SegmentGraph,
    path: str | os.PathLike[str],
    *,
    image: np.ndarray | None = None,
    dpi: float = PNG_DPI,
    show_junctions: bool = True,
    stroke_width: float | None = None,
) -> Path:
    """Render a segment graph (paper Fig. 4b) to a PNG of exactly the graph's image size.

    Drawn with :func:`img2logo.export.plotting.plot_segment_graph`: one colour per segment,
    nodes marked by valence. Atomic and deterministic like :func:`write_png`.

    Parameters
    ----------
    graph : SegmentGraph
        The graph to draw.
    path : str or path-like
        Target file; parent directories are created.
    image : ndarray, shape (height, width) or (height, width, C), C in 1..4, optional
        The input image, drawn faded underneath.
    dpi : float
        Figure resolution; it only converts px to points.
    show_junctions : bool
        Mark the nodes by valence.
    stroke_width : float, optional
        Width of the segments, px; default half of
        :func:`img2logo.export.plotting.default_stroke_width`, at least 1 px.

    Returns
    -------
    pathlib.Path
        The path written.

    Examples
    --------
    >>> import cv2, numpy as np
    >>> image = np.full((160, 160, 3), 255, np.uint8)
    >>> _ = cv2.circle(image, (80, 80), 50, (0, 0, 0), 3)  # a black ring, 50 px round
    >>> from img2logo import build_segment_graph, extract_feature_lines, load_image, write_segment_graph_png
    >>> path = write_segment_graph_png(build_segment_graph(extract_feature_lines(image)), "graph.png")
    >>> load_image(path).height
    160
    """
    check_format_suffix(path, "png")
    from ..segment_graph import SegmentGraph  # lazily: it loads scipy

    if not isinstance(graph, SegmentGraph):
        raise InvalidParameterError(f"graph must be a SegmentGraph, got {type(graph).__name__}")
    width = check_integer(graph.width, "graph width", 1)
    height = check_integer(graph.height, "graph height", 1)
    d = check_positive(dpi, "dpi")
    if stroke_width is None:
        sw = max(1.0, default_stroke_width(width, height) / 2.0)
    else:
        sw = check_positive(stroke_width, "stroke_width")
    lw = sw * 72.0 / d
    ms = max(3.0 * lw, 5.0 * 72.0 / d)  # node dots at least 5 px across

    def draw(ax: Any) -> None:
        plot_segment_graph(graph, ax, image=image, show_junctions=show_junctions, linewidth=lw, markersize=ms)

    return _write_figure_png(path, width, height, d, draw)


# --- helpers -----------------------------------------------------------------------


def _drawing(
    abstraction: Abstraction, fills: Sequence[Fill] | None, stroke_width: float | None
) -> tuple[list[Fill], int, int, float]:
    """The checked inputs of a drawn file: the fills (a list), width and height (px), the stroke width (px)."""
    check_instance(abstraction, Abstraction, "abstraction")
    fill_list = check_fills(fills) or []
    width = check_integer(abstraction.width, "width", 1)
    height = check_integer(abstraction.height, "height", 1)
    sw = level_stroke_width(abstraction) if stroke_width is None else check_positive(stroke_width, "stroke_width")
    return fill_list, width, height, sw


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


def _write_figure_png(
    path: str | os.PathLike[str],
    width: int,
    height: int,
    dpi: float,
    draw: Callable[[Any], None],
    *,
    size: tuple[int, int] | None = None,
    transparent: bool = False,
) -> Path:
    """Draw on full-figure axes of a ``width`` x ``height`` px Agg figure and save it atomically.

    ``size`` (px) resamples the figure to another pixel size: the figure keeps its
    size in points and is saved at ``dpi`` times the scale, so strokes scale with it.
    """
    import matplotlib.style
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    target = as_path(path)
    out_w, out_h = (width, height) if size is None else size
    save_dpi = dpi * out_w / width
    paper = "none" if transparent else "white"
    with matplotlib.style.context("default"):
        # The figure is out_w x out_h px at save_dpi, in inches of the input's size at dpi.
        fig = Figure(figsize=(out_w / save_dpi, out_h / save_dpi), dpi=dpi, facecolor=paper)
        canvas = FigureCanvasAgg(fig)
        ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
        draw(ax)
        if transparent:
            ax.patch.set_alpha(0.0)

        def save(f: IO[bytes]) -> None:
            if transparent:
                fig.savefig(
                    f,
                    format="png",
                    dpi=save_dpi,
                    facecolor=paper,
                    edgecolor=paper,
                    transparent=True,
                    metadata={"Software": None},
                )
                return
            # On white every pixel is opaque: an RGB PNG, without an alpha channel of 255 everywhere.
            from PIL import Image

            fig.set_dpi(save_dpi)
            canvas.draw()
            rgba = np.asarray(canvas.buffer_rgba())
            Image.fromarray(np.ascontiguousarray(rgba[..., :3])).save(f, format="png", dpi=(save_dpi, save_dpi))

        return atomic_write(target, save)


def save_figure(fig: Any, path: str | os.PathLike[str], *, dpi: float = PNG_DPI) -> Path:
    """Save a matplotlib figure (PNG or SVG by the suffix) whole or not at all, byte-deterministically.

    No timestamp or software tag goes into the file, and SVG ids use a fixed
    hash salt, so the same figure gives the same bytes (``make figures`` can be
    checked with ``git diff``).
    """
    import matplotlib

    target = as_path(path)
    fmt = target.suffix.lstrip(".").lower()
    if fmt not in ("png", "svg"):
        raise InvalidParameterError(f"figure path must end in .png or .svg, got {target.name!r}")
    metadata = {"Software": None} if fmt == "png" else {"Date": None, "Creator": None}

    def save(f: IO[bytes]) -> None:
        with matplotlib.rc_context({"svg.hashsalt": "img2logo"}):
            fig.savefig(f, format=fmt, dpi=dpi, metadata=metadata, facecolor="white")

    return atomic_write(target, save)


def write_table(table: Any, path: str | os.PathLike[str]) -> Path:
    """Write a pandas DataFrame as CSV (no index), whole or not at all.

    UTF-8; a file name of bytes that are not UTF-8 (surrogate escapes, PEP 383) is written as its own bytes.
    """
    text = table.to_csv(index=False, lineterminator="\n", float_format="%.6g")
    return atomic_write(path, lambda f: f.write(text.encode("utf-8", "surrogateescape")))


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
