"""Timing (Table 3), design exploration (Fig. 15, 16) and the level explorer.

For ``09_timing`` (Table 3, Sec. 6.4: localized fitting x simplification, the
optimization alone timed; the stages of a full run; not byte-deterministic),
``10_design_exploration`` (Fig. 15: a user's ladder exponents; Fig. 16: a lock
mask; the ladder bias) and ``11_explore_levels`` (:class:`LevelExplorer`: its
callbacks work on plain values, tested without a browser; ipywidgets is
imported only when the widgets are built).
"""

from __future__ import annotations

import dataclasses
import io
import math
import os
import statistics
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np

from ..constants import PHI, RDP_TOLERANCE, TOLERANCE
from ..errors import InvalidParameterError
from ..geometry import Abstraction
from ..plotting import frame_bounds, frame_window, panel_grid, plot_abstraction, plot_segment_graph
from ..quality import detail_error
from . import Run, sweep, table
from .paths import kit_module

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from ..pipeline import Result

#: Longest side of the level explorer's drawing on screen, CSS px: beside its controls (about 400 px)
#: it fits a 1440 x 900 laptop screen in JupyterLab, and it is the size a logo is judged at.
EXPLORER_SIZE = 440


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

#: The cells of Table 3 as variants of a sweep: label -> the two accelerations of Sec. 5.4.
TIMING_VARIANTS: dict[str, dict[str, bool]] = {
    f"localized {_YES_NO[loc]}, simplify {_YES_NO[simp]}": {"localized": loc, "simplify": simp} for loc, simp in CELLS
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
            ax.bar_label(bars, labels=labels, fontsize=7, padding=2)
    for ax, ylabel, title in (
        (ax_s, "time (s), log scale", "Table 3: progressive optimization time"),
        (ax_r, "time / time of Yes/Yes, log scale", "relative to localized + simplified"),
    ):
        ax.set_yscale("log")
        ax.set_xticks(x, [f"localized {_YES_NO[loc]}\nsimplify {_YES_NO[simp]}" for loc, simp in CELLS], fontsize=8)
        ax.set_ylabel(ylabel)
        ax.set_title(title, fontsize=10)
        ax.grid(axis="y", which="major", alpha=0.3)
        ax.margins(y=0.25)
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


# =========================================================================== level explorer
def levels_within(result: Result, tolerance: float | None = None) -> tuple[Abstraction, ...]:
    """The levels a run with T = ``tolerance`` (px, at most the run's T; None: all) gives, read off ``result``.

    The merges do not depend on T: a run stops before the first level whose E^s
    exceeds T (Sec. 5.2, step 2; :func:`~img2logo.experiments.results.final_level_index`,
    checked against runs made per T by notebook 04, ``monotonicity.csv``).

    Raises
    ------
    InvalidParameterError
        ``tolerance`` above the run's T: its levels cannot tell a larger T's.
    """
    from .results import final_level_index

    levels = result.levels
    run_tolerance = levels[0].tolerance
    if tolerance is None:
        return levels
    if not tolerance > 0 or tolerance > run_tolerance:
        raise InvalidParameterError(f"tolerance must be in (0, {run_tolerance:g}] px for this run, got {tolerance}")
    return levels[: final_level_index(result.progression, tolerance) + 1]


def level_title(result: Result, t: int, name: str | None = None, *, tolerance: float | None = None) -> str:
    """The title of level ``t``: the level, |A|, E^s and T (of :func:`levels_within` ``tolerance``)."""
    levels = levels_within(result, tolerance)
    a = levels[t]
    prefix = f"{name}: " if name else ""
    shown = a.tolerance if tolerance is None else tolerance
    return (
        f"{prefix}level t = {a.level} of {len(levels) - 1}, |A| = {len(a.arcs)}, "
        f"E^s = {a.similarity:.2f} px (T = {shown:g})"
    )


def levels_table(result: Result) -> pd.DataFrame:
    """Per level t of a run: |A^t|, distinct radii and E^s (px), the numbers behind the slider."""
    return table(
        result.levels,
        {
            "t": lambda a: a.level,
            "arcs": lambda a: len(a.arcs),
            "distinct radii": lambda a: len({arc.circle.k for arc in a.arcs}),
            "E^s (px)": lambda a: round(a.similarity, 3),
        },
    )


def plot_level_strip(
    result: Result, levels: Sequence[int] | int = 4, *, name: str | None = None, panel_size: float = 3.0
) -> Figure:
    """A row of levels of one run, arcs over the faded input (a static view of the explorer).

    ``levels`` is a list of t (negative counts from the end) or a number of
    levels spread evenly from A^0 to the final one.
    """
    n_levels = len(result.levels)
    if isinstance(levels, int):
        ts = sorted({round(float(v)) for v in np.linspace(0, n_levels - 1, max(1, min(levels, n_levels)))})
    else:
        ts = [t % n_levels for t in levels]
    fig, axes = panel_grid(1, len(ts), panel_size, extra_height=0.5)
    for ax, t in zip(axes[0], ts, strict=True):
        a = result.level(t)
        plot_abstraction(a, ax, image=result.image.rgb)
        _crop(ax, result.graph)
        ax.set_title(f"t = {t}: |A| = {len(a.arcs)}, E^s = {a.similarity:.2f} px", fontsize=9)
    if name:
        fig.suptitle(f"{name}: levels of one run (T = {result.final.tolerance:g})", fontsize=10)
    return fig


@dataclass(frozen=True)
class ExplorerSettings:
    """The inputs of one :class:`LevelExplorer` run.

    Attributes
    ----------
    image : str
        A file name in ``data/`` or a path.
    tolerance : float
        T, px.
    bias : float or None
        The ladder bias sigma; None: automatic (Eqn. 14).
    rdp_tolerance : float
        Ramer-Douglas-Peucker tolerance, px.
    kind : str
        ``"auto"``, ``"photo"``, ``"clipart"`` or ``"drawing"``.
    symmetry : str
        ``"none"``, ``"auto"``, ``"vertical"``, ``"horizontal"`` or an angle in
        degrees: a mirror-symmetric logo (:mod:`img2logo.symmetry`).
    """

    image: str = "clipart-fish.png"
    tolerance: float = TOLERANCE
    bias: float | None = None
    rdp_tolerance: float = RDP_TOLERANCE
    kind: str = "auto"
    symmetry: str = "none"


class LevelExplorer:
    """Browse the levels A^0 ... A^final of a run, and re-run with other settings.

    The state and the callbacks work on plain values, so they run (and are
    tested) without a browser; :meth:`widget` wraps them in ipywidgets: the
    drawing at a fixed size beside its controls, a level slider (instant
    redraw: every level is precomputed), T, the bias (with an "auto" box), the
    RDP tolerance, the image and its kind, and a Run button with a progress bar
    (E^s filling towards T) fed by :func:`img2logo.abstract`'s progress callback.

    Changing T is instant up to the largest T run so far with the same other
    settings: that run holds the levels of every smaller T
    (:func:`levels_within`); a larger T runs again, with the progress bar.

    Parameters
    ----------
    settings : ExplorerSettings, optional
        The first run's inputs; keyword arguments override its fields.
    result : Result, optional
        A precomputed run for ``settings``; computed now when None.
    size : int
        Longest side of the drawing on screen, CSS px.
    dpi : float
        Resolution of the drawing's PNG; ``2 * 72`` pixels per inch of the
        figure is twice the screen size, crisp on high-density screens.

    Attributes
    ----------
    settings : ExplorerSettings
        The inputs of the levels shown (``settings.tolerance`` is the T shown).
    result : Result
        The run holding them: the largest T run so far with these settings.
    levels : tuple of Abstraction
        The levels of T (:func:`levels_within`); ``level`` is the one shown, drawn
        in ``figure`` (its ``title`` shown by the widget).
    progress_text : str
        The last progress message of a run.
    controls : dict
        The widgets by name, once :meth:`widget` built them (else empty).
    """

    def __init__(
        self,
        settings: ExplorerSettings | None = None,
        *,
        result: Result | None = None,
        size: int = EXPLORER_SIZE,
        dpi: float = 144.0,
        **overrides: Any,
    ) -> None:
        from matplotlib.figure import Figure

        self.settings = dataclasses.replace(settings or ExplorerSettings(), **overrides)
        self.dpi = float(dpi)
        self.size = int(size)
        self.controls: dict[str, Any] = {}
        self.progress_text = ""
        self.level = 0
        self.title = ""
        self._syncing = False
        self.result = result if result is not None else self._compute(self.settings)
        self.levels = levels_within(self.result, self.settings.tolerance)
        height, width = self.result.image.rgb.shape[:2]
        scale = self.size / max(height, width)
        self.figure = Figure(figsize=(width * scale / 72.0, height * scale / 72.0))
        self._ax = self.figure.add_axes((0.0, 0.0, 1.0, 1.0))
        self.on_level_change(len(self.levels) - 1)

    # ------------------------------------------------------------------ plain callbacks
    @property
    def n_levels(self) -> int:
        """Number of levels shown (those of T)."""
        return len(self.levels)

    @property
    def name(self) -> str:
        """The image's name."""
        return Path(self.settings.image).stem

    @property
    def title_html(self) -> str:
        """:attr:`title` as HTML, with E<sup>s</sup> and |<i>A</i>| set as in the paper."""
        import html

        return "<b>" + html.escape(self.title).replace("E^s", "E<sup>s</sup>").replace("|A|", "|<i>A</i>|") + "</b>"

    @property
    def screen_size(self) -> tuple[int, int]:
        """Width and height of the drawing on screen, CSS px."""
        w, h = self.figure.get_size_inches() * 72.0
        return round(w), round(h)

    def on_level_change(self, t: int) -> Figure:
        """Show level ``t`` (negative counts from the end): redraw the figure and title."""
        from ..plotting import plot_abstraction

        t = int(t)
        if not -self.n_levels <= t < self.n_levels:
            raise InvalidParameterError(f"level must be in [0, {self.n_levels - 1}], got {t}")
        self.level = t % self.n_levels
        self.title = level_title(self.result, self.level, self.name, tolerance=self.settings.tolerance)
        self._ax.clear()
        plot_abstraction(self.levels[self.level], self._ax, image=self.result.image.rgb)
        self._ax.set_axis_off()
        self._sync_widgets()
        return self.figure

    def on_tolerance_change(self, tolerance: float) -> bool:
        """Show the result of T = ``tolerance``: at once when the run holds it, else run again.

        Returns True when it needed a new run.
        """
        tolerance = float(tolerance)
        if 0 < tolerance <= self.result.levels[0].tolerance:
            self.settings = dataclasses.replace(self.settings, tolerance=tolerance)
            self.levels = levels_within(self.result, tolerance)
            self.on_level_change(self.n_levels - 1)
            return False
        self.on_run(tolerance=tolerance)
        return True

    def on_run(self, **changes: Any) -> Result:
        """Re-run :func:`img2logo.abstract` with ``changes`` to the settings; show its final level.

        ``changes`` are fields of :class:`ExplorerSettings` (``bias=None`` is automatic).
        """
        unknown = set(changes) - {f.name for f in dataclasses.fields(ExplorerSettings)}
        if unknown:
            raise InvalidParameterError(f"unknown settings {sorted(unknown)}")
        settings = dataclasses.replace(self.settings, **changes)
        self.result = self._compute(settings)
        self.settings = settings
        self.levels = self.result.levels
        self.on_level_change(self.n_levels - 1)
        return self.result

    def on_progress(self, t: int, n_arcs: int, similarity: float) -> None:
        """The progress callback of a run: level t reached with ``n_arcs`` arcs and E^s (px).

        The bar fills with E^s towards T, as the terminal bar of :func:`img2logo.abstract`
        does: the loop stops when E^s would exceed T, so the number of merges is
        not known in advance.
        """
        self.progress_text = f"level {t}: |A| = {n_arcs}, E^s = {similarity:.2f} px"
        bar = self.controls.get("progress")
        if bar is not None:
            bar.value = min(float(similarity), bar.max)
            self.controls["status"].value = self.progress_text

    def png(self) -> bytes:
        """The current drawing as PNG bytes, at :attr:`dpi`."""
        buf = io.BytesIO()
        self.figure.savefig(buf, format="png", dpi=self.dpi, facecolor="white", metadata={"Software": None})
        return buf.getvalue()

    def _compute(self, settings: ExplorerSettings) -> Result:
        from ..pipeline import abstract
        from . import data_path, load_example

        image = settings.image
        path = Path(image) if os.sep in image or Path(image).is_file() else data_path(image)
        self.progress_text = "running"
        bar = self.controls.get("progress")
        if bar is not None:
            bar.bar_style = ""
            bar.max = float(settings.tolerance)
            bar.value = 0.0
            self.controls["status"].value = "running"
        result = abstract(
            load_example(path),
            tolerance=settings.tolerance,
            kind=settings.kind,
            rdp_tolerance=settings.rdp_tolerance,
            bias=settings.bias,
            symmetry=settings.symmetry,
            progress=self.on_progress,
        )
        self.progress_text = (
            f"done: {len(result.levels)} levels, |A| = {len(result.final.arcs)}, "
            f"{sum(result.timings.values()):.2f} s ({result.progression.stopped_because})"
        )
        if bar is not None:
            bar.value = min(float(result.final.similarity), bar.max)
            bar.bar_style = "success"
            self.controls["status"].value = self.progress_text
        return result

    # ------------------------------------------------------------------ widgets
    def widget(self) -> Any:
        """The ipywidgets interface (built once): the drawing, and beside it the controls.

        The drawing has a fixed size (:attr:`screen_size`; the PNG has twice its
        pixels), so it stays crisp and the whole fits a laptop screen.
        """
        w = kit_module("ipywidgets")

        from . import example_images

        if "box" in self.controls:
            return self.controls["box"]
        s = self.settings
        images = [p.name for p in example_images()]
        if s.image not in images:
            images.append(s.image)
        c = self.controls
        style = {"description_width": "70px"}
        wide = w.Layout(width="360px")

        def slider(kind: Any, description: str, layout: Any = wide, **kwargs: Any) -> Any:
            return kind(description=description, style=style, layout=layout, **kwargs)

        c["level"] = slider(w.IntSlider, "level t", value=self.level, min=0, max=self.n_levels - 1)
        c["tolerance"] = slider(
            w.FloatSlider, "T (px)", value=s.tolerance, min=0.5, max=30.0, step=0.5, continuous_update=False
        )
        c["image"] = slider(w.Dropdown, "image", options=images, value=s.image)
        c["kind"] = slider(w.Dropdown, "kind", options=["auto", "photo", "clipart", "drawing"], value=s.kind)
        symmetries = list(dict.fromkeys(["none", "auto", "vertical", "horizontal", s.symmetry]))
        c["symmetry"] = slider(w.Dropdown, "symmetry", options=symmetries, value=s.symmetry)
        c["rdp_tolerance"] = slider(
            w.FloatSlider, "RDP (px)", value=s.rdp_tolerance, min=0.5, max=8.0, step=0.25, continuous_update=False
        )
        c["bias"] = slider(
            w.FloatSlider,
            "bias \u03c3",
            w.Layout(width="250px"),
            value=self.result.bias if s.bias is None else s.bias,
            min=0.0,
            max=0.99,
            step=0.01,
            disabled=s.bias is None,
            continuous_update=False,
        )
        c["bias_auto"] = w.Checkbox(
            value=s.bias is None, description="auto", indent=False, layout=w.Layout(width="100px")
        )
        c["run"] = w.Button(description="Run", button_style="primary", icon="play", layout=w.Layout(width="90px"))
        c["progress"] = slider(
            w.FloatProgress,
            "E\u02e2 \u2192 T",
            w.Layout(width="260px"),
            value=min(self.result.final.similarity, s.tolerance),
            min=0.0,
            max=s.tolerance,
        )
        c["status"] = w.Label(value=self.progress_text, layout=wide)
        c["title"] = w.HTML(value=self.title_html)
        width, height = self.screen_size
        c["drawing"] = w.Image(
            value=self.png(),
            format="png",
            layout=w.Layout(width=f"{width}px", height=f"{height}px", flex="0 0 auto", object_fit="contain"),
        )
        c["level"].observe(self._level_widget_changed, names="value")
        c["tolerance"].observe(self._tolerance_widget_changed, names="value")
        c["bias_auto"].observe(self._bias_auto_changed, names="value")
        c["run"].on_click(self._run_clicked)
        note = w.HTML(
            value="<small>T up to the largest T run so far is instant; a larger T, or new image, kind, "
            "symmetry, RDP or bias settings, run again (Run).</small>",
            layout=wide,
        )
        controls = w.VBox(
            [
                c["level"],
                c["tolerance"],
                c["image"],
                c["kind"],
                c["symmetry"],
                c["rdp_tolerance"],
                w.HBox([c["bias"], c["bias_auto"]]),
                w.HBox([c["run"], c["progress"]]),
                c["status"],
                note,
            ],
            layout=w.Layout(flex="0 0 auto", padding="0 0 0 12px"),
        )
        c["box"] = w.VBox([c["title"], w.HBox([c["drawing"], controls], layout=w.Layout(align_items="flex-start"))])
        return c["box"]

    def display(self) -> None:
        """Show :meth:`widget` in the notebook."""
        from IPython.display import display

        display(self.widget())

    def widget_settings(self) -> ExplorerSettings:
        """The settings the widgets hold now."""
        c = self.controls
        if not c:
            return self.settings
        return ExplorerSettings(
            image=c["image"].value,
            tolerance=float(c["tolerance"].value),
            bias=None if c["bias_auto"].value else float(c["bias"].value),
            rdp_tolerance=float(c["rdp_tolerance"].value),
            kind=c["kind"].value,
            symmetry=c["symmetry"].value,
        )

    def _level_widget_changed(self, change: dict[str, Any]) -> None:
        if not self._syncing:
            self.on_level_change(change["new"])

    def _tolerance_widget_changed(self, change: dict[str, Any]) -> None:
        if not self._syncing:
            self._busy(lambda: self.on_tolerance_change(change["new"]))

    def _bias_auto_changed(self, change: dict[str, Any]) -> None:
        self.controls["bias"].disabled = bool(change["new"])

    def _run_clicked(self, _button: Any = None) -> None:
        self._busy(lambda: self.on_run(**dataclasses.asdict(self.widget_settings())))

    def _busy(self, action: Any) -> None:
        """Run ``action`` with the Run button disabled."""
        button = self.controls.get("run")
        if button is not None:
            button.disabled = True
        try:
            action()
        finally:
            if button is not None:
                button.disabled = False

    def _sync_widgets(self) -> None:
        """Push the state (level, its range, T, title, drawing) to the widgets, without echo."""
        c = self.controls
        if not c:
            return
        self._syncing = True
        try:
            c["level"].max = self.n_levels - 1
            c["level"].value = self.level
            c["tolerance"].value = self.settings.tolerance
            c["title"].value = self.title_html
            c["drawing"].value = self.png()
            if self.settings.bias is None:
                c["bias"].value = round(self.result.bias, 2)
        finally:
            self._syncing = False
