"""The image operations of the pipeline, one implementation each, with scipy.ndimage's and scikit-image's results.

Importing ``scipy.ndimage`` costs about 0.2 s of CPU a run and ``skimage.morphology``
about 0.4 s (``python -c "import numpy, cv2, scipy.ndimage"`` against ``import numpy,
cv2``, /usr/bin/time), as much as a clip art's whole run. So each operation is
the compiled kernel or the OpenCV call that gives the library's result, and the
tests compare the two:

=========================  =======================================================  ==========================
operation                  its result                                               by
=========================  =======================================================  ==========================
:func:`gaussian`           ``scipy.ndimage.gaussian_filter``, to the bit            kernel: 1-D correlation
:func:`sobel`              ``scipy.ndimage.sobel`` (zero outside), to the bit       kernel: 1-D correlation
:func:`distance`           ``scipy.ndimage.distance_transform_edt``, to the bit     kernel: Meijster's EDT
:func:`nearest_background` ``distance_transform_edt(..., return_indices=True)``     kernel: Maurer's transform
:func:`components`         ``skimage.measure.label``                                kernel: union-find
:func:`label`              ``scipy.ndimage.label`` (the same labels)                :func:`components`
:func:`bounding_slices`    ``scipy.ndimage.find_objects``                           kernel: one pass
:func:`skeletonize`        ``skimage.morphology.skeletonize`` (Zhang-Suen)          kernel: thinning
:func:`erode`, :func:`dilate`  ``scipy.ndimage.binary_erosion`` / ``_dilation``     OpenCV
=========================  =======================================================  ==========================

The kernels are :mod:`img2logo._compiled.front` and :mod:`img2logo._compiled.ndimage`, loaded by
:mod:`img2logo._compiled.kernels`. Arrays are indexed (row, column); distances in px.
"""

from __future__ import annotations

import numpy as np

from .._compiled import kernels

#: scipy.ndimage's codes of the border modes its filters take (``_ni_support._extend_mode_to_code``).
_MODE_CODES = {"reflect": 2, "constant": 4}


def _correlate(src: np.ndarray, weights: np.ndarray, axis: int, mode: str, out: np.ndarray) -> None:
    """``scipy.ndimage.correlate1d(src, weights, axis, out, mode)`` of a C-ordered float array (``out`` may be it)."""
    shape = src.shape
    view = (int(np.prod(shape[:axis])), shape[axis], int(np.prod(shape[axis + 1 :])))
    entry = kernels.correlate32_kernel if src.dtype == np.float32 else kernels.correlate_kernel
    entry(src.reshape(view), np.ascontiguousarray(weights, dtype=np.float64), _MODE_CODES[mode], 0.0, out.reshape(view))


def _float_image(image: np.ndarray) -> np.ndarray:
    src = np.ascontiguousarray(image)
    if src.dtype not in (np.float32, np.float64):
        raise TypeError(f"the filters take a float32 or float64 image, got {src.dtype}")
    return src


def gaussian(image: np.ndarray, sigma: float | tuple[float, ...], mode: str = "reflect") -> np.ndarray:
    """``scipy.ndimage.gaussian_filter(image, sigma, mode=mode)``, to the bit, in ``image``'s float type (same shape).

    ``sigma`` in px, one for all axes or one per axis (0 leaves an axis
    alone); scipy's kernel (``truncate`` 4 standard deviations), axis after
    axis, each result stored in the image's float type as scipy does.
    ``mode``: ``"reflect"`` (scipy's default) or ``"constant"`` (zero outside).
    """
    src = _float_image(image)
    if isinstance(sigma, (int, float, np.integer, np.floating)):
        sigmas = (float(sigma),) * src.ndim
    else:
        sigmas = tuple(float(v) for v in sigma)
    out = np.zeros(src.shape, dtype=src.dtype)
    current = src
    for axis, sd in enumerate(sigmas):
        if sd <= 1e-15:
            continue
        radius = int(4.0 * sd + 0.5)
        x = np.arange(-radius, radius + 1)
        phi = np.exp(-0.5 / (sd * sd) * x**2)
        _correlate(current, (phi / phi.sum())[::-1], axis, mode, out)
        current = out
    if current is src:
        out[...] = src
    return out


def sobel(image: np.ndarray, axis: int) -> np.ndarray:
    """``scipy.ndimage.sobel(image, axis=axis, mode="constant", cval=0)``, to the bit, (H, W) in ``image``'s type.

    The derivative ``[-1, 0, 1]`` along ``axis``, then the smoothing ``[1, 2, 1]``
    along the other axis, zero outside the image; float images only.
    """
    src = _float_image(image)
    out = np.zeros(src.shape, dtype=src.dtype)
    _correlate(src, np.array([-1.0, 0.0, 1.0]), axis, "constant", out)
    for other in range(src.ndim):
        if other != axis:
            _correlate(out, np.array([1.0, 2.0, 1.0]), other, "constant", out)
    return out


def distance(mask: np.ndarray) -> np.ndarray:
    """Euclidean distance of every pixel of ``mask`` (H, W) to the nearest pixel outside it, px, float64 (H, W).

    ``scipy.ndimage.distance_transform_edt(mask)``, to the bit (the root of the
    integer squared distance), by :func:`img2logo._compiled.front.edt_kernel`
    (Meijster et al. 2000); a mask without an outside pixel gets scipy's answer too.
    """
    inside = np.asarray(mask, dtype=bool)
    if inside.ndim != 2:
        raise ValueError(f"distance needs a 2-D mask, got shape {inside.shape}")
    return kernels.edt_kernel(np.ascontiguousarray(inside).view(np.uint8))


def nearest_background(mask: np.ndarray) -> tuple[np.ndarray, tuple[np.ndarray, np.ndarray]]:
    """``scipy.ndimage.distance_transform_edt(mask, return_indices=True)``, to the bit.

    Returns
    -------
    distance : ndarray of float64, shape (H, W)
        Each pixel's Euclidean distance to the nearest pixel outside ``mask``, px.
    (rows, cols) : ndarrays of int32, shape (H, W)
        That nearest pixel; where several are as near, the one scipy's feature
        transform picks (:func:`img2logo._compiled.ndimage.feature_transform_kernel`).
    """
    inside = np.ascontiguousarray(np.asarray(mask, dtype=bool))
    features = kernels.feature_transform_kernel(inside.view(np.uint8))
    offset = (features - np.indices(inside.shape, dtype=np.int32)).astype(np.float64)
    np.multiply(offset, offset, offset)
    return np.sqrt(np.add.reduce(offset, axis=0)), (features[0], features[1])


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


def components(image: np.ndarray, connectivity: int, background: int = 0) -> np.ndarray:
    """Connected components of equal values, numbered 1.. in raster order, int (H, W).

    What ``skimage.measure.label(image, background=background,
    connectivity=connectivity)`` returns (``connectivity`` 1: 4-neighbours, 2: 8;
    background pixels 0; int32 for a bool image, int64 otherwise): a component is
    numbered by its first pixel in raster order, as scikit-image (and
    ``scipy.ndimage.label``) number them. By :func:`img2logo._compiled.front.label_kernel`
    (two passes with a union-find).
    """
    if connectivity not in (1, 2):
        raise ValueError(f"connectivity must be 1 or 2, got {connectivity}")
    if image.dtype == bool:  # the mask's bytes as they are
        mask = np.ascontiguousarray(image).view(np.uint8)
        return kernels.label_mask_kernel(mask, int(background), connectivity != 1).astype(np.int32)
    values = np.ascontiguousarray(image, dtype=np.int64)
    return kernels.label_kernel(values, int(background), connectivity != 1)


def label(mask: np.ndarray, eight: bool = False) -> tuple[np.ndarray, int]:
    """``scipy.ndimage.label(mask)`` (4-neighbours; ``eight``: ``structure=np.ones((3, 3))``): labels (H, W)
    int32 numbered 1.. in raster order (:func:`components`), and their number."""
    labels = components(np.asarray(mask, dtype=bool), connectivity=2 if eight else 1)
    return labels, int(labels.max()) if labels.size else 0


def bounding_slices(labels: np.ndarray) -> list[tuple[slice, slice] | None]:
    """``scipy.ndimage.find_objects(labels)``: entry ``i`` bounds the pixels labelled ``i + 1``, None where none are.

    By :func:`img2logo._compiled.front.bounds_kernel` (one pass over the pixels).
    """
    flat = np.asarray(labels).ravel()
    n = int(flat.max()) if flat.size else 0
    if n <= 0:
        return []
    top, bottom, left, right = kernels.bounds_kernel(np.asarray(labels), n).T.tolist()
    return [
        (slice(int(top[i]), int(bottom[i]) + 1), slice(int(left[i]), int(right[i]) + 1)) if bottom[i] >= 0 else None
        for i in range(1, n + 1)
    ]


def skeletonize(mask: np.ndarray) -> np.ndarray:
    """1-px skeleton of a 2-D binary ``mask`` (Zhang-Suen thinning), bool (H, W).

    The pixels of ``skimage.morphology.skeletonize(mask)`` (its default method for
    2-D images), by :func:`img2logo._compiled.ndimage.thin_kernel`.
    """
    image = np.asarray(mask)
    if image.ndim != 2:
        raise ValueError(f"skeletonize needs a 2-D mask, got shape {image.shape}")
    return kernels.thin_kernel(np.ascontiguousarray(image, dtype=bool).view(np.uint8))
