"""The library's modules import each other without a cycle (every import statement counts, also inside functions)."""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

PACKAGE = Path(__file__).resolve().parents[1] / "img2logo"


def _imports() -> dict[str, set[str]]:
    """Module -> the img2logo modules it imports (TYPE_CHECKING blocks aside); the notebook layer is left out."""
    modules = {p.stem: p for p in PACKAGE.glob("*.py") if p.stem != "__init__"}
    graph: dict[str, set[str]] = {}
    for name, path in modules.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        typing_only = {
            id(n)
            for node in ast.walk(tree)
            if isinstance(node, ast.If) and getattr(node.test, "id", getattr(node.test, "attr", "")) == "TYPE_CHECKING"
            for sub in node.body
            for n in ast.walk(sub)
        }
        found = set()
        for node in ast.walk(tree):
            if id(node) in typing_only or not isinstance(node, ast.ImportFrom) or node.level != 1:
                continue
            if node.module:  # from .x import y
                found.add(node.module.split(".")[0])
            else:  # from . import x, y
                found.update(a.name for a in node.names)
        graph[name] = {m for m in found if m in modules and m != name}
    return graph


def _cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import cycle of ``graph`` (its modules in order, the first repeated at the end), or None."""
    state: dict[str, int] = {}  # 1 on the path, 2 done
    path: list[str] = []

    def visit(v: str) -> list[str] | None:
        state[v] = 1
        path.append(v)
        for w in sorted(graph[v]):
            if state.get(w) == 1:
                return [*path[path.index(w) :], w]
            if w not in state and (found := visit(w)):
                return found
        state[v] = 2
        path.pop()
        return None

    for v in sorted(graph):
        if v not in state and (found := visit(v)):
            return found
    return None


def test_no_import_cycle():
    graph = _imports()
    assert {"fills", "plotting", "writers", "contract", "arrangement", "svg_path"} <= set(graph)
    assert "plotting" in graph["writers"] and "fill_values" in graph["plotting"]  # the graph is read
    assert _cycle(graph) is None, " -> ".join(_cycle(graph) or [])


def test_a_cycle_is_found():
    assert _cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": set()}) == ["a", "b", "c", "a"]
    assert _cycle({"a": {"b"}, "b": set()}) is None


#: What the file format needs to read and write an ``img2logo.abstraction/1`` document: the values
#: (geometry, its ladders, fills, the mirror axis), their checks, the SVG path data and atomic writes.
CONTRACT_MODULES = {
    "img2logo",
    "img2logo._io",
    "img2logo._validation",
    "img2logo.constants",
    "img2logo.contract",
    "img2logo.errors",
    "img2logo.fill_values",
    "img2logo.geometry",
    "img2logo.golden_ladder",
    "img2logo.mirror",
    "img2logo.svg_path",
}


def test_the_file_format_loads_only_what_it_needs():
    code = "import sys, img2logo.contract; print(sorted(m for m in sys.modules if m.startswith('img2logo')))"
    out = subprocess.run([sys.executable, "-c", code], cwd=PACKAGE.parent, capture_output=True, text=True, check=True)
    loaded = set(ast.literal_eval(out.stdout))
    assert loaded <= CONTRACT_MODULES, sorted(loaded - CONTRACT_MODULES)
    assert "img2logo.contract" in loaded and "img2logo.fill_values" in loaded  # the list is read
