"""Tests of img2logo.geometry.svg_path: one number formatter and one near-full-turn rule; reading path data."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import A, B, abstraction_of, full, golden

from img2logo.design import arrangement
from img2logo.errors import InvalidParameterError
from img2logo.geometry import svg_path
from img2logo.geometry.primitives import TAU, Arc


def test_sample_path_follows_the_arcs():
    a = abstraction_of([full(A), full(B, 1.0, -1.0)])
    for face in arrangement.faces(a):
        rings = svg_path.sample_path(face.path, step=0.25)
        assert len(rings) == 1
        for ring in rings:  # every sample lies on one of the two circles
            off = np.minimum(np.abs(A.distance(ring)), np.abs(B.distance(ring)))
            assert off.max() < 1e-6
    with pytest.raises(InvalidParameterError, match=r"unsupported command 'C'"):
        svg_path.sample_path("M 0 0 C 1 1 2 2 3 3 Z")
    with pytest.raises(InvalidParameterError, match=r"relative commands are not supported"):
        svg_path.sample_path("M 0 0 a 1 1 0 0 1 2 0 Z")
    with pytest.raises(InvalidParameterError, match=r"only circular arcs \(rx == ry\), got rx=1, ry=2"):
        svg_path.sample_path("M 0 0 A 1 2 0 0 1 2 0 Z")
    with pytest.raises(InvalidParameterError, match=r"command 'A' needs 7 numbers"):
        svg_path.sample_path("M 0 0 A 1 1 0 0 1 Z")


def test_svg_number_has_fixed_decimals_without_trailing_zeros():
    n = svg_path.svg_number
    assert [n(1.0), n(2.5), n(1 / 3), n(123.4567896), n(np.float64(-7.25))] == [
        "1",
        "2.5",
        "0.333333",
        "123.45679",
        "-7.25",
    ]
    assert n(-1e-9) == "0" and n(0.0) == "0"  # never "-0"


def test_one_near_full_turn_rule_for_arcs_and_face_outlines():
    c = golden(120.0, 100.0, 9)
    # An arc within 1e-3 rad of a full turn is two commands, a little less than that one.
    assert svg_path.arc_path(Arc(c, 0.4, TAU - 2e-3)).count("A ") == 1
    assert svg_path.arc_path(Arc(c, 0.4, -(TAU - 5e-4))).count("A ") == 2
    # A face bounded by one full circle is written exactly as that circle's arc: the same halves, the same numbers.
    arc = Arc(c, 0.4, TAU)
    (face,) = arrangement.faces(abstraction_of([arc]))
    assert face.path == svg_path.arc_path(arc)
    d = svg_path.arc_path(arc)
    assert d.startswith("M ") and d.count("A ") == 2 and d.endswith(" Z")


def test_loop_path_joins_pieces_of_one_circle():
    c = golden(120.0, 100.0, 8)
    # Three arcs of one circle that together close it: one face, its outline one turn in two halves.
    (face,) = arrangement.faces(abstraction_of([Arc(c, 0.0, 4.0), Arc(c, 4.0, 1.0), Arc(c, 5.0, TAU - 5.0)]))
    assert svg_path.loop_path(face.boundary) == face.path
    assert face.path.count("A ") == 2
