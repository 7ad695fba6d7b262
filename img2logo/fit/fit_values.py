"""The values of the progressive optimization's state (paper Sec. 5.2-5.4): seeds, fits, counts, the axis.

A group's circle on the ladder before its constrained fit (:class:`Seed`, Eqn. 12) and its golden
circle and arc after it (:class:`GroupFit`); the counts of one run (:class:`Stats`); what a
symmetric run holds on its mirror axis (:class:`AxisConstraints`, :func:`on_axis`) and the free
circles of its groups (:class:`FreeCircles`); a constrained fit's new fits and displacements
(:data:`Solution`) and the split of groups anew before their arcs are extracted (:data:`Regroup`);
and a free end's near miss of an arc (:func:`near_miss`). The state that holds them is
:class:`img2logo.fit.fit_state.FitState`.

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from functools import cached_property
from typing import NamedTuple, Protocol, TypeAlias

import numpy as np

from ..constants import GAP_MAX, GAP_MIN
from ..geometry.circle_fitting import fit_circle, mean_abs_error
from .arc_extraction import ArcFit
from .simplification import Group

__all__ = ["AxisConstraints", "FreeCircles", "GroupFit", "Seed", "Stats"]


# --------------------------------------------------------------------------- values
class Seed(NamedTuple):
    """A group's circle before the constrained fit: its centre, its radius on the ladder, its rung.

    Attributes
    ----------
    center : ndarray, shape (2,)
        The starting centre, px.
    radius : float
        The fixed radius, px: ``ladder.radius(k)`` (Eqn. 12), or ``LINE_RADIUS``
        for a straight line.
    k : int or None
        The ladder exponent; None for a straight line (held fixed in the fit).
    """

    center: np.ndarray
    radius: float
    k: int | None


@dataclass(frozen=True, eq=False)
class GroupFit:
    """A group's golden circle after the constrained fit (Eqn. 13) and its arc.

    Attributes
    ----------
    center : ndarray, shape (2,)
        The fitted centre, px.
    radius : float
        The radius, px (the seed's: radii stay on their rungs).
    k : int or None
        The ladder exponent; None for a straight line.
    arc : ArcFit
        The arc extracted on the circle and its discrete Fréchet distance to the group's pixels, px.
    """

    center: np.ndarray
    radius: float
    k: int | None
    arc: ArcFit

    @cached_property
    def seed(self) -> Seed:
        """This circle as the start of the next fit (made once: every candidate merge's window asks)."""
        return Seed(self.center, self.radius, self.k)

    @cached_property
    def arc_row(self) -> tuple[float, float, float, float, float]:
        """The arc as (cx, cy, r, theta0, sweep), the compiled redundant-intersection test's row (made once)."""
        a = self.arc.arc
        return (a.circle.cx, a.circle.cy, a.circle.r, a.theta0, a.sweep)


@dataclass
class Stats:
    """Counts of one run, reported in :attr:`img2logo.fit.progressive.Progression.stats` (as a dict, in this order).

    Attributes
    ----------
    evaluated : int
        Merge candidates evaluated (:func:`img2logo.fit.merging.evaluate`).
    local_failed : int
        Local windows (Sec. 5.4) that did not solve.
    global_solves : int
        Solves of the whole problem (:func:`~img2logo.fit.window_solve.solve_whole`).
    rejected_hopeless : int
        Candidates rejected without a global solve: their own golden circle is off by more than T.
    rejected_intersections : int
        Candidates left with redundant intersections (Fig. 12) when the loop stopped.
    rejected_far_arc : int
        Candidates whose arc strays farther than ``max_arc_distance``: found by
        their fit, or before it where no circle of their radius comes that near.
    released_junctions : int
        Junctions whose connectivity constraint was given up (:func:`img2logo.fit.recovery.recover`).
    tangent_joins : int
        Smooth joins whose circles touch in the result (:mod:`img2logo.fit.tangency`).
    released_tangencies : int
        Smooth joins whose tangency was given up.
    rejected_crossing : int
        Candidates rejected because another arc runs on through their junction (an X), or
        because their arc would run on past an end of its path through a junction another arc
        runs on through (checked for the merge the loop chose, :func:`img2logo.fit.merging.merge_loop`).
    rejected_gaps : int
        Candidates left with a near-miss gap they would make (a free end brought 0.75-6 px
        from an arc; checked for the merge the loop chose, :func:`img2logo.fit.merging.merge_loop`)
        when the loop stopped.
    split_groups : int
        Groups of the line-segment simplification split into their segments again because
        their arc in A^0 made a redundant intersection (:func:`img2logo.fit.progressive.split_crossed`).
    wide_windows : int
        Merge candidates whose local window failed, refitted in the wider window of
        ``MERGE_FALLBACK_RINGS`` rings instead (:func:`img2logo.fit.merging.evaluate`).
    """

    evaluated: int = 0
    local_failed: int = 0
    global_solves: int = 0
    rejected_hopeless: int = 0
    rejected_intersections: int = 0
    rejected_far_arc: int = 0
    released_junctions: int = 0
    tangent_joins: int = 0
    released_tangencies: int = 0
    rejected_crossing: int = 0
    rejected_gaps: int = 0
    split_groups: int = 0
    wide_windows: int = 0

    def as_dict(self) -> dict[str, int]:
        """The counts by name, in the order of the fields."""
        return dataclasses.asdict(self)


class AxisConstraints(Protocol):
    """The mirror axis of a symmetric run, as the state reads it (:class:`img2logo.fit.symmetry.HalfAxis`).

    The graph is one half of a mirror-symmetric drawing, in a frame where the
    axis is the vertical line x = ``x`` px; junctions ``nodes`` stay on it, and
    a group whose end (segment, node) is in ``smooth`` has its circle centred on it.
    """

    @property
    def x(self) -> float: ...

    @property
    def nodes(self) -> frozenset[int]: ...

    @property
    def smooth(self) -> frozenset[tuple[int, int]]: ...

    def mirror(self, points: np.ndarray) -> np.ndarray:
        """Mirror images of frame points (N, 2), px."""
        ...


#: The result of a constrained fit over a window: the new fits by group, the displacements d_k by node.
Solution: TypeAlias = "tuple[dict[int, GroupFit], dict[int, np.ndarray]]"  # a string: autodoc documents it as data


#: :func:`~img2logo.fit.window_solve.solve`'s ``regroup``: (node -> d_k, the fitted groups) ->
#: (groups split anew, join -> px off the line), or None to fail the fit.
Regroup: TypeAlias = (
    "Callable[[Callable[[int], np.ndarray], set[int]], tuple[Mapping[int, Group], Mapping[int, float]] | None]"
)


def on_axis(symmetry: AxisConstraints | None, group: Group) -> bool:
    """Whether ``group``'s circle is centred on the mirror axis (symmetric runs, :mod:`img2logo.fit.symmetry`).

    So it is when the group ends where a line crosses the axis square to it:
    the arc and its mirror image are then one arc through the axis.
    """
    if symmetry is None:
        return False
    ends = ((group.segments[0], group.nodes[0]), (group.segments[-1], group.nodes[-1]))
    return ends[0] in symmetry.smooth or ends[1] in symmetry.smooth


class FreeCircles:
    """The unconstrained circle fits of groups (Sec. 5.3, first stage), cached by their segments.

    Made before the ladder (the bias of Eqn. 14 comes from the longest
    segment's free circle), then handed to the :class:`FitState`.
    """

    def __init__(self, symmetry: AxisConstraints | None = None) -> None:
        self.symmetry = symmetry
        self._cache: dict[tuple[int, ...], tuple[np.ndarray, float]] = {}

    def circle(self, group: Group) -> tuple[np.ndarray, float]:
        """(centre px, radius px) of the group's free fit.

        A circle on the mirror axis is fitted to the pixels and their mirror image.
        """
        key = group.segments
        if key not in self._cache:
            pts = group.points
            if self.symmetry is not None and on_axis(self.symmetry, group):
                pts = np.vstack([pts, self.symmetry.mirror(pts)])
            if len(pts) < 3:  # two pixels: a straight piece, capped like any
                pts = np.linspace(pts[0], pts[-1], 3)
            fit = fit_circle(pts, refine=False)  # the centre is refitted after snapping
            self._cache[key] = (np.asarray(fit.center, dtype=np.float64), float(fit.radius))
        return self._cache[key]

    def error(self, group: Group) -> float:
        """Mean distance of the group's pixels to its free circle, px."""
        center, radius = self.circle(group)
        return mean_abs_error(group.points, center, radius)


def near_miss(nearest: np.ndarray) -> np.ndarray:
    """Whether free ends whose nearest other arc is ``nearest`` (m,) px away are near-miss gaps, (m,) bool.

    ``GAP_MIN`` to ``GAP_MAX`` px, as :func:`img2logo.quality.near_miss_gaps` counts them: an end the
    eye joins to the arc beside it and the logo does not.
    """
    return (nearest >= GAP_MIN) & (nearest <= GAP_MAX)
