"""Frontal faces in a photo (beyond the paper): a portrait's eyes, brows, nose and mouth are inner lines.

:func:`find_faces` runs scikit-image's LBP frontal-face cascade (OpenCV's
``lbpcascade_frontalface``, shipped inside scikit-image: nothing is downloaded) on the photo's
working copy; :func:`img2logo.features.photo.subject.find_subject` keeps the faces inside its subject
(``Subject.faces``) and :mod:`img2logo.features.photo.lines` draws their lines.

Boxes are (x, y, w, h) in px with x the column and y the row of their top-left corner.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from ...images.loading import LoadedImage
from ..constants import (
    FACE_MIN_NEIGHBOURS,
    FACE_MIN_SIDE,
    FACE_SCALE_STEP,
)
from .subject_cues import (
    working_copy,
)

if TYPE_CHECKING:
    pass


def find_faces(img: LoadedImage, mask: np.ndarray | None = None) -> tuple[tuple[int, int, int, int], ...]:
    """Frontal faces in a photo, as boxes (x, y, w, h) in px, largest first.

    scikit-image's LBP frontal-face cascade (OpenCV's ``lbpcascade_frontalface``,
    shipped inside scikit-image: nothing is downloaded) run on the working copy
    (longer side ``SUBJECT_WORK_SIDE`` px); a face at least ``FACE_MIN_SIDE`` of
    the shorter side, found at ``FACE_MIN_NEIGHBOURS`` neighbouring windows or
    more (a face answers at many positions and scales, a face-like patch of
    texture at a few), and with its centre in ``mask`` when one is given.
    """
    import cv2

    small, scale = working_copy(img)
    sh, sw = small.shape[:2]
    side = max(8, round(FACE_MIN_SIDE * min(sh, sw)))
    r0, c0 = 0, 0
    if mask is not None:  # only the subject's box is searched: a face outside it is dropped anyway
        rows, cols = np.nonzero(cv2.resize(mask.astype(np.uint8), (sw, sh), interpolation=cv2.INTER_NEAREST))
        if rows.size == 0:
            return ()
        r0, c0 = int(rows.min()), int(cols.min())
        small = small[r0 : int(rows.max()) + 1, c0 : int(cols.max()) + 1]
    largest = min(small.shape[:2])
    if largest < side:
        return ()
    cascade = _cascade_class()(_cascade_file())
    gray = cv2.cvtColor(np.ascontiguousarray(np.clip(small, 0, 1)), cv2.COLOR_RGB2GRAY)
    found = cascade.detect_multi_scale(
        img=gray,
        scale_factor=FACE_SCALE_STEP,
        step_ratio=1,
        min_size=(side, side),
        max_size=(largest, largest),
        min_neighbor_number=FACE_MIN_NEIGHBOURS,
    )
    faces = []
    for f in sorted(found, key=lambda f: -f["width"] * f["height"]):
        x, y = round((f["c"] + c0) / scale), round((f["r"] + r0) / scale)
        w, h = round(f["width"] / scale), round(f["height"] / scale)
        cx, cy = min(img.width - 1, x + w // 2), min(img.height - 1, y + h // 2)
        if mask is None or mask[cy, cx]:
            faces.append((x, y, w, h))
    return tuple(faces)


def _cascade_file() -> str:
    """The path of scikit-image's LBP frontal-face cascade (``skimage.data.lbp_frontal_face_cascade_filename``).

    It ships in the package's ``data`` folder; asking ``skimage.data`` for it
    loads its download registry and ``skimage.util`` (0.03 s of CPU a run).
    """
    import importlib.util

    spec = importlib.util.find_spec("skimage")
    if spec is not None and spec.origin is not None:
        path = Path(spec.origin).parent / "data" / "lbpcascade_frontalface_opencv.xml"
        if path.is_file():
            return str(path)
    from skimage import data

    return str(data.lbp_frontal_face_cascade_filename())


def _cascade_class() -> type:
    """scikit-image's ``skimage.feature.Cascade``, without importing ``skimage.color``'s colour conversions.

    The compiled module ``skimage.feature._cascade`` imports ``rgb2gray`` from
    ``skimage.color`` when it loads (for colour images; :func:`find_faces` gives
    it gray ones), and ``skimage.color`` imports ``scipy.linalg``, whose array-API
    layer imports most of numpy's optional modules: about 0.4 s of CPU, a fifth
    of a photo's command line. While the module loads, ``skimage.color`` is a
    stand-in whose ``rgb2gray`` imports the real one when first called; the
    stand-in is gone as soon as the module is loaded. Should a later
    scikit-image's cascade import more than that, the stand-in is dropped and
    the package imported as usual (slower, the same faces).
    """
    import sys
    import types

    loaded = sys.modules.get("skimage.feature._cascade")
    if loaded is not None or "skimage.color.colorconv" in sys.modules:
        from skimage.feature import Cascade

        return Cascade
    import skimage

    def rgb2gray(*args: object, **kwargs: object) -> np.ndarray:
        from skimage.color import rgb2gray as real

        return real(*args, **kwargs)

    stand_in = types.ModuleType("skimage.color")
    stand_in.rgb2gray = rgb2gray  # type: ignore[attr-defined]
    before = sys.modules.get("skimage.color")
    sys.modules["skimage.color"] = stand_in
    try:
        import skimage.feature._cascade as module
    except ImportError:  # a scikit-image whose cascade needs more of skimage.color: the whole import
        module = None
    finally:
        if before is None:
            sys.modules.pop("skimage.color", None)
        else:
            sys.modules["skimage.color"] = before
        if getattr(skimage, "color", None) is stand_in:
            del skimage.color
    if module is None:
        from skimage.feature import Cascade

        return Cascade
    return module.Cascade
