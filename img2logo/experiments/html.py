"""Executed notebooks as HTML pages that read offline (``make html``).

:func:`export_html` turns an executed notebook (``build/notebooks/<name>.ipynb``)
into ``build/html/<name>.html`` with nbconvert's ``lab`` template, and makes it
independent of the network: the figures are embedded (they are in the notebook
already), the template's CSS is inline, the math is typeset by a local MathJax
(2.7, from the ``jupyter-server-mathjax`` package, copied once to
``build/html/mathjax/``) drawing SVG paths (no web font to fetch), and the
scripts a page of plots does not need (require.js, jQuery, the widget manager:
the level explorer's widgets need a kernel anyway) are left out. A line at the
top links back to the docs site's notebooks index (``make docs`` puts the pages
beside it) and names the paper figure or table the notebook reproduces. nbconvert and
jupyter-server-mathjax are the extra ``[html]``, installed by ``make html``.
"""

from __future__ import annotations

import os
import re
import shutil
from pathlib import Path

from ..errors import InvalidParameterError

__all__ = ["MATHJAX_DIR", "export_html", "external_references"]

#: The folder, beside the pages, that holds the local MathJax.
MATHJAX_DIR = "mathjax"
# TeX in, SVG out: MathJax's SVG output draws the glyphs from its own JavaScript font
# data, so nothing is fetched as a web font (a file:// page may not load one).
_MATHJAX_CONFIG = "TeX-AMS-MML_HTMLorMML-full,Safe"
_FONT_CONFIG = (
    '<script type="text/x-mathjax-config">'
    'MathJax.Hub.Config({"HTML-CSS": {availableFonts: [], preferredFont: null, webFont: "STIX-Web", '
    'imageFont: null}, showMathMenu: false, messageStyle: "none"});'
    "</script>"
)
_EXTERNAL = re.compile(r"""(?:src|href)\s*=\s*["'](?:https?:)?//[^"']+["']|@import\s+url\(\s*["']?(?:https?:)?//""")


def external_references(html: str) -> list[str]:
    """The network references of a page: ``src``/``href`` to http(s) or ``//`` URLs, CSS ``@import`` of
    one, and URL strings in scripts.

    Links a reader clicks (``<a href>``) are not loads and are not listed.
    """
    found = []
    for m in _EXTERNAL.finditer(html):
        start = html.rfind("<", 0, m.start())
        if html[start : start + 2].lower() == "<a":
            continue
        found.append(m.group(0))
    for script in re.findall(r"<script\b[^>]*>(.*?)</script>", html, flags=re.S | re.I):
        found.extend(re.findall(r"""["'](?:https?:)?//[^"']+["']""", script))  # a URL a script may load
    return found


def export_html(notebook: str | os.PathLike[str], output_dir: str | os.PathLike[str]) -> Path:
    """Write ``output_dir/<notebook stem>.html``, readable offline; return its path.

    Parameters
    ----------
    notebook : str or path-like
        An executed notebook (``.ipynb``).
    output_dir : str or path-like
        The folder of the pages; its ``mathjax/`` is made on first use.

    Raises
    ------
    InvalidParameterError
        If the notebook does not exist, or the page would still load something
        from the network (a notebook output that links a script or style).
    """
    import jupyter_server_mathjax
    import nbformat
    from nbconvert import HTMLExporter

    from .._io import atomic_write

    source = Path(notebook)
    if not source.is_file():
        raise InvalidParameterError(f"notebook not found: {source}")
    out = Path(output_dir)
    mathjax = out / MATHJAX_DIR
    if not (mathjax / "MathJax.js").is_file():
        static = Path(jupyter_server_mathjax.__file__).parent / "static"
        partial = out / f".{MATHJAX_DIR}.part"
        shutil.rmtree(partial, ignore_errors=True)
        shutil.copytree(static, partial)
        shutil.rmtree(mathjax, ignore_errors=True)
        partial.rename(mathjax)
    exporter = HTMLExporter(
        template_name="lab",
        mathjax_url=f"{MATHJAX_DIR}/MathJax.js?config={_MATHJAX_CONFIG}",
        require_js_url="",
        jquery_url="",
        widget_renderer_url="",
        jupyter_widgets_base_url="",
        embed_images=True,
    )
    nb = nbformat.read(source, as_version=4)
    nb.metadata.get("widgets", {}).pop("application/vnd.jupyter.widget-state+json", None)
    body, _ = exporter.from_notebook_node(nb)
    body = _strip_network_scripts(body)
    body = body.replace("<head>", "<head>\n" + _FONT_CONFIG, 1)
    body = re.sub(r"(<body[^>]*>)", lambda m: m.group(1) + "\n" + _back_link(source.stem), body, count=1)
    left = external_references(body)
    if left:
        raise InvalidParameterError(f"{source.name}: the page would still load from the network: {left[0]}")
    return atomic_write(out / f"{source.stem}.html", lambda f: f.write(body.encode("utf-8")))


def _back_link(name: str) -> str:
    """The line at a page's top: back to the docs site's notebooks index, and what the notebook reproduces."""
    from html import escape

    from .runner import PAPER_ITEMS

    item = PAPER_ITEMS.get(name)
    what = f" · {escape(name)} reproduces {escape(item[0])} of the paper" if item else ""
    return (
        '<p style="font: 14px sans-serif; margin: 8px 16px;">'
        f'<a href="notebooks.html">← the notebooks of img2logo</a>{what}</p>'
    )


def _strip_network_scripts(html: str) -> str:
    """Remove ``<script src>`` tags the settings left empty or on a CDN, and the widget state and manager."""
    html = re.sub(r"<script[^>]*\bsrc\s*=\s*[\"'][\"'][^>]*>\s*</script>", "", html)
    html = re.sub(r"<script[^>]*\bsrc\s*=\s*[\"'](?:https?:)?//[^\"']+[\"'][^>]*>\s*</script>", "", html)
    # The template's mermaid loader imports its library from a CDN when a diagram is on the
    # page; the notebooks have none.
    html = re.sub(r'<script type="module">(?:(?!</script>).)*mermaid(?:(?!</script>).)*</script>', "", html, flags=re.S)
    return re.sub(r'<script type="application/vnd\.jupyter\.widget-state\+json">.*?</script>', "", html, flags=re.S)


def main(argv: list[str] | None = None) -> int:
    """``python -m img2logo.experiments.html NOTEBOOK.ipynb OUTPUT_DIR`` (``make html``); errors in one line."""
    import sys

    args = sys.argv[1:] if argv is None else argv
    if len(args) != 2:
        print("usage: python -m img2logo.experiments.html NOTEBOOK.ipynb OUTPUT_DIR", file=sys.stderr)
        return 2
    try:
        path = export_html(args[0], args[1])
    except ImportError as exc:
        print(f"html: error: {exc.name} is missing: install the extra [html] (make html does)", file=sys.stderr)
        return 2
    except InvalidParameterError as exc:
        print(f"html: error: {exc}", file=sys.stderr)
        return 2
    print(f"wrote {path}")
    return 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
