"""The studio's download links: ``<a download>`` anchors carrying the files of the logo shown as ``data:`` URLs.

They work in Voila and in JupyterLab with no JavaScript of ours, and are named after the
image, the level and whether it was edited (:meth:`~.outputs.StudioFiles.download_names`).
"""

from __future__ import annotations

import base64
import html

from ..errors import Img2LogoError
from .session import Studio

#: What each download link says, by :data:`~.session.DOWNLOAD_FORMATS` key (the PNG over the input is left to
#: the command line: a logo to place is on white or on nothing).
DOWNLOAD_LABELS = {
    "svg": "SVG",
    "pdf": "PDF",
    "png": "PNG (white)",
    "png-transparent": "PNG (transparent)",
    "json": "JSON",
}
DOWNLOAD_TYPES = {
    "svg": "image/svg+xml",
    "json": "application/json",
    "pdf": "application/pdf",
    "png": "image/png",
    "png-transparent": "image/png",
}


def pending_html() -> str:
    """The download links replaced by their names, greyed: what they hold is being made anew."""
    names = DOWNLOAD_LABELS.values()
    return "".join(
        f'<span class="studio-download studio-pending" title="being made">{html.escape(n)}</span>' for n in names
    )


def downloads_html(studio: Studio) -> str:
    """The download links of ``studio``'s logo shown (or why there are none), as HTML."""
    s = studio
    if s.shown is None:
        return "<i>Run first: the downloads are the logo shown.</i>"
    formats = tuple(DOWNLOAD_LABELS)
    try:
        files = s.downloads(formats)
    except Img2LogoError as exc:  # said on the page; the drawing stays
        return f'<span class="studio-error">{html.escape(str(exc))}</span>'
    names = s.download_names(formats)
    links = []
    for fmt, label in DOWNLOAD_LABELS.items():
        data = base64.b64encode(files[fmt]).decode("ascii")
        links.append(
            f'<a class="studio-download" download="{html.escape(names[fmt])}" title="{html.escape(names[fmt])}" '
            f'href="data:{DOWNLOAD_TYPES[fmt]};base64,{data}">{html.escape(label)}</a>'
        )
    return "".join(links)


__all__ = ["DOWNLOAD_LABELS", "DOWNLOAD_TYPES", "downloads_html", "pending_html"]
