"""The designer features (paper Sec. 7) for ``12_designer_features``: colour fills (Fig. 18), edits (Fig. 17)."""

from __future__ import annotations

import re
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..design.arrangement import faces
from ..design.fills import Fill, fill_auto, fill_gradient, fill_palette
from ..export.plotting import plot_abstraction
from ..geometry.abstraction import Abstraction
from .layout import panel_grid, show_image

#: A designer's palette for the palette panel (fills cycle through it, largest face first).
DEFAULT_PALETTE = ("#264653", "#2a9d8f", "#e9c46a", "#f4a261", "#e76f51")
#: The two ends of the gradient panels.
DEFAULT_GRADIENT = ("#f9d423", "#e65c00")


def fill_variants(
    abstraction: Abstraction,
    image: np.ndarray,
    *,
    palette: Sequence[str] = DEFAULT_PALETTE,
    gradient: Sequence[str] = DEFAULT_GRADIENT,
) -> dict[str, tuple[Fill, ...]]:
    """The fill modes of Fig. 18 on one result: automatic colours, a palette, linear and radial gradients.

    Parameters
    ----------
    abstraction : Abstraction
        The result to colour.
    image : ndarray, shape (H, W, 3)
        The input image, float RGB in [0, 1], for the automatic colours.
    """
    face_list = faces(abstraction)
    return {
        "automatic (input colours)": fill_auto(abstraction, image, faces=face_list),
        "palette": fill_palette(abstraction, list(palette), faces=face_list),
        "linear gradient": fill_gradient(abstraction, list(gradient), kind="linear", faces=face_list),
        "radial gradient": fill_gradient(abstraction, list(gradient), kind="radial", faces=face_list),
    }


def plot_fill_variants(results: Sequence[tuple[str, Abstraction, np.ndarray]], *, panel_size: float = 3.0) -> Any:
    """One row per result: the input, the arcs, then each fill mode (Fig. 18).

    Parameters
    ----------
    results : sequence of (name, abstraction, image)
        ``image`` is the input, (H, W, 3) float RGB.
    """
    rows = [(name, a, img, fill_variants(a, img)) for name, a, img in results]
    fig, axes = panel_grid(len(rows), 2 + max((len(v) for *_, v in rows), default=0), panel_size)
    for row, (name, a, img, variants) in zip(axes, rows, strict=False):
        show_image(row[0], img)
        row[0].set_title(f"{name}: input", fontsize=9)
        plot_abstraction(a, row[1], linewidth=1.5)
        row[1].set_title(f"{len(a.arcs)} golden arcs", fontsize=9)
        for ax, (mode, fills) in zip(row[2:], variants.items(), strict=False):
            plot_abstraction(a, ax, fills=fills, linewidth=1.5)
            ax.set_title(f"{mode}: {len(fills)} regions", fontsize=9)
        for ax in row:
            ax.set_axis_off()
    return fig


def plot_edit(automated: Abstraction, edited: Abstraction, *, panel_size: float = 4.5) -> Any:
    """The automated result and an edited variant side by side (Fig. 17).

    The automated arcs are drawn faintly under the variant, so what the edits
    changed shows; the titles list the edits from ``edited.params["edits"]``.
    """
    fig, axes = panel_grid(1, 2, panel_size, extra_height=0.8)
    fig.get_layout_engine().set(h_pad=0.15)
    ax_a, ax_b = axes[0]
    plot_abstraction(automated, ax_a, show_junctions=True)
    ax_a.set_title(f"(a) automated result: {len(automated.arcs)} arcs", fontsize=9)
    plot_abstraction(automated, ax_b, color="0.85", linewidth=4.0)
    plot_abstraction(edited, ax_b, show_junctions=True)
    # One edit a line, numbers to one decimal: the record keeps full precision.
    history = "\n".join(re.sub(r"(\d+\.\d)\d+", r"\1", e) for e in edited.params.get("edits", []))
    ax_b.set_title(f"(b) edited variant: {len(edited.arcs)} arcs\n{history}", fontsize=8)
    for ax in (ax_a, ax_b):
        ax.set_axis_off()
    return fig
