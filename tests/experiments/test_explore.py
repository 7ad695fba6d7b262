"""img2logo.experiments.explore: the level explorer (notebook 11), its callbacks without a browser."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import DATA

from img2logo import InvalidParameterError, abstract
from img2logo.experiments import explore


@pytest.fixture(scope="module")
def fish_result():
    return abstract(DATA / "drawing-fish.png", progress=False)


# --------------------------------------------------------------------------- the explorer
def test_level_strip_spreads_the_levels(fish_result):
    n = len(fish_result.levels)
    fig = explore.plot_level_strip(fish_result, 3)
    assert len(fig.axes) == min(3, n)
    assert fig.axes[0].get_title().startswith("t = 0:")
    assert fig.axes[-1].get_title().startswith(f"t = {n - 1}:")
    assert len(explore.plot_level_strip(fish_result, [0, -1]).axes) == 2


def test_levels_table_has_one_row_per_level_with_fewer_arcs_each(fish_result):
    table = explore.levels_table(fish_result)
    assert list(table["t"]) == list(range(len(fish_result.levels)))
    assert (np.diff(table["arcs"]) == -1).all()
    assert table["E^s (px)"].iloc[-1] <= fish_result.final.tolerance


@pytest.fixture
def explorer(fish_result):
    return explore.LevelExplorer(image="drawing-fish.png", tolerance=5.0, result=fish_result)


def test_explorer_shows_the_final_level_first(explorer, fish_result):
    assert explorer.level == len(fish_result.levels) - 1
    assert f"level t = {explorer.level} of {explorer.level}" in explorer.title
    assert explorer.figure.axes[0].get_title() == ""  # one title: the widget's label
    assert explorer.controls == {}  # no widgets until asked for


def test_explorer_drawing_has_a_fixed_crisp_size(explorer):
    pytest.importorskip("ipywidgets", reason="the explorer's widgets need the extra [kit]")
    import io

    from PIL import Image

    width, height = explorer.screen_size
    assert max(width, height) == explore.EXPLORER_SIZE
    with Image.open(io.BytesIO(explorer.png())) as png:
        assert png.size == (2 * width, 2 * height)  # twice the screen size: crisp on a high-density screen
    layout = explorer.widget().children[1].children[0].layout  # the drawing, left of the controls
    assert (layout.width, layout.height) == (f"{width}px", f"{height}px")


def test_levels_within_a_smaller_tolerance_are_those_of_a_run_with_it(fish_result):
    levels = explore.levels_within(fish_result, 3.0)
    alone = abstract(DATA / "drawing-fish.png", tolerance=3.0, progress=False)
    assert [len(a.arcs) for a in levels] == [len(a.arcs) for a in alone.levels]
    assert levels[-1].similarity <= 3.0 < fish_result.levels[len(levels)].similarity
    assert explore.levels_within(fish_result) == fish_result.levels
    with pytest.raises(InvalidParameterError, match="tolerance must be in"):
        explore.levels_within(fish_result, 6.0)


def test_explorer_tolerance_below_the_largest_run_is_instant(explorer, fish_result):
    assert explorer.on_tolerance_change(3.0) is False  # no new run
    assert explorer.result is fish_result
    assert explorer.levels == explore.levels_within(fish_result, 3.0)
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
    pytest.importorskip("ipywidgets", reason="the explorer's widgets need the extra [kit]")
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
    from img2logo.fit.symmetry import is_symmetric

    explorer = explore.LevelExplorer(image="clipart-fox.png")
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


def test_a_settings_value_runs_as_its_option_fields():
    import cv2

    from img2logo.studio.session import StudioSettings

    image = np.full((120, 120, 3), 255, np.uint8)
    cv2.circle(image, (60, 60), 40, (0, 0, 0), 3)
    settings = StudioSettings(tolerance=7.0, ladder="fibonacci", lines=True, fill="auto")  # fill: no option
    got = explore.abstract_with_settings(image, settings, progress=False)
    want = abstract(image, tolerance=7.0, ladder="fibonacci", lines=True, progress=False)
    assert got.final.arcs == want.final.arcs and dict(got.params) == dict(want.params)
    shown = explore.abstract_with_settings(image, explore.ExplorerSettings(image="ring.png"), progress=False)
    assert dict(shown.params) == dict(abstract(image, progress=False).params)
