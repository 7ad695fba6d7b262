"""The result file's contract: the ``img2logo.abstraction/1`` JSON document of an abstraction.

The JSON document is the stable record of a result (``contract/README.md``, JSON
Schema ``abstraction.schema.json`` shipped in this package): :func:`to_document`
makes it (the abstraction checked the contract's invariants when it was made, so
a document that breaks the contract is never written), :func:`from_document`
reads it back,
:func:`validate_document` checks one against the schema and the invariants, and
:func:`read_fills` reads its coloured regions. The files themselves are written
and read by :func:`img2logo.export.writers.write_json` and
:func:`img2logo.export.writers.read_json`.

Coordinates are input-image pixels: x right, y down, angles from +x towards +y.
"""

from __future__ import annotations

import copy
import json
import math
import os
from collections.abc import Mapping, Sequence
from enum import Enum
from functools import lru_cache
from importlib import resources
from typing import Any

import numpy as np

from .._io import as_path
from .._validation import check_instance
from ..constants import FORMAT_NAME, JUNCTION_TOLERANCE, PHI, RADIUS_RELATIVE_TOLERANCE
from ..design.fill_values import Fill, check_fills
from ..errors import InvalidParameterError
from ..geometry.abstraction import Abstraction
from ..geometry.golden_ladder import FIBONACCI_MAX_INDEX, FibonacciLadder, GoldenLadder, Ladder, fibonacci
from ..geometry.mirror import symmetry_extra
from ..geometry.primitives import TAU, Arc, Circle, line_arc
from ..geometry.svg_path import sample_path

__all__ = ["SCHEMA_RESOURCE", "from_document", "read_fills", "to_document", "validate_document"]

#: File name of the packaged JSON Schema of the document (read with importlib.resources).
SCHEMA_RESOURCE: str = "abstraction.schema.json"


def to_document(
    abstraction: Abstraction,
    params: Mapping[str, Any] | None = None,
    *,
    check: bool = False,
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
        The result (its ladder, topology and invariants were checked when it was made).
    params : mapping, optional
        Parameters to record besides ``abstraction.params`` (they win on equal
        keys). Values are made JSON-safe: numpy scalars and arrays become Python
        numbers and lists, tuples lists, paths strings, enums their values, and
        non-finite floats the strings ``"NaN"``, ``"Infinity"``, ``"-Infinity"``.
        The contract's ladder keys come from ``abstraction.ladder``: on the
        Fibonacci ladder ``ladder`` and ``unit``.
    check : bool
        Also check the document against the contract's invariants, as a reader
        does (:func:`validate_document` without the schema). Not needed: the
        abstraction checked them when it was made (radii on its ladder,
        junctions on their arcs' circles and at their end points); a self-test
        of the writer.
    fills : sequence of img2logo.design.fills.Fill, optional
        Coloured regions (paper Fig. 18, :mod:`img2logo.design.fills`), written as the
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
        If a parameter is not JSON-safe, a fill is not a Fill, or (with
        ``check``) an invariant fails.
    """
    check_instance(abstraction, Abstraction, "abstraction")
    fill_list = check_fills(fills)
    if params is not None and not isinstance(params, Mapping):
        raise InvalidParameterError(f"params must be a mapping, got {type(params).__name__}")
    merged = _json_safe({**abstraction.params, **(params or {})}, "params")

    # Straight lines (the lines option) are not arcs of the contract: they go to
    # extra.lines, so every circle of the document stays on the golden ladder.
    arcs = tuple(a for a in abstraction.arcs if not a.is_line)
    arc_number = {i: n for n, i in enumerate(i for i, a in enumerate(abstraction.arcs) if not a.is_line)}
    circles = abstraction.golden_circles
    index = {c: i for i, c in enumerate(circles)}
    circle_docs = [{"cx": float(c.cx), "cy": float(c.cy), "r": float(c.r), "k": int(c.k)} for c in circles]  # type: ignore[arg-type]

    arc_docs = [
        {"circle": index[a.circle], "theta0": float(a.theta0), "sweep": min(TAU, max(-TAU, float(a.sweep)))}
        for a in arcs
    ]

    # Without the connectivity constraint (Fig. 11c) arcs need not meet at their
    # junction: an arc whose end is not at the junction point gets its own
    # junction at that end, so the document keeps the contract.
    unconnected = not abstraction.connected
    junction_docs = []
    for j, point in enumerate(abstraction.junctions):
        kept: list[int] = []
        loose: list[dict[str, Any]] = []
        for ai in abstraction.arcs_at(j):  # an arc passing through the junction is not listed
            if ai not in arc_number:
                continue  # a straight line: recorded in extra.lines
            ai = arc_number[ai]
            if ai in kept or any(ai in d["arcs"] for d in loose):
                continue
            end = _nearest_end(arc_docs[ai], circle_docs[arc_docs[ai]["circle"]], point)
            if unconnected and math.hypot(end[0] - point[0], end[1] - point[1]) > JUNCTION_TOLERANCE / 2:
                loose.append({"x": end[0], "y": end[1], "arcs": [ai]})
            else:
                kept.append(ai)
        if kept:
            junction_docs.append({"x": float(point[0]), "y": float(point[1]), "arcs": kept})
        junction_docs.extend(loose)

    all_segments = [list(segs) for segs in abstraction.arc_segments]
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
        "width": abstraction.width,
        "height": abstraction.height,
        "phi": PHI,
        "bias": abstraction.bias,
        "circles": circle_docs,
        "arcs": arc_docs,
        "junctions": junction_docs,
        "level": abstraction.level,
        "similarity": abstraction.similarity,
        "tolerance": abstraction.tolerance,
        "params": merged,
        "extra": {"arc_segments": arc_segments, **({"lines": line_docs} if line_docs else {})},
    }
    symmetry = symmetry_extra(circles, merged)
    if symmetry is not None:  # a symmetric logo: the axis, and the circles paired with their mirror images
        doc["extra"]["symmetry"] = symmetry
    if isinstance(abstraction.ladder, FibonacciLadder):
        doc["ladder"] = "fibonacci"
        doc["unit"] = float(abstraction.ladder.unit)
    if fill_list is not None:
        doc["fills"] = [f.to_json() for f in fill_list]
    if check:
        _check_invariants(doc)
    return doc


def from_document(doc: Mapping[str, Any]) -> Abstraction:
    """The abstraction stored in an ``img2logo.abstraction/1`` document.

    The document is validated first: against the packaged JSON Schema (with
    jsonschema) and against the contract's invariants.
    Round trip: ``from_document(to_document(a))`` has the same circles, arcs,
    ``arc_segments``, parameters and ladder as ``a``, and its junctions are those of
    ``a`` that had an arc ending there, each listing those arcs. The ladder is the
    top-level ``ladder``, ``bias`` and ``unit`` (with the ``exponents`` and
    ``rounding`` that ``params`` records); each arc's junctions are found at its
    ends; ``extra`` keys other than ``arc_segments`` and ``lines`` are not kept,
    and ``fills`` are read by :func:`read_fills`.

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
    _check_counts(d)
    try:
        _check_schema(d)
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
        return Abstraction(
            level=int(d["level"]),
            arcs=arcs,
            arc_segments=arc_segments,
            junctions=junctions.reshape(-1, 2),
            junction_arcs=junction_arcs,
            similarity=float(d["similarity"]),
            bias=float(d["bias"]),
            tolerance=float(d["tolerance"]),
            width=_whole(d["width"], "width"),
            height=_whole(d["height"], "height"),
            params=params,
            ladder=_document_ladder(d, params),
        )
    except InvalidParameterError:
        raise
    except RecursionError as exc:  # params nested hundreds deep: copying them recurses
        raise InvalidParameterError(f"not a valid {FORMAT_NAME} document: nested too deeply") from exc
    except (KeyError, TypeError, ValueError, IndexError, AttributeError, OverflowError) as exc:
        raise InvalidParameterError(f"not a valid {FORMAT_NAME} document: {type(exc).__name__}: {exc}") from exc


def _whole(value: object, name: str) -> int:
    """A document's integer field: an int or a float of integer value (``512.0``), not 1e308 made an int."""
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise InvalidParameterError(f"{name} must be an integer, got {value!r}")
    if isinstance(value, float) and not (value.is_integer() and abs(value) <= 2**53):
        raise InvalidParameterError(f"{name} must be an integer, got {value!r}")
    return int(value)


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
    """
    if not isinstance(doc, Mapping):
        raise InvalidParameterError(f"document must be a JSON object (mapping), got {type(doc).__name__}")
    d = dict(doc)
    _check_counts(d)
    _check_schema(d)
    try:
        _check_invariants(d)
    except OverflowError as exc:
        raise InvalidParameterError(f"not a valid {FORMAT_NAME} document: {type(exc).__name__}: {exc}") from exc


def read_fills(source: Mapping[str, Any] | str | os.PathLike[str]) -> tuple[Fill, ...]:
    """The coloured regions (``fills`` key, paper Fig. 18) of a document or JSON file.

    Pass them on to :func:`img2logo.export.writers.write_svg` or ``write_png`` with the abstraction
    from :func:`from_document` / :func:`img2logo.export.writers.read_json`. Each comes back as a plain
    :class:`img2logo.design.fills.Fill` (its path and ``#rrggbb`` colour; no gradient
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
        path is not SVG path data that :func:`img2logo.geometry.svg_path.sample_path` reads.
    """
    if isinstance(source, Mapping):
        doc: Any = source
    else:
        p = as_path(source)
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


@lru_cache(maxsize=1)
def _schema() -> dict[str, Any]:
    """The packaged JSON Schema of the document (never read from outside the package)."""
    text = resources.files(__package__).joinpath(SCHEMA_RESOURCE).read_text(encoding="utf-8")
    return json.loads(text)


def _check_schema(doc: dict[str, Any]) -> None:
    """Validate ``doc`` against the packaged schema (jsonschema is imported here: only reading a document needs it)."""
    import jsonschema

    validator = jsonschema.Draft202012Validator(_schema())
    error = jsonschema.exceptions.best_match(validator.iter_errors(doc))
    if error is not None:
        where = "/".join(str(p) for p in error.absolute_path) or "(top level)"
        raise InvalidParameterError(f"document does not match the {FORMAT_NAME} schema at {where}: {error.message}")


#: The most circles, arcs or junctions a document may hold: a logo has tens to hundreds (the 67 images of
#: data/ and benchmarks/data/ at most 58 arcs); checking 10 000 circles takes about 1.5 s, and reading was
#: quadratic-free but linear, so a document of millions would take minutes (checked before any work).
MAX_DOCUMENT_ITEMS: int = 10_000


def _check_counts(doc: Mapping[str, Any]) -> None:
    """Raise InvalidParameterError if ``doc``'s circles, arcs, junctions or fills are over ``MAX_DOCUMENT_ITEMS``."""
    for key in ("circles", "arcs", "junctions", "fills"):
        items = doc.get(key)
        if isinstance(items, Sequence) and not isinstance(items, str) and len(items) > MAX_DOCUMENT_ITEMS:
            raise InvalidParameterError(
                f"{key} must have at most {MAX_DOCUMENT_ITEMS:,} entries (a logo has tens to hundreds), "
                f"got {len(items):,}"
            )


def _check_invariants(doc: Mapping[str, Any]) -> None:
    """Raise InvalidParameterError naming the first contract invariant ``doc`` breaks."""
    if doc.get("format") != FORMAT_NAME:
        raise InvalidParameterError(f"format must be {FORMAT_NAME!r}, got {doc.get('format')!r}")
    phi = float(doc["phi"])
    bias = float(doc["bias"])
    on_fibonacci = doc.get("ladder", "phi") == "fibonacci"
    unit = float(doc["unit"]) if on_fibonacci else 0.0
    circles = doc["circles"]
    for i, c in enumerate(circles):
        r, k = float(c["r"]), int(c["k"])
        if on_fibonacci:
            if not 1 <= k <= FIBONACCI_MAX_INDEX:  # before F(k), whose exact integer is quadratic in k
                raise InvalidParameterError(
                    f"circle {i}: k={k} is not a Fibonacci index of a float radius (1 <= k <= {FIBONACCI_MAX_INDEX})"
                )
            expected, rule = unit * fibonacci(k), f"unit*F(k) (k={k}, unit={unit!r})"
        else:
            try:
                expected, rule = phi ** (k + bias), f"phi**(k+bias) (k={k}, bias={bias!r})"
            except OverflowError:
                size = str(k) if abs(k) < 10**15 else f"about 10**{len(str(abs(k))) - 1}"
                raise InvalidParameterError(
                    f"circle {i}: k={size} gives phi**(k+bias) beyond any float radius (bias={bias!r})"
                ) from None
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
            ex, ey = _nearest_end(a, c, np.array([x, y]))
            gap = math.hypot(x - ex, y - ey)
            if not gap <= tol:
                raise InvalidParameterError(
                    f"junction {j}: arc {ai} has no end point at ({x:.6g}, {y:.6g}): its nearest end is "
                    f"{gap:.3g} px away, more than {tol:g} px"
                )


def _nearest_end(arc: Mapping[str, Any], circle: Mapping[str, Any], point: np.ndarray) -> tuple[float, float]:
    """The end point of a document arc (as the contract computes it) nearest ``point``, px."""
    cx, cy, r = float(circle["cx"]), float(circle["cy"]), float(circle["r"])
    t0 = float(arc["theta0"])
    ends = [(cx + r * math.cos(t), cy + r * math.sin(t)) for t in (t0, t0 + float(arc["sweep"]))]
    return min(ends, key=lambda e: math.hypot(e[0] - float(point[0]), e[1] - float(point[1])))


def _document_ladder(doc: Mapping[str, Any], params: Mapping[str, Any]) -> Ladder:
    """The ladder of a document: Fibonacci with its ``unit`` or phi with its ``bias``.

    The exponents and rounding a run recorded in ``params`` are kept when they
    are valid (an edit may then use them); otherwise the whole ladder.
    """
    exponents = params.get("exponents")
    if not (isinstance(exponents, list) and exponents and all(type(k) is int for k in exponents)):
        exponents = None
    rounding = params.get("rounding") if params.get("rounding") in ("nearest", "ceil") else "nearest"
    if doc.get("ladder") == "fibonacci":
        if exponents is not None and min(exponents) < 2:
            exponents = None
        return FibonacciLadder(float(doc["unit"]), exponents, rounding)  # type: ignore[arg-type]
    return GoldenLadder(float(doc["bias"]), exponents, rounding)  # type: ignore[arg-type]


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
