"""Tests of img2logo.writers: the img2logo.abstraction/1 document, SVG, PNG, atomic writes."""

from __future__ import annotations

import copy
import json
import math
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from conftest import small_graph

from img2logo import writers
from img2logo.constants import FORMAT_NAME, PHI
from img2logo.errors import InvalidParameterError
from img2logo.geometry import Abstraction, Arc, Circle

jsonschema = pytest.importorskip("jsonschema")

BIAS = 0.3
WIDTH, HEIGHT = 200, 160
SVG = "{http://www.w3.org/2000/svg}"
INKSCAPE = "{http://www.inkscape.org/namespaces/inkscape}"


def golden(cx: float, cy: float, k: int, bias: float = BIAS) -> Circle:
    return Circle(cx, cy, PHI ** (k + bias), k)


def intersection(a: Circle, b: Circle) -> np.ndarray:
    """The intersection of two circles with the smaller y (the upper one on screen)."""
    d = math.hypot(b.cx - a.cx, b.cy - a.cy)
    along = (a.r**2 - b.r**2 + d * d) / (2 * d)
    h = math.sqrt(a.r**2 - along**2)
    ux, uy = (b.cx - a.cx) / d, (b.cy - a.cy) / d
    p1 = np.array([a.cx + along * ux - h * uy, a.cy + along * uy + h * ux])
    p2 = np.array([a.cx + along * ux + h * uy, a.cy + along * uy - h * ux])
    return p1 if p1[1] < p2[1] else p2


def make_abstraction(**overrides) -> Abstraction:
    """Two golden circles (k = 8 and 7, bias 0.3) that intersect at P; arc 0 on the first ends at P
    with a positive sweep, arc 1 on the second starts at P with a negative sweep; arc 2 a full circle;
    arc 3 a 270 degree arc with a negative sweep; arc 4 a second arc on the first circle."""
    a, b = golden(60.0, 80.0, 8), golden(130.0, 80.0, 7)
    p = intersection(a, b)
    ta, tb = float(a.angle_of(p)), float(b.angle_of(p))
    arcs = (
        Arc(a, ta - 2.0, 2.0),
        Arc(b, tb, -1.5),
        Arc(golden(170.0, 30.0, 4), 0.0, 2.0 * math.pi),
        Arc(golden(40.0, 140.0, 5), 0.0, -1.5 * math.pi),
        Arc(a, math.pi / 2 + 0.3, 0.8),
    )
    fields = dict(
        level=2,
        arcs=arcs,
        arc_segments=((0, 1), (2,), (3,), (4, 5), (6,)),
        junctions=np.array([p]),
        junction_arcs=((0, 1),),
        similarity=0.5,
        bias=BIAS,
        tolerance=2.0,
        width=WIDTH,
        height=HEIGHT,
        params={"kind": "clipart", "rdp_tolerance": np.float32(1.5)},
    )
    fields.update(overrides)
    return Abstraction(**fields)


# --- the JSON document ----------------------------------------------------------------


def test_document_matches_schema_and_invariants():
    doc = writers.to_document(make_abstraction())
    writers.validate_document(doc)
    # Also after a trip through JSON text, and against the packaged schema directly.
    writers.validate_document(json.loads(json.dumps(doc)))
    jsonschema.validate(doc, writers._schema())


def test_document_contents():
    a = make_abstraction()
    doc = writers.to_document(a, {"tolerance_note": (1, 2), "kind": "drawing"})
    assert doc["format"] == FORMAT_NAME
    assert doc["phi"] == PHI
    assert (doc["width"], doc["height"], doc["level"]) == (WIDTH, HEIGHT, 2)
    assert doc["bias"] == BIAS and doc["similarity"] == 0.5 and doc["tolerance"] == 2.0
    # Arcs 0 and 4 share the first circle: 4 distinct circles, in order of first use.
    assert len(doc["circles"]) == 4
    assert [arc["circle"] for arc in doc["arcs"]] == [0, 1, 2, 3, 0]
    assert [c["k"] for c in doc["circles"]] == [8, 7, 4, 5]
    assert all(type(c["k"]) is int for c in doc["circles"])
    assert doc["junctions"] == [{"x": float(a.junctions[0, 0]), "y": float(a.junctions[0, 1]), "arcs": [0, 1]}]
    # Given params win over the abstraction's; numpy scalars become Python numbers.
    assert doc["params"] == {"kind": "drawing", "rdp_tolerance": 1.5, "tolerance_note": [1, 2]}
    assert type(doc["params"]["rdp_tolerance"]) is float
    assert doc["extra"] == {"arc_segments": [[0, 1], [2], [3], [4, 5], [6]]}
    assert "ladder" not in doc


def test_params_made_json_safe():
    params = {
        "array": np.array([[1, 2], [3, 4]], dtype=np.int32),
        "flag": np.bool_(True),
        "path": Path("/tmp/x.png"),
        "nested": {"inf": math.inf, "nan": float("nan"), "neg": -np.inf, "i": np.int64(3)},
    }
    doc = writers.to_document(make_abstraction(params=params))
    assert doc["params"] == {
        "array": [[1, 2], [3, 4]],
        "flag": True,
        "path": "/tmp/x.png",
        "nested": {"inf": "Infinity", "nan": "NaN", "neg": "-Infinity", "i": 3},
    }
    json.dumps(doc, allow_nan=False)
    with pytest.raises(InvalidParameterError, match=r"params\['obj'\] must be JSON-safe"):
        writers.to_document(make_abstraction(), {"obj": object()})
    with pytest.raises(InvalidParameterError, match="params keys must be strings"):
        writers.to_document(make_abstraction(), {1: 2})


def test_circle_without_k_cannot_be_written():
    c = Circle(50.0, 50.0, 10.0)
    with pytest.raises(InvalidParameterError, match=r"circle 0 \(centre \(50, 50\), r=10\) has no ladder exponent k"):
        make_abstraction(arcs=(Arc(c, 0.0, 1.0),), arc_segments=((0,),), junctions=np.zeros((0, 2)), junction_arcs=())


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("bias", 1.0, r"bias must be in \[0, 1\), got 1.0"),
        ("similarity", -1.0, "similarity must be >= 0"),
        ("tolerance", 0.0, "tolerance must be > 0"),
        ("level", -1, "level must be >= 0"),
        ("width", 0, "width must be >= 1"),
        ("similarity", math.nan, "similarity must be finite"),
    ],
)
def test_out_of_range_fields_rejected(field, value, message):
    with pytest.raises(InvalidParameterError, match=message):
        writers.to_document(make_abstraction(**{field: value}))


def test_junction_without_arcs_is_omitted():
    a = make_abstraction()
    b = make_abstraction(
        junctions=np.array([[5.0, 5.0], a.junctions[0]]),
        junction_arcs=((), (0, 1)),
    )
    doc = writers.to_document(b)
    assert len(doc["junctions"]) == 1
    assert doc["junctions"][0]["arcs"] == [0, 1]
    writers.validate_document(doc)


def test_arc_passing_through_a_junction_is_not_listed():
    a = make_abstraction()
    arc0 = a.arcs[0]
    inside = arc0.circle.point_at(arc0.theta0 + 0.5 * arc0.sweep)  # an interior point of arc 0
    # Junction 0 lists only arc 0, which passes through it: dropped, so the junction is omitted.
    b = make_abstraction(junctions=np.array([inside, a.junctions[0]]), junction_arcs=((0,), (0, 1)))
    doc = writers.to_document(b)
    assert [j["arcs"] for j in doc["junctions"]] == [[0, 1]]
    writers.validate_document(doc)
    # A valence >= 3 junction kept inside a merged arc: the arc ending there is listed, the merged one not.
    r6 = PHI ** (6 + BIAS)
    ends_here = Arc(Circle(inside[0] + r6, inside[1], r6, 6), math.pi, -1.0)  # starts at `inside`
    c = make_abstraction(
        arcs=(arc0, ends_here), arc_segments=((0,), (1,)), junctions=np.array([inside]), junction_arcs=((0, 1),)
    )
    doc = writers.to_document(c)
    assert [j["arcs"] for j in doc["junctions"]] == [[1]]
    writers.validate_document(doc)
    # A full circle ends (and starts) at theta0 only.
    full = a.arcs[2]
    d = make_abstraction(junctions=np.array([full.start, full.circle.point_at(2.0)]), junction_arcs=((2,), (2,)))
    doc = writers.to_document(d)
    assert [(j["x"], j["y"], j["arcs"]) for j in doc["junctions"]] == [(*map(float, full.start), [2])]
    writers.validate_document(doc)


def test_listed_arc_off_its_junction_is_reported():
    a = make_abstraction()
    # The abstraction refuses it when it is made: such a document is never written.
    with pytest.raises(InvalidParameterError, match=r"junction 0: .* px off the circle of arc 0"):
        make_abstraction(junctions=np.array([a.junctions[0] + [0.0, 0.5]]))
    with pytest.raises(InvalidParameterError, match=r"junction 0: arc index 7 is out of range"):
        make_abstraction(junction_arcs=((0, 7),))
    # A reader checks a document that was written elsewhere.
    doc = writers.to_document(a)
    doc["junctions"][0]["y"] += 0.5
    with pytest.raises(InvalidParameterError, match=r"junction 0: .* px off the circle 0 of arc 0"):
        writers.validate_document(doc)
    with pytest.raises(InvalidParameterError, match=r"junction 0: .* off the circle"):
        writers.from_document(doc)


def test_invariant_radius():
    doc = writers.to_document(make_abstraction())
    doc["circles"][1]["r"] = 12.0
    expected = PHI ** (7 + BIAS)
    with pytest.raises(InvalidParameterError, match=r"^circle 1: r=12.0 is not phi\*\*\(k\+bias\) = ") as info:
        writers.validate_document(doc)
    assert f"{expected:.10g}" in str(info.value)
    # Within the contract's 1e-6 relative tolerance is fine, beyond it is not.
    doc = writers.to_document(make_abstraction())
    doc["circles"][0]["r"] *= 1 + 5e-7
    writers.validate_document(doc)
    doc["circles"][0]["r"] *= 1 + 2e-6
    with pytest.raises(InvalidParameterError, match=r"^circle 0: "):
        writers.validate_document(doc)


def test_invariant_junction_on_circle():
    doc = writers.to_document(make_abstraction())
    doc["junctions"][0]["x"] += 0.01
    with pytest.raises(InvalidParameterError, match=r"^junction 0: \(.*\) is 0.0\d+ px off the circle 0 of arc 0"):
        writers.validate_document(doc)
    # Within 1e-3 px is still on the circle and at the end point.
    doc = writers.to_document(make_abstraction())
    doc["junctions"][0]["x"] += 4e-4
    writers.validate_document(doc)


def test_invariant_arc_end_at_junction():
    a = make_abstraction()
    doc = writers.to_document(a)
    # A junction on the circle of arc 4 (which shares circle 0) but not at its ends.
    doc["junctions"][0]["arcs"] = [0, 1, 4]
    with pytest.raises(InvalidParameterError, match=r"^junction 0: arc 4 has no end point at \(.*\): its nearest end"):
        writers.validate_document(doc)
    # An interior point of arc 0 listing arc 0.
    doc = writers.to_document(a)
    mid = a.arcs[0].circle.point_at(a.arcs[0].theta0 + 1.0)
    doc["junctions"].append({"x": float(mid[0]), "y": float(mid[1]), "arcs": [0]})
    with pytest.raises(InvalidParameterError, match=r"^junction 1: arc 0 has no end point"):
        writers.validate_document(doc)


@pytest.mark.parametrize(
    ("mutate", "message"),
    [
        (lambda d: d.__setitem__("format", "other/1"), "format must be"),
        (lambda d: d["arcs"][0].__setitem__("circle", 9), r"^arc 0: circle index 9 is out of range"),
        (lambda d: d["arcs"][0].__setitem__("sweep", 0.0), r"^arc 0: sweep must satisfy"),
        (lambda d: d["junctions"][0]["arcs"].append(11), r"^junction 0: arc index 11 is out of range"),
    ],
)
def test_invariants_indices_and_sweep(mutate, message):
    doc = writers.to_document(make_abstraction())
    mutate(doc)
    with pytest.raises(InvalidParameterError, match=message):
        writers._check_invariants(doc)


@pytest.mark.parametrize(
    ("mutate", "message"),
    [
        (lambda d: d.pop("level"), "at \\(top level\\): 'level' is a required property"),
        (lambda d: d["junctions"][0].__setitem__("arcs", []), "at junctions/0/arcs: .*"),
        (lambda d: d.__setitem__("bias", 1.0), "at bias: 1.0 is greater than or equal to the maximum of 1"),
        (lambda d: d["circles"][0].__setitem__("k", 1.5), "at circles/0/k: 1.5 is not of type 'integer'"),
        (lambda d: d["arcs"][0].__setitem__("sweep", 7.0), "at arcs/0/sweep: 7.0 is greater than the maximum"),
        (lambda d: d.__setitem__("format", "x"), "at format: 'img2logo.abstraction/1' was expected"),
    ],
)
def test_schema_violations(mutate, message):
    doc = writers.to_document(make_abstraction())
    mutate(doc)
    with pytest.raises(InvalidParameterError, match=f"^document does not match the {FORMAT_NAME} schema {message}"):
        writers.validate_document(doc)
    with pytest.raises(InvalidParameterError, match="does not match"):
        writers.from_document(doc)


def test_validate_rejects_non_mapping():
    with pytest.raises(InvalidParameterError, match="document must be a JSON object"):
        writers.validate_document([1, 2])
    with pytest.raises(InvalidParameterError, match="document must be a JSON object"):
        writers.from_document("{}")


def test_round_trip():
    a = make_abstraction()
    for doc in (writers.to_document(a), json.loads(json.dumps(writers.to_document(a)))):
        b = writers.from_document(doc)
        assert b.arcs == a.arcs
        assert b.circles == a.circles
        np.testing.assert_array_equal(b.junctions, a.junctions)
        assert b.junction_arcs == a.junction_arcs
        assert b.arc_segments == a.arc_segments
        assert (b.level, b.similarity, b.bias, b.tolerance, b.width, b.height) == (2, 0.5, BIAS, 2.0, WIDTH, HEIGHT)
        assert b.params == {"kind": "clipart", "rdp_tolerance": 1.5}
        assert writers.to_document(b) == writers.to_document(a)


def test_round_trip_without_arc_segments():
    doc = writers.to_document(make_abstraction())
    del doc["extra"]
    b = writers.from_document(doc)
    assert b.arc_segments == ((),) * 5
    doc["extra"] = {"arc_segments": [[1]]}
    with pytest.raises(InvalidParameterError, match=r"extra.arc_segments must have one entry per arc \(5\), got 1"):
        writers.from_document(doc)


def test_without_jsonschema(monkeypatch):
    monkeypatch.setitem(sys.modules, "jsonschema", None)  # import jsonschema -> ImportError
    doc = writers.to_document(make_abstraction())
    with pytest.raises(ImportError, match="needs the optional package jsonschema"):
        writers.validate_document(doc)
    # Reading still works, and still checks the invariants and the structure.
    assert writers.from_document(doc).arcs == make_abstraction().arcs
    bad = copy.deepcopy(doc)
    bad["circles"][0]["r"] = 1.0
    with pytest.raises(InvalidParameterError, match=r"^circle 0: r=1\.0"):
        writers.from_document(bad)
    bad = copy.deepcopy(doc)
    del bad["arcs"][0]["theta0"]
    with pytest.raises(InvalidParameterError, match=f"not a valid {FORMAT_NAME} document: KeyError"):
        writers.from_document(bad)


def test_fibonacci_ladder():
    from img2logo.golden_ladder import FibonacciLadder

    unit = 3.0
    c1, c2 = Circle(50.0, 50.0, unit * 5, 5), Circle(50.0, 50.0, unit * 8, 6)
    fields = dict(arc_segments=((0,), (1,)), junctions=np.zeros((0, 2)), junction_arcs=(), bias=0.0)
    a = make_abstraction(arcs=(Arc(c1, 0.0, 1.0), Arc(c2, 0.0, -1.0)), ladder=FibonacciLadder(unit), **fields)
    doc = writers.to_document(a)
    assert doc["ladder"] == "fibonacci" and doc["unit"] == unit
    writers.validate_document(doc)
    back = writers.from_document(doc)
    assert back.ladder == FibonacciLadder(unit) and writers.to_document(back) == doc
    doc["circles"][1]["k"] = 7
    with pytest.raises(InvalidParameterError, match=r"^circle 1: r=24.0 is not unit\*F\(k\) = 39 \(k=7, unit=3.0\)"):
        writers.validate_document(doc)
    # The ladder is the abstraction's: a Fibonacci radius is no phi radius.
    with pytest.raises(InvalidParameterError, match=r"^circle 0: r=15.0 is not phi\*\*\(k\+bias\)"):
        make_abstraction(arcs=(Arc(c1, 0.0, 1.0), Arc(c2, 0.0, -1.0)), **fields)


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
    writers.validate_document(doc)
    b = writers.read_json(p1)
    assert b.arcs == a.arcs
    (tmp_path / "bad.json").write_text("{not json")
    with pytest.raises(InvalidParameterError, match="is not JSON"):
        writers.read_json(tmp_path / "bad.json")


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


def svg_arc_center(x1, y1, r, large, sweep, x2, y2):
    """Centre and signed angular extent of an SVG arc command (SVG 1.1 implementation notes F.6.5)."""
    xp, yp = (x1 - x2) / 2, (y1 - y2) / 2
    num = max(0.0, r * r - xp * xp - yp * yp)
    coef = math.sqrt(num / (xp * xp + yp * yp)) * (1 if large != sweep else -1)
    cxp, cyp = coef * yp, -coef * xp
    cx, cy = cxp + (x1 + x2) / 2, cyp + (y1 + y2) / 2
    t1 = math.atan2(yp - cyp, xp - cxp)
    t2 = math.atan2(-yp - cyp, -xp - cxp)
    dt = t2 - t1
    if sweep == 0 and dt > 0:
        dt -= 2 * math.pi
    elif sweep == 1 and dt < 0:
        dt += 2 * math.pi
    return cx, cy, dt


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
    assert [p.get("data-circle") for p in paths] == ["0", "1", "2", "3", "0"]
    assert [p.get("data-k") for p in paths] == ["8", "7", "4", "5", "8"]
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
    circles = layer.findall(f"{SVG}circle")
    assert [c.get("id") for c in circles] == ["circle-0", "circle-1", "circle-2", "circle-3"]
    assert [c.get("data-k") for c in circles] == ["8", "7", "4", "5"]
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


def test_svg_writes_a_line_without_k():
    from img2logo.geometry import line_arc

    a = make_abstraction(
        arcs=(line_arc((10.0, 20.0), (90.0, 20.0)),), arc_segments=((0,),), junctions=np.zeros((0, 2)), junction_arcs=()
    )
    path = ET.fromstring(writers.to_svg(a)).find(f".//{SVG}path")
    assert path.get("data-k") is None and path.get("data-line") == "true"
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
    with pytest.raises(InvalidParameterError, match=r"image must be 160 x 200 px"):
        writers.write_png(a, tmp_path / "x.png", image=np.zeros((10, 10)))
    assert not (tmp_path / "x.png").exists()
    with pytest.raises(InvalidParameterError, match="dpi must be > 0"):
        writers.write_png(a, tmp_path / "x.png", dpi=0)


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


# --- atomic writes ----------------------------------------------------------------------


def leftovers(directory: Path) -> list[str]:
    return sorted(p.name for p in directory.iterdir())


def test_parent_directories_created(tmp_path):
    a = make_abstraction()
    for name, write in (("a.json", writers.write_json), ("a.svg", writers.write_svg), ("a.png", writers.write_png)):
        target = tmp_path / "deep" / "er" / name
        assert write(a, str(target)) == target
        assert target.is_file()
    assert leftovers(tmp_path / "deep" / "er") == ["a.json", "a.png", "a.svg"]


def test_written_file_has_usual_permissions(tmp_path):
    umask = os.umask(0o022)
    try:
        p = writers.write_json(make_abstraction(), tmp_path / "a.json")
    finally:
        os.umask(umask)
    assert p.stat().st_mode & 0o777 == 0o644


def test_failed_replace_leaves_nothing(tmp_path, monkeypatch):
    def fail(*args, **kwargs):
        raise OSError("disk full")

    monkeypatch.setattr(writers.os, "replace", fail)
    with pytest.raises(OSError, match="disk full"):
        writers.write_json(make_abstraction(), tmp_path / "out" / "a.json")
    assert leftovers(tmp_path / "out") == []


def test_failure_midway_keeps_the_old_file(tmp_path, monkeypatch):
    from matplotlib.figure import Figure

    target = tmp_path / "a.png"
    target.write_bytes(b"old")

    def half_then_fail(self, f, **kwargs):
        f.write(b"\x89PNG half")
        raise RuntimeError("renderer crashed")

    monkeypatch.setattr(Figure, "savefig", half_then_fail)
    with pytest.raises(RuntimeError, match="renderer crashed"):
        writers.write_png(make_abstraction(), target)
    assert target.read_bytes() == b"old"
    assert leftovers(tmp_path) == ["a.png"]
    with pytest.raises(RuntimeError, match="renderer crashed"):
        writers.write_png(make_abstraction(), tmp_path / "new.png")
    assert leftovers(tmp_path) == ["a.png"]


def test_atomic_write_helper(tmp_path):
    def boom(f):
        f.write(b"partial")
        raise ValueError("boom")

    with pytest.raises(ValueError, match="boom"):
        writers._atomic_write(tmp_path / "x.bin", boom)
    assert leftovers(tmp_path) == []
    writers._atomic_write(tmp_path / "x.bin", lambda f: f.write(b"whole"))
    assert (tmp_path / "x.bin").read_bytes() == b"whole"
    assert leftovers(tmp_path) == ["x.bin"]


@pytest.mark.parametrize("bad", [None, 3, "", b"bytes.json"])
def test_bad_path_rejected(bad):
    with pytest.raises(InvalidParameterError, match="path must be a non-empty str or path-like"):
        writers.write_json(make_abstraction(), bad)


def test_invalid_document_is_not_written(tmp_path):
    with pytest.raises(InvalidParameterError, match="must be JSON-safe"):
        writers.write_json(make_abstraction(), tmp_path / "a.json", params={"obj": object()})
    assert leftovers(tmp_path) == []


def test_import_does_not_load_matplotlib_or_jsonschema():
    code = (
        "import sys, img2logo.writers, img2logo.plotting; "
        "print(sorted({'matplotlib', 'jsonschema'} & set(sys.modules)))"
    )
    root = Path(__file__).resolve().parents[1]
    out = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


def test_schema_is_read_from_the_package():
    schema = writers._schema()
    assert schema["$id"] == FORMAT_NAME
    assert not re.search(r"shared", writers.__file__)


# --- arcs that do not meet (--no-connectivity) -------------------------------------------


def _unconnected(connectivity: bool) -> Abstraction:
    """make_abstraction with arc 1 turned by 0.05 rad: its start is ~0.4 px off the junction P."""
    a = make_abstraction()
    arcs = list(a.arcs)
    arcs[1] = Arc(arcs[1].circle, arcs[1].theta0 - 0.05, arcs[1].sweep)
    return make_abstraction(arcs=tuple(arcs), params={"connectivity": connectivity}, connected=connectivity)


def test_unconnected_arc_ends_are_their_own_junctions():
    doc = writers.to_document(_unconnected(False))
    writers.validate_document(doc)
    p = make_abstraction().junctions[0]
    start = _unconnected(False).arcs[1].start
    assert doc["junctions"] == [
        {"x": float(p[0]), "y": float(p[1]), "arcs": [0]},
        {"x": pytest.approx(start[0], abs=1e-9), "y": pytest.approx(start[1], abs=1e-9), "arcs": [1]},
    ]
    # With the connectivity constraint on, an arc end off its junction is a bug: never made.
    with pytest.raises(InvalidParameterError, match=r"junction 0.* arc 1"):
        _unconnected(True)


def test_no_connectivity_result_is_a_valid_document(tmp_path):
    from conftest import DATA

    from img2logo import abstract

    result = abstract(DATA / "clipart-fish.png", connectivity=False, progress=False)
    for level in (result.levels[0], result.final):
        writers.validate_document(json.loads(writers.write_json(level, tmp_path / "fish.json").read_text()))


# --- output errors, output sets, stale temporary files ----------------------------------


def test_writer_errors_name_the_path(tmp_path):
    from img2logo.errors import OutputError

    (tmp_path / "file").write_text("x")
    with pytest.raises(OutputError, match=r"cannot write .*folder: is a directory"):
        (tmp_path / "folder").mkdir()
        writers.write_json(make_abstraction(), tmp_path / "folder")
    with pytest.raises(OutputError, match=r"cannot write .*file/a\.svg: Not a directory"):
        writers.write_svg(make_abstraction(), tmp_path / "file" / "a.svg")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["file", "folder"]


def test_output_set_writes_all_or_nothing(tmp_path):
    a = make_abstraction()
    with pytest.raises(KeyboardInterrupt), writers.output_set():
        writers.write_json(a, tmp_path / "new" / "deep" / "a.json")
        writers.write_svg(a, tmp_path / "new" / "a.svg")
        assert not (tmp_path / "new" / "a.svg").exists()  # not before the set ends
        raise KeyboardInterrupt
    assert list(tmp_path.iterdir()) == []  # no file, no temporary file, no folder it created
    with writers.output_set():
        writers.write_json(a, tmp_path / "a.json")
        writers.write_svg(a, tmp_path / "a.svg")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.json", "a.svg"]


def _dead_pid() -> int:
    child = subprocess.Popen([sys.executable, "-c", "pass"])
    child.wait()  # reaped: its process id is free
    return child.pid


def test_stale_temporary_files_of_a_target_are_removed(tmp_path):
    dead, alive = _dead_pid(), os.getpid()
    stale = tmp_path / f".a.json.{dead}-0123abcd.tmp"
    running = tmp_path / f".a.json.{alive}-0123abcd.tmp"  # this process: still writing it
    other = tmp_path / f".b.json.{dead}-0123abcd.tmp"  # another target's
    for p in (stale, running, other):
        p.write_text("partial")
    writers.write_json(make_abstraction(), tmp_path / "a.json")
    assert not stale.exists() and running.exists() and other.exists()


def test_check_output_paths(tmp_path):
    src = tmp_path / "in.png"
    src.write_bytes(b"image")
    (tmp_path / "link.png").symlink_to(src)
    os.link(src, tmp_path / "hard.png")
    (tmp_path / "file").write_text("x")
    (tmp_path / "dir").mkdir()
    check = writers.check_output_paths
    ok = check({"--svg": tmp_path / "new" / "a.svg", "--json": tmp_path / "a.json"}, [src])
    assert ok == {"--svg": tmp_path / "new" / "a.svg", "--json": tmp_path / "a.json"}
    assert not (tmp_path / "new").exists()  # nothing created by a check
    cases = [
        ({"--png": src}, "is the input"),
        ({"--png": tmp_path / "link.png"}, "link.png is the input .*in.png: refusing to write over an input"),
        ({"--png": tmp_path / "hard.png"}, "hard.png is the input"),
        ({"--svg": tmp_path / "o.out", "--json": tmp_path / "./o.out"}, "--svg and --json name the same file"),
        ({"--svg": tmp_path / "dir"}, "--svg .*dir is a folder"),
        ({"--svg": "/dev/null"}, "--svg /dev/null is not a regular file"),
        ({"--svg": tmp_path / "file" / "sub" / "a.svg"}, r"--svg .*a\.svg: .*file is not a folder"),
    ]
    for targets, message in cases:
        with pytest.raises(InvalidParameterError, match=message):
            check(targets, [src])
    with pytest.raises(InvalidParameterError, match=r"--levels-dir .*file is a file, not a folder"):
        check({}, [src], {"--levels-dir": tmp_path / "file"})
