"""Compiled kernels of the image operations that scipy.ndimage and scikit-image give: the same results, to the bit.

* :func:`thin_kernel`: Zhang and Suen's parallel thinning (1984) as
  ``skimage.morphology.skeletonize`` runs it on a 2-D image: two sub-passes a
  sweep, each deciding on the image as it was at the sub-pass's start by a table
  of the 256 neighbourhoods (:data:`ZHANG_SUEN_TABLE`), until a sweep removes nothing.
* :func:`correlate_kernel` (float64) and :func:`correlate32_kernel` (float32):
  ``scipy.ndimage.correlate1d`` along one axis, its border modes ``reflect`` and
  ``constant``: each output value is accumulated in float64 in scipy's order
  (a symmetric kernel adds the mirrored pair before weighting it, an
  antisymmetric one subtracts it), then stored in the array's type.
* :func:`feature_transform_kernel`: the nearest pixel outside a mask, Maurer,
  Qi and Raghavan's exact Euclidean feature transform (2003), as
  ``scipy.ndimage.distance_transform_edt(..., return_indices=True)`` computes it
  (its ties, and its answer for a mask without an outside pixel).

The tests compare each with the library function (scipy and scikit-image are
imported by the tests only); ``LICENSES/THIRD-PARTY.md`` holds the two libraries'
notices. Written in the subset of Python that numba
compiles; loaded through :mod:`img2logo._compiled.kernels`.
"""

from __future__ import annotations

import numpy as np

from .jit import jit as _jit

#: What Zhang-Suen thinning does with a set pixel, by its 8 neighbours coded as one byte (bit 0 north-west,
#: then clockwise: N, NE, E, SE, S, SW, W): 1 removed in the first sub-pass, 2 in the second, 3 in both,
#: 0 kept. The table of scikit-image's implementation (``skimage.morphology.skeletonize``, BSD-3-Clause;
#: its notice in ``LICENSES/THIRD-PARTY.md``), so that the skeletons are scikit-image's pixel for pixel.
ZHANG_SUEN_TABLE = np.frombuffer(
    bytes.fromhex(
        "0000000100000103000003010100010300000000000000000200020003000303"
        "0000000000000000030000000000000000000000000000000200000003000202"
        "0000000000000000000000000000000000000000000000000000000000000000"
        "0200000000000000020000000200000003000000000000000300000003000200"
        "0000030100000103000000000000000100000000000000000000000000000001"
        "0301000000000000000000000000000002000000000000000000000000000000"
        "0203010300000103000000000000000100000000000000000000000000000000"
        "0203000100000001000000000000000003030001000000000202000002000000"
    ),
    dtype=np.uint8,
)


@_jit
def thin_kernel(image):  # pragma: no cover - compiled
    """The 1-px skeleton of ``image`` (H, W) (nonzero: set), bool (H, W): Zhang-Suen thinning (module notes)."""
    h, w = image.shape
    skel = np.zeros((h + 2, w + 2), dtype=np.uint8)  # a border of background: no edge cases
    for i in range(h):
        for j in range(w):
            skel[i + 1, j + 1] = 1 if image[i, j] else 0
    gone_r = np.empty(h * w, dtype=np.int64)
    gone_c = np.empty(h * w, dtype=np.int64)
    removed = True
    while removed:
        removed = False
        for sub in (1, 2):
            n = 0
            for i in range(1, h + 1):
                for j in range(1, w + 1):
                    if skel[i, j] == 0:
                        continue
                    code = (
                        skel[i - 1, j - 1]
                        + 2 * skel[i - 1, j]
                        + 4 * skel[i - 1, j + 1]
                        + 8 * skel[i, j + 1]
                        + 16 * skel[i + 1, j + 1]
                        + 32 * skel[i + 1, j]
                        + 64 * skel[i + 1, j - 1]
                        + 128 * skel[i, j - 1]
                    )
                    if ZHANG_SUEN_TABLE[code] & sub:
                        gone_r[n] = i
                        gone_c[n] = j
                        n += 1
            for k in range(n):  # removed together: each decided on the sub-pass's starting image
                skel[gone_r[k], gone_c[k]] = 0
            if n:
                removed = True
    out = np.empty((h, w), dtype=np.bool_)
    for i in range(h):
        for j in range(w):
            out[i, j] = skel[i + 1, j + 1] != 0
    return out


#: scipy.ndimage's codes of the border modes (``_ni_support._extend_mode_to_code``) the correlation takes.
REFLECT = 2
CONSTANT = 4


@_jit
def correlate_kernel(src, weights, mode, cval, out):  # pragma: no cover - compiled
    """``scipy.ndimage.correlate1d`` along the middle axis of ``src`` (A, N, B) into ``out`` (A, N, B); 0.

    ``weights`` (K,), K odd, centred; ``mode`` :data:`REFLECT` (d c b a | a b c d | d c b a) or
    :data:`CONSTANT` (``cval`` outside). Every line of N values is copied, extended, into a float64
    buffer before its results are written, so ``out`` may be ``src``. Any axis of a C-ordered array is
    the middle one of such a view.
    """
    a_len, n, b_len = src.shape
    k = len(weights)
    half = k // 2
    symmetric = 1
    for i in range(1, half + 1):
        if abs(weights[half + i] - weights[half - i]) > 2.220446049250313e-16:  # scipy's test: DBL_EPSILON
            symmetric = 0
            break
    if symmetric == 0:
        symmetric = -1
        for i in range(1, half + 1):
            if abs(weights[half + i] + weights[half - i]) > 2.220446049250313e-16:
                symmetric = 0
                break
    line = np.empty((n + 2 * half, b_len))
    result = np.empty(b_len)
    period = 2 * n
    for a in range(a_len):
        for p in range(n + 2 * half):
            q = p - half
            if mode == CONSTANT and (q < 0 or q >= n):
                for b in range(b_len):
                    line[p, b] = cval
                continue
            q %= period  # reflect: the line and its mirror image, repeated
            if q >= n:
                q = period - 1 - q
            for b in range(b_len):
                line[p, b] = src[a, q, b]
        if b_len == 1:  # the last axis: one line, its sums in a register
            for p in range(n):
                c = p + half
                if symmetric == 0:
                    acc = line[c + half, 0] * weights[2 * half]
                    for j in range(-half, half):
                        acc += line[c + j, 0] * weights[half + j]
                elif symmetric > 0:
                    acc = line[c, 0] * weights[half]
                    for j in range(-half, 0):
                        acc += (line[c + j, 0] + line[c - j, 0]) * weights[half + j]
                else:
                    acc = line[c, 0] * weights[half]
                    for j in range(-half, 0):
                        acc += (line[c + j, 0] - line[c - j, 0]) * weights[half + j]
                out[a, p, 0] = acc
            continue
        for p in range(n):
            c = p + half  # the centre in the buffer
            if symmetric == 0:  # the last weight first, then the others in order
                for b in range(b_len):
                    result[b] = line[c + half, b] * weights[2 * half]
                for j in range(-half, half):
                    wj = weights[half + j]
                    for b in range(b_len):
                        result[b] += line[c + j, b] * wj
            else:  # the centre, then each mirrored pair from the outside in
                for b in range(b_len):
                    result[b] = line[c, b] * weights[half]
                for j in range(-half, 0):
                    wj = weights[half + j]
                    for b in range(b_len):
                        if symmetric > 0:
                            result[b] += (line[c + j, b] + line[c - j, b]) * wj
                        else:
                            result[b] += (line[c + j, b] - line[c - j, b]) * wj
            for b in range(b_len):
                out[a, p, b] = result[b]
    return 0


#: The same correlation of a float32 array (values stored in float32, as scipy stores them), exported with
#: that signature.
correlate32_kernel = correlate_kernel


@_jit
def _voronoi_line(features, n, fixed, d, f0, f1, g):  # pragma: no cover - compiled
    """One line of Maurer's transform: the nearest of the sites on ``line`` (axis ``d``), scipy's order of steps.

    ``features`` (2, H, W); the line runs along axis ``d`` at index ``fixed`` of the other axis.
    A site is a pixel whose row feature is >= 0; sites no nearer than their neighbours in the
    lower envelope are dropped as the line is walked, then every pixel takes the nearest kept one.
    """
    for i in range(n):
        if d == 0:
            f0[i] = features[0, i, fixed]
            f1[i] = features[1, i, fixed]
        else:
            f0[i] = features[0, fixed, i]
            f1[i] = features[1, fixed, i]
    top = -1
    for i in range(n):
        if f0[i] < 0:
            continue
        # along: the coordinate on the line; across: the squared offset from the line
        fd = np.float64(f0[i] if d == 0 else f1[i])
        t = np.float64((f1[i] if d == 0 else f0[i]) - fixed)
        w_r = t * t
        while top >= 1:
            i1 = g[top]
            i2 = g[top - 1]
            along1 = np.float64(f0[i1] if d == 0 else f1[i1])
            along2 = np.float64(f0[i2] if d == 0 else f1[i2])
            a = along1 - along2
            b = fd - along1
            c = a + b
            tu = np.float64((f1[i2] if d == 0 else f0[i2]) - fixed)
            tv = np.float64((f1[i1] if d == 0 else f0[i1]) - fixed)
            u_r = tu * tu
            v_r = tv * tv
            if c * v_r - b * u_r - a * w_r - a * b * c <= 0.0:
                break
            top -= 1
        top += 1
        g[top] = i
    if top < 0:
        return
    k = 0
    for i in range(n):
        s = g[k]
        t0 = np.float64(f0[s] - i if d == 0 else f0[s] - fixed)
        t1 = np.float64(f1[s] - fixed if d == 0 else f1[s] - i)
        delta1 = t0 * t0 + t1 * t1
        while k < top:
            s = g[k + 1]
            t0 = np.float64(f0[s] - i if d == 0 else f0[s] - fixed)
            t1 = np.float64(f1[s] - fixed if d == 0 else f1[s] - i)
            delta2 = t0 * t0 + t1 * t1
            if delta1 <= delta2:
                break
            delta1 = delta2
            k += 1
        s = g[k]
        if d == 0:
            features[0, i, fixed] = f0[s]
            features[1, i, fixed] = f1[s]
        else:
            features[0, fixed, i] = f0[s]
            features[1, fixed, i] = f1[s]


@_jit
def feature_transform_kernel(inside):  # pragma: no cover - compiled
    """The nearest pixel outside ``inside`` (H, W) (nonzero: inside) of every pixel: (rows, cols) int32 (2, H, W).

    An outside pixel is its own. The columns first, then the rows (Maurer et al. 2003, as
    scipy's ``euclidean_feature_transform``); without any outside pixel every feature is (-1, 0),
    as scipy's is.
    """
    h, w = inside.shape
    features = np.zeros((2, h, w), dtype=np.int32)
    size = max(h, w)
    f0 = np.empty(size, dtype=np.int64)
    f1 = np.empty(size, dtype=np.int64)
    g = np.empty(size, dtype=np.int64)
    for col in range(w):
        for row in range(h):
            if inside[row, col]:
                features[0, row, col] = -1
            else:
                features[0, row, col] = row
                features[1, row, col] = col
        _voronoi_line(features, h, col, 0, f0, f1, g)
    for row in range(h):
        _voronoi_line(features, w, row, 1, f0, f1, g)
    return features
