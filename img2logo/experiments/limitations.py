"""The paper's limitations (Sec. 9): Fig. 14, Fig. 20 and Fig. 21, for ``16_limitations``.

* Fig. 20a: a circle drawn as disconnected strokes, which a designer draws as one arc and the
  framework, merging only neighbouring segments, cannot (:func:`dashed_circle_image`,
  :func:`circle_table`);
* Fig. 20b: long straight strokes, which golden arcs of limited radius bend, against the straight
  lines of ``lines=True`` (:func:`straight_strokes_image`, :func:`straightness_table`);
* Fig. 21: a detail lost where a complex structure is merged too far, and kept by a lock mask
  over it (:func:`worst_window`, then the lock search of :mod:`img2logo.experiments.design`).

Fig. 14 (designers' logos beside the framework's) needs the designers' files, which are not
distributed; the notebook shows the framework's side at increasing T.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..errors import InvalidParameterError
from ..export.plotting import plot_abstraction, plot_segment_graph
from ..geometry.abstraction import Abstraction
from ..quality import logo_points
from . import Run, table
from .layout import panel_grid

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

    from ..segment_graph import SegmentGraph

__all__ = [
    "centre_spread",
    "circle_table",
    "dashed_circle_image",
    "distinct_circles",
    "limitations_reading",
    "logo_deviation",
    "plot_limitation_runs",
    "straight_strokes_image",
    "straightness_table",
    "worst_window",
]


def _canvas(size: int) -> np.ndarray:
    if not (isinstance(size, int) and 64 <= size <= 4096):
        raise InvalidParameterError(f"size must be an integer from 64 to 4096 px, got {size!r}")
    return np.full((size, size, 3), 255, np.uint8)


def dashed_circle_image(size: int = 512, *, pieces: int = 3, gap_degrees: float = 40.0, stroke: int = 8) -> np.ndarray:
    """Fig. 20a's input: one circle drawn as ``pieces`` strokes with gaps of ``gap_degrees`` between them.

    Parameters
    ----------
    size : int
        Side of the square image, px; the circle's radius is ``0.35 * size``.
    pieces : int
        Number of disconnected strokes (at least 2).
    gap_degrees : float
        Angle of each gap, degrees, in (0, 360 / pieces).
    stroke : int
        Stroke width, px.

    Returns
    -------
    ndarray of uint8, shape (size, size, 3)
        Black strokes on white.
    """
    import cv2

    image = _canvas(size)
    if not (isinstance(pieces, int) and pieces >= 2):
        raise InvalidParameterError(f"pieces must be an integer >= 2, got {pieces!r}")
    step = 360.0 / pieces
    if not (0 < gap_degrees < step):
        raise InvalidParameterError(f"gap_degrees must be in (0, {step:g}), got {gap_degrees!r}")
    centre, radius = (size // 2, size // 2), round(0.35 * size)
    for i in range(pieces):
        start = i * step + gap_degrees / 2
        cv2.ellipse(
            image, centre, (radius, radius), 0, start, start + step - gap_degrees, (0, 0, 0), stroke, cv2.LINE_AA
        )
    return image


def straight_strokes_image(size: int = 512, *, stroke: int = 8) -> np.ndarray:
    """Fig. 20b's input: a house, long straight strokes only (a square body under a triangular roof).

    Returns
    -------
    ndarray of uint8, shape (size, size, 3)
        Black strokes on white.
    """
    import cv2

    image = _canvas(size)
    s = size / 512.0
    body = np.array([[120, 250], [392, 250], [392, 440], [120, 440]], float) * s
    roof = np.array([[90, 260], [256, 90], [422, 260]], float) * s
    door = np.array([[226, 440], [226, 340], [286, 340], [286, 440]], float) * s
    for poly, closed in ((body, True), (roof, False), (door, False)):
        pts = np.round(poly).astype(np.int32).reshape(-1, 1, 2)
        cv2.polylines(image, [pts], closed, (0, 0, 0), stroke, cv2.LINE_AA)
    return image


def distinct_circles(abstraction: Abstraction, *, tolerance: float = 2.0) -> int:
    """How many different circles the arcs of ``abstraction`` lie on: arcs on one rung whose centres are
    within ``tolerance`` px of each other count as one circle (a designer's one circle)."""
    found: list[tuple[float, float, float]] = []
    for arc in abstraction.arcs:
        if arc.is_line:
            continue
        c = arc.circle
        if not any(math.hypot(c.cx - x, c.cy - y) <= tolerance and math.isclose(c.r, r) for x, y, r in found):
            found.append((c.cx, c.cy, c.r))
    return len(found)


def centre_spread(abstraction: Abstraction) -> float:
    """The largest distance between the centres of two arcs of ``abstraction`` on the same rung, px (0: none)."""
    circles = [a.circle for a in abstraction.arcs if not a.is_line]
    return max(
        (math.hypot(a.cx - b.cx, a.cy - b.cy) for i, a in enumerate(circles) for b in circles[i + 1 :] if a.k == b.k),
        default=0.0,
    )


def logo_deviation(abstraction: Abstraction, graph: SegmentGraph) -> float:
    """The largest distance from the logo to the feature lines it abstracts, px: how far an arc bends away.

    Every arc and line is sampled every 0.5 px; each sample's distance is to the nearest pixel of
    the segment graph.
    """
    import cv2

    points = logo_points(abstraction, 0.5)
    if not len(points):
        return math.nan
    ink = np.full((graph.height, graph.width), 255, np.uint8)
    pixels = np.vstack(list(graph.segments))
    rows = np.clip(np.floor(pixels[:, 1]).astype(int), 0, graph.height - 1)
    cols = np.clip(np.floor(pixels[:, 0]).astype(int), 0, graph.width - 1)
    ink[rows, cols] = 0
    distance = cv2.distanceTransform(ink, cv2.DIST_L2, cv2.DIST_MASK_PRECISE)
    r = np.clip(np.floor(points[:, 1]).astype(int), 0, graph.height - 1)
    c = np.clip(np.floor(points[:, 0]).astype(int), 0, graph.width - 1)
    inside = (points[:, 0] >= 0) & (points[:, 0] < graph.width) & (points[:, 1] >= 0) & (points[:, 1] < graph.height)
    far = float(distance[r, c].max())
    return far if inside.all() else max(far, float(graph.width + graph.height))


def circle_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Fig. 20a: per run, its segments, the arcs of its logo and the distinct circles they lie on."""
    return table(
        runs,
        {
            "image": lambda r: r.name,
            "variant": lambda r: r.variant,
            "segments": lambda r: r.graph.n_segments,
            "components": lambda r: r.graph.n_components(),
            "arcs": lambda r: len(r.final.arcs),
            "distinct circles": lambda r: distinct_circles(r.final),
            "rungs k": lambda r: " ".join(str(k) for k in sorted({a.circle.k for a in r.final.arcs if not a.is_line})),
            "centre spread (px)": lambda r: round(centre_spread(r.final), 2),
            "E^s (px)": lambda r: round(r.final.similarity, 3),
        },
    )


def straightness_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Fig. 20b: per run, its arcs and straight lines, E^s and how far the logo bends from the strokes."""
    return table(
        runs,
        {
            "image": lambda r: r.name,
            "variant": lambda r: r.variant,
            "arcs": lambda r: sum(not a.is_line for a in r.final.arcs),
            "straight lines": lambda r: sum(a.is_line for a in r.final.arcs),
            "largest radius (px)": lambda r: round(
                max((a.circle.r for a in r.final.arcs if not a.is_line), default=0.0), 1
            ),
            "E^s (px)": lambda r: round(r.final.similarity, 3),
            "largest deviation (px)": lambda r: round(logo_deviation(r.final, r.graph), 2),
        },
    )


def worst_window(abstraction: Abstraction, graph: SegmentGraph, side: float) -> tuple[float, float]:
    """The centre (x, y), px, of the ``side`` px square where the feature lines lie farthest from the logo.

    The mean distance from the segment graph's pixels in a square to the nearest point of the
    arcs (as :func:`img2logo.quality.detail_error`), over every square centred on a segment pixel
    that holds at least ``side`` pixels of the graph: where a detail is lost (Fig. 21).
    """
    if not (math.isfinite(side) and side > 0):
        raise InvalidParameterError(f"side must be finite and > 0 px, got {side!r}")
    pixels = np.vstack(list(graph.segments))
    points = logo_points(abstraction, 0.5)
    if not len(points):
        raise InvalidParameterError("the logo has no arc to measure against")
    distance = _nearest(pixels, points)
    half = side / 2.0
    best, centre = -1.0, (float(pixels[0, 0]), float(pixels[0, 1]))
    for x, y in pixels[:: max(1, len(pixels) // 2000)]:
        near = (np.abs(pixels[:, 0] - x) <= half) & (np.abs(pixels[:, 1] - y) <= half)
        if near.sum() < side:
            continue
        mean = float(distance[near].mean())
        if mean > best:
            best, centre = mean, (float(x), float(y))
    return centre


def _nearest(pixels: np.ndarray, points: np.ndarray) -> np.ndarray:
    """Distance from each pixel to the nearest point, in blocks (memory bounded)."""
    out = np.empty(len(pixels))
    for i in range(0, len(pixels), 2000):
        block = pixels[i : i + 2000]
        out[i : i + 2000] = np.sqrt(((block[:, None, :] - points[None, :, :]) ** 2).sum(axis=2)).min(axis=1)
    return out


def plot_limitation_runs(
    runs: Sequence[Run], *, title: str, captions: Sequence[str] | None = None, panel_size: float = 3.2
) -> Figure:
    """A row of panels: the segment graph of the first run, then each run's final logo with its circles.

    Each logo's panel is titled by ``captions`` (one per run; default: the run's variant), then its
    arcs, straight lines, distinct circles and E^s.
    """
    if not runs:
        raise InvalidParameterError("no runs to plot")
    captions = [r.variant for r in runs] if captions is None else list(captions)
    if len(captions) != len(runs):
        raise InvalidParameterError(f"expected {len(runs)} captions, got {len(captions)}")
    fig, axes = panel_grid(1, 1 + len(runs), panel_size, extra_height=0.5)
    row = axes[0]
    first = runs[0]
    plot_segment_graph(first.graph, row[0], linewidth=1.2, markersize=3.0)
    row[0].set_title(f"(a) {first.name}: |S| = {first.graph.n_segments} segments", fontsize=8)
    for i, (ax, run, caption) in enumerate(zip(row[1:], runs, captions, strict=True)):
        a = run.final
        plot_abstraction(a, ax, show_circles=True, show_junctions=True, linewidth=1.6)
        lines = sum(arc.is_line for arc in a.arcs)
        shape = f"{len(a.arcs) - lines} arcs" + (f", {lines} lines" if lines else "")
        ax.set_title(
            f"({chr(ord('b') + i)}) {caption}\n{shape}, {_circles(a)}, E$^s$ = {a.similarity:.2f} px",
            fontsize=8,
        )
    fig.suptitle(title, fontsize=9)
    return fig


def _circles(abstraction: Abstraction) -> str:
    n = distinct_circles(abstraction)
    return f"{n} circle" + ("" if n == 1 else "s")


def limitations_reading(circles: pd.DataFrame, straight: pd.DataFrame, lock: pd.DataFrame, chosen: float) -> str:
    """What the run's tables of Fig. 20a, 20b and 21 say, as Markdown sentences made from their numbers.

    ``circles`` is :func:`circle_table`, ``straight`` :func:`straightness_table` (its first row the
    golden arcs, its last the straight lines), ``lock`` :func:`img2logo.experiments.design.lock_table`
    and ``chosen`` the T of its figure.
    """
    out = []
    for _, r in circles.iterrows():
        out.append(
            f"**Fig. 20a** ({r['image']}): {r['components']} disconnected strokes, {r['segments']} segments, become "
            f"{r['arcs']} arcs on {r['distinct circles']} circle(s) of rung(s) k = {r['rungs k']} (centres "
            f"{r['centre spread (px)']:.2f} px apart at most): a designer's one arc across the gaps is not made, "
            "since only neighbouring segments merge."
        )
    if len(straight):
        first, last = straight.iloc[0], straight.iloc[-1]
        rows = "; ".join(
            f"{r['variant']}: {r['arcs']} arcs and {r['straight lines']} lines, largest deviation "
            f"{r['largest deviation (px)']:.1f} px, $E^s$ {r['E^s (px)']:.2f} px"
            for _, r in straight.iterrows()
        )
        out.append(
            f"**Fig. 20b** ({first['image']}): {rows}. Drawn with golden arcs the straight strokes bend up to "
            f"{first['largest deviation (px)']:.1f} px away (radii up to {first['largest radius (px)']:.0f} px); "
            f"drawn as in the last row, up to {last['largest deviation (px)']:.1f} px."
        )
    row = lock[lock["T"] == chosen]
    if len(row):
        r = row.iloc[0]
        kept = "kept" if not r["lost with lock"] else "still lost"
        out.append(
            f"**Fig. 21** at T = {chosen:g} px: without the lock the detail error in the window is "
            f"{r['detail error, no lock (px)']:.2f} px ({r['arcs, no lock']} arcs); locking its "
            f"{r['locked segments']} segments brings it to {r['detail error, lock (px)']:.2f} px, {kept} "
            f"({r['arcs, lock']} arcs)."
        )
    return "\n\n".join(out)
