"""Preprocessing (paper Sec. 4): an image's feature lines, by its kind.

Three kinds of input, as in the paper:

* **line drawing**: binarize, drop small specks, thin to a 1-px skeleton, prune
  short spurs (:mod:`img2logo.features.drawing_lines`);
* **clip art**: boundaries between flat-colour regions (:mod:`img2logo.features.clipart`);
* **real photo**: a flow-based line drawing after Kang et al. [KD09]
  (:mod:`img2logo.features.photo.lines`).

The kind is told by :mod:`img2logo.features.kinds`. Loading is :mod:`img2logo.images.loading`; its
names, and the kinds' and the drawing lines' public ones, are re-exported here.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from .._compat import median
from .._validation import check_choice, check_positive, readonly
from ..constants import DETAIL
from ..images.line_ends import join_line_ends
from ..images.loading import load_image, load_mask
from ..images.ndimage import skeletonize
from ..option_values import check_detail
from .clipart import clipart_regions, enclosed_paper
from .clipart_colours import label_lightness
from .constants import PHOTO_MIN_LINE_LENGTH, PHOTO_SPUR_LENGTH, SPUR_LENGTH
from .drawing_lines import clean_skeleton, drawing_ink, keep_dots, median_stroke_width, without_small_parts
from .kinds import detect_kind, detect_kind_and_regions, photo_reason

if TYPE_CHECKING:
    from .photo.line_maps import edge_tangent_flow, flow_dog
    from .photo.subject import Subject

# The photo modules (the flow-based lines, the subject's segmentation) load only for a
# photo: a clip art's or a drawing's run does not import them.
_PHOTO_NAMES = ("edge_tangent_flow", "flow_dog")


def __getattr__(name: str) -> Any:
    if name in _PHOTO_NAMES:
        from .photo import line_maps as photo

        return getattr(photo, name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


__all__ = [
    "KINDS",
    "FeatureLines",
    "detect_kind",
    "detect_kind_and_regions",
    "edge_tangent_flow",
    "extract_feature_lines",
    "flow_dog",
    "keep_dots",
    "load_image",
    "load_mask",
    "median_stroke_width",
    "photo_reason",
    "without_small_parts",
]

KINDS = ("photo", "clipart", "drawing")


@dataclass(frozen=True, eq=False)
class FeatureLines:
    """Feature lines of an image: a 1-px-wide map and how it was made.

    Attributes
    ----------
    lines : ndarray of bool, shape (H, W)
        The 1-px-wide feature-line map.
    kind : str
        ``"photo"``, ``"clipart"`` or ``"drawing"``.
    reason : str
        Why this kind: ``"given"`` or what :func:`~img2logo.features.kinds.detect_kind` measured.
    regions : ndarray of int, shape (H, W), or None
        For clip art, the flat-colour region label of each pixel (0 = background).
    subject : Subject or None
        For photos, the part of the image drawn and how it was found
        (:func:`img2logo.features.photo.subject.find_subject`).
    stroke_width : float or None
        For a line drawing, its median stroke width, px: twice the median
        distance from the ink's skeleton to the paper
        (:func:`~img2logo.features.drawing_lines.median_stroke_width`); None for the other kinds.
    detail : int or None
        For a clip art, the regions kept besides the background
        (:func:`img2logo.features.detail.merge_by_importance`): the ``detail``
        asked, more where what is never merged is more, fewer where there were
        too many regions; None for the other kinds.

    Examples
    --------
    >>> from img2logo import data, extract_feature_lines
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> lines = extract_feature_lines(image)  # FeatureLines
    >>> lines.shape, bool(lines.lines.any())
    ((160, 160), True)
    """

    lines: np.ndarray
    kind: str
    reason: str
    regions: np.ndarray | None = None
    subject: Subject | None = None
    stroke_width: float | None = None
    detail: int | None = None

    @property
    def shape(self) -> tuple[int, int]:
        return (int(self.lines.shape[0]), int(self.lines.shape[1]))


# --------------------------------------------------------------------------- feature lines
def extract_feature_lines(
    image: object,
    kind: str = "auto",
    *,
    foreground: object = "auto",
    subject: object = None,
    spur_length: float | None = None,
    min_line_length: float | None = None,
    detail: int = DETAIL,
    arcs: int | None = None,
) -> FeatureLines:
    """Extract the object's feature lines as a 1-px-wide map (paper Sec. 4).

    Parameters
    ----------
    image : path, ndarray or LoadedImage
        The input, read by :func:`~img2logo.images.loading.load_image`.
    kind : {"auto", "photo", "clipart", "drawing"}
        The kind of input; ``"auto"`` chooses with :func:`~img2logo.features.kinds.detect_kind` and says
        why in the result's ``reason``.
    foreground : {"auto", "none", "grabcut"}, path or ndarray of bool, shape (H, W), optional
        Photos only: the subject whose outline and inner lines are drawn
        (:func:`img2logo.features.photo.subject.find_subject`): found automatically (default;
        an image with transparency uses its alpha), the whole image, GrabCut
        kept whatever it finds, or a mask (white = object). None is ``"auto"``.
    subject : (x, y, w, h) or "X,Y,W,H", optional
        Photos only: a rectangle around the object, px of the input image (before
        any downscale), that seeds GrabCut (:func:`img2logo.features.photo.subject.find_subject`).
    spur_length : float, optional
        Side spurs of the skeleton shorter than this are pruned, px (default
        ``SPUR_LENGTH``; photos ``PHOTO_SPUR_LENGTH``).
    min_line_length : float, optional
        Isolated lines shorter than this are dropped, px (default:
        ``spur_length`` for drawings and clip art, a longer bound for photos,
        whose short lines are mostly texture).
    detail : int
        Clip art only: the regions kept besides the background
        (:func:`img2logo.features.detail.merge_by_importance`; default ``DETAIL``).
    arcs : int or None
        Clip art only: an arc budget, the logo's predicted arcs at most this
        (:func:`img2logo.features.detail.merge_by_importance`; default None: none).

    Returns
    -------
    FeatureLines

    Examples
    --------
    >>> from img2logo import data, extract_feature_lines
    >>> image = data.ring()  # a black ring, 50 px round, on 160 x 160 px
    >>> lines = extract_feature_lines(image)
    >>> lines.kind, lines.lines.shape, lines.lines.dtype
    ('drawing', (160, 160), dtype('bool'))
    """
    img = load_image(image)
    kind = check_choice(kind, "kind", ("auto", *KINDS))
    if spur_length is not None:
        spur_length = check_positive(spur_length, "spur_length", allow_zero=True)
    regions = None
    if kind == "auto":
        kind, reason, regions = detect_kind_and_regions(img)
    else:
        reason = "given"
    found = dots = None
    if spur_length is None:
        spur_length = PHOTO_SPUR_LENGTH if kind == "photo" else SPUR_LENGTH
    radius = stroke = detail_used = None
    budget = 0.0
    if kind == "drawing":
        ink, radius = drawing_ink(img)
        axis = skeletonize(ink)
        stroke = float(2.0 * median(radius[axis])) if axis.any() else 0.0
        raw = join_line_ends(axis)
        min_len = spur_length if min_line_length is None else min_line_length
    elif kind == "clipart":
        # The clip art's modules (its strokes, the regions' ranking) load only for a clip art.
        from .clipart_strokes import clipart_lines
        from .detail import close_line_ends, merge_by_importance

        regions = enclosed_paper(clipart_regions(img) if regions is None else regions, img)
        regions, detail_used, budget = merge_by_importance(
            regions, img.lab, check_detail(detail), arcs=None if arcs is None else check_detail(arcs, "arcs", "arcs")
        )
        raw = _join(clipart_lines(regions, label_lightness(regions, img.lab[..., 0])))
        min_len = spur_length if min_line_length is None else min_line_length
    else:
        from .photo.line_maps import line_maps, start_photo_line_maps
        from .photo.lines import photo_feature_lines, subject_dots, subject_pupils
        from .photo.subject import find_subject

        found = find_subject(img, foreground, subject, beside=start_photo_line_maps)  # the line maps beside the cuts
        dots = subject_dots(img, found)  # the blob dots, while the line maps may still be under way
        maps = line_maps(img)
        dots = subject_pupils(img, found, maps, dots)  # and the pupils in the lines' closed loops
        raw = photo_feature_lines(img, found, dots, maps)
        min_len = PHOTO_MIN_LINE_LENGTH if min_line_length is None else min_line_length
    min_len = check_positive(min_len, "min_line_length", allow_zero=True)
    lines = clean_skeleton(raw, spur_length=spur_length, min_length=min_len, radius=radius)
    if kind == "clipart" and regions is not None:  # every line whole: each end joined, or its mark dropped whole
        closed = close_line_ends(lines, regions, img.lab, budget)
        lines = clean_skeleton(closed, spur_length=spur_length, min_length=min_len)
    if dots is not None and dots.count:  # an eye's outline is shorter than a photo's shortest line
        from .photo.lines import dot_lines

        lines |= dot_lines(raw, dots)
    if found is not None and found.faces:  # a face's eyes and mouth are shorter than a photo's shortest line
        from .photo.lines import face_line_length, face_region

        short = face_line_length(found.faces)
        near_face = face_region(raw.shape, found.faces)
        lines |= clean_skeleton(raw & near_face, spur_length=min(spur_length, short / 2), min_length=short)
    if kind == "drawing":
        lines = keep_dots(lines, ink, stroke)
    return FeatureLines(
        readonly(lines),
        kind,
        reason,
        None if regions is None else readonly(regions),
        found,
        stroke_width=stroke,
        detail=detail_used,
    )


def _join(raw: np.ndarray) -> np.ndarray:
    """Thin a drawing's ink or a clip art's lines and join the ends that stop short of a line.

    A stroke that ends a few px before another (a clip art's whisker by its
    face's outline, a drawing's line that stops at a gap) would give an arc end
    0.75-6 px from another arc: a near-miss gap. :func:`~img2logo.images.line_ends.join_line_ends`
    links it (the same rule as for photos).
    """
    return join_line_ends(skeletonize(raw))
