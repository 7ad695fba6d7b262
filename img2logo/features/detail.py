"""Detail by importance: which regions of a clip art a logo keeps.

A designer's logo of a clip art is its silhouette and the few inner lines that
make the object read; hatching, highlights, texture blotches and tiny fills are
left out. :func:`merge_by_importance` ranks a clip art's regions
(:func:`img2logo.features.clipart.clipart_regions`) so and merges the least
important into their neighbours, before the feature lines are taken.

The ranking is Ward's criterion on the region adjacency graph (Ward 1963;
Beaulieu and Goldberg 1989, hierarchical segmentation): merging two adjacent
regions i and j of areas a_i, a_j and mean CIELAB colours c_i, c_j replaces
both by their mean colour, which adds

    Delta_ij = a_i a_j / (a_i + a_j) * |c_i - c_j|^2

to the picture's squared colour error: the weight of the boundary between them,
which grows with its contrast and with the areas it separates (a thin region's
area is its length times its width, so a long line weighs more than a short
one of its contrast). The cheapest merge is done first, and the merged region's
weights are taken anew, until ``detail`` regions are left besides the
background: the weightiest.

Never merged: the background (label 0, the region that covers most of the
image's frame), so the **silhouette** is kept whole, whatever its contrast; an
ink outline on it (the cartoon style's outer outline); and, at the detail
asked, the dark marks on the object's fills (an eye, a pupil, a spot).

Arrays are indexed (row, column).
"""

from __future__ import annotations

import heapq

import numpy as np

from ..errors import InvalidParameterError
from .clipart import ink_outlines, label_means, outline_strokes, thin_regions
from .constants import CLIPART_MARK_CONTRAST, CLIPART_MAX_REGIONS


def check_detail(value: object) -> int:
    """The ``detail`` option checked: a whole number of regions, at least 1, as int.

    Raises
    ------
    InvalidParameterError
        For anything else (a bool, a string, a fraction, 0 or less).
    """
    if isinstance(value, bool | np.bool_ | str) or not isinstance(value, int | float | np.integer | np.floating):
        raise InvalidParameterError(f"detail must be a whole number of regions, at least 1, got {value!r}")
    v = float(value)
    if not (np.isfinite(v) and v >= 1.0 and v == int(v)):
        raise InvalidParameterError(f"detail must be a whole number of regions, at least 1, got {value!r}")
    return int(v)


def region_adjacency(regions: np.ndarray) -> dict[tuple[int, int], int]:
    """The region adjacency graph: {(i, j): border length} for i < j, in 4-adjacent pixel pairs.

    ``regions`` (H, W) non-negative int labels.
    """
    n = int(regions.max()) + 1
    keys = []
    for a, b in ((regions[:, :-1], regions[:, 1:]), (regions[:-1], regions[1:])):
        diff = a != b
        lo = np.minimum(a[diff], b[diff]).astype(np.int64)
        hi = np.maximum(a[diff], b[diff]).astype(np.int64)
        keys.append(lo * n + hi)
    flat = np.concatenate(keys) if keys else np.zeros(0, dtype=np.int64)
    pairs, counts = np.unique(flat, return_counts=True)
    return {(int(p // n), int(p % n)): int(c) for p, c in zip(pairs, counts, strict=True)}


class DetailWarning(UserWarning):
    """A clip art had more regions than the optimization takes at once: its detail was coarsened."""


def merge_by_importance(
    regions: np.ndarray, lab: np.ndarray, detail: int, *, max_regions: int = CLIPART_MAX_REGIONS
) -> tuple[np.ndarray, int]:
    """Merge a clip art's least important regions into their neighbours: (H, W) int labels, 0 = background.

    Parameters
    ----------
    regions : ndarray of int, shape (H, W)
        Flat-colour regions, 0 = background (:func:`img2logo.features.clipart.clipart_regions`).
    lab : ndarray, shape (H, W, 3)
        The image's CIELAB colours.
    detail : int
        The regions kept besides the background (module docstring), at least
        1; the silhouette's pieces and its ink outline, and the dark marks on
        the object's fills, are kept beyond it.
    max_regions : int
        The most regions (the background included) the optimization is given
        at once (default ``CLIPART_MAX_REGIONS``): where more remain, merging
        goes on with the dark marks too, down to this many, and a
        :class:`DetailWarning` says so in one line, with the detail used.

    Returns
    -------
    regions : ndarray of int, shape (H, W)
        The merged regions, labels packed, the background still 0
        (``regions`` itself when nothing was merged).
    detail : int
        The regions kept besides the background: ``detail``, or more where
        what is never merged is more, or fewer where ``max_regions`` asked it.
    """
    n = int(regions.max()) + 1
    if n - 1 <= detail:
        return regions, n - 1
    target = merge_targets(regions, lab, detail, marks=True)
    if len(np.unique(target)) > max_regions:  # the dark marks too, down to the bound
        target = merge_targets(regions, lab, min(detail, max_regions - 1), marks=False)
        import warnings

        warnings.warn(
            f"{n} regions at detail {detail} are more than the optimization takes at once ({max_regions}): "
            f"coarsened to detail {len(np.unique(target)) - 1}, {len(np.unique(target))} regions",
            DetailWarning,
            stacklevel=2,
        )
    kept = len(np.unique(target))
    if kept == n:
        return regions, n - 1
    alive = np.zeros(len(target), dtype=bool)
    alive[target] = True
    packed = np.cumsum(alive) - 1
    return packed[target][regions].astype(np.int64), kept - 1


def merge_targets(regions: np.ndarray, lab: np.ndarray, detail: int, *, marks: bool = True) -> np.ndarray:
    """The region each label is merged into by :func:`merge_by_importance`: (n,) int, the identity where kept.

    Merges in Ward's order until ``detail`` regions are left besides the
    background, or no merge is allowed. ``marks``: the dark marks on the
    object's fills (:func:`ink_outlines` without the paper, by
    ``CLIPART_MARK_CONTRAST``) take part in no merge.
    """
    counts, means = label_means(regions, lab)
    n = len(counts)
    target = np.arange(n)
    if n < 3:  # the background and at most one region: nothing to merge
        return target
    area = counts.astype(np.float64).copy()
    colour = means.astype(np.float64).copy()
    nbrs: list[dict[int, int]] = [{} for _ in range(n)]
    adjacency = region_adjacency(regions)
    # The silhouette: the background takes part in no merge, nor does an ink outline on it
    # (the cartoon style's outer outline, drawn once along its middle: clipart.clipart_lines).
    fixed = np.zeros(n, dtype=bool)
    fixed[0] = True
    on_paper = np.zeros(n, dtype=bool)
    on_paper[[j for i, j in adjacency if i == 0]] = True
    fixed[np.intersect1d(outline_strokes(regions, means[:, 0]), np.flatnonzero(on_paper))] = True
    # Nor does a dark mark on the object's lighter fills (an eye, a pupil, a spot, an inner
    # outline): the first thing the eye finds in a picture, and what a designer keeps.
    if marks:
        fixed[ink_outlines(regions, means[:, 0], paper=False, contrast=CLIPART_MARK_CONTRAST)] = True
    for (i, j), length in adjacency.items():
        if fixed[i] or fixed[j]:
            continue
        nbrs[i][j] = length
        nbrs[j][i] = length
    version = np.zeros(n, dtype=np.int64)
    stroke = np.zeros(n, dtype=bool)
    stroke[thin_regions(regions, means[:, 0])] = True

    def cost(i: int, j: int) -> float:
        d = colour[i] - colour[j]
        return float(area[i] * area[j] / (area[i] + area[j]) * (d @ d))

    heap = [(cost(i, j), i, j, 0, 0) for i in range(1, n) for j in nbrs[i] if i < j]
    heapq.heapify(heap)
    left = int(np.count_nonzero(counts[1:]))  # besides the background
    while heap and left > detail:
        _, i, j, vi, vj = heapq.heappop(heap)
        if vi != version[i] or vj != version[j] or target[i] != i or target[j] != j:
            continue  # stale: a side was merged since
        left -= 1
        # j into i: a stroke into its fill, never a fill into a stroke (which would widen it
        # past a stroke's width, and its one centre line would become two edges); else the
        # larger keeps its label (the same picture either way).
        if (stroke[i] and not stroke[j]) or (stroke[i] == stroke[j] and area[j] > area[i]):
            i, j = j, i
        colour[i] = (area[i] * colour[i] + area[j] * colour[j]) / (area[i] + area[j])
        area[i] += area[j]
        target[j] = i
        version[i] += 1
        for k, length in nbrs[j].items():
            if k == i:
                continue
            nbrs[i][k] = nbrs[i].get(k, 0) + length
            del nbrs[k][j]
            nbrs[k][i] = nbrs[i][k]
        nbrs[i].pop(j, None)
        nbrs[j] = {}
        for k in nbrs[i]:
            a, b = (i, k) if i < k else (k, i)
            heapq.heappush(heap, (cost(a, b), a, b, int(version[a]), int(version[b])))
    for r in range(n):  # follow chains of merges to their end
        t = r
        while target[t] != t:
            t = target[t]
        target[r] = t
    return target
