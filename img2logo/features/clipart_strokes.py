"""A clip art's strokes (paper Sec. 4): thin regions and ink outlines, drawn once along their middle.

A *thin* region (a whisker, a mouth line, an outline stroke: at most
``CLIPART_STROKE_WIDTH`` px wide and much longer than wide, :func:`thin_regions`)
and an *ink outline* (a region darker than what it touches, :func:`ink_outlines`)
give their centreline instead of a double boundary (:func:`clipart_lines`).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from .._compat import intersect1d, median, setdiff1d, union1d
from .clipart import border_lengths, frame_interior, nearest_labels, region_boundaries
from .constants import (
    CLIPART_EDGE_CONTRAST,
    CLIPART_INK_BORDER,
    CLIPART_MIN_REGION_AREA,
    CLIPART_OUTLINE_WIDTH,
    CLIPART_STROKE_ELONGATION,
    CLIPART_STROKE_MAX_FACTOR,
    CLIPART_STROKE_WIDTH,
)


def thin_regions(regions: np.ndarray, lightness: np.ndarray | None = None) -> np.ndarray:
    """Labels of the thin regions: strokes drawn as filled shapes.

    A region (not the background) is thin when its typical width, twice the
    median distance from its medial axis to its edge, is at most
    ``CLIPART_STROKE_WIDTH`` px and its medial axis is at least
    ``CLIPART_STROKE_ELONGATION`` times longer than that width: a whisker or
    an outline, not a dot.

    An **ink outline** (:func:`ink_outlines`, given the regions' median L*
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
    ``CLIPART_EDGE_CONTRAST``; ``lightness`` (n,) the regions' median L*,
    :func:`~img2logo.features.clipart_colours.label_lightness`): a cartoon's
    outline runs between lighter fills, and touches the odd dark detail (a pupil, a dark shading)
    along a little of its length. The background is none. Without ``paper``
    the border with the background does not count: a dark mark on the
    object's lighter fills (an eye, a spot, an inner outline), and not a dark
    shape alone on the paper.
    """
    n = int(regions.max()) + 1
    border = border_lengths(regions, n).astype(np.float64)
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

    With ``lightness`` (n,), the regions' median L*, the **ink outlines** are
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
        thin = setdiff1d(thin, ink_outlines(regions, lightness))
    if len(thin) == 0 and strokes is None:
        return region_boundaries(regions)
    drawn = np.isin(regions, thin)
    n = int(regions.max()) + 1
    border = border_lengths(regions, n)
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
    out = np.isin(regions, intersect1d(thin, inks))
    for _, sl, part in _ink_parts(regions, setdiff1d(inks, thin)):
        out[sl] |= part
    return out if out.any() else None


def outline_strokes(regions: np.ndarray, lightness: np.ndarray) -> np.ndarray:
    """Labels of the ink outlines drawn as strokes: thin regions, or at least half thin parts; sorted.

    :func:`ink_outlines` that are :func:`thin_regions` whole, or whose
    thin parts (:func:`ink_strokes`) hold at least half their pixels (a cartoon's outline
    network with a few wider blobs); a dark fill (a black disc) is none.
    """
    inks = ink_outlines(regions, lightness)
    thin = intersect1d(thin_regions(regions, lightness), inks)
    area = np.bincount(regions.ravel())
    mostly = [label for label, _, part in _ink_parts(regions, setdiff1d(inks, thin)) if 2 * part.sum() >= area[label]]
    return union1d(thin, np.array(mostly, dtype=np.int64))


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
        inside = pieces > 0  # ufunc.at is slow per element: only the pieces' pixels
        np.maximum.at(half, pieces[inside], depth[inside])
        area = stats[:, cv2.CC_STAT_AREA]
        keep = (area >= CLIPART_MIN_REGION_AREA) & (area >= CLIPART_STROKE_ELONGATION * (2.0 * half) ** 2)
        keep[0] = False
        yield int(label), sl, keep[pieces]
