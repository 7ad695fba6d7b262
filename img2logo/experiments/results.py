"""The paper's results: Fig. 1, 4, 7, 8, 10 and Tables 1, 2 (Sec. 5.3, 6.1, 6.2).

Tables and figure layouts of ``01_overview`` (the framework at a glance, Fig. 1,
4; a level's circles and arcs, Fig. 7; the two stages of golden circle fitting,
Fig. 8), ``02_visual_results`` (Fig. 10), ``03_simplicity`` (Table 1) and
``04_tolerance_sweep`` (Table 2).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..errors import InvalidParameterError
from ..geometry import Abstraction
from ..plotting import frame_image, frame_window, plot_abstraction, plot_circles, plot_segment_graph, square_window
from ..progressive import Progression
from ..quality import junction_gaps
from ..segment_graph import SegmentGraph
from . import Run, by_image, sweep

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..preprocessing import LoadedImage

#: Table 1 of the paper (a fish): |A^t| by iteration t, as far as the text of
#: the paper is legible. The extracted table reads "Iteration 0 | 23 | 28" with
#: the numbers 51 under iteration 0 and 28 under iteration 23; the entry under
#: iteration 28 is not legible (NaN). Each iteration merges one pair of arcs
#: into one, so |A^t| = |A^0| - t: 51 - 23 = 28 confirms the reading, and
#: would put |A^28| at 23 -- an inference, not a value printed in the paper.
PAPER_TABLE1: dict[int, float] = {0: 51.0, 23: 28.0, 28: math.nan}

#: Table 2 of the paper (a bird): the final |A| by tolerance T, px. Only the
#: entry for T = 4 is legible in the paper's text (31); T = 5 is the bird of
#: Fig. 10 (top row), T = 9 the simplest.
PAPER_TABLE2: dict[float, float] = {4.0: 31.0, 5.0: math.nan, 9.0: math.nan}

#: Colours of the arc groups S_i in the figures that tell them apart.
_GROUP_COLORS = tuple("#1f77b4 #d62728 #2ca02c #9467bd #ff7f0e #17becf #8c564b #e377c2 #bcbd22 #7f7f7f".split())
_LIGHT = "#c8c8c8"


# --------------------------------------------------------------------------- levels
def sampled_levels(progression: Progression, count: int = 3) -> list[int]:
    """``count`` iterations t evenly spread over ``[0, final)`` of a run (fewer when it is shorter), increasing.

    E.g. first, a third, two thirds (Fig. 1, 4c): the final level is shown apart.
    """
    if count < 1:
        raise InvalidParameterError(f"count must be >= 1, got {count}")
    last = len(progression.levels) - 1
    out = sorted({round(float(t)) for t in np.linspace(0, last, count + 1)[:-1]})
    return [t for t in out if t < last] or [0] if last > 0 else out


def level_at_fraction(progression: Progression, fraction: float) -> int:
    """The iteration t at ``fraction`` of the run: ``round(fraction * final)``, fraction in [0, 1]."""
    if not 0.0 <= fraction <= 1.0:
        raise InvalidParameterError(f"fraction must be in [0, 1], got {fraction}")
    return round(fraction * (len(progression.levels) - 1))


# --------------------------------------------------------------------------- drawing helpers
def _figure(rows: int, columns: int, panel: float, *, height_ratio: float = 1.0) -> tuple[Figure, np.ndarray]:
    from matplotlib.figure import Figure

    fig = Figure(figsize=(columns * panel, rows * panel * height_ratio), layout="constrained")
    axes = fig.subplots(rows, columns, squeeze=False)
    return fig, axes


def _show_image(ax: Axes, image: LoadedImage) -> None:
    ax.imshow(image.rgb, extent=(0, image.width, image.height, 0), interpolation="antialiased")
    ax.set_axis_off()


def _show_lines(ax: Axes, lines: np.ndarray) -> None:
    """The 1-px feature-line map, thickened to 3 px for display only (a small panel would lose it)."""
    from scipy.ndimage import binary_dilation

    h, w = lines.shape
    ax.imshow(~binary_dilation(lines), cmap="gray", extent=(0, w, h, 0), interpolation="antialiased")
    ax.set_axis_off()


def _group_color(i: int) -> str:
    return _GROUP_COLORS[i % len(_GROUP_COLORS)]


def _draw_groups(
    ax: Axes,
    graph: SegmentGraph,
    groups: Sequence[Sequence[int]],
    *,
    colors: Sequence[str] | None = None,
    linewidth: float = 1.5,
) -> None:
    """Draw the segments of the graph, those of group i (an S_i) in ``colors[i]``."""
    from matplotlib.collections import LineCollection

    lines, cols = [], []
    for i, group in enumerate(groups):
        color = colors[i] if colors is not None else _group_color(i)
        for s in group:
            lines.append(graph.segments[s])
            cols.append(color)
    ax.add_collection(LineCollection(lines, colors=cols, linewidths=linewidth, capstyle="round", zorder=2))
    frame_image(ax, graph.width, graph.height)


def _level_title(a: Abstraction, prefix: str = "") -> str:
    return f"{prefix}$A^{{{a.level}}}$: |A| = {len(a.arcs)}, $E^s$ = {a.similarity:.2f} px"


def _stroke(panel: float) -> float:
    """Arc width in points for a panel ``panel`` inches wide: about 1/150 of the image."""
    return max(0.8, min(2.0, 72.0 * panel / 150.0))


# --------------------------------------------------------------------------- Fig. 1, 4
def plot_overview(runs: Sequence[Run], *, levels: int = 3, panel_size: float = 2.4) -> Figure:
    """The framework at a glance (paper Fig. 1 and Fig. 4), one row per example.

    Columns: (a) the input; (b) its feature lines; the segment graph L = {S, J}
    with every segment in its own colour; (c) ``levels`` sampled levels of the
    progressive optimization, evenly spread from A^0; (d) the final result with
    its golden circles as thin construction circles.

    Parameters
    ----------
    runs : sequence of Run
        Runs with their levels (the paper shows a photo, a clip art and a line drawing).
    levels : int
        How many intermediate levels to sample.
    """
    columns = 3 + levels + 1
    fig, axes = _figure(max(1, len(runs)), columns, panel_size)
    for row, run in zip(axes, runs, strict=False):
        _show_image(row[0], run.image)
        row[0].set_title(f"(a) {run.name} ({run.kind})", fontsize=8)
        _show_lines(row[1], run.lines.lines)
        row[1].set_title("(b) feature lines", fontsize=8)
        plot_segment_graph(run.graph, row[2], show_junctions=False, linewidth=1.0)
        row[2].set_title(f"(b) segments |S| = {run.graph.n_segments}", fontsize=8)
        ts = sampled_levels(run.progression, levels)
        lw = _stroke(panel_size)
        for j in range(levels):
            ax = row[3 + j]
            if j < len(ts):
                plot_abstraction(run.level(ts[j]), ax, linewidth=lw)
                ax.set_title(_level_title(run.level(ts[j]), "(c) "), fontsize=8)
            else:
                ax.set_axis_off()
        plot_abstraction(run.final, ax=row[-1], show_circles=True, linewidth=lw)
        row[-1].set_title(_level_title(run.final, "(d) final "), fontsize=8)
    fig.suptitle(
        "Fig. 1/4: input, feature lines, segments, progressive levels, final result with its golden circles",
        fontsize=10,
    )
    return fig


# --------------------------------------------------------------------------- Fig. 7
def plot_arc_fitting(runs: Sequence[Run], *, fraction: float = 0.5, panel_size: float = 3.0) -> Figure:
    """Golden ratio arc fitting of one level (paper Fig. 7), one row per example.

    For the level A^t at ``fraction`` of the run: (a) its line segments, each
    group S_i (the segments one arc abstracts) in its own colour; (b) the golden
    circles fitted under the connectivity constraint, in the colour of their
    group, over the faded segments; (c) the arcs extracted from the circles.

    Parameters
    ----------
    runs : sequence of Run
        The examples.
    fraction : float
        Which level: ``round(fraction * final)``.
    """
    fig, axes = _figure(max(1, len(runs)), 3, panel_size)
    for row, run in zip(axes, runs, strict=False):
        a = run.level(level_at_fraction(run.progression, fraction))
        colors = [_group_color(i) for i in range(len(a.arcs))]
        _draw_groups(row[0], run.graph, a.arc_segments, colors=colors)
        row[0].set_title(f"(a) {run.name}: {len(a.arcs)} segment groups $S_i$ at t = {a.level}", fontsize=8)
        _draw_groups(row[1], run.graph, a.arc_segments, colors=[_LIGHT] * len(a.arcs), linewidth=1.0)
        for i, arc in enumerate(a.arcs):
            plot_circles([arc.circle], row[1], color=colors[i], linewidth=0.8)
        frame_image(row[1], a.width, a.height)
        row[1].set_title(f"(b) {len(a.circles)} golden circles (constrained fit)", fontsize=8)
        _draw_groups(row[2], run.graph, a.arc_segments, colors=[_LIGHT] * len(a.arcs), linewidth=1.0)
        plot_abstraction(a, row[2], show_junctions=True, linewidth=_stroke(panel_size))
        row[2].set_title(f"(c) extracted arcs, $E^s$ = {a.similarity:.2f} px", fontsize=8)
    fig.suptitle("Fig. 7: a level's segments, its golden circles, its arcs", fontsize=10)
    return fig


# --------------------------------------------------------------------------- Fig. 8
#: The two stages of golden circle fitting (Fig. 8), as variants of a run without merging.
CIRCLE_FITTING_STAGES: dict[str, dict[str, bool]] = {"independent": {"connectivity": False}, "constrained": {}}


def circle_fitting_stages(runs: Sequence[Run]) -> list[Run]:
    """Fit A^0 of each run's segment graph without and with the connectivity constraint (Fig. 8).

    Stage 1 (``"independent"``): each segment group fitted alone, its radius
    snapped to the ladder (Eqn. 12), its centre placed best for that radius,
    so circles need not meet at the junctions. Stage 2 (``"constrained"``):
    the same golden radii, centres and junction displacements optimized under
    the connectivity constraint (Eqn. 13). Both without merging (only A^0) and
    with the run's ladder bias: the same segment groups and radii.

    Returns
    -------
    list of Run
        Two per run, the stages in that order.
    """
    out = []
    for run in runs:
        stages = sweep([run], variants=CIRCLE_FITTING_STAGES, merging=False, bias=run.bias)
        if stages[0].final.arc_segments != stages[1].final.arc_segments:
            raise InvalidParameterError("the two stages have different segment groups")  # pragma: no cover
        out.extend(stages)
    return out


def _gaps(a: Abstraction) -> np.ndarray:
    """Per junction of J', how far apart its arcs pass (the spread of :func:`img2logo.quality.junction_gaps`), px."""
    return junction_gaps(a.arcs, a.junctions, a.junction_arcs)[1]


def circle_fitting_table(stages: Sequence[Run]) -> pd.DataFrame:
    """Per example: arcs of A^0, junctions of J', and the junction gaps of both stages (Fig. 8).

    ``stages`` come from :func:`circle_fitting_stages`; a gap is how far apart
    the arcs of a junction pass, px.

    Returns
    -------
    pandas.DataFrame
        Columns ``image``, ``arcs``, ``junctions``, ``max gap independent (px)``,
        ``mean gap independent (px)``, ``max gap constrained (px)``.
    """
    import pandas as pd

    rows = []
    for name, (ind, st) in by_image(stages).items():
        free, con = _gaps(ind.final), _gaps(st.final)
        rows.append(
            {
                "image": name,
                "arcs": len(st.final.arcs),
                "junctions": len(st.final.junctions),
                "max gap independent (px)": round(float(free.max(initial=0.0)), 3),
                "mean gap independent (px)": round(float(free.mean()) if len(free) else 0.0, 3),
                "max gap constrained (px)": round(float(con.max(initial=0.0)), 3),
            }
        )
    return pd.DataFrame(rows)


def plot_circle_fitting(
    stages: Sequence[Run],
    *,
    window: float = 60.0,
    max_circles: int = 4,
    panel_size: float = 3.0,
) -> Figure:
    """The two stages of golden circle fitting, zoomed on a junction (paper Fig. 8).

    One row per example, zoomed on the junction (where two or more arcs meet)
    with the largest gap in stage 1. (a) the line segments, the groups meeting
    there in colour; (b) their independently fitted golden circles and arcs;
    (c) the connectivity-optimized circles and arcs, which meet at the
    (displaced) junction. Only the circles of the arcs at that junction are
    drawn (as in the paper, "for clarity we only show a few circles"); the
    other arcs are grey. Titles give the gap at the junction and the largest
    gap over all junctions of the level (:func:`img2logo.quality.junction_gaps`).

    Parameters
    ----------
    stages : sequence of Run
        From :func:`circle_fitting_stages`.
    window : float
        Half the side of the zoomed square, px.
    max_circles : int
        Most circles drawn per panel.
    """
    pairs = by_image(stages)
    fig, axes = _figure(max(1, len(pairs)), 3, panel_size)
    for row, (name, (ind, st)) in zip(axes, pairs.items(), strict=False):
        free, con = ind.final, st.final
        gaps_free, gaps_con = _gaps(free), _gaps(con)
        k = int(np.argmax(gaps_free))
        focus = list(free.junction_arcs[k])[:max_circles]
        colors = [_LIGHT] * len(free.arcs)
        for j, i in enumerate(focus):
            colors[i] = _group_color(j)
        _draw_groups(row[0], st.graph, free.arc_segments, colors=colors, linewidth=2.0)
        p0 = st.graph.junctions[_nearest_node(st.graph, free.junctions[k])]
        row[0].plot(*p0, marker="o", color="black", markersize=5, linestyle="none", zorder=4)
        row[0].set_title(f"(a) {name}: line segments", fontsize=8)
        for ax, a, gaps, label in (
            (row[1], free, gaps_free, "(b) independent golden circles"),
            (row[2], con, gaps_con, "(c) connectivity optimized"),
        ):
            plot_abstraction(a, ax, color=_LIGHT, linewidth=1.5)
            for j, i in enumerate(focus):
                plot_circles([a.arcs[i].circle], ax, color=_group_color(j), linewidth=0.8, linestyle="--")
                ax.plot(*a.arcs[i].sample(step=0.5).T, color=_group_color(j), linewidth=2.0, zorder=3)
            ax.plot(*a.junctions[k], marker="o", color="black", markersize=5, linestyle="none", zorder=4)
            ax.set_title(f"{label}\ngap {gaps[k]:.2f} px here, max {gaps.max():.2f} px", fontsize=8)
        for ax in row:
            frame_window(ax, square_window(p0, 2.0 * window, st.graph.width, st.graph.height, shrink=True))
    fig.suptitle("Fig. 8: golden circles fitted per segment, then under the connectivity constraint", fontsize=10)
    return fig


def _nearest_node(graph: SegmentGraph, point: np.ndarray) -> int:
    return int(np.argmin(np.hypot(*(graph.junctions - point).T)))


# --------------------------------------------------------------------------- Fig. 10
def results_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Per image: kind, |S|, |A^0|, final |A|, iterations, E^s of the final level, bias (Fig. 10).
    Columns ``image``, ``kind``, ``segments``, ``arcs A^0``,
    ``final arcs``, ``iterations``, ``E^s (px)``, ``bias``,
    ``stopped because``.
    """
    import pandas as pd

    rows = []
    for run in runs:
        prog = run.progression
        rows.append(
            {
                "image": run.name,
                "kind": run.kind,
                "segments": run.graph.n_segments,
                "arcs A^0": len(prog.levels[0].arcs),
                "final arcs": len(prog.final.arcs),
                "iterations": prog.final.level,
                "E^s (px)": round(prog.final.similarity, 4),
                "bias": round(prog.bias, 4),
                "stopped because": prog.stopped_because,
            }
        )
    return pd.DataFrame(rows)


def _inset_corner(a: Abstraction, size: float) -> tuple[float, float]:
    """Axes-fraction origin of the corner square of side ``size`` holding the fewest arc points."""
    pts = np.vstack([arc.sample(step=2.0) for arc in a.arcs]) if a.arcs else np.zeros((0, 2))
    fx, fy = pts[:, 0] / a.width, 1.0 - pts[:, 1] / a.height
    corners = [(1.0 - size, 0.0), (1.0 - size, 1.0 - size), (0.0, 0.0), (0.0, 1.0 - size)]
    counts = [int(np.sum((fx >= x) & (fx <= x + size) & (fy >= y) & (fy <= y + size))) for x, y in corners]
    return corners[int(np.argmin(counts))]


def plot_results_grid(
    runs: Sequence[Run],
    *,
    columns: int = 5,
    panel_size: float = 3.0,
    inset: float = 0.27,
) -> Figure:
    """Final results of many images, each with the input as a small inset (paper Fig. 10).

    The inset goes in the corner of the panel that the arcs cross least.
    Titles give the image, its kind, the final arc count |A| and E^s.

    Parameters
    ----------
    runs : sequence of Run
        The examples, in the order of the grid (row by row).
    columns : int
        Panels per row.
    inset : float
        Side of the inset, as a fraction of the panel.
    """
    rows = max(1, math.ceil(len(runs) / columns))
    fig, axes = _figure(rows, min(columns, max(1, len(runs))), panel_size)
    flat = axes.ravel()
    for ax, run in zip(flat, runs, strict=False):
        a = run.final
        plot_abstraction(a, ax, linewidth=_stroke(panel_size))
        ax.set_title(
            f"{run.name} ({run.kind})\n|A| = {len(a.arcs)}, $E^s$ = {a.similarity:.2f} px",
            fontsize=9,
        )
        x, y = _inset_corner(a, inset)
        sub = ax.inset_axes((x, y, inset, inset))
        _show_image(sub, run.image)
        sub.set_axis_on()
        sub.set_xticks([])
        sub.set_yticks([])
        for spine in sub.spines.values():
            spine.set_edgecolor("#808080")
            spine.set_linewidth(0.6)
    for ax in flat[len(runs) :]:
        ax.set_axis_off()
    fig.suptitle("Fig. 10: final golden ratio logo abstractions (inset: the input)", fontsize=11)
    return fig


# --------------------------------------------------------------------------- Table 1
def simplicity_table(
    runs: Sequence[Run],
    *,
    fractions: Sequence[float] = (0.0, 0.4, 0.8, 1.0),
    paper: Mapping[int, float] | None = None,
) -> pd.DataFrame:
    """|A^t| and E^s(A^t) for every iteration t of each run, beside the paper's Table 1.

    Parameters
    ----------
    runs : sequence of Run
        The runs.
    fractions : sequence of float
        The levels shown by :func:`plot_simplicity_levels` (marked in column
        ``shown``).
    paper : mapping of int to float, optional
        The paper's |A^t| by iteration (default :data:`PAPER_TABLE1`; NaN where
        illegible). Iterations the paper reports beyond the end of our run get a
        row of their own with our columns empty.

    Returns
    -------
    pandas.DataFrame
        Columns ``image``, ``iteration``, ``arcs``, ``E^s (px)``, ``shown``,
        ``final`` (the run's result), ``paper |A|`` (Table 1, NaN where the
        paper gives no legible value).
    """
    import pandas as pd

    paper = PAPER_TABLE1 if paper is None else paper
    rows = []
    for run in runs:
        prog = run.progression
        last = len(prog.levels) - 1
        shown = {level_at_fraction(prog, f) for f in fractions}
        for t in sorted(set(range(last + 1)) | {int(t) for t in paper}):
            ours = t <= last
            rows.append(
                {
                    "image": run.name,
                    "iteration": t,
                    "arcs": len(prog.levels[t].arcs) if ours else math.nan,
                    "E^s (px)": round(prog.levels[t].similarity, 4) if ours else math.nan,
                    "shown": t in shown,
                    "final": t == last,
                    "paper |A|": paper.get(t, math.nan),
                }
            )
    table = pd.DataFrame(rows)
    if len(table):
        table["arcs"] = table["arcs"].astype("Int64")
    return table


def plot_simplicity_levels(
    runs: Sequence[Run],
    *,
    fractions: Sequence[float] = (0.0, 0.4, 0.8, 1.0),
    panel_size: float = 2.8,
) -> Figure:
    """Levels of increasing simplicity from one run (paper Table 1), one row per run.

    Parameters
    ----------
    runs : sequence of Run
        The runs.
    fractions : sequence of float
        Which levels, as fractions of the run in [0, 1] (1 is the final level).
    """
    fig, axes = _figure(max(1, len(runs)), len(fractions), panel_size)
    for row, run in zip(axes, runs, strict=False):
        prog = run.progression
        last = len(prog.levels) - 1
        for ax, f in zip(row, fractions, strict=True):
            a = prog.levels[level_at_fraction(prog, f)]
            plot_abstraction(a, ax, linewidth=_stroke(panel_size))
            tag = " (final)" if a.level == last else ""
            ax.set_title(
                f"{run.name}: iteration {a.level}{tag}\n|A| = {len(a.arcs)}, $E^s$ = {a.similarity:.2f} px",
                fontsize=8,
            )
    fig.suptitle("Table 1: results of increasing simplicity along the progressive optimization", fontsize=10)
    return fig


def plot_progression(
    runs: Sequence[Run], *, mark: Sequence[float] = (0.0, 0.4, 0.8, 1.0), panel_size: float = 3.6
) -> Figure:
    """|A^t| (left axis) and E^s(A^t) (right axis) against the iteration t, one panel per run.

    The tolerance T of the run is drawn on the E^s axis (a dashed line); the
    levels at the fractions ``mark`` of the run (those of
    :func:`plot_simplicity_levels`) are marked.
    """
    from matplotlib.ticker import MaxNLocator

    fig, axes = _figure(1, max(1, len(runs)), panel_size, height_ratio=0.8)
    for ax, run in zip(axes[0], runs, strict=False):
        prog = run.progression
        t = np.arange(len(prog.levels))
        arcs = np.array(prog.arc_counts)
        es = np.array(prog.similarities)
        tol = prog.final.tolerance
        ax.plot(t, arcs, color="#1f77b4", marker="o", markersize=3, label="|A|")
        ax.set_xlabel("iteration t")
        ax.set_ylabel("|A| (arcs)", color="#1f77b4")
        ax.tick_params(axis="y", colors="#1f77b4")
        right = ax.twinx()
        right.plot(t, es, color="#d62728", marker="s", markersize=3, label="$E^s$")
        right.axhline(tol, color="#d62728", linestyle="--", linewidth=1.0)
        right.annotate(
            f"T = {tol:g} px",
            (0.5, tol),
            xycoords=("axes fraction", "data"),
            xytext=(0, 3),
            textcoords="offset points",
            ha="center",
            color="#d62728",
            fontsize=8,
        )
        right.set_ylabel("$E^s$ (px)", color="#d62728")
        right.tick_params(axis="y", colors="#d62728")
        right.set_ylim(0, max(float(es.max()), tol) * 1.15)
        idx = sorted({level_at_fraction(prog, f) for f in mark})
        ax.plot(idx, arcs[idx], linestyle="none", marker="o", markersize=8, markerfacecolor="none", color="black")
        ax.set_title(f"{run.name} (stopped: {prog.stopped_because})", fontsize=9)
        ax.xaxis.set_major_locator(MaxNLocator(integer=True))
        ax.yaxis.set_major_locator(MaxNLocator(integer=True))
        ax.grid(alpha=0.3)
    # One panel is narrower than the title: break it in two lines there.
    gap = "\n" if len(runs) < 2 else " "
    fig.suptitle(f"Simplicity: |A| falls by one per iteration{gap}while $E^s$ grows towards T", fontsize=10)
    return fig


# --------------------------------------------------------------------------- Table 2
def _tolerance_sweeps(runs: Sequence[Run]) -> dict[str, list[Run]]:
    """The runs of a sweep over T (``sweep(paths, {"tolerance": [...]})``) by image, T increasing.

    A single run with the largest T would hold every level, but the final level
    of a run with a smaller T' is the level before the first one whose E^s
    exceeds T', the last level with E^s <= T' only if E^s grows monotonically
    along the run -- it need not (:func:`monotonicity_table` checks both rules
    against the runs made per T).
    """
    return {name: sorted(mine, key=_tolerance) for name, mine in by_image(runs).items()}


def _tolerance(run: Run) -> float:
    return float(run.final.tolerance)


def _at(runs: Sequence[Run], tolerance: float) -> Progression:
    for run in runs:
        if math.isclose(_tolerance(run), tolerance):
            return run.progression
    raise InvalidParameterError(f"no run with T = {tolerance} in the sweep {[_tolerance(r) for r in runs]}")


def similarity_is_monotone(progression: Progression) -> bool:
    """Whether E^s never decreases from one level to the next."""
    es = np.array(progression.similarities)
    return bool(np.all(np.diff(es) >= 0.0))


def final_level_index(progression: Progression, tolerance: float, *, rule: str = "first_exceedance") -> int:
    """The final level a run with tolerance ``tolerance`` would reach, read off a longer run.

    Parameters
    ----------
    progression : Progression
        A run with a tolerance >= ``tolerance``.
    tolerance : float
        The smaller tolerance T', px.
    rule : {"first_exceedance", "last_within"}
        ``"first_exceedance"``: the level before the first level t >= 1 whose
        E^s exceeds T' (the loop of Sec. 5.2 stops there: step 2). ``"last_within"``:
        the last level with E^s <= T' -- the same when E^s is monotone, but
        not in general.

    Returns
    -------
    int
        The iteration t (0 when even A^1 exceeds T' or A^0 does).
    """
    es = progression.similarities
    if rule == "first_exceedance":
        for t in range(1, len(es)):
            if es[t] > tolerance:
                return t - 1
        return len(es) - 1
    if rule == "last_within":
        within = [t for t, e in enumerate(es) if e <= tolerance]
        return within[-1] if within else 0
    raise InvalidParameterError(f"rule must be 'first_exceedance' or 'last_within', got {rule!r}")


def tolerance_table(sweeps: Sequence[Run], *, paper: Mapping[float, float] | None = None) -> pd.DataFrame:
    """Final |A| and E^s per tolerance T for each sweep, beside the paper's Table 2.

    Parameters
    ----------
    sweeps : sequence of Run
        A sweep over T (:func:`_tolerance_sweeps`).
    paper : mapping of float to float, optional
        The paper's |A| by T (default :data:`PAPER_TABLE2`, a bird).

    Returns
    -------
    pandas.DataFrame
        Columns ``image``, ``T``, ``final arcs``, ``E^s (px)``, ``iterations``,
        ``stopped because``, ``arcs by first exceedance`` and ``arcs by last
        E^s <= T`` (both read off the largest-T run of the sweep), ``paper |A|``.
    """
    import pandas as pd

    paper = PAPER_TABLE2 if paper is None else paper
    rows = []
    for name, mine in _tolerance_sweeps(sweeps).items():
        ref = mine[-1].progression
        for t, prog in ((_tolerance(r), r.progression) for r in mine):
            rows.append(
                {
                    "image": name,
                    "T": t,
                    "final arcs": len(prog.final.arcs),
                    "E^s (px)": round(prog.final.similarity, 4),
                    "iterations": prog.final.level,
                    "stopped because": prog.stopped_because,
                    "arcs by first exceedance": ref.arc_counts[final_level_index(ref, t)],
                    "arcs by last E^s <= T": ref.arc_counts[final_level_index(ref, t, rule="last_within")],
                    "paper |A|": next((v for k, v in paper.items() if math.isclose(k, t)), math.nan),
                }
            )
    return pd.DataFrame(rows)


def monotonicity_table(sweeps: Sequence[Run]) -> pd.DataFrame:
    """Is E^s monotone along the largest-T run, and which rule reproduces the per-T runs?
    Per sweep: ``image``, ``T max``, ``levels``, ``E^s monotone``,
    ``E^s decreases`` (how many steps lower E^s), ``largest decrease (px)``,
    ``first exceedance matches`` and ``last E^s <= T matches`` (whether the
    rule gives the final arc count of every per-T run).
    """
    import pandas as pd

    rows = []
    for name, mine in _tolerance_sweeps(sweeps).items():
        ref = mine[-1].progression
        steps = np.diff(np.array(ref.similarities))
        finals = [len(r.final.arcs) for r in mine]
        by_rule = {
            rule: [ref.arc_counts[final_level_index(ref, _tolerance(r), rule=rule)] for r in mine]
            for rule in ("first_exceedance", "last_within")
        }
        rows.append(
            {
                "image": name,
                "T max": _tolerance(mine[-1]),
                "levels": len(ref.levels),
                "E^s monotone": similarity_is_monotone(ref),
                "E^s decreases": int(np.sum(steps < 0)),
                "largest decrease (px)": round(float(max(0.0, -steps.min())) if len(steps) else 0.0, 4),
                "first exceedance matches": by_rule["first_exceedance"] == finals,
                "last E^s <= T matches": by_rule["last_within"] == finals,
            }
        )
    return pd.DataFrame(rows)


def plot_tolerance_results(
    sweeps: Sequence[Run],
    tolerances: Sequence[float] = (4.0, 5.0, 9.0),
    *,
    paper: Mapping[float, float] | None = None,
    panel_size: float = 2.8,
) -> Figure:
    """The final result for several tolerances side by side (paper Table 2), one row per sweep.

    The first column is the segment graph every run starts from; then one
    column per T with |A|, E^s and the paper's |A| where it gives one.
    """
    paper = PAPER_TABLE2 if paper is None else paper
    groups = _tolerance_sweeps(sweeps)
    fig, axes = _figure(max(1, len(groups)), 1 + len(tolerances), panel_size)
    for row, (name, mine) in zip(axes, groups.items(), strict=False):
        graph = mine[0].graph
        plot_segment_graph(graph, row[0], show_junctions=False, linewidth=1.0)
        row[0].set_title(f"{name}: |S| = {graph.n_segments}", fontsize=8)
        for ax, t in zip(row[1:], tolerances, strict=True):
            a = _at(mine, t).final
            plot_abstraction(a, ax, linewidth=_stroke(panel_size))
            ref = next((v for k, v in paper.items() if math.isclose(k, t)), math.nan)
            ref_text = "" if math.isnan(ref) else f" (paper {ref:g})"
            ax.set_title(f"T = {t:g}: |A| = {len(a.arcs)}{ref_text}\n$E^s$ = {a.similarity:.2f} px", fontsize=8)
    fig.suptitle("Table 2: larger tolerance T, less similarity, fewer arcs", fontsize=10)
    return fig


def plot_tolerance_curve(
    sweeps: Sequence[Run], *, paper: Mapping[float, float] | None = None, panel_size: float = 3.6
) -> Figure:
    """Final |A| against T (left) and the final E^s against T (right), one line per sweep.

    The paper's |A| values (a bird) are drawn as stars; on the right the line
    E^s = T bounds every final level.
    """
    paper = PAPER_TABLE2 if paper is None else paper
    fig, axes = _figure(1, 2, panel_size, height_ratio=0.8)
    left, right = axes[0]
    groups = _tolerance_sweeps(sweeps)
    for i, (name, mine) in enumerate(groups.items()):
        color = _group_color(i)
        ts = [_tolerance(r) for r in mine]
        left.plot(ts, [len(r.final.arcs) for r in mine], marker="o", markersize=3, color=color, label=name)
        right.plot(ts, [r.final.similarity for r in mine], marker="o", markersize=3, color=color, label=name)
    known = [(t, v) for t, v in sorted(paper.items()) if not math.isnan(v)]
    if known:
        left.plot(
            *zip(*known, strict=True),
            linestyle="none",
            marker="*",
            markersize=12,
            color="black",
            label="paper (its bird)",
        )
    all_t = [_tolerance(r) for mine in groups.values() for r in mine]
    if all_t:
        lo, hi = min(all_t), max(all_t)
        right.plot([lo, hi], [lo, hi], linestyle="--", color="#808080", linewidth=1.0, label="$E^s$ = T")
    left.set_xlabel("tolerance T (px)")
    left.set_ylabel("final |A|")
    right.set_xlabel("tolerance T (px)")
    right.set_ylabel("final $E^s$ (px)")
    for ax in (left, right):
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Similarity constraint: the final arc count against the tolerance T", fontsize=10)
    return fig
