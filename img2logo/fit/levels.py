"""The levels A^0 ... A^final of a run (paper Sec. 5.2), each made when it is first asked for.

The merge loop (:mod:`img2logo.fit.merging`) keeps, for every level it reaches, only
its numbers (:class:`LevelState`: the arcs, their junctions, the displaced points,
E^s); :class:`Levels`, the run's :attr:`~img2logo.fit.progressive.Progression.levels`,
makes a level's :class:`~img2logo.geometry.abstraction.Abstraction` when it is first
asked for. Making one reads and checks every arc and junction of the level: work
over all the arcs at every level, which a run that uses only its result (the
command line, a batch) never needs. :class:`LevelContext` keeps what consecutive
levels share, so that making them all costs what making each as the loop reached
it did.
"""

from __future__ import annotations

import threading
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, overload

import numpy as np

from ..constants import JUNCTION_TOLERANCE
from ..geometry.abstraction import Abstraction
from ..geometry.primitives import Arc, ArcJunctions
from .fit_state import FitState

__all__ = ["LevelContext", "LevelState", "Levels", "arc_junctions"]


@dataclass(frozen=True, eq=False)
class LevelState:
    """What level A^t is made of, kept by the merge loop when it makes the level; :meth:`abstraction` makes A^t.

    Kept per level instead of A^t itself: making an :class:`Abstraction` reads
    and checks every arc and junction of the level, work over all arcs at
    every level that a run using only its result never needs.

    Attributes
    ----------
    level : int
        t.
    arcs : tuple of Arc
        The level's arcs, in the order of their groups' first segments.
    arc_segments : tuple of tuple of int
        Each arc's segments of the graph.
    arc_nodes : tuple of tuple of int
        Each arc's junctions of J', nodes of the graph in path order
        (:meth:`~img2logo.fit.fit_state.FitState.constrained_nodes`).
    points : ndarray, shape (N, 2)
        Every node's displaced point p_k + d_k, px (N: the graph's nodes).
    similarity : float
        E^s (Eqn. 3), px.
    params : mapping
        The run's record (:meth:`Options.record` and more).
    run : LevelContext
        What all the levels of the run share.
    """

    level: int
    arcs: tuple[Arc, ...]
    arc_segments: tuple[tuple[int, ...], ...]
    arc_nodes: tuple[tuple[int, ...], ...]
    points: np.ndarray
    similarity: float
    params: Mapping[str, Any]
    run: LevelContext

    @classmethod
    def of(cls, state: FitState, level: int, params: Mapping[str, Any], run: LevelContext) -> LevelState:
        """The current state of ``state`` as level ``level``; ``run``: the run's (one for all its levels)."""
        order = sorted(state.groups, key=lambda g: min(state.groups[g].segments))
        groups = [state.groups[g] for g in order]
        return cls(
            level,
            tuple(state.fits[g].arc.arc for g in order),
            tuple(group.segments for group in groups),
            tuple(state.constrained_nodes(group) for group in groups),
            state.graph.junctions + state.disp,
            float(state.similarity()),
            dict(params),
            run,
        )

    def abstraction(self) -> Abstraction:
        """A^t: the frozen :class:`Abstraction`, with its ladder and topology."""
        run = self.run
        nodes = sorted({n for arc_nodes in self.arc_nodes for n in arc_nodes})
        junction = {n: i for i, n in enumerate(nodes)}
        topology = []
        known = []
        at_node: dict[int, list[int]] = {n: [] for n in nodes}
        for i, (arc, arc_nodes) in enumerate(zip(self.arcs, self.arc_nodes, strict=True)):
            # Which of the arc's junctions its ends are at, by their positions in its path.
            local, checked = run.junctions_of(arc, arc_nodes, self.points[list(arc_nodes)])
            known.append(checked)
            at = tuple(junction[n] for n in arc_nodes)
            topology.append(
                ArcJunctions(
                    None if local.start is None else at[local.start],
                    None if local.end is None else at[local.end],
                    tuple(at[k] for k in local.through),
                )
            )
            for n in set(arc_nodes):  # each junction's arcs in index order
                at_node[n].append(i)
        made = Abstraction._with_known(
            known,
            level=self.level,
            arcs=self.arcs,
            arc_segments=self.arc_segments,
            junctions=self.points[np.asarray(nodes, dtype=np.intp)].reshape(-1, 2),
            junction_arcs=tuple(tuple(at_node[n]) for n in nodes),
            similarity=self.similarity,
            bias=float(run.ladder.bias),
            tolerance=run.tolerance,
            width=run.width,
            height=run.height,
            params=self.params,
            ladder=run.ladder,
            arc_junctions=tuple(topology),
            junction_nodes=tuple(nodes),
            connected=run.connected,
        )
        run.checked(self.arcs)
        return made


class LevelContext:
    """What every level of a run shares: its ladder, T, the image size, and the arcs its levels made so far met.

    Between two levels most arcs stay as they were, at the same junction points:
    where an arc was met before (the same arc, the same junctions at the same
    points), :meth:`LevelState.abstraction` takes which of its junctions are at
    its ends from here (:meth:`junctions_of`) and leaves it out of the new
    level's geometric check (:meth:`Abstraction._with_known`) once a level
    checked it, whatever the order the levels are made in.
    """

    def __init__(self, state: FitState) -> None:
        self.ladder = state.ladder
        self.tolerance = float(state.options.tolerance)
        self.width, self.height = state.graph.width, state.graph.height
        self.connected = state.options.connectivity
        #: id of the arc -> (the arc, its junction nodes, their points, its ArcJunctions by path position, checked).
        self._arcs: dict[int, tuple[Arc, tuple[int, ...], np.ndarray, ArcJunctions, bool]] = {}

    def junctions_of(self, arc: Arc, nodes: tuple[int, ...], points: np.ndarray) -> tuple[ArcJunctions, bool]:
        """:func:`arc_junctions` of ``arc`` through ``nodes`` at ``points`` (by path position), and
        whether a level made before checked the arc at those points."""
        hit = self._arcs.get(id(arc))
        if hit is not None and hit[0] is arc and hit[1] == nodes and np.array_equal(hit[2], points):
            return hit[3], hit[4]
        local = arc_junctions(arc, range(len(nodes)), points)
        self._arcs[id(arc)] = (arc, nodes, points, local, False)
        return local, False

    def checked(self, arcs: Sequence[Arc]) -> None:
        """A level with ``arcs`` (each met by :meth:`junctions_of` for it) passed its checks."""
        for arc in arcs:
            hit = self._arcs[id(arc)]
            if not hit[4]:
                self._arcs[id(arc)] = (*hit[:4], True)


class Levels(Sequence[Abstraction]):
    """The levels A^0 ... A^final of a run, each made when first asked for, then kept.

    A sequence like a tuple: ``levels[t]``, ``levels[-1]``, ``len(levels)``,
    iteration, slices (a tuple); equal to a sequence of the same levels. Its
    items are :class:`Abstraction` values, or :class:`LevelState` values made
    into them on first access (the same value as made at once: the same
    :class:`Abstraction`, made from the same numbers).

    Parameters
    ----------
    items : sequence of Abstraction or LevelState
        The levels in order.
    """

    def __init__(self, items: Sequence[Abstraction | LevelState | _Changed]) -> None:
        self._items: list[Abstraction | LevelState | _Changed] = list(items)
        self._lock = threading.Lock()  # one Abstraction per level, also when threads ask at once

    def __len__(self) -> int:
        return len(self._items)

    @overload
    def __getitem__(self, t: int) -> Abstraction: ...
    @overload
    def __getitem__(self, t: slice) -> tuple[Abstraction, ...]: ...
    def __getitem__(self, t: int | slice) -> Abstraction | tuple[Abstraction, ...]:
        if isinstance(t, slice):
            return tuple(self._made(i) for i in range(len(self._items))[t])
        n = len(self._items)
        if not -n <= t < n:
            raise IndexError(f"level {t} out of range ({n} levels)")
        return self._made(t % n)

    def __iter__(self) -> Iterator[Abstraction]:
        return (self._made(i) for i in range(len(self._items)))

    def __eq__(self, other: object) -> bool:
        if not isinstance(other, Sequence) or isinstance(other, str | bytes) or len(other) != len(self):
            return False
        return all(a is b or a == b for a, b in zip(self, other, strict=True))

    __hash__ = None  # type: ignore[assignment]

    def __repr__(self) -> str:
        return f"Levels({len(self._items)} levels, {self.made()} made)"

    def __reduce__(self) -> tuple[Any, ...]:
        return (Levels, (tuple(self),))  # pickled made

    def _made(self, i: int) -> Abstraction:
        item = self._items[i]
        if isinstance(item, Abstraction):
            return item
        with self._lock:
            item = self._items[i]
            if not isinstance(item, Abstraction):
                item = self._items[i] = item.abstraction()
            return item

    def made(self) -> int:
        """How many of the levels were made so far."""
        return sum(isinstance(x, Abstraction) for x in self._items)

    def arc_counts(self) -> list[int]:
        """|A^t| for every level, without making the levels."""
        return [len(x.arcs) for x in self._items]

    def similarities(self) -> list[float]:
        """E^s(A^t) for every level, px, without making the levels."""
        return [float(x.similarity) for x in self._items]

    def map(self, change: Callable[[Abstraction], Abstraction]) -> Levels:
        """The levels ``change(A^t)``, each made when first asked for (scaled, mirrored, ...)."""
        return Levels([_Changed(self, i, change) for i in range(len(self._items))])


@dataclass(frozen=True, eq=False)
class _Changed:
    """Level ``i`` of ``levels`` changed by ``change``: :meth:`abstraction` makes it (for :meth:`Levels.map`)."""

    levels: Levels
    i: int
    change: Callable[[Abstraction], Abstraction]

    @property
    def arcs(self) -> tuple[Arc, ...]:
        return self.abstraction().arcs

    @property
    def similarity(self) -> float:
        return self.abstraction().similarity

    def abstraction(self) -> Abstraction:
        return self.change(self.levels[self.i])


def arc_junctions(arc: Arc, path: Sequence[int], points: np.ndarray) -> ArcJunctions:
    """Which of a group's junctions (``path``: indices into ``points``, in path order) are at the arc's ends.

    The arc was extracted between (the projections on its circle of) the
    junctions of its path (:meth:`~img2logo.fit.fit_state.FitState.arc_for`): an end is at the junction whose
    projection it is, to ``JUNCTION_TOLERANCE``; an end at none (a released
    junction's projection) is free. The others are passed through, in path order.
    """
    c = arc.circle
    ends: list[int | None] = []
    # The projections of all the path's junctions at once (the same values as one at a time).
    proj = c.point_at(c.angle_of(points[np.asarray(path, dtype=np.intp)])).reshape(-1, 2)
    for end in (arc.start, arc.end):
        d = np.hypot(proj[:, 0] - end[0], proj[:, 1] - end[1])
        near = d <= JUNCTION_TOLERANCE
        # The nearest within the tolerance; on a tie the first in path order.
        ends.append(path[int(np.argmin(np.where(near, d, np.inf)))] if near.any() else None)
    return ArcJunctions(ends[0], ends[1], tuple(j for j in path if j not in ends))
