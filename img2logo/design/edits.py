"""User edits of a golden ratio logo (paper Sec. 7 "User edits", Fig. 17).

Starting from an automated result (an :class:`~img2logo.geometry.abstraction.Abstraction`,
e.g. ``img2logo.abstract(image).final``) the user deletes, adds, connects and
perturbs arcs "based on their underlying circles ... while still satisfying the
golden ratio constraint" (Sec. 7). Every operation here returns a NEW
abstraction and leaves its input untouched (abstractions are immutable values,
so undo is keeping the old one):

* :func:`delete_arc` removes an arc; junctions left without an arc disappear.
* :func:`add_arc` adds an arc on an existing circle between two junctions on it
  (e.g. the other side of a circle).
* :func:`connect` joins two free ends with a new golden arc.
* :func:`move_circle` moves a circle; its neighbours follow.
* :func:`change_rung` moves a circle one rung up or down the golden ladder.

The invariants of the result format (``contract/README.md``) hold after every
edit: every radius stays ``phi ** (k + bias)`` with the same bias (Eqn. 10),
and every junction lies on every arc listed at it (within ``EDIT_TOLERANCE`` =
1e-6 px), at one of its end points or, for an arc passing through, inside it.
Where the geometry changes the junctions are re-solved by the
connectivity-constrained fit of Eqn. 13
(:func:`~img2logo.fit.constrained_fit.fit_constrained`) in a local window like the
localized fitting of Sec. 5.4, and the changed arcs are re-extracted between
their (moved) junctions.

Circles are addressed by their index in ``Abstraction.circles`` (the distinct
circles of the arcs, in order of first use; several arcs may share a circle,
e.g. after :func:`add_arc`); arcs and junctions by their index in ``arcs`` and
``junctions``. Indices of later arcs, circles and junctions shift when one is
removed. Each result records the edit in ``params["edits"]``, a list of
strings such as ``"delete_arc(3)"`` appended to that of the input. ``level``,
``similarity`` (E^s), ``tolerance`` and ``arc_segments`` of surviving arcs are
those of the automated result: the edits are the user's, not a fit to the
image, and E^s is not recomputed (new arcs abstract no segment: ``()``).

Coordinates are input-image pixels (x right, y down), angles radians from +x
towards +y (:mod:`img2logo.geometry.primitives`).
"""

from __future__ import annotations

import math
import numbers
import operator
from collections.abc import Sequence

import numpy as np

from .._validation import check_instance
from ..constants import JUNCTION_TOLERANCE, LOG_PHI, MAX_LENGTH, MIN_LADDER_RADIUS
from ..errors import FitError, InvalidParameterError
from ..geometry.abstraction import Abstraction
from ..geometry.golden_ladder import GoldenLadder
from ..geometry.primitives import TAU, Arc, ArcJunctions, Circle
from .edit_refit import EDIT_TOLERANCE, changed_indices, distinct_circles, edited, format_number, incidence, refit

__all__ = ["EDIT_TOLERANCE", "add_arc", "change_rung", "connect", "delete_arc", "move_circle"]


#: Most equal steps a move or rung change is split into when a single re-fit
#: does not converge (a continuation: each step starts from the last).
_CONTINUATION_STEPS: int = 8


# --------------------------------------------------------------------------- validation
def _check_abstraction(a: object) -> Abstraction:
    return check_instance(a, Abstraction, "abstraction")


def _index(value: object, what: str, size: int) -> int:
    """``value`` as an index in 0..size-1 of an arc, circle or junction, else raise."""
    if isinstance(value, bool | np.bool_):
        raise InvalidParameterError(f"{what} index must be an integer, got {value!r}")
    try:
        i = operator.index(value)  # type: ignore[arg-type]
    except TypeError as exc:
        raise InvalidParameterError(f"{what} index must be an integer, got {value!r}") from exc
    if not 0 <= i < size:
        raise InvalidParameterError(
            f"{what} index {i} is out of range: the abstraction has {size} {what}s (valid: 0..{size - 1})"
            if size
            else f"{what} index {i} is out of range: the abstraction has no {what}s"
        )
    return i


def _sign(value: object, name: str) -> int:
    if isinstance(value, bool | np.bool_) or not isinstance(value, numbers.Real) or value not in (1, -1):
        raise InvalidParameterError(f"{name} must be +1 or -1, got {value!r}")
    return 1 if value == 1 else -1


def _phi_ladder(a: Abstraction, op: str) -> GoldenLadder:
    """The abstraction's phi ladder (the edits keep r = phi**(k+bias)); raise on the Fibonacci ladder."""
    if not isinstance(a.ladder, GoldenLadder):
        raise InvalidParameterError(
            f"{op} supports only the golden ratio ladder r = phi**(k+bias), got the Fibonacci ladder "
            f"(unit {getattr(a.ladder, 'unit', None)!r} px)"
        )
    return a.ladder


# --------------------------------------------------------------------------- the edits
def delete_arc(abstraction: Abstraction, arc: int) -> Abstraction:
    """Delete one arc (Sec. 7, Fig. 17: "delete").

    The other arcs keep their geometry. Junctions left with no arc are dropped;
    arc indices in ``junction_arcs`` above ``arc`` shift down by one, and so do
    junction indices after a dropped junction. Deleting an arc may turn the
    ends of its neighbours into free ends (see :func:`connect`).

    Parameters
    ----------
    abstraction : Abstraction
        The logo to edit (unchanged).
    arc : int
        Index of the arc to delete, in ``abstraction.arcs``.

    Returns
    -------
    Abstraction
        The edited logo; ``params["edits"]`` ends with ``"delete_arc(<arc>)"``.

    Raises
    ------
    InvalidParameterError
        If ``arc`` is not an integer index of an arc, or it is the only arc.
    """
    a = _check_abstraction(abstraction)
    i = _index(arc, "arc", len(a.arcs))
    if len(a.arcs) == 1:
        raise InvalidParameterError(f"cannot delete arc {i}: it is the only arc, and an abstraction needs one")
    renumber = {old: old - (old > i) for old in range(len(a.arcs)) if old != i}
    kept_j, junction_arcs = [], []
    for j, entries in enumerate(a.junction_arcs):
        left = tuple(renumber[int(x)] for x in entries if int(x) != i)
        if left:
            kept_j.append(j)
            junction_arcs.append(left)
    new_index = {j: n for n, j in enumerate(kept_j)}
    return edited(
        a,
        f"delete_arc({i})",
        arcs=a.arcs[:i] + a.arcs[i + 1 :],
        arc_segments=a.arc_segments[:i] + a.arc_segments[i + 1 :],
        junctions=a.junctions[kept_j],
        junction_arcs=junction_arcs,
        arc_junctions=[t.renumbered(new_index) for n, t in enumerate(a.arc_junctions) if n != i],
        junction_nodes=[a.junction_nodes[j] for j in kept_j],
    )


def add_arc(abstraction: Abstraction, circle: int | Circle, j0: int, j1: int, *, sweep_sign: int = +1) -> Abstraction:
    """Add an arc on an existing circle between two junctions on it (Sec. 7, Fig. 17: "add").

    The new arc runs from junction ``j0`` to junction ``j1`` around the circle
    in the sense ``sweep_sign`` (+1: increasing angle, clockwise on screen with
    y down; -1: the other way). For a circle carrying an arc from ``j0`` to
    ``j1``, the opposite ``sweep_sign`` adds its other side. The arc is appended
    (index ``len(abstraction.arcs)``), listed at both junctions, and shares the
    circle with its other arcs. A junction within 1e-3 px of the circle but
    farther than ``EDIT_TOLERANCE`` is put on it by the constrained re-fit of
    the circles meeting there (as :func:`move_circle`).

    Parameters
    ----------
    abstraction : Abstraction
        The logo to edit (unchanged).
    circle : int or Circle
        Index in ``abstraction.circles``, or a circle of the logo itself, e.g.
        ``abstraction.arcs[i].circle`` for the circle of arc i.
    j0, j1 : int
        Indices of the start and end junctions, different, both on the circle.
    sweep_sign : {+1, -1}
        Sense of the new arc.

    Returns
    -------
    Abstraction
        The edited logo; ``params["edits"]`` ends with
        ``"add_arc(circle=<c>, j0=<j0>, j1=<j1>, sweep_sign=<s>)"``.

    Raises
    ------
    InvalidParameterError
        On a bad index, equal junctions, a junction farther than 1e-3 px from the
        circle, or an arc that the circle already has between the two junctions.
    FitError
        If the re-fit putting the junctions on the circle does not converge.
    """
    a = _check_abstraction(abstraction)
    circles = a.circles
    if isinstance(circle, Circle):
        if circle not in circles:
            raise InvalidParameterError(f"circle {circle} is not a circle of the abstraction")
        ci = circles.index(circle)
    else:
        ci = _index(circle, "circle", len(circles))
    n_j = len(a.junctions)
    j0, j1 = _index(j0, "junction", n_j), _index(j1, "junction", n_j)
    sign = _sign(sweep_sign, "sweep_sign")
    if j0 == j1:
        raise InvalidParameterError(f"add_arc needs two different junctions, got junction {j0} twice")
    c = circles[ci]
    for j in (j0, j1):
        off = abs(float(c.distance(a.junctions[j])))
        if off > JUNCTION_TOLERANCE:
            raise InvalidParameterError(
                f"junction {j} at ({a.junctions[j][0]:.6g}, {a.junctions[j][1]:.6g}) is {off:.3g} px off circle "
                f"{ci} (centre ({c.cx:.6g}, {c.cy:.6g}), r={c.r:.6g}), more than {JUNCTION_TOLERANCE:g} px: "
                "add_arc needs two junctions on the circle"
            )
    theta = c.angle_of(a.junctions[[j0, j1]])
    sweep = sign * float(np.mod(sign * (theta[1] - theta[0]), TAU))
    if min(abs(sweep), TAU - abs(sweep)) * c.r <= JUNCTION_TOLERANCE:
        raise InvalidParameterError(f"junctions {j0} and {j1} coincide on circle {ci}: no arc runs between them")
    new_arc = Arc(c, float(theta[0]), sweep)
    ends = a.arc_junctions
    for i, (arc, e) in enumerate(zip(a.arcs, ends, strict=True)):
        same = (e.start, e.end, math.copysign(1, arc.sweep)) in ((j0, j1, sign), (j1, j0, -sign))
        if arc.circle == c and same:
            raise InvalidParameterError(
                f"arc {i} already runs on circle {ci} between junctions {j0} and {j1} that way round; "
                f"sweep_sign={-sign} adds the circle's other side"
            )
    edit = f"add_arc(circle={ci}, j0={j0}, j1={j1}, sweep_sign={sign})"
    arcs = (*a.arcs, new_arc)
    n = len(a.arcs)
    junction_arcs = [tuple(js) + ((n,) if j in (j0, j1) else ()) for j, js in enumerate(a.junction_arcs)]
    junctions = np.array(a.junctions, dtype=np.float64)
    offsets = np.abs(c.distance(a.junctions[[j0, j1]]))
    if offsets.max() > EDIT_TOLERANCE:
        arcs, junctions = refit(
            arcs,
            junctions,
            junction_arcs,
            [*ends, ArcJunctions(j0, j1, ())],
            new_circles={},
            fixed=set(),
            free_junctions={j0, j1},
            references={},
            edit=edit,
        )
    return edited(
        a,
        edit,
        arcs=arcs,
        arc_segments=(*a.arc_segments, ()),
        junctions=junctions,
        junction_arcs=junction_arcs,
        arc_junctions=(*a.arc_junctions, ArcJunctions(j0, j1)),
        changed_arcs=changed_indices(a.arcs, arcs),
    )


def connect(abstraction: Abstraction, j0: int, j1: int, *, k: int | None = None, side: int = +1) -> Abstraction:
    """Connect two free ends with a new golden arc (Sec. 7, Fig. 17: "connect").

    A free end is a junction with a single arc ending there. The new arc lies
    on a new golden circle of radius ``r = phi ** (k + bias)`` (Eqn. 10) through
    both junctions, and is the shorter of its two arcs between them
    (``|sweep| <= pi``), from ``j0`` to ``j1``. Of the two such circles, ``side``
    chooses the centre: with ``u`` the unit vector from ``j0`` to ``j1`` and
    ``n = (-u_y, u_x)`` (u turned by +90 degrees, clockwise on screen), the
    centre is ``midpoint + side * sqrt(r^2 - (d/2)^2) * n``, and the arc bulges
    the other way, towards ``-side * n``. No junction moves.

    Parameters
    ----------
    abstraction : Abstraction
        The logo to edit (unchanged).
    j0, j1 : int
        Indices of two different free-end junctions.
    k : int, optional
        Ladder exponent of the new circle. Default: the smallest rung whose
        circle passes through both points, ``2 r >= d`` with ``d`` their distance
        in px (among ``abstraction.ladder.exponents`` when the run restricted the ladder,
        Sec. 7, Fig. 15). Larger k gives a flatter arc.
    side : {+1, -1}
        Which of the two circles through the points (see above).

    Returns
    -------
    Abstraction
        The edited logo with the new arc appended and listed at both junctions;
        ``params["edits"]`` ends with ``"connect(j0=<j0>, j1=<j1>, k=<k>, side=<side>)"``
        with the k used.

    Raises
    ------
    InvalidParameterError
        On a bad index, equal or coincident junctions, a junction that is not a
        free end, a ``k`` whose diameter is shorter than the distance, or a
        Fibonacci-ladder abstraction.
    """
    a = _check_abstraction(abstraction)
    ladder = _phi_ladder(a, "connect")
    n_j = len(a.junctions)
    j0, j1 = _index(j0, "junction", n_j), _index(j1, "junction", n_j)
    s = _sign(side, "side")
    if j0 == j1:
        raise InvalidParameterError(f"connect needs two different junctions, got junction {j0} twice")
    ends = a.arc_junctions
    for j in (j0, j1):
        listed = sorted(set(a.junction_arcs[j]))
        if len(listed) != 1 or j not in (ends[listed[0]].start, ends[listed[0]].end):
            raise InvalidParameterError(
                f"junction {j} is not a free end: {len(listed)} arcs meet there "
                "(connect needs two junctions with one arc ending at each)"
            )
    p0, p1 = a.junctions[j0], a.junctions[j1]
    d = math.dist(p0, p1)
    if d <= EDIT_TOLERANCE:
        raise InvalidParameterError(f"junctions {j0} and {j1} coincide ({d:.3g} px apart): no arc connects them")
    k_min = math.floor(math.log(d / 2) / LOG_PHI - a.bias) - 1
    while 2 * ladder.radius(k_min) < d:
        k_min += 1
    if k is None:
        allowed = a.ladder.exponents
        if allowed:
            big = sorted(int(e) for e in allowed if int(e) >= k_min)
            if not big:
                raise InvalidParameterError(
                    f"no rung among the ladder's exponents {sorted(int(e) for e in allowed)} can connect junctions "
                    f"{j0} and {j1} ({d:.6g} px apart): it needs k >= {k_min}"
                )
            k_used = big[0]
        else:
            k_used = k_min
    else:
        if isinstance(k, bool | np.bool_) or not isinstance(k, numbers.Integral):
            raise InvalidParameterError(f"k must be an integer, got {k!r}")
        k_used = int(k)
        if k_used < k_min:
            r = ladder.radius(k_used)
            raise InvalidParameterError(
                f"rung k={k_used} (r={r:.6g} px) is too small to connect junctions {j0} and {j1}: they are "
                f"{d:.6g} px apart, more than its diameter {2 * r:.6g} px; use k >= {k_min}"
            )
    r = ladder.radius(k_used)
    u = (p1 - p0) / d
    normal = np.array([-u[1], u[0]])
    h = math.sqrt(max(r * r - d * d / 4, 0.0))
    center = (p0 + p1) / 2 + s * h * normal
    circle = Circle(float(center[0]), float(center[1]), r, k_used)
    theta0 = float(circle.angle_of(p0))
    bulge = math.atan2(-s * normal[1], -s * normal[0])  # direction of the arc's midpoint
    half = math.remainder(bulge - theta0, TAU)
    new_arc = Arc(circle, theta0, 2.0 * half)
    n = len(a.arcs)
    junction_arcs = [tuple(js) + ((n,) if j in (j0, j1) else ()) for j, js in enumerate(a.junction_arcs)]
    return edited(
        a,
        f"connect(j0={j0}, j1={j1}, k={k_used}, side={s})",
        arcs=(*a.arcs, new_arc),
        arc_segments=(*a.arc_segments, ()),
        junction_arcs=junction_arcs,
        arc_junctions=(*a.arc_junctions, ArcJunctions(j0, j1)),
        changed_arcs=(n,),
    )


def move_circle(abstraction: Abstraction, circle: int, new_center: Sequence[float] | np.ndarray) -> Abstraction:
    """Move a circle; its junctions and neighbours follow (Sec. 7, Fig. 17: "perturb").

    The circle keeps its radius and is fixed at ``new_center``. Its junctions
    are carried along with it and then re-solved together with the
    neighbouring circles (those of the other arcs at these junctions) by the
    constrained fit of Eqn. 13 (:func:`~img2logo.fit.constrained_fit.fit_constrained`):
    every junction stays on all its circles, the neighbours keep radii and
    their other junctions, and stay as close as they can to their arcs' current
    points (sampled 1 px apart), the junctions to the carried-along points. If
    that window has no solution, the neighbours' junctions and their circles
    are freed too (the second ring of Sec. 5.4). Every changed arc is then
    re-extracted between its junctions, the same way round as before.

    Parameters
    ----------
    abstraction : Abstraction
        The logo to edit (unchanged).
    circle : int
        Index in ``abstraction.circles``.
    new_center : array_like, shape (2,)
        The new centre (x, y), px.

    Returns
    -------
    Abstraction
        The edited logo; ``params["edits"]`` ends with
        ``"move_circle(<circle>, (<x>, <y>))"``.

    Raises
    ------
    InvalidParameterError
        On a bad index or a centre that is not a finite point.
    FitError
        If the junctions cannot stay on their circles (the re-fit does not converge).
    """
    a = _check_abstraction(abstraction)
    circles = a.circles
    ci = _index(circle, "circle", len(circles))
    try:
        center = np.asarray(new_center, dtype=np.float64)
    except (TypeError, ValueError) as exc:
        raise InvalidParameterError(f"new_center must be a finite point (x, y), got {new_center!r}") from exc
    if center.shape != (2,) or not np.all(np.isfinite(center)):
        raise InvalidParameterError(f"new_center must be a finite point (x, y), got {new_center!r}")
    old = circles[ci]
    moved = Circle(float(center[0]), float(center[1]), old.r, old.k)
    edit = f"move_circle({ci}, ({format_number(center[0])}, {format_number(center[1])}))"
    return _change_circle(a, ci, moved, fixed=True, carry=True, edit=edit)


def change_rung(abstraction: Abstraction, circle: int, delta: int = +1) -> Abstraction:
    """Move a circle ``delta`` rungs along the golden ladder (Sec. 7; Eqn. 10, 11).

    The radius becomes ``phi ** (k + delta + bias)``, i.e. ``r * phi ** delta``,
    the bias unchanged. Its centre, its junctions and the neighbouring circles
    are then re-solved as in :func:`move_circle`, the circle's own centre free
    too (starting where the new radius fits its arcs best), the junctions
    staying as close as they can to where they are; the changed arcs are
    re-extracted between their junctions.

    Parameters
    ----------
    abstraction : Abstraction
        The logo to edit (unchanged).
    circle : int
        Index in ``abstraction.circles``; it must have a ladder exponent k.
    delta : int
        Rungs to move, nonzero: +1 one rung up (larger, flatter), -1 one down.

    Returns
    -------
    Abstraction
        The edited logo; ``params["edits"]`` ends with ``"change_rung(<circle>, delta=<delta>)"``.

    Raises
    ------
    InvalidParameterError
        On a bad index, a ``delta`` that is not a nonzero integer, a circle
        without k, or a Fibonacci-ladder abstraction.
    FitError
        If the junctions cannot stay on their circles (the re-fit does not converge).
    """
    a = _check_abstraction(abstraction)
    ladder = _phi_ladder(a, "change_rung")
    circles = a.circles
    ci = _index(circle, "circle", len(circles))
    if isinstance(delta, bool | np.bool_) or not isinstance(delta, numbers.Integral) or delta == 0:
        raise InvalidParameterError(f"delta must be a nonzero integer, got {delta!r}")
    old = circles[ci]
    if old.k is None:
        raise InvalidParameterError(f"circle {ci} has no ladder exponent k: change_rung needs a golden circle")
    k = old.k + int(delta)
    # Within the radii a ladder may offer (what the contract reads back), checked in log space before any
    # work: a circle of 1e15 px was written and then refused, and its arcs, sampled per pixel, exhaust memory.
    log_r = (k + ladder.bias) * LOG_PHI
    if not math.log(MIN_LADDER_RADIUS) <= log_r <= math.log(MAX_LENGTH):
        raise InvalidParameterError(
            f"change_rung: circle {ci} moved {int(delta)} rungs would have r = phi**{k + ladder.bias:.6g} px; "
            f"a ladder offers {MIN_LADDER_RADIUS:g} to {MAX_LENGTH:g} px"
        )
    r = ladder.radius(k)
    changed = Circle(old.cx, old.cy, r, k)
    edit = f"change_rung({ci}, delta={int(delta)})"
    return _change_circle(a, ci, changed, fixed=False, carry=False, edit=edit)


def _change_circle(a: Abstraction, ci: int, target: Circle, *, fixed: bool, carry: bool, edit: str) -> Abstraction:
    """Replace distinct circle ``ci`` by ``target`` and re-fit its window (move_circle, change_rung).

    When one re-fit does not converge, the change is made in ``2, 4, ...,
    _CONTINUATION_STEPS`` equal steps (centre interpolated linearly, radius
    geometrically), each re-fit starting from the last: a continuation that
    follows the solution for large moves.
    """
    _, arc_circle = distinct_circles(a.arcs)
    circle_junctions, _ = incidence(arc_circle, len(a.circles), a.junction_arcs)
    own = set(circle_junctions[ci])
    ends = a.arc_junctions
    old = a.circles[ci]
    error: FitError | None = None
    n = 1
    while n <= _CONTINUATION_STEPS:
        arcs, junctions = a.arcs, a.junctions
        try:
            for step in range(1, n + 1):
                t = step / n
                current = distinct_circles(arcs)[0][ci]
                new = target
                if step < n:
                    center = old.center + t * (target.center - old.center)
                    new = Circle(float(center[0]), float(center[1]), old.r * (target.r / old.r) ** t, None)
                shift = new.center - current.center
                arcs, junctions = refit(
                    arcs,
                    junctions,
                    a.junction_arcs,
                    ends,
                    new_circles={ci: new},
                    fixed={ci} if fixed else set(),
                    free_junctions=own,
                    references={j: junctions[j] + shift for j in own} if carry else {},
                    edit=edit,
                )
        except FitError as exc:
            error = exc if error is None else error
            n *= 2
            continue
        return edited(a, edit, arcs=arcs, junctions=junctions, changed_arcs=changed_indices(a.arcs, arcs))
    assert error is not None
    raise error
