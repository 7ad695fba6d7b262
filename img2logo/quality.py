"""How well a logo keeps an image's features: measures against a ground truth.

The measures of ``make quality`` (``benchmarks/quality.py``), also usable on any
level of any run:

* **recall** r_d: the fraction of ground-truth feature pixels within d px of the
  logo (its arcs and lines, sampled every ``QUALITY_SAMPLE_STEP`` px);
* **silhouette recall** sil6: the fraction of an object mask's outline pixels
  within 6 px of the logo as drawn (the edge of its stroke, when a stroke width is
  given: a line drawing's logo is drawn at the input's weight);
* **outside**: the fraction of the logo's sample points farther than 12 px from
  the object mask (a logo of the background);
* **crossings**: points where two arcs meet farther than
  ``CROSSING_END_DISTANCE`` from every end point of both (a redundant
  intersection, Sec. 5.2, Fig. 12, judged on the drawing alone);
* **near-miss gaps**: open arc ends that stop short of another arc, between
  ``GAP_MIN`` and ``GAP_MAX`` px from it (a junction the eye sees but the logo
  does not close, Fig. 6);
* **joins on smooth input** (:func:`joins`, beyond the paper): at every junction
  where exactly two arcs end and the input's feature line runs on smoothly
  (:meth:`~img2logo.segment_graph.SegmentGraph.smooth_nodes`), the kink between
  the two arcs' tangents; a join is tangent below ``TANGENT_JOIN_ANGLE``.
* **ink parts lost** (:func:`lost_ink_parts`): dark parts of the input (an eye, a
  dot, a stroke) of at least ``INK_PART_MIN_AREA`` px with no logo point within
  ``INK_PART_DISTANCE`` px: what a ground truth of 1-px skeletons hides from r10;
* **stroke width ratio** (:func:`stroke_width_ratio`): the logo's stroke width
  over the input's median stroke width.

And the measures of one level against what its optimization promised
(the notebooks' ablations): :func:`junction_gaps` (how far the arcs that should
meet at a junction are from meeting, Eqn. 4, Fig. 8, 11) and
:func:`level_redundant_intersections` (Sec. 5.2, Fig. 12).

Pixel (row i, column j) is the point (j + 0.5, i + 0.5), px, x to the right, y
downwards, as everywhere in img2logo.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ._validation import check_instance, check_positive
from .constants import GAP_MAX, GAP_MIN, SMOOTH_JOIN_ANGLE, TANGENT_JOIN_ANGLE
from .errors import InvalidParameterError
from .fit.arc_extraction import nearest_on_arc
from .fit.intersections import RedundantIntersection, arc_intersections, arc_pairs_near, redundant_intersections
from .geometry.abstraction import Abstraction
from .geometry.primitives import Arc
from .segment_graph import SegmentGraph

#: Spacing of the points sampled along a logo's arcs to measure it, px: well under the 3 px of the finest recall
#: measure.
QUALITY_SAMPLE_STEP: float = 0.5
#: Ink parts lost (``quality.lost_ink_parts``): a pixel of the input darker than this gray (0..1, mid-grey) is ink:
#: the black or coloured strokes, outlines and dots of a drawing or a clip art, not its light fills nor the paper.
INK_PART_GRAY: float = 0.5
#: ... an 8-connected part of ink of at least this many px is content (an eye of a 6 px dot has 28 px); smaller
#: ones are specks of anti-aliasing or JPEG ringing ...
INK_PART_MIN_AREA: int = 30
#: ... and it is lost when no logo point is within this of any of its pixels, px: the finest recall distance (r3).
INK_PART_DISTANCE: float = 3.0
#: sil6: an object outline pixel within this of the logo is kept, px.
SILHOUETTE_DISTANCE: float = 6.0
#: A logo point farther than this from the object mask is on the background, px: twice the silhouette distance, so
#: a slightly loose outline does not count.
OUTSIDE_DISTANCE: float = 12.0
#: Two arcs meeting farther than this from all their end points cross, px: arcs that meet at a junction end there
#: (to 1e-3 px); 1.5 px leaves room for the two nearby crossings of circles that touch at a shared junction.
CROSSING_END_DISTANCE: float = 1.5

#: Distances of the recall measures r3, r6, r10, px.
RECALL_DISTANCES: tuple[float, ...] = (3.0, 6.0, 10.0)


@dataclass(frozen=True)
class Quality:
    """The quality measures of one logo.

    Attributes
    ----------
    arcs : int
        Number of arcs and lines.
    recall : tuple of float
        r_d for d in ``RECALL_DISTANCES`` (r3, r6, r10), or NaN without a truth.
    silhouette : float
        sil6, or NaN without a mask.
    outside : float
        Fraction of the logo farther than 12 px from the mask, or NaN without one.
    crossings : int
        Arcs crossing away from their ends.
    gaps : int
        Near-miss gaps: open ends 0.75-6 px from another arc.
    free_ends : int
        Open ends: ends of arcs (not whole circles) that no other arc comes within 0.75 px of. Every
        colour region of a clip art has a closed outline, so there an open end is a broken outline.
    """

    arcs: int
    recall: tuple[float, ...]
    silhouette: float
    outside: float
    crossings: int
    gaps: int
    free_ends: int = 0


@dataclass(frozen=True, eq=False)
class Joins:
    """The joins of a logo on smooth input (:func:`joins`).

    Attributes
    ----------
    junctions : ndarray of int, shape (N,)
        The abstraction's junctions where exactly two arcs end (none passing
        through) at a node where the input's line turns by less than the
        smoothness threshold.
    kinks : ndarray, shape (N,)
        The angle between the two arcs' tangents there, rad in [0, pi]: 0 where
        one arc flows into the other.
    """

    junctions: np.ndarray
    kinks: np.ndarray

    @property
    def count(self) -> int:
        """Number of joins on smooth input."""
        return len(self.kinks)

    def tangent_fraction(self, angle: float = TANGENT_JOIN_ANGLE) -> float:
        """Fraction of the joins whose kink is below ``angle`` rad; NaN without joins."""
        return float(np.mean(self.kinks < angle)) if len(self.kinks) else np.nan

    @property
    def median_kink(self) -> float:
        """Median kink, rad; NaN without joins."""
        return float(np.median(self.kinks)) if len(self.kinks) else np.nan


def arc_direction(arc: Arc, at_start: bool) -> np.ndarray:
    """The unit direction in which ``arc`` leaves its start (or its end) point, into the arc: shape (2,)."""
    t = arc.theta0 if at_start else arc.theta0 + arc.sweep
    sense = math.copysign(1.0, arc.sweep) * (1.0 if at_start else -1.0)
    return sense * np.array([-math.sin(t), math.cos(t)])


def joins(abstraction: Abstraction, graph: SegmentGraph, max_turn: float = SMOOTH_JOIN_ANGLE) -> Joins:
    """The joins of ``abstraction`` on smooth input and their kinks.

    A join is a junction of the level where exactly two arcs end and none
    passes through, at a node of ``graph`` (the segment graph the level was
    made from, through ``abstraction.junction_nodes``) where the feature line
    turns by less than ``max_turn`` rad (:meth:`SegmentGraph.smooth_nodes`).
    Its kink is the angle between the two arcs' tangents at the junction:
    ``arccos(-u . v)`` with u, v the directions in which they leave it.

    Returns
    -------
    Joins
    """
    check_instance(abstraction, Abstraction, "abstraction")
    if not isinstance(graph, SegmentGraph):
        raise InvalidParameterError(f"graph must be a SegmentGraph, got {type(graph).__name__}")
    smooth = graph.smooth_nodes(max_turn)
    found, kinks = [], []
    for j, node in enumerate(abstraction.junction_nodes):
        if node is None or node not in smooth:
            continue
        ending = abstraction.arcs_at(j)
        if len(ending) != 2 or set(abstraction.junction_arcs[j]) != set(ending):
            continue
        leave = []
        for i in ending:
            t = abstraction.arc_junctions[i]
            if t.start == t.end:
                break  # a closed arc: no join of two arcs
            leave.append(arc_direction(abstraction.arcs[i], t.start == j))
        if len(leave) != 2:
            continue
        found.append(j)
        kinks.append(float(np.arccos(np.clip(-np.dot(leave[0], leave[1]), -1.0, 1.0))))
    return Joins(np.array(found, dtype=np.int64), np.array(kinks, dtype=np.float64))


def logo_points(arcs: Abstraction | Sequence[Arc], step: float = QUALITY_SAMPLE_STEP) -> np.ndarray:
    """Points along every arc and line of a logo about ``step`` px apart: (N, 2), px."""
    arcs = _arcs(arcs)
    if not arcs:
        return np.zeros((0, 2))
    return np.vstack([a.sample(step) for a in arcs])


def feature_recall(
    points: np.ndarray, truth: np.ndarray, distances: Sequence[float] = RECALL_DISTANCES
) -> tuple[float, ...]:
    """Fraction of the ``truth`` pixels within each distance of ``points``.

    Parameters
    ----------
    points : ndarray, shape (N, 2)
        The logo's sample points (x, y), px.
    truth : ndarray of bool, shape (H, W)
        Ground-truth feature pixels.
    distances : sequence of float
        The distances d, px.

    Returns
    -------
    tuple of float
        One fraction in [0, 1] per distance; 1.0 for an empty truth.
    """
    _, _, d = _truth_distances(points, truth)
    if len(d) == 0:
        return tuple(1.0 for _ in distances)
    return tuple(float(np.mean(d <= limit)) for limit in distances)


def silhouette_recall(
    points: np.ndarray, mask: np.ndarray, distance: float = SILHOUETTE_DISTANCE, stroke_width: float = 0.0
) -> float:
    """sil6: the fraction of the outline pixels of ``mask`` (H, W) within ``distance`` px of the logo as drawn.

    ``points`` (N, 2) px sample the logo's arcs; drawn with a stroke ``stroke_width`` px wide
    (default 0: the arcs alone), the logo covers half of it on each side: an outline pixel counts
    within ``distance`` of that stroke's edge. A line drawing's logo is drawn at the input's own
    stroke weight (:func:`img2logo.abstract` records it): the centre line of an outline stroke w px
    wide lies w / 2 px inside the object's silhouette, which the stroke covers.
    """
    from skimage.segmentation import find_boundaries

    mask = _check_map(mask, "mask")
    stroke_width = check_positive(stroke_width, "stroke_width", allow_zero=True)
    outline = find_boundaries(mask, mode="inner")
    return feature_recall(points, outline, (distance + stroke_width / 2.0,))[0]


def outside_fraction(points: np.ndarray, mask: np.ndarray, distance: float = OUTSIDE_DISTANCE) -> float:
    """Fraction of ``points`` (N, 2) farther than ``distance`` px from the object ``mask`` (H, W)."""
    from scipy import ndimage

    mask = _check_map(mask, "mask")
    if len(points) == 0:
        return 0.0
    if not mask.any():
        return 1.0
    far = ndimage.distance_transform_edt(~mask)
    h, w = mask.shape
    j = np.clip(np.floor(points[:, 0]).astype(int), 0, w - 1)
    i = np.clip(np.floor(points[:, 1]).astype(int), 0, h - 1)
    return float(np.mean(far[i, j] > distance))


def crossings(arcs: Abstraction | Sequence[Arc], end_distance: float = CROSSING_END_DISTANCE) -> np.ndarray:
    """Points where two arcs meet farther than ``end_distance`` px from all four of their end points.

    Returns
    -------
    ndarray, shape (K, 2)
        The crossing points, px.
    """
    arcs = _arcs(arcs)
    if len(arcs) < 2:
        return np.zeros((0, 2))
    found = []
    for i, j in arc_pairs_near(arcs, np.arange(len(arcs)), 1e-6):
        a, b = arcs[i], arcs[j]
        ends = np.array([a.start, a.end, b.start, b.end])
        for p in arc_intersections(a, b):
            if np.min(np.hypot(*(ends - p).T)) > end_distance:
                found.append(p)
    return np.array(found).reshape(-1, 2)


def near_miss_gaps(arcs: Abstraction | Sequence[Arc], low: float = GAP_MIN, high: float = GAP_MAX) -> np.ndarray:
    """Open arc ends that stop ``low`` to ``high`` px short of another arc.

    An end is open when no other arc passes within ``low`` px of it (at a
    junction, arcs meet to 1e-3 px). An open end farther than ``high`` from
    every other arc is a free end (a whisker's tip), not a gap.

    Returns
    -------
    ndarray, shape (K, 2)
        The ends, px.
    """
    ends, nearest = _end_distances(_arcs(arcs))
    return ends[(nearest >= low) & (nearest <= high)]


def free_ends(arcs: Abstraction | Sequence[Arc], low: float = GAP_MIN) -> np.ndarray:
    """Open arc ends: ends of arcs (not whole circles) that no other arc passes within ``low`` px of.

    Both a near-miss gap and a dangling end (a broken outline, a whisker's tip) are open. An end on
    another arc (a T-junction) or at another arc's end is not.

    Returns
    -------
    ndarray, shape (K, 2)
        The ends, px.

    Examples
    --------
    >>> from img2logo.geometry.primitives import Arc, Circle
    >>> top = Arc(Circle(0.0, 0.0, 10.0), 0.0, 3.141592653589793)
    >>> bottom = Arc(Circle(0.0, 0.0, 10.0), 3.141592653589793, 3.141592653589793)
    >>> len(free_ends([top])), len(free_ends([top, bottom]))
    (2, 0)
    """
    ends, nearest = _end_distances(_arcs(arcs))
    return ends[nearest >= low]


def _end_distances(arcs: list[Arc]) -> tuple[np.ndarray, np.ndarray]:
    """The end points of the arcs that are not whole circles, (K, 2) px, and each one's distance to the
    nearest other arc, (K,) px (inf where there is no other arc)."""
    ends, nearest = [], []
    for i, arc in enumerate(arcs):
        if arc.is_full_circle:
            continue
        pair = np.array([arc.start, arc.end])
        near = np.full(2, np.inf)
        for j, other in enumerate(arcs):
            if j != i:
                near = np.minimum(near, nearest_on_arc(other, pair)[0])
        ends.append(pair)
        nearest.append(near)
    if not ends:
        return np.zeros((0, 2)), np.zeros(0)
    return np.vstack(ends), np.concatenate(nearest)


def junction_gaps(
    arcs: Sequence[Arc], points: np.ndarray, arcs_at: Sequence[Sequence[int]]
) -> tuple[np.ndarray, np.ndarray]:
    """How far the arcs that should meet at each junction are from meeting (Eqn. 4, Fig. 8, 11), px.

    For junction m with point c_m and arcs ``arcs_at[m]``, q_i is the point of
    arc i nearest to c_m (the radial projection, or the nearer end of the arc).

    Parameters
    ----------
    arcs : sequence of Arc
    points : array_like, shape (M, 2)
        The junction points c_m, px.
    arcs_at : sequence of M sequences of int
        The arcs that should pass through each junction.

    Returns
    -------
    gap : ndarray, shape (M,)
        max_i |q_i - c_m|: the farthest that an arc which should pass through
        c_m stays from it (0 under the connectivity constraint).
    spread : ndarray, shape (M,)
        max_{i,j} |q_i - q_j|: how far apart the arcs' closest approaches are
        (0 at a junction with fewer than two arcs).
    """
    points = np.asarray(points, dtype=np.float64).reshape(-1, 2)
    if len(points) != len(arcs_at):
        raise InvalidParameterError(f"{len(points)} junction points but {len(arcs_at)} lists of arcs")
    gap, spread = np.zeros(len(points)), np.zeros(len(points))
    for m, (c, listed) in enumerate(zip(points, arcs_at, strict=True)):
        if not listed:
            continue
        near = [nearest_on_arc(arcs[i], c) for i in listed]
        q = np.array([p for _, p in near])
        diff = q[:, None, :] - q[None, :, :]
        gap[m] = max(float(d) for d, _ in near)
        spread[m] = float(np.max(np.hypot(diff[..., 0], diff[..., 1])))
    return gap, spread


def level_redundant_intersections(abstraction: Abstraction) -> list[RedundantIntersection]:
    """The redundant intersections of a level (Sec. 5.2, Fig. 6c, 12).

    :func:`~img2logo.fit.intersections.redundant_intersections` over all pairs of
    its arcs, each arc owning the junctions it starts at, passes through and ends at.
    """
    owned = [list(t.ordered) for t in abstraction.arc_junctions]
    return redundant_intersections(abstraction.arcs, abstraction.junctions, owned)


def detail_error(abstraction: Abstraction, graph: SegmentGraph, mask: np.ndarray) -> float:
    """How well ``abstraction`` keeps the detail under ``mask`` (H, W) bool, px (Sec. 7, Fig. 16).

    The mean distance from the segment graph's pixels inside ``mask`` to the
    nearest point of the arcs (sampled every 0.5 px); NaN when no pixel is
    inside or there is no arc. A detail is *lost* when this grows beyond a
    pixel or two: its strokes are no longer traced.
    """
    mask = _check_map(mask, "mask")
    pts = np.vstack(list(graph.segments))
    rows = np.clip((pts[:, 1] - 0.5).round().astype(int), 0, mask.shape[0] - 1)
    cols = np.clip((pts[:, 0] - 0.5).round().astype(int), 0, mask.shape[1] - 1)
    inside = pts[mask[rows, cols]]
    if not len(inside) or not abstraction.arcs:
        return np.nan
    return float(_nearest_distance(logo_points(abstraction, 0.5), inside).mean())


def measure(
    arcs: Abstraction | Sequence[Arc],
    truth: np.ndarray | None = None,
    mask: np.ndarray | None = None,
    *,
    stroke_width: float = 0.0,
) -> Quality:
    """Every measure of a logo against a feature truth and an object mask (both optional).

    ``stroke_width``: the width the logo is drawn with, px, for sil6 (:func:`silhouette_recall`).
    """
    arcs = _arcs(arcs)
    points = logo_points(arcs)
    recall = feature_recall(points, truth) if truth is not None else tuple(np.nan for _ in RECALL_DISTANCES)
    sil = silhouette_recall(points, mask, stroke_width=stroke_width) if mask is not None else np.nan
    out = outside_fraction(points, mask) if mask is not None else np.nan
    _, nearest = _end_distances(arcs)
    gaps = int(np.count_nonzero((nearest >= GAP_MIN) & (nearest <= GAP_MAX)))
    return Quality(len(arcs), recall, sil, out, len(crossings(arcs)), gaps, int(np.count_nonzero(nearest >= GAP_MIN)))


def lost_ink_parts(
    points: np.ndarray,
    gray: np.ndarray,
    *,
    level: float = INK_PART_GRAY,
    min_area: int = INK_PART_MIN_AREA,
    distance: float = INK_PART_DISTANCE,
) -> np.ndarray:
    """The ink parts of an image that a logo lost: their centroids, (K, 2) px.

    An ink part is an 8-connected group of at least ``min_area`` pixels of
    ``gray`` below ``level`` (a stroke, an outline, an eye); it is lost when no
    point of ``points`` lies within ``distance`` px of any of its pixels.

    Parameters
    ----------
    points : ndarray, shape (N, 2)
        The logo's sample points (x, y), px (:func:`logo_points`).
    gray : ndarray, shape (H, W)
        The input's gray values, 0 (black) to 1 (white).
    """
    from scipy import ndimage

    gray = np.asarray(gray, dtype=np.float64)
    if gray.ndim != 2:
        raise InvalidParameterError(f"gray must have shape (H, W), got {gray.shape}")
    labels, n = ndimage.label(gray < level, structure=np.ones((3, 3), dtype=bool))
    if n == 0:
        return np.zeros((0, 2))
    area = np.bincount(labels.ravel(), minlength=n + 1)
    rows, cols = np.nonzero(labels)
    lab = labels[rows, cols]
    big = area[lab] >= min_area
    rows, cols, lab = rows[big], cols[big], lab[big]
    near = _nearest_distance(points, np.column_stack([cols + 0.5, rows + 0.5])) <= distance
    kept = np.bincount(lab[near], minlength=n + 1) > 0
    lost = [k for k in np.unique(lab) if not kept[k]]
    if not lost:
        return np.zeros((0, 2))
    centres = ndimage.center_of_mass(np.ones_like(gray), labels, lost)
    return np.array([(c + 0.5, r + 0.5) for r, c in centres]).reshape(-1, 2)


def stroke_width_ratio(logo_width: float, ink: np.ndarray) -> float:
    """The logo's stroke width over the input's median stroke width; NaN without ink.

    The input's width is :func:`img2logo.features.drawing_lines.median_stroke_width` of
    ``ink`` (H, W) bool: twice the median distance from the ink's medial axis to its edge.
    """
    from .features.drawing_lines import median_stroke_width

    width = median_stroke_width(_check_map(ink, "ink"))
    return float(logo_width) / width if width > 0 else float("nan")


def missed_pixels(points: np.ndarray, truth: np.ndarray, distance: float) -> np.ndarray:
    """The ``truth`` pixels farther than ``distance`` px from ``points``: (H, W) bool."""
    rows, cols, d = _truth_distances(points, truth)
    out = np.zeros(np.shape(truth), dtype=bool)
    out[rows[d > distance], cols[d > distance]] = True
    return out


def _truth_distances(points: np.ndarray, truth: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The rows and columns of the ``truth`` pixels (H, W) and their distances to ``points``, px."""
    truth = _check_map(truth, "truth")
    rows, cols = np.nonzero(truth)
    return rows, cols, _nearest_distance(points, np.column_stack([cols + 0.5, rows + 0.5]))


def _nearest_distance(points: np.ndarray, queries: np.ndarray) -> np.ndarray:
    from scipy.spatial import cKDTree

    if len(points) == 0:
        return np.full(len(queries), np.inf)
    return cKDTree(points).query(queries)[0]


def _arcs(arcs: Abstraction | Sequence[Arc]) -> list[Arc]:
    if isinstance(arcs, Abstraction):
        return list(arcs.arcs)
    out = list(arcs)
    for a in out:
        if not isinstance(a, Arc):
            raise InvalidParameterError(f"arcs must be an Abstraction or a sequence of Arc, got {type(a).__name__}")
    return out


def _check_map(arr: np.ndarray, name: str) -> np.ndarray:
    arr = np.asarray(arr)
    if arr.ndim != 2:
        raise InvalidParameterError(f"{name} must have shape (H, W), got {arr.shape}")
    return arr.astype(bool)
