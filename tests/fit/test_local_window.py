"""The refit of a local window, grown ring by ring (Sec. 5.4)."""

from __future__ import annotations

import math

import numpy as np
import pytest

import img2logo.fit.local_window as local_window


# --------------------------------------------------------------------------- the window of a local refit
def _chain_of_three():
    """Circles 0, 1, 2 in a row, r = 10; junction 0 joins circles 0 and 1, junction 1 circles 1 and 2.

    Circle 0's points lie on a circle moved 1 px up: only the fit can say where it goes.
    """
    radii = {0: 10.0, 1: 10.0, 2: 10.0}
    centers = {0: np.array([0.0, 0.0]), 1: np.array([20.0, 0.0]), 2: np.array([40.0, 0.0])}
    t = np.linspace(-1.0, 1.0, 21)
    points = {
        0: np.stack([10 * np.cos(t + math.pi), 10 * np.sin(t + math.pi) - 1.0], axis=1),
        1: np.stack([20 + 10 * np.cos(t - math.pi / 2), 10 * np.sin(t - math.pi / 2)], axis=1),
        2: np.stack([40 + 10 * np.cos(t), 10 * np.sin(t)], axis=1),
    }
    circle_junctions = {0: (0,), 1: (0, 1), 2: (1,)}
    junction_circles = {0: [0, 1], 1: [1, 2]}
    junctions = np.array([[10.0, 0.0], [30.0, 0.0]])
    return points, radii, centers, circle_junctions, junction_circles, junctions


def test_window_holds_the_junctions_beyond_the_first_ring():
    args = _chain_of_three()
    w = local_window.fit_window(*args, changed=[0], free_junctions=[0])
    assert w.ok and w.circles == (0, 1) and w.junctions == (0, 1) and w.free_junctions == {0}
    d = w.displacements()
    np.testing.assert_array_equal(d[1], [0.0, 0.0])  # held: the boundary of the window (Sec. 5.4)
    for c in w.circles:  # every circle still passes through its junctions
        for n in args[3][c]:
            assert math.dist(w.center(c), args[5][n] + d[n]) == pytest.approx(10.0, abs=1e-6)
    assert w.center(0)[1] < -0.1  # circle 0 followed its points up


def test_window_grows_by_a_ring_when_it_does_not_solve_and_keeps_fixed_circles():
    args = _chain_of_three()
    failed = local_window.fit_window(*args, changed=[0], free_junctions=[0], max_violation=-1.0)  # never good enough
    assert not failed.ok and failed.circles == (0, 1, 2) and failed.free_junctions == {0, 1}
    one = local_window.fit_window(*args, changed=[0], free_junctions=[0], max_violation=-1.0, rings=1)
    assert one.circles == (0, 1)
    fixed = local_window.fit_window(*args, changed=[0], free_junctions=[0], fixed={1})
    np.testing.assert_array_equal(fixed.center(1), [20.0, 0.0])
    ordered = local_window.fit_window(*args, changed=[0], free_junctions=[0], order=lambda c: -c)
    assert ordered.circles == (1, 0)
    empty = local_window.fit_window(*args, changed=[], free_junctions=[])
    assert empty.ok and empty.fit is None and empty.displacements() == {}


def test_window_from_a_later_ring_is_the_one_the_rings_before_grow_to():
    """``first_ring``: the windows before it are only grown (they failed already), the later ones solved."""
    args = _chain_of_three()
    grown = local_window.fit_window(*args, changed=[0], free_junctions=[0], rings=2, first_ring=2)
    assert grown.ok and grown.circles == (0, 1, 2) and grown.free_junctions == {0, 1}
    whole = local_window.fit_window(*args, changed=[0], free_junctions=[0, 1], rings=2)  # ring 2's window solved alone
    for c in (0, 1, 2):
        np.testing.assert_array_equal(grown.center(c), whole.center(c))
    # Past the whole connected part there is nothing left to grow: the window failed, unsolved again.
    past = local_window.fit_window(*args, changed=[0], free_junctions=[0], rings=4, first_ring=4)
    assert not past.ok and past.fit is None and past.circles == (0, 1, 2)


def test_window_that_no_junction_touches_is_still_fitted():
    # Every junction released (or a closed curve alone): the circles have no constraint, yet
    # their centres still go where their points are (this window had no fit).
    points, radii, centers, _, _, junctions = _chain_of_three()
    alone = {c: () for c in points}
    w = local_window.fit_window(points, radii, centers, alone, {}, junctions, changed=[0, 1, 2], free_junctions=[])
    assert w.ok and w.circles == (0, 1, 2) and w.junctions == () and w.fit is not None
    np.testing.assert_allclose(w.center(0), [0.0, -1.0], atol=1e-6)  # its points' circle, 1 px up
    np.testing.assert_allclose(w.center(2), [40.0, 0.0], atol=1e-6)
    assert w.displacements() == {}


def test_window_stops_growing_when_a_ring_leaves_the_violation_as_it_was():
    """``stop_when_stuck``: two fixed circles 10 px apart share junction 0; no ring can close that gap."""
    radii = {c: 10.0 for c in range(5)}
    centers = {0: np.array([-10.0, 0.0]), **{c: np.array([20.0 * c, 0.0]) for c in range(1, 5)}}
    t = np.linspace(-1.0, 1.0, 21)
    points = {c: np.stack([centers[c][0] + 10 * np.cos(t), 10 * np.sin(t) + 10.0], axis=1) for c in range(5)}
    circle_junctions = {0: (0,), 1: (0, 1), 2: (1, 2), 3: (2, 3), 4: (3,)}
    junction_circles = {0: [0, 1], 1: [1, 2], 2: [2, 3], 3: [3, 4]}
    junctions = np.array([[5.0, 0.0], [30.0, 0.0], [50.0, 0.0], [70.0, 0.0]])
    args = (points, radii, centers, circle_junctions, junction_circles, junctions)
    kwargs = {"changed": [0], "free_junctions": [0], "fixed": {0, 1}, "rings": 4}
    every = local_window.fit_window(*args, **kwargs)
    assert not every.ok and every.circles == (0, 1, 2, 3, 4)  # four rings, all failed
    stuck = local_window.fit_window(*args, **kwargs, stop_when_stuck=True)
    assert not stuck.ok and stuck.circles == (0, 1, 2)  # the second ring ended as the first: no third
    assert stuck.fit.violation == pytest.approx(every.fit.violation, rel=local_window.STUCK_VIOLATION_CHANGE)
    assert (
        local_window._stuck(1.0, 1.005, 1e-6)
        and not local_window._stuck(1.0, 0.9, 1e-6)
        and local_window._stuck(1e-7, 5e-7, 1e-6)
    )
