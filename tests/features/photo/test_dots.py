"""Tests of img2logo.features.photo.dots: a photo subject's dark dots."""

import numpy as np
import pytest

from img2logo.features.photo.dots import Dots, dark_dots, dot_radii, enclosed_dots


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


def test_a_catch_light_inside_a_dot_is_part_of_it():
    rgb, mask = _face(dots=((80, 100, 6.0),), size=(192, 256))
    yy, xx = np.mgrid[0 : rgb.shape[0], 0 : rgb.shape[1]]
    rgb[np.hypot(yy - 77, xx - 102) <= 1.5] = 0.95  # a catch light, off the dot's centre
    found = dark_dots(rgb, mask)
    assert found.count == 1 and found.region[77, 102]  # one dot, no hole: one outline


def _eye(size=(200, 300), iris=24.0, slit=(5.0, 14.0), pupil_at=(100, 150), catch=True, pupil_lines=True):
    """L* (face 75, iris 50, pupil 5, catch light 97), the lightness lines (the iris's loop, the
    pupil's outline: two 2 px rings) and the mask of a synthetic eye: a slit in a light iris."""
    h, w = size
    yy, xx = np.mgrid[0:h, 0:w]
    light = np.full((h, w), 75.0)
    d_iris = np.hypot(yy - 100, xx - 150)
    light[d_iris < iris] = 50.0
    a, b = slit
    d_pupil = np.hypot((yy - pupil_at[0]) / b, (xx - pupil_at[1]) / a)
    light[d_pupil < 1.0] = 5.0
    if catch:
        light[np.hypot(yy - pupil_at[0] + 6, xx - pupil_at[1] - 1) < 2.5] = 97.0
    lines = (d_iris >= iris - 2) & (d_iris < iris)
    if pupil_lines:
        lines |= (d_pupil < 1.0) & (d_pupil >= 1.0 - 2.0 / a)
    return light, lines, np.ones((h, w), bool)


def test_a_slit_pupil_with_a_catch_light_in_an_iris_is_one_dot():
    light, lines, mask = _eye()
    found = enclosed_dots(light, lines, mask)
    assert len(found) == 1
    (r0, c0), piece = found[0]
    dot = np.zeros(light.shape, bool)
    dot[r0 : r0 + piece.shape[0], c0 : c0 + piece.shape[1]] = piece
    slit = light <= 5.0
    assert (dot & slit).sum() > 0.95 * slit.sum()  # the whole slit ...
    assert dot[94, 151] and dot[100, 150]  # ... the catch light in it ...
    assert dot.sum() < 1.2 * np.pi * 5 * 14 and not dot[100, 158]  # ... and no more
    assert dark_dots(np.repeat((light / 100.0)[..., None], 3, axis=2), mask).count == 0  # no round blob
    assert dark_dots(np.repeat((light / 100.0)[..., None], 3, axis=2), mask, lines).count == 1


def test_no_pupil_without_a_closed_loop_a_dark_inside_or_a_centred_dot():
    light, lines, mask = _eye()
    open_loop = lines.copy()
    open_loop[70:80, 140:160] = False  # the iris's loop cut open at its top
    assert enclosed_dots(light, open_loop, mask) == []
    assert enclosed_dots(np.where(light < 60, 45.0, light), lines, mask) == []  # as dark as its iris
    light, lines, mask = _eye(slit=(0.1, 0.1), catch=False, pupil_lines=False)  # no pupil: a crease
    yy, xx = np.mgrid[-100:100, -150:150]
    arc = (np.abs(np.hypot(yy, xx) - 9.0) < 1.0) & (yy < 4)  # a dark curve, light inside it
    light[arc], lines[arc] = 5.0, True
    assert enclosed_dots(light, lines, mask) == []  # the relief of a coin: its hull is mostly light
    light[np.hypot(yy, xx) < 9.0] = 5.0
    assert len(enclosed_dots(light, lines, mask)) == 1  # filled: a pupil
    light, lines, mask = _eye(slit=(3.0, 6.0), pupil_at=(100, 166))  # a mark by the rim, off the centre
    assert enclosed_dots(light, lines, mask) == []
    light, lines, mask = _eye(size=(120, 160))  # an iris of 24 px is too large a loop in 160 px
    assert enclosed_dots(light, lines, mask) == []
    light, lines, mask = _eye()
    mask[90:110, 140:160] = False  # the pupil off the subject
    assert enclosed_dots(light, lines, mask) == []


def test_radii_follow_the_image_size():
    assert dot_radii((512, 384)) == (2.0, 16.0)
    assert dot_radii((10, 10)) == (2.0, 2.0)


def test_bad_input_is_refused():
    with pytest.raises(ValueError, match="rgb must be"):
        dark_dots(np.zeros((8, 8)), None)
    with pytest.raises(ValueError, match="mask must have"):
        dark_dots(np.zeros((8, 8, 3)), np.ones((4, 4), bool))
    with pytest.raises(ValueError, match="lines must have"):
        dark_dots(np.zeros((8, 8, 3)), None, np.ones((4, 4), bool))
