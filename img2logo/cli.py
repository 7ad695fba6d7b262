"""The ``img2logo`` command line.

``img2logo INPUT [--kind K] [--rdp R] [--min-length L] --segments-png OUT.png``
extracts the feature lines of INPUT, builds the segment graph L = {S, J} and
draws it (each segment its own colour, junctions as dots: paper Fig. 4b).

Errors in the input or the options print one line, ``img2logo: error: ...``, and
exit with status 2; nothing is written then.
"""

from __future__ import annotations

import argparse
import sys
import time
import warnings
from collections.abc import Sequence

from . import __version__
from .constants import MIN_SEGMENT_LENGTH, RDP_TOLERANCE
from .errors import Img2LogoError

EXIT_ERROR = 2


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="img2logo",
        description="Turn an image into a golden ratio logo: circular arcs on a phi circle grid.",
    )
    p.add_argument("input", help="input image (PNG, JPEG, ...): a photo, a clip art or a line drawing")
    p.add_argument(
        "--kind",
        choices=("auto", "photo", "clipart", "drawing"),
        default="auto",
        help="kind of input (default: auto, chosen from the image and reported)",
    )
    p.add_argument(
        "--rdp",
        type=float,
        default=RDP_TOLERANCE,
        metavar="PX",
        help=f"Ramer-Douglas-Peucker tolerance of the over-segmentation, px (default {RDP_TOLERANCE})",
    )
    p.add_argument(
        "--min-length",
        type=float,
        default=MIN_SEGMENT_LENGTH,
        metavar="PX",
        help=f"drop free-hanging segments shorter than this, px (default {MIN_SEGMENT_LENGTH})",
    )
    p.add_argument(
        "--foreground",
        choices=("none", "grabcut"),
        default="none",
        help="photos: keep only lines on the object found by GrabCut (default none)",
    )
    p.add_argument("--segments-png", metavar="OUT.png", help="draw the segment graph L = {S, J} to this PNG")
    p.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")
    p.add_argument("--version", action="version", version=f"img2logo {__version__}")
    return p


def main(argv: Sequence[str] | None = None) -> int:
    """Run the command line; return the exit status."""
    args = _parser().parse_args(argv)
    say = (lambda *a: None) if args.quiet else (lambda *a: print(*a, file=sys.stderr))
    try:
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            status = _run(args, say)
        for w in caught:
            say(f"img2logo: warning: {w.message}")
        return status
    except Img2LogoError as exc:
        print(f"img2logo: error: {exc}", file=sys.stderr)
        return EXIT_ERROR


def _run(args: argparse.Namespace, say) -> int:
    from .preprocessing import extract_feature_lines, load_image
    from .segment_graph import build_segment_graph

    t0 = time.perf_counter()
    image = load_image(args.input)
    foreground = None if args.foreground == "none" else args.foreground
    lines = extract_feature_lines(image, kind=args.kind, foreground=foreground)
    say(f"{args.input}: {image.width}x{image.height} px, kind {lines.kind} ({lines.reason})")
    graph = build_segment_graph(lines, rdp_tolerance=args.rdp, min_length=args.min_length)
    say(
        f"segment graph: {graph.n_segments} segments, {graph.n_junctions} nodes "
        f"({int((graph.valence >= 3).sum())} junctions), {graph.n_components()} components "
        f"in {time.perf_counter() - t0:.2f} s"
    )
    if args.segments_png:
        from .writers import write_segment_graph_png

        write_segment_graph_png(graph, args.segments_png, image=image.rgb)
        say(f"wrote {args.segments_png}")
    elif not args.quiet:
        say("nothing written: give --segments-png OUT.png to draw the segment graph")
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
