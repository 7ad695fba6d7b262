"""Logos of clip art nobody tuned for: a random draw from Debian's ``openclipart-svg``.

``python benchmarks/heldout_openclipart.py [--count 30] [--seed 7] [--out build/heldout-openclipart]``
draws ``count`` SVGs of the package (``/usr/share/openclipart/svg``, public domain; ``apt install
openclipart-svg librsvg2-bin``) from the categories a designer brings (animals, food, plants,
transportation, people, recreation, containers, tools), with at least four fill colours and without
gradients, patterns, filters, masks, embedded images, text or transparency (flat clip art, as the
``openclipart`` family of ``make quality``), none of that family's sources
(``benchmarks/data/openclipart/manifest.json``). Each is rendered by ``rsvg-convert`` at
``SIDE`` px on a white ``MARGIN`` px frame and abstracted with the default options. One row per
image: the kind detected, arcs, free ends, sil6 against a silhouette made without ground truth (the
non-white pixels, closed by a 7 px square and their holes filled: a scene's separate pieces and
its text count), and the command's seconds (CPU of ``abstract``); then the medians and extremes,
and ``contact.png`` (input | logo) in the output folder. A benchmark, not a test: it reads outside
the repository and skips with a message when the package or ``rsvg-convert`` is missing.
"""

from __future__ import annotations

import argparse
import io
import json
import random
import re
import shutil
import statistics
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
#: Where Debian's openclipart-svg puts its drawings.
PACKAGE = Path("/usr/share/openclipart/svg")
#: The categories drawn from: what a designer brings (objects, animals, people), not symbols or maps.
CATEGORIES = ("animals", "food", "plants", "transportation", "people", "recreation", "containers", "tools")
#: Not flat clip art, or not drawable as such: gradients, patterns, filters, masks, images, text, transparency.
NOT_FLAT = re.compile(r"Gradient|<pattern|<filter|<mask|<image|<text|opacity\s*[:=]\s*\"?0?\.\d|clip-path", re.I)
#: The rendered drawing's longer side and the white frame round it, px (a 512 px image).
SIDE, MARGIN = 448, 32
#: The contact sheet's row height, px (input | logo).
ROW = 240


def candidates(package: Path = PACKAGE) -> list[Path]:
    """The package's flat clip arts of :data:`CATEGORIES` with at least four fill colours, sorted, one per name."""
    manifest = json.loads((ROOT / "benchmarks" / "data" / "openclipart" / "manifest.json").read_text("utf-8"))
    used = {m["source"].split(":", 1)[1] for m in manifest if ":" in m.get("source", "")}
    out, stems = [], set()
    for path in sorted(package.rglob("*.svg")):
        rel = path.relative_to(package).as_posix()
        if rel in used or rel.split("/")[0] not in CATEGORIES or path.stem in stems:
            continue  # (a drawing filed under two categories is drawn once)
        text = path.read_text(errors="ignore")
        if len(text) > 400_000 or NOT_FLAT.search(text):
            continue
        if len(set(re.findall(r"fill\s*[:=]\s*\"?(#[0-9a-fA-F]{6})", text))) >= 4:
            out.append(path)
            stems.add(path.stem)
    return out


def render(svg: Path, out: Path) -> Path | None:
    """``svg`` as a PNG of ``SIDE`` px on a ``MARGIN`` px white frame at ``out``; None when it cannot be drawn."""
    from PIL import Image

    try:
        png = subprocess.run(
            ["rsvg-convert", "-w", str(SIDE), "-a", "-b", "white", str(svg)],
            capture_output=True,
            timeout=60,
            check=True,
        ).stdout
        image = Image.open(io.BytesIO(png)).convert("RGB")
    except (subprocess.SubprocessError, OSError):
        return None
    scale = SIDE / max(image.size)
    if abs(scale - 1.0) > 0.01:
        image = image.resize((max(1, round(image.width * scale)), max(1, round(image.height * scale))))
    frame = Image.new("RGB", (image.width + 2 * MARGIN, image.height + 2 * MARGIN), "white")
    frame.paste(image, (MARGIN, MARGIN))
    frame.save(out)
    return out


def silhouette(rgb: np.ndarray) -> np.ndarray:
    """The non-white pixels of ``rgb`` (H, W, 3) uint8, closed by a 7 px square, holes filled: (H, W) bool."""
    import cv2
    from scipy import ndimage

    drawn = (rgb < 245).any(axis=-1).astype(np.uint8)
    closed = cv2.morphologyEx(drawn, cv2.MORPH_CLOSE, np.ones((7, 7), np.uint8)) > 0
    return ndimage.binary_fill_holes(closed)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--count", type=int, default=30, help="how many drawings (default 30)")
    parser.add_argument("--seed", type=int, default=7, help="the draw's random seed (default 7)")
    parser.add_argument("--out", type=Path, default=ROOT / "build" / "heldout-openclipart", help="output folder")
    args = parser.parse_args(argv)
    if not PACKAGE.is_dir() or shutil.which("rsvg-convert") is None:
        print(f"skipped: needs {PACKAGE} (apt install openclipart-svg) and rsvg-convert (librsvg2-bin)")
        return 0

    import cv2

    from img2logo import abstract, quality
    from img2logo.export.writers import png_bytes

    pool = candidates()
    draw = random.Random(args.seed).sample(pool, min(args.count, len(pool)))
    args.out.mkdir(parents=True, exist_ok=True)
    print(f"{len(draw)} of {len(pool)} flat clip arts of the package (seed {args.seed})")
    print("name kind arcs free_ends sil6 seconds")
    rows, sheet = [], []
    for svg in draw:
        png = render(svg, args.out / f"{svg.stem[:40]}.png")
        if png is None:
            print(f"{svg.stem[:40]} not drawn by rsvg-convert")
            continue
        start = time.process_time()
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            result = abstract(png, progress=False)
        seconds = time.process_time() - start
        rgb = np.ascontiguousarray(cv2.imread(str(png), cv2.IMREAD_COLOR)[:, :, ::-1])
        points = quality.logo_points(result.final)
        row = {
            "name": png.stem,
            "kind": result.lines.kind,
            "arcs": len(result.final.arcs),
            "free_ends": len(quality.free_ends(result.final)),
            "sil6": float(quality.silhouette_recall(points, silhouette(rgb))),
            "seconds": seconds,
        }
        rows.append(row)
        print(" ".join(f"{v:.3f}" if isinstance(v, float) else str(v) for v in row.values()), flush=True)
        logo = cv2.imdecode(np.frombuffer(png_bytes(result.final, background="white"), np.uint8), cv2.IMREAD_COLOR)
        pair = np.hstack([rgb[:, :, ::-1], cv2.resize(logo, (rgb.shape[1], rgb.shape[0]))])
        sheet.append(cv2.resize(pair, (round(pair.shape[1] * ROW / pair.shape[0]), ROW)))
    if not rows:
        return 1
    arcs = [r["arcs"] for r in rows]
    free = [r["free_ends"] for r in rows]
    sil = [r["sil6"] for r in rows]
    print(
        f"arcs median {statistics.median(arcs):g}, most {max(arcs)}; free ends median "
        f"{statistics.median(free):g}, most {max(free)}; sil6 mean {statistics.mean(sil):.3f}, least "
        f"{min(sil):.3f}; seconds most {max(r['seconds'] for r in rows):.1f}"
    )
    width = max(s.shape[1] for s in sheet)
    cv2.imwrite(
        str(args.out / "contact.png"),
        np.vstack([np.pad(s, ((0, 0), (0, width - s.shape[1]), (0, 0)), constant_values=255) for s in sheet]),
    )
    print(f"wrote {args.out / 'contact.png'}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
