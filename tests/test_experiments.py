"""img2logo.experiments: paths, repository-relative sources, and what a notebook shows."""

from __future__ import annotations

import pandas as pd
from conftest import DATA
from matplotlib.figure import Figure

from img2logo import abstract, write_json
from img2logo.experiments import (
    load_example,
    project_root,
    repo_relative,
    save_figure,
    save_table,
    show_table,
)


def test_repo_relative_names_data_files_from_the_repository_root(tmp_path):
    assert repo_relative(DATA / "clipart-fish.png") == "data/clipart-fish.png"
    assert repo_relative(project_root() / "notebooks" / ".." / "data" / "x.png") == "data/x.png"
    assert repo_relative(tmp_path / "x.png") == str(tmp_path / "x.png")  # outside: absolute


def test_a_result_document_names_its_input_relative_to_the_repository(tmp_path):
    image = load_example(DATA / "drawing-leaf.png")
    assert image.source == "data/drawing-leaf.png"
    result = abstract(image, progress=False)
    text = write_json(result.final, tmp_path / "leaf.json").read_text()
    assert '"source": "data/drawing-leaf.png"' in text
    assert str(project_root()) not in text  # the same bytes in any checkout


def test_save_figure_shows_the_written_file(tmp_path):
    fig = Figure(figsize=(2, 1))
    fig.subplots().plot([0, 1], [1, 0])
    shown = save_figure(fig, tmp_path / "f.png", dpi=50)
    assert shown.path.is_file()
    assert shown._repr_png_() == shown.path.read_bytes()  # the same bytes, not a second rendering
    assert shown._repr_png_()[:8] == b"\x89PNG\r\n\x1a\n"
    assert shown._repr_svg_() is None
    assert "<Figure" not in repr(shown)
    svg = save_figure(fig, tmp_path / "f.svg")
    assert svg._repr_png_() is None and svg._repr_svg_().lstrip().startswith("<?xml")


def test_tables_are_shown_without_their_index(tmp_path):
    table = pd.DataFrame({"t": [0, 1], "E^s (px)": [2.9164, 3.18123456]})
    shown = save_table(table, tmp_path / "t.csv")
    assert shown.path.read_text() == "t,E^s (px)\n0,2.9164\n1,3.18123\n"
    html = shown._repr_html_()
    assert "<th>t</th>" in html and "3.18123" in html
    assert html.count("<tr") == 3  # header and two rows, no index column header row
    assert "<th>0</th>" not in html  # no index cells
    assert repr(shown).splitlines()[0].split() == ["t", "E^s", "(px)"]
    assert show_table(table).path is None


def test_a_missing_integer_shows_empty_as_in_the_csv(tmp_path):
    table = pd.DataFrame({"iteration": [0, 23], "arcs": pd.array([16, None], dtype="Int64")})
    shown = save_table(table, tmp_path / "t.csv")
    assert shown.path.read_text() == "iteration,arcs\n0,16\n23,\n"
    html = shown._repr_html_()
    assert "<td>16</td>" in html and "<td></td>" in html and "NA" not in html
