"""Tests of img2logo.photo: a photo's outline, inner lines and their joins."""

from __future__ import annotations

import numpy as np
from helpers import textured_photo
from scipy import ndimage

from img2logo import extract_feature_lines, load_image
from img2logo.photo import join_line_ends, photo_feature_lines, subject_outline
from img2logo.subject import Subject


def test_photo_lines_are_the_outline_and_inner_lines_of_the_subject_only():
    rgb, (truth,) = textured_photo([(170, 120, 80, 60, (0.95, 0.75, 0.2))])
    fl = extract_feature_lines(rgb, kind="photo")
    assert fl.subject is not None and fl.subject.method == "auto"
    lines = fl.lines
    # Nothing on the background ...
    near = ndimage.binary_dilation(truth, iterations=3)
    assert lines.any() and not (lines & ~near).any()
    # ... the silhouette, whole, within 3 px ...
    edge = truth & ~ndimage.binary_erosion(truth)
    dist = ndimage.distance_transform_edt(~lines)
    assert np.mean(dist[edge] <= 3) > 0.98
    # ... and the inner stripe (y = 120 +- 7) inside it.
    assert lines[105:136, 120:220].sum() > 100


def test_subject_outline_is_closed_and_leaves_out_the_image_frame():
    mask = np.zeros((100, 120), bool)
    yy, xx = np.mgrid[0:100, 0:120]
    mask[np.hypot(xx - 40, yy - 50) < 30] = True
    out = subject_outline(mask)
    # A closed 8-connected curve: one piece, and every pixel has two neighbours or more.
    _, n = ndimage.label(out, structure=np.ones((3, 3)))
    assert n == 1
    nb = ndimage.convolve(out.astype(int), np.ones((3, 3), int), mode="constant") - 1
    assert (nb[out] >= 2).all()
    r = np.hypot(*(np.argwhere(out)[:, ::-1] + 0.5 - (40.5, 50.5)).T)
    assert np.all(np.abs(r - 30) < 1.5)
    # An object cut by the right edge: no line along the frame.
    mask2 = np.hypot(xx - 110, yy - 50) < 30
    out2 = subject_outline(mask2)
    assert out2.any() and not out2[:, -2:].any()


def test_two_line_ends_3_px_apart_are_joined():
    skel = np.zeros((40, 60), bool)
    skel[20, 5:28] = True  # ends at column 27
    skel[20, 31:55] = True  # starts at column 31: a 3 px gap
    skel[5, 5:20] = True  # far from everything: left alone
    out = join_line_ends(skel)
    assert out[20, 5:55].all()
    _, n = ndimage.label(out, structure=np.ones((3, 3)))
    assert n == 2
    np.testing.assert_array_equal(out[:15], skel[:15])


def test_a_line_end_near_another_line_makes_a_junction():
    skel = np.zeros((40, 40), bool)
    skel[5:35, 20] = True  # vertical line
    skel[18, 2:16] = True  # stops 4 px short of it
    out = join_line_ends(skel)
    assert out[18, 2:21].all()
    assert out.sum() == skel.sum() + 4


def test_an_inner_line_that_runs_into_the_outline_is_carried_on_to_it():
    from img2logo.photo import reach_outline

    outline = np.zeros((60, 80), bool)
    outline[10, 5:75] = True  # the outline along the top
    lines = np.zeros_like(outline)
    lines[18:50, 40] = True  # an edge between two regions: stops 8 px under the outline
    lines[16, 10:30] = True  # runs beside the outline 6 px inside it: left alone
    out = reach_outline(lines, outline)
    assert out[10:50, 40].all()  # carried straight up onto the outline
    np.testing.assert_array_equal(out[:, :35], lines[:, :35])
    far = np.zeros_like(outline)
    far[30:50, 60] = True  # 20 px away: more than the margin and the join distance
    np.testing.assert_array_equal(reach_outline(far, outline), far)
    assert not reach_outline(np.zeros_like(outline), outline).any()


def test_a_scene_draws_the_whole_image():
    rgb, _ = textured_photo([(170, 120, 80, 60, (0.95, 0.75, 0.2))])
    img = load_image(rgb)
    fl = extract_feature_lines(img, kind="photo", foreground="none")
    assert fl.subject.mask is None and fl.subject.method == "none"
    whole = Subject(None, "none", "")
    from img2logo.photo import photo_feature_lines

    assert photo_feature_lines(img, whole).shape == (240, 320)


def test_a_short_branch_beside_its_sibling_is_removed():
    # A fork: a long line and a 10 px branch leaving it at a small angle, its
    # end 3 px from the line. Joining it would make a sliver; it is a spur.
    skel = np.zeros((30, 60), bool)
    skel[20, 5:55] = True
    for i in range(1, 11):
        skel[20 - (i + 2) // 4, 20 + i] = True
    out = join_line_ends(skel)
    np.testing.assert_array_equal(out[20], skel[20])
    assert out[:19].sum() <= 1  # the branch is gone (a stub of 1 px at most next to the fork)


def test_a_portrait_keeps_the_eyes_and_mouth_inside_the_face():
    from skimage import data

    from img2logo.photo import face_region

    rgb = data.astronaut()  # ships with scikit-image
    fl = extract_feature_lines(rgb, kind="photo")
    faces = fl.subject.faces
    assert len(faces) == 1
    face = face_region(fl.lines.shape, faces)
    dist = ndimage.distance_transform_edt(~fl.lines)
    # eyes at about (205, 100) and (248, 100), the mouth at about (232, 132): (x, y) px
    for x, y in ((205, 100), (248, 100), (232, 132)):
        assert dist[y, x] <= 6, (x, y)
    # Drawn without its face, the photo loses them: they are shorter than a photo's shortest line.
    img = load_image(rgb)
    bare = photo_feature_lines(img, Subject(fl.subject.mask, "mask", "the same mask, no face"))
    assert (photo_feature_lines(img, fl.subject) & face).sum() > 2 * (bare & face).sum()
