"""Shared test helpers: the data folder, synthetic images whose segment graphs are known, hand-built abstractions.

Imported by the tests as ``from helpers import ...`` (pytest puts ``tests/`` on the path); the
fixtures are in ``conftest.py``.
"""

from __future__ import annotations

import ast
import math
import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
from scipy import ndimage

from img2logo.constants import PHI
from img2logo.geometry.abstraction import Abstraction
from img2logo.geometry.primitives import TAU, Arc, Circle
from img2logo.segment_graph import SegmentGraph

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data"


def modules_loaded(code: str, *packages: str, cwd: Path = ROOT) -> list[str]:
    """The modules of ``packages`` (each with what is under it) loaded once ``code`` has run in a new interpreter.

    What an import or a run costs at start-up; sorted. ``code`` may print: the answer is the last line.
    """
    probe = (
        f"{code}\nimport sys\n"
        f"print(sorted(m for m in sys.modules if any(m == p or m.startswith(p + '.') for p in {packages!r})))"
    )
    out = subprocess.run([sys.executable, "-c", probe], cwd=cwd, capture_output=True, text=True, check=True)
    return ast.literal_eval(out.stdout.strip().splitlines()[-1])


def blank(size: int = 200) -> np.ndarray:
    """A white RGB uint8 canvas of size x size px."""
    return np.full((size, size, 3), 255, np.uint8)


def drawing(shape: str, thickness: int = 3, size: int = 200) -> np.ndarray:
    """A black-on-white line drawing of a known shape, RGB uint8."""
    im = blank(size)
    black = (0, 0, 0)
    if shape == "circle":
        cv2.circle(im, (100, 100), 60, black, thickness)
    elif shape == "Y":
        for end in ((100, 180), (40, 40), (160, 40)):
            cv2.line(im, (100, 100), end, black, thickness)
    elif shape == "X":
        cv2.line(im, (30, 30), (170, 170), black, thickness)
        cv2.line(im, (30, 170), (170, 30), black, thickness)
    elif shape == "two":
        cv2.line(im, (30, 30), (90, 170), black, thickness)
        cv2.line(im, (120, 30), (170, 170), black, thickness)
    elif shape == "square":
        cv2.rectangle(im, (40, 40), (160, 160), black, thickness)
    elif shape == "spiral":
        t = np.linspace(0.0, 4.0 * np.pi, 400)
        r = (10.0 + 12.0 * t) / 1.5
        pts = np.column_stack([100 + r * np.cos(t), 100 + r * np.sin(t)]).round().astype(np.int32)
        cv2.polylines(im, [pts], False, black, thickness)
    else:
        raise ValueError(shape)
    return im


def two_discs(size: int = 200) -> np.ndarray:
    """Clip art: a red and a blue disc overlapping on white, RGB uint8."""
    im = blank(size)
    cv2.circle(im, (80, 100), 45, (220, 40, 40), -1, lineType=cv2.LINE_AA)
    cv2.circle(im, (130, 100), 45, (40, 90, 220), -1, lineType=cv2.LINE_AA)
    return im


def small_graph():
    """A hand-built segment graph: 5 nodes of valence 1, 3, 2, 1, 1; 4 segments; 20 x 14 px."""
    from img2logo.segment_graph import SegmentGraph

    nodes = np.array([[2.5, 2.5], [10.5, 2.5], [10.5, 10.5], [2.5, 10.5], [17.5, 9.5]])
    segments = (
        np.array([[x + 0.5, 2.5] for x in range(2, 11)]),
        np.array([[10.5, y + 0.5] for y in range(2, 11)]),
        np.array([[10.5 + t, 2.5 + t] for t in range(8)]),
        np.array([[x + 0.5, 10.5] for x in range(10, 1, -1)]),
    )
    ends = np.array([[0, 1], [1, 2], [1, 4], [2, 3]])
    return SegmentGraph(segments=segments, junctions=nodes, ends=ends, width=20, height=14)


# --- abstractions built by hand: golden circles, arcs, junctions --------------------------

BIAS = 0.3
WIDTH, HEIGHT = 200, 160


def frechet_table(p: np.ndarray, q: np.ndarray) -> float:
    """The discrete Fréchet distance of two polylines, (N, 2) and (M, 2), px: the textbook O(N M) table.

    The recurrence of [Eiter & Mannila 1994] in plain Python, on squared distances as the compiled
    kernel computes them (the same bits), the square root taken at the end.
    """
    n, m = len(p), len(q)
    c = np.empty((n, m))
    for i in range(n):
        for j in range(m):
            dx, dy = p[i, 0] - q[j, 0], p[i, 1] - q[j, 1]
            d2 = dx * dx + dy * dy
            if i == 0 and j == 0:
                c[i, j] = d2
            elif i == 0:
                c[i, j] = max(c[0, j - 1], d2)
            elif j == 0:
                c[i, j] = max(c[i - 1, 0], d2)
            else:
                c[i, j] = max(min(c[i - 1, j], c[i - 1, j - 1], c[i, j - 1]), d2)
    return math.sqrt(c[-1, -1])


def golden(cx: float, cy: float, k: int, bias: float = BIAS) -> Circle:
    return Circle(cx, cy, PHI ** (k + bias), k)


def abstraction_of(arcs, junctions=(), junction_arcs=(), width=250, height=200) -> Abstraction:
    """An abstraction of ``arcs`` (level 0, bias ``BIAS``) on a ``width`` x ``height`` px image."""
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


A, B = golden(90.0, 100.0, 8), golden(150.0, 100.0, 7)  # r = 54.27 and 33.54, d = 60: they cross


def two_circles() -> Abstraction:
    return abstraction_of([full(A), full(B, 1.0, -1.0)])


def four_arcs() -> Abstraction:
    """The same two circles as four arcs that end exactly on the two junctions where they cross."""
    p, q = crossings(A, B)
    arcs = []
    for c in (A, B):
        tp, tq = float(c.angle_of(p)), float(c.angle_of(q))
        s = (tq - tp) % TAU
        arcs += [Arc(c, tp, s), Arc(c, tq, TAU - s)]
    return abstraction_of(arcs, [p, q], [(0, 1, 2, 3), (0, 1, 2, 3)])


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


def palette_fills(a: Abstraction) -> tuple:
    """Fills of ``a``'s faces from a three-colour palette."""
    from img2logo.design import fills

    return fills.fill_palette(a, ["#e63946", "#457b9d", "#f4a261"])


def arc_points(center, radius, theta0, sweep, n):
    """n points of the circle (center, radius) from angle theta0 over sweep (radians)."""
    t = theta0 + sweep * np.linspace(0.0, 1.0, n)
    return np.asarray(center, dtype=float) + radius * np.column_stack([np.cos(t), np.sin(t)])


def arc_through(q0, q1, radius, side, n):
    """Centre and n points of the minor arc of radius ``radius`` from q0 to q1."""
    q0, q1 = np.asarray(q0, dtype=float), np.asarray(q1, dtype=float)
    chord = np.linalg.norm(q1 - q0)
    t = (q1 - q0) / chord
    center = (q0 + q1) / 2 + side * math.sqrt(radius**2 - chord**2 / 4) * np.array([-t[1], t[0]])
    a0, a1 = (math.atan2(*(q - center)[::-1]) for q in (q0, q1))
    sweep = (a1 - a0 + math.pi) % (2 * math.pi) - math.pi
    return center, arc_points(center, radius, a0, sweep, n)


def golden_radius(k: int) -> float:
    """The golden radius phi^(k + BIAS), px."""
    return PHI ** (k + BIAS)


def sampled_arc(center, radius, t0, t1, step=1.0, noise=0.0, rng=None):
    """Points of the circle (center, radius) from angle t0 to t1, about ``step`` px apart; inner ones noisy."""
    n = max(3, int(abs(t1 - t0) * radius / step) + 1)
    t = np.linspace(t0, t1, n)
    pts = np.column_stack([center[0] + radius * np.cos(t), center[1] + radius * np.sin(t)])
    if noise:
        pts[1:-1] += rng.normal(0.0, noise, (n - 2, 2))
    return pts


def golden_chain(noise: float = 0.0, seed: int = 0) -> tuple[SegmentGraph, list[tuple[np.ndarray, float]]]:
    """Three golden arcs (k = 8, 9, 10) joined end to end at two junctions: an S-like stroke."""
    rng = np.random.default_rng(seed)
    r1, r2, r3 = golden_radius(8), golden_radius(9), golden_radius(10)
    c1 = np.array([150.0, 150.0])
    a1 = sampled_arc(c1, r1, np.pi, np.pi / 2, noise=noise, rng=rng)  # ends at the bottom of circle 1
    j1 = a1[-1]
    # Circle 2 touches circle 1 at j1 from outside, continuing the stroke.
    c2 = j1 + np.array([0.0, r2])
    a2 = sampled_arc(c2, r2, -np.pi / 2, -np.pi / 2 + 1.2, noise=noise, rng=rng)
    j2 = a2[-1]
    u = (j2 - c2) / r2
    c3 = j2 - u * r3  # circle 3 is internally tangent at j2: the same side, larger
    t3 = np.arctan2(u[1], u[0])
    a3 = sampled_arc(c3, r3, t3, t3 + 0.8, noise=noise, rng=rng)
    graph = SegmentGraph(
        segments=(a1, a2, a3),
        junctions=np.array([a1[0], j1, j2, a3[-1]]),
        ends=np.array([[0, 1], [1, 2], [2, 3]]),
        width=600,
        height=600,
    )
    return graph, [(c1, r1), (c2, r2), (c3, r3)]


def line_and_a_stroke(x: float, tip: float) -> SegmentGraph:
    """A line in two segments (nodes 0-1-2 along y = 100.5, node 1 at x = 150.5) and a stroke up to it at x = ``x``.

    The stroke ends ``tip`` px short of the line (past it when negative); 300 x 300 px.
    """
    left = np.linspace([50.5, 100.5], [150.5, 100.5], 101)
    right = np.linspace([150.5, 100.5], [250.5, 100.5], 101)
    stroke = np.linspace([x, 130.5], [x, 100.5 + tip], 31)
    junctions = np.array([left[0], left[-1], right[-1], stroke[0], stroke[-1]])
    return SegmentGraph((left, right, stroke), junctions, np.array([[0, 1], [1, 2], [3, 4]]), 300, 300)


def hand_built_state(graph: SegmentGraph, state_class: type | None = None, **settings):
    """A :class:`~img2logo.fit.fit_state.FitState` of ``graph`` on ``BIAS``'s ladder, a group per segment, unfitted.

    ``state_class`` is FitState or a subclass of it (default FitState); ``settings`` are fields
    of :class:`~img2logo.options.Options` (``tolerance=0.5``, ...).
    """
    from img2logo.fit.fit_state import FitState
    from img2logo.fit.simplification import Group
    from img2logo.geometry.golden_ladder import make_ladder
    from img2logo.options import Options

    state = (state_class or FitState)(graph, Options.from_keywords(settings), make_ladder("phi", None, bias=BIAS))
    for i, seg in enumerate(graph.segments):
        state.add_group(Group((i,), (int(graph.ends[i, 0]), int(graph.ends[i, 1])), seg, False))
    return state


def check_level(level: Abstraction, atol: float = 1e-6) -> None:
    """Every junction lies on the circle of each arc listed there; arcs pass through it."""
    for point, arcs in zip(level.junctions, level.junction_arcs, strict=True):
        for i in arcs:
            arc = level.arcs[i]
            assert abs(arc.circle.distance(point[None])[0]) <= atol
            assert arc.contains_angle(arc.circle.angle_of(point[None]), tol=1e-6)[0]
    for arc in level.arcs:
        assert abs(arc.circle.r - PHI ** (arc.circle.k + level.bias)) <= 1e-9 * arc.circle.r


def textured_photo(shapes, size=(240, 320), seed=0):
    """Objects on a noise-texture background: an RGB float image and each object's true mask.

    ``shapes`` are (cx, cy, rx, ry, rgb) ellipses; each is shaded softly (lighter
    towards its top-left) and gets a darker inner stripe; the background is a
    blurred random texture of browns and greens with some fine noise.
    """
    rng = np.random.default_rng(seed)
    h, w = size
    tex = ndimage.gaussian_filter(rng.random((h, w, 3)), (3, 3, 0))
    tex = (tex - tex.min()) / np.ptp(tex)
    img = 0.25 + 0.35 * tex * np.array([0.9, 0.8, 0.5])
    yy, xx = np.mgrid[0:h, 0:w]
    masks = []
    for cx, cy, rx, ry, rgb in shapes:
        inside = ((xx - cx) / rx) ** 2 + ((yy - cy) / ry) ** 2 <= 1.0
        shade = 1.0 + 0.15 * ((cx - xx) / rx + (cy - yy) / ry) / 2
        obj = np.clip(np.array(rgb)[None, None, :] * shade[..., None], 0, 1)
        stripe = inside & (np.abs(yy - cy) < ry * 0.12)
        obj[stripe] *= 0.6
        img[inside] = obj[inside]
        masks.append(inside)
    img = ndimage.gaussian_filter(img, (0.8, 0.8, 0)) + 0.01 * rng.standard_normal((h, w, 3))
    return np.clip(img, 0, 1), masks


def random_masks(n: int, seed: int) -> list[np.ndarray]:
    """``n`` random bool masks up to 47 x 47 px, noise or blobs and strokes, from the generator ``seed``."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        h, w = (int(v) for v in rng.integers(1, 48, 2))
        mask = rng.random((h, w)) < rng.uniform(0.05, 0.95)
        if rng.random() < 0.5:  # blobs and strokes, not only noise
            mask = cv2.dilate(mask.astype(np.uint8), np.ones((2, 2), np.uint8)) > 0
        out.append(mask)
    return out
