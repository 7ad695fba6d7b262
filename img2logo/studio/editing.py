"""The studio's selection and edits of the logo shown (paper Sec. 7, Fig. 17), with undo and redo.

:class:`StudioEdits` clicks arcs (several with ``add``) and edits them with
:mod:`img2logo.design.edits` (delete, connect, add the other side of a circle, move,
change the rung), one edit at a time per level, undone and redone; it also says which
segments a lock stroke covers (:meth:`StudioEdits.lock_preview`) and which circle
sizes the next Run uses (Fig. 15).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable

import numpy as np

from ..errors import InvalidParameterError
from ..geometry.abstraction import Abstraction
from ..geometry.primitives import Arc
from .state import StudioState

#: Distance from a click to an arc that still selects it, CSS px of the drawing on screen (a
#: fingertip's width on a touch pad; the arcs of a logo are rarely closer than that).
PICK_DISTANCE = 10.0


class StudioEdits(StudioState):
    """The selection and the edits of the logo shown; every action returns True when it changed something."""

    def pick(self, x: float, y: float, distance: float) -> int | None:
        """The arc of :attr:`shown` nearest (x, y), px, if it is within ``distance`` px; else None."""
        a = self.shown
        if a is None or not a.arcs:
            return None
        samples = self._cached("samples", lambda: [arc.sample(step=1.0) for arc in a.arcs])
        point = np.array([float(x), float(y)])
        gaps = [float(np.min(np.hypot(*(s - point).T))) for s in samples]
        i = int(np.argmin(gaps))
        return i if gaps[i] <= distance else None

    def select_at(self, x: float, y: float, distance: float, *, add: bool = False) -> int | None:
        """Click at (x, y), px: select the nearest arc within ``distance`` px (the last two clicked stay selected).

        A click on the selected arc, or off every arc, clears the selection. With ``add``
        (a shift-click) the arc joins the selection, or leaves it when it was in it, and
        nothing else is dropped.
        """
        i = self.pick(x, y, distance)
        if add and i is not None:
            self.selected = [s for s in self.selected if s != i] + ([] if i in self.selected else [i])
            n = len(self.selected)
            self._say(f"{n} arc{'s' if n != 1 else ''} selected: {', '.join(map(str, self.selected))}")
            return i
        if i is None or (self.selected and self.selected[-1] == i):
            self.selected = []
            self._say("nothing selected")
            return None
        a = self.shown
        if a is None:  # pick found an arc: a logo is shown
            return None
        self.selected = [*[s for s in self.selected if s != i][-1:], i]
        arc = a.arcs[i]
        what = "a straight line" if arc.is_line else f"circle {a.circles.index(arc.circle)}, k = {arc.circle.k}"
        pair = f" (and arc {self.selected[0]}: Connect joins them)" if len(self.selected) == 2 else ""
        self._say(f"arc {i} selected: {what}, {arc.length:.0f} px long{pair}")
        return i

    def _edit(
        self, make: Callable[[Abstraction], Abstraction], what: str, keep: Callable[[Abstraction], list[int]]
    ) -> bool:
        a = self.shown
        if a is None:
            return self._say("error: press Run first", ok=False)
        if not self.selected:
            return self._say("error: select an arc first (click it)", ok=False)

        def act() -> str:
            return self._push(make(a), what, keep)

        return self._attempt(act)

    def _push(self, new: Abstraction, what: str, keep: Callable[[Abstraction], list[int]]) -> str:
        """``new`` becomes the logo shown, one edit (undone by :meth:`undo`); returns the message."""
        self._history.setdefault(self.level, []).append(new)
        self._redo.pop(self.level, None)
        self.selected = keep(new)
        self._cache.clear()
        return f"{what}; {len(new.arcs)} arcs (Undo takes it back)"

    def delete_selected(self) -> bool:
        """Delete the selected arcs (:func:`img2logo.design.edits.delete_arc`), as one edit."""
        from ..design.edits import delete_arc

        chosen = sorted(set(self.selected), reverse=True)  # the last first: the others keep their indices

        def make(a: Abstraction) -> Abstraction:
            for i in chosen:
                a = delete_arc(a, i)
            return a

        what = f"arc {chosen[0]} deleted" if len(chosen) == 1 else f"arcs {', '.join(map(str, chosen[::-1]))} deleted"
        return self._edit(make, what, lambda new: [])

    def _circle_of_selected(self, a: Abstraction, op: str) -> int:
        arc = a.arcs[self.selected[-1]]
        if arc.is_line:
            raise InvalidParameterError(f"{op}: arc {self.selected[-1]} is a straight line, it has no golden circle")
        return a.circles.index(arc.circle)

    def move_selected(self, dx: float, dy: float) -> bool:
        """Move the circle of the selected arc by (dx, dy), px (:func:`img2logo.design.edits.move_circle`)."""
        from ..design.edits import move_circle

        def make(a: Abstraction) -> Abstraction:
            c = self._circle_of_selected(a, "move")
            return move_circle(a, c, a.circles[c].center + np.array([float(dx), float(dy)]))

        i = self.selected[-1] if self.selected else -1
        return self._edit(
            make, f"circle of arc {i} moved by ({dx:g}, {dy:g}) px", lambda new: [min(i, len(new.arcs) - 1)]
        )

    def rung_selected(self, delta: int) -> bool:
        """Move the selected arc's circle ``delta`` rungs (:func:`~img2logo.design.edits.change_rung`)."""
        from ..design.edits import change_rung

        def make(a: Abstraction) -> Abstraction:
            return change_rung(a, self._circle_of_selected(a, "change rung"), int(delta))

        i = self.selected[-1] if self.selected else -1
        return self._edit(make, f"circle of arc {i}: rung {int(delta):+d}", lambda new: [min(i, len(new.arcs) - 1)])

    def add_other_side(self) -> bool:
        """Add the other side of the selected arc's circle, between the arc's two ends (Fig. 17 "add").

        :func:`img2logo.design.edits.add_arc` on the arc's own circle from its start junction to its
        end junction, around the other way.
        """
        from ..design.edits import add_arc

        def make(a: Abstraction) -> Abstraction:
            i = self.selected[-1]
            arc = a.arcs[i]
            self._circle_of_selected(a, "add")
            if a.arc_junctions is None:
                raise InvalidParameterError("add: this logo records no junctions")
            ends = a.arc_junctions[i]
            if ends.start is None or ends.end is None or ends.start == ends.end:
                raise InvalidParameterError(f"add: arc {i} does not end at two junctions (a closed circle?)")
            return add_arc(a, arc.circle, ends.start, ends.end, sweep_sign=-1 if arc.sweep > 0 else +1)

        i = self.selected[-1] if self.selected else -1
        return self._edit(make, f"the other side of arc {i}'s circle added", lambda new: [len(new.arcs) - 1])

    def lock_preview(self) -> list[np.ndarray]:
        """The segments of the last run that the lock mask covers, each (N, 2) points, px: what the next Run locks.

        The rule of the run (:func:`img2logo.fit.progressive.locked_segments`: most of a
        segment's points inside the mask), applied to the last run's segment graph, with the
        mask at its working size (a Run with other settings may find other segments).
        """
        if self.result is None or not self.mask.any():
            return []
        from ..fit.progressive import locked_segments
        from ..images.loading import mask_to_working_size

        graph = self.result.graph
        mask = mask_to_working_size(self.mask, self.result.image, "lock mask")
        locked = locked_segments(graph, mask)
        k = self.work_scale
        return [np.asarray(graph.segments[i], dtype=np.float64) / k for i in np.flatnonzero(locked)]

    def set_exponents(self, text: str) -> bool:
        """The golden circles to use at the next Run (Fig. 15): exponents k as ``"3, 5, 8"``; empty for all."""
        words = [w for w in str(text).replace(",", " ").split() if w]
        try:
            exponents = tuple(sorted({int(w) for w in words})) if words else None
        except ValueError:
            return self._say(f"error: circle sizes must be whole numbers k separated by commas, got {text!r}", False)
        self.settings = dataclasses.replace(self.settings, exponents=exponents)
        chosen = "all" if exponents is None else "k = " + ", ".join(map(str, exponents))
        return self._say(f"circle sizes: {chosen}; press Run")

    @property
    def rungs_used(self) -> tuple[int, ...]:
        """The exponents k of the golden circles of the first level of the run (the candidates of Fig. 15)."""
        if not self.levels:
            return ()
        return tuple(sorted({int(c.k) for c in self.levels[0].golden_circles if c.k is not None}))

    def connect_selected(self) -> bool:
        """Join the two selected arcs at their nearest free ends (:func:`~img2logo.design.edits.connect`)."""
        from ..design.edits import connect

        if len(self.selected) != 2:
            return self._say("error: connect needs two arcs: click one, then the other", ok=False)

        def make(a: Abstraction) -> Abstraction:
            ends = [free_ends(a, i) for i in self.selected]
            for i, e in zip(self.selected, ends, strict=True):
                if not e:
                    raise InvalidParameterError(f"connect: arc {i} has no free end (both its ends meet other arcs)")
            pairs = [(j0, j1) for j0 in ends[0] for j1 in ends[1] if j0 != j1]
            if not pairs:
                raise InvalidParameterError("connect: the two arcs share their only free end")
            j0, j1 = min(pairs, key=lambda p: float(np.hypot(*(a.junctions[p[0]] - a.junctions[p[1]]))))
            return connect(a, j0, j1)

        pair = tuple(self.selected)
        return self._edit(make, f"arcs {pair[0]} and {pair[1]} connected", lambda new: [len(new.arcs) - 1])

    # ------------------------------------------------------------------ an arc between two free ends
    @property
    def ends(self) -> list[int]:
        """The free ends chosen on the logo shown (junction indices, the last clicked last; at most two)."""
        chosen = self._ends
        return list(chosen[1]) if chosen is not None and chosen[0] is self.shown else []

    def free_end_junctions(self) -> list[int]:
        """The free ends of the logo shown: junctions where one arc ends and no other meets (sorted)."""
        a = self.shown
        if a is None or a.arc_junctions is None:
            return []
        return self._cached("free ends", lambda: sorted({j for i in range(len(a.arcs)) for j in free_ends(a, i)}))

    def select_end_at(self, x: float, y: float, distance: float) -> int | None:
        """Click at (x, y), px: choose the free end nearest it within ``distance`` px (the last two stay chosen).

        A click on a chosen end takes it out. Two ends chosen, :meth:`end_arc` is the arc that
        :meth:`add_arc_at_ends` would add between them (Fig. 17 "add"). Returns the junction, or
        None when no free end is that near (the click is then an arc's).
        """
        a, js = self.shown, self.free_end_junctions()
        if a is None or not js:
            return None
        gaps = np.hypot(*(a.junctions[js] - np.array([float(x), float(y)])).T)
        n = int(np.argmin(gaps))
        if gaps[n] > distance:
            return None
        j, ends = js[n], self.ends
        ends = [e for e in ends if e != j] if j in ends else [*ends[-1:], j]
        self._ends, self._end_choice, self.selected = (a, ends), 0, []
        if len(ends) < 2:
            self._say(f"free end {j} chosen: click another free end" if ends else "no free end chosen")
            return j
        self._say(f"free ends {ends[0]} and {ends[1]} chosen: {self._end_words()}")
        return j

    def _end_options(self) -> list[tuple[str, int, int, Abstraction]]:
        """The arcs that can join the two chosen ends, in the order Other circle shows them, each with its logo.

        ``("circle", c, sweep_sign, logo)``: circle c of the logo passes through both ends
        (:func:`~img2logo.design.edits.add_arc`, either way round, unless an arc already runs
        there that way); ``("rung", k, side, logo)``: a new golden circle of rung k through
        both (:func:`~img2logo.design.edits.connect`), from the smallest rung whose diameter
        spans the ends, three rungs up, both sides. An edit the library refuses is no option.
        """
        from ..constants import JUNCTION_TOLERANCE
        from ..design.edits import add_arc, connect

        a, ends = self.shown, self.ends
        if a is None or len(ends) != 2:
            return []

        def make() -> list[tuple[str, int, int, Abstraction]]:
            j0, j1 = ends
            points = a.junctions[ends]
            tries = [
                ("circle", ci, sign, lambda ci=ci, sign=sign: add_arc(a, ci, j0, j1, sweep_sign=sign))
                for ci, c in enumerate(a.circles)
                if float(np.abs(c.distance(points)).max()) <= JUNCTION_TOLERANCE
                for sign in (+1, -1)
            ]
            try:
                k0 = connect(a, j0, j1).arcs[-1].circle.k
            except InvalidParameterError:  # a Fibonacci ladder, or no rung allowed spans the ends
                k0 = None
            if k0 is not None:
                k0 = int(k0)
                exponents = a.ladder.exponents if a.ladder is not None else None
                allowed = sorted(int(e) for e in exponents if int(e) >= k0) if exponents else []
                for k in (allowed or list(range(k0, k0 + 3)))[:3]:
                    tries += [
                        ("rung", k, side, lambda k=k, side=side: connect(a, j0, j1, k=k, side=side))
                        for side in (+1, -1)
                    ]
            options = []
            for kind, value, sign, edit in tries:
                try:
                    options.append((kind, value, sign, edit()))
                except InvalidParameterError:
                    continue
            return options

        return self._cached(f"end options {ends}", make)

    def _end_words(self) -> str:
        options = self._end_options()
        if not options:
            return "no golden circle passes through both"
        n = self._end_choice % len(options)
        kind, value = options[n][:2]
        what = f"circle {value} of the logo" if kind == "circle" else f"a new golden circle k = {value}"
        return (
            f"the dashed arc joins them on {what} (option {n + 1} of {len(options)}); Add arc adds it, "
            "Other circle shows the next"
        )

    def end_logo(self) -> Abstraction:
        """The logo shown with the arc between the two chosen ends on the circle chosen (not yet an edit).

        Raises InvalidParameterError (one line) without two free ends chosen or when no circle can join them.
        """
        ends, options = self.ends, self._end_options()
        if len(ends) != 2:
            raise InvalidParameterError("add arc: click two free ends first (the small rings at the open ends)")
        if not options:
            raise InvalidParameterError(f"add arc: no golden circle passes through free ends {ends[0]} and {ends[1]}")
        return options[self._end_choice % len(options)][3]

    def end_arc(self) -> Arc | None:
        """The arc :meth:`add_arc_at_ends` would add (drawn dashed), or None."""
        try:
            return self.end_logo().arcs[-1] if len(self.ends) == 2 else None
        except InvalidParameterError:
            return None

    def other_end_circle(self) -> bool:
        """The next circle the arc between the two chosen ends may lie on (:meth:`end_arc`)."""
        if len(self.ends) != 2:
            return self._say("error: click two free ends first (the small rings at the open ends)", ok=False)
        self._end_choice += 1
        ends = self.ends
        return self._say(f"free ends {ends[0]} and {ends[1]}: {self._end_words()}")

    def add_arc_at_ends(self) -> bool:
        """Add the arc between the two chosen free ends on the circle chosen (Fig. 17 "add"), as one edit."""
        ends = self.ends

        def act() -> str:
            new = self.end_logo()
            self._ends = None
            return self._push(new, f"arc added between free ends {ends[0]} and {ends[1]}", lambda n: [len(n.arcs) - 1])

        return self._attempt(act)

    def undo(self) -> bool:
        """Take the last edit of the level shown back."""
        return self._shift_edit(self._history, self._redo, "undo", "undone")

    def redo(self) -> bool:
        """Make the last edit undone on the level shown again (a new edit forgets what was undone)."""
        return self._shift_edit(self._redo, self._history, "redo", "redone")

    def _shift_edit(
        self, source: dict[int, list[Abstraction]], target: dict[int, list[Abstraction]], verb: str, done: str
    ) -> bool:
        """Move the last logo of the level shown from one stack (edits, or edits undone) to the other."""
        stack = source.get(self.level)
        if not stack:
            return self._say(f"error: nothing to {verb} on this level", ok=False)
        target.setdefault(self.level, []).append(stack.pop())
        self.selected = []
        self._cache.clear()
        return self._say(f"edit {done}; {self.title}")


def free_ends(a: Abstraction, arc: int) -> list[int]:
    """The ends of arc ``arc`` where no other arc meets it (free ends, :func:`img2logo.design.edits.connect`)."""
    if a.arc_junctions is None:
        return []
    ends = a.arc_junctions[arc]
    out = []
    for j in (ends.start, ends.end):
        if j is not None and set(a.junction_arcs[j]) == {arc} and j not in out:
            out.append(j)
    return out


__all__ = ["PICK_DISTANCE", "StudioEdits", "free_ends"]
