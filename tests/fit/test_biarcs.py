"""The tangent biarcs closest to a pixel chain: found, and their kernels against the numpy references."""

from __future__ import annotations

import numpy as np
import pytest


def test_a_biarc_is_found_where_its_two_circles_touch():
    from img2logo.fit.biarcs import closest_biarcs

    # A smooth line of two tangent circles, radii 50 and 80 px, touching at (0, 0) with the
    # common tangent along x: the head on the circle centred (0, 50), the tail on (0, -80).
    head = np.column_stack([50 * np.sin(t := np.linspace(-1.2, 0.0, 61)), 50 - 50 * np.cos(t)])
    tail = np.column_stack([80 * np.sin(u := np.linspace(0.0, 0.75, 61)[1:]), -80 + 80 * np.cos(u)])
    chain = np.vstack([head, tail])
    found = closest_biarcs(chain, [30.0, 50.0, 80.0], [50.0, 80.0, 130.0])
    worst, ia, ib, i, ca, cb = found[0]
    # The radii of the line, the junction at the touching point, the circles where they are.
    assert (ia, ib) == (1, 1) and i == 60 and worst < 0.5  # the finer grid turns by 1 degree
    assert np.allclose(ca, (0.0, 50.0), atol=1.0) and np.allclose(cb, (0.0, -80.0), atol=1.5)
    # The circles touch: the junction on the line of centres, at both radii.
    assert np.hypot(*(ca - chain[i])) == pytest.approx(50.0) and np.hypot(*(cb - chain[i])) == pytest.approx(80.0)
    assert found == sorted(found, key=lambda f: f[0]) and found[-1][0] > 1.0
    # Too short a chain for a junction with SLIDE_MIN_PIXELS on both sides: none.
    assert closest_biarcs(chain[:6], [50.0], [80.0]) == []


def noisy_arc(rng: np.random.Generator, n: int) -> tuple[np.ndarray, float]:
    """``n`` pixels (N, 2) of an arc of a random radius (returned, px) and turn, with noise, rounded to the grid."""
    t = np.linspace(0.0, rng.uniform(0.5, 3.0), n)
    radius = rng.uniform(10.0, 200.0)
    return np.round(np.stack([radius * np.cos(t), radius * np.sin(t)], 1) + rng.normal(0, 0.7, (n, 2))) + 100.5, radius


def biarc_worst_reference(
    chain: np.ndarray, centre: np.ndarray, index: np.ndarray, splits: np.ndarray, r: float, head: bool
) -> np.ndarray:
    """``biarc_worst`` in numpy past the centres (S, A, 2): the oracle of its compiled kernel."""
    sample = chain[index]
    dist = np.abs(np.hypot(sample[:, 0] - centre[..., :1], sample[:, 1] - centre[..., 1:]) - r)  # (S, A, m)
    mine = index[None, :] <= splits[:, None] if head else index[None, :] >= splits[:, None]
    return np.where(mine[:, None, :], dist, 0.0).max(axis=-1)


def test_biarc_worst_kernel_matches_the_numpy_reference():
    # The compiled kernel measures each side's pixels only: the same bits as the reference.
    from img2logo.fit.biarcs import biarc_normals, biarc_worst

    rng = np.random.default_rng(5)
    for _ in range(40):
        n = int(rng.integers(20, 120))
        chain, _ = noisy_arc(rng, n)
        splits, turns = np.arange(4, n - 5, 3), np.linspace(-0.3, 0.3, 7)
        for head in (True, False):
            for stride in (1, 3):
                r, side = rng.uniform(5.0, 300.0), float(rng.choice([-1.0, 1.0]))
                centre = chain[splits][:, None, :] + side * r * biarc_normals(chain, splits, turns)
                index = np.arange(0, n, stride)
                expected = biarc_worst_reference(chain, centre, index, splits, r, head)
                assert np.array_equal(biarc_worst(chain, splits, turns, r, side, head, stride), expected)


def test_biarc_fine_search_is_the_grids_argmin():
    # The compiled search stops measuring a biarc once it cannot win: for each grid the same
    # value and the same place as numpy's argmin over the two grids' maximum, the first one on
    # a tie (repeated splits and turns make ties); with ``most``, None exactly for the grids
    # that cannot be among the ``most`` smallest (an earlier grid first on a tie).
    from img2logo.fit.biarcs import biarc_fine, biarc_worst

    rng = np.random.default_rng(11)
    for _ in range(40):
        n = int(rng.integers(20, 120))
        chain, _ = noisy_arc(rng, n)
        grids = []
        for _ in range(int(rng.integers(1, 7))):
            splits = np.sort(rng.integers(4, n - 5, int(rng.integers(1, 10))))
            turns = np.sort(np.concatenate([rng.uniform(-0.3, 0.3, 5), [0.0, 0.0]]))
            head = (rng.uniform(5.0, 300.0), float(rng.choice([-1.0, 1.0])))
            tail = (rng.uniform(5.0, 300.0), float(rng.choice([-1.0, 1.0])))
            grids.append((splits, turns, head, tail))
        if rng.random() < 0.3:
            grids.append(grids[0])  # a tie between two grids: the earlier one is kept
        expected = []
        for splits, turns, head, tail in grids:
            w = np.maximum(
                biarc_worst(chain, splits, turns, *head, True, 1), biarc_worst(chain, splits, turns, *tail, False, 1)
            )
            s, a = np.unravel_index(int(np.argmin(w)), w.shape)
            expected.append((float(w[s, a]), int(s), int(a)))
        args = [list(g) for g in zip(*grids, strict=True)]
        assert biarc_fine(chain, *args) == expected
        for most in (1, 2, 3):
            got = biarc_fine(chain, *args, most=most)
            for p, (g, e) in enumerate(zip(got, expected, strict=True)):
                before = sorted(x[0] for x in expected[:p])
                hopeless = len(before) >= most and e[0] >= before[most - 1]
                assert g == (None if hopeless else e)


def test_the_first_biarcs_alone_are_the_first_of_all():
    from img2logo.fit.biarcs import closest_biarcs

    rng = np.random.default_rng(13)
    for _ in range(30):
        n = int(rng.integers(8, 160))
        chain, radius = noisy_arc(rng, n)
        radii_a = list(rng.uniform(5.0, 300.0, int(rng.integers(1, 4))))
        radii_b = [radius, *rng.uniform(5.0, 300.0, int(rng.integers(0, 3)))]
        every = closest_biarcs(chain, radii_a, radii_b)
        for most in (1, 2, 4):
            first = closest_biarcs(chain, radii_a, radii_b, most)
            assert len(first) == min(most, len(every))
            for got, want in zip(first, every, strict=False):
                assert got[:4] == want[:4] and np.array_equal(got[4], want[4]) and np.array_equal(got[5], want[5])


def test_biarc_coarse_search_is_the_grids_choice():
    # The compiled coarse search stops measuring a biarc once it cannot win: for every pair of
    # radii the same sides and place as the smallest of the four grids' minima (numpy's
    # maximum of the two sides' grids), and its argmin, the first on a tie.
    from img2logo.fit.biarcs import biarc_coarse, biarc_normals, biarc_worst
    from img2logo.fit.constants import BIARC_STEP

    sides = ((-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0))
    rng = np.random.default_rng(12)
    for _ in range(20):
        n = int(rng.integers(30, 200))
        chain, radius = noisy_arc(rng, n)
        splits = np.arange(5, n - 5, 4)
        turns = np.sort(np.concatenate([rng.uniform(-0.4, 0.4, 6), [0.0, 0.0]]))
        radii_a, radii_b = list(rng.uniform(5.0, 300.0, 2)), [radius, *rng.uniform(5.0, 300.0, 2)]
        normal = biarc_normals(chain, splits, turns)
        got = biarc_coarse(chain, splits, turns, radii_a, radii_b)
        for ia, ra in enumerate(radii_a):
            for ib, rb in enumerate(radii_b):
                w = [
                    np.maximum(
                        biarc_worst(chain, splits, turns, ra, sa, True, BIARC_STEP, normal),
                        biarc_worst(chain, splits, turns, rb, sb, False, BIARC_STEP, normal),
                    )
                    for sa, sb in sides
                ]
                j = min(range(4), key=lambda j: float(w[j].min()))
                s, a = np.unravel_index(int(np.argmin(w[j])), w[j].shape)
                assert got[ia, ib] == (j, int(s), int(a))
