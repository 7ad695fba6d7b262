"""Tangent joins (beyond the paper): the result's circles touch where the input runs on smoothly."""

from __future__ import annotations

import math

import numpy as np
import pytest
from helpers import DATA

from img2logo import abstract, quality
from img2logo.fit.constants import KINK_WEIGHT
from img2logo.quality import arc_direction


@pytest.fixture(scope="module")
def snail():
    return {t: abstract(DATA / "drawing-snail.png", progress=False, tangency=t) for t in (True, False)}


def test_smooth_joins_are_tangent_and_their_circles_touch(snail):
    result = snail[True]
    found = quality.joins(result.final, result.graph)
    assert found.count >= 1 and result.progression.stats["tangent_joins"] == found.count
    for j in found.junctions:
        a, b = (result.final.arcs[i].circle for i in result.final.arcs_at(j))
        q = result.final.junctions[j]
        distance = math.dist(a.center, b.center)
        # The circles touch at the junction: centre distance |r1 - r2| or r1 + r2, to 1e-6 px ...
        assert min(abs(distance - abs(a.r - b.r)), abs(distance - (a.r + b.r))) <= 1e-6
        # ... and the junction is on the line of centres.
        u = (b.center - a.center) / distance
        assert abs(u[0] * (q - a.center)[1] - u[1] * (q - a.center)[0]) <= 1e-6
    assert np.all(np.degrees(found.kinks) < 1e-3)
    assert result.final.params["tangency"] is True


def test_without_tangency_the_paper_kinks(snail):
    result = snail[False]
    found = quality.joins(result.final, result.graph)
    assert found.count == 2 and np.all(np.degrees(found.kinks) > 2.0)
    assert result.final.params["tangency"] is False
    assert result.progression.stats["tangent_joins"] == 0


def test_a_right_angle_corner_stays_a_corner(tmp_path):
    import cv2

    img = np.full((200, 200, 3), 255, np.uint8)
    cv2.polylines(img, [np.array([[40, 160], [40, 40], [160, 40]], np.int32)], False, (0, 0, 0), 3)
    path = tmp_path / "corner.png"
    cv2.imwrite(str(path), img)
    result = abstract(path, progress=False, kind="drawing")
    graph, level = result.graph, result.final
    assert not result.progression.stats["tangent_joins"]
    corner = [j for j, p in enumerate(level.junctions) if math.dist(p, (40.5, 40.5)) < 6 and len(level.arcs_at(j)) == 2]
    assert corner, "the corner is a junction of two arcs"
    j = corner[0]
    assert level.junction_nodes[j] not in graph.smooth_nodes()
    ends = []
    for i in level.arcs_at(j):
        t = level.arc_junctions[i]
        ends.append(arc_direction(level.arcs[i], t.start == j))
    kink = math.degrees(math.acos(float(np.clip(-np.dot(*ends), -1.0, 1.0))))
    assert kink == pytest.approx(90.0, abs=15.0)


def test_split_a_chain_where_the_junction_slid():
    from img2logo.fit.tangency import split_chain

    chain = np.column_stack([np.arange(10.0), np.zeros(10)])
    head, tail, off = split_chain(chain, np.array([4.25, 0.5]))
    # The foot of the junction on the chain ends the head and starts the tail; its distance off the line.
    assert np.allclose(head[-1], (4.25, 0.0)) and np.allclose(tail[0], (4.25, 0.0))
    assert len(head) == 6 and len(tail) == 6 and off == pytest.approx(0.5)
    assert np.array_equal(np.vstack([head[:-1], tail[1:]]), chain)
    # Slid so far that one group would keep fewer than SLIDE_MIN_PIXELS pixels: no split.
    assert split_chain(chain, np.array([1.5, 0.0])) is None
    assert split_chain(chain, np.array([8.5, 0.0])) is None


def test_a_biarc_is_found_where_its_two_circles_touch():
    from img2logo.fit.tangency import closest_biarcs

    # A smooth line of two tangent circles, radii 50 and 80 px, touching at (0, 0) with the
    # common tangent along x: the head on the circle centred (0, 50), the tail on (0, -80).
    head = np.column_stack([50 * np.sin(t := np.linspace(-1.2, 0.0, 61)), 50 - 50 * np.cos(t)])
    tail = np.column_stack([80 * np.sin(u := np.linspace(0.0, 0.75, 61)[1:]), -80 + 80 * np.cos(u)])
    chain = np.vstack([head, tail])
    found = closest_biarcs(chain, [30.0, 50.0, 80.0], [50.0, 80.0, 130.0])
    worst, ia, ib, i, ca, cb = found[0]
    # The radii of the line, the junction at the touching point, the circles where they are.
    assert (ia, ib) == (1, 1) and i == 60 and worst < 0.5  # the finer grid turns by 1 degree
    assert np.allclose(ca, (0.0, 50.0), atol=1.0) and np.allclose(cb, (0.0, -80.0), atol=1.5)
    # The circles touch: the junction on the line of centres, at both radii.
    assert np.hypot(*(ca - chain[i])) == pytest.approx(50.0) and np.hypot(*(cb - chain[i])) == pytest.approx(80.0)
    assert found == sorted(found, key=lambda f: f[0]) and found[-1][0] > 1.0
    # Too short a chain for a junction with SLIDE_MIN_PIXELS on both sides: none.
    assert closest_biarcs(chain[:6], [50.0], [80.0]) == []


@pytest.fixture(scope="module")
def umbrella():
    return abstract(DATA.parent / "benchmarks" / "data" / "drawing-umbrella.png", progress=False)


def test_joins_made_tangent_one_at_a_time_stay_exact(umbrella):
    result = umbrella
    level = result.final
    found = quality.joins(level, result.graph)
    # Both joins on smooth input tangent (the whole refit at once made one of the two).
    assert found.count == 2 and np.all(np.degrees(found.kinks) < 1e-3)
    assert result.progression.stats["tangent_joins"] == 2
    for j in found.junctions:
        a, b = (level.arcs[i].circle for i in level.arcs_at(j))
        distance = math.dist(a.center, b.center)
        assert min(abs(distance - abs(a.r - b.r)), abs(distance - (a.r + b.r))) <= 1e-6
    # Every arc still ends at its junctions to 1e-6 px, and the radii are on the ladder.
    for arc, t in zip(level.arcs, level.arc_junctions, strict=True):
        for end, j in ((arc.start, t.start), (arc.end, t.end)):
            if j is not None:
                assert math.dist(end, level.junctions[j]) <= 1e-6
        if arc.circle.k is not None:
            assert arc.circle.r == pytest.approx(level.ladder.radius(arc.circle.k), rel=1e-9)
    assert level.similarity <= level.tolerance


# --------------------------------------------------------------------------- the level kept
class _Levels:
    """A stand-in for the optimizer's state: a level is its number of groups; kinks[k] joins stay kinked k back."""

    def __init__(self, kinks):
        from img2logo.fit.fit_state import Stats

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
    import img2logo.fit.tangency as tangency

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
            raise tangency._Outscored
        opt.loose = set(range(kinks[k]))
        return True

    monkeypatch.setattr(tangency, "tangent_joins", fake_pass)
    monkeypatch.setattr(tangency, "KINK_WEIGHT", weight)
    assert tangency.tangent_level(levels, 5.0, history) == back
    assert len(levels.passes) == passes and len(levels.groups) == len(kinks) - back
    assert len(levels.loose) == kinks[back]


def _at(levels, n):
    levels.groups = dict.fromkeys(range(n))
    return levels


def test_biarc_worst_kernel_matches_the_numpy_reference():
    # The compiled kernel measures each side's pixels only: the same bits as the reference.
    from img2logo.fit.tangency import _biarc_worst_reference, biarc_normals, biarc_worst

    rng = np.random.default_rng(5)
    for _ in range(40):
        n = int(rng.integers(20, 120))
        t = np.linspace(0.0, rng.uniform(0.5, 3.0), n)
        radius = rng.uniform(10.0, 200.0)
        chain = np.round(np.stack([radius * np.cos(t), radius * np.sin(t)], 1) + rng.normal(0, 0.7, (n, 2))) + 100.5
        splits, turns = np.arange(4, n - 5, 3), np.linspace(-0.3, 0.3, 7)
        for head in (True, False):
            for stride in (1, 3):
                r, side = rng.uniform(5.0, 300.0), float(rng.choice([-1.0, 1.0]))
                centre = chain[splits][:, None, :] + side * r * biarc_normals(chain, splits, turns)
                index = np.arange(0, n, stride)
                expected = _biarc_worst_reference(chain, centre, index, splits, r, head)
                assert np.array_equal(biarc_worst(chain, splits, turns, r, side, head, stride), expected)


def test_biarc_fine_search_is_the_grids_argmin():
    # The compiled search stops measuring a biarc once it cannot win: the same value and the
    # same place as numpy's argmin over the two grids' maximum, the first one on a tie
    # (repeated splits and turns make ties).
    from img2logo.fit.tangency import biarc_fine, biarc_worst

    rng = np.random.default_rng(11)
    for _ in range(40):
        n = int(rng.integers(20, 120))
        t = np.linspace(0.0, rng.uniform(0.5, 3.0), n)
        radius = rng.uniform(10.0, 200.0)
        chain = np.round(np.stack([radius * np.cos(t), radius * np.sin(t)], 1) + rng.normal(0, 0.7, (n, 2))) + 100.5
        splits = np.sort(rng.integers(4, n - 5, 9))
        turns = np.sort(np.concatenate([rng.uniform(-0.3, 0.3, 5), [0.0, 0.0]]))
        head = (rng.uniform(5.0, 300.0), float(rng.choice([-1.0, 1.0])))
        tail = (rng.uniform(5.0, 300.0), float(rng.choice([-1.0, 1.0])))
        w = np.maximum(
            biarc_worst(chain, splits, turns, *head, True, 1), biarc_worst(chain, splits, turns, *tail, False, 1)
        )
        s, a = np.unravel_index(int(np.argmin(w)), w.shape)
        assert biarc_fine(chain, splits, turns, head, tail) == (float(w[s, a]), int(s), int(a))


def test_biarc_coarse_search_is_the_grids_choice():
    # The compiled coarse search stops measuring a biarc once it cannot win: for every pair of
    # radii the same sides and place as the smallest of the four grids' minima (numpy's
    # maximum of the two sides' grids), and its argmin, the first on a tie.
    from img2logo.fit.constants import BIARC_STEP
    from img2logo.fit.tangency import biarc_coarse, biarc_normals, biarc_worst

    sides = ((-1.0, -1.0), (-1.0, 1.0), (1.0, -1.0), (1.0, 1.0))
    rng = np.random.default_rng(12)
    for _ in range(20):
        n = int(rng.integers(30, 200))
        t = np.linspace(0.0, rng.uniform(0.5, 3.0), n)
        radius = rng.uniform(10.0, 200.0)
        chain = np.round(np.stack([radius * np.cos(t), radius * np.sin(t)], 1) + rng.normal(0, 0.7, (n, 2))) + 100.5
        splits = np.arange(5, n - 5, 4)
        turns = np.sort(np.concatenate([rng.uniform(-0.4, 0.4, 6), [0.0, 0.0]]))
        radii_a, radii_b = list(rng.uniform(5.0, 300.0, 2)), [radius, *rng.uniform(5.0, 300.0, 2)]
        normal = biarc_normals(chain, splits, turns)
        got = biarc_coarse(chain, splits, turns, radii_a, radii_b)
        for ia, ra in enumerate(radii_a):
            for ib, rb in enumerate(radii_b):
                w = [
                    np.maximum(
                        biarc_worst(chain, splits, turns, ra, sa, True, BIARC_STEP, normal),
                        biarc_worst(chain, splits, turns, rb, sb, False, BIARC_STEP, normal),
                    )
                    for sa, sb in sides
                ]
                j = min(range(4), key=lambda j: float(w[j].min()))
                s, a = np.unravel_index(int(np.argmin(w[j])), w[j].shape)
                assert got[ia, ib] == (j, int(s), int(a))


def test_cutting_off_tries_over_the_bound_changes_no_result(monkeypatch):
    """A try is cut off once its E^s must exceed the bound (``FitState.solve``'s ``bound``): the same logo."""
    from img2logo.fit.fit_state import FitState

    image = DATA / "clipart-fish.png"
    cut = abstract(image, progress=False)
    within = FitState._fits_within
    cuts = []

    def never_cut(self, window, groups, seeds, fixed, node_groups, bound, regroup):
        out = within(self, window, groups, seeds, fixed, node_groups, bound, regroup)
        full = within(self, window, groups, seeds, fixed, node_groups, math.inf, regroup)
        cuts.append(out is None and full is not None)
        return full

    monkeypatch.setattr(FitState, "_fits_within", never_cut)
    whole = abstract(image, progress=False)
    assert any(cuts)  # some tries were cut off, and every one would have failed on E^s
    assert whole.progression.stats == cut.progression.stats
    assert whole.final.arcs == cut.final.arcs and whole.final.similarity == cut.final.similarity


def test_the_tangent_joins_make_no_near_miss_gap():
    # Regression: on the seal of make quality's photo2 at T = 7 the tangent refit of a join moved two
    # arcs' free ends 2-5 px from the arc beside them (the loop's last level had none).
    seal = DATA.parent / "benchmarks" / "data" / "photo2" / "photo2-seal.png"
    result = abstract(seal, tolerance=7.0, progress=False)
    assert result.progression.stats["tangent_joins"] >= 1
    assert len(quality.near_miss_gaps(result.final)) == 0 and len(quality.crossings(result.final)) == 0


@pytest.fixture(scope="module")
def warning_sign():
    """Openclipart's warning sign, with and without :func:`~img2logo.fit.tangency.split_kinks`."""
    import img2logo.fit.tangency as tangency

    path = DATA.parent / "benchmarks" / "data" / "openclipart" / "clipart-charge.png"
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(tangency, "split_kinks", lambda opt, tolerance: 0)
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
    import img2logo.fit.tangency as tangency

    path = DATA.parent / "benchmarks" / "data" / "clipart-polar-bear.png"
    stopped = []
    original = tangency.tangent_joins

    def counted(opt, tolerance, most_loose=None):
        try:
            return original(opt, tolerance, most_loose)
        except tangency._Outscored:
            stopped.append(most_loose)
            raise

    def to_the_end(opt, tolerance, most_loose=None):
        return original(opt, tolerance)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(tangency, "tangent_joins", counted)
        fast = abstract(path, progress=False)
        mp.setattr(tangency, "tangent_joins", to_the_end)
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
