"""sRGB to CIELAB without scikit-image: scikit-image's numbers (the oracle, imported by the tests only)."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np
import pytest

from img2logo.images.cielab import rgb2lab, srgb_to_lab
from img2logo.images.loading import load_image

DATA = Path(__file__).resolve().parents[2] / "data"


@pytest.mark.parametrize("shape", [(1, 1, 3), (7, 1, 3), (1, 9, 3), (31, 17, 3), (5, 3)])
def test_rgb2lab_is_skimages_to_the_bit(shape):
    from skimage.color import rgb2lab as oracle

    rgb = np.random.default_rng(len(shape) + shape[0]).random(shape)
    rgb.flat[:4] = [0.0, 1.0, 0.04045, 0.0031]  # the ends and the gamma's joint
    np.testing.assert_array_equal(rgb2lab(rgb), oracle(rgb))


@pytest.mark.parametrize("name", ["clipart-fish", "drawing-rabbit", "photo-cat"])
def test_rgb2lab_of_an_image_is_skimages(name):
    from skimage.color import rgb2lab as oracle

    rgb = load_image(DATA / f"{name}.png").rgb
    np.testing.assert_array_equal(rgb2lab(rgb), oracle(rgb))


def test_other_dtypes_go_to_skimage():
    from skimage.color import rgb2lab as oracle

    rgb = np.random.default_rng(1).integers(0, 256, (4, 4, 3)).astype(np.uint8)
    np.testing.assert_array_equal(rgb2lab(rgb), oracle(rgb))


def test_srgb_to_lab_is_scikit_images_rgb2lab():
    """Once per colour of an 8-bit image, the same bits as the whole image's conversion."""
    from skimage.color import rgb2lab

    rng = np.random.default_rng(3)
    for colours in (2, 50, 5000):
        palette = rng.integers(0, 256, (colours, 3))
        rgb = palette[rng.integers(0, colours, (60, 70))] / 255.0
        assert np.array_equal(srgb_to_lab(rgb), rgb2lab(rgb))
    blurred = cv2.GaussianBlur(rgb, (5, 5), 1.0)  # not 8-bit: converted whole
    assert np.array_equal(srgb_to_lab(blurred), rgb2lab(blurred))
    for name in ("clipart-fish.png", "drawing-rabbit.png", "photo-cat.png"):
        rgb = load_image(DATA / name).rgb
        assert np.array_equal(srgb_to_lab(rgb), rgb2lab(rgb))


def test_the_colour_table_kernel_is_numpys_unique():
    # The compiled table of an 8-bit image's colours: the same colours, order and places as np.unique's.
    from img2logo._compiled import kernels

    rng = np.random.default_rng(7)
    images = [rng.integers(0, 256, (40, 50, 3)) / 255.0, load_image(DATA / "photo-cat.png").rgb]
    images.append(rng.integers(0, 4, (9, 7, 3)) / 255.0)
    for rgb in images:
        ok, colours, index = kernels.colour_table_kernel(np.ascontiguousarray(rgb))
        v = np.rint(rgb * 255.0).astype(np.int64)
        want, want_index = np.unique(((v[..., 0] << 16) | (v[..., 1] << 8) | v[..., 2]).ravel(), return_inverse=True)
        assert ok and np.array_equal(colours, want) and np.array_equal(index, want_index)
    blurred = cv2.GaussianBlur(images[0], (5, 5), 1.0)  # not 8-bit
    assert not kernels.colour_table_kernel(np.ascontiguousarray(blurred))[0]
