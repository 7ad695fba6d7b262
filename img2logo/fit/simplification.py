"""Segment groups and the line-segment simplification (Sec. 5.4).

A *group* is a run of segments of the graph merged into one arc: a path through
the graph. :func:`simplify` merges, before the progressive loop, neighbours at
split points that one arc fits within ``SIMPLIFICATION_ERROR``; the merges of
the loop (:mod:`img2logo.fit.merging`) join groups the same way
(:func:`merge_groups`). :func:`is_straight` and :func:`straight_line` tell a
straight stroke for the lines option.

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import heapq
from collections.abc import Callable, Container, Sequence
from dataclasses import dataclass

import numpy as np

from ..geometry.primitives import cumulative_length
from .constants import LINE_END_SKIP, LINE_TOLERANCE, SIMPLIFICATION_ERROR


@dataclass(frozen=True, eq=False)
class Group:
    """Segments of the graph merged into one arc: a path through the graph.

    ``nodes`` has one more entry than ``segments``; ``points`` is the ordered
    pixel chain, (n, 2) px. A closed group starts and ends at the same node.
    """

    segments: tuple[int, ...]
    nodes: tuple[int, ...]
    points: np.ndarray
    locked: bool

    @property
    def closed(self) -> bool:
        """Whether the path starts and ends at the same node (a loop)."""
        return self.nodes[0] == self.nodes[-1]

    @property
    def ends(self) -> tuple[int, int]:
        """The first and last node of the path."""
        return self.nodes[0], self.nodes[-1]

    def reversed(self) -> Group:
        """The same group traversed the other way."""
        return Group(self.segments[::-1], self.nodes[::-1], self.points[::-1], self.locked)


def merge_groups(a: Group, b: Group, node: int) -> Group:
    """Join ``a`` and ``b`` at their common end ``node``; ``a``'s far end starts the result."""
    # Each turned round in place of a reversed() Group: the same tuples and points, one object fewer.
    a_segments, a_nodes, a_points = (
        (a.segments, a.nodes, a.points) if a.nodes[-1] == node else (a.segments[::-1], a.nodes[::-1], a.points[::-1])
    )
    b_segments, b_nodes, b_points = (
        (b.segments, b.nodes, b.points) if b.nodes[0] == node else (b.segments[::-1], b.nodes[::-1], b.points[::-1])
    )
    return Group(
        a_segments + b_segments,
        a_nodes + b_nodes[1:],
        np.concatenate([a_points, b_points[1:]]),  # (n, 2) each: np.vstack's checks cost more than the copy
        a.locked or b.locked,
    )


#: The merges :func:`merge_candidate` scored, by the two groups' segments: (error, merged group).
_Scores = dict[tuple[tuple[int, ...], tuple[int, ...]], tuple[float, Group]]


def merge_candidate(
    ga: Group, gb: Group, node: int, error: Callable[[Group], float], scores: _Scores
) -> tuple[float, Group] | None:
    """The simplification's candidate of two groups that meet at a split ``node``: (error, merged group), or None.

    None where either group is locked (the lock mask) or they are one group (the
    two ends of a closed one). Scored once per pair of groups, kept in
    ``scores``: two groups that share both their ends (a loop of two) are one
    candidate, merged at the node where it was first scored.
    """
    if ga.locked or gb.locked or ga is gb:
        return None
    key = (ga.segments, gb.segments)
    if key not in scores:
        merged = merge_groups(ga, gb, node)
        scores[key] = (error(merged), merged)
    return scores[key]


def simplify(
    groups: list[Group],
    error: Callable[[Group], float],
    valence: np.ndarray,
    axis_nodes: Container[int] = frozenset(),
) -> list[Group]:
    """Line-segment simplification (Sec. 5.4): merge neighbours one arc fits within 1 px.

    Greedy, the lowest ``error`` (mean absolute distance of the pixels to the
    fitted circle, px) first, while it is below ``SIMPLIFICATION_ERROR``. Only
    at split points (nodes of valence 2 in the graph): a real junction is left
    to the progressive loop; nor at ``axis_nodes`` (the junctions on the
    mirror axis of a symmetric run). ``valence`` is the graph's node valence.
    Returns the simplified groups.
    """
    # Incremental: a merge changes the candidates only at the ends of the two groups
    # it joins, so those are re-scored and a heap gives the next best. The choice is
    # the one of a full scan over the nodes in order: the lowest error, the lowest
    # node on a tie; the groups keep their order (the merged one last), as does
    # each node's pair (the earlier group first), so every merged group is the same.
    current: dict[int, Group] = dict(enumerate(groups))  # insertion-ordered, like the list
    at: dict[int, list[int]] = {}  # node -> ids of the groups with an end there, in order
    for i, g in current.items():
        for n in set(g.ends):
            at.setdefault(n, []).append(i)
    pairs: dict[int, tuple[int, int, Group]] = {}  # node -> the pair whose merge there is a candidate, merged
    heap: list[tuple[float, int, int, int]] = []
    scores: _Scores = {}
    split = set(np.flatnonzero(np.asarray(valence) == 2).tolist())  # the split points: valence 2

    def score(node: int) -> None:
        pairs.pop(node, None)
        idx = at.get(node, [])
        if node not in split or len(idx) != 2 or node in axis_nodes:
            return
        scored = merge_candidate(current[idx[0]], current[idx[1]], node, error, scores)
        if scored is None:
            return
        err, merged = scored
        if err < SIMPLIFICATION_ERROR:  # (a NaN never is)
            pairs[node] = (idx[0], idx[1], merged)
            heapq.heappush(heap, (err, node, idx[0], idx[1]))  # (node, i, j) is never pushed twice

    for node in sorted(at):
        score(node)
    next_id = len(current)
    while heap:
        _, node, i, j = heapq.heappop(heap)
        if pairs.get(node, (None, None))[:2] != (i, j):
            continue  # a pair that an earlier merge broke
        merged = pairs.pop(node)[2]
        ga, gb = current.pop(i), current.pop(j)
        touched = set(ga.ends) | set(gb.ends)
        for g, gid in ((ga, i), (gb, j)):
            for n in set(g.ends):
                at[n].remove(gid)
        current[next_id] = merged
        for n in set(merged.ends):
            at[n].append(next_id)
        next_id += 1
        for n in sorted(touched):
            score(n)
    return list(current.values())


def straight_line(group: Group) -> tuple[np.ndarray, np.ndarray] | None:
    """The end points of a straight group's line, or None if it is not straight.

    The line is the pixels' total-least-squares line; its ends are the
    projections of the group's end points on it.
    """
    if not is_straight(group):
        return None
    pts = group.points
    mean = pts.mean(axis=0)
    direction = np.linalg.svd(pts - mean, full_matrices=False)[2][0]
    ends = mean + np.outer((pts[[0, -1]] - mean) @ direction, direction)
    return ends[0], ends[1]


def is_straight(group: Group) -> bool:
    """Whether an open group is a straight stroke (the lines option).

    Its pixels, but for ``LINE_END_SKIP`` px at each end (where thinning bevels
    a thick stroke's corners towards the junction), all lie within
    ``LINE_TOLERANCE`` of their total-least-squares line.
    """
    if group.closed:
        return False
    pts = group.points
    arc_len = cumulative_length(pts)
    inner = pts[(arc_len >= LINE_END_SKIP) & (arc_len <= arc_len[-1] - LINE_END_SKIP)]
    if len(inner) < 3:
        return False
    centred = inner - inner.mean(axis=0)
    normal = np.linalg.svd(centred, full_matrices=False)[2][1]  # the direction of least spread
    return float(np.max(np.abs(centred @ normal))) <= LINE_TOLERANCE


def hold_line(held: dict[int, list[np.ndarray]], group: Group, nodes: Sequence[int]) -> None:
    """Record a line group's direction at each of its junctions ``nodes`` in ``held`` (see ``FitState.golden``)."""
    d = group.points[-1] - group.points[0]
    u = d / max(float(np.hypot(*d)), 1e-12)
    for n in set(nodes):
        held.setdefault(n, []).append(u)
