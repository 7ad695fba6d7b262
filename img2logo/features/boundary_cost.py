"""What each boundary of a clip art costs the logo: its predicted arcs.

A region count does not bound what a logo costs: a wavy region's outline takes
many arcs, a round one one. :func:`boundary_arcs` predicts, for every pair of
adjacent regions, the arcs that the boundary between them takes in the logo,
so that :func:`img2logo.features.detail.merge_targets` can keep the regions
worth their arcs within an arc budget (``merge_by_importance(..., arcs=)``; no
default uses it: docs/design/detail.md, "An arc budget", says what it predicts
and what it does not).

The prediction follows the fit. The segment graph over-segments each line by
Ramer-Douglas-Peucker at ``RDP_TOLERANCE`` (Sec. 4) and the fit merges
neighbouring segments while an arc stays within T of them (Eqn. 1): a
steadily turning boundary gives few segments and they merge into long arcs,
a wavy one many. Each region's outline (OpenCV's border following, one pixel
per step) is split into runs by the region on its other side; each run is
simplified by Ramer-Douglas-Peucker at that tolerance and an arc is counted
for every ``ARC_CHORDS`` of its chords, at least one per run (a run ends at
junctions, where arcs end). A run shorter than twice the tolerance (a corner
pixel, an antialiased step) is no line of its own and counts nothing. A
boundary is seen from both its regions; its cost is the mean of the two. The
outline of a stroke (a thin region, drawn once along its middle,
:func:`img2logo.features.clipart_strokes.clipart_lines`) is one line for its two
edges, so each of its edges counts half.

Arrays are indexed (row, column).
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np

from ..constants import RDP_TOLERANCE

#: Chords of the Ramer-Douglas-Peucker polyline at RDP_TOLERANCE (the segment graph's over-segmentation) that
#: one arc of the logo stands for: the fit merges about four of the segments it starts from into one arc within
#: T (measured: arcs of the default logo over the chords of its regions' boundaries, median 0.91 at four, the
#: clip arts of the evaluation, held-out and Openclipart families; log spread 0.31: benchmarks/arc_prediction.py).
ARC_CHORDS: float = 4.0


def boundary_arcs(
    regions: np.ndarray, strokes: np.ndarray | None = None, tolerance: float = RDP_TOLERANCE
) -> dict[tuple[int, int], float]:
    """The predicted arcs of the boundary between every pair of adjacent regions.

    Parameters
    ----------
    regions : ndarray of int, shape (H, W)
        Region labels, 0 = background.
    strokes : ndarray of int, optional
        The labels drawn once along their middle (thin regions): each of their edges counts half.
    tolerance : float
        The Ramer-Douglas-Peucker tolerance of the runs, px (default ``RDP_TOLERANCE``).

    Returns
    -------
    dict of (int, int) -> float
        {(i, j): predicted arcs} for i < j, the pairs whose boundary has a run
        of at least 2 T px (8-adjacent across the outline); each run at least one arc.
    """
    import cv2

    regions = np.asarray(regions)
    h, w = regions.shape
    n = int(regions.max()) + 1
    half = np.ones(n)
    if strokes is not None and len(strokes):
        labels = np.asarray(strokes, dtype=np.int64)
        half[labels[labels < n]] = 0.5  # a stroke given away to its sides has no label left
    padded = np.pad(regions, 1, mode="edge")
    seen: dict[tuple[int, int], list[float]] = {}
    from ..images.ndimage import bounding_slices

    boxes = bounding_slices(regions + 1)
    for label, box in enumerate(boxes):
        if box is None:
            continue
        rows = slice(max(box[0].start - 1, 0), min(box[0].stop + 1, h))
        cols = slice(max(box[1].start - 1, 0), min(box[1].stop + 1, w))
        mask = (regions[rows, cols] == label).astype(np.uint8)
        contours, _ = cv2.findContours(mask, cv2.RETR_CCOMP, cv2.CHAIN_APPROX_NONE)
        for contour in contours:
            xy = contour.reshape(-1, 2) + np.array([cols.start, rows.start])
            if len(xy) < 2:
                continue
            across = _across(padded, xy, label)
            for other, run in _runs(xy, across):
                if other < 0 or other == label:
                    continue
                if len(run) < 2.0 * tolerance:
                    continue  # shorter than twice the tolerance (a corner's pixel, an antialiased step): no line
                polyline = cv2.approxPolyDP(run.reshape(-1, 1, 2).astype(np.int32), tolerance, False)
                chords = max(float(len(polyline) - 1), ARC_CHORDS)  # a run between two junctions: at least one arc
                key = (min(label, other), max(label, other))
                seen.setdefault(key, [0.0, 0.0])[0 if label == key[0] else 1] += chords
    out: dict[tuple[int, int], float] = {}
    for key, (a, b) in seen.items():
        both = [v for v in (a, b) if v > 0]
        out[key] = float(np.mean(both)) * min(half[key[0]], half[key[1]]) / ARC_CHORDS
    return out


def _across(padded: np.ndarray, xy: np.ndarray, label: int) -> np.ndarray:
    """The label across each outline pixel: its first 4-neighbour, then diagonal one, not ``label`` (-1 if none)."""
    r = xy[:, 1] + 1
    c = xy[:, 0] + 1
    out = np.full(len(xy), -1, dtype=np.int64)
    for dr, dc in ((0, 1), (1, 0), (0, -1), (-1, 0), (1, 1), (1, -1), (-1, 1), (-1, -1)):
        v = padded[r + dr, c + dc]
        take = (out < 0) & (v != label)
        out[take] = v[take]
    return out


def _runs(xy: np.ndarray, across: np.ndarray) -> Iterator[tuple[int, np.ndarray]]:
    """The outline cut into maximal runs of one label across: (label, (k, 2) points) pairs; a closed run wraps."""
    cuts = np.flatnonzero(across != np.roll(across, 1))
    if len(cuts) == 0:  # one neighbour all round: a closed run
        yield int(across[0]), np.vstack([xy, xy[:1]])
        return
    for a, b in zip(cuts, np.roll(cuts, -1), strict=True):
        idx = np.arange(a, b if b > a else b + len(xy)) % len(xy)
        yield int(across[a]), xy[idx]
