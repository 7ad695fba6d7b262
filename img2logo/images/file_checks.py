"""Checks of an untrusted image file's header before it is decoded: its size, its strips, scans and end.

Each refuses, with a one-line :class:`~img2logo.errors.InvalidImageError`, a file whose decoding would
blow the memory bound or run for long (a decompression bomb, a progressive JPEG of thousands of scans,
a TIFF in one strip of the whole image), reading only the bytes it needs.
"""

from __future__ import annotations

import contextlib
import os
import re
import warnings
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import InvalidImageError
from .constants import MAX_WHOLE_TIFF_BYTES

if TYPE_CHECKING:
    from PIL import Image


def probe(path: Path, max_pixels: int, max_side: int | None = None) -> tuple[int, int, int, str, int] | None:
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
            raise InvalidImageError(too_many_pixels(path, f"{w}x{h} px", max_pixels))
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
            raise InvalidImageError(too_many_pixels(path, "over 178 Mpx", max_pixels)) from exc
        except Exception:  # not a format Pillow knows, or a damaged header: OpenCV decides
            size = _png_size(path)
            if size is None:
                return None
            (w, h), pages, fmt, orientation = size, 1, "PNG", 1
    if w * h > max_pixels:
        raise InvalidImageError(too_many_pixels(path, f"{w}x{h} px", max_pixels))
    return w, h, pages, fmt, orientation


def check_tiff_strips(path: Path) -> None:
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


def check_png_end(path: Path) -> bytes | None:
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
    if end < 0 and not png_has_chunk(path, b"IEND"):
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


def png_has_chunk(path: Path, kind: bytes, *, before_pixels: bool = False) -> bool:
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


def check_jpeg_scans(path: Path) -> None:
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
    size: :func:`probe` then needs no Pillow (whose import is about 0.03 s of CPU,
    more than the rest of a 512 px PNG's reading). The chunks are walked by their
    length fields, as in :func:`_png_exif`; a file without an IEND chunk (cut short)
    is left to Pillow and OpenCV to judge. With ``pixels_first`` the walk stops at the
    first IDAT chunk (the size of a PNG with neither chunk before its pixels): a huge
    PNG's 100 000 IDAT chunks of 8 KB took 1.5 s to walk
    (an eXIf chunk after them is read from the file's end, :func:`check_png_end`).
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


def too_many_pixels(path: Path, size: str, max_pixels: int) -> str:
    return (
        f"{path}: image is {size}, more than the limit of {max_pixels:,} px "
        "(a guard against decompression bombs; downscale it first)"
    )
