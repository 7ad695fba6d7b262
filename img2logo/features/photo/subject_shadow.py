"""Cast shadows: the part of a subject candidate that is background in the object's shadow.

GrabCut on colours takes a soft shadow trapped between an object's legs for
object: it is darker than the lit background and of no colour GrabCut's
background model knows. A cast shadow darkens the surface it falls on by a
factor and keeps two things of it: the chromaticity (linear RGB over its sum)
and the texture of the log-luminance (a factor is an offset in the log). So:

1. the background is sampled in a ring just outside the candidate, the object
   in its core (``SHADOW_RING``, ``SHADOW_CORE`` working px);
2. seeds of shadow are the candidate's pixels darker than the ring's median
   whose chromaticity and log-texture are nearer the background's than the
   object's (Mahalanobis distances);
3. the shadow is grown from them over the candidate's darker pixels whose
   chromaticity alone is the background's (within
   ``SHADOW_MAX_CHROMA_DISTANCE``; the texture is left out here because the
   object's edge raises it beside the object);
4. it is left out only if the outline section it takes away is no edge and
   the one that then runs beside it is one
   (:func:`~img2logo.features.photo.subject_cues.outline_contrast` under, and at least,
   ``SUBJECT_MIN_CONTRAST``): a shadow's far side is a soft penumbra and its
   near side the object's sharp edge. An object's own part of the
   background's colour (a grey foot on grey gravel, a dark eye on the rim of
   a head against dark bricks) has its sharp edge outside and stays.

Arrays are indexed (row, column).
"""

from __future__ import annotations

import math
from functools import partial

import numpy as np

from ..._compat import median, unique
from ...constants import LUMA_WEIGHTS
from ...images.loading import LoadedImage
from ...images.ndimage import dilate, distance, gaussian, label
from ..constants import (
    FOCUS_DETAIL_SIGMA,
    FOCUS_WINDOW,
    SHADOW_CHROMA_SIGMA,
    SHADOW_CORE,
    SHADOW_MAX_CHROMA_DISTANCE,
    SHADOW_RING,
    SUBJECT_MIN_CONTRAST,
)
from .subject_cues import clean_mask, mask_box, outline_contrast, work_scale

#: Fewest pixels in the ring and the core for their statistics to mean something.
_MIN_SAMPLES = 50


def shadow_features(rgb: np.ndarray, scale: float = 1.0) -> tuple[np.ndarray, np.ndarray]:
    """Features a cast shadow keeps, and the one it changes: (features (H, W, 3), log-luminance (H, W)).

    The features are the chromaticity (r, g of linear RGB over its sum,
    smoothed by ``SHADOW_CHROMA_SIGMA``) and the log10 energy of the fine detail
    of the natural log of the linear luminance (as
    :func:`~img2logo.features.photo.subject_cues.fine_detail`); the log-luminance is smoothed
    the same way as the chromaticity. ``scale`` is the working copy's size
    over this image's (the sigmas are in working px). ``rgb`` is sRGB in [0, 1].
    """
    k = 1.0 / scale
    linear = np.clip(np.asarray(rgb, dtype=np.float64), 1.0 / 255.0, 1.0) ** 2.2
    sigma = SHADOW_CHROMA_SIGMA * k
    smooth = gaussian(linear, (sigma, sigma, 0))
    chroma = smooth[..., :2] / smooth.sum(axis=-1, keepdims=True)
    log_lum = np.log(linear @ np.asarray(LUMA_WEIGHTS))
    detail = log_lum - gaussian(log_lum, FOCUS_DETAIL_SIGMA * k)
    texture = np.log10(1e-3 + np.sqrt(gaussian(detail * detail, FOCUS_WINDOW * k)))
    return np.dstack([chroma, texture]), gaussian(log_lum, sigma)


def local_mean(features: np.ndarray, where: np.ndarray, sigma: float) -> np.ndarray:
    """The Gaussian-weighted mean (sigma px) of the feature vectors (H, W, d) of the pixels ``where`` (H, W) bool
    around each pixel, (H, W, d): normalized convolution. Pixels beyond the Gaussian's reach of all of them take
    their mean over all. Channel by channel, so the first channels' means are those of the first features alone.
    """
    import cv2

    # OpenCV's Gaussian (the same 4-sigma reach, mirrored border), several times scipy's speed at this sigma
    blur = partial(cv2.GaussianBlur, ksize=(0, 0), sigmaX=sigma, borderType=cv2.BORDER_REFLECT)
    weight = blur(where.astype(np.float32)).astype(np.float64)
    summed = blur(np.ascontiguousarray(features * where[..., None], dtype=np.float32)).astype(np.float64)
    mean = summed.reshape(features.shape) / np.maximum(weight, 1e-12)[..., None]
    far = weight < 1e-6  # beyond the Gaussian's reach (4 sigma) of every such pixel: their mean over all
    mean[far] = features[where].mean(axis=0)
    return mean


def mahalanobis(
    features: np.ndarray, where: np.ndarray, sigma: float | None = None, mean: np.ndarray | None = None
) -> np.ndarray:
    """Mahalanobis distance of every feature vector (H, W, d) to those of the pixels ``where`` (H, W) bool.

    With ``sigma`` (px), to their local mean (:func:`local_mean`; or ``mean``
    (H, W, d) if given, that mean computed once for several feature sets) and their
    spread about it: a shadow is compared with the background beside it, not
    with every colour of the background (a brick wall's mortar is no match for
    a shadow on its bricks).
    """
    if mean is None:
        mean = features[where].mean(axis=0) if sigma is None else local_mean(features, where, sigma)
    diff = features - mean
    sample = diff[where]
    cov = np.atleast_2d(np.cov(sample.T)) + 1e-9 * np.eye(sample.shape[1])
    return np.sqrt(np.maximum(np.einsum("...i,ij,...j->...", diff, np.linalg.inv(cov), diff), 0.0))


def cast_shadow(img: LoadedImage, mask: np.ndarray) -> np.ndarray | None:
    """The shadowed background inside a subject candidate ``mask`` (H, W) bool, or None if there is none.

    See the module's documentation. Returns the pixels to leave out of
    ``mask`` (H, W) bool, only when leaving them out makes the outline beside
    them the object's sharp edge.
    """
    if not mask.any() or mask.all():
        return None
    scale = work_scale(img)
    # The distances on the mask's box grown past the ring are the whole image's (mask_box);
    # beyond it a pixel is farther than the ring and inside nothing.
    near = mask_box(mask, math.ceil(SHADOW_RING[1] / scale) + 1)
    inside, ring = np.zeros(mask.shape), np.zeros(mask.shape, bool)
    inside[near] = distance(mask[near])
    outside = distance(~mask[near])
    ring[near] = (outside > SHADOW_RING[0] / scale) & (outside <= SHADOW_RING[1] / scale)
    core = inside > SHADOW_CORE / scale
    if ring.sum() < _MIN_SAMPLES or core.sum() < _MIN_SAMPLES:
        return None
    # Only the candidate's box and the ring around it are needed.
    rows, cols = np.nonzero(mask | ring)
    box = (slice(rows.min(), rows.max() + 1), slice(cols.min(), cols.max() + 1))
    features, log_lum = shadow_features(img.rgb[box], scale)
    m, ring_b, core_b = mask[box], ring[box], core[box]
    darker = m & (log_lum < median(log_lum[ring_b]))
    seeds = darker & (inside[box] > 1.0 / scale)
    if not seeds.any():
        return None
    local = SHADOW_RING[1] / scale
    ring_mean = local_mean(features, ring_b, local)  # the chromaticity's is its first two channels
    seeds &= mahalanobis(features, ring_b, mean=ring_mean) < mahalanobis(features, core_b, local)
    if not seeds.any():
        return None
    chroma = features[..., :2]
    grown = darker & (mahalanobis(chroma, ring_b, mean=ring_mean[..., :2]) < SHADOW_MAX_CHROMA_DISTANCE)
    labels, _ = label(grown | seeds)
    hit = unique(labels[seeds])
    shadow = np.zeros(mask.shape, bool)
    shadow[box] = np.isin(labels, hit[hit > 0])
    kept = clean_mask(mask & ~shadow)
    left_out = mask & ~kept
    if not left_out.any() or not kept.any():
        return None
    before = outline_contrast(img, mask, where=left_out)  # the outline's section that goes
    after = outline_contrast(img, kept, where=dilate(left_out, 2))  # and the new one
    if before >= SUBJECT_MIN_CONTRAST or after < SUBJECT_MIN_CONTRAST:
        return None
    return left_out
