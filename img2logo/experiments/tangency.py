"""The tangent-joins ablation (beyond the paper): ``15_tangency``.

Every image runs with tangent joins (the default) and without them (the
paper's fit, ``tangency=False``, :data:`TANGENCY_VARIANTS`); the joins on
smooth input of each result (:func:`img2logo.quality.joins`: junctions where
exactly two arcs end and the input's line turns by less than 10 degrees) are
measured (:func:`tangency_table`, :func:`join_table`) and drawn, circled with
their kink (:func:`plot_tangency`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ..constants import TANGENT_JOIN_ANGLE
from ..export.plotting import frame_image, plot_segment_graph
from ..quality import Joins, joins
from . import Run, table
from .layout import draw_arcs, frame_window, mark_window, panel_grid, ring, square_window

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

#: The two variants: a label and the switches of :func:`img2logo.fit.progressive.optimize`.
TANGENCY_VARIANTS: dict[str, dict[str, Any]] = {
    "with tangency": {},
    "without tangency (the paper)": {"tangency": False},
}
#: Colours of the circles around the joins: tangent (< 2 degrees) and kinked.
TANGENT_COLOR: str = "#2ca02c"
KINK_COLOR: str = "#d62728"


def _joins(run: Run) -> Joins:
    return joins(run.final, run.graph)


def tangency_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Per run: image, variant, |A|, E^s, the joins on smooth input, the fraction tangent and the kinks (degrees)."""

    def kinks(r: Run) -> np.ndarray:
        return np.degrees(_joins(r).kinks)

    return table(
        runs,
        {
            "image": lambda r: r.name,
            "variant": lambda r: r.variant,
            "arcs": lambda r: len(r.final.arcs),
            "E^s": lambda r: round(r.final.similarity, 4),
            "joins": lambda r: _joins(r).count,
            f"tangent (< {math.degrees(TANGENT_JOIN_ANGLE):g} deg)": lambda r: round(_joins(r).tangent_fraction(), 3),
            "median kink (deg)": lambda r: round(float(np.median(kinks(r))), 3) if len(kinks(r)) else np.nan,
            "max kink (deg)": lambda r: round(float(np.max(kinks(r))), 3) if len(kinks(r)) else np.nan,
            "tangencies released": lambda r: int(r.progression.stats.get("released_tangencies", 0)),
        },
    )


def join_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Every join on smooth input of every run: image, variant, junction, x, y (px), kink (degrees, 1e-4)."""
    import pandas as pd

    rows = []
    for run in runs:
        found = _joins(run)
        for j, kink in zip(found.junctions, found.kinks, strict=True):
            x, y = run.final.junctions[j]
            rows.append(
                {
                    "image": run.name,
                    "variant": run.variant,
                    "junction": int(j),
                    "x": round(float(x), 4),
                    "y": round(float(y), 4),
                    "kink (deg)": round(math.degrees(float(kink)), 4),
                }
            )
    return pd.DataFrame(rows, columns=["image", "variant", "junction", "x", "y", "kink (deg)"])


def plot_tangency(runs: Sequence[Run], *, zoom: float = 60.0, panel_size: float = 3.0) -> Figure:
    """Per image: (a) the segment graph, its smooth nodes ringed; then each variant's result with its joins
    circled (green: tangent, red: kinked) and their kinks written (degrees); below, the same columns zoomed
    (a window of side ``zoom`` px) on the most kinked join of the last variant."""
    names = list(dict.fromkeys(r.name for r in runs))
    variants = list(dict.fromkeys(r.variant for r in runs))
    fig, axes = panel_grid(2 * len(names), 1 + len(variants), panel_size, extra_height=0.4)
    for i, name in enumerate(names):
        mine = {r.variant: r for r in runs if r.name == name}
        first = next(iter(mine.values()))
        graph, w, h = first.graph, first.image.width, first.image.height
        found = {v: _joins(r) for v, r in mine.items()}
        last = mine[variants[-1]] if variants[-1] in mine else first
        worst = found[last.variant]
        center = (
            last.final.junctions[worst.junctions[int(np.argmax(worst.kinks))]]
            if worst.count
            else np.array([w / 2.0, h / 2.0])
        )
        win = square_window(center, zoom, w, h, shrink=True)
        smooth = sorted(graph.smooth_nodes())
        for row, zoomed in ((2 * i, False), (2 * i + 1, True)):
            ax = axes[row, 0]
            plot_segment_graph(graph, ax, linewidth=2.0 if zoomed else 1.0, markersize=4.0 if zoomed else 2.5)
            for n in smooth:
                ring(ax, float(graph.junctions[n, 0]), float(graph.junctions[n, 1]), 4.0 if zoomed else 8.0, "#555555")
            if zoomed:
                frame_window(ax, win)
                ax.set_title("(a) zoomed on the most kinked join", fontsize=7)
            else:
                mark_window(ax, win, "zoom")
                ax.set_title(f"{name}\n(a) segments, {len(smooth)} smooth nodes ringed", fontsize=8)
            for ax, v in zip(axes[row, 1:], variants, strict=True):
                if v not in mine:
                    ax.set_axis_off()
                    continue
                run, j = mine[v], found[v]
                frame_image(ax, w, h)
                draw_arcs(ax, run.final.arcs, linewidth=1.6 if zoomed else 1.0)
                for k, kink in zip(j.junctions, j.kinks, strict=True):
                    x, y = (float(c) for c in run.final.junctions[k])
                    color = TANGENT_COLOR if kink < TANGENT_JOIN_ANGLE else KINK_COLOR
                    ring(ax, x, y, 4.0 if zoomed else 10.0, color)
                    if zoomed and win[0] <= x <= win[2] and win[1] <= y <= win[3]:
                        ax.annotate(
                            f"{math.degrees(kink):.1f}°",
                            (x, y),
                            (4, 4),
                            textcoords="offset points",
                            fontsize=7,
                            color=color,
                        )
                if zoomed:
                    frame_window(ax, win)
                    ax.set_title(f"{v}: zoomed", fontsize=7)
                else:
                    mark_window(ax, win, "zoom")
                    median = math.degrees(j.median_kink) if j.count else float("nan")
                    ax.set_title(
                        f"{v}\n|A| = {len(run.final.arcs)}, {j.count} joins, "
                        f"{100 * j.tangent_fraction():.0f} % tangent, median kink {median:.1f}°",
                        fontsize=7,
                    )
    fig.suptitle(
        "Tangent joins on smooth input: green circles = tangent (< 2°), red = kinked (the kink written in the zoom)",
        fontsize=9,
    )
    return fig
