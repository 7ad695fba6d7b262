"""`make bench`: medians of the pipeline's stages on the example images, and ratios.

Speed is measured here, never asserted in the tests. Each in-process figure is
the median of ``--repeat`` runs after one warm-up run (imports and caches
excluded), on one core of whatever machine runs it; the ratio column compares a
median with its budget (below 1 is within budget). The command line is timed
as whole processes (start-up, imports and numba's cached kernels included)
against vtracer, a plain vectorizer (the ``bench`` extra), the two alternated
run by run so that a machine's load falls on both alike (issue 19).
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from img2logo import build_segment_graph, extract_feature_lines, load_image
from img2logo.fit.progressive import optimize
from img2logo.pipeline import abstract

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data"
#: Budget for preprocessing one 512 px image (issue: "well under a second"), s.
PREPROCESS_BUDGET = 1.0
#: Budget for the command line's start-up (import), s.
STARTUP_BUDGET = 0.5
#: Issue 19's budget for ``import img2logo`` and ``img2logo --version`` as whole processes, s.
VERSION_BUDGET = 0.15
#: Budget for the whole pipeline on the 512 px clip-art fish (issue: under 2 s), s.
PIPELINE_BUDGET = 2.0
#: Budget for the whole pipeline on a 512 px photo (issue 9: at most 5 s), s.
PHOTO_PIPELINE_BUDGET = 5.0
#: Issue 19's in-process budgets: the clip-art fish, and a clip art of about 56 arcs (the giraffe), s.
FISH_BUDGET = 0.15
MANY_ARCS_BUDGET = 0.4
#: Issue 19: the command line on a 512 px clip art or drawing at most this many times vtracer's time (goal 5).
VTRACER_RATIO_BUDGET = 10.0
#: The command line against vtracer: 512 px clip arts and drawings (the giraffe: about 56 arcs).
VTRACER_IMAGES = (
    DATA / "clipart-fish.png",
    ROOT / "benchmarks" / "data" / "clipart-giraffe.png",
    DATA / "drawing-rabbit.png",
)
#: Issue 23: a 512 px photo through the command line, as a whole process, at most this long, s.
PHOTO_CLI_BUDGET = 2.0
#: The photos the command is timed on: 512 px on the longer side.
PHOTO_CLI_IMAGES = (
    DATA / "photo-flower.png",
    ROOT / "benchmarks" / "data" / "photo-teddy-bear.png",
    ROOT / "benchmarks" / "data" / "photo2" / "photo2-giraffe.jpg",
)
#: The paper's Table 3 (its fish, Python, i9 3.6 GHz), s; None where it says ">= 2 hrs".
PAPER_TABLE3 = {(False, False): None, (True, False): 257.47, (False, True): 338.87, (True, True): 65.37}


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


def bench_pipeline(name: str, repeat: int, path: Path | None = None, budget: float = PIPELINE_BUDGET) -> None:
    path = DATA / f"{name}.png" if path is None else path
    runs, cpu = [], []
    for _ in range(repeat + 1):
        start, start_cpu = time.perf_counter(), time.process_time()
        result = abstract(path, progress=False)
        runs.append((time.perf_counter() - start, result))
        cpu.append(time.process_time() - start_cpu)
    runs, cpu = runs[1:], cpu[1:]  # the first run pays for imports
    total = statistics.median(t for t, _ in runs)
    stages = {k: statistics.median(r.timings[k] for _, r in runs) for k in runs[0][1].timings}
    result = runs[0][1]
    ratio = total / budget
    print(
        f"\nWhole pipeline on {name} (median of {repeat}): {total:.2f} s (CPU {statistics.median(cpu):.2f} s), "
        f"ratio {ratio:.2f} of {budget:g} s; {_load()}"
    )
    print("  " + ", ".join(f"{k} {v * 1e3:.0f} ms" for k, v in stages.items()))
    prog = result.progression
    print(f"  arcs {prog.arc_counts[0]} -> {prog.arc_counts[-1]} over {len(prog.levels)} levels; stats {prog.stats}")


def bench_table3(name: str, repeat: int) -> None:
    graph = build_segment_graph(extract_feature_lines(DATA / f"{name}.png"))
    # The paper's fit (no tangent joins), as notebook 09's Table 3.
    print(f"\nTable 3 on {name} ({graph.n_segments} segments), optimization only, the paper's fit, median of {repeat}:")
    head = ("localized", "simplify", "ours (s)", "vs both", "paper (s)", "vs both", "arcs")
    print(" ".join(f"{h:>10s}" for h in head))
    cells = {}
    for localized in (False, True):
        for simplify in (False, True):
            t, prog = median_time(
                lambda lo=localized, si=simplify: optimize(graph, localized=lo, simplify=si, tangency=False), repeat
            )
            cells[(localized, simplify)] = (t, prog)
    base = cells[(True, True)][0]
    for key, (t, prog) in cells.items():
        paper = PAPER_TABLE3[key]
        paper_txt = f"{paper:10.2f}" if paper else "   >= 7200"
        paper_ratio = (paper or 7200.0) / PAPER_TABLE3[(True, True)]
        cols = (f"{key[0]!s:>10s}", f"{key[1]!s:>10s}", f"{t:10.2f}", f"{t / base:9.1f}x", paper_txt)
        print(" ".join(cols) + f" {paper_ratio:9.1f}x {prog.arc_counts[-1]:10d}")


def bench_startup(repeat: int) -> None:
    """Start-up as whole processes: ``import img2logo.app.cli``, ``import img2logo`` and ``img2logo --version``."""
    for label, cmd, budget in (
        ("python -c 'import img2logo.app.cli'", [sys.executable, "-c", "import img2logo.app.cli"], STARTUP_BUDGET),
        ("python -c 'import img2logo'", [sys.executable, "-c", "import img2logo"], VERSION_BUDGET),
        ("img2logo --version", [sys.executable, "-m", "img2logo.app.cli", "--version"], VERSION_BUDGET),
    ):
        times = [_process_times(cmd) for _ in range(repeat)]
        med = statistics.median(w for w, _ in times)
        cpu = statistics.median(c for _, c in times)
        print(
            f"\nCommand start-up ({label}, median of {repeat}): "
            f"{med * 1e3:.0f} ms (CPU {cpu * 1e3:.0f} ms), ratio {med / budget:.2f} of {budget:g} s"
        )
    # What every run pays before its work: the modules a run imports and the compiled kernels' load.
    code = "import img2logo.pipeline, img2logo.export.writers, img2logo._compiled.kernels as k; k.usable()"
    times = [_process_times([sys.executable, "-c", code]) for _ in range(repeat)]
    med, cpu = statistics.median(w for w, _ in times), statistics.median(c for _, c in times)
    print(f"\nA run's fixed cost (python -c '{code}', median of {repeat}): {med * 1e3:.0f} ms (CPU {cpu * 1e3:.0f} ms)")
    # The same as the command pays it: started as the command starts (one BLAS thread, no collections during the
    # imports: img2logo.app.cli._start_command), with OpenCV, which every run imports to read its image.
    code = (
        "import img2logo.app.cli as c; c._start_command(); "
        "import img2logo.pipeline, img2logo.export.writers, img2logo._compiled.kernels as k, cv2; "
        "k.usable(); c._freeze_heap()"
    )
    times = [_process_times([sys.executable, "-c", code]) for _ in range(repeat)]
    med, cpu = statistics.median(w for w, _ in times), statistics.median(c for _, c in times)
    print(f"The command's fixed cost (python -c '{code}', median of {repeat}): {med * 1e3:.0f} ms", end="")
    print(f" (CPU {cpu * 1e3:.0f} ms)")


def _process_seconds(cmd: list[str]) -> float:
    return _process_times(cmd)[0]


def _process_times(cmd: list[str]) -> tuple[float, float]:
    """Wall time and CPU time (user + system) of one whole process, s.

    On a machine others share, the CPU time is the fairer measure: the wall time
    also counts the time the process waited for a core.
    """
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def _load() -> str:
    """The machine's load average over the last minute, and its cores, as text."""
    return f"load {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores"


def bench_cli_vs_vtracer(repeat: int) -> None:
    """The ``img2logo`` command and vtracer (spline mode) on the same images, as whole processes, alternated."""
    try:
        import vtracer  # noqa: F401
    except ImportError:
        print("\nvtracer is not installed (pip install -e '.[bench]'): the command-line comparison is skipped")
        return
    print(
        f"\nThe command line against vtracer (whole processes, alternated, median of {repeat}), "
        f"budget {VTRACER_RATIO_BUDGET:.0f}x; {_load()} at the start"
    )
    head = ("image", "img2logo", "vtracer", "ratio", "of budget", "CPU ours", "CPU theirs", "CPU ratio")
    print(f"{head[0]:16s} " + " ".join(f"{h:>10s}" for h in head[1:]))
    with tempfile.TemporaryDirectory() as tmp:
        for path in VTRACER_IMAGES:
            ours_cmd = [
                sys.executable,
                "-m",
                "img2logo.app.cli",
                str(path),
                "-q",
                "--svg",
                os.path.join(tmp, "ours.svg"),
            ]
            code = "import sys, vtracer; vtracer.convert_image_to_svg_py(sys.argv[1], sys.argv[2], mode='spline')"
            theirs_cmd = [sys.executable, "-c", code, str(path), os.path.join(tmp, "vtracer.svg")]
            _process_seconds(ours_cmd)  # warm-up: the compiled kernels (built once per install), the file system's
            _process_seconds(theirs_cmd)
            ours, theirs = [], []
            for _ in range(repeat):
                ours.append(_process_times(ours_cmd))
                theirs.append(_process_times(theirs_cmd))
            t_ours, t_theirs = statistics.median(w for w, _ in ours), statistics.median(w for w, _ in theirs)
            c_ours, c_theirs = statistics.median(c for _, c in ours), statistics.median(c for _, c in theirs)
            ratio = t_ours / t_theirs
            print(
                f"{path.stem:16s} {t_ours:9.2f}s {t_theirs:9.3f}s {ratio:9.0f}x {ratio / VTRACER_RATIO_BUDGET:10.1f}"
                f" {c_ours:9.2f}s {c_theirs:9.3f}s {c_ours / c_theirs:9.0f}x"
            )


def bench_cli_photo(repeat: int) -> None:
    """The ``img2logo`` command on 512 px photos as whole processes: wall and CPU (user + sys) time, medians.

    Everything a user waits for: start-up, imports, numba's cached kernels, the
    subject search, the pipeline and the SVG written. The CPU time is the
    child's (``resource.getrusage``), less noisy than the wall time on a
    shared machine; the photo's two GrabCuts run in two threads, so CPU may
    exceed wall.
    """
    import resource

    print(f"\nThe command line on a 512 px photo (whole processes, median of {repeat}), budget {PHOTO_CLI_BUDGET:g} s")
    print(f"{'image':20s} {'wall':>8s} {'cpu':>8s} {'ratio':>7s}")
    with tempfile.TemporaryDirectory() as tmp:
        for path in PHOTO_CLI_IMAGES:
            cmd = [sys.executable, "-m", "img2logo.app.cli", str(path), "-q", "--svg", os.path.join(tmp, "logo.svg")]
            _process_seconds(cmd)  # warm-up: numba's on-disk cache, the file system's
            walls, cpus = [], []
            for _ in range(repeat):
                before = resource.getrusage(resource.RUSAGE_CHILDREN)
                walls.append(_process_seconds(cmd))
                after = resource.getrusage(resource.RUSAGE_CHILDREN)
                cpus.append(after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime)
            wall = statistics.median(walls)
            print(f"{path.stem:20s} {wall:7.2f}s {statistics.median(cpus):7.2f}s {wall / PHOTO_CLI_BUDGET:7.2f}")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()
    bench_preprocessing(["clipart-fish", "clipart-cat", "drawing-fish", "drawing-rabbit", "photo-cat"], args.repeat)
    bench_pipeline("clipart-fish", args.repeat, budget=FISH_BUDGET)
    giraffe = ROOT / "benchmarks" / "data" / "clipart-giraffe.png"
    bench_pipeline(giraffe.stem, args.repeat, giraffe, MANY_ARCS_BUDGET)
    for photo in (ROOT / "benchmarks" / "data" / "photo-teddy-bear.png", DATA / "photo-flower.png"):
        bench_pipeline(photo.stem, args.repeat, photo, PHOTO_PIPELINE_BUDGET)
    bench_table3("clipart-fish", max(1, args.repeat // 2))
    bench_startup(args.repeat)
    bench_cli_vs_vtracer(args.repeat)
    bench_cli_photo(args.repeat)


if __name__ == "__main__":
    main()
