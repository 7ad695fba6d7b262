"""Ablations of the key components: Fig. 6, 9, 11, 12, 13 (paper Sec. 5.2, 5.3, 6.2).

For ``05_connectivity_ablation`` (Fig. 6, 11: junction gaps, :func:`gap_table`),
``06_redundant_intersections`` (Fig. 12), ``07_arc_extraction`` (Fig. 9: both
arc-selection rules on the same circles, :func:`compare_arc_selection`; a
constructed hook, :func:`hook_example`) and ``08_rdp_robustness`` (Fig. 13).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..arc_extraction import ArcFit, RedundantIntersection, admissible_arcs, extract_arc
from ..constants import TOLERANCE
from ..errors import InvalidParameterError
from ..geometry import Abstraction, Arc, Circle
from ..plotting import (
    draw_arcs,
    frame_image,
    frame_window,
    mark_window,
    panel_grid,
    plot_segment_graph,
    ring,
    square_window,
)
from ..progressive import Progression
from ..quality import junction_gaps, level_redundant_intersections
from ..segment_graph import SegmentGraph
from . import Run, table

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
_WINDOW = {"color": "#555555", "linewidth": 0.8}  # the frame of a zoomed window

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


def _constrained(path: Sequence[int], valence: np.ndarray, inner_junctions: bool) -> tuple[int, ...]:
    """The nodes of J' on a path: its ends and (optionally) inner nodes of valence >= 3, in path order."""
    inner = tuple(n for n in path[1:-1] if valence[n] >= 3) if inner_junctions else ()
    return (path[0], *inner) if path[0] == path[-1] else (path[0], *inner, path[-1])


def junction_nodes(abstraction: Abstraction, graph: SegmentGraph) -> np.ndarray:
    """The graph node behind each junction of a level, shape (J,), int: J' rebuilt from the arcs' paths.

    Raises
    ------
    InvalidParameterError
        If the rebuilt J' does not match the level (it was not built from this graph).
    """
    inner = bool(abstraction.params.get("inner_junctions", True))
    at: dict[int, set[int]] = {}
    for i, path in enumerate(arc_paths(abstraction, graph)):
        for n in _constrained(path, graph.valence, inner):
            at.setdefault(n, set()).add(i)
    nodes = sorted(at)
    listed = [tuple(sorted(at[n])) for n in nodes]
    if len(nodes) != len(abstraction.junctions) or listed != [tuple(sorted(a)) for a in abstraction.junction_arcs]:
        raise InvalidParameterError("the level's junctions do not match its arcs' paths through this graph")
    return np.array(nodes, dtype=np.int64)


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
                f"{v}\n|A| = {len(run.final.arcs)}, E$^s$ = {run.final.similarity:.2f}, "
                f"max gap {max_gap:.2f} px, {len(big)} > {threshold:g}",
                fontsize=7,
            )
        # zoomed insets
        for j, (source, win) in enumerate(windows[name]):
            r = row + 1 + j
            ax = axes[r, 0]
            plot_segment_graph(graph, ax, linewidth=2.0, markersize=5.0)
            frame_window(ax, win, **_WINDOW)
            ax.set_title(f"inset {j + 1} (largest gap of {source[:3]})", fontsize=7)
            for ax, v, run, g in _panels(axes[r, 1:], variants, mine, gaps, w, h):
                _zoomed_arcs(ax, graph, run.final.arcs, 6.0)
                ax.plot(g["x"], g["y"], "o", color="#000000", markersize=3.0, zorder=4, linestyle="none")
                _ring_gaps(ax, g[g["gap"] > threshold], lambda gap: gap + 2.0, linewidth=1.5)
                frame_window(ax, win, **_WINDOW)
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
            frame_window(zax, win, **_WINDOW)
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
        Per arc of the level, each rule's pick among the same candidates
        (:func:`~img2logo.arc_extraction.extract_arc`), with its Fréchet distance, px.
    table : pandas.DataFrame
        One row per arc: ``arc``, ``segments``, ``junctions``, ``candidates``
        (admissible arcs: a choice when > 1), ``sweep F``, ``sweep S`` (degrees),
        ``Fréchet F``, ``Fréchet S`` (px), ``differs``, ``reproduces level``.
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
    """Pick every arc of a level again with both rules on its circle (Fig. 9b Fréchet, 9c sum of squares).

    Arc i's pixel chain (:func:`arc_chain`) and its junction points in path
    order (projected on the circle for a run without the connectivity
    constraint, as the optimizer does) go to
    :func:`~img2logo.arc_extraction.extract_arc` with each ``method``.
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
    """:func:`compare_arc_selection` on every level of every Fréchet run of ``runs`` (a sweep of the variants)."""
    frechet = [r for r in runs if r.settings.get("arc_selection", "frechet") == "frechet"]
    return [compare_arc_selection(level, run.graph, run.name) for run in frechet for level in run.levels]


def differing_arcs(comparisons: Sequence[ArcSelectionComparison]) -> pd.DataFrame:
    """Every arc on which the two rules disagree: ``image``, ``level`` and the columns of
    :attr:`ArcSelectionComparison.table` (empty, with columns, when they always agree)."""
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
    return len(a.levels) == len(b.levels) and all(
        len(x.arcs) == len(y.arcs) and all(_same_arc(u, v) for u, v in zip(x.arcs, y.arcs, strict=True))
        for x, y in zip(a.levels, b.levels, strict=True)
    )


def arc_selection_table(runs: Sequence[Run], comparisons: Sequence[ArcSelectionComparison]) -> pd.DataFrame:
    """Fréchet against sum of squares per image and T (Fig. 9), one row per pair of runs.

    Over every level of the Fréchet run: the arcs compared, those with a
    choice, those that differ and their Fréchet distances by each rule (px);
    then the whole runs: final |A| and E^s by each rule, and whether they are
    identical level by level.
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
    fig, axes = panel_grid(rows, cols, panel_size, extra_height=1.0, width=max(cols, 2) * panel_size)
    axes = axes.ravel()
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

    The pixels run along ``circle`` from the junction at angle 0 the wrong way
    to ``-hook`` radians, back over themselves, and on to the junction at pi / 2:
    the Fréchet rule picks the short arc drawn (Fig. 9b), the sum of squares
    the long way round, over the hook (Fig. 9c).

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
    """The :class:`HookExample` of a ``hook_degrees`` hook (in [0, 180)) on a circle of ``radius`` px centred
    at (``center``, ``center``) px, its arc picked by both rules (Fig. 9)."""
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
    fits = (extract_arc(circle, points, junctions, method=m) for m in ("frechet", "sum_of_squares"))
    return HookExample(float(hook), circle, points, junctions, *fits)


def hook_table(hooks_degrees: Sequence[float]) -> pd.DataFrame:
    """Per hook angle (degrees) of :func:`hook_example`: the sweep of each rule's arc (degrees), its Fréchet
    distance to the pixels (px), whether they differ."""
    return table(
        (hook_example(float(h)) for h in hooks_degrees),
        {
            "hook (deg)": lambda ex: round(math.degrees(ex.hook), 3),
            "sweep F": lambda ex: round(math.degrees(abs(ex.frechet.arc.sweep)), 3),
            "sweep S": lambda ex: round(math.degrees(abs(ex.sum_of_squares.arc.sweep)), 3),
            "Fréchet F": lambda ex: round(ex.frechet.frechet, 4),
            "Fréchet S": lambda ex: round(ex.sum_of_squares.frechet, 4),
            "differs": lambda ex: ex.differs,
        },
    )


def plot_hook_example(example: HookExample, table: pd.DataFrame | None = None, *, panel_size: float = 3.4) -> Figure:
    """Fig. 9 constructed: the hook's pixels, the arc of each rule, and (optionally) a sweep.

    Panels: (a) the pixels (the hook drawn slightly off the circle so that it
    shows), the circle dashed and the two junctions; (b) the Fréchet pick;
    (c) the sum-of-squares pick, its redundant part visible; with ``table``
    (:func:`hook_table`) a fourth panel plots the Fréchet distance of each
    pick against the hook angle.
    """
    from matplotlib.patches import Circle as CirclePatch

    fig, axes = panel_grid(1, 4 if table is not None else 3, panel_size, extra_height=0.3)
    axes = axes[0]
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
        ax.add_patch(CirclePatch((c.cx, c.cy), c.r, fill=False, ls="--", lw=0.6, edgecolor="#999999"))
        ax.plot(shown[:, 0], shown[:, 1], "-", color="#555555", lw=1.2, zorder=3)
        if fit is not None:
            color = DIFFERENCE_COLORS[0] if fit is example.frechet else DIFFERENCE_COLORS[1]
            draw_arcs(ax, [fit.arc], colors=color, linewidth=3.0)
            title += f": sweep {math.degrees(abs(fit.arc.sweep)):.0f}°, Fréchet {fit.frechet:.1f} px"
        j = example.junctions
        ax.plot(j[:, 0], j[:, 1], "o", color="#d62728", ms=5, zorder=5)
        frame_window(ax, box, **_WINDOW)
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
                f"{name}: |A$^0$| = {len(run.levels[0].arcs)}, "
                f"|A| = {len(run.final.arcs)}\nE$^s$ = {run.final.similarity:.2f} px",
                fontsize=7,
            )
    fig.suptitle("Robustness to the initial segmentation (Fig. 13): segments (small) and results", fontsize=9)
    return fig
