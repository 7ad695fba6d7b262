"""The ``img2logo`` command line.

``img2logo INPUT [--svg OUT.svg] [--json OUT.json] [--png OUT.png] [--pdf OUT.pdf]
[--segments-png OUT.png] [--levels-dir DIR] [options]`` turns INPUT into a
golden ratio logo: feature lines, the segment graph L = {S, J}, then the
progressive optimization; it writes the final level (or ``--level N``), every
level with ``--levels-dir``, and the segment graph with ``--segments-png``.

``img2logo batch INPUT_DIR OUTPUT_DIR [options]`` does every image of a folder
(:mod:`img2logo.app.batch.run`) on all cores (``--jobs N``), writing
``OUTPUT_DIR/<stem>.svg``, ``.json``, ``.png`` and ``OUTPUT_DIR/summary.csv``; it
goes on past a bad file, lists it at the end and then exits with status 1.

Every error is one line, ``img2logo: error: ...``, never a traceback (argument
errors too; a control character in a file name is printed escaped). Exit
statuses (:func:`main`): 2 for a bad input, option or output path, found before
any work (nothing is written; an output that is an input -- the image, a
``--lock-mask`` or ``--foreground`` mask, a file of ``--levels-dir`` --, a folder,
a device, shared by two options, under a file or a read-only folder, or with a
suffix naming another format is one; so is a batch's output folder that is its
input folder or that another batch is writing); 1 when an
output cannot be written during the run (the outputs of a run are written as a
set: none of them is left), when memory runs out, or when some images of a
batch failed (the others are written, a failed image's old outputs removed
when img2logo wrote them; a killed worker's images are run again);
130 after Ctrl-C and 143 after SIGTERM (temporary files removed; a batch's
workers end with it, also when it is killed). The same input and options give
the same files, byte for byte.
"""

from __future__ import annotations

import argparse
import contextlib
import gc
import os
import re
import sys
import warnings
from collections.abc import Iterator, Sequence
from typing import NoReturn

from .. import __version__
from .._io import printable
from ..errors import Img2LogoError, InvalidParameterError, OutputError

EXIT_ERROR = 2
#: Exit status when an output could not be written, memory ran out, or (batch) some images failed.
EXIT_FAILED = 1
#: Exit status after Ctrl-C (128 + SIGINT) and after SIGTERM (128 + SIGTERM).
EXIT_INTERRUPTED = 130
EXIT_TERMINATED = 143


#: The examples at the end of ``img2logo --help``, in a designer's words.
EXAMPLES = """\
examples:
  img2logo cat.png --svg cat.svg
      the logo as SVG, to open in Inkscape or Illustrator: the arcs on layer "Arcs",
      and the golden circles they come from on a hidden, locked layer "Golden circles"
  img2logo cat.png --png cat-logo.png --png-background transparent --png-scale 4
      a clean logo (no photo under it) four times the image's size, for a layout
  img2logo cat.png --pdf cat.pdf
      a vector PDF for print (1 px of the image = 1 pt)
  img2logo cat.png --png preview.png
      the logo drawn over the faded image, to check it against the original
  img2logo cat.png --svg simpler.svg --tolerance 9
      fewer, larger arcs: a larger tolerance T lets the logo stray further (px)
  img2logo cat.png --levels-dir levels/
      every level of simplification, from the first fit to the simplest logo
  img2logo cat.png --svg cat.svg --fill auto
      the regions between the arcs coloured like the image
  img2logo batch photos/ logos/
      a whole folder; logos/index.html shows every image beside its logo

img2logo batch INPUT_DIR OUTPUT_DIR [options]: every image of a folder, on all cores, with a summary
table and a gallery page (see img2logo batch --help)."""

#: Said below a photo's subject line when no object was found and the whole image is drawn.
SUBJECT_HINT = "to draw one object instead, give --subject X,Y,W,H (a rectangle around it, px) or --foreground MASK.png"
#: The output flags of one image; without any of them there is nothing to do.
_OUTPUT_FLAGS = ("--svg", "--json", "--png", "--pdf", "--segments-png", "--levels-dir")


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line, ``img2logo: error: ...`` (exit status 2), not usage + error.

    An argument that starts with ``-`` and is no option (``-x.png``) is named, with
    the way to give a file of that name (``img2logo -- -x.png``).
    """

    def parse_args(self, args=None, namespace=None):  # type: ignore[override]
        self._given = list(sys.argv[1:] if args is None else args)
        return super().parse_args(self._given, namespace)

    def error(self, message: str) -> NoReturn:
        about_inputs = message.startswith(("the following arguments are required", "unrecognized arguments"))
        unknown = self._unknown_option() if about_inputs else None  # not for an option's own bad value
        if unknown is not None:
            command = "img2logo batch" if self.prog.endswith("batch") else "img2logo"
            message = (
                f"unknown option {printable(unknown)} (for a file whose name starts with '-', "
                f"write: {command} [OPTIONS] -- {printable(unknown)})"
            )
        elif message.startswith("unrecognized arguments") and "--" in getattr(self, "_given", []):
            message += " (everything after -- is a file name: put the options before --)"
        self.exit(EXIT_ERROR, f"img2logo: error: {printable(message)}\n")

    def _unknown_option(self) -> str | None:
        """The first argument before ``--`` that looks like an option but is none (nor a negative number)."""
        for arg in getattr(self, "_given", []):
            if arg == "--":
                return None
            if not arg.startswith("-") or arg == "-" or _NUMBER.fullmatch(arg):
                continue
            name = arg.split("=", 1)[0] if arg.startswith("--") else arg
            if name in self._option_string_actions:
                continue
            if not arg.startswith("--") and arg[:2] in self._option_string_actions:
                continue  # a short option with its value attached: -j2
            if arg.startswith("--") and any(o.startswith(name) for o in self._option_string_actions):
                continue  # an abbreviation argparse accepts or calls ambiguous itself
            return arg
        return None


#: An argument that is a number (a negative option value such as ``-5``), not an option.
_NUMBER = re.compile(r"-\d+(\.\d*)?([eE][-+]?\d+)?|-\.\d+([eE][-+]?\d+)?|-inf|-nan", re.IGNORECASE)


def build_parser() -> argparse.ArgumentParser:
    p = _Parser(
        prog="img2logo",
        usage="%(prog)s INPUT [options]\n       %(prog)s batch INPUT_DIR OUTPUT_DIR [options]",
        description="Turn an image into a golden ratio logo: circular arcs on a phi circle grid.",
        epilog=EXAMPLES,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("input", help="input image (PNG, JPEG, ...): a photo, a clip art or a line drawing")
    _add_input_options(p, batch=False)
    p.add_argument("--segments-png", metavar="OUT.png", help="draw the segment graph L = {S, J} to this PNG")
    out = p.add_argument_group("outputs (the final level, or --level N)")
    out.add_argument("--svg", metavar="OUT.svg", help="the logo as SVG: exact arcs, golden circles on a hidden layer")
    out.add_argument("--json", metavar="OUT.json", help="the logo as a document of the img2logo.abstraction/1 contract")
    out.add_argument("--png", metavar="OUT.png", help="the logo as PNG (over the faded input unless --png-background)")
    out.add_argument(
        "--png-background",
        choices=("input", "white", "transparent"),
        default="input",
        help="under the logo in the PNG: the faded input (default), white, or transparent",
    )
    out.add_argument(
        "--png-scale",
        type=float,
        default=None,
        metavar="S",
        help=(
            "size of the PNG relative to the input image (default 1, at most 2048 px on the longer side; "
            "4 = four times as wide and high)"
        ),
    )
    out.add_argument("--pdf", metavar="OUT.pdf", help="the logo as a vector PDF (arcs as Bezier curves, 1 px = 1 pt)")
    out.add_argument(
        "--level", type=int, metavar="N", help="write level N (0 = the initial fit) instead of the final one"
    )
    out.add_argument("--levels-dir", metavar="DIR", help="write every level as DIR/level-0000.json and .svg, ...")
    _add_fill_option(out)
    _add_optimization_options(p, batch=False)
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")
    p.add_argument("--version", action="version", version=f"img2logo {__version__}")
    return p


def build_batch_parser() -> argparse.ArgumentParser:
    p = _Parser(
        prog="img2logo batch",
        description="Turn every image of a folder (png, jpg, jpeg, tif, tiff, bmp, webp; sorted by name) into a "
        "golden ratio logo: OUTPUT_DIR/<stem>.svg, .json and .png, OUTPUT_DIR/index.html (a gallery of every input "
        "beside its logo, to open in a browser) and OUTPUT_DIR/summary.csv (image, kind, "
        "arcs, levels, E^s, symmetry, seconds, error). A file that fails is reported at the end and the exit status is "
        "then 1; the other images are done.",
    )
    p.add_argument("input_dir", metavar="INPUT_DIR", help="folder of input images (not searched recursively)")
    p.add_argument("output_dir", metavar="OUTPUT_DIR", help="folder for the results (created if missing)")
    _add_input_options(p, batch=True)
    out = p.add_argument_group("outputs")
    _add_fill_option(out)
    _add_optimization_options(p, batch=True)
    p.add_argument(
        "--jobs",
        "-j",
        type=int,
        metavar="N",
        help="images processed at once, each in its own process (default: the number of CPUs)",
    )
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")
    return p


def _add_input_options(p: argparse.ArgumentParser, *, batch: bool) -> None:
    """--kind, --rdp, --min-length, --foreground (--subject for one image), from :class:`~img2logo.options.Options`."""
    _add_options(p, "input", batch=batch)


def _add_options(p: argparse.ArgumentParser | argparse._ArgumentGroup, stage: str, *, batch: bool) -> None:
    """The flags of the options of ``stage`` (:func:`img2logo.options.cli_fields`); each sets the option of its name."""
    from ..options import cli_fields

    for field_stage, f in cli_fields(batch=batch):
        if field_stage == stage:
            kwargs = dict(f.metadata["cli"])
            kwargs.setdefault("default", f.default)
            p.add_argument(*f.metadata["flags"], dest=f.name, **kwargs)


def _add_fill_option(out: argparse._ArgumentGroup) -> None:
    out.add_argument(
        "--fill",
        metavar="SPEC",
        default="none",
        help="colour the regions bounded by the arcs (paper Fig. 18): none (default), auto (colours of the "
        "input), palette:#rrggbb,..., linear[@DEG]:#rrggbb,#rrggbb,... or radial:#rrggbb,#rrggbb,...",
    )


def _add_optimization_options(p: argparse.ArgumentParser, *, batch: bool) -> None:
    """The optimization options (paper Sec. 5) of :class:`~img2logo.options.Options`; ``--lock-mask`` (one image)."""
    opt = p.add_argument_group("optimization (paper Sec. 5)")
    _add_options(opt, "optimize", batch=batch)
    if not batch:
        opt.add_argument(
            "--lock-mask", metavar="MASK.png", help="segments inside the mask's white pixels are never merged"
        )


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status.

    ``img2logo batch ...`` (the first argument ``batch``) runs a folder; to
    abstract an image file named ``batch``, write ``./batch``.

    Exit statuses: 0 done; 2 a bad input or option, or an output path that
    cannot be used (checked before any work; nothing written); 1 an output
    that could not be written (nothing new is left), out of memory, or in a
    batch some images failed (the others are written); 130 interrupted by
    Ctrl-C, 143 by SIGTERM (the temporary files are removed). Every error is
    one line on standard error, ``img2logo: error: ...``.
    """
    command = argv is None  # the process is the command: its heap is frozen (see _freeze_heap)
    if command:
        _start_command()
    try:
        return _main(argv, command)
    finally:
        if command:
            gc.enable()  # _start_command's pause ends with main, however it ends


def _main(argv: Sequence[str] | None, command: bool) -> int:
    args_list = list(sys.argv[1:] if argv is None else argv)
    batch = bool(args_list) and args_list[0] == "batch"
    if batch:
        args = build_batch_parser().parse_args(args_list[1:])
    else:
        args = build_parser().parse_args(args_list)

    def say(text: object) -> None:
        """Print one line on standard error; a control character in a name cannot start another one."""
        if not args.quiet:
            print(printable(text), file=sys.stderr)

    def show(message, category, filename, lineno, file=None, line=None) -> None:
        say(f"img2logo: warning: {printable(message)}")

    with _terminate_on_sigterm():
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("always")
                warnings.showwarning = show  # as they come, not at the end
                if batch:
                    gc.enable()  # the batch's workers are forked from this process: as before
                    status = _batch(args, say)
                else:
                    status = _run(args, say, freeze=command)
                if command:
                    _freeze_heap()
                return status
        except OutputError as exc:
            print(f"img2logo: error: {printable(exc)}", file=sys.stderr)
            return EXIT_FAILED
        except Img2LogoError as exc:
            print(f"img2logo: error: {printable(exc)}", file=sys.stderr)
            return EXIT_ERROR
        except MemoryError:
            print("img2logo: error: out of memory; try a smaller image or fewer --jobs", file=sys.stderr)
            return EXIT_FAILED
        except KeyboardInterrupt:
            print("img2logo: interrupted; nothing more written", file=sys.stderr)
            return EXIT_INTERRUPTED
        except _Terminated:
            print("img2logo: terminated; nothing more written", file=sys.stderr)
            return EXIT_TERMINATED


#: The thread counts of the numeric libraries that :func:`_start_command` sets to 1 (unless the user set them).
THREAD_VARIABLES = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def _start_command() -> None:
    """What the process that is the command does before it imports numpy: one BLAS thread, no collections.

    numpy's OpenBLAS starts a thread per further core when it loads; between
    its calls each spins on its core before it sleeps. A run's BLAS work is
    small matrices (OpenBLAS runs them on the calling thread anyway): the
    spinning was all the second thread did, 45 ms of CPU on the import of
    numpy alone and 0.05-0.24 s over a run (a clip art, a photo; the outputs
    are the same bytes, ``test_same_files_whatever_the_thread_counts``), taken
    from whatever else the machine runs. A variable the user set is kept. Only
    before numpy is imported (a Python program calling ``main()`` has its own).

    The cyclic garbage collector pauses until the modules are imported and
    frozen (:func:`_freeze_heap`): the imports make hundreds of thousands of
    objects that live as long as the process, and the collections during them
    only walked those (a tenth of numpy's import).
    """
    if "numpy" not in sys.modules:
        for var in THREAD_VARIABLES:
            os.environ.setdefault(var, "1")
    gc.disable()


def _freeze_heap() -> None:
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


class _Terminated(BaseException):
    """Raised in the main thread on SIGTERM, so that ``finally`` blocks remove temporary files."""


@contextlib.contextmanager
def _terminate_on_sigterm() -> Iterator[None]:
    """SIGTERM raises :class:`_Terminated` while the command runs (main thread only)."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return

    def handler(signum, frame) -> None:
        raise _Terminated

    previous = signal.signal(signal.SIGTERM, handler)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


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
    import os
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
    import os

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


def _run(args: argparse.Namespace, say, *, freeze: bool = False) -> int:
    import dataclasses

    from ..images.loading import load_image
    from ..pipeline import abstract

    options = _abstract_options(args)
    fill_spec = _fill_spec(args.fill)
    if not any(getattr(args, flag[2:].replace("-", "_")) for flag in _OUTPUT_FLAGS):  # before any work
        raise InvalidParameterError(f"nothing to write: give {', '.join(_OUTPUT_FLAGS[:-1])} or {_OUTPUT_FLAGS[-1]}")
    if args.png_scale is not None and not 0 < args.png_scale < float("inf"):
        raise InvalidParameterError(f"--png-scale must be a finite number > 0, got {args.png_scale:g}")
    _check_outputs(args)
    image = load_image(args.input)
    if freeze:  # the modules imported so far (numpy, OpenCV, the pipeline's, the writers') live as long as the process
        _freeze_heap()
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
    given = [f"--subject {args.subject}"] if args.subject is not None else []
    given += [f"--foreground {args.foreground}"] if args.foreground != "auto" else []
    ignored = None
    if given:
        from .batch.pool import ignored_subject_options

        ignored = ignored_subject_options(result.lines, given)
    if ignored:
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
    say(
        f"levels: {len(prog.levels)}, arcs {prog.arc_counts[0]} -> {prog.arc_counts[-1]}, "
        f"E^s {prog.final.similarity:.2f} px (T = {prog.final.tolerance:g}), {_ladder_text(prog)}, "
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


def _batch(args: argparse.Namespace, say) -> int:
    """``img2logo batch``: every image of a folder (:func:`img2logo.app.batch.run.run_batch`)."""
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
    return EXIT_FAILED if report.failures else 0


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
    count = len(result.levels)
    if not 0 <= n < count:
        raise InvalidParameterError(f"--level must be in 0..{count - 1} (this run has {count} levels), got {n}")
    return result.levels[n]


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


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
