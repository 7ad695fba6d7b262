"""Loading input images and masks: files or arrays to normalized float RGB + alpha.

The first stage of the pipeline (paper Sec. 4 takes an image as given): every
input, a PNG, JPEG, TIFF, ... or an array of any common dtype and channel count,
becomes a :class:`LoadedImage` (float RGB over white, alpha), checked for the
errors a user can make (a missing file, a text file, a blank or tiny image).

Arrays are indexed (row, column); points are (x, y) = (column + 0.5, row + 0.5)
in px, x to the right, y downwards (``contract/README.md``).
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ._validation import readonly
from .constants import BLANK_IMAGE_RANGE, MAX_IMAGE_SIDE, MIN_IMAGE_SIDE
from .errors import ImageNotFoundError, InvalidImageError, InvalidParameterError


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
