"""A large TIFF decoded a band of rows at a time and box-reduced, so that the full-size image is never in memory.

OpenCV decodes a 12000 x 12000 px 16-bit RGBA TIFF whole: 1.15 GB of pixels and, at its peak,
3.35 GB (measured, issue 20 item 12). Here the first image file directory (IFD) is read
(TIFF 6.0, Sec. 2; BigTIFF too), and for each band of strips (or row of tiles) a small TIFF
is made in memory: the same tags, but the band's height and only the band's strips (a row of
tiles becomes its tiles stacked one above the other, each a strip: OpenCV 5.1 fails to read
8-bit tiles from memory; separate planes are decoded one at a time: it decodes 16-bit ones
wrongly, measured). OpenCV
(libtiff) decodes it, the same decoder with the same tags as the whole file's decode, so a
band's pixels are those rows of the whole image to the bit, whatever the compression (none,
LZW, deflate, PackBits), the predictor, the planar configuration, the byte order, the bit
depth or the photometric interpretation (grey, RGB, a palette). A row of tiles is decoded a
few tiles a call (at most half of ``PNG_STRIP_BYTES``) into one of four band buffers used in
turn, and reduced there at the tiles' padded pitch: the whole row's decode and its reordered
copy (49 MB each for a 12000 px 16-bit RGBA image), fresh every row, cost 3.2 s of page faults
(measured). The bands are decoded by a thread of their own (OpenCV releases the GIL) while the compiled box reduce of
:mod:`img2logo._compiled.png` (the PNG path's: colour averaged premultiplied by alpha, as
``PIL.Image.reduce``) works on the one before.

Why OpenCV and not ``tifffile`` (installed, a dependency of scikit-image): without
``imagecodecs`` tifffile has no LZW decoder at all (the commonest TIFF compression, OpenCV's
default) and decodes PackBits in pure Python; libtiff through OpenCV decodes every one, is
the whole-image path's own decoder, and needs no new dependency. Pillow's decoders driven per
strip would lean on its private tile API and decode 16-bit colour to 8 bits.

Not done here (None: OpenCV decodes the file whole, as before): a compression other than
those four (JPEG-in-TIFF among them); a compressed strip or tile row of more than four
bands' bytes (one compressed strip of the whole image); separate planes other than RGB(A);
samples other than 8 or 16-bit integers (floating point).
"""

from __future__ import annotations

import io
import math
import struct
import sys
import threading
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import BinaryIO

import numpy as np

from ..constants import PNG_STRIP_BYTES
from ..errors import InvalidImageError

#: Compressions decoded band by band: none, LZW, deflate (Adobe's and the old code), PackBits.
COMPRESSIONS = (1, 5, 8, 32946, 32773)
#: Tags copied into each band's TIFF: what libtiff needs to decode the pixels (TIFF 6.0, Sec. 8).
_KEEP = (256, 258, 259, 262, 266, 277, 284, 317, 320, 322, 323, 338, 339)
#: Bytes of one value of each TIFF field type (1 BYTE ... 12 DOUBLE, 16-18 BigTIFF's 8-byte ones).
_TYPE_BYTES = {1: 1, 2: 1, 3: 2, 4: 4, 5: 8, 6: 1, 7: 1, 8: 2, 9: 4, 10: 8, 11: 4, 12: 8, 13: 4, 16: 8, 17: 8, 18: 8}
_INTS = {1: "B", 3: "H", 4: "I", 16: "Q", 13: "I", 18: "Q"}
_STRIP_OFFSETS, _STRIP_COUNTS, _TILE_OFFSETS, _TILE_COUNTS = 273, 279, 324, 325
#: Threads decoding bands (libtiff's inflating, which releases the GIL, is most of the time), and
#: the bands they decode ahead of the one being reduced: each band's buffer is one of ``_AHEAD + 1``.
_WORKERS, _AHEAD = 2, 3


@dataclass(frozen=True)
class _Layout:
    """The first IFD of a TIFF: what the bands are made of.

    Attributes
    ----------
    order : str
        ``"<"`` (II, little-endian) or ``">"`` (MM).
    width, height : int
        Of the image, px.
    rows : int
        Rows of a strip or of a tile row (RowsPerStrip, or TileLength).
    tiled : bool
        Tiles, not strips.
    planes : int
        Separate sample planes (PlanarConfiguration 2: SamplesPerPixel), else 1.
    offsets, counts : ndarray of int64
        The strips' (tiles') byte offsets and byte counts, in the file's order.
    tags : dict
        Tag: (type, count, raw value bytes) of the tags in ``_KEEP`` the file has.
    row_bytes : int
        Bytes of one row of one strip uncompressed (for an uncompressed file's split strips).
    """

    order: str
    width: int
    height: int
    rows: int
    tiled: bool
    planes: int
    offsets: np.ndarray
    counts: np.ndarray
    tags: dict
    row_bytes: int


def _fields(f: BinaryIO) -> tuple[str, dict[int, tuple[int, int, bytes]]] | None:
    """An open TIFF's byte order and first IFD's tags (tag: (type, count, raw value bytes)); None if unreadable."""
    head = f.read(16)
    if len(head) < 8 or head[:2] not in (b"II", b"MM"):
        return None
    order = "<" if head[:2] == b"II" else ">"
    magic = struct.unpack(order + "H", head[2:4])[0]
    if magic == 42:
        big, first = False, struct.unpack(order + "I", head[4:8])[0]
    elif magic == 43 and len(head) == 16:
        big, first = True, struct.unpack(order + "Q", head[8:16])[0]
    else:
        return None
    f.seek(first)
    n_bytes, entry = (8, 20) if big else (2, 12)
    raw = f.read(n_bytes)
    if len(raw) < n_bytes:
        return None
    n = struct.unpack(order + ("Q" if big else "H"), raw)[0]
    table = f.read(n * entry)
    if n == 0 or len(table) < n * entry:
        return None
    fields: dict[int, tuple[int, int, bytes]] = {}
    inline = 8 if big else 4
    for i in range(n):
        e = table[i * entry : (i + 1) * entry]
        tag, kind = struct.unpack(order + "HH", e[:4])
        count = struct.unpack(order + ("Q" if big else "I"), e[4 : 4 + (8 if big else 4)])[0]
        size = _TYPE_BYTES.get(kind, 0) * count
        if size == 0 or count > 1 << 28:
            continue
        value = e[4 + (8 if big else 4) :]
        if size > inline:
            at = struct.unpack(order + ("Q" if big else "I"), value)[0]
            f.seek(at)
            value = f.read(size)
            if len(value) < size:
                return None
        fields[tag] = (kind, count, value[:size])
    return order, fields


def _ints(order: str, fields: dict[int, tuple[int, int, bytes]], tag: int) -> np.ndarray | None:
    """A tag's integer values (int64), None when the IFD has no such integer tag."""
    if tag not in fields or fields[tag][0] not in _INTS:
        return None
    kind, count, value = fields[tag]
    return np.frombuffer(value, dtype=order + _INTS[kind], count=count).astype(np.int64)


def sample_bytes(path: Path) -> int | None:
    """Bytes of a TIFF's decoded samples (width x height x a pixel's bits / 8), from its first IFD; None if unreadable.

    What a decoder that decodes the file whole holds at least once
    (:func:`img2logo.images.loading.load_image` bounds it for the layouts this module
    does not decode a band at a time).
    """
    try:
        with open(path, "rb") as f:
            read = _fields(f)
    except (OSError, struct.error, ValueError):
        return None
    if read is None:
        return None
    order, fields = read
    width, height = _ints(order, fields, 256), _ints(order, fields, 257)
    spp, bits = _ints(order, fields, 277), _ints(order, fields, 258)
    if width is None or height is None or not width.size or not height.size:
        return None
    samples = int(spp[0]) if spp is not None and spp.size else 1
    if bits is None or not bits.size:
        depth = samples  # BitsPerSample's default: 1
    elif bits.size >= samples:
        depth = int(bits[:samples].sum())
    else:
        depth = int(bits[0]) * samples
    return int(width[0]) * int(height[0]) * depth // 8


def _layout(f: BinaryIO) -> _Layout | None:
    """Read the first IFD of an open TIFF; None if it is not one this module decodes (or not readable)."""
    read = _fields(f)
    if read is None:
        return None
    order, fields = read

    def ints(tag: int) -> np.ndarray | None:
        return _ints(order, fields, tag)

    def one(tag: int, default: int | None = None) -> int | None:
        v = ints(tag)
        return default if v is None or v.size == 0 else int(v[0])

    width, height = one(256), one(257)
    compression, planar, spp = one(259, 1), one(284, 1), one(277, 1)
    bits = ints(258)
    tiled = _TILE_OFFSETS in fields
    offsets = ints(_TILE_OFFSETS if tiled else _STRIP_OFFSETS)
    counts = ints(_TILE_COUNTS if tiled else _STRIP_COUNTS)
    rows = one(323) if tiled else one(278, height)
    if width is None or height is None or width <= 0 or height <= 0 or offsets is None or counts is None:
        return None
    if compression not in COMPRESSIONS or planar not in (1, 2) or spp is None or not 1 <= spp <= 8 or rows is None:
        return None
    rows = min(max(1, rows), height) if not tiled else rows
    planes = spp if planar == 2 and spp > 1 else 1
    if planes > 1 and (one(262) != 2 or spp not in (3, 4)):
        return None  # separate planes: RGB and RGBA only
    tile_w = int(one(322, 0) or 0)
    if tiled and (tile_w <= 0 or rows <= 0 or tile_w % 16 or rows % 16):
        return None
    across = -(-width // tile_w) if tiled else 1
    per_plane = across * -(-height // rows)
    if offsets.size < per_plane * planes or counts.size < per_plane * planes:
        return None
    depth = int(bits.sum()) if bits is not None and planes == 1 else int(bits[0]) if bits is not None else 1
    row_bytes = (width * depth + 7) // 8
    tags = {t: fields[t] for t in _KEEP if t in fields}
    if any(kind in (16, 17, 18) for kind, _, _ in tags.values()):
        return None  # BigTIFF's 8-byte types in a tag kept: not in a classic TIFF
    return _Layout(order, width, height, rows, tiled, planes, offsets[: per_plane * planes], counts, tags, row_bytes)


def _split(layout: _Layout, compression: int) -> _Layout:
    """An uncompressed file's strips split into strips of at most a band's bytes: the same rows, addressable alone.

    The new strip height divides the old one, so that every strip but the image's last
    has the same height (as RowsPerStrip says).
    """
    if compression != 1 or layout.tiled or layout.rows * layout.row_bytes <= PNG_STRIP_BYTES:
        return layout
    most = max(1, PNG_STRIP_BYTES // max(1, layout.row_bytes))
    rows = max(d for d in range(1, min(most, layout.rows) + 1) if layout.rows % d == 0)
    per_plane = -(-layout.height // layout.rows)
    offsets, counts = [], []
    for p in range(layout.planes):
        for s in range(per_plane):
            first = s * layout.rows
            for r in range(first, min(layout.height, first + layout.rows), rows):
                offsets.append(int(layout.offsets[p * per_plane + s]) + (r - first) * layout.row_bytes)
                counts.append(min(rows, layout.height - r) * layout.row_bytes)
    return _Layout(
        layout.order,
        layout.width,
        layout.height,
        rows,
        False,
        layout.planes,
        np.array(offsets, dtype=np.int64),
        np.array(counts, dtype=np.int64),
        layout.tags,
        layout.row_bytes,
    )


def _band_tiff(
    layout: _Layout, f: io.BufferedReader, first: int, stop: int, path: Path, plane: int | None = None
) -> np.ndarray:
    """A classic TIFF of rows ``first`` .. ``stop`` (strip or tile-row bounds) of the image: its tags, its data (uint8).

    With ``plane`` (a file of separate planes), that plane alone, as a grey image: OpenCV
    decodes 16-bit separate planes wrongly (5.1: garbage, measured), one plane rightly.
    """
    o = layout.order
    across = -(-layout.width // _tag_int(layout, 322)) if layout.tiled else 1
    per_plane = across * -(-layout.height // layout.rows)
    index: list[int] = []
    for p in range(layout.planes) if plane is None else (plane,):
        for k in range(first // layout.rows, -(-stop // layout.rows)):
            index.extend(p * per_plane + k * across + j for j in range(across))
    lengths = [int(layout.counts[i]) if i < layout.counts.size else -1 for i in index]
    if min(lengths) < 0 or sum(lengths) > 1 << 31:
        raise InvalidImageError(f"{path}: not a readable image: the TIFF's strip sizes are damaged")
    entries = dict(layout.tags)
    if plane is not None:  # one sample a pixel, grey
        for tag in (258, 339):
            if tag in entries:
                kind, _, value = entries[tag]
                entries[tag] = (kind, 1, value[: _TYPE_BYTES[kind]])
        entries.pop(338, None)
        entries.pop(320, None)
        entries[277] = (3, 1, struct.pack(o + "H", 1))
        entries[284] = (3, 1, struct.pack(o + "H", 1))
        entries[262] = (3, 1, struct.pack(o + "H", 1))
    n = len(index)
    entries[257] = (4, 1, struct.pack(o + "I", stop - first))
    if layout.tiled:  # the row's tiles stacked, each a strip: OpenCV's tile reading fails in memory (5.1, 8 bits)
        entries[256] = (4, 1, struct.pack(o + "I", _tag_int(layout, 322)))
        entries[257] = (4, 1, struct.pack(o + "I", layout.rows * n // (1 if plane is not None else layout.planes)))
        del entries[322], entries[323]
    entries[278] = (4, 1, struct.pack(o + "I", layout.rows))
    entries[_STRIP_OFFSETS] = (4, n, b"")  # filled below
    entries[_STRIP_COUNTS] = (4, n, struct.pack(f"{o}{n}I", *lengths))
    ifd_size = 2 + 12 * len(entries) + 4
    extra = sum(len(v) + (len(v) & 1) for t, (_, _, v) in entries.items() if len(v) > 4)
    extra += 4 * n if 4 * n > 4 else 0
    start = 8 + ifd_size + extra
    positions = np.cumsum([start, *lengths[:-1]]).tolist()
    offsets_value = struct.pack(f"{o}{n}I", *positions)
    entries[_STRIP_OFFSETS] = (4, n, offsets_value)
    head = (b"II" if o == "<" else b"MM") + struct.pack(o + "HI", 42, 8)
    table = [struct.pack(o + "H", len(entries))]
    values = []
    at = 8 + ifd_size
    for tag in sorted(entries):
        kind, count, value = entries[tag]
        if len(value) > 4:
            table.append(struct.pack(o + "HHII", tag, kind, count, at))
            padded = value + b"\0" * (len(value) & 1)
            values.append(padded)
            at += len(padded)
        else:
            table.append(struct.pack(o + "HHI", tag, kind, count) + value.ljust(4, b"\0"))
    table.append(b"\0\0\0\0")
    header = b"".join([head, *table, *values])
    out = np.empty(len(header) + sum(lengths), dtype=np.uint8)
    out[: len(header)] = np.frombuffer(header, dtype=np.uint8)
    view, at, k = out.data, len(header), 0
    while k < len(index):  # runs of strips that follow each other in the file: one read each
        j, begin = k + 1, int(layout.offsets[index[k]])
        end = begin + lengths[k]
        while j < len(index) and int(layout.offsets[index[j]]) == end:
            end += lengths[j]
            j += 1
        f.seek(begin)
        if f.readinto(view[at : at + end - begin]) < end - begin:
            raise InvalidImageError(
                f"{path}: not a readable image: its pixel data ends before the last row "
                f"(row {first + 1} of {layout.height}; the file cut short?)"
            )
        at += end - begin
        k = j
    return out


def _untile(stacked: np.ndarray | None, layout: _Layout, rows: int) -> np.ndarray | None:
    """A row of tiles decoded stacked (one above the other) as the band it is: (rows, width[, C])."""
    tile_w = _tag_int(layout, 322)
    across = -(-layout.width // tile_w)
    if stacked is None or stacked.shape[0] % (across * layout.rows) or stacked.shape[1] != tile_w:
        return None
    k = stacked.shape[0] // (across * layout.rows)
    tiles = stacked.reshape(k, across, layout.rows, tile_w, -1).transpose(0, 2, 1, 3, 4)
    band = tiles.reshape(k * layout.rows, across * tile_w, -1)[:rows, : layout.width]
    return np.ascontiguousarray(band if stacked.ndim == 3 else band[:, :, 0])


def _flat_rows(rows: np.ndarray) -> tuple[np.ndarray, int]:
    """Rows of pixels (R, W, C) as the kernel reads them: their bytes (uint8, 1-D) and the bytes from a row to the next.

    Rows of a wider buffer (a tiled band's, the tiles' padded width) are read in place
    where each row's pixels are contiguous; anything else is copied first.
    """
    item = rows.dtype.itemsize
    if rows.strides[1:] != (rows.shape[2] * item, item) or rows.strides[0] < rows.shape[1] * rows.shape[2] * item:
        rows = np.ascontiguousarray(rows)
    pitch = rows.strides[0]
    size = (len(rows) - 1) * pitch + rows.shape[1] * rows.shape[2] * item
    flat = np.lib.stride_tricks.as_strided(rows.view(np.uint8), shape=(size,), strides=(1,))
    return flat, pitch


def _tag_int(layout: _Layout, tag: int) -> int:
    kind, _, value = layout.tags[tag]
    return int(np.frombuffer(value, dtype=layout.order + _INTS[kind], count=1)[0])


class _Bands:
    """The bands of rows decoded by OpenCV in threads of their own, a few ahead: (first row, array).

    Worker ``w`` decodes bands ``w``, ``w + _WORKERS``, ...; band ``i`` is begun once the
    reading thread has asked for band ``i - _AHEAD`` (so it is done with band
    ``i - _AHEAD - 1``, whose tiled band buffer ``i`` then reuses). libtiff's inflating is
    most of the time (a 12000 px 16-bit RGBA deflate TIFF: 9.1 s of 13 s of CPU, the reduce
    4 s, measured): one decoding thread kept the second core half idle.
    """

    def __init__(self, path: Path, layout: _Layout, bounds: list[tuple[int, int]]) -> None:
        self._cv = threading.Condition()
        self._done: dict[int, object] = {}  # band index: (first row, array) or the exception decoding it raised
        self._taken = 0  # bands the reading thread has asked for
        self._stop = False
        self._pool: list[np.ndarray | None] = [None] * (_AHEAD + 1)  # the tiled bands' buffers, reused in turn
        self._n = len(bounds)
        self._threads = [
            threading.Thread(target=self._run, args=(path, layout, bounds, w), name="img2logo-tiff", daemon=True)
            for w in range(min(_WORKERS, self._n))
        ]
        for t in self._threads:
            t.start()

    def _run(self, path: Path, layout: _Layout, bounds: list[tuple[int, int]], worker: int) -> None:
        import cv2

        i = worker
        try:
            with open(path, "rb") as f:
                for i in range(worker, self._n, _WORKERS):
                    with self._cv:
                        self._cv.wait_for(lambda i=i: self._stop or i < self._taken + _AHEAD)  # type: ignore[misc]
                        if self._stop:
                            return
                    first, stop = bounds[i]
                    if layout.tiled and layout.planes == 1:
                        band = self._tile_row(cv2, path, layout, f, first, stop, self._pool, i)
                    else:
                        band = self._strips(cv2, path, layout, f, first, stop)
                    if band is None or band.shape[:2] != (stop - first, layout.width):
                        raise InvalidImageError(
                            f"{path}: not a readable image: its pixel data is damaged "
                            f"(rows {first + 1} to {stop} of {layout.height} cannot be decoded)"
                        )
                    self._hand(i, (first, band))
        except BaseException as exc:  # handed to the reading thread, which raises it
            self._hand(i, exc)

    def _hand(self, i: int, item: object) -> None:
        with self._cv:
            self._done[i] = item
            self._cv.notify_all()

    @staticmethod
    def _strips(
        cv2: object, path: Path, layout: _Layout, f: io.BufferedReader, first: int, stop: int
    ) -> np.ndarray | None:
        """A band of strips (or a row of tiles of separate planes) decoded: (rows, width[, C]), or None."""
        planes = []
        for plane in range(layout.planes) if layout.planes > 1 else (None,):
            tiff = _band_tiff(layout, f, first, stop, path, plane)
            try:
                planes.append(cv2.imdecode(tiff, cv2.IMREAD_UNCHANGED))  # type: ignore[attr-defined]
            except cv2.error:  # type: ignore[attr-defined]
                planes.append(None)
            del tiff
        if layout.tiled:  # (tiles x tile rows, tile width, C) to the band's rows and columns
            planes = [_untile(q, layout, stop - first) for q in planes]
        band = planes[0]
        if layout.planes > 1 and all(q is not None and q.ndim == 2 for q in planes):
            order = [2, 1, 0, *range(3, len(planes))]  # OpenCV's order: blue first
            band = np.dstack([planes[k] for k in order])
        return band

    @staticmethod
    def _tile_row(
        cv2: object,
        path: Path,
        layout: _Layout,
        f: io.BufferedReader,
        first: int,
        stop: int,
        pool: list[np.ndarray | None],
        i: int,
    ) -> np.ndarray | None:
        """A row of tiles decoded a few tiles a call into a reused buffer: (rows, width, C), a view of it; or None.

        A whole row's decode (a 12000 px 16-bit RGBA image's: 49 MB) and its reordering
        into rows are fresh allocations, larger than glibc's mmap threshold (32 MB at most):
        every page of them faulted in anew (3.2 s of system time, measured). A few tiles'
        decode (``PNG_STRIP_BYTES // 2`` at most) is reused by the allocator, and the band
        is written in place into one of ``_AHEAD + 1`` buffers of the padded row (the tiles'
        whole width), taken in turn (see :class:`_Bands`: that buffer's band before is reduced).
        """
        tile_w = _tag_int(layout, 322)
        across = -(-layout.width // tile_w)
        group = max(1, (PNG_STRIP_BYTES // 2) // max(1, layout.rows * tile_w * (layout.row_bytes // layout.width or 1)))
        tall = -(-(stop - first) // layout.rows) * layout.rows  # whole tile rows
        buf: np.ndarray | None = pool[i % len(pool)]
        offsets = layout.offsets.reshape(-1, across)
        counts = layout.counts[: layout.offsets.size].reshape(-1, across)
        for top in range(first, stop, layout.rows):
            at = top - first
            for j in range(0, across, group):
                k = min(group, across - j)
                part = _Layout(
                    layout.order,
                    k * tile_w,
                    layout.height,
                    layout.rows,
                    True,
                    1,
                    offsets[:, j : j + k].reshape(-1),
                    counts[:, j : j + k].reshape(-1),
                    layout.tags,
                    layout.row_bytes,
                )
                tiff = _band_tiff(part, f, top, min(stop, top + layout.rows), path)
                try:
                    q = cv2.imdecode(tiff, cv2.IMREAD_UNCHANGED)  # type: ignore[attr-defined]
                except cv2.error:  # type: ignore[attr-defined]
                    return None
                if q is None or q.shape[:2] != (k * layout.rows, tile_w):
                    return None
                q = q.reshape(k, layout.rows, tile_w, -1)
                if buf is None or buf.shape[0] < tall or buf.shape[2] != q.shape[3] or buf.dtype != q.dtype:
                    buf = np.empty((tall, across * tile_w, q.shape[3]), dtype=q.dtype)
                    pool[i % len(pool)] = buf
                tiles = buf[at : at + layout.rows].reshape(layout.rows, across, tile_w, -1)
                tiles[:, j : j + k] = q.transpose(1, 0, 2, 3)
        if buf is None:
            return None
        band = buf[: stop - first, : layout.width]
        return band if band.shape[2] > 1 else band[:, :, 0]

    def __iter__(self) -> Iterator[tuple[int, np.ndarray]]:
        for i in range(self._n):
            with self._cv:
                self._taken = i + 1  # done with band i - 1: its buffer may be reused
                self._cv.notify_all()
                self._cv.wait_for(lambda i=i: i in self._done)  # type: ignore[misc]
                item = self._done.pop(i)
            if isinstance(item, BaseException):
                raise item
            yield item  # type: ignore[misc]

    def close(self) -> None:
        """Stop the decoding threads (after their current band) and wait for them."""
        with self._cv:
            self._stop = True
            self._cv.notify_all()
        for t in self._threads:
            t.join()


def read_tiff_reduced(path: Path, factor: int) -> np.ndarray | None:
    """The first image of a TIFF box-reduced by ``factor``, decoded a band at a time; as OpenCV gives it, or None.

    Parameters
    ----------
    path : Path
        A TIFF file (little- or big-endian, classic or BigTIFF).
    factor : int
        The box side, px (>= 1): output pixel (i, j) is the mean of the input's
        pixels in rows ``factor * i ..`` and columns ``factor * j ..`` (fewer at the
        right and bottom edges), colour premultiplied by alpha, as ``PIL.Image.reduce``.

    Returns
    -------
    ndarray, shape (ceil(H / factor), ceil(W / factor)) or (.., .., C), or None
        uint8 or uint16 as the file's samples, grey or BGR(A) as OpenCV decodes the
        whole file; None where this module does not decode the file (see the module's
        docstring): OpenCV then decodes it whole.

    Raises
    ------
    InvalidImageError
        The file ends before its last row, or a band's data cannot be decoded:
        one line saying so.
    """
    from .._compiled import kernels

    if not kernels.usable():
        return None
    try:
        with open(path, "rb") as f:
            layout = _layout(f)
    except (OSError, struct.error, ValueError):
        return None
    if layout is None:
        return None
    compression = _tag_int(layout, 259) if 259 in layout.tags else 1
    layout = _split(layout, compression)
    band_rows = layout.rows * max(1, PNG_STRIP_BYTES // max(1, layout.rows * layout.row_bytes * layout.planes))
    if band_rows * layout.row_bytes * layout.planes > 4 * PNG_STRIP_BYTES:
        return None  # a compressed strip of most of the image: no band is smaller than it
    both = math.lcm(layout.rows, factor)  # bands of a multiple of the factor's rows, where that is not many more
    if both * layout.row_bytes * layout.planes <= 2 * PNG_STRIP_BYTES:
        band_rows = -(-band_rows // both) * both
    bounds = [(y, min(layout.height, y + band_rows)) for y in range(0, layout.height, band_rows)]
    reduce = kernels.band_kernels(layout.height * layout.row_bytes * layout.planes)[1]
    result: np.ndarray | None = None
    carry: np.ndarray | None = None  # rows of the last band not yet reduced (fewer than ``factor``)
    done = 0  # output rows written
    little = sys.byteorder == "little"  # OpenCV's samples: the machine's order
    bands = _Bands(path, layout, bounds)
    try:
        for first, band in bands:
            if band.dtype not in (np.uint8, np.uint16):
                return None  # floating-point or 32-bit samples: OpenCV decodes the whole file
            if band.ndim == 2:
                band = band[:, :, None]
            channels = band.shape[2]
            if result is None:
                out_h, out_w = -(-layout.height // factor), -(-layout.width // factor)
                result = np.empty((out_h, out_w, channels), dtype=band.dtype)
            last = first + len(band) == layout.height
            pieces = [band]
            if last and carry is not None and len(carry) + len(band) <= factor:  # the image's last box
                pieces, carry = [np.concatenate([carry, band], axis=0)], None
            if carry is not None:  # the rows after the band before's last whole box (tiles, mostly): one box more
                need = min(factor - len(carry), len(band))
                pieces = [np.concatenate([carry, band[:need]], axis=0), band[need:]]
                carry = None
            for k, piece in enumerate(pieces):
                end = last and k == len(pieces) - 1
                whole = len(piece) if end else len(piece) // factor * factor
                if whole < len(piece):
                    carry = piece[whole:].copy() if carry is None else np.concatenate([carry, piece[whole:]], axis=0)
                if whole:
                    small = np.empty((-(-whole // factor), out_w * channels))
                    flat, pitch = _flat_rows(piece[:whole])
                    depth = 8 * piece.dtype.itemsize
                    n = reduce(
                        flat, whole, pitch, 0, layout.width, channels, depth, little, channels in (2, 4), factor, small
                    )
                    result[done : done + n] = np.rint(small).reshape(n, -1, channels)
                    done += n
            del band
    finally:
        bands.close()
    if result is None or done != result.shape[0]:
        return None
    return result[:, :, 0] if result.shape[2] == 1 else result
