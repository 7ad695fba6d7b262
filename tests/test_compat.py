"""img2logo._compat: each function gives its library's result (the libraries are the oracles)."""

import numpy as np
from helpers import modules_loaded

from img2logo._compat import (
    circle_perimeter,
    intersect1d,
    line,
    median,
    nonzero,
    setdiff1d,
    union1d,
    unique,
    unique_rows,
)


def test_median_is_numpys_to_the_bit():
    rng = np.random.default_rng(4)
    for dtype in (np.float32, np.float64):
        for n in (1, 2, 3, 4, 9, 10, 11, 1000, 1001):
            values = (rng.standard_normal(n) * 100.0).astype(dtype)
            got, want = median(values), np.median(values)
            assert type(got) is type(want) and got == want
    assert np.isnan(median(np.array([1.0, np.nan, 3.0])))
    got = median(np.array([3, 1, 2, 8]))
    assert type(got) is np.float64 and got == 2.5


def test_unique_is_numpys():
    rng = np.random.default_rng(5)
    for n in (0, 1, 2, 7, 100):
        for dtype in (np.int32, np.int64):
            values = rng.integers(-5, 6, n).astype(dtype)
            got, want = unique(values), np.unique(values)
            assert got.dtype == want.dtype and np.array_equal(got, want)
    assert np.array_equal(unique(np.array([[3, 1], [1, 3]])), [1, 3])


def test_unique_rows_is_numpys_unique_along_rows():
    rng = np.random.default_rng(3)
    for _ in range(300):
        rows = rng.integers(0, 5, (int(rng.integers(0, 12)), int(rng.integers(2, 4))))
        got = unique_rows(rows)
        want = np.unique(rows.astype(np.int64), axis=0)
        assert got.dtype == np.int64 and got.shape == want.shape and (got == want).all()


def test_set_operations_are_numpys():
    rng = np.random.default_rng(7)
    for n, m in ((0, 0), (0, 3), (1, 1), (5, 9), (60, 40)):
        for dtype in (np.int32, np.int64):
            a, b = rng.integers(-4, 9, n).astype(dtype), rng.integers(0, 12, m).astype(np.int64)
            for ours, numpys in ((intersect1d, np.intersect1d), (setdiff1d, np.setdiff1d), (union1d, np.union1d)):
                got, want = ours(a, b), numpys(a, b)
                assert got.dtype == want.dtype and np.array_equal(got, want), (ours.__name__, n, m, dtype)
    assert np.array_equal(intersect1d(np.array([[3, 1], [1, 5]]), np.array([5, 5, 1])), [1, 5])


def test_nonzero_is_numpys():
    rng = np.random.default_rng(6)
    for h, w in ((0, 5), (1, 1), (7, 3), (40, 61)):
        mask = rng.random((h, w)) < 0.3
        got, want = nonzero(mask), np.nonzero(mask)
        assert all(g.dtype == np.int64 and np.array_equal(g, v) for g, v in zip(got, want, strict=True))


def test_line_is_skimages_pixel_for_pixel():
    from skimage.draw import line as oracle

    ends = [*np.random.default_rng(0).integers(-12, 40, (3000, 4)).tolist(), [3, 3, 3, 3], [0, 0, 5, 5]]
    for r0, c0, r1, c1 in ends:
        got, want = line(r0, c0, r1, c1), oracle(r0, c0, r1, c1)
        for g, w in zip(got, want, strict=True):
            assert g.dtype == w.dtype
            np.testing.assert_array_equal(g, w)


def test_circle_perimeter_is_skimages_pixel_for_pixel():
    from skimage.draw import circle_perimeter as oracle

    rng = np.random.default_rng(8)
    cases = [(int(a), int(b), int(k), (int(h) + 11, int(w) + 11)) for a, b, k, h, w in rng.integers(-10, 40, (2000, 5))]
    cases += [(4, 4, 3, (10, 10)), (0, 0, 0, (1, 1)), (2, 2, 5, (3, 3)), (200, 100, 60, (512, 320))]
    for r, c, radius, shape in cases:
        got, want = circle_perimeter(r, c, radius, shape), oracle(r, c, radius, shape=shape)
        for g, w in zip(got, want, strict=True):
            assert g.dtype == w.dtype
            np.testing.assert_array_equal(g, w)


def test_none_imports_numpy_ma_or_scikit_image():
    code = (
        "import sys, numpy as np\n"
        "from img2logo._compat import circle_perimeter, intersect1d, line, median, nonzero, setdiff1d, union1d\n"
        "from img2logo._compat import unique\n"
        "median(np.arange(5.0)); unique(np.array([2, 1, 2])); nonzero(np.eye(3)); line(0, 0, 3, 5)\n"
        "circle_perimeter(4, 4, 3, (10, 10))\n"
        "a, b = np.array([3, 1, 3]), np.array([1, 2]); intersect1d(a, b); setdiff1d(a, b); union1d(a, b)\n"
    )
    assert modules_loaded(code, "numpy.ma", "skimage", "scipy") == []
