"""Tests of img2logo.recovery: the initial fit when the joint fit fails, radii that cannot reach."""

from __future__ import annotations

import numpy as np
import pytest
from conftest import check_level, golden_chain

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
