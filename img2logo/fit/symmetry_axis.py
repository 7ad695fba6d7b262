"""The mirror axis of a symmetric logo, found in the feature lines (beyond the paper, Sec. 9).

:func:`find_axis` finds the best mirror axis of the feature-line map at any
angle: every candidate axis reflects a sample of the line pixels, and its
*score* is the fraction whose mirror image lies within
``SYMMETRY_MATCH_DISTANCE`` of a line (looked up in a distance transform).
A coarse search over directions (and offsets around the pixels' centroid,
where a symmetric set has its axis) is refined by least squares on the
matched pairs (each pixel's mirror image against its nearest line pixel).
:func:`choose_axis` decides what ``symmetry=...`` asks for one image
(:class:`SymmetryChoice`); the symmetric fit is :mod:`img2logo.fit.symmetry`.

Coordinates and angles: those of the axis, :mod:`img2logo.geometry.mirror`
(px, x right, y down; an axis at 90 degrees is vertical).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InvalidParameterError
from ..geometry.mirror import Axis
from .constants import (
    SYMMETRY_ANGLE_STEP,
    SYMMETRY_MATCH_DISTANCE,
    SYMMETRY_OFFSET_RANGE,
    SYMMETRY_OFFSET_STEP,
    SYMMETRY_SAMPLE_POINTS,
    SYMMETRY_SNAP_ANGLE,
    SYMMETRY_SNAP_SCORE_LOSS,
    SYMMETRY_THRESHOLD,
)

__all__ = ["SymmetryChoice", "choose_axis", "find_axis"]

_FORCED = {"vertical": 90.0, "horizontal": 0.0}


# --------------------------------------------------------------------------- the axis
@dataclass(frozen=True, eq=False)
class SymmetryChoice:
    """What ``symmetry=...`` decided for one image.

    Attributes
    ----------
    mode : str
        The option: ``"auto"``, ``"vertical"``, ``"horizontal"`` or an angle in degrees.
    axis : Axis or None
        The axis used; None when ``auto`` found none good enough.
    best : Axis
        The best axis found (the one used, or the one ``auto`` turned down).
    description : str
        One line saying what was decided and why.
    """

    mode: str
    axis: Axis | None
    best: Axis
    description: str


def _line_pixels(lines: np.ndarray) -> np.ndarray:
    rows, cols = np.nonzero(lines)
    return np.column_stack([cols + 0.5, rows + 0.5]).astype(np.float64)


class _Scorer:
    """Scores axes (normal angle theta, offset c: the axis is {p : p . n = c}) on a line map."""

    def __init__(self, lines: np.ndarray) -> None:
        from scipy import ndimage

        self.lines = np.asarray(lines, dtype=bool)
        self.h, self.w = self.lines.shape
        pts = _line_pixels(self.lines)
        step = max(1, len(pts) // SYMMETRY_SAMPLE_POINTS)
        self.points = pts[::step]
        dist, idx = ndimage.distance_transform_edt(~self.lines, return_indices=True)
        self.dist = dist
        self.nearest = np.stack([idx[1] + 0.5, idx[0] + 0.5], axis=-1)  # nearest line pixel, (x, y)
        self.centroid = pts.mean(axis=0)

    def reflect(self, theta: float, c: float, pts: np.ndarray | None = None) -> np.ndarray:
        p = self.points if pts is None else pts
        n = np.array([math.cos(theta), math.sin(theta)])
        return p - 2.0 * (p @ n - c)[:, None] * n

    def distances(self, theta: float, c: float) -> np.ndarray:
        q = self.reflect(theta, c)
        col = np.floor(q[:, 0]).astype(np.int64)
        row = np.floor(q[:, 1]).astype(np.int64)
        inside = (col >= 0) & (col < self.w) & (row >= 0) & (row < self.h)
        out = np.full(len(q), np.inf)
        out[inside] = self.dist[row[inside], col[inside]]
        return out

    def scores(self, theta: float, offsets: np.ndarray) -> np.ndarray:
        """:meth:`score` of the axes of one direction at several offsets, shape (K,)."""
        n = np.array([math.cos(theta), math.sin(theta)])
        p = self.points
        shift = 2.0 * (p @ n - offsets[:, None])  # (K, N)
        col = np.floor(p[:, 0] - shift * n[0]).astype(np.int64)
        row = np.floor(p[:, 1] - shift * n[1]).astype(np.int64)
        inside = (col >= 0) & (col < self.w) & (row >= 0) & (row < self.h)
        near = np.zeros(col.shape, dtype=bool)
        near[inside] = self.dist[row[inside], col[inside]] <= SYMMETRY_MATCH_DISTANCE
        return near.mean(axis=1)

    def score(self, theta: float, c: float) -> float:
        return float(np.mean(self.distances(theta, c) <= SYMMETRY_MATCH_DISTANCE))

    def refine(self, theta: float, c: float, fixed_angle: bool) -> tuple[float, float]:
        """Least squares on matched pairs: each pixel's mirror image against its nearest line pixel."""
        from scipy.optimize import least_squares

        for _ in range(3):
            q = self.reflect(theta, c)
            col = np.clip(np.floor(q[:, 0]).astype(np.int64), 0, self.w - 1)
            row = np.clip(np.floor(q[:, 1]).astype(np.int64), 0, self.h - 1)
            d = self.distances(theta, c)
            ok = d <= SYMMETRY_MATCH_DISTANCE
            if ok.sum() < 3:
                break
            p, target = self.points[ok], self.nearest[row[ok], col[ok]]

            def residuals(
                x: np.ndarray, p: np.ndarray = p, target: np.ndarray = target, theta: float = theta
            ) -> np.ndarray:
                t, cc = (theta, x[0]) if fixed_angle else (x[0], x[1])
                return (self.reflect(t, cc, p) - target).ravel()

            x0 = np.array([c] if fixed_angle else [theta, c])
            sol = least_squares(residuals, x0, loss="soft_l1", f_scale=1.0)
            new = (theta, float(sol.x[0])) if fixed_angle else (float(sol.x[0]), float(sol.x[1]))
            if self.score(*new) < self.score(theta, c):
                break
            theta, c = new
        return theta, c


def find_axis(lines: np.ndarray, angle: float | None = None) -> Axis:
    """The best mirror axis of a feature-line map, with its score.

    Parameters
    ----------
    lines : ndarray of bool, shape (H, W)
        The feature lines (``FeatureLines.lines``).
    angle : float, optional
        Force the axis direction, degrees from +x towards +y (90: vertical); only
        its position is searched then. Default: any direction.

    Returns
    -------
    Axis
        Its score is 0.0 for a map without line pixels.

    Raises
    ------
    InvalidParameterError
        If ``lines`` is not a 2-D map.
    """
    arr = np.asarray(lines)
    if arr.ndim != 2:
        raise InvalidParameterError(f"lines must be a 2-D map of shape (H, W), got shape {arr.shape}")
    if not arr.any():
        direction = (0.0, 1.0) if angle is None else (math.cos(math.radians(angle)), math.sin(math.radians(angle)))
        return Axis(np.array([arr.shape[1] / 2, arr.shape[0] / 2]), np.array(direction), 0.0)
    return _search(_Scorer(arr), angle)


def _search(sc: _Scorer, angle: float | None) -> Axis:
    """:func:`find_axis` on a line map's scorer (its distance map made once for several searches)."""
    if angle is None:
        thetas = np.arange(0.0, math.pi, SYMMETRY_ANGLE_STEP)
    else:
        thetas = np.array([math.radians(angle) + math.pi / 2])  # the axis's normal
    offsets = np.arange(-SYMMETRY_OFFSET_RANGE, SYMMETRY_OFFSET_RANGE + 1e-9, SYMMETRY_OFFSET_STEP)
    if angle is not None:
        # A forced direction: its position anywhere across the drawing.
        n = np.array([math.cos(thetas[0]), math.sin(thetas[0])])
        proj = sc.points @ n
        base = float(sc.centroid @ n)
        offsets = np.arange(proj.min() - base, proj.max() - base + 1e-9, SYMMETRY_OFFSET_STEP)
    best = (-1.0, 0.0, 0.0)
    for theta in thetas:
        n = np.array([math.cos(theta), math.sin(theta)])
        cs = float(sc.centroid @ n) + offsets
        scores = sc.scores(float(theta), cs)
        k = int(np.argmax(scores))
        if scores[k] > best[0]:
            best = (float(scores[k]), float(theta), float(cs[k]))
    theta, c = sc.refine(best[1], best[2], fixed_angle=angle is not None)
    n = np.array([math.cos(theta), math.sin(theta)])
    point = sc.centroid - (sc.centroid @ n - c) * n
    return Axis(point, np.array([-n[1], n[0]]), sc.score(theta, c))


def choose_axis(lines: np.ndarray, mode: str) -> SymmetryChoice:
    """Apply the ``symmetry`` option (checked by :func:`check_symmetry_option`) to a line map.

    ``auto`` keeps the best axis at any angle if its score is at least
    ``SYMMETRY_THRESHOLD``; ``vertical``, ``horizontal`` or an angle force the
    direction and keep the best position whatever the score.
    """
    arr = np.asarray(lines)
    scorer = _Scorer(arr) if arr.ndim == 2 and arr.any() else None  # one distance map for every search

    def axis(angle: float | None = None) -> Axis:
        return find_axis(arr, angle) if scorer is None else _search(scorer, angle)

    if mode == "auto":
        best = axis()
        for upright in (0.0, 90.0, 180.0):
            # Nearly upright (or level) is made exactly so, unless that scores worse.
            if 0.0 < abs(best.angle - upright) <= SYMMETRY_SNAP_ANGLE:
                snapped = axis(upright % 180.0)
                if snapped.score >= best.score - SYMMETRY_SNAP_SCORE_LOSS:
                    best = snapped
        if best.score >= SYMMETRY_THRESHOLD:
            text = f"symmetry: {best.describe()} >= {SYMMETRY_THRESHOLD:g}: the logo is made symmetric"
            return SymmetryChoice(mode, best, best, text)
        text = f"symmetry: none (best {best.describe()} < {SYMMETRY_THRESHOLD:g}): the logo is made free"
        return SymmetryChoice(mode, None, best, text)
    angle = _FORCED.get(mode)
    forced = axis(float(mode) if angle is None else angle)
    return SymmetryChoice(mode, forced, forced, f"symmetry: {forced.describe()} ({mode}, as asked)")
