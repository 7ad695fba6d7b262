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
ipycanvas, served by Voila: ``make studio``) is :mod:`.studio_page`.

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
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..constants import DETAIL, RDP_TOLERANCE, TOLERANCE
from ..errors import Img2LogoError, InvalidParameterError
from ..experiments.explore import abstract_with_settings, levels_within
from ..experiments.paths import data_path
from ..geometry.abstraction import Abstraction

if TYPE_CHECKING:
    from ..design.fills import Fill
    from ..images.loading import LoadedImage
    from ..pipeline import Result

#: Distance from a click to an arc that still selects it, CSS px of the drawing on screen (a
#: fingertip's width on a touch pad; the arcs of a logo are rarely closer than that).
PICK_DISTANCE = 10.0

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
#: The downloads, by key: SVG, JSON, PDF, PNG on white, PNG on nothing (transparent), PNG over the faded input.
DOWNLOAD_FORMATS: tuple[str, ...] = ("svg", "json", "pdf", "png", "png-transparent", "png-input")


@dataclass(frozen=True)
class StudioSettings:
    """The inputs of a Run.

    Attributes
    ----------
    tolerance : float
        T, px.
    bias : float or None
        The phi ladder bias sigma; None: automatic (Eqn. 14).
    rdp_tolerance : float
        Ramer-Douglas-Peucker tolerance, px.
    kind : str
        ``"auto"``, ``"photo"``, ``"clipart"`` or ``"drawing"``.
    symmetry : str
        ``"none"``, ``"auto"``, ``"vertical"``, ``"horizontal"`` or degrees.
    lines : bool
        Nearly straight segments become straight lines (Sec. 9, Fig. 20b).
    ladder : str
        ``"phi"`` (golden) or ``"fibonacci"`` (Fig. 2b).
    detail : int
        Clip art: the regions kept besides the background (``--detail``).
    exponents : tuple of int or None
        Only these ladder exponents k (the subset of golden circles of Fig. 15, ``--radii``);
        None: every rung.
    fill : str
        The command line's ``--fill`` option: ``none``, ``auto``,
        ``palette:#rrggbb,...``, ``linear[@DEG]:...`` or ``radial:...``
        (:func:`img2logo.design.fills.parse_fill_option`); it colours what is shown
        and the downloads, without a new Run.
    """

    tolerance: float = TOLERANCE
    bias: float | None = None
    rdp_tolerance: float = RDP_TOLERANCE
    kind: str = "auto"
    symmetry: str = "none"
    lines: bool = False
    ladder: str = "phi"
    exponents: tuple[int, ...] | None = None
    detail: int = DETAIL
    fill: str = "none"


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


def _one_line(exc: BaseException | Warning | str, folder: str | None = None) -> str:
    """The message of ``exc`` on one line, without the temporary folder an upload was read from."""
    text = str(exc)
    if folder:
        text = text.replace(folder + os.sep, "")
    return " ".join(text.split())


class Studio:
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
        self.settings = dataclasses.replace(settings or StudioSettings(), **overrides)
        self.image: LoadedImage | None = None
        self.name = ""
        self.mask = np.zeros((0, 0), dtype=bool)
        self.subject: tuple[int, int, int, int] | None = None
        self.result: Result | None = None
        self.levels: tuple[Abstraction, ...] = ()
        self.level = 0
        self.selected: list[int] = []
        self.message = ""
        self.ok = True
        self.last_run_seconds = 0.0
        self._history: dict[int, list[Abstraction]] = {}
        self._redo: dict[int, list[Abstraction]] = {}
        # The logo (kept, so that its id names it) and its regions' own colours, by the logo's id.
        self._colours: dict[int, tuple[Abstraction, dict[int, str]]] = {}
        self._cache: dict[str, Any] = {}
        if image is not None:
            self.load_example(image)

    # ------------------------------------------------------------------ messages
    def _say(self, text: str, ok: bool = True) -> bool:
        self.message, self.ok = text, ok
        return ok

    def _attempt(
        self, action: Callable[[], str], folder: str | None = None, names: dict[str, str] | None = None
    ) -> bool:
        """Run ``action`` (it returns its message); an img2logo error becomes the message, nothing changed.

        ``folder`` is left out of the messages and each key of ``names`` (a temporary file's name)
        becomes its value (the name the file came with).
        """

        def line(text: BaseException | Warning | str) -> str:
            out = _one_line(text, folder)  # type: ignore[arg-type]
            for old, new in (names or {}).items():
                out = out.replace(old, new)
            return out

        try:
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                text = action()
        except Img2LogoError as exc:
            return self._say(f"error: {line(exc)}", ok=False)
        notes = [line(w.message) for w in caught if issubclass(w.category, UserWarning)]
        return self._say("; ".join([text, *[f"warning: {n}" for n in notes]]))

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

    @property
    def stem(self) -> str:
        """The downloads' name: the input's file name without its suffix."""
        return Path(self.name).stem or "logo"

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

    @property
    def shown(self) -> Abstraction | None:
        """The logo on screen: the level shown, with its edits."""
        if not self.levels:
            return None
        history = self._history.get(self.level)
        return history[-1] if history else self.levels[self.level]

    @property
    def title(self) -> str:
        """One line about the logo shown, in a designer's words: the level t, |A| arcs, the error E^s, T, the edits.

        ``fish: level 12 of 30, 25 arcs, error 3.21 px (tolerance 5 px), 1 edit``.
        """
        a = self.shown
        if a is None:
            return "no result yet: press Run"
        n_edits = len(self._history.get(self.level, []))
        edits = f", {n_edits} edit{'s' if n_edits != 1 else ''}" if n_edits else ""
        # E^s in the pixels T is given in: those of the working copy when the input was worked smaller.
        k = self.work_scale
        work = self.result.image if self.result is not None and k != 1.0 else None
        size = f" of the {work.width}x{work.height} px working copy" if work is not None else ""
        return (
            f"{self.stem}: level {self.level} of {len(self.levels) - 1}, {len(a.arcs)} arcs, "
            f"error {a.similarity * k:.2f} px (tolerance {self.settings.tolerance:g} px{size}){edits}"
        )

    @property
    def work_scale(self) -> float:
        """Working-copy pixels per input pixel of the run (1.0 unless the input was worked smaller).

        T, the progress bar and E^s in the title are in working pixels, as :func:`img2logo.abstract`
        takes T; the logo, the mask, the subject and the clicks are in the input's pixels.
        """
        if self.result is None:
            return 1.0
        return float(self.result.final.params.get("scale", 1.0))

    # ------------------------------------------------------------------ selection and edits
    def pick(self, x: float, y: float, distance: float) -> int | None:
        """The arc of :attr:`shown` nearest (x, y), px, if it is within ``distance`` px; else None."""
        a = self.shown
        if a is None or not a.arcs:
            return None
        samples = self._cached("samples", lambda: [arc.sample(step=1.0) for arc in a.arcs])
        point = np.array([float(x), float(y)])
        gaps = [float(np.min(np.hypot(*(s - point).T))) for s in samples]
        i = int(np.argmin(gaps))
        return i if gaps[i] <= distance else None

    def select_at(self, x: float, y: float, distance: float, *, add: bool = False) -> int | None:
        """Click at (x, y), px: select the nearest arc within ``distance`` px (the last two clicked stay selected).

        A click on the selected arc, or off every arc, clears the selection. With ``add``
        (a shift-click) the arc joins the selection, or leaves it when it was in it, and
        nothing else is dropped.
        """
        i = self.pick(x, y, distance)
        if add and i is not None:
            self.selected = [s for s in self.selected if s != i] + ([] if i in self.selected else [i])
            n = len(self.selected)
            self._say(f"{n} arc{'s' if n != 1 else ''} selected: {', '.join(map(str, self.selected))}")
            return i
        if i is None or (self.selected and self.selected[-1] == i):
            self.selected = []
            self._say("nothing selected")
            return None
        self.selected = [*[s for s in self.selected if s != i][-1:], i]
        a = self.shown
        arc = a.arcs[i]
        what = "a straight line" if arc.is_line else f"circle {a.circles.index(arc.circle)}, k = {arc.circle.k}"
        pair = f" (and arc {self.selected[0]}: Connect joins them)" if len(self.selected) == 2 else ""
        self._say(f"arc {i} selected: {what}, {arc.length:.0f} px long{pair}")
        return i

    def _edit(
        self, make: Callable[[Abstraction], Abstraction], what: str, keep: Callable[[Abstraction], list[int]]
    ) -> bool:
        a = self.shown
        if a is None:
            return self._say("error: press Run first", ok=False)
        if not self.selected:
            return self._say("error: select an arc first (click it)", ok=False)

        def act() -> str:
            new = make(a)
            self._history.setdefault(self.level, []).append(new)
            self._redo.pop(self.level, None)
            self.selected = keep(new)
            self._cache.clear()
            return f"{what}; {len(new.arcs)} arcs (Undo takes it back)"

        return self._attempt(act)

    def delete_selected(self) -> bool:
        """Delete the selected arcs (:func:`img2logo.design.edits.delete_arc`), as one edit."""
        from ..design.edits import delete_arc

        chosen = sorted(set(self.selected), reverse=True)  # the last first: the others keep their indices

        def make(a: Abstraction) -> Abstraction:
            for i in chosen:
                a = delete_arc(a, i)
            return a

        what = f"arc {chosen[0]} deleted" if len(chosen) == 1 else f"arcs {', '.join(map(str, chosen[::-1]))} deleted"
        return self._edit(make, what, lambda new: [])

    def _circle_of_selected(self, a: Abstraction, op: str) -> int:
        arc = a.arcs[self.selected[-1]]
        if arc.is_line:
            raise InvalidParameterError(f"{op}: arc {self.selected[-1]} is a straight line, it has no golden circle")
        return a.circles.index(arc.circle)

    def move_selected(self, dx: float, dy: float) -> bool:
        """Move the circle of the selected arc by (dx, dy), px (:func:`img2logo.design.edits.move_circle`)."""
        from ..design.edits import move_circle

        def make(a: Abstraction) -> Abstraction:
            c = self._circle_of_selected(a, "move")
            return move_circle(a, c, a.circles[c].center + np.array([float(dx), float(dy)]))

        i = self.selected[-1] if self.selected else -1
        return self._edit(
            make, f"circle of arc {i} moved by ({dx:g}, {dy:g}) px", lambda new: [min(i, len(new.arcs) - 1)]
        )

    def rung_selected(self, delta: int) -> bool:
        """Move the selected arc's circle ``delta`` rungs (:func:`~img2logo.design.edits.change_rung`)."""
        from ..design.edits import change_rung

        def make(a: Abstraction) -> Abstraction:
            return change_rung(a, self._circle_of_selected(a, "change rung"), int(delta))

        i = self.selected[-1] if self.selected else -1
        return self._edit(make, f"circle of arc {i}: rung {int(delta):+d}", lambda new: [min(i, len(new.arcs) - 1)])

    def add_other_side(self) -> bool:
        """Add the other side of the selected arc's circle, between the arc's two ends (Fig. 17 "add").

        :func:`img2logo.design.edits.add_arc` on the arc's own circle from its start junction to its
        end junction, around the other way.
        """
        from ..design.edits import add_arc

        def make(a: Abstraction) -> Abstraction:
            i = self.selected[-1]
            arc = a.arcs[i]
            self._circle_of_selected(a, "add")
            if a.arc_junctions is None:
                raise InvalidParameterError("add: this logo records no junctions")
            ends = a.arc_junctions[i]
            if ends.start is None or ends.end is None or ends.start == ends.end:
                raise InvalidParameterError(f"add: arc {i} does not end at two junctions (a closed circle?)")
            return add_arc(a, arc.circle, ends.start, ends.end, sweep_sign=-1 if arc.sweep > 0 else +1)

        i = self.selected[-1] if self.selected else -1
        return self._edit(make, f"the other side of arc {i}'s circle added", lambda new: [len(new.arcs) - 1])

    def lock_preview(self) -> list[np.ndarray]:
        """The segments of the last run that the lock mask covers, each (N, 2) points, px: what the next Run locks.

        The rule of the run (:func:`img2logo.fit.progressive.locked_segments`: most of a
        segment's points inside the mask), applied to the last run's segment graph, with the
        mask at its working size (a Run with other settings may find other segments).
        """
        if self.result is None or not self.mask.any():
            return []
        from ..fit.progressive import locked_segments
        from ..images.loading import mask_to_working_size

        graph = self.result.graph
        mask = mask_to_working_size(self.mask, self.result.image, "lock mask")
        locked = locked_segments(graph, mask)
        k = self.work_scale
        return [np.asarray(graph.segments[i], dtype=np.float64) / k for i in np.flatnonzero(locked)]

    def set_exponents(self, text: str) -> bool:
        """The golden circles to use at the next Run (Fig. 15): exponents k as ``"3, 5, 8"``; empty for all."""
        words = [w for w in str(text).replace(",", " ").split() if w]
        try:
            exponents = tuple(sorted({int(w) for w in words})) if words else None
        except ValueError:
            return self._say(f"error: circle sizes must be whole numbers k separated by commas, got {text!r}", False)
        self.settings = dataclasses.replace(self.settings, exponents=exponents)
        chosen = "all" if exponents is None else "k = " + ", ".join(map(str, exponents))
        return self._say(f"circle sizes: {chosen}; press Run")

    @property
    def rungs_used(self) -> tuple[int, ...]:
        """The exponents k of the golden circles of the first level of the run (the candidates of Fig. 15)."""
        if not self.levels:
            return ()
        return tuple(sorted({int(c.k) for c in self.levels[0].golden_circles if c.k is not None}))

    def connect_selected(self) -> bool:
        """Join the two selected arcs at their nearest free ends (:func:`~img2logo.design.edits.connect`)."""
        from ..design.edits import connect

        if len(self.selected) != 2:
            return self._say("error: connect needs two arcs: click one, then the other", ok=False)

        def make(a: Abstraction) -> Abstraction:
            ends = [free_ends(a, i) for i in self.selected]
            for i, e in zip(self.selected, ends, strict=True):
                if not e:
                    raise InvalidParameterError(f"connect: arc {i} has no free end (both its ends meet other arcs)")
            pairs = [(j0, j1) for j0 in ends[0] for j1 in ends[1] if j0 != j1]
            if not pairs:
                raise InvalidParameterError("connect: the two arcs share their only free end")
            j0, j1 = min(pairs, key=lambda p: float(np.hypot(*(a.junctions[p[0]] - a.junctions[p[1]]))))
            return connect(a, j0, j1)

        pair = tuple(self.selected)
        return self._edit(make, f"arcs {pair[0]} and {pair[1]} connected", lambda new: [len(new.arcs) - 1])

    def undo(self) -> bool:
        """Take the last edit of the level shown back."""
        return self._shift_edit(self._history, self._redo, "undo", "undone")

    def redo(self) -> bool:
        """Make the last edit undone on the level shown again (a new edit forgets what was undone)."""
        return self._shift_edit(self._redo, self._history, "redo", "redone")

    def _shift_edit(
        self, source: dict[int, list[Abstraction]], target: dict[int, list[Abstraction]], verb: str, done: str
    ) -> bool:
        """Move the last logo of the level shown from one stack (edits, or edits undone) to the other."""
        stack = source.get(self.level)
        if not stack:
            return self._say(f"error: nothing to {verb} on this level", ok=False)
        target.setdefault(self.level, []).append(stack.pop())
        self.selected = []
        self._cache.clear()
        return self._say(f"edit {done}; {self.title}")

    @property
    def n_edits(self) -> int:
        """Edits made on the level shown."""
        return len(self._history.get(self.level, []))

    def _reset_edits(self) -> None:
        self._history, self._redo, self._colours = {}, {}, {}
        self.selected = []
        self._cache.clear()

    def _cached(self, key: str, make: Callable[[], Any]) -> Any:
        """``make()`` once per logo shown and fill option (the cache is keyed on both)."""
        full = (key, id(self.shown), self.settings.fill, tuple(sorted(self._colours_of_shown().items())))
        if full not in self._cache:
            self._cache[full] = make()
        return self._cache[full]

    # ------------------------------------------------------------------ fills and downloads
    def fills(self) -> tuple[Fill, ...] | None:
        """The fills of the logo shown (None for ``fill = "none"``), as the command line makes them.

        A region given its own colour (:meth:`colour_region_at`) has that colour, flat.
        """
        from ..design.fills import parse_fill_option

        a = self.shown
        spec = parse_fill_option(self.settings.fill)
        if a is None or spec.mode == "none":
            return None

        def make() -> tuple[Fill, ...]:
            made = spec.make(a, self.result.image)
            own = self._colours_of_shown()
            return tuple(
                dataclasses.replace(f, color=own[i], gradient=None) if i in own else f for i, f in enumerate(made)
            )

        return self._cached("fills", make)

    def _colours_of_shown(self) -> dict[int, str]:
        """The regions of the logo shown given their own colour: fill index -> ``#rrggbb``."""
        entry = self._colours.get(id(self.shown))
        return entry[1] if entry is not None else {}

    def region_at(self, x: float, y: float) -> int | None:
        """The index of the fill region of the logo shown that holds point (x, y), px (even-odd rule); else None."""
        import shapely

        fills = self.fills()
        for i, f in enumerate(fills or ()):
            inside = sum(bool(shapely.contains_xy(shapely.Polygon(r), float(x), float(y))) for r in f.rings())
            if inside % 2:
                return i
        return None

    def colour_region_at(self, x: float, y: float, colour: str) -> bool:
        """Give the fill region at (x, y), px, its own flat colour ``colour`` (``#rrggbb``) in the drawing and files."""
        from ..design.fill_values import parse_color

        if self.fills() is None:
            return self._say("error: choose fills first (a region's colour changes a fill)", ok=False)

        def act() -> str:
            value = parse_color(colour, "colour")
            i = self.region_at(x, y)
            if i is None:
                raise InvalidParameterError(f"no region at ({x:.0f}, {y:.0f}) px: click inside a filled region")
            a = self.shown
            if a is None:
                raise InvalidParameterError("press Run first")
            own = dict(self._colours_of_shown())
            own[i] = value
            self._colours[id(a)] = (a, own)
            return f"region {i}: {value}"

        return self._attempt(act)

    def set_fill(self, fill: str) -> bool:
        """Colour the logo with the command line's ``--fill`` option ``fill`` (no new Run)."""

        def act() -> str:
            from ..design.fills import parse_fill_option

            parse_fill_option(fill)
            old = self.settings
            self.settings = dataclasses.replace(old, fill=fill)
            self._colours = {}  # another fill option: other regions, or the same in another order
            try:
                fills = self.fills()
            except Img2LogoError:
                self.settings = old
                raise
            return f"fill {fill}: {len(fills)} regions" if fills is not None else "no fill"

        return self._attempt(act)

    @property
    def download_stem(self) -> str:
        """The downloads' name without suffix: the image's stem, the level, and ``-edited`` after an edit.

        ``hedgehog-level12-edited``: the variants a designer saves do not overwrite each other.
        """
        if not self.levels:
            return self.stem
        return f"{self.stem}-level{self.level}" + ("-edited" if self.n_edits else "")

    def download_names(self, formats: tuple[str, ...] = DOWNLOAD_FORMATS) -> dict[str, str]:
        """The file name of each download, by format (:data:`DOWNLOAD_FORMATS`)."""
        check = set(formats) - set(DOWNLOAD_FORMATS)
        if check:
            raise InvalidParameterError(f"format must be one of {', '.join(DOWNLOAD_FORMATS)}, got {sorted(check)}")
        ends = {"png-transparent": "-transparent.png", "png-input": "-over-input.png"}
        return {fmt: self.download_stem + ends.get(fmt, "." + fmt) for fmt in formats}

    def downloads(self, formats: tuple[str, ...] = DOWNLOAD_FORMATS) -> dict[str, bytes]:
        """The files of the logo shown, by format: the bytes the command line's writers give.

        ``img2logo INPUT --level t --fill F --svg/--json/--pdf/--png [--png-background B]`` writes
        these files for the level without edits: ``png`` is on white, ``png-transparent`` on
        nothing, ``png-input`` over the faded input (the writers
        :func:`~img2logo.export.writers.write_svg`, :func:`~img2logo.export.writers.write_json`,
        :func:`~img2logo.export.writers.write_pdf` and :func:`~img2logo.export.writers.write_png`
        are called as the command line calls them, into a temporary folder).
        """
        from ..export import writers

        a = self.shown
        if a is None:
            raise InvalidParameterError("nothing to download: press Run first")
        names = self.download_names(formats)
        fills = self.fills()
        backgrounds = {"png": "white", "png-transparent": "transparent", "png-input": "input"}

        def make() -> dict[str, bytes]:
            out: dict[str, bytes] = {}
            with tempfile.TemporaryDirectory(prefix="img2logo-studio-") as folder:
                for fmt in formats:
                    written = writers.write(
                        a,
                        Path(folder) / names[fmt],
                        fmt.split("-")[0],
                        fills=fills,
                        image=self.result.image.rgb,
                        background=backgrounds.get(fmt),
                    )
                    out[fmt] = written.read_bytes()
            return out

        return self._cached("downloads:" + ",".join(formats), make)


def free_ends(a: Abstraction, arc: int) -> list[int]:
    """The ends of arc ``arc`` where no other arc meets it (free ends, :func:`img2logo.design.edits.connect`)."""
    ends = a.arc_junctions[arc]
    out = []
    for j in (ends.start, ends.end):
        if j is not None and set(a.junction_arcs[j]) == {arc} and j not in out:
            out.append(j)
    return out


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
