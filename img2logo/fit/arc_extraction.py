"""Arc extraction and arc-arc intersections (paper Sec. 5.2, 5.3, Fig. 6, 9, 12).

*Arc extraction* (Sec. 5.3): once a segment's golden circle is fitted, its arc
is the piece of the circle between two of the segment's junction points
p_k + d_k. Every pair of junctions gives two candidates (both ways round); those
that do not pass through all the junctions are dropped (the connectivity
constraint, Eqn. 4), and the one with the smallest discrete Fréchet distance
[EM94] to the segment's pixels wins. The sum-of-squares distance of the pixels
to the arc (the circle fitting error) is the paper's baseline (Fig. 9c): it
cannot penalize a redundant part of the arc.

*Redundant intersections* (Sec. 5.2, Fig. 6 red box, Fig. 12): two arcs that
cross at a point that is not a junction they both belong to.

Coordinates and angles follow :mod:`img2logo.geometry.primitives`: px, x right, y down;
angles in radians from +x towards +y; a point of an arc is
``(cx + r cos t, cy + r sin t)`` for t from ``theta0`` to ``theta0 + sweep``.

The discrete Fréchet distance is computed here, exactly, by the dynamic program
of Eiter and Mannila, compiled with numba.
``shapely.frechet_distance`` is not used: with GEOS 3.14 it is not the exact
discrete Fréchet distance (its diagonal-band heuristic overestimates it on
about 7 % of small random curve pairs, by up to 97 %), and it is very slow on
dissimilar curves (64 s for 575 against 1312 points, the "long way round"),
as measured with shapely 2.2.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

import numpy as np

from .._compat import unique
from .._validation import check_choice, check_points, check_positive, readonly
from ..constants import INTERSECTION_TOL, JUNCTION_TOLERANCE
from ..errors import FitError, InvalidParameterError
from ..geometry.primitives import TAU, Arc, Circle, polyline_length
from .constants import (
    ARC_CANDIDATE_LENGTH_RATIO,
    ARC_CANDIDATE_LENGTH_SLACK,
    FRECHET_SAMPLE_STEP,
    REDUNDANT_INTERSECTION_TOL,
)

__all__ = [
    "ArcFit",
    "RedundantIntersection",
    "admissible_arcs",
    "arc_intersections",
    "arc_pairs_near",
    "arc_params",
    "candidate_arcs",
    "discrete_frechet",
    "distances_to_arcs",
    "extract_arc",
    "frechet_distance",
    "nearest_on_arc",
    "redundant_intersections",
]


# --------------------------------------------------------------------------- Fréchet
def frechet_distance(p: np.ndarray, q: np.ndarray) -> float:
    """Discrete Fréchet distance between two polylines [EM94] (Eqn. 3), px.

    The smallest, over all couplings of the vertices of ``p`` and ``q`` that
    walk both from first to last without going back, of the largest distance
    between coupled vertices. Direction matters: ``p`` reversed is not ``p``.

    Parameters
    ----------
    p : array_like, shape (N, 2)
        First polyline, px, N >= 1.
    q : array_like, shape (M, 2)
        Second polyline, px, M >= 1.

    Returns
    -------
    float
        The distance, px. One point against a polyline is the largest distance
        from it to the polyline's vertices.

    Notes
    -----
    Exact, by the dynamic program of [EM94], compiled with numba: only the
    band of its table within a greedy coupling's distance is filled
    (:func:`img2logo._compiled.arcs.frechet`), a few cells a row where the
    curves run close together, O(N M) at worst.
    """
    p = check_points(p, "p")
    q = check_points(q, "q")
    return discrete_frechet(p, q)


def discrete_frechet(p: np.ndarray, q: np.ndarray, bound: float = math.inf) -> float:
    """Exact discrete Fréchet distance; ``inf`` as soon as it is known to be >= ``bound``."""
    kernel = _frechet_kernel()
    return float(kernel(np.ascontiguousarray(p, dtype=np.float64), np.ascontiguousarray(q, dtype=np.float64), bound))


def _frechet_kernel():
    """The compiled dynamic program of [EM94] (:func:`img2logo._compiled.arcs.frechet`).

    Loaded here, on first use, not at module import, so that the command line
    starts fast (:mod:`img2logo._compiled.kernels`: compiled once ahead of time, no numba
    at run time).
    """
    from .._compiled import kernels

    return kernels.frechet


# --------------------------------------------------------------------------- arc extraction
@dataclass(frozen=True)
class ArcFit:
    """An extracted arc and its similarity to the segment (Sec. 5.3).

    Attributes
    ----------
    arc : Arc
        The arc, in the orientation (of its two) with the smaller Fréchet
        distance to the pixel chain: normally it starts where the chain starts.
    frechet : float
        Discrete Fréchet distance between the segment's pixels and the arc
        sampled about ``FRECHET_SAMPLE_STEP`` px apart, px: E^f of Eqn. 3.
    """

    arc: Arc
    frechet: float


def extract_arc(
    circle: Circle,
    segment_points: np.ndarray,
    junction_points: np.ndarray,
    *,
    method: Literal["frechet", "sum_of_squares"] = "frechet",
) -> ArcFit:
    """Extract the arc of a segment from its fitted circle (Sec. 5.3, Fig. 9).

    Candidates are the arcs of ``circle`` between every pair of junction points,
    both ways round; only those passing through all the junction points are
    kept (the connectivity constraint, Eqn. 4). A candidate longer than
    ``ARC_CANDIDATE_LENGTH_RATIO`` times the segment's polyline length plus
    ``ARC_CANDIDATE_LENGTH_SLACK`` px is skipped (the "long way round" of a
    huge circle), unless every candidate is that long: then the shortest is
    kept, and its Fréchet distance is computed from no more samples than an
    admitted candidate would have. When the first and last junction points
    coincide (a closed loop) the candidate is the whole circle starting there.

    Only containment is checked, as in the paper: the order of the middle
    junctions along the arc is left to the Fréchet distance.

    Parameters
    ----------
    circle : Circle
        The segment's fitted (golden) circle.
    segment_points : array_like, shape (N, 2)
        Ordered pixel chain of the segment(s) the arc abstracts, px, N >= 2.
    junction_points : array_like, shape (m, 2)
        The displaced junctions p_k + d_k the arc must pass through, px, m >= 2,
        in order along the segment: first the start node, last the end node.
        Each must lie on ``circle`` within ``JUNCTION_TOLERANCE`` px.
    method : {"frechet", "sum_of_squares"}
        How the candidate is chosen: smallest discrete Fréchet distance to the
        pixels (the paper's choice, Fig. 9b), or smallest sum of squared
        distances from the pixels to the arc (the baseline, Fig. 9c).

    Returns
    -------
    ArcFit
        The chosen arc, oriented like the pixel chain (of its two orientations
        the one with the smaller Fréchet distance), and that Fréchet distance.

    Raises
    ------
    InvalidParameterError
        On inputs of the wrong type, shape or value.
    FitError
        If a junction point is off the circle.
    """
    if not isinstance(circle, Circle):
        raise InvalidParameterError(f"circle must be a Circle, got {type(circle).__name__}")
    seg = check_points(segment_points, "segment_points", min_count=2)
    junctions = check_points(junction_points, "junction_points", min_count=2)
    method = check_choice(method, "method", ("frechet", "sum_of_squares"))
    return _extract(circle, seg, junctions, method)


def _extract(circle: Circle, seg: np.ndarray, junctions: np.ndarray, method: str = "frechet") -> ArcFit:
    """:func:`extract_arc` on checked inputs: float64 arrays (N, 2) and (m, 2), N, m >= 2, a known ``method``.

    The progressive optimization extracts an arc for every circle of every
    candidate's window from arrays it made itself: the checks of the public
    boundary were a quarter of the extraction's time there.
    """
    if method == "sum_of_squares":
        _check_on_circle(circle, junctions)
        kept, cap = admissible_arcs(circle, seg, junctions)
        chosen = min(kept, key=lambda a: float(np.sum(nearest_on_arc(a, seg)[0] ** 2)))
        return _best_by_frechet([chosen], seg, cap)
    from .._compiled import kernels  # the compiled kernels load on the first extraction, not at import

    if not kernels.usable():
        _check_on_circle(circle, junctions)
        return _extract_reference(circle, seg, junctions)
    found, theta0, sweep, reverse, frechet, near_tol = kernels.extract_arc_kernel(
        circle.cx,
        circle.cy,
        circle.r,
        seg,
        junctions,
        circle.angle_of(junctions),
        JUNCTION_TOLERANCE,
        ARC_CANDIDATE_LENGTH_RATIO,
        ARC_CANDIDATE_LENGTH_SLACK,
        FRECHET_SAMPLE_STEP,
    )
    if near_tol:  # a junction at least half the tolerance off the circle: checked here, with numpy's rounding
        _check_on_circle(circle, junctions)
    if not found:  # cannot happen with two distinct points on the circle
        raise FitError("no candidate arc passes through all the junction points")
    arc = Arc(circle, float(theta0), float(sweep))
    return ArcFit(_reversed(arc) if reverse else arc, float(frechet))


def _check_on_circle(circle: Circle, junctions: np.ndarray) -> None:
    """Raise :class:`FitError` if a junction point is more than ``JUNCTION_TOLERANCE`` px off ``circle``.

    The compiled extraction measures the junctions itself and calls this only
    for those at least half the tolerance off (numpy's calls cost more than the
    extraction's arithmetic on the usual two or three junctions, all within a
    micrometre of their circle).
    """
    off = np.abs(circle.distance(junctions))
    if off.max() > JUNCTION_TOLERANCE:
        worst = int(np.argmax(off))
        raise FitError(
            f"junction point {worst} is {off[worst]:.3g} px off the circle (tolerance {JUNCTION_TOLERANCE} px)"
        )


def _extract_reference(circle: Circle, seg: np.ndarray, junctions: np.ndarray) -> ArcFit:
    """:func:`extract_arc` (method "frechet") in Python, the reference of its compiled kernel."""
    kept, cap = admissible_arcs(circle, seg, junctions)
    return _best_by_frechet(kept, seg, cap)


def _wrap(theta: float) -> float:
    """The same angle in [-pi, pi]."""
    return math.remainder(theta, TAU)


def _reversed(arc: Arc) -> Arc:
    """The same points walked the other way."""
    return Arc(arc.circle, _wrap(arc.theta0 + arc.sweep), -arc.sweep)


def candidate_arcs(circle: Circle, junctions: np.ndarray) -> list[Arc]:
    """The arcs of ``circle`` between two of the ``junctions`` (m, 2), both ways round, through all of them."""
    theta = circle.angle_of(junctions)
    tol = JUNCTION_TOLERANCE / circle.r  # radians
    if np.hypot(*(junctions[0] - junctions[-1])) <= JUNCTION_TOLERANCE:
        # A closed loop: the whole circle from the loop's node.
        return [Arc(circle, float(theta[0]), TAU)]
    out = []
    for a in range(len(theta)):
        for b in range(a + 1, len(theta)):
            sweep = float(np.mod(theta[b] - theta[a], TAU))
            if sweep <= tol or sweep >= TAU - tol:  # coincident junctions bound no arc
                continue
            for s in (sweep, sweep - TAU):
                arc = Arc(circle, float(theta[a]), s)
                if np.all(arc.contains_angle(theta, tol)):
                    out.append(arc)
    if not out:  # cannot happen with two distinct points on the circle
        raise FitError("no candidate arc passes through all the junction points")
    return out


def admissible_arcs(circle: Circle, segment_points: np.ndarray, junctions: np.ndarray) -> tuple[list[Arc], float]:
    """The candidate arcs :func:`extract_arc` chooses among, and the length cap it applied, px.

    The arcs of :func:`candidate_arcs` no longer than ``ARC_CANDIDATE_LENGTH_RATIO``
    times the length of the pixel chain ``segment_points`` (N, 2) plus
    ``ARC_CANDIDATE_LENGTH_SLACK`` px; the shortest candidate when every one is longer.
    """
    candidates = candidate_arcs(circle, junctions)
    seg_length = polyline_length(segment_points)
    cap = ARC_CANDIDATE_LENGTH_RATIO * seg_length + ARC_CANDIDATE_LENGTH_SLACK
    kept = [a for a in candidates if a.length <= cap]
    return (kept or [min(candidates, key=lambda a: a.length)]), cap


def _best_by_frechet(arcs: Sequence[Arc], seg: np.ndarray, cap: float) -> ArcFit:
    """Of ``arcs`` in both orientations, the one with the smallest Fréchet distance to ``seg``.

    Candidates are tried in increasing order of a lower bound (the distance
    between the coupled end points), and each computation stops as soon as it
    cannot beat the best so far. An arc longer than ``cap`` px (the fallback
    when every candidate is) gets no more samples than one of length ``cap``.
    """
    options = []
    for arc in arcs:
        samples = arc.sample(FRECHET_SAMPLE_STEP * max(1.0, arc.length / cap))
        for oriented, pts in ((arc, samples), (_reversed(arc), samples[::-1])):
            lower = max(math.dist(seg[0], pts[0]), math.dist(seg[-1], pts[-1]))
            options.append((lower, len(options), oriented, pts))
    options.sort(key=lambda o: (o[0], o[1]))
    best, best_arc = math.inf, options[0][2]
    for lower, _, oriented, pts in options:
        if lower >= best:
            break
        value = discrete_frechet(seg, pts, bound=best)
        if value < best:
            best, best_arc = value, oriented
    return ArcFit(best_arc, best)


def nearest_on_arc(arc: Arc, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The point of ``arc`` nearest to each of ``points`` and its distance, px.

    The radial projection when it falls on the arc, else the nearer end (also for
    the circle's centre itself).

    Parameters
    ----------
    arc : Arc
    points : array_like, shape (N, 2) or (2,)
        Points (x, y), px.

    Returns
    -------
    distances : ndarray, shape (N,)
    nearest : ndarray, shape (N, 2)
        For one point of shape (2,), shapes () and (2,).
    """
    p = np.asarray(points, dtype=np.float64)
    single = p.ndim == 1
    p = np.atleast_2d(p)
    c = arc.circle
    theta = c.angle_of(p)
    on = arc.contains_angle(theta) & (np.hypot(*(p - c.center).T) > 0)
    ends = np.array([arc.start, arc.end])
    to_ends = np.hypot(*(p[:, None, :] - ends[None, :, :]).transpose(2, 0, 1))
    q = np.where(on[:, None], c.point_at(theta), ends[np.argmin(to_ends, axis=1)])
    d = np.hypot(*(q - p).T)
    return (d[0], q[0]) if single else (d, q)


def distances_to_arcs(points: np.ndarray, params: np.ndarray, limit: float = math.inf) -> np.ndarray:
    """Distances from ``points`` (m, 2) to arcs given as rows (cx, cy, r, theta0, sweep) (n, 5): (m, n), px.

    :func:`nearest_on_arc`'s distances for every point and arc at once: the
    radial distance where the point's angle lies on the arc, else the distance
    to the nearer end (also for the centre itself). Where the point is farther
    than ``limit`` px from the arc's circle, the distance to the circle is
    given instead (a lower bound, also above ``limit``): the merge loop's
    near-miss test (:mod:`img2logo.fit.merging`), which reads every open end
    against every arc of a level, asks only which arcs come within a few px.
    """
    p = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    arcs = np.asarray(params, dtype=np.float64).reshape(-1, 5)
    dx = p[:, 0, None] - arcs[:, 0]
    dy = p[:, 1, None] - arcs[:, 1]
    rho = np.hypot(dx, dy)
    out = np.abs(rho - arcs[:, 2])
    i, j = np.nonzero(out <= limit) if limit < math.inf else np.indices(out.shape).reshape(2, -1)
    if not len(i):
        return out
    cx, cy, r, t0, sw = arcs[j].T
    offset = np.mod((np.arctan2(dy[i, j], dx[i, j]) - t0) * np.where(sw < 0, -1.0, 1.0), TAU)
    on = (np.abs(sw) >= TAU - 1e-9) | (offset <= np.abs(sw) + 1e-9) | (offset >= TAU - 1e-9)
    px, py = p[i, 0], p[i, 1]
    t1 = t0 + sw
    to_start = np.hypot(px - (cx + r * np.cos(t0)), py - (cy + r * np.sin(t0)))
    to_end = np.hypot(px - (cx + r * np.cos(t1)), py - (cy + r * np.sin(t1)))
    out[i, j] = np.where(on & (rho[i, j] > 0), out[i, j], np.minimum(to_start, to_end))
    return out


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
    Python reference ``_redundant_reference``).
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
    pairs, points = _redundant_arrays(arcs, junctions, ptr, flat.astype(np.int64), rows.astype(np.int64), tol)
    return [RedundantIntersection(i, j, readonly(p.copy())) for (i, j), p in zip(pairs.tolist(), points, strict=True)]


def _redundant_arrays(
    arcs: Sequence[Arc],
    junctions: np.ndarray,
    ptr: np.ndarray,
    flat: np.ndarray,
    rows: np.ndarray,
    tol: float,
    params: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`redundant_intersections` on checked arrays: (pairs (R, 2), points (R, 2)).

    Arc i's junctions are ``flat[ptr[i]:ptr[i + 1]]`` (int64, indices into
    ``junctions``); ``rows`` the sorted candidate arcs; ``params`` the arcs'
    rows of :func:`arc_params` when the caller has them. The merge loop calls
    it directly with arrays it builds (every candidate merge is checked).
    """
    if len(arcs) < 2 or len(rows) == 0:
        return np.zeros((0, 2), dtype=np.int64), np.zeros((0, 2))

    from .._compiled import kernels  # the compiled kernels load on the first check, not at import

    if not kernels.usable():
        owned = [flat[ptr[i] : ptr[i + 1]] for i in range(len(arcs))]
        found = _redundant_reference(arcs, junctions, owned, rows, tol)
        return (
            np.array([(r.arc_a, r.arc_b) for r in found], dtype=np.int64).reshape(-1, 2),
            np.array([r.point for r in found], dtype=np.float64).reshape(-1, 2),
        )
    if params is None:
        params = arc_params(arcs)
    return kernels.redundant_kernel(params, rows, junctions, ptr, flat, INTERSECTION_TOL, tol)


def _redundant_reference(
    arcs: Sequence[Arc], junctions: np.ndarray, owned: Sequence[np.ndarray], rows: np.ndarray, tol: float
) -> list[RedundantIntersection]:
    """The test of :func:`redundant_intersections` in Python (the reference of its compiled kernel)."""
    out = []
    for i, j in _arc_pairs_reference(arcs, rows, INTERSECTION_TOL):
        shared = junctions[np.intersect1d(owned[i], owned[j])]
        for p in _intersections(arcs[i], arcs[j], INTERSECTION_TOL):
            if len(shared) and np.min(np.hypot(*(shared - p).T)) <= tol:
                continue
            out.append(RedundantIntersection(int(i), int(j), readonly(p.copy())))
    return out


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
    if not kernels.usable():
        return _arc_pairs_reference(arcs, rows, tol)
    return [(i, j) for i, j in kernels.arc_pairs_kernel(arc_params(arcs), rows, float(tol)).tolist()]


def _arc_pairs_reference(arcs: Sequence[Arc], rows: np.ndarray, tol: float) -> list[tuple[int, int]]:
    """:func:`arc_pairs_near` in numpy (the reference of its compiled kernel)."""
    params = arc_params(arcs)
    centers, radii = params[:, :2], params[:, 2]
    boxes = _bounding_boxes(params)  # (n, 4): xmin, ymin, xmax, ymax
    n = len(arcs)
    d = np.hypot(*(centers[rows, None, :] - centers[None, :, :]).transpose(2, 0, 1))
    rr, rc = radii[rows, None], radii[None, :]
    meet = (d <= rr + rc + tol) & (d >= np.abs(rr - rc) - tol)
    br, bc = boxes[rows, None, :], boxes[None, :, :]
    overlap = (br[..., 0] <= bc[..., 2] + tol) & (bc[..., 0] <= br[..., 2] + tol)
    overlap &= (br[..., 1] <= bc[..., 3] + tol) & (bc[..., 1] <= br[..., 3] + tol)
    mask = meet & overlap
    mask[np.arange(len(rows)), rows] = False
    r_idx, c_idx = np.nonzero(mask)
    i, j = rows[r_idx], c_idx
    lo, hi = np.minimum(i, j), np.maximum(i, j)
    key = unique(lo * n + hi)  # a pair of two candidates appears twice
    return [(int(k // n), int(k % n)) for k in key]


def _bounding_boxes(params: np.ndarray) -> np.ndarray:
    """Axis-aligned bounding boxes of arcs given as rows (cx, cy, r, theta0, sweep): (n, 4).

    Columns xmin, ymin, xmax, ymax, px: the extremes of the end points and of the
    points at angles 0, pi/2, pi, 3 pi/2 that lie on the arc.
    """
    cx, cy, r, t0, sw = params.T
    ang = np.empty((len(params), 6))
    ang[:, 0], ang[:, 1], ang[:, 2:] = t0, t0 + sw, np.arange(4) * (math.pi / 2)
    offset = np.mod((ang - t0[:, None]) * np.sign(sw)[:, None], TAU)
    on = (offset <= np.abs(sw)[:, None]) | (np.abs(sw)[:, None] >= TAU - 1e-9)
    on[:, :2] = True
    x = cx[:, None] + r[:, None] * np.cos(ang)
    y = cy[:, None] + r[:, None] * np.sin(ang)
    inf = np.where(on, 0.0, np.inf)
    return np.stack([(x + inf).min(1), (y + inf).min(1), (x - inf).max(1), (y - inf).max(1)], axis=1)
