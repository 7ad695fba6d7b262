"""The object's silhouette in the optimizer's state (beyond the paper): arcs held within T of its pixels.

A group that runs through a segment of the object's silhouette (``FitState.outline``,
:func:`on_outline`) may lie no farther from its pixels than the tolerance T (:func:`arc_cap`, with
``Options.arc_bound`` for every arc); a refit whose arc strays past its cap and past where it was
(:func:`strays`, :func:`outline_strays` for the silhouette's arcs alone) is refused by the merge loop,
the tangent pass and the kink splits.

Coordinates: px, x right, y down (``contract/README.md``).
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import TYPE_CHECKING

from .fit_values import GroupFit
from .simplification import Group

if TYPE_CHECKING:
    from .fit_state import FitState


def on_outline(state: FitState, group: Group) -> bool:
    """Whether ``group`` runs through a segment of the object's silhouette (``state.outline``)."""
    return bool(state.outline) and not state.outline.isdisjoint(group.segments)


def arc_cap(state: FitState, group: Group) -> float | None:
    """The farthest an arc of ``group`` may lie from its pixels (discrete Fréchet), px; None: no bound.

    ``Options.arc_bound``, and on the object's silhouette (a group through a
    segment of ``state.outline``) the tolerance T, whichever is less.
    """
    cap = state.options.arc_bound
    if on_outline(state, group):
        tolerance = float(state.options.tolerance)
        cap = tolerance if cap is None else min(cap, tolerance)
    return cap


def outline_strays(
    state: FitState, fits: Mapping[int, GroupFit], groups: Mapping[int, Group], before: Mapping[int, GroupFit]
) -> bool:
    """:func:`strays` of those of ``fits`` whose groups run on the object's silhouette (:func:`on_outline`).

    A refit moves the junctions, so the arcs beside the ones it was for
    change too; one of the silhouette's moved farther than T is the
    silhouette cut as the refitted arc would cut it.
    """
    if not state.outline:
        return False
    return strays(state, {g: f for g, f in fits.items() if on_outline(state, groups[g])}, groups, before)


def strays(
    state: FitState, fits: Mapping[int, GroupFit], groups: Mapping[int, Group], before: Mapping[int, GroupFit]
) -> bool:
    """Whether a refit's arc lies farther from its pixels than its :func:`arc_cap` and than before.

    ``fits`` are the refit's arcs by group id, ``groups`` their groups, ``before`` the fits
    they replace (a group missing there is held to its cap alone).
    """
    for g, fit in fits.items():
        cap = arc_cap(state, groups[g])
        if cap is not None and fit.arc.frechet > cap and (g not in before or fit.arc.frechet > before[g].arc.frechet):
            return True
    return False
