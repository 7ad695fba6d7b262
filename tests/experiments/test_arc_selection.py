"""Arc extraction, Fréchet against sum of squares (Fig. 9): experiments.arc_selection."""

from __future__ import annotations

import math

import pytest
from matplotlib.figure import Figure

from img2logo import experiments
from img2logo.errors import InvalidParameterError
from img2logo.experiments import arc_selection


@pytest.fixture(scope="module")
def bird() -> experiments.Run:
    return experiments.preprocess([experiments.data_path("drawing-bird.png")])[0]


def test_hook_sum_of_squares_keeps_a_redundant_part() -> None:
    ex = arc_selection.hook_example(60.0)
    assert ex.differs
    assert abs(ex.frechet.arc.sweep) == pytest.approx(math.pi / 2)
    assert abs(ex.sum_of_squares.arc.sweep) == pytest.approx(1.5 * math.pi)
    assert ex.sum_of_squares.frechet > ex.frechet.frechet + 40.0
    table = arc_selection.hook_table([0.0, 60.0])
    assert list(table["differs"]) == [False, True]
    assert table.loc[0, "Fréchet F"] == pytest.approx(0.0, abs=1e-9)
    assert isinstance(arc_selection.plot_hook_example(ex, table), Figure)
    with pytest.raises(InvalidParameterError):
        arc_selection.hook_example(200.0)


def test_compare_arc_selection_reproduces_the_levels(bird) -> None:
    runs = experiments.sweep([bird], variants=arc_selection.ARC_SELECTION_VARIANTS)
    comparisons = arc_selection.arc_selection_study(runs)
    assert len(comparisons) == len(runs[0].progression.levels)
    for comp in comparisons:
        assert comp.table["reproduces level"].all()
        assert len(comp.table) == len(comp.level.arcs)
        assert (comp.table["candidates"] >= 1).all()
    table = arc_selection.arc_selection_table(runs, comparisons)
    assert len(table) == 1
    row = table.iloc[0]
    assert row["arcs compared"] == sum(len(c.level.arcs) for c in comparisons)
    assert row["differ"] == len(arc_selection.differing_arcs(comparisons))
    assert isinstance(arc_selection.plot_arc_selection(comparisons), Figure)
