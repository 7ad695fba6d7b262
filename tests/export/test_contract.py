"""Tests of img2logo.export.contract: the img2logo.abstraction/1 document, its schema and invariants."""

from __future__ import annotations

import copy
import json
import math
import re
from pathlib import Path

import numpy as np
import pytest
from helpers import BIAS, HEIGHT, WIDTH, four_arcs, make_abstraction, modules_loaded, palette_fills

from img2logo.constants import FORMAT_NAME, PHI
from img2logo.design import fills
from img2logo.errors import InvalidParameterError
from img2logo.export import contract, writers
from img2logo.geometry.abstraction import Abstraction
from img2logo.geometry.primitives import Arc, Circle

jsonschema = pytest.importorskip("jsonschema")


def test_document_matches_schema_and_invariants():
    doc = contract.to_document(make_abstraction())
    contract.validate_document(doc)
    # Also after a trip through JSON text, and against the packaged schema directly.
    contract.validate_document(json.loads(json.dumps(doc)))
    jsonschema.validate(doc, _packaged_schema())


def test_document_contents():
    a = make_abstraction()
    doc = contract.to_document(a, {"tolerance_note": (1, 2), "kind": "drawing"})
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
    doc = contract.to_document(make_abstraction(params=params))
    assert doc["params"] == {
        "array": [[1, 2], [3, 4]],
        "flag": True,
        "path": "/tmp/x.png",
        "nested": {"inf": "Infinity", "nan": "NaN", "neg": "-Infinity", "i": 3},
    }
    json.dumps(doc, allow_nan=False)
    with pytest.raises(InvalidParameterError, match=r"params\['obj'\] must be JSON-safe"):
        contract.to_document(make_abstraction(), {"obj": object()})
    with pytest.raises(InvalidParameterError, match="params keys must be strings"):
        contract.to_document(make_abstraction(), {1: 2})


def test_junction_without_arcs_is_omitted():
    a = make_abstraction()
    b = make_abstraction(
        junctions=np.array([[5.0, 5.0], a.junctions[0]]),
        junction_arcs=((), (0, 1)),
    )
    doc = contract.to_document(b)
    assert len(doc["junctions"]) == 1
    assert doc["junctions"][0]["arcs"] == [0, 1]
    contract.validate_document(doc)


def test_arc_passing_through_a_junction_is_not_listed():
    a = make_abstraction()
    arc0 = a.arcs[0]
    inside = arc0.circle.point_at(arc0.theta0 + 0.5 * arc0.sweep)  # an interior point of arc 0
    # Junction 0 lists only arc 0, which passes through it: dropped, so the junction is omitted.
    b = make_abstraction(junctions=np.array([inside, a.junctions[0]]), junction_arcs=((0,), (0, 1)))
    doc = contract.to_document(b)
    assert [j["arcs"] for j in doc["junctions"]] == [[0, 1]]
    contract.validate_document(doc)
    # A valence >= 3 junction kept inside a merged arc: the arc ending there is listed, the merged one not.
    r6 = PHI ** (6 + BIAS)
    ends_here = Arc(Circle(inside[0] + r6, inside[1], r6, 6), math.pi, -1.0)  # starts at `inside`
    c = make_abstraction(
        arcs=(arc0, ends_here), arc_segments=((0,), (1,)), junctions=np.array([inside]), junction_arcs=((0, 1),)
    )
    doc = contract.to_document(c)
    assert [j["arcs"] for j in doc["junctions"]] == [[1]]
    contract.validate_document(doc)
    # A full circle ends (and starts) at theta0 only.
    full = a.arcs[2]
    d = make_abstraction(junctions=np.array([full.start, full.circle.point_at(2.0)]), junction_arcs=((2,), (2,)))
    doc = contract.to_document(d)
    assert [(j["x"], j["y"], j["arcs"]) for j in doc["junctions"]] == [(*map(float, full.start), [2])]
    contract.validate_document(doc)


def test_listed_arc_off_its_junction_is_reported():
    a = make_abstraction()
    # The abstraction refuses it when it is made: such a document is never written.
    with pytest.raises(InvalidParameterError, match=r"junction 0: .* px off the circle of arc 0"):
        make_abstraction(junctions=np.array([a.junctions[0] + [0.0, 0.5]]))
    with pytest.raises(InvalidParameterError, match=r"junction 0: arc index 7 is out of range"):
        make_abstraction(junction_arcs=((0, 7),))
    # A reader checks a document that was written elsewhere.
    doc = contract.to_document(a, check=True)
    doc["junctions"][0]["y"] += 0.5
    with pytest.raises(InvalidParameterError, match=r"junction 0: .* px off the circle 0 of arc 0"):
        contract.validate_document(doc)
    with pytest.raises(InvalidParameterError, match=r"junction 0: .* off the circle"):
        contract.from_document(doc)


def test_invariant_radius():
    doc = contract.to_document(make_abstraction())
    doc["circles"][1]["r"] = 12.0
    expected = PHI ** (7 + BIAS)
    with pytest.raises(InvalidParameterError, match=r"^circle 1: r=12.0 is not phi\*\*\(k\+bias\) = ") as info:
        contract.validate_document(doc)
    assert f"{expected:.10g}" in str(info.value)
    # Within the contract's 1e-6 relative tolerance is fine, beyond it is not.
    doc = contract.to_document(make_abstraction())
    doc["circles"][0]["r"] *= 1 + 5e-7
    contract.validate_document(doc)
    doc["circles"][0]["r"] *= 1 + 2e-6
    with pytest.raises(InvalidParameterError, match=r"^circle 0: "):
        contract.validate_document(doc)


def test_invariant_junction_on_circle():
    doc = contract.to_document(make_abstraction())
    doc["junctions"][0]["x"] += 0.01
    with pytest.raises(InvalidParameterError, match=r"^junction 0: \(.*\) is 0.0\d+ px off the circle 0 of arc 0"):
        contract.validate_document(doc)
    # Within 1e-3 px is still on the circle and at the end point.
    doc = contract.to_document(make_abstraction())
    doc["junctions"][0]["x"] += 4e-4
    contract.validate_document(doc)


def test_invariant_arc_end_at_junction():
    a = make_abstraction()
    doc = contract.to_document(a)
    # A junction on the circle of arc 4 (which shares circle 0) but not at its ends.
    doc["junctions"][0]["arcs"] = [0, 1, 4]
    with pytest.raises(InvalidParameterError, match=r"^junction 0: arc 4 has no end point at \(.*\): its nearest end"):
        contract.validate_document(doc)
    # An interior point of arc 0 listing arc 0.
    doc = contract.to_document(a)
    mid = a.arcs[0].circle.point_at(a.arcs[0].theta0 + 1.0)
    doc["junctions"].append({"x": float(mid[0]), "y": float(mid[1]), "arcs": [0]})
    with pytest.raises(InvalidParameterError, match=r"^junction 1: arc 0 has no end point"):
        contract.validate_document(doc)


@pytest.mark.parametrize(
    ("mutate", "message"),
    [
        (lambda d: d["arcs"][0].__setitem__("circle", 9), r"^arc 0: circle index 9 is out of range"),
        (lambda d: d["arcs"][0].__setitem__("sweep", 0.0), r"^arc 0: sweep must satisfy"),
        (lambda d: d["junctions"][0]["arcs"].append(11), r"^junction 0: arc index 11 is out of range"),
    ],
)
def test_invariants_indices_and_sweep(mutate, message):
    doc = contract.to_document(make_abstraction())
    mutate(doc)
    with pytest.raises(InvalidParameterError, match=message):
        contract.validate_document(doc)


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
    doc = contract.to_document(make_abstraction())
    mutate(doc)
    with pytest.raises(InvalidParameterError, match=f"^document does not match the {FORMAT_NAME} schema {message}"):
        contract.validate_document(doc)
    with pytest.raises(InvalidParameterError, match="does not match"):
        contract.from_document(doc)


def test_validate_rejects_non_mapping():
    with pytest.raises(InvalidParameterError, match="document must be a JSON object"):
        contract.validate_document([1, 2])
    with pytest.raises(InvalidParameterError, match="document must be a JSON object"):
        contract.from_document("{}")


def test_round_trip():
    a = make_abstraction()
    for doc in (contract.to_document(a), json.loads(json.dumps(contract.to_document(a)))):
        b = contract.from_document(doc)
        assert b.arcs == a.arcs
        assert b.circles == a.circles
        np.testing.assert_array_equal(b.junctions, a.junctions)
        assert b.junction_arcs == a.junction_arcs
        assert b.arc_segments == a.arc_segments
        assert (b.level, b.similarity, b.bias, b.tolerance, b.width, b.height) == (2, 0.5, BIAS, 2.0, WIDTH, HEIGHT)
        assert b.params == {"kind": "clipart", "rdp_tolerance": 1.5}
        assert contract.to_document(b) == contract.to_document(a)


def test_round_trip_without_arc_segments():
    doc = contract.to_document(make_abstraction())
    del doc["extra"]
    b = contract.from_document(doc)
    assert b.arc_segments == ((),) * 5
    doc["extra"] = {"arc_segments": [[1]]}
    with pytest.raises(InvalidParameterError, match=r"extra.arc_segments must have one entry per arc \(5\), got 1"):
        contract.from_document(doc)


def test_reading_checks_the_invariants_and_the_structure():
    doc = contract.to_document(make_abstraction())
    assert contract.from_document(doc).arcs == make_abstraction().arcs
    bad = copy.deepcopy(doc)
    bad["circles"][0]["r"] = 1.0
    with pytest.raises(InvalidParameterError, match=r"^circle 0: r=1\.0"):
        contract.from_document(bad)
    bad = copy.deepcopy(doc)
    del bad["arcs"][0]["theta0"]
    with pytest.raises(InvalidParameterError, match=f"does not match the {FORMAT_NAME} schema at arcs/0"):
        contract.from_document(bad)


def test_fibonacci_ladder():
    from img2logo.geometry.golden_ladder import FibonacciLadder

    unit = 3.0
    c1, c2 = Circle(50.0, 50.0, unit * 5, 5), Circle(50.0, 50.0, unit * 8, 6)
    fields = dict(arc_segments=((0,), (1,)), junctions=np.zeros((0, 2)), junction_arcs=(), bias=0.0)
    a = make_abstraction(arcs=(Arc(c1, 0.0, 1.0), Arc(c2, 0.0, -1.0)), ladder=FibonacciLadder(unit), **fields)
    doc = contract.to_document(a)
    assert doc["ladder"] == "fibonacci" and doc["unit"] == unit
    contract.validate_document(doc)
    back = contract.from_document(doc)
    assert back.ladder == FibonacciLadder(unit) and contract.to_document(back) == doc
    doc["circles"][1]["k"] = 7
    with pytest.raises(InvalidParameterError, match=r"^circle 1: r=24.0 is not unit\*F\(k\) = 39 \(k=7, unit=3.0\)"):
        contract.validate_document(doc)
    # The ladder is the abstraction's: a Fibonacci radius is no phi radius.
    with pytest.raises(InvalidParameterError, match=r"^circle 0: r=15.0 is not phi\*\*\(k\+bias\)"):
        make_abstraction(arcs=(Arc(c1, 0.0, 1.0), Arc(c2, 0.0, -1.0)), **fields)


def _packaged_schema():
    """The JSON Schema the package ships (``SCHEMA_RESOURCE`` beside the contract module)."""
    from importlib import resources

    return json.loads(resources.files("img2logo.export").joinpath(contract.SCHEMA_RESOURCE).read_text("utf-8"))


def test_schema_is_read_from_the_package():
    schema = _packaged_schema()
    assert schema["$id"] == FORMAT_NAME
    assert not re.search(r"shared", contract.__file__)


# --- arcs that do not meet (--no-connectivity) -------------------------------------------


def _unconnected(connectivity: bool) -> Abstraction:
    """make_abstraction with arc 1 turned by 0.05 rad: its start is ~0.4 px off the junction P."""
    a = make_abstraction()
    arcs = list(a.arcs)
    arcs[1] = Arc(arcs[1].circle, arcs[1].theta0 - 0.05, arcs[1].sweep)
    return make_abstraction(arcs=tuple(arcs), params={"connectivity": connectivity}, connected=connectivity)


def test_unconnected_arc_ends_are_their_own_junctions():
    doc = contract.to_document(_unconnected(False))
    contract.validate_document(doc)
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
    from helpers import DATA

    from img2logo import abstract

    result = abstract(DATA / "clipart-fish.png", connectivity=False, progress=False)
    for level in (result.levels[0], result.final):
        contract.validate_document(json.loads(writers.write_json(level, tmp_path / "fish.json").read_text()))


# --- fills in the document ----------------------------------------------------------------


def test_json_with_fills_validates_and_reads_back(tmp_path):
    pytest.importorskip("jsonschema")
    a = four_arcs()
    fs = palette_fills(a)
    doc = contract.to_document(a, fills=fs)
    contract.validate_document(doc)
    assert doc["fills"] == [{"path": f.path, "color": f.color} for f in fs]
    assert "fills" not in contract.to_document(a)
    assert contract.to_document(a, fills=())["fills"] == []
    path = writers.write_json(a, tmp_path / "logo.json", fills=fs)
    contract.validate_document(json.loads(path.read_text()))
    back = contract.read_fills(path)
    assert [(f.path, f.color) for f in back] == [(f.path, f.color) for f in fs]
    assert contract.read_fills(doc) == back and all(f.face is None for f in back)
    writers.read_json(path)  # the abstraction itself still reads
    # A gradient's JSON colour is its colour at the face's centroid.
    grad = fills.fill_gradient(a, ["#000000", "#ffffff"])
    assert [e["color"] for e in contract.to_document(a, fills=grad)["fills"]] == [f.color for f in grad]


def test_json_fills_validation():
    a = four_arcs()
    with pytest.raises(InvalidParameterError, match=r"fills\[0\] must be a Fill, got dict"):
        contract.to_document(a, fills=[{"path": "M 0 0 Z", "color": "#ffffff"}])
    with pytest.raises(InvalidParameterError, match="fills must be a sequence of Fill, got Fill"):
        contract.to_document(a, fills=palette_fills(a)[0])
    with pytest.raises(InvalidParameterError, match=r"fills\[0\]: fill color 'blue' is not of the form #rrggbb"):
        contract.read_fills({"fills": [{"path": "M 0 0 A 1 1 0 0 1 2 0 Z", "color": "blue"}]})
    with pytest.raises(InvalidParameterError, match=r"fills\[0\] must be an object with 'path' and 'color'"):
        contract.read_fills({"fills": [{"path": "M 0 0 Z"}]})
    assert contract.read_fills({"format": "x"}) == ()


def test_reading_a_document_loads_no_part_of_the_pipeline():
    # The file format is a reader's business: reading or writing a (symmetric) document must not
    # load the axis search, the segment graph or the optimizer (the axis helpers are in mirror).
    loaded = set(modules_loaded("import img2logo.export.contract, img2logo.export.writers", "img2logo"))
    pipeline = {
        "fit.symmetry",
        "fit.progressive",
        "fit.constrained_fit",
        "fit.merging",
        "segment_graph",
        "features.preprocessing",
        "pipeline",
    }
    assert not loaded & {f"img2logo.{m}" for m in pipeline}
    assert "img2logo.geometry.mirror" in loaded


@pytest.mark.parametrize(
    ("width", "message"),
    [
        (1e308, r"width must be an integer, got 1e\+308"),
        (10**30, r"width x height must be at most 150,000,000 px \(the largest image img2logo reads\), got 1e\+30 x"),
        (2_000_000, r"width x height must be at most 150,000,000 px"),
    ],
)
def test_a_document_of_an_absurd_size_is_refused(tmp_path, width, message):
    # write_png then raised matplotlib's TypeError or asked for 40 GB.
    doc = contract.to_document(make_abstraction())
    doc["width"] = width
    with pytest.raises(InvalidParameterError, match=message):
        contract.from_document(doc)
    (tmp_path / "big.json").write_text(json.dumps(doc))
    with pytest.raises(InvalidParameterError, match=message):
        writers.read_json(tmp_path / "big.json")


# --------------------------------------------------------------------------- hostile documents
def _nested(depth: int) -> dict:
    inner: dict = {}
    for _ in range(depth):
        inner = {"a": inner}
    return inner


@pytest.mark.parametrize(
    ("mutate", "message"),
    [
        (
            lambda d: d["circles"][0].update(k=2000),
            r"circle 0: k=2000 gives phi\*\*\(k\+bias\) beyond any float radius",
        ),
        (lambda d: d["circles"][0].update(k=10**400), r"circle 0: k=about 10\*\*400 gives phi\*\*\(k\+bias\) beyond"),
        (lambda d: d.update(width=10**400), r"not a valid img2logo.abstraction/1 document: OverflowError"),
        (lambda d: d["params"].update(deep=_nested(500)), r"not a valid img2logo.abstraction/1 document: nested too"),
    ],
)
def test_a_hostile_document_is_one_line_not_an_overflow_or_recursion(tmp_path, mutate, message):
    # OverflowError and RecursionError went through read_json (31 of 2,058 malformed documents).
    doc = contract.to_document(make_abstraction())
    mutate(doc)
    path = tmp_path / "hostile.json"
    path.write_text(json.dumps(doc), encoding="utf-8")
    with pytest.raises(InvalidParameterError, match=message) as caught:
        writers.read_json(path)
    assert "\n" not in str(caught.value)


def test_a_json_nested_thousands_deep_or_an_integer_of_thousands_of_digits_is_one_line(tmp_path):
    path = tmp_path / "deep.json"
    path.write_text("[" * 100_000 + "]" * 100_000, encoding="utf-8")
    with pytest.raises(InvalidParameterError, match=r"deep\.json is not a valid document: JSON nested too deeply"):
        writers.read_json(path)
    path.write_text('{"width": ' + "9" * 5000 + "}", encoding="utf-8")
    with pytest.raises(InvalidParameterError, match=r"deep\.json is not JSON: Exceeds the limit"):
        writers.read_json(path)


@pytest.mark.parametrize("k", [10**6, 2**31])
def test_a_huge_fibonacci_index_is_refused_before_any_work(k):
    # fibonacci(k)'s exact integer is quadratic in k: a document of k = 10**6 hung.
    from img2logo.geometry.golden_ladder import FibonacciLadder

    c1 = Circle(50.0, 50.0, 15.0, 5)
    fields = dict(arc_segments=((0,),), junctions=np.zeros((0, 2)), junction_arcs=(), bias=0.0)
    doc = contract.to_document(make_abstraction(arcs=(Arc(c1, 0.0, 1.0),), ladder=FibonacciLadder(3.0), **fields))
    doc["circles"][0]["k"] = k
    with pytest.raises(InvalidParameterError, match=rf"^circle 0: k={k} is not a Fibonacci index of a float radius"):
        contract.from_document(doc)


def test_a_document_of_too_many_circles_is_refused_before_any_work(monkeypatch):
    # 10**5 circles took 29 s to check.
    doc = contract.to_document(make_abstraction())
    doc["circles"] = doc["circles"] * (contract.MAX_DOCUMENT_ITEMS // len(doc["circles"]) + 1)
    checked = []
    monkeypatch.setattr(contract, "_check_invariants", lambda d: checked.append(d))
    with pytest.raises(InvalidParameterError, match=r"^circles must have at most 10,000 entries"):
        contract.from_document(doc)
    with pytest.raises(InvalidParameterError, match=r"^circles must have at most 10,000 entries"):
        contract.validate_document(doc)
    assert checked == []
