"""Tests of img2logo.features.clipart: flat-colour regions, subtle and noisy, strokes, and kind detection."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from helpers import DATA, blank, two_discs

from img2logo import build_segment_graph, detect_kind, extract_feature_lines, load_image
from img2logo.features.clipart import clipart_regions
from img2logo.features.clipart_colours import colour_noise
from img2logo.features.clipart_strokes import thin_regions

EVAL = DATA.parent / "benchmarks" / "data"


def _disc(fill: tuple[int, int, int], ground: tuple[int, int, int], size: int = 200) -> np.ndarray:
    im = np.empty((size, size, 3), np.uint8)
    im[:] = ground
    cv2.circle(im, (100, 100), 60, fill, -1, lineType=cv2.LINE_AA)
    return im


def _jpeg(im: np.ndarray, quality: int) -> np.ndarray:
    ok, data = cv2.imencode(".jpg", im[:, :, ::-1], [cv2.IMWRITE_JPEG_QUALITY, quality])
    assert ok
    return cv2.imdecode(data, cv2.IMREAD_COLOR)[:, :, ::-1]


def _regions(im: np.ndarray) -> np.ndarray:
    return clipart_regions(load_image(im))


# --------------------------------------------------------------------------- known answers
@pytest.mark.parametrize(
    ("fill", "ground"),
    [((225, 225, 225), (255, 255, 255)), ((255, 255, 255), (225, 225, 225))],
    ids=["light-grey-on-white", "white-on-light-grey"],
)
def test_a_subtle_disc_is_one_region_with_one_boundary(fill, ground):
    # Delta E about 5 between disc and ground: below the old palette's 12, visible to the eye.
    regions = _regions(_disc(fill, ground))
    assert len(np.unique(regions)) == 2
    assert regions[100, 100] != regions[5, 5] == 0
    graph = build_segment_graph(extract_feature_lines(_disc(fill, ground), kind="clipart"))
    assert graph.n_segments >= 1
    pts = np.vstack(graph.segments)
    radius = np.hypot(pts[:, 0] - 100.5, pts[:, 1] - 100.5)
    assert np.all(np.abs(radius - 60.0) < 2.0)  # only the disc's outline


def test_a_smooth_gradient_is_one_region():
    im = blank()
    ramp = np.linspace(40, 220, 120).astype(np.uint8)
    im[40:160, 40:160] = np.stack([ramp, np.full(120, 90, np.uint8), 255 - ramp], axis=1)[None, :, :]
    regions = _regions(im)
    assert len(np.unique(regions)) == 2  # the square and the white ground
    lines = extract_feature_lines(im, kind="clipart").lines
    assert not lines[50:150, 50:150].any()  # nothing inside the square: only its outline


def test_noise_is_measured_on_the_fills():
    clean = two_discs()
    _, fraction = colour_noise(load_image(clean).lab)
    assert fraction < 0.04  # exactly flat fills, and edges
    level, noisy = colour_noise(load_image(_jpeg(clean, 60)).lab)
    assert noisy > 0.04 and 0.5 < level < 9.2


def test_jpeg_gives_the_same_regions_and_graph():
    im = two_discs()
    cv2.circle(im, (100, 150), 20, (250, 200, 40), -1, lineType=cv2.LINE_AA)
    png = build_segment_graph(extract_feature_lines(im, kind="clipart"))
    jpg_lines = extract_feature_lines(_jpeg(im, 60), kind="clipart")
    assert len(np.unique(jpg_lines.regions)) == len(np.unique(_regions(im))) == 4  # white, red, blue, yellow
    jpg = build_segment_graph(jpg_lines)
    # The same junctions, and the same lines within 10 % of their length (the RDP
    # split points of a slightly wavier edge differ).
    assert sorted(jpg.valence[jpg.valence >= 3]) == sorted(png.valence[png.valence >= 3])

    def length(g):
        return sum(float(np.hypot(*np.diff(s, axis=0).T).sum()) for s in g.segments)

    assert length(jpg) == pytest.approx(length(png), rel=0.1)


@pytest.mark.parametrize("quality", [60, 75, 85])
def test_a_small_dark_fill_of_a_jpeg_keeps_its_region(quality):
    """A 10 x 16 px black eye on yellow: JPEG ringing leaves it no flat pixel, it is still a region."""
    im = _disc((250, 190, 50), (255, 255, 255))
    cv2.ellipse(im, (80, 90), (5, 8), 0, 0, 360, (20, 20, 25), -1, lineType=cv2.LINE_AA)
    regions = _regions(_jpeg(im, quality))
    eye, body = regions[90, 80], regions[100, 130]
    assert eye not in (body, regions[5, 5])
    assert 110 <= int((regions == eye).sum()) <= 200  # the eye (about 150 px with its anti-aliased rim)
    assert len(np.unique(regions)) == 3  # paper, disc, eye: no ringing seeded


def _spots(small_radius: int) -> np.ndarray:
    """An orange body with two brown spots 32 px across and a third, small one of their colour (4x, area-reduced)."""
    s = 4
    im = np.full((200 * s, 200 * s, 3), 255, np.uint8)
    cv2.ellipse(im, (100 * s, 100 * s), (85 * s, 60 * s), 0, 0, 360, (240, 170, 60), -1, lineType=cv2.LINE_AA)
    for x, y, r in ((60, 90, 16), (140, 90, 16), (100, 125, small_radius)):
        cv2.circle(im, (x * s, y * s), r * s, (170, 95, 40), -1, lineType=cv2.LINE_AA)
    return cv2.resize(im, (200, 200), interpolation=cv2.INTER_AREA)


@pytest.mark.parametrize("quality", [60, 70, 85, 95])
@pytest.mark.parametrize("radius", [5, 7])
def test_a_small_spot_of_a_jpeg_keeps_its_region_beside_larger_ones_of_its_colour(quality, radius):
    """A 10-14 px spot whose flat part is smaller than a seed, of the colour of two large spots 25 px away.

    Its pixels more than 4 px from the body's flat pixels are near no seed; the colour of the large
    spots (beyond a 16 px chroma block) used to explain them, so they seeded nothing and made a
    region without a seed pixel, merged into the body as a sliver (the JPEG giraffe's small spots).
    """
    regions = _regions(_jpeg(_spots(radius), quality))
    spot, body = regions[125, 100], regions[100, 100]
    assert spot not in (body, regions[5, 5])
    assert np.pi * (radius - 1.5) ** 2 <= int((regions == spot).sum()) <= np.pi * (radius + 1.5) ** 2
    assert len(np.unique(regions)) == 5  # paper, body, three spots: no ringing along the body's edge seeded


@pytest.mark.parametrize("quality", [60, 70, 85, 95])
@pytest.mark.parametrize("radius", [5, 7])
def test_a_small_spot_of_a_jpeg_near_a_larger_one_of_its_colour_keeps_its_region(quality, radius):
    """A 10-14 px spot 10 px from a 32 px spot of its colour, within a 16 px chroma block of it.

    The larger spot's seed is near the small spot's pixels, but across the body's colour: it
    explains them only through pixels of its own colour, which stop at its rim (the lost spot
    of ``clipart-critter-d-jpeg``).
    """
    s = 4
    im = np.full((200 * s, 200 * s, 3), 255, np.uint8)
    cv2.ellipse(im, (100 * s, 100 * s), (85 * s, 60 * s), 0, 0, 360, (240, 170, 60), -1, lineType=cv2.LINE_AA)
    x = 60 + 16 + 10 + radius
    for cx, cy, r in ((60, 100, 16), (x, 100, radius)):
        cv2.circle(im, (cx * s, cy * s), r * s, (170, 95, 40), -1, lineType=cv2.LINE_AA)
    regions = _regions(_jpeg(cv2.resize(im, (200, 200), interpolation=cv2.INTER_AREA), quality))
    spot, big, body = regions[100, x], regions[100, 60], regions[70, 100]
    assert spot not in (body, big, regions[5, 5])
    assert np.pi * (radius - 1.5) ** 2 <= int((regions == spot).sum()) <= np.pi * (radius + 1.5) ** 2
    assert len(np.unique(regions)) == 4  # paper, body, two spots


def test_thin_strokes_of_a_jpeg_drawing_seed_no_fill_where_they_cross():
    """Two 3 px lines crossing: the crossing is thick enough to have an inside, but is no small fill."""
    im = blank()
    for end in ((40, 40, 160, 160), (40, 160, 160, 40)):
        cv2.line(im, end[:2], end[2:], (0, 0, 0), 3, lineType=cv2.LINE_AA)
    cv2.circle(im, (100, 40), 5, (0, 0, 0), -1, lineType=cv2.LINE_AA)  # and an 11 px dot
    kind, reason = detect_kind(_jpeg(im, 70))
    assert kind == "drawing", reason


def test_a_thin_stripe_becomes_one_stroke():
    im = _disc((230, 120, 40), (255, 255, 255))
    cv2.line(im, (55, 100), (145, 100), (60, 30, 20), 3)  # a 3 px dark stripe across the disc
    regions = _regions(im)
    stripe = regions[100, 100]
    assert stripe in thin_regions(regions)
    lines = extract_feature_lines(im, kind="clipart").lines
    # One line across the stripe's width, not its two edges.
    for x in (80, 100, 120):
        assert lines[94:107, x].sum() == 1


def test_a_thin_anti_aliased_line_has_a_region():
    im = blank()
    cv2.circle(im, (100, 100), 60, (30, 60, 200), 3, lineType=cv2.LINE_AA)  # no flat pixel in it
    regions = _regions(im)
    assert len(np.unique(regions)) == 3  # paper outside, the ring, paper inside
    assert regions[100, 40] not in (regions[100, 100], regions[5, 5])


def test_a_round_dot_is_not_a_stroke():
    im = _disc((40, 40, 40), (255, 255, 255))
    cv2.circle(im, (100, 100), 3, (250, 250, 250), -1)
    regions = _regions(im)
    assert len(thin_regions(regions)) == 0


def test_rgba_with_black_hidden_pixels_equals_white():
    im = two_discs()
    rgba = np.dstack([im, np.full(im.shape[:2], 255, np.uint8)])
    hidden = (im == 255).all(axis=2)
    rgba[hidden] = 0  # transparent black
    a = extract_feature_lines(im, kind="clipart").lines
    b = extract_feature_lines(rgba, kind="clipart").lines
    np.testing.assert_array_equal(a, b)


def test_gray_one_channel_clip_art():
    gray = np.full((200, 200), 255, np.uint8)
    cv2.circle(gray, (100, 100), 70, 150, -1, lineType=cv2.LINE_AA)
    cv2.circle(gray, (100, 100), 30, 60, -1, lineType=cv2.LINE_AA)
    fl = extract_feature_lines(gray)
    assert fl.kind == "clipart", fl.reason
    assert len(np.unique(fl.regions)) == 3


# --------------------------------------------------------------------------- kinds
def test_kinds_of_synthetic_images():
    greys = blank()
    cv2.circle(greys, (100, 100), 70, (160, 160, 160), -1, lineType=cv2.LINE_AA)
    cv2.circle(greys, (80, 90), 25, (210, 210, 210), -1, lineType=cv2.LINE_AA)
    cv2.circle(greys, (125, 90), 8, (40, 40, 40), -1, lineType=cv2.LINE_AA)
    assert detect_kind(greys)[0] == "clipart"  # greys, not a drawing
    assert detect_kind(_disc((244, 244, 244), (255, 255, 255)))[0] == "clipart"  # near-white on white
    thick = blank()
    cv2.circle(thick, (100, 100), 60, (0, 0, 0), 12, lineType=cv2.LINE_AA)
    cv2.line(thick, (40, 100), (160, 100), (0, 0, 0), 12, lineType=cv2.LINE_AA)
    kind, reason = detect_kind(thick)
    assert kind == "drawing", reason
    blue = blank()
    cv2.circle(blue, (100, 100), 60, (30, 60, 200), 3, lineType=cv2.LINE_AA)
    assert detect_kind(blue)[0] == "drawing"  # one ink, any colour
    assert detect_kind(_jpeg(blue, 70))[0] == "drawing"


def test_a_gray_photo_is_a_photo():
    rng = np.random.default_rng(3)
    yy, xx = np.mgrid[0:160, 0:200]
    scene = 0.5 + 0.3 * np.sin(xx / 17.0) * np.cos(yy / 23.0) + 0.02 * rng.standard_normal((160, 200))
    kind, reason = detect_kind(np.clip(scene, 0.0, 1.0))
    assert kind == "photo" and "photo" in reason


@pytest.mark.parametrize(
    "name",
    ["clipart-polar-bear.png", "clipart-seal.png", "clipart-giraffe-jpeg.jpg", "clipart-sunflower-gray.png"],
)
def test_kind_of_evaluation_clip_arts(name):
    kind, reason = detect_kind(EVAL / name)
    assert kind == "clipart", reason


@pytest.mark.parametrize("name", ["clipart-fish.png", "clipart-dolphin.png"])
def test_a_jpeg_of_an_example_draws_the_same_lines(name):
    # Most of their 8x8 blocks stay exactly flat, so the noise is measured between them;
    # with the noise taken as 0, each block's shade became a region of its own.
    png = load_image(DATA / name)
    jpg = _jpeg(np.round(png.rgb * 255).astype(np.uint8), 70)
    a = build_segment_graph(extract_feature_lines(png))
    b = build_segment_graph(extract_feature_lines(jpg))
    assert sorted(b.valence[b.valence >= 3]) == sorted(a.valence[a.valence >= 3])

    def length(g):
        return sum(float(np.hypot(*np.diff(s, axis=0).T).sum()) for s in g.segments)

    assert length(b) == pytest.approx(length(a), rel=0.1)


def test_near_entries_match_a_whole_image_dilation():
    # The entries are dilated within their boxes (a speed-up): the same answer as dilating
    # each entry's mask over the whole image, at the image's edges too.
    from img2logo.features.clipart_palette import near_entries

    rng = np.random.default_rng(7)
    for _ in range(40):
        h, w = (int(v) for v in rng.integers(1, 40, 2))
        n = int(rng.integers(1, 6))
        index = rng.integers(-1, n, (h, w))
        index[rng.random((h, w)) < rng.uniform(0.0, 0.9)] = -1
        rest = index < 0
        for radius in (1, 3, 7):
            disk = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * radius + 1, 2 * radius + 1))
            expected = np.stack(
                [cv2.dilate((index == e).astype(np.uint8), disk)[rest] > 0 for e in range(n)], axis=1
            ).reshape(int(rest.sum()), n)
            assert np.array_equal(near_entries(index, n, rest, radius), expected)


def test_flat_areas_match_the_padded_window():
    # Each pixel pair is measured once (a speed-up): the same areas as the window's
    # largest difference over an edge-padded image, as first written.
    from img2logo.features.clipart_colours import flat_areas
    from img2logo.features.constants import CLIPART_FLAT_RADIUS as rad

    def reference(lab: np.ndarray, link: float) -> np.ndarray:
        from img2logo.images.ndimage import components as label

        h, w = lab.shape[:2]
        lab32 = lab.astype(np.float32)
        padded = np.pad(lab32, ((rad, rad), (rad, rad), (0, 0)), mode="edge")
        spread = np.zeros((h, w), dtype=np.float32)
        for dr in range(-rad, rad + 1):
            for dc in range(-rad, rad + 1):
                diff = padded[rad + dr : rad + dr + h, rad + dc : rad + dc + w] - lab32
                np.maximum(spread, np.einsum("ijk,ijk->ij", diff, diff), out=spread)
        flat = np.sqrt(spread) <= link
        labels = label(flat, connectivity=1)
        labels[~flat] = labels.max() + 1 + np.arange(int((~flat).sum()))
        return labels - 1

    rng = np.random.default_rng(8)
    for _ in range(60):
        h, w = (int(v) for v in rng.integers(1, 30, 2))
        lab = np.round(rng.random((h, w, 3)) * rng.choice([1.0, 5.0, 50.0]), int(rng.integers(0, 3)))
        for link in (0.0, 1.0, 3.0):
            assert np.array_equal(flat_areas(lab, link), reference(lab, link))
    lab = load_image(DATA / "clipart-fish.png").lab
    assert np.array_equal(flat_areas(lab, 1.15), reference(lab, 1.15))


def test_label_means_match_bincount():
    # One compiled pass for all channels (a speed-up): the same bits as np.bincount per channel.
    from img2logo.features.clipart_colours import label_means

    rng = np.random.default_rng(9)
    for _ in range(20):
        h, w = (int(v) for v in rng.integers(1, 50, 2))
        labels = rng.integers(0, int(rng.integers(1, 300)), (h, w))
        values = rng.random((h, w, 3)) * 100.0
        flat = labels.ravel()
        counts = np.bincount(flat).astype(np.float64)
        sums = np.stack([np.bincount(flat, weights=values[..., c].ravel(), minlength=len(counts)) for c in range(3)], 1)
        got_counts, got_means = label_means(labels, values)
        assert np.array_equal(got_counts, counts)
        assert np.array_equal(got_means, sums / np.maximum(counts, 1.0)[:, None])


# --------------------------------------------------------------------------- the kernels' oracles
def lab_spread_reference(lab: np.ndarray, pairs: list[tuple[int, int]]) -> np.ndarray:
    """:func:`lab_spread` in numpy: the largest squared float32 CIELAB difference over ``pairs``, (H, W)."""
    h, w = lab.shape[:2]
    lab32 = lab.astype(np.float32)
    most = np.zeros((h, w), dtype=np.float32)
    for dr, dc in pairs:
        if dr >= h or abs(dc) >= w:
            continue  # no such pair in so small an image
        here = (slice(0, h - dr), slice(max(0, -dc), w - max(0, dc)))
        there = (slice(dr, h), slice(max(0, dc), w - max(0, -dc)))
        diff = lab32[there] - lab32[here]
        d = np.einsum("ijk,ijk->ij", diff, diff)
        np.maximum(most[here], d, out=most[here])
        np.maximum(most[there], d, out=most[there])
    return most


def spreads_reference(lab, pairs, in_a, in_b):
    """``spreads_kernel``'s two spreads, each by :func:`lab_spread_reference`."""
    offsets = [(int(dr), int(dc)) for dr, dc in pairs]
    return (
        lab_spread_reference(lab, [o for o, a in zip(offsets, in_a, strict=True) if a]),
        lab_spread_reference(lab, [o for o, b in zip(offsets, in_b, strict=True) if b]),
    )


def label_sums_reference(labels, values, n):
    """``label_sums_kernel``: np.bincount's counts and sums by channel."""
    counts = np.bincount(labels, minlength=n).astype(np.float64)
    sums = np.stack([np.bincount(labels, weights=values[:, c], minlength=n) for c in range(values.shape[1])], 1)
    return counts, sums


def nearest_colour_reference(colours, singles, near):
    """``nearest_colour_kernel``: each colour's distance to the nearest of the ``near`` seeds' colours (inf: none)."""
    best = np.full(len(colours), np.inf)
    for a in range(len(singles)):
        on_a = near[:, a]
        if on_a.any():
            best[on_a] = np.minimum(best[on_a], np.linalg.norm(colours[on_a] - singles[a], axis=1))
    return best


def relabel_reference(regions):
    """``relabel_kernel``: the used labels packed to 0..n-1 in their order, int64."""
    used = np.bincount(regions.ravel()) > 0
    return (np.cumsum(used) - 1)[regions].astype(np.int64)


def palette_regions_reference(index, min_area):
    """``palette_regions_kernel``: 4-connected pieces of one entry, tiny ones joined 8-connected, packed."""
    from img2logo.images.ndimage import components

    regions = components(index, connectivity=1, background=-1)
    tiny = np.bincount(regions.ravel())[regions] < min_area
    if tiny.any():
        joined = components(np.where(tiny, index, -1), connectivity=2, background=-1)
        regions = np.where(tiny, joined + regions.max() + 1, regions)
    return relabel_reference(regions)


REFERENCES = {
    "spreads_kernel": spreads_reference,
    "colour_distance_kernel": lambda lab, colour: np.linalg.norm(lab - colour, axis=2),
    "label_sums_kernel": label_sums_reference,
    "nearest_colour_kernel": nearest_colour_reference,
    "relabel_kernel": relabel_reference,
    "palette_regions_kernel": palette_regions_reference,
}


def test_spread_kernel_is_the_numpy_reference():
    # The colour spreads of the flat areas and the noise, compiled: the same float32 bits as numpy's.
    from img2logo.features.clipart_colours import lab_spread

    window = [(dr, dc) for dr in range(3) for dc in range(-2, 3) if dr > 0 or dc > 0]
    rng = np.random.default_rng(5)
    labs = [rng.random((h, w, 3)) * 100.0 for h, w in ((1, 1), (2, 7), (9, 3), (40, 33))]
    labs.append(load_image(DATA / "clipart-fish.png").lab)
    for lab in labs:
        got = lab_spread(lab, window)
        assert got.dtype == np.float32 and np.array_equal(got, lab_spread_reference(lab, window))
        assert np.array_equal(lab_spread(lab, [(0, 1), (1, 0)]), lab_spread_reference(lab, [(0, 1), (1, 0)]))


def test_palette_kernels_are_their_references():
    from img2logo._compiled import kernels

    rng = np.random.default_rng(6)
    for _ in range(30):
        h, w = (int(v) for v in rng.integers(1, 40, 2))
        index = rng.integers(-1, int(rng.integers(1, 6)), (h, w))
        assert np.array_equal(kernels.palette_regions_kernel(index, 3), palette_regions_reference(index, 3))
        labels = rng.integers(0, 50, (h, w)) * int(rng.integers(1, 4))
        assert np.array_equal(kernels.relabel_kernel(labels), relabel_reference(labels))
        colours, singles = rng.random((h * w, 3)) * 100.0, rng.random((5, 3)) * 100.0
        near = rng.random((h * w, 5)) < 0.3
        assert np.array_equal(
            kernels.nearest_colour_kernel(colours, singles, near), nearest_colour_reference(colours, singles, near)
        )


@pytest.mark.parametrize("path", [DATA / "clipart-fish.png", EVAL / "clipart-giraffe-jpeg.jpg"])
def test_regions_are_the_same_with_the_kernels_references(monkeypatch, path):
    # The compiled steps (the spreads, colour distances, label sums, nearest seed colours, the
    # palette's labelling and packing) against their numpy and OpenCV references: the same
    # regions, for a clean clip art and a compressed one.
    from img2logo._compiled import kernels

    img = load_image(path)
    compiled = clipart_regions(img)
    thin = thin_regions(compiled)  # (its edges' distances are compiled either way)
    for name, reference in REFERENCES.items():
        monkeypatch.setattr(kernels, name, reference)
    assert np.array_equal(compiled, clipart_regions(img))
    assert np.array_equal(thin, thin_regions(compiled))


def test_near_entries_look_round_or_dilate_alike(monkeypatch):
    # Each pixel looking round itself (compiled) and each entry dilated: the same answer.
    from img2logo.features import clipart_palette as clipart

    rng = np.random.default_rng(3)
    index = np.where(rng.random((60, 80)) < 0.2, -1, rng.integers(0, 5, (60, 80)))
    rest = index < 0
    looked = clipart.near_entries(index, 5, rest)
    monkeypatch.setattr(clipart, "_NEAR_PIXEL_WORK", -1)  # never look round: dilate
    assert np.array_equal(looked, clipart.near_entries(index, 5, rest))
    assert looked.any() and not looked.all()


def test_colour_distance_and_spreads_are_numpys():
    from img2logo.features.clipart_colours import colour_distance, lab_spreads

    rng = np.random.default_rng(4)
    labs = [rng.random((h, w, 3)) * 100.0 for h, w in ((1, 1), (2, 7), (9, 3), (40, 33))]
    pairs_a, pairs_b = [(0, 1), (1, 0)], [(0, 1), (1, -1), (1, 0), (1, 1), (2, 2)]
    for lab in labs:
        assert np.array_equal(colour_distance(lab, lab[0, 0]), np.linalg.norm(lab - lab[0, 0], axis=2))
        a, b = lab_spreads(lab, pairs_a, pairs_b)
        assert a.dtype == np.float32 and np.array_equal(a, lab_spread_reference(lab, pairs_a))
        assert np.array_equal(b, lab_spread_reference(lab, pairs_b))


# --------------------------------------------------------------------------- the silhouette, JPEG parity
def _legs(size: int = 256) -> np.ndarray:
    """A brown body on two white legs, every part outlined by a 3 px black line, drawn at 4x and reduced."""
    s = 4
    big = np.full((size * s, size * s, 3), 255, np.uint8)
    for x in (60, 150):  # the legs: white, as the paper, enclosed by their outlines and the body
        leg = np.array([[x, 150], [x + 40, 150], [x + 40, 225], [x, 225]]) * s
        cv2.polylines(big, [leg], True, (0, 0, 0), 3 * s)
    cv2.ellipse(big, (128 * s, 110 * s), (100 * s, 60 * s), 0, 0, 360, (140, 70, 40), -1)
    cv2.ellipse(big, (128 * s, 110 * s), (100 * s, 60 * s), 0, 0, 360, (0, 0, 0), 3 * s)
    return cv2.resize(big, (size, size), interpolation=cv2.INTER_AREA)


def test_paper_enclosed_by_an_outline_a_jpeg_lost_is_no_background():
    """Known answer: in the JPEG the legs' 3 px outlines have no seed and take the paper's colour, so the
    palette makes the legs one region with the paper; cut to the paper that reaches the frame, each leg
    is a region of its own again, as in the PNG (whose regions are left as they are)."""
    from img2logo.features.clipart import enclosed_paper

    png = load_image(_legs())
    regions = clipart_regions(png)
    assert enclosed_paper(regions, png) is regions  # a clean image's background stops at its first edge
    assert len({regions[200, 80], regions[200, 170], 0}) == 3
    jpeg = load_image(_jpeg(_legs(), 75))
    lost = clipart_regions(jpeg)
    assert lost[200, 80] == lost[200, 170] == 0  # what the palette makes of the JPEG alone
    cut = enclosed_paper(lost, jpeg)
    assert len({cut[200, 80], cut[200, 170], 0}) == 3
    assert cut[5, 5] == 0 and cut[240, 128] == 0  # the paper round the object stays the background


def test_a_jpeg_of_a_clip_art_gives_nearly_the_logo_of_its_png():
    """Known answer: the JPEG (quality 75) of the legged body: the same kind, the silhouette kept whole by
    both logos, and the logos within 3 px of each other (0.25 / 0.41 of their points when the legs
    joined the paper, 4 arcs)."""
    import warnings

    from scipy import ndimage
    from scipy.spatial import cKDTree

    from img2logo import abstract
    from img2logo.quality import logo_points, silhouette_recall

    png, jpeg = _legs(), _jpeg(_legs(), 75)
    object_mask = ndimage.binary_fill_holes((png < 245).any(axis=2))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a, b = abstract(png, progress=False), abstract(jpeg, progress=False)
    assert a.lines.kind == b.lines.kind == "clipart"
    pa, pb = logo_points(a.final), logo_points(b.final)
    assert silhouette_recall(pa, object_mask) >= 0.95
    assert silhouette_recall(pb, object_mask) >= 0.95
    assert np.mean(cKDTree(pb).query(pa)[0] <= 3.0) >= 0.9
    assert np.mean(cKDTree(pa).query(pb)[0] <= 3.0) >= 0.9


def test_the_openclipart_jpeg_beagle_keeps_its_white_legs_off_the_background():
    """Openclipart's beagle as a JPEG: its white legs and chest, inside thin black outlines, joined the
    paper (sil6 0.42 where the PNG has 0.89); the background is now the paper outside the silhouette."""
    from img2logo.features.clipart import enclosed_paper

    folder = EVAL / "openclipart"
    img = load_image(folder / "clipart-beagle-jpeg.jpg")
    silhouette = cv2.imread(str(folder / "clipart-beagle-jpeg.silhouette.png"), cv2.IMREAD_GRAYSCALE) > 127
    regions = clipart_regions(img)
    assert np.mean(regions[silhouette] == 0) > 0.2  # the palette alone: a quarter of the dog is paper
    cut = enclosed_paper(regions, img)
    assert np.mean(cut[silhouette] == 0) < 0.05  # measured 0.026 (the PNG's regions: 0.004)
