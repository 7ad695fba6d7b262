"""Feature lines of clip art (paper Sec. 4): boundaries between flat-colour regions.

A clip art is a few flat (or smoothly graded) colours with anti-aliased edges,
possibly compressed. Its regions are found in steps, each with its reason:

1. **Noise.** :func:`~img2logo.features.clipart_colours.colour_noise` tells a clean image (every fill pixel is
   exactly flat or on a visible edge) from a compressed one (many sub-visible
   differences). A compressed image is mean-shift filtered first
   (:func:`~img2logo.features.clipart_colours.mean_shift`), which collapses each fill's noise to its colour and
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
instead of a double boundary (:func:`~img2logo.features.clipart_strokes.thin_regions`).
"""

from __future__ import annotations

import numpy as np

from .._compat import median, unique
from ..images.loading import LoadedImage
from .clipart_colours import (
    NOISE_PAIRS,
    colour_distance,
    colour_noise,
    flat_areas,
    lab_spreads,
    mean_shift,
    window_pairs,
)
from .clipart_palette import palette_regions, relabel
from .constants import (
    CLIPART_LINK_DISTANCE,
    CLIPART_MIN_CONTRAST,
    CLIPART_MIN_REGION_AREA,
    CLIPART_NOISE_FACTOR,
    CLIPART_NOISY_FRACTION,
    CLIPART_SEED_AREA,
)


def clipart_regions(img: LoadedImage) -> np.ndarray:
    """Flat-colour regions of a clip art, (H, W) int labels, 0 = background.

    The background is the region covering most of the image border. See the
    module docstring for the four steps.
    """
    lab = img.lab
    # The noise's and the flat areas' colour differences in one pass (the latter kept for a clean image).
    window_most: np.ndarray | None
    noise_most, window_most = lab_spreads(lab, list(NOISE_PAIRS), window_pairs())
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
        rgb, lab = mean_shift(img.rgb, max(2 * CLIPART_MIN_CONTRAST, CLIPART_NOISE_FACTOR * noise))
        noise, _ = colour_noise(lab)
        window_most = None  # of the filtered colours, below
    link = max(CLIPART_LINK_DISTANCE, CLIPART_NOISE_FACTOR * noise)
    contrast = max(CLIPART_MIN_CONTRAST, CLIPART_NOISE_FACTOR * noise)
    areas = flat_areas(lab, link, most=window_most)
    regions, seeded = palette_regions(areas, rgb, lab, seed_area, contrast, compressed=not clean)
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
    visible edge. Taken after the kind is told (:func:`img2logo.features.kinds.detect_kind`
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
    open_paper[unique(parts[frame & paper])] = True
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
    return relabel(np.where(background & ~opened, np.where(rest, given, piece), regions))


def _background_first(regions: np.ndarray) -> np.ndarray:
    """Relabel so that the region covering most of the image border is 0."""
    border = np.concatenate([regions[0], regions[-1], regions[:, 0], regions[:, -1]])
    bg = int(np.bincount(border).argmax())
    swap = np.arange(int(regions.max()) + 1)
    swap[bg] = 0
    swap[0] = bg  # label 0 was taken: swap
    return relabel(swap[regions])


def border_lengths(regions: np.ndarray, n: int) -> np.ndarray:
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
        border = border_lengths(regions, n)
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
    return relabel(regions)


def nearest_labels(regions: np.ndarray, strokes: np.ndarray) -> np.ndarray:
    """``regions`` with every pixel of ``strokes`` given the label of the nearest pixel outside them: (H, W) int."""
    import cv2

    free = np.where(strokes, 255, 0).astype(np.uint8)  # the zero pixels are the sources
    _, nearest = cv2.distanceTransformWithLabels(free, cv2.DIST_L2, 5, labelType=cv2.DIST_LABEL_PIXEL)
    rows, cols = np.nonzero(free == 0)
    owner = np.zeros(int(nearest.max()) + 1, dtype=regions.dtype)
    owner[nearest[rows, cols]] = regions[rows, cols]
    return np.where(strokes, owner[nearest], regions)


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
