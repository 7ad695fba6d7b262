"""The batch's worker and its pool: one image as plain values, on any executor (:mod:`img2logo.app.batch.run`).

:func:`process_image` abstracts one image and returns its files as bytes and its
numbers, never raising for a bad image; :func:`run_tasks` runs it for a list of
images on a :class:`concurrent.futures.Executor`, by default a process pool of its
own whose workers end with their parent, retrying the images of a pool that broke
(a worker killed by the out-of-memory killer) in a fresh one, then one at a time.
"""

from __future__ import annotations

import contextlib
import gc
import os
import sys
import threading
import time
import warnings
from collections.abc import Callable, Iterator, Mapping, Sequence
from concurrent.futures import Executor, Future, as_completed
from pathlib import Path
from typing import Any

from ...errors import Img2LogoError, InvalidParameterError
from ...options import Options
from ..kind_options import ignored_options, kind_options

__all__ = ["OUTPUT_FORMATS", "BatchProgress", "one_line", "process_image", "run_tasks"]

#: The files written per image, by suffix.
OUTPUT_FORMATS: tuple[str, ...] = ("svg", "json", "png")

#: Signature of a progress callback: (images done, images in all, name of the last one).
BatchProgress = Callable[[int, int, str], None]

# matplotlib's style context (used by the PNG writer) is global state: within one
# process, files are written one at a time (it matters for a ThreadPoolExecutor).
_WRITE_LOCK = threading.Lock()


# --------------------------------------------------------------------------- the worker
def process_image(
    path: str,
    options: Options | Mapping[str, Any] | None = None,
    outputs: Sequence[str] = OUTPUT_FORMATS,
    fill: str = "none",
) -> dict[str, Any]:
    """Abstract one image; return its files and numbers as plain values (the batch worker).

    Module-level and picklable, it takes and returns only plain values, so any
    :class:`concurrent.futures.Executor` (processes, threads, a dask cluster)
    can run it. It never raises for a bad image: the error is returned.

    Parameters
    ----------
    path : str
        The input image.
    options : Options or mapping, optional
        The options of :func:`img2logo.abstract` (:class:`~img2logo.options.Options`,
        or its keywords: ``tolerance``, ``kind``, ``ladder``, ...).
    outputs : sequence of {"svg", "json", "png"}
        The files to make, as :func:`img2logo.export.writers.write` writes them (the PNG over
        the faded input), made in memory by :func:`img2logo.export.writers.encode`.
    fill : str
        The ``--fill`` option (:func:`img2logo.design.fills.parse_fill_option`).

    Returns
    -------
    dict
        ``image`` (file name), ``path``, ``seconds``, ``warnings`` (list of str)
        and either ``error`` (the one-line message) or ``kind``, ``arcs``,
        ``levels``, ``similarity`` and ``files`` (suffix -> bytes).
    """
    start = time.perf_counter()
    name = Path(path).name
    record = threading.current_thread() is threading.main_thread()
    caught: list[warnings.WarningMessage] = []
    try:
        if record:  # warnings.catch_warnings is process-wide: only outside thread pools
            with warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                out = _process(path, options, tuple(outputs), fill)
        else:
            out = _process(path, options, tuple(outputs), fill)
    except Exception as exc:  # a batch keeps going past a bad file
        out = {"error": one_line(exc)}
    seen = dict.fromkeys(" ".join(str(w.message).split()) for w in caught)
    return {"image": name, "path": str(path), "seconds": time.perf_counter() - start, "warnings": list(seen), **out}


def _process(
    path: str, options: Options | Mapping[str, Any] | None, outputs: tuple[str, ...], fill: str
) -> dict[str, Any]:
    from ...design.fills import parse_fill_option
    from ...export import writers
    from ...pipeline import abstract

    spec = parse_fill_option(fill)
    if not isinstance(options, Options):
        options = Options.from_keywords(options or {})
    result = abstract(path, options=options, progress=False)
    final = result.final
    for ignored in ignored_options(result.lines, kind_options(options)):
        warnings.warn(ignored, UserWarning, stacklevel=2)
    fills = None if spec.mode == "none" else spec.make(final, result.image)
    files: dict[str, bytes] = {}
    with _WRITE_LOCK:  # in memory: the calling process writes the files
        for fmt in outputs:
            files[fmt] = writers.encode(final, fmt, fills=fills, image=result.image.rgb)
    return {
        "kind": result.lines.kind,
        "arcs": len(final.arcs),
        "levels": len(result.progression.levels),  # without making every level
        "similarity": float(final.similarity),
        "symmetry": _symmetry_cell(result.symmetry),
        "files": files,
    }


def _symmetry_cell(choice: Any) -> str:
    """The summary's symmetry cell of a :class:`~img2logo.fit.symmetry_axis.SymmetryChoice` (None: not asked for)."""
    if choice is None:
        return ""
    if choice.axis is None:
        return f"free, score {choice.best.score:.2f}"
    return f"{choice.axis.angle:.1f} deg, score {choice.axis.score:.2f}"


def one_line(exc: BaseException) -> str:
    """The exception's message on one line; its type is named unless it is one of ours."""
    text = " ".join(str(exc).split())
    if not isinstance(exc, Img2LogoError):
        text = f"{type(exc).__name__}: {text}" if text else type(exc).__name__
    return text


def _init_worker(parent: int | None = None) -> None:
    """Initializer of the default process pool's workers.

    One thread per worker (the pool uses the cores). A worker ends when its
    parent ends, however it ends: on Linux by the parent-death signal
    (``prctl(PR_SET_PDEATHSIG, SIGKILL)``), elsewhere by a thread that watches
    the parent's process id. Ctrl-C reaches the whole process group: the
    workers ignore it and the parent, which handles it, stops them.
    """
    import signal

    if parent is not None:
        _die_with_parent(parent)
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # not the command line's handler, inherited by fork
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
        os.environ.setdefault(var, "1")
    try:
        import cv2

        cv2.setNumThreads(1)
    except ImportError:  # pragma: no cover - a dependency
        pass
    # The modules loaded before the fork (:func:`_warm`) live as long as the worker: out of the cyclic
    # collector's sight, its collections walk only the objects of the images run here.
    gc.freeze()


def _die_with_parent(parent: int) -> None:
    """End this process (SIGKILL) when process ``parent`` ends; it may have ended already."""
    import signal

    if sys.platform.startswith("linux"):
        import ctypes

        pr_set_pdeathsig = 1
        try:
            libc = ctypes.CDLL(None, use_errno=True)
            armed = libc.prctl(pr_set_pdeathsig, int(signal.SIGKILL), 0, 0, 0) == 0
        except (OSError, AttributeError):  # pragma: no cover - no prctl
            armed = False
        if os.getppid() != parent:  # the parent died before the signal was armed
            os._exit(1)
        if armed:
            return

    def watch() -> None:  # pragma: no cover - not Linux
        while os.getppid() == parent:
            time.sleep(1.0)
        os._exit(1)

    threading.Thread(target=watch, name="img2logo-parent-watch", daemon=True).start()


def _stop_workers(pool: Executor) -> None:
    """Kill the processes of a ProcessPoolExecutor made here (leaving on an error or an interrupt)."""
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        with contextlib.suppress(Exception):
            proc.kill()
    for proc in list((getattr(pool, "_processes", None) or {}).values()):
        with contextlib.suppress(Exception):
            proc.join(timeout=5)


def run_tasks(
    tasks: list[tuple[Any, ...]],
    executor: Executor | None,
    jobs: int | None,
    progress: BatchProgress | bool | None,
    on_result: Callable[[int, dict[str, Any]], None] | None = None,
    notes: list[str] | None = None,
) -> list[dict[str, Any]]:
    """Run ``process_image(*task)`` for every task; results in task order.

    ``on_result(i, result)`` is called here, in the calling thread, as each
    task finishes. An executor failure (a crashed worker) becomes that task's
    error, marked ``lost``: no fault of the image. When a worker of the default
    pool dies (killed by a signal, e.g. by the out-of-memory killer) the pool is
    broken: the unfinished tasks run again in a fresh pool; after a second break
    each runs alone in a pool of its own, so that only a task that kills its
    own worker fails. ``notes`` gets one line per break.
    """
    if jobs is not None:
        if isinstance(jobs, bool) or not isinstance(jobs, int) or jobs < 1:
            raise InvalidParameterError(f"jobs must be an integer >= 1, got {jobs!r}")
    total = len(tasks)
    results: list[dict[str, Any] | None] = [None] * total
    bar: list[Any] = [_silent, _nothing, False, 0]  # tick, close, started, images done

    def start_bar() -> None:
        if not bar[2]:
            bar[0], bar[1] = _progress(progress, total)
            bar[2] = True

    def finish(i: int, result: dict[str, Any]) -> None:
        results[i] = result
        if on_result is not None:
            on_result(i, result)
        bar[3] += 1
        bar[0](bar[3], total, result["image"])

    try:
        workers = min(jobs or os.cpu_count() or 1, total)
        if executor is None and workers <= 1:
            start_bar()
            for i, task in enumerate(tasks):
                finish(i, process_image(*task))
        elif executor is not None:
            _run_on(executor, tasks, list(range(total)), finish, start_bar, own=False)
        else:
            pending, breaks = list(range(total)), 0
            while pending:
                alone = breaks >= _POOL_BREAKS_BEFORE_ALONE
                broken: list[int] = []
                for chunk in [[i] for i in pending] if alone else [pending]:
                    pool = _default_pool(min(workers, len(chunk)), drawn=any("png" in t[2] for t in tasks))
                    lost = _run_on(pool, tasks, chunk, finish, start_bar, own=True)
                    if alone and lost:  # this task, alone in its pool, killed its worker
                        finish(lost[0], _lost(tasks[lost[0]], _WORKER_DIED))
                    else:
                        broken.extend(lost)
                pending = sorted(broken)
                if pending:
                    breaks += 1
                    if notes is not None:
                        again = "each alone" if breaks >= _POOL_BREAKS_BEFORE_ALONE else "in a fresh pool"
                        notes.append(
                            f"a worker process died ({_WORKER_DIED}); "
                            f"{len(pending)} unfinished images run again {again}"
                        )
    finally:
        bar[1]()
    return [r for r in results if r is not None]


#: Breaks of the default pool after which the unfinished images run one at a time, each in a pool of its own.
_POOL_BREAKS_BEFORE_ALONE = 2
_WORKER_DIED = "killed by a signal, e.g. by the out-of-memory killer"


def _lost(task: tuple[Any, ...], why: str) -> dict[str, Any]:
    """The result of a task whose worker was lost: an error that is no fault of the image (``lost``)."""
    return {
        "image": Path(task[0]).name,
        "path": task[0],
        "seconds": 0.0,
        "error": f"the worker process running it was lost ({why}); its earlier outputs are kept",
        "lost": True,
    }


def _run_on(
    pool: Executor,
    tasks: list[tuple[Any, ...]],
    indices: list[int],
    finish: Callable[[int, dict[str, Any]], None],
    start_bar: Callable[[], None],
    *,
    own: bool,
) -> list[int]:
    """Run the tasks ``indices`` on ``pool``, calling ``finish(i, result)`` as each ends.

    With ``own`` (a pool made here) the pool is shut down at the end, and the
    tasks whose pool broke (a worker died) are returned, not finished; with
    another executor, its failure is the task's (lost) error.
    """
    from concurrent.futures import BrokenExecutor

    broken: list[int] = []
    finished = False
    try:
        # A forked worker inherits OpenCV's thread pool without its threads: its
        # cv2.setNumThreads(1) would wait for them forever. The workers are forked at the
        # first submit, so OpenCV runs single-threaded here until all are submitted.
        with _opencv_threads(1 if own else None):
            futures: dict[Future[dict[str, Any]], int] = {pool.submit(process_image, *tasks[i]): i for i in indices}
        start_bar()  # a thread: only now, so that a forked worker does not inherit it
        for future in as_completed(futures):
            i = futures[future]
            try:
                result = future.result()
            except Exception as exc:  # the executor failed, not the image (a worker died)
                if own and isinstance(exc, BrokenExecutor):
                    broken.append(i)
                    continue
                result = _lost(tasks[i], one_line(exc))
                result["error"] = one_line(exc)
            finish(i, result)
        finished = True
    finally:
        if own:
            if not finished:  # an error or an interrupt: do not wait for the images running
                _stop_workers(pool)
            pool.shutdown(wait=finished, cancel_futures=True)
    return broken


@contextlib.contextmanager
def _opencv_threads(n: int | None) -> Iterator[None]:
    """Run the block with OpenCV on ``n`` threads (None: as it is), then restore its setting."""
    if n is None:
        yield
        return
    import cv2

    before = cv2.getNumThreads()
    cv2.setNumThreads(n)
    try:
        yield
    finally:
        cv2.setNumThreads(before)


def _default_pool(workers: int, *, drawn: bool = True) -> Executor:
    """A ProcessPoolExecutor of ``workers`` processes, by the platform's default start method.

    That is fork on Linux before Python 3.14: a script without an ``if __name__ ==
    "__main__":`` guard works, and the workers start warm (:func:`_warm`; ``drawn``:
    the PNG's modules too). Where it is spawn or forkserver, the guard is needed.
    """
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor

    if multiprocessing.get_start_method() == "fork":
        _warm(drawn=drawn)
    return ProcessPoolExecutor(max_workers=workers, initializer=_init_worker, initargs=(os.getpid(),))


def _warm(*, drawn: bool) -> None:
    """Load in this process what every image's run loads (the pipeline, the writers, the compiled kernels, OpenCV).

    The workers forked from it start with them loaded: each saves their load
    (about 0.15 s of CPU; 10 small drawings on two workers: 4.2 -> 3.9 s of CPU in all).
    With ``drawn`` (PNGs are made) also matplotlib's Agg canvas and Pillow's PNG encoder:
    about 0.5 s of CPU that every worker would spend on its first PNG.
    """
    import cv2  # noqa: F401

    from ..._compiled import kernels
    from ...export import writers  # noqa: F401
    from ...pipeline import abstract  # noqa: F401

    kernels.usable()
    if drawn:
        import matplotlib.backends.backend_agg
        import matplotlib.collections
        import matplotlib.figure
        import matplotlib.style  # noqa: F401
        from PIL import Image

        Image.preinit()  # the encoders a first PNG would load


def _progress(progress: BatchProgress | bool | None, total: int) -> tuple[BatchProgress, Callable[[], None]]:
    """The progress callback and a function closing its bar (see :func:`run_batch`)."""
    if callable(progress):
        return progress, _nothing
    if progress is False or (progress is None and not sys.stderr.isatty()):
        return _silent, _nothing
    from tqdm.auto import tqdm

    bar = tqdm(total=total, desc="images", unit="image", file=sys.stderr, leave=False)

    def tick(done: int, n: int, image: str) -> None:
        bar.n = done
        bar.set_postfix_str(image, refresh=True)

    return tick, bar.close


def _silent(done: int, total: int, image: str) -> None:
    """A progress callback that shows nothing."""


def _nothing() -> None:
    """Nothing to close."""
