"""Ablations of the key components: Fig. 6, 9, 11, 12, 13 (paper Sec. 5.2, 5.3, 6.2).

Tables and figure layouts of ``05_connectivity_ablation`` (Fig. 6, 11: the
junction gaps of each variant of the connectivity constraint, :func:`gap_table`),
``06_redundant_intersections`` (Fig. 12), ``07_arc_extraction`` (Fig. 9: both
arc-selection rules on the same circles, :func:`compare_arc_selection`, and a
constructed "hook", :func:`hook_example`) and ``08_rdp_robustness`` (Fig. 13).

A level records the segments of each arc and the arcs of each junction of J',
not which graph node a junction is: :func:`arc_paths` and :func:`junction_nodes`
recover that from the graph as the optimizer builds J' (the ends of each arc's
path and, unless only the ends are constrained, its inner nodes of valence >= 3),
and check the result against the level.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..arc_extraction import ArcFit, RedundantIntersection, admissible_arcs, extract_arc
from ..constants import TOLERANCE
from ..errors import InvalidParameterError
from ..geometry import Abstraction, Arc, Circle
from ..plotting import draw_arcs, frame_image, frame_window, plot_segment_graph, ring, square_window
from ..progressive import Progression
from ..quality import junction_gaps, level_redundant_intersections
from ..segment_graph import SegmentGraph
from . import Run

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
#: Colour of the arcs on which two arc-selection rules disagree (Fig. 9).
DIFFERENCE_COLORS: tuple[str, str] = ("#1f77b4", "#ff7f0e")

#: The variants of Fig. 11 (b)-(e): a label and the switches of
#: :func:`img2logo.progressive.optimize`. Panel (a) is the segment graph.
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
    """The path through the graph of an arc's segments: its nodes and its pixel chain.

    Parameters
    ----------
    graph : SegmentGraph
        The segment graph the level was built from.
    segments : sequence of int
        The arc's segments in order along it (``Abstraction.arc_segments[i]``).

    Returns
    -------
    nodes : tuple of int
        The nodes of the path, one more than ``segments``; a closed path starts
        and ends at the same node. A single segment keeps its stored direction.
    points : ndarray, shape (N, 2)
        The ordered pixels of the path, px (consecutive segments share a node).

    Raises
    ------
    InvalidParameterError
        If consecutive segments do not share a node.
    """
    segs = [int(s) for s in segments]
    if not segs:
        raise InvalidParameterError("an arc must abstract at least one segment")
    for start in (int(n) for n in graph.ends[segs[0]]):
        walked = _walk(graph, segs, start)
        if walked is not None:
            return walked
    raise InvalidParameterError(f"segments {segs} do not form a path through the graph")


def _walk(graph: SegmentGraph, segs: Sequence[int], start: int) -> tuple[tuple[int, ...], np.ndarray] | None:
    """The path of ``segs`` from node ``start``, or None if they do not chain from there."""
    nodes, pieces, current = [start], [], start
    for s in segs:
        a, b = (int(n) for n in graph.ends[s])
        if a == current:
            pieces.append(graph.segments[s])
            current = b
        elif b == current:
            pieces.append(graph.segments[s][::-1])
            current = a
        else:
            return None
        nodes.append(current)
    return tuple(nodes), np.vstack([pieces[0], *(p[1:] for p in pieces[1:])])


def arc_paths(abstraction: Abstraction, graph: SegmentGraph) -> tuple[tuple[int, ...], ...]:
    """For each arc of a level, the nodes of its path through the graph (:func:`arc_chain`)."""
    return tuple(arc_chain(graph, segs)[0] for segs in abstraction.arc_segments)


def _constrained(path: Sequence[int], valence: np.ndarray, inner_junctions: bool) -> tuple[int, ...]:
    """The nodes of J' on a path: its ends and (optionally) inner nodes of valence >= 3, in path order."""
    inner = tuple(n for n in path[1:-1] if valence[n] >= 3) if inner_junctions else ()
    if path[0] == path[-1]:
        return (path[0], *inner)
    return (path[0], *inner, path[-1])


def junction_nodes(abstraction: Abstraction, graph: SegmentGraph) -> np.ndarray:
    """The node of the graph behind each junction of a level: shape (J,), int.

    ``abstraction.junctions[k]`` is ``graph.junctions[nodes[k]]`` plus its
    displacement d_k. J' is rebuilt from the arcs' paths as the optimizer
    builds it (the ends of each path and, unless the run constrained only the
    ends, Fig. 11d, its inner nodes of valence >= 3), in increasing node order.

    Raises
    ------
    InvalidParameterError
        If the rebuilt J' does not match the level's junctions and junction arcs
        (the level was not built from this graph).
    """
    inner = bool(abstraction.params.get("inner_junctions", True))
    valence = graph.valence
    at: dict[int, set[int]] = {}
    for i, path in enumerate(arc_paths(abstraction, graph)):
        for n in _constrained(path, valence, inner):
            at.setdefault(n, set()).add(i)
    nodes = sorted(at)
    listed = [tuple(sorted(at[n])) for n in nodes]
    if len(nodes) != len(abstraction.junctions) or listed != [tuple(sorted(a)) for a in abstraction.junction_arcs]:
        raise InvalidParameterError("the level's junctions do not match its arcs' paths through this graph")
    return np.array(nodes, dtype=np.int64)


# =========================================================================== Fig. 11: junction gaps
def gap_table(abstraction: Abstraction, graph: SegmentGraph) -> pd.DataFrame:
    """How far the arcs that should meet at each junction are from meeting (Fig. 11), px.

    A *junction of the result* is a node of the graph on the paths of two or
    more arcs (at an end of a path, or inside it): in the input those
    segments meet there, so the arcs should meet there too (Eqn. 4). Its
    *junction point* c is the level's displaced junction p_k + d_k when the
    node is in J', else the node p_k itself (an inner node that a run with
    only start/end constraints, Fig. 11d, does not constrain). Then, with q_i
    the point of arc i nearest to c (the radial projection, or the nearer end
    of the arc; :func:`img2logo.quality.junction_gaps`):

    * ``gap`` = max_i |q_i - c|: the largest distance from the junction point
      to an arc that should pass through it. With the connectivity constraint
      every arc passes through c and the gap is 0 (to the solver's tolerance).
      Without it (Fig. 11c) each arc ends where the junction projects on its
      own circle, so c lies on none of them. With start/end constraints only
      (Fig. 11d) a merged arc misses the inner junctions of its path.
    * ``spread`` = max_{i,j} |q_i - q_j|: how far apart the arcs' closest
      approaches to the junction are (0 when they meet at c).
        One row per junction of the result, in node order: ``node``, ``x``,
        ``y`` (the junction point c, px), ``in_J'`` (whether the level
        constrains it), ``valence`` (in the graph), ``arcs`` (how many arcs
        meet there), ``gap``, ``spread`` (px).
    """
    import pandas as pd

    paths = arc_paths(abstraction, graph)
    nodes = junction_nodes(abstraction, graph)
    point_of = {int(n): abstraction.junctions[k] for k, n in enumerate(nodes)}
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
    """The measured junction gaps of each variant (Fig. 11), one row per run.

    Columns: ``image``, ``variant``, ``arcs`` (|A| of the final level), ``E^s``
    (px), ``junctions`` (of the result, see :func:`gap_table`), ``max gap``,
    ``mean gap`` (px), ``junctions with gap > {threshold} px``, ``max spread``
    (px), ``redundant intersections`` (Fig. 6c, red box) and ``paper`` (what
    Fig. 11 shows; it gives no numbers).
    """
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
    """Every junction of every run's final level with its gap (:func:`gap_table`).

    Columns: ``image``, ``variant`` and those of :func:`gap_table`, the
    coordinates and distances rounded to 1e-4 px.
    """
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
    """Redundant intersections of every run (Fig. 12), one row per run.

    Columns: ``image``, ``T`` (px), ``variant``, ``arcs`` (|A| of the final
    level), ``E^s`` (px), ``redundant intersections`` (of the final level,
    :func:`img2logo.quality.level_redundant_intersections`), ``at A^0`` (of the initial fit,
    which no merge decision can change) and ``merges rejected`` (candidate
    merges the run turned down for leaving a redundant intersection).
    """
    import pandas as pd

    rows = []
    for run in runs:
        rows.append(
            {
                "image": run.name,
                "T": run.final.tolerance,
                "variant": run.variant,
                "arcs": len(run.final.arcs),
                "E^s": round(run.final.similarity, 4),
                "redundant intersections": len(level_redundant_intersections(run.final)),
                "at A^0": len(level_redundant_intersections(run.progression.levels[0])),
                "merges rejected": int(run.progression.stats.get("rejected_intersections", 0)),
            }
        )
    return pd.DataFrame(rows)


def avoidance_effect(
    table: pd.DataFrame,
    *,
    with_label: str = "(b) with avoidance",
    without_label: str = "(c) without avoidance",
) -> pd.DataFrame:
    """Per image and T, the redundant intersections with and without avoidance side by side.

    ``table`` is a :func:`redundant_table`. Columns: ``image``, ``T``, ``with``,
    ``without``, ``difference`` (without - with), ``arcs with``, ``arcs without``.
    """
    key = ["image", "T"]
    a = table[table["variant"] == with_label].set_index(key)
    b = table[table["variant"] == without_label].set_index(key)
    cols = ["redundant intersections", "arcs"]
    out = (
        a[cols]
        .join(b[cols].add_suffix(" without"), how="inner")
        .rename(
            columns={
                "redundant intersections": "with",
                "redundant intersections without": "without",
                "arcs": "arcs with",
            }
        )
    )
    out["difference"] = out["without"] - out["with"]
    return out.reset_index()[["image", "T", "with", "without", "difference", "arcs with", "arcs without"]]


def select_cases(effect: pd.DataFrame, count: int = 4, *, prefer: float = TOLERANCE) -> list[tuple[str, float]]:
    """The (image, T) cases where avoidance matters most, for the figure (Fig. 12).

    From an :func:`avoidance_effect` table, the cases where the run without
    avoidance has more redundant intersections; at most one per image (its
    largest difference, ties to the T closest to ``prefer``); the ``count``
    largest differences, ties to T closest to ``prefer``, then by name.
    """
    cases = effect[effect["difference"] > 0].copy()
    cases["distance"] = (cases["T"] - prefer).abs()
    cases = cases.sort_values(["difference", "distance", "image"], ascending=[False, True, True])
    cases = cases.drop_duplicates("image").head(count)
    return [(str(i), float(t)) for i, t in zip(cases["image"], cases["T"], strict=True)]


# =========================================================================== drawing helpers
def _arc_colors(n: int) -> list[Any]:
    """``n`` distinct colours cycled from tab10."""
    import matplotlib

    cmap = matplotlib.colormaps["tab10"]
    return [cmap(i % cmap.N) for i in range(n)]


def _box(ax: Axes, window: tuple[float, float, float, float], label: str, color: str = "#555555") -> None:
    """A dashed rectangle (x0, y0, x1, y1) with a label at its corner."""
    from matplotlib.patches import Rectangle

    x0, y0, x1, y1 = window
    ax.add_patch(
        Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, edgecolor=color, linewidth=0.8, linestyle="--", zorder=6)
    )
    ax.text(x0, y0, label, color=color, fontsize=7, ha="left", va="bottom", zorder=6)


def _show_window(ax: Axes, window: tuple[float, float, float, float]) -> None:
    frame_window(ax, window, color="#555555", linewidth=0.8)


def _faint_segments(ax: Axes, graph: SegmentGraph, color: str = "#c8c8c8", linewidth: float = 3.0) -> None:
    """The input segments as a wide faint band under a drawing."""
    from matplotlib.collections import LineCollection

    lc = LineCollection(list(graph.segments), colors=color, linewidths=linewidth, capstyle="round", zorder=1)
    ax.add_collection(lc, autolim=False)


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

    For each variant of ``variants`` in turn (cycling), its largest gap above
    ``threshold`` not already inside a chosen window; the window is a square of
    side max(``min_size``, 4 x gap + 16) px around that junction, inside the
    image. Returns at most ``count`` (variant, (x0, y0, x1, y1)) pairs.
    """
    by_variant = {r.variant: r for r in runs}
    queues = []
    for v in variants:
        if v not in by_variant:
            continue
        run = by_variant[v]
        gaps = gap_table(run.final, run.graph)
        gaps = gaps[gaps["gap"] > threshold].sort_values(["gap", "node"], ascending=[False, True])
        queues.append((v, run, list(gaps.itertuples(index=False))))
    out: list[tuple[str, tuple[float, float, float, float]]] = []
    while len(out) < count and any(q for _, _, q in queues):
        for v, run, queue in queues:
            while queue:
                row = queue.pop(0)
                inside = any(w[0] <= row.x <= w[2] and w[1] <= row.y <= w[3] for _, w in out)
                if not inside:
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
    """Fig. 11 (and Fig. 6): the variants of the connectivity constraint side by side.

    For each image: a row of full views, (a) the segment graph and the final
    levels of the runs (b)-(e) in black, every junction gap above
    ``threshold`` circled in green (Fig. 6c's green box) and every redundant
    intersection in red (its red box); then ``zooms`` rows of insets on the
    largest gaps of (c) and (d) (:func:`gap_windows`), the same window in every
    column: the input segments as a faint grey band, each arc in its own
    colour, the junction points as black dots.

    Parameters
    ----------
    runs : sequence of Run
        From :func:`img2logo.experiments.sweep` with :data:`CONNECTIVITY_VARIANTS`
        (any subset, any number of images), image-major.
    zooms : int
        Inset rows per image.
    threshold : float
        Gaps above this are circled, px.
    title : str
        The figure's title; the colour key is appended.
    """
    from matplotlib.figure import Figure

    names = list(dict.fromkeys(r.name for r in runs))
    variants = list(dict.fromkeys(r.variant for r in runs))
    windows = {n: gap_windows([r for r in runs if r.name == n], count=zooms, threshold=threshold) for n in names}
    rows_per = {n: 1 + len(windows[n]) for n in names}
    n_rows, n_cols = sum(rows_per.values()), 1 + len(variants)
    fig = Figure(figsize=(n_cols * panel_size, n_rows * panel_size + 0.4), layout="constrained")
    axes = fig.subplots(n_rows, n_cols, squeeze=False)
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
            _box(ax, win, str(j + 1))
        for col, v in enumerate(variants, start=1):
            ax = axes[row, col]
            if v not in mine:
                frame_image(ax, w, h)
                continue
            run = mine[v]
            frame_image(ax, w, h)
            draw_arcs(ax, run.final.arcs, linewidth=1.0)
            g = gaps[v]
            big = g[g["gap"] > threshold]
            for x, y, gap in zip(big["x"], big["y"], big["gap"], strict=True):
                ring(ax, x, y, max(12.0, gap + 6.0), GAP_COLOR)
            for ri in level_redundant_intersections(run.final):
                ring(ax, float(ri.point[0]), float(ri.point[1]), 12.0, INTERSECTION_COLOR)
            for j, (_, win) in enumerate(windows[name]):
                _box(ax, win, str(j + 1))
            max_gap = float(g["gap"].max()) if len(g) else 0.0
            ax.set_title(
                f"{v}\n|A| = {len(run.final.arcs)}, E$^s$ = {run.final.similarity:.2f}, "
                f"max gap {max_gap:.2f} px, {len(big)} > {threshold:g}",
                fontsize=7,
            )
        # zoomed insets
        for j, (source, win) in enumerate(windows[name]):
            r = row + 1 + j
            ax = axes[r, 0]
            plot_segment_graph(graph, ax, linewidth=2.0, markersize=5.0)
            _show_window(ax, win)
            ax.set_title(f"inset {j + 1} (largest gap of {source[:3]})", fontsize=7)
            for col, v in enumerate(variants, start=1):
                ax = axes[r, col]
                frame_image(ax, w, h)
                if v not in mine:
                    continue
                run = mine[v]
                _faint_segments(ax, graph, linewidth=6.0)
                draw_arcs(ax, run.final.arcs, colors=_arc_colors(len(run.final.arcs)), linewidth=1.6)
                g = gaps[v]
                ax.plot(g["x"], g["y"], "o", color="#000000", markersize=3.0, zorder=4, linestyle="none")
                big = g[g["gap"] > threshold]
                for x, y, gap in zip(big["x"], big["y"], big["gap"], strict=True):
                    ring(ax, x, y, gap + 2.0, GAP_COLOR, linewidth=1.5)
                _show_window(ax, win)
                inside = g[(g["x"] >= win[0]) & (g["x"] <= win[2]) & (g["y"] >= win[1]) & (g["y"] <= win[3])]
                worst = float(inside["gap"].max()) if len(inside) else 0.0
                ax.set_title(f"{v[:3]} inset {j + 1}: largest gap {worst:.2f} px", fontsize=7)
        row += rows_per[name]
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
    """Fig. 12: results with and without redundant-intersection avoidance.

    One row per case (image, T): (a) the segment graph, (b) the final level
    with avoidance, (c) without, every redundant intersection circled in red;
    then (b) and (c) zoomed on the same window of side ``zoom`` px around a
    redundant intersection of (c) that (b) does not have nearby (else the
    first of (c), else of (b)), each arc in its own colour over the input
    segments in faint grey.

    Parameters
    ----------
    runs : sequence of Run
        From :func:`img2logo.experiments.sweep` with :data:`AVOIDANCE_VARIANTS`.
    cases : sequence of (str, float), optional
        The (image, T) rows to show (:func:`select_cases`); when None or
        empty (avoidance changed nothing), every (image, T) of ``runs``.
    """
    from matplotlib.figure import Figure

    index = {(r.name, r.final.tolerance, r.variant): r for r in runs}
    cases = list(cases or [])
    if not cases:
        cases = list(dict.fromkeys((r.name, r.final.tolerance) for r in runs))
    fig = Figure(figsize=(5 * panel_size, max(1, len(cases)) * panel_size + 0.4), layout="constrained")
    axes = fig.subplots(max(1, len(cases)), 5, squeeze=False)
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
                _box(ax, win, "zoom")
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
            _faint_segments(zax, graph, linewidth=5.0)
            draw_arcs(zax, run.final.arcs, colors=_arc_colors(len(run.final.arcs)), linewidth=1.6)
            j = run.final.junctions
            zax.plot(j[:, 0], j[:, 1], "o", color="#000000", markersize=3.0, zorder=4, linestyle="none")
            for ri in points:
                ring(zax, float(ri.point[0]), float(ri.point[1]), zoom / 12.0, INTERSECTION_COLOR, linewidth=1.5)
            _show_window(zax, win)
            zax.set_title(f"{run.variant[:3]} zoomed", fontsize=7)
    fig.suptitle("Redundant intersection avoidance (Fig. 12): red circles = redundant intersections", fontsize=9)
    return fig


# =========================================================================== Fig. 9: arc selection
#: The variants of Fig. 9 (b), (c) as whole runs: the rule also steers the merges.
ARC_SELECTION_VARIANTS: dict[str, dict[str, Any]] = {
    "(b) Fréchet": {"arc_selection": "frechet"},
    "(c) sum of squares": {"arc_selection": "sum_of_squares"},
}


def _same_arc(a: Arc, b: Arc, tol: float = 1e-6) -> bool:
    """Whether two arcs of one circle cover the same points (either orientation)."""
    if a.circle != b.circle or abs(abs(a.sweep) - abs(b.sweep)) > tol / a.circle.r:
        return False
    if a.is_full_circle:
        return True
    ends_a, ends_b = (a.start, a.end), (b.start, b.end)
    same = all(math.dist(p, q) <= tol for p, q in zip(ends_a, ends_b, strict=True))
    flipped = all(math.dist(p, q) <= tol for p, q in zip(ends_a, ends_b[::-1], strict=True))
    return same or flipped


@dataclass(frozen=True, eq=False)
class ArcSelectionComparison:
    """Both arc-selection rules applied to the circles and junctions of one level (Fig. 9).

    Attributes
    ----------
    name : str
        The image's name.
    level : Abstraction
        The level whose circles and (displaced) junctions are used.
    frechet, sum_of_squares : tuple of ArcFit
        For each arc of the level, the arc each rule picks among the same
        candidates (:func:`~img2logo.arc_extraction.extract_arc`) and its
        Fréchet distance to the arc's pixels, px.
    table : pandas.DataFrame
        One row per arc: ``arc``, ``segments``, ``junctions`` (constraints),
        ``candidates`` (admissible candidate arcs: a choice exists when > 1),
        ``sweep F``, ``sweep S`` (degrees), ``Fréchet F``, ``Fréchet S`` (px),
        ``differs``, ``reproduces level`` (the Fréchet pick is the level's arc).
    """

    name: str
    level: Abstraction
    frechet: tuple[ArcFit, ...]
    sum_of_squares: tuple[ArcFit, ...]
    table: Any

    @property
    def with_choice(self) -> list[int]:
        """Indices of the arcs whose circle offered more than one admissible candidate."""
        return [int(i) for i in self.table.loc[self.table["candidates"] > 1, "arc"]]

    @property
    def differing(self) -> list[int]:
        """Indices of the arcs on which the two rules disagree."""
        return [int(i) for i in self.table.loc[self.table["differs"], "arc"]]


def compare_arc_selection(abstraction: Abstraction, graph: SegmentGraph, name: str = "") -> ArcSelectionComparison:
    """Pick every arc of a level again with both rules, on the same circles (Fig. 9).

    For arc i, its pixel chain (:func:`arc_chain`), its circle and its
    junction points p_k + d_k in path order (the ends of its path and, when the
    run constrained them, its inner junctions; a run without the connectivity
    constraint projects them on the circle, as the optimizer does) go to
    :func:`~img2logo.arc_extraction.extract_arc` with ``method="frechet"``
    (the paper's choice, Fig. 9b) and with ``method="sum_of_squares"`` (the
    circle fitting error, Fig. 9c).
    """
    import pandas as pd

    inner = bool(abstraction.params.get("inner_junctions", True))
    project = not bool(abstraction.params.get("connectivity", True))
    nodes = junction_nodes(abstraction, graph)
    index = {int(n): k for k, n in enumerate(nodes)}
    valence = graph.valence
    by_f, by_s, rows = [], [], []
    for i, (arc, segs) in enumerate(zip(abstraction.arcs, abstraction.arc_segments, strict=True)):
        path, points = arc_chain(graph, segs)
        constrained = list(_constrained(path, valence, inner))
        if path[0] == path[-1]:
            constrained.append(path[0])
        pts = np.array([abstraction.junctions[index[n]] for n in constrained])
        circle = arc.circle
        if project:
            pts = circle.point_at(circle.angle_of(pts))
        f = extract_arc(circle, points, pts, method="frechet")
        s = extract_arc(circle, points, pts, method="sum_of_squares")
        choice = len(admissible_arcs(circle, points, pts)[0])
        by_f.append(f)
        by_s.append(s)
        rows.append(
            {
                "arc": i,
                "segments": len(segs),
                "junctions": len(set(constrained)),
                "candidates": choice,
                "sweep F": round(math.degrees(abs(f.arc.sweep)), 3),
                "sweep S": round(math.degrees(abs(s.arc.sweep)), 3),
                "Fréchet F": round(f.frechet, 4),
                "Fréchet S": round(s.frechet, 4),
                "differs": not _same_arc(f.arc, s.arc),
                "reproduces level": _same_arc(f.arc, arc),
            }
        )
    return ArcSelectionComparison(name, abstraction, tuple(by_f), tuple(by_s), pd.DataFrame(rows))


def arc_selection_study(runs: Sequence[Run]) -> list[ArcSelectionComparison]:
    """:func:`compare_arc_selection` on every level of every Fréchet run of ``runs``.

    ``runs`` come from :func:`img2logo.experiments.sweep` with :data:`ARC_SELECTION_VARIANTS`;
    the sum-of-squares runs are compared whole in :func:`arc_selection_table`.
    Returns the comparisons run-major, level by level.
    """
    out = []
    for run in runs:
        if run.settings.get("arc_selection", "frechet") != "frechet":
            continue
        out.extend(compare_arc_selection(level, run.graph, run.name) for level in run.progression.levels)
    return out


def differing_arcs(comparisons: Sequence[ArcSelectionComparison]) -> pd.DataFrame:
    """Every arc on which the two rules disagree (Fig. 9), one row each.

    Columns: ``image``, ``level`` and those of
    :attr:`ArcSelectionComparison.table`; empty (with the columns) when the
    rules always agree.
    """
    import pandas as pd

    parts = []
    for comp in comparisons:
        t = comp.table[comp.table["differs"].astype(bool)].copy()
        t.insert(0, "level", comp.level.level)
        t.insert(0, "image", comp.name)
        parts.append(t)
    if not parts:
        return pd.DataFrame(columns=["image", "level", "arc", "Fréchet F", "Fréchet S"])
    return pd.concat(parts, ignore_index=True)


def _levels_equal(a: Progression, b: Progression) -> bool:
    """Whether two runs produced the same levels, arc by arc."""
    if len(a.levels) != len(b.levels):
        return False
    for x, y in zip(a.levels, b.levels, strict=True):
        if len(x.arcs) != len(y.arcs) or not all(_same_arc(u, v) for u, v in zip(x.arcs, y.arcs, strict=True)):
            return False
    return True


def arc_selection_table(runs: Sequence[Run], comparisons: Sequence[ArcSelectionComparison]) -> pd.DataFrame:
    """Fréchet against sum of squares per image and T (Fig. 9), one row per pair of runs.

    Columns: ``image``, ``T``; over every level of the Fréchet run, the arcs
    re-picked on the same circles (``arcs compared``), those whose circle
    offered a choice (``with a choice``), those on which the rules disagree
    (``differ``) and their Fréchet distances with each rule (``Fréchet F``,
    ``Fréchet S``: lists, px); then the whole runs: final |A| and E^s with each
    rule and whether the two runs are identical level by level.
    """
    import pandas as pd

    rows = []
    pairs: dict[tuple[str, float], dict[str, Run]] = {}
    for run in runs:
        pairs.setdefault((run.name, run.final.tolerance), {})[run.settings.get("arc_selection", "frechet")] = run
    for (name, t), both in pairs.items():
        f_run, s_run = both.get("frechet"), both.get("sum_of_squares")
        if f_run is None:
            continue
        mine = [c for c in comparisons if c.name == name and any(c.level is lv for lv in f_run.progression.levels)]
        tables = [c.table for c in mine]
        table = pd.concat(tables, ignore_index=True) if tables else pd.DataFrame(columns=["candidates", "differs"])
        diff = table[table["differs"].astype(bool)]
        rows.append(
            {
                "image": name,
                "T": t,
                "levels": len(f_run.progression.levels),
                "arcs compared": len(table),
                "with a choice": int((table["candidates"] > 1).sum()),
                "differ": len(diff),
                "Fréchet F": " ".join(f"{v:.2f}" for v in diff.get("Fréchet F", [])),
                "Fréchet S": " ".join(f"{v:.2f}" for v in diff.get("Fréchet S", [])),
                "final arcs F": len(f_run.final.arcs),
                "final arcs S": len(s_run.final.arcs) if s_run else None,
                "E^s F": round(f_run.final.similarity, 4),
                "E^s S": round(s_run.final.similarity, 4) if s_run else None,
                "runs identical": _levels_equal(f_run.progression, s_run.progression) if s_run else None,
            }
        )
    return pd.DataFrame(rows)


def plot_arc_selection(comparisons: Sequence[ArcSelectionComparison], *, panel_size: float = 3.2) -> Figure:
    """Fig. 9 on real images: the arcs each rule picks on the same circles.

    One panel per image: of its comparisons (:func:`arc_selection_study`), the
    level where the rules disagree on most arcs (ties: the later level, so the
    final one when they never disagree). The level's arcs in black, those whose circle
    offered a choice between candidate arcs in thin blue, and where the rules
    disagree the Fréchet pick (Fig. 9b) thick in blue and the sum-of-squares
    pick (Fig. 9c) thick in orange, over the faded input segments.
    """
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D

    chosen: dict[str, ArcSelectionComparison] = {}
    for comp in comparisons:
        best = chosen.get(comp.name)
        if best is None or len(comp.differing) >= len(best.differing):
            chosen[comp.name] = comp
    comparisons = list(chosen.values())
    n = max(1, len(comparisons))
    cols = min(n, 4)
    rows = math.ceil(n / cols)
    # At least two panels wide: the title and the legend need the width even for one image.
    fig = Figure(figsize=(max(cols, 2) * panel_size, rows * panel_size + 1.0), layout="constrained")
    axes = fig.subplots(rows, cols, squeeze=False).ravel()
    for ax in axes:
        ax.set_axis_off()
    for ax, comp in zip(axes, comparisons, strict=False):
        lv = comp.level
        frame_image(ax, lv.width, lv.height)
        differing, choice = set(comp.differing), set(comp.with_choice)
        draw_arcs(ax, [a for i, a in enumerate(lv.arcs) if i not in choice], linewidth=1.0)
        draw_arcs(ax, [a for i, a in enumerate(lv.arcs) if i in choice - differing], colors="#6baed6", linewidth=1.2)
        draw_arcs(ax, [comp.frechet[i].arc for i in sorted(differing)], colors=DIFFERENCE_COLORS[0], linewidth=3.5)
        draw_arcs(
            ax, [comp.sum_of_squares[i].arc for i in sorted(differing)], colors=DIFFERENCE_COLORS[1], linewidth=2.0
        )
        ax.set_title(
            f"{comp.name}, level {lv.level}: |A| = {len(lv.arcs)}\n"
            f"{len(choice)} arcs with a choice, {len(differing)} differ",
            fontsize=8,
        )
    handles = [
        Line2D([], [], color="#000000", lw=1.0, label="one admissible arc"),
        Line2D([], [], color="#6baed6", lw=1.2, label="a choice; both rules agree"),
        Line2D([], [], color=DIFFERENCE_COLORS[0], lw=3.5, label="differs: Fréchet pick (Fig. 9b)"),
        Line2D([], [], color=DIFFERENCE_COLORS[1], lw=2.0, label="differs: sum-of-squares pick (Fig. 9c)"),
    ]
    fig.legend(handles=handles, loc="outside lower center", ncols=2 if cols < 4 else 4, fontsize=8, frameon=False)
    fig.suptitle("Arc extraction (Fig. 9): both rules on the same circles and junctions", fontsize=9)
    return fig


# =========================================================================== Fig. 9: the hook
@dataclass(frozen=True, eq=False)
class HookExample:
    """A constructed segment where the two arc-selection rules disagree (Fig. 9).

    The pixels run along ``circle`` from the junction at angle 0 the wrong
    way, to ``-hook`` radians, come back over themselves, and go on to the
    junction at pi / 2 (angles from +x towards +y, y down). The short arc
    between the junctions is what was drawn (Fig. 9b); the sum of squared
    distances to the arc prefers the long way round, which also covers the hook,
    at the price of a redundant part nobody drew (Fig. 9c).

    Attributes
    ----------
    hook : float
        The hook's angle, radians (0 to pi).
    circle : Circle
    points : ndarray, shape (N, 2)
        The pixel chain, about 1 px apart.
    junctions : ndarray, shape (2, 2)
    frechet, sum_of_squares : ArcFit
        The arc each rule picks, with its Fréchet distance to the pixels.
    """

    hook: float
    circle: Circle
    points: np.ndarray
    junctions: np.ndarray
    frechet: ArcFit
    sum_of_squares: ArcFit

    @property
    def differs(self) -> bool:
        """Whether the two rules pick different arcs."""
        return not _same_arc(self.frechet.arc, self.sum_of_squares.arc)


def hook_example(hook_degrees: float = 60.0, *, radius: float = 50.0, center: float = 100.0) -> HookExample:
    """Build the hook of :class:`HookExample` and pick its arc with both rules (Fig. 9).

    Parameters
    ----------
    hook_degrees : float
        How far the pixels first run the wrong way, degrees, in [0, 180).
    radius : float
        The circle's radius, px.
    center : float
        Both coordinates of the circle's centre, px.
    """
    if not 0.0 <= float(hook_degrees) < 180.0:
        raise InvalidParameterError(f"hook_degrees must be in [0, 180), got {hook_degrees}")
    hook = math.radians(float(hook_degrees))
    circle = Circle(float(center), float(center), float(radius))

    def run(t0: float, t1: float) -> np.ndarray:
        n = max(2, math.ceil(abs(t1 - t0) * radius) + 1)
        return circle.point_at(np.linspace(t0, t1, n))

    back = run(-hook, math.pi / 2)
    points = np.vstack([run(0.0, -hook), back[1:]]) if hook > 0 else run(0.0, math.pi / 2)
    junctions = circle.point_at(np.array([0.0, math.pi / 2]))
    return HookExample(
        float(hook),
        circle,
        points,
        junctions,
        extract_arc(circle, points, junctions, method="frechet"),
        extract_arc(circle, points, junctions, method="sum_of_squares"),
    )


def hook_table(hooks_degrees: Sequence[float]) -> pd.DataFrame:
    """The hook of :func:`hook_example` for several hook angles (degrees): which arc each rule picks.

    Columns: ``hook (deg)``, ``sweep F``, ``sweep S`` (degrees of the picked
    arcs), ``Fréchet F``, ``Fréchet S`` (their Fréchet distances to the
    pixels, px), ``differs``.
    """
    import pandas as pd

    rows = []
    for h in hooks_degrees:
        ex = hook_example(float(h))
        rows.append(
            {
                "hook (deg)": round(math.degrees(ex.hook), 3),
                "sweep F": round(math.degrees(abs(ex.frechet.arc.sweep)), 3),
                "sweep S": round(math.degrees(abs(ex.sum_of_squares.arc.sweep)), 3),
                "Fréchet F": round(ex.frechet.frechet, 4),
                "Fréchet S": round(ex.sum_of_squares.frechet, 4),
                "differs": ex.differs,
            }
        )
    return pd.DataFrame(rows)


def plot_hook_example(example: HookExample, table: pd.DataFrame | None = None, *, panel_size: float = 3.4) -> Figure:
    """Fig. 9 constructed: the hook's pixels, the arc of each rule, and (optionally) a sweep.

    Panels: (a) the pixels (the hook drawn slightly off the circle so that it
    shows), the circle dashed and the two junctions; (b) the Fréchet pick;
    (c) the sum-of-squares pick, its redundant part visible; with ``table``
    (:func:`hook_table`) a fourth panel plots the Fréchet distance of each
    pick against the hook angle.
    """
    from matplotlib.figure import Figure

    n = 4 if table is not None else 3
    fig = Figure(figsize=(n * panel_size, panel_size + 0.3), layout="constrained")
    axes = fig.subplots(1, n, squeeze=False)[0]
    c = example.circle
    pad = 0.25 * c.r
    box = (c.cx - c.r - pad, c.cy - c.r - pad, c.cx + c.r + pad, c.cy + c.r + pad)
    # the pixels, pushed inward along the hook so the way out and back are both seen
    t = c.angle_of(example.points)
    k = int(np.argmin(np.unwrap(t))) if example.hook > 0 else 0
    shown = example.points.copy()
    if k > 0:
        inward = (c.center - shown[: k + 1]) / c.r
        shown[: k + 1] += 3.0 * inward
    arcs = (
        (None, "(a) segment pixels"),
        (example.frechet, "(b) Fréchet"),
        (example.sum_of_squares, "(c) sum of squares"),
    )
    for ax, (fit, title) in zip(axes[:3], arcs, strict=True):
        from matplotlib.patches import Circle as CirclePatch

        ax.add_patch(CirclePatch((c.cx, c.cy), c.r, fill=False, ls="--", lw=0.6, edgecolor="#999999"))
        ax.plot(shown[:, 0], shown[:, 1], "-", color="#555555", lw=1.2, zorder=3)
        if fit is not None:
            color = DIFFERENCE_COLORS[0] if fit is example.frechet else DIFFERENCE_COLORS[1]
            draw_arcs(ax, [fit.arc], colors=color, linewidth=3.0)
            title += f": sweep {math.degrees(abs(fit.arc.sweep)):.0f}°, Fréchet {fit.frechet:.1f} px"
        j = example.junctions
        ax.plot(j[:, 0], j[:, 1], "o", color="#d62728", ms=5, zorder=5)
        _show_window(ax, box)
        ax.set_title(title, fontsize=8)
    if table is not None:
        ax = axes[3]
        ax.plot(table["hook (deg)"], table["Fréchet F"], "o-", color=DIFFERENCE_COLORS[0], label="Fréchet pick")
        ax.plot(table["hook (deg)"], table["Fréchet S"], "s--", color=DIFFERENCE_COLORS[1], label="sum-of-squares pick")
        ax.set_xlabel("hook angle (degrees)", fontsize=8)
        ax.set_ylabel("Fréchet distance to the pixels (px)", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.legend(fontsize=7)
        ax.set_title("(d) the hook grows", fontsize=8)
    fig.suptitle(
        f"Arc extraction (Fig. 9): a segment with a {math.degrees(example.hook):.0f}° hook, junctions in red",
        fontsize=9,
    )
    return fig


# =========================================================================== Fig. 13: RDP tolerance
def rdp_table(runs: Sequence[Run]) -> pd.DataFrame:
    """One row per run of a sweep over the RDP tolerance (Fig. 13): ``sweep(paths, {"rdp_tolerance": [...]})``.

    Columns: ``image``, ``rdp tolerance`` (px), ``segments`` (|S|), ``arcs at
    A^0`` (after the line-segment simplification of Sec. 5.4), ``final arcs``,
    ``E^s`` (px) and ``levels``.
    """
    import pandas as pd

    rows = []
    for run in runs:
        rows.append(
            {
                "image": run.name,
                "rdp tolerance": float(run.settings["rdp_tolerance"]),
                "segments": run.graph.n_segments,
                "arcs at A^0": len(run.progression.levels[0].arcs),
                "final arcs": len(run.final.arcs),
                "E^s": round(run.final.similarity, 4),
                "levels": len(run.progression.levels),
            }
        )
    return pd.DataFrame(rows)


def _rdp_label(run: Run) -> str:
    return f"RDP {float(run.settings['rdp_tolerance']):g} px"


def plot_rdp_sweep(runs: Sequence[Run], *, panel_size: float = 3.0, inset: float = 0.6) -> Figure:
    """Fig. 13: final results for several RDP tolerances, each beside its segments.

    One row per image; for each tolerance, a small panel (``inset`` of the
    result's size) with the segment graph the run started from, each segment
    in its own colour, then the final level in black.
    """
    from matplotlib.figure import Figure

    names = list(dict.fromkeys(r.name for r in runs))
    labels = list(dict.fromkeys(_rdp_label(r) for r in runs))
    n_cols = 2 * max(1, len(labels))
    fig = Figure(figsize=(len(labels) * (1 + inset) * panel_size, len(names) * panel_size + 0.4), layout="constrained")
    axes = fig.subplots(max(1, len(names)), n_cols, squeeze=False, width_ratios=[inset, 1.0] * max(1, len(labels)))
    index = {(r.name, _rdp_label(r)): r for r in runs}
    for row, name in zip(axes, names, strict=True):
        for j, label in enumerate(labels):
            seg_ax, ax = row[2 * j], row[2 * j + 1]
            run = index.get((name, label))
            if run is None:
                seg_ax.set_axis_off()
                ax.set_axis_off()
                continue
            w, h = run.image.width, run.image.height
            plot_segment_graph(run.graph, seg_ax, show_junctions=False, linewidth=1.2)
            seg_ax.set_title(f"{label}\n|S| = {run.graph.n_segments}", fontsize=7)
            frame_image(ax, w, h)
            draw_arcs(ax, run.final.arcs, linewidth=1.2)
            ax.set_title(
                f"{name}: |A$^0$| = {len(run.progression.levels[0].arcs)}, "
                f"|A| = {len(run.final.arcs)}\nE$^s$ = {run.final.similarity:.2f} px",
                fontsize=7,
            )
    fig.suptitle("Robustness to the initial segmentation (Fig. 13): segments (small) and results", fontsize=9)
    return fig
