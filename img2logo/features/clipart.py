"""Feature lines of clip art (paper Sec. 4): boundaries between flat-colour regions.

A clip art is a few flat (or smoothly graded) colours with anti-aliased edges,
possibly compressed. Its regions are found in steps, each with its reason:

1. **Noise.** :func:`colour_noise` tells a clean image (every fill pixel is
   exactly flat or on a visible edge) from a compressed one (many sub-visible
   differences). A compressed image is mean-shift filtered first
   (:func:`_mean_shift`), which collapses each fill's noise to its colour and
   keeps the edges where they are.
2. **Flat areas.** A pixel is flat when its whole 3x3 neighbourhood is within
   a *link* distance of it (``CLIPART_LINK_DISTANCE``, half a just noticeable
   difference, or twice the noise of a compressed image); 4-adjacent flat
   pixels are joined. A smooth gradient is one area; an edge, even a subtle
   one, is not crossed, since its rim pixels are never flat.
3. **Seeds and palette.** Flat areas of at least ``CLIPART_SEED_AREA`` px (a
   compressed image: ``CLIPART_MIN_REGION_AREA``, a JPEG block) are seeds; in
   a clean image, pixels that are no blend of the seeds near them are seeds
   too (a 3 px anti-aliased line has no flat pixel). The seeds' mean colours,
   no two closer than the just noticeable difference (``CLIPART_MIN_CONTRAST``,
   CIELAB Delta E 2.3), are the palette: subtle but visible differences (a
   near-white animal on white, Delta E 3-10) keep their own entries.
4. **Assignment.** Every other pixel takes the nearest palette colour among
   the seeds within ``CLIPART_RIM_RADIUS`` px: a rim falls to the side it
   resembles, never to a third colour. The regions are the connected pieces of
   one entry; pieces without a seed pixel (JPEG slivers along an edge) and
   pieces under ``CLIPART_MIN_REGION_AREA`` px are merged into the neighbour
   they share the longest border with.

Region boundaries (the background included) are the feature lines; a *thin*
region (a whisker, a mouth line, an outline stroke: at most
``CLIPART_STROKE_WIDTH`` px wide and much longer than wide) gives its centreline
instead of a double boundary (:func:`thin_regions`).

Arrays are indexed (row, column); points are (x, y) = (column + 0.5, row + 0.5)
in px, x to the right, y downwards (``contract/README.md``).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from .._compat import median
from ..images.cielab import srgb_to_lab
from ..images.loading import LoadedImage
from .constants import (
    CLIPART_BLOCK_REACH,
    CLIPART_EDGE_CONTRAST,
    CLIPART_FILL_SPREAD,
    CLIPART_FLAT_RADIUS,
    CLIPART_INK_BORDER,
    CLIPART_LINK_DISTANCE,
    CLIPART_MIN_CONTRAST,
    CLIPART_MIN_REGION_AREA,
    CLIPART_NOISE_FACTOR,
    CLIPART_NOISY_FRACTION,
    CLIPART_OUTLINE_WIDTH,
    CLIPART_RIM_RADIUS,
    CLIPART_RING_WIDTH,
    CLIPART_SEED_AREA,
    CLIPART_SHIFT_RADIUS,
    CLIPART_STROKE_ELONGATION,
    CLIPART_STROKE_MAX_FACTOR,
    CLIPART_STROKE_WIDTH,
)

#: The offsets whose colour differences :func:`colour_noise` measures: the 4-neighbours.
_NOISE_PAIRS = ((0, 1), (1, 0))


def _window_pairs() -> list[tuple[int, int]]:
    """The offsets of :func:`flat_areas`' window, each pair of its pixels once (see there)."""
    rad = CLIPART_FLAT_RADIUS
    return [(dr, dc) for dr in range(rad + 1) for dc in range(-rad, rad + 1) if dr > 0 or dc > 0]


def colour_noise(lab: np.ndarray, *, most: np.ndarray | None = None) -> tuple[float, float]:
    """Colour noise of a clip art's fills: (typical neighbour difference, noisy fraction).

    Over the pixels that differ visibly (by more than ``CLIPART_MIN_CONTRAST``)
    from the background colour (the median colour of the image border), each
    pixel's largest CIELAB difference to a 4-neighbour is taken. In a clean
    clip art a pixel either sits in an exactly flat fill (0) or on an edge
    (a visible difference); compression noise adds pixels in between.

    Parameters
    ----------
    lab : ndarray, shape (H, W, 3)
        CIELAB colours.

    Returns
    -------
    level : float
        The noise of a compressed image, Delta E: the larger of the median of
        those differences and their median where they are neither 0 nor an edge
        (above ``CLIPART_EDGE_CONTRAST``). The first is the level where noise
        covers the fills; the second where JPEG keeps most 8x8 blocks exactly
        flat and the noise sits between them. About 2-3 for JPEGs of quality
        70. Meaningful for a noisy image only (see ``fraction``): in a clean one
        the differences are edges.
    fraction : float
        The fraction of those pixels whose difference is above 0 but below the
        just noticeable difference: at most 0.02 on clean clip arts, at least
        0.058 on JPEGs of quality 70 (the examples and the evaluation set).

    The background is left out because a white background stays exactly flat
    even in a JPEG and would hide the fills' noise. ``most``: those largest
    squared differences, if known (:func:`lab_spreads`).
    """
    if most is None:
        most = lab_spread(lab, list(_NOISE_PAIRS))  # squared, until the end
    border = np.concatenate([lab[0], lab[-1], lab[:, 0], lab[:, -1]])
    paper = np.array([median(border[:, c]) for c in range(border.shape[1])])  # np.median(border, axis=0)
    fill = colour_distance(lab, paper) > CLIPART_MIN_CONTRAST
    if not fill.any():
        return 0.0, 0.0
    v = np.sqrt(most[fill])
    noisy = v[(v > 0) & (v <= CLIPART_EDGE_CONTRAST)]
    level = max(float(median(v)), float(median(noisy)) if len(noisy) else 0.0)
    return level, float(np.mean((v > 0) & (v <= CLIPART_MIN_CONTRAST)))


def colour_distance(lab: np.ndarray, colour: np.ndarray) -> np.ndarray:
    """``np.linalg.norm(lab - colour, axis=2)``: the distance of every colour of ``lab`` (H, W, 3) to ``colour`` (3,).

    (H, W) float64, the same bits; compiled where the kernels are usable
    (:func:`img2logo._compiled.front.colour_distance_kernel`: one pass, no
    temporary images).
    """
    from .._compiled import kernels

    if kernels.usable():
        return kernels.colour_distance_kernel(lab, np.asarray(colour, dtype=np.float64))
    return np.linalg.norm(lab - colour, axis=2)


def clipart_regions(img: LoadedImage) -> np.ndarray:
    """Flat-colour regions of a clip art, (H, W) int labels, 0 = background.

    The background is the region covering most of the image border. See the
    module docstring for the four steps.
    """
    lab = img.lab
    # The noise's and the flat areas' colour differences in one pass (the latter kept for a clean image).
    window_most: np.ndarray | None
    noise_most, window_most = lab_spreads(lab, list(_NOISE_PAIRS), _window_pairs())
    noise, fraction = colour_noise(lab, most=noise_most)
    # A clean clip art's fills are exactly flat: any flat 3x3 block is a fill. In a
    # compressed one, a flat patch smaller than a JPEG block (8 x 8 px) can be an
    # artefact of one block, so seeds must be as large as a region.
    clean = fraction <= CLIPART_NOISY_FRACTION
    seed_area = CLIPART_SEED_AREA if clean else CLIPART_MIN_REGION_AREA
    rgb = img.rgb
    if clean:
        noise = 0.0  # the differences measured are edges' (a drawing has little fill)
    else:
        rgb, lab = _mean_shift(img.rgb, max(2 * CLIPART_MIN_CONTRAST, CLIPART_NOISE_FACTOR * noise))
        noise, _ = colour_noise(lab)
        window_most = None  # of the filtered colours, below
    link = max(CLIPART_LINK_DISTANCE, CLIPART_NOISE_FACTOR * noise)
    contrast = max(CLIPART_MIN_CONTRAST, CLIPART_NOISE_FACTOR * noise)
    areas = flat_areas(lab, link, most=window_most)
    regions, seeded = _palette_regions(areas, rgb, lab, seed_area, contrast, compressed=not clean)
    # A region without a single seed pixel is made of rims only: a sliver along an
    # edge (JPEG ringing), not a fill.
    rimmed = np.bincount(regions.ravel()[seeded.ravel()], minlength=int(regions.max()) + 1) == 0
    regions = _merge_small_regions(regions, CLIPART_MIN_REGION_AREA, also=rimmed)
    return _background_first(regions)


def enclosed_paper(regions: np.ndarray, img: LoadedImage) -> np.ndarray:
    """A clip art's ``regions`` with the background cut to the paper that reaches the image frame: (H, W) int.

    The object's silhouette is where the paper ends. The paper is the pixels of
    the background region within the least visible difference (Delta E: the
    just noticeable difference ``CLIPART_MIN_CONTRAST``, or twice the colour
    noise of a compressed image, as :func:`clipart_regions` takes it) of its
    colour on the image frame (the median there); the background is the paper
    4-connected to the frame. The background region of the palette can reach
    further: a thin dark outline that no seed explains (a 3 px line in a JPEG
    has no flat pixel and no core) takes the colour of the fill beside it, and
    a white leg inside its outline becomes one region with the paper around it,
    its silhouette lost. Each 4-connected piece of paper enclosed so, of at
    least ``CLIPART_MIN_REGION_AREA`` px, becomes a region of its own (a fill of
    the paper's colour, as its outline encloses it in the input); the other
    pixels of the background region that are not paper (the lost outline, rims)
    go to the nearest of the background and those pieces, so the silhouette
    runs along the outline's middle.

    ``regions`` itself when there is no such piece: a clean clip art's regions
    are connected pieces of one colour, so its background stops at the first
    visible edge. Taken after the kind is told (:func:`img2logo.features.preprocessing.detect_kind`
    reads the paper enclosed by a drawing's ink as paper).

    Parameters
    ----------
    regions : ndarray of int, shape (H, W)
        Labels, 0 = background (:func:`clipart_regions`).
    img : LoadedImage
        The image they were found on.
    """
    import cv2

    lab = img.lab
    noise, fraction = colour_noise(lab)
    contrast = (
        CLIPART_MIN_CONTRAST
        if fraction <= CLIPART_NOISY_FRACTION
        else max(CLIPART_MIN_CONTRAST, CLIPART_NOISE_FACTOR * noise)
    )
    background = regions == 0
    frame = ~frame_interior(regions.shape) & background
    if not frame.any():
        return regions
    on_frame = lab[frame]
    colour = np.array([median(on_frame[:, c]) for c in range(3)])  # np.median(lab[frame], axis=0)
    paper = background & (colour_distance(lab, colour) <= contrast)
    count, parts = cv2.connectedComponents(paper.view(np.uint8), connectivity=4)
    open_paper = np.zeros(count, dtype=bool)
    open_paper[np.unique(parts[frame & paper])] = True
    open_paper[0] = False
    opened = open_paper[parts]
    enclosed = paper & ~opened
    if not enclosed.any():
        return regions
    count, pieces, stats, _ = cv2.connectedComponentsWithStats(enclosed.view(np.uint8), connectivity=4)
    keep = stats[:, cv2.CC_STAT_AREA] >= CLIPART_MIN_REGION_AREA
    keep[0] = False
    if not keep.any():
        return regions
    n = int(regions.max()) + 1
    new_label = np.where(keep, n + np.cumsum(keep) - 1, -1)
    piece = new_label[pieces]
    sources = np.where(opened, 0, piece)  # -1: neither the background nor an enclosed piece
    rest = background & (sources < 0)
    given = nearest_labels(sources, sources < 0)
    return _relabel(np.where(background & ~opened, np.where(rest, given, piece), regions))


def label_means(labels: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pixel count and mean value of every label: (n,) float64 and (n, C).

    ``labels`` is (H, W) of non-negative ints, ``values`` (H, W, C); n is the
    largest label + 1, and an unused label has count 0 and mean 0.
    """
    from .._compiled import kernels

    flat = labels.ravel()
    chans = values.reshape(len(flat), -1)
    if kernels.usable() and len(flat):  # one pass for every channel, adding as np.bincount does
        counts, sums = kernels.label_sums_kernel(flat, chans, int(flat.max()) + 1)
    else:
        counts = np.bincount(flat).astype(np.float64)
        sums = np.stack(
            [np.bincount(flat, weights=chans[:, c], minlength=len(counts)) for c in range(chans.shape[1])], 1
        )
    return counts, sums / np.maximum(counts, 1.0)[:, None]


def _label_means_of_two(labels: np.ndarray, a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, ...]:
    """:func:`label_means` of ``labels`` for two images of values at once: (counts, means of a, means of b).

    One pass over the labels where the kernels are usable
    (:func:`img2logo._compiled.front.label_sums2_kernel`): the same sums.
    """
    from .._compiled import kernels

    flat = labels.ravel()
    if not (kernels.usable() and len(flat)):
        counts, a_means = label_means(labels, a)
        return counts, a_means, label_means(labels, b)[1]
    counts, a_sums, b_sums = kernels.label_sums2_kernel(
        flat, a.reshape(len(flat), -1), b.reshape(len(flat), -1), int(flat.max()) + 1
    )
    scale = np.maximum(counts, 1.0)[:, None]
    return counts, a_sums / scale, b_sums / scale


def _palette_regions(
    areas: np.ndarray, rgb: np.ndarray, lab: np.ndarray, seed_area: int, contrast: float, *, compressed: bool
) -> tuple[np.ndarray, np.ndarray]:
    """Regions from flat-area seeds and a palette of their colours: (H, W) labels, (H, W) seed mask.

    Flat areas of at least ``seed_area`` px are seeds. Their mean colours,
    clustered so that no two entries are closer than ``contrast`` (the largest
    seed first), are the palette. A seed pixel takes its seed's entry; any
    other pixel takes the entry nearest to its colour among the seeds within
    ``CLIPART_RIM_RADIUS`` (a rim is a blend of its two sides, not a third
    colour from elsewhere), as the ground truth of a clip art is made; the
    regions are the connected components of equal entries. A smooth gradient
    is one seed, so it keeps one entry throughout.

    Pixels that are no blend of the seeds near them are a colour of their own
    (:func:`_unexplained_seeds`): in a clean image a line too thin to have flat
    pixels (a 3 px stroke with anti-aliased edges), in a ``compressed`` one a
    small fill that JPEG ringing leaves without a flat pixel (an eye, a horn's
    tip). They seed entries too.
    """
    from .._compiled import kernels
    from ..images.ndimage import components

    counts, lab_means, rgb_means = _label_means_of_two(areas, lab, rgb)
    seeds = np.flatnonzero(counts >= seed_area)
    if len(seeds) == 0:
        seeds = np.array([int(np.argmax(counts))])
    seed_id = np.full(len(counts), -1, dtype=np.int64)
    seed_id[seeds] = np.arange(len(seeds))
    seed_of = seed_id[areas]
    means = lab_means[seeds]
    sizes = counts[seeds]
    groups = _unexplained_seeds(seed_of, rgb_means[seeds], rgb, lab, contrast, seed_area, compressed)
    if groups is not None:
        # Only the groups' pixels (label 0, no group, is never used): the same sums, in the same order.
        at = np.flatnonzero(groups)
        in_group = groups.ravel()[at]
        extra, extra_means = label_means(in_group, lab.reshape(-1, 3)[at])
        keep = np.flatnonzero(extra[1:] > 0) + 1
        new_id = np.full(len(extra), -1, dtype=np.int64)
        new_id[keep] = len(means) + np.arange(len(keep))
        renamed = new_id[in_group]
        np.put(seed_of, at[renamed >= 0], renamed[renamed >= 0])  # seed_of is this function's own array
        means = np.vstack([means, extra_means[keep]])
        sizes = np.concatenate([sizes, extra[keep]])
    entry_of = np.empty(len(means), dtype=np.int64)
    palette: list[np.ndarray] = []
    for i in np.argsort(-sizes, kind="stable"):
        d = [np.linalg.norm(means[i] - p) for p in palette]
        if d and min(d) < contrast:
            entry_of[i] = int(np.argmin(d))
        else:
            entry_of[i] = len(palette)
            palette.append(means[i])
    pal = np.array(palette)
    index = np.append(entry_of, -1)[seed_of]  # a seed's entry; -1 (the last) for the rest
    rest = index < 0
    if rest.any():
        near = near_entries(index, len(pal), rest)
        colours = lab.reshape(-1, 3)[np.flatnonzero(rest)]
        cost = np.full(near.shape, np.inf)
        for e in range(len(pal)):  # the entries near each pixel only (a few of them)
            at = np.flatnonzero(near[:, e])
            cost[at, e] = ((colours[at] - pal[e]) ** 2).sum(axis=1)
        lonely = ~near.any(axis=1)
        cost[lonely] = ((colours[lonely, None, :] - pal[None]) ** 2).sum(axis=2)
        index[rest] = np.argmin(cost, axis=1)
    # A 1 px line drawn without anti-aliasing is a string of pixels touching at
    # their corners: tiny 4-connected pieces that are one 8-connected region.
    if kernels.usable():  # the steps below in one compiled call
        return kernels.palette_regions_kernel(index, CLIPART_MIN_REGION_AREA), ~rest
    regions = components(index, connectivity=1, background=-1)
    tiny = np.bincount(regions.ravel())[regions] < CLIPART_MIN_REGION_AREA
    if tiny.any():
        joined = components(np.where(tiny, index, -1), connectivity=2, background=-1)
        regions = np.where(tiny, joined + regions.max() + 1, regions)
    return _relabel(regions), ~rest


#: :func:`near_entries` looks round each pixel (compiled) while that reads at most this many
#: pixels per pixel of the image; beyond (a JPEG's many rim pixels, the 16 px reach) it dilates
#: each entry's pixels instead. Both give the same answer; this only picks the faster.
_NEAR_PIXEL_WORK = 4


def near_entries(index: np.ndarray, n: int, rest: np.ndarray, radius: int = CLIPART_RIM_RADIUS) -> np.ndarray:
    """For each pixel of ``rest``, which of the ``n`` entries have seed pixels within ``radius`` px: (R, n) bool."""
    import cv2

    from .._compat import nonzero
    from .._compiled import kernels
    from ..images.ndimage import bounding_slices

    size = 2 * radius + 1
    disk = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (size, size))
    h, w = index.shape
    pix_rows, pix_cols = nonzero(rest)
    offsets = np.argwhere(disk) - radius  # the disc is symmetric: a dilation by it reads these
    if kernels.usable() and len(pix_rows) * len(offsets) <= _NEAR_PIXEL_WORK * index.size:
        # Few pixels to answer (a clean clip art's rims): each looks round itself, compiled.
        return kernels.near_kernel(index, pix_rows, pix_cols, n, offsets)
    # Each entry is dilated within its bounding box grown by the radius: nothing
    # farther is near it, and an eye's box is a thousandth of a large image.
    where = np.full(index.shape, -1, dtype=np.int64)
    where[rest] = np.arange(int(rest.sum()))
    near = np.zeros((int(rest.sum()), n), dtype=bool)
    boxes = bounding_slices(index + 1)  # entry e's pixels: label e + 1 (every index < n)
    for e in range(min(n, len(boxes))):
        box = boxes[e]
        if box is None:
            continue
        rows = slice(max(box[0].start - radius, 0), min(box[0].stop + radius, h))
        cols = slice(max(box[1].start - radius, 0), min(box[1].stop + radius, w))
        grown = cv2.dilate((index[rows, cols] == e).view(np.uint8), disk) > 0
        at = where[rows, cols][grown]
        near[at[at >= 0], e] = True
    return near


def _unexplained_seeds(
    seed_of: np.ndarray,
    areas_rgb: np.ndarray,
    rgb: np.ndarray,
    lab: np.ndarray,
    contrast: float,
    seed_area: int,
    compressed: bool,
) -> np.ndarray | None:
    """Seeds of the colours that no blend of the flat seeds explains: (H, W) labels (0 = none), or None.

    A clean image: the 8-connected groups of :func:`_unexplained` pixels of at
    least ``seed_area`` px (a line too thin to have flat pixels).

    A compressed image: a small fill of high contrast (a 10 px eye, black on
    yellow) has no flat pixel, since JPEG rings most in the blocks of its
    strongest edges, and would fall to its surroundings. Its pixels are farther
    than ``CLIPART_EDGE_CONTRAST`` (four just noticeable differences: beyond a
    fill's compression noise, which the mean shift has halved) from every
    blend of the seeds near them (a pixel with no seed near, of the seeds
    within ``CLIPART_BLOCK_REACH`` whose own colour reaches it,
    :func:`_reached_entries`: not the colour of a seed farther away or across
    another colour, or a 12-14 px spot of the colour of larger ones elsewhere
    or nearby would be explained, seed nothing and be merged away as a region
    without a seed pixel). The seeds are
    such pixels more than ``CLIPART_RING_WIDTH`` px from any other (a ringing
    halo or chroma bleeding along an edge is a strip no wider than that and has
    none), in 8-connected groups of at least
    ``CLIPART_SEED_AREA`` px (a 3x3 block, as the flat seeds of a clean image),
    unless their 8-connected part of unexplained pixels is more than
    ``CLIPART_FILL_SPREAD`` times what lies within ``CLIPART_RIM_RADIUS`` px of
    them (thin strokes that cross, not a fill).
    """
    from ..images.ndimage import components

    if not compressed:
        own = _unexplained(seed_of, areas_rgb, rgb, lab, contrast)
        if not own.any():
            return None
        groups = components(own, connectivity=2)
        # Over the unexplained pixels only (a few thousand): the same counts and the same zeros.
        at = np.flatnonzero(own)
        in_group = groups.ravel()[at]
        small = np.bincount(in_group) < seed_area
        small[0] = False
        dropped = small[in_group]
        np.put(groups, at[dropped], 0)
        return groups if not dropped.all() else None
    import cv2

    own = _unexplained(seed_of, areas_rgb, rgb, lab, CLIPART_EDGE_CONTRAST, lonely=True)
    if not own.any():
        return None
    own8 = own.astype(np.uint8)
    core = cv2.distanceTransform(own8, cv2.DIST_L2, cv2.DIST_MASK_PRECISE) > CLIPART_RING_WIDTH
    if not core.any():
        return None
    # A small fill's unexplained pixels are its inside and its rim, near its core; a core in a
    # network of thin strokes (where two 3 px lines of a JPEG drawing cross) is no small fill.
    parts = components(own, connectivity=2)
    size = 2 * CLIPART_RIM_RADIUS + 1
    near = (cv2.dilate(core.astype(np.uint8), np.ones((size, size), np.uint8)) > 0) & own
    spread = np.bincount(parts.ravel()) > CLIPART_FILL_SPREAD * np.bincount(parts[near], minlength=parts.max() + 1)
    core &= ~spread[parts]
    groups = components(core, connectivity=2)
    small = np.bincount(groups.ravel()) < CLIPART_SEED_AREA
    small[0] = False
    groups[small[groups]] = 0
    return groups if groups.any() else None


def _unexplained(
    seed_of: np.ndarray,
    areas_rgb: np.ndarray,
    rgb: np.ndarray,
    lab: np.ndarray,
    contrast: float,
    *,
    lonely: bool = False,
) -> np.ndarray:
    """Non-seed pixels farther than ``contrast`` (Delta E) from every blend of two seeds near them: (H, W) bool.

    Anti-aliasing blends the two sides' colours in sRGB, so the blend is taken
    there (a straight line in sRGB is a curve in CIELAB) and compared in CIELAB.
    ``areas_rgb`` holds the seeds' mean sRGB colours, shape (S, 3). A pixel
    with no seed within ``CLIPART_RIM_RADIUS`` is unexplained, or with
    ``lonely`` compared with the blends of the seeds within
    ``CLIPART_BLOCK_REACH`` whose own colour reaches it (:func:`_reached_entries`;
    unexplained with none).
    """
    from .._compiled import kernels
    from ..images.cielab import rgb2lab  # skimage.color.rgb2lab, without importing scipy.linalg

    rest = seed_of < 0
    out = np.zeros(seed_of.shape, dtype=bool)
    if not rest.any():
        return out
    n = len(areas_rgb)
    near = near_entries(seed_of, n, rest)
    at = np.flatnonzero(rest)  # by index: a third of the time of the mask on (H, W, 3)
    colours, colours_lab = rgb.reshape(-1, 3)[at], lab.reshape(-1, 3)[at]
    best = np.full(len(colours), np.inf)
    singles = rgb2lab(areas_rgb[None])[0]
    if lonely:
        alone = ~near.any(axis=1)
        if alone.any():
            near[alone] = _reached_entries(seed_of, singles, lab, contrast, rest, np.asarray(alone))
    if kernels.usable():  # the loop below, compiled: the same norms, their minimum
        best = kernels.nearest_colour_kernel(colours_lab, np.ascontiguousarray(singles, dtype=np.float64), near)
    else:
        for a in range(n):
            on_a = near[:, a]
            if on_a.any():
                best[on_a] = np.minimum(best[on_a], np.linalg.norm(colours_lab[on_a] - singles[a], axis=1))
    # Only a pixel far from every seed's own colour can be far from every blend: the blends
    # (an sRGB to CIELAB conversion each) are taken for those alone.
    far = np.flatnonzero(best > contrast)
    near, colours, colours_lab, far_best = near[far], colours[far], colours_lab[far], best[far]
    for a in range(n):
        on_a = np.flatnonzero(near[:, a])
        if len(on_a) == 0:
            continue
        # The seeds b > a near some of these pixels: only those pairs have pixels near both.
        for b in np.flatnonzero(near[on_a, a + 1 :].any(axis=0)) + a + 1:
            both = on_a[near[on_a, b]]  # the pixels near both, ascending: the mask's rows
            ab = areas_rgb[b] - areas_rgb[a]
            t = np.clip((colours[both] - areas_rgb[a]) @ ab / max(float(ab @ ab), 1e-12), 0.0, 1.0)
            blend = rgb2lab((areas_rgb[a] + t[:, None] * ab)[:, None, :])[:, 0, :]
            far_best[both] = np.minimum(far_best[both], np.linalg.norm(colours_lab[both] - blend, axis=1))
    best[far] = far_best
    out[rest] = best > contrast
    return out


def _reached_entries(
    seed_of: np.ndarray,
    singles: np.ndarray,
    lab: np.ndarray,
    contrast: float,
    rest: np.ndarray,
    alone: np.ndarray,
) -> np.ndarray:
    """Which seeds explain the ``alone`` pixels of ``rest`` from afar: (A, S) bool, A = ``alone.sum()``.

    A pixel with no seed within ``CLIPART_RIM_RADIUS`` px (inside a JPEG block that
    ringing left without a flat pixel, or a rim that chroma bleeding widened) is
    explained by the seeds within ``CLIPART_BLOCK_REACH`` px whose own colour
    reaches it: the seed's 8-connected part of pixels within ``contrast`` (Delta
    E) of its colour ``singles[s]`` (CIELAB, (S, 3)), its seed pixels included,
    comes within ``CLIPART_RIM_RADIUS`` px of the pixel, as the seed's own pixels
    would for a pixel near it. A seed across pixels of another colour (the paper
    between two spots) does not: a 14 px spot 10 px from a larger one of its
    colour is a fill of its own, not that spot's blurred rim. The parts are
    taken within the box of the seed and the pixels it may explain, grown by the
    reach.
    """
    import cv2

    from .._compat import nonzero

    h, w = seed_of.shape
    n = len(singles)
    within = near_entries(seed_of, n, rest, CLIPART_BLOCK_REACH)[alone]
    out = np.zeros(within.shape, dtype=bool)
    pix_rows, pix_cols = nonzero(rest)
    pix_rows, pix_cols = pix_rows[alone], pix_cols[alone]
    size = 2 * CLIPART_RIM_RADIUS + 1
    disk = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (size, size))
    margin = CLIPART_BLOCK_REACH + CLIPART_RIM_RADIUS
    for s in np.flatnonzero(within.any(axis=0)):
        at = np.flatnonzero(within[:, s])
        rows = slice(max(int(pix_rows[at].min()) - margin, 0), min(int(pix_rows[at].max()) + 1 + margin, h))
        cols = slice(max(int(pix_cols[at].min()) - margin, 0), min(int(pix_cols[at].max()) + 1 + margin, w))
        own = seed_of[rows, cols] == s
        diff = lab[rows, cols] - singles[s]
        colour = own | (np.einsum("ijk,ijk->ij", diff, diff) <= contrast * contrast)
        count, parts = cv2.connectedComponents(colour.view(np.uint8), connectivity=8)
        seeded = np.bincount(parts[own], minlength=count) > 0
        seeded[0] = False
        grown = cv2.dilate(seeded[parts].view(np.uint8), disk) > 0
        out[at, s] = grown[pix_rows[at] - rows.start, pix_cols[at] - cols.start]
    return out


def _mean_shift(rgb: np.ndarray, colour_radius: float) -> tuple[np.ndarray, np.ndarray]:
    """Mean shift filtering (Comaniciu and Meer 2002) of a noisy clip art: sRGB and CIELAB, (H, W, 3) each.

    Each pixel moves to the mode of the colours within ``CLIPART_SHIFT_RADIUS``
    px and ``colour_radius`` (Delta E) of it: a fill's compression noise
    collapses to its colour, while an edge of more contrast than the radius
    stays where it is (a blur would move it). OpenCV's filter works on 8-bit
    CIELAB, whose units are close to Delta E.
    """
    import cv2

    u8 = np.clip(np.round(rgb * 255.0), 0, 255).astype(np.uint8)
    shifted = cv2.pyrMeanShiftFiltering(cv2.cvtColor(u8, cv2.COLOR_RGB2Lab), CLIPART_SHIFT_RADIUS, colour_radius)
    out = cv2.cvtColor(shifted, cv2.COLOR_Lab2RGB) / 255.0
    return out, srgb_to_lab(out)


def flat_areas(lab: np.ndarray, link: float, *, most: np.ndarray | None = None) -> np.ndarray:
    """Connected components of flat pixels: (H, W) labels.

    A pixel is flat when every pixel within ``CLIPART_FLAT_RADIUS`` px of it
    (a square window) is within ``link`` (Delta E) of it; 4-adjacent flat
    pixels are joined. Only flat pixels join, and flatness looks past the next
    pixel: along a shallow anti-aliased or blurred (JPEG) edge the colour changes
    little from one pixel to the next, and joining such pixels would bridge the
    two sides, but across the window such a pixel sees more than ``link`` of
    the edge's contrast. Every other pixel is an area of its own. ``most``: the
    window's largest squared differences (:func:`lab_spread` of :func:`_window_pairs`), if known.
    """
    # Each pair of pixels of a window once, for both its ends: (dr, dc) from one is
    # (-dr, -dc) from the other, and the squared difference is the same number. Beyond
    # the image's edge a window is the edge pixels repeated, pixels of the window
    # already, so the pixels inside the image give its largest difference.
    spread = np.sqrt(lab_spread(lab, _window_pairs()) if most is None else most)
    flat = spread <= link
    # Adjacent flat pixels are within the link of each other by definition, so the
    # flat areas are the 4-connected components of the flat mask; every other pixel
    # is an area of its own (labels after the components').
    from ..images.ndimage import components

    labels = components(flat, connectivity=1)
    n = int(labels.max())
    rest = ~flat
    labels[rest] = n + 1 + np.arange(int(rest.sum()))
    return labels - 1


def lab_spreads(
    lab: np.ndarray, pairs_a: list[tuple[int, int]], pairs_b: list[tuple[int, int]]
) -> tuple[np.ndarray, np.ndarray]:
    """:func:`lab_spread` of ``lab`` for two sets of offsets: two (H, W) float32, the same bits.

    Compiled, in one pass (:func:`img2logo._compiled.front.spreads_kernel`), where the kernels are usable.
    """
    from .._compiled import kernels

    if not kernels.usable():
        return lab_spread(lab, pairs_a), lab_spread(lab, pairs_b)
    both = sorted(set(pairs_a) | set(pairs_b))
    return kernels.spreads_kernel(
        np.ascontiguousarray(lab, dtype=np.float64),
        np.array(both, dtype=np.int64).reshape(-1, 2),
        np.array([p in pairs_a for p in both], dtype=bool),
        np.array([p in pairs_b for p in both], dtype=bool),
    )


def lab_spread(lab: np.ndarray, pairs: list[tuple[int, int]]) -> np.ndarray:
    """Largest squared CIELAB difference of every pixel to the pixels at ``pairs`` (dr, dc) from it and to it.

    (H, W) float32. Squared distances in float32 (a third of the time of
    float64); compiled (:func:`img2logo._compiled.front.spreads_kernel` with one set, the
    same bits) where the kernels are usable, else the numpy below.
    """
    from .._compiled import kernels

    h, w = lab.shape[:2]
    if kernels.usable():
        offsets = np.array(pairs, dtype=np.int64).reshape(-1, 2)
        every, none = np.ones(len(offsets), dtype=bool), np.zeros(len(offsets), dtype=bool)
        return kernels.spreads_kernel(np.ascontiguousarray(lab, dtype=np.float64), offsets, every, none)[0]
    lab32 = lab.astype(np.float32)
    most = np.zeros((h, w), dtype=np.float32)
    for dr, dc in pairs:
        if dr >= h or abs(dc) >= w:
            continue  # no such pair in so small an image
        here = (slice(0, h - dr), slice(max(0, -dc), w - max(0, dc)))
        there = (slice(dr, h), slice(max(0, dc), w - max(0, -dc)))
        diff = lab32[there] - lab32[here]
        d = np.einsum("ijk,ijk->ij", diff, diff)
        np.maximum(most[here], d, out=most[here])
        np.maximum(most[there], d, out=most[there])
    return most


def _background_first(regions: np.ndarray) -> np.ndarray:
    """Relabel so that the region covering most of the image border is 0."""
    border = np.concatenate([regions[0], regions[-1], regions[:, 0], regions[:, -1]])
    bg = int(np.bincount(border).argmax())
    swap = np.arange(int(regions.max()) + 1)
    swap[bg] = 0
    swap[0] = bg  # label 0 was taken: swap
    return _relabel(swap[regions])


def thin_regions(regions: np.ndarray, lightness: np.ndarray | None = None) -> np.ndarray:
    """Labels of the thin regions: strokes drawn as filled shapes.

    A region (not the background) is thin when its typical width, twice the
    median distance from its medial axis to its edge, is at most
    ``CLIPART_STROKE_WIDTH`` px and its medial axis is at least
    ``CLIPART_STROKE_ELONGATION`` times longer than that width: a whisker or
    an outline, not a dot.

    An **ink outline** (:func:`ink_outlines`, given the regions' mean L*
    ``lightness`` (n,)), a region darker than what it touches, is a stroke up
    to ``CLIPART_OUTLINE_WIDTH`` px wide: the cartoon style's dark line between
    lighter fills, drawn once along its centre as a drawing's stroke is, not as
    two edges.

    Returns
    -------
    ndarray of int
        The labels, sorted.
    """
    from .._compiled import kernels
    from ..images.ndimage import bounding_slices, skeletonize

    # The distance to the nearest other region: pad with -1 so that the image
    # frame is an edge too.
    depth = kernels.region_depth_kernel(regions)  # the edges and their distance (ndimage.distance's) in one call
    dist = depth[1:-1, 1:-1] + 0.5
    out = []
    n = int(regions.max()) + 1
    widest = np.full(n, CLIPART_STROKE_WIDTH)
    if lightness is not None:
        widest[ink_outlines(regions, lightness)] = CLIPART_OUTLINE_WIDTH
    slices = bounding_slices(regions + 1)
    for label in range(1, n):
        sl = slices[label] if label < len(slices) else None
        if sl is None:
            continue
        inside = regions[sl] == label
        local = dist[sl][inside]
        # A stroke is thin everywhere: a region with a wide part (a balloon on its
        # string) keeps its outline.
        if 2.0 * local.max() > CLIPART_STROKE_MAX_FACTOR * widest[label]:
            continue
        axis = skeletonize(inside)
        if not axis.any():
            continue
        width = 2.0 * float(median(dist[sl][axis]))
        if width <= widest[label] and axis.sum() >= CLIPART_STROKE_ELONGATION * width:
            out.append(label)
    return np.array(out, dtype=np.int64)


def ink_outlines(
    regions: np.ndarray, lightness: np.ndarray, *, paper: bool = True, contrast: float = CLIPART_EDGE_CONTRAST
) -> np.ndarray:
    """Labels of the ink outlines: regions darker than what they touch, sorted.

    A region is one when at least ``CLIPART_INK_BORDER`` of its border (in
    pixel pairs) is with regions lighter by ``contrast`` (L*, default
    ``CLIPART_EDGE_CONTRAST``; ``lightness`` (n,) the regions' mean): a cartoon's outline runs between
    lighter fills, and touches the odd dark detail (a pupil, a dark shading)
    along a little of its length. The background is none. Without ``paper``
    the border with the background does not count: a dark mark on the
    object's lighter fills (an eye, a spot, an inner outline), and not a dark
    shape alone on the paper.
    """
    n = int(regions.max()) + 1
    border = _border_lengths(regions, n).astype(np.float64)
    if not paper:
        border[:, 0] = 0.0
    lighter = lightness[None, :] - lightness[:, None] >= contrast  # [i, j]: j lighter than i
    share = (border * lighter).sum(axis=1) / np.maximum(border.sum(axis=1), 1.0)
    dark = share >= CLIPART_INK_BORDER
    dark[0] = False
    return np.flatnonzero(dark)


def clipart_lines(regions: np.ndarray, lightness: np.ndarray | None = None) -> np.ndarray:
    """A clip art's line map before thinning: region boundaries, and strokes drawn once.

    Thin regions (:func:`thin_regions`) are given to the neighbour they share
    the longest border with before the boundaries are taken, and their pixels
    are added to the map, so that thinning turns each into its centreline,
    joined to the boundaries it touches.

    With ``lightness`` (n,), the regions' mean L*, the **ink outlines** are
    drawn once, as a drawing's strokes (:func:`ink_strokes`: the thin ink
    regions and the thin parts of the others, a cartoon's outline network).
    Each of their pixels is given to the region nearest to it, so that the
    boundary between a stroke's two sides runs along its middle; the pixels
    are added to the map (a stroke that ends inside a fill, a whisker, keeps its
    end here; :func:`img2logo.features.detail.close_line_ends` joins it or drops
    it later). On the silhouette the stroke is the silhouette's line: a stroke pixel
    within ``CLIPART_OUTLINE_WIDTH`` px of both the background and a fill of the
    object goes to the nearest region of the object and is not added, so the
    line runs along the outline's outer edge, where the object ends. A line on
    the paper alone (a whisker beside the face) is drawn along its middle.

    Returns
    -------
    ndarray of bool, shape (H, W)
    """
    strokes = None
    thin = thin_regions(regions, lightness)
    if lightness is not None:
        strokes = ink_strokes(regions, lightness, thin)
        thin = np.setdiff1d(thin, ink_outlines(regions, lightness))
    if len(thin) == 0 and strokes is None:
        return region_boundaries(regions)
    drawn = np.isin(regions, thin)
    n = int(regions.max()) + 1
    border = _border_lengths(regions, n)
    target = np.arange(n)
    for label in thin:
        row = border[label].astype(np.float64)
        row[thin] = 0.0  # into a region that stays, never into another stroke
        if row.max() > 0:
            target[label] = int(np.argmax(row))
    merged = target[regions]
    if strokes is not None:
        import cv2

        paper = merged == 0
        fill = ~paper & ~strokes

        def within(mask: np.ndarray) -> np.ndarray:  # the pixels within an outline's width of ``mask``
            return cv2.distanceTransform((~mask).astype(np.uint8), cv2.DIST_L2, 5) <= CLIPART_OUTLINE_WIDTH

        # An outline between the paper and a fill of the object; a line on the paper alone is drawn as it is.
        near_paper = strokes & within(paper) & within(fill) if fill.any() else np.zeros_like(strokes)
        far = strokes & ~near_paper
        given = merged
        if far.any():  # the nearest region of any kind: the boundary runs along the stroke's middle
            given = np.where(far, nearest_labels(merged, strokes), given)
        if near_paper.any():  # the nearest region of the object: the line runs along the silhouette
            given = np.where(near_paper, nearest_labels(merged, strokes | paper), given)
        merged = given
        drawn |= far
    return region_boundaries(merged) | (drawn & frame_interior(regions.shape))


def ink_strokes(regions: np.ndarray, lightness: np.ndarray, thin: np.ndarray) -> np.ndarray | None:
    """The pixels of the ink outlines drawn as strokes: (H, W) bool, or None if there are none.

    The :func:`ink_outlines` among the ``thin`` regions, whole, and the thin
    parts of the other ink outlines: their pixels that no disc ``CLIPART_OUTLINE_WIDTH`` + 1 px
    across inside them covers (:func:`_ink_parts`).
    """
    inks = ink_outlines(regions, lightness)
    out = np.isin(regions, np.intersect1d(thin, inks))
    for _, sl, part in _ink_parts(regions, np.setdiff1d(inks, thin)):
        out[sl] |= part
    return out if out.any() else None


def outline_strokes(regions: np.ndarray, lightness: np.ndarray) -> np.ndarray:
    """Labels of the ink outlines drawn as strokes: thin regions, or at least half thin parts; sorted.

    :func:`ink_outlines` that are :func:`thin_regions` whole, or whose
    thin parts (:func:`ink_strokes`) hold at least half their pixels (a cartoon's outline
    network with a few wider blobs); a dark fill (a black disc) is none.
    """
    inks = ink_outlines(regions, lightness)
    thin = np.intersect1d(thin_regions(regions, lightness), inks)
    area = np.bincount(regions.ravel())
    mostly = [
        label for label, _, part in _ink_parts(regions, np.setdiff1d(inks, thin)) if 2 * part.sum() >= area[label]
    ]
    return np.union1d(thin, np.array(mostly, dtype=np.int64))


def _ink_parts(regions: np.ndarray, labels: np.ndarray) -> Iterator[tuple[int, tuple[slice, slice], np.ndarray]]:
    """(label, box, thin part within the box) of each of ``labels``.

    The thin part of a region: its pixels that no disc ``CLIPART_OUTLINE_WIDTH``
    + 1 px across inside it covers (what a morphological opening by that disc
    removes, Soille 2003, Sec. 4.4), in 8-connected pieces of at least
    ``CLIPART_MIN_REGION_AREA`` px (a wide blob's corners are not covered
    either, but are a few px each) and at least ``CLIPART_STROKE_ELONGATION``
    times longer than wide (a dot, an eye, is no stroke).
    """
    import cv2

    from ..images.ndimage import bounding_slices

    if len(labels) == 0:
        return
    size = int(CLIPART_OUTLINE_WIDTH) + 1
    disc = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (size, size))
    slices = bounding_slices(regions + 1)
    h, w = regions.shape
    for label in labels:
        box = slices[label]
        if box is None:
            continue
        sl = (
            slice(max(0, box[0].start - size), min(box[0].stop + size, h)),
            slice(max(0, box[1].start - size), min(box[1].stop + size, w)),
        )
        own = (regions[sl] == label).astype(np.uint8)
        part = own.astype(bool) & (cv2.morphologyEx(own, cv2.MORPH_OPEN, disc) == 0)
        count, pieces, stats, _ = cv2.connectedComponentsWithStats(part.view(np.uint8), connectivity=8)
        # A stroke, not a dot: at least CLIPART_STROKE_ELONGATION times longer than wide (its
        # area over its width, twice its largest inner distance), as thin_regions asks.
        depth = cv2.distanceTransform(part.view(np.uint8), cv2.DIST_L2, 5)
        half = np.zeros(count)
        np.maximum.at(half, pieces.ravel(), depth.ravel())
        area = stats[:, cv2.CC_STAT_AREA]
        keep = (area >= CLIPART_MIN_REGION_AREA) & (area >= CLIPART_STROKE_ELONGATION * (2.0 * half) ** 2)
        keep[0] = False
        yield int(label), sl, keep[pieces]


def nearest_labels(regions: np.ndarray, strokes: np.ndarray) -> np.ndarray:
    """``regions`` with every pixel of ``strokes`` given the label of the nearest pixel outside them: (H, W) int."""
    import cv2

    free = np.where(strokes, 255, 0).astype(np.uint8)  # the zero pixels are the sources
    _, nearest = cv2.distanceTransformWithLabels(free, cv2.DIST_L2, 5, labelType=cv2.DIST_LABEL_PIXEL)
    rows, cols = np.nonzero(free == 0)
    owner = np.zeros(int(nearest.max()) + 1, dtype=regions.dtype)
    owner[nearest[rows, cols]] = regions[rows, cols]
    return np.where(strokes, owner[nearest], regions)


def _border_lengths(regions: np.ndarray, n: int) -> np.ndarray:
    """(n, n) counts of 4-adjacent pixel pairs between each two labels."""
    pairs = []
    for a, b in ((regions[:, :-1], regions[:, 1:]), (regions[:-1], regions[1:])):
        diff = a != b
        pairs.append(np.column_stack([a[diff], b[diff]]))
        pairs.append(np.column_stack([b[diff], a[diff]]))
    edges = np.vstack(pairs)
    return np.bincount(edges[:, 0] * n + edges[:, 1], minlength=n * n).reshape(n, n)


def _merge_small_regions(regions: np.ndarray, min_area: int, also: np.ndarray | None = None) -> np.ndarray:
    """Merge regions smaller than ``min_area``, and the labels flagged in ``also``, into a neighbour.

    Each goes to the neighbour it shares the longest border with, preferably one
    that stays.
    """
    regions = regions.copy()
    for _ in range(8):  # a few passes: a merged sliver can enable the next
        areas = np.bincount(regions.ravel())
        weak = (areas > 0) & (areas < min_area)
        if also is not None:
            weak[: len(also)] |= also[: len(weak)] & (areas[: len(also)] > 0)
            also = None  # labels change below; later passes look at sizes only
        small = np.flatnonzero(weak)
        if len(small) == 0:
            break
        n = len(areas)
        border = _border_lengths(regions, n)
        target = np.arange(n)
        for r in small[np.argsort(areas[small], kind="stable")]:
            row = border[r].astype(np.float64)
            row[small] = row[small] * 1e-3  # prefer merging into a large region
            if row.max() > 0:
                target[r] = int(np.argmax(row))
        for r in small:  # follow chains of merges to their end
            t = r
            for _ in range(n):
                if target[t] == t:
                    break
                t = target[t]
            target[r] = t
        regions = target[regions]
    return _relabel(regions)


def _relabel(regions: np.ndarray) -> np.ndarray:
    """Labels 0..n-1 in the order of the (non-negative) values: the used ones, packed; int64.

    Compiled where the kernels are usable (:func:`img2logo._compiled.front.relabel_kernel`).
    """
    from .._compiled import kernels

    if kernels.usable() and regions.ndim == 2:
        return kernels.relabel_kernel(regions)
    used = np.bincount(regions.ravel()) > 0
    return (np.cumsum(used) - 1)[regions].astype(np.int64)


def region_boundaries(regions: np.ndarray) -> np.ndarray:
    """Boundaries between regions as a thin map (thinned to 1 px by the caller)."""
    # skimage.segmentation.find_boundaries(regions, connectivity=1, mode="inner"):
    # a labelled pixel whose 4-neighbourhood holds another label, by OpenCV (exact
    # on float64 labels) rather than importing skimage.morphology (0.1 s a run).
    import cv2

    values = regions.astype(np.float64)
    cross = cv2.getStructuringElement(cv2.MORPH_CROSS, (3, 3))
    edge = cv2.dilate(values, cross) != cv2.erode(values, cross)
    return edge & (regions != 0) & frame_interior(regions.shape)


def frame_interior(shape: tuple[int, int]) -> np.ndarray:
    """Everything but the 1-px image frame, where a region edge is no feature."""
    out = np.zeros(shape, dtype=bool)
    out[1:-1, 1:-1] = True
    return out
