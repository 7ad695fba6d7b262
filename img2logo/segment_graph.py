"""The line-segment graph L = {S, J} (paper Sec. 4, 5.1) built from feature lines.

A 1-px-wide feature-line map becomes a graph whose nodes are end points
(valence 1), junctions (valence >= 3; touching junction pixels are one node) and
the split points of the Ramer-Douglas-Peucker over-segmentation (valence 2), and
whose edges are the ordered pixel chains between them: the segments.

Coordinates follow ``contract/README.md``: x to the right, y downwards, pixel
(row i, column j) has its centre at (j + 0.5, i + 0.5).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ._validation import check_positive, readonly
from .constants import JUNCTION_MERGE_DISTANCE, MAX_RADIUS_FACTOR, MIN_SEGMENT_LENGTH, RDP_TOLERANCE, SMOOTH_JOIN_ANGLE
from .errors import FitError, InvalidParameterError
from .geometry.circle_fitting import fit_circle
from .geometry.primitives import cumulative_length, polyline_length
from .images import skeleton as _skeleton
from .images.ndimage import skeletonize

#: A segment's end tangent is that of the circle fitted to its pixels within this arc length of the node, px.
SMOOTH_TANGENT_LENGTH: float = 30.0


@dataclass(frozen=True, eq=False)
class SegmentGraph:
    """The line-segment graph L = {S, J}.

    Attributes
    ----------
    segments : tuple of ndarray, each of shape (n_i, 2)
        Ordered pixel centres (x, y) of each segment, px, n_i >= 2. The first
        point is exactly ``junctions[ends[i, 0]]`` and the last exactly
        ``junctions[ends[i, 1]]``, so segments meet where they share a node.
    junctions : ndarray, shape (J, 2)
        The nodes p_k: end points, junctions and RDP split points, px.
    ends : ndarray of int, shape (S, 2)
        ``ends[i] = (k0, k1)``: the nodes at the start and end of segment i.
        ``k0 != k1`` always: closed loops are split.
    width, height : int
        Size of the image the graph was built from, px.

    Examples
    --------
    >>> from img2logo import build_segment_graph, data, extract_feature_lines
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> graph = build_segment_graph(extract_feature_lines(image))
    >>> graph.width, graph.height, graph.segments[0].shape[1]
    (160, 160, 2)
    """

    segments: tuple[np.ndarray, ...]
    junctions: np.ndarray
    ends: np.ndarray
    width: int
    height: int

    def __post_init__(self) -> None:
        segs = tuple(readonly(np.array(s, dtype=np.float64).reshape(-1, 2)) for s in self.segments)
        junctions = readonly(np.array(self.junctions, dtype=np.float64).reshape(-1, 2))
        ends = readonly(np.array(self.ends, dtype=np.int64).reshape(-1, 2))
        if len(ends) != len(segs):
            raise InvalidParameterError(f"ends must have one row per segment ({len(segs)}), got {len(ends)}")
        if len(ends) and (ends.min() < 0 or ends.max() >= len(junctions)):
            raise InvalidParameterError(f"ends must index junctions 0..{len(junctions) - 1}")
        for i, s in enumerate(segs):
            if len(s) < 2:
                raise InvalidParameterError(f"segment {i} must have at least 2 points, got {len(s)}")
        object.__setattr__(self, "segments", segs)
        object.__setattr__(self, "junctions", junctions)
        object.__setattr__(self, "ends", ends)

    @property
    def n_segments(self) -> int:
        """|S|, the number of segments."""
        return len(self.segments)

    @property
    def n_junctions(self) -> int:
        """|J|, the number of nodes (end points, junctions and split points)."""
        return len(self.junctions)

    @cached_property
    def valence(self) -> np.ndarray:
        """Number of segment ends at each node, shape (J,)."""
        return readonly(np.bincount(self.ends.ravel(), minlength=self.n_junctions))

    @cached_property
    def lengths(self) -> np.ndarray:
        """Polyline length of each segment, shape (S,), px."""
        return readonly(np.array([polyline_length(s) for s in self.segments]))

    @cached_property
    def turns(self) -> np.ndarray:
        """How much the feature line turns at each node of valence 2, shape (J,), rad in [0, pi].

        The angle between the two segments' end tangents there (:func:`end_tangent`;
        0 where the line runs straight on, pi where it folds back); NaN at end
        points, junctions of valence >= 3, and a node where one segment ends twice.
        """
        from ._compiled import kernels

        out = np.full(self.n_junctions, np.nan)
        at: dict[int, list[tuple[int, int]]] = {}
        for i, (a, b) in enumerate(self.ends.tolist()):
            at.setdefault(a, []).append((i, 0))
            at.setdefault(b, []).append((i, 1))
        pairs = [(k, ends) for k, ends in at.items() if len(ends) == 2 and ends[0][0] != ends[1][0]]
        if pairs:
            # Every end's tangent in one compiled call (the same steps as end_tangent's).
            sizes = np.array([len(s) for s in self.segments], dtype=np.int64)
            stops = np.cumsum(sizes)
            which = np.array([i for _, ends in pairs for i, _ in ends], dtype=np.int64)
            first = np.array([e == 0 for _, ends in pairs for _, e in ends], dtype=bool)
            points = np.concatenate(self.segments).astype(np.float64, copy=False)
            tangents = kernels.end_tangents_kernel(
                points, stops[which] - sizes[which], stops[which], first, SMOOTH_TANGENT_LENGTH, MAX_RADIUS_FACTOR
            )
            for m, (k, _) in enumerate(pairs):
                out[k] = float(np.arccos(np.clip(-np.dot(tangents[2 * m], tangents[2 * m + 1]), -1.0, 1.0)))
        return readonly(out)

    def smooth_nodes(self, max_turn: float = SMOOTH_JOIN_ANGLE) -> frozenset[int]:
        """The nodes of valence 2 where the feature line turns by less than ``max_turn`` rad (:attr:`turns`).

        Where two arcs end at such a node the logo should not kink: the tangent
        joins of the constrained fit (:mod:`img2logo.fit.constrained_fit`) and of
        ``make quality`` (:func:`img2logo.quality.joins`).
        """
        turns = self.turns
        return frozenset(int(k) for k in np.flatnonzero(turns < max_turn))

    def segments_at(self, k: int) -> tuple[int, ...]:
        """Indices of the segments with an end at node ``k`` (the paper's Omega(p_k))."""
        return tuple(int(i) for i in np.flatnonzero((self.ends == k).any(axis=1)))

    def n_components(self) -> int:
        """Number of connected components of the graph (a junction on no segment is one).

        A union-find over the segments' ends: the count of
        ``scipy.sparse.csgraph.connected_components`` (the tests compare them)
        without importing ``scipy.sparse`` for it.
        """
        root = list(range(self.n_junctions))

        def find(k: int) -> int:
            while root[k] != k:
                root[k] = root[root[k]]
                k = root[k]
            return k

        count = self.n_junctions
        for a, b in self.ends.tolist():
            ra, rb = find(a), find(b)
            if ra != rb:
                root[ra] = rb
                count -= 1
        return count


def build_segment_graph(
    lines: object,
    *,
    rdp_tolerance: float = RDP_TOLERANCE,
    min_length: float = MIN_SEGMENT_LENGTH,
) -> SegmentGraph:
    """Build the segment graph L = {S, J} from a feature-line map (paper Sec. 4).

    Parameters
    ----------
    lines : FeatureLines or ndarray of bool, shape (H, W)
        Feature lines, as returned by :func:`img2logo.extract_feature_lines`, or
        any binary map of lines (it is thinned to 1 px first).
    rdp_tolerance : float, optional
        Tolerance of the Ramer-Douglas-Peucker over-segmentation, px (> 0). Each
        chain between two nodes is split at the vertices RDP keeps, and those
        split points become nodes of valence 2. Larger values give fewer, longer
        segments (paper Fig. 13).
    min_length : float, optional
        Side spurs (a chain from a free end to a junction) and isolated chains
        shorter than this are dropped, px (>= 0).

    Returns
    -------
    SegmentGraph
        Nodes are end points (valence 1), junctions (valence >= 3, touching
        junction pixels merged into one node at their centroid) and RDP split
        points (valence 2). A closed loop with no junction is split at its
        first pixel and at the middle of its length, so every segment has two
        distinct end nodes.

    Raises
    ------
    InvalidParameterError
        If ``lines`` is not a 2-D map or a parameter is out of range.

    Examples
    --------
    >>> from img2logo import build_segment_graph, data, extract_feature_lines
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> graph = build_segment_graph(extract_feature_lines(image))
    >>> graph.n_components(), graph.width, graph.height
    (1, 160, 160)
    """
    rdp_tolerance = check_positive(rdp_tolerance, "rdp_tolerance")
    min_length = check_positive(min_length, "min_length", allow_zero=True)
    line_map = getattr(lines, "lines", lines)
    arr = np.asarray(line_map)
    if arr.ndim != 2:
        raise InvalidParameterError(f"lines must be a 2-D map of shape (H, W), got shape {arr.shape}")
    skel = skeletonize(arr.astype(bool))
    graph = _skeleton.trace(skel)
    _skeleton.prune(graph, spur_length=min_length, min_length=min_length, junction_merge=JUNCTION_MERGE_DISTANCE)

    junctions = list(graph.nodes)
    segments: list[np.ndarray] = []
    ends: list[tuple[int, int]] = []
    for c, (a, b) in enumerate(graph.ends):
        poly = graph.polyline(c)
        pieces = [(a, b, poly)]
        if a == b:
            # A loop on one node: split it half-way along its length.
            mid = _index_at_half_length(poly)
            junctions.append(poly[mid])
            m = len(junctions) - 1
            pieces = [(a, m, poly[: mid + 1]), (m, b, poly[mid:])]
        for start, stop, piece in pieces:
            cuts = _rdp_split_indices(piece, rdp_tolerance)
            nodes = [start]
            for i in cuts:
                junctions.append(piece[i])
                nodes.append(len(junctions) - 1)
            nodes.append(stop)
            bounds = [0, *cuts, len(piece) - 1]
            for k in range(len(bounds) - 1):
                segments.append(piece[bounds[k] : bounds[k + 1] + 1])
                ends.append((nodes[k], nodes[k + 1]))
    h, w = arr.shape
    return SegmentGraph(
        segments=tuple(segments),
        junctions=np.array(junctions).reshape(-1, 2),
        ends=np.array(ends, dtype=np.int64).reshape(-1, 2),
        width=w,
        height=h,
    )


def end_tangent(points: np.ndarray, at_start: bool, length: float = SMOOTH_TANGENT_LENGTH) -> np.ndarray:
    """The unit tangent of a segment at one of its ends, pointing into the segment: shape (2,).

    The tangent at the end point of the circle fitted (algebraically,
    :func:`img2logo.geometry.circle_fitting.fit_circle`) to the segment's pixels within
    ``length`` px of arc length of that end: a circle follows the line's
    curvature, and over that length the 0.5 px steps of a raster line tilt it
    little (see ``SMOOTH_TANGENT_LENGTH``). A straight one (its circle capped)
    and one of fewer than 3 distinct points give their chord.

    Parameters
    ----------
    points : ndarray, shape (n, 2)
        The segment's ordered pixels, px; n >= 2.
    at_start : bool
        The end: ``points[0]`` (True) or ``points[-1]``.
    length : float
        Arc length of the pixels used, px.
    """
    pts = np.asarray(points, dtype=np.float64)
    pts = pts if at_start else pts[::-1]
    cum = cumulative_length(pts)
    near = pts[: max(int(np.searchsorted(cum, length, side="right")), 2)]
    chord = near[-1] - near[0]
    try:
        fit = fit_circle(near, refine=False)
    except FitError:
        fit = None
    if fit is None or fit.capped:  # (nearly) straight: the chord, not the capped circle's bow
        return chord / max(float(np.hypot(*chord)), 1e-300)
    radial = near[0] - fit.center
    t = np.array([-radial[1], radial[0]])
    if np.dot(t, chord) < 0:
        t = -t
    return t / max(float(np.hypot(*t)), 1e-300)


def _index_at_half_length(poly: np.ndarray) -> int:
    cum = cumulative_length(poly)
    mid = int(np.searchsorted(cum, cum[-1] / 2.0))
    return min(max(mid, 1), len(poly) - 2)


def _rdp_split_indices(poly: np.ndarray, tolerance: float) -> list[int]:
    """Indices of the interior vertices that Ramer-Douglas-Peucker keeps."""
    import cv2

    if len(poly) < 3:
        return []
    # OpenCV's approxPolyDP is RDP; it returns a subset of the input points in
    # order, so their indices are found by a forward scan (a chain may cross
    # itself, so no lookup table).
    pts = poly.astype(np.float32)
    kept = cv2.approxPolyDP(pts.reshape(-1, 1, 2), tolerance, False).reshape(-1, 2)
    # Compared as Python floats (the float32 values exactly): np.array_equal per pixel
    # was most of the segment graph's time.
    chain = pts.tolist()
    out, i = [], 0
    for q in kept[1:-1].tolist():
        while chain[i] != q:
            i += 1
        out.append(i)
    return [k for k in out if 0 < k < len(poly) - 1]
