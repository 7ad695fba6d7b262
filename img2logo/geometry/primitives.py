"""Frozen geometry values passed between the stages: circles, arcs, lines, an arc's junctions, a run's parameters.

Coordinate convention (``contract/README.md``): input-image pixels, x to the
right, y downwards, origin at the top-left corner of the image, so the pixel in
row i, column j has its centre at (x, y) = (j + 0.5, i + 0.5). Angles are in
radians, measured from +x towards +y: with y pointing down a positive sweep turns
clockwise on screen, the same sense as SVG's ``sweep-flag=1``.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validation import check_integer, readonly
from ..errors import InvalidParameterError
from .constants import LINE_RADIUS
from .golden_ladder import Ladder

TAU = 2.0 * math.pi


def cumulative_length(points: np.ndarray) -> np.ndarray:
    """Length along a polyline at each of its points, shape (n,), px; 0 at the first.

    ``points`` has shape (n, 2), px (n >= 1).
    """
    return np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(points, axis=0).T))])


def polyline_length(points: np.ndarray) -> float:
    """Length of a polyline of shape (n, 2), px (0 for one point)."""
    return float(np.sum(np.hypot(*np.diff(points, axis=0).T)))


@dataclass(frozen=True)
class Circle:
    """A circle of the golden circle grid.

    Attributes
    ----------
    cx, cy : float
        Centre, px.
    r : float
        Radius, px; for a golden circle ``r == phi ** (k + bias)`` (Eqn. 10).
    k : int or None
        Integer ladder exponent, or None for a circle not (yet) on the ladder.

    Examples
    --------
    >>> from img2logo import Circle
    >>> c = Circle(10.0, 20.0, 5.0)
    >>> c.center, c.point_at(0.0)
    (array([10., 20.]), array([15., 20.]))
    """

    cx: float
    cy: float
    r: float
    k: int | None = None

    def __post_init__(self) -> None:
        if not (math.isfinite(self.cx) and math.isfinite(self.cy)):
            raise InvalidParameterError(f"circle centre must be finite, got ({self.cx}, {self.cy})")
        if not (math.isfinite(self.r) and self.r > 0):
            raise InvalidParameterError(f"circle radius must be finite and > 0, got {self.r}")

    @property
    def center(self) -> np.ndarray:
        """Centre as an array of shape (2,), px."""
        return np.array([self.cx, self.cy])

    def angle_of(self, points: np.ndarray) -> np.ndarray:
        """Polar angles of ``points`` (N, 2) around the centre, radians in (-pi, pi]."""
        p = np.asarray(points, dtype=np.float64)
        return np.arctan2(p[..., 1] - self.cy, p[..., 0] - self.cx)

    def point_at(self, theta: np.ndarray | float) -> np.ndarray:
        """Points on the circle at angles ``theta`` (radians): shape (..., 2), px."""
        t = np.asarray(theta, dtype=np.float64)
        # Written into one array: np.stack costs more than the arithmetic (this runs ~10^4 times a run).
        out = np.empty((*t.shape, 2))
        out[..., 0] = self.cx + self.r * np.cos(t)
        out[..., 1] = self.cy + self.r * np.sin(t)
        return out

    def distance(self, points: np.ndarray) -> np.ndarray:
        """Signed geometric distance ``|p - o| - r`` of ``points`` (N, 2), px (Eqn. 9)."""
        p = np.asarray(points, dtype=np.float64)
        return np.hypot(p[..., 0] - self.cx, p[..., 1] - self.cy) - self.r


@dataclass(frozen=True)
class Arc:
    """A circular arc: the part of ``circle`` from ``theta0`` over ``sweep``.

    A point of the arc is ``(cx + r cos t, cy + r sin t)`` for t from ``theta0``
    to ``theta0 + sweep`` (the contract's definition). ``0 < |sweep| <= 2 pi``;
    ``|sweep| == 2 pi`` is a whole circle.

    Examples
    --------
    >>> import numpy as np
    >>> from img2logo import Arc, Circle
    >>> quarter = Arc(Circle(0.0, 0.0, 10.0), 0.0, np.pi / 2)
    >>> round(quarter.length, 3), quarter.end.round(6)
    (15.708, array([ 0., 10.]))
    """

    circle: Circle
    theta0: float
    sweep: float

    def __post_init__(self) -> None:
        if not math.isfinite(self.theta0) or not math.isfinite(self.sweep):
            raise InvalidParameterError(f"arc angles must be finite, got theta0={self.theta0}, sweep={self.sweep}")
        if not (0.0 < abs(self.sweep) <= TAU + 1e-12):
            raise InvalidParameterError(f"arc sweep must satisfy 0 < |sweep| <= 2 pi, got {self.sweep}")

    @property
    def length(self) -> float:
        """Arc length, px."""
        return abs(self.sweep) * self.circle.r

    @property
    def is_line(self) -> bool:
        """False: a circular arc. A straight line is a :class:`Line` (the lines option)."""
        return False

    @property
    def is_full_circle(self) -> bool:
        """True when the arc is the whole circle."""
        return abs(self.sweep) >= TAU - 1e-9

    @property
    def start(self) -> np.ndarray:
        """Start point, shape (2,), px."""
        return self.circle.point_at(self.theta0)

    @property
    def end(self) -> np.ndarray:
        """End point, shape (2,), px."""
        return self.circle.point_at(self.theta0 + self.sweep)

    def sample(self, step: float = 1.0, min_points: int = 2) -> np.ndarray:
        """Points along the arc about ``step`` px apart, ends included: (N, 2)."""
        n = max(min_points, math.ceil(self.length / step) + 1)
        return self.circle.point_at(self.theta0 + self.sweep * np.linspace(0.0, 1.0, n))

    def contains_angle(self, theta: np.ndarray | float, tol: float = 1e-9) -> np.ndarray:
        """Whether the angles ``theta`` (radians) lie on the arc, within ``tol`` radians."""
        t = np.asarray(theta, dtype=np.float64)
        if self.is_full_circle:
            return np.ones(t.shape, dtype=bool)
        # Offset from the start measured in the sweep's own sense, in [0, 2 pi).
        offset = np.mod((t - self.theta0) * math.copysign(1.0, self.sweep), TAU)
        return (offset <= abs(self.sweep) + tol) | (offset >= TAU - tol)


@dataclass(frozen=True)
class Line(Arc):
    """A straight line (the lines option, paper Sec. 9, Fig. 20b): its own marked primitive.

    It is stored as the short arc of a ``LINE_RADIUS`` circle between its two
    end points (0.03 px from straight over a 500 px chord), so the fit, the
    arc extraction and the drawing handle it like any arc; its circle has no
    ladder exponent (``k`` None) and is not on the ladder. Writers write it as
    the straight segment from :attr:`start` to :attr:`end`, apart from the
    golden circles. Build one with :func:`line_arc`.
    """

    def __post_init__(self) -> None:
        super().__post_init__()
        if self.circle.k is not None:
            raise InvalidParameterError(f"a line's circle has no ladder exponent, got k={self.circle.k}")

    @property
    def is_line(self) -> bool:
        """True: a straight line."""
        return True

    @classmethod
    def of(cls, arc: Arc) -> Line:
        """The arc ``arc`` of a ``LINE_RADIUS`` circle, marked as a line."""
        return cls(arc.circle, arc.theta0, arc.sweep)


def line_arc(p0: np.ndarray, p1: np.ndarray, side: float = 1.0) -> Line:
    """The straight line from ``p0`` to ``p1`` (px) as an arc of a ``LINE_RADIUS`` circle.

    The circle's centre is on the perpendicular bisector, on the left of the
    direction p0 -> p1 for ``side`` > 0 (right otherwise); the arc is the short
    way from p0 to p1, so its ends are exactly p0 and p1 (to rounding).
    """
    a, b = np.asarray(p0, dtype=np.float64), np.asarray(p1, dtype=np.float64)
    chord = b - a
    length = float(np.hypot(*chord))
    if not length > 0:
        raise InvalidParameterError("a line needs two distinct end points")
    normal = np.array([-chord[1], chord[0]]) / length * math.copysign(1.0, side)
    centre = (a + b) / 2.0 + normal * math.sqrt(LINE_RADIUS**2 - (length / 2.0) ** 2)
    circle = Circle(float(centre[0]), float(centre[1]), LINE_RADIUS, None)
    t0 = math.atan2(a[1] - centre[1], a[0] - centre[0])
    t1 = math.atan2(b[1] - centre[1], b[0] - centre[0])
    return Line(circle, t0, math.remainder(t1 - t0, TAU))


def golden_circle(center: object, radius: float, ladder: Ladder) -> Circle:
    """A circle at ``center`` (x, y; px) with ``radius`` snapped to ``ladder`` (Eqn. 12).

    Returns
    -------
    Circle
        With ``r = ladder.snap(radius)[1]`` and ``k`` the ladder exponent.
    """
    c = np.asarray(center, dtype=np.float64)
    if c.shape != (2,):
        raise InvalidParameterError(f"center must have shape (2,), got {c.shape}")
    k, r = ladder.snap(radius)
    return Circle(float(c[0]), float(c[1]), r, k)


# --------------------------------------------------------------------------- parameters
class Params(Mapping[str, Any]):
    """An immutable mapping of the parameters of a run (``Abstraction.params``).

    Built from any mapping: nested mappings become :class:`Params` and lists
    tuples, so nothing inside can change. It compares equal to a mapping with
    the same items (a tuple entry equals the same tuple, not a list), pickles
    and copies like a dict, and :func:`img2logo.export.contract.to_document` writes it
    as the JSON object it was built from.
    """

    __slots__ = ("_items",)

    def __init__(self, items: Mapping[str, Any] | None = None) -> None:
        if items is not None and not isinstance(items, Mapping):
            raise InvalidParameterError(f"params must be a mapping, got {type(items).__name__}")
        object.__setattr__(self, "_items", {key: _frozen(value) for key, value in (items or {}).items()})

    def __getitem__(self, key: str) -> Any:
        return self._items[key]

    def __iter__(self) -> Iterator[str]:
        return iter(self._items)

    def __len__(self) -> int:
        return len(self._items)

    def __setattr__(self, name: str, value: Any) -> None:
        raise AttributeError("Params is immutable")

    def __repr__(self) -> str:
        return f"Params({self._items!r})"

    def __reduce__(self) -> tuple[type[Params], tuple[dict[str, Any]]]:
        return (Params, (self.to_dict(),))

    def __deepcopy__(self, memo: dict[int, Any]) -> Params:
        return self  # immutable all the way down

    def to_dict(self) -> dict[str, Any]:
        """A plain, mutable copy: nested Params become dicts (tuples stay tuples)."""
        return {key: value.to_dict() if isinstance(value, Params) else value for key, value in self._items.items()}


def _frozen(value: Any) -> Any:
    """``value`` with mappings made :class:`Params` and lists (and tuples) tuples, recursively."""
    if isinstance(value, Params):
        return value
    if isinstance(value, Mapping):
        return Params(value)
    if isinstance(value, list | tuple):
        return tuple(_frozen(v) for v in value)
    if isinstance(value, np.ndarray):
        return readonly(value.copy())
    return value


# --------------------------------------------------------------------------- topology
@dataclass(frozen=True)
class ArcJunctions:
    """Where one arc meets the junctions of its abstraction (indices into ``junctions``).

    Attributes
    ----------
    start, end : int or None
        The junction at the arc's start point (``theta0``) and at its end point
        (``theta0 + sweep``); None for a free end. A closed arc (a whole circle)
        starts and ends at one junction: ``start == end``.
    through : tuple of int
        The junctions the arc passes through inside (the progressive optimization
        keeps junctions of valence >= 3 inside merged arcs, Sec. 6.2), in order
        along the arc.
    """

    start: int | None = None
    end: int | None = None
    through: tuple[int, ...] = ()

    def __post_init__(self) -> None:
        for name in ("start", "end"):
            value = getattr(self, name)
            if value is not None:
                object.__setattr__(self, name, check_integer(value, f"ArcJunctions.{name}", 0))
        object.__setattr__(
            self, "through", tuple(check_integer(j, "ArcJunctions.through entry", 0) for j in self.through)
        )

    @property
    def ordered(self) -> tuple[int, ...]:
        """The junctions in order along the arc: start, those passed through, end (free ends left out)."""
        ends_at = () if self.end is None or self.end == self.start else (self.end,)
        return (*(() if self.start is None else (self.start,)), *self.through, *ends_at)

    @property
    def ends(self) -> tuple[int, ...]:
        """The junctions at an end point of the arc (each once)."""
        start, end = self.start, self.end  # (read for every arc of every level: no generator)
        if start is None:
            return () if end is None else (end,)
        return (start,) if end is None or end == start else (start, end)

    def renumbered(self, mapping: Mapping[int, int]) -> ArcJunctions:
        """The same with junction ``j`` renamed ``mapping[j]``; a junction not in it is dropped (a free end)."""
        through = tuple(mapping[j] for j in self.through if j in mapping)
        return ArcJunctions(mapping.get(self.start), mapping.get(self.end), through)  # type: ignore[arg-type]
