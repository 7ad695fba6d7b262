"""Property tests (hypothesis) of the library's exact pieces: the free circle fit, the discrete
Fréchet distance, the SVG arc path data and the JSON document's round trip.

Each property is a statement that must hold for every input of the strategy, checked against an
independent oracle (a textbook dynamic program, the SVG 1.1 arc parametrisation, the circle the
points were drawn from), not against the code's own output.
"""

from __future__ import annotations

import math

import numpy as np
from helpers import abstraction_of, frechet_table, golden, svg_arc_center
from hypothesis import HealthCheck, given, settings, strategies as st

from img2logo.export.contract import from_document, to_document
from img2logo.fit.arc_extraction import frechet_distance
from img2logo.geometry.circle_fitting import fit_circle
from img2logo.geometry.primitives import TAU, Arc
from img2logo.geometry.svg_path import arc_path

# Derandomized (the same examples on every run and machine), bounded, and without a deadline:
# part of make test, never flaky on a slow machine.
PROPERTY = settings(
    max_examples=60, deadline=None, derandomize=True, database=None, suppress_health_check=[HealthCheck.too_slow]
)

coordinate = st.floats(-200.0, 200.0, allow_nan=False, allow_infinity=False)


polyline = st.lists(st.tuples(coordinate, coordinate), min_size=1, max_size=12).map(np.array)


# --------------------------------------------------------------------------- Fréchet distance
@PROPERTY
@given(polyline, polyline)
def test_frechet_distance_is_the_textbook_recurrence(p, q):
    assert math.isclose(frechet_distance(p, q), frechet_table(p, q), rel_tol=1e-12, abs_tol=1e-9)


@PROPERTY
@given(polyline, polyline)
def test_frechet_distance_is_symmetric_and_bounded_by_the_vertex_distances(p, q):
    d = frechet_distance(p, q)
    assert math.isclose(d, frechet_distance(q, p), rel_tol=1e-12, abs_tol=1e-9)
    # The end points are always coupled, and no coupling exceeds the farthest pair of vertices.
    ends = max(math.dist(p[0], q[0]), math.dist(p[-1], q[-1]))
    farthest = max(math.dist(a, b) for a in p for b in q)
    assert ends - 1e-9 <= d <= farthest + 1e-9
    assert frechet_distance(p, p) == 0.0


# --------------------------------------------------------------------------- the free circle fit
@PROPERTY
@given(
    cx=coordinate,
    cy=coordinate,
    radius=st.floats(5.0, 300.0),
    theta0=st.floats(0.0, TAU),
    span=st.floats(math.pi / 3, TAU),
    seed=st.integers(0, 2**32 - 1),
)
def test_fit_circle_recovers_the_circle_of_noisy_points(cx, cy, radius, theta0, span, seed):
    # 80 points over at least 60 degrees of arc, with 0.1 px of Gaussian noise: the geometric fit
    # recovers the centre and radius to a small multiple of the noise, and its rms is the noise's.
    rng = np.random.default_rng(seed)
    t = np.linspace(theta0, theta0 + span, 80)
    pts = np.column_stack([cx + radius * np.cos(t), cy + radius * np.sin(t)]) + rng.normal(0.0, 0.1, (80, 2))
    fit = fit_circle(pts)
    # The error of an arc fit grows as the arc gets shorter relative to its radius (the sagitta):
    # bounded for a 60 degree arc by about 10x the noise in the radius.
    assert abs(fit.radius - radius) <= 1.5
    assert math.dist(fit.center, (cx, cy)) <= 1.5
    assert fit.rms <= 0.2
    assert not fit.capped


@PROPERTY
@given(cx=coordinate, cy=coordinate, radius=st.floats(1.0, 500.0), theta0=st.floats(0.0, TAU))
def test_fit_circle_is_exact_on_exact_points(cx, cy, radius, theta0):
    t = theta0 + np.linspace(0.0, 1.5 * math.pi, 40)
    pts = np.column_stack([cx + radius * np.cos(t), cy + radius * np.sin(t)])
    fit = fit_circle(pts)
    assert math.isclose(fit.radius, radius, rel_tol=1e-6, abs_tol=1e-6)
    assert math.dist(fit.center, (cx, cy)) <= 1e-6 * max(1.0, radius)


# --------------------------------------------------------------------------- SVG arc path data
@PROPERTY
@given(
    cx=st.floats(20.0, 220.0),
    cy=st.floats(20.0, 180.0),
    k=st.integers(0, 9),
    theta0=st.floats(-TAU, TAU),
    sweep=st.floats(0.05, TAU).flatmap(lambda s: st.sampled_from([s, -s])),
)
def test_arc_path_draws_the_arc(cx, cy, k, theta0, sweep):
    # Every A command of the path data, read with the SVG 1.1 centre parametrisation (F.6.5),
    # lies on the arc's circle, and the commands together turn through the arc's sweep.
    arc = Arc(golden(cx, cy, k), theta0, sweep)
    tokens = arc_path(arc).replace(",", " ").split()
    assert tokens[0] == "M"
    x, y = float(tokens[1]), float(tokens[2])
    start = arc.circle.point_at(theta0)
    assert math.dist((x, y), start) <= 1e-3
    turned = 0.0
    rest = tokens[3:]
    while rest:
        assert rest[0] == "A"
        r, _, _, large, flag, x2, y2 = (float(v) for v in rest[1:8])
        ccx, ccy, extent = svg_arc_center(x, y, r, int(large), int(flag), x2, y2)
        assert math.isclose(r, arc.circle.r, rel_tol=1e-5, abs_tol=1e-3)
        assert math.dist((ccx, ccy), (cx, cy)) <= 1e-2
        turned += extent
        x, y, rest = x2, y2, rest[8:]
    assert math.isclose(turned, sweep, abs_tol=1e-3)
    assert math.dist((x, y), arc.circle.point_at(theta0 + sweep)) <= 1e-3


# --------------------------------------------------------------------------- the JSON document
arc_strategy = st.builds(
    lambda cx, cy, k, theta0, sweep: Arc(golden(cx, cy, k), theta0, sweep),
    st.floats(0.0, 250.0),
    st.floats(0.0, 200.0),
    st.integers(-2, 12),
    st.floats(-math.pi, math.pi),
    st.floats(0.01, TAU).flatmap(lambda s: st.sampled_from([s, -s])),
)


@PROPERTY
@given(st.lists(arc_strategy, min_size=1, max_size=8))
def test_json_document_round_trip_keeps_every_arc(arcs):
    a = abstraction_of(arcs)
    doc = to_document(a)
    b = from_document(doc)
    assert len(b.arcs) == len(a.arcs)
    for x, y in zip(a.arcs, b.arcs, strict=True):
        assert (x.circle.k, x.circle.cx, x.circle.cy) == (y.circle.k, y.circle.cx, y.circle.cy)
        assert math.isclose(x.circle.r, y.circle.r, rel_tol=1e-12)
        assert (x.theta0, x.sweep) == (y.theta0, y.sweep)
    assert to_document(b) == doc
