"""A^0 when the joint constrained fit fails: relaxed connectivity (paper Sec. 9, future work).

The initial fit of the progressive optimization (:mod:`img2logo.fit.progressive`,
on a :class:`~img2logo.fit.fit_state.FitState`)
solves Eqn. 13 for every circle at once. When that does not converge, each
connected part of the drawing is fitted alone, and in a part that still fails
the junctions its circles miss most are released one at a time
(:func:`recover`): "a logo for every valid image". :func:`check_reach` names
the user's radii that are too small before any fit.

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

import numpy as np

from ..constants import MAX_RADIUS_FACTOR
from ..errors import FitError, InvalidParameterError
from . import window_solve

if TYPE_CHECKING:
    from ..geometry.golden_ladder import Ladder
    from .fit_state import FitState
    from .fit_values import GroupFit, Seed, Solution


class ConnectivityWarning(UserWarning):
    """Some junctions of the initial fit were released: their arcs end apart there."""


def check_reach(state: FitState, seeds: Mapping[int, Seed]) -> None:
    """Raise when the user's radii are too small for the segments' junctions (see :meth:`FitState.reach`)."""
    if state.ladder.exponents is None:
        return
    short = [g for g, (_, r, k) in seeds.items() if k is not None and r < state.reach(state.groups[g])]
    if short:
        ks = sorted(state.ladder.exponents)
        widest = max(2.0 * state.reach(state.groups[g]) for g in short)
        raise InvalidParameterError(
            f"the chosen radii (k = {', '.join(map(str, ks))}: {state.ladder.radius(ks[0]):.3g} to "
            f"{state.ladder.radius(ks[-1]):.3g} px) are too small: {len(short)} segments need a circle through "
            f"junctions up to {widest:.0f} px apart; allow larger radii"
        )


def check_span(ladder: Ladder, width: int, height: int) -> None:
    """Raise when the smallest radius the user's ladder allows is too large for the image.

    A free circle fit caps its radius at ``MAX_RADIUS_FACTOR`` (20) times the
    extent of its points; a circle larger than that many times the image's longer
    side is a straight line to every segment in it, and the fit of its centre
    (Eqn. 13) is ill-posed along the chord: ``--unit 1e5`` on a 512 px drawing.
    """
    from ..geometry.golden_ladder import FibonacciLadder

    fibonacci = isinstance(ladder, FibonacciLadder)
    if ladder.exponents is None and not fibonacci:
        return  # the full phi ladder has rungs of every size
    smallest = ladder.radius(min(ladder.exponents) if ladder.exponents else 2)
    bound = MAX_RADIUS_FACTOR * max(width, height)
    if smallest > bound:
        what = "a smaller unit (--unit)" if fibonacci and not ladder.exponents else "smaller exponents (--radii)"
        raise InvalidParameterError(
            f"the chosen radii are too large for the image: the smallest, {smallest:.4g} px, is over "
            f"{MAX_RADIUS_FACTOR:g} x the image's longer side ({max(width, height)} px), where a circle is a straight "
            f"line; choose {what}"
        )


def recover(state: FitState, seeds: Mapping[int, Seed]) -> Solution:
    """A^0 when the joint fit fails: each connected part alone, releasing junctions as needed.

    The parts of the drawing that share no junction are independent
    problems, so a part that converges keeps its exact connectivity. A part
    that does not is tried again from its circles' best centres for their
    snapped radii (:func:`centred_seeds`). In a part that still does not, the junction its golden circles miss most (the
    largest distance from the junction to a circle through it, before the
    fit) is released: its arcs end where it projects on their circles, like
    a free end. This repeats until the part converges (a part with every
    junction released always does); the count is reported.
    """
    fits: dict[int, GroupFit] = {}
    disp: dict[int, np.ndarray] = {}
    n_total = len(state.groups)
    centred: dict[int, Seed] | None = None
    for part in parts(state):
        while True:
            groups = {g: state.groups[g] for g in part}
            at = state.node_groups(groups)
            out = window_solve.solve_whole(
                state, groups, seeds, at, n_groups_total=n_total, n_junctions_total=max(len(state.node_groups()), 1)
            )
            if out is None:
                # The free centres with the snapped radii can start the fit far from the pixels;
                # the same problem from the centres that fit each radius best, before any release.
                centred = centred_seeds(state, seeds) if centred is None else centred
                out = window_solve.solve_whole(
                    state,
                    groups,
                    centred,
                    at,
                    n_groups_total=n_total,
                    n_junctions_total=max(len(state.node_groups()), 1),
                )
            if out is not None:
                fits.update(out[0])
                disp.update(out[1])
                break
            miss = {
                n: max(
                    abs(float(np.hypot(*(state.graph.junctions[n] - seeds[g].center))) - seeds[g].radius) for g in gs
                )
                for n, gs in at.items()  # nothing has changed since the attempt
            }
            if not miss:  # no constraint left, yet no fit: a numerical failure, said as such
                raise FitError(f"the circles of {len(part)} segments could not be fitted, even unconstrained")
            state.release(max(miss, key=lambda n: (miss[n], -n)))
    state.stats.released_junctions = len(state.released)
    if state.released:
        import warnings

        warnings.warn(
            f"the connectivity-constrained fit could not meet {len(state.released)} of "
            f"{len(state.released) + len(state.node_groups())} junctions; their arcs end apart there",
            ConnectivityWarning,
            stacklevel=2,
        )
    return fits, disp


def centred_seeds(state: FitState, seeds: Mapping[int, Seed]) -> dict[int, Seed]:
    """The seeds with each golden circle's centre where it fits its group's pixels best (:func:`fit_center`).

    A seed's centre is its free circle's (:meth:`FitState.golden`): once the
    radius is snapped up or down the ladder (by up to a factor of phi, or from a
    capped free radius to a rung far above it), that circle runs off its pixels
    by the difference of the radii, 240 px for a straight 70 px segment whose
    free radius was capped at 1400 px and snapped to 1646. Eqn. 13 started there
    can stall where it converges from the centre placed for the snapped radius
    (the second stage of Sec. 5.3 for each circle alone). Straight lines and
    circles held on a mirror axis keep their centres.
    """
    from ..geometry.circle_fitting import fit_center

    out = dict(seeds)
    for g, seed in seeds.items():
        group = state.groups[g]
        if seed.k is not None and not state.on_axis(group):
            out[g] = seed._replace(center=fit_center(group.points, seed.radius, seed.center))
    return out


def parts(state: FitState) -> list[list[int]]:
    """The groups in connected parts: groups sharing a constrained junction are in one part."""
    parent = {g: g for g in state.groups}

    def root(g: int) -> int:
        while parent[g] != g:
            parent[g] = parent[parent[g]]
            g = parent[g]
        return g

    for gs in state.node_groups().values():
        for g in gs[1:]:
            parent[root(g)] = root(gs[0])
    parts: dict[int, list[int]] = {}
    for g in sorted(state.groups):
        parts.setdefault(root(g), []).append(g)
    return list(parts.values())
