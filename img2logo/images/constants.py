"""The defaults and thresholds that only the ``images`` stage uses.

One line of reason each; units, and where the measurements are, as in :mod:`img2logo.constants`.
"""

from __future__ import annotations

# --- Input images (preprocessing) ---------------------------------------------
#: Smallest accepted side of an input image, px.
MIN_IMAGE_SIDE: int = 16
#: Largest accepted floating-point image (Radiance HDR, PFM), pixels: OpenCV decodes it whole into float32 RGB, 12
#: bytes a pixel, and the range check adds 3 more.
MAX_FLOAT_IMAGE_PIXELS: int = 64_000_000
#: Largest strip (or tile) of a TIFF, bytes of decoded samples (its width x rows x a pixel's bits / 8).
MAX_WHOLE_TIFF_BYTES: int = 350_000_000
#: Rows composited over white at a time when a large image with alpha is downscaled: bounds the float32 temporaries
#: to about 4 MB per 1000 px of width.
DOWNSCALE_STRIP_ROWS: int = 256
