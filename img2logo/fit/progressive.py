"""Progressive optimization (paper Sec. 5.2-5.4): a sequence of golden ratio abstractions.

Starting from the segment graph L = {S, J}, every segment gets a golden circle
(Sec. 5.3: a free fit, its radius snapped to the ladder by Eqn. 12, then the
connectivity-constrained fit of Eqn. 13 moving centres and junctions) and an
arc (the candidate with the smallest discrete Fréchet distance to its pixels).
Then neighbouring segments are merged one pair at a time, the pair with the
lowest merge error first, until the similarity error E^s (Eqn. 3) would exceed
the tolerance T. Every iteration is kept: level t is the abstraction A^t.

Two accelerations of Sec. 5.4 are switches: *line-segment simplification*
(before the loop, neighbours that one arc fits with a mean error below 1 px are
merged) and *localized fitting* (a merge refits only the new circle and its
neighbours, the junctions it does not touch held fixed; when that window does
not converge the global problem is solved instead). So are the ablations of
Sec. 6.2: the connectivity constraint (Fig. 11c), constraints only at the ends
of merged segments (Fig. 11d), no merging (Fig. 11e) and redundant-intersection
avoidance (Fig. 12).

The *merge error* of a candidate pair is the E^s that the abstraction would
have after merging it, computed from the exact local refit. All candidates are
compared on that one scale (|A| and |J'| of the state after the merge), which
the changing weights 1/|A| and 1/|J'| would otherwise distort. A candidate's
score is cached with the set of arcs its refit touched, and recomputed from
the current state whenever one of them changed.

This module holds the entry point :func:`optimize` and the initial fit; the
optimizer's state (groups, golden circles, arcs, the constrained fit of a
window) is :class:`img2logo.fit.fit_state.FitState`. The stages it
runs are their own modules: the segment groups and the
line-segment simplification (:mod:`img2logo.fit.simplification`), the recovery of
an initial fit that fails (:mod:`img2logo.fit.recovery`), the merge
candidates, their evaluation and the loop (:mod:`img2logo.fit.merging`), and the
levels, each made when first asked for (:mod:`img2logo.fit.levels`).

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import dataclasses
import math
import os
import time
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .._compiled import kernels
from ..constants import LOGO_ARCS
from ..errors import InvalidParameterError
from ..geometry.abstraction import Abstraction
from ..geometry.golden_ladder import FibonacciLadder, Ladder, make_ladder
from ..geometry.primitives import polyline_length
from ..options import Options
from ..segment_graph import SegmentGraph
from . import window_solve
from .constants import OUTLINE_DISTANCE, OUTLINE_STROKE_DISTANCE
from .fit_state import FitState
from .fit_values import AxisConstraints, FreeCircles, Seed
from .kinks import tangent_level
from .levels import LevelContext, Levels, LevelState
from .merge_checks import redundant_pairs
from .merging import TIME_BUDGET_STOP, merge_loop
from .recovery import check_reach, check_span, recover
from .simplification import Group, hold_line, simplify as simplify_groups
from .tangency import snapshot

#: Signature of a progress callback: (level t, number of arcs, E^s in px).
ProgressCallback = Callable[[int, int, float], None]


class TimeBudgetWarning(UserWarning):
    """The optimization reached its time budget (``Options.time_budget``): merging stopped at the last level."""


# --------------------------------------------------------------------------- results
@dataclass(frozen=True, eq=False)
class Progression:
    """The output of :func:`optimize`: every level A^0 ... A^final.

    Attributes
    ----------
    levels : Levels (a sequence of Abstraction)
        ``levels[t]`` is A^t; each has fewer arcs than the one before. The last
        one is the result: its E^s is within the tolerance (unless A^0 already
        exceeds it, then A^0 is the only level). Each level is made when it is
        first asked for (:class:`Levels`); a run that uses only its result makes only that.
    bias : float
        The ladder bias sigma used (Eqn. 14 from the longest segment, or given);
        0.0 on the Fibonacci ladder (its unit is ``ladder.unit``).
    simplified : tuple of tuple of int
        The segments of the graph grouped by the line-segment simplification
        (Sec. 5.4), in the order of A^0's arcs.
    stopped_because : str
        Why the loop stopped: ``"tolerance"``, ``"no mergeable pair"``, ``"merging off"``
        or ``"time budget"`` (``Options.time_budget``; a :class:`TimeBudgetWarning` says so);
        where it went on past T (``Options.stretch``), ``"past T, 40 arcs"`` (the
        budget reached), ``"past T, 1.62 T"`` (the stretched tolerance reached) or
        ``"past T, no mergeable pair"``.
    stats : dict of str to int
        The counts of :class:`~img2logo.fit.fit_values.Stats` by name, in its order:
        merge candidates evaluated, local windows that failed, global solves,
        candidates rejected (hopeless, redundant intersections, an arc too far,
        a crossing), released junctions and tangencies, tangent joins.
    timings : dict
        Seconds spent in simplification, the initial fit, the loop and the tangent joins' refit.
    ladder : GoldenLadder or FibonacciLadder or None
        The ladder the radii were snapped to.

    Examples
    --------
    >>> from img2logo import build_segment_graph, data, extract_feature_lines, optimize
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> progression = optimize(build_segment_graph(extract_feature_lines(image)))
    >>> progression.final is progression.levels[-1], progression.stopped_because != ""
    (True, True)
    """

    levels: Sequence[Abstraction]
    bias: float
    simplified: tuple[tuple[int, ...], ...]
    stopped_because: str
    stats: dict[str, int] = field(default_factory=dict)
    timings: dict[str, float] = field(default_factory=dict)
    ladder: Ladder | None = None

    @property
    def final(self) -> Abstraction:
        """The result: the last level, the simplest within the tolerance."""
        return self.levels[-1]

    @property
    def arc_counts(self) -> list[int]:
        """|A^t| for every level t."""
        if isinstance(self.levels, Levels):
            return self.levels.arc_counts()
        return [len(a.arcs) for a in self.levels]

    @property
    def similarities(self) -> list[float]:
        """E^s(A^t) for every level t, px."""
        if isinstance(self.levels, Levels):
            return self.levels.similarities()
        return [a.similarity for a in self.levels]


# --------------------------------------------------------------------------- A^0
def initial_fit(state: FitState) -> None:
    """A^0: golden circles for every group of ``state``, fitted jointly (Sec. 5.3).

    When the joint fit fails, :func:`~img2logo.fit.recovery.recover` fits each
    connected part alone, releasing junctions as needed. With
    redundant-intersection avoidance (Fig. 12), a group of several segments
    (the line-segment simplification's, Sec. 5.4) whose arc meets another arc
    at a redundant point is split into its segments again and A^0 fitted anew
    (:func:`split_crossed`), until no simplified group is in a redundant intersection.
    """
    _fit_all(state)
    while state.options.avoid_intersections and split_crossed(state):
        _fit_all(state)


def _fit_all(state: FitState) -> None:
    """The joint fit of every group of ``state`` (or the recovery), into its fits and displacements."""
    # Longest groups first: a straight group is a line unless a line already
    # holds one of its junctions (see FitState.golden).
    seeds: dict[int, Seed] = {}
    held: dict[int, list[np.ndarray]] = {}
    for gid in sorted(state.groups, key=lambda g: -polyline_length(state.groups[g].points)):
        seeds[gid] = state.golden(state.groups[gid], held=held)
        if seeds[gid].k is None:
            hold_line(held, state.groups[gid], state.constrained_nodes(state.groups[gid]))
    check_reach(state, seeds)
    out = window_solve.solve_whole(state, dict(state.groups), seeds, state.node_groups())
    if out is None:
        out = recover(state, seeds)
    fits, disp = out
    state.fits = fits
    for n, d in disp.items():
        state.disp[n] = d


def split_crossed(state: FitState) -> int:
    """Split the fitted groups of several segments that are in a redundant intersection; how many were split.

    The line-segment simplification (Sec. 5.4) merges neighbours that one
    golden circle fits within ``SIMPLIFICATION_ERROR``, before any constrained
    fit: an acceleration, standing for merges the loop would make first. But
    the loop refuses a merge that leaves a redundant intersection (Sec. 5.2,
    Fig. 12), and the simplification cannot see one: the arc through the
    group's displaced end junctions can leave its pixels where they turn
    sharply at a junction and cross the arc beside them (scikit-image's coffee
    cup: a hairpin where the saucer's rim meets the spoon, a 20 px circle over
    three segments bulging 3 px over the rim's arc). Such a group goes back to
    its segments, one group each as before the simplification, and the loop
    decides on their merges with its rule. The state is left with the groups
    (all of them re-added in the order of their first segment, as
    :func:`optimize` adds them) and without fits, for the fit of A^0 again;
    the displacements are reset. Counted in ``stats.split_groups``.
    """
    crossed = {g for pair in redundant_pairs(state) for g in pair if len(state.groups[g].segments) > 1}
    if not crossed:
        return 0
    graph = state.graph
    groups = []
    for gid, group in state.groups.items():
        if gid not in crossed:
            groups.append(group)
            continue
        for s in group.segments:
            groups.append(Group((s,), (int(graph.ends[s][0]), int(graph.ends[s][1])), graph.segments[s], group.locked))
    state.groups.clear()
    state.fits = {}
    state.disp[:] = 0.0
    state.invalidate()
    for g in sorted(groups, key=lambda g: min(g.segments)):
        state.add_group(g)
    state.stats.split_groups += len(crossed)
    return len(crossed)


# --------------------------------------------------------------------------- the entry point
def optimize(
    graph: SegmentGraph,
    options: Options | None = None,
    *,
    lock_mask: np.ndarray | None = None,
    silhouette: np.ndarray | None = None,
    progress: ProgressCallback | None = None,
    params: Mapping[str, Any] | None = None,
    symmetry: AxisConstraints | None = None,
    started: float | None = None,
    **settings: Any,
) -> Progression:
    """Run the progressive optimization of Sec. 5.2 on a segment graph.

    Parameters
    ----------
    graph : SegmentGraph
        The line-segment graph L = {S, J}.
    options : Options, optional
        The settings and switches (:class:`~img2logo.options.Options`: the
        tolerance T, the ladder, the ablations of Sec. 6, ...); default the
        defaults. Its feature-line settings (``kind``, ``rdp_tolerance``, ...)
        are not used here: the graph is made.
    lock_mask : ndarray of bool, shape (H, W), optional
        Segments mostly inside it are never merged (Sec. 7, Fig. 16).
    silhouette : ndarray of bool, shape (H, W), optional
        The paper around the object (a clip art's background region): the
        segments along its edge (:func:`outline_segments`) are the object's
        silhouette, and a merge whose new arc would stray farther than the
        tolerance T (discrete Fréchet) from their pixels is rejected. E^s is a
        mean over the arcs, so without it one merge can cut across a corner of
        the silhouette by far more than T (a bandage's rounded end, a leg)
        while the mean stays within T; the silhouette is the first line of a
        logo, and each of its arcs is held to T, as every arc of a photo is
        (``PHOTO_MAX_ARC_FACTOR``). Inner lines merge as before.
    progress : callable, optional
        Called as ``progress(t, n_arcs, similarity)`` after every level the merge
        loop makes (A^0 first), then, when the tangent joins were refitted
        (``tangency``), once more with the result's final level: its t may be
        smaller than the last reported (the later levels are dropped) and its
        arcs and E^s are those after the refit. The last call is always the
        result's ``final``.
    params : mapping, optional
        Extra entries recorded in every level's ``params``.
    symmetry : img2logo.fit.symmetry.HalfAxis, optional
        For a symmetric run (:func:`img2logo.fit.symmetry.optimize_symmetric`): the
        graph is one half of a mirror-symmetric drawing in a frame whose axis is
        the vertical line ``symmetry.x``; junctions ``symmetry.nodes`` stay on
        it, circles ending square to it are centred on it, and no arc runs on
        through it (Eqn. 13 with the symmetry constraints).
    started : float, optional
        The process's CPU time (:func:`time.process_time`, s) the time budget
        (``Options.time_budget``) counts from: default this call's start;
        :func:`img2logo.abstract` gives its own, so that the budget bounds the
        whole run, the image's feature lines and segment graph included.
    **settings
        Fields of :class:`~img2logo.options.Options` (``tolerance=7.0``,
        ``merging=False``, ...), replacing those of ``options``.

    Returns
    -------
    Progression
        Every level records :meth:`Options.record` in its ``params`` (with
        ``arcs``, the arc budget of :func:`arc_budget`, ``locked_segments``,
        ``params``, and the ``bias``, or Fibonacci ``unit``,
        used), and carries its ladder: phi with the bias of Eqn. 14 (or the one
        given), or the Fibonacci grid with its unit (bias 0.0).

    Raises
    ------
    InvalidParameterError
        On an unknown setting or a value out of range (before any work), an
        empty graph, or a lock mask of the wrong shape.

    Examples
    --------
    >>> from img2logo import build_segment_graph, data, extract_feature_lines, optimize
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> progression = optimize(build_segment_graph(extract_feature_lines(image)))
    >>> progression.arc_counts[-1], progression.final.arcs[0].circle.k
    (1, 8)
    """
    opts = Options.from_keywords(settings, base=options) if settings or options is None else options
    if not isinstance(opts, Options):
        raise InvalidParameterError(f"options must be an Options value, got {type(opts).__name__}")
    if not isinstance(graph, SegmentGraph):
        raise InvalidParameterError(f"graph must be a SegmentGraph, got {type(graph).__name__}")
    if graph.n_segments == 0:
        raise InvalidParameterError("the segment graph has no segments: nothing to abstract (no feature lines found)")
    if started is not None and (
        isinstance(started, bool) or not isinstance(started, int | float) or math.isnan(started)
    ):
        raise InvalidParameterError(f"started must be a process_time() reading, s, or None, got {started!r}")
    locked = locked_segments(graph, lock_mask)
    budget = arc_budget(opts)
    record = {**opts.record(), "arcs": budget, "locked_segments": int(locked.sum()), **(params or {})}
    ladder, bias, unit, simplify = opts.ladder, opts.bias, opts.unit, opts.simplify

    circles = FreeCircles(symmetry)
    axis_nodes = symmetry.nodes if symmetry is not None else frozenset()
    timings: dict[str, float] = {}
    if started is None:  # the kernels load (or compile, once per machine) before the clock starts
        kernels.usable()
    over_budget = _budget(opts.time_budget, started)
    start = time.perf_counter()
    groups = [
        Group((i,), tuple(int(n) for n in graph.ends[i]), seg, bool(locked[i])) for i, seg in enumerate(graph.segments)
    ]
    # The bias comes from the longest segment after simplification (Eqn. 14), by
    # free circles as in the paper. The simplification that the loop starts
    # from then asks for a *golden* arc within 1 px: a free fit within 1 px can
    # be far off once its radius is snapped up the ladder (by up to phi). The
    # Fibonacci ladder's unit comes from the same radius (unit_from_radius).
    longest = None
    if (unit if ladder == "fibonacci" else bias) is None:
        probe = simplify_groups(groups, circles.error, graph.valence, axis_nodes) if simplify else groups
        longest = circles.circle(max(probe, key=lambda g: polyline_length(g.points)))[1]
    golden = make_ladder(ladder, longest, bias=bias, unit=unit, exponents=opts.exponents, rounding=opts.rounding)
    check_span(golden, graph.width, graph.height)
    state = FitState(graph, opts, golden, symmetry, circles=circles)
    state.outline = frozenset(np.flatnonzero(outline_segments(graph, silhouette)).tolist())
    if simplify:
        groups = simplify_groups(groups, state.golden_error, graph.valence, axis_nodes)
    for g in sorted(groups, key=lambda g: min(g.segments)):
        state.add_group(g)
    timings["simplification"] = time.perf_counter() - start

    start = time.perf_counter()
    initial_fit(state)
    record["bias"] = float(golden.bias)
    if isinstance(golden, FibonacciLadder):
        record["unit"] = float(golden.unit)
    run = LevelContext(state)
    levels: list[LevelState | Abstraction] = [LevelState.of(state, 0, record, run)]
    simplified = levels[0].arc_segments
    timings["initial_fit"] = time.perf_counter() - start
    if progress:
        progress(0, len(levels[0].arcs), levels[0].similarity)

    history = [snapshot(state)] if state.smooth else []

    def add_level(state: FitState) -> None:
        """A merge was made: the state is level A^t, t = len(levels)."""
        level = LevelState.of(state, len(levels), record, run)
        levels.append(level)
        if state.smooth:
            history.append(snapshot(state))
        if progress:
            progress(level.level, len(level.arcs), level.similarity)

    start = time.perf_counter()
    stopped = "merging off"
    tolerance = opts.tolerance
    if opts.merging:
        stopped = merge_loop(state, tolerance, add_level, over_budget)
        if stopped != TIME_BUDGET_STOP and opts.stretch > 1.0 and logo_arcs(state) > budget:
            # Simplicity past T: more arcs than a logo holds. Merging goes on, the cheapest first,
            # every check as before and the silhouette's arcs held to the stretched tolerance.
            tolerance = opts.stretch * opts.tolerance
            state.options = dataclasses.replace(opts, tolerance=tolerance)
            stopped = merge_loop(state, tolerance, add_level, over_budget, lambda: logo_arcs(state) <= budget)
            said = {"arcs": f"{budget} arcs", "tolerance": f"{opts.stretch:.3g} T"}.get(stopped, stopped)
            stopped = f"past T, {said}"
    timings["loop"] = time.perf_counter() - start
    start = time.perf_counter()
    if state.smooth:
        # The result, its circles touching at the smooth joins (beyond the paper); it may be
        # a level before the loop's last, whose shorter arcs leave room for more tangencies.
        # An arc budget the loop met bounds the result: a tangency trades for arcs only below it. One the
        # stretched tolerance kept it from does not: those levels back lower E^s past T as well as kinks.
        arcs = logo_arcs(state)
        room = (budget - arcs) // (1 if state.symmetry is None else 2) if arcs <= budget else None
        back = tangent_level(state, tolerance, history, over_budget, room)
        del levels[len(levels) - back :]
        levels[-1] = LevelState.of(state, levels[-1].level, record, run).abstraction()
        if progress:  # the result: an earlier t than the last reported when levels were dropped
            progress(levels[-1].level, len(levels[-1].arcs), levels[-1].similarity)
    timings["tangency"] = time.perf_counter() - start
    made = Levels(levels)
    if stopped.endswith(TIME_BUDGET_STOP):
        final = made[-1]
        warnings.warn(
            TimeBudgetWarning(
                f"the optimization reached its time budget ({opts.time_budget:g} s of CPU) and stopped merging at "
                f"level {final.level}: {len(final.arcs)} arcs, E^s {final.similarity:.2f} px within "
                f"{'T' if tolerance == opts.tolerance else f'{opts.stretch:.3g} T'} = {tolerance:g} px "
                "(fewer arcs may fit: give it longer with --time-budget S or none)"
            ),
            stacklevel=2,
        )
    return Progression(made, float(golden.bias), simplified, stopped, state.stats.as_dict(), timings, golden)


def arc_budget(options: Options) -> int:
    """The arcs a logo holds: ``options.arcs``, or ``LOGO_ARCS`` when none is given.

    Examples
    --------
    >>> from img2logo import Options
    >>> from img2logo.fit.progressive import arc_budget
    >>> arc_budget(Options()), arc_budget(Options(arcs=25))
    (40, 25)
    """
    return LOGO_ARCS if options.arcs is None else options.arcs


def logo_arcs(state: FitState) -> int:
    """The arcs of the logo the state draws: one per group; for a symmetric half (:mod:`img2logo.fit.symmetry`)
    each with its mirror image, but for those centred on the axis, which are one arc with it."""
    n = len(state.fits)
    if state.symmetry is None:
        return n
    return 2 * n - sum(1 for g in state.fits if state.on_axis(state.groups[g]))


def _budget(seconds: float | None, since: float | None = None) -> Callable[[], bool] | None:
    """Whether ``seconds`` of this process's CPU time have passed since ``since`` (default now; None: no bound).

    CPU time, not wall time: other processes' load does not shorten it (a run
    stops at about the same merge on an idle and on a busy machine). The
    process's, not the thread's: reading a thread's CPU clock took 4-5 ms a
    read on a loaded machine here, the process's about 1 us; in a pool of
    threads the threads' work counts together.
    """
    if seconds is None:
        return None
    deadline = (time.process_time() if since is None else since) + seconds
    # A process's CPU clock runs at most as fast as the wall clock times the machine's CPUs: until the wall
    # clock has run that far, the CPU clock cannot have passed the deadline, and it is not read (each read
    # is a system call, some microseconds of CPU; the merge loop asks before every candidate's refit).
    cpus = os.cpu_count()  # (None when unknown: then the CPU clock is read every time)
    unread_until = -math.inf  # the wall time before which the answer is known to be False, s

    def over() -> bool:
        nonlocal unread_until
        now = time.perf_counter()
        if now < unread_until:
            return False
        left = deadline - time.process_time()
        if left < 0.0:
            return True
        if cpus:
            unread_until = now + left / cpus
        return False

    return over


def outline_segments(graph: SegmentGraph, silhouette: np.ndarray | None) -> np.ndarray:
    """Segments along the edge of ``silhouette`` (H, W) bool, the paper around the object: (n_segments,) bool.

    Those with most of their points on the object's outermost line: a clip art's
    line between the background and a fill runs on the object's pixels next to the
    paper (:func:`img2logo.features.clipart.region_boundaries`), within
    ``OUTLINE_DISTANCE`` px of it; an outline stroke is drawn along its middle
    (:func:`img2logo.features.clipart_strokes.clipart_lines`), half its width from
    the paper, and is the silhouette where the paper reaches it without crossing
    another line (4-connected, so no diagonal step of a line lets it through),
    within ``OUTLINE_STROKE_DISTANCE`` px. An inner line behind it is not.
    """
    if silhouette is None:
        return np.zeros(graph.n_segments, dtype=bool)
    import cv2

    from ..images.ndimage import distance

    paper = _image_mask(graph, silhouette, "silhouette")
    away = distance(~paper)
    drawn = np.zeros(paper.shape, dtype=np.uint8)
    cv2.polylines(  # each segment joined point to point, up to its junctions: no gap lets the paper in
        drawn,
        [
            np.stack([_pixel_cols(seg, graph.width), _pixel_rows(seg, graph.height)], axis=1).astype(np.int32)
            for seg in graph.segments
        ],
        isClosed=False,
        color=1,
        lineType=cv2.LINE_8,
    )
    lines = drawn.view(bool)
    count, pieces = cv2.connectedComponents((~lines).view(np.uint8), connectivity=4)
    touches = np.zeros(count, dtype=bool)
    touches[pieces[paper & ~lines]] = True
    reached = touches[pieces] & ~lines
    beside = cv2.dilate(reached.view(np.uint8), cv2.getStructuringElement(cv2.MORPH_CROSS, (3, 3))) > 0
    outermost = lines & beside & (away <= OUTLINE_STROKE_DISTANCE)
    return _mostly_inside(graph, (~paper & (away <= OUTLINE_DISTANCE)) | outermost)


def locked_segments(graph: SegmentGraph, lock_mask: np.ndarray | None) -> np.ndarray:
    """Segments with most of their points inside ``lock_mask`` (Sec. 7, Fig. 16)."""
    if lock_mask is None:
        return np.zeros(graph.n_segments, dtype=bool)
    return _mostly_inside(graph, _image_mask(graph, lock_mask, "lock_mask"))


def _image_mask(graph: SegmentGraph, mask: np.ndarray, name: str) -> np.ndarray:
    """``mask`` as (H, W) bool of the graph's image; a clear error for another shape."""
    arr = np.asarray(mask)
    if arr.shape != (graph.height, graph.width):
        raise InvalidParameterError(
            f"{name} must have the image's shape {(graph.height, graph.width)}, got {arr.shape}"
        )
    return arr.astype(bool)


def _mostly_inside(graph: SegmentGraph, mask: np.ndarray) -> np.ndarray:
    """Which segments have more than half of their points on ``mask`` (H, W) bool: (n_segments,) bool."""
    out = np.zeros(graph.n_segments, dtype=bool)
    for i, seg in enumerate(graph.segments):
        out[i] = mask[_pixel_rows(seg, graph.height), _pixel_cols(seg, graph.width)].mean() > 0.5
    return out


def _pixel_cols(points: np.ndarray, width: int) -> np.ndarray:
    """The pixel columns of points (N, 2) px (x = column + 0.5), within the image."""
    return np.clip((points[:, 0] - 0.5).round().astype(int), 0, width - 1)


def _pixel_rows(points: np.ndarray, height: int) -> np.ndarray:
    """The pixel rows of points (N, 2) px (y = row + 0.5), within the image."""
    return np.clip((points[:, 1] - 0.5).round().astype(int), 0, height - 1)
