"""Tests of img2logo.design.fills: colour fills of the faces of a logo (paper Fig. 18): palettes, gradients, auto."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import A, B, abstraction_of, full, golden, two_circles, two_discs

from img2logo.design import arrangement, fills
from img2logo.design.arrangement import Face
from img2logo.design.fills import Fill, FillSpec, Gradient
from img2logo.errors import InvalidImageError, InvalidParameterError

# --- palettes, gradients ----------------------------------------------------------------


def test_palette_deals_colours_by_area_and_keeps_neighbours_apart():
    a = two_circles()
    found = arrangement.faces(a)
    fs = fills.fill_palette(a, ["#FF0000", "#00ff00", (0.0, 0.0, 1.0)])
    assert [f.color for f in fs] == ["#ff0000", "#00ff00", "#0000ff"]
    assert [f.face for f in fs] == [0, 1, 2]
    assert [f.path for f in fs] == [f.path for f in found]
    assert fs == fills.fill_palette(a, ["#FF0000", "#00ff00", (0.0, 0.0, 1.0)], faces=found)  # deterministic
    # Two colours: the crescents take them in turn; the lens borders both, so the cycle's colour.
    assert [f.color for f in fills.fill_palette(a, ["#111111", "#222222"])] == ["#111111", "#222222", "#111111"]
    # One colour for all.
    assert {f.color for f in fills.fill_palette(a, ["#123456"])} == {"#123456"}
    # A mapping fills only the faces it names.
    only = fills.fill_palette(a, {2: "#abcdef"})
    assert [(f.face, f.color) for f in only] == [(2, "#abcdef")]


def test_palette_validation():
    a = two_circles()
    with pytest.raises(InvalidParameterError, match="the palette is empty: give at least one colour"):
        fills.fill_palette(a, [])
    with pytest.raises(InvalidParameterError, match=r"palette colour 1 '#12345' is not of the form #rrggbb"):
        fills.fill_palette(a, ["#ffffff", "#12345"])
    with pytest.raises(InvalidParameterError, match=r"palette face index 3 is out of range \(the abstraction has 3"):
        fills.fill_palette(a, {3: "#ffffff"})
    with pytest.raises(InvalidParameterError, match="colors must be a sequence of colours or a mapping"):
        fills.fill_palette(a, "#ffffff")
    with pytest.raises(InvalidParameterError, match=r"palette colour 0 must be '#rrggbb' or 3 floats in \[0, 1\]"):
        fills.fill_palette(a, [(1.0, 2.0, 0.0)])


@pytest.mark.parametrize("kind", ["linear", "radial"])
def test_gradient_spans_the_logo_and_records_centroid_colours(kind):
    a = two_circles()
    found = arrangement.faces(a)
    fs = fills.fill_gradient(a, ["#ff0000", "#0000ff"], kind=kind, angle=0.0)
    assert len(fs) == 3 and len({f.gradient for f in fs}) == 1
    g = fs[0].gradient
    assert g.kind == kind and g.stops == ((0.0, "#ff0000"), (1.0, "#0000ff"))
    x0, x1 = A.cx - A.r, B.cx + B.r
    if kind == "linear":  # left to right across the bounding box of the faces
        assert g.start[0] == pytest.approx(x0, abs=0.01) and g.end[0] == pytest.approx(x1, abs=0.01)
        assert g.start[1] == pytest.approx(g.end[1])
    else:  # from the box's centre to its corner
        assert g.start == pytest.approx((0.5 * (x0 + x1), 100.0), abs=0.01)
    for f, face in zip(fs, found, strict=True):
        expected = g.color_at(np.array(face.centroid))
        assert f.color == "#{:02x}{:02x}{:02x}".format(*(round(v * 255) for v in expected))
    np.testing.assert_allclose(g.color_at(np.array([g.start, g.end])), [[1, 0, 0], [0, 0, 1]])
    assert 'stop-color="#ff0000"' in g.svg("g0") and f"{kind}Gradient" in g.svg("g0")


def test_gradient_validation():
    a = two_circles()
    with pytest.raises(InvalidParameterError, match="a gradient needs at least two colours, got 1"):
        fills.fill_gradient(a, ["#ffffff"])
    with pytest.raises(InvalidParameterError, match=r"kind must be one of 'linear', 'radial', got 'conic'"):
        fills.fill_gradient(a, ["#ffffff", "#000000"], kind="conic")
    with pytest.raises(InvalidParameterError, match="angle must be a finite number of radians, got nan"):
        fills.fill_gradient(a, ["#ffffff", "#000000"], angle=math.nan)
    with pytest.raises(InvalidParameterError, match="gradient stop 1: offsets must be non-decreasing"):
        Gradient("linear", ((0.5, "#000000"), (0.2, "#ffffff")), (0, 0), (1, 0))
    with pytest.raises(InvalidParameterError, match="gradient start and end must differ"):
        Gradient("radial", ((0.0, "#000000"), (1.0, "#ffffff")), (1, 1), (1, 1))


def test_fill_validation():
    with pytest.raises(InvalidParameterError, match=r"fill color 'red' is not of the form #rrggbb"):
        Fill("M 0 0 A 1 1 0 0 1 2 0 Z", "red")
    with pytest.raises(InvalidParameterError, match="fill path must be SVG path data starting with 'M'"):
        Fill("", "#ffffff")
    assert Fill("M 0 0 A 1 1 0 0 1 2 0 Z", "#ABCDEF").color == "#abcdef"


# --- automatic colours from the image (Sec. 9 future work) ----------------------------------


def test_auto_colours_of_two_disc_clip_art(discs_result):
    a = discs_result.final
    found = arrangement.faces(a)
    auto = fills.fill_auto(a, discs_result.image.rgb, faces=found)
    colours = sorted(tuple(int(f.color[k : k + 2], 16) for k in (1, 3, 5)) for f in auto)
    # The blue disc (drawn over the red one) and the red disc's visible crescent: within 6 / 255 per channel.
    assert len(auto) == 2
    for got, want in zip(colours, [(40, 90, 220), (220, 40, 40)], strict=True):
        assert np.max(np.abs(np.subtract(got, want))) <= 6
    # The white background is bounded by no arc: no fill is white; every face inside got a colour.
    assert all(f.color != "#ffffff" for f in auto)
    assert {f.face for f in auto} == set(range(len(found)))
    # A LoadedImage and a uint8 array work too, and give the same colours.
    assert fills.fill_auto(a, discs_result.image) == auto
    assert [f.color for f in fills.fill_auto(a, two_discs())] == [f.color for f in auto]


def test_auto_fills_enclosed_faces_of_the_background_colour_and_leaves_border_faces_empty():
    size = 200
    image = np.full((size, size, 3), 255, np.uint8)
    yy, xx = np.mgrid[0:size, 0:size] + 0.5
    c_red, c_white, c_edge = golden(70.0, 100.0, 8), golden(150.0, 100.0, 6), golden(195.0, 40.0, 5)
    image[np.hypot(xx - c_red.cx, yy - c_red.cy) < c_red.r] = (200, 30, 60)
    a = abstraction_of([full(c_red), full(c_white), full(c_edge)], width=size, height=size)
    auto = fills.fill_auto(a, image)
    # The white disc is enclosed (a penguin's belly): it keeps its white; the circle
    # crossing the border reaches outside and stays empty.
    assert sorted(f.color for f in auto) == ["#c81e3c", "#ffffff"]
    assert auto[0].face == 0 and arrangement.faces(a)[0].area == pytest.approx(math.pi * c_red.r**2)
    # On request, faces of the border's colour are left empty.
    (only,) = fills.fill_auto(a, image, background="auto")
    assert only.color == "#c81e3c"
    assert fills.fill_auto(a, image, background="#c81e3c", background_distance=5.0)[0].color == "#ffffff"


def test_auto_leaves_transparent_faces_empty():
    size = 200
    rgba = np.zeros((size, size, 4), np.uint8)  # transparent black
    yy, xx = np.mgrid[0:size, 0:size] + 0.5
    c_body, c_belly, c_hole = golden(100.0, 100.0, 9), golden(80.0, 100.0, 6), golden(140.0, 100.0, 4)
    body = np.hypot(xx - c_body.cx, yy - c_body.cy) < c_body.r
    rgba[body] = (20, 20, 20, 255)
    rgba[np.hypot(xx - c_belly.cx, yy - c_belly.cy) < c_belly.r] = (255, 255, 255, 255)
    rgba[np.hypot(xx - c_hole.cx, yy - c_hole.cy) < c_hole.r] = (0, 0, 0, 0)  # a hole through the body
    a = abstraction_of([full(c_body), full(c_belly), full(c_hole)], width=size, height=size)
    colours = sorted(f.color for f in fills.fill_auto(a, rgba))
    assert colours == ["#141414", "#ffffff"]  # body and belly; the hole shows the page


def test_auto_validation():
    a = two_circles()
    with pytest.raises(InvalidImageError, match=r"image: image must be 200 x 250 px"):
        fills.fill_auto(a, np.zeros((10, 10, 3)))
    with pytest.raises(InvalidParameterError, match=r"inset must be >= 0, got -1\.0"):
        fills.fill_auto(a, np.zeros((200, 250, 3)), inset=-1)


def test_auto_fills_of_the_clip_art_sit_inside_the_arcs(data_dir):
    """Fills are drawn where the input has their colour: no leak across the arcs (clip art fish)."""
    import img2logo

    result = img2logo.abstract(data_dir / "clipart-fish.png")
    a = result.final
    found = arrangement.faces(a)
    auto = fills.fill_auto(a, result.image.rgb, faces=found)
    assert len(auto) >= 4
    rgb = result.image.rgb
    rows, cols = np.mgrid[0 : a.height, 0 : a.width]
    import shapely

    agree = []
    for f in auto:
        inside = shapely.contains_xy(found[f.face].polygon.buffer(-6.0), cols + 0.5, rows + 0.5)
        colour = np.array([int(f.color[k : k + 2], 16) for k in (1, 3, 5)]) / 255.0
        agree.append(np.mean(np.abs(rgb[inside] - colour).max(axis=1) < 0.1))
    assert np.mean(agree) > 0.9
    assert isinstance(found[0], Face)


# --- the command line option ------------------------------------------------------------


def test_parse_fill_option():
    assert fills.parse_fill_option("auto") == FillSpec("auto")
    assert fills.parse_fill_option(" None ") == FillSpec("none")
    assert fills.parse_fill_option("palette:#FF0000, #00ff00") == FillSpec("palette", ("#ff0000", "#00ff00"))
    assert fills.parse_fill_option("palette:#123456").colors == ("#123456",)
    lin = fills.parse_fill_option("linear@45:#000000,#ffffff,#ff0000")
    assert lin.mode == "linear" and lin.angle == pytest.approx(math.pi / 4) and len(lin.colors) == 3
    assert fills.parse_fill_option("radial:#000000,#ffffff").mode == "radial"
    a = two_circles()
    assert fills.parse_fill_option("none").make(a) == ()
    assert len(fills.parse_fill_option("palette:#123456").make(a)) == 3
    assert fills.parse_fill_option("linear:#000000,#ffffff").make(a)[0].gradient is not None


@pytest.mark.parametrize(
    ("spec", "message"),
    [
        ("palette:", "fill option 'palette:': the palette is empty: give at least one #rrggbb colour after 'palette:'"),
        ("palette", "fill option 'palette': give the colours after 'palette:', e.g. palette:#1f77b4,#ff7f0e"),
        ("palette:#12345", "fill option 'palette:#12345': colour 1 '#12345' is not of the form #rrggbb"),
        ("palette:#ffffff,red", "fill option 'palette:#ffffff,red': colour 2 'red' is not of the form #rrggbb"),
        ("palette:#ffffff,", "fill option 'palette:#ffffff,': colour 2 '' is not of the form #rrggbb"),
        ("linear:#ffffff", "fill option 'linear:#ffffff': a linear gradient needs at least two #rrggbb colours, got 1"),
        ("radial:", "fill option 'radial:': a radial gradient needs at least two #rrggbb colours, got 0"),
        ("linear@up:#000000,#ffffff", "fill option 'linear@up:#000000,#ffffff': the angle after '@' must be"),
        ("rainbow", "fill option must be 'none', 'auto', 'palette:#rrggbb,#rrggbb,...', "),
        ("auto:#ffffff", "fill option must be 'none', 'auto', "),
        ("radial@30:#000000,#ffffff", "fill option must be 'none', 'auto', "),
        ("", "fill option must be 'none', 'auto', "),
    ],
)
def test_parse_fill_option_errors(spec, message):
    with pytest.raises(InvalidParameterError) as info:
        fills.parse_fill_option(spec)
    assert str(info.value).startswith(message)


def test_auto_option_needs_the_image():
    with pytest.raises(InvalidParameterError, match="fill mode 'auto' needs the input image, got None"):
        fills.parse_fill_option("auto").make(two_circles())
    with pytest.raises(InvalidParameterError, match="fill option must be a string, got int"):
        fills.parse_fill_option(3)
