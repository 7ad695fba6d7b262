"""The cues that tell a photo's subject from its background: colour edges, texture, focus.

Measurements only; :mod:`img2logo.features.photo.subject` decides with them. Each works on a
:class:`~img2logo.images.loading.LoadedImage` (or its arrays) and a candidate mask:

* :func:`outline_contrast`, :func:`texture_lab`, :func:`outline_normals`:
  how sharply a mask's outline separates colours (across it) against the
  texture (along it), what it compares given a texture, the outline's normals;
* :func:`texture_map`, :func:`texture_colour_image`, :func:`texture_step`:
  the local energy of fine detail, a feature image for GrabCut that carries
  it beside CIELAB, and how much a mask's texture differs from that around it;
* :class:`FocusSeeds`, :func:`fine_detail`, :func:`focus_seeds`,
  :func:`focus_step`: depth of field (a close-up in focus in front of a
  blurred background), GrabCut's seeds from it, and the focus step across an
  outline;
* :func:`thin_parts`: the thin parts of the object (a tail, a tripod's
  legs) that leave a candidate mask and that GrabCut and the smoothing drop;
* :func:`clean_mask`, :func:`largest_part`, :func:`fill_small_holes`: a
  candidate mask's cleaning (its largest piece, GrabCut's specks filled, smoothed);
  :func:`mask_box`: the box on which a mask's distance transforms are exact;
* :func:`working_copy`, :func:`work_scale`, :func:`frame_box`,
  :func:`frame_strip`: the small copy GrabCut and the cues work on, and the
  strip along the image frame that is taken as background;
* :func:`lightness`: CIELAB's L*, to the bit, without importing ``skimage.color``
  (scipy.ndimage's filters, likewise without importing it, are in :mod:`img2logo.images.ndimage`).

Arrays are indexed (row, column); a box is (x, y, w, h) in px.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..._compat import median
from ..._validation import readonly
from ...constants import LUMA_WEIGHTS
from ...images.loading import LoadedImage
from ...images.ndimage import distance, erode, gaussian, label
from ..constants import (
    FOCUS_BLURRED,
    FOCUS_DETAIL_SIGMA,
    FOCUS_MIN_BLURRED_FRAME,
    FOCUS_MIN_SHARP_AREA,
    FOCUS_MIN_SHARP_FRAME,
    FOCUS_MIN_SOFT,
    FOCUS_SHARP,
    FOCUS_SHARP_CORE,
    FOCUS_SOFT_SIGMAS,
    FOCUS_SOFT_WINDOW,
    FOCUS_STEP,
    FOCUS_WINDOW,
    SUBJECT_CONTRAST_STEP,
    SUBJECT_FRAME_INSET,
    SUBJECT_MAX_HOLE,
    SUBJECT_MIN_CONTRAST,
    SUBJECT_SMOOTH_SIGMA,
    SUBJECT_TEXTURE_FLOOR,
    SUBJECT_TEXTURE_WEIGHT,
    SUBJECT_THIN_MAX_CONTACT,
    SUBJECT_THIN_MIN_ELONGATION,
    SUBJECT_THIN_WINDOW,
    SUBJECT_WORK_SIDE,
)

#: sRGB's linear RGB to CIE XYZ (D65), as scikit-image's ``skimage.color.colorconv.xyz_from_rgb``.
_XYZ_FROM_RGB = np.array(
    [[0.412453, 0.357580, 0.180423], [0.212671, 0.715160, 0.072169], [0.019334, 0.119193, 0.950227]]
)


def outline_contrast(
    img: LoadedImage,
    mask: np.ndarray,
    step: float = SUBJECT_CONTRAST_STEP,
    texture: np.ndarray | None = None,
    where: np.ndarray | None = None,
    lab: np.ndarray | None = None,
) -> float:
    """How sharply a mask's outline separates colours (and textures): across over along, unit-free.

    At every outline pixel, the CIELAB difference between the points ``step``
    px inside and outside along the outline's normal (across), and the larger of
    the differences between the points ``step`` px either way along the
    outline, inside and outside (along: the texture). Returns median(across) /
    median(along). An object's outline follows an edge (several times the
    texture); a cut through fur or gravel does not (about 2). Given ``where``
    (H, W) bool, only the outline's pixels in it count (one section of it);
    0 if there are none. ``lab`` (H, W, C), if given, is the image compared,
    :func:`texture_lab` of ``texture`` computed once for several masks.
    """
    if not mask.any() or mask.all():
        return 0.0
    if lab is None:
        lab = img.smooth_lab if texture is None else texture_lab(img, texture)
    rows, cols, nx, ny = outline_normals(mask, where)
    if rows.size == 0:
        return 0.0
    h, w = mask.shape

    def at(dr: np.ndarray, dc: np.ndarray) -> np.ndarray:
        rr = np.clip(np.round(rows + dr).astype(np.int64), 0, h - 1)
        cc = np.clip(np.round(cols + dc).astype(np.int64), 0, w - 1)
        return lab[rr, cc]

    across = np.linalg.norm(at(step * ny, step * nx) - at(-step * ny, -step * nx), axis=1)
    along = np.zeros_like(across)
    for side in (1.0, -1.0):
        r0, c0 = side * step * ny, side * step * nx
        diff = at(r0 + step * nx, c0 - step * ny) - at(r0 - step * nx, c0 + step * ny)
        along = np.maximum(along, np.linalg.norm(diff, axis=1))
    return float(median(across) / (median(along) + 1e-9))


def texture_lab(img: LoadedImage, texture: np.ndarray) -> np.ndarray:
    """CIELAB averaged over the texture's window, and :func:`texture_map` ``texture``: (H, W, 4) float.

    What :func:`outline_contrast` compares given a texture: the grass's blades
    are no step, its mean colour is.
    """
    window = FOCUS_WINDOW / work_scale(img)
    return np.dstack([gaussian(img.smooth_lab, (window, window, 0)), texture])


def outline_normals(
    mask: np.ndarray, where: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A mask's outline pixels (in ``where``, if given) and their inward unit normals: rows, cols, nx, ny.

    The outline is the mask's pixels next to a pixel outside it; the normal is
    the gradient of the signed distance to it, smoothed by a Gaussian of 2 px
    (x = column, y = row direction).
    """
    # Only the mask's box and a margin past the smoothing's reach (8 px) and the gradient's
    # (1 px) are needed; the distances there are those of the whole image (see mask_box).
    if not mask.any():
        empty = np.zeros(0, np.int64)
        return empty, empty, empty.astype(float), empty.astype(float)
    box = mask_box(mask, 12)
    mask = mask[box]
    signed = distance(mask) - distance(~mask)
    gy, gx = np.gradient(gaussian(signed, 2.0))
    edge = mask & ~erode(mask)
    rows, cols = np.nonzero(edge if where is None else edge & where[box])
    norm = np.hypot(gx[rows, cols], gy[rows, cols]) + 1e-12
    return rows + box[0].start, cols + box[1].start, gx[rows, cols] / norm, gy[rows, cols] / norm


def mask_box(mask: np.ndarray, margin: int) -> tuple[slice, slice]:
    """The bounding box of a non-empty mask (H, W) bool grown by ``margin`` px, clipped to the image: (rows, cols).

    On this box, the distance transforms of ``mask`` and of ``~mask`` equal
    the whole image's: every mask pixel is in it, and the pixel nearest to an
    inside one outside the mask is too (projecting a pixel beyond the box onto
    the box's 1 px ring brings it nearer and keeps it outside the mask), for
    any ``margin`` >= 1. Work on the box costs its area instead of the image's.
    """
    rows = np.flatnonzero(mask.any(axis=1))
    cols = np.flatnonzero(mask.any(axis=0))
    h, w = mask.shape
    return (
        slice(max(0, int(rows[0]) - margin), min(h, int(rows[-1]) + margin + 1)),
        slice(max(0, int(cols[0]) - margin), min(w, int(cols[-1]) + margin + 1)),
    )


def texture_step(img: LoadedImage, texture: np.ndarray, mask: np.ndarray) -> float:
    """How much a mask's texture differs from that around it all along its outline, decades of fine-detail energy.

    At every outline pixel (those within four texture windows, ``FOCUS_WINDOW``
    working px, of the image frame left out), the difference of
    :func:`texture_map` ``texture`` (H, W) three windows inside and three
    outside along the outline's normal, where the window no longer straddles
    the outline; returns the absolute median of these differences. An object
    of another texture than its background (a smooth body on grass) gives most
    of a decade or more; a cut through one texture about 0. The median over
    the outline asks the step of most of it: a cut through smooth sky that
    meets textured towers on its sides only (the rocket of
    ``skimage.data.rocket``) is no texture edge (0.2-0.3), although the
    medians of a band inside and a ring outside it differ by 0.6 decades.
    """
    if not mask.any() or mask.all():
        return 0.0
    window = FOCUS_WINDOW / work_scale(img)
    rows, cols, nx, ny = outline_normals(mask)
    h, w = mask.shape
    far = 4.0 * window
    keep = (rows > far) & (rows < h - 1 - far) & (cols > far) & (cols < w - 1 - far)
    if not keep.any():
        return 0.0
    rows, cols, nx, ny = rows[keep], cols[keep], nx[keep], ny[keep]

    def at(d: float) -> np.ndarray:
        rr = np.clip(np.round(rows + d * ny).astype(np.int64), 0, h - 1)
        cc = np.clip(np.round(cols + d * nx).astype(np.int64), 0, w - 1)
        return texture[rr, cc]

    return abs(float(median(at(3.0 * window) - at(-3.0 * window)))) / SUBJECT_TEXTURE_WEIGHT


def working_copy(img: LoadedImage) -> tuple[np.ndarray, float]:
    """The photo at the working scale (longer side ``SUBJECT_WORK_SIDE`` px at most): RGB (h, w, 3) float32, scale."""
    import cv2

    h, w = img.height, img.width
    scale = work_scale(img)
    sw, sh = max(8, round(w * scale)), max(8, round(h * scale))
    return cv2.resize(img.rgb.astype(np.float32), (sw, sh), interpolation=cv2.INTER_AREA), scale


def work_scale(img: LoadedImage) -> float:
    """The working copy's size over the photo's: its longer side is ``SUBJECT_WORK_SIDE`` px at most."""
    return min(1.0, SUBJECT_WORK_SIDE / max(img.height, img.width))


def frame_box(shape: tuple[int, int]) -> tuple[int, int, int, int]:
    """The box (x, y, width, height) inside the frame strip of an (h, w) image, px."""
    sh, sw = shape
    x0, y0 = round(SUBJECT_FRAME_INSET * sw), round(SUBJECT_FRAME_INSET * sh)
    return x0, y0, sw - 2 * x0, sh - 2 * y0


def frame_strip(shape: tuple[int, int]) -> np.ndarray:
    """The strip of ``SUBJECT_FRAME_INSET`` of each side along the frame, (h, w) bool."""
    x0, y0, bw, bh = frame_box(shape)
    strip = np.ones(shape, bool)
    strip[y0 : y0 + bh, x0 : x0 + bw] = False
    return strip


@dataclass(frozen=True, eq=False)
class FocusSeeds:
    """Where a photo is in focus and where it is blurred, at GrabCut's working scale.

    Attributes
    ----------
    focus : ndarray of float, shape (h, w)
        Fine detail (:func:`fine_detail`) over its 90th percentile over the
        image, unit-free: about 1 in the sharpest parts, under
        ``FOCUS_BLURRED`` where the image is out of focus (or flat).
    label : ndarray of uint8, shape (h, w)
        GrabCut's start labels: background where the frame is blurred,
        probably background where the inside is blurred, object in the cores
        of the sharp parts, probably object elsewhere.
    """

    focus: np.ndarray
    label: np.ndarray


def fine_detail(gray: np.ndarray) -> np.ndarray:
    """Local energy of the finest detail of a gray image, (H, W) float, gray units.

    The RMS, over a Gaussian window of ``FOCUS_WINDOW`` px, of the image minus
    its Gaussian blur of ``FOCUS_DETAIL_SIGMA`` px: texture and edges in focus
    give much, a defocused (or flat) part next to nothing, whatever its colour.
    """
    g = np.asarray(gray, dtype=np.float64)
    hf = g - gaussian(g, FOCUS_DETAIL_SIGMA)
    return np.sqrt(gaussian(hf * hf, FOCUS_WINDOW))


def focus_seeds(img: LoadedImage) -> FocusSeeds | None:
    """GrabCut's seeds from depth of field, or None when the photo shows none.

    A photo whose subject is in focus in front of a blurred background (a
    close-up: it may fill most of the frame and run off it) has two kinds of
    frame: blurred where the background shows, sharp where the subject runs
    off the picture. Then only the blurred parts of the frame are background
    seeds, and the cores of the sharp parts (the sharp map eroded by
    ``FOCUS_SHARP_CORE`` px: texture in focus, not a lone edge) object seeds.
    Used only when the frame shows both (at least ``FOCUS_MIN_BLURRED_FRAME``
    of the frame strip blurred, at least ``FOCUS_MIN_SHARP_FRAME`` in focus),
    the blurred part of the frame is soft rather than flat (the median energy
    of the band between Gaussians of ``FOCUS_SOFT_SIGMAS`` px there, over the
    same 90th percentile, at least ``FOCUS_MIN_SOFT``: a defocused background
    keeps its shapes, a clear sky or a plain wall has none and is no evidence
    of depth of field) and the sharp cores cover at least
    ``FOCUS_MIN_SHARP_AREA`` of the image. Otherwise None, and GrabCut starts
    from the whole frame: a subject away from the frame (the photo-likes, a
    flower in the middle of a blurred garden) is found that way.
    """
    import cv2

    small, _ = working_copy(img)
    gray = small @ np.array(LUMA_WEIGHTS, np.float32)
    detail = fine_detail(gray)
    top = float(np.percentile(detail, 90))
    if top <= 1e-6:
        return None
    focus = detail / top
    strip = frame_strip(focus.shape)
    blurred = focus < FOCUS_BLURRED
    in_focus = focus > FOCUS_SHARP
    if blurred[strip].mean() < FOCUS_MIN_BLURRED_FRAME or in_focus[strip].mean() < FOCUS_MIN_SHARP_FRAME:
        return None
    band = gaussian(gray, FOCUS_SOFT_SIGMAS[0]) - gaussian(gray, FOCUS_SOFT_SIGMAS[1])
    soft = np.sqrt(gaussian(band * band, FOCUS_SOFT_WINDOW)) / top
    if median(soft[strip & blurred]) < FOCUS_MIN_SOFT:
        return None
    sharp = erode(in_focus, FOCUS_SHARP_CORE)
    if sharp.mean() < FOCUS_MIN_SHARP_AREA:
        return None
    label = np.full(focus.shape, cv2.GC_PR_FGD, np.uint8)
    label[blurred] = cv2.GC_PR_BGD
    label[sharp] = cv2.GC_FGD
    label[strip & blurred] = cv2.GC_BGD
    return FocusSeeds(readonly(focus), readonly(label))


def focus_step(seeds: FocusSeeds, mask: np.ndarray) -> float:
    """How much sharper a mask is just inside its outline than just outside, unit-free.

    The median focus (:attr:`FocusSeeds.focus`) ``FOCUS_STEP`` working px
    inside the outline over the median ``FOCUS_STEP`` px outside, at the
    working scale; the outline's parts on the image frame are left out. A
    subject in focus against a blurred background gives several; a cut
    through a scene in focus about 1.
    """
    import cv2

    sh, sw = seeds.focus.shape
    small = cv2.resize(mask.astype(np.float32), (sw, sh), interpolation=cv2.INTER_AREA) >= 0.5
    if not small.any() or small.all():
        return 0.0
    inside = distance(small)
    outside = distance(~small)
    band = (inside > FOCUS_STEP - 1) & (inside <= FOCUS_STEP)
    ring = (outside > FOCUS_STEP - 1) & (outside <= FOCUS_STEP)
    away = erode(np.ones((sh, sw), bool), FOCUS_STEP + 2)
    band, ring = band & away, ring & away
    if not band.any() or not ring.any():
        return 0.0
    return float(median(seeds.focus[band]) / max(float(median(seeds.focus[ring])), 1e-6))


def texture_map(rgb: np.ndarray, scale: float = 1.0) -> np.ndarray:
    """The texture of a photo in CIELAB-like units, (H, W) float.

    ``SUBJECT_TEXTURE_WEIGHT * log10(SUBJECT_TEXTURE_FLOOR + e)``, with ``e``
    the local energy of the finest detail of L* (as :func:`fine_detail`, its
    sigmas taken at the working scale: ``scale`` is the working copy's size
    over this image's), so one decade of texture energy (smooth skin against
    grass, a flat body against gravel) weighs as a clear colour step.
    """
    light = lightness(rgb)
    k = 1.0 / scale  # this image's px per working px
    detail = light - gaussian(light, FOCUS_DETAIL_SIGMA * k)
    energy = np.sqrt(gaussian(detail * detail, FOCUS_WINDOW * k))
    return SUBJECT_TEXTURE_WEIGHT * np.log10(SUBJECT_TEXTURE_FLOOR + energy)


def lightness(rgb: np.ndarray) -> np.ndarray:
    """CIELAB's L* of sRGB ``rgb`` (H, W, 3), clipped to [0, 1]: (H, W) float64, to the bit
    ``skimage.color.rgb2lab(rgb)[..., 0]`` (D65), without its a* and b* (half its time).
    """
    lin = np.clip(np.asarray(rgb, dtype=np.float64), 0.0, 1.0)
    curve = lin > 0.04045
    lin[curve] = np.power((lin[curve] + 0.055) / 1.055, 2.4)
    lin[~curve] /= 12.92
    y = (lin @ _XYZ_FROM_RGB.T)[..., 1]  # the reference white's Y is 1
    return np.where(y > 0.008856, 116.0 * np.cbrt(y), 116.0 * (7.787 * y + 16.0 / 116.0)) - 16.0


def texture_colour_image(lab: np.ndarray, texture: np.ndarray) -> np.ndarray:
    """Colour and texture in three 8-bit channels, for GrabCut: (h, w, 3) uint8.

    The four features at every pixel, CIELAB ``lab`` (h, w, 3) and
    :func:`texture_map` ``texture`` (h, w), are projected on their three
    principal axes (over the image), each stretched to 0-255 between its 0.5th
    and 99.5th percentiles (GrabCut takes three 8-bit channels). Deterministic.
    """
    h, w = lab.shape[:2]
    features = np.dstack([lab, texture]).reshape(-1, 4)
    features = features - features.mean(axis=0)
    _, _, axes = np.linalg.svd(features[:: max(1, features.shape[0] // 20000)], full_matrices=False)
    # A row of the image at a time (numpy's stacked matmul): one (H*W, 4) product is large enough
    # for OpenBLAS to share it out to its threads, which then spin idle for a while after it
    # (about 0.1 s of CPU time on two cores, four times the work); the products are the same.
    proj = (features.reshape(h, w, 4) @ axes[:3].T).reshape(-1, 3)
    lo, hi = np.percentile(proj, (0.5, 99.5), axis=0)
    proj = np.clip((proj - lo) / np.maximum(hi - lo, 1e-9), 0.0, 1.0)
    return np.ascontiguousarray((proj * 255).round().astype(np.uint8).reshape(h, w, 3))


def largest_part(mask: np.ndarray) -> np.ndarray:
    """The largest 8-connected piece of ``mask``."""
    lab, n = label(mask, eight=True)
    if n <= 1:
        return mask.copy()
    sizes = np.bincount(lab.ravel())[1:]
    return lab == 1 + int(np.argmax(sizes))


def clean_mask(mask: np.ndarray) -> np.ndarray:
    """Largest piece, holes filled, smoothed by a Gaussian of ``SUBJECT_SMOOTH_SIGMA`` px, (H, W) bool."""
    if not mask.any():
        return mask
    mask = fill_small_holes(largest_part(mask))
    smooth = gaussian(mask.astype(np.float32), SUBJECT_SMOOTH_SIGMA) >= 0.5
    smooth = largest_part(smooth)
    return fill_small_holes(smooth) if smooth.any() else mask


def fill_small_holes(mask: np.ndarray) -> np.ndarray:
    """Fill the holes of ``mask`` smaller than ``SUBJECT_MAX_HOLE`` of its area (GrabCut's specks).

    What ``skimage.morphology.remove_small_holes(mask, max_size=...)`` does (its
    4-connected parts of ``~mask`` of at most that many px filled), by OpenCV's
    component labelling: importing ``skimage.morphology`` costs about 0.1 s of
    CPU a run.
    """
    import cv2

    max_size = max(1, int(SUBJECT_MAX_HOLE * mask.sum()))
    _, parts, stats, _ = cv2.connectedComponentsWithStats((~mask).astype(np.uint8), connectivity=4)
    small = stats[:, cv2.CC_STAT_AREA] <= max_size
    small[0] = False  # label 0: the mask's own pixels
    return mask | small[parts]


def thin_parts(img: LoadedImage, mask: np.ndarray) -> np.ndarray:
    """The thin parts of the object that leave ``mask``: (H, W) bool, outside it.

    The logo draws the subject whole (paper Fig. 1, 10). GrabCut on the
    working copy and :func:`clean_mask`'s smoothing drop a part a few px wide
    (a tail, a tripod's legs); here it is found at full size by what makes it
    a part of its own:

    * it is thin: a median filter of CIELAB over a square window of
      ``SUBJECT_THIN_WINDOW`` of the longer side takes it away (it covers under
      half the window; a step edge, with more than half the window on either
      side, stays), and the colour differs from that median by
      ``SUBJECT_MIN_CONTRAST`` times the local level of such differences (the
      median over a window twice as wide: grass, gravel, grain);
    * it leaves the mask: a connected piece of those pixels further than 2 px
      from the mask (nearer, the outline's own blurred rim) that comes within
      3 px of it over at most ``SUBJECT_THIN_MAX_CONTACT`` of its length (its
      skeleton's), and is at least ``SUBJECT_THIN_MIN_ELONGATION`` times
      longer than wide (a rim along the outline, a shadow's edge, a blob of
      texture are not), and it ends in the picture (one that runs off it, a
      stalk, a pole, a wire, may pass behind the object);
    * it stands apart from what is around it: its median CIELAB distance from
      the median colour around it (within half a window, the mask and other
      thin pixels left out) at least ``SUBJECT_MIN_CONTRAST`` times that
      surround's own spread (median distance from its median), the same ratio
      as an outline's (:func:`outline_contrast`): a strip in clutter (shelves,
      towers) is no further from its surround than the surround is from itself;
    * it is no pattern of the background's: the pixels of the thin strokes
      that do not leave the mask (as elongated as a part must be) closer to
      its median colour than half that step are fewer than its own (brick
      mortar, grass blades, poles repeat).
    """
    import cv2

    from ...images.ndimage import skeletonize

    h, w = mask.shape
    found = np.zeros((h, w), bool)
    if not mask.any() or mask.all():
        return found
    mask = np.ascontiguousarray(mask, dtype=bool)
    rgb8 = np.clip(np.round(np.asarray(img.rgb, np.float32) * 255.0), 0, 255).astype(np.uint8)
    lab8 = cv2.cvtColor(np.ascontiguousarray(rgb8), cv2.COLOR_RGB2LAB)  # L* x 255/100, a* and b* + 128
    window = max(3, round(SUBJECT_THIN_WINDOW * max(h, w))) | 1
    scale = np.array([100.0 / 255.0, 1.0, 1.0], np.float32)
    lab = lab8.astype(np.float32) * scale
    apart = np.linalg.norm(lab - cv2.medianBlur(lab8, window).astype(np.float32) * scale, axis=2)
    levels = np.clip(np.round(apart * 4.0), 0, 255).astype(np.uint8)  # quarter dE steps
    level = cv2.medianBlur(levels, 2 * window + 1).astype(np.float32) / 4.0 + 0.25
    rim = cv2.dilate(mask.view(np.uint8), cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (5, 5))).astype(bool)
    near = cv2.dilate(rim.view(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)  # the next px out
    thin = (apart > SUBJECT_MIN_CONTRAST * level) & ~rim  # the outline's own blurred rim (2 px) left out
    count, parts, stats, _ = cv2.connectedComponentsWithStats(thin.view(np.uint8), connectivity=8)
    reach = window // 2
    around_disc = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * reach + 1, 2 * reach + 1))
    leaving = np.unique(parts[near & thin])
    lengths = np.bincount(parts[skeletonize(thin)], minlength=count)
    strokes = lengths**2 >= SUBJECT_THIN_MIN_ELONGATION * stats[:, cv2.CC_STAT_AREA]  # length / width
    strokes[leaving] = False
    elsewhere = lab[strokes[parts] & thin]  # the background's own strokes (not a blot's rounded corner)
    for i in leaving:
        x, y, bw, bh, area = stats[i]
        if i == 0 or area < window or x <= 1 or y <= 1 or x + bw >= w - 1 or y + bh >= h - 1:
            continue  # too small for a stroke; or it runs off the picture (a stalk, a pole, a wire behind)
        box = (slice(max(0, y - reach), min(h, y + bh + reach)), slice(max(0, x - reach), min(w, x + bw + reach)))
        part = parts[box] == i
        length = int(lengths[i])
        contact = int((part & near[box]).sum())
        if contact > SUBJECT_THIN_MAX_CONTACT * length or length < SUBJECT_THIN_MIN_ELONGATION * area / max(length, 1):
            continue
        around = cv2.dilate(part.view(np.uint8), around_disc).astype(bool) & ~thin[box] & ~mask[box]
        if not around.any():
            continue
        ground = np.median(lab[box][around], axis=0)
        spread = float(median(np.linalg.norm(lab[box][around] - ground, axis=1)))
        step = float(median(np.linalg.norm(lab[box][part] - ground, axis=1)))
        if step < SUBJECT_MIN_CONTRAST * max(spread, SUBJECT_TEXTURE_FLOOR):  # the floor: photo noise
            continue
        own = np.median(lab[box][part], axis=0)
        alike = int((np.linalg.norm(elsewhere - own, axis=1) < step / 2).sum()) if elsewhere.size else 0
        if alike < area:  # not a pattern of the background's (mortar, poles, blades): the object's
            found[box] |= part
    return found
