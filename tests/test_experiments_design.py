"""img2logo.experiments.design: Table 3 timing, Fig. 15, 16 and the level explorer (notebooks 09-11)."""

from __future__ import annotations

import math
import subprocess
import sys

import numpy as np
import pytest
from conftest import DATA

from img2logo import InvalidParameterError, abstract
from img2logo.experiments import design, preprocess, sweep
from img2logo.geometry import Abstraction, Arc, Circle

#: The beak of drawing-bird.png (Fig. 16): centre (x, y) and radius, px.
BEAK = ((375.0, 155.0), 40.0)


@pytest.fixture(scope="module")
def leaf():
    return preprocess([DATA / "drawing-leaf.png"])[0]


@pytest.fixture(scope="module")
def fish():
    return preprocess([DATA / "drawing-fish.png"])[0]


@pytest.fixture(scope="module")
def bird():
    return preprocess([DATA / "drawing-bird.png"])[0]


@pytest.fixture(scope="module")
def fish_result():
    return abstract(DATA / "drawing-fish.png", progress=False)


# --------------------------------------------------------------------------- imports
def test_importing_the_experiments_does_not_import_ipywidgets():
    code = "import sys, img2logo.experiments, img2logo.experiments.design; print('ipywidgets' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


# --------------------------------------------------------------------------- Table 3
def test_timing_table_has_the_four_cells_and_the_paper_beside(leaf):
    runs = sweep([leaf], variants=design.TIMING_VARIANTS, repeats=2)
    assert [design._cell(r) for r in runs] == list(design.CELLS)
    assert all(len(r.seconds) == 2 and min(r.seconds) > 0 for r in runs)
    table = design.timing_table(runs)
    assert len(table) == 4
    for column in ("median (s)", "ratio to Yes/Yes", "paper (s)", "paper ratio to Yes/Yes", "initial arcs"):
        assert column in table.columns
    yes_yes = table[(table["localized"] == "Yes") & (table["simplify"] == "Yes")].iloc[0]
    assert yes_yes["ratio to Yes/Yes"] == pytest.approx(1.0)
    assert yes_yes["paper (s)"] == "65.37"
    no_no = table[(table["localized"] == "No") & (table["simplify"] == "No")].iloc[0]
    assert no_no["paper (s)"] == ">= 2 hrs" and no_no["paper ratio to Yes/Yes"].startswith(">= ")
    # The simplification starts the loop from fewer arcs; without it A^0 has one arc per segment.
    simplified = table[table["simplify"] == "Yes"]["initial arcs"]
    assert (simplified < leaf.graph.n_segments).all()
    assert (table[table["simplify"] == "No"]["initial arcs"] == leaf.graph.n_segments).all()
    fig = design.plot_timing(runs)
    assert len(fig.axes) == 2 and all(ax.get_yscale() == "log" for ax in fig.axes)


def test_stage_table_sums_the_stages(fish_result):
    table = design.stage_table([fish_result], ["drawing-fish"])
    assert list(table.columns) == ["image", *design.STAGES, "total", "arcs"]
    row = table.iloc[0]
    assert row["total"] == pytest.approx(sum(row[s] for s in design.STAGES))
    assert row["arcs"] == len(fish_result.final.arcs)
    assert len(design.plot_stages(table).axes) == 1


# --------------------------------------------------------------------------- Fig. 15
def _abstraction(ks_and_lengths):
    arcs = tuple(Arc(Circle(0.0, 0.0, 10.0, k), 0.0, length / 10.0) for k, length in ks_and_lengths)
    return Abstraction(0, arcs, tuple((i,) for i in range(len(arcs))), np.zeros((0, 2)), (), 1.0, 0.5, 5.0, 64, 64)


def test_most_used_exponents_counts_arcs_and_breaks_ties_by_length():
    a = _abstraction([(3, 5.0), (3, 5.0), (5, 1.0), (7, 20.0), (9, 2.0), (9, 2.0), (9, 2.0)])
    assert design.most_used_exponents(a, 1) == (9,)
    assert design.most_used_exponents(a, 2) == (3, 9)
    assert design.most_used_exponents(a, 3) == (3, 7, 9)  # 7 beats 5: a longer arc
    assert design.most_used_exponents(a, 10) == (3, 5, 7, 9)
    with pytest.raises(InvalidParameterError):
        design.most_used_exponents(a, 0)


def test_user_exponents_restrict_the_radii(fish):
    comparison = design.compare_exponents(fish, n_exponents=2)
    auto, user = comparison
    allowed = user.settings["exponents"]
    assert len(allowed) == 2
    assert allowed == design.most_used_exponents(auto.final, 2)
    assert {a.circle.k for a in user.final.arcs} <= set(allowed)
    assert user.bias == pytest.approx(auto.bias)
    table = design.exponent_table(comparison)
    assert table["arcs, automated"].sum() == len(auto.final.arcs)
    assert table["arcs, user-specified"].sum() == len(user.final.arcs)
    assert table.loc[~table["allowed in user setting"], "arcs, user-specified"].sum() == 0
    summary = design.comparison_table(comparison)
    assert list(summary["setting"]) == ["automated", "user-specified"]
    assert summary.loc[1, "distinct radii"] <= 2
    fig = design.plot_exponent_comparison(comparison)
    assert len(fig.axes) == 3
    assert [len(ax.child_axes) for ax in fig.axes] == [0, 1, 1]  # the ladder insets


def test_explicit_exponents_are_used_as_given(fish):
    comparison = design.compare_exponents(fish, exponents=[9, 7, 9])
    assert comparison[1].settings["exponents"] == (7, 9)


# --------------------------------------------------------------------------- Fig. 16
def test_region_mask_disc_and_square():
    disc = design.region_mask((100, 120), (60.0, 50.0), 10.0)
    assert disc.shape == (100, 120) and disc.dtype == bool
    assert abs(int(disc.sum()) - math.pi * 100) < 20
    assert disc[49, 59] and not disc[49, 75]  # pixel (row 49, col 59) has its centre at (59.5, 49.5)
    square = design.region_mask(np.zeros((100, 120, 3)), (60.0, 50.0), 10.0, form="square")
    assert int(square.sum()) == 400
    with pytest.raises(InvalidParameterError):
        design.region_mask((10, 10), (5, 5), 2.0, form="star")
    with pytest.raises(InvalidParameterError):
        design.region_mask((10, 10), (5, 5), 0.0)


def test_the_lock_keeps_the_beak_of_the_bird(bird):
    mask = design.region_mask(bird.image, *BEAK)
    runs = sweep([bird], {"tolerance": [3.0, 8.0]}, design.lock_variants(mask))
    table = design.lock_table(runs, mask, threshold=2.0)
    assert list(table["T"]) == [3.0, 8.0]
    assert (table["locked segments"] > 0).all()
    # Without the lock the beak is merged away at the larger T, with it every T keeps it.
    assert not table.loc[0, "lost without lock"] and table.loc[1, "lost without lock"]
    assert not table["lost with lock"].any()
    assert design.first_lost(runs, mask, 2.0) == 8.0
    fig = design.plot_lock_comparison(runs, mask, 8.0, center=BEAK[0], radius=BEAK[1])
    assert len(fig.axes) == 6


def test_bias_sweep_uses_the_given_bias(fish):
    runs = sweep([fish], {"bias": [None, 0.0, 0.5]})
    assert [r.bias for r in runs[1:]] == [0.0, 0.5]
    table = design.bias_table(runs)
    assert list(table["bias"]) == ["auto (Eqn. 14)", "0", "0.5"]
    assert len(design.plot_bias_sweep(runs).axes) == 3


# --------------------------------------------------------------------------- the explorer
def test_level_strip_spreads_the_levels(fish_result):
    n = len(fish_result.levels)
    fig = design.plot_level_strip(fish_result, 3)
    assert len(fig.axes) == min(3, n)
    assert fig.axes[0].get_title().startswith("t = 0:")
    assert fig.axes[-1].get_title().startswith(f"t = {n - 1}:")
    assert len(design.plot_level_strip(fish_result, [0, -1]).axes) == 2


def test_levels_table_has_one_row_per_level_with_fewer_arcs_each(fish_result):
    table = design.levels_table(fish_result)
    assert list(table["t"]) == list(range(len(fish_result.levels)))
    assert (np.diff(table["arcs"]) == -1).all()
    assert table["E^s (px)"].iloc[-1] <= fish_result.final.tolerance


@pytest.fixture
def explorer(fish_result):
    return design.LevelExplorer(image="drawing-fish.png", tolerance=5.0, result=fish_result)


def test_explorer_shows_the_final_level_first(explorer, fish_result):
    assert explorer.level == len(fish_result.levels) - 1
    assert f"level t = {explorer.level} of {explorer.level}" in explorer.title
    assert explorer.figure.axes[0].get_title() == ""  # one title: the widget's label
    assert explorer.controls == {}  # no widgets until asked for


def test_explorer_drawing_has_a_fixed_crisp_size(explorer):
    import io

    from PIL import Image

    width, height = explorer.screen_size
    assert max(width, height) == design.EXPLORER_SIZE
    with Image.open(io.BytesIO(explorer.png())) as png:
        assert png.size == (2 * width, 2 * height)  # twice the screen size: crisp on a high-density screen
    layout = explorer.widget().children[1].children[0].layout  # the drawing, left of the controls
    assert (layout.width, layout.height) == (f"{width}px", f"{height}px")


def test_levels_within_a_smaller_tolerance_are_those_of_a_run_with_it(fish_result):
    levels = design.levels_within(fish_result, 3.0)
    alone = abstract(DATA / "drawing-fish.png", tolerance=3.0, progress=False)
    assert [len(a.arcs) for a in levels] == [len(a.arcs) for a in alone.levels]
    assert levels[-1].similarity <= 3.0 < fish_result.levels[len(levels)].similarity
    assert design.levels_within(fish_result) == fish_result.levels
    with pytest.raises(InvalidParameterError, match="tolerance must be in"):
        design.levels_within(fish_result, 6.0)


def test_explorer_tolerance_below_the_largest_run_is_instant(explorer, fish_result):
    assert explorer.on_tolerance_change(3.0) is False  # no new run
    assert explorer.result is fish_result
    assert explorer.levels == design.levels_within(fish_result, 3.0)
    assert explorer.level == explorer.n_levels - 1 and "(T = 3)" in explorer.title
    assert explorer.on_tolerance_change(5.0) is False and explorer.levels == fish_result.levels


def test_explorer_level_change_redraws(explorer):
    assert explorer.n_levels > 2
    before_title, before_png = explorer.title, explorer.png()
    explorer.on_level_change(0)
    assert explorer.level == 0
    assert "level t = 0" in explorer.title and explorer.title != before_title
    assert f"|A| = {len(explorer.result.levels[0].arcs)}" in explorer.title
    assert explorer.png() != before_png
    explorer.on_level_change(-1)
    assert explorer.level == explorer.n_levels - 1
    with pytest.raises(InvalidParameterError):
        explorer.on_level_change(explorer.n_levels)


def test_explorer_run_with_another_tolerance_changes_the_levels(explorer):
    n_before = explorer.n_levels
    seen = []
    result = explorer.on_run(tolerance=2.5)
    assert explorer.settings.tolerance == 2.5 and explorer.result is result
    assert explorer.n_levels != n_before
    assert explorer.level == explorer.n_levels - 1
    assert "T = 2.5" in explorer.title
    assert explorer.progress_text.startswith("done:")
    explorer.on_progress(3, 10, 1.5)
    seen.append(explorer.progress_text)
    assert seen == ["level 3: |A| = 10, E^s = 1.50 px"]
    with pytest.raises(InvalidParameterError):
        explorer.on_run(colour="red")


def test_explorer_widgets_drive_the_callbacks(explorer):
    box = explorer.widget()
    assert explorer.widget() is box
    c = explorer.controls
    assert c["level"].max == explorer.n_levels - 1 and c["level"].value == explorer.level
    drawing = c["drawing"].value
    c["level"].value = 1  # what dragging the slider does
    assert explorer.level == 1 and c["title"].value == explorer.title_html and "level t = 1" in explorer.title
    assert c["drawing"].value != drawing
    assert c["bias"].disabled
    c["bias_auto"].value = False
    assert not c["bias"].disabled
    c["bias_auto"].value = True
    n_before = explorer.n_levels
    first = explorer.result
    c["tolerance"].value = 3.0  # below the run's T: no new run
    assert explorer.result is first and explorer.n_levels < n_before and "(T = 3)" in c["title"].value
    fills = []
    c["progress"].observe(lambda change: fills.append(change["new"]), names="value")
    c["tolerance"].value = 9.0  # above it: a run, with the progress bar
    assert explorer.result is not first
    assert len(fills) >= 3 and max(fills) <= 9.0  # the bar moved during the run
    fills.clear()
    c["run"].click()  # what pressing Run does
    assert len(fills) >= 3 and max(fills) <= 9.0
    assert explorer.settings.tolerance == 9.0 and explorer.settings.bias is None
    assert explorer.n_levels != n_before
    assert c["level"].max == explorer.n_levels - 1 and c["level"].value == explorer.level
    assert c["progress"].max == 9.0 and c["progress"].bar_style == "success"
    assert c["progress"].value == pytest.approx(explorer.result.final.similarity)
    assert c["status"].value.startswith("done:")
    assert not c["run"].disabled


def test_explorer_symmetry_toggle_runs_a_symmetric_logo():
    pytest.importorskip("ipywidgets")
    from img2logo.symmetry import is_symmetric

    explorer = design.LevelExplorer(image="clipart-fox.png")
    assert explorer.result.symmetry is None
    explorer.widget()
    c = explorer.controls
    assert c["symmetry"].value == "none" and "auto" in c["symmetry"].options
    c["symmetry"].value = "auto"  # what choosing it does; Run runs with it
    assert explorer.widget_settings().symmetry == "auto"
    c["run"].click()
    assert explorer.settings.symmetry == "auto" and explorer.result.symmetry.axis is not None
    record = explorer.result.final.params["symmetry"]
    assert all(is_symmetric(level, record["point"], record["direction"]) for level in explorer.levels)
