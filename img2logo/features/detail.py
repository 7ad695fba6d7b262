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
weights are taken anew, until the regions kept explain the share ``detail`` of
the picture's colour variance (the sum of a_i |c_i - c|^2 over its regions, c
their mean colour): ``detail`` 1 merges nothing, a smaller ``detail`` keeps
fewer regions, the weightiest.

The **silhouette** is never touched: the background (label 0, the region that
covers most of the image's frame) takes part in no merge, so the boundary
between it and the object is kept whole, whatever its contrast or thinness (a
thin outer outline stroke stays a region of its own as long as it weighs more
than what is merged).

Arrays are indexed (row, column).
"""

from __future__ import annotations

import heapq

import numpy as np

from ..constants import CLIPART_MARK_CONTRAST, CLIPART_MAX_REGIONS
from ..errors import InvalidParameterError
from .clipart import ink_outlines, label_means, outline_strokes, thin_regions


def check_detail(value: object) -> float:
    """The ``detail`` option checked: a number in (0, 1], as float.

    Raises
    ------
    InvalidParameterError
        For anything else (a bool, a string, NaN, 0 or less, above 1).
    """
    if isinstance(value, bool | np.bool_ | str) or not isinstance(value, int | float | np.integer | np.floating):
        raise InvalidParameterError(f"detail must be a number in (0, 1], got {value!r}")
    v = float(value)
    if not (0.0 < v <= 1.0):
        raise InvalidParameterError(f"detail must be a number in (0, 1], got {value!r}")
    return v


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
    regions: np.ndarray, lab: np.ndarray, detail: float, *, max_regions: int = CLIPART_MAX_REGIONS
) -> tuple[np.ndarray, float]:
    """Merge a clip art's least important regions into their neighbours: (H, W) int labels, 0 = background.

    Parameters
    ----------
    regions : ndarray of int, shape (H, W)
        Flat-colour regions, 0 = background (:func:`img2logo.features.clipart.clipart_regions`).
    lab : ndarray, shape (H, W, 3)
        The image's CIELAB colours.
    detail : float
        In (0, 1]: the share of the picture's colour variance the kept regions
        explain (module docstring). 1 keeps every region (up to ``max_regions``).
    max_regions : int
        The most regions (the background included) the optimization is given
        at once (default ``CLIPART_MAX_REGIONS``): where more remain at
        ``detail``, merging goes on in the same order down to this many, and a
        :class:`DetailWarning` says so in one line, with the detail used.

    Returns
    -------
    regions : ndarray of int, shape (H, W)
        The merged regions, labels packed, the background still 0
        (``regions`` itself when nothing was merged).
    detail : float
        The share of the picture's colour variance they explain: at least
        ``detail``, less where ``max_regions`` coarsened it.
    """
    n = int(regions.max()) + 1
    if detail >= 1.0 and n <= max_regions:
        return regions, 1.0
    target, used = merge_targets(regions, lab, detail, max_regions=None)
    if len(np.unique(target)) > max_regions:  # the dark marks too, down to the bound
        target, used = merge_targets(regions, lab, detail, max_regions=max_regions)
    kept = len(np.unique(target))
    if used < detail:
        import warnings

        warnings.warn(
            f"{n} regions at detail {detail:g} are more than the optimization takes at once ({max_regions}): "
            f"coarsened to detail {used:.3f}, {kept} regions",
            DetailWarning,
            stacklevel=2,
        )
    if kept == n:
        return regions, used
    alive = np.zeros(len(target), dtype=bool)
    alive[target] = True
    packed = np.cumsum(alive) - 1
    return packed[target][regions].astype(np.int64), used


def merge_targets(
    regions: np.ndarray, lab: np.ndarray, detail: float, *, max_regions: int | None = CLIPART_MAX_REGIONS
) -> tuple[np.ndarray, float]:
    """The region each label is merged into by :func:`merge_by_importance`, and the detail reached.

    ``max_regions`` None: the dark marks on the object (:func:`ink_outlines`
    without the paper) are kept, and merging stops at ``detail``; a number:
    they may merge too, and merging goes on until at most that many regions
    are left.

    Returns
    -------
    target : ndarray of int, shape (n,)
        The label each label's pixels take; the identity where kept.
    detail : float
        The share of the picture's colour variance the regions kept explain:
        at least ``detail``, unless ``max_regions`` asked for fewer regions.
    """
    counts, means = label_means(regions, lab)
    n = len(counts)
    target = np.arange(n)
    if n < 3:  # the background and at most one region: nothing to merge
        return target, 1.0
    centre = np.average(means, axis=0, weights=counts)
    total = float(np.sum(counts * np.sum((means - centre) ** 2, axis=1)))
    budget = (1.0 - detail) * total
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
    if max_regions is None:
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
    spent = 0.0
    left = int(np.count_nonzero(counts))
    while heap:
        c, i, j, vi, vj = heapq.heappop(heap)
        if vi != version[i] or vj != version[j] or target[i] != i or target[j] != j:
            continue  # stale: a side was merged since
        if spent + c > budget and left <= (n if max_regions is None else max_regions):
            break
        spent += c
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
    return target, 1.0 - spent / total if total > 0 else 1.0
