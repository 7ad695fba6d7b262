"""Subject isolation for photos: which pixels are the object the logo is of.

A photo shows its subject on a background; the logo should draw the subject
only (paper Fig. 1, 10). :func:`find_subject` finds it without user input
(``foreground="auto"``) or from the user's hint:

* an image with transparency: its opaque pixels;
* ``"auto"``: OpenCV's GrabCut [RKB04] started from the frame of the image (a
  strip of ``SUBJECT_FRAME_INSET`` of each side is background, the rest maybe
  object), run on a copy whose longer side is ``SUBJECT_WORK_SIDE`` px, then
  refined at full size in a band around its boundary. GrabCut runs twice:
  on the colours, and on colour and texture (:func:`~img2logo.features.photo.subject_cues.texture_colour_image`:
  the local energy of fine detail beside CIELAB, so that an object of the
  background's own hue but another texture, a smooth body on grass or
  gravel, is told apart); the candidate whose outline is the sharper edge
  (:func:`~img2logo.features.photo.subject_cues.outline_contrast`) is taken. The result is kept if
  it is one dominant object: between ``SUBJECT_MIN_AREA`` and
  ``SUBJECT_MAX_AREA`` of the image, touching at most ``SUBJECT_MAX_FRAME`` of
  the frame, with an outline that is an edge (:func:`~img2logo.features.photo.subject_cues.outline_contrast` at
  least ``SUBJECT_MIN_CONTRAST``; or, in a photo without depth of field, a
  texture edge: :func:`~img2logo.features.photo.subject_cues.texture_step` at least ``SUBJECT_MIN_TEXTURE_STEP``).
  If it is not, and the photo shows depth of
  field (:func:`~img2logo.features.photo.subject_cues.focus_seeds`: a close-up in focus that runs off the picture
  in front of a blurred background), GrabCut starts again from the blurred
  parts of the frame (background) and the sharp cores (object); that result is
  kept if it covers between ``SUBJECT_MIN_AREA`` and ``SUBJECT_MAX_AREA``
  (it may touch the frame) and its outline is a colour edge or a focus edge
  (:func:`~img2logo.features.photo.subject_cues.focus_step` at least ``FOCUS_MIN_STEP``). Otherwise the whole image
  is kept (a scene, or a close-up that fills the frame), and
  :attr:`Subject.description` says why. A kept candidate made of parts of
  different texture joined by a thin neck (a pagoda and the trees beside
  it) keeps its dominant part (:func:`dominant_part`). Before that, a kept
  candidate from the frame that comes near the frame strip is let into the
  strip where its colours say so (:func:`~img2logo.features.photo.subject_cut.reach_frame`: a disc that almost
  fills the picture, a portrait's shoulders that run off its foot), if it is
  then still one dominant object with an object's outline. Last, the thin
  parts that leave it, which GrabCut at the working size and the smoothing
  drop (a tail, a tripod's legs: :func:`~img2logo.features.photo.subject_cues.thin_parts`),
  are joined to it;
* ``"grabcut"``: the same GrabCut, kept whatever it finds;
* a rectangle ``subject=(x, y, w, h)``: GrabCut started from it (outside is
  background);
* a mask (an array, or a file read by :func:`img2logo.load_mask`);
* ``"none"``: the whole image.

Whatever found the subject, the frontal faces in it are found too
(:func:`~img2logo.features.photo.faces.find_faces`, :attr:`Subject.faces`): a portrait's eyes, brows, nose and
mouth are kept as inner lines (:mod:`img2logo.features.photo.lines`).

The mask is cleaned the same way whatever found it: its largest connected
piece, holes under ``SUBJECT_MAX_HOLE`` of its area filled (a handle's loop
stays open), then smoothed by a Gaussian of ``SUBJECT_SMOOTH_SIGMA``
(no pixel staircase from the small working copy).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ..._compat import median
from ..._validation import readonly
from ...errors import InvalidParameterError
from ...images.loading import LoadedImage, load_mask
from ...images.ndimage import dilate, label
from ..constants import (
    FOCUS_MIN_STEP,
    SUBJECT_CONTRAST_STEP,
    SUBJECT_MAX_AREA,
    SUBJECT_MAX_FRAME,
    SUBJECT_MIN_AREA,
    SUBJECT_MIN_CONTRAST,
    SUBJECT_MIN_PART,
    SUBJECT_MIN_TEXTURE_STEP,
    SUBJECT_NECK,
    SUBJECT_TEXTURE_WEIGHT,
)
from .subject_cues import (
    FocusSeeds,
    clean_mask,
    fill_small_holes,
    focus_seeds,
    focus_step,
    frame_strip,
    largest_part,
    outline_contrast,
    texture_step,
    thin_parts,
)
from .subject_cut import SmallCut, both_cuts, grab_cut, near_frame_strip, reach_frame, refine_cut, start_beside
from .subject_shadow import cast_shadow

if TYPE_CHECKING:
    from concurrent.futures import Executor

    from .subject_cut import Beside
from .faces import find_faces

#: The string values of ``foreground``.
FOREGROUND_CHOICES = ("auto", "none", "grabcut")


@dataclass(frozen=True, eq=False)
class Subject:
    """The part of a photo its logo is drawn from.

    Attributes
    ----------
    mask : ndarray of bool, shape (H, W), or None
        The object's pixels; None when the whole image is kept.
    method : str
        How it was found: ``"alpha"``, ``"auto"``, ``"grabcut"``,
        ``"rectangle"``, ``"mask"`` or ``"none"``.
    description : str
        One line for the user: what was kept and how it was found.
    faces : tuple of (x, y, w, h)
        The faces found in it (:func:`~img2logo.features.photo.faces.find_faces`), px; their inner lines
        (eyes, brows, nose, mouth) are kept as features of the subject.
    """

    mask: np.ndarray | None
    method: str
    description: str
    faces: tuple[tuple[int, int, int, int], ...] = ()


def check_foreground_option(foreground: object) -> None:
    """Check a ``foreground`` value without reading anything (see :func:`find_subject`)."""
    if foreground is None or isinstance(foreground, (np.ndarray, Path)):
        return
    if isinstance(foreground, str) and (foreground in FOREGROUND_CHOICES or Path(foreground).suffix):
        return
    raise InvalidParameterError(
        f"foreground must be one of {', '.join(FOREGROUND_CHOICES)}, a mask image or array, got {foreground!r}"
    )


def subject_rectangle_numbers(value: object) -> list[float]:
    """The four numbers of a subject rectangle ``(x, y, w, h)`` or ``"X,Y,W,H"``, checked for form only."""
    if isinstance(value, str):
        parts = value.split(",")
        try:
            nums = [float(p) for p in parts]
        except ValueError:
            nums = []
    else:
        try:
            nums = [float(v) for v in np.asarray(value, dtype=float).ravel()]
        except (TypeError, ValueError):
            nums = []
    if len(nums) != 4 or not all(np.isfinite(nums)):
        raise InvalidParameterError(f"subject must be a rectangle X,Y,W,H of four numbers in px, got {value!r}")
    return nums


def parse_subject_rectangle(value: object, shape: tuple[int, int]) -> tuple[int, int, int, int]:
    """Check a subject rectangle ``(x, y, w, h)`` (or the text ``"X,Y,W,H"``) against an image of ``shape``.

    Returns
    -------
    (x, y, w, h) : tuple of int
        Clipped to the image, px.
    """
    x, y, w, h = (round(v) for v in subject_rectangle_numbers(value))
    height, width = shape
    x0, y0 = max(0, x), max(0, y)
    x1, y1 = min(width, x + w), min(height, y + h)
    if w <= 0 or h <= 0 or x1 - x0 < 4 or y1 - y0 < 4:
        raise InvalidParameterError(
            f"subject rectangle {x},{y},{w},{h} must cover at least 4x4 px of the {width}x{height} image"
        )
    if x0 == 0 and y0 == 0 and x1 == width and y1 == height:
        raise InvalidParameterError(
            f"subject rectangle {x},{y},{w},{h} covers the whole {width}x{height} image: it must leave some "
            "background outside"
        )
    return x0, y0, x1 - x0, y1 - y0


def find_subject(
    img: LoadedImage,
    foreground: object = "auto",
    subject: object = None,
    *,
    beside: Beside | None = None,
) -> Subject:
    """Find the subject of a photo, and the faces in it (:func:`~img2logo.features.photo.faces.find_faces`).

    Parameters
    ----------
    img : LoadedImage
        The photo.
    foreground : {"auto", "none", "grabcut"}, None, path or ndarray of bool, shape (H, W)
        How to find it (see the module's documentation); None is ``"auto"``. A
        path is read as a mask image (white = object).
    subject : (x, y, w, h) or "X,Y,W,H", optional
        A rectangle around the object, px of the input image (before any
        downscale: ``img.input_width`` by ``img.input_height``; it is scaled
        by ``img.scale`` here, and said as given): GrabCut starts from it.
        Only with ``foreground`` ``"auto"`` or ``"grabcut"``.
    beside : callable, optional
        Work that does not depend on the subject, started as ``beside(img,
        pool)`` in a thread of its own (``pool``'s) while the subject is
        searched, from when a core is free of GrabCut: the photo's line maps
        (:func:`img2logo.features.photo.lines.start_photo_line_maps`), which the photo's lines
        (:func:`img2logo.features.photo.lines.photo_feature_lines`) then take. Given here, not
        imported, so that this stage knows nothing of the next.

    Returns
    -------
    Subject
    """
    from concurrent.futures import ThreadPoolExecutor

    pool = ThreadPoolExecutor(max_workers=2) if beside is not None else None
    try:
        found = _find_subject(img, foreground, subject, pool, beside)
    finally:
        if pool is not None:
            pool.shutdown(wait=False)  # the line maps go on being made
    faces = find_faces(img, found.mask)
    if not faces:
        return found
    note = f"; {len(faces)} face(s) kept with their features"
    return dataclasses.replace(found, faces=faces, description=found.description + note)


def _find_subject(
    img: LoadedImage, foreground: object, subject: object, pool: Executor | None, beside: Beside | None
) -> Subject:
    shape = (img.height, img.width)
    check_foreground_option(foreground)
    if foreground is None:
        foreground = "auto"
    if isinstance(foreground, str) and foreground not in FOREGROUND_CHOICES:
        foreground = Path(foreground)
    if subject is not None:
        if not (isinstance(foreground, str) and foreground in ("auto", "grabcut")):
            raise InvalidParameterError("subject (a rectangle) needs foreground auto or grabcut, not a mask or none")
        said = parse_subject_rectangle(subject, (img.input_height, img.input_width))  # the input's pixels
        rect = said if img.scale == 1.0 else _at_working_size(said, img)
        start_beside(img, pool, beside)  # one cut: the other core makes the line maps
        mask = clean_mask(grab_cut(img, rect=rect))
        if not mask.any():
            raise InvalidParameterError(f"no object found in the subject rectangle {','.join(map(str, said))}")
        x, y, w, h = said
        return Subject(
            readonly(mask), "rectangle", f"kept the object in {x},{y},{w},{h} (GrabCut): {mask.mean():.0%} of the image"
        )
    if isinstance(foreground, str):
        if foreground == "none":
            return Subject(None, "none", "kept the whole image (foreground none)")
        if foreground == "auto" and img.has_alpha and not img.foreground.all():
            mask = img.foreground
            return Subject(readonly(mask.copy()), "alpha", f"kept the opaque pixels (alpha): {mask.mean():.0%}")
        texture = None
        small_cuts: list[SmallCut] = []  # the colours' and the texture's cuts at the working scale
        taken = 0  # which of them the mask is
        if foreground == "auto":  # the same cut with texture: take the candidate whose outline is the sharper edge
            mask, texture, textured, lab = both_cuts(img, pool, beside, keep=small_cuts)
            if lab is not None:  # texture_lab of the texture, once for both candidates
                if outline_contrast(img, textured, lab=lab) > outline_contrast(img, mask, lab=lab):
                    mask, taken = textured, 1
        else:
            start_beside(img, pool, beside)
            mask = clean_mask(grab_cut(img))
        if foreground == "grabcut":
            if not mask.any():
                return Subject(None, "grabcut", "GrabCut found no object: kept the whole image")
            return Subject(
                readonly(mask), "grabcut", f"kept the object found by GrabCut: {mask.mean():.0%} of the image"
            )
        why = _not_dominant(mask) or _weak_outline(img, mask)
        how = "found by GrabCut from the image frame"
        seeds = focus_seeds(img) if why else None
        if why and seeds is None and not _not_dominant(mask):  # no colour edge, no depth of field: a texture edge?
            step = texture_step(img, texture, mask)
            if step >= SUBJECT_MIN_TEXTURE_STEP:
                why, how = "", f"found by GrabCut from the image frame, by its texture: {step:.1f} decades"
            else:
                why = f"{why}, texture step {step:.2f} decades"
        if seeds is not None:  # a close-up in focus that runs off the picture: try depth of field
            focused = clean_mask(grab_cut(img, seeds=seeds))
            why_focus = _not_dominant(focused, frame=False) or _weak_focus_outline(img, seeds, focused)
            if not why_focus:
                mask, why, how = focused, "", "found by GrabCut from the sharp subject and the blurred background"
            else:
                why = f"{why}; from depth of field: {why_focus}"
        if why:
            return Subject(None, "auto", f"kept the whole image: no dominant object ({why})")
        if how.startswith("found by GrabCut from the image frame") and near_frame_strip(mask):
            # one dominant object, found with the frame strip as certain background: it runs into the strip,
            # so its cut goes on with the strip near it open (reach_frame); kept if it is still one object
            cut = reach_frame(small_cuts[taken])
            reached = None if cut is None else clean_mask(refine_cut(img, cut))
            if (
                reached is not None
                and (reached & frame_strip(mask.shape) & ~mask).any()
                and not _not_dominant(reached)
                and _object_outline(img, texture, reached)
                and moved_outline(img, mask, reached) >= SUBJECT_MIN_CONTRAST
            ):
                mask, how = reached, f"{how}; its part in the frame strip kept"
        kept = dominant_part(mask, texture)
        if kept is not mask:
            mask, how = kept, f"{how}; a part of another texture beyond a thin neck left out"
        if not how.startswith("found by GrabCut from the sharp"):  # a blurred background shows no cast shadow
            shadow = cast_shadow(img, mask)
            if shadow is not None:
                mask, how = clean_mask(mask & ~shadow), f"{how}; its cast shadow left out"
        mask, how = _with_thin_parts(img, mask, how)
        return Subject(readonly(mask), "auto", f"kept the main object, {mask.mean():.0%} of the image ({how})")
    mask = load_mask(foreground, shape) if isinstance(foreground, Path) else np.asarray(foreground)
    if mask.shape != shape:
        raise InvalidParameterError(f"foreground mask must have the image's shape {shape}, got {mask.shape}")
    mask = mask.astype(bool)
    if not mask.any():
        raise InvalidParameterError("foreground mask is empty: no pixel is marked as the object")
    return Subject(readonly(mask.copy()), "mask", f"kept the object of the given mask: {mask.mean():.0%} of the image")


def _with_thin_parts(img: LoadedImage, mask: np.ndarray, how: str) -> tuple[np.ndarray, str]:
    """``mask`` with the thin parts that leave it (:func:`~.subject_cues.thin_parts`), and ``how`` said.

    Each is joined to the mask across the 3 px it lies off it, and kept as
    found at full size: :func:`~img2logo.features.photo.subject_cues.clean_mask`'s smoothing
    would take a part 3 px wide away again.
    """
    thin = thin_parts(img, mask)
    if not thin.any():
        return mask, how
    count = label(thin, eight=True)[1]
    bridge = dilate(thin, 3) & dilate(mask, 3)
    joined = largest_part(fill_small_holes(mask | thin | bridge))
    return joined, f"{how}; {count} thin part(s) leaving it kept"


def _at_working_size(rect: tuple[int, int, int, int], img: LoadedImage) -> tuple[int, int, int, int]:
    """A rectangle (x, y, w, h) in the input's pixels, checked, at the size ``img`` is worked at (``img.scale``)."""
    x, y, w, h = rect
    x0, y0 = int(np.floor(x * img.scale)), int(np.floor(y * img.scale))
    x1, y1 = min(img.width, int(np.ceil((x + w) * img.scale))), min(img.height, int(np.ceil((y + h) * img.scale)))
    if x1 - x0 < 4 or y1 - y0 < 4:
        raise InvalidParameterError(
            f"subject rectangle {x},{y},{w},{h} must cover at least 4x4 px of the image as it is worked at "
            f"({img.width}x{img.height} px, {img.scale:.3g} of the input's {img.input_width}x{img.input_height})"
        )
    if x0 == 0 and y0 == 0 and x1 == img.width and y1 == img.height:
        raise InvalidParameterError(
            f"subject rectangle {x},{y},{w},{h} covers the whole image as it is worked at "
            f"({img.width}x{img.height} px): it must leave some background outside"
        )
    return x0, y0, x1 - x0, y1 - y0


def dominant_part(mask: np.ndarray, texture: np.ndarray | None) -> np.ndarray:
    """The dominant part of a subject made of parts of different texture joined by a thin neck, (H, W) bool.

    A candidate such as a pagoda and the trees beside it: opening the mask by
    a disc of radius ``SUBJECT_NECK`` times the square root of its area cuts
    its thin necks; if that leaves two or more parts of at least
    ``SUBJECT_MIN_PART`` of the mask's area and the largest differs in texture
    (median :func:`~img2logo.features.photo.subject_cues.texture_map`) from another by at least
    ``SUBJECT_MIN_TEXTURE_STEP`` decades, only the largest is kept, with the
    mask's pixels within the disc's radius of it. Otherwise ``mask`` itself is
    returned (a giraffe's neck joins parts of one texture: it stays).
    """
    import cv2

    if texture is None or not mask.any():
        return mask
    radius = max(1, round(SUBJECT_NECK * float(np.sqrt(mask.sum()))))
    disc = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * radius + 1, 2 * radius + 1))
    opened = cv2.morphologyEx(mask.astype(np.uint8), cv2.MORPH_OPEN, disc).astype(bool)
    labels, n = label(opened)
    if n < 2:
        return mask
    sizes = np.bincount(labels.ravel())[1:]
    parts = [i + 1 for i in np.argsort(-sizes) if sizes[i] >= SUBJECT_MIN_PART * mask.sum()]
    if len(parts) < 2:
        return mask
    medians = [float(median(texture[labels == i])) for i in parts]
    step = max(abs(m - medians[0]) for m in medians[1:]) / SUBJECT_TEXTURE_WEIGHT
    if step < SUBJECT_MIN_TEXTURE_STEP:
        return mask
    near = cv2.dilate((labels == parts[0]).astype(np.uint8), disc).astype(bool)
    return largest_part(mask & near)


def _not_dominant(mask: np.ndarray, frame: bool = True) -> str:
    """Why ``mask`` is not one dominant object, or ``""`` if it is.

    ``frame=False`` does not limit how much of the image frame it touches (a
    close-up in focus runs off the picture).
    """
    area = float(mask.mean())
    if area < SUBJECT_MIN_AREA:
        return f"the best candidate covers {area:.1%} of the image, under {SUBJECT_MIN_AREA:.0%}"
    if area > SUBJECT_MAX_AREA:
        return f"the candidate covers {area:.0%} of the image, over {SUBJECT_MAX_AREA:.0%}"
    border = np.concatenate([mask[0], mask[-1], mask[1:-1, 0], mask[1:-1, -1]])
    touching = float(border.mean())
    if frame and touching > SUBJECT_MAX_FRAME:
        return f"the candidate touches {touching:.0%} of the image frame"
    return ""


def _weak_outline(img: LoadedImage, mask: np.ndarray) -> str:
    """Why the outline of ``mask`` is no object's edge, or ``""`` if it is."""
    ratio = outline_contrast(img, mask)
    if ratio < SUBJECT_MIN_CONTRAST:
        return f"the candidate's outline is no edge: colour step across it {ratio:.1f}x the texture's"
    return ""


def _object_outline(img: LoadedImage, texture: np.ndarray | None, mask: np.ndarray) -> bool:
    """Whether the outline of ``mask`` is an object's: a colour edge, or (given ``texture``) a texture edge.

    The tests a candidate from the image frame passes (:func:`_weak_outline`,
    :func:`~img2logo.features.photo.subject_cues.texture_step`), asked again of it once it
    has reached into the frame strip (:func:`~img2logo.features.photo.subject_cut.reach_frame`).
    """
    if not _weak_outline(img, mask):
        return True
    return texture is not None and texture_step(img, texture, mask) >= SUBJECT_MIN_TEXTURE_STEP


def moved_outline(img: LoadedImage, before: np.ndarray, after: np.ndarray) -> float:
    """How sharp an edge the outline of ``after`` is where it moved from that of ``before``, unit-free.

    :func:`~img2logo.features.photo.subject_cues.outline_contrast` of the outline of
    ``after`` (H, W) bool within 2 px of the pixels where the two masks
    differ, and farther than two ``SUBJECT_CONTRAST_STEP`` from the image
    frame (nearer, its samples fall off the picture; on the frame the outline
    is the picture's edge, not the object's). A part that :func:`~img2logo.features.photo.subject_cut.reach_frame`
    let into the frame strip is the object's when the outline it moved to is
    an edge, as every object's outline is (at least ``SUBJECT_MIN_CONTRAST``):
    a disc's rim, a portrait's arm against the backdrop. Measured: skimage's
    retina 35, astronaut 6.3, camera 4.4, coffee 16, the photo2 octopus 27; the
    shelves behind skimage's motorcycle, a cluttered scene that runs off the
    picture behind the object and is cut through there, 2.6. 0 if the outline
    did not move.
    """
    h, w = after.shape
    off = round(2 * SUBJECT_CONTRAST_STEP)
    where = dilate(after ^ before, 2)
    where[:off] = where[h - off :] = False
    where[:, :off] = where[:, w - off :] = False
    return outline_contrast(img, after, where=where)


def _weak_focus_outline(img: LoadedImage, seeds: FocusSeeds, mask: np.ndarray) -> str:
    """Why the outline of ``mask`` is neither a colour edge nor a focus edge, or ``""``."""
    step = focus_step(seeds, mask)
    if step >= FOCUS_MIN_STEP:
        return ""
    ratio = outline_contrast(img, mask)
    if ratio >= SUBJECT_MIN_CONTRAST:
        return ""
    return (
        f"the candidate's outline is no edge: colour step across it {ratio:.1f}x the texture's, "
        f"sharpness inside {step:.1f}x outside"
    )
