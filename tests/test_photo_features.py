"""Tests of img2logo.photo_features: a photo subject's dark dots."""

import numpy as np
import pytest

from img2logo.photo_features import Dots, dark_dots, dot_radii


def _face(dots=((40, 40, 5.0),), size=(96, 128), face=0.8, dot=0.15, noise=0.0, seed=0):
    """A light disc of a face on a darker ground, with dark dots (row, col, radius)."""
    rng = np.random.default_rng(seed)
    h, w = size
    yy, xx = np.mgrid[0:h, 0:w]
    mask = np.hypot(yy - h / 2, xx - w / 2) < 0.45 * min(h, w)
    gray = np.where(mask, face, 0.3)
    for r, c, rad in dots:
        gray = np.where(np.hypot(yy - r, xx - c) <= rad, dot, gray)
    gray = np.clip(gray + rng.normal(0.0, noise, gray.shape), 0.0, 1.0)
    return np.repeat(gray[..., None], 3, axis=2), mask


def test_two_eyes_are_found_with_their_discs():
    rgb, mask = _face(dots=((40, 50, 5.0), (40, 78, 5.0)))
    found = dark_dots(rgb, mask)
    assert isinstance(found, Dots) and found.count == 2
    assert found.region[40, 50] and found.region[40, 78] and not found.region[60, 64]
    assert 0.7 < found.region.sum() / (2 * np.pi * 25) < 1.3  # the dots' own area, not the ring's


def test_a_dot_off_the_subject_or_faint_or_on_texture_is_not_one():
    rgb, mask = _face(dots=((8, 8, 4.0),))  # on the ground, outside the subject
    assert dark_dots(rgb, mask).count == 0
    rgb, mask = _face(dot=0.75)  # 5 L* darker: shading
    assert dark_dots(rgb, mask).count == 0
    rgb, mask = _face(noise=0.2)  # the surround varies as much as the dot is dark
    assert dark_dots(rgb, mask).count == 0


def test_a_dark_stroke_is_no_dot():
    rgb, mask = _face(dots=())
    rgb[45:49, 30:100] = 0.1  # a line across the face
    assert dark_dots(rgb, mask).count == 0


def test_a_speck_is_no_dot_and_no_mask_is_the_whole_image():
    rgb, _ = _face(dots=((48, 64, 2.0),))
    assert dark_dots(rgb, None).count == 0  # 13 px: under MIN_SPECK_AREA
    rgb, _ = _face(dots=((48, 64, 3.5),))  # 128 px: dots up to 4 px
    assert dark_dots(rgb, None).count == 1


def test_radii_follow_the_image_size():
    assert dot_radii((512, 384)) == (2.0, 16.0)
    assert dot_radii((10, 10)) == (2.0, 2.0)


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="rgb must be"):
        dark_dots(np.zeros((8, 8)), None)
    with pytest.raises(ValueError, match="mask must have"):
        dark_dots(np.zeros((8, 8, 3)), np.ones((4, 4), bool))
