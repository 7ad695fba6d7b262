"""Joining a skeleton's line ends across small gaps: an end that stops short of another line reaches it.

A gap in a stroke (a pen lifted, a JPEG-broken line) leaves two ends facing each other, or an end
facing a line; :func:`join_line_ends` draws the missing pixels, straightest first, and cuts the spur
an end already reaches round to.
"""

from __future__ import annotations

import math

import numpy as np

from .._compat import line, nonzero
from ..constants import LINE_JOIN_DISTANCE
from .skeleton import classify


# --------------------------------------------------------------------------- joining line ends
def join_line_ends(skel: np.ndarray, distance: float = LINE_JOIN_DISTANCE) -> np.ndarray:
    """Link every end of a 1-px line map that stops near another line to it, (H, W) bool.

    For an end (a pixel with one 8-neighbour), the nearest line pixel at most
    ``distance`` px away that is not on its own stretch of line (the pixels
    within ``1.5 * distance`` steps along it):

    * on another line, or far along its own: the end is joined to it by a
      straight run of pixels (a junction; no near-miss gap);
    * within ``3 * distance`` steps along the line (the other branch of a fork
      just behind the end): the end's branch is a spur that would run beside
      its sibling, and is removed back to the fork.

    Of nearest pixels at the same distance, the one the line points at most
    nearly (:func:`_straightest`). Ends are taken in raster order; a new run is
    itself a line for the ends after it.
    """
    out = np.asarray(skel, dtype=bool).copy()
    if not out.any():
        return out
    ends = np.column_stack(nonzero(out & (classify(out)[1] == 1)))  # np.argwhere
    if len(ends) == 0:
        return out
    first = out.copy()  # the line pixels searched: those of the map as given
    near_steps, reach = math.ceil(1.5 * distance), math.ceil(3.0 * distance)
    h, w = out.shape
    for r, c in ends:
        end = (int(r), int(c))
        if not out[end]:
            continue
        own = pixels_within_steps(out, end, near_steps)
        best, best_d, tied = None, math.inf, []
        for q in pixels_within(first, end, distance):
            if q in own or not out[q]:
                continue
            d = math.hypot(q[0] - end[0], q[1] - end[1])
            if d < best_d:
                best, best_d, tied = q, d, [q]
            elif d == best_d:
                tied.append(q)
        if len(tied) > 1:
            best = _straightest(end, own, tied)
        if best is None or best_d <= 1.5:
            continue
        if best in pixels_within_steps(out, end, reach):
            spur = branch_to_fork(out, end)
            if spur is not None and len(spur) <= reach:
                for q in spur:
                    out[q] = False
        else:
            rr, cc = line(end[0], end[1], best[0], best[1])
            out[np.clip(rr, 0, h - 1), np.clip(cc, 0, w - 1)] = True
    return out


def pixels_within(pixels: np.ndarray, at: tuple[int, int], distance: float) -> list[tuple[int, int]]:
    """The set pixels of ``pixels`` (H, W) bool at most ``distance`` px from ``at`` (row, col), in raster order.

    The ball query of a k-d tree over the set pixels, read off the window of
    ``2 * floor(distance) + 1`` px around ``at`` instead (no tree to build per map).
    """
    reach = math.floor(distance)
    r0, c0 = max(at[0] - reach, 0), max(at[1] - reach, 0)
    rows, cols = np.nonzero(pixels[r0 : at[0] + reach + 1, c0 : at[1] + reach + 1])
    rows += r0
    cols += c0
    inside = (rows - at[0]) ** 2 + (cols - at[1]) ** 2 <= distance * distance
    return list(zip(rows[inside].tolist(), cols[inside].tolist(), strict=True))


def _straightest(end: tuple[int, int], own: set[tuple[int, int]], tied: list[tuple[int, int]]) -> tuple[int, int]:
    """Of line pixels ``tied`` equally near ``end``, the one the line reaching ``end`` points at most nearly.

    A join continues its stroke: the line's direction at the end is from the
    centroid of its own stretch (``own``, the pixels just behind the end) to the
    end; the pixel whose direction from the end turns least from it is taken,
    the first in raster order among equal turns.
    """
    back_r = sum(p[0] for p in own) / len(own)
    back_c = sum(p[1] for p in own) / len(own)
    dr, dc = end[0] - back_r, end[1] - back_c
    return max(tied, key=lambda q: (q[0] - end[0]) * dr + (q[1] - end[1]) * dc)  # equal lengths: the cosine


def branch_to_fork(skel: np.ndarray, end: tuple[int, int]) -> list[tuple[int, int]] | None:
    """The pixels from ``end`` along ``skel`` up to (not including) the first fork; None without a fork."""
    h, w = skel.shape
    path = [end]
    seen = {end}
    cur = end
    while True:
        nbrs = [
            (cur[0] + dr, cur[1] + dc)
            for dr in (-1, 0, 1)
            for dc in (-1, 0, 1)
            if (dr or dc) and 0 <= cur[0] + dr < h and 0 <= cur[1] + dc < w and skel[cur[0] + dr, cur[1] + dc]
        ]
        if len(nbrs) > 2:
            return path[:-1]
        nxt = [q for q in nbrs if q not in seen]
        if not nxt or (cur != end and len(nbrs) != 2):
            return None
        cur = nxt[0]
        seen.add(cur)
        path.append(cur)


def pixels_within_steps(skel: np.ndarray, start: tuple[int, int], steps: int) -> set[tuple[int, int]]:
    """Pixels of ``skel`` within ``steps`` 8-connected steps of ``start`` along it."""
    h, w = skel.shape
    seen = {start}
    frontier = [start]
    for _ in range(steps):
        nxt = []
        for r, c in frontier:
            for dr in (-1, 0, 1):
                for dc in (-1, 0, 1):
                    q = (r + dr, c + dc)
                    if 0 <= q[0] < h and 0 <= q[1] < w and skel[q] and q not in seen:
                        seen.add(q)
                        nxt.append(q)
        if not nxt:
            break
        frontier = nxt
    return seen
