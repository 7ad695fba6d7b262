"""Circle fitting: free fits to one segment (Sec. 5.3, first stage).

* :func:`fit_circle` fits centre and radius to one segment's points: the
  algebraic Hyper fit [Al-Sharadqah & Chernov 2009] followed by a geometric
  Levenberg-Marquardt refinement of the residuals ``|p - o| - r`` (Eqn. 9). It is
  the first stage of the two-stage golden ratio circle fitting, whose radii are
  then snapped to the ladder (Eqn. 12), and the fit behind the bias estimate
  (Eqn. 14). Unlike the Kasa fit (scikit-image's ``CircleModel``) it does not
  shrink the radius of short noisy arcs.
* :func:`fit_center` places the centre of a circle of fixed (golden) radius.
* :func:`mean_abs_error` is the "average fitting error" of the line-segment
  simplification (Sec. 5.4).

The second stage, the connectivity-constrained fit of Eqn. 13 and its local
window, is :mod:`img2logo.fit.constrained_fit`.

Coordinates are input-image pixels: x to the right, y downwards, the pixel in row
i, column j has its centre at (j + 0.5, i + 0.5). Lengths are in px.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validation import check_points, check_positive, readonly
from ..constants import MAX_RADIUS_FACTOR
from ..errors import FitError, InvalidParameterError
from .constants import CIRCLE_REFINE_MAX_ITER

__all__ = [
    "CircleFit",
    "fit_center",
    "fit_circle",
    "mean_abs_error",
]


# --------------------------------------------------------------------------------
# Free fit of one circle
# --------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class CircleFit:
    """The result of :func:`fit_circle`.

    Attributes
    ----------
    center : ndarray, shape (2,)
        Centre (x, y), px.
    radius : float
        Radius, px.
    rms : float
        Root mean square of the geometric residuals ``|p - o| - r``, px.
    capped : bool
        True when the points were (nearly) straight and the radius was capped at
        ``max_radius`` (see :func:`fit_circle`).
    """

    center: np.ndarray
    radius: float
    rms: float
    capped: bool


def _hyper_fit(x: np.ndarray, y: np.ndarray) -> tuple[float, float, float]:
    """Hyper fit of centred, unit-scaled coordinates: (a, b, r); r is inf for a line."""
    z = x * x + y * y
    design = np.column_stack([z, x, y, np.ones_like(x)])
    if len(design) < 4:  # zero rows change nothing but give the SVD four singular values
        design = np.vstack([design, np.zeros((4 - len(design), 4))])
    _, s, vt = np.linalg.svd(design, full_matrices=False)
    if s[3] < 1e-12 * s[0]:  # points exactly on a circle (or line): the null vector
        coef = vt[3]
    else:
        # Generalized eigenproblem M A = eta N A with the Hyper constraint matrix N;
        # solved as in Chernov's HyperSVD through W = V S V^T (M = W^2 / n).
        w = vt.T @ np.diag(s) @ vt
        zm, xm, ym = z.mean(), x.mean(), y.mean()
        n_mat = np.array(
            [[8 * zm, 4 * xm, 4 * ym, 2], [4 * xm, 1, 0, 0], [4 * ym, 0, 1, 0], [2, 0, 0, 0]], dtype=np.float64
        )
        evals, evecs = np.linalg.eig(w @ np.linalg.solve(n_mat, w))
        order = np.argsort(evals.real)
        coef = np.linalg.solve(w, evecs[:, order[1]].real)  # the smallest positive eigenvalue
    a0, a1, a2, a3 = coef
    disc = a1 * a1 + a2 * a2 - 4 * a0 * a3
    if abs(a0) <= 1e-14 * math.sqrt(max(disc, 0.0)) or disc <= 0:
        return 0.0, 0.0, math.inf
    return -a1 / (2 * a0), -a2 / (2 * a0), math.sqrt(disc) / (2 * abs(a0))


def _refine(x: np.ndarray, y: np.ndarray, a: float, b: float, r: float) -> tuple[float, float, float]:
    """Levenberg-Marquardt on the geometric residuals ``|(x, y) - (a, b)| - r`` (Eqn. 9).

    Works in the centred, unit-scaled coordinates of :func:`fit_circle`; stops when
    a step is below 1e-9 of the radius.
    """

    def residuals(a: float, b: float, r: float) -> tuple[float, np.ndarray]:
        dx, dy = x - a, y - b
        d = np.sqrt(dx * dx + dy * dy)
        safe = np.where(d > 0, d, 1.0)
        # Rows: residuals e, and their derivatives by a and b (the one by r is -1).
        rows = np.stack([d - r, np.where(d > 0, -dx / safe, 1.0), -dy / safe])
        return float(rows[0] @ rows[0]), rows

    f, rows = residuals(a, b, r)
    lam = 1e-6
    for _ in range(CIRCLE_REFINE_MAX_ITER):
        # J^T J and J^T e from one matrix product (cheaper than nine sums).
        m = rows @ np.vstack([rows, np.ones(len(x))]).T  # (3, 4)
        jtj = np.array([[m[1, 1], m[1, 2], -m[1, 3]], [m[1, 2], m[2, 2], -m[2, 3]], [-m[1, 3], -m[2, 3], len(x)]])
        grad = np.array([m[0, 1], m[0, 2], -m[0, 3]])
        while lam < 1e10:
            step = np.linalg.solve(jtj + lam * np.diag(np.diag(jtj)), -grad)
            if np.max(np.abs(step)) <= 1e-9 * max(1.0, abs(r)):
                return a, b, r  # converged
            f_new, rows_new = residuals(a + step[0], b + step[1], r + step[2])
            if f_new <= f:
                a, b, r = a + step[0], b + step[1], r + step[2]
                f, rows = f_new, rows_new
                lam = max(lam / 10, 1e-12)
                break
            lam *= 10
        else:
            break  # no decrease: at the minimum to rounding
    return a, b, r


def fit_circle(points: object, *, max_radius: float | None = None, refine: bool = True) -> CircleFit:
    """Fit a circle to ``points`` (unconstrained; first stage of Sec. 5.3, and Eqn. 14).

    The algebraic Hyper fit [Al-Sharadqah & Chernov 2009] (a 4x4 eigenproblem on
    centred, unit-scaled coordinates) gives a start that a few Levenberg-Marquardt
    iterations refine into the geometric least-squares circle, minimizing
    ``sum (|p - o| - r)^2``.

    Nearly straight points have a huge (or, exactly collinear, infinite) radius.
    If the fitted radius exceeds ``max_radius``, or no finite circle exists, the
    result is instead the circle of radius ``max_radius`` through the two
    extreme points of ``points`` along their principal axis (the end points of a
    straight-ish segment), with its centre on the concave side of the points,
    i.e. curving the same way they do (the side opposite to their mean offset
    from the chord). For exactly straight points the centre is on the left of
    the chord direction (the direction is fixed by making the principal axis
    point towards +x, or +y if vertical), and ``capped`` is True.

    Parameters
    ----------
    points : array_like, shape (N, 2)
        Points (x, y), px, at least 3 distinct. Their order does not matter.
    max_radius : float, optional
        Largest radius returned, px. Default: ``MAX_RADIUS_FACTOR`` (20) times the
        points' extent (the distance between the two extreme points).
    refine : bool, optional
        Polish the Hyper fit by Levenberg-Marquardt (default). The progressive
        optimization skips it: it snaps the radius to the ladder and refits the
        centre anyway, and the Hyper fit's radius is already unbiased to
        second order.

    Returns
    -------
    CircleFit

    Raises
    ------
    FitError
        Fewer than 3 (distinct) points, or ``max_radius`` smaller
        than half the extent (no circle of that radius through the end points).
    InvalidParameterError
        ``points`` not of shape (N, 2) or not finite; ``max_radius`` not > 0.
    """
    p = _points(points)
    if len(p) < 3:
        raise FitError(f"a circle fit needs at least 3 points, got {len(p)}")
    if max_radius is not None:
        check_positive(max_radius, "max_radius")
    if refine:
        return _fit_circle_svd(p, max_radius, refine)
    status, cx, cy, radius, rms, capped = _kernels()["fit_circle_kernel"](  # loaded on the first fit, not at import
        p, 0.0 if max_radius is None else float(max_radius), MAX_RADIUS_FACTOR
    )
    if status == 1:
        raise FitError(f"a circle fit needs at least 3 distinct points, got {int(cx)}")
    if status == 2:
        raise FitError(f"max_radius {cx:g} is less than half the points' extent {cy:g}")
    return CircleFit(readonly(np.array([cx, cy])), radius, rms, capped)


def _fit_circle_svd(p: np.ndarray, max_radius: float | None, refine: bool) -> CircleFit:
    """:func:`fit_circle` in numpy, the Hyper fit by SVD: the refined fit, and the compiled kernel's oracle."""
    # Count distinct points up to 3 (np.unique(axis=0) is slow): any circle through
    # two points would fit them exactly.
    not_first = np.any(p != p[0], axis=1)
    distinct = 1
    if not_first.any():
        not_second = np.any(p != p[np.argmax(not_first)], axis=1)
        distinct = 3 if np.any(not_first & not_second) else 2
    if distinct < 3:
        raise FitError(f"a circle fit needs at least 3 distinct points, got {distinct}")
    centroid = p.mean(axis=0)
    q = p - centroid
    scale = math.sqrt(float(np.mean(np.sum(q * q, axis=1))))
    # The principal axis, oriented towards +x (or +y), and the extreme points along it.
    axis = np.linalg.svd(q, full_matrices=False)[2][0]
    if axis[0] < 0 or (axis[0] == 0 and axis[1] < 0):
        axis = -axis
    proj = q @ axis
    end_a, end_b = p[np.argmin(proj)], p[np.argmax(proj)]
    extent = float(np.hypot(*(end_b - end_a)))
    r_max = MAX_RADIUS_FACTOR * extent if max_radius is None else check_positive(max_radius, "max_radius")

    x, y = q[:, 0] / scale, q[:, 1] / scale
    a, b, r = _hyper_fit(x, y)
    if refine and math.isfinite(r) and r * scale <= 1e3 * max(r_max, extent):
        a, b, r = _refine(x, y, a, b, r)
    center = centroid + scale * np.array([a, b])
    radius = abs(r) * scale
    capped = not (math.isfinite(radius) and radius <= r_max)
    if capped:
        half = extent / 2
        if r_max < half:
            raise FitError(f"max_radius {r_max:g} is less than half the points' extent {half:g}")
        tangent = (end_b - end_a) / extent
        normal = np.array([-tangent[1], tangent[0]])
        mid = (end_a + end_b) / 2
        bow = float(np.mean((p - mid) @ normal))
        side = -1.0 if bow > 1e-12 * extent else 1.0  # the centre is opposite the bulge
        center = mid + side * math.sqrt(r_max * r_max - half * half) * normal
        radius = r_max
    res = np.hypot(p[:, 0] - center[0], p[:, 1] - center[1]) - radius
    return CircleFit(readonly(center), float(radius), float(np.sqrt(np.mean(res * res))), capped)


def mean_abs_error(points: object, center: object, radius: float) -> float:
    """Mean absolute geometric error ``mean | |p - o| - r |`` of ``points`` (N, 2), px.

    The "average fitting error" of the line-segment simplification (Sec. 5.4).
    """
    p = _points(points)
    o = np.asarray(center, dtype=np.float64)
    if o.shape != (2,):
        raise InvalidParameterError(f"center must be a finite array of shape (2,), got {o.shape}")
    cx, cy = float(o[0]), float(o[1])
    if not (math.isfinite(cx) and math.isfinite(cy)):
        raise InvalidParameterError(f"center must be a finite array of shape (2,), got {o.shape}")
    r = check_positive(radius, "radius")
    return float(_kernels()["mean_abs_error_kernel"](p, cx, cy, r))


def fit_center(points: object, radius: float, center0: object, *, iterations: int = 8) -> np.ndarray:
    """Best centre, shape (2,), px, of a circle of fixed ``radius`` for ``points`` (N, 2).

    Gauss-Newton on the geometric residuals ``|p - o| - r`` from ``center0``:
    the second stage of Sec. 5.3 for one circle alone, when its radius has been
    snapped to the ladder (Eqn. 12) and no junction constrains it. Stops early
    once a step is below 1e-9 px.
    """
    p = _points(points)
    o = np.array(center0, dtype=np.float64).reshape(2)
    r = check_positive(radius, "radius")
    return np.array(_kernels()["fit_center_kernel"](p, r, float(o[0]), float(o[1]), int(iterations)))


_FLOAT64 = np.dtype(np.float64)


def _points(points: object) -> np.ndarray:
    """:func:`~img2logo._validation.check_points` (shape (N, 2), N >= 1, finite), C-contiguous float64.

    The fits run thousands of times on a run's groups (the simplification, the
    initial fit, every merge): an array that is already right passes on one sum,
    which is finite only if every value is (a NaN or an infinity makes it NaN or
    infinite).
    """
    if (
        type(points) is np.ndarray
        and points.dtype is _FLOAT64
        and points.ndim == 2
        and points.shape[1] == 2
        and len(points)
        and math.isfinite(points.sum())
    ):
        return points if points.flags.c_contiguous else np.ascontiguousarray(points)
    return np.ascontiguousarray(check_points(points))


_KERNELS: Any = None  # img2logo._compiled.kernels, once a fit asked for it (its import is not every run's)


def _kernels() -> dict[str, Any]:
    """The compiled kernels by name (:mod:`img2logo._compiled.kernels`; numba's JIT where none can be cached)."""
    global _KERNELS
    if _KERNELS is None:
        from .._compiled import kernels

        _KERNELS = kernels
    return _KERNELS._load()
