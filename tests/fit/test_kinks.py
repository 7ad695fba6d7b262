"""The level kept and the arcs split beside a kink, after the tangent pass."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import DATA

from img2logo import abstract, quality
from img2logo.fit.constants import KINK_WEIGHT


# --------------------------------------------------------------------------- the level kept
class _Levels:
    """A stand-in for the optimizer's state: a level is its number of groups; kinks[k] joins stay kinked k back."""

    def __init__(self, kinks):
        from img2logo.fit.fit_values import Stats

        self.kinks, self.passes = kinks, []
        self.fits, self.disp, self.groups = {}, np.zeros((1, 2)), dict.fromkeys(range(len(kinks)))
        self.off_line, self.loose, self.held, self.stats = {}, set(), set(), Stats()
        self.outline = frozenset()  # no silhouette: no arc is split at a kink (split_kinks)

    def invalidate(self):
        pass


@pytest.mark.parametrize(
    ("kinks", "weight", "back", "passes"),
    [
        ((3, 1, 0), 1, 1, 2),  # 3 kinks, or 1 more arc and 1 kink: 2 back could only tie, so it is not tried
        ((1, 0, 0), 1, 0, 1),  # one kink: a level further back cannot do better than one more arc
        ((0, 0, 0), 2, 0, 1),  # all tangent on the last level: the loop's result
        ((4, 3, 0, 0, 0), 1, 2, 3),  # the search stops where the levels back reach the best score
        ((1, 1, 0, 0), 2, 0, 2),  # a kink weighs two arcs: 2 more arcs for it only tie, the later level kept
        ((1, 0, 0), 2, 1, 2),  # ... and one more arc for it wins
    ],
)
@pytest.mark.parametrize("stops", [False, True])
def test_the_level_kept_has_the_fewest_arcs_plus_weighted_kinks(monkeypatch, kinks, weight, back, passes, stops):
    from img2logo.fit import kinks as kink_pass, tangency

    levels = _Levels(kinks)
    history = [tangency.snapshot(_at(levels, len(kinks) - k)) for k in range(len(kinks))][::-1]
    levels.groups = dict.fromkeys(range(len(kinks)))  # the last level is the current state

    def fake_pass(opt, tolerance, most_loose=None):
        k = len(kinks) - len(opt.groups)  # levels back
        opt.passes.append(k)
        assert (most_loose is None) == (k == 0)  # the last level's pass is never stopped
        # A pass that stops once it cannot win: the same level kept.
        if stops and most_loose is not None and kinks[k] > most_loose:
            opt.loose = set(range(most_loose + 1))  # what it left half made
            raise tangency.Outscored
        opt.loose = set(range(kinks[k]))
        return True

    monkeypatch.setattr(kink_pass, "tangent_joins", fake_pass)
    monkeypatch.setattr(kink_pass, "KINK_WEIGHT", weight)
    assert kink_pass.tangent_level(levels, 5.0, history) == back
    assert len(levels.passes) == passes and len(levels.groups) == len(kinks) - back
    assert len(levels.loose) == kinks[back]


@pytest.mark.parametrize(("room", "back", "passes"), [(0, 0, 1), (1, 1, 2), (2, 2, 3), (None, 2, 3)])
def test_the_levels_back_stay_within_the_arc_budget(monkeypatch, room, back, passes):
    """4 kinks on the last level, 2 one back, none two back: a kink weighs one arc, so two levels back win,
    unless the arc budget leaves room for fewer arcs; then the kinks stay."""
    from img2logo.fit import kinks as kink_pass, tangency

    kinks = (4, 2, 0, 0, 0)
    levels = _Levels(kinks)
    history = [tangency.snapshot(_at(levels, len(kinks) - k)) for k in range(len(kinks))][::-1]
    levels.groups = dict.fromkeys(range(len(kinks)))

    def fake_pass(opt, tolerance, most_loose=None):
        opt.passes.append(len(kinks) - len(opt.groups))
        opt.loose = set(range(kinks[len(kinks) - len(opt.groups)]))
        return True

    monkeypatch.setattr(kink_pass, "tangent_joins", fake_pass)
    monkeypatch.setattr(kink_pass, "KINK_WEIGHT", 1)
    assert kink_pass.tangent_level(levels, 5.0, history, room=room) == back
    assert len(levels.passes) == passes and len(levels.loose) == kinks[back]


def _at(levels, n):
    levels.groups = dict.fromkeys(range(n))
    return levels


@pytest.fixture(scope="module")
def warning_sign():
    """Openclipart's warning sign, with and without :func:`~img2logo.fit.kinks.split_kinks`."""
    from img2logo.fit import kinks as kink_pass

    path = DATA.parent / "benchmarks" / "data" / "openclipart" / "clipart-charge.png"
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(kink_pass, "split_kinks", lambda opt, tolerance, room=None: 0)
        kinked = abstract(path, progress=False)
    return path, kinked, abstract(path, progress=False)


def test_a_short_arc_at_a_kinked_silhouette_join_makes_it_tangent_within_t(warning_sign):
    """The sign's rounded corners: two long arcs of the silhouette meet at a smooth node and no two circles
    on their rungs touch there within T of the pixels. Split beside the kink, a short arc turns the
    tangent between them: every smooth join tangent, the silhouette kept (sil6 0.90 before)."""
    import cv2

    from img2logo.quality import logo_points, silhouette_recall

    path, kinked, split = warning_sign
    before = quality.joins(kinked.final, kinked.graph)
    after = quality.joins(split.final, split.graph)
    assert np.any(np.degrees(before.kinks) >= 2.0)
    assert after.count > before.count and np.all(np.degrees(after.kinks) < 2.0)
    assert len(kinked.final.arcs) < len(split.final.arcs) <= len(kinked.final.arcs) + KINK_WEIGHT * before.count
    mask = cv2.imread(str(path.with_suffix(".silhouette.png")), cv2.IMREAD_GRAYSCALE) > 127
    assert silhouette_recall(logo_points(split.final), mask) >= silhouette_recall(logo_points(kinked.final), mask)
    assert split.final.similarity <= split.final.params["tolerance"]


@pytest.fixture(scope="module")
def polar_bear_passes():
    """The polar bear's result with its tangent passes stopped once they cannot win, and run to the end."""
    from img2logo.fit import kinks as kink_pass, tangency

    path = DATA.parent / "benchmarks" / "data" / "clipart-polar-bear.png"
    stopped = []
    original = tangency.tangent_joins

    def counted(opt, tolerance, most_loose=None):
        try:
            return original(opt, tolerance, most_loose)
        except tangency.Outscored:
            stopped.append(most_loose)
            raise

    def to_the_end(opt, tolerance, most_loose=None):
        return original(opt, tolerance)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(kink_pass, "tangent_joins", counted)
        fast = abstract(path, progress=False)
        mp.setattr(kink_pass, "tangent_joins", to_the_end)
        full = abstract(path, progress=False)
    return fast, full, stopped


def test_a_tangent_pass_that_cannot_win_stops_and_the_result_is_the_same(polar_bear_passes):
    # Its last level leaves joins kinked, so levels back are searched; the passes that cannot
    # beat the best level stop early, and the level kept and its arcs are the same to the bit.
    fast, full, stopped = polar_bear_passes
    assert stopped, "some pass stopped early"
    assert fast.final.level == full.final.level and len(fast.levels) == len(full.levels)
    assert fast.final.similarity == full.final.similarity
    for a, b in zip(fast.final.arcs, full.final.arcs, strict=True):
        assert a == b
    for key in ("tangent_joins", "released_tangencies"):
        assert fast.progression.stats[key] == full.progression.stats[key]
