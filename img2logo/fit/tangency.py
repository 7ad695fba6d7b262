"""Tangent joins (beyond the paper): the result's circles touch where the input runs on smoothly.

Where exactly two arcs of the result end at a node of the segment graph where
the input's feature line does not turn (a node of valence 2 whose two segments'
end tangents differ by less than ``SMOOTH_JOIN_ANGLE``,
:meth:`~img2logo.segment_graph.SegmentGraph.smooth_nodes`), a designer draws
the two arcs so that one flows into the other: their circles touch at the
junction (the junction on the line of centres, centre distance |r1 - r2| or
r1 + r2). :func:`tangent_joins` refits the last level of the progressive
optimization (:mod:`img2logo.fit.progressive`) with that tangency as one more
equality per join in the constrained fit (Eqn. 13,
:func:`~img2logo.fit.constrained_fit.fit_constrained`, ``tangents``), one join at a
time in its local window (Sec. 5.4), the radii on the ladder.

Two freedoms make a tangency affordable where fixed rungs and fixed nodes make
it rigid:

* **the rungs of the two circles are chosen jointly** (:func:`_rung_choices`):
  when the rungs the paper chose (Eqn. 12) cannot touch within the tolerance,
  each circle may go one rung up or down, which turns its tangent at the join
  by as much as the kink; the choice of lowest E^s is kept;
* **the junction slides along the line** (:func:`_slide`): a smooth join's node
  is only where the over-segmentation split one smooth feature line, so the
  two groups' pixels are split anew where the junction now is, and E^s counts
  the junction's distance off the line instead of its displacement (a junction
  moved along a smooth line moves the logo away from nothing);
* **the two circles are fitted as one unit** (:func:`_biarc_starts`): when no
  refit from the current circles touches within T, the tangent biarc closest
  to the two groups' joined pixels (rungs of both and one up or down for each,
  its junction anywhere on the pixels, :func:`closest_biarcs`) is the refit's start,
  the junction's rest point moved there for the fit. Where a smooth line's
  curvature changes from one rung to the next is seldom where the
  over-segmentation put the node: on the polar bear's kinked joins the best
  biarc's junction lies 15-85 px along the line from the node, farther than the
  refit from the current circles moves it (its displacement term of Eqn. 13
  pulls it back, and each group's pixels stay on their own circle).

A tangency that makes the fit fail, lifts E^s above the tolerance T, breaks
one made before, adds a redundant intersection or makes a near-miss gap (a free
end moved 0.75-6 px from an arc, as the merge loop refuses one too:
:func:`img2logo.fit.merging.evaluate`) is released (only that one):
a kink is left there, and a valid image always gets a logo. Corners (where
the input turns) are never constrained.

Where the tangencies are made, and why there. With the radii fixed on the
ladder, a chain of tangent circles is rigid, and the first levels join every
short piece of the over-segmentation. Measured (``make quality``):
enforcing every tangency in A^0 and every merge's window raises E^s(A^0) of the
clip-art fish from 2.36 to 9.77 px (no merge fits under T = 5 any more), and on
the evaluation set's clip arts gives 47.1 arcs instead of 40.0 and one failed
run; enforcing all of a window's tangencies in the merges gives 41.6 arcs and
33 % tangent. So four narrower steps:

* a merge is judged with the tangencies it leaves in place
  (:func:`img2logo.fit.merging.evaluate`): the smooth joins at the merged arc's
  two ends, and those earlier merges made tangent (``FitState.held``), are held
  in its local refit, so the merge error is the E^s of the logo with them;
* after the loop, this pass (:func:`tangent_joins`) on the last level;
* a kinked join of the object's silhouette, where no two circles on their
  rungs touch with both arcs within T, has one of its arcs split beside the
  kink (:func:`split_kinks`): a short arc rounds the corner;
* the result may be a level before the last (:func:`tangent_level`): the merge
  loop stops where E^s is within a few tenths of a px of T (the polar bear:
  4.59 of 5), and a tangency there costs 0.1-1 px of E^s (its long arcs move
  5-10 px to touch), while a level with one more arc has shorter arcs and more
  room. The level kept has the fewest arcs plus ``KINK_WEIGHT`` x its kinked
  joins.

On the clip arts and drawings of ``make quality`` the pass alone made 37 % of
70 joins tangent (median kink 9.8 degrees), with the merges judged with their
tangencies 58 % of 88 (40.2 -> 41.6 clip-art arcs), with the level chosen too
78 % of 90 (42.4 arcs; a kink weighing one arc: 72 %), with the biarc starts
91 % of 93 (42.8 arcs; the polar bear 7 of 16 -> 16 of 19 with 32 -> 39 arcs). Tried and not kept, as
they changed nothing or less: every rung pair of one step (8 choices, not 2:
the pass alone stayed at 37 %); and, with a kink weighing one arc, E^s counting
every smooth join's junction by its distance off the line in the merge loop too
(69 % against 72 %; with two arcs a kink, 74 % against 78 % for 0.2 fewer
clip-art arcs) and growing a merge's window to the far circle of a held join
(72 %, the same).

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, cast
from weakref import WeakKeyDictionary

import numpy as np

from ..geometry.golden_ladder import FibonacciLadder
from .constants import (
    ALL_AT_ONCE_TRIES,
    BIARC_STARTS,
    BIARC_STEP,
    BIARC_TURN,
    BIARC_TURN_STEPS,
    CONSTRAINED_FIT_TOL,
    KINK_WEIGHT,
    RUNG_CHOICES,
    SLIDE_MIN_PIXELS,
)
from .fit_state import Seed
from .simplification import Group, merge_groups

if TYPE_CHECKING:
    from ..segment_graph import SegmentGraph
    from .fit_state import FitState, GroupFit, Stats


def tangent_joins(opt: FitState, tolerance: float, most_loose: int | None = None) -> bool:
    """Make the circles of the current state touch at its smooth joins; whether the state changed.

    The joins of ``opt.tangencies`` are made tangent one at a time
    (:func:`_one_at_a_time`); when that leaves some released, the whole
    refit with every tangency at once is tried too (:func:`_all_at_once`),
    and the result with more tangent joins is kept (on a tie the lower E^s):
    one join's refit may spend the slack under T that a joint refit shares.
    Both keep E^s (Eqn. 3) within ``max(tolerance, E^s now)``, move no arc of
    the object's silhouette farther than T from its pixels (or than it was:
    :meth:`~img2logo.fit.fit_state.FitState.strays`) and add no redundant
    intersection and no near-miss gap. Counts go to ``opt.stats.tangent_joins`` and
    ``["released_tangencies"]``.

    With ``most_loose``, a pass that cannot end with at most that many joins
    kinked raises :class:`_Outscored` as soon as that is known, the state left
    half made: once one join at a time has released more, the refit of all at
    once is run (from the state as it came, as it would be after) and, if it
    too leaves more, the joins not yet tried are not.
    """
    seeds = {g: f.seed for g, f in opt.fits.items()}
    joins = opt.tangencies(opt.groups, seeds)
    if not joins:
        return False
    bound = max(float(tolerance), opt.similarity())
    start = _state(opt)
    whole_enough: list[bool] = []

    def give_up(released: int) -> bool:
        """Whether neither way can leave at most ``most_loose`` joins kinked, ``released`` by one at a time."""
        if most_loose is None or released <= most_loose:
            return False
        if not whole_enough:
            now = _state(opt)
            _restore(opt, start)
            # Nonempty only if it leaves at most ``most_loose`` of the joins kinked.
            whole_enough.append(bool(_all_at_once(opt, joins, bound, least=len(joins) - most_loose)))
            _restore(opt, now)
        return not whole_enough[0]

    made = _one_at_a_time(opt, joins, bound, give_up)
    if len(made) < len(joins):
        one = _state(opt), opt.similarity()
        _restore(opt, start)
        whole = _all_at_once(opt, joins, bound, least=len(made))
        if len(whole) > len(made) or (len(whole) == len(made) and opt.similarity() < one[1]):
            made = whole
        else:
            _restore(opt, one[0])
    opt.stats.tangent_joins = len(made)
    opt.stats.released_tangencies = len(opt.loose)
    return bool(made)


def tangent_level(
    opt: FitState, tolerance: float, history: Sequence[tuple], over_budget: Callable[[], bool] | None = None
) -> int:
    """Make the result's smooth joins tangent, on the last level or one before it; how many levels back.

    ``history`` holds :func:`snapshot` of every level of the merge loop, the
    last the current state. A join whose tangency does not fit under T on the
    last level (:func:`tangent_joins`) may fit on a level before it, whose
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
    is). ``opt`` is left in the kept level's state, tangent where it could be made so.
    """
    best: tuple[int, int, tuple, Stats] | None = None
    for back in _levels_back(len(history)):
        if best is not None and (back >= best[0] or (over_budget is not None and over_budget())):
            break
        if back:
            _restore(opt, history[-1 - back])
        opt.loose, opt.off_line = set(), {}
        try:
            # A level back wins only with fewer kinks than this: its pass stops once it cannot.
            tangent_joins(opt, tolerance, None if best is None else (best[0] - back - 1) // KINK_WEIGHT)
        except _Outscored:
            continue
        score = back + KINK_WEIGHT * len(opt.loose)
        if best is None or score < best[0]:
            best = (score, back, _state(opt), replace(opt.stats))
    assert best is not None  # the last level is always tried
    _restore(opt, best[2])
    opt.stats = best[3]
    split_kinks(opt, tolerance)
    return best[1]


def split_kinks(opt: FitState, tolerance: float) -> int:
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
    and no arc of the silhouette moved farther than T from its pixels (or than it was).
    """
    splits = 0
    if not opt.outline or not opt.loose or opt.symmetry is not None:  # a mirror pairs the groups as they are
        return splits
    tried: set[tuple[int, ...]] = set()
    while True:
        seeds = {g: f.seed for g, f in opt.fits.items()}
        loose, opt.loose = opt.loose, set()
        joins = opt.tangencies(opt.groups, seeds)  # the released joins too
        opt.loose = loose
        kinked = sorted(n for n in opt.loose if n in joins and any(opt.on_outline(opt.groups[g]) for g in joins[n]))
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
                before, stats = _state(opt), replace(opt.stats)
                if _split_group(opt, g, inner, bound):
                    opt.loose = set()
                    try:  # kept only below ``score``: the pass stops once it cannot be
                        tangent_joins(opt, tolerance, (score - len(opt.fits) - 1) // KINK_WEIGHT)
                        kept = len(opt.fits) + KINK_WEIGHT * len(opt.loose) < score and opt.similarity() <= bound
                    except _Outscored:
                        kept = False
                    if kept:
                        splits += 1
                        done = True
                        break
                _restore(opt, before)
                opt.stats = stats
            if done:
                break
        if not done:
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
    each half within its :meth:`~img2logo.fit.fit_state.FitState.arc_cap`. On
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
    node_groups = opt.node_groups()
    out = opt.solve(
        dict(opt.groups),
        seeds,
        node_groups,
        changed=halves,
        free_nodes=sorted({n for h in halves for n in opt.constrained_nodes(opt.groups[h])}),
        fixed=set(),
        n_groups_total=len(opt.groups),
        n_junctions_total=len(node_groups),
        rings=2,
    )
    if out is None or not all(h in out[0] for h in halves):
        return False
    fits, disp = out
    if opt.strays(fits, opt.groups, opt.fits):
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


def snapshot(opt: FitState) -> tuple:
    """What a level of the merge loop is in the optimizer's state (a copy), for :func:`tangent_level`."""
    return _state(opt)


def _state(opt: FitState) -> tuple:
    """What the tangent pass changes in the optimizer's state (a copy)."""
    return dict(opt.fits), opt.disp.copy(), dict(opt.groups), dict(opt.off_line), set(opt.loose), set(opt.held)


def _restore(opt: FitState, state: tuple) -> None:
    """Put back a state of :func:`_state` (copied again: it may be restored twice)."""
    fits, disp, groups, off_line, loose, held = state
    if groups.keys() != opt.groups.keys():
        opt.invalidate()
    opt.fits, opt.disp, opt.groups = dict(fits), disp.copy(), dict(groups)
    opt.off_line, opt.loose, opt.held = dict(off_line), set(loose), set(held)


class _Outscored(Exception):
    """A tangent pass of :func:`tangent_level` stopped: its level cannot score better than one tried before."""


def _one_at_a_time(
    opt: FitState,
    joins: dict[int, tuple[int, int]],
    bound: float,
    give_up: Callable[[int], bool] | None = None,
) -> dict[int, tuple[int, int]]:
    """Make ``joins`` tangent one at a time; the joins made.

    Taken in order of their kink now (the nearest to touching first). For each,
    the circles of its two groups, with the groups tied to them by joins
    already made tangent, are refitted in a local window (Sec. 5.4,
    :meth:`~img2logo.fit.fit_state.FitState.solve`) with every tangency made so
    far and this one; first on their rungs, and if that fails, with the rung
    choices of :func:`_rung_choices`, the one of lowest E^s kept; the junction
    slides along the line (:func:`_slide`). A choice is kept only if the fit
    converges, E^s stays within ``bound``, no arc moves farther from its
    pixels than its cap (:meth:`~img2logo.fit.fit_state.FitState.arc_cap`:
    ``arc_bound``, and T on the silhouette) or than it was, the tangencies made before
    still hold, and no redundant intersection or near-miss gap
    (:meth:`~img2logo.fit.fit_state.FitState.gap_ends`) is added; otherwise the join is
    released (``opt.loose``), a kink is left there, and the next join is tried;
    :class:`_Outscored` is raised once ``give_up`` of the number released is true.
    """
    seeds = {g: f.seed for g, f in opt.fits.items()}
    order = sorted(joins, key=lambda n: (_apart(opt, seeds, n, joins[n]), n))
    opt.loose |= set(joins)
    made: dict[int, tuple[int, int]] = {}
    released = 0
    for node in order:
        a, b = joins[node]
        opt.loose.discard(node)
        made[node] = (a, b)
        best = None
        before: dict[frozenset[int], int] = {}  # the state's crossings by window: the same for every try here
        gaps = opt.gap_ends()  # the state's near-miss gaps: the same for every try here
        for combo in _rung_choices(opt, node, (a, b)):
            trial = _try(opt, made, node, combo, bound, before=before, gaps=gaps)
            if trial is not None and (best is None or trial.similarity < best.similarity):
                best = trial
            if best is not None and not any(combo.values()):
                break  # the rungs the paper chose serve: no reason to leave them
        if best is None:
            # No start near the current circles touches within T: fit the pair as one unit
            # (a tangent biarc over the two groups' joined pixels, the junction anywhere on
            # them, :func:`closest_biarcs`) and start the refit from there.
            for combo, start in _biarc_starts(opt, node, (a, b)):
                trial = _try(opt, made, node, combo, bound, start, before=before, gaps=gaps)
                if trial is not None and (best is None or trial.similarity < best.similarity):
                    best = trial
        if best is None:
            del made[node]
            opt.loose.add(node)
            released += 1
            if give_up is not None and give_up(released):
                raise _Outscored
            continue
        opt.fits.update(best.fits)
        for n, d in best.disp.items():
            opt.disp[n] = d
        opt.groups.update(best.groups)
        opt.off_line.update(best.off_line)
    return made


def _all_at_once(
    opt: FitState, joins: dict[int, tuple[int, int]], bound: float, *, least: int = 0
) -> dict[int, tuple[int, int]]:
    """Refit the whole state with every tangency of ``joins`` at once; the joins made.

    Every circle and junction free, straight lines fixed, the rungs and the
    nodes as they are. While the fit fails, lifts E^s above ``bound``, adds a
    redundant intersection or makes a near-miss gap, the join whose circles are farthest from touching
    now is released (``opt.loose``) and the fit tried again; once fewer than
    ``least`` joins are left (what one join at a time made: a result that
    :func:`tangent_joins` would not keep), or after ``ALL_AT_ONCE_TRIES``
    tries, none is made and the state is left for the caller to restore. Each
    try is a global solve, its cost growing with the drawing: unbounded, the
    polar bear's passes made 62 of them (78 % of its time), and on the 47 clip
    arts and drawings of data/ and benchmarks/data/ (held-out ones included)
    its 43 calls made 173 tries without keeping a single result.
    """
    seeds = {g: f.seed for g, f in opt.fits.items()}
    groups = dict(opt.groups)
    node_groups = opt.node_groups()
    before = _state(opt)
    crossings = _redundant(opt, set(groups))
    gaps = opt.gap_ends()
    for _ in range(ALL_AT_ONCE_TRIES):
        touching = opt.tangencies(groups, seeds)
        if not touching or len(touching) < least:
            return {}
        out = opt.solve_whole(
            groups, seeds, node_groups, n_groups_total=len(groups), n_junctions_total=len(node_groups), tangent=True
        )
        if out is not None:
            fits, disp = out
            opt.fits.update(fits)
            for n, d in disp.items():
                opt.disp[n] = d
            if (
                opt.similarity() <= bound
                and not opt.outline_strays(fits, groups, before[0])
                and _redundant(opt, set(groups)) <= crossings
                and opt.gap_ends() <= gaps
            ):
                return touching
            loose = set(opt.loose)
            _restore(opt, before)
            opt.loose = loose
        opt.loose.add(max(touching, key=lambda n: (_apart(opt, seeds, n, touching[n]), -n)))
    return {}


def _rung_choices(opt: FitState, node: int, pair: tuple[int, int]) -> list[dict[int, int]]:
    """Rung changes to try for a join's two circles, group -> step on the ladder: no change first.

    With the radii on the ladder, two circles of given rungs through given
    junctions touch only where the junctions happen to allow it; a circle one
    rung up or down (a factor phi) turns its tangent at the join and may let
    the two touch with a small move. Only circles (not lines), only allowed
    rungs (:func:`_neighbour_rung`), each step at most one rung; and only the
    choices that bring the two circles nearer to touching where the junctions
    are now (:func:`_predicted_apart`), the nearest first, at most
    ``RUNG_CHOICES`` of them (each costs a fit).
    """
    steps: dict[int, list[int]] = {}
    rungs: dict[tuple[int, int], tuple[int, float]] = {}  # (group, step) -> (k, r), each looked up once
    for g in pair:
        steps[g] = [0]
        if opt.fits[g].k is None:
            continue
        for s in (-1, 1):
            rung = _neighbour_rung(opt, g, s)
            if rung is not None:
                rungs[g, s] = rung
                steps[g].append(s)
    a, b = pair
    combos = [{a: sa, b: sb} for sa in steps[a] for sb in steps[b] if sa or sb]
    placed: dict = {}  # each circle's radius to the junction by (group, step), placed once
    now = _predicted_apart(opt, node, pair, {}, placed=placed)
    apart = {i: _predicted_apart(opt, node, pair, c, rungs, placed) for i, c in enumerate(combos)}
    nearer = sorted((i for i in apart if apart[i] < now), key=lambda i: (apart[i], i))
    return [{a: 0, b: 0}, *(combos[i] for i in nearer[:RUNG_CHOICES])]


def _predicted_apart(
    opt: FitState,
    node: int,
    pair: tuple[int, int],
    combo: dict[int, int],
    rungs: dict[tuple[int, int], tuple[int, float]] | None = None,
    placed: dict | None = None,
) -> float:
    """|sin| of the angle between the radii to a join's junction of its two circles, rungs stepped by ``combo``.

    Each circle is placed through the junction and the group's other end
    where they are now (on the side of its centre now): how far from touching
    the choice of rungs leaves the two before any junction moves. Lines keep
    their circle. Infinite if a radius is too short to reach the other end.
    ``rungs`` holds the offered rungs by (group, step) when they are known;
    ``placed`` keeps the circles placed so far by (group, step) for the next
    call on the same join (:func:`_rung_choices` scores up to 9 choices of 6 circles).
    """
    placed = {} if placed is None else placed
    radii = []
    for g in pair:
        step = combo.get(g, 0)
        if (g, step) not in placed:
            placed[g, step] = _placed(opt, node, g, step, rungs)
        radius = placed[g, step]
        if radius is None:
            return np.inf
        radii.append(radius)
    (a, ha), (b, hb) = radii
    return abs(float(a[0] * b[1] - a[1] * b[0])) / max(float(ha * hb), 1e-300)


def _placed(
    opt: FitState, node: int, g: int, step: int, rungs: dict[tuple[int, int], tuple[int, float]] | None
) -> tuple[np.ndarray, Any] | None:
    """:func:`_predicted_apart`'s circle of group ``g`` at the join ``node``, its rung stepped by ``step``.

    (its radius vector to the junction, that vector's length); None if the
    radius is too short to reach the group's other end.
    """
    q = opt.graph.junctions[node] + opt.disp[node]
    f, group = opt.fits[g], opt.groups[g]
    center = f.center
    if f.k is not None:
        r = f.radius if not step else (rungs[g, step] if rungs else _offered_rung(opt, g, step))[1]
        other = group.nodes[0] if group.nodes[-1] == node else group.nodes[-1]
        p = opt.graph.junctions[other] + opt.disp[other]
        half = 0.5 * float(np.hypot(*(p - q)))
        if r < half or half == 0.0:
            return None
        mid, u = 0.5 * (p + q), np.array([q[1] - p[1], p[0] - q[0]]) / (2.0 * half)
        s = np.sqrt(r * r - half * half)
        side = 1.0 if float((f.center - mid) @ u) >= 0.0 else -1.0
        center = mid + side * s * u
    radius = center - q
    return radius, np.hypot(*radius)


def _offered_rung(opt: FitState, gid: int, step: int) -> tuple[int, float]:
    """:func:`_neighbour_rung` for a step :func:`_rung_choices` offered (so it exists)."""
    rung = _neighbour_rung(opt, gid, step)
    if rung is None:
        raise RuntimeError(f"group {gid} has no rung {step:+d} from its own; it was not offered")
    return rung


def _neighbour_rung(opt: FitState, gid: int, step: int) -> tuple[int, float] | None:
    """The allowed rung ``step`` (-1 or +1) places from group ``gid``'s, (k, r); None if there is none.

    A rung whose circle cannot reach the group's junctions (a diameter shorter
    than their span, :meth:`~img2logo.fit.fit_state.FitState.reach`) is none.
    """
    ladder, k = opt.ladder, opt.fits[gid].k
    if k is None:
        return None  # a straight line has no rung
    if ladder.exponents is not None:
        allowed = sorted(ladder.exponents)
        if k not in allowed:
            return None
        i = allowed.index(k) + step
        if not 0 <= i < len(allowed):
            return None
        j = allowed[i]
    else:
        j = k + step
        if j < 2 and isinstance(ladder, FibonacciLadder):
            return None  # F(1) = F(2): k = 2 is the unit, the smallest rung
    r = ladder.radius(j)
    if r < opt.reach(opt.groups[gid]):
        return None
    return j, r


@dataclass
class _Trial:
    """A tangent refit tried for one join (:func:`_try`): what applying it changes."""

    similarity: float  # E^s (Eqn. 3) after it, px
    fits: dict[int, GroupFit]  # the new fits of the window's groups
    disp: dict[int, np.ndarray]  # node -> new d_k
    groups: dict[int, Group]  # groups whose pixels were split anew at a slid join
    off_line: dict[int, float]  # tangent join -> its junction's distance off the input's line, px


def _try(
    opt: FitState,
    made: dict[int, tuple[int, int]],
    node: int,
    combo: dict[int, int],
    bound: float,
    start: _Start | None = None,
    *,
    before: dict[frozenset[int], int] | None = None,
    gaps: set[int] | None = None,
) -> _Trial | None:
    """Refit the window of the join at ``node`` with the rung steps ``combo``; None if it fails a rule.

    The rules are those of :func:`tangent_joins`. After the fit, the pixels of
    the two groups at every tangent join in the window are split anew where the
    junction now is (:func:`split_chain`), and their arcs extracted and scored
    against them: in the solve, before any arc is extracted, which stops
    extracting once E^s must exceed ``bound`` (``FitState.solve``'s ``bound``
    and ``regroup``; measured, the arcs extracted in the tangent pass 286 -> 212
    on the clip-art fish, 4986 -> 3815 on the polar bear, the same results).
    With ``start`` (:func:`_biarc_starts`) the fit starts from a tangent
    biarc (its arcs extracted after the fit, as before): the join's two circles there, their pixels split at its
    junction, and the junction's rest point moved there for the fit (its
    displacement term of Eqn. 13 pulls towards the biarc's junction, not back
    along the line to the node). The state is left as it was. ``before`` caches
    the state's redundant intersections by the groups refitted, for the tries of
    one join (the state does not change between them); ``gaps`` the state's
    near-miss gaps (:meth:`~img2logo.fit.fit_state.FitState.gap_ends`, made here without it).
    """
    seeds = {g: f.seed for g, f in opt.fits.items()}
    for g, step in combo.items():
        if step:
            k, r = _offered_rung(opt, g, step)
            seeds[g] = Seed(opt.fits[g].center, r, k)
    changed, free = _window(opt, made, made[node])
    node_groups = opt.node_groups()
    saved = dict(opt.fits), opt.disp.copy(), dict(opt.groups), dict(opt.off_line)
    graph = opt.graph
    slid: tuple[dict[int, Group], dict[int, float]] = ({}, {})

    def regroup(at: Any, moved: set[int]) -> tuple[dict[int, Group], dict[int, float]] | None:
        nonlocal slid
        groups, off_line = _slide(opt, made, moved, at)
        if groups is None:
            return None
        slid = groups, off_line
        return slid

    try:
        if start is not None:
            seeds.update(start.seeds)
            opt.groups.update(start.groups)
            rest = graph.junctions.copy()
            rest[node] = start.junction
            opt.disp[node] = 0.0
            opt.graph = cast("SegmentGraph", _Moved(graph, rest))
        out = opt.solve(
            dict(opt.groups),
            seeds,
            node_groups,
            changed=sorted(changed),
            free_nodes=sorted(free),
            fixed=set(),
            n_groups_total=len(opt.groups),
            n_junctions_total=len(node_groups),
            rings=2,
            tangent=True,
            # E^s above ``bound`` fails the try below: no arc is extracted once it must be, and the
            # groups at the tangent joins are split anew (:func:`_slide`) before their arcs are
            # extracted, not after. A biarc's start keeps the order below: its junction's rest point
            # is moved for the fit and its arcs read the graph's own again.
            bound=None if start is not None else bound,
            regroup=None if start is not None else regroup,
        )
        if start is not None:
            opt.graph = graph
            if out is not None:  # the displacements from the graph's own node again
                out[1][node] = out[1].get(node, opt.disp[node]) + start.junction - graph.junctions[node]
        if out is None:
            return None
        fits, disp = out
        opt.fits.update(fits)
        for n, d in disp.items():
            opt.disp[n] = d
        if start is None:
            groups, off_line = slid  # split in the solve, the arcs extracted there
        else:
            moved, off_line = _slide(opt, made, set(fits))
            if moved is None:
                return None
            groups = moved
            for g, group in groups.items():
                f = opt.fits[g]
                fits[g] = replace(f, arc=opt.arc_for(group, f.center, f.radius, f.k, opt.disp.__getitem__))
        opt.groups.update(groups)
        opt.off_line.update(off_line)
        if opt.strays(fits, opt.groups, saved[0]):
            return None
        opt.fits.update(fits)
        similarity = opt.similarity()
        if similarity > bound or not _touching(opt, made):
            return None
        crossings = _redundant(opt, set(fits))
        made_gaps = opt.gap_ends()
    finally:
        opt.graph = graph
        opt.fits, opt.disp, opt.groups, opt.off_line = saved
    before = {} if before is None else before
    key = frozenset(fits)
    if key not in before:
        before[key] = _redundant(opt, set(fits))
    if crossings > before[key]:
        return None
    if not made_gaps <= (opt.gap_ends() if gaps is None else gaps):
        return None
    return _Trial(similarity, fits, disp, groups, off_line)


class _Moved:
    """A segment graph with other rest points for its junctions (a biarc's start, :func:`_try`)."""

    def __init__(self, graph: SegmentGraph, junctions: np.ndarray) -> None:
        self._graph = graph
        self.junctions = junctions

    def __getattr__(self, name: str) -> Any:
        return getattr(self._graph, name)


@dataclass(frozen=True)
class _Start:
    """A tangent biarc to start a join's refit from (:func:`_biarc_starts`)."""

    seeds: dict[int, Seed]  # the two groups' circles, touching at ``junction``
    groups: dict[int, Group]  # the two groups, their pixels split at ``junction``
    junction: np.ndarray  # (2,) px, on the joined pixel chain


def _biarc_starts(opt: FitState, node: int, pair: tuple[int, int]) -> list[tuple[dict[int, int], _Start]]:
    """Tangent biarcs over a smooth join's two groups, as starts of its refit: (rung steps, start), best first.

    Why: two circles of fixed rungs touch at one point only, and where the
    curvature of a smooth line changes from one rung to the next is seldom where
    the over-segmentation put the node: measured on the polar bear's kinked
    joins, the best tangent biarc over the two groups' joined pixels has its
    junction 15-85 px along the line from the node, and its pixels within
    1.5-3 px of its circles (the two arcs now: 1-4 px), while the refit from the
    current circles keeps the junction within a few px of the node (its
    displacement term) and each group's pixels on their own circle. So the two
    circles are fitted as one unit (:func:`closest_biarcs`) on the rungs of both and one
    rung up or down for each, and the ``BIARC_STARTS`` of smallest largest
    pixel distance are returned. None for a straight line (fixed) or a closed group.
    """
    a, b = pair
    fa, fb = opt.fits[a], opt.fits[b]
    ga, gb = opt.groups[a], opt.groups[b]
    if fa.k is None or fb.k is None or ga.closed or gb.closed:
        return []
    chain = merge_groups(ga, gb, node).points
    rungs = {}
    for g in pair:
        k = cast(int, opt.fits[g].k)
        rungs[g] = [(0, k, opt.fits[g].radius)]
        rungs[g] += [(s, *r) for s in (-1, 1) if (r := _neighbour_rung(opt, g, s)) is not None]
    radii = tuple(r for g in pair for _, _, r in rungs[g])
    key = (ga.segments, gb.segments, node, len(chain), *chain[0], *chain[-1], *radii)
    cache = _BIARCS.setdefault(opt, {})
    if key not in cache:
        cache[key] = closest_biarcs(chain, [r for _, _, r in rungs[a]], [r for _, _, r in rungs[b]])
    found = cache[key]
    out = []
    for _, ia, ib, i, ca, cb in found[:BIARC_STARTS]:
        (sa, ka, ra), (sb, kb, rb) = rungs[a][ia], rungs[b][ib]
        head, tail = chain[: i + 1], chain[i:]
        groups = {
            a: replace(ga, points=head if ga.nodes[-1] == node else head[::-1]),
            b: replace(gb, points=tail if gb.nodes[0] == node else tail[::-1]),
        }
        seeds = {a: Seed(ca, ra, ka), b: Seed(cb, rb, kb)}
        out.append(({a: sa, b: sb}, _Start(seeds, groups, chain[i].copy())))
    return out


#: The biarcs of a run's smooth joins (:func:`closest_biarcs`), by the joined pixels and the radii:
#: the levels that :func:`tangent_level` tries share most of their groups.
_BIARCS: WeakKeyDictionary[FitState, dict[tuple, list]] = WeakKeyDictionary()


def closest_biarcs(
    chain: np.ndarray, radii_a: Sequence[float], radii_b: Sequence[float]
) -> list[tuple[float, int, int, int, np.ndarray, np.ndarray]]:
    """The tangent biarcs closest to a pixel chain (n, 2), one per pair of radii: best first.

    For every radius ``radii_a[ia]`` of the head's circle and ``radii_b[ib]`` of
    the tail's: the junction is a pixel ``chain[i]`` (at least
    ``SLIDE_MIN_PIXELS`` from either end); the common tangent there is the
    chain's direction turned by up to ``BIARC_TURN`` rad either way; each circle
    on either side. The head ``chain[:i + 1]`` goes with the first circle, the
    tail ``chain[i:]`` with the second; the biarc kept has the smallest largest
    distance of a pixel from its circle (the discrete Fréchet distance of E^s
    is at least that). Searched on a grid (every ``BIARC_STEP`` pixels, every
    ``BIARC_TURN / BIARC_TURN_STEPS`` rad, every ``BIARC_STEP``-th pixel
    measured), then around the best of each pair on every pixel and a grid four
    times finer. Returns (largest distance px, ia, ib, i, centre a, centre b)
    sorted by the distance; empty if the chain is too short.
    """
    n = len(chain)
    lo, hi = SLIDE_MIN_PIXELS + 1, n - SLIDE_MIN_PIXELS - 1
    if hi <= lo:
        return []
    step = BIARC_TURN / BIARC_TURN_STEPS
    splits = np.arange(lo, hi, BIARC_STEP)
    turns = np.arange(-BIARC_TURN_STEPS, BIARC_TURN_STEPS + 1) * step
    sides = ((-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0))
    coarse = biarc_coarse(chain, splits, turns, radii_a, radii_b)
    out = []
    for ia, ra in enumerate(radii_a):
        for ib, rb in enumerate(radii_b):
            j, s, t = coarse[ia, ib]
            sa, sb = sides[j]
            # Around the best on the coarse grid: every pixel and a finer turn, every pixel measured.
            fine = np.arange(max(lo, splits[s] - BIARC_STEP), min(hi, splits[s] + BIARC_STEP + 1))
            near = turns[t] + np.arange(-4, 5) * (step / 4.0)
            worst, s2, t2 = biarc_fine(chain, fine, near, (ra, sa), (rb, sb))
            i = int(fine[s2])
            normal = biarc_normals(chain, np.array([i]), np.array([near[t2]]))[0, 0]
            out.append((worst, ia, ib, i, chain[i] + sa * ra * normal, chain[i] + sb * rb * normal))
    out.sort(key=lambda t: t[0])
    return out


def biarc_coarse(
    chain: np.ndarray, splits: np.ndarray, turns: np.ndarray, radii_a: Sequence[float], radii_b: Sequence[float]
) -> dict[tuple[int, int], tuple[int, int, int]]:
    """The best biarc of :func:`closest_biarcs`'s coarse grid for every pair of radii: (ia, ib) -> (sides, split, turn).

    Sides index ``((-1, -1), (-1, 1), (1, -1), (1, 1))`` (the head's circle's and
    the tail's); every ``BIARC_STEP``-th pixel measured. The smallest largest
    distance over the sides and the grid, the first in that order on a tie.
    Compiled (:func:`img2logo._compiled.arcs.biarc_coarse_kernel`), a biarc's
    pixels stop being measured once it cannot beat the best so far: the same
    choice as the smallest of numpy's minima over the four grids of the two
    sides' :func:`biarc_worst`, and its argmin.
    """
    normal = biarc_normals(chain, splits, turns)  # shared by every radius and side
    from .._compiled import kernels

    out = {}
    if kernels.usable():
        base = chain[splits][:, None, :]
        heads = [np.stack([base + side * r * normal for side in (-1.0, 1.0)]) for r in radii_a]
        tails = [np.stack([base + side * r * normal for side in (-1.0, 1.0)]) for r in radii_b]
        index = np.arange(0, len(chain), BIARC_STEP)
        at = np.asarray(splits, dtype=np.int64)
        for ia, ra in enumerate(radii_a):
            for ib, rb in enumerate(radii_b):
                _, j, s, t = kernels.biarc_coarse_kernel(chain, index, at, heads[ia], tails[ib], ra, rb)
                out[ia, ib] = (int(j), int(s), int(t))
        return out
    sides = ((-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0))
    head = [
        {sa: biarc_worst(chain, splits, turns, r, sa, True, BIARC_STEP, normal) for sa in (-1.0, 1.0)} for r in radii_a
    ]
    tail = [
        {sb: biarc_worst(chain, splits, turns, r, sb, False, BIARC_STEP, normal) for sb in (-1.0, 1.0)} for r in radii_b
    ]
    for ia in range(len(radii_a)):
        for ib in range(len(radii_b)):
            w = [np.maximum(head[ia][sa], tail[ib][sb]) for sa, sb in sides]
            j = min(range(4), key=lambda j: float(w[j].min()))
            s, t = np.unravel_index(int(np.argmin(w[j])), w[j].shape)
            out[ia, ib] = (j, int(s), int(t))
    return out


def biarc_fine(
    chain: np.ndarray, splits: np.ndarray, turns: np.ndarray, head: tuple[float, float], tail: tuple[float, float]
) -> tuple[float, int, int]:
    """The best biarc of a grid of ``splits`` and ``turns``: (largest pixel distance px, split index, turn index).

    ``head`` and ``tail`` are the two circles' (radius, side); every pixel is
    measured. The smallest over the grid of the larger of the head's and the
    tail's :func:`biarc_worst`, the first in row-major order on a tie. Compiled
    (:func:`img2logo._compiled.arcs.biarc_best_kernel`), a biarc's pixels stop
    being measured once it cannot beat the best so far: the same numbers as the
    two grids, a third of the work on the clip arts' joins.
    """
    (ra, sa), (rb, sb) = head, tail
    from .._compiled import kernels

    if kernels.usable():
        normal = biarc_normals(chain, splits, turns)
        base = chain[splits][:, None, :]
        worst, s, t = kernels.biarc_best_kernel(
            chain, base + sa * ra * normal, base + sb * rb * normal, np.asarray(splits, dtype=np.int64), ra, rb
        )
        return float(worst), int(s), int(t)
    w = np.maximum(
        biarc_worst(chain, splits, turns, ra, sa, True, 1), biarc_worst(chain, splits, turns, rb, sb, False, 1)
    )
    s, t = np.unravel_index(int(np.argmin(w)), w.shape)
    return float(w[s, t]), int(s), int(t)


def biarc_normals(chain: np.ndarray, splits: np.ndarray, turns: np.ndarray) -> np.ndarray:
    """Unit normals (S, A, 2) of the chain's direction at pixels ``splits`` turned by ``turns`` rad."""
    n = len(chain)
    d = chain[np.minimum(splits + 3, n - 1)] - chain[np.maximum(splits - 3, 0)]
    theta = np.arctan2(d[:, 1], d[:, 0])[:, None] + turns[None, :]
    return np.stack([-np.sin(theta), np.cos(theta)], axis=-1)


def biarc_worst(
    chain: np.ndarray,
    splits: np.ndarray,
    turns: np.ndarray,
    r: float,
    side: float,
    head: bool,
    stride: int,
    normal: np.ndarray | None = None,
) -> np.ndarray:
    """Largest distance (S, A) px of the head's (or tail's) pixels from a circle of radius ``r``, per split and turn.

    The circle touches the chain's turned direction at ``chain[split]``, its
    centre on the ``side`` (+1 or -1) of it; every ``stride``-th pixel measured.
    ``normal`` is :func:`biarc_normals` of ``splits`` and ``turns`` when known.
    """
    if normal is None:
        normal = biarc_normals(chain, splits, turns)
    centre = chain[splits][:, None, :] + side * r * normal  # (S, A, 2)
    index = np.arange(0, len(chain), stride)
    from .._compiled import kernels

    if kernels.usable():  # the same numbers, without the (S, A, m) distances of both sides
        return kernels.biarc_worst_kernel(chain, centre, index, np.asarray(splits, dtype=np.int64), float(r), head)
    return _biarc_worst_reference(chain, centre, index, splits, r, head)


def _biarc_worst_reference(
    chain: np.ndarray, centre: np.ndarray, index: np.ndarray, splits: np.ndarray, r: float, head: bool
) -> np.ndarray:
    """:func:`biarc_worst` in numpy past the centres (S, A, 2): the compiled kernel's reference."""
    sample = chain[index]
    dist = np.abs(np.hypot(sample[:, 0] - centre[..., :1], sample[:, 1] - centre[..., 1:]) - r)  # (S, A, m)
    mine = index[None, :] <= splits[:, None] if head else index[None, :] >= splits[:, None]
    return np.where(mine[:, None, :], dist, 0.0).max(axis=-1)


def _slide(
    opt: FitState, made: dict[int, tuple[int, int]], moved: set[int], disp: Any = None
) -> tuple[dict[int, Group] | None, dict[int, float]]:
    """The groups split anew at the tangent joins of ``moved`` groups, and those joins' distances off the line.

    At a smooth join the node is only where the over-segmentation happened to
    split one smooth feature line: a junction that slides along the line to
    where the two circles touch moves the logo away from nothing. So the two
    groups' pixels are split where the displaced junction projects on their
    joined pixel chain (:func:`split_chain`), and E^s counts the junction's distance
    off the line instead of its displacement (``opt.off_line``). (None, {}) if
    a junction slid past the end of one of the groups (fewer than
    ``SLIDE_MIN_PIXELS`` left): the join would swallow it. ``disp``: node ->
    d_k (default the state's), for a fit not applied yet.
    """
    disp = opt.disp.__getitem__ if disp is None else disp
    groups: dict[int, Group] = {}
    off: dict[int, float] = {}
    for n, (a, b) in made.items():
        if a not in moved and b not in moved:
            continue
        ga, gb = groups.get(a, opt.groups[a]), groups.get(b, opt.groups[b])
        chain = merge_groups(ga, gb, n).points
        split = split_chain(chain, opt.graph.junctions[n] + disp(n))
        if split is None:
            return None, {}
        pa, pb, off[n] = split
        groups[a] = replace(ga, points=pa if ga.nodes[-1] == n else pa[::-1])
        groups[b] = replace(gb, points=pb if gb.nodes[0] == n else pb[::-1])
    return groups, off


def split_chain(chain: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, float] | None:
    """Split a pixel chain (n, 2) px at the point nearest ``q``: (head, tail, distance of q from the chain, px).

    The nearest point of the polyline ends the head and starts the tail. None
    if either would keep fewer than ``SLIDE_MIN_PIXELS`` pixels.
    """
    a, v = chain[:-1], np.diff(chain, axis=0)
    t = np.clip(np.einsum("ij,ij->i", q - a, v) / np.maximum(np.einsum("ij,ij->i", v, v), 1e-300), 0.0, 1.0)
    foot = a + t[:, None] * v
    dist = np.hypot(*(q - foot).T)
    i = int(np.argmin(dist))
    head, tail = np.vstack([chain[: i + 1], foot[i]]), np.vstack([foot[i], chain[i + 1 :]])
    if len(head) <= SLIDE_MIN_PIXELS or len(tail) <= SLIDE_MIN_PIXELS:  # the pixels and the foot
        return None
    return head, tail, float(dist[i])


def _window(opt: FitState, made: dict[int, tuple[int, int]], pair: tuple[int, int]) -> tuple[set[int], set[int]]:
    """The groups and the free junctions of a join's window: (changed groups, free nodes).

    The join's two groups, and every group tied to them by a tangent join
    already made (a chain of touching circles moves as one); their junctions
    are free. A circle of the window that touches one outside it at a fixed
    junction would turn about that junction and break the tangency: the
    junction is freed too, which brings the other circle in.
    """
    changed = set(pair)
    grown = True
    while grown:
        grown = False
        for x, y in made.values():
            if (x in changed) != (y in changed):
                changed |= {x, y}
                grown = True
    free = {n for g in changed for n in opt.constrained_nodes(opt.groups[g])}
    node_groups = opt.node_groups()
    while True:
        members = changed | {c for n in free for c in node_groups.get(n, ())}
        more = {m for m, (x, y) in made.items() if ((x in members) != (y in members)) and m not in free}
        if not more:
            return changed, free
        free |= more


def _touching(opt: FitState, made: dict[int, tuple[int, int]]) -> bool:
    """Whether the circles of every join in ``made`` touch at it, to ``CONSTRAINED_FIT_TOL`` px (see :func:`_apart`)."""
    seeds = {g: f.seed for g, f in opt.fits.items()}
    return all(
        _apart(opt, seeds, n, pair) * min(opt.fits[pair[0]].radius, opt.fits[pair[1]].radius) <= CONSTRAINED_FIT_TOL
        for n, pair in made.items()
    )


def _redundant(opt: FitState, of: set[int]) -> int:
    """Redundant intersections (Sec. 5.2, Fig. 12) of the state's arcs that involve the groups ``of``.

    :meth:`FitState.redundant_pairs <img2logo.fit.fit_state.FitState.redundant_pairs>`, counted.
    """
    return len(opt.redundant_pairs(of))


def _apart(opt: FitState, seeds: dict, node: int, pair: tuple[int, int]) -> float:
    """|sin| of the angle between two circles' radii to a junction: 0 where they touch there."""
    p = opt.graph.junctions[node] + opt.disp[node]
    a, b = seeds[pair[0]][0] - p, seeds[pair[1]][0] - p
    return abs(float(a[0] * b[1] - a[1] * b[0])) / max(float(np.hypot(*a) * np.hypot(*b)), 1e-300)
