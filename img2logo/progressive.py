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

This module holds the entry point :func:`optimize` and the optimizer's state
(groups, golden circles, arcs, the constrained fit of a window, the levels).
The stages it runs are their own modules: the segment groups and the
line-segment simplification (:mod:`img2logo.simplification`), the recovery of
an initial fit that fails (:mod:`img2logo.recovery`), and the merge
candidates, their evaluation and the loop (:mod:`img2logo.merging`).

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .arc_extraction import ArcFit, extract_arc
from .circle_fitting import fit_center, fit_circle, mean_abs_error
from .constants import (
    JUNCTION_TOLERANCE,
    LINE_MIN_ANGLE,
    SYMMETRY_FIT_STALL,
)
from .constrained_fit import WindowFit, fit_window
from .errors import InvalidParameterError
from .geometry import Abstraction, ArcJunctions, Circle, Line, line_arc, polyline_length
from .golden_ladder import Ladder, make_ladder
from .merging import MergeOutcome, merge_loop
from .options import Options
from .recovery import check_reach, check_span, recover
from .segment_graph import SegmentGraph
from .simplification import Group, hold_line, straight_line
from .simplification import simplify as simplify_groups
from .tangency import tangent_joins

#: Signature of a progress callback: (level t, number of arcs, E^s in px).
ProgressCallback = Callable[[int, int, float], None]


# --------------------------------------------------------------------------- results
@dataclass(frozen=True, eq=False)
class Progression:
    """The output of :func:`optimize`: every level A^0 ... A^final.

    Attributes
    ----------
    levels : tuple of Abstraction
        ``levels[t]`` is A^t; each has fewer arcs than the one before. The last
        one is the result: its E^s is within the tolerance (unless A^0 already
        exceeds it, then A^0 is the only level).
    bias : float
        The ladder bias sigma used (Eqn. 14 from the longest segment, or given);
        0.0 on the Fibonacci ladder (its unit is ``ladder.unit``).
    simplified : tuple of tuple of int
        The segments of the graph grouped by the line-segment simplification
        (Sec. 5.4), in the order of A^0's arcs.
    stopped_because : str
        Why the loop stopped: ``"tolerance"``, ``"no mergeable pair"`` or ``"merging off"``.
    stats : dict
        Counts: merge candidates evaluated, local windows that failed, global
        solves, candidates rejected without a global solve because their own
        golden circle is off by more than T, candidates rejected for redundant
        intersections.
    timings : dict
        Seconds spent in simplification, the initial fit, the loop and the tangent joins' refit.
    ladder : GoldenLadder or FibonacciLadder or None
        The ladder the radii were snapped to.
    """

    levels: tuple[Abstraction, ...]
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
        return [len(a.arcs) for a in self.levels]

    @property
    def similarities(self) -> list[float]:
        """E^s(A^t) for every level t, px."""
        return [a.similarity for a in self.levels]


# --------------------------------------------------------------------------- state
@dataclass
class _Fit:
    """A group's golden circle and arc (private, mutable state of the loop)."""

    center: np.ndarray
    radius: float
    k: int
    arc: ArcFit


class _Lazy(dict):
    """A mapping whose values are computed on first access (only the window's are needed)."""

    def __init__(self, value: Callable[[Any], Any]) -> None:
        super().__init__()
        self._value = value

    def __missing__(self, key: Any) -> Any:
        value = self[key] = self._value(key)
        return value


def _rung_reaching(ladder: Ladder, k: int, reach: float) -> tuple[int, float]:
    """The smallest allowed rung above ``k`` whose radius is at least ``reach`` px: (k, r).

    Without one (a user's subset of small radii), the largest allowed rung.
    """
    if ladder.exponents is not None:
        allowed = sorted(ladder.exponents)
        above = [j for j in allowed if ladder.radius(j) >= reach]
        j = above[0] if above else allowed[-1]
        return j, ladder.radius(j)
    while ladder.radius(k) < reach:
        k += 1
    return k, ladder.radius(k)


class _Optimizer:
    """The mutable state of one run of the progressive optimization (private)."""

    def __init__(self, graph: SegmentGraph, options: Options, symmetry: Any = None) -> None:
        self.graph = graph
        self.options = options
        #: The mirror axis of a symmetric run (``img2logo.symmetry.HalfAxis``), or None.
        self.symmetry = symmetry
        self.groups: dict[int, Group] = {}
        self.fits: dict[int, _Fit] = {}
        self.disp = np.zeros((graph.n_junctions, 2))
        self.next_id = 0
        self.stats = {
            "evaluated": 0,
            "local_failed": 0,
            "global_solves": 0,
            "rejected_hopeless": 0,
            "rejected_intersections": 0,
            "rejected_far_arc": 0,
            "released_junctions": 0,
            "tangent_joins": 0,
            "released_tangencies": 0,
            "rejected_crossing": 0,
        }
        self._circle_cache: dict[tuple[int, ...], tuple[np.ndarray, float]] = {}
        self.ladder: Ladder | None = None
        #: Junctions whose connectivity constraint was given up (see recover).
        self.released: set[int] = set()
        self._path_cache: dict[tuple[int, ...], tuple[int, ...]] = {}
        self._node_groups: dict[int, list[int]] | None = None
        #: Nodes where two groups ending there must touch (tangent joins, beyond the
        #: paper): where the input's line runs on smoothly (SegmentGraph.smooth_nodes).
        self.smooth: frozenset[int] = graph.smooth_nodes() if options.tangency and options.connectivity else frozenset()
        #: Smooth nodes whose tangency was given up (img2logo.tangency): a kink is left there.
        self.loose: set[int] = set()
        #: Tangent joins whose junction slides along the input's line (img2logo.tangency):
        #: node -> its distance off the line, px, which E^s counts instead of |d_k|.
        self.off_line: dict[int, float] = {}

    # ----------------------------------------------------------------- groups and nodes
    def add_group(self, group: Group) -> int:
        gid = self.next_id
        self.next_id += 1
        self.groups[gid] = group
        self._node_groups = None
        return gid

    def release(self, node: int) -> None:
        """Give up the connectivity constraint at junction ``node`` (:func:`~img2logo.recovery.recover`)."""
        self.released.add(node)
        self._node_groups = None

    def tangencies(
        self, groups: Mapping[int, Group], seeds: Mapping[int, tuple[np.ndarray, float, int | None]]
    ) -> dict[int, tuple[int, int]]:
        """Smooth node -> the two groups of ``groups`` that end there, whose circles must touch at it.

        A tangent join (beyond the paper): at a node of valence 2 where the
        input's line turns by less than ``SMOOTH_JOIN_ANGLE``
        (:meth:`SegmentGraph.smooth_nodes`), two different groups end, and the
        constrained fit makes their circles touch there (``tangents`` of
        :func:`~img2logo.constrained_fit.fit_constrained`). Not at a released
        junction or tangency, nor between two straight lines (both fixed).
        """
        if not self.smooth:
            return {}
        at: dict[int, list[int]] = {}
        for gid, g in groups.items():
            for n in set(g.ends):
                if n in self.smooth:
                    at.setdefault(n, []).append(gid)
        out = {}
        for n, gids in at.items():
            if len(gids) != 2 or n in self.loose or n in self.released:
                continue
            if seeds[gids[0]][2] is None and seeds[gids[1]][2] is None:
                continue
            out[n] = (gids[0], gids[1])
        return out

    def constrained_nodes(self, group: Group) -> tuple[int, ...]:
        """Nodes where ``group``'s arc must pass (its J' part), in path order.

        The two ends, and inner nodes where other segments meet (valence >= 3
        in the graph, Sec. 6.2) unless only the ends are constrained (Fig. 11d).
        """
        nodes = self.path_nodes(group)
        return tuple(n for n in nodes if n not in self.released) if self.released else nodes

    def path_nodes(self, group: Group) -> tuple[int, ...]:
        """:meth:`constrained_nodes` with the released junctions (see :meth:`recover`), in path order."""
        # Called for every group of every window of every candidate merge: cached by the
        # group's node path, which is all the answer depends on.
        hit = self._path_cache.get(group.nodes)
        if hit is None:
            hit = self._path_cache[group.nodes] = self._path_nodes(group)
        return hit

    def _path_nodes(self, group: Group) -> tuple[int, ...]:
        n = group.nodes
        inner = ()
        if self.options.inner_junctions:
            valence = self.graph.valence
            inner = tuple(m for m in n[1:-1] if valence[m] >= 3)
        return (n[0], *inner) if group.closed else (n[0], *inner, n[-1])

    def node_groups(self, groups: dict[int, Group] | None = None) -> dict[int, list[int]]:
        """For every node of J', the groups constrained there (of ``groups``, default the current ones).

        The current state's is cached until the groups or the released junctions
        change; treat it as read-only.
        """
        if groups is None and self._node_groups is not None:
            return self._node_groups
        out: dict[int, list[int]] = {}
        for gid, g in (self.groups if groups is None else groups).items():
            for n in set(self.constrained_nodes(g)):
                out.setdefault(n, []).append(gid)
        if groups is None:
            self._node_groups = out
        return out

    def node_groups_after(self, a: int, b: int, merged: Group) -> dict[int, list[int]]:
        """:meth:`node_groups` after merging groups ``a`` and ``b`` into ``merged`` (id -1).

        Only the nodes of the three groups change: the rest is the current state's.
        """
        now = self.node_groups()
        out = dict(now)
        touched = set(self.constrained_nodes(self.groups[a])) | set(self.constrained_nodes(self.groups[b]))
        new = set(self.constrained_nodes(merged))
        for n in touched | new:
            gs = [g for g in now.get(n, ()) if g not in (a, b)]
            if n in new:
                gs.append(-1)
            if gs:
                out[n] = gs
            else:
                out.pop(n, None)
        return out

    def end_groups(self) -> dict[int, list[int]]:
        """For every node, the groups with an end there (each group once)."""
        out: dict[int, list[int]] = {}
        for gid, g in self.groups.items():
            for n in set(g.ends):
                out.setdefault(n, []).append(gid)
        return out

    # ----------------------------------------------------------------- circles
    def on_axis(self, group: Group) -> bool:
        """Whether ``group``'s circle is centred on the mirror axis (symmetric runs, :mod:`img2logo.symmetry`).

        So it is when the group ends where a line crosses the axis square to it:
        the arc and its mirror image are then one arc through the axis.
        """
        sym = self.symmetry
        if sym is None:
            return False
        return (group.segments[0], group.nodes[0]) in sym.smooth or (group.segments[-1], group.nodes[-1]) in sym.smooth

    def free_circle(self, group: Group) -> tuple[np.ndarray, float]:
        """Unconstrained circle fit of a group (Sec. 5.3, first stage), cached.

        A circle on the mirror axis is fitted to the pixels and their mirror image.
        """
        key = group.segments
        if key not in self._circle_cache:
            pts = group.points
            if self.on_axis(group):
                pts = np.vstack([pts, self.symmetry.mirror(pts)])
            if len(pts) < 3:  # two pixels: a straight piece, capped like any
                pts = np.linspace(pts[0], pts[-1], 3)
            fit = fit_circle(pts, refine=False)  # the centre is refitted after snapping
            self._circle_cache[key] = (np.asarray(fit.center, dtype=np.float64), float(fit.radius))
        return self._circle_cache[key]

    def free_error(self, group: Group) -> float:
        """Mean distance of the group's pixels to its free circle, px."""
        center, radius = self.free_circle(group)
        return mean_abs_error(group.points, center, radius)

    def golden_error(self, group: Group) -> float:
        """Mean distance of the group's pixels to its golden circle, px.

        The free radius snapped to the ladder (Eqn. 12), the centre then placed
        where it fits best for that fixed radius.
        """
        center, radius, _ = self.golden(group)
        pts = group.points
        if self.on_axis(group):  # the arc runs on into its mirror image: fitted together
            pts = np.vstack([pts, self.symmetry.mirror(pts)])
        return mean_abs_error(pts, fit_center(pts, radius, center), radius)

    def golden(
        self, group: Group, *, held: Mapping[int, list[np.ndarray]] | None = None
    ) -> tuple[np.ndarray, float, int | None]:
        """Free fit snapped to the ladder (Eqn. 12): (centre, radius, k).

        With the lines option, a group whose pixels all lie within
        ``LINE_TOLERANCE`` of the chord between its ends is a straight line
        instead: a circle of ``LINE_RADIUS`` with k None (see :func:`line_arc`),
        placed on the pixels' total-least-squares line; it stays fixed in the
        constrained fit, where its junctions slide onto it. ``held`` maps a
        junction to the directions of the lines already there: a junction takes
        at most two lines, at least ``LINE_MIN_ANGLE`` apart, since fixed lines
        pin it to their intersection (far away, or nowhere, for nearly parallel
        ones); otherwise the group stays an arc.
        """
        line = straight_line(group) if self.options.lines and not self.on_axis(group) else None
        if line is not None and held is not None:
            u = (line[1] - line[0]) / np.hypot(*(line[1] - line[0]))
            for n in self.constrained_nodes(group):
                others = held.get(n, [])
                if len(others) >= 2 or any(abs(float(u @ v)) > math.cos(LINE_MIN_ANGLE) for v in others):
                    line = None
                    break
        if line is not None:
            arc = line_arc(line[0], line[1])
            return arc.circle.center, arc.circle.r, None
        center, radius = self.free_circle(group)
        k, r = self.ladder.snap(radius)
        reach = self.reach(group)
        if r < reach:
            k, r = _rung_reaching(self.ladder, k, reach)
        if self.on_axis(group):
            center = self.axis_seed(group, center, r)
        return center, r, k

    def axis_seed(self, group: Group, center: np.ndarray, radius: float) -> np.ndarray:
        """A circle centred on the mirror axis that passes through the group's end on it (the fit's start).

        On the axis, on the side of the free fit's centre: the snapped radius
        would otherwise leave it far from its junction.
        """
        sym = self.symmetry
        smooth = [
            n
            for s, n in ((group.segments[0], group.nodes[0]), (group.segments[-1], group.nodes[-1]))
            if (s, n) in sym.smooth
        ]
        y = float(self.graph.junctions[smooth[0], 1])
        return np.array([sym.x, y + math.copysign(radius, float(center[1]) - y)])

    def reach(self, group: Group) -> float:
        """Half the largest distance between the junctions ``group``'s circle must pass, px.

        A circle passes through two points only if its diameter spans them: a
        nearly semicircular segment whose fitted radius rounds down to a rung
        cannot reach its own ends, and the constrained fit (Eqn. 13) would have
        to drag them together. Its radius goes up to the first rung that reaches.
        """
        nodes = self.constrained_nodes(group)
        if len(nodes) < 2:
            return 0.0
        pts = self.graph.junctions[list(nodes)]
        return 0.5 * float(np.max(np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))))

    # ----------------------------------------------------------------- arcs
    def arc_for(self, group: Group, center: np.ndarray, radius: float, k: int, disp: Any) -> ArcFit:
        """Extract the arc of ``group`` on its circle through its displaced junctions."""
        circle = Circle(float(center[0]), float(center[1]), float(radius), None if k is None else int(k))
        nodes = self.path_nodes(group)
        pts = np.array([self.graph.junctions[n] + (self.disp[n] if n in self.released else disp(n)) for n in nodes])
        if group.closed:
            pts = np.vstack([pts, pts[:1]])
            nodes = (*nodes, nodes[0])
        if not self.options.connectivity:
            # No constraint: the arc ends where the junctions project on its circle.
            pts = circle.point_at(circle.angle_of(pts))
        elif self.released:
            # A released junction is no constraint: the arc ends where it projects.
            loose = np.array([n in self.released for n in nodes])
            if loose.any():
                pts[loose] = circle.point_at(circle.angle_of(pts[loose]))
        fit = extract_arc(circle, group.points, pts, method=self.options.arc_selection)
        return fit if k is not None else ArcFit(Line.of(fit.arc), fit.frechet)

    # ----------------------------------------------------------------- the constrained fit
    def solve(
        self,
        groups: dict[int, Group],
        seeds: Mapping[int, tuple[np.ndarray, float, int | None]],
        node_groups: Mapping[int, Sequence[int]],
        *,
        changed: Sequence[int],
        free_nodes: Sequence[int],
        fixed: set[int],
        n_groups_total: int,
        n_junctions_total: int,
        rings: int = 1,
        order: Callable[[int], Any] | None = None,
        tangent: bool = False,
    ) -> tuple[dict[int, _Fit], dict[int, np.ndarray]] | None:
        """Eqn. 13 over a window of ``groups`` (:func:`~img2logo.constrained_fit.fit_window`), then their arcs.

        The window is the ``changed`` groups and those through ``free_nodes``,
        grown by up to ``rings`` rings; the ``fixed`` groups keep their circles,
        and so do straight lines (a huge free circle is nearly singular along
        its chord: their junctions slide onto them). With ``tangent``, the
        circles of :meth:`tangencies` touch at their junctions too. None if it fails.
        """
        fixed = set(fixed) | {g for g in groups if seeds[g][2] is None}
        window = fit_window(
            _Lazy(lambda g: groups[g].points),
            _Lazy(lambda g: seeds[g][1]),
            _Lazy(lambda g: seeds[g][0]),
            _Lazy(lambda g: tuple(set(self.constrained_nodes(groups[g])))),
            node_groups,
            self.graph.junctions,
            changed=changed,
            free_junctions=free_nodes,
            fixed=fixed,
            rings=rings,
            order=order,
            displacements0=self.disp,
            n_circles=n_groups_total,
            n_junctions=n_junctions_total,
            connectivity=self.options.connectivity,
            constraints=lambda circles, nodes: self.axis_constraints(circles, groups, nodes),
            tangencies=self.tangencies(groups, seeds) if tangent else None,
        )
        if not window.ok:
            return None
        return self._fits(window, groups, seeds, fixed)

    def solve_whole(
        self,
        groups: dict[int, Group],
        seeds: Mapping[int, tuple[np.ndarray, float, int | None]],
        node_groups: Mapping[int, Sequence[int]],
        *,
        n_groups_total: int,
        n_junctions_total: int,
        order: Callable[[int], Any] | None = None,
        tangent: bool = False,
    ) -> tuple[dict[int, _Fit], dict[int, np.ndarray]] | None:
        """:meth:`solve` over all of ``groups`` at once, every junction free (a global solve, counted).

        The initial fit of A^0, a connected part in :func:`~img2logo.recovery.recover`, a merge
        whose local windows failed, the tangent refit: none of them holds a circle fixed.
        """
        self.stats["global_solves"] += 1
        return self.solve(
            groups,
            seeds,
            node_groups,
            changed=list(groups),
            free_nodes=sorted(node_groups),
            fixed=set(),
            n_groups_total=n_groups_total,
            n_junctions_total=n_junctions_total,
            order=order,
            tangent=tangent,
        )

    def axis_constraints(
        self, gids: Sequence[int], groups: Mapping[int, Group], node_list: Sequence[int]
    ) -> dict[str, Any]:
        """Keywords of :func:`~img2logo.constrained_fit.fit_constrained`: circles and junctions held on the axis."""
        sym = self.symmetry
        if sym is None:
            return {}
        return {
            "axis": sym.x,
            "axis_circles": [i for i, g in enumerate(gids) if self.on_axis(groups[g])],
            "axis_junctions": [i for i, n in enumerate(node_list) if n in sym.nodes],
            "stall": SYMMETRY_FIT_STALL,
        }

    def _fits(
        self,
        window: WindowFit,
        groups: dict[int, Group],
        seeds: Mapping[int, tuple[np.ndarray, float, int | None]],
        fixed: set[int],
    ) -> tuple[dict[int, _Fit], dict[int, np.ndarray]]:
        """The new fits (the window's free groups, and lines whose junctions moved) and displacements."""
        disp = window.displacements()
        if not self.options.connectivity:
            disp = {n: np.zeros(2) for n in window.junctions}
        fits = {}
        moved = window.free_junctions
        for gid in window.circles:
            line_moved = seeds[gid][2] is None and bool(moved & set(self.constrained_nodes(groups[gid])))
            if gid in fixed and not line_moved:
                continue
            _, r, k = seeds[gid]
            center = window.center(gid)
            fits[gid] = _Fit(center, r, k, self.arc_for(groups[gid], center, r, k, lambda n: disp[n]))
        return fits, disp

    def initial_fit(self) -> None:
        """A^0: golden circles for every group, fitted jointly (Sec. 5.3)."""
        # Longest groups first: a straight group is a line unless a line already
        # holds one of its junctions (see golden).
        seeds: dict[int, tuple[np.ndarray, float, int | None]] = {}
        held: dict[int, list[np.ndarray]] = {}
        for gid in sorted(self.groups, key=lambda g: -polyline_length(self.groups[g].points)):
            seeds[gid] = self.golden(self.groups[gid], held=held)
            if seeds[gid][2] is None:
                hold_line(held, self.groups[gid], self.constrained_nodes(self.groups[gid]))
        check_reach(self, seeds)
        node_groups = self.node_groups()
        out = self.solve_whole(
            dict(self.groups), seeds, node_groups, n_groups_total=len(self.groups), n_junctions_total=len(node_groups)
        )
        if out is None:
            out = recover(self, seeds)
        fits, disp = out
        self.fits = fits
        for n, d in disp.items():
            self.disp[n] = d

    # ----------------------------------------------------------------- errors
    def totals(self) -> tuple[float, float, int]:
        """(sum of Fréchet distances, sum of |d_k| over J', |J'|)."""
        nodes = list(self.node_groups())
        f = sum(fit.arc.frechet for fit in self.fits.values())
        d = float(np.sum(np.linalg.norm(self.disp[nodes], axis=1))) if nodes else 0.0
        for n, off in self.off_line.items():  # a tangent join slid along a smooth line (img2logo.tangency)
            d += off - float(np.hypot(*self.disp[n]))
        return f, d, len(nodes)

    def similarity(self) -> float:
        """E^s (Eqn. 3): mean Fréchet distance of the arcs plus mean junction displacement."""
        f, d, nj = self.totals()
        return f / max(len(self.fits), 1) + (d / nj if nj else 0.0)

    # ----------------------------------------------------------------- merging (chosen by img2logo.merging)
    def apply(self, outcome: MergeOutcome) -> int:
        """Carry out a merge: the merged group replaces its two parts."""
        a, b, _ = outcome.pair
        del self.groups[a], self.groups[b]
        self._node_groups = None
        self.fits.pop(a)
        self.fits.pop(b)
        gid = self.add_group(outcome.merged)
        for g, fit in outcome.fits.items():
            self.fits[gid if g == -1 else g] = fit
        for n, d in outcome.displacements.items():
            self.disp[n] = d
        return gid

    # ----------------------------------------------------------------- levels
    def abstraction(self, level: int, params: Mapping[str, Any]) -> Abstraction:
        """The current state as a frozen :class:`Abstraction` A^t, with its ladder and topology."""
        order = sorted(self.groups, key=lambda g: min(self.groups[g].segments))
        index = {g: i for i, g in enumerate(order)}
        node_groups = self.node_groups()
        nodes = sorted(node_groups)
        junction = {n: i for i, n in enumerate(nodes)}
        points = np.array([self.graph.junctions[n] + self.disp[n] for n in nodes]).reshape(-1, 2)
        arcs = tuple(self.fits[g].arc.arc for g in order)
        topology = tuple(
            self.arc_junctions(arc, [junction[n] for n in self.constrained_nodes(self.groups[g])], points)
            for g, arc in zip(order, arcs, strict=True)
        )
        return Abstraction(
            level=level,
            arcs=arcs,
            arc_segments=tuple(self.groups[g].segments for g in order),
            junctions=points,
            junction_arcs=tuple(tuple(sorted(index[g] for g in node_groups[n])) for n in nodes),
            similarity=float(self.similarity()),
            bias=float(self.ladder.bias),
            tolerance=float(self.options.tolerance),
            width=self.graph.width,
            height=self.graph.height,
            params=params,
            ladder=self.ladder,
            arc_junctions=topology,
            junction_nodes=tuple(nodes),
            connected=self.options.connectivity,
        )

    @staticmethod
    def arc_junctions(arc: Any, path: Sequence[int], points: np.ndarray) -> ArcJunctions:
        """Which of a group's junctions (``path``: indices into ``points``, in path order) are at the arc's ends.

        The arc was extracted between (the projections on its circle of) the
        junctions of its path (:meth:`arc_for`): an end is at the junction whose
        projection it is, to ``JUNCTION_TOLERANCE``; an end at none (a released
        junction's projection) is free. The others are passed through, in path order.
        """
        c = arc.circle
        ends: list[int | None] = []
        # The projections of all the path's junctions at once (the same values as one at a time).
        proj = c.point_at(c.angle_of(points[np.asarray(path, dtype=np.intp)])).reshape(-1, 2)
        for end in (arc.start, arc.end):
            d = np.hypot(proj[:, 0] - end[0], proj[:, 1] - end[1])
            near = d <= JUNCTION_TOLERANCE
            # The nearest within the tolerance; on a tie the first in path order.
            ends.append(path[int(np.argmin(np.where(near, d, np.inf)))] if near.any() else None)
        return ArcJunctions(ends[0], ends[1], tuple(j for j in path if j not in ends))


# --------------------------------------------------------------------------- the entry point
def optimize(
    graph: SegmentGraph,
    options: Options | None = None,
    *,
    lock_mask: np.ndarray | None = None,
    progress: ProgressCallback | None = None,
    params: Mapping[str, Any] | None = None,
    symmetry: Any = None,
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
    progress : callable, optional
        Called as ``progress(t, n_arcs, similarity)`` after every level.
    params : mapping, optional
        Extra entries recorded in every level's ``params``.
    symmetry : img2logo.symmetry.HalfAxis, optional
        For a symmetric run (:func:`img2logo.symmetry.optimize_symmetric`): the
        graph is one half of a mirror-symmetric drawing in a frame whose axis is
        the vertical line ``symmetry.x``; junctions ``symmetry.nodes`` stay on
        it, circles ending square to it are centred on it, and no arc runs on
        through it (Eqn. 13 with the symmetry constraints).
    **settings
        Fields of :class:`~img2logo.options.Options` (``tolerance=7.0``,
        ``merging=False``, ...), replacing those of ``options``.

    Returns
    -------
    Progression
        Every level records :meth:`Options.record` in its ``params`` (with
        ``locked_segments``, ``params``, and the ``bias``, or Fibonacci ``unit``,
        used), and carries its ladder: phi with the bias of Eqn. 14 (or the one
        given), or the Fibonacci grid with its unit (bias 0.0).

    Raises
    ------
    InvalidParameterError
        On an unknown setting or a value out of range (before any work), an
        empty graph, or a lock mask of the wrong shape.
    """
    opts = Options.from_keywords(settings, base=options) if settings or options is None else options
    if not isinstance(opts, Options):
        raise InvalidParameterError(f"options must be an Options value, got {type(opts).__name__}")
    if not isinstance(graph, SegmentGraph):
        raise InvalidParameterError(f"graph must be a SegmentGraph, got {type(graph).__name__}")
    if graph.n_segments == 0:
        raise InvalidParameterError("the segment graph has no segments: nothing to abstract (no feature lines found)")
    locked = _locked_segments(graph, lock_mask)
    record = {**opts.record(), "locked_segments": int(locked.sum()), **(params or {})}
    ladder, bias, unit, simplify = opts.ladder, opts.bias, opts.unit, opts.simplify

    opt = _Optimizer(graph, opts, symmetry)
    axis_nodes = symmetry.nodes if symmetry is not None else frozenset()
    timings: dict[str, float] = {}
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
        probe = simplify_groups(groups, opt.free_error, graph.valence, axis_nodes) if simplify else groups
        longest = opt.free_circle(max(probe, key=lambda g: polyline_length(g.points)))[1]
    opt.ladder = make_ladder(ladder, longest, bias=bias, unit=unit, exponents=opts.exponents, rounding=opts.rounding)
    check_span(opt.ladder, graph.width, graph.height)
    if simplify:
        groups = simplify_groups(groups, opt.golden_error, graph.valence, axis_nodes)
    for g in sorted(groups, key=lambda g: min(g.segments)):
        opt.add_group(g)
    timings["simplification"] = time.perf_counter() - start

    start = time.perf_counter()
    opt.initial_fit()
    record["bias"] = float(opt.ladder.bias)
    if ladder == "fibonacci":
        record["unit"] = float(opt.ladder.unit)
    levels = [opt.abstraction(0, record)]
    simplified = tuple(lv for lv in levels[0].arc_segments)
    timings["initial_fit"] = time.perf_counter() - start
    if progress:
        progress(0, len(levels[0].arcs), levels[0].similarity)

    start = time.perf_counter()
    stopped = "merging off"
    if opts.merging:
        stopped = merge_loop(opt, levels, record, opts.tolerance, progress)
    timings["loop"] = time.perf_counter() - start
    start = time.perf_counter()
    if opt.smooth and tangent_joins(opt, opts.tolerance):
        # The result, its circles touching at the smooth joins (beyond the paper).
        levels[-1] = opt.abstraction(levels[-1].level, record)
    timings["tangency"] = time.perf_counter() - start
    return Progression(tuple(levels), float(opt.ladder.bias), simplified, stopped, dict(opt.stats), timings, opt.ladder)


def _locked_segments(graph: SegmentGraph, lock_mask: np.ndarray | None) -> np.ndarray:
    """Segments with most of their points inside ``lock_mask`` (Sec. 7, Fig. 16)."""
    if lock_mask is None:
        return np.zeros(graph.n_segments, dtype=bool)
    mask = np.asarray(lock_mask)
    if mask.shape != (graph.height, graph.width):
        raise InvalidParameterError(
            f"lock_mask must have the image's shape {(graph.height, graph.width)}, got {mask.shape}"
        )
    mask = mask.astype(bool)
    out = np.zeros(graph.n_segments, dtype=bool)
    for i, seg in enumerate(graph.segments):
        cols = np.clip((seg[:, 0] - 0.5).round().astype(int), 0, graph.width - 1)
        rows = np.clip((seg[:, 1] - 0.5).round().astype(int), 0, graph.height - 1)
        out[i] = mask[rows, cols].mean() > 0.5
    return out
