"""Batch runs: every image of a folder, on all cores or on any executor (beyond the paper).

:func:`run_batch` abstracts a list of images with :func:`img2logo.abstract` and
writes, for each, ``OUTPUT_DIR/<stem>.svg``, ``.json`` and ``.png`` (the same files
as ``img2logo INPUT --svg --json --png``), then ``OUTPUT_DIR/index.html`` (a gallery,
:mod:`img2logo.app.batch.gallery`) and ``OUTPUT_DIR/summary.csv``: one row per image
(``image, kind, arcs, levels, similarity, symmetry, seconds, error``; a text
cell that a spreadsheet would run as a formula is quoted). A file that
fails (unreadable, blank, ...) does not stop the others: it is reported in
:attr:`BatchReport.failures` with its one-line error message, and its outputs of an
earlier run are removed if img2logo wrote them (``OUTPUT_DIR/.img2logo-outputs``
lists the files it wrote). While a batch runs, it holds ``OUTPUT_DIR/.img2logo-batch.lock``:
a second batch on the same folder is refused. A worker of the default pool that
is killed (the out-of-memory killer) loses nothing: its pool's unfinished images
run again in a fresh one.

The work is done by :func:`process_image`, a module-level function that takes and
returns plain values (a path, a dict of options; a dict with the file contents as
bytes), so that any :class:`concurrent.futures.Executor` can run it:

- by default a local :class:`~concurrent.futures.ProcessPoolExecutor` with
  ``os.cpu_count()`` workers (``jobs`` to change it; ``jobs=1`` runs in this process);
- a :class:`~concurrent.futures.ThreadPoolExecutor` (mostly for tests: the work
  is Python-bound and holds the GIL);
- a cluster: ``run_batch(paths, out, executor=client.get_executor())`` with a
  ``dask.distributed.Client`` (the ``[dask]`` extra: ``pip install 'img2logo[dask]'``;
  on one machine ``Client(LocalCluster())``), or any other executor. The workers read the input
  images, so they must see the paths (a shared file system); the results come
  back as bytes and are written by the calling process, so the output folder need
  not be shared.

The results do not depend on the executor: every image is processed alone and
deterministically, the files are byte-identical, and rows are in input order.
"""

from __future__ import annotations

import dataclasses
import os
import warnings
from collections.abc import Callable, Iterable, Mapping, Sequence
from concurrent.futures import Executor
from pathlib import Path
from typing import IO, Any

from ..._validation import check_choice
from ...errors import Img2LogoError, InvalidParameterError
from ...options import Options
from .folder import (
    LOCK_NAME,
    MANIFEST_NAME,
    batch_lock,
    check_output_folder,
    check_targets,
    output_stems,
    read_manifest,
    remove_old_outputs,
    write_manifest,
)
from .pool import OUTPUT_FORMATS, BatchProgress, process_image, run_tasks
from .report import SUMMARY_COLUMNS, BatchFailure, BatchReport, BatchRow, report_of

__all__ = [
    "IMAGE_SUFFIXES",
    "LOCK_NAME",
    "MANIFEST_NAME",
    "OUTPUT_FORMATS",
    "SUMMARY_COLUMNS",
    "BatchFailure",
    "BatchProgress",
    "BatchReport",
    "BatchRow",
    "SkippedEntryWarning",
    "check_options",
    "find_images",
    "foreground_file",
    "process_image",
    "run_batch",
]

#: File suffixes (lower case) of the images a folder run picks up.
IMAGE_SUFFIXES: tuple[str, ...] = (".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".webp")


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
        from ..._io import printable

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
        e.g. ``"auto"`` (:func:`img2logo.design.fills.parse_fill_option`).
    summary : bool
        Write ``output_dir/summary.csv`` (:meth:`BatchReport.summary_csv`) and
        ``output_dir/index.html``, the gallery of inputs and logos (:mod:`img2logo.app.batch.gallery`).
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
    >>> import cv2
    >>> from pathlib import Path
    >>> from img2logo import data, run_batch
    >>> _ = cv2.imwrite("ring.png", data.ring())  # a black ring, 50 px round, on 160 x 160 px
    >>> report = run_batch(["ring.png"], "logos", outputs=("svg",), jobs=1, progress=False)
    >>> len(report.rows), len(report.failures), [p.name for p in Path("logos").glob("*.svg")]
    (1, 0, ['ring.svg'])
    >>> report = run_batch(find_images("data"), "out", tolerance=7.0, ladder="fibonacci")  # doctest: +SKIP
    >>> from dask.distributed import Client  # doctest: +SKIP
    >>> with Client("scheduler:8786") as client:  # doctest: +SKIP
    ...     report = run_batch(find_images("/shared/in"), "out", executor=client.get_executor())
    """
    inputs = [Path(p) for p in paths]
    if not inputs:
        raise InvalidParameterError("paths must name at least one image, got none")
    formats = _check_outputs(outputs)
    opts = check_options(settings, fill, options)
    out_dir = Path(output_dir)
    stems = output_stems(inputs)
    mask = foreground_file(opts.foreground)
    check_targets([*inputs, *([mask] if mask else [])], out_dir, stems, formats, summary)
    check_output_folder(inputs, out_dir)
    tasks = [(str(p), opts, formats, fill) for p in inputs]

    with batch_lock(out_dir):
        manifest = read_manifest(out_dir)
        written: dict[int, tuple[str, ...]] = {}
        notes: list[str] = []

        def write(i: int, result: dict[str, Any]) -> None:
            from ..._io import atomic_write, output_set

            files = result.get("files") or {}
            if "error" in result:
                if not result.get("lost"):  # an image that now fails keeps no result of an earlier run
                    for name in remove_old_outputs(out_dir, stems[i], formats, manifest):
                        manifest.discard(name)
                return  # a lost worker is no fault of the image: its earlier outputs are kept
            done = []
            with output_set():  # the files of an image appear together
                for fmt in formats:
                    if fmt in files:
                        done.append(str(atomic_write(out_dir / f"{stems[i]}.{fmt}", _writer(files[fmt]))))
            written[i] = tuple(done)
            manifest.update(Path(d).name for d in done)

        try:
            results = run_tasks(tasks, executor, jobs, progress, on_result=write, notes=notes)
            report = report_of(inputs, results, written, notes)
            if summary:  # the table and the gallery (img2logo.app.batch.gallery) appear together, or neither
                from ..._io import atomic_write, output_set
                from .gallery import write_gallery

                table = report.summary_csv().encode("utf-8", "surrogateescape")
                with output_set():
                    path = atomic_write(out_dir / "summary.csv", _writer(table))
                    gallery = write_gallery(report, out_dir)
                manifest.update((path.name, gallery.name))
                report = dataclasses.replace(report, summary_path=str(path))
        finally:
            write_manifest(out_dir, manifest)  # also after an interrupt: what this run wrote is recorded
    return report


def _writer(data: bytes) -> Callable[[IO[bytes]], object]:
    """What :func:`~img2logo._io.atomic_write` calls to write ``data`` into its temporary file."""
    return lambda f: f.write(data)


def _check_outputs(outputs: Sequence[str]) -> tuple[str, ...]:
    if isinstance(outputs, str):
        outputs = (outputs,)
    formats = tuple(dict.fromkeys(outputs))
    for fmt in formats:
        check_choice(fmt, "outputs entry", OUTPUT_FORMATS)
    return formats


def check_options(settings: Mapping[str, Any], fill: str, base: Options | None = None) -> Options:
    """The options of a batch, checked before any work: a bad value should not fail every image one by one.

    Parameters
    ----------
    settings : mapping of str to object
        Fields of :class:`~img2logo.options.Options`, replacing those of ``base``.
    fill : str
        The ``--fill`` option (:func:`img2logo.design.fills.parse_fill_option`).
    base : Options, optional
        The options the settings replace fields of; default ``Options()``.

    Returns
    -------
    Options
        The checked options; a ``--foreground`` mask file has been read once.

    Raises
    ------
    InvalidParameterError
        If a setting or ``fill`` is unknown or out of range.
    Img2LogoError
        If the foreground mask file cannot be read (the message names ``--foreground``).
    """
    from ...design.fills import parse_fill_option

    options = Options.from_keywords(settings, base=base)
    parse_fill_option(fill)
    mask = foreground_file(options.foreground)
    if mask is not None:  # read once here: a missing or unreadable mask would fail every image
        from ...images.loading import load_mask

        try:
            load_mask(mask)
        except Img2LogoError as exc:  # the same error, naming the option: the image is not at fault
            raise type(exc)(f"--foreground: {exc}") from exc
    return options


def foreground_file(foreground: object) -> Path | None:
    """The mask file a ``foreground`` option names (``--foreground MASK.png``), or None (a choice or an array).

    A batch checks and reads it before any image, and names it among its inputs
    (an output must not overwrite it).
    """
    from ...features.photo.subject import FOREGROUND_CHOICES

    if isinstance(foreground, Path) or (isinstance(foreground, str) and foreground not in FOREGROUND_CHOICES):
        return Path(foreground)
    return None
