"""Feature lines of real photos (paper Sec. 4): a flow-based line drawing [KD09].

An edge tangent flow from the smoothed structure tensor, a difference of
Gaussians across the flow, smoothed along it, binarized (thinned by the caller);
optionally only on the foreground object (a mask, or OpenCV's GrabCut).

Arrays are indexed (row, column); points are (x, y) = (column + 0.5, row + 0.5)
in px, x to the right, y downwards (``contract/README.md``).
"""

from __future__ import annotations

import math

import numpy as np

from ._validation import check_choice
from .constants import (
    BILATERAL_DIAMETER,
    BILATERAL_SIGMA_COLOR,
    ETF_SIGMA,
    FDOG_RHO,
    FDOG_SIGMA_C,
    FDOG_SIGMA_M,
    FDOG_TAU,
)
from .errors import InvalidParameterError
from .loading import LoadedImage


def foreground_mask(img: LoadedImage, foreground: object) -> np.ndarray | None:
    if foreground is None:
        return img.foreground if img.has_alpha else None
    if isinstance(foreground, str):
        check_choice(foreground, "foreground", ("grabcut",))
        return _grabcut(img)
    mask = np.asarray(foreground)
    if mask.shape != (img.height, img.width):
        raise InvalidParameterError(
            f"foreground mask must have the image's shape {(img.height, img.width)}, got {mask.shape}"
        )
    mask = mask.astype(bool)
    if not mask.any():
        raise InvalidParameterError("foreground mask is empty: no pixel is marked as the object")
    return mask


def _grabcut(img: LoadedImage) -> np.ndarray:
    """Foreground by OpenCV's GrabCut started from a rectangle inset by 5 % of each side."""
    import cv2

    h, w = img.height, img.width
    bgr = np.ascontiguousarray((img.rgb[:, :, ::-1] * 255).round().astype(np.uint8))
    mask = np.zeros((h, w), np.uint8)
    rect = (int(0.05 * w), int(0.05 * h), int(0.9 * w), int(0.9 * h))
    bgd, fgd = np.zeros((1, 65), np.float64), np.zeros((1, 65), np.float64)
    cv2.setRNGSeed(0)  # deterministic
    cv2.grabCut(bgr, mask, rect, bgd, fgd, 5, cv2.GC_INIT_WITH_RECT)
    return (mask == cv2.GC_FGD) | (mask == cv2.GC_PR_FGD)


def photo_lines(img: LoadedImage, mask: np.ndarray | None) -> np.ndarray:
    """Flow-based difference of Gaussians [KD09], binarized, on ``mask`` if given.

    The gray image is first smoothed by a bilateral filter (KD09 smooth with a
    flow-based bilateral filter): fur, grain and texture fade, edges stay.
    """
    import cv2

    smooth = cv2.bilateralFilter(img.gray.astype(np.float32), BILATERAL_DIAMETER, BILATERAL_SIGMA_COLOR, 5.0)
    lines = flow_dog(smooth)
    if mask is not None:
        from scipy import ndimage

        # Keep the object's outline too: lines within a few px of the mask.
        lines &= ndimage.binary_dilation(mask, iterations=3)
    return lines


def edge_tangent_flow(gray: np.ndarray, sigma: float = ETF_SIGMA) -> np.ndarray:
    """Edge tangent flow: unit vectors along the edges, shape (H, W, 2) as (x, y).

    The eigenvector of the smoothed structure tensor with the smaller eigenvalue
    (the direction of least change), a standard stand-in for Kang's iterative
    ETF filter [KD09].
    """
    from skimage.feature import structure_tensor

    arr, arc, acc = structure_tensor(gray, sigma=sigma, order="rc")
    # Tensor in (x, y) = (col, row): [[acc, arc], [arc, arr]]; the minor
    # eigenvector's angle is half the orientation angle plus 90 degrees.
    theta = 0.5 * np.arctan2(2.0 * arc, acc - arr) + math.pi / 2.0
    return np.stack([np.cos(theta), np.sin(theta)], axis=-1)


def flow_dog(
    gray: np.ndarray,
    *,
    sigma_c: float = FDOG_SIGMA_C,
    sigma_m: float = FDOG_SIGMA_M,
    rho: float = FDOG_RHO,
    tau: float = FDOG_TAU,
) -> np.ndarray:
    """Flow-based difference of Gaussians [KD09]: a (H, W) bool line map.

    A 1-D DoG ``G_sc - rho G_1.6sc`` is taken across the edge tangent flow at
    every pixel, then those responses are averaged with a Gaussian of
    ``sigma_m`` along the flow curves; a pixel is a line where the result is
    negative and ``1 + tanh(H) < tau``.
    """
    import cv2

    g = np.ascontiguousarray(gray, dtype=np.float32)
    h, w = g.shape
    flow = edge_tangent_flow(gray).astype(np.float32)
    tx, ty = flow[..., 0], flow[..., 1]
    nx, ny = -ty, tx  # gradient direction, across the edge
    ys, xs = np.mgrid[0:h, 0:w].astype(np.float32)

    def sample(img: np.ndarray, px: np.ndarray, py: np.ndarray) -> np.ndarray:
        return cv2.remap(img, px, py, cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE)

    sigma_s = 1.6 * sigma_c
    half = math.ceil(3.0 * sigma_s)
    t = np.arange(-half, half + 1, dtype=np.float32)
    dog = np.exp(-(t**2) / (2 * sigma_c**2)) / (sigma_c * math.sqrt(2 * math.pi)) - rho * np.exp(
        -(t**2) / (2 * sigma_s**2)
    ) / (sigma_s * math.sqrt(2 * math.pi))
    across = np.zeros_like(g)
    for ti, wi in zip(t, dog, strict=True):
        across += wi * sample(g, xs + ti * nx, ys + ti * ny)

    steps = math.ceil(3.0 * sigma_m)
    weights = np.exp(-(np.arange(steps + 1) ** 2) / (2 * sigma_m**2)).astype(np.float32)
    acc = weights[0] * across
    total = weights[0]
    for direction in (1.0, -1.0):
        px, py = xs.copy(), ys.copy()
        vx, vy = direction * tx, direction * ty
        for s in range(1, steps + 1):
            px, py = px + vx, py + vy
            # Follow the flow: keep the sense of travel where the field flips.
            fx, fy = sample(tx, px, py), sample(ty, px, py)
            sign = np.sign(fx * vx + fy * vy)
            sign[sign == 0] = 1
            vx, vy = fx * sign, fy * sign
            acc += weights[s] * sample(across, px, py)
            total += weights[s]
    response = acc / total
    scale = np.max(np.abs(response)) or 1.0
    response = response / scale * 8.0  # unit-free: the tanh threshold acts on a fixed range
    return (response < 0) & (1.0 + np.tanh(response) < tau)
