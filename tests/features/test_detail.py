"""Tests of img2logo.features.detail: detail by importance, ink outlines drawn once, bounded regions."""

from __future__ import annotations

import warnings

import cv2
import numpy as np
import pytest
from helpers import DATA, blank

from img2logo import DetailWarning, InvalidParameterError, Options, abstract, extract_feature_lines, load_image
from img2logo.features.clipart import clipart_regions
from img2logo.features.clipart_colours import label_lightness
from img2logo.features.clipart_strokes import ink_outlines, thin_regions
from img2logo.features.constants import CLIPART_EDGE_CONTRAST
from img2logo.features.detail import merge_by_importance, region_adjacency

OPENCLIPART = DATA.parent / "benchmarks" / "data" / "openclipart"
ORANGE, DARK_ORANGE = (230, 120, 40), (200, 90, 20)


def _disc(size: int = 200, radius: int = 70, fill: tuple[int, int, int] = ORANGE) -> np.ndarray:
    im = blank(size)
    cv2.circle(im, (size // 2, size // 2), radius, fill, -1, lineType=cv2.LINE_AA)
    return im


def _merged(im: np.ndarray, detail: int = 1) -> tuple[np.ndarray, np.ndarray]:
    img = load_image(im)
    regions = clipart_regions(img)
    return regions, merge_by_importance(regions, img.lab, detail)[0]


def _circle_arcs(result) -> list:
    return [(a.circle.cx, a.circle.cy, a.circle.r) for a in result.final.arcs]


# --------------------------------------------------------------------------- known answers
def test_a_hatching_line_inside_a_disc_is_merged_and_one_circle_kept():
    im = _disc()
    cv2.line(im, (60, 80), (140, 120), DARK_ORANGE, 1, lineType=cv2.LINE_AA)
    regions, merged = _merged(im)
    assert regions.max() == 2  # the line is a region of its own ...
    assert merged.max() == 1  # ... merged into the disc at detail 1 (one region kept)
    result = abstract(im, progress=False, detail=1)
    (cx, cy, r), *more = _circle_arcs(result)
    assert not more
    assert abs(cx - 100) < 2 and abs(cy - 100) < 2 and abs(r - 70) < 3
    # the default keeps a picture of so few regions whole: the line is drawn
    kept = extract_feature_lines(im).lines
    assert kept[100, 95:106].any()


def test_a_ring_of_forty_blotches_goes_and_the_silhouette_stays():
    im = blank(240)
    cv2.rectangle(im, (40, 40), (200, 200), (60, 160, 60), -1)
    for k in range(40):
        a = 2 * np.pi * k / 40
        cv2.circle(im, (int(120 + 55 * np.cos(a)), int(120 + 55 * np.sin(a))), 5, (40, 130, 40), -1)
    regions, merged = _merged(im)
    assert regions.max() >= 2  # the blotches are regions
    assert merged.max() == 1  # only the square is left
    assert np.array_equal(merged > 0, regions > 0)  # the silhouette is the same
    lines = extract_feature_lines(im, detail=1).lines
    rows, cols = np.nonzero(lines)
    off_outline = np.minimum.reduce([np.abs(rows - 40), np.abs(rows - 200), np.abs(cols - 40), np.abs(cols - 200)])
    assert off_outline.max() <= 2  # every line is the square's outline
    assert lines[40:201, 39:42].any(axis=1).mean() > 0.9  # and the outline is there, whole


def test_a_thick_black_ring_between_two_fills_is_one_centre_line_circle():
    im = blank(256)
    cv2.rectangle(im, (20, 20), (236, 236), (250, 210, 120), -1)
    cv2.circle(im, (128, 128), 60, (40, 160, 220), -1, lineType=cv2.LINE_AA)
    cv2.circle(im, (128, 128), 60, (0, 0, 0), 10, lineType=cv2.LINE_AA)
    assert clipart_regions(load_image(im)).max() == 3  # the square, the disc and the ink
    result = abstract(im, progress=False)
    inner = [(cx, cy, r) for cx, cy, r in _circle_arcs(result) if r < 1000]  # the square's sides are straight
    (cx, cy, r), *more = inner
    assert not more
    assert abs(cx - 128) < 2 and abs(cy - 128) < 2 and abs(r - 60) < 2.5  # the ring's centre line


def test_a_thick_black_ring_on_the_silhouette_is_drawn_once_along_it():
    im = _disc(256, 80, (40, 160, 220))
    cv2.circle(im, (128, 128), 80, (0, 0, 0), 10, lineType=cv2.LINE_AA)
    assert clipart_regions(load_image(im)).max() == 2  # the fill and the ink
    result = abstract(im, progress=False)
    circles = {(round(cx), round(cy), round(r)) for cx, cy, r in _circle_arcs(result)}
    (cx, cy, r), *more = circles
    assert not more  # one circle (its arcs), not the ring's two edges
    assert abs(cx - 128) <= 2 and abs(cy - 128) <= 2 and abs(r - 85) <= 2  # the ring's outer edge: the silhouette


def test_an_inner_boundary_is_dropped_whole_not_half():
    im = _disc()
    cv2.ellipse(im, (110, 90), (25, 12), 30, 0, 360, (215, 110, 40), -1, lineType=cv2.LINE_AA)
    regions, merged = _merged(im)
    assert regions.max() == 2 and merged.max() == 1
    lines = extract_feature_lines(im, detail=1).lines
    yy, xx = np.nonzero(lines)
    assert np.hypot(yy + 0.5 - 100, xx + 0.5 - 100).min() > 66  # no piece of the ellipse is left
    kept = extract_feature_lines(im, detail=2).lines
    yy, xx = np.nonzero(kept)
    inner = np.hypot(yy + 0.5 - 100, xx + 0.5 - 100) < 50
    assert inner.sum() > 100  # at detail 2 the ellipse is drawn, whole (about 120 px round)


def test_the_silhouette_is_kept_at_any_detail():
    im = _disc()
    cv2.circle(im, (100, 100), 30, (40, 90, 220), -1, lineType=cv2.LINE_AA)
    cv2.circle(im, (100, 100), 10, (250, 250, 250), -1, lineType=cv2.LINE_AA)
    regions, merged = _merged(im, 1)
    assert regions.max() == 3 and merged.max() == 1
    assert np.array_equal(merged > 0, regions > 0)


def test_the_heavier_region_is_kept_first():
    # Two blobs on one disc: a large one of strong colour contrast (not darker: no mark) and a small faint one.
    im = _disc(240, 100)
    cv2.circle(im, (90, 120), 30, (120, 200, 250), -1, lineType=cv2.LINE_AA)
    cv2.circle(im, (160, 120), 8, DARK_ORANGE, -1, lineType=cv2.LINE_AA)
    regions, kept = _merged(im, 3)
    assert regions.max() == 3 and kept.max() == 3
    two, n, _ = merge_by_importance(regions, load_image(im).lab, 2)
    assert n == 2 and two.max() == 2
    assert two[120, 90] != two[120, 200]  # the strong blob stayed
    assert two[120, 160] == two[120, 200]  # the faint one went into the disc


def test_a_dark_mark_is_kept_whatever_its_size():
    im = _disc(240, 100)
    cv2.circle(im, (100, 100), 4, (0, 0, 0), -1, lineType=cv2.LINE_AA)  # an eye
    cv2.circle(im, (150, 130), 20, (250, 200, 140), -1, lineType=cv2.LINE_AA)  # a larger light patch
    regions, merged = _merged(im, 1)
    assert regions.max() == 3
    assert merged.max() == 2
    assert merged[100, 100] != merged[60, 120]  # the eye stayed, the patch went


def test_a_dark_mark_takes_in_the_light_spots_it_encloses():
    # A wing's black with six light spots in it, on an orange disc: the spots touch the black
    # alone, and at a low detail they go into it (the black, larger, is never painted over).
    im = _disc(240, 100)
    cv2.circle(im, (120, 120), 60, (10, 10, 10), -1, lineType=cv2.LINE_AA)
    for k in range(6):
        a = 2 * np.pi * k / 6
        cv2.circle(im, (int(120 + 35 * np.cos(a)), int(120 + 35 * np.sin(a))), 9, (250, 230, 150), -1)
    cv2.circle(im, (120, 120), 7, (200, 220, 255), -1)  # and a highlight in its middle
    regions, merged = _merged(im, 1)
    assert regions.max() == 9
    assert merged.max() == 2  # the disc and the black, whole
    assert merged[120, 155] == merged[120, 120] == merged[120, 100] != merged[120, 30]


def test_too_many_regions_are_coarsened_and_said_in_one_line():
    im = blank(400)
    rng = np.random.default_rng(3)
    for row in range(8):
        for col in range(8):  # a mosaic of 64 touching tiles of distinct colours
            colour = tuple(int(v) for v in rng.integers(0, 200, 3))
            cv2.rectangle(im, (40 + 40 * col, 40 + 40 * row), (79 + 40 * col, 79 + 40 * row), colour, -1)
    img = load_image(im)
    regions = clipart_regions(img)
    assert regions.max() + 1 > 40
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        merged, kept, _ = merge_by_importance(regions, img.lab, 60, max_regions=40)
    assert merged.max() + 1 == 40
    assert kept == 39
    (w,) = [c for c in caught if issubclass(c.category, DetailWarning)]
    message = str(w.message)
    assert "\n" not in message and f"{regions.max() + 1} regions" in message and "40 regions" in message


def test_fills_that_touch_only_the_outline_are_not_merged_across_it_and_the_warning_says_so():
    im = blank(400)
    rng = np.random.default_rng(5)
    cv2.rectangle(im, (36, 36), (363, 363), (0, 0, 0), -1)  # a black outline network ...
    for row in range(8):
        for col in range(8):  # ... round 64 tiles of distinct light colours, each touching only the black
            colour = tuple(int(v) for v in rng.integers(120, 255, 3))
            cv2.rectangle(im, (42 + 40 * col, 42 + 40 * row), (75 + 40 * col, 75 + 40 * row), colour, -1)
    img = load_image(im)
    regions = clipart_regions(img)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        merged, kept, _ = merge_by_importance(regions, img.lab, 24, max_regions=40)
    assert merged.max() == regions.max() == kept == 65  # the tiles, the outline and the paper: nothing merged
    (w,) = [c for c in caught if issubclass(c.category, DetailWarning)]
    assert str(w.message).endswith("66 regions (no fewer without merging across the outline)")


def test_few_regions_give_no_warning_and_detail_one_changes_nothing():
    im = _disc()
    img = load_image(im)
    regions = clipart_regions(img)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert merge_by_importance(regions, img.lab, Options().detail) == (regions, int(regions.max()), 0.0)


def test_region_adjacency_counts_pixel_pairs():
    regions = np.array([[0, 0, 1], [0, 2, 1]])
    assert region_adjacency(regions) == {(0, 1): 1, (0, 2): 2, (1, 2): 1}


# --------------------------------------------------------------------------- ink outlines
def test_an_ink_outline_is_a_stroke_but_a_light_band_of_its_width_is_not():
    im = _disc(256, 80, (40, 160, 220))
    cv2.circle(im, (128, 128), 80, (0, 0, 0), 10, lineType=cv2.LINE_AA)
    img = load_image(im)
    regions = clipart_regions(img)
    lightness = label_lightness(regions, img.lab[..., 0])
    ring = int(regions[128, 48])
    assert ring in thin_regions(regions, lightness)
    assert ring not in thin_regions(regions)  # 10 px: wider than a fill's stroke
    light = _disc(256, 80, (40, 160, 220))
    cv2.circle(light, (128, 128), 80, (250, 220, 120), 10, lineType=cv2.LINE_AA)  # lighter than the fill
    img = load_image(light)
    regions = clipart_regions(img)
    lightness = label_lightness(regions, img.lab[..., 0])
    assert int(regions[128, 48]) not in thin_regions(regions, lightness)


def test_a_thin_black_outline_beside_a_dark_fill_is_ink_drawn_once():
    """Known answer: a black outline 3 px wide round a dark brown disc (L* 16), drawn at 4x and reduced
    as an SVG is rendered: its anti-aliased rim is most of its pixels, so its mean L* is 2.4 from the
    brown's, under an edge's contrast; its median is the black's, and it is an ink outline, drawn once."""
    s = 4
    big = np.full((256 * s, 256 * s, 3), 255, np.uint8)
    cv2.circle(big, (128 * s, 128 * s), 80 * s, (12, 36, 92), -1)
    cv2.circle(big, (128 * s, 128 * s), 80 * s, (0, 0, 0), 3 * s)
    im = cv2.resize(big, (256, 256), interpolation=cv2.INTER_AREA)
    img = load_image(im)
    regions = clipart_regions(img)
    ring, brown = int(regions[128, 48]), int(regions[128, 128])
    from img2logo.features.clipart_colours import label_means

    mean = label_means(regions, img.lab)[1][:, 0]
    median = label_lightness(regions, img.lab[..., 0])
    assert mean[brown] - mean[ring] < CLIPART_EDGE_CONTRAST <= median[brown] - median[ring]
    assert ring in ink_outlines(regions, median) and ring not in ink_outlines(regions, mean)
    lines = extract_feature_lines(im).lines
    assert 1 == int(lines[128, 30:70].sum()) == int(lines[128, 186:226].sum())


# --------------------------------------------------------------------------- the option
@pytest.mark.parametrize("bad", [0, -3, 2.5, float("nan"), float("inf"), "5", True, None])
def test_detail_must_be_a_whole_number_of_regions(bad):
    with pytest.raises(InvalidParameterError, match="detail must be a whole number of regions"):
        Options(detail=bad)


def test_detail_is_an_option_of_abstract():
    assert Options(detail=5.0).detail == 5
    assert Options().keywords() == {}
    assert Options(detail=5).keywords() == {"detail": 5}


def test_the_detail_kept_is_recorded():
    im = _disc()
    cv2.line(im, (60, 80), (140, 120), DARK_ORANGE, 1, lineType=cv2.LINE_AA)
    assert abstract(im, progress=False, detail=1).final.params["detail"] == 1
    assert abstract(im, progress=False).final.params["detail"] == 2


# --------------------------------------------------------------------------- real clip art
@pytest.mark.parametrize("name", ["clipart-gallo.png", "clipart-beagle.png", "clipart-tramway.png"])
def test_real_clip_art_keeps_its_silhouette_with_fewer_regions(name):
    img = load_image(OPENCLIPART / name)
    regions = clipart_regions(img)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DetailWarning)  # the tramway's 68 regions are coarsened
        merged, kept, _ = merge_by_importance(regions, img.lab, Options().detail)
    assert merged.max() < regions.max()
    assert merged.max() == kept and merged.max() + 1 <= 40
    assert np.array_equal(merged > 0, regions > 0)
