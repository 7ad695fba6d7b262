"""The colours of a clip art's pixels (paper Sec. 4): noise, flat areas, mean shift, region means.

The measurements :mod:`img2logo.features.clipart` finds its regions from: the
colour noise that tells a clean image from a compressed one (:func:`colour_noise`),
the mean shift that flattens a compressed one's fills (:func:`mean_shift`), the
largest colour difference in each pixel's window (:func:`lab_spread`) and the
flat areas it gives (:func:`flat_areas`), and the regions' mean colours
(:func:`label_means`).
"""

from __future__ import annotations

import numpy as np

from .._compat import median
from ..images.cielab import srgb_to_lab
from .constants import (
    CLIPART_EDGE_CONTRAST,
    CLIPART_FLAT_RADIUS,
    CLIPART_MIN_CONTRAST,
    CLIPART_SHIFT_RADIUS,
)

#: The offsets whose colour differences :func:`colour_noise` measures: the 4-neighbours.
NOISE_PAIRS = ((0, 1), (1, 0))


def window_pairs() -> list[tuple[int, int]]:
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
        most = lab_spread(lab, list(NOISE_PAIRS))  # squared, until the end
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

    (H, W) float64, the same bits; compiled
    (:func:`img2logo._compiled.front.colour_distance_kernel`: one pass, no
    temporary images).
    """
    from .._compiled import kernels

    return kernels.colour_distance_kernel(lab, np.asarray(colour, dtype=np.float64))


def label_means(labels: np.ndarray, values: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pixel count and mean value of every label: (n,) float64 and (n, C).

    ``labels`` is (H, W) of non-negative ints, ``values`` (H, W, C); n is the
    largest label + 1, and an unused label has count 0 and mean 0.
    """
    from .._compiled import kernels

    flat = labels.ravel()
    chans = values.reshape(len(flat), -1)
    if not len(flat):  # no label: no count, no mean
        return np.zeros(0), np.zeros((0, chans.shape[1]))
    # One pass for every channel, adding as np.bincount does.
    counts, sums = kernels.label_sums_kernel(flat, chans, int(flat.max()) + 1)
    return counts, sums / np.maximum(counts, 1.0)[:, None]


def label_lightness(labels: np.ndarray, lightness: np.ndarray) -> np.ndarray:
    """The median L* of every label, to 0.1: (n,) float64.

    ``labels`` (H, W) non-negative ints, ``lightness`` (H, W) L* in [0, 100]; n is
    the largest label + 1, an unused label 0. The median, not the mean: a thin
    stroke's anti-aliased rim is half its pixels and takes a mean halfway to the
    fills beside it (a cartoon's black outline 3-4 px wide beside dark brown hair:
    mean L* 16, median 0.5). From one histogram per label (scipy's
    ``ndimage.median`` sorts every pixel: 60 times longer on a 512 px image).

    Examples
    --------
    >>> import numpy as np
    >>> labels = np.array([[0, 0, 1, 1, 1]])
    >>> label_lightness(labels, np.array([[50.0, 60.0, 0.0, 0.0, 40.0]]))
    array([50.,  0.])
    """
    flat = np.asarray(labels).ravel()
    if not len(flat):
        return np.zeros(0)
    n = int(flat.max()) + 1
    steps = np.clip(np.rint(np.asarray(lightness, dtype=np.float64).ravel() * 10.0), 0, 1000).astype(np.int64)
    cumulative = np.cumsum(np.bincount(flat * 1001 + steps, minlength=n * 1001).reshape(n, 1001), axis=1)
    return np.argmax(2 * cumulative >= cumulative[:, -1:], axis=1) / 10.0


def mean_shift(rgb: np.ndarray, colour_radius: float) -> tuple[np.ndarray, np.ndarray]:
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
    window's largest squared differences (:func:`lab_spread` of :func:`window_pairs`), if known.
    """
    # Each pair of pixels of a window once, for both its ends: (dr, dc) from one is
    # (-dr, -dc) from the other, and the squared difference is the same number. Beyond
    # the image's edge a window is the edge pixels repeated, pixels of the window
    # already, so the pixels inside the image give its largest difference.
    spread = np.sqrt(lab_spread(lab, window_pairs()) if most is None else most)
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

    Compiled, in one pass (:func:`img2logo._compiled.front.spreads_kernel`).
    """
    from .._compiled import kernels

    both = sorted(set(pairs_a) | set(pairs_b))
    return kernels.spreads_kernel(
        np.ascontiguousarray(lab, dtype=np.float64),
        np.array(both, dtype=np.int64).reshape(-1, 2),
        np.array([p in pairs_a for p in both], dtype=bool),
        np.array([p in pairs_b for p in both], dtype=bool),
    )


def lab_spread(lab: np.ndarray, pairs: list[tuple[int, int]]) -> np.ndarray:
    """Largest squared CIELAB difference of every pixel to the pixels at ``pairs`` (dr, dc) from it and to it.

    (H, W) float32: squared distances in float32 (a third of the time of
    float64), compiled (:func:`img2logo._compiled.front.spreads_kernel` with one set).
    A pair that reaches beyond so small an image counts for no pixel.
    """
    from .._compiled import kernels

    offsets = np.array(pairs, dtype=np.int64).reshape(-1, 2)
    every, none = np.ones(len(offsets), dtype=bool), np.zeros(len(offsets), dtype=bool)
    return kernels.spreads_kernel(np.ascontiguousarray(lab, dtype=np.float64), offsets, every, none)[0]
