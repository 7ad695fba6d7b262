"""Compiled kernels of the graph steps that used to load scipy: shortest paths and the global KKT solve.

* :func:`dijkstra_kernel` is the multi-source Dijkstra of ``scipy.sparse.csgraph.dijkstra``
  (``min_only=True``, a directed graph in CSR form) with the same order of the scanned
  nodes, so that where two paths are equally short it keeps the same one: the skeleton's
  traced chains (:mod:`img2logo.images.skeleton`) are scipy's pixel for pixel.
* :func:`banded_solve_kernel` solves a sparse square system (the damped KKT system of a
  global solve, :func:`img2logo.fit.constrained_sqp.solve_kkt`, hundreds of unknowns) by
  Gaussian elimination with partial pivoting in a band, after a reverse Cuthill-McKee
  ordering: a KKT system of the segment graph has a band of about 20 there
  (measured on the clip-art fish and giraffe: 147-588 unknowns, bandwidth 16-23), so the
  elimination is about n * 3 * bw^2 operations, less than scipy's SuperLU's set-up.

Importing ``scipy.sparse`` (through its array-API layer, which touches all of numpy's
lazy submodules) and ``scipy.sparse.linalg`` (which imports ``scipy.linalg``) cost a
run about 0.4 s of CPU before its work; these kernels are the reason a clip art's run
imports no scipy at all.

Written in the subset of Python that numba compiles; loaded through
:mod:`img2logo._compiled.kernels` (ahead of time, or numba's JIT as a fallback), never
imported by the pipeline directly.
"""

from __future__ import annotations

import numpy as np

from .circle import fit_circle_kernel
from .jit import jit as _jit


@_jit
def _before(da, ia, db, ib):  # pragma: no cover - compiled
    """Whether heap entry (distance da, node ia) comes out before (db, ib): nearer first, then the larger node."""
    return da < db or (da == db and ia > ib)


@_jit
def _push(hd, hi, size, d, i):  # pragma: no cover - compiled
    """Push (d, i) on the binary heap of ``size`` entries (hd, hi); the new size."""
    k = size
    while k > 0:
        up = (k - 1) // 2
        if not _before(d, i, hd[up], hi[up]):
            break
        hd[k] = hd[up]
        hi[k] = hi[up]
        k = up
    hd[k] = d
    hi[k] = i
    return size + 1


@_jit
def _pop(hd, hi, size):  # pragma: no cover - compiled
    """Remove the first entry (hd[0], hi[0]) of the heap of ``size`` entries; the new size."""
    size -= 1
    d = hd[size]
    i = hi[size]
    k = 0
    while True:
        c = 2 * k + 1
        if c >= size:
            break
        if c + 1 < size and _before(hd[c + 1], hi[c + 1], hd[c], hi[c]):
            c += 1
        if not _before(hd[c], hi[c], d, i):
            break
        hd[k] = hd[c]
        hi[k] = hi[c]
        k = c
    hd[k] = d
    hi[k] = i
    return size


@_jit
def dijkstra_kernel(indptr, indices, weights, sources, dist, pred):  # pragma: no cover - compiled
    """Shortest distances from the nearest of ``sources`` over a CSR graph, with scipy's choice among equal paths.

    Parameters
    ----------
    indptr, indices : ndarray of int64, shapes (N + 1,) and (E,)
        The graph in CSR form: the edges of node i go to ``indices[indptr[i]:indptr[i + 1]]``.
    weights : ndarray of float64, shape (E,)
        Their non-negative lengths.
    sources : ndarray of int64, shape (S,)
        The start nodes.
    dist : ndarray of float64, shape (N,)
        Out: the distance to the nearest source (inf where none reaches).
    pred : ndarray of int64, shape (N,)
        Out: the predecessor on that path (-9999 at the sources and where none reaches).

    Returns
    -------
    int
        0. ``dist`` and ``pred`` are ``scipy.sparse.csgraph.dijkstra(graph,
        indices=sources, min_only=True, return_predecessors=True)``'s first two
        (scipy >= 1.15): a node is scanned once, nearest first and, among equally
        near ones, the larger index first (scipy's priority queue of (-distance,
        node) pairs); a node's predecessor changes only for a strictly shorter path.
        Which path wins a tie therefore depends on the graph alone, not on the
        order of its edges.
    """
    n = len(dist)
    for k in range(n):
        dist[k] = np.inf
        pred[k] = -9999
    cap = len(sources) + len(indices) + 1  # every push but the sources' is a strict improvement along an edge
    hd = np.empty(cap)
    hi = np.empty(cap, dtype=np.int64)
    size = 0
    for s in sources:
        dist[s] = 0.0
        size = _push(hd, hi, size, 0.0, s)
    while size > 0:
        d = hd[0]
        v = hi[0]
        size = _pop(hd, hi, size)
        if dist[v] < d:
            continue  # a stale entry: v was reached by a shorter path since
        for e in range(indptr[v], indptr[v + 1]):
            j = indices[e]
            next_val = d + weights[e]
            if dist[j] > next_val:
                dist[j] = next_val
                size = _push(hd, hi, size, next_val, j)
                pred[j] = v
    return 0


@_jit
def _cuthill_mckee(n, rows, cols):  # pragma: no cover - compiled
    """A reverse Cuthill-McKee order of the symmetrized pattern (rows, cols): position -> unknown."""
    deg = np.zeros(n, dtype=np.int64)
    for e in range(len(rows)):
        if rows[e] != cols[e]:
            deg[rows[e]] += 1
            deg[cols[e]] += 1
    ptr = np.zeros(n + 1, dtype=np.int64)
    for i in range(n):
        ptr[i + 1] = ptr[i] + deg[i]
    fill = ptr[:-1].copy()
    adj = np.empty(ptr[n], dtype=np.int64)
    for e in range(len(rows)):
        r, c = rows[e], cols[e]
        if r != c:
            adj[fill[r]] = c
            fill[r] += 1
            adj[fill[c]] = r
            fill[c] += 1
    order = np.empty(n, dtype=np.int64)
    seen = np.zeros(n, dtype=np.bool_)
    by_degree = np.argsort(deg, kind="mergesort")  # lowest degree first, ties by index
    head = 0
    tail = 0
    for start in by_degree:
        if seen[start]:
            continue
        seen[start] = True
        order[tail] = start
        tail += 1
        while head < tail:
            v = order[head]
            head += 1
            first = tail
            for e in range(ptr[v], ptr[v + 1]):
                w = adj[e]
                if not seen[w]:
                    seen[w] = True
                    order[tail] = w
                    tail += 1
            # The new neighbours by increasing degree (insertion sort: a handful each).
            for a in range(first + 1, tail):
                w = order[a]
                b = a - 1
                while b >= first and deg[order[b]] > deg[w]:
                    order[b + 1] = order[b]
                    b -= 1
                order[b + 1] = w
    return order[::-1].copy()


@_jit
def banded_solve_kernel(rows, cols, vals, rhs, x):  # pragma: no cover - compiled
    """Solve the sparse system sum over entries ``A[rows, cols] += vals``, ``A x = rhs``, in a band.

    Parameters
    ----------
    rows, cols : ndarray of int64, shape (E,)
        The entries' positions in the n x n matrix (n = ``len(rhs)``); repeated
        positions are summed.
    vals : ndarray of float64, shape (E,)
        Their values.
    rhs : ndarray of float64, shape (n,)
        The right-hand side.
    x : ndarray of float64, shape (n,)
        Out: the solution.

    Returns
    -------
    int
        0, or 1 where a pivot is exactly zero (a singular matrix, as SuperLU's
        "Factor is exactly singular").

    Notes
    -----
    The unknowns are renumbered by reverse Cuthill-McKee; the elimination keeps the
    band (kl below, ku above the diagonal) and its growth by row exchanges (kl
    more above), as LAPACK's ``gbtrf`` does.
    """
    return banded_solve_ordered(_cuthill_mckee(len(rhs), rows, cols), rows, cols, vals, rhs, x)


@_jit
def banded_solve_ordered(order, rows, cols, vals, rhs, x):  # pragma: no cover - compiled
    """:func:`banded_solve_kernel` in a given order of the unknowns (position -> unknown).

    For a sequence of systems of one pattern (the steps of a global solve, in
    :func:`img2logo._compiled.sqp.sqp_banded`): the order is found once.
    """
    n = len(rhs)
    pos = np.empty(n, dtype=np.int64)
    for i in range(n):
        pos[order[i]] = i
    kl = 0
    ku = 0
    for e in range(len(rows)):
        d = pos[cols[e]] - pos[rows[e]]
        if d > ku:
            ku = d
        if -d > kl:
            kl = -d
    width = 2 * kl + ku + 1
    band = np.zeros((n, width))  # A[i, j] at band[i, j - i + kl]
    for e in range(len(rows)):
        i = pos[rows[e]]
        band[i, pos[cols[e]] - i + kl] += vals[e]
    b = np.empty(n)
    for i in range(n):
        b[i] = rhs[order[i]]
    for k in range(n):
        last_row = min(n - 1, k + kl)
        last_col = min(n - 1, k + kl + ku)
        p = k
        big = abs(band[k, kl])
        for i in range(k + 1, last_row + 1):
            a = abs(band[i, k - i + kl])
            if a > big:
                big = a
                p = i
        if big == 0.0:
            return 1
        if p != k:
            for j in range(k, last_col + 1):
                t = band[k, j - k + kl]
                band[k, j - k + kl] = band[p, j - p + kl]
                band[p, j - p + kl] = t
            t = b[k]
            b[k] = b[p]
            b[p] = t
        pivot = band[k, kl]
        for i in range(k + 1, last_row + 1):
            f = band[i, k - i + kl] / pivot
            if f != 0.0:
                band[i, k - i + kl] = 0.0
                for j in range(k + 1, last_col + 1):
                    band[i, j - i + kl] -= f * band[k, j - k + kl]
                b[i] -= f * b[k]
    y = np.empty(n)
    for k in range(n - 1, -1, -1):
        s = b[k]
        for j in range(k + 1, min(n - 1, k + kl + ku) + 1):
            s -= band[k, j - k + kl] * y[j]
        y[k] = s / band[k, kl]
    for i in range(n):
        x[order[i]] = y[i]
    return 0


@_jit
def end_tangents_kernel(points, starts, stops, at_start, length, radius_factor):  # pragma: no cover - compiled
    """``segment_graph.end_tangent`` of many segment ends: (M, 2) unit tangents into the segments.

    Segment m is ``points[starts[m]:stops[m]]`` (px), its end the first point
    when ``at_start[m]``, else the last (the points taken backwards). As the
    Python function: the points within ``length`` px of arc length of the end
    (the cumulative hypot of the steps, added in order; at least 2), their
    circle (:func:`img2logo._compiled.circle.fit_circle_kernel`, the fit
    ``fit_circle(..., refine=False)`` runs), the tangent at the end point
    oriented along the chord, or the chord where no circle or a capped one.
    """
    out = np.empty((len(starts), 2))
    for m in range(len(starts)):
        a, b = starts[m], stops[m]
        n = b - a
        near = np.empty((n, 2))
        for i in range(n):
            k = a + i if at_start[m] else b - 1 - i
            near[i, 0] = points[k, 0]
            near[i, 1] = points[k, 1]
        cum = 0.0
        count = 1  # the points whose length from the end is <= length: the first always (0)
        for i in range(1, n):
            cum = cum + np.hypot(near[i, 0] - near[i - 1, 0], near[i, 1] - near[i - 1, 1])
            if cum <= length:
                count = i + 1
            else:
                break
        count = max(count, 2)
        chord0 = near[count - 1, 0] - near[0, 0]
        chord1 = near[count - 1, 1] - near[0, 1]
        use_chord = True
        if count >= 3:
            status, cx, cy, _radius, _rms, capped = fit_circle_kernel(near[:count].copy(), 0.0, radius_factor)
            if status == 0 and not capped:
                use_chord = False
                t0 = -(near[0, 1] - cy)
                t1 = near[0, 0] - cx
                if t0 * chord0 + t1 * chord1 < 0:
                    t0 = -t0
                    t1 = -t1
                norm = max(np.hypot(t0, t1), 1e-300)
                out[m, 0] = t0 / norm
                out[m, 1] = t1 / norm
        if use_chord:
            norm = max(np.hypot(chord0, chord1), 1e-300)
            out[m, 0] = chord0 / norm
            out[m, 1] = chord1 / norm
    return out
