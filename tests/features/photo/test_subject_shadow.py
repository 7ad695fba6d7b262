"""Tests of img2logo.features.photo.subject_shadow: a cast shadow trapped in a subject candidate is background."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np
from scipy import ndimage

from img2logo import load_image
from img2logo.features.photo.subject import find_subject
from img2logo.features.photo.subject_shadow import cast_shadow, shadow_features

ROOT = Path(__file__).resolve().parents[3]
PHOTO2 = ROOT / "benchmarks" / "data" / "photo2"


def arch_on_wood(gap: str, size: int = 256, seed: int = 0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """An arch (a body on two legs) on a grainy light-brown background: RGB, the arch, the gap between its legs.

    ``gap`` is ``"shadow"`` (the background there darkened to 40 %, the
    darkening blurred by a Gaussian of 10 px: a soft cast shadow) or ``"part"`` (a sharp-edged part of the object of
    the background's colour at 40 %, a dark foot).
    """
    rng = np.random.default_rng(seed)
    grain = ndimage.gaussian_filter(rng.random((size, size)), (1.0, 3.0))
    grain = (grain - grain.min()) / np.ptp(grain)
    img = np.array([0.80, 0.62, 0.45]) * (0.55 + 0.5 * grain)[..., None]
    yy, xx = np.mgrid[0:size, 0:size]
    body = (yy >= 60) & (yy < 120) & (xx >= 60) & (xx < 196)
    legs = (yy >= 120) & (yy < 200) & (((xx >= 60) & (xx < 90)) | ((xx >= 166) & (xx < 196)))
    arch = body | legs
    gap_box = (yy >= 120) & (yy < 200) & (xx >= 90) & (xx < 166)
    if gap == "shadow":  # darkened by 60 %, the darkening blurred: a soft penumbra
        dark = ndimage.gaussian_filter(gap_box.astype(float), 10.0) * 0.6
    else:  # a sharp-edged dark part of the same chromaticity
        dark = gap_box * 0.6
    img = img * (1.0 - dark[..., None])
    img[arch] = (0.25, 0.45, 0.85)
    img = ndimage.gaussian_filter(img, (0.8, 0.8, 0)) + 0.01 * rng.standard_normal(img.shape)
    return np.clip(img, 0, 1), arch, gap_box


def test_a_cast_shadow_keeps_chromaticity_and_log_texture():
    rgb, _, _ = arch_on_wood("shadow")
    features, log_lum = shadow_features(rgb)
    darker, _ = shadow_features(rgb * 0.5)
    np.testing.assert_allclose(darker, features, atol=1e-6)  # a factor changes neither ...
    _, log_half = shadow_features(rgb * 0.5)
    inner = (slice(20, -20), slice(20, -20))
    assert np.allclose(log_half[inner] - log_lum[inner], np.log(0.5**2.2), atol=1e-6)  # ... only the log-luminance


def test_the_shadow_between_the_legs_is_left_out():
    rgb, arch, gap = arch_on_wood("shadow")
    bridged = arch | gap  # what GrabCut on colours gives: the legs joined across the shadow
    shadow = cast_shadow(load_image(rgb), bridged)
    assert shadow is not None
    assert (shadow & gap).sum() > 0.85 * gap.sum()  # also its part far from the lit background
    assert (shadow & arch).sum() < 0.01 * arch.sum()


def test_a_dark_part_of_the_background_colour_with_a_sharp_edge_outside_stays():
    rgb, arch, gap = arch_on_wood("part")
    assert cast_shadow(load_image(rgb), arch | gap) is None


def test_no_shadow_in_an_object_alone():
    rgb, arch, _ = arch_on_wood("shadow")
    assert cast_shadow(load_image(rgb), arch) is None
    assert cast_shadow(load_image(rgb), np.zeros(arch.shape, bool)) is None


def test_the_giraffe_s_shadow_between_its_legs_is_background():
    img = load_image(PHOTO2 / "photo2-giraffe.jpg")
    truth = cv2.imread(str(PHOTO2 / "photo2-giraffe.mask.png"), cv2.IMREAD_GRAYSCALE) > 127
    subject = find_subject(img)
    assert "cast shadow left out" in subject.description
    assert subject.mask is not None
    assert (subject.mask & truth).sum() / (subject.mask | truth).sum() > 0.91  # 0.87 with the shadow


def test_the_chromaticity_s_local_mean_is_the_first_two_channels_of_the_features_one():
    from img2logo.features.photo.subject_shadow import local_mean, mahalanobis

    rgb, _, gap = arch_on_wood("shadow")
    features, _ = shadow_features(rgb)
    ring = ndimage.binary_dilation(gap, iterations=12) & ~ndimage.binary_dilation(gap, iterations=3)
    mean = local_mean(features, ring, 20.0)
    chroma = np.ascontiguousarray(features[..., :2])
    np.testing.assert_array_equal(mean[..., :2], local_mean(chroma, ring, 20.0))  # cast_shadow shares it
    np.testing.assert_array_equal(mahalanobis(chroma, ring, mean=mean[..., :2]), mahalanobis(chroma, ring, 20.0))
