"""sRGB to CIELAB without scikit-image: scikit-image's numbers (the oracle, imported by the tests only)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from img2logo._cielab import rgb2lab
from img2logo.loading import load_image

DATA = Path(__file__).resolve().parents[1] / "data"


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
