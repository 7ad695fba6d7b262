"""The studio's page: ipywidgets and ipycanvas around a :class:`~.studio.Studio` (``make studio``, Voila).

:class:`StudioPage` draws the logo shown on an :class:`ipycanvas.MultiCanvas`
(vector arcs and fills, drawn by the browser's canvas: a level or an edit redraws
without rendering a PNG) over the faded input, and takes the mouse on it: a click
selects an arc or a free end (two free ends chosen, Add arc joins them on the circle
Other circle picks: Fig. 17 "add"), a drag paints or erases the lock mask or draws
the subject rectangle, by the tool chosen. Every control calls one method of the :class:`~.studio.Studio`
and then redraws what changed; its one-line message is the page's status line.
The golden circles of the level shown can be drawn under it (the SVG's
construction layer), the selected arc's circle and centre always are; dragging
that centre moves the circle (:func:`img2logo.design.edits.move_circle`, on
release). The wheel zooms about the mouse (the + and - keys too, 0 fits the
image again), the Hand tool (or any tool with Space held) drags the zoomed drawing:
the browser shows each such frame at once and this page draws it exactly
(:mod:`.zoom_pan`).
With the drawing focused (click it) the keys edit: Ctrl+Z and
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

The drawing is :class:`~.drawing.StudioDrawing`, the widgets and their layout
:mod:`.controls`, the download links :mod:`.downloads`; this module wires them to the
:class:`~.session.Studio`.
"""

from __future__ import annotations

import asyncio
import html
from typing import Any

import numpy as np

from .controls import FILL_PRESETS, MOVES, level_slider, make_controls, page_layout
from .downloads import downloads_html, pending_html
from .drawing import (
    CENTRE_RADIUS,
    DRAWING_SIZE,
    MASK_RGBA,
    PIXEL_RATIO,
    SUBJECT_COLOR,
    ZOOM_STEP,
    StudioDrawing,
    ipycanvas_module,
)
from .session import PICK_DISTANCE, Studio
from .zoom_pan import operations

#: Step of the move buttons and arrow keys, px of the image.
MOVE_STEP = 2.0
#: Seconds the page must be still before the download links are made (a scrub makes none on the way).
DOWNLOADS_DELAY = 0.25
ARROW_KEYS = {"ArrowLeft": (-1, 0), "ArrowUp": (0, -1), "ArrowDown": (0, 1), "ArrowRight": (1, 0)}


class StudioPage(StudioDrawing):
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
        self._drag: list[tuple[float, float]] = []
        self._moving: tuple[float, float] | None = None  # the centre being dragged, image px
        self._pending_downloads: asyncio.TimerHandle | None = None
        self._view = None  # (scale, x, y) when zoomed; None: fitted
        self._input_source = None
        self._gradients = {}
        self._fill_outlines = None
        self._mask_source = None
        self._locked = None
        self._pointer = (self.size * PIXEL_RATIO / 2.0,) * 2  # the mouse's last canvas position: the wheel's centre
        self._add_next = False
        self._syncing = False
        self.controls = make_controls(studio, self.size)
        self.canvas = self.controls["canvas"]
        self._wire()
        self.box = page_layout(self.controls, self.size)
        self.redraw(background=True)

    def _wire(self) -> None:
        """Each control calls its method of the studio, then redraws what changed."""
        c = self.controls
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
        # The wheel and the pan are the browser's (zoom_pan.js): it sends their operations, the view draws them.
        c["zoom_pan"].on_msg(lambda _widget, content, _buffers: self.operate(operations(content)))
        c["level"].observe(self._level_changed, names="value")
        for name, (_label, dx, dy) in MOVES.items():
            c[f"move_{name}"].on_click(
                lambda _b, dx=dx, dy=dy: self._act(lambda: self.studio.move_selected(dx * MOVE_STEP, dy * MOVE_STEP))
            )
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
        c["add_arc"].on_click(lambda _b: self._act(self.studio.add_arc_at_ends))
        c["other_circle"].on_click(lambda _b: self._act(self.studio.other_end_circle, logo=False))

    # ------------------------------------------------------------------ drawing
    def redraw(self, *, background: bool = False, logo: bool = True, mask: bool = False, overlay: bool = True) -> None:
        """Draw the layers asked for and refresh the title, status, level slider and downloads.

        The downloads are made last: until then their links are names without a link
        (:meth:`_downloads_pending`), so that the drawing appears first and no click saves an old file.
        """
        self._downloads_pending()
        if background:  # every layer: the view's own drawing
            self.show_view()
            self._sync()
            return
        with ipycanvas_module().hold_canvas():
            if logo:
                self._draw_circles()
                self._draw_logo()
            if mask:
                self._draw_mask()
            if overlay:
                self._draw_overlay()
        self._sync()

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
                c["level"] = level_slider(n - 1, s.level)
                c["level"].observe(self._level_changed, names="value")
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
            for name in ("add_arc", "other_circle"):
                c[name].disabled = len(s.ends) != 2
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
            self.controls["downloads"].value = downloads_html(self.studio)
            return

        def make() -> None:
            self._pending_downloads = None
            self.controls["downloads"].value = downloads_html(self.studio)

        self._pending_downloads = loop.call_later(DOWNLOADS_DELAY, make)

    def _downloads_pending(self) -> None:
        """The download links replaced by their names, greyed: what they hold is being made anew."""
        if self._pending_downloads is not None:  # the files of the state being left are not wanted
            self._pending_downloads.cancel()
            self._pending_downloads = None
        self.controls["downloads"].value = pending_html()

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
            "arcs": int(c["arcs"].value) or None,
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
        if key == " ":  # held, a drag pans whatever the tool: the browser's (zoom_pan.js)
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
        elif key in ("+", "=", "-"):
            self.zoom_at(*self._pointer, ZOOM_STEP if key != "-" else 1.0 / ZOOM_STEP)
            self.show_view()
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
        if tool == "hand":  # a pan: the browser's (zoom_pan.js)
            return
        ix, iy = self.to_image(x, y)
        add, self._add_next = self._add_next, False
        if tool == "select":
            if not add and self._centre_hit(ix, iy):
                self._moving = (ix, iy)
                return
            reach = PICK_DISTANCE * PIXEL_RATIO / self.scale
            if not add and self.studio.select_end_at(ix, iy, reach) is not None:
                self.redraw(logo=False)
                return
            self.studio.select_at(ix, iy, reach, add=add)
            self.redraw(logo=False)
            return
        if tool == "colour":
            self._act(lambda: self.studio.colour_region_at(ix, iy, self.controls["colour"].value))
            return
        self._drag = [(ix, iy)]
        if tool in ("brush", "eraser"):
            self._paint_segment()

    def _mouse_move(self, x: float, y: float) -> None:
        self._pointer = (float(x), float(y))
        if self._moving is not None:
            ix, iy = self.to_image(x, y)
            with ipycanvas_module().hold_canvas():
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
            with ipycanvas_module().hold_canvas():
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
        with ipycanvas_module().hold_canvas():
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
