"""Batch runs: every image of a folder, on all cores or on any executor (beyond the paper).

:func:`run_batch` abstracts a list of images with :func:`img2logo.abstract` and
writes, for each, ``OUTPUT_DIR/<stem>.svg``, ``.json`` and ``.png`` (the same files
as ``img2logo INPUT --svg --json --png``), then ``OUTPUT_DIR/summary.csv``: one row
per image (``image, kind, arcs, levels, similarity, symmetry, seconds, error``; a text
cell that a spreadsheet would run as a formula is quoted). A file that
fails (unreadable, blank, ...) does not stop the others: it is reported in
:attr:`BatchReport.failures` with its one-line error message, and its outputs of an
earlier run are removed if img2logo wrote them (``OUTPUT_DIR/.img2logo-outputs``
lists the files it wrote). While a batch runs, it holds ``OUTPUT_DIR/.img2logo-batch.lock``:
a second batch on the same folder is refused. A worker of the default pool that
is killed (the out-of-memory killer) loses nothing: its pool's unfinished images
run again in a fresh one. :func:`sweep` runs a
grid of parameters over images and returns the table (for the notebooks).

The work is done by :func:`process_image`, a module-level function that takes and
returns plain values (a path, a dict of options; a dict with the file contents as
bytes), so that any :class:`concurrent.futures.Executor` can run it:

- by default a local :class:`~concurrent.futures.ProcessPoolExecutor` with
  ``os.cpu_count()`` workers (``jobs`` to change it; ``jobs=1`` runs in this process);
- a :class:`~concurrent.futures.ThreadPoolExecutor` (mostly for tests: the work
  is Python-bound and holds the GIL);
- a cluster: ``run_batch(paths, out, executor=client.get_executor())`` with a
  ``dask.distributed.Client`` (or any other executor). The workers read the input
  images, so they must see the paths (a shared file system); the results come
  back as bytes and are written by the calling process, so the output folder need
  not be shared.

The results do not depend on the executor: every image is processed alone and
deterministically, the files are byte-identical, and rows are in input order.
"""

from __future__ import annotations

import contextlib
import dataclasses
import os
import sys
import tempfile
import threading
import time
import warnings
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from concurrent.futures import Executor, Future, as_completed
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, NoReturn

from ._validation import check_choice
from .errors import Img2LogoError, InvalidParameterError
from .options import Options

if TYPE_CHECKING:
    import pandas as pd

__all__ = [
    "IMAGE_SUFFIXES",
    "OUTPUT_FORMATS",
    "SUMMARY_COLUMNS",
    "BatchFailure",
    "BatchProgress",
    "BatchReport",
    "BatchRow",
    "SkippedEntryWarning",
    "find_images",
    "ignored_subject_options",
    "process_image",
    "run_batch",
    "sweep",
]

#: File suffixes (lower case) of the images a folder run picks up.
IMAGE_SUFFIXES: tuple[str, ...] = (".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".webp")
#: The files written per image, by suffix.
OUTPUT_FORMATS: tuple[str, ...] = ("svg", "json", "png")
#: Columns of ``summary.csv`` and of :meth:`BatchReport.to_frame`.
SUMMARY_COLUMNS: tuple[str, ...] = ("image", "kind", "arcs", "levels", "similarity", "symmetry", "seconds", "error")

#: Signature of a progress callback: (images done, images in all, name of the last one).
BatchProgress = Callable[[int, int, str], None]

# matplotlib's style context (used by the PNG writer) is global state: within one
# process, files are written one at a time (it matters for a ThreadPoolExecutor).
_WRITE_LOCK = threading.Lock()


# --------------------------------------------------------------------------- results
@dataclass(frozen=True)
class BatchRow:
    """One image abstracted.

    Attributes
    ----------
    image : str
        The input's file name.
    path : str
        The input's path, as given.
    kind : str
        The kind of input used (``"photo"``, ``"clipart"``, ``"drawing"``).
    arcs : int
        |A| of the final level.
    levels : int
        The number of levels A^0 ... A^final.
    similarity : float
        E^s of the final level (paper Eqn. 3), px.
    seconds : float
        Wall time for the image: loading, the abstraction and the files.
    outputs : tuple of str
        The files written.
    symmetry : str
        What ``symmetry=...`` decided: the mirror axis used and its score
        (``"90.0 deg, score 0.99"``), ``"free, score 0.57"`` when ``auto``
        found no axis good enough, or ``""`` when symmetry was not asked for.
    """

    image: str
    path: str
    kind: str
    arcs: int
    levels: int
    similarity: float
    seconds: float
    outputs: tuple[str, ...] = ()
    symmetry: str = ""


@dataclass(frozen=True)
class BatchFailure:
    """One image that failed: its file name, its path as given and the one-line error message."""

    image: str
    path: str
    message: str

    @property
    def line(self) -> str:
        """The message naming the file: ``"<path>: <message>"``, the path not repeated."""
        return self.message if self.message.startswith(self.path) else f"{self.path}: {self.message}"


@dataclass(frozen=True)
class BatchReport:
    """The outcome of :func:`run_batch`.

    Attributes
    ----------
    rows : tuple of BatchRow
        The images done, in input order.
    failures : tuple of BatchFailure
        The images that failed, in input order.
    inputs : tuple of str
        Every input path, in input order (the order of :meth:`to_frame`).
    warnings : tuple of str
        ``"<image>: <message>"`` for every warning a run gave (e.g. an image
        downscaled), in input order. Not collected under a thread pool
        (Python's warning capture is not thread-safe): they are printed there.
    summary_path : str or None
        The ``summary.csv`` written, if any.
    """

    rows: tuple[BatchRow, ...]
    failures: tuple[BatchFailure, ...]
    inputs: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    summary_path: str | None = None

    @property
    def ok(self) -> bool:
        """True when no image failed."""
        return not self.failures

    def to_frame(self) -> pd.DataFrame:
        """The summary table: one row per image (failed ones with their ``error``), ``SUMMARY_COLUMNS``."""
        import pandas as pd

        keyed = [
            (
                r.path,
                {
                    "image": r.image,
                    "kind": r.kind,
                    "arcs": r.arcs,
                    "levels": r.levels,
                    "similarity": r.similarity,
                    "symmetry": r.symmetry,
                    "seconds": r.seconds,
                    "error": "",
                },
            )
            for r in self.rows
        ]
        keyed += [(f.path, {"image": f.image, "error": f.message}) for f in self.failures]
        order = {path: i for i, path in enumerate(self.inputs)}
        keyed.sort(key=lambda item: order.get(item[0], len(order)))  # stable: rows before failures otherwise
        table = pd.DataFrame.from_records([rec for _, rec in keyed], columns=list(SUMMARY_COLUMNS))
        return table.astype({"arcs": "Int64", "levels": "Int64"})

    def summary(self, *, failures: bool = True) -> str:
        """The summary as a text table: image, kind, arcs, E^s, (symmetry,) seconds; then the failures.

        The symmetry column is shown when some image was run with ``symmetry``;
        the failures are left out when ``failures`` is False.
        """
        head = ("image", "kind", "arcs", "E^s (px)", "symmetry", "seconds")
        from ._io import printable

        body = [
            (printable(r.image), r.kind, str(r.arcs), f"{r.similarity:.2f}", r.symmetry, f"{r.seconds:.1f}")
            for r in self.rows
        ]
        align = ("<", "<", ">", ">", "<", ">")
        if not any(r.symmetry for r in self.rows):
            head, align, body = head[:4] + head[5:], align[:4] + align[5:], [row[:4] + row[5:] for row in body]
        widths = [max(len(row[i]) for row in [head, *body]) for i in range(len(head))]

        def line(row: Sequence[str]) -> str:
            return "  ".join(f"{cell:{a}{w}}" for cell, a, w in zip(row, align, widths, strict=True)).rstrip()

        lines = [line(head), line(["-" * w for w in widths]), *(line(row) for row in body)]
        total = len(self.rows) + len(self.failures)
        seconds = sum(r.seconds for r in self.rows)
        lines.append(f"{len(self.rows)} of {total} images done, {seconds:.1f} s of work")
        if self.failures and failures:
            lines.append(f"{len(self.failures)} failed:")
            lines.extend(f"  {printable(f.line)}" for f in self.failures)
        return "\n".join(lines)


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
        The files to make, as :func:`img2logo.writers.write_svg`,
        :func:`~img2logo.writers.write_json` and :func:`~img2logo.writers.write_png`
        (over the faded input) write them.
    fill : str
        The ``--fill`` option (:func:`img2logo.fills.parse_fill_option`).

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
        out = {"error": _one_line(exc)}
    seen = dict.fromkeys(" ".join(str(w.message).split()) for w in caught)
    return {"image": name, "path": str(path), "seconds": time.perf_counter() - start, "warnings": list(seen), **out}


def _process(
    path: str, options: Options | Mapping[str, Any] | None, outputs: tuple[str, ...], fill: str
) -> dict[str, Any]:
    from . import writers
    from .fills import parse_fill_option
    from .pipeline import abstract

    spec = parse_fill_option(fill)
    if not isinstance(options, Options):
        options = Options.from_keywords(options or {})
    result = abstract(path, options=options, progress=False)
    final = result.final
    fg = options.foreground
    given = (
        [] if isinstance(fg, str) and fg == "auto" else [f"--foreground {fg if isinstance(fg, str | Path) else 'MASK'}"]
    )
    ignored = ignored_subject_options(result.lines, given)
    if ignored:
        warnings.warn(ignored, UserWarning, stacklevel=2)
    fills = None if spec.mode == "none" else spec.make(final, result.image)
    files: dict[str, bytes] = {}
    if outputs:
        with _WRITE_LOCK, tempfile.TemporaryDirectory(prefix="img2logo-") as tmp:
            for fmt in outputs:
                target = Path(tmp) / f"logo.{fmt}"
                if fmt == "svg":
                    writers.write_svg(final, target, fills=fills)
                elif fmt == "json":
                    writers.write_json(final, target, fills=fills)
                else:
                    writers.write_png(final, target, image=result.image.rgb, fills=fills)
                files[fmt] = target.read_bytes()
    return {
        "kind": result.lines.kind,
        "arcs": len(final.arcs),
        "levels": len(result.levels),
        "similarity": float(final.similarity),
        "symmetry": _symmetry_cell(result.symmetry),
        "files": files,
    }


def ignored_subject_options(lines: Any, given: Sequence[str]) -> str | None:
    """The warning that the subject options ``given`` (``"--subject 1,2,3,4"``) are ignored, or None.

    Only a photo has a subject to find (:mod:`img2logo.subject`); for clip art
    and drawings every line is drawn, so ``foreground`` and ``subject`` do nothing.
    ``lines`` is the run's :class:`~img2logo.preprocessing.FeatureLines`.
    """
    if not given or lines.kind == "photo":
        return None
    which = " and ".join(given)
    verb = "is" if len(given) == 1 else "are"
    return (
        f"{which} {verb} ignored: the image is {lines.kind} ({lines.reason}), and only a photo has a subject "
        "to find (give --kind photo to treat it as one)"
    )


def _symmetry_cell(choice: Any) -> str:
    """The summary's symmetry cell of a :class:`~img2logo.symmetry.SymmetryChoice` (None: not asked for)."""
    if choice is None:
        return ""
    if choice.axis is None:
        return f"free, score {choice.best.score:.2f}"
    return f"{choice.axis.angle:.1f} deg, score {choice.axis.score:.2f}"


def _one_line(exc: BaseException) -> str:
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


# --------------------------------------------------------------------------- running
def find_images(folder: str | os.PathLike[str]) -> list[Path]:
    """The images directly in ``folder`` (suffixes ``IMAGE_SUFFIXES``, any case), sorted by name.

    An entry named like an image that is no regular file (a dangling link, a
    FIFO, a socket, a device, a folder) is skipped and reported in one
    :class:`SkippedEntryWarning` that counts and names them; it is never
    opened (a FIFO would block).

    Raises
    ------
    InvalidParameterError
        If ``folder`` is not a directory or holds no image.
    """
    root = Path(folder)
    if not root.is_dir():
        raise InvalidParameterError(f"input folder not found: {root}")
    found, skipped = [], []
    with os.scandir(root) as entries:
        for entry in entries:
            if Path(entry.name).suffix.lower() not in IMAGE_SUFFIXES:
                continue
            if entry.is_file():  # stat only (links followed): nothing is opened
                found.append(root / entry.name)
            else:
                skipped.append((entry.name, _entry_kind(entry)))
    if skipped:
        from ._io import printable

        names = ", ".join(f"'{printable(name)}' ({kind})" for name, kind in sorted(skipped))
        warnings.warn(
            f"{root}: skipped {len(skipped)} {'entry' if len(skipped) == 1 else 'entries'} named like images "
            f"that are no regular files: {names}",
            SkippedEntryWarning,
            stacklevel=2,
        )
    found.sort(key=lambda p: p.name)
    if not found:
        kinds = ", ".join(s.lstrip(".") for s in IMAGE_SUFFIXES)
        raise InvalidParameterError(f"no images ({kinds}) in {root}")
    return found


class SkippedEntryWarning(UserWarning):
    """:func:`find_images` skipped entries named like images that are no regular files."""


def _entry_kind(entry: os.DirEntry[str]) -> str:
    """What a directory entry that is no regular file is: a dangling link, a FIFO, a folder, ..."""
    import stat

    try:
        mode = entry.stat().st_mode
    except OSError:
        return "a dangling link" if entry.is_symlink() else "unreadable"
    for test, kind in (
        (stat.S_ISDIR, "a folder"),
        (stat.S_ISFIFO, "a FIFO"),
        (stat.S_ISSOCK, "a socket"),
        (stat.S_ISCHR, "a character device"),
        (stat.S_ISBLK, "a block device"),
    ):
        if test(mode):
            return kind
    return "not a regular file"  # pragma: no cover


def run_batch(
    paths: Iterable[str | os.PathLike[str]],
    output_dir: str | os.PathLike[str],
    *,
    executor: Executor | None = None,
    jobs: int | None = None,
    progress: BatchProgress | bool | None = None,
    outputs: Sequence[str] = OUTPUT_FORMATS,
    fill: str = "none",
    summary: bool = True,
    options: Options | None = None,
    **settings: Any,
) -> BatchReport:
    """Abstract every image of ``paths``, writing ``output_dir/<stem>.svg``, ``.json``, ``.png``.

    Each image is processed by :func:`process_image` on ``executor``; the files
    come back as bytes and are written here, atomically, as the images finish.
    A failing image is reported, never raised. The files are the same bytes
    whatever the executor, and the report's rows are in input order.

    Parameters
    ----------
    paths : iterable of str or path-like
        The input images, e.g. :func:`find_images` of a folder.
    output_dir : str or path-like
        Where the files go; created if missing. Two inputs with the same stem
        (``a.png``, ``a.jpg``) are written as ``a-png.*`` and ``a-jpg.*``.
    executor : concurrent.futures.Executor, optional
        Runs the images. Default: a ProcessPoolExecutor of ``jobs`` workers,
        made and shut down here. Any executor works: a ThreadPoolExecutor, or on
        a cluster a dask.distributed client's ``client.get_executor()`` (the
        workers must be able to read ``paths``). It is not shut down.
    jobs : int, optional
        Workers of the default pool (>= 1); default ``os.cpu_count()``. With 1
        (or a single image) the images run here, one after the other. Ignored
        when ``executor`` is given.
    progress : callable, bool or None
        ``progress(done, total, image)`` after every image; ``True`` shows a
        tqdm bar on standard error; ``None`` (default) shows it only when
        standard error is a terminal; ``False`` shows nothing.
    outputs : sequence of {"svg", "json", "png"}
        The files to write per image.
    fill : str
        Colour the regions (paper Fig. 18): the ``--fill`` option's syntax,
        e.g. ``"auto"`` (:func:`img2logo.fills.parse_fill_option`).
    summary : bool
        Write ``output_dir/summary.csv`` (:meth:`BatchReport.to_frame`).
    options : Options, optional
        The options of every image (:class:`~img2logo.options.Options`).
    **settings
        Fields of :class:`~img2logo.options.Options` (``tolerance``, ``kind``,
        ``ladder``, the switches, ...), replacing those of ``options``.

    Returns
    -------
    BatchReport

    Raises
    ------
    InvalidParameterError
        Before any work, if an option is unknown or out of range, ``outputs``
        names an unknown format, ``jobs`` < 1, or ``paths`` is empty.

    Examples
    --------
    >>> report = run_batch(find_images("data"), "out", tolerance=7.0, ladder="fibonacci")  # doctest: +SKIP
    >>> from dask.distributed import Client  # doctest: +SKIP
    >>> with Client("scheduler:8786") as client:  # doctest: +SKIP
    ...     report = run_batch(find_images("/shared/in"), "out", executor=client.get_executor())
    """
    inputs = [Path(p) for p in paths]
    if not inputs:
        raise InvalidParameterError("paths must name at least one image, got none")
    formats = _check_outputs(outputs)
    opts = _check_options(settings, fill, options)
    out_dir = Path(output_dir)
    stems = _output_stems(inputs)
    mask = _foreground_file(opts.foreground)
    _check_targets([*inputs, *([mask] if mask else [])], out_dir, stems, formats, summary)
    _check_output_folder(inputs, out_dir)
    tasks = [(str(p), opts, formats, fill) for p in inputs]

    with _batch_lock(out_dir):
        manifest = _read_manifest(out_dir)
        written: dict[int, tuple[str, ...]] = {}
        notes: list[str] = []

        def write(i: int, result: dict[str, Any]) -> None:
            from ._io import atomic_write, output_set

            files = result.get("files") or {}
            if "error" in result:
                if not result.get("lost"):  # an image that now fails keeps no result of an earlier run
                    for name in _remove_old_outputs(out_dir, stems[i], formats, manifest):
                        manifest.discard(name)
                return  # a lost worker is no fault of the image: its earlier outputs are kept
            done = []
            with output_set():  # the files of an image appear together
                for fmt in formats:
                    if fmt in files:
                        data = files[fmt]
                        done.append(str(atomic_write(out_dir / f"{stems[i]}.{fmt}", lambda f, d=data: f.write(d))))
            written[i] = tuple(done)
            manifest.update(Path(d).name for d in done)

        try:
            results = _run_tasks(tasks, executor, jobs, progress, on_result=write, notes=notes)
            report = _report(inputs, results, written, notes)
            if summary:
                from .writers import write_table

                path = write_table(_csv_safe(report.to_frame()), out_dir / "summary.csv")
                manifest.add(path.name)
                report = dataclasses.replace(report, summary_path=str(path))
        finally:
            _write_manifest(out_dir, manifest)  # also after an interrupt: what this run wrote is recorded
    return report


def _report(
    inputs: Sequence[Path], results: list[dict[str, Any]], written: Mapping[int, tuple[str, ...]], notes: list[str]
) -> BatchReport:
    """The :class:`BatchReport` of the results of :func:`process_image`, in input order."""
    rows, failures, warns = [], [], list(notes)
    for i, res in enumerate(results):
        warns.extend(f"{res['image']}: {w}" for w in res.get("warnings", ()))
        if "error" in res:
            failures.append(BatchFailure(res["image"], res["path"], res["error"]))
        else:
            rows.append(
                BatchRow(
                    res["image"],
                    res["path"],
                    res["kind"],
                    int(res["arcs"]),
                    int(res["levels"]),
                    float(res["similarity"]),
                    float(res["seconds"]),
                    written.get(i, ()),
                    res.get("symmetry", ""),
                )
            )
    return BatchReport(tuple(rows), tuple(failures), tuple(str(p) for p in inputs), tuple(warns))


def sweep(
    paths: Iterable[str | os.PathLike[str]],
    parameter_grid: Sequence[Mapping[str, Any]],
    *,
    executor: Executor | None = None,
    jobs: int | None = None,
    progress: BatchProgress | bool | None = None,
) -> pd.DataFrame:
    """Run :func:`img2logo.abstract` for every image and every parameter set; the results as a table.

    No file is written. Runs on ``executor`` like :func:`run_batch` (same
    ``jobs`` and ``progress``), so a sweep can use all cores or a cluster.

    Parameters
    ----------
    paths : iterable of str or path-like
        The input images.
    parameter_grid : sequence of mapping
        Keyword arguments of :func:`img2logo.abstract`, one mapping per run,
        e.g. ``[{"tolerance": t} for t in (3, 5, 9)]``.

    Returns
    -------
    pandas.DataFrame
        One row per (image, parameter set), image-major in the given orders:
        ``image``, one column per parameter named in the grid (missing: NaN),
        then ``kind``, ``arcs``, ``levels``, ``similarity``, ``seconds``,
        ``error`` (empty when the run succeeded).

    Raises
    ------
    InvalidParameterError
        If the grid is empty or a parameter set has an unknown or bad option.
    """
    import pandas as pd

    inputs = [Path(p) for p in paths]
    grid = [dict(g) for g in parameter_grid]
    if not inputs:
        raise InvalidParameterError("paths must name at least one image, got none")
    if not grid:
        raise InvalidParameterError("parameter_grid must hold at least one set of parameters, got none")
    checked = [_check_options(params, "none") for params in grid]
    keys = list(dict.fromkeys(k for g in grid for k in g))
    tasks = [(str(p), opts, (), "none") for p in inputs for opts in checked]
    results = _run_tasks(tasks, executor, jobs, progress)
    records = []
    for params, res in zip([g for _ in inputs for g in grid], results, strict=True):
        records.append(
            {
                "image": res["image"],
                **{k: params.get(k) for k in keys},
                "kind": res.get("kind"),
                "arcs": res.get("arcs"),
                "levels": res.get("levels"),
                "similarity": res.get("similarity"),
                "seconds": res["seconds"],
                "error": res.get("error", ""),
            }
        )
    columns = ["image", *keys, "kind", "arcs", "levels", "similarity", "seconds", "error"]
    return pd.DataFrame.from_records(records, columns=columns).astype({"arcs": "Int64", "levels": "Int64"})


def _run_tasks(
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
                    pool = _default_pool(min(workers, len(chunk)))
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
                result = _lost(tasks[i], _one_line(exc))
                result["error"] = _one_line(exc)
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


def _default_pool(workers: int) -> Executor:
    """A ProcessPoolExecutor of ``workers`` processes, by the platform's default start method.

    That is fork on Linux before Python 3.14: a script without an ``if __name__ ==
    "__main__":`` guard works. Where it is spawn or forkserver, the guard is needed.
    """
    from concurrent.futures import ProcessPoolExecutor

    return ProcessPoolExecutor(max_workers=workers, initializer=_init_worker, initargs=(os.getpid(),))


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


def _check_outputs(outputs: Sequence[str]) -> tuple[str, ...]:
    if isinstance(outputs, str):
        outputs = (outputs,)
    formats = tuple(dict.fromkeys(outputs))
    for fmt in formats:
        check_choice(fmt, "outputs entry", OUTPUT_FORMATS)
    return formats


def _check_options(settings: Mapping[str, Any], fill: str, base: Options | None = None) -> Options:
    """The options, checked before any work: a bad value should not fail every image one by one."""
    from .fills import parse_fill_option

    options = Options.from_keywords(settings, base=base)
    parse_fill_option(fill)
    mask = _foreground_file(options.foreground)
    if mask is not None:  # read once here: a missing or unreadable mask would fail every image
        from .loading import load_mask

        load_mask(mask)
    return options


def _foreground_file(foreground: object) -> Path | None:
    """The mask file a ``foreground`` option names (``--foreground MASK.png``), or None (a choice or an array)."""
    from .subject import FOREGROUND_CHOICES

    if isinstance(foreground, Path) or (isinstance(foreground, str) and foreground not in FOREGROUND_CHOICES):
        return Path(foreground)
    return None


def _check_targets(
    inputs: Sequence[Path], out_dir: Path, stems: Sequence[str], formats: Sequence[str], summary: bool
) -> None:
    """Before any work: the output folder can be written and no file a run writes is one of the inputs."""
    from .writers import check_output_paths

    if out_dir.exists() and not out_dir.is_dir():
        raise InvalidParameterError(f"output folder {out_dir} is a file, not a folder")
    names = [f"{stem}.{fmt}" for stem in stems for fmt in formats] + (["summary.csv"] if summary else [])
    targets = {str(out_dir / name): out_dir / name for name in names}
    try:
        check_output_paths(targets, inputs, {"output folder": out_dir})
    except InvalidParameterError as exc:
        raise InvalidParameterError(f"output folder {out_dir}: {exc}") from exc


def _check_output_folder(inputs: Sequence[Path], out_dir: Path) -> None:
    """Refuse an output folder that holds an input (``img2logo batch in in``, also through a link).

    Its outputs (``<stem>.png``) would be taken as inputs by the next run of the same folder.
    """
    if not out_dir.is_dir():
        return
    for p in inputs:
        with contextlib.suppress(OSError):
            if os.path.samefile(p.parent if str(p.parent) else ".", out_dir):
                raise InvalidParameterError(
                    f"output folder {out_dir} is the folder of the input {p}: the next run would take its "
                    "outputs as inputs; give another folder"
                )


#: In the output folder: the lock of the batch writing it, and the list of the files img2logo wrote there.
LOCK_NAME = ".img2logo-batch.lock"
MANIFEST_NAME = ".img2logo-outputs"
_MANIFEST_HEADER = "# img2logo batch outputs/1: the files img2logo wrote in this folder, one a line\n"


@contextlib.contextmanager
def _batch_lock(out_dir: Path) -> Iterator[None]:
    """Hold ``out_dir``'s batch lock while the block runs: a second batch on the same folder is refused.

    The lock is ``out_dir/.img2logo-batch.lock`` with :func:`fcntl.flock`, which
    the system releases when its process ends, however it ends: a lock file
    left by a killed batch is stale and taken over. The file is removed at the
    end (while still locked, and a batch that took a removed file tries again).
    The folder is created if missing, and removed again if the block leaves it empty.
    Where ``fcntl`` is missing (Windows) no lock is taken.

    Raises
    ------
    InvalidParameterError
        If another batch holds the lock: its process id is named.
    """
    try:
        import fcntl
    except ImportError:  # pragma: no cover - not POSIX
        yield
        return
    from ._io import _make_parents, _Stage, os_message
    from .errors import OutputError

    made = _Stage()  # records the folders created
    lock = out_dir / LOCK_NAME
    try:
        _make_parents(out_dir, made)
        for _ in range(100):
            fd = _open_lock(lock, os.O_RDWR | os.O_CREAT)
            try:
                fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
            except OSError:
                _refuse_locked(out_dir, fd)
            try:
                same = os.fstat(fd).st_ino == os.stat(lock).st_ino
            except FileNotFoundError:
                same = False
            if same:
                break
            os.close(fd)  # the holder removed that file as we took it: take the new one
        os.ftruncate(fd, 0)
        os.pwrite(fd, f"{os.getpid()}\n".encode(), 0)
    except OSError as exc:
        raise OutputError(os_message(lock, exc)) from exc
    try:
        yield
    finally:
        with contextlib.suppress(OSError):
            os.unlink(lock)
        os.close(fd)
        for folder in reversed(made.folders):
            with contextlib.suppress(OSError):
                folder.rmdir()  # only if empty: nothing was written


def _open_lock(lock: Path, flags: int) -> int:
    """Open the lock file: never through a link, never a FIFO or a device, never a file with other names.

    A lock file planted as a link to (or a hard link of) a file of the user's would
    otherwise be written over; such a folder is refused.
    """
    import stat

    nofollow, nonblock = getattr(os, "O_NOFOLLOW", 0), getattr(os, "O_NONBLOCK", 0)
    try:
        fd = os.open(lock, flags | nofollow | nonblock, 0o666)
    except FileNotFoundError:
        raise
    except OSError as exc:
        if lock.is_symlink():
            raise InvalidParameterError(f"output folder {lock.parent}: {lock.name} is a link; remove it") from exc
        raise
    st = os.fstat(fd)
    if not stat.S_ISREG(st.st_mode) or st.st_nlink > 1:
        os.close(fd)
        raise InvalidParameterError(
            f"output folder {lock.parent}: {lock.name} is not a lock file img2logo made "
            "(not a regular file, or a file with other names); remove it"
        )
    return fd


def _refuse_locked(out_dir: Path, fd: int) -> NoReturn:
    """Close ``fd`` (the lock file another batch holds) and raise the error naming that batch's process."""
    try:
        owner = os.pread(fd, 32, 0).decode("ascii", "replace").strip()
    finally:
        os.close(fd)
    who = f" (process {owner})" if owner.isdigit() else ""
    raise InvalidParameterError(
        f"output folder {out_dir} is being written by another img2logo batch{who}; "
        "wait for it to end or give another folder"
    )


def _check_unlocked(out_dir: Path) -> None:
    """Raise, without taking it, if another batch holds ``out_dir``'s lock (see :func:`_batch_lock`)."""
    try:
        import fcntl

        fd = _open_lock(out_dir / LOCK_NAME, os.O_RDONLY)
    except (ImportError, FileNotFoundError):  # no lock file: no batch holds it
        return
    try:
        fcntl.flock(fd, fcntl.LOCK_SH | fcntl.LOCK_NB)
    except OSError:
        _refuse_locked(out_dir, fd)
    os.close(fd)  # closing releases the shared lock


def _read_manifest(out_dir: Path) -> set[str]:
    """The names of the files earlier img2logo batches wrote in ``out_dir`` (:data:`MANIFEST_NAME`)."""
    try:
        text = (out_dir / MANIFEST_NAME).read_text(encoding="utf-8", errors="surrogateescape")
    except (OSError, ValueError):
        return set()
    if not text.startswith(_MANIFEST_HEADER):
        return set()
    return {line for line in text[len(_MANIFEST_HEADER) :].split("\n") if line and "/" not in line}


def _write_manifest(out_dir: Path, names: Iterable[str]) -> None:
    """Record the files img2logo wrote in ``out_dir`` (those still there), whole or not at all."""
    from ._io import atomic_write

    if not out_dir.is_dir():
        return
    kept = sorted(n for n in names if (out_dir / n).is_file() and "\n" not in n)
    if not kept and not (out_dir / MANIFEST_NAME).exists():
        return
    text = _MANIFEST_HEADER + "".join(f"{n}\n" for n in kept)
    atomic_write(out_dir / MANIFEST_NAME, lambda f: f.write(text.encode("utf-8", "surrogateescape")))


def _written_by_img2logo(path: Path, manifest: set[str]) -> bool:
    """Whether ``path`` is a regular file an img2logo run wrote.

    It is when the folder's manifest lists it; a JSON file also when it is an
    ``img2logo.abstraction/1`` document, an SVG when its description says img2logo
    wrote it (outputs of runs before the manifest). A file of the user's
    (``notes.json``), a link or anything else is not.
    """
    if path.is_symlink() or not path.is_file():
        return False
    if path.name in manifest:
        return True
    try:
        if path.suffix == ".json" and path.stat().st_size <= 256 * 2**20:
            import json

            from .constants import FORMAT_NAME

            doc = json.loads(path.read_bytes())
            return isinstance(doc, dict) and doc.get("format") == FORMAT_NAME
        if path.suffix == ".svg":
            with path.open("rb") as f:
                return b"golden ratio logo by img2logo" in f.read(4096)
    except (OSError, ValueError):
        return False
    return False


def _remove_old_outputs(out_dir: Path, stem: str, formats: Sequence[str], manifest: set[str]) -> list[str]:
    """Remove ``out_dir/<stem>.<fmt>`` that an earlier img2logo run wrote (never an input, checked before).

    Returns the names removed. A file img2logo did not write (see
    :func:`_written_by_img2logo`) is left alone.
    """
    removed = []
    for fmt in formats:
        old = out_dir / f"{stem}.{fmt}"
        if _written_by_img2logo(old, manifest):
            from ._io import remove_file

            remove_file(old)
            removed.append(old.name)
    return removed


#: First characters that make a spreadsheet read a CSV cell as a formula (CSV injection, OWASP).
_FORMULA_STARTS: tuple[str, ...] = ("=", "+", "-", "@", "\t", "\r")


def _csv_safe(table: pd.DataFrame) -> pd.DataFrame:
    """``table`` with every text cell that a spreadsheet would run as a formula quoted by a leading ``'``.

    An image named ``=HYPERLINK(...).png`` (or an error message naming it) is then
    shown as text when ``summary.csv`` is opened in a spreadsheet. Numbers are untouched.
    """
    safe = table.copy()
    for column in ("image", "kind", "symmetry", "error"):
        safe[column] = [f"'{v}" if isinstance(v, str) and v.startswith(_FORMULA_STARTS) else v for v in safe[column]]
    return safe


def _output_stems(paths: Sequence[Path]) -> list[str]:
    """File stems of the outputs: the input's stem, ``<stem>-<suffix>`` where stems collide, numbered if still."""
    counts: dict[str, int] = {}
    for p in paths:
        counts[p.stem] = counts.get(p.stem, 0) + 1
    stems = [p.stem if counts[p.stem] == 1 else f"{p.stem}-{p.suffix.lstrip('.').lower()}" for p in paths]
    seen: dict[str, int] = {}
    out = []
    for s in stems:
        seen[s] = seen.get(s, 0) + 1
        out.append(s if seen[s] == 1 else f"{s}-{seen[s]}")
    return out
