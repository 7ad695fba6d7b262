"""Huge inputs: the command's wall time, CPU time and peak memory on 10000-12000 px images.

``python benchmarks/huge.py`` makes the images (seeded, in a temporary folder, or in ``--dir``
where they are kept and reused) from the repository's 512 px ``data/`` images and runs
``/usr/bin/time -f '%e %U %S %M' python -m img2logo IN -q --svg o.svg --json o.json`` on each,
printing one row per run: wall, user and sys seconds, peak resident memory (GB), the arcs of
the logo. The target: at most 1.5 GB and 15 s for any accepted image.

The images (16-bit RGBA PNGs unless said; the largest accepted input is MAX_IMAGE_PIXELS):

* ``fox-10000.png``, ``fox-12000.png``: ``data/clipart-fox.png`` upscaled bicubic, opaque;
* ``fish-12000.png``: ``data/drawing-fish.png`` upscaled bicubic, opaque;
* ``flower-12000.png``: ``data/photo-flower.png`` stretched to 12000 x 12000 px with seeded
  Gaussian noise (so it compresses badly: about 0.95 GB), alpha a soft disc;
* ``flower-12000.jpg``: the same noisy flower, 8-bit RGB, JPEG quality 90;
* ``flower-12000-paeth.png``: the noisy flower with every row Paeth-filtered (OpenCV's files use
  the Sub filter, the cheapest to undo; other encoders choose per row, Paeth often on photos):
  the slowest PNG to decode;
* the noisy flower in the other formats ``load_image`` accepts (what OpenCV decodes), written by
  OpenCV with its defaults unless said: ``flower-12000.tif`` (16-bit RGBA, LZW with the
  horizontal predictor, a strip a row), ``flower-12000-deflate-tiled.tif`` (16-bit RGBA,
  deflate, 512 px tiles, by Pillow's libtiff), ``flower-12000-packbits.tif`` (8-bit RGB),
  ``flower-12000.webp`` (8-bit RGBA, quality 90), ``flower-12000.bmp`` (8-bit RGBA),
  ``flower-12000.gif`` (a palette), ``flower-12000.jp2`` (JPEG 2000, 8-bit RGB),
  ``flower-12000.ppm`` (16-bit RGB), ``flower-12000.pfm`` (float RGB), ``flower-12000.hdr``
  (Radiance), ``flower-12000.avif`` (8-bit RGB, speed 10), ``flower-12000.ras`` (Sun raster).

``--checkout DIR`` (repeatable) runs each image with each checkout's ``img2logo`` in turn
(``PYTHONPATH=DIR``), alternating run by run, e.g. a ``git archive`` of the base commit
in /tmp and ``.``: on a shared machine the wall time follows the load, so compare CPU
(user + sys) and memory, and alternate. A benchmark, not a test (not part of ``make test``).
"""

from __future__ import annotations

import argparse
import fnmatch
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
DATA = ROOT / "data"
SEED = 20
#: name: (source in data/, side px, kind of image to make)
IMAGES = {
    "fox-10000.png": ("clipart-fox.png", 10000, "plain"),
    "fox-12000.png": ("clipart-fox.png", 12000, "plain"),
    "fish-12000.png": ("drawing-fish.png", 12000, "plain"),
    "flower-12000.png": ("photo-flower.png", 12000, "noisy"),
    "flower-12000.jpg": ("photo-flower.png", 12000, "noisy"),
    "flower-12000-paeth.png": ("photo-flower.png", 12000, "noisy-paeth"),
    "flower-12000.tif": ("photo-flower.png", 12000, "noisy"),
    "flower-12000-deflate-tiled.tif": ("photo-flower.png", 12000, "noisy-deflate-tiled"),
    "flower-12000-packbits.tif": ("photo-flower.png", 12000, "noisy-packbits"),
    "flower-12000.webp": ("photo-flower.png", 12000, "noisy"),
    "flower-12000.bmp": ("photo-flower.png", 12000, "noisy"),
    "flower-12000.gif": ("photo-flower.png", 12000, "noisy"),
    "flower-12000.jp2": ("photo-flower.png", 12000, "noisy"),
    "flower-12000.ppm": ("photo-flower.png", 12000, "noisy"),
    "flower-12000.pfm": ("photo-flower.png", 12000, "noisy"),
    "flower-12000.hdr": ("photo-flower.png", 12000, "noisy"),
    "flower-12000.avif": ("photo-flower.png", 12000, "noisy"),
    "flower-12000.ras": ("photo-flower.png", 12000, "noisy"),
}
#: What each other format is given: (channels, dtype) of the array written (BGR(A), 16-bit: as made).
FORMATS = {
    ".tif": (4, np.uint16),
    ".webp": (4, np.uint8),
    ".bmp": (4, np.uint8),
    ".gif": (3, np.uint8),
    ".jp2": (3, np.uint8),
    ".ppm": (3, np.uint16),
    ".pfm": (3, np.float32),
    ".hdr": (3, np.float32),
    ".avif": (3, np.uint8),
    ".ras": (3, np.uint8),
}
STRIP = 1000  # rows made at a time (bounds the float temporaries)


def make_image(name: str, folder: Path) -> Path:
    """``folder/name`` made as described in the module's docstring (kept if it is already there)."""
    import cv2

    out = folder / name
    if out.exists():
        return out
    source, side, how = IMAGES[name]
    src = cv2.imread(str(DATA / source), cv2.IMREAD_COLOR)  # BGR, 8 bits
    h0, w0 = src.shape[:2]
    size = (side, side) if how.startswith("noisy") else (round(w0 * side / max(h0, w0)), round(h0 * side / max(h0, w0)))
    big = cv2.resize(src, size, interpolation=cv2.INTER_CUBIC)  # uint8, clipped by OpenCV
    jpeg = name.endswith(".jpg")
    h, w = big.shape[:2]
    arr = np.empty((h, w, 3 if jpeg else 4), dtype=np.uint8 if jpeg else np.uint16)
    yy, xx = np.ogrid[:STRIP, :w]
    for r in range(0, h, STRIP):
        block = big[r : r + STRIP].astype(np.float32) * np.float32(257.0)  # 16-bit scale
        if how.startswith("noisy"):
            rng = np.random.default_rng(SEED + r)
            block += rng.normal(0.0, 3.0 * 257.0, block.shape).astype(np.float32)
        block = np.clip(block, 0.0, 65535.0)
        if jpeg:
            arr[r : r + STRIP] = np.rint(block / np.float32(257.0)).astype(np.uint8)
            continue
        arr[r : r + STRIP, :, :3] = np.rint(block).astype(np.uint16)
        if how.startswith("noisy"):  # a soft disc: opaque inside 0.45 of the side, clear from 0.49
            d = np.hypot(yy[: len(block)] + r + 0.5 - h / 2, xx + 0.5 - w / 2) / side
            arr[r : r + STRIP, :, 3] = np.rint(np.clip((0.49 - d) / 0.04, 0.0, 1.0) * 65535.0).astype(np.uint16)
        else:
            arr[r : r + STRIP, :, 3] = 65535
    del big
    params = [cv2.IMWRITE_JPEG_QUALITY, 90] if jpeg else []
    if how == "noisy-paeth":
        params = [cv2.IMWRITE_PNG_FILTER, cv2.IMWRITE_PNG_FILTER_PAETH]
    tmp = out.with_suffix(".part" + out.suffix)
    if how in ("noisy-deflate-tiled", "noisy-packbits"):
        _write_with_pillow(arr, tmp, how)
        tmp.replace(out)
        return out
    if out.suffix in FORMATS:
        channels, dtype = FORMATS[out.suffix]
        arr = arr[:, :, :channels]
        if dtype == np.uint8:
            arr = (arr >> 8).astype(np.uint8)
        elif dtype == np.float32:
            arr = arr.astype(np.float32) / np.float32(65535.0)
        params = {
            ".webp": [cv2.IMWRITE_WEBP_QUALITY, 90],
            ".avif": [getattr(cv2, "IMWRITE_AVIF_SPEED", 0), 10],
        }.get(out.suffix, [])
    if not cv2.imwrite(str(tmp), arr, params):
        raise SystemExit(f"huge.py: cannot write {tmp}")
    tmp.replace(out)
    return out


def _write_with_pillow(arr: np.ndarray, tmp: Path, how: str) -> None:
    """A TIFF OpenCV does not write: 16-bit RGBA deflate in 512 px tiles (tifffile), or 8-bit RGB PackBits (Pillow)."""
    import tifffile
    from PIL import Image

    rgb = arr[:, :, [2, 1, 0, 3]]  # RGBA
    if how == "noisy-packbits":
        Image.fromarray((rgb[:, :, :3] >> 8).astype(np.uint8)).save(tmp, format="TIFF", compression="packbits")
    else:
        tifffile.imwrite(
            tmp,
            rgb,
            photometric="rgb",
            extrasamples=["unassalpha"],
            compression="zlib",
            tile=(512, 512),
            predictor=True,
        )


def run(image: Path, checkout: Path, work: Path) -> tuple[float, float, float, float, int | str]:
    """(wall s, user s, sys s, peak RSS GB, arcs) of the command on ``image`` with ``checkout``'s img2logo."""
    svg, js, times = work / "o.svg", work / "o.json", work / "time.txt"
    for f in (svg, js):
        f.unlink(missing_ok=True)
    env = dict(os.environ, PYTHONPATH=str(checkout))
    cmd = ["/usr/bin/time", "-o", str(times), "-f", "%e %U %S %M", sys.executable, "-m", "img2logo", str(image)]
    done = subprocess.run([*cmd, "-q", "--svg", str(svg), "--json", str(js)], env=env, cwd=work, check=False)
    wall, user, system, kb = times.read_text().split()[-4:]
    arcs: int | str = f"exit {done.returncode}"
    if done.returncode == 0:
        arcs = len(json.loads(js.read_text(encoding="utf-8"))["arcs"])
    return float(wall), float(user), float(system), int(kb) / 1e6, arcs


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default="*", help="images whose name matches this glob (default all)")
    parser.add_argument("--dir", type=Path, help="make and keep the images here (default: a temporary folder)")
    parser.add_argument("--repeat", type=int, default=1, help="runs per image and checkout (default 1)")
    parser.add_argument(
        "--checkout", type=Path, action="append", help="an img2logo checkout to run (repeatable; default this one)"
    )
    parser.add_argument("--make-only", action="store_true", help="make the images and stop")
    args = parser.parse_args(argv)
    checkouts = [c.resolve() for c in (args.checkout or [ROOT])]
    names = [n for n in IMAGES if fnmatch.fnmatch(n, args.only)]
    with tempfile.TemporaryDirectory(prefix="img2logo-huge-") as tmp:
        folder = args.dir or Path(tmp)
        folder.mkdir(parents=True, exist_ok=True)
        work = Path(tmp) / "work"
        work.mkdir()
        images = [make_image(n, folder) for n in names]
        if args.make_only:
            return 0
        print("image checkout run wall_s user_s sys_s cpu_s peak_GB arcs", flush=True)
        for image in images:
            for k in range(args.repeat):
                for c in checkouts:
                    wall, user, system, gb, arcs = run(image, c, work)
                    print(
                        f"{image.name} {c} {k + 1} {wall:.1f} {user:.1f} {system:.1f} {user + system:.1f} "
                        f"{gb:.2f} {arcs}",
                        flush=True,
                    )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
