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
#: A level's PNG's zlib strategy (Pillow's ``compress_type``): 3 is ``Z_RLE``, matches at distance 1 only. On the
#: 40 logos over faded inputs of ``make bench``'s batch: 2.6x less CPU than zlib's default strategy, files 2 %
#: larger (at most 14 %); the same pixels, any inflater reads it (docs/design/speed.md).
PNG_ZLIB_STRATEGY: int = 3
#: The SVG's "Golden circles" layer is clipped to the image plus this fraction of its longer side on every side.
CONSTRUCTION_MARGIN: float = 0.5
