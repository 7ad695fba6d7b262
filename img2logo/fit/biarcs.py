"""Tangent biarcs (beyond the paper): the pair of tangent circles on given rungs closest to a pixel chain.

Two circles that touch at a junction (centre distance |r1 - r2| or r1 + r2) fit a smooth feature line
whose curvature changes at one point; :func:`closest_biarcs` finds, for each pair of radii, the junction
along the chain and the tangent direction there whose two arcs are closest to the chain (the largest
distance of a pixel to its arc, :func:`biarc_worst`), on a coarse grid (:func:`biarc_coarse`) and then
finer around its best (:func:`biarc_fine`). The tangent pass (:mod:`img2logo.fit.tangency`) starts a
refit of two groups from them.

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from .constants import (
    BIARC_STEP,
    BIARC_TURN,
    BIARC_TURN_STEPS,
    SLIDE_MIN_PIXELS,
)


def closest_biarcs(
    chain: np.ndarray, radii_a: Sequence[float], radii_b: Sequence[float], most: int | None = None
) -> list[tuple[float, int, int, int, np.ndarray, np.ndarray]]:
    """The tangent biarcs closest to a pixel chain (n, 2), one per pair of radii: best first.

    For every radius ``radii_a[ia]`` of the head's circle and ``radii_b[ib]`` of
    the tail's: the junction is a pixel ``chain[i]`` (at least
    ``SLIDE_MIN_PIXELS`` from either end); the common tangent there is the
    chain's direction turned by up to ``BIARC_TURN`` rad either way; each circle
    on either side. The head ``chain[:i + 1]`` goes with the first circle, the
    tail ``chain[i:]`` with the second; the biarc kept has the smallest largest
    distance of a pixel from its circle (the discrete Fréchet distance of E^s
    is at least that). Searched on a grid (every ``BIARC_STEP`` pixels, every
    ``BIARC_TURN / BIARC_TURN_STEPS`` rad, every ``BIARC_STEP``-th pixel
    measured), then around the best of each pair on every pixel and a grid four
    times finer (:func:`biarc_fine`). Returns (largest distance px, ia, ib, i, centre a, centre b)
    sorted by the distance (a stable sort: on a tie the pairs in order); empty if the chain is too short.
    ``most``: only the first ``most`` of that list (None: all); a pair's fine search stops as
    soon as it cannot be among them, the same list's head as :func:`closest_biarcs` without it.
    """
    n = len(chain)
    lo, hi = SLIDE_MIN_PIXELS + 1, n - SLIDE_MIN_PIXELS - 1
    if hi <= lo:
        return []
    step = BIARC_TURN / BIARC_TURN_STEPS
    splits = np.arange(lo, hi, BIARC_STEP)
    turns = np.arange(-BIARC_TURN_STEPS, BIARC_TURN_STEPS + 1) * step
    sides = ((-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0))
    coarse = biarc_coarse(chain, splits, turns, radii_a, radii_b)
    pairs = [(ia, ib) for ia in range(len(radii_a)) for ib in range(len(radii_b))]
    # Around the best on the coarse grid: every pixel and a finer turn, every pixel measured.
    grids = []
    for ia, ib in pairs:
        j, s, t = coarse[ia, ib]
        fine = np.arange(max(lo, splits[s] - BIARC_STEP), min(hi, splits[s] + BIARC_STEP + 1))
        grids.append((fine, turns[t] + np.arange(-4, 5) * (step / 4.0), sides[j]))
    heads = [(radii_a[ia], sa) for (ia, _), (_, _, (sa, _)) in zip(pairs, grids, strict=True)]
    tails = [(radii_b[ib], sb) for (_, ib), (_, _, (_, sb)) in zip(pairs, grids, strict=True)]
    found = biarc_fine(chain, [g[0] for g in grids], [g[1] for g in grids], heads, tails, most or 0)
    kept = [(f, pair, grid) for f, pair, grid in zip(found, pairs, grids, strict=True) if f is not None]
    out = []
    for (worst, s2, t2), (ia, ib), (fine, near, (sa, sb)) in sorted(kept, key=lambda k: k[0][0])[:most]:
        ra, rb = radii_a[ia], radii_b[ib]
        i = int(fine[s2])
        normal = biarc_normals(chain, np.array([i]), np.array([near[t2]]))[0, 0]
        out.append((worst, ia, ib, i, chain[i] + sa * ra * normal, chain[i] + sb * rb * normal))
    return out


def biarc_coarse(
    chain: np.ndarray, splits: np.ndarray, turns: np.ndarray, radii_a: Sequence[float], radii_b: Sequence[float]
) -> dict[tuple[int, int], tuple[int, int, int]]:
    """The best biarc of :func:`closest_biarcs`'s coarse grid for every pair of radii: (ia, ib) -> (sides, split, turn).

    Sides index ``((-1, -1), (-1, 1), (1, -1), (1, 1))`` (the head's circle's and
    the tail's); every ``BIARC_STEP``-th pixel measured. The smallest largest
    distance over the sides and the grid, the first in that order on a tie.
    Compiled (:func:`img2logo._compiled.arcs.biarc_coarse_kernel`, every pair in
    one call), a biarc's pixels stop being measured once it cannot beat the best
    so far: the same choice as the smallest of numpy's minima over the four grids
    of the two sides' :func:`biarc_worst`, and its argmin.
    """
    normal = biarc_normals(chain, splits, turns)  # shared by every radius and side
    from .._compiled import kernels

    base = chain[splits][:, None, :]
    heads = np.stack([np.stack([base + side * r * normal for side in (-1.0, 1.0)]) for r in radii_a])
    tails = np.stack([np.stack([base + side * r * normal for side in (-1.0, 1.0)]) for r in radii_b])
    index = np.arange(0, len(chain), BIARC_STEP)
    at = np.asarray(splits, dtype=np.int64)
    best = kernels.biarc_coarse_kernel(
        chain, index, at, heads, tails, np.array(radii_a, dtype=np.float64), np.array(radii_b, dtype=np.float64)
    ).tolist()
    return {(ia, ib): tuple(best[ia][ib]) for ia in range(len(radii_a)) for ib in range(len(radii_b))}


def biarc_fine(
    chain: np.ndarray,
    splits: Sequence[np.ndarray],
    turns: Sequence[np.ndarray],
    heads: Sequence[tuple[float, float]],
    tails: Sequence[tuple[float, float]],
    most: int = 0,
) -> list[tuple[float, int, int] | None]:
    """The best biarc of each grid of ``splits[p]`` and ``turns[p]``: (largest pixel distance px, split, turn index).

    ``heads[p]`` and ``tails[p]`` are grid ``p``'s two circles' (radius, side);
    every pixel is measured. The smallest over each grid of the larger of the
    head's and the tail's :func:`biarc_worst`, the first in row-major order on a
    tie. With ``most`` > 0, None for a grid that cannot be among the ``most``
    smallest of the grids (the earlier grid first on a tie): its search stops at
    the ``most``-th smallest of the grids before it. Compiled
    (:func:`img2logo._compiled.arcs.biarc_fine_kernel`, every grid in one call),
    a biarc's pixels stop being measured once it cannot beat the best so far:
    the same numbers as the two grids, a third of the work on the clip arts'
    joins. Each grid has the same number of turns, and at most ``2 BIARC_STEP + 1`` splits.
    """
    from .._compiled import kernels

    width = max(len(s) for s in splits)
    counts = np.array([len(s) for s in splits], dtype=np.int64)
    # Each grid's splits padded with its last (never measured: past counts[p]).
    at = np.array([np.concatenate([s, np.full(width - len(s), s[-1])]) for s in splits], dtype=np.int64)
    near = np.array(turns, dtype=np.float64)
    normal = biarc_normals(chain, at, near)  # (P, S, A, 2)
    base = chain[at][:, :, None, :]
    ra = np.array([r for r, _ in heads], dtype=np.float64)
    rb = np.array([r for r, _ in tails], dtype=np.float64)
    # The centres as biarc_normals' caller makes them for one grid: base + (side * radius) * normal.
    scale_a = np.array([side * r for r, side in heads], dtype=np.float64)[:, None, None, None]
    scale_b = np.array([side * r for r, side in tails], dtype=np.float64)[:, None, None, None]
    worst, s, a = kernels.biarc_fine_kernel(
        chain, base + scale_a * normal, base + scale_b * normal, at, counts, ra, rb, int(most)
    )
    return [None if s[p] < 0 else (float(worst[p]), int(s[p]), int(a[p])) for p in range(len(splits))]


def biarc_normals(chain: np.ndarray, splits: np.ndarray, turns: np.ndarray) -> np.ndarray:
    """Unit normals (S, A, 2) of the chain's direction at pixels ``splits`` (S,) turned by ``turns`` (A,) rad.

    Of many grids at once: splits (P, S) and turns (P, A) give (P, S, A, 2), each grid's the same
    numbers as alone (numpy's elementwise functions).
    """
    n = len(chain)
    d = chain[np.minimum(splits + 3, n - 1)] - chain[np.maximum(splits - 3, 0)]
    theta = np.arctan2(d[..., 1], d[..., 0])[..., None] + turns[..., None, :]
    return np.stack([-np.sin(theta), np.cos(theta)], axis=-1)


def biarc_worst(
    chain: np.ndarray,
    splits: np.ndarray,
    turns: np.ndarray,
    r: float,
    side: float,
    head: bool,
    stride: int,
    normal: np.ndarray | None = None,
) -> np.ndarray:
    """Largest distance (S, A) px of the head's (or tail's) pixels from a circle of radius ``r``, per split and turn.

    The circle touches the chain's turned direction at ``chain[split]``, its
    centre on the ``side`` (+1 or -1) of it; every ``stride``-th pixel measured.
    ``normal`` is :func:`biarc_normals` of ``splits`` and ``turns`` when known.
    """
    if normal is None:
        normal = biarc_normals(chain, splits, turns)
    centre = chain[splits][:, None, :] + side * r * normal  # (S, A, 2)
    index = np.arange(0, len(chain), stride)
    from .._compiled import kernels

    return kernels.biarc_worst_kernel(chain, centre, index, np.asarray(splits, dtype=np.int64), float(r), head)
