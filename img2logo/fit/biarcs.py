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
    chain: np.ndarray, radii_a: Sequence[float], radii_b: Sequence[float]
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
    times finer. Returns (largest distance px, ia, ib, i, centre a, centre b)
    sorted by the distance; empty if the chain is too short.
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
    out = []
    for ia, ra in enumerate(radii_a):
        for ib, rb in enumerate(radii_b):
            j, s, t = coarse[ia, ib]
            sa, sb = sides[j]
            # Around the best on the coarse grid: every pixel and a finer turn, every pixel measured.
            fine = np.arange(max(lo, splits[s] - BIARC_STEP), min(hi, splits[s] + BIARC_STEP + 1))
            near = turns[t] + np.arange(-4, 5) * (step / 4.0)
            worst, s2, t2 = biarc_fine(chain, fine, near, (ra, sa), (rb, sb))
            i = int(fine[s2])
            normal = biarc_normals(chain, np.array([i]), np.array([near[t2]]))[0, 0]
            out.append((worst, ia, ib, i, chain[i] + sa * ra * normal, chain[i] + sb * rb * normal))
    out.sort(key=lambda t: t[0])
    return out


def biarc_coarse(
    chain: np.ndarray, splits: np.ndarray, turns: np.ndarray, radii_a: Sequence[float], radii_b: Sequence[float]
) -> dict[tuple[int, int], tuple[int, int, int]]:
    """The best biarc of :func:`closest_biarcs`'s coarse grid for every pair of radii: (ia, ib) -> (sides, split, turn).

    Sides index ``((-1, -1), (-1, 1), (1, -1), (1, 1))`` (the head's circle's and
    the tail's); every ``BIARC_STEP``-th pixel measured. The smallest largest
    distance over the sides and the grid, the first in that order on a tie.
    Compiled (:func:`img2logo._compiled.arcs.biarc_coarse_kernel`), a biarc's
    pixels stop being measured once it cannot beat the best so far: the same
    choice as the smallest of numpy's minima over the four grids of the two
    sides' :func:`biarc_worst`, and its argmin.
    """
    normal = biarc_normals(chain, splits, turns)  # shared by every radius and side
    from .._compiled import kernels

    base = chain[splits][:, None, :]
    heads = [np.stack([base + side * r * normal for side in (-1.0, 1.0)]) for r in radii_a]
    tails = [np.stack([base + side * r * normal for side in (-1.0, 1.0)]) for r in radii_b]
    index = np.arange(0, len(chain), BIARC_STEP)
    at = np.asarray(splits, dtype=np.int64)
    out = {}
    for ia, ra in enumerate(radii_a):
        for ib, rb in enumerate(radii_b):
            _, j, s, t = kernels.biarc_coarse_kernel(chain, index, at, heads[ia], tails[ib], ra, rb)
            out[ia, ib] = (int(j), int(s), int(t))
    return out


def biarc_fine(
    chain: np.ndarray, splits: np.ndarray, turns: np.ndarray, head: tuple[float, float], tail: tuple[float, float]
) -> tuple[float, int, int]:
    """The best biarc of a grid of ``splits`` and ``turns``: (largest pixel distance px, split index, turn index).

    ``head`` and ``tail`` are the two circles' (radius, side); every pixel is
    measured. The smallest over the grid of the larger of the head's and the
    tail's :func:`biarc_worst`, the first in row-major order on a tie. Compiled
    (:func:`img2logo._compiled.arcs.biarc_best_kernel`), a biarc's pixels stop
    being measured once it cannot beat the best so far: the same numbers as the
    two grids, a third of the work on the clip arts' joins.
    """
    (ra, sa), (rb, sb) = head, tail
    from .._compiled import kernels

    normal = biarc_normals(chain, splits, turns)
    base = chain[splits][:, None, :]
    worst, s, t = kernels.biarc_best_kernel(
        chain, base + sa * ra * normal, base + sb * rb * normal, np.asarray(splits, dtype=np.int64), ra, rb
    )
    return float(worst), int(s), int(t)


def biarc_normals(chain: np.ndarray, splits: np.ndarray, turns: np.ndarray) -> np.ndarray:
    """Unit normals (S, A, 2) of the chain's direction at pixels ``splits`` turned by ``turns`` rad."""
    n = len(chain)
    d = chain[np.minimum(splits + 3, n - 1)] - chain[np.maximum(splits - 3, 0)]
    theta = np.arctan2(d[:, 1], d[:, 0])[:, None] + turns[None, :]
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
