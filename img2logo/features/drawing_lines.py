"""A line drawing's lines (paper Sec. 4): its ink, its strokes' width, the skeleton cleaned, dots kept.

The ink is the drawing's dark (or light) strokes by Otsu's threshold, the paper
pinched between two strokes kept apart (:func:`drawing_ink`); thinned to a 1-px
skeleton, its spurs, specks and tiny loops pruned (:func:`clean_skeleton`, for
every kind); a filled dot left without a line gets a circle (:func:`keep_dots`).
"""

from __future__ import annotations

import numpy as np

from .._compat import circle_perimeter, median
from ..constants import BLANK_IMAGE_RANGE, JUNCTION_MERGE_DISTANCE
from ..images import skeleton as _skeleton
from ..images.loading import LoadedImage
from ..images.ndimage import components, distance, skeletonize
from .constants import (
    DOT_MIN_DIAMETER,
    DOT_MIN_RADIUS,
    MIN_SPECK_AREA,
    SEAM_CONTRAST,
    SEAM_LENGTH,
    SEAM_RIM,
    SEAM_WIDTH,
)


def drawing_ink(img: LoadedImage) -> tuple[np.ndarray, np.ndarray]:
    """Ink of a line drawing and its strokes' half width: Otsu threshold, specks removed, holes of 1-2 px filled.

    Returns
    -------
    ink : ndarray of bool, shape (H, W)
        The drawing's strokes.
    radius : ndarray of float32, shape (H, W)
        :func:`half_width` of ``ink``, px.
    """
    luma = img.gray  # computed at each access: once here
    gray = gaussian_blur(luma, 1.0)  # smooths the stroke edges: fewer spurs
    if np.ptp(gray) < BLANK_IMAGE_RANGE:
        return np.zeros(gray.shape, dtype=bool), np.zeros(gray.shape, dtype=np.float32)
    thresholded = gray < otsu_threshold(gray)
    dark = thresholded.mean() <= 0.5
    if not dark:  # light strokes on a dark ground
        thresholded = ~thresholded
    depth = distance(thresholded)
    ink = thresholded & ~_paper_seams(luma if dark else 1.0 - luma, thresholded, depth)
    ink = without_small_parts(ink, MIN_SPECK_AREA - 1)
    ink = ~without_small_parts(~ink, MIN_SPECK_AREA // 4)
    # Mostly no seam, speck or hole changed the ink: its distance to the paper is known then.
    return ink, half_width(ink, depth if np.array_equal(ink, thresholded) else None)


def _paper_seams(gray: np.ndarray, ink: np.ndarray, depth: np.ndarray) -> np.ndarray:
    """The paper pinched between two strokes that run side by side: (H, W) bool.

    ``depth`` (H, W) is the distance of ``ink`` to the paper (:func:`img2logo.images.ndimage.distance`).

    Where two thick strokes nearly touch, the paper between them is a light line
    only a pixel or two wide whose anti-aliased grey falls below the ink
    threshold (a 13 px erosion of ``data/drawing-bird.png`` closes the gap
    between its wing and its body so, L* 48): the strokes would be one blob,
    thinned to one centre line between the two. Such a line is a light ridge of
    ``gray`` (ink dark, 0-1): a white top-hat (Soille, Morphological Image
    Analysis, 2003, Sec. 4.4) with a disc ``SEAM_WIDTH`` px across, above
    ``SEAM_CONTRAST`` of the paper-ink contrast, within the ink. A stroke's edge
    against open paper is no ridge, so nothing else changes.
    """
    import cv2

    if not ink.any() or ink.all():
        return np.zeros(ink.shape, dtype=bool)
    g = np.asarray(gray, dtype=np.float32)
    contrast = float(median(g[~ink]) - median(g[ink]))
    disc = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (SEAM_WIDTH, SEAM_WIDTH))
    ridge = cv2.morphologyEx(g, cv2.MORPH_TOPHAT, disc) > SEAM_CONTRAST * contrast
    # Pinched paper lies inside the ink; the tip of a paper wedge where two strokes meet at an
    # acute angle is a ridge too, but next to open paper: the junction stays where it is.
    ridge &= depth > SEAM_WIDTH / 2
    if not ridge.any():
        return ridge
    # Two strokes that only touch (an ear's base, a tail on a body) leave a ridge about as long
    # as they are wide, where they are one in the drawing too; side by side, the pinch runs
    # along them: a seam is at least SEAM_LENGTH stroke widths long.
    parts = components(ridge, connectivity=2)
    n = int(parts.max())
    long = np.bincount(parts.ravel(), minlength=n + 1) >= SEAM_LENGTH * _median_stroke_width(ink, depth)
    long[0] = False
    ridge = long[parts].astype(np.uint8)
    # A ridge 1 px wide runs diagonally in steps that 8-connected ink crosses: widened by the
    # light pixels beside it (the strokes' rims), never into the ink itself.
    light = g > median(g[ink]) + SEAM_RIM * contrast
    return ink & light & (cv2.dilate(ridge, cv2.getStructuringElement(cv2.MORPH_CROSS, (3, 3))) > 0)


def median_stroke_width(ink: np.ndarray) -> float:
    """The typical width of the strokes of ``ink`` (H, W) bool, px; 0 without ink.

    Twice the median, over the ink's skeleton (its medial axis), of the distance
    to the nearest pixel that is not ink: a stroke w px wide has its axis w / 2
    from both edges (to within half a pixel).
    """
    return _median_stroke_width(ink, distance(ink))


def _median_stroke_width(ink: np.ndarray, dist: np.ndarray) -> float:
    """:func:`median_stroke_width` of ``ink`` whose distance to the paper ``dist`` (``ndimage.distance``) is known."""
    skel = skeletonize(ink)
    return float(2.0 * median(dist[skel])) if skel.any() else 0.0


def keep_dots(lines: np.ndarray, ink: np.ndarray, stroke_width: float) -> np.ndarray:
    """Give every ink part left without a feature line a closed line at its centre: (H, W) bool.

    A filled dot (an animal's eye) thins to a point or a stub, and a small ring
    to a loop shorter than the length filters keep: both would vanish from the
    logo. An 8-connected part of ``ink`` with no pixel of ``lines`` and a
    diameter (that of the disc of its area) of at least ``DOT_MIN_DIAMETER``
    (the speck filter's bound: smaller ink is noise) gets a 1-px circle at its
    centroid, of the radius whose stroke covers it: (d - ``stroke_width``) / 2,
    at least ``DOT_MIN_RADIUS``. The optimization fits it with one full golden
    circle.

    Parameters
    ----------
    lines : ndarray of bool, shape (H, W)
        The cleaned feature lines.
    ink : ndarray of bool, shape (H, W)
        The drawing's ink.
    stroke_width : float
        The drawing's median stroke width, px.
    """
    labels = components(ink, connectivity=2)
    n = int(labels.max())
    if n == 0:
        return lines
    lined = np.bincount(labels[lines], minlength=n + 1) > 0
    area = np.bincount(labels.ravel(), minlength=n + 1)
    diameter = 2.0 * np.sqrt(area / np.pi)
    bare = [k for k in range(1, n + 1) if not lined[k] and diameter[k] >= DOT_MIN_DIAMETER]
    if not bare:
        return lines
    out = lines.copy()
    # scipy.ndimage.center_of_mass(ink, labels, bare): the same sums, by label, over the bare parts'
    # pixels only (in raster order, as over the whole image: the same additions in the same order).
    is_bare = np.zeros(n + 1, dtype=bool)
    is_bare[bare] = True
    at = np.flatnonzero(is_bare[labels])
    label_at = labels.ravel()[at]
    rows, cols = np.divmod(at, ink.shape[1])
    mass = np.bincount(label_at, weights=np.ones(len(at)), minlength=n + 1)[bare]
    centres = zip(
        np.bincount(label_at, weights=rows.astype(np.float64), minlength=n + 1)[bare] / mass,
        np.bincount(label_at, weights=cols.astype(np.float64), minlength=n + 1)[bare] / mass,
        strict=True,
    )
    for k, (r, c) in zip(bare, centres, strict=True):
        radius = max(DOT_MIN_RADIUS, (diameter[k] - stroke_width) / 2.0)
        rr, cc = circle_perimeter(round(r), round(c), round(radius), out.shape)
        out[rr, cc] = True
    return out


def clean_skeleton(
    mask: np.ndarray, *, spur_length: float, min_length: float, radius: np.ndarray | None = None
) -> np.ndarray:
    """Thin ``mask`` to 1 px and prune spurs, specks and tiny loops.

    ``radius`` (H, W), px: a drawing's stroke half width, which lengthens the
    spurs pruned at a junction by the stroke's half width there
    (:func:`_skeleton.prune`).
    """
    skel = skeletonize(mask)
    graph = _skeleton.trace(skel)
    _skeleton.prune(
        graph,
        spur_length=spur_length,
        min_length=min_length,
        junction_merge=JUNCTION_MERGE_DISTANCE,
        radius=radius,
    )
    return _skeleton.rasterize(graph, skel.shape)


def half_width(ink: np.ndarray, dist: np.ndarray | None = None) -> np.ndarray:
    """The half width of a drawing's strokes at every pixel, px: the ink's distance to the paper, (H, W) float32.

    Measured on the skeleton, where it is the radius of the stroke's inscribed
    disc; 0 on the paper. ``dist``: that distance (``ndimage.distance(ink)``) when it is known.
    """
    return (distance(ink) if dist is None else dist).astype(np.float32)


def gaussian_blur(image: np.ndarray, sigma: float) -> np.ndarray:
    """``scipy.ndimage.gaussian_filter(image, sigma)`` of a 2-D image, to the bit, float64 (H, W).

    :func:`img2logo.images.ndimage.gaussian` on the image as float64: scipy's kernel
    (``truncate`` 4 standard deviations, mode ``reflect``) and its compiled 1-D
    correlations, rows then columns, without importing ``scipy.ndimage``.
    """
    from ..images.ndimage import gaussian

    return gaussian(np.asarray(image, dtype=np.float64), sigma)


def otsu_threshold(gray: np.ndarray) -> float:
    """Otsu's threshold of a grey image (Otsu 1979), as ``skimage.filters.threshold_otsu(gray)`` computes it.

    The maximum of the between-class variance over a 256-bin histogram of the
    image's range; the threshold is that bin's centre. Written out because
    ``skimage.filters`` imports ``scipy.ndimage`` (about 0.1 s of CPU a run);
    the same steps in the same float types give the same threshold.
    """
    values = np.asarray(gray).reshape(-1)
    if np.all(values == values[0]):
        return float(values[0])
    hist, edges = np.histogram(values, bins=256)
    centres = (edges[:-1] + edges[1:]) / 2.0
    counts = hist.astype(np.float32)
    below, above = np.cumsum(counts), np.cumsum(counts[::-1])[::-1]
    mean_below = np.cumsum(counts * centres) / below
    mean_above = (np.cumsum((counts * centres)[::-1]) / above[::-1])[::-1]
    between = below[:-1] * above[1:] * (mean_below[:-1] - mean_above[1:]) ** 2
    return float(centres[np.argmax(between)])


def without_small_parts(mask: np.ndarray, max_size: int) -> np.ndarray:
    """``mask`` less its 4-connected parts of at most ``max_size`` px, bool (H, W).

    What ``skimage.morphology.remove_small_objects(mask, max_size=max_size)``
    does (and, on ``~mask``, ``remove_small_holes``), by OpenCV's component
    labelling: importing ``skimage.morphology`` costs about 0.1 s of CPU a run.
    The parts' areas are counted by ``np.bincount``: OpenCV's statistics (boxes,
    centroids) took twice as long as the labelling and the count together.
    """
    import cv2

    count, parts = cv2.connectedComponents(mask.astype(np.uint8), connectivity=4)
    keep = np.bincount(parts.ravel(), minlength=count) > max_size
    keep[0] = False  # the background
    return keep[parts]
