"""Tangent joins (beyond the paper): the result's circles touch where the input runs on smoothly.

Where exactly two arcs of the result end at a node of the segment graph where
the input's feature line does not turn (a node of valence 2 whose two segments'
end tangents differ by less than ``SMOOTH_JOIN_ANGLE``,
:meth:`~img2logo.segment_graph.SegmentGraph.smooth_nodes`), a designer draws
the two arcs so that one flows into the other: their circles touch at the
junction (the junction on the line of centres, centre distance |r1 - r2| or
r1 + r2). :func:`tangent_joins` refits the last level of the progressive
optimization (:mod:`img2logo.progressive`) with that tangency as one more
equality per join in the constrained fit (Eqn. 13,
:func:`~img2logo.constrained_fit.fit_constrained`, ``tangents``), the radii
staying on their rungs.

Why the last level and not every fit: with the radii fixed on the ladder, a
chain of tangent circles is rigid, and the first levels join every short piece
of the over-segmentation. Measured (``make quality``, issue 17): enforcing it
in A^0 and every merge's window raises E^s(A^0) of the clip-art fish from 2.36
to 9.77 px (no merge fits under T = 5 any more), and on the evaluation set's
clip arts gives 47.1 arcs instead of 40.0 (the polar bear 49 instead of 30,
r10 0.90 instead of 0.99) and one failed run; enforcing it in the merge windows
only gives 41.6 arcs and runs the clip-art fish 2x slower. It would make 93 %
and 33 % of the joins tangent; this refit alone makes 20 %.

A tangency that makes the fit infeasible, or lifts E^s above the tolerance T,
is released, the most kinked join first (like the junction release of
:mod:`img2logo.recovery`): a kink is left there, and a valid image always gets
a logo. Corners (where the input turns) are never constrained.

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from .fit_state import FitState


def tangent_joins(opt: FitState, tolerance: float) -> bool:
    """Make the circles of the current state touch at its smooth joins; whether the state changed.

    The whole problem is refitted (every circle and junction free, straight
    lines fixed) with the tangencies of ``opt.tangencies``; while the fit
    fails or its E^s (Eqn. 3) exceeds ``max(tolerance, E^s now)``, the join
    whose circles are farthest from touching now is released
    (``opt.loose``) and the fit tried again. Counts go to
    ``opt.stats.tangent_joins`` and ``.released_tangencies``.
    """
    seeds = {g: f.seed for g, f in opt.fits.items()}
    bound = max(float(tolerance), opt.similarity())
    groups = dict(opt.groups)
    node_groups = opt.node_groups()
    before = (dict(opt.fits), opt.disp.copy())
    changed = False
    while True:
        touching = opt.tangencies(groups, seeds)
        if not touching:
            break
        out = opt.solve_whole(
            groups, seeds, node_groups, n_groups_total=len(groups), n_junctions_total=len(node_groups), tangent=True
        )
        if out is not None:
            fits, disp = out
            opt.fits.update(fits)
            for n, d in disp.items():
                opt.disp[n] = d
            if opt.similarity() <= bound:
                changed = True
                break
            opt.fits, opt.disp = dict(before[0]), before[1].copy()
        opt.loose.add(max(touching, key=lambda n: (_apart(opt, seeds, n, touching[n]), -n)))
    opt.stats.tangent_joins = len(opt.tangencies(groups, seeds)) if changed else 0
    opt.stats.released_tangencies = len(opt.loose)
    return changed


def _apart(opt: FitState, seeds: dict, node: int, pair: tuple[int, int]) -> float:
    """|sin| of the angle between two circles' radii to a junction: 0 where they touch there."""
    p = opt.graph.junctions[node] + opt.disp[node]
    a, b = seeds[pair[0]][0] - p, seeds[pair[1]][0] - p
    return abs(float(a[0] * b[1] - a[1] * b[0])) / max(float(np.hypot(*a) * np.hypot(*b)), 1e-300)
