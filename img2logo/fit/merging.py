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
0.75-6 px from an arc, :func:`~img2logo.fit.merge_checks.new_gaps`) and for an arc running on past the
end of its path through a junction another arc runs on through (:func:`~img2logo.fit.merge_checks.runs_through_twice`).

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from typing import TypeAlias, cast

import numpy as np

from . import window_solve
from .constants import FAR_ARC_RETRY, MERGE_FALLBACK_RINGS
from .fit_state import FitState
from .fit_values import GroupFit, Seed, Solution
from .merge_checks import LevelView, Pair, level_view, new_gaps, redundant_after_merge, runs_through_twice, too_far
from .outline import arc_cap, outline_strays
from .simplification import Group, hold_line, merge_groups

#: Called by :func:`merge_loop` after every merge, with the state (now one level further).
MergeCallback: TypeAlias = Callable[[FitState], None]

#: Why :func:`merge_loop` stopped when its time budget ran out.
TIME_BUDGET_STOP = "time budget"


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


def evaluate(
    state: FitState, pair: Pair, tried: set[int] | None = None, level: LevelView | None = None
) -> MergeOutcome | None:
    """Merge ``pair`` tentatively, refit, and score it; None if infeasible.

    ``tried``: when given and the refit fails (its windows, or the global
    problem, have no solution), or its merged arc lies farther than
    ``FAR_ARC_RETRY`` times its cap from its pixels, it receives the groups of
    the state whose circles the windows held (the pair's two for the merged
    group): the problem they solved, but for the weights 1/|A| and 1/|J'|,
    stays as it is until a merge changes one of them (:func:`merge_loop`).
    When :func:`~img2logo.fit.merge_checks.too_far` proves the merged arc too far
    (it reads the two groups only), it receives the pair's two groups. ``level``: the
    state's :func:`~img2logo.fit.merge_checks.level_view`, when the caller has it.
    """
    state.stats.evaluated += 1
    a, b, node = pair
    level = level_view(state) if level is None else level
    # Two arcs that both run on through one junction cross there (an X): one
    # of them ends at the junction instead, so that arcs meet only at their
    # ends or where one ends on the other (a T), and no crossing is left.
    if any(g != a and g != b for g in level.inner.get(node, ())):
        state.stats.rejected_crossing += 1
        return None
    group_a, group_b = state.groups[a], state.groups[b]
    far = state.far_pairs.get(pair)
    then = (len(state.released), state.options.tolerance)
    if far is not None and far[0] is group_a and far[1] is group_b and far[2:] == then:
        # :func:`too_far` rejected this merge of these two groups before: it reads nothing else that changes.
        state.stats.rejected_far_arc += 1
        _tried(pair, {-1}, tried)  # (until a merge changes a or b: then the pair is gone)
        return None
    merged = merge_groups(group_a, group_b, node)
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
    cap = arc_cap(state, merged)
    if cap is not None and too_far(state, merged, seeds[-1], cap):
        # Every path below would end in the rejection of the fit's arc (or a failed fit).
        state.stats.rejected_far_arc += 1
        if not held:  # (the lines held at its junctions refused a straight line: that may change)
            state.far_pairs[pair] = (group_a, group_b, *then)
            _tried(pair, {-1}, tried)
        return None

    merged_nodes = set(state.constrained_nodes(merged))
    hold = held_joins(state, seeds, merged, pair, level)
    lines = [g for g in level.lines if g != a and g != b]  # the groups after the merge that are straight
    if seeds[-1].k is None:
        lines.append(-1)
    global_solve = not state.options.localized
    out: Solution | None = None
    windows: set[int] = set()  # the groups of the windows that failed

    def solve_window(
        fixed: set[int], tangent: bool | dict[int, tuple[int, int]] = False, rings: int = 2
    ) -> Solution | None:
        return window_solve.solve(
            state,
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

        def solve_global(tangent: bool | dict[int, tuple[int, int]] = False) -> Solution | None:
            return window_solve.solve_whole(
                state,
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
        if fits[-1].arc.frechet > FAR_ARC_RETRY * cap:  # far enough that the weights alone will not bring it in
            _tried(pair, windows, tried)
        return None
    # The merged arc (id -1) is held to its cap above; the silhouette's arcs beside it, moved by the refit, here.
    if outline_strays(state, {g: f for g, f in fits.items() if g != -1}, after, state.fits):
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
        redundant = redundant_after_merge(state, pair, merged, fits, disp, level)
    return MergeOutcome(
        pair, merged, fits, disp, window_ids, delta_f, delta_d, nj_after - len(old_nodes), redundant, global_solve
    )


def _tried(pair: Pair, windows: set[int], tried: set[int] | None) -> None:
    """For a refit of :func:`evaluate` that failed: ``tried`` receives the groups of ``windows`` (-1: the pair's)."""
    if tried is not None:
        tried.update(windows - {-1}, pair[:2] if -1 in windows else ())


def held_joins(
    state: FitState, seeds: dict[int, Seed], merged: Group, pair: Pair, level: LevelView | None = None
) -> dict[int, tuple[int, int]]:
    """The smooth joins a merge's refit holds tangent (beyond the paper, :mod:`img2logo.fit.tangency`).

    Those the loop made tangent before (``state.held``) and those at the merged
    group's two ends: a merge is judged with the tangencies it would leave in
    place. Not the merge's own node, which the merged arc runs on through.
    Each is a join of :meth:`FitState.tangencies` after the merge (the merged
    group's id -1, last), found from the groups ending at it (only the merge's
    two groups and the merged one change): node -> its two groups, as there.
    """
    if not state.smooth:
        return {}
    a, b, node = pair
    ends = (level_view(state) if level is None else level).ends
    out = {}
    for n in state.held | set(merged.ends):
        if n == node or n not in state.smooth or n in state.loose or n in state.released:
            continue
        gids = [g for g in ends.get(n, ()) if g != a and g != b]
        if n in merged.ends:
            gids.append(-1)
        if len(gids) != 2 or (seeds[gids[0]].k is None and seeds[gids[1]].k is None):
            continue
        out[n] = (gids[0], gids[1])
    return out


def recheck_redundant(state: FitState, outcome: MergeOutcome) -> int:
    """Redundant intersections a cached outcome would leave against the *current* arcs.

    A cached count goes stale when any arc moves, not only the arcs of the
    outcome's window: the chosen merge is checked again before it is made.
    """
    return redundant_after_merge(state, outcome.pair, outcome.merged, outcome.fits, outcome.displacements)


def recheck_gaps(state: FitState, outcome: MergeOutcome) -> int:
    """Near-miss gaps a cached outcome would make against the *current* arcs.

    See :func:`~img2logo.fit.merge_checks.new_gaps`.
    """
    return new_gaps(state, outcome.pair, outcome.fits, outcome.displacements)


def recheck_crossing(state: FitState, outcome: MergeOutcome) -> bool:
    """Whether a cached outcome would leave two arcs running on through one junction.

    See :func:`~img2logo.fit.merge_checks.runs_through_twice`.
    """
    return runs_through_twice(
        state, outcome.pair, outcome.merged, outcome.fits, outcome.displacements, level_view(state)
    )


def merge_loop(
    state: FitState,
    tolerance: float,
    merged: MergeCallback | None = None,
    over_budget: Callable[[], bool] | None = None,
    done: Callable[[], bool] | None = None,
) -> str:
    """Merge the best pair until E^s would exceed ``tolerance`` (Sec. 5.2, steps 1-6).

    Scores are kept between iterations. After a merge, the pairs with the new
    segment are scored afresh; a pair whose refit window the merge changed
    keeps its old score as an estimate (the paper keeps it as it was, step 5)
    and is rescored from the current state when it comes out best: so the pair
    merged is always scored exactly (lazy greedy). After every merge it calls
    ``merged(state)`` (the progressive optimization records the level there);
    returns why it stopped: ``"tolerance"``, ``"arcs"`` (``done()`` was true
    before a merge: the logo is down to its arc budget), ``"no mergeable pair"`` or
    ``"time budget"``: ``over_budget()`` was true before a candidate's refit,
    and the state is the last level made (a refit is tentative: a level's
    candidates stop wherever the budget ends, and nothing of them is kept).

    The chosen merge is checked before it is made, against the current arcs:
    for redundant intersections (scored with every candidate too, Fig. 12),
    and, for it alone, for the near-miss gaps it would make (:func:`~img2logo.fit.merge_checks.new_gaps`)
    and an arc it would let run on through a junction another arc runs on
    through (:func:`~img2logo.fit.merge_checks.runs_through_twice`). One that fails is set aside like a
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
    # A candidate whose refit failed, or left its arc far past its cap, by the groups its windows held
    # (evaluate's ``tried``): it is tried again once a merge changed one of them, like a candidate with
    # a score (the windows' problem is the same until then; only the weights 1/|A|, 1/|J'| of their
    # objective move).
    failed: dict[Pair, frozenset[int]] = {}

    def score(pair: Pair) -> None:
        tried: set[int] = set()
        cache[pair] = out = evaluate(state, pair, tried, level)
        stale.discard(pair)
        if out is None and tried:
            failed[pair] = frozenset(tried)
        else:
            failed.pop(pair, None)

    while True:
        if done is not None and done():
            return "arcs"
        pairs = candidates(state)
        level = level_view(state)  # the level's view for its candidates: they change nothing it was made of
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
