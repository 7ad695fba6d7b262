"""The kind of an image (paper Sec. 4): a photo, a clip art or a line drawing, and why.

Told from what the pixels show (:func:`detect_kind`): camera noise and texture
make a photo; flat fills a synthetic image, a line drawing when it has one ink
(with its anti-aliased rims, or grey shading) drawn in strokes, else a clip art.
A clip art's regions, found on the way, are kept (:func:`detect_kind_and_regions`).
"""

from __future__ import annotations

import numpy as np

from ..constants import SYNTHETIC_WORK_SIDE
from ..images.loading import LoadedImage, downscale, load_image
from ..images.ndimage import bounding_slices, distance
from .clipart import clipart_regions
from .clipart_colours import label_means
from .constants import (
    CLIPART_OUTLINE_WIDTH,
    CLIPART_RIM_RADIUS,
    DRAWING_MAX_STROKE_FRACTION,
    INK_COLOUR_SPREAD,
    INK_SHARE,
    MIN_SPECK_AREA,
    OUTLINE_BAND_REACH,
    SHADED_INK_MAX_LIGHTNESS,
    SHADED_INK_SHARE,
    SYNTHETIC_FLAT_FRACTION,
)
from .drawing_lines import median_stroke_width, without_small_parts


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
    >>> from img2logo import data, detect_kind
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
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
        kind, outlined, stroke = _ink_kind(inked)
        if kind == "clipart":
            return "clipart", outlined, regions
        if kind == "drawing":
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
        kind, outlined, stroke = _ink_kind(inked)
        if kind == "clipart":
            return "clipart", outlined, regions
        if kind == "drawing":
            share = area[ink].sum() / area[solid].sum()
            return (
                "drawing",
                f"one ink colour with grey shading on a plain background, the ink {share:.0%} of what is drawn, in "
                f"strokes about {stroke:.0f} px wide: a line drawing",
                None,
            )
    return "clipart", f"{flat:.0%} of the pixels sit in flat fills of {colours} colours: a clip art", regions


def _ink_kind(ink: np.ndarray) -> tuple[str | None, str, float]:
    """What one ink ``ink`` (H, W) bool draws: (kind, reason, median stroke width px).

    ``"clipart"`` with the reason when it is outlined shapes (:func:`_outlined_shapes`),
    ``"drawing"`` when its strokes are at most ``DRAWING_MAX_STROKE_FRACTION`` of the
    shorter image side, else None (shapes too wide for strokes).
    """
    stroke = median_stroke_width(ink)
    outlined = _outlined_shapes(ink)
    if outlined is not None:
        return "clipart", outlined, stroke
    if stroke <= DRAWING_MAX_STROKE_FRACTION * min(ink.shape):
        return "drawing", "", stroke
    return None, "", stroke


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
    of the ink's colour (within ``INK_COLOUR_SPREAD`` of it) are ink; every other blend, dark
    or light, is shading laid with it. It is such a drawing when the ink is more than
    ``SHADED_INK_SHARE`` of what is drawn (the ``solid`` regions, by area): its lines carry it,
    the shading is an accent. A grey animal or vehicle with a black outline is mostly fill, in
    greys dark and light: a clip art of greys.
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
    ink[drawn[np.linalg.norm(means[drawn] - means[darkest], axis=1) <= INK_COLOUR_SPREAD]] = True
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
