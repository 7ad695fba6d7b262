"""Merging (paper Sec. 5.2, steps 1-6): candidate pairs, their evaluation, the greedy loop.

Neighbouring groups (:mod:`img2logo.simplification`) of the progressive
optimization's state (:mod:`img2logo.progressive`) are merged one pair at a
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
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from .arc_extraction import redundant_intersections
from .simplification import Group, hold_line, merge_groups

if TYPE_CHECKING:
    from .geometry import Abstraction
    from .progressive import ProgressCallback, _Fit, _Optimizer


@dataclass
class MergeOutcome:
    """What merging one candidate pair would give (:func:`evaluate`)."""

    pair: tuple[int, int, int]  # (group a, group b, shared node)
    merged: Group
    fits: dict[int, _Fit]  # new fits of the changed groups; key -1 is the merged group
    displacements: dict[int, np.ndarray]  # node -> new d_k
    window: frozenset[int]  # groups whose state this outcome depends on
    delta_f: float  # change of the sum of Fréchet distances
    delta_d: float  # change of the sum of |d_k| over J'
    delta_j: int  # change of |J'|
    redundant: int  # redundant intersections the merge would leave
    global_solve: bool


def candidates(opt: _Optimizer) -> list[tuple[int, int, int]]:
    """Mergeable pairs (a, b, node): two groups with a common end (Sec. 5.2)."""
    out = []
    sym = opt.symmetry
    for node, gids in sorted(opt.end_groups().items()):
        if sym is not None and node in sym.nodes:
            continue  # an arc never runs on through the mirror axis: its mirror image would cross it
        ok = [g for g in sorted(gids) if not opt.groups[g].locked and not opt.groups[g].closed]
        out.extend((a, b, node) for i, a in enumerate(ok) for b in ok[i + 1 :])
    return out


def evaluate(opt: _Optimizer, pair: tuple[int, int, int]) -> MergeOutcome | None:
    """Merge ``pair`` tentatively, refit, and score it; None if infeasible."""
    opt.stats["evaluated"] += 1
    a, b, node = pair
    # Two arcs that both run on through one junction cross there (an X): one
    # of them ends at the junction instead, so that arcs meet only at their
    # ends or where one ends on the other (a T), and no crossing is left.
    if any(node in g.nodes[1:-1] for gid, g in opt.groups.items() if gid not in (a, b)):
        opt.stats["rejected_crossing"] += 1
        return None
    merged = merge_groups(opt.groups[a], opt.groups[b], node)
    after = {g: grp for g, grp in opt.groups.items() if g not in (a, b)}
    after[-1] = merged
    n_groups = len(after)
    node_groups_after = opt.node_groups_after(a, b, merged)
    nj_after = len(node_groups_after)
    seeds = {g: (opt.fits[g].center, opt.fits[g].radius, opt.fits[g].k) for g in after if g != -1}
    held: dict[int, list[np.ndarray]] = {}
    for g, f in opt.fits.items():
        if f.k is None and g not in (a, b):
            hold_line(held, opt.groups[g], opt.constrained_nodes(opt.groups[g]))
    seeds[-1] = opt.golden(merged, held=held)

    merged_nodes = set(opt.constrained_nodes(merged))
    global_solve = not opt.options.localized
    out = None
    if not global_solve:
        # The window: the new circle and its neighbours, with the new circle's
        # junctions free (Sec. 5.4). If the fixed junctions leave no solution,
        # a second ring (the neighbours' junctions and their circles) is freed
        # before the global problem is solved. Without the connectivity
        # constraint only the new circle moves.
        out = opt.solve(
            after,
            seeds,
            node_groups_after,
            changed=[-1],
            free_nodes=sorted(merged_nodes),
            fixed=set() if opt.options.connectivity else set(after) - {-1},
            n_groups_total=n_groups,
            n_junctions_total=nj_after,
            rings=2,
            order=lambda g: (g != -1, g),
        )
        if out is None:
            opt.stats["local_failed"] += 1
            # A merged segment whose pixels lie on average more than T from
            # their own best golden circle, constraints aside, cannot give an
            # arc within the tolerance: reject it without the costly global
            # solve (measured: such windows fail globally too).
            if opt.golden_error(merged) > opt.options.tolerance:
                opt.stats["rejected_hopeless"] += 1
                return None
            global_solve = True
    if global_solve:
        out = opt.solve_whole(
            after,
            seeds,
            node_groups_after,
            n_groups_total=n_groups,
            n_junctions_total=nj_after,
            order=lambda g: (g == -1, g),  # the merged group last, as in ``after``
        )
        if out is None:
            return None
    fits, disp = out
    cap = opt.options.arc_bound
    if cap is not None and fits[-1].arc.frechet > cap:
        opt.stats["rejected_far_arc"] += 1
        return None

    old_nodes = set(opt.node_groups())
    changed_nodes = set(disp) | {node}
    delta_d = sum(float(np.linalg.norm(disp[n])) for n in changed_nodes if n in node_groups_after and n in disp)
    delta_d -= sum(float(np.linalg.norm(opt.disp[n])) for n in changed_nodes if n in old_nodes)
    delta_f = sum(f.arc.frechet for f in fits.values())
    delta_f -= sum(opt.fits[g].arc.frechet for g in {a, b} | (set(fits) - {-1}))
    window_ids = frozenset({a, b} | (set(fits) - {-1}))

    redundant = 0
    if opt.options.avoid_intersections:
        redundant = _redundant(opt, after, fits, disp, node_groups_after)
    return MergeOutcome(
        pair, merged, fits, disp, window_ids, delta_f, delta_d, nj_after - len(old_nodes), redundant, global_solve
    )


def _redundant(
    opt: _Optimizer,
    after: dict[int, Group],
    fits: dict[int, _Fit],
    disp: dict[int, np.ndarray],
    node_groups_after: dict[int, list[int]],
) -> int:
    """Redundant intersections that involve the arcs a merge changed."""
    gids = list(after)
    arcs = [(fits[g] if g in fits else opt.fits[g]).arc.arc for g in gids]
    nodes = sorted(node_groups_after)
    node_index = {n: i for i, n in enumerate(nodes)}
    points = np.array([opt.graph.junctions[n] + (disp[n] if n in disp else opt.disp[n]) for n in nodes]).reshape(-1, 2)
    arc_junctions = [[node_index[n] for n in opt.constrained_nodes(after[g])] for g in gids]
    changed = [i for i, g in enumerate(gids) if g in fits]
    return len(redundant_intersections(arcs, points, arc_junctions, candidates=changed))


def recheck_redundant(opt: _Optimizer, outcome: MergeOutcome) -> int:
    """Redundant intersections a cached outcome would leave against the *current* arcs.

    A cached count goes stale when any arc moves, not only the arcs of the
    outcome's window: the chosen merge is checked again before it is made.
    """
    a, b, _ = outcome.pair
    after = {g: grp for g, grp in opt.groups.items() if g not in (a, b)}
    after[-1] = outcome.merged
    return _redundant(opt, after, outcome.fits, outcome.displacements, opt.node_groups_after(a, b, outcome.merged))


def merge_loop(
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
    merged is always scored exactly (lazy greedy). Appends the levels to
    ``levels``, each recording ``record``; returns why it stopped.
    """
    cache: dict[tuple[int, int, int], MergeOutcome | None] = {}
    stale: set[tuple[int, int, int]] = set()
    while True:
        pairs = candidates(opt)
        if not pairs:
            return "no mergeable pair"
        f, d, nj = opt.totals()
        n_arcs = len(opt.fits)
        while True:
            best, best_error = None, math.inf
            for pair in pairs:
                if pair not in cache or (pair in stale and cache[pair] is None):
                    cache[pair] = evaluate(opt, pair)
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
            cache[best] = evaluate(opt, best)
            stale.discard(best)
        opt.stats["rejected_intersections"] = sum(1 for o in cache.values() if o is not None and o.redundant)
        if best is None:
            return "no mergeable pair"
        if best_error > tolerance:
            return "tolerance"
        outcome = cache[best]
        if opt.options.avoid_intersections:
            now = recheck_redundant(opt, outcome)
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
