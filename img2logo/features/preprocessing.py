"""Preprocessing (paper Sec. 4): an image's feature lines, by its kind.

Three kinds of input, as in the paper:

* **line drawing**: binarize, drop small specks, thin to a 1-px skeleton, prune
  short spurs (here);
* **clip art**: boundaries between flat-colour regions (:mod:`img2logo.features.clipart`);
* **real photo**: a flow-based line drawing after Kang et al. [KD09]
  (:mod:`img2logo.features.photo.lines`).

Loading is :mod:`img2logo.images.loading`; its names are re-exported here.

Arrays are indexed (row, column); points are (x, y) = (column + 0.5, row + 0.5)
in px, x to the right, y downwards (``contract/README.md``).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from .._compat import median
from .._validation import check_choice, check_positive, readonly
from ..constants import BLANK_IMAGE_RANGE, DETAIL, JUNCTION_MERGE_DISTANCE, SYNTHETIC_WORK_SIDE
from ..images import skeleton as _skeleton
from ..images.line_ends import join_line_ends
from ..images.loading import LoadedImage, downscale, load_image, load_mask
from ..images.ndimage import bounding_slices, components, distance, skeletonize
from .clipart import clipart_lines, clipart_regions, enclosed_paper, label_means
from .constants import (
    CLIPART_OUTLINE_WIDTH,
    CLIPART_RIM_RADIUS,
    DOT_MIN_DIAMETER,
    DOT_MIN_RADIUS,
    DRAWING_MAX_STROKE_FRACTION,
    INK_COLOUR_SPREAD,
    INK_SHARE,
    MIN_SPECK_AREA,
    OUTLINE_BAND_REACH,
    PHOTO_MIN_LINE_LENGTH,
    PHOTO_SPUR_LENGTH,
    SEAM_CONTRAST,
    SEAM_LENGTH,
    SEAM_RIM,
    SEAM_WIDTH,
    SHADED_INK_MAX_LIGHTNESS,
    SHADED_INK_SHARE,
    SPUR_LENGTH,
    SYNTHETIC_FLAT_FRACTION,
)
from .detail import check_detail, close_line_ends, merge_by_importance

if TYPE_CHECKING:
    from .photo.line_maps import edge_tangent_flow, flow_dog
    from .photo.subject import Subject

# The photo modules (the flow-based lines, the subject's segmentation) load only for a
# photo: a clip art's or a drawing's run does not import them.
_PHOTO_NAMES = ("edge_tangent_flow", "flow_dog")


def __getattr__(name: str) -> Any:
    if name in _PHOTO_NAMES:
        from .photo import line_maps as photo

        return getattr(photo, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "KINDS",
    "FeatureLines",
    "detect_kind",
    "detect_kind_and_regions",
    "edge_tangent_flow",
    "extract_feature_lines",
    "flow_dog",
    "keep_dots",
    "load_image",
    "load_mask",
    "median_stroke_width",
    "photo_reason",
    "without_small_parts",
]

KINDS = ("photo", "clipart", "drawing")


@dataclass(frozen=True, eq=False)
class FeatureLines:
    """Feature lines of an image: a 1-px-wide map and how it was made.

    Attributes
    ----------
    lines : ndarray of bool, shape (H, W)
        The 1-px-wide feature-line map.
    kind : str
        ``"photo"``, ``"clipart"`` or ``"drawing"``.
    reason : str
        Why this kind: ``"given"`` or what :func:`detect_kind` measured.
    regions : ndarray of int, shape (H, W), or None
        For clip art, the flat-colour region label of each pixel (0 = background).
    subject : Subject or None
        For photos, the part of the image drawn and how it was found
        (:func:`img2logo.features.photo.subject.find_subject`).
    stroke_width : float or None
        For a line drawing, its median stroke width, px: twice the median
        distance from the ink's skeleton to the paper
        (:func:`median_stroke_width`); None for the other kinds.
    detail : int or None
        For a clip art, the regions kept besides the background
        (:func:`img2logo.features.detail.merge_by_importance`): the ``detail``
        asked, more where what is never merged is more, fewer where there were
        too many regions; None for the other kinds.

    Examples
    --------
    >>> import cv2, numpy as np
    >>> image = np.full((160, 160, 3), 255, np.uint8)
    >>> _ = cv2.circle(image, (80, 80), 50, (0, 0, 0), 3)  # a black ring, 50 px round
    >>> from img2logo import extract_feature_lines
    >>> lines = extract_feature_lines(image)  # FeatureLines
    >>> lines.shape, bool(lines.lines.any())
    ((160, 160), True)
    """

    lines: np.ndarray
    kind: str
    reason: str
    regions: np.ndarray | None = None
    subject: Subject | None = None
    stroke_width: float | None = None
    detail: int | None = None

    @property
    def shape(self) -> tuple[int, int]:
        return (int(self.lines.shape[0]), int(self.lines.shape[1]))


# --------------------------------------------------------------------------- kinds
def detect_kind(image: object) -> tuple[str, str]:
    """Guess the kind of an image: ``(kind, reason)``, the reason one line of what was measured.

    * A **photo** has camera noise and texture everywhere: few of its pixels
      have four neighbours of exactly their colour. A clip art or a drawing is
      made of flat fills, whose pixels do, even after JPEG compression (whose
      flat blocks stay exactly flat): an image is synthetic when at least
      ``SYNTHETIC_FLAT_FRACTION`` of its pixels are such.
    * A synthetic image is a **line drawing** when, beside its background, it
      has one colour only (the ink, any colour: its flat regions' colours are
      within ``INK_COLOUR_SPREAD`` of their mean) drawn in strokes at most
      ``DRAWING_MAX_STROKE_FRACTION`` of the image's shorter side wide;
    * otherwise a **clip art**: several flat colours (a grey animal on white is
      a clip art of greys, not a drawing).

    Measured, as :func:`img2logo.abstract` does, on a copy at most
    ``SYNTHETIC_WORK_SIDE`` px on its longer side (the size these tests were
    chosen at: an upscaled drawing's strokes are ramps that read as a second
    colour at 2048 px), so both tell the same kind.

    Examples
    --------
    >>> import cv2, numpy as np
    >>> image = np.full((160, 160, 3), 255, np.uint8)
    >>> _ = cv2.circle(image, (80, 80), 50, (0, 0, 0), 3)  # a black ring, 50 px round
    >>> from img2logo import detect_kind
    >>> kind, why = detect_kind(image)
    >>> kind
    'drawing'
    """
    kind, reason, _ = detect_kind_and_regions(downscale(load_image(image), SYNTHETIC_WORK_SIDE))
    return kind, reason


def photo_reason(img: LoadedImage) -> str | None:
    """Why ``img`` is a photo (:func:`detect_kind`'s first test: camera noise and texture), or None if it is not one.

    Cheap (one pass over the pixels): the pipeline asks it first, since a
    photo's work is done at ``PHOTO_WORK_SIDE`` (:func:`img2logo.pipeline.abstract`).
    """
    return _photo_reason(img.flat_fraction)


def _photo_reason(flat: float) -> str | None:
    if flat >= SYNTHETIC_FLAT_FRACTION:
        return None
    # A share under 1% would read "only 0%": said as it is.
    share = (
        "no pixel sits"
        if flat == 0.0
        else "under 1% of the pixels sit"
        if flat < 0.01
        else f"only {flat:.0%} of the pixels sit"
    )
    return f"{share} in flat fills (camera noise, texture): a photo"


def detect_kind_and_regions(img: LoadedImage) -> tuple[str, str, np.ndarray | None]:
    """(kind, reason, clip-art regions or None): the regions are reused for a clip art."""
    flat = img.flat_fraction
    reason = _photo_reason(flat)
    if reason is not None:
        return "photo", reason, None
    regions = clipart_regions(img)

    area, means = label_means(regions, img.lab)
    # Paper: the background and the regions of its colour it encloses (inside a wheel).
    paper = np.linalg.norm(means - means[0], axis=1) <= INK_COLOUR_SPREAD
    if paper.all():
        return "clipart", "one flat colour: a clip art", regions
    solid = ~paper
    if not _one_ink(means[solid], area[solid]):
        # Only then: a stroke's rim may be what makes a second colour.
        solid &= ~_rim_regions(regions, img.rgb, means, paper)
    colours = 1 + len(_distinct(means[solid]))
    if _one_ink(means[solid], area[solid]):
        inked = solid[regions]
        stroke = median_stroke_width(inked)
        outlined = _outlined_shapes(inked)
        if outlined is not None:
            return "clipart", outlined, regions
        if stroke <= DRAWING_MAX_STROKE_FRACTION * min(regions.shape):
            return (
                "drawing",
                f"one ink colour on a plain background, {inked.mean():.0%} of the pixels, in strokes about "
                f"{stroke:.0f} px wide: a line drawing",
                None,
            )
        return "clipart", f"one flat colour on a plain background, in shapes {stroke:.0f} px wide: a clip art", regions
    ink = _shaded_ink(regions, img.rgb, means, solid, paper)
    if ink is not None:
        inked = ink[regions]
        stroke = median_stroke_width(inked)
        outlined = _outlined_shapes(inked)
        if outlined is not None:
            return "clipart", outlined, regions
        if stroke <= DRAWING_MAX_STROKE_FRACTION * min(regions.shape):
            share = area[ink].sum() / area[solid].sum()
            return (
                "drawing",
                f"one ink colour with grey shading on a plain background, the ink {share:.0%} of what is drawn, in "
                f"strokes about {stroke:.0f} px wide: a line drawing",
                None,
            )
    return "clipart", f"{flat:.0%} of the pixels sit in flat fills of {colours} colours: a clip art", regions


def _outlined_shapes(ink: np.ndarray) -> str | None:
    """Why the one ink ``ink`` (H, W) bool is outlined shapes, a clip art (:func:`outline_band_width`); else None."""
    band = outline_band_width(ink)
    if band is None or band <= CLIPART_OUTLINE_WIDTH:
        return None
    return (
        f"one ink colour in closed outlines {band:.0f} px wide, each round paper with nothing in it: "
        "outlined shapes, a clip art"
    )


def outline_band_width(ink: np.ndarray) -> float | None:
    """The width of ``ink`` (H, W) bool, px, when it is only closed outlines; None when it is not.

    A speech or thought bubble, a badge, a sticker: shapes filled with the
    paper's colour, each drawn by its outline alone. Their ink is closed bands,
    each round one hole of paper with nothing in it (no ink inside, no second
    hole), every pixel of each within ``OUTLINE_BAND_REACH`` times the bands'
    width of the paper it encloses: no stroke runs off an outline (a balloon's
    string, a stem, an umbrella's handle reaches many widths away). A line
    drawing's strokes end, or enclose other strokes, or part the paper into
    several holes (a wheel's spokes, a face's features); a single ring is
    ambiguous, and its width decides (below).

    The width is the bands' area over their length (the mean of their outer
    and inner edges' lengths: a band's centre line), over all of them.
    :func:`detect_kind` reads the outlines as a clip art's when they are wider
    than ``CLIPART_OUTLINE_WIDTH``: their centre line is then more than 6 px
    (the distance at which sil6 counts a silhouette kept and the segment graph
    merges junctions) from both edges, and stands for neither the shape's
    silhouette nor its fill's edge; a narrower outline's centre line stands for
    both, and the drawing, drawn at its stroke width, is the picture.
    Ink parts smaller than ``MIN_SPECK_AREA`` px are specks and not looked at.
    """
    import cv2

    u8 = without_small_parts(ink, MIN_SPECK_AREA - 1).view(np.uint8)
    contours, hierarchy = cv2.findContours(u8, cv2.RETR_TREE, cv2.CHAIN_APPROX_NONE)
    if hierarchy is None:
        return None
    tree = hierarchy[0]  # (next, previous, first child, parent) per contour
    depth = np.zeros(len(tree), dtype=np.int64)
    for i in range(len(tree)):
        parent = tree[i][3]
        while parent >= 0:
            depth[i] += 1
            parent = tree[parent][3]
    if depth.max() != 1:
        return None  # no hole, or ink inside a hole
    outer = np.flatnonzero(depth == 0)
    holes = np.bincount(tree[depth == 1][:, 3], minlength=len(tree))
    if np.any(holes[outer] != 1):
        return None
    area = sum(cv2.contourArea(c) * (1 if d == 0 else -1) for c, d in zip(contours, depth, strict=True))
    length = sum(cv2.arcLength(c, True) for c in contours) / 2.0
    if length <= 0.0:
        return None
    width = area / length
    # A stroke that runs off an outline (a balloon's string, a stem, a whisker) reaches farther
    # from the paper the outlines enclose than a band's width: a band's every pixel is within it.
    enclosed = np.zeros(u8.shape, dtype=np.uint8)
    cv2.drawContours(enclosed, [c for c, d in zip(contours, depth, strict=True) if d == 1], -1, 1, cv2.FILLED)
    enclosed &= 1 - u8
    reach = cv2.distanceTransform(1 - enclosed, cv2.DIST_L2, cv2.DIST_MASK_PRECISE)[u8 > 0]
    return float(width) if reach.max() <= OUTLINE_BAND_REACH * width else None


def _one_ink(means: np.ndarray, area: np.ndarray) -> bool:
    """Whether the regions' colours (n, 3) CIELAB all lie within ``INK_COLOUR_SPREAD`` of their mean."""
    ink = np.average(means, axis=0, weights=area)
    return bool(np.max(np.linalg.norm(means - ink, axis=1)) <= INK_COLOUR_SPREAD)


def _blends(regions: np.ndarray, rgb: np.ndarray, ink: np.ndarray, paper: np.ndarray) -> np.ndarray:
    """The blends of the paper's colour and the ink's, (65, 3) CIELAB, from the paper (first) to the ink (last).

    ``ink`` and ``paper`` (n,) bool pick the regions of ``regions`` whose mean sRGB colours,
    weighted by area, are mixed: in sRGB, as anti-aliasing and a grey tint of the ink do.
    """
    from ..images.cielab import rgb2lab  # skimage.color.rgb2lab, without importing scipy.linalg

    area, rgb_means = label_means(regions, rgb)  # np.bincount's sums by channel, divided by the areas
    ink_rgb = np.average(rgb_means[ink], axis=0, weights=area[ink])
    paper_rgb = np.average(rgb_means[paper], axis=0, weights=area[paper])
    t = np.linspace(0.0, 1.0, 65)
    return rgb2lab((paper_rgb[None] + t[:, None] * (ink_rgb - paper_rgb)[None])[:, None, :])[:, 0, :]


def _shaded_ink(
    regions: np.ndarray, rgb: np.ndarray, means: np.ndarray, solid: np.ndarray, paper: np.ndarray
) -> np.ndarray | None:
    """The ink's regions of a drawing in one ink with grey shading, (n,) bool; None when the image is not one.

    A pencil or ink drawing is often shaded: a telescope's tube filled grey, a feather's vane
    light grey, a swan's body in bands of grey. Its colours beside the paper are then all
    blends of the paper and the ink, each within ``INK_COLOUR_SPREAD`` of one (:func:`_blends`;
    a black ink's greys: a colour of its own is no shading), the ink being the drawn colour
    farthest from the paper's, and dark (L* at most ``SHADED_INK_MAX_LIGHTNESS``). The regions
    nearer the ink than the paper on that blend are ink, as a threshold halfway between them
    reads it (:func:`_drawing_lines`); the lighter ones are shading. It is such a drawing when
    the ink is more than ``SHADED_INK_SHARE`` of what is drawn (the ``solid`` regions, by
    area): its lines carry it, the shading is an accent. A grey animal with a black outline
    is mostly fill: a clip art of greys.
    """
    drawn = np.flatnonzero(solid)
    if len(drawn) < 2:
        return None
    area = np.bincount(regions.ravel(), minlength=len(means)).astype(np.float64)
    darkest = drawn[np.argmax(np.linalg.norm(means[drawn] - means[0], axis=1))]
    if means[darkest, 0] > SHADED_INK_MAX_LIGHTNESS:
        return None  # no dark ink: light greys on white are a clip art's, or a drawing's in one ink
    blends = _blends(regions, rgb, np.arange(len(means)) == darkest, paper)
    gap = np.linalg.norm(means[drawn][:, None, :] - blends[None, :, :], axis=2)
    if np.any(gap.min(axis=1) > INK_COLOUR_SPREAD):
        return None
    ink = np.zeros(len(means), dtype=bool)
    ink[drawn[np.argmin(gap, axis=1) >= len(blends) // 2]] = True
    return ink if area[ink].sum() > SHADED_INK_SHARE * area[solid].sum() else None


def _rim_regions(regions: np.ndarray, rgb: np.ndarray, means: np.ndarray, paper: np.ndarray) -> np.ndarray:
    """Which regions are an anti-aliased rim of the ink, not a colour: (n,) bool.

    A narrow strip of paper between two strokes, or between a stroke and the
    paper it encloses, is all rim: its pixels blend the ink and the paper and
    none is far from either, so the clip-art regions make it a region of a grey
    of its own (a 9 px erosion of ``data/drawing-bird.png`` has one of 691 px
    at L* 81 between the wing and the body, and is no clip art of 3 colours).
    The ink is the largest region that is not paper and the regions of its
    colour (within ``INK_COLOUR_SPREAD``); another region is a rim when

    * its mean colour is within ``INK_COLOUR_SPREAD`` of a blend (in sRGB, as
      anti-aliasing mixes) of the paper's colour and the ink's;
    * none of its pixels is farther than ``CLIPART_RIM_RADIUS`` px from its
      edge (a rim is a few px wide; a grey fill has an inside);
    * it touches the ink: it is the edge of a stroke, or a gap between two
      strokes pinched shut (a 13 px erosion of the bird has one of 155 px at
      L* 48 enclosed by ink).

    A region at least ``INK_SHARE`` of whose pixels are of the ink's colour
    is ink too, whatever its depth and neighbours: ink with its rims and the
    paper it encloses, too little to seed a region of its own (a small ring of
    a 4 px stroke whose hole is 6 px across, mean L* 30). A grey fill or a grey
    line has none of the ink's colour.

    A grey fill of a clip art is wide; a grey line on the paper touches no ink:
    both stay colours of their own. As soon as one region is neither ink nor
    such a rim the image has a second colour and the rest is not looked at.
    """
    from ..images.cielab import rgb2lab  # skimage.color.rgb2lab, without importing scipy.linalg

    n = len(means)
    out = np.zeros(n, dtype=bool)
    inked = np.flatnonzero(~paper)
    if len(inked) < 2:
        return out
    area = np.bincount(regions.ravel(), minlength=n).astype(np.float64)
    largest = inked[np.argmax(area[inked])]
    ink = ~paper & (np.linalg.norm(means - means[largest], axis=1) <= INK_COLOUR_SPREAD)
    blends = _blends(regions, rgb, ink, paper)
    others = np.flatnonzero(~paper & ~ink)
    if any(np.min(np.linalg.norm(blends - means[r], axis=1)) > INK_COLOUR_SPREAD for r in others):
        return out  # a colour of its own: no rim makes this one ink
    import cv2

    slices = bounding_slices(regions + 1)
    eight = np.ones((3, 3), dtype=np.uint8)
    ink_lab = blends[-1]  # the ink's own colour
    for r in others:
        box = slices[r]
        if box is None:  # no pixel: never, the labels are packed
            continue
        sl = tuple(slice(max(0, s.start - 1), s.stop + 1) for s in box)
        own = regions[sl] == r
        if np.mean(np.linalg.norm(rgb2lab(rgb[sl][own]) - ink_lab, axis=-1) <= INK_COLOUR_SPREAD) >= INK_SHARE:
            out[r] = True  # ink with its rims and the paper it encloses (a small ring), not a grey
            continue
        if distance(np.pad(own, 1)).max() > CLIPART_RIM_RADIUS + 0.5:
            return out
        if not ink[regions[sl][(cv2.dilate(own.view(np.uint8), eight) > 0) & ~own]].any():
            return out
        out[r] = True
    return out


def _distinct(colours: np.ndarray) -> list[np.ndarray]:
    """Colours (N, 3) CIELAB, clustered greedily at ``INK_COLOUR_SPREAD``: one per visible colour."""
    out: list[np.ndarray] = []
    for c in colours:
        if all(np.linalg.norm(c - o) > INK_COLOUR_SPREAD for o in out):
            out.append(c)
    return out


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


# --------------------------------------------------------------------------- feature lines
def extract_feature_lines(
    image: object,
    kind: str = "auto",
    *,
    foreground: object = "auto",
    subject: object = None,
    spur_length: float | None = None,
    min_line_length: float | None = None,
    detail: int = DETAIL,
    arcs: int | None = None,
) -> FeatureLines:
    """Extract the object's feature lines as a 1-px-wide map (paper Sec. 4).

    Parameters
    ----------
    image : path, ndarray or LoadedImage
        The input, read by :func:`load_image`.
    kind : {"auto", "photo", "clipart", "drawing"}
        The kind of input; ``"auto"`` chooses with :func:`detect_kind` and says
        why in the result's ``reason``.
    foreground : {"auto", "none", "grabcut"}, path or ndarray of bool, shape (H, W), optional
        Photos only: the subject whose outline and inner lines are drawn
        (:func:`img2logo.features.photo.subject.find_subject`): found automatically (default;
        an image with transparency uses its alpha), the whole image, GrabCut
        kept whatever it finds, or a mask (white = object). None is ``"auto"``.
    subject : (x, y, w, h) or "X,Y,W,H", optional
        Photos only: a rectangle around the object, px of the input image (before
        any downscale), that seeds GrabCut (:func:`img2logo.features.photo.subject.find_subject`).
    spur_length : float, optional
        Side spurs of the skeleton shorter than this are pruned, px (default
        ``SPUR_LENGTH``; photos ``PHOTO_SPUR_LENGTH``).
    min_line_length : float, optional
        Isolated lines shorter than this are dropped, px (default:
        ``spur_length`` for drawings and clip art, a longer bound for photos,
        whose short lines are mostly texture).
    detail : int
        Clip art only: the regions kept besides the background
        (:func:`img2logo.features.detail.merge_by_importance`; default ``DETAIL``).
    arcs : int or None
        Clip art only: an arc budget, the logo's predicted arcs at most this
        (:func:`img2logo.features.detail.merge_by_importance`; default None: none).

    Returns
    -------
    FeatureLines

    Examples
    --------
    >>> import cv2, numpy as np
    >>> image = np.full((160, 160, 3), 255, np.uint8)
    >>> _ = cv2.circle(image, (80, 80), 50, (0, 0, 0), 3)  # a black ring, 50 px round
    >>> from img2logo import extract_feature_lines
    >>> lines = extract_feature_lines(image)
    >>> lines.kind, lines.lines.shape, lines.lines.dtype
    ('drawing', (160, 160), dtype('bool'))
    """
    img = load_image(image)
    kind = check_choice(kind, "kind", ("auto", *KINDS))
    if spur_length is not None:
        spur_length = check_positive(spur_length, "spur_length", allow_zero=True)
    regions = None
    if kind == "auto":
        kind, reason, regions = detect_kind_and_regions(img)
    else:
        reason = "given"
    found = dots = None
    if spur_length is None:
        spur_length = PHOTO_SPUR_LENGTH if kind == "photo" else SPUR_LENGTH
    radius = stroke = detail_used = None
    budget = 0.0
    if kind == "drawing":
        ink = _drawing_lines(img)
        radius = _half_width(ink)
        axis = skeletonize(ink)
        stroke = float(2.0 * median(radius[axis])) if axis.any() else 0.0
        raw = join_line_ends(axis)
        min_len = spur_length if min_line_length is None else min_line_length
    elif kind == "clipart":
        regions = enclosed_paper(clipart_regions(img) if regions is None else regions, img)
        regions, detail_used, budget = merge_by_importance(
            regions, img.lab, check_detail(detail), arcs=None if arcs is None else check_detail(arcs, "arcs", "arcs")
        )
        raw = _join(clipart_lines(regions, label_means(regions, img.lab)[1][:, 0]))
        min_len = spur_length if min_line_length is None else min_line_length
    else:
        from .photo.line_maps import line_maps, start_photo_line_maps
        from .photo.lines import photo_feature_lines, subject_dots, subject_pupils
        from .photo.subject import find_subject

        found = find_subject(img, foreground, subject, beside=start_photo_line_maps)  # the line maps beside the cuts
        dots = subject_dots(img, found)  # the blob dots, while the line maps may still be under way
        maps = line_maps(img)
        dots = subject_pupils(img, found, maps, dots)  # and the pupils in the lines' closed loops
        raw = photo_feature_lines(img, found, dots, maps)
        min_len = PHOTO_MIN_LINE_LENGTH if min_line_length is None else min_line_length
    min_len = check_positive(min_len, "min_line_length", allow_zero=True)
    lines = _clean_skeleton(raw, spur_length=spur_length, min_length=min_len, radius=radius)
    if kind == "clipart" and regions is not None:  # every line whole: each end joined, or its mark dropped whole
        closed = close_line_ends(lines, regions, img.lab, budget)
        lines = _clean_skeleton(closed, spur_length=spur_length, min_length=min_len)
    if dots is not None and dots.count:  # an eye's outline is shorter than a photo's shortest line
        from .photo.lines import dot_lines

        lines |= dot_lines(raw, dots)
    if found is not None and found.faces:  # a face's eyes and mouth are shorter than a photo's shortest line
        from .photo.lines import face_line_length, face_region

        short = face_line_length(found.faces)
        near_face = face_region(raw.shape, found.faces)
        lines |= _clean_skeleton(raw & near_face, spur_length=min(spur_length, short / 2), min_length=short)
    if kind == "drawing":
        lines = keep_dots(lines, ink, stroke)
    return FeatureLines(
        readonly(lines),
        kind,
        reason,
        None if regions is None else readonly(regions),
        found,
        stroke_width=stroke,
        detail=detail_used,
    )


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
    from skimage.draw import circle_perimeter  # only for a dot (skimage.draw imports scipy)

    out = lines.copy()
    # scipy.ndimage.center_of_mass(ink, labels, bare): the same sums, by label.
    rows, cols = np.indices(ink.shape, dtype=np.float64)
    mass = np.bincount(labels.ravel(), weights=ink.ravel())[bare]
    centres = zip(
        np.bincount(labels.ravel(), weights=(ink * rows).ravel())[bare] / mass,
        np.bincount(labels.ravel(), weights=(ink * cols).ravel())[bare] / mass,
        strict=True,
    )
    for k, (r, c) in zip(bare, centres, strict=True):
        radius = max(DOT_MIN_RADIUS, (diameter[k] - stroke_width) / 2.0)
        rr, cc = circle_perimeter(round(r), round(c), round(radius), shape=out.shape)
        out[rr, cc] = True
    return out


def _join(raw: np.ndarray) -> np.ndarray:
    """Thin a drawing's ink or a clip art's lines and join the ends that stop short of a line.

    A stroke that ends a few px before another (a clip art's whisker by its
    face's outline, a drawing's line that stops at a gap) would give an arc end
    0.75-6 px from another arc: a near-miss gap. :func:`~img2logo.images.line_ends.join_line_ends`
    links it (the same rule as for photos).
    """
    return join_line_ends(skeletonize(raw))


def _clean_skeleton(
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


def _half_width(ink: np.ndarray) -> np.ndarray:
    """The half width of a drawing's strokes at every pixel, px: the ink's distance to the paper.

    Measured on the skeleton, where it is the radius of the stroke's inscribed
    disc; 0 on the paper.
    """
    return distance(ink).astype(np.float32)


def _paper_seams(gray: np.ndarray, ink: np.ndarray) -> np.ndarray:
    """The paper pinched between two strokes that run side by side: (H, W) bool.

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
    depth = distance(ink)
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


def _drawing_lines(img: LoadedImage) -> np.ndarray:
    """Ink of a line drawing: Otsu threshold, specks removed, holes of 1-2 px filled."""
    gray = gaussian_blur(img.gray, 1.0)  # smooths the stroke edges: fewer spurs
    if np.ptp(gray) < BLANK_IMAGE_RANGE:
        return np.zeros(gray.shape, dtype=bool)
    ink = gray < otsu_threshold(gray)
    dark = ink.mean() <= 0.5
    if not dark:  # light strokes on a dark ground
        ink = ~ink
    ink &= ~_paper_seams(img.gray if dark else 1.0 - img.gray, ink)
    ink = without_small_parts(ink, MIN_SPECK_AREA - 1)
    return ~without_small_parts(~ink, MIN_SPECK_AREA // 4)


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
    """
    import cv2

    _, parts, stats, _ = cv2.connectedComponentsWithStats(mask.astype(np.uint8), connectivity=4)
    keep = stats[:, cv2.CC_STAT_AREA] > max_size
    keep[0] = False  # the background
    return keep[parts]
