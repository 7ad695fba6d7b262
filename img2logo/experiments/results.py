"""The paper's results: Fig. 1, 4, 7, 8, 10 and Tables 1, 2 (Sec. 5.3, 6.1, 6.2).

For ``01_overview`` (Fig. 1, 4, 7, 8), ``02_visual_results`` (Fig. 10),
``03_simplicity`` (Table 1) and ``04_tolerance_sweep`` (Table 2).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..errors import InvalidParameterError
from ..export.plotting import frame_image, plot_abstraction, plot_circles, plot_segment_graph
from ..fit.progressive import Progression
from ..geometry.abstraction import Abstraction
from ..quality import junction_gaps, logo_points
from . import RUN_COLUMNS, Run, by_image, sweep, table
from .layout import (
    GROUP_COLORS,
    draw_segment_groups,
    emptiest_corner,
    frame_window,
    panel_grid,
    show_image,
    square_window,
)

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

#: Table 1 of the paper (a fish): |A^t| by iteration t, as far as its text is legible: 51 at t = 0,
#: 28 at t = 23; the entry at t = 28 is not (NaN; |A^t| = |A^0| - t would make it 23).
PAPER_TABLE1: dict[int, float] = {0: 51.0, 23: 28.0, 28: math.nan}

#: Table 2 of the paper (a bird): the final |A| by tolerance T, px; only T = 4 is legible (31).
PAPER_TABLE2: dict[float, float] = {4.0: 31.0, 5.0: math.nan, 9.0: math.nan}

_LIGHT = "#c8c8c8"
_SIMPLICITY_FRACTIONS = (0.0, 0.4, 0.8, 1.0)


# --------------------------------------------------------------------------- levels
def sampled_levels(progression: Progression, count: int = 3) -> list[int]:
    """``count`` iterations t evenly spread over ``[0, final)`` of a run (fewer when it is shorter), increasing."""
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


def _level_title(a: Abstraction, prefix: str = "") -> str:
    """A level's panel title on two lines: a narrow panel holds them at a legible size."""
    return f"{prefix}$A^{{{a.level}}}$\n|A| = {len(a.arcs)}, $E^s$ = {a.similarity:.2f} px"


def _stroke(panel: float) -> float:
    """Arc width in points for a panel ``panel`` inches wide: about 1/150 of the image."""
    return max(0.8, min(2.0, 72.0 * panel / 150.0))


# --------------------------------------------------------------------------- Fig. 1, 4, 7
def plot_overview(runs: Sequence[Run], *, levels: int = 3, panel_size: float = 2.4) -> Figure:
    """The framework at a glance (Fig. 1, 4), one row per run.

    Columns: the input, its feature lines, the segment graph, ``levels``
    sampled levels (:func:`sampled_levels`), the final result with its golden circles.
    """
    fig, axes = panel_grid(len(runs), 3 + levels + 1, panel_size)
    lw = _stroke(panel_size)
    for row, run in zip(axes, runs, strict=False):
        show_image(row[0], run.image.rgb)
        row[0].set_title(f"(a) {run.name} ({run.kind})", fontsize=8)
        show_image(row[1], run.lines.lines, thicken=True)
        row[1].set_title("(b) feature lines", fontsize=8)
        plot_segment_graph(run.graph, row[2], show_junctions=False, linewidth=1.0)
        row[2].set_title(f"(b) segments |S| = {run.graph.n_segments}", fontsize=8)
        ts = sampled_levels(run.progression, levels)
        for j, ax in enumerate(row[3:-1]):
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


def plot_arc_fitting(runs: Sequence[Run], *, fraction: float = 0.5, panel_size: float = 3.0) -> Figure:
    """Golden ratio arc fitting of the level at ``fraction`` of each run (Fig. 7), one row per run.

    (a) the segment groups S_i, each in its colour; (b) their golden circles
    (constrained fit); (c) the extracted arcs.
    """
    fig, axes = panel_grid(len(runs), 3, panel_size)
    for row, run in zip(axes, runs, strict=False):
        a = run.level(level_at_fraction(run.progression, fraction))
        colors = [GROUP_COLORS[i % len(GROUP_COLORS)] for i in range(len(a.arcs))]
        draw_segment_groups(row[0], run.graph, a.arc_segments, colors)
        row[0].set_title(f"(a) {run.name}: {len(a.arcs)} segment groups $S_i$ at t = {a.level}", fontsize=8)
        draw_segment_groups(row[1], run.graph, a.arc_segments, [_LIGHT] * len(a.arcs), linewidth=1.0)
        for i, arc in enumerate(a.arcs):
            plot_circles([arc.circle], row[1], color=colors[i], linewidth=0.8)
        frame_image(row[1], a.width, a.height)
        row[1].set_title(f"(b) {len(a.circles)} golden circles (constrained fit)", fontsize=8)
        draw_segment_groups(row[2], run.graph, a.arc_segments, [_LIGHT] * len(a.arcs), linewidth=1.0)
        plot_abstraction(a, row[2], show_junctions=True, linewidth=_stroke(panel_size))
        row[2].set_title(f"(c) extracted arcs, $E^s$ = {a.similarity:.2f} px", fontsize=8)
    fig.suptitle("Fig. 7: a level's segments, its golden circles, its arcs", fontsize=10)
    return fig


# --------------------------------------------------------------------------- Fig. 8
#: The two stages of golden circle fitting (Fig. 8), as variants of a run without merging.
# The constrained stage is the paper's Eqn. 13 alone: the tangent joins (beyond the paper,
# img2logo.fit.tangency) may move a circle to the next rung, and the figure compares equal radii.
# Neither splits a simplified group whose arc crosses another (avoid_intersections, beyond the
# paper's A^0: progressive.split_crossed): the figure compares the same segment groups.
CIRCLE_FITTING_STAGES: dict[str, dict[str, bool]] = {
    "independent": {"connectivity": False, "avoid_intersections": False},
    "constrained": {"tangency": False, "avoid_intersections": False},
}


def circle_fitting_stages(runs: Sequence[Run]) -> list[Run]:
    """A^0 of each run fitted without, then with the connectivity constraint (Fig. 8; Eqn. 12, 13).

    Both without merging, without tangent joins and with the run's bias, so the
    segment groups and the radii are the same. Returns two runs per run, in that order.
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
    """Per image of :func:`circle_fitting_stages`: |A^0|, |J'| and the junction gaps of both stages, px."""
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
    stages: Sequence[Run], *, window: float = 60.0, max_circles: int = 4, panel_size: float = 3.0
) -> Figure:
    """The two stages of golden circle fitting (Fig. 8), zoomed on each image's junction with the largest stage-1 gap.

    (a) the segments, the groups meeting there in colour; (b) the independent
    golden circles and arcs; (c) the constrained ones. Only the circles of the
    arcs at that junction (at most ``max_circles``) are drawn; ``window`` is
    half the side of the zoomed square, px.
    """
    pairs = by_image(stages)
    fig, axes = panel_grid(len(pairs), 3, panel_size)
    for row, (name, (ind, st)) in zip(axes, pairs.items(), strict=False):
        free, con = ind.final, st.final
        gaps_free, gaps_con = _gaps(free), _gaps(con)
        k = int(np.argmax(gaps_free))
        focus = list(free.junction_arcs[k])[:max_circles]
        colors = [_LIGHT] * len(free.arcs)
        for j, i in enumerate(focus):
            colors[i] = GROUP_COLORS[j]
        draw_segment_groups(row[0], st.graph, free.arc_segments, colors, linewidth=2.0)
        p0 = st.graph.junctions[int(np.argmin(np.hypot(*(st.graph.junctions - free.junctions[k]).T)))]
        row[0].plot(*p0, marker="o", color="black", markersize=5, linestyle="none", zorder=4)
        row[0].set_title(f"(a) {name}: line segments", fontsize=8)
        for ax, a, gaps, label in (
            (row[1], free, gaps_free, "(b) independent golden circles"),
            (row[2], con, gaps_con, "(c) connectivity optimized"),
        ):
            plot_abstraction(a, ax, color=_LIGHT, linewidth=1.5)
            for j, i in enumerate(focus):
                plot_circles([a.arcs[i].circle], ax, color=GROUP_COLORS[j], linewidth=0.8, linestyle="--")
                ax.plot(*a.arcs[i].sample(step=0.5).T, color=GROUP_COLORS[j], linewidth=2.0, zorder=3)
            ax.plot(*a.junctions[k], marker="o", color="black", markersize=5, linestyle="none", zorder=4)
            ax.set_title(f"{label}\ngap {gaps[k]:.2f} px here, max {gaps.max():.2f} px", fontsize=8)
        for ax in row:
            frame_window(ax, square_window(p0, 2.0 * window, st.graph.width, st.graph.height, shrink=True))
    fig.suptitle("Fig. 8: golden circles fitted per segment, then under the connectivity constraint", fontsize=10)
    return fig


# --------------------------------------------------------------------------- Fig. 10
def results_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Per run: kind, |S|, |A^0|, final |A|, iterations, final E^s (px), bias, why it stopped (Fig. 10)."""
    return table(
        runs,
        {
            **RUN_COLUMNS,
            "arcs A^0": lambda r: len(r.levels[0].arcs),
            "final arcs": lambda r: len(r.final.arcs),
            "iterations": lambda r: r.final.level,
            "E^s (px)": lambda r: round(r.final.similarity, 4),
            "bias": lambda r: round(r.bias, 4),
            "stopped because": lambda r: r.progression.stopped_because,
        },
    )


def plot_results_grid(runs: Sequence[Run], *, columns: int = 5, panel_size: float = 3.0, inset: float = 0.27) -> Figure:
    """Final results, ``columns`` panels a row, each with its input as an inset (side ``inset`` of the panel) in the
    corner the arcs cross least (Fig. 10)."""
    rows = max(1, math.ceil(len(runs) / columns))
    fig, axes = panel_grid(rows, min(columns, max(1, len(runs))), panel_size)
    flat = axes.ravel()
    for ax, run in zip(flat, runs, strict=False):
        a = run.final
        plot_abstraction(a, ax, linewidth=_stroke(panel_size))
        ax.set_title(f"{run.name} ({run.kind})\n|A| = {len(a.arcs)}, $E^s$ = {a.similarity:.2f} px", fontsize=9)
        points = logo_points(a, 2.0)
        x, y = emptiest_corner(points, a.width, a.height, inset)
        sub = ax.inset_axes((x, y, inset, inset))
        show_image(sub, run.image.rgb)
        frame_window(sub, (0, 0, a.width, a.height), color="#808080", linewidth=0.6, equal=False)
    for ax in flat[len(runs) :]:
        ax.set_axis_off()
    fig.suptitle("Fig. 10: final golden ratio logo abstractions (inset: the input)", fontsize=11)
    return fig


# --------------------------------------------------------------------------- Table 1
def simplicity_table(
    runs: Sequence[Run],
    *,
    fractions: Sequence[float] = _SIMPLICITY_FRACTIONS,
    paper: Mapping[int, float] | None = None,
) -> pd.DataFrame:
    """|A^t| and E^s(A^t) (px) at every iteration t of each run, beside the paper's |A^t| (Table 1).

    ``shown`` marks the levels at ``fractions`` (:func:`plot_simplicity_levels`),
    ``final`` the result; an iteration of ``paper`` (default :data:`PAPER_TABLE1`)
    beyond the end of a run gets a row with our columns empty.
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
    out = pd.DataFrame(rows)
    if len(out):
        out["arcs"] = out["arcs"].astype("Int64")
    return out


def plot_simplicity_levels(
    runs: Sequence[Run], *, fractions: Sequence[float] = _SIMPLICITY_FRACTIONS, panel_size: float = 2.8
) -> Figure:
    """The levels at ``fractions`` of each run (1 is the final level), one row per run (Table 1)."""
    fig, axes = panel_grid(len(runs), len(fractions), panel_size)
    for row, run in zip(axes, runs, strict=False):
        last = len(run.levels) - 1
        for ax, f in zip(row, fractions, strict=True):
            a = run.level(level_at_fraction(run.progression, f))
            plot_abstraction(a, ax, linewidth=_stroke(panel_size))
            tag = " (final)" if a.level == last else ""
            title = f"{run.name}: iteration {a.level}{tag}\n|A| = {len(a.arcs)}, $E^s$ = {a.similarity:.2f} px"
            ax.set_title(title, fontsize=8)
    fig.suptitle("Table 1: results of increasing simplicity along the progressive optimization", fontsize=10)
    return fig


def plot_progression(
    runs: Sequence[Run], *, mark: Sequence[float] = _SIMPLICITY_FRACTIONS, panel_size: float = 3.6
) -> Figure:
    """|A^t| (left axis) and E^s(A^t) (right axis, with T dashed) against t, one panel per run; the levels at
    the fractions ``mark`` circled."""
    from matplotlib.ticker import MaxNLocator

    fig, axes = panel_grid(1, len(runs), panel_size, height_ratio=0.8)
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
    """The runs of a sweep over T (``sweep(paths, {"tolerance": [...]})``) by image, T increasing."""
    return {name: sorted(mine, key=_tolerance) for name, mine in by_image(runs).items()}


def _tolerance(run: Run) -> float:
    return float(run.final.tolerance)


def _at(runs: Sequence[Run], tolerance: float) -> Progression:
    for run in runs:
        if math.isclose(_tolerance(run), tolerance):
            return run.progression
    raise InvalidParameterError(f"no run with T = {tolerance} in the sweep {[_tolerance(r) for r in runs]}")


def _paper(paper: Mapping[float, float], t: float) -> float:
    return next((v for k, v in paper.items() if math.isclose(k, t)), math.nan)


def similarity_is_monotone(progression: Progression) -> bool:
    """Whether E^s never decreases from one level to the next."""
    return bool(np.all(np.diff(np.array(progression.similarities)) >= 0.0))


def final_level_index(progression: Progression, tolerance: float, *, rule: str = "first_exceedance") -> int:
    """The final level t a run with the smaller tolerance T' = ``tolerance`` (px) would reach, read off ``progression``.

    ``rule``: ``"first_exceedance"``, the level before the first t >= 1 whose E^s
    exceeds T' (where the loop of Sec. 5.2 stops); ``"last_within"``, the last
    level with E^s <= T' (the same only when E^s is monotone). 0 when even A^1 exceeds T'.
    """
    es = progression.similarities
    if rule == "first_exceedance":
        return next((t - 1 for t in range(1, len(es)) if es[t] > tolerance), len(es) - 1)
    if rule == "last_within":
        within = [t for t, e in enumerate(es) if e <= tolerance]
        return within[-1] if within else 0
    raise InvalidParameterError(f"rule must be 'first_exceedance' or 'last_within', got {rule!r}")


def tolerance_table(sweeps: Sequence[Run], *, paper: Mapping[float, float] | None = None) -> pd.DataFrame:
    """Per run of a sweep over T: the final |A|, E^s (px), iterations, why it stopped; the |A| both rules of
    :func:`final_level_index` read off the image's largest-T run; the paper's |A| (default :data:`PAPER_TABLE2`)."""
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
                    "paper |A|": _paper(paper, t),
                }
            )
    return pd.DataFrame(rows)


def monotonicity_table(sweeps: Sequence[Run]) -> pd.DataFrame:
    """Per image of a sweep over T: is E^s monotone along its largest-T run (how often and how much it
    decreases, px), and does each rule of :func:`final_level_index` give the final |A| of every per-T run?"""
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
    """Per image of a sweep over T: its segment graph, then the final result at each of ``tolerances`` (Table 2)."""
    paper = PAPER_TABLE2 if paper is None else paper
    groups = _tolerance_sweeps(sweeps)
    fig, axes = panel_grid(len(groups), 1 + len(tolerances), panel_size)
    for row, (name, mine) in zip(axes, groups.items(), strict=False):
        graph = mine[0].graph
        plot_segment_graph(graph, row[0], show_junctions=False, linewidth=1.0)
        row[0].set_title(f"{name}: |S| = {graph.n_segments}", fontsize=8)
        for ax, t in zip(row[1:], tolerances, strict=True):
            a = _at(mine, t).final
            plot_abstraction(a, ax, linewidth=_stroke(panel_size))
            ref = _paper(paper, t)
            ref_text = "" if math.isnan(ref) else f" (paper {ref:g})"
            ax.set_title(f"T = {t:g}: |A| = {len(a.arcs)}{ref_text}\n$E^s$ = {a.similarity:.2f} px", fontsize=8)
    fig.suptitle("Table 2: larger tolerance T, less similarity, fewer arcs", fontsize=10)
    return fig


def plot_tolerance_curve(
    sweeps: Sequence[Run], *, paper: Mapping[float, float] | None = None, panel_size: float = 3.6
) -> Figure:
    """The final |A| (left; the paper's as stars) and E^s (right; E^s = T dashed) against T, a line per image."""
    paper = PAPER_TABLE2 if paper is None else paper
    fig, axes = panel_grid(1, 2, panel_size, height_ratio=0.8)
    left, right = axes[0]
    groups = _tolerance_sweeps(sweeps)
    for i, (name, mine) in enumerate(groups.items()):
        color = GROUP_COLORS[i % len(GROUP_COLORS)]
        ts = [_tolerance(r) for r in mine]
        left.plot(ts, [len(r.final.arcs) for r in mine], marker="o", markersize=3, color=color, label=name)
        right.plot(ts, [r.final.similarity for r in mine], marker="o", markersize=3, color=color, label=name)
    known = [(t, v) for t, v in sorted(paper.items()) if not math.isnan(v)]
    if known:
        style = {"linestyle": "none", "marker": "*", "markersize": 12, "color": "black"}
        left.plot(*zip(*known, strict=True), **style, label="paper (its bird)")
    all_t = [_tolerance(r) for mine in groups.values() for r in mine]
    if all_t:
        lo, hi = min(all_t), max(all_t)
        right.plot([lo, hi], [lo, hi], linestyle="--", color="#808080", linewidth=1.0, label="$E^s$ = T")
    for ax, ylabel in ((left, "final |A|"), (right, "final $E^s$ (px)")):
        ax.set_xlabel("tolerance T (px)")
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8)
    fig.suptitle("Similarity constraint: the final arc count against the tolerance T", fontsize=10)
    return fig
