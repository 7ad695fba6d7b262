"""Feature lines of real photos (paper Sec. 4): the subject's outline and a flow-based line drawing [KD09].

:func:`photo_feature_lines` draws a photo's subject (found by
:mod:`img2logo.features.photo.subject`) as

* its **outline**: the boundary of the subject mask, a closed smooth curve
  (the mask is smoothed; the parts on the image frame are left out);
* its **inner lines**: an edge tangent flow from the smoothed structure tensor,
  a difference of Gaussians across the flow, smoothed along it, binarized
  (:func:`~img2logo.features.photo.line_maps.flow_dog`), kept ``INNER_LINE_MARGIN`` px inside the outline; only
  the long ones, not tangles, the longest first within a length budget
  (:func:`salient_lines`);
* its **colour lines**: the FDoG of the colour-opponent channel
  (:func:`~img2logo.features.photo.line_maps.photo_lines`), after the lightness lines and within what they leave
  of the budget; one is drawn where no drawn line is that edge already and no
  stronger lightness edge lies beside it, whole back to the line it meets
  (:func:`~img2logo.features.photo.line_maps.new_colour_lines`): a pink nose's top on tan fur;
* its **dark dots** (:func:`subject_dots`, :mod:`img2logo.features.photo.dots`): eyes
  and noses, small dark blobs on the subject, and pupils, dark dots inside the
  closed loops of the lightness lines (an iris), each drawn as its closed outline
  first (a catch light inside), the lines of its own edge left out; the caller
  keeps them through the length filters (:func:`dot_lines`);
* **faces** (:attr:`Subject.faces`): inside the ellipse of each face found,
  the FDoG lines are kept down to ``FACE_MIN_LINE`` of the face's side, first
  in the budget: eyes, brows, nose and mouth are inner lines of the subject;
* **carried to the outline**: an inner line that runs into the outline and
  stops within the margin of it is carried on to it (:func:`reach_outline`);
* **joined**: a line end that stops within ``LINE_JOIN_DISTANCE`` of another
  line is linked to it by a straight run of pixels (:func:`join_line_ends`), so
  that the segment graph has a junction there, not a near-miss gap; a short
  branch beside the other branch of its fork is removed instead.

Without a subject (a scene) the salient lines of the whole image are drawn and
joined. The caller prunes spurs (``PHOTO_SPUR_LENGTH``) and short isolated
lines.
"""

from __future__ import annotations

import math

import numpy as np

from ...constants import LINE_JOIN_DISTANCE
from ...images.line_ends import join_line_ends
from ...images.loading import LoadedImage
from ..constants import (
    COLOUR_LINE_GATE,
    EDGE_SIDE_REACH,
    FACE_MIN_LINE,
    FDOG_SIGMA_C,
    INNER_LINE_MARGIN,
    INNER_MIN_LENGTH,
    INNER_MIN_SPAN,
    OUTLINE_FRAME_MARGIN,
    PHOTO_LINE_BUDGET,
    STEP_SIDE_CONTRAST,
)
from .dots import Dots, cielab_lightness, dark_dots, with_enclosed_dots
from .line_maps import LineMaps, line_maps, new_colour_lines
from .subject import Subject


def subject_dots(img: LoadedImage, subject: Subject, maps: LineMaps | None = None) -> Dots:
    """The dark dots of a photo's subject (:func:`img2logo.features.photo.dots.dark_dots`): none without a subject.

    With the photo's line maps (:func:`~img2logo.features.photo.line_maps.line_maps`), the dark dots inside the
    closed loops of its lightness lines too (:func:`subject_pupils`).
    """
    if subject.mask is None:  # a scene: no face to keep the dots of
        return Dots(np.zeros((img.height, img.width), bool), 0)
    return dark_dots(img.rgb, subject.mask, None if maps is None else maps.lightness)


def subject_pupils(img: LoadedImage, subject: Subject, maps: LineMaps, dots: Dots) -> Dots:
    """``dots`` (:func:`subject_dots` without line maps) and the dark dots inside the closed loops of
    the lightness lines: pupils in irises (:func:`img2logo.features.photo.dots.enclosed_dots`).

    Two steps, so that the blob dots are found while the line maps are still
    being made beside the subject's cuts (:func:`~img2logo.features.photo.line_maps.start_photo_line_maps`).
    """
    if subject.mask is None:
        return dots
    return with_enclosed_dots(dots, cielab_lightness(img.rgb), maps.lightness, subject.mask)


def dot_lines(raw: np.ndarray, dots: Dots) -> np.ndarray:
    """The lines of ``raw`` (:func:`photo_feature_lines`) that draw the dots: (H, W) bool.

    A dot's outline is shorter than a photo's shortest line (``PHOTO_MIN_LINE_LENGTH``);
    the caller adds these back after the length filters.
    """
    from ...images.ndimage import dilate  # scipy.ndimage's binary dilation, without importing it

    if not dots.count:
        return np.zeros(raw.shape, bool)
    return raw & dilate(dots.region, 2)


def photo_feature_lines(
    img: LoadedImage, subject: Subject, dots: Dots | None = None, maps: LineMaps | None = None
) -> np.ndarray:
    """A photo's feature lines, (H, W) bool, 1 px wide: outline, dots, inner lines, joined.

    Parameters
    ----------
    img : LoadedImage
        The photo.
    subject : Subject
        Its subject (:func:`img2logo.features.photo.subject.find_subject`); a mask of None
        draws the whole image.
    dots : Dots, optional
        Its dark dots (:func:`subject_dots`, found here by default): each is
        drawn as its outline, and the lines within ``EDGE_SIDE_REACH`` of it
        (its own edge's FDoG lines) are not.
    maps : LineMaps, optional
        Its line maps (:func:`~img2logo.features.photo.line_maps.line_maps`, made or taken here by default).
    """
    from ...images.ndimage import dilate, erode, skeletonize

    mask = subject.mask
    if maps is None:
        maps = line_maps(img)
    inner = maps.lightness
    budget = PHOTO_LINE_BUDGET * (img.height + img.width)
    if dots is None:
        dots = subject_dots(img, subject, maps)
    dot_outline = np.zeros(inner.shape, bool)
    if dots.count:
        dot_outline = subject_outline(dots.region, frame_margin=0.0)
        inner = inner & ~dilate(dots.region, math.ceil(EDGE_SIDE_REACH))
        budget = max(0.0, budget - float(dot_outline.sum()))
    faces = face_region((img.height, img.width), subject.faces)
    if mask is None:
        lines, budget = _chosen_lines(inner, faces, subject.faces, budget)
        colour = new_colour_lines(maps, lines)
        colour_lines, _ = _chosen_lines(colour, faces, subject.faces, budget, budget)
        return join_line_ends(lines | colour_lines)
    inside = erode(mask, INNER_LINE_MARGIN)
    if maps.steps is not None:
        inner = inner | clear_steps(img.gray, maps.steps & inside, inner)
    outline = subject_outline(mask)
    budget = max(0.0, budget - float(outline.sum()))
    lines, budget = _chosen_lines(inner & inside, faces, subject.faces, budget)
    # A colour line within the gate of the outline is the outline again (its lightness line
    # lay outside the mask): colour lines are kept that much further inside.
    if maps.colour.any():  # the erosion by ceil(gate) 4-neighbour steps: taxicab distance to the outside
        deep = erode(inside, math.ceil(COLOUR_LINE_GATE))  # taxicab distance > ceil(gate)
        if dots.count:  # a dot's colour lines are its outline again
            deep &= ~dilate(dots.region, math.ceil(COLOUR_LINE_GATE))
        colour = new_colour_lines(maps, lines | outline | dot_outline, deep, inside)
        lines |= _chosen_lines(colour, faces, subject.faces, budget, budget)[0]
    return join_line_ends(skeletonize(reach_outline(lines, outline) | outline | dot_outline))


def _chosen_lines(
    lines: np.ndarray,
    region: np.ndarray,
    faces: tuple[tuple[int, int, int, int], ...],
    budget: float,
    face_budget: float = math.inf,
) -> tuple[np.ndarray, float]:
    """The salient lines of a line map (H, W) bool, the faces' first; and the budget left, px.

    Inside the faces' ``region`` lines down to :func:`face_line_length` are
    kept within ``face_budget`` (a face's eyes and mouth are short), the rest by
    :func:`salient_lines` within ``budget`` less the faces' lines.
    """
    from ...images.ndimage import skeletonize

    chosen = np.zeros(lines.shape, bool)
    if faces:
        length = face_line_length(faces)
        chosen = salient_lines(skeletonize(lines & region), length, length, face_budget)
        budget = max(0.0, budget - float(chosen.sum()))
    chosen |= salient_lines(skeletonize(lines & ~region), budget=budget)
    return chosen, max(0.0, budget - float(chosen.sum()))


def clear_steps(gray: np.ndarray, steps: np.ndarray, lines: np.ndarray) -> np.ndarray:
    """The lines of clear lightness steps that the lightness lines miss: (H, W) bool, 1 px wide.

    The lightness lines' bias to dark sides (``FDOG_RHO`` < 1, [KD09]) leaves out
    the step between two light regions (a seal's white belly on its grey body:
    the bias, 1 % of the blurred gray, is most of the step's response). ``steps``
    are the dark sides of every edge, the FDoG without that bias. Those more than
    ``LINE_JOIN_DISTANCE / 2`` px from ``lines``, thinned, long enough for
    :func:`salient_lines`, are kept where they are a clear step: the median
    lightness difference between the two sides (``gray`` sampled ``EDGE_SIDE_REACH``
    px across the line, along the gradient) is at least ``STEP_SIDE_CONTRAST``
    times the sides' own spread (the mean of their 10-90 % ranges along the line):
    an edge between two even regions, not a crease in texture (fur, petals, skin).
    """
    import cv2

    from ...images.ndimage import dilate, label, skeletonize

    out = np.zeros(steps.shape, bool)
    new = steps & ~dilate(lines, math.ceil(LINE_JOIN_DISTANCE / 2.0)) if lines.any() else steps
    if not new.any():
        return out
    new = salient_lines(skeletonize(new))
    labels, n = label(new, eight=True)
    if n == 0:
        return out
    g = cv2.GaussianBlur(np.ascontiguousarray(gray, dtype=np.float32), (0, 0), FDOG_SIGMA_C)
    rows, cols = np.nonzero(labels)
    gx = cv2.Sobel(g, cv2.CV_32F, 1, 0)[rows, cols]
    gy = cv2.Sobel(g, cv2.CV_32F, 0, 1)[rows, cols]
    norm = np.hypot(gx, gy) + np.float32(1e-12)
    dx, dy = EDGE_SIDE_REACH * gx / norm, EDGE_SIDE_REACH * gy / norm

    def side(sign: float) -> np.ndarray:
        x, y = (cols + sign * dx).astype(np.float32), (rows + sign * dy).astype(np.float32)
        return cv2.remap(g, x[None], y[None], cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)[0]

    light, dark = side(1.0), side(-1.0)
    which = labels[rows, cols]
    keep = np.zeros(n + 1, bool)
    for i in range(1, n + 1):
        on = which == i
        a, b = light[on], dark[on]
        spread = 0.5 * (np.subtract(*np.percentile(a, (90.0, 10.0))) + np.subtract(*np.percentile(b, (90.0, 10.0))))
        keep[i] = float(np.median(a - b)) >= STEP_SIDE_CONTRAST * spread
    return keep[labels]


def reach_outline(lines: np.ndarray, outline: np.ndarray) -> np.ndarray:
    """Inner lines (H, W) bool, those that run into the outline carried on to it.

    Inner lines are cut ``INNER_LINE_MARGIN`` px inside the outline (and the
    FDoG fades where three regions meet), so an edge between two of the
    subject's regions stops short of the outline it meets: further than
    ``LINE_JOIN_DISTANCE`` it would stay a near-miss gap. An end within
    ``INNER_LINE_MARGIN + LINE_JOIN_DISTANCE`` of ``outline`` is carried
    straight on (its direction: from the mean of the line's pixels within
    ``LINE_JOIN_DISTANCE`` of the end to the end); if that meets the outline
    within the same distance, the end is joined to the outline there by a
    straight run. A line running beside the outline is left alone.
    """
    from ..._compat import line
    from ...images.ndimage import label, nearest_background
    from ...images.skeleton import classify

    out = np.asarray(lines, dtype=bool).copy()
    if not out.any() or not outline.any():
        return out
    h, w = out.shape
    dist, (near_r, near_c) = nearest_background(~outline)
    reach = INNER_LINE_MARGIN + LINE_JOIN_DISTANCE
    ends = np.argwhere(out & (classify(out)[1] == 1) & (dist <= reach) & (dist > 1.5))
    labels, _ = label(out, eight=True)
    box = math.ceil(LINE_JOIN_DISTANCE)
    for r, c in ends:
        r0, c0 = max(0, r - box), max(0, c - box)
        rows, cols = np.nonzero(labels[r0 : r + box + 1, c0 : c + box + 1] == labels[r, c])
        rows, cols = rows + r0, cols + c0
        close = np.hypot(rows - r, cols - c) <= LINE_JOIN_DISTANCE
        heading = np.array([r - rows[close].mean(), c - cols[close].mean()])
        if not np.any(heading):
            continue
        heading /= np.linalg.norm(heading)
        for t in np.arange(1.0, reach + 1.0):  # straight on from the end: does it meet the outline?
            qr, qc = (round(v) for v in np.array([r, c]) + t * heading)
            if not (0 <= qr < h and 0 <= qc < w):
                break
            if dist[qr, qc] <= 1.0:
                rr, cc = line(int(r), int(c), int(near_r[qr, qc]), int(near_c[qr, qc]))
                out[rr, cc] = True
                break
    return out


def face_region(shape: tuple[int, int], faces: tuple[tuple[int, int, int, int], ...]) -> np.ndarray:
    """The ellipses inscribed in face boxes (x, y, w, h), px, as an (H, W) bool map."""
    out = np.zeros(shape, bool)
    if not faces:  # no import of skimage.draw (it imports scipy) for a photo without faces
        return out
    from skimage.draw import ellipse

    for x, y, w, h in faces:
        rr, cc = ellipse(y + h / 2.0, x + w / 2.0, h / 2.0, w / 2.0, shape=shape)
        out[rr, cc] = True
    return out


def face_line_length(faces: tuple[tuple[int, int, int, int], ...]) -> float:
    """The shortest line kept inside the faces, px: ``FACE_MIN_LINE`` of the smallest face's side."""
    return FACE_MIN_LINE * min((min(w, h) for _, _, w, h in faces), default=0.0)


def salient_lines(
    skel: np.ndarray,
    min_length: float = INNER_MIN_LENGTH,
    min_span: float = INNER_MIN_SPAN,
    budget: float = math.inf,
) -> np.ndarray:
    """The long lines of a 1-px line map, (H, W) bool, before any are joined.

    A connected line is kept if it has at least ``min_length`` pixels and its
    extent (the diagonal of its bounding box) is at least ``min_span`` px:
    short strokes of texture and small tangles (a thinned blob of fur) go,
    before joining could link them into a network. Of those, the longest are
    kept while their pixels add up to at most ``budget``.
    """
    from ...images.ndimage import bounding_slices, label

    skel = np.asarray(skel, dtype=bool)
    lab, n = label(skel, eight=True)
    if n == 0:
        return skel.copy()
    sizes = np.bincount(lab.ravel(), minlength=n + 1)
    keep = np.zeros(n + 1, bool)
    for i, sl in enumerate(bounding_slices(lab), start=1):
        if sl is None:
            continue
        span = math.hypot(sl[0].stop - sl[0].start, sl[1].stop - sl[1].start)
        keep[i] = sizes[i] >= min_length and span >= min_span
    total = 0
    for i in sorted(np.flatnonzero(keep), key=lambda i: (-sizes[i], i)):
        total += int(sizes[i])
        keep[i] = total <= budget
    return keep[lab]


def subject_outline(mask: np.ndarray, frame_margin: float = OUTLINE_FRAME_MARGIN) -> np.ndarray:
    """The outline of a subject mask as 8-connected 1-px curves, (H, W) bool.

    The iso-line at one half of the mask (blurred by a Gaussian of 1 px, so the
    curve is sub-pixel smooth), with the parts within ``frame_margin`` px of the
    image frame left out: there the picture ends, not the object. Holes give
    their own closed curves.
    """
    from skimage.measure import find_contours

    from ..._compat import line
    from ...images.ndimage import gaussian

    h, w = mask.shape
    out = np.zeros((h, w), bool)
    soft = gaussian(np.pad(mask.astype(np.float64), 1), 1.0)
    for contour in find_contours(soft, 0.5):
        rc = contour - 1.0  # (row, col) of pixel centres, unpadded
        keep = (
            (rc[:, 0] >= frame_margin)
            & (rc[:, 0] <= h - 1 - frame_margin)
            & (rc[:, 1] >= frame_margin)
            & (rc[:, 1] <= w - 1 - frame_margin)
        )
        ij = np.clip(np.round(rc).astype(np.int64), 0, [h - 1, w - 1])
        both = keep[:-1] & keep[1:]
        # A step to a neighbour (all of marching squares') is its two end pixels; a longer one a line.
        near = both & (np.abs(np.diff(ij, axis=0)).max(axis=1, initial=0) <= 1)
        out[ij[:-1][near, 0], ij[:-1][near, 1]] = True
        out[ij[1:][near, 0], ij[1:][near, 1]] = True
        for a in np.flatnonzero(both & ~near):
            rr, cc = line(ij[a, 0], ij[a, 1], ij[a + 1, 0], ij[a + 1, 1])
            out[rr, cc] = True
    return out
