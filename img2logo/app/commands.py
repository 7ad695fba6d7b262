"""The work of the two commands: ``img2logo INPUT ...`` (:func:`run_image`) and ``img2logo batch`` (:func:`run_folder`).

Each takes the parsed arguments of :mod:`img2logo.app.cli` and a ``say`` function (one line on standard
error); every check of an option or an output path is made before any work, and the outputs of a run
are written as a set (:func:`img2logo.export.writers.output_set`).
"""

from __future__ import annotations

import argparse
import gc
import os
import re
import sys

from .._io import printable
from ..errors import Img2LogoError, InvalidParameterError, OutputError

#: Said below a photo's subject line when no object was found and the whole image is drawn.
SUBJECT_HINT = "to draw one object instead, give --subject X,Y,W,H (a rectangle around it, px) or --foreground MASK.png"


#: The output flags of one image; without any of them there is nothing to do.
_OUTPUT_FLAGS = ("--svg", "--json", "--png", "--pdf", "--segments-png", "--levels-dir")


def freeze_heap() -> None:
    """Move every object alive now out of the cyclic garbage collector's sight (``gc.freeze``); collections resume.

    Only when the process is the command (``main()`` without ``argv``), not when
    Python code calls ``main([...])``. The modules a run imports (numpy, scipy,
    scikit-image, OpenCV, numba's compiler) are hundreds of thousands of objects
    that live until the process ends, and every full collection during the run
    and the collections at interpreter exit walk them all: 0.25-0.35 s of CPU on a
    2 s clip-art run (``benchmarks/bench.py`` measures the command). Frozen
    objects are still freed by reference counting; nothing else changes.
    """
    gc.freeze()
    gc.enable()  # after _start_command's pause


def _abstract_options(args: argparse.Namespace, *, batch: bool = False):
    """The :class:`img2logo.options.Options` the flags ask for, checked (``--subject`` aside: it needs the image).

    Checked before the run: a bad value should not cost a run.
    """
    from ..options import Options, check_lock_mask, cli_fields

    given = {}
    for _, f in cli_fields(batch=batch):
        if f.name == "subject":
            continue
        value = getattr(args, f.name)
        parse = f.metadata["parse"]
        given[f.name] = value if parse is None else parse(value)
    try:
        options = Options.from_keywords(given)
    except InvalidParameterError as exc:  # the library names its keyword; the user typed the flag
        flags = {f.name: f.metadata["flags"][0] for _, f in cli_fields(batch=batch)}
        said = re.match(r"(\w+)(?: \(--[\w-]+\))? ", str(exc))
        if said is None or said.group(1) not in flags:
            raise
        raise InvalidParameterError(flags[said.group(1)] + " " + str(exc)[said.end() :]) from exc
    check_lock_mask(options, getattr(args, "lock_mask", None))
    if getattr(args, "level", None) is not None and args.level < 0:
        raise InvalidParameterError(f"--level must be >= 0, got {args.level}")
    return options


def _check_outputs(args: argparse.Namespace) -> dict:
    """Every output path of a single-image run, checked before any work (see :func:`writers.check_output_paths`).

    None is an input (the image, the lock mask, the ``--foreground`` mask), none
    is a folder or a device, no two share a file, every parent exists or can be
    created and is writable, and every suffix names the format written. A file
    of ``--levels-dir`` that this run writes or removes (``level-NNNN.json``,
    ``.svg``) is none of the inputs either, also through a link, and no other
    output is one of them.
    """
    from pathlib import Path

    from ..export.writers import check_output_paths

    mask = _foreground_file(args.foreground)
    inputs = [args.input] + ([args.lock_mask] if args.lock_mask else []) + ([mask] if mask else [])
    targets = {
        flag: path
        for flag, path in (
            ("--segments-png", args.segments_png),
            ("--json", args.json),
            ("--svg", args.svg),
            ("--png", args.png),
            ("--pdf", args.pdf),
        )
        if path
    }
    folders = {"--levels-dir": args.levels_dir} if args.levels_dir else {}
    checked = check_output_paths(targets, inputs, folders)
    for flag, path in targets.items():
        _check_suffix(flag, path)
    if args.levels_dir:
        folder = Path(args.levels_dir)
        real_folder = os.path.realpath(folder)
        for given in inputs:
            real = Path(os.path.realpath(given))
            if str(real.parent) == real_folder and LEVEL_FILE.fullmatch(real.name):
                raise InvalidParameterError(
                    f"--levels-dir {args.levels_dir} holds the input {given}: refusing to write over an input"
                )
        if folder.is_dir():  # its level files (links too) are written or removed: none may be an input
            level_files = {str(p): p for p in sorted(folder.iterdir()) if LEVEL_FILE.fullmatch(p.name)}
            try:
                check_output_paths(level_files, inputs)
            except InvalidParameterError as exc:
                raise InvalidParameterError(f"--levels-dir {args.levels_dir}: {exc}") from exc
        for flag, target in checked.items():
            t = Path(os.path.realpath(target))
            if str(t.parent) == real_folder and LEVEL_FILE.fullmatch(t.name):
                raise InvalidParameterError(f"{flag} {target} is inside --levels-dir and may be one of its files")
    return checked


#: The files of ``--levels-dir``: ``level-0000.json``, ``level-0000.svg``, ... (more digits past 9999).
LEVEL_FILE = re.compile(r"level-\d{4,}\.(json|svg)")


#: The suffix each output option's format has (:data:`img2logo.export.writers.FORMAT_SUFFIXES` names the others).
_SUFFIXES: dict[str, tuple[str, ...]] = {
    "--svg": (".svg",),
    "--json": (".json",),
    "--png": (".png",),
    "--pdf": (".pdf",),
    "--segments-png": (".png",),
}


def _check_suffix(flag: str, path: str) -> None:
    """Refuse an output whose suffix names another format (``--svg out.pdf``): the file would lie about its content.

    A suffix that names no known format (``logo.out``, none at all) is accepted:
    the name is the user's.
    """

    from ..export.writers import FORMAT_SUFFIXES

    suffix = os.path.splitext(path)[1].lower()
    if suffix in FORMAT_SUFFIXES and suffix not in _SUFFIXES[flag]:
        wanted = " or ".join(_SUFFIXES[flag])
        raise InvalidParameterError(
            f"{flag} {path}: {suffix} names another format ({flag} writes {_SUFFIXES[flag][0][1:].upper()}); "
            f"give a file name ending in {wanted}"
        )


def _naming(path: str, call, *a, **kw):
    """``call(*a, **kw)``; an img2logo error that does not name ``path`` is raised again naming it."""
    try:
        return call(*a, **kw)
    except Img2LogoError as exc:
        if str(path) in str(exc) or isinstance(exc, OutputError):
            raise
        raise type(exc)(f"{path}: {exc}") from exc


def _foreground_file(foreground: object):
    """:func:`img2logo.app.batch.run.foreground_file`; the batch module (and its pool's) loads only for a mask."""
    if foreground == "auto":  # the default: no file
        return None
    from .batch.run import foreground_file as of_batch

    return of_batch(foreground)


def _fill_spec(spec: object):
    """:func:`img2logo.design.fills.parse_fill_option`, or None for the default ``none`` (no fills: not imported)."""
    if spec == "none":
        return None
    from ..design.fills import parse_fill_option

    return parse_fill_option(spec)


def run_image(args: argparse.Namespace, say, *, freeze: bool = False) -> int:
    """``img2logo INPUT ...``: abstract one image and write the outputs asked for; 0 when done.

    Every option, mask and output path is checked before the work; ``freeze``
    (the process is the command) freezes the heap once the input is read (:func:`freeze_heap`).
    """
    import dataclasses

    from ..images.loading import load_image
    from ..pipeline import abstract
    from .kind_options import ignored_options, kind_options

    options = _abstract_options(args)
    given = kind_options(options, args.subject)  # as typed, before a mask file is read into the options
    fill_spec = _fill_spec(args.fill)
    if not any(getattr(args, flag[2:].replace("-", "_")) for flag in _OUTPUT_FLAGS):  # before any work
        raise InvalidParameterError(f"nothing to write: give {', '.join(_OUTPUT_FLAGS[:-1])} or {_OUTPUT_FLAGS[-1]}")
    if args.png_scale is not None and not 0 < args.png_scale < float("inf"):
        raise InvalidParameterError(f"--png-scale must be a finite number > 0, got {args.png_scale:g}")
    _check_outputs(args)
    image = load_image(args.input)
    if freeze:  # the modules imported so far (numpy, OpenCV, the pipeline's, the writers') live as long as the process
        freeze_heap()
    # Masks and the subject rectangle are in the input's pixels (abstract scales them to a downscaled input);
    # a mask is read here, before the work, whatever the kind turns out to be.
    shape = (image.input_height, image.input_width)
    lock_mask = None if not args.lock_mask else _mask_option("--lock-mask", args.lock_mask, shape)
    foreground = _foreground_file(args.foreground)
    if foreground is not None:
        options = dataclasses.replace(options, foreground=_mask_option("--foreground", foreground, shape))
    say(f"{args.input}: {image.width}x{image.height} px")
    if args.png:  # the PNG's size is checked before the work, in the input's pixels as write_png draws it
        from ..constants import MAX_PNG_IMAGE_SIDE, MAX_PNG_SIDE
        from ..export.writers import png_size

        try:
            png_size(image.input_width, image.input_height, args.png_scale, args.png_background)
        except InvalidParameterError:
            side = f"{max(image.input_width, image.input_height) * args.png_scale:.0f}"  # inf for 1e308
            over = args.png_background == "input"
            raise InvalidParameterError(
                f"--png-scale {args.png_scale:g} makes the PNG {side} px on its longer side; it must be "
                + (
                    f"1..{MAX_PNG_IMAGE_SIDE} over the faded input (--png-background white or transparent: "
                    f"1..{MAX_PNG_SIDE})"
                    if over
                    else f"1..{MAX_PNG_SIDE}"
                )
            ) from None
    if args.subject is not None:
        from ..features.photo.subject import parse_subject_rectangle

        try:
            subject = parse_subject_rectangle(args.subject, shape)
        except InvalidParameterError as exc:  # named as typed: "--subject 1e308,0,5,5", not its 309 digits
            said = re.match(r"subject(?: rectangle \S+)? ", str(exc))
            if said is None:
                raise
            typed = f"--subject {printable(args.subject)} " if " rectangle " in said.group(0) else "--subject "
            raise InvalidParameterError(typed + str(exc)[said.end() :]) from exc
        options = dataclasses.replace(options, subject=subject)
    progress = None if not args.quiet else False
    result = _naming(args.input, abstract, image, options=options, lock_mask=lock_mask, progress=progress)
    graph, prog = result.graph, result.progression
    say(f"kind {result.lines.kind} ({result.lines.reason})")
    if result.lines.detail is not None and options.arcs is not None:  # what the arc budget kept
        say(f"detail: {result.lines.detail} regions kept besides the background, for about {options.arcs} arcs")
    for ignored in ignored_options(result.lines, given):
        say(f"img2logo: warning: {ignored}")
    if result.lines.subject is not None:
        say(f"subject: {result.lines.subject.description}")
        if result.lines.subject.mask is None and result.lines.subject.method == "auto":
            # Said where the user looks: the way to choose the object when none was found.
            say(f"subject: {SUBJECT_HINT}")
    if result.symmetry is not None:
        say(result.symmetry.description)
    say(
        f"segment graph: {graph.n_segments} segments, {graph.n_junctions} nodes "
        f"({_count(int((graph.valence >= 3).sum()), 'junction')}), {_count(graph.n_components(), 'component')}"
    )
    # As the studio's title: the level's own E^s above T (a loop past T may end within it).
    past_t = prog.final.similarity > prog.final.tolerance
    past = f"; past it, up to {options.stretch:.3g} T, for the arc budget" if past_t else ""
    say(
        f"levels: {len(prog.levels)}, arcs {prog.arc_counts[0]} -> {prog.arc_counts[-1]}, "
        f"E^s {prog.final.similarity:.2f} px (T = {prog.final.tolerance:g}"
        f"{past}), "
        f"{_ladder_text(prog)}, "
        f"stopped: {prog.stopped_because}, {sum(result.timings.values()):.2f} s"
    )
    level = _pick_level(result, args.level)
    _write_outputs(result, level, args, say, fill_spec)
    return 0


def _mask_option(flag: str, path, shape: tuple[int, int]):
    """The mask a flag names, of the input's ``shape``; its error names the flag (the image is not at fault)."""
    from ..images.loading import load_mask

    try:
        return load_mask(path, shape)
    except Img2LogoError as exc:
        raise type(exc)(f"{flag}: {exc}") from exc


def _count(n: int, noun: str) -> str:
    """``"1 junction"``, ``"3 junctions"``."""
    return f"{n} {noun}" if n == 1 else f"{n} {noun}s"


def _ladder_text(prog) -> str:
    """``bias 0.1234`` on the phi ladder, ``Fibonacci unit 0.8726 px`` on the Fibonacci one."""
    unit = getattr(prog.ladder, "unit", None)
    return f"bias {prog.bias:.4f}" if unit is None else f"Fibonacci unit {unit:.4g} px"


def run_folder(args: argparse.Namespace, say) -> int:
    """``img2logo batch``: every image of a folder (:func:`img2logo.app.batch.run.run_batch`); how many failed."""
    from pathlib import Path

    from .batch.folder import check_output_folder, check_targets, check_unlocked, output_stems
    from .batch.run import OUTPUT_FORMATS, check_options, find_images, foreground_file, run_batch

    options = check_options({}, args.fill, _abstract_options(args, batch=True))  # the --foreground mask read
    if args.jobs is not None and args.jobs < 1:
        raise InvalidParameterError(f"--jobs must be >= 1, got {args.jobs}")
    paths = find_images(args.input_dir)
    out_dir = Path(args.output_dir)
    mask = foreground_file(options.foreground)
    check_targets([*paths, *([mask] if mask else [])], out_dir, output_stems(paths), OUTPUT_FORMATS, True)
    check_output_folder(paths, out_dir)
    check_unlocked(out_dir)  # all before the count
    say(f"{args.input_dir}: {len(paths)} images")
    report = run_batch(
        paths,
        args.output_dir,
        jobs=args.jobs,
        progress=_batch_progress(args.quiet, say),
        fill=args.fill,
        options=options,
    )
    for w in report.warnings:
        say(f"img2logo: warning: {w}")
    for line in report.summary(failures=False).splitlines():  # the names in it are escaped
        say(line)
    say(
        f"wrote {len(report.rows)} logos (.svg, .json, .png) to {args.output_dir}/, {report.summary_path} "
        f"and the gallery {Path(args.output_dir) / 'index.html'}"
    )
    for f in report.failures:
        print(f"img2logo: error: {printable(f.line)}", file=sys.stderr)
    return len(report.failures)


def _batch_progress(quiet: bool, say):
    """A batch's progress: none under ``-q``, a bar on a terminal, else one line per image done (a log's progress)."""
    if quiet:
        return False
    if sys.stderr.isatty():
        return None

    def line(done: int, total: int, image: str) -> None:
        say(f"{done}/{total} done: {image}")

    return line


def _pick_level(result, n: int | None):
    if n is None:
        return result.final
    count = len(result.progression.levels)  # without making every level
    if not 0 <= n < count:
        raise InvalidParameterError(f"--level must be in 0..{count - 1} (this run has {count} levels), got {n}")
    return result.level(n)


def _write_outputs(result, level, args: argparse.Namespace, say, fill_spec) -> None:
    """Write every output of the run together (:func:`writers.output_set`): all of them, or none."""
    from pathlib import Path

    from .._io import remove_file
    from ..export import writers

    fills = None if fill_spec is None or fill_spec.mode == "none" else fill_spec.make(level, result.image)
    if fills is not None:
        say(f"fills: {len(fills)} regions ({args.fill})")

    done, stale = [], []
    with writers.output_set():
        if args.segments_png:
            done.append(writers.write_segment_graph_png(result.graph, args.segments_png, image=result.image.rgb))
        for fmt in ("json", "svg", "png", "pdf"):
            if getattr(args, fmt):  # the PNG's image, background and scale are ignored by the other formats
                image, background, scale = result.image.rgb, args.png_background, args.png_scale
                done.append(
                    writers.write(
                        level, getattr(args, fmt), fmt, fills=fills, image=image, background=background, scale=scale
                    )
                )
        if args.levels_dir:
            folder = Path(args.levels_dir)
            names = set()
            for lv in result.levels:
                for fmt in ("json", "svg"):
                    names.add(writers.write(lv, folder / f"level-{lv.level:04d}.{fmt}", fmt).name)
            stale = _stale_level_files(folder, names)
            for path in stale:  # an earlier run's levels past this run's last: removed with the set
                remove_file(path)
    image = result.image
    if args.png and args.png_scale is None:
        size = writers.png_size(image.input_width, image.input_height, None, args.png_background)
        if size != (image.input_width, image.input_height):
            say(
                f"png: drawn at {size[0]}x{size[1]} px (the input is {image.input_width}x{image.input_height} px; "
                "--png-scale S draws S times that)"
            )
    for path in done:
        say(f"wrote {path}")
    if args.levels_dir:
        gone = f" (removed {_count(len(stale), 'file')} of an earlier run's other levels)" if stale else ""
        say(f"wrote {_count(len(result.levels), 'level')} to {args.levels_dir}/{gone}")


def _stale_level_files(folder, keep: set[str]) -> list:
    """The level files of an earlier run in ``folder`` that this run does not write: img2logo's own only.

    A file is img2logo's when its name is one of :data:`LEVEL_FILE` and, a regular
    file (no link), its content says so (an ``img2logo.abstraction/1`` JSON
    document, an SVG that img2logo describes as its own): never a file of the user's.
    """
    from .batch.folder import written_by_img2logo

    if not folder.is_dir():
        return []
    return sorted(
        p
        for p in folder.iterdir()
        if LEVEL_FILE.fullmatch(p.name) and p.name not in keep and written_by_img2logo(p, set())
    )
