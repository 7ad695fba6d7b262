"""The defaults and thresholds that only the ``geometry`` stage uses.

One line of reason each; units, and where the measurements are, as in :mod:`img2logo.constants`.
"""

from __future__ import annotations

import math

# --- Result files and figures (writers, plotting) -----------------------------
#: Decimal places of the coordinates written to SVG: 1e-6 px, far below ``JUNCTION_TOLERANCE``.
SVG_DECIMALS: int = 6
#: An SVG arc command whose |sweep| exceeds this, rad, is written as two commands (a full circle always is): near a
#: full turn its two end points are so close that a renderer cannot place the centre reliably.
SVG_NEAR_FULL_SWEEP: float = 2.0 * math.pi - 1e-3

# --- Golden ladder and circle fitting (golden_ladder.py, circle_fitting.py, constrained_fit.py) ---
#: fit_circle: most Levenberg-Marquardt iterations refining the algebraic (Hyper) fit.
CIRCLE_REFINE_MAX_ITER: int = 30

# --- Arc extraction and intersections (arc_extraction.py) ---------------------
#: Ladder snapping (Eqn. 12): a radius at most this fraction above a rung snaps to that rung, not the next one (a
#: clean circle fit is exact to about 1e-12 only).
LADDER_SNAP_RTOL: float = 1e-9

# --- Straight lines (paper Sec. 9 future work, Fig. 20b) ----------------------
#: A line is fitted as a circle of this fixed radius (outside the ladder, k = None): the connectivity-constrained
#: fit handles it like any circle, and over a 500 px chord it is 0.03 px from straight.
LINE_RADIUS: float = 1e6
