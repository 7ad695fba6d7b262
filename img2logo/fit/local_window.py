"""The refit of a local window (Sec. 5.4), grown ring by ring when it does not solve.

:func:`fit_window` fits the circles that a change touches and the junctions around them with the
connectivity-constrained fit (Eqn. 13, :func:`img2logo.fit.constrained_fit.fit_constrained`), the rest
held fixed; when that window does not solve, one more ring of neighbouring circles and junctions is
freed, up to ``rings``. It is the refit used by the progressive optimization and the edits.

Coordinates are input-image pixels: x to the right, y downwards, the pixel in row
i, column j has its centre at (j + 0.5, i + 0.5). Lengths are in px.
"""

from __future__ import annotations

from collections.abc import Callable, Container, Hashable, Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from .constants import (
    CONSTRAINED_FIT_TOL,
)
from .constrained_fit import ConstrainedFit, WindowProblem, fit_constrained, solve_sqp

__all__ = ["WindowFit", "fit_window"]


#: fit_window(stop_when_stuck=True): a ring whose fit ends at the constraint violation of the
#: ring before, to this fraction of it (or to the fit's tolerance), ends the growth. Its freed
#: junctions did not relieve the constraints: most likely they are infeasible inside the window
#: (the merged circle's fixed radius against its own junctions), and a wider window fails as well (on the
#: clip arts of data/, benchmarks/data/, its heldout/ and two busy Openclipart ones, 380 wider windows,
#: none solved after two of its rings ended this alike; the 101 images' logos are the same with the rule).
#: A heuristic, not a proof: a window can solve a ring later (the clip-art cactus: one whose local window's
#: second ring and its third ended alike solved at its fourth), which is why only rings of one call compare.
STUCK_VIOLATION_CHANGE = 0.01


@dataclass(frozen=True, eq=False)
class WindowFit:
    """The result of :func:`fit_window`.

    Attributes
    ----------
    ok : bool
        Whether the last window solved (converged, within the violation asked).
    circles : tuple
        The circles of the last window, in the order of the fit.
    junctions : tuple
        Its junctions, sorted.
    free_junctions : frozenset
        The junctions that were free in it.
    fit : ConstrainedFit or None
        The fit of the last window (None for an empty window: no circle
        and no junction, nothing to solve, ``ok`` is True; and for a window
        that ``first_ring`` of :func:`fit_window` grew over its whole connected
        part without solving it, ``ok`` False). A window of circles
        that no junction touches (every junction released, a closed curve
        alone) is still fitted: each free centre moves to its best position
        for its fixed radius.
    """

    ok: bool
    circles: tuple[Hashable, ...]
    junctions: tuple[Hashable, ...]
    free_junctions: frozenset[Hashable]
    fit: ConstrainedFit | None

    def center(self, circle: Hashable) -> np.ndarray:
        """The fitted centre of a circle of the window, shape (2,), px."""
        return self.fit.centers[self.circles.index(circle)].copy()  # type: ignore[union-attr]

    def displacements(self) -> dict[Hashable, np.ndarray]:
        """Junction -> its fitted displacement d_k, shape (2,), px."""
        if self.fit is None:
            return {}
        return {n: self.fit.displacements[i].copy() for i, n in enumerate(self.junctions)}


def fit_window(
    points: Mapping[Hashable, np.ndarray],
    radii: Mapping[Hashable, float],
    centers: Mapping[Hashable, np.ndarray],
    circle_junctions: Mapping[Hashable, Sequence[Hashable]],
    junction_circles: Mapping[Hashable, Iterable[Hashable]],
    junction_points: np.ndarray,
    *,
    changed: Iterable[Hashable] = (),
    free_junctions: Iterable[Hashable] = (),
    fixed: Container[Hashable] = frozenset(),
    rings: int = 2,
    first_ring: int = 1,
    order: Callable[[Hashable], Any] | None = None,
    displacements0: np.ndarray | None = None,
    n_circles: int | None = None,
    n_junctions: int | None = None,
    connectivity: bool = True,
    tol: float = CONSTRAINED_FIT_TOL,
    max_violation: float | None = None,
    constraints: Callable[[tuple[Hashable, ...], tuple[Hashable, ...]], Mapping[str, Any]] | None = None,
    tangencies: Mapping[Hashable, tuple[Hashable, Hashable]] | None = None,
    stop_when_stuck: bool = False,
) -> WindowFit:
    """The constrained fit of Eqn. 13 in a local window, grown ring by ring until it solves (Sec. 5.4).

    The window is the ``changed`` circles and every circle through a free
    junction; its junctions are all those of its circles, the free ones moving
    and the others held where they are (the boundary conditions of the
    localized fitting). When it does not solve, the junctions of its circles
    are freed too (the next ring: their other circles join the window), up to
    ``rings`` windows. Used by the progressive optimization after a merge and
    by the user edits (:mod:`img2logo.design.edits`), with one weighting: each
    circle's term is the mean squared distance of its points (``1 / (C n_i)``),
    the displacements' term ``1 / J`` (Eqn. 7 with E^sqr a mean).

    Parameters
    ----------
    points, radii, centers : mapping
        Circle -> its points (n_i, 2) px, its fixed radius px, its starting centre (2,) px.
    circle_junctions : mapping
        Circle -> the junctions it must pass through (in the order the
        constraints are written).
    junction_circles : mapping
        Junction -> the circles through it.
    junction_points : ndarray, shape (N, 2)
        The junctions p_k by index, px (the displacements are measured from them).
    changed : iterable
        Circles always in the window (the merged or edited one).
    free_junctions : iterable
        The junctions free in the first window.
    fixed : container
        Circles of the window that keep their centre (straight lines, a moved circle).
    rings : int
        Most windows tried.
    first_ring : int
        The first window solved (1: the first; a larger one when the windows
        before it are known to fail): the windows before it only grow it.
    order : callable, optional
        Sort key of the window's circles (the order of the fit's unknowns).
    displacements0 : ndarray, shape (N, 2), optional
        Starting displacements by junction index (default zeros).
    n_circles, n_junctions : int, optional
        C and J of the weights; default the window's own counts.
    connectivity : bool
        False: no constraints (Fig. 11c); the window always "solves".
    tol : float
        Tolerance of :func:`fit_constrained`, px.
    max_violation : float, optional
        A converged fit must also keep every constraint within this, px.
    constraints : callable, optional
        ``constraints(circles, junctions)`` of a window (in the fit's order):
        more keywords of :func:`fit_constrained` for it (a mirror axis).
    tangencies : mapping, optional
        Junction -> the two circles that touch there (``tangents`` of
        :func:`fit_constrained`), enforced in a window that holds the junction
        and both circles, unless both are ``fixed``.
    stop_when_stuck : bool
        Stop growing the window when a ring's fit ends at the constraint
        violation of the ring before (``STUCK_VIOLATION_CHANGE``): the merge
        loop's wider window, where the rings cost more the wider they are.

    Returns
    -------
    WindowFit
    """
    free_j = set(free_junctions)
    seeds = set(changed)
    last: WindowFit | None = None
    before: float | None = None  # the violation the ring before ended at
    touching = {} if tangencies is None else tangencies
    for ring in range(1, max(int(rings), 1) + 1):
        members = seeds | {c for n in free_j for c in junction_circles.get(n, ())}
        window = tuple(sorted(members, key=order))
        if ring < first_ring:  # a window known to fail: only grown
            grown = set(free_j).union(*(circle_junctions[c] for c in window))
            if grown == free_j:  # it holds its whole connected part already, and failed
                return WindowFit(False, window, (), frozenset(free_j), None)
            free_j = grown
            continue
        owned = [circle_junctions[c] for c in window]  # each circle's junctions, read once
        node_set = set(free_j)
        for js in owned:
            node_set.update(js)
        nodes = tuple(sorted(node_set))
        if not window and not nodes:
            return WindowFit(True, window, (), frozenset(free_j), None)
        node_index = {n: i for i, n in enumerate(nodes)}
        # Distinct and sorted, as fit_constrained makes them (sorted tuples: a lexsort of a few rows).
        incidence = sorted({(i, node_index[n]) for i, js in enumerate(owned) for n in js})
        tangents = []
        if touching:
            circle_index = {c: i for i, c in enumerate(window)}
            for n in nodes:
                pair = touching.get(n)
                if pair is None or pair[0] not in circle_index or pair[1] not in circle_index:
                    continue
                if pair[0] in fixed and pair[1] in fixed:
                    continue  # only the junction could move: two fixed circles touch or they do not
                tangents.append((circle_index[pair[0]], circle_index[pair[1]], node_index[n]))
        sets = [points[c] for c in window]
        lengths = [len(s) for s in sets]
        extra = {} if constraints is None else constraints(window, nodes)
        free_c = [i for i, c in enumerate(window) if c not in fixed]
        free_k = [node_index[n] for n in sorted(free_j)]
        weights = 1.0 / (max(n_circles or len(window), 1) * np.array(lengths))
        node_list = list(nodes)
        junc = junction_points[node_list]
        disp0 = np.zeros((len(nodes), 2)) if displacements0 is None else displacements0[node_list]
        inc = np.array(incidence, dtype=np.int64).reshape(-1, 2)
        tangents = sorted(set(tangents))
        tan = np.array(tangents, dtype=np.int64).reshape(-1, 3)
        if extra:  # a mirror axis: the public path, which places the held coordinates on it
            fit = fit_constrained(
                sets, np.array([radii[c] for c in window]), np.array([centers[c] for c in window]), junc, inc,
                displacements0=disp0, free_circles=free_c, free_junctions=free_k, segment_weight=weights,
                junction_weight=1.0 / max(n_junctions or len(nodes), 1), tol=tol, connectivity=connectivity,
                tangents=tan, **extra,
            )  # fmt: skip
        else:
            # The window's own arrays are well formed by construction (float64 points,
            # indices sorted and in range, incidence and tangent rows distinct and
            # sorted): no checks of the public boundary here. Its KKT size is counted
            # here on the lists (WindowProblem.kkt_size on its arrays, the same number).
            size = 2 * (len(free_c) + len(free_k))
            if connectivity:
                on_c = set(free_c)
                on_k = set(free_k)
                size += sum(1 for i, k in incidence if i in on_c or k in on_k)
                size += sum(1 for a, b, k in tangents if a in on_c or b in on_c or k in on_k)
            fit = solve_sqp(
                WindowProblem(
                    np.concatenate([np.asarray(s, dtype=np.float64) for s in sets]) if sets else np.zeros((0, 2)),
                    np.arange(len(window)).repeat(lengths),  # np.repeat's wrapper costs more than the copy
                    np.array([radii[c] for c in window], dtype=np.float64),
                    np.array([centers[c] for c in window], dtype=np.float64).reshape(-1, 2),
                    np.asarray(junc, dtype=np.float64).reshape(-1, 2),
                    np.asarray(disp0, dtype=np.float64).reshape(-1, 2),
                    inc, np.array(free_c, dtype=np.int64), np.array(free_k, dtype=np.int64), weights,
                    1.0 / max(n_junctions or len(nodes), 1), bool(connectivity), tan, (), float(tol),
                ),
                size=size,
            )  # fmt: skip
        ok = not connectivity or (fit.converged and (max_violation is None or fit.violation <= max_violation))
        last = WindowFit(ok, window, nodes, frozenset(free_j), fit)
        if ok:
            return last
        grown = node_set  # the free junctions and all those of the window's circles
        if grown == free_j:
            break  # the next ring would be the same window
        if stop_when_stuck and before is not None and _stuck(before, fit.violation, tol):
            break
        before = fit.violation
        free_j = grown
    assert last is not None
    return last


def _stuck(before: float, after: float, tol: float) -> bool:
    """Whether two rings' fits ended at alike violations, px (``STUCK_VIOLATION_CHANGE`` apart, plus ``tol``)."""
    return abs(after - before) <= STUCK_VIOLATION_CHANGE * max(after, before) + tol
