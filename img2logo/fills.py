"""Colour fills of the regions bounded by the arcs (paper Sec. 7, Fig. 18; Sec. 9, future work).

A golden ratio logo is a set of circular arcs; its colourized versions (Fig. 18)
fill the closed regions that the arcs bound. This module computes those regions,
the *faces* of the arrangement of the arcs, exactly, and colours them in three
ways:

- a user palette (:func:`fill_palette`): Fig. 18's "simple color palette";
- a linear or radial gradient over the logo (:func:`fill_gradient`): Fig. 18's
  "gradients";
- automatic colours from the input image (:func:`fill_auto`): the paper's future
  work (Sec. 9, "automatically fill colors ... according to the full color
  information of the input image"): each face takes the median colour, in
  CIELAB, of the input pixels under it; faces of the image's background colour
  and faces that reach the image border are left empty.

Faces (:func:`faces`). Every arc is split at its end points, at the junctions on
it, at the end points of other arcs that lie on it and at its exact
intersections with the other arcs (circle-circle intersections,
:func:`img2logo.arc_extraction.arc_intersections`); points closer than
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
(:attr:`Face.path`) is made of exact elliptical-arc commands (``A``) that end on
the junctions, and its area is computed exactly (Green's theorem on arcs).

Colours are ``#rrggbb`` strings, as in the ``fills`` key of the
``img2logo.abstraction/1`` document (``contract/README.md``). A :class:`Fill` is
a face's SVG path and its colour, optionally with a :class:`Gradient`; the
writers (:func:`img2logo.writers.write_svg`, ``write_json``, ``write_png``) take
a tuple of fills. The command line's ``--fill`` option is parsed by
:func:`parse_fill_option`.

Coordinates are input-image pixels, x right, y down; angles in radians from +x
towards +y (clockwise on screen), as everywhere in img2logo. Shapely and
scikit-image are imported inside the functions that need them.
"""

from __future__ import annotations

import itertools
import math
import re
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ._validation import check_choice, check_positive
from .constants import ARC_SAMPLE_STEP, INTERSECTION_TOL, LINE_RADIUS, SVG_DECIMALS
from .errors import InvalidParameterError
from .geometry import TAU, Abstraction, Circle

if TYPE_CHECKING:
    from shapely.geometry import Polygon

__all__ = [
    "AUTO_FILL_INSET",
    "BACKGROUND_DISTANCE",
    "DEFAULT_GRADIENT_ANGLE",
    "FACE_MIN_AREA",
    "FACE_SNAP_TOLERANCE",
    "ArcPiece",
    "Face",
    "Fill",
    "FillSpec",
    "Gradient",
    "face_adjacency",
    "faces",
    "fill_auto",
    "fill_gradient",
    "fill_palette",
    "parse_color",
    "parse_fill_option",
    "sample_path",
]

#: Points where arcs end or meet that are closer than this are one vertex of the
#: arrangement, px. Junctions are exact to about 1e-6 px; this also absorbs the
#: two crossings, a few hundredths of a px apart, of circles that should touch
#: tangentially at a junction but overlap by a rounding error.
FACE_SNAP_TOLERANCE: float = 0.05
#: Faces smaller than this are dropped, px^2: slivers between nearly tangent arcs,
#: invisible under the strokes.
FACE_MIN_AREA: float = 1.0
#: :func:`fill_auto`: the face is shrunk by this much before its pixels are read,
#: px, so that anti-aliased boundary pixels and the neighbouring region (the arcs
#: are within the tolerance T of the image's edges, not on them) do not bleed in.
AUTO_FILL_INSET: float = 2.0
#: :func:`fill_auto` with a ``background`` colour: a face within this CIELAB Delta E
#: 76 of it is left empty (a visible difference: five times the just noticeable one).
BACKGROUND_DISTANCE: float = 12.0
#: :func:`fill_auto`: width of the image border whose median colour is the
#: background colour, px.
BORDER_WIDTH: int = 2
#: :func:`fill_auto`: a face whose inset leaves fewer pixels than this is read
#: without the inset.
AUTO_FILL_MIN_PIXELS: int = 8
#: Default direction of a linear gradient, radians from +x towards +y: pi/2 runs
#: from the top of the logo (first colour) to its bottom (last colour).
DEFAULT_GRADIENT_ANGLE: float = math.pi / 2.0

#: An arc command whose |sweep| exceeds this is written as two commands (as the
#: arcs themselves are in :func:`img2logo.writers.write_svg`): near a full turn
#: its end points are too close for a renderer to place the centre reliably.
_NEAR_FULL_SWEEP: float = TAU - 1e-3
#: Arc length at which pieces leaving a vertex along one tangent are told apart
#: by their curvature, px.
_CURVATURE_PROBE: float = 1e-3
_HEX = re.compile(r"^#[0-9a-fA-F]{6}$")
_FILL_MODES = ("none", "auto", "palette", "linear", "radial")
_FILL_SYNTAX = (
    "'none', 'auto', 'palette:#rrggbb,#rrggbb,...', 'linear[@degrees]:#rrggbb,#rrggbb,...' "
    "or 'radial:#rrggbb,#rrggbb,...'"
)


# --- values --------------------------------------------------------------------------


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
        ``SVG_DECIMALS`` decimals, like the arcs of :func:`img2logo.writers.write_svg`.
        """
        return " ".join(_loop_path(loop) for loop in self.loops)


@dataclass(frozen=True)
class Gradient:
    """A linear or radial colour gradient, in image pixels (SVG ``userSpaceOnUse``).

    Attributes
    ----------
    kind : {"linear", "radial"}
        ``"linear"``: the colour varies along the vector ``start -> end`` (SVG
        ``x1 y1 x2 y2``), offset 0 at ``start``, 1 at ``end``, constant across.
        ``"radial"``: ``start`` is the centre (offset 0) and the circle through
        ``end`` has offset 1 (SVG ``cx cy r``).
    stops : tuple of (float, str)
        ``(offset, "#rrggbb")`` pairs, offsets non-decreasing in [0, 1], at least
        two. Colours are interpolated linearly in sRGB between stops and held
        beyond the first and the last (SVG's defaults: ``color-interpolation``
        sRGB, ``spreadMethod`` pad).
    start, end : (float, float)
        See ``kind``, px.
    """

    kind: str
    stops: tuple[tuple[float, str], ...]
    start: tuple[float, float]
    end: tuple[float, float]

    def __post_init__(self) -> None:
        check_choice(self.kind, "gradient kind", ("linear", "radial"))
        stops = tuple(self.stops)
        if len(stops) < 2:
            raise InvalidParameterError(f"a gradient needs at least two stops, got {len(stops)}")
        clean = []
        last = 0.0
        for i, stop in enumerate(stops):
            try:
                offset, color = stop
                offset = float(offset)
            except (TypeError, ValueError) as exc:
                raise InvalidParameterError(f"gradient stop {i} must be a pair (offset, colour), got {stop!r}") from exc
            if not (math.isfinite(offset) and last <= offset <= 1.0):
                raise InvalidParameterError(
                    f"gradient stop {i}: offsets must be non-decreasing in [0, 1], got {offset!r} after {last!r}"
                )
            last = offset
            clean.append((offset, parse_color(color, f"gradient stop {i} colour")))
        object.__setattr__(self, "stops", tuple(clean))
        for name in ("start", "end"):
            value = getattr(self, name)
            try:
                x, y = (float(v) for v in value)
            except (TypeError, ValueError) as exc:
                raise InvalidParameterError(f"gradient {name} must be a point (x, y), got {value!r}") from exc
            if not (math.isfinite(x) and math.isfinite(y)):
                raise InvalidParameterError(f"gradient {name} must be finite, got {value!r}")
            object.__setattr__(self, name, (x, y))
        if self.start == self.end:
            raise InvalidParameterError(f"gradient start and end must differ, got {self.start} twice")

    def offsets(self, points: np.ndarray) -> np.ndarray:
        """Gradient offsets of ``points`` (..., 2), clipped to [0, 1]."""
        p = np.asarray(points, dtype=np.float64)
        s = np.asarray(self.start)
        d = np.asarray(self.end) - s
        if self.kind == "linear":
            t = ((p - s) @ d) / float(d @ d)
        else:
            t = np.hypot(p[..., 0] - s[0], p[..., 1] - s[1]) / math.hypot(d[0], d[1])
        return np.clip(t, 0.0, 1.0)

    def color_at(self, points: np.ndarray) -> np.ndarray:
        """The gradient's colours at ``points`` (..., 2): RGB floats in [0, 1], shape (..., 3)."""
        t = self.offsets(points)
        offs = np.array([o for o, _ in self.stops])
        rgb = np.array([_hex_to_rgb(c) for _, c in self.stops])
        return np.stack([np.interp(t, offs, rgb[:, k]) for k in range(3)], axis=-1)

    def svg(self, element_id: str) -> str:
        """The ``<linearGradient>`` or ``<radialGradient>`` element, in user space (image px)."""
        n = _svg_number
        (x1, y1), (x2, y2) = self.start, self.end
        if self.kind == "linear":
            head = f'<linearGradient id="{element_id}" gradientUnits="userSpaceOnUse" x1="{n(x1)}" y1="{n(y1)}" '
            head += f'x2="{n(x2)}" y2="{n(y2)}">'
            tail = "</linearGradient>"
        else:
            r = math.hypot(x2 - x1, y2 - y1)
            head = f'<radialGradient id="{element_id}" gradientUnits="userSpaceOnUse" cx="{n(x1)}" cy="{n(y1)}" '
            head += f'r="{n(r)}">'
            tail = "</radialGradient>"
        stops = "".join(f'<stop offset="{n(o)}" stop-color="{c}"/>' for o, c in self.stops)
        return head + stops + tail


@dataclass(frozen=True)
class Fill:
    """One filled region: an SVG path and its colour (an entry of the document's ``fills``).

    Attributes
    ----------
    path : str
        SVG path data of the region, normally :attr:`Face.path` (exact arc
        commands, one subpath per loop), drawn with ``fill-rule="evenodd"``.
    color : str
        ``#rrggbb`` (lower case). With a gradient, the gradient's colour at the
        face's centroid: the ``img2logo.abstraction/1`` document only knows one
        colour per region, so that is what the JSON records, while the SVG and
        the PNG draw the true gradient.
    gradient : Gradient or None
        Paint the region with this gradient instead of ``color`` (SVG, PNG).
    face : int or None
        Index of the face in :func:`faces` of the abstraction, when known (None
        for fills read back from a document).
    """

    path: str
    color: str
    gradient: Gradient | None = None
    face: int | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.path, str) or not self.path.strip().upper().startswith("M"):
            raise InvalidParameterError(f"fill path must be SVG path data starting with 'M', got {self.path!r:.60}")
        object.__setattr__(self, "color", parse_color(self.color, "fill color"))
        if self.gradient is not None and not isinstance(self.gradient, Gradient):
            raise InvalidParameterError(f"fill gradient must be a Gradient or None, got {type(self.gradient).__name__}")
        if self.face is not None and (isinstance(self.face, bool) or not isinstance(self.face, int | np.integer)):
            raise InvalidParameterError(f"fill face must be an integer or None, got {self.face!r}")

    def rings(self, step: float = ARC_SAMPLE_STEP) -> list[np.ndarray]:
        """The closed loops of :attr:`path` sampled about ``step`` px apart (see :func:`sample_path`)."""
        return sample_path(self.path, step)

    def to_json(self) -> dict[str, str]:
        """The document entry ``{"path": ..., "color": ...}``."""
        return {"path": self.path, "color": self.color}


@dataclass(frozen=True)
class FillSpec:
    """A parsed ``--fill`` option (see :func:`parse_fill_option`).

    Attributes
    ----------
    mode : {"none", "auto", "palette", "linear", "radial"}
    colors : tuple of str
        The ``#rrggbb`` colours of a palette or gradient, in order.
    angle : float
        Direction of a linear gradient, radians from +x towards +y.
    """

    mode: str
    colors: tuple[str, ...] = ()
    angle: float = DEFAULT_GRADIENT_ANGLE

    def make(self, abstraction: Abstraction, image: Any = None) -> tuple[Fill, ...]:
        """The fills of ``abstraction`` this option asks for.

        Parameters
        ----------
        abstraction : Abstraction
        image : ndarray or LoadedImage, optional
            The input image; needed by ``"auto"`` (see :func:`fill_auto`).

        Returns
        -------
        tuple of Fill
            Empty for ``"none"``.
        """
        if self.mode == "none":
            return ()
        if self.mode == "auto":
            if image is None:
                raise InvalidParameterError("fill mode 'auto' needs the input image, got None")
            return fill_auto(abstraction, image)
        if self.mode == "palette":
            return fill_palette(abstraction, self.colors)
        return fill_gradient(abstraction, self.colors, kind=self.mode, angle=self.angle)


# --- faces of the arrangement ----------------------------------------------------------


def check_fills(fills: object) -> list[Fill] | None:
    """``fills`` as a list of :class:`Fill`, or None when not given (writers and plotting)."""
    if fills is None:
        return None
    if isinstance(fills, Fill | str) or not isinstance(fills, Sequence):
        raise InvalidParameterError(f"fills must be a sequence of Fill, got {type(fills).__name__}")
    out = list(fills)
    for i, f in enumerate(out):
        if not isinstance(f, Fill):
            raise InvalidParameterError(f"fills[{i}] must be a Fill, got {type(f).__name__}")
    return out


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
    if not isinstance(abstraction, Abstraction):
        raise InvalidParameterError(f"abstraction must be an Abstraction, got {type(abstraction).__name__}")
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
        from .arc_extraction import arc_intersections

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


# --- SVG path data ---------------------------------------------------------------------


def _svg_number(v: float) -> str:
    """A coordinate for SVG: ``SVG_DECIMALS`` decimals, trailing zeros dropped (as the writers)."""
    s = f"{float(v):.{SVG_DECIMALS}f}"
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _continues(a: ArcPiece, b: ArcPiece) -> bool:
    """True when ``b`` goes on along ``a``'s circle in the same sense: one arc command."""
    ca, cb = a.circle, b.circle
    if not (ca == cb or (abs(ca.cx - cb.cx) <= 1e-9 and abs(ca.cy - cb.cy) <= 1e-9 and abs(ca.r - cb.r) <= 1e-9)):
        return False
    if (a.sweep > 0) != (b.sweep > 0):
        return False
    gap = math.remainder(b.t0 - a.t1, TAU)
    return abs(gap) * ca.r <= 1e-6


def _loop_path(loop: Sequence[ArcPiece]) -> str:
    """SVG subpath of one closed loop of pieces (see :attr:`Face.path`)."""
    pieces = list(loop)
    n = len(pieces)
    joins = [_continues(pieces[k - 1], pieces[k]) for k in range(n)]  # joins[k]: piece k continues k-1
    if not all(joins):
        first = next(k for k in range(n) if not joins[k])
        pieces = pieces[first:] + pieces[:first]
        joins = joins[first:] + joins[:first]
    runs: list[list[ArcPiece]] = []
    for k, piece in enumerate(pieces):
        if k == 0 or not joins[k]:
            runs.append([piece])
        else:
            runs[-1].append(piece)
    n_ = _svg_number
    parts = [f"M {n_(pieces[0].start[0])} {n_(pieces[0].start[1])}"]
    for run in runs:
        circle = run[0].circle
        sweep = sum(p.sweep for p in run)
        end = run[-1].end
        halves = 2 if abs(sweep) > _NEAR_FULL_SWEEP else 1
        flag = 1 if sweep > 0 else 0
        large = 1 if abs(sweep) / halves > math.pi else 0
        if circle.k is None and circle.r >= 0.5 * LINE_RADIUS:
            parts.append(f"L {n_(end[0])} {n_(end[1])}")  # a straight line (the lines option)
            continue
        r = n_(circle.r)
        if halves == 2:
            mid = circle.point_at(run[0].t0 + 0.5 * sweep)
            parts.append(f"A {r} {r} 0 {large} {flag} {n_(mid[0])} {n_(mid[1])}")
        parts.append(f"A {r} {r} 0 {large} {flag} {n_(end[0])} {n_(end[1])}")
    parts.append("Z")
    return " ".join(parts)


_TOKEN = re.compile(r"[A-Za-z]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def sample_path(path: str, step: float = ARC_SAMPLE_STEP) -> list[np.ndarray]:
    """The closed loops of SVG path data, sampled: for drawing fills and reading them back.

    Understands the absolute commands a fill path uses: ``M``, ``L``, ``H``,
    ``V``, ``A`` with a circular arc (``rx == ry``; the rotation is then
    irrelevant; a radius too small for its end points is scaled up, as SVG
    renderers do) and ``Z``. Every subpath is a closed loop (a fill closes it
    anyway).

    Parameters
    ----------
    path : str
        SVG path data, e.g. :attr:`Face.path`.
    step : float
        Spacing of the samples along arcs, px.

    Returns
    -------
    list of ndarray, shape (N, 2)
        One polyline per subpath, its first point not repeated at the end.

    Raises
    ------
    InvalidParameterError
        On a command other than those, a relative command, an elliptical arc,
        a missing number or text that is not path data.
    """
    if not isinstance(path, str):
        raise InvalidParameterError(f"path must be SVG path data (a string), got {type(path).__name__}")
    step = check_positive(step, "step")
    stripped = re.sub(r"[\s,]+", " ", path).strip()
    tokens = _TOKEN.findall(stripped)
    if "".join(tokens).replace(" ", "") != stripped.replace(" ", ""):
        raise InvalidParameterError(f"fill path is not SVG path data: {path!r:.80}")
    arity = {"M": 2, "L": 2, "H": 1, "V": 1, "A": 7, "Z": 0}
    rings: list[np.ndarray] = []
    current: list[np.ndarray] = []
    pos = np.zeros(2)
    i = 0
    command = ""

    def close() -> None:
        if current:
            ring = np.concatenate(current)
            if len(ring) > 1 and np.allclose(ring[0], ring[-1], atol=1e-9, rtol=0.0):
                ring = ring[:-1]
            if len(ring) >= 3:
                rings.append(ring)
        current.clear()

    while i < len(tokens):
        tok = tokens[i]
        if tok.isalpha():
            command = tok
            i += 1
            if command not in arity:
                hint = " (relative commands are not supported)" if command.upper() in arity else ""
                raise InvalidParameterError(
                    f"fill path: unsupported command {command!r}{hint}: only absolute M, L, H, V, A (circular) and Z"
                )
            if command == "Z":
                close()
                continue
        elif not command or command == "Z":
            raise InvalidParameterError(f"fill path: number {tok!r} without a command: {path!r:.80}")
        k = arity[command]
        args = tokens[i : i + k]
        if len(args) < k or any(a.isalpha() for a in args):
            raise InvalidParameterError(f"fill path: command {command!r} needs {k} numbers: {path!r:.80}")
        v = [float(a) for a in args]
        i += k
        if command == "M":
            close()
            pos = np.array(v)
            current.append(pos[None, :])
            command = "L"  # implicit repeats of M are line-tos
        elif command in ("L", "H", "V"):
            target = (
                np.array(v)
                if command == "L"
                else (np.array([v[0], pos[1]]) if command == "H" else np.array([pos[0], v[0]]))
            )
            if not current:
                current.append(pos[None, :])
            current.append(target[None, :])
            pos = target
        else:
            rx, ry, _, large, sweep, x, y = v
            if abs(abs(rx) - abs(ry)) > 1e-6 * max(abs(rx), abs(ry), 1.0):
                raise InvalidParameterError(f"fill path: only circular arcs (rx == ry), got rx={rx:g}, ry={ry:g}")
            target = np.array([x, y])
            if not current:
                current.append(pos[None, :])
            current.append(_sample_svg_arc(pos, target, abs(rx), bool(large), bool(sweep), step)[1:])
            pos = target
    close()
    return rings


def _sample_svg_arc(p0: np.ndarray, p1: np.ndarray, r: float, large: bool, sweep: bool, step: float) -> np.ndarray:
    """Points of an SVG circular arc command from ``p0`` to ``p1`` (SVG 1.1 F.6.5), ends included."""
    half = 0.5 * (p1 - p0)
    d = math.hypot(half[0], half[1])
    if d == 0.0 or r == 0.0:
        return np.array([p0, p1])
    r = max(r, d)
    h = math.sqrt(max(r * r - d * d, 0.0))
    sign = 1.0 if large != sweep else -1.0
    # Centre: midpoint plus h along the normal (x1', y1') -> (y1', -x1') of F.6.5.2 (rotation 0).
    x1, y1 = -half[0], -half[1]
    centre = 0.5 * (p0 + p1) + sign * (h / d) * np.array([y1, -x1])
    a0 = math.atan2(p0[1] - centre[1], p0[0] - centre[0])
    a1 = math.atan2(p1[1] - centre[1], p1[0] - centre[0])
    delta = a1 - a0
    if sweep and delta < 0.0:
        delta += TAU
    elif not sweep and delta > 0.0:
        delta -= TAU
    n = max(2, math.ceil(abs(delta) * r / step) + 1)
    t = a0 + delta * np.linspace(0.0, 1.0, n)
    pts = np.stack([centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)], axis=-1)
    pts[0], pts[-1] = p0, p1
    return pts


# --- colours -------------------------------------------------------------------------


def parse_color(value: object, name: str = "colour") -> str:
    """A colour as lower-case ``#rrggbb``.

    Parameters
    ----------
    value : str or sequence of 3 numbers
        ``"#rrggbb"`` (any case), or RGB floats in [0, 1].
    name : str
        What to call it in an error message.

    Raises
    ------
    InvalidParameterError
        ``colour '#12345' is not of the form #rrggbb`` and the like.
    """
    if isinstance(value, str):
        if not _HEX.match(value):
            raise InvalidParameterError(f"{name} {value!r} is not of the form #rrggbb")
        return value.lower()
    try:
        rgb = [float(c) for c in value]  # type: ignore[attr-defined]
    except (TypeError, ValueError) as exc:
        raise InvalidParameterError(f"{name} must be '#rrggbb' or 3 floats in [0, 1], got {value!r}") from exc
    if len(rgb) != 3 or not all(math.isfinite(c) and 0.0 <= c <= 1.0 for c in rgb):
        raise InvalidParameterError(f"{name} must be '#rrggbb' or 3 floats in [0, 1], got {value!r}")
    return _rgb_to_hex(np.array(rgb))


def _rgb_to_hex(rgb: np.ndarray) -> str:
    r, g, b = (round(float(c) * 255.0) for c in np.clip(rgb, 0.0, 1.0))
    return f"#{r:02x}{g:02x}{b:02x}"


def _hex_to_rgb(color: str) -> np.ndarray:
    return np.array([int(color[k : k + 2], 16) for k in (1, 3, 5)], dtype=np.float64) / 255.0


def _faces_of(abstraction: Abstraction, face_list: Sequence[Face] | None) -> tuple[Face, ...]:
    if not isinstance(abstraction, Abstraction):
        raise InvalidParameterError(f"abstraction must be an Abstraction, got {type(abstraction).__name__}")
    if face_list is None:
        return faces(abstraction)
    out = tuple(face_list)
    for i, f in enumerate(out):
        if not isinstance(f, Face):
            raise InvalidParameterError(f"faces[{i}] must be a Face, got {type(f).__name__}")
    return out


def fill_palette(
    abstraction: Abstraction,
    colors: Sequence[Any] | Mapping[int, Any],
    *,
    faces: Sequence[Face] | None = None,
) -> tuple[Fill, ...]:
    """Fill the faces from a user palette (Fig. 18, "simple color palette").

    Parameters
    ----------
    abstraction : Abstraction
    colors : sequence of colours, or mapping face index -> colour
        A mapping fills exactly the faces it names (indices into
        :func:`faces`). A sequence is dealt out in a deterministic order: the
        faces largest first, face number k starting from colour ``k mod n`` and
        taking the first colour, cyclically, that no adjacent face already
        coloured has (adjacent: sharing a piece of arc; when every colour is
        taken the colour ``k mod n`` is used), so neighbours differ whenever the
        palette allows. Colours are ``#rrggbb`` or RGB floats in [0, 1].
    faces : sequence of Face, optional
        The faces, if already computed (:func:`faces` of ``abstraction``).

    Returns
    -------
    tuple of Fill
        In face order.

    Raises
    ------
    InvalidParameterError
        On an empty palette, a bad colour or a face index out of range.
    """
    face_list = _faces_of(abstraction, faces)
    if isinstance(colors, Mapping):
        chosen: dict[int, str] = {}
        for key, value in colors.items():
            if isinstance(key, bool) or not isinstance(key, int | np.integer):
                raise InvalidParameterError(f"palette keys must be face indices (integers), got {key!r}")
            if not 0 <= int(key) < len(face_list):
                raise InvalidParameterError(
                    f"palette face index {int(key)} is out of range (the abstraction has {len(face_list)} faces)"
                )
            chosen[int(key)] = parse_color(value, f"palette colour for face {int(key)}")
        return tuple(Fill(face_list[i].path, chosen[i], face=i) for i in sorted(chosen))
    if isinstance(colors, str) or not isinstance(colors, Sequence):
        raise InvalidParameterError(
            f"colors must be a sequence of colours or a mapping face -> colour, got {type(colors).__name__}"
        )
    palette = [parse_color(c, f"palette colour {i}") for i, c in enumerate(colors)]
    if not palette:
        raise InvalidParameterError("the palette is empty: give at least one colour")
    adjacent = face_adjacency(face_list)
    assigned: dict[int, str] = {}
    n = len(palette)
    for k in range(len(face_list)):
        taken = {assigned[j] for j in adjacent[k] if j in assigned}
        pick = palette[k % n]
        for off in range(n):
            candidate = palette[(k + off) % n]
            if candidate not in taken:
                pick = candidate
                break
        assigned[k] = pick
    return tuple(Fill(face_list[k].path, assigned[k], face=k) for k in range(len(face_list)))


def fill_gradient(
    abstraction: Abstraction,
    colors: Sequence[Any],
    kind: str = "linear",
    angle: float = DEFAULT_GRADIENT_ANGLE,
    *,
    faces: Sequence[Face] | None = None,
) -> tuple[Fill, ...]:
    """Fill every face with one gradient across the whole logo (Fig. 18, "gradients").

    The gradient spans the bounding box of the faces (the logo), so it runs on
    continuously from face to face. Linear: along the direction ``angle`` from
    the box's side where the first colour sits to the opposite side, through
    the box's centre. Radial: from the box's centre (first colour) to its
    corners (last colour). Stops are evenly spaced.

    The ``img2logo.abstraction/1`` document has one ``#rrggbb`` colour per
    region, so each fill's :attr:`Fill.color` (written to the JSON) is the
    gradient's colour at the face's centroid; the SVG and the PNG draw the true
    gradient (:attr:`Fill.gradient`).

    Parameters
    ----------
    abstraction : Abstraction
    colors : sequence of colours
        At least two, ``#rrggbb`` or RGB floats in [0, 1].
    kind : {"linear", "radial"}
    angle : float
        Direction of a linear gradient, radians from +x towards +y (y down): 0
        runs left to right, pi/2 (the default) top to bottom. Ignored for radial.
    faces : sequence of Face, optional
        The faces, if already computed.

    Returns
    -------
    tuple of Fill
        One per face, in face order; empty when there is no face.
    """
    check_choice(kind, "kind", ("linear", "radial"))
    a = float(angle) if isinstance(angle, int | float | np.number) and not isinstance(angle, bool) else math.nan
    if not math.isfinite(a):
        raise InvalidParameterError(f"angle must be a finite number of radians, got {angle!r}")
    if isinstance(colors, str) or not isinstance(colors, Sequence):
        raise InvalidParameterError(f"colors must be a sequence of colours, got {type(colors).__name__}")
    palette = [parse_color(c, f"gradient colour {i}") for i, c in enumerate(colors)]
    if len(palette) < 2:
        raise InvalidParameterError(f"a gradient needs at least two colours, got {len(palette)}")
    face_list = _faces_of(abstraction, faces)
    if not face_list:
        return ()
    bounds = np.array([f.polygon.bounds for f in face_list])
    x0, y0 = bounds[:, 0].min(), bounds[:, 1].min()
    x1, y1 = bounds[:, 2].max(), bounds[:, 3].max()
    centre = np.array([0.5 * (x0 + x1), 0.5 * (y0 + y1)])
    if kind == "linear":
        d = np.array([math.cos(a), math.sin(a)])
        reach = 0.5 * (abs(d[0]) * (x1 - x0) + abs(d[1]) * (y1 - y0))
        start, end = centre - reach * d, centre + reach * d
    else:
        start, end = centre, np.array([x1, y1])
    stops = tuple((i / (len(palette) - 1), c) for i, c in enumerate(palette))
    gradient = Gradient(kind, stops, (float(start[0]), float(start[1])), (float(end[0]), float(end[1])))
    out = []
    for k, face in enumerate(face_list):
        color = _rgb_to_hex(gradient.color_at(np.array(face.centroid)))
        out.append(Fill(face.path, color, gradient=gradient, face=k))
    return tuple(out)


def fill_auto(
    abstraction: Abstraction,
    image: Any,
    *,
    faces: Sequence[Face] | None = None,
    inset: float = AUTO_FILL_INSET,
    background: Any = None,
    background_distance: float = BACKGROUND_DISTANCE,
) -> tuple[Fill, ...]:
    """Colours from the input image: the paper's future work (Sec. 9; Fig. 18 done automatically).

    Each face takes the median, channel by channel in CIELAB, of the input
    pixels whose centres lie inside it shrunk by ``inset`` px (the whole face
    when the inset leaves fewer than ``AUTO_FILL_MIN_PIXELS``): a robust average
    that ignores a minority of other colours (the anti-aliased boundary, a bit
    of the neighbouring region where the arcs, within the tolerance T, leave
    the image's edges). A face is background, and gets no fill, when it reaches
    the image border (within 1 px), or when most of its pixels are transparent
    in an input with an alpha channel: a face enclosed by the object keeps its
    colour even when that is the background's (a penguin's white belly). On
    request (``background``), faces of a given colour are left empty too.

    Parameters
    ----------
    abstraction : Abstraction
    image : ndarray, shape (height, width, 3) or (height, width, 4) or (height, width), or LoadedImage
        The input image the abstraction was made from (uint8, or floats in
        [0, 1]; RGBA is composited on white), of the abstraction's size.
    faces : sequence of Face, optional
        The faces, if already computed.
    inset : float
        Shrink faces by this much before reading pixels, px (>= 0).
    background : None, "auto" or colour
        None (default): only faces that reach the border or the transparent
        background are empty. A colour (``#rrggbb`` or RGB floats), or
        ``"auto"`` for the median colour of the image's outer
        ``BORDER_WIDTH`` px: faces of that colour are left empty too.
    background_distance : float
        Delta E 76 below which a face has the ``background`` colour.

    Returns
    -------
    tuple of Fill
        One per face that is not background, in face order, each with
        :attr:`Fill.face` set.
    """
    from skimage.color import lab2rgb, rgb2lab

    face_list = _faces_of(abstraction, faces)
    width, height = int(abstraction.width), int(abstraction.height)
    inset = check_positive(inset, "inset", allow_zero=True)
    background_distance = check_positive(background_distance, "background_distance", allow_zero=True)
    from .plotting import _background_rgb

    pixels = getattr(image, "rgb", image)
    if pixels is None:
        raise InvalidParameterError("image must be an array of shape (H, W, 3), got None")
    rgb = _background_rgb(np.asarray(pixels), width, height, fade=0.0)
    lab = rgb2lab(rgb)
    alpha = _alpha_of(image, width, height)
    if isinstance(background, str) and background == "auto":
        b = BORDER_WIDTH
        frame = np.ones((height, width), dtype=bool)
        frame[b:-b, b:-b] = False
        back_lab: np.ndarray | None = np.median(lab[frame], axis=0)
    elif background is None:
        back_lab = None
    else:
        back_lab = rgb2lab(_hex_to_rgb(parse_color(background, "background"))[None, None, :])[0, 0]
    if not face_list:
        return ()

    out = []
    for k, face in enumerate(face_list):
        x0, y0, x1, y1 = face.polygon.bounds
        if x0 < 1.0 or y0 < 1.0 or x1 > width - 1.0 or y1 > height - 1.0:
            continue  # reaches the border: background
        samples = _pixels_inside(face.polygon, inset, width, height)
        if len(samples[0]) < AUTO_FILL_MIN_PIXELS:
            samples = _pixels_inside(face.polygon, 0.0, width, height)
        if len(samples[0]) == 0:
            continue  # thinner than a pixel: nothing to read
        if alpha is not None and float(np.median(alpha[samples])) < 0.5:
            continue  # the transparent background
        colour_lab = np.median(lab[samples], axis=0)
        if back_lab is not None and float(np.linalg.norm(colour_lab - back_lab)) < background_distance:
            continue
        colour = lab2rgb(colour_lab[None, None, :])[0, 0]
        out.append(Fill(face.path, _rgb_to_hex(colour), face=k))
    return tuple(out)


def _alpha_of(image: Any, width: int, height: int) -> np.ndarray | None:
    """Opacity (H, W) in [0, 1] of an input with an alpha channel, else None."""
    if getattr(image, "has_alpha", False):
        return np.asarray(image.alpha)
    arr = np.asarray(getattr(image, "rgb", image))
    if arr.ndim == 3 and arr.shape[2] == 4 and arr.shape[:2] == (height, width):
        a = arr[:, :, 3]
        return a / 255.0 if arr.dtype == np.uint8 else a.astype(np.float64)
    return None


def _pixels_inside(polygon: Polygon, inset: float, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """(rows, cols) of the pixels whose centres lie inside ``polygon`` shrunk by ``inset`` px."""
    import shapely

    shape = polygon if polygon.is_valid else shapely.make_valid(polygon)
    if inset > 0.0:
        shape = shape.buffer(-inset)
    if shape.is_empty:
        return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp)
    x0, y0, x1, y1 = shape.bounds
    c0, c1 = max(0, math.floor(x0)), min(width, math.ceil(x1) + 1)
    r0, r1 = max(0, math.floor(y0)), min(height, math.ceil(y1) + 1)
    if c0 >= c1 or r0 >= r1:
        return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp)
    rows, cols = np.mgrid[r0:r1, c0:c1]
    shapely.prepare(shape)
    inside = shapely.contains_xy(shape, cols.ravel() + 0.5, rows.ravel() + 0.5)
    return rows.ravel()[inside], cols.ravel()[inside]


# --- the command line option -----------------------------------------------------------


def parse_fill_option(spec: object) -> FillSpec:
    """Parse the command line's ``--fill`` option.

    Forms: ``none``; ``auto`` (colours from the input image, :func:`fill_auto`);
    ``palette:#rrggbb,#rrggbb,...`` (:func:`fill_palette`, one or more
    colours); ``linear:#rrggbb,#rrggbb,...`` or ``linear@DEG:...`` with the
    direction in degrees from +x towards +y (default 90, top to bottom), and
    ``radial:#rrggbb,#rrggbb,...`` (:func:`fill_gradient`, two or more
    colours). The mode is case-insensitive; spaces around items are ignored.

    Returns
    -------
    FillSpec
        Call ``spec.make(abstraction, image)`` for the fills.

    Raises
    ------
    InvalidParameterError
        With the form expected, e.g. ``fill option 'palette:': the palette is
        empty: give at least one #rrggbb colour after 'palette:'`` or ``fill
        option 'palette:#12345': colour 1 '#12345' is not of the form #rrggbb``.
    """
    if not isinstance(spec, str):
        raise InvalidParameterError(f"fill option must be a string, got {type(spec).__name__}")
    text = spec.strip()
    head, sep, rest = text.partition(":")
    mode, at, degrees = head.strip().lower().partition("@")
    if mode not in _FILL_MODES or (mode in ("none", "auto") and (sep or at)) or (at and mode != "linear"):
        raise InvalidParameterError(f"fill option must be {_FILL_SYNTAX}, got {spec!r}")
    if mode in ("none", "auto"):
        return FillSpec(mode)
    if not sep:
        raise InvalidParameterError(
            f"fill option {spec!r}: give the colours after '{mode}:', e.g. {mode}:#1f77b4,#ff7f0e"
        )
    angle = DEFAULT_GRADIENT_ANGLE
    if at:
        try:
            angle = math.radians(float(degrees))
        except ValueError:
            angle = math.nan
        if not math.isfinite(angle):
            raise InvalidParameterError(
                f"fill option {spec!r}: the angle after '@' must be a number of degrees, got {degrees!r}"
            )
    items = [c.strip() for c in rest.split(",")]
    if items == [""]:
        items = []
    if not items and mode == "palette":
        raise InvalidParameterError(
            f"fill option {spec!r}: the palette is empty: give at least one #rrggbb colour after 'palette:'"
        )
    colors = []
    for i, c in enumerate(items, start=1):
        if not _HEX.match(c):
            raise InvalidParameterError(f"fill option {spec!r}: colour {i} {c!r} is not of the form #rrggbb")
        colors.append(c.lower())
    if mode != "palette" and len(colors) < 2:
        raise InvalidParameterError(
            f"fill option {spec!r}: a {mode} gradient needs at least two #rrggbb colours, got {len(colors)}"
        )
    return FillSpec(mode, tuple(colors), angle)
