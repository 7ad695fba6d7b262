"""The kit's figure layout: a grid of panels, an image panel, a zoomed window and its mark, arcs, segment groups.

What the notebooks' figures (:mod:`img2logo.experiments`) are laid out with; the
library's own drawings (an abstraction, a segment graph, golden circles, the PNG
writer's) are :mod:`img2logo.export.plotting`. Every drawing is in the input image's pixel
frame: x to the right, y downwards, the image covering ``[0, width] x [0, height]``
px; figures are :class:`matplotlib.figure.Figure` (never pyplot's), with constrained
layout. Line widths are matplotlib points. Matplotlib is imported inside the functions.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import Img2LogoError
from ..export.plotting import ARC_COLOR, frame_image

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..geometry.primitives import Arc
    from ..segment_graph import SegmentGraph

__all__ = [
    "GROUP_COLORS",
    "FigureTextError",
    "draw_arcs",
    "draw_segment_groups",
    "emptiest_corner",
    "fit_titles",
    "frame_bounds",
    "frame_window",
    "mark_window",
    "panel_grid",
    "ring",
    "show_image",
    "square_window",
    "text_problems",
]


class FigureTextError(Img2LogoError):
    """A figure's texts overlap or leave the figure (:func:`text_problems`): it would not read."""


#: Colours cycled over groups told apart in a figure (the segment groups S_i of Fig. 7, one line per image).
GROUP_COLORS: tuple[str, ...] = tuple(
    "#1f77b4 #d62728 #2ca02c #9467bd #ff7f0e #17becf #8c564b #e377c2 #bcbd22 #7f7f7f".split()
)


def square_window(
    center: Sequence[float], side: float, width: int, height: int, *, shrink: bool = False
) -> tuple[float, float, float, float]:
    """A square window (x0, y0, x1, y1) of side ``side`` px around ``center``, inside the image where it fits.

    With ``shrink`` a window larger than the image is made small enough to fit.
    """
    half = side / 2.0
    if shrink:
        half = min(half, width / 2.0, height / 2.0)
    x = min(max(float(center[0]), half), max(width - half, half))
    y = min(max(float(center[1]), half), max(height - half, half))
    return (x - half, y - half, x + half, y + half)


def frame_window(
    ax: Axes,
    window: Sequence[float],
    *,
    color: str | None = None,
    linewidth: float | None = None,
    equal: bool = True,
) -> None:
    """Show the window (x0, y0, x1, y1), px, y down, framed without ticks (a zoomed inset).

    ``color`` and ``linewidth`` style the frame (matplotlib's default when None);
    ``equal`` keeps the aspect ratio 1.
    """
    x0, y0, x1, y1 = window
    ax.set_xlim(x0, x1)
    ax.set_ylim(y1, y0)
    if equal:
        ax.set_aspect("equal")
    ax.set_axis_on()
    ax.set_xticks([])
    ax.set_yticks([])
    for spine in ax.spines.values():
        if color is not None:
            spine.set_edgecolor(color)
        if linewidth is not None:
            spine.set_linewidth(linewidth)


def draw_arcs(
    ax: Axes,
    arcs: Sequence[Arc],
    *,
    colors: Sequence[object] | str = ARC_COLOR,
    linewidth: float = 1.5,
    zorder: float = 2,
) -> None:
    """Draw arcs as polylines sampled every 0.25 px, one colour each or one for all (no autoscale)."""
    from matplotlib.collections import LineCollection

    if not arcs:
        return
    lines = [a.sample(step=0.25) for a in arcs]
    ax.add_collection(
        LineCollection(lines, colors=colors, linewidths=linewidth, capstyle="round", zorder=zorder), autolim=False
    )


def ring(ax: Axes, x: float, y: float, radius: float, color: str, linewidth: float = 1.2) -> None:
    """An open circle of ``radius`` px around (x, y), px: marks a place on a figure."""
    from matplotlib.patches import Circle as CirclePatch

    ax.add_patch(CirclePatch((x, y), radius, fill=False, edgecolor=color, linewidth=linewidth, zorder=5))


def panel_grid(
    rows: int,
    columns: int,
    panel: float,
    *,
    height_ratio: float = 1.0,
    extra_height: float = 0.0,
    width: float | None = None,
    **subplots: Any,
) -> tuple[Figure, np.ndarray]:
    """A grid of panels: a figure (not pyplot's, constrained layout) and its axes, shape (rows, columns).

    Parameters
    ----------
    rows, columns : int
        At least one each.
    panel : float
        Side of a panel, inches; its height is ``height_ratio * panel``.
    extra_height : float
        Inches added to the height (a title, a legend).
    width : float, optional
        The figure's width, inches, instead of ``columns * panel``.
    **subplots
        Keywords of :meth:`matplotlib.figure.Figure.subplots` (``width_ratios``, ...).
    """
    from matplotlib.figure import Figure

    rows, columns = max(1, rows), max(1, columns)
    height = rows * panel * height_ratio + extra_height
    fig = Figure(figsize=(columns * panel if width is None else width, height), layout="constrained")
    return fig, fig.subplots(rows, columns, squeeze=False, **subplots)


def show_image(ax: Axes, image: np.ndarray, *, cmap: str | None = None, thicken: bool = False) -> None:
    """Show an image, shape (height, width[, C]), over ``[0, width] x [0, height]`` px, y down, axes off.

    ``thicken`` dilates a 1-px line map (bool) to 3 px and shows its lines
    black on white, for display only (a small panel would lose them).
    """
    if thicken:
        from scipy.ndimage import binary_dilation

        image, cmap = ~binary_dilation(image), "gray"
    h, w = image.shape[:2]
    ax.imshow(image, cmap=cmap, extent=(0, w, h, 0), interpolation="antialiased")
    ax.set_axis_off()


def draw_segment_groups(
    ax: Axes, graph: SegmentGraph, groups: Sequence[Sequence[int]], colors: Sequence[str], *, linewidth: float = 1.5
) -> None:
    """Draw the segments of ``graph`` grouped, group i (e.g. the S_i of an arc) in ``colors[i]``; frame the image."""
    from matplotlib.collections import LineCollection

    pairs = [(graph.segments[s], color) for group, color in zip(groups, colors, strict=True) for s in group]
    lines, cols = [p[0] for p in pairs], [p[1] for p in pairs]
    ax.add_collection(LineCollection(lines, colors=cols, linewidths=linewidth, capstyle="round", zorder=2))
    frame_image(ax, graph.width, graph.height)


def frame_bounds(ax: Axes, points: np.ndarray, width: int, height: int, *, pad: float = 0.08) -> None:
    """Show the bounding box of ``points`` (N, 2), px, padded by ``pad`` of its size plus 2 px, inside the image."""
    lo, hi = points.min(axis=0), points.max(axis=0)
    margin = pad * float(max(hi - lo)) + 2.0
    ax.set_xlim(max(lo[0] - margin, 0.0), min(hi[0] + margin, width))
    ax.set_ylim(min(hi[1] + margin, height), max(lo[1] - margin, 0.0))


def mark_window(ax: Axes, window: Sequence[float], label: str, color: str = "#555555") -> None:
    """A dashed rectangle around the window (x0, y0, x1, y1), px, labelled at its corner: where a zoom looks."""
    from matplotlib.patches import Rectangle

    x0, y0, x1, y1 = window
    ax.add_patch(
        Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, edgecolor=color, linewidth=0.8, linestyle="--", zorder=6)
    )
    ax.text(x0, y0, label, color=color, fontsize=7, ha="left", va="bottom", zorder=6)


def emptiest_corner(points: np.ndarray, width: int, height: int, size: float) -> tuple[float, float]:
    """Where an inset goes: the origin (axes fraction) of the corner square of side ``size`` (axes fraction)
    of the ``width`` x ``height`` px image frame holding the fewest of ``points``, shape (N, 2), px."""
    fx, fy = points[:, 0] / width, 1.0 - points[:, 1] / height
    corners = [(1.0 - size, 0.0), (1.0 - size, 1.0 - size), (0.0, 0.0), (0.0, 1.0 - size)]
    counts = [int(np.sum((fx >= x) & (fx <= x + size) & (fy >= y) & (fy <= y + size))) for x, y in corners]
    return corners[int(np.argmin(counts))]


def _titles(fig: Any) -> list[tuple[Any, float]]:
    """Each non-empty title of ``fig`` with the width it may take, display px: an axes' titles
    their axes' width, the figure's suptitle the figure's."""
    found = []
    ax: Any
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        width = ax.get_window_extent().width
        for text in (ax.title, ax._left_title, ax._right_title):
            if text.get_text() and text.get_visible():
                found.append((text, width))
    if fig._suptitle is not None and fig._suptitle.get_text():
        found.append((fig._suptitle, fig.bbox.width))
    return found


def _wrap(text: Any, width: float, renderer: Any) -> bool:
    """Re-break ``text``'s lines at spaces so that each fits ``width`` display px; True if it changed.

    A word wider than ``width`` stays whole on its line (it is reported by :func:`text_problems`).
    """
    original = text.get_text()
    lines: list[str] = []
    for line in original.split("\n"):
        words = _keep_together(line.split(" "))
        current = words[0]
        for word in words[1:]:
            text.set_text(f"{current} {word}")
            if text.get_window_extent(renderer).width <= width:
                current = f"{current} {word}"
            else:
                lines.append(current)
                current = word
        lines.append(current)
    wrapped = "\n".join(lines)
    text.set_text(wrapped)
    return wrapped != original


def _keep_together(words: list[str]) -> list[str]:
    """Join ``a = b`` into one word, so that a line is never broken around an equals sign."""
    out: list[str] = []
    for word in words:
        if out and (word in ("=", "<=", ">=", "<", ">") or out[-1].endswith(("=", "<", ">"))):
            out[-1] = f"{out[-1]} {word}"
        else:
            out.append(word)
    return out


def fit_titles(fig: Figure) -> Figure:
    """Break every title of ``fig`` onto more lines where it is wider than its axes (the suptitle:
    than the figure); return ``fig``.

    Titles are set in points and panels in inches, so a title that fits at one font size runs
    into its neighbour's at a larger one (:func:`img2logo.experiments.make_legible`); constrained
    layout makes room for the added lines when the figure is drawn. Lines are broken at spaces, never
    around an equals sign, so ``|A| = 12`` and a title's math (``E$^s$``) stay whole.
    """
    for _ in range(3):  # the axes' widths may change once the titles take more lines
        renderer = _layout_renderer(fig)
        changed = False
        for text, width in _titles(fig):
            if text.get_window_extent(renderer).width > width:
                changed |= _wrap(text, width, renderer)
        if not changed:
            break
    return fig


def text_problems(fig: Figure, *, tolerance: float = 0.5) -> list[str]:
    """What makes a figure's text unreadable: texts that overlap, and texts cut by the figure's edge.

    The figure is drawn (its layout done) and every visible, non-empty text measured in display
    pixels: titles, axis labels, tick labels, legend entries, texts placed in an axes or on the
    figure. Two texts overlap when their boxes share more than ``tolerance`` px each way; a text is
    clipped when its box leaves the figure by more than ``tolerance`` px.

    Returns
    -------
    list of str
        One line per problem, naming the texts; empty when every text reads.
    """
    renderer = _layout_renderer(fig)
    boxes = []
    for text in _drawn_texts(fig):
        label = text.get_text().strip()
        if not label or not text.get_visible():
            continue
        box = text.get_window_extent(renderer)
        if box.width > 0 and box.height > 0:
            boxes.append((label.replace("\n", " / "), box))
    problems = []
    frame = fig.bbox
    for label, box in boxes:
        if (
            box.x0 < frame.x0 - tolerance
            or box.y0 < frame.y0 - tolerance
            or box.x1 > frame.x1 + tolerance
            or box.y1 > frame.y1 + tolerance
        ):
            problems.append(f"clipped by the figure's edge: {label!r}")
    for i, (a, box_a) in enumerate(boxes):
        for b, box_b in boxes[i + 1 :]:
            dx = min(box_a.x1, box_b.x1) - max(box_a.x0, box_b.x0)
            dy = min(box_a.y1, box_b.y1) - max(box_a.y0, box_b.y0)
            if dx > tolerance and dy > tolerance:
                problems.append(f"overlap: {a!r} and {b!r}")
    return problems


def _layout_renderer(fig: Any) -> Any:
    """Lay ``fig`` out (constrained layout) and return a renderer that measures its texts."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    if not hasattr(fig.canvas, "get_renderer"):  # a Figure made without pyplot has no renderer yet
        FigureCanvasAgg(fig)
    fig.draw_without_rendering()
    return fig.canvas.get_renderer()


def _drawn_texts(fig: Any) -> list[Any]:
    """The texts a draw of ``fig`` shows: the figure's, and each visible axes' titles, axis labels,
    tick labels within the view, texts and legend entries."""
    texts = [t for t in (fig._suptitle, fig._supxlabel, fig._supylabel) if t is not None]
    texts += list(fig.texts)
    for legend in fig.legends:
        texts += [*legend.get_texts(), legend.get_title()]
    ax: Any
    for ax in fig.axes:
        if not ax.get_visible():
            continue
        texts += [ax.title, ax._left_title, ax._right_title, *ax.texts]
        if ax.axison:
            axis: Any
            for axis in (ax.xaxis, ax.yaxis):
                if not axis.get_visible():
                    continue
                texts += [axis.label, axis.offsetText]
                for tick in axis._update_ticks():  # the ticks within the view, as drawn
                    texts += [tick.label1, tick.label2]
        shown = ax.get_legend()
        if shown is not None and shown.get_visible():
            texts += [*shown.get_texts(), shown.get_title()]
    return list({id(t): t for t in texts}.values())  # the suptitle is also one of fig.texts
