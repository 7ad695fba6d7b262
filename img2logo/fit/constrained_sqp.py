"""The Python SQP of Eqn. 13 (Sec. 5.3): the problem in its free variables and the KKT solve.

:func:`img2logo.fit.constrained_fit.fit_constrained` solves Eqn. 13 by sequential
quadratic programming. Its local windows (a dense KKT system of at most
``KKT_DENSE_MAX`` unknowns) run compiled (:mod:`img2logo._compiled.kernels`); this module is
the same step in numpy, kept as the reference the kernels are tested against (the
global solves run compiled too, :func:`img2logo._compiled.sqp.sqp_banded`):

* :class:`Problem` holds Eqn. 13 in terms of the free variables x = (free
  centres, free junction displacements): E^l (Eqn. 7), the incidence residuals
  (Eqn. 8, 9) and the tangency residuals of the tangent joins, their Jacobian,
  and the Newton and Gauss-Newton KKT matrices.
* :func:`solve_kkt` solves one KKT system for the step and the multipliers (a
  large one, :class:`SparseKKT`, in a band by a compiled kernel: no scipy).

Coordinates are input-image pixels: x to the right, y downwards. Lengths are in px.
"""

from __future__ import annotations

from typing import NamedTuple, Protocol

import numpy as np

from .constants import KKT_DAMPING, KKT_DENSE_MAX

__all__ = ["Problem", "ProblemArrays", "SparseKKT", "solve_kkt"]


class SparseKKT(NamedTuple):
    """A KKT matrix above ``KKT_DENSE_MAX`` unknowns as its entries: ``M[rows, cols] += data``, (size, size)."""

    data: np.ndarray
    rows: np.ndarray
    cols: np.ndarray
    size: int

    def toarray(self) -> np.ndarray:
        """The dense (size, size) matrix (repeated entries summed)."""
        mat = np.zeros((self.size, self.size))
        np.add.at(mat, (self.rows, self.cols), self.data)
        return mat


def _norm(vx: np.ndarray, vy: np.ndarray) -> np.ndarray:
    # sqrt(x^2 + y^2): pixel coordinates cannot overflow, and np.hypot is ~5x slower.
    return np.sqrt(vx * vx + vy * vy)


class ProblemArrays(Protocol):
    """The arrays of Eqn. 13 that :class:`Problem` is made from.

    :class:`img2logo.fit.constrained_fit.WindowProblem` is one (its fields document
    them); a protocol, so that this module need not import that one (which imports it).
    """

    @property
    def points(self) -> np.ndarray: ...

    @property
    def owner(self) -> np.ndarray: ...

    @property
    def radii(self) -> np.ndarray: ...

    @property
    def centers(self) -> np.ndarray: ...

    @property
    def junctions(self) -> np.ndarray: ...

    @property
    def disp(self) -> np.ndarray: ...

    @property
    def incidence(self) -> np.ndarray: ...

    @property
    def free_c(self) -> np.ndarray: ...

    @property
    def free_j(self) -> np.ndarray: ...

    @property
    def ws(self) -> np.ndarray: ...

    @property
    def wj(self) -> float: ...

    @property
    def connectivity(self) -> bool: ...

    @property
    def tangents(self) -> np.ndarray: ...


class Problem:
    """Eqn. 13 in terms of the free variables x = (free centres, free displacements), of ``arrays``."""

    def __init__(self, arrays: ProblemArrays) -> None:
        a = arrays
        points, owner, radii, centers, junctions, disp = a.points, a.owner, a.radii, a.centers, a.junctions, a.disp
        incidence, free_c, free_j, ws, wj, connectivity = a.incidence, a.free_c, a.free_j, a.ws, a.wj, a.connectivity
        tangents = a.tangents
        self.radii, self.junctions, self.wj = radii, junctions, wj
        self.centers, self.disp = centers.copy(), disp.copy()
        self.free_c, self.free_j = free_c, free_j
        nc, nj = len(free_c), len(free_j)
        self.n = 2 * (nc + nj)
        # Positions of circles / junctions among the free ones (-1: fixed).
        pos_c = np.full(len(radii), -1)
        pos_c[free_c] = np.arange(nc)
        pos_j = np.full(len(junctions), -1)
        pos_j[free_j] = np.arange(nj)
        # Points of free circles vary (grouped by circle: every group is non-empty,
        # so sums per circle are np.add.reduceat); those of fixed circles add a constant.
        on_free = pos_c[owner] >= 0
        self.px, self.py = points[on_free, 0].copy(), points[on_free, 1].copy()
        self.counts = np.bincount(pos_c[owner[on_free]], minlength=nc)
        self.starts = (np.cumsum(self.counts) - self.counts).astype(np.intp)
        self.r_pts = np.repeat(radii[free_c], self.counts)
        self.pt_circle = np.repeat(free_c, self.counts)  # the circle of each point (free circles' points)
        self.w_pts = np.repeat(ws[free_c], self.counts)  # the segment weight of each point
        fixed_pts, fixed_own = points[~on_free], owner[~on_free]
        e = _norm(*(fixed_pts - centers[fixed_own]).T) - radii[fixed_own]
        fixed_j = np.ones(len(junctions), dtype=bool)
        fixed_j[free_j] = False
        self.f_const = float(np.sum(ws[fixed_own] * e * e)) + wj * float(np.sum(disp[fixed_j] ** 2))
        # Incidences: all are evaluated; those with a free variable are constraints.
        self.inc_i, self.inc_k = incidence[:, 0], incidence[:, 1]
        self.inc_p, self.inc_r = junctions[self.inc_k], radii[self.inc_i]  # constant: gathered once
        ci, ck = pos_c[self.inc_i], pos_j[self.inc_k]
        self.active = ((ci >= 0) | (ck >= 0)) if connectivity else np.zeros(len(incidence), dtype=bool)
        self.m_inc = int(self.active.sum())
        ci, ck = ci[self.active], ck[self.active]
        # Tangencies (circle a, circle b, junction k): all are evaluated; those with a
        # free variable are constraints, written after the incidences.
        tan = np.zeros((0, 3), dtype=np.int64) if tangents is None else tangents
        self.tan_a, self.tan_b, self.tan_k = tan[:, 0], tan[:, 1], tan[:, 2]
        # Scaled by 1 / max(r_a, r_b): cross(o_a - q, o_b - q) / max(r) = min(r) sin(angle
        # between the radii to q), px, like the incidences' residuals (see _tangency).
        self.tan_s = 1.0 / np.maximum(radii[self.tan_a], radii[self.tan_b]) if len(tan) else np.zeros(0)
        ta, tb, tk = pos_c[self.tan_a], pos_c[self.tan_b], pos_j[self.tan_k]
        self.tan_active = ((ta >= 0) | (tb >= 0) | (tk >= 0)) if connectivity else np.zeros(len(tan), dtype=bool)
        self.m_tan = int(self.tan_active.sum())
        self.m = self.m_inc + self.m_tan
        ta, tb, tk = ta[self.tan_active], tb[self.tan_active], tk[self.tan_active]
        # Sparsity pattern of the KKT matrix [[H, A^T], [A, -delta I]]: the 2x2 blocks
        # of H, the entries of A and A^T for free centres and displacements, the diagonal.
        blk = np.repeat(np.arange(0, self.n, 2), 4)
        blk_r, blk_c = blk + np.tile([0, 0, 1, 1], self.n // 2), blk + np.tile([0, 1, 0, 1], self.n // 2)
        rows_a = np.arange(self.m_inc)
        self.a_mask_c, self.a_mask_k = ci >= 0, ck >= 0
        a_rows = np.concatenate([np.repeat(rows_a[self.a_mask_c], 2), np.repeat(rows_a[self.a_mask_k], 2)])
        a_cols = np.concatenate(
            [(2 * ci[self.a_mask_c])[:, None] + [0, 1], (2 * (nc + ck[self.a_mask_k]))[:, None] + [0, 1]]
        ).ravel()
        # The tangency rows of A: entries for o_a, o_b and d_k where free (their
        # second-order blocks may repeat the incidences' entries: summed apart, see matrix).
        rows_t = self.m_inc + np.arange(self.m_tan)
        self.t_mask = (ta >= 0, tb >= 0, tk >= 0)
        t_blocks = (2 * ta, 2 * tb, 2 * (nc + tk))
        a_rows = np.concatenate([a_rows, *(np.repeat(rows_t[on], 2) for on in self.t_mask)])
        a_cols = np.concatenate(
            [a_cols, *((b[on][:, None] + [0, 1]).ravel() for b, on in zip(t_blocks, self.t_mask, strict=True))]
        )
        # (row block, column block, sign of J) of the Hessian of lam * cross(o_a - q, o_b - q):
        # J on (o_a, o_b) and (o_b, q), -J on (o_a, q), and their transposes (J^T = -J).
        pairs = []
        for (r, rm), (c, cm), sign in (
            ((t_blocks[0], self.t_mask[0]), (t_blocks[1], self.t_mask[1]), 1.0),
            ((t_blocks[0], self.t_mask[0]), (t_blocks[2], self.t_mask[2]), -1.0),
            ((t_blocks[1], self.t_mask[1]), (t_blocks[2], self.t_mask[2]), 1.0),
        ):
            on = rm & cm
            pairs.append((r[on], c[on], sign, on))
            pairs.append((c[on], r[on], -sign, on))
        self.t_hess = pairs
        # Second-order coupling blocks (o_i, d_k) of the constraint curvature, both free.
        self.both = self.a_mask_c & self.a_mask_k
        cb, kb = 2 * ci[self.both], 2 * (nc + ck[self.both])
        cpl_r = np.concatenate([(cb[:, None] + [0, 0, 1, 1]).ravel(), (kb[:, None] + [0, 0, 1, 1]).ravel()])
        cpl_c = np.concatenate([(kb[:, None] + [0, 1, 0, 1]).ravel(), (cb[:, None] + [0, 1, 0, 1]).ravel()])
        # Block (of H) of the centre and of the displacement in each constraint; -1: fixed.
        self.blk_ci = np.where(self.a_mask_c, ci, -1)
        self.blk_ck = np.where(self.a_mask_k, nc + ck, -1)
        diag_m = np.arange(self.n, self.n + self.m)
        self.kkt_rows = np.concatenate([blk_r, self.n + a_rows, a_cols, cpl_r, diag_m])
        self.kkt_cols = np.concatenate([blk_c, a_cols, self.n + a_rows, cpl_c, diag_m])

    def set_x(self, x: np.ndarray) -> None:
        nc = len(self.free_c)
        self.centers[self.free_c] = x[: 2 * nc].reshape(-1, 2)
        self.disp[self.free_j] = x[2 * nc :].reshape(-1, 2)

    def get_x(self) -> np.ndarray:
        return np.concatenate([self.centers[self.free_c].ravel(), self.disp[self.free_j].ravel()])

    def constraints(self) -> tuple[np.ndarray, np.ndarray]:
        """All incidence residuals ``|o_i - (p_k + d_k)| - r_i`` (M,) and vectors v (M, 2)."""
        v = self.centers[self.inc_i] - self.inc_p - self.disp[self.inc_k]
        return _norm(v[:, 0], v[:, 1]) - self.inc_r, v

    def tangency(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """All tangency residuals (T,), px, and the vectors a = o_a - q, b = o_b - q (T, 2).

        The residual is ``cross(a, b) / max(r_a, r_b)``: with q on both circles
        (the incidences) it is ``min(r) sin(theta)``, theta the angle between the
        radii to q, zero exactly when q is on the line of centres, i.e. when the
        circles touch at q (centre distance |r_a - r_b| or r_a + r_b). Bilinear in
        the unknowns (a constant Hessian), well scaled in px for any radii, and
        regular where the two circles coincide (same radius, same side), unlike
        the distance of q from the line of centres.
        """
        q = self.junctions[self.tan_k] + self.disp[self.tan_k]
        a = self.centers[self.tan_a] - q
        b = self.centers[self.tan_b] - q
        return (a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]) * self.tan_s, a, b

    def violation(self) -> float:
        """The largest |residual| of every incidence and tangency, px."""
        return max(
            float(np.max(np.abs(self.constraints()[0]), initial=0.0)),
            float(np.max(np.abs(self.tangency()[0]), initial=0.0)),
        )

    def objective(self) -> tuple[float, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """E^l (Eqn. 7); point residuals, vectors o - p (x, y) and distances of free circles."""
        # Array methods, not np.sum & co.: the same reductions without the dispatch (this runs ~10^4 times a run).
        vx = self.centers[self.pt_circle, 0] - self.px
        vy = self.centers[self.pt_circle, 1] - self.py
        dist = _norm(vx, vy)
        e = dist - self.r_pts
        d = self.disp[self.free_j]
        return self.f_const + float((self.w_pts * e * e).sum()) + self.wj * float((d * d).sum()), e, vx, vy, dist

    def merit(self, nu: float) -> float:
        """The L1 merit function E^l + nu * sum |c| over the constraints."""
        out = self.objective()[0] + nu * float(np.abs(self.constraints()[0][self.active]).sum())
        if self.m_tan:
            out += nu * float(np.abs(self.tangency()[0][self.tan_active]).sum())
        return out

    def linearize(self) -> tuple[float, np.ndarray, np.ndarray, float]:
        """E^l, its gradient g, active constraint values c, and the violation (max |c| over all).

        Keeps the unit vectors and residuals that :meth:`matrix` needs.
        """
        nj = len(self.free_j)
        f, e, vx, vy, dist = self.objective()
        safe = np.where(dist > 0, dist, 1.0)
        ux, uy = np.where(dist > 0, vx / safe, 1.0), vy / safe
        self._pt = (ux, uy, e / safe)
        g = np.concatenate(
            [
                np.stack([self._gsum(e * ux), self._gsum(e * uy)], axis=1).ravel(),
                (2.0 * self.wj * self.disp[self.free_j]).ravel(),
            ]
        )
        self._gn = np.concatenate(
            [
                np.stack([self._gsum(ux * ux), self._gsum(ux * uy), self._gsum(ux * uy), self._gsum(uy * uy)], axis=1),
                np.tile([2.0 * self.wj, 0.0, 0.0, 2.0 * self.wj], (nj, 1)),
            ]
        )
        c_all, vc = self.constraints()
        c, vc = c_all[self.active], vc[self.active]
        dc = _norm(vc[:, 0], vc[:, 1])
        dsafe = np.where(dc > 0, dc, 1.0)
        self._uc = np.stack([np.where(dc > 0, vc[:, 0] / dsafe, 1.0), vc[:, 1] / dsafe], axis=1)
        self._dc = dsafe
        violation = float(np.abs(c_all).max(initial=0.0))
        if len(self.tan_s):
            t_all, ta, tb = self.tangency()
            violation = max(violation, float(np.max(np.abs(t_all))))
            on, s = self.tan_active, self.tan_s[self.tan_active, None]
            # d c / d o_a = s J b, d c / d o_b = s J^T a, d c / d d_k = -(both); J = [[0, 1], [-1, 0]].
            ga = s * np.column_stack([tb[on, 1], -tb[on, 0]])
            gb = s * np.column_stack([-ta[on, 1], ta[on, 0]])
            self._ta = (ga, gb, -(ga + gb))
            c = np.concatenate([c, t_all[on]])
        return f, g, c, violation

    def _gsum(self, values: np.ndarray) -> np.ndarray:
        """2 * the segment-weighted sum of ``values`` over each free circle's points."""
        return 2.0 * np.add.reduceat(self.w_pts * values, self.starts) if len(self.starts) else np.zeros(0)

    def matrix(self, lam: np.ndarray | None) -> tuple[SparseKKT | np.ndarray, float]:
        """The damped KKT matrix at the last :meth:`linearize`, and the damping delta.

        ``lam=None`` gives the Gauss-Newton matrix J^T J; with multipliers it is the
        Hessian of the Lagrangian E^l + lam^T c (residual and constraint curvature).
        """
        h = self._gn.copy()  # rows: the 2x2 blocks (xx, xy, yx, yy) of the free variables
        scale = max(float(h.max(initial=0.0)), 1e-300)
        h[:, 0] += KKT_DAMPING * scale
        h[:, 3] += KKT_DAMPING * scale
        cpl = np.zeros((int(self.both.sum()), 4))
        if lam is not None:
            # Residual curvature: 2 w sum (e / |o - p|) (I - u u^T) for each centre.
            ux, uy, q = self._pt
            qxy = self._gsum(q * ux * uy)
            h[: len(self.starts)] += np.stack([self._gsum(q * uy * uy), -qxy, -qxy, self._gsum(q * ux * ux)], axis=1)
            # Constraint curvature: lam (I - u u^T) / |v| on o_i and d_k, minus it between them.
            ux, uy = self._uc[:, 0], self._uc[:, 1]
            s = lam[: self.m_inc] / self._dc
            k = np.stack([s * uy * uy, -s * ux * uy, -s * ux * uy, s * ux * ux], axis=1)
            for blk in (self.blk_ci, self.blk_ck):
                on = blk >= 0
                np.add.at(h, blk[on], k[on])
            cpl = -k[self.both]
        a_vals = np.concatenate([self._uc[self.a_mask_c].ravel(), -self._uc[self.a_mask_k].ravel()])
        if self.m_tan:
            a_vals = np.concatenate([a_vals, *(v[on].ravel() for v, on in zip(self._ta, self.t_mask, strict=True))])
        delta = KKT_DAMPING / scale
        cpl = cpl.ravel()
        data = np.concatenate([h.ravel(), a_vals, a_vals, cpl, cpl, np.full(self.m, -delta)])
        size = self.n + self.m
        extra = self._tangency_curvature(lam) if lam is not None and self.m_tan else None
        if size <= KKT_DENSE_MAX:
            mat = np.zeros((size, size))
            mat[self.kkt_rows, self.kkt_cols] = data
            if extra is not None:
                np.add.at(mat, (extra[1], extra[2]), extra[0])
            return mat, delta
        if extra is None:
            return SparseKKT(data, self.kkt_rows, self.kkt_cols, size), delta
        rows, cols = np.concatenate([self.kkt_rows, extra[1]]), np.concatenate([self.kkt_cols, extra[2]])
        return SparseKKT(np.concatenate([data, extra[0]]), rows, cols, size), delta

    def _tangency_curvature(self, lam: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The entries (values, rows, columns) of sum_t lam_t s_t Hess(cross): +-J blocks between the variables."""
        lt = lam[self.m_inc :] * self.tan_s[self.tan_active]
        vals, rows, cols = [], [], []
        for r, c, sign, on in self.t_hess:
            w = sign * lt[on]
            # J = [[0, 1], [-1, 0]]: entries (x, y) = +w and (y, x) = -w of the 2x2 block.
            vals += [w, -w]
            rows += [r, r + 1]
            cols += [c + 1, c]
        return np.concatenate(vals), np.concatenate(rows), np.concatenate(cols)


def solve_kkt(
    mat: SparseKKT | np.ndarray,
    delta: float,
    g: np.ndarray,
    c: np.ndarray,
    keep: np.ndarray | None = None,
) -> tuple[np.ndarray, np.ndarray, float] | None:
    """Solve the KKT system for (dx, lambda); also return the curvature dx^T W dx (None: failed).

    ``keep`` (indices into the unknowns) solves the system reduced to them; the
    others (coordinates held on a mirror axis) get a zero step. A dense matrix is
    solved by LAPACK (``np.linalg.solve``); a large sparse one (a global solve) by
    Gaussian elimination with partial pivoting in a band after a reverse
    Cuthill-McKee ordering (:func:`_solve_sparse`).
    """
    rhs = np.concatenate([-g, -c])
    part = rhs if keep is None else rhs[keep]
    if isinstance(mat, np.ndarray):
        dense = mat if keep is None else mat[np.ix_(keep, keep)]
        try:
            part = np.linalg.solve(dense, part)
        except np.linalg.LinAlgError:
            return None
    else:
        part = _solve_sparse(mat, part, keep)
        if part is None:
            return None
    if not np.isfinite(part).all():
        return None
    if keep is None:
        sol = part
    else:
        sol = np.zeros(len(rhs))
        sol[keep] = part
    n = len(g)
    dx, lam = sol[:n], sol[n:]
    # From the first block row W dx = -g - A^T lam and A dx - delta lam = -c.
    curvature = -float((g * dx).sum()) + float((lam * c).sum()) - delta * float((lam * lam).sum())
    return dx, lam, curvature


def _solve_sparse(mat: SparseKKT, rhs: np.ndarray, keep: np.ndarray | None) -> np.ndarray | None:
    """The solution of the sparse KKT system (reduced to ``keep``), None where it is exactly singular.

    The compiled band solver (:func:`img2logo._compiled.graph.banded_solve_kernel`):
    the system of a global solve is hundreds of unknowns with a band of about 20
    after reordering, which it solves in well under a millisecond, and a run
    imports neither ``scipy.sparse`` nor ``scipy.linalg`` (about 0.4 s of CPU)
    for scipy's SuperLU. The two agree to rounding (about 1e-11 relative on the
    giraffe's 155 global steps; the tests compare them).
    """
    from .._compiled import kernels

    rows, cols, data = mat.rows, mat.cols, mat.data
    if keep is not None:
        new = np.full(mat.size, -1, dtype=np.int64)
        new[keep] = np.arange(len(keep))
        rows, cols = new[rows], new[cols]
        on = (rows >= 0) & (cols >= 0)
        rows, cols, data = rows[on], cols[on], data[on]
    out = np.empty(len(rhs))
    if kernels.banded_solve_kernel(
        np.ascontiguousarray(rows, dtype=np.int64), np.ascontiguousarray(cols, dtype=np.int64), data, rhs, out
    ):
        return None
    return out
