"""`make quality`: what the logos keep of the evaluation set's features, and what they add.

Runs the whole pipeline at the default options on every image of
``benchmarks/data/`` (clip arts, line drawings and photo-like images with a
ground truth; ``benchmarks/data/README.md`` says how the truth was made), on
the second photo-like family ``benchmarks/data/photo2/`` (built by
``benchmarks/make_photo2.py`` the same way), on the held-out clip arts and
drawings of ``benchmarks/data/heldout/`` (built by ``benchmarks/make_heldout.py``
from OpenCV's drawing primitives, JPEG and thick variants included: families
``heldout clipart`` and ``heldout drawing``), on the held-out photo-likes of
``benchmarks/data/heldout-photo/`` (built by ``benchmarks/make_photo2.py`` after
the code it checks, not tuned on: family ``heldout photo``) and on the photos of ``data/`` (no
truth: only arcs, crossings and gaps), on five real photos that ship with
scikit-image (family ``real``, no truth either: :data:`REAL_PHOTOS`) and on thick versions of the drawings of
``data/`` (kind "thick drawing": strokes widened by 9 and 13 px; the truth is
the thin original's feature lines), then prints one row per image and the
means per family (the kind; ``photo2``; the three held-out families; ``data``; ``real``), writes them to
``build/quality/quality.csv`` and draws one contact sheet per family,
``build/quality/contact-<family>.png``: input | ground truth, the pixels farther
than 10 px from the logo in red | logo.

Columns: kind (true) and detected; arcs; r3, r6, r10 (fraction of the truth's
feature pixels within 3, 6, 10 px of the logo's arcs and lines, sampled every
0.5 px); sil6 (fraction of the object mask's outline within 6 px of the logo's arcs) and sil6 drawn
(the same within 6 px of the logo as drawn: for a detected drawing, of its stroke's edge, the logo
being drawn at the drawing's own stroke weight; for every other kind, sil6) and outside (fraction
of the logo's points farther than 12 px from the mask),
for photo-likes, against the object's silhouette for the Openclipart families; crossings; gaps
(near-miss gaps: open ends 0.75-6 px from another arc); free ends (arc ends, not of whole circles,
that no other arc comes within 0.75 px of: in a clip art, broken outlines); line ends (the ends of
the input's feature lines, nodes of valence 1 of the segment graph: a stroke that ends, a clip art's
thin mark drawn as its centre line; free ends beyond them were made by the fit); joins (junctions where
exactly two arcs end and the input's feature line turns by less than 10 degrees), tangent (the fraction of them where
the two arcs kink by less than 2 degrees) and kink (their median kink, degrees);
ink lost (dark parts of the input of at least 30 px with no logo
point within 3 px, for clip arts and drawings: an eye the skeleton truth hides
from r10); stroke ratio (the logo's stroke width over the input's median stroke
width, for drawings); seconds (the whole pipeline, one process per image at a time). Below the means
per kind, the joins of the evaluation set's clip arts and drawings pooled.

A benchmark, not a test: it prints and never fails on a bad number. An image
whose run fails is a row with its error.
"""

from __future__ import annotations

import argparse
import fnmatch
import json
import sys
import time
import warnings
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
EVAL = ROOT / "benchmarks" / "data"
#: The second photo-like family (``benchmarks/make_photo2.py``), reported with its own means.
PHOTO2 = EVAL / "photo2"
#: The held-out clip arts and drawings (``benchmarks/make_heldout.py``): families ``heldout clipart``
#: and ``heldout drawing``, each with its own means.
HELDOUT = EVAL / "heldout"
#: The held-out photo-likes (``benchmarks/make_photo2.py``'s ``HELDOUT_CASES``): family ``heldout photo``.
HELDOUT_PHOTO = EVAL / "heldout-photo"
#: Real clip art and line art from Openclipart (``benchmarks/data/openclipart/README.md``): families
#: ``openclipart clipart`` and ``openclipart drawing``; sil6 is measured against each object's silhouette.
OPENCLIPART = EVAL / "openclipart"
OUT = ROOT / "build" / "quality"
#: The docs site's quality page, rewritten by a full run (no ``--only``).
DOCS_PAGE = ROOT / "docs" / "quality.md"
COLUMNS = (
    "name",
    "family",
    "kind",
    "detected",
    "arcs",
    "r3",
    "r6",
    "r10",
    "sil6",
    "sil6 drawn",
    "outside",
    "crossings",
    "gaps",
    "free ends",
    "line ends",
    "joins",
    "tangent",
    "kink",
    "seconds",
)
#: The columns of what a designer sees beside the features (:func:`ink_columns`).
INK_COLUMNS = ("ink lost", "stroke ratio")


def cases() -> list[dict]:
    """The evaluation set's manifest entries, the second photo-like family, the held-out clip arts and
    drawings, the held-out photo-likes, then the photos of data/ (no truth) and the thick drawings.

    ``family`` is the kind, except for the second photo-like family (``photo2``),
    the held-out images (``heldout clipart``, ``heldout drawing``, ``heldout photo``) and the photos
    of ``data/`` (``data``): the means are per family.
    """
    out = []
    for folder in (EVAL, PHOTO2, HELDOUT, HELDOUT_PHOTO, OPENCLIPART):
        manifest = json.loads((folder / "manifest.json").read_text(encoding="utf-8"))
        for m in manifest:
            family = f"openclipart {m['kind']}" if folder == OPENCLIPART else m.get("family", m["kind"])
            name = f"openclipart/{m['name']}" if folder == OPENCLIPART else m["name"]
            out.append(dict(m, name=name, family=family, path=folder / m["file"], folder=folder))
    for path in sorted((ROOT / "data").glob("photo-*.png")):
        out.append({"name": f"data/{path.stem}", "kind": "photo", "family": "data", "path": path, "folder": EVAL})
    for path in real_photos():
        out.append({"name": f"real/{path.stem}", "kind": "photo", "family": "real", "path": path, "folder": EVAL})
    for path in sorted((ROOT / "data").glob("drawing-*.png")):
        for kernel in THICK_KERNELS:
            out.append(
                {
                    "name": f"thick/{path.stem}-{kernel}",
                    "kind": THICK,
                    "family": THICK,
                    "original": path,
                    "kernel": kernel,
                }
            )
    return out


#: Real photos that ship with scikit-image (``skimage.data``'s files; each licence is in its function's
#: docstring: CC0 or public domain): a portrait, a cup on a table, a launch pad at dusk, a motorcycle in a
#: cluttered garage, a gray cameraman on a lawn. No truth: the family ``real`` reports arcs, crossings,
#: gaps and seconds, and its contact sheet shows what a user would get. (``chelsea.png`` is ``data/photo-cat.png``.)
REAL_PHOTOS = ("astronaut.png", "coffee.png", "rocket.jpg", "motorcycle_left.png", "camera.png")


def real_photos() -> list[Path]:
    """The files of :data:`REAL_PHOTOS` in the installed scikit-image (those it has)."""
    import skimage.data

    folder = Path(skimage.data.__file__).parent
    return [folder / name for name in REAL_PHOTOS if (folder / name).is_file()]


#: Kind of the thick versions of data/'s drawings: their strokes widened by eroding the paper
#: with elliptical kernels of these sizes, px (13 px strokes become 20 and 24 px). They must be
#: read as drawings; their truth is the feature lines of the thin original (its centre lines).
THICK = "thick drawing"
THICK_KERNELS = (9, 13)


def thick_case(case: dict):
    """The image and truth of a thick version of a drawing: (RGB uint8 array, (H, W) bool)."""
    import cv2

    from img2logo import extract_feature_lines

    image = cv2.imread(str(case["original"]))[:, :, ::-1]
    kernel = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (case["kernel"], case["kernel"]))
    return np.ascontiguousarray(cv2.erode(image, kernel)), extract_feature_lines(case["original"]).lines


def run_case(case: dict, **settings) -> tuple[dict, object]:
    """One image's row of measures and its (result, truth); ``settings`` go to :func:`img2logo.abstract`."""
    from img2logo import Img2LogoError, abstract, load_mask, quality

    row: dict = {"name": case["name"], "family": case["family"], "kind": case["kind"]}
    start = time.perf_counter()
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            image, thin = thick_case(case) if case["kind"] == THICK else (case["path"], None)
            result = abstract(image, progress=False, **settings)
    except Img2LogoError as exc:
        row.update(detected="-", error=str(exc), seconds=time.perf_counter() - start)
        return row, None
    row["seconds"] = time.perf_counter() - start
    truth = load_mask(case["folder"] / case["gt"]) if "gt" in case else thin
    outline = case.get("mask") or case.get("silhouette")  # the object whose outline sil6 measures
    mask = load_mask(case["folder"] / outline) if outline else None
    # A line drawing's logo is drawn at its own stroke weight (recorded by abstract): sil6 measures that stroke's edge.
    stroke = result.final.params.get("stroke_width", 0.0) if result.lines.kind == "drawing" else 0.0
    q = quality.measure(result.final, truth, mask)
    drawn = q.silhouette
    if mask is not None and stroke > 0:
        drawn = quality.silhouette_recall(quality.logo_points(result.final), mask, stroke_width=stroke)
    found = quality.joins(result.final, result.graph)
    row.update(
        detected=result.lines.kind,
        arcs=q.arcs,
        r3=q.recall[0],
        r6=q.recall[1],
        r10=q.recall[2],
        sil6=q.silhouette,
        **{"sil6 drawn": drawn},
        outside=q.outside,
        crossings=q.crossings,
        gaps=q.gaps,
        **{"free ends": q.free_ends, "line ends": int(np.count_nonzero(result.graph.valence == 1))},
        joins=found.count,
        tangent=found.tangent_fraction(),
        kink=np.degrees(found.median_kink),
        kinks=np.degrees(found.kinks),
    )
    row.update(ink_columns(case, result))
    return row, (result, truth)


def ink_columns(case: dict, result) -> dict:
    """Ink parts lost (clip arts, drawings) and the stroke width ratio (drawings) of one run."""
    from img2logo import quality
    from img2logo.export.plotting import level_stroke_width
    from img2logo.quality import INK_PART_GRAY

    out = dict.fromkeys(INK_COLUMNS, np.nan)
    if case["kind"] in ("clipart", "drawing", THICK):
        points = quality.logo_points(result.final)
        out["ink lost"] = len(quality.lost_ink_parts(points, result.image.gray))
    if case["kind"] in ("drawing", THICK):
        ink = result.image.gray < INK_PART_GRAY
        out["stroke ratio"] = quality.stroke_width_ratio(level_stroke_width(result.final), ink)
    return out


def contact_sheet(kind: str, runs: list[tuple[dict, object]], path: Path) -> None:
    from img2logo import plot_abstraction, quality
    from img2logo.experiments.layout import panel_grid
    from img2logo.export.writers import save_figure

    fig, axes = panel_grid(len(runs), 3, 3.0)
    for (row, run), ax_row in zip(runs, axes, strict=True):
        for ax in ax_row:
            ax.set_axis_off()
        if run is None:
            ax_row[0].set_title(f"{row['name']}: failed", fontsize=8)
            ax_row[1].text(0.0, 0.5, row.get("error", "")[:200], fontsize=6, wrap=True)
            continue
        result, truth = run
        ax_row[0].imshow(result.image.rgb)
        ax_row[0].set_title(f"{row['name']} ({row['detected']})", fontsize=8)
        if truth is not None:
            missed = quality.missed_pixels(quality.logo_points(result.final), truth, 10.0)
            shown = np.ones((*truth.shape, 3))
            shown[truth] = (0.6, 0.6, 0.6)
            shown[missed] = (0.9, 0.0, 0.0)
            ax_row[1].imshow(shown, interpolation="nearest")
            ax_row[1].set_title(f"truth, missed in red (r10 {row['r10']:.2f})", fontsize=8)
        plot_abstraction(result.final, ax_row[2], linewidth=1.2)
        ax_row[2].set_title(f"{row['arcs']} arcs, {row['crossings']} crossings, {row['gaps']} gaps", fontsize=8)
    save_figure(fig, path, dpi=60)


def markdown_table(frame) -> str:
    """A pandas table as a Markdown pipe table, numbers to 2 decimals, empty cells for NaN."""

    def cell(value) -> str:
        if isinstance(value, float):
            return "" if np.isnan(value) else f"{value:.2f}"
        return str(value).replace("|", "\\|")

    lines = ["| " + " | ".join(str(c) for c in frame.columns) + " |", "|" + " --- |" * len(frame.columns)]
    lines += ["| " + " | ".join(cell(v) for v in row) + " |" for row in frame.itertuples(index=False)]
    return "\n".join(lines)


def write_page(path: Path, table, means, pooled: str, argv: list[str]) -> None:
    """Write the docs page of a run: the means per family, the pooled joins, one row per image.

    The page says the date and the command that reproduces it; it is written whole or not at all.
    """
    import shlex

    command = " ".join(["python benchmarks/quality.py", *map(shlex.quote, argv)])
    # Seconds are the performance page's (make bench): taken here, beside the others' work, they say little.
    family_means = means.reset_index().drop(columns=["seconds", "most seconds"], errors="ignore")
    front = ["family", "images", "kind right", "failed"]
    family_means = family_means[front + [c for c in family_means.columns if c not in front]]
    text = "\n\n".join(
        [
            "# Quality",
            f"Written by `{command}` (or `make quality`) on {time.strftime('%Y-%m-%d', time.gmtime())}; "
            "the measures are those of `img2logo.quality` and the families those of the script's docstring "
            "(`benchmarks/quality.py`). Contact sheets of each family go to `build/quality/`.",
            "## Means per family",
            markdown_table(family_means),
            *([pooled + "."] if pooled else []),
            "## One row per image",
            markdown_table(table.drop(columns=["error", "seconds"], errors="ignore")),
        ]
    )
    partial = path.with_name(path.name + ".part")
    partial.write_text(text + "\n", encoding="utf-8")
    partial.replace(path)


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--only", default="*", help="run the images whose name matches this glob (e.g. 'clipart-*')")
    parser.add_argument("--no-sheets", action="store_true", help="skip the contact sheets")
    parser.add_argument("--out", type=Path, default=OUT, help="output folder (default build/quality)")
    parser.add_argument(
        "--docs",
        type=Path,
        default=None,
        help="write the tables as the docs page PATH (default: docs/quality.md on a full run, none with --only)",
    )
    parser.add_argument(
        "--arcs",
        type=int,
        default=None,
        metavar="N",
        help="run with abstract(..., arcs=N), the clip arts' arc budget (default: the default options)",
    )
    parser.add_argument(
        "--set",
        action="append",
        default=[],
        metavar="NAME=VALUE",
        help="run with abstract(..., NAME=VALUE), a number (e.g. --set stretch=1, --set tolerance=7); repeatable",
    )
    args = parser.parse_args(argv)
    settings: dict = {} if args.arcs is None else {"arcs": args.arcs}
    for item in args.set:
        name, _, value = item.partition("=")
        try:
            settings[name.strip()] = float(value)
        except ValueError:
            parser.error(f"--set takes NAME=NUMBER, got {item!r}")
    if settings and args.docs is None and args.only == "*":
        parser.error("--arcs and --set measure options other than the defaults: give --only or --docs")

    import pandas as pd

    selected = [c for c in cases() if fnmatch.fnmatch(c["name"], args.only)]
    runs = []
    for case in selected:
        row, run = run_case(case, **settings)
        runs.append((row, run))
        status = f"failed: {row['error']}" if run is None else f"{row['arcs']} arcs, r10 {row['r10']:.2f}"
        print(f"  {row['name']:28s} {row['seconds']:6.1f} s  {status}", file=sys.stderr, flush=True)
    table = pd.DataFrame([{k: v for k, v in r.items() if k != "kinks"} for r, _ in runs])
    for col in (*COLUMNS, *INK_COLUMNS):
        if col not in table:
            table[col] = np.nan
    table = table[[*COLUMNS, *INK_COLUMNS, *(["error"] if "error" in table else [])]]
    args.out.mkdir(parents=True, exist_ok=True)
    table.to_csv(args.out / "quality.csv", index=False, float_format="%.3f")
    with pd.option_context("display.width", 200, "display.max_columns", 40, "display.max_colwidth", 60):
        print(table.drop(columns=["error"], errors="ignore").to_string(index=False, float_format="%.2f"))
        numeric = [*COLUMNS[COLUMNS.index("arcs") :], *INK_COLUMNS]  # every measured column
        by = table["family"]
        means = table.groupby(by)[numeric].mean()
        means["least sil6"] = table.groupby(by)["sil6"].min()
        for col in ("free ends", "arcs"):  # a patchwork shows in the median and the worst image
            means[f"median {col}"] = table.groupby(by)[col].median()
            means[f"most {col}"] = table.groupby(by)[col].max()
        means["most seconds"] = table.groupby(by)["seconds"].max()
        means["images"] = table.groupby(by).size()
        means["failed"] = table.groupby(by)["detected"].apply(lambda s: int((s == "-").sum()))
        expected = table["kind"].replace({THICK: "drawing"})
        means["kind right"] = (expected == table["detected"]).groupby(by).sum()
        print(
            "\nMeans per family (the kind, or photo2: the second photo-like family; heldout: the held-out "
            "clip arts, drawings and photo-likes; data: the photos of data/; real: scikit-image's real photos)"
        )
        print(means.to_string(float_format="%.2f"))
    kinks = np.concatenate(
        [r["kinks"] for r, _ in runs if r["family"] in ("clipart", "drawing") and "kinks" in r] or [np.zeros(0)]
    )
    pooled = ""
    if len(kinks):
        pooled = (
            f"Joins on smooth input, clip arts and drawings pooled: {len(kinks)} joins, "
            f"{100 * np.mean(kinks < 2.0):.0f} % tangent (< 2 degrees), median kink {np.median(kinks):.1f} degrees"
        )
        print("\n" + pooled)
    page = args.docs if args.docs is not None else (DOCS_PAGE if args.only == "*" else None)
    if page is not None:
        write_page(page, table, means, pooled, argv if argv is not None else sys.argv[1:])
        print(f"wrote {page}")
    if not args.no_sheets:
        for kind in sorted(table["family"].unique()):
            chosen = [(r, run) for r, run in runs if r["family"] == kind]
            contact_sheet(kind, chosen, args.out / f"contact-{kind.replace(' ', '-')}.png")
    print(f"\nwrote {args.out / 'quality.csv'} and the contact sheets beside it")
    return 0


if __name__ == "__main__":
    sys.exit(main())
