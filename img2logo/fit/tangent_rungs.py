"""The rungs of two circles made tangent at a join (beyond the paper): chosen jointly.

When the rungs the paper chose (Eqn. 12) cannot touch within the tolerance, each circle of a smooth
join may go one rung up or down on the golden ladder (:func:`rung_choices`), which turns its tangent at
the join by as much as the kink; the tangent pass (:mod:`img2logo.fit.tangency`) keeps the choice of
lowest E^s. The rungs offered are the neighbours of the current one (:func:`neighbour_rung`,
:func:`offered_rung`), ordered by how far apart the two circles are predicted to be.

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from ..geometry.golden_ladder import FibonacciLadder
from .constants import (
    RUNG_CHOICES,
)

if TYPE_CHECKING:
    from .fit_state import FitState


def rung_choices(opt: FitState, node: int, pair: tuple[int, int]) -> list[dict[int, int]]:
    """Rung changes to try for a join's two circles, group -> step on the ladder: no change first.

    With the radii on the ladder, two circles of given rungs through given
    junctions touch only where the junctions happen to allow it; a circle one
    rung up or down (a factor phi) turns its tangent at the join and may let
    the two touch with a small move. Only circles (not lines), only allowed
    rungs (:func:`neighbour_rung`), each step at most one rung; and only the
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
            rung = neighbour_rung(opt, g, s)
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
    call on the same join (:func:`rung_choices` scores up to 9 choices of 6 circles).
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
        r = f.radius if not step else (rungs[g, step] if rungs else offered_rung(opt, g, step))[1]
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


def offered_rung(opt: FitState, gid: int, step: int) -> tuple[int, float]:
    """:func:`neighbour_rung` for a step :func:`rung_choices` offered (so it exists)."""
    rung = neighbour_rung(opt, gid, step)
    if rung is None:
        raise RuntimeError(f"group {gid} has no rung {step:+d} from its own; it was not offered")
    return rung


def neighbour_rung(opt: FitState, gid: int, step: int) -> tuple[int, float] | None:
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
