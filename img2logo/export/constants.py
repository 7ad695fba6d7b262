"""The defaults and thresholds that only the ``export`` stage uses.

One line of reason each; units, and where the measurements are, as in :mod:`img2logo.constants`.
"""

from __future__ import annotations

# --- Result files and figures (writers, plotting) -----------------------------
#: Default stroke width of drawn arcs, as a fraction of the longer image side ...
STROKE_WIDTH_FRACTION: float = 1.0 / 128.0
#: The default stroke width (STROKE_WIDTH_FRACTION of the longer side) is never thinner than this, px.
MIN_STROKE_WIDTH: float = 1.0
#: Resolution of PNG figures, dots per inch.
PNG_DPI: float = 100.0
#: The SVG's "Golden circles" layer is clipped to the image plus this fraction of its longer side on every side.
CONSTRUCTION_MARGIN: float = 0.5
