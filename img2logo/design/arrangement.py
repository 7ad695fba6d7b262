"""The arrangement of an abstraction's arcs: the closed regions (faces) they bound (paper Sec. 7, Fig. 18).

A golden ratio logo is a set of circular arcs; its colourized versions (Fig. 18,
:mod:`img2logo.design.fills`) fill the closed regions that the arcs bound. This module
computes those regions, the *faces* of the arrangement of the arcs, exactly.

Faces (:func:`faces`). Every arc is split at its end points, at the junctions on
it, at the end points of other arcs that lie on it and at its exact
intersections with the other arcs (circle-circle intersections,
:func:`img2logo.fit.intersections.arc_intersections`); points closer than
``FACE_SNAP_TOLERANCE`` are one vertex, placed on the junction when the group has
one (junctions are exact to about 1e-6 px and arcs end exactly on them). The
pieces form a planar graph whose bridges (dangling arcs, arcs joining two
separate loops) bound no region and are set aside; walking the faces of the
rest (at each vertex the next piece clockwise, ordered by tangent direction and
then curvature, so that tangent arcs are ordered right) gives closed loops of
pieces; loops of one connected component that turn positively are its bounded
faces, the one that turns negatively its outline, which is a hole of the
smallest face of another component around it (an eye inside a head: the head's
face gets the eye's outline as a hole, and the eye is a face of its own). A
face keeps its loops as pieces of the original arcs, so its SVG path
(:attr:`Face.path`, :func:`img2logo.geometry.svg_path.loop_path`) is made of exact
elliptical-arc commands (``A``) that end on the junctions, and its area is
computed exactly (Green's theorem on arcs).

Coordinates are input-image pixels, x right, y down; angles in radians from +x
towards +y (clockwise on screen), as everywhere in img2logo. Shapely and SciPy
are imported inside the functions that need them.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from .._validation import check_instance, check_positive
from ..constants import ARC_SAMPLE_STEP, INTERSECTION_TOL
from ..geometry.abstraction import Abstraction
from ..geometry.primitives import TAU, Circle
from ..geometry.svg_path import loop_path

if TYPE_CHECKING:
    from shapely.geometry import Polygon

__all__ = ["FACE_MIN_AREA", "FACE_SNAP_TOLERANCE", "ArcPiece", "Face", "face_adjacency", "faces"]

#: Points where arcs end or meet that are closer than this are one vertex of the
#: arrangement, px. Junctions are exact to about 1e-6 px; this also absorbs the
#: two crossings, a few hundredths of a px apart, of circles that should touch
#: tangentially at a junction but overlap by a rounding error.
FACE_SNAP_TOLERANCE: float = 0.05
#: Faces smaller than this are dropped, px^2: slivers between nearly tangent arcs,
#: invisible under the strokes.
FACE_MIN_AREA: float = 1.0
#: Arc length at which pieces leaving a vertex along one tangent are told apart
#: by their curvature, px.
_CURVATURE_PROBE: float = 1e-3


@dataclass(frozen=True)
class ArcPiece:
    """A piece of one arc of an abstraction, as walked along a face boundary.

    Attributes
    ----------
    arc : int
        Index of the arc in ``abstraction.arcs``.
    circle : Circle
        Its circle.
    t0, t1 : float
        Angles on the circle where the piece starts and ends, radians, in the
        direction of the walk (``t1 - t0`` is the signed sweep, within the arc's
        angle range ``theta0 .. theta0 + sweep``).
    start, end : (float, float)
        The vertices the piece joins, px: the junction when there is one at that
        vertex, otherwise the point where the arcs meet. Within
        ``FACE_SNAP_TOLERANCE`` of ``circle.point_at(t0)`` and ``point_at(t1)``.
    edge : int
        Index of the piece in the arrangement: the two faces on either side of a
        piece both list it with the same ``edge``.
    """

    arc: int
    circle: Circle
    t0: float
    t1: float
    start: tuple[float, float]
    end: tuple[float, float]
    edge: int

    @property
    def sweep(self) -> float:
        """Signed sweep ``t1 - t0``, radians."""
        return self.t1 - self.t0

    @property
    def length(self) -> float:
        """Length of the piece, px."""
        return abs(self.sweep) * self.circle.r

    def sample(self, step: float = ARC_SAMPLE_STEP) -> np.ndarray:
        """Points along the piece about ``step`` px apart, shape (N, 2), N >= 4, px.

        The first and last points are ``start`` and ``end`` exactly.
        """
        n = max(4, math.ceil(self.length / step) + 1)
        pts = self.circle.point_at(np.linspace(self.t0, self.t1, n))
        pts[0] = self.start
        pts[-1] = self.end
        return pts


@dataclass(frozen=True, eq=False)
class Face:
    """A bounded region of the plane cut out by the arcs: what Fig. 18 colours.

    Attributes
    ----------
    polygon : shapely.geometry.Polygon
        The face sampled about every 0.5 px along its boundary, with its holes,
        px. For rasterizing and point tests; the exact boundary is below. Always
        valid for shapely: where the boundary passes a vertex twice (a tiny
        loop of two crossing arcs hanging at the crossing, lobes meeting at a
        point) it is :func:`shapely.make_valid`'s repair, a polygon whose hole
        touches its shell or, for lobes, a ``MultiPolygon``.
    boundary : tuple of ArcPiece
        The outer boundary, pieces of the original arcs in order (each piece
        starts where the previous one ends; the last ends at the first's start),
        turning positively (counter-clockwise with y up, clockwise on screen).
    holes : tuple of tuple of ArcPiece
        Inner boundaries (e.g. the outline of an eye inside a head), each a loop
        of pieces turning negatively. The region inside a hole is not part of
        the face (it may be a face itself).
    area : float
        Exact area of the face (outer region less the holes), px^2.
    """

    polygon: Polygon
    boundary: tuple[ArcPiece, ...]
    holes: tuple[tuple[ArcPiece, ...], ...]
    area: float

    @property
    def loops(self) -> tuple[tuple[ArcPiece, ...], ...]:
        """The boundary and then the holes."""
        return (self.boundary, *self.holes)

    @property
    def arcs(self) -> frozenset[int]:
        """Indices of the arcs that bound the face."""
        return frozenset(p.arc for loop in self.loops for p in loop)

    @property
    def centroid(self) -> tuple[float, float]:
        """Centroid of the sampled polygon, px (may lie outside a non-convex face)."""
        c = self.polygon.centroid
        return (float(c.x), float(c.y))

    @property
    def path(self) -> str:
        """SVG path data of the face with exact elliptical-arc commands.

        One subpath per loop (``M x y A r r 0 large-arc sweep x y ... Z``), the
        boundary first and then the holes: draw it with ``fill-rule="evenodd"``
        (the holes then stay empty whatever their orientation). Consecutive
        pieces of one circle are joined into one command; a command that would
        turn more than ``2 pi - 1e-3`` is split in two halves, so a face bounded
        by one full circle is ``M p A r r 0 0 f q A r r 0 0 f p Z``. Every
        command ends on a vertex (a junction where there is one), written with
        ``SVG_DECIMALS`` decimals, like the arcs of :func:`img2logo.export.writers.write_svg`
        (both by :mod:`img2logo.geometry.svg_path`).
        """
        return " ".join(loop_path(loop) for loop in self.loops)


def faces(
    abstraction: Abstraction,
    *,
    snap: float = FACE_SNAP_TOLERANCE,
    min_area: float = FACE_MIN_AREA,
    step: float = ARC_SAMPLE_STEP,
) -> tuple[Face, ...]:
    """The faces of the arrangement of an abstraction's arcs: the closed regions they bound.

    The regions that Fig. 18 (Sec. 7) colours. See the module docstring for the
    method: exact splitting of the arcs at their meeting points, a planar graph
    of the pieces without its bridges, and a walk of its faces; holes are the
    outlines of separate components inside a face.

    Parameters
    ----------
    abstraction : Abstraction
        The logo.
    snap : float
        Points closer than this are one vertex, px (``FACE_SNAP_TOLERANCE``).
    min_area : float
        Faces smaller than this are dropped, px^2 (``FACE_MIN_AREA``); 0 keeps all.
    step : float
        Spacing of the samples of :attr:`Face.polygon`, px.

    Returns
    -------
    tuple of Face
        Largest first (ties: by centroid, top to bottom, then left to right).
        Faces do not overlap; a face inside another's hole is listed too.
        Empty when the arcs bound no region (e.g. open strokes only).
    """
    check_instance(abstraction, Abstraction, "abstraction")
    snap = check_positive(snap, "snap")
    min_area = check_positive(min_area, "min_area", allow_zero=True)
    step = check_positive(step, "step")
    from shapely.geometry import Polygon

    graph = _Arrangement(abstraction, snap)
    cycles, outer_of_component, component_of_cycle = graph.cycles()
    if not cycles:
        return ()
    areas = [graph.cycle_area(c) for c in cycles]
    bounded = [i for i in range(len(cycles)) if i not in outer_of_component.values() and areas[i] > 0.0]
    rings = {i: graph.sample_cycle(cycles[i], step) for i in range(len(cycles))}
    polygons = {i: _ring_polygon(rings[i]) for i in bounded}

    # The outline of every component is a hole of the smallest bounded face of
    # another component around it (components do not cross each other).
    holes: dict[int, list[int]] = {i: [] for i in bounded}
    import shapely

    for comp, outer in sorted(outer_of_component.items()):
        probe = graph.cycle_probe(cycles[outer])
        best, best_area = -1, math.inf
        for i in bounded:
            if component_of_cycle[i] == comp or areas[i] >= best_area:
                continue
            if bool(shapely.contains_xy(polygons[i], probe[0], probe[1])):
                best, best_area = i, areas[i]
        if best >= 0:
            holes[best].append(outer)

    result = []
    for i in bounded:
        area = areas[i] + sum(areas[h] for h in holes[i])
        if area < min_area:
            continue
        polygon = _valid_polygon(Polygon(rings[i], [rings[h] for h in holes[i]]))
        result.append(
            Face(
                polygon=polygon,
                boundary=graph.pieces(cycles[i]),
                holes=tuple(graph.pieces(cycles[h]) for h in holes[i]),
                area=float(area),
            )
        )

    def order(face: Face) -> tuple[float, float, float]:
        cx, cy = face.centroid
        return (-round(face.area, 6), round(cy, 6), round(cx, 6))

    return tuple(sorted(result, key=order))


def face_adjacency(face_list: Sequence[Face]) -> list[set[int]]:
    """For each face, the indices of the faces that share a piece of arc with it.

    Faces that only touch at a point are not adjacent.
    """
    owners: dict[int, list[int]] = {}
    for i, face in enumerate(face_list):
        for loop in face.loops:
            for piece in loop:
                owners.setdefault(piece.edge, []).append(i)
    adjacent: list[set[int]] = [set() for _ in face_list]
    for members in owners.values():
        for i in members:
            adjacent[i].update(j for j in members if j != i)
    return adjacent


class _Arrangement:
    """The planar graph of the pieces of the arcs (the arcs split where they meet)."""

    def __init__(self, abstraction: Abstraction, snap: float) -> None:
        from ..fit.intersections import arc_intersections

        arcs = abstraction.arcs
        self.snap = snap
        points: list[np.ndarray] = []
        priority: list[int] = []  # 0 junction, 1 arc end, 2 intersection: the vertex sits on the lowest
        stops: list[list[tuple[float, int]]] = [[] for _ in arcs]

        def add(p: np.ndarray, prio: int) -> int:
            points.append(np.asarray(p, dtype=np.float64))
            priority.append(prio)
            return len(points) - 1

        for i, a in enumerate(arcs):
            stops[i].append((0.0, add(a.start, 1)))
            stops[i].append((1.0, add(a.end, 1)))
        for p in abstraction.junctions:
            add(p, 0)
        # Junctions and end points of other arcs lying on an arc split it.
        candidates = np.array(points).reshape(-1, 2)
        ids = np.arange(len(candidates))
        for i, a in enumerate(arcs):
            u = _params_on_arc(a, candidates, snap)
            own = (ids == 2 * i) | (ids == 2 * i + 1)
            for k in np.flatnonzero(np.isfinite(u) & ~own):
                stops[i].append((float(u[k]), int(k)))
        # Exact crossings of every pair of arcs whose circles' boxes overlap.
        boxes = np.array([[a.circle.cx, a.circle.cy, a.circle.r] for a in arcs]).reshape(-1, 3)
        for i in range(len(arcs)):
            for m in range(i + 1, len(arcs)):
                ci, cm = boxes[i], boxes[m]
                if abs(ci[0] - cm[0]) > ci[2] + cm[2] + snap or abs(ci[1] - cm[1]) > ci[2] + cm[2] + snap:
                    continue
                for p in arc_intersections(arcs[i], arcs[m], tol=INTERSECTION_TOL):
                    k = add(p, 2)
                    for idx in (i, m):
                        u = _params_on_arc(arcs[idx], p[None, :], snap)[0]
                        if np.isfinite(u):
                            stops[idx].append((float(u), k))

        # Vertices: points within `snap` of each other, joined transitively.
        pts = np.array(points).reshape(-1, 2)
        vertex_of_point = _cluster(pts, snap)
        n_vertices = int(vertex_of_point.max()) + 1 if len(pts) else 0
        rep = np.zeros((n_vertices, 2))
        best = np.full(n_vertices, 99)
        for k, v in enumerate(vertex_of_point):
            if priority[k] < best[v]:
                best[v], rep[v] = priority[k], pts[k]
        self.vertices = rep

        # Pieces: consecutive stops along each arc; a piece that only repeats another
        # (arcs overlapping on one circle) is kept once, on the lower arc index.
        edges: list[tuple[int, float, float, int, int]] = []
        by_ends: dict[tuple[int, int], list[int]] = {}
        for i, a in enumerate(arcs):
            length = abs(a.sweep) * a.circle.r
            ordered = sorted((u, int(vertex_of_point[k])) for u, k in stops[i])
            merged: list[tuple[float, int]] = []
            for u, v in ordered:
                if merged and merged[-1][1] == v and (u - merged[-1][0]) * length < 4.0 * snap:
                    continue
                merged.append((u, v))
            for (u0, v0), (u1, v1) in itertools.pairwise(merged):
                if v0 == v1 and (u1 - u0) * length < 4.0 * snap:
                    continue
                t0, t1 = a.theta0 + a.sweep * u0, a.theta0 + a.sweep * u1
                mid = a.circle.point_at(0.5 * (t0 + t1))
                key = (min(v0, v1), max(v0, v1))
                twins = by_ends.setdefault(key, [])
                if any(_same_piece(edges[e], arcs, mid, snap) for e in twins):
                    continue
                twins.append(len(edges))
                edges.append((i, t0, t1, v0, v1))
        self.arcs = arcs
        self.edges = edges
        bridges = _bridges(n_vertices, [(e[3], e[4]) for e in edges])
        self.kept = [e for e in range(len(edges)) if e not in bridges]

    # half-edge h = 2 e walks edge e from its first vertex to its second, h = 2 e + 1 back.
    def _half(self, h: int) -> tuple[Circle, float, float, int, int, int]:
        arc, t0, t1, v0, v1 = self.edges[h // 2]
        circle = self.arcs[arc].circle
        if h % 2 == 0:
            return circle, t0, t1, v0, v1, arc
        return circle, t1, t0, v1, v0, arc

    def cycles(self) -> tuple[list[list[int]], dict[int, int], dict[int, int]]:
        """Face loops (lists of half-edges), the outline loop of each component, each loop's component."""
        if not self.kept:
            return [], {}, {}
        outgoing: dict[int, list[tuple[float, int]]] = {}
        parent = list(range(len(self.vertices)))

        def find(v: int) -> int:
            while parent[v] != v:
                parent[v] = parent[parent[v]]
                v = parent[v]
            return v

        for e in self.kept:
            for h in (2 * e, 2 * e + 1):
                circle, ta, tb, va, _, _ = self._half(h)
                s = 1.0 if tb > ta else -1.0
                direction = math.atan2(s * math.cos(ta), -s * math.sin(ta))
                # Tangent pieces: the one turning more to the left (curvature s / r) comes later.
                key = math.fmod(direction + 0.5 * _CURVATURE_PROBE * s / circle.r + 2.0 * TAU, TAU)
                outgoing.setdefault(va, []).append((key, h))
            _, _, _, va, vb, _ = self._half(2 * e)
            parent[find(va)] = find(vb)
        position: dict[int, tuple[int, int]] = {}
        for v, lst in outgoing.items():
            lst.sort()
            for i, (_, h) in enumerate(lst):
                position[h] = (v, i)

        def following(h: int) -> int:
            v, i = position[h ^ 1]
            lst = outgoing[v]
            return lst[(i - 1) % len(lst)][1]

        seen: set[int] = set()
        cycles: list[list[int]] = []
        for e in self.kept:
            for h in (2 * e, 2 * e + 1):
                if h in seen:
                    continue
                loop = []
                while h not in seen:
                    seen.add(h)
                    loop.append(h)
                    h = following(h)
                cycles.append(loop)
        component_of_cycle = {i: find(self._half(c[0])[3]) for i, c in enumerate(cycles)}
        areas = [self.cycle_area(c) for c in cycles]
        outer: dict[int, int] = {}
        for i in range(len(cycles)):
            comp = component_of_cycle[i]
            if comp not in outer or areas[i] < areas[outer[comp]]:
                outer[comp] = i
        return cycles, outer, component_of_cycle

    def cycle_area(self, cycle: list[int]) -> float:
        """Signed area enclosed by a loop of half-edges, px^2 (Green's theorem, exact on arcs).

        Positive for a loop turning counter-clockwise with y up (clockwise on
        screen). The gaps between consecutive pieces (< ``snap``) are closed by
        straight segments.
        """
        total = 0.0
        ends = []
        for h in cycle:
            c, ta, tb, _, _, _ = self._half(h)
            # 1/2 of the integral of x dy - y dx along the arc.
            total += 0.5 * (
                c.r * c.cx * (math.sin(tb) - math.sin(ta))
                - c.r * c.cy * (math.cos(tb) - math.cos(ta))
                + c.r**2 * (tb - ta)
            )
            ends.append((c.point_at(ta), c.point_at(tb)))
        for k in range(len(ends)):
            p, q = ends[k][1], ends[(k + 1) % len(ends)][0]
            total += 0.5 * (p[0] * q[1] - q[0] * p[1])
        return float(total)

    def cycle_probe(self, cycle: list[int]) -> np.ndarray:
        """A point on the loop: the middle of its first piece, px."""
        c, ta, tb, _, _, _ = self._half(cycle[0])
        return c.point_at(0.5 * (ta + tb))

    def sample_cycle(self, cycle: list[int], step: float) -> np.ndarray:
        """The loop as a closed polyline (first point not repeated), shape (N, 2), px."""
        return np.concatenate([p.sample(step)[:-1] for p in self.pieces(cycle)])

    def pieces(self, cycle: list[int]) -> tuple[ArcPiece, ...]:
        out = []
        for h in cycle:
            circle, ta, tb, va, vb, arc = self._half(h)
            start = (float(self.vertices[va, 0]), float(self.vertices[va, 1]))
            end = (float(self.vertices[vb, 0]), float(self.vertices[vb, 1]))
            out.append(ArcPiece(arc=arc, circle=circle, t0=ta, t1=tb, start=start, end=end, edge=h // 2))
        return tuple(out)


def _params_on_arc(arc: Any, points: np.ndarray, tol: float) -> np.ndarray:
    """Parameters u in [0, 1] along ``arc`` of ``points`` (K, 2) lying on it within ``tol`` px; NaN elsewhere."""
    c = arc.circle
    p = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    off_circle = np.abs(np.hypot(p[:, 0] - c.cx, p[:, 1] - c.cy) - c.r)
    theta = np.arctan2(p[:, 1] - c.cy, p[:, 0] - c.cx)
    span = abs(arc.sweep)
    offset = np.mod((theta - arc.theta0) * math.copysign(1.0, arc.sweep), TAU)
    angle_tol = tol / c.r
    if arc.is_full_circle:
        u = np.minimum(offset / span, 1.0)
    else:
        u = offset / span
        beyond = offset > span
        u = np.where(beyond & (offset <= span + angle_tol), 1.0, u)
        u = np.where(beyond & (offset >= TAU - angle_tol), 0.0, u)
        u = np.where(beyond & (offset > span + angle_tol) & (offset < TAU - angle_tol), np.nan, u)
    return np.where(off_circle <= tol, u, np.nan)


def _cluster(points: np.ndarray, tol: float) -> np.ndarray:
    """Label points joined by chains of neighbours closer than ``tol``: labels 0.. in first-seen order."""
    n = len(points)
    if n == 0:
        return np.zeros(0, dtype=np.int64)
    from scipy.spatial import cKDTree

    parent = np.arange(n)

    def find(i: int) -> int:
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return int(i)

    for i, j in sorted(cKDTree(points).query_pairs(tol)):
        ri, rj = find(i), find(j)
        if ri != rj:
            parent[max(ri, rj)] = min(ri, rj)
    roots = [find(i) for i in range(n)]
    labels: dict[int, int] = {}
    return np.array([labels.setdefault(r, len(labels)) for r in roots], dtype=np.int64)


def _same_piece(edge: tuple[int, float, float, int, int], arcs: Sequence[Any], mid: np.ndarray, tol: float) -> bool:
    """True when ``edge`` has its middle within ``tol`` of ``mid`` (same ends assumed): a repeated piece."""
    arc, t0, t1, _, _ = edge
    other = arcs[arc].circle.point_at(0.5 * (t0 + t1))
    return float(np.hypot(*(other - mid))) <= tol


def _bridges(n_vertices: int, ends: list[tuple[int, int]]) -> set[int]:
    """Indices of the bridges of a multigraph (edges whose removal disconnects it); loops never are."""
    adjacency: list[list[tuple[int, int]]] = [[] for _ in range(n_vertices)]
    for e, (a, b) in enumerate(ends):
        if a != b:
            adjacency[a].append((b, e))
            adjacency[b].append((a, e))
    disc = [-1] * n_vertices
    low = [0] * n_vertices
    timer = 0
    bridges: set[int] = set()
    for root in range(n_vertices):
        if disc[root] != -1 or not adjacency[root]:
            continue
        disc[root] = low[root] = timer
        timer += 1
        stack = [(root, -1, iter(adjacency[root]))]
        while stack:
            v, via, it = stack[-1]
            for w, e in it:
                if e == via:
                    continue
                if disc[w] == -1:
                    disc[w] = low[w] = timer
                    timer += 1
                    stack.append((w, e, iter(adjacency[w])))
                    break
                low[v] = min(low[v], disc[w])
            else:
                stack.pop()
                if stack:
                    u = stack[-1][0]
                    low[u] = min(low[u], low[v])
                    if low[v] > disc[u]:
                        bridges.add(via)
    return bridges


def _ring_polygon(ring: np.ndarray) -> Polygon:
    from shapely.geometry import Polygon

    return _valid_polygon(Polygon(ring))


def _valid_polygon(polygon: Polygon) -> Polygon:
    """``polygon`` made valid for shapely when its boundary touches itself at a vertex.

    A face walk can pass a vertex twice (a small loop of two arcs hanging at a
    crossing, two lobes meeting at a point): the ring is then not simple and
    shapely calls it invalid. :func:`shapely.make_valid` turns it into a polygon
    with a hole touching the shell, or into a MultiPolygon of the lobes.
    """
    import shapely
    from shapely.geometry import MultiPolygon, Polygon

    if polygon.is_valid:
        return polygon
    parts = [g for g in shapely.get_parts(shapely.make_valid(polygon)) if isinstance(g, Polygon) and not g.is_empty]
    if len(parts) == 1:
        return parts[0]
    return MultiPolygon(parts)
