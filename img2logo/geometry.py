"""Frozen geometry values passed between the stages: circles, arcs, abstractions.

Coordinate convention (``contract/README.md``): input-image pixels, x to the
right, y downwards, origin at the top-left corner of the image, so the pixel in
row i, column j has its centre at (x, y) = (j + 0.5, i + 0.5). Angles are in
radians, measured from +x towards +y: with y pointing down a positive sweep turns
clockwise on screen, the same sense as SVG's ``sweep-flag=1``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ._validation import readonly
from .constants import LINE_RADIUS, PHI
from .errors import InvalidParameterError

TAU = 2.0 * math.pi


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
        return np.stack([self.cx + self.r * np.cos(t), self.cy + self.r * np.sin(t)], axis=-1)

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
        """True for a straight line (the lines option): an arc of a ``LINE_RADIUS`` circle without k.

        It is drawn and written as the straight segment from :attr:`start` to
        :attr:`end`; its circle is not on the golden ladder.
        """
        return self.circle.k is None and self.circle.r >= 0.5 * LINE_RADIUS

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


def line_arc(p0: np.ndarray, p1: np.ndarray, side: float = 1.0) -> Arc:
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
    return Arc(circle, t0, math.remainder(t1 - t0, TAU))


@dataclass(frozen=True, eq=False)
class Abstraction:
    """One level A^t of the progressive optimization (Sec. 5.2): a golden ratio logo.

    Attributes
    ----------
    level : int
        The iteration t that produced it (0 for the initial fit).
    arcs : tuple of Arc
        The arcs; ``arcs[i].circle`` is its golden circle.
    arc_segments : tuple of tuple of int
        For each arc, the indices of the segments of the initial segment graph
        that it abstracts (the paper's S_i), in order along the arc.
    junctions : ndarray, shape (J, 2)
        Displaced junction points p_k + d_k, px.
    junction_arcs : tuple of tuple of int
        For each junction, the indices of the arcs that end (or pass) there.
    similarity : float
        E^s of this level (Eqn. 3), px.
    bias : float
        The ladder bias sigma in [0, 1) (Eqn. 10, 14).
    tolerance : float
        The tolerance T the run used, px.
    width, height : int
        Size of the input image, px.
    params : dict
        Every other parameter of the run (kind, RDP tolerance, ...), for the record.
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
    params: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        j = np.asarray(self.junctions, dtype=np.float64).reshape(-1, 2)
        object.__setattr__(self, "junctions", readonly(j.copy()))
        if len(self.arc_segments) != len(self.arcs):
            raise InvalidParameterError(
                f"arc_segments must have one entry per arc ({len(self.arcs)}), got {len(self.arc_segments)}"
            )
        if len(self.junction_arcs) != len(j):
            raise InvalidParameterError(
                f"junction_arcs must have one entry per junction ({len(j)}), got {len(self.junction_arcs)}"
            )

    @property
    def circles(self) -> tuple[Circle, ...]:
        """The distinct circles of the arcs, in order of first use."""
        return tuple(dict.fromkeys(a.circle for a in self.arcs))

    @property
    def phi(self) -> float:
        """The golden ratio this abstraction was built on."""
        return PHI
