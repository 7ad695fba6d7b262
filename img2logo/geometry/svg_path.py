"""SVG path data of arcs: writing it with exact arc commands, and reading it back as polylines.

One number formatter (:func:`svg_number`) and one rule for arcs near a full turn
(``SVG_NEAR_FULL_SWEEP``: such an arc is written as two commands) serve every
path img2logo writes: the arcs of the SVG writer (:func:`arc_path`) and the
outlines of the faces that fills colour (:func:`loop_path`), so that a face's
outline and the arcs it follows are written with the same numbers.
:func:`sample_path` reads such path data back (fills in a document, PNG drawing).

Coordinates are input-image pixels, x right, y down; angles in radians from +x
towards +y, so a positive sweep is clockwise on screen, SVG's ``sweep-flag = 1``.
"""

from __future__ import annotations

import math
import re
from collections.abc import Sequence
from typing import Protocol

import numpy as np

from .._validation import check_positive
from ..constants import ARC_SAMPLE_STEP
from ..errors import InvalidParameterError
from .constants import LINE_RADIUS, SVG_DECIMALS, SVG_NEAR_FULL_SWEEP
from .primitives import TAU, Arc, Circle

__all__ = ["LoopPiece", "arc_path", "loop_path", "sample_path", "svg_number"]


class LoopPiece(Protocol):
    """What :func:`loop_path` reads of a piece of an arc along a loop (:class:`img2logo.design.arrangement.ArcPiece`).

    Its ``circle``, the angles ``t0``, ``t1`` where it starts and ends (radians,
    in the direction of the loop; ``sweep = t1 - t0``) and its end points, px.
    """

    @property
    def circle(self) -> Circle: ...
    @property
    def t0(self) -> float: ...
    @property
    def t1(self) -> float: ...
    @property
    def start(self) -> tuple[float, float]: ...
    @property
    def end(self) -> tuple[float, float]: ...
    @property
    def sweep(self) -> float: ...


def svg_number(v: float) -> str:
    """A coordinate for SVG: fixed point with ``SVG_DECIMALS`` decimals, trailing zeros dropped."""
    s = f"{float(v):.{SVG_DECIMALS}f}"
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _halves(sweep: float) -> int:
    """How many arc commands an arc of ``sweep`` radians is written as: 2 near a full turn, else 1."""
    return 2 if abs(sweep) > SVG_NEAR_FULL_SWEEP else 1


def _arc_to(r: float, sweep: float, halves: int, x: float, y: float) -> str:
    """One elliptical-arc command ``A r r 0 large-arc sweep-flag x y`` of a circle of radius ``r``.

    ``sweep`` is the whole arc's signed sweep, written as ``halves`` commands:
    ``large-arc = |sweep| / halves > pi``, ``sweep-flag = 1`` for a positive sweep.
    """
    large = 1 if abs(sweep) / halves > math.pi else 0
    flag = 1 if sweep > 0 else 0
    n = svg_number
    return f"A {n(r)} {n(r)} 0 {large} {flag} {n(x)} {n(y)}"


def arc_path(arc: Arc) -> str:
    """SVG path data of an arc with elliptical-arc commands (see :func:`img2logo.export.writers.write_svg`).

    ``M x0 y0 A r r 0 large-arc sweep-flag x1 y1``; an arc within 1e-3 rad of a
    full turn is two commands, and a full circle is two half arcs closed with ``Z``.
    """
    c = arc.circle
    sweep = min(TAU, max(-TAU, float(arc.sweep)))
    halves = _halves(sweep)
    angles = float(arc.theta0) + sweep * np.linspace(0.0, 1.0, halves + 1)
    points = c.point_at(angles)
    if arc.is_full_circle:
        points[-1] = points[0]
    parts = [f"M {svg_number(points[0, 0])} {svg_number(points[0, 1])}"]
    parts.extend(_arc_to(c.r, sweep, halves, x, y) for x, y in points[1:])
    if arc.is_full_circle:
        parts.append("Z")
    return " ".join(parts)


def _continues(a: LoopPiece, b: LoopPiece) -> bool:
    """True when ``b`` goes on along ``a``'s circle in the same sense: one arc command."""
    ca, cb = a.circle, b.circle
    if not (ca == cb or (abs(ca.cx - cb.cx) <= 1e-9 and abs(ca.cy - cb.cy) <= 1e-9 and abs(ca.r - cb.r) <= 1e-9)):
        return False
    if (a.sweep > 0) != (b.sweep > 0):
        return False
    gap = math.remainder(b.t0 - a.t1, TAU)
    return abs(gap) * ca.r <= 1e-6


def loop_path(loop: Sequence[LoopPiece]) -> str:
    """SVG subpath of one closed loop of pieces of arcs (see :attr:`img2logo.design.arrangement.Face.path`).

    ``M x y A ... Z``: consecutive pieces of one circle are joined into one
    command, split in two near a full turn as in :func:`arc_path`; every command
    ends on the loop's vertex; a piece of a straight line (the lines option) is
    an ``L`` command.
    """
    pieces = list(loop)
    n = len(pieces)
    joins = [_continues(pieces[k - 1], pieces[k]) for k in range(n)]  # joins[k]: piece k continues k-1
    if not all(joins):
        first = next(k for k in range(n) if not joins[k])
        pieces = pieces[first:] + pieces[:first]
        joins = joins[first:] + joins[:first]
    runs: list[list[LoopPiece]] = []
    for k, piece in enumerate(pieces):
        if k == 0 or not joins[k]:
            runs.append([piece])
        else:
            runs[-1].append(piece)
    parts = [f"M {svg_number(pieces[0].start[0])} {svg_number(pieces[0].start[1])}"]
    for run in runs:
        circle = run[0].circle
        sweep = sum(p.sweep for p in run)
        end = run[-1].end
        if circle.k is None and circle.r >= 0.5 * LINE_RADIUS:
            parts.append(f"L {svg_number(end[0])} {svg_number(end[1])}")  # a straight line (the lines option)
            continue
        halves = _halves(sweep)
        if halves == 2:
            mid = circle.point_at(run[0].t0 + 0.5 * sweep)
            parts.append(_arc_to(circle.r, sweep, halves, mid[0], mid[1]))
        parts.append(_arc_to(circle.r, sweep, halves, end[0], end[1]))
    parts.append("Z")
    return " ".join(parts)


_TOKEN = re.compile(r"[A-Za-z]|[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def check_path_data(path: object, name: str = "fill path") -> str:
    """``path`` if it is SVG path data: command letters, numbers, spaces and commas only, starting with ``M``.

    Anything else (a ``"`` that would end the ``d`` attribute, markup) is refused,
    so path data is always safe to write into an SVG attribute.

    Raises
    ------
    InvalidParameterError
        Naming the first character that is not path data.
    """
    if not isinstance(path, str) or not path.strip().upper().startswith("M"):
        raise InvalidParameterError(f"{name} must be SVG path data starting with 'M', got {path!r:.60}")
    bad = re.search(r"[^MmZzLlHhVvCcSsQqTtAa0-9eE.+\-,\s]", path)
    if bad is not None:
        raise InvalidParameterError(
            f"{name} is not SVG path data: {bad.group()!r} at character {bad.start()} of {path!r:.60}"
        )
    return path


def sample_path(path: str, step: float = ARC_SAMPLE_STEP) -> list[np.ndarray]:
    """The closed loops of SVG path data, sampled: for drawing fills and reading them back.

    Understands the absolute commands a fill path uses: ``M``, ``L``, ``H``,
    ``V``, ``A`` with a circular arc (``rx == ry``; the rotation is then
    irrelevant; a radius too small for its end points is scaled up, as SVG
    renderers do) and ``Z``. Every subpath is a closed loop (a fill closes it
    anyway).

    Parameters
    ----------
    path : str
        SVG path data, e.g. :attr:`img2logo.design.arrangement.Face.path`.
    step : float
        Spacing of the samples along arcs, px.

    Returns
    -------
    list of ndarray, shape (N, 2)
        One polyline per subpath, its first point not repeated at the end.

    Raises
    ------
    InvalidParameterError
        On a command other than those, a relative command, an elliptical arc,
        a missing number or text that is not path data.
    """
    if not isinstance(path, str):
        raise InvalidParameterError(f"path must be SVG path data (a string), got {type(path).__name__}")
    step = check_positive(step, "step")
    stripped = re.sub(r"[\s,]+", " ", path).strip()
    tokens = _TOKEN.findall(stripped)
    if "".join(tokens).replace(" ", "") != stripped.replace(" ", ""):
        raise InvalidParameterError(f"fill path is not SVG path data: {path!r:.80}")
    arity = {"M": 2, "L": 2, "H": 1, "V": 1, "A": 7, "Z": 0}
    rings: list[np.ndarray] = []
    current: list[np.ndarray] = []
    pos = np.zeros(2)
    i = 0
    command = ""

    def close() -> None:
        if current:
            ring = np.concatenate(current)
            if len(ring) > 1 and np.allclose(ring[0], ring[-1], atol=1e-9, rtol=0.0):
                ring = ring[:-1]
            if len(ring) >= 3:
                rings.append(ring)
        current.clear()

    while i < len(tokens):
        tok = tokens[i]
        if tok.isalpha():
            command = tok
            i += 1
            if command not in arity:
                hint = " (relative commands are not supported)" if command.upper() in arity else ""
                raise InvalidParameterError(
                    f"fill path: unsupported command {command!r}{hint}: only absolute M, L, H, V, A (circular) and Z"
                )
            if command == "Z":
                close()
                continue
        elif not command or command == "Z":
            raise InvalidParameterError(f"fill path: number {tok!r} without a command: {path!r:.80}")
        k = arity[command]
        args = tokens[i : i + k]
        if len(args) < k or any(a.isalpha() for a in args):
            raise InvalidParameterError(f"fill path: command {command!r} needs {k} numbers: {path!r:.80}")
        v = [float(a) for a in args]
        i += k
        if command == "M":
            close()
            pos = np.array(v)
            current.append(pos[None, :])
            command = "L"  # implicit repeats of M are line-tos
        elif command in ("L", "H", "V"):
            target = (
                np.array(v)
                if command == "L"
                else (np.array([v[0], pos[1]]) if command == "H" else np.array([pos[0], v[0]]))
            )
            if not current:
                current.append(pos[None, :])
            current.append(target[None, :])
            pos = target
        else:
            rx, ry, _, large, sweep, x, y = v
            if abs(abs(rx) - abs(ry)) > 1e-6 * max(abs(rx), abs(ry), 1.0):
                raise InvalidParameterError(f"fill path: only circular arcs (rx == ry), got rx={rx:g}, ry={ry:g}")
            target = np.array([x, y])
            if not current:
                current.append(pos[None, :])
            current.append(_sample_svg_arc(pos, target, abs(rx), bool(large), bool(sweep), step)[1:])
            pos = target
    close()
    return rings


def _sample_svg_arc(p0: np.ndarray, p1: np.ndarray, r: float, large: bool, sweep: bool, step: float) -> np.ndarray:
    """Points of an SVG circular arc command from ``p0`` to ``p1`` (SVG 1.1 F.6.5), ends included."""
    half = 0.5 * (p1 - p0)
    d = math.hypot(half[0], half[1])
    if d == 0.0 or r == 0.0:
        return np.array([p0, p1])
    r = max(r, d)
    h = math.sqrt(max(r * r - d * d, 0.0))
    sign = 1.0 if large != sweep else -1.0
    # Centre: midpoint plus h along the normal (x1', y1') -> (y1', -x1') of F.6.5.2 (rotation 0).
    x1, y1 = -half[0], -half[1]
    centre = 0.5 * (p0 + p1) + sign * (h / d) * np.array([y1, -x1])
    a0 = math.atan2(p0[1] - centre[1], p0[0] - centre[0])
    a1 = math.atan2(p1[1] - centre[1], p1[0] - centre[0])
    delta = a1 - a0
    if sweep and delta < 0.0:
        delta += TAU
    elif not sweep and delta > 0.0:
        delta -= TAU
    n = max(2, math.ceil(abs(delta) * r / step) + 1)
    t = a0 + delta * np.linspace(0.0, 1.0, n)
    pts = np.stack([centre[0] + r * np.cos(t), centre[1] + r * np.sin(t)], axis=-1)
    pts[0], pts[-1] = p0, p1
    return pts
