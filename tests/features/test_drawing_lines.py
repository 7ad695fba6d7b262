"""Tests of img2logo.features.drawing_lines: stroke width, blur and threshold against their references."""

from __future__ import annotations

import numpy as np
from helpers import random_masks


def test_median_stroke_width_known_answers():
    from img2logo.features.drawing_lines import median_stroke_width

    ink = np.zeros((100, 100), dtype=bool)
    assert median_stroke_width(ink) == 0.0
    ink[40:50, 10:90] = True  # a bar 10 px wide
    assert abs(median_stroke_width(ink) - 10.0) <= 1.0


def test_drawing_blur_and_threshold_match_ndimage_and_skimage() -> None:
    # A drawing's run avoids scipy.ndimage and skimage.filters (which imports it): about 0.1 s of CPU.
    from scipy import ndimage
    from skimage.filters import threshold_otsu

    from img2logo.features.drawing_lines import gaussian_blur, otsu_threshold

    rng = np.random.default_rng(6)
    for mask in random_masks(60, 6):
        image = mask * rng.uniform(0.2, 1.0) + rng.random(mask.shape) * rng.uniform(0.0, 0.3)
        for sigma in (1.0, 0.7, 2.5):
            expected = ndimage.gaussian_filter(image, sigma)
            assert np.array_equal(gaussian_blur(image, sigma).view(np.uint64), expected.view(np.uint64))
        assert otsu_threshold(image) == threshold_otsu(image)
    assert otsu_threshold(np.full((4, 5), 0.25)) == 0.25  # one grey: skimage returns it


def test_keep_dots_circles_bare_parts_at_scipys_centres_of_mass() -> None:
    from scipy import ndimage

    from img2logo._compat import circle_perimeter
    from img2logo.features.constants import DOT_MIN_DIAMETER, DOT_MIN_RADIUS
    from img2logo.features.drawing_lines import keep_dots

    rng = np.random.default_rng(3)
    for mask in random_masks(40, 9):
        lines = np.zeros(mask.shape, dtype=bool)
        lines[: mask.shape[0] // 3] = mask[: mask.shape[0] // 3]  # the parts reaching the top third have a line
        labels, n = ndimage.label(mask, structure=np.ones((3, 3)))
        stroke = float(rng.uniform(0.0, 4.0))
        expected = lines.copy()
        for k in range(1, n + 1):
            part = labels == k
            diameter = 2.0 * np.sqrt(part.sum() / np.pi)
            if (part & lines).any() or diameter < DOT_MIN_DIAMETER:
                continue
            r, c = ndimage.center_of_mass(mask, labels, k)
            radius = max(DOT_MIN_RADIUS, (diameter - stroke) / 2.0)
            rr, cc = circle_perimeter(round(r), round(c), round(radius), mask.shape)
            expected[rr, cc] = True
        assert np.array_equal(keep_dots(lines, mask, stroke), expected)
