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

* **the rungs of the two circles are chosen jointly** (:func:`~img2logo.fit.tangent_rungs.rung_choices`):
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
  its junction anywhere on the pixels, :func:`~img2logo.fit.biarcs.closest_biarcs`) is the refit's start,
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
short piece of the over-segmentation: enforcing every tangency from A^0 on
leaves no merge under T. So four narrower steps:

* a merge is judged with the tangencies it leaves in place
  (:func:`img2logo.fit.merging.evaluate`): the smooth joins at the merged arc's
  two ends, and those earlier merges made tangent (``FitState.held``), are held
  in its local refit, so the merge error is the E^s of the logo with them;
* after the loop, this pass (:func:`tangent_joins`) on the last level;
* a kinked join of the object's silhouette has one of its arcs split beside
  the kink, and the result may be a level before the last, the one with the
  fewest arcs plus ``KINK_WEIGHT`` x its kinked joins (:mod:`img2logo.fit.kinks`).

Measured, and what was tried and not kept: ``docs/design/tangency.md``.

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Mapping
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING, Any, cast
from weakref import WeakKeyDictionary

import numpy as np

from .constants import (
    ALL_AT_ONCE_TRIES,
    BIARC_STARTS,
    CONSTRAINED_FIT_TOL,
    SLIDE_MIN_PIXELS,
)
from .fit_values import Seed
from .simplification import Group, merge_groups

if TYPE_CHECKING:
    from .fit_state import FitState
    from .fit_values import GroupFit
from . import window_solve
from .biarcs import closest_biarcs
from .merge_checks import gap_ends, redundant_pairs
from .outline import outline_strays, strays
from .tangent_rungs import neighbour_rung, offered_rung, rung_choices


def tangent_joins(opt: FitState, tolerance: float, most_loose: int | None = None) -> bool:
    """Make the circles of the current state touch at its smooth joins; whether the state changed.

    The joins of ``opt.tangencies`` are made tangent one at a time
    (:func:`_one_at_a_time`); when that leaves some released, the whole
    refit with every tangency at once is tried too (:func:`_all_at_once`),
    and the result with more tangent joins is kept (on a tie the lower E^s):
    one join's refit may spend the slack under T that a joint refit shares.
    Both keep E^s (Eqn. 3) within ``max(tolerance, E^s now)``, move no arc of
    the object's silhouette farther than T from its pixels (or than it was:
    :func:`~img2logo.fit.outline.strays`) and add no redundant
    intersection and no near-miss gap. Counts go to ``opt.stats.tangent_joins`` and
    ``["released_tangencies"]``.

    With ``most_loose``, a pass that cannot end with at most that many joins
    kinked raises :class:`Outscored` as soon as that is known, the state left
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
            restore(opt, start)
            # Nonempty only if it leaves at most ``most_loose`` of the joins kinked.
            whole_enough.append(bool(_all_at_once(opt, joins, bound, least=len(joins) - most_loose)))
            restore(opt, now)
        return not whole_enough[0]

    made = _one_at_a_time(opt, joins, bound, give_up)
    if len(made) < len(joins):
        one = _state(opt), opt.similarity()
        restore(opt, start)
        whole = _all_at_once(opt, joins, bound, least=len(made))
        if len(whole) > len(made) or (len(whole) == len(made) and opt.similarity() < one[1]):
            made = whole
        else:
            restore(opt, one[0])
    opt.stats.tangent_joins = len(made)
    opt.stats.released_tangencies = len(opt.loose)
    return bool(made)


def snapshot(opt: FitState) -> tuple:
    """What a level of the merge loop is in the optimizer's state (a copy).

    For :func:`~img2logo.fit.kinks.tangent_level`.
    """
    return _state(opt)


def _state(opt: FitState) -> tuple:
    """What the tangent pass changes in the optimizer's state (a copy)."""
    return dict(opt.fits), opt.disp.copy(), dict(opt.groups), dict(opt.off_line), set(opt.loose), set(opt.held)


def restore(opt: FitState, state: tuple) -> None:
    """Put back a state of :func:`snapshot` (copied again: it may be restored twice)."""
    fits, disp, groups, off_line, loose, held = state
    if groups.keys() != opt.groups.keys():
        opt.invalidate()
    opt.fits, opt.disp, opt.groups = dict(fits), disp.copy(), dict(groups)
    opt.off_line, opt.loose, opt.held = dict(off_line), set(loose), set(held)


class Outscored(Exception):
    """A tangent pass stopped: its level cannot score better than one tried before.

    Raised for :func:`~img2logo.fit.kinks.tangent_level`.
    """


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
    :func:`~img2logo.fit.window_solve.solve`) with every tangency made so
    far and this one; first on their rungs, and if that fails, with the rung
    choices of :func:`~img2logo.fit.tangent_rungs.rung_choices`, the one of lowest E^s kept; the junction
    slides along the line (:func:`_slide`). A choice is kept only if the fit
    converges, E^s stays within ``bound``, no arc moves farther from its
    pixels than its cap (:func:`~img2logo.fit.outline.arc_cap`:
    ``arc_bound``, and T on the silhouette) or than it was, the tangencies made before
    still hold, and no redundant intersection or near-miss gap
    (:func:`~img2logo.fit.merge_checks.gap_ends`) is added; otherwise the join is
    released (``opt.loose``), a kink is left there, and the next join is tried;
    :class:`Outscored` is raised once ``give_up`` of the number released is true.
    """
    seeds = {g: f.seed for g, f in opt.fits.items()}
    order = sorted(joins, key=lambda n: (_apart(opt, seeds, n, joins[n]), n))
    # The state's tangencies but for the joins loose at the time: a try moves pixels and rungs, not ends.
    every = opt.tangencies(opt.groups, seeds)
    opt.loose |= set(joins)
    made: dict[int, tuple[int, int]] = {}
    released = 0
    for node in order:
        a, b = joins[node]
        opt.loose.discard(node)
        made[node] = (a, b)
        join = _join(opt, made, node, {n: pair for n, pair in every.items() if n not in opt.loose})
        # The rungs the paper chose first: when they serve, no reason to leave them (nor to rank the others).
        best = _try(opt, made, join, {a: 0, b: 0}, bound)
        if best is None:
            for combo in rung_choices(opt, node, (a, b))[1:]:
                # A try kept only below the best's E^s: its solve stops once E^s must reach that.
                trial = _try(opt, made, join, combo, bound if best is None else min(bound, best.similarity))
                if trial is not None and (best is None or trial.similarity < best.similarity):
                    best = trial
        if best is None:
            # No start near the current circles touches within T: fit the pair as one unit
            # (a tangent biarc over the two groups' joined pixels, the junction anywhere on
            # them, :func:`~img2logo.fit.biarcs.closest_biarcs`) and start the refit from there.
            for combo, start in _biarc_starts(opt, node, (a, b)):
                # As above: a try that cannot beat the best so far stops early.
                trial = _try(opt, made, join, combo, bound if best is None else min(bound, best.similarity), start)
                if trial is not None and (best is None or trial.similarity < best.similarity):
                    best = trial
        if best is None:
            del made[node]
            opt.loose.add(node)
            released += 1
            if give_up is not None and give_up(released):
                raise Outscored
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
    # The state's redundant intersections and near-miss gaps, read once a refit needs them (most end above
    # ``bound``, and the solve then returns None): the state is as it came until a refit is applied.
    crossings: int | None = None
    gaps: set[int] = set()
    for _ in range(ALL_AT_ONCE_TRIES):
        touching = opt.tangencies(groups, seeds)
        if not touching or len(touching) < least:
            return {}
        out = window_solve.solve_whole(
            opt,
            groups,
            seeds,
            node_groups,
            tangent=True,
            bound=bound,  # E^s above it fails the try below: its arcs are extracted only while it may not
        )
        if out is not None:
            if crossings is None:
                crossings, gaps = _redundant(opt, set(groups)), gap_ends(opt)
            fits, disp = out
            opt.fits.update(fits)
            for n, d in disp.items():
                opt.disp[n] = d
            if (
                opt.similarity() <= bound
                and not outline_strays(opt, fits, groups, before[0])
                and _redundant(opt, set(groups)) <= crossings
                and gap_ends(opt) <= gaps
            ):
                return touching
            loose = set(opt.loose)
            restore(opt, before)
            opt.loose = loose
        opt.loose.add(max(touching, key=lambda n: (_apart(opt, seeds, n, touching[n]), -n)))
    return {}


@dataclass
class _Trial:
    """A tangent refit tried for one join (:func:`_try`): what applying it changes."""

    similarity: float  # E^s (Eqn. 3) after it, px
    fits: dict[int, GroupFit]  # the new fits of the window's groups
    disp: dict[int, np.ndarray]  # node -> new d_k
    groups: dict[int, Group]  # groups whose pixels were split anew at a slid join
    off_line: dict[int, float]  # tangent join -> its junction's distance off the input's line, px


@dataclass(frozen=True)
class _Join:
    """What every try of one join shares (:func:`_try`): the state does not change between them."""

    node: int  # the join's node
    seeds: dict[int, Seed]  # the state's circles
    changed: list[int]  # the window's groups (:func:`_window`), sorted
    free: list[int]  # its free junctions, sorted
    lines: set[int]  # the groups that are straight lines: fixed in the fit, never given a rung
    touching: dict[int, tuple[int, int]]  # the joins held tangent: a try moves pixels and rungs, not ends
    gaps: set[int]  # the state's near-miss gaps (:func:`~img2logo.fit.merge_checks.gap_ends`)
    crossings: dict[frozenset[int], int]  # the state's redundant intersections by the groups refitted
    chains: dict  # the joined pixels of two groups at a join (:func:`_slide`), by the join and the groups


def _join(opt: FitState, made: dict[int, tuple[int, int]], node: int, touching: dict[int, tuple[int, int]]) -> _Join:
    """The :class:`_Join` of the join at ``node`` (in ``made``) in the current state, ``touching`` its tangencies."""
    changed, free = _window(opt, made, made[node])
    now = {g: f.seed for g, f in opt.fits.items()}
    return _Join(
        node,
        now,
        sorted(changed),
        sorted(free),
        {g for g, seed in now.items() if seed.k is None},
        touching,
        gap_ends(opt),
        {},
        {},
    )


def _try(
    opt: FitState,
    made: dict[int, tuple[int, int]],
    join: _Join,
    combo: dict[int, int],
    bound: float,
    start: _Start | None = None,
) -> _Trial | None:
    """Refit the window of ``join`` with the rung steps ``combo``; None if it fails a rule.

    The rules are those of :func:`tangent_joins`. After the fit, the pixels of
    the two groups at every tangent join in the window are split anew where the
    junction now is (:func:`split_chain`), and their arcs extracted and scored
    against them: in the solve, before any arc is extracted, which stops
    extracting once E^s must exceed ``bound`` (``window_solve.solve``'s ``bound``
    and ``regroup``; measured, the arcs extracted in the tangent pass 286 -> 212
    on the clip-art fish, 4986 -> 3815 on the polar bear, the same results).
    With ``start`` (:func:`_biarc_starts`) the fit starts from a tangent
    biarc: the join's two circles there, their pixels split at its
    junction, and the junction's rest point moved there for the fit (its
    displacement term of Eqn. 13 pulls towards the biarc's junction, not back
    along the line to the node; ``window_solve.solve``'s ``rest``). The state is left as it was;
    ``join.crossings`` gains the state's redundant intersections of the groups refitted.
    """
    seeds = dict(join.seeds)
    for g, step in combo.items():
        if step:
            k, r = offered_rung(opt, g, step)
            seeds[g] = Seed(opt.fits[g].center, r, k)
    node_groups = opt.node_groups()
    saved = dict(opt.fits), opt.disp.copy(), dict(opt.groups), dict(opt.off_line)
    slid: tuple[dict[int, Group], dict[int, float]] = ({}, {})

    def regroup(at: Any, moved: set[int]) -> tuple[dict[int, Group], dict[int, float]] | None:
        nonlocal slid
        groups, off_line = _slide(opt, made, moved, at, join.chains)
        if groups is None:
            return None
        slid = groups, off_line
        return slid

    try:
        if start is not None:
            seeds.update(start.seeds)
            opt.groups.update(start.groups)
        out = window_solve.solve(
            opt,
            dict(opt.groups),
            seeds,
            node_groups,
            changed=join.changed,
            free_nodes=join.free,
            fixed=set(),
            rings=2,
            tangent=join.touching,
            lines=join.lines,
            # E^s above ``bound`` fails the try below: no arc is extracted once it must be, and the
            # groups at the tangent joins are split anew (:func:`_slide`) before their arcs are
            # extracted, not after.
            bound=bound,
            regroup=regroup,
            rest=None if start is None else {join.node: start.junction},
        )
        if out is None:
            return None
        fits, disp = out
        opt.fits.update(fits)
        for n, d in disp.items():
            opt.disp[n] = d
        groups, off_line = slid  # split in the solve, the arcs extracted there
        opt.groups.update(groups)
        opt.off_line.update(off_line)
        if strays(opt, fits, opt.groups, saved[0]):
            return None
        opt.fits.update(fits)
        similarity = opt.similarity()
        # The joins made before touched in the state the try starts from (a try is kept only then).
        if similarity > bound or not _touching(opt, made, fits, disp):
            return None
        crossings = _redundant(opt, set(fits))
        made_gaps = gap_ends(opt)
    finally:
        opt.fits, opt.disp, opt.groups, opt.off_line = saved
    key = frozenset(fits)
    if key not in join.crossings:
        join.crossings[key] = _redundant(opt, set(fits))
    if crossings > join.crossings[key]:
        return None
    if not made_gaps <= join.gaps:
        return None
    return _Trial(similarity, fits, disp, groups, off_line)


@dataclass(frozen=True)
class _Start:
    """A tangent biarc to start a join's refit from (:func:`_biarc_starts`)."""

    seeds: dict[int, Seed]  # the two groups' circles, touching at ``junction``
    groups: dict[int, Group]  # the two groups, their pixels split at ``junction``
    junction: np.ndarray  # (2,) px, on the joined pixel chain


def _biarc_starts(opt: FitState, node: int, pair: tuple[int, int]) -> list[tuple[dict[int, int], _Start]]:
    """Tangent biarcs over a smooth join's two groups, as starts of its refit: (rung steps, start), best first.

    Two circles of fixed rungs touch at one point only, seldom where the
    over-segmentation put the node, and the refit from the current circles keeps
    the junction near the node (the module's docstring). So the two circles are
    fitted as one unit (:func:`~img2logo.fit.biarcs.closest_biarcs`) on the rungs
    of both and one rung up or down for each, and the ``BIARC_STARTS`` of smallest
    largest pixel distance are returned. None for a straight line (fixed) or a closed group.
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
        rungs[g] += [(s, *r) for s in (-1, 1) if (r := neighbour_rung(opt, g, s)) is not None]
    radii = tuple(r for g in pair for _, _, r in rungs[g])
    key = (ga.segments, gb.segments, node, len(chain), *chain[0], *chain[-1], *radii)
    cache = _BIARCS.setdefault(opt, {})
    if key not in cache:
        cache[key] = closest_biarcs(chain, [r for _, _, r in rungs[a]], [r for _, _, r in rungs[b]], BIARC_STARTS)
    found = cache[key]
    out = []
    for _, ia, ib, i, ca, cb in found:
        (sa, ka, ra), (sb, kb, rb) = rungs[a][ia], rungs[b][ib]
        head, tail = chain[: i + 1], chain[i:]
        groups = {
            a: replace(ga, points=head if ga.nodes[-1] == node else head[::-1]),
            b: replace(gb, points=tail if gb.nodes[0] == node else tail[::-1]),
        }
        seeds = {a: Seed(ca, ra, ka), b: Seed(cb, rb, kb)}
        out.append(({a: sa, b: sb}, _Start(seeds, groups, chain[i].copy())))
    return out


#: The biarcs of a run's smooth joins (:func:`~img2logo.fit.biarcs.closest_biarcs`), by the joined pixels and the radii:
#: the levels that :func:`~img2logo.fit.kinks.tangent_level` tries share most of their groups.
_BIARCS: WeakKeyDictionary[FitState, dict[tuple, list]] = WeakKeyDictionary()


def _slide(
    opt: FitState, made: dict[int, tuple[int, int]], moved: set[int], disp: Any = None, chains: dict | None = None
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
    d_k (default the state's), for a fit not applied yet. ``chains`` keeps the joined pixels of the two
    groups (the same objects) at a join for the next call.
    """
    disp = opt.disp.__getitem__ if disp is None else disp
    groups: dict[int, Group] = {}
    off: dict[int, float] = {}
    for n, (a, b) in made.items():
        if a not in moved and b not in moved:
            continue
        ga, gb = groups.get(a, opt.groups[a]), groups.get(b, opt.groups[b])
        hit = None if chains is None else chains.get((n, id(ga), id(gb)))
        if hit is not None and hit[0] is ga and hit[1] is gb:  # the groups are held there: ids not reused
            chain = hit[2]
        else:
            chain = merge_groups(ga, gb, n).points
            if chains is not None:
                chains[n, id(ga), id(gb)] = (ga, gb, chain)
        split = split_chain(chain, opt.graph.junctions[n] + disp(n))
        if split is None:
            return None, {}
        pa, pb, off[n] = split
        groups[a] = Group(ga.segments, ga.nodes, pa if ga.nodes[-1] == n else pa[::-1], ga.locked)
        groups[b] = Group(gb.segments, gb.nodes, pb if gb.nodes[0] == n else pb[::-1], gb.locked)
    return groups, off


def split_chain(chain: np.ndarray, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, float] | None:
    """Split a pixel chain (n, 2) px at the point nearest ``q``: (head, tail, distance of q from the chain, px).

    The nearest point of the polyline ends the head and starts the tail. None
    if either would keep fewer than ``SLIDE_MIN_PIXELS`` pixels.
    """
    from .._compiled import kernels  # loaded by the first fit already

    i, x, y, dist = kernels.nearest_on_chain_kernel(chain, float(q[0]), float(q[1]))
    if i + 2 <= SLIDE_MIN_PIXELS or len(chain) - i <= SLIDE_MIN_PIXELS:  # the pixels and the foot
        return None
    at = np.array([[x, y]])
    return np.concatenate((chain[: i + 1], at)), np.concatenate((at, chain[i + 1 :])), float(dist)


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


def _touching(opt: FitState, made: dict[int, tuple[int, int]], groups: Collection[int], nodes: Collection[int]) -> bool:
    """Whether the circles of every join in ``made`` touch at it, to ``CONSTRAINED_FIT_TOL`` px (see :func:`_apart`).

    Only the joins of a group of ``groups`` or at a node of ``nodes`` are measured: the state's other
    circles and junctions are those of a state where every join of ``made`` touched (the caller's).
    """
    fits = opt.fits
    return all(
        _apart(opt, fits, n, pair) * min(fits[pair[0]].radius, fits[pair[1]].radius) <= CONSTRAINED_FIT_TOL
        for n, pair in made.items()
        if pair[0] in groups or pair[1] in groups or n in nodes
    )


def _redundant(opt: FitState, of: set[int]) -> int:
    """Redundant intersections (Sec. 5.2, Fig. 12) of the state's arcs that involve the groups ``of``.

    :func:`~img2logo.fit.merge_checks.redundant_pairs`, counted.
    """
    return len(redundant_pairs(opt, of))


def _apart(opt: FitState, circles: Mapping[int, Any], node: int, pair: tuple[int, int]) -> float:
    """|sin| of the angle between two circles' radii to a junction: 0 where they touch there.

    ``circles``: group -> its :class:`~img2logo.fit.fit_values.Seed` or fit (anything with a ``center``).
    """
    p = opt.graph.junctions[node] + opt.disp[node]
    a, b = circles[pair[0]].center - p, circles[pair[1]].center - p
    return abs(float(a[0] * b[1] - a[1] * b[0])) / max(float(np.hypot(*a) * np.hypot(*b)), 1e-300)
