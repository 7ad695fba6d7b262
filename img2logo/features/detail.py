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
asked, the dark marks on the object's fills (an eye, a pupil, a spot), which
only take in smaller regions (a pupil's highlight, the spots a wing's black
encloses).

Fills that face each other across a stroke of that outline (the cartoon
style, where fills touch only the outline) are neighbours too, weighed with
the stroke between them, which goes when they merge
(:mod:`img2logo.features.stroke_sides`), under an arc budget only: there the
count takes them when no fills sharing a border are left to merge, and the
budget by its one order; without one the outline stays as drawn.

With an arc budget (``arcs``, :func:`merge_by_importance`) merging then goes
on, the least Ward weight per predicted arc saved first
(:mod:`img2logo.features.boundary_cost`), until the logo's predicted arcs
are within it.

:func:`close_line_ends` then makes every line of the map whole: a line end,
the end of a mark drawn as its centre line inside one fill, is joined to the
line it stops short of, or the mark is dropped whole when it weighs less than
the detail budget (the lightest boundary the ranking kept).

Arrays are indexed (row, column).
"""

from __future__ import annotations

import heapq
from typing import NamedTuple

import numpy as np

from .._compat import intersect1d, unique
from ..constants import LINE_JOIN_DISTANCE
from .boundary_cost import boundary_arcs
from .clipart_colours import label_lightness, label_means
from .clipart_strokes import ink_outlines, outline_strokes, thin_regions
from .constants import CLIPART_MARK_CONTRAST, CLIPART_MAX_REGIONS, CLIPART_OUTLINE_WIDTH
from .stroke_sides import StrokeSides, across_strokes, open_strokes, stroke_sides


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


def ward_weight(area_a: float, area_b: float, distance_sq: float) -> float:
    """Ward's criterion of merging two regions: a_a a_b / (a_a + a_b) |c_a - c_b|^2, squared Delta E times px.

    The squared colour error painting both in their mean colour adds (Ward 1963): what a
    merge of :func:`merge_targets` paints over. ``distance_sq`` is |c_a - c_b|^2 in CIELAB.

    Examples
    --------
    >>> from img2logo.features.detail import ward_weight
    >>> ward_weight(10.0, 30.0, 4.0)  # 10 px and 30 px, 2 Delta E apart
    30.0
    """
    return area_a * area_b / (area_a + area_b) * distance_sq


class Merged(NamedTuple):
    """What :func:`merge_by_importance` gives: the merged regions, the detail kept, the detail budget."""

    regions: np.ndarray
    detail: int
    budget: float


class DetailWarning(UserWarning):
    """A clip art had more regions than the optimization takes at once: its detail was coarsened."""


def merge_by_importance(
    regions: np.ndarray,
    lab: np.ndarray,
    detail: int,
    *,
    arcs: float | None = None,
    max_regions: int = CLIPART_MAX_REGIONS,
) -> Merged:
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
    arcs : float or None
        An arc budget (None, the default: none): after the count, regions go
        on merging, the least Ward weight per predicted arc saved first, until
        the logo's predicted arcs (:func:`img2logo.features.boundary_cost.boundary_arcs`
        of every boundary kept, the silhouette's included) are at most
        ``arcs``; what is never merged is kept beyond it.
    max_regions : int
        The most regions (the background included) the optimization is given
        at once (default ``CLIPART_MAX_REGIONS``): where more remain, merging
        goes on with the dark marks too, down to this many, and a
        :class:`DetailWarning` says so in one line, with the detail used.

    Returns
    -------
    Merged
        ``regions`` (H, W) int, the merged regions, labels packed, the
        background still 0 (``regions`` itself when nothing was merged);
        ``detail``, the regions kept besides the background: ``detail``, or
        more where what is never merged is more, or fewer where
        ``max_regions`` asked it; ``budget``, the Ward weight of the heaviest
        merge made (0 when none was), squared Delta E times px.
    """
    n = int(regions.max()) + 1
    # Under an arc budget fills facing each other across the outline's strokes merge too; the count
    # alone keeps the outline as drawn (a beak or an eye enclosed by it stays its own fill).
    sides = outline_sides(regions, lab) if arcs is not None else None
    target, budget = merge_targets(regions, lab, detail, marks=True, arcs=arcs, sides=sides)
    if n - 1 <= detail and len(unique(target)) == n:
        return Merged(regions, n - 1, budget)
    coarsened = len(unique(target)) > max_regions
    if coarsened:  # the dark marks too, down to the bound
        target, budget = merge_targets(regions, lab, min(detail, max_regions - 1), marks=False, arcs=arcs, sides=sides)
    kept = len(unique(target))
    if coarsened:
        import warnings

        warnings.warn(
            f"{n} regions at detail {detail} are more than the optimization takes at once ({max_regions}): "
            f"coarsened to detail {kept - 1}, {kept} regions"
            + (" (no fewer without merging across the outline)" if kept > max_regions else ""),
            DetailWarning,
            stacklevel=2,
        )
    if kept == n:
        return Merged(regions, n - 1, budget)
    if sides is not None:  # the stroke between fills merged into one goes, as a shared boundary would
        regions = open_strokes(regions, sides, target)
    alive = np.zeros(len(target), dtype=bool)
    alive[target] = True
    packed = np.cumsum(alive) - 1
    return Merged(packed[target][regions].astype(np.int64), kept - 1, budget)


def outline_sides(regions: np.ndarray, lab: np.ndarray) -> StrokeSides | None:
    """The sides of the strokes of the ink outlines on the paper (:func:`img2logo.features.stroke_sides.stroke_sides`).

    ``regions`` (H, W) int, 0 = background; ``lab`` (H, W, 3) CIELAB. None when there are none.
    """
    lightness = label_lightness(regions, lab[..., 0])
    on_paper = np.zeros(len(lightness), dtype=bool)
    on_paper[[j for i, j in region_adjacency(regions) if i == 0]] = True
    return stroke_sides(regions, lightness, thin_regions(regions, lightness), on_paper)


def merge_targets(
    regions: np.ndarray,
    lab: np.ndarray,
    detail: int,
    *,
    marks: bool = True,
    arcs: float | None = None,
    sides: StrokeSides | None = None,
) -> tuple[np.ndarray, float]:
    """The region each label is merged into by :func:`merge_by_importance`, and the detail budget.

    Merges in Ward's order until ``detail`` regions are left besides the
    background, or no merge is allowed. ``marks``: the dark marks on the
    object's fills (:func:`ink_outlines` without the paper, by
    ``CLIPART_MARK_CONTRAST``) take part in no merge. ``arcs``: then, while
    the predicted arcs of the boundaries kept exceed it, the allowed merge of the
    least Ward weight per predicted arc of the boundary it removes (a
    rate-distortion order: the least colour error per arc saved); its merges
    do not raise the returned budget, which the marks' line ends are weighed
    against (:func:`close_line_ends`). ``sides``: the strokes of the ink
    outlines on the paper (:func:`outline_sides`): the fills facing each other
    across them are neighbours too (:func:`img2logo.features.stroke_sides.across_strokes`),
    the side-border's length their border.

    Returns
    -------
    target : ndarray of int, shape (n,)
        The label each label is merged into, the identity where kept.
    budget : float
        The Ward weight of the heaviest merge made (0 when none was): what
        the detail asked painted over, squared Delta E times px.
    """
    counts, means = label_means(regions, lab)
    n = len(counts)
    target = np.arange(n)
    if n < 3:  # the background and at most one region: nothing to merge
        return target, 0.0
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
    lightness = label_lightness(regions, lab[..., 0])  # a stroke's colour, not its rim's (label_lightness)
    fixed[intersect1d(outline_strokes(regions, lightness), np.flatnonzero(on_paper))] = True
    # Nor is a dark mark on the object's lighter fills (an eye, a pupil, a spot, an inner
    # outline), the first thing the eye finds in a picture and what a designer keeps, ever
    # painted over: it only takes in smaller regions (a pupil's highlight, the light spots
    # enclosed by a wing's black), which take its colour, and no other mark.
    dark = np.zeros(n, dtype=bool)
    if marks:
        dark[ink_outlines(regions, lightness, paper=False, contrast=CLIPART_MARK_CONTRAST)] = True
    stroke = np.zeros(n, dtype=bool)
    stroke[thin_regions(regions, lightness)] = True
    # Fills facing each other across a stroke of the outline on the paper are neighbours too,
    # the stroke between them their boundary (stroke_sides).
    across = None if sides is None else across_strokes(sides, fixed, lab)
    ink: dict[tuple[int, int], float] = {} if across is None else {k: float(v) for k, v in across.ink.items()}
    touch = {pair for pair in adjacency if not (fixed[pair[0]] or fixed[pair[1]])}  # a shared border
    for (i, j), length in [*adjacency.items(), *([] if across is None else across.border.items())]:
        if fixed[i] or fixed[j] or (dark[i] and dark[j]):
            continue
        nbrs[i][j] = nbrs[i].get(j, 0) + length
        nbrs[j][i] = nbrs[i][j]
    version = np.zeros(n, dtype=np.int64)

    def allowed(i: int, j: int) -> bool:  # a mark, never a stroke, takes in only what is smaller than it
        mark, other = (i, j) if dark[i] else (j, i)
        return not dark[mark] or (not dark[other] and not stroke[mark] and area[other] < area[mark])

    def cost(i: int, j: int) -> float:
        d = colour[i] - colour[j]
        weight = ward_weight(area[i], area[j], d @ d)
        painted = ink.get((i, j) if i < j else (j, i), 0.0)
        if painted and across is not None:  # and the stroke between them, painted in their mean colour
            both = (area[i] * colour[i] + area[j] * colour[j]) / (area[i] + area[j])
            e = both - across.colour
            weight += ward_weight(area[i] + area[j], painted, e @ e)
        return float(weight)

    def merge(i: int, j: int) -> tuple[int, int]:
        """Merge the pair; (kept, gone) labels."""
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
            jk, ik = (min(j, k), max(j, k)), (min(i, k), max(i, k))
            if jk in ink:  # the stroke between j and k is now between i and k
                ink[ik] = ink.get(ik, 0.0) + ink.pop(jk)
            if jk in touch:
                touch.add(ik)
            nbrs[i][k] = nbrs[i].get(k, 0) + length
            del nbrs[k][j]
            nbrs[k][i] = nbrs[i][k]
        nbrs[i].pop(j, None)
        nbrs[j] = {}
        return i, j

    def tier(i: int, j: int) -> int:  # fills that share a border first; across a stroke only then
        return 0 if ((i, j) if i < j else (j, i)) in touch else 1

    heap = [(tier(i, j), cost(i, j), i, j, 0, 0) for i in range(1, n) for j in nbrs[i] if i < j]
    heapq.heapify(heap)
    left = int(np.count_nonzero(counts[1:]))  # besides the background
    budget = 0.0
    while heap and left > detail:
        level, weight, i, j, vi, vj = heapq.heappop(heap)
        if vi != version[i] or vj != version[j] or target[i] != i or target[j] != j:
            continue  # stale: a side was merged since
        if not allowed(i, j):
            continue  # taken anew when either side grows
        left -= 1
        if level == 0:  # a merge across a stroke does not raise what the marks are weighed against
            budget = max(budget, weight)
        i, _ = merge(i, j)
        for k in nbrs[i]:
            a, b = (i, k) if i < k else (k, i)
            heapq.heappush(heap, (tier(a, b), cost(a, b), a, b, int(version[a]), int(version[b])))
    if arcs is not None:  # then down to the arc budget, the least weight per arc first
        inner = _boundary_arcs(regions if sides is None else sides.given, stroke, target)

        def key(i: int, j: int, c: float) -> float:  # the colour error painted over per arc saved
            return cost(i, j) / c

        rate = [(key(i, j, c), i, j, int(version[i]), int(version[j])) for (i, j), c in inner.items() if j in nbrs[i]]
        heapq.heapify(rate)
        total = sum(inner.values())
        while rate and total > arcs:
            _, i, j, vi, vj = heapq.heappop(rate)
            if vi != version[i] or vj != version[j] or target[i] != i or target[j] != j or not allowed(i, j):
                continue  # stale, or taken anew when either side grows
            total -= inner.pop((i, j))
            i, j = merge(i, j)
            for (a, b), c in [(p, c) for p, c in inner.items() if j in p]:  # j's boundaries are now i's
                del inner[a, b]
                k = b if a == j else a
                pair = (min(i, k), max(i, k))
                inner[pair] = inner.get(pair, 0.0) + c
            for k in nbrs[i]:
                a, b = (i, k) if i < k else (k, i)
                if (a, b) in inner:
                    heapq.heappush(rate, (key(a, b, inner[a, b]), a, b, int(version[a]), int(version[b])))
    # The detail budget: the weight of the next merge the ranking would make, the lightest
    # boundary it kept (the heaviest it made where none is left to make).
    for level, weight, i, j, vi, vj in sorted(heap):
        if level == 0 and vi == version[i] and vj == version[j] and target[i] == i and target[j] == j and allowed(i, j):
            budget = max(budget, weight)
            break
    _follow(target)
    return target, budget


def _follow(target: np.ndarray) -> None:
    """Follow each label's chain of merges to its end, in place."""
    for r in range(len(target)):
        t = r
        while target[t] != t:
            t = target[t]
        target[r] = t


def _boundary_arcs(regions: np.ndarray, stroke: np.ndarray, target: np.ndarray) -> dict[tuple[int, int], float]:
    """The predicted arcs of each boundary between the regions merged so far, the silhouette's included.

    :func:`img2logo.features.boundary_cost.boundary_arcs` of ``regions``, summed
    over the labels each label is merged into (``target``, chains followed on a copy).
    """
    ends = target.copy()
    _follow(ends)
    out: dict[tuple[int, int], float] = {}
    for (i, j), c in boundary_arcs(regions, np.flatnonzero(stroke)).items():
        a, b = sorted((int(ends[i]), int(ends[j])))
        if a != b:
            out[a, b] = out.get((a, b), 0.0) + c
    return out


def close_line_ends(lines: np.ndarray, regions: np.ndarray, lab: np.ndarray, budget: float) -> np.ndarray:
    """A clip art's line map with every line whole: each line end joined, or its mark dropped whole.

    Every region boundary of a clip art is closed, so a line end inside the
    picture is a **mark** drawn as its centre line (a stroke's tapered tip, a
    hatching line, a whisker) that ends inside one fill. Each is, in turn:

    1. **joined** to the line it stops short of, when one is within
       ``CLIPART_OUTLINE_WIDTH`` + ``LINE_JOIN_DISTANCE`` px
       (:func:`img2logo.images.line_ends.join_line_ends`): a stroke that meets
       the silhouette in the input stops an outline's width short of it in the
       map (its pixels there are the silhouette's line,
       :func:`img2logo.features.clipart_strokes.clipart_lines`), and one that meets an
       inner boundary stops about its half width short, plus a near-miss;
    2. else **dropped whole** (a branch back to the junction it hangs on, an
       open line entirely) when its visual weight is below the detail
       ``budget``: its Ward weight, the squared colour error of painting its
       ink (the mark's region within ``CLIPART_OUTLINE_WIDTH`` / 2 px of the
       line) in the colour of the fill it lies on, a_m a_f / (a_m + a_f)
       |c_m - c_f|^2 (:func:`merge_targets`), against the weight of the
       heaviest merge the ranking made at the detail asked: the mark is what
       the ranking would have painted over had it been a region of its own;
    3. else kept as it is (a mark as weighty as the regions kept).

    Ends within 2 px of the image frame are where a boundary leaves the
    picture and are left alone; a mark on the background (a whisker, an
    eyelash) is part of the silhouette and is never dropped.

    Parameters
    ----------
    lines : ndarray of bool, shape (H, W)
        The clip art's 1-px line map.
    regions : ndarray of int, shape (H, W)
        Its regions after :func:`merge_by_importance`, 0 = background.
    lab : ndarray, shape (H, W, 3)
        The image's CIELAB colours.
    budget : float
        :attr:`Merged.budget`, squared Delta E times px.

    Returns
    -------
    ndarray of bool, shape (H, W)
        The map (thin it and prune it again: a join or a drop leaves a node
        of valence 2 or a short spur).
    """
    import cv2

    from ..images import skeleton
    from ..images.line_ends import join_line_ends

    out = join_line_ends(np.asarray(lines, dtype=bool), CLIPART_OUTLINE_WIDTH + LINE_JOIN_DISTANCE)
    if budget <= 0.0:
        return out
    graph = skeleton.trace(out)
    valence = graph.valence()
    counts, means = label_means(regions, lab)
    h, w = out.shape
    size = 2 * int(CLIPART_OUTLINE_WIDTH // 2) + 1
    disc = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (size, size))
    drop = np.zeros_like(out)
    for c, (a, b) in enumerate(graph.ends):
        free = [k for k in (a, b) if valence[k] == 1 and a != b]
        if not free:
            continue
        pixels = np.vstack([graph.chains[c].reshape(-1, 2)] + [graph.node_pixels[k] for k in free])
        if (pixels.min(axis=0) < 2).any() or (pixels.max(axis=0) >= (h - 2, w - 2)).any():
            continue  # a boundary leaving the picture
        rows, cols = pixels[:, 0], pixels[:, 1]
        mark = int(np.bincount(regions[rows, cols]).argmax())
        box = (
            slice(max(rows.min() - size, 0), rows.max() + size + 1),
            slice(max(cols.min() - size, 0), cols.max() + size + 1),
        )
        on = np.zeros(out[box].shape, dtype=np.uint8)
        on[rows - box[0].start, cols - box[1].start] = 1
        near = cv2.dilate(on, disc) > 0
        local = regions[box]
        ink = float(np.count_nonzero(near & (local == mark)))
        others = local[near & (local != mark)]
        if ink == 0.0 or len(others) == 0:
            continue
        fill = int(np.bincount(others).argmax())
        if fill == 0:
            continue  # a mark on the paper (a whisker, an eyelash) is part of the silhouette
        d = means[mark] - means[fill]
        weight = ward_weight(ink, counts[fill], float(d @ d))
        if weight < budget:
            drop[rows, cols] = True
    return out & ~drop
