"""Result files: the ``img2logo.abstraction/1`` JSON document, SVG, PNG and PDF, and :func:`write`, which writes any.

The SVG writer is :mod:`img2logo.export.svg`, the drawn files' (PNG, PDF) :mod:`img2logo.export.figures`;
their names are importable from here, where the command line, the batch and the studio take them.

The JSON document is the stable record of a result (its contract, made and
checked by :mod:`img2logo.export.contract`). The SVG is for designers: one exact
elliptical-arc ``<path>`` per arc in an "Arcs" layer (path data by
:mod:`img2logo.geometry.svg_path`), and the golden circles in a hidden, locked and clipped
"Golden circles" construction layer that Inkscape shows as a layer to toggle, and,
when given, the coloured regions of :mod:`img2logo.design.fills` (paper Fig. 18) in a
"Fills" layer under everything else (also the document's ``fills`` key and the
PNG). The PNGs are drawn with :mod:`img2logo.export.plotting` on matplotlib's Agg
canvas, ``width`` x ``height`` px of the input image (times a scale), over the
faded input, on white or transparent; the PDF is vector, drawn by matplotlib's
PDF backend, 1 px = 1 pt.

Every writer is atomic and deterministic: the bytes go to a temporary file in the
target's directory that is then renamed over the target (:func:`os.replace`), so a
file is written whole or not at all; missing parent directories are created; the
same input always gives byte-identical files (sorted JSON keys, ``repr`` floats, SVG
written by hand with fixed decimals, PNG without timestamp or software metadata).
Inside :func:`output_set` the files of a run appear together at its end, or none
of them. A path that cannot be written raises :class:`~img2logo.errors.OutputError`
naming it; :func:`check_output_paths` finds most such paths, and outputs that
are inputs, before any work (both from :mod:`img2logo._io`, with the atomic write).

Coordinates are input-image pixels: x right, y down, angles from +x towards +y, so
a positive sweep is clockwise on screen, SVG's ``sweep-flag = 1``.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .._io import as_path, atomic_write, check_output_paths, output_set
from .._validation import check_choice
from ..errors import InputNotFoundError, InvalidParameterError
from ..geometry.abstraction import Abstraction

if TYPE_CHECKING:
    from ..design.fill_values import Fill

from .figures import (
    PNG_BACKGROUNDS,
    pdf_bytes,
    png_bytes,
    png_size,
    save_figure,
    write_pdf,
    write_png,
    write_segment_graph_png,
)
from .formats import FORMAT_SUFFIXES, check_format_suffix
from .svg import SVG_METADATA_NS, to_svg, write_svg

__all__ = [
    "FORMAT_SUFFIXES",
    "LEVEL_FORMATS",
    "PNG_BACKGROUNDS",
    "SVG_METADATA_NS",
    "check_format_suffix",
    "check_output_paths",
    "encode",
    "json_bytes",
    "output_set",
    "pdf_bytes",
    "png_bytes",
    "png_size",
    "read_json",
    "save_figure",
    "to_svg",
    "write",
    "write_json",
    "write_pdf",
    "write_png",
    "write_segment_graph_png",
    "write_svg",
    "write_table",
]


def read_json(path: str | os.PathLike[str]) -> Abstraction:
    """Read an ``img2logo.abstraction/1`` JSON file written by :func:`write_json`.

    Raises
    ------
    InputNotFoundError
        If there is no such file (an Img2LogoError and a FileNotFoundError).
    InvalidParameterError
        If it is a folder, cannot be read, is not UTF-8 JSON or not a valid document
        (see :func:`img2logo.export.contract.from_document`).

    Examples
    --------
    >>> from img2logo import abstract, data, read_json, write_json
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> path = write_json(abstract(image, progress=False).final, "ring.json")
    >>> logo = read_json("ring.json")
    >>> round(logo.arcs[0].circle.r, 1), logo.arcs[0].circle.k
    (50.0, 8)
    """
    import json  # the JSON document's modules load with its first reader or writer, not for an SVG

    from .contract import from_document

    p = as_path(path)
    if not p.exists():
        raise InputNotFoundError(f"JSON file not found: {p}")
    if p.is_dir():
        raise InvalidParameterError(f"{p} is a folder, not a JSON file")
    if not p.is_file():  # a FIFO would block the read
        raise InvalidParameterError(f"{p} is not a regular file (a device, a pipe, ...), not a JSON file")
    try:
        text = p.read_text(encoding="utf-8")
    except UnicodeDecodeError as exc:
        raise InvalidParameterError(f"{p} is not JSON: not UTF-8 text ({exc.reason} at byte {exc.start})") from exc
    except OSError as exc:
        raise InvalidParameterError(f"{p}: cannot read the file: {exc.strerror or exc}") from exc
    try:
        doc = json.loads(text)
    except ValueError as exc:  # JSONDecodeError, or an integer of more than 4300 digits
        raise InvalidParameterError(f"{p} is not JSON: {exc}") from exc
    except RecursionError as exc:  # arrays or objects nested thousands deep
        raise InvalidParameterError(f"{p} is not a valid document: JSON nested too deeply") from exc
    return from_document(doc)


def write_json(
    abstraction: Abstraction,
    path: str | os.PathLike[str],
    params: Mapping[str, Any] | None = None,
    *,
    check: bool = False,
    fills: Sequence[Fill] | None = None,
) -> Path:
    """Write the ``img2logo.abstraction/1`` document of ``abstraction`` (:func:`~img2logo.export.contract.to_document`).

    UTF-8 JSON with sorted keys, two-space indentation and a final newline; floats
    are written with Python's ``repr``, so they read back exactly. Atomic.
    ``fills`` (:mod:`img2logo.design.fills`) go into the ``fills`` key; read them back
    with :func:`img2logo.export.contract.read_fills`.

    Returns
    -------
    pathlib.Path
        The path of the JSON document.

    Examples
    --------
    >>> from img2logo import abstract, data, read_json, write_json
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> result = abstract(image, progress=False)
    >>> write_json(result.final, "ring.json", result.params).name
    'ring.json'
    >>> len(read_json("ring.json").arcs)
    1
    """
    check_format_suffix(path, "json")
    data = json_bytes(abstraction, params, check=check, fills=fills)
    return atomic_write(path, lambda f: f.write(data))


def json_bytes(
    abstraction: Abstraction,
    params: Mapping[str, Any] | None = None,
    *,
    check: bool = False,
    fills: Sequence[Fill] | None = None,
) -> bytes:
    """The bytes of the JSON document :func:`write_json` writes (the same parameters, without the path)."""
    import json

    from .contract import to_document

    doc = to_document(abstraction, params, check=check, fills=fills)
    text = json.dumps(doc, indent=2, sort_keys=True, allow_nan=False, ensure_ascii=False) + "\n"
    # A file name of bytes that are not UTF-8 holds surrogate escapes (PEP 383): written as JSON's own
    # escape (\udce9), valid UTF-8 that json.loads reads back as the same name.
    return text.encode("utf-8", errors="backslashreplace")


#: The formats :func:`write` writes a level in.
LEVEL_FORMATS: tuple[str, ...] = ("json", "svg", "pdf", "png")


def write(
    level: Abstraction,
    path: str | os.PathLike[str],
    format: str,
    *,
    fills: Sequence[Fill] | None = None,
    image: np.ndarray | None = None,
    background: str | None = None,
    scale: float | None = None,
) -> Path:
    """Write ``level`` to ``path`` in ``format``: the one way the command line, the batch and the studio write a level.

    Parameters
    ----------
    level : Abstraction
        The level to write.
    path : str or path-like
        Target file, its suffix the format's; parent directories are created.
    format : {"json", "svg", "pdf", "png"}
        :func:`write_json`, :func:`write_svg`, :func:`write_pdf` or :func:`write_png`.
    fills : sequence of img2logo.design.fills.Fill, optional
        Coloured regions (paper Fig. 18).
    image, background, scale
        The PNG's (:func:`write_png`); the other formats do not draw the input.

    Returns
    -------
    pathlib.Path
        The path of the file in ``format``.

    Raises
    ------
    InvalidParameterError
        If ``format`` is none of ``LEVEL_FORMATS``, or the writer refuses a value.
    """
    check_choice(format, "format", LEVEL_FORMATS)
    check_format_suffix(path, format)
    data = encode(level, format, fills=fills, image=image, background=background, scale=scale)
    return atomic_write(path, lambda f: f.write(data))


def encode(
    level: Abstraction,
    format: str,
    *,
    fills: Sequence[Fill] | None = None,
    image: np.ndarray | None = None,
    background: str | None = None,
    scale: float | None = None,
) -> bytes:
    """The bytes :func:`write` writes for ``level`` in ``format``, kept in memory (no file).

    The batch's workers make their files so and hand them back as bytes: the same
    bytes as :func:`write`'s file, with no temporary file written, synced and read back.

    Parameters
    ----------
    level : Abstraction
        The level to encode.
    format : {"json", "svg", "pdf", "png"}
        As :func:`json_bytes`, :func:`~img2logo.export.svg.to_svg` (UTF-8),
        :func:`~img2logo.export.figures.pdf_bytes` or :func:`~img2logo.export.figures.png_bytes`.
    fills, image, background, scale
        As in :func:`write`.

    Returns
    -------
    bytes

    Raises
    ------
    InvalidParameterError
        If ``format`` is none of ``LEVEL_FORMATS``, or the encoder refuses a value.
    """
    check_choice(format, "format", LEVEL_FORMATS)
    if format == "json":
        return json_bytes(level, fills=fills)
    if format == "svg":
        return to_svg(level, fills=fills).encode("utf-8")
    if format == "pdf":
        return pdf_bytes(level, fills=fills)
    return png_bytes(level, image=image, fills=fills, background=background, scale=scale)


def write_table(table: Any, path: str | os.PathLike[str]) -> Path:
    """Write a pandas DataFrame as CSV (no index), whole or not at all.

    UTF-8; a file name of bytes that are not UTF-8 (surrogate escapes, PEP 383) is written as its own bytes.
    """
    text = table.to_csv(index=False, lineterminator="\n", float_format="%.6g")
    return atomic_write(path, lambda f: f.write(text.encode("utf-8", "surrogateescape")))
