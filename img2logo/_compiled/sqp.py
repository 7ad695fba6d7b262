"""Compiled kernels of the constrained fit of Eqn. 13 (the SQP of a local window or a global solve), on plain arrays.

The progressive optimization (Sec. 5) evaluates hundreds of merge candidates,
each a windowed least-squares problem of 10-60 unknowns: the arithmetic is
microseconds, the interpreter around small numpy arrays was the cost.
:func:`sqp_dense` does the same arithmetic as its Python reference
(:mod:`img2logo.fit.constrained_sqp`, the one that documents the method) in compiled
loops: residuals, Jacobian, the KKT matrix, its solve by LU with partial
pivoting (:func:`sqp_dense`, a local window) or in a band (:func:`sqp_banded`, a
global solve of hundreds of unknowns), the line search on the L1 merit.

Written in the subset of Python that numba compiles; loaded through
:mod:`img2logo._compiled.kernels` (ahead of time, or numba's JIT as a fallback), never
imported by the pipeline directly. Coordinates follow :mod:`img2logo.geometry.primitives`:
px, x right, y down.
"""

from __future__ import annotations

import math

import numpy as np

from .graph import _cuthill_mckee, banded_solve_ordered
from .jit import jit as _jit
from .kkt import kkt_pattern, lu_solve
from .sqp_terms import max_abs, set_x, sqp_constraints, sqp_objective, sqp_tangency, trial_step

# --------------------------------------------------------------------------------
# The constrained fit (Eqn. 13), dense KKT systems
# --------------------------------------------------------------------------------


@_jit
def sqp_dense(
    points,
    owner,
    radii,
    centers,
    junctions,
    disp,
    incidence,
    free_c,
    free_j,
    ws,
    wj,
    connectivity,
    tangents,
    tan_s_all,
    held,
    tol,
    max_iter,
    stall,
    ftol,
    damping,
):  # pragma: no cover - compiled
    """The SQP solve of Eqn. 13 with a dense KKT system (a local window); see :func:`_sqp`."""
    return _sqp(
        points, owner, radii, centers, junctions, disp, incidence, free_c, free_j, ws, wj, connectivity, tangents,
        tan_s_all, held, tol, max_iter, stall, ftol, damping, False,
    )  # fmt: skip


@_jit
def sqp_banded(
    points,
    owner,
    radii,
    centers,
    junctions,
    disp,
    incidence,
    free_c,
    free_j,
    ws,
    wj,
    connectivity,
    tangents,
    tan_s_all,
    held,
    tol,
    max_iter,
    stall,
    ftol,
    damping,
):  # pragma: no cover - compiled
    """The SQP solve of Eqn. 13 with the KKT system solved in a band (a global solve); see :func:`_sqp`."""
    return _sqp(
        points, owner, radii, centers, junctions, disp, incidence, free_c, free_j, ws, wj, connectivity, tangents,
        tan_s_all, held, tol, max_iter, stall, ftol, damping, True,
    )  # fmt: skip


@_jit
def _sqp(
    points,
    owner,
    radii,
    centers,
    junctions,
    disp,
    incidence,
    free_c,
    free_j,
    ws,
    wj,
    connectivity,
    tangents,
    tan_s_all,
    held,
    tol,
    max_iter,
    stall,
    ftol,
    damping,
    banded,
):  # pragma: no cover - compiled
    """The SQP solve of Eqn. 13; ``centers`` and ``disp`` are updated in place.

    The same method, step for step, as the Python reference in
    :mod:`img2logo.fit.constrained_fit` (see :func:`~img2logo.fit.constrained_fit.fit_constrained`):
    a Newton step on the Lagrangian once multipliers are known, Gauss-Newton
    before or when that step lacks positive curvature; the damped KKT system
    ``[[W + mu I, A^T], [A, -delta I]]`` solved by LU with partial pivoting; a
    backtracking line search on the L1 merit. With ``banded`` (a global solve of
    hundreds of unknowns) the system is solved as the reference solves a large
    one: its entries, in the reference's order, by Gaussian elimination with
    partial pivoting in a band after a reverse Cuthill-McKee ordering
    (:func:`img2logo._compiled.graph.banded_solve_kernel`).

    Parameters
    ----------
    points : (P, 2) float64, px; owner : (P,) int64, the circle of each point (grouped by circle, in order).
    radii : (C,); centers : (C, 2), px; junctions, disp : (J, 2), px.
    incidence : (M, 2) int64, unique rows (circle, junction).
    free_c, free_j : sorted unique int64 indices of the free circles and junctions.
    ws : (C,) segment weights; wj : the junction weight.
    tangents : (T, 3) int64 unique rows (a, b, k); tan_s_all : (T,) their scales 1 / max(r_a, r_b).
    held : (n,) bool, the unknowns held fixed (a mirror axis).
    banded : bool, solve the KKT system in a band (else densely by LU).

    Returns
    -------
    (iterations, converged, objective, violation)
    """
    n_c, n_j = radii.shape[0], junctions.shape[0]
    nc, nj = free_c.shape[0], free_j.shape[0]
    n = 2 * (nc + nj)
    pos_c = -np.ones(n_c, np.int64)
    for i in range(nc):
        pos_c[free_c[i]] = i
    pos_j = -np.ones(n_j, np.int64)
    for j in range(nj):
        pos_j[free_j[j]] = j
    # Points of free circles vary; those of fixed circles add a constant.
    n_pts = 0
    for p in range(owner.shape[0]):
        if pos_c[owner[p]] >= 0:
            n_pts += 1
    px, py = np.empty(n_pts), np.empty(n_pts)
    pt_circle, pt_pos = np.empty(n_pts, np.int64), np.empty(n_pts, np.int64)
    r_pts, w_pts = np.empty(n_pts), np.empty(n_pts)
    f_fixed = 0.0
    q = 0
    for p in range(owner.shape[0]):
        o = owner[p]
        if pos_c[o] >= 0:
            px[q], py[q] = points[p, 0], points[p, 1]
            pt_circle[q], pt_pos[q] = o, pos_c[o]
            r_pts[q], w_pts[q] = radii[o], ws[o]
            q += 1
        else:
            ax, ay = points[p, 0] - centers[o, 0], points[p, 1] - centers[o, 1]
            ee = math.sqrt(ax * ax + ay * ay) - radii[o]
            f_fixed += ws[o] * ee * ee
    d_fixed = 0.0
    for k in range(n_j):
        if pos_j[k] < 0:
            d_fixed += disp[k, 0] * disp[k, 0] + disp[k, 1] * disp[k, 1]
    f_const = f_fixed + wj * d_fixed
    # Incidences: all are evaluated; those with a free variable are constraints.
    m_all = incidence.shape[0]
    inc_i, inc_k = np.empty(m_all, np.int64), np.empty(m_all, np.int64)
    for r in range(m_all):
        inc_i[r], inc_k[r] = incidence[r, 0], incidence[r, 1]
    inc_p, inc_r = np.empty((m_all, 2)), np.empty(m_all)
    active = np.zeros(m_all, np.bool_)
    m_inc = 0
    for r in range(m_all):
        inc_p[r, 0], inc_p[r, 1] = junctions[inc_k[r], 0], junctions[inc_k[r], 1]
        inc_r[r] = radii[inc_i[r]]
        if connectivity and (pos_c[inc_i[r]] >= 0 or pos_j[inc_k[r]] >= 0):
            active[r] = True
            m_inc += 1
    act_rows = np.nonzero(active)[0]
    # Tangencies (a, b, k): all evaluated; those with a free variable are constraints, after the incidences.
    t_n = tangents.shape[0]
    tan_a, tan_b, tan_k = np.empty(t_n, np.int64), np.empty(t_n, np.int64), np.empty(t_n, np.int64)
    for t in range(t_n):
        tan_a[t], tan_b[t], tan_k[t] = tangents[t, 0], tangents[t, 1], tangents[t, 2]
    tan_active = np.zeros(t_n, np.bool_)
    m_tan = 0
    for t in range(t_n):
        if connectivity and (pos_c[tan_a[t]] >= 0 or pos_c[tan_b[t]] >= 0 or pos_j[tan_k[t]] >= 0):
            tan_active[t] = True
            m_tan += 1
    tan_rows = np.nonzero(tan_active)[0]
    m = m_inc + m_tan
    size = n + m
    # The unknowns the system keeps (a mirror axis holds some x coordinates).
    n_keep = 0
    keep = np.empty(size, np.int64)
    for u in range(size):
        if u >= n or not held[u]:
            keep[n_keep] = u
            n_keep += 1
    keep = keep[:n_keep]

    e, vx, vy, dist = np.empty(n_pts), np.empty(n_pts), np.empty(n_pts), np.empty(n_pts)
    c_all, vcx, vcy = np.empty(m_all), np.empty(m_all), np.empty(m_all)
    t_all, tab = np.empty(t_n), np.empty((t_n, 4))
    g = np.zeros(n)
    gn = np.zeros((nc + nj, 4))
    hq = np.zeros((nc, 4))  # residual curvature per free centre
    c = np.zeros(m)
    uc = np.zeros((m_inc, 2))
    dc = np.ones(m_inc)
    tg = np.zeros((m_tan, 6))  # d c / d o_a, d c / d o_b, d c / d d_k of each active tangency
    mat = np.zeros((size, size))
    sub = np.zeros((0, 0) if banded else (n_keep, n_keep))
    if banded:
        pat_r, pat_c, pat_fr, pat_fc, pat_first = kkt_pattern(
            n, nc, m_inc, m_tan, act_rows, inc_i, inc_k, pos_c, pos_j, tan_rows, tan_a, tan_b, tan_k, keep
        )
    else:
        pat_r, pat_c = np.zeros(0, np.int64), np.zeros(0, np.int64)
        pat_fr, pat_fc, pat_first = np.zeros(0, np.int64), np.zeros(0, np.int64), np.zeros(0, np.bool_)
    pat_v = np.zeros(pat_r.shape[0])
    out = np.empty(n_keep)
    # The elimination order of the pattern (the same in every step), found once.
    order = _cuthill_mckee(n_keep, pat_r, pat_c) if banded else np.zeros(0, np.int64)
    rhs = np.zeros(n_keep)
    sol = np.zeros(size)
    dx = np.zeros(n)
    lam = np.zeros(m)
    have_lam = False
    x = np.empty(n)
    for i in range(nc):
        x[2 * i], x[2 * i + 1] = centers[free_c[i], 0], centers[free_c[i], 1]
    for j in range(nj):
        x[2 * (nc + j)], x[2 * (nc + j) + 1] = disp[free_j[j], 0], disp[free_j[j], 1]
    xt = np.empty(n)
    history = np.empty(max_iter + 1)
    n_hist = 0
    iterations, converged, nu = 0, False, 0.0

    while True:
        # --- linearize: E^l, its gradient, the active constraints, the violation
        f = sqp_objective(centers, disp, free_j, px, py, pt_circle, r_pts, w_pts, f_const, wj, e, vx, vy, dist)
        g.fill(0.0)
        gn.fill(0.0)
        hq.fill(0.0)
        for p in range(n_pts):
            safe = dist[p] if dist[p] > 0 else 1.0
            ux = vx[p] / safe if dist[p] > 0 else 1.0
            uy = vy[p] / safe
            qq = e[p] / safe
            w = w_pts[p]
            i = pt_pos[p]
            g[2 * i] += w * (e[p] * ux)
            g[2 * i + 1] += w * (e[p] * uy)
            gn[i, 0] += w * (ux * ux)
            gn[i, 1] += w * (ux * uy)
            gn[i, 3] += w * (uy * uy)
            hq[i, 0] += w * (qq * uy * uy)
            hq[i, 1] += w * (qq * ux * uy)
            hq[i, 3] += w * (qq * ux * ux)
        for i in range(nc):
            g[2 * i] *= 2.0
            g[2 * i + 1] *= 2.0
            gn[i, 0] *= 2.0
            gn[i, 1] *= 2.0
            gn[i, 2] = gn[i, 1]
            gn[i, 3] *= 2.0
            hq[i, 0] *= 2.0
            hq[i, 1] *= 2.0
            hq[i, 3] *= 2.0
        for j in range(nj):
            g[2 * (nc + j)] = 2.0 * wj * disp[free_j[j], 0]
            g[2 * (nc + j) + 1] = 2.0 * wj * disp[free_j[j], 1]
            gn[nc + j, 0] = 2.0 * wj
            gn[nc + j, 3] = 2.0 * wj
        sqp_constraints(centers, disp, inc_i, inc_k, inc_p, inc_r, c_all, vcx, vcy)
        for q in range(m_inc):
            r = act_rows[q]
            c[q] = c_all[r]
            d = math.sqrt(vcx[r] * vcx[r] + vcy[r] * vcy[r])
            dsafe = d if d > 0 else 1.0
            uc[q, 0] = vcx[r] / dsafe if d > 0 else 1.0
            uc[q, 1] = vcy[r] / dsafe
            dc[q] = dsafe
        violation = max_abs(c_all)
        if t_n:
            sqp_tangency(centers, disp, junctions, tan_a, tan_b, tan_k, tan_s_all, t_all, tab)
            violation = max(violation, max_abs(t_all))
            for q in range(m_tan):
                t = tan_rows[q]
                s = tan_s_all[t]
                # d c / d o_a = s J b, d c / d o_b = s J^T a, d c / d d_k = -(both); J = [[0, 1], [-1, 0]].
                gax, gay = s * tab[t, 3], -s * tab[t, 2]
                gbx, gby = -s * tab[t, 1], s * tab[t, 0]
                tg[q, 0], tg[q, 1], tg[q, 2], tg[q, 3] = gax, gay, gbx, gby
                tg[q, 4], tg[q, 5] = -(gax + gbx), -(gay + gby)
                c[m_inc + q] = t_all[t]
        feasible = violation <= tol or not connectivity
        if n == 0 or iterations >= max_iter:
            converged = feasible and n == 0
            break
        history[n_hist] = violation
        n_hist += 1
        if not feasible and n_hist > stall and violation > 0.5 * history[n_hist - 1 - stall]:
            break  # stalled: most likely the fixed variables leave no feasible solution
        # --- the KKT step: Newton on the Lagrangian once multipliers are known, else Gauss-Newton
        scale = 0.0
        for b in range(nc + nj):
            for u in range(4):
                scale = max(scale, gn[b, u])
        scale = max(scale, 1e-300)
        delta = damping / scale
        found, curvature = False, 0.0
        for attempt in range(2):
            newton = attempt == 0 and have_lam
            if attempt == 0 and not have_lam:
                continue
            if banded:  # only the pattern's entries are ever written
                for ent in range(pat_r.shape[0]):
                    mat[pat_fr[ent], pat_fc[ent]] = 0.0
            else:
                mat.fill(0.0)
            for b in range(nc + nj):
                h0 = gn[b, 0] + damping * scale
                h1, h2 = gn[b, 1], gn[b, 2]
                h3 = gn[b, 3] + damping * scale
                if newton and b < nc:
                    h0 += hq[b, 0]
                    h1 -= hq[b, 1]
                    h2 -= hq[b, 1]
                    h3 += hq[b, 3]
                mat[2 * b, 2 * b], mat[2 * b, 2 * b + 1] = h0, h1
                mat[2 * b + 1, 2 * b], mat[2 * b + 1, 2 * b + 1] = h2, h3
            for q in range(m_inc):
                r = act_rows[q]
                ci, ck = pos_c[inc_i[r]], pos_j[inc_k[r]]
                row = n + q
                if ci >= 0:
                    mat[row, 2 * ci], mat[row, 2 * ci + 1] = uc[q, 0], uc[q, 1]
                    mat[2 * ci, row], mat[2 * ci + 1, row] = uc[q, 0], uc[q, 1]
                if ck >= 0:
                    cb = 2 * (nc + ck)
                    mat[row, cb], mat[row, cb + 1] = -uc[q, 0], -uc[q, 1]
                    mat[cb, row], mat[cb + 1, row] = -uc[q, 0], -uc[q, 1]
                if newton:
                    # Constraint curvature lam (I - u u^T) / |v| on o_i and d_k, minus it between them.
                    s = lam[q] / dc[q]
                    ux, uy = uc[q, 0], uc[q, 1]
                    k0, k1, k3 = s * uy * uy, -s * ux * uy, s * ux * ux
                    for blk in (ci, nc + ck if ck >= 0 else -1):
                        if blk >= 0:
                            mat[2 * blk, 2 * blk] += k0
                            mat[2 * blk, 2 * blk + 1] += k1
                            mat[2 * blk + 1, 2 * blk] += k1
                            mat[2 * blk + 1, 2 * blk + 1] += k3
                    if ci >= 0 and ck >= 0:
                        a0, b0 = 2 * ci, 2 * (nc + ck)
                        mat[a0, b0], mat[a0, b0 + 1], mat[a0 + 1, b0], mat[a0 + 1, b0 + 1] = -k0, -k1, -k1, -k3
                        mat[b0, a0], mat[b0, a0 + 1], mat[b0 + 1, a0], mat[b0 + 1, a0 + 1] = -k0, -k1, -k1, -k3
            for q in range(m_tan):
                t = tan_rows[q]
                row = n + m_inc + q
                blocks = (pos_c[tan_a[t]], pos_c[tan_b[t]], nc + pos_j[tan_k[t]] if pos_j[tan_k[t]] >= 0 else -1)
                for v in range(3):
                    blk = blocks[v]
                    if blk >= 0:
                        mat[row, 2 * blk], mat[row, 2 * blk + 1] = tg[q, 2 * v], tg[q, 2 * v + 1]
                        mat[2 * blk, row], mat[2 * blk + 1, row] = tg[q, 2 * v], tg[q, 2 * v + 1]
                if newton:
                    # lam s Hess(cross(o_a - q, o_b - q)): J on (o_a, o_b) and (o_b, q), -J on (o_a, q), J^T = -J.
                    lt = lam[m_inc + q] * tan_s_all[t]
                    for pr in range(3):
                        if pr == 0:
                            rb, cb, sign = blocks[0], blocks[1], 1.0
                        elif pr == 1:
                            rb, cb, sign = blocks[0], blocks[2], -1.0
                        else:
                            rb, cb, sign = blocks[1], blocks[2], 1.0
                        if rb >= 0 and cb >= 0:
                            w = sign * lt
                            mat[2 * rb, 2 * cb + 1] += w
                            mat[2 * rb + 1, 2 * cb] += -w
                            mat[2 * cb, 2 * rb + 1] += -w
                            mat[2 * cb + 1, 2 * rb] += w
            for q in range(m):
                mat[n + q, n + q] = -delta
            for a in range(n_keep):
                rhs[a] = -g[keep[a]] if keep[a] < n else -c[keep[a] - n]
            if banded:
                for ent in range(pat_r.shape[0]):
                    pat_v[ent] = mat[pat_fr[ent], pat_fc[ent]] if pat_first[ent] else 0.0
                ok = banded_solve_ordered(order, pat_r, pat_c, pat_v, rhs, out) == 0
                for a in range(n_keep):
                    rhs[a] = out[a]
            else:
                for a in range(n_keep):
                    for b in range(n_keep):
                        sub[a, b] = mat[keep[a], keep[b]]
                ok = lu_solve(sub, rhs)
            if ok:
                for a in range(n_keep):
                    if not math.isfinite(rhs[a]):
                        ok = False
            if not ok:
                found = False
                continue
            sol.fill(0.0)
            for a in range(n_keep):
                sol[keep[a]] = rhs[a]
            gdx, lc, ll = 0.0, 0.0, 0.0
            for u in range(n):
                dx[u] = sol[u]
                gdx += g[u] * dx[u]
            for q in range(m):
                lam[q] = sol[n + q]
                lc += lam[q] * c[q]
                ll += lam[q] * lam[q]
            # From the first block row W dx = -g - A^T lam and A dx - delta lam = -c.
            curvature = -gdx + lc - delta * ll
            found = True
            have_lam = True
            if curvature > 0:
                break
        if not found:
            break
        lam_max = 0.0
        c_sum = 0.0
        for q in range(m):
            lam_max = max(lam_max, abs(lam[q]))
            c_sum += abs(c[q])
        nu = max(nu, 1.5 * lam_max + 1e-12)
        phi0 = f + nu * c_sum
        dx_max = 0.0
        for u in range(n):
            dx_max = max(dx_max, abs(dx[u]))
        if feasible and (dx_max <= tol or abs(curvature) <= ftol * f):
            # Converged; a last full step polishes the result, if it helps.
            converged = True
            merit, new_violation = trial_step(
                x, 1.0, dx, xt, centers, disp, free_c, free_j, px, py, pt_circle, r_pts, w_pts, f_const, wj, e, vx,
                vy, dist, inc_i, inc_k, inc_p, inc_r, c_all, vcx, vcy, junctions, tan_a, tan_b, tan_k, tan_s_all,
                t_all, tab, active, tan_active, nu,
            )  # fmt: skip
            if merit <= phi0 and (not connectivity or new_violation <= violation):
                iterations += 1
            else:
                set_x(x, centers, disp, free_c, free_j)
            break
        gdx = 0.0
        for u in range(n):
            gdx += g[u] * dx[u]
        slope = gdx - nu * c_sum
        alpha, accepted = 1.0, False
        for _ in range(40):
            merit, _ = trial_step(
                x, alpha, dx, xt, centers, disp, free_c, free_j, px, py, pt_circle, r_pts, w_pts, f_const, wj, e, vx,
                vy, dist, inc_i, inc_k, inc_p, inc_r, c_all, vcx, vcy, junctions, tan_a, tan_b, tan_k, tan_s_all,
                t_all, tab, active, tan_active, nu,
            )  # fmt: skip
            if merit <= phi0 + 1e-4 * alpha * min(slope, 0.0):
                accepted = True
                break
            alpha *= 0.5
        if not accepted:
            set_x(x, centers, disp, free_c, free_j)
            converged = feasible
            break
        for u in range(n):
            x[u] = x[u] + alpha * dx[u]
        iterations += 1

    f = sqp_objective(centers, disp, free_j, px, py, pt_circle, r_pts, w_pts, f_const, wj, e, vx, vy, dist)
    sqp_constraints(centers, disp, inc_i, inc_k, inc_p, inc_r, c_all, vcx, vcy)
    violation = max_abs(c_all)
    if t_n:
        sqp_tangency(centers, disp, junctions, tan_a, tan_b, tan_k, tan_s_all, t_all, tab)
        violation = max(violation, max_abs(t_all))
    return iterations, converged, f, violation


# --------------------------------------------------------------------------------
# A merged arc that is certainly too far (the photo's arc bound, before the fit)
# --------------------------------------------------------------------------------


@_jit
def far_circle_kernel(points, r, cx0, cy0, bound, budget):  # pragma: no cover - compiled
    """Whether no circle of radius ``r`` passes within ``bound`` px of every one of ``points`` (N, 2).

    True is a proof: every centre is excluded, by a branch and bound over boxes of
    centres in which one point's nearest and farthest distances to the box both
    miss the annulus ``[r - bound, r + bound]`` around it. False means only "not
    shown": a centre within ``bound`` of all points was found (``cx0, cy0`` is tried
    first), a box got too small, or ``budget`` boxes were tried. Then an arc on
    any circle of radius ``r``, which the Fréchet distance couples to every point,
    is at least ``bound`` from one of them (:func:`img2logo.fit.merging.evaluate`).
    """
    n = points.shape[0]
    worst = 0.0
    for i in range(n):
        worst = max(worst, abs(math.hypot(points[i, 0] - cx0, points[i, 1] - cy0) - r))
    if worst <= bound:
        return False
    outer, inner = r + bound, r - bound
    x0, x1, y0, y1 = -math.inf, math.inf, -math.inf, math.inf
    for i in range(n):  # every centre is within r + bound of every point
        x0, x1 = max(x0, points[i, 0] - outer), min(x1, points[i, 0] + outer)
        y0, y1 = max(y0, points[i, 1] - outer), min(y1, points[i, 1] + outer)
    if x0 > x1 or y0 > y1:
        return True
    stack = np.empty((128, 4))
    stack[0, 0], stack[0, 1], stack[0, 2], stack[0, 3] = x0, x1, y0, y1
    top, boxes, last = 1, 0, 0
    while top > 0:
        top -= 1
        bx0, bx1, by0, by1 = stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3]
        boxes += 1
        if boxes > budget:
            return False
        excluded = False
        for t in range(n):  # the point that excluded the last box first
            i = last + t
            if i >= n:
                i -= n
            px, py = points[i, 0], points[i, 1]
            dx = bx0 - px if px < bx0 else (px - bx1 if px > bx1 else 0.0)
            dy = by0 - py if py < by0 else (py - by1 if py > by1 else 0.0)
            fx = max(abs(px - bx0), abs(px - bx1))
            fy = max(abs(py - by0), abs(py - by1))
            if math.sqrt(dx * dx + dy * dy) > outer or math.sqrt(fx * fx + fy * fy) < inner:
                excluded = True
                last = i
                break
        if excluded:
            continue
        cx, cy = 0.5 * (bx0 + bx1), 0.5 * (by0 + by1)
        worst = 0.0
        for i in range(n):
            worst = max(worst, abs(math.hypot(points[i, 0] - cx, points[i, 1] - cy) - r))
        if worst <= bound:
            return False
        if max(bx1 - bx0, by1 - by0) < 1e-7 or top + 2 > stack.shape[0]:
            return False
        if bx1 - bx0 >= by1 - by0:  # halve the longer side
            stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3] = bx0, cx, by0, by1
            stack[top + 1, 0], stack[top + 1, 1], stack[top + 1, 2], stack[top + 1, 3] = cx, bx1, by0, by1
        else:
            stack[top, 0], stack[top, 1], stack[top, 2], stack[top, 3] = bx0, bx1, by0, cy
            stack[top + 1, 0], stack[top + 1, 1], stack[top + 1, 2], stack[top + 1, 3] = bx0, bx1, cy, by1
        top += 2
    return True
