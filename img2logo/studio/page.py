"""The studio's page: ipywidgets and ipycanvas around a :class:`~.studio.Studio` (``make studio``, Voila).

:class:`StudioPage` draws the logo shown on an :class:`ipycanvas.MultiCanvas`
(vector arcs, drawn by the browser's canvas: a level or an edit redraws without
rendering a PNG) over the faded input, and takes the mouse on it: a click selects
an arc, a drag paints or erases the lock mask or draws the subject rectangle,
by the tool chosen. Every control calls one method of the :class:`~.studio.Studio`
and then redraws what changed; its one-line message is the page's status line.
The golden circles of the level shown can be drawn under it (the SVG's
construction layer), the selected arc's circle and centre always are; dragging
that centre moves the circle (:func:`img2logo.design.edits.move_circle`, on
release). The wheel zooms about the mouse (the + and - keys too, 0 fits the
image again), the Hand tool drags the zoomed drawing; only the part in view
of the input, the fills and the mask is drawn. With the drawing focused (click it) the keys edit: Ctrl+Z and
Ctrl+Shift+Z (or Ctrl+Y) undo and redo, Delete removes the selected arcs, the
arrows nudge the selected circle (with Shift ten times as far), Escape clears
the selection; a click with Shift held adds an arc to the selection or takes it out
(ipycanvas sends no modifier keys with a click: the Shift key's own key press,
on the focused drawing, marks the next click).
The downloads are ``<a download>`` anchors carrying the files as ``data:`` URLs
(they work in Voila and in JupyterLab, with no JavaScript of ours), named after
the image, the level and whether it was edited. Every change first replaces them
by their names without a link, and they come back made from what is drawn once the
page has been still for a moment: a click can never save a file of a level no
longer shown, and a scrub through the levels makes no files on the way.

The canvas has twice the pixels of its size on screen (crisp on high-density
screens); ipycanvas gives the mouse in canvas pixels.
"""

from __future__ import annotations

import asyncio
import base64
import html
from typing import Any

import numpy as np

from ..constants import IMAGE_FADE
from ..errors import Img2LogoError
from ..experiments.paths import example_images, kit_module
from ..export.plotting import ARC_COLOR, default_stroke_width
from .session import PICK_DISTANCE, Studio

#: Side of the square drawing on screen, CSS px: with two columns of controls of
#: ``CONTROLS_WIDTH`` beside it the page fits a 1366 x 768 laptop screen.
DRAWING_SIZE = 480
#: Width of the controls' labels (the designer's words), CSS px.
LABEL_WIDTH = "122px"
#: Width of each column of controls, CSS px.
CONTROLS_WIDTH = 400
#: Canvas pixels per CSS px of the drawing.
PIXEL_RATIO = 2
#: Colours on screen: the selection, the lock mask (with its opacity) and the subject rectangle.
SELECTION_COLOR = "#1f6fd1"
MASK_RGBA = (230, 60, 40, 110)
#: The segments a lock stroke covers (what the next Run keeps unmerged).
LOCKED_COLOR = "#8b0a50"
SUBJECT_COLOR = "#0a8a3a"
#: Background around an image that is not square.
FRAME_COLOR = "#eeeeee"
#: Step of the move buttons and arrow keys, px of the image.
MOVE_STEP = 2.0
#: Seconds the page must be still before the download links are made (a scrub makes none on the way).
DOWNLOADS_DELAY = 0.25
#: The largest zoom (times the fitted drawing) and the step of a wheel notch or a + / - key.
MAX_ZOOM = 16.0
ZOOM_STEP = 1.25
ARROW_KEYS = {"ArrowLeft": (-1, 0), "ArrowUp": (0, -1), "ArrowDown": (0, 1), "ArrowRight": (1, 0)}
#: How much the input under the logo is faded towards white: as the PNG writer's, more, or hidden.
INPUT_FADES = {"faded": IMAGE_FADE, "dim": 0.88, "hidden": 1.0}
#: The golden circles on screen (the SVG's construction layer), and the selected arc's circle and centre.
CIRCLE_RGBA = "rgba(192, 151, 58, 0.55)"
CENTRE_RADIUS = 7.0
#: What each download link says, by :data:`~.session.DOWNLOAD_FORMATS` key (the PNG over the input is left to
#: the command line: a logo to place is on white or on nothing).
DOWNLOAD_LABELS = {
    "svg": "SVG",
    "pdf": "PDF",
    "png": "PNG (white)",
    "png-transparent": "PNG (transparent)",
    "json": "JSON",
}
DOWNLOAD_TYPES = {
    "svg": "image/svg+xml",
    "json": "application/json",
    "pdf": "application/pdf",
    "png": "image/png",
    "png-transparent": "image/png",
}
FILL_PRESETS = {
    "none": "none",
    "auto": "auto",
    "palette": "palette:#264653,#2a9d8f,#e9c46a,#f4a261,#e76f51",
    "gradient": "linear@90:#ffb347,#ff5e62",
}
CSS = """
<style>
body[data-voila] .jp-MarkdownCell { display: none; }
body[data-voila] .jp-Cell { padding: 0; }
body[data-voila] { padding: 6px 12px; }
.img2logo-studio, .img2logo-studio .widget-label, .img2logo-studio .widget-button,
.img2logo-studio .widget-toggle-button, .img2logo-studio select, .img2logo-studio input,
.img2logo-studio .widget-readout { font-size: 13px; }
.img2logo-studio .studio-head { font-size: 18px; font-weight: 600; }
.img2logo-studio .studio-section { font-size: 13px; font-weight: 600; margin-top: 4px; color: #333; }
.img2logo-studio .studio-download { display: inline-block; margin: 2px 6px 2px 0; padding: 4px 10px;
  border: 1px solid #1f6fd1; border-radius: 3px; color: #1f6fd1; text-decoration: none; font-size: 13px; }
.img2logo-studio a.studio-download:hover { background: #e8f0fb; }
.img2logo-studio .studio-download.studio-pending { border-color: #bbb; color: #999; }
.img2logo-studio .studio-status { font-size: 13px; }
.img2logo-studio .studio-title { padding-right: 12px; box-sizing: border-box; }
.img2logo-studio .studio-title b { white-space: normal; }
.img2logo-studio .studio-hint { font-size: 12px; line-height: 1.4; color: #444; }
.img2logo-studio .studio-error { color: #b00020; font-weight: 600; }
</style>
"""


def _ipycanvas() -> Any:
    """ipycanvas, or one line saying how to install it (the extra ``[studio]``)."""
    try:
        import ipycanvas
    except ImportError:
        raise Img2LogoError(
            "ipycanvas is missing: the studio needs the extra [studio] (pip install -e '.[studio]'; make studio "
            "installs it)"
        ) from None
    return ipycanvas


class StudioPage:
    """The widgets of the studio around ``studio``; :attr:`box` is the page.

    Parameters
    ----------
    studio : Studio
        The state (an image loaded, perhaps a run made).
    size : int
        Side of the square drawing on screen, CSS px.

    Attributes
    ----------
    controls : dict
        The widgets by name (``run``, ``level``, ``tolerance``, ``upload``, ``tool``, ...).
    canvas : ipycanvas.MultiCanvas
        Five layers: the faded image, the golden circles, the logo, the lock mask, the selection
        (its circle and centre) and the subject.
    """

    def __init__(self, studio: Studio, *, size: int = DRAWING_SIZE) -> None:
        self.studio = studio
        self.size = int(size)
        self.side = self.size * PIXEL_RATIO
        self.controls: dict[str, Any] = {}
        self._drag: list[tuple[float, float]] = []
        self._moving: tuple[float, float] | None = None  # the centre being dragged, image px
        self._pending_downloads: asyncio.TimerHandle | None = None
        self._view: tuple[float, float, float] | None = None  # (scale, x, y) when zoomed; None: fitted
        self._pointer = (self.size * PIXEL_RATIO / 2.0,) * 2  # the mouse's last canvas position: the wheel's centre
        self._add_next = False
        self._syncing = False
        self.box = self._build()
        self.redraw(background=True)

    # ------------------------------------------------------------------ geometry of the drawing
    def _fit(self) -> tuple[float, float, float]:
        """(scale, x, y) of the whole image centred in the square: canvas px per image px, its corner's position."""
        img = self.studio.image
        if img is None:
            return 1.0, 0.0, 0.0
        k = self.side / max(img.input_width, img.input_height)
        return k, (self.side - img.input_width * k) / 2.0, (self.side - img.input_height * k) / 2.0

    @property
    def scale(self) -> float:
        """Canvas pixels per image pixel (the whole image fitted, times the zoom)."""
        return (self._view or self._fit())[0]

    @property
    def offset(self) -> tuple[float, float]:
        """Canvas position of the image's top-left corner (centred when fitted; zoom and pan move it)."""
        _, x, y = self._view or self._fit()
        return x, y

    @property
    def zoom(self) -> float:
        """The drawing's zoom: 1 when the whole image is fitted."""
        return self.scale / self._fit()[0]

    def zoom_at(self, x: float, y: float, factor: float) -> None:
        """Zoom by ``factor`` about canvas point (x, y) (the image point under it stays), within 1..``MAX_ZOOM``."""
        fit, _, _ = self._fit()
        k = min(max(self.scale * float(factor), fit), fit * MAX_ZOOM)
        ix, iy = self.to_image(x, y)
        self._view = None if k <= fit * (1.0 + 1e-9) else (k, float(x) - ix * k, float(y) - iy * k)
        self._redraw_view()

    def pan_by(self, dx: float, dy: float) -> None:
        """Move the zoomed drawing by (dx, dy), canvas px (the image keeps a quarter of the square in view)."""
        img = self.studio.image
        if self._view is None or img is None:
            return
        k, x, y = self._view
        w, h = img.input_width * k, img.input_height * k
        keep = self.side / 4.0
        x = min(max(x + float(dx), keep - w), self.side - keep)
        y = min(max(y + float(dy), keep - h), self.side - keep)
        self._view = (k, x, y)
        self._redraw_view()

    def fit_view(self) -> None:
        """The whole image in the square again."""
        self._view = None
        self._redraw_view()

    def _redraw_view(self) -> None:
        """Every layer again at the view's zoom and pan (the files do not change)."""
        with _ipycanvas().hold_canvas():
            for draw in (self._draw_background, self._draw_circles, self._draw_logo, self._draw_mask):
                draw()
            self._draw_overlay()
        self.controls["zoom"].value = f"{self.zoom:.0%}" if self._view is not None else "fit"

    def _visible(self, height: int, width: int, per_px: float) -> tuple[slice, slice, int, int, int, int] | None:
        """The part of a raster of ``height`` x ``width`` cells, ``per_px`` cells per image px, that is in view.

        Returns (rows, cols, x, y, w, h): the cells to draw and the canvas rectangle they fill;
        None when none is in view (a raster larger than the view is cut, not drawn whole).
        """
        k, (ox, oy) = self.scale, self.offset
        c0 = max(0, int(np.floor(-ox / k * per_px)))
        r0 = max(0, int(np.floor(-oy / k * per_px)))
        c1 = min(width, int(np.ceil((self.side - ox) / k * per_px)))
        r1 = min(height, int(np.ceil((self.side - oy) / k * per_px)))
        if c1 <= c0 or r1 <= r0:
            return None
        x, y = round(ox + c0 / per_px * k), round(oy + r0 / per_px * k)
        w, h = round(ox + c1 / per_px * k) - x, round(oy + r1 / per_px * k) - y
        return slice(r0, r1), slice(c0, c1), x, y, max(1, w), max(1, h)

    def to_image(self, x: float, y: float) -> tuple[float, float]:
        """Canvas pixels to image pixels."""
        ox, oy = self.offset
        return (float(x) - ox) / self.scale, (float(y) - oy) / self.scale

    # ------------------------------------------------------------------ building
    def _build(self) -> Any:
        w = kit_module("ipywidgets")
        ipycanvas = _ipycanvas()
        s, c = self.studio.settings, self.controls
        style = {"description_width": LABEL_WIDTH}
        wide = w.Layout(width=f"{CONTROLS_WIDTH - 10}px")

        def labelled(kind: Any, description: str, layout: Any = wide, **kwargs: Any) -> Any:
            kwargs.setdefault("style", style)
            return kind(description=description, layout=layout, **kwargs)

        self.canvas = ipycanvas.MultiCanvas(
            5,
            width=self.side,
            height=self.side,
            layout=w.Layout(width=f"{self.size}px", height=f"{self.size}px", flex="0 0 auto"),
        )
        # A canvas's drawing is the front end's: a page opened (or reloaded) after it was drawn gets it again.
        layers = (self._draw_background, self._draw_circles, self._draw_logo, self._draw_mask, self._draw_overlay)
        for i, draw in enumerate(layers):
            self.canvas[i].on_client_ready(lambda draw=draw: self._redraw_layer(draw))
        top = self.canvas[4]
        top.on_mouse_down(self._mouse_down)
        top.on_mouse_move(self._mouse_move)
        top.on_mouse_up(self._mouse_up)
        top.on_mouse_out(self._mouse_up)
        top.on_key_down(self._key_down)
        top.on_mouse_wheel(self._wheel)
        c["canvas"] = self.canvas

        c["status"] = w.HTML(layout=w.Layout(width="100%")).add_class("studio-status")
        c["title"] = w.HTML(layout=wide).add_class("studio-title")
        c["tool"] = w.ToggleButtons(
            options=[
                ("Select", "select"),
                ("Hand", "hand"),
                ("Brush", "brush"),
                ("Eraser", "eraser"),
                ("Subject", "subject"),
                ("Colour", "colour"),
            ],
            value="select",
            tooltips=[
                "click an arc to select it (a second one to connect the two); drag the selected circle's centre",
                "drag to move the zoomed drawing (the wheel zooms)",
                "paint where merges are forbidden (the lock mask, Fig. 16)",
                "erase the lock mask",
                "drag a rectangle around the subject of a photo (GrabCut's seed)",
                "click a filled region to give it the colour beside (fills on)",
            ],
            style={"button_width": "68px"},
        )
        c["colour"] = w.ColorPicker(
            value="#e76f51", concise=True, tooltip="the Colour tool's colour", layout=w.Layout(width="36px")
        )
        c["fit"] = w.Button(description="Fit", tooltip="the whole image (key 0)", layout=w.Layout(width="44px"))
        c["zoom"] = w.Label("fit", layout=w.Layout(width="46px"))
        c["brush"] = w.IntSlider(
            description="Brush (px)",
            value=8,
            min=1,
            max=40,
            tooltip="the brush's radius on screen",
            style={"description_width": "70px"},
            layout=w.Layout(width="230px"),
        )
        c["clear_mask"] = w.Button(description="Clear mask", layout=w.Layout(width="110px"))
        c["clear_subject"] = w.Button(description="Clear subject", layout=w.Layout(width="110px"))

        images = [p.name for p in example_images()]
        c["upload"] = w.FileUpload(
            accept="image/*,.png,.jpg,.jpeg,.webp,.tif,.tiff,.bmp",
            multiple=False,
            description="Upload image",
            layout=w.Layout(width="150px"),
        )
        c["example"] = w.Dropdown(
            options=["(example)", *images],
            value=self.studio.name if self.studio.name in images else "(example)",
            layout=w.Layout(width=f"{CONTROLS_WIDTH - 170}px"),
        )
        c["kind"] = labelled(
            w.Dropdown,
            "Image type",
            options=[("automatic", "auto"), ("photo", "photo"), ("clip art", "clipart"), ("drawing", "drawing")],
            value=s.kind,
            tooltip="kind (--kind): how the feature lines are found (Sec. 4)",
        )
        c["tolerance"] = labelled(
            w.FloatSlider,
            "Tolerance (px)",
            value=s.tolerance,
            min=0.5,
            max=30.0,
            step=0.5,
            continuous_update=False,
            tooltip="T: merging stops before a level whose error E^s exceeds it (Sec. 5.2); larger, fewer arcs",
        )
        c["bias"] = labelled(
            w.FloatSlider,
            "Circle size offset",
            w.Layout(width=f"{CONTROLS_WIDTH - 100}px"),
            value=0.0 if s.bias is None else s.bias,
            min=0.0,
            max=0.99,
            step=0.01,
            disabled=s.bias is None,
            continuous_update=False,
            tooltip="\u03c3: the radii are \u03c6^(k + \u03c3) (Eqn. 10); automatic: the best fit (Eqn. 14)",
        )
        c["bias_auto"] = w.Checkbox(
            value=s.bias is None, description="auto", indent=False, layout=w.Layout(width="80px")
        )
        c["rdp_tolerance"] = labelled(
            w.FloatSlider,
            "Simplify lines (px)",
            value=s.rdp_tolerance,
            min=0.5,
            max=8.0,
            step=0.25,
            continuous_update=False,
            tooltip="the Ramer-Douglas-Peucker tolerance of the feature lines (Sec. 4); larger, less detail",
        )
        c["symmetry"] = labelled(
            w.Dropdown,
            "Symmetry",
            options=["none", "auto", "vertical", "horizontal"],
            value=str(s.symmetry),
            tooltip="mirror the logo about an axis (Sec. 9)",
        )
        c["ladder"] = w.ToggleButtons(
            options=[("golden", "phi"), ("Fibonacci", "fibonacci")],
            value=s.ladder,
            tooltips=["radii phi**(k + bias) (the paper)", "radii unit * F(k), the Fibonacci grid (Fig. 2b)"],
            style={"button_width": "90px"},
        )
        c["lines"] = w.Checkbox(
            value=s.lines,
            description="Straighten nearly straight parts",
            indent=False,
            tooltip="lines: nearly straight segments become straight lines (Sec. 9, Fig. 20b)",
        )
        fill_mode = next((k for k, v in FILL_PRESETS.items() if v == s.fill), "palette")
        c["fill"] = labelled(
            w.Dropdown,
            "Fills",
            w.Layout(width="236px"),
            options=list(FILL_PRESETS),
            value=fill_mode,
            tooltip="colour the regions between the arcs (Fig. 18; --fill)",
        )
        c["fill_spec"] = w.Text(
            value=s.fill, placeholder="--fill, e.g. palette:#264653,#e9c46a", layout=w.Layout(width="144px")
        )
        c["run"] = w.Button(description="Run", button_style="primary", icon="play", layout=w.Layout(width="90px"))
        c["progress"] = labelled(
            w.FloatProgress,
            "Error",
            w.Layout(width="290px"),
            value=0.0,
            min=0.0,
            max=s.tolerance,
            tooltip="E^s, the similarity error of the level being merged, filling towards T",
        )

        c["level"] = self._level_slider(0)
        c["level_box"] = w.Box([c["level"]])
        c["circles"] = w.Checkbox(
            value=False,
            description="Golden circles",
            indent=False,
            layout=w.Layout(width="118px"),
            tooltip="the circles of the level shown, the SVG's construction layer",
        )
        c["input"] = w.ToggleButtons(
            options=[("Faded", "faded"), ("Dim", "dim"), ("Hidden", "hidden")],
            value="faded",
            tooltips=["the input under the logo, as in the PNG", "fainter", "no input: the logo alone"],
            style={"button_width": "62px"},
        )
        c["delete"] = w.Button(
            description="Delete arc",
            icon="trash",
            tooltip="Delete key (drawing focused)",
            layout=w.Layout(width="110px"),
        )
        c["connect"] = w.Button(
            description="Connect",
            icon="link",
            tooltip="a new golden arc between the nearest free ends of the two selected arcs (Fig. 17)",
            layout=w.Layout(width="90px"),
        )
        c["undo"] = w.Button(
            description="Undo", icon="undo", tooltip="Ctrl+Z (drawing focused)", layout=w.Layout(width="90px")
        )
        c["redo"] = w.Button(
            description="Redo", icon="repeat", tooltip="Ctrl+Shift+Z (drawing focused)", layout=w.Layout(width="90px")
        )
        arrows = {
            "left": ("\u2190", -1, 0),
            "up": ("\u2191", 0, -1),
            "down": ("\u2193", 0, 1),
            "right": ("\u2192", 1, 0),
        }
        for name, (label, dx, dy) in arrows.items():
            b = w.Button(
                description=label, tooltip=f"move the circle {name} (arrow key)", layout=w.Layout(width="44px")
            )
            b.on_click(
                lambda _b, dx=dx, dy=dy: self._act(lambda: self.studio.move_selected(dx * MOVE_STEP, dy * MOVE_STEP))
            )
            c[f"move_{name}"] = b
        c["rung_down"] = w.Button(
            description="Smaller", tooltip="the next smaller golden circle: k \u2212 1", layout=w.Layout(width="80px")
        )
        c["rung_up"] = w.Button(
            description="Larger", tooltip="the next larger golden circle: k + 1", layout=w.Layout(width="80px")
        )
        c["add"] = w.Button(
            description="Add other side",
            tooltip="Fig. 17 add: an arc on the selected arc's circle between its two ends, around the other way",
            layout=w.Layout(width="130px"),
        )
        c["detail"] = labelled(
            w.IntSlider,
            "Detail",
            value=s.detail,
            min=1,
            max=60,
            continuous_update=False,
            tooltip="clip art: the regions kept besides the background (--detail); fewer, the least important merge",
        )
        c["sizes"] = labelled(
            w.Text,
            "Only circle sizes",
            value="" if s.exponents is None else ", ".join(map(str, s.exponents)),
            placeholder="all (or k, e.g. 5, 7, 8)",
            tooltip="Fig. 15: only the golden circles of these rungs k, radii \u03c6^(k + \u03c3) (--radii)",
        )
        c["downloads"] = w.HTML(layout=wide)

        c["fit"].on_click(lambda _b: self.fit_view())
        c["circles"].observe(lambda _ch: self._redraw_layer(self._draw_circles), names="value")
        c["input"].observe(lambda _ch: self._redraw_layer(self._draw_background), names="value")
        c["upload"].observe(self._uploaded, names="value")
        c["example"].observe(self._example_chosen, names="value")
        c["tool"].observe(lambda _ch: self._drag.clear(), names="value")
        c["clear_mask"].on_click(lambda _b: self._act(self.studio.clear_mask, logo=False, mask=True))
        c["clear_subject"].on_click(lambda _b: self._act(self.studio.clear_subject, overlay=True))
        c["bias_auto"].observe(lambda ch: setattr(c["bias"], "disabled", bool(ch["new"])), names="value")
        c["run"].on_click(lambda _b: self.run())
        c["tolerance"].observe(self._tolerance_changed, names="value")
        c["fill"].observe(self._fill_mode_changed, names="value")
        c["fill_spec"].observe(self._fill_spec_changed, names="value")
        c["delete"].on_click(lambda _b: self._act(self.studio.delete_selected))
        c["connect"].on_click(lambda _b: self._act(self.studio.connect_selected))
        c["undo"].on_click(lambda _b: self._act(self.studio.undo))
        c["redo"].on_click(lambda _b: self._act(self.studio.redo))
        c["rung_down"].on_click(lambda _b: self._act(lambda: self.studio.rung_selected(-1)))
        c["rung_up"].on_click(lambda _b: self._act(lambda: self.studio.rung_selected(+1)))
        c["add"].on_click(lambda _b: self._act(self.studio.add_other_side))

        def section(text: str) -> Any:
            return w.HTML(f'<div class="studio-section">{html.escape(text)}</div>')

        hint = w.HTML(
            '<div class="studio-hint"><b>Select</b>: click an arc (a second one to connect them; Shift-click: '
            "several); drag its circle's centre to move it; keys: Ctrl+Z, Ctrl+Shift+Z, Delete, arrows. "
            "<b>Hand</b>: drag the zoomed drawing (the wheel zooms). <b>Brush</b> / <b>Eraser</b>: paint where "
            "merges are forbidden, then Run. <b>Subject</b>: a photo's subject. <b>Colour</b>: click a filled "
            "region.</div>",
            layout=w.Layout(width=f"{self.size}px"),
        )
        tools = w.VBox(
            [
                w.HBox([c["tool"], c["colour"]]),
                w.HBox([c["brush"], c["clear_mask"], c["clear_subject"]]),
                w.HBox(
                    [c["circles"], w.Label("Input", layout=w.Layout(width="40px")), c["input"], c["fit"], c["zoom"]]
                ),
                hint,
            ],
            layout=w.Layout(width=f"{self.size}px"),
        )
        left = w.VBox([self.canvas, tools], layout=w.Layout(flex="0 0 auto"))
        middle = w.VBox(
            [
                section("Your image"),
                w.HBox([c["upload"], c["example"]]),
                section("Settings (Run applies them)"),
                c["kind"],
                c["tolerance"],
                w.HBox([c["bias"], c["bias_auto"]]),
                c["rdp_tolerance"],
                c["detail"],
                c["symmetry"],
                w.HBox([w.Label("Ladder", layout=w.Layout(width="126px")), c["ladder"]]),
                c["sizes"],
                w.HBox([w.Label("", layout=w.Layout(width="126px")), c["lines"]]),
                w.HBox([c["fill"], c["fill_spec"]]),
                w.HBox([c["run"], c["progress"]]),
            ],
            layout=w.Layout(width=f"{CONTROLS_WIDTH}px", padding="0 0 0 14px", flex="0 0 auto"),
        )
        right = w.VBox(
            [
                section("Level"),
                c["title"],
                c["level_box"],
                section("Edit the selected arc"),
                w.HBox([c["delete"], c["connect"], c["undo"], c["redo"]]),
                w.HBox(
                    [
                        w.Label("move", layout=w.Layout(width="44px")),
                        c["move_left"],
                        c["move_up"],
                        c["move_down"],
                        c["move_right"],
                        c["rung_down"],
                        c["rung_up"],
                    ]
                ),
                c["add"],
                section("Save what is shown"),
                c["downloads"],
            ],
            layout=w.Layout(width=f"{CONTROLS_WIDTH}px", padding="0 0 0 14px", flex="0 0 auto"),
        )
        head = w.HTML(
            CSS + '<span class="studio-head">img2logo studio</span> '
            "<span>&mdash; your image to a golden ratio logo: circular arcs whose radii are "
            "&phi;<sup>k+&sigma;</sup></span>"
        )
        page = w.VBox([head, c["status"], w.HBox([left, middle, right], layout=w.Layout(align_items="flex-start"))])
        page.add_class("img2logo-studio")
        c["box"] = page
        return page

    def _level_slider(self, last: int, value: int = 0) -> Any:
        """The level slider, 0..``last``."""
        w = kit_module("ipywidgets")
        slider = w.IntSlider(
            description="Level",
            value=value,
            min=0,
            max=last,
            continuous_update=True,
            tooltip="t: the level A^t of the run, 0 the first fit, the last the simplest (Sec. 5.2)",
            style={"description_width": LABEL_WIDTH},
            layout=w.Layout(width=f"{CONTROLS_WIDTH - 10}px"),
        )
        slider.observe(self._level_changed, names="value")
        return slider

    # ------------------------------------------------------------------ drawing
    def redraw(self, *, background: bool = False, logo: bool = True, mask: bool = False, overlay: bool = True) -> None:
        """Draw the layers asked for and refresh the title, status, level slider and downloads.

        The downloads are made last: until then their links are names without a link
        (:meth:`_downloads_pending`), so that the drawing appears first and no click saves an old file.
        """
        ipycanvas = _ipycanvas()
        self._downloads_pending()
        with ipycanvas.hold_canvas():
            if background:
                self._draw_background()
                mask = True
            if logo:
                self._draw_circles()
                self._draw_logo()
            if mask:
                self._draw_mask()
            if overlay:
                self._draw_overlay()
        self._sync()

    def _redraw_layer(self, draw: Any) -> None:
        with _ipycanvas().hold_canvas():
            draw()

    def _draw_background(self) -> None:
        layer = self.canvas[0]
        layer.clear()
        img = self.studio.image
        if img is None:
            return
        import cv2

        layer.fill_style = FRAME_COLOR
        layer.fill_rect(0, 0, self.side, self.side)
        # The loaded copy (at most MAX_IMAGE_SIDE px) drawn over the input's frame, the part in view.
        view = self._visible(img.height, img.width, img.width / img.input_width)
        if view is None:
            return
        rows, cols, x, y, w, h = view
        fade = INPUT_FADES[self.controls["input"].value]
        if fade >= 1.0:
            layer.fill_style = "#ffffff"
            layer.fill_rect(x, y, w, h)
            return
        part = img.rgb[rows, cols]
        rgb = fade + (1.0 - fade) * part
        shrink = w < part.shape[1]
        shown = cv2.resize(rgb, (w, h), interpolation=cv2.INTER_AREA if shrink else cv2.INTER_NEAREST)
        layer.put_image_data(np.clip(shown * 255.0 + 0.5, 0, 255).astype(np.uint8), x, y)

    def _stroke_arcs(self, layer: Any, arcs: Any, color: str, width: float) -> None:
        k, (ox, oy) = self.scale, self.offset
        layer.stroke_style = color
        layer.line_width = width
        layer.line_cap = "round"
        layer.line_join = "round"
        for arc in arcs:
            layer.begin_path()
            if arc.is_line:
                layer.move_to(ox + arc.start[0] * k, oy + arc.start[1] * k)
                layer.line_to(ox + arc.end[0] * k, oy + arc.end[1] * k)
            else:
                c = arc.circle
                layer.arc(ox + c.cx * k, oy + c.cy * k, c.r * k, arc.theta0, arc.theta0 + arc.sweep, arc.sweep < 0)
            layer.stroke()

    def _draw_circles(self) -> None:
        """The golden circles of the logo shown (the SVG's hidden construction layer), when asked for."""
        layer = self.canvas[1]
        layer.clear()
        a = self.studio.shown
        if a is None or not self.controls["circles"].value:
            return
        k, (ox, oy) = self.scale, self.offset
        layer.stroke_style = CIRCLE_RGBA
        layer.line_width = 1.5
        for c in a.golden_circles:
            layer.stroke_circle(ox + c.cx * k, oy + c.cy * k, c.r * k)

    def _draw_logo(self) -> None:
        layer = self.canvas[2]
        layer.clear()
        a = self.studio.shown
        if a is None:
            return
        try:
            fills = self.studio.fills() or ()
        except Img2LogoError as exc:  # a fill that fails is said, the arcs still drawn
            self.studio.message, self.studio.ok, fills = f"error: fills: {exc}", False, ()
        if fills:
            self._draw_fills(layer, fills)
        width = default_stroke_width(a.width, a.height) * self.scale
        self._stroke_arcs(layer, a.arcs, ARC_COLOR, max(width, 2.0))

    def _draw_fills(self, layer: Any, fills: Any) -> None:
        """The fills drawn as the PNG writer draws them (:func:`img2logo.export.plotting.draw_fills`), as pixels."""
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure

        from ..export.plotting import draw_fills, frame_image

        a = self.studio.shown
        view = None if a is None else self._visible(a.height, a.width, 1.0)
        if a is None or view is None:
            return
        rows, cols, x, y, w, h = view
        fig = Figure(figsize=(w / 100.0, h / 100.0), dpi=100.0)
        fig.patch.set_alpha(0.0)
        agg = FigureCanvasAgg(fig)
        ax = fig.add_axes((0.0, 0.0, 1.0, 1.0))
        ax.patch.set_alpha(0.0)
        draw_fills(list(fills), ax, width=a.width, height=a.height)
        frame_image(ax, a.width, a.height)
        ax.set_xlim(cols.start, cols.stop)  # the part in view
        ax.set_ylim(rows.stop, rows.start)
        agg.draw()
        layer.put_image_data(np.asarray(agg.buffer_rgba()).copy(), x, y)

    def _draw_mask(self) -> None:
        layer = self.canvas[3]
        layer.clear()
        m = self.studio.mask
        if not m.size or not m.any():
            return
        import cv2

        view = self._visible(m.shape[0], m.shape[1], 1.0)
        if view is None:
            return
        rows, cols, x, y, w, h = view
        big = cv2.resize(m[rows, cols].astype(np.uint8), (w, h), interpolation=cv2.INTER_NEAREST).astype(bool)
        rgba = np.zeros((h, w, 4), dtype=np.uint8)
        rgba[big] = MASK_RGBA
        layer.put_image_data(rgba, x, y)
        # What the next Run locks: the segments of the last run under the mask, highlighted.
        k, (ox, oy) = self.scale, self.offset
        layer.stroke_style = LOCKED_COLOR
        layer.line_width = 4.0
        layer.line_cap = "round"
        for seg in self.studio.lock_preview():
            layer.stroke_lines(np.column_stack([ox + seg[:, 0] * k, oy + seg[:, 1] * k]))

    def _draw_overlay(self, moved: tuple[float, float] = (0.0, 0.0)) -> None:
        """The selected arcs, the last one's golden circle and centre (moved by ``moved``, image px), the subject."""
        layer = self.canvas[4]
        layer.clear()
        a, s = self.studio.shown, self.studio
        k, (ox, oy) = self.scale, self.offset
        if a is not None and s.selected:
            width = max(default_stroke_width(a.width, a.height) * k * 2.0, 6.0)
            arcs = [a.arcs[i] for i in s.selected if i < len(a.arcs)]
            self._stroke_arcs(layer, arcs[:-1], "#8db6ea", width)
            if moved == (0.0, 0.0):
                self._stroke_arcs(layer, arcs[-1:], SELECTION_COLOR, width)
            if arcs and not arcs[-1].is_line:
                c = arcs[-1].circle
                x, y = ox + (c.cx + moved[0]) * k, oy + (c.cy + moved[1]) * k
                layer.stroke_style = SELECTION_COLOR
                layer.line_width = 2.0
                layer.set_line_dash([10, 6])
                layer.stroke_circle(x, y, c.r * k)
                layer.set_line_dash([])
                layer.fill_style = SELECTION_COLOR
                layer.fill_circle(x, y, CENTRE_RADIUS)
                layer.stroke_style = "#ffffff"
                layer.stroke_circle(x, y, CENTRE_RADIUS)
        if s.subject is not None:
            x, y, w, h = s.subject
            layer.stroke_style = SUBJECT_COLOR
            layer.line_width = 3.0
            layer.set_line_dash([12, 6])
            layer.stroke_rect(ox + x * k, oy + y * k, w * k, h * k)
            layer.set_line_dash([])

    def _sync(self) -> None:
        """The title, status line, level slider, progress and downloads from the studio's state."""
        c, s = self.controls, self.studio
        self._syncing = True
        try:
            symbols = "level: t; arcs: |A|; error: the similarity error E^s (Eqn. 3); tolerance: T"
            c["title"].value = f'<b title="{symbols}">{html.escape(s.title)}</b>'

            css = "studio-status" if s.ok else "studio-status studio-error"
            c["status"].value = f'<div class="{css}">{html.escape(s.message)}</div>'
            n = max(len(s.levels), 1)
            if c["level"].max != n - 1:
                # A new slider: the browser's keeps the range it was first drawn with for its End key.
                c["level"] = self._level_slider(n - 1, s.level)
                c["level_box"].children = (c["level"],)
            elif c["level"].value != s.level:
                c["level"].value = s.level
            c["tolerance"].value = s.settings.tolerance
            used = ", ".join(map(str, s.rungs_used)) or "none yet"
            c["sizes"].tooltip = (
                "Fig. 15: only the golden circles of these rungs k, radii \u03c6^(k + \u03c3) (--radii); "
                f"the run's first level uses k = {used}"
            )
            for name in ("delete", "connect", "undo", "redo", "add"):
                c[name].disabled = s.shown is None
            self._schedule_downloads()
        finally:
            self._syncing = False

    def _schedule_downloads(self) -> None:
        """Make the download links once the page has been still for ``DOWNLOADS_DELAY`` s.

        In a kernel (Voila, Jupyter) a change made meanwhile (the next level of a scrub) cancels
        the files of this one: the drawing follows the slider without waiting for files nobody
        saves. Without an event loop they are made at once.
        """
        if self._pending_downloads is not None:
            self._pending_downloads.cancel()
            self._pending_downloads = None
        try:
            loop = asyncio.get_running_loop()
        except RuntimeError:
            self.controls["downloads"].value = self._downloads_html()
            return

        def make() -> None:
            self._pending_downloads = None
            self.controls["downloads"].value = self._downloads_html()

        self._pending_downloads = loop.call_later(DOWNLOADS_DELAY, make)

    def _downloads_pending(self) -> None:
        """The download links replaced by their names, greyed: what they hold is being made anew."""
        if self._pending_downloads is not None:  # the files of the state being left are not wanted
            self._pending_downloads.cancel()
            self._pending_downloads = None
        names = DOWNLOAD_LABELS.values()
        self.controls["downloads"].value = "".join(
            f'<span class="studio-download studio-pending" title="being made">{html.escape(n)}</span>' for n in names
        )

    def _downloads_html(self) -> str:
        s = self.studio
        if s.shown is None:
            return "<i>Run first: the downloads are the logo shown.</i>"
        formats = tuple(DOWNLOAD_LABELS)
        try:
            files = s.downloads(formats)
        except Img2LogoError as exc:  # said on the page; the drawing stays
            return f'<span class="studio-error">{html.escape(str(exc))}</span>'
        names = s.download_names(formats)
        links = []
        for fmt, label in DOWNLOAD_LABELS.items():
            data = base64.b64encode(files[fmt]).decode("ascii")
            links.append(
                f'<a class="studio-download" download="{html.escape(names[fmt])}" title="{html.escape(names[fmt])}" '
                f'href="data:{DOWNLOAD_TYPES[fmt]};base64,{data}">{html.escape(label)}</a>'
            )
        return "".join(links)

    # ------------------------------------------------------------------ events
    def _act(self, action: Any, *, logo: bool = True, mask: bool = False, overlay: bool = True) -> None:
        self._downloads_pending()
        action()
        self.redraw(logo=logo, mask=mask, overlay=overlay)

    def run(self) -> bool:
        """Run with the settings the controls hold (the Run button)."""
        c = self.controls
        if not self.studio.set_exponents(c["sizes"].value):
            self.redraw(logo=False, overlay=False)
            return False
        fill = c["fill_spec"].value.strip() or "none"
        changes = {
            "kind": c["kind"].value,
            "tolerance": float(c["tolerance"].value),
            "bias": None if c["bias_auto"].value else float(c["bias"].value),
            "rdp_tolerance": float(c["rdp_tolerance"].value),
            "symmetry": c["symmetry"].value,
            "lines": bool(c["lines"].value),
            "detail": int(c["detail"].value),
            "ladder": c["ladder"].value,
            "fill": fill,
        }
        return self._run(**changes)

    def _run(self, **changes: Any) -> bool:
        c = self.controls
        bar = c["progress"]
        bar.bar_style, bar.max, bar.value = "", float(changes.get("tolerance", self.studio.settings.tolerance)), 0.0
        c["run"].disabled = True
        c["status"].value = '<div class="studio-status">running&hellip;</div>'
        self._downloads_pending()

        def progress(t: int, n_arcs: int, similarity: float) -> None:
            bar.value = min(float(similarity), bar.max)

        try:
            ok = self.studio.run(progress, **changes)
        finally:
            c["run"].disabled = False
        bar.bar_style = "success" if ok else "danger"
        if ok and self.studio.result is not None:
            bar.value = min(float(self.studio.result.final.similarity), bar.max)
        self.redraw()
        return ok

    def _uploaded(self, change: dict[str, Any]) -> None:
        files = change["new"]
        if self._syncing or not files:
            return
        f = files[0]
        ok = self.studio.load_upload(f["name"], bytes(f["content"]))
        self._syncing = True
        try:
            # Emptied: the same file chosen again is a new upload (the widget's value would not change).
            self.controls["upload"].value = ()
            if ok:
                self.controls["example"].value = "(example)"
        finally:
            self._syncing = False
        self._loaded(ok)

    def _example_chosen(self, change: dict[str, Any]) -> None:
        if self._syncing or change["new"] == "(example)":
            return
        self._loaded(self.studio.load_example(change["new"]))

    def _loaded(self, ok: bool) -> None:
        """A new image is shown and Run at once with the settings on the page; a bad file keeps what was shown."""
        if not ok:
            self.redraw(logo=False, overlay=False)
            return
        self._view = None
        self.controls["zoom"].value = "fit"
        self.redraw(background=True)
        self.run()

    def _level_changed(self, change: dict[str, Any]) -> None:
        if not self._syncing:
            self._downloads_pending()
            self.studio.set_level(change["new"])
            self.redraw()

    def _tolerance_changed(self, change: dict[str, Any]) -> None:
        if self._syncing:
            return
        s = self.studio
        self._downloads_pending()
        if s.result is not None and float(change["new"]) > s.run_tolerance * (1.0 + 1e-9):
            self._run(tolerance=float(change["new"]))
        else:
            s.set_tolerance(change["new"])
            self.redraw()

    def _fill_mode_changed(self, change: dict[str, Any]) -> None:
        self.controls["fill_spec"].value = FILL_PRESETS[change["new"]]

    def _fill_spec_changed(self, change: dict[str, Any]) -> None:
        self._downloads_pending()
        self.studio.set_fill(change["new"].strip() or "none")
        self.redraw(overlay=False)

    def _key_down(self, key: str, shift: bool, ctrl: bool, meta: bool) -> None:
        """The drawing's keys (it has the focus once clicked): undo, redo, delete, nudge, select several."""
        s, command = self.studio, ctrl or meta
        # Shift alone marks the next click; Shift as part of a shortcut (Ctrl+Shift+Z, Shift+arrow) does not.
        self._add_next = key == "Shift"
        if key == "Shift":
            return
        if command and key.lower() == "z":
            self._act(s.redo if shift else s.undo)
        elif command and key.lower() == "y":
            self._act(s.redo)
        elif key in ("Delete", "Backspace"):
            self._act(s.delete_selected)
        elif key in ARROW_KEYS:
            dx, dy = ARROW_KEYS[key]
            step = MOVE_STEP * (10.0 if shift else 1.0)
            self._act(lambda: s.move_selected(dx * step, dy * step))
        elif key == "0":
            self.fit_view()
        elif key in ("+", "="):
            self.zoom_at(*self._pointer, ZOOM_STEP)
        elif key == "-":
            self.zoom_at(*self._pointer, 1.0 / ZOOM_STEP)
        elif key == "Escape":
            s.selected = []
            s.message, s.ok = "nothing selected", True
            self.redraw(logo=False)

    def _centre_hit(self, ix: float, iy: float) -> bool:
        """Whether (ix, iy), image px, is on the selected arc's centre handle."""
        a, s = self.studio.shown, self.studio
        if a is None or not s.selected or s.selected[-1] >= len(a.arcs) or a.arcs[s.selected[-1]].is_line:
            return False
        c = a.arcs[s.selected[-1]].circle
        return float(np.hypot(ix - c.cx, iy - c.cy)) * self.scale <= 2.0 * CENTRE_RADIUS

    def _mouse_down(self, x: float, y: float) -> None:
        tool = self.controls["tool"].value
        ix, iy = self.to_image(x, y)
        add, self._add_next = self._add_next, False
        if tool == "select":
            if not add and self._centre_hit(ix, iy):
                self._moving = (ix, iy)
                return
            self.studio.select_at(ix, iy, PICK_DISTANCE * PIXEL_RATIO / self.scale, add=add)
            self.redraw(logo=False)
            return
        if tool == "hand":
            self._drag = [(float(x), float(y))]  # canvas px: the view moves under the mouse
            return
        if tool == "colour":
            self._act(lambda: self.studio.colour_region_at(ix, iy, self.controls["colour"].value))
            return
        self._drag = [(ix, iy)]
        if tool in ("brush", "eraser"):
            self._paint_segment()

    def _wheel(self, dx: float, dy: float) -> None:
        """The wheel zooms about the mouse: a step of ``ZOOM_STEP`` a notch, in towards the screen."""
        if dy:
            self.zoom_at(*self._pointer, ZOOM_STEP ** (-np.sign(dy)))

    def _mouse_move(self, x: float, y: float) -> None:
        self._pointer = (float(x), float(y))
        if self._drag and self.controls["tool"].value == "hand":
            (x0, y0), self._drag = self._drag[-1], [(float(x), float(y))]
            self.pan_by(float(x) - x0, float(y) - y0)
            return
        if self._moving is not None:
            ix, iy = self.to_image(x, y)
            with _ipycanvas().hold_canvas():
                self._draw_overlay(moved=(ix - self._moving[0], iy - self._moving[1]))
            return
        if not self._drag:
            return
        tool = self.controls["tool"].value
        self._drag.append(self.to_image(x, y))
        if tool in ("brush", "eraser"):
            self._paint_segment()
        elif tool == "subject":
            (x0, y0), (x1, y1) = self._drag[0], self._drag[-1]
            layer, k, (ox, oy) = self.canvas[4], self.scale, self.offset
            with _ipycanvas().hold_canvas():
                layer.clear()
                layer.stroke_style = SUBJECT_COLOR
                layer.line_width = 3.0
                layer.stroke_rect(ox + min(x0, x1) * k, oy + min(y0, y1) * k, abs(x1 - x0) * k, abs(y1 - y0) * k)

    def _mouse_up(self, x: float, y: float) -> None:
        if self._moving is not None:
            (x0, y0), (x1, y1) = self._moving, self.to_image(x, y)
            self._moving = None
            if (x1, y1) == (x0, y0):
                self.redraw(logo=False)
            else:  # the arcs and junctions follow on release: one edit, one re-fit
                self._act(lambda: self.studio.move_selected(round(x1 - x0, 2), round(y1 - y0, 2)))
            return
        if not self._drag:
            return
        tool, drag = self.controls["tool"].value, self._drag
        self._drag = []
        if tool == "hand":
            return
        if tool == "subject":
            (x0, y0), (x1, y1) = drag[0], self.to_image(x, y)
            self.studio.set_subject(x0, y0, x1, y1)
            self.redraw(logo=False)
        else:
            self.redraw(logo=False, mask=True, overlay=False)
            n = len(self.studio.lock_preview())
            if self.studio.result is not None:  # said after the stroke, not at every move
                self.studio.message += f"; the next Run locks {n} segment{'s' if n != 1 else ''} (highlighted)"
                self._sync()

    def _paint_segment(self) -> None:
        """Paint the last piece of the stroke into the mask, and show it at once on the mask layer.

        The brush's size is on screen: its radius in image pixels follows the drawing's scale.
        """
        erase = self.controls["tool"].value == "eraser"
        radius = float(self.controls["brush"].value) * PIXEL_RATIO / self.scale
        points = self._drag[-2:]
        self.studio.paint(points, radius, erase=erase)
        layer, k, (ox, oy) = self.canvas[3], self.scale, self.offset
        with _ipycanvas().hold_canvas():
            layer.global_composite_operation = "destination-out" if erase else "source-over"
            layer.stroke_style = "rgba({}, {}, {}, {})".format(*MASK_RGBA[:3], MASK_RGBA[3] / 255.0)
            layer.line_width = 2.0 * radius * k
            layer.line_cap = "round"
            layer.begin_path()
            layer.move_to(ox + points[0][0] * k, oy + points[0][1] * k)
            layer.line_to(ox + points[-1][0] * k, oy + points[-1][1] * k)
            layer.stroke()
            layer.global_composite_operation = "source-over"
        self.controls["status"].value = f'<div class="studio-status">{html.escape(self.studio.message)}</div>'


def studio_page(image: str | None = "clipart-fish.png", *, run: bool = False, **settings: Any) -> StudioPage:
    """A :class:`StudioPage` on ``image`` (a file of ``data/``), run at once with ``run``."""
    studio = Studio(image, **settings)
    page = StudioPage(studio)
    if run:
        page.run()
    return page
