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
  strip where its colours say so (:func:`reach_frame`: a disc that almost
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
(:func:`find_faces`, :attr:`Subject.faces`): a portrait's eyes, brows, nose and
mouth are kept as inner lines (:mod:`img2logo.features.photo.lines`).

The mask is cleaned the same way whatever found it: its largest connected
piece, holes under ``SUBJECT_MAX_HOLE`` of its area filled (a handle's loop
stays open), then smoothed by a Gaussian of ``SUBJECT_SMOOTH_SIGMA``
(no pixel staircase from the small working copy).

Arrays are indexed (row, column); a rectangle is (x, y, w, h) in px with x the
column and y the row of its top-left corner.
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
from ...images.ndimage import dilate, distance, erode, label
from ..constants import (
    FACE_MIN_NEIGHBOURS,
    FACE_MIN_SIDE,
    FACE_SCALE_STEP,
    FOCUS_GRABCUT_ITERATIONS,
    FOCUS_MIN_STEP,
    SUBJECT_CONTRAST_STEP,
    SUBJECT_FRAME_REACH,
    SUBJECT_FRAME_ROUNDS,
    SUBJECT_GRABCUT_ITERATIONS,
    SUBJECT_MAX_AREA,
    SUBJECT_MAX_FRAME,
    SUBJECT_MIN_AREA,
    SUBJECT_MIN_CONTRAST,
    SUBJECT_MIN_PART,
    SUBJECT_MIN_TEXTURE_STEP,
    SUBJECT_NECK,
    SUBJECT_REFINE_BAND,
    SUBJECT_TEXTURE_WEIGHT,
)
from .subject_cues import (
    FocusSeeds,
    clean_mask,
    fill_small_holes,
    focus_seeds,
    focus_step,
    frame_box,
    frame_strip,
    largest_part,
    outline_contrast,
    texture_colour_image,
    texture_lab,
    texture_map,
    texture_step,
    thin_parts,
    work_scale,
    working_copy,
)
from .subject_shadow import cast_shadow

if TYPE_CHECKING:
    from collections.abc import Callable
    from concurrent.futures import Executor

    #: :func:`find_subject`'s ``beside``: work started in a spare thread of the subject search.
    _Beside = Callable[[LoadedImage, Executor], object]

#: The string values of ``foreground``.
FOREGROUND_CHOICES = ("auto", "none", "grabcut")
#: The rectangle argument of ``cv2.grabCut`` where it is unused (GC_INIT_WITH_MASK, GC_EVAL): OpenCV
#: accepts None there, its type stubs want a rectangle.
_NO_RECT = (0, 0, 0, 0)


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
        The faces found in it (:func:`find_faces`), px; their inner lines
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
    beside: _Beside | None = None,
) -> Subject:
    """Find the subject of a photo, and the faces in it (:func:`find_faces`).

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
    img: LoadedImage, foreground: object, subject: object, pool: Executor | None, beside: _Beside | None
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
        _start_beside(img, pool, beside)  # one cut: the other core makes the line maps
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
            _start_beside(img, pool, beside)
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
        if how.startswith("found by GrabCut from the image frame") and _near_frame_strip(mask):
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


def _start_beside(img: LoadedImage, pool: Executor | None, beside: _Beside | None) -> None:
    """Start :func:`find_subject`'s ``beside`` work in ``pool``, if it was given."""
    if pool is not None and beside is not None:
        beside(img, pool)


def both_cuts(
    img: LoadedImage,
    pool: Executor | None = None,
    beside: _Beside | None = None,
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
    found nothing). Given a ``pool`` of two threads (:func:`find_subject`'s
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
        _start_beside(img, pool, beside)  # a core is free now, or will be as soon as the other cut is done
        texture, cut, lab = other.result()
    finally:
        if own is not None:
            own.shutdown()
    if keep is not None:
        keep.extend(kept_colour + kept_texture)
    return mask, texture, cut, lab


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


def find_faces(img: LoadedImage, mask: np.ndarray | None = None) -> tuple[tuple[int, int, int, int], ...]:
    """Frontal faces in a photo, as boxes (x, y, w, h) in px, largest first.

    scikit-image's LBP frontal-face cascade (OpenCV's ``lbpcascade_frontalface``,
    shipped inside scikit-image: nothing is downloaded) run on the working copy
    (longer side ``SUBJECT_WORK_SIDE`` px); a face at least ``FACE_MIN_SIDE`` of
    the shorter side, found at ``FACE_MIN_NEIGHBOURS`` neighbouring windows or
    more (a face answers at many positions and scales, a face-like patch of
    texture at a few), and with its centre in ``mask`` when one is given.
    """
    import cv2

    small, scale = working_copy(img)
    sh, sw = small.shape[:2]
    side = max(8, round(FACE_MIN_SIDE * min(sh, sw)))
    r0, c0 = 0, 0
    if mask is not None:  # only the subject's box is searched: a face outside it is dropped anyway
        rows, cols = np.nonzero(cv2.resize(mask.astype(np.uint8), (sw, sh), interpolation=cv2.INTER_NEAREST))
        if rows.size == 0:
            return ()
        r0, c0 = int(rows.min()), int(cols.min())
        small = small[r0 : int(rows.max()) + 1, c0 : int(cols.max()) + 1]
    largest = min(small.shape[:2])
    if largest < side:
        return ()
    cascade = _cascade_class()(_cascade_file())
    gray = cv2.cvtColor(np.ascontiguousarray(np.clip(small, 0, 1)), cv2.COLOR_RGB2GRAY)
    found = cascade.detect_multi_scale(
        img=gray,
        scale_factor=FACE_SCALE_STEP,
        step_ratio=1,
        min_size=(side, side),
        max_size=(largest, largest),
        min_neighbor_number=FACE_MIN_NEIGHBOURS,
    )
    faces = []
    for f in sorted(found, key=lambda f: -f["width"] * f["height"]):
        x, y = round((f["c"] + c0) / scale), round((f["r"] + r0) / scale)
        w, h = round(f["width"] / scale), round(f["height"] / scale)
        cx, cy = min(img.width - 1, x + w // 2), min(img.height - 1, y + h // 2)
        if mask is None or mask[cy, cx]:
            faces.append((x, y, w, h))
    return tuple(faces)


def _cascade_file() -> str:
    """The path of scikit-image's LBP frontal-face cascade (``skimage.data.lbp_frontal_face_cascade_filename``).

    It ships in the package's ``data`` folder; asking ``skimage.data`` for it
    loads its download registry and ``skimage.util`` (0.03 s of CPU a run).
    """
    import importlib.util

    spec = importlib.util.find_spec("skimage")
    if spec is not None and spec.origin is not None:
        path = Path(spec.origin).parent / "data" / "lbpcascade_frontalface_opencv.xml"
        if path.is_file():
            return str(path)
    from skimage import data

    return str(data.lbp_frontal_face_cascade_filename())


def _cascade_class() -> type:
    """scikit-image's ``skimage.feature.Cascade``, without importing ``skimage.color``'s colour conversions.

    The compiled module ``skimage.feature._cascade`` imports ``rgb2gray`` from
    ``skimage.color`` when it loads (for colour images; :func:`find_faces` gives
    it gray ones), and ``skimage.color`` imports ``scipy.linalg``, whose array-API
    layer imports most of numpy's optional modules: about 0.4 s of CPU, a fifth
    of a photo's command line. While the module loads, ``skimage.color`` is a
    stand-in whose ``rgb2gray`` imports the real one when first called; the
    stand-in is gone as soon as the module is loaded. Should a later
    scikit-image's cascade import more than that, the stand-in is dropped and
    the package imported as usual (slower, the same faces).
    """
    import sys
    import types

    loaded = sys.modules.get("skimage.feature._cascade")
    if loaded is not None or "skimage.color.colorconv" in sys.modules:
        from skimage.feature import Cascade

        return Cascade
    import skimage

    def rgb2gray(*args: object, **kwargs: object) -> np.ndarray:
        from skimage.color import rgb2gray as real

        return real(*args, **kwargs)

    stand_in = types.ModuleType("skimage.color")
    stand_in.rgb2gray = rgb2gray  # type: ignore[attr-defined]
    before = sys.modules.get("skimage.color")
    sys.modules["skimage.color"] = stand_in
    try:
        import skimage.feature._cascade as module
    except ImportError:  # a scikit-image whose cascade needs more of skimage.color: the whole import
        module = None
    finally:
        if before is None:
            sys.modules.pop("skimage.color", None)
        else:
            sys.modules["skimage.color"] = before
        if getattr(skimage, "color", None) is stand_in:
            del skimage.color
    if module is None:
        from skimage.feature import Cascade

        return Cascade
    return module.Cascade


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
    has reached into the frame strip (:func:`reach_frame`).
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
    is the picture's edge, not the object's). A part that :func:`reach_frame`
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


def _near_frame_strip(mask: np.ndarray) -> bool:
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
