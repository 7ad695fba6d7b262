"""Tests of img2logo.recovery: the initial fit when the joint fit fails, radii that cannot reach."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import check_level, golden_chain

from img2logo import InvalidParameterError
from img2logo.progressive import optimize


def test_radii_too_small_for_the_junctions_are_named():
    graph, _ = golden_chain()
    with pytest.raises(InvalidParameterError, match=r"chosen radii \(k = 1, 2, 3: .* px\) are too small"):
        optimize(graph, exponents=[1, 2, 3])


def test_a_junction_the_fit_cannot_meet_is_released(monkeypatch):
    from img2logo import progressive, recovery

    graph, _ = golden_chain()
    stuck = 2  # pretend that no fit can meet junction 2 (where arcs 2 and 3 join)
    solve = progressive._Optimizer.solve

    def failing(self, groups, *args, **kwargs):
        nodes = {n for g in groups.values() for n in self.constrained_nodes(g)}
        return None if stuck in nodes else solve(self, groups, *args, **kwargs)

    monkeypatch.setattr(progressive._Optimizer, "solve", failing)
    with pytest.warns(recovery.ConnectivityWarning, match=r"could not meet [12] of 4 junctions"):
        progression = optimize(graph, merging=False, simplify=False)
    assert 1 <= progression.stats["released_junctions"] <= 2
    level = progression.levels[0]
    check_level(level)  # the junctions it lists are met exactly
    assert len(level.arcs) == 3
    assert not any(np.allclose(j, graph.junctions[stuck], atol=1e-6) for j in level.junctions)


def test_a_part_with_every_junction_released_still_gets_its_arcs(monkeypatch):
    # No fit with any constraint succeeds: recovery releases every junction, and the last
    # solve (a window no junction touches) fits each circle alone (issue 20, item 1).
    from img2logo import progressive, recovery

    graph, truth = golden_chain()
    solve = progressive._Optimizer.solve

    def failing(self, groups, *args, **kwargs):
        constrained = any(self.constrained_nodes(g) for g in groups.values())
        return None if constrained else solve(self, groups, *args, **kwargs)

    monkeypatch.setattr(progressive._Optimizer, "solve", failing)
    with pytest.warns(recovery.ConnectivityWarning, match=r"could not meet 4 of 4 junctions"):
        progression = optimize(graph, merging=False, simplify=False)
    level = progression.levels[0]
    assert len(level.arcs) == 3 and progression.stats["released_junctions"] == 4
    for arc, (center, radius) in zip(level.arcs, truth, strict=True):  # each circle where its points are
        assert arc.circle.r == pytest.approx(radius, rel=1e-9)
        np.testing.assert_allclose(arc.circle.center, center, atol=1e-3)


def test_one_huge_radius_on_a_real_drawing_gives_a_logo(data_dir):
    # --radii 15 (r = 1364 px on a 512 px drawing): no fit meets the junctions; released, not a crash.
    from img2logo import abstract, recovery

    with pytest.warns(recovery.ConnectivityWarning):
        result = abstract(data_dir / "drawing-fish.png", exponents=[15], progress=False)
    assert result.final.arcs and {a.circle.k for a in result.final.arcs} == {15}


def test_radii_too_large_for_the_image_are_named():
    # The smallest radius allowed is over 20 x the longer side (600 px): a straight line to the fit.
    graph, _ = golden_chain()
    with pytest.raises(
        InvalidParameterError, match=r"the smallest, 1\.5e\+04 px, is over 20 x .* \(600 px\), .*--unit"
    ):
        optimize(graph, ladder="fibonacci", unit=15000.0)
    with pytest.raises(InvalidParameterError, match=r"choose smaller exponents \(--radii\)"):
        optimize(graph, exponents=[24, 25], bias=0.0)  # phi**24 = 103682 px
