"""scipy.ndimage's filters, to the bit, without importing ``scipy.ndimage``.

Importing ``scipy.ndimage`` costs about 0.2 s of CPU a run (it brings
``scipy.special`` and scipy's array-API layer). These give its results to the
bit: scipy's own compiled 1-D correlations (:func:`gaussian`, :func:`sobel`; a
drawing's blur, :func:`img2logo.features.preprocessing.gaussian_blur`, is this
gaussian), OpenCV's exact distance transform (:func:`distance`, through
:func:`img2logo.images.skeleton.distance_to_background`), scipy's compiled feature
transform (:func:`nearest_background`), labelling (:func:`label`), and OpenCV's
morphology with scipy's border (:func:`erode`, :func:`dilate`); :func:`median`
is numpy's without ``numpy.ma`` (every kind of image uses it; ``np.unique``'s twin is
:func:`img2logo.images.skeleton.unique`).

A low-level module of the photo path: :mod:`img2logo.images.loading` (a photo's
smoothed CIELAB), :mod:`img2logo.features.photo.subject_cues`, :mod:`img2logo.features.photo.subject`,
:mod:`img2logo.features.photo.subject_shadow` and :mod:`img2logo.features.photo.lines` use it; it imports
none of them. Arrays are indexed (row, column); distances in px.
"""

from __future__ import annotations

import numpy as np


def _correlate1d():  # scipy.ndimage's compiled 1-D correlation (scipy.ndimage._nd_image.correlate1d)
    from .skeleton import compiled_module

    return compiled_module("scipy", "ndimage", "_nd_image").correlate1d


#: scipy.ndimage's codes of the border modes its filters take (``_ni_support._extend_mode_to_code``).
_MODE_CODES = {"reflect": 2, "constant": 4}


def gaussian(image: np.ndarray, sigma: float | tuple[float, ...], mode: str = "reflect") -> np.ndarray:
    """``scipy.ndimage.gaussian_filter(image, sigma, mode=mode)``, to the bit, in ``image``'s float type (same shape).

    ``sigma`` in px, one for all axes or one per axis (0 leaves an axis
    alone); scipy's kernel (``truncate`` 4 standard deviations), axis after
    axis, each result stored in the image's float type as scipy does.
    ``mode``: ``"reflect"`` (scipy's default) or ``"constant"`` (zero outside).
    """
    src = np.asarray(image)
    if isinstance(sigma, (int, float, np.integer, np.floating)):
        sigmas = (float(sigma),) * src.ndim
    else:
        sigmas = tuple(float(v) for v in sigma)
    try:
        correlate1d = _correlate1d()
    except (ImportError, AttributeError):
        from scipy import ndimage

        return np.asarray(ndimage.gaussian_filter(src, sigmas, mode=mode))
    out = np.zeros(src.shape, dtype=src.dtype)
    current = src
    for axis, sd in enumerate(sigmas):
        if sd <= 1e-15:
            continue
        radius = int(4.0 * sd + 0.5)
        x = np.arange(-radius, radius + 1)
        phi = np.exp(-0.5 / (sd * sd) * x**2)
        weights = np.ascontiguousarray((phi / phi.sum())[::-1], dtype=np.float64)
        correlate1d(current, weights, axis, out, _MODE_CODES[mode], 0.0, 0)
        current = out
    if current is src:
        out[...] = src
    return out


def sobel(image: np.ndarray, axis: int) -> np.ndarray:
    """``scipy.ndimage.sobel(image, axis=axis, mode="constant", cval=0)``, to the bit, (H, W) in ``image``'s type.

    The derivative ``[-1, 0, 1]`` along ``axis``, then the smoothing ``[1, 2, 1]``
    along the other axis, zero outside the image; float images only.
    """
    src = np.asarray(image)
    try:
        correlate1d = _correlate1d()
    except (ImportError, AttributeError):
        from scipy import ndimage

        return np.asarray(ndimage.sobel(src, axis=axis, mode="constant", cval=0))
    out = np.zeros(src.shape, dtype=src.dtype)
    constant = _MODE_CODES["constant"]
    correlate1d(src, np.array([-1.0, 0.0, 1.0]), axis, out, constant, 0.0, 0)
    for other in range(src.ndim):
        if other != axis:
            correlate1d(out, np.array([1.0, 2.0, 1.0]), other, out, constant, 0.0, 0)
    return out


def distance(mask: np.ndarray) -> np.ndarray:
    """``scipy.ndimage.distance_transform_edt(mask)``, to the bit, float64 (H, W), px."""
    from .skeleton import distance_to_background

    mask = np.asarray(mask, dtype=bool)
    if mask.all():  # no background pixel: scipy's own answer
        from scipy import ndimage

        return np.asarray(ndimage.distance_transform_edt(mask), dtype=np.float64)
    return distance_to_background(mask)


def nearest_background(mask: np.ndarray) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray]]:
    """``scipy.ndimage.distance_transform_edt(mask, return_indices=True)``, to the bit.

    Returns
    -------
    distance : ndarray of float64, shape (H, W)
        Each pixel's Euclidean distance to the nearest pixel outside ``mask``, px.
    (rows, cols) : ndarrays of int32, shape (H, W)
        That nearest pixel; where several are as near, the one scipy's feature
        transform picks (it is scipy's compiled transform, loaded without
        importing ``scipy.ndimage``). ``mask`` must hold a pixel outside it.
    """
    from .skeleton import compiled_module

    inside = np.asarray(mask, dtype=bool)
    try:
        transform = compiled_module("scipy", "ndimage", "_nd_image").euclidean_feature_transform
    except (ImportError, AttributeError):
        from scipy import ndimage

        dist, (rows, cols) = ndimage.distance_transform_edt(inside, return_indices=True)
        return dist, (rows, cols)
    features = np.zeros((2, *inside.shape), dtype=np.int32)
    transform(np.atleast_1d(inside.astype(np.int8)), None, features)
    offset = (features - np.indices(inside.shape, dtype=np.int32)).astype(np.float64)
    np.multiply(offset, offset, offset)
    return np.sqrt(np.add.reduce(offset, axis=0)), (features[0], features[1])


def median(values: np.ndarray) -> np.floating:
    """``np.median(values)`` of all the values, to the bit, without importing ``numpy.ma``.

    The same partition and the same mean of the one or two middle values as
    numpy's, a numpy scalar of numpy's type (integers give float64); NaN if any
    value is NaN. ``np.median`` looks up ``np.ma`` to check for NaNs, and that
    imports ``numpy.ma`` (about 0.02 s of CPU a run).
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


def erode(mask: np.ndarray, iterations: int = 1) -> np.ndarray:
    """``scipy.ndimage.binary_erosion(mask, iterations=iterations)``: the 4-neighbour cross, outside the image
    empty, (H, W) bool."""
    import cv2

    cross = cv2.getStructuringElement(cv2.MORPH_CROSS, (3, 3))
    src = np.ascontiguousarray(mask, dtype=bool).view(np.uint8)
    return cv2.erode(src, cross, iterations=iterations, borderType=cv2.BORDER_CONSTANT, borderValue=0).astype(bool)


def dilate(mask: np.ndarray, iterations: int = 1) -> np.ndarray:
    """``scipy.ndimage.binary_dilation(mask, iterations=iterations)``: the 4-neighbour cross, (H, W) bool."""
    import cv2

    cross = cv2.getStructuringElement(cv2.MORPH_CROSS, (3, 3))
    src = np.ascontiguousarray(mask, dtype=bool).view(np.uint8)
    return cv2.dilate(src, cross, iterations=iterations, borderType=cv2.BORDER_CONSTANT, borderValue=0).astype(bool)


def label(mask: np.ndarray, eight: bool = False) -> tuple[np.ndarray, int]:
    """``scipy.ndimage.label(mask)`` (4-neighbours; ``eight``: ``structure=np.ones((3, 3))``): labels (H, W)
    int32 numbered 1.. in raster order, and their number."""
    from .skeleton import label as components

    labels = components(np.asarray(mask, dtype=bool), connectivity=2 if eight else 1)
    return labels, int(labels.max()) if labels.size else 0
