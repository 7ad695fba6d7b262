"""The values several stages share: the golden ratio, the input and output bounds, the defaults of
the options, the contract's tolerances.

A value used by one stage lives with it (``img2logo/<stage>/constants.py``, or the one module that
uses it). Units: lengths in pixels of the input image (px), angles in radians. How each value was
measured, and what was tried instead: ``docs/design/defaults.md``.
"""

from __future__ import annotations

import math

#: The golden ratio phi = (1 + sqrt 5) / 2 (paper Eqn. 2, 10).
PHI: float = (1.0 + math.sqrt(5.0)) / 2.0
#: log(phi), used to move between radii and ladder exponents (Eqn. 12, 14).
LOG_PHI: float = math.log(PHI)
#: Weights of R, G, B in the gray value (ITU-R BT.601 luma), unit-free: the gray of the photo's line drawing, of a
#: mask image and of the subject's focus measure.
LUMA_WEIGHTS: tuple[float, float, float] = (0.299, 0.587, 0.114)
#: Name of the result-file format (``contract/README.md``).
FORMAT_NAME: str = "img2logo.abstraction/1"

# --- Input images (preprocessing) ---------------------------------------------
#: Images whose longer side exceeds this are downscaled (with a warning), px.
MAX_IMAGE_SIDE: int = 2048
#: A clip art or a line drawing is worked at most this size on its longer side, px, for the photo's reason (the
#: result is scaled back to the input's pixels, as for MAX_IMAGE_SIDE).
SYNTHETIC_WORK_SIDE: int = 512
#: Largest accepted input, pixels (width x height), read from the file's header before decoding: 8-bit RGBA at this
#: size is 600 MB decoded.
MAX_IMAGE_PIXELS: int = 150_000_000
#: The largest length an option takes (``tolerance``, ``rdp_tolerance``, ``min_length``, ``max_arc_distance``, the
#: Fibonacci ``unit``) and the largest radius a ladder may offer, px.
MAX_LENGTH: float = 1e7
#: The smallest radius a ladder may offer (``exponents``, ``--radii``; the Fibonacci ``unit``), px: a thousandth of
#: a pixel, a circle no drawing can show; below it phi ** k only heads for underflow (``--radii=-1000000``).
MIN_LADDER_RADIUS: float = 1e-3
#: An image whose channel values span less than this (on a 0..1 scale) is "blank".
BLANK_IMAGE_RANGE: float = 1.0 / 255.0

# --- Feature lines ------------------------------------------------------------
#: Clip art: the default ``detail`` (:func:`img2logo.features.detail.merge_by_importance`): the regions kept
#: besides the background, the weightiest by Ward's criterion.
DETAIL: int = 24
#: Photo inner lines: an end of a line that stops within this distance of another line is joined to it (a
#: junction), px.
LINE_JOIN_DISTANCE: float = 6.0

# --- Segment graph ------------------------------------------------------------
#: Default Ramer-Douglas-Peucker tolerance of the over-segmentation, px (Sec. 4).
RDP_TOLERANCE: float = 2.0
#: Default: segments (whole chains between nodes) shorter than this are dropped when they hang free at one end, px.
MIN_SEGMENT_LENGTH: float = 6.0
#: Two junctions joined by a chain shorter than this are one junction, px (a thick "X" thins to two "Y"s and a
#: short bridge).
JUNCTION_MERGE_DISTANCE: float = 6.0
#: Tangent joins (beyond the paper): the feature line runs on smoothly through a node of valence 2 when the two
#: segments' end tangents turn by less than this, rad.
SMOOTH_JOIN_ANGLE: float = math.radians(10.0)
#: ``make quality``: a join on smooth input is tangent when the logo's two arcs kink there by less than this, rad
#: (the target: >= 90 % of the joins); two degrees is below what the eye sees at a stroke's join.
TANGENT_JOIN_ANGLE: float = math.radians(2.0)

# --- Result files and figures (writers, plotting) -----------------------------
#: Contract invariant: a circle's radius is phi ** (k + bias) within this fraction of r (``contract/README.md``).
RADIUS_RELATIVE_TOLERANCE: float = 1e-6
#: Contract invariant: a junction lies on the circle of each arc listed for it, and at an end point of that arc,
#: within this distance, px (``contract/README.md``).
JUNCTION_TOLERANCE: float = 1e-3
#: Largest side of a PNG written with ``scale`` (``--png-scale``), px: 16384 x 16384 RGBA is 1 GiB in memory while
#: it is drawn; larger is a slip of the keyboard, or a job for the PDF.
MAX_PNG_SIDE: int = 16384
#: Largest side of a PNG drawn over the faded input (``background="input"``), px: matplotlib resamples the image
#: under the logo in floating point, about 85 bytes per output pixel (measured: 3.1 GB peak for 6000 x 6000 px, 0.2
#: GB without the image), so 4096 x 4096 px is about 1.4 GB; a white or transparent background goes to
#: ``MAX_PNG_SIDE``.
MAX_PNG_IMAGE_SIDE: int = 4096
#: How far a background image is faded towards white under a drawing (0 = as it is, 1 = white).
IMAGE_FADE: float = 0.6
#: Spacing of the sample points when an arc is drawn as a polyline in a raster, px.
ARC_SAMPLE_STEP: float = 0.5

# --- Golden ladder and circle fitting (golden_ladder.py, circle_fitting.py, constrained_fit.py) ---
#: fit_circle: default cap on a fitted radius, as a multiple of the points' extent (the distance between their two
#: extreme points along the principal axis).
MAX_RADIUS_FACTOR: float = 20.0

# --- Progressive optimization (progressive.py) --------------------------------
#: Default tolerance T on the similarity error E^s (Eqn. 1), px; the paper's default.
TOLERANCE: float = 5.0
#: A logo's arcs when no budget is given (``Options.arcs`` None): where the fit within T has more, merging goes on
#: past T (``Options.stretch``); where it reaches the budget, the tangent pass adds no arcs past it. A golden ratio
#: logo is a silhouette and a few inner lines, a few dozen arcs.
LOGO_ARCS: int = 40
#: How far past T merging may go to bring a logo down to its arcs, as a factor of T: phi, one step of the golden
#: ladder. docs/design/logo-size.md has the measurements (2 T cut the silhouettes of busy clip arts).
STRETCH: float = PHI

# --- Arc extraction and intersections (arc_extraction.py) ---------------------
#: Arc-arc intersection: circles that overlap or miss each other by at most this touch once (tangency); centres and
#: radii equal within it make one circle; a point within it of an arc's angle range is on the arc, px.
INTERSECTION_TOL: float = 1e-6

# --- Quality measures (quality.py, make quality) ------------------------------
#: An open arc end this close to another arc or closer is joined to it, px.
GAP_MIN: float = 0.75
#: An open arc end within GAP_MIN..GAP_MAX of another arc is a near-miss gap (the eye closes it, the logo does
#: not); farther, it is a free end, px.
GAP_MAX: float = 6.0

# --- Symmetric logos (img2logo.fit.symmetry) ----------------------------------
#: Symmetric output: mirror-image circles are matched to within this distance, px.
SYMMETRY_PAIR_TOLERANCE: float = 1e-6
