"""The library's modules import each other without a cycle.

Every import statement counts: inside functions, and under ``TYPE_CHECKING`` too (a type-only
import is a dependency a reader follows, and a circle of them is a design that leans both ways).
The notebook kit (``img2logo/experiments``) is covered with the library.
"""

from __future__ import annotations

import ast
import os
import subprocess
import sys
from pathlib import Path

import pytest
from helpers import modules_loaded

PACKAGE = Path(__file__).resolve().parents[1] / "img2logo"


def _module_name(path: Path) -> str:
    """``experiments/runner.py`` -> ``experiments.runner``; a package's ``__init__.py`` is the package."""
    parts = list(path.relative_to(PACKAGE).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts = parts[:-1]
    return ".".join(parts) or "img2logo"


def _imports() -> dict[str, set[str]]:
    """Module -> the img2logo modules it imports (``from . import x`` of a name, not a module: the package)."""
    paths = {_module_name(p): p for p in PACKAGE.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for name, path in paths.items():
        package = name.split(".") if path.name == "__init__.py" and name != "img2logo" else name.split(".")[:-1]
        if name == "img2logo":
            package = []
        found: set[str] = set()
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Import):
                found.update(a.name.removeprefix("img2logo.") for a in node.names if a.name.startswith("img2logo."))
                continue
            if not isinstance(node, ast.ImportFrom):
                continue
            if node.level == 0:
                if not (node.module or "").startswith("img2logo"):
                    continue
                base = (node.module or "").split(".")[1:]
            else:
                base = package[: len(package) - (node.level - 1)] + (node.module.split(".") if node.module else [])
            target = ".".join(base) or "img2logo"
            for alias in node.names:
                sub = ".".join([*base, alias.name])
                found.add(sub if sub in paths else target)
        graph[name] = {m for m in found if m in paths and m != name}
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
    assert {"design.fills", "export.plotting", "export.writers", "export.contract", "geometry.svg_path"} <= set(graph)
    assert "export.plotting" in graph["export.figures"] and "design.fill_values" in graph["export.plotting"]  # read
    assert _cycle(graph) is None, " -> ".join(_cycle(graph) or [])


def test_type_only_imports_and_the_kit_are_counted():
    graph = _imports()
    assert "fit.fit_state" in graph["fit.tangency"]  # under TYPE_CHECKING only
    assert "experiments" in graph["experiments.ablations"]  # from . import Run: the kit's package
    assert "experiments.runner" in graph["experiments"]


def test_the_optimizers_stages_import_its_state_not_each_other():
    graph = _imports()
    for stage in ("fit.merging", "fit.recovery", "fit.tangency"):
        assert "fit.fit_state" in graph[stage] and "fit.progressive" not in graph[stage]
    assert (
        not {"fit.merging", "fit.recovery", "fit.tangency", "fit.progressive", "fit.symmetry"} & graph["fit.fit_state"]
    )


#: The stage packages in the order data flows through them (image -> feature lines -> segment graph
#: -> levels -> design -> export), then the applications above the library. A module imports only
#: its own stage and earlier ones; the foundation (top-level modules: values, options, errors) is shared.
STAGES = ("_compiled", "geometry", "images", "features", "segment_graph", "fit", "design", "export")
APPS = ("app", "studio", "experiments")


def _stage(module: str) -> str | None:
    head = module.split(".")[0]
    return head if head in STAGES or head in APPS else None


def test_the_library_never_imports_the_applications():
    for module, imported in _imports().items():
        if _stage(module) in APPS or module in ("img2logo", "__main__"):  # the public API, python -m img2logo
            continue
        reached = {m for m in imported if _stage(m) in APPS}
        assert not reached, f"{module} imports {sorted(reached)}"


def test_the_stages_import_only_earlier_stages():
    order = {name: i for i, name in enumerate(STAGES)}
    for module, imported in _imports().items():
        stage = _stage(module)
        if stage not in order:
            continue
        later = {m for m in imported if _stage(m) in order and order[_stage(m)] > order[stage]}
        assert not later, f"{module} ({stage}) imports later stages: {sorted(later)}"


def test_export_never_imports_features_or_fit():
    for module, imported in _imports().items():
        if module.startswith("export."):
            assert not {m for m in imported if m.startswith(("features.", "fit."))}, module


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
    "img2logo.export",
    "img2logo.design",
    "img2logo.geometry",
    "img2logo.export.contract",
    "img2logo.errors",
    "img2logo.design.fill_values",
    "img2logo.geometry.primitives",
    "img2logo.geometry.abstraction",
    "img2logo.geometry.constants",
    "img2logo.geometry.golden_ladder",
    "img2logo.geometry.mirror",
    "img2logo.geometry.svg_path",
}


def test_the_file_format_loads_only_what_it_needs():
    loaded = set(modules_loaded("import img2logo.export.contract", "img2logo"))
    assert loaded <= CONTRACT_MODULES, sorted(loaded - CONTRACT_MODULES)
    assert "img2logo.export.contract" in loaded and "img2logo.design.fill_values" in loaded  # the list is read


@pytest.mark.parametrize("image", ["data/clipart-fish.png", "benchmarks/data/drawing-deer.png"])
def test_a_run_of_the_command_loads_only_what_it_needs(tmp_path, image):
    """The command on a clip art and on a drawing with a filled dot (an eye), writing SVG, with one BLAS thread.

    Not numba (the kernels are compiled ahead of time), scipy, scikit-image (not
    even their compiled modules: their operations are kernels), Pillow, matplotlib, numpy.ma, the JSON
    contract, the photo path or the batch; nor :mod:`tempfile` (the image decoder's standard error is
    held in a memory file), nor the fills' and the mirror's modules; a drawing's, nor the clip art's strokes and
    ranking of regions.
    """
    code = (
        "import os, sys\n"
        "from img2logo.app.cli import main\n"
        "unneeded = sys.argv[3].split()\n"
        "sys.argv = ['img2logo', sys.argv[1], '-q', '--svg', sys.argv[2]]\n"
        "assert main() == 0\n"
        "print(os.environ.get('OPENBLAS_NUM_THREADS'))\n"
        "print(sorted(m for m in unneeded if m in sys.modules))\n"
    )
    unneeded = (
        "numba scipy skimage PIL matplotlib numpy.ma img2logo.export.contract img2logo.features.photo.lines "
        "img2logo.features.photo.line_maps img2logo.features.photo.subject"
    )
    unneeded += " img2logo.app.batch.run img2logo.design.fills tempfile"
    unneeded += " img2logo.design.fill_values img2logo.geometry.mirror"  # no fills, no mirror axis
    if "drawing" in image:  # nor a clip art's strokes and regions' ranking
        unneeded += " img2logo.features.detail img2logo.features.stroke_sides img2logo.features.clipart_strokes"
    pinned = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
    env = {k: v for k, v in os.environ.items() if k not in pinned}
    svg = tmp_path / "logo.svg"
    cmd = [sys.executable, "-c", code, str(PACKAGE.parent / image), str(svg), unneeded]
    out = subprocess.run(cmd, cwd=PACKAGE.parent, env=env, capture_output=True, text=True, check=True).stdout
    blas, loaded = out.splitlines()
    assert blas == "1"
    assert ast.literal_eval(loaded) == []
    assert svg.read_text().startswith("<?xml")


def _private_imports(path: Path, root: Path = PACKAGE.parent) -> list[str]:
    """``from img2logo.x import _name`` in ``path`` where ``_name`` belongs to another package: "line: x._name".

    A module may use the private names of its own package (a library module's
    folder); anything else (another package, a test, a benchmark) uses public
    names. A submodule (``from img2logo import _io``) is a module, not a name,
    and a compiled kernel's Python reference (``*_reference``), its oracle, is
    the tests' to import.
    """
    rel = path.relative_to(root)
    in_library = rel.parts[0] == "img2logo"
    package = list(rel.parent.parts)
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if not isinstance(node, ast.ImportFrom):
            continue
        module = (node.module or "").split(".") if node.module else []
        target = package[: len(package) - (node.level - 1)] + module if node.level else module
        if target[:1] != ["img2logo"]:
            continue
        for alias in node.names:
            name = alias.name
            if not name.startswith("_") or name.startswith("__"):
                continue
            folder = root.joinpath(*target)
            if (folder / f"{name}.py").exists() or (folder / name / "__init__.py").exists():
                continue  # a private module, imported as a module
            if not in_library and name.endswith("_reference"):
                continue
            own_package = target[:-1] if (root.joinpath(*target).with_suffix(".py")).exists() else target
            if in_library and own_package == package:
                continue
            found.append(f"{rel}:{node.lineno}: {'.'.join(target)}.{name}")
    return found


def test_no_module_imports_another_packages_private_names():
    root = PACKAGE.parent
    files = [p for folder in ("img2logo", "tests", "benchmarks", "tools") for p in (root / folder).rglob("*.py")]
    assert len(files) > 100
    found = [hit for p in sorted(files) for hit in _private_imports(p)]
    assert not found, "\n".join(found)


def test_a_private_name_of_another_package_is_found(tmp_path):
    (tmp_path / "img2logo" / "fit").mkdir(parents=True)
    (tmp_path / "tests").mkdir()
    for name in ("__init__.py", "_io.py", "fit/__init__.py", "fit/a.py", "fit/b.py"):
        (tmp_path / "img2logo" / name).write_text("")
    (tmp_path / "img2logo" / "fit" / "b.py").write_text("from .a import _own\nfrom .._io import _Stage\n")
    probe = tmp_path / "tests" / "test_probe.py"
    probe.write_text(
        "from img2logo._io import _Stage\nfrom img2logo import _io\nfrom img2logo.fit.a import _x_reference\n"
    )
    assert _private_imports(probe, tmp_path) == ["tests/test_probe.py:1: img2logo._io._Stage"]
    assert _private_imports(tmp_path / "img2logo" / "fit" / "b.py", tmp_path) == [
        "img2logo/fit/b.py:2: img2logo._io._Stage"
    ]
