"""The drawing's zoom and pan in the browser: an anywidget whose front end, ``zoom_pan.js``, takes wheel and pan.

A wheel notch or a pan's move shows at once, with no round trip to the kernel: the
browser moves and scales the drawing its canvas already holds to the new view, and sends
the operation here, where :class:`~.drawing.StudioDrawing` (the view's truth: its scale
and offset map every click, drag and download to image pixels) applies it with its own
``zoom_at`` / ``pan_by`` and redraws the layers exactly; that drawing then replaces the
moved one. Operations made while one message is unanswered go together in the next, applied
in order (quick notches end at the view of slow ones). Each view drawn is announced to
the front end before its drawing, which ends on an undisplayed marker canvas, so the front
end knows which view the canvas holds (see ``zoom_pan.js``).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from .drawing import studio_module

AnyWidget: Any = studio_module("anywidget").AnyWidget
ipycanvas = studio_module("ipycanvas")
traitlets = studio_module("traitlets")
widgets = studio_module("ipywidgets")

#: The operations the front end sends, by name: their number of arguments (canvas px; a zoom's factor).
OPERATIONS = {"zoom": 3, "pan": 2}


class ZoomPan(AnyWidget):
    """The front end of the drawing's zoom and pan (shown as nothing; it acts on ``canvas``).

    Attributes
    ----------
    canvas : ipycanvas.MultiCanvas
        The drawing whose canvas the wheel and the pan act on.
    marker : ipycanvas.Canvas
        Undisplayed, 1 x 1: drawn last in each view's drawing, so the front end knows it arrived.
    geometry : dict
        What the front end needs to foresee a view: ``view`` ([scale, x, y] or None when fitted),
        ``fit`` (the fitted view), ``size`` (the image, px), ``side`` (the canvas, px),
        ``max_zoom``, ``keep`` (canvas px of the image kept in view by a pan), ``step`` (a wheel
        notch's factor) and ``frame`` (the colour around the image).
    tool_index, pan_tool : int
        The tool chosen (linked in the browser to the tool buttons' index, :func:`ipywidgets.jslink`)
        and the one whose drag pans (the Hand); Space held pans with any tool.
    """

    _esm = Path(__file__).with_name("zoom_pan.js")
    canvas = traitlets.Instance(ipycanvas.MultiCanvas).tag(sync=True, **widgets.widget_serialization)
    marker = traitlets.Instance(ipycanvas.Canvas).tag(sync=True, **widgets.widget_serialization)
    geometry = traitlets.Dict().tag(sync=True)
    tool_index = traitlets.Int(0).tag(sync=True)
    pan_tool = traitlets.Int(-1).tag(sync=True)


def operations(content: Any) -> list[tuple[str, tuple[float, ...]]]:
    """The valid operations of a front end's message ``{"ops": [[name, *numbers], ...]}``, in order.

    An operation that is not a known name (:data:`OPERATIONS`) with its count of finite
    numbers (a zoom's factor positive) is left out: the message comes from the browser.
    """
    ops = content.get("ops") if isinstance(content, dict) else None
    out: list[tuple[str, tuple[float, ...]]] = []
    for op in ops if isinstance(ops, list) else []:
        if not isinstance(op, list) or not op or op[0] not in OPERATIONS or len(op) != OPERATIONS[op[0]] + 1:
            continue
        if not all(isinstance(v, int | float) and not isinstance(v, bool) and math.isfinite(v) for v in op[1:]):
            continue
        if op[0] == "zoom" and op[3] <= 0:
            continue
        out.append((op[0], tuple(float(v) for v in op[1:])))
    return out


__all__ = ["OPERATIONS", "ZoomPan", "operations"]
