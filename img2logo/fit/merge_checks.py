"""What a merge must not make (Sec. 5.3, and beyond the paper), on one view of the level.

A merge of the progressive loop (:mod:`img2logo.fit.merging`) is refused, or rechecked once chosen,
when it would leave redundant intersections (:func:`redundant_after_merge`, Fig. 12), bring a free
end near an arc without meeting it (a near-miss gap, :func:`new_gaps`), run an arc on through a
junction another arc runs on through (:func:`runs_through_twice`), or make an arc certainly farther
than the bound from its pixels before any fit (:func:`too_far`). All of them read the level through
one :class:`LevelView`, made once a level (:func:`level_view`).

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import math
import operator
from collections.abc import Callable, Collection, Sequence
from dataclasses import dataclass, field
from itertools import chain
from typing import TypeAlias, cast
from weakref import WeakKeyDictionary

import numpy as np

from ..constants import GAP_MAX, JUNCTION_TOLERANCE
from .arc_extraction import distances_to_arcs
from .constants import FAR_ARC_BUDGET, FAR_ARC_MARGIN, REDUNDANT_INTERSECTION_TOL
from .fit_state import FitState
from .fit_values import GroupFit, Seed, near_miss
from .intersections import redundant_arrays
from .simplification import Group

#: A merge candidate: (group a, group b, their common end node).
Pair: TypeAlias = "tuple[int, int, int]"  # a string: autodoc documents it as data, not as a class


#: A fit's :func:`_overshoots`, by the fit (its arc was extracted through its junctions' points then:
#: a junction that moves gets its arcs extracted anew, new fits), with the group's path it was read for.
_OVERSHOOTS: WeakKeyDictionary[GroupFit, tuple[tuple[int, ...], tuple[int, ...]]] = WeakKeyDictionary()


def _overshoots(state: FitState, group: Group, fit: GroupFit, at: Callable[[int], np.ndarray]) -> tuple[int, ...]:
    """The end nodes of ``group``'s path that its arc runs on through, not ends at (an arc past its pixels).

    An arc is extracted between two of its junctions, the candidate of
    smallest Fréchet distance that contains them all (Sec. 5.3): with three or
    more junctions (a merged group's inner ones) its ends can be two inner
    junctions, and then it runs on through the path's end junctions (the
    clip-art cactus at T = 9: an arm's outline running on across the stem
    at the two nodes where it ends on it). ``at(n)``: node n's d_k.
    """
    nodes = state.constrained_nodes(group)
    if len(nodes) < 3 or group.closed:
        return ()
    hit = _OVERSHOOTS.get(fit)
    if hit is not None and hit[0] == nodes:
        return hit[1]
    # img2logo.fit.levels.arc_junctions' test for the path's two end nodes: a node is an end of the arc
    # when its projection on the circle lies within JUNCTION_TOLERANCE of one of the arc's ends.
    arc = fit.arc.arc
    cx, cy, r = arc.circle.cx, arc.circle.cy, arc.circle.r
    t1 = arc.theta0 + arc.sweep
    ends = (
        (cx + r * math.cos(arc.theta0), cy + r * math.sin(arc.theta0)),
        (cx + r * math.cos(t1), cy + r * math.sin(t1)),
    )
    out = []
    for n in (nodes[0], nodes[-1]):
        x, y = state.graph.junctions[n] + at(n)
        t = math.atan2(y - cy, x - cx)
        q = (cx + r * math.cos(t), cy + r * math.sin(t))
        if min(math.dist(q, e) for e in ends) > JUNCTION_TOLERANCE:
            out.append(n)
    _OVERSHOOTS[fit] = (nodes, tuple(out))
    return tuple(out)


def _through(state: FitState, level: LevelView) -> dict[int, set[int]]:
    """Node -> the level's groups whose arcs run on through it: their paths' inner nodes and their overshoots.

    Made once a level (kept in ``level.memo``); see :func:`_overshoots`.
    """
    hit = level.memo.get("through")
    if hit is not None:
        return cast("dict[int, set[int]]", hit)
    out = {n: set(gs) for n, gs in level.inner.items()}
    for gid, group, fit in zip(level.gids, level.groups, level.fits, strict=True):
        if fit is not None:
            for n in _overshoots(state, group, fit, state.disp.__getitem__):
                out.setdefault(n, set()).add(gid)
    level.memo["through"] = out
    return out


def runs_through_twice(
    state: FitState,
    pair: Pair,
    merged: Group,
    fits: dict[int, GroupFit],
    disp: dict[int, np.ndarray],
    level: LevelView,
) -> bool:
    """Whether after a merge two arcs run on through one junction (an X), one of them an arc the merge changed.

    The rule at the head of :func:`evaluate` reads the groups' paths (the
    merge's own node); an arc that runs on past an end of its path
    (:func:`_overshoots`) makes an X there too, with an arc whose path runs
    on through that node or another that overshoots it. Checked for the arcs
    of ``fits`` (the merged group's, id -1, and the window's refitted ones)
    against the level's other arcs and each other.
    """
    a, b, node = pair
    through = _through(state, level)
    if any(g != a and g != b for g in through.get(node, ())):
        return True  # an arc of the level overshoots the merge's node
    now = state.disp

    def at(n: int) -> np.ndarray:
        return disp[n] if n in disp else now[n]

    mine: dict[int, set[int]] = {}
    for gid, fit in fits.items():
        group = merged if gid == -1 else state.groups[gid]
        for n in _overshoots(state, group, fit, at):
            mine.setdefault(n, set()).add(gid)
    if not mine:
        return False
    for gid in fits:
        group = merged if gid == -1 else state.groups[gid]
        for n in group.nodes[1:-1]:
            mine.setdefault(n, set()).add(gid)
    changed = set(fits) | {a, b}
    for n, gs in mine.items():
        if len(gs) + sum(1 for g in through.get(n, ()) if g not in changed) > 1:
            return True
    return False


def too_far(state: FitState, merged: Group, seed: Seed, cap: float) -> bool:
    """Whether the merged group's arc is certainly farther than ``cap`` px from its pixels, before any fit.

    Its circle keeps the seed's radius r through the fit (Eqn. 12); its arc's
    discrete Fréchet distance to the pixels is at least every pixel's distance
    to the circle. When no centre brings every pixel within ``cap`` +
    ``FAR_ARC_MARGIN`` of a circle of radius r (a proof by
    :func:`img2logo._compiled.sqp.far_circle_kernel`), the fit's arc would be
    rejected as too far, or the fit fail: the candidate is rejected without it,
    with the same outcome. Made once per merged group and radius (the loop asks
    again at every level); never for a straight line (its centre is fixed far
    away).
    """
    if seed.k is None:
        return False
    key = (merged.segments, merged.nodes, float(seed.radius), float(cap))
    hit = state.far_arcs.get(key)
    if hit is None:
        from .._compiled import kernels  # loaded by the first fit already

        hit = bool(
            kernels.far_circle_kernel(
                np.ascontiguousarray(merged.points, dtype=np.float64).reshape(-1, 2),
                float(seed.radius),
                float(seed.center[0]),
                float(seed.center[1]),
                cap + FAR_ARC_MARGIN,
                FAR_ARC_BUDGET,
            )
        )
        state.far_arcs[key] = hit
    return hit


@dataclass(frozen=True, eq=False)
class LevelView:
    """What every candidate of one level reads of the current groups (made once a level, :func:`level_view`).

    ``groups``, ``fits``, ``released``: what it was made from (compared by
    identity). ``gids``: the groups in ``state.groups``'s order; ``params``
    their arcs' rows (cx, cy, r, theta0, sweep) of the compiled
    redundant-intersection test; ``flat`` their junction nodes in order, of
    arc ``owner``; ``lengths`` how many each; ``inner`` node -> the groups
    that run on through it; ``ends`` node -> the groups ending there (each
    once); ``lines`` the straight lines (k None), in ``state.fits``'s order;
    ``pos`` group -> its index in ``gids``; ``seeds`` group -> its fit's
    :class:`~img2logo.fit.fit_values.Seed` (in ``state.groups``'s order).
    """

    groups: tuple[Group, ...]
    fits: tuple[GroupFit | None, ...]
    released: int
    gids: tuple[int, ...]
    params: np.ndarray
    flat: np.ndarray
    owner: np.ndarray
    lengths: np.ndarray
    inner: dict[int, list[int]]
    ends: dict[int, list[int]]
    lines: tuple[int, ...]
    pos: dict[int, int]
    seeds: dict[int, Seed]
    #: What is made of the level on first use (:func:`_open_ends`).
    memo: dict[str, object] = field(default_factory=dict)


def level_view(state: FitState) -> LevelView:
    """The current level's :class:`LevelView`, made again when a group, a fit or a released junction changed."""
    # Compared element by element by identity in C (map, operator.is_): ~10^3 calls a run.
    gids = tuple(state.groups)
    groups = tuple(state.groups.values())
    fits = tuple(map(state.fits.get, gids))  # (a group not fitted yet: only its topology is read)
    cached = cast("LevelView | None", state.merge_cache)
    if (
        cached is not None
        and cached.gids == gids
        and cached.released == len(state.released)
        and all(map(operator.is_, cached.groups, groups))
        and all(map(operator.is_, cached.fits, fits))
    ):
        return cached
    owned = [state.constrained_nodes(g) for g in groups]
    lengths = np.array([len(ks) for ks in owned], dtype=np.int64)
    inner: dict[int, list[int]] = {}
    for gid, g in zip(gids, groups, strict=True):
        for n in g.nodes[1:-1]:
            inner.setdefault(n, []).append(gid)
    level = LevelView(
        groups,
        fits,
        len(state.released),
        gids,
        np.array([f.arc_row for f in fits if f is not None], dtype=np.float64).reshape(-1, 5),
        np.fromiter(chain.from_iterable(owned), dtype=np.int64, count=int(lengths.sum())),
        np.repeat(np.arange(len(gids), dtype=np.int64), lengths),
        lengths,
        inner,
        state.end_groups(),
        tuple(g for g, f in state.fits.items() if f.k is None),
        {g: i for i, g in enumerate(gids)},
        {g: f.seed for g, f in zip(gids, fits, strict=True) if f is not None},
    )
    state.merge_cache = level
    return level


def redundant_after_merge(
    state: FitState,
    pair: Pair,
    merged: Group,
    fits: dict[int, GroupFit],
    disp: dict[int, np.ndarray],
    level: LevelView | None = None,
) -> int:
    """Redundant intersections that involve the arcs a merge changed.

    The arcs are the level's (:func:`level_view`) without the pair's two, in the
    state's order, with the merged group's (id -1) last, as ``after`` of
    :func:`evaluate`. The junctions are indexed by node (every node of the
    graph, displaced; the window's new d_k over the state's): the kernel reads
    only the junctions the arcs own.
    """
    a, b, _ = pair
    level = level_view(state) if level is None else level
    pos = level.pos
    pa, pb = pos[a], pos[b]
    keep = np.ones(len(level.gids), dtype=bool)
    keep[[pa, pb]] = False
    # After the merge: arc i of the level is arc i - (how many of a, b come before it).
    new_pos = np.cumsum(keep) - 1
    params = np.vstack([level.params[keep], np.asarray(fits[-1].arc_row, dtype=np.float64).reshape(1, 5)])
    changed_list = []
    for g, f in fits.items():
        if g == -1:
            continue
        i = int(new_pos[pos[g]])
        params[i] = f.arc_row
        changed_list.append(i)
    changed_list.append(len(params) - 1)
    changed = np.array(sorted(changed_list), dtype=np.int64)
    merged_nodes = state.constrained_nodes(merged)
    lengths = np.append(level.lengths[keep], len(merged_nodes))
    ptr = np.zeros(len(lengths) + 1, dtype=np.int64)
    np.cumsum(lengths, out=ptr[1:])
    flat = np.concatenate(
        [level.flat[(level.owner != pa) & (level.owner != pb)], np.array(merged_nodes, dtype=np.int64)]
    )
    junctions = state.graph.junctions
    points = junctions + state.disp
    if disp:
        moved = np.fromiter(disp, dtype=np.intp, count=len(disp))
        points[moved] = junctions[moved] + np.array(list(disp.values()), dtype=np.float64).reshape(-1, 2)
    pairs, _ = redundant_arrays(params, points, ptr, flat, changed, REDUNDANT_INTERSECTION_TOL)
    return len(pairs)


@dataclass(frozen=True, eq=False)
class _OpenEnds:
    """A level's open ends and how far each lies from every arc (:func:`_open_ends`).

    ``nodes``: the free ends (:func:`open_ends`); ``owners`` (m,): the group
    each is an end of; ``columns`` (m,): that group's position in the level's
    ``gids``; ``points`` (m, 2): the junctions' p_k + d_k, px; ``distances``
    (m, n): from each to each arc of the level, px (infinite to its own);
    ``gap`` (m,): whether it is a near-miss gap now (its nearest other arc
    ``GAP_MIN`` to ``GAP_MAX`` px away, as :func:`img2logo.quality.near_miss_gaps`
    counts it).
    """

    nodes: list[int]
    owners: np.ndarray
    columns: np.ndarray
    points: np.ndarray
    distances: np.ndarray
    gap: np.ndarray


def _open_ends(state: FitState, level: LevelView) -> _OpenEnds:
    """The level's :class:`_OpenEnds`, made once a level (kept in ``level.memo``)."""
    hit = level.memo.get("open")
    if hit is not None:
        return cast(_OpenEnds, hit)
    found = open_ends(state)
    nodes = [n for n, _ in found]
    owners = np.array([g for _, g in found], dtype=np.int64)
    columns = np.array([level.pos[g] for _, g in found], dtype=np.intp)
    points, distances = end_distances(state, found, level.params, columns)
    nearest = distances.min(axis=1) if distances.shape[1] else np.full(len(nodes), np.inf)
    out = _OpenEnds(nodes, owners, columns, points, distances, near_miss(nearest))
    level.memo["open"] = out
    return out


def new_gaps(
    state: FitState,
    pair: Pair,
    fits: dict[int, GroupFit],
    disp: dict[int, np.ndarray],
    level: LevelView | None = None,
) -> int:
    """Near-miss gaps a merge would make: open ends it brings ``GAP_MIN`` to ``GAP_MAX`` px from an arc.

    A near-miss gap is a near intersection: an end of the input's line that
    the logo shows a hair's breadth from another arc, which the eye closes and
    the logo does not (:func:`img2logo.quality.near_miss_gaps`). Like a
    redundant intersection (Fig. 12), the merge loop must not make one that
    the input does not have: a merge's refit moves its window's junctions (a
    free end too, by its d_k) and arcs, and can move a free end towards an arc
    that ran past it farther than ``GAP_MAX`` (on scikit-image's coffee cup a
    short branch beside the cup's rim, its tip 6.3 px from the rim's arc, 4.4
    px after the merge that carried its arc on through the branch point). An
    open end (:class:`_OpenEnds`) counts when it is a gap after the merge and
    was not one before: a gap the level has already (a line of the input that
    ends that near another) is no reason to refuse a merge. After the merge an
    end's nearest arc is the nearer of the level's arcs the merge leaves as
    they are (the level's distances; those of an end the refit moved are
    measured again) and the arcs of ``fits`` (the merged group's, id -1, and
    the window's refitted ones).
    """
    level = level_view(state) if level is None else level
    ends = _open_ends(state, level)
    if not ends.nodes:
        return 0
    a, b, _ = pair
    pos = level.pos
    stale = [pos[a], pos[b], *(pos[g] for g in fits if g != -1)]
    moved = [i for i, n in enumerate(ends.nodes) if n in disp]
    old = ends.distances.copy()
    points = ends.points
    if moved:
        points = points.copy()
        at = np.array([ends.nodes[i] for i in moved], dtype=np.intp)
        points[moved] = state.graph.junctions[at] + np.array([disp[int(n)] for n in at]).reshape(-1, 2)
        old[moved] = distances_to_arcs(points[moved], level.params, GAP_MAX)
        old[moved, ends.columns[moved]] = np.inf
    old[:, stale] = np.inf
    nearest = old.min(axis=1)
    gids = np.fromiter(fits, dtype=np.int64, count=len(fits))
    new = distances_to_arcs(points, np.array([f.arc_row for f in fits.values()], dtype=np.float64), GAP_MAX)
    owners = np.where((ends.owners == a) | (ends.owners == b), -1, ends.owners)
    new[owners[:, None] == gids[None, :]] = np.inf
    nearest = np.minimum(nearest, new.min(axis=1))
    return int(np.count_nonzero(near_miss(nearest) & ~ends.gap))


def redundant_pairs(state: FitState, of: Collection[int] | None = None) -> list[tuple[int, int]]:
    """Redundant intersections (Sec. 5.2, Fig. 6c, 12) of the current arcs: the pairs of groups that meet.

    Two arcs meet redundantly at a point farther than ``REDUNDANT_INTERSECTION_TOL``
    from every junction they both pass (their constrained nodes, displaced);
    :func:`~img2logo.fit.intersections.redundant_intersections` on arrays the
    state already has (the fits' arc rows, every junction's p_k + d_k at
    once), past its checks: the same test on the same numbers. Only pairs
    with a group of ``of`` (default all), in the state's order of groups;
    a pair that meets at several points appears once per point.
    """
    gids = tuple(state.groups)
    at, ptr, flat = _incidence(state, gids)
    points = (state.graph.junctions[at] + state.disp[at]).reshape(-1, 2)
    rows = np.array([i for i, g in enumerate(gids) if of is None or g in of], dtype=np.int64)
    fits = [state.fits[g] for g in gids]
    params = np.array([f.arc_row for f in fits], dtype=np.float64).reshape(-1, 5)
    pairs, _ = redundant_arrays(params, points, ptr, flat, rows, REDUNDANT_INTERSECTION_TOL)
    return [(gids[i], gids[j]) for i, j in pairs.tolist()]


#: :func:`_incidence` of a state, with the node_groups and the groups' order it was made for.
_INCIDENCE: WeakKeyDictionary[FitState, tuple[dict[int, list[int]], tuple[int, ...], tuple]] = WeakKeyDictionary()


def _incidence(state: FitState, gids: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The nodes of J' (sorted, as indices into the graph's), and each group's of ``gids``: (at, ptr, flat).

    Group ``gids[i]`` passes the nodes ``at[flat[ptr[i]:ptr[i + 1]]]`` (its constrained nodes in path
    order). Made again when :meth:`FitState.node_groups` was (the groups' paths or the released
    junctions changed) or the groups' order did: the tangent pass asks on every try.
    """
    node_groups = state.node_groups()
    hit = _INCIDENCE.get(state)
    if hit is not None and hit[0] is node_groups and hit[1] == gids:
        return hit[2]
    nodes = sorted(node_groups)
    index = {n: i for i, n in enumerate(nodes)}
    at = np.asarray(nodes, dtype=np.intp)
    owned = [[index[n] for n in state.constrained_nodes(state.groups[g])] for g in gids]
    ptr = np.zeros(len(gids) + 1, dtype=np.int64)
    ptr[1:] = np.cumsum([len(ks) for ks in owned])
    flat = np.fromiter((k for ks in owned for k in ks), dtype=np.int64, count=int(ptr[-1]))
    _INCIDENCE[state] = (node_groups, gids, (at, ptr, flat))
    return at, ptr, flat


def open_ends(state: FitState) -> list[tuple[int, int]]:
    """The free ends of the current groups: (node, group) pairs, by node.

    A node of J' where exactly one group is constrained, at an end of it,
    the group not closed: the input's line ends there, and so does its arc
    (to ``JUNCTION_TOLERANCE``). At every other node of J' two arcs or more
    meet, so no end there is open; nor on a symmetric run's mirror axis,
    where the arc meets its mirror image.
    """
    axis = state.symmetry.nodes if state.symmetry is not None else frozenset()
    out = []
    for n, gs in state.node_groups().items():
        if len(gs) == 1 and n not in axis:
            group = state.groups[gs[0]]
            if not group.closed and n in group.ends:
                out.append((n, gs[0]))
    out.sort()
    return out


def gap_ends(state: FitState) -> set[int]:
    """The free ends (:func:`open_ends`) that are near-miss gaps now: their nearest other arc 0.75-6 px away.

    As :func:`img2logo.quality.near_miss_gaps` counts them (``GAP_MIN`` to
    ``GAP_MAX``): an end the eye joins to the arc beside it and the logo does
    not. Measured from the junction's p_k + d_k to every other arc.
    """
    ends = open_ends(state)
    if not ends or len(state.fits) < 2:
        return set()
    gids = list(state.fits)
    col = {g: i for i, g in enumerate(gids)}
    rows = np.array([state.fits[g].arc_row for g in gids], dtype=np.float64)
    _, distances = end_distances(state, ends, rows, [col[g] for _, g in ends])
    gap = near_miss(distances.min(axis=1))
    return {n for (n, _), is_gap in zip(ends, gap.tolist(), strict=True) if is_gap}


def end_distances(
    state: FitState, ends: Sequence[tuple[int, int]], rows: np.ndarray, own: Sequence[int] | np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Free ends (:func:`open_ends`) and how far each lies from arcs: points (m, 2) and distances (m, n), px.

    ``rows`` (n, 5) are arcs as :attr:`GroupFit.arc_row`; ``own`` (m,) the row of
    each end's own arc, whose distance is infinite. The points are the
    junctions' p_k + d_k; distances beyond ``GAP_MAX`` may be any larger value.
    """
    nodes = np.array([n for n, _ in ends], dtype=np.intp)
    points = (state.graph.junctions[nodes] + state.disp[nodes]).reshape(-1, 2)
    distances = distances_to_arcs(points, rows, GAP_MAX)
    distances[np.arange(len(ends)), np.asarray(own, dtype=np.intp)] = np.inf
    return points, distances
