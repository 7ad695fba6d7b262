"""Loading input images and masks: files or arrays to normalized float RGB + alpha.

The first stage of the pipeline (paper Sec. 4 takes an image as given): every
input, a PNG, JPEG, TIFF, ... or an array of any common dtype and channel count,
becomes a :class:`LoadedImage` (float RGB over white, alpha), checked for the
errors a user can make (a missing file, a text file, a blank or tiny image).

Arrays are indexed (row, column); points are (x, y) = (column + 0.5, row + 0.5)
in px, x to the right, y downwards (``contract/README.md``).
"""

from __future__ import annotations

import functools
import sys
import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._validation import readonly
from ..constants import BLANK_IMAGE_RANGE, LUMA_WEIGHTS, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE
from ..errors import InvalidImageError, InvalidParameterError
from .constants import DOWNSCALE_STRIP_ROWS, MIN_IMAGE_SIDE
from .reading import PageWarning as PageWarning, read_file, working_size


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
    input_size : (int, int) or None
        (width, height) of the input before the downscale, px; None: this size.

    Examples
    --------
    >>> import numpy as np
    >>> from img2logo import load_image
    >>> pixels = np.full((30, 20, 3), 255, np.uint8)
    >>> pixels[10:20, 5:15] = 0  # a black square on white
    >>> img = load_image(pixels)  # a LoadedImage
    >>> img.gray.shape, round(float(img.gray.min()), 3), round(float(img.gray.max()), 3)
    ((30, 20), 0.0, 1.0)
    """

    rgb: np.ndarray
    alpha: np.ndarray
    has_alpha: bool = False
    scale: float = 1.0
    source: str = "<array>"
    input_size: tuple[int, int] | None = None

    @property
    def input_width(self) -> int:
        """Width of the input image, px (before any downscale): the frame of the results."""
        return int(self.input_size[0]) if self.input_size is not None else self.width

    @property
    def input_height(self) -> int:
        """Height of the input image, px (before any downscale)."""
        return int(self.input_size[1]) if self.input_size is not None else self.height

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
        return self.rgb @ np.array(LUMA_WEIGHTS)

    @functools.cached_property
    def flat_fraction(self) -> float:
        """The fraction of pixels whose four neighbours have exactly their colour (8 bits a channel); computed
        once (the pipeline's photo test and the kind detection both need it, :func:`img2logo.detect_kind`)."""
        v = self.rgb * 255.0
        np.rint(v, out=v)
        # The 24-bit code r * 65536 + g * 256 + b, exact in float64 (whole numbers below 2**24): one
        # product, where integer shifts and ors took three times as long.
        key = v @ np.array([65536.0, 256.0, 1.0])
        same = np.ones(key.shape, dtype=bool)
        eh, ev = key[:, 1:] == key[:, :-1], key[1:] == key[:-1]
        same[:, 1:] &= eh
        same[:, :-1] &= eh
        same[1:] &= ev
        same[:-1] &= ev
        return float(same.mean())

    @functools.cached_property
    def lab(self) -> np.ndarray:
        """CIELAB colours (D65), (H, W, 3) float64, read-only; computed once (kind detection and
        clip-art regions both need them)."""
        from .cielab import srgb_to_lab  # skimage's rgb2lab, once per colour of an 8-bit image

        return readonly(srgb_to_lab(self.rgb))

    @functools.cached_property
    def smooth_lab(self) -> np.ndarray:
        """CIELAB colours of the image smoothed by a 1 px Gaussian (pixel noise out), (H, W, 3) float64,
        read-only; computed once (the subject's outline test may run for two candidates).
        The blur is ``scipy.ndimage.gaussian_filter`` to the bit, without importing ``scipy.ndimage``
        (:func:`img2logo.images.ndimage.gaussian`)."""
        from .cielab import rgb2lab
        from .ndimage import gaussian

        return readonly(rgb2lab(gaussian(self.rgb, (1.0, 1.0, 0.0))))


# --------------------------------------------------------------------------- loading
def load_image(source: object, *, max_side: int = MAX_IMAGE_SIDE, max_pixels: int = MAX_IMAGE_PIXELS) -> LoadedImage:
    """Read and normalize an input image.

    Memory follows the working size: a file larger than ``max_side`` is decoded
    at a reduced size where the format allows it (JPEG: 1/2, 1/4 or 1/8 in the
    decoder) and otherwise downscaled as 8- or 16-bit integers before the
    float conversion, so a 10000 x 10000 px PNG needs about its decoded bytes
    (300 MB), not the float64 copies (2.4 GB each).

    Parameters
    ----------
    source : str, Path, ndarray or LoadedImage
        A file PNG, JPEG, TIFF, BMP, WebP, ... or an array of shape (H, W),
        (H, W, 1), (H, W, 2) (gray + alpha), (H, W, 3) (RGB) or (H, W, 4) (RGBA),
        of dtype uint8, uint16, bool or float in [0, 1]. The input is never
        modified. A file of several pages (a multi-page TIFF) gives its first
        page, with a :class:`PageWarning`.
    max_side : int, optional
        An image whose longer side exceeds this is downscaled to it (area
        interpolation) with a :class:`DownscaleWarning`, issued as soon as the
        size is known (before the work on the image).
    max_pixels : int, optional
        A file of more pixels (width x height, read from its header before
        decoding) is refused: a guard against decompression bombs.

    Returns
    -------
    LoadedImage

    Raises
    ------
    ImageNotFoundError
        The path does not exist, is a directory or is not a regular file.
    InvalidImageError
        Not an image, empty, more than ``max_pixels`` px, fewer than 16 px on a
        side (after the downscale to ``max_side``), or blank (one colour).

    Examples
    --------
    >>> import numpy as np
    >>> from img2logo import load_image
    >>> pixels = np.zeros((40, 60, 3), np.uint8)
    >>> pixels[10:20, 10:30] = 255  # a white bar on black
    >>> img = load_image(pixels)
    >>> img.width, img.height, img.rgb.dtype, img.has_alpha
    (60, 40, dtype('float64'), False)
    """
    if isinstance(source, LoadedImage):
        return source
    max_side = int(max_side)
    if max_side < MIN_IMAGE_SIDE:
        raise InvalidParameterError(f"max_side must be >= {MIN_IMAGE_SIDE} px, got {max_side}")
    if isinstance(source, (str, Path)):
        name = str(source)
        arr, (w, h) = read_file(Path(source), max_side=max_side, max_pixels=max_pixels)
        bgr = True
    elif isinstance(source, np.ndarray):
        arr, name, bgr = source, "<array>", False
        _check_layout(arr, name)
        h, w = arr.shape[:2]
    else:
        raise InvalidImageError(f"image must be a file path or a numpy array, got {type(source).__name__}")
    size = working_size(w, h, max_side, name)
    scale = 1.0
    if size != (w, h):
        scale = max_side / max(h, w)
        warnings.warn(
            f"{name}: image is {w}x{h} px, larger than {max_side} px; downscaled to {size[0]}x{size[1]} px",
            DownscaleWarning,
            stacklevel=2,
        )
        rgb, alpha, has_alpha = _shrink(arr, size, name, bgr=bgr, owned=bgr)  # a decoded file is ours to overwrite
    else:
        rgb, alpha, has_alpha = composite_on_white(arr, name, bgr=bgr)
    _check_not_blank(rgb, alpha, name)
    return LoadedImage(readonly(rgb), readonly(alpha), has_alpha, scale, name, (int(w), int(h)))


def downscale(img: LoadedImage, max_side: int, why: str | None = None) -> LoadedImage:
    """``img`` shrunk to ``max_side`` px on its longer side (area interpolation), or ``img`` if not larger.

    The input's size is kept (``input_size``) and ``scale`` becomes the whole
    factor from the input, so results and masks convert as for a large input
    (:func:`mask_to_working_size`); a :class:`DownscaleWarning` says ``why``
    (None: no warning, the caller says it with :func:`warn_downscaled`).
    """
    side = max(img.width, img.height)
    if side <= max_side:
        return img
    import cv2

    f = max_side / side
    size = (max(MIN_IMAGE_SIDE, round(img.width * f)), max(MIN_IMAGE_SIDE, round(img.height * f)))
    rgb = np.clip(cv2.resize(img.rgb, size, interpolation=cv2.INTER_AREA), 0.0, 1.0)
    alpha = np.clip(cv2.resize(img.alpha, size, interpolation=cv2.INTER_AREA), 0.0, 1.0)
    scale = max_side / max(img.input_width, img.input_height)  # as load_image's: the whole factor from the input
    small = LoadedImage(
        readonly(rgb), readonly(alpha), img.has_alpha, scale, img.source, (img.input_width, img.input_height)
    )
    if why is not None:
        warn_downscaled(small, why, stacklevel=3)
    return small


def warn_downscaled(img: LoadedImage, why: str, stacklevel: int = 2) -> None:
    """The :class:`DownscaleWarning` of a working copy ``img``: ``why``, its size and the input's."""
    warnings.warn(
        f"{img.source}: {why}: {img.width}x{img.height} px (the results are in the input's "
        f"{img.input_width}x{img.input_height} px)",
        DownscaleWarning,
        stacklevel=stacklevel + 1,
    )


def mask_to_working_size(mask: object, img: LoadedImage, name: str) -> np.ndarray | None:
    """A mask given in the input's pixels (a path or an array, as :func:`load_mask`) at ``img``'s working size.

    For an input over ``MAX_IMAGE_SIDE`` the work is done at the downscaled
    size; a mask (``lock_mask``, a ``foreground`` mask) is given at the input's
    size and shrunk the same way (area interpolation, then >= 50 %). None stays None.

    Raises
    ------
    InvalidParameterError
        If the mask does not have the input's shape, naming ``name``.
    """
    if mask is None:
        return None
    full = (img.input_height, img.input_width)
    m = load_mask(mask)
    if m.shape != full:
        raise InvalidParameterError(f"{name}: mask must have the input image's shape {full}, got {m.shape}")
    if img.input_size is None or full == (img.height, img.width):
        return m
    import cv2

    small = cv2.resize(m.astype(np.uint8) * np.uint8(255), (img.width, img.height), interpolation=cv2.INTER_AREA)
    return small >= 128


def _check_not_blank(rgb: np.ndarray, alpha: np.ndarray, name: str) -> None:
    """Raise if the image is one colour (any colour, and one opacity): each channel spans < ``BLANK_IMAGE_RANGE``."""
    # Channel by channel: a reduction over axes (0, 1) of (H, W, 3) is ten times slower.
    lo = np.array([rgb[..., c].min() for c in range(rgb.shape[2])])
    hi = np.array([rgb[..., c].max() for c in range(rgb.shape[2])])
    if np.all(hi - lo < BLANK_IMAGE_RANGE) and np.ptp(alpha) < BLANK_IMAGE_RANGE:
        colour = "#" + "".join(f"{round(float(v) * 255):02x}" for v in (lo + hi) / 2)
        raise InvalidImageError(f"{name}: image is blank (one colour, {colour}, in every pixel); nothing to trace")


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

    Examples
    --------
    >>> import numpy as np
    >>> from img2logo import load_mask
    >>> mask = load_mask(np.eye(4))
    >>> mask.dtype, int(mask.sum())
    (dtype('bool'), 4)
    """
    if isinstance(source, (str, Path)):
        # A mask is never downscaled: it must have the (loaded) image's shape.
        arr, name, bgr = read_file(Path(source), max_side=sys.maxsize)[0], str(source), True
    else:
        arr, name, bgr = np.asarray(source), "<array>", False
    if arr.dtype == bool and arr.ndim == 2:
        mask = arr.copy()
    else:
        rgb, alpha, _ = composite_on_white(arr, name, bgr=bgr)
        mask = (rgb @ np.array(LUMA_WEIGHTS) >= 0.5) & (alpha >= 0.5)
    if shape is not None and mask.shape != tuple(shape):
        raise InvalidParameterError(f"{name}: mask must have the image's shape {tuple(shape)}, got {mask.shape}")
    return mask


def _check_layout(arr: np.ndarray, name: str) -> None:
    """Raise InvalidImageError unless ``arr`` is (H, W) or (H, W, C), C in 1..4, not empty."""
    if arr.ndim not in (2, 3) or (arr.ndim == 3 and arr.shape[2] not in (1, 2, 3, 4)):
        raise InvalidImageError(
            f"{name}: image must have shape (H, W) or (H, W, C) with C in 1..4, got {tuple(np.shape(arr))}"
        )
    if arr.shape[0] == 0 or arr.shape[1] == 0:
        shape = arr.shape if arr.ndim == 3 else (*arr.shape, 1)  # as (H, W, C)
        raise InvalidImageError(f"{name}: image is empty (shape {shape})")


def _shrink(
    arr: np.ndarray, size: tuple[int, int], name: str, *, bgr: bool, owned: bool = False
) -> tuple[np.ndarray, np.ndarray, bool]:
    """Downscale ``arr`` to ``size`` (width, height) in its own dtype, then normalize (see :func:`composite_on_white`).

    Colour is composited over white strip by strip (``DOWNSCALE_STRIP_ROWS``
    rows at a time, float32), so no full-size float copy is ever made; area
    interpolation then works on 8/16-bit integers (float32 for float input).
    With ``owned`` (an array decoded from a file, nobody else's) the composited
    colour overwrites the array's own colour channels and one resize takes
    colour and alpha together (area interpolation is per channel: the same
    values), so no second full-size array is made: a 12000 x 12000 16-bit RGBA
    PNG needs its 1.15 GB decoded, not 2 GB more.
    """
    import cv2

    if arr.ndim == 2:
        arr = arr[:, :, None]
    if arr.dtype == bool:
        arr = arr.astype(np.uint8) * np.uint8(255)
    elif np.issubdtype(arr.dtype, np.floating):
        _to_unit(arr, name)  # the range and finiteness checks
        arr = arr.astype(np.float32, copy=False)
    elif arr.dtype not in (np.uint8, np.uint16):
        _to_unit(arr, name)  # raises: unsupported dtype
    channels = arr.shape[2]
    has_alpha = channels in (2, 4)
    full = 1.0 if np.issubdtype(arr.dtype, np.floating) else float(np.iinfo(arr.dtype).max)
    if has_alpha and owned and arr.flags.writeable and arr.flags.c_contiguous:
        for r in range(0, arr.shape[0], DOWNSCALE_STRIP_ROWS):
            block = arr[r : r + DOWNSCALE_STRIP_ROWS]
            a = block[:, :, -1:].astype(np.float32) / np.float32(full)
            mixed = block[:, :, :-1] * a + (1.0 - a) * np.float32(full)
            block[:, :, :-1] = mixed if full == 1.0 else np.rint(mixed)
        small_all = cv2.resize(arr, size, interpolation=cv2.INTER_AREA)
        if small_all.ndim == 2:  # cv2 drops a last axis of one
            small_all = small_all[:, :, None]
        rgb, _, _ = composite_on_white(np.ascontiguousarray(small_all[:, :, :-1]), name, bgr=bgr)
        alpha = np.clip(_to_unit(np.ascontiguousarray(small_all[:, :, -1]), name), 0.0, 1.0)
        return np.clip(rgb, 0.0, 1.0), alpha, has_alpha
    if has_alpha:
        colour = np.empty((*arr.shape[:2], channels - 1), dtype=arr.dtype)
        for r in range(0, arr.shape[0], DOWNSCALE_STRIP_ROWS):
            block = arr[r : r + DOWNSCALE_STRIP_ROWS]
            a = block[:, :, -1:].astype(np.float32) / np.float32(full)
            mixed = block[:, :, :-1] * a + (1.0 - a) * np.float32(full)
            colour[r : r + DOWNSCALE_STRIP_ROWS] = mixed if full == 1.0 else np.rint(mixed)
        alpha_small = cv2.resize(np.ascontiguousarray(arr[:, :, -1]), size, interpolation=cv2.INTER_AREA)
    else:
        colour = arr
        alpha_small = None
    small = cv2.resize(np.ascontiguousarray(colour), size, interpolation=cv2.INTER_AREA)
    rgb, _, _ = composite_on_white(small, name, bgr=bgr)
    rgb = np.clip(rgb, 0.0, 1.0)
    alpha = np.ones(rgb.shape[:2]) if alpha_small is None else np.clip(_to_unit(alpha_small, name), 0.0, 1.0)
    return rgb, alpha, has_alpha


def _to_unit(arr: np.ndarray, name: str) -> np.ndarray:
    """Values as float64 in [0, 1] by dtype (uint8 / 255, uint16 / 65535, bool, float checked)."""
    if arr.dtype == bool:
        return arr.astype(np.float64)
    if arr.dtype == np.uint8:
        return arr / 255.0
    if arr.dtype == np.uint16:
        return arr / 65535.0
    if np.issubdtype(arr.dtype, np.floating):
        if not np.all(np.isfinite(arr)):
            raise InvalidImageError(f"{name}: image contains NaN or infinite values")
        lo, hi = float(arr.min()), float(arr.max())
        if lo < 0.0 or hi > 1.0:
            raise InvalidImageError(f"{name}: float images must have values in [0, 1], got [{lo:g}, {hi:g}]")
        return arr.astype(np.float64)
    raise InvalidImageError(f"{name}: unsupported dtype {arr.dtype} (use uint8, uint16, bool or float in [0, 1])")


def _to_rgb_order(arr: np.ndarray) -> np.ndarray:
    """A BGR or BGRA array (H, W, 3 or 4) as RGB(A), C-contiguous, its samples unchanged.

    Swapped on the stored samples, before their conversion to float (a quarter of the bytes
    of uint8), by OpenCV for the dtypes it decodes to (a strided numpy copy takes 40 times
    longer); the float conversion then reads in order (on a float view reversed in its last
    axis it took ten times longer).
    """
    if arr.dtype in (np.uint8, np.uint16, np.float32):
        import cv2

        code = cv2.COLOR_BGR2RGB if arr.shape[2] == 3 else cv2.COLOR_BGRA2RGBA
        return cv2.cvtColor(np.ascontiguousarray(arr), code)
    return np.ascontiguousarray(arr[:, :, [2, 1, 0, 3][: arr.shape[2]]])


def composite_on_white(
    arr: object, name: str = "image", *, bgr: bool = False, size: tuple[int, int] | None = None
) -> tuple[np.ndarray, np.ndarray, bool]:
    """An image array as float RGB composited over white, and its opacity.

    The one reading of pixel values in img2logo: input images (:func:`load_image`,
    :func:`load_mask`), the image drawn under a plot (:mod:`img2logo.export.plotting`)
    and the colours read by :func:`img2logo.design.fills.fill_auto`.

    Parameters
    ----------
    arr : array_like, shape (H, W) or (H, W, C), C in 1..4
        Grey (C = 1), grey + alpha (2), colour (3) or colour + alpha (4), of
        dtype uint8 (0..255), uint16 (0..65535), bool, or float in [0, 1].
    name : str
        What to call the image in a message (a file name, ``"image"``).
    bgr : bool
        The colour channels are in OpenCV's order, blue first.
    size : (int, int), optional
        The (width, height) the image must have, px.

    Returns
    -------
    rgb : ndarray, shape (H, W, 3), float64
        In [0, 1], composited over white by the opacity.
    alpha : ndarray, shape (H, W), float64
        The opacity in [0, 1], all ones without an alpha channel.
    has_alpha : bool
        Whether the array had an alpha channel.

    Raises
    ------
    InvalidImageError
        On another shape or dtype, a float outside [0, 1] or not finite, or a
        size other than ``size``, saying what was expected and what came.
    """
    arr = np.asarray(arr)
    _check_layout(arr, name)
    if size is not None and arr.shape[:2] != (size[1], size[0]):
        raise InvalidImageError(
            f"{name}: image must be {size[1]} x {size[0]} px (rows x columns), got {arr.shape[0]} x {arr.shape[1]}"
        )
    if arr.ndim == 2:
        arr = arr[:, :, None]
    channels = arr.shape[2]
    if bgr and channels >= 3:
        arr = _to_rgb_order(arr)
    val = _to_unit(arr, name)
    has_alpha = channels in (2, 4)
    alpha = val[:, :, -1].copy() if has_alpha else np.ones(val.shape[:2])
    colour = val[:, :, : channels - 1] if has_alpha else val
    if colour.shape[2] == 1:
        colour = np.repeat(colour, 3, axis=2)
    if has_alpha:
        rgb = colour * alpha[:, :, None] + (1.0 - alpha[:, :, None])
    elif np.issubdtype(arr.dtype, np.floating):  # alpha 1 everywhere: colour * 1 + 0 (+ 0.0 turns a -0.0 into 0.0)
        rgb = colour + 0.0
    else:  # integers and booleans scaled to [0, 1]: no -0.0, and `colour` is a new array of this function's
        rgb = colour
    return np.ascontiguousarray(rgb), alpha, has_alpha
