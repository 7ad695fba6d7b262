"""How the optimization's cost grows with the drawing: n copies of one clip art side by side.

Each copy keeps its size (the tiled image is worked as it is, not downscaled
to 512 px: :func:`img2logo.extract_feature_lines` and
:func:`img2logo.fit.progressive.optimize` are called directly), so |A^0| and
the final arcs grow n-fold and a cost linear in the drawing grows n-fold too.
The time is CPU time (user + system of this process), the fairer measure on a
shared machine. Used by ``make bench`` (:func:`tiled_rows`); alone:
``python benchmarks/growth.py [--copies 1,2,4,8] [--image PATH]``.
"""

from __future__ import annotations

import argparse
import statistics
import time
import warnings
from pathlib import Path

import numpy as np

from img2logo import build_segment_graph, extract_feature_lines, load_image
from img2logo.fit.progressive import optimize

ROOT = Path(__file__).resolve().parents[1]
#: The clip art tiled: the fish of the examples, at ``TILE_SIDE`` px. Eight copies hold more regions than a
#: clip art keeps (the ``--detail`` bound): its A^0 grows less than eight-fold, and its time with it.
TILED_IMAGE = ROOT / "data" / "clipart-fish.png"
#: The drawing tiled: the fish of the examples, at ``TILE_SIDE`` px (a drawing's lines have no such bound).
TILED_DRAWING = ROOT / "data" / "drawing-fish.png"
#: Each copy's longer side, px: eight copies side by side stay within the largest image read (2048 px).
TILE_SIDE = 256
#: The numbers of copies side by side.
COPIES = (1, 2, 4, 8)


def tiled(path: Path, copies: int) -> np.ndarray:
    """``path`` at ``TILE_SIDE`` px, ``copies`` times side by side: RGB in [0, 1], shape (H, copies W, 3)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the downscale to TILE_SIDE is the point
        pixels = load_image(path, max_side=TILE_SIDE).rgb
    return np.concatenate([pixels] * copies, axis=1)


def tiled_rows(
    path: Path = TILED_IMAGE, copies: tuple[int, ...] = COPIES, budget: float | None = None, repeat: int = 3
) -> list[dict]:
    """One row per number of copies: |A^0|, final arcs, CPU s of the optimization, the shares of
    its merge loop and tangent joins (of its wall time), the global solves, why the loop stopped.

    ``budget``: the optimization's ``time_budget`` (None: unbounded, so that the growth itself is measured).
    Every run stops at T (``stretch=1``, the paper's rule): n copies are the same drawing n times, where
    the default arc budget of a logo would take the larger tilings past T and make them other work.
    The CPU time is the median of ``repeat`` runs after a warm-up: one copy's run is tens of ms, whose
    noise on a shared machine would otherwise move every row's 'per copy'.
    """
    rows = []
    settings: dict = {"stretch": 1.0, **({} if budget is None else {"time_budget": budget})}
    for n in copies:
        lines = extract_feature_lines(tiled(path, n), kind="drawing" if path.stem.startswith("drawing") else "clipart")
        graph = build_segment_graph(lines)
        optimize(graph, **settings)
        times = []
        for _ in range(max(1, repeat)):
            start = time.process_time()
            prog = optimize(graph, **settings)
            times.append(time.process_time() - start)
        cpu = statistics.median(times)
        rows.append(
            {
                "copies": n,
                "size": f"{graph.width}x{graph.height}",
                "a0": prog.arc_counts[0],
                "final": prog.arc_counts[-1],
                "cpu": cpu,
                "loop": prog.timings["loop"] / sum(prog.timings.values()),
                "tangency": prog.timings["tangency"] / sum(prog.timings.values()),
                "global_solves": prog.stats["global_solves"],
                "stopped": prog.stopped_because,
            }
        )
        print(_row_text(rows[-1], rows[0]), flush=True)
    return rows


def _row_text(row: dict, first: dict) -> str:
    per_copy = row["cpu"] / row["copies"] / first["cpu"]
    return (
        f"{row['copies']:6d} {row['size']:>10s} {row['a0']:6d} {row['final']:6d} {row['cpu']:8.2f}s "
        f"{row['loop']:8.0%} {row['tangency']:8.0%} {per_copy:9.2f} {row['global_solves']:7d}  {row['stopped']}"
    )


HEADER = (
    f"{'copies':>6s} {'size':>10s} {'|A^0|':>6s} {'final':>6s} {'CPU':>9s} {'loop':>8s} {'tangency':>8s} "
    f"{'per copy':>9s} {'global':>7s}  stopped"
)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--copies", default=",".join(map(str, COPIES)), help="numbers of copies, e.g. 1,2,4,8")
    parser.add_argument("--repeat", type=int, default=3, help="runs per row (the median CPU time)")
    parser.add_argument(
        "--image", type=Path, default=TILED_IMAGE, help="the image tiled (a drawing when its name starts so)"
    )
    args = parser.parse_args()
    copies = tuple(int(c) for c in args.copies.split(","))
    print(f"{args.image.name} tiled side by side; 'per copy': CPU per copy over one copy's (1.00 is linear)")
    print(HEADER)
    tiled_rows(args.image, copies, repeat=args.repeat)


if __name__ == "__main__":
    main()
