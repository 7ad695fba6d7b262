"""A photo's flow-based line drawing [KD09] and its colour lines, before the subject is drawn.

An edge tangent flow from the smoothed structure tensor (:func:`edge_tangent_flow`), a difference
of Gaussians across the flow, smoothed along it, binarized (:func:`flow_dog`): the lightness lines
(:func:`photo_lines`). The same on the colour-opponent channel (:func:`opponent_channel`) gives the
colour lines; one is drawn where no drawn line is that edge already and no stronger lightness edge
lies beside it (:func:`new_colour_lines`). The maps do not depend on the subject: they are made
once per image (:func:`line_maps`), ahead of their use while the subject is found
(:func:`start_photo_line_maps`). :mod:`img2logo.features.photo.lines` draws the subject with them.
"""

from __future__ import annotations

import math
import weakref
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ...images.loading import LoadedImage
from ...images.ndimage import distance
from ..constants import (
    BILATERAL_DIAMETER,
    BILATERAL_SIGMA_COLOR,
    COLOUR_LINE_GATE,
    COLOUR_LINE_SUBSAMPLE,
    EDGE_SIDE_REACH,
    ETF_SIGMA,
    FDOG_RHO,
    FDOG_SIGMA_C,
    FDOG_SIGMA_M,
    FDOG_TAU,
)

if TYPE_CHECKING:
    from concurrent.futures import Executor, Future


def photo_lines(img: LoadedImage) -> np.ndarray:
    """Flow-based difference of Gaussians [KD09] of the whole photo, binarized: (H, W) bool.

    Lightness lines: the FDoG of the gray image, first smoothed by a bilateral
    filter (KD09 smooth with a flow-based bilateral filter): fur, grain and
    texture fade, edges stay. Colour lines: the same FDoG (no dark-side bias,
    ``rho`` 1) of the photo's colour-opponent channel (:func:`opponent_channel`)
    on a copy ``COLOUR_LINE_SUBSAMPLE`` times smaller, on its own flow (on the
    lightness's flow a colour edge with no lightness step has no direction:
    its line breaks up), kept only farther than ``COLOUR_LINE_GATE`` from every
    lightness line: an edge of colour with no step of lightness (a pink nose
    on tan fur) is drawn, an outline already drawn in lightness is not drawn
    again beside it (the gate is measured from both sides of the lightness edge,
    its dark line and its bright lobe: a colour line lies on the less red side,
    which may be the bright one). Both are binarized on the lightness response's scale (a
    colour step makes a line where a lightness step of the same CIELAB size
    would). The lightness lines are those of the FDoG alone.
    """
    lightness, colour = photo_line_maps(img)
    return lightness | colour


#: Line maps being made ahead of their use, by image (:func:`start_photo_line_maps`).
_AHEAD: weakref.WeakKeyDictionary[LoadedImage, Future[LineMaps]] = weakref.WeakKeyDictionary()


def start_photo_line_maps(img: LoadedImage, pool: Executor) -> None:
    """Start making :func:`photo_line_maps` of ``img`` in ``pool`` (a thread); that function then takes them.

    The line maps do not depend on the subject: :func:`img2logo.features.photo.subject.find_subject`
    starts them on the core its cuts leave free, so that they are made while the
    subject's outline is weighed, not after it.
    """
    _AHEAD[img] = pool.submit(_line_maps, img)


def photo_line_maps(img: LoadedImage) -> tuple[np.ndarray, np.ndarray]:
    """The photo's lightness lines and its colour lines (:func:`photo_lines`), each (H, W) bool."""
    maps = line_maps(img)
    colour_lines = maps.colour
    if maps.edges.any() and colour_lines.any():
        colour_lines = colour_lines & (distance(~maps.edges) > COLOUR_LINE_GATE)  # edges.any(): EDT
    return maps.lightness, colour_lines


@dataclass(frozen=True)
class LineMaps:
    """A photo's FDoG line maps before the colour lines are gated, each (H, W).

    Attributes
    ----------
    lightness : ndarray of bool
        The lightness lines (:func:`photo_lines`).
    colour : ndarray of bool
        The colour lines, not gated.
    edges : ndarray of bool
        Both sides of every lightness edge: its dark line and its bright lobe.
    lightness_step, colour_step : ndarray of float32
        The strength of the lightness edge (the FDoG response without its bias
        to dark sides, either sign) and of the colour line (the colour FDoG's
        negative response), on the same scale (L* / 100).
    steps : ndarray of bool, optional
        The dark side of every lightness edge: the FDoG line without its bias
        to dark sides (:func:`~img2logo.features.photo.lines.clear_steps`); None: not made.
    """

    lightness: np.ndarray
    colour: np.ndarray
    edges: np.ndarray
    lightness_step: np.ndarray
    colour_step: np.ndarray
    steps: np.ndarray | None = None


def line_maps(img: LoadedImage) -> LineMaps:
    """The photo's lightness lines, its colour lines not yet gated, and the edges' sides and strengths.

    See :func:`photo_lines`; :func:`photo_line_maps` gates the colour lines
    against every lightness edge, :func:`new_colour_lines` against the drawn ones.
    Those started by :func:`start_photo_line_maps`, when they were (they are taken
    once), or made here.
    """
    ahead = _AHEAD.pop(img, None)
    return ahead.result() if ahead is not None else _line_maps(img)


def _line_maps(img: LoadedImage) -> LineMaps:
    import cv2

    gray = cv2.bilateralFilter(img.gray.astype(np.float32), BILATERAL_DIAMETER, BILATERAL_SIGMA_COLOR, 5.0)
    light = flow_dog_response(gray)
    scale = float(np.max(np.abs(light))) or 1.0
    lines = _binarize(light, scale)
    h, w = gray.shape
    small = (max(1, round(w / COLOUR_LINE_SUBSAMPLE)), max(1, round(h / COLOUR_LINE_SUBSAMPLE)))
    rgb = cv2.resize(np.ascontiguousarray(img.rgb, dtype=np.float32), small, interpolation=cv2.INTER_AREA)
    opponent = cv2.bilateralFilter(opponent_channel(rgb), BILATERAL_DIAMETER, BILATERAL_SIGMA_COLOR, 5.0)
    colour = cv2.resize(flow_dog_response(opponent, rho=1.0), (w, h), interpolation=cv2.INTER_LINEAR)
    # Both sides of every lightness edge: the response without its bias to dark sides (the DoG's
    # surround weighted by rho < 1 leaves (1 - rho) x the blurred gray, positive on flat ground).
    unbiased = light - (1.0 - FDOG_RHO) * cv2.GaussianBlur(gray, (0, 0), 1.6 * FDOG_SIGMA_C)
    steps = _binarize(unbiased, scale)  # the dark sides
    return LineMaps(
        lines,
        _binarize(colour, scale),
        steps | _binarize(-unbiased, scale),
        np.abs(unbiased).astype(np.float32),
        -colour,
        steps,
    )


def new_colour_lines(
    maps: LineMaps, drawn: np.ndarray, deep: np.ndarray | None = None, inside: np.ndarray | None = None
) -> np.ndarray:
    """The colour lines (H, W) bool that draw an edge not drawn yet, whole up to the lines they meet.

    A colour line within ``COLOUR_LINE_GATE`` of both sides of a ``drawn``
    line (``maps.edges`` within ``EDGE_SIDE_REACH`` of it) is that line's edge
    again: drawn, it would double it; it goes. Within the gate of a lightness
    edge that is not drawn (too short or too faint: the petals' shading of a
    flower, a 20 px stroke of lightness along a pink nose's top) it is kept
    only if its colour step is stronger than every such lightness step within
    the gate: then the edge is one of colour (the nose's top on tan fur); a
    weaker one is that lightness edge's own tint. A kept colour line is drawn
    whole back to the line it meets (restored along itself for
    ``COLOUR_LINE_GATE + EDGE_SIDE_REACH`` px, each step nearer the drawn
    line than the last, so never along a line beside it), so that the two join (a nose's
    top meets its sides, a wing's edge the body's outline) instead of stopping
    a gate's width short of it.

    Parameters
    ----------
    maps : LineMaps
        The photo's line maps (:func:`line_maps`).
    drawn : ndarray of bool, shape (H, W)
        The lines drawn already (the chosen lightness lines and the outline).
    deep : ndarray of bool, shape (H, W), optional
        Where a colour line may start (default: everywhere): far enough inside
        the outline not to be the outline again ...
    inside : ndarray of bool, shape (H, W), optional
        ... and where it may be drawn back to the line it meets (default: everywhere).
    """
    import cv2

    colour = maps.colour if inside is None else maps.colour & inside
    drawn = np.asarray(drawn, dtype=bool)
    if not colour.any():
        return colour.copy()
    sides = drawn | (maps.edges & (distance(~drawn) <= EDGE_SIDE_REACH)) if drawn.any() else drawn
    reach = math.ceil(COLOUR_LINE_GATE)
    disc = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * reach + 1, 2 * reach + 1))
    undrawn = cv2.dilate(np.where(sides, np.float32(0.0), maps.lightness_step), disc)
    own = colour & (maps.colour_step > undrawn)
    if maps.edges.any():
        own |= colour & (distance(~maps.edges) > COLOUR_LINE_GATE)
    if not sides.any():
        return own & deep if deep is not None else own
    away = distance(~sides).astype(np.float32)
    out = own & (away > COLOUR_LINE_GATE)
    if deep is not None:
        out &= deep
    step = np.ones((3, 3), np.uint8)
    for _ in range(math.ceil(COLOUR_LINE_GATE + EDGE_SIDE_REACH)):
        # Along the line, each step nearer the drawn line than the pixel it grows from: back to
        # the line it meets, never along one that runs beside a drawn line.
        parent = cv2.dilate(np.where(out, away, np.float32(-1.0)), step)
        grown = out | (own & (parent > away))
        if np.array_equal(grown, out):
            break
        out = grown
    return out


def opponent_channel(rgb: np.ndarray) -> np.ndarray:
    """A photo's colour-opponent channel, (H, W) float32, CIELAB units / 100.

    The CIELAB chroma (a*, b*) of ``rgb`` ((H, W, 3) in [0, 1]) projected on
    its principal axis over the image (the direction in which the photo's
    colours differ most: tan fur against a pink nose, a green leaf against a red
    petal), signed so that the axis points to +a* (red); on the gray image's
    scale (L* / 100), so that a colour step and a lightness step of the same
    CIELAB size give the same response.
    """
    import cv2

    lab = cv2.cvtColor(np.ascontiguousarray(rgb, dtype=np.float32), cv2.COLOR_RGB2Lab)
    ab = lab[..., 1:3].reshape(-1, 2) / np.float32(100.0)
    centred = ab - ab.mean(axis=0, dtype=np.float64).astype(np.float32)
    _, vectors = np.linalg.eigh((centred.T @ centred).astype(np.float64))
    axis = vectors[:, -1]
    if axis[0] < 0 or (axis[0] == 0 and axis[1] < 0):
        axis = -axis
    return (ab @ axis.astype(np.float32)).reshape(lab.shape[:2])


def _binarize(response: np.ndarray, scale: float) -> np.ndarray:
    """FDoG lines [KD09]: a negative response with ``1 + tanh(H) < FDOG_TAU``, H on a unit-free range."""
    h = response / scale * 8.0  # unit-free: the tanh threshold acts on a fixed range
    return (h < 0) & (1.0 + np.tanh(h) < FDOG_TAU)


def edge_tangent_flow(gray: np.ndarray, sigma: float = ETF_SIGMA) -> np.ndarray:
    """Edge tangent flow: unit vectors along the edges, shape (H, W, 2) as (x, y).

    The eigenvector of the smoothed structure tensor with the smaller eigenvalue
    (the direction of least change), a standard stand-in for Kang's iterative
    ETF filter [KD09]. The tensor is scikit-image's ``structure_tensor`` (Sobel
    derivatives, Gaussian of ``sigma`` px, zero outside), written out with
    ``scipy.ndimage``: the same numbers without importing ``skimage.feature``,
    which loads ``scipy.stats`` (most of a second of a photo's command line), nor
    ``scipy.ndimage`` (:func:`~img2logo.images.ndimage.sobel`, :func:`~img2logo.images.ndimage.gaussian`).
    """
    from ...images.ndimage import gaussian, sobel

    gray = np.asarray(gray)
    if gray.dtype.kind != "f":  # the flow's angles do not depend on the scale, only the sums' range does
        gray = gray.astype(np.float64)
    d_row, d_col = (sobel(gray, axis) for axis in (0, 1))
    arr, arc, acc = (
        gaussian(a * b, sigma, mode="constant") for a, b in ((d_row, d_row), (d_row, d_col), (d_col, d_col))
    )
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
    ``sigma_m`` along the flow curves (:func:`flow_dog_response`); a pixel is a
    line where the result is negative and ``1 + tanh(H) < tau``.
    """
    response = flow_dog_response(gray, sigma_c=sigma_c, sigma_m=sigma_m, rho=rho)
    scale = np.max(np.abs(response)) or 1.0
    response = response / scale * 8.0  # unit-free: the tanh threshold acts on a fixed range
    return (response < 0) & (1.0 + np.tanh(response) < tau)


def flow_dog_response(
    gray: np.ndarray,
    *,
    sigma_c: float = FDOG_SIGMA_C,
    sigma_m: float = FDOG_SIGMA_M,
    rho: float = FDOG_RHO,
) -> np.ndarray:
    """The FDoG response [KD09] of a channel (H, W): (H, W) float32, in the channel's units.

    A 1-D DoG ``G_sc - rho G_1.6sc`` across the edge tangent flow
    (:func:`edge_tangent_flow`) at every pixel, averaged with a Gaussian of
    ``sigma_m`` px along the flow curves. ``rho`` below 1 biases a lightness
    channel to lines on dark sides; a colour-opponent channel has no dark side (1).
    """
    import cv2

    g = np.ascontiguousarray(gray, dtype=np.float32)
    h, w = g.shape
    flow = np.ascontiguousarray(edge_tangent_flow(gray), dtype=np.float32)
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
    # The flow and the response sampled in one pass (one remap of 3 channels: the same
    # numbers as one channel at a time, bilinear per channel); the sum runs over all three.
    packed = np.ascontiguousarray(np.dstack([flow, across]))
    acc = weights[0] * packed
    total = weights[0]
    for direction in (1.0, -1.0):
        px, py = xs.copy(), ys.copy()
        vx, vy = direction * tx, direction * ty
        for s in range(1, steps + 1):
            px, py = px + vx, py + vy
            f = sample(packed, px, py)
            acc += weights[s] * f
            total += weights[s]
            # Follow the flow: keep the sense of travel where the field flips.
            fx, fy = f[..., 0], f[..., 1]
            sign = np.sign(fx * vx + fy * vy)
            sign[sign == 0] = 1
            vx, vy = fx * sign, fy * sign
    return acc[..., 2] / total
