"""img2logo.abstract: the whole pipeline on the example images, and the contract."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from helpers import DATA, drawing

import img2logo
from img2logo import InvalidParameterError, abstract
from img2logo.constants import PHI
from img2logo.export.contract import to_document, validate_document


@pytest.fixture(scope="module", params=["clipart-fish", "drawing-bird", "photo-cat"])
def result(request):
    return abstract(DATA / f"{request.param}.png", progress=False)


def test_result_holds_every_stage(result):
    assert result.graph.n_segments > 0
    assert result.levels[0].level == 0 and result.final is result.levels[-1]
    assert result.level(-1) is result.final
    assert 0.0 <= result.bias < 1.0
    assert set(result.timings) == {
        "feature_lines",
        "segment_graph",
        "simplification",
        "initial_fit",
        "loop",
        "tangency",
    }
    assert result.params["kind"] == result.lines.kind


def test_every_level_is_a_valid_contract_document(result):
    pytest.importorskip("jsonschema")
    for level in result.levels:
        doc = to_document(level)
        validate_document(doc)
        assert doc["similarity"] == pytest.approx(level.similarity)
        json.dumps(doc)  # serializable


def test_final_level_is_far_simpler_than_the_segments(result):
    assert len(result.final.arcs) <= 0.5 * result.graph.n_segments
    assert result.final.similarity <= result.final.tolerance


def test_abstract_accepts_arrays_and_reports_the_kind():
    res = abstract(drawing("circle"), tolerance=5.0, progress=False)
    assert res.lines.kind == "drawing"
    assert len(res.final.arcs) == 1


def test_progress_callback_and_switches_pass_through():
    calls = []
    res = abstract(drawing("spiral"), tolerance=3.0, progress=lambda *a: calls.append(a), merging=False)
    # A^0 as made, then A^0 with its tangent joins refitted: the last call is the result.
    assert len(res.levels) == 1 and [c[0] for c in calls] == [0, 0]
    assert calls[-1] == (0, len(res.final.arcs), res.final.similarity)


def test_unknown_switch_is_an_error():
    with pytest.raises(TypeError, match="connectvity"):
        abstract(drawing("Y"), progress=False, connectvity=False)


def test_tolerance_zero_is_refused():
    with pytest.raises(InvalidParameterError, match=r"tolerance must be > 0, got 0\.0"):
        abstract(drawing("Y"), tolerance=0, progress=False)


def test_public_names_resolve():
    for name in img2logo.__all__:
        assert getattr(img2logo, name) is not None
    with pytest.raises(AttributeError, match=r"no attribute 'nope'"):
        img2logo.nope  # noqa: B018


def test_the_options_value_and_its_errors_are_public():
    # The README passes options=img2logo.Options(...); the error and warning a caller catches
    # are reachable from the top level too.
    from img2logo.errors import UnknownOptionError
    from img2logo.fit.recovery import ConnectivityWarning
    from img2logo.options import Options

    assert img2logo.Options is Options
    assert img2logo.UnknownOptionError is UnknownOptionError
    assert img2logo.ConnectivityWarning is ConnectivityWarning
    assert abstract(drawing("Y"), options=img2logo.Options(tolerance=7.0), progress=False).final.tolerance == 7.0


def test_keywords_are_checked_before_any_work(tmp_path):
    from img2logo.errors import UnknownOptionError

    missing = tmp_path / "missing.png"  # never read: the keyword check comes first
    with pytest.raises(UnknownOptionError, match=r"unknown option 'foo': expected keyword arguments"):
        abstract(missing, foo=1)
    with pytest.raises(InvalidParameterError, match=r"min_length must be >= 0, got -5"):
        abstract(missing, min_length=-5)


def test_tolerance_and_progress_of_the_wrong_type_are_refused_before_any_work(tmp_path):
    # '5', True and 'yes' were taken as 5.0, 1.0 and a progress bar.
    missing = tmp_path / "missing.png"
    for value in ("5", True):
        with pytest.raises(InvalidParameterError, match=rf"^tolerance must be a number of px, got {value!r}$"):
            abstract(missing, tolerance=value)
    with pytest.raises(
        InvalidParameterError, match=r"^progress must be a callable .*, True, False or None, got 'yes'$"
    ):
        abstract(missing, progress="yes")


def test_level_out_of_range_names_the_range(result):
    n = len(result.levels)
    assert result.level(n - 1) is result.final and result.level(-n) is result.levels[0]
    for bad in (n, -n - 1, 99, 1.0, True):
        with pytest.raises(InvalidParameterError, match=rf"level must be an integer in 0\.\.{n - 1} \(or -{n}\.\.-1"):
            result.level(bad)


def test_a_photo_is_drawn_from_its_subject_with_every_arc_within_t():
    from helpers import textured_photo

    from img2logo import abstract

    rgb, (truth,) = textured_photo([(170, 120, 80, 60, (0.95, 0.75, 0.2))])
    result = abstract(rgb, kind="photo", tolerance=4.0, progress=False)
    assert result.lines.subject.method == "auto"
    assert result.final.params["max_arc_distance"] == 4.0
    from img2logo import quality

    assert quality.outside_fraction(quality.logo_points(result.final), truth) == 0.0
    assert quality.silhouette_recall(quality.logo_points(result.final), truth) > 0.95
    none = abstract(rgb, kind="photo", foreground="none", max_arc_distance=None, progress=False)
    assert none.lines.subject.mask is None and "max_arc_distance" not in none.final.params


@pytest.mark.parametrize("name", ["clipart-seal.png", "clipart-giraffe.png"])
def test_images_whose_initial_fit_did_not_converge_give_a_logo(name):
    # Both stopped with "the connectivity-constrained fit of the initial segments did
    # not converge": golden radii rounded below half their junctions' distance.
    res = abstract(DATA.parent / "benchmarks" / "data" / name, progress=False)
    assert res.lines.kind == "clipart"
    # Within T, or past it up to stretch x T where the logo had more than its arc budget (the giraffe).
    assert res.final.similarity <= res.final.tolerance * res.final.params["stretch"]
    validate_document(to_document(res.final))
    assert res.progression.stats["released_junctions"] == 0  # exact connectivity, nothing released


# --- an input over the size bound: results in its pixels --------------------
def _downscaled_fish():
    """drawing-fish.png (512 px) loaded with a 256 px bound: the work at half size, as a 4096 px input at 2048."""
    import warnings

    from img2logo.images.loading import DownscaleWarning, load_image

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DownscaleWarning)
        return load_image(DATA / "drawing-fish.png", max_side=256)


def test_a_downscaled_input_gets_its_result_in_its_own_pixels(tmp_path):
    import cv2
    from scipy import ndimage

    from img2logo.export import contract, writers

    img = _downscaled_fish()
    assert (img.width, img.scale, img.input_width, img.input_height) == (256, 0.5, 512, 512)
    result = abstract(img, progress=False)
    final = result.final
    assert (final.width, final.height) == (512, 512)
    contract.to_document(final, check=True)  # every radius exactly on its ladder, junctions on their arcs
    assert result.bias == final.bias and final.tolerance == pytest.approx(10.0)  # T = 5 px of the working image
    # The arcs lie on the fish's ink at full size: the distance from their samples to a stroke pixel.
    ink = cv2.imread(str(DATA / "drawing-fish.png"), cv2.IMREAD_GRAYSCALE) < 128
    distance = ndimage.distance_transform_edt(~ink)
    pts = np.concatenate([a.circle.point_at(np.linspace(a.theta0, a.theta0 + a.sweep, 50)) for a in final.arcs])
    inside = (pts >= 0).all(axis=1) & (pts < 512).all(axis=1)
    assert inside.mean() > 0.99
    d = distance[pts[inside, 1].astype(int), pts[inside, 0].astype(int)]
    assert np.median(d) < 3.0
    svg = writers.to_svg(final)
    assert 'viewBox="0 0 512 512"' in svg
    writers.write_png(final, tmp_path / "f.png", image=img.rgb)  # the working image stretched under it
    assert cv2.imread(str(tmp_path / "f.png")).shape[:2] == (512, 512)


def test_masks_of_a_downscaled_input_are_given_at_its_size():
    img = _downscaled_fish()
    full = np.zeros((512, 512), bool)
    full[:, :256] = True  # the left half: its segments are never merged
    result = abstract(img, progress=False, lock_mask=full, merging=False)
    assert result.final.params["locked_segments"] > 0
    with pytest.raises(InvalidParameterError, match=r"lock_mask: mask must have the input image's shape \(512, 512\)"):
        abstract(img, progress=False, lock_mask=np.zeros((256, 256), bool))


def test_a_symmetric_logo_of_a_downscaled_input_keeps_its_axis_in_its_pixels():
    import warnings

    from img2logo.fit.symmetry import is_symmetric
    from img2logo.images.loading import DownscaleWarning, load_image

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DownscaleWarning)
        img = load_image(drawing("Y", size=400), max_side=200)  # the Y is mirror-symmetric about x = 100
    result = abstract(img, progress=False, symmetry="vertical")
    record = result.final.params["symmetry"]
    assert record["point"][0] == pytest.approx(100.5, abs=3.0)  # in the input's pixels, not the working 50
    assert is_symmetric(result.final, record["point"], record["direction"])


def test_a_photo_over_the_photo_working_size_is_worked_at_it_and_drawn_in_its_own_pixels():
    """A photo is worked at PHOTO_WORK_SIDE px, the size its defaults were chosen at."""
    import warnings

    import cv2

    from img2logo.export import contract
    from img2logo.images.loading import DownscaleWarning
    from img2logo.pipeline import PHOTO_WORK_SIDE

    small = cv2.cvtColor(cv2.imread(str(DATA / "photo-flower.png")), cv2.COLOR_BGR2RGB)  # 512 x 342
    big = cv2.resize(small, (1024, 684), interpolation=cv2.INTER_CUBIC)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = abstract(big, progress=False)
    said = [str(w.message) for w in caught if issubclass(w.category, DownscaleWarning)]
    assert said == [
        f"<array>: a photo is worked at {PHOTO_WORK_SIDE} px on its longer side: 512x342 px "
        "(the results are in the input's 1024x684 px)"
    ]
    assert (result.image.width, result.image.height, result.image.scale) == (512, 342, 0.5)
    assert result.lines.kind == "photo" and result.lines.reason.endswith("a photo")  # detected, not "given"
    final = result.final
    assert (final.width, final.height) == (1024, 684) and final.tolerance == pytest.approx(10.0)
    contract.to_document(final, check=True)  # radii exactly on the ladder after the scale back
    # The same logo as the photo at 512 px, scaled by 2: its arcs' count is of the same order.
    at_512 = abstract(small, progress=False).final
    assert abs(len(final.arcs) - len(at_512.arcs)) <= max(3, len(at_512.arcs) // 4)
    # kind="photo" given: the same size, "given"; a photo at or under the size is worked as it is.
    with pytest.warns(DownscaleWarning, match="a photo is worked at"):
        given = abstract(big, kind="photo", progress=False)
    assert given.image.width == 512 and given.lines.reason == "given"
    # A subject rectangle is given, and said, in the input's pixels (the work is at half of them).
    with pytest.warns(DownscaleWarning):
        boxed = abstract(big, subject=(200, 60, 620, 560), progress=False)
    assert boxed.lines.subject.description.startswith("kept the object in 200,60,620,560 (GrabCut)")
    assert abstract(small, progress=False).image.width == 512


def test_an_upscaled_clip_art_gives_the_logo_of_its_original():
    """Worked at SYNTHETIC_WORK_SIDE = 512 px, a clip art upscaled to 700 px is its 512 px original again.

    The resampled copy has other regions (5 where the original has 8: its edges are blends), so the
    two logos differ in detail: 20 and 25 arcs since the silhouette's arcs are held to T (23 and 23
    before), their points within 6 px of each other for 0.78 and 0.95 of them (0.79 and 0.94 before).
    """
    import cv2
    from scipy.spatial import cKDTree

    from img2logo.constants import SYNTHETIC_WORK_SIDE
    from img2logo.quality import logo_points

    small = cv2.imread(str(DATA / "clipart-fish.png"))
    big = cv2.resize(small, (700, 700), interpolation=cv2.INTER_NEAREST)
    with pytest.warns(UserWarning, match="a clip art or a drawing is worked at 512 px"):
        result = abstract(big[:, :, ::-1], progress=False)
    assert SYNTHETIC_WORK_SIDE == 512 and result.lines.kind == "clipart"
    assert (result.image.width, result.final.width) == (512, 700)
    original = abstract(small[:, :, ::-1], progress=False).final
    assert abs(len(result.final.arcs) - len(original.arcs)) <= 5
    ours, theirs = logo_points(result.final) * 512 / 700, logo_points(original)
    assert np.mean(cKDTree(ours).query(theirs)[0] <= 6.0) >= 0.75
    assert np.mean(cKDTree(theirs).query(ours)[0] <= 6.0) >= 0.9


def test_a_clip_art_or_a_drawing_over_the_synthetic_working_size_is_worked_at_it(monkeypatch):
    """Clip art and drawings are worked at SYNTHETIC_WORK_SIDE px (here made 256 to stay small), with one warning,
    their results in the input's pixels; the photo test runs once, on that working copy."""
    import functools
    import warnings

    from img2logo import pipeline
    from img2logo.export import contract
    from img2logo.images.loading import DownscaleWarning, LoadedImage

    monkeypatch.setattr(pipeline, "SYNTHETIC_WORK_SIDE", 256)
    measured = []
    original = LoadedImage.__dict__["flat_fraction"].func

    def counted(self):
        measured.append(self.width)
        return original(self)

    prop = functools.cached_property(counted)
    prop.__set_name__(LoadedImage, "flat_fraction")
    monkeypatch.setattr(LoadedImage, "flat_fraction", prop)
    for name, kind in (("clipart-fish", "clipart"), ("drawing-fish", "drawing")):
        measured.clear()
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            result = abstract(DATA / f"{name}.png", progress=False)
        said = [str(w.message) for w in caught if issubclass(w.category, DownscaleWarning)]
        assert said == [
            f"{DATA / name}.png: a clip art or a drawing is worked at 256 px on its longer side: 256x256 px "
            "(the results are in the input's 512x512 px)"
        ]
        assert result.lines.kind == kind and (result.image.width, result.image.scale) == (256, 0.5)
        assert measured == [256]  # once: the pipeline's photo test, reused by the kind detection
        final = result.final
        assert (final.width, final.height) == (512, 512) and final.tolerance == pytest.approx(10.0)
        contract.to_document(final, check=True)
    with pytest.warns(DownscaleWarning, match="a clip art or a drawing is worked at 256 px"):
        given = abstract(DATA / "drawing-fish.png", kind="drawing", progress=False)
    assert given.image.width == 256 and given.lines.reason == "given"


def test_a_photo_over_the_synthetic_working_size_is_worked_at_the_photo_size_with_one_warning(monkeypatch):
    """The photo test runs on the synthetic working copy; a photo is then shrunk from the loaded image."""
    import warnings

    from img2logo import pipeline
    from img2logo.images.loading import DownscaleWarning

    monkeypatch.setattr(pipeline, "SYNTHETIC_WORK_SIDE", 384)  # the cat is 451 x 300
    monkeypatch.setattr(pipeline, "PHOTO_WORK_SIDE", 256)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        result = abstract(DATA / "photo-cat.png", progress=False)
    said = [str(w.message) for w in caught if issubclass(w.category, DownscaleWarning)]
    assert said == [
        f"{DATA}/photo-cat.png: a photo is worked at 256 px on its longer side: 256x170 px "
        "(the results are in the input's 451x300 px)"
    ]
    assert result.lines.kind == "photo" and result.lines.reason.endswith("a photo")
    assert (result.image.width, result.final.width) == (256, 451)


def _ring_and_dot(ring: bool, dot: bool):
    import cv2
    import numpy as np

    im = drawing("Y") if dot else np.full((200, 200, 3), 255, np.uint8)
    if ring:
        cv2.circle(im, (100, 100), 50, (0, 0, 0), 12)
    if dot:
        cv2.circle(im, (150, 150), 4, (0, 0, 0), -1)  # a 9 px filled dot (an eye)
    return im


def test_a_12_px_black_ring_is_one_circle_stroked_12_px():
    result = abstract(_ring_and_dot(ring=True, dot=False), progress=False)
    assert result.lines.kind == "drawing"
    assert len(result.final.arcs) == 1 and result.final.arcs[0].is_full_circle
    circle = result.final.arcs[0].circle
    assert abs(circle.cx - 100.5) <= 1.0 and abs(circle.cy - 100.5) <= 1.0 and abs(circle.r - 50.0) <= 2.0
    assert abs(result.params["stroke_width"] - 12.0) <= 2.0
    assert result.final.params["stroke_width"] == result.params["stroke_width"]


def test_a_9_px_dot_becomes_one_full_golden_circle_at_the_dot():
    result = abstract(_ring_and_dot(ring=False, dot=True), progress=False)
    full = [a for a in result.final.arcs if a.is_full_circle]
    assert len(full) == 1
    c = full[0].circle
    assert math.hypot(c.cx - 150.5, c.cy - 150.5) <= 1.0 and c.r <= 4.5
    assert c.r == pytest.approx(PHI ** (c.k + result.bias), rel=1e-6)  # on the ladder


def test_a_jpeg_drawing_with_a_9_px_dot_keeps_one_full_circle_at_the_dot():
    import cv2

    _, data = cv2.imencode(".jpg", _ring_and_dot(ring=False, dot=True), [cv2.IMWRITE_JPEG_QUALITY, 70])
    result = abstract(cv2.imdecode(data, cv2.IMREAD_COLOR), progress=False)
    assert result.lines.kind == "drawing", result.lines.reason
    full = [a for a in result.final.arcs if a.is_full_circle]
    assert len(full) == 1
    c = full[0].circle
    assert math.hypot(c.cx - 150.5, c.cy - 150.5) <= 1.0 and c.r <= 4.5


def test_stroke_width_option_overrides_and_is_checked():
    result = abstract(_ring_and_dot(ring=True, dot=False), progress=False, stroke_width=3.0)
    assert result.params["stroke_width"] == 3.0
    assert "stroke_width" not in abstract(DATA / "clipart-fish.png", progress=False).params  # the default
    with pytest.raises(InvalidParameterError, match="stroke_width must be > 0, got -1"):
        abstract(_ring_and_dot(ring=True, dot=False), stroke_width=-1)


def _free_ends_at_line_ends(result) -> tuple[int, int]:
    """(free ends of the logo, how many of them lie within GAP_MAX px of an end of the input's lines).

    The fit may stop an arc a few px short of a stroke's tip (the beagle's forehead stroke: 3.3 px);
    a break where the input's line runs on has no line end within the near-miss distance.
    """
    from img2logo.constants import GAP_MAX
    from img2logo.quality import free_ends

    ends = free_ends(result.final)
    line_ends = result.graph.junctions[result.graph.valence == 1]
    if len(ends) == 0:
        return 0, 0
    if len(line_ends) == 0:
        return len(ends), 0
    near = np.hypot(*(ends[:, None, :] - line_ends[None, :, :]).transpose(2, 0, 1)).min(axis=1) <= GAP_MAX
    return len(ends), int(near.sum())


def test_closed_outlines_stay_whole_and_a_stroke_keeps_only_its_own_ends():
    """Known answers: the two discs' region boundaries are closed, so the logo has no free end; a Y
    drawn in strokes has three line ends, and the logo's free ends are those three."""
    from helpers import two_discs

    found, at_ends = _free_ends_at_line_ends(abstract(two_discs(), progress=False))
    assert found == at_ends == 0
    found, at_ends = _free_ends_at_line_ends(abstract(drawing("Y"), progress=False))
    assert found == at_ends == 3


@pytest.mark.parametrize("name", ["clipart-beagle", "drawing-toque"])
def test_every_free_end_of_a_real_logo_is_an_end_of_the_input_s_lines(name):
    """Openclipart: the merges, the simplification and the tangent joins leave no dangling end where
    the input's line runs on; the free ends are the ends of its strokes (a clip art's thin marks
    drawn as centre lines, a drawing's fold lines)."""
    result = abstract(DATA.parent / "benchmarks" / "data" / "openclipart" / f"{name}.png", progress=False)
    found, at_ends = _free_ends_at_line_ends(result)
    assert found > 0
    assert at_ends == found


@pytest.mark.parametrize(("name", "least"), [("clipart-pansement", 0.97), ("clipart-beagle", 0.94)])
def test_a_real_clip_art_s_silhouette_survives_the_fit(name, least):
    """Openclipart: the silhouette is in the segment graph whole (sil6 of the first level about 1.0) and the
    merges and tangent joins no longer cut it (final sil6 0.84 for the bandage, whose rounded ends were
    cut by single arcs, and 0.89 for the beagle, before its arcs were held to T). The beagle's bound
    leaves room for the eye it keeps at the level T allows (0.949 with it, 0.97 without)."""
    import cv2

    from img2logo.quality import logo_points, silhouette_recall

    folder = DATA.parent / "benchmarks" / "data" / "openclipart"
    result = abstract(folder / f"{name}.png", progress=False)
    mask = cv2.imread(str(folder / f"{name}.silhouette.png"), cv2.IMREAD_GRAYSCALE) > 127
    assert silhouette_recall(logo_points(result.final), mask) >= least


def _several_regions() -> np.ndarray:
    """An ellipse with three round bumps, each bump and a square on the body of a colour of its own, at 4x, reduced."""
    import cv2

    s = 4
    big = np.full((256 * s, 256 * s, 3), 255, np.uint8)
    cv2.ellipse(big, (128 * s, 128 * s), (90 * s, 60 * s), 0, 0, 360, (200, 120, 40), -1)
    colours = [(40, 120, 200), (60, 170, 80), (150, 60, 160)]
    for angle, colour in zip(np.radians([40, 150, 260]), colours, strict=True):
        centre = (int((128 + 90 * np.cos(angle)) * s), int((128 + 60 * np.sin(angle)) * s))
        cv2.circle(big, centre, 12 * s, colour, -1)
    cv2.rectangle(big, (100 * s, 90 * s), (156 * s, 166 * s), (230, 200, 90), -1)
    return cv2.resize(big, (256, 256), interpolation=cv2.INTER_AREA)


@pytest.mark.parametrize("detail", [24, 1])
def test_a_silhouette_made_of_several_regions_is_kept_whole(detail):
    """Known answer: the outline runs through four regions (the body and three bumps); whether they stay
    (detail 24) or merge into one (detail 1), every pixel of it is within T (and the pixel between the
    line and the mask's edge) of the logo: 18.0 and 14.4 px at the farthest when its arcs were held
    to T only on average, the bumps cut off."""
    import cv2
    from scipy.spatial import cKDTree

    from img2logo.quality import logo_points

    image = _several_regions()
    edge = cv2.Canny((image < 245).any(axis=2).astype(np.uint8) * 255, 50, 100) > 0
    outline = np.argwhere(edge)[:, ::-1] + 0.5  # (x, y) px
    result = abstract(image, progress=False, detail=detail)
    assert int(result.lines.regions.max()) + 1 == (6 if detail == 24 else 2)
    farthest = cKDTree(logo_points(result.final)).query(outline)[0].max()
    assert farthest <= result.final.params["tolerance"] + 2.0
