"""The whole pipeline in one call: image -> feature lines -> segment graph -> levels.

:func:`abstract` is what the command line, the notebooks and most users call.
It returns a :class:`Result` holding every stage's output, so that a slider can
show any level without recomputing and a figure can show any stage.
"""

from __future__ import annotations

import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .constants import MIN_SEGMENT_LENGTH, PHOTO_MAX_ARC_FACTOR, RDP_TOLERANCE, TOLERANCE
from .errors import InvalidParameterError
from .geometry import Abstraction
from .options import check_abstract_options
from .preprocessing import FeatureLines, LoadedImage, extract_feature_lines, load_image
from .progressive import ProgressCallback, Progression, optimize
from .segment_graph import SegmentGraph, build_segment_graph
from .symmetry import SymmetryChoice, check_symmetry_option, choose_axis, optimize_symmetric


@dataclass(frozen=True, eq=False)
class Result:
    """Everything one run computed.

    Attributes
    ----------
    image : LoadedImage
    lines : FeatureLines
    graph : SegmentGraph
        L = {S, J}, the input of the optimization.
    progression : Progression
        Every level A^0 ... A^final, the bias, stats.
    timings : dict
        Seconds per stage: ``feature_lines``, ``segment_graph``,
        ``simplification``, ``initial_fit``, ``loop``.
    params : dict
        The parameters of the run (as recorded in every level).
    symmetry : SymmetryChoice or None
        What the ``symmetry`` option decided (None for ``"none"``); when it
        kept an axis, ``graph`` is the symmetric segment graph and every level
        is mirror-symmetric.
    """

    image: LoadedImage
    lines: FeatureLines
    graph: SegmentGraph
    progression: Progression
    timings: dict[str, float] = field(default_factory=dict)
    params: dict[str, Any] = field(default_factory=dict)
    symmetry: SymmetryChoice | None = None

    @property
    def levels(self) -> tuple[Abstraction, ...]:
        """A^0 ... A^final."""
        return self.progression.levels

    @property
    def final(self) -> Abstraction:
        """The result: the simplest level within the tolerance."""
        return self.progression.final

    @property
    def bias(self) -> float:
        """The ladder bias sigma used."""
        return self.progression.bias

    def level(self, t: int) -> Abstraction:
        """A^t; negative t counts from the end like a list index.

        Raises
        ------
        InvalidParameterError
            If ``t`` is not an integer in 0 .. len(levels) - 1 (or -len(levels) .. -1).
        """
        n = len(self.progression.levels)
        if isinstance(t, bool) or not isinstance(t, int | np.integer) or not -n <= t < n:
            raise InvalidParameterError(f"level must be an integer in 0..{n - 1} (or -{n}..-1 from the end), got {t!r}")
        return self.progression.levels[t]


def abstract(
    image: object,
    tolerance: float = TOLERANCE,
    kind: str = "auto",
    *,
    rdp_tolerance: float = RDP_TOLERANCE,
    min_length: float = MIN_SEGMENT_LENGTH,
    foreground: object = "auto",
    subject: object = None,
    bias: float | None = None,
    exponents: Sequence[int] | None = None,
    ladder: str = "phi",
    unit: float | None = None,
    lock_mask: np.ndarray | None = None,
    progress: ProgressCallback | bool | None = None,
    symmetry: object = "none",
    **switches: Any,
) -> Result:
    """Turn an image into a sequence of golden ratio logo abstractions.

    Parameters
    ----------
    image : path, ndarray or LoadedImage
        The input (see :func:`img2logo.load_image`).
    tolerance : float
        T, the largest similarity error E^s (Eqn. 1) accepted, px.
    kind : {"auto", "photo", "clipart", "drawing"}
        The kind of input (see :func:`img2logo.extract_feature_lines`).
    rdp_tolerance, min_length : float
        Segment-graph parameters (see :func:`img2logo.build_segment_graph`), px.
    foreground : {"auto", "none", "grabcut"}, path or ndarray of bool
        Photos: the subject drawn (see :func:`img2logo.extract_feature_lines`);
        found automatically by default.
    subject : (x, y, w, h) or "X,Y,W,H", optional
        Photos: a rectangle around the object that seeds its segmentation, px.
    bias, exponents, lock_mask
        The ladder bias, a subset of ladder exponents, a lock mask (Sec. 7).
    ladder : {"phi", "fibonacci"}
        Radii ``phi ** (k + bias)`` (default, the paper) or ``unit * F(k)``,
        the Fibonacci grid designers draw (Fig. 2b; see
        :func:`img2logo.progressive.optimize`).
    unit : float, optional
        The Fibonacci ladder's unit, px; default: chosen from the longest segment.
    symmetry : {"none", "auto", "vertical", "horizontal"} or float
        A symmetric logo (:mod:`img2logo.symmetry`): ``auto`` finds the best
        mirror axis of the feature lines and keeps it if its score reaches
        ``SYMMETRY_THRESHOLD``; ``vertical``, ``horizontal`` or an angle in
        degrees (from +x towards +y) force its direction. ``none`` (default):
        free, as in the paper. What was decided is ``Result.symmetry``.
    progress : callable, bool or None
        A callback ``progress(t, n_arcs, similarity)``; ``True`` shows a
        progress bar on the terminal; ``None`` (default) shows one only when
        standard error is a terminal.
    **switches
        The ablation switches of :func:`img2logo.progressive.optimize`:
        ``connectivity``, ``inner_junctions``, ``merging``,
        ``avoid_intersections``, ``localized``, ``simplify``, ``arc_selection``,
        and ``max_arc_distance`` (photos: ``PHOTO_MAX_ARC_FACTOR * tolerance``
        unless given; None for no bound).

    Returns
    -------
    Result

    Raises
    ------
    InvalidParameterError
        Before any work, if a keyword is unknown or a value out of range
        (:func:`img2logo.options.check_abstract_options`).
    """
    given = {"tolerance": tolerance, "kind": kind, "rdp_tolerance": rdp_tolerance, "min_length": min_length}
    given.update(foreground=foreground, subject=subject, bias=bias, exponents=exponents, ladder=ladder, unit=unit)
    given.update(symmetry=symmetry, lock_mask=lock_mask)
    check_abstract_options({**given, **switches})
    timings: dict[str, float] = {}
    start = time.perf_counter()
    img = load_image(image)
    lines = extract_feature_lines(img, kind=kind, foreground=foreground, subject=subject)
    timings["feature_lines"] = time.perf_counter() - start
    start = time.perf_counter()
    graph = build_segment_graph(lines, rdp_tolerance=rdp_tolerance, min_length=min_length)
    timings["segment_graph"] = time.perf_counter() - start
    params = {
        "source": img.source,
        "kind": lines.kind,
        "rdp_tolerance": float(rdp_tolerance),
        "min_length": float(min_length),
        "scale": img.scale,
    }
    if lines.kind == "photo" and "max_arc_distance" not in switches:
        # A photo's logo is a few long arcs: no arc may stray far from its line.
        switches = {**switches, "max_arc_distance": PHOTO_MAX_ARC_FACTOR * float(tolerance)}
    callback, bar = _progress(progress, tolerance)
    choice = None
    mode = check_symmetry_option(symmetry)
    if mode is not None:
        start = time.perf_counter()
        choice = choose_axis(lines.lines, mode)
        timings["symmetry"] = time.perf_counter() - start
    try:
        if choice is not None and choice.axis is not None:
            progression, graph, _ = optimize_symmetric(
                graph,
                choice.axis,
                choice=choice,
                tolerance=tolerance,
                bias=bias,
                exponents=exponents,
                ladder=ladder,
                unit=unit,
                progress=callback,
                params=params,
                **switches,
            )
        else:
            progression = optimize(
                graph,
                tolerance=tolerance,
                bias=bias,
                exponents=exponents,
                ladder=ladder,
                unit=unit,
                lock_mask=lock_mask,
                progress=callback,
                params=params,
                **switches,
            )
    finally:
        if bar is not None:
            bar.close()
    timings.update(progression.timings)
    return Result(img, lines, graph, progression, timings, dict(progression.levels[0].params), choice)


def _progress(progress: ProgressCallback | bool | None, tolerance: float) -> tuple[ProgressCallback | None, Any]:
    """A callback, and the tqdm bar behind it when one is shown.

    The bar fills with E^s towards the tolerance T: the loop stops when E^s
    would exceed T, so the number of merges is not known in advance.
    """
    if callable(progress):
        return progress, None
    if progress is False or (progress is None and not sys.stderr.isatty()):
        return None, None
    from tqdm.auto import tqdm

    bar = tqdm(
        total=float(tolerance),
        desc="merging",
        leave=False,
        bar_format="{desc}: {bar} E^s {n:.2f} of T = {total:.2f} px{postfix}",
    )

    def update(t: int, n_arcs: int, similarity: float) -> None:
        bar.n = min(float(similarity), float(tolerance))
        bar.set_postfix_str(f"level {t}, {n_arcs} arcs", refresh=True)

    return update, bar
