"""Tests of img2logo.design.arrangement: the faces of the arrangement of arcs (the regions Fig. 18 fills)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import BIAS, A, B, abstraction_of, four_arcs, full, golden, svg_arc_center, two_circles
from hypothesis import HealthCheck, given, settings, strategies as st

from img2logo.constants import PHI
from img2logo.design import arrangement
from img2logo.errors import InvalidParameterError
from img2logo.geometry.primitives import TAU, Arc, Circle


def lens_area(r1: float, r2: float, d: float) -> float:
    """Area of the intersection of two discs (radii r1, r2, centres d apart)."""
    a1 = r1 * r1 * math.acos((d * d + r1 * r1 - r2 * r2) / (2 * d * r1))
    a2 = r2 * r2 * math.acos((d * d + r2 * r2 - r1 * r1) / (2 * d * r2))
    return a1 + a2 - 0.5 * math.sqrt((-d + r1 + r2) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2))


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
    found = arrangement.faces(a)
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
    for face in arrangement.faces(a):
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
    a = abstraction_of([Arc(c, 0.4, TAU)])
    (face,) = arrangement.faces(a)
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
    a = abstraction_of([full(outer), full(inner, 2.0, -1.0)])
    ring, disc = arrangement.faces(a)
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
    a = abstraction_of([full(big, 0.0), full(small, 0.0, -1.0)], [[big.cx + big.r, big.cy]], [(0, 1)])
    found = arrangement.faces(a)
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
    a = abstraction_of([full(c), bridge, full(d, math.pi), tail], [p, q, bottom], [(0, 1), (1, 2), (3,)], width=260)
    found = arrangement.faces(a)
    assert [f.area for f in found] == pytest.approx([math.pi * c.r**2, math.pi * d.r**2], rel=1e-12)
    assert all(f.holes == () for f in found)


def test_overlapping_arcs_of_one_circle_count_once():
    c = golden(120.0, 100.0, 8)
    a = abstraction_of([Arc(c, 0.0, 4.0), Arc(c, 3.0, 3.5), Arc(c, 6.0, -1.0)])  # together they close the circle
    (face,) = arrangement.faces(a)
    assert face.area == pytest.approx(math.pi * c.r**2, rel=1e-12)
    assert len(parse_path(face.path)[0][1]) == 2  # joined into one turn, written as two halves


def test_no_closed_region_gives_no_face():
    c = golden(100.0, 100.0, 8)
    assert arrangement.faces(abstraction_of([Arc(c, 0.0, 3.0)])) == ()
    assert arrangement.faces(abstraction_of([])) == ()


def test_faces_validation():
    with pytest.raises(InvalidParameterError, match="abstraction must be an Abstraction, got str"):
        arrangement.faces("logo")
    with pytest.raises(InvalidParameterError, match=r"snap must be > 0, got 0.0"):
        arrangement.faces(two_circles(), snap=0)


def test_face_adjacency_of_the_two_circles():
    found = arrangement.faces(two_circles())
    adjacent = arrangement.face_adjacency(found)
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
    found = arrangement.faces(abstraction_of([full(c, 0.1 * i) for i, c in enumerate(cs)]), min_area=0.0)
    union = shapely.unary_union([Point(c.cx, c.cy).buffer(c.r, quad_segs=256) for c in cs])
    assert sum(f.area for f in found) == pytest.approx(union.area, rel=1e-3)
    for f in found:
        assert f.area > 0.0
        assert f.polygon.area == pytest.approx(f.area, rel=2e-3, abs=0.5)
