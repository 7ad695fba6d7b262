"""The whole pipeline in one call: image -> feature lines -> segment graph -> levels.

:func:`abstract` is what the command line, the notebooks and most users call.
It returns a :class:`Result` holding every stage's output, so that a slider can
show any level without recomputing and a figure can show any stage.
"""

from __future__ import annotations

import dataclasses
import functools
import sys
import time
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ._compiled import kernels
from .constants import SYNTHETIC_WORK_SIDE
from .errors import InvalidParameterError
from .export.constants import MIN_STROKE_WIDTH
from .features.kinds import photo_reason
from .features.preprocessing import FeatureLines, extract_feature_lines
from .fit.progressive import Levels, ProgressCallback, Progression, optimize
from .geometry.abstraction import Abstraction
from .images.loading import LoadedImage, downscale, load_image, mask_to_working_size, warn_downscaled
from .options import AUTO, Options, check_lock_mask, check_symmetry_option
from .segment_graph import SegmentGraph, build_segment_graph

if TYPE_CHECKING:  # the symmetry module loads only for a run that asks for an axis
    from .fit.symmetry import SymmetryChoice

#: A photo is worked at most this size on its longer side, px (the result is scaled back to the input's pixels, as
#: for MAX_IMAGE_SIDE).
PHOTO_WORK_SIDE: int = 512

#: Photos: a merge whose new arc lies farther than this many T (discrete Fréchet distance) from its pixels is
#: rejected: T bounds every arc, not only their mean E^s.
PHOTO_MAX_ARC_FACTOR: float = 1.0

#: ``abstract``'s ``tolerance`` and ``kind`` when not given: those of ``options`` (default 5 px, "auto").
_DEFAULT: Any = type("Default", (), {"__repr__": lambda self: "<default>"})()


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
        ``simplification``, ``initial_fit``, ``loop``, ``tangency`` (the refit of the tangent joins).
    params : Mapping
        The parameters of the run (as recorded in every level: immutable).
    symmetry : SymmetryChoice or None
        What the ``symmetry`` option decided (None for ``"none"``); when it
        kept an axis, ``graph`` is the symmetric segment graph and every level
        is mirror-symmetric.

    Examples
    --------
    >>> from img2logo import abstract, data
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> result = abstract(image, progress=False)  # a Result
    >>> result.final is result.levels[-1], result.image.width, result.graph.n_components()
    (True, 160, 1)
    """

    image: LoadedImage
    lines: FeatureLines
    graph: SegmentGraph
    progression: Progression
    timings: dict[str, float] = field(default_factory=dict)
    params: Mapping[str, Any] = field(default_factory=dict)
    symmetry: SymmetryChoice | None = None

    @functools.cached_property
    def levels(self) -> tuple[Abstraction, ...]:
        """A^0 ... A^final, all of them made (``progression.levels`` makes each when first asked for)."""
        return tuple(self.progression.levels)

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
    tolerance: float = _DEFAULT,  # type: ignore[assignment]
    kind: str = _DEFAULT,  # type: ignore[assignment]
    *,
    options: Options | None = None,
    lock_mask: np.ndarray | None = None,
    progress: ProgressCallback | bool | None = None,
    **settings: Any,
) -> Result:
    """Turn an image into a sequence of golden ratio logo abstractions.

    Parameters
    ----------
    image : path, ndarray or LoadedImage
        The input (see :func:`img2logo.load_image`). Over 512 px on its longer
        side it is worked at 512 px (``SYNTHETIC_WORK_SIDE``, ``PHOTO_WORK_SIDE``:
        the size every default was chosen at), with one warning, and every level
        is scaled back to the input's pixels.
    tolerance : float
        T, the largest similarity error E^s (Eqn. 1) accepted, px (default 5).
    kind : {"auto", "photo", "clipart", "drawing"}
        The kind of input (see :func:`img2logo.extract_feature_lines`).
    options : Options, optional
        Every setting and switch at once (:class:`~img2logo.options.Options`);
        ``tolerance``, ``kind`` and ``**settings`` given here replace its own.
    lock_mask : ndarray of bool, shape (H, W), optional
        Segments mostly inside it are never merged (Sec. 7, Fig. 16); not with symmetry.
    progress : callable, bool or None
        A callback ``progress(t, n_arcs, similarity)``, called after every level
        the merge loop makes, then once more with the result's final level when
        the tangent joins chose it (its t may be earlier than the last reported:
        :func:`img2logo.fit.progressive.optimize`); the last call is always
        ``Result.final``. ``True`` shows a progress bar on the terminal;
        ``None`` (default) shows one only when standard error is a terminal.
    **settings
        Any other field of :class:`~img2logo.options.Options`: ``detail`` (clip
        art: the regions kept besides the background; :mod:`img2logo.features.detail`), ``arcs`` (clip art:
        an arc budget), ``rdp_tolerance``,
        ``min_length``, ``foreground``, ``subject``, ``symmetry`` (``"none"``,
        ``"auto"``, ``"vertical"``, ``"horizontal"`` or degrees: a mirror-symmetric
        logo, :mod:`img2logo.fit.symmetry`; what was decided is ``Result.symmetry``),
        the ladder (``ladder``,
        ``bias``, ``unit``, ``exponents``, ``rounding``), the switches
        (``connectivity``, ``inner_junctions``, ``merging``,
        ``avoid_intersections``, ``localized``, ``simplify``, ``lines``),
        ``arc_selection`` and ``max_arc_distance`` (photos:
        ``PHOTO_MAX_ARC_FACTOR * tolerance`` unless given; None for no bound).

    Returns
    -------
    Result

    Raises
    ------
    InvalidParameterError
        Before any work, if a keyword is unknown or a value out of range
        (:class:`~img2logo.options.Options`).

    Examples
    --------
    >>> from img2logo import abstract, data
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> result = abstract(image, progress=False)
    >>> result.lines.kind, len(result.final.arcs), result.final.arcs[0].is_full_circle
    ('drawing', 1, True)
    """
    given = {name: value for name, value in (("tolerance", tolerance), ("kind", kind)) if value is not _DEFAULT}
    if not (progress is None or isinstance(progress, bool) or callable(progress)):
        raise InvalidParameterError(
            f"progress must be a callable progress(t, n_arcs, similarity), True, False or None, got {progress!r}"
        )
    opts = Options.from_keywords({**given, **settings}, base=options)
    check_lock_mask(opts, lock_mask)
    # The kernels load (or, once per machine, compile) before the clock starts: the budget bounds the run.
    kernels.usable()
    started = time.process_time()  # the time budget bounds the whole run
    timings: dict[str, float] = {}
    start = time.perf_counter()
    img, work_kind, reason = _working_copy(load_image(image), opts.kind)
    if img.scale != 1.0:
        # The work is done at the downscaled size: masks, given in the input's pixels, are scaled
        # in here (the subject rectangle by find_subject, which says it as given), and every level
        # is scaled back to the input's pixels below.
        lock_mask = mask_to_working_size(lock_mask, img, "lock_mask")
        from .features.photo.subject import FOREGROUND_CHOICES

        foreground = opts.foreground
        if isinstance(foreground, np.ndarray | Path) or (
            isinstance(foreground, str) and foreground not in FOREGROUND_CHOICES
        ):
            foreground = mask_to_working_size(foreground, img, "foreground")
        opts = dataclasses.replace(opts, foreground=foreground)
    lines = extract_feature_lines(
        img, kind=work_kind, foreground=opts.foreground, subject=opts.subject, detail=opts.detail, arcs=opts.arcs
    )
    if reason is not None:  # what the photo test measured (_working_copy), not "given"
        lines = dataclasses.replace(lines, reason=reason)
    timings["feature_lines"] = time.perf_counter() - start
    start = time.perf_counter()
    graph = build_segment_graph(lines, rdp_tolerance=opts.rdp_tolerance, min_length=opts.min_length)
    timings["segment_graph"] = time.perf_counter() - start
    if graph.n_segments == 0 and np.any(lines.lines):  # lines there were: the option removed them all
        raise InvalidParameterError(
            f"min_length (--min-length) = {opts.min_length:g} px removes every feature line: none is that long "
            f"(the image is {img.width}x{img.height} px at work); nothing to abstract"
        )
    params = {
        "source": img.source,
        "kind": lines.kind,
        "rdp_tolerance": float(opts.rdp_tolerance),
        "min_length": float(opts.min_length),
        "scale": img.scale,
    }
    if lines.detail is not None:  # a clip art's regions kept (coarsened where there were too many)
        params["detail"] = int(lines.detail)
    # The logo's stroke weight: the one asked for, else a drawing's own (clip arts and
    # photos are drawn with the writers' default, which is not recorded).
    stroke = opts.stroke_width if opts.stroke_width is not None else lines.stroke_width
    if stroke:
        params["stroke_width"] = max(MIN_STROKE_WIDTH, float(stroke))
    if opts.max_arc_distance == AUTO:
        # A photo's logo is a few long arcs: no arc may stray far from its line.
        bound = PHOTO_MAX_ARC_FACTOR * opts.tolerance if lines.kind == "photo" else None
        opts = dataclasses.replace(opts, max_arc_distance=bound)
    callback, bar = _progress(progress, opts.tolerance)
    choice = None
    mode = check_symmetry_option(opts.symmetry)
    if mode is not None:
        from .fit.symmetry import choose_axis, optimize_symmetric

        start = time.perf_counter()
        choice = choose_axis(lines.lines, mode)
        timings["symmetry"] = time.perf_counter() - start
    try:
        if choice is not None and choice.axis is not None:
            progression, graph, _ = optimize_symmetric(
                graph, choice.axis, choice=choice, options=opts, progress=callback, params=params, started=started
            )
        else:
            # A clip art's background is the paper round the object: its silhouette is held (optimize).
            paper = lines.regions == 0 if lines.kind == "clipart" and lines.regions is not None else None
            progression = optimize(
                graph, opts, lock_mask=lock_mask, silhouette=paper, progress=callback, params=params, started=started
            )
    finally:
        if bar is not None:
            bar.close()
    if img.scale != 1.0:
        progression = _in_input_pixels(progression, img)
    timings.update(progression.timings)
    return Result(img, lines, graph, progression, timings, progression.final.params, choice)


def _working_copy(img: LoadedImage, kind: str) -> tuple[LoadedImage, str, str | None]:
    """The image at the size its kind is worked at, the kind to extract it as, and why it is a photo (or None).

    Every kind's default lengths (T = 5 px, the spurs, the smallest region, ...) were chosen on
    images of 300-512 px: a clip art or a drawing is worked at ``SYNTHETIC_WORK_SIDE`` px at most
    and a photo at ``PHOTO_WORK_SIDE`` (constants, with the measurements), so that a larger file of
    the same picture gives about the same logo and the time follows the working size, not the
    input's. The photo test (:func:`photo_reason`) runs once, on the synthetic working copy, and
    the kind detection reuses it (:attr:`LoadedImage.flat_fraction` is cached); the reason is
    "given" when ``kind`` says photo. One :class:`DownscaleWarning` says the size chosen.
    """
    reason = None
    work = img if kind == "photo" else downscale(img, SYNTHETIC_WORK_SIDE)  # said below, once the kind is known
    if kind == "photo" and max(img.width, img.height) > PHOTO_WORK_SIDE:
        reason = "given"
    elif kind == "auto" and (work is not img or max(img.width, img.height) > PHOTO_WORK_SIDE):
        reason = photo_reason(work)
    if reason is not None:
        side = min(PHOTO_WORK_SIDE, max(img.width, img.height))
        photo = (
            work if max(work.width, work.height) == side else downscale(img, PHOTO_WORK_SIDE)
        )  # from the loaded copy
        if photo is not img:
            warn_downscaled(photo, f"a photo is worked at {PHOTO_WORK_SIDE} px on its longer side")
        return photo, "photo", reason
    if work is not img:
        warn_downscaled(work, f"a clip art or a drawing is worked at {SYNTHETIC_WORK_SIDE} px on its longer side")
    return work, kind, reason


def _in_input_pixels(progression: Progression, img: LoadedImage) -> Progression:
    """Every level scaled from the working size back to the input's pixels (:meth:`Abstraction.scaled`)."""
    factor = max(img.input_width, img.input_height) / max(img.width, img.height)

    def params(a: Abstraction) -> Mapping[str, Any]:
        out = dict(a.params)
        sym = out.get("symmetry")
        if isinstance(sym, Mapping) and "point" in sym:  # the mirror axis's point is a length too
            out["symmetry"] = {**sym, "point": [float(v) * factor for v in sym["point"]]}
        return out

    def scaled(a: Abstraction) -> Abstraction:
        return a.scaled(factor, img.input_width, img.input_height, params=params(a))

    levels = progression.levels
    scaled_levels = levels.map(scaled) if isinstance(levels, Levels) else Levels([scaled(a) for a in levels])
    final = scaled_levels[-1]  # every level has the same ladder
    return dataclasses.replace(progression, levels=scaled_levels, bias=final.bias, ladder=final.ladder)


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
