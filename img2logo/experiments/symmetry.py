"""Notebook 13: free against symmetric logos (:mod:`img2logo.fit.symmetry`).

:func:`compare` runs every image twice, free and with ``symmetry="auto"``,
and :func:`comparison_table` / :func:`plot_comparison` show the mirror axis
found, its score and what the symmetric logo costs or gains (arcs, E^s, and
r10 against the ground truth of the evaluation set's images).
"""

from __future__ import annotations

import dataclasses
import math
import os
import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import Img2LogoError
from ..export.plotting import plot_abstraction
from ..images.loading import load_mask
from ..pipeline import Result, abstract
from ..quality import feature_recall, logo_points
from . import repo_relative

__all__ = ["Comparison", "compare", "comparison_table", "plot_comparison"]


@dataclass(frozen=True, eq=False)
class Comparison:
    """One image, free and symmetric (``symmetry="auto"``).

    Attributes
    ----------
    name : str
        The image's path relative to the repository.
    free, symmetric : Result
        The two runs; ``symmetric.symmetry`` says what ``auto`` decided (when it
        found no axis good enough, ``symmetric`` is a free run too).
    truth : ndarray of bool or None
        The ground-truth feature pixels (the evaluation set's ``.gt.png``), if any.
    """

    name: str
    free: Result
    symmetric: Result
    truth: np.ndarray | None

    @property
    def made_symmetric(self) -> bool:
        """Whether ``auto`` kept an axis."""
        return self.symmetric.symmetry is not None and self.symmetric.symmetry.axis is not None


def compare(paths: Sequence[str | os.PathLike[str]], *, tolerance: float) -> list[Comparison]:
    """Run each image free and with ``symmetry="auto"`` at tolerance T (px)."""
    out = []
    for path in paths:
        p = Path(path)
        truth_file = p.with_name(p.stem + ".gt.png")
        truth = load_mask(truth_file) if truth_file.is_file() else None
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # a released junction is counted in the runs' stats
            sym = abstract(p, tolerance=tolerance, progress=False, symmetry="auto")
            if sym.symmetry is not None and sym.symmetry.axis is None:
                free = dataclasses.replace(sym, symmetry=None)  # auto kept no axis: that run is the free one
            else:
                free = abstract(p, tolerance=tolerance, progress=False)
        out.append(Comparison(repo_relative(p), free, sym, truth))
    return out


def comparison_table(comparisons: Sequence[Comparison]) -> Any:
    """One row per image: the axis (degrees, 90 upright), its score, what ``auto`` did, arcs, E^s and r10.

    ``paired`` is the fraction of the segment length whose mirror image lies
    near a segment; r10 (the fraction of the ground truth within 10 px of the
    logo) is empty without a ground truth.
    """
    import pandas as pd

    rows = []
    for c in comparisons:
        choice = c.symmetric.symmetry
        best = choice.best
        record = c.symmetric.final.params.get("symmetry", {})
        r10 = [
            feature_recall(logo_points(r.final), c.truth)[2] if c.truth is not None else math.nan
            for r in (c.free, c.symmetric)
        ]
        rows.append(
            {
                "image": c.name,
                "axis (deg)": round(best.angle, 2),
                "score": round(best.score, 3),
                "auto": "symmetric" if c.made_symmetric else "free",
                "paired": round(record["paired_fraction"], 3) if record else math.nan,
                "arcs free": len(c.free.final.arcs),
                "arcs symmetric": len(c.symmetric.final.arcs),
                "E^s free (px)": round(c.free.final.similarity, 3),
                "E^s symmetric (px)": round(c.symmetric.final.similarity, 3),
                "r10 free": round(r10[0], 3),
                "r10 symmetric": round(r10[1], 3),
            }
        )
    return pd.DataFrame(rows)


def plot_comparison(comparisons: Sequence[Comparison], *, panel_size: float = 3.2, every: bool = False) -> Any:
    """Input, free logo and symmetric logo (its mirror axis dashed) side by side, one row per image.

    Only the images ``auto`` made symmetric, unless ``every`` (then the others
    show their best score and the free logo again).
    """
    from matplotlib.figure import Figure

    comparisons = [c for c in comparisons if every or c.made_symmetric]
    if not comparisons:
        raise Img2LogoError("no image was made symmetric: nothing to compare (every=True shows them all)")

    fig = Figure(figsize=(3 * panel_size, panel_size * len(comparisons)), layout="constrained")
    axes = fig.subplots(len(comparisons), 3, squeeze=False)
    for row, c in zip(axes, comparisons, strict=True):
        image = c.free.image
        row[0].imshow(image.rgb, extent=(0, image.width, image.height, 0))
        row[0].set_title(Path(c.name).stem, fontsize=9)
        plot_abstraction(c.free.final, row[1])
        row[1].set_title(f"free: {len(c.free.final.arcs)} arcs, $E^s$ {c.free.final.similarity:.2f} px", fontsize=9)
        plot_abstraction(c.symmetric.final, row[2])
        axis = c.symmetric.symmetry.axis if c.symmetric.symmetry is not None else None
        if axis is not None:
            reach = float(np.hypot(image.width, image.height))
            ends = np.array([axis.point - reach * axis.direction, axis.point + reach * axis.direction])
            row[2].plot(ends[:, 0], ends[:, 1], "--", color="tab:cyan", linewidth=0.8)
            text = f"symmetric ({axis.angle:.0f}°, score {axis.score:.2f}): {len(c.symmetric.final.arcs)} arcs"
        else:
            text = f"no axis (best score {c.symmetric.symmetry.best.score:.2f}): free"
        row[2].set_title(f"{text}, $E^s$ {c.symmetric.final.similarity:.2f} px", fontsize=9)
        for ax in row:
            ax.set_xlim(0, image.width)
            ax.set_ylim(image.height, 0)
            ax.set_aspect("equal")
            ax.axis("off")
    return fig
