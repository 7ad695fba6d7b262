"""The connectivity-constrained circle fit (Sec. 5.3, Eqn. 13) and its local window (Sec. 5.4).

* :func:`fit_constrained` solves Eqn. 13: with the (golden) radii fixed it moves
  the circle centres o_i and junction displacements d_k to minimize E^l (Eqn. 7)
  subject to every circle passing through its displaced junctions (Eqn. 8, 9).
  Variables may be held fixed, which is the localized fitting of Sec. 5.4.
* :func:`~img2logo.fit.local_window.fit_window` is the refit of a local window, grown ring by
  ring when it does not solve: the one used by the progressive optimization and the edits.

The Python SQP step (the problem, its KKT matrices and solve) is
:mod:`img2logo.fit.constrained_sqp`, the reference of the compiled one (:mod:`img2logo._compiled.kernels`).
The free fits of one circle (the first stage) are :mod:`img2logo.geometry.circle_fitting`.

Coordinates are input-image pixels: x to the right, y downwards, the pixel in row
i, column j has its centre at (j + 0.5, i + 0.5). Lengths are in px.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from .._compat import unique, unique_rows
from .._validation import check_finite, check_points, check_positive, readonly
from ..errors import InvalidParameterError
from .constants import (
    CONSTRAINED_FIT_FTOL,
    CONSTRAINED_FIT_MAX_ITER,
    CONSTRAINED_FIT_STALL,
    CONSTRAINED_FIT_TOL,
    KKT_COMPILED_MAX,
    KKT_DAMPING,
    KKT_DENSE_MAX,
)
from .constrained_sqp import Problem, solve_kkt

__all__ = [
    "ConstrainedFit",
    "fit_constrained",
]


# --------------------------------------------------------------------------------
# Connectivity-constrained fit (Eqn. 13)
# --------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class ConstrainedFit:
    """The result of :func:`fit_constrained`.

    Attributes
    ----------
    centers : ndarray, shape (C, 2)
        Circle centres o_i, px.
    displacements : ndarray, shape (J, 2)
        Junction displacements d_k, px; the displaced junctions are ``p_k + d_k``.
    objective : float
        E^l of Eqn. 7 at the result, px^2 (times the weights).
    violation : float
        Largest ``| |o_i - (p_k + d_k)| - r_i |`` over all incidences and largest
        tangency residual (see ``tangents`` of :func:`fit_constrained`), px; 0 if
        there are none. Those between fixed variables count too.
    iterations : int
        SQP steps taken.
    converged : bool
        Whether ``violation <= tol`` and the next step would be below ``tol`` px
        or lower E^l by less than ``CONSTRAINED_FIT_FTOL`` of it (for
        ``connectivity=False``, only the latter). False when ``max_iter`` ran
        out, the constraints cannot be met, or the line search stalled while
        infeasible.
    """

    centers: np.ndarray
    displacements: np.ndarray
    objective: float
    violation: float
    iterations: int
    converged: bool


def _index_array(values: object, name: str, size: int) -> np.ndarray:
    arr = np.asarray(values)
    if arr.size == 0:
        return np.zeros(0, dtype=np.int64)
    if arr.ndim != 1 or not np.issubdtype(arr.dtype, np.integer):
        raise InvalidParameterError(f"{name} must be a 1-D array of integers, got shape {arr.shape}, {arr.dtype}")
    if arr.min() < 0 or arr.max() >= size:
        raise InvalidParameterError(f"{name} must index 0..{size - 1}, got values from {arr.min()} to {arr.max()}")
    return unique(arr).astype(np.int64)


def _as_points(values: object, name: str, count: int | None = None) -> np.ndarray:
    if np.size(values) == 0 and count in (None, 0):
        return np.zeros((0, 2))
    arr = check_points(values, name)
    if count is not None and len(arr) != count:
        raise InvalidParameterError(f"{name} must have shape ({count}, 2), got {arr.shape}")
    return arr


def fit_constrained(
    point_sets: Sequence[object],
    radii: object,
    centers0: object,
    junctions: object,
    incidence: object,
    *,
    displacements0: object | None = None,
    free_circles: object | None = None,
    free_junctions: object | None = None,
    segment_weight: float | np.ndarray | None = None,
    junction_weight: float | None = None,
    tol: float = CONSTRAINED_FIT_TOL,
    max_iter: int = CONSTRAINED_FIT_MAX_ITER,
    connectivity: bool = True,
    axis: float | None = None,
    axis_circles: object = (),
    axis_junctions: object = (),
    stall: int = CONSTRAINED_FIT_STALL,
    tangents: object = (),
) -> ConstrainedFit:
    """Connectivity-constrained least-squares fit of circles with fixed radii (Eqn. 13).

    Minimizes E^l (Eqn. 7)::

        segment_weight * sum_i sum_{p in S_i} (|p - o_i| - r_i)^2
            + junction_weight * sum_k |d_k|^2

    over the free centres o_i and free junction displacements d_k, subject to
    ``|o_i - (p_k + d_k)| - r_i = 0`` for every incidence (i, k) (Eqn. 8, 9).

    The solver is an SQP method with analytic derivatives: each step solves the
    KKT system ``[[W + mu I, A^T], [A, -delta I]] [dx; lambda] = [-g; -c]``,
    with g the gradient of E^l, A the Jacobian of the constraints c, and W the
    Gauss-Newton matrix J^T J (block-diagonal with 2x2 blocks) in the first step;
    afterwards W is the Hessian of the Lagrangian (adding the residual curvature
    and the multiplier-weighted constraint curvature, which couples a centre
    with its junctions), falling back to J^T J when that step lacks positive
    curvature. ``mu`` and ``delta`` are ``KKT_DAMPING`` relative to the largest
    entry of J^T J, so nearly singular systems (huge radii, redundant
    constraints) stay solvable. The system is solved densely for a small
    window and by a banded elimination (:func:`img2logo.fit.constrained_sqp.solve_kkt`)
    above ``KKT_DENSE_MAX`` unknowns; a backtracking line search on the L1
    merit ``E^l + nu * sum |c|`` (``nu`` = 1.5 x the largest multiplier seen)
    chooses the step length.

    Parameters
    ----------
    point_sets : sequence of array_like, each of shape (n_i, 2)
        The points of the segments S_i that circle i fits, px; n_i >= 1.
    radii : array_like, shape (C,)
        The fixed (golden) radii r_i, px, > 0.
    centers0 : array_like, shape (C, 2)
        Starting centres o_i, px; the final centres of the fixed circles.
    junctions : array_like, shape (J, 2)
        The undisplaced junctions p_k, px.
    incidence : array_like of int, shape (M, 2)
        Rows (i, k): circle i must pass through displaced junction k.
    displacements0 : array_like, shape (J, 2), optional
        Starting displacements d_k, px (default zeros); the final displacements
        of the fixed junctions.
    free_circles, free_junctions : array_like of int, optional
        Indices of the circles / junctions that may move; None means all. The
        others keep their given values exactly (the boundary conditions of the
        localized fitting, Sec. 5.4).
    segment_weight : float or array_like of shape (C,), optional
        Weight of the fitting term, one for all circles or one per circle;
        default ``1 / C`` (the paper's 1/|S|). ``1 / (C n_i)`` makes each
        segment's term its mean squared error instead of its sum.
    junction_weight : float, optional
        Weight of the displacement term, default ``1 / J`` (the paper's 1/|J|).
    tol : float
        Tolerance on the constraints and on the last step, px.
    max_iter : int
        Most SQP steps.
    connectivity : bool
        False drops the constraints (the ablation of Fig. 11c): each free centre
        moves to its best position for its fixed radius, and free displacements go
        to zero.
    axis : float, optional
        A vertical mirror axis x = ``axis``, px (symmetric logos,
        :mod:`img2logo.fit.symmetry`): the centres of ``axis_circles`` and the
        displaced junctions ``axis_junctions`` (indices) are held on it, their x
        set to it and never moved, only their y (Eqn. 13 with the symmetry
        constraints).
    stall : int
        Give up when the constraint violation has not halved over this many
        steps (an infeasible problem, most likely).
    tangents : array_like of int, shape (T, 3), optional
        Rows (a, b, k): circles a and b touch at displaced junction k (both
        should also pass through it by ``incidence``, or the residual is only the
        collinearity of o_a, o_b and q_k). The residual
        ``cross(o_a - q_k, o_b - q_k) / max(r_a, r_b)`` is ``min(r) sin(theta)``,
        px, theta the angle between the two radii to q_k: exact tangency at
        ``tol``, either internal (same side) or external, whichever is nearer the
        start. Rows between fixed variables only are evaluated, not enforced;
        none are with ``connectivity=False``.

    Returns
    -------
    ConstrainedFit
        With ``converged=False`` (never an exception) when the constraints could
        not be met, e.g. when fixed junctions leave no feasible circle position.

    Raises
    ------
    InvalidParameterError
        On inputs of the wrong shape, out-of-range indices, or bad weights.
    """
    radii_arr = np.asarray(radii, dtype=np.float64)
    if radii_arr.ndim != 1:
        raise InvalidParameterError(f"radii must have shape (C,), got {radii_arr.shape}")
    if not np.all(np.isfinite(radii_arr)) or np.any(radii_arr <= 0):
        raise InvalidParameterError("radii must be finite and > 0")
    n_c = len(radii_arr)
    if len(point_sets) != n_c:
        raise InvalidParameterError(f"point_sets must have one entry per radius ({n_c}), got {len(point_sets)}")
    sets = [check_points(s, f"point_sets[{i}]") for i, s in enumerate(point_sets)]
    centers = _as_points(centers0, "centers0", n_c)
    junc = _as_points(junctions, "junctions")
    n_j = len(junc)
    disp = np.zeros((n_j, 2)) if displacements0 is None else _as_points(displacements0, "displacements0", n_j)
    inc = np.asarray(incidence)
    if inc.size == 0:
        inc = np.zeros((0, 2), dtype=np.int64)
    if inc.ndim != 2 or inc.shape[1] != 2 or not np.issubdtype(inc.dtype, np.integer):
        raise InvalidParameterError(f"incidence must be an integer array of shape (M, 2), got {inc.shape}, {inc.dtype}")
    _index_array(inc[:, 0], "incidence[:, 0]", n_c)
    _index_array(inc[:, 1], "incidence[:, 1]", n_j)
    free_c = np.arange(n_c) if free_circles is None else _index_array(free_circles, "free_circles", n_c)
    free_j = np.arange(n_j) if free_junctions is None else _index_array(free_junctions, "free_junctions", n_j)
    if segment_weight is None:
        ws = np.full(n_c, 1.0 / max(n_c, 1))
    elif np.ndim(segment_weight) == 0:
        ws = np.full(n_c, check_positive(segment_weight, "segment_weight", allow_zero=True))
    else:
        ws = np.asarray(segment_weight, dtype=np.float64)
        if ws.shape != (n_c,):
            raise InvalidParameterError(f"segment_weight must be a number or have shape ({n_c},), got {ws.shape}")
        if not np.all(np.isfinite(ws)) or np.any(ws < 0):
            raise InvalidParameterError("segment_weight must be finite and >= 0")
    if junction_weight is None:
        wj = 1.0 / n_j if n_j else 1.0
    else:
        wj = check_positive(junction_weight, "junction_weight", allow_zero=True)
    tol = check_positive(tol, "tol")
    if isinstance(max_iter, bool) or not isinstance(max_iter, int) or max_iter < 0:
        raise InvalidParameterError(f"max_iter must be an integer >= 0, got {max_iter!r}")

    on_c = _index_array(axis_circles, "axis_circles", n_c)
    on_j = _index_array(axis_junctions, "axis_junctions", n_j)
    if axis is not None:
        axis = check_finite(axis, "axis")
    elif len(on_c) or len(on_j):
        raise InvalidParameterError("axis_circles and axis_junctions need an axis")
    tan = np.asarray(tangents)
    if tan.size == 0:
        tan = np.zeros((0, 3), dtype=np.int64)
    if tan.ndim != 2 or tan.shape[1] != 3 or not np.issubdtype(tan.dtype, np.integer):
        raise InvalidParameterError(f"tangents must be an integer array of shape (T, 3), got {tan.shape}, {tan.dtype}")
    _index_array(tan[:, :2].ravel(), "tangents[:, :2]", n_c)
    _index_array(tan[:, 2], "tangents[:, 2]", n_j)
    if np.any(tan[:, 0] == tan[:, 1]):
        raise InvalidParameterError("tangents must name two different circles in each row")
    problem = WindowProblem.of(
        sets, radii_arr, centers, junc, disp, inc, free_c, free_j, ws, wj, connectivity, tan,
        axis=axis, on_c=on_c, on_j=on_j, tol=tol, max_iter=max_iter, stall=stall,
    )  # fmt: skip
    return solve_sqp(problem)


@dataclass(frozen=True, eq=False)
class WindowProblem:
    """Eqn. 13 on checked arrays: what the SQP of :func:`fit_constrained` solves (one value, not 18 arguments).

    Built by :func:`fit_constrained` after its checks (:meth:`of`), and directly
    by :func:`~img2logo.fit.local_window.fit_window` from the window's own arrays, which are well formed by
    construction. Solved by :func:`solve_sqp`: the compiled kernels (a local window
    densely, a global solve in a band), or the Python reference
    (:class:`~img2logo.fit.constrained_sqp.Problem`, made of this value: it is a
    :class:`~img2logo.fit.constrained_sqp.ProblemArrays`).

    Attributes
    ----------
    points : ndarray, shape (P, 2)
        Every circle's points, px (float64), grouped by circle in circle order.
    owner : ndarray of int64, shape (P,)
        The circle of each point.
    radii : ndarray, shape (C,)
        The fixed radii r_i, px.
    centers : ndarray, shape (C, 2)
        The starting centres o_i, px (the fixed circles' final ones).
    junctions : ndarray, shape (J, 2)
        The undisplaced junctions p_k, px.
    disp : ndarray, shape (J, 2)
        The starting displacements d_k, px (the fixed junctions' final ones).
    incidence : ndarray of int64, shape (M, 2)
        Rows (i, k), distinct and sorted: circle i passes through junction k.
    free_c, free_j : ndarray of int64
        The free circles and junctions, sorted, distinct.
    ws : ndarray, shape (C,)
        The segment weight of each circle.
    wj : float
        The displacement weight.
    connectivity : bool
        False: no constraints (Fig. 11c).
    tangents : ndarray of int64, shape (T, 3)
        Rows (a, b, k), distinct and sorted: circles a and b touch at junction k.
    held : tuple of int
        Unknowns held where they are (the x coordinates on a mirror axis), as
        indices into x = (free centres, free displacements).
    tol : float
        Tolerance on the constraints and the last step, px.
    max_iter, stall : int
        Most SQP steps; steps without the violation halving before giving up.
    """

    points: np.ndarray
    owner: np.ndarray
    radii: np.ndarray
    centers: np.ndarray
    junctions: np.ndarray
    disp: np.ndarray
    incidence: np.ndarray
    free_c: np.ndarray
    free_j: np.ndarray
    ws: np.ndarray
    wj: float
    connectivity: bool
    tangents: np.ndarray
    held: tuple[int, ...] = ()
    tol: float = CONSTRAINED_FIT_TOL
    max_iter: int = CONSTRAINED_FIT_MAX_ITER
    stall: int = CONSTRAINED_FIT_STALL

    @classmethod
    def of(
        cls,
        sets: Sequence[np.ndarray],
        radii: np.ndarray,
        centers: np.ndarray,
        junctions: np.ndarray,
        disp: np.ndarray,
        incidence: np.ndarray,
        free_c: np.ndarray,
        free_j: np.ndarray,
        ws: np.ndarray,
        wj: float,
        connectivity: bool,
        tangents: np.ndarray,
        *,
        axis: float | None = None,
        on_c: np.ndarray | None = None,
        on_j: np.ndarray | None = None,
        tol: float = CONSTRAINED_FIT_TOL,
        max_iter: int = CONSTRAINED_FIT_MAX_ITER,
        stall: int = CONSTRAINED_FIT_STALL,
    ) -> WindowProblem:
        """The problem of :func:`fit_constrained`'s checked inputs (float64 points, sorted unique int64 indices).

        Incidence and tangent rows are made distinct and sorted; with a mirror
        ``axis``, the centres ``on_c`` and junctions ``on_j`` are placed on it
        and their x coordinates held.
        """
        inc = unique_rows(incidence)
        tan = unique_rows(tangents)
        held: list[int] = []
        if axis is not None:
            on_c = np.zeros(0, dtype=np.int64) if on_c is None else on_c
            on_j = np.zeros(0, dtype=np.int64) if on_j is None else on_j
            centers = centers.copy()
            disp = disp.copy()
            centers[on_c, 0] = axis
            disp[on_j, 0] = axis - junctions[on_j, 0]
            # The x coordinates held on the axis: their unknowns leave the KKT system.
            pos_c = {int(c): i for i, c in enumerate(free_c)}
            pos_j = {int(k): i for i, k in enumerate(free_j)}
            held = [2 * pos_c[int(c)] for c in on_c if int(c) in pos_c]
            held += [2 * (len(free_c) + pos_j[int(k)]) for k in on_j if int(k) in pos_j]
        owner = np.repeat(np.arange(len(radii)), [len(s) for s in sets])
        points = np.concatenate(sets) if sets else np.zeros((0, 2))
        return cls(
            points, owner, radii, centers, junctions, disp, inc, free_c, free_j, ws, wj, connectivity, tan,
            tuple(held), tol, max_iter, stall,
        )  # fmt: skip

    def kkt_size(self) -> int:
        """Unknowns plus multipliers of its KKT system (:class:`~img2logo.fit.constrained_sqp.Problem`), not built."""
        n = 2 * (len(self.free_c) + len(self.free_j))
        if not self.connectivity:
            return n
        on_c, on_j = np.zeros(len(self.radii), dtype=bool), np.zeros(len(self.junctions), dtype=bool)
        on_c[self.free_c], on_j[self.free_j] = True, True
        inc, tan = self.incidence, self.tangents
        m = int(np.count_nonzero(on_c[inc[:, 0]] | on_j[inc[:, 1]]))
        m += int(np.count_nonzero(on_c[tan[:, 0]] | on_c[tan[:, 1]] | on_j[tan[:, 2]]))
        return n + m

    def reference(self) -> Problem:
        """The Python reference's :class:`~img2logo.fit.constrained_sqp.Problem` of it."""
        return Problem(self)


def solve_sqp(problem: WindowProblem, compiled: bool = True, size: int | None = None) -> ConstrainedFit:
    """The SQP solve of :func:`fit_constrained` on its checked arrays.

    A KKT system of at most ``KKT_DENSE_MAX`` unknowns and multipliers (a local
    window) is solved by the compiled kernel :func:`img2logo._compiled.sqp.sqp_dense`,
    the same method step for step; larger ones (a global solve) by
    :func:`img2logo._compiled.sqp.sqp_banded`, the same again with the KKT system's
    entries in the reference's order eliminated in a band (the giraffe's global
    solves: about 3.5x faster than the Python loop, the same iterates to ~1e-11 px).
    ``compiled=False`` always runs the Python reference :func:`_fit_reference`
    (the tests compare them), as does a system above ``KKT_COMPILED_MAX``.
    ``size``: the problem's :meth:`WindowProblem.kkt_size` when the caller counted it.
    """
    from .._compiled import kernels  # the compiled kernels load on the first fit, not at import

    p = problem
    if size is None:
        size = p.kkt_size()
    if compiled and size <= KKT_COMPILED_MAX:
        kernel = kernels.sqp_dense if size <= KKT_DENSE_MAX else kernels.sqp_banded
        centers, disp = np.array(p.centers, dtype=np.float64), np.array(p.disp, dtype=np.float64)
        held_mask = np.zeros(2 * (len(p.free_c) + len(p.free_j)), dtype=bool)
        if p.held:
            held_mask[np.asarray(p.held, dtype=np.intp)] = True
        if len(p.tangents):
            tan_s = 1.0 / np.maximum(p.radii[p.tangents[:, 0]], p.radii[p.tangents[:, 1]])
        else:
            tan_s = np.zeros(0)
        iterations, converged, objective, violation = kernel(
            np.ascontiguousarray(p.points, dtype=np.float64).reshape(-1, 2),
            np.ascontiguousarray(p.owner, dtype=np.int64),
            np.ascontiguousarray(p.radii, dtype=np.float64),
            centers,
            np.ascontiguousarray(p.junctions, dtype=np.float64).reshape(-1, 2),
            disp.reshape(-1, 2),
            np.ascontiguousarray(p.incidence, dtype=np.int64).reshape(-1, 2),
            np.ascontiguousarray(p.free_c, dtype=np.int64),
            np.ascontiguousarray(p.free_j, dtype=np.int64),
            np.ascontiguousarray(p.ws, dtype=np.float64),
            float(p.wj),
            bool(p.connectivity),
            np.ascontiguousarray(p.tangents, dtype=np.int64).reshape(-1, 3),
            tan_s,
            held_mask,
            float(p.tol),
            int(p.max_iter),
            int(p.stall),
            CONSTRAINED_FIT_FTOL,
            KKT_DAMPING,
        )
        return ConstrainedFit(
            centers=readonly(centers),
            displacements=readonly(disp),
            objective=float(objective),
            violation=float(violation),
            iterations=int(iterations),
            converged=bool(converged),
        )
    prob = p.reference()
    keep = np.setdiff1d(np.arange(prob.n + prob.m), p.held) if p.held else None
    return _fit_reference(prob, keep, p.connectivity, p.tol, p.max_iter, p.stall)


def _fit_reference(
    prob: Problem, keep: np.ndarray | None, connectivity: bool, tol: float, max_iter: int, stall: int
) -> ConstrainedFit:
    """The SQP loop of :func:`fit_constrained` in Python (the reference of :func:`img2logo._compiled.sqp.sqp_dense`)."""
    iterations, converged, nu, lam = 0, False, 0.0, None
    x = prob.get_x()
    history: list[float] = []  # violations, to stop early on infeasible problems
    while True:
        f, g, c, violation = prob.linearize()
        feasible = violation <= tol or not connectivity
        if prob.n == 0 or iterations >= max_iter:
            converged = feasible and prob.n == 0
            break
        history.append(violation)
        if not feasible and len(history) > stall and violation > 0.5 * history[-1 - stall]:
            break  # stalled: most likely the fixed variables leave no feasible solution
        # A Newton step on the Lagrangian once multipliers are known; Gauss-Newton
        # when there are none yet or the Newton step has no positive curvature.
        sol = None
        for multipliers in (lam, None) if lam is not None else (None,):
            sol = solve_kkt(*prob.matrix(multipliers), g, c, keep)
            if sol is not None and sol[2] > 0:
                break
        if sol is None:
            break
        dx, lam, curvature = sol
        nu = max(nu, 1.5 * float(np.abs(lam).max(initial=0.0)) + 1e-12)
        phi0 = f + nu * float(np.abs(c).sum())
        # Converged: feasible, and the step is below tol px or would lower E^l by a
        # negligible fraction (ill-conditioned directions, e.g. huge radii, keep
        # rounding-noise steps larger than tol).
        if feasible and (np.abs(dx).max() <= tol or abs(curvature) <= CONSTRAINED_FIT_FTOL * f):
            converged = True
            prob.set_x(x + dx)  # a last full step polishes the result, if it helps
            new_violation = prob.violation()
            if prob.merit(nu) <= phi0 and (not connectivity or new_violation <= violation):
                iterations += 1
            else:
                prob.set_x(x)
            break
        slope = float((g * dx).sum()) - nu * float(np.abs(c).sum())
        alpha, accepted = 1.0, False
        for _ in range(40):
            prob.set_x(x + alpha * dx)
            if prob.merit(nu) <= phi0 + 1e-4 * alpha * min(slope, 0.0):
                accepted = True
                break
            alpha *= 0.5
        if not accepted:
            prob.set_x(x)
            converged = feasible
            break
        x = x + alpha * dx
        iterations += 1

    return ConstrainedFit(
        centers=readonly(prob.centers.copy()),
        displacements=readonly(prob.disp.copy()),
        objective=prob.objective()[0],
        violation=prob.violation(),
        iterations=iterations,
        converged=converged,
    )
