"""Where a batch's time goes: start-up, the stages of every image, the files, and the order of the work.

``python benchmarks/batch_split.py [--repeat N]`` over the images of ``make bench``'s batch
(``bench.BATCH_IMAGES``, 40 clip arts, drawings and held-out photo-likes):

1. start-up as whole processes (CPU, medians of ``--repeat``): the command line's import,
   what a batch's parent loads before it forks its workers (:func:`img2logo.app.batch.pool`'s
   warm-up: the pipeline, the writers, the compiled kernels, OpenCV), matplotlib's canvas
   (the PNG), and pandas;
2. every image in one warm process, CPU by stage: loading, the front end
   (:func:`img2logo.extract_feature_lines`), the segment graph, the optimization, and the
   SVG, JSON and PNG a batch makes (:func:`img2logo.export.writers.encode`); by kind;
3. the order of the work: two workers taking the images in input order (as
   :func:`img2logo.app.batch.run.run_batch` hands them out) against the longest first
   and against an even split, from the CPU each image took in 2;
4. the batch as ``img2logo batch --jobs 2`` runs it (``make bench``'s command, every output written),
   in a process of its own: the parent's CPU (its imports, the workers' warm-up, writing the files,
   the summary and gallery) and the workers' (before their first image, ``abstract()``, each format).

CPU time (user + system), the fairer measure on a shared machine.
"""

from __future__ import annotations

import argparse
import contextlib
import heapq
import json
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from collections import defaultdict
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

#: bench.py, beside this file (imported by :func:`main` only: section 4's process counts its own imports).
BENCH_DIR = Path(__file__).resolve().parent

#: Start-up steps, each a fresh process: a label and the Python code it runs.
STARTUP: tuple[tuple[str, str], ...] = (
    ("python alone", "pass"),
    ("the command's import", "import img2logo.app.cli"),
    (
        "a worker's warm-up (pipeline, writers, kernels, OpenCV)",
        "import cv2, img2logo.pipeline, img2logo.export.writers, img2logo._compiled.kernels as k; k.usable()",
    ),
    (
        "the same and matplotlib's canvas",
        "import cv2, img2logo.pipeline, img2logo.export.writers, img2logo._compiled.kernels as k; k.usable(); "
        "import matplotlib.backends.backend_agg, matplotlib.figure, matplotlib.style",
    ),
    ("pandas", "import pandas"),
)


def child_cpu(code: str) -> float:
    """CPU seconds (user + system) of ``python -c code`` as a whole process."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run([sys.executable, "-c", code], check=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


@contextlib.contextmanager
def timing(module: Any, name: str, into: dict[str, float], key: str) -> Iterator[None]:
    """While the block runs, ``module.name`` adds the CPU seconds of its calls to ``into[key]``."""
    inner: Callable[..., Any] = getattr(module, name)

    def timed(*args: Any, **kwargs: Any) -> Any:
        start = time.process_time()
        try:
            return inner(*args, **kwargs)
        finally:
            into[key] += time.process_time() - start

    setattr(module, name, timed)
    try:
        yield
    finally:
        setattr(module, name, inner)


def stages(paths: Sequence[Path]) -> tuple[dict[str, float], dict[str, list[float]], list[float]]:
    """CPU by stage over ``paths`` in this process, the CPU of each image by kind, and each image's CPU in order."""
    from img2logo import pipeline
    from img2logo.export import writers

    result = pipeline.abstract(paths[0], progress=False)  # imports and caches: not an image's cost
    for fmt in ("svg", "json", "png"):
        writers.encode(result.final, fmt, image=result.image.rgb)
    spent: dict[str, float] = defaultdict(float)
    by_kind: dict[str, list[float]] = defaultdict(list)
    each = []
    with contextlib.ExitStack() as stack:
        for name, key in (
            ("load_image", "load"),
            ("extract_feature_lines", "front end"),
            ("build_segment_graph", "segment graph"),
            ("optimize", "optimization"),
        ):
            stack.enter_context(timing(pipeline, name, spent, key))
        for path in paths:
            start = time.process_time()
            result = pipeline.abstract(path, progress=False)
            by_kind[result.lines.kind].append(time.process_time() - start)
            for fmt in ("svg", "json", "png"):
                t = time.process_time()
                writers.encode(result.final, fmt, image=result.image.rgb)
                spent[f"the {fmt.upper()}"] += time.process_time() - t
            each.append(time.process_time() - start)
    return spent, by_kind, each


def two_workers(costs: Sequence[float]) -> float:
    """When the last of two workers ends, each taking the next cost as it becomes free (a pool's hand-out)."""
    free = [0.0, 0.0]
    for cost in costs:
        heapq.heappush(free, heapq.heappop(free) + cost)
    return max(free)


#: Section 4's sums in this process (the parent's, or a forked worker's own copy), and where the workers write them.
_SPENT: dict[str, float] = defaultdict(float)
_LOG: list[Path] = []


def _timed_image(*args: Any, **kwargs: Any) -> dict[str, Any]:
    """:func:`img2logo.app.batch.pool.process_image`, adding its CPU to ``_SPENT`` and the sums to the log.

    Module-level, so that the pool can pickle it by name; a forked worker's clock starts at 0.
    """
    from img2logo.app.batch import pool

    _SPENT.setdefault("before the first image", time.process_time())
    try:
        return pool.process_image.__wrapped__(*args, **kwargs)  # type: ignore[attr-defined]
    finally:
        with open(_LOG[0], "a") as f:
            f.write(json.dumps({"worker": os.getpid(), "cpu": time.process_time(), **_SPENT}) + "\n")


def whole_batch(paths: Sequence[Path], log: Path) -> None:
    """Run ``img2logo batch --jobs 2`` over ``paths`` in this process, writing where the CPU went to ``log``.

    Called in a fresh process (:func:`whole`): the command's own imports are counted. The workers,
    forked from this process, write the CPU of each stage of their images so far to ``log`` after each
    image (one JSON line); the parent adds one line at the end.
    """
    start = time.process_time()
    from img2logo import pipeline
    from img2logo.app import cli
    from img2logo.app.batch import gallery, pool
    from img2logo.export import writers

    _SPENT["imports"] = time.process_time() - start
    _LOG.append(log)
    inner = writers.encode

    def encode(level: Any, fmt: str, **kwargs: Any) -> bytes:
        t = time.process_time()
        try:
            return inner(level, fmt, **kwargs)
        finally:
            _SPENT[f"the {fmt.upper()}"] += time.process_time() - t

    _timed_image.__wrapped__ = pool.process_image  # type: ignore[attr-defined]
    with tempfile.TemporaryDirectory() as tmp, contextlib.ExitStack() as stack:
        for module, name, key in (
            (pipeline, "abstract", "abstract()"),
            (pool, "_warm", "warm-up"),
            (gallery, "write_gallery", "gallery"),
        ):
            stack.enter_context(timing(module, name, _SPENT, key))
        writers.encode = encode  # type: ignore[assignment]
        pool.process_image = _timed_image  # type: ignore[assignment]
        folder = Path(tmp) / "in"
        folder.mkdir()
        for path in paths:
            (folder / path.name).symlink_to(path)
        cli.main(["batch", str(folder), str(Path(tmp) / "out"), "-q", "--jobs", "2"])
    with open(log, "a") as f:
        f.write(json.dumps({"worker": None, "cpu": time.process_time() - start, **_SPENT}) + "\n")


def whole(paths: Sequence[Path]) -> None:
    """Print where the CPU of ``img2logo batch --jobs 2`` over ``paths`` goes (:func:`whole_batch`, a fresh process)."""
    with tempfile.TemporaryDirectory() as tmp:
        log = Path(tmp) / "cpu.jsonl"
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        subprocess.run([sys.executable, __file__, "--whole-batch", str(log), *map(str, paths)], check=True)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        lines = [json.loads(line) for line in log.read_text().splitlines()]
    total = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    parent = next(line for line in lines if line["worker"] is None)
    last = {line["worker"]: line for line in lines if line["worker"] is not None}  # each worker's running sums
    workers: dict[str, float] = defaultdict(float)
    for sums in last.values():
        for key, value in sums.items():
            if key != "worker":
                workers[key] += value
    writing = parent["cpu"] - parent["imports"] - parent.get("warm-up", 0.0) - parent.get("gallery", 0.0)
    started = total - parent["cpu"] - workers["cpu"]
    per_image = total / len(paths) * 1e3
    print(f"\nimg2logo batch --jobs 2, {len(paths)} images: {total:.2f} s of CPU ({per_image:.0f} ms an image)")
    formats = ("SVG", "JSON", "PNG")
    rows = [
        ("python's start, the workers' ends (not timed)", started),
        ("the parent: its imports", parent["imports"]),
        ("the parent: the workers' warm-up", parent.get("warm-up", 0.0)),
        ("the parent: the rest (files, report, start)", writing),
        ("the parent: the summary and gallery", parent.get("gallery", 0.0)),
        (f"{len(last)} workers: before their first image", workers["before the first image"]),
        ("the workers: abstract()", workers["abstract()"]),
        *((f"the workers: the {fmt}", workers[f"the {fmt}"]) for fmt in formats),
        (
            "the workers: the rest",
            workers["cpu"]
            - workers["before the first image"]
            - workers["abstract()"]
            - sum(workers[f"the {fmt}"] for fmt in formats),
        ),
    ]
    for label, seconds in rows:
        print(f"  {label:46s} {seconds:6.2f} s  {seconds / total * 100:5.1f} %")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5, help="runs of each start-up step (median)")
    parser.add_argument("--whole-batch", type=Path, help=argparse.SUPPRESS)  # section 4's process: LOG IMAGE...
    args, images = parser.parse_known_args()
    if args.whole_batch is not None:
        whole_batch([Path(p) for p in images], args.whole_batch)
        return
    sys.path.insert(0, str(BENCH_DIR))
    import bench

    paths = list(bench.BATCH_IMAGES)
    print(f"Start-up, whole processes, CPU (median of {args.repeat})")
    for label, code in STARTUP:
        cpu = statistics.median(child_cpu(code) for _ in range(args.repeat))
        print(f"  {label:58s} {cpu * 1e3:6.0f} ms")
    spent, by_kind, each = stages(paths)
    total = sum(each)
    print(f"\n{len(paths)} images in one process: {total:.2f} s of CPU ({total / len(paths) * 1e3:.0f} ms an image)")
    for key, seconds in spent.items():
        print(f"  {key:16s} {seconds:6.2f} s  {seconds / total * 100:5.1f} %")
    for kind, cpu in sorted(by_kind.items()):
        print(
            f"  abstract() of {len(cpu):2d} {kind:8s} {sum(cpu):6.2f} s, {statistics.median(cpu) * 1e3:5.0f} ms median"
        )
    order = two_workers(each)
    longest = two_workers(sorted(each, reverse=True))
    print(
        f"\nTwo workers, from each image's CPU: input order ends at {order:.2f} s, the longest first at "
        f"{longest:.2f} s, an even split at {total / 2:.2f} s (the last image: {each[-1]:.2f} s)"
    )
    whole(paths)


if __name__ == "__main__":
    main()
