"""Tests of img2logo.design.edits: user edits of a golden ratio logo (paper Sec. 7, Fig. 17)."""

from __future__ import annotations

import copy
import dataclasses
import math

import numpy as np
import pytest
from helpers import DATA

import img2logo
from img2logo.constants import PHI
from img2logo.design import edits
from img2logo.errors import FitError, InvalidParameterError
from img2logo.export.contract import to_document, validate_document
from img2logo.geometry.abstraction import Abstraction
from img2logo.geometry.golden_ladder import FibonacciLadder, GoldenLadder
from img2logo.geometry.primitives import Arc, Circle, line_arc

pytest.importorskip("jsonschema")

TOL = 1e-6
BIAS = 0.25


# --------------------------------------------------------------------------- helpers
def golden(cx: float, cy: float, k: int, bias: float = BIAS) -> Circle:
    return Circle(cx, cy, PHI ** (k + bias), k)


def check_invariants(a: Abstraction) -> None:
    """The contract (schema, ladder, junctions on arcs to 1e-3) and, directly, to 1e-6 px."""
    validate_document(to_document(a))
    assert len(a.arc_segments) == len(a.arcs)
    for c in a.circles:
        assert c.k is not None
        assert abs(c.r - PHI ** (c.k + a.bias)) <= 1e-9 * c.r
    for j, (p, listed) in enumerate(zip(a.junctions, a.junction_arcs, strict=True)):
        assert listed, f"junction {j} lists no arc"
        for i in listed:
            arc = a.arcs[i]
            assert abs(float(arc.circle.distance(p))) <= TOL, (j, i)
            at_end = min(math.dist(p, arc.start), math.dist(p, arc.end)) <= TOL
            inside = bool(arc.contains_angle(float(arc.circle.angle_of(p)), tol=TOL / arc.circle.r))
            assert at_end or inside, (j, i)


def snapshot(a: Abstraction) -> tuple:
    """Everything of an abstraction, to check that an edit left it unchanged."""
    return (
        a.level,
        a.arcs,
        a.arc_segments,
        a.junctions.copy(),
        a.junction_arcs,
        a.similarity,
        a.bias,
        copy.deepcopy(a.params),
    )


def assert_unchanged(a: Abstraction, snap: tuple) -> None:
    now = snapshot(a)
    for x, y in zip(now, snap, strict=True):
        if isinstance(x, np.ndarray):
            np.testing.assert_array_equal(x, y)
        else:
            assert x == y
    assert not a.junctions.flags.writeable


def end_junctions(a: Abstraction, i: int) -> tuple[int | None, int | None]:
    """The junctions at the start and at the end of arc i (None: none there)."""
    arc = a.arcs[i]
    out = []
    for point in (arc.start, arc.end):
        found = [
            j for j, listed in enumerate(a.junction_arcs) if i in listed and math.dist(a.junctions[j], point) <= TOL
        ]
        out.append(found[0] if found else None)
    return out[0], out[1]


def free_ends(a: Abstraction) -> list[int]:
    return [j for j, listed in enumerate(a.junction_arcs) if len(set(listed)) == 1]


@pytest.fixture(scope="module")
def fish() -> Abstraction:
    """The automated result of the drawing-fish (12 arcs; the gill stroke has two free ends)."""
    return img2logo.abstract(DATA / "drawing-fish.png", progress=False).final


@pytest.fixture
def lens() -> Abstraction:
    """By hand: two golden circles meeting at junctions 0 (top) and 1 (bottom).

    Arc 0 runs the long way round circle 0 (left) from the top to the bottom
    junction, arc 1 the long way round circle 1 (right) from the bottom to the
    top: the outline of two overlapping discs.
    """
    a, b = golden(100.0, 100.0, 8), golden(160.0, 100.0, 8)
    half = 30.0
    h = math.sqrt(a.r**2 - half**2)
    top, bottom = np.array([130.0, 100.0 - h]), np.array([130.0, 100.0 + h])
    ta_top, ta_bottom = float(a.angle_of(top)), float(a.angle_of(bottom))
    tb_top, tb_bottom = float(b.angle_of(top)), float(b.angle_of(bottom))
    arc0 = Arc(a, ta_top, -float(np.mod(ta_top - ta_bottom, 2 * math.pi)))  # counter-clockwise via the left
    arc1 = Arc(b, tb_bottom, -float(np.mod(tb_bottom - tb_top, 2 * math.pi)))  # via the right
    out = Abstraction(
        level=3,
        arcs=(arc0, arc1),
        arc_segments=((0,), (1, 2)),
        junctions=np.array([top, bottom]),
        junction_arcs=((0, 1), (0, 1)),
        similarity=1.5,
        bias=BIAS,
        tolerance=5.0,
        width=260,
        height=200,
        params={"kind": "drawing"},
    )
    return out


@pytest.fixture
def passing() -> Abstraction:
    """By hand: arc 0 on circle 0 runs from junction 0 through junction 1 to junction 2;
    arc 1 on circle 1 ends at junction 1 (where arc 0 passes) and at the free end 3."""
    a = golden(100.0, 100.0, 8)
    c = golden(0.0, 0.0, 6)
    c = Circle(100.0 - a.r - c.r, 100.0, c.r, c.k)  # touches circle 0 at its leftmost point
    left = np.array([100.0 - a.r, 100.0])
    j0, j2 = a.point_at(-math.pi / 2), a.point_at(math.pi / 2)  # top and bottom
    arc0 = Arc(a, -math.pi / 2, -math.pi)  # top -> left -> bottom
    arc1 = Arc(c, 0.0, math.pi / 2)  # from the touching point downwards
    return Abstraction(
        level=0,
        arcs=(arc0, arc1),
        arc_segments=((0,), (1,)),
        junctions=np.array([j0, left, j2, arc1.end]),
        junction_arcs=((0,), (0, 1), (0,), (1,)),
        similarity=0.5,
        bias=BIAS,
        tolerance=5.0,
        width=200,
        height=200,
        params={},
    )


# --------------------------------------------------------------------------- inputs
def test_inputs_are_valid(fish: Abstraction, lens: Abstraction, passing: Abstraction) -> None:
    for a in (fish, lens, passing):
        check_invariants(a)
    assert len(free_ends(fish)) >= 2  # the gill stroke


# --------------------------------------------------------------------------- delete_arc
def test_delete_arc_fish(fish: Abstraction) -> None:
    snap = snapshot(fish)
    i = 4
    b = edits.delete_arc(fish, i)
    check_invariants(b)
    assert len(b.arcs) == len(fish.arcs) - 1
    assert b.arcs == fish.arcs[:i] + fish.arcs[i + 1 :]
    assert b.arc_segments == fish.arc_segments[:i] + fish.arc_segments[i + 1 :]
    # Arc 4 shared its two junctions with arcs 3 and 5: both stay, now free ends.
    assert len(b.junctions) == len(fish.junctions)
    assert len(free_ends(b)) == len(free_ends(fish)) + 2
    assert b.params["edits"] == (f"delete_arc({i})",)
    assert "edits" not in fish.params
    assert_unchanged(fish, snap)


def test_delete_arc_drops_orphan_junctions(fish: Abstraction) -> None:
    gill = next(i for i in range(len(fish.arcs)) if all(j in free_ends(fish) for j in end_junctions(fish, i)))
    b = edits.delete_arc(fish, gill)
    check_invariants(b)
    assert len(b.arcs) == len(fish.arcs) - 1
    assert len(b.junctions) == len(fish.junctions) - 2  # the gill's two free ends
    assert all(i < len(b.arcs) for listed in b.junction_arcs for i in listed)


def test_delete_arc_renumbers(lens: Abstraction) -> None:
    b = edits.delete_arc(lens, 0)
    check_invariants(b)
    assert b.arcs == (lens.arcs[1],)
    assert b.junction_arcs == ((0,), (0,))
    assert b.arc_segments == ((1, 2),)
    np.testing.assert_array_equal(b.junctions, lens.junctions)
    with pytest.raises(InvalidParameterError, match=r"^cannot delete arc 0: it is the only arc"):
        edits.delete_arc(b, 0)


def test_history_accumulates(lens: Abstraction) -> None:
    b = edits.change_rung(edits.delete_arc(lens, 1), 0, +1)
    assert b.params["edits"] == (
        "delete_arc(1)",
        "change_rung(0, delta=1)",
    )
    assert b.params["kind"] == "drawing"
    assert lens.params == {"kind": "drawing"}
    assert (b.level, b.similarity, b.tolerance, b.width, b.height) == (3, 1.5, 5.0, 260, 200)


# --------------------------------------------------------------------------- add_arc
def test_add_arc_other_side(lens: Abstraction) -> None:
    snap = snapshot(lens)
    start, end = end_junctions(lens, 0)
    assert (start, end) == (0, 1)
    # Arc 0 runs from junction 0 to 1 with a negative sweep: +1 adds the other side of circle 0.
    b = edits.add_arc(lens, 0, 0, 1, sweep_sign=+1)
    check_invariants(b)
    assert len(b.arcs) == 3 and len(b.circles) == 2
    new = b.arcs[2]
    assert new.circle == lens.circles[0]
    assert new.sweep > 0
    assert new.sweep - lens.arcs[0].sweep == pytest.approx(2 * math.pi)  # together the whole circle
    assert end_junctions(b, 2) == (0, 1)
    assert b.junction_arcs == ((0, 1, 2), (0, 1, 2))
    assert b.arc_segments[2] == ()
    assert b.params["edits"] == ("add_arc(circle=0, j0=0, j1=1, sweep_sign=1)",)
    assert_unchanged(lens, snap)
    # The same arc again, either way round, is refused.
    with pytest.raises(InvalidParameterError, match=r"^arc 0 already runs on circle 0 between junctions 0 and 1"):
        edits.add_arc(lens, 0, 0, 1, sweep_sign=-1)
    with pytest.raises(InvalidParameterError, match=r"^arc 0 already runs on circle 0 between junctions 1 and 0"):
        edits.add_arc(lens, 0, 1, 0, sweep_sign=+1)


def test_add_arc_by_circle_object(fish: Abstraction) -> None:
    gill = next(i for i in range(len(fish.arcs)) if all(j in free_ends(fish) for j in end_junctions(fish, i)))
    start, end = end_junctions(fish, gill)
    sign = 1 if fish.arcs[gill].sweep < 0 else -1
    b = edits.add_arc(fish, fish.arcs[gill].circle, start, end, sweep_sign=sign)
    check_invariants(b)
    assert len(b.circles) == len(fish.circles)
    assert abs(b.arcs[-1].sweep) + abs(fish.arcs[gill].sweep) == pytest.approx(2 * math.pi)
    assert start not in free_ends(b) and end not in free_ends(b)


def test_add_arc_errors(lens: Abstraction, fish: Abstraction) -> None:
    with pytest.raises(InvalidParameterError, match=r"^circle index 2 is out of range: the abstraction has 2 circles"):
        edits.add_arc(lens, 2, 0, 1)
    with pytest.raises(InvalidParameterError, match=r"^junction index 5 is out of range: the abstraction has 2 "):
        edits.add_arc(lens, 0, 0, 5)
    with pytest.raises(InvalidParameterError, match=r"^add_arc needs two different junctions, got junction 1 twice$"):
        edits.add_arc(lens, 0, 1, 1)
    with pytest.raises(InvalidParameterError, match=r"^sweep_sign must be \+1 or -1, got 2$"):
        edits.add_arc(lens, 0, 0, 1, sweep_sign=2)
    with pytest.raises(InvalidParameterError, match=r"^circle Circle\(.*\) is not a circle of the abstraction$"):
        edits.add_arc(lens, golden(0.0, 0.0, 3), 0, 1)
    # Junctions 0 and 2 of the fish are not both on circle 0.
    off = next(j for j in range(len(fish.junctions)) if abs(float(fish.circles[0].distance(fish.junctions[j]))) > 1)
    with pytest.raises(
        InvalidParameterError, match=rf"^junction {off} at \(.*\) is .* px off circle 0 .*more than 0.001 px: add_arc"
    ):
        edits.add_arc(fish, 0, *sorted({end_junctions(fish, 0)[0], off}))


def test_add_arc_snaps_near_junction(lens: Abstraction) -> None:
    """A junction within 1e-3 px of the circle is put on it (to 1e-6) by the re-fit."""
    moved = lens.junctions.copy()
    moved[0, 1] -= 4e-4  # off both circles by ~4e-4 px
    near = Abstraction(
        level=0,
        arcs=lens.arcs,
        arc_segments=lens.arc_segments,
        junctions=moved,
        junction_arcs=lens.junction_arcs,
        similarity=0.0,
        bias=lens.bias,
        tolerance=5.0,
        width=lens.width,
        height=lens.height,
    )
    b = edits.add_arc(near, 1, 0, 1, sweep_sign=-1)
    check_invariants(b)
    assert np.abs(b.junctions - moved).max() < 1e-2


# --------------------------------------------------------------------------- connect
def test_connect_gill(fish: Abstraction) -> None:
    snap = snapshot(fish)
    j0, j1 = free_ends(fish)[:2]
    p0, p1 = fish.junctions[j0], fish.junctions[j1]
    d = math.dist(p0, p1)
    b = edits.connect(fish, j0, j1)
    check_invariants(b)
    new = b.arcs[-1]
    c = new.circle
    # Golden, the smallest rung through both points, and the short arc between them.
    assert c.r == pytest.approx(PHI ** (c.k + fish.bias), rel=1e-12)
    assert 2 * c.r >= d > 2 * c.r / PHI
    assert abs(float(c.distance(p0))) < 1e-9 and abs(float(c.distance(p1))) < 1e-9
    np.testing.assert_allclose(new.start, p0, atol=1e-9)
    np.testing.assert_allclose(new.end, p1, atol=1e-9)
    assert abs(new.sweep) <= math.pi
    assert end_junctions(b, len(b.arcs) - 1) == (j0, j1)
    assert j0 not in free_ends(b) and j1 not in free_ends(b)
    assert b.params["edits"] == (f"connect(j0={j0}, j1={j1}, k={c.k}, side=1)",)
    np.testing.assert_array_equal(b.junctions, fish.junctions)
    assert_unchanged(fish, snap)


def test_connect_side_and_rung(lens: Abstraction) -> None:
    open_ = edits.delete_arc(lens, 1)  # arc 0 alone: junctions 0 and 1 are free ends
    p0, p1 = open_.junctions
    arcs = {}
    for side in (1, -1):
        b = edits.connect(open_, 0, 1, k=10, side=side)
        check_invariants(b)
        arcs[side] = b.arcs[-1]
        c = arcs[side].circle
        assert c.k == 10 and c.r == pytest.approx(PHI ** (10 + BIAS))
        u = (p1 - p0) / math.dist(p0, p1)
        normal = np.array([-u[1], u[0]])
        assert side * float((c.center - (p0 + p1) / 2) @ normal) > 0  # the centre on the chosen side
        mid = c.point_at(arcs[side].theta0 + arcs[side].sweep / 2)
        assert side * float((mid - (p0 + p1) / 2) @ normal) < 0  # the arc bulges the other way
    assert arcs[1].circle.center[0] < arcs[-1].circle.center[0]  # n points left for p0 above p1


def test_connect_errors(fish: Abstraction, lens: Abstraction) -> None:
    j0, j1 = free_ends(fish)[:2]
    busy = next(j for j, listed in enumerate(fish.junction_arcs) if len(listed) == 2)
    with pytest.raises(InvalidParameterError, match=rf"^junction {busy} is not a free end: 2 arcs meet there"):
        edits.connect(fish, j0, busy)
    with pytest.raises(
        InvalidParameterError, match=rf"^connect needs two different junctions, got junction {j0} twice"
    ):
        edits.connect(fish, j0, j0)
    d = math.dist(fish.junctions[j0], fish.junctions[j1])
    k_min = edits.connect(fish, j0, j1).arcs[-1].circle.k
    with pytest.raises(
        InvalidParameterError,
        match=rf"^rung k={k_min - 1} \(r=.* px\) is too small to connect junctions {j0} and {j1}: they are "
        rf"{d:.6g} px apart, more than its diameter .* px; use k >= {k_min}$",
    ):
        edits.connect(fish, j0, j1, k=k_min - 1)
    with pytest.raises(InvalidParameterError, match=r"^side must be \+1 or -1, got 0$"):
        edits.connect(fish, j0, j1, side=0)
    with pytest.raises(InvalidParameterError, match=r"^k must be an integer, got 2.5$"):
        edits.connect(fish, j0, j1, k=2.5)
    with pytest.raises(InvalidParameterError, match=r"^junction 0 is not a free end: 2 arcs meet there"):
        edits.connect(lens, 0, 1)


def test_connect_respects_exponents(lens: Abstraction) -> None:
    """With a restricted ladder (Sec. 7, Fig. 15) the default rung is the smallest allowed one that fits."""
    open_ = edits.delete_arc(lens, 1)
    d = math.dist(*open_.junctions)
    b = edits.connect(dataclasses.replace(open_, ladder=GoldenLadder(BIAS, (3, 12))), 0, 1)
    check_invariants(b)
    assert b.arcs[-1].circle.k == 12
    k_min = edits.connect(open_, 0, 1).arcs[-1].circle.k
    with pytest.raises(
        InvalidParameterError,
        match=rf"^no rung among the ladder's exponents \[2, 3\] can connect junctions 0 and 1 \({d:.6g} px apart\): "
        rf"it needs k >= {k_min}$",
    ):
        edits.connect(dataclasses.replace(open_, ladder=GoldenLadder(BIAS, (3, 2))), 0, 1)


# --------------------------------------------------------------------------- move_circle
def test_move_circle_fish(fish: Abstraction) -> None:
    snap = snapshot(fish)
    ci = next(i for i, c in enumerate(fish.circles) if c == fish.arcs[3].circle)
    old = fish.circles[ci]
    target = (old.cx + 6.0, old.cy - 4.0)
    b = edits.move_circle(fish, ci, target)
    check_invariants(b)
    moved = b.circles[ci]
    assert (moved.cx, moved.cy) == target
    assert (moved.r, moved.k) == (old.r, old.k)
    # Its junctions moved with it, and the neighbours still meet it there.
    own = [j for j, listed in enumerate(fish.junction_arcs) if any(fish.arcs[i].circle == old for i in listed)]
    assert own
    for j in own:
        assert abs(float(moved.distance(b.junctions[j]))) <= TOL
        assert math.dist(b.junctions[j], fish.junctions[j]) > 1.0
        for i in b.junction_arcs[j]:
            assert abs(float(b.arcs[i].circle.distance(b.junctions[j]))) <= TOL
    # Same arcs, same senses, radii and ladder exponents; far circles unchanged.
    assert len(b.arcs) == len(fish.arcs)
    for x, y in zip(b.arcs, fish.arcs, strict=True):
        assert math.copysign(1, x.sweep) == math.copysign(1, y.sweep)
        assert (x.circle.r, x.circle.k) == (y.circle.r, y.circle.k)
        assert abs(x.sweep - y.sweep) < 1.0
    unchanged = sum(x is y for x, y in zip(b.arcs, fish.arcs, strict=True))
    assert unchanged >= len(fish.arcs) - 5
    assert b.params["edits"] == (f"move_circle({ci}, ({target[0]!r}, {target[1]!r}))",)
    assert_unchanged(fish, snap)


def test_move_circle_large_moves(fish: Abstraction) -> None:
    """Moves of 20-40 px of every circle of the body keep the logo connected."""
    for ci, c in enumerate(fish.circles):
        for dx, dy in ((20.0, 10.0), (-30.0, 0.0)):
            b = edits.move_circle(fish, ci, (c.cx + dx, c.cy + dy))
            check_invariants(b)
            assert b.circles[ci].center == pytest.approx(c.center + np.array([dx, dy]))


def test_move_circle_free_arc_is_rigid(fish: Abstraction) -> None:
    """The gill's circle has only free ends: the arc and its ends translate with it."""
    gill = next(i for i in range(len(fish.arcs)) if all(j in free_ends(fish) for j in end_junctions(fish, i)))
    ci = fish.circles.index(fish.arcs[gill].circle)
    c = fish.circles[ci]
    b = edits.move_circle(fish, ci, (c.cx - 15.0, c.cy + 5.0))
    check_invariants(b)
    assert b.arcs[gill].theta0 == pytest.approx(fish.arcs[gill].theta0, abs=1e-9)
    assert b.arcs[gill].sweep == pytest.approx(fish.arcs[gill].sweep, abs=1e-9)
    for j in end_junctions(fish, gill):
        np.testing.assert_allclose(b.junctions[j], fish.junctions[j] + (-15.0, 5.0), atol=1e-6)
    assert sum(x is not y for x, y in zip(b.arcs, fish.arcs, strict=True)) == 1


def test_move_circle_lens(lens: Abstraction) -> None:
    b = edits.move_circle(lens, 1, (165.0, 103.0))
    check_invariants(b)
    assert b.circles[1].center.tolist() == [165.0, 103.0]
    # Circle 0 is the neighbour: it follows a little, the junctions are where both meet.
    assert math.dist(b.circles[0].center, lens.circles[0].center) < 5.0
    for j in (0, 1):
        for c in b.circles:
            assert abs(float(c.distance(b.junctions[j]))) <= TOL
    assert end_junctions(b, 0) == (0, 1) and end_junctions(b, 1) == (1, 0)


def test_move_circle_keeps_passing_junction(passing: Abstraction) -> None:
    """Arc 0 passes through junction 1, where arc 1 ends: moving circle 1 moves circle 0 too."""
    b = edits.move_circle(passing, 1, (passing.circles[1].cx - 2.0, passing.circles[1].cy + 3.0))
    check_invariants(b)
    arc0 = b.arcs[0]
    assert math.dist(arc0.start, b.junctions[1]) > 1 and math.dist(arc0.end, b.junctions[1]) > 1
    assert arc0.contains_angle(float(arc0.circle.angle_of(b.junctions[1])))
    assert end_junctions(b, 0) == (0, 2)
    assert b.circles[0] != passing.circles[0]


def test_move_circle_errors(fish: Abstraction) -> None:
    n = len(fish.circles)
    with pytest.raises(InvalidParameterError, match=rf"^circle index {n} is out of range: .* \(valid: 0..{n - 1}\)$"):
        edits.move_circle(fish, n, (0.0, 0.0))
    with pytest.raises(InvalidParameterError, match=r"^circle index -1 is out of range"):
        edits.move_circle(fish, -1, (0.0, 0.0))
    with pytest.raises(InvalidParameterError, match=r"^circle index must be an integer, got 1.0$"):
        edits.move_circle(fish, 1.0, (0.0, 0.0))
    with pytest.raises(InvalidParameterError, match=r"^new_center must be a finite point \(x, y\), got \(1.0, nan\)$"):
        edits.move_circle(fish, 0, (1.0, math.nan))
    with pytest.raises(InvalidParameterError, match=r"^new_center must be a finite point \(x, y\), got \[1, 2, 3\]$"):
        edits.move_circle(fish, 0, [1, 2, 3])
    with pytest.raises(InvalidParameterError, match=r"^abstraction must be an Abstraction, got dict$"):
        edits.move_circle({}, 0, (0.0, 0.0))


def test_move_circle_unreachable(fish: Abstraction) -> None:
    """Far away, the neighbours (held by their other junctions) cannot reach the circle."""
    body = next(i for i, c in enumerate(fish.circles) if c == fish.arcs[0].circle)
    c = fish.circles[body]
    with pytest.raises(FitError, match=rf"^move_circle\({body}, .*\) cannot keep the junctions connected"):
        edits.move_circle(fish, body, (c.cx + 2000.0, c.cy))


# --------------------------------------------------------------------------- change_rung
@pytest.mark.parametrize("delta", [1, -1])
def test_change_rung_fish(fish: Abstraction, delta: int) -> None:
    snap = snapshot(fish)
    for ci in range(len(fish.circles)):
        old = fish.circles[ci]
        b = edits.change_rung(fish, ci, delta)
        check_invariants(b)
        new = b.circles[ci]
        assert new.k == old.k + delta
        assert new.r == pytest.approx(old.r * PHI**delta, rel=1e-12)
        assert b.params["edits"] == (f"change_rung({ci}, delta={delta})",)
        assert [c.k for i, c in enumerate(b.circles) if i != ci] == [c.k for i, c in enumerate(fish.circles) if i != ci]
    assert_unchanged(fish, snap)


def test_change_rung_lens(lens: Abstraction) -> None:
    b = edits.change_rung(lens, 0, +1)
    check_invariants(b)
    assert b.circles[0].k == 9 and b.circles[0].r == pytest.approx(PHI ** (9 + BIAS))
    for j in (0, 1):
        for c in b.circles:
            assert abs(float(c.distance(b.junctions[j]))) <= TOL
    back = edits.change_rung(b, 0, -1)
    check_invariants(back)
    assert back.circles[0].r == pytest.approx(lens.circles[0].r, rel=1e-12)


def test_change_rung_errors(lens: Abstraction) -> None:
    for delta in (0, 0.5, True):
        with pytest.raises(InvalidParameterError, match=rf"^delta must be a nonzero integer, got {delta!r}$"):
            edits.change_rung(lens, 0, delta)
    fields = dict(arc_segments=((),), junctions=np.zeros((0, 2)), junction_arcs=(), similarity=0.0, tolerance=5.0)
    line = Abstraction(0, (line_arc((10.0, 50.0), (90.0, 50.0)),), bias=BIAS, width=100, height=100, **fields)
    with pytest.raises(InvalidParameterError, match=r"^circle 0 has no ladder exponent k: change_rung needs a golden"):
        edits.change_rung(line, 0, 1)
    fib_arc = Arc(Circle(50.0, 50.0, 3.0 * 5, 5), 0.0, 1.0)
    fib = Abstraction(0, (fib_arc,), bias=0.0, width=100, height=100, ladder=FibonacciLadder(3.0), **fields)
    with pytest.raises(InvalidParameterError, match=r"^change_rung supports only the golden ratio ladder"):
        edits.change_rung(fib, 0, 1)


def test_delete_arc_errors(fish: Abstraction) -> None:
    n = len(fish.arcs)
    with pytest.raises(InvalidParameterError, match=rf"^arc index {n} is out of range: the abstraction has {n} arcs"):
        edits.delete_arc(fish, n)
    for bad in (1.5, True, "2", None):
        with pytest.raises(InvalidParameterError, match=rf"^arc index must be an integer, got {bad!r}$"):
            edits.delete_arc(fish, bad)
    assert len(edits.delete_arc(fish, np.int64(2)).arcs) == n - 1


def test_full_circle_stays_full() -> None:
    """A full circle (an eye) with a stroke ending on it: moved or re-runged, it stays whole."""
    eye = golden(100.0, 100.0, 6)
    p = eye.point_at(0.0)
    stroke = golden(0.0, 0.0, 7)
    stroke = Circle(float(p[0]) + stroke.r, float(p[1]), stroke.r, stroke.k)
    arc1 = Arc(stroke, math.pi, 0.8)
    a = Abstraction(
        level=0,
        arcs=(Arc(eye, 0.0, 2 * math.pi), arc1),
        arc_segments=((0,), (1,)),
        junctions=np.array([p, arc1.end]),
        junction_arcs=((0, 1), (1,)),
        similarity=0.0,
        bias=BIAS,
        tolerance=5.0,
        width=200,
        height=200,
    )
    check_invariants(a)
    for b in (edits.change_rung(a, 0, 1), edits.move_circle(a, 0, (96.0, 104.0)), edits.change_rung(a, 1, -1)):
        check_invariants(b)
        assert b.arcs[0].sweep == 2 * math.pi
        np.testing.assert_allclose(b.arcs[0].start, b.junctions[0], atol=TOL)
        assert end_junctions(b, 1) == (0, 1)


@pytest.mark.parametrize("delta", [60, -60, 10**6])
def test_change_rung_keeps_the_radius_where_the_contract_reads_it_back(lens: Abstraction, delta: int) -> None:
    # change_rung(a, c, 60) gave r = 8.7e14 px: write_json wrote a file read_json refused.
    with pytest.raises(InvalidParameterError, match=r"^change_rung: circle 0 moved -?\d+ rungs would have r = phi\*\*"):
        edits.change_rung(lens, 0, delta)
    b = edits.change_rung(lens, 0, 20)  # 4.4e4 times larger: still a ladder radius
    validate_document(to_document(b))
