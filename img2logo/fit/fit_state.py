"""The state of one run of the progressive optimization (paper Sec. 5.2-5.4), as a public value.

:class:`FitState` holds what the stages of :func:`img2logo.fit.progressive.optimize`
read and change: the segment groups (:class:`~img2logo.fit.simplification.Group`),
the golden circle and arc of each (:class:`GroupFit`), the junction
displacements d_k, the ladder, the released junctions and tangencies, and the
counts of :class:`Stats`. It fits circles (the free fit and its snapping to the
ladder, Eqn. 12, as a :class:`Seed`), solves the connectivity-constrained fit of
Eqn. 13 over a window of groups, extracts arcs and measures E^s (Eqn. 3). The
stages that drive it are their own modules and import this one, never the other
way: the merge loop (:mod:`img2logo.fit.merging`), the recovery of an initial fit
that fails (:mod:`img2logo.fit.recovery`) and the tangent joins
(:mod:`img2logo.fit.tangency`). A symmetric run hands it the mirror axis as an
:class:`AxisConstraints` (:class:`img2logo.fit.symmetry.HalfAxis` is one).

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable, Collection, Hashable, Mapping, Sequence
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any, NamedTuple, Protocol, TypeAlias, cast

import numpy as np

from ..constants import GAP_MAX, GAP_MIN, JUNCTION_TOLERANCE
from ..geometry.abstraction import Abstraction
from ..geometry.circle_fitting import fit_center, fit_circle, mean_abs_error
from ..geometry.golden_ladder import Ladder
from ..geometry.primitives import ArcJunctions, Circle, Line, line_arc
from ..options import Options
from ..segment_graph import SegmentGraph
from .arc_extraction import ArcFit, _extract, _redundant_arrays, distances_to_arcs
from .constants import CONSTRAINED_FIT_TOL, CUT_MARGIN, LINE_MIN_ANGLE, REDUNDANT_INTERSECTION_TOL, SYMMETRY_FIT_STALL
from .constrained_fit import WindowFit, fit_window
from .simplification import Group, straight_line

__all__ = ["AxisConstraints", "FitState", "FreeCircles", "GroupFit", "Seed", "Stats"]


# --------------------------------------------------------------------------- values
class Seed(NamedTuple):
    """A group's circle before the constrained fit: its centre, its radius on the ladder, its rung.

    Attributes
    ----------
    center : ndarray, shape (2,)
        The starting centre, px.
    radius : float
        The fixed radius, px: ``ladder.radius(k)`` (Eqn. 12), or ``LINE_RADIUS``
        for a straight line.
    k : int or None
        The ladder exponent; None for a straight line (held fixed in the fit).
    """

    center: np.ndarray
    radius: float
    k: int | None


@dataclass(frozen=True, eq=False)
class GroupFit:
    """A group's golden circle after the constrained fit (Eqn. 13) and its arc.

    Attributes
    ----------
    center : ndarray, shape (2,)
        The fitted centre, px.
    radius : float
        The radius, px (the seed's: radii stay on their rungs).
    k : int or None
        The ladder exponent; None for a straight line.
    arc : ArcFit
        The arc extracted on the circle and its discrete Fréchet distance to the group's pixels, px.
    """

    center: np.ndarray
    radius: float
    k: int | None
    arc: ArcFit

    @cached_property
    def seed(self) -> Seed:
        """This circle as the start of the next fit (made once: every candidate merge's window asks)."""
        return Seed(self.center, self.radius, self.k)

    @cached_property
    def arc_row(self) -> tuple[float, float, float, float, float]:
        """The arc as (cx, cy, r, theta0, sweep), the compiled redundant-intersection test's row (made once)."""
        a = self.arc.arc
        return (a.circle.cx, a.circle.cy, a.circle.r, a.theta0, a.sweep)


@dataclass
class Stats:
    """Counts of one run, reported in :attr:`img2logo.fit.progressive.Progression.stats` (as a dict, in this order).

    Attributes
    ----------
    evaluated : int
        Merge candidates evaluated (:func:`img2logo.fit.merging.evaluate`).
    local_failed : int
        Local windows (Sec. 5.4) that did not solve.
    global_solves : int
        Solves of the whole problem (:meth:`FitState.solve_whole`).
    rejected_hopeless : int
        Candidates rejected without a global solve: their own golden circle is off by more than T.
    rejected_intersections : int
        Candidates left with redundant intersections (Fig. 12) when the loop stopped.
    rejected_far_arc : int
        Candidates whose arc strays farther than ``max_arc_distance``: found by
        their fit, or before it where no circle of their radius comes that near.
    released_junctions : int
        Junctions whose connectivity constraint was given up (:func:`img2logo.fit.recovery.recover`).
    tangent_joins : int
        Smooth joins whose circles touch in the result (:mod:`img2logo.fit.tangency`).
    released_tangencies : int
        Smooth joins whose tangency was given up.
    rejected_crossing : int
        Candidates rejected because another arc runs on through their junction (an X), or
        because their arc would run on past an end of its path through a junction another arc
        runs on through (checked for the merge the loop chose, :func:`img2logo.fit.merging.merge_loop`).
    rejected_gaps : int
        Candidates left with a near-miss gap they would make (a free end brought 0.75-6 px
        from an arc; checked for the merge the loop chose, :func:`img2logo.fit.merging.merge_loop`)
        when the loop stopped.
    split_groups : int
        Groups of the line-segment simplification split into their segments again because
        their arc in A^0 made a redundant intersection (:func:`img2logo.fit.progressive.split_crossed`).
    wide_windows : int
        Merge candidates whose local window failed, refitted in the wider window of
        ``MERGE_FALLBACK_RINGS`` rings instead (:func:`img2logo.fit.merging.evaluate`).
    """

    evaluated: int = 0
    local_failed: int = 0
    global_solves: int = 0
    rejected_hopeless: int = 0
    rejected_intersections: int = 0
    rejected_far_arc: int = 0
    released_junctions: int = 0
    tangent_joins: int = 0
    released_tangencies: int = 0
    rejected_crossing: int = 0
    rejected_gaps: int = 0
    split_groups: int = 0
    wide_windows: int = 0

    def as_dict(self) -> dict[str, int]:
        """The counts by name, in the order of the fields."""
        return dataclasses.asdict(self)


class AxisConstraints(Protocol):
    """The mirror axis of a symmetric run, as the state reads it (:class:`img2logo.fit.symmetry.HalfAxis`).

    The graph is one half of a mirror-symmetric drawing, in a frame where the
    axis is the vertical line x = ``x`` px; junctions ``nodes`` stay on it, and
    a group whose end (segment, node) is in ``smooth`` has its circle centred on it.
    """

    @property
    def x(self) -> float: ...

    @property
    def nodes(self) -> frozenset[int]: ...

    @property
    def smooth(self) -> frozenset[tuple[int, int]]: ...

    def mirror(self, points: np.ndarray) -> np.ndarray:
        """Mirror images of frame points (N, 2), px."""
        ...


#: The result of a constrained fit over a window: the new fits by group, the displacements d_k by node.
Solution: TypeAlias = "tuple[dict[int, GroupFit], dict[int, np.ndarray]]"  # a string: autodoc documents it as data
#: :meth:`FitState.solve`'s ``regroup``: (node -> d_k, the fitted groups) -> (groups split anew, join -> px off
#: the line), or None to fail the fit.
Regroup: TypeAlias = (
    "Callable[[Callable[[int], np.ndarray], set[int]], tuple[Mapping[int, Group], Mapping[int, float]] | None]"
)


def on_axis(symmetry: AxisConstraints | None, group: Group) -> bool:
    """Whether ``group``'s circle is centred on the mirror axis (symmetric runs, :mod:`img2logo.fit.symmetry`).

    So it is when the group ends where a line crosses the axis square to it:
    the arc and its mirror image are then one arc through the axis.
    """
    if symmetry is None:
        return False
    ends = ((group.segments[0], group.nodes[0]), (group.segments[-1], group.nodes[-1]))
    return ends[0] in symmetry.smooth or ends[1] in symmetry.smooth


class FreeCircles:
    """The unconstrained circle fits of groups (Sec. 5.3, first stage), cached by their segments.

    Made before the ladder (the bias of Eqn. 14 comes from the longest
    segment's free circle), then handed to the :class:`FitState`.
    """

    def __init__(self, symmetry: AxisConstraints | None = None) -> None:
        self.symmetry = symmetry
        self._cache: dict[tuple[int, ...], tuple[np.ndarray, float]] = {}

    def circle(self, group: Group) -> tuple[np.ndarray, float]:
        """(centre px, radius px) of the group's free fit.

        A circle on the mirror axis is fitted to the pixels and their mirror image.
        """
        key = group.segments
        if key not in self._cache:
            pts = group.points
            if self.symmetry is not None and on_axis(self.symmetry, group):
                pts = np.vstack([pts, self.symmetry.mirror(pts)])
            if len(pts) < 3:  # two pixels: a straight piece, capped like any
                pts = np.linspace(pts[0], pts[-1], 3)
            fit = fit_circle(pts, refine=False)  # the centre is refitted after snapping
            self._cache[key] = (np.asarray(fit.center, dtype=np.float64), float(fit.radius))
        return self._cache[key]

    def error(self, group: Group) -> float:
        """Mean distance of the group's pixels to its free circle, px."""
        center, radius = self.circle(group)
        return mean_abs_error(group.points, center, radius)


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


# --------------------------------------------------------------------------- the state


def near_miss(nearest: np.ndarray) -> np.ndarray:
    """Whether free ends whose nearest other arc is ``nearest`` (m,) px away are near-miss gaps, (m,) bool.

    ``GAP_MIN`` to ``GAP_MAX`` px, as :func:`img2logo.quality.near_miss_gaps` counts them: an end the
    eye joins to the arc beside it and the logo does not.
    """
    return (nearest >= GAP_MIN) & (nearest <= GAP_MAX)


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
        #: group -> (arc, junction nodes, the :meth:`abstraction` call that last saw it, ArcJunctions
        #: by path position, the nodes' indices in that level, its ArcJunctions there, whether a
        #: level checked that arc at those points): :meth:`_topology`.
        self._topologies: dict[
            int, tuple[Any, tuple[int, ...], int, ArcJunctions, tuple[int, ...], ArcJunctions | None, bool]
        ] = {}
        #: What the last :meth:`abstraction` call read: its number, every node's displaced point, J' in order.
        self._last_level: tuple[int, np.ndarray | None, list[int]] = (0, None, [])
        self.smooth: frozenset[int] = graph.smooth_nodes() if options.tangency and options.connectivity else frozenset()
        self.loose: set[int] = set()
        #: Smooth joins the merge loop made tangent (img2logo.fit.merging): held in every later merge's window.
        self.held: set[int] = set()
        #: Tangent joins whose junction slides along the input's line (img2logo.fit.tangency):
        #: node -> its distance off the line, px, which E^s counts instead of |d_k|.
        self.off_line: dict[int, float] = {}
        #: What the merge loop keeps of one level for all its candidates (img2logo.fit.merging.level_view).
        self.merge_cache: object | None = None
        #: (merged group's segments, nodes, radius) -> whether no circle of that radius comes within
        #: the arc bound of its pixels (img2logo.fit.merging._too_far): asked again at every level.
        self.far_arcs: dict[tuple[tuple[int, ...], tuple[int, ...], float], bool] = {}

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

    def _touching(
        self, groups: Mapping[int, Group], seeds: Mapping[int, Seed], tangent: bool | Collection[int]
    ) -> dict[int, tuple[int, int]]:
        """:meth:`tangencies` of ``groups``; only those at the nodes ``tangent`` when it is a collection."""
        joins = self.tangencies(groups, seeds)
        if tangent is True:
            return joins
        return {n: pair for n, pair in joins.items() if n in cast(Collection[int], tangent)}

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
        """Unconstrained circle fit of a group (Sec. 5.3, first stage), cached (:class:`FreeCircles`)."""
        return self.circles.circle(group)

    def free_error(self, group: Group) -> float:
        """Mean distance of the group's pixels to its free circle, px."""
        return self.circles.error(group)

    def on_outline(self, group: Group) -> bool:
        """Whether ``group`` runs through a segment of the object's silhouette (:attr:`outline`)."""
        return bool(self.outline) and not self.outline.isdisjoint(group.segments)

    def arc_cap(self, group: Group) -> float | None:
        """The farthest an arc of ``group`` may lie from its pixels (discrete Fréchet), px; None: no bound.

        ``Options.arc_bound``, and on the object's silhouette (a group through a
        segment of :attr:`outline`) the tolerance T, whichever is less.
        """
        cap = self.options.arc_bound
        if self.on_outline(group):
            tolerance = float(self.options.tolerance)
            cap = tolerance if cap is None else min(cap, tolerance)
        return cap

    def outline_strays(
        self, fits: Mapping[int, GroupFit], groups: Mapping[int, Group], before: Mapping[int, GroupFit]
    ) -> bool:
        """:meth:`strays` of those of ``fits`` whose groups run on the object's silhouette (:meth:`on_outline`).

        A refit moves the junctions, so the arcs beside the ones it was for
        change too; one of the silhouette's moved farther than T is the
        silhouette cut as the refitted arc would cut it.
        """
        if not self.outline:
            return False
        return self.strays({g: f for g, f in fits.items() if self.on_outline(groups[g])}, groups, before)

    def strays(self, fits: Mapping[int, GroupFit], groups: Mapping[int, Group], before: Mapping[int, GroupFit]) -> bool:
        """Whether a refit's arc lies farther from its pixels than its :meth:`arc_cap` and than before.

        ``fits`` are the refit's arcs by group id, ``groups`` their groups, ``before`` the fits
        they replace (a group missing there is held to its cap alone).
        """
        for g, fit in fits.items():
            cap = self.arc_cap(groups[g])
            if (
                cap is not None
                and fit.arc.frechet > cap
                and (g not in before or fit.arc.frechet > before[g].arc.frechet)
            ):
                return True
        return False

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
        """Free fit snapped to the ladder (Eqn. 12): the group's :class:`Seed`.

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
    def arc_for(self, group: Group, center: np.ndarray, radius: float, k: int | None, disp: Any) -> ArcFit:
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
        fit = _extract(circle, np.asarray(group.points, dtype=np.float64), pts, self.options.arc_selection)
        return fit if k is not None else ArcFit(Line.of(fit.arc), fit.frechet)

    # ----------------------------------------------------------------- the constrained fit
    def solve(
        self,
        groups: Mapping[int, Group],
        seeds: Mapping[int, Seed],
        node_groups: Mapping[int, Sequence[int]],
        *,
        changed: Sequence[int],
        free_nodes: Sequence[int],
        fixed: set[int],
        n_groups_total: int,
        n_junctions_total: int,
        rings: int = 1,
        first_ring: int = 1,
        order: Callable[[int], Any] | None = None,
        tangent: bool | Collection[int] = False,
        cap: float | None = None,
        lines: Collection[int] | None = None,
        bound: float | None = None,
        regroup: Regroup | None = None,
        tried: set[int] | None = None,
        stop_when_stuck: bool = False,
    ) -> Solution | None:
        """Eqn. 13 over a window of ``groups`` (:func:`~img2logo.fit.constrained_fit.fit_window`), then their arcs.

        The window is the ``changed`` groups and those through ``free_nodes``,
        grown by up to ``rings`` rings (solved from ring ``first_ring`` on); the ``fixed`` groups keep their circles,
        and so do straight lines (a huge free circle is nearly singular along
        its chord: their junctions slide onto them). With ``tangent``, the
        circles of :meth:`tangencies` touch at their junctions too. With ``cap``
        (px), a merged group (id -1) whose arc strays farther than that is the
        only fit returned (see :meth:`_fits`). ``lines``: the groups whose seeds
        are straight lines (k None), when the caller knows them (a merge candidate's
        from its level's); default found in ``seeds``. With ``bound`` (px), None
        as soon as E^s (Eqn. 3) of the state with the new fits and displacements
        must exceed it, and ``regroup`` may split groups anew before their arcs
        are extracted (:meth:`_fits_within`; a tangent join's slide). None if it fails;
        then ``tried``, when given, receives the groups of the last (widest) window solved.
        ``stop_when_stuck``: that of :func:`~img2logo.fit.constrained_fit.fit_window`.
        """
        fixed = set(fixed)
        fixed.update({g for g in groups if seeds[g].k is None} if lines is None else lines)
        window = fit_window(
            _Lazy(lambda g: groups[g].points),
            _Lazy(lambda g: seeds[g].radius),
            _Lazy(lambda g: seeds[g].center),
            _Lazy(lambda g: tuple(set(self.constrained_nodes(groups[g])))),
            cast(Mapping[Hashable, Sequence[Hashable]], node_groups),
            self.graph.junctions,
            changed=changed,
            free_junctions=free_nodes,
            fixed=fixed,
            rings=rings,
            first_ring=first_ring,
            order=cast(Callable[[Hashable], Any] | None, order),
            displacements0=self.disp,
            n_circles=n_groups_total,
            n_junctions=n_junctions_total,
            connectivity=self.options.connectivity,
            constraints=lambda circles, nodes: self.axis_constraints(
                cast(Sequence[int], circles), groups, cast(Sequence[int], nodes)
            ),
            tangencies=cast(Mapping[Hashable, tuple[Hashable, Hashable]], self._touching(groups, seeds, tangent))
            if tangent
            else None,
            stop_when_stuck=stop_when_stuck,
        )
        if not window.ok:
            if tried is not None:
                tried.update(cast(Collection[int], window.circles))
            return None
        if bound is not None:
            return self._fits_within(window, groups, seeds, fixed, node_groups, bound, regroup)
        return self._fits(window, groups, seeds, fixed, cap)

    def solve_whole(
        self,
        groups: Mapping[int, Group],
        seeds: Mapping[int, Seed],
        node_groups: Mapping[int, Sequence[int]],
        *,
        n_groups_total: int,
        n_junctions_total: int,
        order: Callable[[int], Any] | None = None,
        tangent: bool | Collection[int] = False,
        cap: float | None = None,
    ) -> Solution | None:
        """:meth:`solve` over all of ``groups`` at once, every junction free (a global solve, counted).

        The initial fit of A^0, a connected part in :func:`~img2logo.fit.recovery.recover`, a merge
        whose local windows failed, the tangent refit: none of them holds a circle fixed.
        """
        self.stats.global_solves += 1
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
            cap=cap,
        )

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

    def _window_displacements(self, window: WindowFit) -> dict[int, np.ndarray]:
        """The window's d_k by node (px, (2,) each): zero for every junction without connectivity."""
        if not self.options.connectivity:
            return {cast(int, n): np.zeros(2) for n in window.junctions}
        return cast(dict[int, np.ndarray], window.displacements())

    def _refitted(
        self, window: WindowFit, groups: Mapping[int, Group], seeds: Mapping[int, Seed], fixed: set[int]
    ) -> list[int]:
        """The window's groups whose arcs are extracted anew, in its order.

        Its free groups, and the straight lines (fixed) whose junctions moved.
        """
        moved = window.free_junctions
        return [
            gid
            for gid in cast(Sequence[int], window.circles)
            if gid not in fixed or (seeds[gid].k is None and bool(moved & set(self.constrained_nodes(groups[gid]))))
        ]

    def _fits(
        self,
        window: WindowFit,
        groups: Mapping[int, Group],
        seeds: Mapping[int, Seed],
        fixed: set[int],
        cap: float | None = None,
    ) -> Solution:
        """The new fits (the window's free groups, and lines whose junctions moved) and displacements.

        With ``cap``, the merged group's (id -1) arc is extracted first, and
        when it is farther than ``cap`` px from its pixels only it is returned:
        the merge loop rejects that merge (``max_arc_distance``) and reads no other arc.
        """
        disp = self._window_displacements(window)
        todo = self._refitted(window, groups, seeds, fixed)

        def fit(gid: int) -> GroupFit:
            _, r, k = seeds[gid]
            center = window.center(gid)
            return GroupFit(center, r, k, self.arc_for(groups[gid], center, r, k, disp.__getitem__))

        first = None
        if cap is not None and -1 in todo:
            first = fit(-1)
            if first.arc.frechet > cap:
                return {-1: first}, disp  # the merge is rejected: the window's other arcs are not needed
        fits = {gid: first if gid == -1 and first is not None else fit(gid) for gid in todo}
        return fits, disp

    def _fits_within(
        self,
        window: WindowFit,
        groups: Mapping[int, Group],
        seeds: Mapping[int, Seed],
        fixed: set[int],
        node_groups: Mapping[int, Sequence[int]],
        bound: float,
        regroup: Regroup | None,
    ) -> Solution | None:
        """:meth:`_fits`, or None once E^s (Eqn. 3) of the state with them must exceed ``bound`` px.

        With ``regroup``, called with the window's displacements (node -> d_k,
        the others the state's) and the groups it fits, the groups it returns
        take the pixels it gives them before any arc is extracted (a group
        outside the window keeps its circle), and its joins are counted by their
        distance off the line (``off_line``); None from it is None. A lower bound
        of E^s is kept as the arcs are extracted: the Fréchet distances of the
        current fits left as they are and of the arcs extracted so far, over the
        number of fits, plus the displacements over the number of nodes of
        ``node_groups`` (each term at least 0). Once it exceeds ``bound`` by
        more than the rounding of the sums (``CUT_MARGIN``) so does E^s, and no
        further arc is extracted (on the clip-art fish 14 of 25 tangent tries,
        on the polar bear 258 of 358, were rejected for E^s only after every
        arc). Otherwise the fits are those :meth:`_fits` and then a re-extraction
        of the regrouped groups' arcs would give, the same numbers.
        """
        disp = self._window_displacements(window)
        todo = self._refitted(window, groups, seeds, fixed)
        now = self.disp

        def at(n: int) -> np.ndarray:
            return disp[n] if n in disp else now[n]

        new_groups: Mapping[int, Group] = {}
        off: Mapping[int, float] = {}
        if regroup is not None:
            out = regroup(at, set(todo))
            if out is None:
                return None
            new_groups, off = out
        fitted = set(todo)
        todo += [g for g in new_groups if g not in fitted]
        n_fits = len(self.fits.keys() | set(todo))
        skip = set(todo)
        running = sum(f.arc.frechet for g, f in self.fits.items() if g not in skip)
        off_line = {**self.off_line, **off}
        d = sum(off_line[n] if n in off_line else float(np.hypot(*at(n))) for n in node_groups)
        shift = d / len(node_groups) if node_groups else 0.0
        limit = bound + CUT_MARGIN * max(1.0, abs(bound))
        fits = {}
        for gid in todo:
            if running / max(n_fits, 1) + shift > limit:
                return None
            group = new_groups.get(gid, groups[gid])
            if gid in fitted:
                _, r, k = seeds[gid]
                center = window.center(gid)
                f = GroupFit(center, r, k, self.arc_for(group, center, r, k, at))
            else:  # split anew at a join of a fitted group: its circle stays
                f = self.fits[gid]
                f = replace(f, arc=self.arc_for(group, f.center, f.radius, f.k, at))
            fits[gid] = f
            running += f.arc.frechet
        if running / max(n_fits, 1) + shift > limit:
            return None
        return fits, disp

    # ----------------------------------------------------------------- topology
    def redundant_pairs(self, of: Collection[int] | None = None) -> list[tuple[int, int]]:
        """Redundant intersections (Sec. 5.2, Fig. 6c, 12) of the current arcs: the pairs of groups that meet.

        Two arcs meet redundantly at a point farther than ``REDUNDANT_INTERSECTION_TOL``
        from every junction they both pass (their constrained nodes, displaced);
        :func:`~img2logo.fit.arc_extraction.redundant_intersections` on arrays the
        state already has (the fits' arc rows, every junction's p_k + d_k at
        once), past its checks: the same test on the same numbers. Only pairs
        with a group of ``of`` (default all), in the state's order of groups;
        a pair that meets at several points appears once per point.
        """
        gids = list(self.groups)
        node_groups = self.node_groups()
        nodes = sorted(node_groups)
        index = {n: i for i, n in enumerate(nodes)}
        at = np.asarray(nodes, dtype=np.intp)
        points = (self.graph.junctions[at] + self.disp[at]).reshape(-1, 2)
        owned = [[index[n] for n in self.constrained_nodes(self.groups[g])] for g in gids]
        ptr = np.zeros(len(gids) + 1, dtype=np.int64)
        ptr[1:] = np.cumsum([len(ks) for ks in owned])
        flat = np.fromiter((k for ks in owned for k in ks), dtype=np.int64, count=int(ptr[-1]))
        rows = np.array([i for i, g in enumerate(gids) if of is None or g in of], dtype=np.int64)
        fits = [self.fits[g] for g in gids]
        params = np.array([f.arc_row for f in fits], dtype=np.float64).reshape(-1, 5)
        arcs = [f.arc.arc for f in fits]
        pairs, _ = _redundant_arrays(arcs, points, ptr, flat, rows, REDUNDANT_INTERSECTION_TOL, params)
        return [(gids[i], gids[j]) for i, j in pairs.tolist()]

    def open_ends(self) -> list[tuple[int, int]]:
        """The free ends of the current groups: (node, group) pairs, by node.

        A node of J' where exactly one group is constrained, at an end of it,
        the group not closed: the input's line ends there, and so does its arc
        (to ``JUNCTION_TOLERANCE``). At every other node of J' two arcs or more
        meet, so no end there is open; nor on a symmetric run's mirror axis,
        where the arc meets its mirror image.
        """
        axis = self.symmetry.nodes if self.symmetry is not None else frozenset()
        out = []
        for n, gs in self.node_groups().items():
            if len(gs) == 1 and n not in axis:
                group = self.groups[gs[0]]
                if not group.closed and n in group.ends:
                    out.append((n, gs[0]))
        out.sort()
        return out

    def gap_ends(self) -> set[int]:
        """The free ends (:meth:`open_ends`) that are near-miss gaps now: their nearest other arc 0.75-6 px away.

        As :func:`img2logo.quality.near_miss_gaps` counts them (``GAP_MIN`` to
        ``GAP_MAX``): an end the eye joins to the arc beside it and the logo does
        not. Measured from the junction's p_k + d_k to every other arc.
        """
        ends = self.open_ends()
        if not ends or len(self.fits) < 2:
            return set()
        gids = list(self.fits)
        col = {g: i for i, g in enumerate(gids)}
        rows = np.array([self.fits[g].arc_row for g in gids], dtype=np.float64)
        _, distances = self.end_distances(ends, rows, [col[g] for _, g in ends])
        gap = near_miss(distances.min(axis=1))
        return {n for (n, _), is_gap in zip(ends, gap.tolist(), strict=True) if is_gap}

    def end_distances(
        self, ends: Sequence[tuple[int, int]], rows: np.ndarray, own: Sequence[int] | np.ndarray
    ) -> tuple[np.ndarray, np.ndarray]:
        """Free ends (:meth:`open_ends`) and how far each lies from arcs: points (m, 2) and distances (m, n), px.

        ``rows`` (n, 5) are arcs as :attr:`GroupFit.arc_row`; ``own`` (m,) the row of
        each end's own arc, whose distance is infinite. The points are the
        junctions' p_k + d_k; distances beyond ``GAP_MAX`` may be any larger value.
        """
        nodes = np.array([n for n, _ in ends], dtype=np.intp)
        points = (self.graph.junctions[nodes] + self.disp[nodes]).reshape(-1, 2)
        distances = distances_to_arcs(points, rows, GAP_MAX)
        distances[np.arange(len(ends)), np.asarray(own, dtype=np.intp)] = np.inf
        return points, distances

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

    # ----------------------------------------------------------------- levels
    def abstraction(self, level: int, params: Mapping[str, Any]) -> Abstraction:
        """The current state as a frozen :class:`Abstraction` A^t, with its ladder and topology."""
        order = sorted(self.groups, key=lambda g: min(self.groups[g].segments))
        nodes = sorted(self.node_groups())
        junction = {n: i for i, n in enumerate(nodes)}
        displaced = self.graph.junctions + self.disp  # every node's p_k + d_k at once, (N, 2)
        points = displaced[np.asarray(nodes, dtype=np.intp)].reshape(-1, 2)
        arcs = tuple(self.fits[g].arc.arc for g in order)
        # The nodes whose point moved since the last call (all of them on the first), and
        # whether J' is numbered as then: a group's topology is read again only where they changed.
        call, before, nodes_before = self._last_level
        moved: set[int] | None = None
        if before is not None and before.shape == displaced.shape:
            moved = set(np.flatnonzero((displaced != before).any(axis=1)).tolist())
        self._last_level = (call + 1, displaced, nodes)
        renumbered = nodes != nodes_before
        topology = tuple(
            self._topology(g, arc, junction, displaced, moved, renumbered, call)
            for g, arc in zip(order, arcs, strict=True)
        )
        # Each junction's arcs in index order: the groups walked in that order (what
        # sorting each node's groups by index gives, without a sort per node).
        at_node: dict[int, list[int]] = {n: [] for n in nodes}
        for i, g in enumerate(order):
            for n in set(self.constrained_nodes(self.groups[g])):
                at_node[n].append(i)
        # The arcs an earlier level checked, with the same junction points: left out of its geometric check.
        known = tuple(self._topologies[g][6] for g in order)
        out = Abstraction._with_known(
            known,
            level=level,
            arcs=arcs,
            arc_segments=tuple(self.groups[g].segments for g in order),
            junctions=points,
            junction_arcs=tuple(map(tuple, map(at_node.__getitem__, nodes))),
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
        for g in order:  # checked now
            entry = self._topologies[g]
            if not entry[6]:
                self._topologies[g] = (*entry[:6], True)
        return out

    def _topology(
        self,
        g: int,
        arc: Any,
        junction: Mapping[int, int],
        displaced: np.ndarray,
        moved: set[int] | None,
        renumbered: bool,
        call: int,
    ) -> ArcJunctions:
        """:meth:`arc_junctions` of group ``g``'s ``arc``, its junctions numbered by ``junction`` (node -> index).

        Found in the group's own path positions and kept while its arc and its
        junctions' points (rows of ``displaced``, by node) stay the same: between
        two levels most arcs do; so is the numbered value while the numbering does.
        ``moved``: the nodes whose point changed since the last :meth:`abstraction`
        call (None: any may have), ``call`` that call's number; ``renumbered``:
        whether J' is numbered differently from then. An entry is reused only when
        that last call saw it (a group of an earlier level restored later is read again).
        """
        nodes = self.constrained_nodes(self.groups[g])
        cached = self._topologies.get(g)
        if (
            cached is None
            or cached[0] is not arc
            or cached[2] != call
            or cached[1] != nodes
            or moved is None
            or not moved.isdisjoint(nodes)
        ):
            points = displaced[list(nodes)]
            cached = (arc, nodes, call, self.arc_junctions(arc, range(len(nodes)), points), (), None, False)
        elif not renumbered and cached[5] is not None:
            self._topologies[g] = (*cached[:2], call + 1, *cached[3:])
            return cached[5]
        at = tuple(junction[n] for n in nodes)
        if cached[5] is not None and cached[4] == at:
            self._topologies[g] = (*cached[:2], call + 1, *cached[3:])
            return cached[5]
        local = cached[3]
        value = ArcJunctions(
            None if local.start is None else at[local.start],
            None if local.end is None else at[local.end],
            tuple(at[i] for i in local.through),
        )
        self._topologies[g] = (*cached[:2], call + 1, cached[3], at, value, cached[6])
        return value

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
