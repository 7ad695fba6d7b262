"""Arc extraction (Fig. 9, Sec. 5.3) for ``07_arc_extraction``: the Fréchet rule against the sum of squares.

Both rules on the circles and junctions of every level of real runs
(:func:`compare_arc_selection`), whole runs with each rule, and a constructed
hook where they disagree (:func:`hook_example`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import InvalidParameterError
from ..export.plotting import frame_image
from ..fit.arc_extraction import ArcFit, admissible_arcs, extract_arc
from ..fit.progressive import Progression
from ..geometry.abstraction import Abstraction
from ..geometry.primitives import Arc, Circle
from ..segment_graph import SegmentGraph
from . import Run, table
from .ablations import WINDOW_FRAME, arc_chain
from .layout import draw_arcs, frame_window, panel_grid

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

#: Colour of the arcs on which two arc-selection rules disagree (Fig. 9).
DIFFERENCE_COLORS: tuple[str, str] = ("#1f77b4", "#ff7f0e")

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
        (:func:`~img2logo.fit.arc_extraction.extract_arc`), with its Fréchet distance, px.
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

    Arc i's pixel chain (:func:`~img2logo.experiments.ablations.arc_chain`) and
    its junctions (the level's ``arc_nodes(i)``) in path order (projected on the
    circle for a run without the connectivity constraint, as the optimizer
    does) go to
    :func:`~img2logo.fit.arc_extraction.extract_arc` with each ``method``.
    """
    import pandas as pd

    index = {n: k for k, n in enumerate(abstraction.junction_nodes) if n is not None}
    by_f, by_s, rows = [], [], []
    for i, (arc, segs) in enumerate(zip(abstraction.arcs, abstraction.arc_segments, strict=True)):
        path, points = arc_chain(graph, segs)
        # the arc's junctions (J' on its path, as the optimizer kept them) in path order;
        # a closed path has its first node at both ends
        mine = set(abstraction.arc_nodes(i))
        constrained = [n for n in path if n in mine]
        pts = np.array([abstraction.junctions[index[n]] for n in constrained])
        circle = arc.circle
        if not abstraction.connected:
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
            title += f"\nsweep {math.degrees(abs(fit.arc.sweep)):.0f}°, Fréchet {fit.frechet:.1f} px"
        j = example.junctions
        ax.plot(j[:, 0], j[:, 1], "o", color="#d62728", ms=5, zorder=5)
        frame_window(ax, box, **WINDOW_FRAME)
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
