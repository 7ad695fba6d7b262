"""A mirror axis, and what a symmetric result records of it.

The value :class:`Axis` and the helpers that read a symmetric level (its circles
paired with their mirror images, the document's ``extra.symmetry``, the check that
a level is symmetric, the part of the axis inside the image). They need only the
result values (:mod:`img2logo.geometry.primitives`), so the result-file contract and the
writers read a symmetric logo without loading the axis search or the optimizer
(:mod:`img2logo.fit.symmetry`).

Coordinates: input-image pixels, x right, y down, pixel (row i, column j)
centred at (j + 0.5, i + 0.5). Angles: from +x towards +y; an axis at 90 degrees
is vertical (upright).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validation import readonly
from ..constants import SYMMETRY_PAIR_TOLERANCE
from .abstraction import Abstraction
from .primitives import Circle

__all__ = ["Axis", "axis_segment", "circle_pairs", "is_symmetric", "symmetry_extra"]


@dataclass(frozen=True, eq=False)
class Axis:
    """A mirror axis in image pixels.

    Attributes
    ----------
    point : ndarray, shape (2,)
        A point of the axis, px (the foot of the perpendicular from the line
        pixels' centroid).
    direction : ndarray, shape (2,)
        Unit vector along the axis, pointing down the image (dy > 0, or dx > 0
        for a horizontal axis).
    score : float
        In [0, 1]: the fraction of the feature-line pixels whose mirror image lies
        within ``SYMMETRY_MATCH_DISTANCE`` px of a feature line.
    """

    point: np.ndarray
    direction: np.ndarray
    score: float

    def __post_init__(self) -> None:
        d = np.asarray(self.direction, dtype=np.float64).reshape(2)
        d = d / float(np.hypot(*d))
        d[np.abs(d) < 1e-12] = 0.0  # cos(pi / 2): an upright or level axis is exactly so
        d = d / float(np.hypot(*d))
        if d[1] < 0 or (d[1] == 0 and d[0] < 0):
            d = -d
        d = d + 0.0  # no negative zero
        object.__setattr__(self, "direction", readonly(d))
        object.__setattr__(self, "point", readonly(np.asarray(self.point, dtype=np.float64).reshape(2).copy()))

    @property
    def angle(self) -> float:
        """Direction of the axis, degrees in [0, 180) from +x towards +y (90: upright)."""
        return math.degrees(math.atan2(self.direction[1], self.direction[0])) % 180.0

    def reflect(self, points: np.ndarray) -> np.ndarray:
        """Mirror images of ``points`` (..., 2) about the axis, px."""
        p = np.asarray(points, dtype=np.float64)
        n = np.array([-self.direction[1], self.direction[0]])
        return p - 2.0 * ((p - self.point) @ n)[..., None] * n

    def describe(self) -> str:
        """One line: the angle, a point and the score."""
        x, y = self.point
        return f"mirror axis at {self.angle:.1f} deg through ({x:.1f}, {y:.1f}), score {self.score:.2f}"


def circle_pairs(
    circles: Sequence[Circle], point: object, direction: object
) -> tuple[list[list[int]], list[int], list[int]]:
    """Pair circles with their mirror images about an axis.

    Parameters
    ----------
    circles : sequence of Circle
    point, direction : array_like, shape (2,)
        The axis, px (``direction`` need not be a unit vector).

    Returns
    -------
    (pairs, on_axis, alone)
        ``pairs``: [i, j] with i < j, circle j the mirror image of circle i (centres
        within ``SYMMETRY_PAIR_TOLERANCE`` px, equal k and r); ``on_axis``: circles
        centred on the axis; ``alone``: the others.
    """
    axis = Axis(np.asarray(point, dtype=np.float64), np.asarray(direction, dtype=np.float64), 0.0)
    centres = np.array([[c.cx, c.cy] for c in circles]).reshape(-1, 2)
    mirrored = axis.reflect(centres)
    pairs, on_axis, alone, used = [], [], [], set()
    for i, c in enumerate(circles):
        if i in used:
            continue
        if np.hypot(*(mirrored[i] - centres[i])) <= 2 * SYMMETRY_PAIR_TOLERANCE:
            on_axis.append(i)
            continue
        match = [
            j
            for j in range(i + 1, len(circles))
            if j not in used
            and circles[j].k == c.k
            and abs(circles[j].r - c.r) <= SYMMETRY_PAIR_TOLERANCE
            and np.hypot(*(mirrored[i] - centres[j])) <= SYMMETRY_PAIR_TOLERANCE
        ]
        if match:
            pairs.append([i, match[0]])
            used.add(match[0])
        else:
            alone.append(i)
    return pairs, on_axis, alone


def symmetry_extra(circles: Sequence[Circle], params: Mapping[str, Any]) -> dict[str, Any] | None:
    """The result document's ``extra.symmetry`` for a symmetric level, or None.

    ``{"point": [x, y], "direction": [dx, dy], "circle_pairs": [[i, j], ...],
    "on_axis": [i, ...]}``: pixel coordinates, the direction along the axis, and
    the indices of the document's circles.
    """
    record = params.get("symmetry")
    if not isinstance(record, Mapping) or "point" not in record:
        return None
    pairs, on_axis, _ = circle_pairs(circles, record["point"], record["direction"])
    return {
        "point": [float(v) for v in record["point"]],
        "direction": [float(v) for v in record["direction"]],
        "circle_pairs": pairs,
        "on_axis": on_axis,
    }


def is_symmetric(level: Abstraction, point: object, direction: object, tol: float = SYMMETRY_PAIR_TOLERANCE) -> bool:
    """Whether every circle of ``level`` is on the axis or paired with its mirror image (to ``tol`` px).

    Also every arc: its mirror image is an arc of the level, or it is its own.
    """
    alone = circle_pairs(level.circles, point, direction)[2]
    if alone:
        return False
    axis = Axis(np.asarray(point, dtype=np.float64), np.asarray(direction, dtype=np.float64), 0.0)
    ends = [np.array([a.start, a.end, a.circle.point_at(a.theta0 + a.sweep / 2)]) for a in level.arcs]
    for e in ends:
        m = axis.reflect(e)
        # The mirror image runs the other way: its start is this arc's end.
        if not any(
            np.allclose(m[[0, 1, 2]], f[[1, 0, 2]], atol=10 * tol) or np.allclose(m, f, atol=10 * tol) for f in ends
        ):
            return False
    return True


def axis_segment(params: Mapping[str, Any], width: float, height: float) -> tuple[np.ndarray, np.ndarray] | None:
    """The part of a symmetric level's mirror axis inside the image (0..width, 0..height), px, or None.

    None when ``params`` has no ``"symmetry"`` record or the axis misses the image.
    """
    record = params.get("symmetry")
    if not isinstance(record, Mapping) or "point" not in record:
        return None
    p = np.asarray(record["point"], dtype=np.float64)
    d = np.asarray(record["direction"], dtype=np.float64)
    d = d / float(np.hypot(*d))
    lo, hi = -math.inf, math.inf
    for k, size in ((0, width), (1, height)):
        if abs(d[k]) < 1e-12:
            if not 0.0 <= p[k] <= size:
                return None
            continue
        t0, t1 = sorted(((0.0 - p[k]) / d[k], (size - p[k]) / d[k]))
        lo, hi = max(lo, t0), min(hi, t1)
    if not lo < hi:
        return None
    return p + lo * d, p + hi * d
