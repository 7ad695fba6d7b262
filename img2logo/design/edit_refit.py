"""The local re-solve behind every user edit (:mod:`img2logo.design.edits`; paper Sec. 7, Eqn. 13, Sec. 5.4).

An edit changes a circle or an arc; :func:`refit` re-solves the junctions and the
neighbouring circles around it by the connectivity-constrained fit of Eqn. 13 in a
local window (:func:`~img2logo.fit.local_window.fit_window`, grown ring by ring like
the localized fitting of Sec. 5.4), :func:`reextract` runs each changed arc between
its moved junctions, and :func:`edited` assembles the new abstraction, recording the
edit, after :func:`check_connected` has checked that every junction still lies on
its arcs within ``EDIT_TOLERANCE``.

Coordinates are input-image pixels (x right, y down), angles radians from +x
towards +y (:mod:`img2logo.geometry.primitives`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from ..errors import FitError
from ..fit.local_window import fit_window
from ..geometry.abstraction import Abstraction
from ..geometry.circle_fitting import fit_center
from ..geometry.primitives import TAU, Arc, ArcJunctions, Circle

__all__ = [
    "EDIT_TOLERANCE",
    "changed_indices",
    "check_connected",
    "distinct_circles",
    "edited",
    "format_number",
    "incidence",
    "reextract",
    "refit",
]


#: After an edit every junction lies on the circle of every arc listed at it, and
#: at an end point of that arc (or inside it, for an arc passing through), within
#: this distance, px. It is the tolerance of the constrained re-fit (Eqn. 13).
EDIT_TOLERANCE: float = 1e-6

#: Spacing of the points sampled along an arc that the re-fit of a changed
#: neighbour keeps its circle close to (the E^l term of Eqn. 7), px.
_SAMPLE_STEP: float = 1.0

#: Windows of the re-fit tried before giving up: the edited circle's junctions
#: and its neighbours first; then also the neighbours' junctions and their
#: circles (the second ring of the localized fitting, Sec. 5.4).
_RINGS: int = 2


# --------------------------------------------------------------------------- topology
def distinct_circles(arcs: Sequence[Arc]) -> tuple[list[Circle], list[int]]:
    """The distinct circles (order of first use, as ``Abstraction.circles``) and each arc's index."""
    index: dict[Circle, int] = {}
    for arc in arcs:
        index.setdefault(arc.circle, len(index))
    return list(index), [index[arc.circle] for arc in arcs]


def incidence(
    arc_circle: Sequence[int], n_circles: int, junction_arcs: Sequence[Sequence[int]]
) -> tuple[list[set[int]], list[set[int]]]:
    """Junctions of each circle and circles at each junction (through the listed arcs)."""
    circle_junctions: list[set[int]] = [set() for _ in range(n_circles)]
    junction_circles: list[set[int]] = [set() for _ in junction_arcs]
    for j, entries in enumerate(junction_arcs):
        for i in entries:
            c = arc_circle[int(i)]
            circle_junctions[c].add(j)
            junction_circles[j].add(c)
    return circle_junctions, junction_circles


# --------------------------------------------------------------------------- re-extraction
def reextract(old: Arc, circle: Circle, ends: ArcJunctions, junctions: np.ndarray, edit: str) -> Arc:
    """The arc ``old`` on its changed ``circle``, running between its (moved) junctions.

    The start and end angles are those of the arc's junctions on the new circle
    (an end without a junction keeps its angle). Of the two arcs between them,
    the same way round as ``old`` and the other, the one whose sweep is nearer
    ``old.sweep`` is taken (it keeps the orientation and the long or short way
    of a continuous deformation), among those still containing the junctions
    the arc passes through. A full circle stays a full circle.

    Raises
    ------
    FitError
        If no arc between the junctions contains the inner junctions, or the
        start and end junction have come together.
    """
    theta0 = float(circle.angle_of(junctions[ends.start])) if ends.start is not None else old.theta0
    make = type(old)  # a line stays a line
    if old.is_full_circle:
        return make(circle, theta0, old.sweep)
    theta1 = float(circle.angle_of(junctions[ends.end])) if ends.end is not None else old.theta0 + old.sweep
    sense = math.copysign(1.0, old.sweep)
    same_way = sense * float(np.mod(sense * (theta1 - theta0), TAU))
    inner = circle.angle_of(junctions[list(ends.through)]) if ends.through else np.zeros(0)
    options = []
    for sweep in (same_way, same_way - sense * TAU):
        if abs(sweep) * circle.r <= EDIT_TOLERANCE or (TAU - abs(sweep)) * circle.r <= EDIT_TOLERANCE:
            continue  # the two ends coincide: no arc left between them
        arc = make(circle, theta0, sweep)
        if np.all(arc.contains_angle(inner, tol=EDIT_TOLERANCE / circle.r)):
            options.append(arc)
    if not options:
        raise FitError(f"{edit} cannot keep the junctions connected: an arc no longer runs through its junctions")
    return min(options, key=lambda arc: abs(arc.sweep - old.sweep))


# --------------------------------------------------------------------------- the re-fit
def refit(
    arcs: Sequence[Arc],
    junctions: np.ndarray,
    junction_arcs: Sequence[Sequence[int]],
    ends: Sequence[ArcJunctions],
    *,
    new_circles: dict[int, Circle],
    fixed: set[int],
    free_junctions: set[int],
    references: dict[int, np.ndarray],
    edit: str,
) -> tuple[tuple[Arc, ...], np.ndarray]:
    """Re-solve the junctions and neighbouring circles around an edit (Eqn. 13, Sec. 5.4).

    Parameters
    ----------
    arcs, junctions, junction_arcs, ends
        The state before the re-fit: arcs, (J, 2) junction points px, the arcs
        listed at each junction, and the junctions of each arc (``Abstraction.arc_junctions``).
    new_circles : dict
        Distinct-circle index -> the user's new circle (moved, or a new radius):
        its start value in the fit.
    fixed : set of int
        Distinct circles held fixed (a moved circle stays where it was put).
    free_junctions : set of int
        Junctions that may move (the window's first ring).
    references : dict
        Junction index -> the point (2,) its displacement is measured from, px
        (default: where it is). A moved circle carries its junctions along.
    edit : str
        The edit, for the error message.

    Returns
    -------
    arcs : tuple of Arc
        The arcs, those on changed circles re-extracted.
    junctions : ndarray, shape (J, 2)
        The junctions, px.

    Raises
    ------
    FitError
        If the constrained fit does not converge in the widest window.
    """
    circles, arc_circle = distinct_circles(arcs)
    circle_junctions, junction_circles = incidence(arc_circle, len(circles), junction_arcs)
    start = {c: new_circles.get(c, circles[c]) for c in range(len(circles))}
    samples: list[list[np.ndarray]] = [[] for _ in circles]
    for arc, c in zip(arcs, arc_circle, strict=True):
        samples[c].append(arc.sample(_SAMPLE_STEP, min_points=3))
    points = {c: np.concatenate(samples[c]) for c in range(len(circles))}
    ref = np.array(junctions, dtype=np.float64, copy=True).reshape(-1, 2)
    for j, p in references.items():
        ref[j] = p
    centers = {}
    for c in range(len(circles)):
        center = start[c].center
        if c in new_circles and c not in fixed and not math.isclose(start[c].r, circles[c].r):
            # A new radius: start where that radius fits the arcs' points best.
            center = fit_center(points[c], start[c].r, center)
        centers[c] = center
    # The window of the localized fitting (Sec. 5.4), as the optimization solves it.
    window = fit_window(
        points,
        {c: start[c].r for c in range(len(circles))},
        centers,
        {c: sorted(js) for c, js in enumerate(circle_junctions)},
        {j: cs for j, cs in enumerate(junction_circles)},
        ref,
        changed=new_circles,
        free_junctions=free_junctions,
        fixed=fixed,
        rings=_RINGS,
        tol=EDIT_TOLERANCE / 10,
        max_violation=EDIT_TOLERANCE,
    )
    if not window.ok:
        violation = math.nan if window.fit is None else window.fit.violation
        raise FitError(
            f"{edit} cannot keep the junctions connected: the constrained fit (Eqn. 13) did not converge "
            f"(largest junction-circle gap {violation:.3g} px)"
        )

    new = dict(start)
    out_junctions = np.array(junctions, dtype=np.float64, copy=True).reshape(-1, 2)
    if window.fit is not None:
        for c in window.circles:
            cx, cy = window.center(c)
            new[c] = Circle(float(cx), float(cy), start[c].r, start[c].k)
        for j, d in window.displacements().items():
            out_junctions[j] = ref[j] + d
    changed = {c for c in range(len(circles)) if new[c] != circles[c]} | set(new_circles)
    out_arcs = tuple(
        reextract(arc, new[c], e, out_junctions, edit) if c in changed else arc
        for arc, c, e in zip(arcs, arc_circle, ends, strict=True)
    )
    return out_arcs, out_junctions


# --------------------------------------------------------------------------- assembling
def edited(
    a: Abstraction,
    edit: str,
    *,
    arcs: Sequence[Arc] | None = None,
    arc_segments: Sequence[Sequence[int]] | None = None,
    junctions: np.ndarray | None = None,
    junction_arcs: Sequence[Sequence[int]] | None = None,
    arc_junctions: Sequence[ArcJunctions] | None = None,
    junction_nodes: Sequence[int | None] | None = None,
    changed_arcs: Sequence[int] = (),
) -> Abstraction:
    """A copy of ``a`` with the given parts replaced and ``edit`` appended to ``params["edits"]``.

    Checks first that every junction that moved, and every junction of the
    arcs in ``changed_arcs`` (new indices), lies on its arcs (at an end or
    inside) within ``EDIT_TOLERANCE`` px, and raises FitError if not. The rest
    is as connected as it was in ``a``. The ladder, the topology (unless
    replaced) and the graph nodes of the junctions are ``a``'s.
    """
    arcs = tuple(a.arcs if arcs is None else arcs)
    points = np.array(a.junctions if junctions is None else junctions, dtype=np.float64).reshape(-1, 2)
    listed = tuple(tuple(int(i) for i in js) for js in (a.junction_arcs if junction_arcs is None else junction_arcs))
    moved = set()
    if junctions is not None and len(points) == len(a.junctions):
        moved = set(np.flatnonzero(np.any(points != a.junctions, axis=1)).tolist())
    check_connected(arcs, points, listed, edit, set(changed_arcs), moved)
    return Abstraction(
        level=a.level,
        arcs=arcs,
        arc_segments=tuple(tuple(s) for s in (a.arc_segments if arc_segments is None else arc_segments)),
        junctions=points,
        junction_arcs=listed,
        similarity=a.similarity,
        bias=a.bias,
        tolerance=a.tolerance,
        width=a.width,
        height=a.height,
        params={**a.params, "edits": (*a.params.get("edits", ()), edit)},
        ladder=a.ladder,
        arc_junctions=tuple(a.arc_junctions if arc_junctions is None else arc_junctions),
        junction_nodes=tuple(a.junction_nodes if junction_nodes is None else junction_nodes),
        connected=a.connected,
    )


def check_connected(
    arcs: Sequence[Arc],
    points: np.ndarray,
    junction_arcs: Sequence[Sequence[int]],
    edit: str,
    changed: set[int],
    junctions: set[int],
) -> None:
    """Raise FitError unless the junctions listed at the ``changed`` arcs, and ``junctions``, lie on their arcs."""
    for j, (point, entries) in enumerate(zip(points, junction_arcs, strict=True)):
        for i in entries:
            if i not in changed and j not in junctions:
                continue
            arc = arcs[i]
            off = abs(float(arc.circle.distance(point)))
            at_end = min(math.dist(point, arc.start), math.dist(point, arc.end)) <= EDIT_TOLERANCE
            inside = bool(arc.contains_angle(float(arc.circle.angle_of(point)), tol=EDIT_TOLERANCE / arc.circle.r))
            if off > EDIT_TOLERANCE or not (at_end or inside):
                where = f"{off:.3g} px off the circle of arc {i}" if off > EDIT_TOLERANCE else f"not on arc {i}"
                raise FitError(f"{edit} cannot keep the junctions connected: junction {j} is {where}")


def changed_indices(old: Sequence[Arc], new: Sequence[Arc]) -> list[int]:
    """Indices of the arcs of ``new`` that are not those of ``old`` (new ones included)."""
    return [i for i, arc in enumerate(new) if i >= len(old) or arc is not old[i]]


def format_number(x: float) -> str:
    """``x`` as an edit records it in ``params["edits"]``: the shortest repr that reads back the same float."""
    return repr(float(x))
