"""img2logo.experiments.design: Table 3 timing, Fig. 15, 16 (notebooks 09, 10)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import DATA, modules_loaded

from img2logo import InvalidParameterError, abstract
from img2logo.experiments import design, preprocess, sweep
from img2logo.geometry.abstraction import Abstraction
from img2logo.geometry.primitives import Arc, Circle

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
    code = "import img2logo.experiments, img2logo.experiments.design, img2logo.experiments.explore"
    assert modules_loaded(code, "ipywidgets") == []


# --------------------------------------------------------------------------- Table 3
def test_timing_table_has_the_four_cells_and_the_paper_beside(leaf):
    runs = sweep([leaf], variants=design.TIMING_VARIANTS, repeats=2)
    cells = [(r.settings.get("localized", True), r.settings.get("simplify", True)) for r in runs]
    assert cells == list(design.CELLS)
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
    golden = {k: ((1.0 + math.sqrt(5.0)) / 2.0) ** (k + 0.5) for k, _ in ks_and_lengths}  # radii on the ladder
    arcs = tuple(Arc(Circle(0.0, 0.0, golden[k], k), 0.0, length / golden[k]) for k, length in ks_and_lengths)
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
