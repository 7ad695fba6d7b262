"""The studio's fills and downloads of the logo shown: the files the command line's writers give.

:class:`StudioFiles` colours the logo with a ``--fill`` option (a region may get its
own colour) and makes the SVG, JSON, PDF and PNGs of what is shown, named by the
image, the level and whether it was edited.
"""

from __future__ import annotations

import dataclasses
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import Img2LogoError, InvalidParameterError
from .state import StudioState

if TYPE_CHECKING:
    from ..design.fills import Fill

#: The downloads, by key: SVG, JSON, PDF, PNG on white, PNG on nothing (transparent), PNG over the faded input.
DOWNLOAD_FORMATS: tuple[str, ...] = ("svg", "json", "pdf", "png", "png-transparent", "png-input")


class StudioFiles(StudioState):
    """The fills and downloads of :class:`~.state.StudioState`'s logo shown."""

    def fills(self) -> tuple[Fill, ...] | None:
        """The fills of the logo shown (None for ``fill = "none"``), as the command line makes them.

        A region given its own colour (:meth:`colour_region_at`) has that colour, flat.
        """
        from ..design.fills import parse_fill_option

        a, result = self.shown, self.result
        spec = parse_fill_option(self.settings.fill)
        if a is None or result is None or spec.mode == "none":
            return None

        def make() -> tuple[Fill, ...]:
            made = spec.make(a, result.image)
            own = self._colours_of_shown()
            return tuple(
                dataclasses.replace(f, color=own[i], gradient=None) if i in own else f for i, f in enumerate(made)
            )

        return self._cached("fills", make)

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

        a, result = self.shown, self.result
        if a is None or result is None:
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
                        image=result.image.rgb,
                        background=backgrounds.get(fmt),
                    )
                    out[fmt] = written.read_bytes()
            return out

        return self._cached("downloads:" + ",".join(formats), make)


__all__ = ["DOWNLOAD_FORMATS", "StudioFiles"]
