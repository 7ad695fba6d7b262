"""img2logo.experiments: paths, repository-relative sources, what a notebook shows, the runs and the sweep."""

from __future__ import annotations

import subprocess
import sys

import pandas as pd
import pytest
from helpers import DATA
from matplotlib.figure import Figure

from img2logo import abstract, write_json
from img2logo.errors import Img2LogoError, InvalidParameterError
from img2logo.experiments import (
    by_image,
    load_example,
    preprocess,
    project_root,
    repo_relative,
    save_figure,
    save_table,
    show_table,
    sweep,
)
from img2logo.fit.progressive import optimize
from img2logo.pipeline import Result


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
    fig = Figure(figsize=(2, 1), layout="constrained")  # as the kit's: its tick labels inside the figure
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
    assert "<th>t</th>" in html and "<td>3.18</td>" in html  # shown to 3 digits, the CSV keeps 6
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


# --------------------------------------------------------------------------- runs and the sweep
def test_a_sweep_runs_every_image_with_every_grid_point_and_variant():
    (leaf,) = preprocess([DATA / "drawing-leaf.png"])
    assert leaf.name == "drawing-leaf" and leaf.progression is None and len(leaf.seconds) == 1
    with pytest.raises(Img2LogoError, match="only preprocessed"):
        leaf.final  # noqa: B018
    variants = {"merged": {}, "A^0 only": {"merging": False}}
    runs = sweep([leaf], {"tolerance": [3.0, 9.0]}, variants)
    assert [(r.variant, r.final.tolerance) for r in runs] == [
        ("merged", 3.0),
        ("A^0 only", 3.0),
        ("merged", 9.0),
        ("A^0 only", 9.0),
    ]
    # A sweep over T runs with the paper's stopping rule (stretch 1): T's effect alone.
    assert dict(runs[1].settings) == {"stretch": 1.0, "tolerance": 3.0, "merging": False} and len(runs[1].levels) == 1
    assert all(r.final.params["stretch"] == 1.0 for r in runs)
    assert sweep([leaf], {"tolerance": [3.0]}, stretch=2.0)[0].final.params["stretch"] == 2.0  # unless given
    assert len(runs[2].final.arcs) <= len(runs[0].final.arcs)  # a larger T merges at least as much
    same = optimize(leaf.graph, tolerance=9.0)
    assert [len(a.arcs) for a in runs[2].levels] == [len(a.arcs) for a in same.levels]
    assert all(r.graph is leaf.graph for r in runs)  # the graph is built once


def test_a_sweep_over_the_rdp_tolerance_rebuilds_the_graph_and_times_each_repeat():
    runs = sweep([DATA / "drawing-leaf.png"], {"rdp_tolerance": [1.0, 8.0]}, repeats=2, merging=False)
    assert [r.settings["rdp_tolerance"] for r in runs] == [1.0, 8.0]
    assert runs[0].graph.n_segments > runs[1].graph.n_segments
    assert all(len(r.seconds) == 2 and min(r.seconds) > 0 for r in runs)
    with pytest.raises(InvalidParameterError, match="repeats"):
        sweep(runs, repeats=0)
    with pytest.raises(InvalidParameterError, match=r"grid\['tolerance'\]: expected a non-empty list of values, got 5"):
        sweep(runs, {"tolerance": 5})
    with pytest.raises(TypeError):
        runs[0].settings["tolerance"] = 1.0  # a run's settings are read-only


def test_a_pipeline_sweep_is_abstract():
    (run,) = sweep([DATA / "drawing-leaf.png"], tolerance=4.0, pipeline=True)
    result = abstract(load_example(DATA / "drawing-leaf.png"), tolerance=4.0, progress=False)
    assert run.name == "drawing-leaf" and run.kind == result.lines.kind
    assert [a.similarity for a in run.levels] == [a.similarity for a in result.levels]
    assert by_image([run, run]) == {"drawing-leaf": [run, run]}
    # the run holds abstract's Result (its timings and params too), not copies of its levels
    assert isinstance(run.result, Result) and run.result.timings.keys() == result.timings.keys()
    assert run.levels is run.result.levels and run.final is run.result.final and run.bias == run.result.bias
    assert run.result.graph is run.graph and run.result.params == result.params


def test_an_optimize_sweep_holds_a_result_and_a_preprocessed_run_none():
    (pre,) = preprocess([DATA / "drawing-leaf.png"])
    (run,) = sweep([pre], tolerance=6.0)
    assert pre.result is None and pre.progression is None
    with pytest.raises(Img2LogoError, match="drawing-leaf was only preprocessed: it has no levels"):
        _ = pre.final
    assert isinstance(run.result, Result) and run.result.graph is run.graph and run.result.image is pre.image
    assert run.progression is run.result.progression and run.final is run.result.final


def test_the_library_runs_without_the_kit_extras(tmp_path):
    """papermill, ipywidgets and ipykernel are the kit's ([kit] extra): the library never imports them."""
    code = f"""
import importlib, importlib.abc, pkgutil, sys

class Block(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in ("papermill", "ipywidgets", "ipykernel"):
            raise ImportError("blocked: " + name)

sys.meta_path.insert(0, Block())
import img2logo
for m in pkgutil.iter_modules(img2logo.__path__):
    importlib.import_module("img2logo." + m.name)
from img2logo import experiments
from img2logo.experiments import ablations, design, features, results
from img2logo.app.cli import main
status = main([{str(DATA / "drawing-leaf.png")!r}, "--svg", {str(tmp_path / "leaf.svg")!r}])
print(status, sorted(m for m in ("papermill", "ipywidgets", "ipykernel") if m in sys.modules))
"""
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["0", "[]"]
    assert (tmp_path / "leaf.svg").read_text().startswith("<?xml")


# --------------------------------------------------------------------------- legibility, provenance, progress
def test_rounded_shows_meaningful_digits():
    from img2logo.experiments import rounded

    assert [rounded(v) for v in (2.918273, 12.0, 0.004567, 1234.56, 0.0, 1.5e-7, float("nan"))] == [
        "2.92",
        "12",
        "0.00457",
        "1235",
        "0",
        "1.5e-07",
        "nan",
    ]


def test_make_legible_raises_small_text_to_the_screen_minimum():
    from matplotlib.figure import Figure

    from img2logo.experiments import MIN_TEXT_PX, NOTEBOOK_WIDTH_PX, make_legible

    fig = Figure(figsize=(16.0, 3.0))  # 1600 px at dpi 100: shown at NOTEBOOK_WIDTH_PX
    ax = fig.add_subplot()
    small = ax.set_title("small", fontsize=6)
    big = fig.suptitle("big", fontsize=30)
    make_legible(fig, dpi=100.0)
    shown = NOTEBOOK_WIDTH_PX / 1600.0
    assert small.get_fontsize() * 100.0 / 72.0 * shown == pytest.approx(MIN_TEXT_PX)
    assert big.get_fontsize() == 30  # larger text is left alone
    for label in ax.get_xticklabels():
        if label.get_text():
            assert label.get_fontsize() * 100.0 / 72.0 * shown >= MIN_TEXT_PX - 1e-9


def test_environment_records_python_packages_and_platform():
    import platform

    from img2logo.experiments import PROVENANCE_PACKAGES, environment

    env = environment()
    assert env["python"] == platform.python_version()
    packages = env["packages"]
    for name in ("numpy", "scipy", "scikit-image", "matplotlib", "numba", "opencv-contrib-python-headless"):
        assert name in PROVENANCE_PACKAGES and packages[name], name
    import numpy

    assert packages["numpy"] == numpy.__version__ and packages["opencv"]
    assert env["platform"]["machine"] == platform.machine() and env["platform"]["cpu_count"] >= 1


def test_sweep_shows_progress_unless_papermill_runs_it(monkeypatch, capsys):
    from img2logo import experiments
    from img2logo.experiments.runner import PROGRESS_ENV

    monkeypatch.delenv(PROGRESS_ENV, raising=False)
    leaf = experiments.data_path("drawing-leaf.png")
    runs = experiments.sweep([leaf], {"tolerance": [6.0, 9.0]})
    assert len(runs) == 2
    assert "runs" in capsys.readouterr().err  # tqdm's bar, on standard error outside Jupyter
    monkeypatch.setenv(PROGRESS_ENV, "0")
    experiments.sweep(runs[:1], {"tolerance": [9.0]})
    assert capsys.readouterr().err == ""


def test_provenance_removes_what_an_earlier_run_left_and_lists_the_outputs(tmp_path, monkeypatch):
    import datetime
    import json
    import os

    from img2logo.experiments import write_provenance
    from img2logo.experiments.paths import ROOT_ENV

    (tmp_path / "data").mkdir()
    (tmp_path / "data" / "ATTRIBUTION.md").write_text("examples\n")
    monkeypatch.setenv(ROOT_ENV, str(tmp_path))
    folder = tmp_path / "figures" / "99_demo"
    folder.mkdir(parents=True)
    start = datetime.datetime.now(datetime.UTC)
    stale = folder / "level11.svg"  # an earlier run's name for an output
    stale.write_text("<svg/>")
    os.utime(stale, (start.timestamp() - 3600, start.timestamp() - 3600))
    (folder / "level8.svg").write_text("<svg/>")  # this run's
    executed = tmp_path / "99_demo.ipynb"
    executed.write_text(
        json.dumps(
            {
                "cells": [{"cell_type": "code", "metadata": {"tags": ["parameters"]}, "source": ["level = 8\n"]}],
                "metadata": {"papermill": {"start_time": start.isoformat(), "duration": 1.5, "parameters": {}}},
            }
        )
    )

    record = json.loads(write_provenance(executed).read_text(encoding="utf-8"))

    assert not stale.exists()
    assert (folder / "level8.svg").exists()
    assert record["removed"] == ["level11.svg"]
    assert record["outputs"] == ["level8.svg"]
    assert record["parameters_cell"] == "level = 8\n"
