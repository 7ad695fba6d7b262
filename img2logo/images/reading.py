"""Reading an image file into an array: libvips (shrink-on-load), Pillow, OpenCV, each where it reads best.

:func:`read_file` is what :func:`img2logo.images.loading.load_image` and ``load_mask`` call on a path;
the headers of untrusted files are checked first (:mod:`img2logo.images.file_checks`).
"""

from __future__ import annotations

import contextlib
import os
import re
import sys
import warnings
from collections.abc import Iterator
from pathlib import Path
from typing import IO, TYPE_CHECKING, Any

import numpy as np

from ..constants import MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE
from ..errors import ImageNotFoundError, InvalidImageError
from .constants import DOWNSCALE_STRIP_ROWS, MAX_FLOAT_IMAGE_PIXELS, MIN_IMAGE_SIDE
from .file_checks import check_jpeg_scans, check_png_end, check_tiff_strips, png_has_chunk, probe, too_many_pixels

if TYPE_CHECKING:
    from PIL import Image

#: Files of at least this many bytes (with an ASCII name) are decoded by OpenCV from the file, not from
#: their bytes read into memory first: its decoders stream a file.
STREAM_DECODE_BYTES = 64 << 20


class PageWarning(UserWarning):
    """An input file holds several pages (a multi-page TIFF); only the first is used."""


def working_size(w: int, h: int, max_side: int, name: str) -> tuple[int, int]:
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


def read_file(path: Path, *, max_side: int = MAX_IMAGE_SIDE, max_pixels: int = MAX_IMAGE_PIXELS) -> tuple:
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
    header = probe(path, max_pixels, max_side)
    floats = _float_image_size(path)
    if floats is not None and floats[0] * floats[1] > min(max_pixels, MAX_FLOAT_IMAGE_PIXELS):
        fw, fh, kind = floats
        if fw * fh > max_pixels:
            raise InvalidImageError(too_many_pixels(path, f"{fw}x{fh} px", max_pixels))
        raise InvalidImageError(
            f"{path}: image is {fw}x{fh} px of floating-point samples ({kind}); such a file is decoded whole, "
            f"so img2logo reads it up to {MAX_FLOAT_IMAGE_PIXELS:,} px (its memory limit): downscale it first"
        )
    flags = cv2.IMREAD_UNCHANGED  # the pixels as stored: EXIF orientation is applied below
    orientation = 1
    if header is not None:
        w, h, pages, fmt, orientation = header
        working_size(w, h, max_side, str(path))
        if pages > 1:
            warnings.warn(f"{path}: the file has {pages} pages; only the first is used", PageWarning, stacklevel=3)
        if fmt == "PNG":
            exif_after = check_png_end(path)
            if exif_after is not None and orientation == 1:
                orientation = _exif_orientation(exif_after)
        elif fmt in ("JPEG", "MPO"):
            check_jpeg_scans(path)
        elif fmt == "TIFF":
            check_tiff_strips(path)
        factor = max([f for f in (2, 4, 8) if max(w, h) / f >= max_side], default=1)
        if fmt in ("JPEG", "MPO") and factor > 1:
            reduced = {2: cv2.IMREAD_REDUCED_COLOR_2, 4: cv2.IMREAD_REDUCED_COLOR_4, 8: cv2.IMREAD_REDUCED_COLOR_8}
            flags = reduced[factor] | cv2.IMREAD_IGNORE_ORIENTATION
        small = None
        # An animated PNG (an acTL chunk) is read as its default image, the IDAT's, by libvips: OpenCV
        # composes its first frame from the fcTL chunks and gave a damaged one's as all black.
        animated = fmt == "PNG" and (pages > 1 or png_has_chunk(path, b"acTL", before_pixels=True))
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
            raise InvalidImageError(too_many_pixels(path, f"{w}x{h} px", max_pixels))
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
    """Hold standard error (file descriptor 2) in an anonymous file (:func:`_anonymous_file`) while a C decoder runs.

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
    hold = _anonymous_file()
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


def _anonymous_file() -> IO[bytes]:
    """A file without a name, read and written as bytes: in memory (``memfd_create``) where the system has it.

    Elsewhere (or if the call fails) a temporary file; :mod:`tempfile` (with :mod:`random`) is imported only
    then, not by every run of the command.
    """
    if hasattr(os, "memfd_create"):
        try:
            return os.fdopen(os.memfd_create("img2logo-stderr", os.MFD_CLOEXEC), "w+b")
        except OSError:  # no memfd in this kernel (or a sandbox refuses it)
            pass
    import tempfile

    return tempfile.TemporaryFile()


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


def _quiet_opencv() -> None:
    """Silence OpenCV's log lines (``[ WARN:0@...] ...``) on standard error, once."""
    import cv2

    global _OPENCV_QUIET
    if not _OPENCV_QUIET:
        with contextlib.suppress(AttributeError, cv2.error):
            cv2.utils.logging.setLogLevel(cv2.utils.logging.LOG_LEVEL_SILENT)
        _OPENCV_QUIET = True


_OPENCV_QUIET = False
