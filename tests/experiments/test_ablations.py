"""The ablations of Sec. 6.2 (Fig. 6, 11, 12, 13): experiments.ablations."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest
from helpers import drawing
from matplotlib.figure import Figure

from img2logo import experiments
from img2logo.errors import InvalidParameterError
from img2logo.experiments import ablations
from img2logo.fit.progressive import optimize
from img2logo.segment_graph import SegmentGraph


@pytest.fixture(scope="module")
def bird() -> experiments.Run:
    return experiments.preprocess([experiments.data_path("drawing-bird.png")])[0]


@pytest.fixture(scope="module")
def connectivity_runs(bird) -> list[experiments.Run]:
    return experiments.sweep([bird], variants=ablations.CONNECTIVITY_VARIANTS)


def y_graph() -> SegmentGraph:
    """A "Y": three straight segments meeting at node 0, the stem split in two at node 4."""
    arm = np.linspace(0.0, 30.0, 31)
    segments = [
        np.column_stack([50 - arm, 50 - arm]),  # 0 -> 1
        np.column_stack([50 + arm, 50 - arm]),  # 0 -> 2
        np.column_stack([50 + 0 * arm, 50 + arm]),  # 0 -> 4
        np.column_stack([50 + 0 * arm, 80 + arm]),  # 4 -> 3
    ]
    nodes = [[50, 50], [20, 20], [80, 20], [50, 110], [50, 80]]
    return SegmentGraph(tuple(segments), np.array(nodes, float), np.array([[0, 1], [0, 2], [0, 4], [4, 3]]), 120, 120)


# --------------------------------------------------------------------------- topology of a level
def test_arc_chain_orients_the_segments_along_the_path() -> None:
    g = y_graph()
    nodes, points = ablations.arc_chain(g, [1, 2, 3])
    assert nodes == (2, 0, 4, 3)
    np.testing.assert_allclose(points[0], [80, 20])
    np.testing.assert_allclose(points[-1], [50, 110])
    assert len(points) == 3 * 31 - 2
    assert ablations.arc_chain(g, [2])[0] == (0, 4)  # one segment keeps its direction
    with pytest.raises(InvalidParameterError, match="do not form a path"):
        ablations.arc_chain(g, [0, 3])


def test_arc_paths_hold_the_junctions_the_optimizer_kept(connectivity_runs) -> None:
    for run in connectivity_runs:
        for level in (run.progression.levels[0], run.final):
            for i, path in enumerate(ablations.arc_paths(level, run.graph)):
                assert set(level.arc_nodes(i)) <= set(path)
                assert {path[0], path[-1]} <= set(level.arc_nodes(i))  # its ends are junctions


# --------------------------------------------------------------------------- Fig. 11
def test_connectivity_constraint_closes_every_gap(connectivity_runs) -> None:
    table = ablations.connectivity_table(connectivity_runs)
    assert list(table["variant"]) == list(ablations.CONNECTIVITY_VARIANTS)
    assert {"arcs", "E^s", "max gap", "mean gap", "junctions with gap > 0.5 px", "redundant intersections"} <= set(
        table.columns
    )
    by = table.set_index("variant")
    assert by.loc["(b) with connectivity", "max gap"] < 1e-3
    assert by.loc["(e) as (d), no merging", "max gap"] < 1e-3
    assert by.loc["(c) without connectivity", "max gap"] > 1.0
    assert by.loc["(c) without connectivity", "junctions with gap > 0.5 px"] > 0
    # no merging keeps more arcs than merging
    assert by.loc["(e) as (d), no merging", "arcs"] > by.loc["(d) start/end junctions only", "arcs"]
    assert (table["E^s"] <= 5.0).all()


def test_end_junction_constraints_miss_an_inner_junction_of_a_synthetic_y() -> None:
    # The Y's stem (segments 2, 3) merged into one arc: with only its ends
    # constrained it need not pass through node 0, where the arms end.
    g = y_graph()
    bent = optimize(g, tolerance=50.0, inner_junctions=False)
    gaps = ablations.gap_table(bent.final, g)
    assert set(gaps.columns) >= {"node", "x", "y", "gap", "spread", "arcs"}
    assert (gaps["arcs"] >= 2).all()
    assert bent.final.arc_segments == ((0,), (1, 2, 3))  # an arm and the stem through node 0
    inner = gaps.set_index("node").loc[0]
    assert inner["in_J'"] and inner["valence"] == 3
    assert inner["gap"] > 0.5  # the merged arc misses the junction the other arm ends at
    full = ablations.gap_table(optimize(g, tolerance=50.0).final, g)
    assert full["gap"].max() < 1e-3


def test_gap_table_and_figure(connectivity_runs) -> None:
    gaps = ablations.junction_gap_table(connectivity_runs)
    assert set(gaps["variant"]) == set(ablations.CONNECTIVITY_VARIANTS)
    windows = ablations.gap_windows(connectivity_runs, count=2)
    assert 1 <= len(windows) <= 2
    for _, (x0, y0, x1, y1) in windows:
        assert x1 - x0 == pytest.approx(y1 - y0) and x1 - x0 >= 48.0
    fig = ablations.plot_connectivity_ablation(connectivity_runs, zooms=1)
    assert isinstance(fig, Figure)
    assert len(fig.axes) == 2 * 5


# --------------------------------------------------------------------------- Fig. 12
def test_redundant_table_and_selection(bird) -> None:
    runs = experiments.sweep([bird], {"tolerance": [5.0, 9.0]}, ablations.AVOIDANCE_VARIANTS)
    table = ablations.redundant_table(runs)
    assert len(table) == 4
    assert list(table["T"]) == [5.0, 5.0, 9.0, 9.0]
    assert (table["redundant intersections"] >= 0).all()
    effect = ablations.avoidance_effect(table)
    assert list(effect.columns) == ["image", "T", "with", "without", "difference", "arcs with", "arcs without"]
    assert len(effect) == 2
    fake = pd.DataFrame({"image": ["a", "a", "b", "c"], "T": [5.0, 9.0, 5.0, 5.0], "difference": [1, 3, 1, 0]})
    assert ablations.select_cases(fake, 2) == [("a", 9.0), ("b", 5.0)]
    fig = ablations.plot_redundant_intersections(runs, [("drawing-bird", 5.0)])
    assert len(fig.axes) == 5
    with pytest.raises(InvalidParameterError, match="no runs"):
        ablations.plot_redundant_intersections(runs, [("drawing-bird", 7.0)])


# --------------------------------------------------------------------------- Fig. 13
def test_rdp_sweep_fewer_segments_for_larger_tolerances() -> None:
    from img2logo.features.preprocessing import load_image

    runs = experiments.sweep([load_image(drawing("spiral", size=160))], {"rdp_tolerance": [1.0, 4.0]})
    table = ablations.rdp_table(runs)
    assert list(table["rdp tolerance"]) == [1.0, 4.0]
    assert table["segments"].iloc[0] > table["segments"].iloc[1]
    assert (table["final arcs"] <= table["arcs at A^0"]).all()
    assert (table["arcs at A^0"] <= table["segments"]).all()
    fig = ablations.plot_rdp_sweep(runs)
    assert len(fig.axes) == 4
