"""Result files: the ``img2logo.abstraction/1`` JSON document, SVG and PNG.

The JSON document is the stable record of a result (``contract/README.md``, JSON
Schema ``abstraction.schema.json`` shipped in this package). The SVG is for
designers: one exact elliptical-arc ``<path>`` per arc in an "Arcs" layer, and the
golden circles in a hidden "Golden circles" construction layer that Inkscape and
Illustrator show as a layer to toggle, and, when given, the coloured regions of
:mod:`img2logo.fills` (paper Fig. 18) in a "Fills" layer under everything else
(also the document's ``fills`` key and the PNG). The PNGs are quick looks, drawn with
:mod:`img2logo.plotting` on matplotlib's Agg canvas, exactly ``width`` x ``height``
px of the input image.

Every writer is atomic and deterministic: the bytes go to a temporary file in the
target's directory that is then renamed over the target (:func:`os.replace`), so a
file is written whole or not at all; missing parent directories are created; the
same input always gives byte-identical files (sorted JSON keys, ``repr`` floats, SVG
written by hand with fixed decimals, PNG without timestamp or software metadata).
Inside :func:`output_set` the files of a run appear together at its end, or none
of them. A path that cannot be written raises :class:`~img2logo.errors.OutputError`
naming it; :func:`check_output_paths` finds most such paths, and outputs that
are inputs, before any work.

Coordinates are input-image pixels: x right, y down, angles from +x towards +y, so
a positive sweep is clockwise on screen, SVG's ``sweep-flag = 1``.
"""

from __future__ import annotations

import contextlib
import contextvars
import copy
import errno
import glob
import json
import math
import os
import re
import secrets
from collections.abc import Callable, Iterator, Mapping, Sequence
from enum import Enum
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any

import numpy as np

from ._validation import check_finite, check_positive
from .constants import (
    FORMAT_NAME,
    JUNCTION_TOLERANCE,
    LINE_RADIUS,
    PHI,
    PNG_DPI,
    RADIUS_RELATIVE_TOLERANCE,
    SVG_DECIMALS,
)
from .errors import InvalidParameterError, OutputError
from .fills import Fill, check_fills, sample_path
from .geometry import TAU, Abstraction, Arc, Circle, line_arc
from .plotting import ARC_COLOR, CIRCLE_COLOR, default_stroke_width, plot_abstraction, plot_segment_graph
from .symmetry import axis_segment, symmetry_extra

if TYPE_CHECKING:
    from .segment_graph import SegmentGraph

__all__ = [
    "SCHEMA_RESOURCE",
    "check_output_paths",
    "from_document",
    "output_set",
    "read_fills",
    "read_json",
    "to_document",
    "to_svg",
    "validate_document",
    "write_json",
    "write_png",
    "write_segment_graph_png",
    "write_svg",
]

#: File name of the packaged JSON Schema of the document (read with importlib.resources).
SCHEMA_RESOURCE: str = "abstraction.schema.json"

#: An arc whose |sweep| exceeds this (but is not a full circle) has its two end points
#: so close that an SVG renderer could not place its centre reliably: it is written as
#: two arc commands. A full circle always is.
_NEAR_FULL_SWEEP: float = TAU - 1e-3

_SVG_NS = "http://www.w3.org/2000/svg"
_INKSCAPE_NS = "http://www.inkscape.org/namespaces/inkscape"


# --- the JSON document --------------------------------------------------------------


def to_document(
    abstraction: Abstraction,
    params: Mapping[str, Any] | None = None,
    *,
    check: bool = True,
    fills: Sequence[Fill] | None = None,
) -> dict[str, Any]:
    """The ``img2logo.abstraction/1`` JSON document of an abstraction (``contract/README.md``).

    Circles are deduplicated: arcs on one circle share its index, and circles are
    numbered in order of first use (``Abstraction.circles``). A junction lists only
    the arcs that have an end point there: an arc that passes through a junction
    in its interior (the progressive optimization keeps valence >= 3 junctions
    inside merged arcs) is left out, as the contract requires. Junctions left with
    no arc are omitted. ``extra.arc_segments`` records, for each arc, the indices of
    the segment-graph segments it abstracts.

    Parameters
    ----------
    abstraction : Abstraction
        The result; every circle must have its ladder exponent ``k``.
    params : mapping, optional
        Parameters to record besides ``abstraction.params`` (they win on equal
        keys). Values are made JSON-safe: numpy scalars and arrays become Python
        numbers and lists, tuples lists, paths strings, enums their values, and
        non-finite floats the strings ``"NaN"``, ``"Infinity"``, ``"-Infinity"``.
        ``params["ladder"] == "fibonacci"`` (with ``params["unit"]``) writes the
        contract's Fibonacci-ladder keys ``ladder`` and ``unit``.
    check : bool
        Check the contract's invariants on the result (radii on the ladder,
        junctions on their arcs' circles and at their end points) and raise if one
        fails, so a file that breaks the contract is never written. The JSON
        Schema itself is checked by :func:`validate_document` (needs jsonschema).
    fills : sequence of img2logo.fills.Fill, optional
        Coloured regions (paper Fig. 18, :mod:`img2logo.fills`), written as the
        contract's optional ``fills`` key: a list of ``{"path", "color"}``, the
        SVG path data of the region (exact arc commands, even-odd rule) and its
        ``#rrggbb`` colour. A gradient fill records the gradient's colour at its
        face's centroid (the contract has one colour per region); the SVG
        writer draws the true gradient. None (the default) writes no ``fills``
        key; an empty sequence writes an empty list.

    Returns
    -------
    dict
        A JSON-safe document (only dicts, lists, str, int, float, bool, None).

    Raises
    ------
    InvalidParameterError
        If a circle has no ``k``, a field is out of the contract's range, a
        parameter is not JSON-safe, a fill is not a Fill, or (with ``check``) an
        invariant fails.
    """
    if not isinstance(abstraction, Abstraction):
        raise InvalidParameterError(f"abstraction must be an Abstraction, got {type(abstraction).__name__}")
    fill_list = check_fills(fills)
    if params is not None and not isinstance(params, Mapping):
        raise InvalidParameterError(f"params must be a mapping, got {type(params).__name__}")
    if not isinstance(abstraction.params, Mapping):
        raise InvalidParameterError(f"abstraction.params must be a mapping, got {type(abstraction.params).__name__}")
    merged = _json_safe({**abstraction.params, **(params or {})}, "params")

    width = _int_at_least(abstraction.width, "width", 1)
    height = _int_at_least(abstraction.height, "height", 1)
    level = _int_at_least(abstraction.level, "level", 0)
    bias = check_finite(abstraction.bias, "bias")
    if not 0.0 <= bias < 1.0:
        raise InvalidParameterError(f"bias must be in [0, 1), got {bias!r}")
    similarity = check_finite(abstraction.similarity, "similarity")
    if similarity < 0.0:
        raise InvalidParameterError(f"similarity must be >= 0, got {similarity!r}")
    tolerance = check_finite(abstraction.tolerance, "tolerance")
    if tolerance <= 0.0:
        raise InvalidParameterError(f"tolerance must be > 0, got {tolerance!r}")

    # Straight lines (the lines option) are not arcs of the contract: they go to
    # extra.lines, so every circle of the document stays on the golden ladder.
    arcs = tuple(a for a in abstraction.arcs if not a.is_line)
    arc_number = {i: n for n, i in enumerate(i for i, a in enumerate(abstraction.arcs) if not a.is_line)}
    circles = tuple(dict.fromkeys(a.circle for a in arcs))
    index = {c: i for i, c in enumerate(circles)}
    circle_docs = []
    for i, c in enumerate(circles):
        if c.k is None:
            raise InvalidParameterError(
                f"circle {i} (centre ({c.cx:.6g}, {c.cy:.6g}), r={c.r:.6g}) has no ladder exponent k: "
                "only golden circles, r = phi**(k+bias), can be written"
            )
        circle_docs.append({"cx": float(c.cx), "cy": float(c.cy), "r": float(c.r), "k": int(c.k)})

    arc_docs = [
        {"circle": index[a.circle], "theta0": float(a.theta0), "sweep": min(TAU, max(-TAU, float(a.sweep)))}
        for a in arcs
    ]

    # Without the connectivity constraint (Fig. 11c) arcs need not meet at their
    # junction: an arc whose end is not at the junction point gets its own
    # junction at that end, so the document keeps the contract.
    unconnected = merged.get("connectivity") is False
    junction_docs = []
    for j, (point, listed) in enumerate(zip(abstraction.junctions, abstraction.junction_arcs, strict=True)):
        kept: list[int] = []
        loose: list[dict[str, Any]] = []
        for a in listed:
            ai = _int_at_least(a, f"junction_arcs[{j}] entry", 0)
            if ai >= len(abstraction.arcs):
                raise InvalidParameterError(
                    f"junction {j}: arc index {ai} is out of range (the abstraction has {len(abstraction.arcs)} arcs)"
                )
            if ai not in arc_number:
                continue  # a straight line: recorded in extra.lines
            ai = arc_number[ai]
            if ai in kept or any(ai in d["arcs"] for d in loose) or _passes_through(arcs[ai], point):
                continue
            end = _nearest_end(arc_docs[ai], circle_docs[arc_docs[ai]["circle"]], point)
            if unconnected and math.hypot(end[0] - point[0], end[1] - point[1]) > JUNCTION_TOLERANCE / 2:
                loose.append({"x": end[0], "y": end[1], "arcs": [ai]})
            else:
                kept.append(ai)
        if kept:
            junction_docs.append({"x": float(point[0]), "y": float(point[1]), "arcs": kept})
        junction_docs.extend(loose)

    all_segments = [[_int_at_least(s, "arc_segments entry", 0) for s in segs] for segs in abstraction.arc_segments]
    arc_segments = [all_segments[i] for i in arc_number]
    line_docs = [
        {
            "x0": float(a.start[0]),
            "y0": float(a.start[1]),
            "x1": float(a.end[0]),
            "y1": float(a.end[1]),
            "segments": all_segments[i],
        }
        for i, a in enumerate(abstraction.arcs)
        if a.is_line
    ]

    doc: dict[str, Any] = {
        "format": FORMAT_NAME,
        "width": width,
        "height": height,
        "phi": PHI,
        "bias": bias,
        "circles": circle_docs,
        "arcs": arc_docs,
        "junctions": junction_docs,
        "level": level,
        "similarity": similarity,
        "tolerance": tolerance,
        "params": merged,
        "extra": {"arc_segments": arc_segments, **({"lines": line_docs} if line_docs else {})},
    }
    symmetry = symmetry_extra(circles, merged)
    if symmetry is not None:  # a symmetric logo: the axis, and the circles paired with their mirror images
        doc["extra"]["symmetry"] = symmetry
    ladder = merged.get("ladder", "phi")
    if ladder == "fibonacci":
        unit = merged.get("unit")
        doc["ladder"] = "fibonacci"
        doc["unit"] = check_positive(unit, "params['unit'] (the Fibonacci ladder's unit)")
    elif ladder != "phi":
        raise InvalidParameterError(f"params['ladder'] must be 'phi' or 'fibonacci', got {ladder!r}")
    if fill_list is not None:
        doc["fills"] = [f.to_json() for f in fill_list]
    if check:
        _check_invariants(doc)
    return doc


def from_document(doc: Mapping[str, Any]) -> Abstraction:
    """The abstraction stored in an ``img2logo.abstraction/1`` document.

    The document is validated first: against the packaged JSON Schema when
    jsonschema is installed, and always against the contract's invariants.
    Round trip: ``from_document(to_document(a))`` has the same circles, arcs,
    ``arc_segments`` and parameters as ``a``, and its junctions are those of ``a``
    that had an arc ending there, each listing those arcs. Top-level ``ladder`` and
    ``unit`` go into ``params``; ``extra`` keys other than ``arc_segments`` are
    not kept, and ``fills`` are read by :func:`read_fills`.

    Parameters
    ----------
    doc : mapping
        The parsed JSON document.

    Returns
    -------
    Abstraction

    Raises
    ------
    InvalidParameterError
        With jsonschema's message if the document does not match the schema, or
        naming the first invariant that fails.
    """
    if not isinstance(doc, Mapping):
        raise InvalidParameterError(f"document must be a JSON object (mapping), got {type(doc).__name__}")
    d = dict(doc)
    _check_schema(d, required=False)
    try:
        _check_invariants(d)
        circles = [Circle(float(c["cx"]), float(c["cy"]), float(c["r"]), int(c["k"])) for c in d["circles"]]
        arcs = tuple(Arc(circles[int(a["circle"])], float(a["theta0"]), float(a["sweep"])) for a in d["arcs"])
        junctions = np.array([[float(j["x"]), float(j["y"])] for j in d["junctions"]], dtype=np.float64)
        junction_arcs = tuple(tuple(int(i) for i in j["arcs"]) for j in d["junctions"])
        extra = d.get("extra") or {}
        segs = extra.get("arc_segments")
        if segs is None:
            arc_segments: tuple[tuple[int, ...], ...] = tuple(() for _ in arcs)
        else:
            if len(segs) != len(arcs):
                raise InvalidParameterError(
                    f"extra.arc_segments must have one entry per arc ({len(arcs)}), got {len(segs)}"
                )
            arc_segments = tuple(tuple(int(s) for s in entry) for entry in segs)
        lines = extra.get("lines") or []
        arcs += tuple(line_arc((ln["x0"], ln["y0"]), (ln["x1"], ln["y1"])) for ln in lines)
        arc_segments += tuple(tuple(int(s) for s in ln.get("segments", ())) for ln in lines)
        params = copy.deepcopy(dict(d["params"]))
        if d.get("ladder") == "fibonacci":
            params.setdefault("ladder", "fibonacci")
            params.setdefault("unit", d["unit"])
        return Abstraction(
            level=int(d["level"]),
            arcs=arcs,
            arc_segments=arc_segments,
            junctions=junctions.reshape(-1, 2),
            junction_arcs=junction_arcs,
            similarity=float(d["similarity"]),
            bias=float(d["bias"]),
            tolerance=float(d["tolerance"]),
            width=int(d["width"]),
            height=int(d["height"]),
            params=params,
        )
    except InvalidParameterError:
        raise
    except (KeyError, TypeError, ValueError, IndexError, AttributeError) as exc:
        raise InvalidParameterError(f"not a valid {FORMAT_NAME} document: {type(exc).__name__}: {exc}") from exc


def validate_document(doc: Mapping[str, Any]) -> None:
    """Check a document against the packaged JSON Schema and the contract's invariants.

    The invariants (``contract/README.md``), checked in this order:

    - ``format`` is ``img2logo.abstraction/1``;
    - every circle has ``abs(r - phi**(k + bias)) <= 1e-6 r`` (Fibonacci ladder:
      ``abs(r - unit * F(k)) <= 1e-6 r``);
    - every arc names an existing circle and has ``0 < abs(sweep) <= 2 pi``;
    - every junction lists existing arcs, lies on the circle of each within
      1e-3 px, and each has an end point at the junction within 1e-3 px.

    Parameters
    ----------
    doc : mapping
        The parsed JSON document.

    Raises
    ------
    InvalidParameterError
        With jsonschema's message and the failing path, or naming the first
        violated invariant, e.g. ``circle 3: r=12.0 is not phi**(k+bias) = 11.09 ...``.
    ImportError
        If jsonschema (a development dependency) is not installed.
    """
    if not isinstance(doc, Mapping):
        raise InvalidParameterError(f"document must be a JSON object (mapping), got {type(doc).__name__}")
    d = dict(doc)
    _check_schema(d, required=True)
    _check_invariants(d)


def read_fills(source: Mapping[str, Any] | str | os.PathLike[str]) -> tuple[Fill, ...]:
    """The coloured regions (``fills`` key, paper Fig. 18) of a document or JSON file.

    Pass them on to :func:`write_svg` or :func:`write_png` with the abstraction
    from :func:`from_document` / :func:`read_json`. Each comes back as a plain
    :class:`img2logo.fills.Fill` (its path and ``#rrggbb`` colour; no gradient
    and no face index, which the document does not record).

    Parameters
    ----------
    source : mapping or str or path-like
        A parsed document, or the path of a JSON file.

    Returns
    -------
    tuple of Fill
        Empty when the document has no ``fills``.

    Raises
    ------
    InvalidParameterError
        If an entry has no ``path`` or ``color``, a colour is not ``#rrggbb`` or a
        path is not SVG path data that :func:`img2logo.fills.sample_path` reads.
    """
    if isinstance(source, Mapping):
        doc: Any = source
    else:
        p = _as_path(source)
        try:
            doc = json.loads(p.read_text(encoding="utf-8"))
        except json.JSONDecodeError as exc:
            raise InvalidParameterError(f"{p} is not JSON: {exc}") from exc
        if not isinstance(doc, Mapping):
            raise InvalidParameterError(f"{p}: document must be a JSON object, got {type(doc).__name__}")
    entries = doc.get("fills")
    if entries is None:
        return ()
    if not isinstance(entries, list):
        raise InvalidParameterError(f"fills must be a list, got {type(entries).__name__}")
    out = []
    for i, entry in enumerate(entries):
        if not isinstance(entry, Mapping) or "path" not in entry or "color" not in entry:
            raise InvalidParameterError(f"fills[{i}] must be an object with 'path' and 'color', got {entry!r:.80}")
        try:
            fill = Fill(entry["path"], entry["color"])
            sample_path(fill.path)
        except InvalidParameterError as exc:
            raise InvalidParameterError(f"fills[{i}]: {exc}") from exc
        out.append(fill)
    return tuple(out)


def read_json(path: str | os.PathLike[str]) -> Abstraction:
    """Read an ``img2logo.abstraction/1`` JSON file written by :func:`write_json`.

    Raises
    ------
    FileNotFoundError
        If there is no such file.
    InvalidParameterError
        If it is not JSON or not a valid document (see :func:`from_document`).
    """
    p = _as_path(path)
    text = p.read_text(encoding="utf-8")
    try:
        doc = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InvalidParameterError(f"{p} is not JSON: {exc}") from exc
    return from_document(doc)


def write_json(
    abstraction: Abstraction,
    path: str | os.PathLike[str],
    params: Mapping[str, Any] | None = None,
    *,
    check: bool = True,
    fills: Sequence[Fill] | None = None,
) -> Path:
    """Write the ``img2logo.abstraction/1`` document of ``abstraction`` (see :func:`to_document`).

    UTF-8 JSON with sorted keys, two-space indentation and a final newline; floats
    are written with Python's ``repr``, so they read back exactly. Atomic.
    ``fills`` (:mod:`img2logo.fills`) go into the ``fills`` key; read them back
    with :func:`read_fills`.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    doc = to_document(abstraction, params, check=check, fills=fills)
    data = (json.dumps(doc, indent=2, sort_keys=True, allow_nan=False, ensure_ascii=False) + "\n").encode("utf-8")
    return _atomic_write(path, lambda f: f.write(data))


# --- SVG ---------------------------------------------------------------------------


def to_svg(
    abstraction: Abstraction,
    *,
    construction_circles: bool = True,
    show_construction_circles: bool = False,
    stroke_width: float | None = None,
    image_size: tuple[float, float] | None = None,
    fills: Sequence[Fill] | None = None,
) -> str:
    """The SVG text of an abstraction (see :func:`write_svg` for the layout)."""
    if not isinstance(abstraction, Abstraction):
        raise InvalidParameterError(f"abstraction must be an Abstraction, got {type(abstraction).__name__}")
    fill_list = check_fills(fills) or []
    width = _int_at_least(abstraction.width, "width", 1)
    height = _int_at_least(abstraction.height, "height", 1)
    sw = default_stroke_width(width, height) if stroke_width is None else check_positive(stroke_width, "stroke_width")
    if image_size is None:
        shown_w, shown_h = float(width), float(height)
    else:
        try:
            shown_w, shown_h = image_size
        except (TypeError, ValueError) as exc:
            raise InvalidParameterError(f"image_size must be a pair (width, height), got {image_size!r}") from exc
        shown_w = check_positive(shown_w, "image_size width")
        shown_h = check_positive(shown_h, "image_size height")

    circles = abstraction.circles
    index = {c: i for i, c in enumerate(circles)}
    n = _num
    if abstraction.params.get("ladder") == "fibonacci":
        grid = f"unit*F(k) (Fibonacci grid, unit={float(abstraction.params['unit']):.6g} px)"
    else:
        grid = f"phi**(k+bias); bias={float(abstraction.bias):.6g}"
    desc = (
        f"{FORMAT_NAME} golden ratio logo by img2logo (Hsiao et al., Img2Logo, CGF 2023): "
        f"{len(abstraction.arcs)} circular arcs on {len(circles)} circles of radius {grid}, "
        f"level={int(abstraction.level)}, "
        f"E^s={float(abstraction.similarity):.6g} px, tolerance T={float(abstraction.tolerance):.6g} px. "
        f"Coordinates in pixels of the {width} x {height} input image."
    )
    lines = [
        '<?xml version="1.0" encoding="UTF-8" standalone="no"?>',
        f'<svg xmlns="{_SVG_NS}" xmlns:inkscape="{_INKSCAPE_NS}" version="1.1" '
        f'width="{n(shown_w)}" height="{n(shown_h)}" viewBox="0 0 {width} {height}">',
        f"  <title>{_escape(f'Golden ratio logo (level {int(abstraction.level)})')}</title>",
        f"  <desc>{_escape(desc)}</desc>",
    ]
    if fill_list:
        lines.extend(_svg_fill_layer(fill_list))
    if construction_circles:
        hidden = "" if show_construction_circles else ' style="display:none"'
        lines.append(
            '  <g id="golden-circles" inkscape:groupmode="layer" inkscape:label="Golden circles"'
            f'{hidden} fill="none" stroke="{CIRCLE_COLOR}" stroke-width="{n(max(0.5, sw / 4.0))}">'
        )
        for i, c in enumerate(circles):
            if c.k is None and c.r >= 0.5 * LINE_RADIUS:
                continue  # the circle of a straight line is no construction circle
            lines.append(f'    <circle id="circle-{i}"{_k_attr(c)} cx="{n(c.cx)}" cy="{n(c.cy)}" r="{n(c.r)}"/>')
        guide = axis_segment(abstraction.params, width, height)
        if guide is not None:  # a symmetric logo: its mirror axis as a guide line across the image
            (x0, y0), (x1, y1) = guide
            ends = f'x1="{n(x0)}" y1="{n(y0)}" x2="{n(x1)}" y2="{n(y1)}"'
            lines.append(f'    <line id="mirror-axis" {ends} stroke-dasharray="4 2"/>')
        lines.append("  </g>")
    lines.append(
        f'  <g id="arcs" inkscape:groupmode="layer" inkscape:label="Arcs" fill="none" stroke="{ARC_COLOR}" '
        f'stroke-width="{n(sw)}" stroke-linecap="round" stroke-linejoin="round">'
    )
    for i, a in enumerate(abstraction.arcs):
        if a.is_line:
            d = f"M {n(a.start[0])} {n(a.start[1])} L {n(a.end[0])} {n(a.end[1])}"
            lines.append(f'    <path id="line-{i}" data-line="true" d="{d}"/>')
            continue
        lines.append(
            f'    <path id="arc-{i}" data-circle="{index[a.circle]}"{_k_attr(a.circle)} d="{_arc_path_data(a)}"/>'
        )
    lines.append("  </g>")
    lines.append("</svg>")
    return "\n".join(lines) + "\n"


def write_svg(
    abstraction: Abstraction,
    path: str | os.PathLike[str],
    *,
    construction_circles: bool = True,
    show_construction_circles: bool = False,
    stroke_width: float | None = None,
    image_size: tuple[float, float] | None = None,
    fills: Sequence[Fill] | None = None,
) -> Path:
    """Write an abstraction as SVG for designers: exact arcs, construction circles as a layer.

    The drawing's user units are input-image pixels: ``viewBox="0 0 W H"`` with W x H
    the input size. Each arc is one ``<path id="arc-i" data-circle="c" data-k="k">``
    made of SVG elliptical-arc commands ``A r r 0 large-arc sweep x y`` (exact, not
    polylines): ``large-arc = |sweep| > pi``, ``sweep-flag = 1`` for a positive
    sweep (clockwise with y down). A full circle is two half arcs closed with
    ``Z``; an arc within 1e-3 rad of a full turn is also split in two. Arcs sit in
    an Inkscape layer "Arcs" (black stroke, no fill, round caps and joins); the
    circles, numbered as in the JSON document, in a layer "Golden circles" hidden
    by default (``style="display:none"``). Coordinates carry ``SVG_DECIMALS``
    decimals. Atomic and deterministic.

    With ``fills`` (paper Fig. 18, :mod:`img2logo.fills`) the coloured regions
    come first, so they lie under everything else: an Inkscape layer "Fills"
    (``<g id="fills">``, no stroke) with one ``<path id="fill-i" fill="#rrggbb"
    fill-rule="evenodd">`` per region, its ``d`` the region's exact arc path
    (holes as extra subpaths). Gradient fills are painted with
    ``fill="url(#fill-gradient-j)"``, the gradients defined once each in
    ``<defs>`` in image-pixel user space.

    Parameters
    ----------
    abstraction : Abstraction
        The result to write.
    path : str or path-like
        Target file; parent directories are created.
    construction_circles : bool
        Include the "Golden circles" layer.
    show_construction_circles : bool
        Make that layer visible instead of hidden.
    stroke_width : float, optional
        Width of the arcs, px; default :func:`img2logo.plotting.default_stroke_width`.
    image_size : (float, float), optional
        Displayed size (width, height) in px of the SVG; default the input size.
        The viewBox stays the input frame, so the drawing scales.
    fills : sequence of img2logo.fills.Fill, optional
        Coloured regions, drawn under the arcs.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    text = to_svg(
        abstraction,
        construction_circles=construction_circles,
        show_construction_circles=show_construction_circles,
        stroke_width=stroke_width,
        image_size=image_size,
        fills=fills,
    )
    data = text.encode("utf-8")
    return _atomic_write(path, lambda f: f.write(data))


# --- PNG ---------------------------------------------------------------------------


def write_png(
    abstraction: Abstraction,
    path: str | os.PathLike[str],
    *,
    image: np.ndarray | None = None,
    dpi: float = PNG_DPI,
    show_junctions: bool = False,
    show_circles: bool = False,
    stroke_width: float | None = None,
    fills: Sequence[Fill] | None = None,
) -> Path:
    """Render an abstraction to a PNG of exactly the input image's size.

    Drawn with :func:`img2logo.plotting.plot_abstraction` on matplotlib's Agg
    canvas with matplotlib's default style (a user's matplotlibrc does not change
    the file), on white, without metadata that could vary: the same input gives
    the same bytes. Atomic.

    Parameters
    ----------
    abstraction : Abstraction
        The result to draw.
    path : str or path-like
        Target file; parent directories are created.
    image : ndarray, shape (height, width) or (height, width, 3 or 4), optional
        The input image, drawn faded underneath.
    dpi : float
        Figure resolution; it only converts px to points, the PNG is always
        ``width`` x ``height`` px.
    show_junctions, show_circles : bool
        Mark the junctions; draw the golden circles.
    stroke_width : float, optional
        Width of the arcs, px; default :func:`img2logo.plotting.default_stroke_width`.
    fills : sequence of img2logo.fills.Fill, optional
        Coloured regions (paper Fig. 18), drawn under the arcs
        (:func:`img2logo.plotting.draw_fills`).

    Returns
    -------
    pathlib.Path
        The path written.
    """
    if not isinstance(abstraction, Abstraction):
        raise InvalidParameterError(f"abstraction must be an Abstraction, got {type(abstraction).__name__}")
    fill_list = check_fills(fills)
    width = _int_at_least(abstraction.width, "width", 1)
    height = _int_at_least(abstraction.height, "height", 1)
    d = check_positive(dpi, "dpi")
    sw = default_stroke_width(width, height) if stroke_width is None else check_positive(stroke_width, "stroke_width")

    def draw(ax: Any) -> None:
        plot_abstraction(
            abstraction,
            ax,
            image=image,
            show_circles=show_circles,
            show_junctions=show_junctions,
            linewidth=sw * 72.0 / d,
            fills=fill_list,
        )

    return _write_figure_png(path, width, height, d, draw)


def write_segment_graph_png(
    graph: SegmentGraph,
    path: str | os.PathLike[str],
    *,
    image: np.ndarray | None = None,
    dpi: float = PNG_DPI,
    show_junctions: bool = True,
    stroke_width: float | None = None,
) -> Path:
    """Render a segment graph (paper Fig. 4b) to a PNG of exactly the graph's image size.

    Drawn with :func:`img2logo.plotting.plot_segment_graph`: one colour per segment,
    nodes marked by valence. Atomic and deterministic like :func:`write_png`.

    Parameters
    ----------
    graph : SegmentGraph
        The graph to draw.
    path : str or path-like
        Target file; parent directories are created.
    image : ndarray, shape (height, width) or (height, width, 3 or 4), optional
        The input image, drawn faded underneath.
    dpi : float
        Figure resolution; it only converts px to points.
    show_junctions : bool
        Mark the nodes by valence.
    stroke_width : float, optional
        Width of the segments, px; default half of
        :func:`img2logo.plotting.default_stroke_width`, at least 1 px.

    Returns
    -------
    pathlib.Path
        The path written.
    """
    from .segment_graph import SegmentGraph  # lazily: it loads scipy

    if not isinstance(graph, SegmentGraph):
        raise InvalidParameterError(f"graph must be a SegmentGraph, got {type(graph).__name__}")
    width = _int_at_least(graph.width, "graph width", 1)
    height = _int_at_least(graph.height, "graph height", 1)
    d = check_positive(dpi, "dpi")
    if stroke_width is None:
        sw = max(1.0, default_stroke_width(width, height) / 2.0)
    else:
        sw = check_positive(stroke_width, "stroke_width")
    lw = sw * 72.0 / d
    ms = max(3.0 * lw, 5.0 * 72.0 / d)  # node dots at least 5 px across

    def draw(ax: Any) -> None:
        plot_segment_graph(graph, ax, image=image, show_junctions=show_junctions, linewidth=lw, markersize=ms)

    return _write_figure_png(path, width, height, d, draw)


# --- helpers -----------------------------------------------------------------------


def _svg_fill_layer(fills: Sequence[Fill]) -> list[str]:
    """The ``<defs>`` of the gradients and the "Fills" layer (see :func:`write_svg`)."""
    gradient_ids: dict[Any, str] = {}
    for f in fills:
        if f.gradient is not None and f.gradient not in gradient_ids:
            gradient_ids[f.gradient] = f"fill-gradient-{len(gradient_ids)}"
    lines = []
    if gradient_ids:
        lines.append("  <defs>")
        lines.extend(f"    {g.svg(gid)}" for g, gid in gradient_ids.items())
        lines.append("  </defs>")
    lines.append('  <g id="fills" inkscape:groupmode="layer" inkscape:label="Fills" stroke="none">')
    for i, f in enumerate(fills):
        paint = f.color if f.gradient is None else f"url(#{gradient_ids[f.gradient]})"
        face = "" if f.face is None else f' data-face="{int(f.face)}"'
        lines.append(f'    <path id="fill-{i}"{face} fill="{paint}" fill-rule="evenodd" d="{_escape(f.path)}"/>')
    lines.append("  </g>")
    return lines


def _write_figure_png(
    path: str | os.PathLike[str], width: int, height: int, dpi: float, draw: Callable[[Any], None]
) -> Path:
    """Draw on full-figure axes of a ``width`` x ``height`` px Agg figure and save it atomically."""
    import matplotlib.style
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    target = _as_path(path)
    with matplotlib.style.context("default"):
        fig = Figure(figsize=(width / dpi, height / dpi), dpi=dpi, facecolor="white")
        FigureCanvasAgg(fig)
        ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
        draw(ax)

        def save(f: IO[bytes]) -> None:
            fig.savefig(
                f,
                format="png",
                dpi=dpi,
                facecolor="white",
                edgecolor="white",
                transparent=False,
                metadata={"Software": None},
            )

        return _atomic_write(target, save)


def save_figure(fig: Any, path: str | os.PathLike[str], *, dpi: float = PNG_DPI) -> Path:
    """Save a matplotlib figure (PNG or SVG by the suffix) whole or not at all, byte-deterministically.

    No timestamp or software tag goes into the file, and SVG ids use a fixed
    hash salt, so the same figure gives the same bytes (``make figures`` can be
    checked with ``git diff``).
    """
    import matplotlib

    target = _as_path(path)
    fmt = target.suffix.lstrip(".").lower()
    if fmt not in ("png", "svg"):
        raise InvalidParameterError(f"figure path must end in .png or .svg, got {target.name!r}")
    metadata = {"Software": None} if fmt == "png" else {"Date": None, "Creator": None}

    def save(f: IO[bytes]) -> None:
        with matplotlib.rc_context({"svg.hashsalt": "img2logo"}):
            fig.savefig(f, format=fmt, dpi=dpi, metadata=metadata, facecolor="white")

    return _atomic_write(target, save)


def write_table(table: Any, path: str | os.PathLike[str]) -> Path:
    """Write a pandas DataFrame as CSV (no index), whole or not at all."""
    text = table.to_csv(index=False, lineterminator="\n", float_format="%.6g")
    return _atomic_write(path, lambda f: f.write(text.encode("utf-8")))


def check_output_paths(
    targets: Mapping[str, str | os.PathLike[str]],
    inputs: Sequence[str | os.PathLike[str]] = (),
    folders: Mapping[str, str | os.PathLike[str]] | None = None,
) -> dict[str, Path]:
    """Check, before any work, that every output can be written and that none is an input.

    Links are resolved (symbolic links by :func:`os.path.realpath`, hard links
    by the file's identity), so a target that is an input under another name is
    found. Temporary files of the targets left by killed runs are removed.

    Parameters
    ----------
    targets : mapping of str to path
        What each output is called in a message (``"--svg"``) -> its file.
    inputs : sequence of path
        The files the run reads: no target may be one of them.
    folders : mapping of str to path, optional
        Output folders (``"--levels-dir"``) -> folder: each must be a folder or
        creatable, and writable.

    Returns
    -------
    dict of str to pathlib.Path

    Raises
    ------
    InvalidParameterError
        Naming the output and the path: a target that is an input, a folder or
        not a regular file (a device such as /dev/null); two outputs on one
        file; a parent that is a regular file, or a folder that cannot be
        written (no permission, a read-only file system).
    """
    checked: dict[str, Path] = {}
    seen: dict[str, str] = {}
    real_inputs = {os.path.realpath(os.fspath(p)): Path(p) for p in inputs}
    for name, path in targets.items():
        target = _as_path(path)
        label = name if name == str(target) else f"{name} {target}"
        if target.is_dir():
            raise InvalidParameterError(f"{label} is a folder; give a file name")
        if target.exists() and not target.is_file():
            raise InvalidParameterError(f"{label} is not a regular file (a device, a pipe, ...)")
        real = os.path.realpath(target)
        for real_input, given in real_inputs.items():
            if real == real_input or (target.exists() and _same_file(target, given)):
                raise InvalidParameterError(f"{label} is the input {given}: refusing to write over an input")
        if real in seen:
            raise InvalidParameterError(f"{seen[real]} and {name} name the same file {target}; give two files")
        seen[real] = name
        _check_writable_parent(label, target.parent)
        _remove_stale_temporaries(target)
        checked[name] = target
    for name, path in (folders or {}).items():
        folder = _as_path(path)
        if folder.exists() and not folder.is_dir():
            raise InvalidParameterError(f"{name} {folder} is a file, not a folder")
        _check_writable_parent(f"{name} {folder}", folder)
    return checked


def _same_file(a: Path, b: Path) -> bool:
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


def _check_writable_parent(label: str, folder: Path) -> None:
    """Raise unless ``folder`` (or its first existing ancestor, where it would be created) is a writable folder."""
    p = folder if str(folder) else Path(".")
    while not p.exists() and not p.is_symlink() and p != p.parent:
        p = p.parent
    if not p.is_dir():
        raise InvalidParameterError(f"{label}: {p} is not a folder")
    if not os.access(p, os.W_OK | os.X_OK):
        raise InvalidParameterError(f"{label}: cannot write in {p} (no permission, or a read-only file system)")


class _Stage:
    """The files of one :func:`output_set`: (temporary, target) pairs and the folders it created."""

    def __init__(self) -> None:
        self.files: list[tuple[Path, Path]] = []
        self.folders: list[Path] = []

    def discard(self) -> None:
        """Remove the temporary files and the folders created (if left empty)."""
        for tmp, _ in self.files:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        for folder in reversed(self.folders):
            with contextlib.suppress(OSError):
                folder.rmdir()
        self.files.clear()
        self.folders.clear()

    def commit(self) -> None:
        """Move every temporary file over its target, with SIGINT and SIGTERM held off meanwhile."""
        import signal
        import threading

        held = threading.current_thread() is threading.main_thread() and hasattr(signal, "pthread_sigmask")
        if held:
            old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
        try:
            while self.files:
                tmp, target = self.files[0]
                try:
                    os.replace(tmp, target)
                except OSError as exc:
                    self.discard()
                    raise OutputError(_os_message(target, exc)) from exc
                self.files.pop(0)
        finally:
            if held:
                signal.pthread_sigmask(signal.SIG_SETMASK, old)


_STAGE: contextvars.ContextVar[_Stage | None] = contextvars.ContextVar("img2logo_output_stage", default=None)


@contextlib.contextmanager
def output_set() -> Iterator[None]:
    """Write every file of a run together: all of them appear at the end, or none.

    Inside the ``with`` block every writer of this module writes its bytes to
    a temporary file next to its target; when the block ends normally the
    temporary files are renamed over their targets one after the other (signals
    held off meanwhile); when it ends with an exception (an error, Ctrl-C, a
    SIGTERM turned into an exception) they are removed, with the folders the
    block created, and no target is touched.

    Examples
    --------
    >>> with output_set():  # doctest: +SKIP
    ...     write_json(level, "out/logo.json")
    ...     write_svg(level, "out/logo.svg")
    """
    stage = _Stage()
    token = _STAGE.set(stage)
    try:
        yield
    except BaseException:
        stage.discard()
        raise
    finally:
        _STAGE.reset(token)
    stage.commit()


def _atomic_write(path: str | os.PathLike[str], write: Callable[[IO[bytes]], object]) -> Path:
    """Write a file whole or not at all: into a temporary sibling, then :func:`os.replace`.

    ``write`` gets the open binary temporary file. Parent directories are created.
    On any error the temporary file is removed and an existing target is untouched;
    an operating-system error (a read-only file system, a full disk, a parent
    that is a file, a target that is a folder) is raised as :class:`OutputError`
    naming the path. Temporary files of the same target left by a process that
    no longer runs (killed while writing) are removed first. Inside
    :func:`output_set` the rename waits for the end of the set. The file gets
    the usual permissions (0o666 less the umask).
    """
    target = _as_path(path)
    stage = _STAGE.get()
    try:
        if target.is_dir():
            raise IsADirectoryError(errno.EISDIR, "is a directory", str(target))
        _make_parents(target.parent, stage)
        _remove_stale_temporaries(target)
        fd, tmp = _open_temporary(target)
    except OSError as exc:
        raise OutputError(_os_message(target, exc)) from exc
    try:
        with os.fdopen(fd, "wb") as f:
            write(f)
            f.flush()
            os.fsync(f.fileno())
        if stage is not None:
            stage.files.append((tmp, target))
        else:
            os.replace(tmp, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError) and not isinstance(exc, OutputError):
            raise OutputError(_os_message(target, exc)) from exc
        raise
    return target


#: Temporary files: ``.<target name>.<pid>-<8 hex>.tmp`` next to the target.
_TEMPORARY = re.compile(r"\.(?P<name>.+)\.(?P<pid>\d+)-[0-9a-f]{8}\.tmp")


def _open_temporary(target: Path) -> tuple[int, Path]:
    """Create and open a new temporary file next to ``target``: (file descriptor, path)."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_BINARY", 0)
    for _ in range(100):
        tmp = target.parent / f".{target.name}.{os.getpid()}-{secrets.token_hex(4)}.tmp"
        try:
            return os.open(tmp, flags, 0o666), tmp
        except FileExistsError:
            continue
    raise FileExistsError(errno.EEXIST, "could not create a temporary file next to it", str(target))  # pragma: no cover


def _remove_stale_temporaries(target: Path) -> list[Path]:
    """Remove ``target``'s temporary files whose writing process is gone; return them."""
    removed = []
    with contextlib.suppress(OSError):
        for p in target.parent.glob(f".{glob.escape(target.name)}.*.tmp"):
            m = _TEMPORARY.fullmatch(p.name)
            if m is None or m["name"] != target.name or _process_alive(int(m["pid"])):
                continue
            with contextlib.suppress(FileNotFoundError):
                p.unlink()
                removed.append(p)
    return removed


def _process_alive(pid: int) -> bool:
    """Whether a process ``pid`` exists (this one included)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OverflowError, OSError):
        return True
    return True


def _make_parents(folder: Path, stage: _Stage | None) -> None:
    """Create ``folder`` and its missing parents; a stage records those it created."""
    missing = []
    p = folder
    while not p.exists() and p != p.parent:
        missing.append(p)
        p = p.parent
    for p in reversed(missing):
        try:
            p.mkdir()
        except FileExistsError:
            if not p.is_dir():
                raise
            continue
        if stage is not None:
            stage.folders.append(p)


def _os_message(target: Path, exc: OSError) -> str:
    """``cannot write <target>: <reason>``, naming the path that failed when it is not the target."""
    reason = exc.strerror or str(exc) or type(exc).__name__
    where = None if exc.filename is None else Path(os.fsdecode(exc.filename))
    if where is not None and where != target and not where.name.startswith(f".{target.name}."):
        reason = f"{reason} ({where})"
    return f"cannot write {target}: {reason}"


def _as_path(path: object) -> Path:
    """``path`` as a :class:`pathlib.Path`, for a str or path-like that is not empty."""
    if isinstance(path, str | os.PathLike):
        p = os.fspath(path)
        if isinstance(p, str) and p:
            return Path(p)
    raise InvalidParameterError(f"path must be a non-empty str or path-like, got {path!r}")


@lru_cache(maxsize=1)
def _schema() -> dict[str, Any]:
    """The packaged JSON Schema of the document (never read from outside the package)."""
    text = resources.files(__package__).joinpath(SCHEMA_RESOURCE).read_text(encoding="utf-8")
    return json.loads(text)


def _check_schema(doc: dict[str, Any], *, required: bool) -> None:
    """Validate ``doc`` against the packaged schema; without jsonschema raise or skip."""
    try:
        import jsonschema
    except ImportError as exc:
        if not required:
            return
        raise ImportError(
            "validating an img2logo document against its JSON Schema needs the optional package "
            "jsonschema (a development dependency): pip install jsonschema"
        ) from exc
    validator = jsonschema.Draft202012Validator(_schema())
    error = jsonschema.exceptions.best_match(validator.iter_errors(doc))
    if error is not None:
        where = "/".join(str(p) for p in error.absolute_path) or "(top level)"
        raise InvalidParameterError(f"document does not match the {FORMAT_NAME} schema at {where}: {error.message}")


def _check_invariants(doc: Mapping[str, Any]) -> None:
    """Raise InvalidParameterError naming the first contract invariant ``doc`` breaks."""
    if doc.get("format") != FORMAT_NAME:
        raise InvalidParameterError(f"format must be {FORMAT_NAME!r}, got {doc.get('format')!r}")
    phi = float(doc["phi"])
    bias = float(doc["bias"])
    fibonacci = doc.get("ladder", "phi") == "fibonacci"
    unit = float(doc["unit"]) if fibonacci else 0.0
    circles = doc["circles"]
    for i, c in enumerate(circles):
        r, k = float(c["r"]), int(c["k"])
        if fibonacci:
            if k < 1:
                raise InvalidParameterError(f"circle {i}: k={k} is not a Fibonacci index (k >= 1)")
            expected, rule = unit * _fibonacci(k), f"unit*F(k) (k={k}, unit={unit!r})"
        else:
            expected, rule = phi ** (k + bias), f"phi**(k+bias) (k={k}, bias={bias!r})"
        if not abs(r - expected) <= RADIUS_RELATIVE_TOLERANCE * r:
            name, _, detail = rule.partition(" ")
            raise InvalidParameterError(
                f"circle {i}: r={r!r} is not {name} = {expected:.10g} {detail}, "
                f"relative error {abs(r - expected) / r:.3g} > {RADIUS_RELATIVE_TOLERANCE:g}"
            )
    arcs = doc["arcs"]
    for i, a in enumerate(arcs):
        ci = int(a["circle"])
        if not 0 <= ci < len(circles):
            raise InvalidParameterError(
                f"arc {i}: circle index {ci} is out of range (the document has {len(circles)} circles)"
            )
        sweep = float(a["sweep"])
        if not 0.0 < abs(sweep) <= TAU + 1e-12:
            raise InvalidParameterError(f"arc {i}: sweep must satisfy 0 < |sweep| <= 2 pi, got {sweep!r}")
    tol = JUNCTION_TOLERANCE
    for j, junction in enumerate(doc["junctions"]):
        x, y = float(junction["x"]), float(junction["y"])
        for ai in junction["arcs"]:
            ai = int(ai)
            if not 0 <= ai < len(arcs):
                raise InvalidParameterError(
                    f"junction {j}: arc index {ai} is out of range (the document has {len(arcs)} arcs)"
                )
            a = arcs[ai]
            ci = int(a["circle"])
            c = circles[ci]
            cx, cy, r = float(c["cx"]), float(c["cy"]), float(c["r"])
            off = abs(math.hypot(x - cx, y - cy) - r)
            if not off <= tol:
                raise InvalidParameterError(
                    f"junction {j}: ({x:.6g}, {y:.6g}) is {off:.3g} px off the circle {ci} of arc {ai}, "
                    f"more than {tol:g} px"
                )
            t0 = float(a["theta0"])
            t1 = t0 + float(a["sweep"])
            ends = [(cx + r * math.cos(t), cy + r * math.sin(t)) for t in (t0, t1)]
            gap = min(math.hypot(x - ex, y - ey) for ex, ey in ends)
            if not gap <= tol:
                raise InvalidParameterError(
                    f"junction {j}: arc {ai} has no end point at ({x:.6g}, {y:.6g}): its nearest end is "
                    f"{gap:.3g} px away, more than {tol:g} px"
                )


def _fibonacci(k: int) -> int:
    """F(k) with F(1) = F(2) = 1."""
    a, b = 0, 1
    for _ in range(k):
        a, b = b, a + b
    return a


def _nearest_end(arc: Mapping[str, Any], circle: Mapping[str, Any], point: np.ndarray) -> tuple[float, float]:
    """The end point of a document arc (as the contract computes it) nearest ``point``, px."""
    cx, cy, r = float(circle["cx"]), float(circle["cy"]), float(circle["r"])
    t0 = float(arc["theta0"])
    ends = [(cx + r * math.cos(t), cy + r * math.sin(t)) for t in (t0, t0 + float(arc["sweep"]))]
    return min(ends, key=lambda e: math.hypot(e[0] - float(point[0]), e[1] - float(point[1])))


def _passes_through(arc: Arc, point: np.ndarray) -> bool:
    """True when ``point`` lies on ``arc`` strictly inside it, not at one of its end points.

    Within the contract's junction tolerance: such a junction must not list the arc.
    """
    p = np.asarray(point, dtype=np.float64)
    tol = JUNCTION_TOLERANCE
    if min(float(np.hypot(*(p - arc.start))), float(np.hypot(*(p - arc.end)))) <= tol:
        return False
    c = arc.circle
    if abs(float(c.distance(p))) > tol:
        return False
    return bool(arc.contains_angle(float(c.angle_of(p)), tol=tol / c.r))


def _json_safe(value: Any, where: str) -> Any:
    """``value`` made of JSON types only (see :func:`to_document`); raise if impossible."""
    if value is None or isinstance(value, bool | str):
        return value
    if isinstance(value, np.bool_):
        return bool(value)
    if isinstance(value, int | np.integer):
        return int(value)
    if isinstance(value, float | np.floating):
        f = float(value)
        if math.isnan(f):
            return "NaN"
        if math.isinf(f):
            return "Infinity" if f > 0 else "-Infinity"
        return f
    if isinstance(value, Enum):
        return _json_safe(value.value, where)
    if isinstance(value, os.PathLike):
        return os.fsdecode(os.fspath(value))
    if isinstance(value, np.ndarray):
        return _json_safe(value.tolist(), where)
    if isinstance(value, Mapping):
        out = {}
        for key, item in value.items():
            if not isinstance(key, str):
                raise InvalidParameterError(f"{where} keys must be strings, got {key!r}")
            out[key] = _json_safe(item, f"{where}[{key!r}]")
        return out
    if isinstance(value, list | tuple):
        return [_json_safe(item, f"{where}[{i}]") for i, item in enumerate(value)]
    raise InvalidParameterError(
        f"{where} must be JSON-safe (numbers, strings, lists, mappings, numpy values), got {type(value).__name__}"
    )


def _int_at_least(value: object, name: str, minimum: int) -> int:
    """``value`` as an int >= ``minimum`` (Python or numpy integer, not bool)."""
    if isinstance(value, bool | np.bool_) or not isinstance(value, int | np.integer):
        raise InvalidParameterError(f"{name} must be an integer, got {value!r}")
    v = int(value)
    if v < minimum:
        raise InvalidParameterError(f"{name} must be >= {minimum}, got {v}")
    return v


def _num(v: float) -> str:
    """A coordinate for SVG: fixed point with ``SVG_DECIMALS`` decimals, trailing zeros dropped."""
    s = f"{float(v):.{SVG_DECIMALS}f}"
    if "." in s:
        s = s.rstrip("0").rstrip(".")
    return "0" if s in ("-0", "") else s


def _escape(text: str) -> str:
    """``text`` safe as XML character data (``xml.sax.saxutils.escape`` without its slow import)."""
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _k_attr(circle: Circle) -> str:
    """The ``data-k`` attribute of a circle, or nothing when it has no k."""
    return "" if circle.k is None else f' data-k="{int(circle.k)}"'


def _arc_path_data(arc: Arc) -> str:
    """SVG path data of an arc with elliptical-arc commands (see :func:`write_svg`)."""
    c = arc.circle
    sweep = min(TAU, max(-TAU, float(arc.sweep)))
    pieces = 2 if (arc.is_full_circle or abs(sweep) > _NEAR_FULL_SWEEP) else 1
    angles = float(arc.theta0) + sweep * np.linspace(0.0, 1.0, pieces + 1)
    points = c.point_at(angles)
    if arc.is_full_circle:
        points[-1] = points[0]
    large = 1 if abs(sweep) / pieces > math.pi else 0
    flag = 1 if sweep > 0 else 0
    r = _num(c.r)
    parts = [f"M {_num(points[0, 0])} {_num(points[0, 1])}"]
    for x, y in points[1:]:
        parts.append(f"A {r} {r} 0 {large} {flag} {_num(x)} {_num(y)}")
    if arc.is_full_circle:
        parts.append("Z")
    return " ".join(parts)
