"""The studio's state, shared by its runs (:mod:`.session`), edits (:mod:`.editing`) and files (:mod:`.outputs`).

:class:`StudioState` holds what the page shows (an image, its mask and subject, a run,
the level shown, the edits of each level, the selection, the one-line message) and
what every action uses: the message, the logo shown (:attr:`StudioState.shown`), its
title, and a cache per logo shown. :class:`StudioSettings` are the inputs of a Run.
"""

from __future__ import annotations

import dataclasses
import os
import warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..constants import DETAIL, RDP_TOLERANCE, TOLERANCE
from ..errors import Img2LogoError
from ..geometry.abstraction import Abstraction

if TYPE_CHECKING:
    from ..images.loading import LoadedImage
    from ..pipeline import Result


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
    arcs : int or None
        About this many arcs at most (``--arcs``); None: the default, about ``LOGO_ARCS``.
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
    arcs: int | None = None
    fill: str = "none"


def one_line(exc: BaseException | Warning | str, folder: str | None = None) -> str:
    """The message of ``exc`` on one line, without the temporary folder an upload was read from."""
    text = str(exc)
    if folder:
        text = text.replace(folder + os.sep, "")
    return " ".join(text.split())


class StudioState:
    """What the studio shows and remembers, and the helpers every action uses (no image loaded yet).

    Parameters
    ----------
    settings : StudioSettings, optional
        The first Run's settings; keyword arguments override its fields.
    """

    def __init__(self, settings: StudioSettings | None = None, **overrides: Any) -> None:
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
        self._cache: dict[tuple[Any, ...], Any] = {}
        # The free ends chosen, with the logo they are ends of, and which circle joins them (editing).
        self._ends: tuple[Abstraction, list[int]] | None = None
        self._end_choice = 0

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
            out = one_line(text, folder)  # type: ignore[arg-type]
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

    @property
    def stem(self) -> str:
        """The downloads' name: the input's file name without its suffix."""
        return Path(self.name).stem or "logo"

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

        ``fish: level 12 of 30, 25 arcs, error 3.21 px (tolerance 5 px), 1 edit``; a level made
        past T for the arc budget: ``... error 6.80 px (tolerance 5 px, past it for the arc budget)``.
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
        # A level made past T for the arc budget (Options.stretch) says so: its error is above the tolerance.
        past = ", past it for the arc budget" if a.similarity > a.tolerance else ""
        return (
            f"{self.stem}: level {self.level} of {len(self.levels) - 1}, {len(a.arcs)} arcs, "
            f"error {a.similarity * k:.2f} px (tolerance {self.settings.tolerance:g} px{size}{past}){edits}"
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

    def _colours_of_shown(self) -> dict[int, str]:
        """The regions of the logo shown given their own colour: fill index -> ``#rrggbb``."""
        entry = self._colours.get(id(self.shown))
        return entry[1] if entry is not None else {}


__all__ = ["StudioSettings", "StudioState", "one_line"]
