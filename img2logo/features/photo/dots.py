"""A photo subject's dark dots (paper Sec. 4, beyond it): eyes and noses, drawn as their closed outlines.

The flow-based lines of :mod:`img2logo.features.photo.lines` draw a photo's edges, and keep
the long ones: a small dark dot (an animal's eye, a button nose) gives a short
closed line, which the length filters meant for texture drop, so a teddy bear
or a seal loses its face. A designer always keeps those dots. :func:`dark_dots`
finds them with a scale-space blob detector, the scale-normalized Laplacian of
Gaussian [Lin98] of the CIELAB lightness, and keeps a blob if

* it lies on the subject: the ring around it (``1.5 r`` to ``2.5 r`` of its
  centre, r = sqrt(2) sigma, the blob's radius) is inside the subject mask;
* it is strongly darker than that ring: the ring's median lightness less the
  blob centre's mean is at least ``DOT_MIN_CONTRAST`` L* and at least
  ``DOT_SURROUND_CONTRAST`` times the ring's own spread (its 10-90 % range): a dot on
  an even face, not a dark gap in texture (fur, petals), whose surround varies
  as much as the gap is dark;
* it is a dot, not a part of a longer dark line or of texture: its region (the
  pixels darker than half-way between the centre and the ring, connected to the
  centre) closes within ``1.5 r`` of the centre, and it is no speck (at least
  ``MIN_SPECK_AREA`` px).

Only dark blobs: eyes and nostrils are dark (a pupil and a cavity absorb the
light), while small bright blobs in photos are mostly specular highlights (an
eye's catch light, a lamp), which a designer leaves out: a catch light inside a
dot is filled, so that the dot has one outline, not a ring around the light.
:mod:`img2logo.features.photo.lines` draws each dot as its region's outline, the half-contrast
iso-line (a closed 1-px curve), which the optimization turns into a closed
golden arc or circle.

A pupil in a large eye (a close-up of a cat) fails those tests: a slit is
elongated, so its region runs beyond ``1.5 r`` of the round blob, and its ring
takes in the dark eyelid and the iris's shading, which vary as much as the pupil
is dark. The eye itself says where to measure: :func:`enclosed_dots` finds a dark
dot inside a lighter **closed loop** of the photo's lightness lines (an iris, an
eye's opening), measured against the loop's inside, not a ring. A loop (a
4-connected region between the lines, not open to the frame) of radius up to
``EYE_MAX_RADIUS_FRACTION`` of the image holds a pupil if the largest piece of
lines inside its convex hull (the pupil's outline and what it encloses)

* is no speck (``MIN_SPECK_AREA``), a dot by size (its convex hull within the
  largest dot radius) and at most ``EYE_MAX_PUPIL_SHARE`` of the loop's hull;
* is enclosed by the loop's inside (``EYE_ENCLOSED_SHARE`` of its rim), not a
  bay of a concave loop nor a line running into it;
* lies near the loop's centre (``EYE_MAX_PUPIL_OFFSET``), as a pupil in its iris;
* is dark as a whole: the median of its convex hull (the dot as drawn, below)
  is darker than nine tenths of the loop's inside (its 10th percentile, the
  pixels next to the lines left out) by ``DOT_MIN_CONTRAST`` L*: a population of
  its own, not the dark end of the iris's shading or of texture, and not a
  crease in a light surface (the relief of a coin), whose hull is mostly that
  surface. The loop is the evidence of an eye that the ring test asks the
  surround's evenness for.

The pupil is drawn as the convex hull of those lines: a slit or a disc, with
the catch light and the cornea's reflections that the lines went round inside
it (a pupil is convex).

[Lin98] T. Lindeberg, Feature detection with automatic scale selection, IJCV 30(2), 1998.

Arrays are indexed (row, column), as in :mod:`img2logo.features.photo.lines`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from ..constants import (
    DOT_MAX_RADIUS_FRACTION,
    DOT_MIN_CONTRAST,
    DOT_MIN_RADIUS,
    DOT_SCALES_PER_OCTAVE,
    DOT_SURROUND_CONTRAST,
    EYE_ENCLOSED_SHARE,
    EYE_MAX_PUPIL_OFFSET,
    EYE_MAX_PUPIL_SHARE,
    EYE_MAX_RADIUS_FRACTION,
    MIN_SPECK_AREA,
)

#: The ring around a blob that its contrast is measured on, and the disc its region must close in,
#: in blob radii: the LoG of a disc of radius r changes sign at r, and its surround reaches about 2.5 r.
_CLOSE, _RING_IN, _RING_OUT = 1.5, 1.5, 2.5


@dataclass(frozen=True)
class Dots:
    """The dark dots of a photo's subject (:func:`dark_dots`).

    Attributes
    ----------
    region : ndarray of bool, shape (H, W)
        The dots' pixels: each dot a connected region, inside its half-contrast
        iso-line (its holes, catch lights, filled), or a pupil's convex hull
        (:func:`enclosed_dots`).
    count : int
        How many.
    """

    region: np.ndarray
    count: int


def dot_radii(shape: tuple[int, int]) -> tuple[float, float]:
    """The smallest and the largest radius of a dot in an image of this (H, W), px.

    From ``DOT_MIN_RADIUS`` (the smallest closed line the segment graph splits)
    to ``DOT_MAX_RADIUS_FRACTION`` of the image's longer side, at least the smallest.
    """
    return DOT_MIN_RADIUS, max(DOT_MIN_RADIUS, DOT_MAX_RADIUS_FRACTION * max(shape))


def dark_dots(rgb: np.ndarray, mask: np.ndarray | None, lines: np.ndarray | None = None) -> Dots:
    """The dark dots of a photo's subject: eyes, noses (see the module's docstring).

    Parameters
    ----------
    rgb : ndarray, shape (H, W, 3)
        The photo, in [0, 1].
    mask : ndarray of bool, shape (H, W), or None
        The subject; None: the whole image.
    lines : ndarray of bool, shape (H, W), optional
        The photo's lightness lines (:func:`img2logo.features.photo.line_maps.photo_lines`): the
        dark dots inside their closed loops are found too (:func:`enclosed_dots`).
    """

    rgb = np.asarray(rgb)
    if rgb.ndim != 3 or rgb.shape[2] != 3:
        raise ValueError(f"rgb must be an (H, W, 3) array, got shape {rgb.shape}")
    h, w = rgb.shape[:2]
    if mask is None:
        mask = np.ones((h, w), bool)
    mask = np.asarray(mask, dtype=bool)
    if mask.shape != (h, w):
        raise ValueError(f"mask must have the image's shape {(h, w)}, got {mask.shape}")
    region = np.zeros((h, w), bool)
    if not mask.any():
        return Dots(region, 0)
    lightness = cielab_lightness(rgb)
    if lines is not None:
        lines = np.asarray(lines, dtype=bool)
        if lines.shape != (h, w):
            raise ValueError(f"lines must have the image's shape {(h, w)}, got {lines.shape}")
    count = 0
    for r, c, radius in _blobs(lightness, mask):
        if region[r, c]:
            continue  # a dot found at another scale already
        dot = _dot_region(lightness, mask, r, c, radius)
        if dot is not None:
            (r0, c0), piece = dot
            region[r0 : r0 + piece.shape[0], c0 : c0 + piece.shape[1]] |= fill_holes(piece)
            count += 1
    dots = Dots(region, count)
    return dots if lines is None else with_enclosed_dots(dots, lightness, lines, mask)


def with_enclosed_dots(dots: Dots, lightness: np.ndarray, lines: np.ndarray, mask: np.ndarray) -> Dots:
    """``dots`` and the dark dots inside the closed loops of ``lines`` (:func:`enclosed_dots`).

    One that overlaps a dot of ``dots`` makes it whole (a catch light's notch
    in its rim filled) and is not counted again.
    """
    region = dots.region.copy()
    count = dots.count
    for (r0, c0), piece in enclosed_dots(lightness, lines, mask):
        window = region[r0 : r0 + piece.shape[0], c0 : c0 + piece.shape[1]]
        count += int(not window[piece].any())
        window |= piece
    return Dots(region, count)


def cielab_lightness(rgb: np.ndarray) -> np.ndarray:
    """The CIELAB lightness L* (H, W) float32 of a photo ``rgb`` (H, W, 3) in [0, 1]."""
    import cv2

    return cv2.cvtColor(np.ascontiguousarray(rgb, dtype=np.float32), cv2.COLOR_RGB2Lab)[..., 0]


def fill_holes(piece: np.ndarray) -> np.ndarray:
    """A region (bool) with its holes filled: a catch light inside an eye's dot is part of it.

    The holes are the parts of the background not 4-connected to the window's border.
    """
    import cv2

    outside = np.pad(~np.asarray(piece, dtype=bool), 1, constant_values=True).astype(np.uint8)
    cv2.floodFill(outside, None, (0, 0), 2)
    return outside[1:-1, 1:-1] != 2


def convex_hull(piece: np.ndarray) -> np.ndarray:
    """A region (bool) and the pixels of its convex hull: an eye's catch light is part of its dot.

    A catch light inside a pupil leaves a hole in its dark region, one on its
    rim a notch; an eye, a nostril, a button nose is convex.
    """
    import cv2

    piece = np.asarray(piece, dtype=bool)
    hull = np.zeros(piece.shape, np.uint8)
    cv2.fillPoly(hull, [cv2.convexHull(np.argwhere(piece)[:, ::-1].astype(np.int32))], 1)
    return piece | hull.astype(bool)


def _blobs(lightness: np.ndarray, mask: np.ndarray) -> list[tuple[int, int, float]]:
    """Dark blobs of ``lightness`` (L*) centred in ``mask``: (row, column, radius px), strongest first.

    The local maxima over position and scale of the scale-normalized Laplacian
    of Gaussian ``sigma^2 LoG`` (positive at a dark blob's centre), sigma from
    r_min / sqrt(2) to r_max / sqrt(2) (:func:`dot_radii`), ``DOT_SCALES_PER_OCTAVE``
    a doubling; the response of a disc of contrast C is about 0.8 C at its scale, so
    a maximum below half ``DOT_MIN_CONTRAST`` is not measured further. On OpenCV's
    filters: scikit-image's ``blob_log`` does this job, but importing it costs
    0.2 s (measured), a third of a 512 px photo's run, which loads no scipy.
    """
    import cv2

    r_min, r_max = dot_radii(lightness.shape)
    n = 1 + math.floor(DOT_SCALES_PER_OCTAVE * math.log2(r_max / r_min) + 1e-9)
    sigmas = [r_min / math.sqrt(2.0) * 2.0 ** (k / DOT_SCALES_PER_OCTAVE) for k in range(n)]
    rows, cols = np.nonzero(mask)
    pad = math.ceil(_RING_OUT * r_max) + 1  # the crop around the subject, with room for the rings
    r0, r1 = max(0, rows.min() - pad), min(lightness.shape[0], rows.max() + pad + 1)
    c0, c1 = max(0, cols.min() - pad), min(lightness.shape[1], cols.max() + pad + 1)
    crop = np.ascontiguousarray(lightness[r0:r1, c0:c1])
    stack = np.stack([s * s * cv2.Laplacian(cv2.GaussianBlur(crop, (0, 0), s), cv2.CV_32F) for s in sigmas])
    square = np.ones((3, 3), np.uint8)
    near = np.stack([cv2.dilate(layer, square) for layer in stack])  # the 3 x 3 maximum in each layer
    most = near.copy()
    most[1:] = np.maximum(most[1:], near[:-1])
    most[:-1] = np.maximum(most[:-1], near[1:])
    peaks = (stack >= most) & (stack > 0.5 * DOT_MIN_CONTRAST) & mask[r0:r1, c0:c1][None]
    k, pr, pc = np.nonzero(peaks)
    order = np.argsort(-stack[k, pr, pc], kind="stable")
    return [(int(pr[i]) + r0, int(pc[i]) + c0, math.sqrt(2.0) * sigmas[k[i]]) for i in order]


def enclosed_dots(
    lightness: np.ndarray, lines: np.ndarray, mask: np.ndarray
) -> list[tuple[tuple[int, int], np.ndarray]]:
    """The dark dots inside lighter closed loops of ``lines``: pupils in irises (see the module).

    Parameters
    ----------
    lightness : ndarray of float, shape (H, W)
        The photo's CIELAB lightness, L*.
    lines : ndarray of bool, shape (H, W)
        Its lightness lines (:func:`img2logo.features.photo.line_maps.photo_lines`), before any length filter.
    mask : ndarray of bool, shape (H, W)
        The subject: a dot lies on it.

    Returns
    -------
    list of ((row, column), ndarray of bool)
        Each dot as the top-left corner of a window and its pixels in it: the
        convex hull of the lines inside a loop and of what they enclose.
    """
    import cv2

    h, w = lines.shape
    _, r_dot = dot_radii((h, w))
    r_eye = EYE_MAX_RADIUS_FRACTION * max(h, w)
    n, labels, stats, _ = cv2.connectedComponentsWithStats((~lines).astype(np.uint8), connectivity=4)
    square = np.ones((3, 3), np.uint8)
    found = []
    for i in range(1, n):
        x, y, bw, bh, area = (int(v) for v in stats[i])
        if x == 0 or y == 0 or x + bw == w or y + bh == h:
            continue  # open to the frame: no loop
        if area < MIN_SPECK_AREA or max(bw, bh) > 2.0 * r_eye:
            continue
        r0, c0 = y - 1, x - 1  # a pixel of the loop's lines around it
        inside = labels[r0 : y + bh + 1, c0 : x + bw + 1] == i
        eye = convex_hull(inside)
        if eye.sum() > math.pi * r_eye * r_eye:
            continue
        n_in, parts, part_stats, _ = cv2.connectedComponentsWithStats((eye & ~inside).astype(np.uint8), connectivity=8)
        if n_in < 2:
            continue  # nothing inside
        k = 1 + int(np.argmax(part_stats[1:, cv2.CC_STAT_AREA]))
        lined = parts == k
        if part_stats[k, cv2.CC_STAT_AREA] < MIN_SPECK_AREA:
            continue
        dot = convex_hull(lined)
        size = int(dot.sum())
        if size > EYE_MAX_PUPIL_SHARE * eye.sum() or size > math.pi * r_dot * r_dot:
            continue
        if not mask[r0 : r0 + dot.shape[0], c0 : c0 + dot.shape[1]][dot].all():
            continue
        rim = cv2.dilate(lined.astype(np.uint8), square).astype(bool) & ~lined
        if (rim & inside).sum() < EYE_ENCLOSED_SHARE * rim.sum():
            continue  # a bay of the loop, or a line running into it
        if _offset(eye, dot) > EYE_MAX_PUPIL_OFFSET:
            continue  # off its loop's centre: not its pupil
        ring = cv2.dilate(dot.astype(np.uint8), square).astype(bool)
        iris = cv2.erode(inside.astype(np.uint8), square).astype(bool) & ~ring
        if iris.sum() < MIN_SPECK_AREA:
            continue
        light = lightness[r0 : r0 + dot.shape[0], c0 : c0 + dot.shape[1]]
        if np.percentile(light[iris], 10.0) - np.median(light[dot]) < DOT_MIN_CONTRAST:
            continue  # not darker than the iris's shaded parts, or a crease in a light surface
        found.append(((r0, c0), dot))
    return found


def _offset(loop: np.ndarray, dot: np.ndarray) -> float:
    """How far the centre of ``dot`` is from that of ``loop`` (bool, one window), in the loop's radii.

    Measured in the loop's own ellipse (the Mahalanobis distance under the
    second moments of its pixels, halved: 1 on the rim of a uniform ellipse).
    """
    ly, lx = np.nonzero(loop)
    dy, dx = np.nonzero(dot)
    cov = np.cov(np.vstack([ly, lx]).astype(np.float64))
    delta = np.array([dy.mean() - ly.mean(), dx.mean() - lx.mean()])
    try:
        return 0.5 * math.sqrt(max(0.0, float(delta @ np.linalg.solve(cov, delta))))
    except np.linalg.LinAlgError:  # a loop one pixel wide: no centre to speak of
        return math.inf


@functools.lru_cache(maxsize=64)
def _window(radius: float) -> tuple[int, np.ndarray, np.ndarray, np.ndarray]:
    """A blob's window around its centre: its half side (px), and in it the centre's disc (0.5 r),
    the ring (1.5-2.5 r) and the pixels beyond the disc its region must close in (1.5 r), bool."""
    reach = math.ceil(_RING_OUT * radius)
    yy, xx = np.ogrid[-reach : reach + 1, -reach : reach + 1]
    d = np.hypot(yy, xx)
    return reach, d <= 0.5 * radius, (d > _RING_IN * radius) & (d <= _RING_OUT * radius), d > _CLOSE * radius


def _dot_region(
    lightness: np.ndarray, mask: np.ndarray, r: int, c: int, radius: float
) -> tuple[tuple[int, int], np.ndarray] | None:
    """The region of the blob at (r, c) of this radius if it is a dot (see the module), else None.

    Returns the top-left corner (row, column) of a window and the dot's pixels in it.
    """
    import cv2

    h, w = lightness.shape
    reach, centre_disc, ring, beyond = _window(radius)
    r0, r1, c0, c1 = r - reach, r + reach + 1, c - reach, c + reach + 1
    if r0 < 0 or c0 < 0 or r1 > h or c1 > w:
        return None  # its ring leaves the image: not on the subject
    light = lightness[r0:r1, c0:c1]
    if not mask[r0:r1, c0:c1][ring].all():
        return None
    centre = float(light[centre_disc].mean())
    low, around, high = (float(v) for v in np.percentile(light[ring], (10.0, 50.0, 90.0)))
    if around - centre < max(DOT_MIN_CONTRAST, DOT_SURROUND_CONTRAST * (high - low)):
        return None
    dark = (light < 0.5 * (centre + around)).astype(np.uint8)
    if not dark[reach, reach]:
        return None
    _, labels = cv2.connectedComponents(dark, connectivity=8)
    piece = labels == labels[reach, reach]
    if piece[beyond].any():
        return None  # it runs on: a part of a longer dark line, or of texture
    if piece.sum() < MIN_SPECK_AREA:
        return None  # a speck of noise or grain
    return (r0, c0), piece
