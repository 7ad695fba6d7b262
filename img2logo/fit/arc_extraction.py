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

from .._validation import check_choice, check_points
from ..constants import JUNCTION_TOLERANCE
from ..errors import FitError, InvalidParameterError
from ..geometry.primitives import TAU, Arc, Circle, polyline_length
from .constants import (
    ARC_CANDIDATE_LENGTH_RATIO,
    ARC_CANDIDATE_LENGTH_SLACK,
    FRECHET_SAMPLE_STEP,
)

__all__ = [
    "ArcFit",
    "admissible_arcs",
    "best_by_frechet",
    "candidate_arcs",
    "discrete_frechet",
    "distances_to_arcs",
    "extract_arc",
    "frechet_distance",
    "nearest_on_arc",
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
        return best_by_frechet([chosen], seg, cap)
    from .._compiled import kernels  # the compiled kernels load on the first extraction, not at import

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


def best_by_frechet(arcs: Sequence[Arc], seg: np.ndarray, cap: float) -> ArcFit:
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
