"""Matplotlib figures of abstractions, segment graphs and golden circles.

For notebooks, and used by :mod:`img2logo.export.writers` for the PNG outputs. Every
drawing is in the input image's pixel frame of ``contract/README.md``: x to the
right, y downwards, the image covering ``[0, width] x [0, height]`` so that pixel
(row i, column j) has its centre at (j + 0.5, i + 0.5); equal aspect, axes off.

Matplotlib is imported inside the functions, so that ``import img2logo`` stays
fast. With ``ax=None`` a new figure is made with :func:`matplotlib.pyplot.subplots`
(shown inline in a notebook); pass an ``ax`` to draw into your own figure.

Line widths and marker sizes here are in matplotlib points, as everywhere in
matplotlib; :mod:`img2logo.export.writers` converts its pixel stroke widths to points.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from typing import TYPE_CHECKING

import numpy as np

from .._validation import check_instance, check_positive
from ..constants import ARC_SAMPLE_STEP, IMAGE_FADE
from ..errors import InvalidParameterError
from ..geometry.abstraction import Abstraction
from ..geometry.primitives import Circle
from ..images.loading import composite_on_white
from .constants import MIN_STROKE_WIDTH, STROKE_WIDTH_FRACTION

if TYPE_CHECKING:
    from matplotlib.axes import Axes

    from ..design.fill_values import Fill
    from ..segment_graph import SegmentGraph

__all__ = [
    "ARC_COLOR",
    "CIRCLE_COLOR",
    "END_POINT_COLOR",
    "JUNCTION_COLOR",
    "SEGMENT_COLORMAP",
    "SPLIT_POINT_COLOR",
    "default_stroke_width",
    "draw_fills",
    "evenodd_orient",
    "faded_pixels",
    "frame_image",
    "given_fills",
    "level_stroke_width",
    "plot_abstraction",
    "plot_circles",
    "plot_segment_graph",
]

#: Colour of the arcs of an abstraction.
ARC_COLOR: str = "#000000"
#: Colour of construction (golden) circles, a muted gold.
CIRCLE_COLOR: str = "#c0973a"
#: Colour of the junction points of an abstraction and of the valence >= 3
#: junctions of a segment graph.
JUNCTION_COLOR: str = "#d62728"
#: Face colour of the end points (valence 1) of a segment graph.
END_POINT_COLOR: str = "#ffffff"
#: Colour of the RDP split points (valence 2) of a segment graph.
SPLIT_POINT_COLOR: str = "#404040"
#: Qualitative colormap cycled over the segments of a segment graph (Fig. 4b).
SEGMENT_COLORMAP: str = "tab10"


def default_stroke_width(width: int, height: int) -> float:
    """The default stroke width of arcs in a ``width`` x ``height`` px drawing, px.

    ``STROKE_WIDTH_FRACTION`` of the longer side, at least ``MIN_STROKE_WIDTH``
    (both in :mod:`img2logo.export.constants`).
    """
    return max(MIN_STROKE_WIDTH, STROKE_WIDTH_FRACTION * max(int(width), int(height)))


def given_fills(fills: object) -> list[Fill]:
    """``fills`` checked (:func:`img2logo.design.fill_values.check_fills`) as a list; [] when None.

    The fills' module is imported only when some are given: a logo written without
    fills (the command's default) does not load it.
    """
    if fills is None:
        return []
    from ..design.fill_values import check_fills

    return check_fills(fills) or []


def level_stroke_width(abstraction: Abstraction) -> float:
    """The stroke width a level is drawn with, px: the run's ``stroke_width`` param, else the default.

    :func:`img2logo.abstract` records ``stroke_width`` in ``params``: a line
    drawing's measured median stroke width, the ``stroke_width`` option when
    given, :func:`default_stroke_width` otherwise. A level without it (made by
    hand, or read from an older file) gets :func:`default_stroke_width`.
    """
    value = abstraction.params.get("stroke_width")
    if isinstance(value, int | float) and not isinstance(value, bool) and value > 0:
        return float(value)
    return default_stroke_width(abstraction.width, abstraction.height)


def plot_abstraction(
    abstraction: Abstraction,
    ax: Axes | None = None,
    *,
    image: np.ndarray | None = None,
    show_circles: bool = False,
    show_junctions: bool = False,
    color: str = ARC_COLOR,
    linewidth: float = 2.0,
    circle_color: str = CIRCLE_COLOR,
    junction_color: str = JUNCTION_COLOR,
    image_fade: float = IMAGE_FADE,
    fills: Sequence[Fill] | None = None,
) -> Axes:
    """Draw a golden ratio abstraction: its arcs, optionally over the input image and fills.

    Parameters
    ----------
    abstraction : Abstraction
        The result to draw.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; a new figure is made when None.
    image : ndarray, shape (height, width) or (height, width, C), C in 1..4, optional
        The input image, drawn faded underneath (uint8, or float in [0, 1]).
    show_circles : bool
        Also draw the golden circles of the arcs as thin construction circles
        (the paper's Fig. 8 look).
    show_junctions : bool
        Mark the junction points p_k + d_k.
    color : str
        Colour of the arcs.
    linewidth : float
        Width of the arcs, points.
    circle_color, junction_color : str
        Colours of the construction circles and of the junction marks.
    image_fade : float
        How far ``image`` is faded towards white, in [0, 1].
    fills : sequence of img2logo.design.fills.Fill, optional
        Coloured regions (paper Fig. 18; :mod:`img2logo.design.fills`), drawn under the
        arcs and circles and over the image: each fill's path sampled every
        ``ARC_SAMPLE_STEP`` px, its loops filled with the even-odd rule (holes
        stay empty), in its colour or its gradient.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into, in image pixels with y down.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from img2logo import abstract, data, plot_abstraction
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> ax = plot_abstraction(abstract(image, progress=False).final, image=image, show_circles=True)
    >>> [float(x) for x in ax.get_xlim()]
    [0.0, 160.0]
    """
    from matplotlib.collections import LineCollection

    check_instance(abstraction, Abstraction, "abstraction")
    lw = check_positive(linewidth, "linewidth")
    width, height = int(abstraction.width), int(abstraction.height)
    fill_list = given_fills(fills)
    ax = _axes(ax, width, height)
    if image is not None:
        _draw_image(ax, image, width, height, image_fade)
    if fill_list:
        draw_fills(fill_list, ax, width=width, height=height)
    if show_circles:
        golden = [c for c in abstraction.circles if c.k is not None]  # not the circles of straight lines
        plot_circles(golden, ax, color=circle_color, width=width, height=height)
    lines = [
        arc.sample(step=ARC_SAMPLE_STEP) if not arc.is_line else np.array([arc.start, arc.end])
        for arc in abstraction.arcs
    ]
    collection = LineCollection(lines, colors=color, linewidths=lw, capstyle="round", joinstyle="round", zorder=2)
    ax.add_collection(collection, autolim=False)
    if show_junctions and len(abstraction.junctions):
        j = abstraction.junctions
        ax.plot(
            j[:, 0],
            j[:, 1],
            linestyle="none",
            marker="o",
            markersize=max(3.0, 2.0 * lw),
            markerfacecolor=junction_color,
            markeredgecolor="none",
            zorder=3,
            label="junction",
        )
    frame_image(ax, width, height)
    return ax


def plot_segment_graph(
    graph: SegmentGraph,
    ax: Axes | None = None,
    *,
    image: np.ndarray | None = None,
    show_junctions: bool = True,
    linewidth: float = 1.5,
    markersize: float = 4.0,
    cmap: str = SEGMENT_COLORMAP,
    image_fade: float = IMAGE_FADE,
) -> Axes:
    """Draw a line-segment graph L = {S, J}, each segment in its own colour (Fig. 4b).

    Segment i is drawn in colour ``i mod N`` of the qualitative colormap ``cmap``
    (N its number of colours), so the colours are deterministic. Nodes are marked
    by valence: end points (valence <= 1) as white dots, RDP split points
    (valence 2) as small dark dots, junctions (valence >= 3) as larger red dots.
    Each kind carries a legend label; call ``ax.legend()`` to show them.

    Parameters
    ----------
    graph : SegmentGraph
        The graph to draw.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; a new figure is made when None.
    image : ndarray, shape (height, width) or (height, width, C), C in 1..4, optional
        The input image, drawn faded underneath.
    show_junctions : bool
        Mark the nodes by valence.
    linewidth : float
        Width of the segments, points.
    markersize : float
        Size of the end point and junction dots, points (split points are smaller).
    cmap : str
        Name of a qualitative (listed) matplotlib colormap.
    image_fade : float
        How far ``image`` is faded towards white, in [0, 1].

    Returns
    -------
    matplotlib.axes.Axes
        The axes of the segment graph: image pixels, y down.

    Examples
    --------
    >>> import matplotlib
    >>> matplotlib.use("Agg")
    >>> from img2logo import build_segment_graph, data, extract_feature_lines, plot_segment_graph
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> ax = plot_segment_graph(build_segment_graph(extract_feature_lines(image)))
    >>> [float(y) for y in ax.get_ylim()]  # image rows grow downwards
    [160.0, 0.0]
    """
    import matplotlib
    from matplotlib.collections import LineCollection

    from ..segment_graph import SegmentGraph  # lazily: it loads scipy

    if not isinstance(graph, SegmentGraph):
        raise InvalidParameterError(f"graph must be a SegmentGraph, got {type(graph).__name__}")
    lw = check_positive(linewidth, "linewidth")
    ms = check_positive(markersize, "markersize")
    try:
        colormap = matplotlib.colormaps[cmap]
    except (KeyError, ValueError) as exc:
        raise InvalidParameterError(f"cmap must be the name of a matplotlib colormap, got {cmap!r}") from exc
    width, height = int(graph.width), int(graph.height)
    ax = _axes(ax, width, height)
    if image is not None:
        _draw_image(ax, image, width, height, image_fade)
    colors = [colormap(i % colormap.N) for i in range(graph.n_segments)]
    collection = LineCollection(
        list(graph.segments), colors=colors, linewidths=lw, capstyle="round", joinstyle="round", zorder=2
    )
    ax.add_collection(collection, autolim=False)
    if show_junctions and graph.n_junctions:
        valence = graph.valence
        p = graph.junctions
        kinds = (
            (valence <= 1, "end point (valence 1)", "o", ms, END_POINT_COLOR, "#000000"),
            (valence == 2, "split point (valence 2)", "o", 0.7 * ms, SPLIT_POINT_COLOR, "none"),
            (valence >= 3, "junction (valence \u2265 3)", "o", 1.4 * ms, JUNCTION_COLOR, "#000000"),
        )
        for z, (mask, label, marker, size, face, edge) in enumerate(kinds):
            if not np.any(mask):
                continue
            ax.plot(
                p[mask, 0],
                p[mask, 1],
                linestyle="none",
                marker=marker,
                markersize=size,
                markerfacecolor=face,
                markeredgecolor=edge,
                markeredgewidth=0.75,
                zorder=3 + z,
                label=label,
            )
    frame_image(ax, width, height)
    return ax


def plot_circles(
    circles: Iterable[Circle],
    ax: Axes | None = None,
    *,
    color: str = CIRCLE_COLOR,
    linewidth: float = 0.75,
    linestyle: str = "-",
    show_centers: bool = False,
    width: int | None = None,
    height: int | None = None,
) -> Axes:
    """Draw construction circles, e.g. the golden circles of a fit (Fig. 8).

    Parameters
    ----------
    circles : iterable of Circle
        The circles, centre and radius in px.
    ax : matplotlib.axes.Axes, optional
        Axes to draw into; a new figure is made when None.
    color : str
        Colour of the circles.
    linewidth : float
        Width of the circle outlines, points.
    linestyle : str
        Matplotlib line style of the outlines.
    show_centers : bool
        Also mark each centre with a small cross.
    width, height : int, optional
        Size of the image frame, px. When both are given the axes show exactly
        ``[0, width] x [0, height]``; otherwise, on axes that have no frame yet,
        the view fits the circles. The y axis points down either way.

    Returns
    -------
    matplotlib.axes.Axes
        The axes drawn into.
    """
    from matplotlib.patches import Circle as CirclePatch

    items = list(circles)
    for i, c in enumerate(items):
        if not isinstance(c, Circle):
            raise InvalidParameterError(f"circles[{i}] must be a Circle, got {type(c).__name__}")
    lw = check_positive(linewidth, "linewidth")
    if (width is None) != (height is None):
        raise InvalidParameterError("width and height must be given together")
    fresh = ax is None
    if width is not None and height is not None:
        w = int(check_positive(width, "width"))
        h = int(check_positive(height, "height"))
        ax = _axes(ax, w, h)
    elif ax is None:
        ax = _axes(None, 640, 480)
    for c in items:
        ax.add_patch(
            CirclePatch((c.cx, c.cy), c.r, fill=False, edgecolor=color, linewidth=lw, linestyle=linestyle, zorder=1)
        )
    if show_centers and items:
        centres = np.array([[c.cx, c.cy] for c in items])
        ax.plot(centres[:, 0], centres[:, 1], linestyle="none", marker="+", color=color, zorder=1)
    if width is not None and height is not None:
        frame_image(ax, int(width), int(height))
    elif fresh and items:
        lo = min(c.cx - c.r for c in items), min(c.cy - c.r for c in items)
        hi = max(c.cx + c.r for c in items), max(c.cy + c.r for c in items)
        pad = 0.05 * max(hi[0] - lo[0], hi[1] - lo[1])
        ax.set_xlim(lo[0] - pad, hi[0] + pad)
        ax.set_ylim(hi[1] + pad, lo[1] - pad)
        ax.set_aspect("equal")
        ax.set_axis_off()
    else:
        ax.set_aspect("equal")
        if not ax.yaxis_inverted():
            ax.invert_yaxis()
    return ax


def draw_fills(
    fills: Sequence[Fill],
    ax: Axes,
    *,
    width: int,
    height: int,
    zorder: float = 0.5,
) -> Axes:
    """Draw coloured regions (paper Fig. 18; :mod:`img2logo.design.fills`) into image-pixel axes.

    Each fill's SVG path is sampled every ``ARC_SAMPLE_STEP`` px
    (:func:`img2logo.geometry.svg_path.sample_path`) and drawn as one matplotlib
    ``PathPatch`` without edge; its loops are oriented by nesting depth so that
    matplotlib's non-zero rule fills them as SVG's ``fill-rule="evenodd"``
    would (a loop inside another is a hole). A fill with a gradient is drawn as
    the gradient, computed at every pixel centre of the ``width`` x ``height``
    frame, clipped to the region.

    Parameters
    ----------
    fills : sequence of Fill
    ax : matplotlib.axes.Axes
        Axes in image pixels (y down), e.g. from :func:`plot_abstraction`.
    width, height : int
        Size of the image frame, px (for gradients).
    zorder : float
        Matplotlib z-order of the patches: the default puts them over an image
        (0) and under circles (1) and arcs (2).

    Returns
    -------
    matplotlib.axes.Axes
    """
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath

    fill_list = given_fills(fills)
    w = int(check_positive(width, "width"))
    h = int(check_positive(height, "height"))
    gradients: dict[object, np.ndarray] = {}
    for fill in fill_list:
        rings = evenodd_orient(fill.rings(ARC_SAMPLE_STEP))
        if not rings:
            continue
        vertices = np.concatenate([np.vstack([r, r[:1]]) for r in rings])
        codes = np.concatenate(
            [[MplPath.MOVETO] + [MplPath.LINETO] * (len(r) - 1) + [MplPath.CLOSEPOLY] for r in rings]
        )
        path = MplPath(vertices, codes)
        if fill.gradient is None:
            ax.add_patch(PathPatch(path, facecolor=fill.color, edgecolor="none", linewidth=0.0, zorder=zorder))
            continue
        patch = PathPatch(path, facecolor="none", edgecolor="none", linewidth=0.0, zorder=zorder)
        ax.add_patch(patch)
        if fill.gradient not in gradients:
            rows, cols = np.mgrid[0:h, 0:w]
            centres = np.stack([cols + 0.5, rows + 0.5], axis=-1)
            gradients[fill.gradient] = fill.gradient.color_at(centres)
        shown = ax.imshow(
            gradients[fill.gradient],
            extent=(0.0, float(w), float(h), 0.0),
            origin="upper",
            interpolation="nearest",
            zorder=zorder,
        )
        shown.set_clip_path(patch)
    return ax


# --- helpers -----------------------------------------------------------------------


def evenodd_orient(rings: list[np.ndarray]) -> list[np.ndarray]:
    """Orient loops so that the non-zero rule fills like even-odd: outer loops positive, holes negative.

    A loop's depth is the number of other loops around its first point; loops
    are assumed not to cross (faces of an arrangement never do).
    """
    from matplotlib.path import Path as MplPath

    paths = [MplPath(r) for r in rings]
    out = []
    for i, r in enumerate(rings):
        depth = sum(1 for j, p in enumerate(paths) if j != i and p.contains_point(r[0]))
        x, y = r[:, 0], r[:, 1]
        signed = 0.5 * float(np.dot(x, np.roll(y, -1)) - np.dot(np.roll(x, -1), y))
        if (signed < 0) != (depth % 2 == 1):
            r = r[::-1]
        out.append(r)
    return out


def _axes(ax: Axes | None, width: int, height: int) -> Axes:
    """Return ``ax``, or new axes on a figure of the image's aspect ratio."""
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    scale = 6.4 / max(width, height)
    _, new_ax = plt.subplots(figsize=(max(1.0, width * scale), max(1.0, height * scale)))
    return new_ax


def frame_image(ax: Axes, width: int, height: int) -> None:
    """Show exactly the image ``[0, width] x [0, height]``, px, y down, equal aspect, no axes."""
    ax.set_xlim(0.0, float(width))
    ax.set_ylim(float(height), 0.0)
    ax.set_aspect("equal")
    ax.set_axis_off()


def _draw_image(ax: Axes, image: np.ndarray, width: int, height: int, fade: float) -> None:
    """Draw ``image`` faded towards white, each pixel covering its unit square.

    An image of the same proportions but another size (the downscaled working
    image of an input over ``MAX_IMAGE_SIDE``, under a result in the input's
    pixels) is stretched over the frame.
    """
    shape = np.shape(image)
    if len(shape) >= 2 and (shape[1], shape[0]) != (width, height):
        h_img, w_img = shape[0], shape[1]
        if abs(w_img * height - h_img * width) <= max(width, height):  # the same aspect, to a pixel's rounding
            width_img, height_img = w_img, h_img
            # In 8 bits: matplotlib resamples to the output size, a float64 copy there would be 8x larger.
            rgb = np.rint(_background_rgb(image, width_img, height_img, fade) * 255.0).astype(np.uint8)
            ax.imshow(rgb, extent=(0.0, float(width), float(height), 0.0), origin="upper", zorder=0)
            return
    rgb = _background_rgb(image, width, height, fade)
    ax.imshow(rgb, extent=(0.0, float(width), float(height), 0.0), origin="upper", interpolation="nearest", zorder=0)


def faded_pixels(image: np.ndarray, width: int, height: int, fade: float = IMAGE_FADE) -> np.ndarray:
    """The input faded towards white as the 8-bit pixels that :func:`plot_abstraction` draws of it at 1 px a pixel.

    Matplotlib turns the float RGB of :func:`_background_rgb` into bytes as
    ``floor(255 * value)`` (``ScalarMappable.to_rgba(bytes=True)``); so does this,
    so that a PNG that lays these pixels down directly has the bytes of one drawn with
    ``imshow`` (:func:`img2logo.export.figures.png_bytes`).

    Parameters
    ----------
    image, width, height, fade
        As :func:`_background_rgb` takes them: the input, the size it must have (px), the fade in [0, 1].

    Returns
    -------
    ndarray, shape (height, width, 3), uint8
    """
    return (_background_rgb(image, width, height, fade) * 255.0).astype(np.uint8)


def _background_rgb(image: np.ndarray, width: int, height: int, fade: float = IMAGE_FADE) -> np.ndarray:
    """The image as float RGB in [0, 1], alpha composited on white, faded towards white.

    Parameters
    ----------
    image : array_like, shape (height, width) or (height, width, C), C in 1..4
        As :func:`img2logo.images.loading.composite_on_white` reads it: uint8,
        uint16, bool, or floats in [0, 1].
    width, height : int
        The size the image must have, px.
    fade : float
        In [0, 1]: 0 keeps the image, 1 makes it white.

    Returns
    -------
    ndarray, shape (height, width, 3), float64
    """
    f = float(fade)
    if not (math.isfinite(f) and 0.0 <= f <= 1.0):
        raise InvalidParameterError(f"image_fade must be in [0, 1], got {fade!r}")
    rgb, _, _ = composite_on_white(image, "image", size=(width, height))
    return f + (1.0 - f) * rgb
