"""Merging (paper Sec. 5.2, steps 1-6): candidate pairs, their evaluation, the greedy loop.

Neighbouring groups (:mod:`img2logo.simplification`) of the progressive
optimization's state (:class:`img2logo.fit_state.FitState`) are merged one pair at a
time, the pair with the lowest merge error first, until the similarity error
E^s (Eqn. 3) would exceed the tolerance T (:func:`merge_loop`).
:func:`candidates` lists the pairs; :func:`evaluate` merges one tentatively,
refits its local window (Sec. 5.4; the global problem when the window fails)
and scores it as the E^s the abstraction would have after it, with the rules
that reject a merge (an X through a junction, a hopeless window, an arc
farther than the bound, redundant intersections, Fig. 12).

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from itertools import chain
from typing import TypeAlias, cast

import numpy as np

from .arc_extraction import _redundant_arrays
from .constants import REDUNDANT_INTERSECTION_TOL
from .fit_state import FitState, GroupFit, Seed, Solution
from .simplification import Group, hold_line, merge_groups

#: Called by :func:`merge_loop` after every merge, with the state (now one level further).
MergeCallback: TypeAlias = Callable[[FitState], None]

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


def candidates(state: FitState) -> list[Pair]:
    """Mergeable pairs (a, b, node): two groups with a common end (Sec. 5.2).

    Neither locked (Sec. 7) nor closed; not at a node on a symmetric run's
    mirror axis. In the order of the nodes, then of the groups (a < b).
    """
    out: list[Pair] = []
    sym = state.symmetry
    for node, gids in sorted(state.end_groups().items()):
        if sym is not None and node in sym.nodes:
            continue  # an arc never runs on through the mirror axis: its mirror image would cross it
        ok = [g for g in sorted(gids) if not state.groups[g].locked and not state.groups[g].closed]
        out.extend((a, b, node) for i, a in enumerate(ok) for b in ok[i + 1 :])
    return out


def evaluate(state: FitState, pair: Pair) -> MergeOutcome | None:
    """Merge ``pair`` tentatively, refit, and score it; None if infeasible."""
    state.stats.evaluated += 1
    a, b, node = pair
    # Two arcs that both run on through one junction cross there (an X): one
    # of them ends at the junction instead, so that arcs meet only at their
    # ends or where one ends on the other (a T), and no crossing is left.
    if any(node in g.nodes[1:-1] for gid, g in state.groups.items() if gid not in (a, b)):
        state.stats.rejected_crossing += 1
        return None
    merged = merge_groups(state.groups[a], state.groups[b], node)
    after = {g: grp for g, grp in state.groups.items() if g not in (a, b)}
    after[-1] = merged
    n_groups = len(after)
    node_groups_after = state.node_groups_after(a, b, merged)
    nj_after = len(node_groups_after)
    seeds: dict[int, Seed] = {g: state.fits[g].seed for g in after if g != -1}
    held: dict[int, list[np.ndarray]] = {}
    for g, f in state.fits.items():
        if f.k is None and g not in (a, b):
            hold_line(held, state.groups[g], state.constrained_nodes(state.groups[g]))
    seeds[-1] = state.golden(merged, held=held)

    merged_nodes = set(state.constrained_nodes(merged))
    hold = _hold(state, after, seeds, merged, node)
    global_solve = not state.options.localized
    out: Solution | None = None

    def solve_window(fixed: set[int], tangent: bool | set[int] = False) -> Solution | None:
        return state.solve(
            after,
            seeds,
            node_groups_after,
            changed=[-1],
            free_nodes=sorted(merged_nodes),
            fixed=fixed,
            n_groups_total=n_groups,
            n_junctions_total=nj_after,
            rings=2,
            order=lambda g: (g != -1, g),
            tangent=tangent,
        )

    if not global_solve and hold:
        out = solve_window(set(), tangent=hold)
    if not global_solve and out is None:
        # The window: the new circle and its neighbours, with the new circle's
        # junctions free (Sec. 5.4). If the fixed junctions leave no solution,
        # a second ring (the neighbours' junctions and their circles) is freed
        # before the global problem is solved. Without the connectivity
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
                return None
            global_solve = True
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
            )

        if hold:
            out = solve_global(tangent=hold)
        if out is None:
            out = solve_global()
    if out is None:  # the global problem has no solution either
        return None
    fits, disp = out
    cap = state.options.arc_bound
    if cap is not None and fits[-1].arc.frechet > cap:
        state.stats.rejected_far_arc += 1
        return None

    old_nodes = set(state.node_groups())
    changed_nodes = set(disp) | {node}
    delta_d = sum(float(np.linalg.norm(disp[n])) for n in changed_nodes if n in node_groups_after and n in disp)
    delta_d -= sum(float(np.linalg.norm(state.disp[n])) for n in changed_nodes if n in old_nodes)
    delta_f = sum(f.arc.frechet for f in fits.values())
    delta_f -= sum(state.fits[g].arc.frechet for g in {a, b} | (set(fits) - {-1}))
    window_ids = frozenset({a, b} | (set(fits) - {-1}))

    redundant = 0
    if state.options.avoid_intersections:
        redundant = _redundant(state, after, fits, disp, node_groups_after)
    return MergeOutcome(
        pair, merged, fits, disp, window_ids, delta_f, delta_d, nj_after - len(old_nodes), redundant, global_solve
    )


def _hold(state: FitState, after: dict[int, Group], seeds: dict[int, Seed], merged: Group, node: int) -> set[int]:
    """The smooth joins a merge's refit holds tangent (beyond the paper, :mod:`img2logo.tangency`).

    Those the loop made tangent before (``state.held``) and those at the merged
    group's two ends: a merge is judged with the tangencies it would leave in
    place. Not the merge's own node, which the merged arc runs on through.
    """
    if not state.smooth:
        return set()
    joins = state.tangencies(after, seeds)
    return {n for n in joins if n != node and (n in state.held or n in merged.ends)}


def _redundant(
    state: FitState,
    after: dict[int, Group],
    fits: dict[int, GroupFit],
    disp: dict[int, np.ndarray],
    node_groups_after: dict[int, list[int]],
) -> int:
    """Redundant intersections that involve the arcs a merge changed.

    The junctions are indexed by node (every node of the graph, displaced; the
    window's new d_k over the state's): the kernel reads only the junctions the
    arcs own, which are the nodes of ``node_groups_after``.
    """
    gids = list(after)
    group_fits = [fits[g] if g in fits else state.fits[g] for g in gids]
    arcs = [f.arc.arc for f in group_fits]
    params = np.array([f.arc_row for f in group_fits], dtype=np.float64).reshape(-1, 5)
    junctions = state.graph.junctions
    points = junctions + state.disp
    if disp:
        moved = np.fromiter(disp, dtype=np.intp, count=len(disp))
        points[moved] = junctions[moved] + np.array(list(disp.values()), dtype=np.float64).reshape(-1, 2)
    # Each arc's junctions as one flat array of node ids (the kernel's layout).
    owned = [state.constrained_nodes(after[g]) for g in gids]
    ptr = np.zeros(len(owned) + 1, dtype=np.int64)
    np.cumsum([len(ks) for ks in owned], out=ptr[1:])
    flat = np.fromiter(chain.from_iterable(owned), dtype=np.int64, count=int(ptr[-1]))
    changed = np.array([i for i, g in enumerate(gids) if g in fits], dtype=np.int64)
    pairs, _ = _redundant_arrays(arcs, points, ptr, flat, changed, REDUNDANT_INTERSECTION_TOL, params)
    return len(pairs)


def recheck_redundant(state: FitState, outcome: MergeOutcome) -> int:
    """Redundant intersections a cached outcome would leave against the *current* arcs.

    A cached count goes stale when any arc moves, not only the arcs of the
    outcome's window: the chosen merge is checked again before it is made.
    """
    a, b, _ = outcome.pair
    after = {g: grp for g, grp in state.groups.items() if g not in (a, b)}
    after[-1] = outcome.merged
    return _redundant(state, after, outcome.fits, outcome.displacements, state.node_groups_after(a, b, outcome.merged))


def merge_loop(state: FitState, tolerance: float, merged: MergeCallback | None = None) -> str:
    """Merge the best pair until E^s would exceed ``tolerance`` (Sec. 5.2, steps 1-6).

    Scores are kept between iterations. After a merge, the pairs with the new
    segment are scored afresh; a pair whose refit window the merge changed
    keeps its old score as an estimate (the paper keeps it as it was, step 5)
    and is rescored from the current state when it comes out best: so the pair
    merged is always scored exactly (lazy greedy). After every merge it calls
    ``merged(state)`` (the progressive optimization records the level there);
    returns why it stopped: ``"tolerance"`` or ``"no mergeable pair"``.
    """
    cache: dict[Pair, MergeOutcome | None] = {}
    stale: set[Pair] = set()
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
                    cache[pair] = evaluate(state, pair)
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
            cache[best] = evaluate(state, best)
            stale.discard(best)
        state.stats.rejected_intersections = sum(1 for o in cache.values() if o is not None and o.redundant)
        if best is None:
            return "no mergeable pair"
        if best_error > tolerance:
            return "tolerance"
        outcome = cast(MergeOutcome, cache[best])  # the best pair has an outcome
        if state.options.avoid_intersections:
            now = recheck_redundant(state, outcome)
            if now:
                cache[best] = dataclasses.replace(outcome, redundant=now)
                continue
        state.merge(outcome.pair[0], outcome.pair[1], outcome.merged, outcome.fits, outcome.displacements)
        if state.smooth:
            state.held = state.touching_joins(state.held | set(outcome.merged.ends))
        changed = outcome.window | {outcome.pair[0], outcome.pair[1]}
        cache = {p: o for p, o in cache.items() if p[0] in state.groups and p[1] in state.groups}
        for p, o in cache.items():
            if outcome.global_solve or o is None or (o.window & changed):
                stale.add(p)
        stale &= set(cache)
        if merged is not None:
            merged(state)
