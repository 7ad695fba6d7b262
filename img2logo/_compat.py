"""numpy and scikit-image functions written again for start-up time or speed, each with the library's result.

A run of the command pays for every module it imports; each of these few
functions saves its library call's cost on a clip art's run, measured by
``time.process_time()`` around the first call (on the shared machine under load):

* :func:`unique`: ``np.unique``'s first call imports ``numpy.ma``: 0.008 s of CPU.
* :func:`median`: ``np.median`` looks ``np.ma`` up, which imports ``numpy.ma``: the same 0.008 s.
* :func:`unique_rows`: ``np.unique(a, axis=0)`` sorts a structured view: 28 us against 7.7 us on a local
  window's 12 incidence rows (``timeit`` under load); it runs for every constrained fit.
* :func:`intersect1d`, :func:`setdiff1d`, :func:`union1d`: numpy's, given the inputs' :func:`unique` values
  (numpy's own call of ``np.unique`` would import ``numpy.ma``).
* :func:`nonzero`: ``np.nonzero`` of a 512 x 512 mask takes 2.5 ms whatever its count (``python -m
  timeit``), ``np.flatnonzero`` and a division 0.22 ms.
* :func:`line`: ``skimage.draw.line``'s first call imports scikit-image and scipy: 0.017 s of CPU.
* :func:`circle_perimeter`: ``skimage.draw.circle_perimeter``'s first call imports them too (a drawing with a
  filled dot, an animal's eye): 64 M instructions (valgrind), 0.015 s of CPU.
"""

from __future__ import annotations

import numpy as np


def unique(values: np.ndarray) -> np.ndarray:
    """``np.unique(values)``: the distinct values of an integer array, sorted, 1-D, of its type."""
    a = np.sort(np.asarray(values).ravel())
    if a.size > 1:
        a = a[np.concatenate(([True], a[1:] != a[:-1]))]
    return a


def unique_rows(arr: np.ndarray) -> np.ndarray:
    """``np.unique(arr, axis=0)`` of an integer array (R, K) as int64: the distinct rows, sorted (by a lexsort)."""
    arr = arr.astype(np.int64)
    if len(arr) < 2:
        return arr
    rows = arr[np.lexsort(arr.T[::-1])]
    keep = np.ones(len(rows), dtype=bool)
    keep[1:] = (rows[1:] != rows[:-1]).any(axis=1)
    return rows[keep]


def intersect1d(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.intersect1d(a, b)`` of integer arrays: the values in both, sorted, 1-D."""
    return np.intersect1d(unique(a), unique(b), assume_unique=True)


def setdiff1d(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.setdiff1d(a, b)`` of integer arrays: the values of ``a`` not in ``b``, sorted, 1-D."""
    return np.setdiff1d(unique(a), unique(b), assume_unique=True)


def union1d(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``np.union1d(a, b)`` of integer arrays: the values in either, sorted, 1-D."""
    return unique(np.concatenate((a, b), axis=None))


def median(values: np.ndarray) -> np.floating:
    """``np.median(values)`` of all the values, to the bit.

    The same partition and the same mean of the one or two middle values as
    numpy's, a numpy scalar of numpy's type (integers give float64); NaN if any
    value is NaN.
    """
    a = np.asarray(values, dtype=np.result_type(values, np.float16)).ravel()  # floats, as np.median's mean
    n = len(a)
    if n == 0:
        return np.mean(a)  # NaN with numpy's warning, as np.median gives
    half = n // 2
    part = np.partition(a, [half - 1, half, -1] if n % 2 == 0 else [half, -1])  # -1: a NaN sorts last
    if np.isnan(part[-1]):
        return part[-1]
    return np.mean(part[half - 1 : half + 1] if n % 2 == 0 else part[half : half + 1])


def nonzero(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """``np.nonzero(mask)`` of a 2-D ``mask``: the rows and columns of its set pixels, in raster order, int64."""
    mask = np.asarray(mask)
    if mask.size == 0:
        return np.zeros(0, dtype=np.int64), np.zeros(0, dtype=np.int64)
    rows, cols = np.divmod(np.flatnonzero(mask), mask.shape[1])
    return rows, cols


def line(r0: int, c0: int, r1: int, c1: int) -> tuple[np.ndarray, np.ndarray]:
    """The pixels (rows, columns) of the digital line from (r0, c0) to (r1, c1), ends included.

    ``skimage.draw.line`` pixel for pixel (Bresenham's algorithm as scikit-image
    writes it).
    """
    r, c = r0, c0
    dr, dc = abs(r1 - r0), abs(c1 - c0)
    sc = 1 if c1 - c > 0 else -1
    sr = 1 if r1 - r > 0 else -1
    steep = dr > dc
    if steep:
        r, c, dr, dc, sr, sc = c, r, dc, dr, sc, sr
    d = 2 * dr - dc
    rr, cc = [], []
    for _ in range(dc):
        rr.append(c if steep else r)
        cc.append(r if steep else c)
        while d >= 0:
            r += sr
            d -= 2 * dc
        c += sc
        d += 2 * dr
    rr.append(r1)
    cc.append(c1)
    return np.array(rr, dtype=np.intp), np.array(cc, dtype=np.intp)


def circle_perimeter(r: int, c: int, radius: int, shape: tuple[int, int]) -> tuple[np.ndarray, np.ndarray]:
    """The pixels (rows, columns) of the digital circle of centre (r, c) and ``radius``, inside ``shape``.

    ``skimage.draw.circle_perimeter(r, c, radius, shape=shape)`` pixel for pixel: Bresenham's midpoint
    circle (scikit-image's default method), one octant stepped from the top and mirrored eight ways, the
    pixels outside an image of ``shape`` (rows, columns) left out.
    """
    rows: list[int] = []
    cols: list[int] = []
    x, y = 0, radius
    d = 3 - 2 * radius  # the midpoint's decision variable
    while y >= x:
        rows += [y, -y, y, -y, x, -x, x, -x]
        cols += [x, x, -x, -x, y, y, -y, -y]
        if d < 0:
            d += 4 * x + 6
        else:
            d += 4 * (x - y) + 10
            y -= 1
        x += 1
    rr = np.array(rows, dtype=np.intp) + r
    cc = np.array(cols, dtype=np.intp) + c
    inside = (rr >= 0) & (rr < shape[0]) & (cc >= 0) & (cc < shape[1])
    return rr[inside], cc[inside]
