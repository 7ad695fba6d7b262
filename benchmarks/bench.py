"""`make bench`: medians of the pipeline's stages on the example images, and ratios.

Speed is measured here, never asserted in the tests. Each in-process figure is
the median of ``--repeat`` runs after one warm-up run (imports and caches
excluded), on one core of whatever machine runs it; the ratio column compares a
median with its budget (below 1 is within budget). The command line is timed
as whole processes (start-up, imports and numba's cached kernels included)
against vtracer, a plain vectorizer (the ``bench`` extra), the two alternated
run by run so that a machine's load falls on both alike.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from collections.abc import Sequence
from pathlib import Path
from typing import TextIO

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))  # growth.py beside this file

import growth

from img2logo import build_segment_graph, extract_feature_lines, load_image
from img2logo.fit.progressive import optimize
from img2logo.options import TIME_BUDGET
from img2logo.pipeline import abstract

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "data"
#: Budget for preprocessing one 512 px image (issue: "well under a second"), s.
PREPROCESS_BUDGET = 1.0
#: Budget for the command line's start-up (import), s.
STARTUP_BUDGET = 0.5
#: The budget for ``import img2logo`` and ``img2logo --version`` as whole processes, s.
VERSION_BUDGET = 0.15
#: Budget for the whole pipeline on the 512 px clip-art fish (issue: under 2 s), s.
PIPELINE_BUDGET = 2.0
#: Budget for the whole pipeline on a 512 px photo (at most 5 s), s.
PHOTO_PIPELINE_BUDGET = 5.0
#: The in-process budgets: the clip-art fish, and a clip art of about 56 arcs (the giraffe), s.
FISH_BUDGET = 0.15
MANY_ARCS_BUDGET = 0.4
#: The command line against vtracer over ``CLI_IMAGES``: targets for the worst and the median ratio.
WORST_RATIO_TARGET = 8.0
MEDIAN_RATIO_TARGET = 6.0
BENCHMARK_DATA = ROOT / "benchmarks" / "data"
#: The command line against vtracer and the growth table: ten 512 px drawings and clip arts of the examples
#: and the evaluation set, 10 to 58 final arcs (the most any of them has), held-out ones among them.
CLI_IMAGES = (
    BENCHMARK_DATA / "drawing-bike.png",
    DATA / "drawing-fish.png",
    DATA / "drawing-rabbit.png",
    BENCHMARK_DATA / "drawing-deer.png",
    DATA / "clipart-fish.png",
    BENCHMARK_DATA / "heldout" / "clipart-critter-d.png",
    BENCHMARK_DATA / "clipart-honeybee.png",
    BENCHMARK_DATA / "clipart-polar-bear.png",
    BENCHMARK_DATA / "clipart-giraffe.png",
    BENCHMARK_DATA / "clipart-cactus.png",
)
#: Busier clip arts for the growth table only (Openclipart, hundreds of arcs at A^0, over 100 in the logo).
BUSY_IMAGES = (
    BENCHMARK_DATA / "openclipart" / "clipart-farfalla.png",
    BENCHMARK_DATA / "openclipart" / "clipart-gallo.png",
)
#: Batch throughput: the evaluation set's 40 clip arts, drawings and held-out photo-likes (the clip arts and
#: drawings of benchmarks/data/, of its heldout/, and its heldout-photo/), ``img2logo batch --jobs 2``.
BATCH_IMAGES = tuple(
    sorted(
        p
        for folder in (BENCHMARK_DATA, BENCHMARK_DATA / "heldout", BENCHMARK_DATA / "heldout-photo")
        for p in folder.iterdir()
        if p.suffix in (".png", ".jpg")
        and ".gt." not in p.name
        and ".mask." not in p.name
        and not p.name.startswith("photo-")
    )
)
#: Batch throughput target on two cores, images/s.
BATCH_TARGET = 10.0
#: The yardsticks' own venv (vtracer alone), made by the benchmark when missing.
BENCH_VENV = ROOT / "build" / "bench-venv"
#: The page ``make bench`` writes.
PAGE = ROOT / "docs" / "performance.md"
#: a 512 px photo through the command line, as a whole process, at most this long, s.
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
        "import img2logo.app.commands as m; k.usable(); m.freeze_heap()"
    )
    times = [_process_times([sys.executable, "-c", code]) for _ in range(repeat)]
    med, cpu = statistics.median(w for w, _ in times), statistics.median(c for _, c in times)
    print(f"The command's fixed cost (python -c '{code}', median of {repeat}): {med * 1e3:.0f} ms", end="")
    print(f" (CPU {cpu * 1e3:.0f} ms)")


#: The images of :func:`bench_command_parts`: a drawing and a clip art of the command-line comparison.
PARTS_IMAGES = (BENCHMARK_DATA / "drawing-bike.png", DATA / "clipart-fish.png")
#: The steps of :func:`bench_command_parts`, each a process that does one thing more than the one before.
_PARTS = (
    ("the interpreter's start (python -c pass)", "pass"),
    ("img2logo.app.cli, argparse", "import img2logo.app.cli as c; c._start_command()"),
    ("numpy (one BLAS thread)", "import img2logo.app.cli as c; c._start_command(); import numpy"),
    ("OpenCV", "import img2logo.app.cli as c; c._start_command(); import numpy, cv2"),
    (
        "img2logo's modules, the kernels' load",
        "import img2logo.app.cli as c; c._start_command(); import numpy, cv2; "
        "import img2logo.pipeline, img2logo.export.writers, img2logo._compiled.kernels as k; "
        "import img2logo.app.commands as m; k.usable(); m.freeze_heap()",
    ),
)


def bench_command_parts(repeat: int, page: Page) -> None:
    """Where the command's time goes: whole processes that each do one step more, alternated run by run.

    The steps (:data:`_PARTS`) start Python, import the command's module (as the command starts: one BLAS
    thread, no collections meanwhile), numpy, OpenCV, then img2logo's modules with the compiled kernels'
    load; the last process is the command on the image (``-m img2logo.app.cli IMAGE -q --svg OUT``). The
    difference of two consecutive medians is what the step adds; the last row (the run: reading the image,
    :func:`img2logo.abstract`, writing the SVG, the interpreter's exit) also holds ``-m``'s own start.
    """
    page.say(f"\nWhere the command's time goes (whole processes, alternated, median of {repeat}); {_load()}")
    columns: list[list[tuple[float, float]]] = []
    with tempfile.TemporaryDirectory() as tmp:
        steps = [[sys.executable, "-c", code] for _, code in _PARTS]
        for path in PARTS_IMAGES:
            run = [sys.executable, "-m", "img2logo.app.cli", str(path), "-q", "--svg", os.path.join(tmp, "o.svg")]
            wall, cpu = _alternated([*steps, run], repeat)
            parts = [(cpu[0], wall[0])] + [(cpu[i] - cpu[i - 1], wall[i] - wall[i - 1]) for i in range(1, len(cpu))]
            columns.append(parts)
            page.say(f"{path.stem}: CPU {cpu[-1] * 1e3:.0f} ms, wall {wall[-1] * 1e3:.0f} ms")
    labels = [label for label, _ in _PARTS] + ["the run (read, abstract, write, exit)"]
    rows = []
    for i, label in enumerate(labels):
        cells: list[object] = [label]
        for col in columns:
            total = sum(c for c, _ in col)
            cells += [f"{col[i][0] * 1e3:.0f}", f"{col[i][0] / total:.0%}", f"{col[i][1] * 1e3:.0f}"]
        rows.append(cells)
        page.say(f"  {label:42s} " + "  ".join(f"{c!s:>6s}" for c in cells[1:]))
    page.say(f"  (per image: CPU ms, share of CPU, wall ms); {_load()} at the end")
    head: list[str] = ["part"]
    for path in PARTS_IMAGES:
        head += [f"{path.stem} CPU (ms)", "share", "wall (ms)"]
    page.table(
        "Where the command's time goes",
        head,
        rows,
        f"Whole processes, each one step more than the last, alternated run by run, medians of {repeat}; a part "
        "is the difference of two consecutive medians (`benchmarks/bench.py --only startup`). The last row is "
        "the command on the image minus the processes before it: reading the image, `abstract()`, writing the "
        "SVG and the exit.",
    )


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


def _alternated(cmds: Sequence[list[str]], repeat: int) -> tuple[list[float], list[float]]:
    """Each command's median wall and CPU time over ``repeat`` whole processes, the commands alternated run by run.

    One warm-up run of each first: the compiled kernels (built once per install), the file system's caches.
    """
    for cmd in cmds:
        _process_times(cmd)
    times: list[list[tuple[float, float]]] = [[] for _ in cmds]
    for _ in range(repeat):
        for i, cmd in enumerate(cmds):
            times[i].append(_process_times(cmd))
    return [statistics.median(w for w, _ in t) for t in times], [statistics.median(c for _, c in t) for t in times]


def _load() -> str:
    """The machine's load average over the last minute, and its cores, as text."""
    return f"load {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores"


def bench_venv() -> Path | None:
    """The interpreter of the yardsticks' own venv (``build/bench-venv``, made with vtracer if missing), or None.

    vtracer is started as a user starts it: a plain interpreter (``python -I``
    of a venv that holds vtracer alone), not the project's (whose editable
    install adds about 13 ms to every start).
    """
    python = BENCH_VENV / "bin" / "python"
    if not python.exists() or subprocess.run([python, "-I", "-c", "import vtracer"], capture_output=True).returncode:
        base = shutil.which("python3") or sys.executable
        print(f"making {BENCH_VENV.relative_to(ROOT)} ({base} -m venv; pip install vtracer) ...", flush=True)
        made = subprocess.run([base, "-m", "venv", "--clear", BENCH_VENV], capture_output=True, text=True)
        if made.returncode == 0:
            made = subprocess.run(
                [python, "-m", "pip", "install", "--quiet", "vtracer"], capture_output=True, text=True
            )
        if made.returncode:
            print(f"could not make the venv with vtracer: {(made.stderr.strip().splitlines() or ['?'])[-1]}")
            return None
    return python


def _kind(path: Path) -> str:
    return "drawing" if path.stem.startswith("drawing") else "clipart"


def _pbm(path: Path, out: Path) -> None:
    """The image as a plain bitmap for potrace (ink: mean RGB below 0.5), made once before the timing."""
    ink = load_image(path).rgb.mean(axis=2) < 0.5
    rows = "\n".join(" ".join("1" if v else "0" for v in row) for row in ink)
    out.write_text(f"P1\n{ink.shape[1]} {ink.shape[0]}\n{rows}\n")


def bench_cli_vs_vtracer(repeat: int, page: Page) -> None:
    """The ``img2logo`` command against vtracer (and potrace on drawings) on ``CLI_IMAGES``, whole processes.

    Alternated run by run (ours, vtracer, potrace), so that a machine's load
    falls on all alike; wall and CPU (user + sys of the child) medians. vtracer
    runs in colour mode on clip arts and binary mode on drawings (what a user
    tracing a line drawing picks), from its own venv (:func:`bench_venv`).
    potrace (Debian's ``potrace``) reads a PBM made before the timing.
    """
    python = bench_venv()
    if python is None:
        page.say("\nvtracer is not available (no network for pip?): the command-line comparison is skipped")
        return
    potrace = shutil.which("potrace")
    page.say(
        f"\nThe command line against vtracer (whole processes, alternated, median of {repeat}); {_load()} at the "
        "start" + ("" if potrace else "; potrace is not installed (apt-get install potrace): its column is empty")
    )
    head = ("image", "kind", "arcs", "img2logo", "vtracer", "ratio", "CPU ours", "CPU vtr", "CPU ratio", "potrace")
    page.say(f"{head[0]:24s} {head[1]:8s} {head[2]:>5s} " + " ".join(f"{h:>9s}" for h in head[3:]))
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for path in CLI_IMAGES:
            kind = _kind(path)
            ours_cmd = [sys.executable, "-m", "img2logo.app.cli", str(path), "-q", "--svg", os.path.join(tmp, "o.svg")]
            mode = "binary" if kind == "drawing" else "color"
            code = (
                "import sys, vtracer; "
                f"vtracer.convert_image_to_svg_py(sys.argv[1], sys.argv[2], colormode='{mode}', mode='spline')"
            )
            theirs_cmd = [str(python), "-I", "-c", code, str(path), os.path.join(tmp, "v.svg")]
            cmds = [ours_cmd, theirs_cmd]
            if potrace and kind == "drawing":
                pbm = Path(tmp) / f"{path.stem}.pbm"
                _pbm(path, pbm)
                cmds.append([potrace, "-s", "-o", os.path.join(tmp, "p.svg"), str(pbm)])
            subprocess.run([*ours_cmd[:-2], "--json", os.path.join(tmp, "o.json")], check=True, capture_output=True)
            arcs = len(json.loads(Path(tmp, "o.json").read_text())["arcs"])
            wall, cpu = _alternated(cmds, repeat)
            row = {
                "image": path.stem,
                "kind": kind,
                "arcs": arcs,
                "ours": wall[0],
                "vtracer": wall[1],
                "ratio": wall[0] / wall[1],
                "cpu_ours": cpu[0],
                "cpu_vtracer": cpu[1],
                "cpu_ratio": cpu[0] / cpu[1],
                "potrace": wall[2] if len(wall) > 2 else None,
            }
            rows.append(row)
            pot = f"{row['potrace']:8.3f}s" if row["potrace"] is not None else f"{'-':>9s}"
            page.say(
                f"{row['image']:24s} {kind:8s} {arcs:5d} {wall[0]:8.2f}s {wall[1]:8.3f}s {row['ratio']:8.1f}x"
                f" {cpu[0]:8.2f}s {cpu[1]:8.3f}s {row['cpu_ratio']:8.1f}x {pot}"
            )
    ratios = [r["ratio"] for r in rows]
    cpu_ratios = [r["cpu_ratio"] for r in rows]
    page.say(
        f"worst ratio {max(ratios):.1f}x, median {statistics.median(ratios):.1f}x (targets: worst <= "
        f"{WORST_RATIO_TARGET:g}x, median <= {MEDIAN_RATIO_TARGET:g}x); CPU: worst {max(cpu_ratios):.1f}x, "
        f"median {statistics.median(cpu_ratios):.1f}x; {_load()} at the end"
    )
    page.table(
        "The command line against vtracer",
        ("image", "kind", "final arcs", "img2logo (s)", "vtracer (s)", "ratio", "CPU ratio", "potrace (s)"),
        [
            (
                r["image"],
                r["kind"],
                r["arcs"],
                f"{r['ours']:.2f}",
                f"{r['vtracer']:.3f}",
                f"{r['ratio']:.1f}x",
                f"{r['cpu_ratio']:.1f}x",
                "-" if r["potrace"] is None else f"{r['potrace']:.3f}",
            )
            for r in rows
        ],
        f"Whole processes, alternated run by run, medians of {repeat}. Worst ratio **{max(ratios):.1f}x**, median "
        f"**{statistics.median(ratios):.1f}x** (CPU time: worst {max(cpu_ratios):.1f}x, median "
        f"{statistics.median(cpu_ratios):.1f}x). vtracer: colour mode on clip arts, binary mode on drawings, "
        "spline paths, from its own venv started with `python -I`; potrace (drawings only) reads a PBM made before "
        "the timing.",
    )


def bench_growth(repeat: int, page: Page) -> None:
    """In-process time against |A^0| and the final arcs (``CLI_IMAGES``, ``BUSY_IMAGES``); the tiled series."""
    page.say(f"\nGrowth: abstract() in process (CPU s, median of {repeat} after a warm-up), against |A^0| and arcs")
    page.say(
        f"{'image':24s} {'|A^0|':>6s} {'final':>6s} {'CPU':>8s} {'loop':>8s} {'tangency':>8s} {'global':>7s} "
        f"{'wide':>5s}  stopped"
    )
    rows = []
    for path in (*CLI_IMAGES, *BUSY_IMAGES):
        abstract(path, progress=False)
        cpu, runs = [], []
        for _ in range(repeat):
            start = time.process_time()
            runs.append(abstract(path, progress=False))
            cpu.append(time.process_time() - start)
        r = runs[0]
        wall = sum(r.timings.values())
        row = (
            path.stem,
            r.progression.arc_counts[0],
            r.progression.arc_counts[-1],
            statistics.median(cpu),
            r.timings["loop"] / wall,
            r.timings["tangency"] / wall,
            r.progression.stats["global_solves"],
            r.progression.stats["wide_windows"],
            r.progression.stopped_because,
        )
        rows.append(row)
        page.say(
            f"{row[0]:24s} {row[1]:6d} {row[2]:6d} {row[3]:7.3f}s {row[4]:8.0%} {row[5]:8.0%} {row[6]:7d} {row[7]:5d}"
            f"  {row[8]}"
        )
    ten = rows[: len(CLI_IMAGES)]  # the line through the ten images (the busier ones grow faster: see their rows)
    arcs = np.array([r[2] for r in ten], dtype=float)
    a0 = np.array([r[1] for r in ten], dtype=float)
    cpu = np.array([r[3] for r in ten])
    slope, fixed = np.polyfit(arcs, cpu, 1)
    slope0, fixed0 = np.polyfit(a0, cpu, 1)
    fit = (
        f"least-squares line through the ten images of the comparison: {fixed * 1e3:.0f} ms + {slope * 1e3:.1f} ms "
        f"per final arc; {fixed0 * 1e3:.0f} ms + {slope0 * 1e3:.2f} ms per arc of A^0"
    )
    page.say(fit)
    page.table(
        "Growth with the drawing",
        ("image", "A^0 arcs", "final arcs", "CPU (s)", "merge loop", "tangent joins", "global solves", "wide windows"),
        [(r[0], r[1], r[2], f"{r[3]:.3f}", f"{r[4]:.0%}", f"{r[5]:.0%}", r[6], r[7]) for r in rows],
        f"`abstract()` in process, CPU time, medians of {repeat} after a warm-up; the loop's and the tangent "
        "joins' shares of its wall time; global solves (the initial fit, the tangent joins' joint refit) and "
        "merge candidates refitted in the wider window (`MERGE_FALLBACK_RINGS`) after their local window failed. "
        f"The last two rows are busier Openclipart clip arts (not in the comparison above). A {fit}.",
    )
    for image in (growth.TILED_IMAGE, growth.TILED_DRAWING):
        kind = "drawing" if image.stem.startswith("drawing") else "clip art"
        page.say(f"\nTiled: {image.name} at {growth.TILE_SIDE} px, copies side by side, optimize() only")
        page.say(growth.HEADER)
        tiled = growth.tiled_rows(image, repeat=repeat)
        bound = (
            " Eight copies of the clip art hold more regions than a clip art keeps (the `--detail` bound): its A^0 "
            "grows less than eight-fold, and its time with it; the tiled drawing has no such bound."
            if kind == "clip art"
            else ""
        )
        page.table(
            f"Growth on a tiled {kind}",
            ("copies", "size", "A^0 arcs", "final arcs", "CPU (s)", "per copy", "global solves", "stopped"),
            [
                (
                    t["copies"],
                    t["size"],
                    t["a0"],
                    t["final"],
                    f"{t['cpu']:.2f}",
                    f"{t['cpu'] / t['copies'] / tiled[0]['cpu']:.2f}",
                    t["global_solves"],
                    t["stopped"],
                )
                for t in tiled
            ],
            f"`python benchmarks/growth.py --image {image.relative_to(ROOT)}`: n copies at {growth.TILE_SIDE} px side "
            "by side, the segment graph optimized as it is (no downscale, no time budget, stopped at T: no arc "
            "budget), CPU time, medians of "
            f"{repeat}; 'per copy' is CPU per copy over one copy's (1.00: linear).{bound}",
        )


def bench_batch(repeat: int, page: Page) -> None:
    """``img2logo batch --jobs 2`` over ``BATCH_IMAGES`` as a whole process, against vtracer on two processes.

    The folder as a user gives it (every output of the batch written: SVG, JSON, PNG, the gallery and the
    summary); vtracer converts the same files in a pool of two processes of its own venv. Alternated run by
    run; medians of wall and CPU time (user + sys of the children). Images per second: images over wall time.
    """
    n = len(BATCH_IMAGES)
    python = bench_venv()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp) / "in"
        folder.mkdir()
        for path in BATCH_IMAGES:
            (folder / path.name).symlink_to(path)
        ours = [sys.executable, "-m", "img2logo.app.cli", "batch", str(folder), os.path.join(tmp, "out"), "-q"]
        cmds = [[*ours, "--jobs", "2"]]
        if python is not None:
            code = (
                "import sys, os, multiprocessing, vtracer\n"
                "def one(a):\n"
                "    src, out = a\n"
                "    mode = 'binary' if os.path.basename(src).startswith('drawing') else 'color'\n"
                "    vtracer.convert_image_to_svg_py(src, out, colormode=mode, mode='spline')\n"
                "if __name__ == '__main__':\n"
                "    files = sorted(os.listdir(sys.argv[1]))\n"
                "    jobs = [(os.path.join(sys.argv[1], f), os.path.join(sys.argv[2], f + '.svg')) for f in files]\n"
                "    with multiprocessing.Pool(2) as pool:\n"
                "        pool.map(one, jobs, chunksize=1)\n"
            )
            script = Path(tmp) / "vtracer_batch.py"
            script.write_text(code)
            (Path(tmp) / "vout").mkdir()
            cmds.append([str(python), "-I", str(script), str(folder), os.path.join(tmp, "vout")])
        page.say(f"\nBatch: {n} images, `img2logo batch --jobs 2` (median of {repeat}); {_load()} at the start")
        wall, cpu = _alternated(cmds, repeat)
    rate = n / wall[0]
    line = (
        f"img2logo batch --jobs 2: {wall[0]:.1f} s for {n} images, {rate:.1f} images/s (target >= {BATCH_TARGET:g}), "
        f"CPU {cpu[0]:.1f} s ({cpu[0] / n * 1e3:.0f} ms an image)"
    )
    if len(wall) > 1:
        line += f"; vtracer on 2 processes: {wall[1]:.1f} s, {n / wall[1]:.1f} images/s, CPU {cpu[1]:.1f} s"
    page.say(line + f"; {_load()} at the end")
    page.table(
        "Batch throughput",
        ("command", "images", "wall (s)", "images/s", "CPU (s)"),
        [("img2logo batch --jobs 2", n, f"{wall[0]:.1f}", f"{rate:.1f}", f"{cpu[0]:.1f}")]
        + (
            [("vtracer, 2 processes", n, f"{wall[1]:.1f}", f"{n / wall[1]:.1f}", f"{cpu[1]:.1f}")]
            if len(wall) > 1
            else []
        ),
        f"The {n} clip arts, drawings and held-out photo-likes of benchmarks/data/, heldout/ and heldout-photo/, "
        f"every output written (SVG, JSON, PNG, gallery); whole processes alternated, medians of {repeat}; the "
        f"target is {BATCH_TARGET:g} images/s on two cores.",
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


class Page:
    """What a run printed, and its main tables, for the docs' performance page (:data:`PAGE`)."""

    def __init__(self) -> None:
        self.text: list[str] = []
        self.tables: list[str] = []

    def say(self, text: str) -> None:
        print(text, flush=True)

    def table(self, title: str, head: Sequence[str], rows: Sequence[Sequence[object]], note: str) -> None:
        lines = [f"## {title}", "", note, "", "| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
        lines += ["| " + " | ".join(str(v) for v in row) + " |" for row in rows]
        self.tables.append("\n".join(lines))

    def write(self, path: Path, command: str, started: datetime.datetime, repeat: int, load: float) -> None:
        cores = os.cpu_count() or 1
        busy = (
            f"The machine was busy (load average {load:.1f} at the start, {os.getloadavg()[0]:.1f} at the end, "
            f"on {cores} cores): the wall times are inflated, compare the CPU columns."
            if max(load, os.getloadavg()[0]) > 0.5 * cores
            else f"Load average {load:.1f} at the start, {os.getloadavg()[0]:.1f} at the end, on {cores} cores."
        )
        head = [
            "# Performance",
            "",
            f"Generated by `{command}` on {started:%Y-%m-%d %H:%M} UTC (do not edit: `make bench` writes it again), "
            f"{platform.processor() or platform.machine()}, Python {platform.python_version()}, medians of "
            f"{repeat}. {busy} A run stops merging at its time budget (`--time-budget`, default "
            f"{TIME_BUDGET:g} s of CPU from its start) with a warning; the 'stopped' column of the growth output "
            "says whether it did here.",
            "",
        ]
        body = "\n\n".join(self.tables)
        out = "\n".join([*head, body, "", "## The whole output", "", "```text", "".join(self.text).rstrip(), "```", ""])
        part = path.with_suffix(".md.part")
        part.write_text(out)
        part.replace(path)  # whole or not at all


class _Tee:
    """Standard output that the page keeps a copy of."""

    def __init__(self, out: TextIO, page: Page) -> None:
        self.out, self.page = out, page

    def write(self, text: str) -> int:
        self.page.text.append(text)
        return self.out.write(text)

    def flush(self) -> None:
        self.out.flush()


SECTIONS = ("preprocessing", "pipeline", "table3", "startup", "cli", "growth", "batch", "photo")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument(
        "--only",
        default=",".join(SECTIONS),
        help=f"sections, comma-separated, of {','.join(SECTIONS)}; "
        f"the page ({PAGE.relative_to(ROOT)}) is written only when every section ran",
    )
    args = parser.parse_args()
    only = set(args.only.split(","))
    if only - set(SECTIONS):
        parser.error(f"--only takes sections of {','.join(SECTIONS)}, got {args.only!r}")
    started, load = datetime.datetime.now(datetime.UTC), os.getloadavg()[0]
    page = Page()
    stdout, sys.stdout = sys.stdout, _Tee(sys.stdout, page)  # type: ignore[assignment]
    try:
        if "preprocessing" in only:
            names = ["clipart-fish", "clipart-cat", "drawing-fish", "drawing-rabbit", "photo-cat"]
            bench_preprocessing(names, args.repeat)
        if "pipeline" in only:
            bench_pipeline("clipart-fish", args.repeat, budget=FISH_BUDGET)
            giraffe = BENCHMARK_DATA / "clipart-giraffe.png"
            bench_pipeline(giraffe.stem, args.repeat, giraffe, MANY_ARCS_BUDGET)
            for photo in (BENCHMARK_DATA / "photo-teddy-bear.png", DATA / "photo-flower.png"):
                bench_pipeline(photo.stem, args.repeat, photo, PHOTO_PIPELINE_BUDGET)
        if "table3" in only:
            bench_table3("clipart-fish", max(1, args.repeat // 2))
        if "startup" in only:
            bench_startup(args.repeat)
            bench_command_parts(args.repeat, page)
        if "cli" in only:
            bench_cli_vs_vtracer(args.repeat, page)
        if "growth" in only:
            bench_growth(args.repeat, page)
        if "batch" in only:
            bench_batch(max(1, args.repeat // 2), page)
        if "photo" in only:
            bench_cli_photo(args.repeat)
    finally:
        sys.stdout = stdout
    if only == set(SECTIONS):
        command = "make bench" if args.repeat == 5 else f"python benchmarks/bench.py --repeat {args.repeat}"
        page.write(PAGE, command, started, args.repeat, load)
        print(f"wrote {PAGE.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
