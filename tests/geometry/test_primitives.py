"""Tests of the frozen geometry values: lines, parameters, and the abstraction's ladder, topology and invariants."""

from __future__ import annotations

import copy
import dataclasses
import math
import pickle

import numpy as np
import pytest

from img2logo.constants import PHI
from img2logo.errors import InvalidParameterError
from img2logo.geometry.abstraction import Abstraction
from img2logo.geometry.golden_ladder import FibonacciLadder, GoldenLadder
from img2logo.geometry.primitives import Arc, ArcJunctions, Circle, Line, Params, line_arc

BIAS = 0.3


def golden(cx: float, cy: float, k: int) -> Circle:
    return Circle(cx, cy, PHI ** (k + BIAS), k)


def chain(**overrides) -> Abstraction:
    """Arc 0 runs from junction 0 through junction 1 to junction 2 (a half circle); arc 1 starts at junction 1
    and ends free; arc 2 is a line from junction 2."""
    return Abstraction(**chain_fields(**overrides))


def chain_fields(**overrides) -> dict:
    """The fields of :func:`chain`'s abstraction, with ``overrides``."""
    c = golden(100.0, 100.0, 8)
    arc0 = Arc(c, math.pi, math.pi)  # left -> top -> right: (100 - r, 100) over (100, 100 - r) to (100 + r, 100)
    top, right = c.point_at(-math.pi / 2), c.point_at(0.0)
    d = golden(0.0, 0.0, 5)
    d = Circle(float(top[0]), float(top[1]) - d.r, d.r, d.k)  # touches c at its top
    arc1 = Arc(d, math.pi / 2, 1.0)
    line = line_arc(right, np.add(right, (40.0, 0.0)))
    fields = dict(
        level=1,
        arcs=(arc0, arc1, line),
        arc_segments=((0, 1), (2,), (3,)),
        junctions=np.array([c.point_at(math.pi), top, right]),
        junction_arcs=((0,), (0, 1), (0, 2)),
        similarity=0.5,
        bias=BIAS,
        tolerance=5.0,
        width=260,
        height=200,
        params={"kind": "drawing", "exponents": [5, 8]},
    )
    fields.update(overrides)
    return fields


# --------------------------------------------------------------------------- lines
def test_a_line_is_its_own_primitive():
    line = line_arc((10.0, 20.0), (310.0, 170.0))
    assert isinstance(line, Line) and line.is_line and line.circle.k is None
    np.testing.assert_allclose([line.start, line.end], [[10.0, 20.0], [310.0, 170.0]], atol=1e-6)
    # The same arc, unmarked, is a circular arc (off the ladder): no longer taken for a line.
    plain = Arc(line.circle, line.theta0, line.sweep)
    assert not plain.is_line and plain != line and Line.of(plain) == line
    with pytest.raises(InvalidParameterError, match="a line's circle has no ladder exponent, got k=3"):
        Line(Circle(0.0, 0.0, 1e6, 3), 0.0, 1e-4)


# --------------------------------------------------------------------------- params
def test_params_are_immutable_and_compare_like_a_mapping():
    p = Params({"a": 1, "edits": ["x"], "nested": {"b": [1, 2]}})
    assert p == {"a": 1, "edits": ("x",), "nested": {"b": (1, 2)}}
    assert isinstance(p["nested"], Params)
    with pytest.raises(TypeError):
        p["a"] = 2  # type: ignore[index]
    with pytest.raises(AttributeError):
        p._items = {}  # type: ignore[misc]
    assert pickle.loads(pickle.dumps(p)) == p and copy.deepcopy(p) is p
    assert p.to_dict() == {"a": 1, "edits": ("x",), "nested": {"b": (1, 2)}}
    with pytest.raises(InvalidParameterError, match="params must be a mapping, got list"):
        Params([1])  # type: ignore[arg-type]


def test_abstraction_freezes_its_params():
    given = {"kind": "drawing", "exponents": [5, 8]}
    a = chain(params=given)
    given["kind"] = "photo"
    assert a.params["kind"] == "drawing" and a.params["exponents"] == (5, 8)
    with pytest.raises(TypeError):
        a.params["kind"] = "photo"  # type: ignore[index]


# --------------------------------------------------------------------------- topology
def test_topology_found_from_the_geometry_when_not_given():
    a = chain()
    assert a.arc_junctions == (ArcJunctions(0, 2, (1,)), ArcJunctions(1, None), ArcJunctions(2, None))
    assert a.arc_junctions[0].ordered == (0, 1, 2) and a.arc_junctions[0].ends == (0, 2)
    assert a.arcs_at(1) == (1,)  # arc 0 passes through junction 1: only arc 1 ends there
    assert a.junction_nodes == (None, None, None)


def test_topology_given_is_checked_against_the_junctions():
    a = chain(arc_junctions=(ArcJunctions(0, 2, (1,)), ArcJunctions(1), ArcJunctions(2)), junction_nodes=(4, 9, 11))
    assert a.junction_nodes == (4, 9, 11)
    assert a.arc_nodes(0) == (4, 9, 11) and a.arc_nodes(1) == (9,)
    with pytest.raises(
        InvalidParameterError, match=r"junction 1 lists arcs \[0, 1\], but arc_junctions puts arcs \[1\]"
    ):
        chain(arc_junctions=(ArcJunctions(0, 2), ArcJunctions(1), ArcJunctions(2)))
    with pytest.raises(InvalidParameterError, match="junction 1: arc 0 has no end point at"):
        chain(arc_junctions=(ArcJunctions(0, 1, (2,)), ArcJunctions(1), ArcJunctions(2)))
    with pytest.raises(InvalidParameterError, match="arc_junctions must have one entry per arc"):
        chain(arc_junctions=(ArcJunctions(0, 2, (1,)),))
    with pytest.raises(InvalidParameterError, match="junction_nodes must have one entry per junction"):
        chain(junction_nodes=(1, 2))


def test_a_closed_arc_starts_and_ends_at_one_junction():
    c = golden(100.0, 100.0, 6)
    a = Abstraction(
        0, (Arc(c, 0.0, 2 * math.pi),), ((0,),), np.array([c.point_at(0.0)]), ((0,),), 0.0, BIAS, 5.0, 200, 200
    )
    assert a.arc_junctions == (ArcJunctions(0, 0),)
    assert a.arc_junctions[0].ordered == (0,) and a.arcs_at(0) == (0,)


def test_renumbered_drops_a_junction_to_a_free_end():
    t = ArcJunctions(3, 7, (5,))
    assert t.renumbered({3: 0, 5: 1}) == ArcJunctions(0, None, (1,))


# --------------------------------------------------------------------------- invariants
def test_unconnected_junctions_need_not_meet_their_arcs():
    moved = np.add(chain().junctions, [[3.0, 0.0], [0.0, 0.0], [0.0, 0.0]])
    with pytest.raises(InvalidParameterError, match=r"junction 0: .* is 3 px off the circle of arc 0"):
        chain(junctions=moved)
    a = chain(junctions=moved, connected=False)  # the connectivity ablation (Fig. 11c): its gaps are its point
    assert not a.connected and a.arc_junctions[0].start == 0


def test_an_unconnected_arc_with_one_junction_has_it_at_one_end():
    c = golden(100.0, 100.0, 8)
    arc = Arc(c, 0.0, 1.0)
    near_end = np.add(arc.end, (2.0, 0.0))  # 2 px off the end: a gap of the connectivity ablation
    a = Abstraction(0, (arc,), ((0,),), np.array([near_end]), ((0,),), 0.0, BIAS, 5.0, 200, 200, connected=False)
    assert a.arc_junctions == (ArcJunctions(None, 0),)


def test_every_circle_is_on_the_ladder():
    a = chain()
    assert a.ladder == GoldenLadder(BIAS)
    off = Circle(10.0, 10.0, 12.0, 5)
    with pytest.raises(InvalidParameterError, match=r"circle 3: r=12.0 is not phi\*\*\(k\+bias\) = 12.81"):
        chain(arcs=(*a.arcs, Arc(off, 0.0, 1.0)), arc_segments=(*a.arc_segments, ()))
    with pytest.raises(InvalidParameterError, match=r"circle 3 \(centre \(10, 10\), r=12\) has no ladder exponent k"):
        chain(arcs=(*a.arcs, Arc(Circle(10.0, 10.0, 12.0), 0.0, 1.0)), arc_segments=(*a.arc_segments, ()))
    with pytest.raises(InvalidParameterError, match=r"bias 0.3 is not the ladder's bias 0.0"):
        chain(ladder=FibonacciLadder(1.0))
    with pytest.raises(InvalidParameterError, match=r"circle 0: r=.* is not unit\*F\(k\)"):
        chain(ladder=FibonacciLadder(1.0), bias=0.0)


@pytest.mark.parametrize(
    ("field", "value", "message"),
    [
        ("bias", 1.0, r"bias must be in \[0, 1\), got 1.0"),
        ("similarity", -1.0, "similarity must be >= 0"),
        ("tolerance", 0.0, "tolerance must be > 0"),
        ("level", -1, "level must be >= 0"),
        ("width", 0, "width must be >= 1"),
        ("height", 2.5, "height must be an integer, got 2.5"),
        ("similarity", math.nan, "similarity must be finite"),
        ("junction_arcs", ((0,), (0, 5), (0, 2)), r"junction 1: arc index 5 is out of range"),
        ("arc_segments", ((0,),), r"arc_segments must have one entry per arc \(3\), got 1"),
    ],
)
def test_fields_out_of_range_are_refused(field, value, message):
    with pytest.raises(InvalidParameterError, match=message):
        chain(**{field: value})


def test_replace_checks_again():
    a = chain()
    with pytest.raises(InvalidParameterError, match="tolerance must be > 0"):
        dataclasses.replace(a, tolerance=-1.0)
    assert dataclasses.replace(a, level=4).arc_junctions == a.arc_junctions


def test_scaled_abstraction_stays_on_the_ladder_and_scales_back():
    # a result of a downscaled input is written in the input's pixels.
    from helpers import make_abstraction

    from img2logo.constants import LOG_PHI

    a = make_abstraction()
    b = a.scaled(2.0, 2 * a.width, 2 * a.height)
    assert (b.width, b.height) == (2 * a.width, 2 * a.height)
    t = a.bias + math.log(2.0) / LOG_PHI
    assert b.bias == pytest.approx(t - math.floor(t), abs=1e-12)
    for ca, cb in zip(a.golden_circles, b.golden_circles, strict=True):
        assert cb.k == ca.k + math.floor(t) and cb.r == pytest.approx(2.0 * ca.r, rel=1e-12)
        assert (cb.cx, cb.cy) == pytest.approx((2.0 * ca.cx, 2.0 * ca.cy), rel=1e-12)
        assert cb.r == b.ladder.radius(cb.k)  # exactly a rung of the new ladder
    np.testing.assert_allclose(b.junctions, 2.0 * a.junctions, rtol=1e-12)
    assert (b.similarity, b.tolerance) == pytest.approx((2.0 * a.similarity, 2.0 * a.tolerance))
    back = b.scaled(0.5, a.width, a.height)
    assert back.bias == pytest.approx(a.bias, abs=1e-12)
    assert [c.k for c in back.golden_circles] == [c.k for c in a.golden_circles]
    np.testing.assert_allclose(back.junctions, a.junctions, atol=1e-9)
    fib = a.scaled(1.0, a.width, a.height)  # nothing changes at factor 1
    assert [c.r for c in fib.golden_circles] == pytest.approx([c.r for c in a.golden_circles], rel=1e-12)


def test_polyline_lengths_are_known_answers():
    from img2logo.geometry.primitives import cumulative_length, polyline_length

    pts = np.array([[0.0, 0.0], [3.0, 4.0], [3.0, 5.0]])  # a 3-4-5 triangle's hypotenuse, then 1 px
    assert polyline_length(pts) == 6.0
    np.testing.assert_array_equal(cumulative_length(pts), [0.0, 5.0, 6.0])
    assert polyline_length(pts[:1]) == 0.0
    np.testing.assert_array_equal(cumulative_length(pts[:1]), [0.0])


def test_arcs_known_to_hold_are_left_out_of_the_geometric_check_only():
    fields = chain_fields(arc_junctions=(ArcJunctions(0, 2, (1,)), ArcJunctions(1), ArcJunctions(2)))
    plain = Abstraction(**fields)
    known = Abstraction._with_known((True, False, True), **fields)
    assert known.arcs == plain.arcs and known.arc_junctions == plain.arc_junctions
    assert np.array_equal(known.junctions, plain.junctions) and "_known" not in vars(known)
    # Arc 0 ends at junction 1 instead of 2: caught, unless arc 0 is known.
    wrong = dict(fields, arc_junctions=(ArcJunctions(0, 1, (2,)), ArcJunctions(1), ArcJunctions(2)))
    with pytest.raises(InvalidParameterError, match="junction 1: arc 0 has no end point at"):
        Abstraction._with_known((False, True, True), **wrong)
    assert Abstraction._with_known((True, False, False), **wrong).arc_junctions[0].end == 1
    # The structural checks run for known arcs too.
    with pytest.raises(InvalidParameterError, match="junction 1 lists arcs"):
        Abstraction._with_known(
            (True, True, True), **dict(fields, arc_junctions=(ArcJunctions(0, 2), ArcJunctions(1), ArcJunctions(2)))
        )
