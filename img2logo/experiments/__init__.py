"""The notebook kit: paths, runs, the sweep, what a notebook shows, provenance.

A notebook is a parameters cell plus a few calls and plots: it asks this package
for paths (absolute, so a notebook runs from any folder), runs its images with
:func:`sweep` (one record type, :class:`Run`) and gets tables (pandas
DataFrames) and figures (:class:`matplotlib.figure.Figure`, never pyplot, in the
image pixel frame: x right, y down) back from ``results`` (Fig. 1, 4, 7, 8, 10,
Tables 1, 2), ``ablations`` (Fig. 6, 11, 12, 13), ``arc_selection`` (Fig. 9),
``design`` (Table 3, Fig. 15, 16), ``explore`` (the level explorer) and
``features`` (Fig. 17, 18), laid out with ``layout`` (panel grids, windows); ``provenance``
records where each figure came from. Tables hold no
timings unless they are about time: they are committed and must be the same
bytes from run to run. papermill and ipywidgets (the extra ``[kit]``) are
imported only by the functions that use them.
"""

from __future__ import annotations

import dataclasses
import os
import time
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

from ..constants import MIN_SEGMENT_LENGTH, RDP_TOLERANCE
from ..errors import Img2LogoError, InvalidParameterError
from ..features.preprocessing import FeatureLines, extract_feature_lines
from ..images.loading import LoadedImage
from ..segment_graph import SegmentGraph, build_segment_graph
from .paths import (  # noqa: F401  (re-exported)
    ROOT_ENV,
    data_path,
    eval_path,
    example_images,
    figure_dir,
    kit_module,
    load_example,
    project_root,
    repo_relative,
)
from .provenance import (
    PROVENANCE_PACKAGES as PROVENANCE_PACKAGES,
    environment as environment,
    write_provenance as write_provenance,
)
from .runner import check_parameters as check_parameters

if TYPE_CHECKING:
    import pandas as pd

    from ..fit.progressive import Progression
    from ..geometry.abstraction import Abstraction
    from ..pipeline import Result


# --------------------------------------------------------------------------- outputs shown
@dataclass(frozen=True, eq=False)
class SavedFigure:
    """A figure file a notebook wrote; Jupyter displays the file itself.

    The image shown in the notebook (an ``image/png`` or ``image/svg+xml``
    output) is the bytes of ``path``: the same figure as in ``figures/``, not a
    second rendering.
    """

    path: Path

    def _repr_png_(self) -> bytes | None:
        return self.path.read_bytes() if self.path.suffix.lower() == ".png" else None

    def _repr_svg_(self) -> str | None:
        return self.path.read_text(encoding="utf-8") if self.path.suffix.lower() == ".svg" else None

    def __repr__(self) -> str:
        return f"figure {repo_relative(self.path)}"


@dataclass(frozen=True, eq=False)
class SavedTable:
    """A table (a pandas DataFrame) a notebook shows, and the CSV it wrote, if any.

    Jupyter displays it without the index: the CSV has no index column, so
    neither has the table shown (a row number beside a ``t`` or ``image``
    column only repeats it). Floats are shown with ``TABLE_DIGITS`` significant
    digits (:func:`rounded`); the CSV keeps 6.
    """

    path: Path | None
    table: Any

    def _repr_html_(self) -> str:
        return self._shown().to_html(index=False, float_format=rounded, na_rep="")

    def __repr__(self) -> str:
        return self._shown().to_string(index=False, float_format=rounded, na_rep="")

    def _shown(self) -> Any:
        """The table with nullable integer columns as floats, so a missing value shows empty (as in the CSV)."""
        import pandas as pd

        nullable = [c for c, t in self.table.dtypes.items() if isinstance(t, pd.api.extensions.ExtensionDtype)]
        nullable = [c for c in nullable if pd.api.types.is_integer_dtype(self.table[c].dtype)]
        return self.table.astype({c: "float64" for c in nullable}) if nullable else self.table


# --------------------------------------------------------------------------- the kit's figure style
# Figure size, font size and dpi are set together here, for every notebook: what a
# reader sees is pt * dpi / 72 * shrink px, where JupyterLab shrinks a figure wider
# than its output area to that width.
#: Resolution of the kit's figures, dots per inch (the PNG writer's).
FIGURE_DPI: float = 100.0
#: Width of a notebook's output area in JupyterLab 4 in a 1366 x 768 browser window with its
#: file browser open, px (measured in chromium; a make html page there has 1244 px).
NOTEBOOK_WIDTH_PX: float = 934.0
#: Smallest text a figure shows on screen at that width, px (about 7.5 pt at 1:1: the
#: smallest size set for reading, not only for recognising, on a screen).
MIN_TEXT_PX: float = 10.0
#: Significant digits of the floats a notebook's table shows (a timing to 1 ms of a second,
#: an error to 0.01 px of ~1 px); the CSV files keep 6.
TABLE_DIGITS: int = 3


def rounded(value: float) -> str:
    """``value`` with ``TABLE_DIGITS`` significant digits (but all its units), trailing zeros dropped (12.0 -> "12")."""
    import math

    import numpy as np

    v = float(value)
    if not math.isfinite(v):
        return str(v)
    if v != 0.0 and not 1e-4 <= abs(v) < 1e7:
        return np.format_float_scientific(v, precision=TABLE_DIGITS - 1, unique=False, trim="-")
    if abs(v) >= 10 ** (TABLE_DIGITS - 1):  # never round the units away (1234.5 -> "1234", not "1230")
        return f"{v:.0f}"
    return np.format_float_positional(v, precision=TABLE_DIGITS, unique=False, fractional=False, trim="-")


def make_legible(fig: Any, *, dpi: float = FIGURE_DPI) -> Any:
    """Raise every text of ``fig`` to at least ``MIN_TEXT_PX`` on screen in a notebook; return ``fig``.

    A figure ``w`` inches wide saved at ``dpi`` is shown ``min(1, NOTEBOOK_WIDTH_PX /
    (w * dpi))`` times its pixel size, so a text needs at least ``MIN_TEXT_PX * 72 /
    (dpi * that)`` points. Texts already larger are left alone; constrained layout
    (the kit's figures use it) makes room for the larger ones when the figure is saved.
    """
    from matplotlib.text import Text

    shown = min(1.0, NOTEBOOK_WIDTH_PX / (fig.get_figwidth() * dpi))
    least = MIN_TEXT_PX * 72.0 / (dpi * shown)
    for ax in fig.axes:  # tick labels made when the figure is drawn take the axis' tick label size
        for axis in (ax.xaxis, ax.yaxis):
            ticks = axis.get_major_ticks()
            if ticks and ticks[0].label1.get_fontsize() < least:
                axis.set_tick_params(which="both", labelsize=least)
    for text in fig.findobj(Text):
        if text.get_text() and text.get_fontsize() < least:
            text.set_fontsize(least)
    return fig


def save_figure(fig: Any, path: str | os.PathLike[str], *, dpi: float | None = None) -> SavedFigure:
    """Write ``fig`` with :func:`img2logo.export.writers.save_figure` and return it for display.

    The last expression of a notebook cell, it shows the written file inline.
    ``dpi`` None is ``FIGURE_DPI``. The figure's texts are first raised to a
    legible size (:func:`make_legible`), then titles wider than their panels are
    broken onto more lines (:func:`img2logo.experiments.layout.fit_titles`).

    Raises
    ------
    FigureTextError
        If texts of the figure still overlap or leave it
        (:func:`img2logo.experiments.layout.text_problems`); nothing is written.
    """
    from ..export import writers
    from .layout import FigureTextError, fit_titles, text_problems

    d = FIGURE_DPI if dpi is None else dpi
    # A browser shows an SVG's points at 96 / 72 px each, whatever the dpi.
    make_legible(fig, dpi=d if Path(path).suffix.lower() != ".svg" else 96.0)
    fit_titles(fig)
    problems = text_problems(fig)
    if problems:
        more = f" (and {len(problems) - 1} more)" if len(problems) > 1 else ""
        raise FigureTextError(f"{Path(path).name}: the figure would not read: {problems[0]}{more}")
    return SavedFigure(Path(writers.save_figure(fig, path, dpi=d)))


def save_table(table: Any, path: str | os.PathLike[str]) -> SavedTable:
    """Write a pandas DataFrame as CSV (:func:`img2logo.export.writers.write_table`) and return it for display."""
    from ..export import writers

    return SavedTable(Path(writers.write_table(table, path)), table)


@dataclass(frozen=True)
class Prose:
    """Markdown a notebook computes from its run (numbers in its reading), shown as text by Jupyter."""

    markdown: str

    def _repr_markdown_(self) -> str:
        return self.markdown

    def __repr__(self) -> str:
        return self.markdown


def show_prose(markdown: str) -> Prose:
    """Show ``markdown`` as formatted text in a notebook: the sentences whose numbers come from the run."""
    return Prose(str(markdown))


def show_table(table: Any) -> SavedTable:
    """A pandas DataFrame for display without its index (a part of a table saved whole)."""
    return SavedTable(None, table)


# --------------------------------------------------------------------------- runs
@dataclass(frozen=True, eq=False)
class Run:
    """One image through the pipeline with one setting: the notebooks' one run record.

    Attributes
    ----------
    name : str
        The image's file stem, e.g. ``"clipart-fish"``.
    image : LoadedImage
    lines : FeatureLines
    graph : SegmentGraph
        L = {S, J}, the input of the optimization.
    result : Result or None
        The run: a :class:`img2logo.pipeline.Result` (its ``progression``, every level
        A^0 ... A^final; with ``pipeline=True`` also its ``timings``, ``params`` and
        ``symmetry``, from :func:`img2logo.abstract`; an optimize run's has empty ``timings``
        and ``params``). Its ``image``, ``lines`` and ``graph`` are the run's. None for an
        image only preprocessed (:func:`preprocess`).
    variant : str
        The label of the run's variant (:func:`sweep`), or ``""``.
    settings : mapping (read-only)
        The keywords of :func:`img2logo.fit.progressive.optimize` (or of
        :func:`img2logo.abstract`) the run was given, with the swept ones
        (``rdp_tolerance`` too when it was swept).
    seconds : tuple of float
        Wall time of each repeat of the run (the optimization, or the whole
        pipeline), s: for the notebook's text and the timing table, never for a
        table that must stay byte for byte.
    """

    name: str
    image: LoadedImage
    lines: FeatureLines
    graph: SegmentGraph
    result: Result | None = None
    variant: str = ""
    settings: Mapping[str, Any] = field(default_factory=lambda: MappingProxyType({}))
    seconds: tuple[float, ...] = ()

    @property
    def kind(self) -> str:
        """``"photo"``, ``"clipart"`` or ``"drawing"``."""
        return self.lines.kind

    @property
    def progression(self) -> Progression | None:
        """Every level A^0 ... A^final, the bias and stats (the result's); None for an image only preprocessed."""
        return None if self.result is None else self.result.progression

    @property
    def levels(self) -> tuple[Abstraction, ...]:
        """A^0 ... A^final, all of them made (the result's :attr:`~img2logo.pipeline.Result.levels`)."""
        return self._result.levels

    @property
    def final(self) -> Abstraction:
        """The result: the last level (the result's :attr:`~img2logo.pipeline.Result.final`)."""
        return self._result.final

    @property
    def bias(self) -> float:
        """The ladder bias sigma the run used."""
        return self._result.bias

    def level(self, t: int) -> Abstraction:
        """A^t; negative t counts from the end (the result's :meth:`~img2logo.pipeline.Result.level`)."""
        return self._result.level(t)

    @property
    def _result(self) -> Result:
        if self.result is None:
            raise Img2LogoError(f"{self.name} was only preprocessed: it has no levels")
        return self.result


def preprocess(
    paths: Iterable[Any],
    *,
    kind: str = "auto",
    rdp_tolerance: float = RDP_TOLERANCE,
    min_length: float = MIN_SEGMENT_LENGTH,
) -> list[Run]:
    """Load each image (a path, or anything :func:`img2logo.load_image` takes), find its feature lines, build its graph.

    Returns runs without levels (Sec. 4); ``seconds`` holds the time it took.
    """
    out = []
    for path in paths:
        start = time.perf_counter()
        image = load_example(path)
        lines = extract_feature_lines(image, kind=kind)
        graph = build_segment_graph(lines, rdp_tolerance=rdp_tolerance, min_length=min_length)
        name = Path(str(getattr(path, "source", path))).stem
        out.append(Run(name, image, lines, graph, seconds=(time.perf_counter() - start,)))
    return out


def sweep(
    images: Iterable[Any],
    grid: Mapping[str, Sequence[Any]] | None = None,
    variants: Mapping[str, Mapping[str, Any]] | None = None,
    *,
    repeats: int = 1,
    pipeline: bool = False,
    kind: str = "auto",
    progress: bool | None = None,
    **options: Any,
) -> list[Run]:
    """Run every image with every combination of the ``grid`` and every variant: the notebooks' one sweep.

    Parameters
    ----------
    images : iterable
        Paths (or loaded images), or runs of :func:`preprocess` (their feature
        lines and graph are used again).
    grid : mapping of str to sequence, optional
        Keyword -> the values it takes, e.g. ``{"tolerance": [4, 5, 9]}``: every
        combination runs, the first keyword outermost. ``rdp_tolerance`` and
        ``min_length`` rebuild the segment graph from the same feature lines.
    variants : mapping of str to mapping, optional
        Label -> keywords of the run (e.g. ablation switches); one unlabelled
        variant when None.
    repeats : int
        How often each run is made and timed (>= 1): round robin over all runs,
        so a burst of load from other processes spreads over them instead of
        skewing one; with more than one, an untimed run comes first (the first
        call in a process compiles the Fréchet kernel). The runs are
        deterministic: the last one is kept.
    pipeline : bool
        False: every run is :func:`img2logo.fit.progressive.optimize` on the
        image's segment graph. True: every run is :func:`img2logo.abstract`
        (a photo's arcs kept near its lines as on the command line; the feature
        lines found again for each run).
    kind : str
        The kind of input, or ``"auto"`` (for images not yet preprocessed).
    progress : bool, optional
        Show a bar of the runs done (``tqdm.auto``: a widget in Jupyter, text
        elsewhere), removed when the sweep ends. None (default): shown unless
        the environment variable ``IMG2LOGO_PROGRESS`` is ``"0"`` (papermill's
        runs for ``make figures``: no bar in the executed notebooks).
    **options
        Keywords shared by every run. A grid over ``tolerance`` runs with the
        paper's stopping rule, ``stretch=1``, unless ``stretch`` is given: a
        sweep over T shows T's effect alone, where the library's default goes
        on past T down to about ``LOGO_ARCS`` arcs.

    Returns
    -------
    list of Run
        Image-major, then the grid, then the variants in the order given;
        ``settings`` holds each run's keywords.

    Raises
    ------
    InvalidParameterError
        ``repeats`` is not a positive integer; a keyword or value the run
        refuses (:func:`img2logo.fit.progressive.optimize`, :func:`img2logo.abstract`).
    """
    from itertools import product

    from ..fit.progressive import optimize
    from ..pipeline import Result, abstract

    if isinstance(repeats, bool) or not isinstance(repeats, int) or repeats < 1:
        raise InvalidParameterError(f"repeats must be an integer >= 1, got {repeats!r}")
    grid = dict(grid or {})
    for name, values in grid.items():
        if not isinstance(values, list | tuple) or not values:
            raise InvalidParameterError(f"grid[{name!r}]: expected a non-empty list of values, got {values!r}")
    points = [dict(zip(grid, values, strict=True)) for values in product(*grid.values())]
    if "tolerance" in grid and "stretch" not in grid:  # T's effect alone: the paper's rule
        options = {"stretch": 1.0, **options}
    jobs: list[tuple[Run, str, dict[str, Any]]] = []
    for ex in images if pipeline else _preprocessed(images, kind):
        for point in points:
            for label, switches in (variants or {"": {}}).items():
                jobs.append((ex, label, {**options, **point, **switches}))

    def run(ex: Any, settings: dict[str, Any]) -> Run:
        if pipeline:
            r = abstract(load_example(ex.image if isinstance(ex, Run) else ex), kind=kind, progress=False, **settings)
            return Run(Path(str(r.image.source)).stem, r.image, r.lines, r.graph, r)
        shape = {k: settings.pop(k) for k in ("rdp_tolerance", "min_length") if k in settings}
        graph = build_segment_graph(ex.lines, **shape) if shape else ex.graph
        return dataclasses.replace(
            ex, graph=graph, result=Result(ex.image, ex.lines, graph, optimize(graph, **settings))
        )

    if progress is None:
        from .runner import PROGRESS_ENV

        progress = os.environ.get(PROGRESS_ENV, "1") != "0"
    bar = None
    if progress and jobs:
        from tqdm.auto import tqdm

        bar = tqdm(total=len(jobs) * repeats, desc="runs", unit="run", leave=False)
    try:
        if repeats > 1 and jobs:
            run(jobs[0][0], dict(jobs[0][2]))
        seconds: list[list[float]] = [[] for _ in jobs]
        done: list[Run] = []
        for _ in range(repeats):
            done = []
            for (ex, label, settings), times in zip(jobs, seconds, strict=True):
                start = time.perf_counter()
                result = run(ex, dict(settings))
                times.append(time.perf_counter() - start)
                done.append(dataclasses.replace(result, variant=label, settings=MappingProxyType(settings)))
                if bar is not None:
                    bar.set_postfix_str(ex.name if isinstance(ex, Run) else Path(str(ex)).name, refresh=False)
                    bar.update(1)
    finally:
        if bar is not None:
            bar.close()
    return [dataclasses.replace(r, seconds=tuple(t)) for r, t in zip(done, seconds, strict=True)]


def by_image(runs: Iterable[Run]) -> dict[str, list[Run]]:
    """The runs grouped by image name, images and runs in the order given."""
    out: dict[str, list[Run]] = {}
    for run in runs:
        out.setdefault(run.name, []).append(run)
    return out


def _preprocessed(images: Iterable[Any], kind: str) -> list[Run]:
    images = list(images)
    if all(isinstance(i, Run) for i in images):
        return images
    return preprocess(images, kind=kind)


def table(items: Iterable[Any], columns: Mapping[str, Callable[[Any], Any]]) -> pd.DataFrame:
    """The kit's one table builder: a pandas DataFrame, a row per item, a column per ``columns`` entry.

    ``columns`` maps a column's name to the function giving an item's value,
    e.g. ``table(runs, {"image": lambda r: r.name, "arcs": lambda r: len(r.final.arcs)})``;
    an empty ``items`` gives the columns without rows.
    """
    import pandas as pd

    rows = [{name: value(item) for name, value in columns.items()} for item in items]
    return pd.DataFrame(rows, columns=list(columns))


#: The first columns of a table of runs (:func:`table`): the image, its kind, |S|.
RUN_COLUMNS: dict[str, Callable[[Run], Any]] = {
    "image": lambda r: r.name,
    "kind": lambda r: r.kind,
    "segments": lambda r: r.graph.n_segments,
}


def preprocessing_table(examples: Iterable[Run]) -> pd.DataFrame:
    """Per example: its kind, |S|, its nodes by valence and its components (no timings: ``make bench`` has them)."""
    return table(
        examples,
        {
            **RUN_COLUMNS,
            "junctions (valence >= 3)": lambda r: int((r.graph.valence >= 3).sum()),
            "end points": lambda r: int((r.graph.valence == 1).sum()),
            "split points": lambda r: int((r.graph.valence == 2).sum()),
            "components": lambda r: r.graph.n_components(),
        },
    )


def plot_preprocessing(examples: Sequence[Run], *, panel_size: float = 3.0) -> Any:
    """One row per example: input | feature lines | segment graph (paper Fig. 4a, 4b)."""
    from ..export.plotting import plot_segment_graph
    from .layout import panel_grid, show_image

    fig, axes = panel_grid(len(examples), 3, panel_size)
    for row, ex in zip(axes, examples, strict=False):
        show_image(row[0], ex.image.rgb)
        show_image(row[1], ~ex.lines.lines, cmap="gray")
        plot_segment_graph(ex.graph, row[2])
        titles = (f"{ex.name} ({ex.lines.kind})", "feature lines", f"segments |S| = {ex.graph.n_segments}")
        for ax, title in zip(row, titles, strict=True):
            ax.set_title(title, fontsize=9)
    return fig
