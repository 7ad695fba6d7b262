"""The KKT systems of the compiled SQP of Eqn. 13: a dense solve by LU, the pattern of a banded one.

:func:`lu_solve` solves a local window's dense KKT system by LU with partial pivoting;
:func:`kkt_pattern` lists the entries of the KKT matrix in the Python reference's order, for a global
solve in a band (:func:`img2logo._compiled.graph.banded_solve_ordered`). Used by :mod:`img2logo._compiled.sqp`.

Written in the subset of Python that numba compiles; loaded through :mod:`img2logo._compiled.kernels`.
"""

from __future__ import annotations

import numpy as np

from .jit import jit as _jit


@_jit
def lu_solve(a, b):  # pragma: no cover - compiled
    """Solve a x = b in place by Gaussian elimination with partial pivoting; False on an exactly zero pivot."""
    n = a.shape[0]
    for k in range(n):
        p = k
        best = abs(a[k, k])
        for i in range(k + 1, n):
            v = abs(a[i, k])
            if v > best:
                best, p = v, i
        if best == 0.0:
            return False
        if p != k:
            for j in range(n):
                a[k, j], a[p, j] = a[p, j], a[k, j]
            b[k], b[p] = b[p], b[k]
        piv = a[k, k]
        for i in range(k + 1, n):
            f = a[i, k] / piv
            if f != 0.0:
                for j in range(k + 1, n):
                    a[i, j] -= f * a[k, j]
                b[i] -= f * b[k]
    for i in range(n - 1, -1, -1):
        s = b[i]
        for j in range(i + 1, n):
            s -= a[i, j] * b[j]
        b[i] = s / a[i, i]
    return True


@_jit
def kkt_pattern(n, nc, m_inc, m_tan, act_rows, inc_i, inc_k, pos_c, pos_j, tan_rows, tan_a, tan_b, tan_k, keep):
    """The entries (rows, cols) of the KKT matrix, in the order of the Python reference's (``Problem``).

    The 2x2 blocks of H, the entries of A (centres, then displacements, then the
    tangencies' o_a, o_b, d_k), those of A^T, the coupling blocks (o_i, d_k) and
    (d_k, o_i) of the constraint curvature, the diagonal of the multipliers, then
    the tangencies' curvature blocks; reduced to the unknowns ``keep`` and
    renumbered. An entry repeated (a tangency's curvature on a coupling block)
    is listed each time, as the reference lists it; ``first`` marks the first.
    """
    size = n + m_inc + m_tan
    cap = 4 * (n // 2) + 4 * 2 * (2 * m_inc + 6 * m_tan) + 8 * m_inc + (m_inc + m_tan) + 24 * m_tan
    rows = np.empty(cap, np.int64)
    cols = np.empty(cap, np.int64)
    e = 0
    for b in range(n // 2):
        for u in range(4):
            rows[e], cols[e] = 2 * b + u // 2, 2 * b + u % 2
            e += 1
    a0 = e
    for q in range(m_inc):
        ci = pos_c[inc_i[act_rows[q]]]
        if ci >= 0:
            for u in range(2):
                rows[e], cols[e] = n + q, 2 * ci + u
                e += 1
    for q in range(m_inc):
        ck = pos_j[inc_k[act_rows[q]]]
        if ck >= 0:
            for u in range(2):
                rows[e], cols[e] = n + q, 2 * (nc + ck) + u
                e += 1
    for v in range(3):
        for q in range(m_tan):
            t = tan_rows[q]
            blk = pos_c[tan_a[t]] if v == 0 else (pos_c[tan_b[t]] if v == 1 else pos_j[tan_k[t]])
            if blk >= 0:
                if v == 2:
                    blk += nc
                for u in range(2):
                    rows[e], cols[e] = n + m_inc + q, 2 * blk + u
                    e += 1
    a1 = e
    for f in range(a0, a1):
        rows[e], cols[e] = cols[f], rows[f]
        e += 1
    for side in range(2):
        for q in range(m_inc):
            ci, ck = pos_c[inc_i[act_rows[q]]], pos_j[inc_k[act_rows[q]]]
            if ci >= 0 and ck >= 0:
                cb, kb = 2 * ci, 2 * (nc + ck)
                rb, lb = (cb, kb) if side == 0 else (kb, cb)
                for u in range(4):
                    rows[e], cols[e] = rb + u // 2, lb + u % 2
                    e += 1
    for q in range(m_inc + m_tan):
        rows[e], cols[e] = n + q, n + q
        e += 1
    for pr in range(3):
        for side in range(2):
            for half in range(2):
                for q in range(m_tan):
                    t = tan_rows[q]
                    ba, bb = pos_c[tan_a[t]], pos_c[tan_b[t]]
                    bk = nc + pos_j[tan_k[t]] if pos_j[tan_k[t]] >= 0 else -1
                    r, c = (ba, bb) if pr == 0 else ((ba, bk) if pr == 1 else (bb, bk))
                    if r >= 0 and c >= 0:
                        if side == 1:
                            r, c = c, r
                        rows[e], cols[e] = 2 * r + half, 2 * c + 1 - half
                        e += 1
    new = -np.ones(size, np.int64)
    for a in range(keep.shape[0]):
        new[keep[a]] = a
    seen = np.zeros((keep.shape[0], keep.shape[0]), np.bool_)
    out_r, out_c = np.empty(e, np.int64), np.empty(e, np.int64)
    full_r, full_c = np.empty(e, np.int64), np.empty(e, np.int64)
    first = np.zeros(e, np.bool_)
    k = 0
    for f in range(e):
        r, c = new[rows[f]], new[cols[f]]
        if r >= 0 and c >= 0:
            out_r[k], out_c[k] = r, c
            full_r[k], full_c[k] = rows[f], cols[f]
            if not seen[r, c]:
                seen[r, c] = True
                first[k] = True
            k += 1
    return out_r[:k].copy(), out_c[:k].copy(), full_r[:k].copy(), full_c[:k].copy(), first[:k].copy()
