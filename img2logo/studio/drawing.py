"""The studio's drawing: the logo shown on an :class:`ipycanvas.MultiCanvas`, its zoom and pan.

:class:`StudioDrawing` draws the layers of the drawing (the faded input, the golden
circles, the logo with its fills, the lock mask with the segments it covers, the
selection with its circle and centre, and the subject) as vector commands of the
browser's canvas: a level or an edit redraws without rendering a PNG. The input and the
mask are sent once each (to undisplayed canvases at their own size) and drawn scaled, so
a zoom or pan sends no pixels. The canvas has twice the pixels of its size on screen
(crisp on high-density screens); ipycanvas gives the mouse in canvas pixels.
"""

from __future__ import annotations

import importlib
import zlib
from typing import TYPE_CHECKING, Any

import numpy as np

from ..constants import IMAGE_FADE
from ..design.fill_values import Gradient
from ..errors import Img2LogoError
from ..export.plotting import ARC_COLOR, default_stroke_width, evenodd_orient
from .session import Studio

if TYPE_CHECKING:
    from ..geometry.abstraction import Abstraction
    from ..images.loading import LoadedImage

#: Side of the square drawing on screen, CSS px: with two columns of controls of
#: ``CONTROLS_WIDTH`` beside it the page fits a 1366 x 768 laptop screen.
DRAWING_SIZE = 480
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
#: The largest zoom (times the fitted drawing) and the step of a wheel notch or a + / - key.
MAX_ZOOM = 16.0
ZOOM_STEP = 1.25
#: How much of the square a pan keeps the zoomed image in, at least (each way).
PAN_KEEP = 0.25
#: How much the input under the logo is faded towards white: as the PNG writer's, more, or hidden.
INPUT_FADES = {"faded": IMAGE_FADE, "dim": 0.88, "hidden": 1.0}
#: The golden circles on screen (the SVG's construction layer), and the selected arc's circle and centre.
CIRCLE_RGBA = "rgba(192, 151, 58, 0.55)"
CENTRE_RADIUS = 7.0
#: The free ends (rings, canvas px) and the arc that would join the two chosen (Fig. 17 "add").
END_RADIUS = 5.0
END_ARC_COLOR = "#d1461f"
#: Canvas gradients kept (one per gradient of the fills shown; more means another fill option).
MAX_GRADIENTS = 16


def one_outline(rings: list[np.ndarray]) -> np.ndarray:
    """The loops ``rings`` (each (N, 2), px) as one closed polygon, (M, 2): the fill of all of them.

    Each loop is closed at its first point; the polygon goes from loop to loop by their
    first points and comes back the same way, so the links add nothing to the winding
    number at any point (a canvas fills one polygon per call).
    """
    closed = [np.vstack([r, r[:1]]) for r in rings]
    back = [r[:1] for r in rings[-2::-1]]
    return np.vstack([*closed, *back])


def studio_module(name: str) -> Any:
    """``name``, a package of the extra ``[studio]`` (ipycanvas, anywidget), or one line saying how to install it."""
    try:
        return importlib.import_module(name)
    except ImportError:
        raise Img2LogoError(
            f"{name} is missing: the studio needs the extra [studio] (pip install -e '.[studio]'; make studio "
            "installs it)"
        ) from None


def ipycanvas_module() -> Any:
    """ipycanvas, or one line saying how to install it (the extra ``[studio]``)."""
    return studio_module("ipycanvas")


class StudioDrawing:
    """The drawing of ``studio``'s logo shown on ``canvas``, ``side`` canvas px square, zoomed and panned.

    Attributes
    ----------
    studio : Studio
        What is drawn.
    canvas : ipycanvas.MultiCanvas
        Five layers: the faded image, the golden circles, the logo, the lock mask, the selection
        (its circle and centre) and the subject.
    controls : dict
        The page's widgets by name: the drawing reads ``input`` and ``circles``, sets ``zoom``, and
        announces its views to ``zoom_pan`` (:mod:`.zoom_pan`), drawing ``view_marker`` last.
    """

    studio: Studio
    canvas: Any
    controls: dict[str, Any]
    side: int
    _view: tuple[float, float, float] | None
    #: The image whose loaded copy the undisplayed canvas holds, and that canvas (:meth:`_input_canvas`).
    _input_source: tuple[Any, Any] | None
    _gradients: dict[Gradient, Any]
    _fill_outlines: tuple[Any, list[tuple[Any, np.ndarray]]] | None
    #: The mask's key (shape, checksum) and its undisplayed canvas; the segments it locks, by mask and run.
    _mask_source: tuple[tuple[Any, ...], Any] | None
    _locked: tuple[tuple[Any, ...], list[np.ndarray]] | None

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
        """Zoom by ``factor`` about canvas point (x, y) (the image point under it stays), within 1..``MAX_ZOOM``.

        Changes the view only: :meth:`show_view` draws it.
        """
        fit, _, _ = self._fit()
        k = min(max(self.scale * float(factor), fit), fit * MAX_ZOOM)
        ix, iy = self.to_image(x, y)
        self._view = None if k <= fit * (1.0 + 1e-9) else (k, float(x) - ix * k, float(y) - iy * k)

    def pan_by(self, dx: float, dy: float) -> None:
        """Move the zoomed drawing by (dx, dy), canvas px (the image keeps ``PAN_KEEP`` of the square in view).

        Changes the view only: :meth:`show_view` draws it.
        """
        img = self.studio.image
        if self._view is None or img is None:
            return
        k, x, y = self._view
        w, h = img.input_width * k, img.input_height * k
        keep = self.side * PAN_KEEP
        x = min(max(x + float(dx), keep - w), self.side - keep)
        y = min(max(y + float(dy), keep - h), self.side - keep)
        self._view = (k, x, y)

    def fit_view(self) -> None:
        """The whole image in the square again, drawn."""
        self._view = None
        self.show_view()

    def view_geometry(self) -> dict[str, Any]:
        """What the browser needs to foresee a zoom or pan (:class:`~.zoom_pan.ZoomPan`'s ``geometry``)."""
        img = self.studio.image
        size = (0, 0) if img is None else (img.input_width, img.input_height)
        return {
            "view": None if self._view is None else list(self._view),
            "fit": list(self._fit()),
            "size": list(size),
            "side": self.side,
            "max_zoom": MAX_ZOOM,
            "keep": self.side * PAN_KEEP,
            "step": ZOOM_STEP,
            "frame": FRAME_COLOR,
        }

    def show_view(self, *, answer: bool = False) -> None:
        """Every layer again at the view's zoom and pan (the files do not change), announced to the browser.

        The view is announced before its drawing (``answer``: to the browser's message that
        asked for it), and the drawing ends on the marker canvas: the browser then knows which
        view the canvas holds (:mod:`.zoom_pan`).
        """
        geometry = self.view_geometry()
        front = self.controls["zoom_pan"]
        front.send({"view": geometry["view"], "geometry": geometry, "answer": answer})
        with ipycanvas_module().hold_canvas():
            for draw in (self._draw_background, self._draw_circles, self._draw_logo, self._draw_mask):
                draw()
            self._draw_overlay()
            self.controls["view_marker"].clear()
        front.geometry = geometry  # a page opened later starts from it
        self.controls["zoom"].value = f"{self.zoom:.0%}" if self._view is not None else "fit"

    def operate(self, ops: list[tuple[str, tuple[float, ...]]]) -> None:
        """Zoom and pan by the browser's operations (:func:`~.zoom_pan.operations`), in order, then draw once."""
        try:
            for name, args in ops:
                if name == "zoom":
                    self.zoom_at(*args)
                else:
                    self.pan_by(*args)
        finally:  # always answered: the browser waits for it to send what came meanwhile
            self.show_view(answer=True)

    def to_image(self, x: float, y: float) -> tuple[float, float]:
        """Canvas pixels to image pixels."""
        ox, oy = self.offset
        return (float(x) - ox) / self.scale, (float(y) - oy) / self.scale

    def _redraw_layer(self, draw: Any) -> None:
        """One layer again (``draw``, one of the ``_draw_*`` methods), in one message to the browser."""
        with ipycanvas_module().hold_canvas():
            draw()

    def _draw_background(self) -> None:
        """The input under the logo, faded towards white (:data:`INPUT_FADES`), in its frame.

        The loaded copy (at most ``MAX_IMAGE_SIDE`` px) is sent once to an undisplayed canvas
        (:meth:`_input_canvas`); a zoom or pan draws it scaled there, sending no pixels.
        """
        layer = self.canvas[0]
        layer.clear()
        img = self.studio.image
        if img is None:
            return
        layer.fill_style = FRAME_COLOR
        layer.fill_rect(0, 0, self.side, self.side)
        k, (x, y) = self.scale, self.offset
        w, h = img.input_width * k, img.input_height * k
        layer.fill_style = "#ffffff"
        layer.fill_rect(x, y, w, h)
        fade = INPUT_FADES[self.controls["input"].value]
        if fade >= 1.0:
            return
        # Over white at opacity 1 - fade: fade + (1 - fade) * rgb, the PNG writer's faded input.
        layer.global_alpha = 1.0 - fade
        # Enlarged, the loaded pixels stay square; shrunk, the browser averages them.
        layer.image_smoothing_enabled = bool(w < img.width)
        layer.draw_image(self._input_canvas(img), x, y, w, h)
        layer.global_alpha = 1.0

    def _input_canvas(self, img: LoadedImage) -> Any:
        """The undisplayed canvas holding the loaded input ``img`` at its own size (made anew for a new image)."""
        if self._input_source is not None and self._input_source[0] is img:
            return self._input_source[1]
        if self._input_source is not None:
            self._input_source[1].close()
        source = ipycanvas_module().Canvas(width=img.width, height=img.height)
        pixels = np.clip(img.rgb * 255.0 + 0.5, 0, 255).astype(np.uint8)

        def send() -> None:
            with ipycanvas_module().hold_canvas():
                source.put_image_data(pixels, 0, 0)
                if self._input_source is not None and self._input_source[1] is source:
                    self._draw_background()

        source.put_image_data(pixels, 0, 0)
        # A page opened (or reloaded) later gets an empty canvas: the pixels again, then the drawing.
        source.on_client_ready(send)
        self._input_source = (img, source)
        return source

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
        """The fills as the SVG paints them, as vectors the browser fills: each region in its colour or gradient.

        A region's loops are one polygon (:func:`one_outline`) oriented so that the canvas's
        non-zero rule fills it as SVG's ``evenodd`` does; the coordinates and gradients are
        image px (a canvas transform maps them), so a gradient widget serves every view.
        """
        a = self.studio.shown
        if a is None:
            return
        k, (ox, oy) = self.scale, self.offset
        layer.save()
        layer.set_transform(k, 0.0, 0.0, k, ox, oy)
        layer.begin_path()
        layer.rect(0, 0, a.width, a.height)  # the image's frame, as the files' view box
        layer.clip()
        for fill, outline in self._outlines(fills):
            layer.fill_style = fill.color if fill.gradient is None else self._canvas_gradient(fill.gradient)
            layer.fill_polygon(outline)
        layer.restore()

    def _outlines(self, fills: Any) -> list[tuple[Any, np.ndarray]]:
        """Each fill with its outline (:func:`one_outline`, image px), kept for the fills last drawn (a pan)."""
        if self._fill_outlines is None or self._fill_outlines[0] is not fills:
            made = [(f, evenodd_orient(f.rings())) for f in fills]
            self._fill_outlines = (fills, [(f, one_outline(rings)) for f, rings in made if rings])
        return self._fill_outlines[1]

    def _canvas_gradient(self, gradient: Gradient) -> Any:
        """The canvas gradient of ``gradient`` (image px), made once per gradient."""
        if gradient not in self._gradients:
            if len(self._gradients) >= MAX_GRADIENTS:  # another fill option: the old ones are not drawn again
                for old in self._gradients.values():
                    old.close()
                self._gradients.clear()
            layer = self.canvas[2]
            (x0, y0), (x1, y1) = gradient.start, gradient.end
            stops = [(float(o), c) for o, c in gradient.stops]
            if gradient.kind == "linear":
                made = layer.create_linear_gradient(x0, y0, x1, y1, stops)
            else:
                r = float(np.hypot(x1 - x0, y1 - y0))
                made = layer.create_radial_gradient(x0, y0, 0.0, x0, y0, r, stops)
            self._gradients[gradient] = made
        return self._gradients[gradient]

    def _draw_mask(self) -> None:
        """The lock mask, translucent, and the segments of the last run it locks, highlighted.

        The mask goes to an undisplayed canvas at its own size once it changed (a stroke ended,
        it was cleared, a new image); a zoom or pan draws that canvas scaled, its pixels square.
        """
        layer = self.canvas[3]
        layer.clear()
        m = self.studio.mask
        if not m.size or not m.any():
            return
        key = (m.shape, zlib.crc32(np.packbits(m).tobytes()), id(self.studio.result))
        k, (ox, oy) = self.scale, self.offset
        layer.image_smoothing_enabled = False
        layer.draw_image(self._mask_canvas(m, key[:2]), ox, oy, m.shape[1] * k, m.shape[0] * k)
        if self._locked is None or self._locked[0] != key:
            self._locked = (key, self.studio.lock_preview())
        layer.stroke_style = LOCKED_COLOR
        layer.line_width = 4.0
        layer.line_cap = "round"
        for seg in self._locked[1]:
            layer.stroke_lines(np.column_stack([ox + seg[:, 0] * k, oy + seg[:, 1] * k]))

    def _mask_canvas(self, m: np.ndarray, key: tuple[Any, ...]) -> Any:
        """The undisplayed canvas holding mask ``m`` (H, W) as RGBA pixels, sent again when ``key`` changed."""
        if self._mask_source is not None and self._mask_source[0] == key:
            return self._mask_source[1]
        rgba = np.zeros((*m.shape, 4), dtype=np.uint8)
        rgba[m] = MASK_RGBA
        if self._mask_source is not None and self._mask_source[0][0] == m.shape:
            source = self._mask_source[1]
            source.clear()  # its pixels are drawn over what it holds
        else:
            if self._mask_source is not None:
                self._mask_source[1].close()
            source = ipycanvas_module().Canvas(width=m.shape[1], height=m.shape[0])
        source.put_image_data(rgba, 0, 0)
        self._mask_source = (key, source)
        return source

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
        if a is not None:
            self._draw_ends(layer, a)
        if s.subject is not None:
            x, y, w, h = s.subject
            layer.stroke_style = SUBJECT_COLOR
            layer.line_width = 3.0
            layer.set_line_dash([12, 6])
            layer.stroke_rect(ox + x * k, oy + y * k, w * k, h * k)
            layer.set_line_dash([])

    def _draw_ends(self, layer: Any, a: Abstraction) -> None:
        """The free ends of the logo shown ``a`` as rings, the two chosen filled, and the arc that would join them."""
        s = self.studio
        k, (ox, oy) = self.scale, self.offset
        chosen = s.ends
        arc = s.end_arc()
        if arc is not None:
            self._stroke_arcs(layer, [arc], END_ARC_COLOR, 3.0)
            layer.stroke_style = END_ARC_COLOR
            layer.line_width = 1.5
            layer.set_line_dash([10, 6])
            layer.stroke_circle(ox + arc.circle.cx * k, oy + arc.circle.cy * k, arc.circle.r * k)
            layer.set_line_dash([])
        layer.line_width = 2.0
        for j in s.free_end_junctions():
            x, y = ox + a.junctions[j][0] * k, oy + a.junctions[j][1] * k
            layer.fill_style = SELECTION_COLOR if j in chosen else "#ffffff"
            layer.fill_circle(x, y, END_RADIUS)
            layer.stroke_style = SELECTION_COLOR
            layer.stroke_circle(x, y, END_RADIUS)
