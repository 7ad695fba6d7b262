"""An abstraction A^t: one level of a logo, its arcs, their circles, junctions and the run's parameters.

The frozen value every stage after the fit passes on (paper Sec. 3, 5), in the coordinates of
:mod:`img2logo.geometry.primitives` (input-image pixels, x right, y down, angles from +x towards +y).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from itertools import chain
from typing import Any, cast

import numpy as np

from .._validation import check_finite, check_integer, check_positive, readonly
from ..constants import JUNCTION_TOLERANCE, MAX_IMAGE_PIXELS, PHI, RADIUS_RELATIVE_TOLERANCE
from ..errors import InvalidParameterError
from .golden_ladder import FibonacciLadder, GoldenLadder, Ladder
from .primitives import TAU, Arc, ArcJunctions, Circle, Params, line_arc


# --------------------------------------------------------------------------- the abstraction
@dataclass(frozen=True, eq=False)
class Abstraction:
    """One level A^t of the progressive optimization (Sec. 5.2): a golden ratio logo.

    The value carries its ladder and its topology, and checks every invariant of
    the result contract (``contract/README.md``) once, when it is made.

    Attributes
    ----------
    level : int
        The iteration t that produced it (0 for the initial fit), >= 0.
    arcs : tuple of Arc
        The arcs; ``arcs[i].circle`` is its golden circle. Straight lines (the
        lines option) are :class:`Line` arcs, off the ladder.
    arc_segments : tuple of tuple of int
        For each arc, the indices of the segments of the initial segment graph
        that it abstracts (the paper's S_i), in order along the arc.
    junctions : ndarray, shape (J, 2)
        Displaced junction points p_k + d_k, px (read-only).
    junction_arcs : tuple of tuple of int
        For each junction, the indices of the arcs that end (or pass) there.
    similarity : float
        E^s of this level (Eqn. 3), px, >= 0.
    bias : float
        The ladder bias sigma in [0, 1) (Eqn. 10, 14); 0.0 on the Fibonacci ladder.
    tolerance : float
        The tolerance T the run used, px, > 0.
    width, height : int
        Size of the input image, px, >= 1, at most ``MAX_IMAGE_PIXELS`` in all.
    params : Params
        Every other parameter of the run (kind, RDP tolerance, the options, ...),
        for the record: an immutable mapping (any mapping given is frozen).
    ladder : GoldenLadder or FibonacciLadder
        The radii: ``phi ** (k + bias)`` or ``unit * F(k)`` (with the exponents
        the run allowed). Default: the phi ladder of ``bias``.
    arc_junctions : tuple of ArcJunctions
        For each arc, the junction at its start, those it passes through, and
        the one at its end. Default: the junctions listing it, at the end they
        lie at (within ``JUNCTION_TOLERANCE``), the others passed through.
    junction_nodes : tuple of (int or None)
        For each junction, the node of the segment graph it displaces (None
        where it has none: a document read back, a junction an edit made).
    connected : bool
        False for a result of the connectivity ablation (Fig. 11c): its arcs end
        where their junctions project on their circles, not at the junctions.

    Raises
    ------
    InvalidParameterError
        If a field is out of range or an invariant fails: a circle of an arc
        (not a line) without ``k`` or off the ladder (relative
        ``RADIUS_RELATIVE_TOLERANCE``), an index out of range, ``junction_arcs``
        and ``arc_junctions`` disagreeing, or (when connected) a junction farther
        than ``JUNCTION_TOLERANCE`` from its arcs' circles, end points, or from
        inside the arcs that pass through it.

    Examples
    --------
    >>> from img2logo import abstract, data
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> logo = abstract(image, progress=False).final  # an Abstraction: the arcs of one level
    >>> logo.level, len(logo.arcs), len(logo.golden_circles)
    (0, 1, 1)
    """

    level: int
    arcs: tuple[Arc, ...]
    arc_segments: tuple[tuple[int, ...], ...]
    junctions: np.ndarray
    junction_arcs: tuple[tuple[int, ...], ...]
    similarity: float
    bias: float
    tolerance: float
    width: int
    height: int
    params: Mapping[str, Any] = field(default_factory=Params)
    ladder: Ladder | None = None
    arc_junctions: tuple[ArcJunctions, ...] | None = None
    junction_nodes: tuple[int | None, ...] | None = None
    connected: bool = True

    def __post_init__(self) -> None:
        put = object.__setattr__
        j = np.asarray(self.junctions, dtype=np.float64).reshape(-1, 2)
        put(self, "junctions", readonly(j.copy()))
        put(self, "arcs", tuple(self.arcs))
        if not all(isinstance(a, Arc) for a in self.arcs):
            bad = next(a for a in self.arcs if not isinstance(a, Arc))
            raise InvalidParameterError(f"arcs must be Arc values, got {type(bad).__name__}")
        put(self, "level", check_integer(self.level, "level", 0))
        put(self, "width", check_integer(self.width, "width", 1))
        put(self, "height", check_integer(self.height, "height", 1))
        if self.width * self.height > MAX_IMAGE_PIXELS:  # as load_image: a PNG of it would not fit in memory
            raise InvalidParameterError(
                f"width x height must be at most {MAX_IMAGE_PIXELS:,} px (the largest image img2logo reads), "
                f"got {self.width:.3g} x {self.height:.3g}"
            )
        similarity = check_positive(self.similarity, "similarity", allow_zero=True)
        tolerance = check_positive(self.tolerance, "tolerance")
        bias = check_finite(self.bias, "bias")
        if not 0.0 <= bias < 1.0:
            raise InvalidParameterError(f"bias must be in [0, 1), got {bias!r}")
        put(self, "similarity", similarity)
        put(self, "tolerance", tolerance)
        put(self, "bias", bias)
        put(self, "params", Params(self.params))
        put(self, "connected", bool(self.connected))
        self._check_ladder()
        put(self, "arc_segments", _int_tuples(self.arc_segments, "arc_segments"))
        put(self, "junction_arcs", _int_tuples(self.junction_arcs, "junction_arcs"))
        if len(self.arc_segments) != len(self.arcs):
            raise InvalidParameterError(
                f"arc_segments must have one entry per arc ({len(self.arcs)}), got {len(self.arc_segments)}"
            )
        if len(self.junction_arcs) != len(j):
            raise InvalidParameterError(
                f"junction_arcs must have one entry per junction ({len(j)}), got {len(self.junction_arcs)}"
            )
        for k, listed in enumerate(self.junction_arcs):
            for i in listed:
                if i >= len(self.arcs):
                    raise InvalidParameterError(
                        f"junction {k}: arc index {i} is out of range (the abstraction has {len(self.arcs)} arcs)"
                    )
        nodes = (None,) * len(j) if self.junction_nodes is None else tuple(self.junction_nodes)
        if len(nodes) != len(j):
            raise InvalidParameterError(f"junction_nodes must have one entry per junction ({len(j)}), got {len(nodes)}")
        # The common case (Python ints >= 0, every level of a run) in one pass in C.
        if not (set(map(type, nodes)) <= {int} and min(cast(tuple[int, ...], nodes), default=0) >= 0):
            nodes = tuple(None if n is None else check_integer(n, "junction_nodes entry", 0) for n in nodes)
        put(self, "junction_nodes", nodes)
        if self.arc_junctions is None:
            put(self, "arc_junctions", self._found_arc_junctions())
        self._check_topology()

    @classmethod
    def _with_known(cls, known: Sequence[bool], **fields: Any) -> Abstraction:
        """``Abstraction(**fields)``, with the arcs ``known`` (by index) left out of the geometric topology check.

        For :meth:`img2logo.fit.levels.LevelState.abstraction`, which knows the
        arcs that an earlier level checked with the same junction points (and
        the same ladder, the run's: they are left out of the radius check too);
        every other check runs as for any value.
        """
        self = cls.__new__(cls)
        self.__dict__["_known"] = tuple(known)
        self.__init__(**fields)  # type: ignore[misc]
        return self

    # ----------------------------------------------------------------- checks
    def _check_ladder(self) -> None:
        ladder = self.ladder
        if ladder is None:
            ladder = GoldenLadder(self.bias)
            object.__setattr__(self, "ladder", ladder)
        if not isinstance(ladder, GoldenLadder | FibonacciLadder):
            raise InvalidParameterError(
                f"ladder must be a GoldenLadder or FibonacciLadder, got {type(ladder).__name__}"
            )
        if ladder.bias != self.bias:
            raise InvalidParameterError(f"bias {self.bias!r} is not the ladder's bias {ladder.bias!r}")
        if self._ladder_clearly_holds(ladder):
            return
        golden = set(self.golden_circles)
        radii: dict[int, float] = {}  # k -> its ladder radius (many circles share a rung)
        for i, c in enumerate(self.circles):
            if c not in golden:
                continue  # a straight line's circle (no k) is none of the document's
            if c.k is None:
                raise InvalidParameterError(
                    f"circle {i} (centre ({c.cx:.6g}, {c.cy:.6g}), r={c.r:.6g}) has no ladder exponent k: "
                    "only golden circles, r = phi**(k+bias), can be written"
                )
            try:
                expected = radii[c.k] if c.k in radii else radii.setdefault(c.k, ladder.radius(c.k))
            except InvalidParameterError as exc:
                raise InvalidParameterError(f"circle {i}: {exc}") from exc
            if not abs(c.r - expected) <= RADIUS_RELATIVE_TOLERANCE * c.r:
                rule = (
                    f"unit*F(k) = {expected:.10g} (k={c.k}, unit={ladder.unit!r})"
                    if isinstance(ladder, FibonacciLadder)
                    else f"phi**(k+bias) = {expected:.10g} (k={c.k}, bias={self.bias!r})"
                )
                raise InvalidParameterError(
                    f"circle {i}: r={c.r!r} is not {rule}, "
                    f"relative error {abs(c.r - expected) / c.r:.3g} > {RADIUS_RELATIVE_TOLERANCE:g}"
                )

    def _ladder_clearly_holds(self, ladder: Ladder) -> bool:
        """The radius check of :meth:`_check_ladder` arc by arc, without naming circles (every level of a run).

        True when every arc's circle that is not a line's has a k and its
        ladder radius; otherwise :meth:`_check_ladder` decides and names the circle.
        The arcs an earlier level of the run checked (:meth:`_with_known`) are left out.
        """
        radii: dict[int, float] = {}
        known = self.__dict__.get("_known", ())  # arcs an earlier level of the run checked (_with_known)
        for i, a in enumerate(self.arcs):
            if (known and known[i]) or a.is_line:
                continue
            c = a.circle
            if c.k is None:
                return False
            expected = radii.get(c.k)
            if expected is None:
                try:
                    expected = radii[c.k] = ladder.radius(c.k)
                except InvalidParameterError:
                    return False
            if not abs(c.r - expected) <= RADIUS_RELATIVE_TOLERANCE * c.r:
                return False
        return True

    def _found_arc_junctions(self) -> tuple[ArcJunctions, ...]:
        """Each arc's junctions when none are given: the listed junction nearest each end, the others passed through.

        Connected, an end has a junction only within ``JUNCTION_TOLERANCE``;
        unconnected (its gaps are the point), the nearest at any distance.
        """
        listed: list[list[int]] = [[] for _ in self.arcs]
        for k, entries in enumerate(self.junction_arcs):
            for i in dict.fromkeys(entries):
                listed[i].append(k)
        out = []
        for arc, js in zip(self.arcs, listed, strict=True):
            ends: list[int | None] = []
            for point in (arc.start, arc.end):
                d = [math.dist(point, self.junctions[k]) for k in js]
                best = int(np.argmin(d)) if d else -1
                near = d and (d[best] <= JUNCTION_TOLERANCE or not self.connected)
                ends.append(js[best] if near else None)
            if not self.connected and ends[0] is not None and ends[0] == ends[1] and not arc.is_full_circle:
                # One junction for both ends of an open arc: it is at the nearer end only.
                near_start = math.dist(arc.start, self.junctions[ends[0]]) <= math.dist(
                    arc.end, self.junctions[ends[0]]
                )
                ends[1 if near_start else 0] = None
            through = tuple(k for k in js if k not in ends)
            out.append(ArcJunctions(ends[0], ends[1], through))
        return tuple(out)

    def _topology_clearly_holds(self, topology: tuple[ArcJunctions, ...], known: Sequence[bool] = ()) -> bool:
        """The geometric checks of :meth:`_check_topology` for all the arcs at once, with a margin.

        True when every junction is on its arc's circle, at its end point and
        within its angle range by more than rounding (a level of the progressive
        optimization: ~10^2 arcs, ~10^2 times a run). Otherwise the arc-by-arc
        checks decide, and name what fails. The arcs ``known`` (by index) are
        left out: those the progressive optimization checked at an earlier
        level, with the same arc and the same junction points
        (:meth:`img2logo.fit.levels.LevelState.abstraction`).
        """
        tol, margin = JUNCTION_TOLERANCE, 1e-9
        on_arc: list[int] = []
        on_junction: list[int] = []
        ends_arc: list[int] = []
        ends_junction: list[int] = []
        ends_angle: list[float] = []
        through_arc: list[int] = []
        through_junction: list[int] = []
        for i, t in enumerate(topology):
            if known and known[i]:
                continue
            for k in (*t.ends, *t.through):
                on_arc.append(i)
                on_junction.append(k)
            for k in t.through:
                through_arc.append(i)
                through_junction.append(k)
            for end, angle in ((t.start, 0.0), (t.end, 1.0)):
                if end is not None:
                    ends_arc.append(i)
                    ends_junction.append(end)
                    ends_angle.append(angle)
        if not on_arc:
            return True
        circles = np.array([(a.circle.cx, a.circle.cy, a.circle.r, a.theta0, a.sweep) for a in self.arcs])
        cx, cy, r, theta0, sweep = circles.T
        j, c = self.junctions[on_junction], np.asarray(on_arc)
        if not np.all(np.abs(np.hypot(j[:, 0] - cx[c], j[:, 1] - cy[c]) - r[c]) <= tol - margin):
            return False
        if ends_arc:
            e = np.asarray(ends_arc)
            angle = theta0[e] + np.asarray(ends_angle) * sweep[e]
            p = self.junctions[ends_junction]
            if not np.all(
                np.hypot(p[:, 0] - cx[e] - r[e] * np.cos(angle), p[:, 1] - cy[e] - r[e] * np.sin(angle)) <= tol - margin
            ):
                return False
        if through_arc:
            c = np.asarray(through_arc)
            p = self.junctions[through_junction]
            full = np.abs(sweep[c]) >= TAU - 1e-9
            offset = np.mod((np.arctan2(p[:, 1] - cy[c], p[:, 0] - cx[c]) - theta0[c]) * np.sign(sweep[c]), TAU)
            slack = tol / r[c] - margin
            if not np.all(full | (offset <= np.abs(sweep[c]) + slack) | (offset >= TAU - slack)):
                return False
        return True

    def _check_topology(self) -> None:
        topology = tuple(self.arc_junctions or ())
        if len(topology) != len(self.arcs):
            raise InvalidParameterError(
                f"arc_junctions must have one entry per arc ({len(self.arcs)}), got {len(topology)}"
            )
        for t in topology:
            if not isinstance(t, ArcJunctions):
                raise InvalidParameterError(f"arc_junctions entries must be ArcJunctions, got {type(t).__name__}")
        object.__setattr__(self, "arc_junctions", topology)
        n = len(self.junctions)
        at: list[set[int]] = [set() for _ in range(n)]
        for i, t in enumerate(topology):
            for k in (*t.ends, *t.through):
                if k >= n:
                    raise InvalidParameterError(
                        f"arc {i}: junction index {k} is out of range (the abstraction has {n} junctions)"
                    )
                at[k].add(i)
        for k, listed in enumerate(self.junction_arcs):
            if set(listed) != at[k]:
                raise InvalidParameterError(
                    f"junction {k} lists arcs {sorted(set(listed))}, but arc_junctions puts arcs {sorted(at[k])} there"
                )
        known = self.__dict__.pop("_known", ())  # set by _with_known only, for this check only
        if not self.connected:
            return
        if self._topology_clearly_holds(topology, known):
            return
        tol = JUNCTION_TOLERANCE
        for i, (arc, t) in enumerate(zip(self.arcs, topology, strict=True)):
            c = arc.circle
            # Each arc's junctions checked at once; the messages name the first that fails.
            ks = (*t.ends, *t.through)
            if ks:
                offs = np.abs(c.distance(self.junctions[list(ks)]))
                if not np.all(offs <= tol):
                    bad = int(np.argmin(offs <= tol))
                    k, p, off = ks[bad], self.junctions[ks[bad]], float(offs[bad])
                    raise InvalidParameterError(
                        f"junction {k}: ({p[0]:.6g}, {p[1]:.6g}) is {off:.3g} px off the circle of arc {i}, "
                        f"more than {tol:g} px"
                    )
            for jend, end in ((t.start, arc.start), (t.end, arc.end)):
                if jend is not None and not math.dist(self.junctions[jend], end) <= tol:
                    raise InvalidParameterError(
                        f"junction {jend}: arc {i} has no end point at ({self.junctions[jend][0]:.6g}, "
                        f"{self.junctions[jend][1]:.6g}): it is {math.dist(self.junctions[jend], end):.3g} px from it, "
                        f"more than {tol:g} px"
                    )
            if t.through:
                on = arc.contains_angle(c.angle_of(self.junctions[list(t.through)]), tol=tol / c.r)
                if not np.all(on):
                    k = t.through[int(np.argmin(on))]
                    raise InvalidParameterError(f"junction {k} is on the circle of arc {i} but not on the arc")

    # ----------------------------------------------------------------- derived values
    def scaled(self, factor: float, width: int, height: int, *, params: Mapping[str, Any] | None = None) -> Abstraction:
        """The same logo in a frame ``factor`` times larger, ``width`` x ``height`` px; still on a ladder.

        How an input over ``MAX_IMAGE_SIDE`` gets its result in its own pixels: the
        optimization works at the downscaled size, and its levels are scaled back
        by ``factor = 1 / scale``. Centres, radii, junctions, line ends, E^s and T
        are multiplied by ``factor``; angles, the topology and ``params`` stay
        (unless ``params`` is given: the caller scales what in them is a length).
        The radii stay exactly on a ladder: phi ** (k + bias) * factor =
        phi ** (k + n + bias') with bias' + n = bias + log_phi(factor), n an
        integer, bias' in [0, 1) (so k becomes k + n, exponents given too); on
        the Fibonacci grid the unit is multiplied by ``factor`` and k stays.
        """
        f = check_positive(factor, "factor")
        ladder = cast(Ladder, self.ladder)  # __post_init__ always sets it
        new_ladder: Ladder
        if isinstance(ladder, FibonacciLadder):
            shift, new_ladder = 0, FibonacciLadder(ladder.unit * f, ladder.exponents, ladder.rounding)
        else:
            t = ladder.bias + math.log(f) / math.log(PHI)
            shift = math.floor(t)
            bias = t - shift
            if bias >= 1.0:  # rounding
                shift, bias = shift + 1, 0.0
            exps = None if ladder.exponents is None else tuple(k + shift for k in ladder.exponents)
            new_ladder = GoldenLadder(bias, exps, ladder.rounding)
        circles = {
            c: Circle(c.cx * f, c.cy * f, new_ladder.radius(c.k + shift), c.k + shift)  # type: ignore[operator]
            for c in self.golden_circles
        }

        def arc(a: Arc) -> Arc:
            if not a.is_line:
                return Arc(circles[a.circle], a.theta0, a.sweep)
            mid = (a.start + a.end) / 2.0
            chord = a.end - a.start
            d = a.circle.center - mid
            side = float(chord[0] * d[1] - chord[1] * d[0])  # the centre's side of the chord
            return line_arc(a.start * f, a.end * f, side=1.0 if side >= 0 else -1.0)

        return Abstraction(
            level=self.level,
            arcs=tuple(arc(a) for a in self.arcs),
            arc_segments=self.arc_segments,
            junctions=self.junctions * f,
            junction_arcs=self.junction_arcs,
            similarity=self.similarity * f,
            bias=new_ladder.bias,
            tolerance=self.tolerance * f,
            width=width,
            height=height,
            params=self.params if params is None else params,
            ladder=new_ladder,
            arc_junctions=self.arc_junctions,
            junction_nodes=self.junction_nodes,
            connected=self.connected,
        )

    @property
    def circles(self) -> tuple[Circle, ...]:
        """The distinct circles of the arcs, in order of first use."""
        return tuple(dict.fromkeys(a.circle for a in self.arcs))

    @property
    def golden_circles(self) -> tuple[Circle, ...]:
        """The distinct circles of the arcs that are not straight lines, in order of first use.

        The circles of the result file, numbered as there (:mod:`img2logo.export.contract`):
        a straight line's circle (``LINE_RADIUS``, no k) is none of them.
        """
        return tuple(dict.fromkeys(a.circle for a in self.arcs if not a.is_line))

    @property
    def phi(self) -> float:
        """The golden ratio this abstraction was built on."""
        return PHI

    def arc_nodes(self, arc: int) -> tuple[int | None, ...]:
        """The graph nodes of an arc's junctions in order along it (start, passed through, end): J' on its path."""
        nodes, ends = self._filled()
        return tuple(nodes[j] for j in ends[arc].ordered)

    def arcs_at(self, junction: int) -> tuple[int, ...]:
        """The arcs with an end point at ``junction`` (those passing through it left out), in index order."""
        ends = self._filled()[1]
        return tuple(i for i in self.junction_arcs[junction] if junction in ends[i].ends)

    def _filled(self) -> tuple[tuple[int | None, ...], tuple[ArcJunctions, ...]]:
        """``junction_nodes`` and ``arc_junctions``, which ``__post_init__`` always fills (None only as arguments)."""
        return cast(tuple[int | None, ...], self.junction_nodes), cast(tuple[ArcJunctions, ...], self.arc_junctions)


def _int_tuples(values: Sequence[Sequence[int]], name: str) -> tuple[tuple[int, ...], ...]:
    out = tuple(map(tuple, values))
    # The common case (Python ints >= 0, every level of a run) in one pass in C.
    if set(map(type, chain.from_iterable(out))) <= {int} and min(chain.from_iterable(out), default=0) >= 0:
        return out
    return tuple(tuple(check_integer(v, f"{name} entry", 0) for v in t) for t in out)
