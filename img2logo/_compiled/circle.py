"""Compiled kernels of the circle fits: the free fit of one segment, a golden circle's centre.

The methods are those of their Python references in :mod:`img2logo.geometry.circle_fitting`
(which documents them: the Hyper fit [Al-Sharadqah & Chernov 2009] of Sec. 5.3's
first stage, the radius cap of nearly straight points; the Gauss-Newton centre of
a circle of fixed radius), on points as (N, 2) arrays, px. The Hyper fit here
takes Chernov's route: the smallest root of the generalized eigenproblem's
characteristic polynomial by Newton's method from 0, then the centre from its
2 x 2 system (no SVD or eigen-decomposition, which the ahead-of-time module
cannot call). It is the same circle to rounding: the tests compare the two.

Written in the subset of Python that numba compiles; loaded through
:mod:`img2logo._compiled.kernels` (ahead of time, or numba's JIT as a fallback), never
imported by the pipeline directly.
"""

from __future__ import annotations

import math

import numpy as np

from .jit import jit as _jit

#: Newton iterations on the Hyper fit's characteristic polynomial (Chernov's limit).
HYPER_NEWTON_MAX_ITER = 99


@_jit
def _hyper(x, y):  # pragma: no cover - compiled
    """Hyper fit of (nearly) centred, unit-scaled coordinates: (a, b, r); r is inf for a line."""
    n = len(x)
    mx = 0.0
    my = 0.0
    for i in range(n):
        mx += x[i]
        my += y[i]
    mx /= n
    my /= n
    sxx = syy = sxy = sxz = syz = szz = 0.0
    for i in range(n):
        xi = x[i] - mx
        yi = y[i] - my
        zi = xi * xi + yi * yi
        sxy += xi * yi
        sxx += xi * xi
        syy += yi * yi
        sxz += xi * zi
        syz += yi * zi
        szz += zi * zi
    sxx /= n
    syy /= n
    sxy /= n
    sxz /= n
    syz /= n
    szz /= n
    mz = sxx + syy
    cov_xy = sxx * syy - sxy * sxy
    var_z = szz - mz * mz
    a2 = 4.0 * cov_xy - 3.0 * mz * mz - szz
    a1 = var_z * mz + 4.0 * cov_xy * mz - sxz * sxz - syz * syz
    a0 = sxz * (sxz * syy - syz * sxy) + syz * (syz * sxx - sxz * sxy) - var_z * cov_xy
    a22 = a2 + a2
    root = 0.0
    value = a0
    for _ in range(HYPER_NEWTON_MAX_ITER):
        slope = a1 + root * (a22 + 16.0 * root * root)
        new = root - value / slope
        if new == root or not math.isfinite(new):
            break
        new_value = a0 + new * (a1 + new * (a2 + 4.0 * new * new))
        if abs(new_value) >= abs(value):
            break
        root = new
        value = new_value
    det = root * root - root * mz + cov_xy
    if det == 0.0:
        return 0.0, 0.0, math.inf
    a = (sxz * (syy - root) - syz * sxy) / det / 2.0
    b = (syz * (sxx - root) - sxz * sxy) / det / 2.0
    r2 = a * a + b * b + mz - root - root
    if not (math.isfinite(a) and math.isfinite(b) and math.isfinite(r2)) or r2 <= 0.0:
        return 0.0, 0.0, math.inf
    return a + mx, b + my, math.sqrt(r2)


@_jit
def fit_circle_kernel(p, max_radius, radius_factor):  # pragma: no cover - compiled
    """``circle_fitting.fit_circle(p, refine=False)``: (status, cx, cy, radius, rms, capped).

    ``max_radius`` <= 0 means the default, ``radius_factor`` times the extent.
    Status 0 is a fit; 1: fewer than 3 distinct points (their count in ``cx``);
    2: ``max_radius`` (in ``cx``) below half the extent (in ``cy``).
    """
    n = len(p)
    distinct = 1
    second = -1
    for i in range(n):
        if p[i, 0] != p[0, 0] or p[i, 1] != p[0, 1]:
            second = i
            distinct = 2
            break
    if second >= 0:
        for i in range(n):
            if (p[i, 0] != p[0, 0] or p[i, 1] != p[0, 1]) and (p[i, 0] != p[second, 0] or p[i, 1] != p[second, 1]):
                distinct = 3
                break
    if n < 3 or distinct < 3:
        return 1, float(min(n, distinct)), 0.0, 0.0, 0.0, False
    cx0 = 0.0
    cy0 = 0.0
    for i in range(n):
        cx0 += p[i, 0]
        cy0 += p[i, 1]
    cx0 /= n
    cy0 /= n
    x = p[:, 0] - cx0
    y = p[:, 1] - cy0
    sxx = syy = sxy = 0.0
    for i in range(n):
        sxx += x[i] * x[i]
        syy += y[i] * y[i]
        sxy += x[i] * y[i]
    scale = math.sqrt((sxx + syy) / n)
    # The principal axis (of the 2 x 2 scatter matrix), oriented towards +x (or +y).
    angle = 0.5 * math.atan2(2.0 * sxy, sxx - syy)
    ux = math.cos(angle)
    uy = math.sin(angle)
    if ux < 0 or (ux == 0 and uy < 0):
        ux = -ux
        uy = -uy
    lo = 0
    hi = 0
    plo = x[0] * ux + y[0] * uy
    phi = plo
    for i in range(1, n):
        proj = x[i] * ux + y[i] * uy
        if proj < plo:
            plo = proj
            lo = i
        if proj > phi:
            phi = proj
            hi = i
    ex = p[hi, 0] - p[lo, 0]
    ey = p[hi, 1] - p[lo, 1]
    extent = math.hypot(ex, ey)
    r_max = radius_factor * extent if max_radius <= 0 else max_radius
    a, b, r = _hyper(x / scale, y / scale)
    cx = cx0 + scale * a
    cy = cy0 + scale * b
    radius = abs(r) * scale
    capped = not (math.isfinite(radius) and radius <= r_max)
    if capped:
        half = extent / 2
        if r_max < half:
            return 2, r_max, half, 0.0, 0.0, True
        tx = ex / extent
        ty = ey / extent
        mx = (p[lo, 0] + p[hi, 0]) / 2
        my = (p[lo, 1] + p[hi, 1]) / 2
        bow = 0.0
        for i in range(n):
            bow += (p[i, 0] - mx) * -ty + (p[i, 1] - my) * tx
        bow /= n
        side = -1.0 if bow > 1e-12 * extent else 1.0  # the centre is opposite the bulge
        offset = side * math.sqrt(r_max * r_max - half * half)
        cx = mx - offset * ty
        cy = my + offset * tx
        radius = r_max
    sq = 0.0
    for i in range(n):
        e = math.hypot(p[i, 0] - cx, p[i, 1] - cy) - radius
        sq += e * e
    return 0, cx, cy, radius, math.sqrt(sq / n), capped


@_jit
def fit_center_kernel(p, radius, cx, cy, iterations):  # pragma: no cover - compiled
    """``circle_fitting.fit_center``: Gauss-Newton on ``|p - o| - r`` from (cx, cy); the centre (x, y).

    The 2 x 2 normal equations are solved directly; a singular one (all the
    points at one spot) takes no step, as least squares' minimum-norm answer
    to a zero right-hand side would.
    """
    n = len(p)
    for _ in range(iterations):
        sxx = sxy = syy = gx = gy = 0.0
        for i in range(n):
            vx = cx - p[i, 0]
            vy = cy - p[i, 1]
            d = math.sqrt(vx * vx + vy * vy)
            if d == 0:
                d = 1e-12
            ux = vx / d
            uy = vy / d
            e = d - radius
            sxx += ux * ux
            sxy += ux * uy
            syy += uy * uy
            gx += ux * e
            gy += uy * e
        det = sxx * syy - sxy * sxy
        if not det > 4.440892098500626e-16 * (sxx + syy) ** 2:  # lstsq's cut: 2 eps of the larger
            # (nearly) rank one: all the directions along one line; step along it.
            norm = sxx + syy
            if norm == 0:
                break
            if sxx >= syy:
                wx, wy = sxx, sxy
            else:
                wx, wy = sxy, syy
            w = math.hypot(wx, wy)
            wx /= w
            wy /= w
            s = -(wx * gx + wy * gy) / norm
            sx = s * wx
            sy = s * wy
        else:
            sx = -(syy * gx - sxy * gy) / det
            sy = -(sxx * gy - sxy * gx) / det
        cx += sx
        cy += sy
        if max(abs(sx), abs(sy)) < 1e-9:
            break
    return cx, cy


@_jit
def mean_abs_error_kernel(p, cx, cy, radius):  # pragma: no cover - compiled
    """``circle_fitting.mean_abs_error``: mean | |p - o| - r |, px."""
    n = len(p)
    total = 0.0
    for i in range(n):
        total += abs(math.hypot(p[i, 0] - cx, p[i, 1] - cy) - radius)
    return total / n


@_jit
def largest_gap_kernel(p, cx, cy, radius):  # pragma: no cover - compiled
    """The largest | |p - o| - r | of points (N, 2), px: the farthest point's distance from the circle."""
    return farthest_from_circle(p, cx, cy, radius, 0.0, math.inf)


@_jit
def biarc_worst_kernel(chain, centre, index, splits, radius, head):  # pragma: no cover - compiled
    """``biarcs.biarc_worst`` past its circles' centres: the largest distance (S, A), px.

    ``centre`` (S, A, 2) holds the circle of each split and turn; of the pixels
    ``chain[index]`` those up to the split (``head``) or from it on count. The
    same arithmetic as the numpy reference, which measures every pixel and
    zeroes the others' distances (the distances are not negative: the largest
    is the same).
    """
    n_splits = centre.shape[0]
    n_turns = centre.shape[1]
    pixels = chain[index]
    out = np.zeros((n_splits, n_turns))
    for s in range(n_splits):
        if head:  # index increases: the pixels up to the split are a head of them, those from it on a tail
            side = pixels[: np.searchsorted(index, splits[s], side="right")]
        else:
            side = pixels[np.searchsorted(index, splits[s], side="left") :]
        for a in range(n_turns):
            out[s, a] = farthest_from_circle(side, centre[s, a, 0], centre[s, a, 1], radius, 0.0, math.inf)
    return out


@_jit
def farthest_from_circle(points, cx, cy, radius, worst, best):  # pragma: no cover - compiled
    """The largest of ``worst`` and the distances | |p - o| - r | of ``points`` (n, 2) from a circle, px.

    In the points' order, stopping once it reaches ``best`` (it can only grow): a biarc
    search's candidate that far is no better than the best so far.
    """
    return measure_from_circle(points, cx, cy, radius, worst, best)[0]


@_jit
def measure_from_circle(points, cx, cy, radius, worst, best):  # pragma: no cover - compiled
    """:func:`farthest_from_circle`, and how many of the points it measured (all, or up to the one reaching ``best``).

    Measuring the rest later, from the largest so far, gives the same largest distance as from the start.
    """
    for i in range(points.shape[0]):
        d = abs(math.hypot(points[i, 0] - cx, points[i, 1] - cy) - radius)
        if d > worst:
            worst = d
            if worst >= best:
                return worst, i + 1
    return worst, points.shape[0]
