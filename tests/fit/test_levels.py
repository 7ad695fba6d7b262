"""Tests of img2logo.fit.levels: a run's levels, each made when first asked for, the same values in any order."""

from __future__ import annotations

import pytest
from helpers import DATA

from img2logo import build_segment_graph, extract_feature_lines
from img2logo.fit.levels import Levels
from img2logo.fit.progressive import optimize
from img2logo.geometry.abstraction import Abstraction


def _document(level: Abstraction) -> dict:
    from img2logo.export.contract import to_document

    return to_document(level)


@pytest.fixture(scope="module")
def fish_graph():
    return build_segment_graph(extract_feature_lines(DATA / "clipart-fish.png"))


def test_a_runs_levels_are_made_when_first_asked_for(fish_graph):
    prog = optimize(fish_graph, tolerance=5.0)
    levels = prog.levels
    assert isinstance(levels, Levels) and len(levels) > 5
    assert levels.made() <= 1  # at most the final (the tangent joins' refit makes it at once)
    counts, similarities = prog.arc_counts, prog.similarities  # without making the levels
    assert levels.made() <= 1
    final = prog.final
    assert final is levels[-1] is levels[len(levels) - 1] and levels.made() <= 2
    made = list(levels)
    assert levels.made() == len(levels) and all(a is b for a, b in zip(made, levels, strict=True))
    assert counts == [len(a.arcs) for a in made] and similarities == [a.similarity for a in made]
    assert [a.level for a in made] == list(range(len(made)))


def test_levels_made_in_any_order_are_those_made_in_order(fish_graph):
    """Each level is the same value whatever the order the levels are made in (its arcs' topology
    reused from a level made before where the arc and its junctions' points are the same)."""
    in_order = [_document(a) for a in optimize(fish_graph, tolerance=5.0).levels]
    levels = optimize(fish_graph, tolerance=5.0).levels
    n = len(levels)
    order = [n - 1, 0, n // 2, *range(n - 2, 0, -1)]
    by_level = {t: _document(levels[t]) for t in dict.fromkeys(order)}
    assert len(by_level) == n and [by_level[t] for t in range(n)] == in_order


def test_levels_behave_as_a_tuple_of_abstractions(fish_graph, tmp_path):
    import pickle
    from concurrent.futures import ThreadPoolExecutor

    prog = optimize(fish_graph, tolerance=5.0)
    levels = prog.levels
    with ThreadPoolExecutor(4) as pool:  # threads asking for one level at once get one Abstraction
        got = list(pool.map(lambda _: levels[3], range(8)))
    assert all(a is got[0] for a in got)
    assert isinstance(levels[1:4], tuple) and len(levels[1:4]) == 3 and levels[1:4][0] is levels[1]
    assert levels[::-1][0] is levels[-1] and levels == tuple(levels) and levels != tuple(levels)[:-1]
    assert levels != "levels" and levels.index(levels[2]) == 2
    with pytest.raises(IndexError, match="out of range"):
        levels[len(levels)]
    with pytest.raises(TypeError):
        hash(levels)
    back = pickle.loads(pickle.dumps(prog))
    assert [_document(a) for a in back.levels] == [_document(a) for a in levels]
    shifted = levels.map(lambda a: a.scaled(2.0, 2 * a.width, 2 * a.height))
    assert shifted.made() == 0 and len(shifted) == len(levels)
    assert _document(shifted[-1]) == _document(levels[-1].scaled(2.0, 2 * levels[-1].width, 2 * levels[-1].height))
    assert shifted.arc_counts() == prog.arc_counts
