"""The image kernels against scipy.ndimage and scikit-image, whose results they give (imported by the tests only)."""

from __future__ import annotations

import numpy as np
import pytest

from img2logo._compiled import kernels, ndimage as kernels_ndimage


def _blobs(seed: int, shape: tuple[int, int] | None = None, fill: float = 0.55) -> np.ndarray:
    """A random mask of blobs and lines: a thresholded, smoothed noise image (many ties and corners)."""
    import cv2

    rng = np.random.default_rng(seed)
    h, w = shape if shape is not None else tuple(int(v) for v in rng.integers(1, 70, 2))
    noise = rng.random((h, w)).astype(np.float32)
    smooth = cv2.GaussianBlur(noise, (0, 0), float(rng.uniform(0.5, 3.0)))
    return smooth > np.quantile(smooth, 1.0 - fill)


def test_the_thinning_table_is_scikit_images():
    """Every neighbourhood: a pixel whose 8 neighbours are coded ``code``, thinned as skimage thins it."""
    from skimage.morphology import skeletonize

    table = kernels_ndimage.ZHANG_SUEN_TABLE
    assert table.shape == (256,) and set(np.unique(table).tolist()) <= {0, 1, 2, 3}
    for code in range(256):
        patch = np.zeros((7, 7), dtype=bool)
        patch[3, 3] = True
        for bit, (dr, dc) in enumerate(((-1, -1), (-1, 0), (-1, 1), (0, 1), (1, 1), (1, 0), (1, -1), (0, -1))):
            patch[3 + dr, 3 + dc] = bool((code >> bit) & 1)
        assert np.array_equal(kernels.thin_kernel(patch.view(np.uint8)), skeletonize(patch)), code


@pytest.mark.parametrize("seed", range(30))
def test_thinning_is_scikit_images(seed):
    from skimage.morphology import skeletonize

    mask = _blobs(seed)
    assert np.array_equal(kernels.thin_kernel(mask.view(np.uint8)), skeletonize(mask))


@pytest.mark.parametrize("seed", range(20))
@pytest.mark.parametrize("mode", ["reflect", "constant"])
def test_the_correlation_is_scipys_to_the_bit(seed, mode):
    from scipy import ndimage

    rng = np.random.default_rng(seed)
    shape = tuple(int(v) for v in rng.integers(1, 30, 3))
    for dtype, entry in ((np.float64, kernels.correlate_kernel), (np.float32, kernels.correlate32_kernel)):
        src = rng.normal(size=shape).astype(dtype)
        sd = float(rng.uniform(0.3, 6.0))
        radius = int(4.0 * sd + 0.5)
        phi = np.exp(-0.5 / (sd * sd) * np.arange(-radius, radius + 1) ** 2)
        for weights in ((phi / phi.sum())[::-1], np.array([-1.0, 0.0, 1.0]), rng.normal(size=5)):
            weights = np.ascontiguousarray(weights, dtype=np.float64)
            for axis in range(3):
                out = np.empty_like(src)
                view = (int(np.prod(shape[:axis])), shape[axis], int(np.prod(shape[axis + 1 :])))
                code = {"reflect": kernels_ndimage.REFLECT, "constant": kernels_ndimage.CONSTANT}[mode]
                entry(src.reshape(view), weights, code, 0.0, out.reshape(view))
                expected = ndimage.correlate1d(src, weights, axis, mode=mode, cval=0.0)
                assert out.dtype == expected.dtype and np.array_equal(out, expected), (dtype, axis, len(weights))


@pytest.mark.parametrize("seed", range(40))
def test_the_feature_transform_is_scipys(seed):
    from scipy import ndimage

    mask = _blobs(seed, fill=0.8)
    if seed % 10 == 0:
        mask[:] = True  # no outside pixel: scipy's answer, whatever it is
    features = kernels.feature_transform_kernel(mask.view(np.uint8))
    dist, indices = ndimage.distance_transform_edt(mask, return_indices=True)
    assert features.dtype == np.int32 and np.array_equal(features, indices)
    assert np.array_equal(kernels.edt_kernel(mask.view(np.uint8)), dist)  # the distances alone: Meijster's
