"""Tests of img2logo.experiments.results: the runs, tables and figures of notebooks 01-04."""

from __future__ import annotations

import math
from types import SimpleNamespace

import matplotlib

matplotlib.use("Agg")

import numpy as np
import pytest
from matplotlib.figure import Figure

from img2logo import experiments
from img2logo.errors import InvalidParameterError
from img2logo.experiments import results
from img2logo.experiments.layout import emptiest_corner

IMAGE = "drawing-bird.png"  # the smallest example: 43 segments, about 1 s a run
T = 5.0


@pytest.fixture(scope="module")
def run() -> experiments.Run:
    (r,) = experiments.sweep([experiments.data_path(IMAGE)], tolerance=T, pipeline=True)
    return r


@pytest.fixture(scope="module")
def sweep() -> list[experiments.Run]:
    # The paper's fit: with tangent joins the result may be a level before the loop's last
    # (img2logo.fit.kinks.tangent_level), and the runs are no longer prefixes of one another.
    return experiments.sweep([experiments.data_path(IMAGE)], {"tolerance": [12.0, 3.0, 6.0]}, tangency=False)


def fake_progression(similarities: list[float]) -> SimpleNamespace:
    """Enough of a Progression for the functions that only read levels and E^s."""
    n = len(similarities)
    return SimpleNamespace(levels=[None] * n, similarities=list(similarities), arc_counts=list(range(n + 10, 10, -1)))


# --------------------------------------------------------------------------- level picking
def test_sampled_levels_spread_before_the_final_level():
    prog = fake_progression([1.0] * 10)  # levels 0..9
    assert results.sampled_levels(prog, 3) == [0, 3, 6]
    assert results.sampled_levels(fake_progression([1.0]), 3) == [0]
    assert results.sampled_levels(fake_progression([1.0, 2.0]), 3) == [0]
    with pytest.raises(InvalidParameterError):
        results.sampled_levels(prog, 0)


def test_level_at_fraction():
    prog = fake_progression([1.0] * 11)  # levels 0..10
    assert [results.level_at_fraction(prog, f) for f in (0.0, 0.4, 0.8, 1.0)] == [0, 4, 8, 10]
    with pytest.raises(InvalidParameterError):
        results.level_at_fraction(prog, 1.5)


def test_final_level_rules_differ_when_similarity_is_not_monotone():
    prog = fake_progression([1.0, 2.0, 4.0, 3.0, 5.0])
    assert not results.similarity_is_monotone(prog)
    assert results.final_level_index(prog, 3.5) == 1  # level 2 exceeds 3.5: the loop stops there
    assert results.final_level_index(prog, 3.5, rule="last_within") == 3
    assert results.final_level_index(prog, 10.0) == 4
    assert results.final_level_index(prog, 0.5) == 0
    assert results.final_level_index(prog, 0.5, rule="last_within") == 0
    with pytest.raises(InvalidParameterError):
        results.final_level_index(prog, 1.0, rule="nope")
    assert results.similarity_is_monotone(fake_progression([1.0, 1.0, 2.0]))


# --------------------------------------------------------------------------- junction gaps
def _spread(a):
    """How far apart the arcs of each junction pass, px (:func:`img2logo.quality.junction_gaps`)."""
    from img2logo.quality import junction_gaps

    return junction_gaps(a.arcs, a.junctions, a.junction_arcs)[1]


def test_circle_fitting_stages_meet_only_with_connectivity(run):
    stages = results.circle_fitting_stages([run])
    free, con = (s.final for s in stages)
    assert [s.variant for s in stages] == ["independent", "constrained"]
    assert free.arc_segments == con.arc_segments
    assert [a.circle.r for a in free.arcs] == pytest.approx([a.circle.r for a in con.arcs])
    assert _spread(con).max() < 1e-3
    assert _spread(free).max() > 0.5
    table = results.circle_fitting_table(stages)
    assert list(table.columns) == [
        "image",
        "arcs",
        "junctions",
        "max gap independent (px)",
        "mean gap independent (px)",
        "max gap constrained (px)",
    ]
    assert table.loc[0, "max gap constrained (px)"] < table.loc[0, "max gap independent (px)"]
    fig = results.plot_circle_fitting(stages)
    assert isinstance(fig, Figure)
    assert len(fig.axes) == 3
    assert "px here" in fig.axes[1].get_title()


# --------------------------------------------------------------------------- Fig. 1, 4, 7, 10
def test_results_table(run):
    table = results.results_table([run])
    assert list(table.columns) == [
        "image",
        "kind",
        "segments",
        "arcs A^0",
        "final arcs",
        "iterations",
        "E^s (px)",
        "bias",
        "stopped because",
    ]
    row = table.iloc[0]
    assert row["image"] == "drawing-bird"
    assert row["kind"] == "drawing"
    assert row["arcs A^0"] - row["iterations"] == row["final arcs"]  # one arc less per merge
    assert row["final arcs"] <= row["arcs A^0"] <= row["segments"]
    assert row["E^s (px)"] <= T
    assert 0.0 <= row["bias"] < 1.0


def test_figures_have_their_panels(run):
    fig = results.plot_overview([run], levels=3)
    assert isinstance(fig, Figure)
    assert len(fig.axes) == 3 + 3 + 1
    assert fig.axes[-1].get_title().startswith("(d) final")
    fig = results.plot_arc_fitting([run, run])
    assert len(fig.axes) == 6
    grid = results.plot_results_grid([run, run, run], columns=2)
    main = [ax for ax in grid.axes if ax.get_title()]
    assert len(main) == 3  # and one empty panel, turned off
    assert all("|A| =" in ax.get_title() for ax in main)
    assert len(grid.axes) == 4
    assert sum(len(ax.child_axes) for ax in grid.axes) == 3  # an inset of the input per result


def test_inset_goes_where_the_arcs_are_not(run):
    a = run.final
    points = np.vstack([arc.sample(step=2.0) for arc in a.arcs])
    x, y = emptiest_corner(points, a.width, a.height, 0.3)
    assert (x, y) in {(0.7, 0.0), (0.7, 0.7), (0.0, 0.0), (0.0, 0.7)}


# --------------------------------------------------------------------------- Table 1
def test_simplicity_table(run):
    table = results.simplicity_table([run], fractions=(0.0, 1.0))
    ours = table[table["arcs"].notna()]
    assert list(ours["iteration"]) == list(range(len(run.levels)))
    assert np.all(np.diff(ours["arcs"].to_numpy(dtype=float)) == -1.0)
    assert ours["final"].sum() == 1 and bool(ours["final"].iloc[-1])
    assert ours["shown"].sum() == 2
    assert table.loc[table["iteration"] == 0, "paper |A|"].item() == 51
    assert table.loc[table["iteration"] == 23, "paper |A|"].item() == 28
    assert math.isnan(table.loc[table["iteration"] == 28, "paper |A|"].item())
    fig = results.plot_simplicity_levels([run], fractions=(0.0, 0.5, 1.0))
    assert len(fig.axes) == 3
    assert "(final)" in fig.axes[-1].get_title()
    fig = results.plot_progression([run])
    assert len(fig.axes) == 2  # |A| and its twin E^s axis


# --------------------------------------------------------------------------- Table 2
def test_tolerance_sweep_arc_counts_fall_with_tolerance(sweep):
    mine = sorted(sweep, key=lambda r: r.final.tolerance)  # one image's runs
    assert [r.final.tolerance for r in mine] == [3.0, 6.0, 12.0]
    arcs = [len(r.final.arcs) for r in mine]
    assert arcs == sorted(arcs, reverse=True)
    assert arcs[0] > arcs[-1]
    for r in mine:
        assert r.final.similarity <= r.final.tolerance
    with pytest.raises(InvalidParameterError, match=r"^no run with T = 4.0 in the sweep \[3.0, 6.0, 12.0\]"):
        results.plot_tolerance_results(sweep, (4.0,))


def test_tolerance_tables(sweep):
    table = results.tolerance_table(sweep, paper={3.0: 99.0})
    assert list(table["T"]) == [3.0, 6.0, 12.0]
    assert table.loc[0, "paper |A|"] == 99.0
    assert table["paper |A|"].isna().sum() == 2
    # The merges do not depend on T: each run is a prefix of the largest-T run.
    assert list(table["arcs by first exceedance"]) == list(table["final arcs"])
    mono = results.monotonicity_table(sweep)
    assert mono.loc[0, "first exceedance matches"]
    assert mono.loc[0, "levels"] == len(sweep[0].levels)  # T = 12, the longest run
    assert mono.loc[0, "E^s monotone"] == results.similarity_is_monotone(sweep[0].progression)
    fig = results.plot_tolerance_results(sweep, (3.0, 12.0))
    assert len(fig.axes) == 3
    fig = results.plot_tolerance_curve(sweep)
    assert len(fig.axes) == 2


def test_paper_tables():
    assert results.PAPER_TABLE1[0] == 51 and results.PAPER_TABLE1[23] == 28
    assert results.PAPER_TABLE2[4.0] == 31
