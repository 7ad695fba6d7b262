"""Helpers for the notebooks: where data and figures live, sweeps and figure layouts.

Notebooks communicate, the library computes: a notebook asks this package for
paths (absolute, so a notebook runs from any working directory; it never
writes ``../data`` itself), runs the sweeps it defines and gets the figures
and tables back. Submodules group them by the paper's evaluation:
``results`` (Fig. 1, 4, 7, 8, 10, Tables 1, 2), ``ablations`` (Fig. 6, 9, 11,
12, 13), ``design`` (Table 3, Fig. 15, 16, the level explorer).
"""

from __future__ import annotations

import dataclasses
import os
import time
from collections.abc import Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..constants import MIN_SEGMENT_LENGTH, RDP_TOLERANCE
from ..errors import Img2LogoError
from ..preprocessing import FeatureLines, LoadedImage, extract_feature_lines, load_image
from ..segment_graph import SegmentGraph, build_segment_graph

#: Environment variable naming the repository root, when it cannot be found.
ROOT_ENV = "IMG2LOGO_ROOT"
_MARKER = Path("data") / "ATTRIBUTION.md"


def project_root() -> Path:
    """The repository root: the folder holding ``data/ATTRIBUTION.md``.

    Looked up from ``$IMG2LOGO_ROOT``, then upwards from the working directory,
    then upwards from this package (an editable install inside the repository).
    """
    env = os.environ.get(ROOT_ENV)
    if env:
        root = Path(env).resolve()
        if not (root / _MARKER).is_file():
            raise Img2LogoError(f"${ROOT_ENV}={env} does not hold {_MARKER}")
        return root
    for start in (Path.cwd(), Path(__file__).resolve().parent.parent):
        for folder in (start, *start.parents):
            if (folder / _MARKER).is_file():
                return folder
    raise Img2LogoError(f"cannot find the img2logo repository (a folder with {_MARKER}); set ${ROOT_ENV}")


def data_path(name: str) -> Path:
    """Absolute path of an example image in ``data/``, e.g. ``data_path("clipart-fish.png")``."""
    path = project_root() / "data" / name
    if not path.is_file():
        available = ", ".join(sorted(p.name for p in (project_root() / "data").glob("*.png")))
        raise Img2LogoError(f"no example image {name!r} in data/; available: {available}")
    return path


def repo_relative(path: str | os.PathLike[str]) -> str:
    """``path`` relative to the repository root (``data/clipart-fish.png``), POSIX style.

    A path outside the repository is returned absolute. Result documents name
    their input this way, so a ``make figures`` in any checkout writes the same
    bytes.
    """
    resolved = Path(path).resolve()
    try:
        return resolved.relative_to(project_root()).as_posix()
    except ValueError:
        return str(resolved)


def load_example(path: Any) -> LoadedImage:
    """:func:`img2logo.load_image`, with ``source`` relative to the repository (:func:`repo_relative`).

    A path is loaded and its ``source`` made relative; a loaded image or an
    array goes to :func:`img2logo.load_image` unchanged.
    """
    if not isinstance(path, str | os.PathLike):
        return load_image(path)
    return dataclasses.replace(load_image(path), source=repo_relative(path))


def example_images(prefix: str = "") -> list[Path]:
    """The example images of ``data/`` whose names start with ``prefix``, sorted."""
    return sorted((project_root() / "data").glob(f"{prefix}*.png"))


def figure_dir(notebook: str, *, smoke: bool = False) -> Path:
    """The output folder of a notebook, created: ``figures/<notebook>/``.

    Smoke runs (CI) write to ``build/smoke/<notebook>/`` instead, never over the
    committed figures.
    """
    base = project_root() / ("build/smoke" if smoke else "figures")
    out = base / notebook
    out.mkdir(parents=True, exist_ok=True)
    return out


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
    column only repeats it). Floats are shown as in the CSV (6 significant digits).
    """

    path: Path | None
    table: Any

    def _repr_html_(self) -> str:
        return self._shown().to_html(index=False, float_format=lambda v: f"{v:.6g}", na_rep="")

    def __repr__(self) -> str:
        return self._shown().to_string(index=False, float_format=lambda v: f"{v:.6g}", na_rep="")

    def _shown(self) -> Any:
        """The table with nullable integer columns as floats, so a missing value shows empty (as in the CSV)."""
        import pandas as pd

        nullable = [c for c, t in self.table.dtypes.items() if isinstance(t, pd.api.extensions.ExtensionDtype)]
        nullable = [c for c in nullable if pd.api.types.is_integer_dtype(self.table[c].dtype)]
        return self.table.astype({c: "float64" for c in nullable}) if nullable else self.table


def save_figure(fig: Any, path: str | os.PathLike[str], *, dpi: float | None = None) -> SavedFigure:
    """Write ``fig`` with :func:`img2logo.writers.save_figure` and return it for display.

    The last expression of a notebook cell, it shows the written file inline.
    ``dpi`` None is the writer's default.
    """
    from .. import writers

    kwargs = {} if dpi is None else {"dpi": dpi}
    return SavedFigure(Path(writers.save_figure(fig, path, **kwargs)))


def save_table(table: Any, path: str | os.PathLike[str]) -> SavedTable:
    """Write a pandas DataFrame as CSV (:func:`img2logo.writers.write_table`) and return it for display."""
    from .. import writers

    return SavedTable(Path(writers.write_table(table, path)), table)


def show_table(table: Any) -> SavedTable:
    """A pandas DataFrame for display without its index (a part of a table saved whole)."""
    return SavedTable(None, table)


# --------------------------------------------------------------------------- preprocessing
@dataclass(frozen=True, eq=False)
class Preprocessed:
    """One example through preprocessing: image, feature lines, segment graph, time (s)."""

    name: str
    image: LoadedImage
    lines: FeatureLines
    graph: SegmentGraph
    seconds: float


def preprocess(
    paths: Iterable[str | os.PathLike[str]],
    *,
    kind: str = "auto",
    rdp_tolerance: float = RDP_TOLERANCE,
    min_length: float = MIN_SEGMENT_LENGTH,
) -> list[Preprocessed]:
    """Load each image, extract its feature lines and build its segment graph (Sec. 4)."""
    out = []
    for path in paths:
        start = time.perf_counter()
        image = load_example(path)
        lines = extract_feature_lines(image, kind=kind)
        graph = build_segment_graph(lines, rdp_tolerance=rdp_tolerance, min_length=min_length)
        out.append(Preprocessed(Path(path).stem, image, lines, graph, time.perf_counter() - start))
    return out


def preprocessing_table(examples: Iterable[Preprocessed]) -> Any:
    """A pandas DataFrame: per example its kind, |S|, node counts by valence, components.

    No timings: the table is a committed figure and must not change from run to
    run; ``make bench`` measures speed.
    """
    import pandas as pd

    rows = []
    for ex in examples:
        g = ex.graph
        rows.append(
            {
                "image": ex.name,
                "kind": ex.lines.kind,
                "segments": g.n_segments,
                "junctions (valence >= 3)": int((g.valence >= 3).sum()),
                "end points": int((g.valence == 1).sum()),
                "split points": int((g.valence == 2).sum()),
                "components": g.n_components(),
            }
        )
    return pd.DataFrame(rows)


def plot_preprocessing(examples: list[Preprocessed], *, panel_size: float = 3.0) -> Any:
    """A figure, one row per example: input | feature lines | segment graph (paper Fig. 4a, 4b)."""
    from matplotlib.figure import Figure

    from ..plotting import plot_segment_graph

    fig = Figure(figsize=(3 * panel_size, panel_size * max(1, len(examples))), layout="constrained")
    axes = fig.subplots(max(1, len(examples)), 3, squeeze=False)
    for row, ex in zip(axes, examples, strict=False):
        row[0].imshow(ex.image.rgb, extent=(0, ex.image.width, ex.image.height, 0))
        row[0].set_title(f"{ex.name} ({ex.lines.kind})", fontsize=9)
        row[1].imshow(~ex.lines.lines, cmap="gray", extent=(0, ex.image.width, ex.image.height, 0))
        row[1].set_title("feature lines", fontsize=9)
        plot_segment_graph(ex.graph, row[2])
        row[2].set_title(f"segments |S| = {ex.graph.n_segments}", fontsize=9)
        for ax in row:
            ax.set_axis_off()
    return fig


# --------------------------------------------------------------------------- provenance
def write_provenance(executed: str | os.PathLike[str]) -> Path:
    """Write ``figures/<notebook>/provenance.json`` for a notebook papermill executed.

    It records the git commit of the repository (and whether the work tree had
    uncommitted changes), the parameters papermill injected and the defaults of
    the notebook's parameters cell, and the date of the run (UTC): what a
    reader needs to know where a committed figure came from.
    """
    import datetime
    import json
    import subprocess

    from .._io import atomic_write

    path = Path(executed)
    nb = json.loads(path.read_text(encoding="utf-8"))
    meta = nb.get("metadata", {}).get("papermill", {})
    defaults = next(
        ("".join(c["source"]) for c in nb["cells"] if "parameters" in c.get("metadata", {}).get("tags", [])), ""
    )
    root = project_root()

    def git(*args: str) -> str:
        done = subprocess.run(["git", *args], cwd=root, capture_output=True, text=True, check=False)
        return done.stdout.strip() if done.returncode == 0 else "unknown"

    record = {
        "notebook": f"notebooks/{path.name}",
        "git_commit": git("rev-parse", "HEAD"),
        "uncommitted_changes": bool(git("status", "--porcelain", "--", "img2logo", "notebooks", "data")),
        "parameters_injected": meta.get("parameters", {}),
        "parameters_cell": defaults,
        "date_utc": datetime.datetime.now(datetime.UTC).strftime("%Y-%m-%dT%H:%M:%SZ"),
        "duration_s": round(float(meta.get("duration") or 0.0), 1),
    }
    target = figure_dir(path.stem) / "provenance.json"
    text = json.dumps(record, indent=2, sort_keys=True) + "\n"
    return atomic_write(target, lambda f: f.write(text.encode("utf-8")))


from .runner import check_parameters as check_parameters  # noqa: E402  (needs data_path above)
