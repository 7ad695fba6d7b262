"""Drawn files: the PNG of a level (over the faded input, on white or transparent), its vector PDF, the
segment graph's PNG and any matplotlib figure, drawn with :mod:`img2logo.export.plotting`.

PNGs are drawn on matplotlib's Agg canvas, ``width`` x ``height`` px of the input image (times a
scale), without timestamp or software metadata; the PDF by matplotlib's PDF backend, 1 px = 1 pt.
"""

from __future__ import annotations

import functools
import math
import os
import threading
from collections.abc import Callable, Sequence
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any

import numpy as np

from .._io import as_path, atomic_write
from .._validation import check_choice, check_integer, check_positive
from ..constants import MAX_IMAGE_SIDE, MAX_PNG_IMAGE_SIDE, MAX_PNG_SIDE
from ..errors import InvalidParameterError
from ..geometry.abstraction import Abstraction
from .constants import PNG_DPI, PNG_ZLIB_STRATEGY
from .plotting import (
    ARC_COLOR,
    default_stroke_width,
    faded_pixels,
    plot_abstraction,
    plot_segment_graph,
)

if TYPE_CHECKING:
    from ..design.fill_values import Fill
    from ..segment_graph import SegmentGraph

from .formats import check_format_suffix, checked_drawing

#: A PNG's figure of at most this many pixels is kept, emptied, for the thread's next PNG of its size (4 MiB of
#: canvas at 1024 x 1024 px; making the axes again is about 5 ms of CPU).
KEPT_CANVAS_PIXELS: int = 1024 * 1024
#: What ``--png-background`` offers (:func:`write_png`).
PNG_BACKGROUNDS: tuple[str, ...] = ("input", "white", "transparent")


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
        The path of the PNG written (whole, or nothing on failure).

    Examples
    --------
    >>> from img2logo import abstract, data, load_image, write_png
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> path = write_png(abstract(image, progress=False).final, "ring.png", image=image)
    >>> load_image(path).width
    160
    """
    check_format_suffix(path, "png")
    data = png_bytes(
        abstraction,
        image=image,
        dpi=dpi,
        show_junctions=show_junctions,
        show_circles=show_circles,
        stroke_width=stroke_width,
        fills=fills,
        background=background,
        scale=scale,
    )
    return atomic_write(path, lambda f: f.write(data))


def png_bytes(
    abstraction: Abstraction,
    *,
    image: np.ndarray | None = None,
    dpi: float = PNG_DPI,
    show_junctions: bool = False,
    show_circles: bool = False,
    stroke_width: float | None = None,
    fills: Sequence[Fill] | None = None,
    background: str | None = None,
    scale: float | None = None,
) -> bytes:
    """The bytes of the PNG :func:`write_png` writes (the same parameters, without the path).

    For a caller that keeps the file in memory (the batch's workers hand their files back as bytes).
    An input of the PNG's own pixel size is laid under the drawing pixel for pixel
    (:func:`img2logo.export.plotting.faded_pixels`), the bytes ``imshow`` would give without its resampling
    pass; another size (a downscaled working image, a ``scale``) is resampled by ``imshow``. Deflated with
    zlib's run-length strategy (``PNG_ZLIB_STRATEGY``): the pixels of zlib's default, in about 0.4 of its time.
    """
    fill_list, width, height, sw = checked_drawing(abstraction, fills, stroke_width)
    d = check_positive(dpi, "dpi")
    if background is None:
        background = "white" if image is None else "input"
    check_choice(background, "background", PNG_BACKGROUNDS)
    if background == "input" and image is None:
        raise InvalidParameterError('background "input" needs the input image (image=...), got none')
    size = png_size(width, height, scale, background)
    under = image if background == "input" else None
    backdrop = None
    if under is not None and size == (width, height) and np.shape(under)[:2] == (height, width):
        # Pixel for pixel: the faded input is laid down as it is, not resampled by imshow (the same bytes).
        backdrop, under = faded_pixels(under, width, height), None

    def draw(ax: Any) -> None:
        plot_abstraction(
            abstraction,
            ax,
            image=under,
            show_circles=show_circles,
            show_junctions=show_junctions,
            linewidth=sw * 72.0 / d,
            fills=fill_list,
        )

    return _figure_png(
        width,
        height,
        d,
        draw,
        size=size,
        transparent=background == "transparent",
        backdrop=backdrop,
        zlib_strategy=PNG_ZLIB_STRATEGY,
    )


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
        The path of the PDF written.
    """
    check_format_suffix(path, "pdf")
    data = pdf_bytes(abstraction, stroke_width=stroke_width, fills=fills)
    return atomic_write(path, lambda f: f.write(data))


def pdf_bytes(
    abstraction: Abstraction,
    *,
    stroke_width: float | None = None,
    fills: Sequence[Fill] | None = None,
) -> bytes:
    """The bytes of the PDF :func:`write_pdf` writes (the same parameters, without the path)."""
    import io

    import matplotlib.style
    from matplotlib.backends.backend_pdf import FigureCanvasPdf
    from matplotlib.figure import Figure
    from matplotlib.patches import PathPatch
    from matplotlib.path import Path as MplPath
    from matplotlib.transforms import Affine2D

    from .plotting import draw_fills, frame_image

    fill_list, width, height, sw = checked_drawing(abstraction, fills, stroke_width)
    buffer = io.BytesIO()
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
        fig.savefig(
            buffer, format="pdf", facecolor="white", metadata={"Creator": None, "Producer": None, "CreationDate": None}
        )
    return buffer.getvalue()


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
        The path of the segment graph's PNG.

    Examples
    --------
    >>> from img2logo import build_segment_graph, data, extract_feature_lines, load_image, write_segment_graph_png
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
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


def _write_figure_png(
    path: str | os.PathLike[str],
    width: int,
    height: int,
    dpi: float,
    draw: Callable[[Any], None],
) -> Path:
    """Draw on full-figure axes of a ``width`` x ``height`` px Agg figure (:func:`_figure_png`); save it atomically."""
    target = as_path(path)
    data = _figure_png(width, height, dpi, draw)
    return atomic_write(target, lambda f: f.write(data))


def _figure_png(
    width: int,
    height: int,
    dpi: float,
    draw: Callable[[Any], None],
    *,
    size: tuple[int, int] | None = None,
    transparent: bool = False,
    backdrop: np.ndarray | None = None,
    zlib_strategy: int = -1,
) -> bytes:
    """The PNG of full-figure axes of a ``width`` x ``height`` px Agg figure that ``draw(ax)`` drew on.

    ``size`` (px) resamples the figure to another pixel size: the figure keeps its
    size in points and is saved at ``dpi`` times the scale, so strokes scale with it.
    ``backdrop``, uint8 RGB of shape (out_h, out_w, 3), is laid under the drawing pixel for pixel
    (in place of the white page; not with ``transparent``). ``zlib_strategy`` is zlib's (Pillow's
    ``compress_type``; -1: zlib's default): it changes the file's size and the time to make it, never its pixels.
    """
    import io

    import matplotlib.style

    out_w, out_h = (width, height) if size is None else size
    save_dpi = dpi * out_w / width
    paper = "none" if transparent else "white"
    buffer = io.BytesIO()
    with matplotlib.style.context("default"):
        # The figure is out_w x out_h px at save_dpi, in inches of the input's size at dpi.
        figsize = (out_w / save_dpi, out_h / save_dpi)
        fig, canvas, ax = figure = _full_axes(figsize, dpi, paper)
        try:
            draw(ax)
            if transparent:
                ax.patch.set_alpha(0.0)
                fig.savefig(
                    buffer,
                    format="png",
                    dpi=save_dpi,
                    facecolor=paper,
                    edgecolor=paper,
                    transparent=True,
                    metadata={"Software": None},
                    pil_kwargs={"compress_type": zlib_strategy},
                )
                return buffer.getvalue()
            # On white every pixel is opaque: an RGB PNG, without an alpha channel of 255 everywhere.
            from PIL import Image

            fig.set_dpi(save_dpi)
            if backdrop is not None:
                fig.add_artist(_pixel_layer(backdrop))
            canvas.draw()
            rgba = np.asarray(canvas.buffer_rgba())
            Image.fromarray(np.ascontiguousarray(rgba[..., :3])).save(
                buffer, format="png", dpi=(save_dpi, save_dpi), compress_type=zlib_strategy
            )
        finally:
            _keep_empty(figure, figsize, dpi, paper, (out_w, out_h))
    return buffer.getvalue()


#: The empty full-figure axes each thread drew its last PNG on, with their key (:func:`_full_axes`).
_LAST_AXES = threading.local()


def _full_axes(figsize: tuple[float, float], dpi: float, paper: str) -> tuple[Any, Any, Any]:
    """(figure, Agg canvas, full-figure axes) of ``figsize`` inches at ``dpi``, on ``paper``, with nothing drawn.

    The axes this thread's last PNG of the same figure was drawn on, emptied (:func:`_keep_empty`), or new
    ones: making the axes (their axis, ticks and spines) is about 5 ms of CPU, a sixth of a 512 px PNG over
    its input. Made in matplotlib's default style (the caller's context).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    last = getattr(_LAST_AXES, "kept", None)
    _LAST_AXES.kept = None  # in use: a PNG drawn meanwhile makes its own
    if last is not None and last[0] == (figsize, dpi, paper):
        return last[1]
    fig = Figure(figsize=figsize, dpi=dpi, facecolor=paper)
    canvas = FigureCanvasAgg(fig)
    return fig, canvas, fig.add_axes((0.0, 0.0, 1.0, 1.0))


def _keep_empty(
    figure: tuple[Any, Any, Any], figsize: tuple[float, float], dpi: float, paper: str, pixels: tuple[int, int]
) -> None:
    """Remove what a PNG drew on ``figure`` (figure, canvas, axes of :func:`_full_axes`) and keep it for the next.

    Kept for this thread's next PNG of the same ``figsize``, ``dpi`` and ``paper`` if it is empty again
    (a drawing that failed half-way may leave it otherwise) and its canvas of ``pixels`` (width, height)
    has at most ``KEPT_CANVAS_PIXELS`` (the canvas's buffer stays in memory).
    """
    fig, _, ax = figure

    def drawn() -> list[Any]:
        on_axes = (ax.collections, ax.images, ax.lines, ax.patches, ax.texts, ax.artists, ax.tables)
        return [a for group in (*on_axes, fig.artists, fig.images, fig.lines, fig.patches, fig.texts) for a in group]

    try:
        for artist in drawn():
            artist.remove()
    except (NotImplementedError, ValueError):  # an artist that cannot be removed: the figure is not kept
        return
    fig.set_dpi(dpi)
    if not drawn() and ax.get_legend() is None and pixels[0] * pixels[1] <= KEPT_CANVAS_PIXELS:
        _LAST_AXES.kept = ((figsize, dpi, paper), figure)


def _pixel_layer(pixels: np.ndarray) -> Any:
    """A figure artist that lays ``pixels`` (uint8 RGB, shape (rows, columns, 3)) on the canvas from its top left.

    Through :meth:`RendererAgg.draw_image`, unresampled: each pixel is one device pixel, as ``imshow``
    draws an image of the canvas's size with ``interpolation="nearest"``, without its resampling pass.
    Drawn first (``zorder`` below the axes).
    """
    rgba = np.empty((*pixels.shape[:2], 4), dtype=np.uint8)
    rgba[..., :3] = pixels[::-1]  # draw_image's rows go up from the bottom
    rgba[..., 3] = 255
    layer = _pixel_layer_class()(rgba)
    layer.set_zorder(-1.0)
    return layer


@functools.cache
def _pixel_layer_class() -> type:
    """The artist class of :func:`_pixel_layer`, made once (matplotlib loads lazily)."""
    from matplotlib.artist import Artist

    class PixelLayer(Artist):
        def __init__(self, rgba: np.ndarray) -> None:
            super().__init__()
            self.rgba = rgba

        def draw(self, renderer: Any) -> None:
            gc = renderer.new_gc()
            renderer.draw_image(gc, 0.0, 0.0, self.rgba)
            gc.restore()

    return PixelLayer


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
