"""img2logo.images.ndimage: numpy's median without numpy.ma (scipy's filters: tests/features/photo/test_subject.py)."""

import subprocess
import sys

import numpy as np

from img2logo.images.ndimage import median


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


def test_neither_imports_numpy_ma():
    code = (
        "import sys, numpy as np\n"
        "from img2logo.images.ndimage import median\nfrom img2logo.images.skeleton import unique\n"
        "median(np.arange(5.0)); unique(np.array([2, 1, 2]))\n"
        "print('numpy.ma' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
