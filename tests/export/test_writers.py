"""Tests of img2logo.export.writers: JSON, SVG and PNG files of a result (with fills), deterministic bytes."""

from __future__ import annotations

import io
import json
import math
import os
import re
import subprocess
import threading
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from helpers import (
    DATA,
    HEIGHT,
    WIDTH,
    abstraction_of,
    four_arcs,
    full,
    golden,
    make_abstraction,
    modules_loaded,
    palette_fills,
    small_graph,
    svg_arc_center,
)

from img2logo.constants import FORMAT_NAME
from img2logo.design import fills
from img2logo.errors import InvalidImageError, InvalidParameterError
from img2logo.export import contract, writers
from img2logo.geometry.primitives import Arc

SVG = "{http://www.w3.org/2000/svg}"
INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"
SODIPODI = "{http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd}"
OWN = "{urn:img2logo:svg:1}"


def test_write_json_deterministic_and_readable(tmp_path):
    a = make_abstraction()
    p1 = writers.write_json(a, tmp_path / "one.json")
    p2 = writers.write_json(make_abstraction(), str(tmp_path / "two.json"))
    assert p1 == tmp_path / "one.json" and p2 == tmp_path / "two.json"
    data = p1.read_bytes()
    assert data == p2.read_bytes()
    assert data.endswith(b"\n")
    doc = json.loads(data)
    assert list(doc) == sorted(doc)
    contract.validate_document(doc)
    b = writers.read_json(p1)
    assert b.arcs == a.arcs
    (tmp_path / "bad.json").write_text("{not json")
    with pytest.raises(InvalidParameterError, match="is not JSON"):
        writers.read_json(tmp_path / "bad.json")


def test_read_json_errors_are_img2logo_errors(tmp_path):
    # a missing file was a bare FileNotFoundError.
    from img2logo.errors import Img2LogoError, InputNotFoundError

    with pytest.raises(InputNotFoundError, match=r"^JSON file not found: .*nope\.json$") as info:
        writers.read_json(tmp_path / "nope.json")
    assert isinstance(info.value, Img2LogoError) and isinstance(info.value, FileNotFoundError)
    with pytest.raises(InvalidParameterError, match=r"is a folder, not a JSON file"):
        writers.read_json(tmp_path)
    os.mkfifo(tmp_path / "pipe.json")  # read, it would block
    with pytest.raises(InvalidParameterError, match=r"pipe\.json is not a regular file"):
        writers.read_json(tmp_path / "pipe.json")
    (tmp_path / "latin.json").write_bytes(b"\xff\xfe{")
    with pytest.raises(InvalidParameterError, match=r"latin\.json is not JSON: not UTF-8 text"):
        writers.read_json(tmp_path / "latin.json")


def test_invalid_document_is_not_written(tmp_path):
    with pytest.raises(InvalidParameterError, match="must be JSON-safe"):
        writers.write_json(make_abstraction(), tmp_path / "a.json", params={"obj": object()})
    assert list(tmp_path.iterdir()) == []


# --- SVG --------------------------------------------------------------------------------


def parse_path(d: str) -> tuple[tuple[float, float], list[tuple[float, int, int, float, float]], bool]:
    """Split path data 'M x y A r r 0 L S x y ... [Z]' into its start, arc commands and closure."""
    tokens = d.split()
    assert tokens[0] == "M"
    start = (float(tokens[1]), float(tokens[2]))
    commands, i = [], 3
    while i < len(tokens) and tokens[i] == "A":
        rx, ry, rot, large, sweep, x, y = tokens[i + 1 : i + 8]
        assert rx == ry and rot == "0"
        commands.append((float(rx), int(large), int(sweep), float(x), float(y)))
        i += 8
    closed = i < len(tokens) and tokens[i] == "Z"
    assert i + closed == len(tokens)
    return start, commands, closed


def test_svg_structure_and_exact_arcs(tmp_path):
    a = make_abstraction()
    path = writers.write_svg(a, tmp_path / "logo.svg")
    root = ET.parse(path).getroot()
    assert root.tag == f"{SVG}svg"
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == ("200", "160", "0 0 200 160")
    title, desc = root.find(f"{SVG}title"), root.find(f"{SVG}desc")
    assert title is not None and desc is not None
    for fragment in (FORMAT_NAME, "bias=0.3", "level=2", "E^s=0.5 px"):
        assert fragment in desc.text
    paths = root.findall(f".//{SVG}path")
    assert [p.get("id") for p in paths] == [f"arc-{i}" for i in range(5)]
    assert [p.get(f"{OWN}circle") for p in paths] == ["0", "1", "2", "3", "0"]
    assert [p.get(f"{OWN}k") for p in paths] == ["8", "7", "4", "5", "8"]
    arcs_layer = root.find(f"{SVG}g[@id='arcs']")
    assert arcs_layer.get(f"{INKSCAPE}groupmode") == "layer"
    assert arcs_layer.get(f"{INKSCAPE}label") == "Arcs"
    assert arcs_layer.get("stroke") == "#000000" and arcs_layer.get("fill") == "none"
    assert arcs_layer.get("stroke-linecap") == "round" and arcs_layer.get("stroke-linejoin") == "round"
    assert "display" not in (arcs_layer.get("style") or "")
    for arc, element in zip(a.arcs, paths, strict=True):
        start, commands, closed = parse_path(element.get("d"))
        np.testing.assert_allclose(start, arc.start, atol=1e-6)
        np.testing.assert_allclose(commands[-1][3:], arc.end, atol=1e-6)
        assert closed == arc.is_full_circle
        # Reconstruct each command's circle the way a renderer does: same centre, same total sweep.
        total, (x, y) = 0.0, start
        for r, large, sweep, x2, y2 in commands:
            assert r == pytest.approx(arc.circle.r, abs=1e-6)
            cx, cy, dt = svg_arc_center(x, y, r, large, sweep, x2, y2)
            assert (cx, cy) == pytest.approx((arc.circle.cx, arc.circle.cy), abs=1e-4)
            total += dt
            x, y = x2, y2
        assert total == pytest.approx(arc.sweep, abs=1e-5)


def test_svg_flags():
    a = make_abstraction()
    root = ET.fromstring(writers.to_svg(a))
    ds = {p.get("id"): p.get("d") for p in root.iter(f"{SVG}path")}
    # Arc 0: positive sweep of 2 rad -> small arc, clockwise on screen (sweep-flag 1).
    _, cmds, _ = parse_path(ds["arc-0"])
    assert [(c[1], c[2]) for c in cmds] == [(0, 1)]
    # Arc 1: negative sweep of 1.5 rad -> small, sweep-flag 0.
    _, cmds, _ = parse_path(ds["arc-1"])
    assert [(c[1], c[2]) for c in cmds] == [(0, 0)]
    # Arc 2: full circle -> two half arcs and Z, back at the start.
    start, cmds, closed = parse_path(ds["arc-2"])
    assert len(cmds) == 2 and closed and cmds[-1][3:] == start
    assert ds["arc-2"].count("A ") == 2
    # Arc 3: 270 degrees with a negative sweep -> large-arc 1, sweep-flag 0, one command.
    _, cmds, _ = parse_path(ds["arc-3"])
    assert [(c[1], c[2]) for c in cmds] == [(1, 0)]


def test_svg_nearly_full_arc_split_in_two():
    c = golden(100.0, 80.0, 9)
    a = make_abstraction(
        arcs=(Arc(c, 0.3, -(2 * math.pi - 1e-5)),), arc_segments=((0,),), junctions=np.zeros((0, 2)), junction_arcs=()
    )
    root = ET.fromstring(writers.to_svg(a))
    _, cmds, closed = parse_path(root.find(f".//{SVG}path").get("d"))
    assert len(cmds) == 2 and not closed
    assert [(cmd[1], cmd[2]) for cmd in cmds] == [(0, 0), (0, 0)]
    np.testing.assert_allclose(cmds[-1][3:], a.arcs[0].end, atol=1e-6)


def test_svg_construction_layer():
    a = make_abstraction()
    root = ET.fromstring(writers.to_svg(a))
    layer = root.find(f"{SVG}g[@id='golden-circles']")
    assert layer is not None
    assert layer.get(f"{INKSCAPE}groupmode") == "layer"
    assert layer.get(f"{INKSCAPE}label") == "Golden circles"
    assert layer.get("style") == "display:none"
    assert layer.get(f"{SODIPODI}insensitive") == "true"  # locked: a click selects an arc, not a circle
    # Clipped to the image plus CONSTRUCTION_MARGIN x its longer side (200 px) on every side.
    clip = root.find(f"{SVG}clipPath[@id='golden-circles-clip']")
    assert layer.get("clip-path") == "url(#golden-circles-clip)"
    rect = clip.find(f"{SVG}rect")
    assert [float(rect.get(k)) for k in ("x", "y", "width", "height")] == [-100.0, -100.0, 400.0, 360.0]
    circles = layer.findall(f"{SVG}circle")
    assert [c.get("id") for c in circles] == ["circle-0", "circle-1", "circle-2", "circle-3"]
    assert [c.get(f"{OWN}k") for c in circles] == ["8", "7", "4", "5"]
    for element, circle in zip(circles, a.circles, strict=True):
        got = [float(element.get(key)) for key in ("cx", "cy", "r")]
        np.testing.assert_allclose(got, [circle.cx, circle.cy, circle.r], atol=1e-6)
    # The construction layer is drawn first (underneath the arcs).
    assert [g.get("id") for g in root.findall(f"{SVG}g")] == ["golden-circles", "arcs"]
    shown = ET.fromstring(writers.to_svg(a, show_construction_circles=True)).find(f"{SVG}g[@id='golden-circles']")
    assert shown is not None and shown.get("style") is None
    absent = ET.fromstring(writers.to_svg(a, construction_circles=False))
    assert absent.find(f"{SVG}g[@id='golden-circles']") is None
    assert not absent.findall(f".//{SVG}circle")
    assert len(absent.findall(f".//{SVG}path")) == 5


def test_svg_options_and_determinism(tmp_path):
    a = make_abstraction()
    root = ET.fromstring(writers.to_svg(a, stroke_width=3.25, image_size=(400, 320)))
    assert (root.get("width"), root.get("height"), root.get("viewBox")) == ("400", "320", "0 0 200 160")
    assert root.find(f"{SVG}g[@id='arcs']").get("stroke-width") == "3.25"
    p1 = writers.write_svg(a, tmp_path / "a.svg")
    p2 = writers.write_svg(make_abstraction(), tmp_path / "b.svg")
    assert p1.read_bytes() == p2.read_bytes()
    with pytest.raises(InvalidParameterError, match="stroke_width must be > 0"):
        writers.to_svg(a, stroke_width=0)
    with pytest.raises(InvalidParameterError, match="image_size must be a pair"):
        writers.to_svg(a, image_size=5)


def test_the_runs_stroke_width_param_strokes_svg_and_png(tmp_path):
    """A drawing's measured stroke width (params["stroke_width"]) is the default; an argument wins."""
    import cv2

    bold = make_abstraction(params={"kind": "drawing", "stroke_width": 12.5})
    assert ET.fromstring(writers.to_svg(bold)).find(f"{SVG}g[@id='arcs']").get("stroke-width") == "12.5"
    assert ET.fromstring(writers.to_svg(bold, stroke_width=2)).find(f"{SVG}g[@id='arcs']").get("stroke-width") == "2"
    plain = make_abstraction()  # no stroke_width param: the default, 1/128 of the longer side
    got = float(ET.fromstring(writers.to_svg(plain)).find(f"{SVG}g[@id='arcs']").get("stroke-width"))
    assert got == pytest.approx(max(1.0, max(plain.width, plain.height) / 128.0))
    # The PNG draws the full circle (arc 2, r = phi**(4 + 0.3) = 7.9 px) with the same width.
    thin = cv2.imread(str(writers.write_png(plain, tmp_path / "thin.png")), cv2.IMREAD_GRAYSCALE)
    thick = cv2.imread(str(writers.write_png(bold, tmp_path / "bold.png")), cv2.IMREAD_GRAYSCALE)
    assert (thick < 128).sum() > 3 * (thin < 128).sum()


def test_svg_writes_a_line_without_k():
    from img2logo.geometry.primitives import line_arc

    a = make_abstraction(
        arcs=(line_arc((10.0, 20.0), (90.0, 20.0)),), arc_segments=((0,),), junctions=np.zeros((0, 2)), junction_arcs=()
    )
    path = ET.fromstring(writers.to_svg(a)).find(f".//{SVG}path")
    assert path.get(f"{OWN}k") is None and path.get(f"{OWN}line") == "true"
    assert path.get("d") == "M 10 20 L 90 20"


# --- PNG --------------------------------------------------------------------------------


def read_png(path: Path) -> np.ndarray:
    import matplotlib.image

    return matplotlib.image.imread(path)


def darkness(img: np.ndarray, point: np.ndarray) -> float:
    """1 - mean RGB of the pixel under ``point`` (x, y), px."""
    j, i = int(point[0]), int(point[1])
    return 1.0 - float(img[i, j, :3].mean())


def test_png_size_determinism_and_orientation(tmp_path):
    a = make_abstraction()
    p1 = writers.write_png(a, tmp_path / "a.png", show_junctions=True)
    p2 = writers.write_png(make_abstraction(), tmp_path / "b.png", show_junctions=True)
    assert p1.read_bytes() == p2.read_bytes()
    img = read_png(p1)
    assert img.shape[:2] == (HEIGHT, WIDTH)
    assert darkness(img, (5.5, 5.5)) < 0.02  # white background
    for arc in a.arcs:
        mid = arc.circle.point_at(arc.theta0 + 0.5 * arc.sweep)
        assert darkness(img, mid) > 0.5, arc
    # y down: arc 3 (centre (40, 140), from angle 0 over -270 deg) covers the top of its circle
    # and leaves out the quarter towards +x +y (bottom right on screen).
    d = a.arcs[3].circle
    assert darkness(img, d.point_at(-math.pi / 2)) > 0.5
    assert darkness(img, d.point_at(math.pi / 4)) < 0.1
    # Arc 0 (positive sweep, ending at the intersection) runs over the top of the first circle.
    c = a.arcs[0].circle
    assert darkness(img, c.point_at(-math.pi / 2)) > 0.5
    assert darkness(img, c.point_at(math.pi / 2)) < 0.1


def test_png_with_background_image(tmp_path):
    a = make_abstraction()
    image = np.zeros((HEIGHT, WIDTH, 3), dtype=np.uint8)  # black image, faded to light grey
    img = read_png(writers.write_png(a, tmp_path / "bg.png", image=image, show_circles=True))
    assert img.shape[:2] == (HEIGHT, WIDTH)
    assert 0.2 < darkness(img, (5.5, 5.5)) < 0.6
    assert darkness(img, a.arcs[1].circle.point_at(a.arcs[1].theta0 - 0.7)) > 0.8
    with pytest.raises(InvalidImageError, match=r"image must be 160 x 200 px"):
        writers.write_png(a, tmp_path / "x.png", image=np.zeros((10, 10)))
    assert not (tmp_path / "x.png").exists()
    with pytest.raises(InvalidParameterError, match="dpi must be > 0"):
        writers.write_png(a, tmp_path / "x.png", dpi=0)


@pytest.mark.parametrize("form", ["rgb", "grey", "rgba", "uint16", "float"])
def test_png_over_the_input_has_the_bytes_matplotlib_draws(form):
    # The faded input is laid down pixel for pixel (figures._pixel_layer): the file is the one drawn with imshow.
    import matplotlib.style
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from img2logo.export import figures, plotting

    a = make_abstraction()
    rng = np.random.default_rng(3)
    image = {
        "rgb": rng.integers(0, 256, (HEIGHT, WIDTH, 3), dtype=np.uint8),
        "grey": rng.integers(0, 256, (HEIGHT, WIDTH), dtype=np.uint8),
        "rgba": rng.integers(0, 256, (HEIGHT, WIDTH, 4), dtype=np.uint8),
        "uint16": rng.integers(0, 65536, (HEIGHT, WIDTH, 3), dtype=np.uint16),
        "float": rng.random((HEIGHT, WIDTH, 3)),
    }[form]
    data = writers.png_bytes(a, image=image, fills=palette_fills(a), show_junctions=True)
    with matplotlib.style.context("default"):
        fig = Figure(figsize=(WIDTH / 100.0, HEIGHT / 100.0), dpi=100.0, facecolor="white")
        canvas = FigureCanvasAgg(fig)
        ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
        width = plotting.level_stroke_width(a) * 72.0 / 100.0
        plotting.plot_abstraction(a, ax, image=image, show_junctions=True, linewidth=width, fills=palette_fills(a))
        canvas.draw()
        drawn = np.asarray(canvas.buffer_rgba())[..., :3]
    assert np.array_equal(read_png_bytes(data), drawn / 255.0)
    pixels = plotting.faded_pixels(image, WIDTH, HEIGHT)
    assert pixels.dtype == np.uint8 and pixels.shape == (HEIGHT, WIDTH, 3)
    assert figures.png_bytes(a, image=image) != figures.png_bytes(a, image=255 - pixels)  # the input is drawn


@pytest.mark.parametrize("background", ["input", "white", "transparent"])
def test_png_run_length_deflate_keeps_the_pixels(background, monkeypatch):
    """A level's PNG is deflated with zlib's run-length strategy: the pixels of zlib's default, read by any decoder."""
    import cv2
    from PIL import Image

    from img2logo.export import figures

    a = make_abstraction()
    image = np.random.default_rng(5).integers(0, 256, (HEIGHT, WIDTH, 3), dtype=np.uint8)
    fast = writers.png_bytes(a, image=image, background=background, show_junctions=True)
    monkeypatch.setattr(figures, "PNG_ZLIB_STRATEGY", -1)
    default = writers.png_bytes(a, image=image, background=background, show_junctions=True)
    assert fast != default  # another deflate stream
    mine, theirs = Image.open(io.BytesIO(fast)), Image.open(io.BytesIO(default))
    assert mine.mode == theirs.mode and mine.info["dpi"] == theirs.info["dpi"]
    pixels = np.asarray(mine)
    assert np.array_equal(pixels, np.asarray(theirs))
    libpng = cv2.imdecode(np.frombuffer(fast, np.uint8), cv2.IMREAD_UNCHANGED)  # OpenCV's libpng: BGR(A)
    order = [2, 1, 0, 3] if pixels.shape[2] == 4 else [2, 1, 0]
    assert np.array_equal(libpng[..., order], pixels)


def test_png_figure_kept_for_the_next_draws_the_same_bytes(monkeypatch):
    """The emptied figure a PNG is drawn on again gives the bytes of a new one, also after a drawing that failed."""
    from img2logo.export import figures, plotting

    a, b = make_abstraction(), four_arcs()
    image = np.random.default_rng(7).integers(0, 256, (HEIGHT, WIDTH, 3), dtype=np.uint8)
    draws = [
        dict(level=a, image=image, fills=palette_fills(a), show_junctions=True),
        dict(level=b, background="white", show_circles=True),
        dict(level=a, background="transparent"),
        dict(level=a, image=image, scale=0.5),
        dict(level=a, image=image),
    ]

    def png(kw: dict, *, fresh: bool) -> bytes:
        if fresh:
            monkeypatch.setattr(figures, "_LAST_AXES", threading.local())
        kw = dict(kw)
        return writers.png_bytes(kw.pop("level"), **kw)

    new = [png(kw, fresh=True) for kw in draws]
    assert [png(kw, fresh=False) for kw in draws + draws] == new + new
    assert figures._LAST_AXES.kept is not None  # the last one was kept

    def fails(*args, **kwargs):
        raise RuntimeError("half-way")

    drawn = plotting.plot_abstraction
    monkeypatch.setattr(figures, "plot_abstraction", lambda *args, **kw: (drawn(*args, **kw), fails())[0])
    with pytest.raises(RuntimeError, match="half-way"):
        png(draws[4], fresh=False)
    monkeypatch.setattr(figures, "plot_abstraction", drawn)
    assert png(draws[4], fresh=False) == new[4]


def test_segment_graph_png(tmp_path):
    graph = small_graph()
    assert list(graph.valence) == [1, 3, 2, 1, 1]
    p = writers.write_segment_graph_png(graph, tmp_path / "g" / "graph.png")
    img = read_png(p)
    assert img.shape[:2] == (14, 20)
    assert darkness(img, (6.5, 2.5)) > 0.2  # on segment 0
    assert darkness(img, (5.5, 7.5)) < 0.05  # off the graph
    assert p.read_bytes() == writers.write_segment_graph_png(graph, tmp_path / "again.png").read_bytes()
    image = np.full((14, 20), 0.5)
    assert read_png(writers.write_segment_graph_png(graph, tmp_path / "bg.png", image=image)).shape[:2] == (14, 20)


# --- fills: SVG layer, gradients, PNG -------------------------------------------------------


def test_svg_fill_layer_is_under_the_arcs(tmp_path):
    a = four_arcs()
    fs = palette_fills(a)
    path = writers.write_svg(a, tmp_path / "logo.svg", fills=fs)
    root = ET.parse(path).getroot()
    layers = [g.get("id") for g in root.findall(f"{SVG}g")]
    assert layers == ["fills", "golden-circles", "arcs"]  # first drawn is underneath
    layer = root.find(f"{SVG}g[@id='fills']")
    assert layer.get(f"{INKSCAPE}groupmode") == "layer" and layer.get(f"{INKSCAPE}label") == "Fills"
    assert layer.get("stroke") == "none"
    paths = layer.findall(f"{SVG}path")
    assert [p.get("id") for p in paths] == ["fill-0", "fill-1", "fill-2"]
    assert [p.get("fill") for p in paths] == [f.color for f in fs]
    assert {p.get("fill-rule") for p in paths} == {"evenodd"}
    assert [p.get("d") for p in paths] == [f.path for f in fs]
    assert all(re.fullmatch(r"[MAZ0-9. \-]+", p.get("d")) for p in paths)  # arcs only, no polylines
    # Without fills the SVG has no fill layer and is unchanged.
    assert writers.to_svg(a) == writers.to_svg(a, fills=None)
    assert "Fills" not in writers.to_svg(a)


def test_fill_path_that_is_not_path_data_is_refused_and_never_lands_unescaped(tmp_path):
    # a '"' in Fill.path ended the d attribute: onload="..." landed in the file.
    evil = 'M 0 0 L 10 0 L 10 10 Z" onload="alert(1)'
    with pytest.raises(InvalidParameterError, match=r"fill path is not SVG path data: '\"' at character 22"):
        fills.Fill(evil, "#ff0000")
    with pytest.raises(InvalidParameterError, match=r"fill path is not SVG path data: '<'"):
        fills.Fill("M 0 0 <script/>", "#ff0000")
    forged = fills.Fill("M 0 0 L 10 0 L 10 10 Z", "#ff0000")
    object.__setattr__(forged, "path", evil)  # past the check: the writer escapes it still
    a = four_arcs()
    root = ET.parse(writers.write_svg(a, tmp_path / "x.svg", fills=[forged])).getroot()
    path = root.find(f"{SVG}g[@id='fills']/{SVG}path")
    assert path.get("d") == evil and path.get("onload") is None


def test_svg_gradient_defs(tmp_path):
    a = four_arcs()
    fs = fills.fill_gradient(a, ["#ff0000", "#ffff00", "#0000ff"], kind="radial")
    root = ET.fromstring(writers.to_svg(a, fills=fs))
    (grad,) = root.findall(f"{SVG}defs/{SVG}radialGradient")
    assert grad.get("id") == "fill-gradient-0" and grad.get("gradientUnits") == "userSpaceOnUse"
    assert [s.get("stop-color") for s in grad.findall(f"{SVG}stop")] == ["#ff0000", "#ffff00", "#0000ff"]
    assert {p.get("fill") for p in root.findall(f"{SVG}g[@id='fills']/{SVG}path")} == {"url(#fill-gradient-0)"}


def read_png_bytes(data: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"), dtype=np.float64) / 255.0


def test_png_shows_fills_with_holes(tmp_path):
    outer, inner = golden(120.0, 100.0, 9), golden(120.0, 100.0, 6)
    a = abstraction_of([full(outer), full(inner, 2.0, -1.0)])
    ring = fills.fill_palette(a, {0: "#0000ff"})  # the annulus only: its hole stays white
    png = read_png_bytes(writers.write_png(a, tmp_path / "ring.png", fills=ring).read_bytes())
    assert png.shape == (200, 250, 3)
    np.testing.assert_allclose(png[100, 120], [1, 1, 1])  # centre: in the hole
    np.testing.assert_allclose(png[100, 120 + 45], [0, 0, 1])  # between the circles
    np.testing.assert_allclose(png[5, 5], [1, 1, 1])  # outside
    # Gradients are drawn as gradients: top and bottom of the disc differ.
    grad = fills.fill_gradient(a, ["#ff0000", "#0000ff"])
    png = read_png_bytes(writers.write_png(a, tmp_path / "grad.png", fills=grad).read_bytes())
    assert png[40, 120, 0] > 0.7 and png[160, 120, 2] > 0.7


@pytest.mark.parametrize("which", ["palette", "gradient", "auto"])
def test_svg_renders_like_the_png(tmp_path, which, discs_result):
    """The SVG with fills, rendered by a real SVG renderer (resvg), matches the matplotlib PNG."""
    resvg_py = pytest.importorskip("resvg_py")
    if which == "auto":
        a = discs_result.final
        fs = fills.fill_auto(a, discs_result.image.rgb)
    else:
        outer, inner = golden(120.0, 100.0, 9), golden(120.0, 100.0, 6)
        a = abstraction_of([full(outer), full(inner, 2.0, -1.0), full(golden(60.0, 60.0, 6))])
        fs = palette_fills(a) if which == "palette" else fills.fill_gradient(a, ["#ff0000", "#00ffaa", "#0000ff"])
    svg = writers.write_svg(a, tmp_path / "logo.svg", fills=fs).read_text()
    rendered = read_png_bytes(bytes(resvg_py.svg_to_bytes(svg_string=svg, background="#ffffff")))
    drawn = read_png_bytes(writers.write_png(a, tmp_path / "logo.png", fills=fs).read_bytes())
    assert rendered.shape == drawn.shape == (a.height, a.width, 3)
    difference = np.abs(rendered - drawn)
    assert difference.mean() < 0.01
    assert np.mean(difference.max(axis=2) > 0.25) < 0.01  # differences only along anti-aliased edges


def test_import_does_not_load_matplotlib_jsonschema_or_scipy():
    code = "import img2logo.export.writers, img2logo.export.contract, img2logo.export.plotting"
    assert modules_loaded(code, "matplotlib", "jsonschema", "scipy") == []


def test_svg_numbers_circles_as_the_json_does_with_straight_lines(tmp_path):
    """A straight line's circle is no circle of the document: the SVG must not count it either.

    On the whale with ``lines=True`` the line comes before some arcs, so counting its circle
    shifted the SVG's ``img2logo:circle`` of every later arc by one against the JSON.
    """
    import img2logo

    a = img2logo.abstract(DATA / "drawing-whale.png", lines=True, progress=False).final
    assert any(arc.is_line for arc in a.arcs)
    doc = contract.to_document(a)
    svg = writers.to_svg(a)
    assert [int(c) for c in re.findall(r'img2logo:circle="(\d+)"', svg)] == [arc["circle"] for arc in doc["arcs"]]
    assert len(re.findall(r'<circle id="circle-', svg)) == len(doc["circles"]) == len(a.golden_circles)


# --- SVG 1.1 validity, clean PNGs, PDF, Inkscape ------------------------------------------


def test_svg_own_attributes_are_namespaced(tmp_path):
    """No undeclared ``data-*`` attribute (not SVG 1.1): img2logo's own are in its namespace, declared."""
    a = make_abstraction()
    text = writers.to_svg(a, fills=palette_fills(abstraction_of([full(golden(120.0, 100.0, 9))])))
    assert "data-" not in text
    assert f'xmlns:img2logo="{writers.SVG_METADATA_NS}"' in text
    root = ET.fromstring(text)  # namespaces well-formed (an undeclared prefix would not parse)
    for element in root.iter():
        for key in element.attrib:
            assert not key.startswith("{") or key.split("}")[0][1:] in (
                writers.SVG_METADATA_NS,
                "http://www.inkscape.org/namespaces/inkscape",
                "http://sodipodi.sourceforge.net/DTD/sodipodi-0.dtd",
            ), key


def test_png_clean_backgrounds_and_scale(tmp_path):
    a = make_abstraction()
    image = np.zeros((HEIGHT, WIDTH, 3), dtype=np.uint8)  # black: faded, it would be grey
    white = read_png(writers.write_png(a, tmp_path / "w.png", image=image, background="white"))
    assert white.shape == (HEIGHT, WIDTH, 3)  # opaque: no alpha channel
    assert darkness(white, (5.5, 5.5)) < 0.02  # no input under the logo
    assert darkness(white, a.arcs[0].circle.point_at(a.arcs[0].theta0 + 0.5 * a.arcs[0].sweep)) > 0.5
    clear = read_png(writers.write_png(a, tmp_path / "t.png", image=image, background="transparent"))
    assert clear.shape == (HEIGHT, WIDTH, 4)
    assert clear[5, 5, 3] == 0.0  # off the strokes: fully transparent
    mid = a.arcs[0].circle.point_at(a.arcs[0].theta0 + 0.5 * a.arcs[0].sweep)
    assert clear[int(mid[1]), int(mid[0]), 3] > 0.5 and clear[int(mid[1]), int(mid[0]), :3].max() < 0.1
    big = read_png(writers.write_png(a, tmp_path / "x3.png", background="white", scale=3.0))
    assert big.shape[:2] == (3 * HEIGHT, 3 * WIDTH)
    assert darkness(big, 3.0 * mid) > 0.5  # the same drawing, three times larger
    odd = read_png(writers.write_png(a, tmp_path / "odd.png", scale=0.37))
    assert odd.shape[:2] == (round(0.37 * HEIGHT), round(0.37 * WIDTH))
    # The default is today's look (over the input) when the image is given, white without.
    default = writers.write_png(a, tmp_path / "d.png", image=image).read_bytes()
    assert default == writers.write_png(a, tmp_path / "i.png", image=image, background="input").read_bytes()
    assert read_png(tmp_path / "d.png").shape == (HEIGHT, WIDTH, 3)
    with pytest.raises(InvalidParameterError, match="background must be one of 'input', 'white', 'transparent'"):
        writers.write_png(a, tmp_path / "bad.png", background="black")
    with pytest.raises(InvalidParameterError, match='background "input" needs the input image'):
        writers.write_png(a, tmp_path / "bad.png", background="input")
    with pytest.raises(InvalidParameterError, match="scale must be > 0"):
        writers.write_png(a, tmp_path / "bad.png", scale=0)
    with pytest.raises(InvalidParameterError, match=r"each side must be in 1..16384 px"):
        writers.write_png(a, tmp_path / "bad.png", scale=1000)
    with pytest.raises(InvalidParameterError, match=r"must be in 1..4096 px over the faded input"):
        writers.write_png(a, tmp_path / "bad.png", image=image, scale=1000)
    assert not (tmp_path / "bad.png").exists()


def test_png_size_is_the_input_size_bounded_by_the_working_size():
    """Without a scale, the input's size up to MAX_IMAGE_SIDE (a 12000 px input's PNG took 12 GB at full size)."""
    assert writers.png_size(512, 300) == (512, 300)
    assert writers.png_size(12000, 9000) == (2048, 1536)
    assert writers.png_size(12000, 9000, 0.5, "white") == (6000, 4500)
    assert writers.png_size(3000, 1000, 1.0, "input") == (3000, 1000)
    with pytest.raises(InvalidParameterError, match=r"scale 1 makes a 6000 x 4500 px PNG; .*1..4096 px over the faded"):
        writers.png_size(6000, 4500, 1.0, "input")
    with pytest.raises(InvalidParameterError, match="scale must be a number"):
        writers.png_size(512, 300, "2")


def test_pdf_is_vector_deterministic_and_renders_like_the_png(tmp_path):
    a = make_abstraction()
    p1 = writers.write_pdf(a, tmp_path / "a.pdf")
    data = p1.read_bytes()
    assert data.startswith(b"%PDF-") and data == writers.write_pdf(make_abstraction(), tmp_path / "b.pdf").read_bytes()
    assert b"CreationDate" not in data
    # 1 px = 1 pt: the page is the image's size.
    assert re.search(rb"/MediaBox \[\s*0 0 200 160\s*\]", data)
    pdftoppm = __import__("shutil").which("pdftoppm")
    if pdftoppm is None:
        pytest.skip("pdftoppm (poppler-utils) is not installed: the PDF is not rendered")
    subprocess.run([pdftoppm, "-png", "-r", "72", "-singlefile", str(p1), str(tmp_path / "r")], check=True)
    rendered = read_png(tmp_path / "r.png")[..., :3]
    drawn = read_png(writers.write_png(a, tmp_path / "a.png"))[..., :3]
    assert rendered.shape == drawn.shape == (HEIGHT, WIDTH, 3)
    ink_r, ink_d = rendered.mean(axis=2) < 0.5, drawn.mean(axis=2) < 0.5
    assert ink_d.sum() > 200
    assert (ink_r & ink_d).sum() / (ink_r | ink_d).sum() > 0.85  # the same strokes, by another renderer
    with pytest.raises(InvalidParameterError, match="stroke_width must be > 0"):
        writers.write_pdf(a, tmp_path / "bad.pdf", stroke_width=-1)
    assert not (tmp_path / "bad.pdf").exists()


def test_pdf_arcs_are_bezier_curves_not_polylines(tmp_path):
    import zlib

    a = make_abstraction()
    data = writers.write_pdf(a, tmp_path / "a.pdf").read_bytes()
    streams = [zlib.decompress(m) for m in re.findall(rb"stream\r?\n(.*?)endstream", data, re.S) if m[:1] == b"x"]
    content = b"\n".join(streams)
    curves = len(re.findall(rb" c\n", content))
    # matplotlib's Path.arc: 2 ** ceil(sweep / 90 deg) cubic pieces per arc (a polyline would have none).
    pieces = sum(2 ** math.ceil(abs(arc.sweep) / (math.pi / 2) - 1e-9) for arc in a.arcs)
    assert len(a.arcs) <= curves <= pieces


def test_inkscape_opens_the_svg_and_renders_it_like_resvg(tmp_path, discs_result):
    """A real result opened by Inkscape from the command line, exported to PNG, against resvg."""
    import shutil

    inkscape = shutil.which("inkscape")
    if inkscape is None:
        pytest.skip("inkscape is not installed (apt-get install inkscape): the SVG is not opened in Inkscape")
    resvg_py = pytest.importorskip("resvg_py")
    a = discs_result.final
    svg = writers.write_svg(a, tmp_path / "logo.svg")
    out = tmp_path / "inkscape.png"
    done = subprocess.run(
        [
            inkscape,
            str(svg),
            "--export-type=png",
            f"--export-filename={out}",
            "--export-background=#ffffff",
            "--export-background-opacity=1",
            "--export-area-page",
        ],
        capture_output=True,
        text=True,
        timeout=300,
        env={"HOME": str(tmp_path), "PATH": "/usr/bin:/bin"},
    )
    assert done.returncode == 0, done.stderr[-2000:]
    drawn = read_png(out)[..., :3]
    rendered = read_png_bytes(bytes(resvg_py.svg_to_bytes(svg_string=svg.read_text(), background="#ffffff")))
    assert drawn.shape == rendered.shape == (a.height, a.width, 3)
    assert np.abs(drawn - rendered).mean() < 0.01  # the hidden, clipped construction layer stays hidden
    # Inkscape reads the layers: the construction layer is locked and hidden.
    query = subprocess.run(
        [inkscape, str(svg), "--query-id=golden-circles", "--query-all"],
        capture_output=True,
        text=True,
        timeout=300,
        env={"HOME": str(tmp_path), "PATH": "/usr/bin:/bin"},
    )
    assert query.returncode == 0 and "arc-0" in query.stdout


@pytest.mark.parametrize(
    ("write", "name", "fmt"),
    [
        ("write_svg", "logo.pdf", "SVG"),
        ("write_png", "logo.jpg", "PNG"),
        ("write_json", "logo.svg", "JSON"),
        ("write_pdf", "logo.png", "PDF"),
    ],
)
def test_a_suffix_that_names_another_format_is_refused(tmp_path, write, name, fmt):
    """``write_svg(a, "logo.pdf")`` put SVG into a .pdf; a suffix of no format is the user's."""
    level = make_abstraction()
    with pytest.raises(InvalidParameterError, match=rf"names another format \(this writes {fmt}\); give a file name"):
        getattr(writers, write)(level, tmp_path / name)
    assert not (tmp_path / name).exists()
    assert getattr(writers, write)(level, tmp_path / "logo.out").is_file()


def test_write_is_the_formats_own_writer(tmp_path):
    a = make_abstraction()
    image = np.full((HEIGHT, WIDTH, 3), 200, np.uint8)
    own = {
        "json": lambda p: writers.write_json(a, p),
        "svg": lambda p: writers.write_svg(a, p),
        "pdf": lambda p: writers.write_pdf(a, p),
        "png": lambda p: writers.write_png(a, p, image=image, background="transparent", scale=0.5),
    }
    assert set(own) == set(writers.LEVEL_FORMATS)
    for fmt, write in own.items():
        got = writers.write(a, tmp_path / f"one.{fmt}", fmt, image=image, background="transparent", scale=0.5)
        assert got == tmp_path / f"one.{fmt}"
        assert got.read_bytes() == write(tmp_path / f"two.{fmt}").read_bytes(), fmt
    with pytest.raises(InvalidParameterError, match="format"):
        writers.write(a, tmp_path / "a.gif", "gif")
    assert not (tmp_path / "a.gif").exists()


@pytest.mark.parametrize("fmt", writers.LEVEL_FORMATS)
def test_encode_gives_the_bytes_write_writes(tmp_path, fmt):
    """``encode`` keeps in memory (the batch's workers) exactly the file ``write`` and each format's writer write."""
    a = make_abstraction()
    regions = palette_fills(a)
    image = np.zeros((HEIGHT, WIDTH, 3), dtype=np.uint8)
    data = writers.encode(a, fmt, fills=regions, image=image)
    assert data == writers.write(a, tmp_path / f"w.{fmt}", fmt, fills=regions, image=image).read_bytes()
    own = {
        "json": lambda p: writers.write_json(a, p, fills=regions),
        "svg": lambda p: writers.write_svg(a, p, fills=regions),
        "pdf": lambda p: writers.write_pdf(a, p, fills=regions),
        "png": lambda p: writers.write_png(a, p, fills=regions, image=image),
    }[fmt]
    assert data == own(tmp_path / f"own.{fmt}").read_bytes()
    assert writers.encode(a, fmt, fills=regions, image=image) == data  # deterministic
    if fmt == "png":  # the other backgrounds too
        for background in ("white", "transparent"):
            png = writers.encode(a, "png", background=background, scale=1.5)
            assert (
                png
                == writers.write_png(a, tmp_path / f"{background}.png", background=background, scale=1.5).read_bytes()
            )


def test_encode_and_write_refuse_what_they_cannot_make(tmp_path):
    a = make_abstraction()
    with pytest.raises(InvalidParameterError, match="format must be one of"):
        writers.encode(a, "gif")
    with pytest.raises(InvalidParameterError, match=r"\.svg names another format \(this writes PNG\)"):
        writers.write(a, tmp_path / "logo.svg", "png")
    with pytest.raises(InvalidParameterError, match='background "input" needs the input image'):
        writers.encode(a, "png", background="input")
    assert list(tmp_path.iterdir()) == []
