"""The notebooks: committed clean, parametrized, and executed (smoke) by papermill."""

from __future__ import annotations

import ast
import base64
import json
import re
from pathlib import Path

import pytest

from img2logo.experiments.runner import SMOKE, NotebookParameterError, main, run_notebook

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted((ROOT / "notebooks").glob("*.ipynb"))


def _load(path: Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))


def _code(cell: dict) -> str:
    return "".join(cell["source"])


def _parameter_names(nb: dict) -> set[str]:
    cells = [c for c in nb["cells"] if "parameters" in c.get("metadata", {}).get("tags", [])]
    assert len(cells) == 1, "exactly one cell tagged 'parameters'"
    tree = ast.parse(_code(cells[0]))
    return {t.id for node in tree.body if isinstance(node, ast.Assign) for t in node.targets if isinstance(t, ast.Name)}


def _calls(tree: ast.AST, name: str) -> list[ast.Call]:
    """Calls of ``<anything>.name(...)`` or ``name(...)`` in ``tree``."""
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            func = node.func
            if (isinstance(func, ast.Attribute) and func.attr == name) or (
                isinstance(func, ast.Name) and func.id == name
            ):
                out.append(node)
    return out


def test_there_are_notebooks():
    assert NOTEBOOKS


def test_every_notebook_has_smoke_parameters():
    assert sorted(SMOKE) == [p.stem for p in NOTEBOOKS]


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_is_committed_stripped(path):
    nb = _load(path)
    assert nb["metadata"].get("kernelspec", {}).get("name") == "python3"
    assert "papermill" not in nb["metadata"]
    for cell in nb["cells"]:
        if cell["cell_type"] == "code":
            assert not cell.get("outputs"), f"{path.name}: a code cell has outputs; strip them"
            assert cell.get("execution_count") is None, f"{path.name}: a code cell has an execution count"
        assert "papermill" not in cell.get("metadata", {})


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_starts_with_markdown_then_parameters(path):
    nb = _load(path)
    assert nb["cells"][0]["cell_type"] == "markdown"
    assert "parameters" in nb["cells"][1].get("metadata", {}).get("tags", [])
    missing = set(SMOKE[path.stem]) - _parameter_names(nb)
    assert not missing, f"{path.name}: smoke parameters {sorted(missing)} are not in its parameters cell"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_checks_all_its_parameters_first(path):
    # The first code cell after the parameters validates every parameter, by name, in one call.
    nb = _load(path)
    first = next(c for c in nb["cells"][2:] if c["cell_type"] == "code")
    calls = _calls(ast.parse(_code(first)), "check_parameters")
    assert len(calls) == 1, f"{path.name}: its first code cell does not call check_parameters once"
    assert {k.arg for k in calls[0].keywords} == _parameter_names(nb)


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_never_overwrites_a_parameter(path):
    # A value passed in (by papermill, make, the tests) is the value used.
    nb = _load(path)
    names = _parameter_names(nb)
    for cell in nb["cells"][2:]:
        if cell["cell_type"] != "code":
            continue
        for node in ast.walk(ast.parse(_code(cell))):
            targets = []
            if isinstance(node, ast.Assign):
                targets = node.targets
            elif isinstance(node, ast.AugAssign | ast.AnnAssign | ast.For | ast.comprehension):
                targets = [node.target]
            assigned = {n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name)}
            assert not assigned & names, f"{path.name}: a cell assigns the parameter(s) {sorted(assigned & names)}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_markdown_sets_the_paper_symbols_as_math(path):
    # E^s, A^t, |A| are written $E^s$, $A^t$, $|A|$ (MathJax in Jupyter), never as plain text.
    for cell in _load(path)["cells"]:
        if cell["cell_type"] != "markdown":
            continue
        text = re.sub(r"`[^`]*`", "", _code(cell))  # code spans are code
        assert "$$" not in text, f"{path.name}: display math or a doubled $: {text[:80]!r}"
        assert text.count("$") % 2 == 0, f"{path.name}: unbalanced $ in {text[:80]!r}"
        prose = re.sub(r"\$[^$]*\$", "", text)
        bare = re.findall(r"E\^s|A\^\w|\|A\||S_i|p_k", prose)
        assert not bare, f"{path.name}: {bare} outside math in {text[:80]!r}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_holds_no_algorithm(path):
    # Notebooks communicate, the library computes: no function definitions.
    for cell in _load(path)["cells"]:
        if cell["cell_type"] == "code":
            tree = ast.parse(_code(cell))
            assert not any(isinstance(n, ast.FunctionDef | ast.ClassDef) for n in ast.walk(tree))


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_a_figure_cell_ends_by_showing_the_saved_figure(path):
    # save_figure returns the written file for display: it must be the cell's last expression.
    for cell in _load(path)["cells"]:
        if cell["cell_type"] == "code" and "save_figure(" in _code(cell):
            tree = ast.parse(_code(cell))
            last = tree.body[-1]
            assert isinstance(last, ast.Expr) and _calls(last, "save_figure"), f"{path.name}: {_code(cell)[:60]!r}"


def test_an_unknown_parameter_name_is_refused_before_anything_runs(tmp_path):
    pytest.importorskip("papermill", reason="the notebook runner needs the extra [kit]")
    out = tmp_path / "out.ipynb"
    with pytest.raises(NotebookParameterError, match=r"no parameter smok; its parameters are .*smoke"):
        run_notebook(ROOT / "notebooks" / "11_explore_levels.ipynb", out, {"smok": True})
    assert not out.exists()


def test_the_runner_command_refuses_an_unknown_name_with_one_line(tmp_path, capsys):
    pytest.importorskip("papermill", reason="the notebook runner needs the extra [kit]")
    nb = ROOT / "notebooks" / "04_tolerance_sweep.ipynb"
    assert main([str(nb), str(tmp_path / "out.ipynb"), "--smoke", "-p", "tolerance", "3"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1
    assert "04_tolerance_sweep.ipynb: no parameter tolerance" in err


def test_the_kernel_runs_one_blas_thread_and_the_environment_is_restored(tmp_path, monkeypatch):
    papermill = pytest.importorskip("papermill", reason="the notebook runner needs the extra [kit]")
    import os

    from img2logo.app.cli import THREAD_VARIABLES
    from img2logo.experiments.runner import PROGRESS_ENV

    seen = {}

    def execute(path, output, **kwargs):  # the kernel inherits os.environ as it is here
        seen.update({var: os.environ.get(var) for var in (*THREAD_VARIABLES, PROGRESS_ENV)})
        Path(output).write_text(Path(path).read_text())

    monkeypatch.setattr(papermill, "execute_notebook", execute)
    monkeypatch.delenv("OPENBLAS_NUM_THREADS", raising=False)
    monkeypatch.setenv("OMP_NUM_THREADS", "3")  # a count the user set is kept
    monkeypatch.delenv(PROGRESS_ENV, raising=False)
    run_notebook(ROOT / "notebooks" / "04_tolerance_sweep.ipynb", tmp_path / "out.ipynb")
    assert seen["OPENBLAS_NUM_THREADS"] == "1" and seen["OMP_NUM_THREADS"] == "3" and seen[PROGRESS_ENV] == "0"
    assert "OPENBLAS_NUM_THREADS" not in os.environ and os.environ["OMP_NUM_THREADS"] == "3"
    assert PROGRESS_ENV not in os.environ


@pytest.mark.notebook
def test_a_bad_parameter_value_stops_the_notebook_with_one_line(tmp_path):
    pytest.importorskip("papermill", reason="the notebook runner needs the extra [kit]")
    out = tmp_path / "out.ipynb"
    with pytest.raises(NotebookParameterError) as caught:
        run_notebook(
            ROOT / "notebooks" / "11_explore_levels.ipynb", out, {**SMOKE["11_explore_levels"], "tolerance": -1}
        )
    message = str(caught.value)
    assert "\n" not in message
    assert "parameter tolerance: expected a positive number (px), got -1" in message
    # The notebook shows the same line, not a traceback.
    errors = [o for c in _load(out)["cells"] for o in c.get("outputs", []) if o["output_type"] == "error"]
    assert [e["traceback"] for e in errors] == [[f"NotebookParameterError: {errors[0]['evalue']}"]]


@pytest.mark.notebook
@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_notebook_runs_with_smoke_parameters_and_shows_its_figures(path, tmp_path):
    pytest.importorskip("papermill")
    out = run_notebook(path, tmp_path / path.name, SMOKE[path.stem])
    executed = _load(out)
    assert executed["metadata"]["papermill"]["parameters"] == SMOKE[path.stem]
    for cell in executed["cells"]:
        if cell["cell_type"] != "code":
            continue
        outputs = cell.get("outputs", [])
        assert not [o for o in outputs if o["output_type"] == "error"]
        texts = ["".join(o.get("text", "")) + "".join(o.get("data", {}).get("text/plain", "")) for o in outputs]
        assert not [t for t in texts if "<Figure size" in t], f"{path.name}: a figure shown as text"
        if "save_figure(" in _code(cell):
            pngs = [o["data"]["image/png"] for o in outputs if "image/png" in o.get("data", {})]
            assert len(pngs) == 1, f"{path.name}: a figure cell shows no image: {_code(cell)[:60]!r}"
            # The image shown is a file written to the notebook's folder, byte for byte.
            shown = base64.b64decode(pngs[0])
            assert any(p.read_bytes() == shown for p in (ROOT / "build" / "smoke" / path.stem).glob("*.png"))
