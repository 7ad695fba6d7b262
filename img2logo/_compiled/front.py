"""Compiled kernels of the front end: the clip-art regions' per-label sums, and colour spreads.

:func:`label_sums_kernel` is ``clipart.label_means``'s ``np.bincount`` per
channel in one pass over the pixels: each label's count and its sums, added
in the pixels' order as ``np.bincount`` adds them, so the same bits.
:func:`spreads_kernel` is the largest squared colour difference of every pixel
to its neighbours at given offsets, for one or two sets of them (``clipart.flat_areas``' window,
``clipart.colour_noise``'s 4-neighbours), in float32 as numpy computed it: the
same differences, squares and sums in the same order, so the same bits, in one
pass instead of a dozen of temporary images. :func:`label_kernel` numbers the
connected components of equal values by their first pixel in raster order
(``skimage.measure.label``'s numbering), in two passes with a union-find instead of OpenCV's
labelling of each value's mask and a renumbering. :func:`colour_table_kernel` is
``_cielab.srgb_to_lab``'s table of an 8-bit image's colours: the 24-bit code of
every pixel (when every value is k / 255), the codes present in ascending
order and each pixel's place among them, as ``np.unique(..., return_inverse=True)``
gives them, by a bit set of the 2**24 codes instead of a sort.

The rest are the front's other full-image passes in one loop each,
every one the same numbers as the numpy or OpenCV steps it replaces (the tests
compare them): :func:`colour_distance_kernel` (a CIELAB distance image),
:func:`spreads_kernel` (two sets of spreads in one pass),
:func:`bounds_kernel` (``find_objects``' boxes), :func:`near_kernel` (the entries
round each rim pixel), :func:`nearest_colour_kernel`, :func:`relabel_kernel`,
:func:`palette_regions_kernel` (the palette's pieces, joined and packed),
:func:`edt_kernel` (an exact Euclidean distance transform, Meijster et al. 2000),
:func:`region_depth_kernel` (the region edges' distances) and
:func:`sparse_label_kernel` (the components of a skeleton's pixels alone).

Written in the subset of Python that numba compiles; loaded through
:mod:`img2logo._compiled.kernels` (ahead of time, or numba's JIT as a fallback), never
imported by the pipeline directly.
"""

from __future__ import annotations

import numpy as np

from .jit import jit as _jit


@_jit
def label_sums_kernel(labels, values, n):  # pragma: no cover - compiled
    """Pixel count (n,) and per-channel sums (n, C) of every label of ``labels`` (N,), ``values`` (N, C)."""
    counts = np.zeros(n)
    sums = np.zeros((n, values.shape[1]))
    for i in range(len(labels)):
        k = labels[i]
        counts[k] += 1.0
        for c in range(values.shape[1]):
            sums[k, c] += values[i, c]
    return counts, sums


@_jit
def spreads_kernel(lab, pairs, in_a, in_b):  # pragma: no cover - compiled
    """Largest squared difference of each pixel of ``lab`` (H, W, 3) to those at two sets of offsets, float32 (H, W).

    Returned: (largest of set a, largest of set b).

    Each offset (dr, dc) of ``pairs`` (P, 2) is taken both ways (from a pixel
    and to it), within the image. The colours are rounded to float32 and the
    squared differences ``d0 * d0 + d1 * d1 + d2 * d2`` summed in float32
    (numpy's ``einsum("ijk,ijk->ij")`` of the float32 differences).

    ``pairs`` (P, 2) holds both sets; ``in_a[p]``, ``in_b[p]`` say which a pair
    is in. Each pair's squared difference is computed once and taken
    into the maxima of its sets.
    """
    h, w = lab.shape[0], lab.shape[1]
    flat = lab.reshape(h * w * 3)
    lab32 = np.empty(h * w * 3, dtype=np.float32)
    for k in range(h * w * 3):
        lab32[k] = np.float32(flat[k])
    most_a = np.zeros((h, w), dtype=np.float32)
    most_b = np.zeros((h, w), dtype=np.float32)
    ma = most_a.reshape(h * w)
    mb = most_b.reshape(h * w)
    for i in range(h):
        for p in range(pairs.shape[0]):
            dr, dc = pairs[p, 0], pairs[p, 1]
            if dr >= h or abs(dc) >= w or i + dr >= h:
                continue
            step = dr * w + dc
            to_a, to_b = in_a[p], in_b[p]
            for j in range(max(0, -dc), w - max(0, dc)):
                a = i * w + j
                b = a + step
                d0 = lab32[3 * b] - lab32[3 * a]
                d1 = lab32[3 * b + 1] - lab32[3 * a + 1]
                d2 = lab32[3 * b + 2] - lab32[3 * a + 2]
                d = d0 * d0 + d1 * d1
                d = d + d2 * d2
                if to_a:
                    if d > ma[a]:
                        ma[a] = d
                    if d > ma[b]:
                        ma[b] = d
                if to_b:
                    if d > mb[a]:
                        mb[a] = d
                    if d > mb[b]:
                        mb[b] = d
    return most_a, most_b


@_jit
def label_kernel(image, background, eight):  # pragma: no cover - compiled
    """Connected components of equal values of ``image`` (H, W), numbered 1.. by their first pixel in raster order.

    Pixels equal to ``background`` are 0; ``eight``: 8-neighbours, else 4.
    Two passes with a union-find (Rosenfeld and Pfaltz 1966): each pixel takes
    the provisional labels of its neighbours already scanned that have its
    value, a new one where none; every union keeps the smaller label as the
    root. A component's first pixel in raster order has no such neighbour, so
    its root is the label made there, and the roots in their order are the
    components in the order of their first pixels.
    """
    h, w = image.shape
    prov = np.zeros((h, w), dtype=np.int64)
    parent = np.empty(h * w + 1, dtype=np.int64)
    n = 0
    for i in range(h):
        for j in range(w):
            v = image[i, j]
            if v == background:
                continue
            best = 0
            for k in range(4):
                if k == 0:
                    ii, jj = i, j - 1
                elif k == 1:
                    ii, jj = i - 1, j
                elif k == 2:
                    if not eight:
                        break
                    ii, jj = i - 1, j - 1
                else:
                    ii, jj = i - 1, j + 1
                if ii < 0 or jj < 0 or jj >= w or image[ii, jj] != v:
                    continue
                r = prov[ii, jj]
                while parent[r] != r:
                    parent[r] = parent[parent[r]]  # path halving: a grandparent is smaller still
                    r = parent[r]
                if best == 0:
                    best = r
                elif r != best:
                    if r < best:
                        parent[best] = r
                        best = r
                    else:
                        parent[r] = best
            if best == 0:
                n += 1
                parent[n] = n
                best = n
            prov[i, j] = best
    final = np.zeros(n + 1, dtype=np.int64)
    count = 0
    for k in range(1, n + 1):
        if parent[k] == k:
            count += 1
            final[k] = count
        else:
            final[k] = final[parent[k]]  # the parent is smaller: numbered already
    for i in range(h):
        for j in range(w):
            prov[i, j] = final[prov[i, j]]
    return prov


#: The same labelling for a mask (H, W) of uint8 (a bool mask's bytes), exported with that
#: signature: no int64 copy of the mask.
label_mask_kernel = label_kernel

_M1 = np.uint64(0x5555555555555555)
_M2 = np.uint64(0x3333333333333333)
_M4 = np.uint64(0x0F0F0F0F0F0F0F0F)
_H01 = np.uint64(0x0101010101010101)


@_jit
def _popcount(x):  # pragma: no cover - compiled
    """Set bits of a uint64 (the SWAR count)."""
    x = x - ((x >> np.uint64(1)) & _M1)
    x = (x & _M2) + ((x >> np.uint64(2)) & _M2)
    x = (x + (x >> np.uint64(4))) & _M4
    return np.int64((x * _H01) >> np.uint64(56))


@_jit
def colour_table_kernel(rgb):  # pragma: no cover - compiled
    """An 8-bit image's colours: (ok, codes present ascending (U,), each pixel's index among them (H * W,)).

    ``rgb`` (H, W, 3) in [0, 1]; a pixel's code is ``(r << 16) | (g << 8) | b``
    of its values times 255, rounded (``np.rint``). Not ok (and empty arrays)
    when some value is not k / 255 for an integer k in 0..255.
    """
    h, w = rgb.shape[0], rgb.shape[1]
    n = h * w
    codes = np.empty(n, dtype=np.int64)
    bits = np.zeros(1 << 18, dtype=np.uint64)
    one = np.uint64(1)
    for i in range(h):
        for j in range(w):
            code = 0
            for c in range(3):
                x = rgb[i, j, c]
                v = np.rint(x * 255.0)
                if not (v / 255.0 == x and 0.0 <= v <= 255.0):
                    return False, np.empty(0, dtype=np.int64), np.empty(0, dtype=np.int64)
                code = code * 256 + np.int64(v)
            codes[i * w + j] = code
            bits[code >> 6] |= one << np.uint64(code & 63)
    before = np.empty(1 << 18, dtype=np.int64)
    total = 0
    for k in range(1 << 18):
        before[k] = total
        total += _popcount(bits[k])
    colours = np.empty(total, dtype=np.int64)
    m = 0
    for k in range(1 << 18):
        word = bits[k]
        b = 0
        while word != np.uint64(0):
            if word & one:
                colours[m] = k * 64 + b
                m += 1
            word = word >> one
            b += 1
    index = np.empty(n, dtype=np.int64)
    for p in range(n):
        code = codes[p]
        k = code >> 6
        below = bits[k] & ((one << np.uint64(code & 63)) - one)
        index[p] = before[k] + _popcount(below)
    return True, colours, index


@_jit
def colour_distance_kernel(lab, colour):  # pragma: no cover - compiled
    """``np.linalg.norm(lab - colour, axis=2)`` of ``lab`` (H, W, 3) and ``colour`` (3,): (H, W).

    The same bits: the three squared differences summed in order, then the
    square root, as numpy's reduction over a 3-long axis adds them.
    """
    h, w = lab.shape[0], lab.shape[1]
    out = np.empty((h, w))
    for i in range(h):
        for j in range(w):
            d0 = lab[i, j, 0] - colour[0]
            d1 = lab[i, j, 1] - colour[1]
            d2 = lab[i, j, 2] - colour[2]
            s = d0 * d0 + d1 * d1
            s = s + d2 * d2
            out[i, j] = np.sqrt(s)
    return out


@_jit
def bounds_kernel(labels, n):  # pragma: no cover - compiled
    """The bounding box of every label 1..n of ``labels`` (H, W): (n + 1, 4) rows of (top, bottom, left, right).

    Inclusive bounds; a label without a pixel keeps (H, -1, W, -1). One pass
    over the pixels (``np.minimum.at`` and ``np.maximum.at`` of the rows and
    columns, by label); labels <= 0 or > n are skipped.
    """
    h, w = labels.shape
    out = np.empty((n + 1, 4), dtype=np.int64)
    for k in range(n + 1):
        out[k, 0] = h
        out[k, 1] = -1
        out[k, 2] = w
        out[k, 3] = -1
    for i in range(h):
        for j in range(w):
            k = labels[i, j]
            if k <= 0 or k > n:
                continue
            if i < out[k, 0]:
                out[k, 0] = i
            if i > out[k, 1]:
                out[k, 1] = i
            if j < out[k, 2]:
                out[k, 2] = j
            if j > out[k, 3]:
                out[k, 3] = j
    return out


@_jit
def near_kernel(index, rows, cols, n, offsets):  # pragma: no cover - compiled
    """Which of the entries 0..n-1 of ``index`` (H, W) lie at ``offsets`` (K, 2) of each pixel (rows[p], cols[p]).

    (P, n) bool: ``near[p, e]`` when some pixel (rows[p] + dr, cols[p] + dc) of
    the image holds ``e``, the offsets being a structuring element's: the
    dilation of each entry's pixels by it, read at the given pixels. Values
    outside 0..n-1 are no entry.
    """
    h, w = index.shape
    near = np.zeros((len(rows), n), dtype=np.bool_)
    for p in range(len(rows)):
        r, c = rows[p], cols[p]
        for k in range(offsets.shape[0]):
            rr, cc = r + offsets[k, 0], c + offsets[k, 1]
            if 0 <= rr < h and 0 <= cc < w:
                e = index[rr, cc]
                if 0 <= e < n:
                    near[p, e] = True
    return near


@_jit
def relabel_kernel(labels):  # pragma: no cover - compiled
    """Non-negative labels (H, W) renumbered 0..n-1 in the order of their values, the used ones packed."""
    h, w = labels.shape
    rank = np.cumsum(np.bincount(labels.ravel()) > 0) - 1  # the used label's place; an unused one's is never read
    out = np.empty((h, w), dtype=np.int64)
    for i in range(h):
        for j in range(w):
            out[i, j] = rank[labels[i, j]]
    return out


@_jit
def edt_kernel(inside):  # pragma: no cover - compiled
    """Euclidean distance of every pixel of ``inside`` (H, W) to the nearest pixel outside it, px: (H, W).

    Exact: Meijster, Roerdink and Hesselink's two-pass algorithm (2000) in
    integers (each column's distance to its nearest outside pixel, then each
    row's lower envelope of parabolas), then the square root of the integer
    squared distance, as ``scipy.ndimage.distance_transform_edt`` gives it.
    Outside pixels are 0. Without any outside pixel, the distance to the pixel (-1, 0) just
    above the first corner: scipy's answer then (its nearest features are (-1, 0)).
    """
    h, w = inside.shape
    if np.all(inside != 0):
        lone = np.empty((h, w))
        for y in range(h):
            for x in range(w):
                lone[y, x] = np.sqrt(np.float64((y + 1) * (y + 1) + x * x))
        return lone
    big = h + w  # farther than any pixel: a column without an outside pixel
    g = np.empty((h, w), dtype=np.int64)
    for x in range(w):  # the columns' passes row by row (the memory's order)
        g[0, x] = big if inside[0, x] else 0
    for y in range(1, h):
        for x in range(w):
            g[y, x] = 1 + g[y - 1, x] if inside[y, x] else 0
    for y in range(h - 2, -1, -1):
        for x in range(w):
            if g[y + 1, x] < g[y, x]:
                g[y, x] = 1 + g[y + 1, x]
    out = np.empty((h, w))
    s = np.empty(w, dtype=np.int64)
    t = np.empty(w, dtype=np.int64)
    for y in range(h):
        q = 0
        s[0] = 0
        t[0] = 0
        for u in range(1, w):
            gu = g[y, u]
            while q >= 0:
                gs = g[y, s[q]]
                if (t[q] - s[q]) * (t[q] - s[q]) + gs * gs > (t[q] - u) * (t[q] - u) + gu * gu:
                    q -= 1
                else:
                    break
            if q < 0:
                q = 0
                s[0] = u
            else:
                i = s[q]
                gi = g[y, i]
                sep = (u * u - i * i + gu * gu - gi * gi) // (2 * (u - i))
                if sep + 1 < w:
                    q += 1
                    s[q] = u
                    t[q] = sep + 1
        for u in range(w - 1, -1, -1):
            i = s[q]
            gi = g[y, i]
            out[y, u] = np.sqrt(np.float64((u - i) * (u - i) + gi * gi))
            if u == t[q]:
                q -= 1
    return out


@_jit
def palette_regions_kernel(index, min_area):  # pragma: no cover - compiled
    """The regions of a palette's entries ``index`` (H, W) (``clipart_palette.palette_regions``' last steps).

    The 4-connected pieces of one entry (:func:`label_kernel`, -1 no entry);
    the pixels of pieces under ``min_area`` px joined into their 8-connected
    pieces of one entry, numbered after the others; every label packed
    (:func:`relabel_kernel`). The steps numpy took, in one call.
    """
    h, w = index.shape
    regions = label_kernel(index, -1, False)
    counts = np.bincount(regions.ravel())
    top = counts.shape[0] - 1
    tiny = np.empty((h, w), dtype=np.int64)
    any_tiny = False
    for i in range(h):
        for j in range(w):
            if counts[regions[i, j]] < min_area:
                tiny[i, j] = index[i, j]
                any_tiny = True
            else:
                tiny[i, j] = -1
    if any_tiny:
        joined = label_kernel(tiny, -1, True)
        for i in range(h):
            for j in range(w):
                if counts[regions[i, j]] < min_area:
                    regions[i, j] = joined[i, j] + top + 1
    return relabel_kernel(regions)


@_jit
def nearest_colour_kernel(colours, singles, near):  # pragma: no cover - compiled
    """The distance of each colour (P, 3) to the nearest of ``singles`` (S, 3) it is ``near`` (P, S): (P,).

    ``np.linalg.norm``'s bits (the three squares added in order, the root);
    infinite where no single is near.
    """
    out = np.empty(colours.shape[0])
    for p in range(colours.shape[0]):
        best = np.inf
        for a in range(singles.shape[0]):
            if near[p, a]:
                d0 = colours[p, 0] - singles[a, 0]
                d1 = colours[p, 1] - singles[a, 1]
                d2 = colours[p, 2] - singles[a, 2]
                s = d0 * d0 + d1 * d1
                s = s + d2 * d2
                d = np.sqrt(s)
                if d < best:
                    best = d
        out[p] = best
    return out


@_jit
def region_depth_kernel(regions):  # pragma: no cover - compiled
    """The distance of every pixel to the nearest region edge, in ``regions`` padded by one pixel of -1: (H + 2, W + 2).

    A padded pixel is an edge when a 4-neighbour holds another label (``clipart.thin_regions``'
    edge map); :func:`edt_kernel` of the rest.
    """
    h, w = regions.shape
    padded = np.full((h + 2, w + 2), -1, dtype=np.int64)
    padded[1 : h + 1, 1 : w + 1] = regions
    inside = np.ones((h + 2, w + 2), dtype=np.uint8)
    for i in range(h + 2):
        for j in range(w + 2):
            v = padded[i, j]
            if j + 1 < w + 2 and padded[i, j + 1] != v:
                inside[i, j] = 0
                inside[i, j + 1] = 0
            if i + 1 < h + 2 and padded[i + 1, j] != v:
                inside[i, j] = 0
                inside[i + 1, j] = 0
    return edt_kernel(inside)


@_jit
def sparse_label_kernel(rows, cols, h, w):  # pragma: no cover - compiled
    """The 8-connected components of the pixels (rows[p], cols[p]) (in raster order) of an (h, w) image: (P,) labels.

    Numbered 1.. by their first pixel in raster order, as :func:`label_kernel`
    numbers those of a mask holding just these pixels; a union-find over the
    pixels alone (a skeleton's few thousand), each joined to its neighbours
    met before it, the smaller index the root.
    """
    n = len(rows)
    where = np.full(h * w, -1, dtype=np.int64)
    for p in range(n):
        where[rows[p] * w + cols[p]] = p
    parent = np.arange(n)
    for p in range(n):
        r, c = rows[p], cols[p]
        for k in range(4):
            if k == 0:
                rr, cc = r, c - 1
            elif k == 1:
                rr, cc = r - 1, c - 1
            elif k == 2:
                rr, cc = r - 1, c
            else:
                rr, cc = r - 1, c + 1
            if rr < 0 or cc < 0 or cc >= w:
                continue
            q = where[rr * w + cc]
            if q < 0:
                continue
            a = p
            while parent[a] != a:
                parent[a] = parent[parent[a]]  # path halving: a grandparent is earlier still
                a = parent[a]
            b = q
            while parent[b] != b:
                parent[b] = parent[parent[b]]
                b = parent[b]
            if a < b:
                parent[b] = a
            elif b < a:
                parent[a] = b
    out = np.empty(n, dtype=np.int64)
    count = 0
    for p in range(n):
        if parent[p] == p:
            count += 1
            out[p] = count
        else:
            out[p] = out[parent[p]]  # the parent is an earlier pixel: labelled already
    return out
