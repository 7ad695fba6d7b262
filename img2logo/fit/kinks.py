"""Kinks left by the tangent pass (beyond the paper): the level kept, and arcs split beside a kink.

Where the tangent pass (:func:`img2logo.fit.tangency.tangent_joins`) leaves a smooth join kinked:

* a kinked join of the object's silhouette, where no two circles on their rungs touch with both arcs
  within T, has one of its arcs split beside the kink (:func:`split_kinks`): a short arc rounds the
  corner;
* the result may be a level before the last (:func:`tangent_level`): the merge loop stops where E^s is
  within a few tenths of a px of T, and a tangency there costs 0.1-1 px of E^s, while a level with one
  more arc has shorter arcs and more room. The level kept has the fewest arcs plus ``KINK_WEIGHT`` x
  its kinked joins.

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import TYPE_CHECKING

from .constants import (
    KINK_WEIGHT,
)
from .simplification import Group

if TYPE_CHECKING:
    from .fit_state import FitState
    from .fit_values import Stats
from . import window_solve
from .outline import on_outline, strays
from .tangency import Outscored, restore, snapshot, split_chain, tangent_joins


def tangent_level(
    opt: FitState,
    tolerance: float,
    history: Sequence[tuple],
    over_budget: Callable[[], bool] | None = None,
    room: int | None = None,
) -> int:
    """Make the result's smooth joins tangent, on the last level or one before it; how many levels back.

    ``history`` holds :func:`~img2logo.fit.tangency.snapshot` of every level of the merge loop, the
    last the current state. A join whose tangency does not fit under T on the
    last level (:func:`~img2logo.fit.tangency.tangent_joins`) may fit on a level before it, whose
    arcs are shorter and whose E^s leaves more slack: the level kept is the
    one with the fewest arcs plus kinked joins, a kink weighing
    ``KINK_WEIGHT`` arcs (on a tie the later level), its tangent refit within
    T. A level k back adds k arcs, so the search stops as soon as k reaches
    the best score: no level further back can win. The levels tried are 0, 1,
    2, 3 back and then about sqrt(2) times further each (4, 6, 8, 11, 16, ...):
    a tangent pass costs about as much on every level (0.2 s on a 512 px clip
    art with a dozen joins, 0.5 s at 2048 px), and trying every level made the
    search 20 passes long where many joins stay kinked (the polar bear, a clip
    art at 2048 px), while the kinks left fall slowly with the levels gone
    back, so the levels between two tried ones seldom score better. Once
    ``over_budget()`` is true no further level is tried (the last level always
    is). ``room`` bounds the arcs the levels back and the splits add (None: no bound): the logo's
    arc budget is a ceiling on the result, so a kink is kept rather than an arc added past it.
    ``opt`` is left in the kept level's state, tangent where it could be made so.
    """
    best: tuple[int, int, tuple, Stats] | None = None
    for back in _levels_back(len(history)):
        if best is not None and (back >= best[0] or (over_budget is not None and over_budget())):
            break
        if room is not None and back > room:
            break
        if back:
            restore(opt, history[-1 - back])
        opt.loose, opt.off_line = set(), {}
        try:
            # A level back wins only with fewer kinks than this: its pass stops once it cannot.
            tangent_joins(opt, tolerance, None if best is None else (best[0] - back - 1) // KINK_WEIGHT)
        except Outscored:
            continue
        score = back + KINK_WEIGHT * len(opt.loose)
        if best is None or score < best[0]:
            best = (score, back, snapshot(opt), replace(opt.stats))
    assert best is not None  # the last level is always tried
    restore(opt, best[2])
    opt.stats = best[3]
    split_kinks(opt, tolerance, None if room is None else room - best[1])
    window_solve.forget_arcs(opt)
    return best[1]


def split_kinks(opt: FitState, tolerance: float, room: int | None = None) -> int:
    """Split an arc at a kinked join of the silhouette where that makes the joins tangent; how many split.

    A join of two arcs of the object's silhouette is left kinked when no two
    circles on their rungs (one up or down) touch there with both arcs within T
    of their pixels: the two groups' joined pixels are no tangent biarc within
    T (on the evaluation clip arts the best one lies 6-27 px off them). Three
    arcs may be: one of the two groups is split at a smooth inner node (where
    the over-segmentation had split it), the nearest to the kink
    (:func:`_split_node`), the two halves refitted in their window, and the
    tangent pass run again (every join, its refits held to the same rules). The split
    is kept when it lowers the score :func:`tangent_level` ranks levels by (arcs
    plus ``KINK_WEIGHT`` x kinked joins) with E^s within ``max(T, E^s now)``
    and no arc of the silhouette moved farther than T from its pixels (or than it was). At most
    ``room`` arcs are split (None: no bound).
    """
    splits = 0
    if not opt.outline or not opt.loose or opt.symmetry is not None:  # a mirror pairs the groups as they are
        return splits
    tried: set[tuple[int, ...]] = set()
    while room is None or splits < room:
        seeds = {g: f.seed for g, f in opt.fits.items()}
        loose, opt.loose = opt.loose, set()
        joins = opt.tangencies(opt.groups, seeds)  # the released joins too
        opt.loose = loose
        kinked = sorted(n for n in opt.loose if n in joins and any(on_outline(opt, opt.groups[g]) for g in joins[n]))
        score = len(opt.fits) + KINK_WEIGHT * len(opt.loose)
        bound = max(float(tolerance), opt.similarity())
        done = False
        for node in kinked:
            for g in joins[node]:
                group = opt.groups[g]
                inner = _split_node(opt, group, node)
                if inner is None or group.nodes in tried:
                    continue
                tried.add(group.nodes)
                before, stats = snapshot(opt), replace(opt.stats)
                if _split_group(opt, g, inner, bound):
                    opt.loose = set()
                    try:  # kept only below ``score``: the pass stops once it cannot be
                        tangent_joins(opt, tolerance, (score - len(opt.fits) - 1) // KINK_WEIGHT)
                        kept = len(opt.fits) + KINK_WEIGHT * len(opt.loose) < score and opt.similarity() <= bound
                    except Outscored:
                        kept = False
                    if kept:
                        splits += 1
                        done = True
                        break
                restore(opt, before)
                opt.stats = stats
            if done:
                break
        if not done:
            return splits
    return splits


def _split_node(opt: FitState, group: Group, join: int) -> int | None:
    """The smooth inner node of ``group``'s path nearest to its end at ``join``; None if it has none.

    The arc added there is a short one beside the kink: it can turn the tangent
    between the two long arcs, as a fillet does, while they keep their pixels.
    """
    inner = [i for i in range(1, len(group.nodes) - 1) if group.nodes[i] in opt.smooth]
    if not inner or group.closed:
        return None
    return group.nodes[min(inner) if group.nodes[0] == join else max(inner)]


def _split_group(opt: FitState, gid: int, node: int, bound: float) -> bool:
    """Replace group ``gid`` by its two halves at inner ``node``, refitted in their window; whether it fits.

    The halves start on their golden circles (Eqn. 12); the fit (Eqn. 13,
    with the state's tangencies) must converge, keep E^s within ``bound`` and
    each half within its :func:`~img2logo.fit.outline.arc_cap`. On
    failure the state may be left changed: the caller restores it.
    """
    group = opt.groups[gid]
    i = group.nodes.index(node)
    cut = split_chain(group.points, opt.graph.junctions[node] + opt.disp[node])
    if cut is None:
        return False
    head = Group(group.segments[:i], group.nodes[: i + 1], cut[0], group.locked)
    tail = Group(group.segments[i:], group.nodes[i:], cut[1], group.locked)
    del opt.groups[gid]
    opt.fits.pop(gid)
    opt.invalidate()
    halves = [opt.add_group(head), opt.add_group(tail)]
    seeds = {g: f.seed for g, f in opt.fits.items()}
    for h in halves:
        seeds[h] = opt.golden(opt.groups[h])
        if seeds[h].k is None:
            return False
    out = window_solve.solve(
        opt,
        dict(opt.groups),
        seeds,
        opt.node_groups(),
        changed=halves,
        free_nodes=sorted({n for h in halves for n in opt.constrained_nodes(opt.groups[h])}),
        fixed=set(),
        rings=2,
    )
    if out is None or not all(h in out[0] for h in halves):
        return False
    fits, disp = out
    if strays(opt, fits, opt.groups, opt.fits):
        return False
    opt.fits.update(fits)
    for n, d in disp.items():
        opt.disp[n] = d
    return opt.similarity() <= bound


def _levels_back(n: int) -> list[int]:
    """The levels back that :func:`tangent_level` tries, of ``n``: 0-3, then about sqrt(2) times further each."""
    backs = {0, 1, 2, 3}
    step = 4.0
    while step < n:
        backs.add(int(step))
        step *= math.sqrt(2.0)
    return sorted(b for b in backs if b < n)
