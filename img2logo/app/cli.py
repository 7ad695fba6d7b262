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
from ..errors import Img2LogoError, OutputError
from .commands import freeze_heap, run_folder, run_image

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


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line, ``img2logo: error: ...`` (exit status 2), not usage + error.

    An argument that starts with ``-`` and is no option (``-x.png``) is named, with
    the way to give a file of that name (``img2logo -- -x.png``).
    """

    def parse_args(self, args=None, namespace=None):  # type: ignore[override]
        self._given = list(sys.argv[1:] if args is None else args)
        return super().parse_args(self._given, namespace)

    def add_argument(self, *args, **kwargs):  # type: ignore[no-untyped-def]
        # argparse makes a help formatter for every option added, only to check its metavar; that
        # check needs no width, which the formatter would ask the terminal for (importing shutil).
        self._checking_metavar = True
        try:
            return super().add_argument(*args, **kwargs)
        finally:
            self._checking_metavar = False

    def _get_formatter(self) -> argparse.HelpFormatter:
        if getattr(self, "_checking_metavar", False):
            return self.formatter_class(prog=self.prog, width=80)  # type: ignore[call-arg]
        return super()._get_formatter()

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
    command = argv is None  # the process is the command: its heap is frozen (see freeze_heap)
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
                    status = EXIT_FAILED if run_folder(args, say) else 0
                else:
                    status = run_image(args, say, freeze=command)
                if command:
                    freeze_heap()
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
    frozen (:func:`freeze_heap`): the imports make hundreds of thousands of
    objects that live as long as the process, and the collections during them
    only walked those (a tenth of numpy's import).
    """
    if "numpy" not in sys.modules:
        for var in THREAD_VARIABLES:
            os.environ.setdefault(var, "1")
    gc.disable()


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


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
