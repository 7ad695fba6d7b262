"""`make bench`: medians of the pipeline's stages on the example images, and ratios.

Speed is measured here, never asserted in the tests. Each figure is the median
of ``--repeat`` runs after one warm-up run (imports and caches excluded), on one
core of whatever machine runs it; the ratio column compares a median with its
budget (below 1 is within budget).
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time
from pathlib import Path

from img2logo import build_segment_graph, extract_feature_lines, load_image

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data"
#: Budget for preprocessing one 512 px image (issue: "well under a second"), s.
PREPROCESS_BUDGET = 1.0
#: Budget for the command line's start-up (import), s.
STARTUP_BUDGET = 0.5


def median_time(fn, repeat: int) -> tuple[float, object]:
    result = fn()  # warm-up
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        result = fn()
        times.append(time.perf_counter() - start)
    return statistics.median(times), result


def bench_preprocessing(names: list[str], repeat: int) -> None:
    print(f"Preprocessing (median of {repeat}), budget {PREPROCESS_BUDGET:.1f} s per image")
    head = ("image", "kind", "size", "load", "lines", "graph", "total", "ratio")
    print(f"{head[0]:16s} {head[1]:8s} " + " ".join(f"{h:>8s}" for h in head[2:]))
    for name in names:
        path = DATA / f"{name}.png"
        t_load, image = median_time(lambda p=path: load_image(p), repeat)
        t_lines, lines = median_time(lambda im=image: extract_feature_lines(im), repeat)
        t_graph, _ = median_time(lambda fl=lines: build_segment_graph(fl), repeat)
        total = t_load + t_lines + t_graph
        size = f"{image.width}x{image.height}"
        print(
            f"{name:16s} {lines.kind:8s} {size:>8s} {t_load * 1e3:6.1f}ms {t_lines * 1e3:6.1f}ms "
            f"{t_graph * 1e3:6.1f}ms {total * 1e3:6.1f}ms {total / PREPROCESS_BUDGET:6.2f}"
        )


def bench_startup(repeat: int) -> None:
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        subprocess.run([sys.executable, "-c", "import img2logo.cli"], check=True)
        times.append(time.perf_counter() - start)
    med = statistics.median(times)
    print(
        f"\nCommand start-up (python -c 'import img2logo.cli', median of {repeat}): "
        f"{med * 1e3:.0f} ms, ratio {med / STARTUP_BUDGET:.2f} of {STARTUP_BUDGET:.1f} s"
    )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    bench_preprocessing(["clipart-fish", "clipart-cat", "drawing-fish", "drawing-rabbit", "photo-cat"], args.repeat)
    bench_startup(args.repeat)


if __name__ == "__main__":
    main()
