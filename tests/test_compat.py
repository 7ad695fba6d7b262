"""img2logo._compat: each function gives its library's result (the libraries are the oracles)."""

import numpy as np
from helpers import modules_loaded

from img2logo._compat import line, median, nonzero, unique


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


def test_none_imports_numpy_ma_or_scikit_image():
    code = (
        "import sys, numpy as np\n"
        "from img2logo._compat import line, median, nonzero, unique\n"
        "median(np.arange(5.0)); unique(np.array([2, 1, 2])); nonzero(np.eye(3)); line(0, 0, 3, 5)\n"
    )
    assert modules_loaded(code, "numpy.ma", "skimage", "scipy") == []
