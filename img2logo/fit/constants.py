"""The defaults and thresholds that only the ``fit`` stage uses.

One line of reason each; units, and where the measurements are, as in :mod:`img2logo.constants`.
"""

from __future__ import annotations

import math

# --- Segment graph ------------------------------------------------------------
#: A tangent join's junction slides along the input's line (img2logo.fit.tangency), the two groups' pixels split
#: anew where it is: each keeps at least this many pixels, the fewest a circle is fitted to (three points fix a
#: circle).
SLIDE_MIN_PIXELS: int = 3
#: A tangent join whose circles cannot touch on their rungs tries at most this many choices of one rung up or down
#: for the two circles (img2logo.fit.tangency), those that bring the circles nearest to touching first.
RUNG_CHOICES: int = 2
#: The joint refit of a level's tangent joins (img2logo.fit.tangency._all_at_once) tries at most this many times,
#: releasing one join after each failure: every try solves the whole drawing at once.
ALL_AT_ONCE_TRIES: int = 2
#: The result's level (img2logo.fit.kinks.tangent_level): a smooth join left kinked weighs this many arcs, and
#: the level kept, the merge loop's last or one before it, has the fewest arcs plus weighted kinks after its
#: tangent refit.
KINK_WEIGHT: int = 2
#: A smooth join that no refit from its circles makes tangent is fitted as one unit, a tangent biarc over its two
#: groups' joined pixels (img2logo.fit.biarcs.closest_biarcs).
BIARC_STEP: int = 6
#: ... its common tangent there up to this far from the chain's direction, rad (the kinks left on smooth input are
#: 3-25 degrees, measured) ...
BIARC_TURN: float = math.radians(30.0)
#: ... in this many steps either way (4 degrees; the grid is searched again four times finer around its best) ...
BIARC_TURN_STEPS: int = 8
#: ... and the refit starts from the best this many of the rung choices (each a fit).
BIARC_STARTS: int = 2

# --- Golden ladder and circle fitting (golden_ladder.py, circle_fitting.py, constrained_fit.py) ---
#: fit_constrained: default tolerance on the connectivity constraints (Eqn. 13), and on the size of the last SQP
#: step, px.
CONSTRAINED_FIT_TOL: float = 1e-6
#: window_solve.solve with a bound: a fit is cut off once a lower bound of E^s exceeds the bound by more than this
#: fraction of it (at least 1 px times it).
CUT_MARGIN: float = 1e-9
#: fit_constrained: a feasible iterate whose next step would lower E^l (Eqn. 7) by less than this fraction of it
#: has converged, even if the step exceeds the tolerance.
CONSTRAINED_FIT_FTOL: float = 1e-12
#: fit_constrained: default maximum number of SQP iterations.
CONSTRAINED_FIT_MAX_ITER: int = 50
#: fit_constrained: a fit whose constraint violation (still above the tolerance) has not halved over this many
#: iterations stops, unconverged: the fixed variables most likely leave no feasible solution.
CONSTRAINED_FIT_STALL: int = 5
#: fit_constrained: damping mu of the KKT system, relative to the largest diagonal entry of the Gauss-Newton matrix
#: (the constraint block gets the same relative regularization), so nearly singular systems (huge radii) stay
#: solvable.
KKT_DAMPING: float = 1e-9
#: fit_constrained: KKT systems larger than this (unknowns + multipliers) are solved by a sparse LU, smaller ones
#: (a local window) by a dense solve.
KKT_DENSE_MAX: int = 60
#: fit_constrained: the largest KKT system the compiled global solve takes (kernels_sqp.sqp_banded assembles it in
#: a dense size x size scratch matrix before reading its band: 2500 is about 50 MB; the examples' largest is about
#: 700, the cactus's initial fit); larger ones run the Python reference, whose memory grows with the band only.
KKT_COMPILED_MAX: int = 2500

# --- Progressive optimization (progressive.py) --------------------------------
#: Rings of the wider window a merge candidate is refitted in when its local window (two rings) fails: the new
#: circle's junctions free, then those of the circles through them, ... (Sec. 5.4).
MERGE_FALLBACK_RINGS: int = 6
#: Line-segment simplification (Sec. 5.4): neighbours are merged before the loop when one circle fits them with a
#: mean absolute error below this, px (the paper's 1.0).
SIMPLIFICATION_ERROR: float = 1.0
#: A segment of a clip art is on the object's silhouette when most of its points lie within this many px of the
#: background (its line runs on the object's pixels next to the paper), px ...
OUTLINE_DISTANCE: float = 2.0
#: ... or within this many px and reached from the paper without crossing another line: the centre line of an
#: outline stroke up to CLIPART_STROKE_WIDTH (6 px) wide lies half its width from the paper, px.
OUTLINE_STROKE_DISTANCE: float = OUTLINE_DISTANCE + 3.0
#: A merge candidate whose new circle (radius fixed on the ladder) cannot pass within ``max_arc_distance`` + this
#: of all its pixels, wherever its centre, is rejected before its fit (img2logo.fit.merging,
#: kernels_sqp.far_circle_kernel): the fit's arc, coupled to every pixel by the Fréchet distance, would be farther.
FAR_ARC_MARGIN: float = 1e-6
#: Most boxes of centres the proof above tries before giving up (then the fit decides): on the flower's 117 merged
#: groups at most ~800 us each, ~4 ms in all.
FAR_ARC_BUDGET: int = 20000
#: A merge candidate whose merged arc lies farther than this times its cap (``max_arc_distance``, T on the
#: silhouette) from its pixels after its window's refit is refitted again only once a merge changes a group of that
#: window (img2logo.fit.merging.merge_loop), as one whose window failed: until then its refit changes only by the
#: weights 1/|A|, 1/|J'| and the junctions it shares with groups outside it. Measured on the 101 images of data/ and
#: benchmarks/data/, refitting every time: of 15917 such refits 99 % moved the arc by less than 1 % of the cap, and
#: the 6 that brought it within the cap were less than 0.3 % past it before (with 1 here, 3 of the logos changed).
FAR_ARC_RETRY: float = 1.1

# --- Arc extraction and intersections (arc_extraction.py) ---------------------
#: Spacing of the samples of a candidate arc compared with a segment's pixels by the discrete Fréchet distance
#: (Sec. 5.3, Eqn. 3), px: about one per pixel, like the pixel chain itself.
FRECHET_SAMPLE_STEP: float = 1.0
#: Arc extraction skips a candidate arc longer than this multiple of the segment's polyline length plus
#: ``ARC_CANDIDATE_LENGTH_SLACK`` before computing its Fréchet distance.
ARC_CANDIDATE_LENGTH_RATIO: float = 3.0
#: See ``ARC_CANDIDATE_LENGTH_RATIO``, px: keeps short segments' candidates.
ARC_CANDIDATE_LENGTH_SLACK: float = 10.0
#: A point where two arcs meet is redundant (Sec. 5.2, Fig. 6c, 12) unless it is within this distance of a junction
#: both arcs belong to, px.
REDUNDANT_INTERSECTION_TOL: float = 1.0

# --- Straight lines (paper Sec. 9 future work, Fig. 20b) ----------------------
#: With the lines option, a segment whose pixels all lie within this of their best (total least squares) line is a
#: straight line, px; a pixel staircase strays up to about 0.7 px from its line.
LINE_TOLERANCE: float = 1.0
#: ... not counting this much of the segment at each end, px: thinning bevels the corners of thick strokes towards
#: the junction.
LINE_END_SKIP: float = 4.0
#: Two lines meeting at a junction must differ in direction by at least this, radians (15 degrees): fixed lines pin
#: their junction to their intersection.
LINE_MIN_ANGLE: float = 0.2617993877991494

# --- Symmetric logos (img2logo.fit.symmetry) ----------------------------------
#: Mirror-axis detection: a feature-line pixel is matched when its mirror image lies within this distance of a
#: feature-line pixel, px.
SYMMETRY_MATCH_DISTANCE: float = 2.0
#: Mirror-axis detection: the feature-line pixels sampled (evenly along the map) to score candidate axes; enough
#: for the score to within about 1 % and fast.
SYMMETRY_SAMPLE_POINTS: int = 2000
#: Mirror-axis detection: angular step of the coarse search over axis directions, radians (2 degrees).
SYMMETRY_ANGLE_STEP: float = math.radians(2.0)
#: Mirror-axis detection: the coarse search tries axes this far on either side of the line pixels' centroid (a
#: symmetric point set has its centroid on its axis), px.
SYMMETRY_OFFSET_RANGE: float = 16.0
#: Mirror-axis detection: offset step of the coarse search, px.
SYMMETRY_OFFSET_STEP: float = 1.0
#: ``symmetry="auto"`` keeps the best axis when its score (the fraction of feature-line pixels whose mirror image
#: is a feature line within SYMMETRY_MATCH_DISTANCE) is at least this.
SYMMETRY_THRESHOLD: float = 0.72
#: Symmetric segment graph: points within this distance of the axis are put on it, px (a line along the axis, a
#: junction on it, the end of a line that stops at it).
SYMMETRY_SNAP_DISTANCE: float = 1.0
#: Symmetric segment graph: a line that meets the axis within this angle of square to it continues smoothly into
#: its mirror image, so its circle is centred on the axis.
SYMMETRY_SMOOTH_ANGLE: float = math.radians(30.0)
#: Symmetric segment graph: the direction of a line where it meets the axis is taken over this length of it, px
#: (the last pixels are bent by thinning).
SYMMETRY_TANGENT_LENGTH: float = 6.0
#: Symmetric runs: the constrained fit gives up when the violation has not halved over this many steps
#: (CONSTRAINED_FIT_STALL elsewhere).
SYMMETRY_FIT_STALL: int = 20
#: ``symmetry="auto"``: an axis found within this many degrees of upright (or level) is made exactly upright
#: (level) when that costs at most SYMMETRY_SNAP_SCORE_LOSS of score.
SYMMETRY_SNAP_ANGLE: float = 1.0
#: See SYMMETRY_SNAP_ANGLE: the score an exactly upright axis may lose, as a fraction.
SYMMETRY_SNAP_SCORE_LOSS: float = 0.01
