"""Arc-arc intersections and the redundant ones (paper Sec. 5.2, Fig. 6, 12).

*Redundant intersections* (Sec. 5.2, Fig. 6 red box, Fig. 12): two arcs that
cross at a point that is not a junction they both belong to
(:func:`redundant_intersections`). :func:`arc_intersections` gives the points where two arcs
meet; :func:`arc_pairs_near` the pairs of arcs whose bounding boxes overlap, the only ones that
can meet.

Coordinates and angles follow :mod:`img2logo.geometry.primitives`: px, x right, y down;
angles in radians from +x towards +y; a point of an arc is
``(cx + r cos t, cy + r sin t)`` for t from ``theta0`` to ``theta0 + sweep``.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .._compat import unique
from .._validation import check_points, check_positive, readonly
from ..constants import INTERSECTION_TOL
from ..errors import InvalidParameterError
from ..geometry.primitives import Arc
from .constants import (
    REDUNDANT_INTERSECTION_TOL,
)

__all__ = ["RedundantIntersection", "arc_intersections", "arc_pairs_near", "arc_params", "redundant_intersections"]


# --------------------------------------------------------------------------- intersections
def arc_intersections(a: Arc, b: Arc, *, tol: float = INTERSECTION_TOL) -> np.ndarray:
    """Points where two arcs meet, exactly (circle-circle intersection, then angle ranges).

    Parameters
    ----------
    a, b : Arc
        The arcs.
    tol : float
        Geometric tolerance, px (default ``INTERSECTION_TOL``): circles that
        overlap or miss each other by at most ``tol`` touch once (tangency);
        circles whose centres and radii agree within ``tol`` are the same
        circle; a point within ``tol`` of an arc's angle range is on it.

    Returns
    -------
    ndarray, shape (K, 2)
        The points, px; K is 0, 1 or 2 for arcs on different circles. For arcs
        on the same circle: the end points of their overlap (each arc's end
        points that lie on the other, without repeats), so arcs that touch end
        to end meet once and overlapping arcs at least twice; two whole circles
        have no end points and give their common start point, so that they are
        still seen to meet.
    """
    for name, arc in (("a", a), ("b", b)):
        if not isinstance(arc, Arc):
            raise InvalidParameterError(f"{name} must be an Arc, got {type(arc).__name__}")
    tol = check_positive(tol, "tol", allow_zero=True)
    return _intersections(a, b, tol)


def _intersections(a: Arc, b: Arc, tol: float) -> np.ndarray:
    ca, cb = a.circle, b.circle
    r1, r2 = ca.r, cb.r
    dx, dy = cb.cx - ca.cx, cb.cy - ca.cy
    d = math.hypot(dx, dy)
    if d <= tol:
        return _same_circle_overlap(a, b, tol) if abs(r1 - r2) <= tol else np.empty((0, 2))
    outside, inside = d - (r1 + r2), abs(r1 - r2) - d  # > 0: apart, one inside the other
    if outside > tol or inside > tol:
        return np.empty((0, 2))
    x = (d * d + r1 * r1 - r2 * r2) / (2.0 * d)  # along the centre line, from a's centre
    ux, uy = dx / d, dy / d
    base = np.array([ca.cx + x * ux, ca.cy + x * uy])
    if abs(outside) <= tol or abs(inside) <= tol:  # tangent
        pts = base[None, :]
    else:
        # Half the chord, by a product of differences of the inputs (no cancellation).
        h2 = -outside * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2) / (4.0 * d * d)
        h = math.sqrt(max(h2, 0.0))
        pts = np.array([base + h * np.array([-uy, ux]), base - h * np.array([-uy, ux])])
    keep = a.contains_angle(ca.angle_of(pts), tol / ca.r) & b.contains_angle(cb.angle_of(pts), tol / cb.r)
    return pts[keep]


def _same_circle_overlap(a: Arc, b: Arc, tol: float) -> np.ndarray:
    """End points of the overlap of two arcs of one circle."""
    if a.is_full_circle and b.is_full_circle:
        return a.start[None, :]
    pts = []
    for arc, other in ((a, b), (b, a)):
        if arc.is_full_circle:
            continue
        for p in (arc.start, arc.end):
            if other.contains_angle(other.circle.angle_of(p), tol / other.circle.r):
                pts.append(p)
    out: list[np.ndarray] = []
    for p in pts:
        if all(math.dist(p, q) > tol for q in out):
            out.append(p)
    return np.array(out).reshape(-1, 2)


@dataclass(frozen=True, eq=False)
class RedundantIntersection:
    """Two arcs meeting at a point that is not a junction of both (Sec. 5.2, Fig. 6, 12).

    Attributes
    ----------
    arc_a, arc_b : int
        Indices of the arcs, ``arc_a < arc_b``.
    point : ndarray, shape (2,)
        Where they meet, px (read-only).
    """

    arc_a: int
    arc_b: int
    point: np.ndarray


def redundant_intersections(
    arcs: Sequence[Arc],
    junction_points: np.ndarray,
    arc_junctions: Sequence[Sequence[int]],
    *,
    candidates: Sequence[int] | None = None,
    tol: float = REDUNDANT_INTERSECTION_TOL,
) -> list[RedundantIntersection]:
    """Redundant intersections of an arc set (Sec. 5.2, 6.2; Fig. 6c red box, Fig. 12).

    Two arcs meeting at a point farther than ``tol`` from every junction that
    both of them belong to form a redundant intersection: the input line
    segments have no such crossing. Arcs that share a junction and cross or
    touch (tangentially) there are fine.

    Parameters
    ----------
    arcs : sequence of Arc
        The arc set A.
    junction_points : array_like, shape (J, 2)
        The displaced junctions p_k + d_k, px.
    arc_junctions : sequence of sequence of int
        For each arc, the indices of the junctions it ends at or passes through.
    candidates : sequence of int, optional
        Check only the pairs that involve at least one of these arc indices
        (the progressive optimizer checks only the arcs a merge changed). Default:
        all pairs.
    tol : float
        Distance from a shared junction within which a meeting point is that
        junction, px (default ``REDUNDANT_INTERSECTION_TOL``).

    Returns
    -------
    list of RedundantIntersection
        Sorted by (arc_a, arc_b); a pair that meets at several redundant points
        appears once per point.

    Notes
    -----
    Pairs whose circles cannot meet or whose bounding boxes are disjoint are
    discarded by a prefilter (:func:`arc_pairs_near`); only the rest get the
    exact test of :func:`arc_intersections`. Both run compiled
    (:func:`img2logo._compiled.arcs.redundant_kernel`, the same arithmetic as the
    Python reference in the tests, ``redundant_reference``).
    """
    arcs = list(arcs)
    for i, arc in enumerate(arcs):
        if not isinstance(arc, Arc):
            raise InvalidParameterError(f"arcs[{i}] must be an Arc, got {type(arc).__name__}")
    n = len(arcs)
    junctions = check_points(junction_points, "junction_points", min_count=0)
    if len(arc_junctions) != n:
        raise InvalidParameterError(f"arc_junctions must have one entry per arc ({n}), got {len(arc_junctions)}")
    owned = [np.asarray(ks, dtype=np.int64).ravel() for ks in arc_junctions]
    sizes = np.array([len(ks) for ks in owned])
    flat = np.concatenate(owned) if owned else np.empty(0, np.int64)
    bad = (flat < 0) | (flat >= len(junctions))
    if bad.any():
        i = int(np.searchsorted(np.cumsum(sizes), np.argmax(bad), side="right"))
        raise InvalidParameterError(f"arc_junctions[{i}] must index junction_points 0..{len(junctions) - 1}")
    tol = check_positive(tol, "tol", allow_zero=True)
    if candidates is None:
        rows = np.arange(n)
    else:
        rows = unique(np.asarray(list(candidates), dtype=np.int64))
        if len(rows) and (rows[0] < 0 or rows[-1] >= n):
            raise InvalidParameterError(f"candidates must index arcs 0..{n - 1}")
    ptr = np.concatenate([[0], np.cumsum(sizes)]).astype(np.int64)
    pairs, points = redundant_arrays(
        arc_params(arcs), junctions, ptr, flat.astype(np.int64), rows.astype(np.int64), tol
    )
    return [RedundantIntersection(i, j, readonly(p.copy())) for (i, j), p in zip(pairs.tolist(), points, strict=True)]


def redundant_arrays(
    params: np.ndarray,
    junctions: np.ndarray,
    ptr: np.ndarray,
    flat: np.ndarray,
    rows: np.ndarray,
    tol: float,
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`redundant_intersections` on checked arrays: (pairs (R, 2), points (R, 2)).

    The arcs are the rows (n, 5) of :func:`arc_params` ``params``; arc i's
    junctions are ``flat[ptr[i]:ptr[i + 1]]`` (int64, indices into
    ``junctions``); ``rows`` the sorted candidate arcs. The merge loop calls
    it directly with arrays it builds (every candidate merge is checked).
    """
    if len(params) < 2 or len(rows) == 0:
        return np.zeros((0, 2), dtype=np.int64), np.zeros((0, 2))

    from .._compiled import kernels  # the compiled kernels load on the first check, not at import

    return kernels.redundant_kernel(params, rows, junctions, ptr, flat, INTERSECTION_TOL, tol)


def arc_params(arcs: Sequence[Arc]) -> np.ndarray:
    """Arcs as rows (cx, cy, r, theta0, sweep), shape (n, 5)."""
    return np.array(
        [(a.circle.cx, a.circle.cy, a.circle.r, a.theta0, a.sweep) for a in arcs], dtype=np.float64
    ).reshape(-1, 5)


def arc_pairs_near(arcs: Sequence[Arc], rows: np.ndarray, tol: float) -> list[tuple[int, int]]:
    """Pairs (i, j), i < j, i or j in ``rows``, whose circles meet and bounding boxes overlap (within ``tol`` px).

    A cheap filter before :func:`arc_intersections`: only these pairs can meet.
    Sorted by (i, j).
    """
    from .._compiled import kernels

    rows = unique(np.asarray(rows, dtype=np.int64))
    return [(i, j) for i, j in kernels.arc_pairs_kernel(arc_params(arcs), rows, float(tol)).tolist()]
