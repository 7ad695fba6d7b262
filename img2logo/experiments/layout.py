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

from ..export.plotting import ARC_COLOR, frame_image

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..geometry.primitives import Arc
    from ..segment_graph import SegmentGraph

__all__ = [
    "GROUP_COLORS",
    "draw_arcs",
    "draw_segment_groups",
    "emptiest_corner",
    "frame_bounds",
    "frame_window",
    "mark_window",
    "panel_grid",
    "ring",
    "show_image",
    "square_window",
]

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
