"""The designer's studio (``14_studio``): your own image to a finished golden ratio logo in one page.

:class:`Studio` holds the state of the page and its callbacks on plain values
(no widget, no browser), so every step runs, and is tested, in Python: load an
upload or an example image, paint the lock mask (paper Sec. 7, Fig. 16), drag
the subject rectangle of a photo (GrabCut's seed, ``--subject``), Run, choose a
level and T (:func:`~img2logo.experiments.explore.levels_within`: a smaller T
is read off the largest run), choose only some circle sizes k (Fig. 15), click
arcs (several with ``add``), edit them with :mod:`img2logo.design.edits` (Fig. 17:
delete, connect, add the other side of a circle, move, change the rung), undo
and redo, see which segments a lock stroke covers before the Run
(:meth:`Studio.lock_preview`), and download the SVG, JSON, PDF and PNGs (on white,
transparent, over the input) of what is shown: the bytes the command line's
writers give for that level and those edits (:meth:`Studio.downloads`), named by
the image, the level and whether it was edited. The page itself (ipywidgets and
ipycanvas, served by Voila: ``make studio``) is :mod:`.page`.

:class:`Studio` is the runs (the input, the mask and subject, Run, levels and T); its
selection and edits are :class:`~.editing.StudioEdits`, its fills and downloads
:class:`~.outputs.StudioFiles`, what they share :class:`~.state.StudioState`.

Every action returns True when it changed the state; on bad input (an
unreadable upload, a blank image, a mask that locks everything, an edit that
would break the invariants) it returns False, leaves the previous result as it
was and says what and why in :attr:`Studio.message`, one line: the library's
own message (:class:`~img2logo.errors.Img2LogoError`), as the command line
prints it.

Coordinates are input-image pixels (x right, y down; pixel (i, j) covers
[j, j + 1) x [i, i + 1), centred at (j + 0.5, i + 0.5)), also for an input over
``MAX_IMAGE_SIDE`` that is worked smaller; T and the error E^s are in the
working copy's pixels, as :func:`img2logo.abstract` takes T (:attr:`Studio.work_scale`).
"""

from __future__ import annotations

import dataclasses
import os
import re
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import InvalidParameterError
from ..experiments.explore import abstract_with_settings, levels_within
from ..experiments.paths import data_path
from .editing import PICK_DISTANCE, StudioEdits, free_ends
from .outputs import DOWNLOAD_FORMATS, StudioFiles
from .state import StudioSettings

#: Largest upload accepted, bytes: the command line reads any size, but the page receives the file
#: through the kernel's websocket in one message; 9 MB holds a 12-megapixel JPEG.
MAX_UPLOAD_BYTES = 9_000_000
#: Largest websocket message the studio's server takes, bytes (``websocket_max_message_size`` in its
#: ``voila.json``): Tornado's default, 10 MiB, dropped a larger upload without a word; up to this size
#: a file too large for the studio reaches the kernel and gets :data:`MAX_UPLOAD_BYTES`'s line.
WEBSOCKET_MAX_MESSAGE_BYTES = 128 * 1024 * 1024
#: Longest name of an upload kept, characters (file systems allow 255 bytes; UTF-8 takes up to 4 a character).
MAX_NAME_CHARS = 60


#: The kinds of image in a designer's words.
KIND_WORDS = {"photo": "photo", "clipart": "clip art", "drawing": "drawing"}


def front_end_live() -> bool:
    """Whether the kernel serves a live front end: a Voila page, or a notebook opened in Jupyter.

    Voila gives its kernels ``SERVER_SOFTWARE=voila/<version>``; Jupyter Server names the notebook of
    a kernel it started in ``JPY_SESSION_NAME``. papermill sets neither.
    """
    return os.environ.get("SERVER_SOFTWARE", "").startswith("voila") or bool(os.environ.get("JPY_SESSION_NAME"))


def upload_name(filename: object) -> str:
    """The name an uploaded file is shown and downloaded by: the browser's name, cleaned.

    Only its last path component, printable characters, at most ``MAX_NAME_CHARS``
    characters (a longer stem is cut, its suffix kept); ``"upload"`` when nothing is left
    (an empty name, ``.`` or ``..``).
    """
    text = "".join(ch for ch in str(filename) if ch.isprintable()).replace("\\", "/")
    name = text.rsplit("/", 1)[-1].strip()
    if name in ("", ".", ".."):
        return "upload"
    if len(name) > MAX_NAME_CHARS:
        stem, dot, suffix = name.rpartition(".")
        suffix = dot + suffix if dot and stem and len(suffix) <= 10 else ""
        name = name[: MAX_NAME_CHARS - len(suffix)] + suffix
    return name


class Studio(StudioEdits, StudioFiles):
    """The studio's state: an image, its lock mask and subject, a run, the level shown and its edits.

    Parameters
    ----------
    image : str, optional
        A file name in ``data/`` or a path, loaded at once (not run).
    settings : StudioSettings, optional
        The first Run's settings; keyword arguments override its fields.

    Attributes
    ----------
    image : LoadedImage or None
        The input; ``name`` is the file name it came with (the downloads are named after its stem).
    mask : ndarray of bool, shape (H, W)
        The lock mask painted so far (Sec. 7, Fig. 16).
    subject : (x, y, w, h) or None
        The subject rectangle, px (ints, inside the image).
    result : Result or None
        The largest-T run with the current settings; ``levels`` those of ``settings.tolerance``.
    level : int
        The level shown, t.
    selected : list of int
        Indices of the selected arcs of :attr:`shown` (the last one clicked last; at most two).
    message : str
        One line: what the last action did, or why it did nothing (``error: ...``).
    ok : bool
        False when the last action failed.
    """

    def __init__(self, image: str | None = None, settings: StudioSettings | None = None, **overrides: Any) -> None:
        super().__init__(settings, **overrides)
        if image is not None:
            self.load_example(image)

    # ------------------------------------------------------------------ the input
    def load_upload(self, filename: str, content: bytes) -> bool:
        """Take an uploaded file (its name and bytes) as the input, read as the command line reads a file.

        An unreadable or blank file keeps the previous image and says why.
        """
        name = upload_name(filename)
        data = bytes(content)
        if len(data) > MAX_UPLOAD_BYTES:
            return self._say(
                f"error: {name}: the file has {len(data)} bytes, more than the studio takes "
                f"({MAX_UPLOAD_BYTES}); use the img2logo command for it",
                ok=False,
            )
        with tempfile.TemporaryDirectory(prefix="img2logo-upload-") as folder:
            # The browser's name is shown, never used as a path: "..", a NUL byte or 300 bytes are names too.
            suffix = Path(name).suffix
            path = Path(folder) / ("upload" + (suffix if re.fullmatch(r"\.[A-Za-z0-9]{1,10}", suffix) else ""))
            path.write_bytes(data)
            return self._attempt(lambda: self._take(path, name), folder, {path.name: name})

    def load_example(self, name: str) -> bool:
        """Take a file of ``data/`` (or a path) as the input."""

        def take() -> str:
            path = Path(name) if os.sep in name else data_path(name)
            return self._take(path, path.name)

        return self._attempt(take)

    def _take(self, path: Path, name: str) -> str:
        from ..images.loading import load_image

        img = dataclasses.replace(load_image(path), source=name)
        self.image, self.name = img, name
        # In the input's pixels, as abstract() takes it (an input over MAX_IMAGE_SIDE is worked smaller).
        self.mask = np.zeros((img.input_height, img.input_width), dtype=bool)
        self.subject = None
        self.result, self.levels, self.level = None, (), 0
        self._reset_edits()
        return f"{name}: {img.input_width}x{img.input_height} px; press Run"

    # ------------------------------------------------------------------ lock mask and subject
    def paint(self, points: Any, radius: float, *, erase: bool = False) -> int:
        """Paint (or with ``erase`` clear) discs of ``radius`` px at ``points`` (N, 2), px, into :attr:`mask`.

        A pixel is painted when its centre lies within ``radius`` of a point, or of the segment
        between two consecutive points (a stroke dragged fast leaves no gaps). Returns the number
        of pixels now in the mask.
        """
        if self.image is None:
            self._say("error: load an image first", ok=False)
            return 0
        p = np.asarray(points, dtype=np.float64).reshape(-1, 2)
        if not np.isfinite(p).all():
            raise InvalidParameterError(f"points must be finite, got {p.tolist()}")
        r = float(radius)
        if not r > 0:
            raise InvalidParameterError(f"radius must be > 0 px, got {radius}")
        h, w = self.mask.shape
        if len(p) == 1:
            p = np.vstack([p, p])
        x0, y0 = np.floor(p.min(axis=0) - r).astype(int)
        x1, y1 = np.ceil(p.max(axis=0) + r).astype(int)
        x0, y0, x1, y1 = max(x0, 0), max(y0, 0), min(x1, w), min(y1, h)
        if x0 < x1 and y0 < y1:
            yy, xx = np.mgrid[y0:y1, x0:x1]
            centres = np.stack([xx + 0.5, yy + 0.5], axis=-1).reshape(-1, 1, 2)
            a, b = p[:-1], p[1:]
            d = b - a
            length2 = np.maximum((d * d).sum(axis=1), 1e-12)
            t = np.clip(((centres - a) * d).sum(axis=2) / length2, 0.0, 1.0)
            nearest = a + t[..., None] * d
            hit = (((centres - nearest) ** 2).sum(axis=2) <= r * r).any(axis=1).reshape(yy.shape)
            self.mask[y0:y1, x0:x1] = np.where(hit, not erase, self.mask[y0:y1, x0:x1])
        count = int(self.mask.sum())
        self._say(f"lock mask: {count} px ({100.0 * count / self.mask.size:.1f}% of the image); press Run")
        return count

    def clear_mask(self) -> None:
        """Empty the lock mask."""
        self.mask[:] = False
        self._say("lock mask cleared; press Run")

    def set_subject(self, x0: float, y0: float, x1: float, y1: float) -> tuple[int, int, int, int] | None:
        """The subject rectangle dragged from (x0, y0) to (x1, y1), px: (x, y, w, h) inside the image.

        The rectangle is the pixels it covers, clipped to the image; one smaller than 2 px on a
        side clears the subject.
        """
        if self.image is None:
            self._say("error: load an image first", ok=False)
            return None
        h, w = self.mask.shape
        left, right = sorted((float(x0), float(x1)))
        top, bottom = sorted((float(y0), float(y1)))
        left, top = max(0, int(np.floor(left))), max(0, int(np.floor(top)))
        right, bottom = min(w, int(np.ceil(right))), min(h, int(np.ceil(bottom)))
        if right - left < 2 or bottom - top < 2:
            self.subject = None
            self._say("subject cleared (a rectangle must be at least 2 px on each side)")
            return None
        self.subject = (left, top, right - left, bottom - top)
        note = "" if self.settings.kind == "photo" else " (used when the image is a photo: set kind to photo)"
        self._say(f"subject: x={left}, y={top}, w={right - left}, h={bottom - top} px; press Run{note}")
        return self.subject

    def clear_subject(self) -> None:
        """Forget the subject rectangle (a photo's subject is then found automatically)."""
        self.subject = None
        self._say("subject cleared; press Run")

    # ------------------------------------------------------------------ runs, levels, T
    def run(self, progress: Callable[[int, int, float], None] | None = None, **changes: Any) -> bool:
        """Run :func:`img2logo.abstract` on the image with the settings (``changes`` applied), mask and subject.

        Shows the final level. On an error (or a lock mask that locks every segment, so that
        nothing could be merged) the previous run stays shown.
        """
        if self.image is None:
            return self._say("error: load an image first (upload one, or choose an example)", ok=False)
        unknown = set(changes) - {f.name for f in dataclasses.fields(StudioSettings)}
        if unknown:
            raise InvalidParameterError(f"unknown settings {sorted(unknown)}")

        def act() -> str:
            from ..design.fills import parse_fill_option

            settings = dataclasses.replace(self.settings, **changes)
            parse_fill_option(settings.fill)  # a bad --fill is said before the run
            start = time.perf_counter()
            result = abstract_with_settings(
                self.image,
                settings,
                subject=self.subject,
                lock_mask=self.mask.copy() if self.mask.any() else None,
                progress=progress or False,
            )
            locked = int(result.final.params.get("locked_segments", 0))
            if locked and locked >= result.graph.n_segments:
                raise InvalidParameterError(
                    f"the lock mask covers all {locked} segments of the image: nothing could be merged; "
                    "erase part of it (the previous result is kept)"
                )
            self.last_run_seconds = time.perf_counter() - start
            self.settings, self.result = settings, result
            self.levels = result.levels
            self.level = len(self.levels) - 1
            self._reset_edits()
            lock = f", {locked} segments locked" if locked else ""
            found = result.lines.subject
            subject = f"; subject: {found.description}" if found is not None else ""
            return (
                f"done: {KIND_WORDS.get(result.lines.kind, result.lines.kind)}, {len(self.levels)} levels, "
                f"{len(result.final.arcs)} arcs"
                f"{lock}, {self.last_run_seconds:.2f} s{subject}"
            )

        return self._attempt(act)

    def set_level(self, t: int) -> bool:
        """Show level ``t`` of T (its edits, if any were made on it, come back with it)."""
        if not self.levels:
            return self._say("error: press Run first", ok=False)
        t = int(t)
        if not 0 <= t < len(self.levels):
            return self._say(f"error: level must be in [0, {len(self.levels) - 1}], got {t}", ok=False)
        self.level = t
        self.selected = []
        return self._say(self.title)

    def set_tolerance(self, tolerance: float, progress: Callable[[int, int, float], None] | None = None) -> bool:
        """Show the result of T = ``tolerance``: read off the run when it holds it (instant), else Run."""
        if self.result is None:
            self.settings = dataclasses.replace(self.settings, tolerance=float(tolerance))
            return self._say(f"T = {float(tolerance):g} px; press Run")
        if 0 < float(tolerance) <= self.run_tolerance * (1.0 + 1e-9):  # the same T, scaled there and back
            self.settings = dataclasses.replace(self.settings, tolerance=float(tolerance))
            self.levels = levels_within(
                self.result, min(float(tolerance) / self.work_scale, self.result.levels[0].tolerance)
            )
            self.level = len(self.levels) - 1
            self.selected = []
            return self._say(self.title)
        return self.run(progress, tolerance=float(tolerance))

    @property
    def run_tolerance(self) -> float:
        """T of the run made, px of the working copy (a smaller T is read off it); 0 before a Run."""
        if self.result is None:
            return 0.0
        return float(self.result.levels[0].tolerance) * self.work_scale

    def update_settings(self, **changes: Any) -> None:
        """Record settings for the next Run (``fill`` takes effect at once: it only colours)."""
        self.settings = dataclasses.replace(self.settings, **changes)


__all__ = [
    "DOWNLOAD_FORMATS",
    "MAX_NAME_CHARS",
    "MAX_UPLOAD_BYTES",
    "PICK_DISTANCE",
    "WEBSOCKET_MAX_MESSAGE_BYTES",
    "Studio",
    "StudioSettings",
    "free_ends",
    "front_end_live",
    "upload_name",
]
