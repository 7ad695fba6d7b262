"""Colour fills of the regions bounded by the arcs (paper Sec. 7, Fig. 18; Sec. 9, future work).

A golden ratio logo is a set of circular arcs; its colourized versions (Fig. 18)
fill the closed regions that the arcs bound, the faces of their arrangement
(:func:`img2logo.design.arrangement.faces`). This module colours those faces in three
ways:

- a user palette (:func:`fill_palette`): Fig. 18's "simple color palette";
- a linear or radial gradient over the logo (:func:`fill_gradient`): Fig. 18's
  "gradients";
- automatic colours from the input image (:func:`fill_auto`): the paper's future
  work (Sec. 9, "automatically fill colors ... according to the full color
  information of the input image"): each face takes the median colour, in
  CIELAB, of the input pixels under it; faces of the image's background colour
  and faces that reach the image border are left empty.

Colours are ``#rrggbb`` strings, as in the ``fills`` key of the
``img2logo.abstraction/1`` document (``contract/README.md``). A :class:`Fill` is
a face's SVG path and its colour, optionally with a :class:`Gradient`; the
writers (:func:`img2logo.export.writers.write_svg`, ``write_json``, ``write_png``) take
a tuple of fills. The command line's ``--fill`` option is parsed by
:func:`parse_fill_option` into a :class:`FillSpec`.

Coordinates are input-image pixels, x right, y down; angles in radians from +x
towards +y (clockwise on screen), as everywhere in img2logo. Shapely and
scikit-image are imported inside the functions that need them.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from .._validation import check_choice, check_instance, check_positive
from ..errors import InvalidParameterError
from ..geometry.abstraction import Abstraction
from ..images.loading import composite_on_white
from .arrangement import Face, face_adjacency, faces
from .fill_values import HEX_COLOR, Fill, Gradient, check_fills, hex_to_rgb, parse_color, rgb_to_hex

if TYPE_CHECKING:
    from shapely.geometry import Polygon

__all__ = [
    "AUTO_FILL_INSET",
    "BACKGROUND_DISTANCE",
    "DEFAULT_GRADIENT_ANGLE",
    "Fill",
    "FillSpec",
    "Gradient",
    "check_fills",
    "fill_auto",
    "fill_gradient",
    "fill_palette",
    "parse_color",
    "parse_fill_option",
]

#: :func:`fill_auto`: the face is shrunk by this much before its pixels are read,
#: px, so that anti-aliased boundary pixels and the neighbouring region (the arcs
#: are within the tolerance T of the image's edges, not on them) do not bleed in.
AUTO_FILL_INSET: float = 2.0
#: :func:`fill_auto` with a ``background`` colour: a face within this CIELAB Delta E
#: 76 of it is left empty (a visible difference: five times the just noticeable one).
BACKGROUND_DISTANCE: float = 12.0
#: :func:`fill_auto`: width of the image border whose median colour is the
#: background colour, px.
BORDER_WIDTH: int = 2
#: :func:`fill_auto`: a face whose inset leaves fewer pixels than this is read
#: without the inset.
AUTO_FILL_MIN_PIXELS: int = 8
#: Default direction of a linear gradient, radians from +x towards +y: pi/2 runs
#: from the top of the logo (first colour) to its bottom (last colour).
DEFAULT_GRADIENT_ANGLE: float = math.pi / 2.0
_FILL_MODES = ("none", "auto", "palette", "linear", "radial")
_FILL_SYNTAX = (
    "'none', 'auto', 'palette:#rrggbb,#rrggbb,...', 'linear[@degrees]:#rrggbb,#rrggbb,...' "
    "or 'radial:#rrggbb,#rrggbb,...'"
)


# --- values --------------------------------------------------------------------------


@dataclass(frozen=True)
class FillSpec:
    """A parsed ``--fill`` option (see :func:`parse_fill_option`).

    Attributes
    ----------
    mode : {"none", "auto", "palette", "linear", "radial"}
    colors : tuple of str
        The ``#rrggbb`` colours of a palette or gradient, in order.
    angle : float
        Direction of a linear gradient, radians from +x towards +y.
    """

    mode: str
    colors: tuple[str, ...] = ()
    angle: float = DEFAULT_GRADIENT_ANGLE

    def make(self, abstraction: Abstraction, image: Any = None) -> tuple[Fill, ...]:
        """The fills of ``abstraction`` this option asks for.

        Parameters
        ----------
        abstraction : Abstraction
        image : ndarray or LoadedImage, optional
            The input image; needed by ``"auto"`` (see :func:`fill_auto`).

        Returns
        -------
        tuple of Fill
            Empty for ``"none"``.
        """
        if self.mode == "none":
            return ()
        if self.mode == "auto":
            if image is None:
                raise InvalidParameterError("fill mode 'auto' needs the input image, got None")
            return fill_auto(abstraction, image)
        if self.mode == "palette":
            return fill_palette(abstraction, self.colors)
        return fill_gradient(abstraction, self.colors, kind=self.mode, angle=self.angle)


# --- colours -------------------------------------------------------------------------


def _faces_of(abstraction: Abstraction, face_list: Sequence[Face] | None) -> tuple[Face, ...]:
    check_instance(abstraction, Abstraction, "abstraction")
    if face_list is None:
        return faces(abstraction)
    out = tuple(face_list)
    for i, f in enumerate(out):
        if not isinstance(f, Face):
            raise InvalidParameterError(f"faces[{i}] must be a Face, got {type(f).__name__}")
    return out


def fill_palette(
    abstraction: Abstraction,
    colors: Sequence[Any] | Mapping[int, Any],
    *,
    faces: Sequence[Face] | None = None,
) -> tuple[Fill, ...]:
    """Fill the faces from a user palette (Fig. 18, "simple color palette").

    Parameters
    ----------
    abstraction : Abstraction
    colors : sequence of colours, or mapping face index -> colour
        A mapping fills exactly the faces it names (indices into
        :func:`img2logo.design.arrangement.faces`). A sequence is dealt out in a deterministic order: the
        faces largest first, face number k starting from colour ``k mod n`` and
        taking the first colour, cyclically, that no adjacent face already
        coloured has (adjacent: sharing a piece of arc; when every colour is
        taken the colour ``k mod n`` is used), so neighbours differ whenever the
        palette allows. Colours are ``#rrggbb`` or RGB floats in [0, 1].
    faces : sequence of Face, optional
        The faces, if already computed (:func:`img2logo.design.arrangement.faces` of ``abstraction``).

    Returns
    -------
    tuple of Fill
        In face order.

    Raises
    ------
    InvalidParameterError
        On an empty palette, a bad colour or a face index out of range.
    """
    face_list = _faces_of(abstraction, faces)
    if isinstance(colors, Mapping):
        chosen: dict[int, str] = {}
        for key, value in colors.items():
            if isinstance(key, bool) or not isinstance(key, int | np.integer):
                raise InvalidParameterError(f"palette keys must be face indices (integers), got {key!r}")
            if not 0 <= int(key) < len(face_list):
                raise InvalidParameterError(
                    f"palette face index {int(key)} is out of range (the abstraction has {len(face_list)} faces)"
                )
            chosen[int(key)] = parse_color(value, f"palette colour for face {int(key)}")
        return tuple(Fill(face_list[i].path, chosen[i], face=i) for i in sorted(chosen))
    if isinstance(colors, str) or not isinstance(colors, Sequence):
        raise InvalidParameterError(
            f"colors must be a sequence of colours or a mapping face -> colour, got {type(colors).__name__}"
        )
    palette = [parse_color(c, f"palette colour {i}") for i, c in enumerate(colors)]
    if not palette:
        raise InvalidParameterError("the palette is empty: give at least one colour")
    adjacent = face_adjacency(face_list)
    assigned: dict[int, str] = {}
    n = len(palette)
    for k in range(len(face_list)):
        taken = {assigned[j] for j in adjacent[k] if j in assigned}
        pick = palette[k % n]
        for off in range(n):
            candidate = palette[(k + off) % n]
            if candidate not in taken:
                pick = candidate
                break
        assigned[k] = pick
    return tuple(Fill(face_list[k].path, assigned[k], face=k) for k in range(len(face_list)))


def fill_gradient(
    abstraction: Abstraction,
    colors: Sequence[Any],
    kind: str = "linear",
    angle: float = DEFAULT_GRADIENT_ANGLE,
    *,
    faces: Sequence[Face] | None = None,
) -> tuple[Fill, ...]:
    """Fill every face with one gradient across the whole logo (Fig. 18, "gradients").

    The gradient spans the bounding box of the faces (the logo), so it runs on
    continuously from face to face. Linear: along the direction ``angle`` from
    the box's side where the first colour sits to the opposite side, through
    the box's centre. Radial: from the box's centre (first colour) to its
    corners (last colour). Stops are evenly spaced.

    The ``img2logo.abstraction/1`` document has one ``#rrggbb`` colour per
    region, so each fill's :attr:`Fill.color` (written to the JSON) is the
    gradient's colour at the face's centroid; the SVG and the PNG draw the true
    gradient (:attr:`Fill.gradient`).

    Parameters
    ----------
    abstraction : Abstraction
    colors : sequence of colours
        At least two, ``#rrggbb`` or RGB floats in [0, 1].
    kind : {"linear", "radial"}
    angle : float
        Direction of a linear gradient, radians from +x towards +y (y down): 0
        runs left to right, pi/2 (the default) top to bottom. Ignored for radial.
    faces : sequence of Face, optional
        The faces, if already computed.

    Returns
    -------
    tuple of Fill
        One per face, in face order; empty when there is no face.
    """
    check_choice(kind, "kind", ("linear", "radial"))
    a = float(angle) if isinstance(angle, int | float | np.number) and not isinstance(angle, bool) else math.nan
    if not math.isfinite(a):
        raise InvalidParameterError(f"angle must be a finite number of radians, got {angle!r}")
    if isinstance(colors, str) or not isinstance(colors, Sequence):
        raise InvalidParameterError(f"colors must be a sequence of colours, got {type(colors).__name__}")
    palette = [parse_color(c, f"gradient colour {i}") for i, c in enumerate(colors)]
    if len(palette) < 2:
        raise InvalidParameterError(f"a gradient needs at least two colours, got {len(palette)}")
    face_list = _faces_of(abstraction, faces)
    if not face_list:
        return ()
    bounds = np.array([f.polygon.bounds for f in face_list])
    x0, y0 = bounds[:, 0].min(), bounds[:, 1].min()
    x1, y1 = bounds[:, 2].max(), bounds[:, 3].max()
    centre = np.array([0.5 * (x0 + x1), 0.5 * (y0 + y1)])
    if kind == "linear":
        d = np.array([math.cos(a), math.sin(a)])
        reach = 0.5 * (abs(d[0]) * (x1 - x0) + abs(d[1]) * (y1 - y0))
        start, end = centre - reach * d, centre + reach * d
    else:
        start, end = centre, np.array([x1, y1])
    stops = tuple((i / (len(palette) - 1), c) for i, c in enumerate(palette))
    gradient = Gradient(kind, stops, (float(start[0]), float(start[1])), (float(end[0]), float(end[1])))
    out = []
    for k, face in enumerate(face_list):
        color = rgb_to_hex(gradient.color_at(np.array(face.centroid)))
        out.append(Fill(face.path, color, gradient=gradient, face=k))
    return tuple(out)


def fill_auto(
    abstraction: Abstraction,
    image: Any,
    *,
    faces: Sequence[Face] | None = None,
    inset: float = AUTO_FILL_INSET,
    background: Any = None,
    background_distance: float = BACKGROUND_DISTANCE,
) -> tuple[Fill, ...]:
    """Colours from the input image: the paper's future work (Sec. 9; Fig. 18 done automatically).

    Each face takes the median, channel by channel in CIELAB, of the input
    pixels whose centres lie inside it shrunk by ``inset`` px (the whole face
    when the inset leaves fewer than ``AUTO_FILL_MIN_PIXELS``): a robust average
    that ignores a minority of other colours (the anti-aliased boundary, a bit
    of the neighbouring region where the arcs, within the tolerance T, leave
    the image's edges). A face is background, and gets no fill, when it reaches
    the image border (within 1 px), or when most of its pixels are transparent
    in an input with an alpha channel: a face enclosed by the object keeps its
    colour even when that is the background's (a penguin's white belly). On
    request (``background``), faces of a given colour are left empty too.

    Parameters
    ----------
    abstraction : Abstraction
    image : ndarray, shape (height, width) or (height, width, C), C in 1..4, or LoadedImage
        The input image the abstraction was made from, of the abstraction's
        size: uint8, uint16, bool or floats in [0, 1]; its alpha channel (C =
        2 or 4) is composited on white
        (:func:`img2logo.images.loading.composite_on_white`).
    faces : sequence of Face, optional
        The faces, if already computed.
    inset : float
        Shrink faces by this much before reading pixels, px (>= 0).
    background : None, "auto" or colour
        None (default): only faces that reach the border or the transparent
        background are empty. A colour (``#rrggbb`` or RGB floats), or
        ``"auto"`` for the median colour of the image's outer
        ``BORDER_WIDTH`` px: faces of that colour are left empty too.
    background_distance : float
        Delta E 76 below which a face has the ``background`` colour.

    Returns
    -------
    tuple of Fill
        One per face that is not background, in face order, each with
        :attr:`Fill.face` set.
    """
    from skimage.color import lab2rgb, rgb2lab

    if (
        faces is None
        and hasattr(image, "input_size")
        and (image.width, image.height)
        != (
            abstraction.width,
            abstraction.height,
        )
    ):
        # A result in the pixels of an input over MAX_IMAGE_SIDE, its image the downscaled working one:
        # colours are read at the working size, and the fills get the faces' paths in the input's pixels.
        small = abstraction.scaled(image.width / abstraction.width, image.width, image.height)
        face_list = _faces_of(abstraction, None)
        found = fill_auto(small, image, inset=inset, background=background, background_distance=background_distance)
        return tuple(Fill(face_list[f.face].path, f.color, face=f.face) for f in found)  # type: ignore[index]
    face_list = _faces_of(abstraction, faces)
    width, height = int(abstraction.width), int(abstraction.height)
    inset = check_positive(inset, "inset", allow_zero=True)
    background_distance = check_positive(background_distance, "background_distance", allow_zero=True)
    pixels = getattr(image, "rgb", image)
    if pixels is None:
        raise InvalidParameterError("image must be an array of shape (H, W, 3), got None")
    rgb, alpha, has_alpha = composite_on_white(pixels, "image", size=(width, height))
    lab = rgb2lab(rgb)
    if getattr(image, "has_alpha", False):
        alpha = np.asarray(image.alpha)  # a LoadedImage: its rgb is already composited
    elif not has_alpha:
        alpha = None
    if isinstance(background, str) and background == "auto":
        b = BORDER_WIDTH
        frame = np.ones((height, width), dtype=bool)
        frame[b:-b, b:-b] = False
        back_lab: np.ndarray | None = np.median(lab[frame], axis=0)
    elif background is None:
        back_lab = None
    else:
        back_lab = rgb2lab(hex_to_rgb(parse_color(background, "background"))[None, None, :])[0, 0]
    if not face_list:
        return ()

    out = []
    for k, face in enumerate(face_list):
        x0, y0, x1, y1 = face.polygon.bounds
        if x0 < 1.0 or y0 < 1.0 or x1 > width - 1.0 or y1 > height - 1.0:
            continue  # reaches the border: background
        samples = _pixels_inside(face.polygon, inset, width, height)
        if len(samples[0]) < AUTO_FILL_MIN_PIXELS:
            samples = _pixels_inside(face.polygon, 0.0, width, height)
        if len(samples[0]) == 0:
            continue  # thinner than a pixel: nothing to read
        if alpha is not None and float(np.median(alpha[samples])) < 0.5:
            continue  # the transparent background
        colour_lab = np.median(lab[samples], axis=0)
        if back_lab is not None and float(np.linalg.norm(colour_lab - back_lab)) < background_distance:
            continue
        colour = lab2rgb(colour_lab[None, None, :])[0, 0]
        out.append(Fill(face.path, rgb_to_hex(colour), face=k))
    return tuple(out)


def _pixels_inside(polygon: Polygon, inset: float, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """(rows, cols) of the pixels whose centres lie inside ``polygon`` shrunk by ``inset`` px."""
    import shapely

    shape = polygon if polygon.is_valid else shapely.make_valid(polygon)
    if inset > 0.0:
        shape = shape.buffer(-inset)
    if shape.is_empty:
        return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp)
    x0, y0, x1, y1 = shape.bounds
    c0, c1 = max(0, math.floor(x0)), min(width, math.ceil(x1) + 1)
    r0, r1 = max(0, math.floor(y0)), min(height, math.ceil(y1) + 1)
    if c0 >= c1 or r0 >= r1:
        return np.zeros(0, dtype=np.intp), np.zeros(0, dtype=np.intp)
    rows, cols = np.mgrid[r0:r1, c0:c1]
    shapely.prepare(shape)
    inside = shapely.contains_xy(shape, cols.ravel() + 0.5, rows.ravel() + 0.5)
    return rows.ravel()[inside], cols.ravel()[inside]


# --- the command line option -----------------------------------------------------------


def parse_fill_option(spec: object) -> FillSpec:
    """Parse the command line's ``--fill`` option.

    Forms: ``none``; ``auto`` (colours from the input image, :func:`fill_auto`);
    ``palette:#rrggbb,#rrggbb,...`` (:func:`fill_palette`, one or more
    colours); ``linear:#rrggbb,#rrggbb,...`` or ``linear@DEG:...`` with the
    direction in degrees from +x towards +y (default 90, top to bottom), and
    ``radial:#rrggbb,#rrggbb,...`` (:func:`fill_gradient`, two or more
    colours). The mode is case-insensitive; spaces around items are ignored.

    Returns
    -------
    FillSpec
        Call ``spec.make(abstraction, image)`` for the fills.

    Raises
    ------
    InvalidParameterError
        With the form expected, e.g. ``fill option 'palette:': the palette is
        empty: give at least one #rrggbb colour after 'palette:'`` or ``fill
        option 'palette:#12345': colour 1 '#12345' is not of the form #rrggbb``.
    """
    if not isinstance(spec, str):
        raise InvalidParameterError(f"fill option must be a string, got {type(spec).__name__}")
    text = spec.strip()
    head, sep, rest = text.partition(":")
    mode, at, degrees = head.strip().lower().partition("@")
    if mode not in _FILL_MODES or (mode in ("none", "auto") and (sep or at)) or (at and mode != "linear"):
        raise InvalidParameterError(f"fill option must be {_FILL_SYNTAX}, got {spec!r}")
    if mode in ("none", "auto"):
        return FillSpec(mode)
    if not sep:
        raise InvalidParameterError(
            f"fill option {spec!r}: give the colours after '{mode}:', e.g. {mode}:#1f77b4,#ff7f0e"
        )
    angle = DEFAULT_GRADIENT_ANGLE
    if at:
        try:
            angle = math.radians(float(degrees))
        except ValueError:
            angle = math.nan
        if not math.isfinite(angle):
            raise InvalidParameterError(
                f"fill option {spec!r}: the angle after '@' must be a number of degrees, got {degrees!r}"
            )
    items = [c.strip() for c in rest.split(",")]
    if items == [""]:
        items = []
    if not items and mode == "palette":
        raise InvalidParameterError(
            f"fill option {spec!r}: the palette is empty: give at least one #rrggbb colour after 'palette:'"
        )
    colors = []
    for i, c in enumerate(items, start=1):
        if not HEX_COLOR.match(c):
            raise InvalidParameterError(f"fill option {spec!r}: colour {i} {c!r} is not of the form #rrggbb")
        colors.append(c.lower())
    if mode != "palette" and len(colors) < 2:
        raise InvalidParameterError(
            f"fill option {spec!r}: a {mode} gradient needs at least two #rrggbb colours, got {len(colors)}"
        )
    return FillSpec(mode, tuple(colors), angle)
