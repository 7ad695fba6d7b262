"""The state of one run of the progressive optimization (paper Sec. 5.2-5.4), as a public value.

:class:`FitState` holds what the stages of :func:`img2logo.fit.progressive.optimize`
read and change: the segment groups (:class:`~img2logo.fit.simplification.Group`),
the golden circle and arc of each, the junction displacements d_k, the ladder,
the released junctions and tangencies, and the counts of a run (the values of
:mod:`img2logo.fit.fit_values`). It fits circles (the free fit and its snapping
to the ladder, Eqn. 12), extracts arcs and measures E^s (Eqn. 3). The stages
that drive it are their own modules and import this one, never the other way:
the constrained fit over a window of groups (:mod:`img2logo.fit.window_solve`),
the merge loop (:mod:`img2logo.fit.merging`) and what a merge must not make
(:mod:`img2logo.fit.merge_checks`), the silhouette's arcs
(:mod:`img2logo.fit.outline`), the recovery of an initial fit that fails
(:mod:`img2logo.fit.recovery`) and the tangent joins (:mod:`img2logo.fit.tangency`).
A symmetric run hands it the mirror axis as an :class:`~img2logo.fit.fit_values.AxisConstraints`
(:class:`img2logo.fit.symmetry.HalfAxis` is one).

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import math
from collections.abc import Collection, Mapping, Sequence
from typing import Any, cast

import numpy as np

from ..geometry.circle_fitting import fit_center, mean_abs_error
from ..geometry.golden_ladder import Ladder
from ..geometry.primitives import Circle, Line, line_arc
from ..options import Options
from ..segment_graph import SegmentGraph
from .arc_extraction import ArcFit, _extract
from .constants import CONSTRAINED_FIT_TOL, LINE_MIN_ANGLE, SYMMETRY_FIT_STALL
from .fit_values import AxisConstraints, FreeCircles, GroupFit, Seed, Stats, on_axis
from .simplification import Group, straight_line

__all__ = ["FitState"]


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


# --------------------------------------------------------------------------- the state


class FitState:
    """The state of one run of the progressive optimization: groups, their fits, the displacements.

    Parameters
    ----------
    graph : SegmentGraph
        The line-segment graph L = {S, J} (for a symmetric run, the half graph).
    options : Options
        The settings and switches of the run.
    ladder : GoldenLadder or FibonacciLadder
        The ladder the radii are snapped to (Eqn. 12).
    symmetry : AxisConstraints, optional
        The mirror axis of a symmetric run.
    circles : FreeCircles, optional
        The free circle fits made so far (with the same ``symmetry``); default none.

    Attributes
    ----------
    groups : dict of int to Group
        The current groups by id (ids are never reused).
    fits : dict of int to GroupFit
        Each group's golden circle and arc.
    disp : ndarray, shape (J, 2)
        The displacement d_k of every node of the graph, px.
    released : set of int
        Junctions whose connectivity constraint was given up (:func:`img2logo.fit.recovery.recover`).
    smooth : frozenset of int
        Nodes where two groups ending there must touch (tangent joins, beyond the
        paper): where the input's line runs on smoothly (:meth:`SegmentGraph.smooth_nodes`).
    loose : set of int
        Smooth nodes whose tangency was given up (:mod:`img2logo.fit.tangency`): a kink is left there.
    stats : Stats
        The counts of the run.
    """

    def __init__(
        self,
        graph: SegmentGraph,
        options: Options,
        ladder: Ladder,
        symmetry: AxisConstraints | None = None,
        *,
        circles: FreeCircles | None = None,
    ) -> None:
        self.graph = graph
        self.options = options
        self.ladder = ladder
        self.symmetry = symmetry
        self.circles = FreeCircles(symmetry) if circles is None else circles
        self.groups: dict[int, Group] = {}
        self.fits: dict[int, GroupFit] = {}
        self.disp = np.zeros((graph.n_junctions, 2))
        self.next_id = 0
        self.stats = Stats()
        #: The segments of the object's silhouette: an arc through any of them is held to the tolerance
        #: (:func:`img2logo.fit.progressive.optimize`'s ``silhouette``).
        self.outline: frozenset[int] = frozenset()
        self.released: set[int] = set()
        self._path_cache: dict[tuple[int, ...], tuple[int, ...]] = {}
        self._constrained: dict[tuple[int, ...], tuple[int, ...]] = {}
        #: group path -> (the junctions' rest points it was measured on, :meth:`reach`).
        self._reach: dict[tuple[int, ...], tuple[np.ndarray, float]] = {}
        #: group path -> (released junctions when made, straight_line, the arc's Seed or None): :meth:`golden`.
        self._golden: dict[tuple[tuple[int, ...], tuple[int, ...]], tuple[int, Any, Seed | None]] = {}
        #: group path -> (released junctions when made, :meth:`golden_error`).
        self._golden_error: dict[tuple[tuple[int, ...], tuple[int, ...]], tuple[int, float]] = {}
        self._node_groups: dict[int, list[int]] | None = None
        self.smooth: frozenset[int] = graph.smooth_nodes() if options.tangency and options.connectivity else frozenset()
        self.loose: set[int] = set()
        #: Smooth joins the merge loop made tangent (img2logo.fit.merging): held in every later merge's window.
        self.held: set[int] = set()
        #: Tangent joins whose junction slides along the input's line (img2logo.fit.tangency):
        #: node -> its distance off the line, px, which E^s counts instead of |d_k|.
        self.off_line: dict[int, float] = {}
        #: What the merge loop keeps of one level for all its candidates (img2logo.fit.merge_checks.level_view).
        self.merge_cache: object | None = None
        #: (merged group's segments, nodes, radius, arc bound) -> whether no circle of that radius comes
        #: within the bound of its pixels (img2logo.fit.merge_checks.too_far): asked again at every level.
        self.far_arcs: dict[tuple[tuple[int, ...], tuple[int, ...], float, float], bool] = {}
        #: Merge candidates (a, b, node) whose merged arc too_far rejected -> (group a, group b, released
        #: junctions then, T then): the same two groups are rejected again without being merged while T
        #: is the same (past T it grows: img2logo.fit.progressive) (img2logo.fit.merging).
        self.far_pairs: dict[tuple[int, int, int], tuple[Group, Group, int, float]] = {}

    # ----------------------------------------------------------------- groups and nodes
    def add_group(self, group: Group) -> int:
        """Add ``group`` (without a fit yet); its new id."""
        gid = self.next_id
        self.next_id += 1
        self.groups[gid] = group
        self._node_groups = None
        return gid

    def merge(
        self, a: int, b: int, merged: Group, fits: Mapping[int, GroupFit], displacements: Mapping[int, np.ndarray]
    ) -> int:
        """Carry out a merge: ``merged`` replaces groups ``a`` and ``b``; its new id.

        ``fits`` are the new fits of the changed groups (key -1: the merged
        group), ``displacements`` the new d_k by node (:func:`img2logo.fit.merging.evaluate`).
        """
        del self.groups[a], self.groups[b]
        self._node_groups = None
        self.fits.pop(a)
        self.fits.pop(b)
        gid = self.add_group(merged)
        for g, fit in fits.items():
            self.fits[gid if g == -1 else g] = fit
        for n, d in displacements.items():
            self.disp[n] = d
        return gid

    def invalidate(self) -> None:
        """Forget what is cached about the groups (after they were replaced wholesale)."""
        self._node_groups = None

    def release(self, node: int) -> None:
        """Give up the connectivity constraint at junction ``node`` (:func:`~img2logo.fit.recovery.recover`)."""
        self.released.add(node)
        self._node_groups = None
        self._constrained.clear()
        self._reach.clear()

    def tangencies(self, groups: Mapping[int, Group], seeds: Mapping[int, Seed]) -> dict[int, tuple[int, int]]:
        """Smooth node -> the two groups of ``groups`` that end there, whose circles must touch at it.

        A tangent join (beyond the paper): at a node of valence 2 where the
        input's line turns by less than ``SMOOTH_JOIN_ANGLE``
        (:meth:`SegmentGraph.smooth_nodes`), two different groups end, and the
        constrained fit makes their circles touch there (``tangents`` of
        :func:`~img2logo.fit.constrained_fit.fit_constrained`). Not at a released
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
            if seeds[gids[0]].k is None and seeds[gids[1]].k is None:
                continue
            out[n] = (gids[0], gids[1])
        return out

    def touching_joins(self, nodes: Collection[int]) -> set[int]:
        """The smooth joins among ``nodes`` whose two circles touch there now, to ``CONSTRAINED_FIT_TOL`` px."""
        seeds = {g: f.seed for g, f in self.fits.items()}
        out = set()
        for n, (a, b) in self.tangencies(self.groups, seeds).items():
            if n not in nodes:
                continue
            p = self.graph.junctions[n] + self.disp[n]
            u, v = seeds[a].center - p, seeds[b].center - p
            sin = abs(float(u[0] * v[1] - u[1] * v[0])) / max(float(np.hypot(*u) * np.hypot(*v)), 1e-300)
            if sin * min(seeds[a].radius, seeds[b].radius) <= CONSTRAINED_FIT_TOL:
                out.add(n)
        return out

    def constrained_nodes(self, group: Group) -> tuple[int, ...]:
        """Nodes where ``group``'s arc must pass (its J' part), in path order.

        The two ends, and inner nodes where other segments meet (valence >= 3
        in the graph, Sec. 6.2) unless only the ends are constrained (Fig. 11d).
        """
        # Tens of thousands of calls a run: cached by the node path, forgotten when a junction is released.
        hit = self._constrained.get(group.nodes)
        if hit is None:
            nodes = self.path_nodes(group)
            hit = tuple(n for n in nodes if n not in self.released) if self.released else nodes
            self._constrained[group.nodes] = hit
        return hit

    def path_nodes(self, group: Group) -> tuple[int, ...]:
        """:meth:`constrained_nodes` with the released junctions (see :meth:`release`), in path order."""
        # Called for every group of every window of every candidate merge: cached by the
        # group's node path, which is all the answer depends on.
        hit = self._path_cache.get(group.nodes)
        if hit is None:
            hit = self._path_cache[group.nodes] = self._path_nodes(group)
        return hit

    def _path_nodes(self, group: Group) -> tuple[int, ...]:
        n = group.nodes
        inner: tuple[int, ...] = ()
        if self.options.inner_junctions:
            valence = self.graph.valence
            inner = tuple(m for m in n[1:-1] if valence[m] >= 3)
        return (n[0], *inner) if group.closed else (n[0], *inner, n[-1])

    def node_groups(self, groups: Mapping[int, Group] | None = None) -> dict[int, list[int]]:
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
        """Whether ``group``'s circle is centred on the mirror axis (see :func:`on_axis`)."""
        return on_axis(self.symmetry, group)

    def free_circle(self, group: Group) -> tuple[np.ndarray, float]:
        """Unconstrained circle fit of a group (Sec. 5.3, first stage), cached (``circles``, a FreeCircles)."""
        return self.circles.circle(group)

    def free_error(self, group: Group) -> float:
        """Mean distance of the group's pixels to its free circle, px."""
        return self.circles.error(group)

    def golden_error(self, group: Group) -> float:
        """Mean distance of the group's pixels to its golden circle, px.

        The free radius snapped to the ladder (Eqn. 12), the centre then placed
        where it fits best for that fixed radius.
        """
        # Cached by the group's path as its seed is (the simplification and the merge loop's
        # hopeless test ask again for the same groups); forgotten when a junction is released.
        key = (group.segments, group.nodes)
        hit = self._golden_error.get(key)
        if hit is not None and hit[0] == len(self.released):
            return hit[1]
        center, radius, _ = self.golden(group)
        pts = group.points
        if self.symmetry is not None and self.on_axis(group):  # the arc runs on into its mirror image
            pts = np.vstack([pts, self.symmetry.mirror(pts)])
        error = mean_abs_error(pts, fit_center(pts, radius, center), radius)
        self._golden_error[key] = (len(self.released), error)
        return error

    def golden(self, group: Group, *, held: Mapping[int, list[np.ndarray]] | None = None) -> Seed:
        """Free fit snapped to the ladder (Eqn. 12): the group's :class:`~img2logo.fit.fit_values.Seed`.

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
        # Cached by the group's path (its pixels are its segments'): every candidate merge
        # of a level, and its rescoring, asks for the merged group's seed again.
        key = (group.segments, group.nodes)
        hit = self._line_hit(group, key)
        line = hit[1]
        if line is not None and held is not None:
            u = (line[1] - line[0]) / np.hypot(*(line[1] - line[0]))
            for n in self.constrained_nodes(group):
                others = held.get(n, [])
                if len(others) >= 2 or any(abs(float(u @ v)) > math.cos(LINE_MIN_ANGLE) for v in others):
                    line = None
                    break
        if line is not None:
            arc = line_arc(line[0], line[1])
            return Seed(arc.circle.center, arc.circle.r, None)
        if hit[2] is None:
            hit = self._golden[key] = (hit[0], hit[1], self._golden_arc(group))
        seed = hit[2]
        if seed is None:  # never: it was just made
            raise RuntimeError("no golden seed was made")
        return seed

    def _line_hit(self, group: Group, key: tuple[tuple[int, ...], tuple[int, ...]]) -> tuple[int, Any, Seed | None]:
        """The :meth:`golden` cache's entry of ``group`` (``key``: its path), with its straight line found."""
        hit = self._golden.get(key)
        if hit is None or hit[0] != len(self.released):
            line = straight_line(group) if self.options.lines and not self.on_axis(group) else None
            hit = self._golden[key] = (len(self.released), line, None)
        return hit

    def straight(self, group: Group) -> bool:
        """Whether ``group`` is a straight line, unless lines held at its junctions refuse it (:meth:`golden`)."""
        return self._line_hit(group, (group.segments, group.nodes))[1] is not None

    def _golden_arc(self, group: Group) -> Seed:
        """The free fit snapped to the ladder (Eqn. 12) as a circle, not a line: :meth:`golden`'s arc."""
        center, radius = self.free_circle(group)
        k, r = self.ladder.snap(radius)
        reach = self.reach(group)
        if r < reach:
            k, r = _rung_reaching(self.ladder, k, reach)
        if self.on_axis(group):
            center = self.axis_seed(group, center, r)
        return Seed(center, r, k)

    def axis_seed(self, group: Group, center: np.ndarray, radius: float) -> np.ndarray:
        """A circle centred on the mirror axis that passes through the group's end on it (the fit's start).

        On the axis, on the side of the free fit's centre: the snapped radius
        would otherwise leave it far from its junction.
        """
        sym = cast(AxisConstraints, self.symmetry)  # called only for a group on the axis
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
        # Asked again for the same groups at every level the tangent passes try: cached by the
        # node path while the rest points are the same array (a biarc's start moves them).
        junctions = self.graph.junctions
        hit = self._reach.get(group.nodes)
        if hit is not None and hit[0] is junctions:
            return hit[1]
        nodes = self.constrained_nodes(group)
        reach = 0.0
        if len(nodes) >= 2:
            pts = junctions[list(nodes)]
            reach = 0.5 * float(np.max(np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))))
        self._reach[group.nodes] = (junctions, reach)
        return reach

    # ----------------------------------------------------------------- arcs
    def arc_for(
        self, group: Group, center: np.ndarray, radius: float, k: int | None, disp: Any, memo: dict | None = None
    ) -> ArcFit:
        """Extract the arc of ``group`` on its circle through its displaced junctions.

        ``memo``: the arcs extracted before, by the group's pixel array (the same object), the circle
        and the arc's ends, kept and read there (the same arc again: extraction is a function of them).
        """
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
        key = None
        if memo is not None:
            key = (id(group.points), circle.k, np.array([circle.cx, circle.cy, circle.r]).tobytes(), pts.tobytes())
            hit = memo.get(key)
            if hit is not None and hit[0] is group.points:  # the array is held there: its id is not reused
                return hit[1]
        fit = _extract(circle, np.asarray(group.points, dtype=np.float64), pts, self.options.arc_selection)
        out = fit if k is not None else ArcFit(Line.of(fit.arc), fit.frechet)
        if key is not None:
            cast(dict, memo)[key] = (group.points, out)
        return out

    def axis_constraints(
        self, gids: Sequence[int], groups: Mapping[int, Group], node_list: Sequence[int]
    ) -> dict[str, Any]:
        """Keywords of :func:`~img2logo.fit.constrained_fit.fit_constrained`: circles and junctions held on the axis."""
        sym = self.symmetry
        if sym is None:
            return {}
        return {
            "axis": sym.x,
            "axis_circles": [i for i, g in enumerate(gids) if self.on_axis(groups[g])],
            "axis_junctions": [i for i, n in enumerate(node_list) if n in sym.nodes],
            "stall": SYMMETRY_FIT_STALL,
        }

    # ----------------------------------------------------------------- errors
    def totals(self) -> tuple[float, float, int]:
        """(sum of Fréchet distances, sum of |d_k| over J', |J'|)."""
        nodes = list(self.node_groups())
        f = sum(fit.arc.frechet for fit in self.fits.values())
        d = float(np.sum(np.linalg.norm(self.disp[nodes], axis=1))) if nodes else 0.0
        for n, off in self.off_line.items():  # a tangent join slid along a smooth line (img2logo.fit.tangency)
            d += off - float(np.hypot(*self.disp[n]))
        return f, d, len(nodes)

    def similarity(self) -> float:
        """E^s (Eqn. 3): mean Fréchet distance of the arcs plus mean junction displacement."""
        f, d, nj = self.totals()
        return f / max(len(self.fits), 1) + (d / nj if nj else 0.0)
