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

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .arc_extraction import ArcFit, extract_arc, redundant_intersections
from .circle_fitting import WindowFit, fit_center, fit_circle, fit_window, mean_abs_error
from .constants import (
    JUNCTION_TOLERANCE,
    LINE_END_SKIP,
    LINE_MIN_ANGLE,
    LINE_TOLERANCE,
    SIMPLIFICATION_ERROR,
    SYMMETRY_FIT_STALL,
)
from .errors import FitError, InvalidParameterError
from .geometry import Abstraction, ArcJunctions, Circle, Line, line_arc
from .golden_ladder import Ladder, make_ladder
from .options import Options
from .segment_graph import SegmentGraph

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
        Seconds spent in simplification, the initial fit and the loop.
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


# --------------------------------------------------------------------------- groups
@dataclass(frozen=True, eq=False)
class _Group:
    """Segments of the graph merged into one arc: a path through the graph (private).

    ``nodes`` has one more entry than ``segments``; ``points`` is the ordered
    pixel chain, (n, 2) px. A closed group starts and ends at the same node.
    """

    segments: tuple[int, ...]
    nodes: tuple[int, ...]
    points: np.ndarray
    locked: bool

    @property
    def closed(self) -> bool:
        return self.nodes[0] == self.nodes[-1]

    @property
    def ends(self) -> tuple[int, int]:
        return self.nodes[0], self.nodes[-1]

    def reversed(self) -> _Group:
        return _Group(self.segments[::-1], self.nodes[::-1], self.points[::-1], self.locked)


def _merge_groups(a: _Group, b: _Group, node: int) -> _Group:
    """Join ``a`` and ``b`` at their common end ``node``; ``a``'s far end starts the result."""
    if a.nodes[-1] != node:
        a = a.reversed()
    if b.nodes[0] != node:
        b = b.reversed()
    return _Group(
        a.segments + b.segments,
        a.nodes + b.nodes[1:],
        np.vstack([a.points, b.points[1:]]),
        a.locked or b.locked,
    )


# --------------------------------------------------------------------------- state
@dataclass
class _Fit:
    """A group's golden circle and arc (private, mutable state of the loop)."""

    center: np.ndarray
    radius: float
    k: int
    arc: ArcFit


@dataclass
class _Outcome:
    """What merging one candidate pair would give (private)."""

    pair: tuple[int, int, int]  # (group a, group b, shared node)
    merged: _Group
    fits: dict[int, _Fit]  # new fits of the changed groups; key -1 is the merged group
    displacements: dict[int, np.ndarray]  # node -> new d_k
    window: frozenset[int]  # groups whose state this outcome depends on
    delta_f: float  # change of the sum of Fréchet distances
    delta_d: float  # change of the sum of |d_k| over J'
    delta_j: int  # change of |J'|
    redundant: int  # redundant intersections the merge would leave
    global_solve: bool


class _Lazy(dict):
    """A mapping whose values are computed on first access (only the window's are needed)."""

    def __init__(self, value: Callable[[Any], Any]) -> None:
        super().__init__()
        self._value = value

    def __missing__(self, key: Any) -> Any:
        value = self[key] = self._value(key)
        return value


class ConnectivityWarning(UserWarning):
    """Some junctions of the initial fit were released: their arcs end apart there."""


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
        self.groups: dict[int, _Group] = {}
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
            "rejected_crossing": 0,
        }
        self._circle_cache: dict[tuple[int, ...], tuple[np.ndarray, float]] = {}
        self.ladder: Ladder | None = None
        #: Junctions whose connectivity constraint was given up (see recover).
        self.released: set[int] = set()
        self._path_cache: dict[int, tuple[_Group, tuple[int, ...]]] = {}
        self._node_groups: dict[int, list[int]] | None = None

    # ----------------------------------------------------------------- groups and nodes
    def add_group(self, group: _Group) -> int:
        gid = self.next_id
        self.next_id += 1
        self.groups[gid] = group
        self._node_groups = None
        return gid

    def constrained_nodes(self, group: _Group) -> tuple[int, ...]:
        """Nodes where ``group``'s arc must pass (its J' part), in path order.

        The two ends, and inner nodes where other segments meet (valence >= 3
        in the graph, Sec. 6.2) unless only the ends are constrained (Fig. 11d).
        """
        nodes = self.path_nodes(group)
        return tuple(n for n in nodes if n not in self.released) if self.released else nodes

    def path_nodes(self, group: _Group) -> tuple[int, ...]:
        """:meth:`constrained_nodes` with the released junctions (see :meth:`recover`), in path order."""
        # Called for every group of every window of every candidate merge: cached per
        # group (groups are immutable; the object is kept so that its id is not reused).
        hit = self._path_cache.get(id(group))
        if hit is not None and hit[0] is group:
            return hit[1]
        nodes = self._path_nodes(group)
        self._path_cache[id(group)] = (group, nodes)
        return nodes

    def _path_nodes(self, group: _Group) -> tuple[int, ...]:
        if group.closed:
            head = (group.nodes[0],)
        else:
            head = ()
        inner = ()
        if self.options.inner_junctions:
            valence = self.graph.valence
            inner = tuple(n for n in group.nodes[1:-1] if valence[n] >= 3)
        if group.closed:
            return head + inner
        return (group.nodes[0], *inner, group.nodes[-1])

    def node_groups(self, groups: dict[int, _Group] | None = None) -> dict[int, list[int]]:
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

    def node_groups_after(self, a: int, b: int, merged: _Group) -> dict[int, list[int]]:
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
    def on_axis(self, group: _Group) -> bool:
        """Whether ``group``'s circle is centred on the mirror axis (symmetric runs, :mod:`img2logo.symmetry`).

        So it is when the group ends where a line crosses the axis square to it:
        the arc and its mirror image are then one arc through the axis.
        """
        sym = self.symmetry
        if sym is None:
            return False
        return (group.segments[0], group.nodes[0]) in sym.smooth or (group.segments[-1], group.nodes[-1]) in sym.smooth

    def free_circle(self, group: _Group) -> tuple[np.ndarray, float]:
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

    def free_error(self, group: _Group) -> float:
        """Mean distance of the group's pixels to its free circle, px."""
        center, radius = self.free_circle(group)
        return mean_abs_error(group.points, center, radius)

    def golden_error(self, group: _Group) -> float:
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
        self, group: _Group, *, held: Mapping[int, list[np.ndarray]] | None = None
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
        line = _straight_line(group) if self.options.lines and not self.on_axis(group) else None
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

    def axis_seed(self, group: _Group, center: np.ndarray, radius: float) -> np.ndarray:
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

    def reach(self, group: _Group) -> float:
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
    def arc_for(self, group: _Group, center: np.ndarray, radius: float, k: int, disp: Any) -> ArcFit:
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
        groups: dict[int, _Group],
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
    ) -> tuple[dict[int, _Fit], dict[int, np.ndarray]] | None:
        """Eqn. 13 over a window of ``groups`` (:func:`~img2logo.circle_fitting.fit_window`), then their arcs.

        The window is the ``changed`` groups and those through ``free_nodes``,
        grown by up to ``rings`` rings; the ``fixed`` groups keep their circles,
        and so do straight lines (a huge free circle is nearly singular along
        its chord: their junctions slide onto them). None if it fails.
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
        )
        if not window.ok:
            return None
        return self._fits(window, groups, seeds, fixed)

    def axis_constraints(
        self, gids: Sequence[int], groups: Mapping[int, _Group], node_list: Sequence[int]
    ) -> dict[str, Any]:
        """The keywords of :func:`fit_constrained` that hold circles and junctions on the mirror axis."""
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
        groups: dict[int, _Group],
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
        for gid in sorted(self.groups, key=lambda g: -_length(self.groups[g].points)):
            seeds[gid] = self.golden(self.groups[gid], held=held)
            if seeds[gid][2] is None:
                _hold(held, self.groups[gid], self.constrained_nodes(self.groups[gid]))
        self.check_reach(seeds)
        nodes = sorted(self.node_groups())
        out = self.solve(
            dict(self.groups),
            seeds,
            self.node_groups(),
            changed=list(self.groups),
            free_nodes=nodes,
            fixed=set(),
            n_groups_total=len(self.groups),
            n_junctions_total=len(nodes),
        )
        self.stats["global_solves"] += 1
        if out is None:
            out = self.recover(seeds)
        fits, disp = out
        self.fits = fits
        for n, d in disp.items():
            self.disp[n] = d

    def check_reach(self, seeds: Mapping[int, tuple[np.ndarray, float, int | None]]) -> None:
        """Raise when the user's radii are too small for the segments' junctions (see :meth:`reach`)."""
        if self.ladder.exponents is None:
            return
        short = [g for g, (_, r, k) in seeds.items() if k is not None and r < self.reach(self.groups[g])]
        if short:
            ks = sorted(self.ladder.exponents)
            widest = max(2.0 * self.reach(self.groups[g]) for g in short)
            raise InvalidParameterError(
                f"the chosen radii (k = {', '.join(map(str, ks))}: {self.ladder.radius(ks[0]):.3g} to "
                f"{self.ladder.radius(ks[-1]):.3g} px) are too small: {len(short)} segments need a circle through "
                f"junctions up to {widest:.0f} px apart; allow larger radii"
            )

    def recover(
        self, seeds: dict[int, tuple[np.ndarray, float, int | None]]
    ) -> tuple[dict[int, _Fit], dict[int, np.ndarray]]:
        """A^0 when the joint fit fails: each connected part alone, releasing junctions as needed.

        The parts of the drawing that share no junction are independent
        problems, so a part that converges keeps its exact connectivity. In a
        part that does not, the junction its golden circles miss most (the
        largest distance from the junction to a circle through it, before the
        fit) is released: its arcs end where it projects on their circles, like
        a free end. This repeats until the part converges (a part with every
        junction released always does); the count is reported.
        """
        fits: dict[int, _Fit] = {}
        disp: dict[int, np.ndarray] = {}
        n_total = len(self.groups)
        for part in self.parts():
            while True:
                groups = {g: self.groups[g] for g in part}
                at = self.node_groups(groups)
                out = self.solve(
                    groups,
                    seeds,
                    at,
                    changed=part,
                    free_nodes=sorted(at),
                    fixed=set(),
                    n_groups_total=n_total,
                    n_junctions_total=max(len(self.node_groups()), 1),
                )
                self.stats["global_solves"] += 1
                if out is not None:
                    fits.update(out[0])
                    disp.update(out[1])
                    break
                miss = {
                    n: max(abs(float(np.hypot(*(self.graph.junctions[n] - seeds[g][0]))) - seeds[g][1]) for g in gs)
                    for n, gs in self.node_groups(groups).items()
                }
                if not miss:  # no constraint left, yet no fit: a numerical failure, said as such
                    raise FitError(f"the circles of {len(part)} segments could not be fitted, even unconstrained")
                self.released.add(max(miss, key=lambda n: (miss[n], -n)))
                self._node_groups = None
        self.stats["released_junctions"] = len(self.released)
        if self.released:
            import warnings

            warnings.warn(
                f"the connectivity-constrained fit could not meet {len(self.released)} of "
                f"{len(self.released) + len(self.node_groups())} junctions; their arcs end apart there",
                ConnectivityWarning,
                stacklevel=2,
            )
        return fits, disp

    def parts(self) -> list[list[int]]:
        """The groups in connected parts: groups sharing a constrained junction are in one part."""
        parent = {g: g for g in self.groups}

        def root(g: int) -> int:
            while parent[g] != g:
                parent[g] = parent[parent[g]]
                g = parent[g]
            return g

        for gs in self.node_groups().values():
            for g in gs[1:]:
                parent[root(g)] = root(gs[0])
        parts: dict[int, list[int]] = {}
        for g in sorted(self.groups):
            parts.setdefault(root(g), []).append(g)
        return list(parts.values())

    # ----------------------------------------------------------------- errors
    def totals(self) -> tuple[float, float, int]:
        """(sum of Fréchet distances, sum of |d_k| over J', |J'|)."""
        nodes = list(self.node_groups())
        f = sum(fit.arc.frechet for fit in self.fits.values())
        d = float(np.sum(np.linalg.norm(self.disp[nodes], axis=1))) if nodes else 0.0
        return f, d, len(nodes)

    def similarity(self) -> float:
        """E^s (Eqn. 3): mean Fréchet distance of the arcs plus mean junction displacement."""
        f, d, nj = self.totals()
        return f / max(len(self.fits), 1) + (d / nj if nj else 0.0)

    # ----------------------------------------------------------------- merging
    def candidates(self) -> list[tuple[int, int, int]]:
        """Mergeable pairs (a, b, node): two groups with a common end (Sec. 5.2)."""
        out = []
        sym = self.symmetry
        for node, gids in sorted(self.end_groups().items()):
            if sym is not None and node in sym.nodes:
                continue  # an arc never runs on through the mirror axis: its mirror image would cross it
            ok = [g for g in sorted(gids) if not self.groups[g].locked and not self.groups[g].closed]
            out.extend((a, b, node) for i, a in enumerate(ok) for b in ok[i + 1 :])
        return out

    def evaluate(self, pair: tuple[int, int, int]) -> _Outcome | None:
        """Merge ``pair`` tentatively, refit, and score it; None if infeasible."""
        self.stats["evaluated"] += 1
        a, b, node = pair
        # Two arcs that both run on through one junction cross there (an X): one
        # of them ends at the junction instead, so that arcs meet only at their
        # ends or where one ends on the other (a T), and no crossing is left.
        if any(node in g.nodes[1:-1] for gid, g in self.groups.items() if gid not in (a, b)):
            self.stats["rejected_crossing"] += 1
            return None
        merged = _merge_groups(self.groups[a], self.groups[b], node)
        after = {g: grp for g, grp in self.groups.items() if g not in (a, b)}
        after[-1] = merged
        n_groups = len(after)
        node_groups_after = self.node_groups_after(a, b, merged)
        nj_after = len(node_groups_after)
        seeds = {g: (self.fits[g].center, self.fits[g].radius, self.fits[g].k) for g in after if g != -1}
        held: dict[int, list[np.ndarray]] = {}
        for g, f in self.fits.items():
            if f.k is None and g not in (a, b):
                _hold(held, self.groups[g], self.constrained_nodes(self.groups[g]))
        seeds[-1] = self.golden(merged, held=held)

        merged_nodes = set(self.constrained_nodes(merged))
        global_solve = not self.options.localized
        out = None
        if not global_solve:
            # The window: the new circle and its neighbours, with the new circle's
            # junctions free (Sec. 5.4). If the fixed junctions leave no solution,
            # a second ring (the neighbours' junctions and their circles) is freed
            # before the global problem is solved. Without the connectivity
            # constraint only the new circle moves.
            out = self.solve(
                after,
                seeds,
                node_groups_after,
                changed=[-1],
                free_nodes=sorted(merged_nodes),
                fixed=set() if self.options.connectivity else set(after) - {-1},
                n_groups_total=n_groups,
                n_junctions_total=nj_after,
                rings=2,
                order=lambda g: (g != -1, g),
            )
            if out is None:
                self.stats["local_failed"] += 1
                # A merged segment whose pixels lie on average more than T from
                # their own best golden circle, constraints aside, cannot give an
                # arc within the tolerance: reject it without the costly global
                # solve (measured: such windows fail globally too).
                if self.golden_error(merged) > self.options.tolerance:
                    self.stats["rejected_hopeless"] += 1
                    return None
                global_solve = True
        if global_solve:
            self.stats["global_solves"] += 1
            out = self.solve(
                after,
                seeds,
                node_groups_after,
                changed=list(after),
                free_nodes=sorted(node_groups_after),
                fixed=set(),
                n_groups_total=n_groups,
                n_junctions_total=nj_after,
                order=lambda g: (g == -1, g),  # the merged group last, as in ``after``
            )
            if out is None:
                return None
        fits, disp = out
        cap = self.options.arc_bound
        if cap is not None and fits[-1].arc.frechet > cap:
            self.stats["rejected_far_arc"] += 1
            return None

        old_nodes = set(self.node_groups())
        changed_nodes = set(disp) | {node}
        delta_d = sum(float(np.linalg.norm(disp[n])) for n in changed_nodes if n in node_groups_after and n in disp)
        delta_d -= sum(float(np.linalg.norm(self.disp[n])) for n in changed_nodes if n in old_nodes)
        delta_f = sum(f.arc.frechet for f in fits.values())
        delta_f -= sum(self.fits[g].arc.frechet for g in {a, b} | (set(fits) - {-1}))
        window_ids = frozenset({a, b} | (set(fits) - {-1}))

        redundant = 0
        if self.options.avoid_intersections:
            redundant = self._redundant(after, fits, disp, node_groups_after)
        return _Outcome(
            pair, merged, fits, disp, window_ids, delta_f, delta_d, nj_after - len(old_nodes), redundant, global_solve
        )

    def _redundant(
        self,
        after: dict[int, _Group],
        fits: dict[int, _Fit],
        disp: dict[int, np.ndarray],
        node_groups_after: dict[int, list[int]],
    ) -> int:
        """Redundant intersections that involve the arcs a merge changed."""
        gids = list(after)
        arcs = [(fits[g] if g in fits else self.fits[g]).arc.arc for g in gids]
        nodes = sorted(node_groups_after)
        node_index = {n: i for i, n in enumerate(nodes)}
        points = np.array([self.graph.junctions[n] + (disp[n] if n in disp else self.disp[n]) for n in nodes])
        arc_junctions = [[node_index[n] for n in self.constrained_nodes(after[g])] for g in gids]
        changed = [i for i, g in enumerate(gids) if g in fits]
        return len(redundant_intersections(arcs, points, arc_junctions, candidates=changed))

    def recheck_redundant(self, outcome: _Outcome) -> int:
        """Redundant intersections a cached outcome would leave against the *current* arcs.

        A cached count goes stale when any arc moves, not only the arcs of the
        outcome's window: the chosen merge is checked again before it is made.
        """
        a, b, _ = outcome.pair
        after = {g: grp for g, grp in self.groups.items() if g not in (a, b)}
        after[-1] = outcome.merged
        return self._redundant(after, outcome.fits, outcome.displacements, self.node_groups_after(a, b, outcome.merged))

    def apply(self, outcome: _Outcome) -> int:
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
        for end in (arc.start, arc.end):
            best, gap = None, math.inf
            for j in path:
                d = float(np.hypot(*(c.point_at(c.angle_of(points[j])) - end)))
                if d <= JUNCTION_TOLERANCE and d < gap:
                    best, gap = j, d
            ends.append(best)
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
    timings: dict[str, float] = {}
    start = time.perf_counter()
    groups = [
        _Group((i,), tuple(int(n) for n in graph.ends[i]), seg, bool(locked[i])) for i, seg in enumerate(graph.segments)
    ]
    # The bias comes from the longest segment after simplification (Eqn. 14), by
    # free circles as in the paper. The simplification that the loop starts
    # from then asks for a *golden* arc within 1 px: a free fit within 1 px can
    # be far off once its radius is snapped up the ladder (by up to phi). The
    # Fibonacci ladder's unit comes from the same radius (unit_from_radius).
    longest = None
    if (unit if ladder == "fibonacci" else bias) is None:
        probe = _simplify(opt, groups, opt.free_error) if simplify else groups
        longest = opt.free_circle(max(probe, key=lambda g: _length(g.points)))[1]
    opt.ladder = make_ladder(ladder, longest, bias=bias, unit=unit, exponents=opts.exponents, rounding=opts.rounding)
    if simplify:
        groups = _simplify(opt, groups, opt.golden_error)
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
        stopped = _loop(opt, levels, record, opts.tolerance, progress)
    timings["loop"] = time.perf_counter() - start
    return Progression(tuple(levels), float(opt.ladder.bias), simplified, stopped, dict(opt.stats), timings, opt.ladder)


def _loop(
    opt: _Optimizer,
    levels: list[Abstraction],
    record: dict[str, Any],
    tolerance: float,
    progress: ProgressCallback | None,
) -> str:
    """Merge the best pair until E^s would exceed ``tolerance`` (Sec. 5.2, steps 1-6).

    Scores are kept between iterations. After a merge, the pairs with the new
    segment are scored afresh; a pair whose refit window the merge changed
    keeps its old score as an estimate (the paper keeps it as it was, step 5)
    and is rescored from the current state when it comes out best: so the pair
    merged is always scored exactly (lazy greedy).
    """
    cache: dict[tuple[int, int, int], _Outcome | None] = {}
    stale: set[tuple[int, int, int]] = set()
    while True:
        pairs = opt.candidates()
        if not pairs:
            return "no mergeable pair"
        f, d, nj = opt.totals()
        n_arcs = len(opt.fits)
        while True:
            best, best_error = None, math.inf
            for pair in pairs:
                if pair not in cache or (pair in stale and cache[pair] is None):
                    cache[pair] = opt.evaluate(pair)
                    stale.discard(pair)
                out = cache[pair]
                if out is None or (out.redundant and pair not in stale):
                    continue
                nj_after = nj + out.delta_j
                error = (f + out.delta_f) / max(n_arcs - 1, 1) + ((d + out.delta_d) / nj_after if nj_after else 0.0)
                if error < best_error:
                    best, best_error = pair, error
            if best is None or best not in stale:
                break
            cache[best] = opt.evaluate(best)
            stale.discard(best)
        opt.stats["rejected_intersections"] = sum(1 for o in cache.values() if o is not None and o.redundant)
        if best is None:
            return "no mergeable pair"
        if best_error > tolerance:
            return "tolerance"
        outcome = cache[best]
        if opt.options.avoid_intersections:
            now = opt.recheck_redundant(outcome)
            if now:
                cache[best] = dataclasses.replace(outcome, redundant=now)
                continue
        opt.apply(outcome)
        changed = outcome.window | {outcome.pair[0], outcome.pair[1]}
        cache = {p: o for p, o in cache.items() if p[0] in opt.groups and p[1] in opt.groups}
        for p, o in cache.items():
            if outcome.global_solve or o is None or (o.window & changed):
                stale.add(p)
        stale &= set(cache)
        level = opt.abstraction(len(levels), record)
        levels.append(level)
        if progress:
            progress(level.level, len(level.arcs), level.similarity)


def _simplify(opt: _Optimizer, groups: list[_Group], error: Callable[[_Group], float]) -> list[_Group]:
    """Line-segment simplification (Sec. 5.4): merge neighbours one arc fits within 1 px.

    Greedy, the lowest ``error`` (mean absolute distance of the pixels to the
    fitted circle, px) first, while it is below ``SIMPLIFICATION_ERROR``. Only
    at split points (nodes of valence 2 in the graph): a real junction is left
    to the progressive loop. Returns the simplified groups.
    """
    valence = opt.graph.valence
    axis_nodes = opt.symmetry.nodes if opt.symmetry is not None else frozenset()
    current = list(groups)
    scores: dict[tuple[tuple[int, ...], tuple[int, ...]], tuple[float, _Group]] = {}
    while True:
        at: dict[int, list[int]] = {}
        for i, g in enumerate(current):
            for n in set(g.ends):
                at.setdefault(n, []).append(i)
        best, best_err = None, SIMPLIFICATION_ERROR
        for node, idx in sorted(at.items()):
            if valence[node] != 2 or len(idx) != 2 or node in axis_nodes:
                continue
            ga, gb = current[idx[0]], current[idx[1]]
            if ga.locked or gb.locked or ga is gb:
                continue
            key = (ga.segments, gb.segments)
            if key not in scores:
                merged = _merge_groups(ga, gb, node)
                scores[key] = (error(merged), merged)
            err, merged = scores[key]
            if err < best_err:
                best, best_err = (idx[0], idx[1], merged), err
        if best is None:
            return current
        i, j, merged = best
        current = [g for k, g in enumerate(current) if k not in (i, j)] + [merged]


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


def _straight_line(group: _Group) -> tuple[np.ndarray, np.ndarray] | None:
    """The end points of a straight group's line, or None if it is not straight.

    The line is the pixels' total-least-squares line; its ends are the
    projections of the group's end points on it.
    """
    if not _is_straight(group):
        return None
    pts = group.points
    mean = pts.mean(axis=0)
    direction = np.linalg.svd(pts - mean, full_matrices=False)[2][0]
    ends = mean + np.outer((pts[[0, -1]] - mean) @ direction, direction)
    return ends[0], ends[1]


def _hold(held: dict[int, list[np.ndarray]], group: _Group, nodes: Sequence[int]) -> None:
    """Record a line group's direction at each of its junctions (see ``golden``)."""
    d = group.points[-1] - group.points[0]
    u = d / max(float(np.hypot(*d)), 1e-12)
    for n in set(nodes):
        held.setdefault(n, []).append(u)


def _is_straight(group: _Group) -> bool:
    """Whether an open group is a straight stroke (the lines option).

    Its pixels, but for ``LINE_END_SKIP`` px at each end (where thinning bevels
    a thick stroke's corners towards the junction), all lie within
    ``LINE_TOLERANCE`` of their total-least-squares line.
    """
    if group.closed:
        return False
    pts = group.points
    arc_len = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(pts, axis=0).T))])
    inner = pts[(arc_len >= LINE_END_SKIP) & (arc_len <= arc_len[-1] - LINE_END_SKIP)]
    if len(inner) < 3:
        return False
    centred = inner - inner.mean(axis=0)
    normal = np.linalg.svd(centred, full_matrices=False)[2][1]  # the direction of least spread
    return float(np.max(np.abs(centred @ normal))) <= LINE_TOLERANCE


def _length(points: np.ndarray) -> float:
    return float(np.sum(np.hypot(*np.diff(points, axis=0).T)))
