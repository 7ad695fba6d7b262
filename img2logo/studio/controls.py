"""The studio's controls: its widgets, in a designer's words with the paper's symbol in a tooltip, and their layout.

:func:`make_controls` makes the widgets (the drawing's canvas among them) from the
studio's settings; :func:`page_layout` sets them out in three columns that fit a
1366 x 768 laptop screen: the drawing with its tools, the settings of a Run, and the
level, the edits and the downloads. What they do is :class:`~.page.StudioPage`'s.
"""

from __future__ import annotations

import html
from typing import Any

from ..constants import LOGO_ARCS
from ..experiments.paths import example_images, kit_module
from .drawing import PIXEL_RATIO, ipycanvas_module
from .session import Studio
from .zoom_pan import ZoomPan

#: Width of the controls' labels (the designer's words), CSS px.
LABEL_WIDTH = "122px"
#: Width of each column of controls, CSS px.
CONTROLS_WIDTH = 400

#: The largest arc budget the page offers: past it a clip art's logo is never cut (0 on the page: no budget).
ARC_BUDGET_MAX = 999
#: The move buttons, by name: their arrow and direction (x right, y down).
MOVES = {"left": ("\u2190", -1, 0), "up": ("\u2191", 0, -1), "down": ("\u2193", 0, 1), "right": ("\u2192", 1, 0)}
#: The Fills menu: each choice sets the ``--fill`` option beside it (which a designer may edit).
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


def make_controls(studio: Studio, size: int) -> dict[str, Any]:
    """The page's widgets by name (``canvas``, its ``zoom_pan``, ``run``, ``level``, ``tool``, ...), not wired.

    ``size`` is the side of the square drawing on screen, CSS px (its canvas has ``PIXEL_RATIO`` times the pixels).
    """
    w = kit_module("ipywidgets")
    s, c = studio.settings, {}
    style = {"description_width": LABEL_WIDTH}
    wide = w.Layout(width=f"{CONTROLS_WIDTH - 10}px")

    def labelled(kind: Any, description: str, layout: Any = wide, **kwargs: Any) -> Any:
        kwargs.setdefault("style", style)
        return kind(description=description, layout=layout, **kwargs)

    def setting(description: str, value: float, bounds: tuple[float, float, float], tooltip: str, **kwargs: Any) -> Any:
        """The slider of a Run's setting, ``bounds`` (min, max, step): its value is taken when it is let go."""
        low, high, step = bounds
        return labelled(
            w.FloatSlider,
            description,
            value=value,
            min=low,
            max=high,
            step=step,
            continuous_update=False,
            tooltip=tooltip,
            **kwargs,
        )

    side = size * PIXEL_RATIO
    ipycanvas = ipycanvas_module()
    c["canvas"] = ipycanvas.MultiCanvas(
        5, width=side, height=side, layout=w.Layout(width=f"{size}px", height=f"{size}px", flex="0 0 auto")
    )
    c["view_marker"] = ipycanvas.Canvas(width=1, height=1)
    c["zoom_pan"] = ZoomPan(canvas=c["canvas"], marker=c["view_marker"], layout=w.Layout(display="none"))

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
            "drag to move the zoomed drawing (or hold Space and drag, with any tool; the wheel zooms)",
            "paint where merges are forbidden (the lock mask, Fig. 16)",
            "erase the lock mask",
            "drag a rectangle around the subject of a photo (GrabCut's seed)",
            "click a filled region to give it the colour beside (fills on)",
        ],
        style={"button_width": "68px"},
    )
    # The browser knows the tool at once (a Hand drag pans there: zoom_pan.js), not after a round trip.
    c["zoom_pan"].pan_tool = [value for _label, value in c["tool"].options].index("hand")
    w.jslink((c["tool"], "index"), (c["zoom_pan"], "tool_index"))
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
        value=studio.name if studio.name in images else "(example)",
        layout=w.Layout(width=f"{CONTROLS_WIDTH - 170}px"),
    )
    c["kind"] = labelled(
        w.Dropdown,
        "Image type",
        options=[("automatic", "auto"), ("photo", "photo"), ("clip art", "clipart"), ("drawing", "drawing")],
        value=s.kind,
        tooltip="kind (--kind): how the feature lines are found (Sec. 4)",
    )
    c["tolerance"] = setting(
        "Tolerance (px)",
        s.tolerance,
        (0.5, 30.0, 0.5),
        "T: merging stops before a level whose error E^s exceeds it (Sec. 5.2); larger, fewer arcs",
    )
    c["bias"] = setting(
        "Circle size offset",
        0.0 if s.bias is None else s.bias,
        (0.0, 0.99, 0.01),
        "\u03c3: the radii are \u03c6^(k + \u03c3) (Eqn. 10); automatic: the best fit (Eqn. 14)",
        layout=w.Layout(width=f"{CONTROLS_WIDTH - 100}px"),
        disabled=s.bias is None,
    )
    c["bias_auto"] = w.Checkbox(value=s.bias is None, description="auto", indent=False, layout=w.Layout(width="80px"))
    c["rdp_tolerance"] = setting(
        "Simplify lines (px)",
        s.rdp_tolerance,
        (0.5, 8.0, 0.25),
        "the Ramer-Douglas-Peucker tolerance of the feature lines (Sec. 4); larger, less detail",
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

    c["level"] = level_slider(0)
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
    for name, (label, _dx, _dy) in MOVES.items():
        c[f"move_{name}"] = w.Button(
            description=label, tooltip=f"move the circle {name} (arrow key)", layout=w.Layout(width="44px")
        )
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
    c["add_arc"] = w.Button(
        description="Add arc",
        tooltip="Fig. 17 add: the dashed arc between the two free ends clicked (the rings), as an edit",
        layout=w.Layout(width="90px"),
    )
    c["other_circle"] = w.Button(
        description="Other circle",
        tooltip="another golden circle through the two free ends: a circle of the logo, or rung k, either side",
        layout=w.Layout(width="110px"),
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
    c["arcs"] = labelled(
        w.BoundedIntText,
        "Arc budget",
        layout=w.Layout(width="230px"),
        value=0 if s.arcs is None else s.arcs,
        min=0,
        max=ARC_BUDGET_MAX,
        tooltip="about this many arcs at most (--arcs): merging goes on past T (up to phi T); a clip art also "
        "merges the regions that cost most arcs for the least colour first, the silhouette and eyes kept; "
        f"0: the default, about {LOGO_ARCS} arcs by the fit alone",
    )
    c["sizes"] = labelled(
        w.Text,
        "Only circle sizes",
        value="" if s.exponents is None else ", ".join(map(str, s.exponents)),
        placeholder="all (or k, e.g. 5, 7, 8)",
        tooltip="Fig. 15: only the golden circles of these rungs k, radii \u03c6^(k + \u03c3) (--radii)",
    )
    c["downloads"] = w.HTML(layout=wide)
    return c


def page_layout(c: dict[str, Any], size: int) -> Any:
    """The page: a head, the status line and three columns of the widgets ``c`` (:func:`make_controls`)."""
    w = kit_module("ipywidgets")

    def section(text: str) -> Any:
        return w.HTML(f'<div class="studio-section">{html.escape(text)}</div>')

    hint = w.HTML(
        '<div class="studio-hint"><b>Select</b>: click an arc (a second one to connect them; Shift-click: '
        "several); drag its circle's centre to move it; click two free ends (rings), then Add arc; keys: "
        "Ctrl+Z, Ctrl+Shift+Z, Delete, arrows. <b>Hand</b> (or Space held): drag the zoomed drawing (the "
        "wheel zooms). <b>Brush</b> / <b>Eraser</b>: paint where "
        "merges are forbidden, then Run. <b>Subject</b>: a photo's subject. <b>Colour</b>: click a filled "
        "region.</div>",
        layout=w.Layout(width=f"{size}px"),
    )
    tools = w.VBox(
        [
            w.HBox([c["tool"], c["colour"]]),
            w.HBox([c["brush"], c["clear_mask"], c["clear_subject"]]),
            w.HBox([c["circles"], w.Label("Input", layout=w.Layout(width="40px")), c["input"], c["fit"], c["zoom"]]),
            hint,
        ],
        layout=w.Layout(width=f"{size}px"),
    )
    left = w.VBox([c["canvas"], c["zoom_pan"], tools], layout=w.Layout(flex="0 0 auto"))
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
            w.HBox([c["arcs"], w.Label(f"0: about {LOGO_ARCS}")]),
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
            w.HBox([c["add"], c["add_arc"], c["other_circle"]]),
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


def level_slider(last: int, value: int = 0) -> Any:
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
    return slider


__all__ = [
    "CONTROLS_WIDTH",
    "CSS",
    "FILL_PRESETS",
    "LABEL_WIDTH",
    "MOVES",
    "level_slider",
    "make_controls",
    "page_layout",
]
