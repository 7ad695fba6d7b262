"""Ablations of the key components: Fig. 6, 11, 12, 13 (paper Sec. 5.2, 6.2).

For ``05_connectivity_ablation`` (Fig. 6, 11: junction gaps, :func:`gap_table`),
``06_redundant_intersections`` (Fig. 12) and ``08_rdp_robustness`` (Fig. 13);
the arc extraction of ``07_arc_extraction`` (Fig. 9) is :mod:`.arc_selection`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ..constants import TOLERANCE
from ..errors import InvalidParameterError
from ..export.plotting import frame_image, plot_segment_graph
from ..fit.intersections import RedundantIntersection
from ..geometry.abstraction import Abstraction
from ..geometry.primitives import Arc
from ..quality import junction_gaps, level_redundant_intersections
from ..segment_graph import SegmentGraph
from . import Run, table
from .layout import draw_arcs, frame_window, mark_window, panel_grid, ring, square_window

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

#: A junction whose gap exceeds this is counted and circled (Fig. 11), px.
GAP_THRESHOLD: float = 0.5
#: Colour of the circles around junction gaps: the green box of Fig. 6c.
GAP_COLOR: str = "#2ca02c"
#: Colour of the circles around redundant intersections: the red box of Fig. 6c, 12.
INTERSECTION_COLOR: str = "#d62728"
#: The frame of a zoomed window (:func:`img2logo.experiments.layout.frame_window` keywords).
WINDOW_FRAME: dict[str, Any] = {"color": "#555555", "linewidth": 0.8}

#: The variants of Fig. 11 (b)-(e): a label and the switches of
#: :func:`img2logo.fit.progressive.optimize`. Panel (a) is the segment graph.
CONNECTIVITY_VARIANTS: dict[str, dict[str, Any]] = {
    "(b) with connectivity": {},
    "(c) without connectivity": {"connectivity": False},
    "(d) start/end junctions only": {"inner_junctions": False},
    "(e) as (d), no merging": {"inner_junctions": False, "merging": False},
}

#: The variants of Fig. 12 (b), (c).
AVOIDANCE_VARIANTS: dict[str, dict[str, Any]] = {
    "(b) with avoidance": {"avoid_intersections": True},
    "(c) without avoidance": {"avoid_intersections": False},
}

#: What the paper's Fig. 11 shows (it gives no numbers): per variant, whether the
#: arcs meet at every junction.
PAPER_FIG11: dict[str, str] = {
    "(b) with connectivity": "arcs meet at perturbed junctions, small displacements",
    "(c) without connectivity": "arcs do not intersect correctly",
    "(d) start/end junctions only": "missing intersections at junctions of valence > 2",
    "(e) as (d), no merging": "arcs meet, but 'waved' artifacts",
}


# =========================================================================== topology of a level
def arc_chain(graph: SegmentGraph, segments: Sequence[int]) -> tuple[tuple[int, ...], np.ndarray]:
    """The path through the graph of an arc's segments (in order along it): its nodes and its pixels.

    Returns
    -------
    nodes : tuple of int
        One more than ``segments``; a closed path starts and ends at the same
        node; a single segment keeps its stored direction.
    points : ndarray, shape (N, 2)
        The ordered pixels of the path, px.

    Raises
    ------
    InvalidParameterError
        If consecutive segments do not share a node.
    """
    segs = [int(s) for s in segments]
    if not segs:
        raise InvalidParameterError("an arc must abstract at least one segment")
    for start in (int(n) for n in graph.ends[segs[0]]):
        nodes, pieces = [start], []
        for s in segs:
            a, b = (int(n) for n in graph.ends[s])
            if nodes[-1] not in (a, b):
                break
            pieces.append(graph.segments[s] if a == nodes[-1] else graph.segments[s][::-1])
            nodes.append(b if a == nodes[-1] else a)
        else:
            return tuple(nodes), np.vstack([pieces[0], *(p[1:] for p in pieces[1:])])
    raise InvalidParameterError(f"segments {segs} do not form a path through the graph")


def arc_paths(abstraction: Abstraction, graph: SegmentGraph) -> tuple[tuple[int, ...], ...]:
    """For each arc of a level, the nodes of its path through the graph (:func:`arc_chain`)."""
    return tuple(arc_chain(graph, segs)[0] for segs in abstraction.arc_segments)


# =========================================================================== Fig. 11: junction gaps
def gap_table(abstraction: Abstraction, graph: SegmentGraph) -> pd.DataFrame:
    """How far the arcs that should meet at each junction of the result are from meeting (Fig. 11, Eqn. 4), px.

    A junction of the result is a graph node on the paths of two or more arcs;
    its point c is the level's p_k + d_k when the node is in J', else p_k.
    ``gap`` and ``spread`` are those of :func:`img2logo.quality.junction_gaps`.

    Returns
    -------
    pandas.DataFrame
        One row per junction, in node order: ``node``, ``x``, ``y`` (c, px),
        ``in_J'``, ``valence``, ``arcs``, ``gap``, ``spread`` (px).
    """
    import pandas as pd

    paths = arc_paths(abstraction, graph)
    point_of = {n: abstraction.junctions[k] for k, n in enumerate(abstraction.junction_nodes) if n is not None}
    on: dict[int, set[int]] = {}
    for i, path in enumerate(paths):
        for n in path:
            on.setdefault(int(n), set()).add(i)
    shared = [n for n in sorted(on) if len(on[n]) >= 2]
    points = np.array([point_of.get(n, graph.junctions[n]) for n in shared]).reshape(-1, 2)
    gap, spread = junction_gaps(abstraction.arcs, points, [sorted(on[n]) for n in shared])
    rows = [
        {
            "node": n,
            "x": float(c[0]),
            "y": float(c[1]),
            "in_J'": n in point_of,
            "valence": int(graph.valence[n]),
            "arcs": len(on[n]),
            "gap": float(g),
            "spread": float(d),
        }
        for n, c, g, d in zip(shared, points, gap, spread, strict=True)
    ]
    columns = ["node", "x", "y", "in_J'", "valence", "arcs", "gap", "spread"]
    return pd.DataFrame(rows, columns=columns)


def connectivity_table(runs: Sequence[Run], *, threshold: float = GAP_THRESHOLD) -> pd.DataFrame:
    """Per run of :data:`CONNECTIVITY_VARIANTS`: |A|, E^s, the junctions of the result and their gaps
    (:func:`gap_table`, px), redundant intersections (Fig. 6c) and what the paper's Fig. 11 shows."""
    import pandas as pd

    rows = []
    for run in runs:
        gaps = gap_table(run.final, run.graph)
        g = gaps["gap"].to_numpy()
        rows.append(
            {
                "image": run.name,
                "variant": run.variant,
                "arcs": len(run.final.arcs),
                "E^s": round(run.final.similarity, 4),
                "junctions": len(gaps),
                "max gap": round(float(g.max()), 4) if len(g) else 0.0,
                "mean gap": round(float(g.mean()), 4) if len(g) else 0.0,
                f"junctions with gap > {threshold:g} px": int((g > threshold).sum()),
                "max spread": round(float(gaps["spread"].max()), 4) if len(g) else 0.0,
                "redundant intersections": len(level_redundant_intersections(run.final)),
                "paper": PAPER_FIG11.get(run.variant, ""),
            }
        )
    return pd.DataFrame(rows)


def junction_gap_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Every junction of every run's final level: ``image``, ``variant`` and the columns of :func:`gap_table`
    (rounded to 1e-4 px)."""
    import pandas as pd

    parts = []
    for run in runs:
        g = gap_table(run.final, run.graph).round({"x": 4, "y": 4, "gap": 4, "spread": 4})
        g.insert(0, "variant", run.variant)
        g.insert(0, "image", run.name)
        parts.append(g)
    return pd.concat(parts, ignore_index=True) if parts else pd.DataFrame()


# =========================================================================== Fig. 12: redundant intersections
def redundant_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Per run: T, variant, |A|, E^s, redundant intersections of the final level and of A^0
    (:func:`img2logo.quality.level_redundant_intersections`), merges rejected for one (Fig. 12)."""
    return table(
        runs,
        {
            "image": lambda r: r.name,
            "T": lambda r: r.final.tolerance,
            "variant": lambda r: r.variant,
            "arcs": lambda r: len(r.final.arcs),
            "E^s": lambda r: round(r.final.similarity, 4),
            "redundant intersections": lambda r: len(level_redundant_intersections(r.final)),
            "at A^0": lambda r: len(level_redundant_intersections(r.levels[0])),
            "merges rejected": lambda r: int(r.progression.stats.get("rejected_intersections", 0)),
        },
    )


def avoidance_effect(
    table: pd.DataFrame, *, with_label: str = "(b) with avoidance", without_label: str = "(c) without avoidance"
) -> pd.DataFrame:
    """Per image and T of a :func:`redundant_table`: ``with``, ``without`` (redundant intersections),
    ``difference`` (without - with), ``arcs with``, ``arcs without``."""
    key, cols = ["image", "T"], ["redundant intersections", "arcs"]
    a = table[table["variant"] == with_label].set_index(key)[cols]
    b = table[table["variant"] == without_label].set_index(key)[cols]
    names = {"redundant intersections": "with", "redundant intersections without": "without", "arcs": "arcs with"}
    out = a.join(b.add_suffix(" without"), how="inner").rename(columns=names)
    out["difference"] = out["without"] - out["with"]
    return out.reset_index()[["image", "T", "with", "without", "difference", "arcs with", "arcs without"]]


def select_cases(effect: pd.DataFrame, count: int = 4, *, prefer: float = TOLERANCE) -> list[tuple[str, float]]:
    """The ``count`` (image, T) of an :func:`avoidance_effect` where avoidance removes the most (Fig. 12).

    At most one per image; ties go to the T closest to ``prefer``, then by name.
    """
    cases = effect[effect["difference"] > 0].copy()
    cases["distance"] = (cases["T"] - prefer).abs()
    cases = cases.sort_values(["difference", "distance", "image"], ascending=[False, True, True])
    cases = cases.drop_duplicates("image").head(count)
    return [(str(i), float(t)) for i, t in zip(cases["image"], cases["T"], strict=True)]


# =========================================================================== drawing helpers
def _zoomed_arcs(ax: Axes, graph: SegmentGraph, arcs: Sequence[Arc], band: float) -> None:
    """A zoomed view: the input segments as a faint band ``band`` points wide, each arc in its own colour."""
    import matplotlib
    from matplotlib.collections import LineCollection

    lc = LineCollection(list(graph.segments), colors="#c8c8c8", linewidths=band, capstyle="round", zorder=1)
    ax.add_collection(lc, autolim=False)
    cmap = matplotlib.colormaps["tab10"]
    draw_arcs(ax, arcs, colors=[cmap(i % cmap.N) for i in range(len(arcs))], linewidth=1.6)


def _ring_gaps(ax: Axes, gaps: pd.DataFrame, radius: Callable[[float], float], **style: float) -> None:
    """Circle in green each junction of a :func:`gap_table` (x, y, gap): a ring of ``radius(gap)`` px."""
    for x, y, gap in zip(gaps["x"], gaps["y"], gaps["gap"], strict=True):
        ring(ax, x, y, radius(gap), GAP_COLOR, **style)


def _panels(
    row: Sequence[Axes], variants: Sequence[str], runs: dict[str, Run], gaps: dict[str, Any], width: int, height: int
) -> list[tuple[Axes, str, Run, pd.DataFrame]]:
    """The panels of a row, one per variant, all framed on the image; those with a run, with it and its gaps."""
    for ax in row:
        frame_image(ax, width, height)
    return [(ax, v, runs[v], gaps[v]) for ax, v in zip(row, variants, strict=True) if v in runs]


# =========================================================================== Fig. 11: figure
def gap_windows(
    runs: Sequence[Run],
    *,
    variants: Sequence[str] = ("(c) without connectivity", "(d) start/end junctions only"),
    count: int = 2,
    threshold: float = GAP_THRESHOLD,
    min_size: float = 48.0,
) -> list[tuple[str, tuple[float, float, float, float]]]:
    """Zoom windows on the largest junction gaps of one image's runs (Fig. 11 insets).

    Taking ``variants`` in turn, each one's largest gap above ``threshold`` not
    yet inside a window: a square of side max(``min_size``, 4 gap + 16) px
    around it, inside the image. At most ``count`` (variant, (x0, y0, x1, y1)).
    """
    by_variant = {r.variant: r for r in runs}
    queues = []
    for v in (v for v in variants if v in by_variant):
        run = by_variant[v]
        gaps = gap_table(run.final, run.graph)
        gaps = gaps[gaps["gap"] > threshold].sort_values(["gap", "node"], ascending=[False, True])
        queues.append((v, run, list(gaps.itertuples(index=False))))
    out: list[tuple[str, tuple[float, float, float, float]]] = []
    while len(out) < count and any(q for _, _, q in queues):
        for v, run, queue in queues:
            while queue:
                row = queue.pop(0)
                if not any(w[0] <= row.x <= w[2] and w[1] <= row.y <= w[3] for _, w in out):
                    size = max(min_size, 4.0 * row.gap + 16.0)
                    out.append((v, square_window((row.x, row.y), size, run.image.width, run.image.height)))
                    break
            if len(out) >= count:
                break
    return out


def plot_connectivity_ablation(
    runs: Sequence[Run],
    *,
    zooms: int = 2,
    threshold: float = GAP_THRESHOLD,
    panel_size: float = 2.6,
    title: str = "Connectivity validation (Fig. 11)",
) -> Figure:
    """Fig. 11 (and Fig. 6): the runs of :data:`CONNECTIVITY_VARIANTS` (any subset) side by side, per image.

    A row of full views, (a) the segment graph then each variant's final level,
    gaps above ``threshold`` px circled green and redundant intersections red;
    then ``zooms`` rows zoomed on the largest gaps (:func:`gap_windows`), the
    same window in every column, each arc in its colour, junction points black.
    ``title`` is the figure's, the colour key appended.
    """
    names = list(dict.fromkeys(r.name for r in runs))
    variants = list(dict.fromkeys(r.variant for r in runs))
    windows = {n: gap_windows([r for r in runs if r.name == n], count=zooms, threshold=threshold) for n in names}
    n_rows = sum(1 + len(windows[n]) for n in names)
    fig, axes = panel_grid(n_rows, 1 + len(variants), panel_size, extra_height=0.4)
    row = 0
    for name in names:
        mine = {r.variant: r for r in runs if r.name == name}
        first = next(iter(mine.values()))
        graph, w, h = first.graph, first.image.width, first.image.height
        gaps = {v: gap_table(r.final, r.graph) for v, r in mine.items()}
        # full views
        ax = axes[row, 0]
        plot_segment_graph(graph, ax, linewidth=1.0, markersize=2.5)
        ax.set_title(f"{name}\n(a) segments |S| = {graph.n_segments}", fontsize=8)
        for j, (_, win) in enumerate(windows[name]):
            mark_window(ax, win, str(j + 1))
        for ax, v, run, g in _panels(axes[row, 1:], variants, mine, gaps, w, h):
            draw_arcs(ax, run.final.arcs, linewidth=1.0)
            big = g[g["gap"] > threshold]
            _ring_gaps(ax, big, lambda gap: max(12.0, gap + 6.0))
            for ri in level_redundant_intersections(run.final):
                ring(ax, float(ri.point[0]), float(ri.point[1]), 12.0, INTERSECTION_COLOR)
            for j, (_, win) in enumerate(windows[name]):
                mark_window(ax, win, str(j + 1))
            max_gap = float(g["gap"].max()) if len(g) else 0.0
            ax.set_title(
                f"{v}\n|A| = {len(run.final.arcs)}, E$^s$ = {run.final.similarity:.2f}\n"
                f"max gap {max_gap:.2f} px, {len(big)} > {threshold:g}",
                fontsize=7,
            )
        # zoomed insets
        for j, (source, win) in enumerate(windows[name]):
            r = row + 1 + j
            ax = axes[r, 0]
            plot_segment_graph(graph, ax, linewidth=2.0, markersize=5.0)
            frame_window(ax, win, **WINDOW_FRAME)
            ax.set_title(f"inset {j + 1} (largest gap of {source[:3]})", fontsize=7)
            for ax, v, run, g in _panels(axes[r, 1:], variants, mine, gaps, w, h):
                _zoomed_arcs(ax, graph, run.final.arcs, 6.0)
                ax.plot(g["x"], g["y"], "o", color="#000000", markersize=3.0, zorder=4, linestyle="none")
                _ring_gaps(ax, g[g["gap"] > threshold], lambda gap: gap + 2.0, linewidth=1.5)
                frame_window(ax, win, **WINDOW_FRAME)
                inside = g[(g["x"] >= win[0]) & (g["x"] <= win[2]) & (g["y"] >= win[1]) & (g["y"] <= win[3])]
                worst = float(inside["gap"].max()) if len(inside) else 0.0
                ax.set_title(f"{v[:3]} inset {j + 1}: largest gap {worst:.2f} px", fontsize=7)
        row += 1 + len(windows[name])
    fig.suptitle(
        f"{title}: green circles = junction gaps > {threshold:g} px, red = redundant intersections", fontsize=9
    )
    return fig


# =========================================================================== Fig. 12: figure
def _zoom_target(
    without: Sequence[RedundantIntersection], with_: Sequence[RedundantIntersection], radius: float
) -> np.ndarray | None:
    """Where to zoom: the first point of ``without`` farther than ``radius`` from all of ``with_``."""
    for ri in without:
        if all(math.dist(ri.point, other.point) > radius for other in with_):
            return ri.point
    if without:
        return without[0].point
    return with_[0].point if with_ else None


def plot_redundant_intersections(
    runs: Sequence[Run],
    cases: Sequence[tuple[str, float]] | None = None,
    *,
    with_label: str = "(b) with avoidance",
    without_label: str = "(c) without avoidance",
    zoom: float = 80.0,
    panel_size: float = 2.6,
) -> Figure:
    """Fig. 12: per case (image, T; :func:`select_cases`, or every one of ``runs`` when None or empty),
    (a) the segments, the final level (b) with and (c) without avoidance (redundant intersections circled red),
    then (b) and (c) zoomed (a window of side ``zoom`` px) on one that (b) does not have nearby.
    """
    index = {(r.name, r.final.tolerance, r.variant): r for r in runs}
    cases = list(cases or []) or list(dict.fromkeys((r.name, r.final.tolerance) for r in runs))
    fig, axes = panel_grid(len(cases), 5, panel_size, extra_height=0.4)
    for row, (name, t) in zip(axes, cases, strict=False):
        pair = [index.get((name, float(t), v)) for v in (with_label, without_label)]
        if any(r is None for r in pair):
            raise InvalidParameterError(f"no runs of {name!r} at T = {t} with both variants")
        graph, w, h = pair[0].graph, pair[0].image.width, pair[0].image.height
        found = [level_redundant_intersections(r.final) for r in pair]
        target = _zoom_target(found[1], found[0], zoom / 2.0)
        win = square_window(target, zoom, w, h) if target is not None else None
        plot_segment_graph(graph, row[0], linewidth=1.0, markersize=2.5)
        row[0].set_title(f"{name}, T = {t:g} px\n(a) segments |S| = {graph.n_segments}", fontsize=8)
        for col, (run, points) in enumerate(zip(pair, found, strict=True), start=1):
            ax = row[col]
            frame_image(ax, w, h)
            draw_arcs(ax, run.final.arcs, linewidth=1.0)
            for ri in points:
                ring(ax, float(ri.point[0]), float(ri.point[1]), 12.0, INTERSECTION_COLOR)
            if win is not None:
                mark_window(ax, win, "zoom")
            ax.set_title(
                f"{run.variant}\n|A| = {len(run.final.arcs)}, E$^s$ = {run.final.similarity:.2f}, "
                f"{len(points)} redundant",
                fontsize=7,
            )
            zax = row[col + 2]
            frame_image(zax, w, h)
            if win is None:
                zax.set_title(f"{run.variant[:3]} zoom: no redundant intersection", fontsize=7)
                continue
            _zoomed_arcs(zax, graph, run.final.arcs, 5.0)
            j = run.final.junctions
            zax.plot(j[:, 0], j[:, 1], "o", color="#000000", markersize=3.0, zorder=4, linestyle="none")
            for ri in points:
                ring(zax, float(ri.point[0]), float(ri.point[1]), zoom / 12.0, INTERSECTION_COLOR, linewidth=1.5)
            frame_window(zax, win, **WINDOW_FRAME)
            zax.set_title(f"{run.variant[:3]} zoomed", fontsize=7)
    fig.suptitle("Redundant intersection avoidance (Fig. 12): red circles = redundant intersections", fontsize=9)
    return fig


# =========================================================================== Fig. 13: RDP tolerance
def rdp_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Per run of a sweep over the RDP tolerance (Fig. 13): |S|, |A^0| (after the simplification of Sec. 5.4),
    final |A|, E^s (px), levels."""
    return table(
        runs,
        {
            "image": lambda r: r.name,
            "rdp tolerance": lambda r: float(r.settings["rdp_tolerance"]),
            "segments": lambda r: r.graph.n_segments,
            "arcs at A^0": lambda r: len(r.levels[0].arcs),
            "final arcs": lambda r: len(r.final.arcs),
            "E^s": lambda r: round(r.final.similarity, 4),
            "levels": lambda r: len(r.levels),
        },
    )


def plot_rdp_sweep(runs: Sequence[Run], *, panel_size: float = 3.0, inset: float = 0.6) -> Figure:
    """Fig. 13: per image, for each RDP tolerance its segment graph (a panel ``inset`` of the result's size)
    and the final level."""

    def label(run: Run) -> str:
        return f"RDP {float(run.settings['rdp_tolerance']):g} px"

    names = list(dict.fromkeys(r.name for r in runs))
    labels = list(dict.fromkeys(label(r) for r in runs))
    width = len(labels) * (1 + inset) * panel_size
    n = max(1, len(labels))
    fig, axes = panel_grid(len(names), 2 * n, panel_size, extra_height=0.4, width=width, width_ratios=[inset, 1.0] * n)
    index = {(r.name, label(r)): r for r in runs}
    for row, name in zip(axes, names, strict=True):
        for seg_ax, ax, lab in zip(row[::2], row[1::2], labels, strict=False):
            run = index.get((name, lab))
            if run is None:
                seg_ax.set_axis_off()
                ax.set_axis_off()
                continue
            plot_segment_graph(run.graph, seg_ax, show_junctions=False, linewidth=1.2)
            seg_ax.set_title(f"{lab}\n|S| = {run.graph.n_segments}", fontsize=7)
            frame_image(ax, run.image.width, run.image.height)
            draw_arcs(ax, run.final.arcs, linewidth=1.2)
            ax.set_title(
                f"{name}\n|A$^0$| = {len(run.levels[0].arcs)}, "
                f"|A| = {len(run.final.arcs)}, E$^s$ = {run.final.similarity:.2f} px",
                fontsize=7,
            )
    fig.suptitle("Robustness to the initial segmentation (Fig. 13): segments (small) and results", fontsize=9)
    return fig
