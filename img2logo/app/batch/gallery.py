"""The gallery of a batch run: ``OUTPUT_DIR/index.html``, every input beside its logo (beyond the paper).

:func:`gallery_html` makes one self-contained HTML page from a
:class:`~img2logo.app.batch.report.BatchReport`: a row per image, in input order, with the
input, the logo (its SVG, else its PNG), |A| (arcs), E^s (paper Eqn. 3, px), the
levels and the seconds it took; a failed image shows its one-line error. The
page has no script and loads nothing from the network: its style is inline and
the pictures are relative links to the files beside it and to the inputs, so it
opens offline, from the folder, in any browser (as long as the input folder
stays where it was relative to the output folder). An input a browser cannot
show (TIFF) is named instead of shown. :func:`write_gallery` writes it atomically.
"""

from __future__ import annotations

import html
import os
from pathlib import Path
from typing import TYPE_CHECKING
from urllib.parse import quote

from ..._io import atomic_write

if TYPE_CHECKING:
    from .report import BatchReport

__all__ = ["GALLERY_NAME", "gallery_html", "write_gallery"]


#: The gallery's file name in the output folder.
GALLERY_NAME = "index.html"
#: Inputs that browsers show in an ``<img>`` (lower-case suffixes); others are named only.
_SHOWN_SUFFIXES = (".png", ".jpg", ".jpeg", ".bmp", ".webp", ".gif")

_STYLE = """
body { font: 15px/1.4 system-ui, sans-serif; margin: 1.5em; color: #222; }
h1 { font-size: 1.4em; margin: 0 0 0.2em; }
p.note { color: #555; margin: 0 0 1em; }
table { border-collapse: collapse; }
th, td { padding: 6px 12px; border-bottom: 1px solid #ddd; text-align: left; vertical-align: middle; }
th { background: #f3f3f3; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
td.pic img { width: 240px; height: 240px; object-fit: contain; background: #fff; border: 1px solid #ccc; }
td.error { color: #a00; }
"""


def _link(target: str | os.PathLike[str], folder: Path) -> str:
    """``target`` as a URL relative to ``folder`` (forward slashes, escaped)."""
    rel = os.path.relpath(os.path.abspath(target), os.path.abspath(folder))
    return quote(os.fsencode(Path(rel).as_posix()))  # a name's own bytes, UTF-8 or not, %-escaped


def gallery_html(report: BatchReport, output_dir: str | os.PathLike[str], *, title: str | None = None) -> str:
    """The gallery page of ``report`` whose files are in ``output_dir`` (see the module docstring).

    Parameters
    ----------
    report : BatchReport
        What :func:`img2logo.app.batch.run.run_batch` did; its rows' ``outputs`` are the files linked.
    output_dir : str or path-like
        The folder the page is written to: the links are relative to it.
    title : str, optional
        The page's heading; default ``"img2logo: <n> logos"``.

    Returns
    -------
    str
        The HTML text.
    """
    folder = Path(output_dir)
    rows = {r.path: r for r in report.rows}
    failures = {f.path: f for f in report.failures}
    order = list(report.inputs) or [*rows, *failures]
    heading = title or f"img2logo: {len(report.rows)} logo{'s' if len(report.rows) != 1 else ''}"
    esc = html.escape
    body = []
    for path in order:
        name = esc(Path(path).name)
        if Path(path).suffix.lower() in _SHOWN_SUFFIXES:
            source = f'<img src="{_link(path, folder)}" alt="{name}" loading="lazy">'
        else:
            source = f"{name}<br>(not shown: browsers do not display {esc(Path(path).suffix)})"
        if path in rows:
            r = rows[path]
            pictures = [o for o in r.outputs if o.endswith(".svg")] or [o for o in r.outputs if o.endswith(".png")]
            logo = f'<img src="{_link(pictures[0], folder)}" alt="logo of {name}">' if pictures else "(no picture)"
            files = " ".join(f'<a href="{_link(o, folder)}">{esc(Path(o).suffix.lstrip("."))}</a>' for o in r.outputs)
            cells = (
                f'<td>{name}<br><small>{esc(r.kind)}</small></td><td class="pic">{source}</td>'
                f'<td class="pic">{logo}</td><td class="num">{r.arcs}</td><td class="num">{r.similarity:.2f}</td>'
                f'<td class="num">{r.levels}</td><td class="num">{r.seconds:.1f}</td><td>{files}</td>'
            )
        elif path in failures:  # its input may not be an image at all: named, not shown
            cells = (
                f'<td>{name}</td><td class="pic">{name}</td>'
                f'<td class="error" colspan="6">failed: {esc(failures[path].message)}</td>'
            )
        else:
            continue
        body.append(f"<tr>{cells}</tr>")
    total = sum(r.seconds for r in report.rows)
    note = (
        f"{len(report.rows)} of {len(order)} images done in {total:.1f} s of work. "
        "Arcs: |A| of the final level; E<sup>s</sup>: its similarity error (paper Eqn. 3), px."
    )
    head = (
        "<tr><th>image</th><th>input</th><th>logo</th><th>arcs</th><th>E<sup>s</sup> (px)</th>"
        "<th>levels</th><th>seconds</th><th>files</th></tr>"
    )
    return "\n".join(
        [
            "<!DOCTYPE html>",
            '<html lang="en">',
            '<head><meta charset="utf-8"><meta name="viewport" content="width=device-width, initial-scale=1">',
            f"<title>{esc(heading)}</title><style>{_STYLE}</style></head>",
            "<body>",
            f"<h1>{esc(heading)}</h1>",
            f'<p class="note">{note}</p>',
            "<table>",
            head,
            *body,
            "</table>",
            "</body>",
            "</html>",
            "",
        ]
    )


def write_gallery(report: BatchReport, output_dir: str | os.PathLike[str], *, title: str | None = None) -> Path:
    """Write :func:`gallery_html` to ``output_dir/index.html``, whole or not at all; return its path."""
    # A file name of bytes that are not UTF-8 (surrogate escapes) is shown with U+FFFD for them; its links
    # carry its bytes (_link).
    data = gallery_html(report, output_dir, title=title).encode("utf-8", "surrogateescape")
    data = data.decode("utf-8", "replace").encode("utf-8")
    return atomic_write(Path(output_dir) / GALLERY_NAME, lambda f: f.write(data))
