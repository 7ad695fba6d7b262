"""The tangent biarcs' compiled searches against their Python references, on seeded chains, to the bit."""

from __future__ import annotations

import math

import numpy as np
import pytest

from img2logo._compiled import kernels

# The Python references of the biarc searches (img2logo.fit.biarcs): their oracles. Every biarc
# measured on every pixel of its side, no search stopped early and nothing kept between pairs.


def _largest(chain: np.ndarray, pixels: np.ndarray, centre: np.ndarray, radius: float) -> float:
    """The largest distance of ``chain[pixels]`` from the circle (centre (2,), radius), px; 0 for no pixel."""
    if not len(pixels):
        return 0.0
    p = chain[pixels]
    return float(np.max(np.abs(np.hypot(p[:, 0] - centre[0], p[:, 1] - centre[1]) - radius)))


def coarse_reference(
    chain: np.ndarray,
    index: np.ndarray,
    splits: np.ndarray,
    heads: np.ndarray,
    tails: np.ndarray,
    radii_a: np.ndarray,
    radii_b: np.ndarray,
) -> np.ndarray:
    """``biarc_coarse_kernel`` in Python: per pair of radii the first (j, s, a) of the smallest largest distance."""
    out = np.zeros((len(radii_a), len(radii_b), 3), dtype=np.int64)
    for ia, ra in enumerate(radii_a):
        for ib, rb in enumerate(radii_b):
            best, where = math.inf, (0, 0, 0)
            for j in range(4):
                side_a, side_b = j // 2, j % 2
                for s, split in enumerate(splits):
                    for a in range(heads.shape[3]):
                        worst = max(
                            _largest(chain, index[index <= split], heads[ia, side_a, s, a], ra),
                            _largest(chain, index[index >= split], tails[ib, side_b, s, a], rb),
                        )
                        if worst < best:
                            best, where = worst, (j, s, a)
            out[ia, ib] = where
    return out


def fine_reference(
    chain: np.ndarray,
    heads: np.ndarray,
    tails: np.ndarray,
    splits: np.ndarray,
    counts: np.ndarray,
    radii_a: np.ndarray,
    radii_b: np.ndarray,
    most: int,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``biarc_fine_kernel`` in Python: each grid's first argmin; with ``most``, none for a grid that cannot be
    among the ``most`` smallest minima of the grids so far (an earlier grid first on a tie)."""
    n = len(chain)
    every = np.arange(n)
    worst_out = np.full(len(counts), math.inf)
    s_out = np.full(len(counts), -1, dtype=np.int64)
    a_out = np.full(len(counts), -1, dtype=np.int64)
    minima: list[float] = []
    for p, count in enumerate(counts):
        best, where = math.inf, (-1, -1)
        for s in range(count):
            split = splits[p, s]
            for a in range(heads.shape[2]):
                worst = max(
                    _largest(chain, every[: split + 1], heads[p, s, a], radii_a[p]),
                    _largest(chain, every[split:], tails[p, s, a], radii_b[p]),
                )
                if worst < best:
                    best, where = worst, (s, a)
        before = sorted(minima)
        minima.append(best)
        if most > 0 and len(before) >= most and best >= before[most - 1]:
            continue
        worst_out[p], (s_out[p], a_out[p]) = best, where
    return worst_out, s_out, a_out


def _chain(rng: np.random.Generator, n: int) -> np.ndarray:
    """``n`` pixels (N, 2) of two arcs of random radii that meet at the middle, rounded to the grid."""
    t = np.linspace(0.0, rng.uniform(0.5, 2.5), n)
    radius = rng.uniform(10.0, 150.0)
    pts = np.stack([radius * np.cos(t), radius * np.sin(t)], 1)
    pts[n // 2 :] += rng.normal(0.0, 0.3) * (np.arange(n - n // 2)[:, None] ** 1.5) / n
    return np.round(pts + rng.normal(0, 0.6, (n, 2))) + 200.5


@pytest.mark.parametrize("seed", range(8))
def test_the_coarse_search_is_its_references_choice(seed):
    # Several pairs share each head's and each tail's circle (kept between them in the kernel),
    # repeated turns make ties: the same sides, split and turn as the reference's, for every pair.
    rng = np.random.default_rng(seed)
    n = int(rng.integers(12, 90))
    chain = _chain(rng, n)
    splits = np.sort(rng.integers(1, n - 1, int(rng.integers(1, 9)))).astype(np.int64)
    n_turns = int(rng.integers(1, 6))
    index = np.arange(0, n, int(rng.integers(1, 5)), dtype=np.int64)
    radii_a = rng.uniform(8.0, 200.0, int(rng.integers(1, 4)))
    radii_b = rng.uniform(8.0, 200.0, int(rng.integers(1, 4)))
    angle = rng.uniform(0, 2 * np.pi, (len(splits), n_turns))
    angle[:, -1] = angle[:, 0]  # a tie
    normal = np.stack([-np.sin(angle), np.cos(angle)], -1)
    base = chain[splits][:, None, :]
    heads = np.stack([np.stack([base + side * r * normal for side in (-1.0, 1.0)]) for r in radii_a])
    tails = np.stack([np.stack([base + side * r * normal for side in (-1.0, 1.0)]) for r in radii_b])
    got = kernels.biarc_coarse_kernel(chain, index, splits, heads, tails, radii_a, radii_b)
    assert np.array_equal(got, coarse_reference(chain, index, splits, heads, tails, radii_a, radii_b))


@pytest.mark.parametrize("seed", range(8))
@pytest.mark.parametrize("most", [0, 1, 2, 3])
def test_the_fine_search_is_its_references_argmin(seed, most):
    # Grids of several pairs, a repeated one among them (a tie between pairs), padded splits past
    # each grid's count: each grid's value and place, and the grids cut exactly where the reference's are.
    rng = np.random.default_rng(100 + seed)
    n = int(rng.integers(12, 90))
    chain = _chain(rng, n)
    n_pairs, width, n_turns = int(rng.integers(1, 7)), int(rng.integers(1, 8)), int(rng.integers(1, 6))
    counts = rng.integers(1, width + 1, n_pairs).astype(np.int64)
    splits = np.sort(rng.integers(1, n - 1, (n_pairs, width)), axis=1).astype(np.int64)
    angle = rng.uniform(0, 2 * np.pi, (n_pairs, width, n_turns))
    radii_a, radii_b = rng.uniform(8.0, 200.0, n_pairs), rng.uniform(8.0, 200.0, n_pairs)
    normal = np.stack([-np.sin(angle), np.cos(angle)], -1)
    base = chain[splits][:, :, None, :]
    heads = base + (rng.choice([-1.0, 1.0], n_pairs) * radii_a)[:, None, None, None] * normal
    tails = base + (rng.choice([-1.0, 1.0], n_pairs) * radii_b)[:, None, None, None] * normal
    if n_pairs > 1:
        for a in (heads, tails, splits, counts, radii_a, radii_b):
            a[-1] = a[0]
    got = kernels.biarc_fine_kernel(chain, heads, tails, splits, counts, radii_a, radii_b, most)
    want = fine_reference(chain, heads, tails, splits, counts, radii_a, radii_b, most)
    for g, w in zip(got, want, strict=True):
        assert np.array_equal(g, w)
