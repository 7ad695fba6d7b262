"""Merging (paper Sec. 5.2, steps 1-6): candidate pairs, their evaluation, the greedy loop.

Neighbouring groups (:mod:`img2logo.fit.simplification`) of the progressive
optimization's state (:class:`img2logo.fit.fit_state.FitState`) are merged one pair at a
time, the pair with the lowest merge error first, until the similarity error
E^s (Eqn. 3) would exceed the tolerance T (:func:`merge_loop`).
:func:`candidates` lists the pairs; :func:`evaluate` merges one tentatively,
refits its local window (Sec. 5.4; the global problem when the window fails)
and scores it as the E^s the abstraction would have after it, with the rules
that reject a merge (an X through a junction, a hopeless window, an arc
farther than the bound, redundant intersections, Fig. 12). The merge the loop
chooses is checked once more before it is made, against the current arcs: for
redundant intersections, for near-miss gaps it would make (a free end brought
0.75-6 px from an arc, :func:`new_gaps`) and for an arc running on past the
end of its path through a junction another arc runs on through (:func:`_runs_through_twice`).

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import dataclasses
import math
import operator
from collections.abc import Callable
from dataclasses import dataclass, field
from itertools import chain
from typing import TypeAlias, cast
from weakref import WeakKeyDictionary

import numpy as np

from ..constants import GAP_MAX, JUNCTION_TOLERANCE
from ..geometry.primitives import Arc
from .arc_extraction import _redundant_arrays, distances_to_arcs
from .constants import FAR_ARC_BUDGET, FAR_ARC_MARGIN, MERGE_FALLBACK_RINGS, REDUNDANT_INTERSECTION_TOL
from .fit_state import FitState, GroupFit, Seed, Solution, near_miss
from .simplification import Group, hold_line, merge_groups

#: Called by :func:`merge_loop` after every merge, with the state (now one level further).
MergeCallback: TypeAlias = Callable[[FitState], None]

#: Why :func:`merge_loop` stopped when its time budget ran out.
TIME_BUDGET_STOP = "time budget"

#: A merge candidate: (group a, group b, their common end node).
Pair: TypeAlias = "tuple[int, int, int]"  # a string: autodoc documents it as data, not as a class


@dataclass(frozen=True, eq=False)
class MergeOutcome:
    """What merging one candidate pair would give (:func:`evaluate`)."""

    pair: Pair  # (group a, group b, shared node)
    merged: Group
    fits: dict[int, GroupFit]  # new fits of the changed groups; key -1 is the merged group
    displacements: dict[int, np.ndarray]  # node -> new d_k
    window: frozenset[int]  # groups whose state this outcome depends on
    delta_f: float  # change of the sum of Fréchet distances
    delta_d: float  # change of the sum of |d_k| over J'
    delta_j: int  # change of |J'|
    redundant: int  # redundant intersections the merge would leave
    global_solve: bool
    gaps: int = 0  # near-miss gaps the merge would make (open ends it brings 0.75-6 px from an arc): see merge_loop


def candidates(state: FitState) -> list[Pair]:
    """Mergeable pairs (a, b, node): two groups with a common end (Sec. 5.2).

    Neither locked (Sec. 7) nor closed; not at a node on a symmetric run's
    mirror axis. In the order of the nodes, then of the groups (a < b).
    """
    out: list[Pair] = []
    sym = state.symmetry
    for node, gids in sorted(level_view(state).ends.items()):  # the level's, made once for its candidates too
        if sym is not None and node in sym.nodes:
            continue  # an arc never runs on through the mirror axis: its mirror image would cross it
        ok = [g for g in sorted(gids) if not state.groups[g].locked and not state.groups[g].closed]
        out.extend((a, b, node) for i, a in enumerate(ok) for b in ok[i + 1 :])
    return out


def evaluate(state: FitState, pair: Pair, tried: set[int] | None = None) -> MergeOutcome | None:
    """Merge ``pair`` tentatively, refit, and score it; None if infeasible.

    ``tried``: when given and the refit fails (its windows, or the global
    problem, have no solution), it receives the groups of the state whose
    circles the windows held (the pair's two for the merged group): the
    problem they solved, but for the weights 1/|A| and 1/|J'|, stays as it is
    until a merge changes one of them (:func:`merge_loop`).
    """
    state.stats.evaluated += 1
    a, b, node = pair
    level = level_view(state)
    # Two arcs that both run on through one junction cross there (an X): one
    # of them ends at the junction instead, so that arcs meet only at their
    # ends or where one ends on the other (a T), and no crossing is left.
    if any(g != a and g != b for g in level.inner.get(node, ())):
        state.stats.rejected_crossing += 1
        return None
    merged = merge_groups(state.groups[a], state.groups[b], node)
    after = dict(state.groups)  # in the state's order, the merged group last
    del after[a], after[b]
    after[-1] = merged
    n_groups = len(after)
    node_groups_after = state.node_groups_after(a, b, merged)
    nj_after = len(node_groups_after)
    seeds: dict[int, Seed] = dict(level.seeds)
    del seeds[a], seeds[b]
    # The lines' directions at their junctions (but a's and b's): read only when the merged group is straight.
    held: dict[int, list[np.ndarray]] = {}
    if state.straight(merged):
        for g in level.lines:
            if g != a and g != b:
                hold_line(held, state.groups[g], state.constrained_nodes(state.groups[g]))
    seeds[-1] = state.golden(merged, held=held)
    cap = state.arc_cap(merged)
    if cap is not None and _too_far(state, merged, seeds[-1], cap):
        # Every path below would end in the rejection of the fit's arc (or a failed fit).
        state.stats.rejected_far_arc += 1
        return None

    merged_nodes = set(state.constrained_nodes(merged))
    hold = held_joins(state, seeds, merged, pair, level)
    lines = [g for g in level.lines if g != a and g != b]  # the groups after the merge that are straight
    if seeds[-1].k is None:
        lines.append(-1)
    global_solve = not state.options.localized
    out: Solution | None = None
    windows: set[int] = set()  # the groups of the windows that failed

    def solve_window(fixed: set[int], tangent: bool | set[int] = False, rings: int = 2) -> Solution | None:
        return state.solve(
            after,
            seeds,
            node_groups_after,
            changed=[-1],
            free_nodes=sorted(merged_nodes),
            fixed=fixed,
            n_groups_total=n_groups,
            n_junctions_total=nj_after,
            rings=rings,
            first_ring=1 if rings == 2 else 3,  # the wider window: the first two rings failed
            order=lambda g: (g != -1, g),
            tangent=tangent,
            cap=cap,
            lines=lines,
            tried=windows,
            stop_when_stuck=rings > 2,
        )

    if not global_solve and hold:
        out = solve_window(set(), tangent=hold)
    if not global_solve and out is None:
        # The window: the new circle and its neighbours, with the new circle's
        # junctions free (Sec. 5.4). If the fixed junctions leave no solution,
        # a second ring (the neighbours' junctions and their circles) is freed,
        # then further rings up to MERGE_FALLBACK_RINGS. Without the connectivity
        # constraint only the new circle moves.
        out = solve_window(set() if state.options.connectivity else set(after) - {-1})
        if out is None:
            state.stats.local_failed += 1
            # A merged segment whose pixels lie on average more than T from
            # their own best golden circle, constraints aside, cannot give an
            # arc within the tolerance: reject it without the costly global
            # solve (measured: such windows fail globally too).
            if state.golden_error(merged) > state.options.tolerance:
                state.stats.rejected_hopeless += 1
                _tried(pair, windows, tried)
                return None
            # The paper solves the global problem here; a window of a bounded number of
            # rings costs the same however large the drawing (MERGE_FALLBACK_RINGS).
            state.stats.wide_windows += 1
            if hold:
                out = solve_window(set(), tangent=hold, rings=MERGE_FALLBACK_RINGS)
            if out is None:
                out = solve_window(set(), rings=MERGE_FALLBACK_RINGS)
    if global_solve:

        def solve_global(tangent: bool | set[int] = False) -> Solution | None:
            return state.solve_whole(
                after,
                seeds,
                node_groups_after,
                n_groups_total=n_groups,
                n_junctions_total=nj_after,
                order=lambda g: (g == -1, g),  # the merged group last, as in ``after``
                tangent=tangent,
                cap=cap,
            )

        if hold:
            out = solve_global(tangent=hold)
        if out is None:
            out = solve_global()
    if out is None:  # the wider window (or the global problem) has no solution either
        _tried(pair, windows, tried)
        return None
    fits, disp = out
    if cap is not None and fits[-1].arc.frechet > cap:  # (then the window's other arcs were not extracted)
        state.stats.rejected_far_arc += 1
        return None
    # The merged arc (id -1) is held to its cap above; the silhouette's arcs beside it, moved by the refit, here.
    if state.outline_strays({g: f for g, f in fits.items() if g != -1}, after, state.fits):
        state.stats.rejected_far_arc += 1
        return None

    old_nodes = set(state.node_groups())
    changed_nodes = set(disp) | {node}
    # |d_k| as np.linalg.norm computes it for a vector (sqrt of its dot with itself), without its dispatch.
    delta_d = sum(math.sqrt(disp[n].dot(disp[n])) for n in changed_nodes if n in node_groups_after and n in disp)
    delta_d -= sum(math.sqrt(state.disp[n].dot(state.disp[n])) for n in changed_nodes if n in old_nodes)
    delta_f = sum(f.arc.frechet for f in fits.values())
    delta_f -= sum(state.fits[g].arc.frechet for g in {a, b} | (set(fits) - {-1}))
    window_ids = frozenset({a, b} | (set(fits) - {-1}))

    redundant = 0
    if state.options.avoid_intersections:
        redundant = _redundant(state, pair, merged, fits, disp, level)
    return MergeOutcome(
        pair, merged, fits, disp, window_ids, delta_f, delta_d, nj_after - len(old_nodes), redundant, global_solve
    )


def _tried(pair: Pair, windows: set[int], tried: set[int] | None) -> None:
    """For a refit of :func:`evaluate` that failed: ``tried`` receives the groups of ``windows`` (-1: the pair's)."""
    if tried is not None:
        tried.update(windows - {-1}, pair[:2] if -1 in windows else ())


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
    # FitState.arc_junctions' test for the path's two end nodes: a node is an end of the arc
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


def _through(state: FitState, level: _Level) -> dict[int, set[int]]:
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


def _runs_through_twice(
    state: FitState,
    pair: Pair,
    merged: Group,
    fits: dict[int, GroupFit],
    disp: dict[int, np.ndarray],
    level: _Level,
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


def _too_far(state: FitState, merged: Group, seed: Seed, cap: float) -> bool:
    """Whether the merged group's arc is certainly farther than ``cap`` px from its pixels, before any fit.

    Its circle keeps the seed's radius r through the fit (Eqn. 12); its arc's
    discrete Fréchet distance to the pixels is at least every pixel's distance
    to the circle. When no centre brings every pixel within ``cap`` +
    ``FAR_ARC_MARGIN`` of a circle of radius r (a proof by
    :func:`img2logo._compiled.sqp.far_circle_kernel`), the fit's arc would be
    rejected as too far, or the fit fail: the candidate is rejected without it,
    with the same outcome. Made once per merged group and radius (the loop asks
    again at every level); never for a straight line (its centre is fixed far
    away), nor without the compiled kernels.
    """
    if seed.k is None:
        return False
    key = (merged.segments, merged.nodes, float(seed.radius))
    hit = state.far_arcs.get(key)
    if hit is None:
        from .._compiled import kernels  # loaded by the first fit already

        hit = False
        if kernels.usable():
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


def held_joins(
    state: FitState, seeds: dict[int, Seed], merged: Group, pair: Pair, level: _Level | None = None
) -> set[int]:
    """The smooth joins a merge's refit holds tangent (beyond the paper, :mod:`img2logo.fit.tangency`).

    Those the loop made tangent before (``state.held``) and those at the merged
    group's two ends: a merge is judged with the tangencies it would leave in
    place. Not the merge's own node, which the merged arc runs on through.
    Each is a join of :meth:`FitState.tangencies` after the merge, found from
    the groups ending at it (only the merge's two groups and the merged one change).
    """
    if not state.smooth:
        return set()
    a, b, node = pair
    ends = (level_view(state) if level is None else level).ends
    out = set()
    for n in state.held | set(merged.ends):
        if n == node or n not in state.smooth or n in state.loose or n in state.released:
            continue
        gids = [g for g in ends.get(n, ()) if g != a and g != b]
        if n in merged.ends:
            gids.append(-1)
        if len(gids) != 2 or (seeds[gids[0]].k is None and seeds[gids[1]].k is None):
            continue
        out.add(n)
    return out


@dataclass(frozen=True, eq=False)
class _Level:
    """What every candidate of one level reads of the current groups (made once a level, :func:`level_view`).

    ``groups``, ``fits``, ``released``: what it was made from (compared by
    identity). ``gids``: the groups in ``state.groups``'s order; ``arcs`` and
    ``params`` their arcs and rows (cx, cy, r, theta0, sweep) of the compiled
    redundant-intersection test; ``flat`` their junction nodes in order, of
    arc ``owner``; ``lengths`` how many each; ``inner`` node -> the groups
    that run on through it; ``ends`` node -> the groups ending there (each
    once); ``lines`` the straight lines (k None), in ``state.fits``'s order;
    ``pos`` group -> its index in ``gids``; ``seeds`` group -> its fit's
    :class:`Seed` (in ``state.groups``'s order).
    """

    groups: tuple[Group, ...]
    fits: tuple[GroupFit | None, ...]
    released: int
    gids: tuple[int, ...]
    arcs: list[Arc]
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


def level_view(state: FitState) -> _Level:
    """The current level's :class:`_Level`, made again when a group, a fit or a released junction changed."""
    # Compared element by element by identity in C (map, operator.is_): ~10^3 calls a run.
    gids = tuple(state.groups)
    groups = tuple(state.groups.values())
    fits = tuple(map(state.fits.get, gids))  # (a group not fitted yet: only its topology is read)
    cached = cast("_Level | None", state.merge_cache)
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
    level = _Level(
        groups,
        fits,
        len(state.released),
        gids,
        [f.arc.arc for f in fits if f is not None],
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


def _redundant(
    state: FitState,
    pair: Pair,
    merged: Group,
    fits: dict[int, GroupFit],
    disp: dict[int, np.ndarray],
    level: _Level | None = None,
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
    arcs = [arc for arc, k in zip(level.arcs, keep.tolist(), strict=True) if k]
    arcs.append(fits[-1].arc.arc)
    changed_list = []
    for g, f in fits.items():
        if g == -1:
            continue
        i = int(new_pos[pos[g]])
        params[i] = f.arc_row
        arcs[i] = f.arc.arc
        changed_list.append(i)
    changed_list.append(len(arcs) - 1)
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
    pairs, _ = _redundant_arrays(arcs, points, ptr, flat, changed, REDUNDANT_INTERSECTION_TOL, params)
    return len(pairs)


@dataclass(frozen=True, eq=False)
class _OpenEnds:
    """A level's open ends and how far each lies from every arc (:func:`_open_ends`).

    ``nodes``: the free ends (:meth:`FitState.open_ends
    <img2logo.fit.fit_state.FitState.open_ends>`); ``owners`` (m,): the group
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


def _open_ends(state: FitState, level: _Level) -> _OpenEnds:
    """The level's :class:`_OpenEnds`, made once a level (kept in ``level.memo``)."""
    hit = level.memo.get("open")
    if hit is not None:
        return cast(_OpenEnds, hit)
    found = state.open_ends()
    nodes = [n for n, _ in found]
    owners = np.array([g for _, g in found], dtype=np.int64)
    columns = np.array([level.pos[g] for _, g in found], dtype=np.intp)
    points, distances = state.end_distances(found, level.params, columns)
    nearest = distances.min(axis=1) if distances.shape[1] else np.full(len(nodes), np.inf)
    out = _OpenEnds(nodes, owners, columns, points, distances, near_miss(nearest))
    level.memo["open"] = out
    return out


def new_gaps(
    state: FitState,
    pair: Pair,
    fits: dict[int, GroupFit],
    disp: dict[int, np.ndarray],
    level: _Level | None = None,
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


def recheck_redundant(state: FitState, outcome: MergeOutcome) -> int:
    """Redundant intersections a cached outcome would leave against the *current* arcs.

    A cached count goes stale when any arc moves, not only the arcs of the
    outcome's window: the chosen merge is checked again before it is made.
    """
    return _redundant(state, outcome.pair, outcome.merged, outcome.fits, outcome.displacements)


def recheck_gaps(state: FitState, outcome: MergeOutcome) -> int:
    """Near-miss gaps (:func:`new_gaps`) a cached outcome would make against the *current* arcs."""
    return new_gaps(state, outcome.pair, outcome.fits, outcome.displacements)


def recheck_crossing(state: FitState, outcome: MergeOutcome) -> bool:
    """Whether a cached outcome would leave two arcs running on through one junction (:func:`_runs_through_twice`)."""
    return _runs_through_twice(
        state, outcome.pair, outcome.merged, outcome.fits, outcome.displacements, level_view(state)
    )


def merge_loop(
    state: FitState,
    tolerance: float,
    merged: MergeCallback | None = None,
    over_budget: Callable[[], bool] | None = None,
) -> str:
    """Merge the best pair until E^s would exceed ``tolerance`` (Sec. 5.2, steps 1-6).

    Scores are kept between iterations. After a merge, the pairs with the new
    segment are scored afresh; a pair whose refit window the merge changed
    keeps its old score as an estimate (the paper keeps it as it was, step 5)
    and is rescored from the current state when it comes out best: so the pair
    merged is always scored exactly (lazy greedy). After every merge it calls
    ``merged(state)`` (the progressive optimization records the level there);
    returns why it stopped: ``"tolerance"``, ``"no mergeable pair"`` or
    ``"time budget"``: ``over_budget()`` was true before a candidate's refit,
    and the state is the last level made (a refit is tentative: a level's
    candidates stop wherever the budget ends, and nothing of them is kept).

    The chosen merge is checked before it is made, against the current arcs:
    for redundant intersections (scored with every candidate too, Fig. 12),
    and, for it alone, for the near-miss gaps it would make (:func:`new_gaps`)
    and an arc it would let run on through a junction another arc runs on
    through (:func:`_runs_through_twice`). One that fails is set aside like a
    candidate with a redundant intersection (with a crossing: like one that
    failed), the next best is taken, and it is scored again once a merge has
    changed its window. A candidate is merged only when it is the best, so
    the best alone is checked, against the arcs as they are then (on
    ``data/photo-flower.png`` 19 checks a run, where checking every candidate
    that passed the other rules took 81; ``make quality``'s table the same
    for both, every row).
    """
    cache: dict[Pair, MergeOutcome | None] = {}
    stale: set[Pair] = set()
    # A candidate whose refit failed, by the groups its windows held (evaluate's ``tried``): it is
    # tried again once a merge changed one of them, like a candidate with a score (the windows'
    # constraints are the same until then; only the weights 1/|A|, 1/|J'| of their objective move).
    failed: dict[Pair, frozenset[int]] = {}

    def score(pair: Pair) -> None:
        tried: set[int] = set()
        cache[pair] = out = evaluate(state, pair, tried)
        stale.discard(pair)
        if out is None and tried:
            failed[pair] = frozenset(tried)
        else:
            failed.pop(pair, None)

    while True:
        pairs = candidates(state)
        if not pairs:
            return "no mergeable pair"
        f, d, nj = state.totals()
        n_arcs = len(state.fits)
        while True:
            best, best_error = None, math.inf
            for pair in pairs:
                if pair not in cache or (pair in stale and cache[pair] is None):
                    if over_budget is not None and over_budget():
                        return TIME_BUDGET_STOP
                    score(pair)
                out = cache[pair]
                if out is None or ((out.redundant or out.gaps) and pair not in stale):
                    continue
                nj_after = nj + out.delta_j
                error = (f + out.delta_f) / max(n_arcs - 1, 1) + ((d + out.delta_d) / nj_after if nj_after else 0.0)
                if error < best_error:
                    best, best_error = pair, error
            if best is None or best not in stale:
                break
            if over_budget is not None and over_budget():
                return TIME_BUDGET_STOP
            score(best)
        state.stats.rejected_intersections = sum(1 for o in cache.values() if o is not None and o.redundant)
        state.stats.rejected_gaps = sum(1 for o in cache.values() if o is not None and o.gaps)
        if best is None:
            return "no mergeable pair"
        if best_error > tolerance:
            return "tolerance"
        outcome = cast(MergeOutcome, cache[best])  # the best pair has an outcome
        if state.options.avoid_intersections:
            now = recheck_redundant(state, outcome)
            gaps = 0 if now else recheck_gaps(state, outcome)
            if now or gaps:
                cache[best] = dataclasses.replace(outcome, redundant=now, gaps=gaps)
                continue
        if recheck_crossing(state, outcome):
            state.stats.rejected_crossing += 1
            cache[best] = None
            continue
        state.merge(outcome.pair[0], outcome.pair[1], outcome.merged, outcome.fits, outcome.displacements)
        if state.smooth:
            state.held = state.touching_joins(state.held | set(outcome.merged.ends))
        changed = outcome.window | {outcome.pair[0], outcome.pair[1]}
        cache = {p: o for p, o in cache.items() if p[0] in state.groups and p[1] in state.groups}
        failed = {p: w for p, w in failed.items() if p in cache}
        for p, o in cache.items():
            window = o.window if o is not None else failed.get(p)
            if outcome.global_solve or window is None or (window & changed):
                stale.add(p)
        stale &= set(cache)
        if merged is not None:
            merged(state)
