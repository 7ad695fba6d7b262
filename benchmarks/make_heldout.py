"""Build a held-out family of clip arts and line drawings, ``benchmarks/data/heldout/`` (seeded).

The evaluation set's clip arts and drawings are icons of two icon sets; the project is also
measured on other images of the same kinds. This family is made differently, from OpenCV's
drawing primitives, so that a rule tuned to the evaluation set shows here: seeded random
creatures (a body, a head, legs, a tail, spots, a ring, eyes as small filled dots) drawn

* as **clip arts**: flat colour fills with anti-aliased edges (drawn at 4x, reduced by area
  averaging, as a renderer does), and JPEG variants of some at quality 60-85;
* as **line drawings**: black strokes 3-5 px wide with filled-dot eyes, and JPEG variants;
* as **thick drawings**: the same strokes 12-18 px wide (kind ``drawing``, variant ``thick``).

Ground truth, as in ``benchmarks/data/README.md``: for a clip art the boundaries between
the fills' labels (drawn at 4x without anti-aliasing, sampled at the pixel centres, thinned
to 1 px), the background included; for a drawing the skeleton of its dark strokes (gray <
128) of the clean render; for a thick drawing that of the same drawing with 3 px strokes
(its centre lines). A JPEG variant has the truth of its clean render.

Run ``.venv/bin/python benchmarks/make_heldout.py``; it rewrites the folder byte for byte.
"""

from __future__ import annotations

import json
from pathlib import Path

import cv2
import numpy as np
from PIL import Image
from skimage.morphology import skeletonize
from skimage.segmentation import find_boundaries

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "benchmarks" / "data" / "heldout"
SIZE = 512
#: Drawn at this many times the image size, then reduced by area averaging (anti-aliasing).
SCALE = 4

#: (name, kind, variant, seed, options): jpeg quality, stroke width (drawings, px).
CASES = [
    ("clipart-critter-a", "clipart", None, 301, {}),
    ("clipart-critter-b", "clipart", None, 302, {}),
    ("clipart-critter-c", "clipart", None, 303, {}),
    ("clipart-critter-d", "clipart", None, 304, {}),
    ("clipart-critter-a-jpeg", "clipart", "jpeg", 301, {"jpeg_quality": 70}),
    ("clipart-critter-c-jpeg", "clipart", "jpeg", 303, {"jpeg_quality": 60}),
    ("clipart-critter-d-jpeg", "clipart", "jpeg", 304, {"jpeg_quality": 85}),
    ("drawing-critter-a", "drawing", None, 401, {"stroke": 3}),
    ("drawing-critter-b", "drawing", None, 402, {"stroke": 4}),
    ("drawing-critter-c", "drawing", None, 403, {"stroke": 5}),
    ("drawing-critter-a-jpeg", "drawing", "jpeg", 401, {"stroke": 3, "jpeg_quality": 65}),
    ("drawing-critter-b-jpeg", "drawing", "jpeg", 402, {"stroke": 4, "jpeg_quality": 80}),
    ("drawing-critter-d-thick", "drawing", "thick", 404, {"stroke": 13}),
    ("drawing-critter-e-thick", "drawing", "thick", 405, {"stroke": 17}),
]

#: Fill colours of the clip arts (sRGB): body, head, legs, spots, ring; a dark for the eyes.
PALETTES = [
    [(240, 170, 60), (250, 200, 90), (200, 120, 50), (170, 95, 40), (90, 160, 210)],
    [(120, 180, 110), (150, 205, 135), (70, 130, 80), (60, 100, 60), (230, 120, 140)],
    [(150, 160, 220), (180, 190, 235), (100, 110, 170), (80, 80, 140), (250, 210, 80)],
    [(225, 225, 230), (240, 240, 242), (170, 170, 180), (140, 140, 150), (240, 150, 60)],
]
EYE = (25, 25, 30)


def creature(rng: np.random.Generator) -> dict:
    """Random shapes of one creature, in image px (floats): a dict of primitives."""
    cx, cy = rng.uniform(230, 280), rng.uniform(260, 300)
    bw, bh = rng.uniform(110, 150), rng.uniform(65, 90)
    hr = rng.uniform(45, 60)
    hx, hy = cx - bw * rng.uniform(0.75, 0.95), cy - bh - hr * rng.uniform(0.2, 0.5)
    legs = []
    for t in np.linspace(-0.6, 0.6, 4 if rng.random() < 0.5 else 2):
        x = cx + t * bw
        legs.append(((x, cy + bh * 0.7), (x + rng.uniform(-15, 15), cy + bh + rng.uniform(50, 80))))
    tail = ((cx + bw * 0.95, cy - bh * 0.2), rng.uniform(35, 55), rng.uniform(180, 250))
    spots = []
    for _ in range(int(rng.integers(2, 5))):
        a, rr = rng.uniform(0, 2 * np.pi), rng.uniform(0.15, 0.6)
        spots.append((cx + rr * bw * np.cos(a), cy + rr * bh * np.sin(a), rng.uniform(7, 16)))
    eyes = [(hx - hr * 0.35, hy - hr * 0.15, rng.uniform(4.5, 7.0))]
    if rng.random() < 0.6:
        eyes.append((hx + hr * 0.3, hy - hr * 0.15, eyes[0][2]))
    ring = (hx + hr * 0.05, hy + hr * 0.45, rng.uniform(6, 9))
    return dict(body=(cx, cy, bw, bh), head=(hx, hy, hr), legs=legs, tail=tail, spots=spots, eyes=eyes, ring=ring)


def _p(*xy: float) -> tuple[int, ...]:
    """Image px to the 4x canvas's integer px (pixel centres: (j + 0.5, i + 0.5))."""
    return tuple(round(v * SCALE) for v in xy)


def draw_clipart(c: dict, palette: list, canvas: np.ndarray, labelled: bool) -> None:
    """The creature as flat fills on ``canvas`` (4x); labels 1.. instead of colours when ``labelled``."""
    line = cv2.LINE_8 if labelled else cv2.LINE_AA
    body, head, legc, spotc, ringc = [(i + 1,) * 3 if labelled else col for i, col in enumerate(palette)]
    eye = (6,) * 3 if labelled else EYE
    cx, cy, bw, bh = c["body"]
    for a, b in c["legs"]:
        cv2.line(canvas, _p(*a), _p(*b), legc, 22 * SCALE, line)
    (tx, ty), tr, tsweep = c["tail"]
    cv2.ellipse(canvas, _p(tx, ty - tr), _p(tr, tr), 0, 90, 90 - tsweep, legc, 9 * SCALE, line)
    cv2.ellipse(canvas, _p(cx, cy), _p(bw, bh), 0, 0, 360, body, -1, line)
    for x, y, r in c["spots"]:
        cv2.circle(canvas, _p(x, y), int(r * SCALE), spotc, -1, line)
    hx, hy, hr = c["head"]
    cv2.circle(canvas, _p(hx, hy), int(hr * SCALE), head, -1, line)
    for x, y, r in c["eyes"]:
        cv2.circle(canvas, _p(x, y), int(r * SCALE), eye, -1, line)
    x, y, r = c["ring"]
    cv2.circle(canvas, _p(x, y), int(r * SCALE), ringc, int(3.5 * SCALE), line)


def draw_lines(c: dict, canvas: np.ndarray, width: float) -> None:
    """The creature as black strokes ``width`` px wide on ``canvas`` (4x), eyes as filled dots."""
    w, ink, aa = round(width * SCALE), (0, 0, 0), cv2.LINE_AA
    cx, cy, bw, bh = c["body"]
    cv2.ellipse(canvas, _p(cx, cy), _p(bw, bh), 0, 0, 360, ink, w, aa)
    hx, hy, hr = c["head"]
    cv2.circle(canvas, _p(hx, hy), int(hr * SCALE), ink, w, aa)
    for a, b in c["legs"]:
        cv2.line(canvas, _p(*a), _p(*b), ink, w, aa)
    (tx, ty), tr, tsweep = c["tail"]
    cv2.ellipse(canvas, _p(tx, ty - tr), _p(tr, tr), 0, 90, 90 - tsweep, ink, w, aa)
    for x, y, r in c["spots"][:2]:
        cv2.circle(canvas, _p(x, y), int(r * SCALE), ink, w, aa)
    for x, y, r in c["eyes"]:
        cv2.circle(canvas, _p(x, y), int(max(r, 0.6 * width) * SCALE), ink, -1, aa)


def reduce(canvas: np.ndarray) -> np.ndarray:
    """The 4x canvas at image size, by area averaging (anti-aliasing): uint8."""
    return cv2.resize(canvas, (SIZE, SIZE), interpolation=cv2.INTER_AREA)


def jpeg(rgb: np.ndarray, quality: int) -> bytes:
    ok, data = cv2.imencode(".jpg", rgb[:, :, ::-1], [cv2.IMWRITE_JPEG_QUALITY, quality])
    assert ok
    return data.tobytes()


def skeleton_truth(rgb: np.ndarray) -> np.ndarray:
    """The skeleton of the dark strokes (gray < 128): (H, W) bool."""
    return skeletonize(cv2.cvtColor(rgb, cv2.COLOR_RGB2GRAY) < 128)


def build(name: str, kind: str, variant: str | None, seed: int, opts: dict) -> tuple[np.ndarray, np.ndarray]:
    """(image RGB uint8 (H, W, 3), truth (H, W) bool) of one case."""
    rng = np.random.default_rng(seed)
    c = creature(rng)
    big = (SIZE * SCALE, SIZE * SCALE, 3)
    if kind == "clipart":
        palette = PALETTES[seed % len(PALETTES)]
        canvas = np.full(big, 255, np.uint8)
        draw_clipart(c, palette, canvas, labelled=False)
        labels = np.zeros(big, np.uint8)
        draw_clipart(c, palette, labels, labelled=True)
        centre = labels[SCALE // 2 :: SCALE, SCALE // 2 :: SCALE, 0]
        return reduce(canvas), skeletonize(find_boundaries(centre, mode="thick"))
    canvas = np.full(big, 255, np.uint8)
    draw_lines(c, canvas, opts["stroke"])
    image = reduce(canvas)
    if variant != "thick":
        return image, skeleton_truth(image)
    thin = np.full(big, 255, np.uint8)
    draw_lines(c, thin, 3)
    return image, skeleton_truth(reduce(thin))


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    manifest = []
    for name, kind, variant, seed, opts in CASES:
        image, truth = build(name, kind, variant, seed, opts)
        entry = dict(name=name, kind=kind, family=f"heldout {kind}", width=SIZE, height=SIZE, gt=f"{name}.gt.png")
        if variant == "jpeg":
            entry["file"] = f"{name}.jpg"
            (OUT / entry["file"]).write_bytes(jpeg(image, opts["jpeg_quality"]))
            entry["jpeg_quality"] = opts["jpeg_quality"]
        else:
            entry["file"] = f"{name}.png"
            Image.fromarray(image).save(OUT / entry["file"], optimize=False)
        Image.fromarray(truth).save(OUT / entry["gt"], optimize=False)
        entry.update(subject="critter", source="generated:benchmarks/make_heldout.py", seed=seed)
        if variant:
            entry["variant"] = variant
        if "stroke" in opts:
            entry["stroke_width"] = opts["stroke"]
        manifest.append(entry)
    (OUT / "manifest.json").write_text(json.dumps(manifest, indent=1) + "\n", encoding="utf-8")
    print(f"wrote {len(manifest)} images to {OUT}")


if __name__ == "__main__":
    main()
