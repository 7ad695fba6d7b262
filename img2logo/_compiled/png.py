"""Compiled kernels of the strip-wise PNG (and TIFF) decoding of a large input: unfiltering and the box reduce.

A PNG larger than the working size is decoded a strip of rows at a time
(:func:`img2logo.images.loading._read_png_strips`): its deflate stream is inflated by
zlib in Python, each strip's rows are unfiltered here (PNG specification, Sec. 9:
filter types None, Sub, Up, Average and Paeth, byte by byte, each row on the one
before it) and box-reduced by an integer factor here, so that the full-size image
is never in memory. The reference is Pillow's decoding and ``Image.reduce``
(averages of colour premultiplied by alpha): the tests compare the two. A large TIFF's
bands of rows, decoded by OpenCV (:mod:`img2logo.images.tiff`), are box-reduced by the same kernel.

Written in the subset of Python that numba compiles; loaded through
:mod:`img2logo._compiled.kernels` (ahead of time, or numba's JIT as a fallback); for a PNG of
at least ``PNG_NOGIL_BYTES`` of pixel data the loader takes the JIT's own, which
release the GIL (:func:`img2logo._compiled.kernels.band_kernels`).
"""

from __future__ import annotations

import numpy as np

from .jit import jit as _jit


@_jit
def png_unfilter(buf, rows, stride, bpp, prior):  # pragma: no cover - compiled
    """Undo the PNG row filters of ``rows`` rows in place; -1, or the first row whose filter type is unknown.

    ``buf`` holds the rows as inflated, each a filter-type byte and ``stride`` bytes;
    ``prior`` (``stride`` bytes, zeros before the first row of the image) is the
    unfiltered row before the first, and is overwritten with the last one. ``bpp``
    is the bytes of one pixel, rounded up to 1 (the filters' left neighbour).
    """
    pitch = stride + 1
    for r in range(rows):
        cur = buf[r * pitch + 1 : (r + 1) * pitch]
        prev = prior if r == 0 else buf[(r - 1) * pitch + 1 : r * pitch]
        kind = buf[r * pitch]
        if kind == 0:
            continue
        if kind == 1:  # Sub: the byte to the left
            for i in range(bpp, stride):
                cur[i] = (np.int64(cur[i]) + np.int64(cur[i - bpp])) & 255
        elif kind == 2:  # Up: the byte above
            for i in range(stride):
                cur[i] = (np.int64(cur[i]) + np.int64(prev[i])) & 255
        elif kind == 3:  # Average: of the left and the upper
            for i in range(min(bpp, stride)):
                cur[i] = (np.int64(cur[i]) + (np.int64(prev[i]) >> 1)) & 255
            for i in range(bpp, stride):
                cur[i] = (np.int64(cur[i]) + ((np.int64(cur[i - bpp]) + np.int64(prev[i])) >> 1)) & 255
        elif kind == 4:  # Paeth: the nearest of left, upper, upper left to left + upper - upper left
            for i in range(min(bpp, stride)):
                cur[i] = (np.int64(cur[i]) + np.int64(prev[i])) & 255
            for i in range(bpp, stride):
                a = np.int64(cur[i - bpp])
                b = np.int64(prev[i])
                c = np.int64(prev[i - bpp])
                pa = abs(b - c)
                pb = abs(a - c)
                pc = abs(a + b - 2 * c)
                if pa <= pb and pa <= pc:
                    pred = a
                elif pb <= pc:
                    pred = b
                else:
                    pred = c
                cur[i] = (np.int64(cur[i]) + pred) & 255
        else:
            return r
    if rows > 0:
        prior[:] = buf[(rows - 1) * pitch + 1 : rows * pitch]
    return -1


@_jit
def png_reduce(buf, rows, pitch, offset, width, channels, depth, little, alpha, factor, out):  # pragma: no cover
    """Box-reduce ``rows`` rows of samples by ``factor``; the number of output rows written to ``out``.

    Row ``r`` of the strip starts at ``buf[r * pitch + offset]``: ``width`` pixels of
    ``channels`` samples of ``depth`` bits (8, or 16: big-endian as in a PNG, little-endian
    with ``little``, as OpenCV decodes a TIFF here), the last an opacity when ``alpha``.
    Output row ``r // factor``, column ``x // factor`` of ``out`` (``channels`` floats a
    pixel, in the samples' scale) is the mean of the box's
    pixels (fewer at the right and bottom edges, as ``PIL.Image.reduce``); with
    ``alpha`` the colour is averaged premultiplied by the opacity and divided by
    the mean opacity (0 where the box is transparent), as Pillow's reduce does.
    """
    out_w = (width + factor - 1) // factor
    nout = (rows + factor - 1) // factor
    sums = np.zeros(out_w * channels)
    colours = channels - 1 if alpha else channels
    step = channels * (depth // 8)
    hi = 1 if little else 0  # the offset of a 16-bit sample's high byte
    lo = 1 - hi
    for oy in range(nout):
        sums[:] = 0.0
        r0 = oy * factor
        r1 = min(rows, r0 + factor)
        for r in range(r0, r1):
            base = r * pitch + offset
            for ox in range(out_w):
                s = ox * channels
                for x in range(ox * factor, min(width, ox * factor + factor)):
                    p = base + x * step
                    if depth == 16:
                        if alpha:
                            q = p + 2 * colours
                            a = np.float64(buf[q + hi]) * 256.0 + np.float64(buf[q + lo])
                            for c in range(colours):
                                v = np.float64(buf[p + 2 * c + hi]) * 256.0 + np.float64(buf[p + 2 * c + lo])
                                sums[s + c] += v * a
                            sums[s + colours] += a
                        else:
                            for c in range(channels):
                                sums[s + c] += np.float64(buf[p + 2 * c + hi]) * 256.0 + np.float64(buf[p + 2 * c + lo])
                    elif alpha:
                        a = np.float64(buf[p + colours])
                        for c in range(colours):
                            sums[s + c] += np.float64(buf[p + c]) * a
                        sums[s + colours] += a
                    else:
                        for c in range(channels):
                            sums[s + c] += np.float64(buf[p + c])
        for ox in range(out_w):
            n = np.float64((r1 - r0) * (min(width, (ox + 1) * factor) - ox * factor))
            s = ox * channels
            if alpha:
                a = sums[s + colours]
                for c in range(colours):
                    out[oy, s + c] = sums[s + c] / a if a > 0.0 else 0.0
                out[oy, s + colours] = a / n
            else:
                for c in range(channels):
                    out[oy, s + c] = sums[s + c] / n
    return nout
