"""Timing (Table 3) and design exploration (Fig. 15, 16).

For ``09_timing`` (Table 3, Sec. 6.4: localized fitting x simplification, the
optimization alone timed; the stages of a full run; not byte-deterministic) and
``10_design_exploration`` (Fig. 15: a user's ladder exponents; Fig. 16: a lock
mask; the ladder bias).
"""

from __future__ import annotations

import math
import statistics
from collections import Counter
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ..constants import PHI, TOLERANCE
from ..errors import InvalidParameterError
from ..export.plotting import plot_abstraction, plot_segment_graph
from ..geometry.abstraction import Abstraction
from ..quality import detail_error
from . import Run, sweep, table
from .layout import frame_bounds, frame_window, panel_grid

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..pipeline import Result

# =========================================================================== Table 3
#: The paper's Table 3 (Python on an Intel i9 at 3.6 GHz, its fish of Fig. 1):
#: (localized, simplify) -> (seconds, as printed). No/No is a lower bound, ">= 2 hrs".
PAPER_TABLE3: dict[tuple[bool, bool], tuple[float, str]] = {
    (False, False): (7200.0, ">= 2 hrs"),
    (True, False): (257.47, "257.47"),
    (False, True): (338.87, "338.87"),
    (True, True): (65.37, "65.37"),
}

#: The four cells of Table 3, in the paper's row order: (localized, simplify).
CELLS: tuple[tuple[bool, bool], ...] = ((False, False), (True, False), (False, True), (True, True))
_YES_NO = {True: "Yes", False: "No"}

#: The cells of Table 3 as variants of a sweep: label -> the two accelerations of Sec. 5.4. Each
#: runs the paper's fit (``tangency=False``): the tangent joins (beyond the paper) add refits and
#: may keep a level before the loop's last, so the cells would not time the paper's algorithm.
TIMING_VARIANTS: dict[str, dict[str, bool]] = {
    f"localized {_YES_NO[loc]}, simplify {_YES_NO[simp]}": {"localized": loc, "simplify": simp, "tangency": False}
    for loc, simp in CELLS
}


def _cell(run: Run) -> tuple[bool, bool]:
    return bool(run.settings.get("localized", True)), bool(run.settings.get("simplify", True))


def timing_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Table 3 from ``sweep(examples, variants=TIMING_VARIANTS, repeats=...)``: per image and cell, our median
    time (s) and the paper's, each also as a ratio to the Yes/Yes cell (the paper's No/No: a lower bound).
    Not byte-deterministic."""
    median = {(r.name, _cell(r)): statistics.median(r.seconds) for r in runs}
    paper_base = PAPER_TABLE3[(True, True)][0]

    def paper_ratio(r: Run) -> str:
        seconds, text = PAPER_TABLE3[_cell(r)]
        return (">= " if text.startswith(">=") else "") + f"{seconds / paper_base:.2f}"

    return table(
        runs,
        {
            "image": lambda r: r.name,
            "localized": lambda r: _YES_NO[_cell(r)[0]],
            "simplify": lambda r: _YES_NO[_cell(r)[1]],
            "segments": lambda r: r.graph.n_segments,
            "initial arcs": lambda r: len(r.levels[0].arcs),
            "levels": lambda r: len(r.levels),
            "final arcs": lambda r: len(r.final.arcs),
            "final E^s (px)": lambda r: round(r.final.similarity, 3),
            "repeats": lambda r: len(r.seconds),
            "median (s)": lambda r: median[(r.name, _cell(r))],
            "min (s)": lambda r: min(r.seconds),
            "max (s)": lambda r: max(r.seconds),
            "ratio to Yes/Yes": lambda r: median[(r.name, _cell(r))] / median.get((r.name, (True, True)), math.nan),
            "paper (s)": lambda r: PAPER_TABLE3[_cell(r)][1],
            "paper ratio to Yes/Yes": paper_ratio,
        },
    )


def timing_reading(table3: pd.DataFrame) -> str:
    """What the run's Table 3 says, as Markdown sentences made from its numbers (:func:`timing_table`).

    For each image: No/No's time as a multiple of Yes/Yes (the paper's: at least 110x), which of
    the two middle cells is faster (in the paper, localized fitting alone, Yes/No), the initial arcs
    with and without the simplification and the merge loop's levels, and the spread of the four
    cells' final arcs and E^s.
    """
    paper_middle = "Yes/No" if PAPER_TABLE3[(True, False)][0] < PAPER_TABLE3[(False, True)][0] else "No/Yes"
    paper_floor = PAPER_TABLE3[(False, False)][0] / PAPER_TABLE3[(True, True)][0]
    sentences = []
    for image, rows in table3.groupby("image", sort=False):
        cell = {(r["localized"], r["simplify"]): r for _, r in rows.iterrows()}
        if len(cell) < len(CELLS):
            continue
        nn, yn, ny, _ = (cell[(_YES_NO[a], _YES_NO[b])] for a, b in CELLS)
        middle = "Yes/No" if yn["median (s)"] < ny["median (s)"] else "No/Yes"
        order = "the paper's order" if middle == paper_middle else "the reverse of the paper's order"
        sentences.append(
            f"**{image}**: No/No takes {nn['ratio to Yes/Yes']:.1f}x the Yes/Yes time (the paper: at least "
            f"{paper_floor:.0f}x); of the middle rows {middle} is the faster "
            f"({yn['ratio to Yes/Yes']:.1f}x and {ny['ratio to Yes/Yes']:.1f}x for Yes/No and No/Yes), "
            f"{order} (the paper: {paper_middle}). The simplification cuts $|A^0|$ from {nn['initial arcs']} to "
            f"{ny['initial arcs']} arcs and the merge loop's levels from {nn['levels']} to {ny['levels']}. The "
            f"four cells end at {rows['final arcs'].min()}-{rows['final arcs'].max()} arcs, $E^s$ "
            f"{rows['final E^s (px)'].min():.2f}-{rows['final E^s (px)'].max():.2f} px."
        )
    return "\n\n".join(sentences)


def _fmt_seconds(v: float) -> str:
    if not math.isfinite(v):
        return ""
    return f"{v / 3600:.3g} h" if v >= 3600 else f"{v:.3g} s" if v >= 0.1 else f"{1000 * v:.3g} ms"


def plot_timing(runs: Sequence[Run], *, figsize: tuple[float, float] = (12.0, 4.5)) -> Figure:
    """Table 3 as bars, log scale: seconds (left) and ratios to the Yes/Yes cell (right), the paper's hatched
    beside ours (one colour per image; its No/No bar is its lower bound, 2 hours)."""
    images = list(dict.fromkeys(r.name for r in runs))
    median = {(r.name, *_cell(r)): statistics.median(r.seconds) for r in runs}
    series = ["paper", *images]
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize, layout="constrained")
    ax_s, ax_r = fig.subplots(1, 2)
    x = np.arange(len(CELLS))
    width = 0.8 / len(series)
    for i, name in enumerate(series):
        offset = (i - (len(series) - 1) / 2) * width
        if name == "paper":
            secs = np.array([PAPER_TABLE3[c][0] for c in CELLS])
            ratios = secs / PAPER_TABLE3[(True, True)][0]
            style = {"color": "0.85", "edgecolor": "0.3", "hatch": "//", "label": "paper (i9 3.6 GHz, its fish)"}
        else:
            secs = np.array([median.get((name, *c), np.nan) for c in CELLS])
            ratios = secs / median.get((name, True, True), np.nan)
            style = {"color": f"C{i - 1}", "label": f"ours: {name}"}
        for ax, values, fmt in (
            (ax_s, secs, _fmt_seconds),
            (ax_r, ratios, lambda v: f"{v:.3g}\u00d7" if math.isfinite(v) else ""),
        ):
            bars = ax.bar(x + offset, values, width, **style)
            labels = [
                ("\u2265 " if name == "paper" and c == (False, False) else "") + fmt(v)
                for v, c in zip(values, CELLS, strict=True)
            ]
            # Upright labels would be wider than their bars and run into the neighbours'.
            ax.bar_label(bars, labels=labels, fontsize=7, padding=2, rotation=90)
    for ax, ylabel, title in (
        (ax_s, "time (s), log scale", "Table 3: progressive optimization time"),
        (ax_r, "time / time of Yes/Yes, log scale", "relative to localized + simplified"),
    ):
        ax.set_yscale("log")
        ax.set_xticks(x, [f"localized {_YES_NO[loc]}\nsimplify {_YES_NO[simp]}" for loc, simp in CELLS], fontsize=8)
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=10)
        ax.grid(axis="y", which="major", alpha=0.3)
        ax.margins(y=0.6)  # room above the tallest bar for its upright label
    ax_r.axhline(1.0, color="0.5", linewidth=0.8)
    ax_s.legend(fontsize=8, loc="upper right")
    return fig


#: The stages of :attr:`img2logo.Result.timings`, in pipeline order.
STAGES: tuple[str, ...] = ("feature_lines", "segment_graph", "simplification", "initial_fit", "loop")


def stage_table(results: Sequence[Result], names: Sequence[str] | None = None) -> pd.DataFrame:
    """Per full :func:`img2logo.abstract` run: seconds per stage of :data:`STAGES` (``Result.timings``),
    ``total``, ``arcs`` (|A|). Not byte-deterministic."""
    import pandas as pd

    names = list(names) if names is not None else [Path(str(r.params.get("source", "?"))).stem for r in results]
    rows = []
    for name, r in zip(names, results, strict=True):
        row: dict[str, Any] = {"image": name}
        row.update({s: float(r.timings.get(s, 0.0)) for s in STAGES})
        row["total"] = sum(row[s] for s in STAGES)
        row["arcs"] = len(r.final.arcs)
        rows.append(row)
    return pd.DataFrame(rows)


def plot_stages(table: pd.DataFrame, *, figsize: tuple[float, float] = (8.0, 2.8)) -> Figure:
    """The per-stage breakdown of :func:`stage_table` as stacked horizontal bars (s)."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(figsize[0], max(figsize[1], 1.2 + 0.6 * len(table))), layout="constrained")
    ax = fig.subplots()
    y = np.arange(len(table))
    left = np.zeros(len(table))
    for i, stage in enumerate(STAGES):
        values = table[stage].to_numpy(dtype=float)
        ax.barh(y, values, left=left, color=f"C{i}", label=stage.replace("_", " "))
        left += values
    for yi, total in zip(y, left, strict=True):
        ax.text(total, yi, f"  {total:.2f} s", va="center", fontsize=8)
    ax.set_yticks(y, list(table["image"]))
    ax.invert_yaxis()
    ax.set_xlabel("time (s)")
    ax.set_xlim(0, 1.2 * max(float(left.max()), 1e-3))
    ax.set_title("one full abstract() run, per stage", fontsize=10)
    ax.legend(fontsize=8, ncols=len(STAGES), loc="upper center", bbox_to_anchor=(0.5, -0.3))
    return fig


# =========================================================================== Fig. 15
def _k_counts(abstraction: Abstraction) -> Counter[int]:
    """How many arcs use each ladder exponent k (straight lines aside)."""
    return Counter(a.circle.k for a in abstraction.arcs if a.circle.k is not None)


def most_used_exponents(abstraction: Abstraction, n: int = 3) -> tuple[int, ...]:
    """The ``n`` ladder exponents k used by the most arcs, sorted (ties: longer arcs in total, then the larger k)."""
    if int(n) < 1:
        raise InvalidParameterError(f"n must be >= 1, got {n!r}")
    count = _k_counts(abstraction)
    length: Counter[int] = Counter()
    for arc in abstraction.arcs:
        if arc.circle.k is not None:
            length[arc.circle.k] += arc.length
    ranked = sorted(count, key=lambda k: (-count[k], -length[k], -k))
    return tuple(sorted(ranked[: int(n)]))


def compare_exponents(
    example: Run, *, tolerance: float = TOLERANCE, exponents: Sequence[int] | None = None, n_exponents: int = 3
) -> list[Run]:
    """The run automated (variant ``"automated"``), then restricted to a few ladder exponents with its bias
    (``"user-specified"``; Sec. 7, Fig. 15).

    Parameters
    ----------
    example : Run
        The input segment graph (:func:`img2logo.experiments.preprocess`).
    tolerance : float
        T, px, for both runs.
    exponents : sequence of int, optional
        The user's k; default: the ``n_exponents`` most used of the automated result (:func:`most_used_exponents`).
    """
    (auto,) = sweep([example], variants={"automated": {}}, tolerance=tolerance)
    chosen = tuple(sorted({int(k) for k in exponents})) if exponents is not None else None
    if chosen is None:
        chosen = most_used_exponents(auto.final, n_exponents)
    user = {"user-specified": {"bias": auto.bias, "exponents": chosen}}
    return [auto, *sweep([example], variants=user, tolerance=tolerance)]


def exponent_table(comparison: Sequence[Run]) -> pd.DataFrame:
    """Per ladder exponent k of :func:`compare_exponents`: its radius (px), whether the user allowed it, the arcs
    using it in each run (Fig. 15)."""
    auto, user = comparison
    a, u, allowed = _k_counts(auto.final), _k_counts(user.final), tuple(user.settings["exponents"])
    return table(
        sorted(set(a) | set(u) | set(allowed)),
        {
            "k": lambda k: k,
            "radius (px)": lambda k: round(PHI ** (k + auto.bias), 3),
            "allowed in user setting": lambda k: k in allowed,
            "arcs, automated": lambda k: a.get(k, 0),
            "arcs, user-specified": lambda k: u.get(k, 0),
        },
    )


def comparison_table(comparison: Sequence[Run]) -> pd.DataFrame:
    """Fig. 15 in numbers (:func:`compare_exponents`): per setting, the allowed and used k, |A|, E^s, levels, bias."""
    return table(
        comparison,
        {
            "setting": lambda r: r.variant,
            "allowed k": lambda r: " ".join(map(str, r.settings["exponents"])) if "exponents" in r.settings else "all",
            "used k": lambda r: " ".join(map(str, sorted(_k_counts(r.final)))),
            "distinct radii": lambda r: len(_k_counts(r.final)),
            "arcs": lambda r: len(r.final.arcs),
            "E^s (px)": lambda r: round(r.final.similarity, 3),
            "levels": lambda r: len(r.levels),
            "bias": lambda r: round(r.bias, 4),
        },
    )


def _ladder_inset(ax: Axes, used: Counter[int], bias: float, ks: Sequence[int], *, margin: float) -> Axes:
    """The ladder radii ``ks`` as nested circles tangent at the bottom, ``used`` ones red.

    Drawn in the right ``margin`` (a fraction of the axes width) that the caller
    left free next to the drawing, with the arc count of every used k above it.
    """
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    side = margin * abs(x1 - x0) / abs(y1 - y0)  # a square inset (equal aspect): its height in axes fraction
    inset = ax.inset_axes((1.0 - margin, 0.02, margin, side))
    big = PHI ** (max(ks) + bias)
    t = np.linspace(0.0, 2.0 * math.pi, 200)
    for k in ks:
        r = PHI ** (k + bias) / big
        on = k in used
        inset.plot(
            r * np.cos(t),
            r * (1.0 + np.sin(t)) - 1.0,
            color="#d62728" if on else "0.75",
            linewidth=1.2 if on else 0.6,
            zorder=2 if on else 1,
        )
    inset.set_aspect("equal")
    inset.set_xlim(-1.05, 1.05)
    inset.set_ylim(-1.05, 1.05)
    inset.set_xticks([])
    inset.set_yticks([])
    for spine in inset.spines.values():
        spine.set_color("0.6")
    lines = ["k  arcs", *(f"{k:<3d} {used[k]}" for k in sorted(used))]
    ax.text(
        1.0 - margin / 2,
        0.04 + side,
        "\n".join(lines),
        transform=ax.transAxes,
        ha="center",
        va="bottom",
        fontsize=7,
        family="monospace",
        color="#d62728",
    )
    return inset


def plot_exponent_comparison(comparison: Sequence[Run], *, panel_size: float = 4.0) -> Figure:
    """Fig. 15: (a) line segments, (b) automated radii, (c) user-specified radii.

    Beside each result, the golden ladder (scaled down, nested circles from the
    smallest to the largest k either result uses) with its radii in red, and
    the number of arcs per exponent k.
    """
    from matplotlib.figure import Figure

    example, user_run = comparison
    margin = 0.28  # fraction of a result panel kept for the ladder
    fig = Figure(figsize=(panel_size * (1 + 2 / (1 - margin)), panel_size + 0.5))
    grid = fig.add_gridspec(1, 3, width_ratios=(1 - margin, 1, 1), left=0.01, right=0.99, bottom=0.02, top=0.86)
    axes = [fig.add_subplot(grid[0, i]) for i in range(3)]
    plot_segment_graph(example.graph, axes[0], show_junctions=False)
    axes[0].set_title(f"(a) line segments of {example.name}\n|S| = {example.graph.n_segments}", fontsize=9)
    used = {"auto": _k_counts(example.final), "user": _k_counts(user_run.final)}
    ks = sorted(set(used["auto"]) | set(used["user"]))
    ks = list(range(ks[0], ks[-1] + 1))
    allowed = ", ".join(map(str, user_run.settings["exponents"]))
    for ax, key, prog, title in (
        (axes[1], "auto", example.progression, "(b) automated setting"),
        (axes[2], "user", user_run.progression, f"(c) user-specified k \u2208 {{{allowed}}}"),
    ):
        a = prog.final
        plot_abstraction(a, ax)
        ax.set_xlim(0.0, a.width / (1 - margin))
        ax.set_title(
            f"{title}\n|A| = {len(a.arcs)}, {len(used[key])} radii, E^s = {a.similarity:.2f} px",
            fontsize=9,
        )
        _ladder_inset(ax, used[key], prog.bias, ks, margin=margin)
    return fig


# =========================================================================== Fig. 16
def region_mask(
    size: tuple[int, int] | np.ndarray | Any,
    center: Sequence[float],
    radius: float,
    *,
    form: str = "disc",
) -> np.ndarray:
    """A lock mask (Sec. 7, Fig. 16): the pixels within ``radius`` of ``center``.

    Parameters
    ----------
    size : (height, width), an image array, or an object with ``width`` and ``height``
    center : (x, y)
        Centre of the region, px (pixel (i, j) has its centre at (j + 0.5, i + 0.5)).
    radius : float
        Radius of the disc, or half the side of the square, px.
    form : {"disc", "square"}

    Returns
    -------
    ndarray of bool, shape (height, width)
    """
    if hasattr(size, "width") and hasattr(size, "height"):
        height, width = int(size.height), int(size.width)
    elif isinstance(size, np.ndarray):
        height, width = size.shape[:2]
    else:
        height, width = (int(v) for v in size)
    if form not in ("disc", "square"):
        raise InvalidParameterError(f"form must be 'disc' or 'square', got {form!r}")
    if not (math.isfinite(float(radius)) and float(radius) > 0):
        raise InvalidParameterError(f"radius must be finite and > 0, got {radius!r}")
    cx, cy = (float(v) for v in center)
    y, x = np.mgrid[0:height, 0:width] + 0.5
    if form == "disc":
        return (x - cx) ** 2 + (y - cy) ** 2 <= float(radius) ** 2
    return (np.abs(x - cx) <= radius) & (np.abs(y - cy) <= radius)


#: The two runs of the Fig. 16 search, without and with the lock mask (pass ``lock_mask`` to the second).
LOCK_VARIANTS = ("no lock", "lock")


def lock_variants(mask: np.ndarray) -> dict[str, dict[str, Any]]:
    """The variants of the Fig. 16 search: without and with ``mask`` locked (a sweep over T runs both)."""
    return {LOCK_VARIANTS[0]: {}, LOCK_VARIANTS[1]: {"lock_mask": mask}}


class _LockPair(NamedTuple):
    """One T of a lock search: the runs without and with the lock and their detail errors
    (:func:`img2logo.quality.detail_error`, px: a detail is lost when it grows beyond a pixel or two)."""

    t: float
    free: Run
    locked: Run
    error_free: float
    error_locked: float


def _lock_pairs(runs: Sequence[Run], mask: np.ndarray) -> list[_LockPair]:
    out = []
    for free, locked in zip(runs[::2], runs[1::2], strict=True):
        if (free.variant, locked.variant) != LOCK_VARIANTS:
            raise InvalidParameterError(f"expected runs of the variants {LOCK_VARIANTS} in turn (lock_variants)")
        errors = (detail_error(free.final, free.graph, mask), detail_error(locked.final, locked.graph, mask))
        out.append(_LockPair(float(free.final.tolerance), free, locked, *errors))
    return out


def lock_table(runs: Sequence[Run], mask: np.ndarray, threshold: float) -> pd.DataFrame:
    """A lock search (``sweep([ex], {"tolerance": ...}, lock_variants(mask))``): per T and variant, |A|, E^s and
    the detail error (px); ``lost``: the detail error exceeds ``threshold`` px."""
    return table(
        _lock_pairs(runs, mask),
        {
            "T": lambda p: p.t,
            "arcs, no lock": lambda p: len(p.free.final.arcs),
            "E^s, no lock (px)": lambda p: round(p.free.final.similarity, 3),
            "detail error, no lock (px)": lambda p: round(p.error_free, 3),
            "lost without lock": lambda p: bool(p.error_free > threshold),
            "locked segments": lambda p: int(p.locked.final.params.get("locked_segments", 0)),
            "arcs, lock": lambda p: len(p.locked.final.arcs),
            "E^s, lock (px)": lambda p: round(p.locked.final.similarity, 3),
            "detail error, lock (px)": lambda p: round(p.error_locked, 3),
            "lost with lock": lambda p: bool(p.error_locked > threshold),
        },
    )


def first_lost(runs: Sequence[Run], mask: np.ndarray, threshold: float) -> float:
    """The smallest T of a lock search where the detail is lost without the lock and kept with it.

    Falls back to the T where the detail errors differ the most when no T qualifies.
    """
    pairs = sorted(_lock_pairs(runs, mask), key=lambda p: p.t)
    if not pairs:
        raise InvalidParameterError("no runs to choose from")
    for t, _, _, e_free, e_locked in pairs:
        if e_free > threshold >= e_locked:
            return t
    return max(pairs, key=lambda p: p.error_free - p.error_locked).t


def _crop(ax: Axes, graph: Any) -> None:
    """Show only the (padded) bounding box of the graph's segments."""
    frame_bounds(ax, np.vstack(list(graph.segments)), graph.width, graph.height)


def _zoom(ax: Axes, center: Sequence[float], radius: float) -> None:
    """Show the square of side 3 ``radius`` around ``center``, framed, with the region dashed."""
    from matplotlib.patches import Circle as CirclePatch

    ax.add_patch(CirclePatch(tuple(center), radius, fill=False, edgecolor="#1f77b4", linestyle="--", linewidth=0.8))
    pad = 1.5 * radius
    window = (center[0] - pad, center[1] - pad, center[0] + pad, center[1] + pad)
    frame_window(ax, window, color="#1f77b4", equal=False)


def plot_lock_comparison(
    runs: Sequence[Run],
    mask: np.ndarray,
    tolerance: float,
    *,
    center: Sequence[float],
    radius: float,
    panel_size: float = 3.6,
) -> Figure:
    """Fig. 16: (a) the user's region over the segments, (b) result without, (c) with the lock.

    ``runs`` are a lock search (:func:`lock_table`), shown at T = ``tolerance``
    (:func:`first_lost`). The bottom row zooms into the region (dashed),
    junctions marked on the results.
    """
    t, free, locked, e_free, e_locked = next(p for p in _lock_pairs(runs, mask) if math.isclose(p.t, tolerance))
    example = free
    fig, axes = panel_grid(2, 3, panel_size, extra_height=0.6, height_ratios=(0.8, 1.0))
    rgb = example.image.rgb
    for ax in axes[:, 0]:
        plot_segment_graph(example.graph, ax, image=rgb, show_junctions=ax is axes[1, 0])
    overlay = np.zeros((*mask.shape, 4))
    overlay[mask] = (0.12, 0.47, 0.71, 0.3)
    axes[0, 0].imshow(overlay, extent=(0, mask.shape[1], mask.shape[0], 0), zorder=4)
    n_locked = int(locked.final.params.get("locked_segments", 0))
    axes[0, 0].set_title(f"(a) locked region of {example.name}\n{n_locked} segments locked", fontsize=9)
    for col, prog, err, title in (
        (1, free.progression, e_free, "(b) without the lock"),
        (2, locked.progression, e_locked, "(c) with the lock"),
    ):
        for ax in axes[:, col]:
            plot_abstraction(prog.final, ax, image=rgb, show_junctions=ax is axes[1, col])
        axes[0, col].set_title(
            f"{title}, T = {t:g}: |A| = {len(prog.final.arcs)}\n"
            f"E^s = {prog.final.similarity:.2f} px, detail error = {err:.2f} px",
            fontsize=9,
        )
    for ax in axes[0]:
        _crop(ax, example.graph)
    for ax in axes[1]:
        _zoom(ax, center, radius)
    axes[1, 0].set_title("the region: segments and nodes", fontsize=9)
    axes[1, 1].set_title("zoom: the detail is merged away", fontsize=9)
    axes[1, 2].set_title("zoom: the locked segments are kept", fontsize=9)
    return fig


def bias_table(runs: Sequence[Run]) -> pd.DataFrame:
    """Per bias of a sweep over it (``sweep([ex], {"bias": [None, 0.25, ...]})``): sigma, |A|, radii, E^s, levels."""
    return table(
        runs,
        {
            "bias": lambda r: "auto (Eqn. 14)" if r.settings["bias"] is None else f"{r.settings['bias']:g}",
            "sigma": lambda r: round(r.bias, 4),
            "arcs": lambda r: len(r.final.arcs),
            "distinct radii": lambda r: len({a.circle.k for a in r.final.arcs}),
            "E^s (px)": lambda r: round(r.final.similarity, 3),
            "levels": lambda r: len(r.levels),
        },
    )


def plot_bias_sweep(runs: Sequence[Run], *, panel_size: float = 3.0) -> Figure:
    """One panel per bias of :func:`bias_table`'s sweep: the result with its golden circles (the Fig. 8 look)."""
    fig, axes = panel_grid(1, len(runs), panel_size, extra_height=0.5)
    for i, (ax, r) in enumerate(zip(axes[0], runs, strict=True)):
        p, b = r.progression, r.settings["bias"]
        plot_abstraction(p.final, ax, show_circles=True)
        label = f"auto \u03c3 = {p.bias:.3f} (Eqn. 14)" if b is None else f"\u03c3 = {p.bias:g}"
        prefix = f"{r.name}: " if i == 0 else ""
        ax.set_title(f"{prefix}{label}\n|A| = {len(p.final.arcs)}, E^s = {p.final.similarity:.2f} px", fontsize=9)
    return fig
