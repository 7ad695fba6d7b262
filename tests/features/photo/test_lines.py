"""Tests of img2logo.features.photo.lines: a photo's outline, inner lines and their joins."""

from __future__ import annotations

import numpy as np
from helpers import modules_loaded, textured_photo
from scipy import ndimage

from img2logo import extract_feature_lines, load_image
from img2logo.features.photo.lines import join_line_ends, photo_feature_lines, subject_outline
from img2logo.features.photo.subject import Subject


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
    from img2logo.features.photo.lines import reach_outline

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
    from img2logo.features.photo.lines import photo_feature_lines

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

    from img2logo.features.photo.lines import face_region

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


def test_a_slit_pupil_with_a_catch_light_is_drawn_as_one_outline():
    from img2logo.features.photo.line_maps import line_maps
    from img2logo.features.photo.lines import subject_dots

    # A light iris (radius 24 px) on a lighter face, a dark vertical slit (5 x 14 px) in it and a
    # bright catch light in the slit: the lightness lines go round the slit and the catch light.
    h, w = 200, 300
    yy, xx = np.mgrid[0:h, 0:w]
    gray = np.full((h, w), 0.75)
    gray[np.hypot(yy - 100, xx - 150) < 24] = 0.5
    gray[np.hypot((yy - 100) / 14.0, (xx - 150) / 5.0) < 1.0] = 0.05
    gray[np.hypot(yy - 94, xx - 151) < 2.5] = 0.97
    img = load_image(np.repeat(ndimage.gaussian_filter(gray, 1.0)[..., None], 3, axis=2))
    subject = Subject(np.ones((h, w), bool), "mask", "the whole image")
    maps = line_maps(img)
    dots = subject_dots(img, subject, maps)
    assert dots.count == 1 and dots.region[94, 151] and dots.region[108, 150]
    lines = photo_feature_lines(img, subject, dots, maps)
    labels, n = ndimage.label(lines, structure=np.ones((3, 3)))
    assert n == 2  # the iris's loop and the pupil's outline
    pupil = ndimage.binary_fill_holes(labels == labels[100, 150 + np.flatnonzero(lines[100, 150:])[0]])
    assert pupil[94, 151] and pupil[100, 150] and not lines[92:97, 149:154].any()  # the catch light inside it
    assert not pupil[100, 160]  # and the iris outside
    assert subject_dots(img, subject).count == 0  # without the lines: a slit is no round blob


def _two_discs(noise=0.01, seed=0):
    """Tan ground; a pink disc of the ground's own luminance (a colour edge only) at (80, 60)
    and a dark red one (a lightness edge too) at (200, 60), radius 30 px: RGB (120, 280, 3)."""
    rng = np.random.default_rng(seed)
    h, w = 120, 280
    yy, xx = np.mgrid[0:h, 0:w]
    tan = np.array([0.75, 0.6, 0.4])
    luma = tan @ np.array([0.299, 0.587, 0.114])
    pink = np.array([0.9, 0.0, 0.55])
    pink[1] = (luma - 0.299 * pink[0] - 0.114 * pink[2]) / 0.587  # the same luminance as the ground
    rgb = np.broadcast_to(tan, (h, w, 3)).copy()
    a = np.hypot(xx - 80, yy - 60) < 30
    b = np.hypot(xx - 200, yy - 60) < 30
    rgb[a], rgb[b] = pink, (0.5, 0.1, 0.1)
    rgb = ndimage.gaussian_filter(rgb, (0.8, 0.8, 0)) + noise * rng.standard_normal((h, w, 3))
    return np.clip(rgb, 0, 1), a, b


def test_a_colour_edge_without_a_lightness_step_is_drawn_once():
    from img2logo.features.photo.line_maps import photo_line_maps

    rgb, a, b = _two_discs()
    lightness, colour = photo_line_maps(load_image(rgb))
    ring_a = np.abs(ndimage.distance_transform_edt(~a) - ndimage.distance_transform_edt(a)) <= 4
    ring_b = np.abs(ndimage.distance_transform_edt(~b) - ndimage.distance_transform_edt(b)) <= 4
    # The pink disc has no lightness line; its colour line runs all round it ...
    assert not lightness[ring_a].any()
    found = ndimage.binary_dilation(colour, iterations=2)
    edge_a = a & ~ndimage.binary_erosion(a)
    assert found[edge_a].mean() > 0.9
    # ... as one line: a row across the disc's left edge crosses one run of it.
    row = colour[60, 30:80]
    assert np.count_nonzero(np.diff(row.astype(int)) == 1) + row[0] == 1
    # The dark red disc's outline is a lightness line, not drawn again as a colour line.
    assert lightness[ring_b].sum() > 100
    assert not colour[ring_b].any()
    # Nothing on the flat ground (the colour line runs in the chroma's blur, up to 10 px out).
    far = ~ndimage.binary_dilation(a | b, iterations=12)
    assert not (lightness | colour)[far].any()


def test_flow_dog_binarizes_the_response_on_its_own_scale():
    from img2logo.features.photo.line_maps import flow_dog, flow_dog_response

    rgb, _, _ = _two_discs()
    gray = load_image(rgb).gray.astype(np.float32)
    h = flow_dog_response(gray)
    h = h / np.abs(h).max() * 8.0
    np.testing.assert_array_equal(flow_dog(gray), (h < 0) & (1.0 + np.tanh(h) < 0.5))


def test_opponent_channel_is_the_main_chroma_axis_pointing_to_red():
    from img2logo.features.photo.line_maps import opponent_channel

    rgb, a, _ = _two_discs(noise=0.0)
    u = opponent_channel(rgb)
    assert u.shape == a.shape and u.dtype == np.float32
    assert u[60, 80] > u[5, 5] + 0.1  # pink (redder) above tan: a step of more than 10 CIELAB units


def test_colour_lines_come_after_the_lightness_lines_in_the_budget(monkeypatch):
    import img2logo.features.photo.lines as photo

    rgb, a, _ = _two_discs()
    img = load_image(rgb)
    whole = Subject(None, "none", "")
    both = photo_feature_lines(img, whole)
    edge_a = a & ~ndimage.binary_erosion(a)
    near = ndimage.distance_transform_edt(~both)
    assert np.mean(near[edge_a] <= 6) > 0.9  # the pink disc is drawn (a colour line)
    # With a budget that the lightness lines use up, the colour lines are left out.
    monkeypatch.setattr(photo, "PHOTO_LINE_BUDGET", 150 / (img.height + img.width))
    tight = photo_feature_lines(img, whole)
    assert np.mean(ndimage.distance_transform_edt(~tight)[edge_a] <= 6) < 0.2


def test_a_photo_s_subject_and_line_maps_import_no_scipy_package(data_dir):
    """The subject search, the faces, the line maps and the outline load nothing of scipy (the kernels give
    its filters): importing ``scipy.ndimage`` or ``scipy.linalg`` (their array-API layer) costs most of a second."""

    code = (
        "import sys\n"
        "from img2logo import load_image\n"
        "from img2logo.features.photo.line_maps import photo_line_maps, start_photo_line_maps\n"
        "from img2logo.features.photo.lines import reach_outline, subject_outline\n"
        "from img2logo.features.photo.subject import find_subject\n"
        f"img = load_image({str(data_dir / 'photo-flower.png')!r})\n"
        "found = find_subject(img, beside=start_photo_line_maps)\n"
        "light, colour = photo_line_maps(img)\n"
        "assert found.mask is not None and light.any()\n"
        "reach_outline(light, subject_outline(found.mask))\n"
    )
    assert modules_loaded(code, "scipy") == []


def _light_disc_on_grey(noise: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """A white disc on a grey body (a seal's belly) and the dark side of its edge, 1 px outside it."""
    rng = np.random.default_rng(1)
    yy, xx = np.mgrid[0:96, 0:96]
    d = np.hypot(yy - 48, xx - 48)
    gray = np.where(d <= 20, 0.9, 0.65) + rng.uniform(-noise, noise, d.shape)
    return gray, np.abs(d - 21.5) <= 0.5


def test_a_clear_step_between_two_light_regions_is_kept():
    from img2logo.features.photo.lines import clear_steps

    gray, steps = _light_disc_on_grey()
    kept = clear_steps(gray, steps, np.zeros_like(steps))
    assert kept.sum() > 0.8 * steps.sum() and not kept[48, 48]


def test_a_step_in_texture_or_beside_a_drawn_line_is_not():
    from img2logo.features.photo.lines import clear_steps

    gray, steps = _light_disc_on_grey(noise=0.5)  # the sides vary (blurred) about as much as they differ
    assert not clear_steps(gray, steps, np.zeros_like(steps)).any()
    gray, steps = _light_disc_on_grey()
    assert not clear_steps(gray, steps, steps).any()  # drawn already
