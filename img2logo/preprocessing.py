"""Preprocessing (paper Sec. 4): load an image and extract its feature lines.

Three kinds of input, as in the paper:

* **line drawing**: binarize, drop small specks, thin to a 1-px skeleton, prune
  short spurs;
* **clip art**: split the image into flat-colour regions (a quantized palette,
  connected regions, small regions merged into a neighbour); the boundaries
  between regions, the background included, are the feature lines, and where
  three or more regions meet is a junction;
* **real photo**: a flow-based line drawing after Kang et al. [KD09]: an edge
  tangent flow from the smoothed structure tensor, a difference of Gaussians
  across the flow, smoothed along it, binarized and thinned; optionally only on
  the foreground object (a mask, or OpenCV's GrabCut).

Arrays are indexed (row, column); points are (x, y) = (column + 0.5, row + 0.5)
in px, x to the right, y downwards (``contract/README.md``).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import _skeleton
from ._validation import check_choice, check_positive, readonly
from .constants import (
    BILATERAL_DIAMETER,
    BILATERAL_SIGMA_COLOR,
    BLANK_IMAGE_RANGE,
    CLIPART_COLOR_DISTANCE,
    CLIPART_MIN_REGION_AREA,
    ETF_SIGMA,
    FDOG_RHO,
    FDOG_SIGMA_C,
    FDOG_SIGMA_M,
    FDOG_TAU,
    JUNCTION_MERGE_DISTANCE,
    MAX_IMAGE_SIDE,
    MIN_IMAGE_SIDE,
    MIN_SPECK_AREA,
    PHOTO_MIN_LINE_LENGTH,
    SPUR_LENGTH,
)
from .errors import ImageNotFoundError, InvalidImageError, InvalidParameterError

KINDS = ("photo", "clipart", "drawing")


class DownscaleWarning(UserWarning):
    """An input image larger than the size bound was downscaled."""


@dataclass(frozen=True, eq=False)
class LoadedImage:
    """A normalized input image.

    Attributes
    ----------
    rgb : ndarray, shape (H, W, 3), float64 in [0, 1]
        Colour, with transparent pixels composited over white.
    alpha : ndarray, shape (H, W), float64 in [0, 1]
        Opacity; all ones for an image without an alpha channel.
    has_alpha : bool
        Whether the input had an alpha channel.
    scale : float
        Factor applied to the input's size (1.0 unless it was downscaled).
    source : str
        The path it was read from, or ``"<array>"``.
    """

    rgb: np.ndarray
    alpha: np.ndarray
    has_alpha: bool = False
    scale: float = 1.0
    source: str = "<array>"

    @property
    def height(self) -> int:
        return int(self.rgb.shape[0])

    @property
    def width(self) -> int:
        return int(self.rgb.shape[1])

    @property
    def foreground(self) -> np.ndarray:
        """Opaque pixels, (H, W) bool: alpha >= 0.5."""
        return self.alpha >= 0.5

    @property
    def gray(self) -> np.ndarray:
        """Luminance (Rec. 601), (H, W) float64 in [0, 1]."""
        return self.rgb @ np.array([0.299, 0.587, 0.114])


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
        Why this kind: ``"given"`` or what :func:`detect_kind` measured.
    regions : ndarray of int, shape (H, W), or None
        For clip art, the flat-colour region label of each pixel (0 = background).
    """

    lines: np.ndarray
    kind: str
    reason: str
    regions: np.ndarray | None = None

    @property
    def shape(self) -> tuple[int, int]:
        return (int(self.lines.shape[0]), int(self.lines.shape[1]))


# --------------------------------------------------------------------------- loading
def load_image(source: object, *, max_side: int = MAX_IMAGE_SIDE) -> LoadedImage:
    """Read and normalize an input image.

    Parameters
    ----------
    source : str, Path, ndarray or LoadedImage
        A file PNG, JPEG, TIFF, BMP, WebP, ... or an array of shape (H, W),
        (H, W, 1), (H, W, 2) (gray + alpha), (H, W, 3) (RGB) or (H, W, 4) (RGBA),
        of dtype uint8, uint16, bool or float in [0, 1]. The input is never
        modified.
    max_side : int, optional
        An image whose longer side exceeds this is downscaled to it (area
        interpolation) with a :class:`DownscaleWarning`.

    Returns
    -------
    LoadedImage

    Raises
    ------
    ImageNotFoundError
        The path does not exist or is a directory.
    InvalidImageError
        Not an image, empty, fewer than 16 px on a side, or blank (one colour).
    """
    if isinstance(source, LoadedImage):
        return source
    if isinstance(source, (str, Path)):
        arr, name, bgr = _read_file(Path(source)), str(source), True
    elif isinstance(source, np.ndarray):
        arr, name, bgr = source, "<array>", False
    else:
        raise InvalidImageError(f"image must be a file path or a numpy array, got {type(source).__name__}")
    rgb, alpha, has_alpha = _normalize(arr, name, bgr=bgr)
    h, w = alpha.shape
    if min(h, w) < MIN_IMAGE_SIDE:
        raise InvalidImageError(f"{name}: image is {w}x{h} px; at least {MIN_IMAGE_SIDE} px on each side is needed")
    scale = 1.0
    if max(h, w) > max_side:
        import cv2

        scale = max_side / max(h, w)
        size = (max(1, round(w * scale)), max(1, round(h * scale)))
        rgb = np.clip(cv2.resize(rgb, size, interpolation=cv2.INTER_AREA), 0.0, 1.0)
        alpha = np.clip(cv2.resize(alpha, size, interpolation=cv2.INTER_AREA), 0.0, 1.0)
        warnings.warn(
            f"{name}: image is {w}x{h} px, larger than {max_side} px; downscaled to {size[0]}x{size[1]} px",
            DownscaleWarning,
            stacklevel=2,
        )
    if np.ptp(rgb) < BLANK_IMAGE_RANGE and np.ptp(alpha) < BLANK_IMAGE_RANGE:
        raise InvalidImageError(f"{name}: image is blank (every pixel has the same colour); nothing to trace")
    return LoadedImage(readonly(rgb), readonly(alpha), has_alpha, scale, name)


def load_mask(source: object, shape: tuple[int, int] | None = None) -> np.ndarray:
    """Read a binary mask (a lock mask, a foreground): white (>= 50 % gray) is True.

    Parameters
    ----------
    source : str, Path or ndarray
        An image file or an array, as for :func:`load_image`; unlike an input
        image, a mask may be all one colour.
    shape : (H, W), optional
        The shape the mask must have (the input image's), checked if given.

    Returns
    -------
    ndarray of bool, shape (H, W)
    """
    if isinstance(source, (str, Path)):
        arr, name, bgr = _read_file(Path(source)), str(source), True
    else:
        arr, name, bgr = np.asarray(source), "<array>", False
    if arr.dtype == bool and arr.ndim == 2:
        mask = arr.copy()
    else:
        rgb, alpha, _ = _normalize(arr, name, bgr=bgr)
        mask = (rgb @ np.array([0.299, 0.587, 0.114]) >= 0.5) & (alpha >= 0.5)
    if shape is not None and mask.shape != tuple(shape):
        raise InvalidParameterError(f"{name}: mask must have the image's shape {tuple(shape)}, got {mask.shape}")
    return mask


def _read_file(path: Path) -> np.ndarray:
    import cv2

    if not path.exists():
        raise ImageNotFoundError(f"image file not found: {path}")
    if not path.is_file():
        raise ImageNotFoundError(f"not an image file (a directory?): {path}")
    data = np.fromfile(path, dtype=np.uint8)  # imdecode: unicode-safe, unlike imread
    if data.size == 0:
        raise InvalidImageError(f"{path}: file is empty")
    arr = cv2.imdecode(data, cv2.IMREAD_UNCHANGED)
    if arr is None or arr.size == 0:
        raise InvalidImageError(f"{path}: not a readable image (expected PNG, JPEG, TIFF, BMP, WebP, ...)")
    return arr


def _normalize(arr: np.ndarray, name: str, *, bgr: bool) -> tuple[np.ndarray, np.ndarray, bool]:
    """Array -> (rgb (H, W, 3) float64 over white, alpha (H, W), had alpha)."""
    if arr.ndim == 2:
        arr = arr[:, :, None]
    if arr.ndim != 3 or arr.shape[2] not in (1, 2, 3, 4):
        raise InvalidImageError(
            f"{name}: image must have shape (H, W) or (H, W, C) with C in 1..4, got {tuple(np.shape(arr))}"
        )
    if arr.shape[0] == 0 or arr.shape[1] == 0:
        raise InvalidImageError(f"{name}: image is empty (shape {arr.shape})")
    if arr.dtype == bool:
        val = arr.astype(np.float64)
    elif arr.dtype == np.uint8:
        val = arr / 255.0
    elif arr.dtype == np.uint16:
        val = arr / 65535.0
    elif np.issubdtype(arr.dtype, np.floating):
        val = arr.astype(np.float64)
        if not np.all(np.isfinite(val)):
            raise InvalidImageError(f"{name}: image contains NaN or infinite values")
        if val.min() < 0.0 or val.max() > 1.0:
            raise InvalidImageError(
                f"{name}: float images must have values in [0, 1], got [{val.min():g}, {val.max():g}]"
            )
    else:
        raise InvalidImageError(f"{name}: unsupported dtype {arr.dtype} (use uint8, uint16, bool or float in [0, 1])")
    channels = val.shape[2]
    has_alpha = channels in (2, 4)
    alpha = val[:, :, -1].copy() if has_alpha else np.ones(val.shape[:2])
    colour = val[:, :, : channels - 1] if has_alpha else val
    if colour.shape[2] == 1:
        colour = np.repeat(colour, 3, axis=2)
    elif bgr:
        colour = colour[:, :, ::-1]
    rgb = colour * alpha[:, :, None] + (1.0 - alpha[:, :, None])
    return np.ascontiguousarray(rgb), alpha, has_alpha


# --------------------------------------------------------------------------- kinds
def detect_kind(image: LoadedImage) -> tuple[str, str]:
    """Guess the kind of an image: ``(kind, reason)``.

    A *line drawing* is nearly gray where it is drawn, mostly light, with thin
    dark strokes; a
    *clip art* has few flat colours (a handful of palette entries cover almost
    every pixel); anything else is a *photo*.
    """
    img = load_image(image)
    rgb = img.rgb
    sat = rgb.max(axis=2) - rgb.min(axis=2)
    gray = img.gray
    ink = gray < 0.5
    ink_fraction = float(ink.mean())
    quant = (np.round(rgb * 15).astype(np.int64) * np.array([256, 16, 1])).sum(axis=2)
    counts = np.sort(np.bincount(quant.ravel()))[::-1]
    coverage = float(counts[:12].sum() / quant.size)
    # Saturation of the drawn pixels only: a white canvas would make any clip art gray.
    drawn = (gray < 0.9) & img.foreground
    drawn_sat = float(np.median(sat[drawn])) if drawn.any() else 0.0
    looks_drawn = drawn_sat < 0.05 and 0.0 < ink_fraction < 0.35
    stroke = _median_stroke_width(ink) if looks_drawn else 0.0  # the costly test last
    if looks_drawn and stroke <= 0.05 * min(gray.shape):
        return "drawing", (
            f"nearly gray, {ink_fraction:.0%} dark pixels in strokes about {stroke:.0f} px wide: a line drawing"
        )
    if coverage > 0.9:
        return "clipart", f"12 flat colours cover {coverage:.0%} of the pixels: a clip art"
    return "photo", f"12 most common colours cover only {coverage:.0%} of the pixels: a photo"


def _median_stroke_width(ink: np.ndarray) -> float:
    from scipy import ndimage
    from skimage.morphology import skeletonize

    dist = ndimage.distance_transform_edt(ink)
    skel = skeletonize(ink)
    return float(2.0 * np.median(dist[skel])) if skel.any() else 0.0


# --------------------------------------------------------------------------- feature lines
def extract_feature_lines(
    image: object,
    kind: str = "auto",
    *,
    foreground: object = None,
    spur_length: float = SPUR_LENGTH,
    min_line_length: float | None = None,
) -> FeatureLines:
    """Extract the object's feature lines as a 1-px-wide map (paper Sec. 4).

    Parameters
    ----------
    image : path, ndarray or LoadedImage
        The input, read by :func:`load_image`.
    kind : {"auto", "photo", "clipart", "drawing"}
        The kind of input; ``"auto"`` chooses with :func:`detect_kind` and says
        why in the result's ``reason``.
    foreground : None, "grabcut" or ndarray of bool, shape (H, W), optional
        Photos only: keep the lines on the object. A boolean mask given by the
        user, or ``"grabcut"`` to segment it with OpenCV's GrabCut from a
        centred rectangle. An image with transparency uses its alpha by default.
    spur_length : float, optional
        Side spurs of the skeleton shorter than this are pruned, px.
    min_line_length : float, optional
        Isolated lines shorter than this are dropped, px (default:
        ``spur_length`` for drawings and clip art, a longer bound for photos,
        whose short lines are mostly texture).

    Returns
    -------
    FeatureLines
    """
    img = load_image(image)
    kind = check_choice(kind, "kind", ("auto", *KINDS))
    spur_length = check_positive(spur_length, "spur_length", allow_zero=True)
    if kind == "auto":
        kind, reason = detect_kind(img)
    else:
        reason = "given"
    regions = None
    if kind == "drawing":
        raw = _drawing_lines(img)
        min_len = spur_length if min_line_length is None else min_line_length
    elif kind == "clipart":
        regions = _clipart_regions(img)
        raw = _region_boundaries(regions)
        min_len = spur_length if min_line_length is None else min_line_length
    else:
        raw = _photo_lines(img, _foreground_mask(img, foreground))
        min_len = PHOTO_MIN_LINE_LENGTH if min_line_length is None else min_line_length
    min_len = check_positive(min_len, "min_line_length", allow_zero=True)
    lines = _clean_skeleton(raw, spur_length=spur_length, min_length=min_len)
    return FeatureLines(readonly(lines), kind, reason, None if regions is None else readonly(regions))


def _clean_skeleton(mask: np.ndarray, *, spur_length: float, min_length: float) -> np.ndarray:
    """Thin ``mask`` to 1 px and prune spurs, specks and tiny loops."""
    from skimage.morphology import skeletonize

    skel = skeletonize(mask)
    graph = _skeleton.trace(skel)
    _skeleton.prune(graph, spur_length=spur_length, min_length=min_length, junction_merge=JUNCTION_MERGE_DISTANCE)
    return _skeleton.rasterize(graph, skel.shape)


def _drawing_lines(img: LoadedImage) -> np.ndarray:
    """Ink of a line drawing: Otsu threshold, specks removed, holes of 1-2 px filled."""
    from scipy import ndimage
    from skimage.filters import threshold_otsu
    from skimage.morphology import remove_small_holes, remove_small_objects

    gray = ndimage.gaussian_filter(img.gray, 1.0)  # smooths the stroke edges: fewer spurs
    if np.ptp(gray) < BLANK_IMAGE_RANGE:
        return np.zeros(gray.shape, dtype=bool)
    ink = gray < threshold_otsu(gray)
    if ink.mean() > 0.5:  # light strokes on a dark ground
        ink = ~ink
    ink = remove_small_objects(ink, max_size=MIN_SPECK_AREA - 1)
    return remove_small_holes(ink, max_size=MIN_SPECK_AREA // 4)


def _clipart_regions(img: LoadedImage) -> np.ndarray:
    """Flat-colour regions of a clip art, (H, W) int labels, 0 = background.

    A palette is built from the most frequent colours (quantized), merging
    entries closer than ``CLIPART_COLOR_DISTANCE`` in CIELAB; each pixel takes
    the entry nearest to its quantized colour; connected regions smaller than
    ``CLIPART_MIN_REGION_AREA`` (anti-aliased rims, specks) are merged into the
    neighbouring region they share the longest border with.
    """
    from skimage.color import rgb2lab
    from skimage.measure import label

    lab = rgb2lab(img.rgb)
    transparent = ~img.foreground
    # Quantize to 4 units of L*, a*, b* and pack into one integer key: a
    # bincount over keys is far faster than np.unique(axis=0) over rows.
    flat = lab.reshape(-1, 3)
    quant = np.clip(np.round(flat / 4.0).astype(np.int64) + np.array([0, 40, 40]), 0, 80)
    key = quant @ np.array([81 * 81, 81, 1])
    counts = np.bincount(key, minlength=81**3)
    sums = np.stack([np.bincount(key, weights=flat[:, c], minlength=81**3) for c in range(3)], axis=1)
    used = np.flatnonzero(counts)
    order = used[np.argsort(-counts[used], kind="stable")]
    palette: list[np.ndarray] = []
    for k in order:
        if counts[k] < CLIPART_MIN_REGION_AREA:
            break
        mean = sums[k] / counts[k]
        if all(np.linalg.norm(mean - p) >= CLIPART_COLOR_DISTANCE for p in palette):
            palette.append(mean)
    if not palette:
        palette = [lab.reshape(-1, 3).mean(axis=0)]
    # Each pixel takes the entry nearest to the mean colour of its quantized
    # cell: one lookup per distinct cell (a few thousand), not per pixel.
    pal = np.array(palette)
    means = sums[used] / counts[used, None]
    lut = np.zeros(81**3, dtype=np.int64)
    lut[used] = np.argmin(((means[:, None, :] - pal[None]) ** 2).sum(axis=2), axis=1)
    index = lut[key].reshape(lab.shape[:2])
    index[transparent] = -1
    regions = label(index, background=-2, connectivity=1)
    regions = _merge_small_regions(regions, CLIPART_MIN_REGION_AREA)
    # The background is the region covering most of the image border.
    border = np.concatenate([regions[0], regions[-1], regions[:, 0], regions[:, -1]])
    bg = np.bincount(border).argmax()
    out = regions.copy()
    out[regions == bg] = 0
    out[(regions != bg) & (regions == 0)] = bg  # label 0 was taken: swap
    return _relabel(out)


def _merge_small_regions(regions: np.ndarray, min_area: int) -> np.ndarray:
    """Merge regions smaller than ``min_area`` into their longest-bordering neighbour."""
    regions = regions.copy()
    for _ in range(8):  # a few passes: a merged sliver can enable the next
        areas = np.bincount(regions.ravel())
        small = np.flatnonzero((areas > 0) & (areas < min_area))
        if len(small) == 0:
            break
        pairs = []
        for a, b in ((regions[:, :-1], regions[:, 1:]), (regions[:-1], regions[1:])):
            diff = a != b
            pairs.append(np.column_stack([a[diff], b[diff]]))
            pairs.append(np.column_stack([b[diff], a[diff]]))
        edges = np.vstack(pairs)
        n = len(areas)
        border = np.bincount(edges[:, 0] * n + edges[:, 1], minlength=n * n).reshape(n, n)
        target = np.arange(n)
        for r in small[np.argsort(areas[small], kind="stable")]:
            row = border[r].astype(np.float64)
            row[small] = row[small] * 1e-3  # prefer merging into a large region
            if row.max() > 0:
                target[r] = int(np.argmax(row))
        for r in small:  # follow chains of merges to their end
            t = r
            for _ in range(n):
                if target[t] == t:
                    break
                t = target[t]
            target[r] = t
        regions = target[regions]
    return _relabel(regions)


def _relabel(regions: np.ndarray) -> np.ndarray:
    """Labels 0..n-1 in order of first appearance of the sorted unique values."""
    _, inv = np.unique(regions, return_inverse=True)
    return inv.reshape(regions.shape).astype(np.int64)


def _region_boundaries(regions: np.ndarray) -> np.ndarray:
    """Boundaries between regions as a thin map (thinned to 1 px by the caller)."""
    from skimage.segmentation import find_boundaries

    return find_boundaries(regions, connectivity=1, mode="inner") & _interior(regions.shape)


def _interior(shape: tuple[int, int]) -> np.ndarray:
    """Everything but the 1-px image frame, where a region edge is no feature."""
    out = np.zeros(shape, dtype=bool)
    out[1:-1, 1:-1] = True
    return out


def _foreground_mask(img: LoadedImage, foreground: object) -> np.ndarray | None:
    if foreground is None:
        return img.foreground if img.has_alpha else None
    if isinstance(foreground, str):
        check_choice(foreground, "foreground", ("grabcut",))
        return _grabcut(img)
    mask = np.asarray(foreground)
    if mask.shape != (img.height, img.width):
        raise InvalidParameterError(
            f"foreground mask must have the image's shape {(img.height, img.width)}, got {mask.shape}"
        )
    mask = mask.astype(bool)
    if not mask.any():
        raise InvalidParameterError("foreground mask is empty: no pixel is marked as the object")
    return mask


def _grabcut(img: LoadedImage) -> np.ndarray:
    """Foreground by OpenCV's GrabCut started from a rectangle inset by 5 % of each side."""
    import cv2

    h, w = img.height, img.width
    bgr = np.ascontiguousarray((img.rgb[:, :, ::-1] * 255).round().astype(np.uint8))
    mask = np.zeros((h, w), np.uint8)
    rect = (int(0.05 * w), int(0.05 * h), int(0.9 * w), int(0.9 * h))
    bgd, fgd = np.zeros((1, 65), np.float64), np.zeros((1, 65), np.float64)
    cv2.setRNGSeed(0)  # deterministic
    cv2.grabCut(bgr, mask, rect, bgd, fgd, 5, cv2.GC_INIT_WITH_RECT)
    return (mask == cv2.GC_FGD) | (mask == cv2.GC_PR_FGD)


def _photo_lines(img: LoadedImage, mask: np.ndarray | None) -> np.ndarray:
    """Flow-based difference of Gaussians [KD09], binarized, on ``mask`` if given.

    The gray image is first smoothed by a bilateral filter (KD09 smooth with a
    flow-based bilateral filter): fur, grain and texture fade, edges stay.
    """
    import cv2

    smooth = cv2.bilateralFilter(img.gray.astype(np.float32), BILATERAL_DIAMETER, BILATERAL_SIGMA_COLOR, 5.0)
    lines = flow_dog(smooth)
    if mask is not None:
        from scipy import ndimage

        # Keep the object's outline too: lines within a few px of the mask.
        lines &= ndimage.binary_dilation(mask, iterations=3)
    return lines


def edge_tangent_flow(gray: np.ndarray, sigma: float = ETF_SIGMA) -> np.ndarray:
    """Edge tangent flow: unit vectors along the edges, shape (H, W, 2) as (x, y).

    The eigenvector of the smoothed structure tensor with the smaller eigenvalue
    (the direction of least change), a standard stand-in for Kang's iterative
    ETF filter [KD09].
    """
    from skimage.feature import structure_tensor

    arr, arc, acc = structure_tensor(gray, sigma=sigma, order="rc")
    # Tensor in (x, y) = (col, row): [[acc, arc], [arc, arr]]; the minor
    # eigenvector's angle is half the orientation angle plus 90 degrees.
    theta = 0.5 * np.arctan2(2.0 * arc, acc - arr) + math.pi / 2.0
    return np.stack([np.cos(theta), np.sin(theta)], axis=-1)


def flow_dog(
    gray: np.ndarray,
    *,
    sigma_c: float = FDOG_SIGMA_C,
    sigma_m: float = FDOG_SIGMA_M,
    rho: float = FDOG_RHO,
    tau: float = FDOG_TAU,
) -> np.ndarray:
    """Flow-based difference of Gaussians [KD09]: a (H, W) bool line map.

    A 1-D DoG ``G_sc - rho G_1.6sc`` is taken across the edge tangent flow at
    every pixel, then those responses are averaged with a Gaussian of
    ``sigma_m`` along the flow curves; a pixel is a line where the result is
    negative and ``1 + tanh(H) < tau``.
    """
    import cv2

    g = np.ascontiguousarray(gray, dtype=np.float32)
    h, w = g.shape
    flow = edge_tangent_flow(gray).astype(np.float32)
    tx, ty = flow[..., 0], flow[..., 1]
    nx, ny = -ty, tx  # gradient direction, across the edge
    ys, xs = np.mgrid[0:h, 0:w].astype(np.float32)

    def sample(img: np.ndarray, px: np.ndarray, py: np.ndarray) -> np.ndarray:
        return cv2.remap(img, px, py, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)

    sigma_s = 1.6 * sigma_c
    half = math.ceil(3.0 * sigma_s)
    t = np.arange(-half, half + 1, dtype=np.float32)
    dog = np.exp(-(t**2) / (2 * sigma_c**2)) / (sigma_c * math.sqrt(2 * math.pi)) - rho * np.exp(
        -(t**2) / (2 * sigma_s**2)
    ) / (sigma_s * math.sqrt(2 * math.pi))
    across = np.zeros_like(g)
    for ti, wi in zip(t, dog, strict=True):
        across += wi * sample(g, xs + ti * nx, ys + ti * ny)

    steps = math.ceil(3.0 * sigma_m)
    weights = np.exp(-(np.arange(steps + 1) ** 2) / (2 * sigma_m**2)).astype(np.float32)
    acc = weights[0] * across
    total = weights[0]
    for direction in (1.0, -1.0):
        px, py = xs.copy(), ys.copy()
        vx, vy = direction * tx, direction * ty
        for s in range(1, steps + 1):
            px, py = px + vx, py + vy
            # Follow the flow: keep the sense of travel where the field flips.
            fx, fy = sample(tx, px, py), sample(ty, px, py)
            sign = np.sign(fx * vx + fy * vy)
            sign[sign == 0] = 1
            vx, vy = fx * sign, fy * sign
            acc += weights[s] * sample(across, px, py)
            total += weights[s]
    response = acc / total
    scale = np.max(np.abs(response)) or 1.0
    response = response / scale * 8.0  # unit-free: the tanh threshold acts on a fixed range
    return (response < 0) & (1.0 + np.tanh(response) < tau)
