"""Feature lines of clip art (paper Sec. 4): boundaries between flat-colour regions.

The image is split into flat-colour regions (a quantized palette, connected
regions, small regions merged into a neighbour); the boundaries between
regions, the background included, are the feature lines, and where three or
more regions meet is a junction.

Arrays are indexed (row, column); points are (x, y) = (column + 0.5, row + 0.5)
in px, x to the right, y downwards (``contract/README.md``).
"""

from __future__ import annotations

import numpy as np

from .constants import CLIPART_COLOR_DISTANCE, CLIPART_MIN_REGION_AREA
from .loading import LoadedImage


def clipart_regions(img: LoadedImage) -> np.ndarray:
    """Flat-colour regions of a clip art, (H, W) int labels, 0 = background.

    A palette is built from the most frequent colours (quantized), merging
    entries closer than ``CLIPART_COLOR_DISTANCE`` in CIELAB; each pixel takes
    the entry nearest to its quantized colour; connected regions smaller than
    ``CLIPART_MIN_REGION_AREA`` (anti-aliased rims, specks) are merged into the
    neighbouring region they share the longest border with.
    """
    from skimage.color import rgb2lab
    from skimage.measure import label

    lab = rgb2lab(img.rgb)
    transparent = ~img.foreground
    # Quantize to 4 units of L*, a*, b* and pack into one integer key: a
    # bincount over keys is far faster than np.unique(axis=0) over rows.
    flat = lab.reshape(-1, 3)
    quant = np.clip(np.round(flat / 4.0).astype(np.int64) + np.array([0, 40, 40]), 0, 80)
    key = quant @ np.array([81 * 81, 81, 1])
    counts = np.bincount(key, minlength=81**3)
    sums = np.stack([np.bincount(key, weights=flat[:, c], minlength=81**3) for c in range(3)], axis=1)
    used = np.flatnonzero(counts)
    order = used[np.argsort(-counts[used], kind="stable")]
    palette: list[np.ndarray] = []
    for k in order:
        if counts[k] < CLIPART_MIN_REGION_AREA:
            break
        mean = sums[k] / counts[k]
        if all(np.linalg.norm(mean - p) >= CLIPART_COLOR_DISTANCE for p in palette):
            palette.append(mean)
    if not palette:
        palette = [lab.reshape(-1, 3).mean(axis=0)]
    # Each pixel takes the entry nearest to the mean colour of its quantized
    # cell: one lookup per distinct cell (a few thousand), not per pixel.
    pal = np.array(palette)
    means = sums[used] / counts[used, None]
    lut = np.zeros(81**3, dtype=np.int64)
    lut[used] = np.argmin(((means[:, None, :] - pal[None]) ** 2).sum(axis=2), axis=1)
    index = lut[key].reshape(lab.shape[:2])
    index[transparent] = -1
    regions = label(index, background=-2, connectivity=1)
    regions = _merge_small_regions(regions, CLIPART_MIN_REGION_AREA)
    # The background is the region covering most of the image border.
    border = np.concatenate([regions[0], regions[-1], regions[:, 0], regions[:, -1]])
    bg = np.bincount(border).argmax()
    out = regions.copy()
    out[regions == bg] = 0
    out[(regions != bg) & (regions == 0)] = bg  # label 0 was taken: swap
    return _relabel(out)


def _merge_small_regions(regions: np.ndarray, min_area: int) -> np.ndarray:
    """Merge regions smaller than ``min_area`` into their longest-bordering neighbour."""
    regions = regions.copy()
    for _ in range(8):  # a few passes: a merged sliver can enable the next
        areas = np.bincount(regions.ravel())
        small = np.flatnonzero((areas > 0) & (areas < min_area))
        if len(small) == 0:
            break
        pairs = []
        for a, b in ((regions[:, :-1], regions[:, 1:]), (regions[:-1], regions[1:])):
            diff = a != b
            pairs.append(np.column_stack([a[diff], b[diff]]))
            pairs.append(np.column_stack([b[diff], a[diff]]))
        edges = np.vstack(pairs)
        n = len(areas)
        border = np.bincount(edges[:, 0] * n + edges[:, 1], minlength=n * n).reshape(n, n)
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
    """Labels 0..n-1 in order of first appearance of the sorted unique values."""
    _, inv = np.unique(regions, return_inverse=True)
    return inv.reshape(regions.shape).astype(np.int64)


def region_boundaries(regions: np.ndarray) -> np.ndarray:
    """Boundaries between regions as a thin map (thinned to 1 px by the caller)."""
    from skimage.segmentation import find_boundaries

    return find_boundaries(regions, connectivity=1, mode="inner") & _interior(regions.shape)


def _interior(shape: tuple[int, int]) -> np.ndarray:
    """Everything but the 1-px image frame, where a region edge is no feature."""
    out = np.zeros(shape, dtype=bool)
    out[1:-1, 1:-1] = True
    return out
