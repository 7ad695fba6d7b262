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
# The pages link to their own headings.
myst_heading_anchors = 3
autosummary_generate = True
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
autodoc_member_order = "bysource"
# numpydoc: the docstrings' sections; no table of every class member (autodoc lists them).
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()
exclude_patterns = ["_build", "_notebooks.md", "_contents.md"]
html_theme = "alabaster"
html_title = f"img2logo {release}"
# A wider page than alabaster's 940 px, still within a 1366 px window.
html_theme_options = {"page_width": "1200px"}
# The site reads offline: MathJax from the notebooks' local copy when make html made it.
# The package re-exports its values (img2logo.Abstraction is img2logo.geometry.abstraction.Abstraction):
# a cross-reference finds both; either is right.
suppress_warnings = ["ref.python"]
nitpicky = False

# The executed notebooks' offline pages (make html), copied to the site's root, and their index:
# each notebook with the paper figure or table it reproduces, linked to its page when it exists.
from img2logo.experiments.runner import PAPER_ITEMS  # noqa: E402

_pages = {p.stem for p in (ROOT / "build" / "html").glob("*.html")}
html_extra_path = [str(ROOT / "build" / "html")] if _pages else []
_rows = ["| notebook | reproduces | shows |", "| --- | --- | --- |"]
for _name, (_item, _shows) in PAPER_ITEMS.items():
    _cell = f'<a href="{_name}.html"><code>{_name}</code></a>' if _name in _pages else f"`{_name}`"
    _rows.append(f"| {_cell} | {_item} | {_shows} |")
if not _pages:
    _rows.append("\nNo page built yet: run `make figures` and `make html`, then `make docs` again.")
(Path(__file__).parent / "_notebooks.md").write_text("\n".join(_rows) + "\n", encoding="utf-8")

# The site's contents; the performance page is written by make bench (benchmarks/bench.py), and
# listed once it exists.
_contents = ["guide/index", "how-it-works", "notebooks", "design/index", "quality", "performance", "api"]
_contents = [c for c in _contents if c != "performance" or (Path(__file__).parent / "performance.md").is_file()]
(Path(__file__).parent / "_contents.md").write_text(
    "```{toctree}\n:maxdepth: 2\n\n" + "\n".join(_contents) + "\n```\n", encoding="utf-8"
)

# Math offline too: MathJax 2 from jupyter-server-mathjax (as make html), into _static/.
import jupyter_server_mathjax  # noqa: E402

html_static_path = [str(Path(jupyter_server_mathjax.__file__).parent / "static"), "_static"]
html_css_files = ["img2logo.css"]
mathjax_path = "MathJax.js?config=TeX-AMS-MML_HTMLorMML-full"
mathjax2_config = {"HTML-CSS": {"availableFonts": [], "preferredFont": None, "webFont": "STIX-Web"}}


# The docstrings write sizes and norms as in the paper, |S|, |r1 - r2|: in reStructuredText a word
# between bars is a substitution, which the docstrings never mean. Bars outside inline literals
# are escaped, so they show as written (a grid table or line block, a bar and a space, is left alone).
_BARS = re.compile(r"\|([^|`\n]+)\|")


# The paper's symbols with a superscript (E^s, A^t, |A^t|, phi^(k+sigma)) become math, typeset by
# MathJax: a one-letter base, then a word, a number or a bracketed expression.
_SUP = r"(?<![\w`\\])([A-Za-zφ])\^(\([^()\s]*\)|\{[^{}\s]*\}|[A-Za-z0-9]+)(?![\w^])"
_MATH = re.compile(rf"\|{_SUP}\||{_SUP}")


def _math(match: re.Match) -> str:
    bars = match.group(1) is not None
    base, sup = (match.group(1), match.group(2)) if bars else (match.group(3), match.group(4))
    sup = sup[1:-1] if sup[0] in "({" and len(sup) > 3 else sup.strip("{}")
    sup = sup.replace("σ", "\\sigma")
    tex = ("\\varphi" if base == "φ" else base) + "^{" + sup + "}"
    return ":math:`" + ("|" + tex + "|" if bars else tex) + "`"


def _literal_bars(app, what, name, obj, options, lines) -> None:
    for i, line in enumerate(lines):
        if line.lstrip().startswith(("| ", "+-", "+=")):  # a line block or a grid table's row
            continue
        parts = re.split(r"(:math:`[^`]*`|``[^`]*``|`[^`]*`)", line)
        parts = [p if p.startswith((":math:", "`")) else _MATH.sub(_math, p) for p in parts]
        parts = re.split(r"(:math:`[^`]*`|``[^`]*``|`[^`]*`)", "".join(parts))
        lines[i] = "".join(p if p.startswith((":math:", "`")) else _BARS.sub(r"\\|\1\\|", p) for p in parts)


def setup(app) -> None:
    # Before numpydoc (priority 500) turns the sections into reStructuredText.
    app.connect("autodoc-process-docstring", _literal_bars, priority=400)
