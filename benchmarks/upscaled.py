"""Logos of the evaluation set's clip arts and drawings upscaled, worked at several sizes.

``python benchmarks/upscaled.py --only 'clipart-*' --sizes 2048:2048,2048:512`` upscales each
512 px image of ``benchmarks/data/`` (bicubic) to N px and works it at W px (each N:W pair), then
prints one row per run: the kind detected, arcs, r3/r6/r10 of the logo scaled back to the 512 px
ground truth (so 10 px of the original at any N), near-miss gaps, crossings and the CPU seconds
of ``abstract``. How ``SYNTHETIC_WORK_SIDE`` (``img2logo/constants.py``, ``docs/design/defaults.md``) was chosen. A
benchmark, not a test.
"""

from __future__ import annotations

import argparse
import fnmatch
import json
import time
import warnings
from pathlib import Path

import numpy as np

EVAL = Path(__file__).resolve().parent / "data"


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default="*", help="images whose name matches this glob (default all)")
    parser.add_argument(
        "--sizes",
        default="512:512,2048:2048,2048:1024,2048:512,4000:1024,4000:512",
        help="N:W pairs: upscale to N px, work at W px",
    )
    args = parser.parse_args(argv)

    import cv2

    from img2logo import abstract, load_mask, pipeline, quality
    from img2logo.images.loading import load_image

    pipeline.SYNTHETIC_WORK_SIDE = 1 << 30  # W is set by the loaded copy, not by the pipeline
    pairs = [tuple(int(v) for v in p.split(":")) for p in args.sizes.split(",")]
    manifest = json.loads((EVAL / "manifest.json").read_text(encoding="utf-8"))
    print("name N W kind arcs r3 r6 r10 gaps crossings cpu")
    for m in manifest:
        if m["kind"] == "photo" or not fnmatch.fnmatch(m["name"], args.only):
            continue
        src = np.ascontiguousarray(cv2.imread(str(EVAL / m["file"]), cv2.IMREAD_COLOR)[:, :, ::-1])
        truth = load_mask(EVAL / m["gt"])
        h0, w0 = src.shape[:2]
        for n, w in pairs:
            f = n / max(h0, w0)
            big = src if f == 1 else cv2.resize(src, (round(w0 * f), round(h0 * f)), interpolation=cv2.INTER_CUBIC)
            start = time.process_time()
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                result = abstract(load_image(big, max_side=w), progress=False)
            cpu = time.process_time() - start
            final = result.final.scaled(1 / f, w0, h0) if f != 1 else result.final
            q = quality.measure(final, truth)
            r3, r6, r10 = q.recall
            print(
                f"{m['name']} {n} {w} {result.lines.kind} {q.arcs} {r3:.3f} {r6:.3f} {r10:.3f} {q.gaps} "
                f"{q.crossings} {cpu:.1f}",
                flush=True,
            )
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
