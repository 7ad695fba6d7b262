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

#: Weights of R, G, B in the gray value (ITU-R BT.601 luma), unit-free: the gray of
#: the photo's line drawing, of a mask image and of the subject's focus measure.
LUMA_WEIGHTS: tuple[float, float, float] = (0.299, 0.587, 0.114)

#: Name of the result-file format (``contract/README.md``).
FORMAT_NAME: str = "img2logo.abstraction/1"

# --- Input images (preprocessing) -------------------------------------------------
#: Smallest accepted side of an input image, px.
MIN_IMAGE_SIDE: int = 16
#: Images whose longer side exceeds this are downscaled (with a warning), px.
MAX_IMAGE_SIDE: int = 2048
#: A photo is worked at most this size on its longer side, px (the result is scaled back
#: to the input's pixels, as for MAX_IMAGE_SIDE). The photo stage's lengths (T = 5 px,
#: PHOTO_MIN_LINE_LENGTH, PHOTO_SPUR_LENGTH, the subject's margins) were chosen and
#: measured on photos of 300-512 px (the evaluation set, data/), and a logo of 20-60 arcs
#: of a photo's subject needs no finer texture: worked at this size, a photo gives the
#: logo those defaults were measured for, whatever its resolution. At the 2048 px
#: working size the noisy 12000 px flower gave 103 arcs, its outline in
#: pieces, and took 25 s of CPU; at 1024 px 60 arcs, at 512 px 33 arcs, whole.
#: Clip art and drawings: SYNTHETIC_WORK_SIDE.
PHOTO_WORK_SIDE: int = 512
#: A clip art or a line drawing is worked at most this size on its longer side, px, for the
#: photo's reason (the result is scaled back to the input's pixels, as for MAX_IMAGE_SIDE):
#: its stage's lengths (T = 5 px, SPUR_LENGTH, CLIPART_RIM_RADIUS, the seed and region
#: areas, the 3x3 flatness test, the drawing's stroke and rim tests) were chosen on 512 px
#: images whose edges are 1-2 px of anti-aliasing, and T = 5 px of 512 is the detail of a
#: logo of 20-60 arcs. Measured with benchmarks/upscaled.py (the evaluation set's 7 clip arts
#: and 9 drawings upscaled bicubic to 2048 and 4000 px; r10 of the logo scaled back, against
#: the 512 px truth): worked at 2048 px (before), the clip arts gave 92 arcs on average for
#: the originals' 39 (the ewe 136), the seal lost its outline (r10 0.18: an upscaled edge is
#: a ramp its noise test takes for compression), 16 s of CPU each, and 5 of the 9 drawings
#: were taken for clip arts; at 1024 px 56 arcs, r10 0.98, and still 5 of 9 drawings taken
#: for clip arts (their strokes' ramps read as a second colour); at 512 px the originals'
#: logos: 39-40 arcs, r10 0.97 (the drawings 12.9 arcs for 12.7, r10 1.00), every kind right,
#: 3 s. Thin strokes survive the area downscale as faint lines: 3 px strokes of a 4096 px
#: drawing and clip art (0.4 px at 512) are all traced. What is lost is what a 512 px copy
#: cannot show (a part under CLIPART_MIN_REGION_AREA there).
SYNTHETIC_WORK_SIDE: int = 512
#: Largest accepted input, pixels (width x height), read from the file's header before
#: decoding: 8-bit RGBA at this size is 600 MB decoded; a larger file is refused as a
#: likely decompression bomb (the largest camera sensors give about 100 Mpx).
MAX_IMAGE_PIXELS: int = 150_000_000
#: Largest accepted floating-point image (Radiance HDR, PFM), pixels: OpenCV decodes it whole
#: into float32 RGB, 12 bytes a pixel, and the range check adds 3 more; at 64 Mpx that is about
#: 1 GB (estimated, 15 bytes a pixel), within the 1.5 GB bound (a 12000 px one: 5.13 GB, 26-29 s of
#: CPU, measured with benchmarks/huge.py).
MAX_FLOAT_IMAGE_PIXELS: int = 64_000_000
#: Largest strip (or tile) of a TIFF, bytes of decoded samples (its width x rows x a pixel's bits / 8):
#: libtiff decodes a strip whole, so a file in one strip of the whole image is the whole image in
#: memory however it is read (a 12000 px 16-bit RGBA TIFF: 1.15 GB of samples). 350 MB keeps the
#: peak within the 1.5 GB bound on any accepted image (8-bit RGB up to about 117 Mpx in one strip).
MAX_WHOLE_TIFF_BYTES: int = 350_000_000
#: The largest length an option takes (``tolerance``, ``rdp_tolerance``,
#: ``min_length``, ``max_arc_distance``, the Fibonacci ``unit``) and the largest
#: radius a ladder may offer, px: longer than any accepted image (MAX_IMAGE_PIXELS
#: in MIN_IMAGE_SIDE rows is 9.4e6 px long). Beyond it values only overflow
#: (``--rdp 1e200``: OpenCV refuses the epsilon; ``--unit 1e308``: LAPACK fails).
MAX_LENGTH: float = 1e7
#: The smallest radius a ladder may offer (``exponents``, ``--radii``; the Fibonacci
#: ``unit``), px: a thousandth of a pixel, a circle no drawing can show; below it
#: phi ** k only heads for underflow (``--radii=-1000000``).
MIN_LADDER_RADIUS: float = 1e-3
#: The largest angle an option takes, degrees (``symmetry``'s axis direction, either sign): a
#: direction repeats every 360 degrees (a mirror axis every 180), so a larger number is a
#: typo, and from about 1e18 degrees on a double's spacing exceeds a turn and the direction
#: it names is noise (``--symmetry 1e308`` had run with an arbitrary axis).
MAX_ANGLE_DEGREES: float = 360.0
#: Rows composited over white at a time when a large image with alpha is downscaled:
#: bounds the float32 temporaries to about 4 MB per 1000 px of width.
DOWNSCALE_STRIP_ROWS: int = 256
#: An image whose channel values span less than this (on a 0..1 scale) is "blank".
BLANK_IMAGE_RANGE: float = 1.0 / 255.0

# --- Feature lines ----------------------------------------------------------------
#: Side spurs of the skeleton shorter than this are pruned, px.
SPUR_LENGTH: float = 12.0
#: Drawing: paper pinched between two strokes to a light line this narrow or less (the disc
#: of the white top-hat, px: lines up to 4 px wide) and lighter than its sides by more than
#: this share of the paper-ink contrast is paper, not ink, so that the two strokes keep two
#: centre lines. A quarter: far above JPEG ringing inside a stroke (a few %), below the
#: 0.45-0.5 of a 1-2 px gap between two anti-aliased strokes.
SEAM_WIDTH: int = 5
SEAM_CONTRAST: float = 0.25
#: ... the seam is widened by the pixels beside it lighter than the ink by this share of the
#: contrast (the strokes' rims), never into the ink: a 1 px diagonal ridge has steps that
#: 8-connected ink would cross.
SEAM_RIM: float = 0.1
#: ... and it is at least this many times the median stroke width long: two strokes that only
#: touch (a tail on a body) leave a ridge about as long as they are wide, and stay joined.
SEAM_LENGTH: float = 2.0
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
#: Kind detection: a region of a paper-ink blend at least this share of whose pixels are of
#: the ink's colour (within INK_COLOUR_SPREAD) is ink with its rims and the paper it
#: encloses (a small ring of a 4 px stroke: about half its pixels), not a grey of its own
#: (a grey fill or line has no pixel of the ink's colour).
INK_SHARE: float = 0.25
#: Kind detection: an image of one ink with shading (its other colours all blends of the
#: paper and the ink: greys for black ink) is a line drawing when the ink is more than this
#: share of what is drawn, the ink's regions over all non-paper regions by area: the lines
#: are then what the image is made of, the shading an accent between them. Measured on
#: Openclipart's shaded drawings: the ink 0.67 (a feather's light grey vane) to 0.93 (an ice
#: cream cone); a clip art of dark outlines around grey fills (X11's eyes) 0.50, the grey
#: clip arts of benchmarks/data (a ewe, a seal) have a grey darker than their largest colour.
SHADED_INK_SHARE: float = 0.6
#: ... and its ink is dark: CIELAB L* at most this (half the paper's), so that greys lie
#: between it and the paper. Measured: the shaded drawings' inks L* 1-10; the darkest
#: colour of a clip art of pale grey hairlines (Openclipart's caduceus) L* 82.
SHADED_INK_MAX_LIGHTNESS: float = 50.0
#: Kind detection: a one-ink image is a line drawing when its strokes (twice the
#: median distance from the ink's medial axis to its edge) are at most this fraction
#: of the shorter image side wide; wider, it is a flat silhouette (a clip art).
DRAWING_MAX_STROKE_FRACTION: float = 0.08
#: Drawing: an ink part of at least MIN_SPECK_AREA px (a disc this wide, px) that thinning
#: and the length filters leave without a feature line (a filled dot, an animal's eye, a
#: ring too small for its loop to pass SPUR_LENGTH) is content, not noise: it becomes a
#: closed line (a full golden circle) at its centre. Smaller ink is removed as a speck
#: before thinning, so this is the speck filter's own bound, written as a diameter.
DOT_MIN_DIAMETER: float = 2.0 * math.sqrt(MIN_SPECK_AREA / math.pi)
#: ... the circle drawn for it is the one whose stroke (the drawing's median stroke
#: width w) covers the part: radius (d - w) / 2 for a part of diameter d, but at least
#: this, px: a 1-px ring of radius 2 is 13 px round, the smallest closed line the
#: SPUR_LENGTH filter keeps and the segment graph can split into two segments.
DOT_MIN_RADIUS: float = 2.0
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
#: Clip art, compressed (JPEG): a small fill of high contrast (an eye) has no flat pixel, as
#: JPEG rings most in the blocks of its strongest edges; its pixels that no blend of the
#: seeds near them explains seed it where they lie more than this from any other pixel, px.
#: Ringing is a 1-2 px halo, but chroma is kept at half resolution (4:2:0) and bleeds: along
#: a yellow-on-blue edge at quality 60 the strip of unexplained colours is up to 6 px wide
#: (measured), so its pixels are all within 3 px of its edge. A dot needs about 10 px across.
CLIPART_RING_WIDTH: float = 3.0
#: Clip art, compressed (JPEG): a pixel with no seed within CLIPART_RIM_RADIUS is explained
#: only by the blends of the seeds within this distance, px: as far as JPEG spreads an edge's
#: colours (chroma is coded at half resolution in 8 x 8 blocks, 16 x 16 px of the image), so
#: a rim or bleeding pixel has its sides' flat pixels this near. Not by a seed's colour from
#: farther away: a 14 px spot of the colour of larger spots elsewhere is a fill of its own;
#: nor across another colour (clipart._reached_entries: the seed's colour must reach the
#: pixel), as a 14 px spot 10 px from a larger one of its colour is.
CLIPART_BLOCK_REACH: int = 16
#: ... and such a seed is a small fill only when its part of unexplained pixels lies mostly
#: near it: at most this many times what is within CLIPART_RIM_RADIUS px of it. Measured:
#: 1.2-1.9 for the eye and horn tips of JPEG clip arts; 27-50 where two 3 px strokes of a
#: line drawing (its whole network unexplained, with no flat pixel) cross.
CLIPART_FILL_SPREAD: float = 4.0
#: Clip art: the spatial radius of the mean shift filter that flattens the fills of a
#: noisy (JPEG) clip art, px: the 8x8 blocks' noise averages out within it.
CLIPART_SHIFT_RADIUS: int = 4
#: Clip art: adjacent regions whose mean colours differ by less than this are one
#: region, CIELAB Delta E 76: the just noticeable difference (Sharma, Digital Color
#: Imaging Handbook, 2003): no visible boundary separates them.
CLIPART_MIN_CONTRAST: float = 2.3
#: Clip art: a neighbour difference above this is an edge, not noise, when the noise
#: level of a compressed image is measured (CIELAB Delta E 76: four just noticeable
#: differences).
CLIPART_EDGE_CONTRAST: float = 9.2
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
#: Clip art: the default ``detail`` (:func:`img2logo.features.detail.merge_by_importance`):
#: the regions kept besides the background, the weightiest by Ward's criterion. The
#: icon-style clip arts whose logos are already good (the evaluation and held-out families:
#: emoji, icons, critters, 8-24 regions besides the background) are left whole; busier clip
#: art (cartoon animals, vehicles, emblems: 20-70) keeps its 24 weightiest regions, plus
#: what is never merged (the silhouette, its ink outline, dark marks).
DETAIL: int = 24
#: Clip art: a region at most this wide (twice the median distance from its medial
#: axis to its edge) is a stroke, px: it gives its centreline, not two boundaries
#: this close (less than the 6 px at which the segment graph merges junctions).
CLIPART_STROKE_WIDTH: float = 6.0
#: Clip art: a region is an ink outline when at least this share of its border is with
#: regions lighter than it by CLIPART_EDGE_CONTRAST (L*): mostly, since a cartoon's outline
#: also touches the odd pupil or dark shading; a grey between a white and a black (half
#: and half) is none.
CLIPART_INK_BORDER: float = 0.75
#: Clip art: a dark mark on the object's fills (an eye, a pupil, a spot, an inner outline:
#: darker than CLIPART_INK_BORDER of the fills around it by at least this, L*) is never
#: merged at the detail asked: a quarter of the lightness range, a black or dark mark on a
#: mid or light fill. Hatching and shading drawn in a darker shade of their fill's colour
#: (10-20 L* darker) merge.
CLIPART_MARK_CONTRAST: float = 25.0
#: Clip art: the most regions (the background included) the optimization is given at once.
#: Where more remain at the detail asked, the least important are merged on, and a warning
#: says so (:func:`img2logo.features.detail.merge_by_importance`).
CLIPART_MAX_REGIONS: int = 40
#: Kinds: an image in one ink is outlined shapes (a speech bubble, a badge) when its ink is
#: closed bands round the paper they enclose, every ink pixel within this many times the
#: bands' width of that paper: a band's pixels are within one width of it (a rounded
#: corner's about 1.4), a stroke running off an outline (a stem, a string) many
#: (``img2logo.features.preprocessing.outline_band_width``).
OUTLINE_BAND_REACH: float = 2.0
#: Clip art: an ink outline (a region darker than every region it touches: the cartoon
#: style's outline between lighter fills) is a stroke up to this wide, px: its centre line
#: is within 6 px of both its edges, the distance at which the segment graph merges
#: junctions and at which sil6 counts the silhouette kept.
CLIPART_OUTLINE_WIDTH: float = 12.0
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
#: Photo: side spurs shorter than this are pruned, px. A photo's side branches
#: are texture or thinning's artefacts, and one up to about 3 x
#: LINE_JOIN_DISTANCE long can run beside its sibling within near-miss distance
#: (measured on 14 photos: near-miss gaps 4 -> 2, crossings 1 -> 0, at 12 -> 20 px;
#: the photo-likes' logos unchanged).
PHOTO_SPUR_LENGTH: float = 20.0
#: Photo: isolated feature lines shorter than this are texture, not features, px.
PHOTO_MIN_LINE_LENGTH: float = 40.0
#: Photo: the bilateral filter applied before the FDoG (diameter px, colour sigma
#: on a 0..1 gray scale).
BILATERAL_DIAMETER: int = 9
BILATERAL_SIGMA_COLOR: float = 0.1
#: Photo: smoothing of the structure tensor for the edge tangent flow, px.
ETF_SIGMA: float = 3.0

#: Photo subject (subject.py): GrabCut runs on a copy whose longer side is this, px
#: (0.1-0.3 s). A working pixel is 2 px of a 512 px photo, so a strip of
#: background 4 px wide (between an animal's legs) survives; at 192 px it
#: closed up (gorilla of the evaluation set: mask IoU 0.85 at 192, 0.94 at 256).
SUBJECT_WORK_SIDE: int = 256
#: ... for this many iterations (OpenCV's default is 5). The fourth and fifth moved the outline of
#: the 18 photo inputs (both families, data/, skimage's astronaut, coffee, rocket, cat) by at most
#: 2 px but on the honeybee and the astronaut (4 px), with make quality's photo and photo2 means
#: within 0.001 (sil6 0.974 -> 0.973, 0.954 -> 0.953; r10 0.901, 0.781 -> 0.780), and cost 12-56 ms
#: each per cut. Two moved the giraffe's shadow decision and the gorilla's outline by 26 px.
SUBJECT_GRABCUT_ITERATIONS: int = 3
#: ... and this many from depth of field's seeds (focus_seeds), whose start is further from the
#: cut: at 3 the close-up of tests/test_subject.py lost part of its outline (mask IoU against the
#: truth 0.989 -> 0.979, outline kept 0.925 -> 0.867; at 4: 0.989, 0.922).
FOCUS_GRABCUT_ITERATIONS: int = 5
#: Automatic subject: the strip of this fraction of each side along the frame is
#: background when GrabCut starts (the object is away from the image's edges).
SUBJECT_FRAME_INSET: float = 0.05
#: ... but an object found that comes within this many strip widths of the strip (it
#: runs into it: a disc almost filling the picture, a portrait's shoulders) has the
#: strip near it reopened as probable background, for the colour models to decide
#: (subject._reach_frame). Two: an object cut back a strip width short of the strip
#: (by a background model that learnt its colours there) reopens the strip's whole
#: depth beside it. Measured: skimage's retina (a disc 2 px from the frame) mask IoU
#: 0.83 -> 0.99; at three the astronaut's arm also let in the red stripes of the flag
#: beside it (27 % of the frame touched: that candidate is refused, as before).
SUBJECT_FRAME_REACH: float = 2.0
#: ... in at most this many rounds of one GrabCut iteration (about 50 ms of CPU
#: each at the working size), each reopening the strip near the object as it has
#: grown (a part of the object that the first cut's background model ate comes
#: back only once the strip beyond it is open too). Measured on skimage's retina:
#: one round left a flat side at its foot (1049 px of the mask's 200k moved);
#: three moved nothing more than two (astronaut 679 px, camera 5, retina 0).
SUBJECT_FRAME_ROUNDS: int = 2
#: The full-size refinement relabels a band this wide around the first cut, px of
#: the working copy (a working pixel is 2-3 px of a 512 px photo).
SUBJECT_REFINE_BAND: int = 2
#: The subject mask is smoothed by a Gaussian of this sigma and thresholded at
#: one half: no pixel staircase, nothing thinner than about 2 sigma, px.
SUBJECT_SMOOTH_SIGMA: float = 2.0
#: Holes of a subject mask smaller than this fraction of its area are GrabCut's
#: specks and are filled; larger ones (a handle's loop) are the object's.
SUBJECT_MAX_HOLE: float = 0.01
#: Automatic subject: a candidate smaller than this fraction of the image is
#: a detail (an eye, a highlight), not the photo's subject ...
SUBJECT_MIN_AREA: float = 0.04
#: ... one larger than this is the scene itself ...
SUBJECT_MAX_AREA: float = 0.85
#: ... and one touching more than this fraction of the image frame runs off
#: the picture: the whole image is kept then.
SUBJECT_MAX_FRAME: float = 0.25
#: Automatic subject: the candidate's outline must be an edge: the median colour
#: step across it (CIELAB, between points SUBJECT_CONTRAST_STEP px inside and
#: outside) at least this many times the median step along it (the texture's).
#: Measured: the evaluation set's photo-likes 3.8 (gorilla, low contrast by
#: design) to 36; GrabCut's cut through a close-up cat's fur 2.0, through
#: scikit-image's rocket scene 1.7.
SUBJECT_MIN_CONTRAST: float = 2.8
#: ... the distance of those points from the outline, px.
SUBJECT_CONTRAST_STEP: float = 4.0
#: Automatic subject, texture (subject_cues.texture_colour_image): GrabCut also cuts
#: on CIELAB plus the texture, this many L* units per decade of the local
#: fine-detail energy: a smooth surface and grass or gravel differ by about a
#: decade, which then weighs as a clear colour edge (about 20 dE) does, so an
#: object of the background's own hue but another texture is told apart ...
SUBJECT_TEXTURE_WEIGHT: float = 20.0
#: ... and the energy floor added before the log, L* units: photo noise and
#: JPEG grain (about 0.3 L* RMS) are no texture, flat surfaces all look alike.
SUBJECT_TEXTURE_FLOOR: float = 0.3
#: ... an automatic subject whose outline is no colour edge is still kept when
#: its texture differs from that around it by at least this many decades of
#: fine-detail energy (subject_cues.texture_step, the median along its outline): a
#: factor of 3. A cut through one texture has the same on both sides (about 0); a
#: flat body on grass-like texture of its own colour gives about 0.8
#: (tests/test_subject.py); skimage's rocket, a cut through smooth sky between
#: textured towers, 0.21 at 512 px (0.29 at its 640 px).
SUBJECT_MIN_TEXTURE_STEP: float = 0.5
#: Scenes (subject.dominant_part): a neck is thinner than a disc of this many
#: times the square root of the candidate's area in radius (0.08: about 17 px
#: for a 220x220 px object; a trunk or a strip of sky between a building and its
#: trees is thinner, the body of an object wider) ...
SUBJECT_NECK: float = 0.08
#: ... and a part cut off by it counts if it holds this fraction of the area
#: (smaller pieces are a tail or a leg, left to the outline).
SUBJECT_MIN_PART: float = 0.15
#: Thin parts (subject_cues.thin_parts): GrabCut at the working size and the mask's
#: smoothing drop a part of the object a few px wide (a tail, a tripod's legs). A
#: part is thin if a median filter over a square window of this fraction of the
#: longer side takes it away (it covers under half the window; about 0.06: 31 px of a
#: 512 px photo removes parts up to about 12 px wide, which GrabCut at 256 px drops),
#: and differs from that median by SUBJECT_MIN_CONTRAST times the local level of such
#: differences (the texture's, the median over a window twice as wide) ...
SUBJECT_THIN_WINDOW: float = 0.06
#: ... it is a part of the object if it leaves the mask (comes within 3 px of it over
#: at most this fraction of its own length: a strip along the outline is a rim or a
#: shadow's edge, not a limb) ...
SUBJECT_THIN_MAX_CONTACT: float = 0.25
#: ... is at least this many times longer than wide (a stroke, not a blob of
#: texture) and its colour differs from the background around it (the median of
#: CIELAB within half a window, other thin parts left out) by SUBJECT_MIN_CONTRAST
#: times that background's own spread (median distance from its median): a strip
#: in clutter (shelves, towers) is no more apart from its surround than the surround
#: is from itself. Measured at 512 px: heldout-photo-critter-c's tail 4.5 (29.8 dE
#: from wood of 6.7 dE spread; 164 px long, 12 wide, 7 px of contact), skimage's
#: camera's tripod 7.3; left out as patterns of the background (subject_cues.thin_parts):
#: photo2-octopus's brick mortar (7.2, but 13184 px of like strokes elsewhere against
#: its 647), critter-b's grass stalk (3.1, 1035 against 432). The motorcycle's shelves
#: and the rocket's towers give no piece that leaves the mask as a stroke: the masks
#: of make quality's photo and photo2 families are unchanged.
SUBJECT_THIN_MIN_ELONGATION: float = 4.0
#: Cast shadows (subject_shadow.cast_shadow): a shadow darkens the background it
#: falls on by a factor and keeps its chromaticity (linear RGB over its sum) and the
#: texture of its log-luminance. Those are compared between the subject candidate
#: and a ring outside it, from this many working px from the outline (the outer
#: radius is also the Gaussian sigma of the local means: a shadow is compared with
#: the background beside it) ...
SHADOW_RING: tuple[float, float] = (1.5, 10.0)
#: ... the object's own features from the candidate this many working px inside
#: its outline ...
SHADOW_CORE: float = 6.0
#: ... chromaticity smoothed by a Gaussian of this sigma, working px (JPEG and
#: sensor noise make a single pixel's chromaticity unreliable) ...
SHADOW_CHROMA_SIGMA: float = 1.0
#: ... a candidate pixel is shadowed background when it is darker than the ring's
#: median and its chromaticity is within this Mahalanobis distance of the ring's
#: (2.5: about 95 % of the background's own spread), grown from the pixels that
#: chromaticity and texture together put nearer the background than the object ...
SHADOW_MAX_CHROMA_DISTANCE: float = 2.5
#: (then it is left out only if the outline section it takes away is no edge and
#: the one left beside it is: SUBJECT_MIN_CONTRAST; a penumbra is soft).
#: Faces (subject.find_faces): a face smaller than this fraction of the
#: shorter side is too small for its eyes and mouth to become arcs of their own ...
FACE_MIN_SIDE: float = 0.08
#: ... the cascade's windows grow by this factor from one scale to the next
#: (the usual Viola-Jones step) ...
FACE_SCALE_STEP: float = 1.1
#: ... and a face is kept if at least this many overlapping windows found it:
#: a face answers at many neighbouring positions and scales, a face-like patch
#: of texture (fur, gravel, a crumpled suit) at a few.
FACE_MIN_NEIGHBOURS: int = 12
#: Inside a face, FDoG lines are kept down to this fraction of the face's side
#: in length (an eye or a brow is about a fifth of the face), instead of the
#: photo's INNER_MIN_LENGTH and PHOTO_MIN_LINE_LENGTH, which would drop them.
FACE_MIN_LINE: float = 0.1
#: Automatic subject, depth of field (subject_cues.focus_seeds): fine detail is the
#: image minus its Gaussian blur of this sigma, px of the working copy ...
FOCUS_DETAIL_SIGMA: float = 1.0
#: ... its energy is averaged over a Gaussian window of this sigma, px of the
#: working copy (about 5 px of a 512 px photo) ...
FOCUS_WINDOW: float = 2.5
#: ... and divided by its 90th percentile over the image. Below this a part is
#: blurred (or flat) ...
FOCUS_BLURRED: float = 0.12
#: ... above this it is in focus; the sharp map is eroded by this many working px
#: (two windows) so that what is left is texture in focus, not one edge between
#: two smooth parts.
FOCUS_SHARP: float = 0.35
FOCUS_SHARP_CORE: int = 5
#: Depth of field is used when at least this fraction of the frame strip is
#: blurred (a background shows there) ...
FOCUS_MIN_BLURRED_FRAME: float = 0.3
#: ... at least this fraction is in focus (the subject runs off the picture
#: there; a subject away from the frame is found from the whole frame, as
#: before: data/photo-flower.png has 6 %, the close-up cat 27 %) ...
FOCUS_MIN_SHARP_FRAME: float = 0.1
#: ... the blurred part of the frame is soft, not flat: the energy of the band
#: between Gaussians of these sigmas (working px), over a window of
#: FOCUS_SOFT_WINDOW, median over the blurred frame, over the fine detail's
#: 90th percentile, at least FOCUS_MIN_SOFT. Measured: the cat's defocused room
#: 1.0-1.3 (crops, flips, scales), textured heads composited on blurred
#: scikit-image photos 0.20-0.69, a studio portrait 0.5; flat skies and backdrops
#: 0.05-0.13 (scikit-image's rocket at night, a synthetic landscape, the dove's
#: backdrop). The margin below is thin (0.13 to 0.20).
FOCUS_SOFT_SIGMAS: tuple[float, float] = (2.0, 8.0)
FOCUS_SOFT_WINDOW: float = 8.0
FOCUS_MIN_SOFT: float = 0.18
#: ... and the sharp cores cover at least this fraction of the image.
FOCUS_MIN_SHARP_AREA: float = 0.02
#: A subject found by depth of field must be sharper inside its outline than
#: outside: median focus this many working px inside over the median as far
#: outside at least FOCUS_MIN_STEP (or its colour step is an edge, as above).
#: The focus map is a window average, so the step is read about three windows
#: (FOCUS_WINDOW) from the outline. Measured: the cat 3.4-3.5 (flipped, scaled),
#: the frame-seeded GrabCut's cut through its fur 1.0, a cut through a synthetic
#: landscape in focus 1.1.
FOCUS_STEP: int = 8
FOCUS_MIN_STEP: float = 2.5
#: Photo outline: parts of the subject's outline within this of the image
#: frame are the picture's edge, not the object's, px.
OUTLINE_FRAME_MARGIN: float = 2.0
#: Photo inner lines are kept this far inside the subject's outline, px (the
#: outline is drawn from the mask; an edge line next to it would double it).
INNER_LINE_MARGIN: int = 4
#: Photo inner lines: before joining, a connected line with fewer pixels than
#: this is a stroke of texture, not a feature (PHOTO_MIN_LINE_LENGTH, the same
#: bound the isolated lines get after thinning), px ...
INNER_MIN_LENGTH: float = 40.0
#: ... and one whose bounding box has a diagonal under this is a tangle (a
#: thinned blob of fur or foam: a 40 px line folded into a 20 px box), px.
INNER_MIN_SPAN: float = 24.0
#: Photo lines: at most this many times (height + width) of line pixels, the
#: subject's outline first, then the longest inner lines (scenes: the longest
#: lines). A logo of at most about 60 arcs: the evaluation set's photo-likes
#: give 15-21 arcs for 1500-2500 px of lines; a 512 px photo gets 3072 px.
PHOTO_LINE_BUDGET: float = 3.0
#: Photo inner lines: an end of a line that stops within this distance of
#: another line is joined to it (a junction), px.
LINE_JOIN_DISTANCE: float = 6.0
#: Photo dark dots (photo_features.dark_dots): eyes and noses, small dark blobs on the subject that
#: a designer always keeps and the length filters above drop (a 5 px eye's outline is 31 px). Their
#: radius runs from DOT_MIN_RADIUS (the smallest closed line the segment graph splits) up to this
#: fraction of the image's longer side (16 px of a 512 px photo): a larger dark disc is a region of
#: the subject, whose outline (100 px and more) the FDoG lines draw as a long line, and a dot is a
#: detail of the whole picture (a logo of at most about 60 arcs).
DOT_MAX_RADIUS_FRACTION: float = 1.0 / 32.0
#: ... the scale-space blob detector's scales per doubling of the radius: three, the usual sampling of a
#: scale space (Lowe's SIFT; Lindeberg), enough that a dot's scale is within 12 % of a sampled one.
DOT_SCALES_PER_OCTAVE: int = 3
#: ... and a dot is at least this much darker than the ring around it, L* (its centre's mean against the
#: ring's median): CIE76 dE 10, colours that read as different at a glance (dE 2.3 is the
#: just-noticeable difference); a fainter dark patch is shading, not a feature.
DOT_MIN_CONTRAST: float = 10.0
#: ... and at least this many times the lightness spread of the ring around it (its 10-90 % range, L*):
#: a dot stands out of an even surround (an eye on a face), a dark gap in texture (between petals, in
#: fur) is no darker than its surround varies. Twice: the dot's contrast then exceeds the surround's
#: variation by as much again, so that its outline is a clean closed curve in any of the surround's
#: light (measured: the evaluation set's eyes and noses 2.5-14, gaps in the cat's fur and the
#: dahlia's petals 0.4-2.0).
DOT_SURROUND_CONTRAST: float = 2.0
#: Photo clear steps (photo.clear_steps): a line of the FDoG without its bias to dark sides is kept
#: inside the subject when the lightness difference between its two sides is at least this many
#: times the sides' own spread along it: an edge between two even regions (a seal's white belly on
#: its grey body), not a crease in texture. Twice, as for a dot (DOT_SURROUND_CONTRAST).
STEP_SIDE_CONTRAST: float = DOT_SURROUND_CONTRAST
#: Photo enclosed dots (photo_features.enclosed_dots): a pupil is a dark dot inside a lighter closed
#: loop of the lightness lines (an iris, an eye's opening). A loop of equivalent radius up to this
#: fraction of the image's longer side (and no wider than that diameter) is looked in: four times
#: a dot's largest radius (DOT_MAX_RADIUS_FRACTION), as a pupil is at least about a quarter of its
#: iris across (a human pupil 2-8 mm in a 12 mm iris; a cat's slit is as long as its iris).
EYE_MAX_RADIUS_FRACTION: float = 4.0 * DOT_MAX_RADIUS_FRACTION
#: ... the dot, the lines inside the loop and what they enclose, is at most this share of the loop's
#: convex hull: the iris is the larger part of an eye, so that the loop's median is the iris's
#: lightness (a human iris fills 30-50 % of the eye's opening, a pupil less of its iris) ...
EYE_MAX_PUPIL_SHARE: float = 0.5
#: ... and it is enclosed: at least this share of the pixels just around it are the loop's inside
#: (the rest: lines of the loop it touches). A third of its rim may touch the loop (a cat's slit
#: pupil reaching its eyelid); a bay of a concave loop (the hull's side) is enclosed about half
#: (measured: the cat's pupils 1.0 and 0.93, bays and lines into a loop 0.5).
EYE_ENCLOSED_SHARE: float = 2.0 / 3.0
#: ... and its centre lies within this share of the loop's radius of the loop's centre (in the
#: loop's own ellipse): a pupil is at its iris's centre, which an eyelid cutting the loop shifts
#: (a cat's half-covered iris: 0.4); a crease or a mark beside a loop's rim is off it (0.55-0.9).
EYE_MAX_PUPIL_OFFSET: float = 0.5

# --- Segment graph ----------------------------------------------------------------
#: Default Ramer-Douglas-Peucker tolerance of the over-segmentation, px (Sec. 4).
RDP_TOLERANCE: float = 2.0
#: Default: segments (whole chains between nodes) shorter than this are dropped
#: when they hang free at one end, px.
MIN_SEGMENT_LENGTH: float = 6.0
#: Two junctions joined by a chain shorter than this are one junction, px (a
#: thick "X" thins to two "Y"s and a short bridge).
JUNCTION_MERGE_DISTANCE: float = 6.0
#: Tangent joins (beyond the paper): the feature line runs on smoothly through a node of
#: valence 2 when the two segments' end tangents turn by less than this, rad. Ten degrees:
#: the tangent of a 1-px raster line is known to about +-4 degrees (SMOOTH_TANGENT_LENGTH),
#: so two such estimates differ by up to ~8 degrees on a smooth line, while the corners a
#: designer draws turn by 20 degrees or more. There the constrained fit makes
#: the two circles touch (TANGENCY), and ``make quality`` counts the join.
SMOOTH_JOIN_ANGLE: float = math.radians(10.0)
#: A segment's end tangent is that of the circle fitted to its pixels within this
#: arc length of the node, px. Longer than "a few px" on purpose: a line through the
#: last 6 px of a 1-px skeleton is off by up to 15 degrees (its staircase steps are
#: 0.5 px), a circle over 30 px by about 4 (measured on rasterized circles of radius
#: 15-150 px and polygons), and a circle, unlike a line, is not biased by the curvature.
SMOOTH_TANGENT_LENGTH: float = 30.0
#: ``make quality``: a join on smooth input is tangent when the logo's two arcs kink
#: there by less than this, rad (the target: >= 90 % of the joins); two
#: degrees is below what the eye sees at a stroke's join.
TANGENT_JOIN_ANGLE: float = math.radians(2.0)
#: A tangent join's junction slides along the input's line (img2logo.fit.tangency), the
#: two groups' pixels split anew where it is: each keeps at least this many pixels,
#: the fewest a circle is fitted to (three points fix a circle); a junction sliding
#: farther would swallow the group, and the join is released instead.
SLIDE_MIN_PIXELS: int = 3
#: A tangent join whose circles cannot touch on their rungs tries at most this many
#: choices of one rung up or down for the two circles (img2logo.fit.tangency), those
#: that bring the circles nearest to touching first: each costs a constrained fit,
#: and the tangent pass must stay within a time budget of 1.2x the pipeline.
RUNG_CHOICES: int = 2
#: The joint refit of a level's tangent joins (img2logo.fit.tangency._all_at_once) tries at most this
#: many times, releasing one join after each failure: every try solves the whole drawing at once.
ALL_AT_ONCE_TRIES: int = 2
#: The result's level (img2logo.fit.tangency.tangent_level): a smooth join left kinked
#: weighs this many arcs, and the level kept, the merge loop's last or one before it,
#: has the fewest arcs plus weighted kinks after its tangent refit. A kink is a defect
#: the eye sees, while an arc added where the joins are tangent flows into its
#: neighbours: two arcs for a kink. Measured on the clip arts and drawings (``make
#: quality``): 1 gives 72 % of the joins tangent and 42.1 clip-art arcs, 2 gives
#: 78 % and 42.4, 3 gives 83 % and 43.3 with two more near-miss gaps (held-out clip arts).
KINK_WEIGHT: int = 2
#: A smooth join that no refit from its circles makes tangent is fitted as one unit, a tangent
#: biarc over its two groups' joined pixels (img2logo.fit.tangency._biarc): its junction is tried
#: every this many pixels of the chain (every pixel around the best), every this many pixels
#: measured ...
BIARC_STEP: int = 6
#: ... its common tangent there up to this far from the chain's direction, rad (the kinks
#: left on smooth input are 3-25 degrees, measured) ...
BIARC_TURN: float = math.radians(30.0)
#: ... in this many steps either way (4 degrees; the grid is searched again four times finer
#: around its best) ...
BIARC_TURN_STEPS: int = 8
#: ... and the refit starts from the best this many of the rung choices (each a fit).
BIARC_STARTS: int = 2

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
#: An SVG arc command whose |sweep| exceeds this, rad, is written as two commands (a full
#: circle always is): near a full turn its two end points are so close that a renderer
#: cannot place the centre reliably. Arcs and face outlines (``svg_path.py``) both use it.
SVG_NEAR_FULL_SWEEP: float = 2.0 * math.pi - 1e-3
#: Default stroke width of drawn arcs, as a fraction of the longer image side ...
STROKE_WIDTH_FRACTION: float = 1.0 / 128.0
#: ... but never thinner than this, px.
MIN_STROKE_WIDTH: float = 1.0
#: Resolution of PNG figures, dots per inch. It only converts px to matplotlib
#: points: a PNG is always exactly width x height px of the input.
PNG_DPI: float = 100.0
#: Largest side of a PNG written with ``scale`` (``--png-scale``), px: 16384 x 16384 RGBA
#: is 1 GiB in memory while it is drawn; larger is a slip of the keyboard, or a job for the PDF.
MAX_PNG_SIDE: int = 16384
#: Largest side of a PNG drawn over the faded input (``background="input"``), px: matplotlib
#: resamples the image under the logo in floating point, about 85 bytes per output pixel
#: (measured: 3.1 GB peak for 6000 x 6000 px, 0.2 GB without the image), so 4096 x 4096 px
#: is about 1.4 GB; a white or transparent background goes to ``MAX_PNG_SIDE``.
MAX_PNG_IMAGE_SIDE: int = 4096
#: How far a background image is faded towards white under a drawing
#: (0 = as it is, 1 = white).
IMAGE_FADE: float = 0.6
#: Spacing of the sample points when an arc is drawn as a polyline in a raster, px.
ARC_SAMPLE_STEP: float = 0.5
#: The SVG's "Golden circles" layer is clipped to the image plus this fraction of its
#: longer side on every side: enough of a circle that runs out of the image to read its
#: curvature, while a radius of the ladder (up to ~14 x the image) cannot fill the artboard.
CONSTRUCTION_MARGIN: float = 0.5

# --- Golden ladder and circle fitting (golden_ladder.py, circle_fitting.py, constrained_fit.py) --------
#: fit_circle: default cap on a fitted radius, as a multiple of the points' extent
#: (the distance between their two extreme points along the principal axis). An
#: arc of radius 20 x its chord c has a sagitta of c / 160: it is nearly straight.
MAX_RADIUS_FACTOR: float = 20.0
#: fit_circle: most Levenberg-Marquardt iterations refining the algebraic (Hyper) fit.
CIRCLE_REFINE_MAX_ITER: int = 30
#: fit_constrained: default tolerance on the connectivity constraints (Eqn. 13),
#: and on the size of the last SQP step, px.
CONSTRAINED_FIT_TOL: float = 1e-6
#: FitState.solve with a bound: a fit is cut off once a lower bound of E^s exceeds the
#: bound by more than this fraction of it (at least 1 px times it): the lower bound and
#: E^s sum the same terms in another order, whose rounding (~1e-15) must not reject a
#: fit that E^s itself keeps.
CUT_MARGIN: float = 1e-9
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
#: fit_constrained: the largest KKT system the compiled global solve takes
#: (kernels_sqp.sqp_banded assembles it in a dense size x size scratch matrix
#: before reading its band: 2500 is about 50 MB; the examples' largest is about
#: 700, the cactus's initial fit); larger ones run the Python reference, whose
#: memory grows with the band only.
KKT_COMPILED_MAX: int = 2500

# --- Progressive optimization (progressive.py) -------------------------------------
#: Default tolerance T on the similarity error E^s (Eqn. 1), px; the paper's default.
TOLERANCE: float = 5.0
#: Rings of the wider window a merge candidate is refitted in when its local window (two rings) fails: the
#: new circle's junctions free, then those of the circles through them, ... (Sec. 5.4). Bounded, so that a
#: candidate's refit costs the same on a large drawing as on a small one; the whole graph solved instead
#: (the paper's fallback) cost 96 % of the time of a 512 px clip art with 544 arcs at A^0.
MERGE_FALLBACK_RINGS: int = 6
#: Default time budget of the progressive optimization, s of CPU time of the process running it (on an
#: idle machine about the wall time): past it the merge loop stops at its last level (``Options.time_budget``).
#: make bench's growth table: the busiest image of benchmarks/data/ (openclipart/clipart-gallo, 299 arcs at A^0)
#: takes about 6 s of CPU in all, the others it lists at most 1.5 s.
TIME_BUDGET: float = 10.0
#: Line-segment simplification (Sec. 5.4): neighbours are merged before the loop when
#: one circle fits them with a mean absolute error below this, px (the paper's 1.0).
SIMPLIFICATION_ERROR: float = 1.0

#: Photos: a merge whose new arc lies farther than this many T (discrete Fréchet
#: distance) from its pixels is rejected: T bounds every arc, not only their
#: mean E^s. A photo's logo has few, long arcs, and without a bound the last
#: merges cut across a backpack's handle and side. Measured on the six
#: photo-likes, sil6 least / mean: 0.76 / 0.90 unbounded, 0.79 / 0.91 at 2 T,
#: 0.85 / 0.93 at 1 T (15-22 arcs).
PHOTO_MAX_ARC_FACTOR: float = 1.0
#: A segment of a clip art is on the object's silhouette when most of its points lie within this
#: many px of the background (its line runs on the object's pixels next to the paper), px.
OUTLINE_DISTANCE: float = 2.0
#: A merge candidate whose new circle (radius fixed on the ladder) cannot pass within
#: ``max_arc_distance`` + this of all its pixels, wherever its centre, is rejected
#: before its fit (img2logo.fit.merging, kernels_sqp.far_circle_kernel): the fit's arc,
#: coupled to every pixel by the Fréchet distance, would be farther. The margin
#: covers rounding: the arc's samples lie on their circle to ~1e-10 px (r <= 1e6 px),
#: the proof's distances to ~1e-12 px; 1e-6 px is far above both.
FAR_ARC_MARGIN: float = 1e-6
#: Most boxes of centres the proof above tries before giving up (then the fit decides):
#: on the flower's 117 merged groups at most ~800 us each, ~4 ms in all.
FAR_ARC_BUDGET: int = 20000

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
#: Ink parts lost (``quality.lost_ink_parts``): a pixel of the input darker than this
#: gray (0..1, mid-grey) is ink: the black or coloured strokes, outlines and dots of a
#: drawing or a clip art, not its light fills nor the paper.
INK_PART_GRAY: float = 0.5
#: ... an 8-connected part of ink of at least this many px is content (an eye of a
#: 6 px dot has 28 px); smaller ones are specks of anti-aliasing or JPEG ringing ...
INK_PART_MIN_AREA: int = 30
#: ... and it is lost when no logo point is within this of any of its pixels, px:
#: the finest recall distance (r3).
INK_PART_DISTANCE: float = 3.0
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

# --- Symmetric logos (img2logo.fit.symmetry) --------------------------------------------
#: Mirror-axis detection: a feature-line pixel is matched when its mirror image lies
#: within this distance of a feature-line pixel, px. Two 1-px lines drawn from the two
#: halves of a symmetric shape sit up to 1 px apart after thinning, and the reflection
#: of a pixel centre about an axis between pixels lands up to 0.5 px off a centre.
SYMMETRY_MATCH_DISTANCE: float = 2.0
#: Mirror-axis detection: the feature-line pixels sampled (evenly along the map) to
#: score candidate axes; enough for the score to within about 1 % and fast.
SYMMETRY_SAMPLE_POINTS: int = 2000
#: Mirror-axis detection: angular step of the coarse search over axis directions, radians (2 degrees).
SYMMETRY_ANGLE_STEP: float = math.radians(2.0)
#: Mirror-axis detection: the coarse search tries axes this far on either side of the
#: line pixels' centroid (a symmetric point set has its centroid on its axis), px.
SYMMETRY_OFFSET_RANGE: float = 16.0
#: Mirror-axis detection: offset step of the coarse search, px.
SYMMETRY_OFFSET_STEP: float = 1.0
#: ``symmetry="auto"`` keeps the best axis when its score (the fraction of feature-line
#: pixels whose mirror image is a feature line within SYMMETRY_MATCH_DISTANCE) is at
#: least this. Chosen from measured scores (README, notebook 13): symmetric
#: fronts (faces, balloon, umbrella, bee) and their mirrored, rotated and cropped
#: variants 0.74-0.98; side views (fish, birds, bike, kayak) and other asymmetric
#: drawings at most 0.55; the threshold sits between.
SYMMETRY_THRESHOLD: float = 0.72
#: Symmetric segment graph: points within this distance of the axis are put on it, px
#: (a line along the axis, a junction on it, the end of a line that stops at it).
SYMMETRY_SNAP_DISTANCE: float = 1.0
#: Symmetric segment graph: a line that meets the axis within this angle of square to it
#: continues smoothly into its mirror image, so its circle is centred on the axis;
#: steeper, the line and its mirror image meet at a corner there (a chin, a heart's top), radians.
SYMMETRY_SMOOTH_ANGLE: float = math.radians(30.0)
#: Symmetric segment graph: the direction of a line where it meets the axis is taken
#: over this length of it, px (the last pixels are bent by thinning).
SYMMETRY_TANGENT_LENGTH: float = 6.0
#: Symmetric output: mirror-image circles are matched to within this distance, px.
SYMMETRY_PAIR_TOLERANCE: float = 1e-6
#: Symmetric runs: the constrained fit gives up when the violation has not halved over
#: this many steps (CONSTRAINED_FIT_STALL elsewhere). A half graph's joint fit can
#: climb out of a plateau more slowly: the clip-art cat's half stalled at 6e-4 px
#: after 11 steps (and 3 junctions were released) but converged in 28.
SYMMETRY_FIT_STALL: int = 20
#: ``symmetry="auto"``: an axis found within this many degrees of upright (or level) is
#: made exactly upright (level) when that costs at most SYMMETRY_SNAP_SCORE_LOSS of
#: score: a designer's axis is upright, and the search's least squares leave it a few
#: thousandths of a degree off (the clip-art cat: 89.994 deg), degrees.
SYMMETRY_SNAP_ANGLE: float = 1.0
#: See SYMMETRY_SNAP_ANGLE: the score an exactly upright axis may lose, as a fraction.
SYMMETRY_SNAP_SCORE_LOSS: float = 0.01

#: Photo colour lines: the colour-opponent FDoG runs on a copy this many times
#: smaller (each side), on its own flow: a photo's chroma is blurrier than its
#: lightness (JPEG keeps it at half resolution, 4:2:0; the eye resolves it at
#: about half the lightness's acuity), a step's DoG response does not depend on
#: the pixel size, and the pass costs a quarter (0.03 s on a 512 px photo).
COLOUR_LINE_SUBSAMPLE: float = 2.0
#: Photo colour lines (photo.photo_lines, photo.new_colour_lines): a line of the colour-opponent FDoG is
#: kept only this far from both sides of every lightness edge, px: 3 x the
#: colour FDoG's surround sigma (1.6 FDOG_SIGMA_C on a copy COLOUR_LINE_SUBSAMPLE
#: times smaller), the reach of its DoG across an edge. Within it, a colour line
#: is the same edge as the lightness line (a colour object's outline lies beside
#: its lightness line: drawn twice, a duck of 16 arcs had 34); beyond it, the
#: edge has no lightness step of its own.
COLOUR_LINE_GATE: float = 3.0 * 1.6 * FDOG_SIGMA_C * COLOUR_LINE_SUBSAMPLE
#: Photo colour lines (photo.new_colour_lines): the two sides of a drawn lightness line (its
#: dark line and its bright lobe, where the colour line of the same edge lies) are the lightness
#: edge within this of it, px: 3 x the lightness FDoG's surround sigma (1.6 FDOG_SIGMA_C), the
#: reach of its DoG across the edge.
EDGE_SIDE_REACH: float = 3.0 * 1.6 * FDOG_SIGMA_C
