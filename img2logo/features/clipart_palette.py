"""A clip art's palette (paper Sec. 4): seeds, their colours, and every pixel given an entry.

Steps 3 and 4 of :mod:`img2logo.features.clipart`: flat areas large enough are
seeds, pixels that no blend of the seeds near them explains seed colours of their
own (:func:`palette_regions`), and every other pixel takes the nearest entry
among the seeds near it (:func:`near_entries`).
"""

from __future__ import annotations

import numpy as np

from .clipart_colours import label_means
from .constants import (
    CLIPART_BLOCK_REACH,
    CLIPART_EDGE_CONTRAST,
    CLIPART_FILL_SPREAD,
    CLIPART_MIN_REGION_AREA,
    CLIPART_RIM_RADIUS,
    CLIPART_RING_WIDTH,
    CLIPART_SEED_AREA,
)


def palette_regions(
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

    counts, lab_means = label_means(areas, lab)
    rgb_means = label_means(areas, rgb)[1]
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
    # The 4-connected pieces of one entry; a 1 px line drawn without anti-aliasing is a string
    # of pixels touching at their corners: tiny 4-connected pieces that are one 8-connected
    # region. Labelled, joined and packed in one compiled call.
    return kernels.palette_regions_kernel(index, CLIPART_MIN_REGION_AREA), ~rest


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
    if len(pix_rows) * len(offsets) <= _NEAR_PIXEL_WORK * index.size:
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
    singles = rgb2lab(areas_rgb[None])[0]
    if lonely:
        alone = ~near.any(axis=1)
        if alone.any():
            near[alone] = _reached_entries(seed_of, singles, lab, contrast, rest, np.asarray(alone))
    # The distance to the nearest seed's own colour among those near each pixel, compiled.
    best = kernels.nearest_colour_kernel(colours_lab, np.ascontiguousarray(singles, dtype=np.float64), near)
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


def relabel(regions: np.ndarray) -> np.ndarray:
    """Labels 0..n-1 in the order of the (non-negative) values: the used ones, packed; int64.

    ``regions`` (H, W); compiled (:func:`img2logo._compiled.front.relabel_kernel`).
    """
    from .._compiled import kernels

    return kernels.relabel_kernel(regions)
