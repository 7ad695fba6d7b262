"""Symmetric logos: a mirror axis found in the feature lines, kept exact in the result.

The paper leaves symmetry to future work (Sec. 9). Here a symmetric logo is made
in three steps:

1. :func:`~img2logo.fit.symmetry_axis.find_axis` finds the best mirror axis of the
   feature-line map at any angle (:mod:`img2logo.fit.symmetry_axis`).
2. :func:`half_graph` turns the segment graph into one half of a symmetric
   graph, in a frame where the axis is the vertical line x = ``HalfAxis.x``:
   the half with more line pixels is kept (its mirror image replaces the other
   half, so a detail without a mirror partner is drawn on both sides: the rule
   that makes every circle paired); a segment that crosses the axis is split
   there; points within ``SYMMETRY_SNAP_DISTANCE`` of the axis are put on it,
   junctions there stay there. Where a line meets the axis nearly square
   (``SYMMETRY_SMOOTH_ANGLE``) it runs smoothly into its mirror image: its
   circle is centred on the axis, and its arc and the mirror image are one arc.
3. :func:`optimize_symmetric` runs the progressive optimization on the half
   with those constraints added to Eqn. 13 (:func:`img2logo.fit.progressive.optimize`,
   ``symmetry=``) and mirrors every level: paired circles share k and have
   exactly mirrored centres, merges are made in mirrored pairs, and E^s is
   the half's (each arc and its mirror image are equally far from their pixels).

Coordinates and angles: those of the axis, :mod:`img2logo.geometry.mirror`
(px, x right, y down; an axis at 90 degrees is vertical).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ..constants import SYMMETRY_PAIR_TOLERANCE
from ..errors import InvalidParameterError
from ..geometry.abstraction import Abstraction
from ..geometry.mirror import Axis, axis_segment, circle_pairs, is_symmetric, symmetry_extra
from ..geometry.primitives import TAU, Arc, Circle, cumulative_length, polyline_length
from ..options import check_symmetry_option, refuse_lock_mask  # the options are checked with the others
from .constants import (
    SYMMETRY_MATCH_DISTANCE,
    SYMMETRY_SMOOTH_ANGLE,
    SYMMETRY_SNAP_DISTANCE,
    SYMMETRY_TANGENT_LENGTH,
)

if TYPE_CHECKING:
    from ..segment_graph import SegmentGraph
    from .progressive import Progression
from .symmetry_axis import SymmetryChoice, choose_axis, find_axis

__all__ = [
    "Axis",
    "HalfAxis",
    "HalfGraph",
    "SymmetryChoice",
    "axis_segment",
    "check_symmetry_option",
    "choose_axis",
    "circle_pairs",
    "find_axis",
    "full_graph",
    "half_graph",
    "is_symmetric",
    "mirror_level",
    "optimize_symmetric",
    "symmetry_extra",
]


# --------------------------------------------------------------------------- the half graph
@dataclass(frozen=True, eq=False)
class HalfAxis:
    """The symmetry constraints of the half graph, for :func:`img2logo.fit.progressive.optimize`.

    The optimizer's state reads them as an :class:`img2logo.fit.fit_values.AxisConstraints`.

    Attributes
    ----------
    x : float
        The axis is the vertical line x = ``x`` of the half graph's frame, px.
    nodes : frozenset of int
        Nodes of the half graph on the axis: their junctions stay on it.
    smooth : frozenset of (int, int)
        (segment, node): the segment meets the axis at that node nearly square
        and runs smoothly into its mirror image; a circle whose arc ends there is
        centred on the axis.
    """

    x: float
    nodes: frozenset[int]
    smooth: frozenset[tuple[int, int]]

    def mirror(self, points: np.ndarray) -> np.ndarray:
        """Mirror images of frame points (N, 2): x -> 2 x_axis - x."""
        p = np.array(points, dtype=np.float64)
        p[..., 0] = 2.0 * self.x - p[..., 0]
        return p


@dataclass(frozen=True, eq=False)
class HalfGraph:
    """One half of a symmetric segment graph, in a frame where the axis is vertical.

    Attributes
    ----------
    graph : SegmentGraph
        The half, in frame coordinates.
    axis : Axis
        The mirror axis in image coordinates.
    constraints : HalfAxis
        The axis in the frame and the nodes and segment ends on it.
    rotation : float
        The frame is the image turned by this angle (radians, from +x towards
        +y) about ``axis.point``, so that the axis is vertical.
    paired_fraction : float
        The fraction of the full graph's segment length whose mirror image lies
        within ``SYMMETRY_MATCH_DISTANCE`` of a segment (before the half replaced
        the other half), in [0, 1].
    """

    graph: SegmentGraph
    axis: Axis
    constraints: HalfAxis
    rotation: float
    paired_fraction: float

    def to_image(self, points: np.ndarray) -> np.ndarray:
        """Frame points (..., 2) in image coordinates, px."""
        return _turn(points, -self.rotation, self.axis.point)

    def to_frame(self, points: np.ndarray) -> np.ndarray:
        """Image points (..., 2) in frame coordinates, px."""
        return _turn(points, self.rotation, self.axis.point)


def _turn(points: np.ndarray, angle: float, about: np.ndarray) -> np.ndarray:
    p = np.asarray(points, dtype=np.float64)
    if angle == 0.0:
        return p.copy()
    c, s = math.cos(angle), math.sin(angle)
    q = p - about
    return np.stack([c * q[..., 0] - s * q[..., 1], s * q[..., 0] + c * q[..., 1]], axis=-1) + about


def half_graph(graph: SegmentGraph, axis: Axis) -> HalfGraph:
    """One half of the symmetric segment graph of ``graph`` about ``axis`` (see the module docstring).

    Raises
    ------
    InvalidParameterError
        If no segment is left on the kept half (the drawing lies on the axis).
    """
    rotation = math.pi / 2.0 - math.atan2(axis.direction[1], axis.direction[0])
    if abs(rotation) < 1e-15:
        rotation = 0.0
    a = float(axis.point[0])
    segs = [_turn(s, rotation, axis.point) for s in graph.segments]
    nodes = _turn(graph.junctions, rotation, axis.point)
    # The half with more line length off the axis is kept; sign +1 keeps x <= a.
    left = sum(polyline_length(s[s[:, 0] < a - SYMMETRY_SNAP_DISTANCE]) for s in segs)
    right = sum(polyline_length(s[s[:, 0] > a + SYMMETRY_SNAP_DISTANCE]) for s in segs)
    sign = 1.0 if left >= right else -1.0

    def side(p: np.ndarray) -> np.ndarray:
        v = sign * (np.asarray(p)[..., 0] - a)
        return np.where(np.abs(v) <= SYMMETRY_SNAP_DISTANCE, 0.0, v)

    def snap(p: np.ndarray) -> np.ndarray:
        p = np.array(p, dtype=np.float64)
        p[side(p) == 0.0, 0] = a
        return p

    nodes = snap(nodes)
    new_nodes: list[np.ndarray] = []
    node_id: dict[int, int] = {}

    def old(k: int) -> int:
        if k not in node_id:
            node_id[k] = len(new_nodes)
            new_nodes.append(nodes[k])
        return node_id[k]

    def fresh(p: np.ndarray) -> int:
        new_nodes.append(np.asarray(p, dtype=np.float64))
        return len(new_nodes) - 1

    out_segs: list[np.ndarray] = []
    out_ends: list[tuple[int, int]] = []
    for i, pts in enumerate(segs):
        pts = snap(pts)
        pts[0], pts[-1] = nodes[graph.ends[i, 0]], nodes[graph.ends[i, 1]]
        v = side(pts)
        inside = v <= 0.0
        j = 0
        while j < len(pts):
            if not inside[j]:
                j += 1
                continue
            start = j
            while j < len(pts) and inside[j]:
                j += 1
            run = [pts[start:j]]
            head = old(int(graph.ends[i, 0])) if start == 0 else None
            tail = old(int(graph.ends[i, 1])) if j == len(pts) else None
            if head is None and v[start] != 0.0:
                run.insert(0, _crossing(pts[start - 1], pts[start], a)[None])
            if tail is None and v[j - 1] != 0.0:
                run.append(_crossing(pts[j - 1], pts[j], a)[None])
            piece = np.vstack(run)
            keep = np.ones(len(piece), dtype=bool)
            keep[1:] = np.any(np.diff(piece, axis=0) != 0, axis=1)
            piece = piece[keep]
            if len(piece) < 2 or polyline_length(piece) < 1.0:
                continue
            head = fresh(piece[0]) if head is None else head
            tail = fresh(piece[-1]) if tail is None else tail
            if head == tail:
                continue
            out_segs.append(piece)
            out_ends.append((head, tail))
    if not out_segs:
        raise InvalidParameterError("no line is left on either side of the mirror axis: nothing to make symmetric")
    junctions = np.array(new_nodes).reshape(-1, 2)
    from ..segment_graph import SegmentGraph  # lazily: it loads scipy, which the writers need not

    half = SegmentGraph(tuple(out_segs), junctions, np.array(out_ends), graph.width, graph.height)
    on_axis = frozenset(int(k) for k in np.flatnonzero(junctions[:, 0] == a))
    used = {int(k) for k in half.ends.ravel()}
    smooth = set()
    for i, (k0, k1) in enumerate(half.ends):
        for k, pts in ((int(k0), half.segments[i]), (int(k1), half.segments[i][::-1])):
            if k in on_axis and _square_to_axis(pts):
                smooth.add((i, k))
    constraints = HalfAxis(a, on_axis & used, frozenset(smooth))
    return HalfGraph(half, axis, constraints, rotation, _paired_fraction(graph, axis))


def _crossing(p: np.ndarray, q: np.ndarray, a: float) -> np.ndarray:
    """The point of the segment p-q on the line x = a (exactly on it)."""
    t = (a - p[0]) / (q[0] - p[0])
    return np.array([a, p[1] + t * (q[1] - p[1])])


def _square_to_axis(pts: np.ndarray) -> bool:
    """Whether the line leaving the axis at ``pts[0]`` does so within SYMMETRY_SMOOTH_ANGLE of square."""
    cum = cumulative_length(pts)
    far = pts[min(int(np.searchsorted(cum, SYMMETRY_TANGENT_LENGTH)), len(pts) - 1)]
    d = far - pts[0]
    norm = float(np.hypot(*d))
    return norm > 0 and abs(d[0]) / norm >= math.cos(SYMMETRY_SMOOTH_ANGLE)


def _paired_fraction(graph: SegmentGraph, axis: Axis) -> float:
    """Fraction of the segment length whose mirror image lies within SYMMETRY_MATCH_DISTANCE of a segment."""
    from scipy.spatial import cKDTree

    pts = np.vstack([_resample(s) for s in graph.segments])
    d, _ = cKDTree(pts).query(axis.reflect(pts))
    return float(np.mean(d <= SYMMETRY_MATCH_DISTANCE))


def _resample(points: np.ndarray, step: float = 1.0) -> np.ndarray:
    cum = cumulative_length(points)
    t = np.linspace(0.0, cum[-1], max(2, math.ceil(cum[-1] / step) + 1))
    return np.column_stack([np.interp(t, cum, points[:, 0]), np.interp(t, cum, points[:, 1])])


# --------------------------------------------------------------------------- mirroring
def _arc_to_image(arc: Arc, half: HalfGraph, mirrored: bool) -> Arc:
    """A frame arc (or its mirror image) in image coordinates."""
    c = arc.circle
    cx, theta0, sweep = c.cx, arc.theta0, arc.sweep
    if mirrored:
        cx, theta0, sweep = 2.0 * half.constraints.x - cx, math.pi - theta0, -sweep
    centre = half.to_image(np.array([cx, c.cy]))
    circle = Circle(float(centre[0]), float(centre[1]), c.r, c.k)
    return type(arc)(circle, math.remainder(theta0 - half.rotation, TAU), sweep)  # a line stays a line


def mirror_level(level: Abstraction, half: HalfGraph, record: Mapping[str, Any] | None = None) -> Abstraction:
    """The whole symmetric abstraction of a level of the half graph, in image coordinates.

    Every arc of the half is drawn with its mirror image; an arc whose circle is
    centred on the axis and that ends on it is one arc with its mirror image (a
    full circle when both its ends are on the axis). Segment indices: the half
    graph's segment i is segment i of :func:`full_graph`, its mirror image
    ``n + i`` (n segments in the half). Junctions on the axis are shared. E^s is
    the half's. ``record`` goes into ``params["symmetry"]``.
    """
    a = half.constraints.x
    n_seg = half.graph.n_segments
    arcs: list[Arc] = []
    segments: list[tuple[int, ...]] = []
    left: list[int] = []
    right: list[int] = []
    mirrors: list[tuple[int, Arc, tuple[int, ...]]] = []
    for i, (arc, segs) in enumerate(zip(level.arcs, level.arc_segments, strict=True)):
        on_axis = arc.circle.cx == a
        ends = [
            abs(float(arc.start[0]) - a) <= SYMMETRY_PAIR_TOLERANCE,
            abs(float(arc.end[0]) - a) <= SYMMETRY_PAIR_TOLERANCE,
        ]
        mirror_segs = tuple(n_seg + s for s in reversed(segs))
        if on_axis and any(ends):
            if ends[0] and not ends[1]:  # the axis end last: the arc then runs on into its mirror image
                arc = Arc(arc.circle, arc.theta0 + arc.sweep, -arc.sweep)
                segs = tuple(reversed(segs))
                mirror_segs = tuple(n_seg + s for s in reversed(segs))
            sweep = math.copysign(min(TAU, 2.0 * abs(arc.sweep)), arc.sweep)
            arcs.append(_arc_to_image(Arc(arc.circle, arc.theta0, sweep), half, False))
            segments.append(tuple(segs) + mirror_segs)
            left.append(len(arcs) - 1)
            right.append(len(arcs) - 1)
            continue
        arcs.append(_arc_to_image(arc, half, False))
        segments.append(tuple(segs))
        left.append(len(arcs) - 1)
        right.append(-1)
        mirrors.append((i, arc, mirror_segs))
    for i, arc, segs in mirrors:
        arcs.append(_arc_to_image(arc, half, True))
        segments.append(segs)
        right[i] = len(arcs) - 1
    junctions: list[np.ndarray] = []
    junction_arcs: list[tuple[int, ...]] = []
    mirrored_junctions: list[tuple[np.ndarray, tuple[int, ...]]] = []
    for p, listed in zip(level.junctions, level.junction_arcs, strict=True):
        if abs(float(p[0]) - a) <= SYMMETRY_PAIR_TOLERANCE:
            junctions.append(half.to_image(np.array([a, p[1]])))
            junction_arcs.append(tuple(sorted({left[i] for i in listed} | {right[i] for i in listed})))
        else:
            junctions.append(half.to_image(p))
            junction_arcs.append(tuple(sorted({left[i] for i in listed})))
            mp = np.array([2.0 * a - p[0], p[1]])
            mirrored_junctions.append((half.to_image(mp), tuple(sorted({right[i] for i in listed}))))
    for p, listed in mirrored_junctions:
        junctions.append(p)
        junction_arcs.append(listed)
    params = dict(level.params)
    params["symmetry"] = dict(record) if record is not None else symmetry_record(half)
    return Abstraction(
        level=level.level,
        arcs=tuple(arcs),
        arc_segments=tuple(segments),
        junctions=np.array(junctions).reshape(-1, 2),
        junction_arcs=tuple(junction_arcs),
        similarity=level.similarity,
        bias=level.bias,
        tolerance=level.tolerance,
        width=level.width,
        height=level.height,
        params=params,
        ladder=level.ladder,
        connected=level.connected,
    )


def full_graph(half: HalfGraph) -> SegmentGraph:
    """The symmetric segment graph in image coordinates: the half's segments, then their mirror images.

    Nodes on the axis are shared by a segment and its mirror image.
    """
    g = half.graph
    a = half.constraints.x
    n_j = g.n_junctions
    mirror_node = {}
    extra: list[np.ndarray] = []
    for k in range(n_j):
        if k in half.constraints.nodes or g.junctions[k, 0] == a:
            mirror_node[k] = k
        else:
            mirror_node[k] = n_j + len(extra)
            extra.append(half.constraints.mirror(g.junctions[k]))
    junctions = np.vstack([g.junctions, np.array(extra).reshape(-1, 2)])
    segs = [half.to_image(s) for s in g.segments]
    segs += [half.to_image(half.constraints.mirror(s)) for s in g.segments]
    ends = np.vstack([g.ends, np.vectorize(mirror_node.__getitem__)(g.ends).reshape(-1, 2)])
    from ..segment_graph import SegmentGraph  # lazily: it loads scipy, which the writers need not

    return SegmentGraph(tuple(segs), half.to_image(junctions), ends, g.width, g.height)


def symmetry_record(half: HalfGraph, choice: SymmetryChoice | None = None) -> dict[str, Any]:
    """The ``params["symmetry"]`` entry of a symmetric level: the axis in image pixels, its score, the option."""
    out: dict[str, Any] = {
        "point": [float(v) for v in half.axis.point],
        "direction": [float(v) for v in half.axis.direction],
        "angle": float(half.axis.angle),
        "score": float(half.axis.score),
        "paired_fraction": float(half.paired_fraction),
    }
    if choice is not None:
        out["mode"] = choice.mode
    return out


def optimize_symmetric(
    graph: SegmentGraph,
    axis: Axis,
    *,
    choice: SymmetryChoice | None = None,
    **options: Any,
) -> tuple[Progression, SegmentGraph, HalfGraph]:
    """The progressive optimization of a symmetric logo (see the module docstring).

    Parameters
    ----------
    graph : SegmentGraph
        The segment graph of the whole image.
    axis : Axis
        The mirror axis (:func:`find_axis`, :func:`choose_axis`).
    choice : SymmetryChoice, optional
        Recorded (its mode) in every level's ``params["symmetry"]``.
    **options
        Keyword arguments of :func:`img2logo.fit.progressive.optimize` (not
        ``lock_mask``: a lock mask is not supported with symmetry).

    Returns
    -------
    (Progression, SegmentGraph, HalfGraph)
        The progression whose levels are the whole symmetric abstractions
        (image pixels), the symmetric segment graph they refer to, and the half.
    """
    import dataclasses

    from .progressive import optimize

    refuse_lock_mask(options.pop("lock_mask", None))
    half = half_graph(graph, axis)
    progression = optimize(half.graph, symmetry=half.constraints, **options)
    record = symmetry_record(half, choice)
    levels = tuple(mirror_level(lv, half, record) for lv in progression.levels)
    return dataclasses.replace(progression, levels=levels), full_graph(half), half


# --------------------------------------------------------------------------- output
