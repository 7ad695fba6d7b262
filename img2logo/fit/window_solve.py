"""The connectivity-constrained fit of the optimizer's state over a window of groups (Sec. 5.3, 5.4).

:func:`solve` fits Eqn. 13 over a local window of groups of a :class:`~img2logo.fit.fit_state.FitState`
(:func:`~img2logo.fit.local_window.fit_window`: the changed groups and those through the freed
junctions, grown ring by ring), then extracts the arcs of the groups it refitted; :func:`solve_whole`
is the global solve over all of them. With a bound on E^s (Eqn. 3) the arcs are extracted only while
E^s can still stay within it. The merge loop, the recovery and the tangent pass call them; the state
is read, not changed: the caller applies the new fits and displacements it accepts.

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Hashable, Mapping, Sequence
from dataclasses import replace
from typing import Any, cast
from weakref import WeakKeyDictionary

import numpy as np

from .constants import CUT_MARGIN
from .fit_state import FitState
from .fit_values import GroupFit, Regroup, Seed, Solution
from .local_window import WindowFit, fit_window
from .simplification import Group


class _Lazy(dict):
    """A mapping whose values are computed on first access (only the window's are needed)."""

    __slots__ = ("_value",)

    def __init__(self, value: Callable[[Any], Any]) -> None:  # empty as made: dict's own __init__ adds nothing
        self._value = value

    def __missing__(self, key: Any) -> Any:
        value = self[key] = self._value(key)
        return value


def _touching(
    state: FitState, groups: Mapping[int, Group], seeds: Mapping[int, Seed], tangent: bool | Collection[int]
) -> dict[int, tuple[int, int]]:
    """:meth:`~img2logo.fit.fit_state.FitState.tangencies` of ``groups``.

    Only those at the nodes ``tangent`` when it is a collection; ``tangent`` itself when it is a
    mapping (node -> the two groups: the caller found them, :func:`img2logo.fit.merging.held_joins`).
    """
    if isinstance(tangent, Mapping):
        return dict(tangent)
    joins = state.tangencies(groups, seeds)
    if tangent is True:
        return joins
    return {n: pair for n, pair in joins.items() if n in cast(Collection[int], tangent)}


def solve(
    state: FitState,
    groups: Mapping[int, Group],
    seeds: Mapping[int, Seed],
    node_groups: Mapping[int, Sequence[int]],
    *,
    changed: Sequence[int],
    free_nodes: Sequence[int],
    fixed: set[int],
    n_groups_total: int | None = None,
    n_junctions_total: int | None = None,
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
    rest: Mapping[int, np.ndarray] | None = None,
) -> Solution | None:
    """Eqn. 13 over a window of ``groups`` (:func:`~img2logo.fit.local_window.fit_window`), then their arcs.

    The window is the ``changed`` groups and those through ``free_nodes``,
    grown by up to ``rings`` rings (solved from ring ``first_ring`` on); the ``fixed`` groups keep their circles,
    and so do straight lines (a huge free circle is nearly singular along
    its chord: their junctions slide onto them). With ``tangent``, the
    circles of :meth:`~img2logo.fit.fit_state.FitState.tangencies` touch at their junctions too (those
    at its nodes when it is a collection; its joins when it is a mapping, :func:`_touching`). With ``cap``
    (px), a merged group (id -1) whose arc strays farther than that is the
    only fit returned (see :func:`_fits`). ``lines``: the groups whose seeds
    are straight lines (k None), when the caller knows them (a merge candidate's
    from its level's); default found in ``seeds``. With ``bound`` (px), None
    as soon as E^s (Eqn. 3) of the state with the new fits and displacements
    must exceed it, and ``regroup`` may split groups anew before their arcs
    are extracted (:func:`_fits`; a tangent join's slide). None if it fails.
    ``tried``, when given, receives the groups of the last (widest) window solved, whether it solved or not.
    ``n_groups_total``, ``n_junctions_total``: C and J of the weights (``n_circles`` and ``n_junctions`` of
    :func:`~img2logo.fit.local_window.fit_window`), default the counts of ``groups`` and ``node_groups``.
    ``stop_when_stuck``: that of :func:`~img2logo.fit.local_window.fit_window`. ``rest``: junction ->
    its rest point p_k for the fit instead of the graph's, px (2,) (a tangent biarc's junction: its d_k
    starts at zero there); the displacements returned, and those the arcs are extracted with, are from
    the graph's own points again.
    """
    fixed = set(fixed)
    junctions, disp0 = state.graph.junctions, state.disp
    if rest:
        junctions, disp0 = junctions.copy(), disp0.copy()
        for n, p in rest.items():
            junctions[n] = p
            disp0[n] = 0.0
    fixed.update({g for g in groups if seeds[g].k is None} if lines is None else lines)
    window = fit_window(
        _Lazy(lambda g: groups[g].points),
        _Lazy(lambda g: seeds[g].radius),
        _Lazy(lambda g: seeds[g].center),
        _Lazy(lambda g: tuple(set(state.constrained_nodes(groups[g])))),
        cast(Mapping[Hashable, Sequence[Hashable]], node_groups),
        junctions,
        changed=changed,
        free_junctions=free_nodes,
        fixed=fixed,
        rings=rings,
        first_ring=first_ring,
        order=cast(Callable[[Hashable], Any] | None, order),
        displacements0=disp0,
        n_circles=len(groups) if n_groups_total is None else n_groups_total,
        n_junctions=len(node_groups) if n_junctions_total is None else n_junctions_total,
        connectivity=state.options.connectivity,
        constraints=lambda circles, nodes: state.axis_constraints(
            cast(Sequence[int], circles), groups, cast(Sequence[int], nodes)
        ),
        tangencies=cast(Mapping[Hashable, tuple[Hashable, Hashable]], _touching(state, groups, seeds, tangent))
        if tangent
        else None,
        stop_when_stuck=stop_when_stuck,
    )
    if tried is not None:
        tried.update(cast(Collection[int], window.circles))
    if not window.ok:
        return None
    disp = _window_displacements(state, window)
    for n, p in (rest or {}).items():
        disp[n] = disp.get(n, 0.0) + p - state.graph.junctions[n]
    return _fits(state, window, disp, groups, seeds, fixed, node_groups, cap=cap, bound=bound, regroup=regroup)


def solve_whole(
    state: FitState,
    groups: Mapping[int, Group],
    seeds: Mapping[int, Seed],
    node_groups: Mapping[int, Sequence[int]],
    *,
    n_groups_total: int | None = None,
    n_junctions_total: int | None = None,
    order: Callable[[int], Any] | None = None,
    tangent: bool | Collection[int] = False,
    cap: float | None = None,
    bound: float | None = None,
) -> Solution | None:
    """:func:`solve` over all of ``groups`` at once, every junction free (a global solve, counted).

    The initial fit of A^0, a connected part in :func:`~img2logo.fit.recovery.recover`, a merge
    whose local windows failed, the tangent refit: none of them holds a circle fixed. ``bound``:
    that of :func:`solve` (None once E^s must exceed it, its arcs extracted only until then).
    """
    state.stats.global_solves += 1
    return solve(
        state,
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
        bound=bound,
    )


def _window_displacements(state: FitState, window: WindowFit) -> dict[int, np.ndarray]:
    """The window's d_k by node (px, (2,) each): zero for every junction without connectivity."""
    if not state.options.connectivity:
        return {cast(int, n): np.zeros(2) for n in window.junctions}
    return cast(dict[int, np.ndarray], window.displacements())


def _refitted(
    state: FitState, window: WindowFit, groups: Mapping[int, Group], seeds: Mapping[int, Seed], fixed: set[int]
) -> list[int]:
    """The window's groups whose arcs are extracted anew, in its order.

    Its free groups, and the straight lines (fixed) whose junctions moved.
    """
    moved = window.free_junctions
    return [
        gid
        for gid in cast(Sequence[int], window.circles)
        if gid not in fixed or (seeds[gid].k is None and bool(moved & set(state.constrained_nodes(groups[gid]))))
    ]


def _fits(
    state: FitState,
    window: WindowFit,
    disp: dict[int, np.ndarray],
    groups: Mapping[int, Group],
    seeds: Mapping[int, Seed],
    fixed: set[int],
    node_groups: Mapping[int, Sequence[int]],
    *,
    cap: float | None = None,
    bound: float | None = None,
    regroup: Regroup | None = None,
) -> Solution | None:
    """The new fits (the window's free groups, and lines whose junctions moved) and displacements.

    ``disp``: the window's d_k by node (:func:`_window_displacements`). With ``cap``, the merged
    group's (id -1) arc is extracted first, and when it is farther than ``cap`` px from its pixels
    only it is returned: the merge loop rejects that merge (``max_arc_distance``) and reads no other arc.

    With ``bound``, None once E^s (Eqn. 3) of the state with the fits must exceed ``bound`` px.
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
    arc). Before any arc is extracted, the same bound with every arc's
    Fréchet distance replaced by its :func:`arc_floor` (its pixels' largest
    distance from its circle) decides most of those: on the polar bear 259
    of the 299 calls that return None, with 659 of the 801 arcs they
    extracted. Otherwise the fits are those without ``bound`` and then a re-extraction
    of the regrouped groups' arcs would give, the same numbers.
    """
    todo = _refitted(state, window, groups, seeds, fixed)
    now = state.disp

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

    memo = None if bound is None else _ARCS.setdefault(state, {})
    centers: dict[int, np.ndarray] = {}

    def center(gid: int) -> np.ndarray:
        if gid not in centers:
            centers[gid] = window.center(gid)
        return centers[gid]

    def fit(gid: int) -> GroupFit:
        group = new_groups.get(gid, groups[gid])
        if gid in fitted:
            _, r, k = seeds[gid]
            # Memoized for the state's own groups only: a group split anew has new pixels every time.
            keep = memo if group is state.groups.get(gid) else None
            return GroupFit(center(gid), r, k, state.arc_for(group, center(gid), r, k, at, keep))
        f = state.fits[gid]  # split anew at a join of a fitted group: its circle stays
        return replace(f, arc=state.arc_for(group, f.center, f.radius, f.k, at))

    first = None
    if cap is not None and -1 in fitted:
        first = fit(-1)
        if first.arc.frechet > cap:
            return {-1: first}, disp  # the merge is rejected: the window's other arcs are not needed
    if bound is None:
        return {gid: first if gid == -1 and first is not None else fit(gid) for gid in todo}, disp
    n_fits = len(state.fits.keys() | set(todo))
    skip = set(todo)
    running = sum(f.arc.frechet for g, f in state.fits.items() if g not in skip)
    off_line = {**state.off_line, **off}
    # |d_k| of every node at once (np.hypot's loop: the numbers of its call on each vector), summed in order.
    nodes = np.fromiter(node_groups, dtype=np.intp, count=len(node_groups))
    moved = np.array([n in disp for n in node_groups], dtype=bool)
    d_all = now[nodes]
    if moved.any():
        d_all[moved] = [disp[n] for n in node_groups if n in disp]
    lengths = np.hypot(d_all[:, 0], d_all[:, 1]).tolist()
    d = sum(off_line[n] if n in off_line else h for n, h in zip(node_groups, lengths, strict=True))
    shift = d / len(node_groups) if node_groups else 0.0
    limit = bound + CUT_MARGIN * max(1.0, abs(bound))
    # Each arc's Fréchet distance is at least its pixels' largest distance from its circle (arc_floor):
    # once those alone take E^s past the bound, so would the arcs, and none is extracted.
    floor = running
    for gid in todo:
        if gid == -1 and first is not None:
            floor += first.arc.frechet
            continue
        circle = (center(gid), seeds[gid][1]) if gid in fitted else (state.fits[gid].center, state.fits[gid].radius)
        floor += arc_floor(new_groups.get(gid, groups[gid]).points, *circle)
        if floor / max(n_fits, 1) + shift > limit + CUT_MARGIN * max(1.0, abs(limit)):
            return None
    fits = {}
    for gid in todo:
        if running / max(n_fits, 1) + shift > limit:
            return None
        fits[gid] = f = first if gid == -1 and first is not None else fit(gid)
        running += f.arc.frechet
    if running / max(n_fits, 1) + shift > limit:
        return None
    return fits, disp


def arc_floor(points: np.ndarray, center: np.ndarray, radius: float) -> float:
    """A lower bound (px) of the discrete Fréchet distance of ``points`` (N, 2) from any arc of the circle.

    The coupling pairs every pixel with a point of the arc, on the circle: at least the pixel's distance from
    the circle away. Less the rounding of the arc's sampled points (1e-9 of the circle's coordinates).
    """
    from .._compiled import kernels  # loaded by the window's solve already

    cx, cy, r = float(center[0]), float(center[1]), float(radius)
    return max(0.0, kernels.largest_gap_kernel(points, cx, cy, r) - 1e-9 * (r + abs(cx) + abs(cy) + 1.0))


#: The arcs extracted by :func:`_fits` with a bound in a run (:meth:`~img2logo.fit.fit_state.FitState.arc_for`'s
#: ``memo``): the tangent passes solve some windows again to the same circles (the passes that
#: :func:`~img2logo.fit.kinks.split_kinks` runs after each split it tries share their groups and weights).
_ARCS: WeakKeyDictionary[FitState, dict] = WeakKeyDictionary()


def forget_arcs(state: FitState) -> None:
    """Drop the arcs :func:`_fits` kept for ``state`` (its tangent passes are over: no window is solved again)."""
    _ARCS.pop(state, None)
