"""The defaults and thresholds that only the ``features`` stage uses.

One line of reason each; units, and where the measurements are, as in :mod:`img2logo.constants`.
"""

from __future__ import annotations

import math

# --- Feature lines ------------------------------------------------------------
#: Side spurs of the skeleton shorter than this are pruned, px.
SPUR_LENGTH: float = 12.0
#: Drawing: paper pinched between two strokes to a light line this narrow or less (the disc of the white top-hat,
#: px: lines up to 4 px wide) and lighter than its sides by more than this share of the paper-ink contrast is
#: paper, not ink, so that the two strokes keep two centre lines.
SEAM_WIDTH: int = 5
SEAM_CONTRAST: float = 0.25
#: ... the seam is widened by the pixels beside it lighter than the ink by this share of the contrast (the strokes'
#: rims), never into the ink: a 1 px diagonal ridge has steps that 8-connected ink would cross.
SEAM_RIM: float = 0.1
#: ... and it is at least this many times the median stroke width long: two strokes that only touch (a tail on a
#: body) leave a ridge about as long as they are wide, and stay joined.
SEAM_LENGTH: float = 2.0
#: Connected specks of line pixels smaller than this are dropped, px (area).
MIN_SPECK_AREA: int = 24
#: Kind detection: an image is synthetic (a clip art or a drawing), not a photo, when at least this fraction of its
#: pixels have four neighbours of exactly their 8-bit colour.
SYNTHETIC_FLAT_FRACTION: float = 0.4
#: Kind detection: a synthetic image whose non-background regions all lie within this colour distance (CIELAB Delta
#: E 76) of their mean colour has one ink: a line drawing if it is drawn in strokes.
INK_COLOUR_SPREAD: float = 4.6
#: Kind detection: a region of a paper-ink blend at least this share of whose pixels are of the ink's colour
#: (within INK_COLOUR_SPREAD) is ink with its rims and the paper it encloses (a small ring of a 4 px stroke: about
#: half its pixels), not a grey of its own (a grey fill or line has no pixel of the ink's colour).
INK_SHARE: float = 0.25
#: Kind detection: an image of one ink with shading (its other colours all blends of the paper and the ink: greys
#: for black ink) is a line drawing when the ink is more than this share of what is drawn, the regions of the ink's
#: colour over all non-paper regions by area: the lines are then what the image is made of, the shading an accent.
SHADED_INK_SHARE: float = 0.6
#: ... and its ink is dark: CIELAB L* at most this (half the paper's), so that greys lie between it and the paper.
SHADED_INK_MAX_LIGHTNESS: float = 50.0
#: Kind detection: a one-ink image is a line drawing when its strokes (twice the median distance from the ink's
#: medial axis to its edge) are at most this fraction of the shorter image side wide.
DRAWING_MAX_STROKE_FRACTION: float = 0.08
#: Drawing: an ink part of at least MIN_SPECK_AREA px (a disc this wide, px) that thinning and the length filters
#: leave without a feature line (a filled dot, an animal's eye, a ring too small for its loop to pass SPUR_LENGTH)
#: is content, not noise: it becomes a closed line (a full golden circle) at its centre.
DOT_MIN_DIAMETER: float = 2.0 * math.sqrt(MIN_SPECK_AREA / math.pi)
#: ... the circle drawn for it is the one whose stroke (the drawing's median stroke width w) covers the part:
#: radius (d - w) / 2 for a part of diameter d, but at least this, px.
DOT_MIN_RADIUS: float = 2.0
#: Clip art: regions smaller than this are merged into a neighbour, px (area); the pixels of smaller flat areas
#: (anti-aliased rims, JPEG ringing) go to the region whose colour they are nearest.
CLIPART_MIN_REGION_AREA: int = 64
#: Clip art: two neighbouring pixels within this colour distance (CIELAB Delta E 76) belong to one flat area.
CLIPART_LINK_DISTANCE: float = 1.0
#: Clip art: a pixel is flat when every pixel within this many px of it (a square window) is within the link
#: distance: the pixel's 8 neighbours, so that a pixel of a diagonal anti-aliased rim is not flat either.
CLIPART_FLAT_RADIUS: int = 1
#: Clip art: a flat area of at least this many px seeds a region, px (area): a 3x3 block, so that a thin or small
#: feature of a noisy image, whose flat pieces are small, still has seeds.
CLIPART_SEED_AREA: int = 9
#: Clip art: a pixel outside the flat seeds takes the colour of a seed within this distance, px: a rim or a
#: JPEG-blurred edge is a blend of the two sides, not a third colour; the 4 px reach over chroma subsampling (2 px)
#: and ringing.
CLIPART_RIM_RADIUS: int = 4
#: Clip art, compressed (JPEG): a small fill of high contrast (an eye) has no flat pixel, as JPEG rings most in the
#: blocks of its strongest edges.
CLIPART_RING_WIDTH: float = 3.0
#: Clip art, compressed (JPEG): a pixel with no seed within CLIPART_RIM_RADIUS is explained only by the blends of
#: the seeds within this distance, px.
CLIPART_BLOCK_REACH: int = 16
#: ... and such a seed is a small fill only when its part of unexplained pixels lies mostly near it: at most this
#: many times what is within CLIPART_RIM_RADIUS px of it.
CLIPART_FILL_SPREAD: float = 4.0
#: Clip art: the spatial radius of the mean shift filter that flattens the fills of a noisy (JPEG) clip art, px:
#: the 8x8 blocks' noise averages out within it.
CLIPART_SHIFT_RADIUS: int = 4
#: Clip art: adjacent regions whose mean colours differ by less than this are one region, CIELAB Delta E 76: the
#: just noticeable difference (Sharma, Digital Color Imaging Handbook, 2003): no visible boundary separates them.
CLIPART_MIN_CONTRAST: float = 2.3
#: Clip art: a neighbour difference above this is an edge, not noise, when the noise level of a compressed image is
#: measured (CIELAB Delta E 76: four just noticeable differences).
CLIPART_EDGE_CONTRAST: float = 9.2
#: Clip art: a noisy image (JPEG) links pixels, and keeps boundaries, only above this many times its fills' typical
#: neighbour difference (``clipart.colour_noise``, a median): twice the median takes in the bulk of the noise of a
#: fill.
CLIPART_NOISE_FACTOR: float = 2.0
#: Clip art: an image is noisy (compressed) when more than this fraction of its fill pixels differ from a neighbour
#: by a sub-visible amount (above 0, at most the just noticeable difference).
CLIPART_NOISY_FRACTION: float = 0.04
#: Clip art: a region at most this wide (twice the median distance from its medial axis to its edge) is a stroke,
#: px.
CLIPART_STROKE_WIDTH: float = 6.0
#: Clip art: a region is an ink outline when at least this share of its border is with regions lighter than it by
#: CLIPART_EDGE_CONTRAST (L*): mostly, since a cartoon's outline also touches the odd pupil or dark shading.
CLIPART_INK_BORDER: float = 0.75
#: Clip art: a dark mark on the object's fills (an eye, a pupil, a spot, an inner outline: darker than
#: CLIPART_INK_BORDER of the fills around it by at least this, L*) is never merged at the detail asked.
CLIPART_MARK_CONTRAST: float = 25.0
#: Clip art: the most regions (the background included) the optimization is given at once.
CLIPART_MAX_REGIONS: int = 40
#: Kinds: an image in one ink is outlined shapes (a speech bubble, a badge) when its ink is closed bands round the
#: paper they enclose, every ink pixel within this many times the bands' width of that paper.
OUTLINE_BAND_REACH: float = 2.0
#: Clip art: an ink outline (a region darker than every region it touches: the cartoon style's outline between
#: lighter fills) is a stroke up to this wide, px.
CLIPART_OUTLINE_WIDTH: float = 12.0
#: ... if its medial axis is at least this many times longer than its width (a stroke, not a dot) ...
CLIPART_STROKE_ELONGATION: float = 3.0
#: ... and no part of it is wider than this many times CLIPART_STROKE_WIDTH.
CLIPART_STROKE_MAX_FACTOR: float = 2.0
#: Photo: the flow-based difference of Gaussians [KD09] parameters.
FDOG_SIGMA_C: float = 1.0
FDOG_SIGMA_M: float = 3.0
FDOG_RHO: float = 0.99
FDOG_TAU: float = 0.5
#: Photo: side spurs shorter than this are pruned, px.
PHOTO_SPUR_LENGTH: float = 20.0
#: Photo: isolated feature lines shorter than this are texture, not features, px.
PHOTO_MIN_LINE_LENGTH: float = 40.0
#: Photo: the bilateral filter applied before the FDoG (diameter px, colour sigma on a 0..1 gray scale).
BILATERAL_DIAMETER: int = 9
BILATERAL_SIGMA_COLOR: float = 0.1
#: Photo: smoothing of the structure tensor for the edge tangent flow, px.
ETF_SIGMA: float = 3.0
#: Photo subject (subject.py): GrabCut runs on a copy whose longer side is this, px (0.1-0.3 s).
SUBJECT_WORK_SIDE: int = 256
#: ... for this many iterations (OpenCV's default is 5).
SUBJECT_GRABCUT_ITERATIONS: int = 3
#: ... and this many from depth of field's seeds (focus_seeds), whose start is further from the cut.
FOCUS_GRABCUT_ITERATIONS: int = 5
#: Automatic subject: the strip of this fraction of each side along the frame is background when GrabCut starts
#: (the object is away from the image's edges).
SUBJECT_FRAME_INSET: float = 0.05
#: ... but an object found that comes within this many strip widths of the strip (it runs into it: a disc almost
#: filling the picture, a portrait's shoulders) has the strip near it reopened as probable background, for the
#: colour models to decide (subject_cut.reach_frame).
SUBJECT_FRAME_REACH: float = 2.0
#: ... in at most this many rounds of one GrabCut iteration (about 50 ms of CPU each at the working size), each
#: reopening the strip near the object as it has grown (a part of the object that the first cut's background model
#: ate comes back only once the strip beyond it is open too).
SUBJECT_FRAME_ROUNDS: int = 2
#: The full-size refinement relabels a band this wide around the first cut, px of the working copy (a working pixel
#: is 2-3 px of a 512 px photo).
SUBJECT_REFINE_BAND: int = 2
#: The subject mask is smoothed by a Gaussian of this sigma and thresholded at one half: no pixel staircase,
#: nothing thinner than about 2 sigma, px.
SUBJECT_SMOOTH_SIGMA: float = 2.0
#: Holes of a subject mask smaller than this fraction of its area are GrabCut's specks and are filled; larger ones
#: (a handle's loop) are the object's.
SUBJECT_MAX_HOLE: float = 0.01
#: Automatic subject: a candidate smaller than this fraction of the image is a detail (an eye, a highlight), not
#: the photo's subject ...
SUBJECT_MIN_AREA: float = 0.04
#: ... one larger than this is the scene itself ...
SUBJECT_MAX_AREA: float = 0.85
#: ... and one touching more than this fraction of the image frame runs off the picture: the whole image is kept
#: then.
SUBJECT_MAX_FRAME: float = 0.25
#: Automatic subject: the candidate's outline must be an edge: the median colour step across it (CIELAB, between
#: points SUBJECT_CONTRAST_STEP px inside and outside) at least this many times the median step along it (the
#: texture's).
SUBJECT_MIN_CONTRAST: float = 2.8
#: ... the distance of those points from the outline, px.
SUBJECT_CONTRAST_STEP: float = 4.0
#: Automatic subject, texture (subject_cues.texture_colour_image): GrabCut also cuts on CIELAB plus the texture,
#: this many L* units per decade of the local fine-detail energy.
SUBJECT_TEXTURE_WEIGHT: float = 20.0
#: ... and the energy floor added before the log, L* units: photo noise and JPEG grain (about 0.3 L* RMS) are no
#: texture, flat surfaces all look alike.
SUBJECT_TEXTURE_FLOOR: float = 0.3
#: ... an automatic subject whose outline is no colour edge is still kept when its texture differs from that around
#: it by at least this many decades of fine-detail energy (subject_cues.texture_step, the median along its
#: outline).
SUBJECT_MIN_TEXTURE_STEP: float = 0.5
#: Scenes (subject.dominant_part): a neck is thinner than a disc of this many times the square root of the
#: candidate's area in radius (0.08: about 17 px for a 220x220 px object; a trunk or a strip of sky between a
#: building and its trees is thinner, the body of an object wider) ...
SUBJECT_NECK: float = 0.08
#: ... and a part cut off by it counts if it holds this fraction of the area (smaller pieces are a tail or a leg,
#: left to the outline).
SUBJECT_MIN_PART: float = 0.15
#: Thin parts (subject_cues.thin_parts): GrabCut at the working size and the mask's smoothing drop a part of the
#: object a few px wide (a tail, a tripod's legs).
SUBJECT_THIN_WINDOW: float = 0.06
#: ... it is a part of the object if it leaves the mask (comes within 3 px of it over at most this fraction of its
#: own length: a strip along the outline is a rim or a shadow's edge, not a limb) ...
SUBJECT_THIN_MAX_CONTACT: float = 0.25
#: ... is at least this many times longer than wide (a stroke, not a blob of texture) and its colour differs from
#: the background around it (the median of CIELAB within half a window, other thin parts left out) by
#: SUBJECT_MIN_CONTRAST times that background's own spread (median distance from its median): a strip in clutter
#: (shelves, towers) is no more apart from its surround than the surround is from itself.
SUBJECT_THIN_MIN_ELONGATION: float = 4.0
#: Cast shadows (subject_shadow.cast_shadow): a shadow darkens the background it falls on by a factor and keeps its
#: chromaticity (linear RGB over its sum) and the texture of its log-luminance.
SHADOW_RING: tuple[float, float] = (1.5, 10.0)
#: ... the object's own features from the candidate this many working px inside its outline ...
SHADOW_CORE: float = 6.0
#: ... chromaticity smoothed by a Gaussian of this sigma, working px (JPEG and sensor noise make a single pixel's
#: chromaticity unreliable) ...
SHADOW_CHROMA_SIGMA: float = 1.0
#: ... ... a candidate pixel is shadowed background when it is darker than the ring's median and its chromaticity
#: is within this Mahalanobis distance of the ring's (2.5: about 95 % of the background's own spread), grown from
#: the pixels that chromaticity and texture together put nearer the background than the object ...
SHADOW_MAX_CHROMA_DISTANCE: float = 2.5
#: (then it is left out only if the outline section it takes away is no edge and the one left beside it is:
#: SUBJECT_MIN_CONTRAST; a penumbra is soft).
FACE_MIN_SIDE: float = 0.08
#: ... the cascade's windows grow by this factor from one scale to the next (the usual Viola-Jones step) ...
FACE_SCALE_STEP: float = 1.1
#: ... and a face is kept if at least this many overlapping windows found it: a face answers at many neighbouring
#: positions and scales, a face-like patch of texture (fur, gravel, a crumpled suit) at a few.
FACE_MIN_NEIGHBOURS: int = 12
#: Inside a face, FDoG lines are kept down to this fraction of the face's side in length (an eye or a brow is about
#: a fifth of the face), instead of the photo's INNER_MIN_LENGTH and PHOTO_MIN_LINE_LENGTH, which would drop them.
FACE_MIN_LINE: float = 0.1
#: Automatic subject, depth of field (subject_cues.focus_seeds): fine detail is the image minus its Gaussian blur
#: of this sigma, px of the working copy ...
FOCUS_DETAIL_SIGMA: float = 1.0
#: ... its energy is averaged over a Gaussian window of this sigma, px of the working copy (about 5 px of a 512 px
#: photo) ...
FOCUS_WINDOW: float = 2.5
#: ... and divided by its 90th percentile over the image.
FOCUS_BLURRED: float = 0.12
#: ... above this it is in focus; the sharp map is eroded by this many working px (two windows) so that what is
#: left is texture in focus, not one edge between two smooth parts.
FOCUS_SHARP: float = 0.35
FOCUS_SHARP_CORE: int = 5
#: Depth of field is used when at least this fraction of the frame strip is blurred (a background shows there) ...
FOCUS_MIN_BLURRED_FRAME: float = 0.3
#: ... at least this fraction is in focus (the subject runs off the picture there; a subject away from the frame is
#: found from the whole frame, as before: data/photo-flower.png has 6 %, the close-up cat 27 %) ...
FOCUS_MIN_SHARP_FRAME: float = 0.1
#: ... the blurred part of the frame is soft, not flat: the energy of the band between Gaussians of these sigmas
#: (working px), over a window of FOCUS_SOFT_WINDOW, median over the blurred frame, over the fine detail's 90th
#: percentile, at least FOCUS_MIN_SOFT.
FOCUS_SOFT_SIGMAS: tuple[float, float] = (2.0, 8.0)
FOCUS_SOFT_WINDOW: float = 8.0
FOCUS_MIN_SOFT: float = 0.18
#: ... and the sharp cores cover at least this fraction of the image.
FOCUS_MIN_SHARP_AREA: float = 0.02
#: A subject found by depth of field must be sharper inside its outline than outside: median focus this many
#: working px inside over the median as far outside at least FOCUS_MIN_STEP (or its colour step is an edge, as
#: above).
FOCUS_STEP: int = 8
FOCUS_MIN_STEP: float = 2.5
#: Photo outline: parts of the subject's outline within this of the image frame are the picture's edge, not the
#: object's, px.
OUTLINE_FRAME_MARGIN: float = 2.0
#: Photo inner lines are kept this far inside the subject's outline, px (the outline is drawn from the mask; an
#: edge line next to it would double it).
INNER_LINE_MARGIN: int = 4
#: Photo inner lines: before joining, a connected line with fewer pixels than this is a stroke of texture, not a
#: feature (PHOTO_MIN_LINE_LENGTH, the same bound the isolated lines get after thinning), px ...
INNER_MIN_LENGTH: float = 40.0
#: ... and one whose bounding box has a diagonal under this is a tangle (a thinned blob of fur or foam: a 40 px
#: line folded into a 20 px box), px.
INNER_MIN_SPAN: float = 24.0
#: Photo lines: at most this many times (height + width) of line pixels, the subject's outline first, then the
#: longest inner lines (scenes: the longest lines).
PHOTO_LINE_BUDGET: float = 3.0
#: Photo dark dots (photo_features.dark_dots): eyes and noses, small dark blobs on the subject that a designer
#: always keeps and the length filters above drop (a 5 px eye's outline is 31 px).
DOT_MAX_RADIUS_FRACTION: float = 1.0 / 32.0
#: ... the scale-space blob detector's scales per doubling of the radius: three, the usual sampling of a scale
#: space (Lowe's SIFT; Lindeberg), enough that a dot's scale is within 12 % of a sampled one.
DOT_SCALES_PER_OCTAVE: int = 3
#: ... and a dot is at least this much darker than the ring around it, L* (its centre's mean against the ring's
#: median): CIE76 dE 10, colours that read as different at a glance (dE 2.3 is the just-noticeable difference).
DOT_MIN_CONTRAST: float = 10.0
#: ... and at least this many times the lightness spread of the ring around it (its 10-90 % range, L*).
DOT_SURROUND_CONTRAST: float = 2.0
#: Photo clear steps (photo.clear_steps): a line of the FDoG without its bias to dark sides is kept inside the
#: subject when the lightness difference between its two sides is at least this many times the sides' own spread
#: along it.
STEP_SIDE_CONTRAST: float = DOT_SURROUND_CONTRAST
#: Photo enclosed dots (photo_features.enclosed_dots): a pupil is a dark dot inside a lighter closed loop of the
#: lightness lines (an iris, an eye's opening).
EYE_MAX_RADIUS_FRACTION: float = 4.0 * DOT_MAX_RADIUS_FRACTION
#: ... the dot, the lines inside the loop and what they enclose, is at most this share of the loop's convex hull.
EYE_MAX_PUPIL_SHARE: float = 0.5
#: ... and it is enclosed: at least this share of the pixels just around it are the loop's inside (the rest: lines
#: of the loop it touches).
EYE_ENCLOSED_SHARE: float = 2.0 / 3.0
#: ... and its centre lies within this share of the loop's radius of the loop's centre (in the loop's own ellipse):
#: a pupil is at its iris's centre, which an eyelid cutting the loop shifts (a cat's half-covered iris: 0.4).
EYE_MAX_PUPIL_OFFSET: float = 0.5

# --- Symmetric logos (img2logo.fit.symmetry) ----------------------------------
#: Photo colour lines: the colour-opponent FDoG runs on a copy this many times smaller (each side), on its own
#: flow: a photo's chroma is blurrier than its lightness (JPEG keeps it at half resolution, 4:2:0; the eye resolves
#: it at about half the lightness's acuity), a step's DoG response does not depend on the pixel size, and the pass
#: costs a quarter (0.03 s on a 512 px photo).
COLOUR_LINE_SUBSAMPLE: float = 2.0
#: Photo colour lines (photo.photo_lines, photo.new_colour_lines): a line of the colour-opponent FDoG is kept only
#: this far from both sides of every lightness edge, px.
COLOUR_LINE_GATE: float = 3.0 * 1.6 * FDOG_SIGMA_C * COLOUR_LINE_SUBSAMPLE
#: Photo colour lines (photo.new_colour_lines): the two sides of a drawn lightness line (its dark line and its
#: bright lobe, where the colour line of the same edge lies) are the lightness edge within this of it, px.
EDGE_SIDE_REACH: float = 3.0 * 1.6 * FDOG_SIGMA_C
