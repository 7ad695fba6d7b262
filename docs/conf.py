"""Sphinx configuration of the img2logo docs site (``make docs`` -> build/docs/)."""

from __future__ import annotations

import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

import img2logo  # noqa: E402

project = "img2logo"
author = "The img2logo developers"
copyright = "2026, The img2logo developers"
release = img2logo.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_parser",
]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
myst_enable_extensions = ["dollarmath"]
# The README's headings are linked to from its own text.
myst_heading_anchors = 3
autosummary_generate = True
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_member_order = "bysource"
# numpydoc: the docstrings' sections; no table of every class member (autodoc lists them).
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()
exclude_patterns = ["_build"]
html_theme = "alabaster"
html_title = f"img2logo {release}"
# The site reads offline: MathJax from the notebooks' local copy when make html made it.
# The package re-exports its values (img2logo.Abstraction is img2logo.geometry.primitives.Abstraction):
# a cross-reference finds both; either is right.
suppress_warnings = ["myst.header", "myst.xref_missing", "ref.python"]
nitpicky = False

# The executed notebooks' offline pages (make html), copied to the site's root, and their list.
_pages = sorted((ROOT / "build" / "html").glob("*.html"))
html_extra_path = [str(ROOT / "build" / "html")] if _pages else []
_list = (
    "\n".join(f'- <a href="{p.name}">{p.stem}</a>' for p in _pages)
    if _pages
    else "None yet: run `make figures` and `make html`, then `make docs` again."
)
(Path(__file__).parent / "_notebooks.md").write_text(_list + "\n", encoding="utf-8")

# Math offline too: MathJax 2 from jupyter-server-mathjax (as make html), into _static/.
import jupyter_server_mathjax  # noqa: E402

html_static_path = [str(Path(jupyter_server_mathjax.__file__).parent / "static")]
mathjax_path = "MathJax.js?config=TeX-AMS-MML_HTMLorMML-full"
mathjax2_config = {"HTML-CSS": {"availableFonts": [], "preferredFont": None, "webFont": "STIX-Web"}}


# The docstrings write sizes and norms as in the paper, |S|, |r1 - r2|: in reStructuredText a word
# between bars is a substitution, which the docstrings never mean. Bars outside inline literals
# are escaped, so they show as written (a grid table or line block, a bar and a space, is left alone).
_BARS = re.compile(r"\|([^|`\n]+)\|")


def _literal_bars(app, what, name, obj, options, lines) -> None:
    for i, line in enumerate(lines):
        if line.lstrip().startswith(("| ", "+-", "+=")):  # a line block or a grid table's row
            continue
        parts = re.split(r"(``[^`]*``|`[^`]*`)", line)
        lines[i] = "".join(p if p.startswith("`") else _BARS.sub(r"\\|\1\\|", p) for p in parts)


def setup(app) -> None:
    # Before numpydoc (priority 500) turns the sections into reStructuredText.
    app.connect("autodoc-process-docstring", _literal_bars, priority=400)
