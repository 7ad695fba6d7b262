"""The terms of the SQP of Eqn. 13, compiled: E^l, the constraints, the tangencies, the merit, a trial step.

:func:`sqp_objective` is E^l (Eqn. 7) with its residuals, :func:`sqp_constraints` the incidence
residuals (Eqn. 8, 9), :func:`sqp_tangency` the tangency residuals of smooth joins, on the variables
that :func:`set_x` writes into the centres and displacements; :func:`sqp_merit` is the L1 merit, and
:func:`trial_step` moves to a trial point of the line search and evaluates it. The loop that uses them
is :mod:`img2logo._compiled.sqp`; their Python reference is :mod:`img2logo.fit.constrained_sqp`.

Written in the subset of Python that numba compiles; loaded through :mod:`img2logo._compiled.kernels`.
Coordinates follow :mod:`img2logo.geometry.primitives`: px, x right, y down.
"""

from __future__ import annotations

import math

from .jit import jit as _jit


@_jit
def set_x(x, centers, disp, free_c, free_j):  # pragma: no cover - compiled
    nc = free_c.shape[0]
    for i in range(nc):
        centers[free_c[i], 0] = x[2 * i]
        centers[free_c[i], 1] = x[2 * i + 1]
    for j in range(free_j.shape[0]):
        disp[free_j[j], 0] = x[2 * (nc + j)]
        disp[free_j[j], 1] = x[2 * (nc + j) + 1]


@_jit
def sqp_objective(
    centers, disp, free_j, px, py, pt_circle, r_pts, w_pts, f_const, wj, e, vx, vy, dist
):  # pragma: no cover
    """E^l (Eqn. 7); fills the residuals e, vectors o - p and distances of the free circles' points."""
    s = 0.0
    for p in range(px.shape[0]):
        c = pt_circle[p]
        ax = centers[c, 0] - px[p]
        ay = centers[c, 1] - py[p]
        d = math.sqrt(ax * ax + ay * ay)
        vx[p], vy[p], dist[p] = ax, ay, d
        ee = d - r_pts[p]
        e[p] = ee
        s += w_pts[p] * ee * ee
    sd = 0.0
    for j in range(free_j.shape[0]):
        k = free_j[j]
        sd += disp[k, 0] * disp[k, 0] + disp[k, 1] * disp[k, 1]
    return f_const + s + wj * sd


@_jit
def sqp_constraints(centers, disp, inc_i, inc_k, inc_p, inc_r, c_all, vcx, vcy):  # pragma: no cover - compiled
    """All incidence residuals |o_i - (p_k + d_k)| - r_i and their vectors."""
    for r in range(inc_i.shape[0]):
        i, k = inc_i[r], inc_k[r]
        ax = centers[i, 0] - inc_p[r, 0] - disp[k, 0]
        ay = centers[i, 1] - inc_p[r, 1] - disp[k, 1]
        vcx[r], vcy[r] = ax, ay
        c_all[r] = math.sqrt(ax * ax + ay * ay) - inc_r[r]


@_jit
def sqp_tangency(centers, disp, junctions, tan_a, tan_b, tan_k, tan_s, t_all, tab):  # pragma: no cover - compiled
    """All tangency residuals cross(o_a - q, o_b - q) / max(r_a, r_b); the vectors a, b as rows (ax, ay, bx, by)."""
    for t in range(tan_a.shape[0]):
        k = tan_k[t]
        qx = junctions[k, 0] + disp[k, 0]
        qy = junctions[k, 1] + disp[k, 1]
        ax = centers[tan_a[t], 0] - qx
        ay = centers[tan_a[t], 1] - qy
        bx = centers[tan_b[t], 0] - qx
        by = centers[tan_b[t], 1] - qy
        tab[t, 0], tab[t, 1], tab[t, 2], tab[t, 3] = ax, ay, bx, by
        t_all[t] = (ax * by - ay * bx) * tan_s[t]


@_jit
def sqp_merit(nu, f, c_all, active, t_all, tan_active):  # pragma: no cover - compiled
    """The L1 merit E^l + nu * sum |c| over the constraints."""
    s = 0.0
    for r in range(c_all.shape[0]):
        if active[r]:
            s += abs(c_all[r])
    out = f + nu * s
    st = 0.0
    n_on = 0
    for t in range(t_all.shape[0]):
        if tan_active[t]:
            st += abs(t_all[t])
            n_on += 1
    if n_on:
        out += nu * st
    return out


@_jit
def trial_step(
    x,
    alpha,
    dx,
    xt,
    centers,
    disp,
    free_c,
    free_j,
    px,
    py,
    pt_circle,
    r_pts,
    w_pts,
    f_const,
    wj,
    e,
    vx,
    vy,
    dist,
    inc_i,
    inc_k,
    inc_p,
    inc_r,
    c_all,
    vcx,
    vcy,
    junctions,
    tan_a,
    tan_b,
    tan_k,
    tan_s_all,
    t_all,
    tab,
    active,
    tan_active,
    nu,
):  # pragma: no cover - compiled
    """Move to ``x + alpha dx`` and evaluate it: (its L1 merit, its constraint violation).

    The trial point of the line search and of the last polishing step
    (``alpha`` = 1): E^l, every incidence and tangency residual at it.
    """
    for u in range(x.shape[0]):
        xt[u] = x[u] + alpha * dx[u]
    set_x(xt, centers, disp, free_c, free_j)
    f_new = sqp_objective(centers, disp, free_j, px, py, pt_circle, r_pts, w_pts, f_const, wj, e, vx, vy, dist)
    sqp_constraints(centers, disp, inc_i, inc_k, inc_p, inc_r, c_all, vcx, vcy)
    violation = max_abs(c_all)
    if tan_a.shape[0]:
        sqp_tangency(centers, disp, junctions, tan_a, tan_b, tan_k, tan_s_all, t_all, tab)
        violation = max(violation, max_abs(t_all))
    return sqp_merit(nu, f_new, c_all, active, t_all, tan_active), violation


@_jit
def max_abs(values):  # pragma: no cover - compiled
    out = 0.0
    for v in values:
        out = max(out, abs(v))
    return out
