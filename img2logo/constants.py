"""The golden ratio and every documented default and tolerance of img2logo.

One place for the numbers: a module that needs a threshold imports it from here,
so that a figure, a test and the README all speak of the same value.

Units: lengths are in pixels of the input image (px), angles in radians.
"""

from __future__ import annotations

import math

#: The golden ratio phi = (1 + sqrt 5) / 2 (paper Eqn. 2, 10).
PHI: float = (1.0 + math.sqrt(5.0)) / 2.0
#: log(phi), used to move between radii and ladder exponents (Eqn. 12, 14).
LOG_PHI: float = math.log(PHI)

#: Name of the result-file format (``contract/README.md``).
FORMAT_NAME: str = "img2logo.abstraction/1"

# --- Input images (preprocessing) -------------------------------------------------
#: Smallest accepted side of an input image, px.
MIN_IMAGE_SIDE: int = 16
#: Images whose longer side exceeds this are downscaled (with a warning), px.
MAX_IMAGE_SIDE: int = 2048
#: Largest accepted input, pixels (width x height), read from the file's header before
#: decoding: 8-bit RGBA at this size is 600 MB decoded; a larger file is refused as a
#: likely decompression bomb (the largest camera sensors give about 100 Mpx).
MAX_IMAGE_PIXELS: int = 150_000_000
#: Rows composited over white at a time when a large image with alpha is downscaled:
#: bounds the float32 temporaries to about 4 MB per 1000 px of width.
DOWNSCALE_STRIP_ROWS: int = 256
#: An image whose channel values span less than this (on a 0..1 scale) is "blank".
BLANK_IMAGE_RANGE: float = 1.0 / 255.0

# --- Feature lines ----------------------------------------------------------------
#: Side spurs of the skeleton shorter than this are pruned, px.
SPUR_LENGTH: float = 12.0
#: Connected specks of line pixels smaller than this are dropped, px (area).
MIN_SPECK_AREA: int = 24
#: Kind detection: an image is synthetic (a clip art or a drawing), not a photo, when
#: at least this fraction of its pixels have four neighbours of exactly their 8-bit
#: colour. Measured: clip arts and drawings 0.95-0.98 as PNG, 0.68-0.89 as JPEG of
#: quality 60 (flat blocks stay flat); photos, gray or colour, at most 0.13 (camera
#: noise and texture). The threshold sits between, with room on both sides.
SYNTHETIC_FLAT_FRACTION: float = 0.4
#: Kind detection: a synthetic image whose non-background regions all lie within this
#: colour distance (CIELAB Delta E 76) of their mean colour has one ink: a line
#: drawing if it is drawn in strokes. Twice the just noticeable difference, so
#: anti-aliasing left in a region does not count as a second colour.
INK_COLOUR_SPREAD: float = 4.6
#: Kind detection: a one-ink image is a line drawing when its strokes (twice the
#: median distance from the ink's medial axis to its edge) are at most this fraction
#: of the shorter image side wide; wider, it is a flat silhouette (a clip art).
DRAWING_MAX_STROKE_FRACTION: float = 0.08
#: Clip art: regions smaller than this are merged into a neighbour, px (area); the
#: pixels of smaller flat areas (anti-aliased rims, JPEG ringing) go to the region
#: whose colour they are nearest.
CLIPART_MIN_REGION_AREA: int = 64
#: Clip art: two neighbouring pixels within this colour distance (CIELAB Delta E 76)
#: belong to one flat area. Below half the just noticeable difference, so that a
#: pixel of an anti-aliased rim of any visible edge is never flat, and above one
#: 8-bit step of a smooth gradient (about 0.4).
CLIPART_LINK_DISTANCE: float = 1.0
#: Clip art: a pixel is flat when every pixel within this many px of it (a square
#: window) is within the link distance: the pixel's 8 neighbours, so that a pixel
#: of a diagonal anti-aliased rim is not flat either.
CLIPART_FLAT_RADIUS: int = 1
#: Clip art: a flat area of at least this many px seeds a region, px (area): a 3x3
#: block, so that a thin or small feature of a noisy image, whose flat pieces are
#: small, still has seeds; regions still smaller than CLIPART_MIN_REGION_AREA after
#: merging by contrast are merged into a neighbour.
CLIPART_SEED_AREA: int = 9
#: Clip art: a pixel outside the flat seeds takes the colour of a seed within this
#: distance, px: a rim or a JPEG-blurred edge is a blend of the two sides, not a
#: third colour; the 4 px reach over chroma subsampling (2 px) and ringing.
CLIPART_RIM_RADIUS: int = 4
#: Clip art: the spatial radius of the mean shift filter that flattens the fills of a
#: noisy (JPEG) clip art, px: the 8x8 blocks' noise averages out within it.
CLIPART_SHIFT_RADIUS: int = 4
#: Clip art: adjacent regions whose mean colours differ by less than this are one
#: region, CIELAB Delta E 76: the just noticeable difference (Sharma, Digital Color
#: Imaging Handbook, 2003): no visible boundary separates them.
CLIPART_MIN_CONTRAST: float = 2.3
#: Clip art: a noisy image (JPEG) links pixels, and keeps boundaries, only above this
#: many times its fills' typical neighbour difference (``clipart.colour_noise``, a
#: median): twice the median takes in the bulk of the noise of a fill.
CLIPART_NOISE_FACTOR: float = 2.0
#: Clip art: an image is noisy (compressed) when more than this fraction of its fill
#: pixels differ from a neighbour by a sub-visible amount (above 0, at most the just
#: noticeable difference); a clean fill is exactly flat and an edge is visible.
#: Measured (``clipart.colour_noise``): clean clip arts at most 0.02, JPEGs of
#: quality 70 at least 0.058; twice the clean maximum.
CLIPART_NOISY_FRACTION: float = 0.04
#: Clip art: a region at most this wide (twice the median distance from its medial
#: axis to its edge) is a stroke, px: it gives its centreline, not two boundaries
#: this close (less than the 6 px at which the segment graph merges junctions).
CLIPART_STROKE_WIDTH: float = 6.0
#: ... if its medial axis is at least this many times longer than its width (a
#: stroke, not a dot) ...
CLIPART_STROKE_ELONGATION: float = 3.0
#: ... and no part of it is wider than this many times CLIPART_STROKE_WIDTH.
CLIPART_STROKE_MAX_FACTOR: float = 2.0
#: Photo: the flow-based difference of Gaussians [KD09] parameters.
FDOG_SIGMA_C: float = 1.0
FDOG_SIGMA_M: float = 3.0
FDOG_RHO: float = 0.99
FDOG_TAU: float = 0.5
#: Photo: isolated feature lines shorter than this are texture, not features, px.
PHOTO_MIN_LINE_LENGTH: float = 40.0
#: Photo: the bilateral filter applied before the FDoG (diameter px, colour sigma
#: on a 0..1 gray scale).
BILATERAL_DIAMETER: int = 9
BILATERAL_SIGMA_COLOR: float = 0.1
#: Photo: smoothing of the structure tensor for the edge tangent flow, px.
ETF_SIGMA: float = 3.0

# --- Segment graph ----------------------------------------------------------------
#: Default Ramer-Douglas-Peucker tolerance of the over-segmentation, px (Sec. 4).
RDP_TOLERANCE: float = 2.0
#: Default: segments (whole chains between nodes) shorter than this are dropped
#: when they hang free at one end, px.
MIN_SEGMENT_LENGTH: float = 6.0
#: Two junctions joined by a chain shorter than this are one junction, px (a
#: thick "X" thins to two "Y"s and a short bridge).
JUNCTION_MERGE_DISTANCE: float = 6.0

# --- Result files and figures (writers, plotting) ---------------------------------
#: Contract invariant: a circle's radius is phi ** (k + bias) within this fraction
#: of r (``contract/README.md``).
RADIUS_RELATIVE_TOLERANCE: float = 1e-6
#: Contract invariant: a junction lies on the circle of each arc listed for it, and
#: at an end point of that arc, within this distance, px (``contract/README.md``).
JUNCTION_TOLERANCE: float = 1e-3
#: Decimal places of the coordinates written to SVG: 1e-6 px, far below
#: ``JUNCTION_TOLERANCE``.
SVG_DECIMALS: int = 6
#: Default stroke width of drawn arcs, as a fraction of the longer image side ...
STROKE_WIDTH_FRACTION: float = 1.0 / 128.0
#: ... but never thinner than this, px.
MIN_STROKE_WIDTH: float = 1.0
#: Resolution of PNG figures, dots per inch. It only converts px to matplotlib
#: points: a PNG is always exactly width x height px of the input.
PNG_DPI: float = 100.0
#: How far a background image is faded towards white under a drawing
#: (0 = as it is, 1 = white).
IMAGE_FADE: float = 0.6
#: Spacing of the sample points when an arc is drawn as a polyline in a raster, px.
ARC_SAMPLE_STEP: float = 0.5

# --- Golden ladder and circle fitting (golden_ladder.py, circle_fitting.py) --------
#: fit_circle: default cap on a fitted radius, as a multiple of the points' extent
#: (the distance between their two extreme points along the principal axis). An
#: arc of radius 20 x its chord c has a sagitta of c / 160: it is nearly straight.
MAX_RADIUS_FACTOR: float = 20.0
#: fit_circle: most Levenberg-Marquardt iterations refining the algebraic (Hyper) fit.
CIRCLE_REFINE_MAX_ITER: int = 30
#: fit_constrained: default tolerance on the connectivity constraints (Eqn. 13),
#: and on the size of the last SQP step, px.
CONSTRAINED_FIT_TOL: float = 1e-6
#: fit_constrained: a feasible iterate whose next step would lower E^l (Eqn. 7) by
#: less than this fraction of it has converged, even if the step exceeds the tolerance.
CONSTRAINED_FIT_FTOL: float = 1e-12
#: fit_constrained: default maximum number of SQP iterations.
CONSTRAINED_FIT_MAX_ITER: int = 50
#: fit_constrained: a fit whose constraint violation (still above the tolerance)
#: has not halved over this many iterations stops, unconverged: the fixed
#: variables most likely leave no feasible solution.
CONSTRAINED_FIT_STALL: int = 5
#: fit_constrained: damping mu of the KKT system, relative to the largest diagonal
#: entry of the Gauss-Newton matrix (the constraint block gets the same relative
#: regularization), so nearly singular systems (huge radii) stay solvable.
KKT_DAMPING: float = 1e-9
#: fit_constrained: KKT systems larger than this (unknowns + multipliers) are
#: solved by a sparse LU, smaller ones (a local window) by a dense solve.
KKT_DENSE_MAX: int = 60

# --- Progressive optimization (progressive.py) -------------------------------------
#: Default tolerance T on the similarity error E^s (Eqn. 1), px; the paper's default.
TOLERANCE: float = 5.0
#: Line-segment simplification (Sec. 5.4): neighbours are merged before the loop when
#: one circle fits them with a mean absolute error below this, px (the paper's 1.0).
SIMPLIFICATION_ERROR: float = 1.0

# --- Arc extraction and intersections (arc_extraction.py) --------------------------
#: Spacing of the samples of a candidate arc compared with a segment's pixels by
#: the discrete Fréchet distance (Sec. 5.3, Eqn. 3), px: about one per pixel, like
#: the pixel chain itself.
FRECHET_SAMPLE_STEP: float = 1.0
#: Arc extraction skips a candidate arc longer than this multiple of the segment's
#: polyline length plus ``ARC_CANDIDATE_LENGTH_SLACK`` before computing its Fréchet
#: distance: the "long way round" of a huge circle is tens of thousands of px long
#: (and as far from the segment). When every candidate is that long, the shortest
#: is kept.
ARC_CANDIDATE_LENGTH_RATIO: float = 3.0
#: See ``ARC_CANDIDATE_LENGTH_RATIO``, px: keeps short segments' candidates.
ARC_CANDIDATE_LENGTH_SLACK: float = 10.0
#: Arc-arc intersection: circles that overlap or miss each other by at most this
#: touch once (tangency); centres and radii equal within it make one circle; a
#: point within it of an arc's angle range is on the arc, px.
INTERSECTION_TOL: float = 1e-6
#: A point where two arcs meet is redundant (Sec. 5.2, Fig. 6c, 12) unless it is
#: within this distance of a junction both arcs belong to, px. It absorbs the two
#: nearby crossings of circles that should touch at a shared junction but overlap
#: by a rounding error: for radii 100 and 162 overlapping by 1e-3 px they lie
#: 0.35 px (touching outside) or 0.72 px (inside) from the point of contact.
REDUNDANT_INTERSECTION_TOL: float = 1.0
#: Ladder snapping (Eqn. 12): a radius at most this fraction above a rung snaps to
#: that rung, not the next one (a clean circle fit is exact to about 1e-12 only).
LADDER_SNAP_RTOL: float = 1e-9

# --- Straight lines (paper Sec. 9 future work, Fig. 20b) ----------------------------
#: With the lines option, a segment whose pixels all lie within this of their
#: best (total least squares) line is a straight line, px; a pixel staircase
#: strays up to about 0.7 px from its line.
LINE_TOLERANCE: float = 1.0
#: ... not counting this much of the segment at each end, px: thinning bevels the
#: corners of thick strokes towards the junction.
LINE_END_SKIP: float = 4.0
#: Two lines meeting at a junction must differ in direction by at least this, radians
#: (15 degrees): fixed lines pin their junction to their intersection.
LINE_MIN_ANGLE: float = 0.2617993877991494
#: A line is fitted as a circle of this fixed radius (outside the ladder, k = None):
#: the connectivity-constrained fit handles it like any circle, and over a 500 px
#: chord it is 0.03 px from straight. It is written as a true line, px.
LINE_RADIUS: float = 1e6

# --- Quality measures (quality.py, make quality) ------------------------------------
#: Spacing of the points sampled along a logo's arcs to measure it, px: well under
#: the 3 px of the finest recall measure.
QUALITY_SAMPLE_STEP: float = 0.5
#: sil6: an object outline pixel within this of the logo is kept, px.
SILHOUETTE_DISTANCE: float = 6.0
#: A logo point farther than this from the object mask is on the background, px:
#: twice the silhouette distance, so a slightly loose outline does not count.
OUTSIDE_DISTANCE: float = 12.0
#: Two arcs meeting farther than this from all their end points cross, px: arcs
#: that meet at a junction end there (to 1e-3 px); 1.5 px leaves room for the
#: two nearby crossings of circles that touch at a shared junction.
CROSSING_END_DISTANCE: float = 1.5
#: An open arc end this close to another arc or closer is joined to it, px.
GAP_MIN: float = 0.75
#: An open arc end within GAP_MIN..GAP_MAX of another arc is a near-miss gap (the
#: eye closes it, the logo does not); farther, it is a free end, px.
GAP_MAX: float = 6.0
