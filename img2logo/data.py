"""Sample images made in memory, for trying the library and for its examples.

As :mod:`skimage.data` gives scikit-image's examples their pictures, this module gives
img2logo's theirs, so that an example is about the function it shows, not about drawing an
input: every public function's example starts from :func:`ring`.

Examples
--------
>>> from img2logo import abstract, data
>>> [round(arc.circle.r, 1) for arc in abstract(data.ring(), progress=False).final.arcs]
[50.0]
"""

from __future__ import annotations

import cv2
import numpy as np

from .errors import InvalidParameterError


def ring(side: int = 160, radius: int = 50, thickness: int = 3) -> np.ndarray:
    """A black ring drawn on white: the simplest line drawing, whose logo is one golden circle.

    Parameters
    ----------
    side : int, optional
        Width and height of the image, px (default 160).
    radius : int, optional
        Radius of the ring's centre line, px, about the image's centre (default 50;
        at most ``side // 2 - thickness`` so the ring stays in the image).
    thickness : int, optional
        Width of the ring's stroke, px (default 3), as OpenCV draws it (``cv2.circle``).

    Returns
    -------
    numpy.ndarray
        The image, shape (side, side, 3), dtype uint8, RGB: 255 where paper, 0 on the ring.

    Raises
    ------
    InvalidParameterError
        If a size is not a positive whole number or the ring does not fit the image.

    Examples
    --------
    >>> from img2logo import data
    >>> image = data.ring()
    >>> image.shape, image.dtype.name, int(image.min()), int(image.max())
    ((160, 160, 3), 'uint8', 0, 255)
    """
    for name, value in (("side", side), ("radius", radius), ("thickness", thickness)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)) or value < 1:
            raise InvalidParameterError(f"ring: {name} must be a positive whole number of px, got {value!r}")
    if radius + thickness > side // 2:
        raise InvalidParameterError(
            f"ring: radius + thickness must be at most side // 2 = {side // 2} px so the ring fits, "
            f"got {radius} + {thickness}"
        )
    image = np.full((side, side, 3), 255, np.uint8)
    centre = side // 2
    cv2.circle(image, (centre, centre), int(radius), (0, 0, 0), int(thickness))
    return image
