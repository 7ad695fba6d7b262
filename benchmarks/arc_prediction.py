"""How well :func:`img2logo.features.boundary_cost.boundary_arcs` predicts a clip art's arcs.

For every clip art of ``benchmarks/quality.py``'s families (``clipart``, ``heldout clipart``,
``openclipart clipart``): the arcs of the default logo, and the arcs predicted from the regions
it was drawn from (the regions the default ``--detail`` keeps, the silhouette's boundary
included). Prints one row per image and the median and log spread of arcs / predicted: the
calibration of ``ARC_CHORDS`` (docs/design/detail.md, "An arc budget").

    python benchmarks/arc_prediction.py [--only GLOB]
"""

from __future__ import annotations

import argparse
import fnmatch
import sys
import warnings
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

FAMILIES = ("clipart", "heldout clipart", "openclipart clipart")


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default="*", help="the images whose name matches this glob")
    args = parser.parse_args(argv)

    import quality

    from img2logo import abstract, load_image
    from img2logo.features.boundary_cost import boundary_arcs
    from img2logo.features.clipart_colours import label_means
    from img2logo.features.clipart_strokes import thin_regions

    ratios = []
    for case in quality.cases():
        if case["family"] not in FAMILIES or not fnmatch.fnmatch(case["name"], args.only):
            continue
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            result = abstract(case["path"], progress=False)
        regions = result.lines.regions
        lightness = label_means(regions, load_image(case["path"]).lab)[1][:, 0]
        predicted = sum(boundary_arcs(regions, thin_regions(regions, lightness)).values())
        arcs = len(result.final.arcs)
        ratios.append(arcs / predicted)
        print(f"{case['name']:36s} {case['family']:20s} arcs {arcs:3d}  predicted {predicted:6.1f}  {ratios[-1]:.2f}")
    r = np.array(ratios)
    print(f"{len(r)} clip arts: arcs / predicted median {np.median(r):.2f}, log spread {np.std(np.log(r)):.2f}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
