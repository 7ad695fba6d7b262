"""Fills that face each other across a cartoon's outline stroke: neighbours of the ranking.

In the cartoon style the fills are separated by a network of dark outline
strokes, not by shared borders: a rooster's tail feathers are strips of colour,
each enclosed by the black outline, so no two fills are adjacent in the region
adjacency graph and none could be merged (they touch only the outline, which
is kept whole as the silhouette's ink). A designer reads the outline network
as *lines* (:func:`img2logo.features.clipart.clipart_lines` draws its thin
parts once, along their middle) and the fills as the regions. So:

- **Sides.** Each pixel of a thin part of an ink outline on the paper
  (:func:`img2logo.features.clipart.ink_strokes` of
  :func:`img2logo.features.clipart.outline_strokes` touching the background,
  at most ``CLIPART_OUTLINE_WIDTH`` px wide) is given to the nearest region
  outside the strokes (a distance transform), as ``clipart_lines`` does: the
  border between two sides runs along the stroke's middle.
- **Neighbours across a stroke** (:func:`across_strokes`): two fills whose
  given pixels meet face each other across the stroke; the length of that
  meeting line is their border. :func:`img2logo.features.detail.merge_targets`
  weighs them by Ward's criterion as two adjacent fills, the stroke between
  them being their boundary.
- **Merged, the stroke between them goes** (:func:`open_strokes`): a stroke
  pixel whose nearest side-border (within half an outline's width) is between
  two fills merged into one is painted with that fill, exactly as merging two
  adjacent fills removes their shared boundary. The silhouette (a side-border
  with the paper) and the stroke between fills kept apart stay; a stroke that
  ends inside a fill (a whisker, no side-border near it) stays too, and is
  joined or dropped by :func:`img2logo.features.detail.close_line_ends`.

Arrays are indexed (row, column).
"""

from __future__ import annotations

from typing import NamedTuple

import numpy as np

from .clipart import ink_strokes, nearest_labels, outline_strokes
from .constants import CLIPART_OUTLINE_WIDTH


class StrokeSides(NamedTuple):
    """The strokes of the ink outlines on the paper and the side each pixel is given to.

    ``strokes`` (H, W) bool, the thin parts of those outlines; ``given`` (H, W)
    int, the regions with every stroke pixel given the label of the nearest
    region outside the strokes (the paper included).
    """

    strokes: np.ndarray
    given: np.ndarray


def stroke_sides(
    regions: np.ndarray, lightness: np.ndarray, thin: np.ndarray, on_paper: np.ndarray
) -> StrokeSides | None:
    """The sides of the strokes of the ink outlines on the paper, or None when there are none.

    Parameters
    ----------
    regions : ndarray of int, shape (H, W)
        Region labels, 0 = background.
    lightness : ndarray, shape (n,)
        The regions' mean L*.
    thin : ndarray of int
        The thin regions' labels (:func:`img2logo.features.clipart.thin_regions`).
    on_paper : ndarray of bool, shape (n,)
        The labels that touch the background.
    """
    inks = np.intersect1d(outline_strokes(regions, lightness), np.flatnonzero(on_paper))
    if len(inks) == 0:
        return None
    strokes = ink_strokes(regions, lightness, thin)
    if strokes is None:
        return None
    strokes &= np.isin(regions, inks)
    if not strokes.any():
        return None
    return StrokeSides(strokes, nearest_labels(regions, strokes))


def _side_pairs(sides: StrokeSides) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The 4-adjacent pixel pairs of two stroke pixels given to different sides: (rows, cols, label a, label b)."""
    strokes, given = sides.strokes, sides.given
    rows, cols, first, second = [], [], [], []
    for dr, dc in ((0, 1), (1, 0)):
        h, w = given.shape
        a = (slice(0, h - dr), slice(0, w - dc))
        b = (slice(dr, h), slice(dc, w))
        meet = strokes[a] & strokes[b] & (given[a] != given[b])
        r, c = np.nonzero(meet)
        rows.append(r)
        cols.append(c)
        first.append(given[a][meet])
        second.append(given[b][meet])
    return np.concatenate(rows), np.concatenate(cols), np.concatenate(first), np.concatenate(second)


def across_strokes(sides: StrokeSides, fixed: np.ndarray) -> dict[tuple[int, int], int]:
    """The fills that face each other across a stroke: {(i, j): length of the side-border} for i < j.

    Pairs with a label of ``fixed`` (n,) bool (the background, the ink
    outlines on it) are left out: they take part in no merge.
    """
    _, _, a, b = _side_pairs(sides)
    keep = ~fixed[a] & ~fixed[b]
    lo = np.minimum(a[keep], b[keep]).astype(np.int64)
    hi = np.maximum(a[keep], b[keep]).astype(np.int64)
    n = len(fixed)
    pairs, counts = np.unique(lo * n + hi, return_counts=True)
    return {(int(p // n), int(p % n)): int(c) for p, c in zip(pairs, counts, strict=True)}


def open_strokes(regions: np.ndarray, sides: StrokeSides, target: np.ndarray) -> np.ndarray:
    """``regions`` with the stroke between fills merged into one painted with that fill: (H, W) int.

    A stroke pixel goes to its side (``sides.given``) when the nearest
    side-border (a pixel of two stroke pixels given to different sides) is
    within ``CLIPART_OUTLINE_WIDTH`` / 2 + 1 px and between two labels that
    ``target`` (n,) merges into one, its own among them. The rest of the
    strokes stays ink: the silhouette, the strokes between fills kept apart,
    and a stroke that ends inside a fill, far from any side-border.
    """
    import cv2

    rows, cols, a, b = _side_pairs(sides)
    if len(rows) == 0:
        return regions
    merged = target[a] == target[b]
    if not merged.any():
        return regions
    h, w = regions.shape
    # Each side-border pair marks its first pixel; a pixel of both a merged and a kept border stays.
    border = np.zeros((h, w), dtype=np.int8)  # 0 none, 1 merged, 2 kept
    np.maximum.at(border, (rows, cols), np.where(merged, 1, 2).astype(np.int8))
    free = np.where(border > 0, 0, 255).astype(np.uint8)
    dist, nearest = cv2.distanceTransformWithLabels(free, cv2.DIST_L2, 5, labelType=cv2.DIST_LABEL_PIXEL)
    br, bc = np.nonzero(free == 0)
    kind = np.zeros(int(nearest.max()) + 1, dtype=np.int8)
    group = np.full(len(kind), -1, dtype=np.int64)
    kind[nearest[br, bc]] = border[br, bc]
    group[nearest[br, bc]] = target[sides.given[br, bc]]
    near = nearest[sides.strokes]
    own = target[sides.given[sides.strokes]]
    paint = (kind[near] == 1) & (group[near] == own) & (dist[sides.strokes] <= CLIPART_OUTLINE_WIDTH / 2 + 1)
    out = regions.copy()
    sr, sc = np.nonzero(sides.strokes)
    out[sr[paint], sc[paint]] = sides.given[sr[paint], sc[paint]]
    return out
