"""The GrabCut [RKB04] of a photo's subject: run small, refined at full size, let into the frame strip.

:func:`grab_cut` runs OpenCV's GrabCut on a copy whose longer side is ``SUBJECT_WORK_SIDE`` px
(:func:`cut_small`, a :class:`SmallCut`) and refines it at full size in a band around its boundary
(:func:`refine_cut`); :func:`both_cuts` runs it on the colours and on colour and texture. A cut from
the frame that comes near the frame strip is let into the strip where its colours say so
(:func:`reach_frame`). :func:`img2logo.features.photo.subject.find_subject` decides which cut is the
subject.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ...images.loading import LoadedImage
from ...images.ndimage import dilate, distance, erode
from ..constants import (
    FOCUS_GRABCUT_ITERATIONS,
    SUBJECT_FRAME_REACH,
    SUBJECT_FRAME_ROUNDS,
    SUBJECT_GRABCUT_ITERATIONS,
    SUBJECT_REFINE_BAND,
)
from .subject_cues import (
    FocusSeeds,
    clean_mask,
    fill_small_holes,
    frame_box,
    frame_strip,
    largest_part,
    texture_colour_image,
    texture_lab,
    texture_map,
    work_scale,
    working_copy,
)

if TYPE_CHECKING:
    from collections.abc import Callable
    from concurrent.futures import Executor

    #: ``subject.find_subject``'s ``beside``: work started in a spare thread of the subject search.
    Beside = Callable[[LoadedImage, Executor], object]


#: The rectangle argument of ``cv2.grabCut`` where it is unused (GC_INIT_WITH_MASK, GC_EVAL): OpenCV
#: accepts None there, its type stubs want a rectangle.
_NO_RECT = (0, 0, 0, 0)


def start_beside(img: LoadedImage, pool: Executor | None, beside: Beside | None) -> None:
    """Start :func:`~img2logo.features.photo.subject.find_subject`'s ``beside`` work in ``pool``, if it was given."""
    if pool is not None and beside is not None:
        beside(img, pool)


def both_cuts(
    img: LoadedImage,
    pool: Executor | None = None,
    beside: Beside | None = None,
    keep: list[SmallCut] | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray | None]:
    """GrabCut on the colours and on colour and texture, run side by side: (mask, texture, textured mask, lab).

    The two cuts are independent and OpenCV releases the interpreter while it
    cuts, so they run in two threads, each seeding its own random generator:
    the result is the same as one after the other. The work around them is
    shared out too: while this thread takes the photo's smoothed CIELAB
    (``img.smooth_lab``), the other makes the texture map, then waits for the
    CIELAB to make its feature image; after its cut it makes what the two
    candidates' outlines are compared on, ``lab``
    (:func:`~img2logo.features.photo.subject_cues.texture_lab`; None when the textured cut
    found nothing). Given a ``pool`` of two threads (:func:`~img2logo.features.photo.subject.find_subject`'s
    ``beside``), the other cut runs in it, and once this thread's cut is
    done ``beside`` is started in its second thread. Given a list ``keep``,
    the two cuts at the working scale are appended to it, the colours' first
    (:func:`grab_cut`).
    """
    import threading
    from concurrent.futures import ThreadPoolExecutor

    lab_ready = threading.Event()
    kept_colour: list[SmallCut] = []
    kept_texture: list[SmallCut] = []

    def textured() -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
        texture = texture_map(img.rgb, work_scale(img))
        lab_ready.wait()
        cut = clean_mask(grab_cut(img, texture=texture, keep=kept_texture))
        return texture, cut, texture_lab(img, texture) if cut.any() else None

    own = ThreadPoolExecutor(max_workers=1) if pool is None else None
    runner = pool if pool is not None else own
    assert runner is not None
    try:
        other = runner.submit(textured)
        try:
            _ = img.smooth_lab  # computed once, here, while the other thread makes the texture map
        finally:
            lab_ready.set()
        mask = clean_mask(grab_cut(img, keep=kept_colour))
        start_beside(img, pool, beside)  # a core is free now, or will be as soon as the other cut is done
        texture, cut, lab = other.result()
    finally:
        if own is not None:
            own.shutdown()
    if keep is not None:
        keep.extend(kept_colour + kept_texture)
    return mask, texture, cut, lab


@dataclass(frozen=True, eq=False)
class SmallCut:
    """GrabCut's result at the working scale, and what its full-size refinement starts from.

    Attributes
    ----------
    label : ndarray of uint8, shape (h, w)
        GrabCut's labels at the working scale.
    bgd, fgd : ndarray of float, shape (1, 65)
        The background's and the object's colour models (OpenCV's GMMs).
    full8 : ndarray of uint8, shape (H, W, 3)
        The image cut, at full size (colours, or colour and texture).
    small8 : ndarray of uint8, shape (h, w, 3)
        The same at the working scale.
    rect : (x, y, w, h) or None
        The user's rectangle, px of the full-size image: outside it stays background.
    """

    label: np.ndarray
    bgd: np.ndarray
    fgd: np.ndarray
    full8: np.ndarray
    small8: np.ndarray
    rect: tuple[int, int, int, int] | None


def grab_cut(
    img: LoadedImage,
    rect: tuple[int, int, int, int] | None = None,
    seeds: FocusSeeds | None = None,
    texture: np.ndarray | None = None,
    keep: list[SmallCut] | None = None,
) -> np.ndarray:
    """GrabCut from a rectangle (default: the frame inset by ``SUBJECT_FRAME_INSET``) or focus seeds, (H, W) bool.

    Run on a copy whose longer side is ``SUBJECT_WORK_SIDE`` px
    (``SUBJECT_GRABCUT_ITERATIONS`` iterations from a rectangle,
    ``FOCUS_GRABCUT_ITERATIONS`` from focus seeds), then once more at full
    size (:func:`refine_cut`).
    Given the photo's :func:`~img2logo.features.photo.subject_cues.texture_map` ``texture``, it cuts on
    :func:`~img2logo.features.photo.subject_cues.texture_colour_image` instead of the colours alone.
    Given a list ``keep``, the cut at the working scale is appended to it (for
    :func:`reach_frame`). Deterministic (OpenCV's random generator is seeded).
    """
    cut = cut_small(img, rect, seeds, texture)
    if keep is not None:
        keep.append(cut)
    return refine_cut(img, cut)


def cut_small(
    img: LoadedImage,
    rect: tuple[int, int, int, int] | None = None,
    seeds: FocusSeeds | None = None,
    texture: np.ndarray | None = None,
) -> SmallCut:
    """:func:`grab_cut`'s cut at the working scale."""
    import cv2

    h, w = img.height, img.width
    small, _ = working_copy(img)
    sh, sw = small.shape[:2]
    sx, sy = sw / w, sh / h
    bgd, fgd = np.zeros((1, 65), np.float64), np.zeros((1, 65), np.float64)
    cv2.setRNGSeed(0)
    # one feature image at full size, shrunk for the first run: the refinement reuses its models
    textured = texture is not None
    full8 = texture_colour_image(img.smooth_lab, texture) if textured else _bgr8(img.rgb)
    small8 = cv2.resize(full8, (sw, sh), interpolation=cv2.INTER_AREA) if textured else _bgr8(small)
    if seeds is not None:
        label = seeds.label.copy()
        cv2.grabCut(small8, label, _NO_RECT, bgd, fgd, FOCUS_GRABCUT_ITERATIONS, cv2.GC_INIT_WITH_MASK)
    else:
        if rect is None:
            box = frame_box((sh, sw))
        else:
            x, y, rw, rh = rect
            bx0, by0 = int(np.floor(x * sx)), int(np.floor(y * sy))
            bx1, by1 = min(sw, int(np.ceil((x + rw) * sx))), min(sh, int(np.ceil((y + rh) * sy)))
            box = (bx0, by0, max(2, bx1 - bx0), max(2, by1 - by0))
        label = np.zeros((sh, sw), np.uint8)
        cv2.grabCut(small8, label, box, bgd, fgd, SUBJECT_GRABCUT_ITERATIONS, cv2.GC_INIT_WITH_RECT)
    return SmallCut(label, bgd, fgd, full8, small8, rect)


def refine_cut(img: LoadedImage, cut: SmallCut) -> np.ndarray:
    """A cut at the working scale (:func:`cut_small`) refined at full size, (H, W) bool.

    GrabCut once more at full size, only in a band of ``SUBJECT_REFINE_BAND`` px
    (at the working scale) around the boundary found, on the band's bounding
    box, starting from the colour models of the first run (copied: ``cut`` is
    left as it is).
    """
    import cv2

    h, w = img.height, img.width
    scale = work_scale(img)
    bgd, fgd = cut.bgd.copy(), cut.fgd.copy()
    fg = largest_part((cut.label == cv2.GC_FGD) | (cut.label == cv2.GC_PR_FGD))
    if not fg.any():
        return np.zeros((h, w), bool)
    fg = fill_small_holes(fg)
    up = cv2.resize(fg.astype(np.float32), (w, h), interpolation=cv2.INTER_LINEAR) >= 0.5
    if scale == 1.0:
        return up
    band = max(2, round(SUBJECT_REFINE_BAND / scale))
    full = np.full((h, w), cv2.GC_BGD, np.uint8)
    near = dilate(up, band)
    full[near] = cv2.GC_PR_BGD
    full[up] = cv2.GC_PR_FGD
    full[erode(up, band)] = cv2.GC_FGD
    if cut.rect is not None:  # outside the user's rectangle stays background
        x, y, rw, rh = cut.rect
        outside = np.ones((h, w), bool)
        outside[y : y + rh, x : x + rw] = False
        full[outside] = cv2.GC_BGD
    # Only the band is open: the cut runs on its bounding box (and 1 px of fixed background
    # around it, so every open pixel keeps its neighbours), starting from the first run's colour
    # models (GC_EVAL: no k-means start at full size; they are re-learnt on the box once).
    rows, cols = np.nonzero(near)
    r0, r1 = max(0, rows.min() - 1), min(h, rows.max() + 2)
    c0, c1 = max(0, cols.min() - 1), min(w, cols.max() + 2)
    crop = np.ascontiguousarray(full[r0:r1, c0:c1])
    cv2.grabCut(np.ascontiguousarray(cut.full8[r0:r1, c0:c1]), crop, _NO_RECT, bgd, fgd, 1, cv2.GC_EVAL)
    full[r0:r1, c0:c1] = crop
    return (full == cv2.GC_FGD) | (full == cv2.GC_PR_FGD)


def reach_frame(cut: SmallCut) -> SmallCut | None:
    """The object of a cut from the frame let into the frame strip where its colours say so.

    GrabCut from the frame (:func:`~img2logo.features.photo.subject_cues.frame_box`) takes the strip of
    ``SUBJECT_FRAME_INSET`` of each side for certain background. An object
    that reaches into it (a disc almost filling the picture, a portrait's
    shoulders running off its foot) then loses its part there, and worse: that
    part's colours are learnt by the background's model, which then eats into
    the object's own pixels of those colours inside the box too (a flat side,
    notches). So the strip within ``SUBJECT_FRAME_REACH`` strip widths of the
    object found (its largest piece) is opened, made probable background, and
    GrabCut goes on for one iteration from the models of the cut: a strip pixel
    the object's colour model explains better than the background's joins the
    object, and once it does the background's model is learnt without it (the
    mechanism by which GrabCut decides inside the box). This is repeated, for
    the strip near the object as it has grown, up to ``SUBJECT_FRAME_ROUNDS``
    times. The rest of the strip stays certain background. ``cut`` is left as
    it is. None if no pixel of the strip joined the object (nothing to refine
    or check again).
    """
    import cv2

    label, bgd, fgd = cut.label.copy(), cut.bgd.copy(), cut.fgd.copy()
    sh, sw = label.shape
    x0, y0, _, _ = frame_box((sh, sw))
    closed = frame_strip((sh, sw)) & (label == cv2.GC_BGD)
    for _ in range(SUBJECT_FRAME_ROUNDS):
        fg = largest_part((label == cv2.GC_FGD) | (label == cv2.GC_PR_FGD))
        if not fg.any():
            break
        near = closed & (distance(~fg) <= SUBJECT_FRAME_REACH * max(x0, y0))
        if not near.any():
            break
        label[near] = cv2.GC_PR_BGD
        closed &= ~near
        cv2.grabCut(cut.small8, label, _NO_RECT, bgd, fgd, 1, cv2.GC_EVAL)
    joined = frame_strip((sh, sw)) & ((label == cv2.GC_FGD) | (label == cv2.GC_PR_FGD))
    if not joined.any():
        return None
    return dataclasses.replace(cut, label=label, bgd=bgd, fgd=fgd)


def near_frame_strip(mask: np.ndarray) -> bool:
    """Whether a subject ``mask`` (H, W) bool comes within ``SUBJECT_FRAME_REACH`` strip widths of the frame strip."""
    h, w = mask.shape
    x0, y0, bw, bh = frame_box((h, w))
    reach = SUBJECT_FRAME_REACH * max(x0, y0)
    rows = np.flatnonzero(mask.any(axis=1))
    cols = np.flatnonzero(mask.any(axis=0))
    if rows.size == 0:
        return False
    return bool(
        rows[0] - y0 < reach or y0 + bh - 1 - rows[-1] < reach or cols[0] - x0 < reach or x0 + bw - 1 - cols[-1] < reach
    )


def _bgr8(rgb: np.ndarray) -> np.ndarray:
    return np.ascontiguousarray((np.clip(rgb[:, :, ::-1], 0.0, 1.0) * 255).round().astype(np.uint8))
