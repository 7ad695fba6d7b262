"""Figures that read: no text of a kit figure overlaps another or leaves the figure.

``layout.text_problems`` measures every drawn text (matplotlib's ``get_window_extent`` with a
renderer); ``save_figure`` breaks titles wider than their panels (``layout.fit_titles``) and
refuses to write a figure whose texts still overlap or are clipped. Every figure-making function
of the kit is called by a notebook, so the notebooks' smoke runs (``make test``) fail on a figure
that would not read.
"""

from __future__ import annotations

import ast
import inspect
import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import pytest
from matplotlib.figure import Figure

from img2logo import experiments
from img2logo.experiments import (
    ablations,
    arc_selection,
    design,
    explore,
    features,
    layout,
    limitations,
    results,
    symmetry,
    tangency,
)

ROOT = Path(__file__).resolve().parents[2]
KIT_MODULES = (
    experiments,
    ablations,
    arc_selection,
    design,
    explore,
    features,
    limitations,
    results,
    symmetry,
    tangency,
)


def _two_panels(title: str) -> Figure:
    fig = Figure(figsize=(4.0, 2.0), layout="constrained")
    left, right = fig.subplots(1, 2)
    left.set_title(title, fontsize=9)
    right.set_title(title, fontsize=9)
    return fig


def test_overlapping_titles_are_found():
    problems = layout.text_problems(_two_panels("a title much wider than its panel: |A| = 12, E^s = 4.31 px"))
    assert any(p.startswith("overlap:") for p in problems), problems


def test_a_text_off_the_figure_is_found():
    fig = Figure(figsize=(3.0, 2.0))
    fig.text(0.9, 0.5, "runs off the right edge")
    assert layout.text_problems(fig) == ["clipped by the figure's edge: 'runs off the right edge'"]


def test_a_readable_figure_has_no_problem():
    fig = _two_panels("short")
    fig.axes[0].set_xlabel("x (px)")
    fig.axes[0].plot([0, 1], [0, 1], label="line")
    fig.axes[0].legend()
    assert layout.text_problems(fig) == []


def test_fit_titles_breaks_wide_titles_at_spaces_until_they_fit():
    fig = layout.fit_titles(_two_panels("(b) with connectivity |A| = 12, E$^s$ = 4.31 px, max gap 0.00 px"))
    assert layout.text_problems(fig) == []
    title = fig.axes[0].get_title()
    assert "\n" in title and "E$^s$" in title  # broken between words, the math whole


def test_save_figure_fixes_titles_and_refuses_what_still_does_not_read(tmp_path):
    fig = _two_panels("(b) with connectivity |A| = 12, E$^s$ = 4.31 px, max gap 0.00 px")
    experiments.save_figure(fig, tmp_path / "ok.png")
    assert layout.text_problems(fig) == []
    bad = Figure(figsize=(3.0, 2.0))
    bad.text(0.2, 0.5, "one text")
    bad.text(0.25, 0.5, "over another")
    with pytest.raises(layout.FigureTextError, match=r"bad.png: the figure would not read: overlap"):
        experiments.save_figure(bad, tmp_path / "bad.png")
    assert not (tmp_path / "bad.png").exists()


@pytest.mark.parametrize("hook", [0.0, 60.0, 90.0])
def test_the_hook_figure_reads(hook, tmp_path):
    # Fig. 9: its (b) and (c) titles ran into each other.
    example = arc_selection.hook_example(hook)
    fig = arc_selection.plot_hook_example(example, arc_selection.hook_table([0, 45, 90]))
    experiments.save_figure(fig, tmp_path / "hook.png")
    assert layout.text_problems(fig) == []


def _figure_functions() -> set[str]:
    """The kit's functions that return a figure (``plot_*``), by name."""
    names = set()
    for module in KIT_MODULES:
        for name, value in vars(module).items():
            if name.startswith("plot_") and inspect.isfunction(value) and value.__module__ == module.__name__:
                names.add(name)
    return names


def _notebook_calls() -> set[str]:
    called = set()
    for path in sorted((ROOT / "notebooks").glob("*.ipynb")):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            if cell["cell_type"] != "code":
                continue
            for node in ast.walk(ast.parse("".join(cell["source"]))):
                if isinstance(node, ast.Call):
                    func = node.func
                    called.add(func.attr if isinstance(func, ast.Attribute) else getattr(func, "id", ""))
    return called


def test_every_figure_function_is_drawn_by_a_notebook():
    # So each is saved through save_figure, which refuses text that does not read, in the smoke runs.
    functions = _figure_functions()
    assert len(functions) >= 20
    missing = sorted(functions - _notebook_calls())
    assert not missing, f"figure functions no notebook draws (their text is unchecked): {missing}"
