"""Loading input images and masks: files or arrays to normalized float RGB + alpha.

The first stage of the pipeline (paper Sec. 4 takes an image as given): every
input, a PNG, JPEG, TIFF, ... or an array of any common dtype and channel count,
becomes a :class:`LoadedImage` (float RGB over white, alpha), checked for the
errors a user can make (a missing file, a text file, a blank or tiny image).

Arrays are indexed (row, column); points are (x, y) = (column + 0.5, row + 0.5)
in px, x to the right, y downwards (``contract/README.md``).
"""

from __future__ import annotations

import contextlib
import functools
import os
import re
import sys
import tempfile
import warnings
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .._validation import readonly
from ..constants import BLANK_IMAGE_RANGE, LUMA_WEIGHTS, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE
from ..errors import ImageNotFoundError, InvalidImageError, InvalidParameterError
from .constants import DOWNSCALE_STRIP_ROWS, MAX_FLOAT_IMAGE_PIXELS, MAX_WHOLE_TIFF_BYTES, MIN_IMAGE_SIDE

if TYPE_CHECKING:
    from PIL import Image


#: Files of at least this many bytes (with an ASCII name) are decoded by OpenCV from the file, not from
#: their bytes read into memory first: its decoders stream a file.
STREAM_DECODE_BYTES = 64 << 20


class DownscaleWarning(UserWarning):
    """An input image larger than the size bound was downscaled."""


class PageWarning(UserWarning):
    """An input file holds several pages (a multi-page TIFF); only the first is used."""


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
        v = np.round(self.rgb * 255.0).astype(np.int32)
        key = (v[..., 0] << 16) | (v[..., 1] << 8) | v[..., 2]
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
        arr, (w, h) = _read_file(Path(source), max_side=max_side, max_pixels=max_pixels)
        bgr = True
    elif isinstance(source, np.ndarray):
        arr, name, bgr = source, "<array>", False
        _check_layout(arr, name)
        h, w = arr.shape[:2]
    else:
        raise InvalidImageError(f"image must be a file path or a numpy array, got {type(source).__name__}")
    size = _working_size(w, h, max_side, name)
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


def _working_size(w: int, h: int, max_side: int, name: str) -> tuple[int, int]:
    """(width, height) after the downscale to ``max_side``; raise if a side is then below the minimum."""
    size = (w, h)
    if max(w, h) > max_side:
        s = max_side / max(h, w)
        size = (max(1, round(w * s)), max(1, round(h * s)))
    if min(size) < MIN_IMAGE_SIDE:
        shrunk = f" (downscaled to {size[0]}x{size[1]} px to fit {max_side} px)" if size != (w, h) else ""
        raise InvalidImageError(
            f"{name}: image is {w}x{h} px{shrunk}; at least {MIN_IMAGE_SIDE} px on each side is needed"
        )
    return size


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
        arr, name, bgr = _read_file(Path(source), max_side=sys.maxsize)[0], str(source), True
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


def _read_file(path: Path, *, max_side: int = MAX_IMAGE_SIDE, max_pixels: int = MAX_IMAGE_PIXELS) -> tuple:
    """Decode ``path``: (array as OpenCV gives it, BGR(A) or gray; (width, height) of the file).

    The header is read first (Pillow, which decodes nothing on open): the pixel
    limit and the minimum size after the downscale are checked before decoding,
    a multi-page file is reported, and a JPEG larger than ``max_side`` is
    decoded at 1/2, 1/4 or 1/8 of its size (never below ``max_side``).
    OpenCV's own log lines are silenced: the errors raised here say it.
    """
    import cv2

    _quiet_opencv()
    if not path.exists():
        raise ImageNotFoundError(f"image file not found: {path}")
    if path.is_dir():
        raise ImageNotFoundError(f"{path} is a directory, not an image file")
    if not path.is_file():
        raise ImageNotFoundError(f"{path} is not a regular file (a device, a pipe, ...), not an image file")
    header = _probe(path, max_pixels, max_side)
    floats = _float_image_size(path)
    if floats is not None and floats[0] * floats[1] > min(max_pixels, MAX_FLOAT_IMAGE_PIXELS):
        fw, fh, kind = floats
        if fw * fh > max_pixels:
            raise InvalidImageError(_too_many_pixels(path, f"{fw}x{fh} px", max_pixels))
        raise InvalidImageError(
            f"{path}: image is {fw}x{fh} px of floating-point samples ({kind}); such a file is decoded whole, "
            f"so img2logo reads it up to {MAX_FLOAT_IMAGE_PIXELS:,} px (its memory limit): downscale it first"
        )
    flags = cv2.IMREAD_UNCHANGED  # the pixels as stored: EXIF orientation is applied below
    orientation = 1
    if header is not None:
        w, h, pages, fmt, orientation = header
        _working_size(w, h, max_side, str(path))
        if pages > 1:
            warnings.warn(f"{path}: the file has {pages} pages; only the first is used", PageWarning, stacklevel=3)
        if fmt == "PNG":
            exif_after = _check_png_end(path)
            if exif_after is not None and orientation == 1:
                orientation = _exif_orientation(exif_after)
        elif fmt in ("JPEG", "MPO"):
            _check_jpeg_scans(path)
        elif fmt == "TIFF":
            _check_tiff_strips(path)
        factor = max([f for f in (2, 4, 8) if max(w, h) / f >= max_side], default=1)
        if fmt in ("JPEG", "MPO") and factor > 1:
            reduced = {2: cv2.IMREAD_REDUCED_COLOR_2, 4: cv2.IMREAD_REDUCED_COLOR_4, 8: cv2.IMREAD_REDUCED_COLOR_8}
            flags = reduced[factor] | cv2.IMREAD_IGNORE_ORIENTATION
        small = None
        # An animated PNG (an acTL chunk) is read as its default image, the IDAT's, by libvips: OpenCV
        # composes its first frame from the fcTL chunks and gave a damaged one's as all black.
        animated = fmt == "PNG" and (pages > 1 or _png_has_chunk(path, b"acTL", before_pixels=True))
        if fmt in _VIPS_LOADERS and (max(w, h) > max_side or fmt == "TIFF" or animated):
            with _decoder_stderr():  # libtiff's "TIFFReadDirectory: ..." lines, libvips' warnings
                small = _read_with_vips(path, fmt, max(1, max(w, h) // max_side))
        elif fmt in ("GIF", "AVIF") and max(w, h) > max_side:
            # Pillow holds a GIF as its palette indices (libvips' GIF loader: an RGBA canvas, 1.50 GB at the
            # peak for a 12000 px one, measured; Pillow's 0.32 GB)
            small = _read_pillow_reduced(path, max(1, max(w, h) // max_side))
        elif fmt == "PPM" and max(w, h) > max_side:
            small = _read_netpbm_reduced(path, max(1, max(w, h) // max_side))
        elif fmt == "JPEG2000" and max(w, h) >= 2 * max_side:
            small = _read_jpeg2000_reduced(path, max(w, h), max_side)
        if small is not None:
            if orientation in (5, 6, 7, 8):
                w, h = h, w
            return _upright(small, orientation), (w, h)
    try:
        # A file of 64 MB or more with a plain name is decoded from the file (OpenCV's decoders stream it):
        # a 12000 px BMP's 576 MB were in memory twice (1.75 GB at the peak, measured). Otherwise from
        # its bytes (imdecode: unicode-safe, unlike imread; the same decoders).
        stream = path.stat().st_size >= STREAM_DECODE_BYTES and str(path).isascii()
        data = np.zeros(1, dtype=np.uint8) if stream else np.fromfile(path, dtype=np.uint8)
    except OSError as exc:
        raise InvalidImageError(f"{path}: cannot read the file: {exc.strerror or exc}") from exc
    if data.size == 0:
        raise InvalidImageError(f"{path}: file is empty")
    try:
        with _decoder_stderr():  # libpng's "libpng warning: iCCP: ..." lines and the like
            arr = cv2.imread(str(path), flags) if stream else cv2.imdecode(data, flags)
    except cv2.error as exc:  # e.g. beyond OpenCV's own size limit
        raise InvalidImageError(f"{path}: not a readable image: {' '.join(str(exc).split())[-200:]}") from exc
    del data
    if arr is None or arr.size == 0:
        raise InvalidImageError(f"{path}: not a readable image (expected PNG, JPEG, TIFF, BMP, WebP, ...)")
    if header is None:
        h, w = arr.shape[:2]
        if w * h > max_pixels:
            raise InvalidImageError(_too_many_pixels(path, f"{w}x{h} px", max_pixels))
    arr = _upright(arr, orientation)
    if orientation in (5, 6, 7, 8):  # a quarter turn: the stored width is the upright height
        w, h = h, w
    return arr, (w, h)


#: Formats (as Pillow's probe names them) read through libvips (``pyvips``): every TIFF, the others when
#: larger than the working size (shrink-on-load); its loader for each, which must be the one that reads it.
_VIPS_LOADERS = {
    "PNG": "pngload",
    "TIFF": "tiffload",
    "WEBP": "webpload",
}
#: libvips' sample formats and the largest value of each (the alpha of full opacity).
_VIPS_FULL = {"uchar": 255.0, "ushort": 65535.0, "float": 1.0}


def _read_with_vips(path: Path, fmt: str, factor: int) -> np.ndarray:
    """A PNG, TIFF or WebP decoded by libvips and box-reduced by ``factor``; BGR(A) or grey, as OpenCV's.

    libvips decodes the file a band of rows at a time (``access="sequential"``) and reduces each
    band as it comes, so the full-size image is never in memory; a WebP is decoded at
    1/``factor`` of its size by libwebp itself. Colour is averaged premultiplied by alpha
    (the average of the composite over any background), at the file's depth: 8 or 16-bit
    integers, or float. A CMYK or CIELAB file is converted to sRGB. The file is read
    through its open descriptor (any file name); libvips' loader must be the format's.
    A file whose decoder reports an error (damaged data, cut short) is refused
    (``fail_on="error"``), as OpenCV's decoders refuse it at the working size, not
    read with the rest of the image left blank.

    Raises
    ------
    InvalidImageError
        The file is damaged or cut short, or not of the format its header says: one line.
    """
    import pyvips

    options: dict[str, Any] = {"access": "sequential", "fail_on": "error"}
    if fmt == "WEBP" and factor > 1:
        options["scale"] = 1.0 / factor
    try:
        with open(path, "rb") as f:  # the descriptor, not the name: a name of any bytes
            im = pyvips.Image.new_from_source(pyvips.Source.new_from_descriptor(f.fileno()), "", **options)
            loader = str(im.get("vips-loader"))
            if not loader.startswith(_VIPS_LOADERS[fmt]):
                raise InvalidImageError(f"{path}: not a readable image: its header says {fmt}, its content not")
            if im.interpretation in ("cmyk", "lab", "labs", "labq", "xyz", "scrgb", "hsv", "lch", "cmc", "yxy"):
                im = im.colourspace("srgb")
            if im.format not in _VIPS_FULL:
                raise InvalidImageError(
                    f"{path}: not a readable image: samples of {im.format} (expected 8 or 16-bit integers or float)"
                )
            if factor > 1 and "scale" not in options:
                im = _box_reduce(im, factor)
            arr = im.numpy()
    except pyvips.Error as exc:
        raise InvalidImageError(f"{path}: not a readable image: {_vips_reason(exc)}") from exc
    if arr.ndim == 3 and arr.shape[2] >= 3:  # OpenCV's channel order, as the rest of loading expects
        arr = np.ascontiguousarray(arr[:, :, [2, 1, 0, *range(3, arr.shape[2])]])
    return arr


def _vips_reason(exc: Exception) -> str:
    """The line of a libvips error that says why, at most 200 characters.

    libvips stacks its messages in one buffer, and a loader's closing "load error"
    or "unable to write to memory" lands before or after the reason depending on
    which of its threads finished first: the reason is the last line that is not
    one of those.
    """
    lines = [line.strip() for line in str(exc).splitlines() if line.strip()]
    reasons = [line for line in lines if not re.search(r"(: load error|unable to write to memory)$", line)]
    return (reasons or lines or ["libvips failed"])[-1][-200:]


def _box_reduce(im: Any, factor: int) -> Any:
    """A libvips image reduced by ``factor`` (int) in boxes of ``factor`` x ``factor`` pixels, at its sample format.

    Colour is averaged premultiplied by alpha (the average of the composite over any
    background); the last row and column of boxes take the image's edge pixels again
    (``extend="copy"``) where the size is not a multiple of ``factor``, so every box
    is whole. Integers are rounded to the nearest.
    """
    width, height = -(-im.width // factor) * factor, -(-im.height // factor) * factor
    if (width, height) != (im.width, im.height):
        im = im.embed(0, 0, width, height, extend="copy")
    kind, full = im.format, _VIPS_FULL.get(im.format, 1.0)
    im = im.cast("double")  # sums in double, one rounding at the end (integer shrinks round twice)
    if im.hasalpha():
        im = im.premultiply(max_alpha=full).shrink(factor, factor).unpremultiply(max_alpha=full)
    else:
        im = im.shrink(factor, factor)
    return im.rint().cast(kind) if kind != "float" else im.cast(kind)


def _read_netpbm_reduced(path: Path, factor: int) -> np.ndarray | None:
    """A binary PGM or PPM (P5, P6) of maxval 255 or 65535 box-reduced by ``factor`` by libvips; grey or BGR.

    Its samples are stored raw (16 bits big-endian), so libvips maps them as they are
    (``rawload``) and reduces them a band of rows at a time: OpenCV decodes a 12000 px
    16-bit PPM whole through a second full-size buffer (1.75 GB at the run's peak,
    measured). Another kind (text samples, another maxval, PAM): None, and OpenCV
    decodes it whole.
    """
    import pyvips

    with open(path, "rb") as f:
        head = f.read(512)
    found = re.match(rb"(P[56])(?:\s+|#[^\n]*\n)+(\d+)(?:\s+|#[^\n]*\n)+(\d+)(?:\s+|#[^\n]*\n)+(\d+)\s", head)
    if found is None:
        return None
    kind, width, height, maxval = found.group(1), *(int(g) for g in found.groups()[1:])
    if maxval not in (255, 65535) or width <= 0 or height <= 0:
        return None
    channels, depth = (3 if kind == b"P6" else 1), (2 if maxval == 65535 else 1)
    if path.stat().st_size < found.end() + width * height * channels * depth:
        raise InvalidImageError(f"{path}: not a readable image: its pixel data ends before the last row (cut short?)")
    try:
        im = pyvips.Image.rawload(
            os.fsencode(path).decode("utf-8", "surrogateescape"),
            width,
            height,
            channels,
            offset=found.end(),
            format="ushort" if depth == 2 else "uchar",
        )
        if depth == 2 and sys.byteorder == "little":  # the file's samples are big-endian
            im = im.byteswap()
        arr = _box_reduce(im, factor).numpy()
    except pyvips.Error as exc:
        raise InvalidImageError(f"{path}: not a readable image: {_vips_reason(exc)}") from exc
    if arr.ndim == 3 and arr.shape[2] == 3:
        arr = np.ascontiguousarray(arr[:, :, ::-1])  # OpenCV's channel order
    return arr


def _read_pillow_reduced(path: Path, factor: int) -> np.ndarray | None:
    """A GIF or an AVIF that will be downscaled, decoded by Pillow and box-reduced by ``factor`` a strip at a time.

    OpenCV decodes a 12000 x 12000 px GIF through full-size BGRA canvases (1.80 GB at the
    run's peak, measured) and an AVIF through 16-bit ones (2.42 GB); Pillow holds a GIF as
    its palette indices (144 MB) and an AVIF as 8-bit RGB(A), and each strip of rows is
    converted to RGB(A) and reduced (:func:`reduce_by_strips`): 0.22 GB and 2.0 s for the
    GIF's load, 1.32 GB and 8.4 s of CPU for the AVIF's (measured). BGR(A); None where
    Pillow cannot (OpenCV then decodes the file whole); a damaged file, one line.
    """
    from PIL import Image

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with Image.open(path) as im:
                im.load()
                alpha = im.mode in ("RGBA", "LA", "PA") or "transparency" in im.info
                mode = ("RGBA" if alpha else "RGB") if im.mode not in ("L", "LA") else im.mode
                arr = reduce_by_strips(im, factor, mode)
    except (OSError, ValueError, SyntaxError, EOFError) as exc:
        raise InvalidImageError(f"{path}: not a readable image: {' '.join(str(exc).split())[-200:]}") from exc
    if arr.ndim == 3 and arr.shape[2] >= 3:  # OpenCV's channel order, as the rest of loading expects
        arr = np.ascontiguousarray(arr[:, :, [2, 1, 0, *range(3, arr.shape[2])]])
    return arr


def reduce_by_strips(im: Image.Image, factor: int, mode: str | None = None) -> np.ndarray:
    """``np.array(im.reduce(factor))``, one strip of rows at a time: no second full-size image.

    Pillow's ``reduce`` of an RGBA image first converts all of it to premultiplied
    alpha (a copy as large as the decoded image: 576 MB at 12000 x 12000 px);
    a strip of ``factor`` x k rows cropped and reduced gives the same pixels, the
    copy a strip's size. With ``mode``, each strip is converted to it first (a palette's).
    """
    if factor <= 1:
        return np.array(im if mode is None or im.mode == mode else im.convert(mode))
    w, h = im.size
    rows = factor * max(1, DOWNSCALE_STRIP_ROWS // factor)

    def strip(y: int) -> Image.Image:
        part = im.crop((0, y, w, min(h, y + rows)))
        return part if mode is None or part.mode == mode else part.convert(mode)

    strips = [np.array(strip(y).reduce(factor)) for y in range(0, h, rows)]
    return np.concatenate(strips, axis=0)


def _read_jpeg2000_reduced(path: Path, side: int, max_side: int) -> np.ndarray | None:
    """A JPEG 2000 image at least twice ``max_side``, decoded at 1/2**k of its size (its wavelet levels); BGR(A).

    OpenJPEG decodes a 12000 x 12000 px file whole in 32-bit integers per sample (OpenCV's
    path: 35 s and 2.3 GB at its peak, measured); Pillow's decoder (OpenJPEG too) stops
    ``k`` resolution levels short (``Image.reduce`` set before ``load``), the largest ``k``
    that leaves ``side / 2**k >= max_side``, as a JPEG's 1/2, 1/4, 1/8. Colour comes at 8 bits
    (Pillow's modes; plenty at the working size), grey at 8 or 16. A mode other than L,
    I;16, LA, RGB, RGBA gives None (OpenCV decodes the file whole); a damaged file, one line.
    """
    from PIL import Image

    levels = 0
    while side / (1 << (levels + 1)) >= max_side:
        levels += 1
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with Image.open(path) as im:
                if im.mode not in ("L", "I;16", "LA", "RGB", "RGBA"):
                    return None
                im.reduce = levels  # type: ignore[method-assign,assignment]  # the plugin's setter
                im.load()
                arr = np.array(im)
    except (OSError, ValueError, SyntaxError, Image.DecompressionBombError) as exc:
        raise InvalidImageError(f"{path}: not a readable image: {' '.join(str(exc).split())[-200:]}") from exc
    if arr.ndim == 3 and arr.shape[2] >= 3:  # OpenCV's channel order, as the rest of loading expects
        arr = np.ascontiguousarray(arr[:, :, [2, 1, 0, *range(3, arr.shape[2])]])
    return arr


def _upright(arr: np.ndarray, orientation: int) -> np.ndarray:
    """The image as every viewer shows it: EXIF ``Orientation`` (1..8) applied, as ``PIL.ImageOps.exif_transpose``.

    A phone stores a portrait photo sideways with Orientation = 6 (turn 90 degrees
    clockwise to view). The transposition is done on the decoded array (OpenCV
    decodes the stored pixels), a view made contiguous only when it is not 1.
    """
    turns = {
        2: lambda a: a[:, ::-1],  # mirrored left-right
        3: lambda a: a[::-1, ::-1],  # upside down
        4: lambda a: a[::-1],  # mirrored top-bottom
        5: lambda a: a.swapaxes(0, 1),  # transposed
        6: lambda a: np.rot90(a, -1),  # stored a quarter turn counter-clockwise
        7: lambda a: a[::-1, ::-1].swapaxes(0, 1),  # transversed
        8: lambda a: np.rot90(a, 1),  # stored a quarter turn clockwise
    }
    if orientation not in turns:
        return arr
    return np.ascontiguousarray(turns[orientation](arr))


#: Lines a C image decoder writes to standard error itself (libpng, libjpeg's warnings (its JWRN_ messages),
#: libtiff, OpenCV).
_DECODER_LINE = re.compile(
    rb"^(libpng (warning|error)|Corrupt JPEG data|Premature end of JPEG|Invalid JPEG|Invalid SOS parameters|"
    rb"Inconsistent progression sequence|Unknown Adobe color transform|Application transferred too|"
    rb"Unsupported marker type|JPEG datastream contains no image|Warning: |TIFF\w*: |\[ ?WARN)"
)


@contextlib.contextmanager
def _decoder_stderr() -> Iterator[None]:
    """Hold standard error (file descriptor 2) in a temporary file while a C decoder runs.

    libpng writes ``libpng warning: iCCP: known incorrect sRGB profile`` (and the
    like) straight to file descriptor 2, which no Python setting silences; the
    errors img2logo raises say what matters. Afterwards every held line that is
    not a decoder's is written to standard error after all (another thread's
    output is delayed, not lost).
    """
    with contextlib.suppress(Exception):
        sys.stderr.flush()
    try:
        saved = os.dup(2)
    except OSError:  # no standard error at all: nothing to hold
        yield
        return
    hold = tempfile.TemporaryFile()
    try:
        os.dup2(hold.fileno(), 2)
        try:
            yield
        finally:
            os.dup2(saved, 2)
            hold.seek(0)
            rest = [line for line in hold.read().splitlines(keepends=True) if not _DECODER_LINE.match(line)]
            if rest:
                with contextlib.suppress(OSError):
                    os.write(2, b"".join(rest))
    finally:
        os.close(saved)
        hold.close()


def _probe(path: Path, max_pixels: int, max_side: int | None = None) -> tuple[int, int, int, str, int] | None:
    """(width, height, pages, format, EXIF orientation) from the file's header, or None if nothing can tell.

    Width and height are as stored (before the orientation, 1 when there is none).
    A PNG whose text chunks Pillow refuses (a zTXt of megabytes) still has its size
    read from its IHDR chunk, so the pixel limit holds before decoding. A PNG larger
    than ``max_side`` (given) with no eXIf or acTL chunk before its pixels is probed up
    to them only: its strip decoder reads an eXIf chunk after them (orientation 1 here).
    Raises InvalidImageError if the image has more than ``max_pixels`` pixels.
    """
    plain = _plain_png_size(path, pixels_first=True) if max_side is not None else None
    if plain is None or max(plain) <= max_side:  # type: ignore[operator]  # max_side is not None with plain
        plain = _plain_png_size(path)
    if plain is not None:  # Pillow would say the same: one frame, no EXIF
        w, h = plain
        if w * h > max_pixels:
            raise InvalidImageError(_too_many_pixels(path, f"{w}x{h} px", max_pixels))
        return w, h, 1, "PNG", 1
    try:
        from PIL import Image
    except ImportError:  # pragma: no cover - a dependency of matplotlib and of img2logo
        return None
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # DecompressionBombWarning, a damaged EXIF block
        try:
            with Image.open(path) as im:
                w, h = im.size
                pages = int(getattr(im, "n_frames", 1) or 1)
                fmt = str(im.format or "")
                try:
                    # A PNG's getexif() decodes the whole image to look for an eXIf chunk after the
                    # pixels (4 s for 144 Mpx); the chunk is found by walking the chunk headers.
                    exif = im.getexif() if fmt != "PNG" else _png_exif(path)
                    orientation = int(exif.get(0x0112, 1))
                except Exception:  # a damaged EXIF block: as stored
                    orientation = 1
        except Image.DecompressionBombError as exc:  # more than twice Pillow's own limit
            raise InvalidImageError(_too_many_pixels(path, "over 178 Mpx", max_pixels)) from exc
        except Exception:  # not a format Pillow knows, or a damaged header: OpenCV decides
            size = _png_size(path)
            if size is None:
                return None
            (w, h), pages, fmt, orientation = size, 1, "PNG", 1
    if w * h > max_pixels:
        raise InvalidImageError(_too_many_pixels(path, f"{w}x{h} px", max_pixels))
    return w, h, pages, fmt, orientation


def _check_tiff_strips(path: Path) -> None:
    """Refuse a TIFF whose strips (or tiles) each hold more than ``MAX_WHOLE_TIFF_BYTES`` of decoded samples.

    libtiff decodes a strip or a tile whole, so one strip of the whole image (a layout
    some writers use) is the whole image in memory however it is read. Its bytes are the
    strip's (tile's) width x rows x the bits of a pixel / 8, from the first image file
    directory as Pillow reads it (TIFF 6.0, Sec. 8 and 15); a file Pillow cannot read is
    left to the decoder, which says why.
    """
    from PIL import Image

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            with Image.open(path) as im:
                tags = im.tag_v2  # type: ignore[attr-defined]  # a TIFF's
                width, height = im.size
                bits = tags.get(258, (1,))
                bits = sum(bits) if isinstance(bits, tuple) else int(bits) * int(tags.get(277, 1))
                if 322 in tags and 323 in tags:
                    size, what = int(tags[322]) * int(tags[323]) * bits // 8, "tiles"
                else:
                    size, what = width * min(int(tags.get(278, height)), height) * bits // 8, "strips"
    except Exception:
        return
    if size > MAX_WHOLE_TIFF_BYTES:
        raise InvalidImageError(
            f"{path}: image is a TIFF in {what} of {size / 1e6:,.0f} MB of samples each, and a strip or tile is "
            f"decoded whole; img2logo reads such a file up to {MAX_WHOLE_TIFF_BYTES / 1e6:,.0f} MB a strip (its "
            "memory limit): downscale it, or save it in smaller strips or tiles"
        )


#: The last chunk of every PNG: IEND, its length (0) before it and its CRC after (PNG specification, Sec. 11.2.5).
_PNG_IEND = b"\x00\x00\x00\x00IEND\xaeB`\x82"


def _check_png_end(path: Path) -> bytes | None:
    """Refuse a PNG without its IEND chunk; the data of an eXIf chunk between its pixels and IEND, or None.

    A PNG ends with IEND (PNG specification, Sec. 5.6); without it the file was cut
    short, whatever its size, so it is refused at every size (libpng through OpenCV
    refuses it at the working size, libvips would read the rows it has). Only the
    file's last 64 KB are read: an eXIf chunk after the pixel data is found there
    by following the chunks' lengths from it to IEND exactly (a huge file's 100 000
    pixel data chunks are not walked).

    Raises
    ------
    InvalidImageError
        The file has no IEND chunk.
    """
    try:
        with open(path, "rb") as f:
            size = f.seek(0, os.SEEK_END)
            start = max(0, size - (64 << 10))
            f.seek(start)
            tail = f.read()
    except OSError:
        return None  # the decode says why
    end = tail.rfind(_PNG_IEND)
    if end < 0 and not _png_has_chunk(path, b"IEND"):
        raise InvalidImageError(
            f"{path}: not a readable image: the PNG ends before its IEND chunk (the file cut short?)"
        )
    found = tail.rfind(b"eXIf", 0, max(end, 0))
    if found < 4 or end < 0:
        return None
    at = found - 4
    while at < end:  # the chunks from the eXIf on: each length must lead to the next, and the last to IEND
        at += 12 + int.from_bytes(tail[at : at + 4], "big")
    return tail[found + 4 : found + 4 + int.from_bytes(tail[found - 4 : found], "big")] if at == end else None


def _png_has_chunk(path: Path, kind: bytes, *, before_pixels: bool = False) -> bool:
    """Whether walking a PNG's chunks by their lengths from its start meets a ``kind`` chunk (before IEND, or
    with ``before_pixels`` before the first IDAT: where acTL must be, PNG specification, Sec. 11.3.4)."""
    with contextlib.suppress(OSError), open(path, "rb") as f:
        f.seek(8)
        while len(chunk := f.read(8)) == 8:
            if chunk[4:] == kind:
                return True
            if chunk[4:] == b"IEND" or (before_pixels and chunk[4:] == b"IDAT"):
                return False
            f.seek(int.from_bytes(chunk[:4], "big") + 4, os.SEEK_CUR)
    return False


#: JPEG markers that start a frame (SOF0-SOF15 but DHT, JPG and DAC): progressive for SOF2, 6, 10, 14.
_JPEG_FRAMES = frozenset(range(0xC0, 0xD0)) - {0xC4, 0xC8, 0xCC}
#: The most scans a JPEG may have: libjpeg-turbo's suggested limit for untrusted files (its ``-maxscans``).
MAX_JPEG_SCANS = 500
#: A marker after entropy-coded data: 0xFF (and fill bytes 0xFF) then neither 0x00 (a stuffed byte) nor RST0-7.
_JPEG_MARKER = re.compile(rb"\xff+[^\x00\xd0-\xd7\xff]")


def _check_jpeg_scans(path: Path) -> None:
    """Refuse a JPEG whose scans repeat (or exceed ``MAX_JPEG_SCANS``) before any decoding.

    A progressive JPEG refines each coefficient of each component once per bit
    (ITU-T T.81, Sec. G.1.1.1: a first scan with Ah = 0, then each refinement's Ah is
    the previous scan's Al); a sequential JPEG codes each component in one scan.
    libjpeg decodes a scan that breaks this order anyway (it warns "Inconsistent
    progression sequence") and each scan costs a pass over every block of the image,
    so a small file of repeated scans decoded for minutes. The markers are walked
    from the frame header on: each scan's components (Cs), its spectral band
    (Ss..Se) and bits (Ah, Al) are checked against what came before.

    Raises
    ------
    InvalidImageError
        A scan repeats what an earlier one coded, or the file has more than
        ``MAX_JPEG_SCANS`` scans: one line.
    """
    try:
        data = path.read_bytes()
    except OSError:
        return  # the decode says why
    pos, progressive, ids = 2, False, []
    coded: dict[int, list[int]] = {}  # component id: the next bit expected of each coefficient (-1: not yet coded)
    scans = 0
    while pos + 4 <= len(data):
        if data[pos] != 0xFF:
            return  # not a marker where one should be: the decoder says what is wrong
        marker = data[pos + 1]
        if marker == 0xFF:  # a fill byte before the marker
            pos += 1
            continue
        if marker in (0xD8, 0x01) or 0xD0 <= marker <= 0xD7:
            pos += 2
            continue
        if marker == 0xD9:  # EOI
            return
        length = int.from_bytes(data[pos + 2 : pos + 4], "big")
        segment = data[pos + 4 : pos + 2 + length]
        if marker in _JPEG_FRAMES and len(segment) >= 6:
            progressive = marker in (0xC2, 0xC6, 0xCA, 0xCE)
            ids = [segment[6 + 3 * k] for k in range(segment[5]) if 6 + 3 * k < len(segment)]
            coded = {c: [-1] * 64 for c in ids}
        if marker == 0xDA and len(segment) >= 1:
            scans += 1
            n = segment[0]
            comps = [segment[1 + 2 * k] for k in range(n) if 1 + 2 * k < len(segment)]
            tail = segment[1 + 2 * n : 4 + 2 * n]
            if len(tail) < 3:
                return
            ss, se, ah, al = tail[0], tail[1], tail[2] >> 4, tail[2] & 15
            if scans > MAX_JPEG_SCANS:
                raise InvalidImageError(
                    f"{path}: not a readable image: the JPEG has more than {MAX_JPEG_SCANS} scans (a damaged or "
                    "hostile file: each scan is a pass over the whole image)"
                )
            for c in comps:
                bits = coded.get(c)
                if bits is None:
                    continue  # a component the frame does not have: the decoder refuses it
                band = range(ss, min(se, 63) + 1) if progressive else range(64)
                for k in band:
                    expected = -1 if ah == 0 else ah
                    if bits[k] != expected or (progressive and al >= (ah if ah else 99)):
                        raise InvalidImageError(
                            f"{path}: not a readable image: scan {scans} of the JPEG codes again what an earlier "
                            f"scan coded (component {c}, coefficient {k}; a damaged or hostile file)"
                        )
                    bits[k] = al
            # The entropy-coded data runs to the next marker: 0xFF followed by neither 0x00 (a stuffed
            # byte) nor a restart marker.
            found = _JPEG_MARKER.search(data, pos + 2 + length)
            if found is None:
                return
            at = found.end() - 2
            pos = at
            continue
        pos += 2 + length


def _float_image_size(path: Path) -> tuple[int, int, str] | None:
    """(width, height, format) of a Radiance HDR or a PFM file from its header (Pillow reads neither), else None.

    Radiance: text lines up to an empty one, then ``-Y H +X W`` (or another axis order); PFM:
    ``PF`` or ``Pf``, then ``W H`` (Netpbm's PFM).
    """
    try:
        with open(path, "rb") as f:
            head = f.read(4096)
    except OSError:
        return None
    if head.startswith((b"#?RADIANCE", b"#?RGBE")):
        end = head.find(b"\n\n")
        size = head[end + 2 :].split(b"\n", 1)[0].split() if end >= 0 else []
        if len(size) == 4 and size[0][1:] in (b"Y", b"X") and size[2][1:] in (b"Y", b"X"):
            with contextlib.suppress(ValueError):
                a, b = int(size[1]), int(size[3])
                return (b, a, "Radiance HDR") if size[0][1:] == b"Y" else (a, b, "Radiance HDR")
        return None
    if head[:3] in (b"PF\n", b"Pf\n", b"PF\r", b"Pf\r"):
        words = head[3:].split(None, 2)
        with contextlib.suppress(ValueError, IndexError):
            return int(words[0]), int(words[1]), "PFM"
    return None


def _exif_orientation(data: bytes) -> int:
    """The Orientation (1..8) of an EXIF block; 1 when it has none or cannot be read."""
    from PIL import Image

    try:
        exif = Image.Exif()
        exif.load(data)
        return int(exif.get(0x0112, 1))
    except Exception:  # a damaged EXIF block: as stored
        return 1


def _png_exif(path: Path) -> Image.Exif:
    """The EXIF of a PNG's eXIf chunk, before or after the pixels (empty without one), decoding nothing.

    The chunks are walked by their length fields (PNG specification, Sec. 5.3): a
    seek over each chunk's data, so a 1 GB file costs its chunk headers only.
    """
    from PIL import Image

    exif = Image.Exif()
    with open(path, "rb") as f:
        if f.read(8) != b"\x89PNG\r\n\x1a\n":
            return exif
        while len(head := f.read(8)) == 8:
            length, kind = int.from_bytes(head[:4], "big"), head[4:]
            if kind == b"eXIf":
                exif.load(f.read(length))
                return exif
            if kind == b"IEND":
                break
            f.seek(length + 4, os.SEEK_CUR)  # the data and the CRC
    return exif


def _plain_png_size(path: Path, *, pixels_first: bool = False) -> tuple[int, int] | None:
    """(width, height) of a whole PNG with neither an eXIf nor an acTL chunk, or None for any other file.

    Such a PNG has one frame and no EXIF orientation, and its IHDR chunk gives its
    size: :func:`_probe` then needs no Pillow (whose import is about 0.03 s of CPU,
    more than the rest of a 512 px PNG's reading). The chunks are walked by their
    length fields, as in :func:`_png_exif`; a file without an IEND chunk (cut short)
    is left to Pillow and OpenCV to judge. With ``pixels_first`` the walk stops at the
    first IDAT chunk (the size of a PNG with neither chunk before its pixels): a huge
    PNG's 100 000 IDAT chunks of 8 KB took 1.5 s to walk
    (an eXIf chunk after them is read from the file's end, :func:`_check_png_end`).
    """
    try:
        with open(path, "rb") as f:
            head = f.read(24)
            if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
                return None
            size = int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")
            f.seek(8)
            while len(chunk := f.read(8)) == 8:
                length, kind = int.from_bytes(chunk[:4], "big"), chunk[4:]
                if kind in (b"eXIf", b"acTL"):  # EXIF, or an animation: Pillow reads them
                    return None
                if kind == b"IEND" or (pixels_first and kind == b"IDAT"):
                    return size
                f.seek(length + 4, os.SEEK_CUR)  # the data and the CRC
    except OSError:
        return None
    return None


def _png_size(path: Path) -> tuple[int, int] | None:
    """(width, height) from a PNG's IHDR chunk (the first, by the PNG specification), or None."""
    try:
        with open(path, "rb") as f:
            head = f.read(24)
    except OSError:
        return None
    if len(head) < 24 or head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        return None
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


def _too_many_pixels(path: Path, size: str, max_pixels: int) -> str:
    return (
        f"{path}: image is {size}, more than the limit of {max_pixels:,} px "
        "(a guard against decompression bombs; downscale it first)"
    )


def _quiet_opencv() -> None:
    """Silence OpenCV's log lines (``[ WARN:0@...] ...``) on standard error, once."""
    import cv2

    global _OPENCV_QUIET
    if not _OPENCV_QUIET:
        with contextlib.suppress(AttributeError, cv2.error):
            cv2.utils.logging.setLogLevel(cv2.utils.logging.LOG_LEVEL_SILENT)
        _OPENCV_QUIET = True


_OPENCV_QUIET = False


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
    val = _to_unit(arr, name)
    channels = val.shape[2]
    has_alpha = channels in (2, 4)
    alpha = val[:, :, -1].copy() if has_alpha else np.ones(val.shape[:2])
    colour = val[:, :, : channels - 1] if has_alpha else val
    if colour.shape[2] == 1:
        colour = np.repeat(colour, 3, axis=2)
    elif bgr:
        colour = colour[:, :, ::-1]
    if has_alpha:
        rgb = colour * alpha[:, :, None] + (1.0 - alpha[:, :, None])
    else:  # alpha 1 everywhere: colour * 1 + 0, the same bits (+ 0.0 turns a -0.0 into 0.0 as that did)
        rgb = colour + 0.0
    return np.ascontiguousarray(rgb), alpha, has_alpha
