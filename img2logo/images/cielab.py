"""sRGB to CIELAB, as scikit-image computes it, without importing ``skimage.color``.

``skimage.color`` imports ``scipy.linalg`` at its import (to invert its colour
matrices), which brings scipy's array-API layer and all of numpy's lazy
submodules: about 0.3 s of CPU before a clip art's run starts, for one colour
conversion. :func:`rgb2lab` is ``skimage.color.rgb2lab`` (illuminant D65, 2
degree observer) step for step, the same numpy operations in the same order, so
the same bits (the tests compare the two).
"""

from __future__ import annotations

import numpy as np

# skimage.color's ``xyz_from_rgb`` (the sRGB specification) and its D65 / 2 degree white.
_XYZ_FROM_RGB = np.array(
    [
        [0.412453, 0.357580, 0.180423],
        [0.212671, 0.715160, 0.072169],
        [0.019334, 0.119193, 0.950227],
    ]
)
_D65_WHITE = np.asarray((0.95047, 1.0, 1.08883), dtype=np.float64)


def rgb2lab(rgb: np.ndarray) -> np.ndarray:
    """CIELAB (L, a, b) of sRGB colours in [0, 1], (..., 3) float64 -> (..., 3) float64.

    ``skimage.color.rgb2lab(rgb)`` to the bit for a float64 array (what the
    package gives it; anything else goes to scikit-image's function): the sRGB
    gamma, the XYZ matrix product, the scaling by the white point and the CIE
    cube root with its linear toe.
    """
    arr = np.asarray(rgb)
    if arr.dtype != np.float64 or arr.shape[-1:] != (3,):  # not met in the package: scikit-image's own
        from skimage.color import rgb2lab as reference

        return reference(arr)
    arr = arr.copy()
    mask = arr > 0.04045
    arr[mask] = np.power((arr[mask] + 0.055) / 1.055, 2.4)
    arr[~mask] /= 12.92
    arr = arr @ _XYZ_FROM_RGB.T.astype(arr.dtype)
    arr = arr / _D65_WHITE
    mask = arr > 0.008856
    arr[mask] = np.cbrt(arr[mask])
    arr[~mask] = 7.787 * arr[~mask] + 16.0 / 116.0
    x, y, z = arr[..., 0], arr[..., 1], arr[..., 2]
    lightness = (116.0 * y) - 16.0
    a = 500.0 * (x - y)
    b = 200.0 * (y - z)
    return np.concatenate([c[..., np.newaxis] for c in (lightness, a, b)], axis=-1)


def srgb_to_lab(rgb: np.ndarray) -> np.ndarray:
    """``skimage.color.rgb2lab(rgb)`` (D65), to the bit, of an (H, W, 3) float64 image in [0, 1].

    An 8-bit image (every value k / 255, as loaded) holds a few thousand colours
    at most where it has 262144 pixels (a 512 px clip art: about a thousand):
    each distinct colour is converted once, by :func:`rgb2lab` on
    the (1, U, 3) array of them (the same row-by-row arithmetic as on the whole
    image), and spread back to its pixels. Any other image is converted whole.
    The table is :func:`img2logo._compiled.front.colour_table_kernel`'s: the
    colours in ascending order of their 24-bit codes and each pixel's place among
    them, as ``np.unique(codes, return_inverse=True)`` gives them, without sorting the pixels.
    """
    from .._compiled import kernels

    if rgb.ndim != 3 or rgb.shape[2] != 3:
        return np.asarray(rgb2lab(rgb))
    ok, colours, index = kernels.colour_table_kernel(np.ascontiguousarray(rgb, dtype=np.float64))
    if not ok:  # not every value k / 255
        return np.asarray(rgb2lab(rgb))
    table = np.stack([(colours >> 16) & 255, (colours >> 8) & 255, colours & 255], axis=1) / 255.0
    return np.asarray(rgb2lab(table[None]))[0].take(index, axis=0).reshape(rgb.shape)  # take: a quarter of [index]
