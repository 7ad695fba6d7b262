"""The level explorer (``11_explore_levels``): the levels of a run beside a slider, T, bias, RDP, image, kind.

:class:`LevelExplorer` keeps its state and callbacks on plain values, so they
run (and are tested) without a browser; ipywidgets is imported only when the
widgets are built. The levels of a smaller T are read off a run with a larger
one (:func:`levels_within`).
"""

from __future__ import annotations

import dataclasses
import io
import os
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..constants import RDP_TOLERANCE, TOLERANCE
from ..errors import InvalidParameterError
from ..export.plotting import plot_abstraction
from ..geometry.abstraction import Abstraction
from . import table
from .layout import frame_bounds, panel_grid
from .paths import data_path, example_images, kit_module, load_example
from .results import final_level_index

if TYPE_CHECKING:
    import pandas as pd
    from matplotlib.figure import Figure

    from ..pipeline import Result

#: Longest side of the level explorer's drawing on screen, CSS px: beside its controls (about 400 px)
#: it fits a 1440 x 900 laptop screen in JupyterLab, and it is the size a logo is judged at.
EXPLORER_SIZE = 440


def abstract_with_settings(image: object, settings: Any, **extra: Any) -> Result:
    """:func:`img2logo.abstract` of ``image`` with the fields of ``settings`` that are :class:`~img2logo.Options`'s.

    The one call of the explorer (:class:`ExplorerSettings`) and the studio
    (:class:`img2logo.studio.session.StudioSettings`): a setting added to their
    dataclass under an option's name reaches the run without a second edit.

    Parameters
    ----------
    image : path, ndarray or LoadedImage
        The input (:func:`img2logo.load_image`).
    settings : dataclass instance
        Its fields named as :class:`~img2logo.options.Options` fields are passed;
        the others (the explorer's image name, the studio's fill) are not.
    **extra
        Further keywords of :func:`img2logo.abstract` (``lock_mask``, ``subject``, ``progress``).

    Returns
    -------
    Result
    """
    from ..options import Options
    from ..pipeline import abstract

    options = {f.name for f in dataclasses.fields(Options)}
    given = {f.name: getattr(settings, f.name) for f in dataclasses.fields(settings) if f.name in options}
    return abstract(image, **given, **extra)


def levels_within(result: Result, tolerance: float | None = None) -> tuple[Abstraction, ...]:
    """The levels a run with T = ``tolerance`` (px, at most the run's T; None: all) gives, read off ``result``.

    The merges do not depend on T: a run stops before the first level whose E^s
    exceeds T (Sec. 5.2, step 2; :func:`~img2logo.experiments.results.final_level_index`,
    checked against runs made per T by notebook 04, ``monotonicity.csv``).

    Raises
    ------
    InvalidParameterError
        ``tolerance`` above the run's T: its levels cannot tell a larger T's.
    """
    levels = result.levels
    run_tolerance = levels[0].tolerance
    if tolerance is None:
        return levels
    if not tolerance > 0 or tolerance > run_tolerance:
        raise InvalidParameterError(f"tolerance must be in (0, {run_tolerance:g}] px for this run, got {tolerance}")
    return levels[: final_level_index(result.progression, tolerance) + 1]


def level_title(result: Result, t: int, name: str | None = None, *, tolerance: float | None = None) -> str:
    """The title of level ``t``: the level, |A|, E^s and T (of :func:`levels_within` ``tolerance``)."""
    levels = levels_within(result, tolerance)
    a = levels[t]
    prefix = f"{name}: " if name else ""
    shown = a.tolerance if tolerance is None else tolerance
    return (
        f"{prefix}level t = {a.level} of {len(levels) - 1}, |A| = {len(a.arcs)}, "
        f"E^s = {a.similarity:.2f} px (T = {shown:g})"
    )


def levels_table(result: Result) -> pd.DataFrame:
    """Per level t of a run: |A^t|, distinct radii and E^s (px), the numbers behind the slider."""
    return table(
        result.levels,
        {
            "t": lambda a: a.level,
            "arcs": lambda a: len(a.arcs),
            "distinct radii": lambda a: len({arc.circle.k for arc in a.arcs}),
            "E^s (px)": lambda a: round(a.similarity, 3),
        },
    )


def plot_level_strip(
    result: Result, levels: Sequence[int] | int = 4, *, name: str | None = None, panel_size: float = 3.0
) -> Figure:
    """A row of levels of one run, arcs over the faded input (a static view of the explorer).

    ``levels`` is a list of t (negative counts from the end) or a number of
    levels spread evenly from A^0 to the final one.
    """
    n_levels = len(result.levels)
    if isinstance(levels, int):
        ts = sorted({round(float(v)) for v in np.linspace(0, n_levels - 1, max(1, min(levels, n_levels)))})
    else:
        ts = [t % n_levels for t in levels]
    fig, axes = panel_grid(1, len(ts), panel_size, extra_height=0.5)
    for ax, t in zip(axes[0], ts, strict=True):
        a = result.level(t)
        plot_abstraction(a, ax, image=result.image.rgb)
        frame_bounds(ax, np.vstack(list(result.graph.segments)), result.graph.width, result.graph.height)
        ax.set_title(f"t = {t}: |A| = {len(a.arcs)}, E^s = {a.similarity:.2f} px", fontsize=9)
    if name:
        fig.suptitle(f"{name}: levels of one run (T = {result.final.tolerance:g})", fontsize=10)
    return fig


@dataclass(frozen=True)
class ExplorerSettings:
    """The inputs of one :class:`LevelExplorer` run.

    Attributes
    ----------
    image : str
        A file name in ``data/`` or a path.
    tolerance : float
        T, px.
    bias : float or None
        The ladder bias sigma; None: automatic (Eqn. 14).
    rdp_tolerance : float
        Ramer-Douglas-Peucker tolerance, px.
    kind : str
        ``"auto"``, ``"photo"``, ``"clipart"`` or ``"drawing"``.
    symmetry : str
        ``"none"``, ``"auto"``, ``"vertical"``, ``"horizontal"`` or an angle in
        degrees: a mirror-symmetric logo (:mod:`img2logo.fit.symmetry`).
    """

    image: str = "clipart-fish.png"
    tolerance: float = TOLERANCE
    bias: float | None = None
    rdp_tolerance: float = RDP_TOLERANCE
    kind: str = "auto"
    symmetry: str = "none"


class LevelExplorer:
    """Browse the levels A^0 ... A^final of a run, and re-run with other settings.

    The state and the callbacks work on plain values, so they run (and are
    tested) without a browser; :meth:`widget` wraps them in ipywidgets: the
    drawing at a fixed size beside its controls, a level slider (instant
    redraw: every level is precomputed), T, the bias (with an "auto" box), the
    RDP tolerance, the image and its kind, and a Run button with a progress bar
    (E^s filling towards T) fed by :func:`img2logo.abstract`'s progress callback.

    Changing T is instant up to the largest T run so far with the same other
    settings: that run holds the levels of every smaller T
    (:func:`levels_within`); a larger T runs again, with the progress bar.

    Parameters
    ----------
    settings : ExplorerSettings, optional
        The first run's inputs; keyword arguments override its fields.
    result : Result, optional
        A precomputed run for ``settings``; computed now when None.
    size : int
        Longest side of the drawing on screen, CSS px.
    dpi : float
        Resolution of the drawing's PNG; ``2 * 72`` pixels per inch of the
        figure is twice the screen size, crisp on high-density screens.

    Attributes
    ----------
    settings : ExplorerSettings
        The inputs of the levels shown (``settings.tolerance`` is the T shown).
    result : Result
        The run holding them: the largest T run so far with these settings.
    levels : tuple of Abstraction
        The levels of T (:func:`levels_within`); ``level`` is the one shown, drawn
        in ``figure`` (its ``title`` shown by the widget).
    progress_text : str
        The last progress message of a run.
    controls : dict
        The widgets by name, once :meth:`widget` built them (else empty).
    """

    def __init__(
        self,
        settings: ExplorerSettings | None = None,
        *,
        result: Result | None = None,
        size: int = EXPLORER_SIZE,
        dpi: float = 144.0,
        **overrides: Any,
    ) -> None:
        from matplotlib.figure import Figure

        self.settings = dataclasses.replace(settings or ExplorerSettings(), **overrides)
        self.dpi = float(dpi)
        self.size = int(size)
        self.controls: dict[str, Any] = {}
        self.progress_text = ""
        self.level = 0
        self.title = ""
        self._syncing = False
        self.result = result if result is not None else self._compute(self.settings)
        self.levels = levels_within(self.result, self.settings.tolerance)
        height, width = self.result.image.rgb.shape[:2]
        scale = self.size / max(height, width)
        self.figure = Figure(figsize=(width * scale / 72.0, height * scale / 72.0))
        self._ax = self.figure.add_axes((0.0, 0.0, 1.0, 1.0))
        self.on_level_change(len(self.levels) - 1)

    # ------------------------------------------------------------------ plain callbacks
    @property
    def n_levels(self) -> int:
        """Number of levels shown (those of T)."""
        return len(self.levels)

    @property
    def name(self) -> str:
        """The image's name."""
        return Path(self.settings.image).stem

    @property
    def title_html(self) -> str:
        """:attr:`title` as HTML, with E<sup>s</sup> and |<i>A</i>| set as in the paper."""
        import html

        return "<b>" + html.escape(self.title).replace("E^s", "E<sup>s</sup>").replace("|A|", "|<i>A</i>|") + "</b>"

    @property
    def screen_size(self) -> tuple[int, int]:
        """Width and height of the drawing on screen, CSS px."""
        w, h = self.figure.get_size_inches() * 72.0
        return round(w), round(h)

    def on_level_change(self, t: int) -> Figure:
        """Show level ``t`` (negative counts from the end): redraw the figure and title."""
        t = int(t)
        if not -self.n_levels <= t < self.n_levels:
            raise InvalidParameterError(f"level must be in [0, {self.n_levels - 1}], got {t}")
        self.level = t % self.n_levels
        self.title = level_title(self.result, self.level, self.name, tolerance=self.settings.tolerance)
        self._ax.clear()
        plot_abstraction(self.levels[self.level], self._ax, image=self.result.image.rgb)
        self._ax.set_axis_off()
        self._sync_widgets()
        return self.figure

    def on_tolerance_change(self, tolerance: float) -> bool:
        """Show the result of T = ``tolerance``: at once when the run holds it, else run again.

        Returns True when it needed a new run.
        """
        tolerance = float(tolerance)
        if 0 < tolerance <= self.result.levels[0].tolerance:
            self.settings = dataclasses.replace(self.settings, tolerance=tolerance)
            self.levels = levels_within(self.result, tolerance)
            self.on_level_change(self.n_levels - 1)
            return False
        self.on_run(tolerance=tolerance)
        return True

    def on_run(self, **changes: Any) -> Result:
        """Re-run :func:`img2logo.abstract` with ``changes`` to the settings; show its final level.

        ``changes`` are fields of :class:`ExplorerSettings` (``bias=None`` is automatic).
        """
        unknown = set(changes) - {f.name for f in dataclasses.fields(ExplorerSettings)}
        if unknown:
            raise InvalidParameterError(f"unknown settings {sorted(unknown)}")
        settings = dataclasses.replace(self.settings, **changes)
        self.result = self._compute(settings)
        self.settings = settings
        self.levels = self.result.levels
        self.on_level_change(self.n_levels - 1)
        return self.result

    def on_progress(self, t: int, n_arcs: int, similarity: float) -> None:
        """The progress callback of a run: level t reached with ``n_arcs`` arcs and E^s (px).

        The bar fills with E^s towards T, as the terminal bar of :func:`img2logo.abstract`
        does: the loop stops when E^s would exceed T, so the number of merges is
        not known in advance.
        """
        self.progress_text = f"level {t}: |A| = {n_arcs}, E^s = {similarity:.2f} px"
        bar = self.controls.get("progress")
        if bar is not None:
            bar.value = min(float(similarity), bar.max)
            self.controls["status"].value = self.progress_text

    def png(self) -> bytes:
        """The current drawing as PNG bytes, at :attr:`dpi`."""
        buf = io.BytesIO()
        self.figure.savefig(buf, format="png", dpi=self.dpi, facecolor="white", metadata={"Software": None})
        return buf.getvalue()

    def _compute(self, settings: ExplorerSettings) -> Result:
        image = settings.image
        path = Path(image) if os.sep in image or Path(image).is_file() else data_path(image)
        self.progress_text = "running"
        bar = self.controls.get("progress")
        if bar is not None:
            bar.bar_style = ""
            bar.max = float(settings.tolerance)
            bar.value = 0.0
            self.controls["status"].value = "running"
        result = abstract_with_settings(load_example(path), settings, progress=self.on_progress)
        self.progress_text = (
            f"done: {len(result.levels)} levels, |A| = {len(result.final.arcs)}, "
            f"{sum(result.timings.values()):.2f} s ({result.progression.stopped_because})"
        )
        if bar is not None:
            bar.value = min(float(result.final.similarity), bar.max)
            bar.bar_style = "success"
            self.controls["status"].value = self.progress_text
        return result

    # ------------------------------------------------------------------ widgets
    def widget(self) -> Any:
        """The ipywidgets interface (built once): the drawing, and beside it the controls.

        The drawing has a fixed size (:attr:`screen_size`; the PNG has twice its
        pixels), so it stays crisp and the whole fits a laptop screen.
        """
        w = kit_module("ipywidgets")
        if "box" in self.controls:
            return self.controls["box"]
        s = self.settings
        images = [p.name for p in example_images()]
        if s.image not in images:
            images.append(s.image)
        c = self.controls
        style = {"description_width": "70px"}
        wide = w.Layout(width="360px")

        def slider(kind: Any, description: str, layout: Any = wide, **kwargs: Any) -> Any:
            return kind(description=description, style=style, layout=layout, **kwargs)

        c["level"] = slider(w.IntSlider, "level t", value=self.level, min=0, max=self.n_levels - 1)
        c["tolerance"] = slider(
            w.FloatSlider, "T (px)", value=s.tolerance, min=0.5, max=30.0, step=0.5, continuous_update=False
        )
        c["image"] = slider(w.Dropdown, "image", options=images, value=s.image)
        c["kind"] = slider(w.Dropdown, "kind", options=["auto", "photo", "clipart", "drawing"], value=s.kind)
        symmetries = list(dict.fromkeys(["none", "auto", "vertical", "horizontal", s.symmetry]))
        c["symmetry"] = slider(w.Dropdown, "symmetry", options=symmetries, value=s.symmetry)
        c["rdp_tolerance"] = slider(
            w.FloatSlider, "RDP (px)", value=s.rdp_tolerance, min=0.5, max=8.0, step=0.25, continuous_update=False
        )
        c["bias"] = slider(
            w.FloatSlider,
            "bias \u03c3",
            w.Layout(width="250px"),
            value=self.result.bias if s.bias is None else s.bias,
            min=0.0,
            max=0.99,
            step=0.01,
            disabled=s.bias is None,
            continuous_update=False,
        )
        c["bias_auto"] = w.Checkbox(
            value=s.bias is None, description="auto", indent=False, layout=w.Layout(width="100px")
        )
        c["run"] = w.Button(description="Run", button_style="primary", icon="play", layout=w.Layout(width="90px"))
        c["progress"] = slider(
            w.FloatProgress,
            "E\u02e2 \u2192 T",
            w.Layout(width="260px"),
            value=min(self.result.final.similarity, s.tolerance),
            min=0.0,
            max=s.tolerance,
        )
        c["status"] = w.Label(value=self.progress_text, layout=wide)
        c["title"] = w.HTML(value=self.title_html)
        width, height = self.screen_size
        c["drawing"] = w.Image(
            value=self.png(),
            format="png",
            layout=w.Layout(width=f"{width}px", height=f"{height}px", flex="0 0 auto", object_fit="contain"),
        )
        c["level"].observe(self._level_widget_changed, names="value")
        c["tolerance"].observe(self._tolerance_widget_changed, names="value")
        c["bias_auto"].observe(self._bias_auto_changed, names="value")
        c["run"].on_click(self._run_clicked)
        note = w.HTML(
            value="<small>T up to the largest T run so far is instant; a larger T, or new image, kind, "
            "symmetry, RDP or bias settings, run again (Run).</small>",
            layout=wide,
        )
        controls = w.VBox(
            [
                c["level"],
                c["tolerance"],
                c["image"],
                c["kind"],
                c["symmetry"],
                c["rdp_tolerance"],
                w.HBox([c["bias"], c["bias_auto"]]),
                w.HBox([c["run"], c["progress"]]),
                c["status"],
                note,
            ],
            layout=w.Layout(flex="0 0 auto", padding="0 0 0 12px"),
        )
        c["box"] = w.VBox([c["title"], w.HBox([c["drawing"], controls], layout=w.Layout(align_items="flex-start"))])
        return c["box"]

    def display(self) -> None:
        """Show :meth:`widget` in the notebook."""
        from IPython.display import display

        display(self.widget())

    def widget_settings(self) -> ExplorerSettings:
        """The settings the widgets hold now."""
        c = self.controls
        if not c:
            return self.settings
        return ExplorerSettings(
            image=c["image"].value,
            tolerance=float(c["tolerance"].value),
            bias=None if c["bias_auto"].value else float(c["bias"].value),
            rdp_tolerance=float(c["rdp_tolerance"].value),
            kind=c["kind"].value,
            symmetry=c["symmetry"].value,
        )

    def _level_widget_changed(self, change: dict[str, Any]) -> None:
        if not self._syncing:
            self.on_level_change(change["new"])

    def _tolerance_widget_changed(self, change: dict[str, Any]) -> None:
        if not self._syncing:
            self._busy(lambda: self.on_tolerance_change(change["new"]))

    def _bias_auto_changed(self, change: dict[str, Any]) -> None:
        self.controls["bias"].disabled = bool(change["new"])

    def _run_clicked(self, _button: Any = None) -> None:
        self._busy(lambda: self.on_run(**dataclasses.asdict(self.widget_settings())))

    def _busy(self, action: Any) -> None:
        """Run ``action`` with the Run button disabled."""
        button = self.controls.get("run")
        if button is not None:
            button.disabled = True
        try:
            action()
        finally:
            if button is not None:
                button.disabled = False

    def _sync_widgets(self) -> None:
        """Push the state (level, its range, T, title, drawing) to the widgets, without echo."""
        c = self.controls
        if not c:
            return
        self._syncing = True
        try:
            c["level"].max = self.n_levels - 1
            c["level"].value = self.level
            c["tolerance"].value = self.settings.tolerance
            c["title"].value = self.title_html
            c["drawing"].value = self.png()
            if self.settings.bias is None:
                c["bias"].value = round(self.result.bias, 2)
        finally:
            self._syncing = False
