"""Fills that face each other across a cartoon's outline stroke: neighbours of the ranking.

In the cartoon style the fills are separated by a network of dark outline
strokes, not by shared borders: a rooster's tail feathers are strips of colour,
each enclosed by the black outline, so no two fills are adjacent in the region
adjacency graph and none could be merged (they touch only the outline, which
is kept whole as the silhouette's ink). A designer reads the outline network
as *lines* (:func:`img2logo.features.clipart_strokes.clipart_lines` draws its thin
parts once, along their middle) and the fills as the regions. So:

- **Sides.** Each pixel of a thin part of an ink outline on the paper
  (:func:`img2logo.features.clipart_strokes.ink_strokes` of
  :func:`img2logo.features.clipart_strokes.outline_strokes` touching the background,
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

from .._compat import intersect1d
from .clipart import nearest_labels
from .clipart_strokes import ink_strokes, outline_strokes
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
        The thin regions' labels (:func:`img2logo.features.clipart_strokes.thin_regions`).
    on_paper : ndarray of bool, shape (n,)
        The labels that touch the background.
    """
    inks = intersect1d(outline_strokes(regions, lightness), np.flatnonzero(on_paper))
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


class Across(NamedTuple):
    """Fills facing each other across a stroke: {(i, j): ...} for i < j.

    ``border``: the length of their side-border, px (4-adjacent pixel pairs);
    ``ink``: the stroke pixels between them (those whose nearest side-border
    is theirs), which merging them paints; ``colour`` (3,) the strokes' mean
    CIELAB colour.
    """

    border: dict[tuple[int, int], int]
    ink: dict[tuple[int, int], int]
    colour: np.ndarray


def across_strokes(sides: StrokeSides, fixed: np.ndarray, lab: np.ndarray) -> Across:
    """The fills that face each other across a stroke, their side-border and the stroke between them.

    Their side-border is longer than ``CLIPART_OUTLINE_WIDTH``: two fills
    that meet only where strokes cross (diagonal squares of a grid) meet along
    about a stroke's width and face each other across no stroke. Pairs with a
    label of ``fixed`` (n,) bool (the background, the ink outlines on it) are
    left out: they take part in no merge. ``lab`` (H, W, 3) the image's
    CIELAB colours.
    """
    rows, cols, a, b = _side_pairs(sides)
    colour = lab[sides.strokes].mean(axis=0)
    keep = ~fixed[a] & ~fixed[b]
    if not keep.any():
        return Across({}, {}, colour)
    n = len(fixed)
    key = np.minimum(a, b).astype(np.int64) * n + np.maximum(a, b)
    pairs, counts = np.unique(key[keep], return_counts=True)
    # Fills that meet only where strokes cross (two diagonal squares of a grid) meet along about
    # a stroke's width: they do not face each other across a stroke.
    border = {
        (int(p // n), int(p % n)): int(c) for p, c in zip(pairs, counts, strict=True) if c > CLIPART_OUTLINE_WIDTH
    }
    nearest = _nearest_border(sides.strokes, rows, cols, key)
    ink_pairs, ink_counts = np.unique(nearest[nearest >= 0], return_counts=True)
    ink = {(int(p // n), int(p % n)): int(c) for p, c in zip(ink_pairs, ink_counts, strict=True)}
    return Across(border, {k: ink.get(k, 0) for k in border}, colour)


def _nearest_border(strokes: np.ndarray, rows: np.ndarray, cols: np.ndarray, key: np.ndarray) -> np.ndarray:
    """For each stroke pixel (row-major order), the key of the nearest side-border pixel within
    ``CLIPART_OUTLINE_WIDTH`` / 2 + 1 px, or -1 (a stroke that ends inside a fill, far from any)."""
    import cv2

    h, w = strokes.shape
    mark = np.full((h, w), -1, dtype=np.int64)
    mark[rows, cols] = key
    free = np.where(mark >= 0, 0, 255).astype(np.uint8)
    dist, nearest = cv2.distanceTransformWithLabels(free, cv2.DIST_L2, 5, labelType=cv2.DIST_LABEL_PIXEL)
    br, bc = np.nonzero(free == 0)
    of = np.full(int(nearest.max()) + 1, -1, dtype=np.int64)
    of[nearest[br, bc]] = mark[br, bc]
    out = of[nearest[strokes]]
    out[dist[strokes] > CLIPART_OUTLINE_WIDTH / 2 + 1] = -1
    return out


def open_strokes(regions: np.ndarray, sides: StrokeSides, target: np.ndarray) -> np.ndarray:
    """``regions`` with the stroke between fills merged into one painted with that fill: (H, W) int.

    A stroke pixel goes to its side (``sides.given``) when the nearest
    side-border (two stroke pixels given to different sides) is within
    ``CLIPART_OUTLINE_WIDTH`` / 2 + 1 px and between two labels that
    ``target`` (n,) merges into one, its own among them. The rest of the
    strokes stays ink: the silhouette, the strokes between fills kept apart,
    and a stroke that ends inside a fill, far from any side-border.
    """
    rows, cols, a, b = _side_pairs(sides)
    if not (target[a] == target[b]).any():
        return regions
    n = len(target)
    key = np.minimum(a, b).astype(np.int64) * n + np.maximum(a, b)
    nearest = _nearest_border(sides.strokes, rows, cols, key)
    sr, sc = np.nonzero(sides.strokes)
    own = target[sides.given[sr, sc]]
    lo, hi = target[np.maximum(nearest, 0) // n], target[np.maximum(nearest, 0) % n]
    paint = (nearest >= 0) & (lo == hi) & (lo == own)
    out = regions.copy()
    out[sr[paint], sc[paint]] = sides.given[sr[paint], sc[paint]]
    return out
