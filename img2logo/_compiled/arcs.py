"""Compiled kernels of the arcs: arc-arc intersections, the redundant-intersection test, the arc extraction.

The same arithmetic as their Python references in :mod:`img2logo.fit.arc_extraction`
(which document the methods: Sec. 5.2's redundant intersections, Sec. 5.3's
arc extraction with the discrete Fréchet distance of [EM94]), on arcs as rows
``(cx, cy, r, theta0, sweep)`` and points as (N, 2) arrays.

Written in the subset of Python that numba compiles; loaded through
:mod:`img2logo._compiled.kernels` (ahead of time, or numba's JIT as a fallback), never
imported by the pipeline directly. Coordinates follow :mod:`img2logo.geometry.primitives`:
px, x right, y down.
"""

from __future__ import annotations

import math

import numpy as np

from .circle import farthest_from_circle, measure_from_circle
from .jit import jit as _jit

# --------------------------------------------------------------------------------
# Arc-arc intersections (Sec. 5.2, Fig. 6, 12): arcs as rows (cx, cy, r, theta0, sweep)
# --------------------------------------------------------------------------------

TAU = 2.0 * math.pi
FULL_CIRCLE_SLACK = 1e-9  # |sweep| >= 2 pi - this is a whole circle (geometry.Arc.is_full_circle)


@_jit
def _mod_tau(value):  # pragma: no cover - compiled
    """``np.mod(value, 2 pi)``: the remainder with the sign of the divisor, as numpy computes it."""
    return value % TAU  # numba's float % is CPython's: fmod, then + 2 pi when negative (numpy's npy_divmod)


@_jit
def _contains_angle(arc, theta, tol):  # pragma: no cover - compiled
    """``Arc.contains_angle`` for one angle (radians), within ``tol`` radians."""
    sweep = arc[4]
    if abs(sweep) >= TAU - FULL_CIRCLE_SLACK:
        return True
    offset = _mod_tau((theta - arc[3]) * math.copysign(1.0, sweep))
    return offset <= abs(sweep) + tol or offset >= TAU - tol


@_jit
def _on_arc(arc, x, y, tol):  # pragma: no cover - compiled
    """Whether the point (x, y) of the arc's circle is within ``tol`` px of the arc's angle range."""
    return _contains_angle(arc, math.atan2(y - arc[1], x - arc[0]), tol / arc[2])


@_jit
def arc_intersections_kernel(a, b, tol, out):  # pragma: no cover - compiled
    """Points where two arcs meet (``intersections.arc_intersections``): written to ``out`` (4, 2), count returned.

    Circle-circle intersection, then the angle ranges; arcs of one circle (centres and
    radii within ``tol``) meet at the end points of their overlap.
    """
    r1, r2 = a[2], b[2]
    dx, dy = b[0] - a[0], b[1] - a[1]
    d = math.hypot(dx, dy)
    if d <= tol:
        if abs(r1 - r2) > tol:
            return 0
        full_a = abs(a[4]) >= TAU - FULL_CIRCLE_SLACK
        full_b = abs(b[4]) >= TAU - FULL_CIRCLE_SLACK
        if full_a and full_b:
            out[0, 0], out[0, 1] = a[0] + a[2] * math.cos(a[3]), a[1] + a[2] * math.sin(a[3])
            return 1
        k = 0
        for side in range(2):
            arc, other = (a, b) if side == 0 else (b, a)
            if abs(arc[4]) >= TAU - FULL_CIRCLE_SLACK:
                continue
            for end in range(2):
                t = arc[3] + (arc[4] if end else 0.0)
                px, py = arc[0] + arc[2] * math.cos(t), arc[1] + arc[2] * math.sin(t)
                if not _on_arc(other, px, py, tol):
                    continue
                new = True
                for q in range(k):
                    if math.hypot(px - out[q, 0], py - out[q, 1]) <= tol:
                        new = False
                if new:
                    out[k, 0], out[k, 1] = px, py
                    k += 1
        return k
    outside, inside = d - (r1 + r2), abs(r1 - r2) - d  # > 0: apart, one inside the other
    if outside > tol or inside > tol:
        return 0
    x = (d * d + r1 * r1 - r2 * r2) / (2.0 * d)  # along the centre line, from a's centre
    ux, uy = dx / d, dy / d
    bx, by = a[0] + x * ux, a[1] + x * uy
    n = 0
    if abs(outside) <= tol or abs(inside) <= tol:  # tangent
        out[0, 0], out[0, 1] = bx, by
        n = 1
    else:
        # Half the chord, by a product of differences of the inputs (no cancellation).
        h2 = -outside * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2) / (4.0 * d * d)
        h = math.sqrt(max(h2, 0.0))
        out[0, 0], out[0, 1] = bx + h * -uy, by + h * ux
        out[1, 0], out[1, 1] = bx - h * -uy, by - h * ux
        n = 2
    k = 0
    for q in range(n):
        px, py = out[q, 0], out[q, 1]
        if _on_arc(a, px, py, tol) and _on_arc(b, px, py, tol):
            out[k, 0], out[k, 1] = px, py
            k += 1
    return k


@_jit
def bounding_boxes(params):  # pragma: no cover - compiled
    """Bounding boxes (n, 4) of arcs (n, 5): xmin, ymin, xmax, ymax, px.

    The extremes of the end points and of the points at angles 0, pi/2, pi, 3 pi/2 on the arc.
    """
    n = params.shape[0]
    out = np.empty((n, 4))
    for i in range(n):
        cx, cy, r, t0, sw = params[i, 0], params[i, 1], params[i, 2], params[i, 3], params[i, 4]
        full = abs(sw) >= TAU - FULL_CIRCLE_SLACK
        xmin, ymin, xmax, ymax = np.inf, np.inf, -np.inf, -np.inf
        for u in range(6):
            if u == 0:
                ang = t0
            elif u == 1:
                ang = t0 + sw
            else:
                ang = (u - 2) * (math.pi / 2)
                if not full and _mod_tau((ang - t0) * np.sign(sw)) > abs(sw):
                    continue
            x, y = cx + r * math.cos(ang), cy + r * math.sin(ang)
            xmin, ymin, xmax, ymax = min(xmin, x), min(ymin, y), max(xmax, x), max(ymax, y)
        out[i, 0], out[i, 1], out[i, 2], out[i, 3] = xmin, ymin, xmax, ymax
    return out


@_jit
def arc_pairs_kernel(params, rows, tol):  # pragma: no cover - compiled
    """Pairs (K, 2) i < j, i or j in ``rows`` (sorted, unique), whose circles meet and boxes overlap within ``tol``.

    Sorted by (i, j) (``intersections.arc_pairs_near``).
    """
    n = params.shape[0]
    boxes = bounding_boxes(params)
    in_rows = np.zeros(n, np.bool_)
    for i in rows:
        in_rows[i] = True
    pairs = np.empty((n * len(rows), 2), np.int64)
    k = 0
    for i in range(n):
        for j in range(i + 1, n):
            if not (in_rows[i] or in_rows[j]):
                continue
            d = math.hypot(params[i, 0] - params[j, 0], params[i, 1] - params[j, 1])
            ri, rj = params[i, 2], params[j, 2]
            if not (d <= ri + rj + tol and d >= abs(ri - rj) - tol):
                continue
            bi, bj = boxes[i], boxes[j]
            if bi[0] <= bj[2] + tol and bj[0] <= bi[2] + tol and bi[1] <= bj[3] + tol and bj[1] <= bi[3] + tol:
                pairs[k, 0], pairs[k, 1] = i, j
                k += 1
    return pairs[:k]


@_jit
def redundant_kernel(params, rows, junctions, owned_ptr, owned_idx, inter_tol, tol):  # pragma: no cover - compiled
    """Redundant intersections (``intersections.redundant_intersections``): pairs (K, 2) and points (K, 2).

    Of the pairs of :func:`arc_pairs_kernel`, every meeting point (within
    ``inter_tol``) farther than ``tol`` px from all the junctions both arcs own
    (arc i owns ``owned_idx[owned_ptr[i]:owned_ptr[i + 1]]``).
    """
    pairs = arc_pairs_kernel(params, rows, inter_tol)
    out_pairs = np.empty((4 * pairs.shape[0], 2), np.int64)
    out_pts = np.empty((4 * pairs.shape[0], 2))
    pts = np.empty((4, 2))
    k = 0
    for q in range(pairs.shape[0]):
        i, j = pairs[q, 0], pairs[q, 1]
        n_pts = arc_intersections_kernel(params[i], params[j], inter_tol, pts)
        for u in range(n_pts):
            px, py = pts[u, 0], pts[u, 1]
            near = False
            for a in range(owned_ptr[i], owned_ptr[i + 1]):
                ka = owned_idx[a]
                shared = False
                for b in range(owned_ptr[j], owned_ptr[j + 1]):
                    if owned_idx[b] == ka:
                        shared = True
                if shared and math.hypot(junctions[ka, 0] - px, junctions[ka, 1] - py) <= tol:
                    near = True
            if not near:
                out_pairs[k, 0], out_pairs[k, 1] = i, j
                out_pts[k, 0], out_pts[k, 1] = px, py
                k += 1
    return out_pairs[:k], out_pts[:k]


# --------------------------------------------------------------------------------
# Arc extraction (Sec. 5.3, Fig. 9): the discrete Fréchet distance and the candidates
# --------------------------------------------------------------------------------


@_jit
def _greedy_coupling(p, q):  # pragma: no cover - compiled
    """The largest squared distance of a greedy coupling of (N, 2) and (M, 2) polylines: >= the Fréchet distance^2.

    From the first pair of vertices to the last, each step to the nearest of the
    next pairs (both on, or one of them); a coupling like any other, so its
    largest distance bounds the discrete Fréchet distance from above. O(N + M).
    """
    n, m = p.shape[0], q.shape[0]
    i, j = 0, 0
    dx, dy = p[0, 0] - q[0, 0], p[0, 1] - q[0, 1]
    worst = dx * dx + dy * dy
    while i < n - 1 or j < m - 1:
        if i == n - 1:
            j += 1
        elif j == m - 1:
            i += 1
        else:
            dx, dy = p[i + 1, 0] - q[j + 1, 0], p[i + 1, 1] - q[j + 1, 1]
            both = dx * dx + dy * dy
            dx, dy = p[i + 1, 0] - q[j, 0], p[i + 1, 1] - q[j, 1]
            on_p = dx * dx + dy * dy
            dx, dy = p[i, 0] - q[j + 1, 0], p[i, 1] - q[j + 1, 1]
            on_q = dx * dx + dy * dy
            if both <= on_p and both <= on_q:
                i += 1
                j += 1
            elif on_p <= on_q:
                i += 1
            else:
                j += 1
        dx, dy = p[i, 0] - q[j, 0], p[i, 1] - q[j, 1]
        worst = max(worst, dx * dx + dy * dy)
    return worst


@_jit
def frechet(p, q, bound):  # pragma: no cover - compiled
    """Exact discrete Fréchet distance [EM94] of (N, 2) and (M, 2) polylines; ``inf`` once known >= ``bound``.

    :func:`_frechet_within` of the smaller of ``bound^2`` and the largest
    squared distance of a greedy coupling (:func:`_greedy_coupling`, which the
    answer cannot exceed).
    """
    return _frechet_within(p, q, min(_greedy_coupling(p, q), bound * bound))


@_jit
def _frechet_within(p, q, cap):  # pragma: no cover - compiled
    """The discrete Fréchet distance [EM94] of (N, 2) and (M, 2) polylines if at most sqrt(``cap``), else ``inf``.

    The coupling table c[i, j] = max(|p_i - q_j|^2, min(c[i-1, j], c[i-1, j-1],
    c[i, j-1])) is filled row by row keeping one row; squared distances give the
    same coupling (the square root is monotone). A coupling through a pair of
    vertices more than sqrt(``cap``) apart has a larger distance, so such a cell
    is left out (infinite), and so is every cell no coupling reaches without
    one: each row is filled only from the first reachable cell of the row above
    to the last one reachable in it, a band along the diagonal a few cells wide
    where the two polylines run close together, instead of the whole table. The
    cells filled hold the whole table's values (maxima and minima of the same
    squared distances), so a result within the cap is the same number. A row
    with no cell left ends the computation: every coupling crosses every row.
    """
    n, m = p.shape[0], q.shape[0]
    row = np.empty(m)
    # Row 0: the running maximum, while within the cap. Cells lo..hi of a row are its band.
    acc = -1.0
    hi = -1
    for j in range(m):
        dx, dy = p[0, 0] - q[j, 0], p[0, 1] - q[j, 1]
        d2 = dx * dx + dy * dy
        if d2 > cap:
            break
        acc = max(acc, d2)
        row[j] = acc
        hi = j
    if hi < 0:
        return math.inf
    lo = 0
    for i in range(1, n):
        px, py = p[i, 0], p[i, 1]
        new_lo, new_hi = -1, -1
        diag = math.inf  # the row above at j - 1
        left = math.inf  # this row at j - 1
        for j in range(lo, m):
            up = row[j] if j <= hi else math.inf
            best = min(up, diag, left)
            diag = up
            if best == math.inf and j > hi:
                break  # past the row above's band and nothing from the left: no further cell is reached
            dx, dy = px - q[j, 0], py - q[j, 1]
            d2 = dx * dx + dy * dy
            if best == math.inf or d2 > cap:
                value = math.inf
            else:
                value = max(best, d2)
                if new_lo < 0:
                    new_lo = j
                new_hi = j
            row[j] = value
            left = value
        if new_lo < 0:
            return math.inf
        lo, hi = new_lo, new_hi
    if hi != m - 1:
        return math.inf
    return math.sqrt(row[m - 1])


@_jit
def _arc_samples(cx, cy, r, theta0, sweep, step, reverse):  # pragma: no cover - compiled
    """``Arc.sample(step)`` (ends included, at least 2 points), walked backwards if ``reverse``."""
    n = max(2, math.ceil(abs(sweep) * r / step) + 1)
    out = np.empty((n, 2))
    dt = 1.0 / (n - 1)
    for i in range(n):
        t = i * dt if i < n - 1 else 1.0  # np.linspace(0, 1, n)
        theta = theta0 + sweep * t
        k = n - 1 - i if reverse else i
        out[k, 0], out[k, 1] = cx + r * math.cos(theta), cy + r * math.sin(theta)
    return out


@_jit
def extract_arc_kernel(cx, cy, r, seg, junctions, theta, junction_tol, ratio, slack, step):  # pragma: no cover
    """The arc of ``arc_extraction.extract_arc`` (method "frechet") on arrays.

    Candidates between every two junctions (m, 2), at polar angles ``theta`` (m,)
    (numpy's ``arctan2``, which rounds unlike libm's), both ways round that contain
    all of them, those no longer than ``ratio`` x the chain's length + ``slack``
    px (else the shortest), both orientations, tried by increasing lower bound
    with the Fréchet computation cut at the best so far and at the smallest
    greedy coupling's distance (:func:`_greedy_coupling`).

    Returns
    -------
    (found, theta0, sweep, reverse, frechet, near_tol)
        The chosen candidate (theta0, sweep) and whether it is walked the other
        way; ``found`` is False when no candidate passes through all the junctions.
        ``near_tol``: a junction is at least half of ``junction_tol`` off the circle
        (the caller checks those against the tolerance itself, with numpy's rounding;
        on the rest, far within it, the check is spared).
    """
    m = junctions.shape[0]
    near_tol = False
    for u in range(m):
        if abs(math.hypot(junctions[u, 0] - cx, junctions[u, 1] - cy) - r) > 0.5 * junction_tol:
            near_tol = True
    tol = junction_tol / r  # radians
    cand = np.empty((max(1, m * (m - 1)), 2))
    n_cand = 0
    if math.hypot(junctions[0, 0] - junctions[m - 1, 0], junctions[0, 1] - junctions[m - 1, 1]) <= junction_tol:
        cand[0, 0], cand[0, 1] = theta[0], TAU  # a closed loop: the whole circle from the loop's node
        n_cand = 1
    else:
        arc = np.empty(5)
        arc[0], arc[1], arc[2] = cx, cy, r
        for a in range(m):
            for b in range(a + 1, m):
                sweep = _mod_tau(theta[b] - theta[a])
                if sweep <= tol or sweep >= TAU - tol:  # coincident junctions bound no arc
                    continue
                for side in range(2):
                    arc[3], arc[4] = theta[a], sweep if side == 0 else sweep - TAU
                    ok = True
                    for u in range(m):
                        if not _contains_angle(arc, theta[u], tol):
                            ok = False
                            break
                    if ok:
                        cand[n_cand, 0], cand[n_cand, 1] = arc[3], arc[4]
                        n_cand += 1
    if n_cand == 0:
        return False, 0.0, 0.0, False, math.inf, near_tol
    seg_length = 0.0
    for i in range(seg.shape[0] - 1):
        seg_length += math.hypot(seg[i + 1, 0] - seg[i, 0], seg[i + 1, 1] - seg[i, 1])
    cap = ratio * seg_length + slack
    kept = np.empty(n_cand, np.int64)
    n_kept = 0
    shortest = 0
    for c in range(n_cand):
        length = abs(cand[c, 1]) * r
        if length <= cap:
            kept[n_kept] = c
            n_kept += 1
        if length < abs(cand[shortest, 1]) * r:
            shortest = c
    if n_kept == 0:
        kept[0] = shortest
        n_kept = 1
    # Both orientations of each kept arc, by increasing lower bound (the coupled end points' distance).
    n_opt = 2 * n_kept
    lower = np.empty(n_opt)
    last = seg.shape[0] - 1
    for o in range(n_opt):
        c = kept[o // 2]
        t0, sw = cand[c, 0], cand[c, 1]
        sx, sy = cx + r * math.cos(t0 + sw * 0.0), cy + r * math.sin(t0 + sw * 0.0)
        ex, ey = cx + r * math.cos(t0 + sw * 1.0), cy + r * math.sin(t0 + sw * 1.0)
        if o % 2:
            sx, sy, ex, ey = ex, ey, sx, sy
        lower[o] = max(math.hypot(seg[0, 0] - sx, seg[0, 1] - sy), math.hypot(seg[last, 0] - ex, seg[last, 1] - ey))
    # A stable insertion sort (ties keep the candidates' order): a few options, and
    # numba's np.argsort costs seconds of compilation.
    order = np.arange(n_opt)
    for o in range(1, n_opt):
        v = order[o]
        u = o - 1
        while u >= 0 and lower[order[u]] > lower[v]:
            order[u + 1] = order[u]
            u -= 1
        order[u + 1] = v
    # Samples of each kept arc (a reversed option walks them backwards) and, per option, the
    # largest distance of a greedy coupling: the smallest of these bounds the winner's distance.
    samples = []
    reverse = []
    hint = math.inf
    for o in range(n_opt):
        c = kept[o // 2]
        if o % 2 == 0:
            length = abs(cand[c, 1]) * r
            samples.append(_arc_samples(cx, cy, r, cand[c, 0], cand[c, 1], step * max(1.0, length / cap), False))
            reverse.append(samples[-1][::-1].copy())
        hint = min(hint, _greedy_coupling(seg, samples[o // 2] if o % 2 == 0 else reverse[o // 2]))
    best, best_opt = math.inf, order[0]
    for o in order:
        if lower[o] >= best:
            break
        pts = samples[o // 2] if o % 2 == 0 else reverse[o // 2]
        # Within the best so far, and within the smallest greedy coupling: an option farther than
        # that is not the nearest one (the nearest is at most that far), so only a band of its
        # table is filled, not a whole table of a far option before the near one is found.
        value = _frechet_within(seg, pts, min(hint, best * best))
        if value < best:
            best, best_opt = value, o
    c = kept[best_opt // 2]
    return True, cand[c, 0], cand[c, 1], best_opt % 2 == 1, best, near_tol


# --------------------------------------------------------------------------------
# Tangent biarcs (img2logo.fit.biarcs.closest_biarcs): the fine search around the coarse grid's best
# --------------------------------------------------------------------------------


@_jit
def biarc_fine_kernel(chain, heads, tails, splits, counts, radii_a, radii_b, most):  # pragma: no cover - compiled
    """The best biarc of each pair's fine grid (``biarcs.closest_biarcs``): (distance px, s, a) per pair.

    For pair ``p``, split ``splits[p, s]`` (``s < counts[p]``) and turn ``a``, the
    head's pixels ``chain[:split + 1]`` go with the circle of centre ``heads[p, s, a]``
    and radius ``radii_a[p]``, the tail's ``chain[split:]`` with ``tails[p, s, a]``
    and ``radii_b[p]``; a biarc's distance is the largest distance of a pixel from
    its circle (:func:`img2logo._compiled.circle.farthest_from_circle`).
    Each pair's smallest over its grid and where, the first in row-major order on
    a tie. With ``most`` > 0 only the pairs that can be among the ``most`` smallest
    (the earlier pair first on a tie) are searched to the end: a pair's search
    starts from the ``most``-th smallest distance of the pairs before it, and a
    pair that finds nothing below it gets s = -1. A biarc's pixels stop being
    measured once it is known to be no better than the best so far (its largest
    distance can only grow).
    """
    n_pairs = heads.shape[0]
    worst_out = np.full(n_pairs, math.inf)
    s_out = np.full(n_pairs, -1, dtype=np.int64)
    a_out = np.full(n_pairs, -1, dtype=np.int64)
    top = np.full(max(most, 1), math.inf)  # the smallest distances found so far, increasing
    for p in range(n_pairs):
        best = top[most - 1] if most > 0 else math.inf
        best_s, best_a = -1, -1
        ra, rb = radii_a[p], radii_b[p]
        for s in range(counts[p]):
            head, tail = chain[: splits[p, s] + 1], chain[splits[p, s] :]
            for a in range(heads.shape[2]):
                worst = farthest_from_circle(head, heads[p, s, a, 0], heads[p, s, a, 1], ra, 0.0, best)
                if worst >= best:
                    continue
                worst = farthest_from_circle(tail, tails[p, s, a, 0], tails[p, s, a, 1], rb, worst, best)
                if worst < best:
                    best, best_s, best_a = worst, s, a
        if best_s < 0:
            continue
        worst_out[p], s_out[p], a_out[p] = best, best_s, best_a
        if most > 0:  # insert into the increasing list, the last one dropped
            k = most - 1
            while k > 0 and top[k - 1] > best:
                top[k] = top[k - 1]
                k -= 1
            top[k] = best
    return worst_out, s_out, a_out


@_jit
def _measure_on(points, centre, radius, worst, done, at, best):  # pragma: no cover - compiled
    """The largest distance of ``points`` from a circle, measured on from where a measure of it stopped, px.

    ``worst[at]`` is the largest of its first ``done[at]`` points' distances (both updated), below
    ``best``; the measure stops once it reaches ``best`` (:func:`img2logo._compiled.circle.measure_from_circle`).
    """
    far, more = measure_from_circle(points[done[at] :], centre[0], centre[1], radius, worst[at], best)
    worst[at] = far
    done[at] += more
    return far


@_jit
def biarc_coarse_kernel(chain, index, splits, heads, tails, radii_a, radii_b):  # pragma: no cover - compiled
    """The best biarc of the coarse grid for every pair of radii (``biarcs.biarc_coarse``): (ia, ib) -> (j, s, a).

    ``heads[ia, side_a, s, a]`` and ``tails[ib, side_b, s, a]`` are the centres
    of the head's circle of radius ``radii_a[ia]`` and the tail's of ``radii_b[ib]``
    (sides -1, +1) at split ``splits[s]`` and turn ``a``; of the pixels
    ``chain[index]`` (increasing) those up to the split go with the head's circle,
    those from it on with the tail's (the arithmetic of
    :func:`img2logo._compiled.circle.biarc_worst_kernel`). For each pair of radii,
    over j = 2 side_a + side_b, then the grid in row-major order, the smallest
    largest distance and where it is first reached. A biarc's pixels stop being
    measured once it is known to be no better than the best so far; a circle's
    largest distance measured so far, and where it stopped, are kept for the
    other pairs that share it (a head's circle serves every tail's and the
    reverse): measuring on from there gives the same maximum as from the start.
    """
    n_a, n_b = heads.shape[0], tails.shape[0]
    n_s, n_t = heads.shape[2], heads.shape[3]
    pixels = chain[index]
    # Each split's pixels up to it, from the chain's start; those from it on, from the chain's end.
    up_to = np.searchsorted(index, splits, side="right")
    from_on = np.searchsorted(index, splits, side="left")
    backwards = pixels[::-1].copy()
    head_worst = np.zeros((n_a, 2, n_s, n_t))
    head_done = np.zeros((n_a, 2, n_s, n_t), dtype=np.int64)  # how many of its pixels are measured
    tail_worst = np.zeros((n_b, 2, n_s, n_t))
    tail_done = np.zeros((n_b, 2, n_s, n_t), dtype=np.int64)
    out = np.zeros((n_a, n_b, 3), dtype=np.int64)
    for ia in range(n_a):
        ra = radii_a[ia]
        for ib in range(n_b):
            rb = radii_b[ib]
            best = math.inf
            best_j, best_s, best_a = 0, 0, 0
            for j in range(4):
                side_a, side_b = j // 2, j % 2
                for s in range(n_s):
                    head, tail = pixels[: up_to[s]], backwards[: len(pixels) - from_on[s]]
                    for a in range(n_t):
                        if head_worst[ia, side_a, s, a] >= best:  # known before measuring on: no call
                            continue
                        at = (ia, side_a, s, a)
                        worst = _measure_on(head, heads[at], ra, head_worst, head_done, at, best)
                        if worst >= best or tail_worst[ib, side_b, s, a] >= best:
                            continue
                        at = (ib, side_b, s, a)
                        tail_far = _measure_on(tail, tails[at], rb, tail_worst, tail_done, at, best)
                        if tail_far < best:
                            best, best_j, best_s, best_a = max(worst, tail_far), j, s, a
            out[ia, ib, 0], out[ia, ib, 1], out[ia, ib, 2] = best_j, best_s, best_a
    return out


@_jit
def nearest_on_chain_kernel(chain, qx, qy):  # pragma: no cover - compiled
    """The point of a pixel chain (n, 2) nearest to (qx, qy), px: (segment i, foot x, foot y, distance).

    ``tangency.split_chain``'s arithmetic: on each step ``chain[i]`` -> ``chain[i + 1]`` the foot of
    the perpendicular at its parameter clipped to [0, 1]; the first step of the smallest distance.
    """
    best, bi, bx, by = math.inf, 0, chain[0, 0], chain[0, 1]
    for i in range(chain.shape[0] - 1):
        ax, ay = chain[i, 0], chain[i, 1]
        vx, vy = chain[i + 1, 0] - ax, chain[i + 1, 1] - ay
        t = ((qx - ax) * vx + (qy - ay) * vy) / max(vx * vx + vy * vy, 1e-300)
        t = min(max(t, 0.0), 1.0)
        fx, fy = ax + t * vx, ay + t * vy
        d = math.hypot(qx - fx, qy - fy)
        if d < best:
            best, bi, bx, by = d, i, fx, fy
    return bi, bx, by, best
