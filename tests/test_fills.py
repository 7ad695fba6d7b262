"""Tests of img2logo.fills: faces of the arrangement of arcs and their colour fills (paper Fig. 18)."""

from __future__ import annotations

import io
import json
import math
import re
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from conftest import two_discs
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from img2logo import fills, writers
from img2logo.constants import PHI
from img2logo.errors import InvalidParameterError
from img2logo.fills import Face, Fill, FillSpec, Gradient
from img2logo.geometry import TAU, Abstraction, Arc, Circle

BIAS = 0.3
SVG = "{http://www.w3.org/2000/svg}"
INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"


def golden(cx: float, cy: float, k: int) -> Circle:
    return Circle(cx, cy, PHI ** (k + BIAS), k)


def make(arcs, junctions=(), junction_arcs=(), width=250, height=200) -> Abstraction:
    return Abstraction(
        level=0,
        arcs=tuple(arcs),
        arc_segments=tuple(() for _ in arcs),
        junctions=np.array(junctions, dtype=float).reshape(-1, 2),
        junction_arcs=tuple(junction_arcs),
        similarity=0.0,
        bias=BIAS,
        tolerance=5.0,
        width=width,
        height=height,
    )


def full(c: Circle, theta0: float = 0.0, sign: float = 1.0) -> Arc:
    return Arc(c, theta0, sign * TAU)


def crossings(a: Circle, b: Circle) -> np.ndarray:
    d = math.hypot(b.cx - a.cx, b.cy - a.cy)
    along = (a.r**2 - b.r**2 + d * d) / (2 * d)
    h = math.sqrt(a.r**2 - along**2)
    ux, uy = (b.cx - a.cx) / d, (b.cy - a.cy) / d
    base = np.array([a.cx + along * ux, a.cy + along * uy])
    return np.array([base + h * np.array([-uy, ux]), base - h * np.array([-uy, ux])])


def lens_area(r1: float, r2: float, d: float) -> float:
    """Area of the intersection of two discs (radii r1, r2, centres d apart)."""
    a1 = r1 * r1 * math.acos((d * d + r1 * r1 - r2 * r2) / (2 * d * r1))
    a2 = r2 * r2 * math.acos((d * d + r2 * r2 - r1 * r1) / (2 * d * r2))
    return a1 + a2 - 0.5 * math.sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2))


A, B = golden(90.0, 100.0, 8), golden(150.0, 100.0, 7)  # r = 54.27 and 33.54, d = 60: they cross


def two_circles() -> Abstraction:
    return make([full(A), full(B, 1.0, -1.0)])


def four_arcs() -> Abstraction:
    """The same two circles as four arcs that end exactly on the two junctions where they cross."""
    p, q = crossings(A, B)
    arcs = []
    for c in (A, B):
        tp, tq = float(c.angle_of(p)), float(c.angle_of(q))
        s = (tq - tp) % TAU
        arcs += [Arc(c, tp, s), Arc(c, tq, TAU - s)]
    return make(arcs, [p, q], [(0, 1, 2, 3), (0, 1, 2, 3)])


def parse_path(d: str) -> list[tuple[tuple[float, float], list[tuple[float, int, int, float, float]]]]:
    """Subpaths of fill path data: (start point, arc commands (r, large, sweep, x, y)); each ends with Z."""
    tokens = d.split()
    out = []
    i = 0
    while i < len(tokens):
        assert tokens[i] == "M"
        start = (float(tokens[i + 1]), float(tokens[i + 2]))
        i += 3
        cmds = []
        while tokens[i] == "A":
            rx, ry, rot, large, sweep, x, y = tokens[i + 1 : i + 8]
            assert rx == ry and rot == "0"
            cmds.append((float(rx), int(large), int(sweep), float(x), float(y)))
            i += 8
        assert tokens[i] == "Z"
        i += 1
        out.append((start, cmds))
    return out


def svg_arc_center(x1, y1, r, large, sweep, x2, y2):
    """Centre and signed extent of an SVG arc command (SVG 1.1 F.6.5), independent of the library."""
    xp, yp = (x1 - x2) / 2, (y1 - y2) / 2
    num = max(0.0, r * r - xp * xp - yp * yp)
    coef = math.sqrt(num / (xp * xp + yp * yp)) * (1 if large != sweep else -1)
    cxp, cyp = coef * yp, -coef * xp
    cx, cy = cxp + (x1 + x2) / 2, cyp + (y1 + y2) / 2
    dt = math.atan2(-yp - cyp, -xp - cxp) - math.atan2(yp - cyp, xp - cxp)
    if sweep == 0 and dt > 0:
        dt -= TAU
    elif sweep == 1 and dt < 0:
        dt += TAU
    return cx, cy, dt


def path_area(d: str) -> float:
    """Area enclosed by fill path data under the even-odd rule, from the arc commands alone.

    Each loop's signed area by Green's theorem on its arcs (centres found as a renderer
    does); holes (loops inside the first) are subtracted by taking absolute values.
    """
    total = []
    for start, cmds in parse_path(d):
        x, y = start
        s = 0.0
        for r, large, sweep, x2, y2 in cmds:
            cx, cy, dt = svg_arc_center(x, y, r, large, sweep, x2, y2)
            t0 = math.atan2(y - cy, x - cx)
            t1 = t0 + dt
            s += 0.5 * (r * cx * (math.sin(t1) - math.sin(t0)) - r * cy * (math.cos(t1) - math.cos(t0)) + r * r * dt)
            x, y = x2, y2
        total.append(abs(s))
    return total[0] - sum(total[1:])


# --- faces: known answers ---------------------------------------------------------------


@pytest.mark.parametrize("build", [two_circles, four_arcs], ids=["two full circles", "four arcs on junctions"])
def test_two_crossing_circles_give_lens_and_two_crescents(build):
    a = build()
    found = fills.faces(a)
    assert len(found) == 3
    lens = lens_area(A.r, B.r, 60.0)
    expected = sorted([lens, math.pi * A.r**2 - lens, math.pi * B.r**2 - lens], reverse=True)
    assert [f.area for f in found] == pytest.approx(expected, rel=1e-12)
    for f in found:
        assert f.holes == ()
        assert f.polygon.is_valid
        assert f.polygon.area == pytest.approx(f.area, rel=2e-4)  # sampled every 0.5 px
        assert path_area(f.path) == pytest.approx(f.area, rel=1e-6)  # the written arcs bound the same area
    # The lens, one arc of each circle: two arc commands once the pieces of one circle are joined.
    ((_, lens_cmds),) = parse_path(found[2].path)
    assert len(lens_cmds) == 2
    assert found[0].polygon.intersection(found[2].polygon).area < 1.0  # faces do not overlap


def test_face_pieces_are_exact_pieces_of_the_arcs_and_end_on_junctions():
    a = four_arcs()
    junctions = a.junctions
    for face in fills.faces(a):
        loop = face.boundary
        for piece, nxt in zip(loop, loop[1:] + loop[:1], strict=True):
            assert piece.end == nxt.start  # the loop is closed, piece to piece
            arc = a.arcs[piece.arc]
            assert piece.circle == arc.circle
            for t, point in ((piece.t0, piece.start), (piece.t1, piece.end)):
                np.testing.assert_allclose(arc.circle.point_at(t), point, atol=1e-9)
                assert bool(arc.contains_angle(t, tol=1e-9))
            # Every vertex here is a junction, exactly.
            assert min(np.hypot(*(junctions - np.array(piece.start)).T)) == 0.0
        for start, cmds in parse_path(face.path):
            for x, y in [start] + [(c[3], c[4]) for c in cmds]:
                assert min(np.hypot(junctions[:, 0] - x, junctions[:, 1] - y)) <= 1e-6


def test_single_full_circle_is_one_face_with_two_half_arcs():
    c = golden(120.0, 90.0, 9)
    a = make([Arc(c, 0.4, TAU)])
    (face,) = fills.faces(a)
    assert face.area == pytest.approx(math.pi * c.r**2, rel=1e-12)
    ((start, cmds),) = parse_path(face.path)
    assert len(cmds) == 2 and face.path.count("A ") == 2 and face.path.endswith("Z")
    assert [(cmd[1], cmd[2]) for cmd in cmds] == [(0, 1), (0, 1)]  # two half turns, clockwise on screen
    assert (cmds[-1][3], cmds[-1][4]) == start
    np.testing.assert_allclose(start, c.point_at(0.4), atol=1e-6)
    x, y = start
    for r, large, sweep, x2, y2 in cmds:
        assert r == pytest.approx(c.r, abs=1e-6)
        cx, cy, dt = svg_arc_center(x, y, r, large, sweep, x2, y2)
        # A half turn's centre is ill-conditioned (end points written to 1e-6 px): within 0.02 px.
        assert (cx, cy, dt) == pytest.approx((c.cx, c.cy, math.pi), abs=0.02)
        x, y = x2, y2


def test_annulus_face_has_a_hole_and_the_inner_disc_is_a_face():
    outer, inner = golden(120.0, 100.0, 9), golden(120.0, 100.0, 6)  # r = 78.2 and 18.5, concentric
    a = make([full(outer), full(inner, 2.0, -1.0)])
    ring, disc = fills.faces(a)
    assert ring.area == pytest.approx(math.pi * (outer.r**2 - inner.r**2), rel=1e-12)
    assert disc.area == pytest.approx(math.pi * inner.r**2, rel=1e-12)
    assert len(ring.holes) == 1 and disc.holes == ()
    assert len(ring.polygon.interiors) == 1
    assert ring.path.count("M ") == 2  # outer loop and hole: two subpaths, filled even-odd
    assert path_area(ring.path) == pytest.approx(ring.area, rel=1e-5)  # half turns: see above
    assert not ring.polygon.contains(disc.polygon.representative_point())


def test_tangent_circles_inside_each_other():
    """A small circle touching a big one from inside at one point (tangent arcs at a vertex)."""
    big = golden(120.0, 100.0, 9)
    small = Circle(big.cx + big.r - PHI ** (6 + BIAS), big.cy, PHI ** (6 + BIAS), 6)
    a = make([full(big, 0.0), full(small, 0.0, -1.0)], [[big.cx + big.r, big.cy]], [(0, 1)])
    found = fills.faces(a)
    assert [f.area for f in found] == pytest.approx([math.pi * (big.r**2 - small.r**2), math.pi * small.r**2])
    assert found[0].polygon.is_valid  # the pinched crescent is repaired for shapely


def test_dangling_and_bridging_arcs_bound_nothing():
    c, d = golden(100.0, 100.0, 8), golden(200.0, 100.0, 5)
    p, q = c.point_at(0.0), d.point_at(math.pi)  # c's rightmost and d's leftmost points
    half = 0.5 * (q[0] - p[0])
    k = math.ceil(math.log(half) / math.log(PHI) - BIAS)
    r = PHI ** (k + BIAS)
    o = Circle(0.5 * (p[0] + q[0]), 100.0 + math.sqrt(r * r - half * half), r, k)  # a golden circle through p, q
    t0, t1 = float(o.angle_of(p)), float(o.angle_of(q))
    bridge = Arc(o, t0, float(np.mod(t1 - t0, TAU)))  # p to q, over the top
    bottom = c.point_at(math.pi / 2)
    t = golden(bottom[0], bottom[1] + PHI ** (5 + BIAS), 5)
    tail = Arc(t, -math.pi / 2, 1.0)  # starts on c (tangent to it) and hangs outside
    a = make([full(c), bridge, full(d, math.pi), tail], [p, q, bottom], [(0, 1), (1, 2), (3,)], width=260)
    found = fills.faces(a)
    assert [f.area for f in found] == pytest.approx([math.pi * c.r**2, math.pi * d.r**2], rel=1e-12)
    assert all(f.holes == () for f in found)


def test_overlapping_arcs_of_one_circle_count_once():
    c = golden(120.0, 100.0, 8)
    a = make([Arc(c, 0.0, 4.0), Arc(c, 3.0, 3.5), Arc(c, 6.0, -1.0)])  # together they close the circle
    (face,) = fills.faces(a)
    assert face.area == pytest.approx(math.pi * c.r**2, rel=1e-12)
    assert len(parse_path(face.path)[0][1]) == 2  # joined into one turn, written as two halves


def test_no_closed_region_gives_no_face():
    c = golden(100.0, 100.0, 8)
    assert fills.faces(make([Arc(c, 0.0, 3.0)])) == ()
    assert fills.faces(make([])) == ()


def test_faces_validation():
    with pytest.raises(InvalidParameterError, match="abstraction must be an Abstraction, got str"):
        fills.faces("logo")
    with pytest.raises(InvalidParameterError, match=r"snap must be > 0, got 0.0"):
        fills.faces(two_circles(), snap=0)


def test_face_adjacency_of_the_two_circles():
    found = fills.faces(two_circles())
    adjacent = fills.face_adjacency(found)
    # The crescents (0, 1) only touch at the two crossing points; the lens (2) borders both.
    assert adjacent == [{2}, {2}, {0, 1}]


@settings(max_examples=25, deadline=None, derandomize=True, suppress_health_check=[HealthCheck.too_slow])
@given(
    circles=st.lists(
        st.tuples(st.floats(60.0, 140.0), st.floats(60.0, 140.0), st.integers(5, 8)), min_size=1, max_size=4
    )
)
def test_faces_of_full_circles_tile_the_union_of_their_discs(circles):
    import shapely
    from shapely.geometry import Point

    cs = [golden(x, y, k) for x, y, k in circles]
    found = fills.faces(make([full(c, 0.1 * i) for i, c in enumerate(cs)]), min_area=0.0)
    union = shapely.unary_union([Point(c.cx, c.cy).buffer(c.r, quad_segs=256) for c in cs])
    assert sum(f.area for f in found) == pytest.approx(union.area, rel=1e-3)
    for f in found:
        assert f.area > 0.0
        assert f.polygon.area == pytest.approx(f.area, rel=2e-3, abs=0.5)


# --- palettes, gradients ----------------------------------------------------------------


def test_palette_deals_colours_by_area_and_keeps_neighbours_apart():
    a = two_circles()
    found = fills.faces(a)
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
    found = fills.faces(a)
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


@pytest.fixture(scope="module")
def discs_result():
    import img2logo

    return img2logo.abstract(two_discs())


def test_auto_colours_of_two_disc_clip_art(discs_result):
    a = discs_result.final
    found = fills.faces(a)
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
    a = make([full(c_red), full(c_white), full(c_edge)], width=size, height=size)
    auto = fills.fill_auto(a, image)
    # The white disc is enclosed (a penguin's belly): it keeps its white; the circle
    # crossing the border reaches outside and stays empty.
    assert sorted(f.color for f in auto) == ["#c81e3c", "#ffffff"]
    assert auto[0].face == 0 and fills.faces(a)[0].area == pytest.approx(math.pi * c_red.r**2)
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
    a = make([full(c_body), full(c_belly), full(c_hole)], width=size, height=size)
    colours = sorted(f.color for f in fills.fill_auto(a, rgba))
    assert colours == ["#141414", "#ffffff"]  # body and belly; the hole shows the page


def test_auto_validation():
    a = two_circles()
    with pytest.raises(InvalidParameterError, match=r"image must be 200 x 250 px"):
        fills.fill_auto(a, np.zeros((10, 10, 3)))
    with pytest.raises(InvalidParameterError, match=r"inset must be >= 0, got -1\.0"):
        fills.fill_auto(a, np.zeros((200, 250, 3)), inset=-1)


# --- the command line option ---------------------------------------------------------------


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


# --- reading paths back --------------------------------------------------------------------


def test_sample_path_follows_the_arcs():
    a = make([full(A), full(B, 1.0, -1.0)])
    for face in fills.faces(a):
        rings = fills.sample_path(face.path, step=0.25)
        assert len(rings) == 1
        for ring in rings:  # every sample lies on one of the two circles
            off = np.minimum(np.abs(A.distance(ring)), np.abs(B.distance(ring)))
            assert off.max() < 1e-6
    with pytest.raises(InvalidParameterError, match=r"unsupported command 'C'"):
        fills.sample_path("M 0 0 C 1 1 2 2 3 3 Z")
    with pytest.raises(InvalidParameterError, match=r"relative commands are not supported"):
        fills.sample_path("M 0 0 a 1 1 0 0 1 2 0 Z")
    with pytest.raises(InvalidParameterError, match=r"only circular arcs \(rx == ry\), got rx=1, ry=2"):
        fills.sample_path("M 0 0 A 1 2 0 0 1 2 0 Z")
    with pytest.raises(InvalidParameterError, match=r"command 'A' needs 7 numbers"):
        fills.sample_path("M 0 0 A 1 1 0 0 1 Z")


# --- writers: JSON, SVG, PNG --------------------------------------------------------------


def palette_fills(a: Abstraction) -> tuple[Fill, ...]:
    return fills.fill_palette(a, ["#e63946", "#457b9d", "#f4a261"])


def test_json_with_fills_validates_and_reads_back(tmp_path):
    pytest.importorskip("jsonschema")
    a = four_arcs()
    fs = palette_fills(a)
    doc = writers.to_document(a, fills=fs)
    writers.validate_document(doc)
    assert doc["fills"] == [{"path": f.path, "color": f.color} for f in fs]
    assert "fills" not in writers.to_document(a)
    assert writers.to_document(a, fills=())["fills"] == []
    path = writers.write_json(a, tmp_path / "logo.json", fills=fs)
    writers.validate_document(json.loads(path.read_text()))
    back = writers.read_fills(path)
    assert [(f.path, f.color) for f in back] == [(f.path, f.color) for f in fs]
    assert writers.read_fills(doc) == back and all(f.face is None for f in back)
    writers.read_json(path)  # the abstraction itself still reads
    # A gradient's JSON colour is its colour at the face's centroid.
    grad = fills.fill_gradient(a, ["#000000", "#ffffff"])
    assert [e["color"] for e in writers.to_document(a, fills=grad)["fills"]] == [f.color for f in grad]


def test_json_fills_validation():
    a = four_arcs()
    with pytest.raises(InvalidParameterError, match=r"fills\[0\] must be a Fill, got dict"):
        writers.to_document(a, fills=[{"path": "M 0 0 Z", "color": "#ffffff"}])
    with pytest.raises(InvalidParameterError, match="fills must be a sequence of Fill, got Fill"):
        writers.to_document(a, fills=palette_fills(a)[0])
    with pytest.raises(InvalidParameterError, match=r"fills\[0\]: fill color 'blue' is not of the form #rrggbb"):
        writers.read_fills({"fills": [{"path": "M 0 0 A 1 1 0 0 1 2 0 Z", "color": "blue"}]})
    with pytest.raises(InvalidParameterError, match=r"fills\[0\] must be an object with 'path' and 'color'"):
        writers.read_fills({"fills": [{"path": "M 0 0 Z"}]})
    assert writers.read_fills({"format": "x"}) == ()


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


def test_svg_gradient_defs(tmp_path):
    a = four_arcs()
    fs = fills.fill_gradient(a, ["#ff0000", "#ffff00", "#0000ff"], kind="radial")
    root = ET.fromstring(writers.to_svg(a, fills=fs))
    (grad,) = root.findall(f"{SVG}defs/{SVG}radialGradient")
    assert grad.get("id") == "fill-gradient-0" and grad.get("gradientUnits") == "userSpaceOnUse"
    assert [s.get("stop-color") for s in grad.findall(f"{SVG}stop")] == ["#ff0000", "#ffff00", "#0000ff"]
    assert {p.get("fill") for p in root.findall(f"{SVG}g[@id='fills']/{SVG}path")} == {"url(#fill-gradient-0)"}


def read_png(data: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(data)).convert("RGB"), dtype=np.float64) / 255.0


def test_png_shows_fills_with_holes(tmp_path):
    outer, inner = golden(120.0, 100.0, 9), golden(120.0, 100.0, 6)
    a = make([full(outer), full(inner, 2.0, -1.0)])
    ring = fills.fill_palette(a, {0: "#0000ff"})  # the annulus only: its hole stays white
    png = read_png(writers.write_png(a, tmp_path / "ring.png", fills=ring).read_bytes())
    assert png.shape == (200, 250, 3)
    np.testing.assert_allclose(png[100, 120], [1, 1, 1])  # centre: in the hole
    np.testing.assert_allclose(png[100, 120 + 45], [0, 0, 1])  # between the circles
    np.testing.assert_allclose(png[5, 5], [1, 1, 1])  # outside
    # Gradients are drawn as gradients: top and bottom of the disc differ.
    grad = fills.fill_gradient(a, ["#ff0000", "#0000ff"])
    png = read_png(writers.write_png(a, tmp_path / "grad.png", fills=grad).read_bytes())
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
        a = make([full(outer), full(inner, 2.0, -1.0), full(golden(60.0, 60.0, 6))])
        fs = palette_fills(a) if which == "palette" else fills.fill_gradient(a, ["#ff0000", "#00ffaa", "#0000ff"])
    svg = writers.write_svg(a, tmp_path / "logo.svg", fills=fs).read_text()
    rendered = read_png(bytes(resvg_py.svg_to_bytes(svg_string=svg, background="#ffffff")))
    drawn = read_png(writers.write_png(a, tmp_path / "logo.png", fills=fs).read_bytes())
    assert rendered.shape == drawn.shape == (a.height, a.width, 3)
    difference = np.abs(rendered - drawn)
    assert difference.mean() < 0.01
    assert np.mean(difference.max(axis=2) > 0.25) < 0.01  # differences only along anti-aliased edges


def test_auto_fills_of_the_clip_art_sit_inside_the_arcs(data_dir):
    """Fills are drawn where the input has their colour: no leak across the arcs (clip art fish)."""
    import img2logo

    result = img2logo.abstract(data_dir / "clipart-fish.png")
    a = result.final
    found = fills.faces(a)
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
